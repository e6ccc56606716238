//! Adversarial geometry, with exact expected values from the independent quadrature:
//! vertices on, just above and just below the horizon; edges through the normal direction;
//! slivers and nearly edge-on polygons; a vertex within 1e-6 of the shading point; tiny far
//! lights (solid angle about 1e-8) and huge near ones; r parallel and antiparallel to the axis.
//!
//! f64 is held to its row of the f64 budget (`tol_f64` in tests/common). f32 and Fast32 are compared with the f64 library on
//! the same rounded inputs, each case against its own bound (`Bounded` in tests/common: the
//! main-regime bound, plus the model's own f32 input sensitivity where it is ill-conditioned
//! and `16 2^-24 size/dist` near a polygon's boundary, capped at `BOUND_CAP`; Fast32 held to
//! 1/1024 below the cap), and must be finite and in range.

mod common;

use arealight::{CapLight, Fast32, HemisphereLight, PhongLobe, PolygonLight, Real, SphereLight};
use common::quadrature as qd;
use common::*;
use std::f64::consts::{FRAC_PI_2, PI};

const MS: [u32; 5] = [0, 1, 2, 64, 255];

/// A polygon case (vertices, p, weight axis k) with a label.
fn polygon_cases() -> Vec<PolyCase> {
    let sq: Vec<V3> = vec![
        [-0.5, -0.5, 1.0],
        [0.5, -0.5, 1.0],
        [0.5, 0.5, 1.0],
        [-0.5, 0.5, 1.0],
    ];
    let mut out = Vec::new();
    let push = |out: &mut Vec<PolyCase>, kind: String, verts: Vec<V3>, p: V3, k: V3| {
        out.push(PolyCase { kind, verts, p, k });
    };
    // Vertex 0 on, just above and just below the horizon of k: k perpendicular to v0 - p,
    // tilted by delta toward v0.
    let u0 = normalize(sq[0]);
    let k0 = normalize(cross(u0, [0.3, 1.0, -0.2]));
    let k0 = if dot(k0, [0.0, 0.0, 1.0]) < 0.0 {
        scale(k0, -1.0)
    } else {
        k0
    };
    for d in [0.0, 1e-12, 1e-9, 1e-6, -1e-12, -1e-9, -1e-6] {
        let k = rotate_toward(k0, u0, d);
        push(
            &mut out,
            format!("vertex at horizon {d:e}"),
            sq.clone(),
            [0.0; 3],
            k,
        );
    }
    // Two vertices (a whole edge) on the horizon.
    push(
        &mut out,
        "edge on horizon".into(),
        sq.clone(),
        [0.0; 3],
        normalize(cross(sq[0], sq[1])),
    );
    // Edges through the normal direction: k toward an edge's midpoint and toward a vertex.
    for t in [
        scale(add(sq[0], sq[1]), 0.5),
        sq[2],
        add(scale(add(sq[1], sq[2]), 0.5), [0.0, 0.0, 0.0]),
    ] {
        push(
            &mut out,
            "k through an edge/vertex".into(),
            sq.clone(),
            [0.0; 3],
            normalize(t),
        );
    }
    // Slivers: a triangle 1e-6 (and 1e-4) wide, seen face-on and from the side.
    for w in [1e-4, 1e-6] {
        let sl = vec![[-0.5, 0.0, 1.0], [0.5, -w, 1.0], [0.5, w, 1.0]];
        for k in [[0.0, 0.0, 1.0], [0.6, 0.2, 0.7], [1.0, 0.0, 0.0]] {
            push(&mut out, format!("sliver {w:e}"), sl.clone(), [0.0; 3], k);
        }
    }
    // Nearly edge-on: p at height h below the plane, foot outside the square.
    for h in [1e-4, 1e-7, 1e-9] {
        for k in [[0.0, 0.0, 1.0], [1.0, 0.2, 0.05], [-0.3, 1.0, 0.4]] {
            push(
                &mut out,
                format!("edge-on h={h:e}"),
                sq.clone(),
                [1.5, 0.2, 1.0 - h],
                k,
            );
        }
    }
    // A vertex within 1e-6 of p (p below the plane, off the vertex).
    for d in [1e-6, 1e-5] {
        let p = sub(sq[0], [d * 0.3, -d * 0.2, d]);
        for k in [[0.0, 0.0, 1.0], [0.5, 0.5, 0.7], [1.0, -0.2, 0.0]] {
            push(&mut out, format!("vertex {d:e} from p"), sq.clone(), p, k);
        }
    }
    // Tiny far light (solid angle ~1e-8) and a huge near one.
    let tiny: Vec<V3> = sq
        .iter()
        .map(|&x| [x[0] * 1e-4, x[1] * 1e-4, 1.0])
        .collect();
    let huge: Vec<V3> = sq.iter().map(|&x| [x[0] * 1e6, x[1] * 1e6, 1.0]).collect();
    for k in [[0.0, 0.0, 1.0], [0.3, 0.1, 0.9], [1.0, 0.0, 1e-3]] {
        push(&mut out, "tiny far quad".into(), tiny.clone(), [0.0; 3], k);
        push(&mut out, "huge near quad".into(), huge.clone(), [0.0; 3], k);
    }
    out
}

