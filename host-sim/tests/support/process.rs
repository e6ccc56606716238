//! What the QEMU harnesses (`qemu_budget.rs`, `qemu_frame.rs`) share: the repository root and
//! running a command to completion within a time limit. Included by each with `#[path]` (a
//! subdirectory of `tests/` is not a test target of its own).

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The repository root (host-sim's parent).
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default()
}

/// Runs `cmd` to completion within `timeout`; its stdout, or why it failed (with the last five
/// stdout lines that `shown_line` keeps, and stderr).
pub fn run(
    cmd: &mut Command,
    timeout: Duration,
    shown_line: fn(&str) -> bool,
) -> Result<String, String> {
    let shown = format!("{cmd:?}");
    let mut child = cmd
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("{shown}: {e}"))?;
    // Drain both pipes while waiting, so a chatty child never blocks on a full pipe.
    let drain = |pipe: Option<Box<dyn std::io::Read + Send>>| {
        std::thread::spawn(move || {
            let mut buf = Vec::new();
            if let Some(mut p) = pipe {
                let _ = p.read_to_end(&mut buf);
            }
            String::from_utf8_lossy(&buf).into_owned()
        })
    };
    let out = drain(child.stdout.take().map(|p| Box::new(p) as _));
    let err = drain(child.stderr.take().map(|p| Box::new(p) as _));
    let start = Instant::now();
    let status = loop {
        match child.try_wait() {
            Ok(Some(status)) => break status,
            Ok(None) if start.elapsed() > timeout => {
                let _ = child.kill();
                let _ = child.wait();
                return Err(format!("{shown}: timed out after {timeout:?}"));
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(20)),
            Err(e) => return Err(format!("{shown}: {e}")),
        }
    };
    let text = out.join().unwrap_or_default();
    let errors = err.join().unwrap_or_default();
    if !status.success() {
        let tail: Vec<&str> = text
            .lines()
            .filter(|l| shown_line(l))
            .rev()
            .take(5)
            .collect();
        return Err(format!(
            "{shown}: {status}\n--- stdout (last lines)\n{}\n--- stderr\n{errors}",
            tail.into_iter().rev().collect::<Vec<_>>().join("\n"),
        ));
    }
    Ok(text)
}
