//! `host-sim budget --out DIR`: the accuracy/cost budget, one row per model id x backend, and
//! beside them the alternatives a user would pick instead (a point light; each area light by
//! k = 1, 4, 16, 64 point samples).
//!
//! Writes `DIR/budget.csv` (`model,backend,host_ns,m4f_insns,m0_insns,code_bytes,max_abs_err,
//! rms_err,rv32imc_insns`, empty where a figure does not apply; the RISC-V column last, so the
//! issue's columns keep their positions), `DIR/budget.md` (the same as tables, with
//! what each column is), `DIR/budget-table.md` (the deterministic tables alone: instruction
//! counts, code bytes, errors; the README embeds it and CI compares it), `DIR/budget-unit.md`
//! (the calls that take a normal, with a `Vec3` and with a `UnitVec3`), `DIR/budget-world.md`
//! (the positional lights in world coordinates against plain ones), `DIR/budget-bar.md`
//! (`phong_polygon` as issues 12 and 13 set their bars: a `PolygonLight<_, 4>` at m = 15),
//! `DIR/budget-host.md`
//! (the host times, one machine's) and `DIR/budget.png` (host time against max error, log-log,
//! Pareto front highlighted).
//!
//! - host ns per call: each kernel of `boards/qemu-budget/src/cases.rs` (the firmware's), timed
//!   over many repetitions per input on the 16 inputs of the QEMU harness; the median over the
//!   inputs, then the median of 5 runs. This build's figures; run it with `--release`.
//! - M4F / M0 / RV32IMC instructions per call: the median over the harness's inputs, read from
//!   `target/qemu-budget/counts.csv` (written by `cargo test -p host-sim --test qemu_budget`;
//!   RV32IMC is `riscv32imc-unknown-none-elf`, ESP32-C3 class, on QEMU `virt`); empty when that
//!   file is missing or has no row.
//! - code bytes: the kernel and everything it reaches, from the same file (thumbv7em for the
//!   float backends, thumbv6m for fixed point).
//! - errors: absolute differences from the library's f64 path (for the alternatives, from the
//!   exact f64 model they approximate) over `--samples` random unit directions (deterministic),
//!   all channels of the RGB models. Every model row is held to the README's accuracy target
//!   ([`target`]: f32 `2e-6 + m 2^-24`, these cases being well-conditioned; f32-fast and fixed
//!   1/1024); `host-sim budget` fails, after writing its files, if a row misses it.

use std::collections::HashMap;
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use arealight::{Fast32, Fixed22, Real};
use clap::Args;

#[allow(dead_code)]
#[path = "../../boards/qemu-budget/src/bar_cases.rs"]
mod bar_cases;
#[allow(dead_code)]
#[path = "../../boards/qemu-budget/src/cases.rs"]
mod cases;
#[allow(dead_code)]
#[path = "../../boards/qemu-budget/src/points.rs"]
mod points;
#[allow(dead_code)]
#[path = "../../boards/qemu-budget/src/world_cases.rs"]
mod world_cases;

use cases::{Backend, Dirs, Lights, Meter, Sample, MODELS};

mod chart;
mod tables;
pub use chart::plot;
#[cfg(test)]
use tables::pareto;
pub use tables::{
    bar_markdown, csv, host_times, markdown, pareto_by, unit_markdown, world_markdown,
};

/// The CSV header (fixed by the issue), then the RISC-V counts (issue 12), last so that the
/// issue's columns keep their positions.
pub const HEADER: &str =
    "model,backend,host_ns,m4f_insns,m0_insns,code_bytes,max_abs_err,rms_err,rv32imc_insns";

