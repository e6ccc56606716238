//! Scenes rendered with the crate's own rasterizer (`arealight::raster`) and lights, and (in
//! `figures`) the built-in figures that reproduce the documents' pictures.
//!
//! Every figure is rendered in 16-row bands through one band buffer (as firmware would), into
//! RGB888 with the sRGB encoding.

use arealight::illuminant::{DirectionalLuminaire, Shaped};
use std::sync::atomic::{AtomicU16, Ordering};

use arealight::raster::{
    self, mesh, Affine, Band, Camera, Cull, DrawOptions, Encoding, Lit, Material, Mesh,
    PixelFormat, Projection, RasterError, Rgb888, Shading, ToneMap, Vertex,
};
use arealight::{
    Ambient, DirectionalLight, DistanceFalloff, Environment, Illuminant, LightFrame, LineLight,
    OvercastSky, ParallelogramLight, PhongLobe, PointLight, PolygonLight, Real, Rgb, Sh9,
    SkyGround, SphereLight, Superellipse, Tinted, Uberlight, UnitVec3, Vec3,
};

use crate::figure::{self, Panel};

mod figures;
pub use figures::figures;

/// `Vec3` from f64 literals.
pub fn v<T: Real>(x: f64, y: f64, z: f64) -> Vec3<T> {
    Vec3::new(T::from_f64(x), T::from_f64(y), T::from_f64(z))
}

/// `Rgb` from f64 literals.
pub fn c<T: Real>(r: f64, g: f64, b: f64) -> Rgb<T> {
    Rgb::new(T::from_f64(r), T::from_f64(g), T::from_f64(b))
}

/// A mesh owning its buffers.
#[derive(Clone)]
pub struct MeshBuf<T> {
    /// Vertices.
    pub verts: Vec<Vertex<T>>,
    /// Triangles.
    pub tris: Vec<[u16; 3]>,
}

fn zero_vertex<T: Real>() -> Vertex<T> {
    Vertex::new(v(0.0, 0.0, 0.0), v(0.0, 0.0, 0.0))
}

fn alloc<T: Real>(c: raster::MeshCounts) -> MeshBuf<T> {
    MeshBuf {
        verts: vec![zero_vertex(); c.vertices],
        tris: vec![[0; 3]; c.triangles],
    }
}

/// A UV sphere of radius `r`.
pub fn sphere<T: Real>(r: f64, stacks: u16, slices: u16) -> Result<MeshBuf<T>, RasterError> {
    let mut m = alloc(mesh::uv_sphere_counts(stacks, slices));
    mesh::uv_sphere(T::from_f64(r), stacks, slices, &mut m.verts, &mut m.tris)?;
    Ok(m)
}

/// A plane in y = 0 facing +y.
pub fn plane<T: Real>(sx: f64, sz: f64, nx: u16, nz: u16) -> Result<MeshBuf<T>, RasterError> {
    let mut m = alloc(mesh::plane_counts(nx, nz));
    mesh::plane(
        T::from_f64(sx),
        T::from_f64(sz),
        nx,
        nz,
        &mut m.verts,
        &mut m.tris,
    )?;
    Ok(m)
}

/// A box of half-extents `h`.
pub fn cuboid<T: Real>(h: [f64; 3]) -> Result<MeshBuf<T>, RasterError> {
    let mut m = alloc(mesh::cuboid_counts());
    mesh::cuboid(v(h[0], h[1], h[2]), &mut m.verts, &mut m.tris)?;
    Ok(m)
}

/// A torus around y.
pub fn torus<T: Real>(major: f64, minor: f64, a: u16, b: u16) -> Result<MeshBuf<T>, RasterError> {
    let mut m = alloc(mesh::torus_counts(a, b));
    mesh::torus(
        T::from_f64(major),
        T::from_f64(minor),
        a,
        b,
        &mut m.verts,
        &mut m.tris,
    )?;
    Ok(m)
}

/// A per-pixel shading function `(p, n, v) -> colour`.
pub type ShadeFn<T> = Box<dyn Fn(Vec3<T>, Vec3<T>, Vec3<T>) -> Rgb<T>>;

