//! The crate's scalar trait: every model is written once over [`Real`].
//!
//! Three scalar types implement it today:
//!
//! | type | what it is | sqrt / atan2 / sin / cos |
//! |---|---|---|
//! | `f64` | the reference | `libm` (correctly rounded sqrt, atan2 within 1 ULP) |
//! | `f32` | the firmware float path | `libm` (`sinf`, ...); `sqrt` is `VSQRT.F32` on FPU targets (`eabihf`), `libm::sqrtf` elsewhere: see [`hw`]; `atan2` is the crate's degree-17 polynomial (1.65 ULP, 63 against libm's 68 to 97 M4F instructions a call) except on soft-float targets, which keep `libm::atan2f` (`src/real/f32_math.rs`); `arc_ratio` (`theta/sin(theta)` for the polygon edge terms) a degree-9 polynomial on the same targets (`src/real/arc_ratio.rs`) |
//! | [`Fast32`] | f32 with the crate's own cheap arctangent | see [`fast32`] |
//!
//! The trait is sealed: the crate's models rely on the error bounds of each backend, which are
//! stated and tested here, so only this crate implements it. The fixed-point types of the
//! FPU-less path are added to the same trait, so no model is written twice per type.
//!
//! Constants are associated `const`s and literals go through [`Real::from_f64`], which every
//! implementation marks `#[inline(always)]` so that a literal argument folds at compile time.

use core::fmt::Debug;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

mod arc_ratio;
pub(crate) use arc_ratio::SOFT_FLOAT;
mod f32_math;
pub mod fast32;
pub use fast32::Fast32;
#[cfg(feature = "fixed")]
pub mod fixed22;
mod float;
mod i64_to_f32;
pub(crate) use i64_to_f32::i64_to_f32;
pub mod hw;
#[cfg(feature = "fixed")]
pub use fixed22::Fixed22;

// The seal of `Real` and the crate-internal arithmetic (its own file: `src/real/sealed.rs`).
pub(crate) mod sealed;

