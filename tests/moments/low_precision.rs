//! f32 and Fast32 against f64 on the same rounded inputs, per regime (`Bounded` of
//! tests/common), with the cases in the library's in-plane cutoff reported apart.

use super::*;

// ---------------------------------------------------------------------------------------------
// f32 and Fast32 vs f64
// ---------------------------------------------------------------------------------------------

/// Whether `p` is within the library's in-plane cutoff for f32 (4 f32 epsilons of the distance
/// to vertex 0, from a rounded normal: taken with margin 4): a case there whose value is exactly
/// 0 got the documented in-plane fallback of every polygon model, since
/// the rounding of `T` cannot tell the two sides of the plane apart. The f64 value there is
/// the solid-angle-like quantity seen from height ~1e-7: up to 2 pi for the raw moments with
/// the foot inside the polygon (no cosine factor), so these cases are reported apart.
fn in_plane_cutoff(verts: &[V3], p: V3) -> bool {
    let nn = normalize(qd::newell(verts));
    let d = sub(verts[0], p);
    let m = d[0].abs().max(d[1].abs()).max(d[2].abs());
    dot(nn, d).abs() <= 32.0 * EPS_F32 * m
}

/// Fast32 near the polygon's boundary (p within 2% of the size from an edge): the edge terms,
/// each up to pi, cancel to the result, and Fast32's atan2 carries an absolute error of
/// 1.2e-5 rad: measured `err <= 1/1024 + 2^-18 size/dist` (stated here, asserted below, capped
/// at `BOUND_CAP`; the cases whose f32 bound is beyond the cap go to `Bounded`'s regimes).
const FAST32_NEAR_FACTOR: f64 = 1.0 / 262_144.0;

fn lowp<T: Real>(bounds: LowpBounds, backend: &str) {
    let mut rng = Rng::new(0x10f3);
    let (rand, adv, _) = cases(&mut rng, 60);
    let mut trackers: Vec<Bounded> = Vec::new();
    let mut cutoff = MaxErr::new(&format!("all models {backend}: in-plane cutoff (value 0)"));
    let mut fast_near = MaxErr::new(&format!(
        "all models {backend}: near boundary, err/(size/dist)"
    ));
    let mut fast_near_bad = Vec::new();
    for model in MODELS {
        let mut t = Bounded::new(&format!("{} {backend} vs f64", name(model)), bounds);
        for cs in rand.iter().chain(adv.iter()) {
            let c = &cs.c;
            let verts: Vec<V3> = c.verts.iter().map(|&x| rdv::<T>(x)).collect();
            let (p, a, b) = (rdv::<T>(c.p), rdv::<T>(c.k), rdv::<T>(cs.b));
            let (Ok(lt), Ok(l64)) = (light::<T, 8>(&verts), light::<f64, 8>(&verts)) else {
                continue;
            };
            for m in MS {
                let got = lib(&lt, model, p, a, b, m);
                let want = lib(&l64, model, p, a, b, m);
                let nv = verts.len();
                let x = flat(
                    &verts.iter().copied().chain([p, a, b]).collect::<Vec<_>>(),
                    &[],
                );
                let sens = sensitivity(
                    |y| {
                        let vs: Vec<V3> = (0..nv).map(|i| v3_at(y, i)).collect();
                        let l = light::<f64, 8>(&vs).ok()?;
                        Some(lib(
                            &l,
                            model,
                            v3_at(y, nv),
                            v3_at(y, nv + 1),
                            v3_at(y, nv + 2),
                            m,
                        ))
                    },
                    &x,
                );
                let near = near_boundary(&verts, p);
                if got == 0.0 && in_plane_cutoff(&verts, p) {
                    cutoff.add(got, want, || format!("m={m} {}", c.describe()));
                    continue;
                }
                let cond = Cond { m, sens, near };
                // Fast32 near the boundary, below the cap (beyond it: `Bounded`'s capped and
                // unresolved regimes, as for f32).
                if let (false, Some((size, dist)), None) =
                    (bounds.extra_terms, near, beyond_cap(&cond))
                {
                    let err = abs_err(got, want);
                    fast_near.add(err * dist / size, 0.0, || {
                        format!("{} m={m} err {err:.3e} {}", name(model), c.describe())
                    });
                    let bound = (TOL_FAST32 + FAST32_NEAR_FACTOR * size / dist).min(BOUND_CAP);
                    if !(err <= bound) {
                        fast_near_bad.push(format!(
                            "{} m={m} err {err:.3e} {}",
                            name(model),
                            c.describe()
                        ));
                    }
                    continue;
                }
                t.add(got, want, cond, || {
                    format!("m={m} b={b:?} {}", c.describe())
                });
            }
        }
        trackers.push(t);
    }
    let mut lune = Bounded::new(&format!("lune_normalization {backend} vs f64"), bounds);
    for i in 0..300 {
        let w = rdv::<T>(rng.dir());
        let t = rng.range(0.0, std::f64::consts::PI);
        let vv = rdv::<T>(if i % 2 == 0 {
            rng.dir()
        } else {
            rng.dir_at(w, t)
        });
        for m in MS {
            let got = lune_normalization(v::<T>(w), v::<T>(vv), m).to_f64();
            let want = lune_normalization(v::<f64>(w), v::<f64>(vv), m);
            let sens = sensitivity(
                |y| {
                    Some(lune_normalization(
                        v::<f64>(v3_at(y, 0)),
                        v::<f64>(v3_at(y, 1)),
                        m,
                    ))
                },
                &flat(&[w, vv], &[]),
            );
            lune.add(
                got,
                want,
                Cond {
                    m,
                    sens,
                    near: None,
                },
                || format!("w={w:?} v={vv:?} m={m}"),
            );
        }
    }
    trackers.push(lune);
    cutoff.report();
    if !bounds.extra_terms {
        fast_near.report();
        assert!(fast_near_bad.is_empty(), "{}", fast_near_bad.join("\n"));
    }
    check_bounded(&trackers.iter().collect::<Vec<_>>());
}

#[test]
fn f32_vs_f64() {
    lowp::<f32>(BOUNDS_F32, "f32");
}

#[test]
fn fast32_vs_f64() {
    lowp::<Fast32>(BOUNDS_FAST32, "Fast32");
}
