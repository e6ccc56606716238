//! The rasterizer: exact coverage (exhaustive on small grids), band rendering equal to
//! full-frame rendering bit for bit, analytic pixel values, depth, culling, clipping, meshes.
#![cfg(feature = "raster")]

use arealight::raster::edge::{edge_function, SUBPIXEL};
use arealight::raster::{
    draw, mesh, Affine, Band, Camera, Cull, DrawOptions, EdgeTriangle, Encoding, FixedPoint, Lit,
    Material, Mesh, PixelFormat, Projection, RasterError, Rgb565, Rgb888, Shading, Vertex,
};
use arealight::{
    HemisphereLight, PhongLobe, PolygonLight, Real, Rgb, SkyGround, SphereLight, Vec3,
};

mod coverage;

/// A small deterministic generator.
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> u32 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 33) as u32
    }
    fn range(&mut self, n: i32) -> i32 {
        (self.next() % n as u32) as i32
    }
}

// ---------------------------------------------------------------------------------------
// A scene for the pipeline tests.

struct Meshes<T> {
    sphere: (Vec<Vertex<T>>, Vec<[u16; 3]>),
    torus: (Vec<Vertex<T>>, Vec<[u16; 3]>),
    cube: (Vec<Vertex<T>>, Vec<[u16; 3]>),
    floor: (Vec<Vertex<T>>, Vec<[u16; 3]>),
}

fn buffers<T: Real>(c: arealight::raster::MeshCounts) -> (Vec<Vertex<T>>, Vec<[u16; 3]>) {
    let z = Vertex::new(
        Vec3::new(T::ZERO, T::ZERO, T::ZERO),
        Vec3::new(T::ZERO, T::ZERO, T::ZERO),
    );
    (vec![z; c.vertices], vec![[0; 3]; c.triangles])
}

fn meshes<T: Real>() -> Meshes<T> {
    let k = T::from_f64;
    let mut sphere = buffers(mesh::uv_sphere_counts(10, 16));
    mesh::uv_sphere(k(0.8), 10, 16, &mut sphere.0, &mut sphere.1).unwrap();
    let mut torus = buffers(mesh::torus_counts(20, 10));
    mesh::torus(k(0.7), k(0.25), 20, 10, &mut torus.0, &mut torus.1).unwrap();
    let mut cube = buffers(mesh::cuboid_counts());
    mesh::cuboid(Vec3::new(k(0.5), k(0.4), k(0.3)), &mut cube.0, &mut cube.1).unwrap();
    let mut floor = buffers(mesh::plane_counts(6, 6));
    // Large enough to cross the near plane and the guard band.
    mesh::plane(k(200.0), k(200.0), 6, 6, &mut floor.0, &mut floor.1).unwrap();
    Meshes {
        sphere,
        torus,
        cube,
        floor,
    }
}

fn camera<T: Real>(w: u16, h: u16) -> Camera<T> {
    let k = T::from_f64;
    Camera::new(
        Vec3::new(k(0.5), k(1.6), k(4.5)),
        Vec3::new(k(0.0), k(0.2), k(0.0)),
        Vec3::new(k(0.0), k(1.0), k(0.0)),
        Projection::Perspective { fov_y: k(0.9) },
        w,
        h,
    )
    .unwrap()
}

type MeshVecs<T> = (Vec<Vertex<T>>, Vec<[u16; 3]>);
type Draw<'a, T> = (
    &'a MeshVecs<T>,
    Affine<T>,
    &'a Material<T>,
    &'a DrawOptions<T>,
);

