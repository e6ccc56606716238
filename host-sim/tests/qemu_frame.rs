//! The QEMU frame harness (`harness = false`): builds `boards/qemu-frame` (the STM32F411
//! firmware's demo frame, `boards/demo-scene` in `f32`) for the Cortex-M4F, runs it under
//! `qemu-system-arm` (`netduinoplus2`, semihosting, `-icount shift=0`), and checks what it
//! prints:
//!
//! - the counter self-check (TIM2 counts executed instructions exactly: a `subs`/`bne` loop of
//!   n iterations reads exactly 2n more than the two loads alone), re-checked here;
//! - every band of every frame (each mode of `scene::MODES`, each frame of `scene::FRAMES`) is
//!   bit-identical to the same frame rendered here on the host, in `f32`, by the same code
//!   (`boards/qemu-frame/src/scene.rs`, included below), and so are the draw statistics.
//!
//! It prints the instructions per stage of each frame (exact; see the firmware's module docs
//! for what each count includes) as a markdown table, and writes it to
//! `target/qemu-frame/frames.md` and `target/qemu-frame/frames.csv`, and the unit costs the
//! firmware measured after its frames (`demo_scene::calibrate`, for `host-sim budget
//! --calibrate`) to `target/qemu-frame/calibration.csv`.
//!
//! Without `qemu-system-arm` it prints SKIPPED and passes, unless the environment variable
//! `CI` is set, where it fails. Run it alone with `cargo test -p host-sim --test qemu_frame`.

// demo-scene's source as a module of this test: host-sim cannot depend on the crate (with the
// root workspace's `members = [".", ...]`, `exclude = ["boards"]` does not apply to path
// dependencies, and demo-scene, a workspace root itself, is refused as a member).
#[allow(dead_code, unused_attributes, unused_imports, unexpected_cfgs)]
#[path = "../../boards/demo-scene/src/lib.rs"]
mod demo_scene;
#[path = "support/process.rs"]
mod process;
use process::{root, run};
#[allow(dead_code)]
#[path = "../../boards/qemu-frame/src/scene.rs"]
mod scene;

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode, Stdio};
use std::time::{Duration, Instant};

use arealight::raster::{Band, Rgb565};
use demo_scene::{Stage, BAND_PIXELS, BAND_ROWS, HEIGHT, WIDTH};

const TRIPLE: &str = "thumbv7em-none-eabihf";
/// The firmware's binary name.
const BIN: &str = "qemu-frame";
/// The clock the table's milliseconds assume (the STM32F411 firmware's).
const MHZ: f64 = 100.0;

/// One frame in one mode, as the firmware reported it or as the host rendered it.
#[derive(Default)]
struct Frame {
    /// The pixels of each band, by its first row.
    bands: BTreeMap<u16, Vec<u16>>,
    /// Instructions per `Stage` (indexed by `Stage as usize`), their sum, and the whole call.
    ticks: [u32; 5],
    total: u32,
    call: u32,
    /// Shader calls, pixels written, triangle setups.
    stats: [u32; 3],
}

/// What the firmware printed: the frames by (mode, frame number), the self-check's pairs, the
/// stack used and its size.
#[derive(Default)]
struct Output {
    frames: BTreeMap<(String, u32), Frame>,
    selfcheck: Vec<(String, u32)>,
    stack: Option<(u32, u32)>,
    /// The unit-cost calibration's lines (`demo_scene::calibrate`): CSV rows
    /// `item,count,setups,calls,ticks`.
    costs: Vec<String>,
}

