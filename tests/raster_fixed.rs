//! The rasterizer in fixed point ([`Fixed22`]) against f64: the same pixels on displays up to
//! 1024 x 1024, with vertices in the guard band (screen coordinates far beyond the type's
//! range of +-512), except for rounding ties (a vertex or a depth that rounds to the other
//! side of a pixel centre). The scenes are drawn with constant colours (an ambient light on
//! matte materials of colour 0 or 1 per channel), so a pixel differs only where coverage or
//! the depth test does.
#![cfg(all(feature = "raster", feature = "fixed"))]

use arealight::raster::{
    draw, mesh, Affine, Band, Camera, Cull, DrawOptions, EncodeTable, Encoding, Lit, Material,
    Mesh, PreparedMesh, PreparedVertex, Projection, RasterError, Rgb888, Shading, Vertex,
};
use arealight::{Ambient, Fixed22, Real, Rgb, Vec3};

type MeshVecs<T> = (Vec<Vertex<T>>, Vec<[u16; 3]>);

fn buffers<T: Real>(c: arealight::raster::MeshCounts) -> MeshVecs<T> {
    let z = Vertex::new(
        Vec3::new(T::ZERO, T::ZERO, T::ZERO),
        Vec3::new(T::ZERO, T::ZERO, T::ZERO),
    );
    (vec![z; c.vertices], vec![[0; 3]; c.triangles])
}

fn v<T: Real>(x: f64, y: f64, z: f64) -> Vec3<T> {
    Vec3::new(T::from_f64(x), T::from_f64(y), T::from_f64(z))
}

/// A small deterministic generator (xorshift).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    /// Uniform in `[lo, hi)`, on a grid of 2^-12 (exact in both types).
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        let steps = ((hi - lo) * 4096.0) as u64;
        lo + (self.next() % steps) as f64 / 4096.0
    }
}

/// The test camera: at `(0.5, 1.6, 3.5)` (inside Fixed22's coordinate range of +-4).
fn camera<T: Real>(w: u16, h: u16) -> Camera<T> {
    Camera::new(
        v(0.5, 1.6, 3.5),
        v(0.0, 0.2, 0.0),
        v(0.0, 1.0, 0.0),
        Projection::Perspective {
            fov_y: T::from_f64(0.9),
        },
        w,
        h,
    )
    .unwrap()
}

/// A mesh, its transform, material and draw options.
type Object<T> = (MeshVecs<T>, Affine<T>, Material<T>, DrawOptions<T>);

struct Scene<T> {
    meshes: Vec<Object<T>>,
}

/// A sphere, a torus, a box and a floor (crossing the near plane and the guard band), each
/// in one colour.
fn scene<T: Real>() -> Scene<T> {
    let k = T::from_f64;
    let mut sphere = buffers(mesh::uv_sphere_counts(10, 16));
    mesh::uv_sphere(k(0.8), 10, 16, &mut sphere.0, &mut sphere.1).unwrap();
    let mut torus = buffers(mesh::torus_counts(20, 10));
    mesh::torus(k(0.7), k(0.25), 20, 10, &mut torus.0, &mut torus.1).unwrap();
    let mut cube = buffers(mesh::cuboid_counts());
    mesh::cuboid(v(0.5, 0.4, 0.3), &mut cube.0, &mut cube.1).unwrap();
    let mut floor = buffers(mesh::plane_counts(6, 6));
    mesh::plane(k(7.0), k(7.0), 6, 6, &mut floor.0, &mut floor.1).unwrap();
    let colour = |r: f64, g: f64, b: f64| Material::matte(Rgb::new(k(r), k(g), k(b))).unwrap();
    let (gouraud, per_pixel) = (
        DrawOptions::new(Shading::Gouraud),
        DrawOptions::new(Shading::PerPixel),
    );
    Scene {
        meshes: vec![
            (
                floor,
                Affine::translation(v(0.0, -0.8, 0.0)).unwrap(),
                colour(1.0, 1.0, 1.0),
                gouraud,
            ),
            (sphere, Affine::identity(), colour(1.0, 0.0, 0.0), per_pixel),
            (
                torus,
                Affine::rotation(v(1.0, 0.0, 0.0), k(1.2))
                    .unwrap()
                    .then(&Affine::translation(v(1.3, 0.0, -0.5)).unwrap()),
                colour(0.0, 1.0, 0.0),
                gouraud,
            ),
            (
                cube,
                Affine::scale(v(1.0, 2.0, 1.0))
                    .unwrap()
                    .then(&Affine::translation(v(-1.4, 0.0, 0.3)).unwrap()),
                colour(0.0, 0.0, 1.0),
                per_pixel,
            ),
        ],
    }
}

