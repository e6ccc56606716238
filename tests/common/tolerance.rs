//! The tolerances: f32's and Fast32's against the f64 library, and the f64 library's own
//! budget against the independent references, one row per model ([`F64_BUDGET`]).

use super::*;

// ---------------------------------------------------------------------------------------------
// Tolerances
// ---------------------------------------------------------------------------------------------

/// f32 (libm) vs f64 library on the same rounded inputs.
pub const TOL_F32: f64 = 2e-6;
/// Fast32 vs f64 library on the same rounded inputs.
pub const TOL_FAST32: f64 = 1.0 / 1024.0;

/// One row of the f64 error budget ([`F64_BUDGET`]).
#[derive(Clone, Copy, Debug)]
pub struct F64Row {
    /// The model id (`models.md`), with the case set in parentheses where one set has its own
    /// row.
    pub id: &'static str,
    /// The largest error measured over every case of the suite that checks this row (the tests
    /// print each as a `[maxerr]` line).
    pub measured: f64,
    /// The tolerance asserted: the measured error times 5, rounded up to one significant digit
    /// (5 to 10 times the measured error; [`tol_f64`] refuses a row beyond 100 times).
    pub tol: f64,
    /// The reference and the test files that check it.
    pub against: &'static str,
}

const fn row(id: &'static str, measured: f64, tol: f64, against: &'static str) -> F64Row {
    F64Row {
        id,
        measured,
        tol,
        against,
    }
}

/// The f64 error budget: per model, the largest absolute error of the library's f64 path
/// against its independent reference measured over the whole suite, and the tolerance every
/// test asserts for it (through [`tol_f64`]; one place, as libm keeps one error budget per
/// function). A regression that multiplies a model's error by 10 fails.
pub const F64_BUDGET: &[F64Row] = &[
    row("hemi_const", 5.6e-16, 3e-15, "quadrature: hemisphere.rs"),
    row("hemi_cos", 6.7e-16, 4e-15, "quadrature: hemisphere.rs"),
    row("sky_overcast", 1.2e-15, 6e-15, "quadrature: hemisphere.rs"),
    row("sky_ground", 5.6e-16, 3e-15, "quadrature: hemisphere.rs"),
    row(
        "cap_lambert",
        1.3e-13,
        7e-13,
        "quadrature: cap.rs, adversarial.rs",
    ),
    row(
        "sphere_lambert",
        5.2e-14,
        3e-13,
        "quadrature: cap.rs, adversarial.rs",
    ),
    row(
        "polygon_lambert",
        1.9e-13,
        1e-12,
        "quadrature (two methods): polygon.rs, adversarial.rs",
    ),
    row(
        "line_lambert",
        1.0e-13,
        5e-13,
        "adaptive Gauss-Kronrod, relative to max(1, I): line.rs",
    ),
    row(
        "line_lambert (p within 1e-2 to 1e-6 lengths of a rotated segment)",
        3.9e-10,
        2e-9,
        "the same; f64's own rounding of a - p: line.rs",
    ),
    row(
        "phong_hemi_const",
        1.9e-13,
        1e-12,
        "quadrature: phong.rs, adversarial.rs",
    ),
    row(
        "phong_hemi_cos",
        5.6e-14,
        3e-13,
        "quadrature: phong.rs, adversarial.rs",
    ),
    row(
        "phong_cap",
        2.5e-13,
        2e-12,
        "quadrature: phong.rs, adversarial.rs",
    ),
    row(
        "phong_sphere",
        5.5e-13,
        3e-12,
        "quadrature: phong.rs, adversarial.rs",
    ),
    row(
        "phong_polygon",
        2.2e-13,
        2e-12,
        "quadrature: phong.rs, adversarial.rs",
    ),
    row(
        "phong_hemi_const (m <= 1001)",
        1.7e-12,
        9e-12,
        "sharp-lobe quadrature: large_exponents.rs",
    ),
    row(
        "phong_hemi_cos (m <= 1001)",
        2.3e-13,
        2e-12,
        "sharp-lobe quadrature: large_exponents.rs",
    ),
    row(
        "phong_cap (m <= 1001)",
        1.8e-12,
        9e-12,
        "sharp-lobe quadrature: large_exponents.rs",
    ),
    row(
        "phong_sphere (m <= 1001)",
        6.8e-13,
        4e-12,
        "sharp-lobe quadrature: large_exponents.rs",
    ),
    row(
        "phong_polygon (m <= 1001)",
        6.5e-15,
        4e-14,
        "sharp-lobe quadrature: large_exponents.rs",
    ),
    row(
        "line_phong_peak",
        5.7e-11,
        3e-10,
        "brute force (dense samples, golden section), m <= 1000: line.rs",
    ),
    row(
        "rect_phong_peak",
        6.7e-13,
        4e-12,
        "brute force, m <= 1000: line.rs",
    ),
    row(
        "line_phong_peak (m = 2^16, 2^20)",
        6.0e-10,
        3e-9,
        "brute force, whose own cos^m carries m times its rounding: line.rs",
    ),
    row(
        "rect_phong_peak (m = 2^16, 2^20)",
        7.0e-10,
        4e-9,
        "brute force, as above: line.rs",
    ),
    row("axial_moment", 1.6e-13, 8e-13, "quadrature: moments.rs"),
    row(
        "double_axis_moment",
        5.2e-14,
        3e-13,
        "quadrature: moments.rs",
    ),
    row(
        "directional_luminaire",
        4.3e-12,
        3e-11,
        "quadrature: moments.rs",
    ),
    row(
        "glossy_reflection",
        1.9e-12,
        1e-11,
        "quadrature: moments.rs",
    ),
    row(
        "glossy_transmission",
        2.0e-12,
        1e-11,
        "quadrature: moments.rs",
    ),
    row(
        "lune_normalization",
        4.5e-14,
        3e-13,
        "quadrature: moments.rs",
    ),
    row(
        "sh9_irradiance",
        1.4e-15,
        7e-15,
        "Gauss-Legendre products: sh9.rs",
    ),
    row("sh9_disc_irradiance", 2.7e-15, 2e-14, "quadrature: sh9.rs"),
    row(
        "Sh9::sky_ground",
        1.8e-15,
        9e-15,
        "pi times the sky_ground quadrature: sh9.rs",
    ),
    row(
        "superellipse_shape",
        5.0e-14,
        3e-13,
        "transcription of the definition: shaping.rs",
    ),
    row(
        "distance_falloff",
        1.5e-14,
        8e-14,
        "transcription, relative to max(1, value): shaping.rs",
    ),
    row(
        "uberlight",
        1.1e-13,
        6e-13,
        "transcription, relative to max(1, value): shaping.rs",
    ),
    row(
        "shaping edge cases",
        1.0e-15,
        5e-15,
        "exact values and the transcription: shaping.rs",
    ),
];

/// The f64 tolerance of `id` (a row of [`F64_BUDGET`]); panics on an unknown id or a row whose
/// tolerance is below its measured error or more than 100 times it.
pub fn tol_f64(id: &str) -> f64 {
    let r = F64_BUDGET
        .iter()
        .find(|r| r.id == id)
        .unwrap_or_else(|| panic!("no row {id:?} in the f64 budget (tests/common/tolerance.rs)"));
    assert!(
        r.tol >= r.measured && r.tol <= 100.0 * r.measured,
        "f64 budget row {id:?}: tolerance {:e} must lie within 1 to 100 times the measured {:e}",
        r.tol,
        r.measured
    );
    r.tol
}
