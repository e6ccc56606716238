//! The addresses a RISC-V (RV32IC) function's code refers to, for `qemu_budget.rs`'s code
//! sizes (the kernel plus everything it reaches): the targets of `jal`/`j`/`c.jal`/`c.j` and of
//! branches, and the addresses built by `lui` (absolute) or `auipc` (PC-relative) with the
//! low 12 bits added by the first later instruction that uses the register as its base
//! (`addi`/`c.addi`, a load or store, `jalr`): calls beyond `jal`'s range, function pointers
//! and constant objects.
//!
//! Decoded sequentially from the function's start (an instruction's length is in its low two
//! bits, so there is no ambiguity as in Thumb). Included by `qemu_budget.rs` with `#[path]`.

/// Sign-extends the low `bits` bits of `v`.
fn sext(v: u32, bits: u32) -> i64 {
    i64::from(((v << (32 - bits)) as i32) >> (32 - bits))
}

fn bit(v: u32, i: u32) -> u32 {
    (v >> i) & 1
}

/// The register a 32-bit instruction writes, if any (`rd`; stores and branches write none).
fn rd32(w: u32) -> Option<u32> {
    match w & 0x7f {
        0x23 | 0x63 | 0x0f | 0x73 => None,
        _ => Some((w >> 7) & 31),
    }
}

/// The low part that a 32-bit instruction adds to base register `reg`, if it uses `reg` so:
/// `addi`, a load or `jalr` (I-type immediate) or a store (S-type).
fn lo32(w: u32, reg: u32) -> Option<i64> {
    let rs1 = (w >> 15) & 31;
    if rs1 != reg {
        return None;
    }
    match w & 0x7f {
        0x13 if (w >> 12) & 7 == 0 => Some(sext(w >> 20, 12)),
        0x03 | 0x67 => Some(sext(w >> 20, 12)),
        0x23 => Some(sext(((w >> 25) << 5) | ((w >> 7) & 31), 12)),
        _ => None,
    }
}

/// The low part that a compressed instruction adds to base register `reg` (`c.addi`,
/// `c.lw`, `c.sw`), and the register it writes (`None` for none).
fn lo16(h: u32, reg: u32) -> (Option<i64>, Option<u32>) {
    let (quadrant, funct3) = (h & 3, h >> 13);
    let rdp = 8 + ((h >> 2) & 7); // rd' (c.lw) / rs2' (c.sw)
    let rs1p = 8 + ((h >> 7) & 7);
    let uimm_w = (bit(h, 6) << 2) | (((h >> 10) & 7) << 3) | (bit(h, 5) << 6);
    match (quadrant, funct3) {
        // c.addi rd, imm (rd = rs1)
        (1, 0) => {
            let r = (h >> 7) & 31;
            let imm = sext((bit(h, 12) << 5) | ((h >> 2) & 31), 6);
            ((r == reg && r != 0).then_some(imm), Some(r))
        }
        // c.lw rd', uimm(rs1')
        (0, 2) => ((rs1p == reg).then_some(i64::from(uimm_w)), Some(rdp)),
        // c.sw rs2', uimm(rs1')
        (0, 6) => ((rs1p == reg).then_some(i64::from(uimm_w)), None),
        // Anything else: its destination if it has one in bits 11:7 (quadrant 2 and c.li,
        // c.lui of quadrant 1), or rd' of quadrant 0 / rs1' of quadrant 1's arithmetic.
        (2, _) if funct3 != 6 => (None, Some((h >> 7) & 31)),
        (1, 2) | (1, 3) => (None, Some((h >> 7) & 31)),
        (1, 4) => (None, Some(rs1p)),
        (0, _) if funct3 < 4 => (None, Some(rdp)),
        _ => (None, None),
    }
}

/// The instructions after a `lui`/`auipc` searched for the one adding its low part.
const PAIR_WINDOW: usize = 8;

