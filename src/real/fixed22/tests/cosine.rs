//! The tests of [`Fixed22`](super::super::Fixed22)'s Lambert-type cosine through Q15
//! (`kernels::cos_unit_q15`, the sealed `cos_unit`, `cos_axis` and `mix_by_cos`) against
//! f64 and the 64-bit products.

extern crate std;

use super::super::*;

/// The Lambert-type cosine through Q15 (`kernels::cos_unit_q15`, the sealed `cos_unit`)
/// against the exact f64 dot product of the same Q22 inputs: within its documented budget
/// `2^-16 (|a|_1 + |b|_1) + 2^-23` on 1 000 000 random pairs of unit vectors (from `unit3`
/// of random vectors of every magnitude, as every `UnitVec3` is made), their negations, and
/// every pair of signed axes; the axes' cosines (0 and +-1) exactly.
#[test]
fn cos_unit_q15_is_within_its_error_budget() {
    use super::kernels::cos_unit_q15;
    let check = |a: [i32; 3], b: [i32; 3]| {
        let got = f64::from(cos_unit_q15(a, b)) / f64::from(1 << 22);
        let (fa, fb) = (
            a.map(|x| f64::from(x) / 4_194_304.0),
            b.map(|x| f64::from(x) / 4_194_304.0),
        );
        let exact = fa[0] * fb[0] + fa[1] * fb[1] + fa[2] * fb[2];
        let l1 = |v: [f64; 3]| v[0].abs() + v[1].abs() + v[2].abs();
        let budget = (l1(fa) + l1(fb)) / 65_536.0 + 1.0 / 8_388_608.0;
        let err = (got - exact).abs();
        assert!(
            err <= budget,
            "{a:?} . {b:?}: {got} against {exact}, off by {err:e} > {budget:e}"
        );
        err
    };
    let one = 1i32 << 22;
    let axes = [
        [one, 0, 0],
        [0, one, 0],
        [0, 0, one],
        [-one, 0, 0],
        [0, -one, 0],
        [0, 0, -one],
    ];
    for a in axes {
        for b in axes {
            let want = a[0] * (b[0] >> 22) + a[1] * (b[1] >> 22) + a[2] * (b[2] >> 22);
            assert_eq!(cos_unit_q15(a, b), want, "{a:?} . {b:?}");
        }
    }
    let mut next = crate::test_rng::xorshift32(0x0C05_1AB3);
    let mut unit = || loop {
        let shift = next() % 31;
        let v = [0, 1, 2].map(|_| Fixed22::from_bits((next() as i32) >> shift));
        if let Some(u) = Fixed22::unit3(v) {
            return u.map(Fixed22::to_bits);
        }
    };
    let mut worst = 0.0f64;
    for _ in 0..1_000_000 {
        let (a, b) = (unit(), unit());
        worst = worst.max(check(a, b));
        worst = worst.max(check(a.map(|x| -x), b));
    }
    std::println!("cos_unit_q15 worst error {worst:e}");
}

