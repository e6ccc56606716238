//! `host-sim`: the host side of arealight.
//!
//! - `host-sim eval --backend f64|f32|f32-fast|fixed`: the eval protocol
//!   (`docs/eval-protocol.md`; the models in `docs/models.md`), JSON Lines from stdin to
//!   stdout; `host-sim eval --list-models` lists the model ids and their parameters.
//! - `host-sim render [--out DIR] [--only NAMES] [--scene FILE]` (the default with no
//!   arguments): the contact sheet, the documents' figures rendered with the crate's
//!   rasterizer, and the backend comparison sheets, as PNG files in `DIR` (default `out/`);
//!   or a TOML scene file (`docs/scene-format.md`).
//! - `host-sim plot [--out DIR]`: Snyder's figures 2 to 6 as line plots.
//! - `host-sim budget [--out DIR]`: the accuracy/cost budget (budget.md, budget.csv,
//!   budget.png), with the QEMU harness's instruction counts where present.

mod budget;
mod compare;
mod eval;
mod figure;
mod plot;
mod render;
mod scene_budget;
mod scene_file;
mod scenes;

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
    /// Reads one JSON object per line, {"id": ..., "model": ..., and the model's parameters},
    /// and writes one JSON line per input line to stdout, in the same order: {"id", "value"},
    /// {"id", "rgb"} or {"id", "error"}. --list-models prints the model ids and their
    /// parameters. The strings "NaN", "Infinity" and "-Infinity" stand for those numbers (and
    /// are refused as invalid input). Blank lines are skipped (no output line). A line that
    /// is not valid JSON, is not an object or has no id gets an error that starts with its
    /// input line number (and "id": null unless an id could be read); unknown or missing
    /// parameters are errors on their line. The exit status is 0 unless reading or writing
    /// fails, even when some lines got an error (the protocol's rule); then one summary line
    /// goes to stderr. Full description: docs/eval-protocol.md; the models: docs/models.md.
    Eval(eval::EvalArgs),
    /// Render the pictures (the default subcommand): the contact sheet and every figure.
    ///
    /// Writes into DIR (default out/): contact_sheet.png (one shaded sphere per model, f32);
    /// the documents' figures rendered with the crate's own rasterizer and models:
    /// snyder_fig7.png (directional, positional, overcast sky, sphere and polygon light on one
    /// scene), june_fig20_3.png (sky/ground), june_fig20_9.png (SH9 disc light, Grace
    /// Cathedral), june_fig20_17.png (uberlight), arvo_fig5.png (directional luminaire, glossy
    /// reflection), arvo_fig8.png (frosted glass), picott_plates.png (point, linear and area
    /// light); and compare_polygon.png, compare_sphere.png (the same frame in f64, f32,
    /// f32-fast and fixed point with error heat maps). Prints each path written, one per line.
    /// With --scene FILE renders a TOML scene file instead (docs/scene-format.md).
    Render(render::RenderArgs),
    /// Plot Snyder's figures 2 to 6 (intensity against omega) as PNG line plots.
    ///
    /// Writes DIR/snyder_fig2.png ... snyder_fig6.png (default out/), computed with the
    /// crate's f64 models; prints each path written.
    Plot(plot::PlotArgs),
    /// Write the accuracy/cost budget: DIR/budget.md, budget.csv and budget.png.
    ///
    /// One row per model id and backend (host ns per call, M4F and M0 instructions per call and
    /// code bytes from target/qemu-budget/counts.csv, max and RMS error against f64), beside
    /// the alternatives: point lights and each area light by k = 1, 4, 16, 64 point samples.
    /// Run `cargo test -p host-sim --test qemu_budget` first for the target columns.
    Budget(budget::BudgetArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Some(Command::Eval(args)) => eval::main(&args),
        Some(Command::Render(args)) => render::main(&args),
        Some(Command::Plot(args)) => plot::main(&args),
        Some(Command::Budget(args)) => budget::main(&args),
        None => render::main(&render::RenderArgs::default()),
    }
}
