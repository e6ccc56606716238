//! `host-sim budget --out DIR`: the accuracy/cost budget, one row per model id x backend, and
//! beside them the alternatives a user would pick instead (a point light; each area light by
//! k = 1, 4, 16, 64 point samples).
//!
//! Writes `DIR/budget.csv` (`model,backend,host_ns,m4f_insns,m0_insns,code_bytes,max_abs_err,
//! rms_err,rv32imc_insns`, empty where a figure does not apply; the RISC-V column last, so the
//! issue's columns keep their positions), `DIR/budget.md` (the same as tables, with
//! what each column is), `DIR/budget-table.md` (the deterministic tables alone: instruction
//! counts, code bytes, errors; the README embeds it and CI compares it), `DIR/budget-unit.md`
//! (the calls that take a normal, with a `Vec3` and with a `UnitVec3`), `DIR/budget-host.md`
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
use std::fmt::Write as _;
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use arealight::{Fast32, Fixed22, Real};
use clap::Args;
use tiny_skia::{Color, Paint, PathBuilder, Pixmap, Rect, Stroke, Transform};

#[allow(dead_code)]
#[path = "../../boards/qemu-budget/src/cases.rs"]
mod cases;
#[allow(dead_code)]
#[path = "../../boards/qemu-budget/src/points.rs"]
mod points;

use cases::{Backend, Dirs, Lights, Meter, Sample, MODELS, RING};

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
    let ring = |i| cases::ring(i);
    let dirs = Dirs {
        count: RING,
        get: &ring,
    };
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

fn opt(x: Option<u64>) -> String {
    x.map(|v| v.to_string()).unwrap_or_default()
}

/// The CSV text.
pub fn csv(rows: &[Row]) -> String {
    let mut s = format!("{HEADER}\n");
    for r in rows {
        let _ = writeln!(
            s,
            "{},{},{:.1},{},{},{},{:.3e},{:.3e},{}",
            r.model,
            r.backend,
            r.host_ns,
            opt(r.m4f),
            opt(r.m0),
            opt(r.code),
            r.max_err,
            r.rms_err,
            opt(r.rv32)
        );
    }
    s
}

/// Indices of the rows on the Pareto front of (`x`, max error) among the rows that have an
/// `x`: no other row is at least as cheap and at least as accurate, and better in one. Sorted
/// by `x`.
pub fn pareto_by(rows: &[Row], x: impl Fn(&Row) -> Option<f64>) -> Vec<usize> {
    let pts: Vec<(usize, f64, f64)> = rows
        .iter()
        .enumerate()
        .filter_map(|(i, r)| Some((i, x(r)?, r.max_err)))
        .collect();
    let mut front: Vec<(usize, f64)> = pts
        .iter()
        .filter(|&&(i, xa, ea)| {
            !pts.iter()
                .any(|&(j, xo, eo)| j != i && xo <= xa && eo <= ea && (xo < xa || eo < ea))
        })
        .map(|&(i, xa, _)| (i, xa))
        .collect();
    front.sort_by(|a, b| a.1.total_cmp(&b.1));
    front.into_iter().map(|(i, _)| i).collect()
}

/// The Pareto front of host time against max error.
pub fn pareto(rows: &[Row]) -> Vec<usize> {
    pareto_by(rows, |r| Some(r.host_ns))
}

