//! The [`Illuminant`](super::Illuminant) impl of the parallelogram light (Picott's peak
//! approximations).

use super::*;
use crate::polygon::for_each_clipped_edge;
use crate::ParallelogramLight;

impl<T: Real> Illuminant<T> for ParallelogramLight<T> {
    /// `[polygon_lambert]` of the four corners (the parallelogram is validated at
    /// construction, so no polygon is built per sample): accuracy and cost those of
    /// [`crate::PolygonLight::lambert`] for a quad. 0 in the light's plane, and for a
    /// non-finite `p` or one beyond [`Real::COORDINATE_LIMIT`] (fixed point), as
    /// [`crate::PolygonLight::lambert`] answers.
    #[inline]
    fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        let n = n.into_inner();
        // (The edge terms' products rely on it: `polygon::edge::offset_products`.)
        if p.check_position("p").is_err() {
            return black();
        }
        let verts = self.vertices();
        let d = p - verts[0];
        if !(self.normal().dot(d).abs() > T::from_f64(4.0) * T::EPSILON * d.max_abs()) {
            return black();
        }
        let mut sum = T::ZERO;
        for_each_clipped_edge(
            &verts,
            p,
            n,
            T::ZERO,
            #[inline(always)]
            |e| sum += e.lambert_term(n),
        );
        grey((sum.abs() * T::FRAC_1_TAU).clamp01())
    }
    /// [`ParallelogramLight::phong_peak`]: Picott's peak of the lobe, not its integral.
    #[inline]
    fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
        grey(self.phong_peak(lobe, p, r))
    }
}
