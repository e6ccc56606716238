//! `host-sim render`: the contact sheet of shaded spheres (one per model, f32) and every
//! built-in figure (the documents' pictures, rendered with the crate's own rasterizer and
//! models), the f64/f32/f32-fast/fixed comparison sheets, and scenes loaded from TOML files.
//!
//! The contact sheet: each tile is a unit sphere at the origin seen orthographically along -z
//! (view direction `v = +z`, x right, y up). A pixel's surface point is `p = n`; Phong models use
//! the reflection `r = 2 (n.v) n - v`. Every light sits up-left-front of the sphere, along
//! `L = (-1, 1, 1)/sqrt 3`. Each tile shows the model's value alone (no ambient, no albedo),
//! scaled so that its brightest pixel is white (the scale is printed under the label as the
//! tile's peak value), clamped and sRGB-encoded.
//!
//! Anti-aliasing: the figures and scene files are supersampled (`--aa K`, default 3: each pixel
//! the mean of 3 x 3 samples, averaged in linear light before the tone curve and sRGB; see
//! `scenes::panel`); about 9 times the shading work of one sample (measured: 8.8 s of CPU for
//! every picture against 1.4 s with `--aa 1`, on one x86-64 machine under load).
//!
//! What firmware can afford: the rasterizer draws one sample per pixel. On the RP2040 demo
//! frame (23.5 M cycles single core, of which 6.9 M scan conversion for 13 000 pixels and 530
//! triangle setups, README "Firmware"), 2 x 2 supersampling would multiply the scan conversion
//! by up to 4 (about 28 M cycles: a frame of about 45 M, 0.34 s at 133 MHz instead of 0.18 s)
//! and need linear samples in the band (6 bytes each: 46 KiB for a 480 x 16 band, plus 15 KiB
//! of depth, where one-sample bands take 15 KiB in all), while the frame is already 5 times
//! over the 30 fps budget: not affordable there. Coverage-based edge anti-aliasing (blending
//! only the silhouette pixels, a few thousand per frame) would cost a fraction of a million
//! cycles; the rasterizer does not implement it.

use std::path::{Path, PathBuf};
use std::time::Instant;

use arealight::{
    CapLight, Environment, HemisphereLight, OvercastSky, PhongLobe, PolygonLight, Rgb, Sh9,
    SkyGround, SphereLight, Vec3,
};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use tiny_skia::{Color, Paint, PathBuilder, Pixmap, PremultipliedColorU8, Rect, Stroke, Transform};

use crate::figure::{srgb8, text, Font, BG};

/// The output directory when none is given.
pub const DEFAULT_OUT: &str = "out";

/// Arguments of `host-sim render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    /// Directory to write the PNG files into (created if missing).
    #[arg(long, value_name = "DIR", default_value = DEFAULT_OUT)]
    pub out: PathBuf,
    /// Render only these pictures (comma-separated file stems, e.g.
    /// `contact_sheet,snyder_fig7,compare_polygon`); all of them by default.
    #[arg(long, value_name = "NAMES", value_delimiter = ',')]
    pub only: Option<Vec<String>>,
    /// Render a scene described in a TOML file (lights, materials, meshes, camera) into
    /// DIR/<file stem>.png instead of the built-in pictures. See host-sim/scenes/example.toml.
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
    /// Anti-aliasing of the figures and scene files: each pixel the mean of K x K samples
    /// (the frame rendered K times wider and higher, averaged in linear light before the
    /// encoding), 1 to 8, about K^2 times the work; 1 is the rasterizer's own one sample per
    /// pixel (what firmware draws: supersampling is beyond its budget). The comparison
    /// sheets always use one sample (they compare pixels).
    #[arg(long, value_name = "K", default_value_t = crate::scenes::DEFAULT_AA,
          value_parser = clap::value_parser!(u16).range(1..=crate::scenes::MAX_AA as i64))]
    pub aa: u16,
}

impl Default for RenderArgs {
    fn default() -> Self {
        RenderArgs {
            out: DEFAULT_OUT.into(),
            only: None,
            scene: None,
            aa: crate::scenes::DEFAULT_AA,
        }
    }
}

const COLS: u32 = 6;
const TILE_W: u32 = 160;
const TILE_H: u32 = 186;
const HEADER_H: u32 = 28;
const RADIUS: f32 = 64.0;

type V = Vec3<f32>;
type Shader = Box<dyn Fn(V) -> [f32; 3]>;

struct Tile {
    /// The model id.
    label: &'static str,
    /// The light's parameters, printed under the label.
    note: &'static str,
    shade: Shader,
}

