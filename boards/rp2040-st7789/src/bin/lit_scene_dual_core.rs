//! The scene of `lit_scene.rs`, drawn by both of the RP2040's cores: core 0 draws the even
//! bands (rows 0-15, 32-47, ...) and sends every band to the display, core 1 draws the odd
//! bands and hands each one over. Each core transforms every vertex, but shades only half of
//! the visible vertices (`Demo::shade_share`: even or odd indices), and the two swap their
//! colours, so the light models are split between the cores too. The frames are the same
//! pixels as `lit_scene.rs`'s. Run it with
//! `cargo run --release --bin lit_scene_dual_core`.
//!
//! The board setup (clocks, timer, SPI, display) is step for step that of `lit_scene.rs`, whose
//! comments explain it; the comments here are about the second core.
//!
//! How the cores cooperate, with no `unsafe` and no shared mutable state outside one mutex:
//!
//! - Each core has its own copy of everything it draws with: meshes, per-frame vertex data,
//!   `Demo`, band and depth band (both copies are built the same way, so both cores compute
//!   identical frames; a vertex both cores shade gets the same colour on both).
//! - [`HANDOFF`], behind a `critical_section::Mutex` (rp2040-hal's critical section is a
//!   hardware spinlock, so it excludes the other core too), carries the frame number from core
//!   0 to core 1, each core's share of the vertex colours to the other, and each finished odd
//!   band (its first row and its pixels) from core 1 to core 0.
//! - A core that finds nothing to do waits for an event (`wfe`); the other core signals one
//!   (`sev`) after every change to the handoff.
#![no_std]
#![no_main]
// Every line here is safe Rust but two, each allowed where it is and explained there.
#![deny(unsafe_code)]

use defmt_rtt as _;
use panic_probe as _;

use core::cell::RefCell;

use arealight::raster::{Band, DrawStats, Rgb565, Shading};
use arealight::Fixed22;
use cortex_m::singleton;
use critical_section::Mutex;
use demo_scene::{
    ColourExchange, Demo, Frame, MeshBuffers, BACKGROUND, BAND_PIXELS, BAND_ROWS, HEIGHT, PERIOD,
    WIDTH,
};
use embedded_hal::digital::OutputPin;
use embedded_hal_bus::spi::ExclusiveDevice;
use hal::clocks::Clock;
use hal::dma::DMAExt;
use hal::fugit::RateExtU32;
use hal::multicore::{Multicore, Stack};
use hal::pac;
use mipidsi::interface::SpiInterface;
use mipidsi::models::ST7789;
use mipidsi::options::ColorInversion;
use mipidsi::Builder;
use rp2040_hal as hal;
use rp2040_st7789::{BandSender, DmaBuffer};
use static_cell::ConstStaticCell;

/// The second-stage bootloader (see `lit_scene.rs`).
#[allow(unsafe_code)]
#[link_section = ".boot2"]
#[used]
pub static BOOT2_FIRMWARE: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

const XTAL_FREQ_HZ: u32 = 12_000_000;

/// Gouraud shading, as in `lit_scene.rs`.
const SHADING: Shading = Shading::Gouraud;

/// The bands of a frame (15 of 16 rows).
const BANDS: u16 = HEIGHT.div_ceil(BAND_ROWS);

/// Each core's meshes, per-frame vertex data and gamma table (about 64 KiB each), initialized
/// at link time (all zeros: no copy through a stack).
static CORE0_BUFFERS: ConstStaticCell<MeshBuffers<Fixed22>> =
    ConstStaticCell::new(MeshBuffers::new());
static CORE1_BUFFERS: ConstStaticCell<MeshBuffers<Fixed22>> =
    ConstStaticCell::new(MeshBuffers::new());

/// Core 1's stack, in words: 16 KiB (the meshes, per-frame data and bands are statics; the stack holds
/// the rasterizer's clipping buffers, a frame's lights and the light models' locals).
static CORE1_STACK: Stack<4096> = Stack::new();

/// What the two cores exchange.
struct Handoff {
    /// The frame core 1 is to draw next (set by core 0, taken by core 1).
    frame: Option<u32>,
    /// A band core 1 has finished: its first row (set by core 1, taken by core 0) ...
    ready: Option<u16>,
    /// ... its pixels ...
    pixels: [Rgb565; BAND_PIXELS],
    /// ... and what drawing it did.
    stats: DrawStats,
    /// `shaded[k]`: core k's share of this frame's vertex colours is in `colours[k]` (set by
    /// core k, cleared by the other core once it has taken them).
    shaded: [bool; 2],
    colours: [ColourExchange; 2],
}

static HANDOFF: Mutex<RefCell<Handoff>> = Mutex::new(RefCell::new(Handoff {
    frame: None,
    ready: None,
    pixels: [Rgb565(0); BAND_PIXELS],
    stats: DrawStats {
        triangles: 0,
        rasterized: 0,
        shaded: 0,
        pixels: 0,
    },
    shaded: [false; 2],
    colours: [ColourExchange::new(), ColourExchange::new()],
}));

