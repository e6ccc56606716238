//! Linear (segment) lights and parallelogram lights (Picott, "Extensions of the Linear and Area
//! Lighting Models"): the Lambertian integral of a segment in closed form (appendix A), and
//! Picott's peak approximation of the Phong term for a segment (eq. 7) and a parallelogram
//! (section 3.2).
//!
//! ## `[line_lambert]`: the integral
//!
//! For the segment `a -> b` seen from `p` with unit normal `n` and decay exponent `k`,
//! `L(t) = a + t (b - a) - p`, the value is Picott's eq. 3 with `I_p k_d = 1`:
//!
//! ```text
//! I = integral over t in [0, 1] of (L(t).n)+ / |L(t)|^(k+1) dt
//! ```
//!
//! Not normalized: it scales as `length^-k`. Picott (appendix A) writes the antiderivatives of
//! `(A + B t)/(C + D t + E t^2)^((k+1)/2)` for k = 0..3 with `A = L0.n`, `B = Ld.n`,
//! `C = L0.L0`, `D = 2 Ld.L0`, `E = Ld.Ld` as logarithms and arc tangents of `sqrt(4CE - D^2)`;
//! taken literally they divide by the perpendicular distance and subtract nearly equal logs and
//! arc tangents when `p` is close to the segment's line, when the segment is far or short, or
//! long. The same integrals are evaluated here in a form that has none of those cancellations.
//!
//! **Frame.** With `e` the unit direction of `b - a`, `s` the signed distance along the line
//! from the foot of the perpendicular from `p`, `H` the perpendicular distance (from the cross
//! product `|(a - p) x e|`, not from `C - D^2/4E`), and `rho(s) = sqrt(H^2 + s^2)`:
//!
//! ```text
//! I = (1/len) integral over [s0, s1] of (alpha + beta s)+ / rho^(k+1) ds,
//!     alpha = h.n (|alpha| <= H),  beta = e.n,  s0 = (a - p).e,  s1 = (b - p).e
//! ```
//!
//! **Clipping first.** `L.n` is linear in `s`, so the part above the tangent plane is one
//! interval: its ends are the segment's own where `L.n > 0` and the crossing
//! `t* = (a - p).n / ((a - p).n - (b - p).n)` (a ratio of two endpoint values of opposite signs:
//! no cancellation) elsewhere, placed from the nearer end, or as `s* = -alpha/beta` from the
//! foot when it is much nearer the foot than the ends (then `s0 + t* len` would cancel, and a
//! shading point close to the segment needs the crossing to the precision of `H`). Then, by
//! the symmetry `s -> -s`, `beta -> -beta`, the interval is either on one side of the foot
//! (`0 <= s0 < s1`) or contains it (`s0 < 0 < s1`).
//!
//! **The two moments.** `F0 = integral rho^-(k+1) ds`, `F1 = integral s rho^-(k+1) ds`,
//! `I = (alpha F0 + beta F1)/len`. With `D = s1 - s0` (from the clipped length, not a
//! difference of two large `s`), `S = s0 + s1`, `P = rho0 rho1`, the identities
//! `rho1 - rho0 = D S/(rho0 + rho1)` and `rho1^2 - rho0^2 = D S` remove every difference of
//! endpoint terms:
//!
//! | k | `F1` | `alpha F0`, one side (`s0 >= 0`) | `alpha F0`, across the foot |
//! |---|---|---|---|
//! | 0 | `rho1 - rho0` | `alpha ln1p((D + rho1 - rho0)/(s0 + rho0))` | `alpha (asinh(s1/H) + asinh(-s0/H))` |
//! | 1 | `ln(rho1/rho0)` (`ln1p(D S/rho0^2)/2` near 1) | `(alpha/H) theta` | `(alpha/H) theta` |
//! | 2 | `(rho1 - rho0)/P` | `alpha D S/((s1 rho0 + s0 rho1) P)` | `(alpha/H^2)(s1/rho1 - s0/rho0)` |
//! | 3 | `D S/(2 P^2)` | `alpha (D/P^2 + 2 (theta/H)^3 Y(2 theta))` | `(alpha/2H^3)(theta + H (s1/rho1^2 - s0/rho0^2))` |
//!
//! where `theta = atan2(H D, H^2 + s0 s1)` is the angle the interval subtends at `p`,
//! `Y(y) = (y - sin y)/y^3` by its series (`y <= pi` on one side), and on one side `theta/H` is
//! evaluated as `(D/(H^2 + s0 s1)) atan(z)/z`, `z = H D/(H^2 + s0 s1)` (so `H = 0`, `p` on the
//! line, is a regular case). Across the foot the angular forms are sums of terms of one sign.
//! On one side none of the forms divides by `H`; the `k = 3` one is the angular
//! `(theta - sin theta cos theta)/(2H^3) + D/P^2`, whose first term would cancel for small
//! `theta`, rewritten with `theta - sin theta cos theta = (2 theta - sin 2 theta)/2` and the
//! series. `alpha` comes from the cross product (`(a - p) x e . (n x e)`), clamped to `[-H, H]`.
//!
//! **Scale.** Every length is divided by the largest component of `a - p`, `b - p` first (and
//! the coordinates are halved first if a difference overflows), so no square overflows or
//! underflows; the result is scaled back by `sigma^-k` at the end.
//!
//! ## `[line_phong_peak]` and `[rect_phong_peak]`: Picott's peak
//!
//! The value is the largest `((u.r)+)^m` over the directions `u` from `p` to a point of the
//! light. For a segment the directions form an arc (less than pi) of the great circle through
//! `p` and the segment; `u.r` along it is `|r'| cos(phi - phi_r)` with `r'` the projection of `r`
//! on the arc's plane, so the maximum is at the closest angular point, `phi = phi_r`, when that
//! lies within the arc, else at an end. The stationary point is Picott's eq. 7 (in `s`:
//! `s* = beta_r H^2/alpha_r`); the test "within the arc" is made without dividing,
//! `alpha_r > 0`, `s0 alpha_r <= H^2 beta_r <= s1 alpha_r`, which is eq. 7 clamped to the segment.
//!
//! For a parallelogram `origin + s eu + t ev` (Picott 3.2) the maximum is 1 when the ray
//! `p + lambda r` (`lambda > 0`) hits the parallelogram; otherwise it is on the boundary (the
//! angular distance to `r` has no other local minimum on the sphere), and each of the four edges
//! is a segment as above. Picott intersects the ray with the plane and picks the edge(s) by the
//! range of `(u, v)`; here the hit test is the sign of `r.(q_i x e_i)` on the four edges (`q_i`
//! the corners relative to `p`: scale-free, no division) and all four edges are searched, which
//! costs a little more and cannot pick the wrong edge.
//!
//! **Accuracy at high m.** `cos^m` amplifies the rounding of a cosine near 1 by `m`. The code
//! computes the versine `v = 1 - cos` directly (`|u - r|^2/2` at an end; in the interior
//! `w^2/(1 + sqrt(1 - w^2))` with `w = r.nu`, `nu` the arc plane's normal, or `1 - |r'|` when
//! `w^2 > 1/2`, where `1 - w^2` would cancel) and returns `exp(m ln1p(-v))`, whose error does
//! not grow with `m`.
//!
//! The exponent is passed as a [`PhongLobe`](crate::PhongLobe) (validated once,
//! `m <= lobe::MAX_EXPONENT`; the exponent asked for,
//! [`PhongLobe::exponent`](crate::PhongLobe::exponent), is used even for an odd-only lobe: the
//! peak is exact and cheap for every `m`). `m = 0` gives 1 if some point of the light is in front of the
//! plane normal to `r`, else 0 (the spec's `((x)+)^0`).
//!
//! A shading point in the plane of the parallelogram (to within a few ULPs) follows the
//! definition too: the peak is not a polygon model (the spec's "valid but degenerate" case
//! gives those 0 there, a projection of zero solid angle), it is the largest `((u.r)+)^m`
//! over the light's points, all of them then seen in the plane: the best over its edges. A
//! shading point on the segment is invalid for every segment model.
//!
//! ## Accuracy (measured by `tests/line/`, which prints them as `[maxerr]` lines)
//!
//! `[line_lambert]`, errors relative to `max(1, |I|)`:
//!
//! - f64 against an adaptive Gauss-Kronrod quadrature of the definition (1864 random and
//!   adversarial cases, k = 0..3): 2e-15, including a shading point within 1e-12 of the segment
//!   (or of an end) in an axis-aligned frame, horizon crossings, long (1e6) and short (1e-9)
//!   segments. Two kinds of case are limited by the conditioning of f64 itself: `p` within
//!   1e-6 of the length of a segment in a general orientation, 4e-10 (the rounding of `a - p`,
//!   relative to `|a - p|`, is `len/H` times larger relative to `H`; the library and the
//!   quadrature sit on either side of the 50-digit value), and nearly collinear far segments,
//!   1e-13 (where a one-ULP change of `p` moves the value by 7e-12).
//! - f32 against f64 on the same inputs: 3.4e-7 where well conditioned. Where the f64 value
//!   itself moves by more than 5e-7 under one-ULP changes of the f32 inputs (grazing horizon
//!   crossings, nearly collinear segments), within 5% of `2e-6 + 4 x` that change; with `p`
//!   closer to the segment than 2% of its length, within a third of `2e-6 + 16 2^-24 len/dist`
//!   (the same regime as the polygons near their boundary).
//! - Fast32 against f64: 2e-5 where well conditioned (its `atan2` is relatively 1.3e-4 off for
//!   small angles, its `sqrt` 4.8e-6).
//!
//! Peaks (values in [0, 1]): f64 against a brute-force search (dense sampling, golden-section
//! refinement) 6e-11 for m <= 1000 (segments of length 2e5 seen from 1; 7e-13 for the
//! parallelograms), 7e-10 at m = 2^16 and 2^20 (the brute force's own `cos^m`). f32 against f64
//! 5e-7 where well conditioned, Fast32 7.4e-6, for m up to 1000. [`crate::Fixed22`]
//! (`tests/fixed_line.rs`, m <= 255, `p` at least 1/256 of the light's size from it): the
//! parallelogram's peak within 9.4e-5 (1.4e-4 over ten other seeds). Not supported in fixed point:
//! the segment's peak (2.6e-2 at m = 255 for `p` near the segment's line beyond an end: `h`,
//! the length of the frame's perpendicular `g`, vanishes when the squares of `g`'s components,
//! relative to the size, fall below `2^-22`, and `p` is refused as on the segment up to 4.3e-4
//! of the length from it), and `[line_lambert]`: its values reach `(size/dist)^k`, beyond the
//! format's 512 for k = 2, 3 near the segment (where they saturate instead of reporting
//! [`crate::Error::Overflow`]), and its k = 3 terms saturate inside (1.6 relative to
//! `max(1, I)` measured at 1/100 of the length).

