//! One arc of a boundary on the unit sphere, as `[phong_polygon]`'s `J` terms and Arvo's
//! moments both integrate it: the arc from the unit direction `s` through the angle `x` about
//! the unit pole `g`, `u(t) = s cos t + (g x s) sin t`, against an axis `w`:
//! `w.u(t) = a cos t + b sin t`. [`arc_axis_form`] sets the form up, [`cos_power_sums`]
//! integrates its powers along the arc.

use crate::real::SOFT_FLOAT;
use crate::Real;
#[cfg(feature = "moments")]
use crate::UnitVec3;

/// The axis `w`'s form `w.u(t) = a cos t + b sin t` along the arc from the unit direction `s`
/// about the unit pole `g`, given `wg = w.g` and `a = w.s`: returns `(b, f)`, `b = w.(g x s)`
/// and `f = a^2 + b^2 = 1 - (w.g)^2`, the latter in the form exact near 1 (to an ULP), where
/// [`cos_power_sums`] raises `f` to the power `n/2`. Cost: a cross product, a dot product,
/// 1 or 2 products.
#[cfg(feature = "moments")]
#[inline(always)]
pub(crate) fn arc_axis_form<T: Real>(
    w: UnitVec3<T>,
    g: UnitVec3<T>,
    s: UnitVec3<T>,
    wg: T,
    a: T,
) -> (T, T) {
    // Every factor here is at most 2 in magnitude (unit vectors, their products, 1 +- wg for
    // |wg| < 1/2): the products without fixed point's saturation tests, the same bits.
    let b = w.triple(g, s);
    (b, arc_axis_f(wg, a, b))
}

/// [`arc_axis_form`]'s `f = a^2 + b^2 = 1 - (w.g)^2` from `wg = w.g`, `a` and `b`: `(1 - wg)(1
/// + wg)` for `|wg| < 1/2`, else `a^2 + b^2` (at most 1), the form exact near 1 (to an ULP).
#[inline(always)]
pub(crate) fn arc_axis_f<T: Real>(wg: T, a: T, b: T) -> T {
    if wg.abs() < T::HALF {
        T::mul_le2(T::ONE - wg, T::ONE + wg)
    } else {
        clamp_excursion(T::mul_le2(a, a) + T::mul_le2(b, b), |v| v.min(T::ONE))
    }
}

/// `clamp(v)` on fixed point, `v` itself on the floats: for a quantity whose exact value lies
/// in the range `clamp` clamps to and leaves it only by rounding (a cosine of unit vectors, a
/// sine from a cross product's length), a few units past the end at most. Fixed point clamps,
/// because its integer forms ([`q28`]) are bounded only for inputs in range; the floats pass
/// the excursion on, a few ULP that the arc's terms carry as rounding (the recurrence grows a
/// power of `g^2 <= 1 + 4 EPSILON` by at most `255 * 4 EPSILON` relative), and NaN-aware
/// comparisons there cost about 9 Cortex-M4F instructions a clamp, 4 clamps an edge. A
/// non-finite value cannot arise from the finite unit vectors the callers pass, and a caller's
/// final `clamp01` would map one to 0 (`phong_polygon`, the moments).
#[inline(always)]
pub(crate) fn clamp_excursion<T: Real>(v: T, clamp: impl FnOnce(T) -> T) -> T {
    if T::RESOLUTION > T::ZERO {
        clamp(v)
    } else {
        v
    }
}

