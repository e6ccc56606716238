//! The fixed-point backend [`Fixed22`]: its elementary functions against f64 (10^6 random
//! inputs plus every edge input, and exhaustive sweeps of the reduced domains), and every
//! model in its scope against f64 on the same (fixed-rounded) inputs, within 1/1024.
//!
//! This file runs in the test profile, which has overflow checks on: an overflow anywhere in
//! the fixed path (the kernels' `i64` arithmetic included) panics and fails the test.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

#[path = "../common/mod.rs"]
mod common;

use arealight::{
    lune_normalization, CapLight, Decay, DistanceFalloff, Fixed22, HemisphereLight, LightFrame,
    LineLight, OvercastSky, ParallelogramLight, PhongLobe, PolygonLight, Real, Rgb, Sh9, SkyGround,
    SphereLight, Superellipse, Uberlight, Vec3,
};
use common::*;
use std::f64::consts::{FRAC_PI_2, PI};

mod models;

type F = Fixed22;
const LSB: f64 = 1.0 / 4_194_304.0;
const TOL: f64 = 1.0 / 1024.0;

fn fx(bits: i32) -> F {
    F::from_bits(bits)
}

/// Edge inputs of a Q22 domain: 0, +-1 LSB, +-1, +-2, the extremes, powers of two and their
/// neighbours.
fn edge_bits() -> Vec<i32> {
    let mut e = vec![0, 1, -1, i32::MAX, i32::MIN, i32::MAX - 1, i32::MIN + 1];
    for k in 0..31 {
        let p = 1i32 << k;
        e.extend([p, p - 1, p + 1, -p, -p + 1, -p - 1]);
    }
    e
}

/// 10^6 random Q22 values: a third uniform over all bits, a third log-uniform in magnitude
/// (small values), a third in [-4, 4].
fn random_bits(rng: &mut Rng, count: usize) -> Vec<i32> {
    (0..count)
        .map(|i| match i % 3 {
            0 => rng.next_u64() as i32,
            1 => {
                let mag = (rng.next_u64() >> (33 + rng.below(31))) as i32;
                if rng.below(2) == 0 {
                    mag
                } else {
                    -mag
                }
            }
            _ => (rng.range(-4.0, 4.0) / LSB) as i32,
        })
        .collect()
}

/// Max error of a unary function in LSBs over the given inputs (`want` is the exact value,
/// clamped to the format's range as the function is documented to saturate).
fn max_lsb(inputs: &[i32], f: impl Fn(F) -> F, want: impl Fn(f64) -> f64) -> (f64, i32) {
    let mut worst = (0.0, 0);
    for &b in inputs {
        let x = fx(b);
        let w = want(x.to_f64()).clamp(F::MIN.to_f64(), F::MAX.to_f64());
        let e = (f(x).to_f64() - w).abs() / LSB;
        assert!(e.is_finite(), "input {b}");
        if e > worst.0 {
            worst = (e, b);
        }
    }
    worst
}

#[test]
fn division_is_correctly_rounded() {
    let mut rng = Rng::new(0xd1f);
    let mut xs = random_bits(&mut rng, 1_000_000);
    xs.extend(edge_bits());
    let ys = random_bits(&mut rng, xs.len());
    let edges = edge_bits();
    let mut worst: f64 = 0.0;
    let mut check = |a: i32, b: i32| {
        let got = (fx(a) / fx(b)).to_f64();
        let exact = if b == 0 {
            if a == 0 {
                0.0
            } else if a > 0 {
                F::MAX.to_f64()
            } else {
                F::MIN.to_f64()
            }
        } else {
            (a as f64 / b as f64).clamp(F::MIN.to_f64(), F::MAX.to_f64())
        };
        let e = (got - exact).abs() / LSB;
        assert!(e <= 0.5, "{a} / {b}: got {got}, want {exact} ({e} LSB)");
        worst = worst.max(e);
    };
    for (&a, &b) in xs.iter().zip(&ys) {
        check(a, b);
    }
    for &a in &edges {
        for &b in &edges {
            check(a, b);
        }
    }
    println!("[maxerr] Fixed22 division: {worst:.3} LSB (bound 0.5, correctly rounded)");
}

