//! Scenes rendered with the crate's own rasterizer (`arealight::raster`) and lights, and the
//! built-in figures that reproduce the documents' pictures.
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

/// A built-in figure: file name, and a function that renders it.
pub struct Figure {
    /// PNG file name.
    pub file: &'static str,
    /// Renders the sheet.
    pub render: fn() -> Result<tiny_skia::Pixmap, RasterError>,
}

/// Every built-in figure.
pub fn figures() -> Vec<Figure> {
    vec![
        Figure {
            file: "snyder_fig7.png",
            render: snyder_fig7,
        },
        Figure {
            file: "june_fig20_3.png",
            render: june_fig20_3,
        },
        Figure {
            file: "june_fig20_9.png",
            render: june_fig20_9,
        },
        Figure {
            file: "june_fig20_17.png",
            render: june_fig20_17,
        },
        Figure {
            file: "arvo_fig5.png",
            render: arvo_fig5,
        },
        Figure {
            file: "arvo_fig8.png",
            render: arvo_fig8,
        },
        Figure {
            file: "picott_plates.png",
            render: picott_plates,
        },
    ]
}

fn snyder_fig7() -> Result<tiny_skia::Pixmap, RasterError> {
    let mut panels = Vec::new();
    for kind in SnyderLight::ALL {
        panels.push(panel(&snyder_scene::<f32>(kind, 220, 180)?, kind.title())?);
    }
    Ok(figure::sheet(
        "Snyder, fig. 7: comparison of area light source results (f32, per-pixel Lambert + Phong)",
        &panels,
        5,
        "same scene and materials; each panel exposed so that the floor at the origin (between the objects) is 80 % of display white before the tone curve (linear to 50 %, compressed above, white at 400 %); Phong m = 8..24",
    ))
}

fn single_sphere<T: Real + 'static>(
    light: Box<dyn Illuminant<T>>,
    exposure: T,
    eye: [f64; 3],
) -> Result<Scene<T>, RasterError> {
    let white = Material::matte(c(1.0, 1.0, 1.0))?;
    Ok(Scene {
        camera: camera(eye, [0.0, 0.0, 0.0], 30.0, 220, 220)?,
        objects: vec![Object::new(
            sphere(1.0, 24, 40)?,
            Affine::identity(),
            Surface::Lit(white),
        )],
        lights: Lights(vec![light]),
        exposure,
        background: [0, 0, 0],
        encoding: Encoding::Srgb,
    })
}

fn june_fig20_3() -> Result<tiny_skia::Pixmap, RasterError> {
    // June's parameters: sky (0.5, 0.5, 1), ground (0.2, 1, 0.2), sky direction +y.
    let sky = SkyGround::new(v(0.0, 1.0, 0.0), c(0.5, 0.5, 1.0), c(0.2, 1.0, 0.2))?;
    let scene = single_sphere::<f32>(Box::new(sky), 1.0, [0.0, 0.0, 4.4])?;
    let mut side = single_sphere::<f32>(
        Box::new(SkyGround::new(
            v(0.0, 1.0, 0.0),
            c(0.5, 0.5, 1.0),
            c(0.2, 1.0, 0.2),
        )?),
        1.0,
        [3.1, 1.6, 2.6],
    )?;
    side.background = [0, 0, 0];
    Ok(figure::sheet(
        "June, fig. 20-3: hemisphere lighting of a sphere",
        &[
            panel(&scene, "sky (.5,.5,1), ground (.2,1,.2)")?,
            panel(&side, "the same, seen from above-right")?,
        ],
        2,
        "sky_ground with the sky toward +y (up), exact (June eq. 20.7); f32, shaded per pixel",
    ))
}

fn june_fig20_9() -> Result<tiny_skia::Pixmap, RasterError> {
    // (a) a white disc of alpha = 20 degrees around +z (toward the viewer), (b) Grace Cathedral.
    let disc = Sh9::<f32>::disc(v(0.0, 0.0, 1.0), 20f32.to_radians(), c(1.0, 1.0, 1.0))?.prepare();
    let grace = Sh9::<f32>::environment(Environment::GraceCathedral).prepare();
    let e_disc = exposure_at(&disc, v(0.0, 0.0, 0.0), v(0.0, 0.0, 1.0));
    let a = single_sphere::<f32>(Box::new(disc), e_disc, [0.0, 0.0, 4.4])?;
    let b = single_sphere::<f32>(Box::new(grace), 1.0, [0.0, 0.0, 4.4])?;
    Ok(figure::sheet(
        "June, fig. 20-9: spherical harmonics lighting",
        &[
            panel(&a, "(a) disc light, alpha = 20 deg, +z")?,
            panel(&b, "(b) Grace Cathedral (Table 20-1)")?,
        ],
        2,
        "sh9_disc_irradiance and sh9_irradiance / pi; (a) exposed x0.8/peak, (b) as June, unscaled",
    ))
}

