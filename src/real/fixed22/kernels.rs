//! The elementary kernels of [`Fixed22`](super::Fixed22) in `i32`/`u32` integer arithmetic:
//! the product, divisions, square roots, arc tangent, sine/cosine, exp and ln (the module docs
//! of `fixed22` tabulate their bounds and costs).

use super::FRAC;

/// `a * b` in Q22, rounded down (exactly `floor(a b / 2^22)`), saturated.
///
/// ARMv6-M (Cortex-M0) has only a 32 x 32 -> 32-bit `MULS`, and the compiler's `i64` product is a
/// call to the 64 x 64-bit `__aeabi_lmul`. Here: four 16 x 16-bit partial products, combined in
/// 32-bit integers only (no 64-bit adds or shifts), and one range test of the high part instead
/// of a 64-bit clamp; the 64-bit arithmetic is left to the (cold) saturating case. With
/// `a = ah 2^16 + al`, `b = bh 2^16 + bl` (`al`, `bl` in [0, 2^16)):
/// `a b = H 2^32 + w 2^16 + (al bl mod 2^16)` with `H = ah bh + (ah bl >> 16) + (al bh >> 16)`
/// and `w = (ah bl mod 2^16) + (al bh mod 2^16) + (al bl >> 16) < 3 2^16`, so
/// `floor(a b / 2^22) = H 2^10 + floor(w / 2^6)`. Measured on the M0: 40 -> 27 instructions
/// per product (in the QEMU harness).
#[inline(always)]
pub(super) fn mul_bits(a: i32, b: i32) -> i32 {
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    // |ah|, |bh| <= 2^15 and al, bl < 2^16: every partial product fits its type.
    let hh = ah * bh;
    let m1 = ah * bl;
    let m2 = al * bh;
    let ll = (al as u32) * (bl as u32);
    let h = hh + (m1 >> 16) + (m2 >> 16);
    let w = ((m1 & 0xFFFF) + (m2 & 0xFFFF)) as u32 + (ll >> 16);
    // H in [-2^21, 2^21 - 3]: H 2^10 + w/2^6 (< 3 2^10) fits an i32.
    if (h.wrapping_add(1 << 21) as u32) <= (1 << 22) - 3 {
        (h << 10) + (w >> 6) as i32
    } else {
        mul_saturated(h, w)
    }
}

/// [`mul_bits`] for factors below 16 in magnitude (`|a|, |b| < 2^26` raw): the same exact
/// `floor(a b / 2^22)`, without the saturation test (the product is below 256) and with the
/// high halves small (`|ah|, |bh| <= 2^10`): `a b = ah bh 2^32 + (ah bl + al bh) 2^16 + al
/// bl`, so `floor(a b / 2^22) = ah bh 2^10 + floor((ah bl + al bh + floor(al bl / 2^16)) /
/// 2^6)`, every term within an `i32` (`|ah bl|, |al bh| < 2^26`, `|ah bh 2^10| <= 2^30`). The
/// normalizations' squares and scalings (their components rescaled to at most 2, the
/// reciprocal length at most 2), and the polygon edge terms' products of offsets (at most 8
/// and 16): about 12 instead of 27 instructions on the M0. Outside that range it wraps;
/// callers keep to it.
#[inline(always)]
pub(super) fn mul_bits_small(a: i32, b: i32) -> i32 {
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    let mid = (ah.wrapping_mul(bl))
        .wrapping_add(al.wrapping_mul(bh))
        .wrapping_add(((al as u32).wrapping_mul(bl as u32) >> 16) as i32);
    (ah.wrapping_mul(bh) << 10).wrapping_add(mid >> 6)
}

