//! The models in `Fixed22` against f64 on the same fixed-rounded inputs, within 1/1024: the
//! hemisphere family, caps and spheres, SH9, polygons, the Phong integrals and the shaping
//! functions.

use super::*;

// ---------------------------------------------------------------------------------------------
// Models, against f64 on the same fixed-rounded inputs.
// ---------------------------------------------------------------------------------------------

/// Runs `f` for Fixed22 and f64 on the same inputs and tracks the max error; `None` from the
/// f64 side (an input the model rejects) skips the case, `None` from the fixed side while f64
/// accepts fails.
pub(super) struct Track {
    e: MaxErr,
    cases: usize,
}
impl Track {
    fn new(name: &str) -> Self {
        Track {
            e: MaxErr::new(name),
            cases: 0,
        }
    }
    fn add<D: Fn() -> String>(&mut self, got: Option<f64>, want: Option<f64>, d: D) {
        let Some(want) = want else { return };
        let Some(got) = got else {
            panic!(
                "{}: fixed rejected a case f64 accepts: {}",
                self.e.name,
                d()
            );
        };
        self.cases += 1;
        self.e.add(got, want, d);
    }
    fn finish(self) {
        println!("{}: {} cases", self.e.name, self.cases);
        self.e.report();
        assert!(self.cases > 0);
        self.e.check(TOL);
    }
}

pub(super) fn dirs(rng: &mut Rng, count: usize) -> Vec<V3> {
    let mut out: Vec<V3> = (0..count).map(|_| rng.sdir()).collect();
    for a in [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] {
        out.push(a);
        out.push(scale(a, -1.0));
    }
    out
}

#[test]
fn hemisphere_family_within_tolerance() {
    let mut rng = Rng::new(0x4e31);
    let mut hc = Track::new("hemi_const Fixed22 vs f64");
    let mut hcos = Track::new("hemi_cos Fixed22 vs f64");
    let mut sky = Track::new("sky_overcast Fixed22 vs f64");
    let mut sg = Track::new("sky_ground Fixed22 vs f64");
    let ns = dirs(&mut rng, 20_000);
    for (i, &n) in ns.iter().enumerate() {
        let axis = if i % 3 == 0 {
            // Grazing: n within 1e-3 .. 1e-7 of the horizon.
            let a = rng.dir();
            let w = FRAC_PI_2 + rng.range(-1e-3, 1e-3);
            let _ = a;
            rng.dir_at(normalize(n), w)
        } else {
            rng.sdir()
        };
        let (n, axis) = (rdv::<F>(n), rdv::<F>(axis));
        fn hemi<T: Real>(axis: V3, n: V3, cos: bool) -> Option<f64> {
            let l = HemisphereLight::<T>::new(v(axis)).ok()?;
            Some(
                if cos {
                    l.lambert_cos(v(n))
                } else {
                    l.lambert_const(v(n))
                }
                .to_f64(),
            )
        }
        let d = || format!("axis={axis:?} n={n:?}");
        hc.add(hemi::<F>(axis, n, false), hemi::<f64>(axis, n, false), d);
        hcos.add(hemi::<F>(axis, n, true), hemi::<f64>(axis, n, true), d);
        let c = rd::<F>(rng.range(0.0, 4.0));
        fn overcast<T: Real>(z: V3, c: f64, n: V3) -> Option<f64> {
            let s = OvercastSky::<T>::new(v(z), T::from_f64(c)).ok()?;
            Some(s.lambert(v(n)).to_f64())
        }
        sky.add(overcast::<F>(axis, c, n), overcast::<f64>(axis, c, n), d);
        let (s, g) = (
            rdv::<F>([rng.unit(), rng.unit(), rng.unit()]),
            rdv::<F>([rng.unit(), rng.unit(), rng.unit()]),
        );
        fn skyground<T: Real>(up: V3, s: V3, g: V3, n: V3) -> Option<f64> {
            let l = SkyGround::<T>::new(v(up), rgb(s), rgb(g)).ok()?;
            let e = l.irradiance(v(n));
            Some(e.r.to_f64().max(e.g.to_f64()).max(e.b.to_f64()))
        }
        fn skyground_err<T: Real>(up: V3, s: V3, g: V3, n: V3) -> Option<[f64; 3]> {
            let l = SkyGround::<T>::new(v(up), rgb(s), rgb(g)).ok()?;
            let e = l.irradiance(v(n));
            Some([e.r.to_f64(), e.g.to_f64(), e.b.to_f64()])
        }
        let _ = skyground::<f64>;
        if let (Some(a), Some(b)) = (
            skyground_err::<F>(axis, s, g, n),
            skyground_err::<f64>(axis, s, g, n),
        ) {
            for k in 0..3 {
                sg.add(Some(a[k]), Some(b[k]), d);
            }
        }
    }
    for t in [hc, hcos, sky, sg] {
        t.finish();
    }
}

