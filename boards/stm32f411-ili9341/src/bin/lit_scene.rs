//! arealight on an STM32F411 (WeAct Black Pill): a sphere and a tumbling torus under a
//! rectangular area light and an orbiting sphere light, shaded (Gouraud) in `f32` on the
//! Cortex-M4F's FPU and streamed to an ILI9341 display (240x320, the scene in its middle
//! 240x240) in 240x16 bands. Each frame's cost in core clock cycles, read from the DWT cycle
//! counter, goes to the defmt log (`cargo run --release` with probe-rs prints it).
//!
//! Wiring (see README.md): SPI1 with SCK on PA5, MOSI on PA7; CS on PA4, DC on PA3, RST on
//! PA2, backlight (LED) on PA1.
#![no_std]
#![no_main]
// No unsafe code of our own (`cortex_m::singleton!` allows it inside itself, so `deny`, not
// `forbid`).
#![deny(unsafe_code)]

// The defmt transport (RTT: the probe reads a ring buffer in RAM; no UART needed) ...
use defmt_rtt as _;
// ... and the panic handler: prints the panic message through defmt, then halts the core.
use panic_probe as _;

use arealight::raster::{Band, EncodeTable, Rgb565, Shading};
use cortex_m::peripheral::DWT;
use cortex_m::singleton;
use cortex_m_rt::entry;
use demo_scene::{Demo, MeshBuffers, Stage, BAND_PIXELS, HEIGHT, PERIOD, WIDTH};
use embedded_graphics_core::pixelcolor::Rgb565 as EgRgb565;
use embedded_graphics_core::prelude::{DrawTarget, RgbColor};
use embedded_hal_bus::spi::ExclusiveDevice;
use mipidsi::interface::SpiInterface;
use mipidsi::models::ILI9341Rgb565;
use mipidsi::options::ColorOrder;
use mipidsi::Builder;
use static_cell::ConstStaticCell;
use stm32f4xx_hal::spi::{Mode, Phase, Polarity, SpiExt};
use stm32f4xx_hal::{pac, prelude::*, rcc::Config};

/// Where the shader runs. Gouraud: the light models (Lambert and Phong of the polygon and
/// the sphere light) once per frame at each visible vertex (about 400), the colours
/// interpolated across the triangles in integers: real-time rates, faceted highlights.
/// `Shading::PerPixel` runs them at every visible pixel (about 13 000, a few thousand
/// instructions each): the area lights' soft, shaped highlights, several times slower (see
/// README.md for both, measured).
const SHADING: Shading = Shading::Gouraud;

/// The scene's meshes and per-frame vertex data, and its gamma table (see step 9).
static BUFFERS: ConstStaticCell<MeshBuffers<f32>> = ConstStaticCell::new(MeshBuffers::new());
static TABLE: ConstStaticCell<EncodeTable> = ConstStaticCell::new(EncodeTable::zeroed());

/// The core clock: the F411's maximum (from the Black Pill's 25 MHz crystal).
const SYSCLK_MHZ: u32 = 100;
/// SPI1 clock. SPI1 runs from APB2 (100 MHz), so 50 MHz (its maximum) or 25 MHz; the ILI9341's
/// datasheet asks for 10 MHz but most modules take 25 MHz and more over short wires.
const SPI_MHZ: u32 = 25;
/// The ILI9341 is 240x320 (portrait): the 240x240 scene goes in its middle rows.
const PANEL_HEIGHT: u16 = 320;
const TOP: u16 = (PANEL_HEIGHT - HEIGHT) / 2;