use crate::unit::Direction;
use crate::{Error, Real, Vec3};

mod peak;
pub use peak::ParallelogramLight;

/// Picott's decay exponent `k` of `[line_lambert]`: the integrand is `cos / |L|^k`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Decay {
    /// `k = 0`: no fall-off with distance.
    Constant,
    /// `k = 1`: `1/|L|`.
    Inverse,
    /// `k = 2`: `1/|L|^2`, the physical inverse square law.
    InverseSquare,
    /// `k = 3`: `1/|L|^3`.
    InverseCube,
}

impl Decay {
    /// The decay of exponent `k`.
    ///
    /// # Errors
    /// [`Error::DecayOutOfRange`] for `k` outside {0, 1, 2, 3}.
    pub fn new(k: u32) -> Result<Self, Error> {
        match k {
            0 => Ok(Decay::Constant),
            1 => Ok(Decay::Inverse),
            2 => Ok(Decay::InverseSquare),
            3 => Ok(Decay::InverseCube),
            _ => Err(Error::DecayOutOfRange),
        }
    }

    /// The exponent `k` (0 to 3).
    pub fn k(self) -> u32 {
        match self {
            Decay::Constant => 0,
            Decay::Inverse => 1,
            Decay::InverseSquare => 2,
            Decay::InverseCube => 3,
        }
    }
}

