//! What each kind of work costs on the chip that runs it: the unit costs `host-sim budget
//! --scene` multiplies a scene's counted work by (docs/scene-budget.md).
//!
//! [`run`] measures, with the caller's clock (core cycles on the RP2040 under rp2040js,
//! instructions on the Cortex-M4F under QEMU), synthetic work that is *not* the demo's frame,
//! so that the demo's frame can check the predictions made from these costs:
//!
//! | item | what is timed | count |
//! |---|---|---|
//! | `diffuse:<kind>` | [`Illuminant::diffuse`] of one light at [`POINTS`] shading points | calls |
//! | `phong8:<kind>`, `phong32:<kind>` | [`Illuminant::phong`] with m = 8 and 32 at the same points | calls |
//! | each of those with `:lit`, `:dark` | the same calls at the points where they give light, and where they give none (each subset in its own loop) | calls |
//! | `lit_matte`, `lit_specular` | [`Lit::shade`] with no light: the material's own work | calls |
//! | `vertex_lit`, `vertex_unlit` | [`PreparedMesh::transform`] / `transform_unlit` of a 10 x 20 UV sphere | vertices |
//! | `shade_vertex` | [`PreparedMesh::shade`] of that sphere with a shader that takes its inputs (as a lit one) and returns a constant | shader calls |
//! | `shade_vertex_flat` | the same with a constant-colour shader that ignores its inputs (an emissive object's) | shader calls |
//! | `band_clear` | [`Band::clear`] of every band of the frame | bands |
//! | `raster_big`, `raster_grid` | Gouraud [`PreparedMesh::draw`] of a square seen face on, as 2 and as 512 triangles, every band | pixels (and triangle setups) |
//! | `raster_big_pp` | the 2-triangle square per pixel with the shader of `shade_vertex` | pixels (and shader calls) |
//!
//! The light kinds are those the firmware's features build (`polygon` (a quad), `sphere`,
//! `cap`, `point`, `directional`, `ambient`); the shading points are [`POINTS`] points of a
//! sphere of radius 0.6 at the origin, every direction (Fibonacci), seen from the demo's
//! camera, so about half of them face away from each light (the early exits count as in a
//! scene). Everything lies within the fixed-point range.
//!
//! A light's cost depends on whether it reaches the point: facing away, below the horizon, a
//! Phong lobe that misses the light, each model exits early. A scene whose visible points
//! mostly face its lights pays the full cost far more often than these points do (half of
//! them face away), so every light item is also measured on its lit and its dark points
//! apart, and `host-sim budget` counts, per object and light, how many calls of the scene give
//! light (the `:lit` cost) and how many give none (the `:dark` cost).

use arealight::raster::{
    mesh, Affine, Band, Camera, Cull, DrawOptions, DrawStats, EncodeTable, Encoding, Lit, Material,
    Mesh, PreparedMesh, PreparedVertex, Projection, RasterError, Rgb565, Shader, Shading, Vertex,
};
use arealight::{
    Ambient, CapLight, DirectionalLight, Illuminant, PhongLobe, PointLight, PolygonLight, Real,
    Rgb, Scene, SceneLight, SphereLight, UnitVec3, Vec3,
};

use super::{BACKGROUND, HEIGHT, WIDTH};

/// Shading points per light call item.
pub const POINTS: usize = 32;

/// One measurement: `ticks` of the caller's clock for `count` units of `item` (and, for the
/// raster items, the triangle setups and shader calls the draws made).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sample {
    /// What was timed (see the module docs).
    pub item: &'static str,
    /// Units of work (calls, vertices, bands or pixels).
    pub count: u32,
    /// Triangle setups of a raster item (0 otherwise).
    pub setups: u32,
    /// Shader calls of a raster item (0 otherwise).
    pub calls: u32,
    /// Clock ticks.
    pub ticks: u32,
}

const SPHERE_STACKS: u16 = 10;
const SPHERE_SLICES: u16 = 20;
const SPHERE_VERTICES: usize = (SPHERE_STACKS as usize + 1) * (SPHERE_SLICES as usize + 1);
const SPHERE_TRIANGLES: usize = 2 * SPHERE_SLICES as usize * (SPHERE_STACKS as usize - 1);
const GRID: u16 = 16;
const GRID_VERTICES: usize = (GRID as usize + 1) * (GRID as usize + 1);
const GRID_TRIANGLES: usize = 2 * GRID as usize * GRID as usize;

