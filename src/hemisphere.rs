//! Infinite hemisphere lights: constant and cosine weighted (Snyder section 2.1, eq. 3-5), the
//! CIE overcast sky (Snyder 2.1.3) and sky/ground hemisphere lighting (June eq. 20.7).
//!
//! With `w` the angle between the normal `n` and the hemisphere's `axis` (the zenith),
//! `c = cos w = n.axis`, `s = sin w`:
//!
//! - `[hemi_const]` radiance 1 where `u.axis >= 0`: `E = (1 + c)/2` (eq. 4).
//! - `[hemi_cos]` radiance `(u.axis)+`: `E = 2/(3 pi) (s^3 + c (pi - w + s c))` (eq. 5).
//! - `[sky_overcast]` radiance `C (1 + 2 u.zenith)/3`: `E = C/3 hemi_const + 2C/3 hemi_cos`.
//! - `[sky_ground]` radiance `sky` above the horizon of `up`, `ground` below:
//!   `E = sky (1 + c)/2 + ground (1 - c)/2`, exact because the two hemispheres tile the sphere.
//!
//! `w` is computed as `atan2(|n x axis|, n.axis)`, accurate at both ends of [0, pi], where
//! `acos(n.axis)` loses half its digits.

use crate::unit::{Direction, LightAxis};
use crate::vec3::angle_to;
use crate::{Error, Real, Rgb, UnitVec3, Vec3};

/// An infinite hemisphere light around `axis` (the zenith) of unit radiance, constant or
/// cosine weighted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HemisphereLight<T> {
    axis: LightAxis<T>,
}

impl<T: Real> HemisphereLight<T> {
    /// A hemisphere around `axis` (any length; normalized here).
    ///
    /// # Errors
    /// [`Error::NotFinite`] or [`Error::ZeroLength`] for a bad `axis`.
    pub fn new(axis: Vec3<T>) -> Result<Self, Error> {
        Ok(HemisphereLight {
            axis: LightAxis::new(UnitVec3::try_new(axis, "axis")?),
        })
    }

    /// The unit axis.
    pub fn axis(&self) -> Vec3<T> {
        self.axis.unit().into_inner()
    }
    /// The unit axis, typed (for the Phong integrals).
    #[inline(always)]
    #[cfg(feature = "phong")]
    pub(crate) fn unit_axis(&self) -> UnitVec3<T> {
        self.axis.unit()
    }

    /// `[hemi_const]`: Lambertian irradiance (normalized, in [0, 1]) from the constant-weighted
    /// hemisphere, `(1 + n.axis)/2` (Snyder eq. 4).
    ///
    /// Accuracy: 2 ULP plus the normalization of `n`; in `Fixed22` the cosine is taken
    /// through Q15 (within 5.3e-5, so the value within 2.7e-5 plus the normalization's
    /// rounding). Cost: 1 normalization (none for a [`UnitVec3`]), 1 dot product: 44
    /// instructions a call on the Cortex-M4F in f32, 30 with a `UnitVec3`; 284 and 40 on the
    /// Cortex-M0 in `Fixed22` (QEMU, exact; 376 and 94 with the cosine's Q22 products, 339
    /// and 52 with the axis rounded to Q15 on every call instead of once by `new`, 332 and 45
    /// with the halving, and the normalization's six products, from four 32-bit products,
    /// not three: the crate-internal `mul_le2`; 297 before the rescaling's exponent came from
    /// comparisons, `fixed22::normalize::top_exponent`).
    /// Fallback: 0 for a zero or non-finite `n`.
    ///
    /// <!-- BEGIN acc-hemi_const: target/accuracy/model-hemi_const.md -->
    /// Measured: f64 within 5.6e-16 of its reference (the independent quadrature); against f64,
    /// f32 1.6e-7, Fast32 1.6e-7, Fixed22 2.0e-5; 68 626 cases in all (`docs/accuracy.md`).
    /// <!-- END acc-hemi_const -->
    #[inline]
    pub fn lambert_const(&self, n: impl Direction<T>) -> T {
        match n.to_unit() {
            // 1/2 times at most 2 (within rounding): `mul_le2`, the bits of `*`.
            Some(n) => T::mul_le2(T::HALF, T::ONE + self.axis.cos_from(n)).clamp01(),
            None => T::ZERO,
        }
    }

