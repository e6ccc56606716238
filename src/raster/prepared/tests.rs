//! Tests of `raster/prepared.rs`: the triangles' recorded band rows draw the same pixels as
//! drawing every triangle in every band.

use super::{PreparedMesh, PreparedVertex, TriangleRows, VertexColour};
use crate::raster::{
    mesh, Affine, Band, Camera, Cull, DrawOptions, EncodeTable, Encoding, Lit, Material, Mesh,
    Projection, Rgb565, Shading, Vertex,
};
use crate::{Rgb, SphereLight, Vec3};

/// The tests' scene: a UV sphere (8 x 16) at the origin lit by a sphere light, plastic, sRGB.
fn with_sphere_scene(
    f: impl FnOnce(Mesh<'_, f32>, &Lit<'_, f32, SphereLight<f32>>, &EncodeTable<Rgb565>),
) {
    let (mut verts, mut tris) = ([Vertex::default(); 17 * 9], [[0u16; 3]; 2 * 16 * 7]);
    let counts = mesh::uv_sphere(1.0f32, 8, 16, &mut verts, &mut tris).unwrap();
    let sphere = Mesh::new(&verts[..counts.vertices], &tris[..counts.triangles]).unwrap();
    let lamp = SphereLight::new(Vec3::new(2.0, 2.0, 3.0), 0.5).unwrap();
    let plastic = Material::new(Rgb::new(0.8, 0.3, 0.2), Rgb::splat(0.5), 16).unwrap();
    let shader = Lit::new(&lamp, &plastic);
    let table = EncodeTable::new::<f32>(Encoding::Srgb);
    f(sphere, &shader, &table);
}

/// The tests' camera: looking at the origin from `eye`, `width` x 64 pixels.
fn camera(eye: Vec3<f32>, width: u16) -> Camera<f32> {
    Camera::new(
        eye,
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
        Projection::Perspective { fov_y: 0.9 },
        width,
        64,
    )
    .unwrap()
}

/// The 64 rows `m` draws with `cam` (at most 64 wide) through 8-row bands cleared to
/// `Rgb565(1)`, row-major.
fn draw_frame(
    m: &PreparedMesh<'_, '_, f32>,
    cam: &Camera<f32>,
    shader: &Lit<'_, f32, SphereLight<f32>>,
    opts: &DrawOptions<f32>,
    table: &EncodeTable<Rgb565>,
) -> [Rgb565; 64 * 64] {
    let mut frame = [Rgb565(0); 64 * 64];
    let (mut px, mut depth) = ([Rgb565(0); 64 * 8], [0u16; 64 * 8]);
    let width = usize::from(cam.width);
    let mut band = Band::new(
        &mut px[..width * 8],
        Some(&mut depth[..width * 8]),
        cam.width,
        0,
    )
    .unwrap();
    for y0 in (0..64).step_by(8) {
        band.move_to(y0);
        band.clear(Rgb565(1));
        m.draw(cam, &mut band, shader, opts, table).unwrap();
        let at = y0 as usize * width;
        frame[at..at + width * 8].copy_from_slice(band.pixels());
    }
    frame
}

#[test]
fn triangle_rows_draw_the_same_pixels() {
    with_sphere_scene(|sphere, shader, table| {
        for (eye, cull) in [
            (Vec3::new(0.0, 0.0, 4.0), Cull::Back),
            (Vec3::new(0.5, 1.0, 2.5), Cull::None),
            (Vec3::new(0.0, 0.3, 1.2), Cull::Back),
        ] {
            let camera = camera(eye, 64);
            let mut opts = DrawOptions::new(Shading::Gouraud);
            opts.cull = cull;
            let mut frames = [[Rgb565(0); 64 * 64]; 2];
            let mut counts = [0u32; 2];
            for (k, frame) in frames.iter_mut().enumerate() {
                let mut storage = [PreparedVertex::EMPTY; 17 * 9];
                let mut rows = [TriangleRows::EMPTY; 2 * 16 * 7];
                let mut m = if k == 0 {
                    PreparedMesh::new(sphere, &mut storage).unwrap()
                } else {
                    PreparedMesh::with_triangle_rows(sphere, &mut storage, &mut rows).unwrap()
                };
                m.transform(&camera, &Affine::identity());
                m.shade(&camera, shader, &opts);
                let (mut px, mut depth) = ([Rgb565(0); 64 * 8], [0u16; 64 * 8]);
                let mut band = Band::new(&mut px, Some(&mut depth), 64, 0).unwrap();
                for y0 in (0..64).step_by(8) {
                    band.move_to(y0);
                    band.clear(Rgb565(1));
                    let s = m.draw(&camera, &mut band, shader, &opts, table).unwrap();
                    counts[k] += s.rasterized;
                    let at = y0 as usize * 64;
                    frame[at..at + 64 * 8].copy_from_slice(band.pixels());
                }
            }
            assert_eq!(frames[0], frames[1]);
            assert_eq!(counts[0], counts[1]);
            assert!(frames[0].iter().filter(|p| p.0 != 1).count() > 200);
        }
    });
}

