//! The calibration: `host-sim budget --calibrate` turns the emulators' measurements (the
//! calibration firmware's per-item counts and the demo frames' flush stage) into the cost
//! table `host-sim/costs.csv`, deriving the items it does not measure from the QEMU budget's
//! per-call counts.

use super::*;

/// A calibration file's rows: item -> (count, setups, calls, ticks).
type Calibration = BTreeMap<String, [f64; 4]>;

fn read_calibration(path: &Path) -> Result<Calibration, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let mut out = BTreeMap::new();
    for line in text.lines().skip(1).filter(|l| !l.trim().is_empty()) {
        let f: Vec<&str> = line.split(',').collect();
        let nums: Result<Vec<f64>, _> = f.iter().skip(1).map(|x| x.parse::<f64>()).collect();
        match (f.first(), nums) {
            (Some(item), Ok(n)) if n.len() == 4 => {
                out.insert((*item).to_owned(), [n[0], n[1], n[2], n[3]]);
            }
            _ => return Err(format!("{}: bad row {line:?}", path.display())),
        }
    }
    Ok(out)
}

/// The per-unit costs of one calibration: every `diffuse:`/`phong*:` item, `lit_*`,
/// `vertex_*`, `shade_vertex` and `band_clear` per unit; `triangle` and `pixel` from the two
/// Gouraud squares (2 equations: big and grid, each ticks = setups triangle + pixels pixel);
/// `pixel_shaded` the per-pixel square's extra ticks per shader call.
fn per_unit(cal: &Calibration) -> Result<BTreeMap<String, f64>, String> {
    let get = |k: &str| {
        cal.get(k)
            .copied()
            .ok_or_else(|| format!("calibration has no {k}"))
    };
    let mut out = BTreeMap::new();
    for (item, [count, ..]) in cal.iter().map(|(k, v)| (k, *v)) {
        let ticks = cal[item][3];
        if item.starts_with("raster_") || count <= 0.0 {
            continue;
        }
        out.insert(item.clone(), ticks / count);
    }
    let [p1, s1, _, t1] = get("raster_big")?;
    let [p2, s2, _, t2] = get("raster_grid")?;
    let det = s1 * p2 - s2 * p1;
    if det.abs() < 1.0 {
        return Err("raster_big and raster_grid do not separate triangles from pixels".into());
    }
    let tri = (t1 * p2 - t2 * p1) / det;
    let px = (s1 * t2 - s2 * t1) / det;
    let [_, _, calls, t3] = get("raster_big_pp")?;
    out.insert("triangle".into(), tri);
    out.insert("pixel".into(), px);
    out.insert("pixel_shaded".into(), (t3 - t1) / calls.max(1.0));
    Ok(out)
}

/// The QEMU budget's median per-call counts (`budget::read_counts`, the per-call table's own
/// reader): (target, backend, model) -> instructions.
fn read_counts(path: &Path) -> Result<BTreeMap<(String, String, String), f64>, String> {
    let counts: BTreeMap<_, f64> = crate::budget::read_counts(path)
        .into_iter()
        .filter_map(|(k, (median, _))| Some((k, median? as f64)))
        .collect();
    if counts.is_empty() {
        return Err(format!(
            "no counts in {} (run cargo test -p host-sim --test qemu_budget first)",
            path.display()
        ));
    }
    Ok(counts)
}

/// A chip's calibration: (chip, calibrated backend, its QEMU budget target, other backends,
/// calibration directory, flush per byte).
type CalibratedChip<'a> = (&'a str, &'a str, &'a str, &'a [&'a str], &'a Path, f64);

/// (backend, item).
type Key = (String, String);