/// Draws the scene into `band` with both shading modes on different objects.
fn draw_scene<T: Real, P: PixelFormat>(band: &mut Band<'_, P>, m: &Meshes<T>, cam: &Camera<T>) {
    let k = T::from_f64;
    let v = |x: f64, y: f64, z: f64| Vec3::new(k(x), k(y), k(z));
    let panel = PolygonLight::<T, 4>::new(&[
        v(-1.0, 3.0, -1.0),
        v(1.0, 3.0, -1.0),
        v(1.0, 3.0, 1.0),
        v(-1.0, 3.0, 1.0),
    ])
    .unwrap();
    let lamp = SphereLight::new(v(2.0, 2.0, 2.0), k(0.4)).unwrap();
    let sky = SkyGround::new(
        v(0.0, 1.0, 0.0),
        Rgb::new(k(0.1), k(0.1), k(0.2)),
        Rgb::new(k(0.05), k(0.04), k(0.0)),
    )
    .unwrap();
    let lights: [&dyn arealight::Illuminant<T>; 3] = [&panel, &lamp, &sky];
    let red = Material::new(Rgb::new(k(0.9), k(0.2), k(0.1)), Rgb::splat(k(0.5)), 20).unwrap();
    let grey = Material::matte(Rgb::splat(k(0.7))).unwrap();
    let mut gouraud = DrawOptions::new(Shading::Gouraud);
    let per_pixel = DrawOptions::new(Shading::PerPixel);
    gouraud.exposure = k(1.5);
    let draws: [Draw<'_, T>; 4] = [
        (
            &m.floor,
            Affine::translation(v(0.0, -0.8, 0.0)).unwrap(),
            &grey,
            &gouraud,
        ),
        (&m.sphere, Affine::identity(), &red, &per_pixel),
        (
            &m.torus,
            Affine::rotation(v(1.0, 0.0, 0.0), k(1.2))
                .unwrap()
                .then(&Affine::translation(v(1.3, 0.0, -0.5)).unwrap()),
            &red,
            &gouraud,
        ),
        (
            &m.cube,
            Affine::scale(v(1.0, 2.0, 1.0))
                .unwrap()
                .then(&Affine::translation(v(-1.4, 0.0, 0.3)).unwrap()),
            &grey,
            &per_pixel,
        ),
    ];
    for (mesh, xf, mat, opts) in draws {
        let mesh = Mesh::new(&mesh.0, &mesh.1).unwrap();
        draw(cam, band, &mesh, &xf, &Lit::new(&lights, mat), opts).unwrap();
    }
}

fn render_full<T: Real, P: PixelFormat + Default>(w: u16, h: u16) -> (Vec<P>, Vec<u16>) {
    let (m, cam) = (meshes::<T>(), camera::<T>(w, h));
    let mut px = vec![P::default(); w as usize * h as usize];
    let mut depth = vec![0u16; px.len()];
    let mut band = Band::new(&mut px, Some(&mut depth), w, 0).unwrap();
    band.clear(P::default());
    draw_scene(&mut band, &m, &cam);
    (px, depth)
}

fn render_banded<T: Real, P: PixelFormat + Default>(
    w: u16,
    h: u16,
    rows: u16,
) -> (Vec<P>, Vec<u16>) {
    let (m, cam) = (meshes::<T>(), camera::<T>(w, h));
    let (mut out, mut out_depth) = (Vec::new(), Vec::new());
    let mut px = vec![P::default(); w as usize * rows as usize];
    let mut depth = vec![0u16; px.len()];
    let mut band = Band::new(&mut px, Some(&mut depth), w, 0).unwrap();
    arealight::raster::render_in_bands::<_, (), _, _>(
        &mut band,
        h,
        P::default(),
        |b| {
            draw_scene(b, &m, &cam);
            Ok(())
        },
        |b| {
            // The last band may run past the frame: keep only the frame's rows.
            let keep = (h - b.y0()).min(b.rows()) as usize * w as usize;
            out.extend_from_slice(&b.pixels()[..keep]);
            out_depth.extend_from_slice(&b.depth().unwrap()[..keep]);
            Ok(())
        },
    )
    .unwrap();
    (out, out_depth)
}

fn bands_equal_full<T: Real, P: PixelFormat + Default + PartialEq + core::fmt::Debug>() {
    let (w, h) = (96, 72);
    let (full, full_depth) = render_full::<T, P>(w, h);
    // The scene covers a good part of the frame, with depth-tested overlaps.
    let drawn = full_depth.iter().filter(|&&d| d != u16::MAX).count();
    assert!(drawn > (w as usize * h as usize) / 2, "{drawn}");
    for rows in [1, 7, 16, 72] {
        let (banded, banded_depth) = render_banded::<T, P>(w, h, rows);
        assert_eq!(banded.len(), full.len());
        let diff = full.iter().zip(&banded).filter(|(a, b)| a != b).count();
        assert_eq!(
            diff, 0,
            "{rows}-row bands differ from the full frame in {diff} pixels"
        );
        assert_eq!(banded_depth, full_depth, "{rows}-row bands: depth differs");
    }
}

