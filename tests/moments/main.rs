//! Arvo's moments: `[axial_moment]`, `[double_axis_moment]`, `[directional_luminaire]`,
//! `[glossy_reflection]`, `[glossy_transmission]`, `[lune_normalization]`.
//!
//! f64 library vs the independent quadrature of `common/moments_quadrature.rs` (absolute,
//! within each model's row of the f64 budget, `F64_BUDGET` in tests/common). The raw moments are
//! in steradians and bounded by the solid angle of the projection (at most 2 pi), the shading
//! models by pi (directional) or about 1 (glossy, normalized), the lune by pi: so the absolute
//! errors are relative to a scale of order 1. Cases:
//! random polygons, adversarial ones (partly behind each clipping plane, nearly edge-on, p near
//! an edge or vertex, non-convex), m in {0, 1, 2, 3, 16, 63, 64}; then f32 and Fast32 vs f64 on
//! the same rounded inputs, per regime (`Bounded` of tests/common).

// `!(a <= b)` is deliberate: true when either side is NaN (as in tests/common).
#![allow(clippy::neg_cmp_op_on_partial_ord)]

#[path = "../common/mod.rs"]
mod common;
mod low_precision;
#[path = "../common/moments_quadrature.rs"]
mod mq;

use arealight::{lune_normalization, Fast32, PolygonLight, Real, Vec3};
use common::quadrature as qd;
use common::*;

const MS: [u32; 7] = [0, 1, 2, 3, 16, 63, 64];

fn light<T: Real, const N: usize>(verts: &[V3]) -> Result<PolygonLight<T, N>, arealight::Error> {
    PolygonLight::<T, N>::new(&verts.iter().map(|&x| v::<T>(x)).collect::<Vec<_>>())
}

/// Which model a case evaluates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Model {
    Axial,
    Double,
    Directional,
    GlossyR,
    GlossyT,
}

const MODELS: [Model; 5] = [
    Model::Axial,
    Model::Double,
    Model::Directional,
    Model::GlossyR,
    Model::GlossyT,
];

/// The library's value: `a` is `w` (axial, double), `n` (shading models); `b` is `v`, `axis`
/// or `e`.
fn lib<T: Real, const N: usize>(
    l: &PolygonLight<T, N>,
    model: Model,
    p: V3,
    a: V3,
    b: V3,
    m: u32,
) -> f64 {
    let (p, a, b) = (v::<T>(p), v::<T>(a), v::<T>(b));
    match model {
        Model::Axial => l.axial_moment(p, a, m),
        Model::Double => l.double_axis_moment(p, a, b, m),
        Model::Directional => l.directional_luminaire(p, a, b, m),
        Model::GlossyR => l.glossy_reflection(p, a, b, m),
        Model::GlossyT => l.glossy_transmission(p, a, b, m),
    }
    .to_f64()
}

fn quad(verts: &[V3], model: Model, p: V3, a: V3, b: V3, m: u32, q: &Quad) -> f64 {
    match model {
        Model::Axial => mq::axial_moment(verts, p, normalize(a), m, q),
        Model::Double => mq::double_axis_moment(verts, p, normalize(a), normalize(b), m, q),
        Model::Directional => mq::directional_luminaire(verts, p, a, b, m, q),
        Model::GlossyR => mq::glossy_reflection(verts, p, a, b, m, q),
        Model::GlossyT => mq::glossy_transmission(verts, p, a, b, m, q),
    }
}

fn name(model: Model) -> &'static str {
    match model {
        Model::Axial => "axial_moment",
        Model::Double => "double_axis_moment",
        Model::Directional => "directional_luminaire",
        Model::GlossyR => "glossy_reflection",
        Model::GlossyT => "glossy_transmission",
    }
}

