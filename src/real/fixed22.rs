//! [`Fixed22`]: the fixed-point [`Real`] for chips without an FPU (Cortex-M0/M0+, RV32IMC).
//!
//! # Format
//!
//! One format for every quantity a model takes and returns: **I10F22** (the `fixed` crate's
//! [`fixed::types::I10F22`]): a two's-complement `i32` with 22 fraction bits, range
//! `[-512, 512)`, resolution `2^-22 = 2.4e-7`. (Inside a model some quantities have formats of
//! their own, chosen for their error budget and the Cortex-M0's 32 x 32 -> 32-bit product:
//! "Formats inside the models" below.) Why this one:
//!
//! - The Phong models raise cosines to the power `m <= 255`, which multiplies an absolute error
//!   `d` of the cosine by up to `m`: the cosine needs `d << 1/(1024 * 255) = 3.8e-6`, so at
//!   least ~20 fraction bits (I16F16's `1.5e-5` fails by itself; measured 4e-3 at m = 255).
//! - The recurrences and normalizations reach integers up to `m + 2 = 257` and constants like
//!   `2 pi`, so 9 integer bits plus sign are needed; 22 fraction bits are what remains.
//! - Positions: the models form cross and dot products of unnormalized point differences
//!   (Lambert's edge terms, the clipping), which must stay inside `[-512, 512)`: positions are
//!   limited to `|x| <= 4` ([`Fixed22::COORDINATE_LIMIT`], checked by every constructor and
//!   every `try_` function). Every area-light model here is scale invariant (a scene scaled by
//!   any factor shades the same), so scenes keep their own units through
//!   [`crate::world`]: positions as 64-bit integers (`2^-32` up to `2^30`), and per sample the
//!   light's points minus `p`, exact, scaled by one power of two so that the largest lands in
//!   `[2, 4]`: `2^-22/4` of the light's extent seen from `p` as the resolution.
//! - Near a polygon light's boundary a direction known to `2^-22` absolute is not enough:
//!   the polygon models refuse a shading point within `2^-9` to `2^-7` of a vertex or of an
//!   edge beside it ([`crate::Error::Unresolved`]; the polygon module's `near_limit`), and
//!   form `ua x d` and `ua.ub` exactly where they cancel.
//!
//! # Formats inside the models
//!
//! | quantity | format | why |
//! |---|---|---|
//! | the elementary functions' kernels (`sin`, `exp`, `atan2`, ...) | Q30 polynomials and reductions | 8 more bits than the result, so the kernel's own error stays a fraction of the result's LSB (the table above) |
//! | the Phong polygon's cosine-power recurrence (`polygon::arc`'s `q28`) | Q28 values, Q32 factors in `[0, 1]` | the recurrence runs up to `m + 2 = 257` steps: six more bits than I10F22 keep its drift below the result's LSB |
//! | the polygon Lambert edge terms' unit directions (`polygon::edge::unit_ratio_term`), normalized in that form (`normalize::unit_q15`), and their arc ratio (`elementary::arc_ratio_q30_to_q15`) | Q15 (cosines and cross products in Q30; the ratio's cubic pieces with Q16 coefficients and a Q19 offset) | one 32-bit product (`MULS`) each instead of four 16-bit ones, and a reciprocal square root without its Newton step: `polygon_lambert` 3 832 -> 3 265 (Q15 products) -> 2 182 (Q15 normalization and ratio) Cortex-M0 instructions (2 038 with the horizon test's sign from 16-bit products, exact: the sealed `height_nonneg`), its error against f64 5.5e-6 -> 6.5e-5 (a Lambert term's sensitivity to its directions is about 1: far inside 1/1024) |
//! | the Lambert-type terms' cosine `n . axis` of two unit vectors (`hemi_const`, `sky_ground`, the exact cap, the sphere; the sealed `cos_unit`, `kernels::cos_unit_q15`) | both vectors rounded to Q15, the sum of products in Q30, rounded to Q22 | one `MULS` a component instead of four: with a `UnitVec3` `hemi_const` 94 -> 52, `sky_ground` 170 -> 133 (102 with the cosine kept in Q15 for its three products, two `MULS` each; 90 with the sums `mid + half c` without their unreachable saturation tests: the sealed `mix_by_cos`), `cap_lambert` 118 -> 73, `sphere_lambert` 571 -> 538 Cortex-M0 instructions (495 with the positions' range test by unsigned comparisons and `r/d`'s product without its saturation test, the same bits); a light's fixed axis rounded to Q15 once by its constructor (the sealed `prepare_axis` and `cos_axis`, the same bits: `hemi_const` 52 -> 45); within 5.3e-5 of the exact cosine (these terms move no more than their cosine: far inside 1/1024) |
//!
//! The Phong terms keep their directions in Q22: at `m = 255` a cosine's error is multiplied
//! by up to `m`, and `255 x 2^-16 = 3.9e-3` from Q15 directions would exceed the 1/1024.
//!
//! Arithmetic **saturates** (never wraps): `+`, `-`, unary `-` are the `fixed` crate's
//! saturating operations; `*` is this module's own product, exactly `floor(a b / 2^22)` as the
//! `fixed` crate's (so each carries at most 1 LSB), saturated; `/` is this module's own
//! (below). Inside the supported ranges nothing saturates: the accuracy tests would see it.
//!
//! # Elementary functions (own code; all total, all in `i32`/`u32` integer arithmetic)
//!
//! The kernels live in `fixed22/kernels.rs` (products, divisions) and `fixed22/elementary.rs`
//! (the functions, square roots to logarithms). Instruction counts are Cortex-M0 (ARMv6-M: no
//! divide, no `CLZ`, a 32 x 32 -> 32-bit `MULS`), measured in the QEMU budget harness.
//!
//! | function | method | bound (tested) | measured |
//! |---|---|---|---|
//! | `a * b` | four 16 x 16-bit products combined in 32-bit integers (`H 2^10 + w/2^6`), one range test of the high part; 64-bit arithmetic only when saturating | exact floor, saturated (`tests/fixed_kernels.rs`) | ~27 instructions (was ~40 with a 64-bit combine and clamp) |
//! | `a / b` | `|b|` normalized by the leading-zero count, its reciprocal from a 16-entry quadratic start and one Newton step (`recip_core`, within 3 units of `floor(2^63/d)`, below it), the quotient estimate from one full product, then the remainder (one `MULS`) corrects it and gives the rounding bit; no division instruction or call | 0.5 LSB (correctly rounded); saturates on overflow; `x / 0` = MAX for `x > 0`, MIN (-512) for `x < 0`, `0 / 0` = 0 | 0.500 LSB; ~150 instead of ~300 instructions (22 restoring steps and a `u32` division) |
//! | `div_u32(n)`, `n <= 256` | the raw bits times `ceil(2^32/o)` (`n = o 2^k`, a 127-entry table) and one remainder correction | bit-identical to `/ from_u32(n)` | ~35 instead of ~290 instructions |
//! | SH9 irradiance's `k0 + sum k[i] m[i]` (8 terms, `|m| <= 1.5`: the monomials of a unit normal) | per term 4 partial products (`k` split at bit 16, `m` at bit 11, once for the three channels) summed exactly in four `i32`s, rounded down once; 64-bit arithmetic only beyond about 256 (cold) | exact `floor`, saturated (the crate's unit tests) | 705 instead of 1434 instructions a `UnitVec3` call |
//! | `mul_u32(n)`, `n < 512` | two 16 x 9-bit products | bit-identical to `* from_u32(n)` | |
//! | `sqrt`, `rsqrt`, `sqrt_rsqrt` | one core: `x = m 4^j`, `m` in [1, 4); a quadratic start per eighth of `[1, 4)` (24-entry table, relative 2^-15.8), one Newton step for `1/sqrt m` in `u32` (relative 2^-29.5); `sqrt = m (1/sqrt m)`; all rounded to nearest | sqrt 1 LSB; rsqrt 1 LSB + 2^-28 relative; 0 for `x <= 0`, rsqrt MAX below `2^-18` | sqrt 0.707 LSB (every input; 0.679 on the random ones), rsqrt 0.553 |
//! | unit vectors (`Vec3::to_unit`, `normalize`; the models' directions) | rescaled by a power of two to a largest component in `[1, 2)`, the sum of squares in `[1, 12]` (three exact products), `1/sqrt` of it from the same start rounded to 16 bits and one Newton step of four `MULS` (`normalize::unit_rsqrt`, relative 2^-28), three products | 3 LSB a component against f64 of the rounded vector (`tests/fixed_kernels.rs`); `y` within 2^-28 on every sum of squares (`fixed22::tests`) | 2.01 LSB (400 000 random vectors); about 210 M0 instructions with the rescaling (`hemi_const`'s `Vec3` row, 250, less its `UnitVec3` row, 40) |
//! | `atan2` | octant reduction to `t = n/d` in [0, 1], the ratio from the division's reciprocal (`recip_core`, Q31); a cubic piece of `atan` per 32nd of [0, 1] (512-byte table), each product as wide as its term needs; in Q30 (kernel error 3.4e-9) | 1 LSB; `atan2(0, 0) = 0`; `atan2(-y, x) = -atan2(y, x)` exactly | 0.516 LSB (was 0.542); ~190 instead of ~465 instructions |
//! | `arc_ratio` (`acos(c)/sqrt(1 - c^2)` for `c` in [0, 1]: the polygon Lambert edge term's `theta/sin(theta)`) | `x = 1 - c`; a cubic piece per 16th of [0, 1] (256-byte table, Chebyshev interpolants in Q22), Horner's rule with exact floors (`mul_bits_le2`); `c` clamped to [0, 1] | 3.9e-7 (1.62 LSB) on every `c` in [0, 1] (`tests/fixed_exhaustive.rs`, in the suite) | 1.610 LSB; 3 products (a degree-8 polynomial in Q25 took 8, within 5.4e-7) |
//! | `sin`, `cos` | reduction by `pi/2` with a Q38 `pi/2`, minimax polynomials of degree 7 (sin) and 8 (cos) in Q30 on `[-pi/4, pi/4]` | 1 LSB for `|x| <= 64`; within `[-1, 1]` (+2 LSB) everywhere | 0.522 LSB |
//! | `exp` | `x = k ln 2 + r`, degree-6 minimax polynomial for `e^r` in Q30, shift by `k` | `(1 + e^x)` LSB; MAX above `9 ln 2`, 0 below -17 | 0.500 |
//! | `ln` | `x = 2^e m`, `m` in `[1/sqrt 2, sqrt 2)`, degree-9 minimax polynomial for `ln(1 + t)` in Q30 | 1 LSB; -512 (MIN) for `x <= 0` | 0.521 LSB |
//!
//! (LSB = `2^-22`. Tests: 10^6 random inputs, every edge input, and exhaustive sweeps of the
//! 2^16 smallest inputs and of the neighbourhoods of the reduction boundaries; `tests/fixed.rs`
//! and `tests/fixed_kernels.rs`.)
//!
//! Exhaustive sweeps (`tests/fixed_exhaustive.rs`, in the test profile with overflow checks on,
//! so no input overflows a kernel's integer arithmetic): every one of the 2^32 inputs of `sqrt`,
//! `rsqrt`, `sqrt_rsqrt` (bit-identical to the pair), `ln`, `sin`, `cos` and `exp` against f64
//! of the exact input, and the documented values at 0, the negatives and the saturating ends.
//! Maxima: sqrt 0.707 LSB (above the 0.679 of the random inputs), rsqrt 0.553 (in units of
//! 1 LSB + 2^-28 relative), ln 0.522 LSB, sin and cos 0.523 LSB on `|x| <= 64` (0.621 LSB on
//! every 7th input beyond), exp 0.500 (in units of `(1 + e^x)` LSB). Division (exactly the
//! correctly rounded quotient, ties away from zero) and `atan2` (0.515 LSB) on grids of
//! 3.4e8 pairs each: a stride over all 2^32 numerators (and `y`) against 2579 divisors (and
//! `x`) of every magnitude, every divisor's saturation boundary, and every pair of small
//! integers. These take about 6 CPU-minutes and run with `-- --ignored` (a CI step of their
//! own); grids of 4.7e7 pairs run with the suite.
//!
//! Why not the `fixed` crate's own division, square root and `cordic`: `fixed`'s `/` divides
//! 64-bit integers (a `__aeabi_ldivmod` call on Cortex-M0, which the per-sample code must not
//! make) and panics on division by zero; its `sqrt` is a bit-by-bit integer square root of the
//! 54-bit `x 2^22`, measured at about 390 instructions per call on the M0 (the demo shade's
//! profile) and rounded down (1.000 LSB), where the table-seeded Newton step above takes about
//! 130 and rounds (0.707 LSB at worst over every input): it measurably beats the crate, about 3x, and is more accurate.
//! The `cordic` crate iterates once per result bit over 64-bit (`U0F64`) angle tables, ~30
//! rounds of 64-bit shifts and adds on a 32-bit core per call, where the polynomials above
//! reach 1 LSB with 5 to 9 multiplies. The polynomial coefficients are minimax fits (Lawson's
//! iteration) or Chebyshev interpolants, quantized to Q30.
//!
//! Products of 32-bit halves written the textbook unsigned way (`ah bh + (ah bl >> 16) + ...`)
//! are recognized by LLVM as a 64-bit multiply and compiled to a `__aeabi_lmul` call on
//! ARMv6-M; the kernels keep their operands below 2^31 and combine signed halves, which it
//! leaves alone (checked in the M0 profile).