    /// `[hemi_cos]`: Lambertian irradiance (normalized, in [0, 2/3]) from the cosine-weighted
    /// hemisphere (Snyder eq. 5).
    ///
    /// Accuracy: measured below (f64 against the quadrature of tests/hemisphere.rs).
    /// Cost: 1 normalization, 1 cross product, 2 sqrt, 1 atan2, ~12 multiply-adds.
    /// Fallback: 0 for a zero or non-finite `n`.
    ///
    /// <!-- BEGIN acc-hemi_cos: target/accuracy/model-hemi_cos.md -->
    /// Measured: f64 within 6.7e-16 of its reference (the independent quadrature); against f64,
    /// f32 1.5e-7, Fast32 2.5e-6, Fixed22 7.4e-7; 68 626 cases in all (`docs/accuracy.md`).
    /// <!-- END acc-hemi_cos -->
    #[inline]
    pub fn lambert_cos(&self, n: impl Direction<T>) -> T {
        match angle_to(n, self.axis.unit()) {
            Some((c, s, w)) => hemi_cos_from_angle(c, s, w),
            None => T::ZERO,
        }
    }
}

/// Snyder eq. 5 from `cos w`, `sin w`, `w`.
#[inline]
pub(crate) fn hemi_cos_from_angle<T: Real>(c: T, s: T, w: T) -> T {
    let k = T::from_f64(2.0 / (3.0 * core::f64::consts::PI));
    (k * (s * s * s + c * ((T::PI - w) + s * c))).clamp(T::ZERO, T::from_f64(2.0 / 3.0))
}

/// The CIE standard overcast sky: radiance `C (1 + 2 u.zenith)/3` above the horizon
/// (Snyder 2.1.3, after Nishita and Nakamae 1986).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OvercastSky<T> {
    sky: HemisphereLight<T>,
    zenith_luminance: T,
}

impl<T: Real> OvercastSky<T> {
    /// A sky with zenith direction `zenith` (any length) and zenith luminance `c`.
    ///
    /// # Errors
    /// [`Error::NotFinite`] / [`Error::ZeroLength`] for `zenith`, [`Error::NotFinite`] for `c`.
    pub fn new(zenith: Vec3<T>, c: T) -> Result<Self, Error> {
        if !c.is_finite() {
            return Err(Error::NotFinite("c"));
        }
        Ok(OvercastSky {
            sky: HemisphereLight::new(zenith)?,
            zenith_luminance: c,
        })
    }

    /// The unit zenith direction.
    pub fn zenith(&self) -> Vec3<T> {
        self.sky.axis.unit().into_inner()
    }
    /// The zenith luminance `C`.
    pub fn zenith_luminance(&self) -> T {
        self.zenith_luminance
    }

    /// `[sky_overcast]`: `C/3 hemi_const + 2C/3 hemi_cos` (not clamped: scales with `C`).
    ///
    /// Accuracy: as [`HemisphereLight::lambert_cos`], times `C`. Cost: that of `lambert_cos`
    /// plus 4 multiply-adds. Fallback: 0 for a zero or non-finite `n` (or an overflowing `C`).
    ///
    /// <!-- BEGIN acc-sky_overcast: target/accuracy/model-sky_overcast.md -->
    /// Measured: f64 within 1.1e-15 of its reference (the independent quadrature); against f64,
    /// f32 1.7e-7, Fast32 1.7e-6, Fixed22 3.6e-6; 68 626 cases in all (`docs/accuracy.md`).
    /// <!-- END acc-sky_overcast -->
    #[inline]
    pub fn lambert(&self, n: impl Direction<T>) -> T {
        match angle_to(n, self.sky.axis.unit()) {
            Some((c, s, w)) => {
                let third = T::from_f64(1.0 / 3.0);
                let e_const = (T::HALF * (T::ONE + c)).clamp01();
                let e_cos = hemi_cos_from_angle(c, s, w);
                (self.zenith_luminance * third * (e_const + T::TWO * e_cos)).finite_or_zero()
            }
            None => T::ZERO,
        }
    }
}

/// Hemisphere lighting: `sky` colour over the upper hemisphere of `up`, `ground` below
/// (June section 20.2, eq. 20.7).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkyGround<T> {
    up: LightAxis<T>,
    sky: Rgb<T>,
    ground: Rgb<T>,
    /// `(sky + ground)/2` and `(sky - ground)/2`, each as `sky/2 +- ground/2` (no overflow):
    /// the irradiance is `mid + half c`.
    mid: Rgb<T>,
    half: Rgb<T>,
    /// Every channel of `sky` and `ground` within `1e30` in magnitude: then `mid + half c`
    /// for `|c| <= 1` cannot overflow, and the per-sample finiteness test is skipped.
    bounded: bool,
}

