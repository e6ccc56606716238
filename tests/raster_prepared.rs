//! The prepared (integer) rasterizer path, `arealight::raster::PreparedMesh`, against the
//! generic `draw` and against exhaustive references: span iteration equals pixel iteration,
//! the encoding table is within one level of the transfer functions, prepared frames cover
//! exactly the pixels `draw` covers with colours close to its, bands equal the full frame, the
//! nearer surface wins, clipped geometry leaves no hole.

use arealight::raster::edge::{Cull, EdgeTriangle, FixedPoint};
use arealight::raster::{
    draw, encode_pixel, mesh, Affine, Band, Camera, DrawOptions, EncodeTable, Encoding, Lit,
    Material, Mesh, PixelFormat, PreparedMesh, PreparedVertex, Projection, Rgb565, Rgb888, Shading,
    Vertex, ENCODE_ENTRIES,
};
use arealight::{Fixed22, PolygonLight, Real, Rgb, SphereLight, Vec3};

/// A small deterministic generator (xorshift).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn range(&mut self, lo: i32, hi: i32) -> i32 {
        lo + (self.next() % (hi - lo) as u64) as i32
    }
}

fn covered_by_pixels(t: &EdgeTriangle, width: i32, r0: i32, r1: i32) -> Vec<(i32, i32)> {
    let mut v = Vec::new();
    t.for_each_covered(width, r0, r1, |x, y, _| v.push((x, y)));
    v
}

fn covered_by_spans(t: &EdgeTriangle, width: i32, r0: i32, r1: i32) -> Vec<(i32, i32)> {
    let mut v = Vec::new();
    t.for_each_span(width, r0, r1, |y, a, b| v.extend((a..=b).map(|x| (x, y))));
    v
}

#[test]
fn spans_are_exactly_the_covered_pixels() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut triangles = 0;
    // Small triangles (the i32 path), slivers, shared edges on the sub-pixel lattice, large
    // ones beyond 1024 pixels (the i64 path), partly off screen, in bands of every size.
    for case in 0..20_000 {
        let (span, off) = match case % 4 {
            0 => (40, 0),
            1 => (400, -100),
            2 => (40_000, -20_000),
            _ => (6, 0),
        };
        let p =
            |rng: &mut Rng| FixedPoint::new(rng.range(off, off + span), rng.range(off, off + span));
        let v = [p(&mut rng), p(&mut rng), p(&mut rng)];
        let Some(t) = EdgeTriangle::new(v, Cull::None) else {
            continue;
        };
        triangles += 1;
        let width = [64, 240, 1024][case % 3];
        let r0 = rng.range(-5, 40);
        let r1 = r0 + rng.range(0, 300);
        assert_eq!(
            covered_by_spans(&t, width, r0, r1),
            covered_by_pixels(&t, width, r0, r1),
            "{v:?} width {width} rows {r0}..{r1}"
        );
    }
    assert!(triangles > 15_000, "{triangles}");
}

#[test]
fn encoding_table_is_within_a_level_of_the_transfer_function() {
    // Every linear value on a fine grid (16 per table step) and the table's own entries.
    // Measured worst differences (RGB565 green, RGB888): the table rounds the linear value to
    // 1/4096, which near black is up to 3 levels of 8-bit gamma 2 (sqrt is steep there).
    for (enc, bound565, bound888) in [
        (Encoding::Linear, 1, 1),
        (Encoding::Gamma2, 1, 3),
        (Encoding::Srgb, 1, 1),
    ] {
        let table565 = EncodeTable::<Rgb565>::new::<f64>(enc);
        let table = EncodeTable::<Rgb888>::new::<f64>(enc);
        let mut worst = [0i32; 2];
        for i in 0..(ENCODE_ENTRIES as i32 - 1) * 16 {
            let x = f64::from(i) / (4096.0 * 16.0);
            let idx = (x * 4096.0).round() as i32;
            let c = Rgb::splat(x);
            let a: Rgb565 = table565.pixel(idx, idx, idx);
            let b: Rgb565 = encode_pixel(c, 1.0, enc);
            let d565 = (i32::from(a.0 >> 5 & 63) - i32::from(b.0 >> 5 & 63)).abs();
            let a: Rgb888 = table.pixel(idx, idx, idx);
            let b: Rgb888 = encode_pixel(c, 1.0, enc);
            let d888 = (i32::from(a.0[0]) - i32::from(b.0[0])).abs();
            worst = [worst[0].max(d565), worst[1].max(d888)];
        }
        println!(
            "{enc:?}: worst difference {} (RGB565 green), {} (RGB888)",
            worst[0], worst[1]
        );
        assert!(
            worst[0] <= bound565 && worst[1] <= bound888,
            "{enc:?}: {worst:?}"
        );
        // The ends are exact.
        let black: Rgb888 = table.pixel(0, 0, 0);
        let white: Rgb888 = table.pixel(4096, 4096, 4096);
        assert_eq!((black.0, white.0), ([0; 3], [255; 3]));
        // Out of range clamps.
        let clamped: Rgb888 = table.pixel(-7, 99_999, i32::MIN);
        assert_eq!(clamped.0, [0, 255, 0]);
    }
}

