//! `--check`: the predictions against emulated frames (rp2040js cycles, QEMU instructions), the
//! host's counts against the firmware's.

use super::*;

/// An emulated frame `--check` compares with.
struct Measured {
    /// Which frame.
    label: String,
    /// The option, in `assignments`' words.
    plan: String,
    /// Its cost, in the chip's unit.
    units: f64,
    /// The firmware's counts: shader calls, pixels, triangle setups.
    counts: Option<[u64; 3]>,
}

/// The emulated frames of `path` for `chip` (frame 0 of each) that render the scene file named
/// `scene` (its stem): the demo firmware's frames for `demo`, the scene-file firmware's
/// (`scene:<name>`: `boards/demo-scene`'s spec player, the scene as written) for the others.
fn measured(path: &Path, chip: &Chip, scene: &str) -> Result<Vec<Measured>, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
    let col = |n: &str| header.iter().position(|h| *h == n);
    let mut out = Vec::new();
    let stages = ["setup", "transform", "shade", "raster", "flush", "wait"];
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        let get = |n: &str| col(n).and_then(|i| f.get(i)).copied();
        if get("frame") != Some("0") {
            continue;
        }
        // The firmware's own stage timing of frame 0 (the whole render_frame).
        let sum: f64 = stages
            .iter()
            .filter_map(|s| get(s).and_then(|x| x.parse::<f64>().ok()))
            .sum();
        let count = |n: &str| get(n).and_then(|x| x.parse::<u64>().ok());
        let counts = match (
            count("shader_calls"),
            count("pixels"),
            count("triangle_setups"),
        ) {
            (Some(a), Some(b), Some(c)) => Some([a, b, c]),
            _ => None,
        };
        let file = get("firmware")
            .or(get("mode"))
            .and_then(|m| m.strip_prefix("scene:"));
        if let Some(name) = file {
            let cores = get("cores")
                .and_then(|c| c.parse::<u32>().ok())
                .unwrap_or(1);
            if name == scene && cores == chip.cores {
                let units = get("total").and_then(|x| x.parse().ok()).unwrap_or(sum);
                out.push(Measured {
                    label: format!("scene-file firmware, {name} frame 0"),
                    plan: "as written".to_owned(),
                    units,
                    counts,
                });
            }
            continue;
        }
        if scene != "demo" {
            continue;
        }
        if let Some(fw) = get("firmware") {
            let want = if chip.cores > 1 {
                "lit_scene_dual_core"
            } else {
                "lit_scene"
            };
            if fw == want {
                out.push(Measured {
                    label: format!("{fw} frame 0"),
                    plan: "as written".to_owned(),
                    units: sum,
                    counts,
                });
            }
        } else if let Some(mode) = get("mode") {
            let plan = match mode {
                "gouraud" => "all Gouraud".to_owned(),
                "per_pixel" => "all per pixel".to_owned(),
                m => match m.strip_suffix("_per_pixel") {
                    Some(kind) => format!("{kind} per pixel"),
                    None => continue,
                },
            };
            let total = get("total").and_then(|x| x.parse().ok()).unwrap_or(sum);
            out.push(Measured {
                label: format!("qemu-frame {mode} frame 0"),
                plan,
                units: total,
                counts,
            });
        }
    }
    if out.is_empty() {
        return Err(format!(
            "{}: no frame 0 of {scene} for {}",
            path.display(),
            chip.name
        ));
    }
    Ok(out)
}

/// `--check`: each measured frame against the prediction of the same option in the chip's
/// first backend. Returns the table and whether every one is within [`CHECK_TOLERANCE`].
pub fn check(b: &Budget, path: &Path) -> Result<(String, bool), String> {
    let backend = b.chip.backends[0];
    let mut s = String::new();
    let _ = writeln!(
        s,
        "| emulated frame | option | predicted | measured | prediction / measured | counts (shader calls, pixels, triangle setups) |"
    );
    let _ = writeln!(s, "|---|---|---:|---:|---:|---|");
    let mut ok = true;
    for m in measured(path, b.chip, &stem(Path::new(&b.scene)))? {
        let (label, plan, units) = (m.label, m.plan, m.units);
        let row = b.rows.iter().filter(|r| r.backend == backend).find(|r| {
            if r.tessellation != 1.0 || r.variant != Variant::AsWritten {
                false
            } else if plan == "as written" {
                r.shading.ends_with("(as written)")
            } else if plan == "all Gouraud" {
                r.shading.starts_with("Gouraud")
            } else if plan == "all per pixel" {
                r.shading.starts_with("per pixel") && !r.shading.contains(':')
            } else {
                let kind = plan.trim_end_matches(" per pixel");
                r.shading.starts_with(&format!("per pixel: {kind} ")) && !r.shading.contains(", ")
            }
        });
        let Some(r) = row else {
            return Err(format!("{label}: no option \"{plan}\" in {backend}"));
        };
        let ratio = r.predicted.total() / units;
        let within = (ratio - 1.0).abs() <= CHECK_TOLERANCE;
        ok &= within;
        // The host's counts must be the firmware's, exactly (the same frame path).
        let w = &r.work;
        let host = [
            w.total(|o| o.vertex_calls + o.pixel_calls),
            w.total(|o| o.pixels),
            w.total(|o| o.setups),
        ];
        let counted = match m.counts {
            Some(c) if c == host => format!("{} {} {}, equal", c[0], c[1], c[2]),
            Some(c) => {
                ok = false;
                format!(
                    "firmware {} {} {}, host {} {} {}: DIFFERENT",
                    c[0], c[1], c[2], host[0], host[1], host[2]
                )
            }
            None => "-".to_owned(),
        };
        let _ = writeln!(
            s,
            "| {label} | {backend}, {} | {} | {} | {:.3}{} | {counted} |",
            r.shading,
            mega(r.predicted.total()),
            mega(units),
            ratio,
            if within { "" } else { " (beyond 15 %)" }
        );
    }
    Ok((s, ok))
}
