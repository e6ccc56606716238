//! Shared test support: the independent quadrature ([`quadrature`]), a seeded PRNG, input
//! rounding for the low-precision backends, error tracking and case generators.
// `!(a <= b)` is deliberate throughout (it is true when either side is NaN, so a NaN error is
// never taken for a small one); the quadrature's integrands take their parameters one by one.
#![allow(
    dead_code,
    unused_imports,
    clippy::neg_cmp_op_on_partial_ord,
    clippy::too_many_arguments
)]

pub mod quadrature;

use arealight::{Real, Rgb, Vec3};
pub use quadrature::{add, cross, dot, norm, normalize, scale, sub, Quad, V3};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

// ---------------------------------------------------------------------------------------------
// PRNG
// ---------------------------------------------------------------------------------------------

/// splitmix64: small, seeded, deterministic.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed ^ 0x9e37_79b9_7f4a_7c15)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
    /// Uniform in [a, b).
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.unit()
    }
    /// Uniform integer in [0, n).
    pub fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n
    }
    /// Uniform on the unit sphere.
    pub fn dir(&mut self) -> V3 {
        let z = self.range(-1.0, 1.0);
        let phi = self.range(0.0, TAU);
        let s = ((1.0 - z) * (1.0 + z)).sqrt();
        [s * phi.cos(), s * phi.sin(), z]
    }
    /// A direction at angle `w` from the unit vector `axis`, random azimuth.
    pub fn dir_at(&mut self, axis: V3, w: f64) -> V3 {
        let (e1, e2) = frame(axis);
        let phi = self.range(0.0, TAU);
        add(
            scale(axis, w.cos()),
            scale(add(scale(e1, phi.cos()), scale(e2, phi.sin())), w.sin()),
        )
    }
    /// A random direction, randomly scaled (not unit length).
    pub fn sdir(&mut self) -> V3 {
        let d = self.dir();
        self.stretch(d)
    }
    /// A random non-unit scale of a direction (implementations must normalize).
    pub fn stretch(&mut self, v: V3) -> V3 {
        let s = [0.25, 1.0, 3.7][self.below(3) as usize];
        scale(v, s)
    }
}

/// An orthonormal pair perpendicular to the unit vector `a` (right-handed with `a`).
pub fn frame(a: V3) -> (V3, V3) {
    let e1 = quadrature::any_perp(a);
    (e1, cross(a, e1))
}

/// `axis cos(w) + perp sin(w)`: the direction at angle `w` from `axis` toward `perp`.
pub fn rotate_toward(axis: V3, perp: V3, w: f64) -> V3 {
    add(scale(axis, w.cos()), scale(perp, w.sin()))
}

// ---------------------------------------------------------------------------------------------
// Scalar conversion
// ---------------------------------------------------------------------------------------------

pub fn v<T: Real>(a: V3) -> Vec3<T> {
    Vec3::from_f64(a)
}
pub fn rgb<T: Real>(a: V3) -> Rgb<T> {
    Rgb::from_f64(a)
}
/// `x` rounded to `T` and back (the input the low-precision backend actually sees).
pub fn rd<T: Real>(x: f64) -> f64 {
    T::from_f64(x).to_f64()
}
pub fn rdv<T: Real>(a: V3) -> V3 {
    [rd::<T>(a[0]), rd::<T>(a[1]), rd::<T>(a[2])]
}
/// `x` rounded to `T`, stepping down if rounding pushed it above `max` (e.g. pi/2 as f32 is
/// above pi/2), so both backends accept the same value.
pub fn rd_max<T: Real>(x: f64, max: f64) -> f64 {
    let mut y = x.min(max);
    loop {
        let r = rd::<T>(y);
        if r <= max {
            return r;
        }
        y -= 1e-7 * max.abs();
    }
}

// ---------------------------------------------------------------------------------------------
// Error tracking
// ---------------------------------------------------------------------------------------------

/// Max absolute error of one model x backend, with the worst case's description.
pub struct MaxErr {
    pub name: String,
    pub max: f64,
    pub worst: String,
    pub count: usize,
}

impl MaxErr {
    pub fn new(name: &str) -> Self {
        MaxErr {
            name: name.to_string(),
            max: 0.0,
            worst: String::from("(none)"),
            count: 0,
        }
    }
    /// Records `|got - want|`; `case` describes the inputs (only built for a new worst).
    pub fn add<F: FnOnce() -> String>(&mut self, got: f64, want: f64, case: F) {
        self.count += 1;
        let err = if got.is_finite() {
            (got - want).abs()
        } else {
            f64::INFINITY
        };
        if err > self.max || (err.is_nan() && !self.max.is_nan()) {
            self.max = err;
            self.worst = format!("{} | got {got:.17e} want {want:.17e}", case());
        }
    }
    pub fn report(&self) {
        println!(
            "[maxerr] {:<44} max abs err {:.3e} over {} cases; worst: {}",
            self.name, self.max, self.count, self.worst
        );
    }
    /// Prints, then asserts `max <= tol`.
    pub fn check(&self, tol: f64) {
        self.report();
        assert!(
            self.max <= tol,
            "{}: max abs err {:.3e} > {:.1e}; worst case: {}",
            self.name,
            self.max,
            tol,
            self.worst
        );
    }
}

