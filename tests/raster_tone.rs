//! The rasterizer's tone curve (`arealight::raster::ToneMap`, `Encoding::SrgbTone`) against
//! an independent f64 computation of its definition (the knee plus Reinhard's extended
//! operator on the excess, written as the textbook formula rather than the crate's
//! multiplied-out form), its shape (continuity and slope at the knee, white at the white
//! point, monotone, in [0, 1] for every input including NaN and infinities), and the
//! tone-mapped `EncodeTable` against `encode_pixel`; and `Camera::with_viewport`, which the
//! host's supersampled renders use.

use arealight::raster::{
    encode_pixel, EncodeTable, Encoding, RasterError, Rgb565, Rgb888, ToneMap,
    TONE_WHITE_MAX_PERCENT,
};
use arealight::{Fast32, Fixed22, Real, Rgb};

/// Reinhard's extended operator with white `w`: `u (1 + u / w^2) / (1 + u)`.
fn reinhard(u: f64, w: f64) -> f64 {
    u * (1.0 + u / (w * w)) / (1.0 + u)
}

/// The definition, in f64: identity to the knee, then the knee plus the extended operator on
/// the excess in units of the headroom `1 - k`, white at `W`.
fn reference(knee: f64, white: f64, x: f64) -> f64 {
    if x.is_nan() || x <= 0.0 {
        0.0
    } else if x <= knee {
        x
    } else if x >= white {
        1.0
    } else {
        let s = 1.0 - knee;
        knee + s * reinhard((x - knee) / s, (white - knee) / s)
    }
}

/// The sRGB transfer function in f64.
fn srgb(x: f64) -> f64 {
    if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    }
}

const CURVES: [(u8, u16); 6] = [
    (0, 400),
    (60, 400),
    (80, 200),
    (0, 101),
    (99, 12_800),
    (50, 1000),
];

/// Every test input: a grid over [-1, 2 W], the knee and white exactly, and non-finite values.
fn inputs(white: f64, knee: f64) -> Vec<f64> {
    let mut xs: Vec<f64> = (0..=20_000)
        .map(|i| -1.0 + (2.0 * white + 1.0) * f64::from(i) / 20_000.0)
        .collect();
    xs.extend([
        knee,
        white,
        0.0,
        1.0,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
    ]);
    xs
}

/// The largest difference from the reference of the curve in `T`, over every input.
fn worst<T: Real>(tm: ToneMap) -> f64 {
    let (k, w) = (
        f64::from(tm.knee_percent()) / 100.0,
        f64::from(tm.white_percent()) / 100.0,
    );
    let mut worst = 0.0f64;
    for x in inputs(w, k) {
        let got = tm.apply(T::from_f64(x)).to_f64();
        // The reference at the input as T holds it (Fixed22 rounds x to 2^-22, saturating).
        let want = reference(k, w, T::from_f64(x).to_f64());
        assert!((0.0..=1.0).contains(&got), "{tm:?} at {x}: {got}");
        worst = worst.max((got - want).abs());
    }
    worst
}

#[test]
fn the_curve_matches_its_definition_on_every_backend() {
    for (knee, white) in CURVES {
        let tm = ToneMap::new(knee, white).unwrap();
        let e = [
            worst::<f64>(tm),
            worst::<f32>(tm),
            worst::<Fast32>(tm),
            worst::<Fixed22>(tm),
        ];
        println!("knee {knee} % white {white} %: worst f64 {:.1e}, f32 {:.1e}, Fast32 {:.1e}, Fixed22 {:.1e}", e[0], e[1], e[2], e[3]);
        assert!(e[0] <= 4e-16, "f64 {e:?}");
        assert!(e[1] <= 4.0 * f64::from(f32::EPSILON), "f32 {e:?}");
        assert!(e[2] <= 4.0 * f64::from(f32::EPSILON), "Fast32 {e:?}");
        assert!(e[3] <= 2f64.powi(-20), "Fixed22 {e:?}");
    }
}

