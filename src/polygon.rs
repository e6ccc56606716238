//! Polygon lights: validation, horizon clipping, Lambertian irradiance (Snyder eq. 8;
//! Iwanicki's edge form) and the solid angle of the clipped projection (Arvo section 5.1).
//!
//! ## Lambert's formula
//!
//! For a polygon whose spherical projection seen from `p` lies above the horizon of `n`, with
//! `u_i = v_i - p`, the normalized irradiance is
//!
//! ```text
//! E = |sum_i theta_i (G_i . n)/|G_i|| / (2 pi),   G_i = u_i x u_i+1,  theta_i = angle(u_i, u_i+1)
//! ```
//!
//! (Snyder eq. 8; the absolute value makes it independent of the winding). Each edge term is
//! computed as `atan2(|G|, u_i . u_i+1) (G . n)/|G|` with `G = u_i x (v_i+1 - v_i)`: Iwanicki's
//! `Omega/sin(Omega)` form written with unnormalized vectors. It is scale-free, so no vertex
//! direction is normalized; it needs no arc cosine (which loses half its digits for short
//! edges); and `G` taken from the polygon's own edge vector keeps its accuracy when an edge is
//! seen nearly end-on. On f32 (with a floating-point unit) an edge subtending at most a right
//! angle takes the same term as `R(c) (G . n)/(|u_i| |u_i+1|)`, `c = cos(theta_i)` and
//! `R(c) = theta/sin(theta)` a degree-9 polynomial ([`Real::arc_ratio`]): no arc tangent.
//!
//! ## Clipping to the horizon
//!
//! The part of the polygon below the plane through `p` normal to `n` must not count. The ring of
//! vertices is clipped on the fly (as in Snyder's appendix H, no buffer): an edge that dives
//! below the horizon ends at its crossing point, and the clipped ring follows the horizon great
//! circle to the point where the boundary comes back up. Such a horizon arc lies on the great
//! circle normal to `n`, so its term is exactly its signed angle about `n`, computed from the
//! unnormalized crossing points (accurate even when the arc spans nearly pi, i.e. the polygon
//! is seen nearly edge-on). For a non-convex polygon the clipped ring may run along the horizon
//! back and forth; those arcs cancel. The Lambert and Phong models (with `r` in place of `n`)
//! share the clipping.
//!
//! ## Solid angle
//!
//! The solid angle of the clipped projection (needed by Phong with even exponents) is the
//! signed sum of the spherical triangles `(k, a, b)` over the clipped edges `(a, b)`, fanned
//! from the clipping direction `k` itself: every clipped point has `u.k >= 0`, so each triangle
//! is proper (Van Oosterom and Strackee's formula for polygon edges; the exact arc angle for
//! horizon arcs, whose triangle has two vertices on the equator of `k`).
//!
//! ## Accuracy
//!
//! f64 agrees with the quadrature of the definition to 1.8e-13 (measured; tested to 1e-12 in
//! `tests/common/tolerance.rs`'s `F64_BUDGET`), including points within
//! 1e-12 of the polygon's plane. In f32 the error is about `2^-24 size/dist` when `p` is within
//! `dist` of an edge or vertex of the polygon (the individual edge terms are then
//! ill-conditioned although their sum is not); the README gives the measured figures.

use crate::unit::Direction;
use crate::{Error, Real, Vec3};
use heapless::Vec;