/// (axis, sigma, r) caps and (center, radius, p, r) spheres: r parallel and antiparallel to
/// the axis, tiny and huge sources.
fn cap_cases() -> Vec<(String, V3, f64, V3)> {
    let a = normalize([0.2, -0.4, 0.9]);
    let perp = frame(a).0;
    let mut out = Vec::new();
    for sigma in [1e-4, 0.3, FRAC_PI_2 - 1e-6, FRAC_PI_2] {
        for w in [0.0, PI, sigma, FRAC_PI_2 - sigma, FRAC_PI_2 + sigma] {
            out.push((
                format!("sigma={sigma:e} w={w:e}"),
                a,
                sigma,
                rotate_toward(a, perp, w),
            ));
        }
    }
    out
}

fn sphere_cases() -> Vec<(String, V3, f64, V3, V3)> {
    let c = [0.3, -0.2, 2.0];
    let mut out = Vec::new();
    // Tiny far: radius 1e-4 at distance ~2 (solid angle ~8e-9); huge near: d/R = 1 + 1e-6.
    for (name, radius, dist) in [
        ("tiny far", 1e-4, 2.0),
        ("huge near", 1e3, 1e3 * (1.0 + 1e-6)),
        ("near", 1.0, 1.001),
    ] {
        let toward = normalize([0.1, 0.3, 1.0]);
        let p = sub(c, scale(toward, dist));
        let sigma = (radius / dist).asin();
        let perp = frame(toward).0;
        for w in [0.0, PI, sigma, FRAC_PI_2, FRAC_PI_2 + sigma] {
            out.push((
                format!("{name} w={w:e}"),
                c,
                radius,
                p,
                rotate_toward(toward, perp, w),
            ));
        }
    }
    out
}

