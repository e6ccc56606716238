//! The tests of [`Fixed22`](super::Fixed22)'s products and normalizations against the
//! type's own saturating arithmetic, bit for bit (the kernels' own tests against f64 are
//! `tests/fixed_kernels.rs` and `tests/fixed_exhaustive.rs`).

extern crate std;

use super::normalize::rescale_for_unit;
use super::*;

/// A random unit vector as the crate makes one (`unit3` of a random vector of any magnitude),
/// for the submodules' tests.
#[cfg(any(feature = "sh9", all(feature = "polygon", feature = "phong")))]
fn random_unit(next: &mut impl FnMut() -> u32) -> [Fixed22; 3] {
    loop {
        let shift = next() % 31;
        let v = [0, 1, 2].map(|_| Fixed22::from_bits((next() as i32) >> shift));
        if let Some(u) = Fixed22::unit3(v) {
            return u;
        }
    }
}

/// The product by a factor of at most 1 is `*`'s bits: every `a` on a stride plus the
/// edges against every `c` edge and a stride of `c` over `[-2^22, 2^22]`.
#[test]
fn unit_factor_products_are_bit_identical() {
    let one = 1i32 << 22;
    let edges = [-one, -one + 1, -1, 0, 1, 0xFFFF, 0x10000, one - 1, one];
    let mut a = i32::MIN as i64;
    while a <= i32::MAX as i64 {
        for &a in &[
            a as i32,
            (a as i32).wrapping_add(1),
            i32::MAX,
            0xFFFF,
            -0x10000,
        ] {
            for c in edges.into_iter().chain((-one..=one).step_by(9973)) {
                if a == i32::MIN && c == -one {
                    continue;
                }
                assert_eq!(mul_bits_unit(a, c), mul_bits(a, c), "{a} * {c}");
            }
        }
        a += 1_000_003;
    }
}

/// `mul_each` is `*` channel by channel, whichever side lies within `(-1, 1]` (or
/// neither): triples drawn from the edges of that range and of the type (1 itself, `MIN`,
/// `MAX`) and random values of every magnitude, both ways round.
#[test]
fn channel_products_are_bit_identical() {
    use crate::real::sealed::Sealed;
    let one = 1i32 << 22;
    let edges = [
        i32::MIN,
        i32::MIN + 1,
        -one - 1,
        -one,
        -one + 1,
        -1,
        0,
        1,
        one - 1,
        one,
        one + 1,
        i32::MAX,
    ];
    let mut next = crate::test_rng::xorshift32(0x0BAD_5EED);
    let mut pick = |k: u32| -> Fixed22 {
        let r = next();
        Fixed22::from_bits(match k % 3 {
            0 => edges[(r % edges.len() as u32) as usize],
            // Within (-1, 1), near its edges or anywhere in it.
            1 => (r as i32) >> 9,
            _ => (r as i32) >> (r % 31),
        })
    };
    let mut within = 0;
    for i in 0..300_000u32 {
        let a = [pick(i), pick(i / 3), pick(i / 9)];
        let b = [pick(i / 27), pick(i / 81), pick(i / 243)];
        let want = [a[0] * b[0], a[1] * b[1], a[2] * b[2]];
        assert_eq!(<Fixed22 as Sealed>::mul_each(a, b), want, "{a:?} * {b:?}");
        assert_eq!(<Fixed22 as Sealed>::mul_each(b, a), want, "{b:?} * {a:?}");
        within += usize::from(a.iter().all(|c| c.to_bits().unsigned_abs() < 1 << 22));
    }
    // Both paths taken often.
    assert!(within > 10_000 && within < 290_000, "{within}");
}