/// [`mul_bits`] by a factor `c` of at most 1 in magnitude (`|c| <= 2^22` raw; any `a` but
/// `i32::MIN` when `c = -2^22`, whose product `+512` is out of range): the same exact
/// `floor(a c / 2^22)`, which cannot saturate (`|a c| <= |a|`), so without the range test,
/// and with the middle product `al ch` (at most `2^16 2^6`) added whole to the low word:
/// `a c = (ah ch + (ah cl >> 16)) 2^32 + ((ah cl mod 2^16) + al ch) 2^16 + al cl`. The
/// factor's split (`ch`, `cl`) is shared by the callers' three channels.
#[inline(always)]
pub(super) fn mul_bits_unit(a: i32, c: i32) -> i32 {
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (ch, cl) = (c >> 16, c & 0xFFFF);
    // |ah| <= 2^15, cl < 2^16: m1 in (-2^31, 2^31); |al ch| <= 2^22.
    let m1 = ah.wrapping_mul(cl);
    let w = (m1 & 0xFFFF)
        .wrapping_add(al.wrapping_mul(ch))
        .wrapping_add(((al as u32).wrapping_mul(cl as u32) >> 16) as i32);
    let h = ah.wrapping_mul(ch).wrapping_add(m1 >> 16);
    // H 2^10 may wrap where the sum does not (the result fits): wrapping arithmetic is exact.
    (h << 10).wrapping_add(w >> 6)
}

/// `k0 + sum k[i] m[i]` over `i` in `0..8` in Q22, rounded down once (exactly
/// `floor((k0 2^22 + sum k[i] m[i]) / 2^22)` of the raw bits), saturated: a fused dot product
/// for factors `m` of at most 1.5 in magnitude (`|m| <= 3 2^21` raw: the monomials of a unit
/// vector) and any `k`.
///
/// Each `m` is split at bit 11 (`m = mh 2^11 + ml`, `mh` in `[-3 2^10, 3 2^10]`, `ml` in
/// `[0, 2^11)`: [`split_11`], once per factor when several dot products share it) and each
/// `k` at bit 16 (`k = kh 2^16 + kl`); the four partial products of every term are summed
/// exactly in four `i32`s (`sum kh mh` at most `8 2^15 3 2^10 = 3 2^28`, `sum kh ml` below
/// `2^29`, `sum kl mh` below `3 2^29`, `sum kl ml` below `2^30`: no overflow), and
/// `sum k m = A 2^27 + B 2^16 + C 2^11 + D` is floored by 2^22 in three exact steps
/// (`floor(floor(x / a) / b) = floor(x / (a b))`). 4 `MULS` a term and no saturation test
/// per term; the 64-bit combination only when `|A| >= 2^25` (a sum beyond about 256, cold).
#[cfg(feature = "sh9")]
#[inline(always)]
pub(super) fn dot8_split_bits(k0: i32, k: [i32; 8], mh: &[i32; 8], ml: &[i32; 8]) -> i32 {
    let (mut a, mut b, mut c, mut d) = (0i32, 0i32, 0i32, 0i32);
    // Written out (the M0 build at opt-level "s" keeps a loop, through the stack).
    macro_rules! term {
        ($($i:literal)*) => {$(
            let (kh, kl) = (k[$i] >> 16, k[$i] & 0xFFFF);
            a = a.wrapping_add(kh.wrapping_mul(mh[$i]));
            b = b.wrapping_add(kh.wrapping_mul(ml[$i]));
            c = c.wrapping_add(kl.wrapping_mul(mh[$i]));
            d = d.wrapping_add(kl.wrapping_mul(ml[$i]));
        )*};
    }
    term!(0 1 2 3 4 5 6 7);
    // floor((C 2^11 + D) / 2^11), then floor((B 2^16 + C 2^11 + D) / 2^16).
    let t = c.wrapping_add(d >> 11);
    let t = b.wrapping_add(t >> 5);
    if (a.wrapping_add(1 << 25) as u32) < 1 << 26 {
        // |A 2^5| < 2^30 and |t / 2^6| < 2^24: the sum fits before the saturating add of k0.
        ((a << 5) + (t >> 6)).saturating_add(k0)
    } else {
        dot8_saturated(k0, a, t)
    }
}

/// The large end of [`dot8_split_bits`]: `k0 + A 2^5 + floor(t / 2^6)` clamped to `i32`.
#[cfg(feature = "sh9")]
#[cold]
#[inline(never)]
fn dot8_saturated(k0: i32, a: i32, t: i32) -> i32 {
    let p = i64::from(k0) + (i64::from(a) << 5) + i64::from(t >> 6);
    p.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
}

