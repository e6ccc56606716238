//! Exact 32 x 32 -> 64-bit products for the integer paths (the rasterizer's edge functions and
//! attribute planes), and the reciprocal core ([`recip_core`]) shared by `Fixed22`'s division
//! and `atan2` and the rasterizer's triangle setup.
//!
//! ARMv6-M (Cortex-M0/M0+) has only a 32 x 32 -> 32-bit `MULS`, and the compiler turns every
//! `i64` product into a call of the 64 x 64-bit `__aeabi_lmul` (about 100 cycles in rp2040js).
//! When both factors fit an `i32`, four 16 x 16-bit products do it inline in about 20
//! instructions. On targets with a widening multiply (`SMULL` on ARMv7-M, x86-64) the plain
//! product is one instruction, and the compiler is given that.

/// `a * b` exactly (`i32 x i32 -> i64`): [`mul_32_by_halves`] on ARMv6-M (recognised by its
/// lack of 32-bit compare-and-swap, which every ARMv7-M and later core has), the plain
/// product elsewhere.
#[inline(always)]
pub(crate) fn mul_32(a: i32, b: i32) -> i64 {
    if cfg!(all(target_arch = "arm", not(target_has_atomic = "32"))) {
        mul_32_by_halves(a, b)
    } else {
        i64::from(a) * i64::from(b)
    }
}

/// `floor(a b / 2^s)` for `16 <= s <= 32`, the caller guaranteeing that it fits an `i32`: on
/// ARMv6-M four 16 x 16-bit products combined in 32-bit integers (as `Fixed22`'s product:
/// with `a b = H 2^32 + w 2^16 + r`, `r < 2^16`, the result is `H 2^(32 - s) + floor(w /
/// 2^(s - 16))`, no 64-bit addition or shift), the plain 64-bit product elsewhere. Exact on
/// both (the same bits).
#[cfg(all(
    feature = "fixed",
    feature = "polygon",
    any(feature = "phong", feature = "moments")
))]
#[inline(always)]
pub(crate) fn mul_shr(a: i32, b: i32, s: u32) -> i32 {
    if cfg!(all(target_arch = "arm", not(target_has_atomic = "32"))) {
        mul_shr_by_halves(a, b, s)
    } else {
        ((i64::from(a) * i64::from(b)) >> s.clamp(16, 32)) as i32
    }
}

/// [`mul_shr`] from four 16 x 16-bit products (each fits the 32-bit `MULS`).
#[cfg(all(
    feature = "fixed",
    feature = "polygon",
    any(feature = "phong", feature = "moments")
))]
#[inline(always)]
pub(crate) fn mul_shr_by_halves(a: i32, b: i32, s: u32) -> i32 {
    let s = s.clamp(16, 32);
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    // |ah|, |bh| <= 2^15 and al, bl < 2^16: every partial product fits its type.
    let (m1, m2, ll) = (ah * bl, al * bh, (al as u32) * (bl as u32));
    let h = (ah * bh).wrapping_add(m1 >> 16).wrapping_add(m2 >> 16);
    let w = ((m1 & 0xFFFF) + (m2 & 0xFFFF)) as u32 + (ll >> 16); // < 3 2^16
    h.wrapping_shl(32 - s).wrapping_add((w >> (s - 16)) as i32)
}

/// A factor in `[0, 1)` as an unsigned Q32 fraction (`m 2^-32`), with its 16-bit halves kept
/// ready: the constant factor of a loop of [`mul_q32`] products is split once.
#[cfg(all(
    feature = "fixed",
    feature = "polygon",
    any(feature = "phong", feature = "moments")
))]
#[derive(Clone, Copy, PartialEq, Debug)]
pub(crate) struct Q32 {
    hi: u32,
    lo: u32,
}

#[cfg(all(
    feature = "fixed",
    feature = "polygon",
    any(feature = "phong", feature = "moments")
))]
impl Q32 {
    /// The fraction `m 2^-32`.
    #[inline(always)]
    pub(crate) fn new(m: u32) -> Self {
        Q32 {
            hi: m >> 16,
            lo: m & 0xFFFF,
        }
    }