#[test]
fn sqrt_within_one_lsb() {
    let mut rng = Rng::new(0x5a7);
    let mut xs = random_bits(&mut rng, 1_000_000);
    xs.extend(edge_bits());
    // Exhaustive over [0, 1/64): 2^16 points, where the relative step is largest.
    xs.extend(0..1 << 16);
    let (e, at) = max_lsb(&xs, |x| x.sqrt(), |x| if x > 0.0 { x.sqrt() } else { 0.0 });
    println!("[maxerr] Fixed22 sqrt: {e:.3} LSB at bits {at} (bound 1)");
    assert!(e <= 1.0);
}

#[test]
fn atan2_within_one_lsb() {
    let mut rng = Rng::new(0xa7a2);
    let xs = random_bits(&mut rng, 1_000_000);
    let ys = random_bits(&mut rng, 1_000_000);
    let mut pairs: Vec<(i32, i32)> = xs.into_iter().zip(ys).collect();
    let edges = edge_bits();
    for &a in &edges {
        for &b in &edges {
            pairs.push((a, b));
        }
    }
    // Exhaustive over the directions of a 256 x 256 grid of small integers (every ratio the
    // reduction can produce at that scale), both signs.
    for i in -128..128 {
        for j in -128..128 {
            pairs.push((i, j));
        }
    }
    let mut worst = (0.0, (0, 0));
    for (y, x) in pairs {
        let got = fx(y).atan2(fx(x)).to_f64();
        let want = (y as f64).atan2(x as f64);
        let e = (got - want).abs() / LSB;
        if e > worst.0 {
            worst = (e, (y, x));
        }
    }
    println!(
        "[maxerr] Fixed22 atan2: {:.3} LSB at (y, x) bits {:?} (bound 1)",
        worst.0, worst.1
    );
    assert!(worst.0 <= 1.0);
}

#[test]
fn sin_cos_within_one_lsb() {
    let mut rng = Rng::new(0x51c0);
    // The documented domain |x| <= 64 (the models call them on angles in [-2 pi, 2 pi]).
    let mut xs: Vec<i32> = (0..1_000_000)
        .map(|_| (rng.range(-64.0, 64.0) / LSB) as i32)
        .collect();
    xs.extend(
        edge_bits()
            .into_iter()
            .filter(|b| b.unsigned_abs() <= 64 << 22),
    );
    // Exhaustive over [0, 2^-6) (2^16 points: the smallest angles) and around pi/2 and pi.
    xs.extend(0..1 << 16);
    for c in [FRAC_PI_2, PI, 2.0 * PI] {
        let b = (c / LSB) as i32;
        xs.extend(b - 1000..b + 1000);
    }
    let (es, at_s) = max_lsb(&xs, |x| x.sin(), f64::sin);
    let (ec, at_c) = max_lsb(&xs, |x| x.cos(), f64::cos);
    println!(
        "[maxerr] Fixed22 sin: {es:.3} LSB at bits {at_s}; cos: {ec:.3} LSB at {at_c} (bound 1)"
    );
    assert!(es <= 1.0 && ec <= 1.0);
    // Outside the documented domain: finite, bounded by 1 in magnitude plus rounding.
    for b in edge_bits() {
        assert!(fx(b).sin().to_f64().abs() <= 1.0 + 2.0 * LSB);
        assert!(fx(b).cos().to_f64().abs() <= 1.0 + 2.0 * LSB);
    }
}

#[test]
fn exp_and_ln_within_bounds() {
    let mut rng = Rng::new(0xe4b);
    let mut xs = random_bits(&mut rng, 1_000_000);
    xs.extend(edge_bits());
    // exp: dense over its whole non-trivial domain [-17, 9 ln 2] (every 64th value: 1.6e6 points).
    xs.extend((-17 << 22..26_165_280).step_by(64));
    let mut worst = (0.0, 0);
    for &b in &xs {
        let x = fx(b).to_f64();
        let want = x.exp().min(F::MAX.to_f64());
        // Bound: 1 LSB plus 2^-22 relative (the Q30 result is shifted up by up to 9 bits).
        let e = (fx(b).exp().to_f64() - want).abs() / (LSB * (1.0 + want));
        if e > worst.0 {
            worst = (e, b);
        }
    }
    println!(
        "[maxerr] Fixed22 exp: {:.3} in units of (1 + e^x) LSB at bits {} (bound 1)",
        worst.0, worst.1
    );
    assert!(worst.0 <= 1.0);
    let mut ys = random_bits(&mut rng, 1_000_000);
    ys.extend(edge_bits());
    ys.extend(1..1 << 16); // exhaustive over (0, 2^-6): the steepest part
    ys.retain(|&b| b > 0);
    let (e, at) = max_lsb(&ys, |x| x.ln(), f64::ln);
    println!("[maxerr] Fixed22 ln: {e:.3} LSB at bits {at} (bound 1)");
    assert!(e <= 1.0);
    assert_eq!(F::ZERO.ln(), F::MIN);
    assert_eq!(fx(-5).ln(), F::MIN);
}

