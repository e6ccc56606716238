//! The budget's text outputs: `budget.csv`, the markdown tables (`budget.md`,
//! `budget-table.md`, `budget-unit.md`, `budget-world.md`, `budget-bar.md`, `budget-host.md`)
//! and the Pareto
//! fronts they mark.

use std::fmt::Write as _;

use super::{bar_cases, cases, points, world_cases, Counts, Kind, Row, HEADER, MODELS};

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

/// The positional lights in world coordinates (`world_cases.rs`: 1000 units from the origin,
/// 64 times as large) against the same calls in plain coordinates, from the QEMU harness's
/// `<model>` and `<model>/world` rows (`budget-world.md`; empty without counts).
pub fn world_markdown(counts: &Counts) -> String {
    paired_markdown(counts, ["plain", "world"], &world_cases::WORLD_CASES)
}

/// The calls that take a normal or a reflection direction, with a `Vec3` of any length (the
/// call normalizes it) and with a `UnitVec3` (normalized once by the caller), from the QEMU
/// harness's `<model>` and `<model>/unit` rows (`budget-unit.md`; empty without counts).
pub fn unit_markdown(counts: &Counts) -> String {
    paired_markdown(counts, ["`Vec3` n", "`UnitVec3` n"], &cases::UNIT_CASES)
}

/// `phong_polygon` as issues 12 and 13 set their bars (`bar_cases.rs`: a `PolygonLight<_, 4>`,
/// m = 15), with the reflection direction as a `Vec3` and as a `UnitVec3`, from the QEMU
/// harness's `phong_polygon/m15` and `phong_polygon/m15/unit` rows (`budget-bar.md`; empty
/// without counts).
pub fn bar_markdown(counts: &Counts) -> String {
    let label = format!(
        "`{}` (`PolygonLight<_, 4>`), m = {}",
        MODELS[bar_cases::BAR_MODEL],
        bar_cases::BAR_PHONG_M
    );
    let [vec, unit] = bar_cases::BAR_CASES.map(|c| c.0);
    rows_markdown(
        counts,
        ["`Vec3` r", "`UnitVec3` r"],
        &[(label, [vec, unit])],
    )
}

/// One row per `(row name, model index)` of `pairs`: the model's row and the paired row, on
/// the M4F (f32), the M0 and RV32IMC (`Fixed22`), under the column names `what`.
fn paired_markdown(counts: &Counts, what: [&str; 2], pairs: &[(&str, usize)]) -> String {
    let rows: Vec<(String, [&str; 2])> = pairs
        .iter()
        .map(|&(paired, model)| (format!("`{}`", MODELS[model]), [MODELS[model], paired]))
        .collect();
    rows_markdown(counts, what, &rows)
}

/// One table row per `(label, [left row, right row])` of `rows`: the two rows' medians on the
/// M4F (f32), the M0 and RV32IMC (`Fixed22`), under the column names `what`.
fn rows_markdown(counts: &Counts, what: [&str; 2], rows: &[(String, [&str; 2])]) -> String {
    let mut s = String::from("| call |");
    for target in ["M4F f32", "M0 `Fixed22`", "RV32IMC `Fixed22`"] {
        for w in what {
            let _ = write!(s, " {target}: {w} |");
        }
    }
    let _ = writeln!(s, "\n|---|---:|---:|---:|---:|---:|---:|");
    let get = |t: &str, b: &str, m: &str| {
        opt(counts
            .get(&(t.to_owned(), b.to_owned(), m.to_owned()))
            .and_then(|c| c.0))
    };
    for (label, [left, right]) in rows {
        let _ = write!(s, "| {label} |");
        for (t, b) in [("m4f", "f32"), ("m0", "fixed"), ("rv32imc", "fixed")] {
            let _ = write!(s, " {} | {} |", get(t, b, left), get(t, b, right));
        }
        s.push('\n');
    }
    s
}
