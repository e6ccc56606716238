//! Independent numerical quadrature of the defining integrals of `shared/spec/models.md`.
//!
//! Plain `std` f64; it never calls the library and never uses a closed form of a model. Every
//! value is a numerical integral over the sphere of directions `u`, to about 1e-13 absolute (in
//! the normalized units of each model), so the f64 library can be checked to 1e-9.
//!
//! ## Building blocks
//!
//! - [`integrate`]: adaptive Gauss-Legendre (order 16 by default) on an interval: a panel is
//!   accepted when the rule on the whole panel and on its two halves agree to the panel's share
//!   of the tolerance, else both halves are refined (depth capped).
//! - [`integrate_smooth_ends`]: the same after the substitution `x = a + (b - a)(3s^2 - 2s^3)`,
//!   whose Jacobian `6 s (1 - s)` vanishes at both ends: a `sqrt(x - a)` or `sqrt(b - x)`
//!   endpoint behaviour becomes analytic in `s`, so the rule converges exponentially again.
//! - [`two_cap_integral`]: the integral of any `f(u)` over the intersection of two spherical
//!   caps `{angle(u, c) <= theta_max}` and `{angle(u, d) <= rho}`, in polar coordinates
//!   `(theta, phi)` about `c`. For each `theta` the second cap cuts the circle of radius `theta`
//!   about `c` in one arc `|phi| <= phi_1(theta)`, found analytically (spherical law of cosines,
//!   in a cancellation-free product form), so the inner `phi` integrand is smooth on its
//!   interval. `phi_1` has square-root behaviour where the arc appears, vanishes or closes, at
//!   `theta = |w - rho|`, `w + rho`, `2 pi - w - rho` (`w` the angle between `c` and `d`): the
//!   `theta` range is split there and each piece integrated with [`integrate_smooth_ends`].
//!
//! A Lambert or Phong integral over a cap source is then the cap `{u.k >= 0}` (radius pi/2 about
//! the weight axis `k = n` or `r`) intersected with the source cap: in coordinates about `k`
//! the kink of `(u.k)+` is the coordinate line `theta = pi/2`, so no integrand has a kink inside
//! the domain, and the Phong lobe `(u.k)^m` depends on `theta` only (its peak, of width about
//! `1/sqrt(m)`, is resolved by the adaptive rule). The same integral in coordinates about the
//! source axis ([`Frame::AboutSource`]) is an independent second evaluation used by the
//! quadrature's self-check (`tests/quadrature.rs`).
//!
//! ## Polygons
//!
//! Two independent methods; the tests use the first, the quadrature's self-check
//! (`tests/quadrature.rs`) compares them.
//!
//! [`polygon_by_circles`] (used for `[polygon_lambert]` and `[phong_polygon]`) works in polar
//! coordinates `(theta, phi)` about the weight axis `k` (`n` or `r`), like the caps: the weight
//! `(u.k)^m` depends on `theta` only, the clipping to `u.k >= 0` is the range `theta <= pi/2`,
//! and for each `theta` the circle of radius `theta` about `k` is cut by the great circles of
//! the polygon's edges (crossings in closed form); each arc between crossings is inside or
//! outside the projection (tested at its midpoint by casting the ray onto the plane: works for
//! non-convex polygons), so the `phi` integral is the inside arc length, exact. The `theta`
//! integrand is analytic between the `theta` of the vertices (kinks) and the tangency angles of
//! the edges' great circles (square-root behaviour); the range is split there and each piece
//! integrated with [`integrate_smooth_ends`]. The lobe peak is at `theta = 0`, an end point.
//!
//! [`polygon_integral`] (the fan method) first clips the planar polygon exactly to the
//! half-space `(x - p).k >= 0` (Sutherland-Hodgman against one plane; for a non-convex polygon
//! the result may contain zero-width bridges along the clip line, which do not change the
//! winding number of any point off that line). The integral over the clipped region is then the
//! signed sum, over its edges `(a, b)`, of the integrals over the fan triangles `(q, a, b)`, `q`
//! the foot of `p` on the plane (exact for any closed chain by the winding-number identity,
//! convex or not). A fan triangle is integrated in spherical coordinates about the plane's
//! normal `nu` (from `p` toward the plane): `u = cos(alpha) nu + sin(alpha) e(psi)`, `psi` the
//! azimuth about `q` swept by the edge, and `alpha` from 0 to
//! `atan2(d / cos(psi - psi_perp), h)`, `h` the height of `p` above the plane, `d` the distance
//! from `q` to the edge's line and `psi_perp` its azimuth. The integrand there is the smooth
//! polynomial `(u.k)^m` (no `max(0, .)`: the parts of the fan triangles outside the clipped
//! region cancel exactly), so both levels are plain adaptive Gauss-Legendre; both are split
//! where the lobe `(u.k)^m` peaks (at `+-k`, width about `1/sqrt(m)`), and `psi` also at
//! `psi_perp` and, when `d < h`, where `alpha` reaches pi/4 (the edge of a thin layer at the
//! ends of a long edge). It is slower and less robust for p within about 1e-6 of the plane
//! (where features narrower than any rule's node spacing appear), which is why the circles
//! method is the reference.
//!
//! ## A caveat on adaptive rules
//!
//! An adaptive rule accepts a panel when two estimates agree; if every node of both misses a
//! narrow peak with fast-decaying tails, it accepts a wrong value. Refinement-level comparisons
//! cannot detect that, so every method here puts the peaks and kinks it knows of at panel
//! ends, and the self-check compares independent methods and partitions of the sphere whose
//! totals are known (caps tiling the sphere, the six faces of a cube around p).