/// The deterministic tables (`budget-table.md`, which the README embeds and CI compares): per
/// row the exact instruction counts, code bytes and errors, then the cost at equal error.
/// Nothing measured by a clock: those figures are [`host_times`]'.
pub fn markdown(rows: &[Row], counts_found: bool) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "| model | backend | M4F insns | M0 insns | RV32IMC insns | code bytes | max abs err | RMS err |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|");
    // The front by the exact M4F counts where the harness ran (host times vary run to run).
    let front = if counts_found {
        pareto_by(rows, |r| r.m4f.map(|n| n as f64))
    } else {
        pareto(rows)
    };
    for (i, r) in rows.iter().enumerate() {
        let star = if front.contains(&i) { " *" } else { "" };
        let _ = writeln!(
            s,
            "| `{}`{star} | {} | {} | {} | {} | {} | {:.1e} | {:.1e} |",
            r.model,
            r.backend,
            opt(r.m4f),
            opt(r.m0),
            opt(r.rv32),
            opt(r.code),
            r.max_err,
            r.rms_err
        );
    }
    let _ = writeln!(
        s,
        "\n`*`: on the Pareto front of {} against max error (`budget.png` shows both fronts).",
        if counts_found {
            "M4F instructions"
        } else {
            "host time (instruction counts and code sizes are empty: run \
             `cargo test -p host-sim --test qemu_budget` first, which needs qemu-system-arm)"
        }
    );
    // Cost at equal error: each sampled light against its analytic model.
    let _ = writeln!(
        s,
        "\nCost at equal error (f32, M4F instructions where measured, else host ns): the fewest \
         samples whose max error is within 1/1024, against the analytic model.\n"
    );
    let _ = writeln!(
        s,
        "| light | analytic: max err, cost | fewest samples within 1/1024 | their cost | 64 samples: max err |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|");
    let cost = |r: &Row| match r.m4f {
        Some(n) => format!("{n} insns"),
        None => format!("{:.0} ns", r.host_ns),
    };
    for (name, exact) in points::ALTERNATIVES
        .iter()
        .filter(|a| !a.0.starts_with("point_"))
    {
        let Some(a) = rows
            .iter()
            .find(|r| r.model == *exact && r.backend == "f32")
        else {
            continue;
        };
        let sampled: Vec<&Row> = rows
            .iter()
            .filter(|r| r.model == *name && r.kind == Kind::Sampled)
            .collect();
        let ok = sampled.iter().find(|r| r.max_err <= 1.0 / 1024.0);
        let k64 = sampled
            .last()
            .map(|r| format!("{:.1e}", r.max_err))
            .unwrap_or_default();
        let _ = writeln!(
            s,
            "| `{exact}` | {:.1e}, {} | {} | {} | {k64} |",
            a.max_err,
            cost(a),
            ok.map(|r| r.backend.trim_start_matches("f32-pts").to_owned())
                .unwrap_or_else(|| "none of 1..64".into()),
            ok.map(|r| cost(r)).unwrap_or_default(),
        );
    }
    s
}

/// The host times (`budget-host.md`): one machine's, measured by a clock, so neither in the
/// README's table nor compared by CI.
pub fn host_times(rows: &[Row]) -> String {
    let mut s = String::from(
        "Host time per call, ns (x86-64, this machine, median of 5 runs; varies from run to run \
         and machine to machine: not checked).\n\n| model | backend | host ns |\n|---|---|---|\n",
    );
    for r in rows {
        let _ = writeln!(s, "| `{}` | {} | {:.0} |", r.model, r.backend, r.host_ns);
    }
    s
}

/// Draws `s` (small font) with its top-left corner at `(x, y)`.
fn text(pix: &mut Pixmap, s: &str, x: f32, y: f32, c: [u8; 3]) {
    crate::figure::text(pix, s, x as i32, y as i32, c, crate::figure::Font::Small);
}

fn paint(c: [u8; 3]) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color(Color::from_rgba8(c[0], c[1], c[2], 255));
    p.anti_alias = true;
    p
}

fn colour(k: Kind) -> [u8; 3] {
    match k {
        Kind::F32 => [90, 160, 255],
        Kind::Fast => [255, 150, 60],
        Kind::Fixed => [120, 220, 120],
        Kind::Point => [240, 220, 90],
        Kind::Sampled => [235, 90, 200],
    }
}

/// The smallest error drawn (smaller errors sit on the bottom edge).
const ERR_FLOOR: f64 = 1e-9;

type Stroker<'a> = dyn Fn(&mut Pixmap, (f32, f32), (f32, f32), &Paint, &Stroke) + 'a;

