//! `budget.png`: host time and instruction counts against max error, log-log, one panel per
//! cost measure, with each panel's Pareto front (drawn with tiny-skia).

use tiny_skia::{Color, Paint, PathBuilder, Pixmap, Rect, Stroke, Transform};

use super::{pareto_by, Kind, Row};

/// Draws `s` (small font) with its top-left corner at `(x, y)`.
fn text(pix: &mut Pixmap, s: &str, x: f32, y: f32, c: [u8; 3]) {
    crate::figure::text(pix, s, x as i32, y as i32, c, crate::figure::Font::Small);
}

fn paint(c: [u8; 3]) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color(Color::from_rgba8(c[0], c[1], c[2], 255));
    p.anti_alias = true;
    p
}

fn colour(k: Kind) -> [u8; 3] {
    match k {
        Kind::F32 => [90, 160, 255],
        Kind::Fast => [255, 150, 60],
        Kind::Fixed => [120, 220, 120],
        Kind::Point => [240, 220, 90],
        Kind::Sampled => [235, 90, 200],
    }
}

/// The smallest error drawn (smaller errors sit on the bottom edge).
const ERR_FLOOR: f64 = 1e-9;

type Stroker<'a> = dyn Fn(&mut Pixmap, (f32, f32), (f32, f32), &Paint, &Stroke) + 'a;

fn draw_line(pix: &mut Pixmap, a: (f32, f32), b: (f32, f32), p: &Paint, st: &Stroke) {
    let mut pb = PathBuilder::new();
    pb.move_to(a.0, a.1);
    pb.line_to(b.0, b.1);
    if let Some(path) = pb.finish() {
        pix.stroke_path(&path, p, st, Transform::identity(), None);
    }
}

fn dot(pix: &mut Pixmap, x: f32, y: f32, r: f32, c: [u8; 3]) {
    if let Some(path) = PathBuilder::from_circle(x, y, r) {
        pix.fill_path(
            &path,
            &paint(c),
            tiny_skia::FillRule::Winding,
            Transform::identity(),
            None,
        );
    }
}

