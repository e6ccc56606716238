//! The STM32F411 firmware's demo frame (`boards/demo-scene` in `f32`, 240x240 through a 240x16
//! band) on QEMU's `netduinoplus2` (STM32F405, Cortex-M4F), counted exactly.
//!
//! For every shading mode of [`scene::MODES`] and every frame of [`scene::FRAMES`] it renders
//! the whole frame with `Demo::render_frame`, the call every board makes, and prints over
//! semihosting:
//!
//! ```text
//! B <mode> <n> <y0> <the band's pixels: RGB565, row-major, 4 hex digits each (big-endian)>
//! ...
//! CALL <mode> <n> <instructions of the whole render_frame call>
//! FRAME <mode> <n> <total> <setup> <transform> <shade> <raster> <flush> <shader calls> <pixels> <triangle setups>
//! ```
//!
//! (one `B` line per band, 15 per frame, printed by the flush), then the unit costs of
//! `demo_scene::calibrate` (`COST <item> <count> <triangle setups> <shader calls>
//! <instructions>`, for `host-sim budget --scene`), then `STACK <used> <size>`
//! (the most stack used, in bytes, of the stack's size) and `DONE`; before them an `INFO` line
//! and the counter self-check's `SELF` line. `host-sim/tests/qemu_frame.rs` builds it, runs
//! it, renders the same frames on the host and checks every band bit for bit.
//!
//! # How instructions are counted
//!
//! Under `-icount shift=0,align=off,sleep=off` QEMU advances its virtual clock by exactly 1 ns
//! per executed instruction, and netduinoplus2 clocks TIM2 at 1 GHz of that clock: TIM2_CNT
//! advances by one per executed instruction. The counter and its self-check are
//! `boards/qemu-budget`'s (`counter.rs`, included here): before anything is counted, `subs`/
//! `bne` loops timed in assembly must read exactly 2 instructions per iteration.
//!
//! `render_frame` reads its clock at the start and after each stage, and adds each difference
//! to that stage: a stage's count is every instruction executed between two reads, which
//! includes `render_frame`'s own bookkeeping of the lap (a few instructions per read: one read
//! per stage of the frame, one per band for the raster and for the flush stage; the board
//! firmware runs the same code with its cycle counter). `<total>` is their sum: every
//! instruction from the first read to the last. `CALL` is the whole call (TIM2 around it, less
//! the empty region's count as in qemu-budget): `<total>` plus the call's entry and exit.
//!
//! The flush stage is the cost of handing a band over, not of semihosting: the flush copies the
//! band into a static buffer (as a firmware hands a band to its display's DMA), then prints
//! that copy with the clock stopped: the clock is TIM2_CNT less the instructions spent printing
//! (measured by two TIM2 reads around the printing). What the flush stage still counts of it is
//! the first of those reads and the update of the paused count: about 5 instructions per band.
#![no_std]
#![no_main]
// With `scene-file` the demo's modes are not rendered.
#![cfg_attr(feature = "scene-file", allow(dead_code))]

#[allow(dead_code)]
#[path = "../../qemu-budget/src/counter.rs"]
mod counter;
mod scene;

// An item of the crate root, so that `scene.rs` (shared with the host test, where demo-scene's
// source is a module) can name it `crate::demo_scene` on both sides.
extern crate demo_scene;

use core::cell::Cell;
use core::convert::Infallible;
use core::fmt::Write;
use core::hint::black_box;
use core::ptr::{addr_of_mut, read_volatile, write_volatile};
use core::sync::atomic::{compiler_fence, Ordering::SeqCst};

use arealight::raster::{Band, Rgb565};
use cortex_m_rt::{entry, exception, ExceptionFrame};
use cortex_m_semihosting::{debug, hio};
#[cfg(not(feature = "scene-file"))]
use demo_scene::calibrate::{self, CalibrationBuffers};
#[cfg(feature = "scene-file")]
use demo_scene::{
    scenes,
    spec::{Player, SpecBuffers},
};
use demo_scene::{Stage, BAND_PIXELS, BAND_ROWS, HEIGHT, WIDTH};

use counter::{cnt, fail, self_check, Line, Tim2};

