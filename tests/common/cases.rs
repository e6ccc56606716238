//! The case generators: cap and sphere configurations, and random, adversarial and edge-on
//! polygons.

use super::*;

// ---------------------------------------------------------------------------------------------
// Cap configurations
// ---------------------------------------------------------------------------------------------

/// Half-angles sigma worth testing: 0, tiny, small, mid, near pi/2, exactly pi/2.
pub fn sigma_grid() -> Vec<f64> {
    vec![
        0.0,
        1e-9,
        1e-6,
        1e-3,
        0.0047,
        0.05,
        PI / 16.0,
        0.3,
        PI / 8.0,
        0.6,
        PI / 4.0,
        1.0,
        3.0 * PI / 8.0,
        1.4,
        FRAC_PI_2 - 1e-3,
        FRAC_PI_2 - 1e-6,
        FRAC_PI_2 - 1e-9,
        FRAC_PI_2,
    ]
}

/// Angles w between the weight axis and the source axis worth testing for a cap of half-angle
/// `sigma`: both ends, the tangencies w = pi/2 +- sigma and just either side, w = sigma
/// (the cap touches the weight axis), pi/2, and a few interior values.
pub fn w_grid(sigma: f64) -> Vec<f64> {
    let mut ws = vec![
        0.0,
        1e-9,
        1e-4,
        0.3,
        1.0,
        FRAC_PI_2,
        2.0,
        2.8,
        PI - 1e-6,
        PI,
    ];
    for c in [FRAC_PI_2 - sigma, FRAC_PI_2 + sigma, sigma] {
        for d in [-1e-3, -1e-7, 0.0, 1e-7, 1e-3] {
            ws.push(c + d);
        }
    }
    ws.retain(|w| (0.0..=PI).contains(w));
    ws
}

/// (axis, sigma, n): the sigma grid x the w grid (tangencies w = pi/2 +- sigma and either
/// side, w = sigma, both ends), random orientation, plus random cases.
pub fn cap_cases(rng: &mut Rng, random: usize) -> Vec<(V3, f64, V3)> {
    let mut out = Vec::new();
    for sigma in sigma_grid() {
        for w in w_grid(sigma) {
            let a = rng.dir();
            let n = rng.dir_at(a, w);
            out.push((rng.stretch(a), sigma, rng.stretch(n)));
        }
    }
    for _ in 0..random {
        let a = rng.dir();
        let n = rng.dir();
        out.push((rng.stretch(a), rng.range(0.0, FRAC_PI_2), n));
    }
    out
}

/// (center, radius, p, n): distances from 1.001 radii (very close) to 1000 radii, n random and
/// at the tangencies of the sphere's cap.
pub fn sphere_cases(rng: &mut Rng, random: usize) -> Vec<(V3, f64, V3, V3)> {
    let mut out = Vec::new();
    let ratios = [1.001, 1.01, 1.2, 2.0, 10.0, 1000.0];
    for (i, &ratio) in ratios.iter().cycle().take(6 * 12).enumerate() {
        let radius = rng.range(0.1, 3.0);
        let center = scale(rng.dir(), rng.range(0.0, 5.0));
        let toward = rng.dir();
        let p = sub(center, scale(toward, ratio * radius));
        let sigma = (1.0 / ratio).asin();
        let w = match i / 6 % 6 {
            0 => FRAC_PI_2 - sigma,
            1 => FRAC_PI_2 + sigma,
            2 => FRAC_PI_2,
            3 => 0.0,
            4 => PI,
            _ => rng.range(0.0, PI),
        };
        let n = rng.dir_at(toward, w);
        out.push((center, radius, p, n));
    }
    for _ in 0..random {
        let radius = rng.range(0.05, 2.0);
        let center = scale(rng.dir(), rng.range(0.0, 3.0));
        let d = radius * (1.0 + rng.range(0.0, 1.0).powi(3) * 20.0) + 1e-3;
        let p = add(center, scale(rng.dir(), d));
        let n = rng.sdir();
        out.push((center, radius, p, n));
    }
    out
}

// ---------------------------------------------------------------------------------------------
// Polygon configurations
// ---------------------------------------------------------------------------------------------