/// Arguments of `host-sim budget`.
#[derive(Args, Debug)]
pub struct BudgetArgs {
    /// Directory to write budget.md, budget.csv and budget.png into (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// The QEMU harness's counts (instructions and code size per target).
    #[arg(
        long,
        value_name = "FILE",
        default_value = "target/qemu-budget/counts.csv"
    )]
    pub counts: PathBuf,
    /// Random directions per model for the errors.
    #[arg(long, default_value_t = 4096)]
    pub samples: usize,
    /// Timing repetitions per input (fewer: faster and noisier).
    #[arg(long, default_value_t = 400)]
    pub reps: u32,
    /// Budget a scene file instead (docs/scene-budget.md): frame time per stage and image
    /// error of each option on --chip; writes DIR/<stem>-<chip>.md, .csv and .png.
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
    /// The chip of --scene: rp2040, rp2040-dual, stm32f411 or cortex-m0.
    #[arg(
        long,
        value_name = "NAME",
        default_value = "rp2040",
        requires = "scene"
    )]
    pub chip: Option<String>,
    /// With --scene: the frame rate to meet.
    #[arg(long, value_name = "F", requires = "scene")]
    pub fps: Option<f64>,
    /// With --scene: the largest mean error per pixel to accept, in 8-bit levels.
    #[arg(long, value_name = "E", requires = "scene")]
    pub max_error: Option<f64>,
    /// With --scene: compare the predictions with the emulated frames of FRAMES.csv
    /// (target/rp2040-emu/frames.csv or target/qemu-frame/frames.csv); exit non-zero if one
    /// is more than 15 % off.
    #[arg(long, value_name = "FRAMES.csv", requires = "scene")]
    pub check: Option<PathBuf>,
    /// With --scene: write the scene, as written, as Rust source for the boards' scene player
    /// (`boards/demo-scene/src/spec.rs`: a `SceneSpec` constant) into OUT.rs, and nothing
    /// else (`boards/demo-scene/src/scenes/` holds the scenes the boards render).
    #[arg(long, value_name = "OUT.rs", requires = "scene")]
    pub emit_spec: Option<PathBuf>,
    /// Write host-sim/costs.csv (the unit costs of --scene) from the emulators' calibration
    /// runs (target/rp2040-emu, target/qemu-frame) and the QEMU budget's counts.
    #[arg(long, conflicts_with = "scene")]
    pub calibrate: bool,
}

/// One row of the budget.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// Model id (or alternative name: `point_lambert`, `point_phong`).
    pub model: String,
    /// Backend (`f32`, `f32-fast`, `fixed`) or alternative (`f32-pts<k>`).
    pub backend: String,
    /// Host nanoseconds per call.
    pub host_ns: f64,
    /// Cortex-M4F instructions per call (median), if measured.
    pub m4f: Option<u64>,
    /// Cortex-M0 instructions per call (median), if measured.
    pub m0: Option<u64>,
    /// RV32IMC (ESP32-C3 class) instructions per call (median), if measured.
    pub rv32: Option<u64>,
    /// Code bytes, if measured.
    pub code: Option<u64>,
    /// Largest absolute error.
    pub max_err: f64,
    /// Root-mean-square error.
    pub rms_err: f64,
    /// Which kind of point it is in the plot.
    pub kind: Kind,
}

/// What a row is, for the plot's colours.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// An analytic model, f32 (libm).
    F32,
    /// An analytic model, f32 with the crate's fast sqrt/atan2.
    Fast,
    /// An analytic model, fixed point.
    Fixed,
    /// A point light.
    Point,
    /// An area light by k point samples.
    Sampled,
}

/// The host meter: repeats each call and reports picoseconds per call.
struct Timer {
    reps: u32,
}

impl Meter for Timer {
    fn call<R>(&mut self, f: impl Fn() -> R) -> (R, u32) {
        let r = f();
        let t = Instant::now();
        for _ in 0..self.reps {
            // Hiding the closure (its captured light and input) each time keeps the call from
            // being hoisted out of the loop.
            black_box(black_box(&f)());
        }
        let ps = t.elapsed().as_nanos() * 1000 / u128::from(self.reps.max(1));
        (r, u32::try_from(ps).unwrap_or(u32::MAX))
    }
}

struct Plain;

impl Meter for Plain {
    fn call<R>(&mut self, f: impl Fn() -> R) -> (R, u32) {
        (f(), 0)
    }
}

