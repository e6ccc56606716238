//! The parallelogram peak `[rect_phong_peak]` in the fixed-point backend [`Fixed22`] against
//! f64 on the same (fixed-rounded) inputs, absolute error (the peak is in [0, 1]), target
//! 1/1024 as every `Fixed22` row (tests/fixed.rs).
//!
//! Cases: the f32 row's generator of tests/line/ (copied below with the segment cases drawn
//! first from the same seed, so these are the f32 row's parallelograms): r hitting the light,
//! near its boundary, beyond a corner, away, p near the plane, thin parallelograms. Each case
//! is scaled by a power of two into the fixed path's coordinate cube
//! ([`Fixed22::COORDINATE_LIMIT`]; a peak is scale invariant) and kept if p is at least 1/256
//! of the light's size from the light ([`MIN_REL_DIST`], the fixed path's range for every area
//! light, README "Fixed point"); exponents m in {0, 1, 2, 3, 8, 16, 32, 63, 64, 128, 255}.
//! With ten other seeds while probing: within 1.4e-4.
//!
//! Not supported in fixed point (measured on tests/line/'s case sets in the same range):
//! `[line_phong_peak]` 1.0e-4 on these cases but 2.6e-2 at m = 255 with another seed (p near
//! the segment's line beyond an end: the perpendicular `g` of the segment frame, relative to
//! the segment's size, has squared components below 2^-22 and its length vanishes; 8.1e-3
//! remains with that length rescaled, p 1/100 of the length from an end), and
//! `[line_lambert]` (not normalized: its values reach `(size/dist)^k`, beyond the format's 512
//! for k = 2, 3 near the segment, and its k = 3 terms saturate inside; measured relative to
//! max(1, I) as its f32 row: 1.6 at k = 3, 7e-2 on the random set). eval's fixed backend
//! answers them "unsupported".
//!
//! This file runs in the test profile, which has overflow checks on.

mod common;
#[path = "common/peak_cases.rs"]
mod peak_cases;

use arealight::{Error, Fixed22, ParallelogramLight, PhongLobe, Real};
use common::*;
use peak_cases::*;

type F = Fixed22;
const TOL: f64 = 1.0 / 1024.0;
const EXPONENTS: [u32; 11] = [0, 1, 2, 3, 8, 16, 32, 63, 64, 128, 255];

// ---------------------------------------------------------------------------------------------
// Fixed22 against f64
// ---------------------------------------------------------------------------------------------

/// The distance from `p` to the segment `a b`.
fn segment_distance(a: V3, b: V3, p: V3) -> f64 {
    let ab = sub(b, a);
    let t = (dot(sub(p, a), ab) / dot(ab, ab)).clamp(0.0, 1.0);
    norm(sub(p, add(a, scale(ab, t))))
}

/// The distance from `p` to the parallelogram `o + s eu + t ev` (the filled region).
fn parallelogram_distance(g: [V3; 3], p: V3) -> f64 {
    let [o, eu, ev] = g;
    let corners = [o, add(o, eu), add(add(o, eu), ev), add(o, ev)];
    let edges = (0..4)
        .map(|i| segment_distance(corners[i], corners[(i + 1) % 4], p))
        .fold(f64::INFINITY, f64::min);
    // The foot of p inside: its height.
    let (uu, vv, uv) = (dot(eu, eu), dot(ev, ev), dot(eu, ev));
    let x = sub(p, o);
    let (xu, xv) = (dot(x, eu), dot(x, ev));
    let det = uu * vv - uv * uv;
    let (s, t) = ((xu * vv - xv * uv) / det, (xv * uu - xu * uv) / det);
    if (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t) {
        let nn = normalize(cross(eu, ev));
        edges.min(dot(x, nn).abs())
    } else {
        edges
    }
}

/// Shading points at least this fraction of the light's size from the light: the fixed path's
/// documented range for the polygon models (README, "Fixed point"), here for the segment and
/// the parallelogram too. Closer, the rounding of `p` (2^-22 absolute) moves the value by
/// about `2^-22 size/dist` per unit of the model's slope; on the segment or the light's face
/// the models jump (the f32 rows' "unresolved" regime).
const MIN_REL_DIST: f64 = 1.0 / 256.0;