/// The recurrence `T(k)` of Snyder's appendix G for one arc of a boundary: `T(k)` is the
/// integral from 0 to `x` of `(a cos t + b sin t)^k dt`, `f = a^2 + b^2`, run upward from
/// `k = n mod 2` in steps of 2. Returns `(T(n mod 2) + ... + T(n - 2), T(n))`. One
/// implementation for `[phong_polygon]`'s `J` terms (which sum all of them) and Arvo's
/// moments (which weigh the last apart). With `stop = Some((coef, budget))` it stops after
/// `T(k)` once `coef c^(k+2) <= budget` (`c = sqrt(f)`) and returns `T(n) = 0` (the tail
/// dropped: the moments' early termination); with `None` that bound costs nothing.
///
/// Cost: 3 products, 2 additions and a division per step on the floats, with `k` and `k - 1`
/// as floats (2 more additions with an FPU, 2 conversions in soft float); on fixed point the
/// Q28 form of [`q28`] (4 integer products of three `MULS` each and a table reciprocal per
/// step: about 78 Cortex-M0 instructions a step, against 230 in the type's own saturating
/// arithmetic; measured in the QEMU budget's single-step trace).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn cos_power_sums<T: Real>(
    n: u32,
    x: T,
    cos_x: T,
    sin_x: T,
    a: T,
    b: T,
    f: T,
    stop: Option<(T, T)>,
) -> (T, T) {
    #[cfg(feature = "fixed")]
    if T::RESOLUTION > T::ZERO {
        // Fixed point (decided at compile time): the same recurrence in Q28 integers.
        return q28::cos_power_sums(n, x, cos_x, sin_x, a, b, f, stop);
    }
    let g = clamp_excursion(a * cos_x + b * sin_x, |v| v.clamp(-T::ONE, T::ONE));
    let g2 = g * g;
    let a2 = a * a;
    let h = a * sin_x - b * cos_x;
    let odd = n & 1 == 1;
    // t = T(k); l = G^(k+1) H, l2 = beta alpha^(k+1): ready for k + 2.
    let (mut t, mut l, mut l2, mut k) = if odd {
        (h + b, g2 * h, b * a2, 1)
    } else {
        (x, g * h, b * a, 0)
    };
    // c^(k+2), for the early-termination bound (only when asked for).
    let mut cpow = match stop {
        Some(_) if odd => f * f.sqrt(),
        Some(_) => f,
        None => T::ZERO,
    };
    let mut sum = T::ZERO;
    // With a floating-point unit, `k` and `k - 1` as `T` beside the integer, stepped by 2
    // (exact: integers far below the floats' 2^24): the same values as `mul_u32(k - 1)` and
    // `div_u32(k)` without two integer-to-float conversions a step (3 of the 16 Cortex-M4F
    // instructions of a step; `phong_polygon` 1 943 -> 1 892). In soft float an addition is
    // the dearer library call (`phong_polygon` 82 427 -> 84 772 on the Cortex-M0): the
    // conversions there.
    let mut kf = T::from_u32(k);
    // One step: `T(k)` into the sum, then `T(k + 2)` (or the early termination's return).
    macro_rules! step {
        () => {
            sum += t;
            if let Some((coef, budget)) = stop {
                if coef * cpow <= budget {
                    return (sum, T::ZERO);
                }
                cpow *= f;
            }
            k += 2;
            t = if SOFT_FLOAT {
                (l + l2 + f.mul_u32(k - 1) * t).div_u32(k)
            } else {
                let km1 = kf + T::ONE;
                kf += T::TWO;
                (l + l2 + f * km1 * t) / kf
            };
            l *= g2;
            l2 *= a2;
        };
    }
    // `k` and `n` have the same parity and `k <= n`: `(n - k)/2` steps. With a floating-point
    // unit, two steps an iteration (the same operations in the same order: the same bits),
    // which spares every other step the loop's count, test and branch and the copy of `t`
    // the register allocator made between steps (`phong_polygon`, the bars' quad at m = 15,
    // 28 steps, in a build of that case alone: 1 132 -> 1 098 Cortex-M4F instructions, with a
    // `UnitVec3` 1 097 -> 1 069).
    // Soft float keeps one step an iteration (its steps are library calls: the unrolled code
    // would double for nothing).
    if SOFT_FLOAT {
        while k < n {
            step!();
        }
    } else {
        while n - k >= 4 {
            step!();
            step!();
        }
        if k < n {
            step!();
        }
    }
    (sum, t)
}

