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

/// The display's sender, here between bands (`None` while a core sends with it). Apart from
/// [`HANDOFF`] so that the handoff stays all zeros (`.bss`: no 14 KiB initial image in
/// flash), which `None` here is not.
static SENDER: Mutex<RefCell<Option<Sender>>> = Mutex::new(RefCell::new(None));

/// A core's band parked at the end of a frame: drawn, its transfer not yet begun (`sent`
/// false), or sent and waiting for its core to take it back (`sent` true).
struct Parked {
    band: Band<'static, Rgb565>,
    sent: bool,
}

/// Each core's parked band (index: the core), apart from [`HANDOFF`] for the same reason as
/// [`SENDER`]. A frame's last bands would otherwise wait for the SPI: the transfer before them
/// runs for up to 154 000 cycles after the last band is drawn, while both cores have nothing
/// to do. Core 1 parks its final band of a frame when the sender is not free at once, and
/// core 0 the last band when any band is parked or the sender is not free; both go out early
/// in the next frame, in order (core 1's, then the last band), before anything of that
/// frame ([`send_parked`]), while the SPI would idle during the transform and the shading.
static PARKED: Mutex<RefCell<[Option<Parked>; 2]>> = Mutex::new(RefCell::new([None, None]));

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

/// The cores' split of the vertex transform: core `core` transforms the vertices of index
/// `core` modulo 2, hands their screen data to the other core and takes the other core's, so
/// that both then hold every vertex's screen data, each vertex transformed once per frame.
/// (Each core keeps the world positions and normals of its own vertices only: the shading
/// split below is the same.)
fn share_transform(
    demo: &mut Demo<'_, Fixed22>,
    frame: &Frame<Fixed22>,
    core: usize,
    own: &mut Outboxes,
) {
    demo.transform_share(frame, core, 2);
    exchange(
        demo,
        core,
        &mut own.screen,
        |h| &mut h.screen,
        |demo, out| demo.export_screen(out, core),
        |demo, theirs, other| demo.import_screen(theirs, other),
    );
}

/// The cores' split of the pass that finds the visible vertices: core `core` makes it over
/// the triangles of index `core` modulo 2, hands its marks and its triangles' rows to the
/// other core and takes the other core's, so that both then know every visible vertex, each
/// triangle visited once per frame (it was twice, once on each core: rp2040js frames 1 to
/// 15, 4 896 673 -> 4 853 557 cycles on average).
fn share_visible(demo: &mut Demo<'_, Fixed22>, core: usize, own: &mut Outboxes) {
    demo.find_visible_share(core, 2);
    exchange(
        demo,
        core,
        &mut own.visible,
        |h| &mut h.visible,
        |demo, out| demo.export_visible(out, core),
        |demo, theirs, other| demo.import_visible(theirs, other),
    );
}

/// The cores' split of the vertex shading: core `core` shades the visible vertices of index
/// `core` modulo 2, hands its colours to the other core and takes the other core's, so that
/// both then hold every visible vertex's colour, each shaded once per frame. (The visible
/// vertices first: [`share_visible`].)
fn share_shading(
    demo: &mut Demo<'_, Fixed22>,
    frame: &Frame<Fixed22>,
    core: usize,
    own: &mut Outboxes,
) -> u32 {
    share_visible(demo, core, own);
    // Core 1 sends what the last frame left (its parked bands, or its last band carried as
    // empty) and this frame's empty bands between its
    // shader calls.
    let mut carried = core == 1 && anything_parked();
    let mut pending = if core == 1 { empty_bands(demo) } else { 0 };
    let calls = demo.shade_share_polling(frame, core, 2, || {
        if carried {
            carried = !send_parked(false);
        } else {
            send_empty_bands(&mut pending);
        }
    });
    exchange(
        demo,
        core,
        &mut own.colours,
        |h| &mut h.colours,
        |demo, out| demo.export_colours(out),
        |demo, theirs, other| demo.import_colours(theirs, other, 2),
    );
    calls
}

/// One core's exchange buffers while it holds them: each core writes its share into its own
/// and reads the other core's, so the two copy at the same time, outside the lock
/// ([`exchange`]).
struct Outboxes {
    screen: Option<&'static mut ScreenExchange<Fixed22>>,
    visible: Option<&'static mut VisibleExchange>,
    colours: Option<&'static mut ColourExchange>,
}