/// How an object is shaded.
pub enum Surface<T> {
    /// A material under the scene's lights.
    Lit(Material<T>),
    /// A custom shader (Arvo's glossy reflection and transmission).
    Custom(ShadeFn<T>),
    /// Constant radiance (a visible light source).
    Emissive(Rgb<T>),
}

/// A mesh placed in the scene with its surface.
pub struct Object<T> {
    /// The mesh.
    pub mesh: MeshBuf<T>,
    /// Model transform.
    pub xf: Affine<T>,
    /// Surface.
    pub surface: Surface<T>,
    /// Gouraud or per pixel.
    pub shading: Shading,
    /// Two-sided (no culling, normals flipped toward the viewer).
    pub two_sided: bool,
}

impl<T: Real> Object<T> {
    /// A one-sided, per-pixel object.
    pub fn new(mesh: MeshBuf<T>, xf: Affine<T>, surface: Surface<T>) -> Self {
        Object {
            mesh,
            xf,
            surface,
            shading: Shading::PerPixel,
            two_sided: false,
        }
    }
}

/// The sum of boxed lights.
pub struct Lights<T>(pub Vec<Box<dyn Illuminant<T>>>);

impl<T: Real> Illuminant<T> for Lights<T> {
    fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        self.0
            .iter()
            .fold(Rgb::splat(T::ZERO), |a, l| a.add(l.diffuse(p, n)))
    }
    fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
        self.0
            .iter()
            .fold(Rgb::splat(T::ZERO), |a, l| a.add(l.phong(lobe, p, r)))
    }
}

/// A scene: camera, objects, lights, exposure.
pub struct Scene<T> {
    /// The camera (and viewport size).
    pub camera: Camera<T>,
    /// The objects, drawn in order with a depth band.
    pub objects: Vec<Object<T>>,
    /// The lights of `Surface::Lit` objects.
    pub lights: Lights<T>,
    /// Multiplies every colour before encoding.
    pub exposure: T,
    /// Clear colour (encoded 8-bit sRGB).
    pub background: [u8; 3],
    /// The output transfer function.
    pub encoding: Encoding,
}

/// Rows per band when rendering.
pub const BAND_ROWS: u16 = 16;

/// What a frame is rendered with: camera, exposure and encoding (a scene's own, or others
/// for the same objects and lights).
pub struct View<'a, T> {
    /// The camera (and viewport size).
    pub camera: &'a Camera<T>,
    /// Multiplies every colour before encoding.
    pub exposure: T,
    /// The output transfer function.
    pub encoding: Encoding,
}

/// Renders `scene` in bands of `band_rows` rows into a full frame of `P`, cleared to
/// `background`.
pub fn render<T: Real, P: PixelFormat + Default>(
    scene: &Scene<T>,
    band_rows: u16,
    background: P,
) -> Result<Vec<P>, RasterError> {
    let view = View {
        camera: &scene.camera,
        exposure: scene.exposure,
        encoding: scene.encoding,
    };
    render_view(scene, &view, band_rows, background)
}

/// Renders the objects and lights of `scene` as `view` sees them, in bands of `band_rows`
/// rows into a full frame of `P`, cleared to `background`.
pub fn render_view<T: Real, P: PixelFormat + Default>(
    scene: &Scene<T>,
    view: &View<'_, T>,
    band_rows: u16,
    background: P,
) -> Result<Vec<P>, RasterError> {
    let (w, h) = (view.camera.width(), view.camera.height());
    let mut frame = Vec::with_capacity(w as usize * h as usize);
    let mut px = vec![P::default(); w as usize * band_rows as usize];
    let mut depth = vec![0u16; px.len()];
    let mut band = Band::new(&mut px, Some(&mut depth), w, 0)?;
    raster::render_in_bands(
        &mut band,
        h,
        background,
        |b| draw_scene(scene, view, b),
        |b| {
            let keep = (h - b.y0()).min(b.rows()) as usize * w as usize;
            frame.extend_from_slice(&b.pixels()[..keep]);
            Ok(())
        },
    )?;
    Ok(frame)
}