/// Every address `code` (a function at `addr`) refers to, as described in the module docs.
pub fn refs(addr: u64, code: &[u8]) -> Vec<u64> {
    // The instructions: (offset, 32-bit word or 16-bit halfword, is compressed).
    let mut insns = Vec::new();
    let mut k = 0;
    while k + 1 < code.len() {
        let h = u32::from(u16::from_le_bytes([code[k], code[k + 1]]));
        if h & 3 == 3 {
            if k + 3 >= code.len() {
                break;
            }
            let w = h | (u32::from(u16::from_le_bytes([code[k + 2], code[k + 3]])) << 16);
            insns.push((k, w, false));
            k += 4;
        } else {
            insns.push((k, h, true));
            k += 2;
        }
    }
    let mut out = Vec::new();
    for (n, &(k, w, compressed)) in insns.iter().enumerate() {
        let pc = addr as i64 + k as i64;
        let target = if compressed {
            match (w & 3, w >> 13) {
                // c.jal (RV32) and c.j: imm[11|4|9:8|10|6|7|3:1|5].
                (1, 1) | (1, 5) => {
                    let imm = (bit(w, 12) << 11)
                        | (bit(w, 11) << 4)
                        | (((w >> 9) & 3) << 8)
                        | (bit(w, 8) << 10)
                        | (bit(w, 7) << 6)
                        | (bit(w, 6) << 7)
                        | (((w >> 3) & 7) << 1)
                        | (bit(w, 2) << 5);
                    Some(pc + sext(imm, 12))
                }
                // c.beqz / c.bnez: imm[8|4:3] (12:10), imm[7:6|2:1|5] (6:2).
                (1, 6) | (1, 7) => {
                    let imm = (bit(w, 12) << 8)
                        | (((w >> 10) & 3) << 3)
                        | (((w >> 5) & 3) << 6)
                        | (((w >> 3) & 3) << 1)
                        | (bit(w, 2) << 5);
                    Some(pc + sext(imm, 9))
                }
                _ => None,
            }
        } else {
            match w & 0x7f {
                // jal: imm[20|10:1|11|19:12].
                0x6f => {
                    let imm = (bit(w, 31) << 20)
                        | (((w >> 21) & 0x3ff) << 1)
                        | (bit(w, 20) << 11)
                        | (((w >> 12) & 0xff) << 12);
                    Some(pc + sext(imm, 21))
                }
                // Branches: imm[12|10:5] (31:25), imm[4:1|11] (11:7).
                0x63 => {
                    let imm = (bit(w, 31) << 12)
                        | (((w >> 25) & 0x3f) << 5)
                        | (((w >> 8) & 0xf) << 1)
                        | (bit(w, 7) << 11);
                    Some(pc + sext(imm, 13))
                }
                // lui (absolute) / auipc (PC-relative): the upper 20 bits, plus the low part of
                // the first later instruction using the register as its base (0 if none
                // before the register is overwritten).
                op @ (0x37 | 0x17) => {
                    let reg = (w >> 7) & 31;
                    let hi = i64::from((w & 0xffff_f000) as i32);
                    let base = if op == 0x37 { hi } else { pc + hi };
                    let mut lo = 0;
                    for &(_, x, c) in insns.iter().skip(n + 1).take(PAIR_WINDOW) {
                        let (add, writes) = if c {
                            lo16(x, reg)
                        } else {
                            (lo32(x, reg), rd32(x))
                        };
                        if let Some(a) = add {
                            lo = a;
                            break;
                        }
                        if writes == Some(reg) {
                            break;
                        }
                    }
                    (reg != 0).then_some(base + lo)
                }
                _ => None,
            }
        };
        // RV32 addresses are 32-bit: `lui` of an address at or above 2^31 (RAM starts at
        // 0x8000_0000) is negative as a sign-extended immediate.
        if let Some(t) = target {
            out.push((t as u64) & 0xffff_ffff);
        }
    }
    out
}