#[test]
fn conversions_and_saturation() {
    assert_eq!(F::from_f64(f64::NAN), F::ZERO);
    assert_eq!(F::from_f64(f64::INFINITY), F::MAX);
    assert_eq!(F::from_f64(-1e300), F::MIN);
    assert_eq!(F::from_u32(511).to_f64(), 511.0);
    assert_eq!(F::from_u32(512), F::MAX);
    assert_eq!(F::from_u32(u32::MAX), F::MAX);
    assert_eq!(F::MAX + F::ONE, F::MAX);
    assert_eq!(F::MIN - F::ONE, F::MIN);
    assert_eq!(-F::MIN, F::MAX);
    assert_eq!(F::MAX * F::TWO, F::MAX);
    assert_eq!(F::MIN * F::TWO, F::MIN);
    assert_eq!(F::MIN * -F::TWO, F::MAX);
    assert_eq!(F::MIN.abs(), F::MAX);
    assert!((F::PI.to_f64() - PI).abs() <= 0.5 * LSB);
    assert_eq!(F::ONE / F::ZERO, F::MAX);
    assert_eq!(-F::ONE / F::ZERO, F::MIN);
    assert_eq!(F::ZERO / F::ZERO, F::ZERO);
}

// ---------------------------------------------------------------------------------------------
// Overflow: raw bit patterns everywhere (this test profile has overflow checks on).
// ---------------------------------------------------------------------------------------------

fn any_bits(rng: &mut Rng) -> F {
    // Half uniform over all 2^32 patterns (mostly huge magnitudes), half small, plus edges.
    match rng.below(8) {
        0..=3 => fx(rng.next_u64() as i32),
        4..=6 => fx((rng.range(-8.0, 8.0) / LSB) as i32),
        _ => [F::MIN, F::MAX, F::ZERO, F::DELTA, -F::DELTA, F::ONE][rng.below(6) as usize],
    }
}
fn any_vec(rng: &mut Rng) -> Vec3<F> {
    Vec3::new(any_bits(rng), any_bits(rng), any_bits(rng))
}