#[test]
fn a_mesh_shaded_again_without_a_transform_draws_as_a_fresh_one() {
    // The second shade of unchanged vertex data skips finding the visible vertices when the
    // culling and viewport are those of the first, and finds them again otherwise: every
    // step must give the calls and pixels of a mesh transformed and shaded afresh.
    with_sphere_scene(|sphere, shader, table| {
        let (near, side) = (Vec3::new(0.3, 0.2, 1.6), Vec3::new(1.5, 0.4, 2.0));
        let draw = |m: &PreparedMesh<'_, '_, f32>, cam: &Camera<f32>, opts: &DrawOptions<f32>| {
            draw_frame(m, cam, shader, opts, table)
        };
        let mut storage = [PreparedVertex::EMPTY; 17 * 9];
        let mut rows = [TriangleRows::EMPTY; 2 * 16 * 7];
        let mut kept = PreparedMesh::with_triangle_rows(sphere, &mut storage, &mut rows).unwrap();
        let mut transformed = None;
        // (transform: the camera's eye and the model's offset in x, or none; the culling; the
        // shading camera's eye and width.)
        let steps = [
            (Some((near, 0.0)), Cull::Back, near, 64),
            (None, Cull::Back, near, 64),
            (None, Cull::None, near, 64),
            (None, Cull::None, near, 64),
            (None, Cull::Back, near, 40),
            (Some((side, 0.0)), Cull::Back, side, 64),
            (Some((side, 0.6)), Cull::Back, side, 64),
            (None, Cull::Back, side, 64),
        ];
        for (k, (transform, cull, eye, width)) in steps.into_iter().enumerate() {
            let mut opts = DrawOptions::new(Shading::Gouraud);
            opts.cull = cull;
            if let Some(t) = transform {
                transformed = Some(t);
            }
            let (t_eye, dx) = transformed.unwrap();
            let placed = Affine::translation(Vec3::new(dx, 0.0, 0.0)).unwrap();
            if transform.is_some() {
                kept.transform(&camera(t_eye, 64), &placed);
            }
            let shading_camera = camera(eye, width);
            let calls = kept.shade(&shading_camera, shader, &opts);
            let mut fresh_storage = [PreparedVertex::EMPTY; 17 * 9];
            let mut fresh_rows = [TriangleRows::EMPTY; 2 * 16 * 7];
            let mut fresh =
                PreparedMesh::with_triangle_rows(sphere, &mut fresh_storage, &mut fresh_rows)
                    .unwrap();
            fresh.transform(&camera(t_eye, 64), &placed);
            assert_eq!(
                calls,
                fresh.shade(&shading_camera, shader, &opts),
                "step {k}"
            );
            assert!(calls > 0, "step {k}");
            let want = draw(&fresh, &shading_camera, &opts);
            assert!(draw(&kept, &shading_camera, &opts) == want, "step {k}");
        }
    });
}

