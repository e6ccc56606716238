//! World coordinates (`arealight::world`): random scenes with positions up to 1000 units (and
//! translated up to 10^6 units away) answered on every backend, fixed point within 1/1024 of
//! the f64 model at the same points, with no refusals; exact invariance under translation and
//! power-of-two scaling; finite answers for any input bits.
//!
//! The reference is the plain f64 model (itself checked against the independent quadrature
//! in `tests/quadrature.rs`) on the light's points minus `p`, differences taken exactly from
//! the world points' bits, so the two sides differ by the world path's power-of-two scaling
//! and its rounding to the backend (f64: by nothing; its answers are the same bits).
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod common;

use arealight::{
    Error, Fast32, Fixed22, PhongLobe, PolygonLight, Real, SphereLight, Vec3, WorldPoint,
    WorldPolygonLight, WorldSphereLight,
};
use common::*;

const TOL_FIXED: f64 = 1.0 / 1024.0;
const CASES: usize = 4000;

/// A world point and its coordinates as the reference sees them.
fn wp(a: V3) -> (WorldPoint, V3) {
    let p = WorldPoint::from_f64(a, "p").expect("in range");
    (p, p.to_f64())
}

/// A point uniform in the cube of half-side `h` around `c`.
fn in_cube(rng: &mut Rng, c: V3, h: f64) -> V3 {
    [
        c[0] + rng.range(-h, h),
        c[1] + rng.range(-h, h),
        c[2] + rng.range(-h, h),
    ]
}

/// `10^u` for `u` uniform in `[a, b)`.
fn log_uniform(rng: &mut Rng, a: f64, b: f64) -> f64 {
    10f64.powf(rng.range(a, b))
}

/// A random sphere case: centre within 1000 units of `origin`, radius 1e-3 to 300, a point
/// outside it (anywhere in the box, or within a few radii).
struct SphereCase {
    center: V3,
    radius: f64,
    p: V3,
    n: V3,
    m: u32,
}

fn sphere_case(rng: &mut Rng, origin: V3) -> SphereCase {
    loop {
        let center = in_cube(rng, origin, 1000.0);
        let radius = log_uniform(rng, -3.0, 2.5);
        let p = if rng.below(2) == 0 {
            in_cube(rng, origin, 1000.0)
        } else {
            let d = radius * log_uniform(rng, 0.001, 1.5);
            add(center, scale(rng.dir(), d))
        };
        // Keep points clear of the surface by more than the world grid can blur.
        if norm(sub(p, center)) > radius * (1.0 + 1e-6) {
            return SphereCase {
                center,
                radius,
                p,
                n: rng.dir(),
                m: rng.below(256) as u32,
            };
        }
    }
}

/// A random planar convex polygon (3 to 8 vertices on an ellipse), centre within 1000 units
/// of `origin`, size 1e-2 to 500, and a point off its plane.
struct PolyCase {
    verts: Vec<V3>,
    p: V3,
    n: V3,
    m: u32,
}

fn polygon_case(rng: &mut Rng, origin: V3) -> PolyCase {
    let c = in_cube(rng, origin, 1000.0);
    let size = log_uniform(rng, -2.0, 2.7);
    let verts = ellipse_polygon(rng, c, size);
    // The plane's normal (any two edges: the polygon is convex, counter-clockwise or not).
    let axis = normalize(cross(sub(verts[1], verts[0]), sub(verts[2], verts[0])));
    let p = loop {
        let p = if rng.below(2) == 0 {
            in_cube(rng, origin, 1000.0)
        } else {
            add(c, scale(rng.dir(), size * log_uniform(rng, -1.0, 0.7)))
        };
        // Off the plane by more than a millionth of the size (the fixed kernels answer
        // "unresolved" within their rounding of it, over the face).
        if dot(sub(p, c), axis).abs() > 1e-6 * size.max(norm(sub(p, c))) {
            break p;
        }
    };
    PolyCase {
        verts,
        p,
        n: rng.dir(),
        m: rng.below(256) as u32,
    }
}

