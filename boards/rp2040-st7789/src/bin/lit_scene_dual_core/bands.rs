//! The bands: which core draws which ([`band_order`], [`next_band`]), the empty bands sent
//! during the shading ([`send_empty_bands`]), the bands parked at the end of a frame and sent
//! early in the next ([`PARKED`], [`send_parked`]), and the display's sender passed between
//! the cores ([`SENDER`], [`take_sender`], [`give_back`]).

use super::*;

/// The display's sender, here between bands (`None` while a core sends with it). Apart from
/// [`HANDOFF`] so that the handoff stays all zeros (`.bss`: no 14 KiB initial image in
/// flash), which `None` here is not.
pub(crate) static SENDER: Mutex<RefCell<Option<Sender>>> = Mutex::new(RefCell::new(None));

/// A core's band parked at the end of a frame: drawn, its transfer not yet begun (`sent`
/// false), or sent and waiting for its core to take it back (`sent` true).
pub(crate) struct Parked {
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
pub(crate) static PARKED: Mutex<RefCell<[Option<Parked>; 2]>> =
    Mutex::new(RefCell::new([None, None]));

/// The bands but the first and the last in the order the cores take them (core 1 from the
/// front, core 0 from the back), from their `cost` in the last frame: split between the cores
/// by the longest-first rule (each band, most expensive first, to the core with the less
/// work so far; core 0 starts with the last band's cost), core 1's share first, cheapest
/// first, then core 0's, cheapest first, so that core 0 starts on its most expensive band
/// while core 1's cheap ones keep the SPI busy. A core that runs out of its share goes on
/// into the other's from its own end (the other's least urgent band).
pub(crate) fn band_order(cost: &[u32; BANDS as usize]) -> [u16; BANDS as usize - 2] {
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
pub(crate) fn band_cost(s: &DrawStats) -> u32 {
    s.rasterized * 30 + s.pixels
}

/// Takes the next band to draw for core `core` from the handoff's list (`None`: none left).
pub(crate) fn next_band(core: usize) -> Option<u16> {
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
pub(crate) fn empty_bands(demo: &Demo<'_, Fixed22>) -> u16 {
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
pub(crate) fn send_empty_bands(pending: &mut u16) {
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
pub(crate) enum Pending {
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
pub(crate) fn send_parked(wait: bool) -> bool {
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
pub(crate) fn anything_parked() -> bool {
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
pub(crate) fn take_back(core: usize) -> Option<Band<'static, Rgb565>> {
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
pub(crate) fn park(core: usize, band: Band<'static, Rgb565>, k: u16, stats: &DrawStats) {
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
pub(crate) fn record(h: &mut Handoff, k: u16, stats: &DrawStats, core: usize) {
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
pub(crate) fn try_take_sender(ready: impl Fn(&Handoff) -> bool) -> Option<Sender> {
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
pub(crate) fn take_sender(ready: impl Fn(&Handoff) -> bool) -> Sender {
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
pub(crate) fn give_back(sender: Sender, k: u16, stats: &DrawStats, core: usize) {
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
pub(crate) fn send(sender: &mut Sender, band: &mut Band<'static, Rgb565>, k: u16) {
    if let Err(e) = sender.send_swapping(band) {
        defmt::error!("band {}: {}", k, defmt::Debug2Format(&e));
    }
}