/// Bands drawn into two pixel buffers in turn, as a firmware that hands each finished buffer
/// to a DMA transfer whole while the next band is drawn into the other (`Band::replace_pixels`:
/// the finished buffer out, the one sent before it back), give the frame drawn through one
/// buffer, bit for bit; a buffer of another length is handed back untouched and the band keeps
/// its own.
#[test]
fn bands_drawn_through_swapped_buffers_equal_the_full_frame() {
    let (w, h, rows) = (96u16, 72u16, 16u16);
    let (full, _) = render_full::<f32, Rgb565>(w, h);
    let (m, cam) = (meshes::<f32>(), camera::<f32>(w, h));
    let n = w as usize * rows as usize;
    // Different garbage in each buffer: a band must not depend on what its buffer held.
    let (mut a, mut b) = (vec![Rgb565(0x1234); n], vec![Rgb565(0xBEEF); n]);
    let mut depth = vec![7u16; n];
    let mut band = Band::new(&mut a, Some(&mut depth), w, 0).unwrap();
    let mut sent: &mut [Rgb565] = &mut b;
    let mut frame = Vec::new();
    let mut y0 = 0;
    while y0 < h {
        band.move_to(y0);
        band.clear(Rgb565::default());
        draw_scene(&mut band, &m, &cam);
        let before = band.pixels().to_vec();
        let drawn = band.replace_pixels(sent).unwrap();
        assert_eq!(drawn, &before[..]);
        let keep = (h - y0).min(rows) as usize * w as usize;
        frame.extend_from_slice(&drawn[..keep]);
        sent = drawn;
        y0 += rows;
    }
    assert_eq!(frame.len(), full.len());
    assert_eq!(frame, full);
    assert!(full.iter().filter(|&&p| p != Rgb565::default()).count() > full.len() / 2);

    let (mut own, mut short) = (vec![Rgb565(3); n], vec![Rgb565(5); n - 1]);
    let mut band = Band::new(&mut own, None, w, 0).unwrap();
    let back = band.replace_pixels(&mut short).unwrap_err();
    assert_eq!(back, &vec![Rgb565(5); n - 1][..]);
    assert_eq!(band.pixels(), &vec![Rgb565(3); n][..]);
}

/// With the `bytemuck` feature the pixel formats are plain words: a band's RGB565 pixels are
/// the `u16`s a DMA channel sends, the same bits.
#[cfg(feature = "bytemuck")]
#[test]
fn pixels_cast_to_words_and_back() {
    let mut px = [Rgb565::new(31, 0, 0), Rgb565::new(0, 63, 0), Rgb565(0xABCD)];
    let words: &mut [u16] = bytemuck::cast_slice_mut(&mut px);
    assert_eq!(words, &[0xF800, 0x07E0, 0xABCD]);
    words[0] = 0x001F;
    assert_eq!(px[0], Rgb565::new(0, 0, 31));
    let rgb = [Rgb888([1, 2, 3]), Rgb888([4, 5, 6])];
    assert_eq!(
        bytemuck::cast_slice::<Rgb888, u8>(&rgb),
        &[1, 2, 3, 4, 5, 6]
    );
}

#[test]
fn band_rendering_equals_full_frame_f32_rgb565() {
    bands_equal_full::<f32, Rgb565>();
}

#[test]
fn band_rendering_equals_full_frame_f64_rgb888() {
    bands_equal_full::<f64, Rgb888>();
}

#[test]
fn band_rendering_equals_full_frame_fast32_rgb565() {
    bands_equal_full::<arealight::Fast32, Rgb565>();
}

