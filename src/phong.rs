//! Phong illumination from area lights (Snyder section 3): hemisphere (eq. 14, 15), cap and
//! sphere (eq. 24, appendices D-F) and polygon (eq. 25, appendices G-H) lights.
//!
//! The model is `I = ((m + 1)/(2 pi)) integral of L(u) ((u.r)+)^m du` with `r` the reflection
//! direction: Snyder's, with no `(n.u)` factor and no clipping to the hemisphere around `n`.
//! A hemisphere of unit radiance around `r` gives 1, and `m = 1`, `r = n` is the Lambertian model
//! of the same source.
//!
//! ## Odd and even exponents
//!
//! By Stokes' theorem (Snyder appendix C) the integral becomes a sum of boundary integrals
//! `J(k)` of the source's projection, `k = m, m - 2, ...`, plus, for even `m`, the solid angle
//! `I(0)` of the projection clipped to the hemisphere around `r`. Snyder restricts `m` to odd
//! values to avoid `I(0)`; here even `m` is exact too: the clipped solid angle of a cap is closed
//! form (below) and that of a polygon is the fan of Van Oosterom-Strackee triangles
//! (Arvo 5.1, [`crate::polygon`]). [`PhongLobe::odd_only`] keeps Snyder's fast path (an even
//! exponent is evaluated as the next odd one) as an opt-in.
//!
//! ## Hemisphere lights
//!
//! `I_const = 1 - S(m, w)/S(m, pi)` (eq. 14) and
//! `I_cos = (m + 1)/((m + 2) S(m + 1, pi)) [sin^(m+2)(w)/(m + 1) + cos w (S(m + 1, pi) - S(m + 1, w))]`
//! (eq. 15), with [`S`](crate::sine_power). We use `S(k, pi) - S(k, w) = S(k, pi - w)` for
//! `w > pi/2`, so the recurrence always integrates the smaller side (no cancellation near
//! `w = pi`).
//!
//! ## Caps and spheres, rewritten for stability
//!
//! On the cap's boundary `z = a + b cos(phi)` with `a = cos(sigma) cos(w)`, `b = -sin(sigma) sin(w)`
//! (eq. 19). Snyder integrates `(a + b cos phi)^k` and `(a + b cos phi)^k cos phi` from
//! `phi_1 = acos(-a/b)` to `2 pi - phi_1` as differences of the recurrences of appendix D from 0.
//! For large `k` and `w > pi/2` those two partial integrals are dominated by the part of the
//! boundary *below* the horizon, where `|z|` is largest, and their difference cancels. By the
//! symmetry `phi -> 2 pi - phi` and the substitution `phi = pi - psi`, the same quantities are
//!
//! ```text
//! F_sum(phi_2) - F_sum(phi_1) =  2 F_sum(a, -b, x),   G_sum(phi_2) - G_sum(phi_1) = -2 G_sum(a, -b, x)
//! ```
//!
//! with `x = pi - phi_1`, integrating only over the visible arc. With `ss = sin sigma`,
//! `cs = cos sigma`, `c = cos w` and `q = sqrt(ss^2 - c^2)`, everything reduces to one arc
//! tangent: `x = atan2(q, -cs c)`, `sin x = q/(ss sin w)`, `cos x = -cs c/(ss sin w)`; the horizon arc
//! of the odd case is `K = 2 atan2(q, cs)` (eq. 23), and the clipped solid angle of the even case
//! is `I(0) = 2 pi - 2 atan2(q, c) - 2 cs x` (the area of a cap cut by a great circle). When the
//! cap is wholly above the horizon `x = pi` and `I(0) = 2 pi (1 - cs)`. `q^2 = ss^2 - c^2` is
//! also `s^2 - cs^2`; the code factors whichever pair is smaller, so it does not cancel when
//! sigma and w are both near pi/2.
//!
//! ## Accuracy
//!
//! f64 agrees with the quadrature of the definition to 5.5e-13 for every `m` tested from 0 to
//! 255, and 1.8e-12 up to `m` = 1001 (measured; tested per model in `F64_BUDGET`). In f32 the recurrences raise numbers within an ULP of 1 to powers up to `m`, so
//! the error grows about as `m 2^-24`: within 2e-6 of f64 up to `m` of about 64, 4.5e-6 (cap) and
//! 1.3e-6 (polygon) at `m = 255`. The inputs are made consistent first (`cos w`, `sin w` with
//! `c^2 + s^2 = 1`; `f = 1 - (r.G)^2`), which cut the m = 255 error three-fold. The README
//! tabulates the measured errors.

