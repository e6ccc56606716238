//! The QEMU budget harness (`harness = false`): builds `boards/qemu-budget` for Cortex-M4F
//! (`thumbv7em-none-eabihf`), Cortex-M0 (`thumbv6m-none-eabi`) and RISC-V (`riscv32imc-unknown-
//! none-elf`, ESP32-C3 class), runs the ARM images under `qemu-system-arm` with semihosting and
//! the RISC-V image under `qemu-system-riscv32` (`virt`, `-bios none`, an RV32IMC hart, output
//! on its UART), and checks what they print:
//!
//! - the counter self-check (TIM2 of `netduinoplus2`, and `instret` on `virt`, under
//!   `-icount shift=0` count executed instructions exactly: a `subs`/`bne` (ARM) or
//!   `addi`/`bnez` (RISC-V) loop of n iterations takes exactly 2n), re-checked here from the
//!   numbers the firmware prints, with the empty region's count that every count is net of
//!   (`base` to `base + 2`), and no count wrapped;
//! - every model id x backend x input is present, and every value is within the accuracy
//!   target of the f64 reference computed here from the same (rounded) inputs;
//! - the `U` lines (the calls with a unit direction) answer the `V` lines' bits, and the `W`
//!   lines (the positional lights in world coordinates, 1000 units out) are within the
//!   accuracy target of the plain cases' reference, and the `B` lines (`phong_polygon` at
//!   the bars' exponent m = 15) within it of f64 at that exponent (`support/unit_rows.rs`,
//!   `support/world_rows.rs`, `support/bar_rows.rs`);
//! - the M0 image gives bit-identical values on `microbit` (a real Cortex-M0 model); it is
//!   built and run as four parts ([`M0_PARTS`]: the models, the rest, the world lights, the
//!   bars' cases), each of which fits the micro:bit's 256 KB where the whole no longer does,
//!   the other targets' as three ([`PARTS`]: the world lights and the bars' cases apart, so
//!   that they do not change the plain kernels' inlining), and each target's lines are read
//!   as one image's;
//! - the board demo's vertex shade (`D` lines: `Lit::shade` with the demo's lights and
//!   materials, `Fixed22` on the M0, f32 on the M4F) is within the backend's target of f64,
//!   scaled by the colour weights the model values are multiplied by.
//!
//! It prints the instructions per call (min, median, max over the inputs) and the code size of
//! each model per target, and writes them to `target/qemu-budget/counts.csv`, which
//! `host-sim budget` reads.
//!
//! Without `qemu-system-arm` it prints SKIPPED and passes, unless the environment variable
//! `CI` is set, where it fails; likewise without `qemu-system-riscv32` (Debian's
//! `qemu-system-misc`) for the RISC-V target alone (the ARM targets still run). Run it alone
//! with `cargo test -p host-sim --test qemu_budget`.

#[path = "support/bar_rows.rs"]
mod bar_rows;
#[path = "support/kernel_sizes.rs"]
mod kernel_sizes;
#[path = "support/process.rs"]
mod process;
#[path = "support/qemu_output.rs"]
mod qemu_output;
#[path = "support/riscv_refs.rs"]
mod riscv_refs;
#[path = "support/unit_rows.rs"]
mod unit_rows;
#[path = "support/world_rows.rs"]
mod world_rows;
use kernel_sizes::{kernel_sizes, kernel_symbol};
use process::{root, run};
use qemu_output::{check_counter, check_no_wrap, parse, Line};

#[allow(dead_code)]
#[path = "../../boards/qemu-budget/src/bar_cases.rs"]
mod bar_cases;
#[allow(dead_code)]
#[path = "../../boards/qemu-budget/src/cases.rs"]
mod cases;
#[allow(dead_code)]
#[path = "../../boards/qemu-budget/src/demo_shade.rs"]
mod demo_shade;
#[allow(dead_code)]
#[path = "../../boards/qemu-budget/src/points.rs"]
mod points;
#[allow(dead_code)]
#[path = "../../boards/qemu-budget/src/world_cases.rs"]
mod world_cases;

