//! The `host-sim budget` command's entry points: `--scene` (print the table, write the
//! report files, `--check` against the emulated frames), `--emit-spec` and `--calibrate`.

use super::*;

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
