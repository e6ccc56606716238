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
//! `tests/common/mod.rs`'s `F64_BUDGET`), including points within
//! 1e-12 of the polygon's plane. In f32 the error is about `2^-24 size/dist` when `p` is within
//! `dist` of an edge or vertex of the polygon (the individual edge terms are then
//! ill-conditioned although their sum is not); the README gives the measured figures.

use crate::unit::Direction;
use crate::{Error, Real, Vec3};
use heapless::Vec;

#[cfg(any(feature = "phong", feature = "moments"))]
mod arc;
#[cfg(any(feature = "phong", feature = "moments"))]
pub(crate) use arc::{arc_axis_form, cos_power_sums};

/// A planar, simple polygon light of unit radiance with at most `N` vertices (validated once,
/// at construction). It emits from both faces.
#[derive(Clone, Debug, PartialEq)]
pub struct PolygonLight<T, const N: usize = 8> {
    verts: Vec<Vec3<T>, N>,
    normal: Vec3<T>,
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
            verts: v,
            normal: Vec3::from_f64(normal),
        })
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
        // (A polygon has at least 3 vertices: `first` only spares the bounds check.)
        let Some(&v0) = self.verts.first() else {
            return true;
        };
        let d = p - v0;
        let dist = self.normal.dot(d);
        let tol = if T::RESOLUTION > T::ZERO {
            T::RESOLUTION * (T::from_f64(IN_PLANE_REL) * d.max_abs() + T::from_f64(IN_PLANE_ABS))
        } else {
            T::from_f64(4.0) * T::EPSILON * d.max_abs()
        };
        !(dist.abs() > tol)
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
    #[inline]
    pub(crate) fn resolved_in_plane(&self, p: Vec3<T>) -> Result<(), Error> {
        if T::RESOLUTION > T::ZERO && self.over_face(p) {
            Err(Error::Unresolved("p"))
        } else {
            Ok(())
        }
    }

    /// `true` if `p` projected on the polygon's plane falls inside the polygon (crossing
    /// number; on an edge either way).
    #[cold]
    #[inline(never)]
    fn over_face(&self, p: Vec3<T>) -> bool {
        let nrm = self.normal.to_f64().map(f64::abs);
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
        let next = self.verts.iter().skip(1).chain(self.verts.first());
        for (va, vb) in self.verts.iter().zip(next) {
            let (va, vb) = (va.to_f64(), vb.to_f64());
            let ((ax, ay), (bx, by)) = ((va[i], va[j]), (vb[i], vb[j]));
            if (ay > py) != (by > py) {
                let x = ax + (py - ay) / (by - ay) * (bx - ax);
                if px < x {
                    inside = !inside;
                }
            }
        }
        inside
    }

    /// `[polygon_lambert]` with precise errors: see [`PolygonLight::lambert`].
    ///
    /// # Errors
    /// [`Error::NotFinite`] for `p` or `n`, [`Error::ZeroLength`] for `n`,
    /// [`Error::OutOfRange`] for `p` beyond [`Real::COORDINATE_LIMIT`] (fixed point only),
    /// [`Error::Unresolved`] for a fixed-point `p` within the type's rounding of the plane, over
    /// the face ([`PolygonLight::resolved_in_plane`]).
    pub fn try_lambert(&self, p: Vec3<T>, n: impl Direction<T>) -> Result<T, Error> {
        p.check_position("p")?;
        let n = n.try_unit("n")?.into_inner();
        if self.in_plane(p) {
            self.resolved_in_plane(p)?;
            return Ok(T::ZERO);
        }
        let mut sum = T::ZERO;
        for_each_clipped_edge(
            &self.verts,
            p,
            n,
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
    /// crossing: a few multiply-adds. Measured on a quad (QEMU, median): 696 Cortex-M4F
    /// instructions in f32 (920 with the arc tangent), 7612 Cortex-M0 instructions in
    /// `Fixed22`. Fallback: 0 for a zero or non-finite input, and 0 when `p` is in the
    /// polygon's plane (fixed point over the face: 0 too, where [`PolygonLight::try_lambert`]
    /// reports [`Error::Unresolved`]).
    ///
    /// <!-- BEGIN acc-polygon_lambert: target/accuracy/model-polygon_lambert.md -->
    /// Measured: f64 within 2.1e-14 of its reference (the independent quadrature, adversarial);
    /// against f64, f32 5.4e-7 (ill-conditioned: 2.9e-6; near boundary: 4.4e-4), Fast32 1.3e-5
    /// (ill-conditioned: 5.0e-6; near boundary: 4.4e-4), Fixed22 1.8e-4; 57 939 cases in all
    /// (`docs/accuracy.md`).
    /// <!-- END acc-polygon_lambert -->
    #[inline]
    pub fn lambert(&self, p: Vec3<T>, n: impl Direction<T>) -> T {
        self.try_lambert(p, n).unwrap_or(T::ZERO)
    }

    /// The solid angle (steradians, in [0, 2 pi]) of the polygon's projection seen from `p`,
    /// clipped to the hemisphere `u.k >= 0` (`k` any length). 0 when `p` is in the plane or `k`
    /// is zero. Cost per clipped edge: 2 normalizations, 1 cross product, 4 dot products,
    /// 1 atan2.
    pub fn clipped_solid_angle(&self, p: Vec3<T>, k: Vec3<T>) -> T {
        let Some(k) = k.normalize() else {
            return T::ZERO;
        };
        if !p.is_finite() || self.in_plane(p) {
            return T::ZERO;
        }
        let mut acc = ApexFan::new(k);
        for_each_clipped_edge(&self.verts, p, k, |e| acc.add(&e));
        acc.total().abs().min(T::TAU)
    }
}

/// One edge of the clipped ring seen from `p`: from `ua` to `ub` (points relative to `p`, not
/// normalized), `d = ub - ua` computed from the polygon's own edge vector (no cancellation
/// through `p`), and whether it is an arc of the horizon.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ClippedEdge<T> {
    pub(crate) ua: Vec3<T>,
    pub(crate) ub: Vec3<T>,
    pub(crate) d: Vec3<T>,
    pub(crate) horizon: bool,
}

