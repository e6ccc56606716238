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

#[path = "../common/mod.rs"]
mod common;
#[path = "../common/line_quadrature.rs"]
mod lq;
#[path = "../common/peak_cases.rs"]
mod peak_cases;

use arealight::{
    Decay, Error, Fast32, LineLight, ParallelogramLight, PhongLobe, PolygonLight, Real, Vec3,
};
use common::*;
use peak_cases::*;

mod peaks;
mod semantics;

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