/// [`cos_power_sums`] for fixed point: the recurrence in `i32` with 28 fraction bits (every
/// quantity of it lies within +-8, bounds below), six more than `Fixed22`'s 22, so its
/// roundings stay below the type's own. Its factors in [0, 1] (`f`, `g^2`, `a^2` and `1/k`) are
/// unsigned Q32 fractions ([`Q32`]; 1 itself becomes `1 - 2^-32`), and each product is
/// [`mul_q32`]: three 16 x 16-bit `MULS` with the constant factor's halves split once per edge,
/// within one unit of 2^-28 of the high word of the exact product (in (-2, 1] units of the
/// product itself, a quarter of a unit below it on average), no saturation test: the bounds
/// hold. The division by the step's `k` becomes `t = u + (l + l2 - u)/k` with `u = f t` (the
/// same value as `(l + l2 + (k - 1) f t)/k`) and `1/k` from a table ([`recip_q32`], one entry
/// for every `k` up to 256): four products and no division per step. Measured on the
/// Cortex-M0 (QEMU budget, `phong_polygon` quad at m = 16, 28 steps, with a `UnitVec3`): about
/// 78 instructions a step; the call 10 491 -> 10 059 when the products went from the exact
/// high word of four `MULS` to three, then 9 908 when `1/k` came from one table for either
/// parity of `k` (at m = 15, whose even `k` took the trailing zeros of `k` and a shift, 10 431
/// -> 9 550 for both); before, 150 a step with Q28 factors and a full 64-bit product each (the
/// call 15 009 -> 14 320 instructions), and 230 in the type's own saturating arithmetic. Errors
/// against f64 (`tests/fixed.rs`, the Phong polygon's worst): 1.08e-5 -> 1.01e-5 at m = 255,
/// 6.7e-6 -> 6.4e-6 at m = 128 (the exact floor's bias of half a unit a product is gone).
///
/// Bounds (which is why nothing can wrap): the inputs are clamped to their ranges (`a`, `b`,
/// `cos x`, `sin x` to [-1, 1], `f` to [0, 1], `x` to [0, 4]; valid callers pass them so),
/// so `|g| <= 1`, `|h| <= 2`, `|l| <= 2` and `|l2| <= 1` for good (the factors `g^2`, `a^2`
/// are below 1), and by induction `|t| <= max(|t0|, 3) <= 4` (each `t` is a weighted mean
/// of `(l + l2)` and the previous `t`): `l + l2 - u` stays within 7 (`7 2^28 < 2^31`), up to the
/// roundings' drift of at most 4 units of 2^-28 per step. The sum (up to 128 terms of at most
/// 4) is kept in an `i64` and returned rounded to 22 fraction bits, saturating as the type's
/// own additions would.
#[cfg(feature = "fixed")]
mod q28 {
    use crate::real::fixed22::recip_q32;
    use crate::wide::{mul_q32, mul_shr, Q32};
    use crate::Real;

    const FRAC: u32 = 28;
    const ONE: i32 = 1 << FRAC;
    /// Whether the exact products below go by 16-bit halves (ARMv6-M, whose 64-bit product is
    /// a library call) or by the 64-bit product (elsewhere: one or two instructions, as on
    /// RV32IMC's `MULH`); the same bits either way.
    const HALVES: bool = cfg!(all(target_arch = "arm", not(target_has_atomic = "32")));

    #[inline(always)]
    fn mul(a: i32, b: i32) -> i32 {
        mul_shr(a, b, FRAC)
    }

    /// `v^2` (Q28, `|v| <= 1`) as a Q32 fraction, exactly rounded down (1 becomes
    /// `1 - 2^-32`), from the 64-bit product: the reference of the tests for
    /// [`square_q32_by_halves`] and [`square22_q32`], which the recurrence takes.
    #[cfg(test)]
    fn square_q32(v: i32) -> Q32 {
        let sq = crate::wide::mul_32(v, v) >> (2 * FRAC - 32);
        Q32::new(sq.clamp(0, i64::from(u32::MAX)) as u32)
    }

    /// [`square_q32`] from three 16 x 16-bit `MULS` in `u32` (the same bits): with `|v| = vh
    /// 2^16 + vl < 2^28` (`vh < 2^12`), `v^2 / 2^24 = vh^2 2^8 + (vh vl 2^17 + vl^2) / 2^24`,
    /// whose floor is `vh^2 2^8 + floor((vh vl + floor(vl^2 / 2^17)) / 2^7)` (nested floors of
    /// nonnegative terms; `vh vl < 2^28`), below `2^32`.
    #[inline(always)]
    fn square_q32_by_halves(v: i32) -> Q32 {
        let u = v.unsigned_abs();
        if u >= 1 << FRAC {
            return Q32::new(u32::MAX);
        }
        let (vh, vl) = (u >> 16, u & 0xFFFF);
        Q32::new(((vh * vh) << 8) + ((vh * vl + ((vl * vl) >> 17)) >> 7))
    }

    /// `v^2` (Q28) as a Q32 fraction: [`square_q32_by_halves`] on ARMv6-M, the 64-bit product
    /// elsewhere ([`HALVES`]); the same bits.
    #[inline(always)]
    fn square28_q32(v: i32) -> Q32 {
        let u = v.unsigned_abs();
        if HALVES || u >= 1 << FRAC {
            square_q32_by_halves(v)
        } else {
            Q32::new(((u64::from(u) * u64::from(u)) >> 24) as u32)
        }
    }

