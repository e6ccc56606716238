//! Sharing a frame between two cores: each core transforms and shades its share of a
//! [`PreparedMesh`]'s vertices (`mine`: e.g. even or odd indices), and takes the other's
//! share from it: the screen positions after [`PreparedMesh::transform_some`]
//! ([`PreparedMesh::screen`], [`PreparedMesh::set_screen`]), the colours after
//! [`PreparedMesh::shade_some`] ([`PreparedMesh::colours`], [`PreparedMesh::set_colours`]).
//! Both then hold the same frame as one core that did all the work, bit for bit: each
//! vertex's work depends on that vertex alone. Between the two, the pass that finds the
//! visible vertices can be shared too, by triangles ([`PreparedMesh::find_visible_some`],
//! [`PreparedMesh::visible_marks`], [`PreparedMesh::triangle_rows`],
//! [`PreparedMesh::set_visible`]): each triangle's verdict depends on that triangle alone.

use super::{screen_rows, Affine, Camera, PreparedMesh, TriangleRows, BEYOND, KEPT, NEEDED};
use crate::raster::edge::FixedPoint;
use crate::raster::Cull;
use crate::{Real, Vec3};

/// A shaded vertex colour as [`PreparedMesh`] keeps it (linear, times the exposure, in fixed
/// point): opaque, to be handed from one core's prepared mesh to another's
/// ([`PreparedMesh::colours`], [`PreparedMesh::set_colours`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct VertexColour([i32; 3]);

impl VertexColour {
    /// Black (to fill exchange buffers).
    pub const BLACK: Self = VertexColour([0; 3]);
}

/// A vertex's screen data as [`PreparedMesh::transform_some`] leaves it (snapped position,
/// depth, `1/w`, clip flags, and the world position, from which a triangle that crosses a
/// clip plane is clipped): opaque, to be handed from one core's prepared mesh to another's
/// ([`PreparedMesh::screen`], [`PreparedMesh::set_screen`]). What Gouraud drawing and finding
/// the visible vertices need; not the normal, which only the shading of the vertex itself
/// reads (so a vertex must be shaded by the core that transformed it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexScreen<T> {
    p: Vec3<T>,
    fp: FixedPoint,
    depth: i32,
    iw: T,
    outside: u8,
    beyond: bool,
}

impl<T: Real> VertexScreen<T> {
    /// A placeholder to fill exchange buffers (all zero bits, so that a `static` of them
    /// costs no flash, as [`PreparedVertex::EMPTY`](super::PreparedVertex::EMPTY)).
    pub const EMPTY: Self = VertexScreen {
        p: Vec3::new(T::ZERO, T::ZERO, T::ZERO),
        fp: FixedPoint::new(0, 0),
        depth: 0,
        iw: T::ZERO,
        outside: 0,
        beyond: false,
    };
}

impl<T: Real> PreparedMesh<'_, '_, T> {
    /// [`PreparedMesh::transform`] of only the vertices whose index `mine` accepts (the others
    /// are left as they are); [`PreparedMesh::set_screen`] then takes the others' screen data
    /// from the core that transformed them. For two cores that share a frame: each transforms
    /// half the vertices, then each takes the other's half, instead of both transforming all.
    /// `normals: false` is [`PreparedMesh::transform_unlit`]'s. Until `set_screen`, the mesh's
    /// rows ([`PreparedMesh::rows`]) are those of this share alone.
    ///
    /// Cost: [`PreparedMesh::transform`]'s per accepted vertex, one call of `mine` per vertex.
    pub fn transform_some(
        &mut self,
        camera: &Camera<T>,
        transform: &Affine<T>,
        normals: bool,
        mine: impl Fn(usize) -> bool,
    ) {
        self.transform_with(camera, transform, normals, mine);
    }

