//! The eval protocol's id-to-function mapping, checked against the independent references of
//! `tests/` through `host-sim eval` itself: for every model id of `models.md`, a few generic
//! cases (non-unit directions, every parameter away from its special values) are written as
//! JSON lines, answered by the binary, and compared with the quadrature of the defining integral
//! (`tests/common/quadrature.rs`, `line_quadrature.rs`, `moments_quadrature.rs`) or, for the
//! shaping functions, a transcription of their definition written here. A model id wired to
//! the wrong function, a parameter read under the wrong name or in the wrong order, a missing
//! normalization: each moves the value far beyond the tolerances.
//!
//! Tolerances: f64 the model's row of the f64 budget (`F64_BUDGET` in tests/common); f32
//! 1e-5, f32-fast and fixed 1/1024 plus 1e-5 (inputs rounded to the backend inside eval, the
//! reference at the exact inputs); all relative to `max(1, |value|)` (the moments and the line
//! light are not normalized). The Hermite approximations: exact outside the fillet, within the
//! measured error of Snyder's approximation inside it (and visibly not the exact model there).
//! The fixed backend answers its models (`SUPPORTED_MODELS`) and `unsupported` for the others.

// `!(a <= b)` is deliberate: true for a NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

// (Each included module allows its own dead code.)
mod cases;
#[path = "../../../tests/common/mod.rs"]
mod common;
#[path = "../../../tests/common/line_quadrature.rs"]
mod lq;
#[path = "../../../tests/common/moments_quadrature.rs"]
mod mq;

use std::collections::BTreeMap;
use std::f64::consts::{FRAC_PI_2, PI};
use std::io::Write;
use std::process::{Command, Stdio};

use cases::{all_cases, Case};
use common::quadrature as qd;
use common::{add, cross, normalize, scale, sub, tol_f64, Quad, Rng, V3};
use serde_json::{json, Value};

/// Every model id of `models.md` (and of the eval protocol).
const IDS: [&str; 27] = [
    "hemi_const",
    "hemi_cos",
    "sky_overcast",
    "sky_ground",
    "cap_lambert",
    "cap_lambert_hermite",
    "sphere_lambert",
    "sphere_lambert_hermite",
    "polygon_lambert",
    "line_lambert",
    "phong_hemi_const",
    "phong_hemi_cos",
    "phong_cap",
    "phong_sphere",
    "phong_polygon",
    "line_phong_peak",
    "rect_phong_peak",
    "axial_moment",
    "double_axis_moment",
    "directional_luminaire",
    "glossy_reflection",
    "glossy_transmission",
    "lune_normalization",
    "sh9_irradiance",
    "sh9_disc_irradiance",
    "superellipse_shape",
    "distance_falloff",
];

/// Cases per model id.
const PER_ID: usize = 4;

/// Runs `host-sim eval --backend <backend>` on the lines; one JSON answer per line.
fn eval(backend: &str, lines: &[Value]) -> Vec<Value> {
    let mut child = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["eval", "--backend", backend])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn host-sim eval");
    let input: String = lines.iter().map(|l| format!("{l}\n")).collect();
    let mut stdin = child.stdin.take().unwrap();
    let writer = std::thread::spawn(move || stdin.write_all(input.as_bytes()).unwrap());
    let out = child.wait_with_output().unwrap();
    writer.join().unwrap();
    assert!(
        out.status.success(),
        "host-sim eval exited with {}",
        out.status
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let answers: Vec<Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).expect("an answer is JSON"))
        .collect();
    assert_eq!(answers.len(), lines.len(), "one answer per line");
    answers
}

/// The answer's numbers: `value`, or the three of `rgb`; `None` for an error line.
fn numbers(a: &Value) -> Option<Vec<f64>> {
    if let Some(x) = a["value"].as_f64() {
        return Some(vec![x]);
    }
    let rgb = a["rgb"].as_array()?;
    rgb.iter().map(Value::as_f64).collect()
}

