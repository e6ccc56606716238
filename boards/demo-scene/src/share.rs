//! Two cores sharing a frame of the [`Demo`]: each transforms, finds the visible triangles of
//! and shades its share of the vertices (index `core` modulo 2), and the cores exchange their
//! shares' results through one buffer each ([`ScreenExchange`], [`VisibleExchange`],
//! [`ColourExchange`]), so that each then draws its bands with every vertex's data.

use super::*;

/// A share's entries ([`ScreenExchange`]'s vertices, [`VisibleExchange`]'s triangle rows)
/// spread to mesh order for `PreparedMesh::set_screen` and `set_visible`: item `i` of the
/// share (`i = 2 j + core`) is entry `j = i >> 1`; the entries at the other indices are not
/// taken.
fn spread<X: Copy>(share: &[X], empty: X) -> impl Iterator<Item = X> + '_ {
    (0..2 * share.len()).map(move |i| share.get(i >> 1).copied().unwrap_or(empty))
}

/// Whether vertex `i` is core `core`'s of `cores` (`i mod cores == core`): with two cores the
/// low bit, no division (an ARMv6-M core has no divide instruction: each `%` by a number
/// known only at run time is a library call, and the shares ask once per vertex several
/// times a frame).
#[inline]
fn share(core: usize, cores: usize) -> impl Fn(usize) -> bool + Copy {
    move |i: usize| {
        if cores == 2 {
            i & 1 == core
        } else {
            i % cores == core
        }
    }
}

