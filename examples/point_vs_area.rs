//! One shading point under two area lights, a square panel (`PolygonLight`) and a spherical
//! lamp (`SphereLight`), evaluated with the three number types a firmware chooses between:
//! `f64` (the reference), `f32` (a chip with an FPU) and `Fixed22` (fixed point, for chips
//! without one), each with its error against `f64`. Beside them, the value a point light at
//! the light's centre would give: the approximation that area lights replace.
//!
//! Run it with
//!
//! ```sh
//! cargo run --example point_vs_area
//! ```
//!
//! The models are defined in `docs/models.md` (`polygon_lambert`, `phong_polygon`,
//! `sphere_lambert`, `sphere_lambert_hermite`, `phong_sphere`). Every value is normalized: a
//! whole hemisphere of unit radiance would give 1. The scene stays inside the cube
//! `[-4, 4]^3`, the fixed-point type's coordinate range (the models are scale invariant, so any
//! scene can be scaled into it).

use arealight::{Fixed22, PhongLobe, PolygonLight, Real, SphereLight, Vec3};

/// The shading point, its normal and the mirror direction of the view (any length).
const P: [f64; 3] = [0.0, 0.0, 0.0];
const N: [f64; 3] = [0.0, 1.0, 0.25];
const R: [f64; 3] = [0.4, 1.0, 0.1];
/// A 1.5 x 1.5 panel overhead, facing down.
const PANEL: [[f64; 3]; 4] = [
    [-1.0, 2.0, -1.0],
    [0.5, 2.0, -1.0],
    [0.5, 2.0, 0.5],
    [-1.0, 2.0, 0.5],
];
/// A spherical lamp low on the horizon, partly below the tangent plane: where a point light
/// is most wrong (fully above the horizon, a sphere gives exactly the point-light value).
const CENTER: [f64; 3] = [1.5, 0.3, -0.3];
const RADIUS: f64 = 0.5;
/// The Phong exponent of the specular rows.
const M: u32 = 16;

/// The five values, in the number type `T`, converted to f64 for printing. `exact_sphere`
/// is false for `Fixed22`, whose supported sphere model is the Hermite approximation.
fn shade<T: Real>(exact_sphere: bool) -> Result<[Option<f64>; 5], arealight::Error> {
    let v = |a: [f64; 3]| Vec3::<T>::from_f64(a);
    // Constructors validate once (zero area, non-planar, radius <= 0...) and return Result.
    let panel = PolygonLight::<T, 4>::new(&PANEL.map(v))?;
    let lamp = SphereLight::new(v(CENTER), T::from_f64(RADIUS))?;
    let lobe = PhongLobe::<T>::new(M)?;
    let (p, n, r) = (v(P), v(N), v(R));
    // Per sample: never panics, never NaN (the `try_` twins report invalid samples instead).
    Ok([
        Some(panel.lambert(p, n).to_f64()),
        Some(panel.phong(&lobe, p, r).to_f64()),
        exact_sphere.then(|| lamp.lambert(p, n).to_f64()),
        Some(lamp.lambert_hermite(p, n).to_f64()),
        Some(lamp.phong(&lobe, p, r).to_f64()),
    ])
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn unit(a: [f64; 3]) -> [f64; 3] {
    let l = dot(a, a).sqrt();
    [a[0] / l, a[1] / l, a[2] / l]
}

/// The point-light approximations, normalized like the area models: all of the light's
/// power from its centre. Lambert: `(1/pi) * solid angle * cos(normal, direction)` with the
/// solid angle `area cos(panel normal, direction) / d^2` (panel) or `pi R^2 / d^2` (sphere);
/// Phong: `((m + 1)/(2 pi)) * solid angle * cos(r, direction)^m`.
fn point_light() -> [f64; 5] {
    let (n, r) = (unit(N), unit(R));
    let centre = PANEL.iter().fold([0.0; 3], |c, v| {
        [c[0] + v[0] / 4.0, c[1] + v[1] / 4.0, c[2] + v[2] / 4.0]
    });
    let to_panel = sub(centre, P);
    let d2 = dot(to_panel, to_panel);
    let l = unit(to_panel);
    let area = 1.5 * 1.5;
    let panel_solid = area * l[1].abs() / d2; // the panel's normal is +-y
    let to_lamp = sub(CENTER, P);
    let lamp_solid = std::f64::consts::PI * RADIUS * RADIUS / dot(to_lamp, to_lamp);
    let s = unit(to_lamp);
    let lambert = |solid: f64, l: [f64; 3]| solid * dot(n, l).max(0.0) / std::f64::consts::PI;
    let phong = |solid: f64, l: [f64; 3]| {
        (M as f64 + 1.0) / std::f64::consts::TAU * solid * dot(r, l).max(0.0).powi(M as i32)
    };
    [
        lambert(panel_solid, l),
        phong(panel_solid, l),
        lambert(lamp_solid, s),
        lambert(lamp_solid, s),
        phong(lamp_solid, s),
    ]
}

fn main() -> Result<(), arealight::Error> {
    let reference = shade::<f64>(true)?;
    let single = shade::<f32>(true)?;
    let fixed = shade::<Fixed22>(false)?;
    let point = point_light();
    let names = [
        "polygon_lambert",
        "phong_polygon (m = 16)",
        "sphere_lambert",
        "sphere_lambert_hermite",
        "phong_sphere (m = 16)",
    ];
    println!(
        "{:<24} {:>12} {:>12} {:>9} {:>12} {:>9} {:>12} {:>9}",
        "model", "f64", "f32", "error", "Fixed22", "error", "point light", "error"
    );
    for (i, name) in names.iter().enumerate() {
        let exact = reference[i].unwrap_or(f64::NAN);
        // The approximations are compared with the exact model they replace.
        let truth = if i == 3 { reference[2] } else { reference[i] }.unwrap_or(f64::NAN);
        let cell = |x: Option<f64>, against: f64| match x {
            Some(x) => format!("{x:>12.8} {:>9.1e}", (x - against).abs()),
            None => format!("{:>12} {:>9}", "-", "-"),
        };
        println!(
            "{name:<24} {exact:>12.8} {} {} {}",
            cell(single[i], exact),
            cell(fixed[i], exact),
            cell(Some(point[i]), truth),
        );
    }
    println!();
    println!("f32 and Fixed22 errors are against f64 on the same model; the point light's");
    println!("error is against the exact area model (sphere_lambert for the Hermite row).");
    println!("Fixed22 answers the Hermite sphere model, not the exact one (docs/models.md).");
    println!("A sphere wholly above the horizon gives exactly the point light's Lambert value;");
    println!("this lamp straddles the horizon, and the panel is too large and too near for its");
    println!("centre to stand for it.");
    Ok(())
}