impl<T: Real> ClippedEdge<T> {
    /// The signed angle of a horizon arc about `k`, in (-pi, pi]: the projection of the
    /// straight segment `ua -> ub` in the horizon plane, positive when it runs
    /// counter-clockwise about `k`. (For a non-convex polygon the clipped ring may run along the
    /// horizon in both directions; the arcs then cancel, so each keeps its own sign.) The sign
    /// comes from the unnormalized `ua x ub`, which keeps its relative accuracy when the arc
    /// nearly spans pi (the polygon seen nearly edge-on), where the cross product of
    /// normalized directions is mostly rounding.
    /// An arc whose products leave the normal range ([`products_in_range`]) is first scaled
    /// by a power of two (cold path).
    #[inline]
    pub(crate) fn horizon_angle(&self, k: Vec3<T>) -> T {
        let mut y = self.ua.cross(self.d).dot(k);
        let mut x = self.ua.dot(self.ub);
        let m = y.abs().max(x.abs());
        if !products_in_range(m, m) {
            let Some((g, dot)) = rescaled_products(self.ua, self.ub, self.d) else {
                return T::ZERO;
            };
            (y, x) = (g.dot(k), dot);
        }
        y.atan2(x)
    }

    /// The edge's term of Lambert's formula about the unit normal `n`: the horizon arc's
    /// signed angle, or [`edge_angle_term`]. (Inlined into the caller's walk.)
    #[inline(always)]
    pub(crate) fn lambert_term(&self, n: Vec3<T>) -> T {
        if self.horizon {
            self.horizon_angle(n)
        } else {
            edge_angle_term(self.ua, self.ub, self.d, n)
        }
    }

