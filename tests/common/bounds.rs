//! The error bounds of the low-precision backends: each case's conditioning ([`Cond`]), its
//! regime and bound ([`f32_bound`]), and the per-case tracking ([`Bounded`]).

use super::*;

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
