//! The fixed-point backend [`Fixed22`]: its elementary functions against f64 (10^6 random
//! inputs plus every edge input, and exhaustive sweeps of the reduced domains), and every
//! model in its scope against f64 on the same (fixed-rounded) inputs, within 1/1024.
//!
//! This file runs in the test profile, which has overflow checks on: an overflow anywhere in
//! the fixed path (the kernels' `i64` arithmetic included) panics and fails the test.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod common;

use arealight::{
    lune_normalization, CapLight, Decay, DistanceFalloff, Fixed22, HemisphereLight, LightFrame,
    LineLight, OvercastSky, ParallelogramLight, PhongLobe, PolygonLight, Real, Rgb, Sh9, SkyGround,
    SphereLight, Superellipse, Uberlight, Vec3,
};
use common::*;
use std::f64::consts::{FRAC_PI_2, PI};

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
// Models, against f64 on the same fixed-rounded inputs.
// ---------------------------------------------------------------------------------------------

/// Runs `f` for Fixed22 and f64 on the same inputs and tracks the max error; `None` from the
/// f64 side (an input the model rejects) skips the case, `None` from the fixed side while f64
/// accepts fails.
struct Track {
    e: MaxErr,
    cases: usize,
}
impl Track {
    fn new(name: &str) -> Self {
        Track {
            e: MaxErr::new(name),
            cases: 0,
        }
    }
    fn add<D: Fn() -> String>(&mut self, got: Option<f64>, want: Option<f64>, d: D) {
        let Some(want) = want else { return };
        let Some(got) = got else {
            panic!(
                "{}: fixed rejected a case f64 accepts: {}",
                self.e.name,
                d()
            );
        };
        self.cases += 1;
        self.e.add(got, want, d);
    }
    fn finish(self) {
        println!("{}: {} cases", self.e.name, self.cases);
        self.e.report();
        assert!(self.cases > 0);
        self.e.check(TOL);
    }
}

fn dirs(rng: &mut Rng, count: usize) -> Vec<V3> {
    let mut out: Vec<V3> = (0..count).map(|_| rng.sdir()).collect();
    for a in [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] {
        out.push(a);
        out.push(scale(a, -1.0));
    }
    out
}

#[test]
fn hemisphere_family_within_tolerance() {
    let mut rng = Rng::new(0x4e31);
    let mut hc = Track::new("hemi_const Fixed22 vs f64");
    let mut hcos = Track::new("hemi_cos Fixed22 vs f64");
    let mut sky = Track::new("sky_overcast Fixed22 vs f64");
    let mut sg = Track::new("sky_ground Fixed22 vs f64");
    let ns = dirs(&mut rng, 20_000);
    for (i, &n) in ns.iter().enumerate() {
        let axis = if i % 3 == 0 {
            // Grazing: n within 1e-3 .. 1e-7 of the horizon.
            let a = rng.dir();
            let w = FRAC_PI_2 + rng.range(-1e-3, 1e-3);
            let _ = a;
            rng.dir_at(normalize(n), w)
        } else {
            rng.sdir()
        };
        let (n, axis) = (rdv::<F>(n), rdv::<F>(axis));
        fn hemi<T: Real>(axis: V3, n: V3, cos: bool) -> Option<f64> {
            let l = HemisphereLight::<T>::new(v(axis)).ok()?;
            Some(
                if cos {
                    l.lambert_cos(v(n))
                } else {
                    l.lambert_const(v(n))
                }
                .to_f64(),
            )
        }
        let d = || format!("axis={axis:?} n={n:?}");
        hc.add(hemi::<F>(axis, n, false), hemi::<f64>(axis, n, false), d);
        hcos.add(hemi::<F>(axis, n, true), hemi::<f64>(axis, n, true), d);
        let c = rd::<F>(rng.range(0.0, 4.0));
        fn overcast<T: Real>(z: V3, c: f64, n: V3) -> Option<f64> {
            let s = OvercastSky::<T>::new(v(z), T::from_f64(c)).ok()?;
            Some(s.lambert(v(n)).to_f64())
        }
        sky.add(overcast::<F>(axis, c, n), overcast::<f64>(axis, c, n), d);
        let (s, g) = (
            rdv::<F>([rng.unit(), rng.unit(), rng.unit()]),
            rdv::<F>([rng.unit(), rng.unit(), rng.unit()]),
        );
        fn skyground<T: Real>(up: V3, s: V3, g: V3, n: V3) -> Option<f64> {
            let l = SkyGround::<T>::new(v(up), rgb(s), rgb(g)).ok()?;
            let e = l.irradiance(v(n));
            Some(e.r.to_f64().max(e.g.to_f64()).max(e.b.to_f64()))
        }
        fn skyground_err<T: Real>(up: V3, s: V3, g: V3, n: V3) -> Option<[f64; 3]> {
            let l = SkyGround::<T>::new(v(up), rgb(s), rgb(g)).ok()?;
            let e = l.irradiance(v(n));
            Some([e.r.to_f64(), e.g.to_f64(), e.b.to_f64()])
        }
        let _ = skyground::<f64>;
        if let (Some(a), Some(b)) = (
            skyground_err::<F>(axis, s, g, n),
            skyground_err::<f64>(axis, s, g, n),
        ) {
            for k in 0..3 {
                sg.add(Some(a[k]), Some(b[k]), d);
            }
        }
    }
    for t in [hc, hcos, sky, sg] {
        t.finish();
    }
}

