//! Fixed point near a polygon light's boundary: no silent wrong answers.
//!
//! `Fixed22` rounds absolutely (`2^-22`), so the direction from a shading point to a vertex a
//! few hundred units of `2^-22` away, or the plane through the point and an edge passing that
//! close, is known only roughly. The polygon models refuse such points
//! (`Error::Unresolved("p")`; the plain functions return 0) and answer every other point within
//! 1/1024. Here: shading points near the vertices and edges of random polygons (0.3 to 500
//! units across, positions up to 1000 units, through the world-coordinate path) at distances
//! from 1e-8 to 0.3 of the polygon's size, every Phong exponent up to 255, against the f64
//! model on the exact differences. Each answered point must be within 1/1024; each point at
//! least 1/64 of the scene's scale from the boundary must be answered.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod common;

use arealight::{
    Error, Fixed22, PhongLobe, PolygonLight, Real, Vec3, WorldPoint, WorldPolygonLight,
};
use common::*;

const TOL: f64 = 1.0 / 1024.0;

/// A random polygon (3 to 8 vertices on an ellipse) and a point near one of its vertices or
/// edges: `(verts, p, n, m, distance / size)`.
fn near_case(rng: &mut Rng) -> (Vec<V3>, V3, V3, u32, f64) {
    let c = [
        rng.range(-1000.0, 1000.0),
        rng.range(-1000.0, 1000.0),
        rng.range(-1000.0, 1000.0),
    ];
    let size = 10f64.powf(rng.range(-0.5, 2.7));
    let verts = ellipse_polygon(rng, c, size);
    let k = verts.len();
    let i = rng.below(k as u64) as usize;
    let rel = 10f64.powf(rng.range(-8.0, -0.5));
    let d = size * rel;
    let at = if rng.below(2) == 0 {
        verts[i]
    } else {
        let t = rng.range(0.0, 1.0);
        add(verts[i], scale(sub(verts[(i + 1) % k], verts[i]), t))
    };
    let p = add(at, scale(rng.dir(), d));
    let m = [rng.below(32), 32 + rng.below(96), 128 + rng.below(128), 255][rng.below(4) as usize];
    (verts, p, rng.dir(), m as u32, rel)
}

/// `a - p` from the world points' bits (exact), rounded once to f64.
fn diff(a: WorldPoint, p: WorldPoint) -> V3 {
    let (a, p) = (a.to_bits(), p.to_bits());
    [0, 1, 2].map(|i| (a[i] - p[i]) as f64 / 4294967296.0)
}

