//! Three-component vectors and RGB triples over [`Real`].

use crate::{Error, Real, UnitVec3};
use core::ops::{Add, Mul, Neg, Sub};

/// A 3-vector: a point, a direction or an edge.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vec3<T> {
    /// x component.
    pub x: T,
    /// y component.
    pub y: T,
    /// z component.
    pub z: T,
}

impl<T: Real> Vec3<T> {
    /// `(x, y, z)`.
    #[inline(always)]
    pub const fn new(x: T, y: T, z: T) -> Self {
        Vec3 { x, y, z }
    }
    /// Converts each component from `f64` (rounding to nearest).
    #[inline]
    pub fn from_f64(v: [f64; 3]) -> Self {
        Vec3::new(T::from_f64(v[0]), T::from_f64(v[1]), T::from_f64(v[2]))
    }
    /// Each component as `f64`.
    #[inline]
    pub fn to_f64(self) -> [f64; 3] {
        [self.x.to_f64(), self.y.to_f64(), self.z.to_f64()]
    }
    /// `self - o` for two positions within [`Real::COORDINATE_LIMIT`] (every caller's
    /// validated vertices and checked shading points): the bits of `-`, without fixed point's
    /// saturation tests, which cannot trigger there (the sealed `sub3_small`).
    #[inline(always)]
    #[cfg_attr(not(feature = "polygon"), allow(dead_code))]
    pub(crate) fn offset_from(self, o: Self) -> Self {
        if T::RESOLUTION == T::ZERO {
            // The floats' `-` itself (the array form cost the Cortex-M4F polygon Lambert 6
            // instructions through its inlining).
            return self - o;
        }
        let [x, y, z] = T::sub3_small([self.x, self.y, self.z], [o.x, o.y, o.z]);
        Vec3::new(x, y, z)
    }
    /// Dot product.
    #[inline(always)]
    pub fn dot(self, o: Self) -> T {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    /// Cross product.
    #[inline(always)]
    pub fn cross(self, o: Self) -> Self {
        Vec3::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }
    /// Euclidean length (may overflow to infinity for huge components; see [`Vec3::normalize`]).
    #[inline(always)]
    pub fn length(self) -> T {
        self.dot(self).sqrt()
    }
    /// `(self / d, d)` with `d` near `m = self.max_abs() > 0` (through [`Real::rescale3`]:
    /// `d = m` for the floats, a power of two for fixed point).
    #[inline(always)]
    pub fn rescale(self, m: T) -> (Self, T) {
        let ([x, y, z], d) = T::rescale3([self.x, self.y, self.z], m);
        (Vec3::new(x, y, z), d)
    }
    /// `true` if every component is finite.
    #[inline(always)]
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite() && self.z.is_finite()
    }
    /// The largest absolute component.
    #[inline(always)]
    pub fn max_abs(self) -> T {
        self.x.abs().max(self.y.abs()).max(self.z.abs())
    }
    /// Unit vector in the same direction, or `None` for a zero or non-finite vector.
    ///
    /// f64, f32 and [`crate::Fast32`] (f32's operations, bit for bit): every finite nonzero
    /// vector has a direction, down to the smallest subnormal component and up to the largest
    /// finite ones. The squared length is computed directly and the vector scaled by its
    /// inverse square root; only a squared length that under- or overflows (below `2^-100` in
    /// f32, `2^-960` in f64, or infinite) takes a cold path that first scales the vector by a
    /// power of two (exact). Each component within 1.5 ULP of 1 (measured,
    /// `tests/normalize.rs`). Cost (hot path): 5 operations for the squared length, 1
    /// unsigned comparison of its bits, 1 square root, 1 division, 3 products: 39 instructions
    /// a call on the Cortex-M4F with 2 float comparisons instead (`VSQRT.F32`; 83 rescaled),
    /// 1756 on the Cortex-M0 in soft float (2499), QEMU exact counts of one non-inlined call
    /// (`Fast32`: 42 and 1761, against 119 and 3509 for the rescaled form with its own `rsqrt`).
    ///
    /// `Fixed22`: the rescaled form: scaled by a power of two near the largest component first
    /// (exact shifts, since its squares would vanish or saturate otherwise), and a vector whose
    /// largest component is not above [`Real::TINY`] counts as zero; then 1 [`Real::rsqrt`].
    ///
    /// See [`Real::normalize3`].
    #[inline]
    pub fn normalize(self) -> Option<Self> {
        T::unit3([self.x, self.y, self.z]).map(|[x, y, z]| Vec3::new(x, y, z))
    }
    /// Like [`Vec3::normalize`] but also returns the original length (for the floats its
    /// square root of the squared length, within 2 ULPs; infinite if the length itself exceeds
    /// the type's range).
    #[inline]
    pub fn normalize_with_length(self) -> Option<(Self, T)> {
        T::normalize3([self.x, self.y, self.z]).map(|([x, y, z], len)| (Vec3::new(x, y, z), len))
    }
    /// Validating normalization for constructors: `param` names the parameter in the error.
    pub fn try_normalize(self, param: &'static str) -> Result<Self, Error> {
        if !self.is_finite() {
            return Err(Error::NotFinite(param));
        }
        self.normalize().ok_or(Error::ZeroLength(param))
    }
    /// `Ok(self)` if every coordinate is finite and within [`Real::COORDINATE_LIMIT`], the
    /// check every constructor makes of a position.
    ///
    /// # Errors
    /// [`Error::NotFinite`] or [`Error::OutOfRange`], naming `param`.
    pub fn check_position(self, param: &'static str) -> Result<Self, Error> {
        if !self.is_finite() {
            return Err(Error::NotFinite(param));
        }
        // Folds away for the float types (no limit); compared in T, where the limit is exact
        // (fixed point: no soft-float f64 per sample).
        if T::COORDINATE_LIMIT < f64::MAX && !T::within_coordinate_limit([self.x, self.y, self.z]) {
            return Err(Error::OutOfRange(param));
        }
        Ok(self)
    }
    /// A unit vector perpendicular to `self` (which must be unit length).
    #[inline]
    pub fn any_perpendicular(self) -> Self {
        let t = if self.x.abs() < T::from_f64(0.57) {
            Vec3::new(T::ONE, T::ZERO, T::ZERO)
        } else {
            Vec3::new(T::ZERO, T::ONE, T::ZERO)
        };
        let c = self.cross(t);
        c.normalize().unwrap_or(Vec3::new(T::ZERO, T::ZERO, T::ONE))
    }
}

