//! Arvo's axial and double-axis moments of polygons, and what they shade: directional
//! luminaires, glossy reflection and transmission, and the lune normalization (Arvo,
//! "Applications of Irradiance Tensors to the Simulation of Non-Lambertian Phenomena",
//! SIGGRAPH 95, sections 4-6).
//!
//! ## The recurrences
//!
//! For a region `A` of the unit sphere and a unit axis `w`, the axial moment
//! `tau^n(A, w) = integral over A of (w.u)^n du` satisfies (Arvo eq. 11, from Stokes' theorem)
//!
//! ```text
//! (n + 1) tau^n = (n - 1) tau^(n-2) - integral over dA of (w.u)^(n-1) (w.nu) ds,
//! ```
//!
//! `nu` the outward normal of the boundary, `tau^0` the solid angle, `tau^-1 = 0`; and the
//! double-axis moment `tau^(n,1)(A, w, v) = integral over A of (w.u)^n (v.u) du` satisfies
//! (eq. 14)
//!
//! ```text
//! (n + 2) tau^(n,1) = n (w.v) tau^(n-1)(A, w) - integral over dA of (w.u)^n (v.nu) ds.
//! ```
//!
//! When `A` is the projection of a polygon its boundary is a ring of great arcs. Walking each
//! arc from `a` to `b` with the region on its left seen from outside the sphere (a
//! counter-clockwise ring: positive solid angle), the outward normal is `-g`, `g` the unit
//! `a x b`, constant on the arc. With `u(t) = s cos t + t' sin t` on the arc (`s = a/|a|`,
//! `t' = g x s`, `t` in `[0, l]`, `l` the arc's angle) and `(alpha, beta) = (w.s, w.t')`, the arc
//! integrals are `T(k) = integral_0^l (alpha cos t + beta sin t)^k dt`, which obey Snyder's
//! recurrence (appendix G; Arvo eq. 19 in shifted form)
//!
//! ```text
//! k T(k) = (k - 1) c^2 T(k - 2) + G^(k-1) H + beta alpha^(k-1),   T(0) = l,  T(1) = H + beta,
//! ```
//!
//! with `c^2 = alpha^2 + beta^2 = 1 - (w.g)^2`, `G = w.u(l)`, `H = alpha sin l - beta cos l`.
//! Unrolling eq. 11 (Arvo eq. 12) and substituting it in eq. 14 gives, with `Q` the sum over
//! the arcs,
//!
//! ```text
//! (n + 1) tau^n     = [n even] Omega + Q_e (w.g) [T(n-1) + T(n-3) + ...]
//! (n + 2) tau^(n,1) = (w.v) ([n odd] Omega + Q_e (w.g) [T(n-2) + T(n-4) + ...]) + Q_e (v.g) T(n)
//! ```
//!
//! so one upward run of the recurrence per arc, to `k = n`, gives everything (Arvo's
//! `CosSumIntegral` returning "one additional term", 5.4): O(n) per edge, O(n k) for `k` edges.
//! The recurrence is forward-stable (`(k - 1) c^2/k < 1` damps earlier errors). `Omega`, the
//! signed solid angle, is the fan of Van Oosterom-Strackee triangles of [`crate::polygon`]
//! (Arvo 5.1).
//!
//! **Orientation.** The raw integrals carry no orientation sign (`docs/models.md`): the
//! sum above is multiplied by the orientation of the ring seen from `p`, the sign of
//! `N.(v - p)` (averaged over the vertices), `N` the polygon's right-handed normal. So the
//! result is the integral over the projection whatever the winding. A point in the polygon's
//! plane sees a projection of zero area: every model is 0 there.
//!
//! **Early termination (eq. 21).** `|T(k)| <= l c^k` (the integrand is at most `c^k`), so after
//! the term `T(K)` the rest of an arc's contribution is at most
//! `l c^(K+2) (|w.v| min((n/2) |w.g|, 1/|w.g|) + |v.g|)` (a geometric tail, `1 - c^2 = (w.g)^2`).
//! The `_within` variants stop an arc's recurrence as soon as that bound is below its share
//! `tol/k` of the tolerance and drop the rest, so the result is within `tol` of the exact
//! moment (in exact arithmetic; rounding adds the error of the full evaluation). This is the
//! rigorous form of Arvo's test, which assumes `|F(k+2)| <= |F(k)|` instead of bounding each
//! term. It pays where every edge's great circle stays far from `w` (`c` well below 1); an
//! edge whose great circle passes near `w` runs to the end.
//!
//! ## Two half-spaces
//!
//! The shading models integrate over `A` clipped to two hemispheres, `{u.w >= 0}` (the lobe)
//! and `{u.v >= 0}` (the cosine factor), and are then the double-axis moment of the clipped
//! region (Arvo 6.1-6.3, the cosine factor being the second axis):
//!
//! | model | w | v | value |
//! |---|---|---|---|
//! | [`PolygonLight::directional_luminaire`] | `-axis` | `n` | `tau^(m,1)` |
//! | [`PolygonLight::glossy_reflection`] | `2 (n.e) n - e` | `n` | `(m + 2)/(2 pi) tau^(m,1)` |
//! | [`PolygonLight::glossy_transmission`] | `-e` | `-n` | `(m + 2)/(2 pi) tau^(m,1)` |
//!
//! The clipping is streamed, with no buffer: the horizon clipper of [`crate::polygon`] clips
//! the ring to the first plane and each clipped arc is clipped to the second plane as it
//! arrives; the second stage remembers the ring's first re-entry to close its last arc along
//! the second plane (the ring may start below it). Clipping by a plane through `p` keeps great
//! arcs great arcs, and an arc along a clipping plane is stored as its chord, whose projection
//! is the arc (less than pi: the projection lies in an open hemisphere). Its great circle is
//! known exactly (the plane's normal), which keeps its terms accurate when it spans nearly pi
//! (a polygon seen nearly edge-on). The solid angle, needed for odd `m`, is the fan about the
//! first plane's normal: exact for arcs on that plane, Van Oosterom-Strackee for the others.
//!
//! ## The lune (Arvo 6.4)
//!
//! On the lune `{w.u >= 0, v.u >= 0}`, with `d = w.v`, `s = |w x v|`, the boundary is half of
//! the circle of `w` (where `w.u = 0`, so only `T(0) = pi` survives) and half of the circle of
//! `v` (where `w.u = s sin t`, so `T(k) = s^k S(k)`, `S(k) = integral_0^pi sin^k`). Eq. 11 and 14
//! then give
//!
//! ```text
//! tau^0 = 2 atan2(s, -d),  tau^1 = pi (1 + d)/2,  (k + 1) tau^k = (k - 1) tau^(k-2) + d s^(k-1) S(k-1),
//! (m + 2) N = m d tau^(m-1) + s^m S(m)      (m >= 1;  N = pi (1 + d)/2 for m = 0),
//! ```
//!
//! O(m), exact for every `w`, `v` (Arvo's procedure N is the same recurrence).
//!
//! ## Accuracy
//!
//! Measured against an independent quadrature of the definitions (`tests/moments/`, m in
//! {0, 1, 2, 3, 16, 63, 64}; absolute errors, the values being at most 2 pi): f64 within
//! 2e-13 for the raw moments and 5e-12 for the clipped models, including polygons seen nearly
//! edge-on (p within 1e-12 of their plane) and partly behind either clipping plane; the lune
//! within 5e-14. f32 within 1.1e-6 of f64 on the same inputs in the main regime; near a
//! polygon's boundary (p within 2% of its size from an edge) the error grows as
//! `2^-24 size/dist` (1.8e-4 at `dist = 1e-3 size`), as for [`PolygonLight::lambert`].
//! [`crate::Fast32`] within 2.1e-4 (main regime), and `1/1024 + 2^-18 size/dist` near the
//! boundary. Within 4 ULPs of the polygon's plane every model returns its documented 0; the
//! raw moments, which have no cosine factor, can be far from 0 there in f32.
//!
//! [`crate::Fixed22`] (`tests/fixed_moments.rs`: the same random, adversarial and edge-on
//! polygons scaled into its coordinate cube, `p` at least 1/256 of the polygon's size from
//! it, m up to 255, which is also the largest `m` it accepts): axial moment within 9.7e-5 of
//! f64, double-axis 2.9e-5 (at most 4.7e-4 and 1.7e-4 over ten other seeds and case counts), the lune 1.6e-6. The clipped
//! models miss 1/1024 there, so the fixed-point eval backend does not answer them: the
//! directional luminaire 2.8e-2 and glossy reflection 9.2e-3 (a star polygon nearly edge-on,
//! `p` 5e-3 of its size from a vertex: the fixed path answers 0; products of two point
//! differences of length `d` carry `2^-22 (size/d)^2`, and the clipped solid angle there is
//! itself 7.1e-3 off), glossy transmission up to 0.93 (edge-on polygons with the foot of `p`
//! in the L's notch, with other seeds). Within a few LSB of the polygon's plane every model
//! answers its in-plane 0, where f64 can see up to 2 pi.
//!
//! Two planes within `sqrt(eps)` of each other are taken as one (an error of about `2 eps`).
//! Planes nearly opposite (`w.v` near -1, a thin lune) make the solid-angle term of odd `m`
//! ill-conditioned (a ratio of two quantities of the lune's width): not yet measured.

