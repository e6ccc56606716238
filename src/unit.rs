//! Unit vectors carried by type: normalize once, use everywhere.
//!
//! Every per-sample function of the models takes its directions (the normal `n`, the reflection
//! direction `r`) as `impl` [`Direction`]: a plain [`Vec3`] of any length, which the function
//! normalizes (and answers its documented fallback for a zero or non-finite vector), or a
//! [`UnitVec3`], which it uses as it is. A renderer normalizes the interpolated normal of a pixel
//! once into a `UnitVec3` and hands it to every light, as nalgebra's `Unit<T>` does for its
//! vectors; the [`Illuminant`](crate::Illuminant) and [`Shader`](crate::raster::Shader) traits
//! take `UnitVec3` for that reason.
//!
//! A `UnitVec3` can only be made by normalizing ([`UnitVec3::new`], [`Vec3::to_unit`]), from
//! the coordinate axes, by negating one, or by the crate itself where the result is unit by
//! construction (the mirror direction of [`reflect`](crate::raster::reflect)). Its length is 1
//! within the backend's rounding: 1.5 ULP per component for the floats (`tests/normalize.rs`),
//! a few LSB of 2^-22 for [`Fixed22`](crate::Fixed22); it is always finite.
//!
//! Cost: a call with a `UnitVec3` skips the normalization the call makes of a `Vec3`, measured
//! (exact QEMU counts of the same calls both ways, the README's "With a unit normal"): 6 to
//! 43 instructions per call on the Cortex-M4F in f32 (`hemi_const` 47 -> 30), 237 to 265 on the
//! Cortex-M0 in `Fixed22` (`hemi_const` 284 -> 40), 249 to 267 on RV32IMC in `Fixed22`.

use crate::{Error, Real, Vec3};
use core::ops::{Deref, Neg};

/// A direction of unit length (within the backend's rounding), normalized once and carried by
/// type. Dereferences to its [`Vec3`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnitVec3<T>(Vec3<T>);

impl<T: Real> UnitVec3<T> {
    /// The unit vector along `v`, or `None` for a zero or non-finite `v` (see
    /// [`Vec3::normalize`] for the accuracy and the cost of each backend).
    #[inline]
    pub fn new(v: Vec3<T>) -> Option<Self> {
        v.normalize().map(UnitVec3)
    }

    /// Like [`UnitVec3::new`], for constructors: `param` names the parameter in the error.
    ///
    /// # Errors
    /// [`Error::NotFinite`] or [`Error::ZeroLength`], naming `param`.
    #[inline]
    pub fn try_new(v: Vec3<T>, param: &'static str) -> Result<Self, Error> {
        v.try_normalize(param).map(UnitVec3)
    }

    /// `+x`.
    #[inline]
    pub fn x_axis() -> Self {
        UnitVec3(Vec3::new(T::ONE, T::ZERO, T::ZERO))
    }
    /// `+y`.
    #[inline]
    pub fn y_axis() -> Self {
        UnitVec3(Vec3::new(T::ZERO, T::ONE, T::ZERO))
    }
    /// `+z`.
    #[inline]
    pub fn z_axis() -> Self {
        UnitVec3(Vec3::new(T::ZERO, T::ZERO, T::ONE))
    }

    /// The vector.
    #[inline(always)]
    pub fn into_inner(self) -> Vec3<T> {
        self.0
    }

    /// The dot product with another unit vector: the value of [`Vec3::dot`], bit for bit. In
    /// fixed point both factors are known to be at most 1 (within rounding), so the products
    /// and the sum skip their saturation tests (M0 `Fixed22` about 40 instructions instead of
    /// 95) and each product takes three 32-bit products instead of four (the sealed
    /// `dot3_le2`, about 12 fewer); the floats compile to the same code as `Vec3::dot`.
    #[inline(always)]
    #[allow(dead_code)] // the families with an axis; unused when none of them is enabled
    pub(crate) fn dot_unit(self, o: UnitVec3<T>) -> T {
        T::dot3_le2(self.array(), o.array())
    }

