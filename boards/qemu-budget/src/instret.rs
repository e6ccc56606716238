//! RISC-V (`riscv32imc`, QEMU's `virt` machine): `instret` as an exact instruction counter,
//! its self-check, output lines on the machine's UART and the exit through its test device.
//! The same interface as the ARM [`counter`](../counter.rs) module (`Line`, `fail`, `cnt`,
//! `SELF_N`, `EMPTY_SLACK`, `self_check`, a counter with `empty`, `net` and `raw`), so that
//! `main.rs` and every shared module count the same calls on both architectures.
//!
//! Under `-icount shift=0,align=off,sleep=off` QEMU's `instret` (and `cycle`, `minstret`)
//! CSRs read the instruction counter of its virtual clock (without `-icount` they read host
//! ticks, which count nothing). [`self_check`] verifies before any count is trusted that it
//! advances by exactly one per executed instruction: `addi`/`bnez` loops of n = 1, 10, 1000,
//! 3000 iterations, timed between two `csrr instret` entirely in assembly, must each read
//! exactly 2n more than the two reads alone (`base`, 1: the first read itself). Measured on
//! QEMU 7.2: base 1, n1 = 3, n10 = 21, n1000 = 2001, n3000 = 6001, each repeating exactly.
//!
//! [`Instret::empty`] is the count of an empty measured region in Rust, which every count is
//! net of: the same two reads, plus at most [`EMPTY_SLACK`] instructions the compiler places
//! between them, so `base <= empty <= base + EMPTY_SLACK` ([`self_check`] fails otherwise,
//! and the host checks the same relation from the `SELF` line).
//!
//! Output: each [`Line`] is written byte by byte to the transmit register of the `virt`
//! machine's NS16550A UART (0x1000_0000; QEMU sends it on at once, no status polling), which
//! the harness runs with `-serial stdio`. The run ends by a write to the machine's SiFive test
//! device (0x10_0000): 0x5555 exits QEMU with status 0, `(code << 16) | 0x3333` with `code`.

use core::fmt::Write;
use core::hint::black_box;
use core::ptr::write_volatile;
use core::sync::atomic::{compiler_fence, Ordering::SeqCst};

/// The transmit holding register of the `virt` machine's NS16550A UART.
const UART_THR: usize = 0x1000_0000;
/// The `virt` machine's SiFive test (finisher) device.
const TEST_DEVICE: usize = 0x10_0000;

/// A line of output, written to the UART when complete.
pub struct Line {
    buf: [u8; 160],
    len: usize,
}

impl Line {
    pub const fn new() -> Self {
        Line {
            buf: [0; 160],
            len: 0,
        }
    }
    pub fn send(&mut self) {
        let _ = self.write_str("\n");
        for &b in &self.buf[..self.len] {
            // SAFETY: the transmit register of the virt machine's UART, a byte-wide MMIO write.
            unsafe { write_volatile(UART_THR as *mut u8, b) };
        }
        self.len = 0;
    }
}

impl Write for Line {
    fn write_str(&mut self, s: &str) -> core::fmt::Result {
        let b = s.as_bytes();
        let end = self.len + b.len();
        if end > self.buf.len() {
            return Err(core::fmt::Error);
        }
        self.buf[self.len..end].copy_from_slice(b);
        self.len = end;
        Ok(())
    }
}

/// Ends the QEMU run: exit status 0 if `success`, 1 otherwise.
pub fn exit(success: bool) -> ! {
    let code = if success { 0x5555 } else { (1 << 16) | 0x3333 };
    // SAFETY: the virt machine's test device: a 32-bit write ends the emulation.
    unsafe { write_volatile(TEST_DEVICE as *mut u32, code) };
    loop {
        core::hint::spin_loop();
    }
}

pub fn fail(line: &mut Line, why: core::fmt::Arguments) -> ! {
    let _ = write!(line, "FAIL {why}");
    line.send();
    exit(false)
}