/// The cap and sphere lights against f64 on the same random and adversarial cases:
/// Snyder's Hermite approximations, or (`exact`) the exact models (`cap_lambert`,
/// `sphere_lambert`: measured 1.4e-6 and 8.4e-5 here, 2.4e-6 and 1.2e-4 over 200 000 random
/// cases each while probing), all within 1/1024.
fn cap_and_sphere_within_tolerance(seed: u64, exact: bool) {
    let name = |m: &str| format!("{m}{} Fixed22 vs f64", if exact { "" } else { "_hermite" });
    let mut rng = Rng::new(seed);
    let mut cap = Track::new(&name("cap_lambert"));
    for (axis, sigma, n) in cap_cases(&mut rng, 20_000) {
        let (axis, n, sigma) = (rdv::<F>(axis), rdv::<F>(n), rd_max::<F>(sigma, FRAC_PI_2));
        fn f<T: Real>(axis: V3, sigma: f64, n: V3, exact: bool) -> Option<f64> {
            let c = CapLight::<T>::new(v(axis), T::from_f64(sigma)).ok()?;
            Some(
                if exact {
                    c.lambert(v(n))
                } else {
                    c.lambert_hermite(v(n))
                }
                .to_f64(),
            )
        }
        cap.add(
            f::<F>(axis, sigma, n, exact),
            f::<f64>(axis, sigma, n, exact),
            || format!("axis={axis:?} sigma={sigma} n={n:?}"),
        );
    }
    cap.finish();
    let mut sph = Track::new(&name("sphere_lambert"));
    for (c, r, p, n) in sphere_cases(&mut rng, 20_000) {
        let k = fit_scale(&[c, p, [r, 0.0, 0.0]]);
        let (c, r, p) = (scale(c, k), r * k, scale(p, k));
        let (c, r, p, n) = (rdv::<F>(c), rd::<F>(r), rdv::<F>(p), rdv::<F>(n));
        fn f<T: Real>(c: V3, r: f64, p: V3, n: V3, exact: bool) -> Option<f64> {
            let s = SphereLight::<T>::new(v(c), T::from_f64(r)).ok()?;
            let got = if exact {
                s.try_lambert(v(p), v(n))
            } else {
                s.try_lambert_hermite(v(p), v(n))
            };
            got.ok().map(|x| x.to_f64())
        }
        sph.add(
            f::<F>(c, r, p, n, exact),
            f::<f64>(c, r, p, n, exact),
            || format!("c={c:?} r={r} p={p:?} n={n:?}"),
        );
    }
    sph.finish();
}