#[cfg(any(feature = "phong", feature = "moments"))]
mod arc;
mod clip;
#[cfg(feature = "phong")]
mod dirs;
#[cfg(feature = "phong")]
pub(crate) use dirs::{Uncached, VertexDirections, VertexDirs};
mod edge;
#[cfg(feature = "phong")]
mod negligible;
mod validate;
#[cfg(feature = "phong")]
pub(crate) use arc::arc_axis_f;
#[cfg(feature = "moments")]
pub(crate) use arc::arc_axis_form;
#[cfg(any(feature = "phong", feature = "moments"))]
pub(crate) use arc::{clamp_excursion, cos_power_sums};
#[cfg(feature = "phong")]
pub(crate) use clip::for_each_clipped_edge_by;
pub(crate) use clip::{for_each_clipped_edge, for_each_unclipped_edge, ApexFan};
#[cfg(any(feature = "phong", feature = "moments"))]
pub(crate) use clip::{ClippedEdge, CROSSING};
#[cfg(feature = "phong")]
pub(crate) use edge::offset_products;
#[cfg(feature = "phong")]
pub(crate) use edge::products_in_range;
#[cfg(feature = "phong")]
pub(crate) use negligible::{
    floats_ball_below, phong_negligible_with, HEIGHTS as NEGLIGIBLE_HEIGHTS,
};
use validate::validate_polygon;
pub(crate) use validate::validate_polygon_f64;

/// A planar, simple polygon light of unit radiance with at most `N` vertices (validated once,
/// at construction). It emits from both faces.
#[derive(Clone, Debug, PartialEq)]
pub struct PolygonLight<T, const N: usize = 8> {
    verts: Vec<Vec3<T>, N>,
    normal: Vec3<T>,
    /// A ball around the polygon, `(centre, radius)`, the radius raised by about `1e-5` over
    /// the exact one for the roundings (fixed point's cheap proof of a negligible Phong term,
    /// `polygon/negligible.rs`). `None` without the `phong` feature; the world-coordinate
    /// path's copy, made per sample, carries the world light's own ball, scaled.
    ball: Option<(Vec3<T>, T)>,
}

/// Fixed point's limit for the Lambert terms, `2^-9` (`2^13` of `Fixed22`'s `2^-22`): see
/// [`near_limit`].
pub(crate) const LAMBERT_NEAR_LOG2: u32 = 9;
/// Fixed point's limits for the Phong terms: `2^-8` below `m = 128`, `2^-7` from 128 to 255 (a
/// sharper lobe magnifies a boundary's error where it lies across the boundary): see
/// [`near_limit`].
#[cfg(feature = "phong")]
#[inline(always)]
pub(crate) fn phong_near_log2(m: u32) -> u32 {
    if m < 128 {
        8
    } else {
        7
    }
}

/// `2^-log2`: how close to a polygon's boundary (a vertex, or an edge beside `p`) fixed point
/// answers, in the kernel's coordinates (the world-coordinate path scales the light seen from
/// `p` so that its largest coordinate is in `[2, 4]`); closer, the `try_` functions report
/// [`Error::Unresolved`] and the plain ones return their fallback, 0.
///
/// Fixed point rounds absolutely (`2^-22`), so an edge vector `u` from `p` has a direction
/// only to `2^-22/|u|`, and the products `G = ua x d`, `ua.ub` of a short edge likewise: the
/// error grows as `p` nears the boundary. (Where `G` is small because `p` is near an edge's
/// line, the products are formed exactly first: the sealed `cross_dot_scaled`.)
///
/// Measured (`tests/fixed_near.rs`: 40 000 points near the vertices and edges of random
/// polygons, 1e-8 to 0.3 of their size away, through world coordinates, against f64 on the
/// exact differences), the largest error of an answered point: Lambert 9.8e-5 at the limit
/// `2^-9` (2.4e-4 at `2^-10`); Phong 1.6e-4 at `2^-8` and `2^-7` (1.2e-3 at `2^-9` and
/// `2^-8`): margins of 10 and 6 under 1/1024. No point farther than 1/64 of the scene's
/// scale from the boundary is refused. The floats: 0 (no limit).
#[inline(always)]
pub(crate) fn near_limit<T: Real>(log2: u32) -> T {
    if T::RESOLUTION > T::ZERO {
        T::from_fixed_i32(1, log2)
    } else {
        T::ZERO
    }
}