#[test]
fn levels_round_exactly_into_every_pixel_format() {
    for level in 0..=u16::MAX {
        let x = f64::from(level) / 65535.0;
        let q = |max: f64| (x * max + 0.5).floor() as u16;
        let p = Rgb565::from_levels(level, level, level);
        assert_eq!(
            (p.0 >> 11, p.0 >> 5 & 63, p.0 & 31),
            (q(31.0), q(63.0), q(31.0)),
            "{level}"
        );
        assert_eq!(
            Rgb888::from_levels(level, level, level).0[1] as u16,
            q(255.0),
            "{level}"
        );
        // A table's entries make the same pixels as the levels, each channel from its own
        // entry (RGB565's entries are packed: every channel's bits of the level).
        let (g, b) = (level ^ 0x5A5A, u16::MAX - level.rotate_left(3));
        let e = <Rgb565 as PixelFormat>::table_entry;
        assert_eq!(
            Rgb565::from_entries(e(level), e(g), e(b)),
            Rgb565::from_levels(level, g, b),
            "{level}"
        );
        let e = <Rgb888 as PixelFormat>::table_entry;
        assert_eq!(
            Rgb888::from_entries(e(level), e(g), e(b)),
            Rgb888::from_levels(level, g, b),
            "{level}"
        );
    }
}

/// The scene: a sphere and a torus lit by a polygon and a sphere light, one in Gouraud and one
/// per pixel, and a floor that crosses the near plane and the guard band (clipped).
/// A mesh of the scene: vertices, triangles, model transform, material, draw options.
type SceneMesh<T> = (
    Vec<Vertex<T>>,
    Vec<[u16; 3]>,
    Affine<T>,
    Material<T>,
    DrawOptions<T>,
);

struct Scene<T: Real> {
    camera: Camera<T>,
    meshes: Vec<SceneMesh<T>>,
    panel: PolygonLight<T, 4>,
    lamp: SphereLight<T>,
}

fn zero_vertex<T: Real>() -> Vertex<T> {
    let o = Vec3::new(T::ZERO, T::ZERO, T::ZERO);
    Vertex::new(o, o)
}

