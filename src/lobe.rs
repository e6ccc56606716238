//! The Phong lobe `((u.r)+)^m` shared by every specular model: its exponent and the
//! per-material constants of Snyder eq. 13-15, computed once.
//!
//! Always compiled (it is small): the Phong integrals of the `phong` feature and Picott's peak
//! approximations of the `line` feature both take a [`PhongLobe`].

use crate::sine_power::sine_power_integral_pi;
use crate::{Error, Real};

/// The largest Phong exponent accepted: every model's cost is O(m), so this bounds the time a
/// sample can take (about a million multiply-adds).
pub const MAX_EXPONENT: u32 = 1 << 20;

/// A Phong lobe: the exponent and its per-material constants `S(m, pi)`, `S(m + 1, pi)`,
/// computed once (in f64, then rounded to `T`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhongLobe<T> {
    pub(crate) requested: u32,
    pub(crate) m: u32,
    pub(crate) s_m_pi: T,
    pub(crate) s_m1_pi: T,
    pub(crate) hemi_cos_scale: T,
    /// The bound for a negligible Phong term (fixed point, f32, Fast32), `(c, c^2, s)` with
    /// `c = 2^(-24/(m+1)) (1 - 2^-6)` and `s` at least `sqrt(1 - c^2)`: where `r.u < c` over a
    /// polygon or a cap, its Phong term is below `2^-24` (`polygon/negligible.rs`). `(0, 0,
    /// 0)`, never used, for f64 and for `m < 11` (`c` below 1/4, where the test's margins would
    /// not hold).
    pub(crate) negligible_cos: (T, T, T),
}

impl<T: Real> PhongLobe<T> {
    /// The exact lobe of exponent `m` (odd or even).
    ///
    /// # Errors
    /// [`Error::ExponentOutOfRange`] for `m > MAX_EXPONENT` (or the evaluated `m` above
    /// [`Real::MAX_PHONG_EXPONENT`], 255 for [`crate::Fixed22`]).
    pub fn new(m: u32) -> Result<Self, Error> {
        Self::build(m, m)
    }

    /// Snyder's odd-only fast path: an even `m` is evaluated as `m + 1` (no solid angle, one
    /// arc tangent fewer per cap sample and one fan term fewer per polygon edge). An
    /// approximation for even `m`; exact for odd `m`.
    ///
    /// # Errors
    /// [`Error::ExponentOutOfRange`] for `m > MAX_EXPONENT` (or the evaluated `m` above
    /// [`Real::MAX_PHONG_EXPONENT`], 255 for [`crate::Fixed22`]).
    pub fn odd_only(m: u32) -> Result<Self, Error> {
        Self::build(m, m | 1)
    }

    fn build(requested: u32, m: u32) -> Result<Self, Error> {
        if requested > MAX_EXPONENT || m > T::MAX_PHONG_EXPONENT {
            return Err(Error::ExponentOutOfRange);
        }
        let s_m = sine_power_integral_pi::<f64>(m);
        let s_m1 = sine_power_integral_pi::<f64>(m + 1);
        let mf = m as f64;
        Ok(PhongLobe {
            requested,
            m,
            s_m_pi: T::from_f64(s_m),
            s_m1_pi: T::from_f64(s_m1),
            hemi_cos_scale: T::from_f64((mf + 1.0) / ((mf + 2.0) * s_m1)),
            negligible_cos: negligible_cos::<T>(m),
        })
    }

    /// The exponent asked for.
    pub fn exponent(&self) -> u32 {
        self.requested
    }
    /// The exponent evaluated (differs only for [`PhongLobe::odd_only`] with an even `m`).
    pub fn evaluated_exponent(&self) -> u32 {
        self.m
    }
}

/// Whether the type answers 0 for a Phong term it proves below `2^-24` (`polygon/negligible.rs`,
/// and the cap's test in `phong.rs`): fixed point (`2^-24` is a quarter of `Fixed22`'s unit),
/// f32 and `Fast32` (`2^-24` is 3 % of f32's error budget of `2e-6`, and a proof costs a
/// fraction of the term), not f64 (decided at compile time).
#[inline(always)]
pub(crate) fn negligible_terms<T: Real>() -> bool {
    T::RESOLUTION > T::ZERO || T::EPSILON > T::from_f64(1e-10)
}