/// The second direction of a case: for the glossy models an eye direction on the side of the
/// normal (reflection) or either side, else any direction; a third of them are tilted to
/// within a few degrees of the polygon's plane seen from p, so the second clipping plane cuts
/// the projection nearly edge-on too.
fn second_dir(rng: &mut Rng, c: &PolyCase, i: usize) -> V3 {
    match i % 3 {
        0 => rng.sdir(),
        1 => {
            // Toward the polygon's centroid, tilted by up to 0.5 rad.
            let cen = c.verts.iter().fold([0.0; 3], |s, &x| add(s, x));
            let cen = scale(cen, 1.0 / c.verts.len() as f64);
            let t = rng.range(0.0, 0.5);
            rng.dir_at(normalize(sub(cen, c.p)), t)
        }
        _ => {
            // Nearly perpendicular to the polygon's normal: its plane nearly contains the
            // polygon's plane direction.
            let nn = normalize(qd::newell(&c.verts));
            let t = rng.range(-0.05, 0.05);
            rng.dir_at(nn, std::f64::consts::FRAC_PI_2 + t)
        }
    }
}

struct Case {
    c: PolyCase,
    b: V3,
}

fn cases(rng: &mut Rng, random: usize) -> (Vec<Case>, Vec<Case>, Vec<Case>) {
    let mk = |rng: &mut Rng, v: Vec<PolyCase>| -> Vec<Case> {
        v.into_iter()
            .enumerate()
            .map(|(i, c)| {
                let b = second_dir(rng, &c, i);
                Case { c, b }
            })
            .collect()
    };
    let r = random_polygons(rng, random);
    let a = adversarial_polygons(rng);
    let e = extreme_edge_on(rng);
    (mk(rng, r), mk(rng, a), mk(rng, e))
}

// ---------------------------------------------------------------------------------------------
// The quadrature's self-check
// ---------------------------------------------------------------------------------------------

#[test]
fn quadrature_self_check() {
    let mut rng = Rng::new(0x3e1f);
    let q = Quad::STD;
    let mut e_sa = MaxErr::new("quad: m=0 axial, axis w1 vs w2");
    let mut e_ph = MaxErr::new("quad: clipped axial vs polygon_by_circles");
    let mut e_vw = MaxErr::new("quad: double(w, w, m) vs axial(m+1)");
    let mut e_fine = MaxErr::new("quad: STD vs FINE (all models)");
    let mut e_lune = MaxErr::new("quad: lune vs known values");
    for (i, c) in random_polygons(&mut rng, 40)
        .into_iter()
        .chain(adversarial_polygons(&mut rng).into_iter().take(40))
        .enumerate()
    {
        let w1 = normalize(c.k);
        let w2 = rng.dir();
        let a = mq::axial_moment(&c.verts, c.p, w1, 0, &q);
        let b = mq::axial_moment(&c.verts, c.p, w2, 0, &q);
        e_sa.add(a, b, || c.describe());
        let m = MS[i % MS.len()];
        let mine = mq::moment_by_circles(
            Some(&c.verts),
            c.p,
            w1,
            w1,
            m,
            false,
            true,
            false,
            q.tol,
            &q,
        );
        let theirs = qd::polygon_by_circles(&c.verts, c.p, w1, |x| x.powi(m as i32), q.tol, &q);
        e_ph.add(mine, theirs, || format!("m={m} {}", c.describe()));
        let d = mq::double_axis_moment(&c.verts, c.p, w1, w1, m, &q);
        let ax = mq::axial_moment(&c.verts, c.p, w1, m + 1, &q);
        e_vw.add(d, ax, || format!("m={m} {}", c.describe()));
        if i % 4 == 0 {
            let model = MODELS[(i / 4) % MODELS.len()];
            let b = rng.sdir();
            let s = quad(&c.verts, model, c.p, c.k, b, m, &q);
            let f = quad(&c.verts, model, c.p, c.k, b, m, &Quad::FINE);
            e_fine.add(s, f, || format!("{} m={m} {}", name(model), c.describe()));
        }
    }
    for i in 0..60 {
        let w = rng.dir();
        let m = MS[i % MS.len()];
        // w = v: 2 pi/(m + 2); m = 0: pi (1 + w.v)/2.
        e_lune.add(
            mq::lune_normalization(w, w, m, &q),
            std::f64::consts::TAU / (m as f64 + 2.0),
            || format!("w=v={w:?} m={m}"),
        );
        let v = rng.dir();
        e_lune.add(
            mq::lune_normalization(w, v, 0, &q),
            std::f64::consts::FRAC_PI_2 * (1.0 + dot(w, v)),
            || format!("w={w:?} v={v:?} m=0"),
        );
    }
    check_all(&[
        (&e_sa, 1e-12),
        (&e_ph, 1e-12),
        (&e_vw, 1e-12),
        (&e_fine, 1e-12),
        (&e_lune, 1e-12),
    ]);
}