fn draw_line(pix: &mut Pixmap, a: (f32, f32), b: (f32, f32), p: &Paint, st: &Stroke) {
    let mut pb = PathBuilder::new();
    pb.move_to(a.0, a.1);
    pb.line_to(b.0, b.1);
    if let Some(path) = pb.finish() {
        pix.stroke_path(&path, p, st, Transform::identity(), None);
    }
}

fn dot(pix: &mut Pixmap, x: f32, y: f32, r: f32, c: [u8; 3]) {
    if let Some(path) = PathBuilder::from_circle(x, y, r) {
        pix.fill_path(
            &path,
            &paint(c),
            tiny_skia::FillRule::Winding,
            Transform::identity(),
            None,
        );
    }
}

/// One log-log panel: `x` of each row (rows without one are left out) against max error, in
/// the rectangle (x0, y0)-(x1, y1), with the Pareto front of that panel.
#[allow(clippy::too_many_arguments)]
fn panel(
    pix: &mut Pixmap,
    rows: &[Row],
    x: &dyn Fn(&Row) -> Option<f64>,
    title: &str,
    xlabel: &str,
    (x0, y0, x1, y1): (f32, f32, f32, f32),
    ymax: f64,
) {
    let line: &Stroker = &draw_line;
    let lx = |v: f64| v.max(1e-3).log10();
    let ly = |v: f64| v.max(ERR_FLOOR).log10();
    let xs: Vec<f64> = rows.iter().filter_map(x).map(lx).collect();
    let xmin = xs.iter().copied().fold(f64::MAX, f64::min).floor();
    let xmax = xs
        .iter()
        .copied()
        .fold(f64::MIN, f64::max)
        .ceil()
        .max(xmin + 1.0);
    let ymin = ly(ERR_FLOOR);
    let px = |v: f64| x0 + ((lx(v) - xmin) / (xmax - xmin)) as f32 * (x1 - x0);
    let py = |v: f64| y1 - ((ly(v) - ymin) / (ymax - ymin)) as f32 * (y1 - y0);
    let grid = paint([60, 60, 68]);
    let axis = paint([200, 200, 200]);
    let thin = Stroke {
        width: 1.0,
        ..Stroke::default()
    };
    let mut e = xmin;
    while e <= xmax + 1e-9 {
        let gx = px(10f64.powf(e));
        line(pix, (gx, y0), (gx, y1), &grid, &thin);
        text(
            pix,
            &format!("1e{e:.0}"),
            gx - 12.0,
            y1 + 6.0,
            [200, 200, 200],
        );
        e += 1.0;
    }
    let mut e = ymin;
    while e <= ymax + 1e-9 {
        let gy = py(10f64.powf(e));
        line(pix, (x0, gy), (x1, gy), &grid, &thin);
        let label = if e == ymin {
            format!("<=1e{e:.0}")
        } else {
            format!("1e{e:.0}")
        };
        text(pix, &label, x0 - 50.0, gy - 5.0, [200, 200, 200]);
        e += 1.0;
    }
    line(pix, (x0, y1), (x1, y1), &axis, &thin);
    line(pix, (x0, y0), (x0, y1), &axis, &thin);
    let w = xlabel.len() as f32 * 6.0;
    text(pix, xlabel, (x0 + x1 - w) / 2.0, y1 + 24.0, [230, 230, 230]);
    text(pix, title, x0, y0 - 18.0, [255, 255, 255]);
    // The Pareto front, as a staircase.
    let front = pareto_by(rows, x);
    let white = paint([255, 255, 255]);
    let wide = Stroke {
        width: 2.0,
        ..Stroke::default()
    };
    let at = |r: &Row| x(r).map(|v| (px(v), py(r.max_err)));
    for pair in front.windows(2) {
        if let (Some((ax, ay)), Some((bx, by))) = (at(&rows[pair[0]]), at(&rows[pair[1]])) {
            line(pix, (ax, ay), (bx, ay), &white, &wide);
            line(pix, (bx, ay), (bx, by), &white, &wide);
        }
    }
    let radius = |r: &Row| {
        if r.kind == Kind::Sampled {
            let k: f32 = r
                .backend
                .trim_start_matches("f32-pts")
                .parse()
                .unwrap_or(1.0);
            2.0 + k.log2() * 0.6
        } else {
            3.5
        }
    };
    let mut dots: Vec<(f32, f32, f32)> = Vec::new();
    for r in rows {
        let Some((cx, cy)) = at(r) else {
            continue;
        };
        let rad = radius(r);
        dot(pix, cx, cy, rad, colour(r.kind));
        dots.push((cx, cy, rad));
    }
    // The front's labels: each at the first free place around its point (clear of the other
    // labels and of every point, else of the labels only), on a dark box, with a leader line
    // when it sits away from its point.
    let mut placed: Vec<Rect> = Vec::new();
    let bounds = (x0, y0, x1, y1);
    for &i in &front {
        let r = &rows[i];
        let Some((cx, cy)) = at(r) else {
            continue;
        };
        let rad = radius(r);
        if let Some(c) = PathBuilder::from_circle(cx, cy, rad + 3.0) {
            pix.stroke_path(&c, &white, &thin, Transform::identity(), None);
        }
        let label = format!("{} {}", r.model, r.backend);
        let (lw, lh) = (label.len() as f32 * 6.0 + 4.0, 12.0);
        let Some((bx, by)) = place_label((cx, cy), rad, (lw, lh), bounds, &placed, &dots) else {
            continue;
        };
        let Some(rect) = Rect::from_xywh(bx, by, lw, lh) else {
            continue;
        };
        let near = (bx - (cx + rad + 4.0)).abs() < 1.0 && (by + lh / 2.0 - cy).abs() < 8.0;
        if !near {
            let lead = paint([170, 170, 175]);
            let tx = if bx > cx { bx } else { bx + lw };
            line(pix, (cx, cy), (tx, by + lh / 2.0), &lead, &thin);
        }
        pix.fill_rect(rect, &paint([24, 24, 28]), Transform::identity(), None);
        text(pix, &label, bx + 2.0, by + 1.0, [255, 255, 255]);
        placed.push(rect);
    }
}