fn lib_rect_peak<T: Real>(c: &PeakCase, m: u32) -> Result<f64, Error> {
    let light = ParallelogramLight::<T>::new(v(c.g[0]), v(c.g[1]), v(c.g[2]))?;
    Ok(light
        .try_phong_peak(&PhongLobe::new(m)?, v(c.p), v(c.r))?
        .to_f64())
}

/// Records one case: f64 refusing skips it (rounding made it invalid for both), the fixed
/// path must then refuse too; fixed refusing a case f64 accepts fails.
fn track(
    e: &mut MaxErr,
    got: Result<f64, Error>,
    want: Result<f64, Error>,
    d: impl Fn() -> String,
) {
    match (got, want) {
        (Ok(g), Ok(w)) => e.add(g, w, d),
        (Err(_), Err(_)) => {}
        (g, w) => panic!("{}: fixed {g:?}, f64 {w:?}: {}", e.name, d()),
    }
}

/// The peak cases of tests/line/ (seed and order as there, so the parallelograms are the
/// f32 row's), scaled into the cube, those in the supported range: segments, parallelograms.
fn peak_cases() -> [(Vec<PeakCase>, usize); 2] {
    let mut rng = Rng::new(0x9ea1);
    let segs = segment_peak_cases(&mut rng);
    let rects = rect_peak_cases(&mut rng);
    [(segs, false), (rects, true)].map(|(cases, is_rect)| {
        let all = cases.len();
        let kept = cases
            .into_iter()
            .map(|c| {
                let [o, eu, ev] = c.g;
                let pts = if is_rect {
                    vec![o, add(o, eu), add(o, ev), add(add(o, eu), ev), c.p]
                } else {
                    vec![o, eu, c.p] // a segment: g = [a, b, 0]
                };
                let s = fit_scale(&pts);
                PeakCase {
                    g: c.g.map(|x| rdv::<F>(scale(x, s))),
                    p: rdv::<F>(scale(c.p, s)),
                    r: rdv::<F>(c.r),
                    kind: c.kind,
                }
            })
            .filter(|c| {
                if is_rect {
                    let [o, eu, ev] = c.g;
                    let size = norm(add(eu, ev)).max(norm(sub(eu, ev)));
                    let _ = o;
                    parallelogram_distance(c.g, c.p) >= MIN_REL_DIST * size
                } else {
                    segment_distance(c.g[0], c.g[1], c.p)
                        >= MIN_REL_DIST * norm(sub(c.g[1], c.g[0]))
                }
            })
            .collect();
        (kept, all)
    })
}

#[test]
fn rect_peak_within_tolerance() {
    let [_, (cases, all)] = peak_cases();
    println!(
        "rect_phong_peak Fixed22: {} of {all} cases in the supported range",
        cases.len()
    );
    let mut trackers = Vec::new();
    for m in EXPONENTS {
        let mut by_kind = std::collections::BTreeMap::<&str, f64>::new();
        let mut e = MaxErr::new(&format!("rect_phong_peak m={m} Fixed22 vs f64"));
        for c in &cases {
            let (got, want) = (lib_rect_peak::<F>(c, m), lib_rect_peak::<f64>(c, m));
            if let (Ok(g), Ok(w)) = (&got, &want) {
                let x = by_kind.entry(c.kind).or_insert(0.0);
                *x = x.max((g - w).abs());
            }
            track(&mut e, got, want, || format!("m={m} {}", c.describe()));
        }
        println!("rect_phong_peak m={m} Fixed22 by kind: {by_kind:?}");
        e.report();
        trackers.push(e);
    }
    for e in &trackers {
        assert!(e.count > 0);
        e.check(TOL);
    }
    // Beyond the format's exponent the lobe refuses.
    assert_eq!(PhongLobe::<F>::new(256), Err(Error::ExponentOutOfRange));
}
