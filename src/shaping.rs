//! Barzel's uberlight shaping (June 20.5): a superellipse beam cross-section and a distance
//! falloff with cut-on and cut-off zones. They are factors, not lights: multiply the value of
//! any light of the crate at a point by them (see [`Uberlight`]).
//!
//! ## The superellipse shape (`[superellipse_shape]`)
//!
//! In light space (beam along +z) a point `(x, y, z)` with `z > 0` projects to the plane
//! `z = 1` at `(X, Y) = (|x/z|, |y/z|)`. The superellipse of half-widths `a`, `b` and roundness
//! `d` is `(X/a)^(2/d) + (Y/b)^(2/d) = 1` (June eq. 20.34: an ellipse for `d = 1`, a rectangle
//! as `d -> 0`, a diamond for `d = 2`, concave for `d > 2`). Its gauge
//!
//! ```text
//! rho_ab(X, Y) = ((X/a)^(2/d) + (Y/b)^(2/d))^(d/2)
//! ```
//!
//! is homogeneous of degree 1, so the ray `s (X, Y)` meets the curve at `s = q = 1/rho_ab`.
//! That is June's eq. 20.41, `q = a b ((b X)^(2/d) + (a Y)^(2/d))^(-d/2)`, with the sum
//! divided by `(a b)^(2/d)`; `r = 1/rho_AB` likewise with the outer sizes (eq. 20.42). The
//! value is `1 - smoothstep(q, r, 1)` with `t = (1 - q)/(r - q)` (eq. 20.37; eq. 20.38 prints
//! the denominator as `c - d`, a typo: GLSL's smoothstep divides by `d - c`, as the spec says).
//!
//! **Computed form.** As `a < A` and `b < B`, `rho_ab > rho_AB` (unless `X = Y = 0`), so
//! `q < r` and
//!
//! - `rho_ab <= 1` (`q >= 1`: on or inside the inner curve, `X = Y = 0` included): 1;
//! - `rho_AB >= 1` (`r <= 1`: on or outside the outer curve): 0;
//! - in between, from `1 - smoothstep(t) = smoothstep(1 - t)` (both are
//!   `1 - 3t^2 + 2t^3`) and `1 - t = (r - 1)/(r - q)`:
//!
//! ```text
//! value = u^2 (3 - 2u),   u = (1 - rho_AB) / (1 - rho_AB/rho_ab)   in (0, 1).
//! ```
//!
//! This form never raises 0 to the negative power `-d/2` (the `q = inf` of the printed
//! formula at `X = Y = 0`), keeps relative accuracy near the outer curve where the value goes
//! to 0, and its denominator is at least `1 - max(a/A, b/B)`: the width of the transition band
//! is the model's own conditioning, nothing is lost to the formula. Each gauge is computed as
//!
//! ```text
//! rho = m (1 + (w/m)^(2/d))^(d/2),   m = max(X/a, Y/b),   w = min(X/a, Y/b)
//! ```
//!
//! so the power's base is in [0, 1] and the sum in [1, 2]: no intermediate overflows or
//! underflows for any finite point and any `d > 0` unless the gauge itself is beyond the
//! format's range. Then it is infinite, which the tests above treat correctly: such a point is
//! outside the outer curve, or (in the band, where `rho_AB < 1`) has `rho_AB/rho_ab` below the
//! format's precision anyway. `X = |x|/z` overflows only when `X` exceeds every finite `A`,
//! likewise outside. For `d = 1` (the ellipse) the gauge is `m sqrt(1 + (w/m)^2)`, and when
//! `A/a = B/b` the outer gauge is `(a/A) rho_ab`: both are used.
//!
//! ## Distance falloff (`[distance_falloff]`)
//!
//! With `z >= 0` the distance along the beam (the light-space `z`, not the distance to the
//! light), the value is
//!
//! ```text
//! smoothstep(znear - near_edge, znear, z) (1 - smoothstep(zfar, zfar + far_edge, z)) D(z)
//! D(z) = (d0/z)^alpha                    for z > d0      (June eq. 20.46, K = 1)
//! D(z) = M exp(s (z/d0)^beta)            for z <= d0,    s = ln(1/M) < 0, beta = -alpha/s >= 0
//! ```
//!
//! June's eq. 20.47 prints `(d0/z)^beta` in the near branch; her listing (and the spec) use
//! `(z/d0)^beta`, the only one of the two for which the branches join smoothly: at `z = d0`
//! both give 1 (`M e^s = 1`) with the same slope `-alpha/d0` (`s beta = -alpha`), and the near
//! branch rises to its peak `M` at `z = 0`. (With `(d0/z)^beta` its slope at `d0` would be
//! `+alpha/d0` and it would fall to 0 at `z = 0`.) For `alpha = 0`, `beta = 0` and
//! `(z/d0)^0 = 1` for every `z`, `z = 0` included (IEEE `pow(0, 0) = 1`, and the limit), so
//! `D = 1` everywhere.
//!
//! **Computed form.** The near branch is `D = exp(-s (1 - w))`, `w = (z/d0)^beta` in [0, 1]:
//! the same number as `M exp(s w)` without the product of `M` and `exp(s w) >= 1/M` (which is
//! subnormal in f32 for `M` above ~1e38). The two windows are evaluated as
//! `smoothstep(1 + (z - znear)/near_edge)` and `smoothstep(1 - (z - zfar)/far_edge)` on
//! [0, 1], without forming `znear - near_edge` (when `near_edge` is much smaller than `znear`
//! that sum keeps little more than its rounding error, which the GLSL form then divides by).