fn june_fig20_17() -> Result<tiny_skia::Pixmap, RasterError> {
    // June's parameters: light at (1, 1, 2) aimed at the origin, eye at (0, 0, 6.3),
    // a, b, A, B, d = 0.2, 0.3, 0.3, 0.4, 0.8; zNear, zFar = 1, 2; edges 0.4, 0.8;
    // maxIntensity 2, d0 = 1, alpha = 1; shininess 4, ambient (0.5, 0.2, 0.2).
    let pos = v::<f32>(1.0, 1.0, 2.0);
    let frame = LightFrame::new(pos, -pos, v(0.0, 1.0, 0.0))?;
    let shape = Superellipse::new(0.2, 0.3, 0.3, 0.4, 0.8)?;
    let falloff = DistanceFalloff::new(2.0, 1.0, 1.0, 1.0, 2.0, 0.4, 0.8)?;
    let uber = Uberlight::new(frame, shape, falloff);
    let ambient = Ambient(c(0.5, 0.2, 0.2));
    let point = Shaped {
        light: PointLight::new(pos)?,
        shape: uber,
    };
    // The same beam shaping a 0.3 x 0.3 square area light at the same place.
    let (u, w) = (frame.right() * 0.15, frame.up() * 0.15);
    let square =
        PolygonLight::<f32, 4>::new(&[pos - u - w, pos + u - w, pos + u + w, pos - u + w])?;
    let k = 0.8 / (square.lambert(v(0.0, 0.0, 1.0), -frame.direction()) as f64).max(1e-6);
    let area = Shaped {
        light: Tinted::new(square, c(k, k, k))?,
        shape: uber,
    };
    let mk = |lights: Lights<f32>| -> Result<Scene<f32>, RasterError> {
        let white = Material::new(c(1.0, 1.0, 1.0), c(1.0, 1.0, 1.0), 4)?;
        let wall = Material::new(c(0.9, 0.9, 0.9), c(0.2, 0.2, 0.2), 4)?;
        Ok(Scene {
            camera: camera([0.0, 0.0, 6.3], [0.0, 0.0, 0.0], 40.0, 260, 220)?,
            objects: vec![
                Object::new(
                    sphere(1.0, 24, 40)?,
                    Affine::identity(),
                    Surface::Lit(white),
                ),
                Object::new(
                    plane(9.0, 9.0, 12, 12)?,
                    rotate([1.0, 0.0, 0.0], 90.0)?.then(&translate(0.0, 0.0, -1.3)?),
                    Surface::Lit(wall),
                ),
            ],
            lights,
            exposure: 1.0,
            background: [0, 0, 0],
            encoding: figure_tone()?,
        })
    };
    let a = mk(Lights(vec![Box::new(point), Box::new(ambient)]))?;
    let b = mk(Lights(vec![Box::new(area), Box::new(ambient)]))?;
    Ok(figure::sheet(
        "June, fig. 20-17: uberlight-like shader, June's parameters",
        &[
            panel(&a, "(a) point light x shape x falloff + ambient")?,
            panel(&b, "(b) the same beam on a square area light")?,
        ],
        2,
        "superellipse a,b,A,B,d = .2,.3,.3,.4,.8; zones 1..2 (edges .4, .8); falloff M=2, d0=1, alpha=1; tone curve linear to 50 %, white at 400 %",
    ))
}

/// Arvo's window: four panes of a 2x2 window on the wall z = `z`, facing +z.
fn window_panes<T: Real>(z: f64) -> Result<Vec<PolygonLight<T, 4>>, RasterError> {
    let mut panes = Vec::new();
    for (x0, y0) in [(-0.95, 0.55), (0.05, 0.55), (-0.95, 1.65), (0.05, 1.65)] {
        let (x1, y1) = (x0 + 0.9, y0 + 1.0);
        panes.push(PolygonLight::new(&[
            v(x0, y0, z),
            v(x1, y0, z),
            v(x1, y1, z),
            v(x0, y1, z),
        ])?);
    }
    Ok(panes)
}

fn quad_mesh<T: Real>(verts: [Vec3<T>; 4], n: Vec3<T>) -> MeshBuf<T> {
    MeshBuf {
        verts: verts.iter().map(|&p| Vertex::new(p, n)).collect(),
        tris: vec![[0, 1, 2], [0, 2, 3]],
    }
}