/// `true` if the two rectangles overlap.
fn overlaps(a: &Rect, b: &Rect) -> bool {
    a.left() < b.right() && b.left() < a.right() && a.top() < b.bottom() && b.top() < a.bottom()
}

/// Where a `size` label for the point `p` (radius `rad`) goes: the top-left corner of the first
/// candidate (right of the point, then left, then further up and down on either side) inside
/// `bounds` that overlaps no `placed` label and no point of `dots`; failing that the first that
/// overlaps no label; `None` when every candidate overlaps a label.
fn place_label(
    p: (f32, f32),
    rad: f32,
    size: (f32, f32),
    bounds: (f32, f32, f32, f32),
    placed: &[Rect],
    dots: &[(f32, f32, f32)],
) -> Option<(f32, f32)> {
    let (cx, cy) = p;
    let (w, h) = size;
    let right = cx + rad + 4.0;
    let left = cx - rad - 4.0 - w;
    let mut candidates = Vec::new();
    for dy in [0.0f32, -14.0, 14.0, -28.0, 28.0, -42.0, 42.0, -56.0, 56.0] {
        candidates.push((right, cy - h / 2.0 + dy));
        candidates.push((left, cy - h / 2.0 + dy));
    }
    let rect = |&(x, y): &(f32, f32)| Rect::from_xywh(x, y, w, h);
    let inside = |r: &Rect| {
        r.left() >= bounds.0
            && r.top() >= bounds.1
            && r.right() <= bounds.2
            && r.bottom() <= bounds.3
    };
    let clear_of_labels = |r: &Rect| inside(r) && !placed.iter().any(|q| overlaps(r, q));
    let clear_of_dots = |r: &Rect| {
        !dots.iter().any(|&(x, y, d)| {
            Rect::from_xywh(x - d, y - d, 2.0 * d, 2.0 * d).is_some_and(|q| overlaps(r, &q))
        })
    };
    candidates
        .iter()
        .find(|c| rect(c).is_some_and(|r| clear_of_labels(&r) && clear_of_dots(&r)))
        .or_else(|| {
            candidates
                .iter()
                .find(|c| rect(c).is_some_and(|r| clear_of_labels(&r)))
        })
        .copied()
}