fn draw_scene<T: Real, P: PixelFormat>(
    scene: &Scene<T>,
    view: &View<'_, T>,
    band: &mut Band<'_, P>,
) -> Result<(), RasterError> {
    let camera = view.camera;
    for o in &scene.objects {
        let mesh = Mesh::new(&o.mesh.verts, &o.mesh.tris)?;
        let mut opts = DrawOptions::new(o.shading);
        opts.exposure = view.exposure;
        opts.encoding = view.encoding;
        if o.two_sided {
            opts.cull = Cull::None;
            opts.two_sided = true;
        }
        match &o.surface {
            Surface::Lit(m) => {
                raster::draw(
                    camera,
                    band,
                    &mesh,
                    &o.xf,
                    &Lit::new(&scene.lights, m),
                    &opts,
                )?;
            }
            Surface::Custom(f) => {
                let shade = |p, n: UnitVec3<T>, v: UnitVec3<T>| f(p, *n, *v);
                raster::draw(camera, band, &mesh, &o.xf, &shade, &opts)?;
            }
            Surface::Emissive(e) => {
                let e = *e;
                let shade = move |_, _, _| e;
                raster::draw(camera, band, &mesh, &o.xf, &shade, &opts)?;
            }
        }
    }
    Ok(())
}

/// A pixel of linear values: the three encoded channels as f64 (with [`Encoding::Linear`]:
/// the linear colour times the exposure, clamped to [0, 1]), and whether anything was drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LinearPx {
    /// Channels in [0, 1].
    pub rgb: [f64; 3],
    /// `false` for the background.
    pub covered: bool,
}

impl PixelFormat for LinearPx {
    fn from_unit<T: Real>(r: T, g: T, b: T) -> Self {
        LinearPx {
            rgb: [r.to_f64(), g.to_f64(), b.to_f64()],
            covered: true,
        }
    }
    fn to_rgb8(self) -> [u8; 3] {
        self.rgb.map(|x| figure::srgb8(x as f32))
    }
}

/// Supersampling of the built-in figures and scene files: each pixel is the mean of `k` x `k`
/// samples (see [`panel`]).
pub const DEFAULT_AA: u16 = 3;
/// The largest supersampling factor (`k` x `k` samples per pixel).
pub const MAX_AA: u16 = 8;

static AA: AtomicU16 = AtomicU16::new(DEFAULT_AA);

/// Sets the supersampling factor of this run's panels (clamped to `1..=MAX_AA`; 1: none).
pub fn set_supersampling(k: u16) {
    AA.store(k.clamp(1, MAX_AA), Ordering::Relaxed);
}

/// The supersampling factor of this run's panels.
pub fn supersampling() -> u16 {
    AA.load(Ordering::Relaxed)
}

/// The linear value of an encoded channel `e` in [0, 1] (the inverse of the transfer function;
/// the tone curve is not inverted: backgrounds sit below its knee).
fn decode(enc: Encoding, e: f64) -> f64 {
    match enc {
        Encoding::Linear => e,
        Encoding::Gamma2 => e * e,
        _ => {
            if e <= 0.040_45 {
                e / 12.92
            } else {
                ((e + 0.055) / 1.055).powf(2.4)
            }
        }
    }
}

/// Renders to an sRGB panel, supersampled `k` x `k` ([`supersampling`]; 1: one sample per
/// pixel, the rasterizer's own output).
///
/// Supersampling renders the frame `k` times wider and higher with the same camera
/// ([`Camera::with_viewport`]) into linear values (the exposure divided by the encoding's
/// white point, so that nothing the encoding would show clips), averages each `k` x `k` block
/// in linear light (samples the background fills count as the background colour, decoded),
/// then encodes the mean with the scene's encoding. A pixel no sample covers is the background
/// colour exactly.
pub fn panel<T: Real>(scene: &Scene<T>, title: &str) -> Result<Panel, RasterError> {
    let k = supersampling();
    let (w, h) = (scene.camera.width(), scene.camera.height());
    let rgb = if k <= 1 {
        let px: Vec<Rgb888> = render(scene, BAND_ROWS, Rgb888(scene.background))?;
        px.into_iter().map(|p| p.0).collect()
    } else {
        supersample(scene, k)?
    };
    Ok(Panel {
        title: title.to_string(),
        w: w as u32,
        h: h as u32,
        rgb,
    })
}