#[cfg(feature = "cap")]
use crate::cap::{CapLight, SphereCap, SphereLight};
#[cfg(feature = "hemisphere")]
use crate::hemisphere::HemisphereLight;
#[cfg(feature = "cap")]
use crate::lobe::negligible_terms;
pub use crate::lobe::{PhongLobe, MAX_EXPONENT};
#[cfg(feature = "hemisphere")]
use crate::sine_power::sine_power_integral;
#[cfg(any(feature = "cap", feature = "hemisphere"))]
use crate::unit::Direction;
#[cfg(any(feature = "cap", feature = "hemisphere"))]
use crate::vec3::cos_sin_between;
#[cfg(feature = "cap")]
use crate::Error;
#[cfg(any(feature = "cap", feature = "hemisphere"))]
use crate::Real;
#[cfg(feature = "cap")]
use crate::UnitVec3;
#[cfg(feature = "cap")]
use crate::Vec3;

#[cfg(feature = "hemisphere")]
impl<T: Real> HemisphereLight<T> {
    /// `[phong_hemi_const]`: Phong illumination from the constant-weighted hemisphere (Snyder
    /// eq. 14), normalized (in [0, 1]); `r` is the reflection direction (any length).
    ///
    /// Accuracy: measured, below. Cost: 1 normalization, 1 cross product, 1 sqrt,
    /// (1 atan2 for even m), and `m/2` recurrence steps. Fallback: 0 for a zero or non-finite `r`.
    ///
    /// <!-- BEGIN acc-phong_hemi_const: target/accuracy/model-phong_hemi_const.md -->
    /// Measured: f64 within 1.1e-13 of its reference (the independent quadrature); against f64,
    /// f32 2.0e-6 at m = 255 (ill-conditioned: 1.0e-6 at m = 255), Fast32 4.2e-6 at m = 64
    /// (ill-conditioned: 2.0e-6 at m = 64), Fixed22 9.9e-5 at m = 0; 88 657 cases in all
    /// (`docs/accuracy.md`).
    /// <!-- END acc-phong_hemi_const -->
    #[inline]
    pub fn phong_const(&self, lobe: &PhongLobe<T>, r: impl Direction<T>) -> T {
        let Some(r) = r.to_unit() else {
            return T::ZERO;
        };
        let (c, s) = cos_sin_between(r, self.unit_axis());
        let m = lobe.m;
        // x only matters for even m (S starts from S(0, x) = x).
        let w = if m & 1 == 0 { s.atan2(c) } else { T::ZERO };
        let v = if c >= T::ZERO {
            T::ONE - sine_power_integral(m, w, s, c) / lobe.s_m_pi
        } else {
            sine_power_integral(m, T::PI - w, s, -c) / lobe.s_m_pi
        };
        v.clamp01()
    }

    /// `[phong_hemi_cos]`: Phong illumination from the cosine-weighted hemisphere (Snyder
    /// eq. 15), in [0, 1].
    ///
    /// Accuracy: measured, below. Cost: that of [`HemisphereLight::phong_const`] plus a
    /// power by squaring.
    /// Fallback: 0 for a zero or non-finite `r`.
    ///
    /// <!-- BEGIN acc-phong_hemi_cos: target/accuracy/model-phong_hemi_cos.md -->
    /// Measured: f64 within 5.5e-14 of its reference (the independent quadrature); against f64,
    /// f32 4.9e-7 at m = 255, Fast32 3.7e-6 at m = 255, Fixed22 7.7e-6 at m = 255; 88 657 cases
    /// in all (`docs/accuracy.md`).
    /// <!-- END acc-phong_hemi_cos -->
    #[inline]
    pub fn phong_cos(&self, lobe: &PhongLobe<T>, r: impl Direction<T>) -> T {
        let Some(r) = r.to_unit() else {
            return T::ZERO;
        };
        let (c, s) = cos_sin_between(r, self.unit_axis());
        let m = lobe.m;
        let k = m + 1;
        let w = if k & 1 == 0 { s.atan2(c) } else { T::ZERO };
        // S(k, pi - w) = integral of sin^k over [w, pi].
        let tail = if c >= T::ZERO {
            lobe.s_m1_pi - sine_power_integral(k, w, s, c)
        } else {
            sine_power_integral(k, T::PI - w, s, -c)
        };
        let v = lobe.hemi_cos_scale * (s.powu(m + 2).div_u32(k) + c * tail);
        v.clamp01()
    }
}

