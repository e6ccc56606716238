//! Segment and parallelogram models: `[line_lambert]`, `[line_phong_peak]`, `[rect_phong_peak]`.
//!
//! - `[line_lambert]` is not normalized (it scales as `length^-k`), so every error is measured
//!   relative to `max(1, |I|)`: absolute below 1, relative above. f64 against an independent
//!   adaptive Gauss-Kronrod quadrature (`tests/common/line_quadrature.rs`) within its rows of
//!   the f64 budget (`F64_BUDGET` in tests/common: one for p within 1e-2 to 1e-6 lengths of a
//!   rotated segment, where f64's own rounding of `a - p` dominates, one for the rest), on
//!   random and adversarial configurations for k = 0..3; f32 and Fast32 against f64 on the same
//!   f32-rounded inputs, per regime (`Bounded` in tests/common: 2e-6 and 1/1024 in the main
//!   regime; f32 near the segment and where the f64 model itself moves under one-ULP changes of
//!   the f32 inputs held to its extra terms, both capped at `BOUND_CAP`, the unresolved cases
//!   reported).
//! - The peaks against a brute-force search (dense sampling plus golden-section refinement)
//!   within their rows of the f64 budget; f32 / Fast32 against f64 as above.
//! - The peak against the Phong integral it stands for (`[phong_polygon]` of the same
//!   parallelogram): a table of `[maxerr]` lines for m in {1, 8, 32, 128}.
//! - Invalid and adversarial inputs (NaN, infinity, huge, subnormal): no panic, no NaN.

mod common;
#[path = "common/line_quadrature.rs"]
mod lq;
#[path = "common/peak_cases.rs"]
mod peak_cases;

use arealight::{
    Decay, Error, Fast32, LineLight, ParallelogramLight, PhongLobe, PolygonLight, Real, Vec3,
};
use common::*;
use peak_cases::*;

// ---------------------------------------------------------------------------------------------
// Cases
// ---------------------------------------------------------------------------------------------

#[derive(Clone, Debug)]
struct LineCase {
    a: V3,
    b: V3,
    p: V3,
    n: V3,
    k: u32,
    kind: &'static str,
}

impl LineCase {
    fn describe(&self) -> String {
        format!(
            "[{}] k={} a={:?} b={:?} p={:?} n={:?}",
            self.kind, self.k, self.a, self.b, self.p, self.n
        )
    }
}

