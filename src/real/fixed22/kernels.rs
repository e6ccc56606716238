//! The arithmetic kernels of [`Fixed22`](super::Fixed22) in `i32`/`u32` integer arithmetic:
//! the products, the divisions and the leading-zero count (the elementary functions, square
//! roots to logarithms, are `elementary.rs`; the module docs of `fixed22` tabulate their
//! bounds and costs).

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
    mul_bits_plus::<0>(a, b)
}

/// [`mul_bits`]' computation with `BIAS` (0 or 32) added to `w` before its shift:
/// `floor(a b / 2^22 + BIAS / 2^6)` exactly (the addition commutes with the floors), so 32
/// rounds to nearest (half up). `w + 32 < 3 2^16` keeps the bound on `H 2^10 + w / 2^6`.
#[inline(always)]
fn mul_bits_plus<const BIAS: u32>(a: i32, b: i32) -> i32 {
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    // |ah|, |bh| <= 2^15 and al, bl < 2^16: every partial product fits its type.
    let hh = ah * bh;
    let m1 = ah * bl;
    let m2 = al * bh;
    let ll = (al as u32) * (bl as u32);
    let h = hh + (m1 >> 16) + (m2 >> 16);
    let w = ((m1 & 0xFFFF) + (m2 & 0xFFFF)) as u32 + (ll >> 16) + BIAS;
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

/// [`mul_bits_small`] for factors of at most about 2 in magnitude (`|a|, |b| <= 2^23 + 2^16`
/// raw, 2 plus `2^-6`: unit vectors' components, their cross products and monomials, cosines
/// and sines and `1 +- c` of them): the same exact `floor(a b / 2^22)` from three 32-bit
/// products instead of four. With `a = ah 2^16 + al` and `b = bh 2^16 + bl`, `a b = (ah b +
/// al bh) 2^16 + al bl`, where `|ah b| <= 129 (2^23 + 2^16) < 2^30 + 2^24` fits an `i32`
/// (beyond `mul_bits_small`'s factors of 16 it would not), so `floor(a b / 2^22) = (ah b +
/// al bh + floor(al bl / 2^16)) >> 6` (the sum below `2^31`). About 4 Cortex-M0 instructions
/// fewer a product: `ah bh` and its shift and addition go.
#[inline(always)]
pub(super) fn mul_bits_le2(a: i32, b: i32) -> i32 {
    mul_bits_le2_plus::<0>(a, b)
}

/// [`mul_bits_le2`] rounded to nearest (half up) instead of down: `floor(a b / 2^22 + 1/2)`,
/// exactly (the sum before the shift is `floor(a b / 2^16)`, and adding 32 there commutes with
/// the floors). The normalizations' three scalings by `1/|v|` (`unit3`, `normalize3`,
/// `sphere_ratios`): half a unit of `2^-22` less bias a component, for one addition.
#[inline(always)]
pub(super) fn mul_bits_le2_round(a: i32, b: i32) -> i32 {
    mul_bits_le2_plus::<32>(a, b)
}

/// [`mul_bits_le2`]'s computation with `BIAS` added before the final shift by 6.
#[inline(always)]
fn mul_bits_le2_plus<const BIAS: i32>(a: i32, b: i32) -> i32 {
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    let mid = ah
        .wrapping_mul(b)
        .wrapping_add(al.wrapping_mul(bh))
        .wrapping_add(((al as u32).wrapping_mul(bl as u32) >> 16) as i32);
    mid.wrapping_add(BIAS) >> 6
}

/// The cosine `a . b` of two unit vectors in raw Q22 bits (every component at most `2^22 +
/// 2^6` in magnitude, which every `UnitVec3` keeps: a few units of `2^-22` past 1 at most),
/// through Q15: each component rounded half up to `q = (x + 2^6) >> 7` (at most `2^15` in
/// magnitude, within `2^-16` of `x 2^-22`), the three products `qa qb` single 32-bit
/// products (one `MULS` each on the Cortex-M0, where an exact Q22 product takes four) summed
/// in Q30, the sum rounded half up to Q22. Bounds: each product at most `2^30`, and the sum
/// and its partial sums at most `|qa| |qb| <= 2^30 (1 + 2^-14)` (Cauchy-Schwarz), inside an
/// `i32` (the operations wrap by definition, never in fact). Error: within `2^-16 (|a|_1 +
/// |b|_1) + 2^-23` of the exact `a . b` of the inputs, at most 5.3e-5 + 1.2e-7 for unit
/// vectors (`tests.rs`: 1 000 000 random pairs and the axes). For the Lambert-type terms,
/// whose value moves no more than the cosine: about 20 Cortex-M0 instructions where
/// `dot3_small` takes about 45.
#[inline(always)]
pub(super) fn cos_unit_q15(a: [i32; 3], b: [i32; 3]) -> i32 {
    // Written out (not `map`, which the M0 build turned into a loop through the stack).
    cos_prepared_q15(a, [q15(b[0]), q15(b[1]), q15(b[2])])
}

/// `x 2^-22` (raw Q22 bits, at most `2^22 + 2^6` in magnitude) rounded half up to Q15: `(x
/// + 2^6) >> 7`, at most `2^15` in magnitude. [`cos_unit_q15`]'s rounding of each component,
/// made once for a light's fixed axis (the sealed `prepare_axis`).
#[inline(always)]
pub(super) fn q15(x: i32) -> i32 {
    x.wrapping_add(1 << 6) >> 7
}

/// [`cos_unit_q15`]`(a, b)`, bit for bit, with `bq` the rounding [`q15`] of `b`'s
/// components, made once.
#[inline(always)]
pub(super) fn cos_prepared_q15(a: [i32; 3], bq: [i32; 3]) -> i32 {
    cos_q30(a, bq).wrapping_add(1 << 7) >> 8
}

/// The sum of [`cos_unit_q15`] in Q30, before its rounding: each component of `a` rounded
/// half up to Q15 ([`q15`]), the three products by `bq` (`b`'s, rounded) summed (the
/// bounds there).
#[inline(always)]
fn cos_q30(a: [i32; 3], bq: [i32; 3]) -> i32 {
    let p = |k: usize| q15(a[k]).wrapping_mul(bq[k]);
    p(0).wrapping_add(p(1)).wrapping_add(p(2))
}

/// The cosine of [`cos_unit_q15`] in Q15 (from `a` and `b`'s rounding `bq`), clamped to
/// `[-1, 1]`: the Q30 sum clamped to `[-2^30, 2^30]` and rounded half up (within `2^-16`
/// more).
#[cfg(feature = "hemisphere")]
#[inline(always)]
pub(super) fn cos_prepared_q15_clamped(a: [i32; 3], bq: [i32; 3]) -> i32 {
    cos_q30(a, bq)
        .clamp(-(1 << 30), 1 << 30)
        .wrapping_add(1 << 14)
        >> 15
}

/// `m + floor(h c / 2^15)` ([`mul_q15`]) for a Q15 factor `|c| <= 2^15`, with a wrapping
/// sum, for `m = s + g` and `h = s - g` with `s` and `g` in `[-2^30, 2^30)` (the sealed
/// `mix_by_cos`'s precondition): `h c / 2^15` lies in `[-|h|, |h|]`, so does its floor
/// (`|h|` is an integer), and the sum lies in `[2 min(s, g), 2 max(s, g)]`, inside an `i32`:
/// the saturating sum's bits, without its test (`tests.rs`: the edges of `s`, `g` and `c`).
#[cfg(feature = "hemisphere")]
#[inline(always)]
pub(super) fn mix_by_cos(m: i32, h: i32, c: i32) -> i32 {
    m.wrapping_add(mul_q15(h, c))
}

/// `floor(h c / 2^15)` for any `h` (raw bits) and a Q15 factor `|c| <= 2^15`: with `h = hh
/// 2^16 + hl` (`|hh| <= 2^15`, `hl` in `[0, 2^16)`), `2 hh c + floor(hl c / 2^15)`, two
/// 32-bit products (`|hl c| < 2^31`). `|h c / 2^15| <= |h|` fits an `i32`, so the wrapping sum
/// is exact even where `2 hh c` alone reaches `2^31` (`hh = c = -2^15`).
#[cfg(feature = "hemisphere")]
#[inline(always)]
pub(super) fn mul_q15(h: i32, c: i32) -> i32 {
    let (hh, hl) = (h >> 16, h & 0xFFFF);
    (hh.wrapping_mul(c) << 1).wrapping_add(hl.wrapping_mul(c) >> 15)
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

/// [`mul_bits`] rounded to nearest (half up) instead of down: `floor(a b / 2^22 + 1/2)`,
/// exactly, saturated. For the camera's scaling of its clip coordinates, once a vertex.
#[cfg(feature = "raster")]
#[inline(always)]
pub(super) fn mul_bits_round(a: i32, b: i32) -> i32 {
    mul_bits_plus::<32>(a, b)
}

/// `a . u` in raw Q22 bits, rounded to nearest within `7/8` of a unit, for an offset `a`
/// (components below 16 in magnitude: `|a_k| < 2^26` raw) and a unit vector `u` (components
/// at most `1 + 2^-16`, which every normalization keeps). Each product is taken exactly to
/// `floor(a_k u_k / 2^19)` (three bits below Q22: `floor(a u / 2^16) = ah uh 2^16 + mid` as in
/// [`mul_bits_small`], so `floor(a u / 2^19) = ah uh 2^13 + (mid >> 3)`, with `|ah uh| <=
/// 2^10 2^7`), the three summed (at most `16 sqrt 3 (1 + 2^-16) < 28` by Cauchy-Schwarz:
/// below `2^30` in Q25, so the wrapping partial sums end exact) and rounded half up to Q22
/// once: within `(-7/8, 1/2]` of a unit of the exact `a . u`, where
/// [`dot3_small`](crate::real::sealed::Sealed::dot3_small)'s three floors lose up to 3.
/// For the camera's clip coordinates, once a vertex: the same four 32-bit products a
/// component as `mul_bits_small`.
#[cfg(feature = "raster")]
#[inline(always)]
pub(super) fn dot3_unit_round(a: [i32; 3], u: [i32; 3]) -> i32 {
    let q25 = |k: usize| {
        let (ah, al) = (a[k] >> 16, a[k] & 0xFFFF);
        let (uh, ul) = (u[k] >> 16, u[k] & 0xFFFF);
        let mid = (ah.wrapping_mul(ul))
            .wrapping_add(al.wrapping_mul(uh))
            .wrapping_add(((al as u32).wrapping_mul(ul as u32) >> 16) as i32);
        (ah.wrapping_mul(uh) << 13).wrapping_add(mid >> 3)
    };
    q25(0)
        .wrapping_add(q25(1))
        .wrapping_add(q25(2))
        .wrapping_add(4)
        >> 3
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

/// `floor(a b / 2^32)` for `a, b <= 2^31` (a precondition its callers keep; beyond it the
/// result is unspecified, never a panic): the high word of the product, exact, from four
/// 16 x 16-bit products in `i32` arithmetic (every partial product and sum fits an `i32` for
/// these operands). Written on signed halves on purpose: LLVM recognizes the textbook
/// unsigned form as a 64-bit multiply and emits the `__aeabi_lmul` call this avoids.
#[inline(always)]
pub(super) fn mul_hi_u32(a: u32, b: u32) -> u32 {
    let (ah, al) = ((a >> 16) as i32, (a & 0xFFFF) as i32);
    let (bh, bl) = ((b >> 16) as i32, (b & 0xFFFF) as i32);
    // ah, bh <= 2^15 and al, bl < 2^16: ah bl < 2^31; al bl as u32.
    let (m1, m2, ll) = (
        ah.wrapping_mul(bl),
        al.wrapping_mul(bh),
        (al as u32).wrapping_mul(bl as u32),
    );
    // < 3 2^16. (Summing `m2` whole in a `u32`, one split fewer, made LLVM see a 64-bit
    // product in some callers and call `__aeabi_lmul`: Cortex-M0 `phong_hemi_cos` +105.)
    let mid = ((ll >> 16) as i32)
        .wrapping_add(m1 & 0xFFFF)
        .wrapping_add(m2 & 0xFFFF);
    ah.wrapping_mul(bh)
        .wrapping_add(m1 >> 16)
        .wrapping_add(m2 >> 16)
        .wrapping_add(mid >> 16) as u32
}

/// `ceil(2^32 / k)` for the integer `k` in [2, 256] (`RECIP[k - 2]`; exact for a power of two,
/// above `2^32/k` by less than one unit otherwise; each at most `2^31`): the reciprocals of
/// [`div_u32_bits`] and of the fixed-point cosine-power recurrence ([`recip_q32`]). 1 020 bytes:
/// every `k` has its entry, so neither needs `k`'s trailing zeros (about 12 Cortex-M0
/// instructions by a multiplication and a table of their own) nor a test of its parity, where
/// 508 bytes held the odd `k` alone.
pub(super) const RECIP: [u32; 255] = {
    let mut t = [0u32; 255];
    let mut i = 0;
    while i < 255 {
        let k = i as u64 + 2;
        t[i] = ((1u64 << 32).div_ceil(k)) as u32;
        i += 1;
    }
    t
};

/// `1/k` as a Q32 fraction for an integer `k >= 2`: [`RECIP`]'s `ceil(2^32/k)` up to 256 (one
/// lookup; above the exact `2^32/k` by less than one unit, never below), `floor((2^32 - 1)/k)`
/// by division above (`u32::MAX` for `k < 2`). The `1/k` steps of the fixed-point
/// cosine-power recurrence (`polygon::arc`): no division.
#[cfg(all(feature = "polygon", any(feature = "phong", feature = "moments")))]
#[inline(always)]
pub(crate) fn recip_q32(k: u32) -> u32 {
    match RECIP.get((k as usize).wrapping_sub(2)) {
        Some(&r) => r,
        None => recip_q32_cold(k),
    }
}

/// [`recip_q32`] outside the table.
#[cfg(all(feature = "polygon", any(feature = "phong", feature = "moments")))]
#[cold]
#[inline(never)]
fn recip_q32_cold(k: u32) -> u32 {
    if k < 2 {
        u32::MAX
    } else {
        u32::MAX / k
    }
}

/// `a / n` in Q22 for an integer `n` in [1, 256]: bit-identical to `div_bits(a, n 2^22)` (the
/// quotient `a / n` of the raw bits, rounded half away from zero), without its reciprocal
/// core and full product. `q = floor(|a| ceil(2^32/n) / 2^32)` ([`RECIP`]) is
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
    let x = a.unsigned_abs(); // <= 2^31
                              // n in [2, 256]: the entry exists (`get`, so that no panic path is compiled). x R / 2^32 is
                              // below x / n + 1/2 (R exceeds 2^32 / n by less than one unit, x <= 2^31): q is floor(x / n)
                              // or one more.
    let mut q = if n == 1 {
        x
    } else {
        match RECIP.get((n as usize).wrapping_sub(2)) {
            Some(&r) => mul_hi_u32(x, r),
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