/// Planarity tolerance, relative to the polygon's size (spec: 1e-6).
const PLANAR_TOL: f64 = 1e-6;

/// [`PolygonLight::in_plane`]'s tolerance for fixed point, in [`Real::RESOLUTION`]s per unit
/// of `|p - v0|_max` (the normal's rounding)...
const IN_PLANE_REL: f64 = 1.5;
/// ... and absolute (the products' truncation and the rounding of `p` and `v0`).
const IN_PLANE_ABS: f64 = 3.0;

impl<T: Real, const N: usize> PolygonLight<T, N> {
    /// A polygon light from its vertices in order (either winding).
    ///
    /// Validation runs in f64 for every backend, so a polygon is accepted or refused alike
    /// whatever the scalar type. Cost: O(k^2) for k vertices (the simplicity test), once.
    ///
    /// # Errors
    /// [`Error::TooFewVertices`], [`Error::TooManyVertices`], [`Error::NotFinite`] (`"verts"`),
    /// [`Error::OutOfRange`] (`"verts"`, beyond [`Real::COORDINATE_LIMIT`]),
    /// [`Error::ZeroArea`], [`Error::NotPlanar`], [`Error::NotSimple`] (edges that cross or
    /// touch, including repeated vertices).
    pub fn new(verts: &[Vec3<T>]) -> Result<Self, Error> {
        if verts.len() < 3 {
            return Err(Error::TooFewVertices);
        }
        if verts.len() > N {
            return Err(Error::TooManyVertices { capacity: N });
        }
        for v in verts {
            v.check_position("verts")?;
        }
        let normal = validate_polygon(verts)?;
        let mut v = Vec::new();
        for &x in verts {
            // Cannot fail: the length was checked against N above.
            let _ = v.push(x);
        }
        Ok(PolygonLight {
            // (Only the Phong terms use it: a build without them carries no f64 square root.)
            ball: if cfg!(feature = "phong") {
                Some(bounding_ball(&v))
            } else {
                None
            },
            verts: v,
            normal: Vec3::from_f64(normal),
        })
    }

    /// A polygon from parts the caller validates: no vertex yet and `normal`, for
    /// [`crate::world`]'s rescaled copy of a validated polygon (its vertices minus `p`, scaled
    /// by a power of two, pushed by [`PolygonLight::push_local`]). Built in place that way:
    /// a vertex list built apart and moved in was copied, and the light with it (about 230
    /// Cortex-M4F instructions of `memcpy` a call for a quad in f32).
    #[inline(always)]
    pub(crate) fn empty_with_normal(normal: Vec3<T>) -> Self {
        PolygonLight {
            verts: Vec::new(),
            normal,
            ball: None,
        }
    }

    /// Appends a vertex of [`PolygonLight::empty_with_normal`]'s polygon (ignored beyond the
    /// capacity, which the caller's own vertex count never exceeds).
    #[inline(always)]
    pub(crate) fn push_local(&mut self, v: Vec3<T>) {
        let _ = self.verts.push(v);
    }

    /// Sets the ball `(centre, radius)`, which must hold the polygon (the world path's scaled
    /// copy of its own ball).
    #[cfg(feature = "phong")]
    #[inline(always)]
    pub(crate) fn set_ball(&mut self, centre: Vec3<T>, radius: T) {
        self.ball = Some((centre, radius));
    }

    /// [`PolygonLight::ball`](Self): the centre and the raised radius, if known.
    #[cfg(feature = "phong")]
    #[inline(always)]
    pub(crate) fn ball(&self) -> Option<(Vec3<T>, T)> {
        self.ball
    }

    /// The vertices.
    pub fn vertices(&self) -> &[Vec3<T>] {
        &self.verts
    }

    /// The unit normal of the polygon's plane (oriented by the winding, right-handed).
    pub fn normal(&self) -> Vec3<T> {
        self.normal
    }

