//! # arealight
//!
//! Analytic area-light shading for microcontrollers and software rasterizers: the closed forms
//! of Snyder's "Area Light Sources for Real-Time Graphics" (MSR-TR-96-11), the SH9
//! irradiance of Ramamoorthi and Hanrahan, Barzel's uberlight shaping, Picott's linear lights
//! and Arvo's irradiance-tensor moments, written once over a scalar trait ([`Real`]) and
//! instantiated for `f64` (the reference), `f32` (via `libm`), [`Fast32`] (f32 with a cheap
//! `atan2`) and, for chips without an FPU, the fixed-point `Fixed22` (I10F22, feature
//! `fixed`; see `real::Fixed22`).
//!
//! `#![no_std]`, no allocation, no panics, no `unsafe` but the audited hardware square root of
//! FPU targets ([`real::hw`]): constructors validate and return
//! [`Result`]; per-sample functions return a documented finite fallback (0) for inputs that
//! have no value, and never NaN or infinity.
//!
//! Every model is defined by the integral it evaluates (`docs/models.md` in the repository)
//! and tested against an independent numerical quadrature of that integral (`tests/`).
//!
//! | model id | type and method | source |
//! |---|---|---|
//! | `hemi_const`, `hemi_cos` | [`HemisphereLight::lambert_const`], [`HemisphereLight::lambert_cos`] | Snyder eq. 4, 5 |
//! | `sky_overcast` | [`OvercastSky::lambert`] | Snyder 2.1.3 |
//! | `sky_ground` | [`SkyGround::irradiance`] | June eq. 20.7 |
//! | `cap_lambert`, `cap_lambert_hermite` | [`CapLight::lambert`], [`CapLight::lambert_hermite`] | Snyder eq. 6, 2.2 |
//! | `sphere_lambert`, `sphere_lambert_hermite` | [`SphereLight::lambert`], [`SphereLight::lambert_hermite`] | Snyder eq. 6, 7 |
//! | `polygon_lambert` | [`PolygonLight::lambert`] | Snyder eq. 8, Iwanicki |
//! | `line_lambert` | [`LineLight::lambert`] with a [`Decay`] | Picott eq. 3, appendix A |
//! | `phong_hemi_const`, `phong_hemi_cos` | [`HemisphereLight::phong_const`], [`HemisphereLight::phong_cos`] | Snyder eq. 14, 15 |
//! | `phong_cap`, `phong_sphere` | [`CapLight::phong`], [`SphereLight::phong`] | Snyder eq. 24 |
//! | `phong_polygon` | [`PolygonLight::phong`] | Snyder eq. 25, Arvo 5.1 |
//! | `line_phong_peak`, `rect_phong_peak` | [`LineLight::phong_peak`], [`ParallelogramLight::phong_peak`] (the peak of the lobe, not its integral) | Picott eq. 7, 3.2 |
//! | `axial_moment`, `double_axis_moment` | [`PolygonLight::axial_moment`], [`PolygonLight::double_axis_moment`] | Arvo eq. 12, 14, 5.3 |
//! | `directional_luminaire` | [`PolygonLight::directional_luminaire`] | Arvo 6.1 |
//! | `glossy_reflection`, `glossy_transmission` | [`PolygonLight::glossy_reflection`], [`PolygonLight::glossy_transmission`] | Arvo 6.2, 6.3 |
//! | `lune_normalization` | [`lune_normalization`] | Arvo 6.4 |
//! | `sh9_irradiance`, `sh9_disc_irradiance` | [`Sh9::prepare`] then [`Sh9Irradiance::irradiance`]; [`Sh9::disc`] | June eq. 20.24-20.33 |
//! | `superellipse_shape` | [`Superellipse::shape`] (a factor: see [`Uberlight`]) | June eq. 20.34-20.42 (Barzel) |
//! | `distance_falloff` | [`DistanceFalloff::falloff`] (a factor: see [`Uberlight`]) | June eq. 20.46, 20.47 and listing (Barzel) |
//!
//! Each model's documentation states its measured error against the reference (f64 against
//! the quadrature; f32, `Fast32` and `Fixed22` against f64), generated from the test suite's
//! measurements like the tables of `docs/accuracy.md` in the repository.
//!
//! ```
//! use arealight::{CapLight, PhongLobe, Vec3};
//!
//! fn main() -> Result<(), arealight::Error> {
//!     // The sun: a cap of half-angle 0.27 degrees, straight up.
//!     let sun = CapLight::<f32>::new(Vec3::new(0.0, 0.0, 1.0), 0.0047)?;
//!     let n = Vec3::new(0.0, 0.6, 0.8);
//!     let e = sun.lambert(n); // normalized irradiance: cos(w) sin^2(sigma) when fully visible
//!     assert!((e - 0.8 * 0.0047f32.sin().powi(2)).abs() < 1e-9);
//!     let lobe = PhongLobe::new(32)?;
//!     let specular = sun.phong(&lobe, n);
//!     println!("diffuse {e:e}, specular {specular:e}");
//!     Ok(())
//! }
//! ```
#![no_std]
// The only `unsafe` is the audited hardware square root, `real::hw` (allowed there alone).
#![deny(unsafe_code)]
#![deny(missing_docs)]
#![warn(clippy::all)]
// `!(x > y)` is deliberate throughout: unlike `x <= y` it is true when x is NaN, which is what
// every validation and fallback here needs.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

