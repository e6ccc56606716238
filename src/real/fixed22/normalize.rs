//! The normalizations' pieces for [`Fixed22`](super::Fixed22): the rescaling by a power of
//! two that brings a vector's largest component to `[1, 2)` ([`rescale_for_unit`]; `[1/2, 1)`
//! for `Real::rescale3` and the edge planes, [`rescale_by_top`]), its sum of squares without
//! saturation tests ([`unit_scale`]), and the square root and reciprocal square root of that
//! sum from the normalizations' table-seeded core ([`unit_sqrt_rsqrt`], [`unit_rsqrt`]:
//! `elementary::rsqrt_core_unit`). `Real::normalize3`, `Real::unit3` and the sealed
//! `sphere_ratios` are put together from them; the 16-bit normalization of the polygon edge
//! terms ([`unit_q15`]) is apart.
//!
//! Measured on the Cortex-M0 (QEMU budget, `Fixed22`): the normalizations' core, the
//! rescaling to `[1, 2)` and the scalings rounded to nearest took about 33 instructions off
//! every normalization (`hemi_const` 284 -> 250, `sphere_lambert` 695 -> 628,
//! `PolygonLight<_, 4>::phong` at m = 15 8 202 -> 7 936 with a `Vec3`, 7 979 -> 7 747 with a
//! `UnitVec3`), and the unit vectors' worst component error against f64 went 6.05 -> 2.01
//! units of `2^-22` (400 000 random vectors of every magnitude).

#[cfg(feature = "polygon")]
use super::elementary::rsqrt_seed;
use super::elementary::{even_top_of_square_sum, rsqrt_core_unit, rsqrt_out, sqrt_out};
use super::kernels::{clz, mul_bits_le2};
use super::{Fixed22, FRAC};
use crate::Real;

/// `x^2 + y^2 + z^2` of components of at most 2 in magnitude (what `rescale_by_top` leaves):
/// each square by `mul_bits_le2` (three 32-bit products), the sum (at most 12) without
/// saturation tests; the same bits as `x * x + y * y + z * z`.
#[inline(always)]
pub(super) fn unit_scale(x: Fixed22, y: Fixed22, z: Fixed22) -> Fixed22 {
    let sq = |c: Fixed22| mul_bits_le2(c.to_bits(), c.to_bits());
    Fixed22::from_bits(sq(x) + sq(y) + sq(z))
}

/// The square root and reciprocal square root of a sum of squares from `unit_scale` (in
/// `[1/4, 12]`) by the normalizations' core (`elementary::rsqrt_core_unit`: `y` to a relative
/// `2^-28`; the Q22 results round it to `2^-22`, so it shows only near a rounding step), the
/// exponent from two comparisons ([`even_top_of_square_sum`]) instead of a leading-zero count.
#[inline(always)]
pub(super) fn unit_sqrt_rsqrt(s: Fixed22) -> (Fixed22, Fixed22) {
    let x = s.to_bits();
    if x <= 0 {
        return (Fixed22::ZERO, Fixed22::ZERO);
    }
    let v = x as u32;
    let (m, j, y) = rsqrt_core_unit(v, even_top_of_square_sum(v));
    (
        Fixed22::from_bits(sqrt_out(m, j, y)),
        Fixed22::from_bits(rsqrt_out(j, y)),
    )
}

/// The reciprocal square root of a sum of squares from `unit_scale`: [`unit_sqrt_rsqrt`]'s.
#[inline(always)]
pub(super) fn unit_rsqrt(s: Fixed22) -> Fixed22 {
    let x = s.to_bits();
    if x <= 0 {
        return Fixed22::ZERO;
    }
    let v = x as u32;
    let (_, j, y) = rsqrt_core_unit(v, even_top_of_square_sum(v));
    Fixed22::from_bits(rsqrt_out(j, y))
}

