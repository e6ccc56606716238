//! One vertex shade of the board demo (`boards/demo-scene`), counted per call: the work of
//! `Lit::shade` for the demo's lights and materials, so the firmware's per-vertex cost is one
//! number. Shared by the QEMU firmware and `host-sim/tests/qemu_budget.rs` (`#[path]`), which
//! evaluates the same calls in f64 for the reference.
//!
//! The lights are the demo's at frame 0 (`demo_scene::Demo::frame(0)`): the 2 x 1.4 panel at
//! y = 1.9 (a `PolygonLight<T, 4>`, colour (2.6, 2.7, 3.0)), the lamp (a `SphereLight` of
//! radius 0.15 at (0, 0.75, 1.3), colour 14 (1.0, 0.8, 0.55)) and the faint ambient term, in a
//! `Scene<T, 3, 4>` as the demo builds it. The materials are the demo's red plastic (m = 20)
//! on the big sphere and teal (m = 48) on the torus; the shading points are [`INPUTS`] points
//! of each object with their normals, seen from the demo's camera. Each call is
//! `Lit::new(&scene, &material).shade(p, n, v)`: the polygon's Lambert and Phong terms, the
//! sphere's Lambert and Phong terms, the ambient term and the products.

use arealight::raster::{Lit, Material, Shader};
use arealight::{Ambient, PolygonLight, Real, Rgb, Scene, SceneLight, SphereLight, UnitVec3, Vec3};

use super::cases::Meter;

/// Shading points per material.
pub const INPUTS: usize = 16;

/// The cases: (name, Phong exponent).
pub const CASES: [(&str, u32); 2] = [("demo_shade_m20", 20), ("demo_shade_m48", 48)];

/// The demo's camera position.
const EYE: [f64; 3] = [0.0, 0.8, 3.3];

/// The sum of the colour weights that multiply normalized model values in one shade (the
/// diffuse reflectance's largest channel times the lights' largest colour channels, plus the
/// specular reflectance's): a model error `e` gives a shade error of at most `WEIGHT e`.
/// (The host's tolerance; unused by the firmware.)
#[allow(dead_code)]
pub fn weight(case: usize) -> f64 {
    let (diffuse, specular) = if case == 0 { (0.85, 0.35) } else { (0.55, 0.5) };
    (diffuse + specular) * (3.0 + 14.0)
}

/// The demo's lights at frame 0, every parameter through `round` (the host rounds them to the
/// backend under test).
pub fn scene<T: Real>(round: fn(f64) -> f64) -> Option<Scene<T, 3, 4>> {
    let v = |a: [f64; 3]| Vec3::from_f64(a.map(round));
    let rgb = |a: [f64; 3]| Rgb::from_f64(a.map(round));
    let panel = PolygonLight::<T, 4>::new(&[
        v([-1.0, 1.9, -1.0]),
        v([1.0, 1.9, -1.0]),
        v([1.0, 1.9, 0.4]),
        v([-1.0, 1.9, 0.4]),
    ])
    .ok()?;
    let lamp = SphereLight::new(v([0.0, 0.75, 1.3]), T::from_f64(round(0.15))).ok()?;
    let mut s: Scene<T, 3, 4> = Scene::new();
    s.push(SceneLight::Polygon(panel), rgb([2.6, 2.7, 3.0]))
        .ok()?;
    s.push(SceneLight::Sphere(lamp), rgb([14.0, 11.2, 7.7]))
        .ok()?;
    s.push(
        SceneLight::Ambient(Ambient(rgb([0.03, 0.035, 0.05]))),
        Rgb::splat(T::ONE),
    )
    .ok()?;
    Some(s)
}

/// The material of case `case` (0: red, m = 20; 1: teal, m = 48).
pub fn material<T: Real>(case: usize, round: fn(f64) -> f64) -> Option<Material<T>> {
    let rgb = |a: [f64; 3]| Rgb::from_f64(a.map(round));
    let (d, s) = if case == 0 {
        ([0.85, 0.22, 0.12], [0.35; 3])
    } else {
        ([0.12, 0.55, 0.5], [0.5; 3])
    };
    Material::new(rgb(d), rgb(s), CASES[case].1).ok()
}

fn unit(a: [f64; 3]) -> [f64; 3] {
    let l = libm::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    a.map(|x| x / l)
}

/// Shading point `i` of case `case`: `(p, n, v)` in f64 (`n`, `v` unit). Case 0: points of the
/// big sphere (centre (-0.7, 0, 0), radius 0.55) facing the camera, on a spiral from the top
/// down to the side; case 1: points of the torus (centre (0.75, 0, 0), radii 0.45 and 0.17,
/// axis y) around the tube and the ring.
pub fn point(case: usize, i: usize) -> ([f64; 3], [f64; 3], [f64; 3]) {
    let t = (i as f64 + 0.5) / INPUTS as f64;
    let (p, n) = if case == 0 {
        // Polar angle from 10 to 120 degrees, azimuth turning toward the camera (+z).
        let theta = (10.0 + 110.0 * t).to_radians();
        let phi = (-60.0 + 240.0 * t).to_radians();
        let n = [
            libm::sin(theta) * libm::sin(phi),
            libm::cos(theta),
            libm::sin(theta) * libm::cos(phi),
        ];
        ([-0.7 + 0.55 * n[0], 0.55 * n[1], 0.55 * n[2]], n)
    } else {
        let ring = (20.0 + 140.0 * t).to_radians();
        let tube = (360.0 * 3.0 * t).to_radians();
        let (cr, sr) = (libm::cos(ring), libm::sin(ring));
        let (ct, st) = (libm::cos(tube), libm::sin(tube));
        let n = [ct * cr, st, ct * sr];
        let rad = 0.45 + 0.17 * ct;
        ([0.75 + rad * cr, 0.17 * st, rad * sr], n)
    };
    let v = unit([EYE[0] - p[0], EYE[1] - p[1], EYE[2] - p[2]]);
    (p, n, v)
}

/// One counted call: the demo's `Lit::shade`.
#[inline(never)]
pub fn k_demo_shade<T: Real>(
    scene: &Scene<T, 3, 4>,
    material: &Material<T>,
    p: Vec3<T>,
    n: UnitVec3<T>,
    v: UnitVec3<T>,
) -> Rgb<T> {
    Lit::new(scene, material).shade(p, n, v)
}

/// Runs both cases over their [`INPUTS`] points through `meter`, handing `out` the case, the
/// input, the colour (f64) and the count. `None` when a constructor refuses (it does not).
pub fn run<T: Real, M: Meter>(
    round: fn(f64) -> f64,
    meter: &mut M,
    out: &mut impl FnMut(usize, usize, [f64; 3], u32),
) -> Option<()> {
    let scene = scene::<T>(round)?;
    for case in 0..CASES.len() {
        let material = material::<T>(case, round)?;
        for i in 0..INPUTS {
            let (p, n, v) = point(case, i);
            let conv = |a: [f64; 3]| Vec3::<T>::from_f64(a.map(round));
            // The rasterizer hands the shader unit vectors (normalized once per vertex).
            let unit = |a: [f64; 3]| conv(a).to_unit().unwrap_or(UnitVec3::z_axis());
            let (p, n, v) = core::hint::black_box((conv(p), unit(n), unit(v)));
            let (s, m) = core::hint::black_box((&scene, &material));
            let (c, count) = meter.call(|| k_demo_shade(s, m, p, n, v));
            out(case, i, c.to_f64(), count);
        }
    }
    Some(())
}