/// The fused dot product is exactly `floor(k0 + sum k m / 2^22)`, saturated: random `k`
/// of every magnitude (the full `i32` range included), factors over their whole range
/// `|m| <= 3 2^21` (edges included), against `i64` arithmetic.
#[test]
#[cfg(feature = "sh9")]
fn fused_dot_is_exact() {
    let mut next = crate::test_rng::xorshift32(0x9E37_79B9);
    let lim = 3 << 21;
    for n in 0..300_000 {
        let shift = next() % 32;
        let k: [i32; 8] = core::array::from_fn(|_| (next() as i32) >> shift);
        let k0 = (next() as i32) >> (next() % 32);
        let m: [i32; 8] = core::array::from_fn(|_| match (n % 4, next() % 8) {
            (0, 0) => lim,
            (0, 1) => -lim,
            (1, _) => [lim, -lim][(next() % 2) as usize],
            _ => (next() % (2 * lim as u32 + 1)) as i32 - lim,
        });
        let (mut mh, mut ml) = ([0; 8], [0; 8]);
        for i in 0..8 {
            (mh[i], ml[i]) = split_11(m[i]);
        }
        let sum: i64 = (0..8).map(|i| i64::from(k[i]) * i64::from(m[i])).sum();
        let want = (i64::from(k0) + (sum >> 22)).clamp(i32::MIN.into(), i32::MAX.into());
        assert_eq!(
            i64::from(dot8_split_bits(k0, k, &mh, &ml)),
            want,
            "{k0} {k:?} {m:?}"
        );
    }
}

/// `recip_core(d)` is `floor(2^63 / d)` or up to 3 below it (what `div_bits` and
/// `atan2_bits` rely on): every `d` with `step = 1` (`-- --ignored`), a stride otherwise.
fn recip_core_within(step: usize) {
    let check = |d: u32| {
        let exact = (1u64 << 63) / u64::from(d);
        let y = u64::from(recip_core(d));
        assert!(y <= exact && exact - y <= 3, "{d}: {y} vs {exact}");
    };
    for d in ((1u32 << 31)..=u32::MAX).step_by(step) {
        check(d);
    }
    for k in 0..16u32 {
        let edge = (1u32 << 31) + (k << 27);
        for d in edge.saturating_sub(4096).max(1 << 31)..=edge.saturating_add(4096) {
            check(d);
        }
    }
    check(u32::MAX);
}

#[test]
fn recip_core_is_within_three_units_below() {
    recip_core_within(97);
}

#[test]
#[ignore = "every d in [2^31, 2^32): run with `-- --ignored`"]
fn recip_core_is_within_three_units_below_everywhere() {
    recip_core_within(1);
}

/// `rsqrt_core_unit` (the normalizations' reciprocal square root) on every sum of squares it
/// can be given, `v` in `[2^20, 2^26)`: the general core's `(m, j)`, and `y` within `2^-28`
/// of `2^32 / sqrt(m / 2^30)` relative (measured: `2^-28.45`; the general core's `2^-29.5`).
#[test]
fn normalization_rsqrt_core_is_within_its_bound() {
    use super::elementary::{even_top_of_square_sum, rsqrt_core_at, rsqrt_core_unit};
    let mut worst = 0f64;
    for v in (1u32 << 20)..(1u32 << 26) {
        let j2 = even_top_of_square_sum(v);
        let (m, j, y) = rsqrt_core_unit(v, j2);
        let (m0, j0, _) = rsqrt_core_at(v, j2);
        assert_eq!((m, j), (m0, j0), "{v}");
        let exact = 4_294_967_296.0 / (f64::from(m) / 1_073_741_824.0).sqrt();
        worst = worst.max((f64::from(y) - exact).abs() / exact);
    }
    std::println!("[rsqrt_core_unit] max relative error 2^{:.2}", worst.log2());
    assert!(worst <= 2f64.powi(-28), "2^{}", worst.log2());
}

/// `mul_bits_small` against `mul_bits` (both orders): every `a` in `[-lim, lim]` on a
/// stride of `step`, against the range's edges, the halves' edges and `a`'s fractions.
fn small_products_on_a_stride(lim: i32, step: i32) {
    let half = lim / 2 + 1;
    let edges = [
        -lim,
        -lim + 1,
        -half,
        -1,
        0,
        1,
        0xFFFF,
        0x10000,
        half,
        lim - 1,
        lim,
    ];
    let mut a = -lim;
    while a <= lim {
        for &b in edges.iter().chain([a / 3, -a / 7, 12_345].iter()) {
            assert_eq!(mul_bits_small(a, b), mul_bits(a, b), "{a} * {b}");
            assert_eq!(mul_bits_small(b, a), mul_bits(b, a), "{b} * {a}");
        }
        a += step;
    }
}