    /// The cosine `self . o` for the Lambert-type terms (whose value moves no more than the
    /// cosine does): [`UnitVec3::dot_unit`]'s bits on the floats; in fixed point through
    /// Q15, one 32-bit product a component, within 5.3e-5 (the sealed `cos_unit`). Not for
    /// the Phong terms, whose sensitivity to the cosine grows with the exponent.
    #[inline(always)]
    #[allow(dead_code)] // the families with an axis; unused when none of them is enabled
    pub(crate) fn cos_to(self, o: UnitVec3<T>) -> T {
        T::cos_unit(self.array(), o.array())
    }

    /// `(cos w, |self x o|)` of the angle `w` to another unit vector: [`Vec3::dot`] and the
    /// length of [`Vec3::cross`], bit for bit, with [`UnitVec3::dot_unit`]'s cheaper fixed
    /// point (the cross product's components are at most 1 too, by Cauchy-Schwarz).
    #[inline(always)]
    #[allow(dead_code)] // the families with an axis; unused when none of them is enabled
    pub(crate) fn dot_and_cross_length(self, o: UnitVec3<T>) -> (T, T) {
        let (a, b) = (self.array(), o.array());
        let c = T::cross3_le2(a, b);
        (T::dot3_le2(a, b), T::dot3_le2(c, c).sqrt())
    }

    /// `(self . o, self x o)`: [`Vec3::dot`] and [`Vec3::cross`], bit for bit, with
    /// [`UnitVec3::dot_unit`]'s cheaper fixed point.
    #[inline(always)]
    #[cfg(all(feature = "polygon", feature = "phong"))]
    pub(crate) fn dot_and_cross(self, o: UnitVec3<T>) -> (T, Vec3<T>) {
        let (a, b) = (self.array(), o.array());
        let [x, y, z] = T::cross3_le2(a, b);
        (T::dot3_le2(a, b), Vec3::new(x, y, z))
    }

    /// The scalar triple product `self . (g x s)` of three unit vectors: the value of
    /// `self.dot(g.cross(s))`, bit for bit, with [`UnitVec3::dot_unit`]'s cheaper fixed point
    /// (the cross product's components are at most 1).
    #[inline(always)]
    #[cfg(all(feature = "polygon", any(feature = "phong", feature = "moments")))]
    pub(crate) fn triple(self, g: UnitVec3<T>, s: UnitVec3<T>) -> T {
        T::dot3_le2(self.array(), T::cross3_le2(g.array(), s.array()))
    }

    /// The quadratic monomials of SH9 irradiance, `[x y, y z, x z, z z, x x - y y]`: the
    /// values of the plain products, bit for bit, with [`UnitVec3::dot_unit`]'s cheaper
    /// fixed point (every factor at most 1).
    #[inline(always)]
    #[cfg(feature = "sh9")]
    pub(crate) fn quadratic_monomials(self) -> [T; 5] {
        let (x, y, z) = (self.0.x, self.0.y, self.0.z);
        let m = T::mul_le2;
        // x x - y y: both at most 1, so the difference cannot saturate.
        [m(x, y), m(y, z), m(x, z), m(z, z), m(x, x) - m(y, y)]
    }

    #[inline(always)]
    #[allow(dead_code)] // as `dot_unit`
    pub(crate) fn array(self) -> [T; 3] {
        [self.0.x, self.0.y, self.0.z]
    }

    /// Wraps a vector the crate has made unit by construction (a normalized vector, the mirror
    /// of one unit vector about another). Not public: a `UnitVec3` from outside is always
    /// normalized by the crate.
    #[inline(always)]
    #[cfg_attr(not(feature = "raster"), allow(dead_code))] // the rasterizer's (reflect, view)
    pub(crate) fn new_unchecked(v: Vec3<T>) -> Self {
        UnitVec3(v)
    }
}