/// Builds the firmware (release) into `target_dir`; the ELF's path.
fn build(target_dir: &Path, features: &[&str]) -> Result<PathBuf, String> {
    let mut cmd = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()));
    cmd.current_dir(root().join("boards/qemu-frame")).args([
        "build",
        "--quiet",
        "--release",
        "--target",
        TRIPLE,
    ]);
    for f in features {
        cmd.args(["--features", f]);
    }
    cmd.arg("--target-dir")
        .arg(target_dir)
        .env_remove("RUSTFLAGS")
        .env_remove("CARGO_ENCODED_RUSTFLAGS")
        .env_remove("CARGO_BUILD_TARGET")
        .env_remove("CARGO_TARGET_DIR");
    run(&mut cmd, Duration::from_secs(900), |l| !l.starts_with("B ")).map_err(|e| {
        format!("building boards/qemu-frame (is the rustup target {TRIPLE} installed?): {e}")
    })?;
    Ok(target_dir.join(TRIPLE).join("release").join(BIN))
}

fn qemu(elf: &Path) -> Result<String, String> {
    let mut cmd = Command::new("qemu-system-arm");
    cmd.args(["-machine", "netduinoplus2", "-nographic"])
        .args(["-monitor", "none", "-serial", "none"])
        .args(["-semihosting-config", "enable=on,target=native"])
        .args(["-icount", "shift=0,align=off,sleep=off"])
        .arg("-kernel")
        .arg(elf)
        .stdin(Stdio::null());
    run(&mut cmd, Duration::from_secs(600), |l| !l.starts_with("B "))
}

fn qemu_version() -> String {
    Command::new("qemu-system-arm")
        .arg("--version")
        .output()
        .ok()
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .and_then(|s| s.lines().next().map(str::to_owned))
        .unwrap_or_else(|| "qemu-system-arm not found".into())
}

fn parse(text: &str) -> Result<Output, String> {
    let mut out = Output::default();
    let mut done = false;
    for l in text.lines() {
        let f: Vec<&str> = l.split_whitespace().collect();
        let num = |i: usize| -> Result<u32, String> {
            f.get(i)
                .ok_or_else(|| format!("{l}: field {i} missing"))?
                .parse()
                .map_err(|e| format!("{l}: {e}"))
        };
        let key = |f: &[&str]| -> Result<(String, u32), String> { Ok((f[1].to_owned(), num(2)?)) };
        match f.first().copied() {
            Some("B") if f.len() == 5 => {
                let hex = f[4].as_bytes();
                if hex.len() != 4 * BAND_PIXELS {
                    return Err(format!(
                        "B {} {} {}: {} hex digits",
                        f[1],
                        f[2],
                        f[3],
                        hex.len()
                    ));
                }
                let pixels = hex
                    .chunks(4)
                    .map(|h| {
                        std::str::from_utf8(h)
                            .ok()
                            .and_then(|h| u16::from_str_radix(h, 16).ok())
                    })
                    .collect::<Option<Vec<u16>>>()
                    .ok_or_else(|| format!("B {} {} {}: not hex", f[1], f[2], f[3]))?;
                let y0 = u16::try_from(num(3)?).map_err(|e| e.to_string())?;
                let frame = out.frames.entry(key(&f)?).or_default();
                if frame.bands.insert(y0, pixels).is_some() {
                    return Err(format!("band {} {} {y0} printed twice", f[1], f[2]));
                }
            }
            Some("CALL") if f.len() == 4 => out.frames.entry(key(&f)?).or_default().call = num(3)?,
            Some("FRAME") if f.len() == 12 => {
                let frame = out.frames.entry(key(&f)?).or_default();
                frame.total = num(3)?;
                for (i, t) in frame.ticks.iter_mut().enumerate() {
                    *t = num(4 + i)?;
                }
                for (i, s) in frame.stats.iter_mut().enumerate() {
                    *s = num(9 + i)?;
                }
            }
            Some("SELF") => {
                out.selfcheck = f[1..]
                    .iter()
                    .filter_map(|kv| {
                        let (k, v) = kv.split_once('=')?;
                        Some((k.to_owned(), v.parse().ok()?))
                    })
                    .collect();
            }
            Some("COST") if f.len() == 6 => {
                for i in 2..6 {
                    num(i)?;
                }
                out.costs.push(f[1..].join(","));
            }
            Some("STACK") if f.len() == 3 => out.stack = Some((num(1)?, num(2)?)),
            Some("FAIL") => return Err(format!("the firmware failed: {l}")),
            Some("DONE") => done = true,
            _ => {}
        }
    }
    if !done {
        return Err("the firmware did not print DONE".into());
    }
    Ok(out)
}

