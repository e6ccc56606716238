//! World coordinates: positions in a wide format, so that a scene in metres or in model units
//! needs no rescaling by hand on any backend.
//!
//! ## Why
//!
//! [`Fixed22`](crate::Fixed22) (I10F22) holds `[-512, 512)`, and its kernels keep products of
//! point differences inside that range by refusing positions beyond
//! [`Real::COORDINATE_LIMIT`] (4). A sphere 100 units away cannot be given to it directly.
//! Yet every positional model here is *scale-free*: its value depends only on the directions
//! and ratios that a light subtends at `p`, unchanged when the scene is translated or
//! scaled uniformly. So the position format and the kernels' format need not be the same.
//!
//! ## How
//!
//! - A [`WorldPoint`] holds each coordinate as an `i64` in units of `2^-32` (I32F32), within
//!   `+-2^30` units ([`WorldPoint::LIMIT`]); its resolution is `2^-32` ([`WorldPoint::RESOLUTION`],
//!   about 2.3e-10) everywhere in that range.
//! - Per sample, the light's points minus `p` are taken exactly in `i64` (two instructions a
//!   coordinate on a Cortex-M0: `SUBS`, `SBCS`); `|q - p| < 2^63` by the limit.
//! - All of them (and a sphere's radius) are then scaled by one power of two that puts the
//!   largest magnitude in `[2^61, 2^62]` (the OR of the magnitudes has the maximum's leading
//!   bit: one leading-zero count for all). A left shift is exact; the one right shift (by a
//!   single bit, for the widest differences) rounds half up.
//! - The result, read as `x 2^-60`, has its largest coordinate in `[2, 4]`, inside every
//!   backend's [`Real::COORDINATE_LIMIT`]; each backend rounds it once to its own type (fixed
//!   point: `2^-22` absolute, a relative `2^-23` to `2^-24` of the largest coordinate).
//! - The model then runs unchanged on that copy of the light with `p` at the origin.
//!
//! Consequences, each checked by `tests/world.rs`:
//! - **No range limit below `2^30`**, on every backend: positions up to 1000 units (and
//!   scenes translated millions of units away) are answered within the backend's bound.
//! - **Exact invariance**: translating a scene by a multiple of `2^-32`, or scaling it by a
//!   power of two (within the limit), leaves every answer the same, bit for bit.
//! - **Small lights gain**: a light 1e-3 units across seen from 1e-2 away is scaled up to the
//!   full precision of the kernels, where fixed point in plain coordinates would keep only a
//!   few bits of it.
//! - A part of the light far smaller than the largest difference rounds in proportion: a
//!   sphere 2^-24 of its distance across has a radius of 0 or 1 unit of fixed point's `2^-22`
//!   after scaling (its value is below `2^-46` then, far inside the bound).
//!
//! ## Accuracy
//!
//! Measured by `tests/world.rs` (4000 random spheres and polygons each, centres and points
//! within 1000 units of the origin, sizes 1e-3 to 500; the reference is f64's plain model on the
//! exact differences), largest absolute error:
//!
//! | backend | `sphere_lambert` | `sphere_lambert_hermite` | `phong_sphere` (m to 255) | `polygon_lambert` | `phong_polygon` (m to 255) |
//! |---|---:|---:|---:|---:|---:|
//! | f64 | 0 (the same bits) | 0 | 0 | 0 | 0 |
//! | f32 | 4.2e-7 | 4.7e-7 | 1.9e-6 | 2.6e-7 | 1.2e-6 |
//! | `Fast32` | 6.2e-6 | 9.0e-6 | 2.6e-5 | 5.3e-6 | 2.5e-5 |
//! | `Fixed22` | 2.5e-6 | 2.5e-6 | 4.0e-5 | 2.0e-6 | 9.5e-6 |
//! | `Fixed22`, 10^6 units from the origin | 3.2e-6 | 3.0e-6 | 5.6e-5 | 1.8e-6 | 1.2e-5 |
//!
//! No case is refused. Near a polygon's boundary fixed point refuses what it cannot resolve
//! (`tests/fixed_near.rs`; README, "Fixed point").
//!
//! ## Cost
//!
//! Per sample: the light's points minus `p` (three 64-bit subtractions each, taken twice:
//! once for the OR of their magnitudes, whose one leading-zero count gives the shift, once to
//! convert them), one conversion per coordinate with the shift folded in (fixed point: a
//! shift of the 32-bit halves and a rounding; f32: the FPU's 32-bit integer conversion with a
//! sticky bit, `real::i64_to_f32`, and a product by a power of two; no 64-bit shift
//! anywhere), then the light's model at `p = 0`, the plain model's cost. A polygon's Phong
//! terms also scale the polygon's ball (its centre as one more point, its radius as one more
//! value) for the proof of a negligible term (`polygon/negligible.rs`). The local polygon is
//! built where the model runs on it (no copy of it).
//!
//! Measured (exact instructions per call, the median of the QEMU budget's 16 inputs:
//! `cargo test -p host-sim --test qemu_budget`, its `W` lines, then `host-sim budget`): each
//! world case is its plain case's light 64 times as large and 1000 units from the origin
//! (`boards/qemu-budget/src/world_cases.rs`), every answer bit for bit the plain call's.
//!
//! <!-- BEGIN budget-world: target/budget/budget-world.md -->
//! | call | M4F f32: plain | M4F f32: world | M0 `Fixed22`: plain | M0 `Fixed22`: world | RV32IMC `Fixed22`: plain | RV32IMC `Fixed22`: world |
//! |---|---:|---:|---:|---:|---:|---:|
//! | `sphere_lambert` | 76 | 206 | 628 | 822 | 550 | 682 |
//! | `sphere_lambert_hermite` | 83 | 214 | 643 | 843 | 543 | 687 |
//! | `polygon_lambert` | 498 | 1088 | 1888 | 2484 | 1493 | 1842 |
//! | `phong_sphere` | 480 | 601 | 4612 | 4822 | 3702 | 3848 |
//! | `phong_polygon` | 1195 | 1951 | 8394 | 9267 | 6360 | 6871 |
//! <!-- END budget-world -->
//!
//! When these rows were first counted, the differences were copied, over the polygon's whole
//! capacity (8 vertices for a quad), and shifted in 64 bits, f32 converted them with
//! `__aeabi_l2f`, and the local polygon was built apart and copied into place: `polygon_lambert`
//! took 2 147 M4F f32 instructions and 7 254 M0 `Fixed22` ones, `sphere_lambert` 384 and
//! 1 533 (a build of those cases alone).
//!
//! The float types gain nothing in range from this (they have no limit), but take the same
//! path, so a scene description in world coordinates runs on any backend.

