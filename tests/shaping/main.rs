//! Uberlight shaping: `[superellipse_shape]`, `[distance_falloff]`, and the `LightFrame` /
//! `Uberlight` helpers.
//!
//! The reference here is written directly from `shared/spec/models.md` ("Shaping"), the
//! straightforward way (June's listing: `q = a b ((b X)^(2/d) + (a Y)^(2/d))^(-d/2)`, GLSL's
//! smoothstep, `M exp(s (z/d0)^beta)`), and shares no code with the library. The library in
//! f64 is held to its row of the f64 budget (`F64_BUDGET` in tests/common) wherever the
//! reference itself is finite; f32 and Fast32 are
//! compared with the f64 library on the same rounded inputs, each case against its own bound
//! (`Bounded` in tests/common: 2e-6 in the main regime for f32, the model's own sensitivity to
//! 1-ULP input rounding added in the ill-conditioned regime; 1/1024 everywhere for Fast32).
//! Falloff errors are relative to `max(1, value)` (the falloff peaks at `M > 1`).
//!
//! Then exact edge cases (axis, `z <= 0`, `z -> 0+`, on the curves, huge and subnormal
//! coordinates, extreme `d`), properties (range, monotonicity, continuity and slope at `d0`),
//! and adversarial inputs (constructors refuse, per-sample functions stay finite).

#[path = "../common/mod.rs"]
mod common;

use arealight::{DistanceFalloff, Error, Fast32, LightFrame, Real, Superellipse, Uberlight, Vec3};
use common::*;
use std::f64::consts::{FRAC_PI_2, TAU};

mod edges;
mod uberlight;
use edges::*;
use uberlight::*;

// ---------------------------------------------------------------------------------------------
// The reference, straight from models.md
// ---------------------------------------------------------------------------------------------

/// GLSL's smoothstep.
fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// `[superellipse_shape]` as models.md writes it; `s = [a, b, A, B, d]`.
fn ref_shape(pos: V3, s: [f64; 5]) -> f64 {
    let [a, b, big_a, big_b, d] = s;
    let [x, y, z] = pos;
    if z <= 0.0 {
        return 0.0;
    }
    let (xx, yy) = ((x / z).abs(), (y / z).abs());
    if xx == 0.0 && yy == 0.0 {
        return 1.0;
    }
    let (e1, e2) = (2.0 / d, -d / 2.0);
    let q = a * b * ((b * xx).powf(e1) + (a * yy).powf(e1)).powf(e2);
    let r = big_a * big_b * ((big_b * xx).powf(e1) + (big_a * yy).powf(e1)).powf(e2);
    1.0 - smoothstep(q, r, 1.0)
}

/// `[distance_falloff]` as models.md writes it; `f = [M, d0, alpha, znear, zfar, near_edge,
/// far_edge]`.
fn ref_falloff(z: f64, f: [f64; 7]) -> f64 {
    let [m, d0, alpha, znear, zfar, near_edge, far_edge] = f;
    let zones =
        smoothstep(znear - near_edge, znear, z) * (1.0 - smoothstep(zfar, zfar + far_edge, z));
    let dist = if z > d0 {
        (d0 / z).powf(alpha)
    } else {
        let s = (1.0 / m).ln();
        let beta = -alpha / s;
        m * (s * (z / d0).powf(beta)).exp()
    };
    zones * dist
}

fn se<T: Real>(s: [f64; 5]) -> Result<Superellipse<T>, Error> {
    let s = s.map(T::from_f64);
    Superellipse::new(s[0], s[1], s[2], s[3], s[4])
}
fn fo<T: Real>(f: [f64; 7]) -> Result<DistanceFalloff<T>, Error> {
    let f = f.map(T::from_f64);
    DistanceFalloff::new(f[0], f[1], f[2], f[3], f[4], f[5], f[6])
}
fn shape<T: Real>(s: [f64; 5], pos: V3) -> f64 {
    se::<T>(s).unwrap().shape(v(pos)).to_f64()
}
fn falloff<T: Real>(f: [f64; 7], z: f64) -> f64 {
    fo::<T>(f).unwrap().falloff(T::from_f64(z)).to_f64()
}

// ---------------------------------------------------------------------------------------------
// Cases
// ---------------------------------------------------------------------------------------------

