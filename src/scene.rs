//! Scenes that pay only for what they use: a fixed-capacity set of lights, prepared once per
//! object so that the lights that cannot reach it cost nothing per sample.
//!
//! A [`Scene`] holds up to `L` lights (a `heapless` vector: no allocation; [`Scene::push`]
//! hands the light back when full), each with a colour and, with the `shaping` feature, an
//! optional [`Uberlight`] beam. Everything per-light constant is computed
//! when the light is built (the models' constructors) or pushed (the light's reach, below).
//!
//! [`Scene::prepare`] takes an object's [`ObjectBounds`] (its bounding sphere and, optionally,
//! the cone its normals lie in) and keeps only the lights that can reach some point and normal
//! of it. The tests are conservative (a light is dropped only when its contribution is exactly
//! 0 for every sample of the object, with a margin for rounding), so a prepared scene renders
//! bit-identical images (`tests/scene.rs`):
//!
//! - **beyond a beam**: a shaped light whose beam cannot contain the object: the object's
//!   depth range along the beam lies wholly before the cut-on zone (`z < znear - near_edge`)
//!   or after the cut-off zone (`z > zfar + far_edge`), or its bounding sphere lies outside the
//!   cone circumscribing the superellipse's outer rectangle (`|x| < A z`, `|y| < B z`). Both
//!   terms are scaled by the beam, so this holds with or without specular.
//! - **below every horizon** (matte objects only, `specular = false`): every point of the
//!   light lies strictly below the tangent plane of every point and normal of the object. With
//!   the normal cone of axis `a` and half-angle `t`, and the light bounded by a sphere `(c, R)`
//!   (or a direction `d` of angular radius `s`, for the lights at infinity), a light can reach
//!   iff `|c - o| cos(max(0, phi - t)) + R + R_o > 0` (`phi` the angle between `c - o` and `a`),
//!   or `cos(max(0, phi - t)) > -sin s`. The Phong term is not culled so: Snyder's Phong
//!   integral has no horizon (a lobe about `r` reaches below the tangent plane), so an object
//!   with a specular material keeps these lights.
//!
//! Per sample, each light exits early where its value is known to be 0 before any arc tangent
//! or recurrence: a beam factor of 0 skips both terms; a cap wholly below the horizon
//! (`n.axis < -sin sigma`) skips the Lambert term, and a Phong lobe that cannot reach it
//! (`r.axis < -sin sigma`) the Phong term; a polygon wholly below the horizon is rejected by
//! the clipper's first pass over the vertices (and one wholly above runs no clipping
//! arithmetic: only the per-vertex sign tests); a directional or point light behind the
//! tangent plane returns 0 after one dot product. A material without specular colour skips
//! every Phong term (`raster::shade`).
//!
//! Cost of [`Scene::prepare`]: a few dozen f64 operations per light (no per-sample cost).

use crate::illuminant::{mul_rgb, Ambient, DirectionalLight, Illuminant, PointLight};

mod reach;
use crate::{PhongLobe, Real, Rgb, UnitVec3, Vec3};
use heapless::Vec as HVec;
#[cfg(feature = "shaping")]
use reach::beam_of;
pub use reach::ObjectBounds;
use reach::{beam_reaches, horizon_reaches, reach_of, Beam, Reach};

#[cfg(feature = "polygon")]
use crate::PolygonLight;
#[cfg(feature = "sh9")]
use crate::Sh9Irradiance;
#[cfg(feature = "shaping")]
use crate::Uberlight;
#[cfg(feature = "cap")]
use crate::{CapLight, SphereLight};
#[cfg(feature = "hemisphere")]
use crate::{HemisphereLight, OvercastSky, SkyGround};