/// An orthographic view straight down on a plane tilted about z by `tilt`.
fn tilted_plane_pixels(tilt: f64, shading: Shading) -> (Vec<Rgb888>, f64) {
    let v = |x: f64, y: f64, z: f64| Vec3::<f64>::new(x, y, z);
    let cam = Camera::new(
        v(0.0, 5.0, 0.0),
        v(0.0, 0.0, 0.0),
        v(0.0, 0.0, -1.0),
        Projection::Orthographic { half_height: 1.0 },
        32,
        32,
    )
    .unwrap();
    let (mut verts, mut tris) = buffers::<f64>(mesh::plane_counts(3, 3));
    mesh::plane(4.0, 4.0, 3, 3, &mut verts, &mut tris).unwrap();
    let mesh = Mesh::new(&verts, &tris).unwrap();
    let xf = Affine::rotation(v(0.0, 0.0, 1.0), tilt).unwrap();
    let light = HemisphereLight::new(v(0.3, 1.0, 0.2)).unwrap();
    let white = Material::matte(Rgb::splat(1.0)).unwrap();
    let mut opts = DrawOptions::new(shading);
    opts.encoding = Encoding::Linear;
    let mut px = vec![Rgb888([1, 2, 3]); 32 * 32];
    let mut band = Band::new(&mut px, None, 32, 0).unwrap();
    draw(
        &cam,
        &mut band,
        &mesh,
        &xf,
        &Lit::new(&light, &white),
        &opts,
    )
    .unwrap();
    // The plane's normal after the rotation, and hemi_const = (1 + n.axis)/2.
    let n = v(-tilt.sin(), tilt.cos(), 0.0);
    let axis = v(0.3, 1.0, 0.2).normalize().unwrap();
    (px, 0.5 * (1.0 + n.dot(axis)))
}

#[test]
fn flat_surfaces_get_the_model_value_in_every_pixel() {
    for shading in [Shading::Gouraud, Shading::PerPixel] {
        for tilt in [0.0, 0.4, -0.9] {
            let (px, e) = tilted_plane_pixels(tilt, shading);
            let q = (e * 255.0 + 0.5).floor() as u8;
            assert!(
                px.iter().all(|p| p.0 == [q, q, q]),
                "tilt {tilt} {shading:?}: expected {q}, got {:?}",
                px.iter().find(|p| p.0 != [q, q, q])
            );
        }
    }
}

#[test]
fn nearer_surface_wins_in_either_order() {
    let v = |x: f64, y: f64, z: f64| Vec3::<f32>::from_f64([x, y, z]);
    let cam = Camera::new(
        v(0.0, 0.0, 5.0),
        v(0.0, 0.0, 0.0),
        v(0.0, 1.0, 0.0),
        Projection::Perspective { fov_y: 0.8 },
        24,
        24,
    )
    .unwrap();
    let (mut verts, mut tris) = buffers::<f32>(mesh::plane_counts(1, 1));
    mesh::plane(3.0, 3.0, 1, 1, &mut verts, &mut tris).unwrap();
    let mesh = Mesh::new(&verts, &tris).unwrap();
    // The plane faces +y; turn it to face the camera (+z), at z = 0 and z = 1.
    let face = Affine::rotation(v(1.0, 0.0, 0.0), core::f32::consts::FRAC_PI_2).unwrap();
    let far = face.then(&Affine::translation(v(0.3, 0.0, 0.0)).unwrap());
    let near = face.then(&Affine::translation(v(-0.3, 0.0, 1.0)).unwrap());
    let light = arealight::Ambient(Rgb::splat(1.0f32));
    let (red, blue) = (
        Material::matte(Rgb::new(1.0, 0.0, 0.0)).unwrap(),
        Material::matte(Rgb::new(0.0, 0.0, 1.0)).unwrap(),
    );
    let opts = DrawOptions::new(Shading::Gouraud);
    let mut results = Vec::new();
    for order in [
        [(&far, &red), (&near, &blue)],
        [(&near, &blue), (&far, &red)],
    ] {
        let mut px = vec![Rgb565(0); 24 * 24];
        let mut depth = vec![0u16; 24 * 24];
        let mut band = Band::new(&mut px, Some(&mut depth), 24, 0).unwrap();
        band.clear(Rgb565(0));
        for (xf, mat) in order {
            draw(&cam, &mut band, &mesh, xf, &Lit::new(&light, mat), &opts).unwrap();
        }
        results.push(px);
    }
    assert_eq!(results[0], results[1]);
    let px = &results[0];
    // The centre is covered by both: the near (blue) one shows.
    assert_eq!(px[12 * 24 + 12], Rgb565::new(0, 0, 31));
    // Both colours appear.
    assert!(px.contains(&Rgb565::new(31, 0, 0)));
}

