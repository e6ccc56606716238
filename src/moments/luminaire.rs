//! The luminaire and glossy models built on the moments: `[directional_luminaire]`,
//! `[glossy_reflection]` and `[glossy_transmission]` (Arvo sections 6.2 and 6.3; the method in
//! the module docs of [`crate::moments`]).

use super::check_m;
use crate::polygon::PolygonLight;
use crate::unit::Direction;
use crate::{Error, Real, Vec3};

impl<T: Real, const N: usize> PolygonLight<T, N> {
    /// `[directional_luminaire]` with precise errors: see
    /// [`PolygonLight::directional_luminaire`].
    ///
    /// # Errors
    /// [`Error::NotFinite`] for `p`, `n` or `axis`, [`Error::ZeroLength`] for `n` or `axis`,
    /// [`Error::ExponentOutOfRange`] for `m > MAX_EXPONENT` (255 for [`crate::Fixed22`]).
    pub fn try_directional_luminaire(
        &self,
        p: Vec3<T>,
        n: impl Direction<T>,
        axis: Vec3<T>,
        m: u32,
    ) -> Result<T, Error> {
        check_m::<T>(m)?;
        if !p.is_finite() {
            return Err(Error::NotFinite("p"));
        }
        let n = n.try_unit("n")?.into_inner();
        let axis = axis.try_normalize("axis")?;
        Ok(self.clipped_moment_sum(p, -axis, n, m) / T::from_u32(m + 2))
    }

    /// `[directional_luminaire]`: the irradiance (not divided by pi) at `p` with normal `n`
    /// from the polygon emitting `((-u).axis)+^m` toward `-u`:
    /// `integral over A of ((-u).axis)+^m (n.u)+ du` (Arvo 6.1), in [0, pi].
    ///
    /// Accuracy: see `tests/moments/`. Cost: that of [`PolygonLight::double_axis_moment`] on
    /// the ring clipped to two planes (at most about twice as many arcs), plus the clipping
    /// (a few multiply-adds per vertex). Fallback: 0 for a zero or non-finite input, `m` out
    /// of range, or `p` in the polygon's plane.
    ///
    /// <!-- BEGIN acc-directional_luminaire: target/accuracy/model-directional_luminaire.md -->
    /// Measured: f64 within 4.2e-12 of its reference (the independent quadrature, adversarial);
    /// against f64, f32 5.8e-7 (ill-conditioned: 1.7e-7; near boundary: 5.1e-5), Fast32 2.7e-5
    /// (ill-conditioned: 8.9e-6); 18 870 cases in all (`docs/accuracy.md`).
    /// <!-- END acc-directional_luminaire -->
    #[inline]
    pub fn directional_luminaire(
        &self,
        p: Vec3<T>,
        n: impl Direction<T>,
        axis: Vec3<T>,
        m: u32,
    ) -> T {
        self.try_directional_luminaire(p, n, axis, m)
            .unwrap_or(T::ZERO)
    }

    /// `[glossy_reflection]` with precise errors: see [`PolygonLight::glossy_reflection`].
    ///
    /// # Errors
    /// [`Error::NotFinite`] for `p`, `n` or `e`, [`Error::ZeroLength`] for `n` or `e`,
    /// [`Error::ExponentOutOfRange`] for `m > MAX_EXPONENT` (255 for [`crate::Fixed22`]).
    pub fn try_glossy_reflection(
        &self,
        p: Vec3<T>,
        n: impl Direction<T>,
        e: impl Direction<T>,
        m: u32,
    ) -> Result<T, Error> {
        check_m::<T>(m)?;
        if !p.is_finite() {
            return Err(Error::NotFinite("p"));
        }
        let n = n.try_unit("n")?.into_inner();
        let e = e.try_unit("e")?.into_inner();
        let mr = (n * (T::TWO * n.dot(e)) - e).normalize().unwrap_or(n);
        Ok(self.clipped_moment_sum(p, mr, n, m) * T::FRAC_1_TAU)
    }

    /// `[glossy_reflection]`: the radiance toward the eye (unit direction `e` from `p`) of the
    /// unit Lambertian polygon off the Phong-lobe BRDF about the mirror direction
    /// `mr = 2 (n.e) n - e`: `(m + 2)/(2 pi) integral over A of ((u.mr)+)^m (n.u)+ du`
    /// (Arvo 6.2).
    ///
    /// Accuracy and cost: as [`PolygonLight::directional_luminaire`]. Fallback: 0 for a zero or
    /// non-finite input, `m` out of range, or `p` in the polygon's plane.
    ///
    /// <!-- BEGIN acc-glossy_reflection: target/accuracy/model-glossy_reflection.md -->
    /// Measured: f64 within 1.9e-12 of its reference (the independent quadrature, h <= 1e-8);
    /// against f64, f32 5.1e-7 (ill-conditioned: 3.7e-7; near boundary: 6.4e-5), Fast32 1.4e-5
    /// (ill-conditioned: 7.2e-6); 18 887 cases in all (`docs/accuracy.md`).
    /// <!-- END acc-glossy_reflection -->
    #[inline]
    pub fn glossy_reflection(
        &self,
        p: Vec3<T>,
        n: impl Direction<T>,
        e: impl Direction<T>,
        m: u32,
    ) -> T {
        self.try_glossy_reflection(p, n, e, m).unwrap_or(T::ZERO)
    }

    /// `[glossy_transmission]` with precise errors: see [`PolygonLight::glossy_transmission`].
    ///
    /// # Errors
    /// As [`PolygonLight::try_glossy_reflection`].
    pub fn try_glossy_transmission(
        &self,
        p: Vec3<T>,
        n: impl Direction<T>,
        e: impl Direction<T>,
        m: u32,
    ) -> Result<T, Error> {
        check_m::<T>(m)?;
        if !p.is_finite() {
            return Err(Error::NotFinite("p"));
        }
        let n = n.try_unit("n")?.into_inner();
        let e = e.try_unit("e")?.into_inner();
        Ok(self.clipped_moment_sum(p, -e, -n, m) * T::FRAC_1_TAU)
    }

    /// `[glossy_transmission]`: the same through a thin frosted slab, the lobe about `-e` on
    /// the far side: `(m + 2)/(2 pi) integral over A of ((-u.e)+)^m ((-n).u)+ du` (Arvo 6.3).
    ///
    /// Accuracy and cost: as [`PolygonLight::directional_luminaire`]. Fallback: 0 for a zero or
    /// non-finite input, `m` out of range, or `p` in the polygon's plane.
    ///
    /// <!-- BEGIN acc-glossy_transmission: target/accuracy/model-glossy_transmission.md -->
    /// Measured: f64 within 1.9e-12 of its reference (the independent quadrature, adversarial);
    /// against f64, f32 2.4e-7 (ill-conditioned: 1.9e-7; near boundary: 9.1e-6), Fast32 1.2e-5
    /// (ill-conditioned: 6.4e-6); 18 859 cases in all (`docs/accuracy.md`).
    /// <!-- END acc-glossy_transmission -->
    #[inline]
    pub fn glossy_transmission(
        &self,
        p: Vec3<T>,
        n: impl Direction<T>,
        e: impl Direction<T>,
        m: u32,
    ) -> T {
        self.try_glossy_transmission(p, n, e, m).unwrap_or(T::ZERO)
    }
}