fn v(x: f32, y: f32, z: f32) -> V {
    Vec3::new(x, y, z)
}

/// Reflection of the view direction +z about `n`.
fn reflect(n: V) -> V {
    let view = v(0.0, 0.0, 1.0);
    n * (2.0 * n.z) - view
}

fn grey(x: f32) -> [f32; 3] {
    [x, x, x]
}

fn rgb(c: Rgb<f32>) -> [f32; 3] {
    [c.r, c.g, c.b]
}

/// The tiles, with their lights built once. Library errors here are programming errors of the
/// scene (the parameters are constants), reported as such.
fn tiles() -> Result<Vec<Tile>, arealight::Error> {
    let l = v(-1.0, 1.0, 1.0).try_normalize("L")?;
    let m = 16;
    let lobe = PhongLobe::<f32>::new(m)?;
    let lobe2 = PhongLobe::<f32>::new(2)?;

    let hemi = HemisphereLight::new(l)?;
    let sky = OvercastSky::new(l, 1.0)?;
    let sky_ground = SkyGround::new(l, Rgb::new(0.55, 0.75, 1.0), Rgb::new(0.35, 0.22, 0.10))?;
    let cap = CapLight::new(l, 0.45)?;
    let phong_cap = CapLight::new(l, 0.25)?;
    let sphere = SphereLight::new(l * 3.0, 1.0)?;
    // A 2.4 x 1.2 rectangle facing the origin, centred 3 units along L, long side horizontal.
    let u = v(0.0, 1.0, 0.0).cross(l).try_normalize("u")?;
    let w = l.cross(u);
    let c = l * 3.0;
    let (hu, hw) = (u * 1.2, w * 0.6);
    let poly = PolygonLight::<f32, 4>::new(&[c - hu - hw, c + hu - hw, c + hu + hw, c - hu + hw])?;
    let grace = Sh9::<f32>::environment(Environment::GraceCathedral).prepare();
    let disc = Sh9::disc(l, 0.45, Rgb::splat(1.0))?.prepare();

    let mut t: Vec<Tile> = Vec::new();
    let mut add = |label: &'static str, note: &'static str, shade: Shader| {
        t.push(Tile { label, note, shade })
    };
    add(
        "hemi_const",
        "",
        Box::new(move |n| grey(hemi.lambert_const(n))),
    );
    add("hemi_cos", "", Box::new(move |n| grey(hemi.lambert_cos(n))));
    add(
        "sky_overcast",
        "c=1",
        Box::new(move |n| grey(sky.lambert(n))),
    );
    add(
        "sky_ground",
        "",
        Box::new(move |n| rgb(sky_ground.irradiance(n))),
    );
    add(
        "cap_lambert",
        "s=0.45",
        Box::new(move |n| grey(cap.lambert(n))),
    );
    add(
        "cap_lambert_hermite",
        "s=0.45",
        Box::new(move |n| grey(cap.lambert_hermite(n))),
    );
    add(
        "sphere_lambert",
        "d=3 r=1",
        Box::new(move |n| grey(sphere.lambert(n, n))),
    );
    add(
        "sphere_lambert_hermite",
        "d=3 r=1",
        Box::new(move |n| grey(sphere.lambert_hermite(n, n))),
    );
    let p = poly.clone();
    add(
        "polygon_lambert",
        "2.4x1.2",
        Box::new(move |n| grey(p.lambert(n, n))),
    );
    add(
        "phong_hemi_const",
        "m=16",
        Box::new(move |n| grey(hemi.phong_const(&lobe, reflect(n)))),
    );
    add(
        "phong_hemi_cos",
        "m=16",
        Box::new(move |n| grey(hemi.phong_cos(&lobe, reflect(n)))),
    );
    add(
        "phong_cap",
        "m=16 s=0.25",
        Box::new(move |n| grey(phong_cap.phong(&lobe, reflect(n)))),
    );
    add(
        "phong_sphere",
        "m=16",
        Box::new(move |n| grey(sphere.phong(&lobe, n, reflect(n)))),
    );
    let p = poly.clone();
    add(
        "phong_polygon",
        "m=16",
        Box::new(move |n| grey(p.phong(&lobe, n, reflect(n)))),
    );
    add(
        "phong_polygon",
        "m=2",
        Box::new(move |n| grey(poly.phong(&lobe2, n, reflect(n)))),
    );
    add(
        "sh9_irradiance",
        "grace",
        Box::new(move |n| rgb(grace.irradiance(n))),
    );
    add(
        "sh9_disc_irradiance",
        "a=0.45",
        Box::new(move |n| rgb(disc.irradiance(n))),
    );
    Ok(t)
}