/// A real-number type the models are generic over (sealed; see the module docs).
///
/// Every method is total: it never panics. Methods whose mathematical domain is restricted
/// (`sqrt`, `acos`) document what they return outside it.
pub trait Real:
    sealed::Sealed
    + Copy
    + Debug
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
{
    /// 0.
    const ZERO: Self;
    /// 1.
    const ONE: Self;
    /// 2.
    const TWO: Self;
    /// 1/2.
    const HALF: Self;
    /// pi.
    const PI: Self;
    /// pi/2.
    const FRAC_PI_2: Self;
    /// 2 pi.
    const TAU: Self;
    /// 1/pi.
    const FRAC_1_PI: Self;
    /// 1/(2 pi).
    const FRAC_1_TAU: Self;
    /// Machine epsilon (the spacing of values just above 1).
    const EPSILON: Self;
    /// The smallest positive value whose square and reciprocal square are both finite and
    /// normal: the models' threshold for degenerate distances. (The rescaled normalization of
    /// `Fixed22` treats vectors below it as zero; f32's, f64's and [`Fast32`]'s give every
    /// finite nonzero vector a direction: see [`Real::normalize3`].)
    const TINY: Self;
    /// The absolute resolution of the type: the spacing of its values wherever they lie, for
    /// a type whose rounding is absolute. 0 for the float types (their rounding is relative:
    /// see [`Real::EPSILON`]); [`Fixed22::DELTA`] (`2^-22`) for fixed point. Tolerances that
    /// must cover the rounding of the inputs themselves add a few of it (the polygon's
    /// planarity and in-plane tests).
    const RESOLUTION: Self = Self::ZERO;
    /// The largest Phong exponent this scalar type supports (beyond it a [`crate::PhongLobe`]
    /// constructor returns [`crate::Error::ExponentOutOfRange`]).
    const MAX_PHONG_EXPONENT: u32 = crate::lobe::MAX_EXPONENT;
    /// The largest absolute coordinate the constructors accept for positions (points, sphere
    /// centres, radii): unbounded for the float types, [`Fixed22::COORDINATE_LIMIT`] for the
    /// fixed-point type, so that differences of points stay representable.
    const COORDINATE_LIMIT: f64 = f64::MAX;

    /// Converts an `f64` (rounding to nearest). Used for literals; folds at compile time.
    fn from_f64(x: f64) -> Self;
    /// Converts an integer: exact for `x <= 2^24` in f32 and [`Fast32`] (rounded to nearest
    /// beyond), for every `u32` in f64, and for `x < 512` in [`Fixed22`], which saturates from
    /// 512 on (to `Fixed22::MAX`, `512 - 2^-22`: its range). Callers whose integer can reach
    /// 512 (viewport sides, segment counts) scale it by a power of two first
    /// ([`Real::from_fixed_i32`]) or scale into integers with [`Real::mul_u32_to_fixed_i32`].
    fn from_u32(x: u32) -> Self;
    /// Converts to `f64` (exact for every backend).
    fn to_f64(self) -> f64;

    /// `|self|`.
    fn abs(self) -> Self;
    /// Square root; returns 0 for negative input (and for NaN).
    fn sqrt(self) -> Self;
    /// Four-quadrant arctangent of `self / x` in [-pi, pi]; `atan2(0, 0) = 0`.
    fn atan2(self, x: Self) -> Self;
    /// Sine (radians).
    fn sin(self) -> Self;
    /// Cosine (radians).
    fn cos(self) -> Self;
    /// `e^self`.
    fn exp(self) -> Self;
    /// Natural logarithm (`-inf` for 0 and NaN for negative input, as libm: callers validate
    /// their domain first).
    fn ln(self) -> Self;
    /// `true` unless NaN or infinite.
    fn is_finite(self) -> bool;
    /// `self^y` for `self > 0` as `exp(y ln self)`; 0 for `self <= 0` (and NaN).
    #[inline(always)]
    fn powf(self, y: Self) -> Self {
        if self > Self::ZERO {
            (y * self.ln()).exp()
        } else {
            Self::ZERO
        }
    }

    /// The larger of two values; a NaN operand loses.
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        if self >= other || other.is_nan_like() {
            self
        } else {
            other
        }
    }
    /// The smaller of two values; a NaN operand loses.
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        if self <= other || other.is_nan_like() {
            self
        } else {
            other
        }
    }
    /// `true` for NaN (never for the fixed-point types).
    #[inline(always)]
    #[allow(clippy::eq_op)]
    fn is_nan_like(self) -> bool {
        self != self
    }
    /// Clamps to [0, 1]; NaN maps to 0. Used on the result of every normalized model: it only
    /// removes rounding excursions, since the exact value lies in [0, 1].
    #[inline(always)]
    fn clamp01(self) -> Self {
        if self > Self::ZERO {
            if self < Self::ONE {
                self
            } else {
                Self::ONE
            }
        } else {
            Self::ZERO
        }
    }
    /// Clamps to [lo, hi]; NaN maps to `lo`.
    #[inline(always)]
    fn clamp(self, lo: Self, hi: Self) -> Self {
        if self > lo {
            if self < hi {
                self
            } else {
                hi
            }
        } else {
            lo
        }
    }
    /// `self` if finite, else 0: the documented fallback of every per-sample function.
    #[inline(always)]
    fn finite_or_zero(self) -> Self {
        if self.is_finite() {
            self
        } else {
            Self::ZERO
        }
    }
    /// `acos(c)/sqrt(1 - c^2)` (the arc ratio `theta/sin(theta)` of the angle whose cosine is
    /// `c = self`) for `c` in [0, 1], where the backend has one cheaper than an arc tangent:
    /// `f32`'s degree-9 polynomial (at most 1.58 ULP; `src/real/arc_ratio.rs`) and
    /// `Fixed22`'s 16 cubic pieces (within 3.9e-7; `src/real/fixed22/elementary.rs`). `None`
    /// for the others (the default), whose polygon edge terms keep the arc-tangent form.
    #[inline(always)]
    fn arc_ratio(self) -> Option<Self> {
        None
    }
    /// Arc cosine in [0, pi] of `self` clamped to [-1, 1], computed as
    /// `atan2(sqrt((1 - x)(1 + x)), x)` (accurate near +-1, where `acos` loses digits).
    #[inline(always)]
    fn acos_clamped(self) -> Self {
        let x = self.clamp(-Self::ONE, Self::ONE);
        ((Self::ONE - x) * (Self::ONE + x)).sqrt().atan2(x)
    }
    /// `(v / d, d)` for `m = max(|x|, |y|, |z|) > 0`: the rescaling that lets lengths be
    /// computed without overflow or underflow, with the scale `d` it divided by. The float
    /// types take `d = m` as given (one reciprocal, three products: the cost of the polygon
    /// edge terms' hot path, which pass the largest component), so they behave as their `/`:
    /// an `m` below the largest component gives components above 1 (exact to rounding, no
    /// wrap), and `m <= 0`, a NaN `m` or one so small that `v / m` overflows gives non-finite
    /// components. The fixed-point type is total: it takes a power of two from the largest
    /// of `m` and the components, whatever `m` is (exact shifts: `1/m` itself would saturate
    /// for `m < 1/512`, and a division costs hundreds of instructions on Cortex-M0; see
    /// [`Fixed22`]'s `rescale3`).
    #[inline(always)]
    fn rescale3(v: [Self; 3], m: Self) -> ([Self; 3], Self) {
        let r = Self::ONE / m;
        ([v[0] * r, v[1] * r, v[2] * r], m)
    }
    /// `1/sqrt(self)` for `self > 0`; 0 otherwise (never infinite). The float types compute
    /// `1 / sqrt(x)`; the fixed-point type has its own Newton iteration (no division).
    #[inline(always)]
    fn rsqrt(self) -> Self {
        if self > Self::ZERO {
            Self::ONE / self.sqrt()
        } else {
            Self::ZERO
        }
    }
    /// `(sqrt(self), 1/sqrt(self))` for `self > 0`, `(0, 0)` otherwise: a length and its
    /// reciprocal, as a normalization needs both. Floats: 1 sqrt and 1 division; fixed point:
    /// 1 [`Real::rsqrt`] and 1 product.
    #[inline(always)]
    fn sqrt_rsqrt(self) -> (Self, Self) {
        if self > Self::ZERO {
            let s = self.sqrt();
            (s, Self::ONE / s)
        } else {
            (Self::ZERO, Self::ZERO)
        }
    }
    /// `Some((v / |v|, |v|))` for a finite nonzero `v`, `None` otherwise: the normalization
    /// behind [`crate::Vec3::normalize_with_length`].
    ///
    /// This default (`Fixed22`) rescales by the largest component first
    /// ([`Real::rescale3`]: fixed-point squares of small components vanish and those of large
    /// ones saturate), and a vector whose largest component is not above [`Real::TINY`] counts
    /// as zero. f32 and f64 override it with the lean form (`normalize3_lean` in the `float`
    /// module): the squared length directly, rescaled by a power of two only when it under- or
    /// overflows, so that every finite nonzero vector has a direction; [`Fast32`] with f32's.
    #[inline(always)]
    fn normalize3(v: [Self; 3]) -> Option<([Self; 3], Self)> {
        let m = v[0].abs().max(v[1].abs()).max(v[2].abs());
        if !(m > Self::TINY) {
            return None;
        }
        let ([x, y, z], d) = Self::rescale3(v, m);
        let s2 = x * x + y * y + z * z;
        // Tested after the rescaling, not on `m`: the NaN-aware `max` drops a NaN component,
        // and a NaN or infinite component makes `s2` NaN (a constant `true` for fixed point).
        if !s2.is_finite() {
            return None;
        }
        let (len, inv) = s2.sqrt_rsqrt();
        Some(([x * inv, y * inv, z * inv], len * d))
    }
    /// `Some(v / |v|)` for a finite nonzero `v`, `None` otherwise: [`Real::normalize3`]
    /// without the length (the fixed-point default needs one [`Real::rsqrt`] and no square
    /// root).
    #[inline(always)]
    fn unit3(v: [Self; 3]) -> Option<[Self; 3]> {
        let m = v[0].abs().max(v[1].abs()).max(v[2].abs());
        if !(m > Self::TINY) {
            return None;
        }
        let ([x, y, z], _) = Self::rescale3(v, m);
        let s2 = x * x + y * y + z * z;
        if !s2.is_finite() {
            return None;
        }
        let r = s2.rsqrt();
        Some([x * r, y * r, z * r])
    }
    /// `round(clamp01(self) * max)` (NaN as 0): a unit value to an integer level, as pixel
    /// and depth quantization need. Each type does it in its own arithmetic (the default goes
    /// through f64, which is soft-float on every Cortex-M).
    #[inline(always)]
    fn unit_to_u32(self, max: u32) -> u32 {
        let v = self.clamp01().to_f64() * f64::from(max) + 0.5;
        if v >= f64::from(max) {
            max
        } else {
            v as u32
        }
    }
    /// `floor(self * 2^frac + 1/2)` (round half up) as an `i32`, saturating at `i32::MIN` /
    /// `i32::MAX`; NaN gives 0. `frac <= 30`. The rasterizer's bridge from `T` to integers
    /// (snapped vertices, attribute planes). Exact on every backend while `|self| 2^frac <
    /// 2^22`; each type does it in its own arithmetic (the default goes through f64).
    #[inline(always)]
    fn to_fixed_i32(self, frac: u32) -> i32 {
        let v = self.to_f64() * f64::from(1u32 << frac.min(30)) + 0.5;
        let t = v as i32; // saturating, NaN -> 0
        if f64::from(t) > v {
            t.saturating_sub(1)
        } else {
            t
        }
    }
    /// `x * 2^-frac` (`frac <= 30`): the inverse of [`Real::to_fixed_i32`], exact where the
    /// type holds the value (f32: `|x| < 2^24`; `Fixed22`: `frac >= 22` or no overflow,
    /// saturating otherwise).
    #[inline(always)]
    fn from_fixed_i32(x: i32, frac: u32) -> Self {
        Self::from_f64(f64::from(x) / f64::from(1u32 << frac.min(30)))
    }
    /// `self / n` for a positive integer `n`: the same value as `self / Self::from_u32(n)` on
    /// every backend (the floats divide; [`Fixed22`] divides its raw bits by `n` through a
    /// reciprocal table, bit-identical to its `/` and a fraction of its cost). The Phong
    /// recurrences' `1/i` steps. Like `from_u32`, [`Fixed22`] is exact for `n < 512` only:
    /// from 512 on it divides by the saturated `512 - 2^-22`.
    #[inline(always)]
    fn div_u32(self, n: u32) -> Self {
        self / Self::from_u32(n)
    }
    /// `self * n` for an integer `n`: the same value as `self * Self::from_u32(n)` on every
    /// backend ([`Fixed22`]: two small integer products instead of a full product; like
    /// `from_u32`, for `n < 512` only: from 512 on it multiplies by `512 - 2^-22`; the product
    /// saturates at +-512 in any case).
    #[inline(always)]
    fn mul_u32(self, n: u32) -> Self {
        self * Self::from_u32(n)
    }
    /// `round(self * n * 2^frac)` (`frac <= 30`, ties up) as an `i32`, saturating (NaN gives
    /// 0): a value scaled by an integer straight into a fixed-point integer, without `n` or the
    /// product having to fit the type. The float types compute `(self * n).to_fixed_i32(frac)`
    /// (the product rounded once in the type, then scaled by the power of two and rounded to
    /// an integer: 2 roundings, a product and a conversion); [`Fixed22`] computes it
    /// exactly from its bits (one 32 x 32 -> 64 product and a rounding shift), so neither
    /// `n >= 512` nor a product beyond its range of +-512 saturates. The rasterizer's viewport
    /// transform (normalized device coordinates times the viewport size in sub-pixels).
    #[inline(always)]
    fn mul_u32_to_fixed_i32(self, n: u32, frac: u32) -> i32 {
        (self * Self::from_u32(n)).to_fixed_i32(frac)
    }
    /// `self * self`.
    #[inline(always)]
    fn sq(self) -> Self {
        self * self
    }
    /// `self^n` by repeated squaring (`n` = 0 gives 1).
    #[inline]
    fn powu(self, mut n: u32) -> Self {
        let mut base = self;
        let mut acc = Self::ONE;
        while n > 0 {
            if n & 1 == 1 {
                acc *= base;
            }
            base *= base;
            n >>= 1;
        }
        acc
    }
}