#[test]
fn the_curve_is_the_identity_to_the_knee_and_white_at_the_white_point() {
    for (knee, white) in CURVES {
        let tm = ToneMap::new(knee, white).unwrap();
        let (k, w) = (f64::from(knee) / 100.0, f64::from(white) / 100.0);
        // Continuous with slope 1 at the knee (one-sided difference quotients).
        assert_eq!(tm.apply(k), k);
        let h = 1e-9;
        let right = (tm.apply(k + h) - k) / h;
        assert!((right - 1.0).abs() < 1e-5, "{tm:?}: slope {right}");
        assert_eq!(tm.apply(w), 1.0);
        assert_eq!(tm.apply(w * 10.0), 1.0);
        assert!(tm.apply(w - 1e-3) < 1.0);
        // Increasing above the knee, flat only at and above white.
        let mut last = tm.apply(k);
        for i in 1..=10_000 {
            let x = k + (w - k) * f64::from(i) / 10_000.0;
            let y = tm.apply(x);
            assert!(
                y > last || (x >= w && y == 1.0),
                "{tm:?} at {x}: {y} after {last}"
            );
            last = y;
        }
        // Below the knee and out of the domain.
        assert_eq!(tm.apply(0.5 * k), 0.5 * k);
        assert_eq!(tm.apply(-3.0f64), 0.0);
        assert_eq!(tm.apply(f64::NAN), 0.0);
        assert_eq!(tm.apply(f64::INFINITY), 1.0);
        assert_eq!(tm.apply(f32::NAN), 0.0);
        assert_eq!(tm.apply(Fixed22::from_f64(1e9)).to_f64(), 1.0);
    }
    // Knee 0: Reinhard's extended operator itself.
    let tm = ToneMap::new(0, 400).unwrap();
    for x in [0.1, 0.5, 1.0, 2.0, 3.9] {
        assert!((tm.apply(x) - reinhard(x, 4.0)).abs() < 1e-15, "{x}");
    }
}

#[test]
fn bad_parameters_are_refused_by_name() {
    let knee = Err(RasterError::BadParameter("knee_percent"));
    let white = Err(RasterError::BadParameter("white_percent"));
    assert_eq!(ToneMap::new(100, 400), knee);
    assert_eq!(ToneMap::new(255, 400), knee);
    assert_eq!(ToneMap::new(50, 100), white);
    assert_eq!(ToneMap::new(50, 0), white);
    assert_eq!(ToneMap::new(50, TONE_WHITE_MAX_PERCENT + 1), white);
    let tm = ToneMap::new(99, TONE_WHITE_MAX_PERCENT).unwrap();
    assert_eq!((tm.knee_percent(), tm.white_percent()), (99, 12_800));
    assert_eq!(tm.white::<f64>(), 128.0);
}

#[test]
fn srgb_tone_encodes_the_curve_then_srgb() {
    let tm = ToneMap::new(60, 400).unwrap();
    let enc = Encoding::SrgbTone(tm);
    for i in 0..=5000 {
        let x = 5.0 * f64::from(i) / 5000.0;
        let want = srgb(reference(0.6, 4.0, x));
        assert!((enc.encode(x) - want).abs() < 1e-14, "{x}");
        assert!((f64::from(enc.encode(x as f32)) - want).abs() < 1e-6, "{x}");
        // Below the knee the same as plain sRGB.
        if x <= 0.6 {
            assert_eq!(enc.encode(x), Encoding::Srgb.encode(x));
        }
    }
    // A highlight the clamp would clip keeps its gradation.
    let (a, b): (Rgb888, Rgb888) = (
        encode_pixel(Rgb::splat(1.5), 1.0, enc),
        encode_pixel(Rgb::splat(2.5), 1.0, enc),
    );
    assert!(a.0[0] < b.0[0] && b.0[0] < 255, "{a:?} {b:?}");
    let clipped: Rgb888 = encode_pixel(Rgb::splat(1.5), 1.0, Encoding::Srgb);
    assert_eq!(clipped.0, [255; 3]);
    assert_eq!(enc.white::<f32>(), 4.0);
    assert_eq!(Encoding::Srgb.white::<f32>(), 1.0);
}

