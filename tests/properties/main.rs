//! Property tests (proptest) of every model, written once as a macro and instantiated per
//! backend (`f64`, `f32`, `Fast32`, `Fixed22`).
//!
//! Polygons are made planar on purpose (`planar_poly`): convex (3 to 8 vertices, the capacity),
//! star-shaped and non-convex, regular stars, L and U shapes, and near-degenerate ones (a
//! sliver, a vanishing edge, a nearly collinear extra vertex), either winding, in a random
//! plane, scaled into the backend's coordinate range (a check asserts that every backend's
//! constructor accepts them, so no property is skipped silently).
//!
//! - range: normalized models in [0, 1] (`hemi_cos` in [0, 2/3], `sky_overcast` in [0, C],
//!   `sky_ground` between the two colours per channel, moments and shaping in their ranges),
//!   for any finite input, including degenerate and badly scaled ones;
//! - winding invariance of every polygon model;
//! - invariance under a rotation and a translation of the whole configuration;
//! - additivity: a quad split into two triangles and an L-shape split into its two rectangles
//!   give the sum of the parts (Lambert, Phong, clipped solid angle);
//! - Phong with m = 1 and r = n equals the Lambert model (hemisphere, cap, sphere, polygon);
//! - the cap at sigma = pi/2 equals the constant hemisphere (Lambert and Phong);
//! - monotone in sigma, in a sphere's radius and in a polygon grown about a point from which
//!   it is star-shaped;
//! - continuity across every case boundary (`continuous`: the step across the boundary against
//!   the other steps of a scan around it, plus a floor far below each backend's bound): the cap
//!   at w = pi/2 - sigma, pi/2, pi/2 + sigma (Lambert) and w = sigma (Phong), a polygon vertex
//!   crossing the horizon, and m changing parity (the moments `mu_m = 2 pi I_m/(m + 1)` are
//!   log-convex in m: `mu_m^2 <= mu_(m-1) mu_(m+1)`, which ties the even path, with its solid
//!   angle, to the odd one).
//!
//! Tolerances: f64 1e-12 (plus 1e-15 m); f32 its main-regime bound `2e-6 + m 2^-24`, Fast32
//! and Fixed22 `1/1024` (tests/common): the generated configurations keep to the
//! well-conditioned regime (spheres at d/R >= 1.05, shading points at least 0.3 sizes from a
//! polygon) except in the range properties, which assert exact bounds. For the low-precision
//! backends the invariance properties also allow the f64 model's own change between the two
//! rounded configurations. The case count per property is `AREALIGHT_PROP_CASES` (default
//! 1024: the whole file then runs in about 0.6 s; 48 took 0.03 s, 256 0.11 s, 4096 2.2 s).

#[path = "../common/mod.rs"]
mod common;
mod configs;

use arealight::{
    lune_normalization, CapLight, DistanceFalloff, Fast32, HemisphereLight, OvercastSky, PhongLobe,
    PolygonLight, Real, SkyGround, SphereLight, Superellipse, Vec3,
};
use common::Rng;
use common::*;
use configs::*;
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