use std::collections::{BTreeMap, HashMap, HashSet};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode, Stdio};
use std::time::Duration;

use arealight::{Fast32, Fixed22, Real};
use cases::{Backend, Lights, Meter, Sample, MODELS, RING};

#[path = "support/budget_checks.rs"]
mod budget_checks;
#[path = "support/host_reference.rs"]
mod host_reference;
use budget_checks::*;
use host_reference::*;

/// The targets: triple, short name, cargo profile, the machine that counts, an optional
/// machine that runs the same image uncounted (a functional check). The QEMU of each is
/// [`qemu_binary`].
const TARGETS: [(&str, &str, &str, &str, Option<&str>); 3] = [
    (
        "thumbv7em-none-eabihf",
        "m4f",
        "release",
        "netduinoplus2",
        None,
    ),
    (
        "thumbv6m-none-eabi",
        "m0",
        "release-m0",
        "netduinoplus2",
        Some("microbit"),
    ),
    (
        "riscv32imc-unknown-none-elf",
        "rv32imc",
        "release-rv",
        "virt",
        None,
    ),
];

/// The QEMU that runs `triple`'s image.
fn qemu_binary(triple: &str) -> &'static str {
    if triple.starts_with("riscv32") {
        "qemu-system-riscv32"
    } else {
        "qemu-system-arm"
    }
}

/// The parts the Cortex-M0 image is built as (`QEMU_BUDGET_PART` of `boards/qemu-budget`):
/// every backend's models, then the demo shader, the alternatives and the scene, then the
/// world lights, then the bars' cases (`phong_polygon` at m = 15, apart for the same reason as the
/// world lights: [`PARTS`]). The whole image came within 450 bytes of the micro:bit's 256 KB; the
/// models alone take about 200 KB. (Measured when split: every value bit for bit the whole image's,
/// and the counts within 0.4 % of it but for `sky_ground` and `sh9_irradiance` with a unit normal,
/// -3.4 % and +2.7 %: LLVM inlines a little differently into the smaller image.)
const M0_PARTS: [&str; 4] = ["models", "extras", "world", "bar"];

/// The parts of the other targets' images: everything but the world lights, then those,
/// which share the plain lights' functions and would change their inlining into the plain
/// kernels (see `boards/qemu-budget/src/main.rs`, `PART`), then the bars' cases, which call
/// the polygon's Phong term with another lobe (a second caller likewise).
const PARTS: [&str; 3] = ["main", "world", "bar"];

/// Builds the image for `target` (only the cases of `part`, if given) into `target_dir`.
fn build(
    target: &str,
    profile: &str,
    target_dir: &Path,
    part: Option<&str>,
) -> Result<PathBuf, String> {
    let dir = root().join("boards/qemu-budget");
    let mut cmd = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()));
    cmd.current_dir(&dir)
        .args(["build", "--quiet", "--profile", profile, "--target", target])
        .arg("--target-dir")
        .arg(target_dir)
        .env_remove("RUSTFLAGS")
        .env_remove("CARGO_ENCODED_RUSTFLAGS")
        .env_remove("CARGO_BUILD_TARGET")
        .env_remove("CARGO_TARGET_DIR")
        .env_remove("QEMU_BUDGET_ONLY")
        .env_remove("QEMU_BUDGET_PART");
    if let Some(part) = part {
        cmd.env("QEMU_BUDGET_PART", part);
    }
    run(&mut cmd, Duration::from_secs(900), |_| true).map_err(|e| {
        format!("building the firmware for {target} (is the rustup target installed?): {e}")
    })?;
    Ok(target_dir.join(target).join(profile).join("qemu-budget"))
}

