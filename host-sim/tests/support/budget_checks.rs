//! The QEMU budget harness's checks of a target's other lines (`qemu_budget.rs`, included with
//! `#[path]`): the scene lines (`S`), the demo's vertex shade (`D`), the hardware square root
//! and the point-sample alternatives.

use super::*;

/// Issue 7 on the target: the `S` lines (one object rendered with 16 lights of which 2 reach
/// it, prepared, against the 2 alone) must show the same frame (equal checksums) for at most
/// 1.25 times the instructions.
pub(crate) fn check_scene(short: &str, out: &str, failures: &mut Vec<String>) {
    let mut got: HashMap<String, (String, u64, String)> = HashMap::new();
    for l in out.lines() {
        let f: Vec<&str> = l.split_whitespace().collect();
        if f.len() == 5 && f[0] == "S" {
            if let Ok(n) = f[3].parse::<u64>() {
                got.insert(f[2].to_owned(), (f[1].to_owned(), n, f[4].to_owned()));
            }
        }
    }
    let (Some(a), Some(b)) = (got.get("16_prepared"), got.get("2_lights")) else {
        failures.push(format!("{short}: no S lines (the scene cost did not run)"));
        return;
    };
    let ratio = a.1 as f64 / b.1 as f64;
    println!(
        "{short} {}: one sphere, 16 lights of which 2 reach it, prepared: {} instructions; the 2 \
         alone: {} ({ratio:.3}x; bound 1.25x); frames {}",
        a.0,
        a.1,
        b.1,
        if a.2 == b.2 { "identical" } else { "DIFFER" }
    );
    if a.2 != b.2 {
        failures.push(format!(
            "{short}: the prepared 16-light frame differs from the 2-light frame ({} vs {})",
            a.2, b.2
        ));
    }
    if ratio.is_nan() || ratio > 1.25 {
        failures.push(format!(
            "{short}: 16 lights prepared cost {ratio:.3}x the 2 lights (bound 1.25x)"
        ));
    }
}

/// The `D` lines (one demo vertex shade per call): every case and input present, each channel
/// within the backend's model target times [`demo_shade::weight`] of the f64 reference
/// evaluated here from the same rounded inputs.
pub(crate) fn check_demo_shade(
    short: &str,
    out: &str,
    rows: &mut BTreeMap<(String, String, usize), Row>,
    failures: &mut Vec<String>,
) {
    for b in backends() {
        let mut got: HashMap<(String, usize), (u32, Vec<f64>)> = HashMap::new();
        for l in out.lines() {
            let f: Vec<&str> = l.split_whitespace().collect();
            if f.len() == 8 && f[0] == "D" && f[1] == b.name {
                let (Ok(i), Ok(n)) = (f[3].parse::<usize>(), f[4].parse::<u32>()) else {
                    failures.push(format!("{short}: bad D line {l}"));
                    continue;
                };
                let v: Vec<f64> = f[5..]
                    .iter()
                    .filter_map(|h| u64::from_str_radix(h, 16).ok().map(f64::from_bits))
                    .collect();
                got.insert((f[2].to_owned(), i), (n, v));
            }
        }
        if got.is_empty() {
            continue;
        }
        let mut reference = Vec::new();
        let ok = demo_shade::run::<f64, _>(b.round, &mut Plain, &mut |case, i, c, _| {
            reference.push((case, i, c))
        });
        if ok.is_none() {
            failures.push(format!("{short}: the f64 demo shade refused its setup"));
            continue;
        }
        let same = (b.demo)();
        for (case, i, want) in reference {
            let (name, m) = demo_shade::CASES[case];
            let row = rows
                .entry((short.to_owned(), b.name.to_owned(), DEMO_ROW + case))
                .or_default();
            let Some((count, v)) = got.get(&(name.to_owned(), i)) else {
                failures.push(format!("{short} {} {name}: input {i} missing", b.name));
                continue;
            };
            row.insns.push(*count);
            if same
                .iter()
                .any(|&(c, j, h)| c == case && j == i && h[..] == v[..])
            {
                row.bit_identical += 1;
            }
            // The models' target, scaled by the colour weights; f32's Phong part grows as m.
            let model_tol = if b.name == "f32" {
                2e-6 + f64::from(m) * 2f64.powi(-24)
            } else {
                (b.tolerance)("demo")
            };
            let tol = model_tol * demo_shade::weight(case);
            for (c, (&v, &w)) in v.iter().zip(&want).enumerate() {
                let err = (v - w).abs() / w.abs().max(1.0);
                row.max_err = row.max_err.max(err);
                if err.is_nan() || err > tol {
                    failures.push(format!(
                        "{short} {} {name} input {i} channel {c}: {v:e} on target, {w:e} in f64: \
                         error {err:.2e} > {tol:.2e}",
                        b.name
                    ));
                }
            }
        }
    }
}