// ---------------------------------------------------------------------------------------------
// f64 vs quadrature
// ---------------------------------------------------------------------------------------------

#[test]
fn f64_vs_quadrature() {
    let mut rng = Rng::new(0xa7c0);
    let q = Quad::STD;
    let (rand, adv, ext) = cases(&mut rng, 40);
    let mut trackers = Vec::new();
    for model in MODELS {
        for (label, set) in [
            ("random", &rand),
            ("adversarial", &adv),
            ("h <= 1e-8", &ext),
        ] {
            let mut e = MaxErr::new(&format!("{} f64 vs quadrature ({label})", name(model)));
            for (i, cs) in set.iter().enumerate() {
                let c = &cs.c;
                let l = light::<f64, 8>(&c.verts).unwrap();
                // Every m for the random and adversarial cases, two per extreme case.
                let ms: Vec<u32> = if label == "h <= 1e-8" {
                    vec![MS[i % 7], MS[(i + 3) % 7]]
                } else {
                    MS.to_vec()
                };
                for m in ms {
                    let got = lib(&l, model, c.p, c.k, cs.b, m);
                    let want = quad(&c.verts, model, c.p, c.k, cs.b, m, &q);
                    e.add(got, want, || format!("m={m} b={:?} {}", cs.b, c.describe()));
                }
            }
            trackers.push((model, e));
        }
    }
    let list: Vec<(&MaxErr, f64)> = trackers
        .iter()
        .map(|(model, e)| (e, tol_f64(name(*model))))
        .collect();
    check_all(&list);
}

#[test]
fn lune_f64_vs_quadrature() {
    let mut rng = Rng::new(0x1e9e);
    let q = Quad::STD;
    let mut e = MaxErr::new("lune_normalization f64 vs quadrature");
    let mut e_known = MaxErr::new("lune_normalization f64 vs known values");
    for i in 0..200 {
        let w = rng.dir();
        // Half the cases near the degenerate ends w.v = +-1 and the right angle.
        let t = rng.range(0.0, 1e-3);
        let vv = match i % 4 {
            0 => rng.dir(),
            1 => rng.dir_at(w, t),
            2 => rng.dir_at(w, std::f64::consts::PI - t),
            _ => rng.dir_at(w, std::f64::consts::FRAC_PI_2 + t - 0.5e-3),
        };
        for m in MS.into_iter().chain([5, 200]) {
            let got = lune_normalization(v::<f64>(w), v::<f64>(vv), m);
            let want = mq::lune_normalization(w, vv, m, &q);
            e.add(got, want, || format!("w={w:?} v={vv:?} m={m}"));
        }
        let m = MS[i % 7];
        e_known.add(
            lune_normalization(v::<f64>(w), v::<f64>(scale(w, 3.0)), m),
            std::f64::consts::TAU / (m as f64 + 2.0),
            || format!("w=v={w:?} m={m}"),
        );
        e_known.add(
            lune_normalization(v::<f64>(w), v::<f64>(scale(w, -0.5)), m),
            0.0,
            || format!("v=-w, w={w:?} m={m}"),
        );
    }
    check_all(&[(&e, tol_f64("lune_normalization")), (&e_known, 1e-14)]);
}

// ---------------------------------------------------------------------------------------------
// Identities of the library
// ---------------------------------------------------------------------------------------------

