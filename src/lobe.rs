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
