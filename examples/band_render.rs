//! A small lit sphere on a floor, rendered band by band into an RGB565 buffer as a firmware
//! would render it for an SPI display, then written as a PPM image.
//!
//! ```sh
//! cargo run --release --example band_render > sphere.ppm   # to standard output
//! cargo run --release --example band_render -- sphere.ppm  # or to a file
//! ```
//!
//! The firmware part (`render_band`'s caller, up to the comment "send the band") uses only
//! `no_std` items of `arealight`: fixed-size arrays, no allocation. The pipeline is the one of
//! `arealight::raster::PreparedMesh`:
//!
//! 1. once per frame, each mesh's vertices are transformed and projected
//!    (`PreparedMesh::transform`), and shaded once each (`PreparedMesh::shade`, Gouraud);
//! 2. per band of 16 rows, the band is cleared and every mesh is drawn into it in integers
//!    (`PreparedMesh::draw`), its colours encoded by a lookup table (`EncodeTable`, sRGB);
//! 3. the band's RGB565 pixels go to the display (here: into a frame for the PPM file).
//!
//! With 16-row bands of a 160-pixel-wide display, the colour and depth bands take 5 KiB each.

use std::io::{IsTerminal, Write};

use arealight::raster::{
    mesh, Affine, Band, Camera, DrawOptions, EncodeTable, Encoding, Lit, Material, Mesh,
    PixelFormat, PreparedMesh, PreparedVertex, Projection, Rgb565, Shading, Vertex,
};
use arealight::{Illuminant, PolygonLight, Rgb, SphereLight, Vec3};

const WIDTH: u16 = 160;
const HEIGHT: u16 = 120;
/// Rows per band.
const BAND: u16 = 16;

/// UV sphere of 12 stacks and 24 slices: (12 + 1)(24 + 1) vertices, 2 * 24 * 11 triangles.
const SPHERE_VERTS: usize = 13 * 25;
const SPHERE_TRIS: usize = 2 * 24 * 11;
/// Floor of 8 x 8 cells.
const FLOOR_VERTS: usize = 9 * 9;
const FLOOR_TRIS: usize = 2 * 8 * 8;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // --- Setup, once: meshes, lights, materials, camera (all on the stack). ---
    let (mut sv, mut st) = ([Vertex::default(); SPHERE_VERTS], [[0u16; 3]; SPHERE_TRIS]);
    let counts = mesh::uv_sphere(0.6f32, 12, 24, &mut sv, &mut st)?;
    let sphere = Mesh::new(&sv[..counts.vertices], &st[..counts.triangles])?;
    let (mut fv, mut ft) = ([Vertex::default(); FLOOR_VERTS], [[0u16; 3]; FLOOR_TRIS]);
    let counts = mesh::plane(4.0f32, 4.0, 8, 8, &mut fv, &mut ft)?;
    let floor = Mesh::new(&fv[..counts.vertices], &ft[..counts.triangles])?;

    let camera = Camera::new(
        Vec3::new(0.0, 1.6, 3.2),
        Vec3::new(0.0, 0.4, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
        Projection::Perspective { fov_y: 0.75 },
        WIDTH,
        HEIGHT,
    )?;
    // A warm spherical lamp to the right and a cool panel overhead, summed.
    let lamp = SphereLight::new(Vec3::new(1.6, 1.8, 1.2), 0.3)?;
    let panel = PolygonLight::<f32, 4>::new(&[
        Vec3::new(-1.0, 2.5, -0.8),
        Vec3::new(0.0, 2.5, -0.8),
        Vec3::new(0.0, 2.5, 0.2),
        Vec3::new(-1.0, 2.5, 0.2),
    ])?;
    let warm = arealight::Tinted::new(lamp, Rgb::new(1.0, 0.85, 0.6))?;
    let cool = arealight::Tinted::new(panel, Rgb::new(0.6, 0.75, 1.0))?;
    let lights: [&dyn Illuminant<f32>; 2] = [&warm, &cool];

    let plastic = Material::new(Rgb::new(0.8, 0.25, 0.2), Rgb::splat(0.4), 24)?;
    let matte = Material::matte(Rgb::splat(0.7))?;
    let (on_sphere, on_floor) = (Lit::new(&lights, &plastic), Lit::new(&lights, &matte));

    // Expose so that the floor under the sphere shows at about 80 %.
    let under = lights.diffuse(Vec3::new(0.0, 0.0, 0.9), arealight::UnitVec3::y_axis());
    let mut opts = DrawOptions::new(Shading::Gouraud);
    opts.exposure = 0.8 / under.r.max(under.g).max(under.b);
    let table = EncodeTable::new::<f32>(Encoding::Srgb);

    // --- Once per frame: transform and shade every vertex. ---
    let mut sphere_storage = [PreparedVertex::EMPTY; SPHERE_VERTS];
    let mut floor_storage = [PreparedVertex::EMPTY; FLOOR_VERTS];
    let mut prepared_sphere = PreparedMesh::new(sphere, &mut sphere_storage)?;
    let mut prepared_floor = PreparedMesh::new(floor, &mut floor_storage)?;
    let lift = Affine::translation(Vec3::new(0.0, 0.6, 0.0))?;
    prepared_sphere.transform(&camera, &lift);
    prepared_floor.transform(&camera, &Affine::identity());
    let calls = prepared_sphere.shade(&camera, &on_sphere, &opts)
        + prepared_floor.shade(&camera, &on_floor, &opts);

    // --- Per band: clear, draw, send. ---
    let mut pixels = [Rgb565(0); WIDTH as usize * BAND as usize];
    let mut depth = [0u16; WIDTH as usize * BAND as usize];
    let mut band = Band::new(&mut pixels, Some(&mut depth), WIDTH, 0)?;
    let background = Rgb565::new(2, 4, 6);
    let mut frame = vec![Rgb565(0); WIDTH as usize * HEIGHT as usize]; // the "display"
    for y0 in (0..HEIGHT).step_by(BAND as usize) {
        band.move_to(y0);
        band.clear(background);
        prepared_floor.draw(&camera, &mut band, &on_floor, &opts, &table)?;
        prepared_sphere.draw(&camera, &mut band, &on_sphere, &opts, &table)?;
        // send the band: on a board, band.pixels() goes to the display's rows y0..y0 + 16.
        let rows = BAND.min(HEIGHT - y0) as usize;
        let start = y0 as usize * WIDTH as usize;
        let len = rows * WIDTH as usize;
        frame[start..start + len].copy_from_slice(&band.pixels()[..len]);
    }

    // --- Host side: the frame as a binary PPM (P6). ---
    let mut ppm = format!("P6\n{WIDTH} {HEIGHT}\n255\n").into_bytes();
    for p in &frame {
        ppm.extend_from_slice(&p.to_rgb8());
    }
    match std::env::args_os().nth(1) {
        Some(path) => std::fs::write(&path, &ppm)?,
        None if std::io::stdout().is_terminal() => {
            std::fs::write("band_render.ppm", &ppm)?;
            eprintln!("stdout is a terminal: wrote band_render.ppm instead");
        }
        None => std::io::stdout().lock().write_all(&ppm)?,
    }
    eprintln!(
        "{WIDTH}x{HEIGHT} in {} bands of {BAND} rows, {calls} vertex shader calls",
        HEIGHT.div_ceil(BAND)
    );
    Ok(())
}
