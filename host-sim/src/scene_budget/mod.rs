//! `host-sim budget --scene FILE --chip NAME`: a scene's frame time on a chip, per option,
//! with each option's image error, before any firmware is written (docs/scene-budget.md).
//!
//! For each option (backend, and per object Gouraud or per pixel) the scene is rendered once
//! on the host through the firmware's own frame path ([`work::render`]): the work of each
//! stage is counted per object (vertices, shader calls, triangle setups, pixels, bands). The
//! counts times the chip's unit costs ([`costs`], measured on the chip's emulator by
//! `boards/demo-scene/src/calibrate.rs` on synthetic work) give the frame time stage by stage;
//! the image against the f64 per-pixel render of the same scene gives the error (max and mean
//! per pixel, in 8-bit levels). The options on the Pareto front (no other is both faster and
//! more accurate) are marked, and the cheapest that meets `--fps` and `--max-error` is
//! recommended. `--check FRAMES.csv` compares the prediction with an emulated frame.

mod check;
mod cli;
pub use cli::{calibrate_main, main};
pub mod costs;
mod report;
pub mod work;
pub use check::check;
use report::mega;
pub use report::{answer, csv, markdown, plot};

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use arealight::raster::Shading;
use arealight::{Fast32, Fixed22, ObjectBounds, Real, Rgb, Scene, Vec3};
use tiny_skia::{Paint, PathBuilder, Pixmap, Stroke, Transform};

use crate::budget::BudgetArgs;
use crate::figure::{self, Font};
use crate::scene_file::{self, Parsed};
use crate::scenes::Surface;
use costs::{Chip, Costs, Finish, LightCost, Prediction};
use work::Work;

/// The tolerance of `--check`: a prediction within 15 % of the emulated frame.
pub const CHECK_TOLERANCE: f64 = 0.15;

/// One option of a scene on a chip.
#[derive(Clone, Debug)]
pub struct Row {
    /// The backend (`fixed`, `f32`, `f32-fast`).
    pub backend: &'static str,
    /// What the shading is, in words.
    pub shading: String,
    /// The meshes' segment counts times this (1: as written).
    pub tessellation: f64,
    /// The models and the light set: as written, Hermite, or culled per object.
    pub variant: Variant,
    /// The predicted frame, in the chip's unit.
    pub predicted: Prediction,
    /// Milliseconds at the chip's clock.
    pub ms: f64,
    /// Largest per-pixel error against the f64 per-pixel frame, 8-bit levels.
    pub max_err: f64,
    /// Mean per-pixel error, 8-bit levels.
    pub mean_err: f64,
    /// Some costs were derived from the QEMU budget's counts rather than calibrated.
    pub derived: bool,
    /// On the Pareto front (time against mean error).
    pub pareto: bool,
    /// The work counted.
    pub work: Work,
}

/// Why an option has no row.
#[derive(Clone, Debug)]
pub struct Skipped {
    /// The backend.
    pub backend: &'static str,
    /// Why.
    pub why: String,
}

/// What a budget of a scene on a chip found.
pub struct Budget {
    /// The chip.
    pub chip: &'static Chip,
    /// The scene file's name.
    pub scene: String,
    /// The options, in the order tried.
    pub rows: Vec<Row>,
    /// Backends that could not render the scene, and why.
    pub skipped: Vec<Skipped>,
}

/// What an option changes besides shading and tessellation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Variant {
    /// The file's lights and models.
    AsWritten,
    /// Every cap and sphere light's diffuse term by Snyder's Hermite approximation
    /// (`lambert_hermite`) instead of the exact one.
    Hermite,
    /// Each object shaded by the lights `Scene::prepare` keeps for it (the lights that cannot
    /// reach its bounding sphere and normal cone skipped: the same frame, fewer calls).
    Culled,
}

impl Variant {
    /// Words appended to an option's shading.
    fn words(self) -> &'static str {
        match self {
            Variant::AsWritten => "",
            Variant::Hermite => ", Hermite caps and spheres",
            Variant::Culled => ", lights culled per object",
        }
    }
}

/// An option's shading: its label, the shading per object, the tessellation factor, the
/// variant.
type Plan = (String, Vec<Shading>, f64, Variant);