fn scene<T: Real>(w: u16, h: u16, shading: [Shading; 3]) -> Scene<T> {
    let k = T::from_f64;
    let v = |x: f64, y: f64, z: f64| Vec3::new(k(x), k(y), k(z));
    let camera = Camera::new(
        v(0.3, 1.2, 3.4),
        v(0.0, 0.1, 0.0),
        v(0.0, 1.0, 0.0),
        Projection::Perspective { fov_y: k(0.9) },
        w,
        h,
    )
    .unwrap()
    .with_depth_range(k(0.05), k(30.0))
    .unwrap();
    let mut sphere = (
        vec![zero_vertex::<T>(); mesh::uv_sphere_counts(10, 18).vertices],
        vec![[0u16; 3]; mesh::uv_sphere_counts(10, 18).triangles],
    );
    mesh::uv_sphere(k(0.7), 10, 18, &mut sphere.0, &mut sphere.1).unwrap();
    let mut torus = (
        vec![zero_vertex::<T>(); mesh::torus_counts(20, 10).vertices],
        vec![[0u16; 3]; mesh::torus_counts(20, 10).triangles],
    );
    mesh::torus(k(0.5), k(0.18), 20, 10, &mut torus.0, &mut torus.1).unwrap();
    let mut floor = (
        vec![zero_vertex::<T>(); mesh::plane_counts(8, 8).vertices],
        vec![[0u16; 3]; mesh::plane_counts(8, 8).triangles],
    );
    mesh::plane(k(8.0), k(8.0), 8, 8, &mut floor.0, &mut floor.1).unwrap();
    let red = Material::new(Rgb::new(k(0.8), k(0.2), k(0.1)), Rgb::splat(k(0.4)), 24).unwrap();
    let teal = Material::new(Rgb::new(k(0.1), k(0.5), k(0.5)), Rgb::splat(k(0.5)), 12).unwrap();
    let grey = Material::matte(Rgb::splat(k(0.6))).unwrap();
    let opts = |s: Shading| {
        let mut o = DrawOptions::new(s);
        o.encoding = Encoding::Gamma2;
        o
    };
    Scene {
        camera,
        meshes: vec![
            (
                sphere.0,
                sphere.1,
                Affine::translation(v(-0.6, 0.0, 0.0)).unwrap(),
                red,
                opts(shading[0]),
            ),
            (
                torus.0,
                torus.1,
                Affine::rotation(v(1.0, 0.0, 0.0), k(1.0))
                    .unwrap()
                    .then(&Affine::translation(v(0.7, 0.0, 0.1)).unwrap()),
                teal,
                opts(shading[1]),
            ),
            (
                floor.0,
                floor.1,
                Affine::translation(v(0.0, -0.75, 0.0)).unwrap(),
                grey,
                opts(shading[2]),
            ),
        ],
        panel: PolygonLight::new(&[
            v(-1.0, 2.0, -1.0),
            v(1.0, 2.0, -1.0),
            v(1.0, 2.0, 0.5),
            v(-1.0, 2.0, 0.5),
        ])
        .unwrap(),
        lamp: SphereLight::new(v(1.5, 1.0, 1.5), k(0.2)).unwrap(),
    }
}

/// Renders `scene` with the prepared path through bands of `rows` rows, or with `draw`.
fn render<T: Real>(s: &Scene<T>, rows: u16, use_prepared: bool) -> (Vec<Rgb565>, Vec<u16>) {
    render_with(s, rows, use_prepared, true)
}

/// [`render`], the prepared meshes shaded after their transform only if `shade`.
fn render_with<T: Real>(
    s: &Scene<T>,
    rows: u16,
    use_prepared: bool,
    shade: bool,
) -> (Vec<Rgb565>, Vec<u16>) {
    let (w, h) = (s.camera.width(), s.camera.height());
    let lights: [&dyn arealight::Illuminant<T>; 2] = [&s.panel, &s.lamp];
    let table = EncodeTable::new::<T>(Encoding::Gamma2);
    let mut storage: Vec<Vec<PreparedVertex<T>>> = s
        .meshes
        .iter()
        .map(|m| vec![PreparedVertex::EMPTY; m.0.len()])
        .collect();
    let mut prepared: Vec<PreparedMesh<'_, '_, T>> = Vec::new();
    for (m, st) in s.meshes.iter().zip(storage.iter_mut()) {
        let mut p = PreparedMesh::new(Mesh::new(&m.0, &m.1).unwrap(), st).unwrap();
        p.transform(&s.camera, &m.2);
        if shade {
            p.shade(&s.camera, &Lit::new(&lights, &m.3), &m.4);
        }
        prepared.push(p);
    }
    in_bands(w, h, rows, |_, band| {
        for (i, m) in s.meshes.iter().enumerate() {
            let lit = Lit::new(&lights, &m.3);
            if use_prepared {
                prepared[i]
                    .draw(&s.camera, band, &lit, &m.4, &table)
                    .unwrap();
            } else {
                draw(
                    &s.camera,
                    band,
                    &Mesh::new(&m.0, &m.1).unwrap(),
                    &m.2,
                    &lit,
                    &m.4,
                )
                .unwrap();
            }
        }
    })
}

