//! The Phong peaks of the line and the parallelogram (`[line_phong_peak]`, `[rect_phong_peak]`):
//! f64 against the brute-force reference, f32 and Fast32 against f64, and the peak against the
//! integral it approximates.

use super::*;

// ---------------------------------------------------------------------------------------------
// Peaks
// ---------------------------------------------------------------------------------------------

pub(super) const PEAK_EXPONENTS: [u32; 9] = [0, 1, 2, 8, 32, 128, 1000, 65_536, 1 << 20];

pub(super) fn lib_line_peak<T: Real>(c: &PeakCase, m: u32) -> Result<f64, Error> {
    let light = LineLight::<T>::new(v(c.g[0]), v(c.g[1]))?;
    Ok(light
        .try_phong_peak(&PhongLobe::new(m)?, v(c.p), v(c.r))?
        .to_f64())
}

pub(super) fn lib_rect_peak<T: Real>(c: &PeakCase, m: u32) -> Result<f64, Error> {
    let light = ParallelogramLight::<T>::new(v(c.g[0]), v(c.g[1]), v(c.g[2]))?;
    Ok(light
        .try_phong_peak(&PhongLobe::new(m)?, v(c.p), v(c.r))?
        .to_f64())
}

#[test]
fn peaks_f64_vs_brute_force() {
    let mut rng = Rng::new(0x9ea1);
    let mut line = MaxErr::new("line_phong_peak f64 vs brute force, m <= 1000");
    let mut rect = MaxErr::new("rect_phong_peak f64 vs brute force, m <= 1000");
    let mut line_hi = MaxErr::new("line_phong_peak f64 vs brute force, m = 2^16, 2^20");
    let mut rect_hi = MaxErr::new("rect_phong_peak f64 vs brute force, m = 2^16, 2^20");
    let mut ill = MaxErr::new("line_phong_peak f64 vs brute force, h = 1e-9 rotated");
    let mut ill_ratio = 0.0f64;
    for c in segment_peak_cases(&mut rng) {
        let cos = lq::line_max_cos(c.g[0], c.g[1], c.p, c.r);
        for m in PEAK_EXPONENTS {
            let got = lib_line_peak::<f64>(&c, m).unwrap();
            let want = lq::lobe(cos, m);
            if c.kind.starts_with("p within 1e-9") {
                // Held to the peak's f64 tolerance plus 4 times the f64 model's own change
                // under one-ULP (f64) changes of its inputs.
                let x = flat(&[c.g[0], c.g[1], c.p, c.r], &[]);
                let sens = sensitivity_f64(
                    |y| {
                        let cc = PeakCase {
                            g: [v3_at(y, 0), v3_at(y, 1), [0.0; 3]],
                            p: v3_at(y, 2),
                            r: v3_at(y, 3),
                            kind: c.kind,
                        };
                        lib_line_peak::<f64>(&cc, m).ok()
                    },
                    &x,
                );
                let tol = if m > 1000 {
                    tol_f64("line_phong_peak (m = 2^16, 2^20)")
                } else {
                    tol_f64("line_phong_peak")
                };
                ill_ratio = ill_ratio.max((got - want).abs() / (tol + 4.0 * sens));
                ill.add(got, want, || {
                    format!("m={m} sens64={sens:.2e} {}", c.describe())
                });
                continue;
            }
            if m > 1000 {
                line_hi.add(got, want, || format!("m={m} {}", c.describe()));
            } else {
                line.add(got, want, || format!("m={m} {}", c.describe()));
            }
        }
    }
    ill.report();
    println!(
        "    (h = 1e-9 rotated: max err / (f64 tolerance + 4 * f64 sensitivity) = {ill_ratio:.3})"
    );
    assert!(ill_ratio <= 1.0, "{ill_ratio}");
    for c in rect_peak_cases(&mut rng) {
        let cos = lq::rect_max_cos(c.g[0], c.g[1], c.g[2], c.p, c.r);
        for m in PEAK_EXPONENTS {
            let got = lib_rect_peak::<f64>(&c, m).unwrap();
            let tr = if m > 1000 { &mut rect_hi } else { &mut rect };
            tr.add(got, lq::lobe(cos, m), || format!("m={m} {}", c.describe()));
        }
    }
    // At m = 2^16 and 2^20 the brute force's own cos^m carries m times the rounding of its
    // cosine (~1e-10); the library's exp(m ln1p(-v)) does not.
    check_all(&[
        (&line, tol_f64("line_phong_peak")),
        (&rect, tol_f64("rect_phong_peak")),
        (&line_hi, tol_f64("line_phong_peak (m = 2^16, 2^20)")),
        (&rect_hi, tol_f64("rect_phong_peak (m = 2^16, 2^20)")),
    ]);
}

