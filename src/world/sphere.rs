//! [`WorldSphereLight`]: a sphere light in world coordinates.

use super::{
    magnitudes, origin, q60_scaled, q60_shift, q60_vec3_scaled, WorldPoint, RAW_LIMIT, SCALE,
};
use crate::unit::Direction;
#[cfg(feature = "phong")]
use crate::PhongLobe;
use crate::{Error, Real, SphereLight};
use core::marker::PhantomData;

/// A spherical light of unit radiance in world coordinates (see [the module](super)): its
/// models computed in `T` on the sphere as seen from each `p`, translated and scaled by a
/// power of two into the kernels' range. The same models and fallbacks as [`SphereLight`],
/// with no range limit below `2^30` units on any backend.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorldSphereLight<T> {
    center: WorldPoint,
    /// The radius in units of `2^-32`, `1 ..< 2^62`.
    radius: i64,
    kernel: PhantomData<T>,
}

impl<T: Real> WorldSphereLight<T> {
    /// A sphere of `radius` world units (rounded to a multiple of `2^-32`) at `center`.
    ///
    /// # Errors
    /// [`Error::NotFinite`] (`"radius"`), [`Error::RadiusNotPositive`] (also a radius that
    /// rounds to 0), [`Error::OutOfRange`] (`"radius"`, `2^30` or more).
    pub fn new(center: WorldPoint, radius: f64) -> Result<Self, Error> {
        if !radius.is_finite() {
            return Err(Error::NotFinite("radius"));
        }
        let bits = libm::round(radius * SCALE);
        if !(bits >= 1.0) {
            return Err(Error::RadiusNotPositive);
        }
        if !(bits < RAW_LIMIT as f64) {
            return Err(Error::OutOfRange("radius"));
        }
        Ok(WorldSphereLight {
            center,
            radius: bits as i64,
            kernel: PhantomData,
        })
    }

    /// The centre.
    pub fn center(&self) -> WorldPoint {
        self.center
    }

    /// The radius in world units.
    pub fn radius(&self) -> f64 {
        self.radius as f64 / SCALE
    }

    /// The sphere as seen from `p`, in `T`: `center - p` and the radius, scaled by the power of
    /// two that puts the largest of them in `[2, 4]`. Its models at the origin are this
    /// light's models at `p`.
    pub fn local(&self, p: WorldPoint) -> SphereLight<T> {
        let d = self.center.minus(p);
        // (`scale_to_q60` and `q60_vec3` without the shifted copies: the same values.)
        let k = q60_shift(magnitudes(d) | self.radius.unsigned_abs());
        SphereLight::from_parts(q60_vec3_scaled(d, k), q60_scaled(self.radius, k))
    }

    /// `[sphere_lambert]` with precise errors: see [`SphereLight::try_lambert`] (no range
    /// error for `p`: a [`WorldPoint`] is always in range).
    ///
    /// # Errors
    /// [`Error::NotFinite`] or [`Error::ZeroLength`] for `n`, [`Error::PointInsideSphere`].
    pub fn try_lambert(&self, p: WorldPoint, n: impl Direction<T>) -> Result<T, Error> {
        self.local(p).try_lambert(origin(), n)
    }

    /// `[sphere_lambert]` at `p`: [`SphereLight::lambert`] of [`WorldSphereLight::local`].
    /// Fallback: 0 for a point inside or on the sphere, or a zero or non-finite `n`.
    /// Accuracy and cost: [the module docs](super) (measured by `tests/world.rs`).
    #[inline]
    pub fn lambert(&self, p: WorldPoint, n: impl Direction<T>) -> T {
        self.local(p).lambert(origin(), n)
    }

    /// `[sphere_lambert_hermite]` with precise errors: see [`WorldSphereLight::try_lambert`].
    ///
    /// # Errors
    /// As [`WorldSphereLight::try_lambert`].
    pub fn try_lambert_hermite(&self, p: WorldPoint, n: impl Direction<T>) -> Result<T, Error> {
        self.local(p).try_lambert_hermite(origin(), n)
    }

    /// `[sphere_lambert_hermite]` at `p`: [`SphereLight::lambert_hermite`] of
    /// [`WorldSphereLight::local`]. Fallback: as [`WorldSphereLight::lambert`].
    /// Accuracy and cost: [the module docs](super) (measured by `tests/world.rs`).
    #[inline]
    pub fn lambert_hermite(&self, p: WorldPoint, n: impl Direction<T>) -> T {
        self.local(p).lambert_hermite(origin(), n)
    }

    /// `[phong_sphere]` with precise errors: see [`SphereLight::try_phong`].
    ///
    /// # Errors
    /// [`Error::NotFinite`] or [`Error::ZeroLength`] for `r`, [`Error::PointInsideSphere`].
    #[cfg(feature = "phong")]
    pub fn try_phong(
        &self,
        lobe: &PhongLobe<T>,
        p: WorldPoint,
        r: impl Direction<T>,
    ) -> Result<T, Error> {
        self.local(p).try_phong(lobe, origin(), r)
    }

    /// `[phong_sphere]` at `p`: [`SphereLight::phong`] of [`WorldSphereLight::local`].
    /// Fallback: as [`WorldSphereLight::lambert`].
    /// Accuracy and cost: [the module docs](super) (measured by `tests/world.rs`).
    #[cfg(feature = "phong")]
    #[inline]
    pub fn phong(&self, lobe: &PhongLobe<T>, p: WorldPoint, r: impl Direction<T>) -> T {
        self.local(p).phong(lobe, origin(), r)
    }
}