/// Geometries (a, b, p, n, kind); each is used with every k.
fn line_geometries(rng: &mut Rng) -> Vec<(V3, V3, V3, V3, &'static str)> {
    let mut g = Vec::new();
    // Random.
    for _ in 0..150 {
        let (a, b, p) = (rbox(rng, 2.0), rbox(rng, 2.0), rbox(rng, 2.0));
        g.push((a, b, p, rng.sdir(), "random"));
    }
    // The tangent plane through p crosses the segment at t*.
    for i in 0..80 {
        let (a, b, p) = (rbox(rng, 2.0), rbox(rng, 2.0), rbox(rng, 2.0));
        let t = [0.02, 0.5, 0.98, 1e-6, 1.0 - 1e-6][i % 5];
        let t = if i % 10 < 5 { t } else { rng.range(0.0, 1.0) };
        let q = add(a, scale(sub(b, a), t));
        let nn = normalize(cross(sub(q, p), rng.dir()));
        let nn = if i % 2 == 0 { nn } else { scale(nn, -1.0) };
        g.push((a, b, p, nn, "horizon crossing"));
    }
    // Close to the segment (rotated: h/len >= 1e-6, where f64 input rounding is below 1e-10),
    // with the horizon through or near the foot.
    for &rel in &[1e-2, 1e-4, 1e-6] {
        for _ in 0..8 {
            let (a, b) = (rbox(rng, 2.0), rbox(rng, 2.0));
            let d = sub(b, a);
            let len = norm(d);
            let e = scale(d, 1.0 / len);
            let t = rng.range(0.05, 0.95);
            let perp = rperp(rng, e);
            let p = add(add(a, scale(d, t)), scale(perp, rel * len));
            g.push((a, b, p, rng.dir(), "close to the segment"));
            // The horizon through a point within a few h of the foot.
            let off = rng.range(-5.0, 5.0) * rel * len;
            let q = add(add(a, scale(d, t)), scale(e, off));
            let nn = normalize(cross(sub(q, p), rng.dir()));
            g.push((a, b, p, nn, "close, horizon near the foot"));
        }
    }
    // Extremely close, in an axis-aligned frame where the geometry is exact in f64 and f32.
    for &h in &[1e-7, 1e-9, 1e-12] {
        for &x in &[0.3, -0.999, 1.999] {
            let (a, b) = ([-1.0, 0.0, 0.0], [2.0, 0.0, 0.0]);
            let p = [x, h, 0.0];
            g.push((a, b, p, [0.3, 0.9, -0.2], "very close (exact frame)"));
            g.push((a, b, p, [0.5, 0.0, 0.1], "very close (exact frame)"));
            g.push((a, b, p, [0.0, 1.0, 0.0], "very close (exact frame)"));
        }
        // Just beyond an end, nearly on the line.
        let p = [2.0 + h, h, 0.0];
        g.push((
            [-1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            p,
            [-1.0, 0.1, 0.3],
            "close to an end (exact frame)",
        ));
        let p = [-1.0 - h, 0.0, h];
        g.push((
            [-1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            p,
            [1.0, 0.2, 0.5],
            "close to an end (exact frame)",
        ));
    }
    // Close to an end point (rotated).
    for &rel in &[1e-3, 1e-6] {
        for _ in 0..6 {
            let (a, b) = (rbox(rng, 2.0), rbox(rng, 2.0));
            let len = norm(sub(b, a));
            let p = add(a, scale(rng.dir(), rel * len));
            g.push((a, b, p, rng.dir(), "close to an end"));
        }
    }
    // Nearly collinear: p near the line's extension, at distance eps off it.
    for &eps in &[0.0, 1e-15, 1e-11, 1e-7, 1e-3] {
        for _ in 0..4 {
            let e = rng.dir();
            let c = rbox(rng, 1.0);
            let s0 = [0.1, 1.0, 30.0][rng.below(3) as usize];
            let s1 = s0 * [1.001, 2.0, 50.0][rng.below(3) as usize];
            let sign = if rng.below(2) == 0 { 1.0 } else { -1.0 };
            let (a, b) = (add(c, scale(e, sign * s0)), add(c, scale(e, sign * s1)));
            let p = add(c, scale(rperp(rng, e), eps * s0));
            g.push((a, b, p, rng.dir(), "nearly collinear"));
            g.push((a, b, p, scale(e, sign), "nearly collinear"));
            g.push((b, a, p, rperp(rng, e), "nearly collinear"));
        }
    }
    // Long segments: p near the middle, near an end, beyond an end.
    for &len in &[1e3, 1e6] {
        for _ in 0..5 {
            let e = rng.dir();
            let c = rbox(rng, 1.0);
            let (a, b) = (add(c, scale(e, -0.5 * len)), add(c, scale(e, 0.5 * len)));
            let perp = rperp(rng, e);
            for (off, kind) in [
                (0.0, "long, p near the middle"),
                (0.5 * len - 2.0, "long, p near an end"),
                (0.5 * len + 3.0, "long, p beyond an end"),
            ] {
                let p = add(add(c, scale(e, off)), scale(perp, rng.range(0.5, 2.0)));
                g.push((a, b, p, rng.dir(), kind));
            }
        }
    }
    // Short segments far away (the point-light limit).
    for &(len, dist) in &[(1e-3, 1.0), (1e-6, 10.0), (1.0, 1e4), (1e-9, 1.0)] {
        for _ in 0..4 {
            let a = rbox(rng, 1.0);
            let b = add(a, scale(rng.dir(), len));
            let p = add(a, scale(rng.dir(), dist));
            g.push((a, b, p, rng.dir(), "short and far"));
        }
    }
    // Grazing: n (nearly) normal to the plane through p and the segment.
    for &tilt in &[0.0, 1e-9, 1e-5] {
        for _ in 0..5 {
            let (a, b, p) = (rbox(rng, 2.0), rbox(rng, 2.0), rbox(rng, 2.0));
            let nu = normalize(cross(sub(a, p), sub(b, p)));
            let nn = add(nu, scale(rng.dir(), tilt));
            g.push((a, b, p, nn, "grazing"));
        }
    }
    // Symmetric: p on the perpendicular bisector; n along the segment.
    for _ in 0..6 {
        let (a, b) = (rbox(rng, 2.0), rbox(rng, 2.0));
        let e = normalize(sub(b, a));
        let mid = scale(add(a, b), 0.5);
        let p = add(mid, scale(rperp(rng, e), rng.range(0.01, 3.0)));
        g.push((a, b, p, rng.dir(), "symmetric"));
        g.push((a, b, p, e, "n along the segment"));
    }
    // Far from the origin (inputs carry the rounding of large coordinates).
    for _ in 0..10 {
        let off = [1e6, -2e6, 3e5];
        let (a, b, p) = (rbox(rng, 2.0), rbox(rng, 2.0), rbox(rng, 2.0));
        g.push((
            add(a, off),
            add(b, off),
            add(p, off),
            rng.sdir(),
            "translated by 1e6",
        ));
    }
    g
}

fn line_cases(rng: &mut Rng) -> Vec<LineCase> {
    let mut out = Vec::new();
    for (a, b, p, n, kind) in line_geometries(rng) {
        for k in 0..4 {
            out.push(LineCase {
                a,
                b,
                p,
                n,
                k,
                kind,
            });
        }
    }
    out
}

/// [`sensitivity`] with one-ULP f64 perturbations: how much the f64 model moves when every
/// input moves by -1, 0 or +1 f64 ULP (8 deterministic pseudo-random patterns).
fn sensitivity_f64<F: FnMut(&[f64]) -> Option<f64>>(mut f: F, x: &[f64]) -> f64 {
    let Some(f0) = f(x) else {
        return 0.0;
    };
    let step = |v: f64, dir: u64| -> f64 {
        if dir == 1 || v == 0.0 || !v.is_finite() {
            return v;
        }
        let bits = v.to_bits();
        // dir 0: toward zero, dir 2: away from zero.
        f64::from_bits(if dir == 2 { bits + 1 } else { bits - 1 })
    };
    let mut rng = Rng::new(x.iter().fold(7, |h, v| h ^ v.to_bits().rotate_left(17)));
    let mut max = 0.0f64;
    for _ in 0..8 {
        let y: Vec<f64> = x.iter().map(|&v| step(v, rng.below(3))).collect();
        if let Some(fy) = f(&y) {
            max = max.max((fy - f0).abs());
        }
    }
    max
}

/// `Some((length, distance))` when `p` is within `NEAR_FRACTION` of the segment's length of
/// it: the "near boundary" regime of tests/common (there the f32 rounding of `a - p`, relative
/// to `|a - p|`, is `length/distance` times larger relative to the distance that sets the
/// value).
fn near_segment(a: V3, b: V3, p: V3) -> Option<(f64, f64)> {
    let ab = sub(b, a);
    let t = (dot(sub(p, a), ab) / dot(ab, ab)).clamp(0.0, 1.0);
    let dist = norm(sub(p, add(a, scale(ab, t))));
    let size = norm(ab);
    (dist < NEAR_FRACTION * size).then_some((size, dist))
}

/// A low-precision backend may find `p` on the segment where f64 does not: only when `p` is
/// within a few f32 ULPs (relative to the coordinates) of it.
fn assert_on_segment_to_f32_precision(a: V3, b: V3, p: V3, case: &str) {
    let ab = sub(b, a);
    let t = (dot(sub(p, a), ab) / dot(ab, ab)).clamp(0.0, 1.0);
    let dist = norm(sub(p, add(a, scale(ab, t))));
    let size = [a, b, p]
        .iter()
        .flat_map(|x| x.iter())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(
        dist <= 16.0 * EPS_F32 * size,
        "refused as on the segment at distance {dist:e} (size {size:e}): {case}"
    );
}

fn lib_lambert<T: Real>(a: V3, b: V3, p: V3, n: V3, k: u32) -> Result<f64, Error> {
    let light = LineLight::<T>::new(v(a), v(b))?;
    Ok(light.try_lambert(v(p), v(n), Decay::new(k)?)?.to_f64())
}

// ---------------------------------------------------------------------------------------------
// [line_lambert]
// ---------------------------------------------------------------------------------------------

#[test]
fn quadrature_rule_constants() {
    let worst = lq::check_rule();
    println!("[maxerr] line quadrature: G10/K21 constants, worst deviation {worst:.3e}");
    assert!(worst < 1e-14, "{worst:e}");
    // The quadrature on integrals with textbook values: a segment from the foot, n toward it,
    // H = 1, length 1: k = 2 gives 1/sqrt(2), k = 0 gives asinh(1), k = 1 atan(1) = pi/4.
    let (a, b, p, n) = ([0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0; 3], [0.0, 0.0, 1.0]);
    let want = [
        1f64.asinh(),
        std::f64::consts::FRAC_PI_4,
        0.5f64.sqrt(),
        0.0,
    ];
    // k = 3: (s/(2 rho^2) + atan(s)/2) from 0 to 1 = 1/4 + pi/8.
    let want3 = 0.25 + std::f64::consts::PI / 8.0;
    for k in 0..4 {
        let (q, est) = lq::line_lambert(a, b, p, n, k);
        let w = if k == 3 { want3 } else { want[k as usize] };
        println!("    k={k}: quadrature {q:.17e} (estimate {est:.1e}) exact {w:.17e}");
        assert!((q - w).abs() < 1e-15, "k={k}");
    }
}

#[test]
fn lambert_f64_vs_quadrature() {
    let mut rng = Rng::new(0x11e0);
    let cases = line_cases(&mut rng);
    let mut all = MaxErr::new("line_lambert f64 vs quadrature (scaled)");
    let mut close = MaxErr::new(
        "line_lambert f64 vs quadrature (scaled), p within 1e-2 to 1e-6 lengths of a rotated segment",
    );
    let mut by_kind: std::collections::BTreeMap<&str, MaxErr> = Default::default();
    let mut worst_est = 0.0f64;
    let mut count_zero = 0;
    for c in &cases {
        let (q, est) = lq::line_lambert(c.a, c.b, c.p, c.n, c.k);
        let s = q.abs().max(1.0);
        worst_est = worst_est.max(est / s);
        let got = lib_lambert::<f64>(c.a, c.b, c.p, c.n, c.k)
            .unwrap_or_else(|e| panic!("{e}: {}", c.describe()));
        if q == 0.0 {
            count_zero += 1;
        }
        if c.kind.starts_with("close") {
            close.add(got / s, q / s, || c.describe());
        } else {
            all.add(got / s, q / s, || c.describe());
        }
        by_kind
            .entry(c.kind)
            .or_insert_with(|| MaxErr::new(&format!("line_lambert f64 [{}]", c.kind)))
            .add(got / s, q / s, || c.describe());
    }
    for e in by_kind.values() {
        e.report();
    }
    println!(
        "    {} cases ({count_zero} wholly below the horizon); quadrature's worst error estimate {worst_est:.1e} of max(1, |I|)",
        cases.len()
    );
    assert!(
        worst_est <= 1e-13,
        "quadrature did not converge: {worst_est:e}"
    );
    check_all(&[
        (&all, tol_f64("line_lambert")),
        (
            &close,
            tol_f64("line_lambert (p within 1e-2 to 1e-6 lengths of a rotated segment)"),
        ),
    ]);
}

/// `I(lambda * geometry) = lambda^-k I(geometry)` (exact powers of two, so the inputs scale
/// exactly): checks the scaling to working units, including near the overflow and underflow
/// thresholds.
#[test]
fn lambert_scales_as_length_to_the_minus_k() {
    let mut rng = Rng::new(0x11e1);
    let mut worst = 0.0f64;
    for _ in 0..200 {
        let (a, b, p, n) = (
            rbox(&mut rng, 2.0),
            rbox(&mut rng, 2.0),
            rbox(&mut rng, 2.0),
            rng.dir(),
        );
        for k in 0..4u32 {
            let base = lib_lambert::<f64>(a, b, p, n, k).unwrap();
            for e in [-1000i32, -600, -100, 100, 600, 1020] {
                let lam = 2f64.powi(e);
                let got = lib_lambert::<f64>(scale(a, lam), scale(b, lam), scale(p, lam), n, k);
                // lambda^-k I may itself overflow or underflow.
                let want = base * lam.powi(-(k as i32));
                match got {
                    Ok(g) if want.is_finite() && want > 1e-290 => {
                        worst = worst.max(((g - want) / want).abs());
                    }
                    Ok(g) => assert!(g.is_finite() && g >= 0.0),
                    Err(err) => assert!(
                        err == Error::Overflow && (want >= 1e300 || want.is_nan()),
                        "{err}: e={e} k={k} want {want:e}"
                    ),
                }
            }
        }
    }
    println!(
        "[maxerr] line_lambert f64 scaling by 2^-1000..2^1020: max relative deviation {worst:.3e}"
    );
    assert!(worst < 1e-13, "{worst:e}");
}

/// Low-precision backend `T` against f64 on the same rounded inputs, scaled by max(1, |I|).
fn lambert_lowp<T: Real>(name: &str, bounds: LowpBounds) -> Bounded {
    let mut rng = Rng::new(0x11e2);
    let cases = line_cases(&mut rng);
    let mut tr = Bounded::new(name, bounds);
    let mut kinds = ByKind::default();
    for c in &cases {
        let (a, b, p, n) = (rdv::<T>(c.a), rdv::<T>(c.b), rdv::<T>(c.p), rdv::<T>(c.n));
        let Ok(want) = lib_lambert::<f64>(a, b, p, n, c.k) else {
            // Rounding put p on the segment: both backends must refuse.
            assert!(
                lib_lambert::<T>(a, b, p, n, c.k).is_err(),
                "{}",
                c.describe()
            );
            continue;
        };
        let s = want.abs().max(1.0);
        let got = match lib_lambert::<T>(a, b, p, n, c.k) {
            Ok(g) => g,
            Err(Error::PointOnSegment) => {
                assert_on_segment_to_f32_precision(a, b, p, &c.describe());
                continue;
            }
            Err(e) => panic!("{name}: {e} for {}", c.describe()),
        };
        let x = flat(&[a, b, p, n], &[]);
        let sens = sensitivity(
            |y| {
                lib_lambert::<f64>(v3_at(y, 0), v3_at(y, 1), v3_at(y, 2), v3_at(y, 3), c.k)
                    .ok()
                    .map(|w| w / s)
            },
            &x,
        );
        let cond = Cond {
            m: 0,
            sens,
            near: near_segment(a, b, p),
        };
        let (regime, _) = tr.classify(abs_err(got / s, want / s), &cond);
        let bound = tr.add(got / s, want / s, cond, || c.describe());
        kinds.add(
            &format!("{} [{}]", c.kind, regime.label()),
            got / s,
            want / s,
            bound,
        );
    }
    kinds.report(name);
    tr
}

#[test]
fn lambert_f32_and_fast32_vs_f64() {
    let f32s = lambert_lowp::<f32>("line_lambert f32 vs f64 (scaled)", BOUNDS_F32);
    // Fast32: 1/1024 in every regime below the cap (tests/common); where the f32 rounding of the
    // inputs alone moves the value by more, the case is beyond the cap for both backends.
    let fast = lambert_lowp::<Fast32>("line_lambert Fast32 vs f64 (scaled)", BOUNDS_FAST32);
    check_bounded(&[&f32s, &fast]);
}

// ---------------------------------------------------------------------------------------------
// Peaks
// ---------------------------------------------------------------------------------------------

const PEAK_EXPONENTS: [u32; 9] = [0, 1, 2, 8, 32, 128, 1000, 65_536, 1 << 20];

fn lib_line_peak<T: Real>(c: &PeakCase, m: u32) -> Result<f64, Error> {
    let light = LineLight::<T>::new(v(c.g[0]), v(c.g[1]))?;
    Ok(light
        .try_phong_peak(&PhongLobe::new(m)?, v(c.p), v(c.r))?
        .to_f64())
}

fn lib_rect_peak<T: Real>(c: &PeakCase, m: u32) -> Result<f64, Error> {
    let light = ParallelogramLight::<T>::new(v(c.g[0]), v(c.g[1]), v(c.g[2]))?;
    Ok(light
        .try_phong_peak(&PhongLobe::new(m)?, v(c.p), v(c.r))?
        .to_f64())
}

#[test]
fn peaks_f64_vs_brute_force() {
    let mut rng = Rng::new(0x9ea1);
    let mut line = MaxErr::new("line_phong_peak f64 vs brute force, m <= 1000");
    let mut rect = MaxErr::new("rect_phong_peak f64 vs brute force, m <= 1000");
    let mut line_hi = MaxErr::new("line_phong_peak f64 vs brute force, m = 2^16, 2^20");
    let mut rect_hi = MaxErr::new("rect_phong_peak f64 vs brute force, m = 2^16, 2^20");
    let mut ill = MaxErr::new("line_phong_peak f64 vs brute force, h = 1e-9 rotated");
    let mut ill_ratio = 0.0f64;
    for c in segment_peak_cases(&mut rng) {
        let cos = lq::line_max_cos(c.g[0], c.g[1], c.p, c.r);
        for m in PEAK_EXPONENTS {
            let got = lib_line_peak::<f64>(&c, m).unwrap();
            let want = lq::lobe(cos, m);
            if c.kind.starts_with("p within 1e-9") {
                // Held to the peak's f64 tolerance plus 4 times the f64 model's own change
                // under one-ULP (f64) changes of its inputs.
                let x = flat(&[c.g[0], c.g[1], c.p, c.r], &[]);
                let sens = sensitivity_f64(
                    |y| {
                        let cc = PeakCase {
                            g: [v3_at(y, 0), v3_at(y, 1), [0.0; 3]],
                            p: v3_at(y, 2),
                            r: v3_at(y, 3),
                            kind: c.kind,
                        };
                        lib_line_peak::<f64>(&cc, m).ok()
                    },
                    &x,
                );
                let tol = if m > 1000 {
                    tol_f64("line_phong_peak (m = 2^16, 2^20)")
                } else {
                    tol_f64("line_phong_peak")
                };
                ill_ratio = ill_ratio.max((got - want).abs() / (tol + 4.0 * sens));
                ill.add(got, want, || {
                    format!("m={m} sens64={sens:.2e} {}", c.describe())
                });
                continue;
            }
            if m > 1000 {
                line_hi.add(got, want, || format!("m={m} {}", c.describe()));
            } else {
                line.add(got, want, || format!("m={m} {}", c.describe()));
            }
        }
    }
    ill.report();
    println!(
        "    (h = 1e-9 rotated: max err / (f64 tolerance + 4 * f64 sensitivity) = {ill_ratio:.3})"
    );
    assert!(ill_ratio <= 1.0, "{ill_ratio}");
    for c in rect_peak_cases(&mut rng) {
        let cos = lq::rect_max_cos(c.g[0], c.g[1], c.g[2], c.p, c.r);
        for m in PEAK_EXPONENTS {
            let got = lib_rect_peak::<f64>(&c, m).unwrap();
            let tr = if m > 1000 { &mut rect_hi } else { &mut rect };
            tr.add(got, lq::lobe(cos, m), || format!("m={m} {}", c.describe()));
        }
    }
    // At m = 2^16 and 2^20 the brute force's own cos^m carries m times the rounding of its
    // cosine (~1e-10); the library's exp(m ln1p(-v)) does not.
    check_all(&[
        (&line, tol_f64("line_phong_peak")),
        (&rect, tol_f64("rect_phong_peak")),
        (&line_hi, tol_f64("line_phong_peak (m = 2^16, 2^20)")),
        (&rect_hi, tol_f64("rect_phong_peak (m = 2^16, 2^20)")),
    ]);
}

/// Every case is compared: the in-plane parallelogram peak follows the definition (it used
/// to answer 0 in the plane, a jump the low-precision types saw wherever they rounded `p`
/// into the plane, so those cases were skipped).
fn peaks_lowp<T: Real>(name: &str, bounds: LowpBounds) -> (Bounded, Bounded) {
    let mut rng = Rng::new(0x9ea1);
    let mut line = Bounded::new(&format!("line_phong_peak {name} vs f64"), bounds);
    let mut rect = Bounded::new(&format!("rect_phong_peak {name} vs f64"), bounds);
    let rd = |c: &PeakCase| PeakCase {
        g: c.g.map(rdv::<T>),
        p: rdv::<T>(c.p),
        r: rdv::<T>(c.r),
        kind: c.kind,
    };
    for (cases, tr, is_rect) in [
        (segment_peak_cases(&mut rng), &mut line, false),
        (rect_peak_cases(&mut rng), &mut rect, true),
    ] {
        for c in cases.iter().map(rd) {
            let eval64 = |c: &PeakCase, m: u32| {
                if is_rect {
                    lib_rect_peak::<f64>(c, m)
                } else {
                    lib_line_peak::<f64>(c, m)
                }
            };
            for m in [0, 1, 8, 32, 128, 1000] {
                let Ok(want) = eval64(&c, m) else {
                    continue;
                };
                let got = match if is_rect {
                    lib_rect_peak::<T>(&c, m)
                } else {
                    lib_line_peak::<T>(&c, m)
                } {
                    Ok(g) => g,
                    Err(Error::PointOnSegment) if !is_rect => {
                        assert_on_segment_to_f32_precision(c.g[0], c.g[1], c.p, &c.describe());
                        continue;
                    }
                    Err(e) => panic!("{name}: {e} for {}", c.describe()),
                };
                let x = flat(&[c.g[0], c.g[1], c.g[2], c.p, c.r], &[]);
                let sens = sensitivity(
                    |y| {
                        let cc = PeakCase {
                            g: [v3_at(y, 0), v3_at(y, 1), v3_at(y, 2)],
                            p: v3_at(y, 3),
                            r: v3_at(y, 4),
                            kind: c.kind,
                        };
                        eval64(&cc, m).ok()
                    },
                    &x,
                );
                // m = 0 in Cond: the peak's error does not grow with m (no "high m" regime).
                let cond = Cond {
                    m: 0,
                    sens,
                    near: if is_rect {
                        let [o, eu, ev] = c.g;
                        let verts = [o, add(o, eu), add(add(o, eu), ev), add(o, ev)];
                        near_boundary(&verts, c.p)
                    } else {
                        near_segment(c.g[0], c.g[1], c.p)
                    },
                };
                tr.add(got, want, cond, || format!("m={m} {}", c.describe()));
            }
        }
    }
    (line, rect)
}

#[test]
fn peaks_f32_and_fast32_vs_f64() {
    let (l32, r32) = peaks_lowp::<f32>("f32", BOUNDS_F32);
    let (lf, rf) = peaks_lowp::<Fast32>("Fast32", BOUNDS_FAST32);
    check_bounded(&[&l32, &r32, &lf, &rf]);
}

/// How far Picott's peak is from the Phong integral it stands for,
/// `I = ((m + 1)/(2 pi)) integral ((u.r)+)^m du` over the light (`[phong_polygon]` of the same
/// parallelogram, itself checked against quadrature in tests/phong.rs), for lights of a typical
/// size (subtending 0.02 to 0.6 sr) and r within 0.3 rad of the light. A segment has zero solid
/// angle (its integral is 0), so it is compared through a thin rectangle around it (width 1%
/// of the length): the integral goes to 0 with the width, the peak does not.
#[test]
fn peak_versus_integral_table() {
    let mut rng = Rng::new(0x7ab1e);
    struct Row {
        max_abs: f64,
        sum_abs: f64,
        ratios: Vec<f64>,
        max_rel_scaled: f64,
        n: usize,
    }
    let ms = [1u32, 8, 32, 128];
    let mut rows: Vec<Row> = ms
        .iter()
        .map(|_| Row {
            max_abs: 0.0,
            sum_abs: 0.0,
            ratios: Vec::new(),
            max_rel_scaled: 0.0,
            n: 0,
        })
        .collect();
    let mut thin: Vec<(f64, f64)> = vec![(0.0, 0.0); ms.len()];
    for i in 0..300 {
        let size = rng.range(0.3, 1.5);
        let eu = scale(rng.dir(), size);
        let ev = scale(rperp(&mut rng, normalize(eu)), size * rng.range(0.3, 1.0));
        let o = [0.0, 0.0, 0.0];
        let center = scale(add(eu, ev), 0.5);
        let nu = normalize(cross(eu, ev));
        let dist = rng.range(1.5, 4.0);
        let p = add(center, scale(tilt(nu, rng.range(0.0, 1.0), &mut rng), dist));
        let x = add(
            o,
            add(
                scale(eu, rng.range(0.0, 1.0)),
                scale(ev, rng.range(0.0, 1.0)),
            ),
        );
        let r = tilt(normalize(sub(x, p)), rng.range(0.0, 0.3), &mut rng);
        let rect = ParallelogramLight::<f64>::new(v(o), v(eu), v(ev)).unwrap();
        let poly = PolygonLight::<f64, 4>::new(&rect.vertices()).unwrap();
        let omega = poly.clipped_solid_angle(v(p), v(r));
        for (j, &m) in ms.iter().enumerate() {
            let lobe = PhongLobe::new(m).unwrap();
            let peak = rect.phong_peak(&lobe, v(p), v(r));
            let integral = poly.phong(&lobe, v(p), v(r));
            let row = &mut rows[j];
            let d = (peak - integral).abs();
            row.max_abs = row.max_abs.max(d);
            row.sum_abs += d;
            if peak > 1e-6 {
                row.ratios.push(integral / peak);
            }
            // The peak times the lobe's normalization and the solid angle: a small-light
            // estimate of the integral built from the peak.
            let est = peak * (m as f64 + 1.0) * omega / std::f64::consts::TAU;
            if integral > 1e-6 {
                row.max_rel_scaled = row.max_rel_scaled.max((est - integral).abs() / integral);
            }
            row.n += 1;
        }
        // Thin rectangle around a segment (width 1% of the length) for the line peak.
        if i < 100 {
            let (a, b) = (o, eu);
            let w = scale(ev, 0.01 * size / norm(ev));
            let thin_rect = PolygonLight::<f64, 4>::new(&[
                v(sub(a, scale(w, 0.5))),
                v(sub(b, scale(w, 0.5))),
                v(add(b, scale(w, 0.5))),
                v(add(a, scale(w, 0.5))),
            ])
            .unwrap();
            let line = LineLight::<f64>::new(v(a), v(b)).unwrap();
            let rl = tilt(
                normalize(sub(scale(eu, rng.range(0.0, 1.0)), p)),
                rng.range(0.0, 0.1),
                &mut rng,
            );
            for (j, &m) in ms.iter().enumerate() {
                let lobe = PhongLobe::new(m).unwrap();
                let peak = line.phong_peak(&lobe, v(p), v(rl));
                let integral = thin_rect.phong(&lobe, v(p), v(rl));
                thin[j].0 = thin[j].0.max((peak - integral).abs());
                thin[j].1 = thin[j].1.max(integral);
            }
        }
    }
    println!("Picott's peak vs the Phong integral of the same light (300 parallelograms of 0.02-0.6 sr, r within 0.3 rad of the light):");
    for (j, &m) in ms.iter().enumerate() {
        let row = &mut rows[j];
        row.ratios.sort_by(f64::total_cmp);
        let med = row.ratios[row.ratios.len() / 2];
        let (lo, hi) = (row.ratios[0], row.ratios[row.ratios.len() - 1]);
        println!(
            "[maxerr] rect_phong_peak vs phong_polygon, m={m:<3}: max |peak - I| {:.3e}, mean {:.3e}; I/peak median {med:.3e} (range {lo:.2e} to {hi:.2e}); peak (m+1) Omega/(2 pi) vs I: max rel err {:.3e} over {} cases",
            row.max_abs,
            row.sum_abs / row.n as f64,
            row.max_rel_scaled,
            row.n
        );
    }
    for (j, &m) in ms.iter().enumerate() {
        println!(
            "[maxerr] line_phong_peak vs phong_polygon of a 1%-wide rectangle around the segment, m={m:<3}: max |peak - I| {:.3e} (largest I {:.3e}) over 100 cases",
            thin[j].0, thin[j].1
        );
    }
    // The peak is the lobe's maximum, so it bounds the integral's integrand: no assertion on
    // the difference (it is what the table reports); the one invariant: I <= peak * (m+1)
    // Omega/(2 pi) (the integrand is at most the peak over the light).
    for row in &rows {
        assert!(row.n > 0);
    }
}

// ---------------------------------------------------------------------------------------------
// Semantics, invalid and adversarial inputs
// ---------------------------------------------------------------------------------------------

#[test]
fn semantics() {
    let z = Vec3::new(0.0, 0.0, 1.0);
    let line = LineLight::<f64>::new(Vec3::new(-1.0, 0.0, 2.0), Vec3::new(1.0, 0.0, 2.0)).unwrap();
    // Wholly below the horizon.
    assert_eq!(
        line.lambert(Vec3::new(0.0, 0.0, 0.0), -z, Decay::InverseSquare),
        0.0
    );
    // Half clipped: the symmetric segment with n along it gives half the k = 1 integral of
    // (s/rho^2) ... and the two halves sum to the unclipped value with n and -n.
    let p = Vec3::new(0.3, 0.1, 0.0);
    let n = Vec3::new(0.0, 0.0, 1.0);
    for k in 0..4 {
        let d = Decay::new(k).unwrap();
        let nx = Vec3::new(1.0, 0.0, 0.0);
        let both = line.lambert(p, nx, d) + line.lambert(p, -nx, d);
        // (L.n)+ + (L.-n)+ = |L.x|: positive everywhere except at the crossing.
        assert!(both > 0.0);
        assert!(line.lambert(p, n, d) > 0.0);
    }
    // Invalid inputs.
    assert_eq!(
        LineLight::<f64>::new(Vec3::new(1.0, 2.0, 3.0), Vec3::new(1.0, 2.0, 3.0)),
        Err(Error::ZeroLength("segment"))
    );
    assert_eq!(
        LineLight::<f32>::new(Vec3::new(f32::NAN, 0.0, 0.0), z.map32()),
        Err(Error::NotFinite("a"))
    );
    let on = Vec3::new(0.25, 0.0, 2.0);
    assert_eq!(
        line.try_lambert(on, z, Decay::Constant),
        Err(Error::PointOnSegment)
    );
    assert_eq!(
        line.try_lambert(line.a(), z, Decay::Constant),
        Err(Error::PointOnSegment)
    );
    let lobe = PhongLobe::new(8).unwrap();
    assert_eq!(
        line.try_phong_peak(&lobe, on, z),
        Err(Error::PointOnSegment)
    );
    assert_eq!(line.phong_peak(&lobe, on, z), 0.0);
    assert_eq!(
        line.try_lambert(p, Vec3::new(0.0, 0.0, 0.0), Decay::Constant),
        Err(Error::ZeroLength("n"))
    );
    assert_eq!(Decay::new(4), Err(Error::DecayOutOfRange));
    // Just beyond the segment, on its line: valid.
    let beyond = Vec3::new(1.5, 0.0, 2.0);
    assert!(
        line.try_lambert(beyond, Vec3::new(-1.0, 0.0, 0.0), Decay::Inverse)
            .unwrap()
            > 0.0
    );
    // m = 0: 1 if any point is in front of the plane normal to r, else 0.
    let l0 = PhongLobe::new(0).unwrap();
    assert_eq!(
        line.phong_peak(&l0, Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.0, -0.45)),
        1.0
    );
    assert_eq!(
        line.phong_peak(&l0, Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 0.0, -1.0)),
        0.0
    );
    // The closest angular point: r straight at the segment's middle gives 1.
    assert!((line.phong_peak(&lobe, Vec3::new(0.0, 0.0, 0.0), z) - 1.0).abs() < 1e-15);

    // Parallelogram.
    let rect = ParallelogramLight::<f64>::new(
        Vec3::new(-1.0, -1.0, 2.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 2.0, 0.0),
    )
    .unwrap();
    assert_eq!(
        rect.phong_peak(&lobe, Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.2, 0.3, 1.0)),
        1.0
    );
    // In the plane, the definition (the best over the light's points, all seen in the
    // plane): from inside every in-plane direction reaches the light; from outside only those
    // toward it. (Polygon models give 0 there; a peak is not one.)
    let x = Vec3::new(1.0, 0.0, 0.0);
    for (q, r, want) in [
        (Vec3::new(0.0, 0.0, 2.0), x, 1.0),
        (Vec3::new(5.0, 0.0, 2.0), x, 0.0),
        (Vec3::new(5.0, 0.0, 2.0), -x, 1.0),
    ] {
        assert_eq!(
            rect.try_phong_peak(&lobe, q, r),
            Ok(want),
            "p = {q:?}, r = {r:?}"
        );
    }
    // Out of the plane by r's tilt: (cos 0.3)^m from outside, in the plane.
    let tilted = Vec3::new(-0.3f64.cos(), 0.0, 0.3f64.sin());
    let got = rect.phong_peak(&lobe, Vec3::new(5.0, 0.0, 2.0), tilted);
    assert!(
        (got - 0.3f64.cos().powi(lobe.exponent() as i32)).abs() < 1e-13,
        "{got}"
    );
    // Behind: r away from the light.
    assert_eq!(rect.phong_peak(&lobe, Vec3::new(0.0, 0.0, 0.0), -z), 0.0);
    // From the back side it is lit too (two-sided).
    assert_eq!(rect.phong_peak(&lobe, Vec3::new(0.0, 0.0, 4.0), -z), 1.0);
    assert_eq!(
        ParallelogramLight::<f64>::new(z, Vec3::new(1.0, 1.0, 0.0), Vec3::new(2.0, 2.0, 0.0)),
        Err(Error::ZeroArea)
    );
    assert_eq!(
        ParallelogramLight::<f64>::new(z, Vec3::new(0.0, 0.0, 0.0), Vec3::new(2.0, 2.0, 0.0)),
        Err(Error::ZeroArea)
    );
}