    /// Whether the fraction is 0.
    #[inline(always)]
    pub(crate) fn is_zero(self) -> bool {
        self.hi | self.lo == 0
    }
}

/// `x m / 2^32` for a signed `x` and the fraction `m`, within one unit of its floor (the high
/// word of the signed-by-unsigned product): from three 16 x 16-bit products with `m`'s halves
/// ready, on every target (the same bits on the host and the Cortex-M0). With `x = xh 2^16 +
/// xl` and `m = mh 2^16 + ml`, `x m = xh mh 2^32 + (a + b) 2^16 + xl ml` (`a = xh ml` signed,
/// `b = xl mh` unsigned); the floor is `xh mh + (a >> 16) + (b >> 16) + c` with the carry `c`
/// in `{0, 1, 2}` of the three dropped fractions (`a`'s and `b`'s low 16 bits, `xl ml / 2^16`,
/// whose sum averages `1.25 2^16`). The result takes `c = 1`: within one unit of the floor
/// either way (`(-2, 1]` units of `x m / 2^32` itself, a quarter of a unit below it on
/// average), from three `MULS` and no carry word: about 4 Cortex-M0 instructions fewer than
/// the exact floor from four (`phong_polygon` on a quad at m = 16, 28 recurrence steps of 4
/// products, with a `UnitVec3`: 10 491 -> 10 059; before, 11 841 -> 11 508 with the middle
/// products whole). Targets with a 64-bit product in an instruction or two pay a few
/// instructions a product for the same bits (RV32IMC, whose `MULH` gave the exact high word:
/// `phong_polygon` 7 304 -> 7 337 after this module's other changes).
#[cfg(all(
    feature = "fixed",
    feature = "polygon",
    any(feature = "phong", feature = "moments")
))]
#[inline(always)]
pub(crate) fn mul_q32(x: i32, m: Q32) -> i32 {
    let (xh, xl) = (x >> 16, (x & 0xFFFF) as u32);
    // |xh| <= 2^15, xl, mh, ml < 2^16: xh mh and a fit an i32, b a u32.
    let hh = xh.wrapping_mul(m.hi as i32);
    let a = xh.wrapping_mul(m.lo as i32);
    let b = xl.wrapping_mul(m.hi);
    hh.wrapping_add(a >> 16)
        .wrapping_add((b >> 16) as i32)
        .wrapping_add(1)
}

/// `a * b` exactly from four 16 x 16-bit products (each fits the 32-bit `MULS`).
#[inline(always)]
pub(crate) fn mul_32_by_halves(a: i32, b: i32) -> i64 {
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    // |ah|, |bh| <= 2^15 and al, bl < 2^16: the cross products fit an i32, the low one a u32.
    let hh = i64::from(ah * bh);
    let mid = i64::from(ah * bl) + i64::from(al * bh);
    let ll = i64::from((al as u32) * (bl as u32));
    (hh << 32) + (mid << 16) + ll
}

/// `a * b` (wrapping) of two `i64`, through [`mul_32`] when both fit an `i32` (the usual
/// case), through the full 64-bit product otherwise.
#[cfg(feature = "raster")]
#[inline(always)]
pub(crate) fn mul_64(a: i64, b: i64) -> i64 {
    if a == i64::from(a as i32) && b == i64::from(b as i32) {
        mul_32(a as i32, b as i32)
    } else {
        a.wrapping_mul(b)
    }
}

/// `floor((a1 b1 + a2 b2) / 2^24)` modulo 2^32 (bits 24 to 55 of the exact sum of two
/// 32 x 32 -> 64-bit products): on ARMv6-M from eight 16 x 16-bit products combined in 32-bit
/// integers ([`dot2_shr24_by_halves`]: no 64-bit addition or shift), the plain 64-bit products
/// elsewhere. The same bits on both.
#[cfg(feature = "raster")]
#[inline(always)]
pub(crate) fn dot2_shr24(a1: i32, b1: i32, a2: i32, b2: i32) -> i32 {
    if cfg!(all(target_arch = "arm", not(target_has_atomic = "32"))) {
        dot2_shr24_by_halves(a1, b1, a2, b2)
    } else {
        // The sum can wrap an i64 (only for two products of i32::MIN), which leaves bits
        // 24 to 55 as they are.
        ((i64::from(a1) * i64::from(b1)).wrapping_add(i64::from(a2) * i64::from(b2)) >> 24) as i32
    }
}

