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
    assert_eq!(printed.trim(), path.display().to_string());
    assert_png(&path);
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
    for args in [&["--help"][..], &["eval", "--help"], &["render", "--help"]] {
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