/// A polygon light case: vertices, shading point, and a weight axis (n or r).
#[derive(Clone, Debug)]
pub struct PolyCase {
    pub kind: String,
    pub verts: Vec<V3>,
    pub p: V3,
    pub k: V3,
}

impl PolyCase {
    pub fn describe(&self) -> String {
        format!(
            "{} verts={:?} p={:?} k={:?}",
            self.kind, self.verts, self.p, self.k
        )
    }
}

/// Places 2D outline points in 3D: `center + size (x e1 + y e2)` for a random plane.
pub fn place(rng: &mut Rng, pts: &[[f64; 2]], center: V3, size: f64) -> Vec<V3> {
    let nrm = rng.dir();
    let (e1, e2) = frame(nrm);
    // A random in-plane rotation.
    let t = rng.range(0.0, TAU);
    let (c, s) = (t.cos(), t.sin());
    pts.iter()
        .map(|&[x, y]| {
            let (x, y) = (c * x - s * y, s * x + c * y);
            add(center, scale(add(scale(e1, x), scale(e2, y)), size))
        })
        .collect()
}

/// A random star-shaped (hence simple) outline with `k` vertices; may be non-convex.
pub fn star_shaped(rng: &mut Rng, k: usize, rmin: f64) -> Vec<[f64; 2]> {
    (0..k)
        .map(|j| {
            let a = TAU * (j as f64 + rng.range(0.0, 0.8)) / k as f64;
            let r = rng.range(rmin, 1.0);
            [r * a.cos(), r * a.sin()]
        })
        .collect()
}

/// A regular star with `k` spikes (2k vertices), inner radius `ri`.
pub fn star(k: usize, ri: f64) -> Vec<[f64; 2]> {
    (0..2 * k)
        .map(|j| {
            let a = PI * j as f64 / k as f64;
            let r = if j % 2 == 0 { 1.0 } else { ri };
            [r * a.cos(), r * a.sin()]
        })
        .collect()
}

/// An L-shape (6 vertices, one reflex corner).
pub fn l_shape() -> Vec<[f64; 2]> {
    vec![
        [-0.5, -0.5],
        [0.7, -0.5],
        [0.7, -0.1],
        [-0.1, -0.1],
        [-0.1, 0.6],
        [-0.5, 0.6],
    ]
}

/// A U-shape (8 vertices, two reflex corners): a horizon through the notch clips it into two.
pub fn u_shape() -> Vec<[f64; 2]> {
    vec![
        [-0.6, -0.5],
        [0.6, -0.5],
        [0.6, 0.6],
        [0.3, 0.6],
        [0.3, -0.1],
        [-0.3, -0.1],
        [-0.3, 0.6],
        [-0.6, 0.6],
    ]
}

/// Random polygon cases: random shapes and placements, random weight axis (so most cases cross
/// the horizon somewhere). At most 8 vertices.
pub fn random_polygons(rng: &mut Rng, count: usize) -> Vec<PolyCase> {
    let mut out = Vec::with_capacity(count);
    for i in 0..count {
        let (kind, pts): (&str, _) = match i % 5 {
            0 => ("triangle", star_shaped(rng, 3, 0.3)),
            1 => ("quad", star_shaped(rng, 4, 0.3)),
            2 => ("star-shaped-7", star_shaped(rng, 7, 0.2)),
            3 => ("L-shape", l_shape()),
            _ => ("U-shape", u_shape()),
        };
        let dist = rng.range(0.3, 3.0);
        let center = scale(rng.dir(), dist);
        let size = rng.range(0.2, 2.0);
        let verts = place(rng, &pts, center, size);
        let d = rng.dir();
        let k = rng.stretch(d);
        out.push(PolyCase {
            kind: kind.to_string(),
            verts,
            p: [0.0; 3],
            k,
        });
    }
    out
}