/// One log-log panel: `x` of each row (rows without one are left out) against max error, in
/// the rectangle (x0, y0)-(x1, y1), with the Pareto front of that panel.
#[allow(clippy::too_many_arguments)]
fn panel(
    pix: &mut Pixmap,
    rows: &[Row],
    x: &dyn Fn(&Row) -> Option<f64>,
    title: &str,
    xlabel: &str,
    (x0, y0, x1, y1): (f32, f32, f32, f32),
    ymax: f64,
) {
    let line: &Stroker = &draw_line;
    let lx = |v: f64| v.max(1e-3).log10();
    let ly = |v: f64| v.max(ERR_FLOOR).log10();
    let xs: Vec<f64> = rows.iter().filter_map(x).map(lx).collect();
    let xmin = xs.iter().copied().fold(f64::MAX, f64::min).floor();
    let xmax = xs
        .iter()
        .copied()
        .fold(f64::MIN, f64::max)
        .ceil()
        .max(xmin + 1.0);
    let ymin = ly(ERR_FLOOR);
    let px = |v: f64| x0 + ((lx(v) - xmin) / (xmax - xmin)) as f32 * (x1 - x0);
    let py = |v: f64| y1 - ((ly(v) - ymin) / (ymax - ymin)) as f32 * (y1 - y0);
    let grid = paint([60, 60, 68]);
    let axis = paint([200, 200, 200]);
    let thin = Stroke {
        width: 1.0,
        ..Stroke::default()
    };
    let mut e = xmin;
    while e <= xmax + 1e-9 {
        let gx = px(10f64.powf(e));
        line(pix, (gx, y0), (gx, y1), &grid, &thin);
        text(
            pix,
            &format!("1e{e:.0}"),
            gx - 12.0,
            y1 + 6.0,
            [200, 200, 200],
        );
        e += 1.0;
    }
    let mut e = ymin;
    while e <= ymax + 1e-9 {
        let gy = py(10f64.powf(e));
        line(pix, (x0, gy), (x1, gy), &grid, &thin);
        let label = if e == ymin {
            format!("<=1e{e:.0}")
        } else {
            format!("1e{e:.0}")
        };
        text(pix, &label, x0 - 50.0, gy - 5.0, [200, 200, 200]);
        e += 1.0;
    }
    line(pix, (x0, y1), (x1, y1), &axis, &thin);
    line(pix, (x0, y0), (x0, y1), &axis, &thin);
    let w = xlabel.len() as f32 * 6.0;
    text(pix, xlabel, (x0 + x1 - w) / 2.0, y1 + 24.0, [230, 230, 230]);
    text(pix, title, x0, y0 - 18.0, [255, 255, 255]);
    // The Pareto front, as a staircase.
    let front = pareto_by(rows, x);
    let white = paint([255, 255, 255]);
    let wide = Stroke {
        width: 2.0,
        ..Stroke::default()
    };
    let at = |r: &Row| x(r).map(|v| (px(v), py(r.max_err)));
    for pair in front.windows(2) {
        if let (Some((ax, ay)), Some((bx, by))) = (at(&rows[pair[0]]), at(&rows[pair[1]])) {
            line(pix, (ax, ay), (bx, ay), &white, &wide);
            line(pix, (bx, ay), (bx, by), &white, &wide);
        }
    }
    let radius = |r: &Row| {
        if r.kind == Kind::Sampled {
            let k: f32 = r
                .backend
                .trim_start_matches("f32-pts")
                .parse()
                .unwrap_or(1.0);
            2.0 + k.log2() * 0.6
        } else {
            3.5
        }
    };
    let mut dots: Vec<(f32, f32, f32)> = Vec::new();
    for r in rows {
        let Some((cx, cy)) = at(r) else {
            continue;
        };
        let rad = radius(r);
        dot(pix, cx, cy, rad, colour(r.kind));
        dots.push((cx, cy, rad));
    }
    // The front's labels: each at the first free place around its point (clear of the other
    // labels and of every point, else of the labels only), on a dark box, with a leader line
    // when it sits away from its point.
    let mut placed: Vec<Rect> = Vec::new();
    let bounds = (x0, y0, x1, y1);
    for &i in &front {
        let r = &rows[i];
        let Some((cx, cy)) = at(r) else {
            continue;
        };
        let rad = radius(r);
        if let Some(c) = PathBuilder::from_circle(cx, cy, rad + 3.0) {
            pix.stroke_path(&c, &white, &thin, Transform::identity(), None);
        }
        let label = format!("{} {}", r.model, r.backend);
        let (lw, lh) = (label.len() as f32 * 6.0 + 4.0, 12.0);
        let Some((bx, by)) = place_label((cx, cy), rad, (lw, lh), bounds, &placed, &dots) else {
            continue;
        };
        let Some(rect) = Rect::from_xywh(bx, by, lw, lh) else {
            continue;
        };
        let near = (bx - (cx + rad + 4.0)).abs() < 1.0 && (by + lh / 2.0 - cy).abs() < 8.0;
        if !near {
            let lead = paint([170, 170, 175]);
            let tx = if bx > cx { bx } else { bx + lw };
            line(pix, (cx, cy), (tx, by + lh / 2.0), &lead, &thin);
        }
        pix.fill_rect(rect, &paint([24, 24, 28]), Transform::identity(), None);
        text(pix, &label, bx + 2.0, by + 1.0, [255, 255, 255]);
        placed.push(rect);
    }
}

/// `true` if the two rectangles overlap.
fn overlaps(a: &Rect, b: &Rect) -> bool {
    a.left() < b.right() && b.left() < a.right() && a.top() < b.bottom() && b.top() < a.bottom()
}