use super::Real;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};
use fixed::types::I10F22;

/// The model ids of `docs/models.md` that the fixed-point path supports within 1/1024 (the
/// README's fixed-point table): the eval protocol's `--backend fixed` answers these and
/// "unsupported" for the others. The other models compile for `Fixed22` too, untested.
pub const SUPPORTED_MODELS: [&str; 18] = [
    "hemi_const",
    "hemi_cos",
    "sky_overcast",
    "sky_ground",
    "cap_lambert",
    "cap_lambert_hermite",
    "sphere_lambert",
    "sphere_lambert_hermite",
    "polygon_lambert",
    "phong_hemi_const",
    "phong_hemi_cos",
    "phong_cap",
    "phong_sphere",
    "phong_polygon",
    "sh9_irradiance",
    "sh9_disc_irradiance",
    "superellipse_shape",
    "distance_falloff",
];

/// Fraction bits of [`Fixed22`].
const FRAC: u32 = 22;

/// A fixed-point number in I10F22 (range `[-512, 512)`, resolution `2^-22`) implementing
/// [`Real`] with saturating arithmetic and the crate's own elementary functions: see the
/// [module docs](self) for the format, the supported ranges and every error bound.
///
/// ```
/// use arealight::{Fixed22, Real};
/// let x = Fixed22::from_f64(0.5);
/// assert_eq!(x.to_f64(), 0.5);
/// assert_eq!((Fixed22::MAX + Fixed22::ONE), Fixed22::MAX); // saturates, never wraps
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Fixed22(I10F22);

