//! Scenes (issue 7): culling drops exactly the lights that cannot reach an object, and a
//! prepared scene shades bit-identically to the whole scene at every point and normal of the
//! object, on every backend.

mod common;

use arealight::{
    DirectionalLight, DistanceFalloff, Fixed22, Illuminant, LightFrame, ObjectBounds, PhongLobe,
    PointLight, PolygonLight, PushError, Real, Rgb, Scene, SceneLight, SphereLight, Superellipse,
    Uberlight, UnitVec3, Vec3,
};
use common::*;

fn v3<T: Real>(x: f64, y: f64, z: f64) -> Vec3<T> {
    Vec3::from_f64([x, y, z])
}

/// A direction as the `Illuminant` trait takes it: normalized once.
fn u<T: Real>(a: V3) -> UnitVec3<T> {
    v::<T>(a).to_unit().expect("a nonzero direction")
}

/// A spot (uberlight) at `origin` pointing along `dir`, its beam cut off beyond `zfar`.
fn spot<T: Real>(origin: Vec3<T>, dir: Vec3<T>, zfar: f64) -> Uberlight<T> {
    let up = if dir.to_f64()[2].abs() < 0.9 {
        v3(0.0, 0.0, 1.0)
    } else {
        v3(1.0, 0.0, 0.0)
    };
    let c = T::from_f64;
    Uberlight::new(
        LightFrame::new(origin, dir, up).unwrap(),
        Superellipse::new(c(0.3), c(0.3), c(0.5), c(0.5), c(0.5)).unwrap(),
        DistanceFalloff::new(c(2.0), c(1.0), c(1.0), c(0.2), c(zfar), c(0.1), c(0.5)).unwrap(),
    )
}

/// The benchmark configuration: 16 lights around a unit-radius object at the origin,
/// of which 2 can reach it (a sphere light and a polygon light); 7 spots point away from it
/// and 7 point at it but are cut off before it. Coordinates within [-4, 4] (fixed point).
pub fn sixteen_lights<T: Real>() -> Scene<T, 16> {
    let mut s = Scene::new();
    let white = Rgb::splat(T::ONE);
    s.push(
        SceneLight::Sphere(SphereLight::new(v3(0.0, 2.0, 2.0), T::from_f64(0.3)).unwrap()),
        white,
    )
    .unwrap();
    let quad = [
        v3(-0.5, -0.5, 2.5),
        v3(0.5, -0.5, 2.5),
        v3(0.5, 0.5, 2.5),
        v3(-0.5, 0.5, 2.5),
    ];
    s.push(
        SceneLight::Polygon(PolygonLight::new(&quad).unwrap()),
        Rgb::from_f64([1.0, 0.8, 0.6]),
    )
    .unwrap();
    for i in 0..14 {
        let a = i as f64 * 0.45;
        let (ca, sa) = (a.cos(), a.sin());
        let origin = v3::<T>(3.0 * ca, 3.0 * sa, 1.0);
        let light = SceneLight::Point(PointLight::new(origin).unwrap());
        let shape = if i % 2 == 0 {
            // Pointing away from the object.
            spot(origin, v3(ca, sa, 0.0), 3.0)
        } else {
            // Pointing at it, cut off at z = 1 + 0.5 < 3.16 - 1.
            spot(origin, v3(-ca, -sa, -1.0 / 3.0), 1.0)
        };
        s.push_shaped(light, white, shape).unwrap();
    }
    s
}