/// A light's fixed unit axis, with the form the Lambert-type cosine takes of it prepared once
/// (the sealed `prepare_axis`: in fixed point its Q15 rounding, which
/// [`UnitVec3::cos_to`] makes on every call; on the floats the axis itself).
#[derive(Clone, Copy, Debug, PartialEq)]
#[allow(dead_code)] // the families with an axis; unused when none of them is enabled
pub(crate) struct LightAxis<T> {
    unit: UnitVec3<T>,
    prepared: [T; 3],
}

#[allow(dead_code)] // as `LightAxis`
impl<T: Real> LightAxis<T> {
    /// The axis `unit`, prepared.
    #[inline]
    pub(crate) fn new(unit: UnitVec3<T>) -> Self {
        LightAxis {
            unit,
            prepared: T::prepare_axis(unit.array()),
        }
    }
    /// The unit axis.
    #[inline(always)]
    pub(crate) fn unit(&self) -> UnitVec3<T> {
        self.unit
    }
    /// `n.cos_to(self.unit())`, bit for bit, without the axis's rounding (the sealed
    /// `cos_axis`).
    #[inline(always)]
    pub(crate) fn cos_from(&self, n: UnitVec3<T>) -> T {
        T::cos_axis(n.array(), self.prepared)
    }
    /// The prepared form (the sealed `mix_by_cos`).
    #[inline(always)]
    pub(crate) fn prepared(&self) -> [T; 3] {
        self.prepared
    }
}

impl<T> Deref for UnitVec3<T> {
    type Target = Vec3<T>;
    #[inline(always)]
    fn deref(&self) -> &Vec3<T> {
        &self.0
    }
}

impl<T: Real> Neg for UnitVec3<T> {
    type Output = Self;
    /// The opposite direction (exact: still unit).
    #[inline(always)]
    fn neg(self) -> Self {
        UnitVec3(-self.0)
    }
}

impl<T: Real> From<UnitVec3<T>> for Vec3<T> {
    #[inline(always)]
    fn from(u: UnitVec3<T>) -> Vec3<T> {
        u.0
    }
}

impl<T: Real> Vec3<T> {
    /// The unit vector along `self` as a [`UnitVec3`], or `None` for a zero or non-finite
    /// vector (as [`Vec3::normalize`]).
    #[inline]
    pub fn to_unit(self) -> Option<UnitVec3<T>> {
        UnitVec3::new(self)
    }
}

/// A direction argument: a [`Vec3`] of any length (normalized by the call) or a [`UnitVec3`]
/// (used as it is). Implemented for exactly these two; per-sample functions are generic over
/// it, so a call with a `UnitVec3` compiles without the normalization.
pub trait Direction<T: Real>: Copy {
    /// The unit direction, or `None` for a zero or non-finite vector (then the caller answers
    /// its documented fallback).
    fn to_unit(self) -> Option<UnitVec3<T>>;
    /// Like [`Direction::to_unit`] with a precise error naming `param`.
    ///
    /// # Errors
    /// [`Error::NotFinite`] or [`Error::ZeroLength`] (never for a [`UnitVec3`]).
    fn try_unit(self, param: &'static str) -> Result<UnitVec3<T>, Error>;
}

impl<T: Real> Direction<T> for Vec3<T> {
    /// [`Vec3::normalize`].
    #[inline(always)]
    fn to_unit(self) -> Option<UnitVec3<T>> {
        UnitVec3::new(self)
    }
    /// [`UnitVec3::try_new`].
    #[inline(always)]
    fn try_unit(self, param: &'static str) -> Result<UnitVec3<T>, Error> {
        UnitVec3::try_new(self, param)
    }
}

impl<T: Real> Direction<T> for UnitVec3<T> {
    /// Itself: no work.
    #[inline(always)]
    fn to_unit(self) -> Option<UnitVec3<T>> {
        Some(self)
    }
    /// Itself: no work.
    #[inline(always)]
    fn try_unit(self, _param: &'static str) -> Result<UnitVec3<T>, Error> {
        Ok(self)
    }
}
