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
mod hemisphere_impls {
    use super::*;
    use crate::{HemisphereLight, OvercastSky, SkyGround};

    impl<T: Real> Illuminant<T> for HemisphereLight<T> {
        /// [`HemisphereLight::lambert_const`] (the constant-weighted hemisphere).
        #[inline]
        fn diffuse(&self, _p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
            grey(self.lambert_const(n))
        }
        /// [`HemisphereLight::phong_const`] (`phong` feature; 0 without it).
        #[inline]
        fn phong(&self, lobe: &PhongLobe<T>, _p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
            #[cfg(feature = "phong")]
            {
                grey(self.phong_const(lobe, r))
            }
            #[cfg(not(feature = "phong"))]
            {
                let _ = (lobe, r);
                black()
            }
        }
    }

    impl<T: Real> Illuminant<T> for OvercastSky<T> {
        /// [`OvercastSky::lambert`].
        #[inline]
        fn diffuse(&self, _p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
            grey(self.lambert(n))
        }
        /// `C/3 phong_hemi_const + 2C/3 phong_hemi_cos` about the zenith: exact for the CIE
        /// overcast radiance, which is that sum of the two hemisphere radiances. Cost: both
        /// hemisphere Phong models (`phong` feature; 0 without it).
        #[inline]
        fn phong(&self, lobe: &PhongLobe<T>, _p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
            #[cfg(feature = "phong")]
            {
                let Ok(h) = HemisphereLight::new(self.zenith()) else {
                    return black();
                };
                let third = T::from_f64(1.0 / 3.0);
                let c = self.zenith_luminance();
                grey(
                    (c * third * (h.phong_const(lobe, r) + T::TWO * h.phong_cos(lobe, r)))
                        .finite_or_zero(),
                )
            }
            #[cfg(not(feature = "phong"))]
            {
                let _ = (lobe, r);
                black()
            }
        }
    }

    impl<T: Real> Illuminant<T> for SkyGround<T> {
        /// [`SkyGround::irradiance`].
        #[inline]
        fn diffuse(&self, _p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
            self.irradiance(n)
        }
        /// `sky phong_hemi_const(up) + ground phong_hemi_const(-up)`: exact for this radiance
        /// (the two hemispheres tile the sphere). Cost: two hemisphere Phong models (`phong`
        /// feature; 0 without it).
        #[inline]
        fn phong(&self, lobe: &PhongLobe<T>, _p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
            #[cfg(feature = "phong")]
            {
                let (Ok(up), Ok(down)) = (
                    HemisphereLight::new(self.up()),
                    HemisphereLight::new(-self.up()),
                ) else {
                    return black();
                };
                self.sky()
                    .scale(up.phong_const(lobe, r))
                    .add(self.ground().scale(down.phong_const(lobe, r)))
                    .finite_or_zero()
            }
            #[cfg(not(feature = "phong"))]
            {
                let _ = (lobe, r);
                black()
            }
        }
    }
}

#[cfg(feature = "cap")]
mod cap_impls {
    use super::*;
    use crate::{CapLight, SphereLight};

    impl<T: Real> Illuminant<T> for CapLight<T> {
        /// [`CapLight::lambert`].
        #[inline]
        fn diffuse(&self, _p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
            grey(self.lambert(n))
        }
        /// [`CapLight::phong`] (`phong` feature; 0 without it).
        #[inline]
        fn phong(&self, lobe: &PhongLobe<T>, _p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
            #[cfg(feature = "phong")]
            {
                grey(CapLight::phong(self, lobe, r))
            }
            #[cfg(not(feature = "phong"))]
            {
                let _ = (lobe, r);
                black()
            }
        }
    }

    impl<T: Real> Illuminant<T> for SphereLight<T> {
        /// [`SphereLight::lambert`] (0 inside the sphere).
        #[inline]
        fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
            grey(self.lambert(p, n))
        }
        /// [`SphereLight::phong`] (`phong` feature; 0 without it).
        #[inline]
        fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
            #[cfg(feature = "phong")]
            {
                grey(SphereLight::phong(self, lobe, p, r))
            }
            #[cfg(not(feature = "phong"))]
            {
                let _ = (lobe, p, r);
                black()
            }
        }
        /// The cap the sphere subtends at `p`, computed once for both terms (the same bits
        /// as the two calls).
        #[cfg(feature = "phong")]
        #[inline]
        fn diffuse_and_phong(
            &self,
            lobe: &PhongLobe<T>,
            p: Vec3<T>,
            n: UnitVec3<T>,
            r: UnitVec3<T>,
        ) -> (Rgb<T>, Rgb<T>) {
            match self.cap_at(p) {
                Ok(cap) => (grey(cap.lambert(n)), grey(cap.phong(lobe, r))),
                Err(_) => (black(), black()),
            }
        }
    }
}