#[cfg(feature = "polygon")]
mod polygon;
#[cfg(feature = "cap")]
mod sphere;

#[cfg(feature = "polygon")]
pub use polygon::WorldPolygonLight;
#[cfg(feature = "cap")]
pub use sphere::WorldSphereLight;

use crate::{Error, Real, Vec3};

/// `2^32`: world units to raw bits.
const SCALE: f64 = 4_294_967_296.0;
/// The largest raw magnitude a coordinate may have, exclusive: `2^62` (`2^30` units).
const RAW_LIMIT: u64 = 1 << 62;

/// A point in world coordinates: each coordinate an `i64` in units of `2^-32` (I32F32), at
/// most `2^30` units in magnitude (see the [module docs](self)).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct WorldPoint {
    raw: [i64; 3],
}

impl WorldPoint {
    /// The largest coordinate magnitude, exclusive: `2^30` units.
    pub const LIMIT: f64 = 1_073_741_824.0;
    /// The spacing of representable coordinates: `2^-32` units.
    pub const RESOLUTION: f64 = 1.0 / SCALE;
    /// The origin.
    pub const ORIGIN: WorldPoint = WorldPoint { raw: [0; 3] };

    /// A point from its coordinates in world units, each rounded to the nearest multiple of
    /// [`WorldPoint::RESOLUTION`].
    ///
    /// # Errors
    /// [`Error::NotFinite`] or [`Error::OutOfRange`] (a coordinate of magnitude `2^30` or more
    /// after rounding), naming `param`.
    pub fn from_f64(v: [f64; 3], param: &'static str) -> Result<Self, Error> {
        let mut raw = [0i64; 3];
        for (r, x) in raw.iter_mut().zip(v) {
            if !x.is_finite() {
                return Err(Error::NotFinite(param));
            }
            let bits = libm::round(x * SCALE);
            if !(bits.abs() < RAW_LIMIT as f64) {
                return Err(Error::OutOfRange(param));
            }
            // In range: the conversion is exact.
            *r = bits as i64;
        }
        Ok(WorldPoint { raw })
    }

