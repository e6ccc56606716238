//! `host-sim plot`: Snyder's figures 2 to 6 as line plots (intensity against omega), computed
//! with the crate's f64 models and drawn with tiny-skia (axes, ticks, labels, legends).

use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use std::time::Instant;

use arealight::{CapLight, HemisphereLight, PhongLobe, Vec3};
use clap::Args;
use tiny_skia::{Color, Paint, PathBuilder, Pixmap, Rect, Stroke, StrokeDash, Transform};

use crate::figure::{self, text, text_width, Font};

/// Arguments of `host-sim plot`.
#[derive(Args, Debug)]
pub struct PlotArgs {
    /// Directory to write snyder_fig2.png ... snyder_fig6.png into (created if missing).
    #[arg(long, value_name = "DIR", default_value = crate::render::DEFAULT_OUT)]
    pub out: PathBuf,
}

/// One curve of a plot.
pub struct Curve {
    /// Legend text.
    pub label: String,
    /// Dashed (the reference curve of Snyder's figures) or solid.
    pub dashed: bool,
    /// Points `(omega, intensity)`.
    pub pts: Vec<(f64, f64)>,
}

/// One plot: title, y range, curves (x is omega in [0, pi]).
pub struct Plot {
    /// Title above the axes.
    pub title: String,
    /// y axis range.
    pub y: (f64, f64),
    /// The curves.
    pub curves: Vec<Curve>,
}

const COLOURS: [[u8; 3]; 6] = [
    [90, 160, 255],
    [255, 150, 60],
    [120, 220, 120],
    [235, 90, 200],
    [240, 220, 90],
    [200, 200, 200],
];

/// `omega` sampled on [0, pi].
fn omegas() -> impl Iterator<Item = f64> {
    (0..=360).map(|i| PI * i as f64 / 360.0)
}

/// A unit direction at angle `w` from +z.
fn dir(w: f64) -> Vec3<f64> {
    Vec3::new(w.sin(), 0.0, w.cos())
}

fn curve(label: String, dashed: bool, f: impl Fn(f64) -> f64) -> Curve {
    Curve {
        label,
        dashed,
        pts: omegas().map(|w| (w, f(w))).collect(),
    }
}

/// `num/den pi` in lowest terms, as Snyder writes it: `pi`, `pi/6`, `2pi/5`.
fn sigma_name(num: u32, den: u32) -> String {
    let g = gcd(num, den).max(1);
    match (num / g, den / g) {
        (1, 1) => "pi".into(),
        (1, d) => format!("pi/{d}"),
        (n, d) => format!("{n}pi/{d}"),
    }
}

fn gcd(a: u32, b: u32) -> u32 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