/// One light of a [`Scene`]: the crate's lights whose families are enabled.
#[derive(Clone, Debug, PartialEq)]
#[allow(clippy::large_enum_variant)]
pub enum SceneLight<T, const N: usize = 8> {
    /// Constant ambient light.
    Ambient(Ambient<T>),
    /// A light at infinity in one direction.
    Directional(DirectionalLight<T>),
    /// A point light.
    Point(PointLight<T>),
    /// A constant hemisphere (`hemi_const`).
    #[cfg(feature = "hemisphere")]
    Hemisphere(HemisphereLight<T>),
    /// The CIE overcast sky.
    #[cfg(feature = "hemisphere")]
    Overcast(OvercastSky<T>),
    /// Sky/ground lighting.
    #[cfg(feature = "hemisphere")]
    SkyGround(SkyGround<T>),
    /// A cap of directions (a distant disc).
    #[cfg(feature = "cap")]
    Cap(CapLight<T>),
    /// A sphere light.
    #[cfg(feature = "cap")]
    Sphere(SphereLight<T>),
    /// A polygon light.
    #[cfg(feature = "polygon")]
    Polygon(PolygonLight<T, N>),
    /// An SH9 environment.
    #[cfg(feature = "sh9")]
    Sh9(Sh9Irradiance<T>),
}

#[derive(Clone, Debug, PartialEq)]
struct Entry<T, const N: usize> {
    light: SceneLight<T, N>,
    colour: Rgb<T>,
    #[cfg(feature = "shaping")]
    shape: Option<Uberlight<T>>,
    reach: Reach,
    beam: Option<Beam>,
}

/// Why [`Scene::push`] refused a light; the light comes back in either case.
#[derive(Clone, Debug, PartialEq)]
pub enum PushError<T, const N: usize = 8> {
    /// The scene already holds its capacity `L` of lights.
    Full(SceneLight<T, N>),
    /// The colour has a NaN or infinite channel.
    NotFinite(SceneLight<T, N>),
}

/// A set of up to `L` lights (polygons of up to `N` vertices): see the module docs.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene<T, const L: usize, const N: usize = 8> {
    entries: HVec<Entry<T, N>, L>,
}

impl<T: Real, const L: usize, const N: usize> Default for Scene<T, L, N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Real, const L: usize, const N: usize> Scene<T, L, N> {
    /// An empty scene.
    pub const fn new() -> Self {
        Scene {
            entries: HVec::new(),
        }
    }

    /// The number of lights.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// `true` for a scene without lights.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Adds `light` with `colour` (per-channel radiance scale); returns its index.
    ///
    /// # Errors
    /// [`PushError::Full`] when the scene holds `L` lights, [`PushError::NotFinite`] for a
    /// colour with a NaN or infinite channel; both hand the light back.
    pub fn push(
        &mut self,
        light: SceneLight<T, N>,
        colour: Rgb<T>,
    ) -> Result<usize, PushError<T, N>> {
        self.push_entry(light, colour, None)
    }

    /// Adds `light` shaped by the uberlight `shape` (both its terms are multiplied by
    /// [`Uberlight::factor`]); returns its index.
    ///
    /// # Errors
    /// As [`Scene::push`].
    #[cfg(feature = "shaping")]
    pub fn push_shaped(
        &mut self,
        light: SceneLight<T, N>,
        colour: Rgb<T>,
        shape: Uberlight<T>,
    ) -> Result<usize, PushError<T, N>> {
        self.push_entry(light, colour, Some(shape))
    }

    #[cfg(feature = "shaping")]
    fn push_entry(
        &mut self,
        light: SceneLight<T, N>,
        colour: Rgb<T>,
        shape: Option<Uberlight<T>>,
    ) -> Result<usize, PushError<T, N>> {
        let beam = shape.as_ref().map(beam_of);
        self.insert(light, colour, beam, shape)
    }

    #[cfg(not(feature = "shaping"))]
    fn push_entry(
        &mut self,
        light: SceneLight<T, N>,
        colour: Rgb<T>,
        _shape: Option<()>,
    ) -> Result<usize, PushError<T, N>> {
        self.insert(light, colour, None, ())
    }