fn cases() -> u32 {
    std::env::var("AREALIGHT_PROP_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1024)
}

/// The exponents the properties draw from (large m: tests/large_exponents.rs).
const PROP_MS: [u32; 10] = [0, 1, 2, 3, 7, 8, 31, 32, 63, 64];

macro_rules! properties {
    (
        $modname:ident,
        $T:ty,
        tol = $tol:expr,
        per_m = $per_m:expr,
        step = $step:expr,
        floor = $floor:expr
    ) => {
        mod $modname {
            use super::*;
            type T = $T;
            /// The backend's main-regime bound for exponent m.
            fn tol(m: u32) -> f64 {
                $tol + m as f64 * $per_m
            }
            /// The continuity step at m = 0 (divided by m + 1: the models' slope grows with m).
            const STEP: f64 = $step;
            /// The smallest jump the continuity check detects (see [`continuous`]).
            const FLOOR: f64 = $floor;
            /// Scale applied to every position so the configuration fits the backend's
            /// coordinate range (1 for the float types; 1/4 for `Fixed22`, whose positions
            /// are limited to [-4, 4]; the models are scale invariant).
            fn k() -> f64 {
                T::COORDINATE_LIMIT.min(16.0) / 16.0
            }
            /// The scale of the polygon configurations (within 7.5 of the origin): 1/2 for
            /// `Fixed22`, as large as its range allows.
            fn pk() -> f64 {
                T::COORDINATE_LIMIT.min(8.0) / 8.0
            }
            /// A direction's length scale clamped into what the backend represents (directions
            /// of any length are valid; `Fixed22` holds lengths in [2^-8, 2^8] exactly enough).
            fn dir_scale(s: f64) -> f64 {
                if T::COORDINATE_LIMIT < f64::MAX {
                    s.clamp(1.0 / 256.0, 256.0)
                } else {
                    s
                }
            }
            /// A length scale `s` clamped into what the backend can represent as a position.
            fn pos_scale(s: f64) -> f64 {
                if T::COORDINATE_LIMIT < f64::MAX {
                    s.clamp(1.0 / 64.0, T::COORDINATE_LIMIT / 25.0)
                } else {
                    s
                }
            }
            fn is_f64() -> bool {
                T::EPSILON.to_f64() < 1e-10
            }
            /// Extra allowance for an invariance property of a low-precision backend: the f64
            /// model's own change between the two configurations as `T` rounds them.
            fn f64_change(a: f64, b: f64) -> f64 {
                if is_f64() {
                    0.0
                } else {
                    diff(a, b)
                }
            }
            fn cfg() -> ProptestConfig {
                ProptestConfig {
                    cases: cases(),
                    failure_persistence: None,
                    ..ProptestConfig::default()
                }
            }

            /// The planar polygons of the properties reach the models on this backend (none
            /// silently skipped for want of range or planarity): every shape is accepted by the
            /// constructor in at least 95 % of 2000 draws. On `Fixed22` this includes the polygons
            /// below 0.6 across, once counted apart: its rounding of the coordinates (2^-23)
            /// moved their vertices off the plane by more than the planarity tolerance, which
            /// now allows for `Real::RESOLUTION`.
            #[test]
            fn planar_polygons_are_accepted() {
                let mut rng = Rng::new(0x91a7);
                let mut by: std::collections::BTreeMap<&str, (usize, usize)> = Default::default();
                for _ in 0..2000 {
                    let c = planar_poly(&mut rng, pk());
                    let ok = poly::<T>(&c.verts).is_some() as usize;
                    let e = by.entry(c.kind).or_default();
                    e.0 += 1;
                    e.1 += ok;
                }
                println!("[props] {}: accepted/drawn by shape {:?}", stringify!($T), by);
                for (kind, (n, ok)) in by {
                    assert!(ok * 100 >= n * 95, "{kind}: {ok} of {n} accepted");
                }
            }

            proptest! {
                #![proptest_config(cfg())]

                /// Every normalized model stays in its range for any finite input.
                #[test]
                fn range(seed in any::<u64>(), ex in -6i32..6, m in 0u32..80) {
                    let mut rng = Rng::new(seed);
                    let s = 10f64.powi(ex);
                    let (axis, n) = (scale(rng.dir(), dir_scale(s)), scale(rng.dir(), dir_scale(1.0 / s)));
                    let sigma = rng.range(0.0, FRAC_PI_2);
                    let l = lobe::<T>(m);
                    let h = hemi::<T>(axis);
                    let c = cap::<T>(axis, sigma);
                    let in01 = |x: T| x.to_f64() >= 0.0 && x.to_f64() <= 1.0;
                    prop_assert!(in01(h.lambert_const(v(n))));
                    let hc = h.lambert_cos(v(n)).to_f64();
                    prop_assert!((0.0..=2.0 / 3.0 + 1e-7).contains(&hc), "hemi_cos {}", hc);
                    prop_assert!(in01(h.phong_const(&l, v(n))));
                    prop_assert!(in01(h.phong_cos(&l, v(n))));
                    prop_assert!(in01(c.lambert(v(n))));
                    prop_assert!(in01(c.lambert_hermite(v(n))));
                    prop_assert!(in01(c.phong(&l, v(n))));
                    let lum = rng.range(0.0, 1e3);
                    let sky = OvercastSky::<T>::new(v(axis), T::from_f64(lum)).unwrap();
                    let e = sky.lambert(v(n)).to_f64();
                    prop_assert!(e >= 0.0 && e <= T::from_f64(lum).to_f64() * (1.0 + 1e-6));
                    let (c1, c2) = ([rng.range(0.0, 5.0), 0.3, 1.0], [0.2, rng.range(0.0, 9.0), 0.0]);
                    let sg = SkyGround::<T>::new(v(axis), rgb(c1), rgb(c2)).unwrap();
                    let e = sg.irradiance(v(n)).to_f64();
                    for i in 0..3 {
                        let (lo, hi) = (c1[i].min(c2[i]), c1[i].max(c2[i]));
                        prop_assert!(e[i] >= lo * (1.0 - 1e-6) && e[i] <= hi * (1.0 + 1e-6), "sky_ground {:?}", e);
                    }
                    // A sphere at any distance and scale, p anywhere outside.
                    let sp = pos_scale(s);
                    let radius = rng.range(1e-3, 2.0) * sp;
                    let p = scale(rng.dir(), radius * (1.0 + 10f64.powi(rng.below(8) as i32 - 6)));
                    let sph = SphereLight::<T>::new(v([0.0; 3]), T::from_f64(radius)).unwrap();
                    prop_assert!(in01(sph.lambert(v(p), v(n))));
                    prop_assert!(in01(sph.lambert_hermite(v(p), v(n))));
                    prop_assert!(in01(sph.phong(&l, v(p), v(n))));
                    // A polygon (possibly seen edge-on or from very close).
                    let pc = planar_poly(&mut rng, sp / 4.0);
                    let pp = scale(pc.verts[0], rng.range(0.0, 1.2));
                    if let Some(pl) = poly::<T>(&pc.verts) {
                        prop_assert!(in01(pl.lambert(v(pp), v(n))));
                        prop_assert!(in01(pl.phong(&l, v(pp), v(n))));
                        let om = pl.clipped_solid_angle(v(pp), v(n)).to_f64();
                        prop_assert!((0.0..=TAU + 1e-5).contains(&om));
                        let d = pl.directional_luminaire(v(pp), v(n), v(axis), m).to_f64();
                        prop_assert!((0.0..=PI * (1.0 + 1e-5)).contains(&d), "luminaire {}", d);
                        let g = pl.glossy_reflection(v(pp), v(n), v(axis), m).to_f64();
                        prop_assert!(g >= 0.0 && g.is_finite(), "glossy {}", g);
                    }
                    let lu = lune_normalization(v::<T>(axis), v(n), m).to_f64();
                    prop_assert!((0.0..=PI * (1.0 + 1e-6)).contains(&lu), "lune {}", lu);
                    let se = Superellipse::<T>::new(
                        T::from_f64(0.3), T::from_f64(0.2), T::from_f64(0.5), T::from_f64(0.4),
                        T::from_f64(rng.range(0.05, 3.0)),
                    ).unwrap();
                    prop_assert!(in01(se.shape(v(n))));
                    let fo = DistanceFalloff::<T>::new(
                        T::from_f64(2.0), T::ONE, T::from_f64(1.5), T::from_f64(0.5),
                        T::from_f64(20.0), T::from_f64(0.2), T::from_f64(3.0),
                    ).unwrap();
                    let z = fo.falloff(T::from_f64(s * rng.unit())).to_f64();
                    prop_assert!((0.0..=2.0).contains(&z), "falloff {}", z);
                }

                /// Polygon models do not depend on the winding.
                #[test]
                fn winding(seed in any::<u64>(), mi in 0usize..10) {
                    let m = PROP_MS[mi];
                    let mut rng = Rng::new(seed);
                    let c = planar_poly(&mut rng, pk());
                    let rev: Vec<V3> = c.verts.iter().rev().copied().collect();
                    let (Some(a), Some(b)) = (poly::<T>(&c.verts), poly::<T>(&rev)) else {
                        return Ok(());
                    };
                    let (p, k, l) = (v(c.p), v(c.k), lobe::<T>(m));
                    let t = tol(m);
                    prop_assert!(diff(a.lambert(p, k).to_f64(), b.lambert(p, k).to_f64()) <= t);
                    prop_assert!(diff(a.phong(&l, p, k).to_f64(), b.phong(&l, p, k).to_f64()) <= t);
                    let (sa, sb) = (a.clipped_solid_angle(p, k).to_f64(), b.clipped_solid_angle(p, k).to_f64());
                    prop_assert!(diff(sa, sb) <= TAU * t);
                    let (ma, mb) = (a.axial_moment(p, k, m).to_f64(), b.axial_moment(p, k, m).to_f64());
                    prop_assert!(diff(ma, mb) <= TAU * t, "axial {} {}", ma, mb);
                }

                /// Rotating and translating the whole configuration changes nothing.
                #[test]
                fn rigid_motion(seed in any::<u64>(), mi in 0usize..10) {
                    let m = PROP_MS[mi];
                    let mut rng = Rng::new(seed);
                    let (r, t) = rigid(&mut rng);
                    let t = scale(t, k());
                    let t_ = tol(m);
                    // Hemisphere and cap: directions only.
                    let (axis, n, sigma) = (rng.dir(), rng.dir(), rng.range(0.0, FRAC_PI_2));
                    let (ra, rn) = (rot(&r, axis), rot(&r, n));
                    let l = lobe::<T>(m);
                    let lf = lobe::<f64>(m);
                    let pairs = [
                        (hemi::<T>(axis).phong_const(&l, v(n)).to_f64(),
                         hemi::<T>(ra).phong_const(&l, v(rn)).to_f64(),
                         hemi::<f64>(rdv::<T>(axis)).phong_const(&lf, v(rdv::<T>(n))),
                         hemi::<f64>(rdv::<T>(ra)).phong_const(&lf, v(rdv::<T>(rn)))),
                        (cap::<T>(axis, sigma).lambert(v(n)).to_f64(),
                         cap::<T>(ra, sigma).lambert(v(rn)).to_f64(),
                         cap::<f64>(rdv::<T>(axis), rd_max::<T>(sigma, FRAC_PI_2)).lambert(v(rdv::<T>(n))),
                         cap::<f64>(rdv::<T>(ra), rd_max::<T>(sigma, FRAC_PI_2)).lambert(v(rdv::<T>(rn)))),
                        (cap::<T>(axis, sigma).phong(&l, v(n)).to_f64(),
                         cap::<T>(ra, sigma).phong(&l, v(rn)).to_f64(),
                         cap::<f64>(rdv::<T>(axis), rd_max::<T>(sigma, FRAC_PI_2)).phong(&lf, v(rdv::<T>(n))),
                         cap::<f64>(rdv::<T>(ra), rd_max::<T>(sigma, FRAC_PI_2)).phong(&lf, v(rdv::<T>(rn)))),
                    ];
                    for (i, (a, b, fa, fb)) in pairs.iter().enumerate() {
                        prop_assert!(diff(*a, *b) <= 2.0 * t_ + f64_change(*fa, *fb), "model {} {} {}", i, a, b);
                    }
                    // Sphere: centre, p moved, r rotated.
                    let (center, radius) = (scale(rng.sdir(), k()), k() * rng.range(0.1, 1.0));
                    let p = add(center, scale(rng.dir(), radius * rng.range(1.05, 8.0)));
                    let s1 = SphereLight::<T>::new(v(center), T::from_f64(radius)).unwrap();
                    let s2 = SphereLight::<T>::new(v(mv(&r, t, center)), T::from_f64(radius)).unwrap();
                    let f1 = SphereLight::<f64>::new(v(rdv::<T>(center)), rd::<T>(radius)).unwrap();
                    let f2 = SphereLight::<f64>::new(v(rdv::<T>(mv(&r, t, center))), rd::<T>(radius)).unwrap();
                    let (p2, n2) = (mv(&r, t, p), rot(&r, n));
                    for (a, b, fa, fb) in [
                        (s1.lambert(v(p), v(n)).to_f64(), s2.lambert(v(p2), v(n2)).to_f64(),
                         f1.lambert(v(rdv::<T>(p)), v(rdv::<T>(n))), f2.lambert(v(rdv::<T>(p2)), v(rdv::<T>(n2)))),
                        (s1.phong(&l, v(p), v(n)).to_f64(), s2.phong(&l, v(p2), v(n2)).to_f64(),
                         f1.phong(&lf, v(rdv::<T>(p)), v(rdv::<T>(n))), f2.phong(&lf, v(rdv::<T>(p2)), v(rdv::<T>(n2)))),
                    ] {
                        prop_assert!(diff(a, b) <= 2.0 * t_ + f64_change(fa, fb), "sphere {} {}", a, b);
                    }
                    // Polygon.
                    let c = planar_poly(&mut rng, pk());
                    let moved: Vec<V3> = c.verts.iter().map(|&x| mv(&r, t, x)).collect();
                    let (p2, k2) = (mv(&r, t, c.p), rot(&r, c.k));
                    let rnd = |vs: &[V3]| vs.iter().map(|&x| rdv::<T>(x)).collect::<Vec<_>>();
                    if let (Some(a), Some(b), Some(fa), Some(fb)) = (
                        poly::<T>(&c.verts), poly::<T>(&moved),
                        poly::<f64>(&rnd(&c.verts)), poly::<f64>(&rnd(&moved)),
                    ) {
                        let (pp, kk, pp2, kk2) = (rdv::<T>(c.p), rdv::<T>(c.k), rdv::<T>(p2), rdv::<T>(k2));
                        let x = (a.lambert(v(c.p), v(c.k)).to_f64(), b.lambert(v(p2), v(k2)).to_f64());
                        let y = (fa.lambert(v(pp), v(kk)), fb.lambert(v(pp2), v(kk2)));
                        prop_assert!(diff(x.0, x.1) <= 2.0 * t_ + f64_change(y.0, y.1), "polygon_lambert {:?}", x);
                        let x = (a.phong(&l, v(c.p), v(c.k)).to_f64(), b.phong(&l, v(p2), v(k2)).to_f64());
                        let y = (fa.phong(&lf, v(pp), v(kk)), fb.phong(&lf, v(pp2), v(kk2)));
                        prop_assert!(diff(x.0, x.1) <= 2.0 * t_ + f64_change(y.0, y.1), "phong_polygon {:?}", x);
                    }
                }

                /// A quad split along a diagonal, and an L-shape split into its two rectangles:
                /// the parts add up (Lambert, Phong, solid angle).
                #[test]
                fn split_polygon(seed in any::<u64>(), mi in 0usize..10) {
                    let m = PROP_MS[mi];
                    let mut rng = Rng::new(seed);
                    let kscale = pk();
                    let mut c = planar_poly(&mut rng, kscale);
                    c.verts.truncate(3);
                    // A fourth vertex making a convex quad: reflect v1 across the v0-v2 midpoint.
                    let mid = scale(add(c.verts[0], c.verts[2]), 0.5);
                    let v3 = add(mid, scale(sub(mid, c.verts[1]), rng.range(0.3, 1.0)));
                    let quad = vec![c.verts[0], c.verts[1], c.verts[2], v3];
                    let t1 = vec![c.verts[0], c.verts[1], c.verts[2]];
                    let t2 = vec![c.verts[0], c.verts[2], v3];
                    let (Some(q), Some(a), Some(b)) = (poly::<T>(&quad), poly::<T>(&t1), poly::<T>(&t2)) else {
                        return Ok(());
                    };
                    let (p, k, l) = (v(c.p), v(c.k), lobe::<T>(m));
                    let t = tol(m);
                    let sum = a.lambert(p, k).to_f64() + b.lambert(p, k).to_f64();
                    prop_assert!(diff(q.lambert(p, k).to_f64(), sum) <= 3.0 * t);
                    let sum = a.phong(&l, p, k).to_f64() + b.phong(&l, p, k).to_f64();
                    prop_assert!(diff(q.phong(&l, p, k).to_f64(), sum) <= 3.0 * t, "phong {} vs {}", q.phong(&l, p, k).to_f64(), sum);
                    let sum = a.clipped_solid_angle(p, k).to_f64() + b.clipped_solid_angle(p, k).to_f64();
                    prop_assert!(diff(q.clipped_solid_angle(p, k).to_f64(), sum) <= 3.0 * TAU * t);
                    // The L-shape (one reflex corner) and its two rectangles, in one placement.
                    let pts: Vec<[f64; 2]> = l_shape()
                        .into_iter()
                        .chain([[-0.5, -0.1], [-0.1, -0.1]])
                        .collect();
                    let size = rng.range(0.2, 1.5);
                    let lcen = scale(rng.dir(), size * rng.range(1.3, 4.0));
                    let placed: Vec<V3> = place(&mut rng, &pts, lcen, size)
                        .into_iter()
                        .map(|x| scale(x, kscale))
                        .collect();
                    let (lv, [e0, e1]) = (&placed[..6], [placed[6], placed[7]]);
                    // l_shape(): 0 (-0.5, -0.5), 1 (0.7, -0.5), 2 (0.7, -0.1), 3 (-0.1, -0.1),
                    // 4 (-0.1, 0.6), 5 (-0.5, 0.6); e0 (-0.5, -0.1), e1 = vertex 3.
                    let _ = e1;
                    let ra = vec![lv[0], lv[1], lv[2], e0];
                    let rb = vec![e0, lv[3], lv[4], lv[5]];
                    let (Some(ql), Some(a), Some(b)) = (poly::<T>(lv), poly::<T>(&ra), poly::<T>(&rb)) else {
                        return Ok(());
                    };
                    let kk = v(rng.dir());
                    let sum = a.lambert(p, kk).to_f64() + b.lambert(p, kk).to_f64();
                    prop_assert!(diff(ql.lambert(p, kk).to_f64(), sum) <= 3.0 * t, "L lambert");
                    let sum = a.phong(&l, p, kk).to_f64() + b.phong(&l, p, kk).to_f64();
                    prop_assert!(diff(ql.phong(&l, p, kk).to_f64(), sum) <= 3.0 * t, "L phong m={}", m);
                    let sum = a.clipped_solid_angle(p, kk).to_f64() + b.clipped_solid_angle(p, kk).to_f64();
                    prop_assert!(diff(ql.clipped_solid_angle(p, kk).to_f64(), sum) <= 3.0 * TAU * t, "L solid angle");
                }

                /// Phong with m = 1 and r = n is the Lambert model of the same source; the cap at
                /// sigma = pi/2 is the constant hemisphere.
                #[test]
                fn phong_one_is_lambert_and_half_cap_is_hemisphere(seed in any::<u64>(), mi in 0usize..10) {
                    let m = PROP_MS[mi];
                    let mut rng = Rng::new(seed);
                    let (axis, n, sigma) = (rng.sdir(), rng.sdir(), rng.range(0.0, FRAC_PI_2));
                    let one = lobe::<T>(1);
                    let t = tol(1);
                    let h = hemi::<T>(axis);
                    prop_assert!(diff(h.phong_const(&one, v(n)).to_f64(), h.lambert_const(v(n)).to_f64()) <= 2.0 * t);
                    prop_assert!(diff(h.phong_cos(&one, v(n)).to_f64(), h.lambert_cos(v(n)).to_f64()) <= 2.0 * t);
                    let c = cap::<T>(axis, sigma);
                    prop_assert!(diff(c.phong(&one, v(n)).to_f64(), c.lambert(v(n)).to_f64()) <= 2.0 * t);
                    let (center, radius) = (scale(rng.sdir(), k()), k() * rng.range(0.1, 1.0));
                    let p = add(center, scale(rng.dir(), radius * rng.range(1.05, 8.0)));
                    let s = SphereLight::<T>::new(v(center), T::from_f64(radius)).unwrap();
                    prop_assert!(diff(s.phong(&one, v(p), v(n)).to_f64(), s.lambert(v(p), v(n)).to_f64()) <= 2.0 * t);
                    let pc = planar_poly(&mut rng, pk());
                    if let Some(pl) = poly::<T>(&pc.verts) {
                        let (pp, k) = (v(pc.p), v(pc.k));
                        prop_assert!(diff(pl.phong(&one, pp, k).to_f64(), pl.lambert(pp, k).to_f64()) <= 2.0 * t);
                    }
                    let half = CapLight::<T>::new(v(axis), T::FRAC_PI_2).unwrap();
                    prop_assert!(diff(half.lambert(v(n)).to_f64(), h.lambert_const(v(n)).to_f64()) <= 2.0 * t);
                    let l = lobe::<T>(m);
                    prop_assert!(diff(half.phong(&l, v(n)).to_f64(), h.phong_const(&l, v(n)).to_f64()) <= 2.0 * tol(m));
                }

                /// Monotone in sigma, in a sphere's radius and in a polygon grown about a point
                /// from which it is star-shaped (the source only gains directions; the weights
                /// are >= 0).
                #[test]
                fn monotone_in_source_size(seed in any::<u64>(), mi in 0usize..10) {
                    let m = PROP_MS[mi];
                    let mut rng = Rng::new(seed);
                    let t = tol(m);
                    let l = lobe::<T>(m);
                    let (axis, n) = (rng.dir(), rng.dir());
                    let (s1, s2) = {
                        let (a, b) = (rng.range(0.0, FRAC_PI_2), rng.range(0.0, FRAC_PI_2));
                        (a.min(b), a.max(b))
                    };
                    let (c1, c2) = (cap::<T>(axis, s1), cap::<T>(axis, s2));
                    prop_assert!(c1.lambert(v(n)).to_f64() <= c2.lambert(v(n)).to_f64() + t);
                    prop_assert!(c1.phong(&l, v(n)).to_f64() <= c2.phong(&l, v(n)).to_f64() + t);
                    let center = scale(rng.dir(), 3.0 * k());
                    let (r1, r2) = (k() * rng.range(0.1, 1.4), k() * rng.range(1.4, 2.8));
                    let p = [0.0; 3];
                    let a = SphereLight::<T>::new(v(center), T::from_f64(r1)).unwrap();
                    let b = SphereLight::<T>::new(v(center), T::from_f64(r2)).unwrap();
                    prop_assert!(a.lambert(v(p), v(n)).to_f64() <= b.lambert(v(p), v(n)).to_f64() + t);
                    prop_assert!(a.phong(&l, v(p), v(n)).to_f64() <= b.phong(&l, v(p), v(n)).to_f64() + t);
                    let c = planar_poly(&mut rng, pk());
                    let Some(cen) = c.kernel else {
                        return Ok(());
                    };
                    let f = rng.range(1.0, 1.3);
                    let big: Vec<V3> = c.verts.iter().map(|&x| add(cen, scale(sub(x, cen), f))).collect();
                    if let (Some(a), Some(b)) = (poly::<T>(&c.verts), poly::<T>(&big)) {
                        let (pp, k) = (v(c.p), v(c.k));
                        let (x, y) = (a.lambert(pp, k).to_f64(), b.lambert(pp, k).to_f64());
                        prop_assert!(x <= y + t, "{} lambert {} > {}: {:?}", c.kind, x, y, c);
                        let (x, y) = (a.phong(&l, pp, k).to_f64(), b.phong(&l, pp, k).to_f64());
                        prop_assert!(x <= y + t, "{} phong m={} {} > {}: {:?}", c.kind, m, x, y, c);
                    }
                }

                /// Continuity across the case boundaries of the cap formulas (w = pi/2 - sigma,
                /// pi/2, pi/2 + sigma for Lambert; also w = sigma for Phong) and where a
                /// polygon's vertex crosses the horizon.
                #[test]
                fn continuity_across_case_boundaries(seed in any::<u64>(), mi in 0usize..10) {
                    let m = PROP_MS[mi];
                    let mut rng = Rng::new(seed);
                    let l = lobe::<T>(m);
                    let (step, floor) = (STEP / (m as f64 + 1.0), FLOOR);
                    let sigma = rng.range(0.05, FRAC_PI_2 - 0.05);
                    let axis = rng.dir();
                    let perp = frame(axis).0;
                    let c = cap::<T>(axis, sigma);
                    let lam = |w: f64| c.lambert(v(rotate_toward(axis, perp, w))).to_f64();
                    let pho = |w: f64| c.phong(&l, v(rotate_toward(axis, perp, w))).to_f64();
                    let herm = |w: f64| c.lambert_hermite(v(rotate_toward(axis, perp, w))).to_f64();
                    for b in [FRAC_PI_2 - sigma, FRAC_PI_2, FRAC_PI_2 + sigma] {
                        continuous(&lam, b, step, floor).map_err(|e| TestCaseError::fail(format!("cap_lambert: {e}")))?;
                        continuous(&herm, b, step, floor).map_err(|e| TestCaseError::fail(format!("cap_lambert_hermite: {e}")))?;
                        continuous(&pho, b, step, floor).map_err(|e| TestCaseError::fail(format!("phong_cap m={m}: {e}")))?;
                    }
                    continuous(&pho, sigma, step, floor).map_err(|e| TestCaseError::fail(format!("phong_cap m={m} at w=sigma: {e}")))?;
                    // Hemisphere lights at w = pi/2.
                    let h = hemi::<T>(axis);
                    let hc = |w: f64| h.lambert_cos(v(rotate_toward(axis, perp, w))).to_f64();
                    let hp = |w: f64| h.phong_const(&l, v(rotate_toward(axis, perp, w))).to_f64();
                    let hpc = |w: f64| h.phong_cos(&l, v(rotate_toward(axis, perp, w))).to_f64();
                    for (name, f) in [("hemi_cos", &hc as &dyn Fn(f64) -> f64), ("phong_hemi_const", &hp), ("phong_hemi_cos", &hpc)] {
                        continuous(f, FRAC_PI_2, step, floor).map_err(|e| TestCaseError::fail(format!("{name} m={m}: {e}")))?;
                    }
                    // A polygon vertex crossing the horizon: k rotated about an axis
                    // perpendicular to (v0 - p) so that v0 sits on the horizon at angle 0.
                    let pc = planar_poly(&mut rng, pk());
                    if let Some(pl) = poly::<T>(&pc.verts) {
                        let u0 = normalize(sub(pc.verts[0], pc.p));
                        let k0 = normalize(cross(u0, rng.dir()));
                        // Tilt k toward u0 by the angle a: u0.k = sin a.
                        let kk = |a: f64| v(rotate_toward(k0, u0, a));
                        let pl_l = |a: f64| pl.lambert(v(pc.p), kk(a)).to_f64();
                        let pl_p = |a: f64| pl.phong(&l, v(pc.p), kk(a)).to_f64();
                        continuous(&pl_l, 0.0, step, floor).map_err(|e| TestCaseError::fail(format!("polygon_lambert: {e}")))?;
                        continuous(&pl_p, 0.0, step, floor).map_err(|e| TestCaseError::fail(format!("phong_polygon m={m}: {e}")))?;
                    }
                }

                /// m changing parity: `mu_m = 2 pi I_m/(m + 1)` is log-convex in m (Cauchy-Schwarz),
                /// so the even exponent's value (solid-angle path) lies within the bound set by
                /// its odd neighbours, and conversely.
                #[test]
                fn parity_log_convex(seed in any::<u64>(), m in 1u32..66) {
                    let mut rng = Rng::new(seed);
                    let axis = rng.dir();
                    let w = rng.range(0.0, 2.0);
                    let r = rng.dir_at(axis, w);
                    let sigma = rng.range(0.05, FRAC_PI_2);
                    let c = cap::<T>(axis, sigma);
                    let h = hemi::<T>(axis);
                    let pc = planar_poly(&mut rng, pk());
                    let pl = poly::<T>(&pc.verts);
                    let kdir = normalize(add(normalize(pc.verts[0]), scale(pc.k, 0.3)));
                    let models: Vec<(&str, Box<dyn Fn(u32) -> f64>)> = vec![
                        ("phong_cap", Box::new(|m| c.phong(&lobe::<T>(m), v(r)).to_f64())),
                        ("phong_hemi_const", Box::new(|m| h.phong_const(&lobe::<T>(m), v(r)).to_f64())),
                        ("phong_hemi_cos", Box::new(|m| h.phong_cos(&lobe::<T>(m), v(r)).to_f64())),
                        ("phong_polygon", Box::new(|m| pl.as_ref().map_or(0.0, |pl| pl.phong(&lobe::<T>(m), v(pc.p), v(kdir)).to_f64()))),
                    ];
                    for (name, f) in &models {
                        let mu = |k: u32| TAU * f(k) / (k as f64 + 1.0);
                        let (a, b, cc) = (mu(m - 1), mu(m), mu(m + 1));
                        let slack = (2.0 * b + a + cc) * TAU * tol(m + 1) / m as f64;
                        prop_assert!(b * b <= a * cc + slack, "{} m={}: mu {:e} {:e} {:e}", name, m, a, b, cc);
                    }
                }
            }
        }
    };
}

properties!(
    f64_props,
    f64,
    tol = 1e-12,
    per_m = 1e-15,
    step = 1e-6,
    floor = 1e-14
);
properties!(
    f32_props,
    f32,
    tol = TOL_F32,
    per_m = EPS_F32,
    step = 1e-4,
    floor = 1e-6
);
properties!(
    fast32_props,
    Fast32,
    tol = TOL_FAST32,
    per_m = 0.0,
    step = 1e-4,
    floor = 1e-4
);
properties!(
    fixed_props,
    arealight::Fixed22,
    tol = 1.0 / 1024.0,
    per_m = 0.0,
    step = 1e-4,
    floor = 2e-4
);