impl TryFrom<u32> for Decay {
    type Error = Error;
    fn try_from(k: u32) -> Result<Self, Error> {
        Decay::new(k)
    }
}

/// A linear light: the segment from `a` to `b` (a fluorescent tube), unit intensity per unit
/// parameter (Picott's `I_p k_d = 1`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineLight<T> {
    a: Vec3<T>,
    b: Vec3<T>,
    /// Unit direction of `b - a`.
    e: Vec3<T>,
}

/// `ln(1 + x)` for `x > -1`, accurate for small `x` (Goldberg's trick: the rounding of `1 + x`
/// cancels between the logarithm and the division).
#[inline]
fn ln_1p<T: Real>(x: T) -> T {
    let u = T::ONE + x;
    if u == T::ONE {
        x
    } else if !u.is_finite() {
        x.ln()
    } else {
        u.ln() * (x / (u - T::ONE))
    }
}

/// `asinh(x)` for `x >= 0`, accurate for small and huge `x`.
#[inline]
fn asinh_pos<T: Real>(x: T) -> T {
    let x2 = x * x;
    // ln(2x) is exact to rounding once 1/(4 x^2) < epsilon (also when x^2 overflows).
    if x2 * T::EPSILON > T::from_f64(0.25) {
        x.ln() + T::from_f64(core::f64::consts::LN_2)
    } else {
        ln_1p(x + x2 / (T::ONE + (T::ONE + x2).sqrt()))
    }
}