/// The cap and sphere lights against f64 on the same random and adversarial cases:
/// Snyder's Hermite approximations, or (`exact`) the exact models (`cap_lambert`,
/// `sphere_lambert`: measured 1.4e-6 and 8.4e-5 here, 2.4e-6 and 1.2e-4 over 200 000 random
/// cases each while probing), all within 1/1024.
pub(super) fn cap_and_sphere_within_tolerance(seed: u64, exact: bool) {
    let name = |m: &str| format!("{m}{} Fixed22 vs f64", if exact { "" } else { "_hermite" });
    let mut rng = Rng::new(seed);
    let mut cap = Track::new(&name("cap_lambert"));
    for (axis, sigma, n) in cap_cases(&mut rng, 20_000) {
        let (axis, n, sigma) = (rdv::<F>(axis), rdv::<F>(n), rd_max::<F>(sigma, FRAC_PI_2));
        fn f<T: Real>(axis: V3, sigma: f64, n: V3, exact: bool) -> Option<f64> {
            let c = CapLight::<T>::new(v(axis), T::from_f64(sigma)).ok()?;
            Some(
                if exact {
                    c.lambert(v(n))
                } else {
                    c.lambert_hermite(v(n))
                }
                .to_f64(),
            )
        }
        cap.add(
            f::<F>(axis, sigma, n, exact),
            f::<f64>(axis, sigma, n, exact),
            || format!("axis={axis:?} sigma={sigma} n={n:?}"),
        );
    }
    cap.finish();
    let mut sph = Track::new(&name("sphere_lambert"));
    for (c, r, p, n) in sphere_cases(&mut rng, 20_000) {
        let k = fit_scale(&[c, p, [r, 0.0, 0.0]]);
        let (c, r, p) = (scale(c, k), r * k, scale(p, k));
        let (c, r, p, n) = (rdv::<F>(c), rd::<F>(r), rdv::<F>(p), rdv::<F>(n));
        fn f<T: Real>(c: V3, r: f64, p: V3, n: V3, exact: bool) -> Option<f64> {
            let s = SphereLight::<T>::new(v(c), T::from_f64(r)).ok()?;
            let got = if exact {
                s.try_lambert(v(p), v(n))
            } else {
                s.try_lambert_hermite(v(p), v(n))
            };
            got.ok().map(|x| x.to_f64())
        }
        sph.add(
            f::<F>(c, r, p, n, exact),
            f::<f64>(c, r, p, n, exact),
            || format!("c={c:?} r={r} p={p:?} n={n:?}"),
        );
    }
    sph.finish();
}

#[test]
fn cap_and_sphere_hermite_within_tolerance() {
    cap_and_sphere_within_tolerance(0xca9, false);
}

/// The exact models are in the fixed path's supported list on the strength of this test.
#[test]
fn cap_and_sphere_exact_within_tolerance() {
    cap_and_sphere_within_tolerance(0xca9e, true);
}