/// Max absolute error and max err/bound per case kind (printed as a breakdown; asserts
/// nothing: the bounds are asserted by [`Bounded`]).
#[derive(Default)]
pub struct ByKind(pub std::collections::BTreeMap<String, (f64, f64)>);

impl ByKind {
    /// Records `|got - want|` and its ratio to `bound` (the case's bound, from
    /// [`Bounded::add`]).
    pub fn add(&mut self, kind: &str, got: f64, want: f64, bound: f64) {
        let e = abs_err(got, want);
        let slot = self.0.entry(kind.to_string()).or_insert((0.0, 0.0));
        if !(e <= slot.0) {
            slot.0 = e;
        }
        if !(e / bound <= slot.1) {
            slot.1 = e / bound;
        }
    }
    pub fn report(&self, title: &str) {
        println!("{title}: max abs err and max err/bound by case kind");
        for (k, (e, r)) in &self.0 {
            println!("    {k:<56} {e:.3e}  (err/bound {r:.3})");
        }
    }
}

/// Checks several trackers, printing all before failing on any.
pub fn check_all(list: &[(&MaxErr, f64)]) {
    for (e, _) in list {
        e.report();
    }
    let bad: Vec<String> = list
        .iter()
        .filter(|(e, tol)| !(e.max <= *tol))
        .map(|(e, tol)| {
            format!(
                "{}: max abs err {:.3e} > {:.1e}; worst case: {}",
                e.name, e.max, tol, e.worst
            )
        })
        .collect();
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

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
        .unwrap_or_else(|| panic!("no row {id:?} in the f64 budget (tests/common/mod.rs)"));
    assert!(
        r.tol >= r.measured && r.tol <= 100.0 * r.measured,
        "f64 budget row {id:?}: tolerance {:e} must lie within 1 to 100 times the measured {:e}",
        r.tol,
        r.measured
    );
    r.tol
}

// ---------------------------------------------------------------------------------------------
// Error bounds of the low-precision backends
// ---------------------------------------------------------------------------------------------
//
// f32 and Fast32 are compared with the f64 library on the same f32-rounded inputs. Every case
// is asserted against its own bound, built by [`f32_bound`] from the case's conditioning
// ([`Cond`]):
//
// - main regime: `TOL` (2e-6 for f32, 1/1024 for Fast32);
// - high m (Phong, f32): `TOL + m 2^-24`: the recurrences raise f32 numbers within an ULP of
//   1 to powers ~m. A Phong case of the main regime whose error exceeds `TOL` is reported
//   under "high m";
// - near boundary (polygons, segments, f32): p within `NEAR_FRACTION size` of the light's
//   boundary (`dist`, the edges as 3D segments; `size` the diameter): the individual edge terms
//   are ill-conditioned although their sum is not: `TOL + m 2^-24 + NEAR_FACTOR 2^-24 size /
//   dist`;
// - ill-conditioned (f32, not near a boundary): the f64 model itself moves by `sens`
//   ([`sensitivity`]) under 1-ULP f32 perturbations of its inputs, and
//   `SENS_FACTOR sens > TOL_F32`: `TOL + m 2^-24 + SENS_FACTOR sens`;
// - beyond the cap: where the f32 bound above exceeds [`BOUND_CAP`] (the models compared
//   this way are normalized or compared relative to `max(1, |value|)`: a bound near 1 asserts
//   nothing), the case belongs to one of two regimes of its own:
//   - "capped": the f64 model resolves the case at f32 precision (`TOL_F32 + SENS_FACTOR sens
//     <= BOUND_CAP`): held to `BOUND_CAP`, f32 and Fast32 alike;
//   - "unresolved": one-ULP f32 changes of the inputs move the f64 model by more than about
//     `BOUND_CAP / 4` (a shading point on a segment or at a polygon's vertex to f32 precision,
//     a falloff at its cut-off): the rounding of the inputs decides the value. Held to the
//     sensitivity bound `TOL + SENS_FACTOR sens` (f32 and Fast32 with their own `TOL`), which
//     still says something while it is well below 1; the cases where it reaches 1 assert only
//     a finite result and are counted apart in the report ("finite only"; the range tests
//     assert the range).
//
// The regime of a case depends on its inputs only (through the f32 bound, whatever the
// backend), except for the main / high m split, and is the same for both backends. Fast32 is
// held to `TOL_FAST32` in every regime below the cap, plus `SENS_FACTOR sens` where the case is
// ill-conditioned (the f64 model's own movement under the f32 rounding of its inputs, which no
// f32-based backend can beat); the arithmetic terms (`m 2^-24`, `size / dist`) do not apply:
// its own approximations dominate. One documented exception, moments.rs near a polygon's
// boundary, where Fast32's atan2 error is amplified like f32's rounding.

