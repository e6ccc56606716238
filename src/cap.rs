//! Sub-hemispherical (cap) lights and spherical lights, Lambertian: exact (Snyder eq. 6) and
//! Snyder's two-segment Hermite approximation (section 2.2).
//!
//! A cap of half-angle `sigma` in [0, pi/2] around `axis` radiates 1 toward every direction `u`
//! with `u.axis >= cos sigma`. A sphere of radius `r` at distance `d` from the shading point is
//! the cap with `sin sigma = r/d` (eq. 7) around the direction to its centre.
//!
//! ## The exact model in a stable form
//!
//! With `c = cos w = n.axis`, `cs = cos sigma`, `ss = sin sigma`, Snyder's eq. 6 has three
//! cases: fully visible (`c >= ss`) `E = c ss^2`; fully below the horizon (`c <= -ss`) `E = 0`;
//! and the fillet in between, which he writes with `gamma = asin(cs / sin w)` and two arc sines.
//! Substituting `sin gamma = cs/s` and using `ss^2 s^2 - cs^2 c^2 = ss^2 - c^2`, the fillet
//! reduces to
//!
//! ```text
//! pi E = c ss^2 atan2(q, -cs c) - cs q + atan2(q, cs),     q = sqrt((ss - c)(ss + c))
//! ```
//!
//! which needs neither `w` nor `sin w`, is continuous at both ends (`q = 0` gives `c ss^2` at
//! `c = ss` and 0 at `c = -ss`), and has no division, so it is well conditioned everywhere,
//! including `sigma = pi/2` (`cs = 0`) and `sigma = 0`. It is the same integral; the tests check
//! it against quadrature of the definition, not against Snyder's form.
//!
//! ## The Hermite approximation
//!
//! Snyder replaces the fillet `w` in [pi/2 - sigma, pi/2 + sigma] by two cubic Hermite segments
//! split at `w = pi/2`, with the end values and slopes
//! `E(pi/2 - sigma) = ss^3`, `E' = -cs ss^2`; `E(pi/2) = (sigma - cs ss)/pi`, `E' = -ss^2/2`;
//! `E(pi/2 + sigma) = 0`, `E' = 0`. It needs `w = acos(c)` per sample. Its error against the
//! exact model is measured in `tests/cap.rs` and tabulated in the README.
//!
//! Beside it, [`CapLight::lambert_hermite_cos`] places the same two segments in `c = cos w`
//! (slopes `dE/dc = E'(w)/(-sin w)`): no arc cosine, and a smaller error for `sigma <= pi/4`.

use crate::unit::Direction;
use crate::{Error, Real, UnitVec3, Vec3};

/// Exact cap irradiance (normalized) from `c = n.axis`, `cs = cos sigma` (called only in the
/// fillet, the one case that needs it: a sphere's cap computes it there), `ss = sin sigma`.
/// (Cosines and sines, and below the arc tangents' angles: every factor at most pi, so the
/// products without fixed point's saturation tests, the same bits.)
#[inline]
pub(crate) fn cap_lambert_from_cos<T: Real>(c: T, cs: impl FnOnce() -> T, ss: T) -> T {
    if c >= ss {
        // `c >= ss >= 0` (`sin sigma`, validated): the products are not negative (in fixed
        // point their floors neither), so only the upper end of `clamp01` can act (`c` is
        // a dot product of unit vectors, 1 within rounding): the same bits.
        let e = T::mul_le2(T::mul_le2(c, ss), ss);
        if e < T::ONE {
            e
        } else {
            T::ONE
        }
    } else if c <= -ss {
        T::ZERO
    } else {
        cap_lambert_fillet(c, cs(), ss)
    }
}

/// The fillet case of [`cap_lambert_from_cos`] (`-ss < c < ss`). Not inlined: the outer
/// cases then need no more registers than a dot product and a product.
#[inline(never)]
fn cap_lambert_fillet<T: Real>(c: T, cs: T, ss: T) -> T {
    let m = T::mul_small;
    let q = m(ss - c, ss + c).sqrt();
    let pi_e = m(m(m(c, ss), ss), q.atan2(m(-cs, c))) - m(cs, q) + q.atan2(cs);
    m(pi_e, T::FRAC_1_PI).clamp01()
}