/// June's figure 20-17: a, b, A, B, d.
const BOOK_SHAPE: [f64; 5] = [0.2, 0.3, 0.3, 0.4, 0.8];
/// June's listing: maxIntensity 2, d0 1, alpha 1; zNear, zFar 1, 2; nearEdge 0.4, farEdge 0.8.
const BOOK_FALLOFF: [f64; 7] = [2.0, 1.0, 1.0, 1.0, 2.0, 0.4, 0.8];
/// The roundness values the brief asks for, and a few more.
const DS: [f64; 8] = [0.1, 0.25, 0.5, 0.8, 1.0, 2.0, 3.0, 4.0];

/// Sizes `[a, b, A, B]`: June's, the outer curve a scaled copy (A/a = B/b, the fast path), a
/// near-circle, a thin-and-wide pair, and a thin transition band (1%: ill-conditioned, the
/// value moves by ~100 per unit of relative change in X).
const SIZES: [[f64; 4]; 5] = [
    [0.2, 0.3, 0.3, 0.4],
    [0.5, 0.25, 1.0, 0.5],
    [1.0, 1.0, 1.2, 1.5],
    [0.05, 0.1, 0.5, 0.12],
    [0.3, 0.3, 0.303, 0.303],
];

fn shape_params(rng: &mut Rng, n: usize) -> Vec<[f64; 5]> {
    let mut out = vec![BOOK_SHAPE];
    for s in SIZES {
        for d in DS {
            out.push([s[0], s[1], s[2], s[3], d]);
        }
    }
    for _ in 0..n {
        let (a, b) = (rng.range(0.05, 2.0), rng.range(0.05, 2.0));
        let d = match rng.below(4) {
            0 => 0.1,
            1 => 1.0,
            2 => 4.0,
            _ => rng.range(0.1, 4.0),
        };
        out.push([a, b, a * rng.range(1.05, 3.0), b * rng.range(1.05, 3.0), d]);
    }
    out
}

/// A point of light space at projected position (`xx`, `yy`) and depth `z`.
fn at(xx: f64, yy: f64, z: f64) -> V3 {
    [xx * z, yy * z, z]
}

/// A point on the superellipse of half-widths `a`, `b` (June eq. 20.35) scaled by `lambda`, in
/// quadrant `quad`.
fn on_curve(a: f64, b: f64, d: f64, theta: f64, lambda: f64, quad: usize) -> (f64, f64) {
    let (sx, sy) = [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)][quad % 4];
    (
        sx * lambda * a * theta.cos().powf(d),
        sy * lambda * b * theta.sin().powf(d),
    )
}

/// Dense grids over the projected plane, points on and near both curves, random points; with
/// random depths (also tiny and huge: the model depends on x/z, y/z only).
fn shape_cases(rng: &mut Rng, params: &[[f64; 5]], grid: usize) -> Vec<([f64; 5], V3)> {
    let mut out = Vec::new();
    for &s in params {
        let [a, b, big_a, big_b, d] = s;
        let (hx, hy) = (1.25 * big_a, 1.25 * big_b);
        for i in 0..=grid {
            for j in 0..=grid {
                let xx = -hx + 2.0 * hx * i as f64 / grid as f64;
                let yy = -hy + 2.0 * hy * j as f64 / grid as f64;
                out.push((s, at(xx, yy, rng.range(0.1, 10.0))));
            }
        }
        for k in 0..=64 {
            let theta = FRAC_PI_2 * k as f64 / 64.0;
            for lambda in [1.0, 1.0 - 1e-9, 1.0 + 1e-9, 0.999, 1.001] {
                for (w, h) in [(a, b), (big_a, big_b)] {
                    let (xx, yy) = on_curve(w, h, d, theta, lambda, k);
                    out.push((s, at(xx, yy, rng.range(0.1, 10.0))));
                }
            }
        }
        for _ in 0..200 {
            let (xx, yy) = (rng.range(-hx, hx), rng.range(-hy, hy));
            let z = [1e-30, 1e-10, 1.0, 1e10, 1e30][rng.below(5) as usize] * rng.range(0.5, 2.0);
            out.push((s, at(xx, yy, z)));
        }
    }
    out
}