/// The largest per-case bound asserted (see the section comment): 1e-2, about 10 times the
/// largest error measured in the "capped" regime.
pub const BOUND_CAP: f64 = 1e-2;

/// 2^-24, the unit roundoff of f32.
pub const EPS_F32: f64 = 1.0 / 16_777_216.0;
/// Ill-conditioned regime: the bound adds `SENS_FACTOR * sensitivity`, and a case belongs to
/// it when that term exceeds `TOL_F32`.
pub const SENS_FACTOR: f64 = 4.0;
/// Near-boundary regime: p within `NEAR_FRACTION * size` of the polygon's boundary.
pub const NEAR_FRACTION: f64 = 0.02;
/// Near-boundary regime: the bound adds `NEAR_FACTOR * 2^-24 * size / dist`.
pub const NEAR_FACTOR: f64 = 16.0;
/// Perturbations per [`sensitivity`] estimate.
pub const SENS_SAMPLES: u64 = 8;

/// `x` (an f32 value) moved by `dir` in {-1, 0, 1} f32 ULPs.
pub fn f32_step(x: f64, dir: i64) -> f64 {
    let f = x as f32;
    debug_assert_eq!(f as f64, x, "f32_step: {x:e} is not an f32 value");
    if dir == 0 || !f.is_finite() {
        return x;
    }
    let up = dir > 0;
    let g = if f == 0.0 {
        let tiny = f32::from_bits(1);
        if up {
            tiny
        } else {
            -tiny
        }
    } else if (f > 0.0) == up {
        f32::from_bits(f.to_bits() + 1) // away from zero
    } else {
        f32::from_bits(f.to_bits() - 1) // toward zero
    };
    g as f64
}

/// How much the f64 model moves under f32 rounding of its inputs: the max of
/// `|f(x') - f(x)|` over [`SENS_SAMPLES`] perturbations `x'` of `x` (every input, already an
/// f32 value, moved by -1, 0 or +1 f32 ULP in a deterministic pseudo-random pattern seeded by
/// `x`). `f` evaluates the f64 model from the flat inputs, `None` when its constructor fails;
/// such perturbations are skipped and replaced, up to `4 SENS_SAMPLES` tries (a polygon whose
/// vertices move may fail the planarity check). 0 if `f(x)` is `None`.
pub fn sensitivity<F: FnMut(&[f64]) -> Option<f64>>(mut f: F, x: &[f64]) -> f64 {
    let Some(f0) = f(x) else {
        return 0.0;
    };
    let seed = x.iter().fold(0x5e45_171f_u64, |h, &xi| {
        (h ^ xi.to_bits()).wrapping_mul(0x100_0000_01b3)
    });
    let mut rng = Rng::new(seed);
    let mut y = x.to_vec();
    let mut max = 0.0f64;
    let mut used = 0;
    for _ in 0..4 * SENS_SAMPLES {
        for (yi, &xi) in y.iter_mut().zip(x) {
            *yi = f32_step(xi, rng.below(3) as i64 - 1);
        }
        if let Some(fy) = f(&y) {
            let d = (fy - f0).abs();
            if !(d <= max) {
                max = d;
            }
            used += 1;
            if used == SENS_SAMPLES {
                break;
            }
        }
    }
    max
}

/// The `i`-th 3-vector of a flat input slice.
pub fn v3_at(x: &[f64], i: usize) -> V3 {
    [x[3 * i], x[3 * i + 1], x[3 * i + 2]]
}

/// Flattens 3-vectors and scalars into one input slice for [`sensitivity`].
pub fn flat(vecs: &[V3], scalars: &[f64]) -> Vec<f64> {
    vecs.iter()
        .flatten()
        .copied()
        .chain(scalars.iter().copied())
        .collect()
}

/// Distance from `p` to the polygon's boundary (its edges as 3D segments).
pub fn boundary_distance(verts: &[V3], p: V3) -> f64 {
    (0..verts.len())
        .map(|i| {
            let (a, b) = (verts[i], verts[(i + 1) % verts.len()]);
            let ab = sub(b, a);
            let t = (dot(sub(p, a), ab) / dot(ab, ab)).clamp(0.0, 1.0);
            norm(sub(p, add(a, scale(ab, t))))
        })
        .fold(f64::INFINITY, f64::min)
}

/// The polygon's diameter (largest vertex-to-vertex distance).
pub fn diameter(verts: &[V3]) -> f64 {
    let mut d = 0.0f64;
    for (i, &a) in verts.iter().enumerate() {
        for &b in &verts[i + 1..] {
            d = d.max(norm(sub(a, b)));
        }
    }
    d
}

/// `Some((size, dist))` (diameter, distance from `p` to the boundary) when `p` is within
/// `NEAR_FRACTION * size` of the polygon's boundary.
pub fn near_boundary(verts: &[V3], p: V3) -> Option<(f64, f64)> {
    let (size, dist) = (diameter(verts), boundary_distance(verts, p));
    (dist < NEAR_FRACTION * size).then_some((size, dist))
}