#[cfg(feature = "polygon")]
mod polygon_impls {
    use super::*;
    use crate::PolygonLight;

    impl<T: Real, const N: usize> Illuminant<T> for PolygonLight<T, N> {
        /// [`PolygonLight::lambert`].
        #[inline]
        fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
            grey(self.lambert(p, n))
        }
        /// [`PolygonLight::phong`] (`phong` feature; 0 without it).
        #[inline]
        fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
            #[cfg(feature = "phong")]
            {
                grey(PolygonLight::phong(self, lobe, p, r))
            }
            #[cfg(not(feature = "phong"))]
            {
                let _ = (lobe, p, r);
                black()
            }
        }
        /// Both terms with `p`'s checks and its test against the polygon's plane done once
        /// (the same bits as the two calls).
        #[cfg(feature = "phong")]
        #[inline]
        fn diffuse_and_phong(
            &self,
            lobe: &PhongLobe<T>,
            p: Vec3<T>,
            n: UnitVec3<T>,
            r: UnitVec3<T>,
        ) -> (Rgb<T>, Rgb<T>) {
            if p.check_position("p").is_err() {
                return (black(), black());
            }
            let plane = self.in_plane(p);
            (
                grey(self.lambert_at(p, n, plane).unwrap_or(T::ZERO)),
                grey(self.phong_at(lobe, p, r, plane).unwrap_or(T::ZERO)),
            )
        }
    }
}

#[cfg(feature = "line")]
mod line_impls {
    use super::*;
    use crate::{Decay, LineLight};

    impl<T: Real> Illuminant<T> for LineLight<T> {
        /// [`LineLight::lambert`] with [`Decay::InverseSquare`] (the physical law; Picott's
        /// `I_p k_d = 1` per unit of the segment's parameter, so a short segment approaches a
        /// point light of unit intensity with the inverse square law).
        #[inline]
        fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
            grey(self.lambert(p, n, Decay::InverseSquare))
        }
        /// [`LineLight::phong_peak`]: Picott's peak of the lobe, not its integral.
        #[inline]
        fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
            grey(self.phong_peak(lobe, p, r))
        }
    }
}

#[cfg(all(feature = "line", feature = "polygon"))]
mod parallelogram_impls {
    use super::*;
    use crate::polygon::for_each_clipped_edge;
    use crate::ParallelogramLight;

    impl<T: Real> Illuminant<T> for ParallelogramLight<T> {
        /// `[polygon_lambert]` of the four corners (the parallelogram is validated at
        /// construction, so no polygon is built per sample): accuracy and cost those of
        /// [`crate::PolygonLight::lambert`] for a quad. 0 in the light's plane, and for a
        /// non-finite `p` or one beyond [`Real::COORDINATE_LIMIT`] (fixed point), as
        /// [`crate::PolygonLight::lambert`] answers.
        #[inline]
        fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
            let n = n.into_inner();
            // (The edge terms' products rely on it: `polygon::edge::offset_products`.)
            if p.check_position("p").is_err() {
                return black();
            }
            let verts = self.vertices();
            let d = p - verts[0];
            if !(self.normal().dot(d).abs() > T::from_f64(4.0) * T::EPSILON * d.max_abs()) {
                return black();
            }
            let mut sum = T::ZERO;
            for_each_clipped_edge(
                &verts,
                p,
                n,
                T::ZERO,
                #[inline(always)]
                |e| sum += e.lambert_term(n),
            );
            grey((sum.abs() * T::FRAC_1_TAU).clamp01())
        }
        /// [`ParallelogramLight::phong_peak`]: Picott's peak of the lobe, not its integral.
        #[inline]
        fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
            grey(self.phong_peak(lobe, p, r))
        }
    }
}

