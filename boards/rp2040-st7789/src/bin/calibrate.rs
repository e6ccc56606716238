//! The unit costs of `host-sim budget --scene` on the RP2040 (Fixed22): what a light model
//! call, a vertex, a triangle setup, a pixel and a band cost, in core cycles, measured on
//! synthetic work (`demo_scene::calibrate`) rather than on the demo's frame, so that the demo's
//! frame can check the predictions made from them.
//!
//! It prints one defmt line per item, `cost <item> <count> <triangle setups> <shader calls>
//! <cycles>`, then `calibration done`, and idles. `boards/rp2040-emu/check.sh` runs it in
//! rp2040js (built with `--features emulator`) and writes the lines to
//! `target/rp2040-emu/calibration.csv`; on a Pico, `cargo run --release --bin calibrate` prints
//! them through the probe.
//!
//! The clock is SysTick on the core clock (125 MHz): exact cycles, 24 bits, extended in
//! software (every interval timed is far below 2^24 cycles, 134 ms).
#![no_std]
#![no_main]
#![deny(unsafe_code)]

use defmt_rtt as _;
use panic_probe as _;

use arealight::raster::{Band, Rgb565};
use arealight::Fixed22;
use cortex_m::peripheral::syst::SystClkSource;
use cortex_m::peripheral::SYST;
use cortex_m::singleton;
use demo_scene::calibrate::{self, CalibrationBuffers};
use demo_scene::WIDTH;
use rp2040_hal as hal;
use static_cell::ConstStaticCell;

use hal::pac;

// The second-stage bootloader, as in `lit_scene`.
#[allow(unsafe_code)]
#[link_section = ".boot2"]
#[used]
pub static BOOT2_FIRMWARE: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

/// The calibration's meshes (about 30 KiB), zeroed at link time.
static BUFFERS: ConstStaticCell<CalibrationBuffers<Fixed22>> =
    ConstStaticCell::new(CalibrationBuffers::new());

/// Rows per band: the single-core firmware's (`lit_scene`), so the band costs are its own.
const ROWS: u16 = 40;
const PIXELS: usize = WIDTH as usize * ROWS as usize;

const XTAL_FREQ_HZ: u32 = 12_000_000;

#[allow(unsafe_code)]
#[hal::entry]
fn main() -> ! {
    defmt::info!("arealight calibration on the RP2040: Fixed22, cycles per item");
    let mut pac = pac::Peripherals::take().unwrap();
    let core = pac::CorePeripherals::take().unwrap();
    let mut watchdog = hal::Watchdog::new(pac.WATCHDOG);
    // The clocks as the firmware sets them: 125 MHz from the PLL.
    let _clocks = hal::clocks::init_clocks_and_plls(
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

    // SysTick counts core cycles down from 2^24 - 1; the clock below counts them up, in 32
    // bits, adding the difference since its last read (modulo 2^24).
    let mut syst = core.SYST;
    syst.set_clock_source(SystClkSource::Core);
    syst.set_reload(0x00FF_FFFF);
    syst.clear_current();
    syst.enable_counter();
    let mut last = SYST::get_current();
    let mut cycles: u32 = 0;
    let mut clock = move || {
        let now = SYST::get_current();
        cycles = cycles.wrapping_add(last.wrapping_sub(now) & 0x00FF_FFFF);
        last = now;
        cycles
    };

    let pixels = singleton!(: [Rgb565; PIXELS] = [Rgb565(0); PIXELS]).unwrap();
    let depth = singleton!(: [u16; PIXELS] = [0; PIXELS]).unwrap();
    let mut band = Band::new(pixels, Some(depth), WIDTH, 0).unwrap();
    let buffers = BUFFERS.take();
    let result = calibrate::run(buffers, &mut band, &mut clock, &mut |s| {
        defmt::info!(
            "cost {=str} {=u32} {=u32} {=u32} {=u32}",
            s.item,
            s.count,
            s.setups,
            s.calls,
            s.ticks
        );
    });
    match result {
        Ok(()) => defmt::info!("calibration done"),
        Err(e) => defmt::error!("calibration failed: {}", defmt::Debug2Format(&e)),
    }
    loop {
        cortex_m::asm::wfi();
    }
}