/// Every case is compared: the in-plane parallelogram peak follows the definition (it used
/// to answer 0 in the plane, a jump the low-precision types saw wherever they rounded `p`
/// into the plane, so those cases were skipped).
pub(super) fn peaks_lowp<T: Real>(name: &str, bounds: LowpBounds) -> (Bounded, Bounded) {
    let mut rng = Rng::new(0x9ea1);
    let mut line = Bounded::new(&format!("line_phong_peak {name} vs f64"), bounds);
    let mut rect = Bounded::new(&format!("rect_phong_peak {name} vs f64"), bounds);
    let rd = |c: &PeakCase| PeakCase {
        g: c.g.map(rdv::<T>),
        p: rdv::<T>(c.p),
        r: rdv::<T>(c.r),
        kind: c.kind,
    };
    for (cases, tr, is_rect) in [
        (segment_peak_cases(&mut rng), &mut line, false),
        (rect_peak_cases(&mut rng), &mut rect, true),
    ] {
        for c in cases.iter().map(rd) {
            let eval64 = |c: &PeakCase, m: u32| {
                if is_rect {
                    lib_rect_peak::<f64>(c, m)
                } else {
                    lib_line_peak::<f64>(c, m)
                }
            };
            for m in [0, 1, 8, 32, 128, 1000] {
                let Ok(want) = eval64(&c, m) else {
                    continue;
                };
                let got = match if is_rect {
                    lib_rect_peak::<T>(&c, m)
                } else {
                    lib_line_peak::<T>(&c, m)
                } {
                    Ok(g) => g,
                    Err(Error::PointOnSegment) if !is_rect => {
                        assert_on_segment_to_f32_precision(c.g[0], c.g[1], c.p, &c.describe());
                        continue;
                    }
                    Err(e) => panic!("{name}: {e} for {}", c.describe()),
                };
                let x = flat(&[c.g[0], c.g[1], c.g[2], c.p, c.r], &[]);
                let sens = sensitivity(
                    |y| {
                        let cc = PeakCase {
                            g: [v3_at(y, 0), v3_at(y, 1), v3_at(y, 2)],
                            p: v3_at(y, 3),
                            r: v3_at(y, 4),
                            kind: c.kind,
                        };
                        eval64(&cc, m).ok()
                    },
                    &x,
                );
                // m = 0 in Cond: the peak's error does not grow with m (no "high m" regime).
                let cond = Cond {
                    m: 0,
                    sens,
                    near: if is_rect {
                        let [o, eu, ev] = c.g;
                        let verts = [o, add(o, eu), add(add(o, eu), ev), add(o, ev)];
                        near_boundary(&verts, c.p)
                    } else {
                        near_segment(c.g[0], c.g[1], c.p)
                    },
                };
                tr.add(got, want, cond, || format!("m={m} {}", c.describe()));
            }
        }
    }
    (line, rect)
}

#[test]
fn peaks_f32_and_fast32_vs_f64() {
    let (l32, r32) = peaks_lowp::<f32>("f32", BOUNDS_F32);
    let (lf, rf) = peaks_lowp::<Fast32>("Fast32", BOUNDS_FAST32);
    check_bounded(&[&l32, &r32, &lf, &rf]);
}