#[test]
fn cap_and_sphere_hermite_within_tolerance() {
    cap_and_sphere_within_tolerance(0xca9, false);
}

/// The exact models are in the fixed path's supported list on the strength of this test.
#[test]
fn cap_and_sphere_exact_within_tolerance() {
    cap_and_sphere_within_tolerance(0xca9e, true);
}

#[test]
fn sh9_within_tolerance() {
    let mut rng = Rng::new(0x5e9);
    let mut env = Track::new("sh9_irradiance Fixed22 vs f64");
    let mut disc = Track::new("sh9_disc_irradiance Fixed22 vs f64");
    let ns = dirs(&mut rng, 20_000);
    for (i, &n) in ns.iter().enumerate() {
        let n = rdv::<F>(n);
        // Random radiance coefficients of magnitude <= 1 (band 0 positive).
        let coeffs: Vec<V3> = (0..9)
            .map(|k| {
                let lo = if k == 0 { 0.0 } else { -1.0 };
                rdv::<F>([rng.range(lo, 1.0), rng.range(lo, 1.0), rng.range(lo, 1.0)])
            })
            .collect();
        fn e<T: Real>(coeffs: &[V3], n: V3) -> Option<[f64; 3]> {
            let c: [Rgb<T>; 9] = core::array::from_fn(|k| rgb(coeffs[k]));
            let x = Sh9::new(c).ok()?.prepare().irradiance(v(n));
            Some([x.r.to_f64(), x.g.to_f64(), x.b.to_f64()])
        }
        if let (Some(a), Some(b)) = (e::<F>(&coeffs, n), e::<f64>(&coeffs, n)) {
            for k in 0..3 {
                env.add(Some(a[k]), Some(b[k]), || {
                    format!("coeffs={coeffs:?} n={n:?}")
                });
            }
        }
        let axis = rdv::<F>(rng.sdir());
        let alpha = if i % 4 == 0 {
            [0.0, 1e-3, FRAC_PI_2, PI][i / 4 % 4]
        } else {
            rng.range(0.0, PI)
        };
        let alpha = rd_max::<F>(alpha, PI);
        fn d<T: Real>(axis: V3, alpha: f64, n: V3) -> Option<f64> {
            let s = Sh9::<T>::disc(v(axis), T::from_f64(alpha), Rgb::splat(T::ONE)).ok()?;
            Some(s.prepare().irradiance(v(n)).r.to_f64())
        }
        disc.add(d::<F>(axis, alpha, n), d::<f64>(axis, alpha, n), || {
            format!("axis={axis:?} alpha={alpha} n={n:?}")
        });
    }
    env.finish();
    disc.finish();
}

/// Polygon cases inside the fixed path's supported range: the shading point at least
/// `MIN_REL_DIST` of the polygon's size from its boundary (closer, the model's derivative
/// `~ size/dist` times the `2^-22` rounding of the direction vectors exceeds the budget; see
/// the module docs of `real::fixed22`).
const MIN_REL_DIST: f64 = 1.0 / 256.0;

fn in_fixed_range(c: &PolyCase) -> bool {
    let verts: Vec<V3> = c.verts.iter().map(|&x| rdv::<F>(x)).collect();
    boundary_distance(&verts, rdv::<F>(c.p)) >= MIN_REL_DIST * diameter(&verts)
}

fn polygon_cases(rng: &mut Rng) -> (Vec<PolyCase>, usize) {
    let mut cases = random_polygons(rng, 10_000);
    cases.extend(adversarial_polygons(rng));
    for c in &mut cases {
        let mut pts = c.verts.clone();
        pts.push(c.p);
        let k = fit_scale(&pts);
        c.verts = c.verts.iter().map(|&x| scale(x, k)).collect();
        c.p = scale(c.p, k);
    }
    let all = cases.len();
    cases.retain(in_fixed_range);
    (cases, all)
}