/// Checks one backend's answers: per id, the largest error (relative to `max(1, |want|)`)
/// against the tolerance; prints a line per id.
fn check_backend(backend: &str, cases: &[Case], tol_of: impl Fn(&Case) -> f64) {
    let lines: Vec<Value> = cases.iter().map(|c| c.line.clone()).collect();
    let answers = eval(backend, &lines);
    let fixed = backend == "fixed";
    // The library's list and the models eval's fixed backend answers beyond it (issue 13).
    let more = [
        "rect_phong_peak",
        "axial_moment",
        "double_axis_moment",
        "lune_normalization",
    ];
    let supported: Vec<&str> = arealight::real::fixed22::SUPPORTED_MODELS
        .iter()
        .copied()
        .chain(more)
        .collect();
    let mut worst: BTreeMap<String, (f64, f64)> = BTreeMap::new();
    let mut failures = Vec::new();
    for (c, a) in cases.iter().zip(&answers) {
        let id = c.line["model"].as_str().unwrap();
        assert_eq!(a["id"], c.line["id"], "answers in input order");
        if fixed && !supported.contains(&id) {
            let e = a["error"].as_str().unwrap_or("");
            assert!(
                e.starts_with("unsupported"),
                "fixed {id}: expected unsupported, got {a}"
            );
            continue;
        }
        let Some(got) = numbers(a) else {
            failures.push(format!("{backend} {id}: no value: {a} for {}", c.line));
            continue;
        };
        assert_eq!(got.len(), c.want.len(), "{backend} {id}: {a}");
        let tol = tol_of(c);
        for (g, w) in got.iter().zip(&c.want) {
            let err = (g - w).abs() / w.abs().max(1.0);
            let slot = worst.entry(id.to_owned()).or_insert((0.0, tol));
            if !(err <= slot.0) {
                slot.0 = err;
            }
            slot.1 = slot.1.max(tol);
            if !(err <= tol) {
                failures.push(format!(
                    "{backend} {id}: got {g:e}, reference {w:e} (error {err:.2e} > {tol:.1e}) for {}",
                    c.line
                ));
            }
            // Hermite inside the fillet at a large cap: an approximation, not the exact model.
            if let Some((_, least)) = c.hermite {
                if !((g - w).abs() >= least) {
                    failures.push(format!(
                        "{backend} {id}: {g:e} is within {least:e} of the exact model {w:e} \
                         where Snyder's approximation is not: {}",
                        c.line
                    ));
                }
            }
        }
    }
    for (id, (e, tol)) in &worst {
        println!("[eval] {backend:<8} {id:<24} max error {e:.2e} (largest tolerance {tol:.1e})");
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn every_model_id_answers_its_defining_integral() {
    let cases = all_cases();
    assert_eq!(cases.len(), IDS.len() * PER_ID);
    // Every id is checked where its value is not trivial: at least three of its cases have a
    // reference above 1e-3, and not all of them are equal.
    for id in IDS {
        let refs: Vec<f64> = cases
            .iter()
            .filter(|c| c.line["model"] == id)
            .map(|c| c.want[0])
            .collect();
        let big = refs.iter().filter(|w| w.abs() > 1e-3).count();
        assert!(big >= 3, "{id}: references {refs:?}");
        assert!(
            refs.iter().any(|w| (w - refs[0]).abs() > 1e-3),
            "{id}: {refs:?}"
        );
    }
    // f64: the model's f64 budget (the Hermite cases: the approximation's own error).
    check_backend("f64", &cases, |c| match c.hermite {
        Some((h, _)) => tol_f64(c.row) + h,
        None => tol_f64(c.row),
    });
    // The low-precision backends: inputs rounded inside eval, so the tolerances include the
    // models' sensitivity to that rounding in these generic cases.
    for (backend, tol) in [
        ("f32", 1e-5),
        ("f32-fast", 1.0 / 1024.0 + 1e-5),
        ("fixed", 1.0 / 1024.0 + 1e-5),
    ] {
        check_backend(backend, &cases, |c| tol + c.hermite.map_or(0.0, |h| h.0));
    }
}