#[test]
fn back_faces_are_culled_unless_asked() {
    let v = |x: f64, y: f64, z: f64| Vec3::<f32>::from_f64([x, y, z]);
    let cam = Camera::new(
        v(0.0, 4.0, 0.0),
        v(0.0, 0.0, 0.0),
        v(0.0, 0.0, -1.0),
        Projection::Orthographic { half_height: 2.0 },
        16,
        16,
    )
    .unwrap();
    let (mut verts, mut tris) = buffers::<f32>(mesh::plane_counts(2, 2));
    mesh::plane(2.0, 2.0, 2, 2, &mut verts, &mut tris).unwrap();
    let flipped: Vec<[u16; 3]> = tris.iter().map(|t| [t[0], t[2], t[1]]).collect();
    let light = arealight::Ambient(Rgb::splat(1.0f32));
    let white = Material::matte(Rgb::splat(1.0)).unwrap();
    let count = |tris: &[[u16; 3]], cull: Cull| {
        let mesh = Mesh::new(&verts, tris).unwrap();
        let mut px = vec![Rgb565(0); 256];
        let mut band = Band::new(&mut px, None, 16, 0).unwrap();
        let mut opts = DrawOptions::new(Shading::Gouraud);
        opts.cull = cull;
        let s = draw(
            &cam,
            &mut band,
            &mesh,
            &Affine::identity(),
            &Lit::new(&light, &white),
            &opts,
        )
        .unwrap();
        (s.pixels, px.iter().filter(|p| p.0 != 0).count() as u32)
    };
    // A 2x2 plane seen from above in a 4x4 view of 16 px: an 8x8 square.
    assert_eq!(count(&tris, Cull::Back), (64, 64));
    assert_eq!(count(&flipped, Cull::Back), (0, 0));
    assert_eq!(count(&flipped, Cull::None), (64, 64));
}

#[test]
fn a_plane_to_the_horizon_is_clipped_without_holes() {
    // The camera stands on a huge floor looking slightly down: the floor crosses the near plane
    // and the guard band; every pixel below the horizon is drawn once.
    let v = |x: f64, y: f64, z: f64| Vec3::<f32>::from_f64([x, y, z]);
    let cam = Camera::new(
        v(0.0, 1.0, 0.0),
        v(0.0, 0.6, -4.0),
        v(0.0, 1.0, 0.0),
        Projection::Perspective { fov_y: 1.2 },
        40,
        30,
    )
    .unwrap()
    .with_depth_range(0.05, 1.0e4)
    .unwrap();
    let (mut verts, mut tris) = buffers::<f32>(mesh::plane_counts(1, 1));
    mesh::plane(2.0e4, 2.0e4, 1, 1, &mut verts, &mut tris).unwrap();
    let mesh = Mesh::new(&verts, &tris).unwrap();
    let light = arealight::Ambient(Rgb::splat(1.0f32));
    let white = Material::matte(Rgb::splat(1.0)).unwrap();
    let mut px = vec![Rgb565(0); 40 * 30];
    let mut band = Band::new(&mut px, None, 40, 0).unwrap();
    let opts = DrawOptions::new(Shading::Gouraud);
    let s = draw(
        &cam,
        &mut band,
        &mesh,
        &Affine::identity(),
        &Lit::new(&light, &white),
        &opts,
    )
    .unwrap();
    assert!(s.rasterized > 2, "the floor was clipped into a fan: {s:?}");
    for y in 0..30 {
        let row: Vec<bool> = (0..40).map(|x| px[y * 40 + x].0 != 0).collect();
        // Each row is all floor or all sky.
        assert!(row.iter().all(|&b| b == row[0]), "row {y}: {row:?}");
    }
    assert!(px[29 * 40].0 != 0 && px[0].0 == 0);
    assert_eq!(s.pixels as usize, px.iter().filter(|p| p.0 != 0).count());
}

