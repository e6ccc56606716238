//! Shared test support: the independent quadrature ([`quadrature`]), a seeded PRNG, input
//! rounding for the low-precision backends, error tracking, and (in submodules re-exported
//! here) the tolerances, the low-precision backends' error bounds and the case generators.
// `!(a <= b)` is deliberate throughout (it is true when either side is NaN, so a NaN error is
// never taken for a small one); the quadrature's integrands take their parameters one by one.
#![allow(
    dead_code,
    unused_imports,
    clippy::neg_cmp_op_on_partial_ord,
    clippy::too_many_arguments
)]

mod bounds;
mod cases;
pub mod quadrature;
mod tolerance;

pub use bounds::*;
pub use cases::*;
pub use tolerance::*;

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
