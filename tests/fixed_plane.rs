//! Fixed point near a polygon light's plane: no silently wrong answer (issue 13).
//!
//! Over a polygon's face the models jump from 0 (the shading point in the plane) to nearly the
//! whole face just off it (`polygon_lambert` 1 facing it). `Fixed22` rounds positions to
//! 2^-22 = 2.4e-7, and its in-plane test has a tolerance of a few of those: a point within it
//! and over the face cannot be told from one in the plane. Before, it answered 0 (f64: 0.970
//! for a point 4.8e-7 above a star polygon's face); now the `try_` functions report
//! `Error::Unresolved("p")` there. Everywhere else they answer.
//!
//! Checked here, for a square, a tilted quad and a non-convex star, on `polygon_lambert`,
//! `phong_polygon` (m = 1, 16, 64) and the axial and double-axis moments (m = 0, 2, 5):
//! - points at heights of -2 to 2 units of 2^-22 above the face (inside the polygon, away from
//!   its edges) give `Unresolved` (the in-plane tolerance is at least 3 units);
//! - points in the plane outside the polygon give 0, as f64 does to within 1/1024;
//! - over the face, at every height from 2^-22 to 2^-4 and below it, the fixed answer is
//!   either `Unresolved` or within 1/1024 of f64 at the same (rounded) point. The heights at
//!   which `Unresolved` is reported are printed.

use arealight::{Error, Fixed22, PhongLobe, PolygonLight, Real, Vec3};

type F = Fixed22;
const LSB: f64 = 1.0 / (1u64 << 22) as f64;
const BOUND: f64 = 1.0 / 1024.0;

fn v<T: Real>(p: [f64; 3]) -> Vec3<T> {
    Vec3::new(T::from_f64(p[0]), T::from_f64(p[1]), T::from_f64(p[2]))
}