/// What [`paint_stack`] fills the unused stack with.
const PAINT: u32 = 0xA5C3_5A3C;
const CPUID: usize = 0xE000_ED00;

/// The statics (see memory.x): the scene's storage, the band, its depth buffer, and the copy
/// the flush hands over.
struct Ram {
    #[cfg(not(feature = "scene-file"))]
    storage: scene::Storage,
    pixels: [Rgb565; BAND_PIXELS],
    depth: [u16; BAND_PIXELS],
    sent: [Rgb565; BAND_PIXELS],
    /// The unit-cost calibration's meshes (`demo_scene::calibrate`).
    #[cfg(not(feature = "scene-file"))]
    calibration: CalibrationBuffers<f32>,
    /// The scene files' meshes (`demo_scene::scenes`, feature `scene-file`).
    #[cfg(feature = "scene-file")]
    scenes: SpecBuffers<f32, { scenes::VERTICES }, { scenes::TRIANGLES }>,
}

/// A constant initializer: the storage is never built on the stack. (`MeshBuffers::new()`
/// evaluated at run time builds its arrays in stack temporaries first: about 145 KiB at
/// opt-level 3, which this RAM cannot hold besides the storage itself.)
static mut RAM: Ram = Ram {
    #[cfg(not(feature = "scene-file"))]
    storage: scene::Storage::new(),
    pixels: [Rgb565(0); BAND_PIXELS],
    depth: [0; BAND_PIXELS],
    sent: [Rgb565(0); BAND_PIXELS],
    #[cfg(not(feature = "scene-file"))]
    calibration: CalibrationBuffers::new(),
    #[cfg(feature = "scene-file")]
    scenes: SpecBuffers::new(),
};

/// Semihosting stdout through a buffer (one host write per 1 KiB, not per line).
struct Out {
    stream: hio::HostStream,
    buf: [u8; 1024],
    len: usize,
}

impl Out {
    fn new(line: &mut Line) -> Self {
        match hio::hstdout() {
            Ok(stream) => Out {
                stream,
                buf: [0; 1024],
                len: 0,
            },
            Err(()) => fail(line, format_args!("semihosting: no stdout")),
        }
    }

    fn byte(&mut self, b: u8) {
        if self.len == self.buf.len() {
            self.flush();
        }
        self.buf[self.len] = b;
        self.len += 1;
    }

    fn flush(&mut self) {
        let _ = self.stream.write_all(&self.buf[..self.len]);
        self.len = 0;
    }
}

impl Write for Out {
    fn write_str(&mut self, s: &str) -> core::fmt::Result {
        s.bytes().for_each(|b| self.byte(b));
        Ok(())
    }
}

/// The `B` line of one band: its pixels, 4 hex digits each.
fn print_band(out: &mut Out, mode: &str, n: u32, y0: u16, pixels: &[Rgb565]) {
    const HEX: &[u8; 16] = b"0123456789abcdef";
    let _ = write!(out, "B {mode} {n} {y0} ");
    for p in pixels {
        for shift in [12, 8, 4, 0] {
            out.byte(HEX[usize::from((p.0 >> shift) & 15)]);
        }
    }
    out.byte(b'\n');
    out.flush();
}

extern "C" {
    // cortex-m-rt's linker script: the stack's bounds (it grows down from `_stack_start` to
    // `_stack_end`, the end of the statics).
    static _stack_start: u32;
    static _stack_end: u32;
}

/// The stack's bounds `[end, start)`, from the linker script.
fn stack_bounds() -> (usize, usize) {
    // Only the symbols' addresses are taken, never their (nonexistent) contents.
    (
        core::ptr::addr_of!(_stack_end) as usize,
        core::ptr::addr_of!(_stack_start) as usize,
    )
}

/// Fills the stack below the current stack pointer (less a margin) with [`PAINT`], so that
/// [`stack_used`] can find the deepest word ever written. Nothing runs below the stack
/// pointer (no interrupts are enabled).
#[inline(never)]
fn paint_stack() {
    let sp = cortex_m::register::msp::read() as usize;
    let (mut at, _) = stack_bounds();
    while at + 256 < sp {
        // SAFETY: an aligned word of the stack's memory below the stack pointer, which
        // nothing uses.
        unsafe { write_volatile(at as *mut u32, PAINT) };
        at += 4;
    }
}