    fn insert(
        &mut self,
        light: SceneLight<T, N>,
        colour: Rgb<T>,
        beam: Option<Beam>,
        #[cfg(feature = "shaping")] shape: Option<Uberlight<T>>,
        #[cfg(not(feature = "shaping"))] _shape: (),
    ) -> Result<usize, PushError<T, N>> {
        if !(colour.r.is_finite() && colour.g.is_finite() && colour.b.is_finite()) {
            return Err(PushError::NotFinite(light));
        }
        if self.entries.is_full() {
            return Err(PushError::Full(light));
        }
        let reach = reach_of(&light);
        let entry = Entry {
            light,
            colour,
            #[cfg(feature = "shaping")]
            shape,
            reach,
            beam,
        };
        match self.entries.push(entry) {
            Ok(()) => Ok(self.entries.len() - 1),
            Err(e) => Err(PushError::Full(e.light)),
        }
    }

    /// The lights that can reach `object` (see the module docs for the tests): a view of the
    /// scene that shades exactly as the whole scene does for every point and normal of the
    /// object, at the cost of the kept lights only. `specular`: whether the object's material
    /// has a Phong term (then lights below its horizons are kept: see the module docs).
    ///
    /// Cost: a few dozen f64 operations per light, once per object.
    pub fn prepare(&self, object: &ObjectBounds, specular: bool) -> PreparedScene<'_, T, L, N> {
        let mut active = HVec::new();
        for (i, e) in self.entries.iter().enumerate() {
            let beam_ok = e.beam.as_ref().is_none_or(|b| beam_reaches(b, object));
            let horizon_ok = specular || horizon_reaches(&e.reach, object);
            if beam_ok && horizon_ok {
                // Cannot fail: at most L entries.
                let _ = active.push(i as u16);
            }
        }
        PreparedScene {
            scene: self,
            active,
        }
    }
}

/// The lights of a [`Scene`] that can reach one object ([`Scene::prepare`]).
#[derive(Clone, Debug)]
pub struct PreparedScene<'a, T, const L: usize, const N: usize = 8> {
    scene: &'a Scene<T, L, N>,
    active: HVec<u16, L>,
}

impl<T: Real, const L: usize, const N: usize> PreparedScene<'_, T, L, N> {
    /// The number of lights kept.
    pub fn active(&self) -> usize {
        self.active.len()
    }
    /// The indices (push order) of the lights kept.
    pub fn active_indices(&self) -> &[u16] {
        &self.active
    }
}

/// Sums over some of the lights, for the rasterizer's split shaders
/// ([`SplitLit`](crate::raster::SplitLit)). (The same folds as the [`Illuminant`] impl's, which
/// does not call these: routed through them, the RP2040 demo frame took 50 000 more cycles,
/// the compiler inlining the scene's sums differently.)
#[cfg(feature = "raster")]
impl<T: Real, const L: usize, const N: usize> Scene<T, L, N> {
    /// `acc` plus the diffuse terms of the lights `lights` (push order; indices past the end
    /// are none), summed one light at a time as [`Illuminant::diffuse`] sums them all: from
    /// `acc` = 0 over `0..k` then from that sum over `k..len`, the bits of the whole sum.
    #[inline]
    pub(crate) fn diffuse_over(
        &self,
        lights: core::ops::Range<usize>,
        acc: Rgb<T>,
        p: Vec3<T>,
        n: UnitVec3<T>,
    ) -> Rgb<T> {
        let e = self.lights_in(lights);
        e.iter().fold(acc, |acc, e| acc.add(e.diffuse(p, n)))
    }

    /// `acc` plus both terms of the lights `lights`, as [`Scene::diffuse_over`] for
    /// [`Illuminant::diffuse_and_phong`].
    #[inline]
    pub(crate) fn diffuse_and_phong_over(
        &self,
        lights: core::ops::Range<usize>,
        acc: (Rgb<T>, Rgb<T>),
        lobe: &PhongLobe<T>,
        p: Vec3<T>,
        n: UnitVec3<T>,
        r: UnitVec3<T>,
    ) -> (Rgb<T>, Rgb<T>) {
        let e = self.lights_in(lights);
        e.iter().fold(acc, |(d, s), e| {
            let (de, se) = e.diffuse_and_phong(lobe, p, n, r);
            (d.add(de), s.add(se))
        })
    }

