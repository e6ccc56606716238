//! Self-checks of the independent quadrature (tests/common/quadrature.rs), without the library:
//! convergence between two refinement levels, two independent coordinate frames, partitions of
//! the sphere (whose integrals are known exactly), and the 1D rules.

mod common;

use common::quadrature::{self as qd, Frame, Radiance};
use common::*;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

#[test]
fn gauss_legendre_rules() {
    let q = Quad::STD;
    // Polynomials and a smooth function.
    let v = qd::integrate(|x| x.powi(7) - 3.0 * x * x, -1.0, 2.0, 1e-15, &q);
    let exact = (2f64.powi(8) - 1.0) / 8.0 - (8.0 + 1.0);
    assert!((v - exact).abs() < 1e-13, "{v} vs {exact}");
    let v = qd::integrate(|x| x.cos(), 0.0, 10.0, 1e-15, &q);
    assert!((v - 10f64.sin()).abs() < 1e-14);
    // Square-root ends, with the smoothing substitution.
    let v = qd::integrate_smooth_ends(|x| (x * (1.0 - x)).sqrt(), 0.0, 1.0, 1e-15, &q);
    assert!((v - PI / 8.0).abs() < 1e-14, "{:e}", v - PI / 8.0);
    // A narrow peak.
    let v = qd::integrate(|x| x.cos().powi(255) * x.sin(), 0.0, FRAC_PI_2, 1e-16, &q);
    assert!((v - 1.0 / 256.0).abs() < 1e-16, "{:e}", v - 1.0 / 256.0);
    println!("[maxerr] quadrature: 1D rules exact to 1e-14");
}

/// Caps: the frame about the weight axis and the frame about the source axis are two
/// independent evaluations; and the STD and FINE levels agree.
#[test]
fn caps_two_frames_and_two_levels() {
    let mut rng = Rng::new(1);
    let mut frames = MaxErr::new("quadrature cap: frame k vs frame axis");
    let mut levels = MaxErr::new("quadrature cap: STD vs FINE");
    let mut coarse = MaxErr::new("quadrature cap: COARSE vs FINE (for scale)");
    let q = Quad::STD;
    for &sigma in &[0.0047, 0.3, PI / 4.0, 1.4, FRAC_PI_2] {
        let axis = rng.dir();
        let perp = frame(axis).0;
        let mut ws = w_grid(sigma);
        ws.retain(|_| rng.unit() < 0.5);
        for w in ws {
            let k = rotate_toward(axis, perp, w);
            for &m in &EXPONENTS {
                for rad in [Radiance::Const, Radiance::Cos] {
                    if rad == Radiance::Cos && sigma != FRAC_PI_2 {
                        continue;
                    }
                    let norm = (m as f64 + 1.0) / TAU;
                    let tol = q.tol / norm;
                    let a = qd::cap_weighted(axis, sigma, rad, k, m, Frame::AboutWeight, tol, &q)
                        * norm;
                    let b = qd::cap_weighted(axis, sigma, rad, k, m, Frame::AboutSource, tol, &q)
                        * norm;
                    let case = || format!("sigma={sigma} w={w} m={m} {rad:?}");
                    frames.add(a, b, case);
                    if m == 3 || m == 64 || m == 255 {
                        let f = Quad::FINE;
                        let c = qd::cap_weighted(
                            axis,
                            sigma,
                            rad,
                            k,
                            m,
                            Frame::AboutWeight,
                            f.tol / norm,
                            &f,
                        ) * norm;
                        levels.add(a, c, case);
                        let cc = Quad::COARSE;
                        let d = qd::cap_weighted(
                            axis,
                            sigma,
                            rad,
                            k,
                            m,
                            Frame::AboutWeight,
                            cc.tol / norm,
                            &cc,
                        ) * norm;
                        coarse.add(d, c, case);
                    }
                }
            }
        }
    }
    coarse.report();
    check_all(&[(&frames, 1e-12), (&levels, 1e-13)]);
}