/// The most stack used since [`paint_stack`]: from the top of the stack down to the lowest
/// word no longer painted.
fn stack_used() -> usize {
    let (mut at, start) = stack_bounds();
    // SAFETY: aligned reads of the stack's memory (RAM).
    while at < start && unsafe { read_volatile(at as *const u32) } == PAINT {
        at += 4;
    }
    start - at
}

/// Renders and prints every frame of one mode: `B` lines (from the flush), then `CALL` and
/// `FRAME`.
#[inline(never)]
fn run_mode(
    t: &Tim2,
    storage: &mut scene::Storage,
    band: &mut Band<'_, Rgb565>,
    sent: &mut [Rgb565; BAND_PIXELS],
    (mode, shading): (&str, [arealight::raster::Shading; 2]),
    line: &mut Line,
) {
    let mut demo = match scene::demo(storage, shading) {
        Ok(d) => d,
        Err(e) => fail(line, format_args!("{mode}: Demo::new: {e:?}")),
    };
    let mut out = Out::new(line);
    for n in scene::FRAMES {
        // Instructions spent printing, which the clock leaves out.
        let paused = Cell::new(0u32);
        let mut clock = || cnt().wrapping_sub(paused.get());
        // The flush hands the band over (a copy), then prints the copy, uncounted.
        let flush = |b: &Band<'_, Rgb565>| {
            let px = b.pixels();
            let len = px.len().min(BAND_PIXELS);
            sent[..len].copy_from_slice(&px[..len]);
            compiler_fence(SeqCst);
            let t0 = cnt();
            compiler_fence(SeqCst);
            print_band(&mut out, mode, n, b.y0(), &sent[..len]);
            compiler_fence(SeqCst);
            let t1 = cnt();
            compiler_fence(SeqCst);
            paused.set(paused.get().wrapping_add(t1.wrapping_sub(t0)));
            Ok::<(), Infallible>(())
        };
        compiler_fence(SeqCst);
        let t0 = clock();
        compiler_fence(SeqCst);
        let report = scene::render(&mut demo, black_box(n), band, &mut clock, flush);
        compiler_fence(SeqCst);
        let t1 = clock();
        compiler_fence(SeqCst);
        let call = t.net(t1.wrapping_sub(t0));
        let report = match report {
            Ok(r) => r,
            Err(e) => fail(line, format_args!("{mode} frame {n}: {e:?}")),
        };
        let _ = write!(line, "CALL {mode} {n} {call}");
        line.send();
        let _ = write!(line, "FRAME {mode} {n} {}", report.total());
        for s in Stage::ALL {
            let _ = write!(line, " {}", report.ticks[s as usize]);
        }
        let st = report.stats;
        let _ = write!(line, " {} {} {}", st.shaded, st.pixels, st.rasterized);
        line.send();
    }
}

