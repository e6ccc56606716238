//! Meshes prepared once per frame, then drawn band by band in integers.
//!
//! [`draw`](super::draw) does all of a triangle's work each time it meets a band: three vertex
//! transforms and projections, the Gouraud shader calls, and per pixel a perspective division
//! and the encoding's transfer function, all in `T` (soft-float or fixed point on a
//! Cortex-M0+). A frame rendered in 15 bands repeats the vertex work for every band a
//! triangle's object touches. [`PreparedMesh`] splits the work by how often it is needed:
//!
//! 1. **Once per frame, per vertex** ([`PreparedMesh::transform`]): the model transform, the
//!    unit normal, the clip-space position, which clip planes it is outside of, its snapped
//!    screen position (1/16 pixel, exactly [`draw`](super::draw)'s) and its depth value.
//! 2. **Once per frame, per visible vertex** ([`PreparedMesh::shade`], Gouraud): the shader,
//!    only at vertices of triangles that will be drawn (front-facing, non-degenerate, on
//!    screen), each vertex once however many triangles and bands share it. The colour (times
//!    the exposure) is kept as an integer with 24 fraction bits.
//! 3. **Per band, per triangle that reaches it** ([`PreparedMesh::draw`]): the edge functions
//!    ([`EdgeTriangle`](super::EdgeTriangle): the same exact coverage as
//!    [`draw`](super::draw)), then every attribute as a plane
//!    `a(x, y) = a_b + (x - x_b) s_x + (y - y_b) s_y` in integers: one setup per triangle
//!    (its barycentric gradients from one integer reciprocal of its area, then per attribute
//!    a few products; all in 32-bit integers for a triangle of display size, exactly as the
//!    64-bit fallback), then per covered pixel one
//!    multiply-add per attribute, a depth compare, and (Gouraud) three loads from an
//!    [`EncodeTable`](super::EncodeTable), with no range test where the triangle's vertex
//!    colours keep every pixel within the table's guards (`gouraud` module). No division and
//!    no `T` arithmetic per pixel in Gouraud mode.
//!
//! The attribute values at a pixel depend only on the triangle and the pixel (the plane is
//! anchored at the triangle's own bounding box, not at the band), so a band gets exactly its
//! rows of the full frame, as with [`draw`](super::draw).
//!
//! ## How it differs from `draw`
//!
//! - Gouraud colours are interpolated affinely in screen space (no perspective correction):
//!   the usual choice for small triangles; the error is the colour difference across a
//!   triangle times the relative depth change across it. Per-pixel positions and normals are
//!   still perspective-correct.
//! - Depth is `far (z - near) / (z (far - near))` (perspective; affine on screen, so it can be
//!   stepped), linear `(z - near) / (far - near)` (orthographic), 16 bits, smaller is nearer:
//!   do not mix [`draw`](super::draw) and [`PreparedMesh::draw`] in one depth band.
//! - Colours go through an [`EncodeTable`](super::EncodeTable) (within one level of [`encode_pixel`](super::encode_pixel)).
//! - Interpolated colours are clamped to `[0, 127]` (times the exposure) at the vertices.
//!
//! Triangles that cross the near, far or guard-band planes are clipped exactly as in
//! [`draw`](super::draw), and their pieces drawn by the same integer loop.
//!
//! ## Cost (measured: see the README's frame tables)
//!
//! Storage: one [`PreparedVertex`] per mesh vertex (caller-provided). Per frame: one vertex
//! transform, normalization and projection per vertex (one division), one shader call per
//! visible vertex. Per band and triangle: a row test (with
//! [`PreparedMesh::with_triangle_rows`], one load and two comparisons per triangle: none of
//! a culled one's vertex loads, nor a drawn one's row and culling tests); per triangle drawn: an edge setup, four
//! attribute planes (Gouraud: depth and three channels; per pixel: depth and two barycentric
//! weights); per covered pixel: Gouraud about 20 integer operations, per pixel the shader, one
//! division and one normalization in `T`.

