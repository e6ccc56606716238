//! What a scene costs (criterion): culling and per-sample early exits (issue 7).
//!
//! `cargo bench -p host-sim --bench scene`. Each benchmark renders one unit sphere (96 x 96,
//! per-pixel shading, depth) with the crate's rasterizer in f32:
//!
//! - `16_lights_prepared` against `2_lights`: a scene of 16 lights of which 2 can reach the
//!   sphere (the other 14 are spots pointing away or cut off before it), prepared for the
//!   sphere, against a scene of only those 2. The bound: the first within 1.25x.
//! - `16_lights_unprepared`: the same 16 lights without `prepare`, for contrast (each culled
//!   light still costs its beam factor per sample).
//! - `cap/half_lit` against `cap/fully_lit`: a cap light in a scene, from the side (half of the
//!   visible sphere is dark: those samples exit after one dot product, Lambert and Phong
//!   alike) and from the camera (every sample lit). `cap/half_lit_model_only`: the bare
//!   model on the half-lit sphere, which computes its way to 0 on the dark half.

use arealight::raster::{
    draw, mesh, Affine, Band, Camera, DrawOptions, Lit, Material, Mesh, Projection, Rgb888,
    Shading, Vertex,
};
use arealight::{
    CapLight, DistanceFalloff, Illuminant, LightFrame, ObjectBounds, PointLight, PolygonLight, Rgb,
    Scene, SceneLight, SphereLight, Superellipse, Uberlight, Vec3,
};
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

type T = f32;

fn v(x: f64, y: f64, z: f64) -> Vec3<T> {
    Vec3::from_f64([x, y, z])
}

fn spot(origin: Vec3<T>, dir: Vec3<T>, zfar: f32) -> Uberlight<T> {
    let up = if dir.z.abs() < 0.9 {
        v(0.0, 0.0, 1.0)
    } else {
        v(1.0, 0.0, 0.0)
    };
    Uberlight::new(
        LightFrame::new(origin, dir, up).unwrap(),
        Superellipse::new(0.3, 0.3, 0.5, 0.5, 0.5).unwrap(),
        DistanceFalloff::new(2.0, 1.0, 1.0, 0.2, zfar, 0.1, 0.5).unwrap(),
    )
}

/// The two lights that reach the sphere, then (with `all`) the 14 that cannot.
fn scene(all: bool) -> Scene<T, 16> {
    let mut s = Scene::new();
    let white = Rgb::splat(1.0);
    s.push(
        SceneLight::Sphere(SphereLight::new(v(0.0, 2.0, 2.0), 0.3).unwrap()),
        white,
    )
    .unwrap();
    let quad = [
        v(-0.5, -0.5, 2.5),
        v(0.5, -0.5, 2.5),
        v(0.5, 0.5, 2.5),
        v(-0.5, 0.5, 2.5),
    ];
    s.push(
        SceneLight::Polygon(PolygonLight::new(&quad).unwrap()),
        Rgb::from_f64([1.0, 0.8, 0.6]),
    )
    .unwrap();
    if all {
        for i in 0..14 {
            let a = i as f64 * 0.45;
            let (ca, sa) = (a.cos(), a.sin());
            let origin = v(3.0 * ca, 3.0 * sa, 1.0);
            let shape = if i % 2 == 0 {
                spot(origin, v(ca, sa, 0.0), 3.0)
            } else {
                spot(origin, v(-ca, -sa, -1.0 / 3.0), 1.0)
            };
            s.push_shaped(
                SceneLight::Point(PointLight::new(origin).unwrap()),
                white,
                shape,
            )
            .unwrap();
        }
    }
    s
}

struct Frame {
    verts: Vec<Vertex<T>>,
    tris: Vec<[u16; 3]>,
    camera: Camera<T>,
    material: Material<T>,
}

impl Frame {
    fn new() -> Self {
        let counts = mesh::uv_sphere_counts(16, 24);
        let zero = v(0.0, 0.0, 0.0);
        let mut verts = vec![Vertex::new(zero, zero); counts.vertices];
        let mut tris = vec![[0u16; 3]; counts.triangles];
        mesh::uv_sphere(1.0, 16, 24, &mut verts, &mut tris).unwrap();
        let camera = Camera::new(
            v(0.3, 1.2, 3.5),
            v(0.0, 0.0, 0.0),
            v(0.0, 1.0, 0.0),
            Projection::Perspective { fov_y: 0.7 },
            96,
            96,
        )
        .unwrap();
        let material =
            Material::new(Rgb::from_f64([0.8, 0.5, 0.3]), Rgb::from_f64([0.4; 3]), 16).unwrap();
        Frame {
            verts,
            tris,
            camera,
            material,
        }
    }

