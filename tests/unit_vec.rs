//! Unit vectors carried by type (`UnitVec3`, `Direction`): a call with a `UnitVec3` answers
//! exactly what the same call answers with the `Vec3` it was made from (the call normalizes a
//! `Vec3` first and then runs the same code), on every backend, for every model family that
//! takes a normal or a reflection direction; zero and non-finite vectors have no unit vector;
//! and the rasterizer's mirror direction (`raster::reflect`) of two unit vectors is unit to its
//! rounding.

mod common;

use arealight::raster::reflect;
use arealight::{
    CapLight, Decay, Direction, Error, Fast32, Fixed22, HemisphereLight, Illuminant, LineLight,
    PhongLobe, PolygonLight, Real, Sh9, SkyGround, SphereLight, UnitVec3, Vec3,
};
use common::*;

/// One backend: every model's `f(v)` and `f(v.to_unit())`, bit for bit, over random
/// directions of random lengths (scaled by powers of two, so the direction is the same in
/// every backend's range).
fn same_with_unit<T: Real>(seed: u64, lengths: &[f64]) -> usize {
    let mut rng = Rng::new(seed);
    let c = |x: f64| T::from_f64(x);
    let hemi = HemisphereLight::<T>::new(v(rng.dir())).unwrap();
    let sky =
        SkyGround::<T>::new(v(rng.dir()), rgb([0.9, 0.8, 0.7]), rgb([0.2, 0.3, 0.1])).unwrap();
    let cap = CapLight::<T>::new(v(rng.dir()), c(0.4)).unwrap();
    let sphere = SphereLight::<T>::new(v([0.3, 0.2, 2.5]), c(0.6)).unwrap();
    let quad = PolygonLight::<T, 4>::new(&[
        v([-0.5, -0.4, 2.0]),
        v([0.6, -0.4, 2.1]),
        v([0.6, 0.5, 2.2]),
        v([-0.5, 0.5, 2.1]),
    ])
    .unwrap();
    let line = LineLight::<T>::new(v([-0.8, 0.3, 1.5]), v([0.9, -0.2, 1.8])).unwrap();
    let sh = Sh9::<T>::directional(v([0.2, 0.9, 0.4]), rgb([1.0, 0.9, 0.8]))
        .unwrap()
        .plus(&Sh9::disc(v([-0.5, 0.3, 0.8]), c(0.6), rgb([0.3, 0.4, 0.9])).unwrap())
        .prepare();
    let lobe = PhongLobe::<T>::new(12).unwrap();
    let p = v::<T>([0.05, -0.1, 0.0]);
    let mut compared = 0;
    for i in 0..4000 {
        let d = rng.dir();
        let len = lengths[i % lengths.len()];
        let raw = v::<T>(d.map(|x| x * len));
        let Some(u) = raw.to_unit() else {
            continue;
        };
        let b = |x: T| x.to_f64().to_bits();
        let b3 = |x: arealight::Rgb<T>| x.to_f64().map(f64::to_bits);
        assert_eq!(
            b(hemi.lambert_const(raw)),
            b(hemi.lambert_const(u)),
            "{d:?}"
        );
        assert_eq!(b(hemi.lambert_cos(raw)), b(hemi.lambert_cos(u)), "{d:?}");
        assert_eq!(b3(sky.irradiance(raw)), b3(sky.irradiance(u)), "{d:?}");
        assert_eq!(b(cap.lambert(raw)), b(cap.lambert(u)), "{d:?}");
        assert_eq!(
            b(cap.lambert_hermite(raw)),
            b(cap.lambert_hermite(u)),
            "{d:?}"
        );
        assert_eq!(b(cap.phong(&lobe, raw)), b(cap.phong(&lobe, u)), "{d:?}");
        assert_eq!(b(sphere.lambert(p, raw)), b(sphere.lambert(p, u)), "{d:?}");
        assert_eq!(
            b(sphere.phong(&lobe, p, raw)),
            b(sphere.phong(&lobe, p, u)),
            "{d:?}"
        );
        assert_eq!(b(quad.lambert(p, raw)), b(quad.lambert(p, u)), "{d:?}");
        assert_eq!(
            b(quad.phong(&lobe, p, raw)),
            b(quad.phong(&lobe, p, u)),
            "{d:?}"
        );
        assert_eq!(
            b(line.lambert(p, raw, Decay::InverseSquare)),
            b(line.lambert(p, u, Decay::InverseSquare)),
            "{d:?}"
        );
        assert_eq!(b3(sh.irradiance(raw)), b3(sh.irradiance(u)), "{d:?}");
        // The trait takes the unit vector: the light's own model, unchanged.
        assert_eq!(
            b3(quad.diffuse(p, u)),
            [b(quad.lambert(p, raw)); 3],
            "{d:?}"
        );
        compared += 1;
    }
    compared
}