/// The counter self-check, from the firmware's numbers: `base` is the two TIM2 loads alone,
/// `n<N>` the same loads around N iterations of `subs`/`bne`; each must be exactly `base + 2N`.
fn check_counter(s: &[(String, u32)]) -> Result<String, String> {
    let base = s.iter().find(|(k, _)| k == "base").map(|kv| kv.1);
    let loops: Vec<(u32, u32)> = s
        .iter()
        .filter_map(|(k, v)| Some((k.strip_prefix('n')?.parse().ok()?, *v)))
        .collect();
    match base {
        Some(b)
            if (1..=2).contains(&b)
                && loops.iter().any(|&(n, _)| n >= 1000)
                && loops.iter().all(|&(n, c)| c == b + 2 * n) =>
        {
            Ok(format!(
                "loads alone {b}, every loop of n iterations exactly 2n + {b}"
            ))
        }
        _ => Err(format!(
            "counter self-check FAILED ({s:?}): TIM2 does not count executed instructions \
             exactly on this QEMU ({}), so no count can be trusted",
            qemu_version()
        )),
    }
}

/// Every frame of every mode rendered on the host, exactly as the firmware renders them (the
/// same storage reused across the modes, the same order), with a clock that never moves.
fn host_frames() -> Result<BTreeMap<(String, u32), Frame>, String> {
    let mut frames = BTreeMap::new();
    let mut storage = Box::new(scene::Storage::new());
    let (mut pixels, mut depth) = ([Rgb565(0); BAND_PIXELS], [0u16; BAND_PIXELS]);
    let mut band = Band::new(&mut pixels, Some(&mut depth), WIDTH, 0)
        .map_err(|e| format!("Band::new: {e:?}"))?;
    for (mode, shading) in scene::MODES {
        let mut demo = scene::demo(&mut storage, shading).map_err(|e| format!("{mode}: {e:?}"))?;
        for n in scene::FRAMES {
            let mut frame = Frame::default();
            let report = scene::render(&mut demo, n, &mut band, &mut || 0, |b| {
                let px = b.pixels().iter().map(|p| p.0).collect();
                frame.bands.insert(b.y0(), px);
                Ok::<(), std::convert::Infallible>(())
            })
            .map_err(|e| format!("{mode} frame {n}: {e:?}"))?;
            let s = report.stats;
            frame.stats = [s.shaded, s.pixels, s.rasterized];
            frames.insert((mode.to_owned(), n), frame);
        }
    }
    Ok(frames)
}

/// Checks one frame of the firmware against the host's: every band bit for bit, the statistics,
/// the stage sum. The number of pixels that differ, or why the frame is unusable.
fn compare(name: &str, target: &Frame, host: &Frame) -> Result<usize, String> {
    let bands = usize::from(HEIGHT.div_ceil(BAND_ROWS));
    if target.bands.len() != bands || target.bands.keys().ne(host.bands.keys()) {
        return Err(format!(
            "{name}: bands at rows {:?}, the host's at {:?}",
            target.bands.keys().collect::<Vec<_>>(),
            host.bands.keys().collect::<Vec<_>>()
        ));
    }
    let sum = target.ticks.iter().fold(0u32, |a, &t| a.wrapping_add(t));
    if sum != target.total || target.total == 0 {
        return Err(format!(
            "{name}: total {} but stages sum to {sum}",
            target.total
        ));
    }
    if target.stats != host.stats {
        return Err(format!(
            "{name}: shader calls, pixels, triangle setups {:?} on the target, {:?} on the host",
            target.stats, host.stats
        ));
    }
    let mut differ = 0;
    for (y0, t) in &target.bands {
        let h = &host.bands[y0];
        for (i, (a, b)) in t.iter().zip(h).enumerate() {
            if a != b {
                if differ < 5 {
                    let (x, y) = (
                        i % usize::from(WIDTH),
                        usize::from(*y0) + i / usize::from(WIDTH),
                    );
                    eprintln!("{name}: pixel ({x}, {y}): target {a:04x}, host {b:04x}");
                }
                differ += 1;
            }
        }
    }
    Ok(differ)
}