/// The five positional models at one case, world path in `T`.
fn sphere_world<T: Real>(s: &SphereCase) -> Result<[f64; 3], Error> {
    let (c, p) = (wp(s.center).0, wp(s.p).0);
    let light = WorldSphereLight::<T>::new(c, s.radius)?;
    let n = Vec3::<T>::from_f64(s.n);
    let lobe = PhongLobe::new(s.m)?;
    Ok([
        light.try_lambert(p, n)?.to_f64(),
        light.try_lambert_hermite(p, n)?.to_f64(),
        light.try_phong(&lobe, p, n)?.to_f64(),
    ])
}

/// `a - p` for two world points: the raw difference (exact in `i64`), then rounded once to f64.
fn diff(a: V3, p: V3) -> V3 {
    let (a, p) = (wp(a).0.to_bits(), wp(p).0.to_bits());
    [0, 1, 2].map(|i| (a[i] - p[i]) as f64 / 4294967296.0)
}

/// The plain f64 model with `p` at the origin and the light's points taken relative to it
/// (exact differences, one rounding each: the best f64 can do; the plain model at the
/// absolute coordinates would round each difference near the far points' ULP).
fn sphere_reference(s: &SphereCase, n: V3) -> Result<[f64; 3], Error> {
    // The radius as the world format rounds it.
    let r = (s.radius * 4294967296.0).round() / 4294967296.0;
    let light = SphereLight::<f64>::new(v(diff(s.center, s.p)), r)?;
    let (o, lobe) = (v([0.0; 3]), PhongLobe::new(s.m)?);
    Ok([
        light.try_lambert(o, v(n))?,
        light.try_lambert_hermite(o, v(n))?,
        light.try_phong(&lobe, o, v(n))?,
    ])
}

fn polygon_world<T: Real>(c: &PolyCase) -> Result<[f64; 2], Error> {
    let verts: Vec<WorldPoint> = c.verts.iter().map(|&a| wp(a).0).collect();
    let light = WorldPolygonLight::<T, 8>::new(&verts)?;
    let (p, n) = (wp(c.p).0, Vec3::<T>::from_f64(c.n));
    let lobe = PhongLobe::new(c.m)?;
    Ok([
        light.try_lambert(p, n)?.to_f64(),
        light.try_phong(&lobe, p, n)?.to_f64(),
    ])
}

fn polygon_reference(c: &PolyCase, n: V3) -> Result<[f64; 2], Error> {
    let verts: Vec<Vec3<f64>> = c.verts.iter().map(|&a| v(diff(a, c.p))).collect();
    let light = PolygonLight::<f64, 8>::new(&verts)?;
    let (o, lobe) = (v([0.0; 3]), PhongLobe::new(c.m)?);
    Ok([
        light.try_lambert(o, v(n))?,
        light.try_phong(&lobe, o, v(n))?,
    ])
}

const SPHERE_IDS: [&str; 3] = ["sphere_lambert", "sphere_lambert_hermite", "phong_sphere"];
const POLY_IDS: [&str; 2] = ["polygon_lambert", "phong_polygon"];

/// Every case answered (no refusal) by `T`'s world path, each model within `tol` of f64 at the
/// same points and at `n` as `T` rounds it (the Phong models within `tol_phong`).
fn within_tolerance<T: Real>(backend: &str, seed: u64, origin: V3, tol: f64, tol_phong: f64) {
    let mut rng = Rng::new(seed);
    let mut errs: Vec<MaxErr> = SPHERE_IDS
        .iter()
        .chain(POLY_IDS.iter())
        .map(|id| MaxErr::new(&format!("world {id} {backend} (origin {:.0e})", origin[0])))
        .collect();
    for i in 0..CASES {
        let s = sphere_case(&mut rng, origin);
        let got = sphere_world::<T>(&s).unwrap_or_else(|e| panic!("sphere case {i}: {e:?}"));
        let want = sphere_reference(&s, rdv::<T>(s.n)).expect("reference");
        for (k, (g, w)) in got.iter().zip(want).enumerate() {
            errs[k].add(*g, w, || {
                format!(
                    "c {:?} r {:e} p {:?} n {:?} m {}",
                    s.center, s.radius, s.p, s.n, s.m
                )
            });
        }
        let c = polygon_case(&mut rng, origin);
        let got = polygon_world::<T>(&c).unwrap_or_else(|e| panic!("polygon case {i}: {e:?}"));
        let want = polygon_reference(&c, rdv::<T>(c.n)).expect("reference");
        for (k, (g, w)) in got.iter().zip(want).enumerate() {
            errs[3 + k].add(*g, w, || {
                format!("verts {:?} p {:?} n {:?} m {}", c.verts, c.p, c.n, c.m)
            });
        }
    }
    for (e, id) in errs.iter().zip(SPHERE_IDS.iter().chain(POLY_IDS.iter())) {
        e.check(if id.starts_with("phong") {
            tol_phong
        } else {
            tol
        });
    }
}