use crate::{Error, Real, Vec3};

/// GLSL's smoothstep on an already normalized argument: `t^2 (3 - 2t)` with `t` clamped to
/// [0, 1] (NaN gives 0).
#[inline(always)]
fn smooth01<T: Real>(t: T) -> T {
    let t = t.clamp01();
    t * t * (T::from_f64(3.0) - T::TWO * t)
}

/// One Newton step toward unit length, `e (3 - e.e)/2`: squares the relative length error,
/// so a vector normalized with Fast32's cheap sqrt (4.8e-6) comes out unit to f32 rounding.
#[inline]
fn refine_unit<T: Real>(e: Vec3<T>) -> Vec3<T> {
    e * (T::from_f64(1.5) - T::HALF * e.dot(e))
}

/// `x` if finite and `> 0`, else the error for parameter `name`.
fn positive<T: Real>(x: T, name: &'static str) -> Result<T, Error> {
    if !x.is_finite() {
        Err(Error::NotFinite(name))
    } else if !(x > T::ZERO) {
        Err(Error::NotPositive(name))
    } else {
        Ok(x)
    }
}

/// `x` if finite, else [`Error::NotFinite`] for parameter `name`.
fn finite<T: Real>(x: T, name: &'static str) -> Result<T, Error> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(Error::NotFinite(name))
    }
}

/// Barzel's beam cross-section: 1 inside the inner superellipse (half-widths `a`, `b`), 0
/// outside the outer one (`A`, `B`), a smoothstep in between; roundness `d` (see the module
/// docs). The spec's `[superellipse_shape]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Superellipse<T> {
    a: T,
    b: T,
    big_a: T,
    big_b: T,
    d: T,
    /// `2/d` (may be `+inf` for a subnormal `d`: handled).
    p: T,
    /// `d/2`.
    half_d: T,
    /// `d == 1`: the gauge is a scaled hypotenuse.
    ellipse: bool,
    /// `Some(a/A)` when `a/A == b/B` (the outer curve is the inner one scaled).
    scaled: Option<T>,
}

