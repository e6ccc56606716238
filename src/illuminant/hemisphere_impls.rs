//! The [`Illuminant`](super::Illuminant) impls of the hemisphere lights (the hemisphere, the
//! overcast sky, sky and ground).

use super::*;
use crate::{HemisphereLight, OvercastSky, SkyGround};

impl<T: Real> Illuminant<T> for HemisphereLight<T> {
    /// [`HemisphereLight::lambert_const`] (the constant-weighted hemisphere).
    #[inline]
    fn diffuse(&self, _p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        grey(self.lambert_const(n))
    }
    /// [`HemisphereLight::phong_const`] (`phong` feature; 0 without it).
    #[inline]
    fn phong(&self, lobe: &PhongLobe<T>, _p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
        #[cfg(feature = "phong")]
        {
            grey(self.phong_const(lobe, r))
        }
        #[cfg(not(feature = "phong"))]
        {
            let _ = (lobe, r);
            black()
        }
    }
}

impl<T: Real> Illuminant<T> for OvercastSky<T> {
    /// [`OvercastSky::lambert`].
    #[inline]
    fn diffuse(&self, _p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        grey(self.lambert(n))
    }
    /// `C/3 phong_hemi_const + 2C/3 phong_hemi_cos` about the zenith: exact for the CIE
    /// overcast radiance, which is that sum of the two hemisphere radiances. Cost: both
    /// hemisphere Phong models (`phong` feature; 0 without it).
    #[inline]
    fn phong(&self, lobe: &PhongLobe<T>, _p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
        #[cfg(feature = "phong")]
        {
            let Ok(h) = HemisphereLight::new(self.zenith()) else {
                return black();
            };
            let third = T::from_f64(1.0 / 3.0);
            let c = self.zenith_luminance();
            grey(
                (c * third * (h.phong_const(lobe, r) + T::TWO * h.phong_cos(lobe, r)))
                    .finite_or_zero(),
            )
        }
        #[cfg(not(feature = "phong"))]
        {
            let _ = (lobe, r);
            black()
        }
    }
}

impl<T: Real> Illuminant<T> for SkyGround<T> {
    /// [`SkyGround::irradiance`].
    #[inline]
    fn diffuse(&self, _p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        self.irradiance(n)
    }
    /// `sky phong_hemi_const(up) + ground phong_hemi_const(-up)`: exact for this radiance
    /// (the two hemispheres tile the sphere). Cost: two hemisphere Phong models (`phong`
    /// feature; 0 without it).
    #[inline]
    fn phong(&self, lobe: &PhongLobe<T>, _p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
        #[cfg(feature = "phong")]
        {
            let (Ok(up), Ok(down)) = (
                HemisphereLight::new(self.up()),
                HemisphereLight::new(-self.up()),
            ) else {
                return black();
            };
            self.sky()
                .scale(up.phong_const(lobe, r))
                .add(self.ground().scale(down.phong_const(lobe, r)))
                .finite_or_zero()
        }
        #[cfg(not(feature = "phong"))]
        {
            let _ = (lobe, r);
            black()
        }
    }
}