impl<T: Real> SkyGround<T> {
    /// Sky/ground light with `up` (any length), `sky` and `ground` radiances.
    ///
    /// # Errors
    /// [`Error::NotFinite`] / [`Error::ZeroLength`] for `up`; [`Error::NotFinite`] for a colour.
    pub fn new(up: Vec3<T>, sky: Rgb<T>, ground: Rgb<T>) -> Result<Self, Error> {
        let (sky, ground) = (sky.check_finite("sky")?, ground.check_finite("ground")?);
        let (s, g) = (sky.scale(T::HALF), ground.scale(T::HALF));
        Ok(SkyGround {
            up: LightAxis::new(UnitVec3::try_new(up, "up")?),
            sky,
            ground,
            mid: Rgb::new(s.r + g.r, s.g + g.g, s.b + g.b),
            half: Rgb::new(s.r - g.r, s.g - g.g, s.b - g.b),
            bounded: [sky.r, sky.g, sky.b, ground.r, ground.g, ground.b]
                .iter()
                .all(|x| x.abs() <= T::from_f64(1e30)),
        })
    }

    /// The unit up direction.
    pub fn up(&self) -> Vec3<T> {
        self.up.unit().into_inner()
    }
    /// The sky radiance (the hemisphere around `up`).
    pub fn sky(&self) -> Rgb<T> {
        self.sky
    }
    /// The ground radiance (the hemisphere around `-up`).
    pub fn ground(&self) -> Rgb<T> {
        self.ground
    }

    /// `[sky_ground]`: `sky (1 + n.up)/2 + ground (1 - n.up)/2` per channel: exact for this
    /// radiance (the two hemisphere terms are Snyder eq. 4 for `up` and `-up`).
    ///
    /// Accuracy: 3 ULP of the largest colour plus the normalization of `n`; in `Fixed22` the
    /// cosine is taken through Q15 and kept there (within 6.9e-5, times `|sky - ground|/2`:
    /// the sealed `mix_by_cos`). Cost: 1 normalization (none for a [`UnitVec3`]), 1 dot
    /// product, 3 multiply-adds: 59 instructions a call on the Cortex-M4F in f32, 45 with a
    /// `UnitVec3`; 327 and 90 on the Cortex-M0 in `Fixed22` (QEMU, exact; 340 before the
    /// rescaling's exponent came from comparisons, `fixed22::normalize::top_exponent`; 371 with the
    /// normalization's six products from four 32-bit products, not three; 383 and 102 with
    /// the axis rounded to Q15 on every call and the sums' saturation tests, which `mid` and
    /// `half` make unreachable; 456 and 170 with
    /// the cosine and the products in Q22; before, the products by `c` skipped the saturation
    /// test that a factor of at most 1 never needs, through the crate-internal `mul_unit`;
    /// and the finiteness test of the result is skipped for radiances within 1e30, which
    /// cannot overflow).
    /// Fallback: black for a zero or non-finite `n`.
    ///
    /// <!-- BEGIN acc-sky_ground: target/accuracy/model-sky_ground.md -->
    /// Measured: f64 within 6.7e-16 of its reference (the independent quadrature); against f64,
    /// f32 1.3e-7, Fast32 1.3e-7, Fixed22 2.2e-5; 205 878 cases in all (`docs/accuracy.md`).
    /// <!-- END acc-sky_ground -->
    #[inline]
    pub fn irradiance(&self, n: impl Direction<T>) -> Rgb<T> {
        match n.to_unit() {
            Some(n) => {
                // sky (1 + c)/2 + ground (1 - c)/2 = mid + half c: one multiply-add a channel,
                // the cosine clamped to [-1, 1], `mid` and `half` the sum and the difference of
                // `sky/2` and `ground/2` (`new`): the sealed `mix_by_cos`.
                let (m, h) = (self.mid, self.half);
                let [r, g, b] = T::mix_by_cos(
                    [m.r, m.g, m.b],
                    [h.r, h.g, h.b],
                    n.array(),
                    self.up.prepared(),
                );
                let e = Rgb::new(r, g, b);
                // Only radiances beyond 1e30 can round a channel past the type's range.
                if self.bounded {
                    e
                } else {
                    e.finite_or_zero()
                }
            }
            None => Rgb::splat(T::ZERO),
        }
    }
}
