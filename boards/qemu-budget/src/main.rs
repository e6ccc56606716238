//! arealight under QEMU: exact instruction counts per model call, and the values computed.
//!
//! Runs every case of [`cases`] (every model id of `models.md`) for every backend of this
//! target, and prints over semihosting one line per call:
//!
//! ```text
//! V <backend> <model> <input> <instructions> <value bits as hex, 1 or 3 channels>
//! ```
//!
//! then, for the alternatives of [`points`] (point lights, k-sample area lights; f32 only),
//!
//! ```text
//! A f32 <alternative> <k> <input> <instructions> <value bits as hex>
//! ```
//!
//! then, on the counted machine, the cost of one object rendered with 16 lights of which 2 reach
//! it (prepared) against the 2 alone ([`scene_cost`]; f32 on the M4F, `Fixed22` on the M0),
//!
//! ```text
//! S <backend> <16_prepared|2_lights> <instructions> <frame checksum>
//! ```
//!
//! plus an `INFO` line, a `SELF` line (the counter self-check) and a final `DONE`.
//! `host-sim/tests/qemu_budget.rs` builds it, runs it and checks every line.
//!
//! # How instructions are counted
//!
//! Under `-icount shift=0,align=off,sleep=off` QEMU advances its virtual clock by exactly 1 ns
//! per executed instruction, and the netduinoplus2 machine (STM32F405) clocks TIM2 at 1 GHz of
//! that clock: TIM2_CNT advances by one per instruction. Before trusting it, [`self_check`]
//! times, entirely in assembly, `subs`/`bne` loops of n = 1, 10, 1000, 3000 iterations between
//! two TIM2_CNT loads and fails unless each reads exactly 2n more than the two loads alone.
//!
//! A call is counted as the difference of two TIM2_CNT reads around it, less the same
//! difference around nothing: every instruction executed from the first read to the second,
//! which includes the call itself, its argument moves and storing the result (the compiler
//! places these per call site: a few instructions).
//!
//! The thumbv6m (Cortex-M0) image runs on netduinoplus2 too (ARMv6-M is a subset of ARMv7-M,
//! and the STM32F405 aliases its flash at 0x0) and is counted there; on `microbit` (a real
//! Cortex-M0 model, found by its CPUID) it runs the same cases uncounted, as a functional check.
#![no_std]
#![no_main]

mod cases;
mod points;
mod scene_cost;

use core::fmt::Write;
use core::hint::black_box;
use core::ptr::{read_volatile, write_volatile};
use core::sync::atomic::{compiler_fence, Ordering::SeqCst};

use arealight::{Fast32, Real};
use cortex_m_rt::entry;
use cortex_m_semihosting::debug;

use cases::{Dirs, Lights, Meter, Sample, MODELS, RING};

/// The backends this target runs (each names itself: [`cases::Backend::NAME`]). Adding a
/// backend is one entry here (and, on the host, one in `host-sim/tests/qemu_budget.rs`).
macro_rules! for_each_backend {
    ($mac:ident) => {
        $mac!(f32);
        $mac!(Fast32);
        // Fixed point on the FPU-less core only (f32 there is soft-float, for contrast).
        #[cfg(not(target_abi = "eabihf"))]
        $mac!(arealight::Fixed22);
    };
}

const TIM2: usize = 0x4000_0000;
const TIM_CR1: usize = TIM2;
const TIM_EGR: usize = TIM2 + 0x14;
const TIM_CNT: usize = TIM2 + 0x24;
const TIM_PSC: usize = TIM2 + 0x28;
const TIM_ARR: usize = TIM2 + 0x2C;
const RCC_APB1ENR: usize = 0x4002_3840;
const CPUID: usize = 0xE000_ED00;

/// A line of output, sent over semihosting when complete.
struct Line {
    buf: [u8; 160],
    len: usize,
}