#[test]
fn mesh_generators_wind_with_their_normals() {
    type M = (Vec<Vertex<f64>>, Vec<[u16; 3]>);
    let mut s: M = buffers(mesh::uv_sphere_counts(7, 9));
    let c1 = mesh::uv_sphere(1.3, 7, 9, &mut s.0, &mut s.1).unwrap();
    let mut p: M = buffers(mesh::plane_counts(3, 5));
    let c2 = mesh::plane(2.0, 1.0, 3, 5, &mut p.0, &mut p.1).unwrap();
    let mut b: M = buffers(mesh::cuboid_counts());
    let c3 = mesh::cuboid(Vec3::new(1.0, 2.0, 3.0), &mut b.0, &mut b.1).unwrap();
    let mut t: M = buffers(mesh::torus_counts(12, 8));
    let c4 = mesh::torus(2.0, 0.5, 12, 8, &mut t.0, &mut t.1).unwrap();
    assert_eq!((c1.vertices, c1.triangles), (80, 2 * 9 * 6));
    assert_eq!((c2.vertices, c2.triangles), (24, 30));
    assert_eq!((c3.vertices, c3.triangles), (24, 12));
    assert_eq!((c4.vertices, c4.triangles), (117, 192));
    for (m, c) in [(&s, c1), (&p, c2), (&b, c3), (&t, c4)] {
        assert_eq!(m.1.len(), c.triangles);
        for v in &m.0 {
            assert!((v.normal.length() - 1.0).abs() < 1e-12);
        }
        for tri in &m.1 {
            let [a, b, c] = tri.map(|i| m.0[i as usize]);
            let g = (b.position - a.position).cross(c.position - a.position);
            assert!(g.length() > 1e-9, "degenerate triangle {tri:?}");
            for v in [a, b, c] {
                assert!(
                    g.dot(v.normal) > 0.0,
                    "triangle {tri:?} winds against its normals"
                );
            }
        }
    }
    // Sphere vertices are on the sphere; the torus's at distance `minor` from its core circle.
    for v in &s.0 {
        assert!((v.position.length() - 1.3).abs() < 1e-12);
    }
    for v in &t.0 {
        let q = v.position;
        let core = (q.x * q.x + q.z * q.z).sqrt() - 2.0;
        assert!((core.hypot(q.y) - 0.5).abs() < 1e-12);
    }
}

#[test]
fn mesh_generators_refuse_small_buffers_and_bad_parameters() {
    let z = Vertex::new(Vec3::new(0.0f32, 0.0, 0.0), Vec3::new(0.0, 0.0, 0.0));
    let (mut v, mut t) = (vec![z; 10], vec![[0u16; 3]; 10]);
    assert_eq!(
        mesh::uv_sphere(1.0, 4, 4, &mut v, &mut t),
        Err(RasterError::BufferTooSmall {
            what: "vertices",
            needed: 25,
            got: 10
        })
    );
    let (mut v2, mut t2) = (vec![z; 24], vec![[0u16; 3]; 11]);
    assert_eq!(
        mesh::cuboid(Vec3::new(1.0, 1.0, 1.0), &mut v2, &mut t2),
        Err(RasterError::BufferTooSmall {
            what: "triangles",
            needed: 12,
            got: 11
        })
    );
    assert_eq!(
        mesh::uv_sphere(1.0, 1, 4, &mut v, &mut t),
        Err(RasterError::BadParameter("stacks"))
    );
    assert_eq!(
        mesh::torus(1.0, 1.0, 4, 4, &mut v, &mut t),
        Err(RasterError::BadParameter("minor"))
    );
    assert_eq!(
        mesh::plane(f32::NAN, 1.0, 1, 1, &mut v, &mut t),
        Err(RasterError::Model(arealight::Error::NotFinite("size_x")))
    );
    assert_eq!(
        mesh::plane(1.0, 1.0, 300, 300, &mut v, &mut t),
        Err(RasterError::TooManyVertices { needed: 301 * 301 })
    );
    assert_eq!(
        Mesh::new(&v[..3], &[[0, 1, 3]]).map(|_| ()),
        Err(RasterError::IndexOutOfRange {
            triangle: 0,
            index: 3
        })
    );
    let mut px = [Rgb565(0); 10];
    assert_eq!(
        Band::new(&mut px, None, 3, 0).map(|_| ()),
        Err(RasterError::BadSize("band"))
    );
}

#[test]
fn pixel_formats_round_and_expand() {
    assert_eq!(Rgb565::from_unit(1.0f32, 1.0, 1.0), Rgb565(0xFFFF));
    assert_eq!(Rgb565::from_unit(0.0f32, f32::NAN, -3.0), Rgb565(0));
    assert_eq!(Rgb565::from_unit(1.0f32, 0.5, 0.0), Rgb565::new(31, 32, 0));
    assert_eq!(Rgb565::new(31, 63, 31).to_rgb8(), [255, 255, 255]);
    assert_eq!(Rgb565::new(16, 32, 1).to_rgb8(), [132, 130, 8]);
    assert_eq!(Rgb888::from_unit(0.5f64, 0.25, 2.0).0, [128, 64, 255]);
    let srgb_half = 1.055 * 0.5f64.powf(1.0 / 2.4) - 0.055;
    assert!((Encoding::Srgb.encode(0.5f64) - srgb_half).abs() < 1e-15);
    assert_eq!(Encoding::Srgb.encode(0.002f64), 12.92 * 0.002);
    assert_eq!(Encoding::Gamma2.encode(0.25f32), 0.5);
}

