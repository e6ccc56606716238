//! What `host-sim budget --scene` writes: the table, the answer, the CSV and the plot of frame
//! time against image error.

use super::*;

pub(super) fn mega(x: f64) -> String {
    format!("{:.2} M", x / 1e6)
}

/// The table (markdown) and a recommendation.
pub fn markdown(b: &Budget, fps: Option<f64>, max_error: Option<f64>) -> String {
    let c = b.chip;
    let mut s = String::new();
    let _ = writeln!(s, "Scene `{}` on `{}`: {}.", b.scene, c.name, c.what);
    let _ = writeln!(
        s,
        "Predicted {} per frame by stage (counted work times the unit costs of `host-sim/costs.csv`), ms at {} MHz; image error against the f64 per-pixel frame, per pixel, in 8-bit levels (largest channel). * = on the Pareto front (time against mean error); d = some costs derived from the QEMU budget's counts, not calibrated on this chip.\n",
        c.unit, c.mhz
    );
    let _ = writeln!(s, "| backend | shading | transform | shade | raster | flush | frame | ms | fps | max error | mean error | |");
    let _ = writeln!(
        s,
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"
    );
    for r in &b.rows {
        let p = &r.predicted;
        let _ = writeln!(
            s,
            "| {}{} | {} | {} | {} | {} | {} | {} | {:.1} | {:.1} | {:.0} | {:.2} | {} |",
            r.backend,
            if r.derived { " (d)" } else { "" },
            r.shading,
            mega(p.transform),
            mega(p.shade),
            mega(p.raster),
            mega(p.flush),
            mega(p.total()),
            r.ms,
            1000.0 / r.ms.max(1e-9),
            r.max_err,
            r.mean_err,
            if r.pareto { "*" } else { "" }
        );
    }
    for k in &b.skipped {
        let _ = writeln!(s, "\n{}: not possible: {}", k.backend, k.why);
    }
    let _ = writeln!(s);
    s.push_str(&answer(b, fps, max_error));
    s
}

/// The answer to `--fps` and `--max-error`: the recommended option, or what misses and by how
/// much.
pub fn answer(b: &Budget, fps: Option<f64>, max_error: Option<f64>) -> String {
    let mut s = String::new();
    if let Some(r) = b
        .rows
        .iter()
        .find(|r| r.tessellation == 1.0 && r.shading.ends_with("(as written)"))
    {
        let _ = writeln!(
            s,
            "As written (the file's shading and meshes, {} on this chip): {:.1} ms ({:.1} fps), mean error {:.2}, max {:.0} levels.\n",
            r.backend,
            r.ms,
            1000.0 / r.ms,
            r.mean_err,
            r.max_err
        );
    }
    let want = match (fps, max_error) {
        (None, None) => "the fastest option".to_owned(),
        (Some(f), None) => format!("{f} fps"),
        (None, Some(e)) => format!("a mean error of at most {e} levels"),
        (Some(f), Some(e)) => format!("{f} fps with a mean error of at most {e} levels"),
    };
    match recommend(&b.rows, fps, max_error) {
        Some(r) => {
            let _ = writeln!(
                s,
                "Recommended for {want}: {} with {}: {:.1} ms ({:.1} fps), mean error {:.2}, max {:.0} levels.",
                r.backend, r.shading, r.ms, 1000.0 / r.ms, r.mean_err, r.max_err
            );
        }
        None => {
            let fastest = b.rows.iter().min_by(|a, b| a.ms.total_cmp(&b.ms));
            let _ = write!(s, "Nothing meets {want}.");
            if let Some(r) = fastest {
                let _ = write!(
                    s,
                    " The fastest option, {} with {}, takes {:.1} ms ({:.1} fps)",
                    r.backend,
                    r.shading,
                    r.ms,
                    1000.0 / r.ms
                );
                if let Some(f) = fps {
                    let _ = write!(
                        s,
                        ": {:.1} times the {:.1} ms of {f} fps",
                        r.ms / (1000.0 / f),
                        1000.0 / f
                    );
                }
                let _ = write!(s, ", mean error {:.2} levels", r.mean_err);
                if let Some(e) = max_error {
                    let best = b
                        .rows
                        .iter()
                        .map(|r| r.mean_err)
                        .fold(f64::INFINITY, f64::min);
                    if best > e {
                        let _ = write!(s, "; the most accurate option's mean error is {best:.2} levels, above {e}");
                    }
                }
                let _ = writeln!(s, ".");
            }
        }
    }
    s
}

/// The rows as CSV.
pub fn csv(b: &Budget) -> String {
    let mut s = String::from("chip,backend,derived,shading,transform,shade,raster,flush,frame,unit,ms,max_err,mean_err,pareto,vertices,vertex_calls,pixel_calls,pixels,triangle_setups,bands\n");
    for r in &b.rows {
        let p = &r.predicted;
        let w = &r.work;
        let _ = writeln!(
            s,
            "{},{},{},\"{}\",{:.0},{:.0},{:.0},{:.0},{:.0},{},{:.3},{},{:.4},{},{},{},{},{},{},{}",
            b.chip.name,
            r.backend,
            r.derived,
            r.shading,
            p.transform,
            p.shade,
            p.raster,
            p.flush,
            p.total(),
            b.chip.unit,
            r.ms,
            r.max_err,
            r.mean_err,
            r.pareto,
            w.total(|o| o.vertices_lit + o.vertices_unlit),
            w.total(|o| o.vertex_calls),
            w.total(|o| o.pixel_calls),
            w.total(|o| o.pixels),
            w.total(|o| o.setups),
            w.bands
        );
    }
    s
}