/// The calibration's storage (no allocation; a `const fn`, for a `static`): about 30 KiB with
/// `Fixed22`.
pub struct CalibrationBuffers<T> {
    sphere_vertices: [Vertex<T>; SPHERE_VERTICES],
    sphere_triangles: [[u16; 3]; SPHERE_TRIANGLES],
    grid_vertices: [Vertex<T>; GRID_VERTICES],
    grid_triangles: [[u16; 3]; GRID_TRIANGLES],
    square_vertices: [Vertex<T>; 4],
    square_triangles: [[u16; 3]; 2],
    prepared: [PreparedVertex<T>; GRID_VERTICES],
    table: EncodeTable,
}

impl<T: Real> CalibrationBuffers<T> {
    const ZERO_VERTEX: Vertex<T> = Vertex::new(
        Vec3::new(T::ZERO, T::ZERO, T::ZERO),
        Vec3::new(T::ZERO, T::ZERO, T::ZERO),
    );
    /// Zeroed buffers ([`run`] fills them).
    pub const fn new() -> Self {
        CalibrationBuffers {
            sphere_vertices: [Self::ZERO_VERTEX; SPHERE_VERTICES],
            sphere_triangles: [[0; 3]; SPHERE_TRIANGLES],
            grid_vertices: [Self::ZERO_VERTEX; GRID_VERTICES],
            grid_triangles: [[0; 3]; GRID_TRIANGLES],
            square_vertices: [Self::ZERO_VERTEX; 4],
            square_triangles: [[0; 3]; 2],
            prepared: [PreparedVertex::EMPTY; GRID_VERTICES],
            table: EncodeTable::zeroed(),
        }
    }
}

impl<T: Real> Default for CalibrationBuffers<T> {
    fn default() -> Self {
        Self::new()
    }
}

/// A constant colour, whatever the point (the shader of an emissive object).
struct Flat<T>(Rgb<T>);

impl<T: Real> Shader<T> for Flat<T> {
    fn shade(&self, _p: Vec3<T>, _n: UnitVec3<T>, _v: UnitVec3<T>) -> Rgb<T> {
        // Opaque, as an emissive object's colour is data (the encoding is not hoisted).
        core::hint::black_box(self.0)
    }
}

/// A constant colour that takes the point, the normal and the view vector it is given (through
/// `black_box`), as a lit shader does: with [`Flat`], which ignores them, the compiler drops
/// the rasterizer's per-call work for them (the interpolated normal normalized, the view
/// vector), which every lit object pays.
struct Probe<T>(Rgb<T>);

impl<T: Real> Shader<T> for Probe<T> {
    fn shade(&self, p: Vec3<T>, n: UnitVec3<T>, v: UnitVec3<T>) -> Rgb<T> {
        core::hint::black_box((p, n, v));
        // Opaque, so that the colour's encoding is not hoisted out of the loop either.
        core::hint::black_box(self.0)
    }
}

/// No light at all (for the material's own cost): black, which the compiler cannot see
/// through (so the material's products and the reflection are not folded away).
struct Dark;

impl<T: Real> Illuminant<T> for Dark {
    fn diffuse(&self, _p: Vec3<T>, _n: UnitVec3<T>) -> Rgb<T> {
        core::hint::black_box(Rgb::splat(T::ZERO))
    }
    fn phong(&self, _lobe: &PhongLobe<T>, _p: Vec3<T>, _r: UnitVec3<T>) -> Rgb<T> {
        core::hint::black_box(Rgb::splat(T::ZERO))
    }
}

fn v3<T: Real>(x: f64, y: f64, z: f64) -> Vec3<T> {
    Vec3::from_f64([x, y, z])
}

/// The shading points: `(p, n, v, r)` for [`POINTS`] directions.
struct Points<T> {
    p: [Vec3<T>; POINTS],
    n: [UnitVec3<T>; POINTS],
    v: [UnitVec3<T>; POINTS],
    r: [UnitVec3<T>; POINTS],
}