#[test]
fn polygon_lambert_within_tolerance() {
    let mut rng = Rng::new(0x9013);
    let (cases, all) = polygon_cases(&mut rng);
    let mut t = Track::new("polygon_lambert Fixed22 vs f64");
    let mut by = ByKind::default();
    for c in &cases {
        let verts: Vec<V3> = c.verts.iter().map(|&x| rdv::<F>(x)).collect();
        let (p, n) = (rdv::<F>(c.p), rdv::<F>(c.k));
        fn f<T: Real>(verts: &[V3], p: V3, n: V3) -> Option<f64> {
            let vs: Vec<Vec3<T>> = verts.iter().map(|&x| v(x)).collect();
            let l = PolygonLight::<T, 16>::new(&vs).ok()?;
            l.try_lambert(v(p), v(n)).ok().map(|x| x.to_f64())
        }
        let (got, want) = (f::<F>(&verts, p, n), f::<f64>(&verts, p, n));
        if let (Some(g), Some(w)) = (got, want) {
            by.add(&c.kind, g, w, TOL);
        }
        t.add(got, want, || c.describe());
    }
    by.report("polygon_lambert Fixed22 vs f64 (random + adversarial)");
    println!(
        "polygon_lambert Fixed22: {} of {all} cases in the supported range",
        cases.len()
    );
    t.finish();
}

const EXPONENTS: [u32; 9] = [0, 1, 2, 3, 16, 63, 64, 128, 255];

#[test]
fn phong_hemi_and_cap_within_tolerance() {
    let mut rng = Rng::new(0xf0a9);
    for m in EXPONENTS {
        let mut hc = Track::new(&format!("phong_hemi_const m={m} Fixed22 vs f64"));
        let mut hcos = Track::new(&format!("phong_hemi_cos m={m} Fixed22 vs f64"));
        let mut cap = Track::new(&format!("phong_cap m={m} Fixed22 vs f64"));
        for (axis, sigma, r) in cap_cases(&mut rng, 3000) {
            let (axis, r, sigma) = (rdv::<F>(axis), rdv::<F>(r), rd_max::<F>(sigma, FRAC_PI_2));
            fn h<T: Real>(m: u32, axis: V3, r: V3, cos: bool) -> Option<f64> {
                let l = HemisphereLight::<T>::new(v(axis)).ok()?;
                let lobe = PhongLobe::new(m).ok()?;
                Some(
                    if cos {
                        l.phong_cos(&lobe, v(r))
                    } else {
                        l.phong_const(&lobe, v(r))
                    }
                    .to_f64(),
                )
            }
            fn c<T: Real>(m: u32, axis: V3, sigma: f64, r: V3) -> Option<f64> {
                let l = CapLight::<T>::new(v(axis), T::from_f64(sigma)).ok()?;
                let lobe = PhongLobe::new(m).ok()?;
                Some(l.phong(&lobe, v(r)).to_f64())
            }
            let d = || format!("axis={axis:?} sigma={sigma} r={r:?}");
            hc.add(h::<F>(m, axis, r, false), h::<f64>(m, axis, r, false), d);
            hcos.add(h::<F>(m, axis, r, true), h::<f64>(m, axis, r, true), d);
            cap.add(c::<F>(m, axis, sigma, r), c::<f64>(m, axis, sigma, r), d);
        }
        for t in [hc, hcos, cap] {
            t.finish();
        }
    }
}