#[test]
fn identities() {
    let mut rng = Rng::new(0x1d);
    let mut e_sa = MaxErr::new("axial m=0 vs clipped_solid_angle");
    let mut e_vw = MaxErr::new("double(w, w, m) vs axial(m+1)");
    let mut e_wind = MaxErr::new("reversed winding (all models)");
    for (i, c) in random_polygons(&mut rng, 200).into_iter().enumerate() {
        let l = light::<f64, 8>(&c.verts).unwrap();
        let rev: Vec<V3> = c.verts.iter().rev().copied().collect();
        let lr = light::<f64, 8>(&rev).unwrap();
        let (p, w) = (v::<f64>(c.p), v::<f64>(c.k));
        // The solid angle clipped to the hemisphere about the polygon's direction (all of it).
        let nn = normalize(qd::newell(&c.verts));
        let toward = if dot(sub(c.verts[0], c.p), nn) > 0.0 {
            nn
        } else {
            scale(nn, -1.0)
        };
        e_sa.add(
            l.axial_moment(p, w, 0),
            l.clipped_solid_angle(p, v::<f64>(toward)),
            || c.describe(),
        );
        let m = MS[i % 7];
        e_vw.add(
            l.double_axis_moment(p, w, w, m),
            l.axial_moment(p, w, m + 1),
            || format!("m={m} {}", c.describe()),
        );
        let b = rng.sdir();
        for model in MODELS {
            e_wind.add(
                lib(&l, model, c.p, c.k, b, m),
                lib(&lr, model, c.p, c.k, b, m),
                || format!("{} m={m} {}", name(model), c.describe()),
            );
        }
    }
    check_all(&[(&e_sa, 1e-13), (&e_vw, 1e-12), (&e_wind, 1e-12)]);
}

// ---------------------------------------------------------------------------------------------
// Early termination
// ---------------------------------------------------------------------------------------------

#[test]
fn early_termination() {
    let mut rng = Rng::new(0xea51);
    for tol in [1e-3, 1e-6, 1e-9] {
        let mut e_ax = MaxErr::new(&format!("axial_moment_within tol={tol:e}"));
        let mut e_da = MaxErr::new(&format!("double_axis_moment_within tol={tol:e}"));
        let mut worst_ratio = 0.0f64;
        for (i, c) in random_polygons(&mut rng, 200).into_iter().enumerate() {
            let l = light::<f64, 8>(&c.verts).unwrap();
            let m = [16, 63, 64, 255, 1000][i % 5];
            let (p, w) = (v::<f64>(c.p), v::<f64>(c.k));
            let b = v::<f64>(rng.sdir());
            let exact = l.axial_moment(p, w, m);
            let fast = l.axial_moment_within(p, w, m, tol);
            e_ax.add(fast, exact, || format!("m={m} {}", c.describe()));
            worst_ratio = worst_ratio.max((fast - exact).abs() / tol);
            let exact = l.double_axis_moment(p, w, b, m);
            let fast = l.double_axis_moment_within(p, w, b, m, tol);
            e_da.add(fast, exact, || format!("m={m} {}", c.describe()));
            worst_ratio = worst_ratio.max((fast - exact).abs() / tol);
        }
        println!("[maxerr] early termination tol={tol:e}: max err/tol {worst_ratio:.3e}");
        // The guarantee is err <= tol (plus rounding of the full evaluation).
        check_all(&[(&e_ax, tol + 1e-13), (&e_da, tol + 1e-13)]);
    }
}

// ---------------------------------------------------------------------------------------------
// Invalid and adversarial inputs
// ---------------------------------------------------------------------------------------------