fn points<T: Real>() -> Points<T> {
    let eye = [0.0, 0.8, 3.3];
    let zero = v3::<T>(0.0, 0.0, 0.0);
    let z = UnitVec3::z_axis();
    let mut out = Points {
        p: [zero; POINTS],
        n: [z; POINTS],
        v: [z; POINTS],
        r: [z; POINTS],
    };
    let golden = core::f64::consts::PI * (3.0 - 2.236_067_977_499_79);
    for i in 0..POINTS {
        let y = 1.0 - (2.0 * i as f64 + 1.0) / POINTS as f64;
        let ring = libm::sqrt(1.0 - y * y);
        let a = golden * i as f64;
        let n = [ring * libm::cos(a), y, ring * libm::sin(a)];
        let p = n.map(|c| 0.6 * c);
        let d = [eye[0] - p[0], eye[1] - p[1], eye[2] - p[2]];
        let len = libm::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        let v = d.map(|c| c / len);
        let nv = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
        let r = [0, 1, 2].map(|k| 2.0 * nv * n[k] - v[k]);
        out.p[i] = Vec3::from_f64(p);
        // Unit vectors, normalized once (as the rasterizer hands them to the shader).
        let unit = |d: [f64; 3]| Vec3::from_f64(d).to_unit().unwrap_or(z);
        out.n[i] = unit(n);
        out.v[i] = unit(v);
        out.r[i] = unit(r);
    }
    out
}

/// Times `f` once: the ticks between two clock reads around it.
fn time(clock: &mut impl FnMut() -> u32, f: impl FnOnce()) -> u32 {
    let t0 = clock();
    f();
    clock().wrapping_sub(t0)
}