impl<T: Real> Demo<'_, T> {
    /// [`Demo::transform`] of this core's share of the vertices: those whose index is `core`
    /// modulo `cores` (the same share as [`Demo::shade_share`]'s, so that each core shades the
    /// vertices it transformed). With two cores, each transforms its half, then each takes the
    /// other's screen data through a [`ScreenExchange`] ([`Demo::export_screen`],
    /// [`Demo::import_screen`]): every vertex is transformed once per frame.
    pub fn transform_share(&mut self, frame: &Frame<T>, core: usize, cores: usize) {
        let [s, t, l] = &frame.transforms;
        let cores = cores.max(1);
        let mine = share(core, cores);
        // (Every core decides the same from the same frames: each skips the sphere, and the
        // exchange leaves it out, in the same frames.)
        if self.sphere_moves(s) {
            self.sphere.transform_some(&self.camera, s, true, mine);
        }
        self.torus.transform_some(&self.camera, t, true, mine);
        self.lamp.transform_some(&self.camera, l, false, mine);
    }

    /// Writes the screen data of core `core`'s share of the vertices (of two cores: those of
    /// index `core` modulo 2) into `exchange` (after [`Demo::transform_share`] with the same
    /// `core` and 2 cores), in vertex order, for the other core to take.
    pub fn export_screen(&self, exchange: &mut ScreenExchange<T>, core: usize) {
        let core = core.min(1);
        let copy = |dst: &mut [VertexScreen<T>], src: &PreparedMesh<'_, '_, T>| {
            for (d, v) in dst.iter_mut().zip(src.screen().skip(core).step_by(2)) {
                *d = v;
            }
        };
        if self.sphere_moved {
            copy(&mut exchange.sphere, &self.sphere);
        }
        copy(&mut exchange.torus, &self.torus);
        copy(&mut exchange.lamp, &self.lamp);
    }

    /// Takes from `exchange` the screen data of the vertices that core `core` of two
    /// transformed (what it exported this frame).
    pub fn import_screen(&mut self, exchange: &ScreenExchange<T>, core: usize) {
        let theirs = share(core.min(1), 2);
        let camera = &self.camera;
        if self.sphere_moved {
            self.sphere.set_screen(
                camera,
                spread(&exchange.sphere, VertexScreen::EMPTY),
                theirs,
            );
        }
        self.torus
            .set_screen(camera, spread(&exchange.torus, VertexScreen::EMPTY), theirs);
        self.lamp
            .set_screen(camera, spread(&exchange.lamp, VertexScreen::EMPTY), theirs);
    }

    /// The visible-vertex pass of the shading ([`PreparedMesh::find_visible_some`]) over this
    /// core's share of each object's triangles: those whose index is `core` modulo `cores`,
    /// for each object whose pass is due (every frame for the torus and the lamp; for the
    /// sphere, which stands still, only when its screen data are new). With two cores, after
    /// [`Demo::import_screen`]: each makes the pass over its half, then each takes the
    /// other's marks and rows through a [`VisibleExchange`] ([`Demo::export_visible`],
    /// [`Demo::import_visible`]), and [`Demo::shade_share`] goes straight to its shader
    /// calls: every triangle is visited once per frame instead of once on each core. Both
    /// cores decide alike which objects take part. Returns how many did (0 once the
    /// exchange has completed every pass).
    pub fn find_visible_share(&mut self, core: usize, cores: usize) -> usize {
        let mine = share(core, cores.max(1));
        let camera = &self.camera;
        self.visible_shared = [
            self.sphere
                .find_visible_some(camera, self.lit[0].cull, mine),
            self.torus.find_visible_some(camera, self.lit[1].cull, mine),
            self.lamp
                .find_visible_some(camera, self.emissive.cull, mine),
        ];
        self.visible_shared.iter().filter(|&&s| s).count()
    }

    /// Writes core `core`'s visible-vertex marks and its triangles' rows (of two cores: the
    /// triangles of index `core` modulo 2) into `exchange` (after
    /// [`Demo::find_visible_share`] with the same `core` and 2 cores), for the other core to
    /// take.
    pub fn export_visible(&self, exchange: &mut VisibleExchange, core: usize) {
        let core = core.min(1);
        let objects: [(&PreparedMesh<'_, '_, T>, &mut [bool], &mut [TriangleRows]); 3] = [
            (
                &self.sphere,
                &mut exchange.marks.sphere,
                &mut exchange.rows.sphere,
            ),
            (
                &self.torus,
                &mut exchange.marks.torus,
                &mut exchange.rows.torus,
            ),
            (
                &self.lamp,
                &mut exchange.marks.lamp,
                &mut exchange.rows.lamp,
            ),
        ];
        for ((mesh, marks, rows), shared) in objects.into_iter().zip(self.visible_shared) {
            if !shared {
                continue;
            }
            for (d, m) in marks.iter_mut().zip(mesh.visible_marks()) {
                *d = m;
            }
            for (d, r) in rows
                .iter_mut()
                .zip(mesh.triangle_rows().skip(core).step_by(2))
            {
                *d = r;
            }
        }
    }

    /// Takes from `exchange` the marks and triangle rows that core `core` of two wrote this
    /// frame, completing each shared object's visible-vertex pass.
    pub fn import_visible(&mut self, exchange: &VisibleExchange, core: usize) {
        let theirs = share(core.min(1), 2);
        let marks = &exchange.marks;
        let rows = &exchange.rows;
        let camera = &self.camera;
        let [sphere, torus, lamp] = self.visible_shared;
        if sphere {
            self.sphere.set_visible(
                camera,
                self.lit[0].cull,
                marks.sphere.iter().copied(),
                spread(&rows.sphere, TriangleRows::EMPTY),
                theirs,
            );
        }
        if torus {
            self.torus.set_visible(
                camera,
                self.lit[1].cull,
                marks.torus.iter().copied(),
                spread(&rows.torus, TriangleRows::EMPTY),
                theirs,
            );
        }
        if lamp {
            self.lamp.set_visible(
                camera,
                self.emissive.cull,
                marks.lamp.iter().copied(),
                spread(&rows.lamp, TriangleRows::EMPTY),
                theirs,
            );
        }
    }

    /// [`Demo::shade`] of this core's share of the visible vertices: those whose index is
    /// `core` modulo `cores`. With two cores, each shades its half, then each takes the
    /// other's colours through a [`ColourExchange`] ([`Demo::export_colours`],
    /// [`Demo::import_colours`]): every visible vertex is shaded once per frame.
    pub fn shade_share(&mut self, frame: &Frame<T>, core: usize, cores: usize) -> u32 {
        let cores = cores.max(1);
        self.shade_where(frame, share(core, cores))
    }

    /// [`Demo::shade_share`], calling `poll` before each of this core's shader calls (one
    /// every 20 000 to 40 000 cycles on the RP2040): a two-core firmware sends the frame's
    /// empty bands from there while the display link would otherwise idle
    /// ([`Demo::band_is_empty`]). The same colours.
    pub fn shade_share_polling(
        &mut self,
        frame: &Frame<T>,
        core: usize,
        cores: usize,
        poll: impl FnMut(),
    ) -> u32 {
        let ours = share(core, cores.max(1));
        // (`shade_some` takes a `Fn` filter: the poll behind a `RefCell`.)
        let poll = core::cell::RefCell::new(poll);
        self.shade_where(frame, |i| {
            let mine = ours(i);
            if mine {
                if let Ok(mut poll) = poll.try_borrow_mut() {
                    (*poll)();
                }
            }
            mine
        })
    }

    /// Writes this frame's vertex colours into `exchange` (after [`Demo::shade_share`]).
    pub fn export_colours(&self, exchange: &mut ColourExchange) {
        let copy = |dst: &mut [VertexColour], src: &PreparedMesh<'_, '_, T>| {
            for (d, c) in dst.iter_mut().zip(src.colours()) {
                *d = c;
            }
        };
        copy(&mut exchange.sphere, &self.sphere);
        copy(&mut exchange.torus, &self.torus);
        copy(&mut exchange.lamp, &self.lamp);
    }

    /// Takes from `exchange` the colours of the vertices that core `core` of `cores` shaded
    /// (what it exported this frame).
    pub fn import_colours(&mut self, exchange: &ColourExchange, core: usize, cores: usize) {
        let cores = cores.max(1);
        let theirs = share(core, cores);
        self.sphere
            .set_colours(exchange.sphere.iter().copied(), theirs);
        self.torus
            .set_colours(exchange.torus.iter().copied(), theirs);
        self.lamp.set_colours(exchange.lamp.iter().copied(), theirs);
    }
}