/// A test polygon: its name, vertices, a point inside (well away from the edges) and a point
/// in the plane outside.
type Case = (&'static str, Vec<[f64; 3]>, [f64; 3], [f64; 3]);

/// The polygons of the check.
fn polygons() -> Vec<Case> {
    let square = vec![
        [-0.5, -0.5, 1.0],
        [0.5, -0.5, 1.0],
        [0.5, 0.5, 1.0],
        [-0.5, 0.5, 1.0],
    ];
    // A quad in the plane through (0, 0, 0.5) with normal (1, 2, 2)/3, vertices at multiples
    // of 2^-6 so that they round exactly.
    let (a, b) = ([2.0, -1.0, 0.0], [2.0, 2.0, -3.0]); // both orthogonal to (1, 2, 2)
    let c = [0.0, 0.0, 0.5];
    let at = |s: f64, t: f64| {
        [
            c[0] + (s * a[0] + t * b[0]) / 8.0,
            c[1] + (s * a[1] + t * b[1]) / 8.0,
            c[2] + (s * a[2] + t * b[2]) / 8.0,
        ]
    };
    let tilted = vec![at(-2.0, -1.0), at(2.0, -1.0), at(2.0, 1.0), at(-2.0, 1.0)];
    let star: Vec<[f64; 3]> = (0..10)
        .map(|i| {
            let ang = std::f64::consts::PI * f64::from(i) / 5.0;
            let r = if i % 2 == 0 { 1.0 } else { 0.375 };
            [r * ang.cos(), r * ang.sin(), -0.75]
        })
        .collect();
    vec![
        ("square", square, [0.125, -0.0625, 1.0], [0.0, 0.0, 0.0]),
        ("tilted", tilted, at(0.25, 0.125), at(3.0, 0.5)),
        ("star", star, [0.0625, 0.03125, -0.75], [0.0, 0.0, 0.0]),
    ]
}

fn normal(name: &str) -> [f64; 3] {
    match name {
        "tilted" => [1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0],
        _ => [0.0, 0.0, 1.0],
    }
}

/// Every model of the check at `p`: `(name, fixed result, f64 value)`.
fn models(verts: &[[f64; 3]], p: [f64; 3], k: [f64; 3]) -> Vec<(String, Result<f64, Error>, f64)> {
    let lf = PolygonLight::<F, 12>::new(&verts.iter().map(|&x| v::<F>(x)).collect::<Vec<_>>())
        .expect("a valid polygon");
    let ld = PolygonLight::<f64, 12>::new(&verts.iter().map(|&x| v::<f64>(x)).collect::<Vec<_>>())
        .expect("a valid polygon");
    let pf = v::<F>(p);
    // f64 at the point fixed point actually sees (p rounded to the grid).
    let pd = v::<f64>(pf.to_f64());
    // The normal / reflection direction: towards the face's front or back, tilted.
    let (kf, kd) = (v::<F>(k), v::<f64>(k));
    let mut out = Vec::new();
    let f = |r: Result<F, Error>| r.map(|x| x.to_f64());
    out.push((
        "polygon_lambert".to_string(),
        f(lf.try_lambert(pf, kf)),
        ld.lambert(pd, kd),
    ));
    for m in [1u32, 16, 64] {
        let (lobe_f, lobe_d) = (
            PhongLobe::<F>::new(m).unwrap(),
            PhongLobe::<f64>::new(m).unwrap(),
        );
        out.push((
            format!("phong_polygon m={m}"),
            f(lf.try_phong(&lobe_f, pf, kf)),
            ld.phong(&lobe_d, pd, kd),
        ));
    }
    for m in [0u32, 2, 5] {
        out.push((
            format!("axial_moment m={m}"),
            f(lf.try_axial_moment(pf, kf, m)),
            ld.axial_moment(pd, kd, m),
        ));
        let w2 = [0.6, -0.0, 0.8];
        out.push((
            format!("double_axis_moment m={m}"),
            f(lf.try_double_axis_moment(pf, kf, v::<F>(w2), m)),
            ld.double_axis_moment(pd, kd, v::<f64>(w2), m),
        ));
    }
    out
}

fn offset(p: [f64; 3], n: [f64; 3], h: f64) -> [f64; 3] {
    [p[0] + h * n[0], p[1] + h * n[1], p[2] + h * n[2]]
}

#[test]
fn within_the_rounding_of_the_face_is_unresolved() {
    let mut checked = 0;
    for (name, verts, inside, _) in polygons() {
        let n = normal(name);
        // The in-plane tolerance is at least 3 units of 2^-22 (more far from vertex 0).
        for lsb in -2..=2 {
            let p = offset(inside, n, f64::from(lsb) * LSB);
            for k in [n, [-n[0], -n[1], -n[2]], [0.3, -0.4, 0.866]] {
                for (model, got, want) in models(&verts, p, k) {
                    checked += 1;
                    assert_eq!(
                        got,
                        Err(Error::Unresolved("p")),
                        "{name} {model} at {lsb} LSB above the face, k={k:?}: f64 says {want}"
                    );
                }
            }
        }
    }
    println!("[fixed_plane] {checked} calls within 2 LSB of a face: all Unresolved");
}

#[test]
fn in_the_plane_outside_the_polygon_is_zero() {
    for (name, verts, _, outside) in polygons() {
        let n = normal(name);
        for k in [n, [0.3, -0.4, 0.866]] {
            for (model, got, want) in models(&verts, outside, k) {
                let got = got.unwrap_or_else(|e| panic!("{name} {model}: {e}"));
                assert!(
                    (got - want).abs() <= BOUND,
                    "{name} {model} in the plane outside: {got} against f64 {want}"
                );
            }
        }
    }
}

#[test]
fn over_the_face_either_unresolved_or_within_the_bound() {
    let (mut answered, mut refused, mut worst) = (0, 0, 0.0f64);
    let mut highest_refused = 0.0f64;
    for (name, verts, inside, _) in polygons() {
        let n = normal(name);
        for e in 0..=18 {
            // Heights 2^-22 to 2^-4 (and just above each power), both sides.
            for h in [LSB * f64::from(1u32 << e), LSB * f64::from(1u32 << e) * 1.5] {
                for side in [1.0, -1.0] {
                    let p = offset(inside, n, side * h);
                    for k in [n, [-n[0], -n[1], -n[2]], [0.3, -0.4, 0.866]] {
                        for (model, got, want) in models(&verts, p, k) {
                            match got {
                                Ok(x) => {
                                    answered += 1;
                                    let err = (x - want).abs();
                                    worst = worst.max(err);
                                    assert!(
                                        err <= BOUND,
                                        "{name} {model} at h={:e}: {x} against f64 {want} (k={k:?})",
                                        side * h
                                    );
                                }
                                Err(Error::Unresolved("p")) => {
                                    refused += 1;
                                    highest_refused = highest_refused.max(h);
                                }
                                Err(e) => panic!("{name} {model} at h={h:e}: {e}"),
                            }
                        }
                    }
                }
            }
        }
    }
    println!(
        "[fixed_plane] over the face, heights 2^-22 to 1.5 2^-4: {answered} answered (max error {worst:.2e}), {refused} Unresolved (up to h = {highest_refused:.2e})"
    );
}