fn falloff_params(rng: &mut Rng, n: usize) -> Vec<[f64; 7]> {
    let mut out = vec![
        BOOK_FALLOFF,
        // Zones wide open: the pure distance curve.
        [2.0, 1.0, 1.0, 0.0, 1e6, 1.0, 1.0],
        [10.0, 0.5, 2.0, 0.0, 1e6, 1.0, 1.0],
        [1.5, 2.0, 0.5, 0.0, 1e6, 1.0, 1.0],
        [2.0, 1.0, 0.0, 0.0, 1e6, 1.0, 1.0], // alpha = 0
        [100.0, 1.0, 4.0, 0.0, 1e6, 1.0, 1.0],
        [1.01, 1.0, 3.0, 0.0, 1e6, 1.0, 1.0], // M near 1: beta large
    ];
    for _ in 0..n {
        let znear = rng.range(-1.0, 5.0);
        out.push([
            1.0 + 10f64.powf(rng.range(-2.0, 2.0)),
            rng.range(0.1, 5.0),
            if rng.below(8) == 0 {
                0.0
            } else {
                rng.range(0.0, 4.0)
            },
            znear,
            znear + rng.range(0.1, 10.0),
            rng.range(0.01, 3.0),
            rng.range(0.01, 3.0),
        ]);
    }
    out
}

/// A dense z grid over [0, zfar + far_edge + 1] and the special points.
fn falloff_cases(rng: &mut Rng, params: &[[f64; 7]], grid: usize) -> Vec<([f64; 7], f64)> {
    let mut out = Vec::new();
    for &f in params {
        let [_, d0, _, znear, zfar, near_edge, far_edge] = f;
        let top = (zfar + far_edge + 1.0).min(50.0 * d0.max(1.0));
        for i in 0..=grid {
            out.push((f, top * i as f64 / grid as f64));
        }
        let specials = [
            0.0,
            d0,
            d0 * (1.0 - 1e-12),
            d0 * (1.0 + 1e-12),
            znear - near_edge,
            znear,
            zfar,
            zfar + far_edge,
            1e-300,
            1e-30,
        ];
        for z in specials {
            if z >= 0.0 {
                out.push((f, z));
            }
        }
        for _ in 0..100 {
            out.push((f, rng.range(0.0, top)));
        }
    }
    out
}

// ---------------------------------------------------------------------------------------------
// f64 library vs the reference
// ---------------------------------------------------------------------------------------------

#[test]
fn f64_vs_reference() {
    let mut rng = Rng::new(0x5a9e);
    let params = shape_params(&mut rng, 40);
    let mut e_shape = MaxErr::new("superellipse_shape f64 vs reference");
    let mut by_d = std::collections::BTreeMap::<String, f64>::new();
    let mut ref_nan = 0;
    for (s, pos) in shape_cases(&mut rng, &params, 64) {
        let want = ref_shape(pos, s);
        if !want.is_finite() {
            ref_nan += 1;
            continue;
        }
        let got = shape::<f64>(s, pos);
        assert!((0.0..=1.0).contains(&got), "shape {got} outside [0, 1]");
        e_shape.add(got, want, || format!("s={s:?} pos={pos:?}"));
        let slot = by_d.entry(format!("{:.3}", s[4])).or_default();
        *slot = slot.max((got - want).abs());
    }
    println!("superellipse_shape f64: {ref_nan} cases where the reference is not finite (skipped)");
    for (d, e) in &by_d {
        println!("[maxerr] superellipse_shape f64 vs reference, d = {d:<6} max abs err {e:.3e}");
    }

    let params = falloff_params(&mut rng, 60);
    let mut e_fall = MaxErr::new("distance_falloff f64 vs reference (rel)");
    for (f, z) in falloff_cases(&mut rng, &params, 2048) {
        let want = ref_falloff(z, f);
        let got = falloff::<f64>(f, z);
        assert!(got >= 0.0 && got <= f[0], "falloff {got} outside [0, M]");
        let scale = want.abs().max(1.0);
        e_fall.add(got / scale, want / scale, || format!("f={f:?} z={z:e}"));
    }
    check_all(&[
        (&e_shape, tol_f64("superellipse_shape")),
        (&e_fall, tol_f64("distance_falloff")),
    ]);
}