/// The `instret` CSR (the instructions retired; exact under `-icount shift=0`).
#[inline(always)]
pub fn cnt() -> u32 {
    let n: u32;
    // SAFETY: reads a counter CSR into a register; nothing else. Not `nomem`: like the ARM
    // counter's volatile load, it is not moved across the memory accesses around it.
    unsafe { core::arch::asm!("csrr {0}, instret", out(reg) n, options(nostack)) };
    n
}

/// The `misa` CSR (the ISA the hart implements; printed in the `INFO` line).
pub fn misa() -> u32 {
    let n: u32;
    // SAFETY: reads a machine-mode CSR (the harness runs in machine mode); nothing else.
    unsafe { core::arch::asm!("csrr {0}, misa", out(reg) n, options(nomem, nostack)) };
    n
}

/// `instret` as an instruction counter (QEMU `virt` under `-icount shift=0`).
pub struct Instret {
    /// The count of an empty measured region.
    pub empty: u32,
}

impl Instret {
    pub fn start() -> Self {
        let mut t = Instret { empty: 0 };
        t.empty = t.raw(|| ()).1;
        t
    }
}

include!("region.rs");
measured_region!(Instret, "instret");

/// `instret` around `n` iterations of `addi`/`bnez` (2n instructions), all in assembly so
/// that the compiler adds nothing: `csrr`, the loop, `csrr`. `n` = 0 times the two reads alone.
fn timed_loop(n: u32) -> u32 {
    let (t0, t1): (u32, u32);
    if n == 0 {
        // SAFETY: two reads of a counter CSR, nothing else.
        unsafe {
            core::arch::asm!(
                "csrr {t0}, instret",
                "csrr {t1}, instret",
                t0 = out(reg) t0,
                t1 = out(reg) t1,
                options(nomem, nostack),
            );
        }
    } else {
        // SAFETY: reads of a counter CSR around a register-only countdown loop.
        unsafe {
            core::arch::asm!(
                "csrr {t0}, instret",
                "2:",
                "addi {n}, {n}, -1",
                "bnez {n}, 2b",
                "csrr {t1}, instret",
                n = inout(reg) n => _,
                t0 = out(reg) t0,
                t1 = out(reg) t1,
                options(nomem, nostack),
            );
        }
    }
    t1.wrapping_sub(t0)
}

/// The loop lengths of the self-check.
pub const SELF_N: [u32; 4] = [1, 10, 1000, 3000];

/// The most instructions the empty Rust region may hold beyond the two reads (the same bound
/// as the ARM counter's; on RISC-V the reads need no address, and the region measures `base`).
pub const EMPTY_SLACK: u32 = 2;

/// Checks that `instret` counts executed instructions exactly: a loop of n `addi`/`bnez`
/// iterations must read exactly 2n more than the two reads alone, for every n of [`SELF_N`],
/// and every measurement must repeat exactly; and that the empty region [`Instret::empty`]
/// (subtracted from every count) is `base` to `base + EMPTY_SLACK`.
pub fn self_check(t: &Instret, line: &mut Line) {
    let base = timed_loop(0);
    let _ = write!(line, "SELF empty={} base={base}", t.empty);
    let mut ok = base > 0 && base <= 2 && timed_loop(0) == base;
    ok &= t.empty >= base && t.empty <= base + EMPTY_SLACK;
    for n in SELF_N {
        let c = timed_loop(black_box(n));
        let again = timed_loop(black_box(n));
        let _ = write!(line, " n{n}={c}");
        ok &= c == base + 2 * n && again == c;
    }
    line.send();
    if !ok {
        fail(
            line,
            format_args!(
                "counter self-check: a loop of n addi/bnez iterations did not read exactly 2n + \
                 {base} on instret, or the empty region ({}) is not {base} to {base} + \
                 {EMPTY_SLACK} (see the SELF line); instret does not count executed \
                 instructions exactly on this QEMU (is -icount shift=0 set?)",
                t.empty
            ),
        );
    }
}
