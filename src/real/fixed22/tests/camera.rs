//! The camera's rounded kernels (`kernels::mul_bits_round`, `kernels::dot3_unit_round`)
//! against the exact 64-bit products.

extern crate std;

use super::super::kernels::{dot3_unit_round, mul_bits_round};
use super::super::*;

/// `mul_bits_round` is `floor(a b / 2^22 + 1/2)` saturated to the `i32` range: the edges of
/// the 16-bit halves and of the range against each other, and 1 000 000 random pairs of
/// every magnitude.
#[test]
fn rounded_products_are_exact() {
    let exact = |a: i32, b: i32| {
        let p = (i64::from(a) * i64::from(b) + (1 << 21)) >> 22;
        p.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
    };
    let mut edges = std::vec::Vec::new();
    for e in [0, 1, 0xFFFF, 0x1_0000, 1 << 21, 1 << 22, 1 << 30, i32::MAX] {
        for d in [-1, 0, 1] {
            let v = e.saturating_add(d);
            edges.push(v);
            edges.push(v.saturating_neg());
        }
    }
    edges.push(i32::MIN);
    for &a in &edges {
        for &b in &edges {
            assert_eq!(mul_bits_round(a, b), exact(a, b), "{a} {b}");
        }
    }
    let mut next = crate::test_rng::xorshift32(0xCA3E_0001);
    let mut factor = || (next() as i32) >> (next() % 31);
    for _ in 0..1_000_000 {
        let (a, b) = (factor(), factor());
        assert_eq!(mul_bits_round(a, b), exact(a, b), "{a} {b}");
    }
}

/// `dot3_unit_round` of an offset (components below 16) and a unit vector (components at
/// most `1 + 2^-16`) is within `(-7/8, 1/2]` of a unit of the exact dot product: the
/// offsets' extreme components against the signed axes and the longest components a
/// normalization leaves, and 1 000 000 random offsets of every magnitude against unit
/// vectors from `unit3` of random vectors. The worst errors seen are printed.
#[test]
fn rounded_unit_dot_products_are_within_seven_eighths() {
    let (mut low, mut high) = (0i64, 0i64);
    let mut check = |a: [i32; 3], u: [i32; 3]| {
        let e: i64 = (0..3).map(|k| i64::from(a[k]) * i64::from(u[k])).sum();
        let d = (i64::from(dot3_unit_round(a, u)) << 22) - e;
        assert!(d > -(7 << 19) && d <= 1 << 21, "{a:?} {u:?}: {d}");
        low = low.min(d);
        high = high.max(d);
    };
    let top = (1 << 26) - 1;
    let ends = [-top, -top + 1, -(1 << 16), -1, 0, 1, 0xFFFF, 1 << 16, top];
    let longest = [1 << 22, (1 << 22) + 64, -(1 << 22), -(1 << 22) - 64];
    for &x in &ends {
        for &y in &ends {
            for &z in &ends {
                for &w in &longest {
                    check([x, y, z], [w, 0, 0]);
                    check([x, y, z], [0, w, 0]);
                    check([x, y, z], [0, 0, w]);
                }
                let s = 2_421_565; // 2^22 / sqrt 3, rounded down
                check([x, y, z], [s, -s, s]);
            }
        }
    }
    let mut next = crate::test_rng::xorshift32(0xCA3E_0002);
    for _ in 0..1_000_000 {
        let shift = next() % 31;
        let v = [0, 1, 2].map(|_| Fixed22::from_bits((next() as i32) >> shift));
        let Some(u) = Fixed22::unit3(v) else {
            continue;
        };
        let shift = 5 + next() % 27;
        let a = [0, 1, 2].map(|_| ((next() as i32) >> shift).max(-top));
        check(a, u.map(Fixed22::to_bits));
    }
    std::println!(
        "[dot3_unit_round] error within [{:.3}, {:.3}] units of 2^-22",
        low as f64 / 4_194_304.0,
        high as f64 / 4_194_304.0
    );
}
