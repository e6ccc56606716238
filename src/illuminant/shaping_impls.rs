//! A light shaped by an uberlight factor ([`Shaped`]) and its [`Illuminant`](super::Illuminant) impl.

use super::*;
use crate::Uberlight;

/// A light shaped by an [`Uberlight`] factor (June 20.5): both terms of `light` times
/// [`Uberlight::factor`] at the shading point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shaped<T, L> {
    /// The light.
    pub light: L,
    /// The shaping factor (frame, superellipse, distance falloff).
    pub shape: Uberlight<T>,
}

impl<T: Real, L: Illuminant<T>> Illuminant<T> for Shaped<T, L> {
    /// The light's diffuse term times the factor (skipped where the factor is 0). Cost:
    /// [`Uberlight::factor`] plus the light's.
    #[inline]
    fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        let f = self.shape.factor(p);
        if !(f > T::ZERO) {
            return black();
        }
        self.light.diffuse(p, n).scale(f).finite_or_zero()
    }
    /// The light's Phong term times the factor (skipped where the factor is 0).
    #[inline]
    fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
        let f = self.shape.factor(p);
        if !(f > T::ZERO) {
            return black();
        }
        self.light.phong(lobe, p, r).scale(f).finite_or_zero()
    }
}