/// Deterministic random unit directions (xorshift64*, rejection from the cube).
pub fn random_dirs(n: usize, seed: u64) -> Vec<[f64; 3]> {
    let mut s = seed.max(1);
    let mut next = || {
        s ^= s >> 12;
        s ^= s << 25;
        s ^= s >> 27;
        (s.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let v = [next(), next(), next()];
        let l2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        if l2 > 1e-4 && l2 <= 1.0 {
            let l = l2.sqrt();
            out.push(v.map(|x| x / l));
        }
    }
    out
}

fn round_f32(x: f64) -> f64 {
    x as f32 as f64
}

fn round_fixed(x: f64) -> f64 {
    Fixed22::from_f64(x).to_f64()
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(0.0)
}

/// Max and RMS of the absolute differences, over every channel.
fn errors(got: &[Sample], want: &[Sample]) -> (f64, f64) {
    let (mut max, mut sum, mut n) = (0.0f64, 0.0f64, 0usize);
    for (g, w) in got.iter().zip(want) {
        for c in 0..g.channels.min(w.channels) {
            let e = (g.value[c] - w.value[c]).abs();
            let e = if e.is_finite() { e } else { f64::INFINITY };
            max = max.max(e);
            sum += e * e;
            n += 1;
        }
    }
    (max, (sum / n.max(1) as f64).sqrt())
}

fn collect(f: impl FnOnce(&mut dyn FnMut(Sample))) -> Vec<Sample> {
    let mut v = Vec::new();
    f(&mut |s| v.push(s));
    v
}

/// Host ns per call of `call` on the ring inputs: median over inputs, median of 5 runs.
fn time_ring(reps: u32, mut call: impl FnMut(&mut Timer, Dirs) -> Vec<Sample>) -> f64 {
    let dirs = cases::ring_dirs();
    let mut runs: Vec<f64> = (0..5)
        .map(|_| {
            let mut per: Vec<f64> = call(&mut Timer { reps }, dirs)
                .iter()
                .map(|s| f64::from(s.count) / 1000.0)
                .collect();
            median(&mut per)
        })
        .collect();
    median(&mut runs)
}

/// The references (f64, inputs rounded by `round`) of every model over `dirs`.
fn references(dirs: Dirs, round: fn(f64) -> f64) -> Result<Vec<Vec<Sample>>, String> {
    let l = Lights::<f64>::new(round).map_err(|e| format!("f64 lights: {e:?}"))?;
    Ok((0..MODELS.len())
        .map(|m| collect(|out| cases::run_model(&l, m, dirs, round, &mut Plain, &mut |s| out(s))))
        .collect())
}

/// The rows of one backend `T` (every model id it supports).
fn backend_rows<T: Backend>(
    kind: Kind,
    round: fn(f64) -> f64,
    dirs: Dirs,
    reps: u32,
) -> Result<Vec<Row>, String> {
    let refs = references(dirs, round)?;
    let name = T::NAME;
    let l = Lights::<T>::new(|x| x).map_err(|e| format!("{name} lights: {e:?}"))?;
    let mut rows = Vec::new();
    for (m, model) in MODELS.iter().enumerate() {
        if !cases::supports(name, model) {
            continue;
        }
        let got = collect(|out| cases::run_model(&l, m, dirs, |x| x, &mut Plain, &mut |s| out(s)));
        let (max_err, rms_err) = errors(&got, &refs[m]);
        let host_ns = time_ring(reps, |t, ring| {
            collect(|out| cases::run_model(&l, m, ring, |x| x, t, &mut |s| out(s)))
        });
        rows.push(Row {
            model: (*model).to_owned(),
            backend: name.to_owned(),
            host_ns,
            m4f: None,
            m0: None,
            rv32: None,
            code: None,
            max_err,
            rms_err,
            kind,
        });
    }
    Ok(rows)
}

/// How a backend's rows are made.
type BackendFn = fn(Kind, fn(f64) -> f64, Dirs, u32) -> Result<Vec<Row>, String>;
/// A backend: its plot colour, how inputs are rounded to it, its rows.
type BackendEntry = (Kind, fn(f64) -> f64, BackendFn);
/// The backends of the budget: adding one is one entry here.
const BACKENDS: [BackendEntry; 3] = [
    (Kind::F32, round_f32, backend_rows::<f32>),
    (Kind::Fast, round_f32, backend_rows::<Fast32>),
    (Kind::Fixed, round_fixed, backend_rows::<Fixed22>),
];

/// The point light and k-sample rows (f32), errors against the exact f64 model.
fn alternative_rows(dirs: Dirs, reps: u32) -> Result<Vec<Row>, String> {
    let refs = references(dirs, round_f32)?;
    let mut rows = Vec::new();
    for k in points::KS {
        let l = points::Sampled::<f32>::new(k, cases::PHONG_M);
        for (alt, (name, exact)) in points::ALTERNATIVES.iter().enumerate() {
            let point = name.starts_with("point_");
            if point && k != 1 {
                continue;
            }
            let m = MODELS
                .iter()
                .position(|x| x == exact)
                .ok_or_else(|| format!("{exact} is not a model id"))?;
            let got =
                collect(|out| points::run_alt(&l, alt, dirs, |x| x, &mut Plain, &mut |s| out(s)));
            let (max_err, rms_err) = errors(&got, &refs[m]);
            let host_ns = time_ring(reps, |t, ring| {
                collect(|out| points::run_alt(&l, alt, ring, |x| x, t, &mut |s| out(s)))
            });
            rows.push(Row {
                model: (*name).to_owned(),
                backend: if point {
                    "f32".to_owned()
                } else {
                    format!("f32-pts{}", l.k())
                },
                host_ns,
                m4f: None,
                m0: None,
                rv32: None,
                code: None,
                max_err,
                rms_err,
                kind: if point { Kind::Point } else { Kind::Sampled },
            });
        }
    }
    Ok(rows)
}

/// The QEMU harness's figures: (target, backend, model) -> (median insns, code bytes).
type Counts = HashMap<(String, String, String), (Option<u64>, Option<u64>)>;

/// Reads `counts.csv` (missing file: no figures).
pub fn read_counts(path: &Path) -> Counts {
    let Ok(text) = std::fs::read_to_string(path) else {
        return HashMap::new();
    };
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name);
    let (Some(t), Some(b), Some(m), Some(md), Some(cb)) = (
        col("target"),
        col("backend"),
        col("model"),
        col("insns_median"),
        col("code_bytes"),
    ) else {
        return HashMap::new();
    };
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let get = |i: usize| f.get(i).copied().unwrap_or("");
            (
                (get(t).to_owned(), get(b).to_owned(), get(m).to_owned()),
                (get(md).parse().ok(), get(cb).parse().ok()),
            )
        })
        .collect()
}

