//! Materials and shaders: what colour a surface point gets.
//!
//! The renderer asks a [`Shader`] for the colour at a world point `p` with unit normal `n`
//! seen from the unit direction `v` (toward the eye), at the vertices (Gouraud) or at every
//! pixel, as [`Shading`] chooses per draw call. [`Lit`] is the shader of the crate's lights:
//! a [`Material`] under any [`Illuminant`]; any closure `Fn(p, n, v) -> Rgb` is a shader too
//! (the host simulator uses that for Arvo's glossy reflection and transmission).

use super::RasterError;
use crate::illuminant::{mul_rgb, Illuminant};
use crate::{PhongLobe, Real, Rgb, UnitVec3, Vec3};

/// Where the shader runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Shading {
    /// At the three vertices, the colours interpolated (perspective-correct) across the
    /// triangle: 3 shader calls per triangle drawn, whatever its size.
    Gouraud,
    /// At every pixel, with the interpolated (perspective-correct) position and renormalized
    /// normal: 1 shader call per visible pixel.
    PerPixel,
}

/// Computes the colour of a surface point.
pub trait Shader<T: Real> {
    /// The linear colour at world point `p` with unit normal `n` (facing the viewer for
    /// two-sided surfaces), `v` the unit direction from `p` toward the eye. Should be finite;
    /// the renderer maps a non-finite channel to 0.
    fn shade(&self, p: Vec3<T>, n: UnitVec3<T>, v: UnitVec3<T>) -> Rgb<T>;
}

impl<T: Real, F: Fn(Vec3<T>, UnitVec3<T>, UnitVec3<T>) -> Rgb<T>> Shader<T> for F {
    #[inline]
    fn shade(&self, p: Vec3<T>, n: UnitVec3<T>, v: UnitVec3<T>) -> Rgb<T> {
        self(p, n, v)
    }
}

/// A surface: diffuse colour, specular colour and Phong exponent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material<T> {
    /// Diffuse reflectance per channel (multiplies [`Illuminant::diffuse`]).
    pub diffuse: Rgb<T>,
    /// Specular reflectance per channel (multiplies [`Illuminant::phong`]); black skips the
    /// Phong evaluation.
    pub specular: Rgb<T>,
    /// The Phong lobe (exponent and its constants).
    pub lobe: PhongLobe<T>,
}

impl<T: Real> Material<T> {
    /// A material with `diffuse` and `specular` colours and Phong exponent `m`.
    ///
    /// # Errors
    /// [`RasterError::Model`] with [`crate::Error::NotFinite`] (`"diffuse"`, `"specular"`) or
    /// [`crate::Error::ExponentOutOfRange`].
    pub fn new(diffuse: Rgb<T>, specular: Rgb<T>, m: u32) -> Result<Self, RasterError> {
        Ok(Material {
            diffuse: diffuse.check_finite("diffuse")?,
            specular: specular.check_finite("specular")?,
            lobe: PhongLobe::new(m)?,
        })
    }

    /// A matte material (no specular term).
    ///
    /// # Errors
    /// As [`Material::new`].
    pub fn matte(diffuse: Rgb<T>) -> Result<Self, RasterError> {
        Self::new(diffuse, Rgb::splat(T::ZERO), 1)
    }
}

/// The mirror direction `2 (n.v) n - v` of `v` about the unit normal `n`: unit by
/// construction (the mirror of a unit vector), to the rounding of its 6 multiply-adds.
/// Fixed point forms its products without saturation tests (unit vectors, and `2 (n.v)` at
/// most 2: factors below 16), the bits of `n * (2 n.dot(v)) - v`.
#[inline]
pub fn reflect<T: Real>(v: UnitVec3<T>, n: UnitVec3<T>) -> UnitVec3<T> {
    let k = T::TWO * n.dot_unit(v);
    let (v, n) = (v.into_inner(), n.into_inner());
    let s = |c: T| T::mul_small(c, k);
    UnitVec3::new_unchecked(Vec3::new(s(n.x), s(n.y), s(n.z)) - v)
}

/// A [`Material`] lit by an [`Illuminant`]: `diffuse * light.diffuse(p, n) +
/// specular * light.phong(lobe, p, reflect(v, n))`.
#[derive(Debug)]
pub struct Lit<'a, T, L: ?Sized> {
    /// The light (any [`Illuminant`]: one light, an array or slice of them, a tinted or
    /// shaped light...).
    pub light: &'a L,
    /// The surface.
    pub material: &'a Material<T>,
}

impl<'a, T, L: ?Sized> Lit<'a, T, L> {
    /// `material` under `light`.
    pub fn new(light: &'a L, material: &'a Material<T>) -> Self {
        Lit { light, material }
    }
}

impl<T: Real, L: Illuminant<T> + ?Sized> Shader<T> for Lit<'_, T, L> {
    /// Accuracy: that of the light's models (plus a few ULPs for the products). Cost: one
    /// [`Illuminant::diffuse`], one [`Illuminant::phong`] unless the specular colour is
    /// black, a reflection (6 multiply-adds) and 6 multiply-adds.
    #[inline]
    fn shade(&self, p: Vec3<T>, n: UnitVec3<T>, v: UnitVec3<T>) -> Rgb<T> {
        let m = self.material;
        let s = m.specular;
        let c = if s.r > T::ZERO || s.g > T::ZERO || s.b > T::ZERO {
            // Both terms in one call: a light that shares work between them does it once.
            let r = reflect(v, n);
            let (d, ph) = self.light.diffuse_and_phong(&m.lobe, p, n, r);
            mul_rgb(m.diffuse, d).add(mul_rgb(s, ph))
        } else {
            mul_rgb(m.diffuse, self.light.diffuse(p, n))
        };
        c.finite_or_zero()
    }
}