/// Renders `scene` at `w` x `h` with `draw` or the prepared path.
fn render<T: Real>(s: &Scene<T>, cam: &Camera<T>, prepared: bool) -> Vec<Rgb888> {
    let (w, h) = (cam.width(), cam.height());
    let light = Ambient(Rgb::splat(T::ONE));
    let table = EncodeTable::new::<T>(Encoding::Linear);
    let mut px = vec![Rgb888::default(); w as usize * h as usize];
    let mut depth = vec![0u16; px.len()];
    let mut band = Band::new(&mut px, Some(&mut depth), w, 0).unwrap();
    band.clear(Rgb888::default());
    for (m, xf, mat, opts) in &s.meshes {
        let lit = Lit::new(&light, mat);
        let mesh = Mesh::new(&m.0, &m.1).unwrap();
        if prepared {
            let mut storage = vec![PreparedVertex::EMPTY; m.0.len()];
            let mut p = PreparedMesh::new(mesh, &mut storage).unwrap();
            p.transform(cam, xf);
            p.shade(cam, &lit, opts);
            p.draw(cam, &mut band, &lit, opts, &table).unwrap();
        } else {
            draw(cam, &mut band, &mesh, xf, &lit, opts).unwrap();
        }
    }
    px
}

fn differing(a: &[Rgb888], b: &[Rgb888]) -> usize {
    assert_eq!(a.len(), b.len());
    a.iter().zip(b).filter(|(p, q)| p != q).count()
}

/// The scene at `w` x `h` in Fixed22 and f64 through both paths: `(pixels differing, pixels
/// covered in f64)` per path.
fn compare_frames(w: u16, h: u16) -> [(usize, usize); 2] {
    let (s64, sfx) = (scene::<f64>(), scene::<Fixed22>());
    let (c64, cfx) = (camera::<f64>(w, h), camera::<Fixed22>(w, h));
    [false, true].map(|prepared| {
        let a = render(&s64, &c64, prepared);
        let b = render(&sfx, &cfx, prepared);
        let covered = a.iter().filter(|p| **p != Rgb888::default()).count();
        let d = differing(&a, &b);
        println!("{w}x{h} prepared={prepared}: {d} of {covered} covered pixels differ");
        (d, covered)
    })
}

// Measured (draw, prepared): 240 x 240 (0, 0) of 37682 covered pixels; 800 x 480 (1, 0) of
// 221794; 1024 x 1024 (1, 1) of 686034. Every differing pixel lies on the line where the box
// stands on the floor (its base at y = -0.8, the floor's plane): the two surfaces have the
// same depth there and the 16-bit depth test's tie goes either way. Before the viewport
// transform ran in sub-pixel integers, 172997 of the 221794 pixels differed at 800 x 480
// (every screen coordinate saturated at 512, and the aspect ratio with it) and 768431 at
// 1024 x 1024.

#[test]
fn fixed22_frames_equal_f64_at_240x240() {
    for (d, covered) in compare_frames(240, 240) {
        assert!(covered > 240 * 240 / 2, "{covered}");
        assert_eq!(d, 0);
    }
}

#[test]
fn fixed22_frames_equal_f64_at_800x480() {
    for (d, covered) in compare_frames(800, 480) {
        assert!(covered > 800 * 480 / 2, "{covered}");
        assert!(d <= 1, "{d}");
    }
}