/// The markdown table and the CSV of the counts.
/// The frames' markdown table and CSV, in the order of `keys` (mode, frame number).
fn tables(frames: &BTreeMap<(String, u32), Frame>, keys: &[(String, u32)]) -> (String, String) {
    let names: Vec<&str> = Stage::ALL.iter().map(|s| s.name()).collect();
    let mut md = format!(
        "| mode | frame | total | {} | whole call | shader calls | pixels | triangle setups | ms at {MHZ} MHz, 1 instruction/cycle |\n",
        names.join(" | ")
    );
    md.push_str(&"|---".repeat(names.len() + 8));
    md.push_str("|\n");
    let mut csv = format!(
        "mode,frame,total,{},call,shader_calls,pixels,triangle_setups\n",
        names.join(",")
    );
    for (mode, n) in keys {
        {
            let Some(f) = frames.get(&(mode.clone(), *n)) else {
                continue;
            };
            let ticks: Vec<String> = f.ticks.iter().map(u32::to_string).collect();
            let [shaded, pixels, setups] = f.stats;
            let ms = f64::from(f.total) / (MHZ * 1e3);
            let _ = writeln!(
                md,
                "| {mode} | {n} | {} | {} | {} | {shaded} | {pixels} | {setups} | {ms:.0} |",
                f.total,
                ticks.join(" | "),
                f.call
            );
            let _ = writeln!(
                csv,
                "{mode},{n},{},{},{},{shaded},{pixels},{setups}",
                f.total,
                ticks.join(","),
                f.call
            );
        }
    }
    (md, csv)
}

/// Builds, runs, checks; the markdown table, or every failure.
fn check(out_dir: &Path) -> Result<String, Vec<String>> {
    let fail = |e: String| vec![e];
    let start = Instant::now();
    let elf = build(&out_dir.join("build"), &[]).map_err(fail)?;
    let built = start.elapsed();
    let start = Instant::now();
    let text = qemu(&elf).map_err(fail)?;
    let ran = start.elapsed();
    println!(
        "qemu_frame: build {:.1} s, QEMU {:.1} s (host time; {} bytes of output)",
        built.as_secs_f64(),
        ran.as_secs_f64(),
        text.len()
    );
    let out = parse(&text).map_err(fail)?;
    println!("counter: {}", check_counter(&out.selfcheck).map_err(fail)?);
    if let Some((used, size)) = out.stack {
        println!("stack: {used} of {size} bytes used");
    }
    let host = host_frames().map_err(fail)?;
    let mut failed = Vec::new();
    for ((mode, n), h) in &host {
        let name = format!("{mode} frame {n}");
        match out.frames.get(&(mode.clone(), *n)) {
            None => failed.push(format!("{name}: not printed by the firmware")),
            Some(t) => match compare(&name, t, h) {
                Ok(0) => println!(
                    "{name}: all {} bands bit-identical to the host",
                    t.bands.len()
                ),
                Ok(d) => failed.push(format!(
                    "{name}: {d} of {} pixels differ from the host's (f32 on the M4F and on \
                     the host should agree bit for bit)",
                    u32::from(WIDTH) * u32::from(HEIGHT)
                )),
                Err(e) => failed.push(e),
            },
        }
    }
    // In the firmware's order: modes as listed, then frames.
    let keys: Vec<(String, u32)> = scene::MODES
        .iter()
        .flat_map(|(m, _)| scene::FRAMES.iter().map(|&n| ((*m).to_owned(), n)))
        .collect();
    let (md, csv) = tables(&out.frames, &keys);
    if out.costs.is_empty() {
        failed.push("no COST lines (the calibration did not run)".into());
    }
    let costs = format!("item,count,setups,calls,ticks\n{}\n", out.costs.join("\n"));
    let written = std::fs::create_dir_all(out_dir)
        .and_then(|()| std::fs::write(out_dir.join("frames.md"), &md))
        .and_then(|()| std::fs::write(out_dir.join("frames.csv"), &csv))
        .and_then(|()| std::fs::write(out_dir.join("calibration.csv"), &costs));
    if let Err(e) = written {
        failed.push(format!("writing {}: {e}", out_dir.display()));
    }
    if failed.is_empty() {
        Ok(md)
    } else {
        println!("\n{md}");
        Err(failed)
    }
}