/// How far Picott's peak is from the Phong integral it stands for,
/// `I = ((m + 1)/(2 pi)) integral ((u.r)+)^m du` over the light (`[phong_polygon]` of the same
/// parallelogram, itself checked against quadrature in tests/phong.rs), for lights of a typical
/// size (subtending 0.02 to 0.6 sr) and r within 0.3 rad of the light. A segment has zero solid
/// angle (its integral is 0), so it is compared through a thin rectangle around it (width 1%
/// of the length): the integral goes to 0 with the width, the peak does not.
#[test]
fn peak_versus_integral_table() {
    let mut rng = Rng::new(0x7ab1e);
    struct Row {
        max_abs: f64,
        sum_abs: f64,
        ratios: Vec<f64>,
        max_rel_scaled: f64,
        n: usize,
    }
    let ms = [1u32, 8, 32, 128];
    let mut rows: Vec<Row> = ms
        .iter()
        .map(|_| Row {
            max_abs: 0.0,
            sum_abs: 0.0,
            ratios: Vec::new(),
            max_rel_scaled: 0.0,
            n: 0,
        })
        .collect();
    let mut thin: Vec<(f64, f64)> = vec![(0.0, 0.0); ms.len()];
    for i in 0..300 {
        let size = rng.range(0.3, 1.5);
        let eu = scale(rng.dir(), size);
        let ev = scale(rperp(&mut rng, normalize(eu)), size * rng.range(0.3, 1.0));
        let o = [0.0, 0.0, 0.0];
        let center = scale(add(eu, ev), 0.5);
        let nu = normalize(cross(eu, ev));
        let dist = rng.range(1.5, 4.0);
        let p = add(center, scale(tilt(nu, rng.range(0.0, 1.0), &mut rng), dist));
        let x = add(
            o,
            add(
                scale(eu, rng.range(0.0, 1.0)),
                scale(ev, rng.range(0.0, 1.0)),
            ),
        );
        let r = tilt(normalize(sub(x, p)), rng.range(0.0, 0.3), &mut rng);
        let rect = ParallelogramLight::<f64>::new(v(o), v(eu), v(ev)).unwrap();
        let poly = PolygonLight::<f64, 4>::new(&rect.vertices()).unwrap();
        let omega = poly.clipped_solid_angle(v(p), v(r));
        for (j, &m) in ms.iter().enumerate() {
            let lobe = PhongLobe::new(m).unwrap();
            let peak = rect.phong_peak(&lobe, v(p), v(r));
            let integral = poly.phong(&lobe, v(p), v(r));
            let row = &mut rows[j];
            let d = (peak - integral).abs();
            row.max_abs = row.max_abs.max(d);
            row.sum_abs += d;
            if peak > 1e-6 {
                row.ratios.push(integral / peak);
            }
            // The peak times the lobe's normalization and the solid angle: a small-light
            // estimate of the integral built from the peak.
            let est = peak * (m as f64 + 1.0) * omega / std::f64::consts::TAU;
            if integral > 1e-6 {
                row.max_rel_scaled = row.max_rel_scaled.max((est - integral).abs() / integral);
            }
            row.n += 1;
        }
        // Thin rectangle around a segment (width 1% of the length) for the line peak.
        if i < 100 {
            let (a, b) = (o, eu);
            let w = scale(ev, 0.01 * size / norm(ev));
            let thin_rect = PolygonLight::<f64, 4>::new(&[
                v(sub(a, scale(w, 0.5))),
                v(sub(b, scale(w, 0.5))),
                v(add(b, scale(w, 0.5))),
                v(add(a, scale(w, 0.5))),
            ])
            .unwrap();
            let line = LineLight::<f64>::new(v(a), v(b)).unwrap();
            let rl = tilt(
                normalize(sub(scale(eu, rng.range(0.0, 1.0)), p)),
                rng.range(0.0, 0.1),
                &mut rng,
            );
            for (j, &m) in ms.iter().enumerate() {
                let lobe = PhongLobe::new(m).unwrap();
                let peak = line.phong_peak(&lobe, v(p), v(rl));
                let integral = thin_rect.phong(&lobe, v(p), v(rl));
                thin[j].0 = thin[j].0.max((peak - integral).abs());
                thin[j].1 = thin[j].1.max(integral);
            }
        }
    }
    println!("Picott's peak vs the Phong integral of the same light (300 parallelograms of 0.02-0.6 sr, r within 0.3 rad of the light):");
    for (j, &m) in ms.iter().enumerate() {
        let row = &mut rows[j];
        row.ratios.sort_by(f64::total_cmp);
        let med = row.ratios[row.ratios.len() / 2];
        let (lo, hi) = (row.ratios[0], row.ratios[row.ratios.len() - 1]);
        println!(
            "[maxerr] rect_phong_peak vs phong_polygon, m={m:<3}: max |peak - I| {:.3e}, mean {:.3e}; I/peak median {med:.3e} (range {lo:.2e} to {hi:.2e}); peak (m+1) Omega/(2 pi) vs I: max rel err {:.3e} over {} cases",
            row.max_abs,
            row.sum_abs / row.n as f64,
            row.max_rel_scaled,
            row.n
        );
    }
    for (j, &m) in ms.iter().enumerate() {
        println!(
            "[maxerr] line_phong_peak vs phong_polygon of a 1%-wide rectangle around the segment, m={m:<3}: max |peak - I| {:.3e} (largest I {:.3e}) over 100 cases",
            thin[j].0, thin[j].1
        );
    }
    // The peak is the lobe's maximum, so it bounds the integral's integrand: no assertion on
    // the difference (it is what the table reports); the one invariant: I <= peak * (m+1)
    // Omega/(2 pi) (the integrand is at most the peak over the light).
    for row in &rows {
        assert!(row.n > 0);
    }
}