#[test]
fn adversarial_f64_vs_quadrature() {
    let q = Quad::STD;
    let mut e_pl = MaxErr::new("adversarial polygon_lambert f64 vs quadrature");
    let mut e_pp = MaxErr::new("adversarial phong_polygon f64 vs quadrature");
    let mut e_cl = MaxErr::new("adversarial cap_lambert f64 vs quadrature");
    let mut e_cp = MaxErr::new("adversarial phong_cap f64 vs quadrature");
    let mut e_sl = MaxErr::new("adversarial sphere_lambert f64 vs quadrature");
    let mut e_sp = MaxErr::new("adversarial phong_sphere f64 vs quadrature");
    let mut e_hc = MaxErr::new("adversarial phong_hemi_const f64 vs quadrature");
    let mut e_hcos = MaxErr::new("adversarial phong_hemi_cos f64 vs quadrature");
    for c in polygon_cases() {
        let vs: Vec<_> = c.verts.iter().map(|&x| v::<f64>(x)).collect();
        let pl = PolygonLight::<f64, 8>::new(&vs).expect(&c.kind);
        e_pl.add(
            pl.lambert(v(c.p), v(c.k)),
            qd::polygon_lambert(&c.verts, c.p, c.k, &q),
            || c.describe(),
        );
        for m in MS {
            let lobe = PhongLobe::<f64>::new(m).unwrap();
            e_pp.add(
                pl.phong(&lobe, v(c.p), v(c.k)),
                qd::phong_polygon_sharp(&c.verts, c.p, c.k, m, &q),
                || format!("m={m} {}", c.describe()),
            );
        }
    }
    for (name, axis, sigma, r) in cap_cases() {
        let cap = CapLight::<f64>::new(v(axis), sigma).unwrap();
        e_cl.add(
            cap.lambert(v(r)),
            qd::cap_lambert(axis, sigma, r, &q),
            || name.clone(),
        );
        let h = HemisphereLight::<f64>::new(v(axis)).unwrap();
        for m in MS {
            let lobe = PhongLobe::<f64>::new(m).unwrap();
            e_cp.add(
                cap.phong(&lobe, v(r)),
                qd::phong_cap_source_sharp(axis, sigma, qd::Radiance::Const, r, m, &q),
                || format!("m={m} {name}"),
            );
            e_hc.add(
                h.phong_const(&lobe, v(r)),
                qd::phong_cap_source_sharp(axis, FRAC_PI_2, qd::Radiance::Const, r, m, &q),
                || format!("const m={m} {name}"),
            );
            e_hcos.add(
                h.phong_cos(&lobe, v(r)),
                qd::phong_cap_source_sharp(axis, FRAC_PI_2, qd::Radiance::Cos, r, m, &q),
                || format!("cos m={m} {name}"),
            );
        }
    }
    for (name, center, radius, p, r) in sphere_cases() {
        let s = SphereLight::<f64>::new(v(center), radius).unwrap();
        e_sl.add(
            s.lambert(v(p), v(r)),
            qd::sphere_lambert(center, radius, p, r, &q),
            || name.clone(),
        );
        let (axis, sigma) = qd::sphere_cap(center, radius, p);
        for m in MS {
            let lobe = PhongLobe::<f64>::new(m).unwrap();
            e_sp.add(
                s.phong(&lobe, v(p), v(r)),
                qd::phong_cap_source_sharp(axis, sigma, qd::Radiance::Const, r, m, &q),
                || format!("m={m} {name}"),
            );
        }
    }
    check_all(&[
        (&e_pl, tol_f64("polygon_lambert")),
        (&e_pp, tol_f64("phong_polygon")),
        (&e_cl, tol_f64("cap_lambert")),
        (&e_cp, tol_f64("phong_cap")),
        (&e_sl, tol_f64("sphere_lambert")),
        (&e_sp, tol_f64("phong_sphere")),
        (&e_hc, tol_f64("phong_hemi_const")),
        (&e_hcos, tol_f64("phong_hemi_cos")),
    ]);
}