/// `sqrt(x^2 + y^2)` without underflow for tiny arguments (the callers' arguments are at most
/// a few units, so nothing overflows).
#[inline]
fn hypot<T: Real>(x: T, y: T) -> T {
    let (x, y) = (x.abs(), y.abs());
    let big = x.max(y);
    if big > T::TINY {
        (x * x + y * y).sqrt()
    } else if big > T::ZERO {
        let (sx, sy) = (x / big, y / big);
        big * (sx * sx + sy * sy).sqrt()
    } else {
        T::ZERO
    }
}

/// `ln(r1/r0)` given `ds = r1^2 - r0^2` computed without cancellation.
#[inline]
fn ln_ratio<T: Real>(r0: T, r1: T, ds: T) -> T {
    if r1 <= T::TWO * r0 && r0 <= T::TWO * r1 {
        T::HALF * ln_1p(ds / (r0 * r0))
    } else {
        (r1 / r0).ln()
    }
}

/// `1/((2n + 2)(2n + 3))` for n = 1, 2, ...: the ratios of the series of `(y - sin y)/y^3`.
const Y_RATIOS: [f64; 16] = [
    1.0 / 20.0,
    1.0 / 42.0,
    1.0 / 72.0,
    1.0 / 110.0,
    1.0 / 156.0,
    1.0 / 210.0,
    1.0 / 272.0,
    1.0 / 342.0,
    1.0 / 420.0,
    1.0 / 506.0,
    1.0 / 600.0,
    1.0 / 702.0,
    1.0 / 812.0,
    1.0 / 930.0,
    1.0 / 1056.0,
    1.0 / 1190.0,
];

/// `(y - sin y)/y^3 = 1/3! - y^2/5! + y^4/7! - ...` for `0 <= y <= pi` (at most 16 terms: the
/// 16th is below 1e-20 at `y = pi`; f32 stops after about 8).
#[inline]
fn y_minus_sin_over_cube<T: Real>(y: T) -> T {
    let y2 = y * y;
    let mut term = T::from_f64(1.0 / 6.0);
    let mut sum = term;
    for &q in &Y_RATIOS {
        term = -(term * y2 * T::from_f64(q));
        sum += term;
        if !(term.abs() > T::EPSILON * sum) {
            break;
        }
    }
    sum
}

/// `theta = atan2(h du, x)` and `theta/h` for `x = h^2 + s0 s1 > 0` (one side of the foot),
/// `theta/h` without dividing by `h` when `theta` is small (so `h = 0` is regular).
#[inline]
fn theta_and_over_h<T: Real>(h: T, du: T, x: T) -> (T, T) {
    let y = h * du;
    let z = y / x;
    if z < T::from_f64(1e-3) {
        let z2 = z * z;
        // atan(z)/z = 1 - z^2/3 + z^4/5 - ...: the next term is below 2e-19 here.
        let toh = (du / x) * (T::ONE - z2 * (T::from_f64(1.0 / 3.0) - z2 * T::from_f64(0.2)));
        (h * toh, toh)
    } else {
        let th = y.atan2(x);
        (th, th / h)
    }
}

