//! Nine-coefficient spherical-harmonic irradiance (Ramamoorthi and Hanrahan 2001; June
//! section 20.4, eq. 20.21-20.33).
//!
//! A radiance environment band-limited to `l <= 2` is `L(u) = sum L_lm Y_lm(u)` (nine RGB
//! coefficients, in the order L00, L1-1, L10, L11, L2-2, L2-1, L20, L21, L22). Its irradiance
//! `E(n) = integral L(u) (n.u)+ du` (not divided by pi) is, by the Funk-Hecke theorem,
//! `E(n) = sum A_l L_lm Y_lm(n)` with `A0 = pi`, `A1 = 2 pi/3`, `A2 = pi/4` (eq. 20.24-20.26),
//! exact for such an `L`. With the real basis of eq. 20.21 (exact constants: `Y00 = 1/(2 sqrt pi)`,
//! `Y1m = sqrt(3/(4 pi)) (y, z, x)`, `Y2-2,2-1,21 = sqrt(15/pi)/2 (xy, yz, xz)`,
//! `Y20 = sqrt(5/pi)/4 (3z^2 - 1)`, `Y22 = sqrt(15/pi)/4 (x^2 - y^2)`), `E` is a quadratic
//! polynomial in `n`; [`Sh9::prepare`] folds every constant into its nine coefficients once,
//! so a sample costs 9 multiply-adds per channel (eq. 20.33).
//!
//! Projections (eq. 20.27-20.29): a unit-radiance disc (cap) of half-angle `alpha` about the z
//! axis has only zonal coefficients
//! `z0 = sqrt(pi) (1 - cos a)`, `z1 = sqrt(3 pi)/2 sin^2 a`, `z2 = sqrt(5 pi)/2 (cos a - cos^3 a)`;
//! rotated to `axis`, `L_lm = sqrt(4 pi/(2l + 1)) z_l Y_lm(axis)`.

use crate::unit::Direction;
use crate::{Error, Real, Rgb, Vec3};

const SQRT_PI: f64 = 1.772_453_850_905_516;
/// `1/(2 sqrt pi)`.
const C00: f64 = 0.5 / SQRT_PI;
/// `sqrt(3/(4 pi))`.
const C1: f64 = 0.488_602_511_902_919_9;
/// `sqrt(15/pi)/2`.
const C2: f64 = 1.092_548_430_592_079_2;
/// `sqrt(5/pi)/4`.
const C20: f64 = 0.315_391_565_252_520_05;
/// `sqrt(15/pi)/4`.
const C22: f64 = 0.546_274_215_296_039_6;
/// `A0`, `A1`, `A2` of eq. 20.26 (exact).
pub const A: [f64; 3] = [
    core::f64::consts::PI,
    2.0 * core::f64::consts::PI / 3.0,
    core::f64::consts::PI / 4.0,
];

/// The nine real SH basis functions at a unit direction, in the crate's coefficient order.
pub fn basis<T: Real>(u: Vec3<T>) -> [T; 9] {
    let (x, y, z) = (u.x, u.y, u.z);
    let k = T::from_f64;
    [
        k(C00),
        k(C1) * y,
        k(C1) * z,
        k(C1) * x,
        k(C2) * x * y,
        k(C2) * y * z,
        k(C20) * (k(3.0) * z * z - T::ONE),
        k(C2) * x * z,
        k(C22) * (x * x - y * y),
    ]
}

/// A radiance environment as nine RGB SH coefficients.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sh9<T> {
    coeffs: [Rgb<T>; 9],
}

/// Table 20-1 of June (after Ramamoorthi and Hanrahan): Grace Cathedral.
pub const GRACE_CATHEDRAL: [[f64; 3]; 9] = [
    [0.79, 0.44, 0.54],
    [0.39, 0.35, 0.60],
    [-0.34, -0.18, -0.27],
    [-0.29, -0.06, 0.01],
    [-0.11, -0.05, -0.12],
    [-0.26, -0.22, -0.47],
    [-0.16, -0.09, -0.15],
    [0.56, 0.21, 0.14],
    [0.21, -0.05, -0.30],
];
/// Table 20-1 of June: Eucalyptus Grove.
pub const EUCALYPTUS_GROVE: [[f64; 3]; 9] = [
    [0.38, 0.43, 0.45],
    [0.29, 0.36, 0.41],
    [0.04, 0.03, 0.01],
    [-0.10, -0.10, -0.09],
    [-0.06, -0.06, -0.04],
    [0.01, -0.01, -0.05],
    [-0.09, -0.13, -0.15],
    [-0.06, -0.05, -0.04],
    [0.02, -0.00, -0.05],
];
/// Table 20-1 of June: St. Peter's Basilica.
pub const ST_PETERS_BASILICA: [[f64; 3]; 9] = [
    [0.36, 0.26, 0.23],
    [0.18, 0.14, 0.13],
    [-0.02, -0.01, -0.00],
    [0.03, 0.02, 0.01],
    [0.02, 0.01, 0.00],
    [-0.05, -0.03, -0.01],
    [-0.09, -0.08, -0.07],
    [0.01, 0.00, 0.00],
    [-0.08, -0.06, 0.00],
];