#[test]
fn sh9_within_tolerance() {
    let mut rng = Rng::new(0x5e9);
    let mut env = Track::new("sh9_irradiance Fixed22 vs f64");
    let mut disc = Track::new("sh9_disc_irradiance Fixed22 vs f64");
    let ns = dirs(&mut rng, 20_000);
    for (i, &n) in ns.iter().enumerate() {
        let n = rdv::<F>(n);
        // Random radiance coefficients of magnitude <= 1 (band 0 positive).
        let coeffs: Vec<V3> = (0..9)
            .map(|k| {
                let lo = if k == 0 { 0.0 } else { -1.0 };
                rdv::<F>([rng.range(lo, 1.0), rng.range(lo, 1.0), rng.range(lo, 1.0)])
            })
            .collect();
        fn e<T: Real>(coeffs: &[V3], n: V3) -> Option<[f64; 3]> {
            let c: [Rgb<T>; 9] = core::array::from_fn(|k| rgb(coeffs[k]));
            let x = Sh9::new(c).ok()?.prepare().irradiance(v(n));
            Some([x.r.to_f64(), x.g.to_f64(), x.b.to_f64()])
        }
        if let (Some(a), Some(b)) = (e::<F>(&coeffs, n), e::<f64>(&coeffs, n)) {
            for k in 0..3 {
                env.add(Some(a[k]), Some(b[k]), || {
                    format!("coeffs={coeffs:?} n={n:?}")
                });
            }
        }
        let axis = rdv::<F>(rng.sdir());
        let alpha = if i % 4 == 0 {
            [0.0, 1e-3, FRAC_PI_2, PI][i / 4 % 4]
        } else {
            rng.range(0.0, PI)
        };
        let alpha = rd_max::<F>(alpha, PI);
        fn d<T: Real>(axis: V3, alpha: f64, n: V3) -> Option<f64> {
            let s = Sh9::<T>::disc(v(axis), T::from_f64(alpha), Rgb::splat(T::ONE)).ok()?;
            Some(s.prepare().irradiance(v(n)).r.to_f64())
        }
        disc.add(d::<F>(axis, alpha, n), d::<f64>(axis, alpha, n), || {
            format!("axis={axis:?} alpha={alpha} n={n:?}")
        });
    }
    env.finish();
    disc.finish();
}

/// Polygon cases inside the fixed path's supported range: the shading point at least
/// `MIN_REL_DIST` of the polygon's size from its boundary (closer, the model's derivative
/// `~ size/dist` times the `2^-22` rounding of the direction vectors exceeds the budget; see
/// the module docs of `real::fixed22`).
pub(super) const MIN_REL_DIST: f64 = 1.0 / 256.0;

pub(super) fn in_fixed_range(c: &PolyCase) -> bool {
    let verts: Vec<V3> = c.verts.iter().map(|&x| rdv::<F>(x)).collect();
    boundary_distance(&verts, rdv::<F>(c.p)) >= MIN_REL_DIST * diameter(&verts)
}

pub(super) fn polygon_cases(rng: &mut Rng) -> (Vec<PolyCase>, usize) {
    let mut cases = random_polygons(rng, 10_000);
    cases.extend(adversarial_polygons(rng));
    for c in &mut cases {
        let mut pts = c.verts.clone();
        pts.push(c.p);
        let k = fit_scale(&pts);
        c.verts = c.verts.iter().map(|&x| scale(x, k)).collect();
        c.p = scale(c.p, k);
    }
    let all = cases.len();
    cases.retain(in_fixed_range);
    (cases, all)
}

