//! Issue 7's comparison on the target: one object rendered with 16 lights of which 2 can reach
//! it (the scene prepared for the object, `prepare` counted) against the same object with only
//! those 2 lights. Prints `S <backend> <scene> <instructions> <checksum>`; the host test checks
//! that both frames are the same pixels (equal checksums) and that the first costs at most
//! 1.25 times the second.
//!
//! The object: a unit UV sphere (4 stacks, 6 slices) rendered per pixel into a 12 x 12 RGB565
//! frame with a depth band, on the stack (no allocation); the lights as in `tests/scene.rs`: a
//! sphere light and a polygon light that reach it, and 14 point lights shaped by uberlight
//! beams that point away from it or are cut off before it. Coordinates stay within [-4, 4]
//! (the fixed-point range).

use arealight::raster::{
    draw, mesh, Affine, Band, Camera, DrawOptions, Lit, Material, Mesh, Projection, Rgb565,
    Shading, Vertex,
};
use arealight::{
    DistanceFalloff, Illuminant, LightFrame, ObjectBounds, PointLight, PolygonLight, Real, Rgb,
    Scene, SceneLight, SphereLight, Superellipse, Uberlight, Vec3,
};

use crate::cases::Meter;

const W: u16 = 12;
const STACKS: u16 = 4;
const SLICES: u16 = 6;
const NV: usize = ((STACKS + 1) * (SLICES + 1)) as usize;
const NT: usize = (2 * SLICES * (STACKS - 1)) as usize;

fn v<T: Real>(x: f64, y: f64, z: f64) -> Vec3<T> {
    Vec3::from_f64([x, y, z])
}

fn spot<T: Real>(origin: Vec3<T>, dir: Vec3<T>, zfar: f64) -> Option<Uberlight<T>> {
    let up = if dir.to_f64()[2].abs() < 0.9 {
        v(0.0, 0.0, 1.0)
    } else {
        v(1.0, 0.0, 0.0)
    };
    let c = T::from_f64;
    Some(Uberlight::new(
        LightFrame::new(origin, dir, up).ok()?,
        Superellipse::new(c(0.3), c(0.3), c(0.5), c(0.5), c(0.5)).ok()?,
        DistanceFalloff::new(c(2.0), c(1.0), c(1.0), c(0.2), c(zfar), c(0.1), c(0.5)).ok()?,
    ))
}

/// The 2 reaching lights, then (with `all`) the 14 that cannot reach the sphere (`L`: the
/// capacity, 2 for the small scene: the M0 image has 16 KB of RAM for everything).
fn scene<T: Real, const L: usize>(all: bool) -> Option<Scene<T, L, 4>> {
    let mut s = Scene::new();
    let white = Rgb::splat(T::ONE);
    let sphere = SphereLight::new(v(0.0, 2.0, 2.0), T::from_f64(0.3)).ok()?;
    s.push(SceneLight::Sphere(sphere), white).ok()?;
    let quad = [
        v(-0.5, -0.5, 2.5),
        v(0.5, -0.5, 2.5),
        v(0.5, 0.5, 2.5),
        v(-0.5, 0.5, 2.5),
    ];
    let panel = PolygonLight::new(&quad).ok()?;
    s.push(SceneLight::Polygon(panel), Rgb::from_f64([1.0, 0.8, 0.6]))
        .ok()?;
    if all {
        for i in 0..14 {
            let a = i as f64 * 0.45;
            let (ca, sa) = (libm::cos(a), libm::sin(a));
            let origin = v(3.0 * ca, 3.0 * sa, 1.0);
            let shape = if i % 2 == 0 {
                spot(origin, v(ca, sa, 0.0), 3.0)?
            } else {
                spot(origin, v(-ca, -sa, -1.0 / 3.0), 1.0)?
            };
            let point = PointLight::new(origin).ok()?;
            s.push_shaped(SceneLight::Point(point), white, shape).ok()?;
        }
    }
    Some(s)
}

/// Renders the sphere under `light` and returns a checksum of the frame's pixels.
fn render<T: Real, L: Illuminant<T> + ?Sized>(
    light: &L,
    verts: &[Vertex<T>],
    tris: &[[u16; 3]],
    camera: &Camera<T>,
    material: &Material<T>,
) -> u32 {
    let mut px = [Rgb565::default(); (W as usize) * (W as usize)];
    let mut depth = [u16::MAX; (W as usize) * (W as usize)];
    let (Ok(mesh), Ok(mut band)) = (
        Mesh::new(verts, tris),
        Band::new(&mut px, Some(&mut depth), W, 0),
    ) else {
        return 0;
    };
    let shader = Lit::new(light, material);
    let _ = draw(
        camera,
        &mut band,
        &mesh,
        &Affine::identity(),
        &shader,
        &DrawOptions::new(Shading::PerPixel),
    );
    px.iter().enumerate().fold(0u32, |h, (i, p)| {
        h.rotate_left(5) ^ (p.0 as u32).wrapping_mul(i as u32 | 1)
    })
}

/// `(instructions, checksum)` of the 16-light (prepared) and 2-light frames, or `None` when a
/// constructor refuses (it does not: the host test fails on a missing `S` line).
pub fn run<T: Real, M: Meter>(meter: &mut M) -> Option<[(u32, u32); 2]> {
    let zero = v::<T>(0.0, 0.0, 0.0);
    let mut verts = [Vertex::new(zero, zero); NV];
    let mut tris = [[0u16; 3]; NT];
    mesh::uv_sphere(T::ONE, STACKS, SLICES, &mut verts, &mut tris).ok()?;
    let camera = Camera::new(
        v(0.3, 1.2, 3.5),
        zero,
        v(0.0, 1.0, 0.0),
        Projection::Perspective {
            fov_y: T::from_f64(0.7),
        },
        W,
        W,
    )
    .ok()?;
    let material =
        Material::new(Rgb::from_f64([0.8, 0.5, 0.3]), Rgb::from_f64([0.4; 3]), 16).ok()?;
    let (sixteen, two) = (scene::<T, 16>(true)?, scene::<T, 2>(false)?);
    let object = ObjectBounds::sphere(zero, T::ONE).ok()?;
    let (a, n16) = meter.call(|| {
        let lit = sixteen.prepare(&object, true);
        render(&lit, &verts, &tris, &camera, &material)
    });
    let (b, n2) = meter.call(|| render(&two, &verts, &tris, &camera, &material));
    Some([(n16, a), (n2, b)])
}