    /// `x y` in Q28 of `x`, `y` in Q22 with `|x|, |y| <= 2^22` (the inputs' bits): exactly
    /// `floor(x y / 2^16)`, the same as [`mul`] of the two shifted to Q28, from four 16 x 16-bit
    /// `MULS` without a carry word. With `x = xh 2^16 + xl` (`|xh| <= 2^6`, `0 <= xl < 2^16`)
    /// and `y` alike, `x y / 2^16 = xh yh 2^16 + xh yl + xl yh + xl yl / 2^16`, and only the
    /// last term has a fraction: the sum is at most `2^28 + 2^23 + 2^16` in magnitude.
    #[inline(always)]
    fn mul22_by_halves(x: i32, y: i32) -> i32 {
        let (xh, xl) = (x >> 16, x & 0xFFFF);
        let (yh, yl) = (y >> 16, y & 0xFFFF);
        ((xh * yh) << 16) + xh * yl + xl * yh + (((xl as u32) * (yl as u32)) >> 16) as i32
    }

    /// `v^2` of `v` in Q22 (`|v| <= 2^22`) as a Q32 fraction: exactly [`square_q32`] of `v`
    /// in Q28, `floor(v^2 / 2^12)` (1 becomes `1 - 2^-32`), in `u32` from three `MULS`: with
    /// `|v| = vh 2^16 + vl < 2^22` (`vh <= 63`), `v^2 / 2^12 = vh^2 2^20 + vh vl 2^5 + vl^2 /
    /// 2^12`, below `2^32`.
    #[inline(always)]
    fn square22_q32_by_halves(v: i32) -> Q32 {
        let u = v.unsigned_abs();
        if u >= 1 << 22 {
            return Q32::new(u32::MAX);
        }
        let (vh, vl) = (u >> 16, u & 0xFFFF);
        Q32::new(((vh * vh) << 20) + ((vh * vl) << 5) + ((vl * vl) >> 12))
    }

    /// [`mul22_by_halves`] on ARMv6-M, the 64-bit product elsewhere ([`HALVES`]); the same
    /// bits.
    #[inline(always)]
    fn mul22(x: i32, y: i32) -> i32 {
        if HALVES {
            mul22_by_halves(x, y)
        } else {
            ((i64::from(x) * i64::from(y)) >> 16) as i32
        }
    }

    /// [`square22_q32_by_halves`] on ARMv6-M, the 64-bit product elsewhere ([`HALVES`]); the
    /// same bits.
    #[inline(always)]
    fn square22_q32(v: i32) -> Q32 {
        let u = v.unsigned_abs();
        if HALVES || u >= 1 << 22 {
            square22_q32_by_halves(v)
        } else {
            Q32::new(((u64::from(u) * u64::from(u)) >> 12) as u32)
        }
    }