/// The Hermite approximation's value where it needs only `c = n.axis`: `c ss^2` where the
/// cap is fully visible (`c >= ss`), 0 where it is below the horizon (`c <= -ss`), `None` in
/// the fillet between. At the fillet's ends the cubics meet these values (`ss^3` and 0), so
/// where rounding puts `c` and the angle `w` on different sides of an end, the two answers
/// differ only by that rounding. Where the cap is fully visible, `c >= ss >= 0` and `ss2 >=
/// 0` keep the product from being negative (in fixed point its floor too), so only the upper
/// end of `clamp01` can act: the same values with one comparison fewer (Cortex-M4F f32
/// `cap_lambert_hermite` 53 -> 50 instructions). The one difference in bits: where `ss`
/// underflowed to 0 (a sphere's `r/d` below the smallest subnormal) and `c` is `-0`, the
/// answer is `-0` as [`cap_lambert_from_cos`]' is, where `clamp01` gave `+0`.
#[inline(always)]
pub(crate) fn outside_fillet<T: Real>(c: T, ss: T, ss2: T) -> Option<T> {
    if c >= ss {
        let e = T::mul_le2(c, ss2);
        Some(if e < T::ONE { e } else { T::ONE })
    } else if c <= -ss {
        Some(T::ZERO)
    } else {
        None
    }
}

/// The two Hermite cubics of Snyder's approximation for one `sigma`, as coefficients of
/// `g(y) = ((a y + b) y + c) y + d` on each segment, `y` in [0, 1].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct HermiteFillet<T> {
    sigma: T,
    ss2: T,
    lo: [T; 4],
    hi: [T; 4],
}

/// The same end conditions as cubics in `c = cos w`, on [-ss, 0] and [0, ss].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct HermiteFilletCos<T> {
    ss: T,
    ss2: T,
    lo: [T; 4],
    hi: [T; 4],
}

/// Cubic Hermite coefficients on [0, 1] from end values and end slopes (already scaled by the
/// interval length): Snyder's `a, b, c, d`.
#[inline]
fn hermite_coeffs<T: Real>(g0: T, g1: T, d0: T, d1: T) -> [T; 4] {
    let three = T::from_f64(3.0);
    [
        d1 + d0 - T::TWO * (g1 - g0),
        three * (g1 - g0) - d1 - T::TWO * d0,
        d0,
        g0,
    ]
}

impl<T: Real> HermiteFillet<T> {
    #[inline]
    pub(crate) fn new(sigma: T, cs: T, ss: T) -> Self {
        let ss2 = ss * ss;
        let h = sigma;
        let e_mid = (sigma - cs * ss) * T::FRAC_1_PI;
        let lo = hermite_coeffs(ss2 * ss, e_mid, -h * cs * ss2, -h * T::HALF * ss2);
        let hi = hermite_coeffs(e_mid, T::ZERO, -h * T::HALF * ss2, T::ZERO);
        HermiteFillet { sigma, ss2, lo, hi }
    }

    /// The approximation for the unit normal `n` around the unit `axis`; see
    /// [`outside_fillet`], which answers first, so the angle `w` (a cross product, a square
    /// root and an arc tangent) is computed only inside the fillet.
    #[inline(always)]
    pub(crate) fn eval_unit(&self, n: UnitVec3<T>, axis: &UnitVec3<T>, ss: T) -> T {
        let d = n.into_inner() - axis.into_inner();
        match outside_fillet(T::ONE - T::HALF * d.dot(d), ss, self.ss2) {
            Some(e) => e,
            None => {
                let n = n.into_inner();
                self.eval_in_fillet(n.x, n.y, n.z, axis)
            }
        }
    }

    /// [`HermiteFillet::eval`] at the angle between the unit normal `(x, y, z)` and `axis`.
    /// Not inlined: kept out of the caller, whose outer cases then need no more registers
    /// than a dot product. The normal's components one by one: a vector argument is passed in
    /// memory, which the caller would store before its test (Cortex-M4F f32 `cap_lambert_hermite`
    /// 3 instructions fewer).
    #[inline(never)]
    fn eval_in_fillet(&self, x: T, y: T, z: T, axis: &UnitVec3<T>) -> T {
        let n = UnitVec3::new_unchecked(Vec3::new(x, y, z));
        let (c, s) = crate::vec3::cos_sin_between(n, *axis);
        self.eval(c, s.atan2(c))
    }