#[test]
fn phong_sphere_and_polygon_within_tolerance() {
    let mut rng = Rng::new(0xf0b0);
    let (cases, _) = polygon_cases(&mut rng);
    for m in EXPONENTS {
        let mut sph = Track::new(&format!("phong_sphere m={m} Fixed22 vs f64"));
        for (c, r, p, dir) in sphere_cases(&mut rng, 2000) {
            let k = fit_scale(&[c, p, [r, 0.0, 0.0]]);
            let (c, r, p) = (scale(c, k), r * k, scale(p, k));
            let (c, rad, p, dir) = (rdv::<F>(c), rd::<F>(r), rdv::<F>(p), rdv::<F>(dir));
            fn f<T: Real>(m: u32, c: V3, rad: f64, p: V3, r: V3) -> Option<f64> {
                let s = SphereLight::<T>::new(v(c), T::from_f64(rad)).ok()?;
                let lobe = PhongLobe::new(m).ok()?;
                s.try_phong(&lobe, v(p), v(r)).ok().map(|x| x.to_f64())
            }
            sph.add(
                f::<F>(m, c, rad, p, dir),
                f::<f64>(m, c, rad, p, dir),
                || format!("c={c:?} radius={rad} p={p:?} r={dir:?}"),
            );
        }
        sph.finish();
        let mut poly = Track::new(&format!("phong_polygon m={m} Fixed22 vs f64"));
        for c in cases.iter().step_by(4) {
            let verts: Vec<V3> = c.verts.iter().map(|&x| rdv::<F>(x)).collect();
            let (p, r) = (rdv::<F>(c.p), rdv::<F>(c.k));
            fn f<T: Real>(m: u32, verts: &[V3], p: V3, r: V3) -> Option<f64> {
                let vs: Vec<Vec3<T>> = verts.iter().map(|&x| v(x)).collect();
                let l = PolygonLight::<T, 16>::new(&vs).ok()?;
                let lobe = PhongLobe::new(m).ok()?;
                l.try_phong(&lobe, v(p), v(r)).ok().map(|x| x.to_f64())
            }
            poly.add(f::<F>(m, &verts, p, r), f::<f64>(m, &verts, p, r), || {
                c.describe()
            });
        }
        poly.finish();
    }
    // Beyond the supported exponent the constructor refuses.
    assert_eq!(
        PhongLobe::<F>::new(256),
        Err(arealight::Error::ExponentOutOfRange)
    );
    assert!(PhongLobe::<F>::new(255).is_ok());
}

#[test]
fn shaping_within_tolerance() {
    let mut rng = Rng::new(0x5a9e);
    let mut se = Track::new("superellipse_shape Fixed22 vs f64");
    let mut df = Track::new("distance_falloff Fixed22 vs f64");
    for _ in 0..20_000 {
        let a = rng.range(0.05, 2.0);
        let b = rng.range(0.05, 2.0);
        let (aa, bb) = (a + rng.range(0.01, 1.0), b + rng.range(0.01, 1.0));
        let d = rng.range(0.05, 1.0);
        let s = [a, b, aa, bb, d].map(rd::<F>);
        let pos = rdv::<F>([
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
            rng.range(0.01, 5.0),
        ]);
        fn sh<T: Real>(s: [f64; 5], pos: V3) -> Option<f64> {
            let s = s.map(T::from_f64);
            let e = Superellipse::<T>::new(s[0], s[1], s[2], s[3], s[4]).ok()?;
            Some(e.shape(v(pos)).to_f64())
        }
        se.add(sh::<F>(s, pos), sh::<f64>(s, pos), || {
            format!("shape={s:?} pos={pos:?}")
        });
        let mm = rng.range(1.01, 10.0);
        let d0 = rng.range(0.05, 2.0);
        let alpha = rng.range(0.0, 4.0);
        let znear = rng.range(0.0, 3.0);
        let zfar = znear + rng.range(0.1, 5.0);
        let (ne, fe) = (rng.range(0.05, 1.0), rng.range(0.05, 2.0));
        let z = rng.range(0.0, 12.0);
        let f = [mm, d0, alpha, znear, zfar, ne, fe, z].map(rd::<F>);
        fn fo<T: Real>(f: [f64; 8]) -> Option<f64> {
            let g = f.map(T::from_f64);
            let l = DistanceFalloff::<T>::new(g[0], g[1], g[2], g[3], g[4], g[5], g[6]).ok()?;
            Some(l.falloff(g[7]).to_f64())
        }
        df.add(fo::<F>(f), fo::<f64>(f), || format!("falloff={f:?}"));
    }
    se.finish();
    df.finish();
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
    xs.extend(1..1 << 16); // exhaustive over the smallest inputs (results near and above MAX)
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