/// `kernels::mul_q15` is the exact `floor(h c / 2^15)` of the 64-bit product for every `h`
/// but `i32::MIN` and every Q15 factor in `[-2^15, 2^15]`: the edges of both and 1 000 000
/// random pairs. And `sky_ground`'s `mid + half c` (the sealed `mix_by_cos`, for `mid = s +
/// g`, `half = s - g`) against `mid` plus `half` times the exact cosine of the same inputs,
/// within the products' budget `(5.3e-5 + 2^-16) |half| + 2^-22` (the cosine's and its
/// rounding to Q15, the product's floor), on 1 000 000 random unit pairs and colours of
/// every magnitude.
#[cfg(feature = "hemisphere")]
#[test]
fn cosine_products_are_within_their_budget() {
    use super::kernels::mul_q15;
    use crate::real::sealed::Sealed;
    let exact = |h: i32, c: i32| ((i64::from(h) * i64::from(c)) >> 15) as i32;
    let hs = [
        i32::MIN + 1,
        -(1 << 30),
        -65_537,
        -65_536,
        -1,
        0,
        1,
        65_535,
        65_536,
        i32::MAX,
    ];
    let cs = [-(1 << 15), -(1 << 15) + 1, -1, 0, 1, (1 << 15) - 1, 1 << 15];
    for &h in &hs {
        for &c in &cs {
            assert_eq!(mul_q15(h, c), exact(h, c), "{h} {c}");
        }
    }
    let mut next = crate::test_rng::xorshift32(0x05C0_5EED);
    for _ in 0..1_000_000 {
        let h = (next() as i32) >> (next() % 31);
        let c = ((next() % ((1 << 16) + 1)) as i32) - (1 << 15);
        if h != i32::MIN {
            assert_eq!(mul_q15(h, c), exact(h, c), "{h} {c}");
        }
    }
    let mut unit = || loop {
        let shift = next() % 31;
        let v = [0, 1, 2].map(|_| Fixed22::from_bits((next() as i32) >> shift));
        if let Some(u) = Fixed22::unit3(v) {
            break u;
        }
    };
    let mut rng = crate::test_rng::xorshift32(0x00A1_1CE5);
    // A colour's half (`x/2` rounded down, as `SkyGround::new`'s `scale(HALF)`).
    let mut half_colour = || ((rng() as i32) >> (rng() % 31)) >> 1;
    let mut worst = 0.0f64;
    for _ in 0..1_000_000 {
        let (a, b) = (unit(), unit());
        let f = |v: [Fixed22; 3]| v.map(Fixed22::to_f64);
        let (fa, fb) = (f(a), f(b));
        let cos = (fa[0] * fb[0] + fa[1] * fb[1] + fa[2] * fb[2]).clamp(-1.0, 1.0);
        let (s, g) = ([0; 3].map(|_| half_colour()), [0; 3].map(|_| half_colour()));
        let mid = [0, 1, 2].map(|k| Fixed22::from_bits(s[k] + g[k]));
        let half = [0, 1, 2].map(|k| Fixed22::from_bits(s[k] - g[k]));
        let got = <Fixed22 as Sealed>::mix_by_cos(mid, half, a, Fixed22::prepare_axis(b));
        for k in 0..3 {
            let want = mid[k].to_f64() + half[k].to_f64() * cos;
            let h = half[k].to_f64().abs();
            let budget = (5.3e-5 + 1.0 / 65_536.0) * h + 1.0 / 4_194_304.0;
            let err = (got[k].to_f64() - want).abs();
            assert!(
                err <= budget,
                "{s:?} {g:?} {a:?} {b:?}: {err:e} > {budget:e}"
            );
            worst = worst.max(err / h.max(1.0));
        }
    }
    std::println!("mix_by_cos worst error relative to max(1, |half|) {worst:e}");
}

/// `kernels::mix_by_cos` (`m + floor(h c / 2^15)`, summed without a saturation test) never
/// wraps under its precondition (`m = s + g`, `h = s - g`, `s` and `g` halves of colours,
/// rounded down): every pair of halves of the format's edge colours and every factor at the
/// ends of `[-2^15, 2^15]` and between, against the exact sum in 64 bits. And the sealed
/// `cos_axis` with a prepared axis is `cos_unit`'s bits on 1 000 000 random unit pairs and
/// the signed axes.
#[cfg(feature = "hemisphere")]
#[test]
fn mix_by_cos_cannot_wrap_and_cos_axis_is_cos_unit() {
    use super::kernels::mix_by_cos;
    use crate::real::sealed::Sealed;
    let colours = [
        i32::MIN,
        i32::MIN + 1,
        i32::MIN + 2,
        -(1 << 30),
        -1,
        0,
        1,
        (1 << 30) - 1,
        i32::MAX - 1,
        i32::MAX,
    ];
    let cs = [
        -(1 << 15),
        -(1 << 15) + 1,
        -12_345,
        -1,
        0,
        1,
        12_345,
        (1 << 15) - 1,
        1 << 15,
    ];
    for &sky in &colours {
        for &ground in &colours {
            let (s, g) = (sky >> 1, ground >> 1);
            let (m, h) = (s + g, s - g);
            for &c in &cs {
                let want = i64::from(m) + ((i64::from(h) * i64::from(c)) >> 15);
                assert!(want >= i64::from(i32::MIN) && want <= i64::from(i32::MAX));
                assert_eq!(i64::from(mix_by_cos(m, h, c)), want, "{sky} {ground} {c}");
            }
        }
    }
    let mut next = crate::test_rng::xorshift32(0x0A11_5EED);
    let mut unit = || loop {
        let shift = next() % 31;
        let v = [0, 1, 2].map(|_| Fixed22::from_bits((next() as i32) >> shift));
        if let Some(u) = Fixed22::unit3(v) {
            break u;
        }
    };
    for _ in 0..1_000_000 {
        let (a, b) = (unit(), unit());
        let got = Fixed22::cos_axis(a, Fixed22::prepare_axis(b));
        assert_eq!(got, Fixed22::cos_unit(a, b), "{a:?} {b:?}");
    }
    let (o, z) = (Fixed22::ONE, Fixed22::ZERO);
    let axes = [
        [o, z, z],
        [z, o, z],
        [z, z, o],
        [-o, z, z],
        [z, -o, z],
        [z, z, -o],
    ];
    for a in axes {
        for b in axes {
            let got = Fixed22::cos_axis(a, Fixed22::prepare_axis(b));
            assert_eq!(got, Fixed22::cos_unit(a, b), "{a:?} {b:?}");
        }
    }
}