impl<T: Real> Superellipse<T> {
    /// The shape with inner half-widths `a` (along light-space x) and `b` (along y), outer
    /// half-widths `big_a` (`A`) and `big_b` (`B`), all measured on the plane at distance 1
    /// along the beam (so they are tangents of the beam's half-angles), and roundness `d`.
    ///
    /// Computes `2/d`, `d/2` and whether the fast paths apply (`d = 1`; `A/a = B/b`) once, here.
    ///
    /// # Errors
    /// [`Error::NotFinite`] or [`Error::NotPositive`] naming `"a"`, `"b"`, `"A"`, `"B"` or
    /// `"d"`; [`Error::NotOrdered`] for `a >= A` or `b >= B`.
    pub fn new(a: T, b: T, big_a: T, big_b: T, d: T) -> Result<Self, Error> {
        for (x, name) in [(a, "a"), (b, "b"), (big_a, "A"), (big_b, "B"), (d, "d")] {
            finite(x, name)?;
        }
        for (x, name) in [(a, "a"), (b, "b"), (big_a, "A"), (big_b, "B"), (d, "d")] {
            positive(x, name)?;
        }
        if !(a < big_a) {
            return Err(Error::NotOrdered {
                low: "a",
                high: "A",
            });
        }
        if !(b < big_b) {
            return Err(Error::NotOrdered {
                low: "b",
                high: "B",
            });
        }
        let (ka, kb) = (a / big_a, b / big_b);
        Ok(Superellipse {
            a,
            b,
            big_a,
            big_b,
            d,
            p: T::TWO / d,
            half_d: d * T::HALF,
            ellipse: d == T::ONE,
            scaled: if ka == kb && ka > T::ZERO {
                Some(ka)
            } else {
                None
            },
        })
    }

    /// `[a, b, A, B, d]`, as given.
    pub fn params(&self) -> [T; 5] {
        [self.a, self.b, self.big_a, self.big_b, self.d]
    }

    /// The gauge `m (1 + (w/m)^p)^(d/2)` of `(u, v)`, `u, v >= 0` (`+inf` allowed): 0 for
    /// `(0, 0)`, `+inf` if either is infinite or the result overflows. Never NaN.
    #[inline]
    fn gauge(&self, u: T, v: T) -> T {
        let (m, w) = if u >= v { (u, v) } else { (v, u) };
        if !(m > T::ZERO) || !m.is_finite() {
            return m;
        }
        let r = w / m;
        if !(r > T::ZERO) {
            return m;
        }
        if self.ellipse {
            // One Newton step: exact-to-rounding for every backend, including Fast32's cheap
            // sqrt (4.8e-6 relative, which a thin transition band would amplify).
            let h = T::ONE + r * r;
            let g = h.sqrt();
            return m * (T::HALF * (g + h / g));
        }
        // r = 1 is special-cased: with p = +inf (subnormal d), inf * ln(1) would be NaN.
        let rp = if r >= T::ONE { T::ONE } else { r.powf(self.p) };
        m * (T::ONE + rp).powf(self.half_d)
    }

    /// The shape at a point of light space with all components finite.
    #[inline]
    fn eval(&self, pos: Vec3<T>) -> T {
        if !(pos.z > T::ZERO) {
            return T::ZERO;
        }
        let x = pos.x.abs() / pos.z;
        let y = pos.y.abs() / pos.z;
        let inner = self.gauge(x / self.a, y / self.b);
        if !(inner > T::ONE) {
            return T::ONE;
        }
        let outer = match self.scaled {
            Some(k) => inner * k,
            None => self.gauge(x / self.big_a, y / self.big_b),
        };
        if !(outer < T::ONE) {
            return T::ZERO;
        }
        let u = (T::ONE - outer) / (T::ONE - outer / inner);
        smooth01(u).finite_or_zero()
    }

    /// `[superellipse_shape]` with precise errors: see [`Superellipse::shape`].
    ///
    /// # Errors
    /// [`Error::NotFinite`] (`"pos"`) for a NaN or infinite component.
    pub fn try_shape(&self, pos: Vec3<T>) -> Result<T, Error> {
        if !pos.is_finite() {
            return Err(Error::NotFinite("pos"));
        }
        Ok(self.eval(pos))
    }