/// A `w` x `h` frame drawn in bands of `rows` rows (`draw(k, band)` draws band `k` into the
/// cleared band): its pixels and depth values, row after row.
fn in_bands(
    w: u16,
    h: u16,
    rows: u16,
    mut draw: impl FnMut(u16, &mut Band<'_, Rgb565>),
) -> (Vec<Rgb565>, Vec<u16>) {
    let n = w as usize * rows as usize;
    let (mut px, mut dp) = (vec![Rgb565(0); n], vec![0u16; n]);
    let mut band = Band::new(&mut px, Some(&mut dp), w, 0).unwrap();
    let (mut out, mut out_depth) = (Vec::new(), Vec::new());
    let mut y0 = 0;
    while y0 < h {
        band.move_to(y0);
        band.clear(Rgb565(0));
        draw(y0 / rows, &mut band);
        let keep = (w as usize * (h - y0).min(rows) as usize).min(n);
        out.extend_from_slice(&band.pixels()[..keep]);
        out_depth.extend_from_slice(&band.depth().unwrap()[..keep]);
        y0 += rows;
    }
    (out, out_depth)
}

fn channels(p: Rgb565) -> [i32; 3] {
    [
        (p.0 >> 11) as i32,
        (p.0 >> 5 & 63) as i32,
        (p.0 & 31) as i32,
    ]
}

#[test]
fn prepared_bands_equal_the_full_frame() {
    fn check<T: Real>() {
        let s = scene::<T>(
            96,
            80,
            [Shading::Gouraud, Shading::PerPixel, Shading::Gouraud],
        );
        let full = render(&s, 80, true);
        assert!(full.1.iter().filter(|&&d| d != u16::MAX).count() > 96 * 80 / 3);
        for rows in [1, 7, 16] {
            assert!(render(&s, rows, true) == full, "{rows}-row bands");
        }
    }
    check::<f32>();
    check::<f64>();
    check::<Fixed22>();
}

/// The normals of a transform are computed where first needed: per pixel by `shade` for the
/// whole mesh, or by `draw` for each triangle when no `shade` came after the transform. The
/// same pixels either way, in bands of several heights.
#[test]
fn per_pixel_draws_the_same_pixels_without_a_shade() {
    fn check<T: Real>() {
        let s = scene::<T>(96, 80, [Shading::PerPixel; 3]);
        let shaded = render_with(&s, 80, true, true);
        assert!(shaded.1.iter().filter(|&&d| d != u16::MAX).count() > 96 * 80 / 3);
        for rows in [7, 16, 80] {
            assert!(
                render_with(&s, rows, true, false) == shaded,
                "{rows}-row bands"
            );
        }
    }
    check::<f32>();
    check::<f64>();
    check::<Fixed22>();
}

/// Pixels of objects drawn apart (no depth conflict between them): the prepared path must
/// cover exactly `draw`'s pixels, with colours within a few levels.
#[test]
fn prepared_frames_cover_drawn_pixels_with_close_colours() {
    fn check<T: Real>(name: &str, max_gouraud: i32, max_per_pixel: i32) {
        for shading in [Shading::Gouraud, Shading::PerPixel] {
            let mut s = scene::<T>(128, 96, [shading; 3]);
            s.meshes.truncate(1); // the sphere alone: coverage depends on no depth order
            let (a, da) = render(&s, 16, true);
            let (b, db) = render(&s, 16, false);
            let (mut worst, mut covered) = (0, 0);
            for ((p, q), (dp, dq)) in a.iter().zip(&b).zip(da.iter().zip(&db)) {
                let drawn = *dp != u16::MAX;
                assert_eq!(drawn, *dq != u16::MAX, "{name}: coverage differs");
                covered += usize::from(drawn);
                let d = channels(*p)
                    .iter()
                    .zip(channels(*q))
                    .map(|(x, y)| (x - y).abs())
                    .max()
                    .unwrap();
                worst = worst.max(d);
            }
            println!(
                "{name} {shading:?}: {covered} pixels, worst channel difference {worst} levels"
            );
            assert!(covered > 1000);
            let bound = if shading == Shading::Gouraud {
                max_gouraud
            } else {
                max_per_pixel
            };
            assert!(worst <= bound, "{name} {shading:?}: {worst} > {bound}");
        }
    }
    // Gouraud: affine instead of perspective-correct interpolation across a triangle, and the
    // table's 1/4096 rounding; per pixel: the table alone (and the barycentric weights'
    // 2^-24 rounding).
    check::<f32>("f32", 1, 1);
    check::<f64>("f64", 1, 1);
    check::<Fixed22>("Fixed22", 1, 1);
}

#[test]
fn nearer_surface_wins_and_clipped_floor_has_no_hole() {
    // The full scene: the floor crosses the near plane and the guard band; the sphere and
    // torus stand on it. Every pixel below the horizon is drawn (no crack from clipping), and
    // drawing the meshes in reverse order gives the same picture (depth decides, not order).
    let s = scene::<f32>(120, 90, [Shading::Gouraud; 3]);
    let (a, depth) = render(&s, 16, true);
    let mut r = scene::<f32>(120, 90, [Shading::Gouraud; 3]);
    r.meshes.reverse();
    let (b, _) = render(&r, 16, true);
    let differ = a.iter().zip(&b).filter(|(p, q)| p != q).count();
    // Exact depth ties (the floor against the objects' bottoms) may go either way.
    assert!(differ <= 3, "{differ} pixels depend on the draw order");
    let (w, h) = (120usize, 90usize);
    // The bottom rows are all floor or objects.
    for y in h - 20..h {
        for x in 0..w {
            assert_ne!(depth[y * w + x], u16::MAX, "hole at ({x}, {y})");
        }
    }
}

/// Renders `scene` (all Gouraud) as two cores share a frame: each transforms and shades the
/// vertices of its parity and takes the other's screen data and colours
/// (`PreparedMesh::transform_some`, `screen`/`set_screen`, `shade_some`,
/// `colours`/`set_colours`); core `k` draws the bands of parity `k`.
fn render_shared<T: Real>(s: &Scene<T>, rows: u16) -> (Vec<Rgb565>, Vec<u16>) {
    let (w, h) = (s.camera.width(), s.camera.height());
    let lights: [&dyn arealight::Illuminant<T>; 2] = [&s.panel, &s.lamp];
    let table = EncodeTable::new::<T>(Encoding::Gamma2);
    let mut storage: [Vec<Vec<PreparedVertex<T>>>; 2] = core::array::from_fn(|_| {
        s.meshes
            .iter()
            .map(|m| vec![PreparedVertex::EMPTY; m.0.len()])
            .collect()
    });
    let [st0, st1] = &mut storage;
    let mut cores: [Vec<PreparedMesh<'_, '_, T>>; 2] = [Vec::new(), Vec::new()];
    for (k, st) in [st0, st1].into_iter().enumerate() {
        for (m, st) in s.meshes.iter().zip(st.iter_mut()) {
            let mut p = PreparedMesh::new(Mesh::new(&m.0, &m.1).unwrap(), st).unwrap();
            p.transform_some(&s.camera, &m.2, true, |i| i % 2 == k);
            cores[k].push(p);
        }
    }
    let [c0, c1] = &mut cores;
    for (a, b) in c0.iter_mut().zip(c1.iter_mut()) {
        let (sa, sb): (Vec<_>, Vec<_>) = (a.screen().collect(), b.screen().collect());
        a.set_screen(&s.camera, sb, |i| i % 2 == 1);
        b.set_screen(&s.camera, sa, |i| i % 2 == 0);
    }
    for (k, c) in cores.iter_mut().enumerate() {
        for (p, m) in c.iter_mut().zip(&s.meshes) {
            p.shade_some(&s.camera, &Lit::new(&lights, &m.3), &m.4, |i| i % 2 == k);
        }
    }
    let [c0, c1] = &mut cores;
    for (a, b) in c0.iter_mut().zip(c1.iter_mut()) {
        let (ca, cb): (Vec<_>, Vec<_>) = (a.colours().collect(), b.colours().collect());
        a.set_colours(cb, |i| i % 2 == 1);
        b.set_colours(ca, |i| i % 2 == 0);
    }
    for (a, b) in cores[0].iter().zip(&cores[1]) {
        assert_eq!(a.rows(), b.rows());
    }
    in_bands(w, h, rows, |k, band| {
        for (p, m) in cores[usize::from(k) % 2].iter().zip(&s.meshes) {
            p.draw(&s.camera, band, &Lit::new(&lights, &m.3), &m.4, &table)
                .unwrap();
        }
    })
}

#[test]
fn two_cores_sharing_a_frame_draw_the_same_pixels_as_one() {
    fn check<T: Real>() {
        // The floor reaches behind the camera (clipped vertices: the rows of a shared mesh
        // are then all rows, found after the exchange).
        let s = scene::<T>(96, 80, [Shading::Gouraud; 3]);
        let one = render(&s, 16, true);
        let two = render_shared(&s, 16);
        fn differ<P: PartialEq>(a: &[P], b: &[P]) -> usize {
            a.iter().zip(b).filter(|(x, y)| x != y).count()
        }
        assert_eq!(differ(&one.0, &two.0), 0, "pixels");
        assert_eq!(differ(&one.1, &two.1), 0, "depth");
        assert_eq!(one.0.len(), two.0.len());
        assert!(one.0.iter().filter(|p| p.0 != 0).count() > 2000);
    }
    check::<f64>();
    check::<f32>();
    check::<Fixed22>();
}
