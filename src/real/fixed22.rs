//! [`Fixed22`]: the fixed-point [`Real`] for chips without an FPU (Cortex-M0/M0+, RV32IMC).
//!
//! # Format
//!
//! One format for every quantity a model touches: **I10F22** (the `fixed` crate's
//! [`fixed::types::I10F22`]): a two's-complement `i32` with 22 fraction bits, range
//! `[-512, 512)`, resolution `2^-22 = 2.4e-7`. Why this one:
//!
//! - The Phong models raise cosines to the power `m <= 255`, which multiplies an absolute error
//!   `d` of the cosine by up to `m`: the cosine needs `d << 1/(1024 * 255) = 3.8e-6`, so at
//!   least ~20 fraction bits (I16F16's `1.5e-5` fails by itself; measured 4e-3 at m = 255).
//! - The recurrences and normalizations reach integers up to `m + 2 = 257` and constants like
//!   `2 pi`, so 9 integer bits plus sign are needed; 22 fraction bits are what remains.
//! - Positions: the models form cross and dot products of unnormalized point differences
//!   (Lambert's edge terms, the clipping), which must stay inside `[-512, 512)`: positions are
//!   limited to `|x| <= 4` ([`Fixed22::COORDINATE_LIMIT`], checked by every constructor; a
//!   shading point beyond it gives a finite but meaningless value). Every area-light model
//!   here is scale invariant (a scene scaled by any factor shades the same), so the limit is
//!   no restriction: scale the scene into the cube, which leaves `2^-22 / 8 = 3e-8` of its
//!   size as the position resolution, as fine as f32's at the cube's corners.
//!
//! Arithmetic **saturates** (never wraps): `+`, `-`, unary `-` and `*` are the `fixed` crate's
//! saturating operations (products are rounded down, so each carries at most 1 LSB);
//! `/` is this module's own (below). Inside the supported ranges nothing saturates: the
//! accuracy tests would see it.
//!
//! # Elementary functions (own code; all total, all in `i32`/`i64` integer arithmetic)
//!
//! | function | method | bound (tested) | measured |
//! |---|---|---|---|
//! | `a / b` | `u32` division for the integer part, 22 restoring-division steps for the fraction and one for rounding; no 64-bit division | 0.5 LSB (correctly rounded); saturates on overflow; `x / 0` = +-MAX, `0 / 0` = 0 | 0.500 LSB |
//! | `sqrt` | the `fixed` crate's integer square root (rounded down) | 1 LSB; 0 for `x <= 0` | 1.000 LSB |
//! | `rsqrt` | `x = m 2^sh`, `m` in [1, 4); a quadratic start per octave pair and two Newton steps in Q30; no division | 1 LSB + 2^-28 relative; 0 for `x <= 0`, MAX below `2^-18` | 0.511 (of the bound) |
//! | `atan2` | octant reduction, the ratio `t <= 1` by 30 restoring-division steps, odd minimax polynomial of degree 17 for `atan t` in Q30 (kernel error 5.8e-9) | 1 LSB; `atan2(0, 0) = 0` | 0.542 LSB |
//! | `sin`, `cos` | reduction by `pi/2` with a Q38 `pi/2`, minimax polynomials of degree 7 (sin) and 8 (cos) in Q30 on `[-pi/4, pi/4]` | 1 LSB for `|x| <= 64`; within `[-1, 1]` (+2 LSB) everywhere | 0.522 LSB |
//! | `exp` | `x = k ln 2 + r`, degree-6 minimax polynomial for `e^r` in Q30, shift by `k` | `(1 + e^x)` LSB; MAX above `9 ln 2`, 0 below -17 | 0.500 |
//! | `ln` | `x = 2^e m`, `m` in `[1/sqrt 2, sqrt 2)`, degree-9 minimax polynomial for `ln(1 + t)` in Q30 | 1 LSB; -512 (MIN) for `x <= 0` | 0.521 LSB |
//!
//! (LSB = `2^-22`. Tests: 10^6 random inputs, every edge input, and exhaustive sweeps of the
//! 2^16 smallest inputs and of the neighbourhoods of the reduction boundaries; `tests/fixed.rs`.)
//!
//! Why not the `fixed` crate's own division and `cordic`: `fixed`'s `/` divides 64-bit
//! integers (a `__aeabi_ldivmod` call on Cortex-M0, which the per-sample code must not make)
//! and panics on division by zero; the `cordic` crate iterates once per result bit over
//! 64-bit (`U0F64`) angle tables, ~30 rounds of 64-bit shifts and adds on a 32-bit core per
//! call, where the polynomials above reach 1 LSB with about 11 multiplies. The polynomial
//! coefficients are
//! minimax fits (Lawson's iteration), quantized to Q30.
//!
//! Cost on Cortex-M0 (no hardware divide, 32x32->32 multiply): every product is a 32x32->64
//! multiply; `/` is one `u32` division plus ~23 shift-compare-subtract steps.