#![allow(dead_code)]

use std::f64::consts::{FRAC_PI_2, PI, TAU};
use std::sync::OnceLock;

mod polygons;
pub use polygons::*;

/// A 3-vector in f64.
pub type V3 = [f64; 3];

pub fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
pub fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}
pub fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}
/// Unit vector (scaled first, so tiny and huge inputs are fine). Panics on zero.
pub fn normalize(a: V3) -> V3 {
    let m = a[0].abs().max(a[1].abs()).max(a[2].abs());
    assert!(m > 0.0 && m.is_finite(), "normalize of {a:?}");
    let s = scale(a, 1.0 / m);
    scale(s, 1.0 / norm(s))
}
/// A unit vector perpendicular to the unit vector `a`.
pub fn any_perp(a: V3) -> V3 {
    let t = if a[0].abs() < 0.57 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    normalize(cross(a, t))
}
/// Angle between two unit vectors, accurate everywhere in [0, pi].
pub fn angle(a: V3, b: V3) -> f64 {
    norm(cross(a, b)).atan2(dot(a, b))
}

// ---------------------------------------------------------------------------------------------
// One-dimensional rules
// ---------------------------------------------------------------------------------------------

/// Accuracy settings. [`Quad::STD`] is what the tests use; [`Quad::FINE`] is a second,
/// independent refinement level (higher order, tighter tolerance) for convergence checks.
#[derive(Clone, Copy, Debug)]
pub struct Quad {
    /// Gauss-Legendre order per panel (16, 24 or 32).
    pub order: usize,
    /// Absolute tolerance, in the normalized units of the model.
    pub tol: f64,
    /// Maximum bisection depth.
    pub max_depth: u32,
    /// Relative rounding floor: a panel is accepted once its two estimates agree to this
    /// fraction of its absolute value (the integrands carry relative rounding noise of up to
    /// ~m ULPs, a power `(u.k)^m` of a rounded dot product, so 4e-14 is the floor; the results
    /// stay within about that relative error of the exact integral).
    pub rel_floor: f64,
}

impl Quad {
    /// The same rule with a 5x looser rounding floor, for an outer integral whose integrand is
    /// itself an inner integral (with errors of up to the inner floor).
    pub fn outer(&self) -> Quad {
        Quad {
            rel_floor: 5.0 * self.rel_floor,
            ..*self
        }
    }
}

impl Quad {
    pub const STD: Quad = Quad {
        order: 16,
        tol: 1e-14,
        max_depth: 30,
        rel_floor: 4e-14,
    };
    pub const FINE: Quad = Quad {
        order: 24,
        tol: 1e-15,
        max_depth: 34,
        rel_floor: 4e-14,
    };
    /// A cheap level (for coarse/fine convergence demonstrations only).
    pub const COARSE: Quad = Quad {
        order: 8,
        tol: 1e-9,
        max_depth: 30,
        rel_floor: 4e-14,
    };
}

