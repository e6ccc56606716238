//! arealight on a Raspberry Pi Pico: a sphere and a tumbling torus under a rectangular area
//! light and an orbiting sphere light, shaded in fixed point (`Fixed22`: the RP2040's
//! Cortex-M0+ has no FPU) and streamed to a 240x240 ST7789 display in 240x60 bands. Each
//! frame's time goes to the defmt log (`cargo run --release` with probe-rs prints it).
//!
//! Wiring (the Waveshare Pico-LCD-1.3's pins; any 240x240 ST7789 module wired the same way
//! works): SPI1 with SCK on GP10, MOSI on GP11, CS on GP9, DC on GP8, RST on GP12, backlight
//! on GP13. See README.md.
#![no_std]
#![no_main]
// Every line here is safe Rust but two, each allowed where it is and explained there.
#![deny(unsafe_code)]

// The defmt transport (RTT: the probe reads a ring buffer in RAM; no UART needed) ...
use defmt_rtt as _;
// ... and the panic handler: prints the panic message through defmt, then halts the core.
use panic_probe as _;

use arealight::raster::{Band, EncodeTable, Rgb565, Shading};
use arealight::Fixed22;
use cortex_m::singleton;
use demo_scene::{Demo, MeshBuffers, Output, Stage, BACKGROUND, HEIGHT, PERIOD, WIDTH};
use embedded_hal::digital::OutputPin;
use embedded_hal_bus::spi::ExclusiveDevice;
use hal::clocks::Clock;
use hal::dma::DMAExt;
use hal::fugit::RateExtU32;
use hal::pac;
use mipidsi::interface::SpiInterface;
use mipidsi::models::ST7789;
use mipidsi::options::ColorInversion;
use mipidsi::Builder;
use rp2040_hal as hal;
use rp2040_st7789::{BandSender, DmaBuffer};
use static_cell::ConstStaticCell;

/// The second-stage bootloader. The RP2040's boot ROM copies the first 256 bytes of flash to
/// SRAM and runs them; this code (for the Pico's W25Q16JV flash, which the W25Q080 loader
/// drives) sets up execute-in-place from the QSPI flash and jumps to the vector table.
// `link_section` counts as unsafe code (the linker puts the bytes where the section says);
// memory.x places `.boot2` at the start of flash, which is exactly what the boot ROM expects.
#[allow(unsafe_code)]
#[link_section = ".boot2"]
#[used]
pub static BOOT2_FIRMWARE: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

/// The scene's meshes and per-frame vertex data, and its gamma table (see step 9).
static BUFFERS: ConstStaticCell<MeshBuffers<Fixed22>> = ConstStaticCell::new(MeshBuffers::new());
static TABLE: ConstStaticCell<EncodeTable> = ConstStaticCell::new(EncodeTable::zeroed());

/// Rows per band: 60, four bands per frame. Taller bands than the scene's default 16 mean fewer
/// triangles set up twice (once per band they cross) and fewer passes over the meshes: 8 %
/// fewer cycles per frame in rp2040js with 40 rows, for 45 KiB of band, depth and DMA buffers
/// (the two-core firmware draws 20-row bands: it has two of everything). Frames 1 to 15 of
/// `run.mjs --frames 16`, on average: 8 255 792 cycles with 40 rows, 8 181 631 with 48,
/// 8 104 917 with 60 (84 KiB of buffers), 8 387 657 with 80 (the frame's last band, a third of
/// it, then waits for the SPI), 8 057 912 with 120 (169 KiB: little left for the stack). It
/// must divide the height.
const ROWS: u16 = 60;
const PIXELS: usize = WIDTH as usize * ROWS as usize;
const _: () = assert!(HEIGHT % ROWS == 0);

/// The Pico's crystal.
const XTAL_FREQ_HZ: u32 = 12_000_000;

/// Where the shader runs. Per pixel, each of the ~13 000 visible pixels would evaluate
/// Lambert and Phong for the polygon and the sphere light in fixed point (seconds per frame);
/// Gouraud evaluates them once per frame at each visible vertex (about 400) and interpolates
/// the colours across the triangles in integers.
const SHADING: Shading = Shading::Gouraud;

// `hal::entry` is cortex-m-rt's `entry` plus a reset of the RP2040's hardware spinlocks (which
// a debugger reset leaves as they were). It expands to an `unsafe` block, hence the `allow`.
#[allow(unsafe_code)]
#[hal::entry]
fn main() -> ! {
    run()
}

