//! The [`Illuminant`](super::Illuminant) impl of the line light.

use super::*;
use crate::{Decay, LineLight};

impl<T: Real> Illuminant<T> for LineLight<T> {
    /// [`LineLight::lambert`] with [`Decay::InverseSquare`] (the physical law; Picott's
    /// `I_p k_d = 1` per unit of the segment's parameter, so a short segment approaches a
    /// point light of unit intensity with the inverse square law).
    #[inline]
    fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        grey(self.lambert(p, n, Decay::InverseSquare))
    }
    /// [`LineLight::phong_peak`]: Picott's peak of the lobe, not its integral.
    #[inline]
    fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
        grey(self.phong_peak(lobe, p, r))
    }
}