/// Gauss-Legendre nodes and weights on [-1, 1] by Newton's method on the three-term recurrence.
fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut xs = vec![0.0; n];
    let mut ws = vec![0.0; n];
    for i in 0..n.div_ceil(2) {
        let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 0.0;
        for iter in 0..100 {
            let (mut p0, mut p1) = (1.0f64, x);
            for k in 2..=n {
                let kf = k as f64;
                let p2 = ((2.0 * kf - 1.0) * x * p1 - (kf - 1.0) * p0) / kf;
                p0 = p1;
                p1 = p2;
            }
            dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
            let dx = p1 / dp;
            x -= dx;
            if dx.abs() < 1e-17 && iter > 2 {
                break;
            }
        }
        let w = 2.0 / ((1.0 - x * x) * dp * dp);
        xs[i] = -x;
        xs[n - 1 - i] = x;
        ws[i] = w;
        ws[n - 1 - i] = w;
    }
    (xs, ws)
}

struct Rule {
    x: Vec<f64>,
    w: Vec<f64>,
}

fn rule(n: usize) -> &'static Rule {
    static R8: OnceLock<Rule> = OnceLock::new();
    static R16: OnceLock<Rule> = OnceLock::new();
    static R24: OnceLock<Rule> = OnceLock::new();
    static R32: OnceLock<Rule> = OnceLock::new();
    let cell = match n {
        8 => &R8,
        16 => &R16,
        24 => &R24,
        32 => &R32,
        _ => panic!("unsupported Gauss-Legendre order {n}"),
    };
    cell.get_or_init(|| {
        let (x, w) = gauss_legendre(n);
        Rule { x, w }
    })
}

#[inline]
fn panel<F: FnMut(f64) -> f64>(f: &mut F, a: f64, b: f64, r: &Rule) -> f64 {
    let c = 0.5 * (a + b);
    let h = 0.5 * (b - a);
    let mut s = 0.0;
    for (x, w) in r.x.iter().zip(&r.w) {
        s += w * f(c + h * x);
    }
    s * h
}

fn adapt<F: FnMut(f64) -> f64>(
    f: &mut F,
    a: f64,
    b: f64,
    whole: f64,
    tol: f64,
    depth: u32,
    r: &Rule,
    q: &Quad,
) -> f64 {
    let m = 0.5 * (a + b);
    let left = panel(f, a, m, r);
    let right = panel(f, m, b, r);
    let both = left + right;
    // Accept at the tolerance or at the rounding level of the panel, whichever is larger.
    let noise = q.rel_floor * (left.abs() + right.abs());
    if (both - whole).abs() <= tol.max(noise) || depth >= q.max_depth || !(m > a && m < b) {
        return both;
    }
    let t = (0.5 * tol).max(1e-19);
    adapt(f, a, m, left, t, depth + 1, r, q) + adapt(f, m, b, right, t, depth + 1, r, q)
}

/// Adaptive Gauss-Legendre integral of `f` over [a, b] to absolute tolerance `tol`.
pub fn integrate<F: FnMut(f64) -> f64>(mut f: F, a: f64, b: f64, tol: f64, q: &Quad) -> f64 {
    if !(b > a) {
        return 0.0;
    }
    let r = rule(q.order);
    let whole = panel(&mut f, a, b, r);
    adapt(&mut f, a, b, whole, tol, 0, r, q)
}

/// [`integrate`] after the substitution `x = a + (b - a)(3 s^2 - 2 s^3)`, which makes square-root
/// endpoint behaviour (at either end) analytic.
pub fn integrate_smooth_ends<F: FnMut(f64) -> f64>(
    mut f: F,
    a: f64,
    b: f64,
    tol: f64,
    q: &Quad,
) -> f64 {
    if !(b > a) {
        return 0.0;
    }
    let len = b - a;
    integrate(
        |s| {
            let t = s * s * (3.0 - 2.0 * s);
            let j = 6.0 * s * (1.0 - s);
            if j == 0.0 {
                0.0
            } else {
                f(a + len * t) * len * j
            }
        },
        0.0,
        1.0,
        tol,
        q,
    )
}

// ---------------------------------------------------------------------------------------------
// Caps
// ---------------------------------------------------------------------------------------------

/// Half-width `phi_1` of the arc of the circle of angular radius `theta` about `c` that lies in
/// the cap of angular radius `rho` about `d`, with `w` = angle(c, d): the arc is
/// `|phi| <= phi_1` with `phi = 0` toward `d`. Returns 0 (no arc) or pi (whole circle) too.
///
/// On the circle, `cos(angle(u, d)) = cos(theta) cos(w) + sin(theta) sin(w) cos(phi)`, so the arc
/// is `cos(phi) >= t`, `t = (cos rho - cos theta cos w)/(sin theta sin w)`, and
/// `tan^2(phi_1/2) = (1 - t)/(1 + t) = (cos(theta - w) - cos rho)/(cos rho - cos(theta + w))`,
/// both differences written as products of sines (no cancellation, no division by
/// `sin theta sin w`).
pub fn arc_half_width(theta: f64, w: f64, rho: f64) -> f64 {
    let n_plus = 2.0 * (0.5 * (theta + w + rho)).sin() * (0.5 * (theta + w - rho)).sin();
    let n_minus = 2.0 * (0.5 * (rho + theta - w)).sin() * (0.5 * (rho - theta + w)).sin();
    if n_plus <= 0.0 {
        PI
    } else if n_minus <= 0.0 {
        0.0
    } else {
        2.0 * n_minus.sqrt().atan2(n_plus.sqrt())
    }
}

