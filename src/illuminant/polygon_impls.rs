//! The [`Illuminant`](super::Illuminant) impl of the polygon light (both terms in one call).

use super::*;
#[cfg(feature = "phong")]
use crate::polygon::VertexDirs;
use crate::PolygonLight;

impl<T: Real, const N: usize> Illuminant<T> for PolygonLight<T, N> {
    /// [`PolygonLight::lambert`].
    #[inline]
    fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        grey(self.lambert(p, n))
    }
    /// [`PolygonLight::phong`] (`phong` feature; 0 without it).
    #[inline]
    fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
        #[cfg(feature = "phong")]
        {
            grey(PolygonLight::phong(self, lobe, p, r))
        }
        #[cfg(not(feature = "phong"))]
        {
            let _ = (lobe, p, r);
            black()
        }
    }
    inline_always_with_fpu! {
        /// Both terms with `p`'s checks and its test against the polygon's plane done once
        /// (the same bits as the two calls).
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
            if p.check_position("p").is_err() {
                return (black(), black());
            }
            let plane = self.in_plane(p);
            // Fixed point: the vertices' unit directions from `p` for the Phong term, each
            // normalized once for its negligibility test and its walk. (The Lambert term takes
            // its own, in 16-bit form: `Sealed::unit3_q15`. The floats' Lambert term takes
            // none, so only their Phong walk would ask: the cache would cost them and save
            // nothing; measured on the Cortex-M4F, a per-pixel frame 4.8 % longer with it.)
            if T::RESOLUTION > T::ZERO {
                let mut dirs = VertexDirs::<T, N>::new();
                let d = self.lambert_at(p, n, plane);
                let s = self.phong_at_with(lobe, p, r, plane, &mut dirs);
                (grey(d.unwrap_or(T::ZERO)), grey(s.unwrap_or(T::ZERO)))
            } else {
                (
                    grey(self.lambert_at(p, n, plane).unwrap_or(T::ZERO)),
                    grey(self.phong_at(lobe, p, r, plane).unwrap_or(T::ZERO)),
                )
            }
        }
    }
}
