//! A scene's frame as the board firmware renders it, counted: every object through
//! [`PreparedMesh`] (transformed once per frame, Gouraud vertices shaded once, then band by
//! band into a frame of RGB888), with the work each stage does per object. The same code path
//! as `boards/demo-scene` (the firmware's frame), so that its counts are the firmware's.

use std::cell::RefCell;

use arealight::raster::{
    Band, Cull, DrawOptions, EncodeTable, Lit, Mesh, PreparedMesh, PreparedVertex, RasterError,
    Rgb888, Shader, Shading,
};
use arealight::{Illuminant, PhongLobe, Real, Rgb, UnitVec3, Vec3};

use crate::scenes::{Lights, Scene, Surface};

/// One light's calls in one stage of one object: its `diffuse` and its `phong` calls, each
/// split into those that gave light (`[0]`: a non-zero channel) and those that gave none
/// (`[1]`: the early exits, which cost less: see `demo_scene::calibrate`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LightCalls {
    /// `diffuse` calls: [lit, dark].
    pub diffuse: [u64; 2],
    /// `phong` calls: [lit, dark].
    pub phong: [u64; 2],
}

/// The scene's lights, counting each light's calls ([`LightCalls`]); the same sums, in the
/// same order, as [`Lights`] (so the frame is the same).
struct Counting<'a, T> {
    lights: &'a Lights<T>,
    calls: RefCell<Vec<LightCalls>>,
}

impl<'a, T> Counting<'a, T> {
    fn new(lights: &'a Lights<T>) -> Self {
        Counting {
            lights,
            calls: RefCell::new(vec![LightCalls::default(); lights.0.len()]),
        }
    }
}

/// 0 for a colour with light in a channel, 1 for black.
fn dark<T: Real>(c: Rgb<T>) -> usize {
    usize::from(!(c.r > T::ZERO || c.g > T::ZERO || c.b > T::ZERO))
}

impl<T: Real> Illuminant<T> for Counting<'_, T> {
    fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        let mut calls = self.calls.borrow_mut();
        self.lights
            .0
            .iter()
            .zip(calls.iter_mut())
            .fold(Rgb::splat(T::ZERO), |a, (l, c)| {
                let d = l.diffuse(p, n);
                c.diffuse[dark(d)] += 1;
                a.add(d)
            })
    }
    fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
        let mut calls = self.calls.borrow_mut();
        self.lights
            .0
            .iter()
            .zip(calls.iter_mut())
            .fold(Rgb::splat(T::ZERO), |a, (l, c)| {
                let d = l.phong(lobe, p, r);
                c.phong[dark(d)] += 1;
                a.add(d)
            })
    }
}

/// What one object cost a frame.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ObjectWork {
    /// Vertices transformed with their normals (lit objects).
    pub vertices_lit: u64,
    /// Vertices transformed without normals (emissive objects).
    pub vertices_unlit: u64,
    /// Shader calls at vertices (Gouraud), once per frame.
    pub vertex_calls: u64,
    /// Shader calls at pixels (per pixel).
    pub pixel_calls: u64,
    /// Pixels written (depth test passed).
    pub pixels: u64,
    /// Triangle setups (per band, clipped pieces counted).
    pub setups: u64,
    /// Per light of the scene, its calls at the vertices (empty for an emissive object).
    pub vertex_lights: Vec<LightCalls>,
    /// Per light of the scene, its calls at the pixels (empty for an emissive object).
    pub pixel_lights: Vec<LightCalls>,
}

/// What a frame cost: per object, and the frame's bands.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Work {
    /// Per object, in the scene's order.
    pub objects: Vec<ObjectWork>,
    /// Bands drawn (and sent).
    pub bands: u64,
    /// Bytes sent to an RGB565 display.
    pub bytes: u64,
}

impl Work {
    /// The sum over objects of `f`.
    pub fn total(&self, f: impl Fn(&ObjectWork) -> u64) -> u64 {
        self.objects.iter().map(f).sum()
    }
}

/// A constant colour (an emissive object's shader).
struct Glow<T>(Rgb<T>);

impl<T: Real> Shader<T> for Glow<T> {
    fn shade(&self, _p: Vec3<T>, _n: UnitVec3<T>, _v: UnitVec3<T>) -> Rgb<T> {
        self.0
    }
}

