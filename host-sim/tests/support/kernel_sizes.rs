//! Code bytes per kernel of the QEMU budget's firmware, from its ELF (the kernel and everything
//! it reaches, each constant object once).

use std::collections::{HashMap, HashSet};

use object::{Object, ObjectSection, ObjectSymbol, SymbolKind};

use crate::riscv_refs;

/// Code bytes per kernel symbol: the kernel plus every function it reaches by `bl`/`b.w` or
/// through a function pointer in its literal pool, plus the constant objects those literal
/// pools point into (each counted once). On RISC-V the references are found by
/// [`riscv_refs::refs`] instead (`jal`/`j` and branches, `lui`/`auipc` pairs: calls, function
/// pointers and constant objects).
///
/// Kernels that compile to the same code (e.g. a model's `Fast32` and `f32` kernels when every
/// operation they use is the same) may be merged by LLVM into one body with several symbols at
/// one address. The graph has one node per address, with every name found there, and every
/// kernel name at a node gets that node's size: two kernels sharing one body are each reported
/// with the whole of it (what either costs in flash alone; together they cost it once). A
/// merged kernel that is left without any symbol is found by [`merged_kernel`].
pub fn kernel_sizes(elf: &[u8]) -> Result<HashMap<String, u64>, String> {
    let file = object::File::parse(elf).map_err(|e| e.to_string())?;
    struct Sym {
        addr: u64,
        size: u64,
        /// Every symbol name at this address (more than one where bodies were merged).
        names: Vec<String>,
        func: bool,
    }
    let mut syms: Vec<Sym> = file
        .symbols()
        .filter(|s| s.size() > 0 && matches!(s.kind(), SymbolKind::Text | SymbolKind::Data))
        .map(|s| Sym {
            addr: s.address() & !1,
            size: s.size(),
            names: vec![s
                .name()
                .map(|n| format!("{:#}", rustc_demangle::demangle(n)))
                .unwrap_or_default()],
            func: s.kind() == SymbolKind::Text,
        })
        .collect();
    syms.sort_by_key(|s| s.addr);
    // One node per address (the first symbol's size and kind, as before), keeping the names of
    // the others: `dedup_by` passes the later element first and drops it.
    syms.dedup_by(|later, kept| {
        let same = later.addr == kept.addr;
        if same {
            kept.names.append(&mut later.names);
        }
        same
    });
    let find = |a: u64| -> Option<usize> {
        let i = syms.partition_point(|s| s.addr <= a);
        (i > 0 && a < syms[i - 1].addr + syms[i - 1].size).then(|| i - 1)
    };
    let bytes_at = |addr: u64, size: u64| -> Option<Vec<u8>> {
        file.sections().find_map(|sec| {
            let (start, len) = (sec.address(), sec.size());
            if addr >= start && addr + size <= start + len {
                let data = sec.data().ok()?;
                let off = (addr - start) as usize;
                data.get(off..off + size as usize).map(<[u8]>::to_vec)
            } else {
                None
            }
        })
    };
    // The edges of the reference graph.
    let mut edges: Vec<Vec<usize>> = vec![Vec::new(); syms.len()];
    let riscv = file.architecture() == object::Architecture::Riscv32;
    for (i, s) in syms.iter().enumerate().filter(|(_, s)| s.func) {
        let Some(code) = bytes_at(s.addr, s.size) else {
            continue;
        };
        if riscv {
            // A function is reached at its start; a constant object anywhere within it.
            for a in riscv_refs::refs(s.addr, &code) {
                let hit = find(a).filter(|&t| !syms[t].func || syms[t].addr == a);
                if let Some(t) = hit.filter(|&t| t != i && !edges[i].contains(&t)) {
                    edges[i].push(t);
                }
            }
            continue;
        }
        let hw = |k: usize| u32::from(u16::from_le_bytes([code[k], code[k + 1]]));
        let mut k = 0;
        while k + 1 < code.len() {
            let h1 = hw(k);
            if h1 >> 11 >= 0b11101 && k + 3 < code.len() {
                let h2 = hw(k + 2);
                let pc = s.addr + k as u64 + 4;
                let s_bit = (h1 >> 10) & 1;
                let (j1, j2) = ((h2 >> 13) & 1, (h2 >> 11) & 1);
                let target = if h1 >> 11 == 0b11110 && h2 & 0x9000 == 0x9000 {
                    // BL / B.W (T4): S:I1:I2:imm10:imm11:0, I = NOT(J XOR S).
                    let i1 = !(j1 ^ s_bit) & 1;
                    let i2 = !(j2 ^ s_bit) & 1;
                    let imm = (s_bit << 24)
                        | (i1 << 23)
                        | (i2 << 22)
                        | ((h1 & 0x3FF) << 12)
                        | ((h2 & 0x7FF) << 1);
                    Some(((imm << 7) as i32 >> 7) as i64)
                } else if h1 >> 11 == 0b11110 && h2 & 0xD000 == 0x8000 && (h1 >> 6) & 0xE != 0xE {
                    // B<cond>.W (T3): S:J2:J1:imm6:imm11:0.
                    let imm = (s_bit << 20)
                        | (j2 << 19)
                        | (j1 << 18)
                        | ((h1 & 0x3F) << 12)
                        | ((h2 & 0x7FF) << 1);
                    Some(((imm << 11) as i32 >> 11) as i64)
                } else {
                    None
                };
                if let Some(t) = target.and_then(|o| find((pc as i64 + o) as u64)) {
                    if t != i {
                        edges[i].push(t);
                    }
                }
                k += 4;
            } else {
                k += 2;
            }
        }
        // Literal-pool words pointing at a function (odd: Thumb) or into a constant object.
        for w in code
            .chunks_exact(4)
            .map(|c| u64::from(u32::from_le_bytes([c[0], c[1], c[2], c[3]])))
        {
            let hit = if w & 1 == 1 {
                find(w & !1).filter(|&t| syms[t].func && syms[t].addr == w & !1)
            } else {
                find(w).filter(|&t| !syms[t].func)
            };
            if let Some(t) = hit.filter(|&t| t != i) {
                edges[i].push(t);
            }
        }
    }
    let mut out = HashMap::new();
    for (i, s) in syms.iter().enumerate() {
        let kernels: Vec<&String> = s
            .names
            .iter()
            .filter(|n| n.contains("::cases::k_") || n.contains("::points::s_"))
            .collect();
        if kernels.is_empty() {
            continue;
        }
        let mut seen = HashSet::from([i]);
        let mut stack = vec![i];
        while let Some(j) = stack.pop() {
            for &t in &edges[j] {
                if seen.insert(t) {
                    stack.push(t);
                }
            }
        }
        let size: u64 = seen.iter().map(|&j| syms[j].size).sum();
        for name in kernels {
            out.insert(name.clone(), size);
        }
    }
    Ok(out)
}

/// The kernel symbol of `model` for the backend whose type is `ty`.
pub fn kernel_symbol(sizes: &HashMap<String, u64>, model: &str, ty: &str) -> Option<u64> {
    let key = format!("::cases::k_{model}::<");
    sizes.iter().find_map(|(name, &size)| {
        let rest = name.split_once(&key)?.1;
        let arg = rest.strip_suffix('>')?;
        (arg == ty || arg.ends_with(&format!("::{ty}"))).then_some(size)
    })
}
