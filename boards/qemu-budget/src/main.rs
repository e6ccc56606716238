//! arealight under QEMU: exact instruction counts per model call, and the values computed.
//!
//! Runs every case of [`cases`] (every model id of `models.md`) for every backend of this
//! target, and prints over semihosting one line per call:
//!
//! ```text
//! V <backend> <model> <input> <instructions> <value bits as hex, 1 or 3 channels>
//! ```
//!
//! then the cases of [`cases::UNIT_CASES`] (the calls that take a normal or a reflection
//! direction) with that direction as a `UnitVec3`, normalized before the count (f32 and
//! f32-fast on the M4F, `Fixed22` on the M0 and RISC-V),
//!
//! ```text
//! U <backend> <model> <input> <instructions> <value bits as hex, 1 or 3 channels>
//! ```
//!
//! and, on the same backends, the cases of [`world_cases::WORLD_CASES`] (the positional lights
//! in world coordinates, 1000 units from the origin),
//!
//! ```text
//! W <backend> <model> <input> <instructions> <value bits as hex>
//! ```
//!
//! and, on the same backends again, the cases of [`bar_cases::BAR_CASES`] (`phong_polygon` as
//! issues 12 and 13 set their bars, a `PolygonLight<_, 4>` at m = 15, with a `Vec3` and with a
//! `UnitVec3`),
//!
//! ```text
//! B <backend> <row> <input> <instructions> <value bits as hex>
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
//! then one vertex shade of the board demo per call ([`demo_shade`]: the demo's lights and
//! materials through `Lit::shade`; `Fixed22` on the M0, f32 on the M4F, what the boards run),
//!
//! ```text
//! D <backend> <case> <input> <instructions> <r g b bits as hex>
//! ```
//!
//! and, on the M4F, the hardware square root (`VSQRT.F32`, which `<f32 as Real>::sqrt` uses
//! there: `arealight::real::hw`) against `libm::sqrtf` over a strided sweep of the positive
//! bit patterns, with the instructions of one call of each,
//!
//! ```text
//! Q sqrt_f32 <hardware 0|1> <patterns checked> <mismatches> <insns Real::sqrt> <insns libm::sqrtf>
//! ```
//!
//! plus an `INFO` line, a `SELF` line (the counter self-check) and a final `DONE`.
//!
//! For profiling, a build with the environment variable `QEMU_BUDGET_ONLY` set to a
//! comma-separated list of model ids (or `demo_shade`) runs only those cases (no alternatives,
//! no scene); the budget never sets it. `QEMU_BUDGET_PART` (`models` or `extras`, also at
//! build time) leaves out the other part's cases and their code: the budget builds the
//! Cortex-M0 image as those two parts, each of which fits the micro:bit's 256 KB (see
//! [`PART`]).
//!
//! `host-sim/tests/qemu_budget.rs` builds it, runs it and checks every line.
//!
//! # How instructions are counted
//!
//! Under `-icount shift=0,align=off,sleep=off` QEMU advances its virtual clock by exactly 1 ns
//! per executed instruction, and the netduinoplus2 machine (STM32F405) clocks TIM2 at 1 GHz of
//! that clock: TIM2_CNT advances by one per instruction. Before trusting it,
//! [`counter::self_check`] times, entirely in assembly, `subs`/`bne` loops of n = 1, 10, 1000,
//! 3000 iterations between two TIM2_CNT loads and fails unless each reads exactly 2n more than
//! the two loads alone. (The counter lives in `counter.rs`, shared with `boards/qemu-frame`.)
//!
//! A call is counted as the difference of two TIM2_CNT reads around it, less the same
//! difference around nothing: every instruction executed from the first read to the second,
//! which includes the call itself, its argument moves and storing the result (the compiler
//! places these per call site: a few instructions).
//!
//! The thumbv6m (Cortex-M0) image runs on netduinoplus2 too (ARMv6-M is a subset of ARMv7-M,
//! and the STM32F405 aliases its flash at 0x0) and is counted there; on `microbit` (a real
//! Cortex-M0 model, found by its CPUID) it runs the same cases uncounted, as a functional check.
//!
//! # RISC-V
//!
//! The same cases, backends and lines on `riscv32imc-unknown-none-elf` (ESP32-C3 class: RV32IMC,
//! no FPU, so f32 is soft-float and `Fixed22` is what such a part runs), on QEMU's `virt`
//! machine with `-bios none`: what the M0 image runs (every model in f32, `Fast32` and
//! `Fixed22`, the `Fixed22` demo shade and scene, the f32 alternatives). There the counter is
//! the `instret` CSR, exact under the same `-icount` ([`counter`] is then `instret.rs`, with the
//! same interface and self-check: `addi`/`bnez` loops must read exactly 2n), the start-up is
//! `rv_start.rs`, and the lines go to the machine's UART.
#![no_std]
#![no_main]