    /// The entries of `lights` (push order), clamped to the scene's.
    #[inline(always)]
    fn lights_in(&self, lights: core::ops::Range<usize>) -> &[Entry<T, N>] {
        let end = lights.end.min(self.entries.len());
        self.entries.get(lights.start.min(end)..end).unwrap_or(&[])
    }
}

impl<T: Real, const L: usize, const N: usize> Illuminant<T> for Scene<T, L, N> {
    /// The sum of every light's diffuse term (with the early exits of the module docs).
    #[inline]
    fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        self.entries
            .iter()
            .fold(Rgb::splat(T::ZERO), |acc, e| acc.add(e.diffuse(p, n)))
    }
    /// The sum of every light's Phong term.
    #[inline]
    fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
        self.entries
            .iter()
            .fold(Rgb::splat(T::ZERO), |acc, e| acc.add(e.phong(lobe, p, r)))
    }
    /// Both sums in one pass over the lights (each summed in the same order as the two
    /// calls: the same bits), a sphere's cap computed once.
    #[inline]
    fn diffuse_and_phong(
        &self,
        lobe: &PhongLobe<T>,
        p: Vec3<T>,
        n: UnitVec3<T>,
        r: UnitVec3<T>,
    ) -> (Rgb<T>, Rgb<T>) {
        let zero = Rgb::splat(T::ZERO);
        self.entries.iter().fold((zero, zero), |(d, s), e| {
            let (de, se) = e.diffuse_and_phong_here(lobe, p, n, r);
            (d.add(de), s.add(se))
        })
    }
}

impl<T: Real, const L: usize, const N: usize> Illuminant<T> for PreparedScene<'_, T, L, N> {
    /// The sum of the kept lights' diffuse terms, in push order (so the sum rounds exactly as
    /// the whole scene's, whose other lights contribute exactly 0 here).
    #[inline]
    fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        // (`get`: the kept indices are the scene's by construction; no bounds check to fail.)
        let e = &self.scene.entries;
        self.active.iter().fold(Rgb::splat(T::ZERO), |acc, &i| {
            e.get(usize::from(i))
                .map_or(acc, |l| acc.add(l.diffuse(p, n)))
        })
    }
    /// The sum of the kept lights' Phong terms, in push order.
    #[inline]
    fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
        let e = &self.scene.entries;
        self.active.iter().fold(Rgb::splat(T::ZERO), |acc, &i| {
            e.get(usize::from(i))
                .map_or(acc, |l| acc.add(l.phong(lobe, p, r)))
        })
    }
    /// Both sums in one pass over the kept lights, in push order (the same bits as the two
    /// calls), a sphere's cap computed once.
    #[inline]
    fn diffuse_and_phong(
        &self,
        lobe: &PhongLobe<T>,
        p: Vec3<T>,
        n: UnitVec3<T>,
        r: UnitVec3<T>,
    ) -> (Rgb<T>, Rgb<T>) {
        let e = &self.scene.entries;
        let zero = Rgb::splat(T::ZERO);
        self.active.iter().fold((zero, zero), |(d, s), &i| {
            e.get(usize::from(i)).map_or((d, s), |l| {
                let (de, se) = l.diffuse_and_phong_here(lobe, p, n, r);
                (d.add(de), s.add(se))
            })
        })
    }
}

impl<T: Real, const N: usize> Entry<T, N> {
    /// The beam factor at `p`, or `None` for an unshaped light: its terms are taken as they
    /// are ([`shaped`]), the same bits as multiplied by 1 without the three products (a
    /// saturating call each in fixed point: about 100 Cortex-M0 instructions a term).
    #[inline(always)]
    fn factor(&self, p: Vec3<T>) -> Option<T> {
        #[cfg(feature = "shaping")]
        if let Some(s) = &self.shape {
            return Some(s.factor(p));
        }
        let _ = p;
        None
    }