    /// `[superellipse_shape]`: the beam's cross-section factor in [0, 1] at `pos`, a point in
    /// light space (beam along +z; see [`LightFrame::to_light`]). 1 on the axis (`x = y = 0`)
    /// and inside the inner curve, 0 outside the outer curve and where `z <= 0`.
    ///
    /// Accuracy (tests/shaping/, d from 0.1 to 4): f64 within 3e-13 of a direct evaluation
    /// of the spec's formula; f32 and [`crate::Fast32`] (identical here) within 2e-6 of f64
    /// where the model is well-conditioned, and within a few times the model's own sensitivity
    /// to 1-ULP input rounding elsewhere (in a 1%-wide transition band that sensitivity is
    /// 4e-5). The measured figures are below. Thin bands are the only ill-conditioning: the error grows like
    /// 1/(band width).
    ///
    /// Cost: 2 divisions and 1 gauge; past the inner curve 1 more gauge (skipped when
    /// `A/a = B/b`) and 2 divisions. A gauge is 3 divisions and 2 `powf` (2 `exp`, 2 `ln`); for
    /// `d = 1` 1 sqrt and 1 more division (a Newton step) instead of the `powf`s; on the axes
    /// 1 division.
    ///
    /// Fallback: 0 for a non-finite `pos`.
    ///
    /// <!-- BEGIN acc-superellipse_shape: target/accuracy/model-superellipse_shape.md -->
    /// Measured: f64 within 5.0e-14 of its reference (reference); against f64, f32 6.2e-7
    /// (ill-conditioned: 2.8e-5), Fast32 6.2e-7 (ill-conditioned: 2.8e-5), Fixed22 9.8e-6; 1 253
    /// 225 cases in all (`docs/accuracy.md`).
    /// <!-- END acc-superellipse_shape -->
    #[inline]
    pub fn shape(&self, pos: Vec3<T>) -> T {
        if !pos.is_finite() {
            return T::ZERO;
        }
        self.eval(pos)
    }
}

/// Barzel's distance falloff along the beam: a cut-on zone ending at `znear`, a cut-off zone
/// starting at `zfar`, and `(d0/z)^alpha` beyond `d0` joined smoothly to a peak `M` at `z = 0`
/// (see the module docs). The spec's `[distance_falloff]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DistanceFalloff<T> {
    peak: T,
    d0: T,
    alpha: T,
    znear: T,
    zfar: T,
    near_edge: T,
    far_edge: T,
    /// `s = ln(1/M) = -ln M < 0`.
    s: T,
    /// `beta = -alpha/s >= 0` (may be `+inf` for `M` within a few ULPs of 1: handled).
    beta: T,
}

impl<T: Real> DistanceFalloff<T> {
    /// The falloff with peak `m` (`M` in the spec) at `z = 0`, canonical distance `d0` (where
    /// the value is 1), exponent `alpha`, cut-on zone `[znear - near_edge, znear]` and cut-off
    /// zone `[zfar, zfar + far_edge]`.
    ///
    /// Computes `s = ln(1/M)` (as `-ln M`) and `beta = -alpha/s` once, here.
    ///
    /// # Errors
    /// [`Error::NotFinite`] naming `"M"`, `"d0"`, `"alpha"`, `"znear"`, `"zfar"`,
    /// `"near_edge"` or `"far_edge"`; [`Error::PeakNotAboveOne`] for `M <= 1`;
    /// [`Error::NotPositive`] for `d0`, `near_edge`, `far_edge`; [`Error::Negative`] for
    /// `alpha < 0`; [`Error::NotOrdered`] for `znear >= zfar`.
    pub fn new(
        m: T,
        d0: T,
        alpha: T,
        znear: T,
        zfar: T,
        near_edge: T,
        far_edge: T,
    ) -> Result<Self, Error> {
        for (x, name) in [
            (m, "M"),
            (d0, "d0"),
            (alpha, "alpha"),
            (znear, "znear"),
            (zfar, "zfar"),
            (near_edge, "near_edge"),
            (far_edge, "far_edge"),
        ] {
            finite(x, name)?;
        }
        if !(m > T::ONE) {
            return Err(Error::PeakNotAboveOne);
        }
        positive(d0, "d0")?;
        if !(alpha >= T::ZERO) {
            return Err(Error::Negative("alpha"));
        }
        positive(near_edge, "near_edge")?;
        positive(far_edge, "far_edge")?;
        if !(znear < zfar) {
            return Err(Error::NotOrdered {
                low: "znear",
                high: "zfar",
            });
        }
        let s = -m.ln();
        Ok(DistanceFalloff {
            peak: m,
            d0,
            alpha,
            znear,
            zfar,
            near_edge,
            far_edge,
            s,
            beta: -alpha / s,
        })
    }