/// The sums `F_sum`, `G_sum` of the F, G recurrences of appendix D for `(A, B) = (a, -b)` at
/// `x`, `a = cs c`, `b = ss s` (the boundary term `(A + B cos x)^i sin x` vanishes: `sin x = 0`
/// or `A + B cos x = 0`), over `i = m - 1, m - 3, ...`.
///
/// `F_i` is the integral of `(a + b cos psi)^i` over the visible arc, whose largest value is
/// `D^i` with `D = a + b = cos(w - sigma)`. Near `D = 1` (r near the cap's boundary, where a
/// sharp lobe sees the edge) running `F_i+1 = a F_i + b G_i` on rounded `a` and `b` raises
/// their rounding to the power `i`: `a + b` is off by about an ULP, so `F_m` is off by about
/// `m` ULPs (2.5e-5 in f32 at m = 1001). For `D > 1/2` the recurrence runs instead on the
/// rescaled `F_i / D^i`, with `t = b/D` and `1 - t = a/D` entering only as
/// `F - t (F - G)`, and the weights `D^i` are built from `1 - D = sin^2(w - sigma)/(1 + D)`,
/// `sin(w - sigma) = s cs - c ss`, which carries no such rounding (f32 at m = 1001: 2.5e-5
/// before, 2.4e-7 after; STABILITY.md). The rescaled form needs `a >= 0` (`t <= 1`): for
/// `t > 1` its `F - G` mode grows as `(2t - 1)^i` before the weight `D^i` brings it back, which
/// overflows f32 at large m. Otherwise (`D <= 1/2`, where the terms fall off as `2^-i`, or
/// `w > pi/2`) the plain recurrence is kept.
#[cfg(feature = "cap")]
#[inline]
fn cap_boundary_sums<T: Real>(m: u32, x: T, sin_x: T, c: T, s: T, cs: T, ss: T) -> (T, T) {
    // Every factor of the loops' products is at most pi in magnitude: `F_i` and `G_i` (and
    // their rescaled forms) are integrals over an arc of at most pi of powers of
    // `|a + b cos psi| <= |a| + |b| <= 1` (`x <= pi`, `sin x <= 1`), `t`, `pw`, `v2`, `a` and
    // `b` are at most 1: the products without fixed point's saturation tests, the same bits
    // (about 15 fewer Cortex-M0 instructions each).
    let mul = T::mul_small;
    let a = cs * c;
    let b = ss * s;
    let parity = (m - 1) & 1;
    let (mut f, mut g) = (x, sin_x);
    let (mut fsum, mut gsum) = if parity == 0 {
        (f, g)
    } else {
        (T::ZERO, T::ZERO)
    };
    if a >= T::ZERO && a + b > T::HALF {
        let sin_d = s * cs - c * ss;
        let v = sin_d * sin_d / (T::ONE + (a + b));
        let d = T::ONE - v;
        let t = b / d;
        // 1 - D^2, and D^i for the next i of the parity.
        let v2 = v * (T::TWO - v);
        let mut pw = if parity == 0 { T::ONE - v2 } else { d };
        for i in 1..m {
            let h = f - g;
            let th = mul(t, h);
            let f_new = f - th;
            g = (g + th).mul_u32(i).div_u32(i + 1);
            f = f_new;
            if i & 1 == parity {
                fsum += mul(pw, f);
                gsum += mul(pw, g);
                pw -= mul(v2, pw);
            }
        }
    } else {
        for i in 1..m {
            let f_new = mul(a, f) + mul(b, g);
            let g_new = (mul(b, f) + mul(a, g)).mul_u32(i).div_u32(i + 1);
            f = f_new;
            g = g_new;
            if i & 1 == parity {
                fsum += f;
                gsum += g;
            }
        }
    }
    (fsum, gsum)
}