#[test]
fn fixed22_frames_equal_f64_at_1024x1024() {
    for (d, covered) in compare_frames(1024, 1024) {
        assert!(covered > 1024 * 1024 / 2, "{covered}");
        assert!(d <= 1, "{d}");
    }
}

/// Random large triangles around the view (vertices up to 4 times the half-width beyond the
/// centre, and beyond the guard band, where they are clipped) at 240 x 240, one at a time.
/// Returns `(pixels differing, pixels covered in f64, vertices projected at x or y >= 512`
/// (beyond Fixed22's range: `Camera::project` refuses them in Fixed22; those inside the
/// guard band are drawn, the others clipped to it at 600)).
fn guard_band_triangles(w: u16, h: u16, count: usize) -> (usize, usize, usize) {
    let (c64, cfx) = (camera::<f64>(w, h), camera::<Fixed22>(w, h));
    let mut rng = Rng(0x2545_F491_4F6C_DD1D);
    let (mut d, mut covered, mut far_out) = (0, 0, 0);
    let opts64 = DrawOptions {
        cull: Cull::None,
        ..DrawOptions::new(Shading::Gouraud)
    };
    let optsfx = DrawOptions {
        cull: Cull::None,
        ..DrawOptions::new(Shading::Gouraud)
    };
    for _ in 0..count {
        let p: [[f64; 3]; 3] = core::array::from_fn(|_| {
            [
                rng.range(-3.9, 3.9),
                rng.range(-3.9, 3.9),
                rng.range(-3.9, 3.4),
            ]
        });
        for q in &p {
            if let Some((x, y)) = c64.project(v(q[0], q[1], q[2])) {
                if x >= 512.0 || y >= 512.0 {
                    far_out += 1;
                }
            }
        }
        let tri = |k: usize| Vertex::new(v(p[k][0], p[k][1], p[k][2]), v(0.0, 0.0, 1.0));
        let a = draw_one::<f64>(&c64, [tri(0), tri(1), tri(2)], &opts64);
        let tf = |k: usize| Vertex::new(v::<Fixed22>(p[k][0], p[k][1], p[k][2]), v(0.0, 0.0, 1.0));
        let b = draw_one::<Fixed22>(&cfx, [tf(0), tf(1), tf(2)], &optsfx);
        covered += a.iter().filter(|p| **p != Rgb888::default()).count();
        d += differing(&a, &b);
    }
    (d, covered, far_out)
}

fn draw_one<T: Real>(cam: &Camera<T>, verts: [Vertex<T>; 3], opts: &DrawOptions<T>) -> Vec<Rgb888> {
    let (w, h) = (cam.width(), cam.height());
    let mut px = vec![Rgb888::default(); w as usize * h as usize];
    let mut band = Band::new(&mut px, None, w, 0).unwrap();
    band.clear(Rgb888::default());
    let tris = [[0u16, 1, 2]];
    let mesh = Mesh::new(&verts, &tris).unwrap();
    let light = Ambient(Rgb::splat(T::ONE));
    let white = Material::matte(Rgb::splat(T::ONE)).unwrap();
    draw(
        cam,
        &mut band,
        &mesh,
        &Affine::identity(),
        &Lit::new(&light, &white),
        opts,
    )
    .unwrap();
    px
}

// Measured: 4 of 3300257 covered pixels differ (pixel centres within a sub-pixel rounding of
// an edge whose vertex Fixed22 snaps to the neighbouring 1/16 pixel), with 74 of the 900
// vertices projecting at 512 or beyond. Before the viewport transform ran in
// sub-pixel integers, 84351 pixels differed (screen coordinates clamped at 512).
#[test]
fn fixed22_guard_band_triangles_equal_f64_at_240x240() {
    let (d, covered, far_out) = guard_band_triangles(240, 240, 300);
    println!("240x240 guard band: {d} of {covered} pixels differ; {far_out} vertices beyond 512");
    assert!(far_out > 60, "{far_out}");
    assert!(d <= 4, "{d}");
}