/// Draws the plot: max error against host time and, where the QEMU harness's counts are
/// present, against Cortex-M4F instructions; log-log, Pareto fronts in white.
pub fn plot(rows: &[Row]) -> Result<Pixmap, String> {
    let with_m4f = rows.iter().any(|r| r.m4f.is_some());
    let pw = 620.0f32;
    let w = if with_m4f {
        90.0 + 2.0 * pw + 90.0 + 230.0
    } else {
        90.0 + pw + 230.0
    };
    let h = 760.0f32;
    let mut pix = Pixmap::new(w as u32, h as u32).ok_or("pixmap")?;
    pix.fill(Color::from_rgba8(24, 24, 28, 255));
    let ymax = rows
        .iter()
        .map(|r| r.max_err.max(ERR_FLOOR).log10())
        .fold(-8.0f64, f64::max)
        .ceil();
    let (y0, y1) = (70.0f32, h - 70.0);
    text(
        &mut pix,
        "arealight budget: max abs error vs f64 (log) against cost (log); one point per model x backend",
        20.0,
        14.0,
        [230, 230, 230],
    );
    panel(
        &mut pix,
        rows,
        &|r| Some(r.host_ns),
        "host (x86-64), ns per call",
        "host ns per call (log)",
        (90.0, y0, 90.0 + pw, y1),
        ymax,
    );
    let mut lx = 90.0 + pw + 20.0;
    if with_m4f {
        let x0 = 90.0 + pw + 90.0;
        panel(
            &mut pix,
            rows,
            &|r| r.m4f.map(|n| n as f64),
            "Cortex-M4F (QEMU, exact), instructions per call",
            "M4F instructions per call (log)",
            (x0, y0, x0 + pw, y1),
            ymax,
        );
        lx = x0 + pw + 20.0;
    }
    let legend = [
        (Kind::F32, "analytic, f32 (libm)"),
        (Kind::Fast, "analytic, f32-fast"),
        (Kind::Fixed, "analytic, fixed (no M4F)"),
        (Kind::Point, "point light (cost floor)"),
        (Kind::Sampled, "k point samples (size ~ k)"),
    ];
    let mut ly0 = y0 + 10.0;
    for (k, label) in legend {
        if !rows.iter().any(|r| r.kind == k) {
            continue;
        }
        dot(&mut pix, lx + 10.0, ly0 + 5.0, 4.0, colour(k));
        text(&mut pix, label, lx + 20.0, ly0, [230, 230, 230]);
        ly0 += 18.0;
    }
    text(
        &mut pix,
        "white: Pareto front",
        lx + 20.0,
        ly0 + 6.0,
        [255, 255, 255],
    );
    if let Some(r) = Rect::from_xywh(lx, y0, 200.0, ly0 - y0 + 24.0) {
        let mut pb = PathBuilder::new();
        pb.push_rect(r);
        if let Some(p) = pb.finish() {
            pix.stroke_path(
                &p,
                &paint([60, 60, 68]),
                &Stroke::default(),
                Transform::identity(),
                None,
            );
        }
    }
    Ok(pix)
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

/// The calls that take a normal or a reflection direction, with a `Vec3` of any length (the
/// call normalizes it) and with a `UnitVec3` (normalized once by the caller), from the QEMU
/// harness's `<model>` and `<model>/unit` rows (`budget-unit.md`; empty without counts).
pub fn unit_markdown(counts: &Counts) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "| call | M4F f32: `Vec3` n | M4F f32: `UnitVec3` n | M0 `Fixed22`: `Vec3` n | M0 `Fixed22`: `UnitVec3` n | RV32IMC `Fixed22`: `Vec3` n | RV32IMC `Fixed22`: `UnitVec3` n |"
    );
    let _ = writeln!(s, "|---|---:|---:|---:|---:|---:|---:|");
    let get = |t: &str, b: &str, m: &str| {
        opt(counts
            .get(&(t.to_owned(), b.to_owned(), m.to_owned()))
            .and_then(|c| c.0))
    };
    for (unit, model) in cases::UNIT_CASES {
        let id = MODELS[model];
        let _ = writeln!(
            s,
            "| `{id}` | {} | {} | {} | {} | {} | {} |",
            get("m4f", "f32", id),
            get("m4f", "f32", unit),
            get("m0", "fixed", id),
            get("m0", "fixed", unit),
            get("rv32imc", "fixed", id),
            get("rv32imc", "fixed", unit),
        );
    }
    s
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
mod tests {
    use super::*;