/// [`PhongLobe`]'s `negligible_cos` for the evaluated exponent `m`: `2^(-24/(m+1))`, the
/// cosine whose power `m + 1` is `2^-24`, lowered by `2^-6` of itself for the rounding of the
/// test that uses it, its square, and its sine raised by `2^-16` (the bounding-ball test
/// wants a sine no smaller than the exact one); `(0, 0, 0)` (off) for f64 (the reference, whose
/// terms are kept however small) and below `m = 11`. In the type's own arithmetic (`exp`,
/// whose error of a few units is far inside the `2^-6`): f64's `exp` would not fit the
/// budget firmware's flash.
fn negligible_cos<T: Real>(m: u32) -> (T, T, T) {
    if !negligible_terms::<T>() || m < 11 {
        return (T::ZERO, T::ZERO, T::ZERO);
    }
    let c = T::from_f64(-24.0 * core::f64::consts::LN_2)
        .div_u32(m + 1)
        .exp()
        * T::from_f64(1.0 - 1.0 / 64.0);
    let c2 = c * c;
    (c, c2, (T::ONE - c2).sqrt() + T::from_fixed_i32(1, 16))
}

#[cfg(all(test, feature = "fixed"))]
mod tests {
    use super::*;
    use crate::Fixed22;

    /// The threshold and its square are within `1e-5` of `2^(-24/(m+1)) (1 - 2^-6)` and its
    /// square for every exponent that uses it (the test's margins are `2^-6` of it, at least
    /// `4e-3`); off below 11 and for the floats.
    #[test]
    fn the_negligible_cosine_is_just_below_its_exact_value() {
        for m in 11..=255u32 {
            let exact = libm::exp2(-24.0 / (f64::from(m) + 1.0)) * (1.0 - 1.0 / 64.0);
            let (c, c2, s) = negligible_cos::<Fixed22>(m);
            let (c, c2, s) = (c.to_f64(), c2.to_f64(), s.to_f64());
            // Fixed22's exp and product: a few units of 2^-22.
            assert!((c - exact).abs() < 1e-5, "{m}: {c} vs {exact}");
            assert!((c2 - exact * exact).abs() < 1e-5, "{m}: {c2} vs {exact}");
            // The sine of the threshold actually used, raised: above, by less than 2^-15.
            let s_exact = libm::sqrt(1.0 - c * c);
            assert!(
                s > s_exact && s < s_exact + 1.0 / 32768.0,
                "{m}: {s} vs {s_exact}"
            );
        }
        assert_eq!(
            negligible_cos::<Fixed22>(10),
            (Fixed22::ZERO, Fixed22::ZERO, Fixed22::ZERO)
        );
        assert_eq!(negligible_cos::<f64>(100), (0.0, 0.0, 0.0));
        assert_eq!(negligible_cos::<f32>(10), (0.0, 0.0, 0.0));
        // The floats (f32, and Fast32 with its own exp): for every exponent the threshold's
        // power m + 1 stays below 2^-24 (what the proofs need), within 1e-5 of the intended
        // value, and the sine is at least that of the threshold used.
        fn floats<T: Real>() {
            for m in 11..=255u32 {
                let exact = libm::exp2(-24.0 / (f64::from(m) + 1.0)) * (1.0 - 1.0 / 64.0);
                let (c, c2, s) = negligible_cos::<T>(m);
                let (c, c2, s) = (c.to_f64(), c2.to_f64(), s.to_f64());
                assert!((c - exact).abs() < 1e-5, "{m}: {c} vs {exact}");
                assert!(
                    libm::pow(c, f64::from(m) + 1.0) < 1.0 / 16_777_216.0,
                    "{m}: {c}"
                );
                assert!(c2 <= c * c * (1.0 + 1e-6), "{m}: {c2} vs {c}");
                assert!(s >= libm::sqrt(1.0 - c * c), "{m}: {s}");
            }
        }
        floats::<f32>();
        floats::<crate::Fast32>();
    }
}
