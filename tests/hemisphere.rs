//! Hemisphere lights: `[hemi_const]`, `[hemi_cos]`, `[sky_overcast]`, `[sky_ground]`.
//!
//! f64 library vs the independent quadrature (within its row of the f64 budget, `F64_BUDGET`
//! in tests/common), then f32 and Fast32 vs f64 on the same rounded inputs (<= 2e-6 and
//! <= 1/1024 in the main regime; see `f32_bound` in tests/common).

mod common;

use arealight::{Fast32, HemisphereLight, OvercastSky, Real, SkyGround};
use common::quadrature as qd;
use common::*;
use std::f64::consts::{FRAC_PI_2, PI};

/// (axis, n) pairs, neither unit length: random, and n at adversarial angles from the axis
/// (0, tiny, just either side of pi/2, near pi, pi).
fn cases(rng: &mut Rng, random: usize) -> Vec<(V3, V3)> {
    let mut out = Vec::new();
    for _ in 0..random {
        let a = rng.dir();
        let n = rng.dir();
        out.push((rng.stretch(a), rng.stretch(n)));
    }
    let ws = [
        0.0,
        1e-12,
        1e-8,
        1e-4,
        0.5,
        1.0,
        FRAC_PI_2 - 1e-8,
        FRAC_PI_2,
        FRAC_PI_2 + 1e-8,
        2.0,
        PI - 1e-4,
        PI - 1e-8,
        PI,
    ];
    for &w in &ws {
        for _ in 0..3 {
            let a = rng.dir();
            let n = rng.dir_at(a, w);
            out.push((rng.stretch(a), rng.stretch(n)));
        }
    }
    // Axis-aligned ones too.
    out.push(([0.0, 0.0, 1.0], [0.0, 0.0, 1.0]));
    out.push(([0.0, 0.0, 1.0], [0.0, 0.0, -2.0]));
    out.push(([0.0, 0.0, 1.0], [1.0, 0.0, 0.0]));
    out
}

#[test]
fn f64_vs_quadrature() {
    let mut rng = Rng::new(0x4e4d);
    let q = Quad::STD;
    let mut e_const = MaxErr::new("hemi_const f64 vs quadrature");
    let mut e_cos = MaxErr::new("hemi_cos f64 vs quadrature");
    let mut e_sky = MaxErr::new("sky_overcast f64 vs quadrature");
    let mut e_sg = MaxErr::new("sky_ground f64 vs quadrature");
    for (axis, n) in cases(&mut rng, 300) {
        let h = HemisphereLight::<f64>::new(v(axis)).unwrap();
        let case = || format!("axis={axis:?} n={n:?}");
        e_const.add(h.lambert_const(v(n)), qd::hemi_const(axis, n, &q), case);
        e_cos.add(h.lambert_cos(v(n)), qd::hemi_cos(axis, n, &q), case);
        let c = rng.range(0.0, 2.0);
        let sky = OvercastSky::<f64>::new(v(axis), c).unwrap();
        e_sky.add(sky.lambert(v(n)), qd::sky_overcast(axis, c, n, &q), || {
            format!("zenith={axis:?} c={c} n={n:?}")
        });
        let (s, g) = (
            [rng.unit(), rng.unit(), rng.unit()],
            [rng.unit(), rng.unit(), rng.unit()],
        );
        let lib = SkyGround::<f64>::new(v(axis), rgb(s), rgb(g))
            .unwrap()
            .irradiance(v(n))
            .to_f64();
        let want = qd::sky_ground(axis, s, g, n, &q);
        for ch in 0..3 {
            e_sg.add(lib[ch], want[ch], || {
                format!("up={axis:?} sky={s:?} ground={g:?} n={n:?} channel {ch}")
            });
        }
    }
    check_all(&[
        (&e_const, tol_f64("hemi_const")),
        (&e_cos, tol_f64("hemi_cos")),
        (&e_sky, tol_f64("sky_overcast")),
        (&e_sg, tol_f64("sky_ground")),
    ]);
}