impl Fixed22 {
    /// The largest value, `512 - 2^-22`.
    pub const MAX: Self = Fixed22(I10F22::MAX);
    /// The smallest value, `-512`.
    pub const MIN: Self = Fixed22(I10F22::MIN);
    /// The resolution, `2^-22`.
    pub const DELTA: Self = Fixed22(I10F22::DELTA);
    /// The largest coordinate the constructors accept for positions (`|x| <= 4`), so that
    /// products of point differences stay inside the format (see the module docs).
    pub const COORDINATE_LIMIT: f64 = 4.0;

    /// From the raw `i32` (the value times `2^22`).
    #[inline(always)]
    pub const fn from_bits(bits: i32) -> Self {
        Fixed22(I10F22::from_bits(bits))
    }
    /// The raw `i32` (the value times `2^22`).
    #[inline(always)]
    pub const fn to_bits(self) -> i32 {
        self.0.to_bits()
    }
    /// From the `fixed` crate's type.
    #[inline(always)]
    pub const fn from_fixed(x: I10F22) -> Self {
        Fixed22(x)
    }
    /// As the `fixed` crate's type.
    #[inline(always)]
    pub const fn to_fixed(self) -> I10F22 {
        self.0
    }
}

impl core::fmt::Display for Fixed22 {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        core::fmt::Display::fmt(&self.0, f)
    }
}