    /// The same edge scaled by a power of two that brings its largest coordinate into [1, 2)
    /// ([`scaled_to_unit`]); `None` for fixed point and an edge with no finite non-zero
    /// coordinate. Every term of an edge is scale-free, so this is the cold path of the edge
    /// terms whose products would leave the normal range.
    #[inline]
    pub(crate) fn rescaled(&self) -> Option<Self> {
        let [ua, ub, d] = scaled_to_unit([self.ua, self.ub, self.d])?;
        Some(ClippedEdge {
            ua,
            ub,
            d,
            horizon: self.horizon,
        })
    }
}

/// `theta (G . k)/|G|` with `G = ua x d (= ua x ub)` and `theta` the angle between `ua` and
/// `ub`: the edge term of Lambert's formula from unnormalized endpoints. Scale-free, and `G`
/// from the edge vector `d` keeps its accuracy for edges seen nearly end-on.
///
/// On a backend with an arc ratio (f32), an edge within a right angle takes
/// [`edge_ratio_term`], inlined into the caller's loop (no arc tangent, and the edge's
/// vectors stay in registers); every other edge, and every edge on the other backends, takes
/// [`edge_atan_term`] (out of line).
#[inline(always)]
pub(crate) fn edge_angle_term<T: Real>(ua: Vec3<T>, ub: Vec3<T>, d: Vec3<T>, k: Vec3<T>) -> T {
    if T::RESOLUTION == T::ZERO {
        if let Some(term) = edge_ratio_term(ua, ub, ua.cross(d), ua.dot(ub), k) {
            return term;
        }
    }
    edge_atan_term(ua, ub, d, k)
}

/// [`edge_angle_term`] with `theta = atan2(|G|, ua.ub)`: no per-vertex normalization is
/// needed (the form is scale-free).
///
/// Where `G` or `ua.ub` would leave the range in which products are normal and finite
/// ([`products_in_range`]: coordinates beyond about `1/TINY` or below `TINY` in absolute terms,
/// e.g. f32 configurations scaled by `2^64` or `2^-70`) the edge is first scaled by a power of
/// two ([`ClippedEdge::rescaled`], exact), on a cold path: the test costs two comparisons.
#[inline]
fn edge_atan_term<T: Real>(ua: Vec3<T>, ub: Vec3<T>, d: Vec3<T>, k: Vec3<T>) -> T {
    let g = ua.cross(d);
    let dot = ua.dot(ub);
    if T::RESOLUTION > T::ZERO {
        // Fixed point (decided at compile time): one exponent, no range to leave; `G` is scaled
        // by its largest component before it is squared.
        return edge_angle_finish(g, g.max_abs(), dot, k);
    }
    // Floats: where `|G|^2` is a normal, finite number (and `ua.ub` in range), `|G|` and
    // `1/|G|` come from it directly, with no scaling (the hot path: every edge of a scene at
    // any ordinary scale); elsewhere the edge is scaled by a power of two first (cold).
    let gg = g.dot(g);
    let lo = T::TINY * T::TINY;
    let hi = T::ONE / lo;
    if gg >= lo && gg <= hi && dot.abs() <= hi {
        let (s, inv) = gg.sqrt_rsqrt();
        return (s.atan2(dot) * g.dot(k) * inv).finite_or_zero();
    }
    edge_angle_term_rescaled(ua, ub, d, k)
}