/// The options tried per backend: as written, all Gouraud, all per pixel, each lit object
/// alone per pixel, and the first two with the meshes' segments halved and doubled; with
/// `hermite` (the scene has cap or sphere lights) the first two with Hermite diffuse terms;
/// with `culled` (culling drops a light for some object) the first three with the lights
/// culled. (Emissive objects are always Gouraud.) Deduplicated.
fn assignments(
    written: &[Shading],
    lit: &[bool],
    names: &[String],
    hermite: bool,
    culled: bool,
) -> Vec<Plan> {
    let all = |s: Shading| -> Vec<Shading> {
        lit.iter()
            .map(|&l| if l { s } else { Shading::Gouraud })
            .collect()
    };
    let mut out = vec![
        ("as written".to_owned(), written.to_vec()),
        ("all Gouraud".to_owned(), all(Shading::Gouraud)),
        ("all per pixel".to_owned(), all(Shading::PerPixel)),
    ];
    if lit.iter().filter(|&&l| l).count() > 1 {
        for (i, _) in lit.iter().enumerate().filter(|(_, &l)| l) {
            let mut a = all(Shading::Gouraud);
            a[i] = Shading::PerPixel;
            out.push((format!("{} per pixel", names[i]), a));
        }
    }
    let mut plans: Vec<Plan> = out
        .into_iter()
        .map(|(l, a)| (l, a, 1.0, Variant::AsWritten))
        .collect();
    for tess in [0.5, 2.0] {
        plans.push((
            "as written".to_owned(),
            written.to_vec(),
            tess,
            Variant::AsWritten,
        ));
        plans.push((
            "all Gouraud".to_owned(),
            all(Shading::Gouraud),
            tess,
            Variant::AsWritten,
        ));
    }
    let firsts = [
        ("as written".to_owned(), written.to_vec()),
        ("all Gouraud".to_owned(), all(Shading::Gouraud)),
        ("all per pixel".to_owned(), all(Shading::PerPixel)),
    ];
    if hermite {
        for (l, a) in firsts.iter().take(2) {
            plans.push((l.clone(), a.clone(), 1.0, Variant::Hermite));
        }
    }
    if culled {
        for (l, a) in &firsts {
            plans.push((l.clone(), a.clone(), 1.0, Variant::Culled));
        }
    }
    let mut seen: Vec<(Vec<Shading>, u64, Variant)> = Vec::new();
    plans.retain(|(_, a, t, v)| {
        let key = (a.clone(), t.to_bits(), *v);
        if seen.contains(&key) {
            false
        } else {
            seen.push(key);
            true
        }
    });
    plans
}

fn describe(a: &[Shading], lit: &[bool], names: &[String]) -> String {
    let per: Vec<&str> = a
        .iter()
        .zip(lit)
        .zip(names)
        .filter(|((s, &l), _)| l && **s == Shading::PerPixel)
        .map(|(_, n)| n.as_str())
        .collect();
    let lit_n = lit.iter().filter(|&&l| l).count();
    match per.len() {
        0 => "Gouraud".into(),
        n if n == lit_n => "per pixel".into(),
        _ => format!("per pixel: {}; Gouraud: the rest", per.join(", ")),
    }
}

/// Renders and predicts every assignment in backend `T`.
#[allow(clippy::too_many_arguments)]
fn rows_in<T: Real + 'static>(
    name: &str,
    src: &str,
    backend: &'static str,
    chip: &'static Chip,
    costs: &Costs,
    reference: &[[u8; 3]],
    plan: &[Plan],
    finishes: &[Finish],
    lit: &[bool],
    names: &[String],
    culled: &[Vec<bool>],
) -> Result<Vec<Row>, String> {
    let mut scenes: Vec<((u64, bool), Parsed<T>)> = Vec::new();
    let mut rows = Vec::new();
    for (label, a, tess, variant) in plan {
        let key = (tess.to_bits(), *variant == Variant::Hermite);
        if !scenes.iter().any(|(k, _)| *k == key) {
            let parsed = scene_file::parse_variant::<T>(name, src, *tess, key.1)
                .map_err(|e| format!("the scene does not build in {backend}: {e}"))?;
            scenes.push((key, parsed));
        }
        let Some((_, parsed)) = scenes.iter().find(|(k, _)| *k == key) else {
            continue;
        };
        let (frame, mut work) = work::render(&parsed.scene, a, chip.band_rows)
            .map_err(|e| format!("{backend}: the rasterizer refused the scene: {e}"))?;
        if *variant == Variant::Culled {
            // The culled lights are not called: their calls cost nothing.
            for (o, drop) in work.objects.iter_mut().zip(culled) {
                for calls in [&mut o.vertex_lights, &mut o.pixel_lights] {
                    for (c, &d) in calls.iter_mut().zip(drop) {
                        if d {
                            *c = work::LightCalls::default();
                        }
                    }
                }
            }
        }
        let lights: Vec<LightCost> = parsed
            .lights
            .iter()
            .map(|l| LightCost {
                kind: l.kind.to_owned(),
                vertices: l.vertices,
            })
            .collect();
        let (max_err, mean_err) = work::image_error(&frame, reference);
        costs.take_derived();
        let predicted = costs::predict(chip, costs, backend, &work, finishes, &lights)?;
        let derived = costs.take_derived();
        let mut shading = if label == "as written" {
            format!("{} (as written)", describe(a, lit, names))
        } else {
            describe(a, lit, names)
        };
        if *tess != 1.0 {
            let _ = write!(shading, ", mesh segments x{tess}");
        }
        shading.push_str(variant.words());
        rows.push(Row {
            backend,
            shading,
            tessellation: *tess,
            variant: *variant,
            ms: predicted.total() / (chip.mhz * 1e3),
            predicted,
            max_err,
            mean_err,
            derived,
            pareto: false,
            work,
        });
    }
    Ok(rows)
}