/// `(m >> 11, m & 0x7FF)`: the split of a factor of [`dot8_split_bits`].
#[cfg(feature = "sh9")]
#[inline(always)]
pub(super) fn split_11(m: i32) -> (i32, i32) {
    (m >> 11, m & 0x7FF)
}

/// The saturating end of [`mul_bits`]: `H 2^10 + w/2^6` clamped to the `i32` range.
#[cold]
#[inline(never)]
pub(super) fn mul_saturated(h: i32, w: u32) -> i32 {
    let p = (i64::from(h) << 10) + i64::from(w >> 6);
    p.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
}

/// The leading zeros of each byte value (`CLZ8[0] = 8`): the last step of [`clz`]. 256 bytes.
const CLZ8: [u8; 256] = {
    let mut t = [0u8; 256];
    let mut i = 0;
    while i < 256 {
        let mut n = 8;
        let mut v = i;
        while v > 0 {
            n -= 1;
            v >>= 1;
        }
        t[i] = n;
        i += 1;
    }
    t
};

/// The leading zeros of `x` (32 for `x = 0`; ARMv6-M has no `CLZ`; `u32::leading_zeros` is a
/// call to `__clzsi2`): two steps of a binary search (16, 8) and a byte table ([`CLZ8`]),
/// about 12 instructions (a five-step search took about 35 on the M0 as compiled).
#[inline(always)]
pub(super) fn clz(mut x: u32) -> u32 {
    let mut n = 0;
    if x < 1 << 16 {
        n = 16;
        x <<= 16;
    }
    if x < 1 << 24 {
        n += 8;
        x <<= 8;
    }
    n + CLZ8.get((x >> 24) as usize).map_or(0, |&c| u32::from(c))
}

/// `floor(a b / 2^32)` for `a, b <= 2^31`: the high word of the product, exact, from four
/// 16 x 16-bit products in `i32` arithmetic (every partial product and sum fits an `i32` for
/// these operands). Written on signed halves on purpose: LLVM recognizes the textbook
/// unsigned form as a 64-bit multiply and emits the `__aeabi_lmul` call this avoids.
#[inline(always)]
pub(super) fn mul_hi_u32(a: u32, b: u32) -> u32 {
    debug_assert!(a <= 1 << 31 && b <= 1 << 31);
    let (ah, al) = ((a >> 16) as i32, (a & 0xFFFF) as i32);
    let (bh, bl) = ((b >> 16) as i32, (b & 0xFFFF) as i32);
    // ah, bh <= 2^15 and al, bl < 2^16: ah bl < 2^31; al bl as u32.
    let (m1, m2, ll) = (ah * bl, al * bh, (al as u32) * (bl as u32));
    let mid = (ll >> 16) as i32 + (m1 & 0xFFFF) + (m2 & 0xFFFF); // < 3 2^16
    (ah * bh + (m1 >> 16) + (m2 >> 16) + (mid >> 16)) as u32
}

/// `ceil(2^32 / o)` for the odd `o` in [3, 255] (`RECIP_ODD[(o - 3) / 2]`): the reciprocals of
/// [`div_u32_bits`] (508 bytes).
pub(super) const RECIP_ODD: [u32; 127] = {
    let mut t = [0u32; 127];
    let mut i = 0;
    while i < 127 {
        let o = 2 * i as u64 + 3;
        t[i] = ((1u64 << 32).div_ceil(o)) as u32;
        i += 1;
    }
    t
};

/// [`recip_q32`] of the odd `k = 2 j + 3` while `k < 256` (`None` beyond): the table entry
/// itself, for a loop over odd `k` that counts `j` (no parity or range tests of `k`).
#[cfg(all(feature = "polygon", any(feature = "phong", feature = "moments")))]
#[inline(always)]
pub(crate) fn recip_q32_odd(j: usize) -> Option<u32> {
    RECIP_ODD.get(j).copied()
}