macro_rules! scene_tests {
    ($name:ident, $T:ty) => {
        mod $name {
            use super::*;
            type T = $T;

            /// Samples of the object: points in its bounding sphere, any unit normal, any
            /// unit reflection direction.
            fn samples(rng: &mut Rng, count: usize, up_only: bool) -> Vec<(V3, V3, V3)> {
                (0..count)
                    .map(|_| {
                        let p = scale(rng.dir(), rng.unit().cbrt());
                        let mut n = rng.dir();
                        if up_only {
                            n = [0.0, 0.0, 1.0];
                        }
                        (p, n, rng.dir())
                    })
                    .collect()
            }

            fn assert_same<L1: Illuminant<T>, L2: Illuminant<T>>(
                a: &L1,
                b: &L2,
                cases: &[(V3, V3, V3)],
            ) {
                // The exact lobe, and an odd-only one evaluated at m = 17.
                let lobes = [
                    PhongLobe::<T>::new(16).unwrap(),
                    PhongLobe::<T>::odd_only(16).unwrap(),
                ];
                for (lobe, &(p, n, r)) in
                    lobes.iter().flat_map(|l| cases.iter().map(move |c| (l, c)))
                {
                    let (p, n, r) = (v::<T>(p), u::<T>(n), u::<T>(r));
                    assert_eq!(a.diffuse(p, n).to_f64(), b.diffuse(p, n).to_f64());
                    assert_eq!(a.phong(lobe, p, r).to_f64(), b.phong(lobe, p, r).to_f64());
                    // Both terms in one call: the same bits as the two calls.
                    let (ad, ap) = a.diffuse_and_phong(lobe, p, n, r);
                    let (bd, bp) = b.diffuse_and_phong(lobe, p, n, r);
                    assert_eq!(ad.to_f64(), a.diffuse(p, n).to_f64());
                    assert_eq!(ap.to_f64(), a.phong(lobe, p, r).to_f64());
                    assert_eq!(bd.to_f64(), b.diffuse(p, n).to_f64());
                    assert_eq!(bp.to_f64(), b.phong(lobe, p, r).to_f64());
                }
            }

            #[test]
            fn sixteen_lights_prepare_to_two_and_shade_identically() {
                let scene = sixteen_lights::<T>();
                assert_eq!(scene.len(), 16);
                let object = ObjectBounds::sphere(v3::<T>(0.0, 0.0, 0.0), T::ONE).unwrap();
                for specular in [false, true] {
                    let prepared = scene.prepare(&object, specular);
                    assert_eq!(prepared.active_indices(), &[0, 1], "specular {specular}");
                }
                let prepared = scene.prepare(&object, true);
                let mut rng = Rng::new(0x5ce);
                let cases = samples(&mut rng, 20_000, false);
                assert_same(&scene, &prepared, &cases);
                // And the kept lights do light the object.
                let lit = cases
                    .iter()
                    .any(|&(p, n, _)| prepared.diffuse(v::<T>(p), u::<T>(n)).to_f64()[0] > 0.01);
                assert!(lit);
            }

            #[test]
            fn lights_below_a_matte_floor_are_culled_only_without_specular() {
                let mut scene: Scene<T, 8> = Scene::new();
                let white = Rgb::splat(T::ONE);
                // Above the floor z = 0 (reach it) ...
                scene
                    .push(
                        SceneLight::Point(PointLight::new(v3(0.0, 0.0, 2.0)).unwrap()),
                        white,
                    )
                    .unwrap();
                scene
                    .push(
                        SceneLight::Directional(DirectionalLight::new(v3(0.2, 0.1, 1.0)).unwrap()),
                        white,
                    )
                    .unwrap();
                // ... and below it (cannot, for the diffuse term).
                scene
                    .push(
                        SceneLight::Sphere(
                            SphereLight::new(v3(0.5, 0.0, -2.0), T::from_f64(0.5)).unwrap(),
                        ),
                        white,
                    )
                    .unwrap();
                let below = [
                    v3(-0.5, -0.5, -2.5),
                    v3(0.5, -0.5, -2.5),
                    v3(0.0, 0.5, -2.5),
                ];
                scene
                    .push(
                        SceneLight::Polygon(PolygonLight::new(&below).unwrap()),
                        white,
                    )
                    .unwrap();
                scene
                    .push(
                        SceneLight::Directional(DirectionalLight::new(v3(0.0, 0.3, -1.0)).unwrap()),
                        white,
                    )
                    .unwrap();
                // The floor: a disc of radius 1 at z = 0 facing up.
                let floor = ObjectBounds::sphere(v3::<T>(0.0, 0.0, 0.0), T::ONE)
                    .unwrap()
                    .with_normal_cone(v3::<T>(0.0, 0.0, 1.0), T::ZERO)
                    .unwrap();
                let matte = scene.prepare(&floor, false);
                assert_eq!(matte.active_indices(), &[0, 1]);
                let glossy = scene.prepare(&floor, true);
                assert_eq!(glossy.active(), 5);
                let mut rng = Rng::new(0xf100);
                let cases: Vec<_> = samples(&mut rng, 20_000, true)
                    .into_iter()
                    .map(|(p, n, r)| ([p[0], p[1], 0.0], n, r))
                    .collect();
                // The matte view equals the whole scene in its diffuse term.
                for &(p, n, _) in &cases {
                    let (p, n) = (v::<T>(p), u::<T>(n));
                    assert_eq!(scene.diffuse(p, n).to_f64(), matte.diffuse(p, n).to_f64());
                }
                assert_same(&scene, &glossy, &cases);
            }

            #[test]
            fn a_full_scene_hands_the_light_back() {
                let mut scene: Scene<T, 2> = Scene::new();
                let l = || SceneLight::Point(PointLight::new(v3::<T>(0.0, 0.0, 1.0)).unwrap());
                assert_eq!(scene.push(l(), Rgb::splat(T::ONE)), Ok(0));
                assert_eq!(scene.push(l(), Rgb::splat(T::ONE)), Ok(1));
                assert_eq!(
                    scene.push(l(), Rgb::splat(T::ONE)),
                    Err(PushError::Full(l()))
                );
                assert_eq!(scene.len(), 2);
            }
        }
    };
}