    fn render<L: Illuminant<T> + ?Sized>(&self, light: &L) -> u32 {
        let mesh = Mesh::new(&self.verts, &self.tris).unwrap();
        let mut px = vec![Rgb888::default(); 96 * 96];
        let mut depth = vec![u16::MAX; 96 * 96];
        let mut band = Band::new(&mut px, Some(&mut depth), 96, 0).unwrap();
        let stats = draw(
            &self.camera,
            &mut band,
            &mesh,
            &Affine::identity(),
            &Lit::new(light, &self.material),
            &DrawOptions::new(Shading::PerPixel),
        )
        .unwrap();
        stats.pixels
    }
}

fn benches(c: &mut Criterion) {
    let frame = Frame::new();
    let (sixteen, two) = (scene(true), scene(false));
    let sphere = ObjectBounds::sphere(v(0.0, 0.0, 0.0), 1.0f32).unwrap();
    let mut g = c.benchmark_group("scene");
    g.bench_function("16_lights_prepared", |b| {
        b.iter(|| {
            // prepare is part of the frame's cost.
            let lit = sixteen.prepare(black_box(&sphere), true);
            frame.render(&lit)
        })
    });
    g.bench_function("2_lights", |b| b.iter(|| frame.render(black_box(&two))));
    g.bench_function("16_lights_unprepared", |b| {
        b.iter(|| frame.render(black_box(&sixteen)))
    });
    // A cap of 0.3 rad from +x: the half of the sphere facing -x is dark.
    let side = CapLight::new(v(1.0, 0.0, 0.0), 0.3).unwrap();
    let front = CapLight::new(v(0.3, 1.2, 3.5), 0.3).unwrap();
    let in_scene = |cap: CapLight<T>| {
        let mut s: Scene<T, 1> = Scene::new();
        s.push(SceneLight::Cap(cap), Rgb::splat(1.0)).unwrap();
        s
    };
    let (half, full) = (in_scene(side), in_scene(front));
    g.bench_function("cap/half_lit", |b| {
        b.iter(|| frame.render(black_box(&half)))
    });
    g.bench_function("cap/fully_lit", |b| {
        b.iter(|| frame.render(black_box(&full)))
    });
    g.bench_function("cap/half_lit_model_only", |b| {
        b.iter(|| frame.render(black_box(&side)))
    });
    // The same with a 1 x 1 polygon light 2.5 from the centre: the dark half's samples are
    // rejected by the clipper's first pass over the vertices.
    let quad = |c: [f64; 3], e1: [f64; 3], e2: [f64; 3]| {
        let p = |a: f64, b: f64| {
            v(
                c[0] + a * e1[0] + b * e2[0],
                c[1] + a * e1[1] + b * e2[1],
                c[2] + a * e1[2] + b * e2[2],
            )
        };
        let mut s: Scene<T, 1> = Scene::new();
        let l =
            PolygonLight::new(&[p(-0.5, -0.5), p(0.5, -0.5), p(0.5, 0.5), p(-0.5, 0.5)]).unwrap();
        s.push(SceneLight::Polygon(l), Rgb::splat(1.0)).unwrap();
        s
    };
    let half = quad([2.5, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
    let full = quad([0.2, 0.8, 2.4], [1.0, 0.0, 0.0], [0.0, 0.95, -0.31]);
    g.bench_function("polygon/half_lit", |b| {
        b.iter(|| frame.render(black_box(&half)))
    });
    g.bench_function("polygon/fully_lit", |b| {
        b.iter(|| frame.render(black_box(&full)))
    });
    g.finish();
}

criterion_group! {
    name = scene_benches;
    config = Criterion::default().sample_size(20).warm_up_time(std::time::Duration::from_millis(300)).measurement_time(std::time::Duration::from_secs(2));
    targets = benches
}
criterion_main!(scene_benches);