/// `1/k` as a Q32 fraction for an integer `k >= 2`: `ceil(2^32/o) / 2^e` from [`RECIP_ODD`]
/// for `k = o 2^e` up to 256 (above the exact `2^32/k` by less than one unit, never below by a
/// unit), `2^(32 - e)` for a power of two, `floor((2^32 - 1)/k)` by division above 256
/// (`u32::MAX` for `k < 2`). The `1/k` steps of the fixed-point cosine-power recurrence
/// (`polygon::arc`): a table lookup, no division.
#[cfg(all(feature = "polygon", any(feature = "phong", feature = "moments")))]
#[inline(always)]
pub(crate) fn recip_q32(k: u32) -> u32 {
    if k & 1 == 1 && k >= 3 {
        // Odd k (the recurrence's every step for an even Phong exponent): one lookup.
        if let Some(&r) = RECIP_ODD.get((k as usize - 3) / 2) {
            return r;
        }
    }
    if !(2..=256).contains(&k) {
        return if k < 2 { u32::MAX } else { u32::MAX / k };
    }
    let e = k.trailing_zeros();
    let o = k >> e;
    if o == 1 {
        // k = 2^e, 1 <= e <= 8.
        1u32 << (32 - e)
    } else {
        RECIP_ODD.get((o as usize - 3) / 2).map_or(0, |&r| r >> e)
    }
}

/// `a / n` in Q22 for an integer `n` in [1, 256]: bit-identical to `div_bits(a, n 2^22)` (the
/// quotient `a / n` of the raw bits, rounded half away from zero), without its reciprocal
/// core and full product. With `n = o 2^k` (`o` odd), `q = floor(|a| ceil(2^32/o) / 2^(32 + k))` is
/// `floor(|a|/n)` or one more (the reciprocal's excess times `|a| <= 2^31` is below 1/2); the
/// remainder `|a| - q n` (one `MULS`) corrects it and gives the rounding bit. Other `n`: `div_bits`.
#[inline]
pub(super) fn div_u32_bits(a: i32, n: u32) -> i32 {
    if n == 0 || n > 256 {
        let b = if n >= 1 << (31 - FRAC) {
            i32::MAX
        } else {
            (n << FRAC) as i32
        };
        return div_bits(a, b);
    }
    let k = n.trailing_zeros();
    let o = n >> k;
    let x = a.unsigned_abs(); // <= 2^31
    let mut q = if o == 1 {
        x >> k
    } else {
        // o is odd in [3, 255]: the entry exists (`get`, so that no panic path is compiled).
        match RECIP_ODD.get((o as usize).wrapping_sub(3) / 2) {
            Some(&r) => mul_hi_u32(x, r) >> k,
            None => return div_bits(a, (n << FRAC) as i32),
        }
    };
    // q n <= 2^31 + n: the remainder is in [-n, n) as an i32.
    let mut r = x.wrapping_sub(q.wrapping_mul(n)) as i32;
    if r < 0 {
        q -= 1;
        r += n as i32;
    }
    if 2 * r as u32 >= n {
        q += 1;
    }
    if a < 0 {
        // q <= 2^31 (only for n = 1, a = MIN): -q wraps to MIN, as div_bits.
        (q as i32).wrapping_neg()
    } else {
        q as i32
    }
}

/// `a n` in Q22 for an integer `n < 512`, saturated: bit-identical to `mul_bits(a, n 2^22)` (the
/// exact product of the raw bits, clamped), from two 16 x 9-bit products. Other `n`: `mul_bits`
/// with the saturated `from_u32(n)`, as `a * Fixed22::from_u32(n)`.
#[inline(always)]
pub(super) fn mul_u32_bits(a: i32, n: u32) -> i32 {
    if n >= 1 << (31 - FRAC) {
        return mul_bits(a, i32::MAX);
    }
    let n = n as i32;
    let lo = (a & 0xFFFF) * n; // < 2^25
    let hi = (a >> 16) * n + (lo >> 16); // the exact product >> 16
    if (hi.wrapping_add(1 << 15) as u32) < 1 << 16 {
        (hi << 16) | (lo & 0xFFFF)
    } else if hi < 0 {
        i32::MIN
    } else {
        i32::MAX
    }
}

pub(super) use crate::wide::{mul_hi_full, recip_core};

