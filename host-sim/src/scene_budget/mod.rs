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

pub mod costs;
pub mod work;

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
        let pts: Vec<[f64; 3]> = o
            .mesh
            .verts
            .iter()
            .map(|v| o.xf.point(v.position).to_f64())
            .collect();
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for p in &pts {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let c = [0, 1, 2].map(|k| 0.5 * (lo[k] + hi[k]));
        let r = pts
            .iter()
            .map(|p| ((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2) + (p[2] - c[2]).powi(2)).sqrt())
            .fold(0.0, f64::max);
        let mut bounds = ObjectBounds::sphere(Vec3::from_f64(c), r * (1.0 + 1e-9) + 1e-12)
            .map_err(|e| format!("culling bounds: {e}"))?;
        if !o.two_sided {
            let ns: Vec<[f64; 3]> = o
                .mesh
                .verts
                .iter()
                .filter_map(|v| {
                    let n = o.xf.normal(v.normal).to_f64();
                    let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                    (l > 0.0).then(|| n.map(|x| x / l))
                })
                .collect();
            let sum = ns
                .iter()
                .fold([0.0; 3], |a, n| [a[0] + n[0], a[1] + n[1], a[2] + n[2]]);
            let len = (sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]).sqrt();
            if len > 1e-6 * ns.len() as f64 {
                let axis = sum.map(|x| x / len);
                let half = ns
                    .iter()
                    .map(|n| {
                        (n[0] * axis[0] + n[1] * axis[1] + n[2] * axis[2])
                            .clamp(-1.0, 1.0)
                            .acos()
                    })
                    .fold(0.0, f64::max);
                let half = (half * (1.0 + 1e-9) + 1e-12).min(core::f64::consts::PI);
                bounds = bounds
                    .with_normal_cone(Vec3::from_f64(axis), half)
                    .map_err(|e| format!("culling bounds: {e}"))?;
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

fn mega(x: f64) -> String {
    format!("{:.2} M", x / 1e6)
}

/// The table (markdown) and a recommendation.
pub fn markdown(b: &Budget, fps: Option<f64>, max_error: Option<f64>) -> String {
    let c = b.chip;
    let mut s = String::new();
    let _ = writeln!(s, "Scene `{}` on `{}`: {}.", b.scene, c.name, c.what);
    let _ = writeln!(
        s,
        "Predicted {} per frame by stage (counted work times the unit costs of `host-sim/costs.csv`), ms at {} MHz; image error against the f64 per-pixel frame, per pixel, in 8-bit levels (largest channel). * = on the Pareto front (time against mean error); d = some costs derived from the QEMU budget's counts, not calibrated on this chip.\n",
        c.unit, c.mhz
    );
    let _ = writeln!(s, "| backend | shading | transform | shade | raster | flush | frame | ms | fps | max error | mean error | |");
    let _ = writeln!(
        s,
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"
    );
    for r in &b.rows {
        let p = &r.predicted;
        let _ = writeln!(
            s,
            "| {}{} | {} | {} | {} | {} | {} | {} | {:.1} | {:.1} | {:.0} | {:.2} | {} |",
            r.backend,
            if r.derived { " (d)" } else { "" },
            r.shading,
            mega(p.transform),
            mega(p.shade),
            mega(p.raster),
            mega(p.flush),
            mega(p.total()),
            r.ms,
            1000.0 / r.ms.max(1e-9),
            r.max_err,
            r.mean_err,
            if r.pareto { "*" } else { "" }
        );
    }
    for k in &b.skipped {
        let _ = writeln!(s, "\n{}: not possible: {}", k.backend, k.why);
    }
    let _ = writeln!(s);
    s.push_str(&answer(b, fps, max_error));
    s
}

/// The answer to `--fps` and `--max-error`: the recommended option, or what misses and by how
/// much.
pub fn answer(b: &Budget, fps: Option<f64>, max_error: Option<f64>) -> String {
    let mut s = String::new();
    if let Some(r) = b
        .rows
        .iter()
        .find(|r| r.tessellation == 1.0 && r.shading.ends_with("(as written)"))
    {
        let _ = writeln!(
            s,
            "As written (the file's shading and meshes, {} on this chip): {:.1} ms ({:.1} fps), mean error {:.2}, max {:.0} levels.\n",
            r.backend,
            r.ms,
            1000.0 / r.ms,
            r.mean_err,
            r.max_err
        );
    }
    let want = match (fps, max_error) {
        (None, None) => "the fastest option".to_owned(),
        (Some(f), None) => format!("{f} fps"),
        (None, Some(e)) => format!("a mean error of at most {e} levels"),
        (Some(f), Some(e)) => format!("{f} fps with a mean error of at most {e} levels"),
    };
    match recommend(&b.rows, fps, max_error) {
        Some(r) => {
            let _ = writeln!(
                s,
                "Recommended for {want}: {} with {}: {:.1} ms ({:.1} fps), mean error {:.2}, max {:.0} levels.",
                r.backend, r.shading, r.ms, 1000.0 / r.ms, r.mean_err, r.max_err
            );
        }
        None => {
            let fastest = b.rows.iter().min_by(|a, b| a.ms.total_cmp(&b.ms));
            let _ = write!(s, "Nothing meets {want}.");
            if let Some(r) = fastest {
                let _ = write!(
                    s,
                    " The fastest option, {} with {}, takes {:.1} ms ({:.1} fps)",
                    r.backend,
                    r.shading,
                    r.ms,
                    1000.0 / r.ms
                );
                if let Some(f) = fps {
                    let _ = write!(
                        s,
                        ": {:.1} times the {:.1} ms of {f} fps",
                        r.ms / (1000.0 / f),
                        1000.0 / f
                    );
                }
                let _ = write!(s, ", mean error {:.2} levels", r.mean_err);
                if let Some(e) = max_error {
                    let best = b
                        .rows
                        .iter()
                        .map(|r| r.mean_err)
                        .fold(f64::INFINITY, f64::min);
                    if best > e {
                        let _ = write!(s, "; the most accurate option's mean error is {best:.2} levels, above {e}");
                    }
                }
                let _ = writeln!(s, ".");
            }
        }
    }
    s
}

/// The rows as CSV.
pub fn csv(b: &Budget) -> String {
    let mut s = String::from("chip,backend,derived,shading,transform,shade,raster,flush,frame,unit,ms,max_err,mean_err,pareto,vertices,vertex_calls,pixel_calls,pixels,triangle_setups,bands\n");
    for r in &b.rows {
        let p = &r.predicted;
        let w = &r.work;
        let _ = writeln!(
            s,
            "{},{},{},\"{}\",{:.0},{:.0},{:.0},{:.0},{:.0},{},{:.3},{},{:.4},{},{},{},{},{},{},{}",
            b.chip.name,
            r.backend,
            r.derived,
            r.shading,
            p.transform,
            p.shade,
            p.raster,
            p.flush,
            p.total(),
            b.chip.unit,
            r.ms,
            r.max_err,
            r.mean_err,
            r.pareto,
            w.total(|o| o.vertices_lit + o.vertices_unlit),
            w.total(|o| o.vertex_calls),
            w.total(|o| o.pixel_calls),
            w.total(|o| o.pixels),
            w.total(|o| o.setups),
            w.bands
        );
    }
    s
}

/// Frame time (x, ms) against mean error (y), one dot per option, the Pareto front joined.
pub fn plot(b: &Budget) -> Result<Pixmap, String> {
    let w = 900u32;
    // The legend: one line per option (the numbers on the dots).
    let legend_h = 14 * b.rows.len() as u32 + 10;
    let h = 430 + legend_h;
    let mut pix = Pixmap::new(w, h).ok_or("plot size")?;
    pix.fill(tiny_skia::Color::from_rgba8(255, 255, 255, 255));
    let (x0, y0, pw, ph) = (70.0f32, 40.0f32, 780.0f32, 330.0f32);
    // Time on a log scale (options span three orders of magnitude), whole decades.
    let lo = b
        .rows
        .iter()
        .map(|r| r.ms)
        .fold(f64::INFINITY, f64::min)
        .max(1e-3);
    let hi = b.rows.iter().map(|r| r.ms).fold(lo * 10.0, f64::max);
    let (d0, d1) = (
        lo.log10().floor(),
        hi.log10().ceil().max(lo.log10().floor() + 1.0),
    );
    let max_e = b.rows.iter().map(|r| r.mean_err).fold(0.1, f64::max) * 1.15;
    let px = |ms: f64| x0 + ((ms.max(1e-3).log10() - d0) / (d1 - d0)) as f32 * pw;
    let py = |e: f64| y0 + ph - (e / max_e) as f32 * ph;
    let black = [0, 0, 0];
    let mut paint = Paint::default();
    paint.set_color_rgba8(0, 0, 0, 255);
    paint.anti_alias = true;
    let stroke = Stroke {
        width: 1.0,
        ..Stroke::default()
    };
    let mut axes = PathBuilder::new();
    axes.move_to(x0, y0);
    axes.line_to(x0, y0 + ph);
    axes.line_to(x0 + pw, y0 + ph);
    if let Some(p) = axes.finish() {
        pix.stroke_path(&p, &paint, &stroke, Transform::identity(), None);
    }
    let title = format!(
        "{} on {}: frame time against image error",
        b.scene, b.chip.name
    );
    figure::text(&mut pix, &title, x0 as i32, 10, black, Font::Big);
    for d in (d0 as i32)..=(d1 as i32) {
        let ms = 10f64.powi(d);
        figure::text(
            &mut pix,
            &format!("{ms}"),
            px(ms) as i32 - 10,
            (y0 + ph) as i32 + 6,
            black,
            Font::Small,
        );
    }
    for k in 0..=4 {
        let e = max_e * f64::from(k) / 4.0;
        figure::text(
            &mut pix,
            &format!("{e:.2}"),
            30,
            py(e) as i32 - 5,
            black,
            Font::Small,
        );
    }
    figure::text(
        &mut pix,
        &format!("predicted ms per frame at {} MHz (log scale)", b.chip.mhz),
        (x0 + pw / 2.0) as i32 - 110,
        (y0 + ph) as i32 + 22,
        black,
        Font::Small,
    );
    figure::text(
        &mut pix,
        "mean error, 8-bit levels",
        4,
        24,
        black,
        Font::Small,
    );
    let mut front: Vec<&Row> = b.rows.iter().filter(|r| r.pareto).collect();
    front.sort_by(|a, b| a.ms.total_cmp(&b.ms));
    let mut line = PathBuilder::new();
    for (i, r) in front.iter().enumerate() {
        if i == 0 {
            line.move_to(px(r.ms), py(r.mean_err));
        } else {
            line.line_to(px(r.ms), py(r.mean_err));
        }
    }
    paint.set_color_rgba8(180, 180, 180, 255);
    if let Some(p) = line.finish() {
        pix.stroke_path(&p, &paint, &stroke, Transform::identity(), None);
    }
    let colour = |backend: &str| match backend {
        "fixed" => (200u8, 60u8, 40u8),
        "f32" => (40, 90, 200),
        _ => (40, 150, 80),
    };
    for (i, r) in b.rows.iter().enumerate() {
        let (cr, cg, cb) = colour(r.backend);
        paint.set_color_rgba8(cr, cg, cb, 255);
        if let Some(c) =
            PathBuilder::from_circle(px(r.ms), py(r.mean_err), if r.pareto { 5.0 } else { 3.5 })
        {
            pix.fill_path(
                &c,
                &paint,
                tiny_skia::FillRule::Winding,
                Transform::identity(),
                None,
            );
        }
        // Labels by index (the legend below says which is which), staggered against overlap.
        let dy = if i % 2 == 0 { -14 } else { 6 };
        figure::text(
            &mut pix,
            &format!("{}", i + 1),
            px(r.ms) as i32 + 6,
            py(r.mean_err) as i32 + dy,
            [cr, cg, cb],
            Font::Small,
        );
    }
    let mut y = (y0 + ph) as i32 + 40;
    for (i, r) in b.rows.iter().enumerate() {
        let (cr, cg, cb) = colour(r.backend);
        let label = format!(
            "{:>2} {}{}: {}: {:.1} ms, mean error {:.2}",
            i + 1,
            r.backend,
            if r.pareto { " (Pareto front)" } else { "" },
            r.shading,
            r.ms,
            r.mean_err
        );
        figure::text(&mut pix, &label, 10, y, [cr, cg, cb], Font::Small);
        y += 14;
    }
    Ok(pix)
}

/// An emulated frame `--check` compares with.
struct Measured {
    /// Which frame.
    label: String,
    /// The option, in `assignments`' words.
    plan: String,
    /// Its cost, in the chip's unit.
    units: f64,
    /// The firmware's counts: shader calls, pixels, triangle setups.
    counts: Option<[u64; 3]>,
}

/// The emulated frames of `path` for `chip` (frame 0 of each) that render the scene file named
/// `scene` (its stem): the demo firmware's frames for `demo`, the scene-file firmware's
/// (`scene:<name>`: `boards/demo-scene`'s spec player, the scene as written) for the others.
fn measured(path: &Path, chip: &Chip, scene: &str) -> Result<Vec<Measured>, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
    let col = |n: &str| header.iter().position(|h| *h == n);
    let mut out = Vec::new();
    let stages = ["setup", "transform", "shade", "raster", "flush", "wait"];
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        let get = |n: &str| col(n).and_then(|i| f.get(i)).copied();
        if get("frame") != Some("0") {
            continue;
        }
        // The firmware's own stage timing of frame 0 (the whole render_frame).
        let sum: f64 = stages
            .iter()
            .filter_map(|s| get(s).and_then(|x| x.parse::<f64>().ok()))
            .sum();
        let count = |n: &str| get(n).and_then(|x| x.parse::<u64>().ok());
        let counts = match (
            count("shader_calls"),
            count("pixels"),
            count("triangle_setups"),
        ) {
            (Some(a), Some(b), Some(c)) => Some([a, b, c]),
            _ => None,
        };
        let file = get("firmware")
            .or(get("mode"))
            .and_then(|m| m.strip_prefix("scene:"));
        if let Some(name) = file {
            let cores = get("cores")
                .and_then(|c| c.parse::<u32>().ok())
                .unwrap_or(1);
            if name == scene && cores == chip.cores {
                let units = get("total").and_then(|x| x.parse().ok()).unwrap_or(sum);
                out.push(Measured {
                    label: format!("scene-file firmware, {name} frame 0"),
                    plan: "as written".to_owned(),
                    units,
                    counts,
                });
            }
            continue;
        }
        if scene != "demo" {
            continue;
        }
        if let Some(fw) = get("firmware") {
            let want = if chip.cores > 1 {
                "lit_scene_dual_core"
            } else {
                "lit_scene"
            };
            if fw == want {
                out.push(Measured {
                    label: format!("{fw} frame 0"),
                    plan: "as written".to_owned(),
                    units: sum,
                    counts,
                });
            }
        } else if let Some(mode) = get("mode") {
            let plan = match mode {
                "gouraud" => "all Gouraud".to_owned(),
                "per_pixel" => "all per pixel".to_owned(),
                m => match m.strip_suffix("_per_pixel") {
                    Some(kind) => format!("{kind} per pixel"),
                    None => continue,
                },
            };
            let total = get("total").and_then(|x| x.parse().ok()).unwrap_or(sum);
            out.push(Measured {
                label: format!("qemu-frame {mode} frame 0"),
                plan,
                units: total,
                counts,
            });
        }
    }
    if out.is_empty() {
        return Err(format!(
            "{}: no frame 0 of {scene} for {}",
            path.display(),
            chip.name
        ));
    }
    Ok(out)
}