#[entry]
fn main() -> ! {
    defmt::info!("arealight on the STM32F411: f32, {}", SHADING);

    // 1. The peripherals, once: the chip's (PAC) and the Cortex-M core's (DWT, DCB, SysTick).
    let dp = pac::Peripherals::take().unwrap();
    let mut cp = cortex_m::Peripherals::take().unwrap();

    // 2. Clocks: the 25 MHz crystal (HSE) through the PLL to 100 MHz. `freeze` also sets the
    //    flash wait states (3 at 100 MHz) and turns on the flash's prefetch and caches (ART).
    let mut rcc = dp
        .RCC
        .freeze(Config::hse(25.MHz()).sysclk(SYSCLK_MHZ.MHz()));

    // 3. The cycle counter: DWT's CYCCNT counts core clock cycles once the debug block's trace
    //    is enabled (DCB DEMCR.TRCENA). 32 bits: it wraps after 42.9 s at 100 MHz, so frames
    //    are timed by wrapping differences (a frame must take less than that).
    cp.DCB.enable_trace();
    cp.DWT.enable_cycle_counter();

    // 4. A blocking delay from SysTick, for the display's reset and init sequence.
    let mut delay = cp.SYST.delay(&rcc.clocks);

    // 5. GPIO: SPI1's pins in their alternate function (AF5), the display's control pins as
    //    push-pull outputs.
    let gpioa = dp.GPIOA.split(&mut rcc);
    let sck = gpioa.pa5.into_alternate();
    let mosi = gpioa.pa7.into_alternate();
    let cs = gpioa.pa4.into_push_pull_output();
    let dc = gpioa.pa3.into_push_pull_output();
    let rst = gpioa.pa2.into_push_pull_output();
    let mut backlight = gpioa.pa1.into_push_pull_output();

    // 6. SPI1, transmit only (the display is never read: no MISO), mode 0.
    let spi_bus = dp.SPI1.spi(
        (Some(sck), pac::SPI1::NoMiso, Some(mosi)),
        Mode {
            polarity: Polarity::IdleLow,
            phase: Phase::CaptureOnFirstTransition,
        },
        SPI_MHZ.MHz(),
        &mut rcc,
    );

    // 7. embedded-hal 1.0 splits the bus (clock and data) from the device (the bus plus this
    //    display's chip select): `ExclusiveDevice` is the device of a bus it alone uses (no
    //    delays inside transactions, so no delay source).
    let spi = ExclusiveDevice::new_no_delay(spi_bus, cs).unwrap();

    // 8. The ILI9341 driver (mipidsi): a 512-byte buffer in which it gathers pixels into SPI
    //    writes, the reset pin, BGR subpixel order (what the common red 2.4"/2.8" modules
    //    have; swap to `ColorOrder::Rgb` if red and blue come out exchanged). `init` resets
    //    the panel and sends the init sequence; then the whole panel is cleared once, the
    //    frames only ever write the scene's 240x240 rows.
    let spi_buffer = singleton!(: [u8; 512] = [0; 512]).unwrap();
    let interface = SpiInterface::new(spi, dc, spi_buffer);
    let mut display = Builder::new(ILI9341Rgb565, interface)
        .color_order(ColorOrder::Bgr)
        .reset_pin(rst)
        .init(&mut delay)
        .unwrap();
    display.clear(EgRgb565::BLACK).unwrap();
    backlight.set_high();

    // 9. The scene (shared with the RP2040 firmware: boards/demo-scene). Its meshes (a UV
    //    sphere and a torus) and their per-frame vertex data (60 KiB), and the gamma table
    //    (16 KiB) live in statics, filled once; the camera, materials and draw options are set
    //    once. `BUFFERS` and `TABLE` are initialized at link time (all zeros: no copy through
    //    the stack, which would need more than the F411's 128 KiB at start-up); `take` hands
    //    out their `&'static mut` once.
    let buffers = BUFFERS.take();
    let mut demo = Demo::<f32>::new(buffers, TABLE.take(), SHADING).unwrap();

    // 10. One band: 240x16 RGB565 pixels and their 16-bit depths (7.5 KiB each). The whole
    //     frame is rendered through it, 15 times per frame.
    let pixels = singleton!(: [Rgb565; BAND_PIXELS] = [Rgb565(0); BAND_PIXELS]).unwrap();
    let depth = singleton!(: [u16; BAND_PIXELS] = [0; BAND_PIXELS]).unwrap();
    let mut band = Band::new(pixels, Some(depth), WIDTH, 0).unwrap();

    // 11. The animation: frame n shows phase n / PERIOD. `render_frame` does the whole frame
    //     (the lights, every vertex transformed and shaded once, then the bands, each sent
    //     as soon as it is drawn) and times its stages in core cycles (DWT).
    let mut n: u32 = 0;
    loop {
        let result = demo.render_frame(n, &mut band, &mut DWT::cycle_count, |band| {
            // Send the band's rows to the panel rows TOP + y0 .. (one address window, then
            // the pixels, converted to embedded-graphics' Rgb565: the same bits).
            let (y0, last) = (TOP + band.y0(), TOP + band.y0() + band.rows() - 1);
            let colours = band.pixels().iter().map(|&p| EgRgb565::from(p));
            display.set_pixels(0, y0, WIDTH - 1, last, colours)
        });
        match result {
            Ok(report) => {
                let c = |s: Stage| report.ticks[s as usize];
                let cycles = report.total();
                defmt::info!(
                    "frame {=u32}: {=u32} cycles = {=u32} ms (setup {=u32}, transform {=u32}, shade {=u32}, raster {=u32}, flush {=u32}), {=u32} shader calls, {=u32} pixels, {=u32} triangle setups",
                    n,
                    cycles,
                    cycles / (SYSCLK_MHZ * 1000),
                    c(Stage::Setup),
                    c(Stage::Transform),
                    c(Stage::Shade),
                    c(Stage::Raster),
                    c(Stage::Flush),
                    report.stats.shaded,
                    report.stats.pixels,
                    report.stats.rasterized
                );
            }
            Err(e) => defmt::error!("frame {=u32}: {}", n, defmt::Debug2Format(&e)),
        }
        if n % PERIOD == PERIOD - 1 {
            defmt::info!("one period ({=u32} frames) done", PERIOD);
        }
        n = n.wrapping_add(1);
    }
}