/// A vector divided by `sigma` (by its reciprocal `inv` when that is finite).
#[inline]
fn shrink<T: Real>(v: Vec3<T>, sigma: T, inv: T) -> Vec3<T> {
    if inv.is_finite() {
        v * inv
    } else {
        Vec3::new(v.x / sigma, v.y / sigma, v.z / sigma)
    }
}

/// A unit vector along any non-zero finite `v` (however small or large), or `None`.
#[inline]
fn unit<T: Real>(v: Vec3<T>) -> Option<Vec3<T>> {
    let m = v.max_abs();
    if !(m > T::ZERO) || !m.is_finite() {
        return None;
    }
    let s = Vec3::new(v.x / m, v.y / m, v.z / m);
    Some(s * (T::ONE / s.length()))
}

/// The segment seen from `p`, in working units: lengths divided by `sigma`, the largest
/// component of `a - p` and `b - p` (so every length below is at most `2 sqrt 3`).
#[derive(Clone, Copy, Debug)]
struct SegmentView<T> {
    /// `(a - p)/sigma`, `(b - p)/sigma`.
    l0: Vec3<T>,
    l1: Vec3<T>,
    /// `s0 = l0.e`, `s1 = l1.e`: signed positions along the line from the foot of `p`.
    s0: T,
    s1: T,
    /// `g = l0 x e`: normal to the plane through `p` and the line, `|g| = h`.
    g: Vec3<T>,
    /// Perpendicular distance from `p` to the line.
    h: T,
    /// `|b - a|/sigma`.
    len: T,
    /// `1/sigma` in the caller's units (may be +inf for a subnormal `sigma`).
    inv_sigma: T,
}

impl<T: Real> LineLight<T> {
    /// The segment from `a` to `b`.
    ///
    /// Cost: 1 normalization, once.
    ///
    /// # Errors
    /// [`Error::NotFinite`] for `a` or `b`; [`Error::ZeroLength`] (`"segment"`) when `a == b`.
    pub fn new(a: Vec3<T>, b: Vec3<T>) -> Result<Self, Error> {
        if !a.is_finite() {
            return Err(Error::NotFinite("a"));
        }
        if !b.is_finite() {
            return Err(Error::NotFinite("b"));
        }
        let d = b - a;
        let d = if d.is_finite() {
            d
        } else {
            b * T::HALF - a * T::HALF
        };
        let e = unit(d).ok_or(Error::ZeroLength("segment"))?;
        Ok(LineLight { a, b, e })
    }

    /// The start point `a`.
    pub fn a(&self) -> Vec3<T> {
        self.a
    }
    /// The end point `b`.
    pub fn b(&self) -> Vec3<T> {
        self.b
    }
    /// The unit direction from `a` to `b`.
    pub fn direction(&self) -> Vec3<T> {
        self.e
    }

    /// The segment seen from `p` (see [`SegmentView`]).
    ///
    /// # Errors
    /// [`Error::NotFinite`] for `p`; [`Error::PointOnSegment`] when `p` is within
    /// `T::TINY sigma` of the segment (on it, to the precision of `T`).
    #[inline]
    fn view(&self, p: Vec3<T>) -> Result<SegmentView<T>, Error> {
        if !p.is_finite() {
            return Err(Error::NotFinite("p"));
        }
        let (a, b) = (self.a, self.b);
        let (mut l0, mut l1, mut d) = (a - p, b - p, b - a);
        // Caller units per working unit before the division by sigma.
        let mut unit_scale = T::ONE;
        if !(l0.is_finite() && l1.is_finite() && d.is_finite()) {
            // Coordinates near the overflow threshold: halve them first (exact).
            l0 = a * T::HALF - p * T::HALF;
            l1 = b * T::HALF - p * T::HALF;
            d = b * T::HALF - a * T::HALF;
            unit_scale = T::TWO;
        }
        let sigma = l0.max_abs().max(l1.max_abs());
        if !(sigma > T::ZERO) {
            return Err(Error::PointOnSegment);
        }
        let inv = T::ONE / sigma;
        let (l0, l1) = (shrink(l0, sigma, inv), shrink(l1, sigma, inv));
        let len = shrink(d, sigma, inv).dot(self.e).max(T::ZERO);
        let e = self.e;
        let (s0, s1) = (l0.dot(e), l1.dot(e));
        let g = l0.cross(e);
        let h = g.length();
        // Distance from p to the segment (not the line).
        let dist = if s0.min(s1) <= T::ZERO && s0.max(s1) >= T::ZERO {
            h
        } else {
            hypot(h, s0).min(hypot(h, s1))
        };
        if !(dist > T::TINY) {
            return Err(Error::PointOnSegment);
        }
        Ok(SegmentView {
            l0,
            l1,
            s0,
            s1,
            g,
            h,
            len,
            inv_sigma: inv / unit_scale,
        })
    }