/// [`dot2_shr24`] from 16 x 16-bit products: with each product `ah bh 2^32 + (ah bl + al bh)
/// 2^16 + al bl`, the sum is `h 2^32 + w 2^16 + r` (the cross products split at bit 16, the
/// low products too; `0 <= w < 6 2^16`, `0 <= r < 2^17`), and `floor(sum / 2^24) = h 2^8 +
/// floor((w + floor(r / 2^16)) / 2^8)`.
#[cfg(feature = "raster")]
#[inline(always)]
pub(crate) fn dot2_shr24_by_halves(a1: i32, b1: i32, a2: i32, b2: i32) -> i32 {
    let halves = |x: i32| (x >> 16, x & 0xFFFF);
    let ((a1h, a1l), (b1h, b1l)) = (halves(a1), halves(b1));
    let ((a2h, a2l), (b2h, b2l)) = (halves(a2), halves(b2));
    // |xh| <= 2^15 and xl < 2^16: every cross product fits an i32, the low ones a u32.
    let m = [a1h * b1l, a1l * b1h, a2h * b2l, a2l * b2h];
    let (ll1, ll2) = ((a1l as u32) * (b1l as u32), (a2l as u32) * (b2l as u32));
    let h = (a1h * b1h)
        .wrapping_add(a2h * b2h)
        .wrapping_add(m[0] >> 16)
        .wrapping_add(m[1] >> 16)
        .wrapping_add(m[2] >> 16)
        .wrapping_add(m[3] >> 16);
    let w = ((m[0] & 0xFFFF) + (m[1] & 0xFFFF) + (m[2] & 0xFFFF) + (m[3] & 0xFFFF)) as u32
        + (ll1 >> 16)
        + (ll2 >> 16);
    let r = (ll1 & 0xFFFF) + (ll2 & 0xFFFF);
    h.wrapping_shl(8)
        .wrapping_add(((w + (r >> 16)) >> 8) as i32)
}

/// `floor(a b / 2^32)` for any `a, b` (the high word of the full 32 x 32-bit product), from
/// four 16 x 16-bit products in `u32` arithmetic: `a b = hh 2^32 + (m1 + m2) 2^16 + ll`, with
/// the carries of `m1 + m2` and of the low word taken explicitly. (The form with
/// `mid = (ll >> 16) + (m1 mod 2^16) + (m2 mod 2^16)`, as `Fixed22`'s signed `mul_hi_u32` but unsigned, is
/// recognized by LLVM as a 64-bit multiply: a `__aeabi_lmul` call on ARMv6-M.)
#[inline(always)]
pub(crate) fn mul_hi_full(a: u32, b: u32) -> u32 {
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    let (m1, m2, ll) = (ah * bl, al * bh, al * bl);
    let (mid, carry) = m1.overflowing_add(m2);
    let (_, low_carry) = (mid << 16).overflowing_add(ll);
    ah * bh + (mid >> 16) + (u32::from(carry) << 16) + u32::from(low_carry)
}

/// Quadratic starts for `1/x` on the 16 intervals `[1 + i/16, 1 + (i + 1)/16)` of `[1, 2)`:
/// `(c0 2^30, c1 2^19, c2 2^19)` of `c0 + c1 t + c2 t^2`, `t` in [0, 1) across the interval
/// (Chebyshev interpolation; relative error 2^-16.9 as evaluated). 128 bytes.
pub(crate) const RECIP_SEED: [(u32, i16, u16); 16] = [
    (1073734349, -32702, 1869),
    (1010574644, -28974, 1566),
    (954432464, -25849, 1326),
    (904199829, -23204, 1132),
    (858990342, -20944, 974),
    (818086435, -18999, 844),
    (780901002, -17313, 737),
    (746949035, -15842, 647),
    (715826361, -14550, 571),
    (687193472, -13410, 506),
    (660763090, -12399, 451),
    (636290495, -11499, 403),
    (613565928, -10692, 362),
    (592408561, -9968, 327),
    (572661675, -9315, 296),
    (554188774, -8724, 268),
];