    /// See the module docs; the same arguments and results as [`super::cos_power_sums`].
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub(super) fn cos_power_sums<T: Real>(
        n: u32,
        x: T,
        cos_x: T,
        sin_x: T,
        a: T,
        b: T,
        f: T,
        stop: Option<(T, T)>,
    ) -> (T, T) {
        // The unit inputs in Q22 (Fixed22's bits, exactly), for the products of two of them in
        // Q28 by `mul22` (the same bits as `mul` of the two in Q28; the call 9 908 -> 9 797
        // Cortex-M0 instructions); `b` in Q28 too.
        let unit = |v: T| v.clamp(-T::ONE, T::ONE).to_fixed_i32(22);
        let (a22, b22, c, s) = (unit(a), unit(b), unit(cos_x), unit(sin_x));
        let bi = b22 << (FRAC - 22);
        // f in [0, 1] as a Q32 fraction (its 22 fraction bits exactly).
        let fq = Q32::new(
            (i64::from(f.clamp01().to_fixed_i32(FRAC)) << (32 - FRAC)).min(i64::from(u32::MAX))
                as u32,
        );
        let xq = x.clamp(T::ZERO, T::TWO + T::TWO).to_fixed_i32(FRAC);
        let g = (mul22(a22, c) + mul22(b22, s)).clamp(-ONE, ONE);
        // (`g` in Q28 proper: its square from three `MULS` in `u32`, the bits of the 64-bit
        // product's; the call 9 365 -> 9 265 Cortex-M0 instructions.)
        let (g2, a2) = (square28_q32(g), square22_q32(a22));
        let h = mul22(a22, s) - mul22(b22, c);
        let odd = n & 1 == 1;
        // t = T(k); l = G^(k+1) H, l2 = beta alpha^(k+1): ready for k + 2.
        let (mut t, mut l, mut l2, mut k) = if odd {
            (h + bi, mul_q32(h, g2), mul_q32(bi, a2), 1)
        } else {
            (xq, mul(g, h), mul22(b22, a22), 0)
        };
        let f = f.clamp01();
        let mut cpow = match stop {
            Some(_) if odd => f * f.sqrt(),
            Some(_) => f,
            None => T::ZERO,
        };
        let mut sum = 0i64;
        let out = |v: i64| {
            T::from_fixed_i32(
                ((v + 32) >> 6).clamp(i32::MIN.into(), i32::MAX.into()) as i32,
                22,
            )
        };
        // An arc that starts or ends on the horizon (the Phong walk's crossings: `a = r.a` is
        // 0 at a crossing up, `G = r.b` a few units of rounding at a crossing down): a factor
        // `a^2` or `g^2` of 0, whose sequence is 1 after its first step (`mul_q32` of
        // anything by 0 is its rounding unit) and needs no product. The loop with one
        // sequence: the same bits, 64 instead of 77 Cortex-M0 instructions a step. Measured
        // on the budget's `phong_polygon` quad at m = 15 with a `UnitVec3`: the clipped calls
        // 8 106 -> 7 978 (the median), the unclipped ones 8 660 -> 8 743 (the test and the
        // second loop cost each edge about 21; out of line, the loop cost the clipped calls
        // their saving); the board demo's shader (`demo_shade`, 33 calls) 414 181 -> 413 813.
        if !(stop.is_none() && (a2.is_zero() || g2.is_zero())) {
            while k < n {
                sum += i64::from(t);
                if let Some((coef, budget)) = stop {
                    if coef * cpow <= budget {
                        return (out(sum), T::ZERO);
                    }
                    cpow *= f;
                }
                k += 2;
                // 1/k from the table, for either parity.
                let r = recip_q32(k);
                let u = mul_q32(t, fq);
                t = u + mul_q32(l + l2 - u, Q32::new(r));
                l = mul_q32(l, g2);
                l2 = mul_q32(l2, a2);
            }
        } else {
            // `s` the sequence that lives (by `q`), `c` the other: its first value, then 1.
            let (mut s, mut c, q) = if a2.is_zero() {
                (l, l2, g2)
            } else {
                (l2, l, a2)
            };
            while k < n {
                sum += i64::from(t);
                k += 2;
                let r = recip_q32(k);
                let u = mul_q32(t, fq);
                t = u + mul_q32(s + c - u, Q32::new(r));
                s = mul_q32(s, q);
                c = 1;
            }
        }
        (out(sum), T::from_fixed_i32(t, FRAC))
    }

    #[cfg(test)]
    mod tests {
        extern crate std;
        use super::*;

        /// `mul22`, `square22_q32` and `square_q32_by_halves` against the Q28 forms they
        /// replace, on every power of two and its neighbours, the ends of the range and random
        /// pairs.
        #[test]
        fn q22_products_equal_the_q28_ones() {
            let mut vals: std::vec::Vec<i32> = std::vec::Vec::new();
            for e in 0..=22 {
                for d in [-1i32, 0, 1] {
                    let v = (1i32 << e) + d;
                    if v.unsigned_abs() <= 1 << 22 {
                        vals.extend([v, -v]);
                    }
                }
            }
            let mut state = 0x9E37_79B9u32;
            for _ in 0..200_000 {
                state ^= state << 13;
                state ^= state >> 17;
                state ^= state << 5;
                let v = (state as i32) >> (9 + state % 23);
                vals.push(v.clamp(-(1 << 22), 1 << 22));
            }
            for (i, &x) in vals.iter().enumerate() {
                let y = vals[(i * 7919 + 13) % vals.len()];
                assert_eq!(mul22_by_halves(x, y), mul(x << 6, y << 6), "{x} * {y}");
                assert_eq!(mul22(x, y), mul(x << 6, y << 6), "{x} * {y}");
                assert_eq!(mul22_by_halves(x, x), mul(x << 6, x << 6), "{x}^2");
                assert_eq!(
                    square22_q32_by_halves(x),
                    square_q32(x << 6),
                    "{x}^2 as Q32"
                );
                assert_eq!(square22_q32(x), square_q32(x << 6), "{x}^2 as Q32");
                // Q28 values of every magnitude up to 1 (and beyond: clamped).
                let v = x.wrapping_mul(64).wrapping_add(y & 63);
                assert_eq!(square_q32_by_halves(v), square_q32(v), "{v}^2 as Q32 (Q28)");
                assert_eq!(square28_q32(v), square_q32(v), "{v}^2 as Q32 (Q28)");
            }
        }
    }
}