use crate::lobe::MAX_EXPONENT;
use crate::polygon::{
    for_each_clipped_edge, near_limit, ApexFan, ClippedEdge, PolygonLight, CROSSING,
    LAMBERT_NEAR_LOG2,
};
use crate::{Error, Real, Vec3};

mod arcs;
mod luminaire;
mod lune;
use arcs::{Arc, Circle, MomentSum, SecondClip};
pub use lune::{lune_normalization, try_lune_normalization};

/// `m` within [`MAX_EXPONENT`] and the scalar type's own limit
/// ([`Real::MAX_PHONG_EXPONENT`]: 255 for [`crate::Fixed22`], whose recurrences reach `m + 2`
/// and whose range ends at 512).
fn check_m<T: Real>(m: u32) -> Result<(), Error> {
    if m > MAX_EXPONENT || m > T::MAX_PHONG_EXPONENT {
        Err(Error::ExponentOutOfRange)
    } else {
        Ok(())
    }
}

impl<T: Real, const N: usize> PolygonLight<T, N> {
    /// The orientation of the ring seen from `p` (+1 counter-clockwise seen from outside the
    /// sphere, i.e. right-handed about the direction toward the polygon), or `None` in the
    /// plane.
    fn orientation(&self, p: Vec3<T>) -> Option<T> {
        if self.in_plane(p) {
            return None;
        }
        let nrm = self.normal();
        let mut h = T::ZERO;
        for &x in self.vertices() {
            h += nrm.dot(x - p);
        }
        if h > T::ZERO {
            Some(T::ONE)
        } else if h < T::ZERO {
            Some(-T::ONE)
        } else {
            None
        }
    }

