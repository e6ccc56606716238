//! The f32 arc tangent (`<f32 as Real>::atan2`, the crate's own polynomial in
//! `src/real/f32_math.rs`) against the f64 reference, next to `libm::atan2f`/`atanf` measured
//! the same way, and its special values against libm's bit for bit.
//!
//! Every call names the trait (`Real::atan2(y, x)`): `y.atan2(x)` on an `f32` is std's inherent
//! method (the host's libm), not the crate's.
//!
//! The sweeps here are strided so that the suite stays fast; `atan_on_unit_interval_exhaustive`
//! (ignored by default: `cargo test --release --test real_f32_math -- --ignored`) checks every
//! f32 in [0, 1].

use arealight::Real;

/// The spacing of f32 values at `x` (the ULP of the f32 nearest `x`).
fn ulp(x: f64) -> f64 {
    let r = (x.abs() as f32).max(f32::MIN_POSITIVE);
    f64::from(f32::from_bits(r.to_bits() + 1) - r)
}

/// Worst errors of one function against the f64 reference: (ULP, absolute, at which input).
#[derive(Default)]
struct Worst {
    ulp: f64,
    abs: f64,
    at: (f32, f32),
}
impl Worst {
    fn add(&mut self, got: f32, want: f64, at: (f32, f32)) {
        let e = (f64::from(got) - want).abs();
        let u = e / ulp(want);
        if u > self.ulp {
            self.ulp = u;
            self.at = at;
        }
        self.abs = self.abs.max(e);
    }
}

/// `atan t` for `t = f32::from_bits(b)`, `b` in `bits` (the crate's through `atan2(t, 1)`,
/// which divides by 1 exactly): worst errors of ours and of `libm::atanf`.
fn atan_unit_sweep(bits: impl Iterator<Item = u32>) -> (Worst, Worst) {
    let (mut ours, mut libm) = (Worst::default(), Worst::default());
    for b in bits {
        let t = f32::from_bits(b);
        let want = f64::from(t).atan();
        ours.add(Real::atan2(t, 1.0), want, (t, 1.0));
        libm.add(libm::atanf(t), want, (t, 1.0));
    }
    (ours, libm)
}

const ONE_BITS: u32 = 0x3F80_0000;

#[test]
fn atan_on_unit_interval_strided() {
    // Every 7th pattern from 0 to 1 (1.5e8 values): every binade, subnormals included.
    let (ours, libm) = atan_unit_sweep((0..=ONE_BITS).step_by(7));
    println!(
        "atan on [0, 1], every 7th f32: ours {:.3} ULP, {:.3e} abs (worst at t = {:e}); libm::atanf {:.3} ULP, {:.3e} abs",
        ours.ulp, ours.abs, ours.at.0, libm.ulp, libm.abs
    );
    assert!(ours.ulp <= 1.35, "atan {} ULP at {:e}", ours.ulp, ours.at.0);
    assert!(ours.abs <= 8.0e-8, "atan {:e} abs", ours.abs);
}