    /// `true` if `p` lies in the polygon's plane (to within a few ULPs), where every polygon
    /// model is 0.
    ///
    /// Floats: `|n.(p - v0)| <= 4 EPSILON |p - v0|_max` (the rounding of `p - v0` and of the
    /// normal, relative). Fixed point, whose rounding is absolute ([`Real::RESOLUTION`] `r`):
    /// `<= r (1.5 |p - v0|_max + 3)`: the normal rounded to the type moves the distance by up
    /// to `r/2 |p - v0|_1`, the three truncated products by up to `3 r` (one-sided), and `p`
    /// and `v0`, rounded from the plane, sit up to `sqrt(3)/2 r` off it each. (The relative
    /// term alone vanishes near vertex 0, where Fixed22's rounding of `p` then read as a
    /// distance from the plane.) Measured on Fixed22: in-plane points near every vertex need
    /// an absolute term above 2.5 r; points 1e-6 (4.2 r) above a polygon are still told apart
    /// up to 3.5 r; 3 is the middle.
    #[inline]
    pub(crate) fn in_plane(&self, p: Vec3<T>) -> bool {
        in_plane(&self.verts, self.normal, p)
    }

    /// For a `p` that [`PolygonLight::in_plane`] counts as in the plane: `Ok(())` where that is
    /// exact enough (the floats, whose tolerance is a few ULPs of `p` itself; and fixed point
    /// outside the polygon's face, where every model is continuous across the plane), and
    /// [`Error::Unresolved`] for fixed point over the face. There the models jump from 0 in
    /// the plane to nearly the whole face (Lambert: 1 facing it) just off it, and a point
    /// within the type's rounding of the plane (a few `2^-22`) cannot be told from either:
    /// 0 would be a silently wrong answer (measured: `polygon_lambert` 0 against f64's 0.970
    /// for a point 4.8e-7 above a star polygon's face). The test projects `p` on the plane
    /// (dropping the normal's largest component) and counts edge crossings, in f64: only on
    /// this path, never per edge.
    ///
    /// Fixed point also refuses a `p` in the plane within `r_min` ([`near_limit`]) of the
    /// polygon's boundary outside the face: there the value rises from 0 to a large part of
    /// the face within the type's rounding too (measured: 0 for f64's 0.16 at 1.2 units of
    /// `2^-22` above the plane, 220 from a vertex).
    #[inline]
    #[cfg_attr(not(any(feature = "phong", feature = "moments")), allow(dead_code))]
    pub(crate) fn resolved_in_plane(&self, p: Vec3<T>, r_min: T) -> Result<(), Error> {
        if T::RESOLUTION > T::ZERO && over_face_or_near(&self.verts, self.normal, p, r_min.to_f64())
        {
            Err(Error::Unresolved("p"))
        } else {
            Ok(())
        }
    }

    /// `[polygon_lambert]` with precise errors: see [`PolygonLight::lambert`].
    ///
    /// # Errors
    /// [`Error::NotFinite`] for `p` or `n`, [`Error::ZeroLength`] for `n`,
    /// [`Error::OutOfRange`] for `p` beyond [`Real::COORDINATE_LIMIT`] (fixed point only),
    /// [`Error::Unresolved`] for a fixed-point `p` within the type's rounding of the plane, over
    /// the face or near its edges (where the value jumps from 0 to nearly the whole face and
    /// the type cannot tell which side `p` is on; in the plane away from the polygon it is 0),
    /// and for a fixed-point `p` within `2^-9` of a vertex or of an edge beside it (see
    /// `near_limit` in this module: the directions are not known to 1/1024 there).
    pub fn try_lambert(&self, p: Vec3<T>, n: impl Direction<T>) -> Result<T, Error> {
        p.check_position("p")?;
        self.lambert_at(p, n, self.in_plane(p))
    }