/// The scene files' frames (the firmware built with its feature `scene-file`: frame 0 of each
/// scene of `demo_scene::scenes`), written to `scenes.md` and `scenes.csv` (modes
/// `scene:<name>`) for `host-sim budget --check`, which compares them with its predictions
/// and requires the host's counts. The markdown table, or the failure.
fn check_scenes(out_dir: &Path) -> Result<String, String> {
    // The same target directory as the demo's build (its dependencies are reused; the ELF
    // is overwritten after the demo's has run).
    let elf = build(&out_dir.join("build"), &["scene-file"])?;
    let out = parse(&qemu(&elf)?)?;
    check_counter(&out.selfcheck)?;
    let keys: Vec<(String, u32)> = out.frames.keys().cloned().collect();
    if keys.len() < 2
        || keys
            .iter()
            .any(|(m, n)| !m.starts_with("scene:") || *n != 0)
    {
        return Err(format!(
            "the scene-file firmware printed the frames {keys:?}: expected frame 0 of at least two scene:<name> modes"
        ));
    }
    let (md, csv) = tables(&out.frames, &keys);
    std::fs::write(out_dir.join("scenes.md"), &md)
        .and_then(|()| std::fs::write(out_dir.join("scenes.csv"), &csv))
        .map_err(|e| format!("writing {}: {e}", out_dir.display()))?;
    Ok(md)
}

fn main() -> ExitCode {
    // `cargo test -- --list` and filters from a plain `cargo test NAME` must not run QEMU.
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.iter().any(|a| a == "--list") {
        println!("qemu_frame: test");
        return ExitCode::SUCCESS;
    }
    if let Some(filter) = args.iter().find(|a| !a.starts_with('-')) {
        if !"qemu_frame".contains(filter.as_str()) {
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
            eprintln!("qemu_frame: FAILED: qemu-system-arm is not installed (CI is set; .ci/run installs it)");
            return ExitCode::FAILURE;
        }
        println!("\n*** qemu_frame SKIPPED: qemu-system-arm is not installed ***");
        println!("*** (apt-get install -y qemu-system-arm; .ci/run does, and there this test fails instead) ***\n");
        println!("0 passed, 0 failed, 1 skipped");
        return ExitCode::SUCCESS;
    }
    println!("qemu_frame: {}", qemu_version());
    let out_dir = root().join("target/qemu-frame");
    let checked = check(&out_dir).and_then(|md| {
        let scenes = check_scenes(&out_dir).map_err(|e| vec![e])?;
        println!("\ninstructions per stage of the scene files' frame 0 (boards/demo-scene's spec player, f32)\n\n{scenes}");
        Ok(md)
    });
    match checked {
        Ok(md) => {
            println!(
                "\ninstructions per stage of the demo frame (exact, QEMU icount; f32 on the \
                 Cortex-M4F; ms: a lower bound at {MHZ} MHz)\n\n{md}"
            );
            println!(
                "wrote {}/frames.md, frames.csv, calibration.csv, scenes.md and scenes.csv",
                out_dir.display()
            );
            println!("1 passed, 0 failed");
            ExitCode::SUCCESS
        }
        Err(failed) => {
            eprintln!("\nqemu_frame FAILED:\n{}", failed.join("\n"));
            println!("0 passed, 1 failed");
            ExitCode::FAILURE
        }
    }
}