/// `2^63 / d` for `d` in `[2^31, 2^32)` (a Q32 reciprocal of `d / 2^31` in [1, 2)), rounded
/// down to within 3 units: `floor(2^63 / d) - 3 <= y <= floor(2^63 / d)` (checked for every
/// `d`: `recip_core_is_within_three_units_below`), so `y <= 2^63 / d` always. A quadratic
/// start from [`RECIP_SEED`] (2^-16.9) and one Newton step `y (1 + (1 - d y))`, whose
/// residual `1 - d y` (below 2^-16) is the high word of one full product: no division, about
/// 50 Cortex-M0 instructions. The one reciprocal of `Fixed22`'s division and `atan2`'s ratio,
/// and (corrected to the exact floor) of the rasterizer's triangle setup.
#[inline(always)]
pub(crate) fn recip_core(d: u32) -> u32 {
    // d >= 2^31: the index is in [0, 16) (`get`, so that no panic path is compiled).
    let (c0, c1, c2) = match RECIP_SEED.get(((d >> 27) & 15) as usize) {
        Some(&e) => e,
        None => RECIP_SEED[0],
    };
    let t = ((d >> 11) & 0xFFFF) as i32;
    // |c1| < 2^15, t < 2^16: every product fits an i32.
    let inner = i32::from(c1) + ((i32::from(c2) * t) >> 16);
    let y0 = (c0 as i32 + ((inner * t) >> 5)).min((1 << 30) - 1) as u32;
    let y = y0 << 2; // Q32, < 2^32 - 3
                     // d y = 2^63 (1 - e): the high word is 2^31 (1 - e), |e| < 2^-16, so |c| < 2^15.
    let c = (1u32 << 31).wrapping_sub(mul_hi_full(d, y)) as i32;
    let (yh, yl) = ((y >> 16) as i32, (y & 0xFFFF) as i32);
    // `y e`, Q32. The high word's floor can make `c` up to one unit large (`delta` up to 2
    // units): the 2 taken off keep `y` below 2^63/d (and below 2^32 where 2^63/d is near
    // 2^32).
    let delta = (yh * c + ((yl * c) >> 16)) >> 15;
    y.wrapping_add(delta.wrapping_sub(2) as u32)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// The tests' generator ([`crate::test_rng`]) as `i32`s from `seed`.
    #[allow(dead_code)] // the tests below are feature-gated
    fn xorshift(seed: u32) -> impl FnMut() -> i32 {
        let mut next = crate::test_rng::xorshift32(seed);
        move || next() as i32
    }

    /// Operands at the 16-bit halves' boundaries and the ends of the range.
    const EDGE: [i32; 9] = [
        0,
        1,
        -1,
        0xFFFF,
        0x10000,
        -0x10000,
        i32::MAX,
        i32::MIN,
        1 << 30,
    ];

    #[cfg(all(
        feature = "fixed",
        feature = "polygon",
        any(feature = "phong", feature = "moments")
    ))]
    #[test]
    fn shifted_products_by_halves_equal_the_64_bit_ones() {
        let mut next = xorshift(0x9E37_79B9);
        let edge = EDGE;
        for s in 16..=32u32 {
            let mut pairs: std::vec::Vec<(i32, i32)> = std::vec::Vec::new();
            for &a in &edge {
                for &b in &edge {
                    pairs.push((a, b));
                }
            }
            for _ in 0..20_000 {
                // Operands of every size, shifted down so that most products fit.
                let (a, b) = (next(), next());
                pairs.push((a >> (next() as u32 % 32), b >> (next() as u32 % 32)));
            }
            for (a, b) in pairs {
                let exact = (i64::from(a) * i64::from(b)) >> s;
                if exact != i64::from(exact as i32) {
                    continue; // the caller's bound excludes it
                }
                assert_eq!(mul_shr_by_halves(a, b, s), exact as i32, "{a} * {b} >> {s}");
                assert_eq!(mul_shr(a, b, s), exact as i32, "{a} * {b} >> {s}");
            }
        }
    }

    #[cfg(all(
        feature = "fixed",
        feature = "polygon",
        any(feature = "phong", feature = "moments")
    ))]
    #[test]
    fn q32_products_are_within_one_unit_of_the_floor() {
        let mut next = xorshift(0x7F4A_7C15);
        let mut pairs: std::vec::Vec<(i32, u32)> = std::vec::Vec::new();
        for &x in &EDGE {
            for &m in &EDGE {
                pairs.push((x, m as u32));
            }
            pairs.push((x, u32::MAX));
        }
        for _ in 0..1_000_000 {
            let (x, m) = (next(), next() as u32);
            pairs.push((x >> (next() as u32 % 32), m >> (next() as u32 % 32)));
        }
        // The error against the real product x m / 2^32, in units: within (-2, 1].
        let err = |x: i32, m: u32| {
            let exact = i64::from(x) * i64::from(m);
            let got = i64::from(mul_q32(x, Q32::new(m)));
            assert!(
                (got - (exact >> 32)).abs() <= 1,
                "{x} * {m} >> 32: {got} against {}",
                exact >> 32
            );
            got as f64 - exact as f64 / 2f64.powi(32)
        };
        for &(x, m) in &pairs {
            let e = err(x, m);
            assert!(e > -2.0 && e <= 1.0, "{x} * {m}: error {e}");
        }
        // On operands of full width (the recurrence's), a quarter of a unit below the real
        // product on average: the three dropped fractions average 1.25 units.
        let n = 1_000_000;
        let mean = (0..n).map(|_| err(next(), next() as u32)).sum::<f64>() / f64::from(n);
        assert!((-0.27..=-0.23).contains(&mean), "mean error {mean}");
    }

    #[cfg(feature = "raster")]
    #[test]
    fn dot2_shr24_by_halves_equals_the_64_bit_sum() {
        let mut next = xorshift(0x2545_F491);
        let edge = EDGE;
        let mut quads: std::vec::Vec<[i32; 4]> = std::vec::Vec::new();
        for &a in &edge {
            for &b in &edge {
                quads.push([a, b, a, b]);
                quads.push([a, b, b, a]);
                quads.push([a, b, -1, a]);
            }
        }
        for _ in 0..200_000 {
            let q = [next(), next(), next(), next()];
            quads.push(q.map(|v| v >> (next() as u32 % 32)));
            quads.push(q);
        }
        for [a1, b1, a2, b2] in quads {
            let exact =
                ((i128::from(a1) * i128::from(b1) + i128::from(a2) * i128::from(b2)) >> 24) as i32;
            assert_eq!(
                dot2_shr24_by_halves(a1, b1, a2, b2),
                exact,
                "{a1} {b1} {a2} {b2}"
            );
            assert_eq!(dot2_shr24(a1, b1, a2, b2), exact, "{a1} {b1} {a2} {b2}");
        }
    }

    #[test]
    fn products_are_exact() {
        let edge: std::vec::Vec<i32> = EDGE
            .iter()
            .copied()
            .chain([i32::MIN + 1, 12345678, -87654321])
            .collect();
        for &a in &edge {
            for &b in &edge {
                assert_eq!(mul_32(a, b), i64::from(a) * i64::from(b), "{a} {b}");
                assert_eq!(
                    mul_32_by_halves(a, b),
                    i64::from(a) * i64::from(b),
                    "{a} {b}"
                );
                #[cfg(feature = "raster")]
                {
                    let (a, b) = (i64::from(a), i64::from(b));
                    assert_eq!(mul_64(a, b), a.wrapping_mul(b));
                    assert_eq!(mul_64(a << 20, b), (a << 20).wrapping_mul(b));
                }
            }
        }
    }
}
