//! The random and adversarial cases of the line and parallelogram peaks
//! (`[line_phong_peak]`, `[rect_phong_peak]`), shared by `tests/line/` (f64, f32, Fast32)
//! and `tests/fixed_line.rs` (Fixed22): the same generators and seeds for every backend.
#![allow(dead_code)]

use crate::common::*;

pub fn rbox(rng: &mut Rng, s: f64) -> V3 {
    [rng.range(-s, s), rng.range(-s, s), rng.range(-s, s)]
}

/// A unit vector perpendicular to the unit `e`, random azimuth.
pub fn rperp(rng: &mut Rng, e: V3) -> V3 {
    let (e1, e2) = frame(e);
    let phi = rng.range(0.0, std::f64::consts::TAU);
    add(scale(e1, phi.cos()), scale(e2, phi.sin()))
}

#[derive(Clone, Debug)]
pub struct PeakCase {
    /// Segment a -> b, or parallelogram (origin, eu, ev).
    pub g: [V3; 3],
    pub p: V3,
    pub r: V3,
    pub kind: &'static str,
}

impl PeakCase {
    pub fn describe(&self) -> String {
        format!(
            "[{}] g={:?} p={:?} r={:?}",
            self.kind, self.g, self.p, self.r
        )
    }
}

/// `r` at angle `w` from the unit `d`.
pub fn tilt(d: V3, w: f64, rng: &mut Rng) -> V3 {
    rotate_toward(d, rperp(rng, d), w)
}

pub fn segment_peak_cases(rng: &mut Rng) -> Vec<PeakCase> {
    let mut out = Vec::new();
    for i in 0..400 {
        let (a, b, p) = (rbox(rng, 2.0), rbox(rng, 2.0), rbox(rng, 2.0));
        let (r, kind) = match i % 5 {
            0 => (rng.sdir(), "random r"),
            1 => {
                let q = add(a, scale(sub(b, a), rng.range(0.0, 1.0)));
                let w = [0.0, 1e-7, 1e-3, 0.05, 0.5][rng.below(5) as usize];
                (tilt(normalize(sub(q, p)), w, rng), "r near the segment")
            }
            2 => {
                let q = add(a, scale(sub(b, a), rng.range(-0.5, 1.5)));
                (
                    normalize(sub(q, p)),
                    "r toward the line, possibly beyond an end",
                )
            }
            3 => {
                let nu = normalize(cross(sub(a, p), sub(b, p)));
                (
                    tilt(nu, rng.range(0.0, 0.2), rng),
                    "r near the arc's normal",
                )
            }
            _ => {
                let q = add(a, scale(sub(b, a), rng.range(0.0, 1.0)));
                (scale(normalize(sub(q, p)), -1.0), "r away from the segment")
            }
        };
        out.push(PeakCase {
            g: [a, b, [0.0; 3]],
            p,
            r,
            kind,
        });
    }
    // p close to the segment, nearly collinear, long segments.
    for _ in 0..40 {
        let (a, b) = (rbox(rng, 2.0), rbox(rng, 2.0));
        let d = sub(b, a);
        let e = normalize(d);
        let t = rng.range(-0.3, 1.3);
        let rel = [1e-6, 1e-3, 0.0, 1e-9][rng.below(4) as usize];
        let p = add(add(a, scale(d, t)), scale(rperp(rng, e), rel * norm(d)));
        if (0.0..=1.0).contains(&t) && rel == 0.0 {
            continue;
        }
        let q = add(a, scale(d, rng.range(0.0, 1.0)));
        let r = tilt(normalize(sub(q, p)), rng.range(0.0, 0.1), rng);
        out.push(PeakCase {
            g: [a, b, [0.0; 3]],
            p,
            r,
            // In a rotated frame the plane through p and the line is known to f64 only to
            // about 1e-16 |a - p|/h: at h = 1e-9 |b - a| the peak at high m moves by more than
            // 1e-9 under one-ULP changes of the inputs (tests below).
            kind: if rel == 1e-9 {
                "p within 1e-9 of the line (rotated)"
            } else {
                "p close to the line"
            },
        });
    }
    // Very close in an axis-aligned frame, where the geometry is exact.
    for i in 0..24 {
        let (a, b) = ([-1.0, 0.0, 0.0], [2.0, 0.0, 0.0]);
        let h = [1e-9, 1e-12][i % 2];
        let x = [0.3, -0.999, 1.999, 2.5][(i / 2) % 4];
        let p = [x, h * 0.6, h * 0.8];
        let q = [rng.range(-1.0, 2.0), 0.0, 0.0];
        let r = tilt(
            normalize(sub(q, p)),
            [0.0, 1e-10, 1e-6, 0.01][(i / 8) % 3],
            rng,
        );
        out.push(PeakCase {
            g: [a, b, [0.0; 3]],
            p,
            r,
            kind: "p very close (exact frame)",
        });
    }
    for _ in 0..20 {
        let e = rng.dir();
        let (a, b) = (scale(e, -1e5), scale(e, 1e5));
        let p = scale(rperp(rng, e), 1.0);
        let r = tilt(rng.dir(), 0.0, rng);
        out.push(PeakCase {
            g: [a, b, [0.0; 3]],
            p,
            r,
            kind: "long segment",
        });
    }
    out
}