/// Whether a case whose f64 model moves by `sens` under 1-ULP f32 input perturbations is in
/// the ill-conditioned regime.
pub fn ill_conditioned(sens: f64) -> bool {
    SENS_FACTOR * sens > TOL_F32
}

/// The f32-vs-f64 bound of one case with Phong exponent `m` (0 for other models), f64-model
/// sensitivity `sens` and `near_boundary = Some((size, dist))` for a polygon near its boundary:
/// `tol + m 2^-24`, plus `NEAR_FACTOR 2^-24 size / dist` near the boundary, else plus
/// `SENS_FACTOR sens` if the case is ill-conditioned. Uncapped: see [`Bounded::classify`].
pub fn f32_bound(tol: f64, m: u32, sens: f64, near_boundary: Option<(f64, f64)>) -> f64 {
    let base = tol + m as f64 * EPS_F32;
    match near_boundary {
        Some((size, dist)) => base + NEAR_FACTOR * EPS_F32 * size / dist,
        None if ill_conditioned(sens) => base + SENS_FACTOR * sens,
        None => base,
    }
}

/// The regime of a case whose f32 bound exceeds [`BOUND_CAP`]: `Some(Capped)` where the f64
/// model resolves it at f32 precision (`TOL_F32 + SENS_FACTOR sens <= BOUND_CAP`),
/// `Some(Unresolved)` where it does not, `None` below the cap.
pub fn beyond_cap(c: &Cond) -> Option<Regime> {
    if !(f32_bound(TOL_F32, c.m, c.sens, c.near) > BOUND_CAP) {
        None
    } else if TOL_F32 + SENS_FACTOR * c.sens <= BOUND_CAP {
        Some(Regime::Capped)
    } else {
        Some(Regime::Unresolved)
    }
}

/// The conditioning of one case: Phong exponent (0 for other models), the f64 model's
/// sensitivity ([`sensitivity`]) and, for polygons near their boundary, `(size, dist)`
/// ([`near_boundary`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct Cond {
    pub m: u32,
    pub sens: f64,
    pub near: Option<(f64, f64)>,
}

/// A low-precision backend's bounds: its main tolerance, and whether the extra terms of
/// [`f32_bound`] apply (f32) or every case is held to `tol` plus the sensitivity term where the
/// case is ill-conditioned (Fast32).
#[derive(Clone, Copy, Debug)]
pub struct LowpBounds {
    pub tol: f64,
    pub extra_terms: bool,
}

pub const BOUNDS_F32: LowpBounds = LowpBounds {
    tol: TOL_F32,
    extra_terms: true,
};
pub const BOUNDS_FAST32: LowpBounds = LowpBounds {
    tol: TOL_FAST32,
    extra_terms: false,
};

/// The regimes of the low-precision bounds (see the section comment).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Regime {
    Main,
    HighM,
    IllConditioned,
    NearBoundary,
    Capped,
    Unresolved,
}

impl Regime {
    pub fn label(self) -> &'static str {
        match self {
            Regime::Main => "main",
            Regime::HighM => "high m",
            Regime::IllConditioned => "ill-conditioned",
            Regime::NearBoundary => "near boundary",
            Regime::Capped => "capped",
            Regime::Unresolved => "unresolved",
        }
    }
}

/// One regime's statistics in a [`Bounded`].
#[derive(Clone, Debug)]
pub struct RegimeStat {
    pub count: usize,
    /// Cases whose bound is 1 or more (only a finite result asserted: "unresolved" regime).
    pub finite_only: usize,
    pub max_err: f64,
    pub worst_err: String,
    pub max_ratio: f64,
    pub worst_ratio: String,
}

/// Per-case bounds of one model x low-precision backend: per regime the max absolute error
/// and the max err/bound, with the cases attaining them; every case exceeding its bound is
/// recorded in full.
pub struct Bounded {
    pub name: String,
    pub bounds: LowpBounds,
    pub stats: std::collections::BTreeMap<Regime, RegimeStat>,
    pub failures: Vec<String>,
}

/// `|got - want|`, infinite for a non-finite `got`.
pub fn abs_err(got: f64, want: f64) -> f64 {
    if got.is_finite() {
        (got - want).abs()
    } else {
        f64::INFINITY
    }
}

impl Bounded {
    pub fn new(name: &str, bounds: LowpBounds) -> Self {
        Bounded {
            name: name.to_string(),
            bounds,
            stats: Default::default(),
            failures: Vec::new(),
        }
    }