    /// `[M, d0, alpha, znear, zfar, near_edge, far_edge]`, as given.
    pub fn params(&self) -> [T; 7] {
        [
            self.peak,
            self.d0,
            self.alpha,
            self.znear,
            self.zfar,
            self.near_edge,
            self.far_edge,
        ]
    }

    /// `(s, beta)`: the near branch's constants.
    pub fn near_constants(&self) -> (T, T) {
        (self.s, self.beta)
    }

    /// The falloff at a finite `z >= 0`.
    #[inline]
    fn eval(&self, z: T) -> T {
        let near = smooth01(T::ONE + (z - self.znear) / self.near_edge);
        let far = smooth01(T::ONE - (z - self.zfar) / self.far_edge);
        let zones = near * far;
        if !(zones > T::ZERO) {
            return T::ZERO;
        }
        let dist = if z > self.d0 {
            if self.alpha > T::ZERO {
                (self.d0 / z).powf(self.alpha)
            } else {
                T::ONE
            }
        } else {
            let r = z / self.d0;
            // beta = 0 (alpha = 0): (z/d0)^0 = 1, at z = 0 too; r = 1: 1 even for beta = inf.
            let w = if self.beta > T::ZERO && r < T::ONE {
                r.powf(self.beta)
            } else {
                T::ONE
            };
            (self.s * (w - T::ONE)).exp()
        };
        (zones * dist).finite_or_zero().clamp(T::ZERO, self.peak)
    }

    /// `[distance_falloff]` with precise errors: see [`DistanceFalloff::falloff`].
    ///
    /// # Errors
    /// [`Error::NotFinite`] (`"z"`), [`Error::Negative`] (`"z"`) for `z < 0`.
    pub fn try_falloff(&self, z: T) -> Result<T, Error> {
        if !z.is_finite() {
            return Err(Error::NotFinite("z"));
        }
        if z < T::ZERO {
            return Err(Error::Negative("z"));
        }
        Ok(self.eval(z))
    }

    /// `[distance_falloff]`: the distance factor in [0, M] at distance `z >= 0` along the beam:
    /// `M` at `z = 0` (for `alpha > 0`, inside the zones), 1 at `d0`, `(d0/z)^alpha` beyond,
    /// times the cut-on and cut-off smoothsteps.
    ///
    /// Accuracy (tests/shaping/, relative to `max(1, value)`, M up to 100, alpha up to 4):
    /// f64 within 8e-14 of a direct evaluation of the spec's formula; f32 and
    /// [`crate::Fast32`] (identical here) within 2e-6 of f64 (measured figures below). The
    /// relative error grows with `|alpha ln(z/d0)|` and `ln M` (the exponents' rounding).
    ///
    /// Cost: 2 divisions and 2 smoothsteps; inside the zones 1 division and 1 `powf` (1 `exp`,
    /// 1 `ln`) beyond `d0`, 1 division, 1 `powf` and 1 `exp` before it.
    ///
    /// Fallback: 0 for `z < 0` or non-finite `z`.
    ///
    /// <!-- BEGIN acc-distance_falloff: target/accuracy/model-distance_falloff.md -->
    /// Measured: f64 within 1.4e-14 of its reference (reference, rel); against f64, f32 4.7e-7
    /// (ill-conditioned: 4.7e-7; unresolved: 1.6e-7), Fast32 4.7e-7 (ill-conditioned: 4.7e-7;
    /// unresolved: 1.6e-7), Fixed22 5.0e-6; 453 840 cases in all (`docs/accuracy.md`).
    /// <!-- END acc-distance_falloff -->
    #[inline]
    pub fn falloff(&self, z: T) -> T {
        self.try_falloff(z).unwrap_or(T::ZERO)
    }
}