#[test]
fn a_tone_mapped_table_is_within_a_level_of_encode_pixel() {
    // The table spans [0, W] in steps of W / 4096; drawn with the exposure scaled by 1 / W,
    // the index is the prepared path's: the scaled value with 24 fraction bits (rounded), >> 12.
    // Measured worst differences: W = 4, 1 level of RGB565 green and 4 of RGB888 (near black,
    // where one step of 1/1024, which the shift truncates, is 3.2 levels of 8-bit sRGB);
    // W = 2, 1 and 2.
    for (knee, white, bound565, bound888) in [(60, 400, 1, 4), (0, 200, 1, 2)] {
        let tm = ToneMap::new(knee, white).unwrap();
        let enc = Encoding::SrgbTone(tm);
        for (table565, table) in [
            (
                EncodeTable::<Rgb565>::new::<f64>(enc),
                EncodeTable::<Rgb888>::new::<f64>(enc),
            ),
            (EncodeTable::new::<f32>(enc), EncodeTable::new::<f32>(enc)),
            (
                EncodeTable::new::<Fixed22>(enc),
                EncodeTable::new::<Fixed22>(enc),
            ),
        ] {
            assert_eq!(table.encoding(), enc);
            let scale: f64 = table.exposure_scale();
            assert_eq!(scale, 100.0 / f64::from(white));
            let mut worst = [0i32; 2];
            for i in 0..=200_000 {
                let x = 1.2 * tm.white::<f64>() * f64::from(i) / 200_000.0;
                let idx = ((x * scale * 16_777_216.0).round() as i64 >> 12) as i32;
                let c = Rgb::splat(x);
                let a: Rgb565 = table565.pixel(idx, idx, idx);
                let b: Rgb565 = encode_pixel(c, 1.0, enc);
                let d565 = (i32::from(a.0 >> 5 & 63) - i32::from(b.0 >> 5 & 63)).abs();
                let a: Rgb888 = table.pixel(idx, idx, idx);
                let b: Rgb888 = encode_pixel(c, 1.0, enc);
                let d888 = (i32::from(a.0[0]) - i32::from(b.0[0])).abs();
                worst = [worst[0].max(d565), worst[1].max(d888)];
            }
            println!("{enc:?}: worst {worst:?} (RGB565 green, RGB888)");
            assert!(
                worst[0] <= bound565 && worst[1] <= bound888,
                "{enc:?}: {worst:?}"
            );
            let white_px: Rgb888 = table.pixel(4096, 4096, 4096);
            let above: Rgb888 = table.pixel(9999, 9999, 9999);
            assert_eq!((white_px.0, above.0), ([255; 3], [255; 3]));
        }
    }
    // The clamping encodings' tables keep their scale of 1.
    for enc in [Encoding::Linear, Encoding::Gamma2, Encoding::Srgb] {
        assert_eq!(
            EncodeTable::<Rgb565>::new::<f32>(enc).exposure_scale::<f32>(),
            1.0
        );
    }
}

#[test]
fn a_camera_with_k_times_the_viewport_projects_to_k_times_the_pixels() {
    // Camera::with_viewport, for supersampling: the same view, every pixel coordinate scaled.
    use arealight::raster::{Camera, Projection};
    use arealight::Vec3;
    let cam = Camera::new(
        Vec3::new(0.3, 2.7, 5.2),
        Vec3::new(0.0, 0.35, -0.1),
        Vec3::new(0.0, 1.0, 0.0),
        Projection::Perspective { fov_y: 0.73f64 },
        220,
        180,
    )
    .unwrap();
    for k in [1u16, 2, 3, 4] {
        let big = cam.with_viewport(220 * k, 180 * k).unwrap();
        assert_eq!((big.width(), big.height()), (220 * k, 180 * k));
        for p in [[0.0, 0.0, 0.0], [1.0, 0.2, -1.3], [-2.0, 1.5, 0.5]] {
            let p = Vec3::new(p[0], p[1], p[2]);
            let (x, y) = cam.project(p).unwrap();
            let (xk, yk) = big.project(p).unwrap();
            let k = f64::from(k);
            assert!(
                (xk - k * x).abs() < 1e-9 && (yk - k * y).abs() < 1e-9,
                "{k}"
            );
        }
    }
    assert_eq!(
        cam.with_viewport(0, 10),
        Err(RasterError::BadSize("viewport"))
    );
    assert!(cam.with_viewport(4097, 10).is_err());
}