fn arvo_fig5() -> Result<tiny_skia::Pixmap, RasterError> {
    // Top row: the luminaire at three orders; bottom row: the glossy floor at three orders.
    let mut panels = Vec::new();
    let mut bottom = Vec::new();
    let orders_l = [1u32, 5, 20];
    let orders_r = [10u32, 50, 200];
    for row in 0..3 {
        // Left: a square luminaire 2 above the floor, facing down, emitting
        // ((-u).axis)^m, scaled by (m + 2)/2 so every order emits the same power.
        let m = orders_l[row];
        let lum = PolygonLight::<f32, 4>::new(&[
            v(-0.6, 2.0, -0.6),
            v(0.6, 2.0, -0.6),
            v(0.6, 2.0, 0.6),
            v(-0.6, 2.0, 0.6),
        ])?;
        let lum_mesh = quad_mesh(
            lum.vertices().try_into().unwrap_or([v(0.0, 0.0, 0.0); 4]),
            v(0.0, -1.0, 0.0),
        );
        let s = (m as f32 + 2.0) / 2.0;
        let light = Tinted::new(
            DirectionalLuminaire::new(lum, v(0.0, -1.0, 0.0), m)?,
            c(s as f64, s as f64, s as f64),
        )?;
        let grey = Material::matte(c(0.7, 0.7, 0.7))?;
        let scene = Scene {
            camera: camera([0.0, 3.4, 4.2], [0.0, 0.4, 0.0], 45.0, 220, 176)?,
            objects: vec![
                Object::new(
                    plane(8.0, 8.0, 8, 8)?,
                    Affine::identity(),
                    Surface::Lit(grey),
                ),
                Object::new(
                    cuboid([0.3, 0.3, 0.3])?,
                    translate(0.9, 0.3, 0.4)?,
                    Surface::Lit(grey),
                ),
                Object {
                    two_sided: true,
                    ..Object::new(
                        lum_mesh,
                        Affine::identity(),
                        Surface::Emissive(c(1.0, 1.0, 0.9)),
                    )
                },
            ],
            lights: Lights(vec![Box::new(light)]),
            exposure: 0.35,
            background: [0, 0, 0],
            encoding: Encoding::Srgb,
        };
        panels.push(panel(&scene, &format!("directional luminaire, order {m}"))?);

        // Right: a glossy floor reflecting a four-pane window (Arvo 6.2), order n.
        let n = orders_r[row];
        let panes = window_panes::<f32>(-2.5)?;
        let glossy: ShadeFn<f32> = Box::new(move |p, nn, e| {
            let mut s = 0.0;
            let mut d = 0.0;
            for pane in &panes {
                s += pane.glossy_reflection(p, nn, e, n);
                d += pane.lambert(p, nn);
            }
            c(0.03, 0.03, 0.035)
                .scale(d)
                .add(c(0.9, 0.85, 0.7).scale(s * 0.5))
        });
        let mut objects = vec![Object::new(
            plane(8.0, 8.0, 1, 1)?,
            Affine::identity(),
            Surface::Custom(glossy),
        )];
        for pane in window_panes::<f32>(-2.5)? {
            let q: [Vec3<f32>; 4] = pane.vertices().try_into().unwrap_or([v(0.0, 0.0, 0.0); 4]);
            objects.push(Object::new(
                quad_mesh(q, v(0.0, 0.0, 1.0)),
                Affine::identity(),
                Surface::Emissive(c(0.9, 0.85, 0.7)),
            ));
        }
        let scene = Scene {
            camera: camera([0.3, 1.1, 3.0], [0.0, 0.5, -1.5], 50.0, 220, 176)?,
            objects,
            lights: Lights(vec![]),
            exposure: 1.0,
            background: [10, 10, 14],
            encoding: Encoding::Srgb,
        };
        bottom.push(panel(&scene, &format!("glossy reflection, order {n}"))?);
    }
    panels.extend(bottom);
    Ok(figure::sheet(
        "Arvo, fig. 5: directional luminaire (top), glossy reflection (bottom)",
        &panels,
        3,
        "top: double-axis moments, emission ((-u).axis)^m x (m+2)/2; bottom: a window's reflection on a glossy floor, (m+2)/2pi int (u.mr)^m (n.u) du",
    ))
}

