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
    /// Both terms with `p`'s checks and its test against the polygon's plane done once
    /// (the same bits as the two calls).
    #[cfg(feature = "phong")]
    #[inline]
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
        // The vertices' unit directions from `p`, each normalized once for both terms.
        let mut dirs = VertexDirs::<T, N>::new();
        (
            grey(
                self.lambert_at_with(p, n, plane, &mut dirs)
                    .unwrap_or(T::ZERO),
            ),
            grey(
                self.phong_at_with(lobe, p, r, plane, &mut dirs)
                    .unwrap_or(T::ZERO),
            ),
        )
    }
}
