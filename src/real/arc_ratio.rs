//! The arc ratio `theta / sin(theta)` from `c = cos(theta)`, for `c` in [0, 1]:
//! [`Real::arc_ratio`](super::Real::arc_ratio), the hot path of the polygon edge terms.
//!
//! # Why
//!
//! A polygon edge seen from `p` contributes `theta (G.k)/|G|` to Lambert's formula, with
//! `theta` the angle the edge subtends and `G = ua x ub`. Written with the endpoints' lengths,
//! `|G| = |ua| |ub| sin(theta)` and `c = ua.ub/(|ua| |ub|)`, the term is
//! `R(c) (G.k)/(|ua| |ub|)` with `R(c) = acos(c)/sqrt(1 - c^2)`: no arc tangent, no square
//! root of `G.G`, one reciprocal square root of `|ua|^2 |ub|^2`. `R` is analytic on [0, 1]
//! (`R(1 - x) = 1 + x/3 + 2x^2/15 + ...`, its nearest singularity is at `c = -1`, where
//! `sin(theta)` vanishes with `theta = pi`), so a short polynomial holds it to the f32 target;
//! edges subtending more than a right angle (`c < 0`) keep the arc-tangent form.
//!
//! # Method (f32)
//!
//! `R(1 - x) = P(x)` on `x` in [0, 1] with `P` of degree 9: the polynomial minimizing the
//! largest *relative* error (1.15e-8), fitted by Lawson's iteration on 1500 Chebyshev nodes,
//! its coefficients rounded to f32. `x = 1 - c` is exact for `c >= 1/2` (Sterbenz), where the
//! short edges of a distant light have `x` near 0 and `P(x)` near 1, so its rounding is an ULP
//! or two. Horner's scheme: 9 multiply-adds and 9 literal loads.
//!
//! # Accuracy (measured: the tests below, every 8th f32 in [0, 1] against f64)
//!
//! At most 1.58 ULP of the result (`f32::EPSILON` units: 1.2e-7 relative, near `c = 0`, where
//! `x = 1 - c` is rounded), against 1.65 ULP for the arc tangent it replaces.
//!
//! # Cost
//!
//! On the Cortex-M4F 19 instructions (9 literal loads, 9 multiply-adds, `1 - c`), inlined
//! into the edge term: with it, `polygon_lambert` on a quad went from 920 to 696 instructions
//! (see [`PolygonLight::lambert`](crate::PolygonLight::lambert)). The other backends answer
//! `None` (f64 keeps its reference arc tangent; `Fast32` and `Fixed22` theirs; f32 on
//! soft-float targets, see [`arc_ratio_f32`]), so the edge term compiles to the arc-tangent
//! form alone there.

/// `P`'s coefficients in `x = 1 - c`, constant term first (see the module docs).
const P: [f32; 10] = [
    1.0,
    0.333_335_58,
    0.133_260_89,
    0.058_037_583,
    0.019_849_317,
    0.030_983_854,
    -0.035_147_794,
    0.052_575_62,
    -0.033_455_75,
    0.011_357_001,
];

/// `true` on soft-float targets (ARM without `eabihf`, RISC-V without F), where every float
/// operation is a library call.
pub(crate) const SOFT_FLOAT: bool = cfg!(any(
    all(target_arch = "arm", not(target_abi = "eabihf")),
    all(
        any(target_arch = "riscv32", target_arch = "riscv64"),
        not(target_feature = "f")
    )
));

/// `<f32 as Real>::arc_ratio`: [`arc_ratio_poly`] where the target has a floating-point unit
/// (or is not a soft-float microcontroller), `None` on soft-float targets ([`SOFT_FLOAT`]),
/// where the arc-tangent form costs fewer library calls (measured on the Cortex-M0:
/// `polygon_lambert` in f32 30 833 instructions with the arc tangent, 34 026 with the
/// polynomial), as for the arc tangent itself (`f32_math`).
#[inline(always)]
pub(crate) fn arc_ratio_f32(c: f32) -> Option<f32> {
    if SOFT_FLOAT {
        None
    } else {
        arc_ratio_poly(c)
    }
}

/// `acos(c)/sqrt(1 - c^2)` for `c` in [0, 1] (1.58 ULP; see the module docs). For `c` slightly
/// outside [0, 1] (rounding) the polynomial continues smoothly; it is finite for every finite
/// `c`, and the caller sends `c < 0` and non-finite `c` elsewhere.
#[inline(always)]
pub(crate) fn arc_ratio_poly(c: f32) -> Option<f32> {
    let x = 1.0 - c;
    let mut q = P[9];
    q = q * x + P[8];
    q = q * x + P[7];
    q = q * x + P[6];
    q = q * x + P[5];
    q = q * x + P[4];
    q = q * x + P[3];
    q = q * x + P[2];
    q = q * x + P[1];
    q = q * x + P[0];
    Some(q)
}

/// The backends without a cheap arc ratio: `None`, so the caller takes the arc-tangent form.
#[inline(always)]
pub(crate) fn no_arc_ratio<T>(_c: T) -> Option<T> {
    None
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::arc_ratio_poly as arc_ratio_f32;
    use std::println;

    /// The exact ratio in f64 (the arc tangent form, accurate near 1 where `acos` is not).
    fn reference(c: f64) -> f64 {
        let s = ((1.0 - c) * (1.0 + c)).sqrt();
        if s == 0.0 {
            1.0
        } else {
            libm::atan2(s, c) / s
        }
    }

    #[test]
    fn within_its_bound_on_every_eighth_f32_of_the_unit_interval() {
        let (mut worst, mut at) = (0.0f64, 0.0f32);
        let one = 1.0f32.to_bits();
        let mut b = 0u32;
        while b <= one {
            let c = f32::from_bits(b);
            let got = arc_ratio_f32(c).unwrap_or(f32::NAN) as f64;
            let want = reference(c as f64);
            // ULPs of the result: R is in [1, pi/2], so one ULP is 2^-23.
            let ulp = (got - want).abs() / f64::from(f32::EPSILON);
            if !(ulp <= worst) {
                worst = ulp;
                at = c;
            }
            b += if b == one { 1 } else { 8.min(one - b) };
        }
        println!("[arc_ratio] f32 max error {worst:.3} ULP at c = {at:e}");
        assert!(worst <= 1.6, "{worst} ULP at c = {at:e}");
    }

    #[test]
    fn exact_at_the_ends() {
        assert_eq!(arc_ratio_f32(1.0), Some(1.0));
        let r0 = arc_ratio_f32(0.0).unwrap_or(0.0);
        assert!((f64::from(r0) - core::f64::consts::FRAC_PI_2).abs() <= 2.0 * 1.2e-7);
    }
}
