//! Phong models: `[phong_hemi_const]`, `[phong_hemi_cos]`, `[phong_cap]`, `[phong_sphere]`,
//! `[phong_polygon]`, for m in {0, 1, 2, 3, 63, 64, 255} (and random m <= 255).
//!
//! f64 library vs the independent quadrature (within its row of the f64 budget, `F64_BUDGET`
//! in tests/common), then f32 and Fast32 vs f64 on the same rounded inputs (<= 2e-6 and
//! <= 1/1024 in the main regime; f32 also <= 2e-6 + m 2^-24 at high m, and the
//! ill-conditioned, near-boundary and capped bounds of `f32_bound` in tests/common).

mod common;

use arealight::{
    CapLight, Fast32, HemisphereLight, PhongLobe, PolygonLight, Real, SphereLight, Vec3,
};
use common::quadrature as qd;
use common::*;
use std::f64::consts::{FRAC_PI_2, PI};

/// (axis, r) pairs for the hemisphere lights: the w grid of a pi/2 cap (r parallel and
/// antiparallel to the axis, perpendicular, near each) plus random.
fn hemi_cases(rng: &mut Rng, random: usize) -> Vec<(V3, V3)> {
    let mut out = Vec::new();
    for w in w_grid(FRAC_PI_2) {
        let a = rng.dir();
        let r = rng.dir_at(a, w);
        out.push((rng.stretch(a), rng.stretch(r)));
    }
    out.push(([0.0, 0.0, 1.0], [0.0, 0.0, 1.0]));
    out.push(([0.0, 0.0, 1.0], [0.0, 0.0, -1.0]));
    for _ in 0..random {
        let a = rng.sdir();
        let r = rng.sdir();
        out.push((a, r));
    }
    out
}

#[test]
fn hemisphere_f64_vs_quadrature() {
    let mut rng = Rng::new(0xf00);
    let q = Quad::STD;
    let mut e_const = MaxErr::new("phong_hemi_const f64 vs quadrature");
    let mut e_cos = MaxErr::new("phong_hemi_cos f64 vs quadrature");
    let cases = hemi_cases(&mut rng, 60);
    let mut ms: Vec<u32> = EXPONENTS.to_vec();
    ms.extend((0..6).map(|_| rng.below(256) as u32));
    for &m in &ms {
        let lobe = PhongLobe::<f64>::new(m).unwrap();
        for &(axis, r) in &cases {
            let h = HemisphereLight::<f64>::new(v(axis)).unwrap();
            let case = || format!("m={m} axis={axis:?} r={r:?}");
            e_const.add(
                h.phong_const(&lobe, v(r)),
                qd::phong_hemi_const(axis, r, m, &q),
                case,
            );
            e_cos.add(
                h.phong_cos(&lobe, v(r)),
                qd::phong_hemi_cos(axis, r, m, &q),
                case,
            );
        }
    }
    check_all(&[
        (&e_const, tol_f64("phong_hemi_const")),
        (&e_cos, tol_f64("phong_hemi_cos")),
    ]);
}

#[test]
fn cap_f64_vs_quadrature() {
    let mut rng = Rng::new(0xf01);
    let q = Quad::STD;
    let mut e_cap = MaxErr::new("phong_cap f64 vs quadrature");
    let cases = cap_cases(&mut rng, 100);
    for (i, &(axis, sigma, r)) in cases.iter().enumerate() {
        let cap = CapLight::<f64>::new(v(axis), sigma).unwrap();
        // Every exponent of the list on the grid; a random one on the random cases.
        let ms: Vec<u32> = if i + 100 < cases.len() {
            EXPONENTS.to_vec()
        } else {
            vec![rng.below(256) as u32]
        };
        for m in ms {
            let lobe = PhongLobe::<f64>::new(m).unwrap();
            e_cap.add(
                cap.phong(&lobe, v(r)),
                qd::phong_cap(axis, sigma, r, m, &q),
                || format!("m={m} axis={axis:?} sigma={sigma:e} r={r:?}"),
            );
        }
    }
    e_cap.check(tol_f64("phong_cap"));
}

