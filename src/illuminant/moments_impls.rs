//! Arvo's directional luminaire as a light ([`DirectionalLuminaire`]) and its
//! [`Illuminant`](super::Illuminant) impl.

use super::*;
use crate::{Error, PolygonLight};

/// Arvo's directional luminaire (6.1): a polygon emitting `((-u).axis)+^m` toward `-u`, as
/// a light. Its diffuse term is [`PolygonLight::directional_luminaire`] divided by pi (so
/// `m = 0` is the polygon's normalized Lambert irradiance).
#[derive(Clone, Debug, PartialEq)]
pub struct DirectionalLuminaire<T, const N: usize = 8> {
    polygon: PolygonLight<T, N>,
    axis: Vec3<T>,
    m: u32,
}

impl<T: Real, const N: usize> DirectionalLuminaire<T, N> {
    /// The luminaire `polygon` emitting mostly along `axis` (any length) with order `m`.
    ///
    /// # Errors
    /// [`Error::NotFinite`] / [`Error::ZeroLength`] (`"axis"`),
    /// [`Error::ExponentOutOfRange`] for `m > MAX_EXPONENT`.
    pub fn new(polygon: PolygonLight<T, N>, axis: Vec3<T>, m: u32) -> Result<Self, Error> {
        if m > crate::lobe::MAX_EXPONENT {
            return Err(Error::ExponentOutOfRange);
        }
        Ok(DirectionalLuminaire {
            polygon,
            axis: axis.try_normalize("axis")?,
            m,
        })
    }
}

impl<T: Real, const N: usize> Illuminant<T> for DirectionalLuminaire<T, N> {
    /// [`PolygonLight::directional_luminaire`] / pi, in [0, 1]: accuracy and cost its.
    #[inline]
    fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        grey((self.polygon.directional_luminaire(p, n, self.axis, self.m) * T::FRAC_1_PI).clamp01())
    }
    /// 0: the luminaire's glossy reflection is a property of the surface, see
    /// [`PolygonLight::glossy_reflection`].
    #[inline]
    fn phong(&self, _lobe: &PhongLobe<T>, _p: Vec3<T>, _r: UnitVec3<T>) -> Rgb<T> {
        black()
    }
}
