//! Tests of `raster/prepared.rs`: the triangles' recorded band rows draw the same pixels as
//! drawing every triangle in every band.

use super::{PreparedMesh, PreparedVertex, TriangleRows};
use crate::raster::{
    mesh, Affine, Band, Camera, Cull, DrawOptions, EncodeTable, Encoding, Lit, Material, Mesh,
    Projection, Rgb565, Shading, Vertex,
};
use crate::{Rgb, SphereLight, Vec3};

#[test]
fn triangle_rows_draw_the_same_pixels() {
    let (mut verts, mut tris) = ([Vertex::default(); 17 * 9], [[0u16; 3]; 2 * 16 * 7]);
    let counts = mesh::uv_sphere(1.0f32, 8, 16, &mut verts, &mut tris).unwrap();
    let sphere = Mesh::new(&verts[..counts.vertices], &tris[..counts.triangles]).unwrap();
    let lamp = SphereLight::new(Vec3::new(2.0, 2.0, 3.0), 0.5).unwrap();
    let plastic = Material::new(Rgb::new(0.8, 0.3, 0.2), Rgb::splat(0.5), 16).unwrap();
    let shader = Lit::new(&lamp, &plastic);
    let table = EncodeTable::new::<f32>(Encoding::Srgb);
    for (eye, cull) in [
        (Vec3::new(0.0, 0.0, 4.0), Cull::Back),
        (Vec3::new(0.5, 1.0, 2.5), Cull::None),
        (Vec3::new(0.0, 0.3, 1.2), Cull::Back),
    ] {
        let camera = Camera::new(
            eye,
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Projection::Perspective { fov_y: 0.9 },
            64,
            64,
        )
        .unwrap();
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
            m.shade(&camera, &shader, &opts);
            let (mut px, mut depth) = ([Rgb565(0); 64 * 8], [0u16; 64 * 8]);
            let mut band = Band::new(&mut px, Some(&mut depth), 64, 0).unwrap();
            for y0 in (0..64).step_by(8) {
                band.move_to(y0);
                band.clear(Rgb565(1));
                let s = m.draw(&camera, &mut band, &shader, &opts, &table).unwrap();
                counts[k] += s.rasterized;
                let at = y0 as usize * 64;
                frame[at..at + 64 * 8].copy_from_slice(band.pixels());
            }
        }
        assert_eq!(frames[0], frames[1]);
        assert_eq!(counts[0], counts[1]);
        assert!(frames[0].iter().filter(|p| p.0 != 1).count() > 200);
    }
}