/// The OR of the components' magnitudes (a bound for [`rescale_by_top`] with the largest
/// magnitude's highest set bit, so the same rescaling), or `None` where the largest magnitude
/// is at most `tiny` (raw bits, below `2^30`): the normalizations' test `max |v_i| <= TINY`,
/// exact. The OR settles it where its highest bit lies above `tiny`'s (every nonzero
/// vector the normalizations meet in practice); only below that are the magnitudes compared
/// (cold). The three saturating absolute values and two NaN-aware maxima it replaces cost
/// about 40 Cortex-M0 instructions; `i32::MIN`'s magnitude `2^31` and the saturated `2^31 -
/// 1` give the same shift (the shift right stops at 8).
#[inline(always)]
pub(super) fn magnitude_top(v: [Fixed22; 3], tiny: Fixed22) -> Option<u32> {
    let [x, y, z] = [v[0].to_bits(), v[1].to_bits(), v[2].to_bits()];
    let top = x.unsigned_abs() | y.unsigned_abs() | z.unsigned_abs();
    let t = tiny.to_bits() as u32;
    if top >> 1 <= t && top_at_most(x, y, z, t) {
        return None;
    }
    Some(top)
}

/// `max |v_i| <= t` for [`magnitude_top`]'s cold case (`top < 2 t + 2`).
#[cold]
#[inline(never)]
fn top_at_most(x: i32, y: i32, z: i32, t: u32) -> bool {
    x.unsigned_abs() <= t && y.unsigned_abs() <= t && z.unsigned_abs() <= t
}

/// `v` scaled by the power of two that brings `top`'s highest set bit (a bound on every
/// component's magnitude in raw bits: no component's bits reach above it) to bit 21 (bit 22
/// for bits 30 and 31, the shift right being limited to 8), and that power of two; `(v, 1)`
/// for `top = 0`. With `top` such a bound no left shift overflows.
#[inline(always)]
pub(super) fn rescale_by_top(v: [Fixed22; 3], top: u32) -> ([Fixed22; 3], Fixed22) {
    if top == 0 {
        return (v, Fixed22::ONE);
    }
    let (scaled, k) = rescale_by_top_exp(v, top);
    (scaled, Fixed22::from_bits(1 << (FRAC as i32 - k)))
}

/// `f(h)` with `h` the position of `top`'s highest set bit (`top > 0`): its four values
/// (given as constants, `f(23)` to `f(20)`) from three comparisons where `h` is in
/// `[20, 23]` (vectors of magnitude 1/4 to 4, those the normalizations mostly meet), from
/// [`clz`] elsewhere. One macro for
/// [`top_exponent`] and [`top_bit`], so that each ladder has its own constants: every way of
/// sharing one function that I tried (a common `Option`, one through the other) LLVM compiled
/// with the clamp or the subtraction back in the band, and one of the two lost its gain
/// (measured on the Cortex-M0).
macro_rules! by_top_bit {
    ($top:expr, [$at23:expr, $at22:expr, $at21:expr, $at20:expr], |$h:ident| $f:expr) => {{
        let top: u32 = $top;
        if top >> 20 != 0 && top >> 24 == 0 {
            if top >= 1 << 22 {
                if top >= 1 << 23 {
                    $at23
                } else {
                    $at22
                }
            } else if top >= 1 << 21 {
                $at21
            } else {
                $at20
            }
        } else {
            let $h = 31 - clz(top) as i32;
            $f
        }
    }};
}

/// The rescaling's exponent `(21 - h).clamp(-8, 21)` for the highest set bit `h` of `top`
/// (`top > 0`), the same value as from [`clz`].
#[inline(always)]
pub(super) fn top_exponent(top: u32) -> i32 {
    by_top_bit!(top, [-2, -1, 0, 1], |h| (21 - h).clamp(-8, 21))
}

/// The normalizations' exponent `(22 - h).clamp(-8, 22)` ([`rescale_for_unit`]): one bit
/// above [`top_exponent`]'s, the same value as from [`clz`].
#[inline(always)]
pub(super) fn unit_top_exponent(top: u32) -> i32 {
    by_top_bit!(top, [-1, 0, 1, 2], |h| (22 - h).clamp(-8, 22))
}

/// The position `31 - clz(top)` of `top`'s highest set bit (`top > 0`): the 16-bit
/// normalization's exponent.
#[cfg(feature = "polygon")]
#[inline(always)]
pub(super) fn top_bit(top: u32) -> i32 {
    by_top_bit!(top, [23, 22, 21, 20], |h| h)
}

/// [`rescale_by_top`] for `top > 0`, with the exponent `k` of its power of two `2^-k` (in
/// `[-8, 21]`) instead of the power itself.
#[inline(always)]
pub(super) fn rescale_by_top_exp(v: [Fixed22; 3], top: u32) -> ([Fixed22; 3], i32) {
    shift_by(v, top_exponent(top))
}