impl Line {
    const fn new() -> Self {
        Line {
            buf: [0; 160],
            len: 0,
        }
    }
    fn send(&mut self) {
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

fn fail(line: &mut Line, why: core::fmt::Arguments) -> ! {
    let _ = write!(line, "FAIL {why}");
    line.send();
    debug::exit(debug::EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}

#[inline(always)]
fn cnt() -> u32 {
    // SAFETY: TIM2_CNT is a readable 32-bit register of the STM32F405 (netduinoplus2).
    unsafe { read_volatile(TIM_CNT as *const u32) }
}

/// TIM2 as an instruction counter (netduinoplus2 under `-icount shift=0`).
struct Tim2 {
    /// The count of an empty measured region.
    empty: u32,
}

impl Tim2 {
    fn start() -> Self {
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

    /// The raw TIM2 difference around `f`.
    #[inline(always)]
    fn raw<R>(&mut self, f: impl Fn() -> R) -> (R, u32) {
        compiler_fence(SeqCst);
        let t0 = cnt();
        compiler_fence(SeqCst);
        let r = black_box(f());
        compiler_fence(SeqCst);
        let t1 = cnt();
        compiler_fence(SeqCst);
        (r, t1.wrapping_sub(t0))
    }
}

impl Meter for Tim2 {
    #[inline(always)]
    fn call<R>(&mut self, f: impl Fn() -> R) -> (R, u32) {
        let (r, n) = self.raw(f);
        (r, n.wrapping_sub(self.empty))
    }
}

/// No counter (micro:bit): every count is 0.
struct Uncounted;

impl Meter for Uncounted {
    #[inline(always)]
    fn call<R>(&mut self, f: impl Fn() -> R) -> (R, u32) {
        (black_box(f()), 0)
    }
}

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
const SELF_N: [u32; 4] = [1, 10, 1000, 3000];

/// Checks that TIM2 counts executed instructions exactly: a loop of n `subs`/`bne` iterations
/// must read exactly 2n more than the two loads alone, for every n of [`SELF_N`], and every
/// measurement must repeat exactly.
fn self_check(t: &Tim2, line: &mut Line) {
    let base = timed_loop(0);
    let _ = write!(line, "SELF empty={} base={base}", t.empty);
    let mut ok = base > 0 && base <= 2 && timed_loop(0) == base;
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
                 {base} on TIM2 (see the SELF line); TIM2 does not count executed instructions \
                 exactly on this QEMU"
            ),
        );
    }
}

fn emit(line: &mut Line, backend: &str, s: &Sample) {
    let model = MODELS.get(s.model).copied().unwrap_or("?");
    let _ = write!(line, "V {backend} {model} {} {}", s.input, s.count);
    for v in &s.value[..s.channels] {
        let _ = write!(line, " {:016x}", v.to_bits());
    }
    line.send();
}

/// The point-light and k-sample alternatives (`A <backend> <alternative> <k> <input> <count>
/// <value>` lines).
#[inline(never)]
fn run_points<T: Real, M: Meter>(name: &str, meter: &mut M) {
    let ring = |i| cases::ring(i);
    let dirs = Dirs {
        count: RING,
        get: &ring,
    };
    let mut line = Line::new();
    for k in points::KS {
        let sampled = points::Sampled::<T>::new(k, cases::PHONG_M);
        for (alt, (alt_name, _)) in points::ALTERNATIVES.iter().enumerate() {
            if alt_name.starts_with("point_") && k != 1 {
                continue;
            }
            points::run_alt(&sampled, alt, dirs, |x| x, meter, &mut |s| {
                let _ = write!(
                    line,
                    "A {name} {alt_name} {} {} {} {:016x}",
                    sampled.k(),
                    s.input,
                    s.count,
                    s.value[0].to_bits()
                );
                line.send();
            });
        }
    }
}

// Not inlined into `main`: each run's locals (every model's light, the scene) then live only
// while it runs, instead of adding up in one frame; the Cortex-M0 image has 16 KB of RAM.
#[inline(never)]
fn run_backend<T: cases::Backend, M: Meter>(meter: &mut M, line: &mut Line) {
    let name = T::NAME;
    let lights = match Lights::<T>::new(|x| x) {
        Ok(l) => l,
        Err(e) => fail(
            line,
            format_args!(
                "{name}: {} refused its parameters: {:?}",
                MODELS.get(e.model).copied().unwrap_or("?"),
                e.error
            ),
        ),
    };
    let ring = |i| cases::ring(i);
    let dirs = Dirs {
        count: RING,
        get: &ring,
    };
    for (model, id) in MODELS.iter().enumerate() {
        if !cases::supports(name, id) {
            continue;
        }
        let mut out = Line::new();
        cases::run_model(&lights, model, dirs, |x| x, meter, &mut |s| {
            emit(&mut out, name, &s)
        });
    }
}

/// The `S` lines of [`scene_cost`] for one backend.
#[inline(never)]
fn run_scene<T: Real, M: Meter>(name: &str, meter: &mut M) {
    let mut line = Line::new();
    match scene_cost::run::<T, M>(meter) {
        Some([(n16, c16), (n2, c2)]) => {
            for (what, n, c) in [("16_prepared", n16, c16), ("2_lights", n2, c2)] {
                let _ = write!(line, "S {name} {what} {n} {c:08x}");
                line.send();
            }
        }
        None => fail(
            &mut line,
            format_args!("{name}: the scene benchmark refused its setup"),
        ),
    }
}

#[entry]
fn main() -> ! {
    let mut line = Line::new();
    // SAFETY: CPUID is a read-only System Control Block register on every Cortex-M.
    let cpuid = unsafe { read_volatile(CPUID as *const u32) };
    let part = (cpuid >> 4) & 0xFFF;
    let target = if cfg!(target_abi = "eabihf") {
        "thumbv7em-none-eabihf"
    } else {
        "thumbv6m-none-eabi"
    };
    let counted = part != 0xC20; // Cortex-M0: the micro:bit, which has no TIM2
    let _ = write!(
        line,
        "INFO target={target} cpuid={cpuid:08x} counted={counted} ring={RING} phong_m={} moment_m={} line_k={}",
        cases::PHONG_M,
        cases::MOMENT_M,
        cases::LINE_K
    );
    line.send();
    if counted {
        let mut t = Tim2::start();
        self_check(&t, &mut line);
        macro_rules! run {
            ($t:ty) => {
                run_backend::<$t, _>(&mut t, &mut line)
            };
        }
        for_each_backend!(run);
        run_points::<f32, _>("f32", &mut t);
        // One backend per core (the M0 image must fit the micro:bit's 256 KB): the float path
        // on the M4F, fixed point on the M0.
        #[cfg(target_abi = "eabihf")]
        run_scene::<f32, _>("f32", &mut t);
        #[cfg(not(target_abi = "eabihf"))]
        run_scene::<arealight::Fixed22, _>("fixed", &mut t);
    } else {
        let mut m = Uncounted;
        macro_rules! run {
            ($t:ty) => {
                run_backend::<$t, _>(&mut m, &mut line)
            };
        }
        for_each_backend!(run);
        run_points::<f32, _>("f32", &mut m);
    }
    let _ = write!(line, "DONE");
    line.send();
    debug::exit(debug::EXIT_SUCCESS);
    loop {
        cortex_m::asm::wfi();
    }
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    let mut line = Line::new();
    fail(&mut line, format_args!("panic: {info}"))
}