/// The program proper, outside the `allow` above.
fn run() -> ! {
    defmt::info!("arealight on the RP2040: Fixed22, {}", SHADING);

    // 1. The peripherals, once (the PAC hands them out a single time).
    let mut pac = pac::Peripherals::take().unwrap();

    // 2. Clocks: the 12 MHz crystal, the system PLL at 125 MHz (core and SPI), the USB PLL at
    //    48 MHz. The watchdog is only needed for its tick, which drives the timer at 1 MHz.
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

    // 3. The 64-bit microsecond timer: frame times, and the delays of the display's reset.
    let mut timer = hal::Timer::new(pac.TIMER, &mut pac.RESETS, &clocks);

    // 4. The GPIO pins (single-cycle IO block for the outputs).
    let sio = hal::Sio::new(pac.SIO);
    let pins = hal::gpio::Pins::new(
        pac.IO_BANK0,
        pac.PADS_BANK0,
        sio.gpio_bank0,
        &mut pac.RESETS,
    );

    // 5. SPI1 on GP10 (SCK) and GP11 (MOSI), transmit only (the ST7789 is never read), at
    //    62.5 MHz: the peripheral clock (125 MHz) over 2, the SPI block's fastest. Mode 0 (the
    //    Pico-LCD-1.3; many bare 240x240 modules without a CS pin want MODE_3 instead).
    let sclk = pins.gpio10.into_function::<hal::gpio::FunctionSpi>();
    let mosi = pins.gpio11.into_function::<hal::gpio::FunctionSpi>();
    let mut spi_bus = hal::spi::Spi::<_, _, _, 8>::new(pac.SPI1, (mosi, sclk)).init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        62_500_000u32.Hz(),
        embedded_hal::spi::MODE_0,
    );

    // 6. The display's control pins: chip select, data/command, reset, backlight.
    let mut cs = pins.gpio9.into_push_pull_output();
    let mut dc = pins.gpio8.into_push_pull_output();
    let rst = pins.gpio12.into_push_pull_output();
    let mut backlight = pins.gpio13.into_push_pull_output();

    // 7. The ST7789's reset and init sequence, by the mipidsi driver. embedded-hal 1.0 splits
    //    the bus (clock and data) from the device (the bus plus this display's chip select):
    //    `ExclusiveDevice` is the device of a bus it alone uses. The driver borrows the bus
    //    and the pins (`&mut`): they come back when it is dropped, after the init. Its
    //    options: IPS colour inversion (the Pico-LCD-1.3 panel, like most 240x240 IPS
    //    modules, shows inverted colours without it), 240x240 of the chip's 240x320 memory.
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

    // 8. The frames go out by DMA (see `rp2040_st7789::BandSender`): SPI1 again, now with
    //    16-bit frames (a pixel per frame, big-endian on the wire), DMA channel 0, and a
    //    buffer of one band (19 KiB) that the DMA reads while the next band is drawn.
    let (spi1, spi_pins) = spi_bus.free();
    let spi16 = hal::spi::Spi::<_, _, _, 16>::new(spi1, spi_pins).init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        62_500_000u32.Hz(),
        embedded_hal::spi::MODE_0,
    );
    let dma = pac.DMA.split(&mut pac.RESETS);
    let dma_buffer = singleton!(: DmaBuffer<PIXELS> = [Rgb565(0); PIXELS]).unwrap();
    let mut display = BandSender::new(dma.ch0, spi16, dma_buffer, dc, cs);

    // 9. The scene (shared with the STM32F411 firmware: boards/demo-scene). Its meshes (a
    //    UV sphere and a torus) and their per-frame vertex data (60 KiB), and the gamma table
    //    (16 KiB) live in statics, filled once; the camera, materials and draw options are set
    //    once. `BUFFERS` and `TABLE` are initialized at link time (all zeros: no copy through
    //    the stack, which 60 KiB would overflow on the second core's firmware); `take` hands
    //    out their `&'static mut` once.
    let buffers = BUFFERS.take();
    let mut demo = Demo::<Fixed22>::new(buffers, TABLE.take(), SHADING).unwrap();

    // 10. One band: 240x60 RGB565 pixels and their 16-bit depths (28 KiB each). The whole
    //     frame is rendered through it, 4 times per frame.
    let pixels = singleton!(: [Rgb565; PIXELS] = [Rgb565(0); PIXELS]).unwrap();
    let depth = singleton!(: [u16; PIXELS] = [0; PIXELS]).unwrap();
    let mut band = Band::new(pixels, Some(depth), WIDTH, 0).unwrap();

    // 11. The animation: frame n shows phase n / PERIOD. `render_frame` does the whole frame
    //     (the lights, every vertex transformed and shaded once, then the bands, each sent
    //     as soon as it is drawn: `BandSender::send`, by DMA, while the next is drawn) and
    //     times its stages with the 1 MHz timer.
    //     An empty last band is not drawn: it is sent as the background early in the next
    //     frame, once its transform is done (`render_frame_carrying`), so the frame does not
    //     wait for the band before it to be sent.
    let mut n: u32 = 0;
    let mut kept: Option<(u16, u16)> = None;
    loop {
        let mut clock = || timer.get_counter_low();
        let result = demo.render_frame_carrying(n, &mut band, &mut clock, |out| match out {
            Output::Band(band) => display.send_swapping(band),
            Output::Keep { y0, rows } => {
                kept = Some((y0, rows));
                Ok(())
            }
            Output::Carried => match kept.take() {
                Some((y0, rows)) => display.send_uniform(y0, rows, BACKGROUND),
                None => Ok(()),
            },
        });
        // The last band's transfer ends the frame (timed with the next frame's first band).
        match result {
            Ok(report) => {
                let us = |s: Stage| report.ticks[s as usize];
                defmt::info!(
                    "frame {=u32}: {=u32} us (setup {=u32}, transform {=u32}, shade {=u32}, raster {=u32}, flush {=u32}), {=u32} shader calls, {=u32} pixels, {=u32} triangle setups",
                    n,
                    report.total(),
                    us(Stage::Setup),
                    us(Stage::Transform),
                    us(Stage::Shade),
                    us(Stage::Raster),
                    us(Stage::Flush),
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
