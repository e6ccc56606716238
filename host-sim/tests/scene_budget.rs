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
    let out = budget(&["--chip", "rp2040", "--fps", "40"], &dir);
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
    // The demo does not reach 40 fps on one RP2040 core, not even with its meshes halved (30
    // fps it does, since the colour table's guards): the answer says so and by how much.
    assert!(stdout.contains("Nothing meets 40 fps."), "{stdout}");
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

/// A floor over a point light far below it (beyond its bounding sphere: `Scene::prepare` drops
/// it for the floor) and under a sphere light.
const CULLED: &str = r#"
[camera]
eye = [0.0, 2.0, 3.0]
target = [0.0, 0.0, 0.0]
width = 120
height = 120

[[light]]
kind = "point"
position = [0.0, -5.0, 0.0]

[[light]]
kind = "sphere"
center = [0.0, 2.0, 0.0]
radius = 0.3

[[material]]
name = "m"
diffuse = [0.5, 0.5, 0.5]

[[mesh]]
kind = "plane"
size = [3.0, 3.0]
cells = [4, 4]
material = "m"
gouraud = true
"#;

/// The CSV rows of `scene` on `chip`: (backend, shading) -> (frame, mean error).
fn budget_rows(scene: &Path, chip: &str, dir: &Path) -> Vec<(String, String, f64, f64)> {
    let out = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .arg("budget")
        .arg("--scene")
        .arg(scene)
        .args(["--chip", chip, "--out"])
        .arg(dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stem = scene.file_stem().unwrap().to_string_lossy().into_owned();
    let csv = std::fs::read_to_string(dir.join(format!("{stem}-{chip}.csv"))).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |n: &str| header.iter().position(|h| *h == n).unwrap();
    csv.lines()
        .skip(1)
        .map(|l| {
            // The shading is the one quoted field.
            let (head, rest) = l.split_once(",\"").unwrap();
            let (shading, tail) = rest.split_once("\",").unwrap();
            let f: Vec<&str> = head.split(',').chain([""]).chain(tail.split(',')).collect();
            (
                f[col("backend")].to_owned(),
                shading.to_owned(),
                f[col("frame")].parse().unwrap(),
                f[col("mean_err")].parse().unwrap(),
            )
        })
        .collect()
}

#[test]
fn culling_and_hermite_are_options_with_their_own_costs() {
    let dir = scratch("variants");
    let scene = dir.join("culled.toml");
    std::fs::write(&scene, CULLED).unwrap();
    let rows = budget_rows(&scene, "stm32f411", &dir);
    let find = |shading: &str| {
        rows.iter()
            .find(|r| r.0 == "f32" && r.1 == shading)
            .unwrap_or_else(|| panic!("no f32 row {shading:?} in {rows:?}"))
    };
    // Culling skips the point light's calls on the floor: the same frame (the same error),
    // fewer instructions; the most where every pixel calls the lights.
    for (plain, culled) in [
        (
            "Gouraud (as written)",
            "Gouraud (as written), lights culled per object",
        ),
        ("per pixel", "per pixel, lights culled per object"),
    ] {
        let (a, b) = (find(plain), find(culled));
        assert_eq!(a.3, b.3, "{plain}: the error must not change");
        assert!(b.2 < a.2, "{plain}: {} is not below {}", b.2, a.2);
    }
    let (a, b) = (
        find("per pixel"),
        find("per pixel, lights culled per object"),
    );
    assert!(b.2 < 0.95 * a.2, "per pixel: {} against {}", b.2, a.2);
    // The sphere light's Hermite approximation: its own row, a different frame cost.
    let h = find("Gouraud (as written), Hermite caps and spheres");
    assert_ne!(h.2, find("Gouraud (as written)").2);
    // The demo scene: nothing to cull (every light reaches both objects), so no such row.
    let demo_rows = budget_rows(&demo(), "stm32f411", &dir);
    assert!(
        demo_rows.iter().all(|r| !r.1.contains("culled")),
        "{demo_rows:?}"
    );
    assert!(demo_rows.iter().any(|r| r.1.contains("Hermite")));
}