    /// The approximation at `c = cos w`, `w` (both of the same direction).
    #[inline]
    pub(crate) fn eval(&self, c: T, w: T) -> T {
        let lo_end = T::FRAC_PI_2 - self.sigma;
        if w <= lo_end {
            return (c * self.ss2).clamp01();
        }
        if w >= T::FRAC_PI_2 + self.sigma || !(self.sigma > T::ZERO) {
            return T::ZERO;
        }
        let (k, y) = if w <= T::FRAC_PI_2 {
            (&self.lo, (w - lo_end) / self.sigma)
        } else {
            (&self.hi, (w - T::FRAC_PI_2) / self.sigma)
        };
        (((k[0] * y + k[1]) * y + k[2]) * y + k[3]).clamp01()
    }
}

impl<T: Real> HermiteFilletCos<T> {
    #[inline]
    pub(crate) fn new(sigma: T, cs: T, ss: T) -> Self {
        let ss2 = ss * ss;
        let ss3 = ss2 * ss;
        let e_mid = (sigma - cs * ss) * T::FRAC_1_PI;
        // dE/dc = E'(w)/(-sin w): ss^2 at c = ss, ss^2/2 at c = 0, 0 at c = -ss; the interval
        // length is ss.
        HermiteFilletCos {
            ss,
            ss2,
            lo: hermite_coeffs(T::ZERO, e_mid, T::ZERO, T::HALF * ss3),
            hi: hermite_coeffs(e_mid, ss3, T::HALF * ss3, ss3),
        }
    }

    /// The approximation at `c = cos w`.
    #[inline]
    pub(crate) fn eval(&self, c: T) -> T {
        if c >= self.ss {
            return (c * self.ss2).clamp01();
        }
        if c <= -self.ss || !(self.ss > T::ZERO) {
            return T::ZERO;
        }
        let (k, y) = if c < T::ZERO {
            (&self.lo, (c + self.ss) / self.ss)
        } else {
            (&self.hi, c / self.ss)
        };
        (((k[0] * y + k[1]) * y + k[2]) * y + k[3]).clamp01()
    }
}

/// A cap light: unit radiance within `sigma` of `axis` (an infinitely distant disc of fixed
/// angular size, e.g. the sun).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CapLight<T> {
    axis: UnitVec3<T>,
    sigma: T,
    cos_sigma: T,
    sin_sigma: T,
    hermite: HermiteFillet<T>,
    hermite_cos: HermiteFilletCos<T>,
}

impl<T: Real> CapLight<T> {
    /// A cap around `axis` (any length) of half-angle `sigma` in [0, pi/2].
    ///
    /// Computes `cos sigma`, `sin sigma` and the Hermite coefficients once, here.
    ///
    /// # Errors
    /// [`Error::NotFinite`] / [`Error::ZeroLength`] for `axis`; [`Error::NotFinite`] or
    /// [`Error::SigmaOutOfRange`] for `sigma`.
    pub fn new(axis: Vec3<T>, sigma: T) -> Result<Self, Error> {
        let axis = UnitVec3::try_new(axis, "axis")?;
        if !sigma.is_finite() {
            return Err(Error::NotFinite("sigma"));
        }
        if !(sigma >= T::ZERO && sigma <= T::FRAC_PI_2) {
            return Err(Error::SigmaOutOfRange);
        }
        let (cs, ss) = (sigma.cos().clamp01(), sigma.sin().clamp01());
        Ok(CapLight {
            axis,
            sigma,
            cos_sigma: cs,
            sin_sigma: ss,
            hermite: HermiteFillet::new(sigma, cs, ss),
            hermite_cos: HermiteFilletCos::new(sigma, cs, ss),
        })
    }