    /// `(n + 2) tau^(n,1)` (unsigned) of the unclipped projection; `tol_q` the tolerance on it.
    fn raw_moment_sum(&self, p: Vec3<T>, w: Vec3<T>, v: Vec3<T>, n: u32, tol_q: T) -> T {
        let Some(sigma) = self.orientation(p) else {
            return T::ZERO;
        };
        let verts = self.vertices();
        let k = verts.len();
        let wv = w.dot(v);
        let mut acc = MomentSum {
            n,
            w,
            v,
            wv,
            k1: w,
            k2: v,
            budget: if tol_q > T::ZERO {
                tol_q / T::from_u32(k as u32)
            } else {
                T::ZERO
            },
            sum: T::ZERO,
        };
        let need_omega = n & 1 == 1;
        let mut fan = ApexFan::new(self.normal() * sigma);
        // Each edge (a, b) of the ring, the last closing it (no indexing: nothing to check).
        for (&a, &b) in verts.iter().zip(verts.iter().skip(1).chain(verts.first())) {
            let arc = Arc {
                ua: a - p,
                ub: b - p,
                d: b - a,
                circle: Circle::Edge,
            };
            if need_omega {
                fan.add(&ClippedEdge {
                    ua: arc.ua,
                    ub: arc.ub,
                    d: arc.d,
                    horizon: false,
                    ia: CROSSING,
                    ib: CROSSING,
                });
            }
            acc.add(&arc);
        }
        let mut q = acc.sum;
        if need_omega {
            q += wv * fan.total();
        }
        (sigma * q).finite_or_zero()
    }

