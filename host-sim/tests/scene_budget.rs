//! `host-sim budget --scene`: the command line, its files, and `--check` failing when a
//! prediction is off (the predictions themselves are tested in `src/scene_budget`).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("host-sim-budget-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn demo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/demo.toml")
}

fn budget(args: &[&str], out: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .arg("budget")
        .arg("--scene")
        .arg(demo())
        .args(args)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap()
}

#[test]
fn writes_the_table_the_csv_and_the_plot_and_answers_the_question() {
    let dir = scratch("files");
    let out = budget(&["--chip", "rp2040", "--fps", "30"], &dir);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8(out.stdout).unwrap();
    for ext in ["md", "csv", "png"] {
        let p = dir.join(format!("demo-rp2040.{ext}"));
        assert!(stdout.contains(&p.display().to_string()), "{stdout}");
        assert!(
            std::fs::metadata(&p).unwrap().len() > 100,
            "{}",
            p.display()
        );
    }
    // The demo does not reach 30 fps on one RP2040 core: the answer says so and by how much.
    assert!(stdout.contains("Nothing meets 30 fps."), "{stdout}");
    let csv = std::fs::read_to_string(dir.join("demo-rp2040.csv")).unwrap();
    let first = csv.lines().nth(1).unwrap();
    assert!(
        first.starts_with("rp2040,fixed,false,\"Gouraud (as written)\""),
        "{first}"
    );
    // A generous frame rate is met by the firmware's own configuration.
    let out = budget(&["--chip", "rp2040", "--fps", "4"], &dir);
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(
        stdout.contains("Recommended for 4 fps: fixed with Gouraud"),
        "{stdout}"
    );
}

#[test]
fn check_fails_when_the_emulated_frame_is_far_from_the_prediction() {
    let dir = scratch("check");
    let out = budget(&["--chip", "stm32f411"], &dir);
    assert!(out.status.success());
    let csv = std::fs::read_to_string(dir.join("demo-stm32f411.csv")).unwrap();
    let row = csv.lines().nth(1).unwrap().to_owned();
    let f: Vec<&str> = row.split(',').collect();
    let predicted: f64 = f[8].parse().unwrap();
    let counts = format!("{},{},{}", f[15], f[17], f[18]);
    let frames = dir.join("frames.csv");
    let header = "mode,frame,total,setup,transform,shade,raster,flush,call,shader_calls,pixels,triangle_setups";
    for (factor, ok) in [(1.10, true), (0.90, true), (1.25, false), (0.80, false)] {
        let total = (predicted * factor).round();
        std::fs::write(
            &frames,
            format!("{header}\ngouraud,0,{total},0,0,0,{total},0,{total},{counts}\n"),
        )
        .unwrap();
        let out = budget(
            &["--chip", "stm32f411", "--check", frames.to_str().unwrap()],
            &dir,
        );
        assert_eq!(
            out.status.success(),
            ok,
            "measured {factor} x the prediction: {}",
            String::from_utf8_lossy(&out.stdout)
        );
    }
    // Counts that differ from the host's fail even when the time agrees.
    std::fs::write(
        &frames,
        format!("{header}\ngouraud,0,{predicted},0,0,0,{predicted},0,{predicted},1,2,3\n"),
    )
    .unwrap();
    let out = budget(
        &["--chip", "stm32f411", "--check", frames.to_str().unwrap()],
        &dir,
    );
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("DIFFERENT"));
}

#[test]
fn an_unknown_chip_is_an_error_naming_the_chips() {
    let dir = scratch("chip");
    let out = budget(&["--chip", "esp32"], &dir);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("unknown chip \"esp32\"") && err.contains("rp2040-dual"),
        "{err}"
    );
}