/// Shades one tile into `pix` with its top-left corner at (x0, y0); returns the peak value.
fn draw_sphere(pix: &mut Pixmap, tile: &Tile, cx: f32, cy: f32) -> f32 {
    let size = (2.0 * RADIUS) as usize + 2;
    let (x0, y0) = ((cx - RADIUS) as i32 - 1, (cy - RADIUS) as i32 - 1);
    // Pass 1: values and coverage.
    let mut vals = vec![([0.0f32; 3], 0.0f32); size * size];
    let mut peak = 0.0f32;
    for j in 0..size {
        for i in 0..size {
            let px = (x0 + i as i32) as f32 + 0.5;
            let py = (y0 + j as i32) as f32 + 0.5;
            let (sx, sy) = ((px - cx) / RADIUS, (cy - py) / RADIUS);
            let d = (sx * sx + sy * sy).sqrt();
            // Analytic edge coverage over about one pixel.
            let cover = ((1.0 - d) * RADIUS + 0.5).clamp(0.0, 1.0);
            if cover <= 0.0 {
                continue;
            }
            // Shade at the nearest point inside the disc.
            let (sx, sy) = if d > 0.999 {
                (sx * 0.999 / d, sy * 0.999 / d)
            } else {
                (sx, sy)
            };
            let nz = (1.0 - sx * sx - sy * sy).max(0.0).sqrt();
            let c = (tile.shade)(v(sx, sy, nz));
            for ch in c {
                if ch.is_finite() {
                    peak = peak.max(ch);
                }
            }
            vals[j * size + i] = (c, cover);
        }
    }
    // Pass 2: expose, tone-map, composite over the background.
    let scale = if peak > 0.0 { 1.0 / peak } else { 1.0 };
    let (w, h) = (pix.width() as i32, pix.height() as i32);
    let data = pix.pixels_mut();
    for j in 0..size {
        for i in 0..size {
            let (c, cover) = vals[j * size + i];
            let (x, y) = (x0 + i as i32, y0 + j as i32);
            if cover <= 0.0 || !(0..w).contains(&x) || !(0..h).contains(&y) {
                continue;
            }
            let ch = |k: usize| {
                let fg = srgb8(if c[k].is_finite() { c[k] * scale } else { 0.0 }) as f32;
                (fg * cover + BG[k] as f32 * (1.0 - cover) + 0.5) as u8
            };
            if let Some(p) = PremultipliedColorU8::from_rgba(ch(0), ch(1), ch(2), 255) {
                data[(y * w + x) as usize] = p;
            }
        }
    }
    peak
}

/// Renders the contact sheet into `out` and returns the PNG's path.
///
/// # Errors
/// A message for a scene the library refuses or a file that cannot be written.
pub fn contact_sheet(out: &Path) -> Result<PathBuf, String> {
    let tiles = tiles().map_err(|e| format!("scene refused by the library: {e}"))?;
    let rows = (tiles.len() as u32).div_ceil(COLS);
    let (w, h) = (COLS * TILE_W, HEADER_H + rows * TILE_H);
    let mut pix = Pixmap::new(w, h).ok_or("cannot allocate the pixmap")?;
    pix.fill(Color::from_rgba8(BG[0], BG[1], BG[2], 255));

    let mut frame = Paint::default();
    frame.set_color_rgba8(70, 70, 80, 255);
    let mut marker = Paint::default();
    marker.set_color_rgba8(255, 210, 80, 255);
    marker.anti_alias = true;
    let stroke = Stroke::default();
    let l = [-1.0f32 / 3f32.sqrt(), 1.0 / 3f32.sqrt()];

    let mut peaks = Vec::with_capacity(tiles.len());
    for (k, tile) in tiles.iter().enumerate() {
        let (col, row) = (k as u32 % COLS, k as u32 / COLS);
        let (tx, ty) = ((col * TILE_W) as f32, (HEADER_H + row * TILE_H) as f32);
        if let Some(rect) =
            Rect::from_xywh(tx + 2.5, ty + 2.5, TILE_W as f32 - 5.0, TILE_H as f32 - 5.0)
        {
            let path = PathBuilder::from_rect(rect);
            pix.stroke_path(&path, &frame, &stroke, Transform::identity(), None);
        }
        let (cx, cy) = (tx + TILE_W as f32 / 2.0, ty + 10.0 + RADIUS);
        peaks.push(draw_sphere(&mut pix, tile, cx, cy));
        // The light's direction, projected: a small dot up-left of the sphere.
        if let Some(dot) =
            PathBuilder::from_circle(cx + l[0] * RADIUS * 1.18, cy - l[1] * RADIUS * 1.18, 3.5)
        {
            pix.fill_path(
                &dot,
                &marker,
                tiny_skia::FillRule::Winding,
                Transform::identity(),
                None,
            );
        }
    }

    text(
        &mut pix,
        "arealight contact sheet - f32, unit sphere, view +z, light along (-1,1,1) (dot)",
        8,
        4,
        [230, 230, 230],
        Font::Small,
    );
    text(
        &mut pix,
        "each tile scaled so its peak is white; under the label: parameters (s sigma, a alpha) and peak",
        8,
        15,
        [150, 150, 160],
        Font::Small,
    );
    for (k, (tile, peak)) in tiles.iter().zip(&peaks).enumerate() {
        let (col, row) = (k as u32 % COLS, k as u32 / COLS);
        let (tx, ty) = ((col * TILE_W) as i32, (HEADER_H + row * TILE_H) as i32);
        let y = ty + 10 + 2 * RADIUS as i32 + 8;
        text(
            &mut pix,
            tile.label,
            tx + 8,
            y,
            [235, 235, 235],
            Font::Small,
        );
        text(
            &mut pix,
            &format!("{:<13}peak {peak:.4}", tile.note),
            tx + 8,
            y + 12,
            [150, 150, 160],
            Font::Small,
        );
    }

    crate::figure::save(&pix, out, "contact_sheet.png")
}