/// Adversarial polygon cases (at most 8 vertices): partly below the horizon (including the
/// horizon through a vertex and through the notch of non-convex shapes), wholly below, nearly
/// edge-on to p (foot outside and inside), p close to a vertex or an edge, stars.
pub fn adversarial_polygons(rng: &mut Rng) -> Vec<PolyCase> {
    let mut out = Vec::new();
    let shapes: Vec<(&'static str, Vec<[f64; 2]>)> = vec![
        ("square", vec![[-1., -1.], [1., -1.], [1., 1.], [-1., 1.]]),
        ("triangle", vec![[-1., -0.7], [1.2, -0.4], [0.1, 1.0]]),
        ("L-shape", l_shape()),
        ("U-shape", u_shape()),
        ("star4", star(4, 0.3)),
    ];
    for (name, pts) in &shapes {
        // The plane z = 1 (normal +z), outline scaled by s, shifted by (ox, oy).
        for &(s, ox, oy) in &[(1.0, 0.0, 0.0), (0.8, 0.9, 0.2), (0.5, 2.5, 0.0)] {
            let verts: Vec<V3> = pts
                .iter()
                .map(|&[x, y]| [ox + s * x, oy + s * y, 1.0])
                .collect();
            // Weight axes: straight at it, tilted so the horizon cuts the polygon at several
            // places, through a vertex, through the notch, edge-on, facing away.
            let mut ks: Vec<V3> = vec![[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]];
            for t in [
                0.3,
                0.7,
                1.2,
                FRAC_PI_2 - 0.05,
                FRAC_PI_2,
                FRAC_PI_2 + 0.2,
                2.5,
            ] {
                for az in [0.0, 0.9, 2.0, 4.0] {
                    ks.push([t.sin() * f64::cos(az), t.sin() * f64::sin(az), t.cos()]);
                }
            }
            // Horizon exactly through vertex 0: k perpendicular to verts[0] (p at origin).
            let v0 = verts[0];
            ks.push(normalize(cross(v0, [0.3, 1.0, 0.2])));
            // Horizon through the polygon's centroid direction along x.
            ks.push([1.0, 0.0, 0.0]);
            ks.push([-1.0, 0.0, 0.0]);
            ks.push([0.0, 1.0, 0.0]);
            for k in ks {
                out.push(PolyCase {
                    kind: format!("{name}, horizon cuts"),
                    verts: verts.clone(),
                    p: [0.0; 3],
                    k,
                });
            }
        }
        // Nearly edge-on: p at height h above the plane z = 1 (relative to size 1).
        for &h in &[1e-2, 1e-4, 1e-6] {
            for &(fx, fy, tag) in &[
                (0.0, 0.0, "foot inside"),
                (1.3, 0.1, "foot outside near edge"),
                (3.0, 2.0, "foot far outside"),
                (1.0 + 1e-3, 0.0, "foot just outside edge"),
            ] {
                let verts: Vec<V3> = pts.iter().map(|&[x, y]| [x, y, 1.0]).collect();
                let p = [fx, fy, 1.0 - h];
                for k in [
                    [0.0, 0.0, 1.0],
                    [0.3, 0.2, 1.0],
                    [1.0, 0.0, 0.05],
                    [-1.0, 0.3, 0.0],
                    [0.0, 0.0, -1.0],
                    [0.2, -1.0, 0.3],
                ] {
                    out.push(PolyCase {
                        kind: format!("{name}, edge-on h={h:e}, {tag}"),
                        verts: verts.clone(),
                        p,
                        k,
                    });
                }
            }
        }
        // p close to a vertex and to an edge midpoint (distance 1e-3).
        let verts: Vec<V3> = pts.iter().map(|&[x, y]| [x, y, 1.0]).collect();
        let mid = scale(add(verts[0], verts[1]), 0.5);
        for p in [
            sub(verts[0], [0.0, 0.0, 1e-3]),
            sub(mid, [0.0, 0.0, 1e-3]),
            sub(verts[1], [1e-3, 1e-3, 1e-3]),
        ] {
            for k in [[0.0, 0.0, 1.0], [0.5, 0.5, 0.7], [1.0, -0.2, 0.0]] {
                out.push(PolyCase {
                    kind: format!("{name}, p near vertex/edge"),
                    verts: verts.clone(),
                    p,
                    k,
                });
            }
        }
    }
    // A random rigid motion of everything, so no case is axis aligned.
    let rot = {
        let a = rng.dir();
        let (b, c) = frame(a);
        [a, b, c]
    };
    let shift = scale(rng.dir(), rng.range(0.0, 5.0));
    let tr = |x: V3| add([dot(rot[0], x), dot(rot[1], x), dot(rot[2], x)], shift);
    let rt = |x: V3| [dot(rot[0], x), dot(rot[1], x), dot(rot[2], x)];
    for c in &mut out {
        c.verts = c.verts.iter().map(|&x| tr(x)).collect();
        c.p = tr(c.p);
        c.k = rt(c.k);
    }
    out
}