    /// The unit axis.
    pub fn axis(&self) -> Vec3<T> {
        self.axis.into_inner()
    }
    /// The unit axis, typed (for the Phong integrals).
    #[inline(always)]
    #[cfg(feature = "phong")]
    pub(crate) fn unit_axis(&self) -> UnitVec3<T> {
        self.axis
    }
    /// The half-angle sigma.
    pub fn sigma(&self) -> T {
        self.sigma
    }
    /// `(cos sigma, sin sigma)`, computed once by the constructor.
    pub fn cos_sin_sigma(&self) -> (T, T) {
        (self.cos_sigma, self.sin_sigma)
    }

    /// `[cap_lambert]`: exact Lambertian irradiance, normalized (in [0, 1]).
    ///
    /// Accuracy: measured below (f64 against the quadrature, the others against f64).
    /// Cost: 1 normalization (none for a [`UnitVec3`]) and 1 dot product; in
    /// the fillet (out of line) also 1 sqrt and 2 atan2: median 44 instructions a call on the
    /// Cortex-M4F in f32, 28 with a `UnitVec3`; 310 and 66 on the Cortex-M0 in `Fixed22`
    /// (QEMU, exact; 361 and 73 with the lit term's two products and the normalization's six
    /// from four 32-bit products each, not three, the crate-internal `mul_le2`, the same bits;
    /// 400 and 118 with the cosine's Q22 products, before it went through Q15:
    /// the sealed `cos_unit`, within 5.3e-5; 52 and 33, 405 and 120 with the fully lit term
    /// clamped at both ends; 449 and 163 with its products' saturation tests).
    /// Fallback: 0 for a zero or non-finite `n`.
    ///
    /// <!-- BEGIN acc-cap_lambert: target/accuracy/model-cap_lambert.md -->
    /// Measured: f64 within 1.2e-13 of its reference (the independent quadrature); against f64,
    /// f32 3.3e-7, Fast32 6.6e-6, Fixed22 2.9e-5; 326 486 cases in all (`docs/accuracy.md`).
    /// <!-- END acc-cap_lambert -->
    #[inline]
    pub fn lambert(&self, n: impl Direction<T>) -> T {
        match n.to_unit() {
            Some(n) => cap_lambert_from_cos(n.cos_to(self.axis), || self.cos_sigma, self.sin_sigma),
            None => T::ZERO,
        }
    }

    /// A variant of [`CapLight::lambert_hermite`] (not a spec model id): the same two Hermite
    /// segments with the same end values and slopes, but as cubics in `c = cos w` instead of
    /// `w`, so it needs no arc cosine (cost: 1 normalization, 1 dot product, 1 division, a
    /// cubic). Its max error against the exact model is smaller than Snyder's for small lights
    /// and larger above `3 pi/8` (where the slope condition at `c = -1` is wrong for a function
    /// linear in `c`): use it for small lights (lamps, the sun). Measured over w in [0, pi]
    /// (`tests/fixtures.rs`):
    ///
    /// <!-- BEGIN acc-hermite: target/accuracy/hermite.md -->
    /// | sigma | Snyder (cubics in w) | cubics in cos w (`lambert_hermite_cos`) |
    /// |---|---|---|
    /// | pi/64 | 4.2e-7 | 4.2e-7 |
    /// | pi/16 | 2.7e-5 | 2.7e-5 |
    /// | pi/8 | 2.2e-4 | 2.0e-4 |
    /// | pi/4 | 1.8e-3 | 7.4e-4 |
    /// | 3pi/8 | 5.5e-3 | 9.0e-3 |
    /// | pi/2 | 5.4e-3 | 7.4e-2 |
    /// <!-- END acc-hermite -->
    ///
    /// Fallback: 0 for a zero or non-finite `n`.
    #[inline]
    pub fn lambert_hermite_cos(&self, n: impl Direction<T>) -> T {
        match n.to_unit() {
            Some(n) => self
                .hermite_cos
                .eval(n.cos_to(self.axis).clamp(-T::ONE, T::ONE)),
            None => T::ZERO,
        }
    }