/// The hot path of [`edge_angle_term`] for a backend with a cheap [`Real::arc_ratio`] (f32):
/// with `r = 1/(|ua| |ub|)` and `c = (ua.ub) r = cos(theta)`, the term `theta (G.k)/|G|` is
/// `R(c) (G.k) r` (`|G| = |ua| |ub| sin(theta)`, `R = theta/sin(theta)`): one reciprocal
/// square root and a short polynomial in place of `|G|`, its reciprocal and an arc tangent.
/// `None` (the caller takes the arc-tangent form) for an edge subtending more than a right
/// angle (`c < 0`, towards `R`'s singularity at `theta = pi`), for squared lengths outside
/// `[TINY, 1/TINY]` (then `|ua|^2 |ub|^2` might leave the normal range) and for a backend
/// without an arc ratio (decided at compile time).
#[inline(always)]
fn edge_ratio_term<T: Real>(ua: Vec3<T>, ub: Vec3<T>, g: Vec3<T>, dot: T, k: Vec3<T>) -> Option<T> {
    T::ONE.arc_ratio()?;
    let (la2, lb2) = (ua.dot(ua), ub.dot(ub));
    let (lo, hi) = (T::TINY, T::ONE / T::TINY);
    if !(la2 >= lo && la2 <= hi && lb2 >= lo && lb2 <= hi) {
        return None;
    }
    let r = (la2 * lb2).rsqrt();
    let c = dot * r;
    if !(c >= T::ZERO) {
        return None;
    }
    Some(c.arc_ratio()? * g.dot(k) * r)
}

/// [`edge_angle_term`] for an edge whose products leave the normal range: the same term from
/// the edge scaled by a power of two (0 if it has no finite, non-zero coordinate).
#[cold]
#[inline(never)]
fn edge_angle_term_rescaled<T: Real>(ua: Vec3<T>, ub: Vec3<T>, d: Vec3<T>, k: Vec3<T>) -> T {
    match rescaled_products(ua, ub, d) {
        Some((g, dot)) => edge_angle_finish(g, g.max_abs(), dot, k),
        None => T::ZERO,
    }
}

/// `atan2(|G|, dot) (G . k)/|G|` from `G`, its largest component `m` and `dot = ua.ub`.
#[inline(always)]
fn edge_angle_finish<T: Real>(g: Vec3<T>, m: T, dot: T, k: Vec3<T>) -> T {
    if !(m > T::ZERO) || !m.is_finite() {
        return T::ZERO;
    }
    // Scale to avoid overflow of |G|^2 for large coordinates.
    let (g, d) = g.rescale(m);
    // |G| and 1/|G| together (fixed point: one rsqrt, no division).
    let (s, inv) = g.dot(g).sqrt_rsqrt();
    let theta = (s * d).atan2(dot);
    (theta * g.dot(k) * inv).finite_or_zero()
}

/// `(ua x d, ua.ub)` from the edge scaled by a power of two ([`scaled_to_unit`]): the cold
/// path of the edge terms whose products leave the normal range. `None` where
/// [`scaled_to_unit`] has no scale.
#[inline(always)]
pub(crate) fn rescaled_products<T: Real>(
    ua: Vec3<T>,
    ub: Vec3<T>,
    d: Vec3<T>,
) -> Option<(Vec3<T>, T)> {
    if T::RESOLUTION > T::ZERO {
        return None;
    }
    rescaled_products_float(ua, ub, d)
}

#[cold]
#[inline(never)]
fn rescaled_products_float<T: Real>(ua: Vec3<T>, ub: Vec3<T>, d: Vec3<T>) -> Option<(Vec3<T>, T)> {
    let [ua, ub, d] = scaled_to_unit_float([ua, ub, d])?;
    Some((ua.cross(d), ua.dot(ub)))
}

/// `true` if products of an edge's coordinates are safe: `m` (the largest component of a
/// product such as `G = ua x d`) in `[TINY^2, 1/TINY^2]` and `big` (another product's
/// magnitude, e.g. `|ua.ub|`) at most `1/TINY^2`. Then every product that matters is a normal
/// float (its rounding relative, as at unit scale) and no square of them overflows, so the
/// result is the unit-scale result to the last bit or so. Always `true` for fixed point
/// (one exponent: there is no range to leave, and no rescaling to do).
#[inline(always)]
pub(crate) fn products_in_range<T: Real>(m: T, big: T) -> bool {
    if T::RESOLUTION > T::ZERO {
        return true;
    }
    let lo = T::TINY * T::TINY;
    let hi = T::ONE / lo;
    m >= lo && m <= hi && big <= hi
}