/// Draws `plot` into the rectangle `(x0, y0, w, h)` of `pix`.
pub fn draw(pix: &mut Pixmap, plot: &Plot, x0: f32, y0: f32, w: f32, h: f32) {
    let (l, r, t, b) = (x0 + 52.0, x0 + w - 12.0, y0 + 26.0, y0 + h - 36.0);
    let (ymin, ymax) = plot.y;
    let px = |x: f64| l + (r - l) * (x / PI) as f32;
    let py = |y: f64| b - (b - t) * ((y - ymin) / (ymax - ymin)) as f32;
    let mut paint = Paint {
        anti_alias: true,
        ..Paint::default()
    };
    // Frame and grid.
    paint.set_color_rgba8(55, 55, 62, 255);
    let grid = Stroke {
        width: 1.0,
        ..Stroke::default()
    };
    let mut pb = PathBuilder::new();
    for i in 0..=4 {
        let x = l + (r - l) * i as f32 / 4.0;
        pb.move_to(x, t);
        pb.line_to(x, b);
        let y = b - (b - t) * i as f32 / 4.0;
        pb.move_to(l, y);
        pb.line_to(r, y);
    }
    if let Some(path) = pb.finish() {
        pix.stroke_path(&path, &paint, &grid, Transform::identity(), None);
    }
    paint.set_color_rgba8(200, 200, 205, 255);
    if let Some(rect) = Rect::from_ltrb(l, t, r, b) {
        let path = PathBuilder::from_rect(rect);
        pix.stroke_path(&path, &paint, &grid, Transform::identity(), None);
    }
    // Ticks and their labels.
    let xt = ["0", "pi/4", "pi/2", "3pi/4", "pi"];
    for (i, s) in xt.iter().enumerate() {
        let x = l + (r - l) * i as f32 / 4.0;
        let mut pb = PathBuilder::new();
        pb.move_to(x, b);
        pb.line_to(x, b + 5.0);
        if let Some(path) = pb.finish() {
            pix.stroke_path(&path, &paint, &grid, Transform::identity(), None);
        }
        let tw = text_width(s, Font::Small);
        text(
            pix,
            s,
            x as i32 - tw / 2,
            b as i32 + 7,
            [200, 200, 205],
            Font::Small,
        );
    }
    for i in 0..=4 {
        let v = ymin + (ymax - ymin) * i as f64 / 4.0;
        let y = py(v);
        let mut pb = PathBuilder::new();
        pb.move_to(l - 5.0, y);
        pb.line_to(l, y);
        if let Some(path) = pb.finish() {
            pix.stroke_path(&path, &paint, &grid, Transform::identity(), None);
        }
        let s = format!("{v:.2}");
        text(
            pix,
            &s,
            l as i32 - 8 - text_width(&s, Font::Small),
            y as i32 - 5,
            [200, 200, 205],
            Font::Small,
        );
    }
    text(
        pix,
        "omega",
        ((l + r) / 2.0) as i32 - 15,
        b as i32 + 20,
        [170, 170, 180],
        Font::Small,
    );
    text(
        pix,
        "I",
        x0 as i32 + 4,
        ((t + b) / 2.0) as i32 - 5,
        [170, 170, 180],
        Font::Small,
    );
    text(
        pix,
        &plot.title,
        l as i32,
        y0 as i32 + 6,
        [235, 235, 235],
        Font::Small,
    );
    // Curves, then the legend on an opaque box over them (top right).
    let colour = |k: usize, c: &Curve| {
        if c.dashed {
            [230, 230, 230]
        } else {
            COLOURS[k % COLOURS.len()]
        }
    };
    let stroke_of = |c: &Curve| {
        let mut stroke = Stroke {
            width: 2.0,
            ..Stroke::default()
        };
        if c.dashed {
            stroke.width = 1.5;
            stroke.dash = StrokeDash::new(vec![6.0, 4.0], 0.0);
        }
        stroke
    };
    for (k, c) in plot.curves.iter().enumerate() {
        let col = colour(k, c);
        paint.set_color_rgba8(col[0], col[1], col[2], 255);
        let mut pb = PathBuilder::new();
        for (i, &(x, y)) in c.pts.iter().enumerate() {
            let (sx, sy) = (px(x), py(y.clamp(ymin, ymax)));
            if i == 0 {
                pb.move_to(sx, sy);
            } else {
                pb.line_to(sx, sy);
            }
        }
        if let Some(path) = pb.finish() {
            pix.stroke_path(&path, &paint, &stroke_of(c), Transform::identity(), None);
        }
    }
    let label_w = plot
        .curves
        .iter()
        .map(|c| text_width(&c.label, Font::Small))
        .max()
        .unwrap_or(0) as f32;
    let box_w = 22.0 + label_w + 8.0;
    let (bx, by) = (r - box_w - 4.0, t + 4.0);
    if let Some(rect) = Rect::from_xywh(bx, by, box_w, 13.0 * plot.curves.len() as f32 + 6.0) {
        paint.set_color_rgba8(figure::BG[0], figure::BG[1], figure::BG[2], 235);
        pix.fill_rect(rect, &paint, Transform::identity(), None);
        paint.set_color_rgba8(70, 70, 80, 255);
        let path = PathBuilder::from_rect(rect);
        pix.stroke_path(&path, &paint, &grid, Transform::identity(), None);
    }
    for (k, c) in plot.curves.iter().enumerate() {
        let col = colour(k, c);
        paint.set_color_rgba8(col[0], col[1], col[2], 255);
        let (lx, ly) = (bx + 4.0, by + 4.0 + 13.0 * k as f32);
        let mut pb = PathBuilder::new();
        pb.move_to(lx, ly + 5.0);
        pb.line_to(lx + 18.0, ly + 5.0);
        if let Some(path) = pb.finish() {
            pix.stroke_path(&path, &paint, &stroke_of(c), Transform::identity(), None);
        }
        text(pix, &c.label, lx as i32 + 22, ly as i32, col, Font::Small);
    }
}

