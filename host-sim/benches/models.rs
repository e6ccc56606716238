//! Host cost of one call of each model, per scalar type (criterion).
//!
//! `cargo bench -p host-sim --bench models` (add `-- NAME` to filter). Each benchmark evaluates
//! the model over a fixed ring of 64 normals sweeping the terminator, so every case of a
//! piecewise formula is exercised, and reports the time per call. Figures for the target chips
//! come from the QEMU instruction counter (boards/), not from here.

use arealight::{
    CapLight, Fast32, Fixed22, HemisphereLight, OvercastSky, PhongLobe, PolygonLight, Real, Rgb,
    Sh9, SkyGround, SphereLight, Vec3,
};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn normals<T: Real>() -> Vec<Vec3<T>> {
    (0..64)
        .map(|i| {
            let t = i as f64 / 64.0 * std::f64::consts::PI;
            Vec3::from_f64([t.sin() * 0.8, t.sin() * 0.6, t.cos()])
        })
        .collect()
}

fn bench_backend<T: Real>(c: &mut Criterion, name: &str) {
    let ns = normals::<T>();
    let v = |x: f64, y: f64, z: f64| Vec3::<T>::from_f64([x, y, z]);
    let z = v(0.0, 0.0, 1.0);
    let p = v(0.0, 0.0, 0.0);
    let hemi = HemisphereLight::new(z).unwrap();
    let sky = OvercastSky::new(z, T::ONE).unwrap();
    let sg = SkyGround::new(
        z,
        Rgb::from_f64([0.5, 0.5, 1.0]),
        Rgb::from_f64([0.2, 1.0, 0.2]),
    )
    .unwrap();
    let cap = CapLight::new(z, T::from_f64(0.4)).unwrap();
    let sphere = SphereLight::new(v(0.0, 0.0, 3.0), T::ONE).unwrap();
    let quad = [
        v(-1.0, -1.0, 2.0),
        v(1.0, -1.0, 2.0),
        v(1.0, 1.0, 2.0),
        v(-1.0, 1.0, 2.0),
    ];
    let poly = PolygonLight::<T, 8>::new(&quad).unwrap();
    let sh = Sh9::<T>::environment(arealight::Environment::GraceCathedral).prepare();
    let lobes = [1u32, 2, 16, 64].map(|m| (m, PhongLobe::<T>::new(m).unwrap()));

    let mut g = c.benchmark_group(name);
    macro_rules! per_normal {
        ($id:expr, $f:expr) => {
            g.bench_function($id, |b| {
                b.iter(|| {
                    let mut acc = T::ZERO;
                    for &n in &ns {
                        acc += $f(black_box(n));
                    }
                    acc
                })
            });
        };
    }
    per_normal!("hemi_const", |n| hemi.lambert_const(n));
    per_normal!("hemi_cos", |n| hemi.lambert_cos(n));
    per_normal!("sky_overcast", |n| sky.lambert(n));
    per_normal!("sky_ground", |n| sg.irradiance(n).r);
    per_normal!("cap_lambert", |n| cap.lambert(n));
    per_normal!("cap_lambert_hermite", |n| cap.lambert_hermite(n));
    per_normal!("sphere_lambert", |n| sphere.lambert(p, n));
    per_normal!("sphere_lambert_hermite", |n| sphere.lambert_hermite(p, n));
    per_normal!("polygon_lambert", |n| poly.lambert(p, n));
    per_normal!("sh9_irradiance", |n| sh.irradiance(n).r);
    for (m, lobe) in &lobes {
        per_normal!(format!("phong_hemi_const/m={m}"), |r| hemi
            .phong_const(lobe, r));
        per_normal!(format!("phong_hemi_cos/m={m}"), |r| hemi.phong_cos(lobe, r));
        per_normal!(format!("phong_cap/m={m}"), |r| cap.phong(lobe, r));
        per_normal!(format!("phong_sphere/m={m}"), |r| sphere.phong(lobe, p, r));
        per_normal!(format!("phong_polygon/m={m}"), |r| poly.phong(lobe, p, r));
    }
    // Arvo's moments, full sum against early termination (eq. 21) at two tolerances.
    for m in [8u32, 64] {
        per_normal!(format!("axial_moment/m={m}"), |w| poly
            .axial_moment(p, w, m));
        for tol in [1e-6, 1e-3] {
            per_normal!(format!("axial_moment_within/m={m}/tol={tol:e}"), |w| poly
                .axial_moment_within(p, w, m, T::from_f64(tol)));
        }
    }
    g.finish();
}

fn benches(c: &mut Criterion) {
    bench_backend::<f64>(c, "f64");
    bench_backend::<f32>(c, "f32");
    bench_backend::<Fast32>(c, "f32-fast");
    bench_backend::<Fixed22>(c, "fixed");
}

criterion_group! {
    name = models;
    config = Criterion::default().sample_size(20).warm_up_time(std::time::Duration::from_millis(200)).measurement_time(std::time::Duration::from_millis(600));
    targets = benches
}
criterion_main!(models);