/// `Camera::project` in Fixed22: the f64 pixel coordinates to the type's rounding where they
/// fit its range, `None` at 512 and beyond (before: clamped at 512, silently).
#[test]
fn fixed22_project_refuses_coordinates_beyond_its_range() {
    let (c64, cfx) = (camera::<f64>(800, 480), camera::<Fixed22>(800, 480));
    let (mut inside, mut refused, mut max_err) = (0, 0, 0.0f64);
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for _ in 0..2000 {
        let p = [
            rng.range(-3.9, 3.9),
            rng.range(-3.9, 3.9),
            rng.range(-3.9, 3.0),
        ];
        let (Some((x, y)), q) = (
            c64.project(v(p[0], p[1], p[2])),
            cfx.project(v(p[0], p[1], p[2])),
        ) else {
            continue;
        };
        if x.abs() < 511.0 && y.abs() < 511.0 {
            let (xf, yf) = q.unwrap();
            max_err = max_err
                .max((xf.to_f64() - x).abs())
                .max((yf.to_f64() - y).abs());
            // Fixed22's clip coordinates carry ~2^-22 relative to the point's distance, times
            // up to 400 pixels: measured max 3.75e-4 pixels (5.6e-4 while the clip transform
            // floored its products, 7.3e-4 with its axes normalized more accurately then).
            assert!((xf.to_f64() - x).abs() < 5e-4, "{x} {xf:?} p={p:?}");
            assert!((yf.to_f64() - y).abs() < 5e-4, "{y} {yf:?} p={p:?}");
            inside += 1;
        } else if x.abs() > 513.0 || y.abs() > 513.0 {
            assert_eq!(q, None, "{x} {y}");
            refused += 1;
        }
    }
    println!("project: {inside} inside (max error {max_err:.2e} pixels), {refused} refused");
    assert!(inside > 500 && refused > 100, "{inside} {refused}");
}

/// The largest coordinate difference between two vertex lists (positions and normals).
fn max_vertex_error(a: &[Vertex<f64>], b: &[Vertex<Fixed22>]) -> f64 {
    let d = |p: Vec3<f64>, q: Vec3<Fixed22>| {
        (p.x - q.x.to_f64())
            .abs()
            .max((p.y - q.y.to_f64()).abs())
            .max((p.z - q.z.to_f64()).abs())
    };
    a.iter()
        .zip(b)
        .map(|(p, q)| d(p.position, q.position).max(d(p.normal, q.normal)))
        .fold(0.0, f64::max)
}