#[test]
fn a_unit_vector_gives_the_same_answer_as_the_vector_it_came_from() {
    // Lengths from tiny to large in each backend's range (Fixed22: directions in [2^-8, 2^8]).
    let float_lengths = [1.0, 1e-20, 3e15, 0.37, 2.0f64.powi(-60)];
    let fixed_lengths = [1.0, 2.0f64.powi(-7), 100.0, 0.37];
    let n = [
        same_with_unit::<f64>(1, &float_lengths),
        same_with_unit::<f32>(2, &float_lengths),
        same_with_unit::<Fast32>(3, &float_lengths),
        same_with_unit::<Fixed22>(4, &fixed_lengths),
    ];
    println!("[unit] cases compared bit for bit (f64, f32, Fast32, Fixed22): {n:?}");
    assert!(n.iter().all(|&k| k >= 3900), "{n:?}");
}

fn refused<T: Real>() {
    let zero = Vec3::<T>::new(T::ZERO, T::ZERO, T::ZERO);
    assert_eq!(UnitVec3::new(zero), None);
    assert_eq!(UnitVec3::try_new(zero, "n"), Err(Error::ZeroLength("n")));
    assert_eq!(zero.try_unit("r"), Err(Error::ZeroLength("r")));
    let u = UnitVec3::<T>::z_axis();
    assert_eq!(u.try_unit("n"), Ok(u));
    assert_eq!(*(-u), Vec3::new(T::ZERO, T::ZERO, -T::ONE));
    assert_eq!(
        Vec3::from(UnitVec3::<T>::x_axis()),
        Vec3::new(T::ONE, T::ZERO, T::ZERO)
    );
    assert_eq!(UnitVec3::<T>::y_axis().into_inner().y, T::ONE);
}

#[test]
fn zero_and_non_finite_vectors_have_no_unit_vector() {
    refused::<f64>();
    refused::<f32>();
    refused::<Fast32>();
    refused::<Fixed22>();
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let v = Vec3::new(bad, 1.0, 0.0);
        assert_eq!(UnitVec3::new(v), None);
        assert_eq!(UnitVec3::try_new(v, "n"), Err(Error::NotFinite("n")));
        // And a per-sample call answers its fallback.
        let hemi = HemisphereLight::<f32>::new(Vec3::new(0.0, 0.0, 1.0)).unwrap();
        assert_eq!(hemi.lambert_const(v), 0.0);
    }
}

/// `| |reflect(v, n)| - 1 |` over random unit pairs, in units of the backend's resolution
/// (f32/f64 epsilon, 2^-22 for Fixed22).
fn reflect_length_error<T: Real>(seed: u64, ulp: f64) -> f64 {
    let mut rng = Rng::new(seed);
    let mut worst = 0f64;
    for _ in 0..100_000 {
        let n = v::<T>(rng.dir()).to_unit().unwrap();
        let e = v::<T>(rng.dir()).to_unit().unwrap();
        let r = reflect(e, n).to_f64();
        let len = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
        worst = worst.max((len - 1.0).abs() / ulp);
    }
    worst
}

#[test]
fn the_mirror_of_a_unit_vector_is_unit() {
    // Each unit vector is within 1.5 ULP per component (tests/normalize.rs) and the mirror
    // adds 6 roundings of magnitude at most 2: 12 units of the resolution bound the length's
    // error (a direction off by that much changes a model by the same relative amount).
    let worst = [
        reflect_length_error::<f64>(5, f64::EPSILON),
        reflect_length_error::<f32>(6, f32::EPSILON as f64),
        reflect_length_error::<Fast32>(7, f32::EPSILON as f64),
        reflect_length_error::<Fixed22>(8, 2f64.powi(-22)),
    ];
    println!("[unit] | |reflect(v, n)| - 1 | in units of the resolution (f64, f32, Fast32, Fixed22): {worst:.2?}");
    assert!(worst.iter().all(|&w| w <= 12.0), "{worst:?}");
}

/// `reflect` against its defining formula `n (2 n.v) - v` in the type's own `*` and `+`, bit
/// for bit (fixed point forms the products without saturation tests): random unit pairs, the
/// axes and their opposites.
fn reflect_matches_its_formula<T: Real>(seed: u64) {
    let mut rng = Rng::new(seed);
    let axes = [
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, -1.0],
    ];
    let mut dirs: Vec<[f64; 3]> = axes.to_vec();
    dirs.extend((0..20_000).map(|_| rng.dir()));
    for (i, &a) in dirs.iter().enumerate() {
        let b = dirs[(i * 7 + 3) % dirs.len()];
        let n = v::<T>(a).to_unit().unwrap();
        let e = v::<T>(b).to_unit().unwrap();
        let (ni, ei) = (n.into_inner(), e.into_inner());
        let want = ni * (T::TWO * ni.dot(ei)) - ei;
        assert_eq!(reflect(e, n).into_inner(), want, "{a:?} {b:?}");
    }
}

#[test]
fn the_mirror_is_its_formula_bit_for_bit() {
    reflect_matches_its_formula::<f64>(15);
    reflect_matches_its_formula::<f32>(16);
    reflect_matches_its_formula::<Fast32>(17);
    reflect_matches_its_formula::<Fixed22>(18);
}