    fn row(model: &str, ns: f64, err: f64) -> Row {
        Row {
            model: model.into(),
            backend: "f32".into(),
            host_ns: ns,
            m4f: None,
            m0: None,
            rv32: None,
            code: None,
            max_err: err,
            rms_err: err,
            kind: Kind::F32,
        }
    }

    #[test]
    fn targets_are_the_readmes() {
        assert_eq!(target("cap_lambert", "f32"), Some(2e-6));
        assert_eq!(target("phong_cap", "f32"), Some(2e-6 + 16.0 / 16_777_216.0));
        assert_eq!(
            target("axial_moment", "f32"),
            Some(2e-6 + 4.0 / 16_777_216.0)
        );
        assert_eq!(target("cap_lambert", "f32-fast"), Some(1.0 / 1024.0));
        assert_eq!(target("polygon_lambert", "fixed"), Some(1.0 / 1024.0));
        assert_eq!(target("point_lambert", "f32"), None);
        let mut r = row("cap_lambert", 1.0, 2.5e-6);
        assert_eq!(missed_targets(std::slice::from_ref(&r)).len(), 1);
        r.max_err = 1.9e-6;
        assert!(missed_targets(std::slice::from_ref(&r)).is_empty());
        r.max_err = f64::NAN;
        assert_eq!(missed_targets(&[r]).len(), 1);
    }

    #[test]
    fn pareto_keeps_only_undominated_rows_sorted_by_time() {
        let rows = [
            row("a", 10.0, 1e-3),
            row("b", 20.0, 1e-6),
            row("c", 30.0, 1e-3), // dominated by a
            row("d", 5.0, 1e-2),
            row("e", 20.0, 1e-5), // dominated by b
        ];
        assert_eq!(pareto(&rows), vec![3, 0, 1]);
    }

    #[test]
    fn random_dirs_are_unit_and_deterministic() {
        let a = random_dirs(100, 7);
        assert_eq!(a, random_dirs(100, 7));
        for d in &a {
            let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            assert!((l - 1.0).abs() < 1e-12, "{l}");
        }
        // Spread over the sphere: the mean is near 0.
        let mean: f64 = a.iter().map(|d| d[2]).sum::<f64>() / 100.0;
        assert!(mean.abs() < 0.2, "{mean}");
    }