/// Mesh generators with 512 segments and more (up to 600) in Fixed22: the vertices of f64 to
/// the type's rounding (measured max 9.3e-7, 4 units of 2^-22, on the sphere 100 x 600). Before,
/// `from_u32(n)` saturated at 512 (and `2 pi k` at `k = 82`), so a sphere of 100 slices
/// wrapped only part of the way round: errors of 0.29 to 2.8 on all but the plane 100 x 7.
#[test]
fn fixed22_meshes_with_many_segments_match_f64() {
    let mut errors = Vec::new();
    for (nx, nz) in [(600u16, 2u16), (3, 600), (100, 7)] {
        let (mut a, mut ta) = buffers::<f64>(mesh::plane_counts(nx, nz));
        let (mut b, mut tb) = buffers::<Fixed22>(mesh::plane_counts(nx, nz));
        mesh::plane(3.0, 2.0, nx, nz, &mut a, &mut ta).unwrap();
        mesh::plane(
            Fixed22::from_f64(3.0),
            Fixed22::from_f64(2.0),
            nx,
            nz,
            &mut b,
            &mut tb,
        )
        .unwrap();
        assert_eq!(ta, tb);
        errors.push(("plane", nx, nz, max_vertex_error(&a, &b)));
    }
    for (stacks, slices) in [(100u16, 600u16), (600, 20), (8, 100)] {
        let (mut a, mut ta) = buffers::<f64>(mesh::uv_sphere_counts(stacks, slices));
        let (mut b, mut tb) = buffers::<Fixed22>(mesh::uv_sphere_counts(stacks, slices));
        mesh::uv_sphere(1.5, stacks, slices, &mut a, &mut ta).unwrap();
        mesh::uv_sphere(Fixed22::from_f64(1.5), stacks, slices, &mut b, &mut tb).unwrap();
        errors.push(("uv_sphere", stacks, slices, max_vertex_error(&a, &b)));
    }
    for (major, minor) in [(600u16, 50u16), (40, 600)] {
        let (mut a, mut ta) = buffers::<f64>(mesh::torus_counts(major, minor));
        let (mut b, mut tb) = buffers::<Fixed22>(mesh::torus_counts(major, minor));
        mesh::torus(1.0, 0.3, major, minor, &mut a, &mut ta).unwrap();
        let k = Fixed22::from_f64;
        mesh::torus(k(1.0), k(0.3), major, minor, &mut b, &mut tb).unwrap();
        errors.push(("torus", major, minor, max_vertex_error(&a, &b)));
    }
    for (what, n, m, e) in &errors {
        println!("{what} {n} x {m}: max vertex error {e:.2e}");
    }
    for (what, n, m, e) in &errors {
        assert!(*e < 1e-6, "{what} {n} x {m}: {e}");
    }
}

/// The float backends compute the mesh angles as `2 pi k / n` in the type (two roundings),
/// bit for bit as before the power-of-two scaling, at any segment count.
#[test]
fn float_mesh_angles_are_unchanged() {
    fn check<T: Real>(slices: u16) {
        let (mut a, mut ta) = buffers::<T>(mesh::uv_sphere_counts(2, slices));
        mesh::uv_sphere(T::ONE, 2, slices, &mut a, &mut ta).unwrap();
        // Ring 1 (the equator) is row `slices + 1 .. 2 (slices + 1)`: x = sin(pi/2) sin(a).
        let (_, s1) = {
            let t = T::PI * T::from_u32(1) / T::from_u32(2);
            (t.cos(), t.sin())
        };
        for j in 0..=slices as usize {
            let ang = T::TAU * T::from_u32(j as u32) / T::from_u32(slices as u32);
            let p = a[(slices as usize + 1) + j].position;
            assert_eq!(p.x.to_f64(), (s1 * ang.sin()).to_f64(), "{slices} {j}");
        }
    }
    for n in [3, 63, 64, 100, 600, 4000] {
        check::<f32>(n);
        check::<f64>(n);
        check::<arealight::Fast32>(n);
    }
}

/// Out-of-range camera positions and translations in Fixed22 are refused with
/// `Error::OutOfRange` instead of drawing a wrong frame (an eye at z = 5 used to render
/// without an error, its clip coordinates and shading points beyond the range the type and
/// the lights handle); the float types accept the same values. `Camera::project` answers
/// `None` for a point beyond the range.
#[test]
fn fixed22_refuses_positions_beyond_the_coordinate_limit() {
    use arealight::Error;
    let out = |what| Some(RasterError::Model(Error::OutOfRange(what)));
    let cam = |eye: [f64; 3], target: [f64; 3]| {
        Camera::<Fixed22>::new(
            v(eye[0], eye[1], eye[2]),
            v(target[0], target[1], target[2]),
            v(0.0, 1.0, 0.0),
            Projection::Perspective {
                fov_y: Fixed22::from_f64(0.9),
            },
            240,
            240,
        )
    };
    assert_eq!(cam([0.0, 0.0, 5.0], [0.0; 3]).err(), out("eye"));
    assert_eq!(cam([0.0, 0.0, -4.01], [0.0; 3]).err(), out("eye"));
    assert_eq!(cam([0.0, 0.0, 3.0], [0.0, 4.5, 0.0]).err(), out("target"));
    assert!(cam([0.0, 0.0, 4.0], [0.0, -4.0, 0.0]).is_ok());
    let cam64 = Camera::<f64>::new(
        v(0.0, 0.0, 5.0),
        v(0.0, 0.0, -100.0),
        v(0.0, 1.0, 0.0),
        Projection::Perspective { fov_y: 0.9 },
        240,
        240,
    );
    assert!(cam64.is_ok());
    assert_eq!(
        Affine::translation(v::<Fixed22>(0.0, 0.0, 4.5)).err(),
        out("t")
    );
    assert!(Affine::translation(v::<f32>(0.0, 0.0, 4.5)).is_ok());
    assert!(Affine::translation(v::<Fixed22>(-4.0, 4.0, 0.0)).is_ok());
    let c = camera::<Fixed22>(240, 240);
    assert!(c.project(v(0.0, 0.0, -4.0)).is_some());
    assert_eq!(c.project(v(0.0, 0.0, -4.5)), None);
    assert!(camera::<f64>(240, 240).project(v(0.0, 0.0, -4.5)).is_some());
}