#[test]
fn fixed22_within_1_1024_up_to_1000_units() {
    within_tolerance::<Fixed22>("Fixed22", 1, [0.0; 3], TOL_FIXED, TOL_FIXED);
}

#[test]
fn fixed22_within_1_1024_a_million_units_away() {
    within_tolerance::<Fixed22>("Fixed22", 2, [1e6, -3e5, 7e5], TOL_FIXED, TOL_FIXED);
}

#[test]
fn fast32_within_1_1024_up_to_1000_units() {
    within_tolerance::<Fast32>("Fast32", 3, [0.0; 3], TOL_FAST32, TOL_FAST32);
}

/// f32's world path against f64: the crate's f32 bound, `TOL_F32` (2e-6), and for the Phong
/// models `TOL_F32 + m 2^-24` at the largest `m` drawn, 255 (the bound of `tests/common`'s
/// `f32_bound`: a Phong lobe raises a cosine's rounding to the `m`th power).
#[test]
fn f32_within_tolerance_up_to_1000_units() {
    within_tolerance::<f32>("f32", 4, [0.0; 3], TOL_F32, TOL_F32 + 255.0 * EPS_F32);
}

/// f64's world path is the plain f64 model on the exact differences, bit for bit (its
/// power-of-two scaling is exact in f64).
#[test]
fn f64_is_the_plain_model_on_the_differences() {
    within_tolerance::<f64>("f64", 5, [0.0; 3], 0.0, 0.0);
}

/// Translating a scene by a multiple of 2^-32 units, or scaling it by a power of two, leaves
/// every fixed-point answer the same, bit for bit.
#[test]
fn fixed22_exactly_invariant_under_translation_and_scaling() {
    let mut rng = Rng::new(6);
    // Points on a grid of 2^-16 units, so that scaling down by up to 2^16 stays exact.
    let grid = |a: V3| a.map(|x| (x * 65536.0).round() / 65536.0);
    let mut checked = 0;
    for _ in 0..1000 {
        let s = sphere_case(&mut rng, [0.0; 3]);
        let c = polygon_case(&mut rng, [0.0; 3]);
        let (sc, sp) = (grid(s.center), grid(s.p));
        let sr = (s.radius * 65536.0).round().max(1.0) / 65536.0;
        // A triangle: planar whatever the grid does to its vertices.
        let verts: Vec<V3> = c.verts.iter().take(3).map(|&a| grid(a)).collect();
        let pp = grid(c.p);
        let shift =
            in_cube(&mut rng, [0.0; 3], 1e5).map(|x| (x * 4294967296.0).round() / 4294967296.0);
        let k = 2f64.powi(rng.below(33) as i32 - 16);
        let n = Vec3::<Fixed22>::from_f64(s.n);
        let lobe = PhongLobe::new(s.m).unwrap();
        let sphere = |f: &dyn Fn(V3) -> V3, r: f64| -> Option<[i32; 3]> {
            let l = WorldSphereLight::<Fixed22>::new(wp(f(sc)).0, r).ok()?;
            let p = wp(f(sp)).0;
            Some([
                l.lambert(p, n).to_bits(),
                l.lambert_hermite(p, n).to_bits(),
                l.phong(&lobe, p, n).to_bits(),
            ])
        };
        let poly = |f: &dyn Fn(V3) -> V3| -> Option<[i32; 2]> {
            let vs: Vec<WorldPoint> = verts.iter().map(|&a| wp(f(a)).0).collect();
            let l = WorldPolygonLight::<Fixed22, 8>::new(&vs).ok()?;
            let p = wp(f(pp)).0;
            Some([l.lambert(p, n).to_bits(), l.phong(&lobe, p, n).to_bits()])
        };
        let id = |a: V3| a;
        let moved = |a: V3| add(a, shift);
        let scaled = |a: V3| scale(a, k);
        let (s0, p0) = (sphere(&id, sr), poly(&id));
        assert!(s0.is_some() && p0.is_some());
        assert_eq!(s0, sphere(&moved, sr), "sphere moved by {shift:?}");
        assert_eq!(s0, sphere(&scaled, sr * k), "sphere scaled by {k}");
        assert_eq!(p0, poly(&moved), "polygon moved by {shift:?}");
        assert_eq!(p0, poly(&scaled), "polygon scaled by {k}");
        checked += 1;
    }
    assert_eq!(checked, 1000);
}