/// `vs` scaled by one power of two, `2^-e` with `2^e <= m < 2^(e+1)` for `m` their largest
/// component, so that `m` lands in [1, 2): exact (only exponents change), so a configuration
/// and its scaled copies give the same bits. The cold path of the polygon terms (the terms are
/// scale-free). `None` if `m` is 0 or not finite, and for fixed point (see
/// [`products_in_range`]). Cost: a conversion to f64 and back, 6 products per vector.
#[inline(always)]
pub(crate) fn scaled_to_unit<T: Real, const K: usize>(vs: [Vec3<T>; K]) -> Option<[Vec3<T>; K]> {
    // Decided at compile time: no cold path at all in the fixed-point kernels.
    if T::RESOLUTION > T::ZERO {
        return None;
    }
    scaled_to_unit_float(vs)
}

#[cold]
#[inline(never)]
fn scaled_to_unit_float<T: Real, const K: usize>(vs: [Vec3<T>; K]) -> Option<[Vec3<T>; K]> {
    let m = vs
        .iter()
        .fold(T::ZERO, |acc, v| acc.max(v.max_abs()))
        .to_f64();
    if !(m > 0.0) || !m.is_finite() {
        return None;
    }
    // Two factors, each representable in T (f32: 2^-e reaches 2^149).
    let e = libm::ilogb(m);
    let e1 = -e / 2;
    let f1 = T::from_f64(libm::ldexp(1.0, e1));
    let f2 = T::from_f64(libm::ldexp(1.0, -e - e1));
    Some(vs.map(|v| v * f1 * f2))
}

/// An edge's endpoint directions and lengths and `ua x d`, for [`ApexFan::add`].
type FanEnds<T> = (Vec3<T>, T, Vec3<T>, T, Vec3<T>);

/// The signed solid angle of a ring clipped to the hemisphere `u.k >= 0`, as a fan of spherical
/// triangles `(k, a, b)` with apex `k`, one per clipped edge `(a, b)` (Arvo 5.1 sums the same
/// signed areas). Every clipped point has `u.k >= 0`, so every fan triangle is proper and the
/// back-and-forth bridges of a non-convex clip cancel exactly. A polygon edge's triangle comes
/// from Van Oosterom and Strackee's `tan(W/2) = k.(a x b)/(1 + a.b + k.a + k.b)`; a horizon
/// arc's triangle has two vertices on the equator of `k`, so its area is exactly the arc's
/// signed angle ([`ClippedEdge::horizon_angle`]): that is the case (a polygon seen nearly
/// edge-on, the arc spanning nearly pi) where the general formula would divide tiny by tiny.
pub(crate) struct ApexFan<T> {
    apex: Vec3<T>,
    sum: T,
}

impl<T: Real> ApexFan<T> {
    pub(crate) fn new(apex: Vec3<T>) -> Self {
        ApexFan { apex, sum: T::ZERO }
    }

    /// Adds the triangle (apex, ua, ub) of the clipped edge `e`.
    ///
    /// An edge whose products leave the normal range ([`products_in_range`]: lengths below
    /// `TINY` or beyond `1/TINY`) is first scaled by a power of two (cold path).
    #[inline]
    pub(crate) fn add(&mut self, e: &ClippedEdge<T>) {
        let k = self.apex;
        if e.horizon {
            self.sum += e.horizon_angle(k);
            return;
        }
        let ends = |e: &ClippedEdge<T>| -> Option<FanEnds<T>> {
            let (a, la) = e.ua.normalize_with_length()?;
            let (b, lb) = e.ub.normalize_with_length()?;
            let l = la.max(lb);
            products_in_range(la * lb, l * l).then_some((a, la, b, lb, e.ua.cross(e.d)))
        };
        let rescaled = || {
            if T::RESOLUTION > T::ZERO {
                None // fixed point: nothing to rescale (decided at compile time)
            } else {
                Self::rescaled_ends(e)
            }
        };
        let Some((a, la, b, lb, g)) = ends(e).or_else(rescaled) else {
            return;
        };
        let num = k.dot(g) / (la * lb);
        let den = T::ONE + a.dot(b) + k.dot(a) + k.dot(b);
        self.sum += T::TWO * num.atan2(den);
    }