mod bar_cases;
mod cases;
#[cfg(target_arch = "arm")]
mod counter;
#[cfg(target_arch = "riscv32")]
#[path = "instret.rs"]
mod counter;
mod demo_shade;
mod points;
#[cfg(target_arch = "riscv32")]
mod rv_start;
mod scene_cost;
mod world_cases;

use core::fmt::Write;
use core::hint::black_box;
#[cfg(target_arch = "arm")]
use core::ptr::read_volatile;

use arealight::{Fast32, Real};
#[cfg(target_arch = "arm")]
use cortex_m_rt::entry;
#[cfg(target_arch = "arm")]
use cortex_m_semihosting::debug;

use cases::{Lights, Meter, Sample, MODELS, RING};
/// The instruction counter of this target: TIM2 (ARM), `instret` (RISC-V).
#[cfg(target_arch = "riscv32")]
use counter::Instret as Tim2;
#[cfg(target_arch = "arm")]
use counter::Tim2;
use counter::{fail, self_check, Line};

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

#[cfg(target_arch = "arm")]
const CPUID: usize = 0xE000_ED00;

impl Meter for Tim2 {
    #[inline(always)]
    fn call<R>(&mut self, f: impl Fn() -> R) -> (R, u32) {
        let (r, n) = self.raw(f);
        (r, self.net(n))
    }
}

/// The counter where it counts, none on the micro:bit (every count 0). One type for both runs,
/// so that every case is compiled once, not once per meter: the M0 image must fit the
/// micro:bit's 256 KB. Only the kernel call lies between the two counter reads either way.
struct Meters(Option<Tim2>);

impl Meter for Meters {
    #[inline(always)]
    fn call<R>(&mut self, f: impl Fn() -> R) -> (R, u32) {
        match &mut self.0 {
            Some(t) => t.call(f),
            None => (black_box(f()), 0),
        }
    }
}

fn emit(line: &mut Line, backend: &str, s: &Sample) {
    emit_as(line, "V", backend, s)
}

/// A `V` line, or with `kind` `U` the same for a call with a unit direction.
fn emit_as(line: &mut Line, kind: &str, backend: &str, s: &Sample) {
    let model = MODELS.get(s.model).copied().unwrap_or("?");
    let _ = write!(line, "{kind} {backend} {model} {} {}", s.input, s.count);
    for v in &s.value[..s.channels] {
        let _ = write!(line, " {:016x}", v.to_bits());
    }
    line.send();
}

/// The point-light and k-sample alternatives (`A <backend> <alternative> <k> <input> <count>
/// <value>` lines).
#[inline(never)]
fn run_points<T: Real, M: Meter>(name: &str, meter: &mut M) {
    let dirs = cases::ring_dirs();
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
    let dirs = cases::ring_dirs();
    for (model, id) in MODELS.iter().enumerate() {
        if !cases::supports(name, id) || !selected(id) {
            continue;
        }
        let mut out = Line::new();
        cases::run_model(&lights, model, dirs, |x| x, meter, &mut |s| {
            emit(&mut out, name, &s)
        });
    }
    // The same calls with a unit direction (`U` lines): the floats where there is an FPU,
    // fixed point on the others (a constant per backend and target: nothing is linked
    // elsewhere).
    if cfg!(target_abi = "eabihf") || T::FIXED {
        for case in 0..cases::UNIT_CASES.len() {
            let id = MODELS[cases::UNIT_CASES[case].1];
            if !cases::supports(name, id) || !selected(id) {
                continue;
            }
            let mut out = Line::new();
            cases::run_unit(&lights, case, dirs, |x| x, meter, &mut |s| {
                emit_as(&mut out, "U", name, &s)
            });
        }
    }
}