fn qemu(triple: &str, machine: &str, elf: &Path) -> Result<String, String> {
    let mut cmd = Command::new(qemu_binary(triple));
    if triple.starts_with("riscv32") {
        // `virt` with no firmware (the image starts at the start of RAM in machine mode), an
        // RV32IMC hart (the default one also has A, F and D: without them any such instruction
        // traps), output on the UART.
        cmd.args(["-machine", machine, "-bios", "none"])
            .args(["-cpu", "rv32,a=false,f=false,d=false"])
            .args(["-display", "none", "-monitor", "none", "-serial", "stdio"]);
    } else {
        cmd.args([
            "-machine",
            machine,
            "-nographic",
            "-monitor",
            "none",
            "-serial",
            "none",
        ])
        .args(["-semihosting-config", "enable=on,target=native"]);
    }
    cmd.args(["-icount", "shift=0,align=off,sleep=off"])
        .arg("-kernel")
        .arg(elf)
        .stdin(Stdio::null());
    run(&mut cmd, Duration::from_secs(120), |_| true)
}

fn qemu_version(binary: &str) -> String {
    Command::new(binary)
        .arg("--version")
        .output()
        .ok()
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .and_then(|s| s.lines().next().map(str::to_owned))
        .unwrap_or_else(|| format!("{binary} not found"))
}