/// A cap and the complementary cap (radius pi - sigma about -axis) tile the sphere: for every
/// weight their normalized Phong integrals sum to 1 (exercises arcs of radius > pi/2).
#[test]
fn caps_tile_the_sphere() {
    let mut rng = Rng::new(2);
    let mut err = MaxErr::new("quadrature cap + complement = 1");
    let q = Quad::STD;
    for _ in 0..40 {
        let axis = rng.dir();
        let sigma = rng.range(0.0, FRAC_PI_2);
        let k = rng.dir();
        let m = EXPONENTS[rng.below(7) as usize];
        let norm = (m as f64 + 1.0) / TAU;
        let f = |u: V3| dot(u, k).max(0.0).powi(m as i32);
        let a = qd::two_cap_integral(k, FRAC_PI_2, axis, sigma, f, q.tol / norm, &q);
        let b = qd::two_cap_integral(
            k,
            FRAC_PI_2,
            scale(axis, -1.0),
            PI - sigma,
            f,
            q.tol / norm,
            &q,
        );
        err.add((a + b) * norm, 1.0, || {
            format!("axis={axis:?} sigma={sigma} k={k:?} m={m}")
        });
    }
    err.check(1e-13);
}

/// The six faces of a cube around p tile the sphere: their normalized Lambert and Phong integrals
/// (each face clipped to the hemisphere, generically into pentagons and triangles) sum to 1.
#[test]
fn cube_faces_tile_the_sphere() {
    let mut rng = Rng::new(3);
    let mut lam = MaxErr::new("quadrature polygon: cube faces, Lambert sum = 1");
    let mut pho = MaxErr::new("quadrature polygon: cube faces, Phong sum = 1");
    let q = Quad::STD;
    for it in 0..42 {
        // Cube [-1, 1]^3 rotated; p inside (off-centre, sometimes close to a face).
        let rot = {
            let a = rng.dir();
            let (b, c) = frame(a);
            [a, b, c]
        };
        let tr = |x: V3| {
            add(
                add(scale(rot[0], x[0]), scale(rot[1], x[1])),
                scale(rot[2], x[2]),
            )
        };
        let p = if it % 3 == 2 {
            tr([0.999, rng.range(-0.5, 0.5), 0.2])
        } else if it % 3 == 1 {
            // Within 1e-6 of a face, near its edge: the lobe of a large m lies along the face.
            tr([1.0 - 1e-6, rng.range(0.99, 0.999), rng.range(-0.5, 0.5)])
        } else {
            tr([
                rng.range(-0.6, 0.6),
                rng.range(-0.6, 0.6),
                rng.range(-0.6, 0.6),
            ])
        };
        let mut faces = Vec::new();
        for ax in 0..3 {
            for s in [-1.0, 1.0] {
                let (b, c) = ((ax + 1) % 3, (ax + 2) % 3);
                let corner = |u: f64, w: f64| {
                    let mut x = [0.0; 3];
                    x[ax] = s;
                    x[b] = u;
                    x[c] = w;
                    tr(x)
                };
                faces.push(vec![
                    corner(-1., -1.),
                    corner(1., -1.),
                    corner(1., 1.),
                    corner(-1., 1.),
                ]);
            }
        }
        let n = if it % 3 == 1 {
            // Nearly parallel to the face x = 1 that p almost touches.
            normalize(tr([
                rng.range(-1e-3, 1e-3),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            ]))
        } else {
            rng.dir()
        };
        let sum: f64 = faces.iter().map(|f| qd::polygon_lambert(f, p, n, &q)).sum();
        lam.add(sum, 1.0, || format!("p={p:?} n={n:?}"));
        let m = EXPONENTS[it % 7];
        let sum: f64 = faces
            .iter()
            .map(|f| qd::phong_polygon(f, p, n, m, &q))
            .sum();
        pho.add(sum, 1.0, || format!("p={p:?} r={n:?} m={m}"));
    }
    check_all(&[(&lam, 1e-12), (&pho, 1e-12)]);
}