    /// A point from a [`Vec3`] of any backend (its coordinates read exactly in f64, then
    /// rounded as [`WorldPoint::from_f64`]).
    ///
    /// # Errors
    /// As [`WorldPoint::from_f64`].
    pub fn from_vec3<T: Real>(v: Vec3<T>, param: &'static str) -> Result<Self, Error> {
        Self::from_f64(v.to_f64(), param)
    }

    /// A point from its raw coordinates (units of `2^-32`).
    ///
    /// # Errors
    /// [`Error::OutOfRange`] (`"point"`) for a magnitude of `2^62` or more.
    pub const fn from_bits(raw: [i64; 3]) -> Result<Self, Error> {
        let mut i = 0;
        while i < 3 {
            if raw[i].unsigned_abs() >= RAW_LIMIT {
                return Err(Error::OutOfRange("point"));
            }
            i += 1;
        }
        Ok(WorldPoint { raw })
    }

    /// The raw coordinates (units of `2^-32`).
    pub const fn to_bits(self) -> [i64; 3] {
        self.raw
    }

    /// The coordinates in world units (exact up to `2^21` units, then rounded to f64's 53
    /// bits).
    pub fn to_f64(self) -> [f64; 3] {
        self.raw.map(|r| r as f64 / SCALE)
    }

    /// `self - p`, exact: both within `2^62` raw, the difference within `2^63`.
    #[inline(always)]
    fn minus(self, p: WorldPoint) -> [i64; 3] {
        [
            self.raw[0].wrapping_sub(p.raw[0]),
            self.raw[1].wrapping_sub(p.raw[1]),
            self.raw[2].wrapping_sub(p.raw[2]),
        ]
    }
}

/// Scales every value of `vals` by the one power of two that puts the largest magnitude in
/// `[2^61, 2^62]` (left shifts exact; a right shift by one bit, for magnitudes from `2^62`,
/// rounded half up). All zero: left as it is. Every `|v| < 2^63`. Returns the shift: `k >= 0`
/// for `2^k`, -1 for the halving. The reference of the tests: the lights convert without the
/// shifted copies ([`q60_shift`] and [`q60_scaled`], the same values).
#[cfg(test)]
fn scale_to_q60(vals: &mut [i64]) -> i32 {
    // The OR of the magnitudes has the largest one's leading bit.
    let k = q60_shift(vals.iter().fold(0u64, |m, v| m | v.unsigned_abs()));
    for v in vals.iter_mut() {
        *v = q60_shifted(*v, k);
    }
    k
}

/// [`scale_to_q60`]'s shift for values whose magnitudes OR to `m` (whose leading bit is the
/// largest magnitude's): `k >= 0` for `2^k`, -1 for the halving, 0 for `m = 0`.
#[inline(always)]
fn q60_shift(m: u64) -> i32 {
    match m.leading_zeros() {
        64 => 0,
        lz if lz >= 2 => lz as i32 - 2,
        _ => -1,
    }
}

