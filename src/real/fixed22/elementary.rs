//! The elementary functions of [`Fixed22`](super::Fixed22) in integer arithmetic: the Q30
//! polynomial helpers and constants, the arc tangent, sine and cosine, exp, the table-seeded
//! square root and reciprocal square root, and ln (the module docs of `fixed22` tabulate their
//! bounds and costs; the products and divisions they use are `kernels.rs`).

use super::kernels::{clz, mul_hi_full, mul_hi_u32, recip_core, wide_mul};
use super::FRAC;

/// `x * y` of two Q30 values with `|x|, |y| < 2` (so each fits an `i32`; a precondition its
/// callers keep: beyond it the factors are truncated to 32 bits, never a panic), rounded down.
#[inline(always)]
pub(super) fn mul_q30(x: i64, y: i64) -> i64 {
    wide_mul(x as i32, y as i32) >> 30
}

/// Horner's rule in Q30 over `c[0] + c[1] z + c[2] z^2 + ...`.
#[inline(always)]
pub(super) fn horner_q30(c: &[i64], z: i64) -> i64 {
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
pub(super) fn q30_to_q22(x: i64) -> i32 {
    let r = (x + (1 << 7)) >> 8;
    r.clamp(i32::MIN as i64, i32::MAX as i64) as i32
}

// Minimax coefficients, Q30 (fitted by Lawson's iteration on 4000 Chebyshev nodes).
/// `sin r = r P(r^2)`, `|r| <= pi/4`: max error 1.2e-9.
pub(super) const SIN_Q30: [i64; 4] = [1073741809, -178956649, 8945971, -208973];
/// `cos r = P(r^2)`, `|r| <= pi/4`: max error 4.7e-11.
pub(super) const COS_Q30: [i64; 5] = [1073741824, -536870908, 44739189, -1491064, 26178];
/// `e^r = P(r)`, `r` in [0, ln 2): max error 2.6e-9.
pub(super) const EXP_Q30: [i64; 7] = [
    1073741827, 1073741427, 536879948, 178879952, 45050186, 8310826, 2119227,
];
/// `ln(1 + t) = t P(t)`, `t` in [1/sqrt(2) - 1, sqrt(2) - 1]: max error 4.6e-9.
pub(super) const LN1P_Q30: [i64; 9] = [
    1073741696, -536870620, 357931939, -268470760, 214091674, -177520736, 161787055, -156520659,
    93339587,
];

pub(super) const PI_Q30: i64 = 3_373_259_426; // pi 2^30
pub(super) const FRAC_PI_2_Q30: i64 = 1_686_629_713; // pi/2 2^30
pub(super) const FRAC_PI_2_Q38: i64 = 431_777_206_567; // pi/2 2^38
pub(super) const FRAC_2_PI_Q32: i64 = 2_734_261_102; // 2/pi 2^32
pub(super) const LN2_Q30: i64 = 744_261_118; // ln 2 2^30
pub(super) const LN2_Q38: i64 = 190_530_846_202; // ln 2 2^38
pub(super) const INV_LN2_Q32: i64 = 6_196_328_019; // 1/ln 2 2^32
pub(super) const SQRT2_Q30: u32 = 1_518_500_250; // sqrt 2 2^30

/// Cubic pieces of `atan` on the 32 intervals `[k/32, (k + 1)/32]` of `[0, 1]`: `[a0 2^30,
/// a1 2^30, a2 2^30, a3 2^16]` of `a0 + a1 u + a2 u^2 + a3 u^3`, `u` the offset from the
/// interval's midpoint `(2k + 1)/64` (Chebyshev interpolation: 2.6e-9 at worst). 512 bytes.
pub(super) const ATAN_TABLE: [[i32; 4]; 32] = [
    [16775851, 1073479742, -16764937, -21810],
    [50294832, 1071387699, -50099040, -21556],
    [83716035, 1067227980, -82851518, -21054],
    [116975535, 1061048614, -114653277, -20321],
    [150011260, 1052919920, -145162159, -19375],
    [182763662, 1042932537, -174071714, -18242],
    [215176307, 1031194961, -201118176, -16953],
    [247196398, 1017830712, -226085382, -15540],
    [278775190, 1002975259, -248807540, -14035],
    [309868319, 986772832, -269169887, -12472],
    [340436021, 969373267, -287107420, -10882],
    [370443265, 950928976, -302601959, -9295],
    [399859786, 931592144, -315677891, -7737],
    [428660036, 911512231, -326396964, -6230],
    [456823068, 890833809, -334852494, -4792],
    [484332354, 869694782, -341163325, -3439],
    [511175550, 848224979, -345467847, -2181],
    [537344230, 826545107, -347918305, -1026],
    [562833590, 804766059, -348675576, 23],
    [587642129, 782988520, -347904546, 964],
    [611771333, 761302841, -345770139, 1799],
    [635225351, 739789153, -342434029, 2530],
    [658010681, 718517647, -338052022, 3162],
    [680135862, 697549011, -332772056, 3700],
    [701611191, 676934972, -326732771, 4151],
    [722448447, 656718906, -320062572, 4522],
    [742660642, 636936497, -312879112, 4821],
    [762261796, 617616418, -305289126, 5053],
    [781266719, 598781009, -297388539, 5226],
    [799690833, 580446946, -289262793, 5347],
    [817549999, 562625881, -280987329, 5422],
    [834860371, 545325048, -272628182, 5457],
];

/// `atan t` in Q30 for `t` in Q31 in `[0, 2^31]` (`[0, 1]`): the piece of [`ATAN_TABLE`] of
/// `t`'s 32nd by Horner's rule, each product only as wide as its term needs (`|u| <= 1/64`):
/// `a2 + a3 u` from one 16 x 16-bit product, `a1 + u (..)` from two (to 2^-24), `a0 + u (..)`
/// from four (to 2^-30). 3.4e-9 at worst (measured on 10^6 `t` against f64), in about 40
/// Cortex-M0 instructions.
#[inline(always)]
fn atan_unit_q30(t: u32) -> i32 {
    let k = (t >> 26).min(31); // t = 2^31 (t = 1) is the last interval's end
    let [a0, a1, a2, a3] = match ATAN_TABLE.get(k as usize) {
        Some(&e) => e,
        None => ATAN_TABLE[31],
    };
    // |u| <= 2^25 (1/64 in Q31): t - (2k + 1) 2^25, in wrapping u32 (t may be 2^31).
    let u = t.wrapping_sub((2 * k + 1) << 25) as i32;
    // a3 u: |a3| < 2^15 (Q16) times |u >> 10| <= 2^15 (Q21): Q37 >> 7 = Q30.
    let p = a2 + ((a3 * (u >> 10)) >> 7);
    // p u: p in Q19 (|p| < 2^18) times u in Q24 (|u| <= 2^18) split into its high bits
    // (<= 2^10) and low 8 bits: each product below 2^28; Q43 >> 13 = Q30.
    let (p19, u24) = (p >> 11, u >> 7);
    let p = a1 + ((p19 * (u24 >> 8) + ((p19 * (u24 & 0xFF)) >> 8)) >> 5);
    // p u / 2^31 exactly rounded down: 0 < p <= 2^30 (p >> 16 <= 2^14), |u >> 16| <= 2^9.
    let (ph, pl) = (p >> 16, p & 0xFFFF);
    let (uh, ul) = (u >> 16, u & 0xFFFF);
    let mid = ph * ul + pl * uh + ((pl as u32 * ul as u32) >> 16) as i32;
    a0 + 2 * ph * uh + (mid >> 15)
}

/// `atan2(y, x)` in Q22, rounded (from Q30). Octant reduction to `t = num/den` in [0, 1], the
/// ratio from [`recip_core`] (`den` normalized by [`clz`]; within 3 2^-31 of `num/den`, in
/// Q31), then `atan t` from a cubic piece per 32nd of [0, 1] ([`atan_unit_q30`], 3.4e-9). The
/// octants in wrapping `u32` Q30 (pi 2^30 < 2^32; `atan t` may be a unit or two below 0 at
/// `t = 0`, which the rounding's `+ 2^7` absorbs); the sign last, so `atan2(-y, x)` is exactly
/// `-atan2(y, x)`.
pub(super) fn atan2_bits(y: i32, x: i32) -> i32 {
    let (ax, ay) = (x.unsigned_abs(), y.unsigned_abs());
    let swap = ay > ax;
    let (num, den) = if swap { (ax, ay) } else { (ay, ax) }; // num <= den <= 2^31
    if den == 0 {
        return 0;
    }
    let s = clz(den);
    // num << s <= den << s < 2^32, and y <= 2^63 / (den << s): t <= 2^31.
    let t = mul_hi_full(num << s, recip_core(den << s));
    let mut a = atan_unit_q30(t) as u32;
    if swap {
        a = (FRAC_PI_2_Q30 as u32).wrapping_sub(a);
    }
    if x < 0 {
        a = (PI_Q30 as u32).wrapping_sub(a);
    }
    let r = (a.wrapping_add(1 << 7) >> 8) as i32; // <= pi 2^22
    if y < 0 {
        -r
    } else {
        r
    }
}

/// `(sin x, cos x)` in Q30 of a Q22 argument.
pub(super) fn sin_cos_q30(x: i32) -> (i64, i64) {
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
pub(super) fn exp_bits(x: i32) -> i32 {
    // e^x < 2^9 needs x < 9 ln 2 = 6.2383246 (Q22: 26165429.93).
    if x > 26_165_429 {
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

/// Quadratic starts for `1/sqrt(m)` on the 24 intervals `[1 + i/8, 1 + (i + 1)/8)` of
/// `[1, 4)`: `(c0 2^30, c1 2^19, c2 2^19)` of `c0 + c1 t + c2 t^2`, `t` in [0, 1) across the
/// interval (Chebyshev interpolation; relative error 2^-15.8 as evaluated). 192 bytes.
pub(super) const RSQRT_SEED: [(u32, i16, u16); 24] = [
    (1073724323, -32613, 2645),
    (1012321715, -27357, 2002),
    (960375622, -23374, 1559),
    (915684119, -20271, 1241),
    (876702073, -17797, 1008),
    (842308993, -15789, 831),
    (811669889, -14131, 695),
    (784148074, -12744, 588),
    (759248454, -11571, 503),
    (736579457, -10566, 434),
    (715826767, -9699, 378),
    (696734772, -8945, 331),
    (679093179, -8283, 292),
    (662727185, -7699, 260),
    (647490122, -7180, 232),
    (633257899, -6718, 208),
    (619924716, -6303, 187),
    (607399740, -5928, 169),
    (595604486, -5590, 154),
    (584470742, -5282, 140),
    (573938903, -5002, 128),
    (563956619, -4746, 118),
    (554477702, -4511, 108),
    (545461221, -4294, 100),
];

/// [`RSQRT_SEED`] indexed by `m >> 27` itself (8 to 31 for `m` in `[2^30, 2^32)`; below 8,
/// for a caller's wrong exponent, its first entry, as before): no subtraction and no bounds
/// test (`m >> 27` of a `u32` is below 32), 3 Cortex-M0 instructions fewer in every square
/// root and normalization, for 64 bytes.
static RSQRT_SEED_BY_TOP: [(u32, i16, u16); 32] = {
    let mut t = [RSQRT_SEED[0]; 32];
    let mut i = 0;
    while i < RSQRT_SEED.len() {
        t[i + 8] = RSQRT_SEED[i];
        i += 1;
    }
    t
};

/// The quadratic start of [`rsqrt_core_at`] for `m` in `[2^30, 2^32)`: `2^30 / sqrt(m /
/// 2^30)` (in `(2^29, 2^30)`) to a relative 2^-15.8 ([`RSQRT_SEED`]), below `2^30`. Also the
/// whole reciprocal square root of the 16-bit normalization (`normalize::unit_q15`), whose
/// precision it matches.
#[inline(always)]
pub(super) fn rsqrt_seed(m: u32) -> u32 {
    // m in [2^30, 2^32): the index is in [8, 32) (a `u32` shifted right by 27: below 32, so
    // no bounds test is compiled; the first entry below 8, for a caller's wrong exponent).
    let (c0, c1, c2) = RSQRT_SEED_BY_TOP[(m >> 27) as usize];
    let t = ((m >> 11) & 0xFFFF) as i32;
    // |c1| < 2^15, t < 2^16: every product fits an i32.
    let inner = i32::from(c1) + ((i32::from(c2) * t) >> 16);
    (c0 as i32 + ((inner * t) >> 5)).min((1 << 30) - 1) as u32
}

/// The shared core of `sqrt`, `rsqrt` and `sqrt_rsqrt`: for `v > 0`, `(m, j, y)` with
/// `v = (m / 2^30) 4^j`, `m` in `[2^30, 2^32)` and `y = 2^32 / sqrt(m / 2^30)` to a relative
/// 2^-29.5 (`y < 2^32`). A quadratic start from [`RSQRT_SEED`] (2^-15.8) and one Newton step
/// `y (1 + (1 - m y^2)/2)`, all in `u32` with 16 x 16-bit products (no 64-bit multiply): the
/// step's correction `1 - m y^2` is below 2^-14, so its product with `y` takes two of them.
#[inline(always)]
pub(super) fn rsqrt_core(v: u32) -> (u32, u32, u32) {
    rsqrt_core_at(v, (31 - clz(v)) & !1)
}

/// [`rsqrt_core`] with `j2`, the position of `v`'s leading one rounded down to even, given:
/// for the normalizations, whose sums of squares lie in `[2^20, 2^26)` and take it from two
/// comparisons instead of the leading-zero count ([`even_top_of_square_sum`]).
#[inline(always)]
pub(super) fn rsqrt_core_at(v: u32, j2: u32) -> (u32, u32, u32) {
    let m = v << (30 - j2);
    // The start in Q32. Then `m >= 2^31` has a zero low bit (`m = v << (30 - j2)` and `v <
    // 2^31`): `m/2` is exact, Q29.
    let y = rsqrt_seed(m) << 2;
    let (mh, yh) = (m >> 1, y >> 1); // both < 2^31
    let s = mul_hi_u32(mh, yh); // m y, Q28, < 2^29
    let e = mul_hi_u32(s << 2, yh); // m y^2, Q29 (s << 2 < 2^31)
    let c = (1u32 << 29).wrapping_sub(e) as i32; // (1 - m y^2), Q29, |c| < 2^15
    let (yh, yl) = ((y >> 16) as i32, (y & 0xFFFF) as i32);
    let delta = (yh * c + ((yl * c) >> 16)) >> 14; // y (1 - m y^2) / 2, Q32
    let y = if delta >= 0 {
        y.saturating_add(delta as u32)
    } else {
        y - delta.unsigned_abs()
    };
    (m, j2 / 2, y)
}

/// [`rsqrt_core_at`] for the normalizations, whose sums of squares `v` lie in `[2^20, 2^26)`
/// (`normalize::unit_scale`) and whose results are `Fixed22` values below 4 (at most 24
/// significant bits): the same `(m, j)`, and `y` to a relative `2^-28` (measured over every
/// such `v` by `fixed22::tests`: `2^-28.45`) instead of `2^-29.5`, for about 30 Cortex-M0
/// instructions fewer. The start rounded to 16 bits, `Y` in `[2^15, 2^16)` (Q16),
/// so that the Newton step's `m Y^2` is two products by a 16-bit factor, each of two 32-bit
/// `MULS` (the general core's two exact high words take eight):
///
/// 1. `t = floor(m Y / 2^16)`: `m Y 2^-46 = sqrt(m / 2^30)` up to the start's error, so `t`
///    is in `[2^30, 2^31]` (halves of `m` times `Y`, each below `2^32`);
/// 2. `q = floor(t Y / 2^15)`, `m Y^2` in Q31, near `2^31` (`t`'s halves times `Y`: `t / 2^16
///    Y` is about `2^30`);
/// 3. `c = 2^31 - q` (wrapping): `1 - m Y^2` in Q31, `|c| < 2^17.1` (the start's `2^-15.8`
///    and the rounding's `2^-16`);
/// 4. `y = Y 2^16 + Y (c / 8) / 2^13`, saturated: `Y (1 + (1 - m Y^2)/2)` in Q32 (`Y (c / 8)`
///    below `2^30.1`).
///
/// Error: the step's own `1.5 e0^2` (`e0 <= 2^-14.9`: `2^-29.2`) and the floors of `t`, `q`
/// and `c / 8` (at most `2^-28` in `1 - m Y^2`, half of it in `y`). The normalizations round
/// their results to `Fixed22`'s `2^-22`, so `y`'s error shows only where a result lies
/// within about `2^-5` of a rounding step of the exact core's.
#[inline(always)]
pub(super) fn rsqrt_core_unit(v: u32, j2: u32) -> (u32, u32, u32) {
    let m = v << (30 - j2);
    // The start in Q30, below 2^30, rounded to Q16: at most 2^16 - 1 after the clamp.
    let yy = ((rsqrt_seed(m) + (1 << 13)) >> 14).min(0xFFFF);
    let t = (m >> 16) * yy + (((m & 0xFFFF) * yy) >> 16);
    let q = (((t >> 16) * yy) << 1).wrapping_add(((t & 0xFFFF) * yy) >> 15);
    let c = (1u32 << 31).wrapping_sub(q) as i32;
    let delta = (yy as i32 * (c >> 3)) >> 13;
    let y = (yy << 16).saturating_add_signed(delta);
    (m, j2 / 2, y)
}

/// `(31 - clz(v)) & !1` for `v > 0`, from comparisons where `v` lies in `[2^20, 2^26)` (the
/// normalizations' sums of squares: see `unit_scale`), from [`clz`] elsewhere (total; never
/// taken there). About 6 instead of 20 Cortex-M0 instructions.
#[inline(always)]
pub(super) fn even_top_of_square_sum(v: u32) -> u32 {
    if !((1 << 20)..(1 << 26)).contains(&v) {
        (31 - clz(v)) & !1
    } else if v >= 1 << 24 {
        24
    } else if v >= 1 << 22 {
        22
    } else {
        20
    }
}

/// `1/sqrt(x)` in Q22 of a Q22 argument, rounded, saturated (MAX below `2^-18`); 0 for
/// `x <= 0`. With `x = v 2^-22` and `v = m 4^j`: `1/sqrt(x) = (y / 2^32) 2^(11 - j)`, so the
/// bits are `y` shifted right by `j - 1`.
#[inline]
pub(super) fn rsqrt_bits(x: i32) -> i32 {
    if x <= 0 {
        return 0;
    }
    let (_, j, y) = rsqrt_core(x as u32);
    rsqrt_out(j, y)
}

/// The Q22 bits of `1/sqrt(x)` from `rsqrt_core`'s `(j, y)`: `y / 2^(j - 1)` rounded, MAX for
/// `j <= 1` (`x < 2^-18`, where the result exceeds 512).
#[inline(always)]
pub(super) fn rsqrt_out(j: u32, y: u32) -> i32 {
    if j <= 1 {
        return i32::MAX;
    }
    let t = y >> (j - 2);
    ((t >> 1) + (t & 1)).min(i32::MAX as u32) as i32
}

/// The Q22 bits of `sqrt(x)` from `rsqrt_core`'s `(m, j, y)`: `m y / 2^(19 - j)` rounded.
#[inline(always)]
pub(super) fn sqrt_out(m: u32, j: u32, y: u32) -> i32 {
    let s = mul_hi_u32(m >> 1, y >> 1) << 2; // m y, Q30, < 2^31 (m >> 1 exact, see rsqrt_core)
    let sh = 19 - j; // >= 4
    ((s + (1 << (sh - 1))) >> sh) as i32
}

/// `sqrt(x)` in Q22 of a Q22 argument, rounded; 0 for `x <= 0`. `sqrt(x) = m y 2^(j - 11)`
/// with `m y` in Q30: the bits are `m y` shifted right by `19 - j` (>= 4).
#[inline]
pub(super) fn sqrt_bits(x: i32) -> i32 {
    if x <= 0 {
        return 0;
    }
    let (m, j, y) = rsqrt_core(x as u32);
    sqrt_out(m, j, y)
}

/// `ln x` in Q22 of a Q22 argument; `i32::MIN` (-512) for `x <= 0`.
pub(super) fn ln_bits(x: i32) -> i32 {
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

/// The arc ratio `R(1 - x)` (`R(c) = acos(c)/sqrt(1 - c^2)`) on `x` in [0, 1] as 16 cubic
/// pieces, one per `[i/16, (i + 1)/16]`: `[a0, a1, a2, a3]` in Q22 of `a0 + a1 u + a2 u^2 +
/// a3 u^3`, `u = x - i/16` (Chebyshev interpolation of each piece on 64 nodes). 256 bytes;
/// evaluated in Q22 ([`arc_ratio_bits`]) within 3.9e-7 (1.62 LSB) of `R`, measured on every
/// input by `tests/fixed_exhaustive.rs`. (One degree-8 polynomial in Q25 was within 5.4e-7
/// for 8 products where these take 3.)
const ARC_RATIO_CUBICS: [[i32; 4]; 16] = [
    [4194304, 1398108, 558692, 253541],
    [4283930, 1470931, 606164, 284352],
    [4378300, 1550051, 659401, 320116],
    [4477833, 1636248, 719327, 361840],
    [4582996, 1730428, 787056, 410779],
    [4694323, 1833652, 863934, 468514],
    [4812415, 1947168, 951605, 537048],
    [4937961, 2072452, 1052084, 618950],
    [5071751, 2211264, 1167864, 717538],
    [5214692, 2365715, 1302057, 837147],
    [5367839, 2538354, 1458580, 983510],
    [5532424, 2732290, 1642417, 1164292],
    [5709892, 2951347, 1859973, 1389897],
    [5901956, 3200271, 2119584, 1674647],
    [6110662, 3485022, 2432238, 2038594],
    [6338474, 3813173, 2812634, 2510327],
];

/// `acos(c)/sqrt(1 - c^2)` (`theta/sin(theta)` with `c = cos(theta)`) in Q22 of a Q22 `c` in
/// [0, 1]: the piece of [`ARC_RATIO_CUBICS`] that `x = 1 - c` falls in, by Horner's rule in
/// Q22 (`mul_bits_le2`, exact floors: the factors stay below 2 and `2^-4`, inside its
/// range). `c` is clamped to [0, 1] first: `c > 1` (a cosine's rounding) answers exactly 1,
/// `c < 0` answers `R(0)`, about `pi/2`, which the caller (the polygon edge terms, only for
/// `c` above 0) never asks. Within 3.9e-7 of `R` on [0, 1]. About 40 Cortex-M0 instructions.
#[inline(always)]
pub(super) fn arc_ratio_bits(c: i32) -> i32 {
    // `x` in [0, 2^22], its piece (x = 1 belongs to the last one) and the offset in it, below
    // 2^18 + 1.
    let x = (1 << FRAC) - c.clamp(0, 1 << FRAC);
    let i = ((x >> 18) as usize).min(15);
    let u = x - ((i as i32) << 18);
    let [a0, a1, a2, a3] = match ARC_RATIO_CUBICS.get(i) {
        Some(&piece) => piece,
        None => ARC_RATIO_CUBICS[0],
    };
    let m = super::kernels::mul_bits_le2;
    m(m(m(a3, u) + a2, u) + a1, u) + a0
}

/// The arc ratio `R(c)` in Q15 (rounded) of a cosine `c` in Q30, for the 16-bit polygon edge
/// terms (`polygon::edge::unit_ratio_term`): the same pieces as [`arc_ratio_bits`], by
/// Horner's rule in 32-bit products (one `MULS` each on the Cortex-M0, where `arc_ratio_bits`'
/// Q22 products take four): `x = 1 - c` in Q30 (`c` clamped to `[0, 1]`), the offset `u` in
/// its piece in Q19 (at most `2^15`), the coefficients but `a0` truncated to Q16. Bounds
/// (nothing wraps; the largest at `x = 1`, the last piece): the inner sums stay below
/// `46 400` and `62 480`, so each product stays below `2^31`. Error before the final rounding:
/// the pieces' 3.9e-7, the offset's truncation to Q19 (`2^-19` times a slope below 0.9), the
/// truncated coefficients and products (each at most `2^-16` in a sum multiplied by `u <=
/// 1/16`, and `2^-22`): within 4.2e-6 (3.9e-6 measured on every 61st `c` by this module's
/// tests); then the rounding to Q15 (`2^-16`). About 20 Cortex-M0 instructions where
/// `arc_ratio_bits` takes about 60.
#[cfg(feature = "polygon")]
#[inline(always)]
pub(super) fn arc_ratio_q30_to_q15(c: i32) -> i32 {
    (arc_ratio_q30_to_q22(c) + (1 << 6)) >> 7
}

/// [`arc_ratio_q30_to_q15`] before its rounding, in Q22.
#[cfg(feature = "polygon")]
#[inline(always)]
pub(super) fn arc_ratio_q30_to_q22(c: i32) -> i32 {
    // `x` in [0, 2^30], its piece (x = 1 belongs to the last one) and the offset in it, in
    // Q19: [0, 2^15].
    let x = (1 << 30) - c.clamp(0, 1 << 30);
    let i = ((x >> 26) as usize).min(15);
    let u = (x - ((i as i32) << 26)) >> 11;
    let [a0, a1, a2, a3] = match ARC_RATIO_CUBICS.get(i) {
        Some(&piece) => piece,
        None => ARC_RATIO_CUBICS[0],
    };
    let t = (a2 >> 6) + (((a3 >> 6) * u) >> 19); // Q16
    let t = (a1 >> 6) + ((t * u) >> 19); // Q16
    a0 + ((t * u) >> 13) // Q22 (Q16 x Q19 = Q35)
}