#[test]
fn sphere_f64_vs_quadrature() {
    let mut rng = Rng::new(0xf02);
    let q = Quad::STD;
    let mut e_sph = MaxErr::new("phong_sphere f64 vs quadrature");
    for (center, radius, p, r) in sphere_cases(&mut rng, 60) {
        let s = SphereLight::<f64>::new(v(center), radius).unwrap();
        for &m in &EXPONENTS {
            let lobe = PhongLobe::<f64>::new(m).unwrap();
            e_sph.add(
                s.phong(&lobe, v(p), v(r)),
                qd::phong_sphere(center, radius, p, r, m, &q),
                || format!("m={m} center={center:?} radius={radius:e} p={p:?} r={r:?}"),
            );
        }
    }
    e_sph.check(tol_f64("phong_sphere"));
}

#[test]
fn polygon_f64_vs_quadrature() {
    let mut rng = Rng::new(0xf03);
    let q = Quad::STD;
    let mut e_rand = MaxErr::new("phong_polygon f64 vs quadrature (random)");
    let mut e_adv = MaxErr::new("phong_polygon f64 vs quadrature (adversarial)");
    for c in random_polygons(&mut rng, 60) {
        let light = PolygonLight::<f64, 8>::new(&c.verts.iter().map(|&x| v(x)).collect::<Vec<_>>())
            .unwrap();
        for &m in &EXPONENTS {
            let lobe = PhongLobe::<f64>::new(m).unwrap();
            e_rand.add(
                light.phong(&lobe, v(c.p), v(c.k)),
                qd::phong_polygon(&c.verts, c.p, c.k, m, &q),
                || format!("m={m} {}", c.describe()),
            );
        }
    }
    for (i, c) in adversarial_polygons(&mut rng).iter().enumerate() {
        let light = PolygonLight::<f64, 8>::new(&c.verts.iter().map(|&x| v(x)).collect::<Vec<_>>())
            .unwrap();
        // Two exponents per case, rotating through the list.
        for m in [EXPONENTS[i % 7], EXPONENTS[(i + 3) % 7]] {
            let lobe = PhongLobe::<f64>::new(m).unwrap();
            e_adv.add(
                light.phong(&lobe, v(c.p), v(c.k)),
                qd::phong_polygon(&c.verts, c.p, c.k, m, &q),
                || format!("m={m} {}", c.describe()),
            );
        }
    }
    let mut e_ext: Vec<MaxErr> = EXPONENTS
        .iter()
        .map(|m| {
            MaxErr::new(&format!(
                "phong_polygon f64 vs quadrature (h <= 1e-8), m={m}"
            ))
        })
        .collect();
    for c in extreme_edge_on(&mut rng) {
        let light = PolygonLight::<f64, 8>::new(&c.verts.iter().map(|&x| v(x)).collect::<Vec<_>>())
            .unwrap();
        for (j, &m) in EXPONENTS.iter().enumerate() {
            let lobe = PhongLobe::<f64>::new(m).unwrap();
            e_ext[j].add(
                light.phong(&lobe, v(c.p), v(c.k)),
                qd::phong_polygon(&c.verts, c.p, c.k, m, &q),
                || format!("m={m} {}", c.describe()),
            );
        }
    }
    let tol = tol_f64("phong_polygon");
    let mut all = vec![(&e_rand, tol), (&e_adv, tol)];
    all.extend(e_ext.iter().map(|e| (e, tol)));
    check_all(&all);
}