/// Any bits: finite answers in [0, 1], and the documented errors.
#[test]
fn any_input_bits_give_finite_answers() {
    let mut rng = Rng::new(7);
    let limit = (1i64 << 62) - 1;
    let point = |rng: &mut Rng| {
        let pick = |rng: &mut Rng| match rng.below(4) {
            0 => (rng.next_u64() as i64) >> 1 >> rng.below(63),
            1 => [0, 1, -1, limit, -limit][rng.below(5) as usize],
            _ => ((rng.next_u64() as i64) >> 2).clamp(-limit, limit),
        };
        WorldPoint::from_bits([pick(rng), pick(rng), pick(rng)]).expect("in range")
    };
    let dirs = [
        [0.0, 0.0, 1.0],
        [f64::NAN, 0.0, 1.0],
        [0.0, 0.0, 0.0],
        [1e-30, -1e-30, 1e-30],
        [511.0, -511.0, 3.0],
    ];
    for i in 0..20_000 {
        let n = if i % 3 == 0 {
            rng.dir()
        } else {
            dirs[rng.below(5) as usize]
        };
        let lobe = PhongLobe::new(rng.below(256) as u32).unwrap();
        let r = 2f64.powi(rng.below(96) as i32 - 33);
        let check = |x: f64| assert!((0.0..=1.0).contains(&x), "{x}");
        if let Ok(s) = WorldSphereLight::<Fixed22>::new(point(&mut rng), r) {
            let p = point(&mut rng);
            let nf = Vec3::<Fixed22>::from_f64(n);
            check(s.lambert(p, nf).to_f64());
            check(s.lambert_hermite(p, nf).to_f64());
            check(s.phong(&lobe, p, nf).to_f64());
            let s = WorldSphereLight::<f32>::new(s.center(), r).unwrap();
            let n32 = Vec3::<f32>::from_f64(n);
            check(s.lambert(p, n32).into());
            check(s.phong(&lobe_f32(&lobe), p, n32).into());
        }
        let k = 3 + rng.below(3) as usize;
        let vs: Vec<WorldPoint> = (0..k).map(|_| point(&mut rng)).collect();
        if let Ok(l) = WorldPolygonLight::<Fixed22, 8>::new(&vs) {
            let p = point(&mut rng);
            let nf = Vec3::<Fixed22>::from_f64(n);
            check(l.lambert(p, nf).to_f64());
            check(l.phong(&lobe, p, nf).to_f64());
        }
    }
    assert_eq!(
        WorldSphereLight::<Fixed22>::new(WorldPoint::ORIGIN, 0.0),
        Err(Error::RadiusNotPositive)
    );
    assert_eq!(
        WorldSphereLight::<Fixed22>::new(WorldPoint::ORIGIN, 1e-10),
        Err(Error::RadiusNotPositive)
    );
    assert_eq!(
        WorldSphereLight::<Fixed22>::new(WorldPoint::ORIGIN, 2e9),
        Err(Error::OutOfRange("radius"))
    );
    assert_eq!(
        WorldSphereLight::<Fixed22>::new(WorldPoint::ORIGIN, f64::INFINITY),
        Err(Error::NotFinite("radius"))
    );
    let s = WorldSphereLight::<Fixed22>::new(WorldPoint::ORIGIN, 1.0).unwrap();
    let inside = WorldPoint::from_f64([0.5, 0.0, 0.0], "p").unwrap();
    let up = Vec3::<Fixed22>::from_f64([0.0, 0.0, 1.0]);
    assert_eq!(s.try_lambert(inside, up), Err(Error::PointInsideSphere));
    assert_eq!(s.lambert(inside, up), Fixed22::ZERO);
}

fn lobe_f32(l: &PhongLobe<Fixed22>) -> PhongLobe<f32> {
    PhongLobe::new(l.exponent()).unwrap()
}