/// The normalizations' small products are `*`'s bits, and the sums `+`'s: every
/// `|a|, |b| <= 2^23` on a stride plus the edges, and the normalizations of 200 000 random
/// vectors of every magnitude against the same formula in the type's own `*` and `+`.
#[test]
fn small_products_and_normalizations_are_bit_identical() {
    small_products_on_a_stride(1 << 23, 997);
    let mut next = crate::test_rng::xorshift32(0x2545_F491);
    for _ in 0..200_000 {
        let shift = next() % 31;
        let v = [0, 1, 2].map(|_| Fixed22::from_bits((next() as i32) >> shift));
        let m = Real::max(Real::max(v[0].abs(), v[1].abs()), v[2].abs());
        let want = if m <= Fixed22::TINY {
            None
        } else {
            let ([x, y, z], k) = rescale_for_unit(v, m.to_bits() as u32);
            let d = Fixed22::from_bits(1 << (22 - k));
            let (len, inv) = unit_sqrt_rsqrt(x * x + y * y + z * z);
            // The scalings rounded to nearest (`mul_bits_le2_round`), in i64.
            let r = |c: Fixed22| {
                let p = i64::from(c.to_bits()) * i64::from(inv.to_bits());
                Fixed22::from_bits(((p + (1 << 21)) >> 22) as i32)
            };
            Some(([r(x), r(y), r(z)], len * d))
        };
        assert_eq!(Fixed22::normalize3(v), want, "{v:?}");
        assert_eq!(Fixed22::unit3(v), want.map(|(u, _)| u), "{v:?}");
    }
}

/// The small products hold to their whole precondition, factors below 16 (`2^26` raw):
/// every `a` on a stride against the edges and a stride of `b`, and the sealed
/// `dot3_small`/`cross3_small` on 200 000 random offsets of the polygon edge terms
/// (`ua`, `ub` within 8, `d` within 16: `polygon::edge::offset_products`) against
/// `Vec3::dot` and `Vec3::cross`, bit for bit.
#[test]
fn small_products_hold_for_factors_below_16() {
    small_products_on_a_stride((1 << 26) - 1, 9_973);
    let mut next = crate::test_rng::xorshift32(0x1234_5677);
    // Raw values in [-2^(22 + k), 2^(22 + k)): below 2^k, of every magnitude.
    let mut coord = |k: u32| {
        let extra = next() % 20;
        Fixed22::from_bits((next() as i32) >> (9 - k + extra))
    };
    for _ in 0..200_000 {
        let ua = crate::Vec3::new(coord(3), coord(3), coord(3));
        let ub = crate::Vec3::new(coord(3), coord(3), coord(3));
        let d = crate::Vec3::new(coord(4), coord(4), coord(4));
        let arr = |v: crate::Vec3<Fixed22>| [v.x, v.y, v.z];
        let c = ua.cross(d);
        assert_eq!(
            <Fixed22 as super::super::sealed::Sealed>::cross3_small(arr(ua), arr(d)),
            arr(c),
            "{ua:?} x {d:?}"
        );
        assert_eq!(
            <Fixed22 as super::super::sealed::Sealed>::dot3_small(arr(ua), arr(ub)),
            ua.dot(ub),
            "{ua:?} . {ub:?}"
        );
    }
}

/// `arc_ratio_q30_to_q15` (the 16-bit polygon edge terms' ratio) against f64's
/// `acos(c)/sqrt(1 - c^2)`: every 61st cosine of `[0, 1]` in Q30 and the ends. Before its
/// rounding (`arc_ratio_q30_to_q22`) within 4.2e-6 of the exact ratio (its documented
/// budget; measured 3.9e-6), after it within `2^-16` more. Outside `[0, 1]` the cosine is clamped: the ends' values.
#[cfg(feature = "polygon")]
#[test]
fn arc_ratio_in_32_bit_products_is_within_its_rounding() {
    use super::elementary::{arc_ratio_q30_to_q15, arc_ratio_q30_to_q22};
    let exact = |c: f64| {
        if c >= 1.0 {
            1.0
        } else {
            c.acos_clamped() / (1.0 - c * c).sqrt()
        }
    };
    const BOUND: f64 = 4.2e-6;
    let (mut worst22, mut worst15) = (0.0f64, 0.0f64);
    let mut c = 0i64;
    let one = 1i64 << 30;
    while c <= one {
        for c in [c, one, one - 1, 0, 1, 1 << 14] {
            let want = exact(c as f64 / one as f64);
            let q22 = f64::from(arc_ratio_q30_to_q22(c as i32)) / f64::from(1 << 22);
            let q15 = f64::from(arc_ratio_q30_to_q15(c as i32)) / 32768.0;
            let (e22, e15) = ((q22 - want).abs(), (q15 - want).abs());
            assert!(e22 <= BOUND, "R({c} 2^-30) = {q22} (Q22): off by {e22:e}");
            assert!(
                e15 <= BOUND + 1.0 / 65536.0,
                "R({c} 2^-30) = {q15}: off by {e15:e}"
            );
            worst22 = worst22.max(e22);
            worst15 = worst15.max(e15);
        }
        c += 61;
    }
    std::println!("arc_ratio_q30_to_q22 worst {worst22:e}, arc_ratio_q30_to_q15 worst {worst15:e}");
    for (c, at) in [
        (i32::MIN, 0),
        (-1, 0),
        (i32::MAX, 1 << 30),
        ((1 << 30) + 1, 1 << 30),
    ] {
        assert_eq!(arc_ratio_q30_to_q15(c), arc_ratio_q30_to_q15(at), "{c}");
    }
}

