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
use crate::{PhongLobe, Real, Rgb, UnitVec3, Vec3};
use heapless::Vec as HVec;

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

/// What a light can reach, computed once when it is pushed. Stored in f32 (a scene of 16
/// lights must fit a Cortex-M0's RAM; every test has a margin far above f32's rounding) and
/// evaluated in f64.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Reach {
    /// Every normal (hemispheres, skies, ambient, SH).
    Everywhere,
    /// A light at infinity: directions within the angle `asin(sin_s)` of `dir`.
    Direction { dir: [f32; 3], sin_s: f32 },
    /// A light inside the sphere `(center, radius)`.
    Bounded { center: [f32; 3], radius: f32 },
}

/// A shaped light's beam (f32, as [`Reach`]): where its factor can be non-zero.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Beam {
    origin: [f32; 3],
    dir: [f32; 3],
    /// Half-angle of the cone circumscribing the outer rectangle `|x| < A z, |y| < B z`.
    half_angle: f32,
    /// The factor is 0 for `z` below this (`znear - near_edge`) ...
    z_on: f32,
    /// ... and above this (`zfar + far_edge`).
    z_off: f32,
}

/// To f32, rounding away from the reachable set's inside: `up` rounds up (radii, cut-off
/// distances, angles), otherwise down. (Used by the bounds of caps, spheres, polygons and
/// shaped lights: unused, and not compiled, without those families.)
#[cfg(any(feature = "cap", feature = "polygon", feature = "shaping"))]
fn f32_of(x: f64, up: bool) -> f32 {
    let y = x as f32;
    let y64 = f64::from(y);
    if up && y64 < x {
        libm::nextafterf(y, f32::INFINITY)
    } else if !up && y64 > x {
        libm::nextafterf(y, f32::NEG_INFINITY)
    } else {
        y
    }
}

fn v32(v: [f64; 3]) -> [f32; 3] {
    v.map(|x| x as f32)
}

fn v64(v: [f32; 3]) -> [f64; 3] {
    v.map(f64::from)
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

/// Where an object is, for [`Scene::prepare`]: a bounding sphere of its points and, optionally,
/// a cone containing all its (unit) normals.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObjectBounds {
    center: [f64; 3],
    radius: f64,
    /// Unit axis and half-angle of the normal cone (`None`: any normal).
    normals: Option<([f64; 3], f64)>,
}

impl ObjectBounds {
    /// An object inside the sphere `(center, radius)`, normals unconstrained.
    ///
    /// # Errors
    /// [`crate::Error::NotFinite`] (`"center"`, `"radius"`), [`crate::Error::Negative`]
    /// (`"radius"`).
    pub fn sphere<T: Real>(center: Vec3<T>, radius: T) -> Result<Self, crate::Error> {
        let c = center.to_f64();
        let r = radius.to_f64();
        if !c.iter().all(|x| x.is_finite()) {
            return Err(crate::Error::NotFinite("center"));
        }
        if !r.is_finite() {
            return Err(crate::Error::NotFinite("radius"));
        }
        if !(r >= 0.0) {
            return Err(crate::Error::Negative("radius"));
        }
        Ok(ObjectBounds {
            center: c,
            radius: r,
            normals: None,
        })
    }