/// `v` scaled by [`q60_shift`]'s `k`: `v 2^k`, or for `k = -1` halved, rounded half up
/// (without the overflow of `v + 1`).
#[inline(always)]
fn q60_shifted(v: i64, k: i32) -> i64 {
    if k >= 0 {
        v << k
    } else {
        (v >> 1) + (v & 1)
    }
}

/// `q60_shifted(v, k) 2^-60` in `T` (`T::from_q60` of it), without the 64-bit shift for
/// `k >= 0` (`Real::from_q60_shl`, the same bits).
#[inline(always)]
fn q60_scaled<T: Real>(v: i64, k: i32) -> T {
    if k >= 0 {
        T::from_q60_shl(v, k as u32)
    } else {
        T::from_q60(q60_shifted(v, k))
    }
}

/// [`q60_scaled`] of each coordinate.
#[inline(always)]
fn q60_vec3_scaled<T: Real>(v: [i64; 3], k: i32) -> Vec3<T> {
    Vec3::new(
        q60_scaled(v[0], k),
        q60_scaled(v[1], k),
        q60_scaled(v[2], k),
    )
}

/// The OR of the coordinates' magnitudes (the largest one's leading bit, for [`q60_shift`]).
#[inline(always)]
fn magnitudes(v: [i64; 3]) -> u64 {
    v[0].unsigned_abs() | v[1].unsigned_abs() | v[2].unsigned_abs()
}

/// `p` of the rescaled copies: the origin.
#[inline(always)]
fn origin<T: Real>() -> Vec3<T> {
    Vec3::new(T::ZERO, T::ZERO, T::ZERO)
}