pub fn rect_peak_cases(rng: &mut Rng) -> Vec<PeakCase> {
    let mut out = Vec::new();
    for i in 0..300 {
        let o = rbox(rng, 2.0);
        let eu = scale(rng.dir(), rng.range(0.1, 3.0));
        let ev = scale(rng.dir(), rng.range(0.1, 3.0));
        let mut p = rbox(rng, 3.0);
        let q = |s: f64, t: f64| add(o, add(scale(eu, s), scale(ev, t)));
        let (r, kind) = match i % 6 {
            0 => (rng.sdir(), "random r"),
            1 => {
                let x = q(rng.range(0.0, 1.0), rng.range(0.0, 1.0));
                (normalize(sub(x, p)), "r hits the light")
            }
            2 => {
                let x = q(rng.range(-0.3, 1.3), rng.range(-0.3, 1.3));
                let w = [0.0, 1e-6, 1e-3][rng.below(3) as usize];
                (tilt(normalize(sub(x, p)), w, rng), "r near the boundary")
            }
            3 => {
                let x = q(rng.range(1.0, 2.0), rng.range(1.0, 2.0));
                (normalize(sub(x, p)), "r beyond a corner")
            }
            4 => {
                // p near the plane.
                let nu = normalize(cross(eu, ev));
                let x = q(rng.range(-0.5, 1.5), rng.range(-0.5, 1.5));
                p = add(x, scale(nu, [1e-6, 1e-3, 0.1][rng.below(3) as usize]));
                let y = q(rng.range(0.0, 1.0), rng.range(0.0, 1.0));
                (tilt(normalize(sub(y, p)), 0.01, rng), "p near the plane")
            }
            _ => {
                let x = q(rng.range(0.0, 1.0), rng.range(0.0, 1.0));
                (scale(normalize(sub(x, p)), -1.0), "r away from the light")
            }
        };
        out.push(PeakCase {
            g: [o, eu, ev],
            p,
            r,
            kind,
        });
    }
    // Thin parallelograms.
    for _ in 0..30 {
        let o = rbox(rng, 2.0);
        let eu = scale(rng.dir(), 2.0);
        let ev = scale(rng.dir(), 1e-4);
        let p = rbox(rng, 3.0);
        let x = add(o, scale(eu, rng.range(0.0, 1.0)));
        let r = tilt(normalize(sub(x, p)), rng.range(0.0, 1e-3), rng);
        out.push(PeakCase {
            g: [o, eu, ev],
            p,
            r,
            kind: "thin parallelogram",
        });
    }
    out
}