/// The normalizations' rescaling (`normalize3`, `unit3`, `sphere_ratios`): `v` scaled by the
/// power of two `2^k` that brings `top`'s highest set bit to bit 22 (bit 23 for bit 31, the
/// shift right being limited to 8), so that the largest component lies in `[1, 2)` (at most
/// 2), and `k` (in `[-8, 22]`; `top > 0`). One bit above [`rescale_by_top_exp`]'s `[1/2, 1)`:
/// the sum of squares is then at least 1, so its three roundings down (`2^-22` each) cost
/// `1/sqrt(S)` at most `1.5 2^-22` relative where at `S = 1/4` they cost four times that.
/// Measured on 400 000 random vectors of every magnitude: the unit vectors' worst component
/// error 6.05 -> 2.01 units of `2^-22` against f64 (`tests/fixed_kernels.rs`), with the
/// scalings rounded to nearest.
#[inline(always)]
pub(super) fn rescale_for_unit(v: [Fixed22; 3], top: u32) -> ([Fixed22; 3], i32) {
    shift_by(v, unit_top_exponent(top))
}

/// `v` times `2^k` by shifts (`k` in `[-8, 22]`, from a bound `top` that keeps the left
/// shifts from overflowing).
#[inline(always)]
fn shift_by(v: [Fixed22; 3], k: i32) -> ([Fixed22; 3], i32) {
    // Written out (not `map`, which the M0 build turned into a loop through the stack).
    let [x, y, z] = [v[0].to_bits(), v[1].to_bits(), v[2].to_bits()];
    let [x, y, z] = if k >= 0 {
        [x << k, y << k, z << k]
    } else {
        let s = -k;
        [x >> s, y >> s, z >> s]
    };
    let scaled = [
        Fixed22::from_bits(x),
        Fixed22::from_bits(y),
        Fixed22::from_bits(z),
    ];
    (scaled, k)
}

/// A length `len` of a vector scaled by `2^k` ([`rescale_by_top_exp`]'s `k`, in `[-8, 21]`, or
/// [`rescale_for_unit`]'s, in `[-8, 22]`)
/// back at the vector's own scale: `len 2^-k` rounded down and saturated, the bits of `len *
/// 2^-k` (`Fixed22`'s product rounds down) by one shift instead of a product (a left shift
/// only for `k < 0`, where `len` may be up to `2 sqrt(3)` and `2^-k` up to 256).
#[inline(always)]
pub(super) fn unscale_length(len: Fixed22, k: i32) -> Fixed22 {
    let bits = len.to_bits();
    Fixed22::from_bits(if k >= 0 {
        bits >> k.min(31)
    } else {
        let s = (-k).min(8);
        if bits > i32::MAX >> s {
            i32::MAX
        } else {
            bits << s
        }
    })
}

/// The sealed `edge_plane_terms`: `(r.g/|g|, d/|g|, |g|)` for `g = a x b` of unit `a`, `b`
/// and `d = r.(g x a)` (so `|d| <= |g|` up to roundings). `g` is scaled by the power of two
/// `2^k` of [`rescale_by_top_exp`] (`k` in `[-1, 21]`: `|g| <= 1`) and `d` by the same, so
/// that `r.g 2^k` and `d 2^k` are multiplied by the one reciprocal `1/|g 2^k|`: the same
/// rescaling, squares and square root as `normalize3` (the length is its bits), without the
/// three products of the unit vector, and `d/|g|` in place of the triple product `r.(gu x a)`
/// of nine. `d 2^k` is first clamped to `[-2, 2]` (its magnitude is `|g 2^k| <= sqrt(3)` up to
/// the roundings of `d`, a few `2^-22` before scaling; the clamp bounds what garbage a caller
/// could pass), so every product is `mul_bits_le2`'s (factors of at most 2).
#[cfg(all(feature = "polygon", feature = "phong"))]
#[inline(always)]
pub(super) fn edge_plane_terms(
    g: [Fixed22; 3],
    r: [Fixed22; 3],
    d: Fixed22,
) -> Option<(Fixed22, Fixed22, Fixed22)> {
    let top = magnitude_top(g, Fixed22::TINY)?;
    let ([x, y, z], k) = rescale_by_top_exp(g, top);
    let (len, inv) = unit_sqrt_rsqrt(unit_scale(x, y, z));
    let m = |a: i32, b: i32| mul_bits_le2(a, b);
    let rg = m(x.to_bits(), r[0].to_bits())
        + m(y.to_bits(), r[1].to_bits())
        + m(z.to_bits(), r[2].to_bits());
    let two = 1i32 << (FRAC + 1);
    let d = if k >= 0 {
        d.to_bits().clamp(-(two >> k), two >> k) << k
    } else {
        (d.to_bits() >> -k).clamp(-two, two)
    };
    let inv = inv.to_bits();
    Some((
        Fixed22::from_bits(m(rg, inv)),
        Fixed22::from_bits(m(d, inv)),
        unscale_length(len, k),
    ))
}