/// A vector of `x 2^-60` coordinates in `T` (the reference of the tests, with
/// [`scale_to_q60`]).
#[cfg(test)]
fn q60_vec3<T: Real>(v: [i64; 3]) -> Vec3<T> {
    Vec3::new(T::from_q60(v[0]), T::from_q60(v[1]), T::from_q60(v[2]))
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::vec;

    #[test]
    fn scale_to_q60_puts_the_largest_in_range() {
        for shift in 2..63u32 {
            let x = 1i64 << shift;
            let mut v = [x, -x / 2, 3];
            scale_to_q60(&mut v);
            // x dominates: a left shift to 2^61 (exact), a right shift from 2^62.
            assert_eq!(v[0], 1 << 61, "{shift}: {v:?}");
            assert_eq!(v[1], -(1 << 60), "{shift}: {v:?}");
        }
        let mut v = [1, 0, 3];
        scale_to_q60(&mut v);
        assert_eq!(v, [1 << 60, 0, 3 << 60]);
        let mut v = [i64::MAX, i64::MIN + 1, -1];
        scale_to_q60(&mut v);
        // Half up: -(2^62 - 1/2) to -(2^62 - 1), -1/2 to 0.
        assert_eq!(v, [1 << 62, -(1 << 62) + 1, 0]);
        let mut z = [0i64; 3];
        scale_to_q60(&mut z);
        assert_eq!(z, [0; 3]);
    }

    /// `Real::from_q60_shl(x, k)` is `from_q60(x << k)` bit for bit on every backend, for
    /// every `k` and values up to the limit, `x << k` within an `i64` (its edges, powers of
    /// two and their neighbours, ties of fixed point's rounding, random bits).
    #[test]
    fn the_shifted_conversions_are_the_shifts() {
        fn check<T: Real>(x: i64, k: u32) {
            let (a, b) = (T::from_q60_shl(x, k), T::from_q60(x << k));
            assert!(
                a == b || (a.is_nan_like() && b.is_nan_like()),
                "{x} << {k}: {a:?} {b:?}"
            );
            assert_eq!(a.to_f64().to_bits(), b.to_f64().to_bits(), "{x} << {k}");
        }
        fn all(x: i64, k: u32) {
            check::<f64>(x, k);
            check::<f32>(x, k);
            check::<crate::Fast32>(x, k);
            #[cfg(feature = "fixed")]
            check::<crate::Fixed22>(x, k);
        }
        let mut next = crate::test_rng::xorshift32(0x0DDB_1A5E);
        for k in 0..=61u32 {
            let lim = i64::MAX >> k; // x << k within an i64
            let mut xs = vec![0, 1, -1, lim, -lim, lim - 1, 1 - lim];
            for e in 0..(63 - k) {
                let p = 1i64 << e;
                xs.extend([p, -p, p + 1, -p - 1, p - 1, 1 - p]);
                // Fixed point's ties: bit 37 - k set, nothing below.
                if k <= 37 && e + k >= 38 {
                    xs.push(p | (1 << (37 - k)));
                    xs.push(-(p | (1 << (37 - k))));
                }
            }
            for _ in 0..2000 {
                let raw = ((u64::from(next()) << 32) | u64::from(next())) as i64;
                xs.push(raw % lim);
            }
            for x in xs {
                all(x, k);
            }
        }
    }

    /// The lights' conversions without the shifted copies are [`scale_to_q60`] and
    /// `q60_vec3` of the differences, bit for bit (random points, sizes and distances over
    /// the whole range, the halving among them).
    #[test]
    fn the_lights_convert_as_the_scaled_copies() {
        fn go<T: Real>(d: [[i64; 3]; 4]) {
            let mut flat: [i64; 12] = [0; 12];
            for (i, v) in d.iter().enumerate() {
                flat[3 * i..3 * i + 3].copy_from_slice(v);
            }
            let k = scale_to_q60(&mut flat);
            let m = d.iter().fold(0u64, |m, v| m | magnitudes(*v));
            assert_eq!(q60_shift(m), k);
            for (i, v) in d.iter().enumerate() {
                let want: Vec3<T> = q60_vec3([flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]]);
                let got: Vec3<T> = q60_vec3_scaled(*v, k);
                assert_eq!(
                    [got.x, got.y, got.z].map(|c| c.to_f64().to_bits()),
                    [want.x, want.y, want.z].map(|c| c.to_f64().to_bits()),
                    "{d:?}"
                );
            }
        }
        let mut next = crate::test_rng::xorshift32(0x5EED_0001);
        for _ in 0..20_000 {
            let bits = next() % 64;
            let mut c = || {
                let raw = ((u64::from(next()) << 32) | u64::from(next())) as i64;
                raw >> (64 - bits.max(1))
            };
            let d = [
                [c(), c(), c()],
                [c(), c(), c()],
                [c(), c(), c()],
                [c(), c(), c()],
            ];
            go::<f64>(d);
            go::<f32>(d);
            go::<crate::Fast32>(d);
            #[cfg(feature = "fixed")]
            go::<crate::Fixed22>(d);
        }
    }

    #[test]
    fn from_f64_rounds_and_limits() {
        let p = WorldPoint::from_f64([1.5, -2.0f64.powi(-33), 1e9], "p").unwrap();
        assert_eq!(p.to_bits()[0], 3 << 31);
        assert_eq!(p.to_f64()[2], 1e9);
        assert_eq!(
            WorldPoint::from_f64([WorldPoint::LIMIT, 0.0, 0.0], "p"),
            Err(Error::OutOfRange("p"))
        );
        assert_eq!(
            WorldPoint::from_f64([0.0, f64::NAN, 0.0], "q"),
            Err(Error::NotFinite("q"))
        );
        assert_eq!(
            WorldPoint::from_bits([0, 1 << 62, 0]),
            Err(Error::OutOfRange("point"))
        );
        assert!(WorldPoint::from_bits([(1 << 62) - 1, 0, 0]).is_ok());
    }
}