/// The named environments of June's Table 20-1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Environment {
    /// Grace Cathedral, San Francisco.
    GraceCathedral,
    /// Eucalyptus Grove, UC Berkeley.
    EucalyptusGrove,
    /// St. Peter's Basilica, Rome.
    StPetersBasilica,
}

impl<T: Real> Sh9<T> {
    /// No light.
    pub fn zero() -> Self {
        Sh9 {
            coeffs: [Rgb::splat(T::ZERO); 9],
        }
    }

    /// From nine RGB coefficients in the crate's order (L00, L1-1, L10, L11, L2-2, L2-1, L20,
    /// L21, L22).
    ///
    /// # Errors
    /// [`Error::NotFinite`] (`"coeffs"`).
    pub fn new(coeffs: [Rgb<T>; 9]) -> Result<Self, Error> {
        if coeffs.iter().all(|c| c.is_finite()) {
            Ok(Sh9 { coeffs })
        } else {
            Err(Error::NotFinite("coeffs"))
        }
    }

    /// One of June's Table 20-1 environments.
    pub fn environment(env: Environment) -> Self {
        let t = match env {
            Environment::GraceCathedral => &GRACE_CATHEDRAL,
            Environment::EucalyptusGrove => &EUCALYPTUS_GROVE,
            Environment::StPetersBasilica => &ST_PETERS_BASILICA,
        };
        Sh9 {
            coeffs: core::array::from_fn(|i| Rgb::from_f64(t[i])),
        }
    }

    /// The coefficients.
    pub fn coefficients(&self) -> &[Rgb<T>; 9] {
        &self.coeffs
    }

    /// The sum of two environments (projection is linear).
    #[must_use]
    pub fn plus(&self, other: &Self) -> Self {
        Sh9 {
            coeffs: core::array::from_fn(|i| self.coeffs[i].add(other.coeffs[i])),
        }
    }

    /// A directional light: radiance `colour` times a delta in direction `dir` (any length),
    /// so that a surface facing it receives about `colour` (the SH9 projection blurs the delta
    /// into a lobe; its irradiance is the band-limited approximation of `colour (n.dir)+`).
    ///
    /// # Errors
    /// [`Error::NotFinite`] / [`Error::ZeroLength`] for `dir`; [`Error::NotFinite`] for `colour`.
    pub fn directional(dir: Vec3<T>, colour: Rgb<T>) -> Result<Self, Error> {
        let d = dir.try_normalize("dir")?;
        let colour = colour.check_finite("colour")?;
        let y = basis(d);
        Ok(Sh9 {
            coeffs: core::array::from_fn(|i| colour.scale(y[i])),
        })
    }

    /// A disc (cap) light of radiance `colour` and half-angle `alpha` in [0, pi] about `axis`
    /// (June eq. 20.28-20.29, rotated). `alpha = pi/2` is a constant hemisphere (a sky), and
    /// `alpha = pi` a uniform environment.
    ///
    /// # Errors
    /// [`Error::NotFinite`] / [`Error::ZeroLength`] for `axis`; [`Error::NotFinite`] or
    /// [`Error::AlphaOutOfRange`] for `alpha`; [`Error::NotFinite`] for `colour`.
    ///
    /// <!-- BEGIN acc-sh9_disc_irradiance: target/accuracy/model-sh9_disc_irradiance.md -->
    /// Measured: f64 within 2.7e-15 of its reference (the independent quadrature); against f64,
    /// f32 1.2e-6 (ill-conditioned: 1.0e-6), Fast32 1.2e-6 (ill-conditioned: 1.0e-6), Fixed22
    /// 1.1e-4; 75 874 cases in all (`docs/accuracy.md`).
    /// <!-- END acc-sh9_disc_irradiance -->
    pub fn disc(axis: Vec3<T>, alpha: T, colour: Rgb<T>) -> Result<Self, Error> {
        if !alpha.is_finite() {
            return Err(Error::NotFinite("alpha"));
        }
        if !(alpha >= T::ZERO && alpha <= T::PI) {
            return Err(Error::AlphaOutOfRange);
        }
        let (ca, sa) = (alpha.cos(), alpha.sin());
        Self::disc_cos_sin(axis, ca, sa, colour)
    }

