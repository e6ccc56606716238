//! [`Illuminant`]: one interface over every light of the crate, so a renderer (the `raster`
//! module, a firmware's own scanline loop) can shade with any of them.
//!
//! A light answers two per-sample questions at a surface point `p`:
//!
//! - [`Illuminant::diffuse`]: the Lambertian irradiance for the unit normal `n`, per channel,
//!   in the light's normalized units (a unit-radiance light filling the hemisphere of `n`
//!   gives 1);
//! - [`Illuminant::phong`]: the Phong term of Snyder's model (his eq. 10, `(m + 1)/(2 pi)`
//!   times the integral of the radiance times `((u.r)+)^m`) for the unit reflection direction
//!   `r = 2 (n.v) n - v` of the view direction `v` (or Picott's peak approximation, for the
//!   lights that have no Phong integral in the crate: stated per implementation).
//!
//! The directions are [`UnitVec3`]s: the renderer normalizes a pixel's normal (and the view
//! and reflection directions) once, and no light normalizes them again (each model's cost
//! below is then its cost without the normalization of `n` or `r`; [`crate::unit`]).
//!
//! Both return finite values for every input (0 where the light's own model has no value: a
//! point inside a sphere light) and never panic; each implementation's accuracy
//! and cost are those of the model it calls, listed on it below.
//!
//! Implemented for the crate's lights (each behind its family's feature; the Phong parts of the
//! Snyder models behind `phong`, where without that feature the term is 0):
//!
//! | light | `diffuse` | `phong` |
//! |---|---|---|
//! | [`HemisphereLight`](crate::HemisphereLight) | `hemi_const` | `phong_hemi_const` |
//! | [`OvercastSky`](crate::OvercastSky) | `sky_overcast` | `C/3 phong_hemi_const + 2C/3 phong_hemi_cos` (exact: the radiance is that sum) |
//! | [`SkyGround`](crate::SkyGround) | `sky_ground` | `sky phong_hemi_const(up) + ground phong_hemi_const(-up)` (exact) |
//! | [`CapLight`](crate::CapLight), [`SphereLight`](crate::SphereLight) | `cap_lambert`, `sphere_lambert` | `phong_cap`, `phong_sphere` |
//! | [`PolygonLight`](crate::PolygonLight) | `polygon_lambert` | `phong_polygon` |
//! | [`LineLight`](crate::LineLight) | `line_lambert`, k = 2 (inverse square) | `line_phong_peak` (the peak, Picott) |
//! | [`ParallelogramLight`](crate::ParallelogramLight) | `polygon_lambert` of its four corners | `rect_phong_peak` (the peak, Picott) |
//! | [`Sh9Irradiance`](crate::Sh9Irradiance) | `sh9_irradiance / pi` | 0 (no specular model) |
//! | [`DirectionalLuminaire`] | `directional_luminaire / pi` (Arvo 6.1) | 0 |
//! | [`DirectionalLight`], [`PointLight`] | `(n.l)+` (point: optionally `/d^2`) | `((r.l)+)^m` |
//! | [`Ambient`] | the colour | 0 |
//!
//! and for the combinators: [`Tinted`] (a colour times a light), [`Shaped`] (a light times an
//! [`Uberlight`](crate::Uberlight) factor, `shaping` feature), references, arrays and slices
//! (the sum of their lights).

use crate::{PhongLobe, Real, Rgb, UnitVec3, Vec3};

/// A light that can shade a surface point: see the module docs.
pub trait Illuminant<T: Real> {
    /// Lambertian irradiance at `p` with unit normal `n`, per channel, normalized as the
    /// light's model is (see the module table). Finite; 0 where the model has no value.
    fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T>;
    /// Phong term at `p` for the unit reflection direction `r` and the lobe's exponent.
    /// Finite; 0 where the model has no value.
    fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T>;
    /// Both terms at one point, `(diffuse(p, n), phong(lobe, p, r))`, bit for bit: a light
    /// that computes something per point for both (the sphere's cap, a [`Scene`](crate::Scene)'s
    /// shaping factors) computes it once. The default calls the two. Cost: at most theirs.
    #[inline]
    fn diffuse_and_phong(
        &self,
        lobe: &PhongLobe<T>,
        p: Vec3<T>,
        n: UnitVec3<T>,
        r: UnitVec3<T>,
    ) -> (Rgb<T>, Rgb<T>) {
        (self.diffuse(p, n), self.phong(lobe, p, r))
    }
}