/// The 16-bit normalization (`normalize::unit_q15`, the sealed `unit3_q15`) against f64's
/// `v / |v|`: `None` exactly where `unit3` is (the largest magnitude at most `TINY`), else
/// every component at most `2^15` in magnitude (the bound `unit_ratio_term` relies on) and
/// within `1.1e-4` of the exact one scaled by `2^15` (its documented error budget: the
/// components' rounding to 15 bits, the seed's and `r`'s, the result's). 400 000 random
/// vectors of every magnitude, and the edges: the type's extremes, `TINY` and just above it,
/// the axes, and components just below a power of two (which round up to `2^15`).
#[cfg(feature = "polygon")]
#[test]
fn unit_q15_is_within_its_error_budget() {
    use super::normalize::unit_q15;
    let check = |v: [i32; 3]| {
        let fv = v.map(Fixed22::from_bits);
        let got = unit_q15(fv);
        assert_eq!(got.is_some(), Fixed22::unit3(fv).is_some(), "{v:?}");
        let Some(got) = got else { return 0.0 };
        let f = v.map(f64::from);
        let len = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
        let mut worst = 0.0f64;
        for (g, x) in got.iter().zip(f) {
            assert!(g.unsigned_abs() <= (1 << 15) + 1, "{v:?} -> {got:?}");
            let err = (f64::from(*g) / 32768.0 - x / len).abs();
            assert!(err <= 1.1e-4, "{v:?} -> {got:?}: off by {err:e}");
            worst = worst.max(err);
        }
        worst
    };
    let tiny = Fixed22::TINY.to_bits();
    let edges = [
        i32::MIN,
        i32::MIN + 1,
        i32::MAX,
        -tiny - 1,
        -tiny,
        0,
        1,
        tiny,
        tiny + 1,
        (1 << 15) - 1,
        (1 << 16) - 1,
        (1 << 22) - 1,
        1 << 22,
        -(1 << 22) + 1,
    ];
    for &x in &edges {
        for &y in &edges {
            for &z in &edges {
                check([x, y, z]);
            }
        }
    }
    let mut next = crate::test_rng::xorshift32(0x51F1_5EED);
    let mut worst = 0.0f64;
    for _ in 0..400_000 {
        let shift = next() % 31;
        let v = [0, 1, 2].map(|_| (next() as i32) >> shift);
        worst = worst.max(check(v));
    }
    std::println!("unit_q15 worst component error {worst:e}");
}