/// Times `call` at every point, then at the points where it gives light (`lit`: a non-zero
/// channel) and at those where it gives none (`dark`: the early exits, a light behind the
/// surface or a lobe that misses it), each subset in a loop of its own: the samples `name`,
/// `lit` and `dark` (a subset with no point gives a sample of count 0).
fn split_item<T: Real>(
    names: [&'static str; 3],
    call: impl Fn(usize) -> Rgb<T>,
    clock: &mut impl FnMut() -> u32,
    out: &mut impl FnMut(Sample),
) {
    let mut sink = T::ZERO;
    let ticks = time(clock, || {
        for i in 0..POINTS {
            sink += core::hint::black_box(call(i)).r;
        }
    });
    out(sample(names[0], POINTS as u32, ticks));
    let (mut lit, mut dark) = ([0u8; POINTS], [0u8; POINTS]);
    let (mut n_lit, mut n_dark) = (0, 0);
    for i in 0..POINTS {
        let c = call(i);
        if c.r > T::ZERO || c.g > T::ZERO || c.b > T::ZERO {
            lit[n_lit] = i as u8;
            n_lit += 1;
        } else {
            dark[n_dark] = i as u8;
            n_dark += 1;
        }
    }
    for (name, subset) in [(names[1], &lit[..n_lit]), (names[2], &dark[..n_dark])] {
        let ticks = time(clock, || {
            for &i in subset {
                sink += core::hint::black_box(call(usize::from(i))).r;
            }
        });
        out(sample(name, subset.len() as u32, ticks));
    }
    core::hint::black_box(sink);
}

/// One light's `diffuse` and `phong` (m = 8, 32) items, each also split into its `:lit` and
/// `:dark` calls ([`split_item`]).
fn light_items<T: Real>(
    names: [[&'static str; 3]; 3],
    light: SceneLight<T, 4>,
    pts: &Points<T>,
    lobes: &[PhongLobe<T>; 2],
    clock: &mut impl FnMut() -> u32,
    out: &mut impl FnMut(Sample),
) -> Result<(), RasterError> {
    // The light as the firmware calls it: in a `Scene` (its dispatch, colour and culling
    // tests included), behind `black_box` so that it is data, as a scene's lights are (the
    // compiler cannot fold its constants into the calls).
    let mut scene = Scene::<T, 1, 4>::new();
    scene
        .push(light, Rgb::splat(T::ONE))
        .map_err(|_| RasterError::BadParameter("calibration scene"))?;
    let scene = core::hint::black_box(&scene);
    split_item(names[0], |i| scene.diffuse(pts.p[i], pts.n[i]), clock, out);
    for (name, lobe) in names[1..].iter().zip(lobes) {
        split_item(*name, |i| scene.phong(lobe, pts.p[i], pts.r[i]), clock, out);
    }
    Ok(())
}

/// The names of one light kind's items: `diffuse:<kind>`, `phong8:<kind>`, `phong32:<kind>`,
/// each with its `:lit` and `:dark` subsets.
macro_rules! items {
    ($kind:literal) => {
        [
            [
                concat!("diffuse:", $kind),
                concat!("diffuse:", $kind, ":lit"),
                concat!("diffuse:", $kind, ":dark"),
            ],
            [
                concat!("phong8:", $kind),
                concat!("phong8:", $kind, ":lit"),
                concat!("phong8:", $kind, ":dark"),
            ],
            [
                concat!("phong32:", $kind),
                concat!("phong32:", $kind, ":lit"),
                concat!("phong32:", $kind, ":dark"),
            ],
        ]
    };
}

fn sample(item: &'static str, count: u32, ticks: u32) -> Sample {
    Sample {
        item,
        count,
        setups: 0,
        calls: 0,
        ticks,
    }
}

/// Measures every item of the module docs with `clock`, handing each [`Sample`] to `out` as
/// soon as it is measured. `band`: a [`WIDTH`]-wide band of the firmware's own height (its
/// rows decide the bands per frame, as in the firmware).
///
/// # Errors
/// None with the constants here; the constructors' errors otherwise.
pub fn run<T: Real>(
    buffers: &mut CalibrationBuffers<T>,
    band: &mut Band<'_, Rgb565>,
    clock: &mut impl FnMut() -> u32,
    out: &mut impl FnMut(Sample),
) -> Result<(), RasterError> {
    let pts = points::<T>();
    let lobes = [PhongLobe::new(8)?, PhongLobe::new(32)?];

    // The lights, as the demo places its own (and a few kinds it does not use).
    let panel = PolygonLight::<T, 4>::new(&[
        v3(-1.0, 1.9, -1.0),
        v3(1.0, 1.9, -1.0),
        v3(1.0, 1.9, 0.4),
        v3(-1.0, 1.9, 0.4),
    ])?;
    light_items(
        items!("polygon"),
        SceneLight::Polygon(panel),
        &pts,
        &lobes,
        clock,
        out,
    )?;
    let lamp = SphereLight::new(v3(0.07, 0.75, 1.3), T::from_f64(0.15))?;
    light_items(
        items!("sphere"),
        SceneLight::Sphere(lamp),
        &pts,
        &lobes,
        clock,
        out,
    )?;
    let cap = CapLight::new(v3(0.3, 1.0, 0.2), T::from_f64(0.3))?;
    light_items(
        items!("cap"),
        SceneLight::Cap(cap),
        &pts,
        &lobes,
        clock,
        out,
    )?;
    let point = PointLight::inverse_square(v3(1.0, 1.5, 1.0))?;
    light_items(
        items!("point"),
        SceneLight::Point(point),
        &pts,
        &lobes,
        clock,
        out,
    )?;
    let sun = DirectionalLight::new(v3(0.3, 1.0, 0.2))?;
    light_items(
        items!("directional"),
        SceneLight::Directional(sun),
        &pts,
        &lobes,
        clock,
        out,
    )?;
    let ambient = Ambient(Rgb::from_f64([0.03, 0.035, 0.05]));
    light_items(
        items!("ambient"),
        SceneLight::Ambient(ambient),
        &pts,
        &lobes,
        clock,
        out,
    )?;

    // The material's own work in `Lit::shade` (no light).
    let matte = Material::matte(Rgb::from_f64([0.8, 0.3, 0.2]))?;
    let glossy = Material::new(
        Rgb::from_f64([0.8, 0.3, 0.2]),
        Rgb::from_f64([0.4, 0.4, 0.4]),
        20,
    )?;
    for (name, material) in [("lit_matte", &matte), ("lit_specular", &glossy)] {
        let lit = Lit::new(&Dark, material);
        let mut sink = T::ZERO;
        let ticks = time(clock, || {
            for i in 0..POINTS {
                sink += core::hint::black_box(lit.shade(pts.p[i], pts.n[i], pts.v[i])).r;
            }
        });
        core::hint::black_box(sink);
        out(sample(name, POINTS as u32, ticks));
    }

    // The frame's stages on synthetic meshes.
    let CalibrationBuffers {
        sphere_vertices,
        sphere_triangles,
        grid_vertices,
        grid_triangles,
        square_vertices,
        square_triangles,
        prepared,
        table,
    } = buffers;
    table.fill::<T>(Encoding::Gamma2);
    let camera = Camera::new(
        v3(0.0, 0.8, 3.3),
        v3(0.0, 0.05, 0.0),
        v3(0.0, 1.0, 0.0),
        Projection::Perspective {
            fov_y: T::from_f64(0.8),
        },
        WIDTH,
        HEIGHT,
    )?
    .with_depth_range(T::from_f64(1.0), T::from_f64(6.0))?;
    let counts = mesh::uv_sphere(
        T::from_f64(0.55),
        SPHERE_STACKS,
        SPHERE_SLICES,
        sphere_vertices,
        sphere_triangles,
    )?;
    let sphere = Mesh::new(
        &sphere_vertices[..counts.vertices],
        &sphere_triangles[..counts.triangles],
    )?;
    let mut opts = DrawOptions::new(Shading::Gouraud);
    opts.cull = Cull::Back;
    opts.encoding = Encoding::Gamma2;
    let flat = Flat(Rgb::from_f64([0.5, 0.4, 0.3]));
    let probe = Probe(Rgb::from_f64([0.5, 0.4, 0.3]));
    let here = Affine::identity();
    {
        let mut sphere = PreparedMesh::new(sphere, &mut prepared[..])?;
        let n = counts.vertices as u32;
        let ticks = time(clock, || sphere.transform(&camera, &here));
        out(sample("vertex_lit", n, ticks));
        let ticks = time(clock, || sphere.transform_unlit(&camera, &here));
        out(sample("vertex_unlit", n, ticks));
        sphere.transform(&camera, &here);
        let mut calls = 0;
        let ticks = time(clock, || calls = sphere.shade(&camera, &probe, &opts));
        out(sample("shade_vertex", calls, ticks));
        // Transformed again, so that this shade finds the visible vertices too, as the first
        // did (a shade after a shade of the same vertex data skips that pass).
        sphere.transform(&camera, &here);
        let ticks = time(clock, || calls = sphere.shade(&camera, &flat, &opts));
        out(sample("shade_vertex_flat", calls, ticks));
    }

    // A 1.6 x 1.6 square facing the camera (about 130 pixels on a side), as 2 triangles and
    // as a 16 x 16 grid of cells.
    let face_on = Affine::rotation(v3(1.0, 0.0, 0.0), T::HALF * T::PI)?;
    let side = T::from_f64(1.6);
    let c = mesh::plane(side, side, 1, 1, square_vertices, square_triangles)?;
    let square = Mesh::new(
        &square_vertices[..c.vertices],
        &square_triangles[..c.triangles],
    )?;
    let c = mesh::plane(side, side, GRID, GRID, grid_vertices, grid_triangles)?;
    let grid = Mesh::new(&grid_vertices[..c.vertices], &grid_triangles[..c.triangles])?;

    let rows = band.rows().max(1);
    let mut clear_ticks = 0u32;
    let mut bands = 0u32;
    let per_pixel = {
        let mut o = opts;
        o.shading = Shading::PerPixel;
        o
    };
    for (name, mesh, o) in [
        ("raster_big", square, &opts),
        ("raster_grid", grid, &opts),
        ("raster_big_pp", square, &per_pixel),
    ] {
        let mut m = PreparedMesh::new(mesh, &mut prepared[..])?;
        m.transform(&camera, &face_on);
        m.shade(&camera, &flat, o);
        let mut stats = DrawStats::default();
        let mut ticks = 0u32;
        let mut y0 = 0u16;
        while y0 < HEIGHT {
            band.move_to(y0);
            let t = time(clock, || band.clear(BACKGROUND));
            if name == "raster_big" {
                clear_ticks = clear_ticks.wrapping_add(t);
                bands += 1;
            }
            let t0 = clock();
            let s = m.draw(&camera, band, &probe, o, table)?;
            ticks = ticks.wrapping_add(clock().wrapping_sub(t0));
            stats.rasterized += s.rasterized;
            stats.pixels += s.pixels;
            stats.shaded += s.shaded;
            y0 = y0.saturating_add(rows);
        }
        if name == "raster_big" {
            out(sample("band_clear", bands, clear_ticks));
        }
        out(Sample {
            item: name,
            count: stats.pixels,
            setups: stats.rasterized,
            calls: stats.shaded,
            ticks,
        });
    }
    Ok(())
}