/// A mesh whose transformed vertices leave Fixed22's coordinate range (a plane 3 units wide,
/// corners at 1.5, scaled by 3: corners at 4.5) is refused by `PreparedMesh::draw` with `Error::OutOfRange("vertex")`
/// and draws nothing, until a transform brings it back in range; f32 draws the same mesh.
#[test]
fn fixed22_prepared_mesh_refuses_vertices_beyond_the_coordinate_limit() {
    use arealight::raster::{
        Band, Cull, EncodeTable, Encoding, Mesh, PreparedMesh, PreparedVertex, Rgb565, Shader,
        Shading,
    };
    use arealight::{Error, Rgb, UnitVec3};
    struct White;
    impl<T: Real> Shader<T> for White {
        fn shade(&self, _p: Vec3<T>, _n: UnitVec3<T>, _v: UnitVec3<T>) -> Rgb<T> {
            Rgb::splat(T::ONE)
        }
    }
    fn attempt<T: Real>(scale: f64) -> Result<u32, RasterError> {
        let c = mesh::plane_counts(2, 2);
        let (mut verts, mut tris) = (
            vec![Vertex::new(v(0.0, 0.0, 0.0), v(0.0, 1.0, 0.0)); c.vertices],
            vec![[0u16; 3]; c.triangles],
        );
        mesh::plane(
            T::from_f64(3.0),
            T::from_f64(3.0),
            2,
            2,
            &mut verts,
            &mut tris,
        )?;
        let m = Mesh::new(&verts, &tris)?;
        let mut store = vec![PreparedVertex::EMPTY; c.vertices];
        let mut p = PreparedMesh::new(m, &mut store)?;
        let cam = camera::<T>(64, 64);
        let xf =
            Affine::scale(v(scale, 1.0, scale))?.then(&Affine::translation(v(0.0, -0.8, 0.0))?);
        let mut opts = DrawOptions::new(Shading::Gouraud);
        opts.cull = Cull::None;
        p.transform(&cam, &xf);
        p.shade(&cam, &White, &opts);
        let table = EncodeTable::new::<T>(Encoding::Linear);
        let (mut px, mut depth) = (vec![Rgb565(0); 64 * 64], vec![0u16; 64 * 64]);
        let mut band = Band::new(&mut px, Some(&mut depth), 64, 0)?;
        band.clear(Rgb565(0));
        let s = p.draw(&cam, &mut band, &White, &opts, &table)?;
        // Nothing drawn on a refusal: checked by the caller through the error.
        Ok(s.pixels)
    }
    assert_eq!(
        attempt::<Fixed22>(3.0).err(),
        Some(RasterError::Model(Error::OutOfRange("vertex")))
    );
    assert!(attempt::<f32>(1.5).unwrap() > 0);
    // In range (corners at 3): drawn as in f32.
    assert_eq!(
        attempt::<Fixed22>(1.0).unwrap(),
        attempt::<f32>(1.0).unwrap()
    );
}
