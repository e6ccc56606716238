//! `host-sim`: the host side of arealight.
//!
//! - `host-sim eval --backend f64|f32|f32-fast|fixed`: the eval protocol
//!   (`shared/spec/eval-protocol.md`), JSON Lines from stdin to stdout.
//! - `host-sim render [--out DIR]` (the default with no arguments): a contact sheet of shaded
//!   spheres, one per model, written to `DIR/contact_sheet.png`.

mod eval;
mod render;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Host simulation for arealight: evaluate models, render them.
///
/// With no subcommand, runs `render` with its defaults.
#[derive(Parser, Debug)]
#[command(name = "host-sim", version, about, long_about)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Evaluate models from JSON Lines on stdin (the eval protocol).
    ///
    /// Reads one JSON object per line ({"id": ..., "model": ..., parameters}) and writes one
    /// JSON line per input line to stdout, in the same order: {"id", "value"}, {"id", "rgb"}
    /// or {"id", "error"}. The strings "NaN", "Infinity" and "-Infinity" stand for those
    /// numbers (and are refused as invalid input). Blank lines are skipped (no output line).
    /// A line that is not valid JSON gets an error with "id": null. Always exits 0 unless
    /// reading or writing fails.
    Eval(eval::EvalArgs),
    /// Render a contact sheet of shaded spheres, one per model (the default subcommand).
    ///
    /// Shades a unit sphere per model in f32 under a light up-left-front of it, labels each
    /// tile with the model id and its peak value, and writes DIR/contact_sheet.png; prints
    /// the path written.
    Render(render::RenderArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Some(Command::Eval(args)) => eval::main(&args),
        Some(Command::Render(args)) => render::main(&args),
        None => render::main(&render::RenderArgs { out: "out".into() }),
    }
}
