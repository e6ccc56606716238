//! The tests of [`Fixed22`](super::super::Fixed22)'s SH9 fast path (`sh9_q15`): its error
//! against f64 within the bound its packing checked, its sums without wrapping at the
//! packing's limit, and its refusals.

extern crate std;

use super::super::sh9_q15::{error_bound, irradiance, pack};
use super::super::*;
use super::random_unit as unit;
use crate::Rgb;

/// The irradiance polynomial at `n` in f64, from the Q22 values.
fn exact(k: &[i32; 9], n: [Fixed22; 3]) -> f64 {
    let [x, y, z] = n.map(|c| c.to_f64());
    let m = [1.0, x, y, z, x * y, y * z, x * z, z * z, x * x - y * y];
    (0..9).map(|i| f64::from(k[i]) / 4_194_304.0 * m[i]).sum()
}

/// The channels of `k` as raw bits.
fn channels(k: &[Rgb<Fixed22>; 9]) -> [[i32; 9]; 3] {
    [
        k.map(|c| c.r.to_bits()),
        k.map(|c| c.g.to_bits()),
        k.map(|c| c.b.to_bits()),
    ]
}

/// The exponent `s` of a packing with shift `sh`.
fn exponent(sh: u8) -> u32 {
    u32::from(sh) + 7
}

/// Random environments of every scale at which the path accepts them (coefficients from
/// `2^-12` to about 2, mixed signs), on random unit normals and the signed axes and
/// diagonals: every channel within the bound `pack` checked (`error_bound`, at most `2^-11`)
/// of the f64 value of the same Q22 coefficients and normal; and each accepted packing's
/// exponent the largest that keeps the sums within their limit.
#[test]
fn fast_sh9_is_within_the_bound_it_checked() {
    let mut next = crate::test_rng::xorshift32(0x5_4915);
    let one = 1 << 22;
    let mut fixed_dirs = std::vec::Vec::new();
    for axis in 0..3 {
        for sign in [one, -one] {
            let mut v = [0; 3];
            v[axis] = sign;
            fixed_dirs.push(v.map(Fixed22::from_bits));
        }
    }
    for sx in [1, -1] {
        for sy in [1, -1] {
            for sz in [1, -1] {
                let v = [sx, sy, sz].map(|s| Fixed22::from_bits(s * one));
                fixed_dirs.extend(Fixed22::unit3(v));
            }
        }
    }
    let (mut accepted, mut worst) = (0, 0.0f64);
    for case in 0..4000 {
        let shift = 8 + next() % 14;
        let k: [Rgb<Fixed22>; 9] = core::array::from_fn(|_| {
            let mut c = || Fixed22::from_bits((next() as i32) >> shift);
            Rgb::new(c(), c(), c())
        });
        let original = channels(&k);
        let mut packed = k;
        let Some(sh) = pack(&mut packed) else {
            assert_eq!(packed, k, "a refused packing leaves k");
            continue;
        };
        accepted += 1;
        let s = exponent(sh);
        for ch in original {
            let bound = error_bound(ch, s) as f64 / (1u64 << 38) as f64;
            assert!(bound <= 1.0 / 2048.0);
        }
        for i in 0..60 {
            let n = if i < fixed_dirs.len() {
                fixed_dirs[i]
            } else {
                unit(&mut next)
            };
            let got = irradiance(&packed, sh, n);
            let got = [got.r, got.g, got.b].map(|c| c.to_f64());
            for (c, ch) in original.iter().enumerate() {
                let bound = error_bound(*ch, s) as f64 / (1u64 << 38) as f64;
                let err = (got[c] - exact(ch, n)).abs();
                worst = worst.max(err);
                assert!(
                    err <= bound,
                    "case {case} channel {c}: {err:e} > {bound:e} (k {ch:?}, n {n:?})"
                );
            }
        }
    }
    std::println!("sh9_q15: {accepted} of 4000 environments accepted, worst error {worst:e}");
    assert!(accepted > 1000);
}