    /// `[cap_lambert_hermite]`: Snyder's two-segment Hermite approximation of
    /// [`CapLight::lambert`]; its error against the exact model is tabulated in the README.
    ///
    /// Cost: 1 normalization (none for a [`UnitVec3`]) and the chord's squared length
    /// `|n - axis|^2` (`c = 1 - |n - axis|^2/2`, accurate near 1); only in the fillet (out of
    /// line) also 1 cross product, 2 sqrt, 1 atan2 and a cubic: median 50 instructions a call
    /// on the Cortex-M4F in f32, 33 with a `UnitVec3`; 396 and 151 on the Cortex-M0 in
    /// `Fixed22` (QEMU, exact; 444 and 158 with four 32-bit products a product of factors
    /// up to 2, not three, the crate-internal `mul_le2`; before the fillet test, 179/158 and
    /// 1499/1167).
    /// Fallback: 0 for a zero or non-finite `n`.
    ///
    /// <!-- BEGIN acc-cap_lambert_hermite: target/accuracy/model-cap_lambert_hermite.md -->
    /// Measured: against f64, f32 2.5e-7, Fast32 5.8e-6, Fixed22 1.3e-6; 325 752 cases in all
    /// (`docs/accuracy.md`).
    /// <!-- END acc-cap_lambert_hermite -->
    #[inline]
    pub fn lambert_hermite(&self, n: impl Direction<T>) -> T {
        match n.to_unit() {
            Some(n) => self.hermite.eval_unit(n, &self.axis, self.sin_sigma),
            None => T::ZERO,
        }
    }
}

/// A spherical light of unit radiance: `radius` at `center`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereLight<T> {
    center: Vec3<T>,
    radius: T,
}

/// Per-sample cap of a sphere seen from `p`: its axis, `sin sigma` and `cos sigma` as
/// parts ([`SphereCap::cs`]), whose square root only the fillet, Phong and SH9 take.
pub(crate) struct SphereCap<T> {
    pub(crate) axis: UnitVec3<T>,
    pub(crate) ss: T,
    /// What `cos sigma` is computed from (`Real`'s sealed `sphere_ratios`, `sphere_cos`).
    cos_parts: [T; 3],
}

impl<T: Real> SphereCap<T> {
    /// `cos sigma` (at most 1: only rounding could take it above). Cost: a square root and a
    /// product, paid only by the callers that need it: a Lambert or Hermite sample outside
    /// the fillet does not (QEMU budget medians, the same values, with `Sealed::sphere_cos`'s
    /// parts: `sphere_lambert` on the Cortex-M4F in f32 99 -> 81, 93 -> 73 with a `UnitVec3`;
    /// on the Cortex-M0 in `Fixed22` 1 080 -> 857, 795 -> 571; Hermite 110 -> 94, 1 096 -> 863).
    #[inline(always)]
    pub(crate) fn cs(&self) -> T {
        T::sphere_cos(self.cos_parts).min(T::ONE)
    }

    /// `[sphere_lambert]` of this cap for the unit normal `n`.
    #[inline(always)]
    pub(crate) fn lambert(&self, n: UnitVec3<T>) -> T {
        cap_lambert_from_cos(n.cos_to(self.axis), || self.cs(), self.ss)
    }

    /// `[sphere_lambert_hermite]` of this cap for the unit normal `n`: outside the fillet
    /// from `c` alone ([`outside_fillet`]); inside it, sigma and the cubics are built here.
    #[inline(always)]
    pub(crate) fn lambert_hermite(&self, n: UnitVec3<T>) -> T {
        match outside_fillet(n.cos_to(self.axis), self.ss, self.ss * self.ss) {
            Some(e) => e,
            None => {
                let n = n.into_inner();
                self.hermite_in_fillet(n.x, n.y, n.z)
            }
        }
    }

    /// The fillet case of [`SphereCap::lambert_hermite`] for the unit normal `(x, y, z)`. Not
    /// inlined, and the normal's components one by one (see
    /// [`HermiteFillet::eval_unit`]).
    #[inline(never)]
    fn hermite_in_fillet(&self, x: T, y: T, z: T) -> T {
        let n = UnitVec3::new_unchecked(Vec3::new(x, y, z));
        let cs = self.cs();
        let sigma = self.ss.atan2(cs);
        let (c, s) = crate::vec3::cos_sin_between(n, self.axis);
        HermiteFillet::new(sigma, cs, self.ss).eval(c, s.atan2(c))
    }
}