/// f32 / Fast32 vs f64 on the same rounded inputs: a dense grid over the angle w in [0, pi]
/// (4097 values plus the adversarial ones, random orientation) and random cases, every case
/// against its own bound (`f32_bound` in tests/common: 2e-6 and 1/1024 in the main regime).
macro_rules! lowp_tests {
    ($modname:ident, $T:ty, $bounds:expr) => {
        mod $modname {
            use super::*;
            type T = $T;
            const B: LowpBounds = $bounds;
            const NAME: &str = stringify!($T);

            fn grid(rng: &mut Rng) -> Vec<(V3, V3)> {
                let mut out = cases(rng, 20_000);
                for i in 0..=4096 {
                    let w = PI * i as f64 / 4096.0;
                    let a = rng.dir();
                    out.push((a, rng.dir_at(a, w)));
                }
                out
            }

            fn cond(sens: f64) -> Cond {
                Cond {
                    m: 0,
                    sens,
                    near: None,
                }
            }

            #[test]
            fn hemisphere_vs_f64() {
                let mut rng = Rng::new(0x1234);
                let mut e_const = Bounded::new(&format!("hemi_const {NAME} vs f64"), B);
                let mut e_cos = Bounded::new(&format!("hemi_cos {NAME} vs f64"), B);
                let mut e_sky = Bounded::new(&format!("sky_overcast {NAME} vs f64"), B);
                let mut e_sg = Bounded::new(&format!("sky_ground {NAME} vs f64"), B);
                for (axis, n) in grid(&mut rng) {
                    let (axis, n) = (rdv::<T>(axis), rdv::<T>(n));
                    let case = || format!("axis={axis:?} n={n:?}");
                    let lo = HemisphereLight::<T>::new(v(axis)).unwrap();
                    let hi = HemisphereLight::<f64>::new(v(axis)).unwrap();
                    let x = flat(&[axis, n], &[]);
                    let light = |x: &[f64]| HemisphereLight::<f64>::new(v(v3_at(x, 0))).ok();
                    let s = sensitivity(|x| Some(light(x)?.lambert_const(v(v3_at(x, 1)))), &x);
                    e_const.add(
                        lo.lambert_const(v(n)).to_f64(),
                        hi.lambert_const(v(n)),
                        cond(s),
                        case,
                    );
                    let s = sensitivity(|x| Some(light(x)?.lambert_cos(v(v3_at(x, 1)))), &x);
                    e_cos.add(
                        lo.lambert_cos(v(n)).to_f64(),
                        hi.lambert_cos(v(n)),
                        cond(s),
                        case,
                    );
                    let c = rd::<T>(rng.range(0.0, 1.0));
                    let lo = OvercastSky::<T>::new(v(axis), <T as arealight::Real>::from_f64(c))
                        .unwrap();
                    let hi = OvercastSky::<f64>::new(v(axis), c).unwrap();
                    let s = sensitivity(
                        |x| {
                            let sky = OvercastSky::<f64>::new(v(v3_at(x, 0)), x[6]).ok()?;
                            Some(sky.lambert(v(v3_at(x, 1))))
                        },
                        &flat(&[axis, n], &[c]),
                    );
                    e_sky.add(lo.lambert(v(n)).to_f64(), hi.lambert(v(n)), cond(s), || {
                        format!("zenith={axis:?} c={c} n={n:?}")
                    });
                    let s = rdv::<T>([rng.unit(), rng.unit(), rng.unit()]);
                    let g = rdv::<T>([rng.unit(), rng.unit(), rng.unit()]);
                    let lo = SkyGround::<T>::new(v(axis), rgb(s), rgb(g))
                        .unwrap()
                        .irradiance(v(n))
                        .to_f64();
                    let hi = SkyGround::<f64>::new(v(axis), rgb(s), rgb(g))
                        .unwrap()
                        .irradiance(v(n))
                        .to_f64();
                    let x = flat(&[axis, n, s, g], &[]);
                    for ch in 0..3 {
                        let sens = sensitivity(
                            |x| {
                                let sg = SkyGround::<f64>::new(
                                    v(v3_at(x, 0)),
                                    rgb(v3_at(x, 2)),
                                    rgb(v3_at(x, 3)),
                                )
                                .ok()?;
                                Some(sg.irradiance(v(v3_at(x, 1))).to_f64()[ch])
                            },
                            &x,
                        );
                        e_sg.add(lo[ch], hi[ch], cond(sens), || {
                            format!("up={axis:?} sky={s:?} ground={g:?} n={n:?} ch {ch}")
                        });
                    }
                }
                check_bounded(&[&e_const, &e_cos, &e_sky, &e_sg]);
            }
        }
    };
}

lowp_tests!(f32_vs_f64, f32, BOUNDS_F32);
lowp_tests!(fast32_vs_f64, Fast32, BOUNDS_FAST32);