#[test]
fn polygon_lambert_within_tolerance() {
    let mut rng = Rng::new(0x9013);
    let (cases, all) = polygon_cases(&mut rng);
    let mut t = Track::new("polygon_lambert Fixed22 vs f64");
    let mut by = ByKind::default();
    for c in &cases {
        let verts: Vec<V3> = c.verts.iter().map(|&x| rdv::<F>(x)).collect();
        let (p, n) = (rdv::<F>(c.p), rdv::<F>(c.k));
        fn f<T: Real>(verts: &[V3], p: V3, n: V3) -> Option<f64> {
            let vs: Vec<Vec3<T>> = verts.iter().map(|&x| v(x)).collect();
            let l = PolygonLight::<T, 16>::new(&vs).ok()?;
            l.try_lambert(v(p), v(n)).ok().map(|x| x.to_f64())
        }
        let (got, want) = (f::<F>(&verts, p, n), f::<f64>(&verts, p, n));
        if let (Some(g), Some(w)) = (got, want) {
            by.add(&c.kind, g, w, TOL);
        }
        t.add(got, want, || c.describe());
    }
    by.report("polygon_lambert Fixed22 vs f64 (random + adversarial)");
    println!(
        "polygon_lambert Fixed22: {} of {all} cases in the supported range",
        cases.len()
    );
    t.finish();
}

pub(super) const EXPONENTS: [u32; 9] = [0, 1, 2, 3, 16, 63, 64, 128, 255];

#[test]
fn phong_hemi_and_cap_within_tolerance() {
    let mut rng = Rng::new(0xf0a9);
    for m in EXPONENTS {
        let mut hc = Track::new(&format!("phong_hemi_const m={m} Fixed22 vs f64"));
        let mut hcos = Track::new(&format!("phong_hemi_cos m={m} Fixed22 vs f64"));
        let mut cap = Track::new(&format!("phong_cap m={m} Fixed22 vs f64"));
        for (axis, sigma, r) in cap_cases(&mut rng, 3000) {
            let (axis, r, sigma) = (rdv::<F>(axis), rdv::<F>(r), rd_max::<F>(sigma, FRAC_PI_2));
            fn h<T: Real>(m: u32, axis: V3, r: V3, cos: bool) -> Option<f64> {
                let l = HemisphereLight::<T>::new(v(axis)).ok()?;
                let lobe = PhongLobe::new(m).ok()?;
                Some(
                    if cos {
                        l.phong_cos(&lobe, v(r))
                    } else {
                        l.phong_const(&lobe, v(r))
                    }
                    .to_f64(),
                )
            }
            fn c<T: Real>(m: u32, axis: V3, sigma: f64, r: V3) -> Option<f64> {
                let l = CapLight::<T>::new(v(axis), T::from_f64(sigma)).ok()?;
                let lobe = PhongLobe::new(m).ok()?;
                Some(l.phong(&lobe, v(r)).to_f64())
            }
            let d = || format!("axis={axis:?} sigma={sigma} r={r:?}");
            hc.add(h::<F>(m, axis, r, false), h::<f64>(m, axis, r, false), d);
            hcos.add(h::<F>(m, axis, r, true), h::<f64>(m, axis, r, true), d);
            cap.add(c::<F>(m, axis, sigma, r), c::<f64>(m, axis, sigma, r), d);
        }
        for t in [hc, hcos, cap] {
            t.finish();
        }
    }
}

