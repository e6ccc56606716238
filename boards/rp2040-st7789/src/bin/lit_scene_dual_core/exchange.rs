//! The cores' exchanges of a frame's shared work: each core transforms, finds the visible
//! triangles of and shades its half of the vertices, writes its results into its own buffer
//! ([`Outboxes`]) and hands the buffer's reference to the other core through [`HANDOFF`]
//! ([`Mailbox`], [`exchange`]), so that the two copy at the same time, outside the lock.

use super::*;

/// The cores' split of the vertex transform: core `core` transforms the vertices of index
/// `core` modulo 2, hands their screen data to the other core and takes the other core's, so
/// that both then hold every vertex's screen data, each vertex transformed once per frame.
/// (Each core keeps the world positions and normals of its own vertices only: the shading
/// split below is the same.)
pub(crate) fn share_transform(
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
pub(crate) fn share_visible(demo: &mut Demo<'_, Fixed22>, core: usize, own: &mut Outboxes) {
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
pub(crate) fn share_shading(
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
pub(crate) struct Outboxes {
    pub(crate) screen: Option<&'static mut ScreenExchange<Fixed22>>,
    pub(crate) visible: Option<&'static mut VisibleExchange>,
    pub(crate) colours: Option<&'static mut ColourExchange>,
}

/// The buffers of one exchange in flight between the cores: `ready[k]` holds core k's share
/// for the other core to read, `back[k]` core k's buffer once read, for core k to take back.
/// Only the buffers' references pass under the lock ([`exchange`]).
pub(crate) struct Mailbox<X: 'static> {
    ready: [Option<&'static mut X>; 2],
    back: [Option<&'static mut X>; 2],
}

impl<X: 'static> Mailbox<X> {
    pub(crate) const EMPTY: Self = Mailbox {
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
pub(crate) fn exchange<X: 'static>(
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
pub(crate) fn wait_for<R>(mut f: impl FnMut(&mut Handoff) -> Option<R>) -> R {
    loop {
        if let Some(r) = critical_section::with(|cs| f(&mut HANDOFF.borrow_ref_mut(cs))) {
            return r;
        }
        cortex_m::asm::wfe();
    }
}