/// The kernel of `model` for the backend `name` when it has no symbol of its own: LLVM merges
/// identical functions, and a kernel whose body is the same as another backend's (e.g. `f32`
/// and `Fast32` where every operation the model uses is the same) is then replaced by it at
/// every call and left without a symbol (it is internal, so no alias is kept). The twin is
/// recognised from the firmware's own output: another backend on this target whose kernel
/// for `model` has a symbol and whose calls took the same instructions and gave the same
/// values, bit for bit, for every input. Its size is then the merged kernel's too (what either
/// costs alone; together they cost it once). `None` if no backend or more than one size fits.
fn merged_kernel(
    sizes: &HashMap<String, u64>,
    lines: &[Line],
    short: &str,
    name: &str,
    model: &str,
) -> Option<(&'static str, u64)> {
    let calls = |backend: &str| -> Vec<(usize, u32, Vec<u64>)> {
        let mut v: Vec<_> = lines
            .iter()
            .filter(|l| l.k.is_none() && l.backend == backend && l.model == model)
            .map(|l| {
                (
                    l.input,
                    l.count,
                    l.value.iter().map(|x| x.to_bits()).collect(),
                )
            })
            .collect();
        v.sort();
        v
    };
    let mine = calls(name);
    if mine.is_empty() {
        return None;
    }
    let twins: Vec<(&'static str, u64)> = backends()
        .into_iter()
        .filter(|b| b.name != name && b.targets.contains(&short))
        .filter_map(|b| Some((b.name, kernel_symbol(sizes, model, b.symbol_type)?)))
        .filter(|(b, _)| calls(b) == mine)
        .collect();
    match twins.as_slice() {
        [first, rest @ ..] if rest.iter().all(|t| t.1 == first.1) => Some(*first),
        _ => None,
    }
}

#[derive(Default)]
struct Row {
    insns: Vec<u32>,
    code: Option<u64>,
    max_err: f64,
    bit_identical: usize,
}

/// Row index of the first demo-shade case (after the models and the alternatives).
const DEMO_ROW: usize = MODELS.len() + points::ALTERNATIVES.len();

#[allow(clippy::too_many_arguments)]
fn check_target(
    triple: &str,
    short: &str,
    profile: &str,
    machine: &str,
    functional: Option<&str>,
    target_dir: &Path,
    refs: &HashMap<&'static str, Vec<Vec<Sample>>>,
    rows: &mut BTreeMap<(String, String, usize), Row>,
) -> Result<(), String> {
    // The parts (each in its own target directory: `PARTS`, `M0_PARTS`), read as one: their
    // lines and outputs in order, their kernels' sizes together (each kernel is in one part).
    let parts: &[&str] = if short == "m0" { &M0_PARTS } else { &PARTS };
    let (mut out, mut lines, mut sizes, mut images) =
        (String::new(), Vec::new(), HashMap::new(), Vec::new());
    for &part in parts {
        let dir = target_dir.join(part);
        let elf = build(triple, profile, &dir, Some(part))?;
        let o = qemu(triple, machine, &elf)?;
        let (l, selfcheck) = parse(&o)?;
        let sc = selfcheck.ok_or("no SELF line: the counter self-check did not run")?;
        let passed = check_counter(triple, &sc)?;
        println!(
            "{short} ({triple} on {machine}, part {part}): counter self-check passed: {passed}"
        );
        sizes.extend(kernel_sizes(
            &std::fs::read(&elf).map_err(|e| e.to_string())?,
        )?);
        out.push_str(&o);
        lines.extend(l);
        images.push((elf, o));
    }
    let mut failures = Vec::new();
    let mut seen = HashSet::new();
    for b in backends()
        .into_iter()
        .filter(|b| b.targets.contains(&short))
    {
        for (mi, model) in MODELS.iter().enumerate() {
            if !cases::supports(b.name, model) {
                continue;
            }
            let host = (b.host)(mi);
            let row = rows
                .entry((short.to_owned(), b.name.to_owned(), mi))
                .or_default();
            row.code = kernel_symbol(&sizes, model, b.symbol_type).or_else(|| {
                let (twin, size) = merged_kernel(&sizes, &lines, short, b.name, model)?;
                println!(
                    "{short} {}: {model}'s kernel merged by LLVM into {twin}'s (no symbol of \
                     its own; the same instruction counts and values for every input): code \
                     bytes from {twin}'s",
                    b.name
                );
                Some(size)
            });
            if row.code.is_none() {
                failures.push(format!("{short} {}: no kernel symbol for {model}", b.name));
            }
            let refv = &refs[b.name][mi];
            for l in lines
                .iter()
                .filter(|l| l.k.is_none() && l.backend == b.name && l.model == *model)
            {
                seen.insert((b.name, mi, l.input));
                row.insns.push(l.count);
                let Some(r) = refv.iter().find(|s| s.input == l.input) else {
                    failures.push(format!("{model}: input {} has no reference", l.input));
                    continue;
                };
                let tol = (b.tolerance)(model);
                for (c, &v) in l.value.iter().enumerate() {
                    let want = r.value[c];
                    let err = (v - want).abs() / want.abs().max(1.0);
                    row.max_err = row.max_err.max(err);
                    if err.is_nan() || err > tol {
                        failures.push(format!(
                            "{short} {} {model} input {} channel {c}: {v:e} on target, {want:e} \
                             in f64: error {err:.2e} > {tol:.2e}",
                            b.name, l.input
                        ));
                    }
                }
                if host
                    .iter()
                    .find(|s| s.input == l.input)
                    .is_some_and(|h| h.value[..h.channels] == l.value[..])
                {
                    row.bit_identical += 1;
                }
            }
            for i in 0..RING {
                if !seen.contains(&(b.name, mi, i)) {
                    failures.push(format!("{short} {} {model}: input {i} missing", b.name));
                }
            }
        }
    }
    check_no_wrap(short, &out, &mut failures);
    check_points(short, &lines, &sizes, rows, &mut failures);
    check_scene(short, &out, &mut failures);
    check_demo_shade(short, &out, rows, &mut failures);
    unit_rows::check(short, &out, rows, &mut failures);
    let tolerance = |backend: &str, model: &str| {
        backends()
            .iter()
            .find(|b| b.name == backend)
            .map_or(0.0, |b| (b.tolerance)(model))
    };
    world_rows::check(short, &out, refs, &tolerance, rows, &mut failures);
    bar_rows::check(short, &out, rows, &mut failures);
    check_sqrt(short, &out, &mut failures);
    if !out.lines().any(|l| l.starts_with("D ")) {
        failures.push(format!("{short}: no D lines (the demo shade did not run)"));
    }
    // Each image again on the functional machine (the M0's: each part on the micro:bit).
    for (elf, out) in &images {
        let Some(m) = functional else {
            break;
        };
        let (lines, _) = parse(out)?;
        let out2 = qemu(triple, m, elf)?;
        let (lines2, _) = parse(&out2)?;
        // The D, U, W and B lines too (their count in the fifth field), without their counts
        // (0 there).
        let shades = |o: &str| -> Vec<String> {
            o.lines()
                .filter(|l| ["D ", "U ", "W ", "B "].iter().any(|k| l.starts_with(k)))
                .map(|l| {
                    let f: Vec<&str> = l.split_whitespace().collect();
                    format!("{} {}", f[..4].join(" "), f[5..].join(" "))
                })
                .collect()
        };
        let (d1, d2) = (shades(out), shades(&out2));
        let differ = lines
            .iter()
            .zip(&lines2)
            .filter(|(a, b)| a.value != b.value || a.model != b.model || a.backend != b.backend)
            .count()
            + d1.iter().zip(&d2).filter(|(a, b)| a != b).count()
            + d1.len().abs_diff(d2.len());
        if lines.len() != lines2.len() || differ > 0 {
            failures.push(format!(
                "{short}: on {m} the same image gave {} lines, {differ} with other values than on {machine}",
                lines2.len()
            ));
        } else {
            println!(
                "{short}: the same image on {m} (a Cortex-M0 model, uncounted) gave the same {} lines' values bit for bit",
                lines2.len() + d2.len()
            );
        }
    }
    if failures.is_empty() {
        Ok(())
    } else {
        Err(failures.join("\n"))
    }
}

/// The name of row `index`: a model id, or an alternative of [`points::ALTERNATIVES`].
fn row_name(index: usize) -> &'static str {
    MODELS
        .get(index)
        .copied()
        .or_else(|| points::ALTERNATIVES.get(index - MODELS.len()).map(|a| a.0))
        .or_else(|| demo_shade::CASES.get(index - DEMO_ROW).map(|c| c.0))
        .or_else(|| unit_rows::row_name(index))
        .or_else(|| world_rows::row_name(index))
        .or_else(|| bar_rows::row_name(index))
        .unwrap_or("?")
}