/// A function always inlined on targets with an FPU and only hinted (`#[inline]`) on
/// soft-float targets (`real::SOFT_FLOAT`'s: ARM without `eabihf`, RISC-V without F), where
/// its callers share one copy (see `scene::Entry::diffuse_and_phong` for the measurements).
#[cfg(any(feature = "cap", feature = "polygon"))]
macro_rules! inline_always_with_fpu {
    ($(#[$attr:meta])* $vis:vis fn $($rest:tt)*) => {
        $(#[$attr])*
        #[cfg_attr(
            any(
                all(target_arch = "arm", not(target_abi = "eabihf")),
                all(
                    any(target_arch = "riscv32", target_arch = "riscv64"),
                    not(target_feature = "f")
                )
            ),
            inline
        )]
        #[cfg_attr(
            not(any(
                all(target_arch = "arm", not(target_abi = "eabihf")),
                all(
                    any(target_arch = "riscv32", target_arch = "riscv64"),
                    not(target_feature = "f")
                )
            )),
            inline(always)
        )]
        $vis fn $($rest)*
    };
}

#[cfg(feature = "cap")]
pub mod cap;
pub mod error;
#[cfg(feature = "hemisphere")]
pub mod hemisphere;
pub mod illuminant;
#[cfg(feature = "line")]
pub mod line;
pub mod lobe;
#[cfg(feature = "moments")]
pub mod moments;
#[cfg(feature = "phong")]
pub mod phong;
#[cfg(feature = "polygon")]
pub mod polygon;
#[cfg(feature = "raster")]
pub mod raster;
pub mod real;
pub mod scene;
#[cfg(feature = "sh9")]
pub mod sh9;
#[cfg(feature = "shaping")]
pub mod shaping;
pub mod sine_power;
#[cfg(test)]
mod test_rng;
pub mod unit;
pub mod vec3;
#[cfg(any(feature = "raster", feature = "fixed"))]
mod wide;
#[cfg(any(feature = "cap", feature = "polygon"))]
pub mod world;

#[cfg(feature = "cap")]
pub use cap::{CapLight, SphereLight};
pub use error::Error;
#[cfg(feature = "hemisphere")]
pub use hemisphere::{HemisphereLight, OvercastSky, SkyGround};
pub use illuminant::{Ambient, DirectionalLight, Illuminant, PointLight, Tinted};
#[cfg(feature = "line")]
pub use line::{Decay, LineLight, ParallelogramLight};
pub use lobe::PhongLobe;
#[cfg(feature = "moments")]
pub use moments::{lune_normalization, try_lune_normalization};
#[cfg(feature = "polygon")]
pub use polygon::PolygonLight;
#[cfg(feature = "fixed")]
pub use real::Fixed22;
pub use real::{Fast32, Real};
pub use scene::{ObjectBounds, PreparedScene, PushError, Scene, SceneLight};
#[cfg(feature = "sh9")]
pub use sh9::{Environment, Sh9, Sh9Irradiance};
#[cfg(feature = "shaping")]
pub use shaping::{DistanceFalloff, LightFrame, Superellipse, Uberlight};
pub use unit::{Direction, UnitVec3};
pub use vec3::{Rgb, Vec3};
#[cfg(any(feature = "cap", feature = "polygon"))]
pub use world::WorldPoint;
#[cfg(feature = "polygon")]
pub use world::WorldPolygonLight;
#[cfg(feature = "cap")]
pub use world::WorldSphereLight;

/// The README's examples, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
