//! The [`Illuminant`](super::Illuminant) impls of the cap and sphere lights.

use super::*;
use crate::{CapLight, SphereLight};

impl<T: Real> Illuminant<T> for CapLight<T> {
    /// [`CapLight::lambert`].
    #[inline]
    fn diffuse(&self, _p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        grey(self.lambert(n))
    }
    /// [`CapLight::phong`] (`phong` feature; 0 without it).
    #[inline]
    fn phong(&self, lobe: &PhongLobe<T>, _p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
        #[cfg(feature = "phong")]
        {
            grey(CapLight::phong(self, lobe, r))
        }
        #[cfg(not(feature = "phong"))]
        {
            let _ = (lobe, r);
            black()
        }
    }
}

impl<T: Real> Illuminant<T> for SphereLight<T> {
    /// [`SphereLight::lambert`] (0 inside the sphere).
    #[inline]
    fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        grey(self.lambert(p, n))
    }
    /// [`SphereLight::phong`] (`phong` feature; 0 without it).
    #[inline]
    fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
        #[cfg(feature = "phong")]
        {
            grey(SphereLight::phong(self, lobe, p, r))
        }
        #[cfg(not(feature = "phong"))]
        {
            let _ = (lobe, p, r);
            black()
        }
    }
    inline_always_with_fpu! {
        /// The cap the sphere subtends at `p`, computed once for both terms (the same bits
        /// as the two calls).
        /// (Always inlined with an FPU, only hinted on soft-float targets: see
        /// `scene::Entry::diffuse_and_phong`.)
        #[cfg(feature = "phong")]
        fn diffuse_and_phong(
            &self,
            lobe: &PhongLobe<T>,
            p: Vec3<T>,
            n: UnitVec3<T>,
            r: UnitVec3<T>,
        ) -> (Rgb<T>, Rgb<T>) {
            match self.cap_at(p) {
                Ok(cap) => {
                    let (diffuse, specular) = cap.lambert_and_phong(lobe, n, r);
                    (grey(diffuse), grey(specular))
                }
                Err(_) => (black(), black()),
            }
        }
    }
}