use super::edge::{edge_small_or_in_range, FixedPoint, SUBPIXEL};
use super::scan::colour_bits;
use super::shade::{Shader, Shading};
use super::split::LightSums;
use super::{Affine, Camera, DrawOptions, Mesh, RasterError};
use crate::{Real, UnitVec3, Vec3};

mod draw;
mod share;
mod split;
mod transform;
pub use share::{VertexColour, VertexScreen};
use transform::{project, screen_rows};

/// Vertex flags: shaded this frame (Gouraud) ...
const NEEDED: u8 = 1;
/// ... and transformed to a finite position beyond [`Real::COORDINATE_LIMIT`] (fixed point) ...
const BEYOND: u8 = 2;
/// ... and its entry of the fixed sums holds its [`SplitShader`](super::SplitShader)'s fixed
/// part for the mesh's `fixed_key` (cleared with the vertex's screen data).
const KEPT: u8 = 4;
/// ... and its normal is not computed yet: the mesh's `normals` transform gives it where it
/// is first needed ([`PreparedMesh::settle_normal`]), the same bits as the transform would
/// have (most vertices are never shaded: they face away or lie off screen).
const NORMAL_DUE: u8 = 8;

/// One vertex of a [`PreparedMesh`] for the current frame (see the module docs). Storage only:
/// its fields are the rasterizer's.
#[derive(Clone, Copy, Debug)]
pub struct PreparedVertex<T> {
    /// World position.
    pub(super) p: Vec3<T>,
    /// Unit world normal (zero if it had no direction).
    pub(super) n: Vec3<T>,
    /// `1 / w`.
    pub(super) iw: T,
    /// Snapped screen position (valid when `outside == 0`).
    pub(super) fp: FixedPoint,
    /// The depth value `q` with [`DEPTH_FRAC`] fraction bits (valid when `outside == 0`).
    pub(super) depth: i32,
    /// The shaded colour times the exposure, [`COLOUR_FRAC`] fraction bits (Gouraud).
    pub(super) colour: [i32; 3],
    /// Bit `k` set: outside clip plane `k` (near, far, guard band x+, x-, y+, y-); all set for
    /// a non-finite position.
    pub(super) outside: u8,
    pub(super) flags: u8,
}

impl<T: Real> PreparedVertex<T> {
    /// An unused vertex (to fill storage arrays; all zero bits, so that a `static` of them
    /// costs no flash).
    pub const EMPTY: Self = PreparedVertex {
        p: Vec3::new(T::ZERO, T::ZERO, T::ZERO),
        n: Vec3::new(T::ZERO, T::ZERO, T::ZERO),
        iw: T::ZERO,
        fp: FixedPoint::new(0, 0),
        depth: 0,
        colour: [0; 3],
        outside: 0,
        flags: 0,
    };
}

impl<T: Real> Default for PreparedVertex<T> {
    fn default() -> Self {
        Self::EMPTY
    }
}

/// The pixel rows one triangle of a [`PreparedMesh`] can touch this frame (see
/// [`PreparedMesh::with_triangle_rows`]): storage only, 4 bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TriangleRows {
    /// No row at or after this one (clamped to `0..=65535`).
    top: u16,
    /// No row before this one (clamped to `0..=65535`).
    end: u16,
}