    /// The fan triangle's inputs from the edge scaled by a power of two (cold path; see
    /// [`ClippedEdge::rescaled`]).
    #[cold]
    #[inline(never)]
    fn rescaled_ends(e: &ClippedEdge<T>) -> Option<FanEnds<T>> {
        let s = e.rescaled()?;
        let (a, la) = s.ua.normalize_with_length()?;
        let (b, lb) = s.ub.normalize_with_length()?;
        Some((a, la, b, lb, s.ua.cross(s.d)))
    }

    /// The signed solid angle (positive for a ring counter-clockwise seen from outside, the
    /// convention of the boundary integrals).
    pub(crate) fn total(&self) -> T {
        self.sum
    }
}

/// Walks the ring `verts` seen from `p`, clipped to the half-space `(v - p).k >= 0`, and calls
/// `f` with each clipped edge in ring order (see [`ClippedEdge`]); horizon arcs run between a
/// crossing down and the next crossing up. Returns `false` if no vertex is above the horizon
/// (nothing is called). No buffer and no normalization. A vertex exactly on the horizon counts
/// as above.
pub(crate) fn for_each_clipped_edge<T: Real, F>(
    verts: &[Vec3<T>],
    p: Vec3<T>,
    k: Vec3<T>,
    mut f: F,
) -> bool
where
    F: FnMut(ClippedEdge<T>),
{
    let nv = verts.len();
    let Some(start) = verts.iter().position(|&v| (v - p).dot(k) >= T::ZERO) else {
        return false;
    };
    // The ring from `start` round to `start` again: `v0` the edge's first vertex, `v1` its
    // second, the index stepped with a wrap (no division: a library call on the M0; `get`, so
    // no bounds check can panic).
    let Some(&first) = verts.get(start) else {
        return false;
    };
    let (mut v0, mut i1) = (first, start);
    let mut u0 = v0 - p;
    let mut d0 = u0.dot(k);
    // The start of the current clipped edge (a vertex or a crossing up).
    let mut a0 = u0;
    let mut below0 = false;
    let mut exit: Option<Vec3<T>> = None;
    for _ in 0..nv {
        i1 = if i1 + 1 == nv { 0 } else { i1 + 1 };
        let Some(&v1) = verts.get(i1) else {
            break;
        };
        let u1 = v1 - p;
        let d1 = u1.dot(k);
        let below1 = d1 < T::ZERO;
        let edge = v1 - v0;
        v0 = v1;
        match (below0, below1) {
            (false, false) => {
                // Here a0 is the vertex u0, so d is the polygon's own edge.
                f(ClippedEdge {
                    ua: a0,
                    ub: u1,
                    d: edge,
                    horizon: false,
                });
                a0 = u1;
            }
            (false, true) => {
                let t = (d0 / (d0 - d1)).clamp01();
                let x = u0 + edge * t;
                f(ClippedEdge {
                    ua: a0,
                    ub: x,
                    d: edge * t,
                    horizon: false,
                });
                exit = Some(x);
            }
            (true, false) => {
                let t = (d0 / (d0 - d1)).clamp01();
                let x = u0 + edge * t;
                if let Some(e) = exit.take() {
                    f(ClippedEdge {
                        ua: e,
                        ub: x,
                        d: x - e,
                        horizon: true,
                    });
                }
                f(ClippedEdge {
                    ua: x,
                    ub: u1,
                    d: edge * (T::ONE - t),
                    horizon: false,
                });
                a0 = u1;
            }
            (true, true) => {}
        }
        u0 = u1;
        d0 = d1;
        below0 = below1;
    }
    true
}