macro_rules! lowp {
    ($name:ident, $T:ty, $bounds:expr) => {
        /// The low-precision backend on the same adversarial cases vs the f64 library (same
        /// rounded inputs), each case against its own bound.
        #[test]
        fn $name() {
            type T = $T;
            let tname = stringify!($T);
            let mut b_poly = Bounded::new(&format!("adversarial polygons {tname} vs f64"), $bounds);
            let mut b_cap = Bounded::new(&format!("adversarial caps {tname} vs f64"), $bounds);
            let mut b_sph = Bounded::new(&format!("adversarial spheres {tname} vs f64"), $bounds);
            let mut skipped = 0;
            for c in polygon_cases() {
                let verts: Vec<V3> = c.verts.iter().map(|&x| rdv::<T>(x)).collect();
                let (p, k) = (rdv::<T>(c.p), rdv::<T>(c.k));
                let lo_v: Vec<_> = verts.iter().map(|&x| v::<T>(x)).collect();
                let hi_v: Vec<_> = verts.iter().map(|&x| v::<f64>(x)).collect();
                let (Ok(lo), Ok(hi)) = (
                    PolygonLight::<T, 8>::new(&lo_v),
                    PolygonLight::<f64, 8>::new(&hi_v),
                ) else {
                    skipped += 1;
                    continue;
                };
                let nv = verts.len();
                let mut pts = verts.clone();
                pts.extend([p, k]);
                let x = flat(&pts, &[]);
                for m in MS {
                    let (ll, lh) = (
                        PhongLobe::<T>::new(m).unwrap(),
                        PhongLobe::<f64>::new(m).unwrap(),
                    );
                    let got = lo.phong(&ll, v(p), v(k)).to_f64();
                    assert!(
                        (0.0..=1.0).contains(&got),
                        "{tname} out of range: {}",
                        c.describe()
                    );
                    let sens = sensitivity(
                        |x| {
                            let vs: Vec<_> = (0..nv).map(|i| v(v3_at(x, i))).collect();
                            let l = PolygonLight::<f64, 8>::new(&vs).ok()?;
                            Some(l.phong(&lh, v(v3_at(x, nv)), v(v3_at(x, nv + 1))))
                        },
                        &x,
                    );
                    let cond = Cond {
                        m,
                        sens,
                        near: near_boundary(&verts, p),
                    };
                    b_poly.add(got, hi.phong(&lh, v(p), v(k)), cond, || {
                        format!("m={m} {}", c.describe())
                    });
                }
            }
            for (name, axis, sigma, r) in cap_cases() {
                let (axis, r) = (rdv::<T>(axis), rdv::<T>(r));
                let sigma = rd_max::<T>(sigma, FRAC_PI_2);
                let lo = CapLight::<T>::new(v(axis), T::from_f64(sigma)).unwrap();
                let hi = CapLight::<f64>::new(v(axis), sigma).unwrap();
                for m in MS {
                    let (ll, lh) = (
                        PhongLobe::<T>::new(m).unwrap(),
                        PhongLobe::<f64>::new(m).unwrap(),
                    );
                    let sens = sensitivity(
                        |x| {
                            let cap = CapLight::<f64>::new(v(v3_at(x, 0)), x[6]).ok()?;
                            Some(cap.phong(&lh, v(v3_at(x, 1))))
                        },
                        &flat(&[axis, r], &[sigma]),
                    );
                    b_cap.add(
                        lo.phong(&ll, v(r)).to_f64(),
                        hi.phong(&lh, v(r)),
                        Cond {
                            m,
                            sens,
                            near: None,
                        },
                        || format!("m={m} {name}"),
                    );
                }
            }
            for (name, center, radius, p, r) in sphere_cases() {
                let (center, p, r) = (rdv::<T>(center), rdv::<T>(p), rdv::<T>(r));
                let radius = rd::<T>(radius);
                let lo = SphereLight::<T>::new(v(center), T::from_f64(radius)).unwrap();
                let hi = SphereLight::<f64>::new(v(center), radius).unwrap();
                for m in MS {
                    let (ll, lh) = (
                        PhongLobe::<T>::new(m).unwrap(),
                        PhongLobe::<f64>::new(m).unwrap(),
                    );
                    // p may round into the sphere: then both refuse it.
                    let Ok(want) = hi.try_phong(&lh, v(p), v(r)) else {
                        skipped += 1;
                        continue;
                    };
                    let sens = sensitivity(
                        |x| {
                            let s = SphereLight::<f64>::new(v(v3_at(x, 0)), x[9]).ok()?;
                            s.try_phong(&lh, v(v3_at(x, 1)), v(v3_at(x, 2))).ok()
                        },
                        &flat(&[center, p, r], &[radius]),
                    );
                    b_sph.add(
                        lo.phong(&ll, v(p), v(r)).to_f64(),
                        want,
                        Cond {
                            m,
                            sens,
                            near: None,
                        },
                        || format!("m={m} {name}"),
                    );
                }
            }
            println!("{tname}: {skipped} cases skipped (invalid after rounding to {tname})");
            check_bounded(&[&b_poly, &b_cap, &b_sph]);
        }
    };
}

lowp!(adversarial_f32_vs_f64, f32, BOUNDS_F32);
// Fast32: 1/1024 in every regime below the cap, like everywhere else; the cases closest to the
// degeneracies (p 1e-6 from a vertex) are beyond the cap for both backends.
lowp!(adversarial_fast32_vs_f64, Fast32, BOUNDS_FAST32);
