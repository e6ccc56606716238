//! The per-frame transform of a [`PreparedMesh`]: each vertex's world, clip and snapped
//! screen position and depth ([`PreparedMesh::transform`]), and its unit normal, which fixed
//! point leaves due until the shading or a drawing per pixel first needs it
//! ([`PreparedMesh::settle_normal`]).

use super::{PreparedMesh, PreparedVertex, BEYOND, NORMAL_DUE};
use crate::raster::affine::NormalMatrix;
use crate::raster::edge::{FixedPoint, SUBPIXEL};
use crate::raster::scan::DEPTH_FRAC;
use crate::raster::{plane_distances, Affine, Camera, Vertex};
use crate::{Real, Vec3};

impl<T: Real> PreparedMesh<'_, '_, T> {
    /// Transforms every vertex through `transform` and `camera` for this frame: world
    /// position, unit normal, clip position, snapped screen position and depth. Clears the
    /// shaded colours. A vertex that lands beyond [`Real::COORDINATE_LIMIT`] (fixed point
    /// only) is marked, and [`PreparedMesh::draw`] refuses the mesh until the next transform.
    ///
    /// In fixed point the unit normals are computed where first needed, by the shading (or by
    /// a drawing per pixel without a shade): the same bits, for only the vertices that are
    /// used (a closed mesh's back faces and off-screen parts are not). The floats compute them
    /// here, where they cost little (deferred, the bookkeeping cost the STM32F411's frame
    /// more than it saved). rp2040js, the demo's one-core frame 1: the transform 5 396 ->
    /// 4 118 us, the shading 26 634 -> 27 534 us, the frame 7 832 551 -> 7 791 783 cycles.
    ///
    /// Cost per vertex: 9 multiply-adds, 1 division, the projection (~15 operations in `T`);
    /// fixed point adds a range test (3 absolute values, 3 comparisons); for the normal (per
    /// vertex used, in fixed point) 9 multiply-adds and 1 normalization. The results stay
    /// until the next transform: a mesh whose transform and camera have not changed since (a
    /// static object) need not be transformed again, and its next [`PreparedMesh::shade`]
    /// skips finding the visible vertices too.
    pub fn transform(&mut self, camera: &Camera<T>, transform: &Affine<T>) {
        self.transform_with(camera, transform, true, |_| true);
    }

    /// [`PreparedMesh::transform`] without the normals (left zero): for a mesh whose shader
    /// does not read them (an emissive object), it saves a normal transform and a
    /// normalization per vertex.
    pub fn transform_unlit(&mut self, camera: &Camera<T>, transform: &Affine<T>) {
        self.transform_with(camera, transform, false, |_| true);
    }

    pub(super) fn transform_with(
        &mut self,
        camera: &Camera<T>,
        transform: &Affine<T>,
        normals: bool,
        mine: impl Fn(usize) -> bool,
    ) {
        let (near, far) = (camera.near, camera.far);
        // q = a - b / z in perspective, (z - near) / (far - near) orthographic.
        let range = far - near;
        let a = far / range;
        let b = far * near / range;
        let inv_range = T::ONE / range;
        let (mut top, mut bottom) = (i32::MAX, i32::MIN);
        let mut clipped = false;
        self.out_of_range = false;
        self.visible = None;
        // Fixed point, a small transform (every demo object's): the products without
        // saturation tests where the vertex's bounds allow (the same bits).
        let small = T::RESOLUTION > T::ZERO && transform.is_small();
        let normal_matrix = transform.normal_matrix(small);
        let eight = T::from_u32(8);
        let arr = |v: Vec3<T>| [v.x, v.y, v.z];
        for (i, (v, src)) in self.verts.iter_mut().zip(self.mesh.vertices()).enumerate() {
            if !mine(i) {
                continue;
            }
            let p = if small && T::all_within(arr(src.position), eight) {
                transform.point_small(src.position)
            } else {
                transform.point(src.position)
            };
            // Folds away for the float types (no limit).
            let beyond = T::COORDINATE_LIMIT < f64::MAX && p.check_position("vertex").is_err();
            self.out_of_range |= beyond && p.is_finite();
            if !p.is_finite() || beyond {
                *v = PreparedVertex {
                    outside: u8::MAX,
                    flags: if beyond && p.is_finite() { BEYOND } else { 0 },
                    ..PreparedVertex::EMPTY
                };
                clipped = true;
                continue;
            }
            let zero = Vec3::new(T::ZERO, T::ZERO, T::ZERO);
            // Fixed point defers the normals (see `NORMAL_DUE`); the floats, whose
            // normalization costs little, compute them here.
            let (n, due) = if !normals {
                (zero, 0)
            } else if Self::defers_normals() {
                (zero, NORMAL_DUE)
            } else {
                (normal_matrix.unit_normal(src.normal), 0)
            };
            // (`p` is within the coordinate limit: checked above.)
            let c = camera.clip_within(p);
            let d = plane_distances(&c, near, far);
            let mut outside = 0u8;
            for (k, dk) in d.iter().enumerate() {
                if !(*dk >= T::ZERO) {
                    outside |= 1 << k;
                }
            }
            *v = PreparedVertex {
                p,
                n,
                iw: T::ZERO,
                fp: FixedPoint::default(),
                depth: 0,
                colour: [0; 3],
                outside,
                flags: due,
            };
            if outside != 0 {
                clipped = true;
                continue;
            }
            let (fp, depth, iw) = project(camera, &c, a, b, inv_range);
            v.fp = fp;
            v.depth = depth;
            v.iw = iw;
            top = top.min(fp.y);
            bottom = bottom.max(fp.y);
        }
        self.rows_cull = None;
        self.rows = screen_rows(camera, clipped, top, bottom);
        if normals && Self::defers_normals() {
            self.normals = normal_matrix.keep();
        }
    }