    /// The regime and bound of a case with error `err`. A main-regime case is held to `tol`;
    /// an f32 Phong case of the main regime above `tol` is "high m", held to `tol + m 2^-24`.
    /// Beyond the cap ([`beyond_cap`]): "capped", held to [`BOUND_CAP`], or "unresolved",
    /// held to `tol + SENS_FACTOR sens`.
    pub fn classify(&self, err: f64, c: &Cond) -> (Regime, f64) {
        let tol = self.bounds.tol;
        match beyond_cap(c) {
            Some(Regime::Capped) => return (Regime::Capped, BOUND_CAP),
            Some(r) => return (r, tol + SENS_FACTOR * c.sens),
            None => {}
        }
        let regime = if c.near.is_some() {
            Regime::NearBoundary
        } else if ill_conditioned(c.sens) {
            Regime::IllConditioned
        } else if err <= tol || !self.bounds.extra_terms || c.m == 0 {
            Regime::Main
        } else {
            Regime::HighM
        };
        let bound = if !self.bounds.extra_terms {
            if ill_conditioned(c.sens) {
                tol + SENS_FACTOR * c.sens
            } else {
                tol
            }
        } else if regime == Regime::Main {
            tol
        } else {
            f32_bound(tol, c.m, c.sens, c.near)
        };
        (regime, bound)
    }

    /// Records `|got - want|` against the case's bound and returns the bound; `case` describes
    /// the inputs (only built for a new worst or a failure).
    pub fn add<F: Fn() -> String>(&mut self, got: f64, want: f64, c: Cond, case: F) -> f64 {
        let err = abs_err(got, want);
        let (regime, bound) = self.classify(err, &c);
        let ratio = err / bound;
        let s = self.stats.entry(regime).or_insert_with(|| RegimeStat {
            count: 0,
            finite_only: 0,
            max_err: 0.0,
            worst_err: String::from("(none)"),
            max_ratio: 0.0,
            worst_ratio: String::from("(none)"),
        });
        s.count += 1;
        if bound >= 1.0 {
            s.finite_only += 1;
        }
        let detail = || {
            format!(
                "{} | got {got:.17e} want {want:.17e} err {err:.3e} sens {:.3e} bound {bound:.3e}",
                case(),
                c.sens
            )
        };
        if !(err <= s.max_err) {
            s.max_err = err;
            s.worst_err = detail();
        }
        if !(ratio <= s.max_ratio) {
            s.max_ratio = ratio;
            s.worst_ratio = detail();
        }
        if !(err <= bound) {
            self.failures.push(format!(
                "{} [{}] exceeds its bound: m={} near={:?} {}",
                self.name,
                regime.label(),
                c.m,
                c.near,
                detail()
            ));
        }
        bound
    }

    /// Prints one `[maxerr]` line per non-empty regime.
    pub fn report(&self) {
        for (r, s) in &self.stats {
            let head = format!("{} [{}]", self.name, r.label());
            let head = if s.finite_only > 0 {
                format!("{head} ({} with a bound >= 1: finite only)", s.finite_only)
            } else {
                head
            };
            if s.worst_err == s.worst_ratio {
                println!(
                    "[maxerr] {head:<56} max abs err {:.3e}, max err/bound {:.3} over {} cases; worst: {}",
                    s.max_err, s.max_ratio, s.count, s.worst_err
                );
            } else {
                println!(
                    "[maxerr] {head:<56} max abs err {:.3e}, max err/bound {:.3} over {} cases; worst err: {}; worst err/bound: {}",
                    s.max_err, s.max_ratio, s.count, s.worst_err, s.worst_ratio
                );
            }
        }
    }
}

/// Reports several [`Bounded`] trackers, prints every case that exceeds its bound, then fails
/// if there is any.
pub fn check_bounded(list: &[&Bounded]) {
    for b in list {
        b.report();
    }
    let bad: Vec<&String> = list.iter().flat_map(|b| b.failures.iter()).collect();
    for f in &bad {
        println!("[maxerr] BOUND EXCEEDED: {f}");
    }
    assert!(
        bad.is_empty(),
        "{} case(s) exceed their bound; first: {}",
        bad.len(),
        bad[0]
    );
}

/// The Phong exponents every Phong test covers.
pub const EXPONENTS: [u32; 7] = [0, 1, 2, 3, 63, 64, 255];

// ---------------------------------------------------------------------------------------------
// Cap configurations
// ---------------------------------------------------------------------------------------------

/// Half-angles sigma worth testing: 0, tiny, small, mid, near pi/2, exactly pi/2.
pub fn sigma_grid() -> Vec<f64> {
    vec![
        0.0,
        1e-9,
        1e-6,
        1e-3,
        0.0047,
        0.05,
        PI / 16.0,
        0.3,
        PI / 8.0,
        0.6,
        PI / 4.0,
        1.0,
        3.0 * PI / 8.0,
        1.4,
        FRAC_PI_2 - 1e-3,
        FRAC_PI_2 - 1e-6,
        FRAC_PI_2 - 1e-9,
        FRAC_PI_2,
    ]
}

/// Angles w between the weight axis and the source axis worth testing for a cap of half-angle
/// `sigma`: both ends, the tangencies w = pi/2 +- sigma and just either side, w = sigma
/// (the cap touches the weight axis), pi/2, and a few interior values.
pub fn w_grid(sigma: f64) -> Vec<f64> {
    let mut ws = vec![
        0.0,
        1e-9,
        1e-4,
        0.3,
        1.0,
        FRAC_PI_2,
        2.0,
        2.8,
        PI - 1e-6,
        PI,
    ];
    for c in [FRAC_PI_2 - sigma, FRAC_PI_2 + sigma, sigma] {
        for d in [-1e-3, -1e-7, 0.0, 1e-7, 1e-3] {
            ws.push(c + d);
        }
    }
    ws.retain(|w| (0.0..=PI).contains(w));
    ws
}