/// The buffers of one exchange in flight between the cores: `ready[k]` holds core k's share
/// for the other core to read, `back[k]` core k's buffer once read, for core k to take back.
/// Only the buffers' references pass under the lock ([`exchange`]).
struct Mailbox<X: 'static> {
    ready: [Option<&'static mut X>; 2],
    back: [Option<&'static mut X>; 2],
}

impl<X: 'static> Mailbox<X> {
    const EMPTY: Self = Mailbox {
        ready: [None, None],
        back: [None, None],
    };
}

/// One exchange between the cores by buffers passed whole (screen data, colours): core
/// `core` writes its share into its own buffer `own` with `export` (waiting for the other
/// core to hand it back from the last exchange if it has not yet), hands it over, then reads
/// the other core's with `import` once it is there and hands that back. The copies run on
/// both cores at once and outside the lock, which only passes the references. (They ran
/// under it, one core at a time: rp2040js, two cores, frame 1, core 0's screen-data
/// exchange took 179 us writing, 272 us waiting and 270 us reading, the visible vertices'
/// 64, 86 and 84, the colours' 71, 87 and 82. Frames 1 to 15 of `run.mjs --dual --frames
/// 16`: 4 419 164 -> 4 390 487 cycles a frame on average with the screen data and colours
/// passed whole, 4 373 605 with the visible vertices too; each core's shares are written
/// densely, so the buffers take the memory the shared ones did.)
#[inline(always)]
fn exchange<X: 'static>(
    demo: &mut Demo<'_, Fixed22>,
    core: usize,
    own: &mut Option<&'static mut X>,
    mailbox: fn(&mut Handoff) -> &mut Mailbox<X>,
    export: impl FnOnce(&Demo<'_, Fixed22>, &mut X),
    import: impl FnOnce(&mut Demo<'_, Fixed22>, &X, usize),
) {
    let other = 1 - core;
    let out = match own.take() {
        Some(out) => out,
        None => wait_for(|h| mailbox(h).back.get_mut(core)?.take()),
    };
    export(demo, out);
    critical_section::with(|cs| {
        if let Some(slot) = mailbox(&mut HANDOFF.borrow_ref_mut(cs)).ready.get_mut(core) {
            *slot = Some(out);
        }
    });
    cortex_m::asm::sev();
    let theirs = wait_for(|h| mailbox(h).ready.get_mut(other)?.take());
    import(demo, theirs, other);
    critical_section::with(|cs| {
        let mut h = HANDOFF.borrow_ref_mut(cs);
        let mailbox = mailbox(&mut h);
        if let Some(slot) = mailbox.back.get_mut(other) {
            *slot = Some(theirs);
        }
        // This core's buffer, if the other core has read it already.
        *own = mailbox.back.get_mut(core).and_then(Option::take);
    });
    cortex_m::asm::sev();
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

/// The bands but the first and the last in the order the cores take them (core 1 from the
/// front, core 0 from the back), from their `cost` in the last frame: split between the cores
/// by the longest-first rule (each band, most expensive first, to the core with the less
/// work so far; core 0 starts with the last band's cost), core 1's share first, cheapest
/// first, then core 0's, cheapest first, so that core 0 starts on its most expensive band
/// while core 1's cheap ones keep the SPI busy. A core that runs out of its share goes on
/// into the other's from its own end (the other's least urgent band).
fn band_order(cost: &[u32; BANDS as usize]) -> [u16; BANDS as usize - 2] {
    let c = |k: u16| cost.get(usize::from(k)).copied().unwrap_or(0);
    let mut by_cost: [u16; BANDS as usize - 2] = core::array::from_fn(|i| i as u16 + 1);
    by_cost.sort_unstable_by_key(|&k| (core::cmp::Reverse(c(k)), k));
    let (mut load0, mut load1) = (c(BANDS - 1), 0u32);
    let mut core0 = 0u16;
    for &k in &by_cost {
        if load0 <= load1 {
            load0 = load0.saturating_add(c(k));
            core0 |= 1 << k;
        } else {
            load1 = load1.saturating_add(c(k));
        }
    }
    let mut order = by_cost;
    order.sort_unstable_by_key(|&k| (core0 & (1 << k) != 0, c(k), k));
    order
}

/// A band's cost for the order of the next frame: its triangle setups (about 3000 cycles
/// each) and pixels (about 100), in units of a pixel.
fn band_cost(s: &DrawStats) -> u32 {
    s.rasterized * 30 + s.pixels
}

/// Takes the next band to draw for core `core` from the handoff's list (`None`: none left).
fn next_band(core: usize) -> Option<u16> {
    critical_section::with(|cs| {
        let mut h = HANDOFF.borrow_ref_mut(cs);
        while h.lo < h.hi {
            let k = if core == 0 {
                h.hi -= 1;
                h.order[h.hi]
            } else {
                h.lo += 1;
                h.order[h.lo - 1]
            };
            if h.early & (1 << k) == 0 {
                return Some(k);
            }
        }
        None
    })
}

/// The bands core 1 may send while it shades: those no object reaches this frame
/// ([`Demo::band_is_empty`]) but the last (sent last, by core 0), and none unless the first
/// band is one of them (the first band is sent first). Bit `k`: band `k`.
fn empty_bands(demo: &Demo<'_, Fixed22>) -> u16 {
    let empty = (0..BANDS - 1)
        .filter(|&k| demo.band_is_empty(k * BAND_ROWS, BAND_ROWS))
        .fold(0u16, |m, k| m | (1 << k));
    if empty & 1 == 0 {
        0
    } else {
        empty
    }
}

/// Sends the lowest band of `pending` (the background: nothing reaches it) if the display's
/// sender is free and its last transfer done, and marks it sent; otherwise returns at once.
/// Core 1 calls it before each of its shader calls, so that the empty bands go out while the
/// SPI would idle during the shading, in order, the first band first. Measured in rp2040js
/// (frame 2 of the demo): core 1's four empty bands had cost it 4.5 ms after the shading,
/// each waiting for the previous band's transfer.
fn send_empty_bands(pending: &mut u16) {
    if *pending == 0 {
        return;
    }
    let k = pending.trailing_zeros() as u16;
    let sender = critical_section::with(|cs| {
        let mut slot = SENDER.borrow_ref_mut(cs);
        match slot.as_ref() {
            Some(s) if s.is_idle() => slot.take(),
            _ => None,
        }
    });
    let Some(mut sender) = sender else {
        return;
    };
    if let Err(e) = sender.send_uniform(k * BAND_ROWS, BAND_ROWS, BACKGROUND) {
        defmt::error!("band {}: {}", k, defmt::Debug2Format(&e));
    }
    *pending &= !(1 << k);
    critical_section::with(|cs| {
        *SENDER.borrow_ref_mut(cs) = Some(sender);
        let mut h = HANDOFF.borrow_ref_mut(cs);
        h.sent += 1;
        h.early |= 1 << k;
        h.cost[usize::from(k)] = 0;
    });
    cortex_m::asm::sev();
}

/// What [`send_parked`] sends next.
enum Pending {
    /// Core `k`'s parked band.
    Band(usize, Band<'static, Rgb565>),
    /// The last frame's last band, which no object reached (the background).
    Empty,
}

/// Sends what the last frame left to send, in order: core 1's parked band, core 0's (the last
/// band), or the last band carried as empty (the background: nothing reached it), each when
/// the display's sender is free and its last transfer done; with `wait`, waiting for them
/// until all is sent, otherwise returning when the sender is busy. Returns whether all is
/// sent (or nothing was to be). A sent band goes back to [`PARKED`] for its core to take
/// ([`take_back`]). Core 1 calls it between its shader calls and both cores before their
/// first band, so a frame still reaches the display from its top left to its bottom right
/// pixel, before anything of the next. Measured in rp2040js (two cores, frames 1 to 15 of
/// `--frames 16`): see the README's frame table.
fn send_parked(wait: bool) -> bool {
    loop {
        let taken = critical_section::with(|cs| {
            let mut h = HANDOFF.borrow_ref_mut(cs);
            let mut parked = PARKED.borrow_ref_mut(cs);
            let unsent = |p: &Option<Parked>| p.as_ref().is_some_and(|p| !p.sent);
            let next = if unsent(&parked[1]) {
                Some(1)
            } else if unsent(&parked[0]) {
                Some(0)
            } else if h.carried {
                Some(2)
            } else {
                None
            };
            let Some(next) = next else {
                return Some(None);
            };
            let mut slot = SENDER.borrow_ref_mut(cs);
            match slot.as_ref() {
                Some(s) if s.is_idle() => {
                    let sender = slot.take()?;
                    let pending = match parked.get_mut(next).and_then(Option::take) {
                        Some(p) => Pending::Band(next, p.band),
                        None => {
                            h.carried = false;
                            Pending::Empty
                        }
                    };
                    Some(Some((sender, pending)))
                }
                _ => None,
            }
        });
        match taken {
            // Nothing (more) to send.
            Some(None) => return true,
            Some(Some((mut sender, pending))) => {
                match pending {
                    Pending::Band(core, mut band) => {
                        let k = band.y0() / BAND_ROWS;
                        send(&mut sender, &mut band, k);
                        critical_section::with(|cs| {
                            if let Some(slot) = PARKED.borrow_ref_mut(cs).get_mut(core) {
                                *slot = Some(Parked { band, sent: true });
                            }
                        });
                    }
                    Pending::Empty => {
                        let last = BANDS - 1;
                        if let Err(e) = sender.send_uniform(last * BAND_ROWS, BAND_ROWS, BACKGROUND)
                        {
                            defmt::error!("band {}: {}", last, defmt::Debug2Format(&e));
                        }
                    }
                }
                critical_section::with(|cs| *SENDER.borrow_ref_mut(cs) = Some(sender));
                cortex_m::asm::sev();
            }
            None if !wait => return false,
            None => cortex_m::asm::wfe(),
        }
    }
}

/// Whether the last frame left anything to send ([`send_parked`]).
fn anything_parked() -> bool {
    critical_section::with(|cs| {
        HANDOFF.borrow_ref(cs).carried
            || PARKED
                .borrow_ref(cs)
                .iter()
                .any(|p| p.as_ref().is_some_and(|p| !p.sent))
    })
}

/// Core `core`'s band back from [`PARKED`] once it is sent (after [`send_parked`]`(true)`),
/// if the core parked it.
fn take_back(core: usize) -> Option<Band<'static, Rgb565>> {
    critical_section::with(|cs| {
        let mut parked = PARKED.borrow_ref_mut(cs);
        let slot = parked.get_mut(core)?;
        if slot.as_ref().is_some_and(|p| p.sent) {
            slot.take().map(|p| p.band)
        } else {
            None
        }
    })
}

/// Parks core `core`'s drawn band `k` ([`PARKED`]), with its counts as [`give_back`] records
/// them.
fn park(core: usize, band: Band<'static, Rgb565>, k: u16, stats: &DrawStats) {
    critical_section::with(|cs| {
        if let Some(slot) = PARKED.borrow_ref_mut(cs).get_mut(core) {
            *slot = Some(Parked { band, sent: false });
        }
        let mut h = HANDOFF.borrow_ref_mut(cs);
        h.parked += 1;
        record(&mut h, k, stats, core);
    });
    cortex_m::asm::sev();
}

/// Records core `core`'s band `k` as drawn, with its counts `stats`: its cost for the next
/// frame's order, and core 1's counts for core 0's log.
fn record(h: &mut Handoff, k: u16, stats: &DrawStats, core: usize) {
    if let Some(cost) = h.cost.get_mut(usize::from(k)) {
        *cost = band_cost(stats);
    }
    if core == 1 {
        h.stats.rasterized += stats.rasterized;
        h.stats.pixels += stats.pixels;
    }
}

/// The display's sender if `ready` says so and it is free with its last transfer done, at
/// once (`None` otherwise).
fn try_take_sender(ready: impl Fn(&Handoff) -> bool) -> Option<Sender> {
    critical_section::with(|cs| {
        if !ready(&HANDOFF.borrow_ref(cs)) {
            return None;
        }
        let mut slot = SENDER.borrow_ref_mut(cs);
        match slot.as_ref() {
            Some(s) if s.is_idle() => slot.take(),
            _ => None,
        }
    })
}

/// Takes the display's sender once `ready` says so, waiting while the other core sends.
fn take_sender(ready: impl Fn(&Handoff) -> bool) -> Sender {
    loop {
        let sender = critical_section::with(|cs| {
            if ready(&HANDOFF.borrow_ref(cs)) {
                SENDER.borrow_ref_mut(cs).take()
            } else {
                None
            }
        });
        if let Some(s) = sender {
            return s;
        }
        cortex_m::asm::wfe();
    }
}

/// Hands the sender back after sending band `k`, with the band's counts `stats` (its cost
/// for the next frame's order; core 1's counts for core 0's log).
fn give_back(sender: Sender, k: u16, stats: &DrawStats, core: usize) {
    critical_section::with(|cs| {
        *SENDER.borrow_ref_mut(cs) = Some(sender);
        let mut h = HANDOFF.borrow_ref_mut(cs);
        h.sent += 1;
        record(&mut h, k, stats, core);
    });
    cortex_m::asm::sev();
}

/// Sends band `k` with `sender`, logging a failure (there is none: the pins' errors are
/// `Infallible`). The band's pixel buffer goes to the DMA transfer and the band takes the
/// sender's, whose transfer has ended (`BandSender::send_swapping`: no copy); the three pixel
/// buffers, core 0's, core 1's and the sender's, pass from one to another.
fn send(sender: &mut Sender, band: &mut Band<'static, Rgb565>, k: u16) {
    if let Err(e) = sender.send_swapping(band) {
        defmt::error!("band {}: {}", k, defmt::Debug2Format(&e));
    }
}

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