#[cfg(feature = "cap")]
impl<T: Real> SphereCap<T> {
    /// `[phong_sphere]` of this cap for the unit reflection direction `r` and the lobe's
    /// evaluated exponent.
    #[inline(always)]
    pub(crate) fn phong(&self, lobe: &PhongLobe<T>, r: UnitVec3<T>) -> T {
        let (c, s) = cos_sin_between(r, self.axis);
        phong_cap_from_angle(lobe, c, s, self.cs(), self.ss)
    }

    /// `([sphere_lambert], [phong_sphere])` of this cap: the two terms of
    /// [`SphereLight`]'s `Illuminant::diffuse_and_phong`, `cos sigma` taken once for both
    /// (the same bits as each alone).
    #[inline(always)]
    pub(crate) fn lambert_and_phong(
        &self,
        lobe: &PhongLobe<T>,
        n: UnitVec3<T>,
        r: UnitVec3<T>,
    ) -> (T, T) {
        let cs = self.cs();
        let diffuse = crate::cap::cap_lambert_from_cos(n.cos_to(self.axis), || cs, self.ss);
        let (c, s) = cos_sin_between(r, self.axis);
        (diffuse, phong_cap_from_angle(lobe, c, s, cs, self.ss))
    }
}

/// Snyder's eq. 24 in the stable form of the module docs, from `c = cos w`, `s = sin w`
/// (`w` between `r` and the cap axis), `cs`, `ss`, for the lobe's evaluated exponent `m`.
///
/// Fixed point, f32 and Fast32 first try to prove the term negligible, as for polygons
/// (`polygon/negligible.rs`): with `r` outside the cap (`w > sigma`, `c < cs`), `r.u` is at
/// most `cos(w - sigma) = c cs + s ss` on it, so the term is at most that to the power
/// `m + 1`, and below `2^-24` where that cosine is below the lobe's threshold (lowered by
/// `2^-6` of itself, far above the rounding of two products). Where `c < cs` is decided
/// wrongly by rounding, `w` is within rounding of `sigma` and the cosine is about 1: never
/// below the threshold. Cost: 2 products and 2 comparisons.
#[cfg(feature = "cap")]
fn phong_cap_from_angle<T: Real>(lobe: &PhongLobe<T>, c: T, s: T, cs: T, ss: T) -> T {
    let m = lobe.m;
    if negligible_terms::<T>()
        && c < cs
        && T::mul_le2(c, cs) + T::mul_le2(s, ss) < lobe.negligible_cos.0
    {
        return T::ZERO;
    }
    // q^2 = ss^2 - c^2 = s^2 - cs^2: the first form cancels when sigma and w are both near
    // pi/2 or c and ss both near 1, the second when both are small; take the factors of the
    // smaller pair. q^2 > 0 exactly when the cap's boundary crosses the horizon of r.
    let q2 = if ss * ss > T::HALF {
        (s - cs) * (s + cs)
    } else {
        (ss - c) * (ss + c)
    };
    let partial = q2 > T::ZERO;
    if !partial && c <= T::ZERO {
        return T::ZERO;
    }
    let full = !partial;
    // x = pi - phi_1 and its sine; q = sqrt(ss^2 - c^2).
    let (x, sin_x, q) = if full {
        (T::PI, T::ZERO, T::ZERO)
    } else {
        let q = q2.sqrt();
        let den = ss * s;
        let x = q.atan2(-cs * c);
        if den > T::TINY {
            (x, (q / den).clamp01(), q)
        } else {
            (x, x.sin(), q)
        }
    };
    let mut total = T::ZERO;
    if m >= 1 {
        let (fsum, gsum) = cap_boundary_sums(m, x, sin_x, c, s, cs, ss);
        // ss (d dF + c' dG) with d = ss c, c' = cs s, dF = 2 fsum, dG = -2 gsum.
        total = T::TWO * ss * (ss * c * fsum - cs * s * gsum);
    }
    let e = if m & 1 == 0 {
        if full {
            T::TAU * (T::ONE - cs)
        } else {
            T::TAU - T::TWO * q.atan2(c) - T::TWO * cs * x
        }
    } else if full {
        T::ZERO
    } else {
        T::TWO * q.atan2(cs)
    };
    ((total + e) * T::FRAC_1_TAU).clamp01()
}