/// The cores' split of the vertex shading: core `core` shades the visible vertices of index
/// `core` modulo 2, hands its colours to the other core and takes the other core's, so that
/// both then hold every visible vertex's colour, each shaded once per frame.
fn share_shading(demo: &mut Demo<'_, Fixed22>, frame: &Frame<Fixed22>, core: usize) -> u32 {
    let calls = demo.shade_share(frame, core, 2);
    wait_for(|h| {
        if h.shaded[core] {
            return None;
        }
        demo.export_colours(&mut h.colours[core]);
        h.shaded[core] = true;
        Some(())
    });
    cortex_m::asm::sev();
    let other = 1 - core;
    wait_for(|h| {
        if !h.shaded[other] {
            return None;
        }
        demo.import_colours(&h.colours[other], other, 2);
        h.shaded[other] = false;
        Some(())
    });
    cortex_m::asm::sev();
    calls
}

/// Runs `f` on the handoff under the lock until it returns `Some`, sleeping until the other
/// core's next event between tries.
fn wait_for<R>(mut f: impl FnMut(&mut Handoff) -> Option<R>) -> R {
    loop {
        if let Some(r) = critical_section::with(|cs| f(&mut HANDOFF.borrow_ref_mut(cs))) {
            return r;
        }
        cortex_m::asm::wfe();
    }
}

/// Core 1: draws the odd bands of each frame core 0 asks for, and hands each one over.
fn core1(buffers: &'static mut MeshBuffers<Fixed22>) {
    let mut demo = Demo::<Fixed22>::new(buffers, SHADING).unwrap();
    // Core 1's band and depth band, in statics like core 0's (7.5 KiB each).
    let pixels = singleton!(: [Rgb565; BAND_PIXELS] = [Rgb565(0); BAND_PIXELS]).unwrap();
    let depth = singleton!(: [u16; BAND_PIXELS] = [0; BAND_PIXELS]).unwrap();
    let mut band = Band::new(pixels, Some(depth), WIDTH, 0).unwrap();
    loop {
        let n = wait_for(|h| h.frame.take());
        let frame = demo.frame(n).unwrap();
        demo.transform(&frame);
        // Counted with the first band handed over.
        let mut shaded = share_shading(&mut demo, &frame, 1);
        for k in (1..BANDS).step_by(2) {
            let mut stats = DrawStats {
                shaded: core::mem::take(&mut shaded),
                ..DrawStats::default()
            };
            band.move_to(k * BAND_ROWS);
            band.clear(BACKGROUND);
            demo.draw_band(&frame, &mut band, &mut stats).unwrap();
            // Wait until core 0 has taken the previous band, then hand this one over.
            wait_for(|h| {
                if h.ready.is_some() {
                    return None;
                }
                h.pixels.copy_from_slice(band.pixels());
                h.ready = Some(band.y0());
                h.stats = stats;
                Some(())
            });
            cortex_m::asm::sev();
        }
    }
}

// `hal::entry`: see `lit_scene.rs`.
#[allow(unsafe_code)]
#[hal::entry]
fn main() -> ! {
    run()
}