    /// Whether [`PreparedMesh::transform`] leaves the normals to be computed where first
    /// needed (`NORMAL_DUE`): in fixed point, whose normalization is the costly part of a
    /// vertex's transform (Cortex-M0, `Fixed22`: about 460 cycles). In floating point the
    /// bookkeeping cost more than it saved: STM32F411 (QEMU, f32), the demo's Gouraud frame 0
    /// took 2 776 398 -> 2 784 039 instructions with the normals deferred.
    #[inline(always)]
    pub(super) fn defers_normals() -> bool {
        T::RESOLUTION > T::ZERO
    }

    /// Vertex `v`'s normal, if still due (`NORMAL_DUE`), from its mesh vertex `src` through
    /// the last transform with normals (`normals`): the transform's computation, moved to
    /// where the normal is first needed.
    #[inline(always)]
    pub(super) fn settle_normal(
        v: &mut PreparedVertex<T>,
        src: Option<&Vertex<T>>,
        normals: &T::KeptNormals,
    ) {
        if !Self::defers_normals() || v.flags & NORMAL_DUE == 0 {
            return;
        }
        v.flags &= !NORMAL_DUE;
        v.n = Self::due_normal(src, normals);
    }

    /// [`PreparedMesh::settle_normal`]'s computation, out of line: one copy for the shading
    /// loops and the drawing's fallback. (The RP2040 firmware, one core: inline in each,
    /// 230 744 bytes of flash and 7 804 515 cycles a frame, rp2040js frames 1 to 15 on
    /// average; out of line, 222 316 bytes and 7 807 899 cycles.)
    #[inline(never)]
    fn due_normal(src: Option<&Vertex<T>>, normals: &T::KeptNormals) -> Vec3<T> {
        match (src, NormalMatrix::kept(normals)) {
            (Some(src), Some(normals)) => normals.unit_normal(src.normal),
            _ => Vec3::new(T::ZERO, T::ZERO, T::ZERO),
        }
    }

    /// Computes every normal still due (for drawing per pixel, which interpolates them).
    pub(super) fn settle_normals(&mut self) {
        if !Self::defers_normals() {
            return;
        }
        let src = self.mesh.vertices();
        for (i, v) in self.verts.iter_mut().enumerate() {
            Self::settle_normal(v, src.get(i), &self.normals);
        }
    }
}
/// The snapped screen position, depth value and `1/w` of clip coordinates `c` inside the
/// guard band (`w > 0`); `q = a - b / w` (perspective) or `(z - near) inv_range`.
#[inline]
pub(super) fn project<T: Real>(
    camera: &Camera<T>,
    c: &[T; 4],
    a: T,
    b: T,
    inv_range: T,
) -> (FixedPoint, i32, T) {
    let (fp, iw, _) = camera.screen_fixed(c);
    let q = if camera.perspective {
        a - b * iw
    } else {
        (c[2] - camera.near) * inv_range
    };
    (fp, q.clamp01().to_fixed_i32(DEPTH_FRAC), iw)
}

/// The screen rows `[top, bottom)` a mesh can cover: all rows if a vertex is clipped (`clipped`),
/// else the rows whose pixel centre (`16 r + 8` sub-pixels) lies in `[top, bottom]`, the
/// vertices' extent in sub-pixels (none if `top > bottom`).
pub(super) fn screen_rows<T>(
    camera: &Camera<T>,
    clipped: bool,
    top: i32,
    bottom: i32,
) -> (i32, i32) {
    if clipped {
        (0, camera.height as i32)
    } else if top > bottom {
        (0, 0)
    } else {
        (
            (top - SUBPIXEL / 2).div_euclid(SUBPIXEL),
            (bottom - SUBPIXEL / 2).div_euclid(SUBPIXEL) + 2,
        )
    }
}