/// `PhongLobe::odd_only(m)` evaluates the exponent `m | 1`; for odd `m` it is the exact lobe.
#[test]
fn odd_only_is_next_odd() {
    let cap = CapLight::<f64>::new(v([0.2, 0.3, 1.0]), 0.4).unwrap();
    let mut err = MaxErr::new("phong odd_only(m) vs new(m | 1)");
    for m in 0..=64u32 {
        let fast = PhongLobe::<f64>::odd_only(m).unwrap();
        let exact = PhongLobe::<f64>::new(m | 1).unwrap();
        assert_eq!(fast.exponent(), m);
        assert_eq!(fast.evaluated_exponent(), m | 1);
        for r in [[0.0, 0.0, 1.0], [1.0, 0.2, 0.1], [0.3, -0.4, 0.5]] {
            err.add(cap.phong(&fast, v(r)), cap.phong(&exact, v(r)), || {
                format!("m={m} r={r:?}")
            });
        }
    }
    err.check(0.0);
}

/// f32 / Fast32 vs f64 on the same rounded inputs, every case against its own bound
/// (`f32_bound` in tests/common: main regime 2e-6 and 1/1024; f32 also `+ m 2^-24` for high m,
/// `+ 4 sensitivity` for ill-conditioned cases, `+ 16 2^-24 size / dist` for polygons near
/// their boundary).
macro_rules! lowp_tests {
    ($modname:ident, $T:ty, $bounds:expr) => {
        mod $modname {
            use super::*;
            type T = $T;
            const B: LowpBounds = $bounds;
            const NAME: &str = stringify!($T);

            fn lobes(m: u32) -> (PhongLobe<T>, PhongLobe<f64>) {
                (
                    PhongLobe::<T>::new(m).unwrap(),
                    PhongLobe::<f64>::new(m).unwrap(),
                )
            }

            fn trackers(model: &str, set: &str) -> Vec<Bounded> {
                EXPONENTS
                    .iter()
                    .map(|m| Bounded::new(&format!("{model} {NAME} vs f64{set}, m={m}"), B))
                    .collect()
            }

            #[test]
            fn hemisphere_vs_f64() {
                let mut rng = Rng::new(0xa00);
                let mut cases = hemi_cases(&mut rng, 3000);
                for i in 0..=1024 {
                    let w = PI * i as f64 / 1024.0;
                    let a = rng.dir();
                    cases.push((a, rng.dir_at(a, w)));
                }
                let mut e_const = trackers("phong_hemi_const", "");
                let mut e_cos = trackers("phong_hemi_cos", "");
                for (j, &m) in EXPONENTS.iter().enumerate() {
                    let (lo_l, hi_l) = lobes(m);
                    for &(axis, r) in &cases {
                        let (axis, r) = (rdv::<T>(axis), rdv::<T>(r));
                        let lo = HemisphereLight::<T>::new(v(axis)).unwrap();
                        let hi = HemisphereLight::<f64>::new(v(axis)).unwrap();
                        let x = flat(&[axis, r], &[]);
                        let light = |x: &[f64]| HemisphereLight::<f64>::new(v(v3_at(x, 0))).ok();
                        let s_const =
                            sensitivity(|x| Some(light(x)?.phong_const(&hi_l, v(v3_at(x, 1)))), &x);
                        let s_cos =
                            sensitivity(|x| Some(light(x)?.phong_cos(&hi_l, v(v3_at(x, 1)))), &x);
                        let case = || format!("m={m} axis={axis:?} r={r:?}");
                        e_const[j].add(
                            lo.phong_const(&lo_l, v(r)).to_f64(),
                            hi.phong_const(&hi_l, v(r)),
                            Cond {
                                m,
                                sens: s_const,
                                near: None,
                            },
                            case,
                        );
                        e_cos[j].add(
                            lo.phong_cos(&lo_l, v(r)).to_f64(),
                            hi.phong_cos(&hi_l, v(r)),
                            Cond {
                                m,
                                sens: s_cos,
                                near: None,
                            },
                            case,
                        );
                    }
                }
                let all: Vec<&Bounded> = e_const.iter().chain(e_cos.iter()).collect();
                check_bounded(&all);
            }

            #[test]
            fn cap_vs_f64() {
                let mut rng = Rng::new(0xa01);
                let mut cases = cap_cases(&mut rng, 3000);
                for i in 0..=32 {
                    let sigma = FRAC_PI_2 * i as f64 / 32.0;
                    for j in 0..=256 {
                        let w = PI * j as f64 / 256.0;
                        let a = rng.dir();
                        cases.push((a, sigma, rng.dir_at(a, w)));
                    }
                }
                let mut errs = trackers("phong_cap", "");
                for (j, &m) in EXPONENTS.iter().enumerate() {
                    let (lo_l, hi_l) = lobes(m);
                    for &(axis, sigma, r) in &cases {
                        let (axis, r) = (rdv::<T>(axis), rdv::<T>(r));
                        let sigma = rd_max::<T>(sigma, FRAC_PI_2);
                        let lo = CapLight::<T>::new(v(axis), T::from_f64(sigma)).unwrap();
                        let hi = CapLight::<f64>::new(v(axis), sigma).unwrap();
                        let sens = sensitivity(
                            |x| {
                                let cap = CapLight::<f64>::new(v(v3_at(x, 0)), x[6]).ok()?;
                                Some(cap.phong(&hi_l, v(v3_at(x, 1))))
                            },
                            &flat(&[axis, r], &[sigma]),
                        );
                        errs[j].add(
                            lo.phong(&lo_l, v(r)).to_f64(),
                            hi.phong(&hi_l, v(r)),
                            Cond {
                                m,
                                sens,
                                near: None,
                            },
                            || format!("m={m} axis={axis:?} sigma={sigma:e} r={r:?}"),
                        );
                    }
                }
                check_bounded(&errs.iter().collect::<Vec<_>>());
            }

            #[test]
            fn sphere_vs_f64() {
                let mut rng = Rng::new(0xa02);
                let cases = sphere_cases(&mut rng, 3000);
                let mut errs = trackers("phong_sphere", "");
                for (j, &m) in EXPONENTS.iter().enumerate() {
                    let (lo_l, hi_l) = lobes(m);
                    for &(center, radius, p, r) in &cases {
                        let (center, p, r) = (rdv::<T>(center), rdv::<T>(p), rdv::<T>(r));
                        let radius = rd::<T>(radius);
                        let lo = SphereLight::<T>::new(v(center), T::from_f64(radius)).unwrap();
                        let hi = SphereLight::<f64>::new(v(center), radius).unwrap();
                        let Ok(want) = hi.try_phong(&hi_l, v(p), v(r)) else {
                            continue;
                        };
                        let sens = sensitivity(
                            |x| {
                                let s = SphereLight::<f64>::new(v(v3_at(x, 0)), x[9]).ok()?;
                                s.try_phong(&hi_l, v(v3_at(x, 1)), v(v3_at(x, 2))).ok()
                            },
                            &flat(&[center, p, r], &[radius]),
                        );
                        errs[j].add(
                            lo.phong(&lo_l, v(p), v(r)).to_f64(),
                            want,
                            Cond {
                                m,
                                sens,
                                near: None,
                            },
                            || {
                                format!(
                                    "m={m} center={center:?} radius={radius:e} p={p:?} r={r:?} \
                                     d/radius={:.6}",
                                    norm(sub(p, center)) / radius
                                )
                            },
                        );
                    }
                }
                check_bounded(&errs.iter().collect::<Vec<_>>());
            }

            #[test]
            fn polygon_vs_f64() {
                let mut rng = Rng::new(0xa03);
                let random = random_polygons(&mut rng, 1500);
                let adversarial = adversarial_polygons(&mut rng);
                let mut all_errs = Vec::new();
                let mut skipped = 0;
                for (set, cases) in [("random", &random), ("adversarial", &adversarial)] {
                    let mut errs = trackers("phong_polygon", &format!(" ({set})"));
                    let mut by = ByKind::default();
                    for (j, &m) in EXPONENTS.iter().enumerate() {
                        let (lo_l, hi_l) = lobes(m);
                        for c in cases.iter() {
                            let verts: Vec<V3> = c.verts.iter().map(|&x| rdv::<T>(x)).collect();
                            let (p, r) = (rdv::<T>(c.p), rdv::<T>(c.k));
                            let lo_v: Vec<_> = verts.iter().map(|&x| v::<T>(x)).collect();
                            let hi_v: Vec<_> = verts.iter().map(|&x| v::<f64>(x)).collect();
                            let (Ok(lo), Ok(hi)) = (
                                PolygonLight::<T, 8>::new(&lo_v),
                                PolygonLight::<f64, 8>::new(&hi_v),
                            ) else {
                                skipped += 1;
                                continue;
                            };
                            let got = lo.phong(&lo_l, v(p), v(r)).to_f64();
                            let want = hi.phong(&hi_l, v(p), v(r));
                            let nv = verts.len();
                            let mut pts = verts.clone();
                            pts.extend([p, r]);
                            let sens = sensitivity(
                                |x| {
                                    let vs: Vec<_> = (0..nv).map(|i| v(v3_at(x, i))).collect();
                                    let l = PolygonLight::<f64, 8>::new(&vs).ok()?;
                                    Some(l.phong(&hi_l, v(v3_at(x, nv)), v(v3_at(x, nv + 1))))
                                },
                                &flat(&pts, &[]),
                            );
                            let cond = Cond {
                                m,
                                sens,
                                near: near_boundary(&verts, p),
                            };
                            let bound = errs[j].add(got, want, cond, || {
                                format!("m={m} {} verts={verts:?} p={p:?} r={r:?}", c.kind)
                            });
                            let parity = if m % 2 == 0 { "even m" } else { "odd m" };
                            by.add(&format!("{parity}: {}", c.kind), got, want, bound);
                        }
                    }
                    if set == "adversarial" {
                        by.report(&format!("phong_polygon {NAME} vs f64 (adversarial)"));
                    }
                    all_errs.extend(errs);
                }
                println!(
                    "phong_polygon {NAME}: {skipped} (case, m) skipped (invalid after rounding)"
                );
                check_bounded(&all_errs.iter().collect::<Vec<_>>());
            }
        }
    };
}