/// `x * 2^22` rounded, for constants (evaluated at compile time).
const fn q22(x: f64) -> Fixed22 {
    let s = x * (1u64 << FRAC) as f64;
    Fixed22::from_bits(if s >= 0.0 {
        (s + 0.5) as i32
    } else {
        (s - 0.5) as i32
    })
}

impl Add for Fixed22 {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Fixed22(self.0.saturating_add(o.0))
    }
}
impl Sub for Fixed22 {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Fixed22(self.0.saturating_sub(o.0))
    }
}
impl Mul for Fixed22 {
    type Output = Self;
    /// The product rounded down (as the `fixed` crate's), saturating; through this module's
    /// 32 x 32 -> 64-bit `wide_mul` instead of the `fixed` crate's `i64` product, which is a
    /// 64 x 64-bit library call on Cortex-M0.
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        Fixed22::from_bits(mul_bits(self.to_bits(), o.to_bits()))
    }
}
impl Div for Fixed22 {
    type Output = Self;
    #[inline]
    fn div(self, o: Self) -> Self {
        Fixed22::from_bits(div_bits(self.to_bits(), o.to_bits()))
    }
}
impl Neg for Fixed22 {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Fixed22(self.0.saturating_neg())
    }
}
impl AddAssign for Fixed22 {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}
impl SubAssign for Fixed22 {
    #[inline(always)]
    fn sub_assign(&mut self, o: Self) {
        *self = *self - o;
    }
}
impl MulAssign for Fixed22 {
    #[inline(always)]
    fn mul_assign(&mut self, o: Self) {
        *self = *self * o;
    }
}