scene_tests!(f64_scene, f64);
scene_tests!(f32_scene, f32);
scene_tests!(fixed_scene, Fixed22);

#[test]
fn non_finite_colour_is_refused() {
    let mut scene: Scene<f32, 2> = Scene::new();
    let l = SceneLight::Point(PointLight::new(v3::<f32>(0.0, 0.0, 1.0)).unwrap());
    assert_eq!(
        scene.push(l.clone(), Rgb::new(f32::NAN, 0.0, 0.0)),
        Err(PushError::NotFinite(l))
    );
    assert!(scene.is_empty());
}

/// Random configurations: a culled light's own contribution is exactly 0 at every sample
/// (the conservative side of every test), for random spots and objects.
#[test]
fn culled_lights_contribute_exactly_zero() {
    let mut rng = Rng::new(0xc011);
    let lobe = PhongLobe::<f32>::new(8).unwrap();
    let mut culled = 0;
    for _ in 0..400 {
        let o = [
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ];
        let radius = rng.range(0.05, 1.0);
        let object = ObjectBounds::sphere(v::<f32>(o), radius as f32).unwrap();
        let origin = [
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
        ];
        let dir = rng.dir();
        let zfar = rng.range(0.3, 4.0);
        let mut scene: Scene<f32, 1> = Scene::new();
        let light = SceneLight::Sphere(SphereLight::new(v::<f32>(origin), 0.1).unwrap());
        scene
            .push_shaped(light, Rgb::splat(1.0), spot(v(origin), v(dir), zfar))
            .unwrap();
        if scene.prepare(&object, true).active() == 1 {
            continue;
        }
        culled += 1;
        for _ in 0..200 {
            let p = add(o, scale(rng.dir(), radius * rng.unit().cbrt()));
            let (p, n, r) = (v::<f32>(p), u::<f32>(rng.dir()), u::<f32>(rng.dir()));
            assert_eq!(scene.diffuse(p, n).to_f64(), [0.0; 3]);
            assert_eq!(scene.phong(&lobe, p, r).to_f64(), [0.0; 3]);
        }
    }
    println!("culled {culled} of 400 random spot/object configurations");
    assert!(culled > 50);
}

/// Renders `light` on a unit UV sphere at the origin (96 x 96, per-pixel, with depth) and
/// returns the RGB888 pixels.
fn render<T: Real, L: Illuminant<T>>(light: &L) -> Vec<arealight::raster::Rgb888> {
    use arealight::raster::{
        draw, mesh, Affine, Band, Camera, DrawOptions, Lit, Material, Mesh, Projection, Rgb888,
        Shading, Vertex,
    };
    let counts = mesh::uv_sphere_counts(12, 20);
    let zero = Vec3::new(T::ZERO, T::ZERO, T::ZERO);
    let mut verts = vec![Vertex::new(zero, zero); counts.vertices];
    let mut tris = vec![[0u16; 3]; counts.triangles];
    mesh::uv_sphere(T::ONE, 12, 20, &mut verts, &mut tris).unwrap();
    let mesh = Mesh::new(&verts, &tris).unwrap();
    let camera = Camera::new(
        v3(0.3, 1.2, 3.5),
        v3(0.0, 0.0, 0.0),
        v3(0.0, 1.0, 0.0),
        Projection::Perspective {
            fov_y: T::from_f64(0.7),
        },
        96,
        96,
    )
    .unwrap();
    let material =
        Material::new(Rgb::from_f64([0.8, 0.5, 0.3]), Rgb::from_f64([0.4; 3]), 16).unwrap();
    let mut px = vec![Rgb888::default(); 96 * 96];
    let mut depth = vec![u16::MAX; 96 * 96];
    let mut band = Band::new(&mut px, Some(&mut depth), 96, 0).unwrap();
    let shader = Lit::new(light, &material);
    draw(
        &camera,
        &mut band,
        &mesh,
        &Affine::identity(),
        &shader,
        &DrawOptions::new(Shading::PerPixel),
    )
    .unwrap();
    px
}

