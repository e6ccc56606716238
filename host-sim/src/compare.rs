//! Comparison sheets: the same frame rendered with the scalar backends f64, f32, f32-fast
//! (`Fast32`) and fixed point (`Fixed22`), side by side, with heat maps of each one's
//! difference from f64 (log scale, colour bar) and the largest difference printed.
//!
//! Errors are measured before the display's clamp: every backend renders the frame into
//! linear floating-point values (no transfer function) with the figure's exposure divided by a
//! power of two `2^j` large enough that nothing reaches 1 (found from the f64 frame), and the
//! values are multiplied back by `2^j` (exact in the floats; in `Fixed22` the scaled product
//! rounds to 2^-22, 2^(j-22) after scaling back, far below its shading error). So the maps show
//! the shading error itself at display scale, highlights included, not 8-bit rounding nor a
//! clamp. A pixel covered in one frame and not in the other (vertex snapping differs by a
//! sub-pixel between backends at a few silhouette pixels) is counted separately, not compared.

use std::path::{Path, PathBuf};

use arealight::raster::{encode_pixel, Encoding, RasterError, Rgb888};
use arealight::{Fast32, Fixed22, Real, Rgb};
use tiny_skia::{Color, Pixmap};

use crate::figure::{self, blit, text, Font, BG};
pub use crate::scenes::LinearPx;
use crate::scenes::{self, SnyderLight, View};

/// The sheets `render` writes: file stem and scene.
pub const SHEETS: [(&str, SnyderLight); 2] = [
    ("compare_polygon", SnyderLight::Polygon),
    ("compare_sphere", SnyderLight::Sphere),
];

const W: u16 = 220;
const H: u16 = 180;

/// The f64 frame's largest channel value at the figure's exposure (before any clamp), from a
/// render at 1/128 of it (the fixed-point rasterizer's largest colour).
fn peak(kind: SnyderLight) -> Result<f64, RasterError> {
    let scene = scenes::snyder_scene::<f64>(kind, W, H)?;
    let view = View {
        camera: &scene.camera,
        exposure: scene.exposure / 128.0,
        encoding: Encoding::Linear,
    };
    let px = scenes::render_view(&scene, &view, scenes::BAND_ROWS, LinearPx::default())?;
    Ok(px.iter().flat_map(|p| p.rgb).fold(0.0, f64::max) * 128.0)
}

/// The frame in `T` at the figure's exposure, linear and unclamped: rendered at the exposure
/// divided by `2^j` and multiplied back.
fn frame<T: Real + 'static>(kind: SnyderLight, j: i32) -> Result<Vec<LinearPx>, RasterError> {
    let scene = scenes::snyder_scene::<T>(kind, W, H)?;
    let down = T::from_f64(2f64.powi(-j));
    let view = View {
        camera: &scene.camera,
        exposure: scene.exposure * down,
        encoding: Encoding::Linear,
    };
    let mut px = scenes::render_view(&scene, &view, scenes::BAND_ROWS, LinearPx::default())?;
    let up = 2f64.powi(j);
    for p in &mut px {
        p.rgb = p.rgb.map(|x| x * up);
    }
    Ok(px)
}

/// Which object each pixel shows (0: background): the scene with every surface replaced by a
/// constant code, so a pixel where two backends' depth tests pick different surfaces (a tie at
/// a contact, like the torus resting on the floor, decided by the last bit of a 16-bit depth)
/// is told apart from a shading difference.
fn id_frame<T: Real + 'static>(kind: SnyderLight) -> Result<Vec<u16>, RasterError> {
    let mut scene = scenes::snyder_scene::<T>(kind, W, H)?;
    scene.encoding = Encoding::Linear;
    scene.exposure = T::ONE;
    for (i, o) in scene.objects.iter_mut().enumerate() {
        o.surface =
            scenes::Surface::Emissive(arealight::Rgb::splat(T::from_f64((i + 1) as f64 / 64.0)));
    }
    let px = scenes::render(&scene, scenes::BAND_ROWS, LinearPx::default())?;
    Ok(px
        .iter()
        .map(|p| {
            if p.covered {
                (p.rgb[0] * 64.0).round() as u16
            } else {
                0
            }
        })
        .collect())
}

/// The log-scale heat colour of an error (1e-8 and below black, 1e-2 and above white).
fn heat(e: f64) -> [u8; 3] {
    let t = ((e.max(1e-12).log10() + 8.0) / 6.0).clamp(0.0, 1.0);
    // black -> blue -> magenta -> orange -> yellow -> white
    let stops: [(f64, [f64; 3]); 6] = [
        (0.0, [0.0, 0.0, 0.0]),
        (0.2, [0.1, 0.1, 0.7]),
        (0.45, [0.7, 0.1, 0.6]),
        (0.7, [1.0, 0.45, 0.0]),
        (0.9, [1.0, 0.9, 0.1]),
        (1.0, [1.0, 1.0, 1.0]),
    ];
    for w in stops.windows(2) {
        let ((t0, c0), (t1, c1)) = (w[0], w[1]);
        if t <= t1 {
            let s = (t - t0) / (t1 - t0);
            return [0, 1, 2].map(|k| ((c0[k] + (c1[k] - c0[k]) * s) * 255.0 + 0.5) as u8);
        }
    }
    [255, 255, 255]
}