impl<T: Real> Add for Vec3<T> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Vec3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}
impl<T: Real> Sub for Vec3<T> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Vec3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}
impl<T: Real> Mul<T> for Vec3<T> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, s: T) -> Self {
        Vec3::new(self.x * s, self.y * s, self.z * s)
    }
}
impl<T: Real> Neg for Vec3<T> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Vec3::new(-self.x, -self.y, -self.z)
    }
}

/// A linear RGB triple (radiance or irradiance per channel).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rgb<T> {
    /// Red.
    pub r: T,
    /// Green.
    pub g: T,
    /// Blue.
    pub b: T,
}

impl<T: Real> Rgb<T> {
    /// `(r, g, b)`.
    #[inline(always)]
    pub const fn new(r: T, g: T, b: T) -> Self {
        Rgb { r, g, b }
    }
    /// The same value in every channel.
    #[inline(always)]
    pub const fn splat(v: T) -> Self {
        Rgb { r: v, g: v, b: v }
    }
    /// Converts each channel from `f64`.
    #[inline]
    pub fn from_f64(c: [f64; 3]) -> Self {
        Rgb::new(T::from_f64(c[0]), T::from_f64(c[1]), T::from_f64(c[2]))
    }
    /// Each channel as `f64`.
    #[inline]
    pub fn to_f64(self) -> [f64; 3] {
        [self.r.to_f64(), self.g.to_f64(), self.b.to_f64()]
    }
    /// `true` if every channel is finite.
    #[inline]
    pub fn is_finite(self) -> bool {
        self.r.is_finite() && self.g.is_finite() && self.b.is_finite()
    }
    /// Validating constructor check: `param` names the parameter in the error.
    pub fn check_finite(self, param: &'static str) -> Result<Self, Error> {
        if self.is_finite() {
            Ok(self)
        } else {
            Err(Error::NotFinite(param))
        }
    }
    /// Channel-wise sum.
    #[inline(always)]
    #[allow(clippy::should_implement_trait)]
    pub fn add(self, o: Self) -> Self {
        Rgb::new(self.r + o.r, self.g + o.g, self.b + o.b)
    }
    /// Scales every channel.
    #[inline(always)]
    pub fn scale(self, s: T) -> Self {
        Rgb::new(self.r * s, self.g * s, self.b * s)
    }
    /// Replaces a non-finite channel by 0 (the per-sample fallback).
    #[inline(always)]
    pub fn finite_or_zero(self) -> Self {
        Rgb::new(
            self.r.finite_or_zero(),
            self.g.finite_or_zero(),
            self.b.finite_or_zero(),
        )
    }
}

/// `(cos w, sin w)` of the angle `w` between two unit vectors, made consistent
/// (`c^2 + s^2 = 1` to rounding): the smaller of the two comes from the dot or cross product
/// (absolute error of a few ULPs, fine for a small value) and the larger from
/// `sqrt((1 - x)(1 + x))` of it, so it carries only a relative error of a few ULPs. Computing
/// both directly would leave the larger one off by an absolute ULP, which a power `s^m` or
/// `c^m` of a Phong recurrence multiplies by `m`.
#[inline]
#[allow(dead_code)] // shared by several model families; unused when none of them is enabled
pub(crate) fn cos_sin_between<T: Real>(d: UnitVec3<T>, axis: UnitVec3<T>) -> (T, T) {
    let (c, s) = d.dot_and_cross_length(axis);
    let (c, s) = (c.clamp(-T::ONE, T::ONE), s.min(T::ONE));
    // The factors lie in [0, 2]: `mul_le2`, the bits of `*` (fixed point: no saturation test,
    // three 32-bit products).
    if c.abs() <= s {
        (c, T::mul_le2(T::ONE - c, T::ONE + c).sqrt())
    } else {
        let mag = T::mul_le2(T::ONE - s, T::ONE + s).sqrt();
        (if c < T::ZERO { -mag } else { mag }, s)
    }
}

/// `(cos w, sin w, w)` between a per-sample direction `d` (any length, or a
/// [`UnitVec3`](crate::UnitVec3)) and a unit `axis`, or `None` when `d` is zero or not finite.
/// Cost: one normalization (none for a `UnitVec3`), a cross product, 2 sqrt, 1 atan2.
#[inline]
#[allow(dead_code)] // shared by several model families; unused when none of them is enabled
pub(crate) fn angle_to<T: Real>(
    d: impl crate::Direction<T>,
    axis: UnitVec3<T>,
) -> Option<(T, T, T)> {
    let d = d.to_unit()?;
    let (c, s) = cos_sin_between(d, axis);
    Some((c, s, s.atan2(c)))
}