fn supersample<T: Real>(scene: &Scene<T>, k: u16) -> Result<Vec<[u8; 3]>, RasterError> {
    let (w, h) = (
        scene.camera.width() as usize,
        scene.camera.height() as usize,
    );
    let kk = k as usize;
    let camera = scene
        .camera
        .with_viewport(scene.camera.width() * k, scene.camera.height() * k)?;
    let white: T = scene.encoding.white();
    let view = View {
        camera: &camera,
        exposure: scene.exposure / white,
        encoding: Encoding::Linear,
    };
    let px = render_view(scene, &view, BAND_ROWS, LinearPx::default())?;
    let white = white.to_f64();
    let bg = scene
        .background
        .map(|c| decode(scene.encoding, f64::from(c) / 255.0) / white);
    let n = (kk * kk) as f64;
    let mut out = Vec::with_capacity(w * h);
    for y in 0..h {
        for x in 0..w {
            let mut sum = [0.0f64; 3];
            let mut covered = 0;
            for j in 0..kk {
                let row = (y * kk + j) * w * kk;
                for i in 0..kk {
                    let p = px[row + x * kk + i];
                    let v = if p.covered {
                        covered += 1;
                        p.rgb
                    } else {
                        bg
                    };
                    for c in 0..3 {
                        sum[c] += v[c];
                    }
                }
            }
            if covered == 0 {
                out.push(scene.background);
                continue;
            }
            let c = arealight::Rgb::new(sum[0] / n, sum[1] / n, sum[2] / n);
            let p: Rgb888 = raster::encode_pixel(c, white, scene.encoding);
            out.push(p.0);
        }
    }
    Ok(out)
}

/// The tone curve of the figures whose highlights exceed the display's white: linear up to
/// the knee, compressed above it to reach white at the white point (see [`ToneMap`]).
pub fn figure_tone() -> Result<Encoding, RasterError> {
    Ok(Encoding::SrgbTone(ToneMap::new(FIGURE_KNEE, FIGURE_WHITE)?))
}

/// The figures' tone curve's knee, percent of display white.
pub const FIGURE_KNEE: u8 = 50;
/// The figures' tone curve's white point, percent of display white.
pub const FIGURE_WHITE: u16 = 400;

/// `0.8 / (largest channel of the diffuse term at p, n)`: the exposure that shows a reference
/// surface at 80 % (1 when the light gives nothing there).
pub fn exposure_at<T: Real>(light: &dyn Illuminant<T>, p: Vec3<T>, n: Vec3<T>) -> T {
    let Some(n) = n.to_unit() else {
        return T::ONE;
    };
    let d = light.diffuse(p, n);
    let m = d.r.max(d.g).max(d.b);
    if m > T::ZERO {
        T::from_f64(0.8) / m
    } else {
        T::ONE
    }
}

fn camera<T: Real>(
    eye: [f64; 3],
    target: [f64; 3],
    fov_deg: f64,
    w: u16,
    h: u16,
) -> Result<Camera<T>, RasterError> {
    Camera::new(
        Vec3::from_f64(eye),
        Vec3::from_f64(target),
        v(0.0, 1.0, 0.0),
        Projection::Perspective {
            fov_y: T::from_f64(fov_deg.to_radians()),
        },
        w,
        h,
    )
}

fn translate<T: Real>(x: f64, y: f64, z: f64) -> Result<Affine<T>, RasterError> {
    Affine::translation(v(x, y, z))
}

fn rotate<T: Real>(axis: [f64; 3], deg: f64) -> Result<Affine<T>, RasterError> {
    Affine::rotation(Vec3::from_f64(axis), T::from_f64(deg.to_radians()))
}

// ---------------------------------------------------------------------------------------
// Snyder figure 7: one scene under five lights.