/// Extremely edge-on cases: p at height h in {1e-8, 1e-10, 1e-12} (relative to size 1) below
/// the plane of a triangle, a square and an L-shape, the foot inside (and, for the L, in the
/// notch), with weight axes tilted so the horizon cuts the projection (f64 only: rounding the
/// inputs to f32 moves p by more than h).
pub fn extreme_edge_on(rng: &mut Rng) -> Vec<PolyCase> {
    let shapes: Vec<(&'static str, Vec<[f64; 2]>)> = vec![
        ("triangle", vec![[-1., -0.7], [1.2, -0.4], [0.1, 1.0]]),
        ("square", vec![[-1., -1.], [1., -1.], [1., 1.], [-1., 1.]]),
        ("L-shape", l_shape()),
    ];
    let mut out = Vec::new();
    for (name, pts) in &shapes {
        let verts: Vec<V3> = pts.iter().map(|&[x, y]| [x, y, 1.0]).collect();
        for &h in &[1e-8, 1e-10, 1e-12] {
            for foot in [[0.05, 0.02], [-0.3, -0.3], [0.2, 0.3]] {
                for k in [
                    [0.6, -0.2, 0.8],
                    [1.0, 0.3, 0.01],
                    [0.2, 1.0, -0.3],
                    [0.0, 0.0, 1.0],
                ] {
                    out.push(PolyCase {
                        kind: format!("{name}, h={h:e}"),
                        verts: verts.clone(),
                        p: [foot[0], foot[1], 1.0 - h],
                        k,
                    });
                }
            }
        }
    }
    // A random rotation about the origin (kept small in size so h stays representable).
    let rot = {
        let a = rng.dir();
        let (b, c) = frame(a);
        [a, b, c]
    };
    let rt = |x: V3| [dot(rot[0], x), dot(rot[1], x), dot(rot[2], x)];
    for c in &mut out {
        c.verts = c.verts.iter().map(|&x| rt(x)).collect();
        c.p = rt(c.p);
        c.k = rt(c.k);
    }
    out
}

/// `PI` re-exported for brevity in test files.
pub const PI_: f64 = PI;

/// The power of two that brings every coordinate of `pts` within `Fixed22`'s
/// `COORDINATE_LIMIT` (exact in f64; the area-light models are scale invariant, so the scaled
/// case is the same case for the model): the fixed-point tests' way into the cube.
pub fn fit_scale(pts: &[V3]) -> f64 {
    let m = pts
        .iter()
        .flat_map(|p| p.iter())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let mut s = 1.0;
    while m * s > arealight::Fixed22::COORDINATE_LIMIT {
        s *= 0.5;
    }
    s
}

/// A random convex polygon of 3 to 8 vertices on an ellipse in a random plane through `c`:
/// semi-axes `size` and `size` times 0.3 to 1, the vertices at jittered equal angles.
pub fn ellipse_polygon(rng: &mut Rng, c: V3, size: f64) -> Vec<V3> {
    let (e1, e2) = frame(rng.dir());
    let k = 3 + rng.below(6) as usize;
    let b = size * rng.range(0.3, 1.0);
    let phase = rng.range(0.0, 1.0);
    (0..k)
        .map(|i| {
            let t = TAU * (i as f64 + phase + rng.range(-0.3, 0.3)) / k as f64;
            add(c, add(scale(e1, size * t.cos()), scale(e2, b * t.sin())))
        })
        .collect()
}