/// The models behind a light kind's `diffuse` and `phong` (the QEMU budget's ids).
const KIND_MODELS: &[(&str, &str, &str)] = &[
    ("polygon", "polygon_lambert", "phong_polygon"),
    ("sphere", "sphere_lambert", "phong_sphere"),
    ("cap", "cap_lambert", "phong_cap"),
    ("sphere_hermite", "sphere_lambert_hermite", "phong_sphere"),
    ("cap_hermite", "cap_lambert_hermite", "phong_cap"),
    ("point", "point_lambert", "point_phong"),
    ("hemisphere", "hemi_const", "phong_hemi_const"),
    ("overcast", "sky_overcast", "phong_hemi_cos"),
    ("sky_ground", "sky_ground", "phong_hemi_const"),
    ("line", "line_lambert", "line_phong_peak"),
    ("parallelogram", "polygon_lambert", "rect_phong_peak"),
    ("sh9", "sh9_irradiance", ""),
];

/// Writes the cost table from the measurements: `rp2040` from `rp2040_dir`
/// (calibration.csv, frames.csv of `boards/rp2040-emu/check.sh`), `stm32f411` from
/// `qemu_frame_dir` (calibration.csv, frames.csv of the QEMU frame test), derived items
/// from `counts` (the QEMU budget's counts.csv).
///
/// # Errors
/// A missing or malformed file.
pub fn calibrate(
    rp2040_dir: &Path,
    qemu_frame_dir: &Path,
    counts: &Path,
) -> Result<String, String> {
    let counts = read_counts(counts)?;
    let mut csv = String::from("chip,backend,item,cost,source\n");
    // (chip, calibrated backend, its QEMU budget target, other backends, calibration dir,
    //  flush per band)
    // Both demo frames send 240 x 240 RGB565 pixels.
    let frame_bytes = 240 * 240 * 2;
    let rp_flush = flush_per_byte(&rp2040_dir.join("frames.csv"), "lit_scene", frame_bytes)?;
    let m4_flush = flush_per_byte(&qemu_frame_dir.join("frames.csv"), "gouraud", frame_bytes)?;
    let chips: [CalibratedChip<'_>; 2] = [
        (
            "rp2040",
            "fixed",
            "m0",
            &["f32-fast", "f32"],
            rp2040_dir,
            rp_flush,
        ),
        (
            "stm32f411",
            "f32",
            "m4f",
            &["f32-fast"],
            qemu_frame_dir,
            m4_flush,
        ),
    ];
    for (chip, backend, target, others, dir, flush) in chips {
        let cal = per_unit(&read_calibration(&dir.join("calibration.csv"))?)?;
        let mut rows: BTreeMap<(String, String), (f64, &str)> = BTreeMap::new();
        for (item, c) in &cal {
            rows.insert((backend.into(), item.clone()), (*c, "calibrate"));
        }
        rows.insert((backend.into(), "flush_byte".into()), (flush, "frame"));
        let count = |b: &str, model: &str| {
            counts
                .get(&(target.to_owned(), b.to_owned(), model.to_owned()))
                .copied()
        };
        // Kinds the calibration did not measure: the calibrated backend's cost of a measured
        // kind, scaled by the QEMU budget's ratio of the two models.
        let scale: f64 = {
            let (mut a, mut b) = (0.0, 0.0);
            for (kind, diffuse, _) in KIND_MODELS {
                if let (Some(c), Some(q)) =
                    (cal.get(&format!("diffuse:{kind}")), count(backend, diffuse))
                {
                    a += c;
                    b += q;
                }
            }
            if b > 0.0 {
                a / b
            } else {
                1.0
            }
        };
        for (kind, diffuse, phong) in KIND_MODELS {
            let key = format!("diffuse:{kind}");
            if !cal.contains_key(&key) {
                if let Some(q) = count(backend, diffuse) {
                    rows.insert((backend.into(), key), (q * scale, "derived"));
                    if let Some(p) = count(backend, phong) {
                        // One count (m = 16): the same for 8 and 32.
                        rows.insert(
                            (backend.into(), format!("phong8:{kind}")),
                            (p * scale, "derived"),
                        );
                        rows.insert(
                            (backend.into(), format!("phong32:{kind}")),
                            (p * scale, "derived"),
                        );
                    } else if phong.is_empty() {
                        rows.insert((backend.into(), format!("phong8:{kind}")), (0.0, "derived"));
                        rows.insert(
                            (backend.into(), format!("phong32:{kind}")),
                            (0.0, "derived"),
                        );
                    }
                }
            }
        }
        // The Hermite variants of the cap and the sphere: the exact kind's calibrated cost
        // times the QEMU budget's ratio of the two diffuse models, and the exact kind's
        // calibrated Phong items (the same function).
        for (base, exact, hermite) in [
            ("sphere", "sphere_lambert", "sphere_lambert_hermite"),
            ("cap", "cap_lambert", "cap_lambert_hermite"),
        ] {
            let kind = format!("{base}_hermite");
            if let (Some(c), Some(qh), Some(qe)) = (
                cal.get(&format!("diffuse:{base}")),
                count(backend, hermite),
                count(backend, exact),
            ) {
                rows.insert(
                    (backend.into(), format!("diffuse:{kind}")),
                    (c * qh / qe, "derived"),
                );
            }
            for (item, c) in &cal {
                if let Some((what, rest)) = item.split_once(':') {
                    let (k, sub) = rest.split_once(':').map_or((rest, ""), |(k, s)| (k, s));
                    if k == base && what.starts_with("phong") {
                        let name = if sub.is_empty() {
                            format!("{what}:{kind}")
                        } else {
                            format!("{what}:{kind}:{sub}")
                        };
                        rows.insert((backend.into(), name), (*c, "calibrate"));
                    }
                }
            }
        }
        // Other backends: every item of the calibrated backend times the QEMU budget's ratio
        // for the models of that item (the frame's own work: the mean ratio of every model).
        let base: Vec<(Key, (f64, &str))> = rows.iter().map(|(k, v)| (k.clone(), *v)).collect();
        for other in others {
            let (mut a, mut n) = (0.0, 0.0);
            for (_, d, _) in KIND_MODELS {
                if let (Some(x), Some(y)) = (count(other, d), count(backend, d)) {
                    a += x / y;
                    n += 1.0;
                }
            }
            let mean = if n > 0.0 { a / n } else { continue };
            for ((_, item), (c, _)) in &base {
                // `diffuse:<kind>` and its `:lit`/`:dark` subsets.
                let ratio = match item.split_once(':') {
                    Some((what, kind)) => KIND_MODELS
                        .iter()
                        .find(|(k, _, _)| Some(*k) == kind.split(':').next())
                        .and_then(|(_, d, p)| {
                            let m = if what == "diffuse" { d } else { p };
                            Some(count(other, m)? / count(backend, m)?)
                        })
                        .unwrap_or(mean),
                    // Integer code whatever the scalar: scan conversion, clears, the flush.
                    None if ["triangle", "pixel", "band_clear", "flush_byte"]
                        .contains(&item.as_str()) =>
                    {
                        1.0
                    }
                    None => mean,
                };
                rows.insert(((*other).to_owned(), item.clone()), (c * ratio, "derived"));
            }
        }
        for ((b, item), (c, source)) in rows {
            let _ = writeln!(csv, "{chip},{b},{item},{c:.1},{source}");
        }
    }
    Ok(csv)
}

/// The flush stage of `firmware` (a frames.csv's first column) at frame 0, per byte sent.
fn flush_per_byte(path: &Path, firmware: &str, bytes: u32) -> Result<f64, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name);
    let (Some(fw), Some(fr), Some(fl)) =
        (col("firmware").or(col("mode")), col("frame"), col("flush"))
    else {
        return Err(format!(
            "{}: no firmware/mode, frame and flush columns",
            path.display()
        ));
    };
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        if f.get(fw) == Some(&firmware) && f.get(fr) == Some(&"0") {
            let flush: f64 = f
                .get(fl)
                .and_then(|x| x.parse().ok())
                .ok_or_else(|| format!("{}: bad flush in {line:?}", path.display()))?;
            return Ok(flush / f64::from(bytes.max(1)));
        }
    }
    Err(format!("{}: no frame 0 of {firmware}", path.display()))
}