/// Culling never changes an image: the 16-light scene and its prepared view render the same
/// pixels, bit for bit, on every backend.
#[test]
fn culled_and_unculled_renders_are_identical() {
    fn check<T: Real>() {
        let scene = sixteen_lights::<T>();
        let object = ObjectBounds::sphere(v3::<T>(0.0, 0.0, 0.0), T::ONE).unwrap();
        let prepared = scene.prepare(&object, true);
        assert_eq!(prepared.active(), 2);
        let (a, b) = (render(&scene), render(&prepared));
        assert!(a.iter().any(|p| p.0 != [0, 0, 0]), "the sphere is lit");
        assert_eq!(a, b);
    }
    check::<f64>();
    check::<f32>();
    check::<Fixed22>();
}

/// A polygon light's `diffuse_and_phong` (one range check and one test against its plane for
/// both terms, and in fixed point each vertex's unit direction normalized once for the
/// Lambert term, the Phong term's negligibility test and its walk) is the two calls bit for
/// bit: random points around a quad, points in its plane
/// over and beside the face, near its vertices (fixed point: `Unresolved`, 0 from both), and
/// beyond the fixed-point coordinate limit; even and odd exponents.
fn polygon_terms_in_one_call<T: Real>(seed: u64) {
    let quad = [
        v3::<T>(-0.5, -0.5, 1.0),
        v3(0.5, -0.5, 1.0),
        v3(0.5, 0.5, 1.2),
        v3(-0.5, 0.5, 1.2),
    ];
    let light = PolygonLight::<T, 4>::new(&quad).unwrap();
    let mut rng = Rng::new(seed);
    let mut points: Vec<V3> = (0..3000)
        .map(|_| scale(rng.dir(), 2.0 * rng.unit()))
        .collect();
    // In the plane (z = 1 + 0.2 (y + 0.5)), over the face and beside it.
    for &(x, y) in &[(0.0, 0.0), (0.2, -0.3), (1.5, 0.0), (0.0, 2.0), (-3.0, 0.5)] {
        points.push([x, y, 1.0 + 0.2 * (y + 0.5)]);
    }
    // Near a vertex and an edge, and beyond the coordinate limit of fixed point.
    points.extend([
        [-0.5 + 1e-6, -0.5, 1.0 - 1e-6],
        [0.0, -0.5 - 1e-6, 0.99],
        [5.0, 0.0, 0.0],
        [0.0, -4.5, 2.0],
    ]);
    let lobes = [16, 17, 48].map(|m| PhongLobe::<T>::new(m).unwrap());
    let mut nonzero = 0;
    for (i, &p) in points.iter().enumerate() {
        let (n, r) = (u::<T>(rng.dir()), u::<T>(rng.dir()));
        let lobe = &lobes[i % lobes.len()];
        let p = v::<T>(p);
        let (d, s) = Illuminant::diffuse_and_phong(&light, lobe, p, n, r);
        assert_eq!(
            d.to_f64(),
            Illuminant::diffuse(&light, p, n).to_f64(),
            "{p:?}"
        );
        assert_eq!(
            s.to_f64(),
            Illuminant::phong(&light, lobe, p, r).to_f64(),
            "{p:?}"
        );
        nonzero += usize::from(d.to_f64()[0] > 0.0 && s.to_f64()[0] > 0.0);
    }
    assert!(nonzero > 100, "{nonzero}");
}

#[test]
fn a_polygon_light_shades_both_terms_in_one_call_bit_for_bit() {
    polygon_terms_in_one_call::<f64>(11);
    polygon_terms_in_one_call::<f32>(12);
    polygon_terms_in_one_call::<Fixed22>(13);
}