/// `height_nonneg` (the polygon walks' horizon test from 16-bit products) is `dot3_small >=
/// 0` over its whole precondition: 1 000 000 offsets below 16 of every magnitude against
/// random unit normals, a third of them moved onto the horizon (`a - (a.b) b`, then nudged
/// by a few units), and the extreme offsets `+-(2^26 - 1)` against the axes and diagonals.
#[cfg(feature = "polygon")]
#[test]
fn height_sign_from_16_bit_products_is_exact() {
    use crate::real::sealed::Sealed;
    let check = |a: [i32; 3], b: [Fixed22; 3]| {
        let a = a.map(Fixed22::from_bits);
        assert_eq!(
            Fixed22::height_nonneg(a, b),
            Fixed22::dot3_small(a, b) >= Fixed22::ZERO,
            "{a:?} . {b:?}"
        );
    };
    let mut next = crate::test_rng::xorshift32(0x0DDB_A115);
    let lim = (1i32 << 26) - 1;
    let (mut near, mut fast) = (0, 0);
    for i in 0..1_000_000 {
        let Some(b) = Fixed22::unit3([0, 1, 2].map(|_| Fixed22::from_bits(next() as i32 >> 8)))
        else {
            continue;
        };
        let shift = 6 + next() % 26;
        let mut a = [0, 1, 2].map(|_| ((next() as i32) >> shift).clamp(-lim, lim));
        if i % 3 == 0 {
            // Onto the plane through the origin normal to b, then a few units off it.
            let d = Fixed22::dot3_small(a.map(Fixed22::from_bits), b).to_bits();
            for (c, bc) in a.iter_mut().zip(b) {
                let t = ((i64::from(d) * i64::from(bc.to_bits())) >> 22) as i32;
                *c = (c.wrapping_sub(t) + (next() as i32 >> 27)).clamp(-lim, lim);
            }
        }
        let e: i32 = (0..3).map(|k| (a[k] >> 11) * (b[k].to_bits() >> 8)).sum();
        if e.abs() < 1 << 18 {
            near += 1;
        } else {
            fast += 1;
        }
        check(a, b);
    }
    // Both paths taken many times.
    assert!(near > 100_000 && fast > 100_000, "{near} {fast}");
    let one = 1i32 << 22;
    let h = (one as f64 / 3f64.sqrt()) as i32;
    for b in [
        [one, 0, 0],
        [0, -one, 0],
        [0, 0, one],
        [h, h, h],
        [-h, h, -h],
    ] {
        let b = b.map(Fixed22::from_bits);
        for a in [
            [lim, lim, lim],
            [-lim, -lim, -lim],
            [lim, -lim, 0],
            [-lim, 0, lim],
        ] {
            check(a, b);
        }
    }
}

/// The positions' range test (the sealed `within_coordinate_limit`) answers as the largest
/// magnitude against the limit in the type's own saturating arithmetic: every triple of the
/// edges (the type's extremes, the limit's bits and their neighbours) and 1 000 000 random
/// triples of every magnitude.
#[test]
fn coordinate_limit_test_is_the_largest_magnitudes() {
    use crate::real::sealed::Sealed;
    let want = |v: [Fixed22; 3]| {
        let m = Real::max(Real::max(v[0].abs(), v[1].abs()), v[2].abs());
        m <= Fixed22::from_f64(Fixed22::COORDINATE_LIMIT)
    };
    let l = 4i32 << 22;
    let edges = [
        i32::MIN,
        i32::MIN + 1,
        -l - 1,
        -l,
        -l + 1,
        -1,
        0,
        1,
        l - 1,
        l,
        l + 1,
        i32::MAX,
    ];
    for &x in &edges {
        for &y in &edges {
            for &z in &edges {
                let v = [x, y, z].map(Fixed22::from_bits);
                assert_eq!(
                    <Fixed22 as Sealed>::within_coordinate_limit(v),
                    want(v),
                    "{v:?}"
                );
            }
        }
    }
    let mut next = crate::test_rng::xorshift32(0x04C1_3177);
    let mut inside = 0;
    for _ in 0..1_000_000 {
        let shift = next() % 31;
        let v = [0, 1, 2].map(|_| Fixed22::from_bits((next() as i32) >> shift));
        let w = want(v);
        inside += usize::from(w);
        assert_eq!(<Fixed22 as Sealed>::within_coordinate_limit(v), w, "{v:?}");
    }
    assert!(inside > 100_000 && inside < 900_000, "{inside}");
}

