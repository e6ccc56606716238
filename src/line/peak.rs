//! The peak approximations `[line_phong_peak]` and `[rect_phong_peak]` (Picott's closest
//! angular point): see the [module docs](super) for the method and its accuracy.

use super::{hypot, ln_1p, shrink, unit, LineLight};
use crate::lobe::PhongLobe;
use crate::unit::Direction;
use crate::{Error, Real, Vec3};

impl<T: Real> LineLight<T> {
    /// `[line_phong_peak]` with precise errors: see [`LineLight::phong_peak`].
    ///
    /// # Errors
    /// [`Error::NotFinite`] for `p` or `r`, [`Error::ZeroLength`] for `r`,
    /// [`Error::PointOnSegment`].
    pub fn try_phong_peak(
        &self,
        lobe: &PhongLobe<T>,
        p: Vec3<T>,
        r: impl Direction<T>,
    ) -> Result<T, Error> {
        let v = self.view(p)?;
        let r = r.try_unit("r")?.into_inner();
        let ver = segment_versine(v.l0, v.l1, self.e, v.s0, v.s1, v.g, v.h, r);
        Ok(lobe_power(lobe.exponent(), ver))
    }

    /// `[line_phong_peak]`: Picott's specular approximation, the largest `((u.r)+)^m` over the
    /// directions `u` from `p` to the segment (the closest angular point of eq. 7, clamped to
    /// the segment); `r` any length. In [0, 1].
    ///
    /// Accuracy (module docs): f64 within 6e-11 of a brute-force search for m <= 1000 (the
    /// worst case a segment 2e5 long seen from 1; 1e-13 typically), the error not growing with
    /// `m`; f32 within 5e-7 of f64 and Fast32 within 7e-6 where well conditioned.
    /// [`crate::Fixed22`] misses 1/1024 (2.6e-2 at m = 255 with `p` near the segment's line
    /// beyond an end, and `p` refused as on the segment up to 4.3e-4 of the length from it:
    /// the frame's perpendicular vanishes below `2^-11` of the size; 8.1e-3 remains with it
    /// rescaled, `p` 1/100 of the length from an end), so the fixed-point eval backend does
    /// not answer this model. Cost: that of
    /// the segment frame (1 normalization, 1 division, 2 cross products, 1-3 sqrt), 2
    /// normalizations, 1 cross product, ~6 dot products, 1 sqrt, 1 `ln`, 1 `exp`. Fallback: 0
    /// for a non-finite or zero input or a point on the segment.
    ///
    /// <!-- BEGIN acc-line_phong_peak: target/accuracy/model-line_phong_peak.md -->
    /// Measured: f64 within 4.7e-9 of its reference (brute force, h = 1e-9 rotated); against f64,
    /// f32 3.5e-7 (capped: 2.3e-3; ill-conditioned: 1.7e-6; near boundary: 2.6e-5; unresolved:
    /// 6.6e-1), Fast32 3.5e-7 (capped: 2.3e-3; ill-conditioned: 1.7e-6; near boundary: 2.6e-5;
    /// unresolved: 6.6e-1); 10 047 cases in all (`docs/accuracy.md`).
    /// <!-- END acc-line_phong_peak -->
    #[inline]
    pub fn phong_peak(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: impl Direction<T>) -> T {
        self.try_phong_peak(lobe, p, r).unwrap_or(T::ZERO)
    }
}

/// The smallest versine `1 - u.r` over the directions `u` from `p` to a segment given in
/// working units: its ends `l0`, `l1`, unit direction `e`, `s0 = l0.e`, `s1 = l1.e`,
/// `g = l0 x e`, `h = |g|`; `r` unit. In [0, 2].
#[allow(clippy::too_many_arguments)]
#[inline]
fn segment_versine<T: Real>(
    l0: Vec3<T>,
    l1: Vec3<T>,
    e: Vec3<T>,
    s0: T,
    s1: T,
    g: Vec3<T>,
    h: T,
    r: Vec3<T>,
) -> T {
    let mut best = T::TWO;
    for l in [l0, l1] {
        if let Some(u) = l.normalize() {
            let c = u - r;
            best = best.min(T::HALF * c.dot(c));
        }
    }
    if h > T::TINY {
        // r's angle in the arc's plane lies within the arc: eq. 7's t in [0, 1].
        let alpha = g.dot(r.cross(e));
        let hb = h * h * e.dot(r);
        if alpha > T::ZERO && s0 * alpha <= hb && hb <= s1 * alpha {
            // The largest cosine is |r'|, r' the part of r in the arc's plane; 1 - |r'| from
            // w = r.nu (nu = g/h) while that is small (|r'| near 1), from |r'| itself when r
            // is nearly normal to the plane (there 1 - w^2 would cancel).
            let w = (g.dot(r) / h).clamp(-T::ONE, T::ONE);
            let w2 = w * w;
            let v = if w2 <= T::HALF {
                w2 / (T::ONE + (T::ONE - w2).sqrt())
            } else {
                T::ONE - hypot(alpha / h, e.dot(r)).min(T::ONE)
            };
            best = best.min(v);
        }
    }
    best
}