    #[inline]
    fn diffuse(&self, p: Vec3<T>, n: UnitVec3<T>) -> Rgb<T> {
        let f = self.factor(p);
        if f.is_some_and(|f| !(f > T::ZERO)) {
            return Rgb::splat(T::ZERO);
        }
        let v = match &self.light {
            SceneLight::Ambient(l) => Illuminant::diffuse(l, p, n),
            SceneLight::Directional(l) => Illuminant::diffuse(l, p, n),
            SceneLight::Point(l) => Illuminant::diffuse(l, p, n),
            #[cfg(feature = "hemisphere")]
            SceneLight::Hemisphere(l) => Illuminant::diffuse(l, p, n),
            #[cfg(feature = "hemisphere")]
            SceneLight::Overcast(l) => Illuminant::diffuse(l, p, n),
            #[cfg(feature = "hemisphere")]
            SceneLight::SkyGround(l) => Illuminant::diffuse(l, p, n),
            #[cfg(feature = "cap")]
            SceneLight::Cap(l) => {
                // Wholly below the horizon: n.axis < -sin sigma (n unit).
                let (_, ss) = cap_cos_sin(l);
                if n.dot(l.axis()) < -ss {
                    return Rgb::splat(T::ZERO);
                }
                Illuminant::diffuse(l, p, n)
            }
            #[cfg(feature = "cap")]
            SceneLight::Sphere(l) => Illuminant::diffuse(l, p, n),
            #[cfg(feature = "polygon")]
            SceneLight::Polygon(l) => Illuminant::diffuse(l, p, n),
            #[cfg(feature = "sh9")]
            SceneLight::Sh9(l) => Illuminant::diffuse(l, p, n),
        };
        shaped(mul_rgb(v, self.colour), f)
    }

    #[inline]
    fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: UnitVec3<T>) -> Rgb<T> {
        let f = self.factor(p);
        if f.is_some_and(|f| !(f > T::ZERO)) {
            return Rgb::splat(T::ZERO);
        }
        let v = match &self.light {
            SceneLight::Ambient(l) => Illuminant::phong(l, lobe, p, r),
            SceneLight::Directional(l) => Illuminant::phong(l, lobe, p, r),
            SceneLight::Point(l) => Illuminant::phong(l, lobe, p, r),
            #[cfg(feature = "hemisphere")]
            SceneLight::Hemisphere(l) => Illuminant::phong(l, lobe, p, r),
            #[cfg(feature = "hemisphere")]
            SceneLight::Overcast(l) => Illuminant::phong(l, lobe, p, r),
            #[cfg(feature = "hemisphere")]
            SceneLight::SkyGround(l) => Illuminant::phong(l, lobe, p, r),
            #[cfg(feature = "cap")]
            SceneLight::Cap(l) => {
                // The lobe ((u.r)+)^m vanishes on the whole cap: r.axis <= -sin sigma.
                let (_, ss) = cap_cos_sin(l);
                if !(r.dot(l.axis()) > -ss) {
                    return Rgb::splat(T::ZERO);
                }
                Illuminant::phong(l, lobe, p, r)
            }
            #[cfg(feature = "cap")]
            SceneLight::Sphere(l) => Illuminant::phong(l, lobe, p, r),
            #[cfg(feature = "polygon")]
            SceneLight::Polygon(l) => Illuminant::phong(l, lobe, p, r),
            #[cfg(feature = "sh9")]
            SceneLight::Sh9(l) => Illuminant::phong(l, lobe, p, r),
        };
        shaped(mul_rgb(v, self.colour), f)
    }
}

impl<T: Real, const N: usize> Entry<T, N> {
    /// [`Entry::diffuse_and_phong_inlined`] where the scene's own sum
    /// ([`Illuminant::diffuse_and_phong`], `Lit`'s) calls it: inlined with an FPU, this
    /// function of its own on soft-float targets (Cortex-M0, RV32IMC: every caller shares it,
    /// code size and all; see [`Entry::diffuse_and_phong`]).
    #[inline(always)]
    fn diffuse_and_phong_here(
        &self,
        lobe: &PhongLobe<T>,
        p: Vec3<T>,
        n: UnitVec3<T>,
        r: UnitVec3<T>,
    ) -> (Rgb<T>, Rgb<T>) {
        if crate::real::SOFT_FLOAT {
            self.diffuse_and_phong(lobe, p, n, r)
        } else {
            self.diffuse_and_phong_inlined(lobe, p, n, r)
        }
    }