/// `a / b` in Q22, correctly rounded (ties away from zero), saturating; `x / 0` is +-MAX by the
/// sign of `x` (0 for `0 / 0`). No division instruction or call: with `|b| = d 2^-s` (`d` in
/// `[2^31, 2^32)`, `s` from [`clz`]) and [`recip_core`]'s `y <= 2^63/d`, the quotient
/// estimate `q = floor(|a| y / 2^(41 - s))` (one full product) is the exact
/// `Q = floor(|a| 2^22 / |b|)` or up to 4 below it; the remainder `|a| 2^22 - q |b|` (one
/// `MULS`, in wrapping `u32`: it is below `|b| + 2^24 <= 2^32`) corrects it to `Q` and gives
/// the rounding bit. About 150 instead of 300 Cortex-M0 instructions (22 restoring steps and a
/// `u32` division), measured in the QEMU harness.
pub(super) fn div_bits(a: i32, b: i32) -> i32 {
    let negative = (a < 0) != (b < 0);
    let (ua, ub) = (a.unsigned_abs(), b.unsigned_abs());
    let saturated = if negative { i32::MIN } else { i32::MAX };
    if ub == 0 {
        return if ua == 0 { 0 } else { saturated };
    }
    // |a/b| >= 2^9 cannot be represented (2^31 / 2^22): |a| >= |b| 2^9, i.e. |a| >> 9 >= |b|.
    if ua >> (31 - FRAC) >= ub {
        return saturated;
    }
    let s = clz(ub);
    let y = recip_core(ub << s);
    // |a| < |b| 2^9 < 2^(41 - s): |a| << (s - 9) fits for s > 9.
    let mut q = if s <= 9 {
        mul_hi_full(ua, y) >> (9 - s)
    } else {
        mul_hi_full(ua << (s - 9), y)
    };
    // Q - q <= 4 (y's deficit is below 4 units of 2^32 / 2^31 in the quotient's scale), and the
    // remainder is below |b| + 2^24 (the deficit times |b|, with Q |b| <= |a| 2^22 < 2^53).
    let mut r = (ua << FRAC).wrapping_sub(q.wrapping_mul(ub));
    while r >= ub {
        r -= ub;
        q += 1;
    }
    // Round half away from zero: the next quotient bit.
    if r >= ub - r {
        q += 1;
    }
    if negative {
        // q <= 2^31 here, so -q fits (and -2^31 is i32::MIN).
        (q as i32).wrapping_neg()
    } else if q > i32::MAX as u32 {
        i32::MAX
    } else {
        q as i32
    }
}

/// `a * b` exactly: the crate's one 32 x 32 -> 64-bit product (`crate::wide`: four 16 x 16-bit
/// products inline on ARMv6-M, whose `i64` product is the library call `__aeabi_lmul`; the
/// widening multiply elsewhere). Measured in the QEMU harness: see the module docs.
#[inline(always)]
pub(super) fn wide_mul(a: i32, b: i32) -> i64 {
    crate::wide::mul_32(a, b)
}

/// `x * y` of two Q30 values with `|x|, |y| < 2` (so each fits an `i32`), rounded down.
#[inline(always)]
pub(super) fn mul_q30(x: i64, y: i64) -> i64 {
    debug_assert!(x == i64::from(x as i32) && y == i64::from(y as i32));
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
    // m in [2^30, 2^32): the index is in [0, 24) (`get`, so that no panic path is compiled;
    // the first entry for a caller's wrong `j2`).
    let (c0, c1, c2) = match RSQRT_SEED.get(((m >> 27) as usize).wrapping_sub(8)) {
        Some(&e) => e,
        None => RSQRT_SEED[0],
    };
    let t = ((m >> 11) & 0xFFFF) as i32;
    // |c1| < 2^15, t < 2^16: every product fits an i32.
    let inner = i32::from(c1) + ((i32::from(c2) * t) >> 16);
    let y0 = (c0 as i32 + ((inner * t) >> 5)).min((1 << 30) - 1) as u32;
    let y = y0 << 2; // Q32
                     // m >= 2^31 has a zero low bit (m = v << (30 - j2) and v < 2^31): m/2 is exact, Q29.
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