// ---------------------------------------------------------------------------------------------
// f32 and Fast32 vs f64
// ---------------------------------------------------------------------------------------------

macro_rules! lowp_tests {
    ($modname:ident, $T:ty, $bounds:expr) => {
        mod $modname {
            use super::*;
            type T = $T;
            const B: LowpBounds = $bounds;
            const NAME: &str = stringify!($T);

            fn cond(sens: f64) -> Cond {
                Cond {
                    m: 0,
                    sens,
                    near: None,
                }
            }

            #[test]
            fn shape_vs_f64() {
                let mut rng = Rng::new(0x5a9f);
                let params = shape_params(&mut rng, 40);
                let mut e = Bounded::new(&format!("superellipse_shape {NAME} vs f64"), B);
                let mut by_d = std::collections::BTreeMap::<String, f64>::new();
                let mut skipped = 0;
                for (s, pos) in shape_cases(&mut rng, &params, 64) {
                    let (s, pos) = (s.map(rd::<T>), rdv::<T>(pos));
                    let (Ok(lo), Ok(hi)) = (se::<T>(s), se::<f64>(s)) else {
                        skipped += 1; // rounding collapsed a < A
                        continue;
                    };
                    let got = lo.shape(v(pos)).to_f64();
                    let want = hi.shape(v(pos));
                    assert!((0.0..=1.0).contains(&got), "{NAME} shape {got} outside [0, 1]");
                    let x = flat(&[pos], &s);
                    let sens = sensitivity(
                        |x| {
                            let s = [x[3], x[4], x[5], x[6], x[7]];
                            Some(se::<f64>(s).ok()?.shape(v(v3_at(x, 0))))
                        },
                        &x,
                    );
                    e.add(got, want, cond(sens), || format!("s={s:?} pos={pos:?}"));
                    let slot = by_d.entry(format!("{:.3}", s[4])).or_default();
                    *slot = slot.max((got - want).abs());
                }
                println!("superellipse_shape {NAME}: {skipped} cases skipped");
                for (d, err) in &by_d {
                    println!(
                        "[maxerr] superellipse_shape {NAME} vs f64, d = {d:<6} max abs err {err:.3e} (all regimes)"
                    );
                }
                check_bounded(&[&e]);
            }

            #[test]
            fn falloff_vs_f64() {
                let mut rng = Rng::new(0xfa11);
                let params = falloff_params(&mut rng, 60);
                let mut e = Bounded::new(&format!("distance_falloff {NAME} vs f64 (rel)"), B);
                let mut skipped = 0;
                for (f, z) in falloff_cases(&mut rng, &params, 2048) {
                    let (f, z) = (f.map(rd::<T>), rd::<T>(z));
                    let (Ok(lo), Ok(hi)) = (fo::<T>(f), fo::<f64>(f)) else {
                        skipped += 1;
                        continue;
                    };
                    let got = lo.falloff(T::from_f64(z)).to_f64();
                    let want = hi.falloff(z);
                    assert!(got >= 0.0 && got <= f[0], "{NAME} falloff {got} outside [0, M]");
                    let scale = want.abs().max(1.0);
                    let x = flat(&[], &[z, f[0], f[1], f[2], f[3], f[4], f[5], f[6]]);
                    let sens = sensitivity(
                        |x| {
                            let g = [x[1], x[2], x[3], x[4], x[5], x[6], x[7]];
                            Some(fo::<f64>(g).ok()?.try_falloff(x[0]).ok()? / scale)
                        },
                        &x,
                    );
                    e.add(got / scale, want / scale, cond(sens), || {
                        format!("f={f:?} z={z:e}")
                    });
                }
                println!("distance_falloff {NAME}: {skipped} cases skipped");
                check_bounded(&[&e]);
            }

            #[test]
            fn edge_cases() {
                edge_cases_for::<T>(NAME, B.tol);
            }

            #[test]
            fn uberlight_vs_f64() {
                uberlight_vs_f64_for::<T>(NAME, B);
            }
        }
    };
}

lowp_tests!(f32_vs_f64, f32, BOUNDS_F32);
lowp_tests!(fast32_vs_f64, Fast32, BOUNDS_FAST32);

#[test]
fn edge_cases_f64() {
    edge_cases_for::<f64>("f64", tol_f64("shaping edge cases"));
}
