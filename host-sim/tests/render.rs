//! `host-sim render` and the CLI surface.

use std::path::PathBuf;
use std::process::Command;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("host-sim-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn assert_png(path: &std::path::Path) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert!(bytes.starts_with(b"\x89PNG\r\n\x1a\n"), "not a PNG");
    assert!(bytes.len() > 10_000, "suspiciously small PNG");
}

#[test]
fn render_writes_the_contact_sheet_where_asked() {
    let dir = scratch("out");
    let target = dir.join("sheets");
    let out = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["render", "--out"])
        .arg(&target)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let printed = String::from_utf8(out.stdout).unwrap();
    let path = target.join("contact_sheet.png");
    let lines: Vec<&str> = printed.lines().collect();
    assert_eq!(lines[0], path.display().to_string());
    assert_png(&path);
    // Every figure of the issue, each printed and written.
    for stem in [
        "snyder_fig7",
        "june_fig20_3",
        "june_fig20_9",
        "june_fig20_17",
        "arvo_fig5",
        "arvo_fig8",
        "picott_plates",
        "compare_polygon",
        "compare_sphere",
    ] {
        let p = target.join(format!("{stem}.png"));
        assert!(
            lines.contains(&p.display().to_string().as_str()),
            "{stem} not printed"
        );
        assert_png(&p);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn no_arguments_renders_into_out() {
    let dir = scratch("default");
    let out = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_png(&dir.join("out").join("contact_sheet.png"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn every_subcommand_has_help() {
    for args in [
        &["--help"][..],
        &["eval", "--help"],
        &["render", "--help"],
        &["plot", "--help"],
    ] {
        let out = Command::new(env!("CARGO_BIN_EXE_host-sim"))
            .args(args)
            .output()
            .unwrap();
        assert!(out.status.success());
        let text = String::from_utf8(out.stdout).unwrap();
        assert!(text.contains("Usage"), "{text}");
    }
    let out = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["eval", "--backend", "f16"])
        .output()
        .unwrap();
    assert!(!out.status.success(), "an unknown backend is a usage error");
}

#[test]
fn plot_writes_snyders_figures_2_to_6() {
    let dir = scratch("plot");
    let out = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["plot", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for k in 2..=6 {
        assert_png(&dir.join(format!("snyder_fig{k}.png")));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn scene_files_render_and_bad_ones_say_where() {
    let dir = scratch("scene");
    let example = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/example.toml");
    let out = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["render", "--scene", example, "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_png(&dir.join("example.png"));
    let bad = dir.join("bad.toml");
    std::fs::write(
        &bad,
        "[camera]\neye = [0, 1, 5]\ntarget = [0, 0, 0]\nwidth = 10\nheight = 10\nfov = 3\n",
    )
    .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["render", "--scene"])
        .arg(&bad)
        .arg("--out")
        .arg(&dir)
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("bad.toml:6:1:") && err.contains("fov"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The figure's pixels as RGB.
fn load(path: &std::path::Path) -> (u32, u32, Vec<[u8; 3]>) {
    let p = tiny_skia::Pixmap::load_png(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let px = p
        .pixels()
        .iter()
        .map(|c| [c.red(), c.green(), c.blue()])
        .collect();
    (p.width(), p.height(), px)
}

#[test]
fn supersampling_changes_the_silhouettes_and_not_the_shading() {
    // June fig. 20-3: two spheres on black. With --aa 4 against --aa 1, every pixel that
    // differs by more than 2 levels is on a silhouette (a neighbour in the one-sample frame is
    // background), there are many of them, and they lie between background and sphere.
    let dir = scratch("aa");
    let mut frames = Vec::new();
    for k in ["1", "4"] {
        let out_dir = dir.join(k);
        let out = Command::new(env!("CARGO_BIN_EXE_host-sim"))
            .args(["render", "--only", "june_fig20_3", "--aa", k, "--out"])
            .arg(&out_dir)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("rendered 1 picture in"), "{err}");
        frames.push(load(&out_dir.join("june_fig20_3.png")));
    }
    let (w, h, one) = &frames[0];
    let (w4, h4, four) = &frames[1];
    assert_eq!((w, h), (w4, h4));
    let (w, h) = (*w as usize, *h as usize);
    let black = |p: [u8; 3]| p == [0, 0, 0];
    let (mut edge, mut interior_worst) = (0, 0u8);
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            let i = y * w + x;
            let d = (0..3)
                .map(|c| one[i][c].abs_diff(four[i][c]))
                .max()
                .unwrap_or(0);
            let near_bg = [i - 1, i + 1, i - w, i + w].iter().any(|&j| black(one[j]));
            if near_bg && !black(one[i]) || black(one[i]) && !black(four[i]) {
                if d > 2 {
                    edge += 1;
                    // Between the background and the sphere's colour, channel by channel.
                    let inner = if black(one[i]) { four[i] } else { one[i] };
                    for c in 0..3 {
                        assert!(four[i][c] <= inner[c].max(one[i][c]), "({x}, {y})");
                    }
                }
            } else {
                interior_worst = interior_worst.max(d);
            }
        }
    }
    assert!(edge > 300, "{edge} silhouette pixels changed");
    assert!(
        interior_worst <= 2,
        "interior differs by {interior_worst} levels"
    );
    let out = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["render", "--aa", "9", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(!out.status.success(), "--aa 9 is out of range");
    let _ = std::fs::remove_dir_all(&dir);
}