impl<T: Real> SphereLight<T> {
    /// A sphere of `radius` > 0 at `center`.
    ///
    /// # Errors
    /// [`Error::NotFinite`] for either parameter, [`Error::RadiusNotPositive`],
    /// [`Error::OutOfRange`] for a coordinate or radius beyond [`Real::COORDINATE_LIMIT`].
    pub fn new(center: Vec3<T>, radius: T) -> Result<Self, Error> {
        center.check_position("center")?;
        if !radius.is_finite() {
            return Err(Error::NotFinite("radius"));
        }
        if !(radius > T::ZERO) {
            return Err(Error::RadiusNotPositive);
        }
        if !(radius.to_f64() <= T::COORDINATE_LIMIT) {
            return Err(Error::OutOfRange("radius"));
        }
        Ok(SphereLight { center, radius })
    }

    /// A sphere from parts the caller has validated: [`crate::world`]'s rescaled sphere
    /// (`radius` >= 0, coordinates within `[-4, 4]`; a radius rounded to 0 gives a cap of
    /// zero size, hence 0).
    #[inline(always)]
    pub(crate) fn from_parts(center: Vec3<T>, radius: T) -> Self {
        SphereLight { center, radius }
    }

    /// The centre.
    pub fn center(&self) -> Vec3<T> {
        self.center
    }
    /// The radius.
    pub fn radius(&self) -> T {
        self.radius
    }