/// Budgets the scene file `path` on `chip`.
///
/// # Errors
/// An unreadable or bad scene file, an unknown chip, a missing cost.
pub fn budget(path: &Path, chip: &str) -> Result<Budget, String> {
    let chip = costs::chip(chip)?;
    let costs = Costs::parse(costs::COSTS_CSV, chip.costs)?;
    let name = path.display().to_string();
    let src = std::fs::read_to_string(path).map_err(|e| format!("cannot read {name}: {e}"))?;
    let reference: Parsed<f64> = scene_file::parse_as::<f64>(&name, &src)?;
    let finishes: Vec<Finish> = reference
        .scene
        .objects
        .iter()
        .map(|o| match &o.surface {
            Surface::Lit(m) => Finish::Lit {
                specular: [m.specular.r, m.specular.g, m.specular.b]
                    .iter()
                    .any(|&c| c > 0.0),
                m: m.lobe.exponent(),
            },
            _ => Finish::Emissive,
        })
        .collect();
    let lit: Vec<bool> = finishes
        .iter()
        .map(|f| matches!(f, Finish::Lit { .. }))
        .collect();
    let names: Vec<String> = reference
        .objects
        .iter()
        .map(|o| format!("{} (line {})", o.kind, o.line))
        .collect();
    let written: Vec<Shading> = reference.scene.objects.iter().map(|o| o.shading).collect();
    let hermite = reference
        .lights
        .iter()
        .any(|l| l.kind == "cap" || l.kind == "sphere");
    let culled = culling(&reference, &finishes)?;
    let plan = assignments(
        &written,
        &lit,
        &names,
        hermite,
        culled.iter().flatten().any(|&d| d),
    );
    let all_per_pixel: Vec<Shading> = vec![Shading::PerPixel; lit.len()];
    let (reference_frame, _) = work::render(&reference.scene, &all_per_pixel, chip.band_rows)
        .map_err(|e| format!("f64: the rasterizer refused the scene: {e}"))?;

    let mut rows = Vec::new();
    let mut skipped = Vec::new();
    for &backend in chip.backends {
        let args = (
            name.as_str(),
            src.as_str(),
            backend,
            chip,
            &costs,
            reference_frame.as_slice(),
            plan.as_slice(),
            finishes.as_slice(),
            lit.as_slice(),
            names.as_slice(),
            culled.as_slice(),
        );
        let got = match backend {
            "fixed" => call::<Fixed22>(args),
            "f32-fast" => call::<Fast32>(args),
            _ => call::<f32>(args),
        };
        match got {
            Ok(r) => rows.extend(r),
            Err(why) => skipped.push(Skipped { backend, why }),
        }
    }
    mark_pareto(&mut rows);
    Ok(Budget {
        chip,
        scene: name,
        rows,
        skipped,
    })
}

type RowsArgs<'a> = (
    &'a str,
    &'a str,
    &'static str,
    &'static Chip,
    &'a Costs,
    &'a [[u8; 3]],
    &'a [Plan],
    &'a [Finish],
    &'a [bool],
    &'a [String],
    &'a [Vec<bool>],
);

