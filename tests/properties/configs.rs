//! The configurations the properties are drawn on (`planar_poly`, `rigid`) and the generic
//! evaluation helpers: the lights built from f64 inputs rounded to `T`, and `continuous`, the
//! test of continuity across a case boundary.

use super::*;

// ---------------------------------------------------------------------------------------------
// Generic evaluation from f64 inputs (rounded to T on the way in)
// ---------------------------------------------------------------------------------------------

pub(crate) fn hemi<T: Real>(axis: V3) -> HemisphereLight<T> {
    HemisphereLight::new(v(axis)).unwrap()
}
pub(crate) fn cap<T: Real>(axis: V3, sigma: f64) -> CapLight<T> {
    CapLight::new(v(axis), T::from_f64(sigma).min(T::FRAC_PI_2)).unwrap()
}
pub(crate) fn lobe<T: Real>(m: u32) -> PhongLobe<T> {
    PhongLobe::new(m).unwrap()
}
pub(crate) fn poly<T: Real>(verts: &[V3]) -> Option<PolygonLight<T, 8>> {
    let vs: Vec<Vec3<T>> = verts.iter().map(|&x| v(x)).collect();
    PolygonLight::new(&vs).ok()
}

/// A polygon configuration: vertices, shading point, weight axis, and a point of the plane
/// from which the polygon is star-shaped (`None` for the U-shape, which has none).
#[derive(Clone, Debug)]
pub(crate) struct Poly {
    pub(crate) kind: &'static str,
    pub(crate) verts: Vec<V3>,
    pub(crate) p: V3,
    pub(crate) k: V3,
    pub(crate) kernel: Option<V3>,
}

/// A planar polygon made on purpose, of size `size` in `[0.2, 1.5]` (times `scale`, which
/// brings the configuration into the backend's coordinate range), at distance at least 0.3
/// sizes from p = the origin (the well-conditioned regime), in a random plane, with a random
/// weight axis: convex (3 to 8 vertices, the capacity), star-shaped (3 to 8, non-convex),
/// regular stars (3 or 4 spikes: 6 or 8 vertices), L (6) and U (8) shapes, and near-degenerate
/// ones: a sliver (thickness 1e-3 of the size), a vanishing edge (1e-4), a nearly collinear
/// extra vertex (1e-4 off its edge).
pub(crate) fn planar_poly(rng: &mut Rng, scale_to: f64) -> Poly {
    let nv = 3 + rng.below(6) as usize;
    let (kind, mut pts, kernel): (&str, Vec<[f64; 2]>, Option<[f64; 2]>) = match rng.below(8) {
        0 | 1 => (
            "convex",
            (0..nv)
                .map(|j| {
                    let a = TAU * (j as f64 + rng.range(0.0, 0.5)) / nv as f64;
                    [a.cos(), a.sin()]
                })
                .collect(),
            Some([0.0, 0.0]),
        ),
        2 => {
            // Star-shaped about the origin from 4 vertices on (angular gaps below pi); a
            // triangle may leave the origin outside: its vertex average is inside.
            let pts = star_shaped(rng, nv, 0.2);
            let kernel = if nv == 3 {
                [
                    (pts[0][0] + pts[1][0] + pts[2][0]) / 3.0,
                    (pts[0][1] + pts[1][1] + pts[2][1]) / 3.0,
                ]
            } else {
                [0.0, 0.0]
            };
            ("star-shaped", pts, Some(kernel))
        }
        3 => (
            "regular star",
            star(3 + rng.below(2) as usize, rng.range(0.3, 0.7)),
            Some([0.0, 0.0]),
        ),
        4 => ("L-shape", l_shape(), Some([-0.3, -0.3])),
        5 => ("U-shape", u_shape(), None),
        6 => {
            // A sliver: a convex polygon flattened to 1e-3 of its size.
            let pts = (0..nv)
                .map(|j| {
                    let a = TAU * (j as f64 + rng.range(0.0, 0.5)) / nv as f64;
                    [a.cos(), 1e-3 * a.sin()]
                })
                .collect();
            ("sliver", pts, Some([0.0, 0.0]))
        }
        _ => {
            // A vanishing edge or a nearly collinear extra vertex on a convex polygon.
            let n0 = nv.min(7);
            let mut pts: Vec<[f64; 2]> = (0..n0)
                .map(|j| {
                    let a = TAU * (j as f64 + rng.range(0.0, 0.5)) / n0 as f64;
                    [a.cos(), a.sin()]
                })
                .collect();
            let j = rng.below(n0 as u64) as usize;
            let (a, b) = (pts[j], pts[(j + 1) % n0]);
            let kind = if rng.below(2) == 0 {
                pts[j] = [b[0] + 1e-4 * (a[0] - b[0]), b[1] + 1e-4 * (a[1] - b[1])];
                "vanishing edge"
            } else {
                let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                let mid = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
                // Off the edge toward the outside (the polygon stays convex).
                pts.insert(j + 1, [mid[0] + 1e-4 * dy, mid[1] - 1e-4 * dx]);
                "nearly collinear vertex"
            };
            // Still convex (a vertex moved along an edge, or pushed out of one): the vertex
            // average is inside (the origin may not be: a triangle with a vanishing edge is a
            // sliver).
            let n = pts.len() as f64;
            let avg = pts
                .iter()
                .fold([0.0, 0.0], |s, q| [s[0] + q[0] / n, s[1] + q[1] / n]);
            (kind, pts, Some(avg))
        }
    };
    // Convex and star outlines as generated run counter-clockwise; a random winding.
    if rng.below(2) == 0 {
        pts.reverse();
    }
    let size = rng.range(0.2, 1.5);
    let dist = size * rng.range(1.3, 4.0);
    let center = scale(rng.dir(), dist);
    // The same random plane for the outline and the kernel point.
    let mut all = pts.clone();
    all.extend(kernel);
    let placed = place(rng, &all, center, size);
    let kernel = kernel.map(|_| scale(placed[pts.len()], scale_to));
    Poly {
        kind,
        verts: placed[..pts.len()]
            .iter()
            .map(|&x| scale(x, scale_to))
            .collect(),
        p: [0.0; 3],
        k: rng.dir(),
        kernel,
    }
}