/// A figure: a title and its plots in one row.
pub struct PlotFigure {
    /// File name.
    pub file: &'static str,
    /// Title.
    pub title: &'static str,
    /// The plots, left to right.
    pub plots: Vec<Plot>,
}

/// Renders a figure to a pixmap.
pub fn render_figure(f: &PlotFigure) -> Pixmap {
    let n = f.plots.len().max(1) as u32;
    let cols = if n == 4 { 2 } else { n.min(3) };
    let rows = n.div_ceil(cols);
    // Plots at least 380 wide, wider when the title needs the room (no text is cut).
    let title_w = text_width(f.title, Font::Big) as u32 + 20;
    let pw = 380u32.max((title_w.saturating_sub(20)).div_ceil(cols));
    let ph = 290u32;
    let mut pix = Pixmap::new(cols * pw + 20, rows * ph + 40).expect("positive size");
    pix.fill(Color::from_rgba8(
        figure::BG[0],
        figure::BG[1],
        figure::BG[2],
        255,
    ));
    text(&mut pix, f.title, 10, 8, [235, 235, 235], Font::Big);
    for (k, p) in f.plots.iter().enumerate() {
        let (c, r) = (k as u32 % cols, k as u32 / cols);
        draw(
            &mut pix,
            p,
            (10 + c * pw) as f32,
            (34 + r * ph) as f32,
            pw as f32,
            ph as f32,
        );
    }
    pix
}

/// Snyder's figures 2 to 6, computed with the crate's f64 models.
///
/// # Errors
/// A library refusal (not expected: the parameters are constants).
pub fn figures() -> Result<Vec<PlotFigure>, arealight::Error> {
    let z = Vec3::new(0.0, 0.0, 1.0);
    let cap = |num: u32, den: u32| CapLight::<f64>::new(z, PI * num as f64 / den as f64);
    let hemi = HemisphereLight::<f64>::new(z)?;

    // Fig. 2: normalized sub-hemispherical Lambert, sigma = pi/6, pi/3, pi/2.
    let mut fig2 = Vec::new();
    for (num, den) in [(1, 6), (1, 3), (1, 2)] {
        let l = cap(num, den)?;
        let s2 = l.sigma().sin().powi(2);
        fig2.push(curve(
            format!("s = {}", sigma_name(num, den)),
            false,
            move |w| l.lambert(dir(w)) / s2,
        ));
    }
    fig2.push(curve("max(0, cos w)".into(), true, |w| w.cos().max(0.0)));

    // Fig. 3: the two-segment Hermite approximation (solid) against the exact model (dashed).
    let mut fig3 = Vec::new();
    for (num, den) in [(1, 2), (1, 4), (1, 8)] {
        let l = cap(num, den)?;
        let s2 = l.sigma().sin().powi(2);
        fig3.push(Plot {
            title: format!("sigma = {}", sigma_name(num, den)),
            y: (0.0, 1.0),
            curves: vec![
                curve("hermite".into(), false, move |w| {
                    l.lambert_hermite(dir(w)) / s2
                }),
                curve("exact".into(), true, move |w| l.lambert(dir(w)) / s2),
            ],
        });
    }

    // Fig. 4: hemisphere Phong, constant (left) and cosine (right) weighted.
    let mut left = Vec::new();
    let mut right = Vec::new();
    for n in [1u32, 4, 16, 64] {
        let lobe = PhongLobe::<f64>::new(n)?;
        left.push(curve(format!("n = {n}"), n == 1, move |w| {
            hemi.phong_const(&lobe, dir(w))
        }));
        right.push(curve(format!("n = {n}"), n == 1, move |w| {
            hemi.phong_cos(&lobe, dir(w))
        }));
    }

    // Fig. 5: sub-hemispherical Phong, sigma = pi/6 (left) and 2pi/6 (right).
    let mut fig5 = Vec::new();
    for (num, den) in [(1, 6), (2, 6)] {
        let l = cap(num, den)?;
        let mut cs = Vec::new();
        for n in [1u32, 3, 15, 63] {
            let lobe = PhongLobe::<f64>::new(n)?;
            cs.push(curve(format!("n = {n}"), n == 1, move |w| {
                l.phong(&lobe, dir(w))
            }));
        }
        fig5.push(Plot {
            title: format!("sigma = {}", sigma_name(num, den)),
            y: (0.0, 1.0),
            curves: cs,
        });
    }

    // Fig. 6: normalized by the value at omega = 0, per exponent; sigma = 5/10 pi .. 1/10 pi.
    let mut fig6 = Vec::new();
    for n in [1u32, 3, 15, 63] {
        let lobe = PhongLobe::<f64>::new(n)?;
        let mut cs = Vec::new();
        for k in (1..=5).rev() {
            let l = cap(k, 10)?;
            let peak = l.phong(&lobe, z);
            cs.push(curve(
                format!("s = {}", sigma_name(k, 10)),
                k == 5,
                move |w| l.phong(&lobe, dir(w)) / peak,
            ));
        }
        fig6.push(Plot {
            title: format!("n = {n}"),
            y: (0.0, 1.0),
            curves: cs,
        });
    }

    Ok(vec![
        PlotFigure {
            file: "snyder_fig2.png",
            title: "Snyder, fig. 2: normalized sub-hemispherical illumination",
            plots: vec![Plot {
                title: "I_hemi-sub / sin^2(sigma) against omega".into(),
                y: (0.0, 1.0),
                curves: fig2,
            }],
        },
        PlotFigure {
            file: "snyder_fig3.png",
            title:
                "Snyder, fig. 3: approximate (two-segment Hermite) sub-hemispherical illumination",
            plots: fig3,
        },
        PlotFigure {
            file: "snyder_fig4.png",
            title: "Snyder, fig. 4: infinite hemisphere Phong illumination",
            plots: vec![
                Plot {
                    title: "constant-weighted".into(),
                    y: (0.0, 1.0),
                    curves: left,
                },
                Plot {
                    title: "cosine-weighted".into(),
                    y: (0.0, 1.0),
                    curves: right,
                },
            ],
        },
        PlotFigure {
            file: "snyder_fig5.png",
            title: "Snyder, fig. 5: sub-hemispherical Phong illumination",
            plots: fig5,
        },
        PlotFigure {
            file: "snyder_fig6.png",
            title: "Snyder, fig. 6: normalized sub-hemispherical Phong illumination",
            plots: fig6,
        },
    ])
}