/// (axis, sigma, n): the sigma grid x the w grid (tangencies w = pi/2 +- sigma and either
/// side, w = sigma, both ends), random orientation, plus random cases.
pub fn cap_cases(rng: &mut Rng, random: usize) -> Vec<(V3, f64, V3)> {
    let mut out = Vec::new();
    for sigma in sigma_grid() {
        for w in w_grid(sigma) {
            let a = rng.dir();
            let n = rng.dir_at(a, w);
            out.push((rng.stretch(a), sigma, rng.stretch(n)));
        }
    }
    for _ in 0..random {
        let a = rng.dir();
        let n = rng.dir();
        out.push((rng.stretch(a), rng.range(0.0, FRAC_PI_2), n));
    }
    out
}

/// (center, radius, p, n): distances from 1.001 radii (very close) to 1000 radii, n random and
/// at the tangencies of the sphere's cap.
pub fn sphere_cases(rng: &mut Rng, random: usize) -> Vec<(V3, f64, V3, V3)> {
    let mut out = Vec::new();
    let ratios = [1.001, 1.01, 1.2, 2.0, 10.0, 1000.0];
    for (i, &ratio) in ratios.iter().cycle().take(6 * 12).enumerate() {
        let radius = rng.range(0.1, 3.0);
        let center = scale(rng.dir(), rng.range(0.0, 5.0));
        let toward = rng.dir();
        let p = sub(center, scale(toward, ratio * radius));
        let sigma = (1.0 / ratio).asin();
        let w = match i / 6 % 6 {
            0 => FRAC_PI_2 - sigma,
            1 => FRAC_PI_2 + sigma,
            2 => FRAC_PI_2,
            3 => 0.0,
            4 => PI,
            _ => rng.range(0.0, PI),
        };
        let n = rng.dir_at(toward, w);
        out.push((center, radius, p, n));
    }
    for _ in 0..random {
        let radius = rng.range(0.05, 2.0);
        let center = scale(rng.dir(), rng.range(0.0, 3.0));
        let d = radius * (1.0 + rng.range(0.0, 1.0).powi(3) * 20.0) + 1e-3;
        let p = add(center, scale(rng.dir(), d));
        let n = rng.sdir();
        out.push((center, radius, p, n));
    }
    out
}

// ---------------------------------------------------------------------------------------------
// Polygon configurations
// ---------------------------------------------------------------------------------------------

/// A polygon light case: vertices, shading point, and a weight axis (n or r).
#[derive(Clone, Debug)]
pub struct PolyCase {
    pub kind: String,
    pub verts: Vec<V3>,
    pub p: V3,
    pub k: V3,
}

impl PolyCase {
    pub fn describe(&self) -> String {
        format!(
            "{} verts={:?} p={:?} k={:?}",
            self.kind, self.verts, self.p, self.k
        )
    }
}

/// Places 2D outline points in 3D: `center + size (x e1 + y e2)` for a random plane.
pub fn place(rng: &mut Rng, pts: &[[f64; 2]], center: V3, size: f64) -> Vec<V3> {
    let nrm = rng.dir();
    let (e1, e2) = frame(nrm);
    // A random in-plane rotation.
    let t = rng.range(0.0, TAU);
    let (c, s) = (t.cos(), t.sin());
    pts.iter()
        .map(|&[x, y]| {
            let (x, y) = (c * x - s * y, s * x + c * y);
            add(center, scale(add(scale(e1, x), scale(e2, y)), size))
        })
        .collect()
}

/// A random star-shaped (hence simple) outline with `k` vertices; may be non-convex.
pub fn star_shaped(rng: &mut Rng, k: usize, rmin: f64) -> Vec<[f64; 2]> {
    (0..k)
        .map(|j| {
            let a = TAU * (j as f64 + rng.range(0.0, 0.8)) / k as f64;
            let r = rng.range(rmin, 1.0);
            [r * a.cos(), r * a.sin()]
        })
        .collect()
}

/// A regular star with `k` spikes (2k vertices), inner radius `ri`.
pub fn star(k: usize, ri: f64) -> Vec<[f64; 2]> {
    (0..2 * k)
        .map(|j| {
            let a = PI * j as f64 / k as f64;
            let r = if j % 2 == 0 { 1.0 } else { ri };
            [r * a.cos(), r * a.sin()]
        })
        .collect()
}

/// An L-shape (6 vertices, one reflex corner).
pub fn l_shape() -> Vec<[f64; 2]> {
    vec![
        [-0.5, -0.5],
        [0.7, -0.5],
        [0.7, -0.1],
        [-0.1, -0.1],
        [-0.1, 0.6],
        [-0.5, 0.6],
    ]
}