impl TriangleRows {
    /// A triangle that touches no row (to fill storage arrays).
    pub const EMPTY: Self = TriangleRows { top: 0, end: 0 };
    /// Every row (a triangle that crosses a clip plane).
    const ALL: Self = TriangleRows {
        top: 0,
        end: u16::MAX,
    };
    /// The rows of a triangle with these (unclipped) vertices: those whose test in
    /// [`PreparedMesh::draw`] (`hi < 16 row0 || lo > 16 row1` with the vertices' lowest and
    /// highest sub-pixel rows `lo`, `hi`) passes: `end = floor(hi / 16) + 1`, `top =
    /// floor((lo - 1) / 16)`, both clamped to `0..=65535` (which keeps the verdict for any
    /// band within `0..=65535`).
    #[inline(always)]
    fn of(fp: &[FixedPoint; 3]) -> Self {
        let lo = fp[0].y.min(fp[1].y).min(fp[2].y);
        let hi = fp[0].y.max(fp[1].y).max(fp[2].y);
        let clamp = |r: i32| r.clamp(0, u16::MAX as i32) as u16;
        TriangleRows {
            top: clamp(lo.saturating_sub(1).div_euclid(SUBPIXEL)),
            end: clamp(hi.div_euclid(SUBPIXEL).saturating_add(1)),
        }
    }
    /// `true` when the triangle can touch no pixel row in `[row0, row1)` (`0 <= row0 < row1
    /// <= 65535`): the same verdict as the sub-pixel test of [`PreparedMesh::draw`].
    #[inline(always)]
    fn misses(self, row0: i32, row1: i32) -> bool {
        i32::from(self.end) <= row0 || i32::from(self.top) >= row1
    }
}

impl Default for TriangleRows {
    fn default() -> Self {
        Self::EMPTY
    }
}

/// A [`Mesh`] with its vertices transformed, projected and (Gouraud) shaded for the current
/// frame, drawn into any number of bands (see the module docs).
///
/// ```
/// use arealight::raster::{
///     mesh, Affine, Band, Camera, DrawOptions, EncodeTable, Encoding, Lit, Material, Mesh,
///     PreparedMesh, PreparedVertex, Projection, Rgb565, Shading, Vertex,
/// };
/// use arealight::{Rgb, SphereLight, Vec3};
///
/// let (mut verts, mut tris) = ([Vertex::default(); 17 * 9], [[0u16; 3]; 2 * 16 * 7]);
/// let counts = mesh::uv_sphere(1.0f32, 8, 16, &mut verts, &mut tris)?;
/// let sphere = Mesh::new(&verts[..counts.vertices], &tris[..counts.triangles])?;
/// let camera = Camera::new(
///     Vec3::new(0.0, 0.0, 4.0), Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0),
///     Projection::Perspective { fov_y: 0.7 }, 64, 64,
/// )?;
/// let lamp = SphereLight::new(Vec3::new(2.0, 2.0, 3.0), 0.5)?;
/// let plastic = Material::new(Rgb::new(0.8, 0.3, 0.2), Rgb::splat(0.5), 16)?;
/// let shader = Lit::new(&lamp, &plastic);
/// let opts = DrawOptions::new(Shading::Gouraud);
/// let table = EncodeTable::new::<f32>(Encoding::Srgb);
///
/// // Once per frame: transform and shade.
/// let mut storage = [PreparedVertex::EMPTY; 17 * 9];
/// let mut prepared = PreparedMesh::new(sphere, &mut storage)?;
/// prepared.transform(&camera, &Affine::identity());
/// prepared.shade(&camera, &shader, &opts);
/// // Per band: draw.
/// let (mut pixels, mut depth) = ([Rgb565(0); 64 * 16], [0u16; 64 * 16]);
/// let mut band = Band::new(&mut pixels, Some(&mut depth), 64, 0)?;
/// for y0 in (0..64).step_by(16) {
///     band.move_to(y0);
///     band.clear(Rgb565(0));
///     prepared.draw(&camera, &mut band, &shader, &opts, &table)?;
///     // send band.pixels() to the display's rows y0..y0 + 16 here
/// }
/// # Ok::<(), arealight::raster::RasterError>(())
/// ```
#[derive(Debug)]
pub struct PreparedMesh<'m, 's, T: Real> {
    mesh: Mesh<'m, T>,
    verts: &'s mut [PreparedVertex<T>],
    /// One entry per triangle (or none: [`PreparedMesh::new`]), set by
    /// [`PreparedMesh::transform`].
    tri_rows: &'s mut [TriangleRows],
    /// `tri_rows` holds this frame's rows, found by [`PreparedMesh::shade`] with this
    /// culling (culled triangles touch no row).
    rows_cull: Option<super::Cull>,
    /// The vertices' `NEEDED` flags (and `tri_rows`, as `rows_cull` says) are those
    /// [`PreparedMesh::shade_some`] found for this culling and viewport size, and no vertex's
    /// screen data has changed since: the next shade with the same finds them again without
    /// visiting the triangles.
    visible: Option<(super::Cull, u16, u16)>,
    /// Screen rows `[top, bottom)` the mesh can cover (all rows if a vertex is clipped).
    rows: (i32, i32),
    /// A transformed vertex lies beyond `T::COORDINATE_LIMIT` (fixed point): `draw` refuses.
    out_of_range: bool,
    /// One entry per vertex (or none): the fixed parts of
    /// [`PreparedMesh::shade_split`]'s shader, valid where the vertex's `KEPT` flag is set.
    fixed_sums: &'s mut [LightSums<T>],
    /// The shader's fixed version and the options' `two_sided` the kept parts are for.
    fixed_key: Option<(u32, bool)>,
    /// The normal matrix of the last transform with normals (fixed point): the normals of
    /// the vertices marked `NORMAL_DUE` go through it when first needed.
    normals: T::KeptNormals,
}