    /// `[line_lambert]` with precise errors: see [`LineLight::lambert`].
    ///
    /// # Errors
    /// [`Error::NotFinite`] for `p` or `n`, [`Error::ZeroLength`] for `n`,
    /// [`Error::PointOnSegment`], and [`Error::Overflow`] when the value is too large for `T`
    /// (`p` extremely close to the segment for `k >= 1`, relative to the segment's size, or a
    /// tiny light in absolute units with a large `k`).
    pub fn try_lambert(&self, p: Vec3<T>, n: impl Direction<T>, k: Decay) -> Result<T, Error> {
        let v = self.view(p)?;
        let n = n.try_unit("n")?.into_inner();
        let (lam0, lam1) = (v.l0.dot(n), v.l1.dot(n));
        if !(lam0 > T::ZERO) && !(lam1 > T::ZERO) {
            return Ok(T::ZERO);
        }
        let k = k.k();
        let value = if !(v.len > T::TINY) {
            // A segment far shorter than its distance (below the precision of T): the point
            // light at a (relative error below len/dist < T::TINY).
            let r = v.l0.length();
            lam0.max(T::ZERO) / r.powu(k + 1)
        } else {
            let e = self.e;
            let beta = e.dot(n);
            let alpha = v.g.dot(n.cross(e)).clamp(-v.h, v.h);
            // Clip to L.n > 0: the interval [u0, u1] of length du.
            let (s0, s1, len) = (v.s0, v.s1, v.len);
            let (u0, u1, du) = if lam0 > T::ZERO && lam1 > T::ZERO {
                (s0, s1, len)
            } else {
                // Keep [s0, s*] (lam0 > 0) or [s*, s1]: the fractions of the segment before
                // and after the crossing, from endpoint values of opposite signs.
                let keep_start = lam0 > T::ZERO;
                let den = (lam0 - lam1).abs();
                let (f0, f1) = ((lam0.abs() / den).clamp01(), (lam1.abs() / den).clamp01());
                let du = len * if keep_start { f0 } else { f1 };
                // The crossing from the nearer end (in t)...
                let (lo, hi) = (s0.min(s1), s0.max(s1));
                let (cut, reference) = if f0 <= f1 {
                    ((s0 + len * f0).clamp(lo, hi), s0)
                } else {
                    ((s1 - len * f1).clamp(lo, hi), s1)
                };
                // ...unless it is much nearer the foot than that end, where the sum above
                // cancels: then from the foot, s* = -alpha/beta (alpha is accurate to the
                // precision of h there, the sum only to that of the end).
                let from_foot = -alpha / beta;
                let near_foot = cut.abs() < T::HALF * reference.abs() && from_foot.is_finite();
                if near_foot {
                    let cut = from_foot.clamp(lo, hi);
                    if keep_start {
                        (s0, cut, cut - s0)
                    } else {
                        (cut, s1, s1 - cut)
                    }
                } else if keep_start {
                    (s0, cut, du)
                } else {
                    (cut, s1, du)
                }
            };
            // Reflect s -> -s so that the interval is not wholly below the foot.
            let (u0, u1, beta) = if u1 <= T::ZERO {
                (-u1, -u0, -beta)
            } else {
                (u0, u1, beta)
            };
            let m = if u0 >= T::ZERO {
                one_side(k, alpha, beta, v.h, u0, u1, du)
            } else {
                across_foot(k, alpha, beta, v.h, u0, u1, du)
            };
            m / len
        };
        let mut out = value;
        for _ in 0..k {
            out *= v.inv_sigma;
        }
        if !out.is_finite() {
            return Err(Error::Overflow);
        }
        Ok(out.max(T::ZERO))
    }

