//! Tests of `line/mod.rs`.

use super::*;
extern crate std;

#[test]
fn helpers() {
    for x in [1e-20f64, 1e-8, 0.3, 1.0, 7.0, 1e7, 1e9, 1e200] {
        let want = libm::asinh(x);
        assert!((asinh_pos(x) - want).abs() <= 4e-16 * want, "asinh {x}");
    }
    for x in [-0.9f64, -1e-9, 1e-18, 1e-5, 0.5, 3.0, 1e300] {
        let want = libm::log1p(x);
        assert!((ln_1p(x) - want).abs() <= 4e-16 * want.abs(), "ln1p {x}");
    }
    for y in [0.0f64, 1e-4, 0.1, 1.0, 2.0, 3.1] {
        let want = if y < 1e-3 {
            1.0 / 6.0 - y * y / 120.0
        } else {
            (y - libm::sin(y)) / (y * y * y)
        };
        assert!((y_minus_sin_over_cube(y) - want).abs() <= 1e-13, "Y({y})");
    }
    assert_eq!(hypot(0.0f64, 0.0), 0.0);
    assert!((hypot(3e-300f64, 4e-300) - 5e-300).abs() < 1e-314);
}

#[test]
fn decay() {
    for k in 0..4 {
        assert_eq!(Decay::new(k).unwrap().k(), k);
    }
    assert_eq!(Decay::new(4), Err(Error::DecayOutOfRange));
}