/// Every constructor and per-sample function of the fixed path on arbitrary bit patterns: no
/// panic (overflow checks are on in this profile), and the normalized models stay in [0, 1]
/// whatever the input (inside the supported ranges the accuracy tests above bound them):
/// the hemisphere family, the exact and Hermite cap and sphere, polygons (Lambert, Phong, the
/// clipped solid angle, every moment and the lune), the line and parallelogram lights, SH9,
/// the superellipse, the falloff, the light frame and `Uberlight`. (Fixed22 answers a subset of
/// the model ids in the eval protocol; every public function must still be total.)
#[test]
fn arbitrary_bit_patterns_never_overflow() {
    let mut rng = Rng::new(0x0f10);
    let unit = |x: F| (0.0..=1.0).contains(&x.to_f64());
    let fin = |x: F| x.is_finite();
    let mut accepted = [0usize; 10];
    for i in 0..100_000 {
        let (a, b, c) = (any_vec(&mut rng), any_vec(&mut rng), any_vec(&mut rng));
        let (s, t) = (any_bits(&mut rng), any_bits(&mut rng));
        let lobe = PhongLobe::<F>::new(rng.below(256) as u32).unwrap();
        if let Ok(h) = HemisphereLight::new(a) {
            accepted[0] += 1;
            assert!(unit(h.lambert_const(b)) && unit(h.lambert_cos(b)));
            assert!(unit(h.phong_const(&lobe, c)) && unit(h.phong_cos(&lobe, c)));
        }
        let _ = OvercastSky::new(a, s).map(|o| o.lambert(b));
        let _ = SkyGround::new(a, Rgb::splat(s), Rgb::splat(t)).map(|g| g.irradiance(b));
        if let Ok(cap) = CapLight::new(a, s) {
            accepted[1] += 1;
            assert!(unit(cap.lambert_hermite(b)) && unit(cap.phong(&lobe, c)));
            assert!(unit(cap.lambert(b)) && unit(cap.lambert_hermite_cos(b)));
        }
        if let Ok(sph) = SphereLight::new(a, s) {
            accepted[2] += 1;
            assert!(unit(sph.lambert_hermite(b, c)) && unit(sph.phong(&lobe, b, c)));
            assert!(unit(sph.lambert(b, c)));
        }
        // Vertices inside the coordinate limit (others are refused, tested above), as a
        // triangle or a planar parallelogram; p and n arbitrary.
        let small = |rng: &mut Rng| {
            let mut q = || F::from_f64(rng.range(-4.0, 4.0));
            Vec3::new(q(), q(), q())
        };
        let (v0, v1, v2) = (small(&mut rng), small(&mut rng), small(&mut rng));
        let tri = [v0, v1, v2, v2 + (v0 - v1) * F::HALF];
        let k = 3 + (i % 2);
        if let Ok(poly) = PolygonLight::<F, 8>::new(&tri[..k]) {
            accepted[3] += 1;
            let (p, n) = (any_vec(&mut rng), any_vec(&mut rng));
            assert!(unit(poly.lambert(p, n)) && unit(poly.phong(&lobe, p, n)));
            assert!(fin(poly.clipped_solid_angle(p, n)));
            // The moments (raw integrals, not normalized: finite), orders up to 255 (the fixed
            // path's limit).
            let (w, e) = (any_vec(&mut rng), any_vec(&mut rng));
            let mm = rng.below(256) as u32;
            assert!(fin(poly.axial_moment(p, w, mm)));
            assert!(fin(poly.axial_moment_within(p, w, mm, t)));
            assert!(fin(poly.double_axis_moment(p, w, e, mm)));
            assert!(fin(poly.double_axis_moment_within(p, w, e, mm, t)));
            assert!(fin(poly.directional_luminaire(p, n, w, mm)));
            assert!(fin(poly.glossy_reflection(p, n, e, mm)));
            assert!(fin(poly.glossy_transmission(p, n, e, mm)));
            assert!(fin(lune_normalization(w, e, mm)));
        }
        // Line and parallelogram lights: endpoints and edges within the coordinate limit
        // (others are refused), p, n, r arbitrary.
        let (la, lb) = (small(&mut rng), small(&mut rng));
        if let Ok(line) = LineLight::new(la, lb) {
            accepted[6] += 1;
            let (p, n, r) = (any_vec(&mut rng), any_vec(&mut rng), any_vec(&mut rng));
            for d in [
                Decay::Constant,
                Decay::Inverse,
                Decay::InverseSquare,
                Decay::InverseCube,
            ] {
                assert!(fin(line.lambert(p, n, d)));
            }
            assert!(unit(line.phong_peak(&lobe, p, r)));
        }
        let (o, eu, ev) = (small(&mut rng), small(&mut rng), small(&mut rng));
        if let Ok(pg) = ParallelogramLight::new(o, eu, ev) {
            accepted[7] += 1;
            let (p, r) = (any_vec(&mut rng), any_vec(&mut rng));
            assert!(unit(pg.phong_peak(&lobe, p, r)));
        }
        let coeffs: [Rgb<F>; 9] = core::array::from_fn(|_| Rgb::splat(any_bits(&mut rng)));
        if let Ok(sh) = Sh9::new(coeffs) {
            accepted[4] += 1;
            let _ = sh.prepare().irradiance(b);
        }
        if let Ok(d) = Sh9::disc(a, s, Rgb::splat(t)) {
            let _ = d.prepare().irradiance(b);
        }
        if let Ok(e) = Superellipse::new(
            s,
            t,
            any_bits(&mut rng),
            any_bits(&mut rng),
            any_bits(&mut rng),
        ) {
            accepted[5] += 1;
            assert!(unit(e.shape(a)));
        }
        let f: [F; 8] = core::array::from_fn(|_| any_bits(&mut rng));
        if let Ok(d) = DistanceFalloff::new(f[0], f[1], f[2], f[3], f[4], f[5], f[6]) {
            let _ = d.falloff(f[7]);
        }
        // The light frame and Uberlight (a valid shape and falloff, arbitrary frame and point).
        if let Ok(frame) = LightFrame::new(a, b, c) {
            accepted[8] += 1;
            let q = any_vec(&mut rng);
            let _ = frame.to_light(q);
            let shape = Superellipse::new(
                F::from_f64(0.3),
                F::from_f64(0.2),
                F::from_f64(0.5),
                F::from_f64(0.4),
                F::from_f64(rng.range(0.05, 3.0)),
            )
            .unwrap();
            let fo = DistanceFalloff::new(
                F::from_f64(2.0),
                F::ONE,
                F::from_f64(rng.range(0.0, 4.0)),
                F::from_f64(0.5),
                F::from_f64(20.0),
                F::from_f64(0.2),
                F::from_f64(3.0),
            )
            .unwrap();
            let u = Uberlight::new(frame, shape, fo).factor(q).to_f64();
            assert!((0.0..=2.0).contains(&u), "uberlight {u}");
            accepted[9] += 1;
        }
    }
    println!(
        "fixed bit patterns: 100000 rounds; accepted hemisphere {}, cap {}, sphere {}, polygon {}, sh9 {}, superellipse {}, line {}, parallelogram {}, light frame {}, uberlight {}",
        accepted[0], accepted[1], accepted[2], accepted[3], accepted[4], accepted[5],
        accepted[6], accepted[7], accepted[8], accepted[9]
    );
    assert!(accepted.iter().all(|&n| n > 200), "{accepted:?}");
}