fn median(v: &[u32]) -> u32 {
    let mut s = v.to_vec();
    s.sort_unstable();
    s.get(s.len() / 2).copied().unwrap_or(0)
}

fn main() -> ExitCode {
    // `cargo test -- --list` and filters from a plain `cargo test NAME` must not run QEMU.
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.iter().any(|a| a == "--list") {
        println!("qemu_budget: test");
        return ExitCode::SUCCESS;
    }
    if let Some(filter) = args.iter().find(|a| !a.starts_with('-')) {
        if !"qemu_budget".contains(filter.as_str()) {
            println!("0 passed, 0 failed, 1 skipped (filtered out)");
            return ExitCode::SUCCESS;
        }
    }
    if Command::new("qemu-system-arm")
        .arg("--version")
        .output()
        .is_err()
    {
        if std::env::var_os("CI").is_some() {
            eprintln!("qemu_budget: FAILED: qemu-system-arm is not installed (CI is set; .ci/run installs it)");
            return ExitCode::FAILURE;
        }
        println!("\n*** qemu_budget SKIPPED: qemu-system-arm is not installed ***");
        println!("*** (apt-get install -y qemu-system-arm; .ci/run does, and there this test fails instead) ***\n");
        println!("0 passed, 0 failed, 1 skipped");
        return ExitCode::SUCCESS;
    }
    println!("qemu_budget: {}", qemu_version("qemu-system-arm"));
    // The RISC-V target needs qemu-system-riscv32 (Debian: qemu-system-misc): without it that
    // target alone is skipped (failed under CI, where .ci/run installs it).
    let riscv = Command::new("qemu-system-riscv32")
        .arg("--version")
        .output()
        .is_ok();
    if riscv {
        println!("qemu_budget: {}", qemu_version("qemu-system-riscv32"));
    } else if std::env::var_os("CI").is_some() {
        eprintln!("qemu_budget: FAILED: qemu-system-riscv32 is not installed (CI is set; .ci/run installs qemu-system-misc)");
        return ExitCode::FAILURE;
    } else {
        println!("\n*** qemu_budget: riscv32imc SKIPPED: qemu-system-riscv32 is not installed ***");
        println!("*** (apt-get install -y qemu-system-misc; .ci/run does, and there this test fails instead) ***\n");
    }
    let out_dir = root().join("target/qemu-budget");
    let mut refs = HashMap::new();
    for b in backends() {
        match reference(b.round) {
            Ok(r) => {
                refs.insert(b.name, r);
            }
            Err(e) => {
                eprintln!("qemu_budget: FAILED: {e}");
                return ExitCode::FAILURE;
            }
        }
    }
    let mut rows = BTreeMap::new();
    let mut failed = Vec::new();
    let mut ran = Vec::new();
    for (triple, short, profile, machine, functional) in TARGETS {
        if !riscv && qemu_binary(triple) == "qemu-system-riscv32" {
            continue;
        }
        ran.push(short);
        let start = std::time::Instant::now();
        if let Err(e) = check_target(
            triple,
            short,
            profile,
            machine,
            functional,
            &out_dir.join("build"),
            &refs,
            &mut rows,
        ) {
            failed.push(format!("{short}: {e}"));
        }
        println!(
            "{short}: built, run and checked in {:.1} s",
            start.elapsed().as_secs_f64()
        );
    }
    // The table, and counts.csv for `host-sim budget`.
    let mut csv = String::from(
        "target,backend,model,insns_min,insns_median,insns_max,code_bytes,max_err,bit_identical_to_host\n",
    );
    println!(
        "\ninstructions per call (exact, QEMU icount; min / median / max over {RING} inputs), \
         code bytes (kernel + everything it reaches), max error vs f64 (relative to max(1, |v|))"
    );
    println!(
        "{:<7} {:<9} {:<29} {:>7} {:>7} {:>7} {:>7} {:>9} {:>6}",
        "tgt", "backend", "model", "min", "median", "max", "bytes", "max err", "ident"
    );
    for ((short, backend, mi), row) in &rows {
        let (mn, md, mx) = (
            row.insns.iter().min().copied().unwrap_or(0),
            median(&row.insns),
            row.insns.iter().max().copied().unwrap_or(0),
        );
        let code = row.code.map(|c| c.to_string()).unwrap_or_default();
        println!(
            "{short:<7} {backend:<9} {:<29} {mn:>7} {md:>7} {mx:>7} {code:>7} {:>9.2e} {:>3}/{}",
            row_name(*mi),
            row.max_err,
            row.bit_identical,
            row.insns.len()
        );
        let _ = writeln!(
            csv,
            "{short},{backend},{},{mn},{md},{mx},{code},{:e},{}",
            row_name(*mi),
            row.max_err,
            row.bit_identical
        );
    }
    if let Err(e) = std::fs::create_dir_all(&out_dir)
        .and_then(|()| std::fs::write(out_dir.join("counts.csv"), &csv))
    {
        failed.push(format!("writing counts.csv: {e}"));
    } else {
        println!("\nwrote {}", out_dir.join("counts.csv").display());
    }
    if failed.is_empty() {
        println!(
            "\nqemu_budget: counter self-check and accuracy checks passed on {}",
            ran.join(", ")
        );
        println!("1 passed, 0 failed");
        ExitCode::SUCCESS
    } else {
        eprintln!("\nqemu_budget FAILED:\n{}", failed.join("\n"));
        println!("0 passed, 1 failed");
        ExitCode::FAILURE
    }
}