#[test]
#[ignore = "every f32 in [0, 1] (1.07e9 values): run in release with --ignored"]
fn atan_on_unit_interval_exhaustive() {
    let threads = 4u32;
    let chunk = ONE_BITS / threads + 1;
    let parts: Vec<(Worst, Worst)> = std::thread::scope(|s| {
        let hs: Vec<_> = (0..threads)
            .map(|i| {
                s.spawn(move || {
                    let lo = i * chunk;
                    let hi = (lo + chunk).min(ONE_BITS + 1);
                    atan_unit_sweep(lo..hi)
                })
            })
            .collect();
        hs.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let mut ours = Worst::default();
    let mut libm = Worst::default();
    for (o, l) in parts {
        if o.ulp > ours.ulp {
            ours.ulp = o.ulp;
            ours.at = o.at;
        }
        ours.abs = ours.abs.max(o.abs);
        libm.ulp = libm.ulp.max(l.ulp);
        libm.abs = libm.abs.max(l.abs);
    }
    println!(
        "atan on [0, 1], every f32: ours {:.3} ULP, {:.3e} abs (worst at t = {:e}); libm::atanf {:.3} ULP, {:.3e} abs",
        ours.ulp, ours.abs, ours.at.0, libm.ulp, libm.abs
    );
    assert!(ours.ulp <= 1.35, "atan {} ULP at {:e}", ours.ulp, ours.at.0);
    assert!(ours.abs <= 8.0e-8, "atan {:e} abs", ours.abs);
}

/// Every quadrant and octant boundary: 2^20 angles around the circle (plus the exact axes and
/// diagonals) at magnitudes from 1e-30 to 1e30, and unequal magnitudes of `y` and `x`.
#[test]
fn atan2_dense_sweep_all_quadrants() {
    let (mut ours, mut libm) = (Worst::default(), Worst::default());
    let n = 1 << 20;
    for i in 0..n {
        let phi =
            (f64::from(i) + 0.5) / f64::from(n) * std::f64::consts::TAU - std::f64::consts::PI;
        let r = [1e-30, 3.7e-12, 1.0, 0.61, 4.2e7, 1e30][i as usize % 6];
        let (y, x) = ((r * phi.sin()) as f32, (r * phi.cos()) as f32);
        let want = f64::from(y).atan2(f64::from(x));
        ours.add(Real::atan2(y, x), want, (y, x));
        libm.add(libm::atan2f(y, x), want, (y, x));
    }
    // Ratios over the whole range (t = y/x from 2^-149 to 2^127), every sign.
    for b in (1..0x7F80_0000u32).step_by(997) {
        let t = f32::from_bits(b);
        for (y, x) in [
            (t, 1.0f32),
            (1.0, t),
            (-t, -1.0),
            (t, -1.0),
            (-1.0, t),
            (1.0, -t),
        ] {
            let want = f64::from(y).atan2(f64::from(x));
            ours.add(Real::atan2(y, x), want, (y, x));
            libm.add(libm::atan2f(y, x), want, (y, x));
        }
    }
    println!(
        "atan2: ours {:.3} ULP, {:.3e} rad abs (worst at y = {:e}, x = {:e}); libm::atan2f {:.3} ULP, {:.3e} rad abs",
        ours.ulp, ours.abs, ours.at.0, ours.at.1, libm.ulp, libm.abs
    );
    assert!(ours.ulp <= 2.0, "atan2 {} ULP at {:?}", ours.ulp, ours.at);
    assert!(ours.abs <= 2.5e-7, "atan2 {:e} abs", ours.abs);
}

/// Signed zeros, infinities and NaN: NaN where `libm::atan2f` gives NaN, the same bits where
/// it gives a zero or +-pi (the sign of a zero `y` selects `pi` or `-pi`: the models rely on
/// this), and otherwise the f32 nearest the exact angle (`pi/2`, `pi/4`, `3 pi/4`: libm's
/// `atanf` returns the f32 just below `pi/2` for infinite arguments, one ULP off).
#[test]
fn atan2_special_values() {
    let specials = [
        0.0f32,
        -0.0,
        1.0,
        -1.0,
        f32::MIN_POSITIVE,
        -f32::from_bits(1),
        f32::MAX,
        -f32::MAX,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        -f32::NAN,
    ];
    for y in specials {
        for x in specials {
            let (a, b) = (Real::atan2(y, x), libm::atan2f(y, x));
            if b.is_nan() {
                assert!(a.is_nan(), "atan2({y:e}, {x:e}) = {a:e}, libm NaN");
                continue;
            }
            let want = f64::from(y).atan2(f64::from(x));
            if b == 0.0 || b.abs() == core::f32::consts::PI {
                assert_eq!(
                    a.to_bits(),
                    b.to_bits(),
                    "atan2({y:e}, {x:e}) = {a:e}, libm {b:e}"
                );
            } else if y.is_infinite() || x.is_infinite() {
                assert_eq!(
                    a, want as f32,
                    "atan2({y:e}, {x:e}) = {a:e}, exact {want:e}"
                );
            } else {
                assert!(
                    (f64::from(a) - want).abs() <= 2.0 * ulp(want),
                    "atan2({y:e}, {x:e})"
                );
            }
            assert_eq!(
                a.is_sign_negative(),
                b.is_sign_negative(),
                "sign of atan2({y:e}, {x:e})"
            );
        }
    }
    assert_eq!(Real::atan2(-0.0f32, -1.0), -core::f32::consts::PI);
    assert_eq!(Real::atan2(0.0f32, -1.0), core::f32::consts::PI);
    assert_eq!(Real::atan2(0.0f32, -0.0), core::f32::consts::PI);
    assert_eq!(Real::atan2(-0.0f32, 0.0).to_bits(), (-0.0f32).to_bits());
    assert_eq!(
        Real::atan2(f32::INFINITY, f32::NEG_INFINITY),
        3.0 * core::f32::consts::FRAC_PI_4
    );
}

/// `Real::acos_clamped` (built on `atan2`) over every 64th f32 of [-1, 1] (3.3e7 values), next
/// to the same formula with `libm::atan2f` and to `libm::acosf`.
#[test]
fn acos_clamped_strided() {
    let (mut ours, mut same_libm, mut acosf) =
        (Worst::default(), Worst::default(), Worst::default());
    for b in (0..=ONE_BITS).step_by(64) {
        for x in [f32::from_bits(b), -f32::from_bits(b)] {
            let want = f64::from(x).acos();
            ours.add(x.acos_clamped(), want, (x, 0.0));
            let y = <f32 as Real>::sqrt((1.0 - x) * (1.0 + x));
            same_libm.add(libm::atan2f(y, x), want, (x, 0.0));
            acosf.add(libm::acosf(x), want, (x, 0.0));
        }
    }
    println!(
        "acos on [-1, 1], every 64th f32: acos_clamped {:.3} ULP, {:.3e} rad abs (worst at {:e}); \
         the same formula with libm::atan2f {:.3} ULP, {:.3e}; libm::acosf {:.3} ULP, {:.3e}",
        ours.ulp, ours.abs, ours.at.0, same_libm.ulp, same_libm.abs, acosf.ulp, acosf.abs
    );
    assert!(ours.ulp <= 2.0, "acos {} ULP at {:e}", ours.ulp, ours.at.0);
    assert!(ours.abs <= 2.5e-7, "acos {:e} rad", ours.abs);
}
