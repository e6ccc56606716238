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
mod edge;
mod validate;
#[cfg(any(feature = "phong", feature = "moments"))]
pub(crate) use arc::{arc_axis_form, cos_power_sums};
pub(crate) use edge::{edge_angle_term, products_in_range, rescaled_products, scaled_to_unit};
use validate::validate_polygon;

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
    /// the face (where the value jumps from 0 to nearly the whole face and the type cannot
    /// tell which side `p` is on; in the plane outside the polygon it is 0).
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
    /// instructions in f32 (920 with the arc tangent), 6089 Cortex-M0 instructions in
    /// `Fixed22`. Fallback: 0 for a zero or non-finite input, and 0 when `p` is in the
    /// polygon's plane (fixed point over the face: 0 too, where [`PolygonLight::try_lambert`]
    /// reports [`Error::Unresolved`]).
    ///
    /// <!-- BEGIN acc-polygon_lambert: target/accuracy/model-polygon_lambert.md -->
    /// Measured: f64 within 2.1e-14 of its reference (the independent quadrature, adversarial);
    /// against f64, f32 5.4e-7 (ill-conditioned: 2.9e-6; near boundary: 4.4e-4), Fast32 5.7e-6
    /// (ill-conditioned: 3.5e-6; near boundary: 4.4e-4), Fixed22 1.8e-4; 57 939 cases in all
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