/// The `W` lines: the positional lights in world coordinates ([`world_cases`]), on the same
/// backends as the `U` lines (the floats where there is an FPU, fixed point on the others).
/// Not inlined: the world lights live only while they run.
#[inline(never)]
fn run_world<T: cases::Backend, M: Meter>(meter: &mut M) {
    if !(cfg!(target_abi = "eabihf") || T::FIXED) {
        return;
    }
    let name = T::NAME;
    let dirs = cases::ring_dirs();
    let lights = match world_cases::WorldLights::<T>::new() {
        Ok(l) => l,
        Err(e) => fail(
            &mut Line::new(),
            format_args!("{name}: a world light refused its parameters: {e:?}"),
        ),
    };
    for case in 0..world_cases::WORLD_CASES.len() {
        let id = MODELS[world_cases::WORLD_CASES[case].1];
        if !selected(id) {
            continue;
        }
        let mut out = Line::new();
        world_cases::run_world(&lights, case, dirs, |x| x, meter, &mut |s| {
            emit_as(&mut out, "W", name, &s)
        });
    }
}

/// The `B` lines: `phong_polygon` at the bars' exponent ([`bar_cases`]), on the same backends
/// as the `U` lines. Not inlined: the bar's light lives only while it runs.
#[inline(never)]
fn run_bar<T: cases::Backend, M: Meter>(meter: &mut M) {
    if !(cfg!(target_abi = "eabihf") || T::FIXED) || !selected(MODELS[bar_cases::BAR_MODEL]) {
        return;
    }
    let name = T::NAME;
    let dirs = cases::ring_dirs();
    let lights = match bar_cases::BarLights::<T>::new(|x| x) {
        Ok(l) => l,
        Err(e) => fail(
            &mut Line::new(),
            format_args!("{name}: the bar's light refused its parameters: {e:?}"),
        ),
    };
    for (case, &(row, _)) in bar_cases::BAR_CASES.iter().enumerate() {
        let mut out = Line::new();
        bar_cases::run_bar(&lights, case, dirs, |x| x, meter, &mut |s| {
            let _ = write!(
                out,
                "B {name} {row} {} {} {:016x}",
                s.input,
                s.count,
                s.value[0].to_bits()
            );
            out.send();
        });
    }
}

/// The profiling filter (see the module docs): `None` runs everything.
const ONLY: Option<&str> = option_env!("QEMU_BUDGET_ONLY");

/// Which cases the image runs: all of them, or with `QEMU_BUDGET_PART` set at build time
/// only the models (`models`: every backend's `V` and `U` lines), only the rest (`extras`:
/// the demo shader, the alternatives, the scene), both (`main`), only the world lights
/// (`world`: the `W` lines), or only the bars' cases (`bar`: the `B` lines, apart for the
/// same reason as the world lights). `host-sim/tests/qemu_budget.rs` builds the Cortex-M0 image as
/// `models`, `extras`, `world` and `bar` (all of it no longer fits the micro:bit's 256 KB;
/// each part is checked on the micro:bit alone) and the others as `main`, `world` and `bar`,
/// and reads their lines as one image's. The world lights are an image apart on every target: they
/// share the plain lights' functions, which then have two callers, and LLVM no longer
/// inlines them into the plain kernels (measured: the M4F `polygon_lambert` row 703 -> 713
/// instructions, `phong_polygon` 1 941 -> 1 961, in one image). A constant: the part left
/// out is not linked.
const PART: Option<&str> = option_env!("QEMU_BUDGET_PART");
const RUN_MODELS: bool = part_runs("models");
const RUN_EXTRAS: bool = part_runs("extras");
const RUN_WORLD: bool = part_runs("world");
const RUN_BAR: bool = part_runs("bar");

/// Whether the part `name` runs (every part without `QEMU_BUDGET_PART`; `main` is every
/// part but `world` and `bar`).
const fn part_runs(name: &str) -> bool {
    match PART {
        None => true,
        Some(part) => {
            cases::str_eq(part, name)
                || (cases::str_eq(part, "main")
                    && !cases::str_eq(name, "world")
                    && !cases::str_eq(name, "bar"))
        }
    }
}

/// Whether case `id` runs under the profiling filter.
fn selected(id: &str) -> bool {
    match ONLY {
        None => true,
        Some(list) => list.split(',').any(|x| x == id),
    }
}

/// The `D` lines of [`demo_shade`] for one backend.
#[inline(never)]
fn run_demo_shade<T: Real, M: Meter>(name: &str, meter: &mut M) {
    if !selected("demo_shade") {
        return;
    }
    let mut line = Line::new();
    let done = demo_shade::run::<T, M>(|x| x, meter, &mut |case, i, c, count| {
        let _ = write!(line, "D {name} {} {i} {count}", demo_shade::CASES[case].0);
        for v in c {
            let _ = write!(line, " {:016x}", v.to_bits());
        }
        line.send();
    });
    if done.is_none() {
        fail(
            &mut line,
            format_args!("{name}: the demo shade refused its setup"),
        );
    }
}