/// Integral of `f(u)` over `{angle(u, c) <= theta_max} ∩ {angle(u, d) <= rho}` (`c`, `d` any
/// length; `theta_max`, `rho` in [0, pi]), in polar coordinates about `c` (see the module docs).
pub fn two_cap_integral<F: Fn(V3) -> f64>(
    c: V3,
    theta_max: f64,
    d: V3,
    rho: f64,
    f: F,
    tol: f64,
    q: &Quad,
) -> f64 {
    two_cap_integral_cuts(c, theta_max, d, rho, f, tol, q, &[])
}

/// The panel ends a sharp lobe `(cos theta)^m` about the polar axis needs: `theta = j/sqrt(m)`
/// for `j` in {1/4, 1/2, 1, 2, 4, 8, 16} (the lobe's half-width is about `1/sqrt(m)`), so every
/// panel near the peak is narrower than the lobe whatever the adaptive rule's first estimate.
/// Empty for `m < 16`.
pub fn lobe_cuts(m: u32) -> Vec<f64> {
    if m < 16 {
        return Vec::new();
    }
    let w = 1.0 / (m as f64).sqrt();
    [0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0]
        .iter()
        .map(|j| j * w)
        .filter(|&t| t < FRAC_PI_2)
        .collect()
}

/// [`two_cap_integral`] with extra panel ends `extra` (angles from `c`) in the `theta` range.
pub fn two_cap_integral_cuts<F: Fn(V3) -> f64>(
    c: V3,
    theta_max: f64,
    d: V3,
    rho: f64,
    f: F,
    tol: f64,
    q: &Quad,
    extra: &[f64],
) -> f64 {
    let c = normalize(c);
    let d = normalize(d);
    let w = angle(c, d);
    let perp = cross(cross(c, d), c);
    let e1 = if norm(perp) > 1e-300 {
        normalize(perp)
    } else {
        any_perp(c)
    };
    let e2 = cross(c, e1);
    let theta_max = theta_max.min(PI);
    if !(theta_max > 0.0) || !(rho > 0.0) {
        return 0.0;
    }
    let mut cuts = vec![0.0, theta_max];
    for &b in [(w - rho).abs(), w + rho, TAU - w - rho]
        .iter()
        .chain(extra)
    {
        if b > 1e-15 && b < theta_max - 1e-15 {
            cuts.push(b);
        }
    }
    cuts.sort_by(|a, b| a.partial_cmp(b).unwrap());
    cuts.dedup();
    let npieces = (cuts.len() - 1) as f64;
    let inner_tol = tol / (TAU * npieces);
    let outer = |theta: f64| {
        let half = arc_half_width(theta, w, rho);
        if half == 0.0 {
            return 0.0;
        }
        let (st, ct) = theta.sin_cos();
        let axial = scale(c, ct);
        let inner = integrate(
            |phi: f64| {
                let (sp, cp) = phi.sin_cos();
                let u = add(axial, scale(add(scale(e1, cp), scale(e2, sp)), st));
                f(u)
            },
            -half,
            half,
            inner_tol,
            q,
        );
        inner * st
    };
    let mut total = 0.0;
    for win in cuts.windows(2) {
        total += integrate_smooth_ends(outer, win[0], win[1], tol / npieces, &q.outer());
    }
    total
}

/// Radiance of a cap-shaped source as a function of `u.axis` (`axis` the source axis).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Radiance {
    /// 1.
    Const,
    /// `(u.axis)+` (the cosine-weighted hemisphere).
    Cos,
    /// `(1 + 2 u.axis)/3` (the CIE overcast sky, per unit zenith luminance).
    Overcast,
}

impl Radiance {
    fn eval(self, ua: f64) -> f64 {
        match self {
            Radiance::Const => 1.0,
            Radiance::Cos => ua.max(0.0),
            Radiance::Overcast => (1.0 + 2.0 * ua) / 3.0,
        }
    }
}