#[test]
fn affine_normals_stay_perpendicular_under_nonuniform_scale() {
    let v = |x: f64, y: f64, z: f64| Vec3::<f64>::new(x, y, z);
    for (sz, det_sign) in [(2.0, 1.0), (-2.0, -1.0)] {
        let xf = Affine::scale(v(3.0, 0.5, sz))
            .unwrap()
            .then(&Affine::rotation(v(1.0, 2.0, 3.0), 0.7).unwrap())
            .then(&Affine::translation(v(1.0, -1.0, 4.0)).unwrap());
        // A tangent plane: two tangents and the normal of the original surface.
        let (t1, t2) = (v(1.0, 0.2, -0.4), v(-0.3, 1.0, 0.5));
        let n = t1.cross(t2);
        let o = v(0.2, 0.1, -0.3);
        let (a, b, c) = (xf.point(o), xf.point(o + t1), xf.point(o + t2));
        let nn = xf.normal(n).normalize().unwrap();
        assert!(nn.dot((b - a).normalize().unwrap()).abs() < 1e-14);
        assert!(nn.dot((c - a).normalize().unwrap()).abs() < 1e-14);
        // The normal keeps its side of the surface (outward stays outward), so under a mirror
        // (negative determinant) it points against the transformed winding.
        assert_eq!(nn.dot((b - a).cross(c - a)).signum(), det_sign);
        // A point off the surface on the normal's side stays on it.
        let side = xf.point(o + n * 0.1) - a;
        assert!(side.dot(nn) > 0.0);
    }
}

#[test]
fn lit_material_is_diffuse_plus_phong() {
    let v = |x: f64, y: f64, z: f64| Vec3::<f64>::new(x, y, z);
    let lamp = SphereLight::new(v(0.0, 3.0, 1.0), 0.5).unwrap();
    let mat = Material::new(Rgb::new(0.5, 0.25, 1.0), Rgb::new(0.2, 0.4, 0.0), 8).unwrap();
    let (p, n, view) = (v(0.1, 0.0, 0.0), v(0.0, 1.0, 0.0), v(0.0, 0.6, 0.8));
    let (n, view) = (n.to_unit().unwrap(), view.to_unit().unwrap());
    let c = arealight::raster::Shader::shade(&Lit::new(&lamp, &mat), p, n, view);
    let lobe = PhongLobe::new(8).unwrap();
    let r = arealight::raster::reflect(view, n);
    assert_eq!(*r, v(0.0, 0.6, -0.8));
    let (d, s) = (lamp.lambert(p, n), lamp.phong(&lobe, p, r));
    assert!(d > 0.01 && s > 0.0);
    assert_eq!(c, Rgb::new(0.5 * d + 0.2 * s, 0.25 * d + 0.4 * s, d));
}

#[cfg(feature = "embedded-graphics")]
mod eg;

/// `Band::clear` fills every pixel and every depth value whatever the buffers' alignment and
/// length (with the `bytemuck` feature it stores 32-bit words between an unaligned first and
/// last value; without it, 16-bit values), and touches nothing outside the band.
#[test]
fn clear_fills_bands_at_every_alignment_and_length() {
    use arealight::raster::DEPTH_FAR;
    let colour = Rgb565::new(3, 50, 17);
    for start in 0..4usize {
        for len in [1usize, 2, 3, 7, 8, 9, 33, 240] {
            let mut px = vec![Rgb565(0x1234); len + 8];
            let mut depth = vec![7u16; len + 8];
            {
                let (p, d) = (&mut px[start..start + len], &mut depth[start..start + len]);
                let mut band = Band::new(p, Some(d), len as u16, 0).unwrap();
                band.clear(colour);
            }
            for (i, (p, d)) in px.iter().zip(&depth).enumerate() {
                let inside = (start..start + len).contains(&i);
                assert_eq!(
                    *p,
                    if inside { colour } else { Rgb565(0x1234) },
                    "pixel {i}"
                );
                assert_eq!(*d, if inside { DEPTH_FAR } else { 7 }, "depth {i}");
            }
        }
    }
}