#[inline(always)]
fn grey<T: Real>(x: T) -> Rgb<T> {
    Rgb::splat(x)
}

#[inline(always)]
fn black<T: Real>() -> Rgb<T> {
    Rgb::splat(T::ZERO)
}

/// Channel-wise product (fixed point: without saturation tests where one side lies within
/// `(-1, 1]`, the same bits).
#[inline(always)]
pub(crate) fn mul_rgb<T: Real>(a: Rgb<T>, b: Rgb<T>) -> Rgb<T> {
    let [r, g, b] = T::mul_each([a.r, a.g, a.b], [b.r, b.g, b.b]);
    Rgb::new(r, g, b)
}

impl<T: Real, L: Illuminant<T> + ?Sized> Illuminant<T> for &L {
    /// The referenced light's [`Illuminant::diffuse`].
    #[inline]
    fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        (**self).diffuse(p, n)
    }
    /// The referenced light's [`Illuminant::phong`].
    #[inline]
    fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
        (**self).phong(lobe, p, r)
    }
    /// The referenced light's [`Illuminant::diffuse_and_phong`].
    #[inline]
    fn diffuse_and_phong(
        &self,
        lobe: &PhongLobe<T>,
        p: Vec3<T>,
        n: UnitVec3<T>,
        r: UnitVec3<T>,
    ) -> (Rgb<T>, Rgb<T>) {
        (**self).diffuse_and_phong(lobe, p, n, r)
    }
}

impl<T: Real, L: Illuminant<T>> Illuminant<T> for [L] {
    /// The sum over the lights (light transport is linear). Cost: the sum of theirs.
    #[inline]
    fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        self.iter()
            .fold(black(), |acc, l| acc.add(l.diffuse(p, n)))
            .finite_or_zero()
    }
    /// The sum over the lights. Cost: the sum of theirs.
    #[inline]
    fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
        self.iter()
            .fold(black(), |acc, l| acc.add(l.phong(lobe, p, r)))
            .finite_or_zero()
    }
}

impl<T: Real, L: Illuminant<T>, const K: usize> Illuminant<T> for [L; K] {
    /// The sum over the lights, as for slices.
    #[inline]
    fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        self[..].diffuse(p, n)
    }
    /// The sum over the lights, as for slices.
    #[inline]
    fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
        self[..].phong(lobe, p, r)
    }
}

/// A light times a colour (the lights of the crate are unit radiance; this gives them one).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tinted<T, L> {
    /// The light.
    pub light: L,
    /// Its colour (radiance scale per channel).
    pub colour: Rgb<T>,
}

impl<T: Real, L> Tinted<T, L> {
    /// `light` scaled by `colour`.
    ///
    /// # Errors
    /// [`crate::Error::NotFinite`] (`"colour"`).
    pub fn new(light: L, colour: Rgb<T>) -> Result<Self, crate::Error> {
        Ok(Tinted {
            light,
            colour: colour.check_finite("colour")?,
        })
    }
}

impl<T: Real, L: Illuminant<T>> Illuminant<T> for Tinted<T, L> {
    /// The light's diffuse term times the colour. Cost: theirs plus 3 multiplications.
    #[inline]
    fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        mul_rgb(self.light.diffuse(p, n), self.colour).finite_or_zero()
    }
    /// The light's Phong term times the colour. Cost: theirs plus 3 multiplications.
    #[inline]
    fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
        mul_rgb(self.light.phong(lobe, p, r), self.colour).finite_or_zero()
    }
}

/// Constant ambient light: `diffuse` is the colour whatever the normal, no specular term.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ambient<T>(pub Rgb<T>);

impl<T: Real> Illuminant<T> for Ambient<T> {
    /// The colour (non-finite channels as 0). Cost: none.
    #[inline]
    fn diffuse(&self, _p: Vec3<T>, _n: UnitVec3<T>) -> Rgb<T> {
        self.0.finite_or_zero()
    }
    /// 0.
    #[inline]
    fn phong(&self, _lobe: &PhongLobe<T>, _p: Vec3<T>, _r: UnitVec3<T>) -> Rgb<T> {
        black()
    }
}