/// Which polar frame [`cap_weighted`] integrates in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Frame {
    /// About the weight axis `k` (the default: the kink of `(u.k)+` is a coordinate line).
    AboutWeight,
    /// About the source axis (an independent second evaluation for self-checks).
    AboutSource,
}

/// `integral over {u.axis >= cos sigma} of L(u.axis) ((u.k)+)^m du` (raw, not normalized).
/// `tol` is absolute in the raw units.
pub fn cap_weighted(
    axis: V3,
    sigma: f64,
    rad: Radiance,
    k: V3,
    m: u32,
    frame: Frame,
    tol: f64,
    q: &Quad,
) -> f64 {
    let a = normalize(axis);
    let k = normalize(k);
    let f = |u: V3| {
        let uk = dot(u, k).max(0.0);
        rad.eval(dot(u, a)) * uk.powi(m as i32)
    };
    match frame {
        Frame::AboutWeight => two_cap_integral(k, FRAC_PI_2, a, sigma, f, tol, q),
        Frame::AboutSource => two_cap_integral(a, sigma, k, FRAC_PI_2, f, tol, q),
    }
}

/// [`cap_weighted`] about the weight axis with the panel ends of [`lobe_cuts`] added: the
/// reference for sharp lobes (m up to 1001, `tests/large_exponents.rs`).
pub fn cap_weighted_sharp(
    axis: V3,
    sigma: f64,
    rad: Radiance,
    k: V3,
    m: u32,
    tol: f64,
    q: &Quad,
) -> f64 {
    let a = normalize(axis);
    let k = normalize(k);
    let f = |u: V3| {
        let uk = dot(u, k).max(0.0);
        rad.eval(dot(u, a)) * uk.powi(m as i32)
    };
    two_cap_integral_cuts(k, FRAC_PI_2, a, sigma, f, tol, q, &lobe_cuts(m))
}

/// [`phong_cap_source`] with the lobe's panel ends ([`cap_weighted_sharp`]); `sigma` may
/// exceed pi/2 (up to pi) for self-checks.
pub fn phong_cap_source_sharp(axis: V3, sigma: f64, rad: Radiance, r: V3, m: u32, q: &Quad) -> f64 {
    let norm = (m as f64 + 1.0) / TAU;
    cap_weighted_sharp(axis, sigma, rad, r, m, q.tol / norm, q) * norm
}

/// Lambert, normalized: `(1/pi) integral L (n.u)+ du` over the cap source.
pub fn lambert_cap_source(axis: V3, sigma: f64, rad: Radiance, n: V3, q: &Quad) -> f64 {
    cap_weighted(axis, sigma, rad, n, 1, Frame::AboutWeight, q.tol * PI, q) / PI
}

/// Phong, normalized: `((m+1)/(2 pi)) integral L ((u.r)+)^m du` over the cap source.
pub fn phong_cap_source(axis: V3, sigma: f64, rad: Radiance, r: V3, m: u32, q: &Quad) -> f64 {
    let norm = (m as f64 + 1.0) / TAU;
    cap_weighted(axis, sigma, rad, r, m, Frame::AboutWeight, q.tol / norm, q) * norm
}