trait Map32 {
    fn map32(self) -> Vec3<f32>;
}
impl Map32 for Vec3<f64> {
    fn map32(self) -> Vec3<f32> {
        Vec3::from_f64(self.to_f64())
    }
}

/// Values that break naive code: NaN, infinities, huge, tiny, subnormal, zero.
fn nasty() -> Vec<f64> {
    vec![
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::MAX,
        -f64::MAX,
        1e300,
        -3e38,
        1e-300,
        5e-324,
        -1e-310,
        1e-45,
        0.0,
        -0.0,
        1.0,
        -0.5,
        2.0,
    ]
}

fn adversarial_inputs<T: Real>() {
    let vals = nasty();
    let mut rng = Rng::new(0xbad);
    let pick = |rng: &mut Rng| -> V3 {
        let mut out = [0.0; 3];
        for o in &mut out {
            *o = if rng.below(3) == 0 {
                vals[rng.below(vals.len() as u64) as usize]
            } else {
                rng.range(-2.0, 2.0)
            };
        }
        out
    };
    let lobes: Vec<PhongLobe<T>> = [0u32, 1, 7, 128, 1 << 20]
        .iter()
        .map(|&m| PhongLobe::new(m).unwrap())
        .collect();
    for i in 0..20_000 {
        let (a, b, p, n, c) = (
            pick(&mut rng),
            pick(&mut rng),
            pick(&mut rng),
            pick(&mut rng),
            pick(&mut rng),
        );
        if let Ok(line) = LineLight::<T>::new(v(a), v(b)) {
            for k in 0..4 {
                let d = Decay::new(k).unwrap();
                let x = line.lambert(v(p), v(n), d).to_f64();
                assert!(
                    x.is_finite() && x >= 0.0,
                    "lambert {x} a={a:?} b={b:?} p={p:?} n={n:?} k={k}"
                );
                if let Ok(y) = line.try_lambert(v(p), v(n), d) {
                    assert_eq!(y.to_f64(), x);
                }
            }
            let x = line.phong_peak(&lobes[i % 5], v(p), v(n)).to_f64();
            assert!((0.0..=1.0).contains(&x), "line peak {x}");
        }
        if let Ok(rect) = ParallelogramLight::<T>::new(v(a), v(b), v(c)) {
            let x = rect.phong_peak(&lobes[i % 5], v(p), v(n)).to_f64();
            assert!(
                (0.0..=1.0).contains(&x),
                "rect peak {x} o={a:?} eu={b:?} ev={c:?} p={p:?} r={n:?}"
            );
        }
    }
    // Structured extremes: a huge segment seen from a huge distance, a subnormal segment.
    let big = T::from_f64(1e38);
    let line = LineLight::<T>::new(
        Vec3::new(-big, T::ZERO, T::ZERO),
        Vec3::new(big, T::ZERO, T::ZERO),
    )
    .unwrap();
    for k in 0..4 {
        let x = line.lambert(
            Vec3::new(T::ZERO, big, -big),
            Vec3::new(T::ZERO, -T::ONE, T::ONE),
            Decay::new(k).unwrap(),
        );
        assert!(x.is_finite() && x >= T::ZERO);
        if k == 0 {
            // Scale-free: the same as the unit geometry.
            let unit = LineLight::<T>::new(
                Vec3::new(-T::ONE, T::ZERO, T::ZERO),
                Vec3::new(T::ONE, T::ZERO, T::ZERO),
            )
            .unwrap()
            .lambert(
                Vec3::new(T::ZERO, T::ONE, -T::ONE),
                Vec3::new(T::ZERO, -T::ONE, T::ONE),
                Decay::Constant,
            );
            assert!((x - unit).abs().to_f64() < 1e-5, "{x:?} vs {unit:?}");
        }
    }
}