/// Writes one picture into the directory given; returns its path.
type MakeFn = Box<dyn Fn(&Path) -> Result<PathBuf, String>>;

/// One picture `render` can write: its file stem and how to make it.
struct Job {
    stem: String,
    make: MakeFn,
}

fn jobs() -> Vec<Job> {
    let mut jobs: Vec<Job> = vec![Job {
        stem: "contact_sheet".into(),
        make: Box::new(contact_sheet),
    }];
    for fig in crate::scenes::figures() {
        let file = fig.file;
        let f = fig.render;
        jobs.push(Job {
            stem: file.trim_end_matches(".png").into(),
            make: Box::new(move |out| {
                let pix = f().map_err(|e| format!("{file}: scene refused: {e}"))?;
                crate::figure::save(&pix, out, file)
            }),
        });
    }
    for (stem, kind) in crate::compare::SHEETS {
        jobs.push(Job {
            stem: stem.to_string(),
            make: Box::new(move |out| crate::compare::sheet(kind, out, stem)),
        });
    }
    jobs
}

/// Renders what `args` asks for; returns the paths written, in order.
///
/// # Errors
/// A message for an unknown `--only` name, a scene the library refuses, a bad scene file or a
/// file that cannot be written.
pub fn render(args: &RenderArgs) -> Result<Vec<PathBuf>, String> {
    crate::scenes::set_supersampling(args.aa);
    if let Some(file) = &args.scene {
        return crate::scene_file::render_file(file, &args.out).map(|p| vec![p]);
    }
    let mut jobs = jobs();
    if let Some(only) = &args.only {
        for name in only {
            if !jobs.iter().any(|j| &j.stem == name) {
                let known: Vec<&str> = jobs.iter().map(|j| j.stem.as_str()).collect();
                return Err(format!(
                    "unknown picture {name:?}; known: {}",
                    known.join(", ")
                ));
            }
        }
        jobs.retain(|j| only.contains(&j.stem));
    }
    let bar = ProgressBar::new(jobs.len() as u64);
    bar.set_style(
        ProgressStyle::with_template("{bar:30} {pos}/{len} {msg} ({elapsed})")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let mut paths = Vec::new();
    for job in &jobs {
        bar.set_message(job.stem.clone());
        paths.push((job.make)(&args.out)?);
        bar.inc(1);
    }
    bar.finish_and_clear();
    Ok(paths)
}

/// `host-sim render`: prints each path written, one per line (the contact sheet first).
pub fn main(args: &RenderArgs) -> std::process::ExitCode {
    let start = Instant::now();
    match render(args) {
        Ok(paths) => {
            for p in &paths {
                println!("{}", p.display());
            }
            let n = paths.len();
            eprintln!(
                "rendered {n} picture{} in {:.3} s",
                if n == 1 { "" } else { "s" },
                start.elapsed().as_secs_f64()
            );
            std::process::ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("host-sim render: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn srgb_ends() {
        assert_eq!(super::srgb8(0.0), 0);
        assert_eq!(super::srgb8(1.0), 255);
        assert_eq!(super::srgb8(2.0), 255);
        assert_eq!(super::srgb8(f32::NAN), 0);
    }
}