    /// A disc light given `cos alpha` and `sin alpha` (`sin alpha >= 0`).
    fn disc_cos_sin(axis: Vec3<T>, ca: T, sa: T, colour: Rgb<T>) -> Result<Self, Error> {
        let axis = axis.try_normalize("axis")?;
        let colour = colour.check_finite("colour")?;
        let k = T::from_f64;
        // sqrt(4 pi/(2l + 1)) z_l, folded.
        let z0 = k(2.0 * SQRT_PI * SQRT_PI) * (T::ONE - ca);
        let z1 = k(SQRT_PI * SQRT_PI) * sa * sa;
        let z2 = k(SQRT_PI * SQRT_PI) * (ca - ca * ca * ca);
        let y = basis(axis);
        let zl = [z0, z1, z1, z1, z2, z2, z2, z2, z2];
        Ok(Sh9 {
            coeffs: core::array::from_fn(|i| colour.scale(zl[i] * y[i])),
        })
    }

    /// A spherical light of radiance `colour`, `radius` at `center`, seen from `p`: the disc of
    /// `sin alpha = radius/d` (eq. 20.32) toward the centre.
    ///
    /// # Errors
    /// [`Error::NotFinite`] for any input, [`Error::RadiusNotPositive`],
    /// [`Error::PointInsideSphere`].
    ///
    /// Needs the `cap` feature (it builds the sphere's cap with [`crate::SphereLight`]).
    #[cfg(feature = "cap")]
    pub fn sphere(center: Vec3<T>, radius: T, p: Vec3<T>, colour: Rgb<T>) -> Result<Self, Error> {
        let s = crate::cap::SphereLight::new(center, radius)?;
        let cap = s.cap_at(p)?;
        Self::disc_cos_sin(cap.axis.into_inner(), cap.cs(), cap.ss, colour)
    }

    /// A constant hemisphere (sky) of radiance `colour` around `up`.
    ///
    /// # Errors
    /// As [`Sh9::disc`].
    pub fn hemisphere(up: Vec3<T>, colour: Rgb<T>) -> Result<Self, Error> {
        Self::disc_cos_sin(up, T::ZERO, T::ONE, colour)
    }

    /// Sky/ground lighting: `sky` above the horizon of `up`, `ground` below. Its SH9 irradiance
    /// is exact (the irradiance of a hemisphere split is linear in `n`, band 1).
    ///
    /// # Errors
    /// As [`Sh9::disc`].
    pub fn sky_ground(up: Vec3<T>, sky: Rgb<T>, ground: Rgb<T>) -> Result<Self, Error> {
        Ok(Self::hemisphere(up, sky)?.plus(&Self::hemisphere(-up, ground)?))
    }

    /// Folds the basis constants and `A_l` into the irradiance polynomial (once per
    /// environment).
    ///
    /// On `Fixed22` it also packs the polynomial as 16-bit mantissas, one exponent per
    /// channel, where the environment's error bound in that form is at most `2^-11` (every
    /// coefficient near 1 or below: about `1.2e-4` of bound for coefficients of 1); then
    /// [`Sh9Irradiance::irradiance`] takes one 32-bit product a term. [`Sh9::prepare_exact`]
    /// keeps the exact Q22 sum. On the floats the two are the same.
    pub fn prepare(&self) -> Sh9Irradiance<T> {
        self.prepare_with(true)
    }

    /// [`Sh9::prepare`] without `Fixed22`'s 16-bit fast path: every evaluation the exact
    /// fused Q22 sum (within `2^-22` of its Q22 monomials; about 3.4 times the Cortex-M0
    /// instructions, see [`Sh9Irradiance::irradiance`]).
    pub fn prepare_exact(&self) -> Sh9Irradiance<T> {
        self.prepare_with(false)
    }

    fn prepare_with(&self, fast: bool) -> Sh9Irradiance<T> {
        let k = T::from_f64;
        let l = &self.coeffs;
        let c = |i: usize, s: f64| l[i].scale(k(s));
        let konst = c(0, A[0] * C00).add(c(6, -A[2] * C20));
        let k = [
            konst,
            c(3, A[1] * C1),        // x
            c(1, A[1] * C1),        // y
            c(2, A[1] * C1),        // z
            c(4, A[2] * C2),        // xy
            c(5, A[2] * C2),        // yz
            c(7, A[2] * C2),        // xz
            c(6, 3.0 * A[2] * C20), // z^2
            c(8, A[2] * C22),       // x^2 - y^2
        ];
        // Every monomial of a unit normal is at most 1 in magnitude, so |E| <= sum |k| per
        // channel; within 1e30 no rounding can take a channel past the type's range.
        let limit = T::from_f64(1e30);
        let sum = |f: fn(&Rgb<T>) -> T| k.iter().fold(T::ZERO, |s, c| s + f(c).abs());
        let bounded = [sum(|c| c.r), sum(|c| c.g), sum(|c| c.b)]
            .iter()
            .all(|s| *s <= limit);
        let mut k = k;
        let shift = T::sh9_pack(&mut k, fast);
        Sh9Irradiance { k, bounded, shift }
    }
}