use super::Real;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};
use fixed::types::I10F22;

/// The model ids of `models.md` that the fixed-point path supports within 1/1024 (the
/// README's fixed-point table): the eval protocol's `--backend fixed` answers these and
/// "unsupported" for the others. The other models compile for `Fixed22` too, untested.
pub const SUPPORTED_MODELS: [&str; 16] = [
    "hemi_const",
    "hemi_cos",
    "sky_overcast",
    "sky_ground",
    "cap_lambert_hermite",
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

/// `a * b` in Q22, rounded down, saturated.
#[inline(always)]
fn mul_bits(a: i32, b: i32) -> i32 {
    let p = wide_mul(a, b) >> FRAC;
    p.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
}

/// `a / b` in Q22, correctly rounded (ties away from zero), saturating; `x / 0` is +-MAX by the
/// sign of `x` (0 for `0 / 0`). No 64-bit division: the integer part is one `u32` division,
/// the 22 fraction bits and the rounding bit are restoring-division steps on the remainder
/// (which stays below the divisor <= 2^31, so doubling it never overflows a `u32`).
fn div_bits(a: i32, b: i32) -> i32 {
    let negative = (a < 0) != (b < 0);
    let (ua, ub) = (a.unsigned_abs(), b.unsigned_abs());
    let saturated = if negative { i32::MIN } else { i32::MAX };
    if ub == 0 {
        return if ua == 0 { 0 } else { saturated };
    }
    // |a/b| >= 2^9 cannot be represented (2^31 / 2^22).
    if u64::from(ua) >= u64::from(ub) << (31 - FRAC) {
        return saturated;
    }
    let mut q = ua / ub; // < 2^9
    let mut r = ua - q * ub;
    for _ in 0..FRAC {
        r <<= 1;
        q <<= 1;
        if r >= ub {
            r -= ub;
            q |= 1;
        }
    }
    // Round half away from zero: the next quotient bit.
    if r >= ub - r {
        q += 1;
    }
    if negative {
        // q <= 2^31 here, so -q fits (and -2^31 is i32::MIN).
        (q as i64).wrapping_neg() as i32
    } else if q > i32::MAX as u32 {
        i32::MAX
    } else {
        q as i32
    }
}

/// `floor(num * 2^30 / den)` for `num <= den`, `den > 0`: 30 restoring-division steps.
fn ratio_q30(num: u32, den: u32) -> u32 {
    if num >= den {
        return 1 << 30;
    }
    let (mut r, mut q) = (num, 0u32);
    for _ in 0..30 {
        r <<= 1;
        q <<= 1;
        if r >= den {
            r -= den;
            q |= 1;
        }
    }
    q
}

/// `a * b` exactly, from four 16 x 16-bit products. ARMv6-M (Cortex-M0) has only a
/// 32 x 32 -> 32-bit multiply, and the compiler's `i64` product is a call to the 64 x 64-bit
/// `__aeabi_lmul`; this is the 32 x 32 -> 64 product the fixed-point path needs, inline.
/// (Measured in the QEMU harness: see the module docs.)
#[inline(always)]
fn wide_mul(a: i32, b: i32) -> i64 {
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    // |ah|, |bh| <= 2^15 and al, bl < 2^16: the cross products fit an i32, the low one a u32.
    let hh = i64::from(ah * bh);
    let mid = i64::from(ah * bl) + i64::from(al * bh);
    let ll = i64::from((al as u32) * (bl as u32));
    (hh << 32) + (mid << 16) + ll
}

/// `x * y` of two Q30 values with `|x|, |y| < 2` (so each fits an `i32`), rounded down.
#[inline(always)]
fn mul_q30(x: i64, y: i64) -> i64 {
    debug_assert!(x == i64::from(x as i32) && y == i64::from(y as i32));
    wide_mul(x as i32, y as i32) >> 30
}

/// `x * y` of two Q30 values of any size (a 64-bit product).
#[inline(always)]
fn mul_q30_i64(x: i64, y: i64) -> i64 {
    (x * y) >> 30
}

/// Horner's rule in Q30 over `c[0] + c[1] z + c[2] z^2 + ...`.
#[inline(always)]
fn horner_q30(c: &[i64], z: i64) -> i64 {
    let mut acc = 0i64;
    let mut i = c.len();
    while i > 0 {
        i -= 1;
        acc = c[i] + mul_q30(acc, z);
    }
    acc
}

/// Q30 to Q22, rounded to nearest, saturated.
#[inline(always)]
fn q30_to_q22(x: i64) -> i32 {
    let r = (x + (1 << 7)) >> 8;
    r.clamp(i32::MIN as i64, i32::MAX as i64) as i32
}

// Minimax coefficients, Q30 (fitted by Lawson's iteration on 4000 Chebyshev nodes).
/// `atan t = t P(t^2)`, `t` in [0, 1]: max error 5.8e-9.
const ATAN_Q30: [i64; 9] = [
    1073741702, -357906035, 214597040, -152055038, 112731566, -77683668, 42714737, -15463324,
    2637884,
];
/// `sin r = r P(r^2)`, `|r| <= pi/4`: max error 1.2e-9.
const SIN_Q30: [i64; 4] = [1073741809, -178956649, 8945971, -208973];
/// `cos r = P(r^2)`, `|r| <= pi/4`: max error 4.7e-11.
const COS_Q30: [i64; 5] = [1073741824, -536870908, 44739189, -1491064, 26178];
/// `e^r = P(r)`, `r` in [0, ln 2): max error 2.6e-9.
const EXP_Q30: [i64; 7] = [
    1073741827, 1073741427, 536879948, 178879952, 45050186, 8310826, 2119227,
];
/// `ln(1 + t) = t P(t)`, `t` in [1/sqrt(2) - 1, sqrt(2) - 1]: max error 4.6e-9.
const LN1P_Q30: [i64; 9] = [
    1073741696, -536870620, 357931939, -268470760, 214091674, -177520736, 161787055, -156520659,
    93339587,
];

/// `1/sqrt(m)` for `m` in [1, 2) and in [2, 4): quadratic minimax starts (relative error
/// 3.2e-3) for two Newton steps (then 3.5e-10).
const RSQRT_LO_Q30: [i64; 3] = [1696124904, -784383972, 158578317];
const RSQRT_HI_Q30: [i64; 3] = [1199341422, -277321613, 28032951];

const PI_Q30: i64 = 3_373_259_426; // pi 2^30
const FRAC_PI_2_Q30: i64 = 1_686_629_713; // pi/2 2^30
const FRAC_PI_2_Q38: i64 = 431_777_206_567; // pi/2 2^38
const FRAC_2_PI_Q32: i64 = 2_734_261_102; // 2/pi 2^32
const LN2_Q30: i64 = 744_261_118; // ln 2 2^30
const LN2_Q38: i64 = 190_530_846_202; // ln 2 2^38
const INV_LN2_Q32: i64 = 6_196_328_019; // 1/ln 2 2^32
const SQRT2_Q30: u32 = 1_518_500_250; // sqrt 2 2^30

/// `atan2(y, x)` in Q30.
fn atan2_q30(y: i32, x: i32) -> i64 {
    if x == 0 && y == 0 {
        return 0;
    }
    let (ax, ay) = (x.unsigned_abs(), y.unsigned_abs());
    let swap = ay > ax;
    let t = i64::from(if swap {
        ratio_q30(ax, ay)
    } else {
        ratio_q30(ay, ax)
    });
    let z = mul_q30(t, t);
    let mut a = mul_q30(t, horner_q30(&ATAN_Q30, z));
    if swap {
        a = FRAC_PI_2_Q30 - a;
    }
    if x < 0 {
        a = PI_Q30 - a;
    }
    if y < 0 {
        -a
    } else {
        a
    }
}

/// `(sin x, cos x)` in Q30 of a Q22 argument.
fn sin_cos_q30(x: i32) -> (i64, i64) {
    let x = i64::from(x);
    // k = round(x / (pi/2)); |x 2/pi 2^32| < 2^31 2^32 fits an i64.
    let k = (x * FRAC_2_PI_Q32 + (1 << 53)) >> 54;
    let r = ((x << 16) - k * FRAC_PI_2_Q38 + (1 << 7)) >> 8; // Q30, |r| <= pi/4 (+ rounding)
    let z = mul_q30(r, r);
    let s = mul_q30(r, horner_q30(&SIN_Q30, z));
    let c = horner_q30(&COS_Q30, z);
    match k & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// `e^x` in Q22 of a Q22 argument, saturated.
fn exp_bits(x: i32) -> i32 {
    // e^x < 2^9 needs x < 9 ln 2 = 6.2383 (Q22: 26165279.6).
    if x > 26_165_279 {
        return i32::MAX;
    }
    // e^-17 = 4.1e-8 is below half an LSB.
    if x < -17 << FRAC {
        return 0;
    }
    let x = i64::from(x);
    let k = (x * INV_LN2_Q32) >> (FRAC + 32); // floor(x / ln 2), in [-25, 9]
    let r = ((x << 16) - k * LN2_Q38) >> 8; // Q30 in [0, ln 2) (to rounding)
    let p = horner_q30(&EXP_Q30, r); // Q30 in [1, 2)
    let shift = 8 - k; // Q30 * 2^k -> Q22
    let v = if shift > 0 {
        (p + (1 << (shift - 1))) >> shift
    } else {
        p << -shift
    };
    v.min(i32::MAX as i64) as i32
}

/// `1/sqrt(x)` in Q22 of a Q22 argument, saturated; 0 for `x <= 0`. With `x = v 2^-22` and
/// `v = m 2^sh` (`m` in Q30 in [1, 4), `sh` even), `1/sqrt(x) = (1/sqrt(m)) 2^(-4 - sh/2)`:
/// a quadratic start and two Newton steps `y (3 - m y^2)/2` in Q30, no division.
fn rsqrt_bits(x: i32) -> i32 {
    if x <= 0 {
        return 0;
    }
    let v = x as u32;
    let top = 31 - v.leading_zeros() as i32; // 0..=30
    let mut sh = top - 30; // in [-30, 0]
    if sh & 1 != 0 {
        sh -= 1; // even, rounding down
    }
    let m = i64::from(v << -sh); // Q30 in [1, 4)
    let c = if m < 2 << 30 {
        &RSQRT_LO_Q30
    } else {
        &RSQRT_HI_Q30
    };
    // m reaches 4 (2^32 in Q30): its products take the 64-bit multiply.
    let mut y = c[0] + mul_q30_i64(c[1] + mul_q30_i64(c[2], m), m);
    for _ in 0..2 {
        let my2 = mul_q30_i64(m, mul_q30(y, y));
        y = mul_q30_i64(y, (3 << 30) - my2) >> 1;
    }
    let s = 12 + sh / 2; // in [-3, 12]
    let r = if s > 0 {
        (y + (1 << (s - 1))) >> s
    } else {
        y << -s
    };
    r.min(i32::MAX as i64) as i32
}

/// `ln x` in Q22 of a Q22 argument; `i32::MIN` (-512) for `x <= 0`.
fn ln_bits(x: i32) -> i32 {
    if x <= 0 {
        return i32::MIN;
    }
    let v = x as u32;
    let top = 31 - v.leading_zeros(); // position of the leading one, 0..=30
    let mut m = v << (30 - top); // Q30 in [1, 2)
    let mut e = top as i64 - FRAC as i64;
    if m > SQRT2_Q30 {
        m >>= 1;
        e += 1;
    }
    let t = i64::from(m) - (1 << 30);
    let l = mul_q30(t, horner_q30(&LN1P_Q30, t));
    q30_to_q22(e * LN2_Q30 + l)
}

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
    #[inline]
    fn sqrt(self) -> Self {
        if self.0 > I10F22::ZERO {
            Fixed22(self.0.sqrt())
        } else {
            Self::ZERO
        }
    }
    #[inline]
    fn atan2(self, x: Self) -> Self {
        Fixed22::from_bits(q30_to_q22(atan2_q30(self.to_bits(), x.to_bits())))
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
    #[inline]
    fn sqrt_rsqrt(self) -> (Self, Self) {
        let r = self.rsqrt();
        (self * r, r)
    }
    /// Scales by a power of two (exact shifts, no division): the largest component lands in
    /// [1/2, 1) (in [1, 2) for `m >= 128`), and the scale returned is that power of two.
    #[inline]
    fn rescale3(v: [Self; 3], m: Self) -> ([Self; 3], Self) {
        let bits = m.to_bits();
        if bits <= 0 {
            return (v, Self::ONE);
        }
        let top = 31 - bits.leading_zeros() as i32; // 0..=30
        let k = (21 - top).clamp(-8, 21);
        let scaled = if k >= 0 {
            v.map(|x| Fixed22::from_bits(x.to_bits() << k))
        } else {
            v.map(|x| Fixed22::from_bits(x.to_bits() >> -k))
        };
        (scaled, Fixed22::from_bits(1 << (FRAC as i32 - k)))
    }
    #[inline(always)]
    fn is_nan_like(self) -> bool {
        false
    }
}