    /// `(n + 2) tau^(n,1)` of the projection clipped to `u.w >= 0` and `u.v >= 0` (`w`, `v`
    /// unit), never negative.
    fn clipped_moment_sum(&self, p: Vec3<T>, w: Vec3<T>, v: Vec3<T>, n: u32) -> T {
        let Some(sigma) = self.orientation(p) else {
            return T::ZERO;
        };
        let wv = w.dot(v);
        // Planes within sqrt(eps) of each other are taken as one: the sliver between them adds
        // at most about 2 |w x v|^2 = 2 eps (its area times the largest (v.u) on it).
        let cr = w.cross(v);
        let line = if cr.length() > T::EPSILON.sqrt() {
            cr.normalize()
        } else {
            None
        };
        if line.is_none() && wv < T::ZERO {
            return T::ZERO; // Opposite half-spaces: a great circle, of zero area.
        }
        let mut acc = MomentSum {
            n,
            w,
            v,
            wv,
            k1: w,
            k2: v,
            budget: T::ZERO,
            sum: T::ZERO,
        };
        let need_omega = n & 1 == 1;
        let mut fan = ApexFan::new(w);
        let mut second = SecondClip {
            k: v,
            k1: w,
            line,
            exit: None,
            first_entry: None,
        };
        // Arcs on the second plane: the fan triangle about w rewritten about v (module docs).
        let mut second_fan = T::ZERO;
        let psi = |x: Vec3<T>| -> T {
            let Some(x) = x.normalize() else {
                return T::ZERO;
            };
            let num = v.dot(x.cross(w));
            let den = T::ONE + x.dot(w) + v.dot(x) + wv;
            T::TWO * num.atan2(den)
        };
        let mut emit = |arc: &Arc<T>| {
            if need_omega {
                if arc.circle == Circle::Second {
                    second_fan += arc.ua.cross(arc.d).dot(v).atan2(arc.ua.dot(arc.ub))
                        + psi(arc.ub)
                        - psi(arc.ua);
                } else {
                    fan.add(&ClippedEdge {
                        ua: arc.ua,
                        ub: arc.ub,
                        d: arc.d,
                        horizon: arc.circle == Circle::First,
                        ia: CROSSING,
                        ib: CROSSING,
                    });
                }
            }
            acc.add(arc);
        };
        for_each_clipped_edge(self.vertices(), p, w, T::ZERO, |e| {
            second.push(
                Arc {
                    ua: e.ua,
                    ub: e.ub,
                    d: e.d,
                    circle: if e.horizon {
                        Circle::First
                    } else {
                        Circle::Edge
                    },
                },
                &mut emit,
            );
        });
        second.finish(&mut emit);
        let mut q = acc.sum;
        if need_omega {
            q += wv * (fan.total() + second_fan);
        }
        (sigma * q).finite_or_zero().max(T::ZERO)
    }