/// The irradiance polynomial of an [`Sh9`] environment:
/// `E = k0 + kx x + ky y + kz z + kxy xy + kyz yz + kxz xz + kzz z^2 + k22 (x^2 - y^2)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sh9Irradiance<T> {
    k: [Rgb<T>; 9],
    /// Each channel's `sum |k|` within 1e30 (no overflow possible): the per-sample
    /// finiteness test is skipped.
    bounded: bool,
    /// What the type's own evaluation needs besides `k` (`Fixed22`'s 16-bit fast path: the
    /// mantissas' shift, and `k` holds the mantissas; 0 otherwise).
    shift: u8,
}

impl<T: Real> Sh9Irradiance<T> {
    /// `[sh9_irradiance]`: irradiance (not divided by pi) for normal `n` (any length), per
    /// channel. Exact for the band-limited environment; may be slightly negative where a
    /// measured environment's projection rings (as in Table 20-1): not clamped.
    ///
    /// Accuracy: a few ULPs of the largest coefficient. Cost: 1 normalization (none for a
    /// [`UnitVec3`](crate::UnitVec3)) and 24 multiply-adds (no finiteness test of the result
    /// when every channel's coefficients sum to at most 1e30 in magnitude, which cannot
    /// overflow): 96 instructions a call on the Cortex-M4F in f32, 82 with a `UnitVec3`
    /// (QEMU, exact). Fallback: black for a zero or non-finite `n`.
    ///
    /// `Fixed22` has two evaluations, chosen once by [`Sh9::prepare`]:
    ///
    /// - **16-bit (the default where the environment allows it):** the monomials (`x`, `y`,
    ///   `z`, `xy`, `yz`, `xz`, `z^2`, `x^2 - y^2`) in Q15 and the coefficients as 16-bit
    ///   mantissas with one exponent, every term one 32-bit `MULS`, the sum in an `i32` that
    ///   cannot wrap. Error: within a bound that `prepare` computes from the coefficients and
    ///   requires to be at most `2^-11` in every channel (half the fixed-point budget of
    ///   1/1024; near `3e-4` for coefficients up to 1, so every environment with its
    ///   radiance coefficients up to about 1 qualifies, Table 20-1's among them; errors
    ///   measured up to `1.3e-4`). M0 `Fixed22`
    ///   with a `UnitVec3`: 688 -> 198 instructions a call; with a `Vec3` 925 -> 417 (QEMU,
    ///   exact; issue 13's bar is 200). Flash: the `sh9` family alone in an M0 `Fixed22`
    ///   firmware 6 060 -> 7 152 bytes (both paths and the packing; `boards/size-probe`).
    /// - **Exact ([`Sh9::prepare_exact`], and any environment beyond that bound):** each
    ///   channel as one fused dot product of its nine coefficients with the Q22 monomials
    ///   (each rounded down once from the unit normal): the exact products summed in
    ///   integers and rounded down once, so the sum adds at most 1 LSB (`2^-22`) to the
    ///   monomials' own rounding; 4 32-bit `MULS` a term and no saturation test. M0: 688
    ///   instructions with a `UnitVec3`, 925 with a `Vec3`.
    ///
    /// <!-- BEGIN acc-sh9_irradiance: target/accuracy/model-sh9_irradiance.md -->
    /// Measured: f64 within 1.8e-15 of its reference (the independent quadrature); against f64,
    /// f32 6.8e-7, Fast32 6.8e-7, Fixed22 1.2e-4; 309 210 cases in all (`docs/accuracy.md`).
    /// <!-- END acc-sh9_irradiance -->
    #[inline]
    pub fn irradiance(&self, n: impl Direction<T>) -> Rgb<T> {
        let Some(n) = n.to_unit() else {
            return Rgb::splat(T::ZERO);
        };
        if let Some(e) = T::sh9_dot(&self.k, self.shift, n) {
            return e.finite_or_zero();
        }
        let [xy, yz, xz, zz, xx_yy] = n.quadratic_monomials();
        let m = [n.x, n.y, n.z, xy, yz, xz, zz, xx_yy];
        let ch = |f: fn(&Rgb<T>) -> T| {
            let [k0, k @ ..] = &self.k;
            let mut s = f(k0);
            for (k, x) in k.iter().zip(m) {
                s += f(k) * x;
            }
            s
        };
        let e = Rgb::new(ch(|c| c.r), ch(|c| c.g), ch(|c| c.b));
        if self.bounded {
            e
        } else {
            e.finite_or_zero()
        }
    }
}