/// A random rotation (orthonormal rows) and translation.
pub(crate) fn rigid(rng: &mut Rng) -> ([V3; 3], V3) {
    let a = rng.dir();
    let (b, c) = frame(a);
    ([a, b, c], scale(rng.dir(), rng.range(0.0, 3.0)))
}
pub(crate) fn rot(r: &[V3; 3], x: V3) -> V3 {
    [dot(r[0], x), dot(r[1], x), dot(r[2], x)]
}
pub(crate) fn mv(r: &[V3; 3], t: V3, x: V3) -> V3 {
    add(rot(r, x), t)
}

/// `|a - b|`, infinite for a non-finite operand.
pub(crate) fn diff(a: f64, b: f64) -> f64 {
    abs_err(a, b).max(abs_err(b, a))
}

/// Continuity at `b` to the resolution of the backend: `f` at the `2 N` points
/// `b + (i + 1/2) h`, `i = -N..N`; the step across `b` must be within twice the largest other
/// step (the local slope and the backend's rounding noise, measured around `b`) plus `floor`,
/// the smallest jump detected, far below the backend's accuracy bound: 1e-14 for f64, 1e-6 for
/// f32 (half its bound), 1e-4 for Fast32 and 2e-4 for Fixed22 (a tenth and a fifth of 1/1024).
/// The floors are 4 to 6 times the largest excess `step - 2 x other` measured over 16 384
/// cases per backend (2.2e-16, 1.8e-7, 2.4e-5, 3.6e-5); the step `h` is 1e-4 / (m + 1) (1e-6
/// / (m + 1) for f64), so the slope term stays small at every m. The old check (a step of 1e-2
/// and an allowance of 4/1024 for Fast32 and Fixed22) let a jump of 4e-3 through.
pub(crate) fn continuous(f: &dyn Fn(f64) -> f64, b: f64, h: f64, floor: f64) -> Result<(), String> {
    const N: usize = 4;
    let ys: Vec<f64> = (0..2 * N)
        .map(|i| f(b + (i as f64 - N as f64 + 0.5) * h))
        .collect();
    let steps: Vec<f64> = ys.windows(2).map(|w| diff(w[1], w[0])).collect();
    let cross = steps[N - 1];
    let other = steps
        .iter()
        .enumerate()
        .filter(|&(i, _)| i != N - 1)
        .fold(0.0f64, |m, (_, &d)| if d > m || d.is_nan() { d } else { m });
    if cross <= 2.0 * other + floor {
        Ok(())
    } else {
        Err(format!(
            "step {cross:.3e} across {b} (h {h:e}) > 2 x the largest other step {other:.3e} + \
             {floor:e}: values {ys:?}"
        ))
    }
}
