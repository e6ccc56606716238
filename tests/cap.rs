//! Caps and spheres, Lambertian: `[cap_lambert]`, `[sphere_lambert]` (and the Hermite
//! approximations `[cap_lambert_hermite]`, `[sphere_lambert_hermite]` for f32/Fast32 vs f64;
//! their error against the exact model is measured in tests/fixtures.rs).
//!
//! f64 library vs the independent quadrature (within its row of the f64 budget, `F64_BUDGET`
//! in tests/common), then f32 and Fast32 vs f64 on the same rounded inputs (<= 2e-6 and
//! <= 1/1024 in the main regime; see `f32_bound` in tests/common).

mod common;

use arealight::{CapLight, Fast32, Real, SphereLight};
use common::quadrature as qd;
use common::*;
use std::f64::consts::{FRAC_PI_2, PI};

#[test]
fn f64_vs_quadrature() {
    let mut rng = Rng::new(0xca9);
    let q = Quad::STD;
    let mut e_cap = MaxErr::new("cap_lambert f64 vs quadrature");
    for (axis, sigma, n) in cap_cases(&mut rng, 300) {
        let lib = CapLight::<f64>::new(v(axis), sigma).unwrap().lambert(v(n));
        e_cap.add(lib, qd::cap_lambert(axis, sigma, n, &q), || {
            format!("axis={axis:?} sigma={sigma:e} n={n:?}")
        });
    }
    let mut e_sph = MaxErr::new("sphere_lambert f64 vs quadrature");
    for (center, radius, p, n) in sphere_cases(&mut rng, 300) {
        let lib = SphereLight::<f64>::new(v(center), radius)
            .unwrap()
            .lambert(v(p), v(n));
        e_sph.add(lib, qd::sphere_lambert(center, radius, p, n, &q), || {
            format!("center={center:?} radius={radius:e} p={p:?} n={n:?}")
        });
    }
    check_all(&[
        (&e_cap, tol_f64("cap_lambert")),
        (&e_sph, tol_f64("sphere_lambert")),
    ]);
}

/// f32 / Fast32 vs f64 on the same rounded inputs: a dense (sigma, w) grid (129 x 1025 plus
/// the adversarial grids) and random spheres, every case against its own bound (`f32_bound` in
/// tests/common: 2e-6 and 1/1024 in the main regime).
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
            fn cap_vs_f64() {
                let mut rng = Rng::new(0xcab);
                let mut cases = cap_cases(&mut rng, 20_000);
                for i in 0..=128 {
                    let sigma = FRAC_PI_2 * i as f64 / 128.0;
                    for j in 0..=1024 {
                        let w = PI * j as f64 / 1024.0;
                        let a = rng.dir();
                        cases.push((a, sigma, rng.dir_at(a, w)));
                    }
                }
                let mut e_cap = Bounded::new(&format!("cap_lambert {NAME} vs f64"), B);
                let mut e_her = Bounded::new(&format!("cap_lambert_hermite {NAME} vs f64"), B);
                for (axis, sigma, n) in cases {
                    let (axis, n) = (rdv::<T>(axis), rdv::<T>(n));
                    let sigma = rd_max::<T>(sigma, FRAC_PI_2);
                    let lo = CapLight::<T>::new(v(axis), T::from_f64(sigma)).unwrap();
                    let hi = CapLight::<f64>::new(v(axis), sigma).unwrap();
                    let x = flat(&[axis, n], &[sigma]);
                    let cap = |x: &[f64]| CapLight::<f64>::new(v(v3_at(x, 0)), x[6]).ok();
                    let case = || format!("axis={axis:?} sigma={sigma:e} n={n:?}");
                    let s = sensitivity(|x| Some(cap(x)?.lambert(v(v3_at(x, 1)))), &x);
                    e_cap.add(lo.lambert(v(n)).to_f64(), hi.lambert(v(n)), cond(s), case);
                    let s = sensitivity(|x| Some(cap(x)?.lambert_hermite(v(v3_at(x, 1)))), &x);
                    e_her.add(
                        lo.lambert_hermite(v(n)).to_f64(),
                        hi.lambert_hermite(v(n)),
                        cond(s),
                        case,
                    );
                }
                check_bounded(&[&e_cap, &e_her]);
            }

            #[test]
            fn sphere_vs_f64() {
                let mut rng = Rng::new(0x5ee);
                let mut e_sph = Bounded::new(&format!("sphere_lambert {NAME} vs f64"), B);
                let mut e_her = Bounded::new(&format!("sphere_lambert_hermite {NAME} vs f64"), B);
                let mut skipped = 0;
                // Max error by band of d/radius (the f32 cap of a sphere seen from close by is
                // ill-conditioned: cos(sigma) = sqrt(1 - (r/d)^2) amplifies the rounding of d).
                let bands = [1.0, 1.001, 1.003, 1.01, 1.1, f64::INFINITY];
                let mut band_max = [0.0f64; 5];
                for (center, radius, p, n) in sphere_cases(&mut rng, 30_000) {
                    let (center, p, n) = (rdv::<T>(center), rdv::<T>(p), rdv::<T>(n));
                    let radius = rd::<T>(radius);
                    let lo = SphereLight::<T>::new(v(center), T::from_f64(radius)).unwrap();
                    let hi = SphereLight::<f64>::new(v(center), radius).unwrap();
                    let Ok(want) = hi.try_lambert(v(p), v(n)) else {
                        skipped += 1; // rounding put p inside the sphere
                        continue;
                    };
                    let ratio = norm(sub(p, center)) / radius;
                    let case = || {
                        format!(
                            "center={center:?} radius={radius:e} p={p:?} n={n:?} d/radius={ratio:.6}"
                        )
                    };
                    let got = lo.lambert(v(p), v(n)).to_f64();
                    let b = bands.windows(2).position(|w| ratio >= w[0] && ratio < w[1]);
                    if let Some(b) = b {
                        band_max[b] = band_max[b].max((got - want).abs());
                    }
                    let x = flat(&[center, p, n], &[radius]);
                    let sph = |x: &[f64]| SphereLight::<f64>::new(v(v3_at(x, 0)), x[9]).ok();
                    let s = sensitivity(
                        |x| sph(x)?.try_lambert(v(v3_at(x, 1)), v(v3_at(x, 2))).ok(),
                        &x,
                    );
                    e_sph.add(got, want, cond(s), case);
                    let s = sensitivity(
                        |x| {
                            sph(x)?
                                .try_lambert_hermite(v(v3_at(x, 1)), v(v3_at(x, 2)))
                                .ok()
                        },
                        &x,
                    );
                    e_her.add(
                        lo.lambert_hermite(v(p), v(n)).to_f64(),
                        hi.lambert_hermite(v(p), v(n)),
                        cond(s),
                        case,
                    );
                }
                println!("sphere {NAME}: {skipped} cases skipped (p inside after rounding)");
                for b in 0..5 {
                    println!(
                        "sphere_lambert {NAME}: d/radius in [{}, {}): max abs err {:.3e}",
                        bands[b],
                        bands[b + 1],
                        band_max[b]
                    );
                }
                check_bounded(&[&e_sph, &e_her]);
            }
        }
    };
}

lowp_tests!(f32_vs_f64, f32, BOUNDS_F32);
lowp_tests!(fast32_vs_f64, Fast32, BOUNDS_FAST32);