/// The sums cannot wrap: at the packing's limit (every mantissa's weight summing to the
/// limit, the signs those of the monomials at an extreme normal), the `i32` result equals
/// the same sum in `i64`, on the signed axes and diagonals and random normals.
#[test]
fn fast_sh9_sums_do_not_wrap_at_the_limit() {
    let mut next = crate::test_rng::xorshift32(0x0051_0015);
    for case in 0..2000 {
        let n = unit(&mut next);
        let q = |c: Fixed22| (c.to_bits() + 64) >> 7;
        let (x, y, z) = (q(n[0]), q(n[1]), q(n[2]));
        let r = |p: i32| (p + (1 << 14)) >> 15;
        let m = [
            1 << 15,
            x,
            y,
            z,
            r(x * y),
            r(y * z),
            r(x * z),
            r(z * z),
            r(x * x - y * y),
        ];
        // Mantissas of the largest magnitudes the limit allows, signed as the monomials.
        let weight = [2, 2, 2, 2, 1, 1, 1, 2, 2];
        let limit = 130_560;
        let sign = [1, -1][case % 2];
        let mut k = [0i32; 9];
        let mut left = limit;
        for i in 0..9 {
            let share = if i == 8 { left } else { left / (9 - i as i32) };
            let mag = share / weight[i];
            left -= mag * weight[i];
            k[i] = sign * mag * if m[i] < 0 { -1 } else { 1 };
        }
        let sh = 6 + (next() % 18) as u8;
        let mut packed = [Rgb::new(Fixed22::ZERO, Fixed22::ZERO, Fixed22::ZERO); 9];
        for i in 0..9 {
            let v = if i == 0 {
                (k[0] << 15) + (1 << (sh - 1))
            } else {
                k[i]
            };
            packed[i] = Rgb::new(Fixed22::from_bits(v), Fixed22::ZERO, Fixed22::ZERO);
        }
        let wide: i64 = i64::from(k[0]) * (1 << 15)
            + (1i64 << (sh - 1))
            + (1..9)
                .map(|i| i64::from(k[i]) * i64::from(m[i]))
                .sum::<i64>();
        assert!(wide.abs() < 1 << 31, "the limit's sum fits: {wide}");
        let got = irradiance(&packed, sh, n).r.to_bits();
        assert_eq!(i64::from(got), wide >> sh, "k {k:?} n {n:?}");
    }
}

/// Environments the path refuses go the exact way: coefficients too large for the bound
/// (`pack` answers `None` and `prepare` equals `prepare_exact`), and the Grace Cathedral
/// environment (the QEMU budget's) is accepted.
#[test]
fn fast_sh9_refuses_what_its_bound_does_not_allow() {
    use crate::{Environment, Sh9, Vec3};
    let big = core::array::from_fn(|i| {
        let c = Fixed22::from_bits([3 << 22, -(2 << 22), 1 << 22][i % 3]);
        Rgb::new(c, c, c)
    });
    let mut k = big;
    assert_eq!(pack(&mut k), None);
    assert_eq!(k, big);
    let grace = Sh9::<Fixed22>::environment(Environment::GraceCathedral);
    let (fast, exact) = (grace.prepare(), grace.prepare_exact());
    assert_ne!(fast, exact, "Grace Cathedral takes the fast path");
    let bright = Sh9::<Fixed22>::new(core::array::from_fn(|_| Rgb::splat(Fixed22::from_f64(3.0))))
        .unwrap_or(grace);
    assert_eq!(bright.prepare(), bright.prepare_exact());
    let f = Fixed22::from_f64;
    let n = Vec3::new(f(0.3), f(-0.5), f(0.8));
    let (a, b) = (
        bright.prepare().irradiance(n),
        bright.prepare_exact().irradiance(n),
    );
    assert_eq!(a, b);
}