/// Writes every plot into `out`; returns the paths.
///
/// # Errors
/// A message for a file that cannot be written.
pub fn plot(out: &Path) -> Result<Vec<PathBuf>, String> {
    let figs = figures().map_err(|e| format!("model refused: {e}"))?;
    figs.iter()
        .map(|f| figure::save(&render_figure(f), out, f.file))
        .collect()
}

/// `host-sim plot`: prints each path written.
pub fn main(args: &PlotArgs) -> std::process::ExitCode {
    let start = Instant::now();
    match plot(&args.out) {
        Ok(paths) => {
            for p in &paths {
                println!("{}", p.display());
            }
            eprintln!("plotted in {:.3} s", start.elapsed().as_secs_f64());
            std::process::ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("host-sim plot: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sigma_names_are_in_lowest_terms() {
        assert_eq!(sigma_name(1, 10), "pi/10");
        assert_eq!(sigma_name(5, 10), "pi/2");
        assert_eq!(sigma_name(4, 10), "2pi/5");
        assert_eq!(sigma_name(2, 6), "pi/3");
        assert_eq!(sigma_name(1, 1), "pi");
        assert_eq!(sigma_name(3, 10), "3pi/10");
    }

    #[test]
    fn figure_curves_match_snyders_stated_values() {
        let figs = figures().unwrap();
        assert_eq!(figs.len(), 5);
        // Fig. 2: every normalized curve is 1 at omega = 0; sigma = pi/2 is (1 + cos w)/2.
        let f2 = &figs[0].plots[0].curves;
        for c in &f2[..3] {
            assert!((c.pts[0].1 - 1.0).abs() < 1e-12);
        }
        for &(w, y) in &f2[2].pts {
            assert!((y - 0.5 * (1.0 + w.cos())).abs() < 1e-12);
        }
        // Fig. 6: normalized to 1 at omega = 0.
        for p in &figs[4].plots {
            for c in &p.curves {
                assert!((c.pts[0].1 - 1.0).abs() < 1e-12);
            }
        }
        // Fig. 5: I(0, sigma, n) = 1 - cos^(n+1) sigma (Snyder).
        for (p, s) in figs[3].plots.iter().zip([PI / 6.0, PI / 3.0]) {
            for (c, n) in p.curves.iter().zip([1, 3, 15, 63]) {
                assert!((c.pts[0].1 - (1.0 - s.cos().powi(n + 1))).abs() < 1e-12);
            }
        }
    }
}