    /// `[line_lambert]`: Picott's Lambertian integral of the segment at `p` with normal `n`
    /// (any length) and decay `k`, the part of the segment below the tangent plane clipped
    /// away; not normalized (see the module docs).
    ///
    /// Accuracy (relative to `max(1, |I|)`; module docs): f64 within 1.0e-13 of the quadrature
    /// of the definition where f64 resolves the geometry; f32 within 3.4e-7 of f64 and Fast32
    /// within 2e-5 where the value is well conditioned. Cost: 3 cross products, ~10 dot
    /// products, 1 normalization, 4-6 divisions, 3-5 sqrt, then k = 0: 1 `ln` (2 across the
    /// foot); k = 1: 1 `atan2` and 1 `ln`; k = 2: no transcendental; k = 3: 1 `atan2` and up to
    /// 16 (f64) or 8 (f32) series terms on one side of the foot. Fallback: 0 for a non-finite
    /// or zero input, a point on the segment, or a value that overflows `T`.
    ///
    /// <!-- BEGIN acc-line_lambert: target/accuracy/model-line_lambert.md -->
    /// Measured: f64 within 3.9e-10 of its reference (close, horizon near the foot); against f64,
    /// f32 2.9e-7 (capped: 8.1e-7; ill-conditioned: 4.6e-5; near boundary: 1.2e-3; unresolved:
    /// 3.0e-1), Fast32 1.8e-5 (capped: 1.4e-4; ill-conditioned: 4.6e-5; near boundary: 1.0e-3;
    /// unresolved: 3.0e-1); 7 424 cases in all (`docs/accuracy.md`).
    /// <!-- END acc-line_lambert -->
    #[inline]
    pub fn lambert(&self, p: Vec3<T>, n: impl Direction<T>, k: Decay) -> T {
        self.try_lambert(p, n, k).unwrap_or(T::ZERO)
    }
}

/// `alpha F0 + beta F1` over `[s0, s1]`, `0 <= s0 < s1`, length `du` (module docs, "one side").
#[inline]
fn one_side<T: Real>(k: u32, alpha: T, beta: T, h: T, s0: T, s1: T, du: T) -> T {
    let (r0, r1) = (hypot(h, s0), hypot(h, s1));
    let ds = du * (s0 + s1); // rho1^2 - rho0^2
    let drho = ds / (r0 + r1);
    let pr = r0 * r1;
    match k {
        0 => alpha * ln_1p((du + drho) / (s0 + r0)) + beta * drho,
        1 => {
            let (_, toh) = theta_and_over_h(h, du, h * h + s0 * s1);
            alpha * toh + beta * ln_ratio(r0, r1, ds)
        }
        2 => alpha * (ds / (s1 * r0 + s0 * r1)) / pr + beta * (drho / pr),
        _ => {
            let (th, toh) = theta_and_over_h(h, du, h * h + s0 * s1);
            let f0 = (du / pr) / pr + T::TWO * toh * toh * toh * y_minus_sin_over_cube(th + th);
            alpha * f0 + beta * (ds / pr) / (T::TWO * pr)
        }
    }
}

/// `alpha F0 + beta F1` over `[s0, s1]`, `s0 < 0 < s1`, `h > 0` (module docs, "across the foot").
#[inline]
fn across_foot<T: Real>(k: u32, alpha: T, beta: T, h: T, s0: T, s1: T, du: T) -> T {
    let (r0, r1) = (hypot(h, s0), hypot(h, s1));
    let ds = du * (s0 + s1);
    let drho = ds / (r0 + r1);
    let pr = r0 * r1;
    let c = alpha / h;
    match k {
        0 => alpha * (asinh_pos(s1 / h) + asinh_pos(-s0 / h)) + beta * drho,
        1 => c * (h * du).atan2(h * h + s0 * s1) + beta * ln_ratio(r0, r1, ds),
        2 => (c / h) * (s1 / r1 - s0 / r0) + beta * (drho / pr),
        _ => {
            let th = (h * du).atan2(h * h + s0 * s1);
            let f = th + h * (s1 / r1 / r1 - s0 / r0 / r0);
            (c / h) / h * T::HALF * f + beta * (ds / pr) / (T::TWO * pr)
        }
    }
}

#[cfg(test)]
mod tests;