fn fill_counts(rows: &mut [Row], counts: &Counts) {
    for r in rows {
        let key = |t: &str| (t.to_owned(), r.backend.clone(), r.model.clone());
        let m4f = counts.get(&key("m4f")).copied().unwrap_or((None, None));
        let m0 = counts.get(&key("m0")).copied().unwrap_or((None, None));
        r.m4f = m4f.0;
        r.m0 = m0.0;
        r.rv32 = counts.get(&key("rv32imc")).and_then(|c| c.0);
        r.code = if r.kind == Kind::Fixed { m0.1 } else { m4f.1 };
    }
}

/// The README's accuracy target of a model row (`None` for the alternatives, which are
/// reported, not held to one): f32 `2e-6 + m 2^-24` where well-conditioned (m the case's Phong
/// exponent or moment order, 0 for the other models), f32-fast and fixed 1/1024. Absolute, as
/// the errors: the models that are not normalized (moments, line light) stay below about 3 in
/// these cases.
pub fn target(model: &str, backend: &str) -> Option<f64> {
    if !MODELS.contains(&model) {
        return None;
    }
    let m = if model.starts_with("phong_") || model.starts_with("glossy_") {
        cases::PHONG_M
    } else if matches!(
        model,
        "axial_moment" | "double_axis_moment" | "directional_luminaire" | "lune_normalization"
    ) {
        cases::MOMENT_M
    } else {
        0
    };
    match backend {
        "f32" => Some(2e-6 + f64::from(m) / 16_777_216.0),
        "f32-fast" | "fixed" => Some(1.0 / 1024.0),
        _ => None,
    }
}