/// Polygons: STD vs FINE on the random and adversarial cases, and the m = 0 (unclipped) solid
/// angle against Van Oosterom-Strackee (a closed form of the solid angle only, not a model).
#[test]
fn polygons_two_levels() {
    let mut rng = Rng::new(4);
    let mut levels = MaxErr::new("quadrature polygon: STD vs FINE");
    let mut vos = MaxErr::new("quadrature polygon: solid angle vs VOS");
    let mut cases = random_polygons(&mut rng, 30);
    let adv = adversarial_polygons(&mut rng);
    cases.extend(adv.into_iter().step_by(9));
    for (i, c) in cases.iter().enumerate() {
        let m = EXPONENTS[i % 7];
        let a = qd::phong_polygon(&c.verts, c.p, c.k, m, &Quad::STD);
        let b = qd::phong_polygon(&c.verts, c.p, c.k, m, &Quad::FINE);
        levels.add(a, b, || format!("m={m} {}", c.describe()));
        let a = qd::polygon_lambert(&c.verts, c.p, c.k, &Quad::STD);
        let b = qd::polygon_lambert(&c.verts, c.p, c.k, &Quad::FINE);
        levels.add(a, b, || format!("lambert {}", c.describe()));
        // Unclipped solid angle: k toward the plane's near side so nothing is clipped.
        let nn = normalize(qd::newell(&c.verts));
        let h = dot(sub(c.verts[0], c.p), nn);
        let k = scale(nn, h.signum());
        let omega = qd::polygon_integral(&c.verts, c.p, k, |_| 1.0, 1e-14, &Quad::STD);
        // VOS fan with its apex at the foot of p on the plane (direction `k`): every fan
        // triangle is proper and well conditioned (a fan from a vertex is not when a diagonal
        // passes within h of the foot, as for the edge-on stars).
        let mut fan = 0.0;
        let nv = c.verts.len();
        for j in 0..nv {
            let a = normalize(sub(c.verts[j], c.p));
            let b = normalize(sub(c.verts[(j + 1) % nv], c.p));
            let num = dot(k, cross(a, b));
            let den = 1.0 + dot(k, a) + dot(a, b) + dot(b, k);
            fan += 2.0 * num.atan2(den);
        }
        vos.add(omega, fan.abs(), || c.describe());
    }
    check_all(&[(&levels, 1e-12), (&vos, 1e-12)]);
}

/// SH: quadrature of the basis is orthonormal, and STD vs FINE agree for the disc.
#[test]
fn sh_basis_orthonormal_and_levels() {
    let q = Quad::STD;
    let mut ortho = MaxErr::new("quadrature SH: Gram matrix vs identity");
    for i in 0..9 {
        for j in 0..9 {
            let g = qd::two_cap_integral(
                [0.0, 0.0, 1.0],
                PI,
                [0.0, 0.0, 1.0],
                PI,
                |u| {
                    let y = qd::sh_basis(u);
                    y[i] * y[j]
                },
                1e-15,
                &q,
            );
            ortho.add(g, if i == j { 1.0 } else { 0.0 }, || format!("({i},{j})"));
        }
    }
    let mut rng = Rng::new(5);
    let mut levels = MaxErr::new("quadrature SH disc: STD vs FINE");
    for _ in 0..10 {
        let axis = rng.dir();
        let alpha = rng.range(0.0, PI);
        let n = rng.dir();
        let a = qd::sh9_disc_irradiance(axis, alpha, n, &Quad::STD);
        let b = qd::sh9_disc_irradiance(axis, alpha, n, &Quad::FINE);
        levels.add(a, b, || format!("axis={axis:?} alpha={alpha} n={n:?}"));
    }
    check_all(&[(&ortho, 1e-14), (&levels, 1e-13)]);
}

/// Polygons: the two independent methods (circles about the weight axis, and the fan from the
/// foot of p with the unclipped integrand) agree on random and adversarial cases.
#[test]
fn polygons_two_methods() {
    let mut rng = Rng::new(6);
    let mut lam = MaxErr::new("quadrature polygon Lambert: circles vs fan");
    let mut pho = MaxErr::new("quadrature polygon Phong: circles vs fan");
    let mut cases = random_polygons(&mut rng, 40);
    cases.extend(adversarial_polygons(&mut rng).into_iter().step_by(5));
    let q = Quad::STD;
    for (i, c) in cases.iter().enumerate() {
        let a = qd::polygon_lambert(&c.verts, c.p, c.k, &q);
        let b = qd::polygon_lambert_fan(&c.verts, c.p, c.k, &q);
        lam.add(a, b, || c.describe());
        let m = EXPONENTS[i % 7];
        let a = qd::phong_polygon(&c.verts, c.p, c.k, m, &q);
        let b = qd::phong_polygon_fan(&c.verts, c.p, c.k, m, &q);
        pho.add(a, b, || format!("m={m} {}", c.describe()));
    }
    check_all(&[(&lam, 1e-12), (&pho, 1e-12)]);
}

/// The f64 error budget (`F64_BUDGET` in tests/common) is one table, checked here as a whole:
/// ids unique, every tolerance at least its measured error and at most 100 times it.
#[test]
fn f64_budget_is_consistent() {
    let mut ids = std::collections::BTreeSet::new();
    for r in F64_BUDGET {
        assert!(ids.insert(r.id), "duplicate f64 budget row {:?}", r.id);
        let tol = tol_f64(r.id);
        println!(
            "[budget] {:<70} measured {:.1e}  tolerance {:.0e} ({:.1}x)  against {}",
            r.id,
            r.measured,
            tol,
            tol / r.measured,
            r.against
        );
    }
}