    /// [`PolygonLight::try_lambert`] for a `p` within the coordinate limit whose
    /// [`PolygonLight::in_plane`] test is `plane` (computed once for both terms by the
    /// polygon's [`Illuminant::diffuse_and_phong`](crate::Illuminant::diffuse_and_phong)).
    #[inline]
    pub(crate) fn lambert_at(
        &self,
        p: Vec3<T>,
        n: impl Direction<T>,
        plane: bool,
    ) -> Result<T, Error> {
        let n = n.try_unit("n")?.into_inner();
        if T::RESOLUTION > T::ZERO {
            return lambert_fixed(&self.verts, self.normal, p, n, plane);
        }
        if plane {
            return Ok(T::ZERO);
        }
        // A ring wholly above the horizon, every edge within a right angle (f32: the arc
        // ratio's form): the walk's sum without its clipping state.
        if let Some(sum) = edge::unclipped_ratio_sum(&self.verts, p, n) {
            return Ok((sum.abs() * T::FRAC_1_TAU).clamp01());
        }
        let mut sum = T::ZERO;
        for_each_clipped_edge(
            &self.verts,
            p,
            n,
            T::ZERO,
            #[inline(always)]
            |e| sum += e.lambert_term(n),
        );
        Ok((sum.abs() * T::FRAC_1_TAU).clamp01())
    }

    /// `[polygon_lambert]`: exact Lambertian irradiance (normalized, in [0, 1]) at `p` with
    /// normal `n`, the polygon clipped to the horizon of `n`.
    ///
    /// Accuracy: measured, below. Cost per edge above the horizon: 2 cross products,
    /// 2 dot products, 1 sqrt, 1 atan2, 1 division (no per-vertex normalization); on f32 with
    /// an FPU, an edge within a right angle 1 cross product, 4 dot products, 1 sqrt,
    /// 1 division and a degree-9 polynomial instead ([`Real::arc_ratio`]); per horizon
    /// crossing: a few multiply-adds. A ring wholly above the horizon takes its edge terms
    /// without the clipping walk (`polygon::for_each_unclipped_edge`; on f32 where every edge
    /// is within a right angle, `polygon::edge::unclipped_ratio_sum`), the same bits; on
    /// `Fixed22` each of its edges within a right angle takes the arc ratio from its ends' unit
    /// directions instead (each vertex normalized once; per edge 2 dot products, 1 cross
    /// product, a table's cubic piece: `polygon::edge::unit_ratio_term`), all in 16-bit form
    /// (directions in Q15, normalized so) so that each product is one 32-bit product.
    /// Measured on a quad (QEMU, median of the budget's 16 inputs): 497 Cortex-M4F
    /// instructions in f32 (at d38eaa0 495: 220 unlit, 495 wholly lit, 744 to 910 clipped; 545 before the
    /// plane test's maximum went off the hot path, each squared length's range was tested
    /// once and `abs` became `VABS.F32`; with the walk alone 224, 703 and 756 to 914; 692 before the plane test moved ahead of the normal's
    /// normalization to be shared with the Phong term, 920 with the arc tangent), 1 938
    /// Cortex-M0 instructions in `Fixed22` (950 unlit, 1 938 wholly lit, 4 238 to 5 941
    /// clipped; 964, 1 987 and 4 273 to 5 957 before the rescalings' exponents came from
    /// comparisons in the common band, `normalize::top_exponent` and `top_bit`; 995, 2 018 and 4 304 to 5 988 before the normal's normalization took three
    /// 32-bit products a product, not four, the crate-internal `mul_le2`; 1 015, 2 038 and 4 324 to 6 008 before the positions' range test went to
    /// one unsigned comparison a coordinate, the sealed `within_coordinate_limit`; 1 049, 2 182 and 4 355 to 6 045 before the horizon test's sign came from
    /// 16-bit products, the sealed `height_nonneg`; with the directions normalized in Q22 and
    /// rounded to Q15 and the ratio in Q22
    /// products, 1 052, 3 265 and 4 366 to 6 052; with the edge terms' directions in Q22,
    /// 1 016, 3 832 and 4 326 to 6 012;
    /// 3 886 with the normalization not inlined, before its directions could be
    /// shared with the Phong term, `polygon::VertexDirs`; with the arc-tangent form for every edge 1 114, 4 646 and 4 562 to 6 257, with
    /// the walk alone 1 046, 4 929 and 4 540 to 6 230; 5 073 with the edge
    /// term's last two products saturating, 6 325 with the offsets' products saturating too:
    /// `polygon::edge::offset_products`).
    /// Fallback: 0 for a zero or non-finite input, and 0 when `p` is in the
    /// polygon's plane (fixed point: 0 too where [`PolygonLight::try_lambert`] reports
    /// [`Error::Unresolved`], over the face or near the boundary).
    ///
    /// <!-- BEGIN acc-polygon_lambert: target/accuracy/model-polygon_lambert.md -->
    /// Measured: f64 within 2.1e-14 of its reference (the independent quadrature, adversarial);
    /// against f64, f32 5.4e-7 (ill-conditioned: 2.9e-6; near boundary: 4.4e-4), Fast32 5.3e-6
    /// (ill-conditioned: 2.9e-6; near boundary: 4.4e-4), Fixed22 6.5e-5; 57 939 cases in all
    /// (`docs/accuracy.md`).
    /// <!-- END acc-polygon_lambert -->
    #[inline]
    pub fn lambert(&self, p: Vec3<T>, n: impl Direction<T>) -> T {
        self.try_lambert(p, n).unwrap_or(T::ZERO)
    }