/// The `Q` line of the M4F: the hardware square root (`VSQRT.F32`, what `<f32 as Real>::sqrt`
/// is there) must be in use and equal `libm::sqrtf` on every pattern of the sweep.
pub(crate) fn check_sqrt(short: &str, out: &str, failures: &mut Vec<String>) {
    let line = out.lines().find(|l| l.starts_with("Q sqrt_f32 "));
    let Some(l) = line else {
        if short == "m4f" {
            failures.push(format!(
                "{short}: no Q line (the square-root sweep did not run)"
            ));
        }
        return;
    };
    let f: Vec<u64> = l
        .split_whitespace()
        .skip(2)
        .filter_map(|x| x.parse().ok())
        .collect();
    if let [hw, checked, mismatches, insns_hw, insns_libm] = f[..] {
        println!(
            "{short}: <f32 as Real>::sqrt is {} : {mismatches} mismatches with libm::sqrtf over \
             {checked} bit patterns; one call {insns_hw} instructions (libm::sqrtf {insns_libm})",
            if hw == 1 { "VSQRT.F32" } else { "libm::sqrtf" }
        );
        if hw != 1 || mismatches != 0 || checked < 500_000 {
            failures.push(format!("{short}: square-root sweep failed: {l}"));
        }
    } else {
        failures.push(format!("{short}: bad Q line {l}"));
    }
}

/// The `A` lines (point lights and k-sample alternatives, f32): all present, each within the
/// f32 target of the same sampler evaluated in f64 on the host.
pub(crate) fn check_points(
    short: &str,
    lines: &[Line],
    sizes: &HashMap<String, u64>,
    rows: &mut BTreeMap<(String, String, usize), Row>,
    failures: &mut Vec<String>,
) {
    for k in points::KS {
        let reference = points::Sampled::<f64>::new(k, cases::PHONG_M);
        let host = points::Sampled::<f32>::new(k, cases::PHONG_M);
        for (alt, (name, _)) in points::ALTERNATIVES.iter().enumerate() {
            let point = name.starts_with("point_");
            if point && k != 1 {
                continue;
            }
            let (mut want, mut same) = (Vec::new(), Vec::new());
            points::run_alt(
                &reference,
                alt,
                ring_dirs(),
                round_f32,
                &mut Plain,
                &mut |s| want.push(s.value[0]),
            );
            points::run_alt(&host, alt, ring_dirs(), |x| x, &mut Plain, &mut |s| {
                same.push(s.value[0])
            });
            let backend = if point {
                "f32".to_owned()
            } else {
                format!("f32-pts{k}")
            };
            let row = rows
                .entry((short.to_owned(), backend.clone(), MODELS.len() + alt))
                .or_default();
            let key = format!("::points::s_{name}::<");
            row.code = sizes
                .iter()
                .find_map(|(n, &b)| (n.contains(&key) && n.ends_with("f32>")).then_some(b));
            let tol = tol_f32(name);
            for l in lines
                .iter()
                .filter(|l| l.k == Some(k) && l.model == *name && l.backend == "f32")
            {
                row.insns.push(l.count);
                let (w, v) = (want[l.input], l.value[0]);
                let err = (v - w).abs() / w.abs().max(1.0);
                row.max_err = row.max_err.max(err);
                if err.is_nan() || err > tol {
                    failures.push(format!(
                        "{short} {name} k={k} input {}: {v:e} on target, {w:e} in f64",
                        l.input
                    ));
                }
                if same[l.input] == v {
                    row.bit_identical += 1;
                }
            }
            if row.insns.len() != RING {
                failures.push(format!(
                    "{short} {name} k={k}: {} of {RING} inputs",
                    row.insns.len()
                ));
            }
        }
    }
}