mod elementary;
mod kernels;
mod normalize;
mod sealed;
#[cfg(feature = "sh9")]
mod sh9_q15;
#[cfg(test)]
mod tests;
use elementary::*;
#[cfg(all(feature = "polygon", any(feature = "phong", feature = "moments")))]
pub(crate) use kernels::recip_q32;
use kernels::*;
use normalize::{
    magnitude_top, rescale_by_top, rescale_for_unit, unit_rsqrt, unit_scale, unit_sqrt_rsqrt,
    unscale_length,
};

impl Real for Fixed22 {
    const ZERO: Self = Fixed22::from_bits(0);
    const ONE: Self = Fixed22::from_bits(1 << FRAC);
    const TWO: Self = Fixed22::from_bits(2 << FRAC);
    const HALF: Self = Fixed22::from_bits(1 << (FRAC - 1));
    const PI: Self = q22(core::f64::consts::PI);
    const FRAC_PI_2: Self = q22(core::f64::consts::FRAC_PI_2);
    const TAU: Self = q22(core::f64::consts::TAU);
    const FRAC_1_PI: Self = q22(core::f64::consts::FRAC_1_PI);
    const FRAC_1_TAU: Self = q22(0.5 * core::f64::consts::FRAC_1_PI);
    const EPSILON: Self = Fixed22::DELTA;
    /// 2^-16 (64 LSB): a vector whose largest component is below it has no reliable
    /// direction (fewer than 6 significant bits) and counts as zero.
    const TINY: Self = Fixed22::from_bits(1 << (FRAC - 16));
    const RESOLUTION: Self = Fixed22::DELTA;
    const MAX_PHONG_EXPONENT: u32 = 255;
    const COORDINATE_LIMIT: f64 = Fixed22::COORDINATE_LIMIT;