#[cfg(feature = "sh9")]
mod sh9_impls {
    use super::*;
    use crate::Sh9Irradiance;

    impl<T: Real> Illuminant<T> for Sh9Irradiance<T> {
        /// [`Sh9Irradiance::irradiance`] divided by pi (so a unit-radiance environment gives 1,
        /// as the normalized models do). May be slightly negative where a measured
        /// environment's projection rings (not clamped, as the model). Cost: 30 multiply-adds.
        #[inline]
        fn diffuse(&self, _p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
            self.irradiance(n).scale(T::FRAC_1_PI)
        }
        /// 0: the crate has no specular model for SH environments.
        #[inline]
        fn phong(&self, _lobe: &PhongLobe<T>, _p: Vec3<T>, _r: UnitVec3<T>) -> Rgb<T> {
            black()
        }
    }
}

#[cfg(feature = "shaping")]
pub use shaping_impls::Shaped;

#[cfg(feature = "shaping")]
mod shaping_impls {
    use super::*;
    use crate::Uberlight;

    /// A light shaped by an [`Uberlight`] factor (June 20.5): both terms of `light` times
    /// [`Uberlight::factor`] at the shading point.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub struct Shaped<T, L> {
        /// The light.
        pub light: L,
        /// The shaping factor (frame, superellipse, distance falloff).
        pub shape: Uberlight<T>,
    }

    impl<T: Real, L: Illuminant<T>> Illuminant<T> for Shaped<T, L> {
        /// The light's diffuse term times the factor (skipped where the factor is 0). Cost:
        /// [`Uberlight::factor`] plus the light's.
        #[inline]
        fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
            let f = self.shape.factor(p);
            if !(f > T::ZERO) {
                return black();
            }
            self.light.diffuse(p, n).scale(f).finite_or_zero()
        }
        /// The light's Phong term times the factor (skipped where the factor is 0).
        #[inline]
        fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
            let f = self.shape.factor(p);
            if !(f > T::ZERO) {
                return black();
            }
            self.light.phong(lobe, p, r).scale(f).finite_or_zero()
        }
    }
}

#[cfg(feature = "moments")]
pub use moments_impls::DirectionalLuminaire;

#[cfg(feature = "moments")]
mod moments_impls {
    use super::*;
    use crate::{Error, PolygonLight};

    /// Arvo's directional luminaire (6.1): a polygon emitting `((-u).axis)+^m` toward `-u`, as
    /// a light. Its diffuse term is [`PolygonLight::directional_luminaire`] divided by pi (so
    /// `m = 0` is the polygon's normalized Lambert irradiance).
    #[derive(Clone, Debug, PartialEq)]
    pub struct DirectionalLuminaire<T, const N: usize = 8> {
        polygon: PolygonLight<T, N>,
        axis: Vec3<T>,
        m: u32,
    }

    impl<T: Real, const N: usize> DirectionalLuminaire<T, N> {
        /// The luminaire `polygon` emitting mostly along `axis` (any length) with order `m`.
        ///
        /// # Errors
        /// [`Error::NotFinite`] / [`Error::ZeroLength`] (`"axis"`),
        /// [`Error::ExponentOutOfRange`] for `m > MAX_EXPONENT`.
        pub fn new(polygon: PolygonLight<T, N>, axis: Vec3<T>, m: u32) -> Result<Self, Error> {
            if m > crate::lobe::MAX_EXPONENT {
                return Err(Error::ExponentOutOfRange);
            }
            Ok(DirectionalLuminaire {
                polygon,
                axis: axis.try_normalize("axis")?,
                m,
            })
        }
    }

    impl<T: Real, const N: usize> Illuminant<T> for DirectionalLuminaire<T, N> {
        /// [`PolygonLight::directional_luminaire`] / pi, in [0, 1]: accuracy and cost its.
        #[inline]
        fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
            grey(
                (self.polygon.directional_luminaire(p, n, self.axis, self.m) * T::FRAC_1_PI)
                    .clamp01(),
            )
        }
        /// 0: the luminaire's glossy reflection is a property of the surface, see
        /// [`PolygonLight::glossy_reflection`].
        #[inline]
        fn phong(&self, _lobe: &PhongLobe<T>, _p: Vec3<T>, _r: UnitVec3<T>) -> Rgb<T> {
            black()
        }
    }
}