/// A light's own frame: `origin` at the light, `+z` along the beam, `+y` toward `up`.
///
/// Maps world points into the light space that [`Superellipse`] and [`DistanceFalloff`]
/// expect (June 20.5 builds the same rotation from two axis rotations, eq. 20.43-20.45; an
/// orthonormal basis from two cross products is the same map, and also fixes the beam's roll).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightFrame<T> {
    origin: Vec3<T>,
    ex: Vec3<T>,
    ey: Vec3<T>,
    ez: Vec3<T>,
}

impl<T: Real> LightFrame<T> {
    /// The frame at `origin` with the beam along `direction` and light-space `+y` the part of
    /// `up` perpendicular to it (neither needs unit length). Light-space `+x` is `y x z`, so
    /// the frame is right-handed.
    ///
    /// Each axis gets one Newton step toward unit length, so the frame is orthonormal to the
    /// backend's rounding (Fast32's cheap sqrt included).
    ///
    /// Cost: 3 normalizations and 3 cross products, once.
    ///
    /// # Errors
    /// [`Error::NotFinite`] for `origin`, `direction` or `up`; [`Error::ZeroLength`] for
    /// `direction` or `up`; [`Error::Parallel`] when `up` is parallel to `direction` (the sine
    /// of their angle at most `16 EPSILON`: no roll can be derived from it).
    pub fn new(origin: Vec3<T>, direction: Vec3<T>, up: Vec3<T>) -> Result<Self, Error> {
        if !origin.is_finite() {
            return Err(Error::NotFinite("origin"));
        }
        let ez = direction.try_normalize("direction")?;
        let up = up.try_normalize("up")?;
        let side = up.cross(ez);
        let parallel = Error::Parallel {
            a: "up",
            b: "direction",
        };
        if !(side.max_abs() > T::from_f64(16.0) * T::EPSILON) {
            return Err(parallel);
        }
        let ez = refine_unit(ez);
        let ex = refine_unit(side.normalize().ok_or(parallel)?);
        let ey = refine_unit(ez.cross(ex).normalize().ok_or(parallel)?);
        // Re-derive x from y and z, so the basis is orthonormal to rounding even when `up` is
        // nearly parallel to the beam.
        let ex = refine_unit(ey.cross(ez));
        Ok(LightFrame { origin, ex, ey, ez })
    }

    /// The light's position.
    pub fn origin(&self) -> Vec3<T> {
        self.origin
    }
    /// The unit beam direction (light-space `+z`).
    pub fn direction(&self) -> Vec3<T> {
        self.ez
    }
    /// The unit light-space `+y` (the `b`, `B` axis of a [`Superellipse`]).
    pub fn up(&self) -> Vec3<T> {
        self.ey
    }
    /// The unit light-space `+x` (the `a`, `A` axis of a [`Superellipse`]).
    pub fn right(&self) -> Vec3<T> {
        self.ex
    }

    /// The world point `p` in light space: `((p - origin).x_l, (p - origin).y_l,
    /// (p - origin).z_l)`, so `z` is the distance along the beam.
    ///
    /// Accuracy: a few ULPs of `|p - origin|` per component. Cost: 1 subtraction, 3 dot
    /// products. Not checked: a non-finite `p` (or a difference that overflows) gives a
    /// non-finite result, which [`Superellipse::shape`] and [`DistanceFalloff::falloff`] map
    /// to their fallback 0.
    #[inline]
    pub fn to_light(&self, p: Vec3<T>) -> Vec3<T> {
        let d = p - self.origin;
        Vec3::new(d.dot(self.ex), d.dot(self.ey), d.dot(self.ez))
    }
}