#[test]
fn two_meshes_sharing_the_visible_pass_by_triangles_draw_as_one_pass() {
    // Each of two prepared meshes finds the visible vertices of its half of the triangles
    // (even and odd indices), takes the other's marks and rows, shades its half of the
    // vertices and takes the other's colours: both must hold what one mesh that did it all
    // holds (shader calls, rows, pixels), and the pass is not due again until a transform.
    with_sphere_scene(|sphere, shader, table| {
        let draw = |m: &PreparedMesh<'_, '_, f32>, cam: &Camera<f32>, opts: &DrawOptions<f32>| {
            draw_frame(m, cam, shader, opts, table)
        };
        for (eye, cull) in [
            (Vec3::new(0.0, 0.0, 4.0), Cull::Back),
            (Vec3::new(0.5, 1.0, 2.5), Cull::None),
            (Vec3::new(0.0, 0.3, 1.2), Cull::Back),
        ] {
            let cam = camera(eye, 64);
            let mut opts = DrawOptions::new(Shading::Gouraud);
            opts.cull = cull;
            let (mut s0, mut r0) = ([PreparedVertex::EMPTY; 17 * 9], [TriangleRows::EMPTY; 224]);
            let mut one = PreparedMesh::with_triangle_rows(sphere, &mut s0, &mut r0).unwrap();
            one.transform(&cam, &Affine::identity());
            let calls = one.shade(&cam, shader, &opts);
            let want = draw(&one, &cam, &opts);
            assert!(want.iter().filter(|p| p.0 != 1).count() > 200);

            let (mut sa, mut ra) = ([PreparedVertex::EMPTY; 17 * 9], [TriangleRows::EMPTY; 224]);
            let (mut sb, mut rb) = ([PreparedVertex::EMPTY; 17 * 9], [TriangleRows::EMPTY; 224]);
            let mut a = PreparedMesh::with_triangle_rows(sphere, &mut sa, &mut ra).unwrap();
            let mut b = PreparedMesh::with_triangle_rows(sphere, &mut sb, &mut rb).unwrap();
            let (even, odd) = (|i: usize| i % 2 == 0, |i: usize| i % 2 == 1);
            for m in [&mut a, &mut b] {
                m.transform(&cam, &Affine::identity());
            }
            assert!(a.find_visible_some(&cam, cull, even));
            assert!(b.find_visible_some(&cam, cull, odd));
            let marks = |m: &PreparedMesh<'_, '_, f32>| {
                let mut out = [false; 17 * 9];
                for (o, v) in out.iter_mut().zip(m.visible_marks()) {
                    *o = v;
                }
                out
            };
            let rows = |m: &PreparedMesh<'_, '_, f32>| {
                let mut out = [TriangleRows::EMPTY; 224];
                for (o, r) in out.iter_mut().zip(m.triangle_rows()) {
                    *o = r;
                }
                out
            };
            let (marks_a, rows_a, marks_b, rows_b) = (marks(&a), rows(&a), marks(&b), rows(&b));
            // Each half alone misses vertices the whole pass finds.
            let mut whole = marks_a;
            for (w, m) in whole.iter_mut().zip(marks_b) {
                *w |= m;
            }
            let count = |m: &[bool]| m.iter().filter(|&&x| x).count();
            assert!(count(&whole) > count(&marks_a) && count(&whole) > count(&marks_b));
            a.set_visible(&cam, cull, marks_b, rows_b, odd);
            b.set_visible(&cam, cull, marks_a, rows_a, even);
            for m in [&a, &b] {
                assert!(m.triangle_rows().eq(one.triangle_rows()));
                assert_eq!(marks(m), whole);
            }
            assert!(!a.find_visible_some(&cam, cull, even));
            let shared =
                a.shade_some(&cam, shader, &opts, even) + b.shade_some(&cam, shader, &opts, odd);
            assert_eq!(shared, calls);
            let mut colours = [[VertexColour::BLACK; 17 * 9]; 2];
            for (k, m) in [&a, &b].into_iter().enumerate() {
                for (o, c) in colours[k].iter_mut().zip(m.colours()) {
                    *o = c;
                }
            }
            a.set_colours(colours[1], odd);
            b.set_colours(colours[0], even);
            assert!(draw(&a, &cam, &opts) == want);
            assert!(draw(&b, &cam, &opts) == want);
            a.transform(&cam, &Affine::identity());
            assert!(a.find_visible_some(&cam, cull, even));
        }
    });
}