/// The unit vector of `v` in Q15, `None` exactly where `Real::unit3` is (`max |v_i| <=
/// TINY`): the sealed `unit3_q15`, for the polygon Lambert edge terms
/// (`polygon::edge::unit_ratio_term`), in 16-bit form throughout so that every product is one
/// 32 x 32 -> 32-bit product (one `MULS` on the Cortex-M0):
///
/// 1. `v` scaled by the power of two that puts its largest magnitude's leading bit at bit 14,
///    rounding half up where it shifts right: `c`, with `2^14 <= max |c_i| <= 2^15`;
/// 2. `S = |c|^2` in `u32`, in `[2^28, 3 2^30]` (each square at most `2^30`);
/// 3. `r = 2^30 / sqrt(S)` from the table's quadratic start alone ([`rsqrt_seed`], relative
///    `2^-15.8`, the precision the 16-bit result keeps; `S` or `4 S` is its argument, in
///    `[2^30, 2^32)`), rounded to an integer: in `[2^14, 2^16]`, relative error at most
///    `2^-15.8 + 2^-15.2` (4.4e-5);
/// 4. `u_i = c_i r / 2^15`, rounded: `c_i r` is `u_i 2^30` to within that error, at most
///    `2^30 (1 + 4.4e-5)`, inside `i32`.
///
/// Bounds (what `unit_ratio_term` relies on): each component is at most `2^15 + 1` in
/// magnitude (`2^15` itself can round up: `[-65, 0, 0]` gives `-32 769`) and the length at
/// most `2^15 (1 + 2^-13)`. Error: the rounding of `c` (at most `2^-15` of `|v|` a
/// component: 5.3e-5 in direction), `r`'s 4.4e-5 and the result's rounding (`2^-16`): within
/// 1.1e-4 of `v / |v|` a component (5.2e-5 measured on 400 000 random vectors of every
/// magnitude by this module's tests), against `2^-16` (1.5e-5) for `unit3`'s Q22 result
/// rounded to Q15. The polygon Lambert sums stay within 1/1024 with a wide margin
/// (`tests/fixed/`, measured in the docs of `unit_ratio_term`). Cost: about 130 Cortex-M0
/// instructions as inlined in the polygon Lambert term (QEMU, traced), where `unit3` took
/// about 330.
#[cfg(feature = "polygon")]
#[inline(always)]
pub(super) fn unit_q15(v: [Fixed22; 3]) -> Option<[i32; 3]> {
    let top = magnitude_top(v, Fixed22::TINY)?;
    let high = top_bit(top); // 0..=31
    let [x, y, z] = [v[0].to_bits(), v[1].to_bits(), v[2].to_bits()];
    let k = 14 - high;
    let [x, y, z] = if k >= 0 {
        [x << k, y << k, z << k]
    } else {
        // Half up without an intermediate overflow: `|x >> (s - 1)|` is at most `2^16`.
        let s = (-k - 1) as u32;
        [
            ((x >> s) + 1) >> 1,
            ((y >> s) + 1) >> 1,
            ((z >> s) + 1) >> 1,
        ]
    };
    // Each square at most 2^30 (`|c| <= 2^15`): the sum at most 3 2^30, in `u32`.
    let s = (x * x) as u32 + (y * y) as u32 + (z * z) as u32;
    let r = if s >= 1 << 30 {
        // S = M 2^30: r = 2^30 / sqrt(S) = 2^15 / sqrt(M) = seed / 2^15.
        (rsqrt_seed(s) + (1 << 14)) >> 15
    } else {
        // S in [2^28, 2^30): M = 4 S / 2^30, r = 2^16 / sqrt(M) = seed / 2^14.
        (rsqrt_seed(s << 2) + (1 << 13)) >> 14
    } as i32;
    let u = |c: i32| (c * r + (1 << 14)) >> 15;
    Some([u(x), u(y), u(z)])
}
