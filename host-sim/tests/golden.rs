//! Golden images: small renders compared with checked-in PNGs (`tests/golden/`).
//!
//! Tolerance: every channel of every pixel within 2/255 of the golden image. The renders are
//! deterministic (IEEE arithmetic and the pure-Rust `libm`), so on the machine that made the
//! goldens they match exactly; the margin absorbs a platform whose `libm` rounds differently.
//! The goldens are the default render (3 x 3 supersampling, the figures' tone curve); to refresh
//! after an intended change: `host-sim render --only NAMES --out host-sim/tests/golden`.

use std::path::{Path, PathBuf};
use std::process::Command;

use tiny_skia::Pixmap;

const TOLERANCE: u8 = 2;
const GOLDEN: [&str; 3] = ["june_fig20_3", "june_fig20_9", "snyder_fig7"];

fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests")
        .join("golden")
}

#[test]
fn small_renders_match_the_golden_images() {
    let dir = std::env::temp_dir().join(format!("host-sim-golden-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let out = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["render", "--only", &GOLDEN.join(","), "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for name in GOLDEN {
        let file = format!("{name}.png");
        let got = Pixmap::load_png(dir.join(&file)).unwrap();
        let want = Pixmap::load_png(golden_dir().join(&file)).unwrap();
        assert_eq!(
            (got.width(), got.height()),
            (want.width(), want.height()),
            "{file}: size"
        );
        let mut worst = 0u8;
        let mut differing = 0usize;
        for (a, b) in got.pixels().iter().zip(want.pixels()) {
            let d = [
                a.red().abs_diff(b.red()),
                a.green().abs_diff(b.green()),
                a.blue().abs_diff(b.blue()),
            ];
            let m = d.into_iter().max().unwrap_or(0);
            worst = worst.max(m);
            differing += usize::from(m > 0);
        }
        assert!(
            worst <= TOLERANCE,
            "{file}: {differing} pixels differ, by up to {worst}/255 (tolerance {TOLERANCE})"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