/// The `Q` line: `<f32 as Real>::sqrt` (the hardware `VSQRT.F32` on the M4F) against
/// `libm::sqrtf` on every 4099th bit pattern of the positive floats and infinity (subnormals,
/// normals, the largest values), and one counted call of each. The M4F only (the M0 has no
/// hardware square root).
#[cfg(target_abi = "eabihf")]
#[inline(never)]
fn run_sqrt_sweep<M: Meter>(meter: &mut M) {
    let (mut checked, mut mismatches) = (0u32, 0u32);
    let mut bits = 1u32;
    while bits <= 0x7F80_0000 {
        let x = f32::from_bits(black_box(bits));
        if <f32 as Real>::sqrt(x).to_bits() != libm::sqrtf(x).to_bits() {
            mismatches += 1;
        }
        checked += 1;
        bits += 4099;
    }
    let x = black_box(2.0f32);
    let (_, hw) = meter.call(|| <f32 as Real>::sqrt(black_box(x)));
    let (_, sw) = meter.call(|| libm::sqrtf(black_box(x)));
    let mut line = Line::new();
    let _ = write!(
        line,
        "Q sqrt_f32 {} {checked} {mismatches} {hw} {sw}",
        u8::from(arealight::real::hw::HARDWARE_SQRT_F32)
    );
    line.send();
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

/// The RISC-V image's `INFO` line and whether it counts (always: `instret` on `virt`).
#[cfg(target_arch = "riscv32")]
fn identify(line: &mut Line) -> bool {
    let _ = write!(
        line,
        "INFO target=riscv32imc-unknown-none-elf misa={:08x} counted=true ring={RING} phong_m={} moment_m={} line_k={}",
        counter::misa(),
        cases::PHONG_M,
        cases::MOMENT_M,
        cases::LINE_K
    );
    line.send();
    true
}

/// The ARM image's `INFO` line and whether it counts (not on the micro:bit's Cortex-M0).
#[cfg(target_arch = "arm")]
fn identify(line: &mut Line) -> bool {
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
    counted
}

#[cfg_attr(target_arch = "arm", entry)]
fn main() -> ! {
    let mut line = Line::new();
    let counted = identify(&mut line);
    // The counter where it counts (after its self-check), none on the micro:bit.
    let mut m = Meters(if counted {
        let t = Tim2::start();
        self_check(&t, &mut line);
        Some(t)
    } else {
        None
    });
    macro_rules! run {
        ($t:ty) => {
            run_backend::<$t, _>(&mut m, &mut line)
        };
    }
    if RUN_MODELS {
        for_each_backend!(run);
    }
    macro_rules! run_w {
        ($t:ty) => {
            run_world::<$t, _>(&mut m)
        };
    }
    if RUN_WORLD {
        for_each_backend!(run_w);
    }
    macro_rules! run_b {
        ($t:ty) => {
            run_bar::<$t, _>(&mut m)
        };
    }
    if RUN_BAR {
        for_each_backend!(run_b);
    }
    // One backend per core (the M0 image must fit the micro:bit's 256 KB): the float path
    // on the M4F, fixed point on the M0, as the boards run them.
    #[cfg(target_abi = "eabihf")]
    if RUN_EXTRAS {
        run_demo_shade::<f32, _>("f32", &mut m);
    }
    #[cfg(not(target_abi = "eabihf"))]
    if RUN_EXTRAS {
        run_demo_shade::<arealight::Fixed22, _>("fixed", &mut m);
    }
    if ONLY.is_none() && RUN_EXTRAS {
        run_points::<f32, _>("f32", &mut m);
        if counted {
            #[cfg(target_abi = "eabihf")]
            run_sqrt_sweep(&mut m);
            #[cfg(target_abi = "eabihf")]
            run_scene::<f32, _>("f32", &mut m);
            #[cfg(not(target_abi = "eabihf"))]
            run_scene::<arealight::Fixed22, _>("fixed", &mut m);
        }
    }
    let _ = write!(line, "DONE");
    line.send();
    #[cfg(target_arch = "riscv32")]
    counter::exit(true);
    #[cfg(target_arch = "arm")]
    {
        debug::exit(debug::EXIT_SUCCESS);
        loop {
            cortex_m::asm::wfi();
        }
    }
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    let mut line = Line::new();
    fail(&mut line, format_args!("panic: {info}"))
}