impl<'m, 's, T: Real> PreparedMesh<'m, 's, T> {
    /// `mesh` with `storage` for its per-frame vertex data (at least one entry per vertex).
    /// Call [`PreparedMesh::transform`] before drawing.
    ///
    /// # Errors
    /// [`RasterError::BufferTooSmall`] (`"prepared vertices"`).
    pub fn new(
        mesh: Mesh<'m, T>,
        storage: &'s mut [PreparedVertex<T>],
    ) -> Result<Self, RasterError> {
        let needed = mesh.vertices().len();
        let got = storage.len();
        let verts = storage
            .get_mut(..needed)
            .ok_or(RasterError::BufferTooSmall {
                what: "prepared vertices",
                needed,
                got,
            })?;
        for v in verts.iter_mut() {
            *v = PreparedVertex::EMPTY;
        }
        Ok(PreparedMesh {
            mesh,
            verts,
            tri_rows: &mut [],
            rows_cull: None,
            visible: None,
            rows: (0, 0),
            out_of_range: false,
            fixed_sums: &mut [],
            fixed_key: None,
            normals: T::NO_KEPT_NORMALS,
        })
    }

    /// [`PreparedMesh::new`] with `rows` for the pixel rows each triangle can touch (at least
    /// one entry per triangle, 4 bytes each), found once per frame by [`PreparedMesh::shade`]
    /// (or [`PreparedMesh::shade_some`]) as it visits the triangles: then (Gouraud)
    /// [`PreparedMesh::draw`] passes over a triangle that misses the band with one load and
    /// two comparisons, instead of loading its three vertices and comparing their rows, and
    /// over a triangle that `shade` culled (with `draw`'s [`Cull`](super::Cull)) the same way;
    /// the others it draws without testing their rows and faces again.
    /// The same pixels either way (without a shade since the last transform, with another
    /// culling, and per pixel, `draw` visits every triangle as without `rows`).
    ///
    /// # Errors
    /// [`RasterError::BufferTooSmall`] (`"prepared vertices"`, `"triangle rows"`).
    pub fn with_triangle_rows(
        mesh: Mesh<'m, T>,
        storage: &'s mut [PreparedVertex<T>],
        rows: &'s mut [TriangleRows],
    ) -> Result<Self, RasterError> {
        let needed = mesh.triangles().len();
        let got = rows.len();
        let rows = rows.get_mut(..needed).ok_or(RasterError::BufferTooSmall {
            what: "triangle rows",
            needed,
            got,
        })?;
        rows.fill(TriangleRows::EMPTY);
        let mut m = Self::new(mesh, storage)?;
        m.tri_rows = rows;
        Ok(m)
    }