    /// Rounds to nearest and saturates; NaN gives 0.
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        if x.is_nan() {
            Self::ZERO
        } else {
            Fixed22(I10F22::saturating_from_num(x))
        }
    }
    /// Exact below 512; saturates to MAX above.
    #[inline(always)]
    fn from_u32(x: u32) -> Self {
        if x >= 1 << (31 - FRAC) {
            Self::MAX
        } else {
            Fixed22::from_bits((x << FRAC) as i32)
        }
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self.0.to_num::<f64>()
    }
    #[inline(always)]
    fn abs(self) -> Self {
        Fixed22(self.0.saturating_abs())
    }
    /// Own table-seeded Newton iteration (see `rsqrt_core`), rounded; 0 for `x <= 0`.
    #[inline]
    fn sqrt(self) -> Self {
        Fixed22::from_bits(sqrt_bits(self.to_bits()))
    }
    /// 16 cubic pieces in Q22 (`arc_ratio_bits`, a 256-byte table): within 3.9e-7 of
    /// `theta/sin(theta)` for `c` in [0, 1] (every input measured); `c` outside [0, 1] is
    /// clamped.
    #[inline(always)]
    fn arc_ratio(self) -> Option<Self> {
        Some(Fixed22::from_bits(arc_ratio_bits(self.to_bits())))
    }
    #[inline]
    fn atan2(self, x: Self) -> Self {
        Fixed22::from_bits(atan2_bits(self.to_bits(), x.to_bits()))
    }
    #[inline]
    fn sin(self) -> Self {
        Fixed22::from_bits(q30_to_q22(sin_cos_q30(self.to_bits()).0))
    }
    #[inline]
    fn cos(self) -> Self {
        Fixed22::from_bits(q30_to_q22(sin_cos_q30(self.to_bits()).1))
    }
    /// Saturates to MAX for `x > 9 ln 2`; 0 below -17.
    #[inline]
    fn exp(self) -> Self {
        Fixed22::from_bits(exp_bits(self.to_bits()))
    }
    /// -512 (MIN) for `x <= 0`.
    #[inline]
    fn ln(self) -> Self {
        Fixed22::from_bits(ln_bits(self.to_bits()))
    }
    #[inline(always)]
    fn is_finite(self) -> bool {
        true
    }
    /// Own Newton iteration (see the module docs); 0 for `x <= 0`, MAX where the result
    /// exceeds the range (`x < 2^-18`).
    #[inline]
    fn rsqrt(self) -> Self {
        Fixed22::from_bits(rsqrt_bits(self.to_bits()))
    }
    /// In integers: a rounding shift of the bits (exact).
    #[inline(always)]
    fn to_fixed_i32(self, frac: u32) -> i32 {
        let (bits, frac) = (self.to_bits() as i64, frac.min(30));
        let v = if frac <= FRAC {
            let sh = FRAC - frac;
            if sh == 0 {
                bits
            } else {
                (bits + (1 << (sh - 1))) >> sh
            }
        } else {
            bits << (frac - FRAC)
        };
        v.clamp(i32::MIN as i64, i32::MAX as i64) as i32
    }
    /// In integers: a shift (exact for `frac >= 22`; saturating where the value exceeds the
    /// range; rounding half up where `frac > 22` drops bits).
    #[inline(always)]
    fn from_fixed_i32(x: i32, frac: u32) -> Self {
        let frac = frac.min(30);
        let bits = if frac >= FRAC {
            let sh = frac - FRAC;
            if sh == 0 {
                x as i64
            } else {
                ((x as i64) + (1 << (sh - 1))) >> sh
            }
        } else {
            (x as i64) << (FRAC - frac)
        };
        Fixed22::from_bits(bits.clamp(i32::MIN as i64, i32::MAX as i64) as i32)
    }
    /// In integers: `(bits max + 2^21) >> 22` from the clamped bits (a 32 x 32 -> 64 product);
    /// `max` up to 2^16 keeps every level reachable (the format's 2^22 steps per unit).
    #[inline(always)]
    fn unit_to_u32(self, max: u32) -> u32 {
        let bits = self.clamp01().to_bits(); // [0, 2^22]
        let max = max.min(i32::MAX as u32) as i32;
        ((wide_mul(bits, max) + (1 << (FRAC - 1))) >> FRAC) as u32
    }
    /// Both from one `rsqrt_core`: the cost of one and a product.
    #[inline]
    fn sqrt_rsqrt(self) -> (Self, Self) {
        let x = self.to_bits();
        if x <= 0 {
            return (Self::ZERO, Self::ZERO);
        }
        let (m, j, y) = rsqrt_core(x as u32);
        (
            Fixed22::from_bits(sqrt_out(m, j, y)),
            Fixed22::from_bits(rsqrt_out(j, y)),
        )
    }
    /// Scales by a power of two (exact shifts, no division) chosen from the largest of `m`
    /// and the components' magnitudes, whatever `m` is (total: a component larger than `m`,
    /// or `m <= 0`, no longer shifts bits out of the top): the largest component lands in
    /// [1/2, 1) (in [1, 2] for a largest value of 256 or more: the shift right stops at 8),
    /// unless `m` exceeds it (then `m` lands there), and the scale returned is that power of
    /// two. All zero (and `m <= 0`): `(v, 1)`. Cost: three absolute values and ORs more than the shift from `m` alone,
    /// which the normalizations (`normalize3`, `unit3`, their `m` the largest component by
    /// construction) keep.
    #[inline]
    fn rescale3(v: [Self; 3], m: Self) -> ([Self; 3], Self) {
        let top = (m.to_bits().max(0) as u32)
            | v[0].to_bits().unsigned_abs()
            | v[1].to_bits().unsigned_abs()
            | v[2].to_bits().unsigned_abs();
        rescale_by_top(v, top)
    }
    /// The default's body, with the rescaling by its `m` (the largest component by
    /// construction: no test of the components needed).
    #[inline(always)]
    ///
    /// The squares and the three scalings by `1/|v|` use `mul_bits_le2`: after the
    /// rescaling every component is at most 2 (`rescale_for_unit`) and `1/|v|` at most 1 (the
    /// largest component is at least 1), so the exact product needs no saturation test and
    /// the sum of squares (at most 12) none either: the same bits as `*` and `+`, about 100
    /// fewer Cortex-M0 instructions a call; and each product takes three 32-bit `MULS`
    /// instead of four (factors up to 2), about 24 fewer. The length goes back to `v`'s scale
    /// by a shift (`normalize::unscale_length`, the bits of the product by the power of two
    /// it replaces): about 30 fewer again (`phong_polygon` at m = 16, whose edges' offsets
    /// take it, 9 367 -> 9 365 with a `UnitVec3`).
    fn normalize3(v: [Self; 3]) -> Option<([Self; 3], Self)> {
        let top = magnitude_top(v, Self::TINY)?;
        let ([x, y, z], k) = rescale_for_unit(v, top);
        let (len, inv) = unit_sqrt_rsqrt(unit_scale(x, y, z));
        let s = |c: Self| Fixed22::from_bits(mul_bits_le2_round(c.to_bits(), inv.to_bits()));
        Some(([s(x), s(y), s(z)], unscale_length(len, k)))
    }
    /// The default's body, with the rescaling by its `m` (see `normalize3`).
    #[inline(always)]
    fn unit3(v: [Self; 3]) -> Option<[Self; 3]> {
        let top = magnitude_top(v, Self::TINY)?;
        let ([x, y, z], _) = rescale_for_unit(v, top);
        let r = unit_rsqrt(unit_scale(x, y, z));
        let s = |c: Self| Fixed22::from_bits(mul_bits_le2_round(c.to_bits(), r.to_bits()));
        Some([s(x), s(y), s(z)])
    }
    #[inline(always)]
    fn is_nan_like(self) -> bool {
        false
    }
    /// By a table of 127 reciprocals and one correction (see `div_u32_bits`): bit-identical to
    /// `self / Fixed22::from_u32(n)`, about 35 instead of ~290 instructions on the M0.
    #[inline]
    fn div_u32(self, n: u32) -> Self {
        Fixed22::from_bits(div_u32_bits(self.to_bits(), n))
    }
    /// Two small integer products (see `mul_u32_bits`): bit-identical to
    /// `self * Fixed22::from_u32(n)`.
    #[inline(always)]
    fn mul_u32(self, n: u32) -> Self {
        Fixed22::from_bits(mul_u32_bits(self.to_bits(), n))
    }
    /// Exact: `bits n` as a 64-bit product (`n` clamped to `2^31 - 1`), shifted right by
    /// `22 - frac` rounding half up (or left by `frac - 22`), clamped to `i32`.
    #[inline(always)]
    fn mul_u32_to_fixed_i32(self, n: u32, frac: u32) -> i32 {
        let p = wide_mul(self.to_bits(), n.min(i32::MAX as u32) as i32);
        let frac = frac.min(30);
        let v = if frac <= FRAC {
            let sh = FRAC - frac;
            if sh == 0 {
                p
            } else {
                (p >> sh) + ((p >> (sh - 1)) & 1)
            }
        } else {
            p.clamp(-(1 << 40), 1 << 40) << (frac - FRAC)
        };
        v.clamp(i32::MIN as i64, i32::MAX as i64) as i32
    }
}