/// A U-shape (8 vertices, two reflex corners): a horizon through the notch clips it into two.
pub fn u_shape() -> Vec<[f64; 2]> {
    vec![
        [-0.6, -0.5],
        [0.6, -0.5],
        [0.6, 0.6],
        [0.3, 0.6],
        [0.3, -0.1],
        [-0.3, -0.1],
        [-0.3, 0.6],
        [-0.6, 0.6],
    ]
}

/// Random polygon cases: random shapes and placements, random weight axis (so most cases cross
/// the horizon somewhere). At most 8 vertices.
pub fn random_polygons(rng: &mut Rng, count: usize) -> Vec<PolyCase> {
    let mut out = Vec::with_capacity(count);
    for i in 0..count {
        let (kind, pts): (&str, _) = match i % 5 {
            0 => ("triangle", star_shaped(rng, 3, 0.3)),
            1 => ("quad", star_shaped(rng, 4, 0.3)),
            2 => ("star-shaped-7", star_shaped(rng, 7, 0.2)),
            3 => ("L-shape", l_shape()),
            _ => ("U-shape", u_shape()),
        };
        let dist = rng.range(0.3, 3.0);
        let center = scale(rng.dir(), dist);
        let size = rng.range(0.2, 2.0);
        let verts = place(rng, &pts, center, size);
        let d = rng.dir();
        let k = rng.stretch(d);
        out.push(PolyCase {
            kind: kind.to_string(),
            verts,
            p: [0.0; 3],
            k,
        });
    }
    out
}

/// Adversarial polygon cases (at most 8 vertices): partly below the horizon (including the
/// horizon through a vertex and through the notch of non-convex shapes), wholly below, nearly
/// edge-on to p (foot outside and inside), p close to a vertex or an edge, stars.
pub fn adversarial_polygons(rng: &mut Rng) -> Vec<PolyCase> {
    let mut out = Vec::new();
    let shapes: Vec<(&'static str, Vec<[f64; 2]>)> = vec![
        ("square", vec![[-1., -1.], [1., -1.], [1., 1.], [-1., 1.]]),
        ("triangle", vec![[-1., -0.7], [1.2, -0.4], [0.1, 1.0]]),
        ("L-shape", l_shape()),
        ("U-shape", u_shape()),
        ("star4", star(4, 0.3)),
    ];
    for (name, pts) in &shapes {
        // The plane z = 1 (normal +z), outline scaled by s, shifted by (ox, oy).
        for &(s, ox, oy) in &[(1.0, 0.0, 0.0), (0.8, 0.9, 0.2), (0.5, 2.5, 0.0)] {
            let verts: Vec<V3> = pts
                .iter()
                .map(|&[x, y]| [ox + s * x, oy + s * y, 1.0])
                .collect();
            // Weight axes: straight at it, tilted so the horizon cuts the polygon at several
            // places, through a vertex, through the notch, edge-on, facing away.
            let mut ks: Vec<V3> = vec![[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]];
            for t in [
                0.3,
                0.7,
                1.2,
                FRAC_PI_2 - 0.05,
                FRAC_PI_2,
                FRAC_PI_2 + 0.2,
                2.5,
            ] {
                for az in [0.0, 0.9, 2.0, 4.0] {
                    ks.push([t.sin() * f64::cos(az), t.sin() * f64::sin(az), t.cos()]);
                }
            }
            // Horizon exactly through vertex 0: k perpendicular to verts[0] (p at origin).
            let v0 = verts[0];
            ks.push(normalize(cross(v0, [0.3, 1.0, 0.2])));
            // Horizon through the polygon's centroid direction along x.
            ks.push([1.0, 0.0, 0.0]);
            ks.push([-1.0, 0.0, 0.0]);
            ks.push([0.0, 1.0, 0.0]);
            for k in ks {
                out.push(PolyCase {
                    kind: format!("{name}, horizon cuts"),
                    verts: verts.clone(),
                    p: [0.0; 3],
                    k,
                });
            }
        }
        // Nearly edge-on: p at height h above the plane z = 1 (relative to size 1).
        for &h in &[1e-2, 1e-4, 1e-6] {
            for &(fx, fy, tag) in &[
                (0.0, 0.0, "foot inside"),
                (1.3, 0.1, "foot outside near edge"),
                (3.0, 2.0, "foot far outside"),
                (1.0 + 1e-3, 0.0, "foot just outside edge"),
            ] {
                let verts: Vec<V3> = pts.iter().map(|&[x, y]| [x, y, 1.0]).collect();
                let p = [fx, fy, 1.0 - h];
                for k in [
                    [0.0, 0.0, 1.0],
                    [0.3, 0.2, 1.0],
                    [1.0, 0.0, 0.05],
                    [-1.0, 0.3, 0.0],
                    [0.0, 0.0, -1.0],
                    [0.2, -1.0, 0.3],
                ] {
                    out.push(PolyCase {
                        kind: format!("{name}, edge-on h={h:e}, {tag}"),
                        verts: verts.clone(),
                        p,
                        k,
                    });
                }
            }
        }
        // p close to a vertex and to an edge midpoint (distance 1e-3).
        let verts: Vec<V3> = pts.iter().map(|&[x, y]| [x, y, 1.0]).collect();
        let mid = scale(add(verts[0], verts[1]), 0.5);
        for p in [
            sub(verts[0], [0.0, 0.0, 1e-3]),
            sub(mid, [0.0, 0.0, 1e-3]),
            sub(verts[1], [1e-3, 1e-3, 1e-3]),
        ] {
            for k in [[0.0, 0.0, 1.0], [0.5, 0.5, 0.7], [1.0, -0.2, 0.0]] {
                out.push(PolyCase {
                    kind: format!("{name}, p near vertex/edge"),
                    verts: verts.clone(),
                    p,
                    k,
                });
            }
        }
    }
    // A random rigid motion of everything, so no case is axis aligned.
    let rot = {
        let a = rng.dir();
        let (b, c) = frame(a);
        [a, b, c]
    };
    let shift = scale(rng.dir(), rng.range(0.0, 5.0));
    let tr = |x: V3| add([dot(rot[0], x), dot(rot[1], x), dot(rot[2], x)], shift);
    let rt = |x: V3| [dot(rot[0], x), dot(rot[1], x), dot(rot[2], x)];
    for c in &mut out {
        c.verts = c.verts.iter().map(|&x| tr(x)).collect();
        c.p = tr(c.p);
        c.k = rt(c.k);
    }
    out
}