/// Per-pixel max channel difference from the reference where both show the same surface
/// (`ids`: the two frames' object codes, see [`id_frame`]); the largest difference and the
/// number of pixels where the surfaces differ (coverage or a depth tie), marked NaN.
pub fn error_map(
    reference: &[LinearPx],
    other: &[LinearPx],
    ids: Option<(&[u16], &[u16])>,
) -> (Vec<f64>, f64, usize) {
    let mut max = 0.0f64;
    let mut mismatched = 0;
    let map = reference
        .iter()
        .zip(other)
        .enumerate()
        .map(|(i, (a, b))| {
            let other_surface = ids.is_some_and(|(x, y)| x[i] != y[i]);
            if a.covered != b.covered || other_surface {
                mismatched += 1;
                return f64::NAN;
            }
            let e = (0..3)
                .map(|k| (a.rgb[k] - b.rgb[k]).abs())
                .fold(0.0, f64::max);
            max = max.max(e);
            e
        })
        .collect();
    (map, max, mismatched)
}

/// Renders one comparison sheet into `out/<stem>.png`.
///
/// # Errors
/// A message for a scene the library refuses or a file that cannot be written.
pub fn sheet(kind: SnyderLight, out: &Path, stem: &str) -> Result<PathBuf, String> {
    let err = |e: RasterError| format!("{stem}: scene refused: {e}");
    let peak = peak(kind).map_err(err)?;
    // The smallest j with the peak at most 0.9 2^j (room for the backends' differences).
    let j = (peak / 0.9).log2().ceil().max(0.0) as i32;
    let display = scenes::snyder_scene::<f64>(kind, W, H).map_err(err)?;
    let f64_frame = frame::<f64>(kind, j).map_err(err)?;
    let f64_ids = id_frame::<f64>(kind).map_err(err)?;
    type Column = (
        &'static str,
        Result<Vec<LinearPx>, RasterError>,
        Option<Vec<u16>>,
    );
    let columns: [Column; 3] = [
        ("f32", frame::<f32>(kind, j), id_frame::<f32>(kind).ok()),
        (
            "f32-fast (Fast32)",
            frame::<Fast32>(kind, j),
            id_frame::<Fast32>(kind).ok(),
        ),
        (
            "fixed (Fixed22, I10F22)",
            frame::<Fixed22>(kind, j),
            id_frame::<Fixed22>(kind).ok(),
        ),
    ];
    let (w, h) = (W as u32, H as u32);
    let bar_w = 80;
    let sheet_w = 10 + 4 * (w + 10) + bar_w;
    let sheet_h = 34 + 2 * (h + 40) + 24;
    let mut pix = Pixmap::new(sheet_w, sheet_h).ok_or("cannot allocate the sheet")?;
    pix.fill(Color::from_rgba8(BG[0], BG[1], BG[2], 255));
    text(
        &mut pix,
        &format!(
            "Backends compared: Snyder fig. 7 {} (as the figure shows it)",
            kind.title()
        ),
        10,
        8,
        [235, 235, 235],
        Font::Big,
    );
    // The frames as the figure shows them: its encoding (tone curve, sRGB) on the unclamped
    // values, the background where nothing is drawn.
    let to_rgb = |f: &[LinearPx]| -> Vec<[u8; 3]> {
        f.iter()
            .map(|p| {
                if p.covered {
                    let c = Rgb::new(p.rgb[0], p.rgb[1], p.rgb[2]);
                    encode_pixel::<f64, Rgb888>(c, 1.0, display.encoding).0
                } else {
                    display.background
                }
            })
            .collect()
    };
    let (y_top, y_bot) = (34, 34 + h + 40);
    blit(&mut pix, &to_rgb(&f64_frame), w, h, 10, y_top);
    text(
        &mut pix,
        "f64 (reference)",
        10,
        (y_top + h + 4) as i32,
        [220, 220, 225],
        Font::Small,
    );
    text(
        &mut pix,
        "error maps: max |channel - f64|,",
        10,
        (y_bot + h / 2) as i32,
        [160, 160, 170],
        Font::Small,
    );
    text(
        &mut pix,
        "before the clamp",
        10,
        (y_bot + h / 2 + 12) as i32,
        [160, 160, 170],
        Font::Small,
    );
    for (k, (name, f, ids)) in columns.iter().enumerate() {
        let x = 10 + (k as u32 + 1) * (w + 10);
        match f {
            Ok(f) => {
                blit(&mut pix, &to_rgb(f), w, h, x, y_top);
                text(
                    &mut pix,
                    name,
                    x as i32,
                    (y_top + h + 4) as i32,
                    [220, 220, 225],
                    Font::Small,
                );
                let ids = ids.as_deref().map(|x| (f64_ids.as_slice(), x));
                let (map, max, mismatched) = error_map(&f64_frame, f, ids);
                let rgb: Vec<[u8; 3]> = map
                    .iter()
                    .map(|&e| if e.is_nan() { [0, 90, 0] } else { heat(e) })
                    .collect();
                blit(&mut pix, &rgb, w, h, x, y_bot);
                text(
                    &mut pix,
                    &format!("max error {max:.2e}"),
                    x as i32,
                    (y_bot + h + 4) as i32,
                    [255, 230, 120],
                    Font::Small,
                );
                text(
                    &mut pix,
                    &format!("{mismatched} px show another surface (green)"),
                    x as i32,
                    (y_bot + h + 16) as i32,
                    [150, 150, 160],
                    Font::Small,
                );
            }
            Err(e) => {
                text(
                    &mut pix,
                    &format!("{name}: not available"),
                    x as i32,
                    (y_top + h / 2) as i32,
                    [255, 140, 120],
                    Font::Small,
                );
                text(
                    &mut pix,
                    &format!("{e}"),
                    x as i32,
                    (y_top + h / 2 + 12) as i32,
                    [150, 150, 160],
                    Font::Small,
                );
            }
        }
    }
    // The colour bar: 1e-8 (bottom) to 1e-2 (top).
    let bx = 10 + 4 * (w + 10) + 8;
    let bar: Vec<[u8; 3]> = (0..h)
        .flat_map(|y| {
            let e = 10f64.powf(-2.0 - 6.0 * y as f64 / (h - 1) as f64);
            [heat(e); 16]
        })
        .collect();
    blit(&mut pix, &bar, 16, h, bx, y_bot);
    for d in 0..=6 {
        let y = y_bot + (d * (h - 1)) / 6;
        text(
            &mut pix,
            &format!("1e-{}", d + 2),
            (bx + 20) as i32,
            y as i32 - 4,
            [200, 200, 205],
            Font::Small,
        );
    }
    text(
        &mut pix,
        &format!(
            "errors on linear values x the figure's exposure, before the display's clamp or tone \
             curve (peak {peak:.2} of display white; rendered at 2^-{j} of the exposure, scaled back)"
        ),
        10,
        (sheet_h - 14) as i32,
        [150, 150, 160],
        Font::Small,
    );
    figure::save(&pix, out, &format!("{stem}.png"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn error_map_compares_only_pixels_covered_in_both() {
        let p = |x: f64, c: bool| LinearPx {
            rgb: [x, x / 2.0, 0.0],
            covered: c,
        };
        let a = [p(0.5, true), p(0.25, true), p(0.0, false), p(0.75, true)];
        let b = [p(0.5, true), p(0.2, true), p(0.0, false), p(0.1, false)];
        let (map, max, mismatched) = error_map(&a, &b, None);
        assert_eq!(map[0], 0.0);
        assert!((map[1] - 0.05).abs() < 1e-15);
        assert!(map[3].is_nan());
        assert!((max - 0.05).abs() < 1e-15);
        assert_eq!(mismatched, 1);
        // A pixel where the two frames show different surfaces is not a shading error.
        let (ia, ib) = ([1u16, 2, 0, 1], [1u16, 3, 0, 0]);
        let (map, max, mismatched) = error_map(&a, &b, Some((&ia, &ib)));
        assert_eq!(map[0], 0.0);
        assert!(map[1].is_nan() && map[3].is_nan());
        assert_eq!(max, 0.0);
        assert_eq!(mismatched, 2);
        assert_eq!(heat(1e-9), [0, 0, 0]);
        assert_eq!(heat(1.0), [255, 255, 255]);
    }

    #[test]
    fn errors_are_measured_before_the_clamp() {
        // The sphere light's frame peaks far above display white (its highlights); the frames
        // keep those values, and the f32 error there is measured, not clamped to 0.
        let kind = SnyderLight::Sphere;
        let peak = peak(kind).unwrap();
        assert!(peak > 2.0, "{peak}");
        let j = (peak / 0.9).log2().ceil() as i32;
        let a = frame::<f64>(kind, j).unwrap();
        let b = frame::<f32>(kind, j).unwrap();
        let (i, top) = a
            .iter()
            .enumerate()
            .map(|(i, p)| (i, p.rgb.into_iter().fold(0.0, f64::max)))
            .fold((0, 0.0), |m, x| if x.1 > m.1 { x } else { m });
        // Power-of-two scalings are exact in f64: the same peak both ways.
        assert_eq!(top, peak);
        let over = a.iter().filter(|p| p.rgb.iter().any(|&x| x > 1.0)).count();
        assert!(over > 100, "{over} pixels above white");
        let (map, max, _) = error_map(&a, &b, None);
        assert!(map[i] > 0.0 && map[i] <= max, "{} {max}", map[i]);
        // f32 against f64 at display scale: below 1e-5 of white even there (measured 9.5e-6).
        assert!(max < 1e-5, "{max}");
    }
}