lowp_tests!(f32_vs_f64, f32, BOUNDS_F32);
lowp_tests!(fast32_vs_f64, Fast32, BOUNDS_FAST32);

/// `[phong_polygon]` is scale invariant: the same configuration scaled by 2^k (exact) gives
/// the same value, on f64 and f32, from the smallest coordinates the type represents to the
/// largest, for odd and even m (the even path adds the solid angle of the clipped projection:
/// the fan and the J terms must drop or keep an edge together). Short edges and close shading
/// points below `T::TINY` in absolute terms are not small relative to the configuration.
/// (Before the fix: f32 at 2^-40 and below and 2^70 and above, f64 at 2^-500, gave 0
/// instead of up to 0.69.) Every scaled copy the constructor accepts at scale 1 must be
/// accepted and evaluated.
fn phong_scale_invariance<T: Real>(name: &str, exps: &[i32], tol: f64) -> Vec<String> {
    let mut rng = Rng::new(0x5ca1e + exps.len() as u64);
    let mut bad = Vec::new();
    let mut worst = 0.0f64;
    let mut evaluated = 0;
    for c in random_polygons(&mut rng, 60) {
        let verts: Vec<V3> = c.verts.iter().map(|&x| rdv::<T>(x)).collect();
        let (p, r) = (rdv::<T>(c.p), rdv::<T>(c.k));
        for m in [1u32, 2, 8, 9] {
            let lobe = PhongLobe::<T>::new(m).unwrap();
            let at = |e: i32| -> Option<f64> {
                let s = 2f64.powi(e);
                let vs: Vec<Vec3<T>> = verts.iter().map(|&x| v(scale(x, s))).collect();
                let l = PolygonLight::<T, 8>::new(&vs).ok()?;
                Some(l.phong(&lobe, v(scale(p, s)), v(r)).to_f64())
            };
            let Some(base) = at(0) else { continue };
            for &e in exps {
                let Some(x) = at(e) else {
                    bad.push(format!("{name} m={m} 2^{e}: refused"));
                    continue;
                };
                evaluated += 1;
                let err = (x - base).abs();
                worst = worst.max(err);
                if err > tol || err.is_nan() {
                    bad.push(format!("{name} m={m} 2^{e}: {x:e} vs {base:e}"));
                }
            }
        }
    }
    println!(
        "[maxerr] phong_polygon {name} scaled by 2^{exps:?} vs unscaled: {worst:.3e} \
         ({evaluated} scaled cases)"
    );
    assert!(
        evaluated >= 100 * exps.len(),
        "{name}: only {evaluated} scaled cases"
    );
    bad
}