/// Validates a polygon in f64; returns its unit normal (Newell's method).
///
/// Works on the vertices relative to vertex 0 scaled by a power of two (exact) that brings
/// their largest coordinate into [1, 2), so a polygon is accepted or refused alike at every
/// scale the type represents (the squares below would otherwise underflow or overflow f64
/// beyond about `2^+-500`).
///
/// Planarity: every vertex within `PLANAR_TOL` of the size of the plane of the largest fan
/// triangle `(v0, v_i, v_i+1)` (the spec's `1e-6`), plus, for a type whose rounding is absolute
/// (fixed point, [`Real::RESOLUTION`] `r > 0`), what rounding the vertices of a planar polygon
/// to the type can do: each vertex moves by up to `e = sqrt(3) r/2`, so a rounded vertex is off
/// the plane through the rounded `v0` by `2e`, and the fitted plane tilts by up to
/// `4 e size/|c|` (`c` the fan triangle's cross product), which moves a vertex at `size` from
/// `v0` by `4 e size^2/|c|`: `sqrt(3) r (1 + 2 size^2/|c|)`, taken with a margin of 1.5 for the
/// second-order terms. Floats add nothing: the spec's tolerance stands.
fn validate_polygon<T: Real>(verts: &[Vec3<T>]) -> Result<[f64; 3], Error> {
    // One copy of the validation for every backend (it runs in f64 anyway).
    // (`get`: no bounds check; every index asked for is below `verts.len()`, and a NaN vertex
    // would be refused.)
    let vert = |i: usize| verts.get(i).map_or([f64::NAN; 3], |v| v.to_f64());
    validate_polygon_f64(verts.len(), &vert, T::RESOLUTION.to_f64())
}