    /// `[axial_moment]` with precise errors and an optional tolerance: see
    /// [`PolygonLight::axial_moment`]. With `tol > 0` each edge's recurrence stops as soon as
    /// the rest of its terms is bounded by its share of `tol` (Arvo eq. 21 in rigorous form,
    /// module docs): the result is within `tol` of the exact moment plus rounding. `tol <= 0`
    /// evaluates exactly.
    ///
    /// # Errors
    /// [`Error::NotFinite`] for `p`, `w` or `tol`, [`Error::OutOfRange`] for a fixed-point `p`
    /// beyond [`Real::COORDINATE_LIMIT`], [`Error::ZeroLength`] for `w`,
    /// [`Error::ExponentOutOfRange`] for `m > MAX_EXPONENT` (255 for [`crate::Fixed22`]),
    /// [`Error::Unresolved`] for a fixed-point `p` within the type's rounding of the plane,
    /// over the face (see [`PolygonLight::try_lambert`]).
    pub fn try_axial_moment_within(
        &self,
        p: Vec3<T>,
        w: Vec3<T>,
        m: u32,
        tol: T,
    ) -> Result<T, Error> {
        check_m::<T>(m)?;
        p.check_position("p")?;
        if !tol.is_finite() {
            return Err(Error::NotFinite("tol"));
        }
        let w = w.try_normalize("w")?;
        // Fixed point within its rounding of the plane over the face: unresolved (the moment
        // jumps from 0 in the plane to the hemisphere's just off it).
        if T::RESOLUTION > T::ZERO && self.in_plane(p) {
            self.resolved_in_plane(p, near_limit::<T>(LAMBERT_NEAR_LOG2))?;
        }
        if m == 0 {
            return Ok(self.signed_solid_angle_abs(p));
        }
        // (m + 1) tau^m is the double-axis sum of order m - 1 with v = w.
        let scale = T::from_u32(m + 1);
        Ok(self.raw_moment_sum(p, w, w, m - 1, tol * scale) / scale)
    }

    /// `|Omega|` of the unclipped projection.
    fn signed_solid_angle_abs(&self, p: Vec3<T>) -> T {
        let Some(sigma) = self.orientation(p) else {
            return T::ZERO;
        };
        let verts = self.vertices();
        let mut fan = ApexFan::new(self.normal() * sigma);
        for (&a, &b) in verts.iter().zip(verts.iter().skip(1).chain(verts.first())) {
            fan.add(&ClippedEdge {
                ua: a - p,
                ub: b - p,
                d: b - a,
                horizon: false,
                ia: CROSSING,
                ib: CROSSING,
            });
        }
        (sigma * fan.total())
            .finite_or_zero()
            .clamp(T::ZERO, T::TAU)
    }

    /// `[axial_moment]` with precise errors: see [`PolygonLight::axial_moment`].
    ///
    /// # Errors
    /// [`Error::NotFinite`] for `p` or `w`, [`Error::OutOfRange`] for a fixed-point `p` beyond
    /// [`Real::COORDINATE_LIMIT`], [`Error::ZeroLength`] for `w`,
    /// [`Error::ExponentOutOfRange`] for `m > MAX_EXPONENT` (255 for [`crate::Fixed22`]).
    #[inline]
    pub fn try_axial_moment(&self, p: Vec3<T>, w: Vec3<T>, m: u32) -> Result<T, Error> {
        self.try_axial_moment_within(p, w, m, T::ZERO)
    }

    /// `[axial_moment]`: `integral over the projection A of (w.u)^m du` (steradians; `w` any
    /// length; signed integrand, so odd `m` can give negative values; no clipping). `m = 0` is
    /// the solid angle.
    ///
    /// Accuracy: see the module docs (f64 within 2e-13 sr of the quadrature). Cost per edge: 2 normalizations, 2 cross products, 1 sqrt, 1 atan2,
    /// 1 division and `m/2` recurrence steps of ~6 operations (plus one Van Oosterom-Strackee
    /// triangle for even `m`). Fallback: 0 for a zero or non-finite input, `m` out of range, or
    /// `p` in the polygon's plane.
    ///
    /// <!-- BEGIN acc-axial_moment: target/accuracy/model-axial_moment.md -->
    /// Measured: f64 within 2.9e-13 of its reference (the independent quadrature, adversarial);
    /// against f64, f32 4.8e-7 (ill-conditioned: 6.0e-7; near boundary: 5.8e-5), Fast32 1.1e-4
    /// (ill-conditioned: 1.8e-4), Fixed22 9.7e-5 at m = 0; 80 205 cases in all
    /// (`docs/accuracy.md`).
    /// <!-- END acc-axial_moment -->
    #[inline]
    pub fn axial_moment(&self, p: Vec3<T>, w: Vec3<T>, m: u32) -> T {
        self.try_axial_moment(p, w, m).unwrap_or(T::ZERO)
    }