#[test]
fn answered_within_1_1024_or_refused_near_the_boundary() {
    let mut rng = Rng::new(0x6e_ea_12);
    let mut lambert = MaxErr::new("near boundary polygon_lambert Fixed22 (world), answered");
    let mut phong = MaxErr::new("near boundary phong_polygon Fixed22 (world), answered");
    // [decade of distance/size] (answered, refused), Lambert and Phong together.
    let mut by_decade = [(0usize, 0usize); 8];
    for _ in 0..40_000 {
        let (verts, p, n, m, rel) = near_case(&mut rng);
        let wv: Vec<WorldPoint> = verts
            .iter()
            .map(|&a| WorldPoint::from_f64(a, "v").unwrap())
            .collect();
        let wp = WorldPoint::from_f64(p, "p").unwrap();
        let Ok(light) = WorldPolygonLight::<Fixed22, 8>::new(&wv) else {
            continue;
        };
        // The reference: f64 on the exact differences, at n as Fixed22 rounds it.
        let nf = rdv::<Fixed22>(n);
        let local: Vec<Vec3<f64>> = wv.iter().map(|&a| v(diff(a, wp))).collect();
        let reference = PolygonLight::<f64, 8>::new(&local).unwrap();
        let o = v([0.0; 3]);
        let lobe = PhongLobe::new(m).unwrap();
        let want = [
            reference.try_lambert(o, v(nf)),
            reference.try_phong(&PhongLobe::new(m).unwrap(), o, v(nf)),
        ];
        let nn = Vec3::<Fixed22>::from_f64(n);
        let got = [light.try_lambert(wp, nn), light.try_phong(&lobe, wp, nn)];
        // The scene's scale: the largest coordinate of the differences.
        let s = local.iter().fold(0.0f64, |a, u| {
            a.max(u.x.abs()).max(u.y.abs()).max(u.z.abs())
        });
        let dist = boundary_distance(
            &local.iter().map(|u| [u.x, u.y, u.z]).collect::<Vec<_>>(),
            [0.0; 3],
        );
        let decade = ((-rel.log10()) as usize).min(7);
        for (k, (g, w)) in got.into_iter().zip(want).enumerate() {
            let Ok(w) = w else { continue };
            let describe = || format!("verts {verts:?} p {p:?} n {n:?} m {m} dist/size {rel:e}");
            match g {
                Ok(g) => {
                    by_decade[decade].0 += 1;
                    let e = if k == 0 { &mut lambert } else { &mut phong };
                    e.add(g.to_f64(), w, describe);
                }
                Err(Error::Unresolved("p")) => {
                    by_decade[decade].1 += 1;
                    assert!(
                        dist < s / 64.0,
                        "refused at {:.3e} of the scale: {}",
                        dist / s,
                        describe()
                    );
                }
                Err(e) => panic!("unexpected {e:?}: {}", describe()),
            }
        }
    }
    for (i, (a, r)) in by_decade.iter().enumerate() {
        println!(
            "distance/size 1e-{} to 1e-{i}: {a} answered, {r} refused",
            i + 1
        );
    }
    // Far enough, nothing is refused; close enough, nothing is answered.
    assert!(by_decade[0].1 == 0 && by_decade[0].0 > 0);
    assert!(by_decade[7].0 == 0 && by_decade[7].1 > 0);
    lambert.check(TOL);
    phong.check(TOL);
}

/// The case, on the plain path: a point 1e-6 from a polygon's vertex (which fixed point
/// answered 0.43 for, 436 times the bound) is refused, and the plain functions give 0.
#[test]
fn a_point_a_millionth_from_a_vertex_is_refused() {
    let verts = [
        [-1.0, -1.0, 1.0],
        [1.0, -1.0, 1.0],
        [1.0, 1.0, 1.0],
        [-1.0, 1.0, 1.0],
    ];
    let light = PolygonLight::<Fixed22, 4>::new(&verts.map(v::<Fixed22>)).unwrap();
    let lobe = PhongLobe::new(16).unwrap();
    let n = v::<Fixed22>([0.0, 0.0, 1.0]);
    for dir in [[1.0, 1.0, -1.0], [-0.3, 0.2, -1.0], [0.5, -0.5, 0.1]] {
        let p = v::<Fixed22>(add([1.0, 1.0, 1.0], scale(normalize(dir), 1e-6)));
        assert_eq!(light.try_lambert(p, n), Err(Error::Unresolved("p")));
        assert_eq!(light.try_phong(&lobe, p, n), Err(Error::Unresolved("p")));
        assert_eq!(light.lambert(p, n), Fixed22::ZERO);
        assert_eq!(light.phong(&lobe, p, n), Fixed22::ZERO);
    }
    // In the plane, just outside an edge (within the rounding of the plane, within 2^-8 of the
    // edge): refused too; in the plane far outside: 0, answered.
    let beside = v::<Fixed22>([1.001, 0.0, 1.0]);
    assert_eq!(light.try_lambert(beside, n), Err(Error::Unresolved("p")));
    let far = v::<Fixed22>([3.0, 0.0, 1.0]);
    assert_eq!(light.try_lambert(far, n), Ok(Fixed22::ZERO));
    // A point well off the boundary is answered, within 1/1024 of f64.
    let p = [0.9, 0.8, 0.7];
    let f64_light = PolygonLight::<f64, 4>::new(&verts.map(v::<f64>)).unwrap();
    let got = light.try_lambert(v(p), n).unwrap().to_f64();
    let want = f64_light.lambert(v(rdv::<Fixed22>(p)), v([0.0, 0.0, 1.0]));
    assert!((got - want).abs() <= TOL, "{got} {want}");
}