    /// The solid angle (steradians, in [0, 2 pi]) of the polygon's projection seen from `p`,
    /// clipped to the hemisphere `u.k >= 0` (`k` any length). 0 when `p` is in the plane, not
    /// finite or (fixed point) beyond [`Real::COORDINATE_LIMIT`], or `k` is zero. Cost per clipped edge: 2 normalizations, 1 cross product, 4 dot products,
    /// 1 atan2.
    pub fn clipped_solid_angle(&self, p: Vec3<T>, k: Vec3<T>) -> T {
        let Some(k) = k.normalize() else {
            return T::ZERO;
        };
        if p.check_position("p").is_err() || self.in_plane(p) {
            return T::ZERO;
        }
        let mut acc = ApexFan::new(k);
        for_each_clipped_edge(&self.verts, p, k, T::ZERO, |e| acc.add(&e));
        acc.total().abs().min(T::TAU)
    }
}

/// A ball that holds every point of the polygon `verts` (in f64, once): the centre is the mean
/// of the vertices rounded to `T`, the radius the largest distance from that rounded centre
/// to a vertex, raised by `1e-6` of itself and `1e-5` (far above the rounding of the f64
/// arithmetic and of the conversion to `T`, which rounds to nearest: `2^-23` for `Fixed22`).
/// A polygon lies in the convex hull of its vertices, hence in any ball that holds them.
#[cold]
fn bounding_ball<T: Real>(verts: &[Vec3<T>]) -> (Vec3<T>, T) {
    let n = verts.len().max(1) as f64;
    let mut c = [0.0f64; 3];
    for v in verts {
        c[0] += v.x.to_f64();
        c[1] += v.y.to_f64();
        c[2] += v.z.to_f64();
    }
    let centre = Vec3::<T>::from_f64([c[0] / n, c[1] / n, c[2] / n]);
    let c = [centre.x.to_f64(), centre.y.to_f64(), centre.z.to_f64()];
    let mut r2 = 0.0f64;
    for v in verts {
        let d = [
            v.x.to_f64() - c[0],
            v.y.to_f64() - c[1],
            v.z.to_f64() - c[2],
        ];
        r2 = r2.max(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    }
    let r = libm::sqrt(r2);
    (centre, T::from_f64(r * (1.0 + 1e-6) + 1e-5))
}

/// `true` if `p` projected on the plane of the polygon `verts` (unit normal `normal`) falls
/// inside it (crossing number; on an edge either way), or within `near` of its boundary: the
/// cold path of [`PolygonLight::resolved_in_plane`], in f64, on the plane of the two axes
/// other than the normal's largest component (where distances shrink by at most `sqrt(3)`:
/// the test errs towards refusing). Over a slice, so one copy serves every capacity `N`.
#[cold]
#[inline(never)]
fn over_face_or_near<T: Real>(verts: &[Vec3<T>], normal: Vec3<T>, p: Vec3<T>, near: f64) -> bool {
    let nrm = normal.to_f64().map(f64::abs);
    // Keep the two axes other than the normal's largest component.
    let (i, j) = if nrm[0] >= nrm[1] && nrm[0] >= nrm[2] {
        (1, 2)
    } else if nrm[1] >= nrm[2] {
        (2, 0)
    } else {
        (0, 1)
    };
    let q = p.to_f64();
    let (px, py) = (q[i], q[j]);
    let mut inside = false;
    // Each edge (va, vb), the last closing the ring (no indexing: nothing to check).
    let next = verts.iter().skip(1).chain(verts.first());
    for (va, vb) in verts.iter().zip(next) {
        let (va, vb) = (va.to_f64(), vb.to_f64());
        let ((ax, ay), (bx, by)) = ((va[i], va[j]), (vb[i], vb[j]));
        // The distance to the edge segment.
        let (ex, ey, wx, wy) = (bx - ax, by - ay, px - ax, py - ay);
        let ee = ex * ex + ey * ey;
        let t = if ee > 0.0 {
            ((wx * ex + wy * ey) / ee).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (dx, dy) = (wx - t * ex, wy - t * ey);
        if dx * dx + dy * dy < near * near {
            return true;
        }
        if (ay > py) != (by > py) {
            let x = ax + (py - ay) / (by - ay) * (bx - ax);
            if px < x {
                inside = !inside;
            }
        }
    }
    inside
}

/// [`PolygonLight::in_plane`] on the polygon's vertices and unit normal.
#[inline]
fn in_plane<T: Real>(verts: &[Vec3<T>], normal: Vec3<T>, p: Vec3<T>) -> bool {
    // (A polygon has at least 3 vertices: `first` only spares the bounds check.)
    let Some(&v0) = verts.first() else {
        return true;
    };
    let d = p - v0;
    // A unit normal and an offset of at most 8 (fixed point: `p` and the vertices within the
    // coordinate limit, which every caller checks): the bits of `Vec3::dot`.
    let dist = T::dot3_small([normal.x, normal.y, normal.z], [d.x, d.y, d.z]);
    let tol = if T::RESOLUTION > T::ZERO {
        // `RESOLUTION (1.5 |d|_max + 3)` in the raw units of `2^-22` (`Fixed22`'s, whose
        // products are exact floors, its sums and absolute values saturating):
        // `floor(1.5 m) = m + floor(m/2)` for `m >= 0`, and the product by the resolution
        // `floor(B / 2^22)`: the same bits as the type's own `*`, `+` and `max_abs`, without
        // two full products and the NaN-aware maxima (the test 156 -> 140 Cortex-M0
        // instructions, traced; `polygon_lambert` and `phong_polygon` take it).
        const _: () = assert!(IN_PLANE_REL == 1.5 && IN_PLANE_ABS == 3.0);
        let raw = |c: T| c.to_fixed_i32(22).saturating_abs();
        let m = raw(d.x).max(raw(d.y)).max(raw(d.z));
        let b = m.saturating_add(m >> 1).saturating_add(3 << 22);
        T::from_fixed_i32(b >> 22, 22)
    } else {
        // The floats: beyond `4 EPSILON |d|_1` (at least the tolerance's `|d|_max`), `p` is
        // off the plane without the NaN-aware maximum (the answer for every `p` not within a
        // few ULPs of the plane; the same answer as the test below, which decides the rest).
        let sum = d.x.abs() + d.y.abs() + d.z.abs();
        if dist.abs() > T::from_f64(4.0) * T::EPSILON * sum {
            return false;
        }
        T::from_f64(4.0) * T::EPSILON * d.max_abs()
    };
    !(dist.abs() > tol)
}

/// [`PolygonLight::try_lambert`] for fixed point (`verts` and the unit `normal` of a validated
/// polygon), after the checks of `p` and `n` (unit): with the tests of [`near_limit`] (a `p`
/// too close to the boundary is [`Error::Unresolved`]). One copy for every kind of normal: out of line on soft-float
/// targets, where the copies inlined into each caller cost about 3 KiB of flash apiece
/// (the Cortex-M0 budget image), for a call's few instructions; and one copy for every
/// capacity `N` (the polygon as a slice), for the same reason.
#[cfg_attr(target_abi = "eabihf", inline)]
#[cfg_attr(not(target_abi = "eabihf"), inline(never))]
fn lambert_fixed<T: Real>(
    verts: &[Vec3<T>],
    normal: Vec3<T>,
    p: Vec3<T>,
    n: Vec3<T>,
    plane: bool,
) -> Result<T, Error> {
    let r_min = near_limit::<T>(LAMBERT_NEAR_LOG2);
    if plane {
        if over_face_or_near(verts, normal, p, r_min.to_f64()) {
            return Err(Error::Unresolved("p"));
        }
        return Ok(T::ZERO);
    }
    // A ring wholly above the horizon: the walk's terms and tests, without its clipping state
    // (`for_each_unclipped_edge`; every vertex's distance tested once, as the walk does).
    // Each edge within a right angle by the arc ratio from its endpoints' unit directions
    // (`edge::unit_ratio_term`), each direction normalized once in 16-bit form
    // (`unit3_q15`): the first vertex's at the first edge, kept for the closing one; the
    // others by the arc-tangent form.
    let (mut sum, mut beside, mut near) = (T::ZERO, false, false);
    let kv = edge::unit_q15([n.x, n.y, n.z]);
    let (mut first, mut a_dir, mut edges_left) = (None, None, verts.len());
    let whole = for_each_unclipped_edge(
        verts,
        p,
        n,
        #[inline(always)]
        |ua, ub, d| {
            near |= T::all_within([ub.x, ub.y, ub.z], r_min);
            if edges_left == verts.len() {
                first = T::unit3_q15([ua.x, ua.y, ua.z]);
                a_dir = first;
            }
            edges_left = edges_left.saturating_sub(1);
            // (`ub` is vertex `len - edges_left`, or vertex 0 for the closing edge.)
            let b_dir = if edges_left == 0 {
                first
            } else {
                T::unit3_q15([ub.x, ub.y, ub.z])
            };
            let ratio = a_dir
                .zip(b_dir)
                .and_then(|(a, b)| edge::unit_ratio_term(a, b, kv));
            let (term, too_near) = match ratio {
                Some(term) => (term, false),
                None => edge::edge_atan_term_fixed(ua, ub, d, n, r_min),
            };
            sum += term;
            beside |= too_near;
            a_dir = b_dir;
            true
        },
    );
    if !whole {
        (sum, beside) = (T::ZERO, false);
        near = for_each_clipped_edge(
            verts,
            p,
            n,
            r_min,
            #[inline(always)]
            |e| {
                let (term, too_near) = e.lambert_term_resolved(n, r_min);
                sum += term;
                beside |= too_near;
            },
        );
    }
    if near || beside {
        return Err(Error::Unresolved("p"));
    }
    Ok((sum.abs() * T::FRAC_1_TAU).clamp01())
}