    /// [`PolygonLight::try_axial_moment_within`] with the 0 fallback.
    #[inline]
    pub fn axial_moment_within(&self, p: Vec3<T>, w: Vec3<T>, m: u32, tol: T) -> T {
        self.try_axial_moment_within(p, w, m, tol)
            .unwrap_or(T::ZERO)
    }

    /// `[double_axis_moment]` with precise errors and an optional tolerance: see
    /// [`PolygonLight::double_axis_moment`] and, for `tol`,
    /// [`PolygonLight::try_axial_moment_within`].
    ///
    /// # Errors
    /// [`Error::NotFinite`] for `p`, `w`, `v` or `tol`, [`Error::OutOfRange`] for a fixed-point
    /// `p` beyond [`Real::COORDINATE_LIMIT`], [`Error::ZeroLength`] for `w` or `v`,
    /// [`Error::ExponentOutOfRange`] for `m > MAX_EXPONENT` (255 for [`crate::Fixed22`]),
    /// [`Error::Unresolved`] as [`PolygonLight::try_axial_moment_within`].
    pub fn try_double_axis_moment_within(
        &self,
        p: Vec3<T>,
        w: Vec3<T>,
        v: Vec3<T>,
        m: u32,
        tol: T,
    ) -> Result<T, Error> {
        check_m::<T>(m)?;
        p.check_position("p")?;
        if !tol.is_finite() {
            return Err(Error::NotFinite("tol"));
        }
        let w = w.try_normalize("w")?;
        let v = v.try_normalize("v")?;
        if T::RESOLUTION > T::ZERO && self.in_plane(p) {
            self.resolved_in_plane(p, near_limit::<T>(LAMBERT_NEAR_LOG2))?;
        }
        let scale = T::from_u32(m + 2);
        Ok(self.raw_moment_sum(p, w, v, m, tol * scale) / scale)
    }

    /// `[double_axis_moment]` with precise errors: see [`PolygonLight::double_axis_moment`].
    ///
    /// # Errors
    /// As [`PolygonLight::try_double_axis_moment_within`].
    #[inline]
    pub fn try_double_axis_moment(
        &self,
        p: Vec3<T>,
        w: Vec3<T>,
        v: Vec3<T>,
        m: u32,
    ) -> Result<T, Error> {
        self.try_double_axis_moment_within(p, w, v, m, T::ZERO)
    }

    /// `[double_axis_moment]`: `integral over the projection A of (w.u)^m (v.u) du`
    /// (steradians; `w`, `v` any length; signed integrand; no clipping), Arvo eq. 14.
    ///
    /// Accuracy: see `tests/moments/`. Cost: that of [`PolygonLight::axial_moment`] with one
    /// more recurrence step per edge. Fallback: 0 for a zero or non-finite input, `m` out of
    /// range, or `p` in the polygon's plane.
    ///
    /// <!-- BEGIN acc-double_axis_moment: target/accuracy/model-double_axis_moment.md -->
    /// Measured: f64 within 9.7e-14 of its reference (the independent quadrature, adversarial);
    /// against f64, f32 4.9e-7 (ill-conditioned: 3.7e-7; near boundary: 2.9e-5), Fast32 5.9e-5
    /// (ill-conditioned: 5.7e-5), Fixed22 2.9e-5 at m = 1; 80 212 cases in all
    /// (`docs/accuracy.md`).
    /// <!-- END acc-double_axis_moment -->
    #[inline]
    pub fn double_axis_moment(&self, p: Vec3<T>, w: Vec3<T>, v: Vec3<T>, m: u32) -> T {
        self.try_double_axis_moment(p, w, v, m).unwrap_or(T::ZERO)
    }

    /// [`PolygonLight::try_double_axis_moment_within`] with the 0 fallback.
    #[inline]
    pub fn double_axis_moment_within(
        &self,
        p: Vec3<T>,
        w: Vec3<T>,
        v: Vec3<T>,
        m: u32,
        tol: T,
    ) -> T {
        self.try_double_axis_moment_within(p, w, v, m, tol)
            .unwrap_or(T::ZERO)
    }
}