/// Renders `scene` with `shading[i]` for object `i` (emissive objects are always Gouraud, as
/// in the firmware) through bands of `band_rows` rows: the frame (RGB888, row-major) and the
/// work counted.
///
/// # Errors
/// The rasterizer's ([`RasterError`]); a custom-shaded object (not in scene files) is refused
/// as [`RasterError::BadParameter`].
pub fn render<T: Real + 'static>(
    scene: &Scene<T>,
    shading: &[Shading],
    band_rows: u16,
) -> Result<(Vec<[u8; 3]>, Work), RasterError> {
    let cam = &scene.camera;
    let (w, h) = (cam.width(), cam.height());
    let table = EncodeTable::new::<T>(scene.encoding);
    let mut storage: Vec<Vec<PreparedVertex<T>>> = scene
        .objects
        .iter()
        .map(|o| vec![PreparedVertex::EMPTY; o.mesh.verts.len()])
        .collect();
    let meshes: Vec<Mesh<'_, T>> = scene
        .objects
        .iter()
        .map(|o| Mesh::new(&o.mesh.verts, &o.mesh.tris))
        .collect::<Result<_, _>>()?;
    let mut work = Work {
        objects: vec![ObjectWork::default(); scene.objects.len()],
        ..Work::default()
    };
    let mut prepared = Vec::new();
    let mut options = Vec::new();
    // Each object's lights, counting its calls at the vertices, then at the pixels.
    let counting: Vec<[Counting<'_, T>; 2]> = scene
        .objects
        .iter()
        .map(|_| [Counting::new(&scene.lights), Counting::new(&scene.lights)])
        .collect();
    for (i, ((o, mesh), store)) in scene
        .objects
        .iter()
        .zip(&meshes)
        .zip(storage.iter_mut())
        .enumerate()
    {
        let emissive = matches!(o.surface, Surface::Emissive(_));
        let mut opts = DrawOptions::new(if emissive {
            Shading::Gouraud
        } else {
            shading.get(i).copied().unwrap_or(o.shading)
        });
        opts.exposure = scene.exposure * table.exposure_scale::<T>();
        opts.encoding = scene.encoding;
        if o.two_sided {
            opts.cull = Cull::None;
            opts.two_sided = true;
        } else {
            opts.cull = Cull::Back;
        }
        let mut p = PreparedMesh::new(*mesh, &mut store[..])?;
        let ow = &mut work.objects[i];
        let n = mesh.vertices().len() as u64;
        let calls = match &o.surface {
            Surface::Lit(m) => {
                p.transform(cam, &o.xf);
                ow.vertices_lit = n;
                p.shade(cam, &Lit::new(&counting[i][0], m), &opts)
            }
            Surface::Emissive(c) => {
                p.transform_unlit(cam, &o.xf);
                ow.vertices_unlit = n;
                p.shade(cam, &Glow(*c), &opts)
            }
            Surface::Custom(_) => return Err(RasterError::BadParameter("custom shader")),
        };
        ow.vertex_calls = u64::from(calls);
        prepared.push(p);
        options.push(opts);
    }

    let mut frame = Vec::with_capacity(usize::from(w) * usize::from(h));
    let rows = band_rows.max(1);
    let mut px = vec![Rgb888([0; 3]); usize::from(w) * usize::from(rows)];
    let mut depth = vec![0u16; px.len()];
    let mut band = Band::new(&mut px, Some(&mut depth), w, 0)?;
    let mut y0 = 0u16;
    while y0 < h {
        band.move_to(y0);
        band.clear(Rgb888(scene.background));
        for (i, ((o, p), opts)) in scene
            .objects
            .iter()
            .zip(&prepared)
            .zip(&options)
            .enumerate()
        {
            let stats = match &o.surface {
                Surface::Lit(m) => {
                    p.draw(cam, &mut band, &Lit::new(&counting[i][1], m), opts, &table)?
                }
                Surface::Emissive(c) => p.draw(cam, &mut band, &Glow(*c), opts, &table)?,
                Surface::Custom(_) => return Err(RasterError::BadParameter("custom shader")),
            };
            let ow = &mut work.objects[i];
            ow.pixel_calls += u64::from(stats.shaded);
            ow.pixels += u64::from(stats.pixels);
            ow.setups += u64::from(stats.rasterized);
        }
        let keep = usize::from((h - y0).min(rows)) * usize::from(w);
        frame.extend(band.pixels()[..keep].iter().map(|p| p.0));
        work.bands += 1;
        work.bytes += 2 * keep as u64;
        y0 = y0.saturating_add(rows);
    }
    for (o, (ow, [v, px])) in scene
        .objects
        .iter()
        .zip(work.objects.iter_mut().zip(counting))
    {
        if matches!(o.surface, Surface::Lit(_)) {
            ow.vertex_lights = v.calls.into_inner();
            ow.pixel_lights = px.calls.into_inner();
        }
    }
    Ok((frame, work))
}

/// Per-pixel error of `got` against `want` (both RGB888, the same size), in 8-bit display
/// levels: the largest channel difference of each pixel; returns (max, mean) over the frame.
pub fn image_error(got: &[[u8; 3]], want: &[[u8; 3]]) -> (f64, f64) {
    let mut max = 0u8;
    let mut sum = 0u64;
    for (a, b) in got.iter().zip(want) {
        let d = (0..3).map(|k| a[k].abs_diff(b[k])).max().unwrap_or(0);
        max = max.max(d);
        sum += u64::from(d);
    }
    let n = got.len().max(1) as f64;
    (f64::from(max), sum as f64 / n)
}