    #[test]
    fn counts_csv_is_read_by_column_name() {
        let dir = std::env::temp_dir().join(format!("budget-counts-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("counts.csv");
        std::fs::write(
            &p,
            "target,backend,model,insns_min,insns_median,insns_max,code_bytes,max_err,x\n\
             m4f,f32,cap_lambert,147,153,383,1328,1.7e-8,16\n\
             rv32imc,fixed,cap_lambert,522,575,1602,6000,2.0e-4,16\n",
        )
        .unwrap();
        let c = read_counts(&p);
        assert_eq!(
            c.get(&("m4f".into(), "f32".into(), "cap_lambert".into())),
            Some(&(Some(153), Some(1328)))
        );
        // The RISC-V median goes to its own column; code bytes stay the ARM images'.
        let mut rows = vec![row("cap_lambert", 1.0, 0.0)];
        rows[0].backend = "fixed".into();
        rows[0].kind = Kind::Fixed;
        fill_counts(&mut rows, &c);
        assert_eq!(
            (rows[0].rv32, rows[0].m0, rows[0].code),
            (Some(575), None, None)
        );
        assert!(csv(&rows).lines().nth(1).unwrap().ends_with(",575"));
        assert!(read_counts(&dir.join("missing.csv")).is_empty());
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn unit_table_pairs_each_call_with_its_unit_row() {
        let mut c = Counts::new();
        let mut put = |t: &str, b: &str, m: &str, n: u64| {
            c.insert((t.into(), b.into(), m.into()), (Some(n), None));
        };
        put("m4f", "f32", "hemi_const", 52);
        put("m4f", "f32", "hemi_const/unit", 20);
        put("m0", "fixed", "hemi_const", 622);
        put("m0", "fixed", "hemi_const/unit", 170);
        put("rv32imc", "fixed", "polygon_lambert/unit", 5600);
        let t = unit_markdown(&c);
        assert_eq!(t.lines().count(), 2 + cases::UNIT_CASES.len());
        assert!(
            t.contains("| `hemi_const` | 52 | 20 | 622 | 170 |  |  |"),
            "{t}"
        );
        assert!(
            t.contains("| `polygon_lambert` |  |  |  |  |  | 5600 |"),
            "{t}"
        );
    }

    #[test]
    fn the_budget_has_every_model_and_alternative_with_errors_in_range() {
        let args = BudgetArgs {
            out: std::env::temp_dir(),
            counts: "/nonexistent/counts.csv".into(),
            samples: 256,
            reps: 1,
            scene: None,
            chip: None,
            fps: None,
            max_error: None,
            check: None,
            emit_spec: None,
            calibrate: false,
        };
        let rows = budget(&args).unwrap();
        for m in MODELS {
            for b in ["f32", "f32-fast"] {
                let r = rows
                    .iter()
                    .find(|r| r.model == m && r.backend == b)
                    .unwrap_or_else(|| panic!("{m} {b} missing"));
                // Within the README's targets: f32 2e-6 + m 2^-24, f32-fast 1/1024.
                let tol = target(m, b).unwrap();
                assert!(r.max_err <= tol, "{m} {b}: {} > {tol:e}", r.max_err);
                assert!(r.rms_err <= r.max_err);
            }
            // Fixed point: the models of its table, within 1/1024; no row for the others.
            let fixed = rows.iter().find(|r| r.model == m && r.backend == "fixed");
            match fixed {
                Some(r) => assert!(
                    r.max_err <= target(m, "fixed").unwrap(),
                    "{m} fixed: {}",
                    r.max_err
                ),
                None => assert!(!cases::FIXED_MODELS.contains(&m), "{m} fixed missing"),
            }
        }
        // The alternatives: k = 1 of the cap is far off, k = 64 much closer.
        let cap = |b: &str| {
            rows.iter()
                .find(|r| r.model == "cap_lambert" && r.backend == b)
                .map(|r| r.max_err)
                .unwrap()
        };
        assert!(
            cap("f32-pts1") > 10.0 * cap("f32-pts64"),
            "{} {}",
            cap("f32-pts1"),
            cap("f32-pts64")
        );
        assert!(cap("f32-pts64") < 1e-2);
        assert!(
            missed_targets(&rows).is_empty(),
            "{:?}",
            missed_targets(&rows)
        );
        let text = csv(&rows);
        assert!(text.starts_with(HEADER));
        assert_eq!(text.lines().count(), rows.len() + 1);
        // No counts file: those columns are empty.
        assert!(text.lines().nth(1).unwrap().contains(",,,,"));
    }
}
