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
//! Per sample: three 64-bit subtractions per point of the light, one leading-zero count and a
//! shift per coordinate, one conversion per coordinate (fixed point: a shift and a rounding;
//! f32: an integer-to-float conversion and a product), then the light's model at `p = 0`, the
//! plain model's cost. A polygon's Phong terms also scale the polygon's ball (its centre as
//! one more point, its radius as one more value) for the proof of a negligible term
//! (`polygon/negligible.rs`). Not yet counted on the targets: the QEMU budget image for the Cortex-M0
//! has 940 bytes of its 256 KiB map left (`llvm-size -A`); adding the world lights' cases there
//! is open work.
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
/// for `2^k`, -1 for the halving.
#[inline]
fn scale_to_q60(vals: &mut [i64]) -> i32 {
    // The OR of the magnitudes has the largest one's leading bit.
    let m = vals.iter().fold(0u64, |m, v| m | v.unsigned_abs());
    if m == 0 {
        return 0;
    }
    let lz = m.leading_zeros();
    if lz >= 2 {
        let k = lz - 2;
        for v in vals.iter_mut() {
            *v <<= k;
        }
        k as i32
    } else {
        for v in vals.iter_mut() {
            // Half up, without the overflow of `v + 1`.
            *v = (*v >> 1) + (*v & 1);
        }
        -1
    }
}

/// `p` of the rescaled copies: the origin.
#[inline(always)]
fn origin<T: Real>() -> Vec3<T> {
    Vec3::new(T::ZERO, T::ZERO, T::ZERO)
}

/// A vector of `x 2^-60` coordinates in `T`.
#[inline(always)]
fn q60_vec3<T: Real>(v: [i64; 3]) -> Vec3<T> {
    Vec3::new(T::from_q60(v[0]), T::from_q60(v[1]), T::from_q60(v[2]))
}

#[cfg(test)]
mod tests {
    use super::*;

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
