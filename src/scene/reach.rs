//! Which light can reach which object ([`Scene::prepare`](super::Scene::prepare)'s tests,
//! derived in the [module docs](super)): each light's reach and beam, computed once when it is
//! pushed and stored in f32, and an object's [`ObjectBounds`], tested in f64 with a margin.

use super::SceneLight;
#[cfg(feature = "shaping")]
use crate::Uberlight;
use crate::{Real, Vec3};

/// What a light can reach, computed once when it is pushed. Stored in f32 (a scene of 16
/// lights must fit a Cortex-M0's RAM; every test has a margin far above f32's rounding) and
/// evaluated in f64.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Reach {
    /// Every normal (hemispheres, skies, ambient, SH).
    Everywhere,
    /// A light at infinity: directions within the angle `asin(sin_s)` of `dir`.
    Direction { dir: [f32; 3], sin_s: f32 },
    /// A light inside the sphere `(center, radius)`.
    Bounded { center: [f32; 3], radius: f32 },
}

/// A shaped light's beam (f32, as [`Reach`]): where its factor can be non-zero.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Beam {
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

/// Where an object is, for [`Scene::prepare`](super::Scene::prepare): a bounding sphere of its points and, optionally,
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

pub(super) fn reach_of<T: Real, const N: usize>(light: &SceneLight<T, N>) -> Reach {
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
pub(super) fn beam_of<T: Real>(u: &Uberlight<T>) -> Beam {
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

/// Relative margin of every culling test: above the rounding of the per-sample arithmetic
/// in any backend (f32: 6e-8; Fixed22: 2^-22 of a coordinate <= 4, and the Lambert-type
/// terms' cosine through Q15, the sealed `cos_unit`, within 5.3e-5).
const MARGIN: f64 = 1e-4;

pub(super) fn beam_reaches(b: &Beam, o: &ObjectBounds) -> bool {
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

pub(super) fn horizon_reaches(r: &Reach, o: &ObjectBounds) -> bool {
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