#[test]
fn phong_sphere_and_polygon_within_tolerance() {
    let mut rng = Rng::new(0xf0b0);
    let (cases, _) = polygon_cases(&mut rng);
    for m in EXPONENTS {
        let mut sph = Track::new(&format!("phong_sphere m={m} Fixed22 vs f64"));
        for (c, r, p, dir) in sphere_cases(&mut rng, 2000) {
            let k = fit_scale(&[c, p, [r, 0.0, 0.0]]);
            let (c, r, p) = (scale(c, k), r * k, scale(p, k));
            let (c, rad, p, dir) = (rdv::<F>(c), rd::<F>(r), rdv::<F>(p), rdv::<F>(dir));
            fn f<T: Real>(m: u32, c: V3, rad: f64, p: V3, r: V3) -> Option<f64> {
                let s = SphereLight::<T>::new(v(c), T::from_f64(rad)).ok()?;
                let lobe = PhongLobe::new(m).ok()?;
                s.try_phong(&lobe, v(p), v(r)).ok().map(|x| x.to_f64())
            }
            sph.add(
                f::<F>(m, c, rad, p, dir),
                f::<f64>(m, c, rad, p, dir),
                || format!("c={c:?} radius={rad} p={p:?} r={dir:?}"),
            );
        }
        sph.finish();
        let mut poly = Track::new(&format!("phong_polygon m={m} Fixed22 vs f64"));
        for c in cases.iter().step_by(4) {
            let verts: Vec<V3> = c.verts.iter().map(|&x| rdv::<F>(x)).collect();
            let (p, r) = (rdv::<F>(c.p), rdv::<F>(c.k));
            fn f<T: Real>(m: u32, verts: &[V3], p: V3, r: V3) -> Option<f64> {
                let vs: Vec<Vec3<T>> = verts.iter().map(|&x| v(x)).collect();
                let l = PolygonLight::<T, 16>::new(&vs).ok()?;
                let lobe = PhongLobe::new(m).ok()?;
                l.try_phong(&lobe, v(p), v(r)).ok().map(|x| x.to_f64())
            }
            poly.add(f::<F>(m, &verts, p, r), f::<f64>(m, &verts, p, r), || {
                c.describe()
            });
        }
        poly.finish();
    }
    // Beyond the supported exponent the constructor refuses.
    assert_eq!(
        PhongLobe::<F>::new(256),
        Err(arealight::Error::ExponentOutOfRange)
    );
    assert!(PhongLobe::<F>::new(255).is_ok());
}

#[test]
fn shaping_within_tolerance() {
    let mut rng = Rng::new(0x5a9e);
    let mut se = Track::new("superellipse_shape Fixed22 vs f64");
    let mut df = Track::new("distance_falloff Fixed22 vs f64");
    for _ in 0..20_000 {
        let a = rng.range(0.05, 2.0);
        let b = rng.range(0.05, 2.0);
        let (aa, bb) = (a + rng.range(0.01, 1.0), b + rng.range(0.01, 1.0));
        let d = rng.range(0.05, 1.0);
        let s = [a, b, aa, bb, d].map(rd::<F>);
        let pos = rdv::<F>([
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
            rng.range(0.01, 5.0),
        ]);
        fn sh<T: Real>(s: [f64; 5], pos: V3) -> Option<f64> {
            let s = s.map(T::from_f64);
            let e = Superellipse::<T>::new(s[0], s[1], s[2], s[3], s[4]).ok()?;
            Some(e.shape(v(pos)).to_f64())
        }
        se.add(sh::<F>(s, pos), sh::<f64>(s, pos), || {
            format!("shape={s:?} pos={pos:?}")
        });
        let mm = rng.range(1.01, 10.0);
        let d0 = rng.range(0.05, 2.0);
        let alpha = rng.range(0.0, 4.0);
        let znear = rng.range(0.0, 3.0);
        let zfar = znear + rng.range(0.1, 5.0);
        let (ne, fe) = (rng.range(0.05, 1.0), rng.range(0.05, 2.0));
        let z = rng.range(0.0, 12.0);
        let f = [mm, d0, alpha, znear, zfar, ne, fe, z].map(rd::<F>);
        fn fo<T: Real>(f: [f64; 8]) -> Option<f64> {
            let g = f.map(T::from_f64);
            let l = DistanceFalloff::<T>::new(g[0], g[1], g[2], g[3], g[4], g[5], g[6]).ok()?;
            Some(l.falloff(g[7]).to_f64())
        }
        df.add(fo::<F>(f), fo::<f64>(f), || format!("falloff={f:?}"));
    }
    se.finish();
    df.finish();
}