/// The program proper, outside the `allow` above.
fn run() -> ! {
    defmt::info!("arealight on the RP2040, both cores: Fixed22, {}", SHADING);

    // Board setup: steps 1 to 8 of `lit_scene.rs`.
    let mut pac = pac::Peripherals::take().unwrap();
    let mut watchdog = hal::Watchdog::new(pac.WATCHDOG);
    let clocks = hal::clocks::init_clocks_and_plls(
        XTAL_FREQ_HZ,
        pac.XOSC,
        pac.CLOCKS,
        pac.PLL_SYS,
        pac.PLL_USB,
        &mut pac.RESETS,
        &mut watchdog,
    )
    .ok()
    .unwrap();
    let mut timer = hal::Timer::new(pac.TIMER, &mut pac.RESETS, &clocks);
    let mut sio = hal::Sio::new(pac.SIO);
    let pins = hal::gpio::Pins::new(
        pac.IO_BANK0,
        pac.PADS_BANK0,
        sio.gpio_bank0,
        &mut pac.RESETS,
    );
    let sclk = pins.gpio10.into_function::<hal::gpio::FunctionSpi>();
    let mosi = pins.gpio11.into_function::<hal::gpio::FunctionSpi>();
    let mut spi_bus = hal::spi::Spi::<_, _, _, 8>::new(pac.SPI1, (mosi, sclk)).init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        62_500_000u32.Hz(),
        embedded_hal::spi::MODE_0,
    );
    let mut cs = pins.gpio9.into_push_pull_output();
    let mut dc = pins.gpio8.into_push_pull_output();
    let rst = pins.gpio12.into_push_pull_output();
    let mut backlight = pins.gpio13.into_push_pull_output();
    {
        let spi = ExclusiveDevice::new(&mut spi_bus, &mut cs, timer).unwrap();
        let spi_buffer = singleton!(: [u8; 512] = [0; 512]).unwrap();
        let interface = SpiInterface::new(spi, &mut dc, spi_buffer);
        Builder::new(ST7789, interface)
            .display_size(WIDTH, HEIGHT)
            .invert_colors(ColorInversion::Inverted)
            .reset_pin(rst)
            .init(&mut timer)
            .unwrap();
    }
    backlight.set_high().unwrap();
    let (spi1, spi_pins) = spi_bus.free();
    let spi16 = hal::spi::Spi::<_, _, _, 16>::new(spi1, spi_pins).init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        62_500_000u32.Hz(),
        embedded_hal::spi::MODE_0,
    );
    let dma = pac.DMA.split(&mut pac.RESETS);
    let dma_buffer = singleton!(: DmaBuffer = [0; BAND_PIXELS]).unwrap();
    let mut display = BandSender::new(dma.ch0, spi16, dma_buffer, dc, cs);

    // 9. Core 1: its meshes and per-frame data (statics, handed to it), its stack, and its
    //    program (`core1`, which builds its own `Demo` from them). The power-on state machine
    //    (PSM) and the FIFO between the cores are used once, to start it.
    let core1_buffers = CORE1_BUFFERS.take();
    let mut multicore = Multicore::new(&mut pac.PSM, &mut pac.PPB, &mut sio.fifo);
    let cores = multicore.cores();
    cores[1]
        .spawn(CORE1_STACK.take().unwrap(), move || core1(core1_buffers))
        .unwrap();

    // 10. Core 0's own scene and band, as in `lit_scene.rs`.
    let buffers = CORE0_BUFFERS.take();
    let mut demo = Demo::<Fixed22>::new(buffers, SHADING).unwrap();
    let pixels = singleton!(: [Rgb565; BAND_PIXELS] = [Rgb565(0); BAND_PIXELS]).unwrap();
    let depth = singleton!(: [u16; BAND_PIXELS] = [0; BAND_PIXELS]).unwrap();
    let mut band = Band::new(pixels, Some(depth), WIDTH, 0).unwrap();

    // 11. Each frame: tell core 1 to start, then go down the bands in order, drawing the even
    //     ones here and taking the odd ones from core 1 (copied into this core's band buffer,
    //     which is free at that point), sending each to the display.
    let mut n: u32 = 0;
    loop {
        let start = timer.get_counter_low();
        critical_section::with(|cs| HANDOFF.borrow_ref_mut(cs).frame = Some(n));
        cortex_m::asm::sev();
        let frame = demo.frame(n).unwrap();
        let t_setup = timer.get_counter_low();
        demo.transform(&frame);
        let t_transform = timer.get_counter_low();
        let mut stats = DrawStats {
            shaded: share_shading(&mut demo, &frame, 0),
            ..DrawStats::default()
        };
        let t_shade = timer.get_counter_low();
        let (mut raster_us, mut wait_us, mut send_us) = (0u32, 0u32, 0u32);
        for k in 0..BANDS {
            let t0 = timer.get_counter_low();
            if k % 2 == 0 {
                band.move_to(k * BAND_ROWS);
                band.clear(BACKGROUND);
                demo.draw_band(&frame, &mut band, &mut stats).unwrap();
                raster_us += timer.get_counter_low().wrapping_sub(t0);
            } else {
                let s = wait_for(|h| {
                    let y0 = h.ready.take()?;
                    band.move_to(y0);
                    band.pixels_mut().copy_from_slice(&h.pixels);
                    Some(h.stats)
                });
                // Core 1 may be waiting to hand over its next band.
                cortex_m::asm::sev();
                stats.rasterized += s.rasterized;
                stats.shaded += s.shaded;
                stats.pixels += s.pixels;
                wait_us += timer.get_counter_low().wrapping_sub(t0);
            }
            let t1 = timer.get_counter_low();
            if let Err(e) = display.send(&band) {
                defmt::error!("frame {}: {}", n, defmt::Debug2Format(&e));
            }
            send_us += timer.get_counter_low().wrapping_sub(t1);
        }
        let total_us = timer.get_counter_low().wrapping_sub(start);
        defmt::info!(
            "frame {=u32}: {=u32} us on core 0 (setup {=u32}, transform {=u32}, shade {=u32}, raster {=u32}, waiting for core 1 {=u32}, flush {=u32}), {=u32} shader calls on both cores, {=u32} pixels, {=u32} triangle setups",
            n,
            total_us,
            t_setup.wrapping_sub(start),
            t_transform.wrapping_sub(t_setup),
            t_shade.wrapping_sub(t_transform),
            raster_us,
            wait_us,
            send_us,
            stats.shaded,
            stats.pixels,
            stats.rasterized
        );
        if n % PERIOD == PERIOD - 1 {
            defmt::info!("one period ({=u32} frames) done", PERIOD);
        }
        n = n.wrapping_add(1);
    }
}