/// `[hemi_const]`.
pub fn hemi_const(axis: V3, n: V3, q: &Quad) -> f64 {
    lambert_cap_source(axis, FRAC_PI_2, Radiance::Const, n, q)
}
/// `[hemi_cos]`.
pub fn hemi_cos(axis: V3, n: V3, q: &Quad) -> f64 {
    lambert_cap_source(axis, FRAC_PI_2, Radiance::Cos, n, q)
}
/// `[sky_overcast]` with zenith luminance `c`.
pub fn sky_overcast(zenith: V3, c: f64, n: V3, q: &Quad) -> f64 {
    c * lambert_cap_source(zenith, FRAC_PI_2, Radiance::Overcast, n, q)
}
/// `[sky_ground]`: per channel, sky over the upper hemisphere of `up`, ground below.
pub fn sky_ground(up: V3, sky: V3, ground: V3, n: V3, q: &Quad) -> V3 {
    let e_sky = lambert_cap_source(up, FRAC_PI_2, Radiance::Const, n, q);
    let e_ground = lambert_cap_source(scale(up, -1.0), FRAC_PI_2, Radiance::Const, n, q);
    add(scale(sky, e_sky), scale(ground, e_ground))
}
/// `[cap_lambert]`.
pub fn cap_lambert(axis: V3, sigma: f64, n: V3, q: &Quad) -> f64 {
    lambert_cap_source(axis, sigma, Radiance::Const, n, q)
}
/// The cap a sphere subtends at `p`: `(axis, sigma)`.
pub fn sphere_cap(center: V3, radius: f64, p: V3) -> (V3, f64) {
    let d = sub(center, p);
    let dist = norm(d);
    assert!(dist > radius, "p inside the sphere");
    let sigma = radius.atan2(((dist - radius) * (dist + radius)).sqrt());
    (d, sigma)
}
/// `[sphere_lambert]`.
pub fn sphere_lambert(center: V3, radius: f64, p: V3, n: V3, q: &Quad) -> f64 {
    let (axis, sigma) = sphere_cap(center, radius, p);
    cap_lambert(axis, sigma, n, q)
}
/// `[phong_hemi_const]`.
pub fn phong_hemi_const(axis: V3, r: V3, m: u32, q: &Quad) -> f64 {
    phong_cap_source(axis, FRAC_PI_2, Radiance::Const, r, m, q)
}
/// `[phong_hemi_cos]`.
pub fn phong_hemi_cos(axis: V3, r: V3, m: u32, q: &Quad) -> f64 {
    phong_cap_source(axis, FRAC_PI_2, Radiance::Cos, r, m, q)
}
/// `[phong_cap]`.
pub fn phong_cap(axis: V3, sigma: f64, r: V3, m: u32, q: &Quad) -> f64 {
    phong_cap_source(axis, sigma, Radiance::Const, r, m, q)
}
/// `[phong_sphere]`.
pub fn phong_sphere(center: V3, radius: f64, p: V3, r: V3, m: u32, q: &Quad) -> f64 {
    let (axis, sigma) = sphere_cap(center, radius, p);
    phong_cap(axis, sigma, r, m, q)
}

// ---------------------------------------------------------------------------------------------
// Spherical harmonics
// ---------------------------------------------------------------------------------------------

/// The nine real SH basis functions of models.md (June eq. 20.21) with exact constants, in the
/// order L00, L1-1, L10, L11, L2-2, L2-1, L20, L21, L22.
pub fn sh_basis(u: V3) -> [f64; 9] {
    let (x, y, z) = (u[0], u[1], u[2]);
    let c00 = 0.5 / PI.sqrt();
    let c1 = (3.0 / (4.0 * PI)).sqrt();
    let c2 = 0.5 * (15.0 / PI).sqrt();
    let c20 = 0.25 * (5.0 / PI).sqrt();
    let c22 = 0.25 * (15.0 / PI).sqrt();
    [
        c00,
        c1 * y,
        c1 * z,
        c1 * x,
        c2 * x * y,
        c2 * y * z,
        c20 * (3.0 * z * z - 1.0),
        c2 * x * z,
        c22 * (x * x - y * y),
    ]
}

/// `[sh9_irradiance]` for one channel: `integral over the sphere of L(u) (n.u)+ du` with
/// `L(u) = sum coeffs[i] Y_i(u)` (not divided by pi), by quadrature over the hemisphere about n.
pub fn sh9_irradiance(coeffs: &[f64; 9], n: V3, q: &Quad) -> f64 {
    let n = normalize(n);
    let f = |u: V3| {
        let y = sh_basis(u);
        let l: f64 = (0..9).map(|i| coeffs[i] * y[i]).sum();
        l * dot(u, n).max(0.0)
    };
    let scale_c: f64 = coeffs.iter().map(|c| c.abs()).sum::<f64>().max(1.0);
    two_cap_integral(n, FRAC_PI_2, n, PI, f, q.tol * scale_c, q)
}

/// The nine SH coefficients of a unit-radiance disc (cap) of half-angle `alpha` about `axis`,
/// by quadrature of `integral over the cap of Y_i(u) du`.
pub fn sh9_project_disc(axis: V3, alpha: f64, q: &Quad) -> [f64; 9] {
    let mut out = [0.0; 9];
    for (i, o) in out.iter_mut().enumerate() {
        *o = two_cap_integral(axis, alpha, axis, PI, |u| sh_basis(u)[i], q.tol, q);
    }
    out
}

/// `[sh9_disc_irradiance]`: E(n) of the nine-term projection of the unit disc.
pub fn sh9_disc_irradiance(axis: V3, alpha: f64, n: V3, q: &Quad) -> f64 {
    let c = sh9_project_disc(axis, alpha, q);
    sh9_irradiance(&c, n, q)
}