/// The five light kinds of Snyder's figure 7.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SnyderLight {
    /// (a) non-area directional.
    Directional,
    /// (b) non-area positional.
    Positional,
    /// (c) overcast sky.
    Overcast,
    /// (d) finite sphere.
    Sphere,
    /// (e) polygon.
    Polygon,
}

impl SnyderLight {
    /// All five, in the figure's order.
    pub const ALL: [SnyderLight; 5] = [
        SnyderLight::Directional,
        SnyderLight::Positional,
        SnyderLight::Overcast,
        SnyderLight::Sphere,
        SnyderLight::Polygon,
    ];
    /// The figure's caption.
    pub fn title(self) -> &'static str {
        match self {
            SnyderLight::Directional => "(a) non-area directional",
            SnyderLight::Positional => "(b) non-area positional",
            SnyderLight::Overcast => "(c) overcast sky",
            SnyderLight::Sphere => "(d) finite spherical",
            SnyderLight::Polygon => "(e) polygonal",
        }
    }
}

/// Snyder's figure 7 scene (floor, sphere, torus, box) under one light, `w` x `h`.
pub fn snyder_scene<T: Real + 'static>(
    kind: SnyderLight,
    w: u16,
    h: u16,
) -> Result<Scene<T>, RasterError> {
    let dir = [-0.55, 1.0, 0.65];
    let len = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
    let at = |d: f64| v::<T>(dir[0] / len * d, dir[1] / len * d, dir[2] / len * d);
    let light: Box<dyn Illuminant<T>> = match kind {
        SnyderLight::Directional => Box::new(DirectionalLight::new(Vec3::from_f64(dir))?),
        SnyderLight::Positional => Box::new(PointLight::new(at(3.2))?),
        SnyderLight::Overcast => Box::new(OvercastSky::new(v(0.0, 1.0, 0.0), T::ONE)?),
        SnyderLight::Sphere => Box::new(SphereLight::new(at(3.2), T::from_f64(0.7))?),
        SnyderLight::Polygon => {
            // A 2.0 x 1.2 panel facing the origin, 3.2 along the light direction.
            let l = at(1.0);
            let u = v::<T>(0.0, 1.0, 0.0).cross(l).try_normalize("u")?;
            let w2 = l.cross(u);
            let (ce, hu, hw) = (at(3.2), u * T::from_f64(1.0), w2 * T::from_f64(0.6));
            Box::new(PolygonLight::<T, 4>::new(&[
                ce - hu - hw,
                ce + hu - hw,
                ce + hu + hw,
                ce - hu + hw,
            ])?)
        }
    };
    let exposure = exposure_at(&*light, v(0.0, 0.0, 0.0), v(0.0, 1.0, 0.0));
    let red = Material::new(c(0.85, 0.22, 0.15), c(0.5, 0.5, 0.5), 24)?;
    let gold = Material::new(c(0.8, 0.6, 0.2), c(0.6, 0.6, 0.5), 12)?;
    let blue = Material::new(c(0.25, 0.35, 0.8), c(0.3, 0.3, 0.3), 8)?;
    let floor = Material::new(c(0.6, 0.6, 0.58), c(0.0, 0.0, 0.0), 1)?;
    let objects = vec![
        Object::new(
            plane(8.0, 8.0, 8, 8)?,
            Affine::identity(),
            Surface::Lit(floor),
        ),
        Object::new(
            sphere(0.7, 16, 28)?,
            translate(-0.95, 0.7, 0.1)?,
            Surface::Lit(red),
        ),
        Object::new(
            torus(0.55, 0.22, 32, 14)?,
            translate(1.05, 0.22, 0.45)?,
            Surface::Lit(gold),
        ),
        Object::new(
            cuboid([0.45, 0.45, 0.45])?,
            rotate([0.0, 1.0, 0.0], 30.0)?.then(&translate(0.35, 0.45, -1.3)?),
            Surface::Lit(blue),
        ),
    ];
    Ok(Scene {
        camera: camera([0.0, 2.7, 5.2], [0.0, 0.35, -0.1], 42.0, w, h)?,
        objects,
        lights: Lights(vec![light]),
        exposure,
        background: [20, 22, 30],
        encoding: figure_tone()?,
    })
}