fn arvo_fig8() -> Result<tiny_skia::Pixmap, RasterError> {
    let mut panels = Vec::new();
    for m in [3u32, 20, 200] {
        // Bright shapes 1.2 behind a frosted pane at z = 0.
        let z = -1.2;
        let shapes: Vec<PolygonLight<f32, 8>> = vec![
            PolygonLight::new(&[v(-1.1, -0.6, z), v(-0.5, -0.6, z), v(-0.8, 0.5, z)])?,
            PolygonLight::new(&[
                v(-0.2, -0.5, z),
                v(0.3, -0.5, z),
                v(0.3, 0.0, z),
                v(0.05, 0.0, z),
                v(0.05, 0.5, z),
                v(-0.2, 0.5, z),
            ])?,
            PolygonLight::new(&[
                v(0.6, -0.4, z),
                v(1.1, -0.4, z),
                v(1.1, 0.4, z),
                v(0.6, 0.4, z),
            ])?,
        ];
        let glass: ShadeFn<f32> = Box::new(move |p, n, e| {
            let mut s = 0.0;
            for sh in &shapes {
                s += sh.glossy_transmission(p, n, e, m);
            }
            c(0.9, 0.95, 1.0).scale(s).add(c(0.02, 0.02, 0.025))
        });
        let pane = Object {
            two_sided: true,
            ..Object::new(
                plane(3.0, 2.2, 1, 1)?,
                rotate([1.0, 0.0, 0.0], 90.0)?,
                Surface::Custom(glass),
            )
        };
        let scene = Scene {
            camera: camera([0.0, 0.0, 3.0], [0.0, 0.0, 0.0], 38.0, 220, 160)?,
            objects: vec![pane],
            lights: Lights(vec![]),
            exposure: 1.4,
            background: [0, 0, 0],
            encoding: figure_tone()?,
        };
        panels.push(panel(&scene, &format!("frosted glass, order {m}"))?);
    }
    Ok(figure::sheet(
        "Arvo, fig. 8: frosted glass (glossy transmission, double-axis moments)",
        &panels,
        3,
        "three emitters 1.2 behind a pane (a triangle, a non-convex L, a rectangle); radiance (m+2)/2pi int (-u.e)^m (-n.u) du; tone curve linear to 50 %, white at 400 %",
    ))
}

fn picott_plates() -> Result<tiny_skia::Pixmap, RasterError> {
    let mut panels = Vec::new();
    for kind in 0..3 {
        let (light, title): (Box<dyn Illuminant<f32>>, &str) = match kind {
            0 => (
                Box::new(PointLight::inverse_square(v(0.0, 2.2, -1.5))?),
                "(a) point light",
            ),
            1 => (
                Box::new(LineLight::new(v(0.0, 2.2, -3.5), v(0.0, 2.2, 0.5))?),
                "(b) linear light (tube along the lane)",
            ),
            _ => (
                Box::new(ParallelogramLight::new(
                    v(-0.7, 2.2, -3.5),
                    v(1.4, 0.0, 0.0),
                    v(0.0, 0.0, 4.0),
                )?),
                "(c) area light (1.4 x 4 panel)",
            ),
        };
        let exposure = exposure_at(&*light, v(0.0, 0.0, -1.5), v(0.0, 1.0, 0.0));
        let lane = Material::new(c(0.75, 0.55, 0.3), c(0.5, 0.5, 0.5), 40)?;
        let gutter = Material::matte(c(0.15, 0.15, 0.17))?;
        let pin = Material::new(c(0.9, 0.9, 0.88), c(0.6, 0.6, 0.6), 30)?;
        let mut objects = vec![
            Object::new(
                plane(1.6, 9.0, 2, 18)?,
                translate(0.0, 0.0, -2.0)?,
                Surface::Lit(lane),
            ),
            Object::new(
                plane(6.0, 9.0, 2, 2)?,
                translate(0.0, -0.05, -2.0)?,
                Surface::Lit(gutter),
            ),
        ];
        // Ten pins in a triangle: a body and a head each.
        for (row, &z) in [-3.0, -3.3, -3.6, -3.9].iter().enumerate() {
            for i in 0..=row {
                let x = (i as f64 - row as f64 / 2.0) * 0.3;
                objects.push(Object::new(
                    sphere(0.1, 10, 16)?,
                    Affine::scale(v(1.0, 1.8, 1.0))?.then(&translate(x, 0.18, z)?),
                    Surface::Lit(pin),
                ));
                objects.push(Object::new(
                    sphere(0.06, 8, 12)?,
                    translate(x, 0.42, z)?,
                    Surface::Lit(pin),
                ));
            }
        }
        // A ball on the lane.
        objects.push(Object::new(
            sphere(0.22, 16, 24)?,
            translate(0.25, 0.22, -0.8)?,
            Surface::Lit(Material::new(c(0.1, 0.15, 0.6), c(0.8, 0.8, 0.8), 60)?),
        ));
        let scene = Scene {
            camera: camera([0.0, 1.2, 2.2], [0.0, 0.2, -2.8], 40.0, 200, 170)?,
            objects,
            lights: Lights(vec![light]),
            exposure,
            background: [8, 8, 10],
            encoding: figure_tone()?,
        };
        panels.push(panel(&scene, title)?);
    }
    Ok(figure::sheet(
        "Picott's plates: one lane under a point, a linear and an area light",
        &panels,
        3,
        "diffuse: point 1/d^2, line_lambert k=2, polygon_lambert; specular: Picott's peaks (line, rect); exposed so the lane under the point light's position is 80 % before the tone curve (linear to 50 %, white at 400 %)",
    ))
}