#[test]
fn invalid_inputs_and_no_nan() {
    use arealight::moments::try_lune_normalization;
    use arealight::phong::MAX_EXPONENT;
    use arealight::Error;
    let sq = [
        [-1.0, -1.0, 2.0],
        [1.0, -1.0, 2.0],
        [1.0, 1.0, 2.0],
        [-1.0, 1.0, 2.0],
    ];
    let l = light::<f64, 8>(&sq).unwrap();
    let o = v::<f64>([0.0; 3]);
    let z = v::<f64>([0.0, 0.0, 1.0]);
    let zero = Vec3::new(0.0, 0.0, 0.0);
    let nan = Vec3::new(f64::NAN, 0.0, 1.0);
    assert_eq!(
        l.try_axial_moment(o, z, MAX_EXPONENT + 1),
        Err(Error::ExponentOutOfRange)
    );
    assert_eq!(l.try_axial_moment(o, zero, 2), Err(Error::ZeroLength("w")));
    assert_eq!(l.try_axial_moment(nan, z, 2), Err(Error::NotFinite("p")));
    assert_eq!(
        l.try_double_axis_moment(o, z, nan, 2),
        Err(Error::NotFinite("v"))
    );
    assert_eq!(
        l.try_axial_moment_within(o, z, 2, f64::NAN),
        Err(Error::NotFinite("tol"))
    );
    assert_eq!(
        l.try_directional_luminaire(o, z, zero, 2),
        Err(Error::ZeroLength("axis"))
    );
    assert_eq!(
        l.try_glossy_reflection(o, zero, z, 2),
        Err(Error::ZeroLength("n"))
    );
    assert_eq!(
        l.try_glossy_transmission(o, z, nan, 2),
        Err(Error::NotFinite("e"))
    );
    assert_eq!(
        try_lune_normalization(z, zero, 2),
        Err(Error::ZeroLength("v"))
    );
    assert_eq!(
        try_lune_normalization(z, z, MAX_EXPONENT + 1),
        Err(Error::ExponentOutOfRange)
    );
    assert_eq!(l.axial_moment(nan, z, 2), 0.0);
    assert_eq!(lune_normalization(nan, z, 2), 0.0);
    // In the plane: 0.
    for p in [[0.0, 0.0, 2.0], [5.0, 0.0, 2.0]] {
        for model in MODELS {
            assert_eq!(lib(&l, model, p, [0.0, 0.2, 1.0], [0.1, 0.0, 1.0], 3), 0.0);
        }
    }
    // The largest exponent, huge and tiny coordinates, axes along the edges' planes: finite.
    let mut rng = Rng::new(0xbad);
    let mut vals = Vec::new();
    for model in MODELS {
        vals.push(lib(
            &l,
            model,
            [0.0; 3],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
            MAX_EXPONENT,
        ));
        vals.push(lib(
            &l,
            model,
            [0.0; 3],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            64,
        ));
        vals.push(lib(
            &l,
            model,
            [0.0, 0.0, 2.0 - 1e-300],
            [0.0, 0.0, 1.0],
            [0.0, 1.0, 0.0],
            3,
        ));
        for c in adversarial_polygons(&mut rng) {
            let big: Vec<V3> = c.verts.iter().map(|&x| scale(x, 1e150)).collect();
            let small: Vec<V3> = c.verts.iter().map(|&x| scale(x, 1e-150)).collect();
            for (vs, p) in [(big, scale(c.p, 1e150)), (small, scale(c.p, 1e-150))] {
                if let Ok(l) = light::<f64, 8>(&vs) {
                    for m in [0, 1, 64] {
                        vals.push(lib(&l, model, p, c.k, rng.sdir(), m));
                    }
                }
                let v32: Vec<V3> = vs.iter().map(|&x| rdv::<f32>(x)).collect();
                if let Ok(l) = light::<f32, 8>(&v32) {
                    vals.push(lib(&l, model, rdv::<f32>(p), c.k, [0.0, 1.0, 0.0], 3));
                }
            }
        }
    }
    for w in [[0.0, 0.0, 1.0], [1e-300, 0.0, 0.0], [1e300, 1e300, 0.0]] {
        vals.push(lune_normalization(
            v::<f64>(w),
            v::<f64>([0.0, 0.0, -1.0]),
            7,
        ));
        vals.push(lune_normalization(v::<f32>(w), v::<f32>([0.0, 1.0, 0.0]), 64).to_f64());
    }
    assert!(vals.iter().all(|x| x.is_finite()), "non-finite: {vals:?}");
}
