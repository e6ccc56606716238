//! The [`Illuminant`](super::Illuminant) impl of the SH9 environment irradiance.

use super::*;
use crate::Sh9Irradiance;

impl<T: Real> Illuminant<T> for Sh9Irradiance<T> {
    /// [`Sh9Irradiance::irradiance`] divided by pi (so a unit-radiance environment gives 1,
    /// as the normalized models do). May be slightly negative where a measured
    /// environment's projection rings (not clamped, as the model). Cost: 30 multiply-adds.
    #[inline]
    fn diffuse(&self, _p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        self.irradiance(n).scale(T::FRAC_1_PI)
    }
    /// 0: the crate has no specular model for SH environments.
    #[inline]
    fn phong(&self, _lobe: &PhongLobe<T>, _p: Vec3<T>, _r: UnitVec3<T>) -> Rgb<T> {
        black()
    }
}