    /// The cap the sphere subtends at `p` (eq. 7).
    ///
    /// # Errors
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] for `p`, [`Error::PointInsideSphere`].
    ///
    /// For the float types the check of `p` waits for a failed normalization: a NaN or
    /// infinite `p` makes `center - p` non-finite, which the normalization refuses, so a
    /// valid `p` costs no test of its own. Fixed point checks `p`'s range first.
    #[inline]
    pub(crate) fn cap_at(&self, p: Vec3<T>) -> Result<SphereCap<T>, Error> {
        self.cap_at_inlined(p)
    }

    /// [`SphereLight::cap_at`] for the plain per-sample calls: always inlined on targets with
    /// a hardware FPU (`eabihf`), where the `Result` then never reaches memory (Cortex-M4F
    /// f32 `sphere_lambert` 132 -> 109 instructions with a `Vec3` normal); elsewhere a hint
    /// only, as `cap_at`: on soft-float targets the inlined copies of every backend cost
    /// about 8 KiB of flash (the Cortex-M0 budget image) for a few percent.
    #[cfg_attr(target_abi = "eabihf", inline(always))]
    #[cfg_attr(not(target_abi = "eabihf"), inline)]
    fn cap_at_inlined(&self, p: Vec3<T>) -> Result<SphereCap<T>, Error> {
        let has_limit = T::COORDINATE_LIMIT < f64::MAX;
        if has_limit {
            p.check_position("p")?;
        }
        let c = self.center - p;
        // The direction, d, r/d and cos sigma = sqrt((d - r)(d + r))/d (see `sphere_ratios`:
        // one division for the floats, none for fixed point).
        let Some(([x, y, z], d, ss, cos_parts)) = T::sphere_ratios([c.x, c.y, c.z], self.radius)
        else {
            return Err(Self::no_cap_at(p));
        };
        let axis = Vec3::new(x, y, z);
        if !(d > self.radius) {
            return Err(Error::PointInsideSphere);
        }
        // 0 < r < d: both ratios are positive, and only rounding can take them above 1
        // (`sphere_ratios` keeps `ss` at most 1; `SphereCap::cs` clamps the other where it is
        // taken).
        Ok(SphereCap {
            axis: UnitVec3::new_unchecked(axis),
            ss,
            cos_parts,
        })
    }

    /// The error of [`SphereLight::cap_at`] when `center - p` has no direction: `p`'s own
    /// (not finite, out of range) if it has one, else [`Error::PointInsideSphere`].
    #[cold]
    #[inline(never)]
    fn no_cap_at(p: Vec3<T>) -> Error {
        match p.check_position("p") {
            Err(e) => e,
            Ok(_) => Error::PointInsideSphere,
        }
    }

    /// `[sphere_lambert]` with precise errors: see [`SphereLight::lambert`].
    ///
    /// # Errors
    /// [`Error::NotFinite`] for `p` or `n`, [`Error::ZeroLength`] for `n`,
    /// [`Error::PointInsideSphere`].
    pub fn try_lambert(&self, p: Vec3<T>, n: impl Direction<T>) -> Result<T, Error> {
        let cap = self.cap_at(p)?;
        Ok(cap.lambert(n.try_unit("n")?))
    }

    /// `[sphere_lambert]`: exact Lambertian irradiance at `p` with normal `n`, normalized.
    ///
    /// Accuracy: measured, below. Cost: 2 normalizations, 1 division (fixed point: no
    /// division, `sin sigma` from the normalization's reciprocal square root); in the
    /// fillet (out of line) also 2 sqrt (`cos sigma` among them) and 2 atan2: median 76 instructions a call on the
    /// Cortex-M4F in f32, 66 with a `UnitVec3`; 695 and 457 on the Cortex-M0 in `Fixed22`
    /// (QEMU, exact; 781 and 495 with the lit term's two products and the normalizations'
    /// products from four 32-bit products each, not three, the crate-internal `mul_le2`, the
    /// same bits; 857 and 571 before the cosine went through Q15, the sealed `cos_unit`,
    /// within 5.3e-5: 824 and 538; the positions' range test to one unsigned comparison a
    /// coordinate, the sealed `within_coordinate_limit`: 805 and 519; and `r/d`'s product
    /// without its saturation test, the same bits). Fallback: 0 for a point inside or on the
    /// sphere, or a zero or non-finite input.
    ///
    /// <!-- BEGIN acc-sphere_lambert: target/accuracy/model-sphere_lambert.md -->
    /// Measured: f64 within 4.4e-16 of its reference (the independent quadrature); against f64,
    /// f32 4.6e-7 (ill-conditioned: 1.7e-6), Fast32 6.4e-6 (ill-conditioned: 6.2e-6), Fixed22
    /// 2.6e-5; 80 588 cases in all (`docs/accuracy.md`).
    /// <!-- END acc-sphere_lambert -->
    #[inline]
    pub fn lambert(&self, p: Vec3<T>, n: impl Direction<T>) -> T {
        // Not through `try_lambert`: its `Result` would be returned in memory.
        match (self.cap_at_inlined(p), n.to_unit()) {
            (Ok(cap), Some(n)) => cap.lambert(n),
            _ => T::ZERO,
        }
    }

    /// `[sphere_lambert_hermite]` with precise errors: see [`SphereLight::lambert_hermite`].
    ///
    /// # Errors
    /// As [`SphereLight::try_lambert`].
    pub fn try_lambert_hermite(&self, p: Vec3<T>, n: impl Direction<T>) -> Result<T, Error> {
        let cap = self.cap_at(p)?;
        Ok(cap.lambert_hermite(n.try_unit("n")?))
    }

    /// `[sphere_lambert_hermite]`: Snyder's Hermite approximation with sigma from the sphere
    /// (the cubics are rebuilt per sample, since sigma changes with `p`).
    ///
    /// Cost: that of [`SphereLight::lambert`] outside the fillet (the value needs only
    /// `n.axis` there); in the fillet 2 atan2 and ~20 multiply-adds more.
    /// Fallback: as [`SphereLight::lambert`].
    ///
    /// <!-- BEGIN acc-sphere_lambert_hermite: target/accuracy/model-sphere_lambert_hermite.md -->
    /// Measured: against f64, f32 5.1e-7 (ill-conditioned: 1.6e-6), Fast32 8.9e-6
    /// (ill-conditioned: 9.2e-6), Fixed22 2.9e-5; 80 216 cases in all (`docs/accuracy.md`).
    /// <!-- END acc-sphere_lambert_hermite -->
    #[inline]
    pub fn lambert_hermite(&self, p: Vec3<T>, n: impl Direction<T>) -> T {
        // Not through `try_lambert_hermite`: its `Result` would be returned in memory.
        match (self.cap_at_inlined(p), n.to_unit()) {
            (Ok(cap), Some(n)) => cap.lambert_hermite(n),
            _ => T::ZERO,
        }
    }
}