/// `((1 - v)+)^m` from the versine `v`, as `exp(m ln1p(-v))` (error independent of `m`).
#[inline]
fn lobe_power<T: Real>(m: u32, v: T) -> T {
    if !(v < T::ONE) {
        return T::ZERO;
    }
    if m == 0 {
        return T::ONE;
    }
    (T::from_u32(m) * ln_1p(-v)).exp().clamp01()
}

/// A parallelogram light `origin + s eu + t ev`, `s, t` in [0, 1] (Picott section 3.2), for the
/// peak approximation `[rect_phong_peak]`. For its Lambertian or Phong integrals build a
/// [`crate::PolygonLight`] from [`ParallelogramLight::vertices`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParallelogramLight<T> {
    origin: Vec3<T>,
    eu: Vec3<T>,
    ev: Vec3<T>,
    /// Unit normal `eu x ev / |eu x ev|` (computed in f64).
    normal: Vec3<T>,
    /// Unit directions of `eu` and `ev`.
    eu_dir: Vec3<T>,
    ev_dir: Vec3<T>,
}

/// Parallelograms whose `|eu x ev|` is at most this fraction of `|eu| |ev|` (the sine of the
/// angle between the edges) are refused as zero area (the polygons' relative tolerance).
const PARALLEL_SINE: f64 = 1e-14;

impl<T: Real> ParallelogramLight<T> {
    /// The parallelogram with corner `origin` and edge vectors `eu`, `ev`.
    ///
    /// Validation runs in f64 for every backend. Cost: a few normalizations, once.
    ///
    /// # Errors
    /// [`Error::NotFinite`] for `origin`, `eu`, `ev` (or a corner that overflows);
    /// [`Error::ZeroArea`] when `eu x ev = 0` (to within a sine of 1e-14 between the edges,
    /// including a zero edge).
    pub fn new(origin: Vec3<T>, eu: Vec3<T>, ev: Vec3<T>) -> Result<Self, Error> {
        for (v, name) in [(origin, "origin"), (eu, "eu"), (ev, "ev")] {
            if !v.is_finite() {
                return Err(Error::NotFinite(name));
            }
        }
        let corner = origin + eu + ev;
        if !(corner.is_finite() && (origin + eu).is_finite() && (origin + ev).is_finite()) {
            return Err(Error::NotFinite("origin"));
        }
        let (u, w) = (
            unit(Vec3::<f64>::from_f64(eu.to_f64())),
            unit(Vec3::<f64>::from_f64(ev.to_f64())),
        );
        let (Some(u), Some(w)) = (u, w) else {
            return Err(Error::ZeroArea);
        };
        let c = u.cross(w);
        if !(c.length() > PARALLEL_SINE) {
            return Err(Error::ZeroArea);
        }
        let normal = c * (1.0 / c.length());
        Ok(ParallelogramLight {
            origin,
            eu,
            ev,
            normal: Vec3::from_f64(normal.to_f64()),
            eu_dir: Vec3::from_f64(u.to_f64()),
            ev_dir: Vec3::from_f64(w.to_f64()),
        })
    }

    /// The corner `origin`.
    pub fn origin(&self) -> Vec3<T> {
        self.origin
    }
    /// The edge vector `eu`.
    pub fn eu(&self) -> Vec3<T> {
        self.eu
    }
    /// The edge vector `ev`.
    pub fn ev(&self) -> Vec3<T> {
        self.ev
    }
    /// The unit normal `eu x ev / |eu x ev|`.
    pub fn normal(&self) -> Vec3<T> {
        self.normal
    }
    /// The corners in order: `origin`, `origin + eu`, `origin + eu + ev`, `origin + ev`.
    pub fn vertices(&self) -> [Vec3<T>; 4] {
        let o = self.origin;
        [o, o + self.eu, o + self.eu + self.ev, o + self.ev]
    }