/// Frame time (x, ms) against mean error (y), one dot per option, the Pareto front joined.
pub fn plot(b: &Budget) -> Result<Pixmap, String> {
    let w = 900u32;
    // The legend: one line per option (the numbers on the dots).
    let legend_h = 14 * b.rows.len() as u32 + 10;
    let h = 430 + legend_h;
    let mut pix = Pixmap::new(w, h).ok_or("plot size")?;
    pix.fill(tiny_skia::Color::from_rgba8(255, 255, 255, 255));
    let (x0, y0, pw, ph) = (70.0f32, 40.0f32, 780.0f32, 330.0f32);
    // Time on a log scale (options span three orders of magnitude), whole decades.
    let lo = b
        .rows
        .iter()
        .map(|r| r.ms)
        .fold(f64::INFINITY, f64::min)
        .max(1e-3);
    let hi = b.rows.iter().map(|r| r.ms).fold(lo * 10.0, f64::max);
    let (d0, d1) = (
        lo.log10().floor(),
        hi.log10().ceil().max(lo.log10().floor() + 1.0),
    );
    let max_e = b.rows.iter().map(|r| r.mean_err).fold(0.1, f64::max) * 1.15;
    let px = |ms: f64| x0 + ((ms.max(1e-3).log10() - d0) / (d1 - d0)) as f32 * pw;
    let py = |e: f64| y0 + ph - (e / max_e) as f32 * ph;
    let black = [0, 0, 0];
    let mut paint = Paint::default();
    paint.set_color_rgba8(0, 0, 0, 255);
    paint.anti_alias = true;
    let stroke = Stroke {
        width: 1.0,
        ..Stroke::default()
    };
    let mut axes = PathBuilder::new();
    axes.move_to(x0, y0);
    axes.line_to(x0, y0 + ph);
    axes.line_to(x0 + pw, y0 + ph);
    if let Some(p) = axes.finish() {
        pix.stroke_path(&p, &paint, &stroke, Transform::identity(), None);
    }
    let title = format!(
        "{} on {}: frame time against image error",
        b.scene, b.chip.name
    );
    figure::text(&mut pix, &title, x0 as i32, 10, black, Font::Big);
    for d in (d0 as i32)..=(d1 as i32) {
        let ms = 10f64.powi(d);
        figure::text(
            &mut pix,
            &format!("{ms}"),
            px(ms) as i32 - 10,
            (y0 + ph) as i32 + 6,
            black,
            Font::Small,
        );
    }
    for k in 0..=4 {
        let e = max_e * f64::from(k) / 4.0;
        figure::text(
            &mut pix,
            &format!("{e:.2}"),
            30,
            py(e) as i32 - 5,
            black,
            Font::Small,
        );
    }
    figure::text(
        &mut pix,
        &format!("predicted ms per frame at {} MHz (log scale)", b.chip.mhz),
        (x0 + pw / 2.0) as i32 - 110,
        (y0 + ph) as i32 + 22,
        black,
        Font::Small,
    );
    figure::text(
        &mut pix,
        "mean error, 8-bit levels",
        4,
        24,
        black,
        Font::Small,
    );
    let mut front: Vec<&Row> = b.rows.iter().filter(|r| r.pareto).collect();
    front.sort_by(|a, b| a.ms.total_cmp(&b.ms));
    let mut line = PathBuilder::new();
    for (i, r) in front.iter().enumerate() {
        if i == 0 {
            line.move_to(px(r.ms), py(r.mean_err));
        } else {
            line.line_to(px(r.ms), py(r.mean_err));
        }
    }
    paint.set_color_rgba8(180, 180, 180, 255);
    if let Some(p) = line.finish() {
        pix.stroke_path(&p, &paint, &stroke, Transform::identity(), None);
    }
    let colour = |backend: &str| match backend {
        "fixed" => (200u8, 60u8, 40u8),
        "f32" => (40, 90, 200),
        _ => (40, 150, 80),
    };
    for (i, r) in b.rows.iter().enumerate() {
        let (cr, cg, cb) = colour(r.backend);
        paint.set_color_rgba8(cr, cg, cb, 255);
        if let Some(c) =
            PathBuilder::from_circle(px(r.ms), py(r.mean_err), if r.pareto { 5.0 } else { 3.5 })
        {
            pix.fill_path(
                &c,
                &paint,
                tiny_skia::FillRule::Winding,
                Transform::identity(),
                None,
            );
        }
        // Labels by index (the legend below says which is which), staggered against overlap.
        let dy = if i % 2 == 0 { -14 } else { 6 };
        figure::text(
            &mut pix,
            &format!("{}", i + 1),
            px(r.ms) as i32 + 6,
            py(r.mean_err) as i32 + dy,
            [cr, cg, cb],
            Font::Small,
        );
    }
    let mut y = (y0 + ph) as i32 + 40;
    for (i, r) in b.rows.iter().enumerate() {
        let (cr, cg, cb) = colour(r.backend);
        let label = format!(
            "{:>2} {}{}: {}: {:.1} ms, mean error {:.2}",
            i + 1,
            r.backend,
            if r.pareto { " (Pareto front)" } else { "" },
            r.shading,
            r.ms,
            r.mean_err
        );
        figure::text(&mut pix, &label, 10, y, [cr, cg, cb], Font::Small);
        y += 14;
    }
    Ok(pix)
}