/// [`validate_polygon`] on the `n` vertices `vert(i)` (in f64) of a backend of resolution `res`.
fn validate_polygon_f64(
    n: usize,
    vert: &dyn Fn(usize) -> [f64; 3],
    res: f64,
) -> Result<[f64; 3], Error> {
    type V = Vec3<f64>;
    let at = |i: usize| -> V { Vec3::from_f64(vert(i % n)) };
    let o = at(0);
    // The power of two: 2^-e with 2^e <= the largest coordinate of v_i - v0 < 2^(e+1), as two
    // factors (each within f64's range).
    let big = (1..n).fold(0.0f64, |m, i| m.max((at(i) - o).max_abs()));
    if !(big > 0.0) || !big.is_finite() {
        return Err(Error::ZeroArea);
    }
    let e = libm::ilogb(big);
    let scale = (libm::ldexp(1.0, -e / 2), libm::ldexp(1.0, -e - (-e / 2)));
    // Vertex i relative to vertex 0, scaled.
    let v = |i: usize| -> V { (at(i) - o) * scale.0 * scale.1 };
    // Size: the largest distance from vertex 0 (within a factor 2 of the diameter).
    let size = (1..n).fold(0.0f64, |m, i| m.max(v(i).length()));
    if !(size > 0.0) || !size.is_finite() {
        return Err(Error::ZeroArea);
    }
    let rel = |i: usize| -> V {
        let d = v(i);
        Vec3::new(d.x / size, d.y / size, d.z / size)
    };
    // A plane first: the largest of the fan cross products (v_i - v0) x (v_i+1 - v0). (Newell's
    // normal cannot serve here: a crossed "bowtie" has a zero Newell normal but is not simple.)
    let mut plane = Vec3::new(0.0, 0.0, 0.0);
    let mut best = 0.0f64;
    for i in 1..n - 1 {
        let c = rel(i).cross(rel(i + 1));
        let l = c.dot(c);
        if l > best {
            best = l;
            plane = c;
        }
    }
    // All vertices collinear (to f64 precision): zero area.
    if !(best > 1e-28) {
        return Err(Error::ZeroArea);
    }
    let root = libm::sqrt(best);
    let plane = Vec3::new(plane.x / root, plane.y / root, plane.z / root);
    // The rounding of the vertices (fixed point; see above), in the scaled coordinates.
    let res = res * scale.0 * scale.1;
    let tol = PLANAR_TOL * size + 1.5 * libm::sqrt(3.0) * res * (1.0 + 2.0 / root);
    for i in 1..n {
        if libm::fabs(plane.dot(v(i))) > tol {
            return Err(Error::NotPlanar);
        }
    }
    let unit = plane.to_f64();
    // Simplicity in the plane: drop the dominant axis of the normal.
    let ax = unit.map(libm::fabs);
    let (ia, ib) = if ax[0] >= ax[1] && ax[0] >= ax[2] {
        (1, 2)
    } else if ax[1] >= ax[2] {
        (2, 0)
    } else {
        (0, 1)
    };
    let p2 = |i: usize| {
        let d = v(i).to_f64();
        [d[ia] / size, d[ib] / size]
    };
    for i in 0..n {
        let (a0, a1) = (p2(i), p2(i + 1));
        for j in (i + 1)..n {
            let adjacent = j == i + 1 || (i == 0 && j == n - 1);
            let (b0, b1) = (p2(j), p2(j + 1));
            if adjacent {
                // Two consecutive edges must not fold back onto each other.
                let (shared, x, y) = if j == i + 1 {
                    (a1, a0, b1)
                } else {
                    (a0, a1, b0)
                };
                let e1 = [x[0] - shared[0], x[1] - shared[1]];
                let e2 = [y[0] - shared[0], y[1] - shared[1]];
                let cross = e1[0] * e2[1] - e1[1] * e2[0];
                let dotp = e1[0] * e2[0] + e1[1] * e2[1];
                let l1 = libm::hypot(e1[0], e1[1]);
                let l2 = libm::hypot(e2[0], e2[1]);
                if l1 == 0.0 || l2 == 0.0 || (libm::fabs(cross) <= 1e-12 * l1 * l2 && dotp > 0.0) {
                    return Err(Error::NotSimple);
                }
            } else if segments_touch(a0, a1, b0, b1) {
                return Err(Error::NotSimple);
            }
        }
    }
    // Newell's normal (twice the area vector, over size^2) for the area and the orientation.
    let mut nn = Vec3::new(0.0f64, 0.0, 0.0);
    for i in 0..n {
        let (a, b) = (rel(i), rel(i + 1));
        nn.x += (a.y - b.y) * (a.z + b.z);
        nn.y += (a.z - b.z) * (a.x + b.x);
        nn.z += (a.x - b.x) * (a.y + b.y);
    }
    let len = nn.length();
    // A simple polygon of relative area below 1e-14 is zero area to f64.
    if !(len > 1e-14) {
        return Err(Error::ZeroArea);
    }
    Ok(nn.to_f64().map(|x| x / len))
}

fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

fn on_segment(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> bool {
    c[0] >= a[0].min(b[0])
        && c[0] <= a[0].max(b[0])
        && c[1] >= a[1].min(b[1])
        && c[1] <= a[1].max(b[1])
}

/// Closed segments `a0a1` and `b0b1` intersect (cross or touch).
fn segments_touch(a0: [f64; 2], a1: [f64; 2], b0: [f64; 2], b1: [f64; 2]) -> bool {
    let eps = 1e-12;
    let d1 = orient(b0, b1, a0);
    let d2 = orient(b0, b1, a1);
    let d3 = orient(a0, a1, b0);
    let d4 = orient(a0, a1, b1);
    if ((d1 > eps && d2 < -eps) || (d1 < -eps && d2 > eps))
        && ((d3 > eps && d4 < -eps) || (d3 < -eps && d4 > eps))
    {
        return true;
    }
    (libm::fabs(d1) <= eps && on_segment(b0, b1, a0))
        || (libm::fabs(d2) <= eps && on_segment(b0, b1, a1))
        || (libm::fabs(d3) <= eps && on_segment(a0, a1, b0))
        || (libm::fabs(d4) <= eps && on_segment(a0, a1, b1))
}