/// An uberlight: a [`LightFrame`], a [`Superellipse`] beam and a [`DistanceFalloff`], giving
/// the factor `shape(l) falloff(l.z)` at a world point `p` (with `l` its light-space position).
///
/// The factor is not a light: it shapes one. Multiply the value of ANY light of the crate at
/// `p` by it (a [`crate::SphereLight`] or [`crate::PolygonLight`] irradiance, a Phong
/// highlight, a cap...), with the frame's origin at (or near) that light: the light keeps its
/// own geometry and falloff with solid angle, the uberlight adds the beam's cross-section and
/// the designer's distance zones (Barzel's model is not physical, June 20.5.3).
///
/// ```
/// use arealight::{
///     DistanceFalloff, LightFrame, PolygonLight, SphereLight, Superellipse, Uberlight, Vec3,
/// };
/// // A small bulb 3 units above the floor, aimed straight down, shaped into a soft rounded
/// // rectangle (June's figure 20-17 sizes) that peaks at 2 next to the bulb and fades out
/// // between 5 and 6 units away.
/// let bulb_at = Vec3::new(0.0f32, 0.0, 3.0);
/// let bulb = SphereLight::new(bulb_at, 0.1)?;
/// let frame = LightFrame::new(bulb_at, Vec3::new(0.0, 0.0, -1.0), Vec3::new(0.0, 1.0, 0.0))?;
/// let beam = Superellipse::new(0.2, 0.3, 0.3, 0.4, 0.8)?;
/// let falloff = DistanceFalloff::new(2.0, 1.0, 1.0, 0.5, 5.0, 0.4, 1.0)?;
/// let spot = Uberlight::new(frame, beam, falloff);
///
/// let n = Vec3::new(0.0, 0.0, 1.0); // the floor's normal
/// let centre = Vec3::new(0.0, 0.0, 0.0); // under the bulb: inside the beam, z = 3
/// let e = bulb.lambert(centre, n) * spot.factor(centre);
/// assert!((spot.factor(centre) - 1.0 / 3.0).abs() < 1e-6); // (d0/z)^alpha = 1/3
/// assert!(e > 0.0);
/// let outside = Vec3::new(2.0, 0.0, 0.0); // X = 2/3 > A: outside the beam
/// assert_eq!(bulb.lambert(outside, n) * spot.factor(outside), 0.0);
///
/// // The same beam shapes a square area light hanging at the same place.
/// let panel = PolygonLight::<f32, 4>::new(&[
///     Vec3::new(-0.2, -0.2, 3.0),
///     Vec3::new(0.2, -0.2, 3.0),
///     Vec3::new(0.2, 0.2, 3.0),
///     Vec3::new(-0.2, 0.2, 3.0),
/// ])?;
/// let p = Vec3::new(0.5, 0.2, 0.0);
/// let shaped = panel.lambert(p, n) * spot.factor(p);
/// assert!(shaped > 0.0 && shaped < panel.lambert(p, n));
/// # Ok::<(), arealight::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Uberlight<T> {
    /// Where the light is and where it points.
    pub frame: LightFrame<T>,
    /// The beam's cross-section.
    pub shape: Superellipse<T>,
    /// The distance factor along the beam.
    pub falloff: DistanceFalloff<T>,
}

impl<T: Real> Uberlight<T> {
    /// Combines already validated parts (so it cannot fail).
    pub fn new(frame: LightFrame<T>, shape: Superellipse<T>, falloff: DistanceFalloff<T>) -> Self {
        Uberlight {
            frame,
            shape,
            falloff,
        }
    }

    /// The shaping factor at the world point `p`: `shape(l) falloff(l.z)` with
    /// `l = frame.to_light(p)`, in [0, M]. 0 behind the light (`l.z <= 0`).
    ///
    /// Accuracy: that of [`Superellipse::shape`] and [`DistanceFalloff::falloff`] at `l`, whose
    /// own rounding is a few ULPs of `|p - origin|`. Cost: [`LightFrame::to_light`] plus the
    /// two factors (the falloff is skipped where the shape is 0).
    ///
    /// Fallback: 0 for a non-finite `p` (or one so far away that `p - origin` overflows).
    #[inline]
    pub fn factor(&self, p: Vec3<T>) -> T {
        let l = self.frame.to_light(p);
        let shape = self.shape.shape(l);
        if !(shape > T::ZERO) {
            return T::ZERO;
        }
        shape * self.falloff.falloff(l.z)
    }
}