/// `--check`: each measured frame against the prediction of the same option in the chip's
/// first backend. Returns the table and whether every one is within [`CHECK_TOLERANCE`].
pub fn check(b: &Budget, path: &Path) -> Result<(String, bool), String> {
    let backend = b.chip.backends[0];
    let mut s = String::new();
    let _ = writeln!(
        s,
        "| emulated frame | option | predicted | measured | prediction / measured | counts (shader calls, pixels, triangle setups) |"
    );
    let _ = writeln!(s, "|---|---|---:|---:|---:|---|");
    let mut ok = true;
    for m in measured(path, b.chip, &stem(Path::new(&b.scene)))? {
        let (label, plan, units) = (m.label, m.plan, m.units);
        let row = b.rows.iter().filter(|r| r.backend == backend).find(|r| {
            if r.tessellation != 1.0 || r.variant != Variant::AsWritten {
                false
            } else if plan == "as written" {
                r.shading.ends_with("(as written)")
            } else if plan == "all Gouraud" {
                r.shading.starts_with("Gouraud")
            } else if plan == "all per pixel" {
                r.shading.starts_with("per pixel") && !r.shading.contains(':')
            } else {
                let kind = plan.trim_end_matches(" per pixel");
                r.shading.starts_with(&format!("per pixel: {kind} ")) && !r.shading.contains(", ")
            }
        });
        let Some(r) = row else {
            return Err(format!("{label}: no option \"{plan}\" in {backend}"));
        };
        let ratio = r.predicted.total() / units;
        let within = (ratio - 1.0).abs() <= CHECK_TOLERANCE;
        ok &= within;
        // The host's counts must be the firmware's, exactly (the same frame path).
        let w = &r.work;
        let host = [
            w.total(|o| o.vertex_calls + o.pixel_calls),
            w.total(|o| o.pixels),
            w.total(|o| o.setups),
        ];
        let counted = match m.counts {
            Some(c) if c == host => format!("{} {} {}, equal", c[0], c[1], c[2]),
            Some(c) => {
                ok = false;
                format!(
                    "firmware {} {} {}, host {} {} {}: DIFFERENT",
                    c[0], c[1], c[2], host[0], host[1], host[2]
                )
            }
            None => "-".to_owned(),
        };
        let _ = writeln!(
            s,
            "| {label} | {backend}, {} | {} | {} | {:.3}{} | {counted} |",
            r.shading,
            mega(r.predicted.total()),
            mega(units),
            ratio,
            if within { "" } else { " (beyond 15 %)" }
        );
    }
    Ok((s, ok))
}