/// With the feature `scene-file`, instead of the demo: renders frame 0 of every scene of
/// `demo_scene::scenes` (the scene files of `host-sim/scenes/`, as written) and prints `CALL`
/// and `FRAME` lines as [`run_mode`] does, with the mode `scene:<name>` (no `B` lines: the
/// check is `host-sim budget --check`'s, on the counts and instructions).
#[cfg(feature = "scene-file")]
#[inline(never)]
fn run_scenes(
    t: &Tim2,
    buffers: &mut SpecBuffers<f32, { scenes::VERTICES }, { scenes::TRIANGLES }>,
    band: &mut Band<'_, Rgb565>,
    sent: &mut [Rgb565; BAND_PIXELS],
    line: &mut Line,
) {
    for spec in scenes::ALL {
        let mode = spec.name;
        let mut player = match Player::new(spec, buffers) {
            Ok(p) => p,
            Err(e) => fail(line, format_args!("scene:{mode}: Player::new: {e:?}")),
        };
        let mut clock = cnt;
        // The flush hands the band over (a copy), as the demo's does.
        let flush = |b: &Band<'_, Rgb565>| {
            let px = b.pixels();
            let len = px.len().min(BAND_PIXELS);
            sent[..len].copy_from_slice(&px[..len]);
            compiler_fence(SeqCst);
            Ok::<(), Infallible>(())
        };
        compiler_fence(SeqCst);
        let t0 = cnt();
        compiler_fence(SeqCst);
        let report = player.render_frame(band, &mut clock, flush);
        compiler_fence(SeqCst);
        let t1 = cnt();
        compiler_fence(SeqCst);
        let call = t.net(t1.wrapping_sub(t0));
        let report = match report {
            Ok(r) => r,
            Err(e) => fail(line, format_args!("scene:{mode}: {e:?}")),
        };
        let _ = write!(line, "CALL scene:{mode} 0 {call}");
        line.send();
        let _ = write!(line, "FRAME scene:{mode} 0 {}", report.total());
        for s in Stage::ALL {
            let _ = write!(line, " {}", report.ticks[s as usize]);
        }
        let st = report.stats;
        let _ = write!(line, " {} {} {}", st.shaded, st.pixels, st.rasterized);
        line.send();
    }
}

/// The unit costs of `host-sim budget --scene` (`demo_scene::calibrate`): `COST` lines.
#[cfg(not(feature = "scene-file"))]
#[inline(never)]
fn calibrate(buffers: &mut CalibrationBuffers<f32>, band: &mut Band<'_, Rgb565>, line: &mut Line) {
    let mut clock = cnt;
    let mut costs = Line::new();
    let result = calibrate::run(buffers, band, &mut clock, &mut |s| {
        let _ = write!(
            costs,
            "COST {} {} {} {} {}",
            s.item, s.count, s.setups, s.calls, s.ticks
        );
        costs.send();
    });
    if let Err(e) = result {
        fail(line, format_args!("calibrate: {e:?}"));
    }
}

#[entry]
fn main() -> ! {
    paint_stack();
    let mut line = Line::new();
    // SAFETY: CPUID is a read-only System Control Block register on every Cortex-M.
    let cpuid = unsafe { read_volatile(CPUID as *const u32) };
    let _ = write!(
        line,
        "INFO target=thumbv7em-none-eabihf cpuid={cpuid:08x} width={WIDTH} height={HEIGHT} band_rows={BAND_ROWS} frames="
    );
    for (i, n) in scene::FRAMES.iter().enumerate() {
        let _ = write!(line, "{}{n}", if i == 0 { "" } else { "," });
    }
    line.send();
    let t = Tim2::start();
    self_check(&t, &mut line);

    // SAFETY: the only reference to RAM, taken once, before anything else could.
    let ram = unsafe { &mut *addr_of_mut!(RAM) };
    let mut band = match Band::new(&mut ram.pixels, Some(&mut ram.depth), WIDTH, 0) {
        Ok(b) => b,
        Err(e) => fail(&mut line, format_args!("Band::new: {e:?}")),
    };
    #[cfg(feature = "scene-file")]
    run_scenes(&t, &mut ram.scenes, &mut band, &mut ram.sent, &mut line);
    #[cfg(not(feature = "scene-file"))]
    for mode in scene::MODES {
        run_mode(
            &t,
            &mut ram.storage,
            &mut band,
            &mut ram.sent,
            mode,
            &mut line,
        );
    }
    // The unit costs of `host-sim budget --scene` (instructions per item).
    #[cfg(not(feature = "scene-file"))]
    calibrate(&mut ram.calibration, &mut band, &mut line);
    let (end, start) = stack_bounds();
    let _ = write!(line, "STACK {} {}", stack_used(), start - end);
    line.send();
    let _ = write!(line, "DONE");
    line.send();
    debug::exit(debug::EXIT_SUCCESS);
    loop {
        cortex_m::asm::wfi();
    }
}

#[exception]
unsafe fn HardFault(ef: &ExceptionFrame) -> ! {
    let mut line = Line::new();
    fail(&mut line, format_args!("hard fault at pc={:08x}", ef.pc()))
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    let mut line = Line::new();
    fail(&mut line, format_args!("panic: {info}"))
}