    /// Restricts the normals to the cone of `axis` (any length) and `half_angle` in [0, pi]
    /// (a plane facing up: `(up, 0)`; a convex object: no cone).
    ///
    /// # Errors
    /// [`crate::Error::NotFinite`] / [`crate::Error::ZeroLength`] (`"axis"`),
    /// [`crate::Error::AlphaOutOfRange`] for a half-angle outside [0, pi].
    pub fn with_normal_cone<T: Real>(
        mut self,
        axis: Vec3<T>,
        half_angle: T,
    ) -> Result<Self, crate::Error> {
        let a = unit(axis.to_f64()).ok_or(if axis.is_finite() {
            crate::Error::ZeroLength("axis")
        } else {
            crate::Error::NotFinite("axis")
        })?;
        let t = half_angle.to_f64();
        if !(0.0..=core::f64::consts::PI).contains(&t) {
            return Err(crate::Error::AlphaOutOfRange);
        }
        self.normals = Some((a, t));
        Ok(self)
    }
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
            let (de, se) = e.diffuse_and_phong(lobe, p, n, r);
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
                let (de, se) = l.diffuse_and_phong(lobe, p, n, r);
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
    /// `(diffuse(p, n), phong(lobe, p, r))`, bit for bit: for a sphere, the beam factor and
    /// the cap once ([`Illuminant::diffuse_and_phong`]); the two calls for the other lights.
    #[inline]
    fn diffuse_and_phong(
        &self,
        lobe: &PhongLobe<T>,
        p: Vec3<T>,
        n: UnitVec3<T>,
        r: UnitVec3<T>,
    ) -> (Rgb<T>, Rgb<T>) {
        #[cfg(feature = "cap")]
        if let SceneLight::Sphere(l) = &self.light {
            let f = self.factor(p);
            if f.is_some_and(|f| !(f > T::ZERO)) {
                return (Rgb::splat(T::ZERO), Rgb::splat(T::ZERO));
            }
            let (d, s) = Illuminant::diffuse_and_phong(l, lobe, p, n, r);
            return (
                shaped(mul_rgb(d, self.colour), f),
                shaped(mul_rgb(s, self.colour), f),
            );
        }
        (self.diffuse(p, n), self.phong(lobe, p, r))
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

/// The culling geometry is f64 [`Vec3`] arithmetic (the crate's one vector type; the
/// polygon's validation uses it too).
type V64 = Vec3<f64>;

/// `v` as a [`V64`].
fn w(v: [f64; 3]) -> V64 {
    Vec3::from_f64(v)
}

/// `v/|v|`, or `None` for a zero or non-finite length.
fn unit(v: [f64; 3]) -> Option<[f64; 3]> {
    let l = w(v).length();
    if l > 0.0 && l.is_finite() {
        Some(v.map(|x| x / l))
    } else {
        None
    }
}

/// The angle between two vectors (any lengths), accurate at both ends.
fn angle(a: V64, b: V64) -> f64 {
    libm::atan2(a.cross(b).length(), a.dot(b))
}

fn reach_of<T: Real, const N: usize>(light: &SceneLight<T, N>) -> Reach {
    match light {
        SceneLight::Ambient(_) => Reach::Everywhere,
        SceneLight::Directional(l) => Reach::Direction {
            dir: v32(l.direction().to_f64()),
            sin_s: 0.0,
        },
        SceneLight::Point(l) => Reach::Bounded {
            center: v32(l.position().to_f64()),
            radius: 0.0,
        },
        #[cfg(feature = "hemisphere")]
        SceneLight::Hemisphere(_) | SceneLight::Overcast(_) | SceneLight::SkyGround(_) => {
            Reach::Everywhere
        }
        #[cfg(feature = "cap")]
        SceneLight::Cap(l) => Reach::Direction {
            dir: v32(l.axis().to_f64()),
            sin_s: f32_of(libm::sin(l.sigma().to_f64()), true),
        },
        #[cfg(feature = "cap")]
        SceneLight::Sphere(l) => Reach::Bounded {
            center: v32(l.center().to_f64()),
            radius: f32_of(l.radius().to_f64(), true),
        },
        #[cfg(feature = "polygon")]
        SceneLight::Polygon(l) => {
            let vs = l.vertices();
            let mut c = [0.0; 3];
            for v in vs {
                let v = v.to_f64();
                for k in 0..3 {
                    c[k] += v[k] / vs.len() as f64;
                }
            }
            let r = vs
                .iter()
                .fold(0.0f64, |m, v| m.max((w(v.to_f64()) - w(c)).length()));
            let c32 = v32(c);
            // The sphere about the rounded centre still contains every vertex.
            let r = r + (w(v64(c32)) - w(c)).length();
            Reach::Bounded {
                center: c32,
                radius: f32_of(r, true),
            }
        }
        #[cfg(feature = "sh9")]
        SceneLight::Sh9(_) => Reach::Everywhere,
    }
}

#[cfg(feature = "shaping")]
fn beam_of<T: Real>(u: &Uberlight<T>) -> Beam {
    let [_, _, big_a, big_b, _] = u.shape.params().map(|x| x.to_f64());
    let [_, _, _, znear, zfar, near_edge, far_edge] = u.falloff.params().map(|x| x.to_f64());
    Beam {
        origin: v32(u.frame.origin().to_f64()),
        dir: v32(unit(u.frame.direction().to_f64()).unwrap_or([0.0, 0.0, 1.0])),
        half_angle: f32_of(libm::atan(libm::hypot(big_a, big_b)), true),
        z_on: f32_of(znear - near_edge, false),
        z_off: f32_of(zfar + far_edge, true),
    }
}

/// Relative margin of every culling test: far above the rounding of the per-sample
/// arithmetic in any backend (f32: 6e-8; Fixed22: 2^-22 of a coordinate <= 4).
const MARGIN: f64 = 1e-4;

fn beam_reaches(b: &Beam, o: &ObjectBounds) -> bool {
    let (origin, dir) = (v64(b.origin), v64(b.dir));
    let (z_on, z_off, half_angle) = (
        f64::from(b.z_on),
        f64::from(b.z_off),
        f64::from(b.half_angle),
    );
    let d = w(o.center) - w(origin);
    let dist = d.length();
    let slack = MARGIN * (dist + o.radius) + MARGIN;
    // The stored direction is unit to f32 rounding (6e-8): far inside the margin.
    let z = d.dot(w(dir));
    if z + o.radius < z_on - slack || z - o.radius > z_off + slack {
        return false;
    }
    if dist <= o.radius + slack {
        return true;
    }
    // Outside the cone: the angle to the object's centre minus its angular radius.
    let phi = angle(d, w(dir));
    let spread = libm::asin((o.radius / dist).min(1.0));
    phi - spread <= half_angle + MARGIN
}

fn horizon_reaches(r: &Reach, o: &ObjectBounds) -> bool {
    let Some((axis, half)) = o.normals else {
        return true;
    };
    match *r {
        Reach::Everywhere => true,
        Reach::Direction { dir, sin_s } => {
            let phi = angle(w(v64(dir)), w(axis));
            libm::cos((phi - half).max(0.0)) > -f64::from(sin_s) - MARGIN
        }
        Reach::Bounded { center, radius } => {
            let (center, radius) = (v64(center), f64::from(radius));
            let d = w(center) - w(o.center);
            let dist = d.length();
            let slack = MARGIN * (dist + radius + o.radius);
            if dist <= radius + o.radius + slack {
                return true;
            }
            let phi = angle(d, w(axis));
            dist * libm::cos((phi - half).max(0.0)) + radius + o.radius > -slack
        }
    }
}