/// One core's share of the vertices' screen data of a frame, as two cores exchange them (see
/// [`Demo::transform_share`]): the vertices of index `core` modulo 2, in order (entry `j` is
/// vertex `2 j + core`). Each core writes its own and reads the other core's, so the two
/// can copy at once (9 KiB each in `Fixed22`).
#[derive(Clone, Debug)]
pub struct ScreenExchange<T> {
    sphere: [VertexScreen<T>; SPHERE_VERTICES.div_ceil(2)],
    torus: [VertexScreen<T>; TORUS_VERTICES.div_ceil(2)],
    lamp: [VertexScreen<T>; LAMP_VERTICES.div_ceil(2)],
}

impl<T: Real> ScreenExchange<T> {
    /// All placeholders (a `const fn`, for a `static`; all zero bits).
    pub const fn new() -> Self {
        ScreenExchange {
            sphere: [VertexScreen::EMPTY; SPHERE_VERTICES.div_ceil(2)],
            torus: [VertexScreen::EMPTY; TORUS_VERTICES.div_ceil(2)],
            lamp: [VertexScreen::EMPTY; LAMP_VERTICES.div_ceil(2)],
        }
    }
}

impl<T: Real> Default for ScreenExchange<T> {
    fn default() -> Self {
        Self::new()
    }
}

/// The shaded vertex colours of one frame, as one core hands them to another (see
/// [`Demo::shade_share`]): 7 KiB.
#[derive(Clone, Debug)]
pub struct ColourExchange {
    sphere: [VertexColour; SPHERE_VERTICES],
    torus: [VertexColour; TORUS_VERTICES],
    lamp: [VertexColour; LAMP_VERTICES],
}

impl ColourExchange {
    /// All black (a `const fn`, for a `static`).
    pub const fn new() -> Self {
        ColourExchange {
            sphere: [VertexColour::BLACK; SPHERE_VERTICES],
            torus: [VertexColour::BLACK; TORUS_VERTICES],
            lamp: [VertexColour::BLACK; LAMP_VERTICES],
        }
    }
}

impl Default for ColourExchange {
    fn default() -> Self {
        Self::new()
    }
}

/// One core's share of a frame's visible-vertex pass, as two cores exchange them (see
/// [`Demo::find_visible_share`]): its marks of every vertex and the rows of its triangles (of
/// index `core` modulo 2, in order). Each core writes its own and reads the other core's, so
/// the two can copy at once (2.5 KiB each).
#[derive(Clone, Debug)]
pub struct VisibleExchange {
    marks: VisibleMarks,
    rows: ExchangedRows,
}

/// Each object's vertices as one core's pass marked them.
#[derive(Clone, Debug)]
struct VisibleMarks {
    sphere: [bool; SPHERE_VERTICES],
    torus: [bool; TORUS_VERTICES],
    lamp: [bool; LAMP_VERTICES],
}

/// Each object's rows of one core's triangles.
#[derive(Clone, Debug)]
struct ExchangedRows {
    sphere: [TriangleRows; SPHERE_TRIANGLES.div_ceil(2)],
    torus: [TriangleRows; TORUS_TRIANGLES.div_ceil(2)],
    lamp: [TriangleRows; LAMP_TRIANGLES.div_ceil(2)],
}

impl VisibleExchange {
    /// Nothing marked, no rows (a `const fn`, for a `static`).
    pub const fn new() -> Self {
        VisibleExchange {
            marks: VisibleMarks {
                sphere: [false; SPHERE_VERTICES],
                torus: [false; TORUS_VERTICES],
                lamp: [false; LAMP_VERTICES],
            },
            rows: ExchangedRows {
                sphere: [TriangleRows::EMPTY; SPHERE_TRIANGLES.div_ceil(2)],
                torus: [TriangleRows::EMPTY; TORUS_TRIANGLES.div_ceil(2)],
                lamp: [TriangleRows::EMPTY; LAMP_TRIANGLES.div_ceil(2)],
            },
        }
    }
}

impl Default for VisibleExchange {
    fn default() -> Self {
        Self::new()
    }
}