    /// `[rect_phong_peak]` with precise errors: see [`ParallelogramLight::phong_peak`].
    ///
    /// # Errors
    /// [`Error::NotFinite`] for `p` or `r`, [`Error::ZeroLength`] for `r`.
    pub fn try_phong_peak(
        &self,
        lobe: &PhongLobe<T>,
        p: Vec3<T>,
        r: impl Direction<T>,
    ) -> Result<T, Error> {
        if !p.is_finite() {
            return Err(Error::NotFinite("p"));
        }
        let r = r.try_unit("r")?.into_inner();
        // Corners relative to p (in quarter units if a sum overflows: the peak is scale-free).
        let mut q0 = self.origin - p;
        let (mut eu, mut ev) = (self.eu, self.ev);
        if !(q0.is_finite() && (q0 + eu + ev).is_finite() && (q0 + eu).is_finite()) {
            let quarter = T::from_f64(0.25);
            q0 = self.origin * quarter - p * quarter;
            eu = eu * quarter;
            ev = ev * quarter;
        }
        // In the plane (to within a few ULPs), every direction toward the light lies in the
        // plane: no ray along r hits it (unless r lies in the plane too), and the largest
        // ((u.r)+)^m over its points is the best over its edges (the 2D case of the segment
        // peak; from inside the parallelogram the edges are seen in every in-plane direction).
        let height = q0.dot(self.normal);
        let in_plane = !(height.abs() > T::from_f64(4.0) * T::EPSILON * q0.max_abs());
        let q = [q0, q0 + eu, q0 + eu + ev, q0 + ev];
        let sigma = q.iter().fold(T::ZERO, |m, v| m.max(v.max_abs()));
        let inv = T::ONE / sigma;
        let q = q.map(|v| shrink(v, sigma, inv));
        let dirs = [self.eu_dir, self.ev_dir, -self.eu_dir, -self.ev_dir];
        let edges = [
            shrink(eu, sigma, inv),
            shrink(ev, sigma, inv),
            -shrink(eu, sigma, inv),
            -shrink(ev, sigma, inv),
        ];
        // The ray p + lambda r (lambda > 0) hits the parallelogram iff r.(q_i x edge_i) has
        // the sign of height = (origin - p).normal on every edge (r inside the pyramid of the
        // corners; the opposite pyramid gives the opposite signs).
        let inside = !in_plane
            && (0..4).all(|i| {
                let t = r.dot(q[i].cross(edges[i]));
                if height > T::ZERO {
                    t >= T::ZERO
                } else {
                    t <= T::ZERO
                }
            });
        if inside {
            return Ok(lobe_power(lobe.exponent(), T::ZERO));
        }
        let mut best = T::TWO;
        for i in 0..4 {
            let (l0, l1, e) = (q[i], q[(i + 1) % 4], dirs[i]);
            let g = l0.cross(e);
            let v = segment_versine(l0, l1, e, l0.dot(e), l1.dot(e), g, g.length(), r);
            best = best.min(v);
        }
        Ok(lobe_power(lobe.exponent(), best))
    }

    /// `[rect_phong_peak]`: Picott's specular approximation for the parallelogram, the largest
    /// `((u.r)+)^m` over the directions `u` from `p` to its points (1 where the ray along `r`
    /// hits it, else the best point of its four edges); `r` any length. In [0, 1]. For `p` in
    /// the parallelogram's plane the definition holds too (a peak is not a polygon model: it
    /// has a value wherever a point of the light is seen): every direction toward the light
    /// then lies in the plane, and the value is the best over the edges.
    ///
    /// Accuracy (module docs): f64 within 7e-13 of a brute-force search for m <= 1000, the
    /// error not growing with `m`; f32 within 5e-7 of f64 and Fast32 within 7.4e-6 where well
    /// conditioned; [`crate::Fixed22`] within 9.4e-5 of f64 for m <= 255 with `p` at least
    /// 1/256 of the light's size from it (`tests/fixed_line.rs`; within a few LSB of its face
    /// the fixed path takes `p` as in the plane: measured 1.3e-2 at m = 255 with `p` 1.1e-6
    /// above the face). Cost: 1 normalization, 1 division, 4 cross products and dot products for
    /// the hit test; if it misses, per edge 2 normalizations, 2 cross products, ~5 dot
    /// products, 1-2 sqrt; then 1 `ln`, 1 `exp` (none when it hits). Fallback: 0 for a
    /// non-finite or zero input.
    ///
    /// <!-- BEGIN acc-rect_phong_peak: target/accuracy/model-rect_phong_peak.md -->
    /// Measured: f64 within 7.0e-10 of its reference (brute force, m = 2^16, 2^20); against f64,
    /// f32 2.9e-7 (ill-conditioned: 4.7e-6; near boundary: 4.5e-7), Fast32 2.9e-7
    /// (ill-conditioned: 4.7e-6; near boundary: 4.5e-7), Fixed22 9.4e-5 at m = 255; 11 294 cases
    /// in all (`docs/accuracy.md`).
    /// <!-- END acc-rect_phong_peak -->
    #[inline]
    pub fn phong_peak(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: impl Direction<T>) -> T {
        self.try_phong_peak(lobe, p, r).unwrap_or(T::ZERO)
    }
}