fn stem(path: &Path) -> String {
    path.file_stem()
        .map_or("scene".into(), |s| s.to_string_lossy().into_owned())
}

/// `host-sim budget --scene`: prints the table, writes DIR/<stem>-<chip>.md, .csv, .png and
/// -answer.md (the answer and the check alone);
/// with `--check`, compares and fails beyond the tolerance.
pub fn main(args: &BudgetArgs, scene: &Path) -> ExitCode {
    if let Some(out) = &args.emit_spec {
        return emit_spec_main(scene, out);
    }
    match run(args, scene) {
        Ok((paths, ok)) => {
            for p in paths {
                println!("{}", p.display());
            }
            if ok {
                ExitCode::SUCCESS
            } else {
                eprintln!(
                    "host-sim budget: a prediction is beyond 15 % of the emulated frame, or the counts differ"
                );
                ExitCode::FAILURE
            }
        }
        Err(e) => {
            eprintln!("host-sim budget: {e}");
            ExitCode::FAILURE
        }
    }
}

/// `--emit-spec OUT.rs`: writes the scene's Rust source for the boards.
fn emit_spec_main(scene: &Path, out: &Path) -> ExitCode {
    let made = std::fs::read_to_string(scene)
        .map_err(|e| format!("{}: {e}", scene.display()))
        .and_then(|src| crate::scene_file::emit_spec(&scene.display().to_string(), &src))
        .and_then(|source| {
            std::fs::write(out, source).map_err(|e| format!("{}: {e}", out.display()))
        });
    match made {
        Ok(()) => {
            println!("{}", out.display());
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("host-sim budget: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(args: &BudgetArgs, scene: &Path) -> Result<(Vec<PathBuf>, bool), String> {
    let chip = args.chip.as_deref().unwrap_or("rp2040");
    let b = budget(scene, chip)?;
    let mut md = markdown(&b, args.fps, args.max_error);
    let mut short = answer(&b, args.fps, args.max_error);
    let mut ok = true;
    let mut check_table = None;
    if let Some(frames) = &args.check {
        let (table, fine) = check(&b, frames)?;
        // The same rows with the scene and the chip first (CI joins these tables into one).
        let with_scene: Vec<String> = table
            .lines()
            .enumerate()
            .map(|(i, l)| match i {
                0 => format!("| scene | chip {l}"),
                1 => format!("|---|---{l}"),
                _ => format!("| {} | {} {l}", stem(scene), b.chip.name),
            })
            .collect();
        check_table = Some(with_scene.join("\n") + "\n");
        let checked = format!(
            "\nAgainst the emulated frames of `{}`:\n\n{table}",
            frames.display()
        );
        md.push_str(&checked);
        short.push_str(&checked);
        ok = fine;
    }
    print!("{md}");
    std::fs::create_dir_all(&args.out)
        .map_err(|e| format!("cannot create {}: {e}", args.out.display()))?;
    let base = format!("{}-{}", stem(scene), b.chip.name);
    let md_path = args.out.join(format!("{base}.md"));
    std::fs::write(&md_path, &md).map_err(|e| format!("{}: {e}", md_path.display()))?;
    let csv_path = args.out.join(format!("{base}.csv"));
    std::fs::write(&csv_path, csv(&b)).map_err(|e| format!("{}: {e}", csv_path.display()))?;
    let png = figure::save(&plot(&b)?, &args.out, &format!("{base}.png"))?;
    // The answer and the check alone (for the README's worked example).
    let answer_path = args.out.join(format!("{base}-answer.md"));
    std::fs::write(&answer_path, &short).map_err(|e| format!("{}: {e}", answer_path.display()))?;
    let mut written = vec![md_path, csv_path, png, answer_path];
    if let Some(t) = check_table {
        let path = args.out.join(format!("{base}-check.md"));
        std::fs::write(&path, t).map_err(|e| format!("{}: {e}", path.display()))?;
        written.push(path);
    }
    Ok((written, ok))
}

/// `host-sim budget --calibrate`: writes host-sim/costs.csv from the emulators' measurements.
pub fn calibrate_main(counts: &Path) -> ExitCode {
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    let root = here.parent().unwrap_or(here);
    let made = costs::calibrate(
        &root.join("target/rp2040-emu"),
        &root.join("target/qemu-frame"),
        counts,
    );
    match made {
        Ok(csv) => {
            let path = here.join("costs.csv");
            match std::fs::write(&path, csv) {
                Ok(()) => {
                    println!("{}", path.display());
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("host-sim budget --calibrate: {}: {e}", path.display());
                    ExitCode::FAILURE
                }
            }
        }
        Err(e) => {
            eprintln!("host-sim budget --calibrate: {e}");
            ExitCode::FAILURE
        }
    }
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
mod tests {
    use super::costs::{call_cost, calls_cost, predict, Costs, Finish, LightCost, CHIPS};
    use super::work::{LightCalls, ObjectWork, Work};
    use super::*;

    use super::demo_scene;

    const DEMO: &str = include_str!("../../scenes/demo.toml");

    /// A cost table in the committed file's format: every item one chip needs.
    fn synthetic() -> Costs {
        let mut csv = String::from("chip,backend,item,cost,source\n");
        for (item, c) in [
            ("lit_matte", 10.0),
            ("lit_specular", 20.0),
            ("diffuse:polygon", 1000.0),
            ("phong8:polygon", 2000.0),
            ("phong32:polygon", 4400.0),
            ("diffuse:ambient", 1.0),
            ("phong8:ambient", 0.0),
            ("phong32:ambient", 0.0),
            ("vertex_lit", 300.0),
            ("vertex_unlit", 200.0),
            ("shade_vertex", 50.0),
            ("shade_vertex_flat", 30.0),
            ("diffuse:polygon:lit", 1500.0),
            ("diffuse:polygon:dark", 200.0),
            ("phong8:polygon:lit", 3000.0),
            ("phong8:polygon:dark", 100.0),
            ("band_clear", 7000.0),
            ("triangle", 2000.0),
            ("pixel", 80.0),
            ("pixel_shaded", 90.0),
            ("flush_byte", 1.5),
        ] {
            csv.push_str(&format!("chip,f32,{item},{c},calibrate\n"));
        }
        Costs::parse(&csv, "chip").unwrap()
    }

    #[test]
    fn a_shader_call_costs_the_material_and_each_light_with_phong_linear_in_m() {
        let c = synthetic();
        let lights = [
            LightCost {
                kind: "polygon".into(),
                vertices: 8,
            },
            LightCost {
                kind: "ambient".into(),
                vertices: 0,
            },
        ];
        // m = 20: halfway between 8 and 32 on the polygon's phong: 3200; an octagon is twice
        // a quad.
        let got = call_cost(
            &c,
            "f32",
            &lights,
            Finish::Lit {
                specular: true,
                m: 20,
            },
        )
        .unwrap();
        assert_eq!(got, 20.0 + 2.0 * (1000.0 + 3200.0) + 1.0);
        let matte = call_cost(
            &c,
            "f32",
            &lights,
            Finish::Lit {
                specular: false,
                m: 20,
            },
        )
        .unwrap();
        assert_eq!(matte, 10.0 + 2.0 * 1000.0 + 1.0);
        assert_eq!(
            call_cost(&c, "f32", &lights, Finish::Emissive).unwrap(),
            0.0
        );
        let unknown = [LightCost {
            kind: "line".into(),
            vertices: 0,
        }];
        let e = call_cost(
            &c,
            "f32",
            &unknown,
            Finish::Lit {
                specular: false,
                m: 1,
            },
        )
        .unwrap_err();
        assert!(e.contains("diffuse:line"), "{e}");
    }

    #[test]
    fn lit_and_dark_calls_take_their_own_costs_where_measured() {
        let c = synthetic();
        let lights = [
            LightCost {
                kind: "polygon".into(),
                vertices: 4,
            },
            LightCost {
                kind: "ambient".into(),
                vertices: 0,
            },
        ];
        let per_light = [
            LightCalls {
                diffuse: [3, 2],
                phong: [1, 4],
            },
            LightCalls {
                diffuse: [5, 0],
                phong: [0, 5],
            },
        ];
        let matte = Finish::Lit {
            specular: false,
            m: 8,
        };
        // The material's own 10 per call; the polygon's split costs; the ambient light has no
        // split: its cost over all points (1), lit or dark.
        assert_eq!(
            calls_cost(&c, "f32", &lights, matte, 5, &per_light).unwrap(),
            5.0 * 10.0 + 3.0 * 1500.0 + 2.0 * 200.0 + 5.0 * 1.0
        );
        // Phong at m = 8: the polygon's split phong8; phong32 has no split (4000 for both),
        // and at m = 8 only phong8 counts.
        let shiny = Finish::Lit {
            specular: true,
            m: 8,
        };
        assert_eq!(
            calls_cost(&c, "f32", &lights, shiny, 5, &per_light).unwrap(),
            5.0 * 20.0 + 3.0 * 1500.0 + 2.0 * 200.0 + 5.0 + 3000.0 + 4.0 * 100.0
        );
        // Without per-light counts: every call at call_cost.
        assert_eq!(
            calls_cost(&c, "f32", &lights, matte, 5, &[]).unwrap(),
            5.0 * call_cost(&c, "f32", &lights, matte).unwrap()
        );
        assert_eq!(
            calls_cost(&c, "f32", &lights, Finish::Emissive, 5, &per_light).unwrap(),
            0.0
        );
    }

    #[test]
    fn a_frame_is_its_counted_work_times_the_unit_costs() {
        let c = synthetic();
        let chip = CHIPS.iter().find(|c| c.name == "stm32f411").unwrap();
        let work = Work {
            objects: vec![
                ObjectWork {
                    vertices_lit: 100,
                    vertex_calls: 40,
                    pixels: 1000,
                    setups: 30,
                    ..ObjectWork::default()
                },
                ObjectWork {
                    vertices_unlit: 10,
                    vertex_calls: 5,
                    pixel_calls: 0,
                    pixels: 200,
                    setups: 4,
                    ..ObjectWork::default()
                },
            ],
            bands: 15,
            bytes: 115_200,
        };
        let lights = [LightCost {
            kind: "polygon".into(),
            vertices: 4,
        }];
        let finishes = [
            Finish::Lit {
                specular: false,
                m: 1,
            },
            Finish::Emissive,
        ];
        let p = predict(chip, &c, "f32", &work, &finishes, &lights).unwrap();
        assert_eq!(p.transform, 100.0 * 300.0 + 10.0 * 200.0);
        // The emissive object's vertices at the flat shader's cost.
        assert_eq!(p.shade, 40.0 * (50.0 + 10.0 + 1000.0) + 5.0 * 30.0);
        assert_eq!(p.raster, 15.0 * 7000.0 + 34.0 * 2000.0 + 1200.0 * 80.0);
        assert_eq!(p.flush, 115_200.0 * 1.5);
        // Two cores halve shade and raster and send every band from core 0 (twice the flush).
        let dual = CHIPS.iter().find(|c| c.name == "rp2040-dual").unwrap();
        let d = predict(dual, &c, "f32", &work, &finishes, &lights).unwrap();
        assert_eq!(
            (d.shade, d.raster, d.flush),
            (p.shade / 2.0, p.raster / 2.0, 2.0 * p.flush)
        );
    }

    #[test]
    fn the_pareto_front_and_the_recommendation() {
        let row = |ms: f64, e: f64| Row {
            backend: "f32",
            shading: format!("{ms} {e}"),
            tessellation: 1.0,
            variant: Variant::AsWritten,
            predicted: Prediction::default(),
            ms,
            max_err: e,
            mean_err: e,
            derived: false,
            pareto: false,
            work: Work::default(),
        };
        let mut rows = vec![
            row(10.0, 3.0),
            row(20.0, 1.0),
            row(30.0, 2.0),
            row(40.0, 0.0),
        ];
        mark_pareto(&mut rows);
        let front: Vec<bool> = rows.iter().map(|r| r.pareto).collect();
        assert_eq!(front, [true, true, false, true]);
        assert_eq!(recommend(&rows, Some(60.0), None).unwrap().ms, 10.0);
        assert_eq!(recommend(&rows, Some(40.0), Some(1.5)).unwrap().ms, 20.0);
        assert!(recommend(&rows, Some(100.0), Some(1.5)).is_none());
    }

    /// The scene file of the demo is the firmware's frame: the host's counts of the scene
    /// file equal `boards/demo-scene`'s own frame 0 (the board code, rendered here), in f32
    /// with its 16-row bands.
    #[test]
    fn the_demo_scene_file_counts_what_the_board_demo_draws() {
        use arealight::raster::{Band, Rgb565};
        let mut buffers = Box::new(demo_scene::MeshBuffers::<f32>::new());
        let mut demo = demo_scene::Demo::new(&mut buffers, Shading::Gouraud).unwrap();
        let (mut px, mut depth) = (
            vec![Rgb565(0); demo_scene::BAND_PIXELS],
            vec![0u16; demo_scene::BAND_PIXELS],
        );
        let mut band = Band::new(&mut px, Some(&mut depth), demo_scene::WIDTH, 0).unwrap();
        let report = demo
            .render_frame(0, &mut band, &mut || 0, |_| Ok::<(), ()>(()))
            .unwrap();
        let parsed = scene_file::parse_as::<f32>("demo.toml", DEMO).unwrap();
        let shading = vec![Shading::Gouraud; parsed.scene.objects.len()];
        let (_, work) = work::render(&parsed.scene, &shading, demo_scene::BAND_ROWS).unwrap();
        let s = report.stats;
        assert_eq!(
            [
                work.total(|o| o.vertex_calls + o.pixel_calls),
                work.total(|o| o.pixels),
                work.total(|o| o.setups)
            ],
            [
                u64::from(s.shaded),
                u64::from(s.pixels),
                u64::from(s.rasterized)
            ]
        );
        assert_eq!(work.total(|o| o.vertices_lit), 231 + 275);
        assert_eq!(work.total(|o| o.vertices_unlit), 77);
        assert_eq!(work.bands, 15);
    }

    /// Every scene of host-sim/scenes on every chip: rows for the chip's first backend (the
    /// firmware's), finite positive times, and the f32 per-pixel frame within a level of the
    /// f64 one (the same path in another precision).
    #[test]
    fn every_scene_budgets_on_every_chip() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
        let mut scenes: Vec<PathBuf> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "toml"))
            .collect();
        scenes.sort();
        assert!(scenes.len() >= 3, "{scenes:?}");
        for scene in &scenes {
            for chip in CHIPS {
                let b = budget(scene, chip.name).unwrap();
                let first = chip.backends[0];
                assert!(
                    b.rows.iter().any(|r| r.backend == first)
                        || b.skipped.iter().any(|s| s.backend == first),
                    "{} {}",
                    scene.display(),
                    chip.name
                );
                for r in &b.rows {
                    assert!(r.ms.is_finite() && r.ms > 0.0, "{r:?}");
                    assert!((0.0..=255.0).contains(&r.max_err), "{r:?}");
                }
                if let Some(r) = b.rows.iter().find(|r| {
                    r.backend == "f32" && r.shading == "per pixel" && r.tessellation == 1.0
                }) {
                    assert!(r.max_err <= 1.0, "{} {}: {r:?}", scene.display(), chip.name);
                }
                assert!(b.rows.iter().any(|r| r.pareto));
            }
        }
    }
}