#[cfg(feature = "cap")]
impl<T: Real> CapLight<T> {
    /// `[phong_cap]`: Phong illumination from the cap (Snyder eq. 24), in [0, 1].
    ///
    /// Accuracy: measured, below. Cost: 1 normalization, 1 cross product, 1 sqrt; if the
    /// cap crosses the horizon of `r` also 1 sqrt, 1-2 atan2, 1 division; then `m - 1`
    /// recurrence steps of ~8 operations. Fixed point, f32 and Fast32, `m >= 11`: 0 at once,
    /// after 2 products, where `r` is outside the cap and `r.u` on it is provably too small for
    /// the term to reach `2^-24` (a quarter of `Fixed22`'s unit, 3 % of f32's error budget; the
    /// recurrence's own error is larger). Measured on the Cortex-M0 (`Fixed22`, QEMU, the
    /// budget's 16 cases at m = 16): the 2 such cases 5 887 -> 978 instructions, the others
    /// within +-46; on the Cortex-M4F (f32), the 2 such cases 515 -> 107, the others at most
    /// 13 dearer (the budget table's median 421 -> 427). The recurrence's products skip
    /// fixed point's saturation tests (every factor at most pi, the same bits): the budget's
    /// median 5 019 -> 4 397 on the Cortex-M0 (4 384 now, the square roots' seed table
    /// indexed without arithmetic). Fallback: 0 for a zero or non-finite `r`.
    ///
    /// <!-- BEGIN acc-phong_cap: target/accuracy/model-phong_cap.md -->
    /// Measured: f64 within 2.4e-13 of its reference (the independent quadrature); against f64,
    /// f32 2.0e-6 at m = 255 (high m: 2.2e-6 at m = 255; ill-conditioned: 2.5e-6 at m = 255),
    /// Fast32 7.8e-6 at m = 255 (ill-conditioned: 6.8e-6 at m = 255), Fixed22 1.6e-4 at m = 0;
    /// 200 854 cases in all (`docs/accuracy.md`).
    /// <!-- END acc-phong_cap -->
    #[inline]
    pub fn phong(&self, lobe: &PhongLobe<T>, r: impl Direction<T>) -> T {
        let Some(r) = r.to_unit() else {
            return T::ZERO;
        };
        let (cs, ss) = self.cos_sin_sigma();
        let (c, s) = cos_sin_between(r, self.unit_axis());
        phong_cap_from_angle(lobe, c, s, cs, ss)
    }
}

#[cfg(feature = "cap")]
impl<T: Real> SphereLight<T> {
    /// `[phong_sphere]` with precise errors: see [`SphereLight::phong`].
    ///
    /// # Errors
    /// [`Error::NotFinite`] for `p` or `r`, [`Error::ZeroLength`] for `r`,
    /// [`Error::PointInsideSphere`].
    pub fn try_phong(
        &self,
        lobe: &PhongLobe<T>,
        p: Vec3<T>,
        r: impl Direction<T>,
    ) -> Result<T, Error> {
        let cap = self.cap_at(p)?;
        Ok(cap.phong(lobe, r.try_unit("r")?))
    }

    /// `[phong_sphere]`: Phong illumination at `p` from the sphere (the cap of eq. 7), in [0, 1].
    ///
    /// Cost: that of [`CapLight::phong`] (with its early 0 in fixed point) plus 1
    /// normalization, 1 division, 1 sqrt. Fallback: 0 for a point inside or on the sphere or a
    /// zero or non-finite input.
    ///
    /// <!-- BEGIN acc-phong_sphere: target/accuracy/model-phong_sphere.md -->
    /// Measured: f64 within 7.9e-14 of its reference (the independent quadrature); against f64,
    /// f32 1.4e-6 at m = 255 (ill-conditioned: 6.1e-6 at m = 255), Fast32 7.6e-6 at m = 255
    /// (ill-conditioned: 8.2e-6 at m = 255), Fixed22 1.1e-4 at m = 255; 62 580 cases in all
    /// (`docs/accuracy.md`).
    /// <!-- END acc-phong_sphere -->
    #[inline]
    pub fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: impl Direction<T>) -> T {
        self.try_phong(lobe, p, r).unwrap_or(T::ZERO)
    }
}

#[cfg(feature = "polygon")]
mod polygon;
#[cfg(all(test, feature = "cap", feature = "fixed"))]
mod tests;