/// The model rows whose max error exceeds their [`target`], described.
pub fn missed_targets(rows: &[Row]) -> Vec<String> {
    rows.iter()
        .filter_map(|r| {
            let t = target(&r.model, &r.backend)?;
            // A NaN error misses too.
            (r.max_err > t || r.max_err.is_nan()).then(|| {
                format!(
                    "{} {}: max error {:.3e} > target {t:.3e}",
                    r.model, r.backend, r.max_err
                )
            })
        })
        .collect()
}

/// Computes every row.
///
/// # Errors
/// A light the backend refuses (never for the fixed cases).
pub fn budget(args: &BudgetArgs) -> Result<Vec<Row>, String> {
    let dirs_v = random_dirs(args.samples.max(1), 0x5EED_B0D6E7);
    let get = |i: usize| dirs_v[i];
    let dirs = Dirs {
        count: dirs_v.len(),
        get: &get,
    };
    let mut rows = Vec::new();
    for (kind, round, f) in BACKENDS {
        rows.extend(f(kind, round, dirs, args.reps)?);
    }
    rows.extend(alternative_rows(dirs, args.reps)?);
    fill_counts(&mut rows, &read_counts(&args.counts));
    Ok(rows)
}

/// Runs the budget and writes the three files; returns their paths.
///
/// # Errors
/// A file that cannot be written, or a case that cannot be built.
pub fn run(args: &BudgetArgs) -> Result<Vec<PathBuf>, String> {
    let rows = budget(args)?;
    let counts_found = rows.iter().any(|r| r.m4f.is_some());
    std::fs::create_dir_all(&args.out).map_err(|e| format!("{}: {e}", args.out.display()))?;
    let write = |name: &str, bytes: &[u8]| -> Result<PathBuf, String> {
        let p = args.out.join(name);
        std::fs::write(&p, bytes).map_err(|e| format!("{}: {e}", p.display()))?;
        Ok(p)
    };
    let mut md = String::from(
        "# arealight budget\n\nGenerated by `host-sim budget`. Instructions are exact (QEMU \
         `-icount`, TIM2 counting executed instructions; see `boards/qemu-budget`), per call of \
         the model's kernel with a fixed light, median over the harness's 16 inputs; no cycle \
         figures are given (cycles would need the cores' timing tables or hardware). Host ns: \
         x86-64, median of runs. Code bytes: the kernel and everything it reaches (thumbv7em for \
         float rows, thumbv6m for fixed). Errors: absolute, against f64 (the alternatives: \
         against the exact f64 model they approximate), over random directions. Phong m = 16, \
         moments m = 4, line decay k = 2.\n\n",
    );
    let table = markdown(&rows, counts_found);
    md.push_str(&table);
    md.push('\n');
    md.push_str(&host_times(&rows));
    let png = plot(&rows)?
        .encode_png()
        .map_err(|e| format!("encoding budget.png: {e}"))?;
    let paths = vec![
        write("budget.csv", csv(&rows).as_bytes())?,
        write("budget.md", md.as_bytes())?,
        // The deterministic part alone, for the README's block (boards/readme-tables.mjs).
        write("budget-table.md", table.as_bytes())?,
        write("budget-host.md", host_times(&rows).as_bytes())?,
        write(
            "budget-unit.md",
            unit_markdown(&read_counts(&args.counts)).as_bytes(),
        )?,
        write(
            "budget-world.md",
            world_markdown(&read_counts(&args.counts)).as_bytes(),
        )?,
        write(
            "budget-bar.md",
            bar_markdown(&read_counts(&args.counts)).as_bytes(),
        )?,
        write("budget.png", &png)?,
    ];
    let missed = missed_targets(&rows);
    if !missed.is_empty() {
        return Err(format!(
            "{} row(s) miss their accuracy target (files written):\n{}",
            missed.len(),
            missed.join("\n")
        ));
    }
    Ok(paths)
}

/// `host-sim budget`.
pub fn main(args: &BudgetArgs) -> ExitCode {
    if args.calibrate {
        return crate::scene_budget::calibrate_main(&args.counts);
    }
    if let Some(scene) = &args.scene {
        return crate::scene_budget::main(args, scene);
    }
    match run(args) {
        Ok(paths) => {
            for p in paths {
                println!("{}", p.display());
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("host-sim budget: {e}");
            ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests;
