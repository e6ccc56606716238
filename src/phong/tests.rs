//! Tests of the early 0 of `phong_cap_from_angle` (fixed point).

use super::*;
use crate::real::sealed::Sealed as _;
use crate::Fixed22;

/// The cap's early 0 (`phong_cap_from_angle`) against f64's term at the same angles: on
/// caps of every size with `r` just outside them, around the threshold angle, wherever
/// `Fixed22` takes the early 0 the exact term is below `2^-24`; and the early 0 is taken
/// often enough that the test is not vacuous.
#[test]
fn the_caps_early_zero_is_below_2_pow_minus_24() {
    let mut rnd = crate::test_rng::uniform(0x9E37_79B9);
    let (mut taken, mut worst) = (0u32, 0.0f64);
    for i in 0..200_000u32 {
        let m = [11, 12, 16, 20, 33, 48, 64, 128, 200, 255][i as usize % 10];
        let sigma = 0.001 + rnd() * 1.5;
        let t = libm::acos(libm::pow(2.0, -24.0 / (f64::from(m) + 1.0)));
        let w = (sigma + t * (0.9 + rnd() * 0.2)).min(core::f64::consts::PI);
        let f = |v: f64| Fixed22::from_f64(v);
        let lobe = PhongLobe::<Fixed22>::new(m).unwrap_or_else(|_| unreachable!());
        let (c, s, cs, ss) = (f(w.cos()), f(w.sin()), f(sigma.cos()), f(sigma.sin()));
        let early =
            c < cs && Fixed22::mul_small(c, cs) + Fixed22::mul_small(s, ss) < lobe.negligible_cos.0;
        let fixed = phong_cap_from_angle(&lobe, c, s, cs, ss);
        if !early {
            continue;
        }
        assert_eq!(fixed, Fixed22::ZERO, "{i}");
        taken += 1;
        // f64 at the angles whose roundings Fixed22 was given (the roundings themselves
        // are not a consistent pair: c^2 + s^2 is 1 only to 2^-21, which the formula's
        // cancelling terms would turn into errors of that order).
        let lobe64 = PhongLobe::<f64>::new(m).unwrap_or_else(|_| unreachable!());
        let exact = phong_cap_from_angle(&lobe64, w.cos(), w.sin(), sigma.cos(), sigma.sin());
        worst = worst.max(exact);
        assert!(exact < 1.0 / 16_777_216.0, "{i}: m = {m}, {exact:e}");
    }
    // Measured: 67 789 of 200 000 taken, the largest exact term 4.9e-9.
    assert!(taken > 20_000 && worst > 0.0, "{taken} {worst:e}");
}
