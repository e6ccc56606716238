//! The scene of `lit_scene.rs`, drawn by both of the RP2040's cores. Each core transforms
//! half of the vertices (`Demo::transform_share`: even or odd indices) and the two swap
//! their screen data, then each shades its half of the visible vertices (`Demo::shade_share`,
//! the same halves) and the two swap their colours, so the transform and the light models
//! are split between the cores. Then the cores share the bands: each takes the next band from a common list, draws
//! it and sends it to the display itself. The frames are the same pixels as `lit_scene.rs`'s.
//! Run it with `cargo run --release --bin lit_scene_dual_core`.
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
//!   0 to core 1, the list of the frame's bands, and each core's share of the vertices'
//!   screen data, visible-vertex marks and colours to the other: not the data themselves,
//!   which each core writes into its own buffers (`CORE0_SCREEN`, ...) outside the lock, but
//!   the buffers' references ([`Mailbox`], [`exchange`]), so the cores copy at the same time;
//!   [`SENDER`], behind another mutex, the display's sender (the DMA channel, SPI and
//!   pins). A core that has drawn a band takes the sender, sends the band (each band is its
//!   own address window, so the order is free; the sender waits for the previous band's
//!   transfer, takes the band's pixel buffer for the new one and gives the band the buffer
//!   that has just been sent: three pixel buffers pass between the cores and the sender) and
//!   puts it back.
//! - A core that finds nothing to do waits for an event (`wfe`); the other core signals one
//!   (`sev`) after every change to the handoff.
//!
//! **Which core draws which band.** The bands' cost is very uneven (the three through the
//! objects' middle take about 1 M cycles each, the empty ones 20 000), and every band takes
//! the SPI 154 000 cycles to send, one at a time. Each core holds its drawn band until the SPI
//! is free, so a core drawing cheap bands is paced by the SPI, while one drawing an expensive
//! band leaves the SPI idle. So the bands (but the first and the last) are split between the
//! cores by their cost in the previous frame (triangle setups and pixels, from `DrawStats`; in
//! frame 0 all equal) with the longest-first rule ([`band_order`]): core 0 takes its share
//! from its most expensive band down, core 1 its share from the cheapest up, so core 1 keeps
//! the SPI busy while core 0 draws the expensive bands, and the two shares end together (a
//! core that runs out goes on into the other's share from its own end). Core 0 draws and
//! sends the first band first and the last band last, so the display receives a frame from
//! its top left to its bottom right pixel as if written in raster order. Measured in
//! rp2040js, frame 1 (an older build): 11.08 M cycles when core 0 drew the even bands and
//! sent every band; 10.52 M with each core sending its own even or odd bands; 10.41 M with
//! one list by cost, core 0 taking from its expensive end and core 1 from its cheap end until
//! they met (10.33 M in frame 2); 10.53 M with both cores taking from the expensive end (the
//! SPI then idles at first and trails at the end). Then frames 1 to 15 of `run.mjs --dual
//! --frames 16`: 6 192 239 cycles a frame on average with that list, which left core 0
//! waiting about 2 ms at the end for core 1's last band, and 5 980 067 with the split (frame
//! 1 alone 5 944 049 -> 5 988 739, the one frame of the fifteen it does not shorten).
//!
//! **Empty bands go out during the shading.** A band that no object reaches this frame
//! (`Demo::band_is_empty`, known once the screen data are swapped) is the background: core 1
//! sends such bands from between its shader calls, whenever the sender is free and its last
//! transfer done ([`send_empty_bands`]; the DMA buffer filled with the background once), in
//! order, and only if the first band is one of them; no core draws them. The SPI idles
//! through the shading otherwise. Measured in rp2040js, frame 1: 8.02 M -> 7.44 M cycles. In
//! frame 2 core 1 had spent 4.5 ms on its four empty bands after the shading, each waiting
//! for the previous band's transfer; core 1's shading now ends 0.6 ms later (the sends), and
//! the bands after it take 25.3 ms instead of 29.1 (per-band timings of a temporary log).
//!
//! **An empty last band is carried into the next frame.** Sending the last band waits for
//! the transfer before it (up to 154 000 cycles), and when no object reaches the last band
//! core 0 would be waiting there with nothing else to do. Such a band is instead sent in the
//! next frame before anything of it, by core 1 between its shader calls once the sender is
//! free ([`send_parked`]; by core 0 before its first band if core 1 has not): the display
//! still receives each frame whole, top left to bottom right, before the next one begins.
//! Measured in rp2040js, frames 1 to 15 of `run.mjs --dual --frames 16`: 5 174 951 -> 5 036 814
//! cycles a frame on average.
//!
//! **So are the last drawn bands, when the SPI is busy.** At the end of a frame the bands
//! still to be sent queue for the SPI (154 000 cycles each) while both cores have nothing to
//! draw: core 0 waited about 990 us for core 1's last band to go out, then for its transfer,
//! before it could send the last band. Now core 1 parks its final band of a frame instead of
//! waiting when the sender is not free at once, and core 0 the last band when any band is
//! parked or the sender is busy ([`PARKED`]: the band keeps its buffers until sent); the
//! next frame sends them first, core 1's before the last band, in the same way as an empty
//! last band ([`send_parked`]), while the SPI would idle during the transform and the
//! shading, and each core takes its band back before drawing. Core 0 starts a frame once
//! core 1 is done drawing the last one. Measured in rp2040js, frames 1 to 15: 4 579 100 ->
//! 4 533 483 cycles a frame on average (frame 1: 4 560 394 -> 4 437 182); core 0's wait at
//! the end of a frame went from about 990 us to 4-6 in most frames (not 1, 5 to 7), and part
//! of it to its sends during the bands (the SPI's pacing).
#![no_std]
#![no_main]
// Every line here is safe Rust but two, each allowed where it is and explained there.
#![deny(unsafe_code)]