/// Per object, per light: whether `Scene::prepare` drops the light for the object (the
/// lights a `Scene` cannot hold, and emissive objects, are never culled). The object's bounds:
/// the bounding sphere of its transformed vertices, and (one-sided objects) the cone of its
/// transformed normals, both widened by a relative 1e-9.
///
/// # Errors
/// A bound the library refuses (not finite).
fn culling(reference: &Parsed<f64>, finishes: &[Finish]) -> Result<Vec<Vec<bool>>, String> {
    let lights = &reference.scene_lights;
    let mut none = vec![vec![false; lights.len()]; finishes.len()];
    // The scene of the lights a `Scene` holds, and their indices in the file.
    let mut scene = Box::new(Scene::<f64, 32, { scene_file::MAX_POLYGON }>::new());
    let mut index = Vec::new();
    for (i, (l, info)) in lights.iter().zip(&reference.lights).enumerate() {
        if let Some(l) = l {
            if scene.push(l.clone(), Rgb::from_f64(info.colour)).is_err() {
                return Ok(none);
            }
            index.push(i);
        }
    }
    for ((o, f), drop) in reference.scene.objects.iter().zip(finishes).zip(&mut none) {
        let Finish::Lit { specular, .. } = *f else {
            continue;
        };
        let pts: Vec<Vec3<f64>> = o
            .mesh
            .verts
            .iter()
            .map(|v| o.xf.point(v.position))
            .collect();
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for p in &pts {
            for (k, x) in p.to_f64().into_iter().enumerate() {
                lo[k] = lo[k].min(x);
                hi[k] = hi[k].max(x);
            }
        }
        let c = Vec3::from_f64([0, 1, 2].map(|k| 0.5 * (lo[k] + hi[k])));
        let r = pts.iter().map(|&p| (p - c).length()).fold(0.0, f64::max);
        let mut bounds = ObjectBounds::sphere(c, r * (1.0 + 1e-9) + 1e-12)
            .map_err(|e| format!("culling bounds: {e}"))?;
        if !o.two_sided {
            let ns: Vec<Vec3<f64>> = o
                .mesh
                .verts
                .iter()
                .filter_map(|v| o.xf.normal(v.normal).normalize())
                .collect();
            let sum = ns.iter().fold(Vec3::from_f64([0.0; 3]), |a, &n| a + n);
            if let Some((axis, len)) = sum.normalize_with_length() {
                if len > 1e-6 * ns.len() as f64 {
                    let half = ns
                        .iter()
                        .map(|n| n.dot(axis).clamp(-1.0, 1.0).acos())
                        .fold(0.0, f64::max);
                    let half = (half * (1.0 + 1e-9) + 1e-12).min(core::f64::consts::PI);
                    bounds = bounds
                        .with_normal_cone(axis, half)
                        .map_err(|e| format!("culling bounds: {e}"))?;
                }
            }
        }
        let kept = scene.prepare(&bounds, specular);
        for (k, &i) in index.iter().enumerate() {
            drop[i] = !kept.active_indices().contains(&(k as u16));
        }
    }
    Ok(none)
}

fn call<T: Real + 'static>(a: RowsArgs<'_>) -> Result<Vec<Row>, String> {
    rows_in::<T>(a.0, a.1, a.2, a.3, a.4, a.5, a.6, a.7, a.8, a.9, a.10)
}

/// Marks the rows no other row beats on both time and mean error.
fn mark_pareto(rows: &mut [Row]) {
    let n = rows.len();
    for i in 0..n {
        let (t, e) = (rows[i].ms, rows[i].mean_err);
        rows[i].pareto = !(0..n).any(|j| {
            j != i
                && rows[j].ms <= t
                && rows[j].mean_err <= e
                && (rows[j].ms < t || rows[j].mean_err < e)
        });
    }
}

/// The cheapest row meeting both limits.
pub fn recommend(rows: &[Row], fps: Option<f64>, max_error: Option<f64>) -> Option<&Row> {
    rows.iter()
        .filter(|r| fps.is_none_or(|f| r.ms <= 1000.0 / f))
        .filter(|r| max_error.is_none_or(|e| r.mean_err <= e))
        .min_by(|a, b| a.ms.total_cmp(&b.ms))
}

/// The file name of a scene without its extension (the reports' and measurements' stem).
fn stem(path: &Path) -> String {
    path.file_stem()
        .map_or("scene".into(), |s| s.to_string_lossy().into_owned())
}

/// The board demo's own code, for the test that the demo's scene file is its frame.
#[cfg(test)]
#[allow(
    dead_code,
    unused_imports,
    unused_attributes,
    unexpected_cfgs,
    clippy::all
)]
#[path = "../../../boards/demo-scene/src/lib.rs"]
mod demo_scene;

#[cfg(test)]
mod tests;