    /// The screen data of the vertices, in vertex order (meaningful for the vertices
    /// transformed this frame): what a core hands the other after
    /// [`PreparedMesh::transform_some`].
    pub fn screen(&self) -> impl Iterator<Item = VertexScreen<T>> + '_ {
        self.verts.iter().map(|v| VertexScreen {
            p: v.p,
            fp: v.fp,
            depth: v.depth,
            iw: v.iw,
            outside: v.outside,
            beyond: v.flags & BEYOND != 0,
        })
    }

    /// Takes the screen data of the vertices whose index `theirs` accepts from `screen` (in
    /// vertex order, as [`PreparedMesh::screen`] gives them; missing entries are left as they
    /// are), then finds the mesh's rows and range flag over all its vertices, as
    /// [`PreparedMesh::transform`] would have. `camera` is the one of the transform. Those
    /// vertices' normals are not taken: shade each vertex on the core that transformed it ([`PreparedMesh::shade_some`] with the same `mine`), and draw with
    /// Gouraud shading (per pixel needs every vertex's position and normal).
    ///
    /// Cost: a few operations per vertex.
    pub fn set_screen(
        &mut self,
        camera: &Camera<T>,
        screen: impl IntoIterator<Item = VertexScreen<T>>,
        theirs: impl Fn(usize) -> bool,
    ) {
        for (i, (v, s)) in self.verts.iter_mut().zip(screen).enumerate() {
            if theirs(i) {
                v.p = s.p;
                v.fp = s.fp;
                v.depth = s.depth;
                v.iw = s.iw;
                v.outside = s.outside;
                v.flags = (v.flags & !(BEYOND | KEPT)) | if s.beyond { BEYOND } else { 0 };
            }
        }
        let (mut top, mut bottom) = (i32::MAX, i32::MIN);
        let (mut clipped, mut beyond) = (false, false);
        for v in self.verts.iter() {
            beyond |= v.flags & BEYOND != 0;
            if v.outside != 0 {
                clipped = true;
            } else {
                top = top.min(v.fp.y);
                bottom = bottom.max(v.fp.y);
            }
        }
        self.out_of_range = beyond;
        self.rows_cull = None;
        self.visible = None;
        self.rows = screen_rows(camera, clipped, top, bottom);
    }

    /// The visible-vertex pass of [`PreparedMesh::shade`] over only the triangles whose index
    /// `mine` accepts, when the pass is due (the screen data changed since the last one, or
    /// `cull` or the viewport did; `false`, nothing done, otherwise): each vertex is marked
    /// if one of these triangles will be drawn, and their rows are recorded. For two cores
    /// that share a frame: each makes the pass over its share of the triangles (e.g. even
    /// and odd indices), hands the other its marks and rows ([`PreparedMesh::visible_marks`],
    /// [`PreparedMesh::triangle_rows`]) and takes the other's ([`PreparedMesh::set_visible`]);
    /// both then know the visible vertices as one pass over every triangle finds them, and
    /// [`PreparedMesh::shade_some`] goes straight to its shader calls. Both cores decide the
    /// same (the same screen data): run the exchange when this returns `true`.
    ///
    /// Cost: the pass's per accepted triangle (about 280 cycles on the RP2040, rp2040js) and
    /// a clear of every vertex's mark.
    pub fn find_visible_some(
        &mut self,
        camera: &Camera<T>,
        cull: Cull,
        mine: impl Fn(usize) -> bool,
    ) -> bool {
        if self.visible == Some((cull, camera.width, camera.height)) {
            return false;
        }
        self.find_visible(camera, cull, mine);
        self.visible = None;
        self.rows_cull = None;
        true
    }

    /// Whether each vertex, in vertex order, is marked visible: after
    /// [`PreparedMesh::find_visible_some`], by this core's triangles.
    pub fn visible_marks(&self) -> impl Iterator<Item = bool> + '_ {
        self.verts.iter().map(|v| v.flags & NEEDED != 0)
    }

    /// The triangles' rows, in triangle order (meaningful for the triangles of the last
    /// pass; none if the mesh records no rows, [`PreparedMesh::with_triangle_rows`]).
    pub fn triangle_rows(&self) -> impl Iterator<Item = TriangleRows> + '_ {
        self.tri_rows.iter().copied()
    }

    /// Completes a pass that [`PreparedMesh::find_visible_some`] made over this core's
    /// triangles with the other core's: marks the vertices `marks` marks (in vertex order, as
    /// [`PreparedMesh::visible_marks`] gives them), takes the rows of the triangles whose
    /// index `theirs` accepts from `rows` (in triangle order, as
    /// [`PreparedMesh::triangle_rows`] gives them), and records the pass as done for `cull`
    /// and the camera's viewport, as one over every triangle would have left the mesh.
    ///
    /// Cost: a few operations per vertex and per triangle.
    pub fn set_visible(
        &mut self,
        camera: &Camera<T>,
        cull: Cull,
        marks: impl IntoIterator<Item = bool>,
        rows: impl IntoIterator<Item = TriangleRows>,
        theirs: impl Fn(usize) -> bool,
    ) {
        for (v, m) in self.verts.iter_mut().zip(marks) {
            if m {
                v.flags |= NEEDED;
            }
        }
        for (k, (slot, r)) in self.tri_rows.iter_mut().zip(rows).enumerate() {
            if theirs(k) {
                *slot = r;
            }
        }
        self.visible_done(camera, cull);
    }

    /// The shaded colours of the vertices, in vertex order (meaningful for the vertices
    /// shaded this frame): what a core hands the other after [`PreparedMesh::shade_some`].
    pub fn colours(&self) -> impl Iterator<Item = VertexColour> + '_ {
        self.verts.iter().map(|v| VertexColour(v.colour))
    }

    /// Takes the colours of the vertices whose index `theirs` accepts from `colours` (in
    /// vertex order, as [`PreparedMesh::colours`] gives them; missing entries are left as
    /// they are).
    pub fn set_colours(
        &mut self,
        colours: impl IntoIterator<Item = VertexColour>,
        theirs: impl Fn(usize) -> bool,
    ) {
        for (i, (v, c)) in self.verts.iter_mut().zip(colours).enumerate() {
            if theirs(i) {
                v.colour = c.0;
            }
        }
    }
}