#[test]
fn rsqrt_within_bound() {
    let mut rng = Rng::new(0x125);
    let mut xs = random_bits(&mut rng, 1_000_000);
    xs.extend(edge_bits());
    // Exhaustive over the smallest inputs (results near and above MAX).
    xs.extend(1..1 << 16);
    // Exhaustive over [1, 1 + 2^-6) and [3.99, 4) in steps of 1 LSB, where the octave changes.
    xs.extend((1 << 22)..(1 << 22) + (1 << 16));
    xs.extend((4 << 22) - (1 << 16)..(4 << 22));
    let mut worst = (0.0, 0);
    for &b in &xs {
        let x = fx(b);
        let got = x.rsqrt().to_f64();
        let want = if b > 0 {
            (1.0 / x.to_f64().sqrt()).min(F::MAX.to_f64())
        } else {
            0.0
        };
        // Bound: 1 LSB plus 2^-28 relative.
        let e = (got - want).abs() / (LSB + want * 2f64.powi(-28));
        if e > worst.0 {
            worst = (e, b);
        }
    }
    println!(
        "[maxerr] Fixed22 rsqrt: {:.3} in units of (1 LSB + 2^-28 relative) at bits {} (bound 1)",
        worst.0, worst.1
    );
    assert!(worst.0 <= 1.0);
    let (s, r) = fx(4 << 22).sqrt_rsqrt();
    assert_eq!((s.to_f64(), r.to_f64()), (2.0, 0.5));
}

/// `Real::unit_to_u32` (pixel and depth quantization) on every backend: rounding, clamping,
/// NaN, and every one of the depth's 65536 levels reachable in fixed point.
#[test]
fn unit_to_u32_rounds_and_clamps() {
    fn check<T: Real>() {
        for max in [31u32, 63, 255, 65535] {
            assert_eq!(T::ZERO.unit_to_u32(max), 0);
            assert_eq!(T::ONE.unit_to_u32(max), max);
            assert_eq!(T::from_f64(-3.0).unit_to_u32(max), 0);
            assert_eq!(T::from_f64(7.0).unit_to_u32(max), max);
            for k in [1u32, 2, max / 3, max / 2, max - 1] {
                // The centre of level k, and just either side of its rounding boundaries.
                let x = T::from_f64(k as f64 / max as f64);
                assert_eq!(
                    x.unit_to_u32(max),
                    k,
                    "{} level {k} of {max}",
                    core::any::type_name::<T>()
                );
            }
        }
    }
    check::<f64>();
    check::<f32>();
    check::<F>();
    assert_eq!(f32::NAN.unit_to_u32(255), 0);
    assert_eq!(f64::NAN.unit_to_u32(255), 0);
    // Fixed point: each depth level is reached (the old path saturated at 512 levels).
    let mut seen = vec![false; 65536];
    for bits in 0..=(1 << 22) {
        seen[fx(bits).unit_to_u32(65535) as usize] = true;
    }
    assert!(seen.iter().all(|&s| s));
}
