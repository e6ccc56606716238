//! TIM2 of QEMU's `netduinoplus2` (STM32F405) as an exact instruction counter, its self-check,
//! and semihosting output lines. One implementation, shared by `boards/qemu-budget` (its module)
//! and `boards/qemu-frame` (included with `#[path]`).
//!
//! Under `-icount shift=0,align=off,sleep=off` QEMU advances its virtual clock by exactly 1 ns
//! per executed instruction, and the machine clocks TIM2 at 1 GHz of that clock: TIM2_CNT
//! advances by one per executed instruction. [`self_check`] verifies this on the running QEMU
//! before any count is trusted; [`Tim2::empty`] is the count of an empty measured region (the
//! fixed overhead of the second read), which callers subtract ([`Tim2::net`]).
//!
//! The empty region's count is checked against the self-check's `base` (the two TIM2 loads
//! alone, in assembly): the Rust region holds the same two loads plus at most the
//! re-materialization of TIM2_CNT's address (one literal load on the M0, `movw`/`movt` on the
//! M4F), so `base <= empty <= base + 2`. [`self_check`] fails otherwise, the `SELF` line
//! prints both and the host checks the same relation. A measured region can never read fewer
//! instructions than the empty one: [`Tim2::net`] fails (a `FAIL` line) rather than wrap.

use core::fmt::Write;
use core::hint::black_box;
use core::ptr::{read_volatile, write_volatile};
use core::sync::atomic::{compiler_fence, Ordering::SeqCst};

use cortex_m_semihosting::debug;

const TIM2: usize = 0x4000_0000;
const TIM_CR1: usize = TIM2;
const TIM_EGR: usize = TIM2 + 0x14;
const TIM_CNT: usize = TIM2 + 0x24;
const TIM_PSC: usize = TIM2 + 0x28;
const TIM_ARR: usize = TIM2 + 0x2C;
const RCC_APB1ENR: usize = 0x4002_3840;

/// A line of output, sent over semihosting when complete.
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
        if let Ok(mut out) = cortex_m_semihosting::hio::hstdout() {
            let _ = out.write_all(&self.buf[..self.len]);
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

pub fn fail(line: &mut Line, why: core::fmt::Arguments) -> ! {
    let _ = write!(line, "FAIL {why}");
    line.send();
    debug::exit(debug::EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}

#[inline(always)]
pub fn cnt() -> u32 {
    // SAFETY: TIM2_CNT is a readable 32-bit register of the STM32F405 (netduinoplus2).
    unsafe { read_volatile(TIM_CNT as *const u32) }
}

/// TIM2 as an instruction counter (netduinoplus2 under `-icount shift=0`).
pub struct Tim2 {
    /// The count of an empty measured region.
    pub empty: u32,
}

impl Tim2 {
    pub fn start() -> Self {
        // SAFETY: STM32F405 register writes: TIM2 clock on, prescaler 1, full 32-bit period,
        // update event to load them, counter on.
        unsafe {
            let en = read_volatile(RCC_APB1ENR as *const u32);
            write_volatile(RCC_APB1ENR as *mut u32, en | 1);
            write_volatile(TIM_PSC as *mut u32, 0);
            write_volatile(TIM_ARR as *mut u32, u32::MAX);
            write_volatile(TIM_EGR as *mut u32, 1);
            write_volatile(TIM_CR1 as *mut u32, 1);
        }
        let mut t = Tim2 { empty: 0 };
        t.empty = t.raw(|| ()).1;
        t
    }
}

include!("region.rs");
measured_region!(Tim2, "TIM2");

/// TIM2 around `n` iterations of `subs`/`bne` (2n instructions), all in assembly so that the
/// compiler adds nothing: `ldr` (count), the loop, `ldr` (count). `n` = 0 times the two loads
/// alone (no loop).
fn timed_loop(n: u32) -> u32 {
    let (t0, t1): (u32, u32);
    if n == 0 {
        // SAFETY: two loads of TIM2_CNT (a readable register), nothing else.
        unsafe {
            core::arch::asm!(
                "ldr r2, [r1]",
                "ldr r3, [r1]",
                in("r1") TIM_CNT,
                out("r2") t0,
                out("r3") t1,
                options(nostack, readonly),
            );
        }
    } else {
        // SAFETY: loads of TIM2_CNT around a register-only countdown loop; r0 is clobbered.
        unsafe {
            core::arch::asm!(
                "ldr r2, [r1]",
                "2:",
                "subs r0, #1",
                "bne 2b",
                "ldr r3, [r1]",
                inout("r0") n => _,
                in("r1") TIM_CNT,
                out("r2") t0,
                out("r3") t1,
                options(nostack, readonly),
            );
        }
    }
    t1.wrapping_sub(t0)
}

/// The loop lengths of the self-check.
pub const SELF_N: [u32; 4] = [1, 10, 1000, 3000];

/// The most instructions the empty Rust region may hold beyond the two loads: the address of
/// TIM2_CNT loaded again (see the module docs).
pub const EMPTY_SLACK: u32 = 2;

/// Checks that TIM2 counts executed instructions exactly: a loop of n `subs`/`bne` iterations
/// must read exactly 2n more than the two loads alone, for every n of [`SELF_N`], and every
/// measurement must repeat exactly; and that the empty region [`Tim2::empty`] (subtracted from
/// every count) is `base` to `base + EMPTY_SLACK`.
pub fn self_check(t: &Tim2, line: &mut Line) {
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
                "counter self-check: a loop of n subs/bne iterations did not read exactly 2n + \
                 {base} on TIM2, or the empty region ({}) is not {base} to {base} + \
                 {EMPTY_SLACK} (see the SELF line); TIM2 does not count executed instructions \
                 exactly on this QEMU",
                t.empty
            ),
        );
    }
}