    /// The mesh.
    pub fn mesh(&self) -> &Mesh<'m, T> {
        &self.mesh
    }

    /// Screen rows `[top, bottom)` the mesh can cover this frame (all rows when a vertex is
    /// clipped); a band outside them costs [`PreparedMesh::draw`] nothing.
    pub fn rows(&self) -> (i32, i32) {
        self.rows
    }

    /// Gouraud: shades, once each, the vertices of the triangles that will be drawn
    /// (front-facing unless `opts.cull` is [`Cull::None`](super::Cull::None), non-degenerate, overlapping the
    /// viewport; all three of a clipped one), and keeps their colours times `opts.exposure`.
    /// Per pixel ([`Shading::PerPixel`]): nothing (the shader runs in [`PreparedMesh::draw`]).
    /// Returns the number of shader calls. Call after [`PreparedMesh::transform`].
    ///
    /// Cost: per triangle a few integer tests (2 multiplications), to find the visible
    /// vertices; per visible vertex one shader call and a normalization (the view
    /// direction), and in fixed point, the first time after a transform, its normal (see
    /// [`PreparedMesh::transform`]). The triangles are not visited again while the vertices' screen data stay
    /// as they are (no [`PreparedMesh::transform`] or [`PreparedMesh::set_screen`] since the
    /// last shade) and the culling and viewport size are the same: a mesh that does not move
    /// needs neither a new transform nor that pass, only its shader calls (the same colours:
    /// the pass depends on nothing else).
    pub fn shade<S: Shader<T> + ?Sized>(
        &mut self,
        camera: &Camera<T>,
        shader: &S,
        opts: &DrawOptions<T>,
    ) -> u32 {
        self.shade_some(camera, shader, opts, |_| true)
    }

    /// [`PreparedMesh::shade`] of only the vertices whose index `mine` accepts: the visible
    /// vertices are found as by `shade`, but only these are shaded. For two cores that share
    /// a frame: each shades its share (e.g. even and odd indices), then each takes the
    /// other's colours ([`PreparedMesh::colours`], [`PreparedMesh::set_colours`]), so that
    /// every visible vertex is shaded once per frame whichever core draws it.
    pub fn shade_some<S, W>(
        &mut self,
        camera: &Camera<T>,
        shader: &S,
        opts: &DrawOptions<T>,
        mine: W,
    ) -> u32
    where
        S: Shader<T> + ?Sized,
        W: Fn(usize) -> bool,
    {
        if opts.shading != Shading::Gouraud {
            // Per pixel, the drawing interpolates the normals: all of them now, once.
            self.settle_normals();
            return 0;
        }
        self.update_visible(camera, opts.cull);
        let mut calls = 0u32;
        let src = self.mesh.vertices();
        for (i, v) in self.verts.iter_mut().enumerate() {
            if v.flags & NEEDED == 0 || !mine(i) {
                continue;
            }
            Self::settle_normal(v, src.get(i), &self.normals);
            let (n, view) = Self::shading_frame(camera, v, opts.two_sided);
            let col = shader.shade(v.p, n, view).finite_or_zero();
            v.colour = colour_bits(col, opts.exposure);
            calls = calls.wrapping_add(1);
        }
        calls
    }

    /// Finds the visible vertices for `cull` and the camera's viewport
    /// ([`PreparedMesh::find_visible`]) unless they are known already.
    #[inline(always)]
    fn update_visible(&mut self, camera: &Camera<T>, cull: super::Cull) {
        let visible = Some((cull, camera.width, camera.height));
        if self.visible != visible {
            self.find_visible(camera, cull, |_| true);
            self.visible_done(camera, cull);
        }
    }

    /// Records the visible-vertex pass as done for `cull` and the camera's viewport (the
    /// triangles' rows with it, where the mesh records them).
    fn visible_done(&mut self, camera: &Camera<T>, cull: super::Cull) {
        let record = self.tri_rows.len() == self.mesh.triangles().len();
        self.rows_cull = record.then_some(cull);
        self.visible = Some((cull, camera.width, camera.height));
    }

    /// A vertex's unit normal (toward the viewer when `two_sided`) and unit view direction,
    /// as the shader gets them.
    #[inline(always)]
    fn shading_frame(
        camera: &Camera<T>,
        v: &PreparedVertex<T>,
        two_sided: bool,
    ) -> (UnitVec3<T>, UnitVec3<T>) {
        let view = camera.view_dir(v.p);
        let n = super::draw::unit_or_view(v.n, view);
        let n = if two_sided && n.dot(*view) < T::ZERO {
            -n
        } else {
            n
        };
        (n, view)
    }

    /// The visible-vertex pass of [`PreparedMesh::shade_some`]: marks `NEEDED` the vertices
    /// of the triangles that will be drawn with `cull` (and records each triangle's rows
    /// where there are `tri_rows`). Cost: per triangle three vertex loads and a few integer
    /// tests (2 multiplications): 2.1 ms for the demo's 940 triangles on the RP2040 at 125
    /// MHz (rp2040js), about 280 cycles a triangle. Only the triangles whose index `mine`
    /// accepts are visited (`PreparedMesh::find_visible_some`: two cores share the pass);
    /// the vertices' marks are all cleared first. Marks the pass done nowhere: the caller does
    /// ([`PreparedMesh::visible_done`]).
    fn find_visible(
        &mut self,
        camera: &Camera<T>,
        cull: super::Cull,
        mine: impl Fn(usize) -> bool,
    ) {
        for v in self.verts.iter_mut() {
            v.flags &= !NEEDED;
        }
        let (w, h) = (
            camera.width as i32 * SUBPIXEL,
            camera.height as i32 * SUBPIXEL,
        );
        let record = self.tri_rows.len() == self.mesh.triangles().len();
        for (k, tri) in self.mesh.triangles().iter().enumerate() {
            if !mine(k) {
                continue;
            }
            let mut set = |r: TriangleRows| {
                if record {
                    if let Some(slot) = self.tri_rows.get_mut(k) {
                        *slot = r;
                    }
                }
            };
            let Some([a, b, c]) = corners(self.verts, tri) else {
                set(TriangleRows::EMPTY);
                continue;
            };
            if a.outside & b.outside & c.outside != 0 {
                set(TriangleRows::EMPTY);
                continue;
            }
            if (a.outside | b.outside | c.outside) != 0 {
                set(TriangleRows::ALL);
            } else {
                let fp = [a.fp, b.fp, c.fp];
                if !faces(&fp, cull) {
                    // `draw` with the same culling skips it too.
                    set(TriangleRows::EMPTY);
                    continue;
                }
                set(TriangleRows::of(&fp));
                let off_screen = fp.iter().all(|p| p.x < 0)
                    || fp.iter().all(|p| p.x > w)
                    || fp.iter().all(|p| p.y < 0)
                    || fp.iter().all(|p| p.y > h);
                if off_screen {
                    continue;
                }
            }
            for i in tri.map(usize::from) {
                if let Some(v) = self.verts.get_mut(i) {
                    v.flags |= NEEDED;
                }
            }
        }
    }
}

/// The three vertices of triangle `tri`, or `None` if an index is out of range.
#[inline(always)]
fn corners<'v, T>(
    verts: &'v [PreparedVertex<T>],
    tri: &[u16; 3],
) -> Option<[&'v PreparedVertex<T>; 3]> {
    Some([
        verts.get(usize::from(tri[0]))?,
        verts.get(usize::from(tri[1]))?,
        verts.get(usize::from(tri[2]))?,
    ])
}

/// The culling test of [`EdgeTriangle::new`](super::EdgeTriangle::new) alone (two products):
/// `false` for a triangle of zero area or (with [`Cull::Back`](super::Cull::Back)) a back
/// face, which it would refuse. Vertices of an unclipped triangle are within the guard band,
/// far inside `i32` products.
#[inline]
fn faces(v: &[FixedPoint; 3], cull: super::Cull) -> bool {
    let area = edge_small_or_in_range(v[0], v[1], v[2]);
    area < 0 || (area > 0 && cull == super::Cull::None)
}

// (Its scene is lit by a sphere light.)
#[cfg(all(test, feature = "cap"))]
mod tests;