/// A directional (infinitely distant point) light, not an area light: the model the area
/// lights generalize (Snyder's figure 7 (a)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionalLight<T> {
    to_light: Vec3<T>,
}

impl<T: Real> DirectionalLight<T> {
    /// A light in the direction `to_light` (from the surface toward the light, any length).
    ///
    /// # Errors
    /// [`crate::Error::NotFinite`] / [`crate::Error::ZeroLength`] (`"to_light"`).
    pub fn new(to_light: Vec3<T>) -> Result<Self, crate::Error> {
        Ok(DirectionalLight {
            to_light: to_light.try_normalize("to_light")?,
        })
    }
    /// The unit direction toward the light.
    pub fn direction(&self) -> Vec3<T> {
        self.to_light
    }
}

impl<T: Real> Illuminant<T> for DirectionalLight<T> {
    /// `max(0, n.l)`: exact; cost 1 dot product.
    #[inline]
    fn diffuse(&self, _p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        grey(n.dot(self.to_light).clamp01())
    }
    /// `max(0, r.l)^m`: a few ULPs times `m`; cost 1 dot product and `log2 m` squarings.
    #[inline]
    fn phong(&self, lobe: &PhongLobe<T>, _p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
        grey(r.dot(self.to_light).clamp01().powu(lobe.exponent()))
    }
}

/// A point light (Snyder's figure 7 (b), "non-area positional"), optionally with the inverse
/// square law.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLight<T> {
    position: Vec3<T>,
    inverse_square: bool,
}

impl<T: Real> PointLight<T> {
    /// A point light at `position` whose intensity does not fall off with distance (the
    /// classic OpenGL light).
    ///
    /// # Errors
    /// [`crate::Error::NotFinite`] (`"position"`).
    pub fn new(position: Vec3<T>) -> Result<Self, crate::Error> {
        if !position.is_finite() {
            return Err(crate::Error::NotFinite("position"));
        }
        Ok(PointLight {
            position,
            inverse_square: false,
        })
    }
    /// A point light at `position` of unit intensity with the inverse square law (`1/d^2`).
    ///
    /// # Errors
    /// [`crate::Error::NotFinite`] (`"position"`).
    pub fn inverse_square(position: Vec3<T>) -> Result<Self, crate::Error> {
        Ok(PointLight {
            inverse_square: true,
            ..Self::new(position)?
        })
    }
    /// The position.
    pub fn position(&self) -> Vec3<T> {
        self.position
    }
}

impl<T: Real> Illuminant<T> for PointLight<T> {
    /// `max(0, n.l)` (divided by `d^2` with the inverse square law), `l` the unit direction to
    /// the light: a few ULPs; cost 1 normalization, 1 dot product (1 division). 0 at the light.
    #[inline]
    fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        let Some((l, d)) = (self.position - p).normalize_with_length() else {
            return black();
        };
        let c = n.dot(l).clamp01();
        grey(if self.inverse_square {
            (c / (d * d)).finite_or_zero()
        } else {
            c
        })
    }
    /// `max(0, r.l)^m` (no distance law: the lobe is normalized as the area models' are).
    /// Cost 1 normalization, 1 dot product, `log2 m` squarings. 0 at the light.
    #[inline]
    fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
        match (self.position - p).normalize() {
            Some(l) => grey(r.dot(l).clamp01().powu(lobe.exponent())),
            None => black(),
        }
    }
}

#[cfg(feature = "hemisphere")]
mod hemisphere_impls;

#[cfg(feature = "cap")]
mod cap_impls;

#[cfg(feature = "polygon")]
mod polygon_impls;

#[cfg(feature = "line")]
mod line_impls;

#[cfg(all(feature = "line", feature = "polygon"))]
mod parallelogram_impls;

#[cfg(feature = "sh9")]
mod sh9_impls;

#[cfg(feature = "shaping")]
pub use shaping_impls::Shaped;

#[cfg(feature = "shaping")]
mod shaping_impls;

#[cfg(feature = "moments")]
pub use moments_impls::DirectionalLuminaire;

#[cfg(feature = "moments")]
mod moments_impls;