use defmt_rtt as _;
use panic_probe as _;

use core::cell::RefCell;

use arealight::raster::{Band, DrawStats, EncodeTable, Rgb565, Shading};
use arealight::Fixed22;
use cortex_m::singleton;
use critical_section::Mutex;
use demo_scene::{
    ColourExchange, Demo, Frame, MeshBuffers, ScreenExchange, VisibleExchange, BACKGROUND, HEIGHT,
    PERIOD, WIDTH,
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

mod bands;
mod exchange;
use bands::*;
use exchange::*;

/// The second-stage bootloader (see `lit_scene.rs`).
#[allow(unsafe_code)]
#[link_section = ".boot2"]
#[used]
pub static BOOT2_FIRMWARE: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

const XTAL_FREQ_HZ: u32 = 12_000_000;

/// Gouraud shading, as in `lit_scene.rs`.
const SHADING: Shading = Shading::Gouraud;

/// Rows per band: 20, where the single-core firmware draws 60 and the other boards 16
/// (`demo_scene::BAND_ROWS`). A triangle is set up once for each band it reaches, and the
/// taller the bands the fewer they are; each core holds a band and a depth band, and three
/// pixel buffers pass between the cores and the sender, five buffers of 9 600 bytes. Measured
/// in rp2040js, frames 1 to 15 of `run.mjs --dual --frames 16` (cycles a frame on average):
/// 4 522 497 with 16 rows (608 triangle setups in frame 1), 4 459 756 with 18 and 4 511 628
/// with 22 (each with a shorter last band), 4 438 195 with 20 (571 setups), 4 453 508 with 24
/// (frame 1 4 648 799: with ten bands the cores' shares end less evenly); with 30 rows the
/// statics leave no room for core 0's stack.
const BAND_ROWS: u16 = 20;
/// Pixels of one band: 4 800 (9 600 bytes of RGB565, as many of depth).
const BAND_PIXELS: usize = WIDTH as usize * BAND_ROWS as usize;
const _: () = assert!(HEIGHT % BAND_ROWS == 0, "whole bands");

/// The bands of a frame (12 of 20 rows).
const BANDS: u16 = HEIGHT.div_ceil(BAND_ROWS);

// The bands are bits of a `u16` (the empty bands sent early, `Handoff::early`, and core 1's
// pending ones): at most 16 of them. (Measured in rp2040js: 12-row bands, 20 of them, ran
// into a deadlock; 24-row bands, 10 of them, took 7 069 721 cycles for frame 1 against
// 6 658 670 with 16 rows.)
const _: () = assert!(BANDS <= 16, "a band is a bit of a u16 mask");

/// Each core's meshes and per-frame vertex data (60 KiB each), and the gamma table both
/// cores draw through (16 KiB: core 0 fills it, then both only read it), initialized at link
/// time (all zeros: no copy through a stack).
static CORE0_BUFFERS: ConstStaticCell<MeshBuffers<Fixed22>> =
    ConstStaticCell::new(MeshBuffers::new());
static CORE1_BUFFERS: ConstStaticCell<MeshBuffers<Fixed22>> =
    ConstStaticCell::new(MeshBuffers::new());
static TABLE: ConstStaticCell<EncodeTable> = ConstStaticCell::new(EncodeTable::zeroed());
/// Each core's exchange buffers (its share of the screen data, 9 KiB, and its colours, 7
/// KiB: [`Outboxes`]), all zeros.
static CORE0_SCREEN: ConstStaticCell<ScreenExchange<Fixed22>> =
    ConstStaticCell::new(ScreenExchange::new());
static CORE1_SCREEN: ConstStaticCell<ScreenExchange<Fixed22>> =
    ConstStaticCell::new(ScreenExchange::new());
static CORE0_VISIBLE: ConstStaticCell<VisibleExchange> =
    ConstStaticCell::new(VisibleExchange::new());
static CORE1_VISIBLE: ConstStaticCell<VisibleExchange> =
    ConstStaticCell::new(VisibleExchange::new());
static CORE0_COLOURS: ConstStaticCell<ColourExchange> = ConstStaticCell::new(ColourExchange::new());
static CORE1_COLOURS: ConstStaticCell<ColourExchange> = ConstStaticCell::new(ColourExchange::new());

/// Core 1's stack, in words: 16 KiB (the meshes, per-frame data and bands are statics; the stack holds
/// the rasterizer's clipping buffers, a frame's lights and the light models' locals).
static CORE1_STACK: Stack<4096> = Stack::new();

/// The display's sender: DMA channel 0, SPI1 in 16-bit frames, DC (GP8) and CS (GP9).
type Sender = BandSender<
    hal::dma::Channel<hal::dma::CH0>,
    hal::spi::Spi<
        hal::spi::Enabled,
        pac::SPI1,
        (
            hal::gpio::Pin<hal::gpio::bank0::Gpio11, hal::gpio::FunctionSpi, hal::gpio::PullDown>,
            hal::gpio::Pin<hal::gpio::bank0::Gpio10, hal::gpio::FunctionSpi, hal::gpio::PullDown>,
        ),
        16,
    >,
    hal::gpio::Pin<hal::gpio::bank0::Gpio8, hal::gpio::FunctionSioOutput, hal::gpio::PullDown>,
    hal::gpio::Pin<hal::gpio::bank0::Gpio9, hal::gpio::FunctionSioOutput, hal::gpio::PullDown>,
    BAND_PIXELS,
>;

/// What the two cores exchange.
struct Handoff {
    /// The frame core 1 is to draw next (set by core 0, taken by core 1).
    frame: Option<u32>,
    /// The bands but the first and the last, in [`band_order`]'s order (set by core 0 at the
    /// start of a frame); `order[lo..hi]` are still to be drawn: core 1 takes `order[lo]`,
    /// core 0 `order[hi - 1]`.
    order: [u16; BANDS as usize - 2],
    lo: usize,
    hi: usize,
    /// Each band's cost in this frame, from its `DrawStats` (set by the core that drew it).
    cost: [u32; BANDS as usize],
    /// The bands sent so far in this frame.
    sent: u16,
    /// The bands core 1 sent while shading (bit `k`: band `k`; see [`send_empty_bands`]), which
    /// no core draws.
    early: u16,
    /// The last frame's last band, which no object reached, is still to be sent: before any
    /// band of this frame (see [`send_parked`]).
    carried: bool,
    /// The bands of this frame parked (drawn, to be sent in the next frame: [`PARKED`]).
    parked: u16,
    /// Core 1 is drawing this frame's bands (set as it takes the frame, cleared once it has
    /// sent or parked its last band): core 0 starts the next frame only after.
    drawing: bool,
    /// What drawing core 1's bands of this frame did (added by core 1 as it sends each band,
    /// read by core 0 once every band is sent).
    stats: DrawStats,
    /// The cores' shares of this frame's vertex screen data on their way ([`Mailbox`]).
    screen: Mailbox<ScreenExchange<Fixed22>>,
    /// The cores' shares of this frame's vertex colours on their way ([`Mailbox`]).
    colours: Mailbox<ColourExchange>,
    /// The cores' visible-vertex marks and their triangles' rows of this frame on their way
    /// ([`Mailbox`]).
    visible: Mailbox<VisibleExchange>,
}

static HANDOFF: Mutex<RefCell<Handoff>> = Mutex::new(RefCell::new(Handoff {
    frame: None,
    order: [0; BANDS as usize - 2],
    lo: 0,
    hi: 0,
    cost: [0; BANDS as usize],
    sent: 0,
    early: 0,
    carried: false,
    parked: 0,
    drawing: false,
    stats: DrawStats {
        triangles: 0,
        rasterized: 0,
        shaded: 0,
        pixels: 0,
    },
    screen: Mailbox::EMPTY,
    colours: Mailbox::EMPTY,
    visible: Mailbox::EMPTY,
}));

/// Core 1: draws and sends bands of each frame core 0 asks for, from the front of the list
/// (its share, cheapest first).
fn core1(
    buffers: &'static mut MeshBuffers<Fixed22>,
    table: &'static EncodeTable,
    mut boxes: Outboxes,
) {
    let mut demo = Demo::<Fixed22>::sharing(buffers, table, SHADING).unwrap();
    // Core 1's band and depth band, in statics like core 0's (9.4 KiB each).
    let pixels = singleton!(: [Rgb565; BAND_PIXELS] = [Rgb565(0); BAND_PIXELS]).unwrap();
    let depth = singleton!(: [u16; BAND_PIXELS] = [0; BAND_PIXELS]).unwrap();
    let mut own = Some(Band::new(pixels, Some(depth), WIDTH, 0).unwrap());
    loop {
        let n = wait_for(|h| {
            let n = h.frame.take()?;
            h.drawing = true;
            Some(n)
        });
        let frame = demo.frame(n).unwrap();
        share_transform(&mut demo, &frame, 1, &mut boxes);
        let shaded = share_shading(&mut demo, &frame, 1, &mut boxes);
        critical_section::with(|cs| HANDOFF.borrow_ref_mut(cs).stats.shaded += shaded);
        // The last frame's parked bands out (if the shading has not sent them), and this
        // core's band back if it parked it.
        send_parked(true);
        if own.is_none() {
            own = take_back(1);
        }
        while let Some(k) = next_band(1) {
            let Some(band) = own.as_mut() else {
                defmt::error!("core 1 has no band");
                break;
            };
            let mut stats = DrawStats::default();
            band.move_to(k * BAND_ROWS);
            band.clear(BACKGROUND);
            demo.draw_band(&frame, band, &mut stats).unwrap();
            // (After the first band, which core 0 sends.) The final band of this core's
            // share is parked if the sender is not free at once.
            let last_of_ours = critical_section::with(|cs| {
                let h = HANDOFF.borrow_ref(cs);
                h.lo >= h.hi
            });
            let sender = if last_of_ours {
                try_take_sender(|h| h.sent > 0)
            } else {
                Some(take_sender(|h| h.sent > 0))
            };
            match sender {
                Some(mut sender) => {
                    send(&mut sender, band, k);
                    give_back(sender, k, &stats, 1);
                }
                None => {
                    if let Some(band) = own.take() {
                        park(1, band, k, &stats);
                    }
                    break;
                }
            }
        }
        critical_section::with(|cs| HANDOFF.borrow_ref_mut(cs).drawing = false);
        cortex_m::asm::sev();
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
    let dma_buffer = singleton!(: DmaBuffer<BAND_PIXELS> = [Rgb565(0); BAND_PIXELS]).unwrap();
    let display: Sender = BandSender::new(dma.ch0, spi16, dma_buffer, dc, cs);
    critical_section::with(|cs| *SENDER.borrow_ref_mut(cs) = Some(display));

    // 9. The gamma table both cores draw through, filled once (then only read).
    let table = TABLE.take();
    Demo::<Fixed22>::fill_table(table);
    let table: &'static EncodeTable = table;

    // 10. Core 1: its meshes and per-frame data (statics, handed to it) and the shared table,
    //    its stack, and its program (`core1`, which builds its own `Demo` from them while core
    //    0 builds its own). The power-on state machine (PSM) and the FIFO between the cores
    //    are used once, to start it.
    let core1_buffers = CORE1_BUFFERS.take();
    let core1_boxes = Outboxes {
        screen: Some(CORE1_SCREEN.take()),
        visible: Some(CORE1_VISIBLE.take()),
        colours: Some(CORE1_COLOURS.take()),
    };
    let mut multicore = Multicore::new(&mut pac.PSM, &mut pac.PPB, &mut sio.fifo);
    let cores = multicore.cores();
    cores[1]
        .spawn(CORE1_STACK.take().unwrap(), move || {
            core1(core1_buffers, table, core1_boxes)
        })
        .unwrap();

    // 11. Core 0's own scene and band, as in `lit_scene.rs`.
    let buffers = CORE0_BUFFERS.take();
    let mut boxes = Outboxes {
        screen: Some(CORE0_SCREEN.take()),
        visible: Some(CORE0_VISIBLE.take()),
        colours: Some(CORE0_COLOURS.take()),
    };
    let mut demo = Demo::<Fixed22>::sharing(buffers, table, SHADING).unwrap();
    let pixels = singleton!(: [Rgb565; BAND_PIXELS] = [Rgb565(0); BAND_PIXELS]).unwrap();
    let depth = singleton!(: [u16; BAND_PIXELS] = [0; BAND_PIXELS]).unwrap();
    let mut own = Some(Band::new(pixels, Some(depth), WIDTH, 0).unwrap());

    // 12. Each frame: split the bands by the last frame's cost and tell core 1 to start, then
    //     draw the first band, the bands from the back of the list (most expensive first),
    //     and the last band, sending each. The first band is sent first and the last band
    //     last (core 1 sends only after the first; an empty last band goes out early in the
    //     next frame, before anything of it), so the display receives each frame from its top
    //     left to its bottom right pixel, as one written in raster order.
    let mut n: u32 = 0;
    let last = BANDS - 1;
    loop {
        let start = timer.get_counter_low();
        // (Once core 1 is done with the last frame's bands.)
        wait_for(|h| {
            if h.drawing {
                return None;
            }
            h.order = band_order(&h.cost);
            h.lo = 0;
            h.hi = h.order.len();
            h.sent = 0;
            h.early = 0;
            h.parked = 0;
            h.stats = DrawStats::default();
            h.frame = Some(n);
            Some(())
        });
        cortex_m::asm::sev();
        let frame = demo.frame(n).unwrap();
        let t_setup = timer.get_counter_low();
        share_transform(&mut demo, &frame, 0, &mut boxes);
        let t_transform = timer.get_counter_low();
        let mut stats = DrawStats {
            shaded: share_shading(&mut demo, &frame, 0, &mut boxes),
            ..DrawStats::default()
        };
        let t_shade = timer.get_counter_low();
        let (mut raster_us, mut wait_us, mut send_us) = (0u32, 0u32, 0u32);
        // What the last frame left to send first, if core 1 has not sent it while shading, and
        // this core's band back if it parked it.
        send_parked(true);
        if own.is_none() {
            own = take_back(0);
        }
        // The first band, unless core 1 sent it (empty) while shading.
        let first_sent = critical_section::with(|cs| HANDOFF.borrow_ref(cs).early & 1 != 0);
        let mut next = if first_sent {
            Some(next_band(0).unwrap_or(last))
        } else {
            Some(0)
        };
        while let Some(k) = next {
            let is_last = k == last;
            if is_last && demo.band_is_empty(k * BAND_ROWS, BAND_ROWS) {
                // Nothing reaches it: carried into the next frame (`send_parked`) once every
                // other band has been handed over or parked, instead of waiting here for the
                // transfer before it.
                let t1 = timer.get_counter_low();
                critical_section::with(|cs| HANDOFF.borrow_ref_mut(cs).cost[usize::from(k)] = 0);
                wait_for(|h| {
                    if h.sent + h.parked == last {
                        h.carried = true;
                        Some(())
                    } else {
                        None
                    }
                });
                wait_us += timer.get_counter_low().wrapping_sub(t1);
                break;
            }
            let Some(band) = own.as_mut() else {
                defmt::error!("core 0 has no band");
                break;
            };
            let t0 = timer.get_counter_low();
            let mut band_stats = DrawStats::default();
            band.move_to(k * BAND_ROWS);
            band.clear(BACKGROUND);
            demo.draw_band(&frame, band, &mut band_stats).unwrap();
            let t1 = timer.get_counter_low();
            raster_us += t1.wrapping_sub(t0);
            let sender = if is_last {
                // The last band waits for every other band to be sent or parked (core 1 done
                // drawing), then goes out now if none is parked and the sender is free, or is
                // parked itself.
                wait_for(|h| (h.sent + h.parked == last).then_some(()));
                try_take_sender(|h| h.parked == 0)
            } else {
                Some(take_sender(|_| true))
            };
            let t2 = timer.get_counter_low();
            wait_us += t2.wrapping_sub(t1);
            match sender {
                Some(mut sender) => {
                    send(&mut sender, band, k);
                    send_us += timer.get_counter_low().wrapping_sub(t2);
                    give_back(sender, k, &band_stats, 0);
                }
                None => {
                    if let Some(band) = own.take() {
                        park(0, band, k, &band_stats);
                    }
                }
            }
            stats.rasterized += band_stats.rasterized;
            stats.pixels += band_stats.pixels;
            next = if is_last {
                None
            } else {
                Some(next_band(0).unwrap_or(last))
            };
        }
        let s = critical_section::with(|cs| HANDOFF.borrow_ref(cs).stats);
        stats.rasterized += s.rasterized;
        stats.shaded += s.shaded;
        stats.pixels += s.pixels;
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