/// Where a `size` label for the point `p` (radius `rad`) goes: the top-left corner of the first
/// candidate (right of the point, then left, then further up and down on either side) inside
/// `bounds` that overlaps no `placed` label and no point of `dots`; failing that the first that
/// overlaps no label; `None` when every candidate overlaps a label.
fn place_label(
    p: (f32, f32),
    rad: f32,
    size: (f32, f32),
    bounds: (f32, f32, f32, f32),
    placed: &[Rect],
    dots: &[(f32, f32, f32)],
) -> Option<(f32, f32)> {
    let (cx, cy) = p;
    let (w, h) = size;
    let right = cx + rad + 4.0;
    let left = cx - rad - 4.0 - w;
    let mut candidates = Vec::new();
    for dy in [0.0f32, -14.0, 14.0, -28.0, 28.0, -42.0, 42.0, -56.0, 56.0] {
        candidates.push((right, cy - h / 2.0 + dy));
        candidates.push((left, cy - h / 2.0 + dy));
    }
    let rect = |&(x, y): &(f32, f32)| Rect::from_xywh(x, y, w, h);
    let inside = |r: &Rect| {
        r.left() >= bounds.0
            && r.top() >= bounds.1
            && r.right() <= bounds.2
            && r.bottom() <= bounds.3
    };
    let clear_of_labels = |r: &Rect| inside(r) && !placed.iter().any(|q| overlaps(r, q));
    let clear_of_dots = |r: &Rect| {
        !dots.iter().any(|&(x, y, d)| {
            Rect::from_xywh(x - d, y - d, 2.0 * d, 2.0 * d).is_some_and(|q| overlaps(r, &q))
        })
    };
    candidates
        .iter()
        .find(|c| rect(c).is_some_and(|r| clear_of_labels(&r) && clear_of_dots(&r)))
        .or_else(|| {
            candidates
                .iter()
                .find(|c| rect(c).is_some_and(|r| clear_of_labels(&r)))
        })
        .copied()
}

/// Draws the plot: max error against host time and, where the QEMU harness's counts are
/// present, against Cortex-M4F instructions; log-log, Pareto fronts in white.
pub fn plot(rows: &[Row]) -> Result<Pixmap, String> {
    let with_m4f = rows.iter().any(|r| r.m4f.is_some());
    let pw = 620.0f32;
    let w = if with_m4f {
        90.0 + 2.0 * pw + 90.0 + 230.0
    } else {
        90.0 + pw + 230.0
    };
    let h = 760.0f32;
    let mut pix = Pixmap::new(w as u32, h as u32).ok_or("pixmap")?;
    pix.fill(Color::from_rgba8(24, 24, 28, 255));
    let ymax = rows
        .iter()
        .map(|r| r.max_err.max(ERR_FLOOR).log10())
        .fold(-8.0f64, f64::max)
        .ceil();
    let (y0, y1) = (70.0f32, h - 70.0);
    text(
        &mut pix,
        "arealight budget: max abs error vs f64 (log) against cost (log); one point per model x backend",
        20.0,
        14.0,
        [230, 230, 230],
    );
    panel(
        &mut pix,
        rows,
        &|r| Some(r.host_ns),
        "host (x86-64), ns per call",
        "host ns per call (log)",
        (90.0, y0, 90.0 + pw, y1),
        ymax,
    );
    let mut lx = 90.0 + pw + 20.0;
    if with_m4f {
        let x0 = 90.0 + pw + 90.0;
        panel(
            &mut pix,
            rows,
            &|r| r.m4f.map(|n| n as f64),
            "Cortex-M4F (QEMU, exact), instructions per call",
            "M4F instructions per call (log)",
            (x0, y0, x0 + pw, y1),
            ymax,
        );
        lx = x0 + pw + 20.0;
    }
    let legend = [
        (Kind::F32, "analytic, f32 (libm)"),
        (Kind::Fast, "analytic, f32-fast"),
        (Kind::Fixed, "analytic, fixed (no M4F)"),
        (Kind::Point, "point light (cost floor)"),
        (Kind::Sampled, "k point samples (size ~ k)"),
    ];
    let mut ly0 = y0 + 10.0;
    for (k, label) in legend {
        if !rows.iter().any(|r| r.kind == k) {
            continue;
        }
        dot(&mut pix, lx + 10.0, ly0 + 5.0, 4.0, colour(k));
        text(&mut pix, label, lx + 20.0, ly0, [230, 230, 230]);
        ly0 += 18.0;
    }
    text(
        &mut pix,
        "white: Pareto front",
        lx + 20.0,
        ly0 + 6.0,
        [255, 255, 255],
    );
    if let Some(r) = Rect::from_xywh(lx, y0, 200.0, ly0 - y0 + 24.0) {
        let mut pb = PathBuilder::new();
        pb.push_rect(r);
        if let Some(p) = pb.finish() {
            pix.stroke_path(
                &p,
                &paint([60, 60, 68]),
                &Stroke::default(),
                Transform::identity(),
                None,
            );
        }
    }
    Ok(pix)
}