/// Extremely edge-on cases: p at height h in {1e-8, 1e-10, 1e-12} (relative to size 1) below
/// the plane of a triangle, a square and an L-shape, the foot inside (and, for the L, in the
/// notch), with weight axes tilted so the horizon cuts the projection (f64 only: rounding the
/// inputs to f32 moves p by more than h).
pub fn extreme_edge_on(rng: &mut Rng) -> Vec<PolyCase> {
    let shapes: Vec<(&'static str, Vec<[f64; 2]>)> = vec![
        ("triangle", vec![[-1., -0.7], [1.2, -0.4], [0.1, 1.0]]),
        ("square", vec![[-1., -1.], [1., -1.], [1., 1.], [-1., 1.]]),
        ("L-shape", l_shape()),
    ];
    let mut out = Vec::new();
    for (name, pts) in &shapes {
        let verts: Vec<V3> = pts.iter().map(|&[x, y]| [x, y, 1.0]).collect();
        for &h in &[1e-8, 1e-10, 1e-12] {
            for foot in [[0.05, 0.02], [-0.3, -0.3], [0.2, 0.3]] {
                for k in [
                    [0.6, -0.2, 0.8],
                    [1.0, 0.3, 0.01],
                    [0.2, 1.0, -0.3],
                    [0.0, 0.0, 1.0],
                ] {
                    out.push(PolyCase {
                        kind: format!("{name}, h={h:e}"),
                        verts: verts.clone(),
                        p: [foot[0], foot[1], 1.0 - h],
                        k,
                    });
                }
            }
        }
    }
    // A random rotation about the origin (kept small in size so h stays representable).
    let rot = {
        let a = rng.dir();
        let (b, c) = frame(a);
        [a, b, c]
    };
    let rt = |x: V3| [dot(rot[0], x), dot(rot[1], x), dot(rot[2], x)];
    for c in &mut out {
        c.verts = c.verts.iter().map(|&x| rt(x)).collect();
        c.p = rt(c.p);
        c.k = rt(c.k);
    }
    out
}

/// `PI` re-exported for brevity in test files.
pub const PI_: f64 = PI;

/// The power of two that brings every coordinate of `pts` within `Fixed22`'s
/// `COORDINATE_LIMIT` (exact in f64; the area-light models are scale invariant, so the scaled
/// case is the same case for the model): the fixed-point tests' way into the cube.
pub fn fit_scale(pts: &[V3]) -> f64 {
    let m = pts
        .iter()
        .flat_map(|p| p.iter())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let mut s = 1.0;
    while m * s > arealight::Fixed22::COORDINATE_LIMIT {
        s *= 0.5;
    }
    s
}

/// A random convex polygon of 3 to 8 vertices on an ellipse in a random plane through `c`:
/// semi-axes `size` and `size` times 0.3 to 1, the vertices at jittered equal angles.
pub fn ellipse_polygon(rng: &mut Rng, c: V3, size: f64) -> Vec<V3> {
    let (e1, e2) = frame(rng.dir());
    let k = 3 + rng.below(6) as usize;
    let b = size * rng.range(0.3, 1.0);
    let phase = rng.range(0.0, 1.0);
    (0..k)
        .map(|i| {
            let t = TAU * (i as f64 + phase + rng.range(-0.3, 0.3)) / k as f64;
            add(c, add(scale(e1, size * t.cos()), scale(e2, b * t.sin())))
        })
        .collect()
}