/// `kernels::mul_bits_le2` (three 32-bit products) is `mul_bits_small`'s exact `floor(a b /
/// 2^22)` for every pair of factors within its bound (`2^23 + 2^16` raw): the edges (the
/// bound, `+-2^23`, `+-2^22` and their neighbours, the halves' boundaries) against each
/// other, 1 000 000 random pairs of every magnitude up to `2^23`, and the 64-bit product.
#[test]
fn products_of_factors_up_to_two_are_exact() {
    use super::kernels::{mul_bits_le2, mul_bits_small};
    let exact = |a: i32, b: i32| ((i64::from(a) * i64::from(b)) >> 22) as i32;
    let mut edges = std::vec::Vec::new();
    for e in [
        0,
        1,
        0xFFFF,
        0x1_0000,
        1 << 22,
        (1 << 22) + 64,
        1 << 23,
        (1 << 23) + (1 << 16),
    ] {
        for d in [-1, 0, 1] {
            let v: i32 = e + d;
            if v.unsigned_abs() <= (1 << 23) + (1 << 16) {
                edges.push(v);
                edges.push(-v);
            }
        }
    }
    for &a in &edges {
        for &b in &edges {
            assert_eq!(mul_bits_le2(a, b), exact(a, b), "{a} {b}");
            assert_eq!(mul_bits_le2(a, b), mul_bits_small(a, b), "{a} {b}");
        }
    }
    let mut next = crate::test_rng::xorshift32(0x1E2C_0DE5);
    let mut factor = || ((next() as i32) >> 8) >> (next() % 24);
    for _ in 0..1_000_000 {
        let (a, b) = (factor(), factor());
        assert_eq!(mul_bits_le2(a, b), exact(a, b), "{a} {b}");
    }
}

/// `kernels::mul_hi_u32` is the high word of the 64-bit product for every pair within its
/// precondition (`a, b <= 2^31`): the edges (0, 1, `2^16 - 1`, `2^16`, `2^31 - 1`, `2^31`
/// and their neighbours) against each other and 1 000 000 random pairs of every magnitude.
#[test]
fn high_words_of_unsigned_products_are_exact() {
    use super::kernels::mul_hi_u32;
    let exact = |a: u32, b: u32| ((u64::from(a) * u64::from(b)) >> 32) as u32;
    let edges = [
        0,
        1,
        0xFFFF,
        0x1_0000,
        0x1_0001,
        0x7FFF_0000,
        0x7FFF_FFFF,
        0x8000_0000,
    ];
    for &a in &edges {
        for &b in &edges {
            assert_eq!(mul_hi_u32(a, b), exact(a, b), "{a} {b}");
        }
    }
    let mut next = crate::test_rng::xorshift32(0x0B16_B00B);
    for _ in 0..1_000_000 {
        let a = (next() >> 1) >> (next() % 31);
        let b = (next() >> 1) >> (next() % 31);
        assert_eq!(mul_hi_u32(a, b), exact(a, b), "{a} {b}");
        assert_eq!(
            mul_hi_u32(a | 0xFFFF, b | 0xFFFF),
            exact(a | 0xFFFF, b | 0xFFFF)
        );
    }
}

/// The Lambert-type cosine through Q15, with a light's prepared axis, and `sky_ground`'s
/// products by it.
mod cosine;

/// The camera's rounded product and dot product against the exact ones.
#[cfg(feature = "raster")]
mod camera;

/// The Phong polygon's edge plane from unit directions against f64.
#[cfg(all(feature = "polygon", feature = "phong"))]
mod edge_plane;

/// SH9's 16-bit fast path against f64 and against its own integer sums.
#[cfg(feature = "sh9")]
mod sh9_q15;

/// `normalize::top_exponent` and `normalize::top_bit` (comparisons in the common band, the
/// leading-zero count elsewhere) are `(21 - h).clamp(-8, 21)` and `h` of the highest set bit
/// `h`: every power of two and its neighbours, the band's ends, and 1 000 000 random values
/// of every magnitude.
#[test]
fn top_exponent_and_top_bit_are_the_leading_bit_formulas() {
    use super::normalize::top_exponent;
    let high = |t: u32| 31 - t.leading_zeros() as i32;
    let check = |t: u32| {
        assert_eq!(top_exponent(t), (21 - high(t)).clamp(-8, 21), "{t:#x}");
        #[cfg(feature = "polygon")]
        assert_eq!(super::normalize::top_bit(t), high(t), "{t:#x}");
    };
    for b in 0..32 {
        let p = 1u32 << b;
        for t in [p, p - 1, p + 1, p | (p - 1)] {
            if t > 0 {
                check(t);
            }
        }
    }
    check(u32::MAX);
    let mut next = crate::test_rng::xorshift32(0x70_9E);
    for _ in 0..1_000_000 {
        check((next() >> (next() % 32)).max(1));
    }
}