    /// [`Entry::diffuse_and_phong_inlined`] as a function of its own: the split shaders' sums
    /// ([`Scene::diffuse_and_phong_over`]) call this one, and on soft-float targets the scene's
    /// own sum too; with an FPU the scene's own sum keeps the inlined body, the lights' own
    /// `diffuse_and_phong` inlined into both. Measured with the split shaders in (rp2040js two
    /// cores, frames 1 to 15, and the firmware's `.text`; `boards/qemu-frame` per pixel, frame
    /// 0): this function called from everywhere, 4 982 153 cycles, 206 672 bytes and 33 764 632
    /// instructions; inlined everywhere, 5 009 582 cycles and 33 412 883 instructions; the
    /// scene's own sum inlined and the lights' always, 4 985 375 cycles, 224 072 bytes and
    /// 33 137 477 instructions (33 225 763 before the split shaders): hence the one on
    /// soft-float targets (the RV32IMC scene cost too: 999 106 instructions the other way,
    /// against 995 536), the other with an FPU.
    #[inline(never)]
    fn diffuse_and_phong(
        &self,
        lobe: &PhongLobe<T>,
        p: Vec3<T>,
        n: UnitVec3<T>,
        r: UnitVec3<T>,
    ) -> (Rgb<T>, Rgb<T>) {
        self.diffuse_and_phong_inlined(lobe, p, n, r)
    }

    /// `(diffuse(p, n), phong(lobe, p, r))`, bit for bit: for a sphere, the beam factor and
    /// the cap once ([`Illuminant::diffuse_and_phong`]); the two calls for the other lights.
    #[inline(always)]
    fn diffuse_and_phong_inlined(
        &self,
        lobe: &PhongLobe<T>,
        p: Vec3<T>,
        n: UnitVec3<T>,
        r: UnitVec3<T>,
    ) -> (Rgb<T>, Rgb<T>) {
        match &self.light {
            #[cfg(feature = "cap")]
            SceneLight::Sphere(l) => self.both_terms(l, lobe, p, n, r),
            #[cfg(all(feature = "polygon", feature = "phong"))]
            SceneLight::Polygon(l) => self.both_terms(l, lobe, p, n, r),
            _ => (self.diffuse(p, n), self.phong(lobe, p, r)),
        }
    }

    /// [`Entry::diffuse_and_phong`] for a light whose own [`Illuminant::diffuse_and_phong`]
    /// shares work between its terms (a sphere's cap, a polygon's plane test): the beam factor
    /// once, then the light's two terms in one call, each times the colour.
    #[cfg(any(feature = "cap", all(feature = "polygon", feature = "phong")))]
    #[inline(always)]
    fn both_terms<L: Illuminant<T>>(
        &self,
        l: &L,
        lobe: &PhongLobe<T>,
        p: Vec3<T>,
        n: UnitVec3<T>,
        r: UnitVec3<T>,
    ) -> (Rgb<T>, Rgb<T>) {
        let f = self.factor(p);
        if f.is_some_and(|f| !(f > T::ZERO)) {
            return (Rgb::splat(T::ZERO), Rgb::splat(T::ZERO));
        }
        let (d, s) = Illuminant::diffuse_and_phong(l, lobe, p, n, r);
        (
            shaped(mul_rgb(d, self.colour), f),
            shaped(mul_rgb(s, self.colour), f),
        )
    }
}

/// `c` times the beam factor `f`, or `c` itself for an unshaped light (`None`).
#[inline(always)]
fn shaped<T: Real>(c: Rgb<T>, f: Option<T>) -> Rgb<T> {
    match f {
        Some(f) => c.scale(f),
        None => c,
    }
}

#[cfg(feature = "cap")]
#[inline(always)]
fn cap_cos_sin<T: Real>(l: &CapLight<T>) -> (T, T) {
    l.cos_sin_sigma()
}