#[test]
fn adversarial_inputs_never_panic_or_give_nan() {
    adversarial_inputs::<f64>();
    adversarial_inputs::<f32>();
    adversarial_inputs::<Fast32>();
}

/// `[rect_phong_peak]` with p in the parallelogram's plane, outside it: the definition (the
/// largest `((u.r)+)^m` over the light's points) holds there too; it is not a polygon model's
/// degenerate case (a peak has a value wherever some point of the light is seen: in the plane
/// every direction toward the light lies in the plane). The case: p = (3, 0, 2),
/// r = (-1, 0.2, 0), origin (-1, -1, 2), eu = (2, 0, 0), ev = (0, 2, 0), m = 8 gives 1 (r
/// points at the light); then random in-plane configurations against the brute force.
#[test]
fn rect_peak_in_plane_follows_the_definition() {
    let light = ParallelogramLight::<f64>::new(
        Vec3::new(-1.0, -1.0, 2.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 2.0, 0.0),
    )
    .unwrap();
    let lobe = PhongLobe::<f64>::new(8).unwrap();
    let got = light.phong_peak(&lobe, Vec3::new(3.0, 0.0, 2.0), Vec3::new(-1.0, 0.2, 0.0));
    assert_eq!(got, 1.0, "the issue's case");
    let mut rng = Rng::new(0x1a7e);
    let mut e = MaxErr::new("rect_phong_peak f64 vs brute force, p in the plane (outside)");
    for _ in 0..200 {
        let o = rbox(&mut rng, 2.0);
        let eu = scale(rng.dir(), rng.range(0.3, 2.0));
        let ev = scale(
            normalize(cross(cross(eu, rng.dir()), eu)),
            rng.range(0.3, 2.0),
        );
        let nu = normalize(cross(eu, ev));
        // p in the plane, outside: beyond an edge or a corner.
        let (s, t) = match rng.below(3) {
            0 => (rng.range(1.2, 3.0), rng.range(0.0, 1.0)),
            1 => (rng.range(-2.0, -0.2), rng.range(-2.0, 3.0)),
            _ => (rng.range(1.2, 3.0), rng.range(1.2, 3.0)),
        };
        let p = add(o, add(scale(eu, s), scale(ev, t)));
        // r toward a point of the light (peak 1), or tilted off the plane, or away.
        let x = add(o, add(scale(eu, rng.unit()), scale(ev, rng.unit())));
        let toward = normalize(sub(x, p));
        let r = match rng.below(3) {
            0 => toward,
            1 => normalize(add(toward, scale(nu, rng.range(-0.5, 0.5)))),
            _ => rng.dir(),
        };
        let cos = lq::rect_max_cos(o, eu, ev, p, r);
        let pl = ParallelogramLight::<f64>::new(v(o), v(eu), v(ev)).unwrap();
        for m in [0u32, 1, 8, 128] {
            let got = pl.phong_peak(&PhongLobe::new(m).unwrap(), v(p), v(r));
            e.add(got, lq::lobe(cos, m), || {
                format!("m={m} o={o:?} eu={eu:?} ev={ev:?} p={p:?} r={r:?}")
            });
        }
    }
    e.check(tol_f64("rect_phong_peak"));
}
