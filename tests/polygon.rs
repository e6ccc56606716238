//! Polygon lights, Lambertian: `[polygon_lambert]`.
//!
//! f64 library vs the independent quadrature (<= 1e-9) on random polygons (triangles, quads,
//! star-shaped 7-gons, L- and U-shapes) and adversarial ones (partly or wholly below the
//! horizon, horizon through a vertex or a notch, nearly edge-on to p with the foot inside and
//! outside, p near a vertex or an edge, stars), then f32 and Fast32 vs f64 on the same rounded
//! inputs (<= 2e-6 and <= 1/1024 in the main regime; see `f32_bound` in tests/common).

mod common;

use arealight::{Fast32, PolygonLight, Real};
use common::quadrature as qd;
use common::*;

/// Stars with 6 spikes (12 vertices, capacity 16), random placement and normal.
fn big_stars(rng: &mut Rng, count: usize) -> Vec<PolyCase> {
    (0..count)
        .map(|_| {
            let pts = star(6, rng.range(0.2, 0.7));
            let center = scale(rng.dir(), rng.range(0.5, 3.0));
            let size = rng.range(0.3, 2.0);
            PolyCase {
                kind: "star6".to_string(),
                verts: place(rng, &pts, center, size),
                p: [0.0; 3],
                k: rng.sdir(),
            }
        })
        .collect()
}

fn light<T: Real, const N: usize>(verts: &[V3]) -> Result<PolygonLight<T, N>, arealight::Error> {
    PolygonLight::<T, N>::new(&verts.iter().map(|&x| v::<T>(x)).collect::<Vec<_>>())
}

#[test]
fn f64_vs_quadrature() {
    let mut rng = Rng::new(0x9017);
    let q = Quad::STD;
    let mut e_rand = MaxErr::new("polygon_lambert f64 vs quadrature (random)");
    let mut e_adv = MaxErr::new("polygon_lambert f64 vs quadrature (adversarial)");
    for c in random_polygons(&mut rng, 300) {
        let lib = light::<f64, 8>(&c.verts).unwrap().lambert(v(c.p), v(c.k));
        e_rand.add(lib, qd::polygon_lambert(&c.verts, c.p, c.k, &q), || {
            c.describe()
        });
    }
    for c in big_stars(&mut rng, 40) {
        let lib = light::<f64, 16>(&c.verts).unwrap().lambert(v(c.p), v(c.k));
        e_rand.add(lib, qd::polygon_lambert(&c.verts, c.p, c.k, &q), || {
            c.describe()
        });
    }
    for c in adversarial_polygons(&mut rng) {
        let lib = light::<f64, 8>(&c.verts).unwrap().lambert(v(c.p), v(c.k));
        e_adv.add(lib, qd::polygon_lambert(&c.verts, c.p, c.k, &q), || {
            c.describe()
        });
    }
    let mut e_ext = MaxErr::new("polygon_lambert f64 vs quadrature (h <= 1e-8)");
    for c in extreme_edge_on(&mut rng) {
        let lib = light::<f64, 8>(&c.verts).unwrap().lambert(v(c.p), v(c.k));
        e_ext.add(lib, qd::polygon_lambert(&c.verts, c.p, c.k, &q), || {
            c.describe()
        });
    }
    check_all(&[(&e_rand, TOL_F64), (&e_adv, TOL_F64), (&e_ext, TOL_F64)]);
}

/// A shading point in the polygon's plane sees nothing (models.md: 0).
#[test]
fn in_plane_is_zero() {
    let verts = [
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 1.0],
        [0.0, 1.0, 1.0],
    ];
    let l = light::<f64, 8>(&verts).unwrap();
    for p in [[0.5, 0.5, 1.0], [3.0, -2.0, 1.0]] {
        for n in [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.3, -0.2, -1.0]] {
            assert_eq!(l.lambert(v(p), v(n)), 0.0);
            assert_eq!(qd::polygon_lambert(&verts, p, n, &Quad::STD), 0.0);
        }
    }
    println!("[maxerr] polygon_lambert in-plane p: exactly 0 (library and quadrature)");
}

/// f32 / Fast32 vs f64 on the same rounded inputs, every case against its own bound
/// (`f32_bound` in tests/common: 2e-6 and 1/1024 in the main regime, f32 near the boundary
/// `2e-6 + 16 2^-24 size / dist`, ill-conditioned `2e-6 + 4 sensitivity`).
macro_rules! lowp_tests {
    ($modname:ident, $T:ty, $bounds:expr) => {
        mod $modname {
            use super::*;
            type T = $T;
            const B: LowpBounds = $bounds;
            const NAME: &str = stringify!($T);

            fn run(cases: &[PolyCase], err: &mut Bounded, by: &mut ByKind, skipped: &mut usize) {
                for c in cases {
                    let verts: Vec<V3> = c.verts.iter().map(|&x| rdv::<T>(x)).collect();
                    let (p, n) = (rdv::<T>(c.p), rdv::<T>(c.k));
                    let (Ok(lo), Ok(hi)) = (light::<T, 16>(&verts), light::<f64, 16>(&verts))
                    else {
                        *skipped += 1;
                        continue;
                    };
                    let (got, want) = (lo.lambert(v(p), v(n)).to_f64(), hi.lambert(v(p), v(n)));
                    let nv = verts.len();
                    let mut pts = verts.clone();
                    pts.extend([p, n]);
                    let sens = sensitivity(
                        |x| {
                            let vs: Vec<V3> = (0..nv).map(|i| v3_at(x, i)).collect();
                            let l = light::<f64, 16>(&vs).ok()?;
                            Some(l.lambert(v(v3_at(x, nv)), v(v3_at(x, nv + 1))))
                        },
                        &flat(&pts, &[]),
                    );
                    let cond = Cond {
                        m: 0,
                        sens,
                        near: near_boundary(&verts, p),
                    };
                    let bound = err.add(got, want, cond, || {
                        format!("{} verts={verts:?} p={p:?} n={n:?}", c.kind)
                    });
                    by.add(&c.kind, got, want, bound);
                }
            }

            #[test]
            fn polygon_vs_f64() {
                let mut rng = Rng::new(0x9018);
                let mut e_rand =
                    Bounded::new(&format!("polygon_lambert {NAME} vs f64 (random)"), B);
                let mut e_adv =
                    Bounded::new(&format!("polygon_lambert {NAME} vs f64 (adversarial)"), B);
                let mut skipped = 0;
                let mut cases = random_polygons(&mut rng, 20_000);
                cases.extend(big_stars(&mut rng, 2000));
                let mut by = ByKind::default();
                run(&cases, &mut e_rand, &mut ByKind::default(), &mut skipped);
                run(
                    &adversarial_polygons(&mut rng),
                    &mut e_adv,
                    &mut by,
                    &mut skipped,
                );
                by.report(&format!("polygon_lambert {NAME} vs f64 (adversarial)"));
                println!(
                    "polygon_lambert {NAME}: {skipped} cases skipped (invalid after rounding)"
                );
                check_bounded(&[&e_rand, &e_adv]);
            }
        }
    };
}

lowp_tests!(f32_vs_f64, f32, BOUNDS_F32);
lowp_tests!(fast32_vs_f64, Fast32, BOUNDS_FAST32);