#[test]

fn phong_polygon_is_scale_invariant() {
    let mut bad = phong_scale_invariance::<f64>("f64", &[-900, -500, -100, 100, 500, 900], 1e-13);
    bad.extend(phong_scale_invariance::<f32>(
        "f32",
        &[-120, -100, -70, -40, 40, 70, 100, 120],
        2e-6,
    ));
    assert!(
        bad.is_empty(),
        "{} cases not scale invariant; first: {}",
        bad.len(),
        bad[..bad.len().min(8)].join("; ")
    );
}

/// An edge shorter than `T::TINY` (a vertex within TINY of its neighbour) changes nothing:
/// the polygon with it equals the polygon without it, for odd m (the J terms) and even m (the
/// J terms plus the fan of the clipped solid angle, which must drop such an edge with them).
#[test]
fn an_edge_below_tiny_changes_nothing() {
    fn check<T: Real>(name: &str, delta: f64, tol: f64) -> f64 {
        let mut rng = Rng::new(0x7e1e);
        let mut worst = 0.0f64;
        for _ in 0..200 {
            let (a, c, d) = ([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
            let b = [delta, delta, 0.0];
            let p = [
                rng.range(-0.5, 1.0),
                rng.range(-0.5, 1.0),
                rng.range(0.1, 1.0),
            ];
            let r = rng.dir();
            let with: Vec<Vec3<T>> = [a, b, c, d].iter().map(|&x| v(x)).collect();
            let without: Vec<Vec3<T>> = [a, c, d].iter().map(|&x| v(x)).collect();
            let (Ok(l4), Ok(l3)) = (
                PolygonLight::<T, 4>::new(&with),
                PolygonLight::<T, 4>::new(&without),
            ) else {
                panic!("{name}: constructor refused the polygon");
            };
            for m in [0u32, 1, 2, 7, 8] {
                let lobe = PhongLobe::<T>::new(m).unwrap();
                let (x, y) = (
                    l4.phong(&lobe, v(p), v(r)).to_f64(),
                    l3.phong(&lobe, v(p), v(r)).to_f64(),
                );
                worst = worst.max((x - y).abs());
                assert!(
                    (x - y).abs() <= tol,
                    "{name} m={m}: {x:e} with the edge, {y:e} without; p={p:?} r={r:?}"
                );
            }
            let (x, y) = (
                l4.lambert(v(p), v(r)).to_f64(),
                l3.lambert(v(p), v(r)).to_f64(),
            );
            assert!((x - y).abs() <= tol, "{name} lambert: {x:e} vs {y:e}");
        }
        println!("[maxerr] {name}: polygon with an edge of {delta:e} vs without: {worst:.3e}");
        worst
    }
    check::<f64>("f64", 1e-160, 1e-15);
    check::<f32>("f32", 1e-20, 1e-6);
}
