//! Independent quadrature of Arvo's moments (`[axial_moment]`, `[double_axis_moment]`, the
//! two-plane clipped models and `[lune_normalization]`): plain `std` f64, never calls the
//! library.
//!
//! The method is that of `polygon_by_circles` in `quadrature.rs`, extended: polar coordinates
//! `(theta, phi)` about the lobe axis `w`, so `(w.u)^m = cos^m(theta)` depends on `theta` only;
//! clipping to `u.w >= 0` is the range `theta <= pi/2` (otherwise `theta` runs to pi, the
//! signed integrand). For each `theta` the circle of radius `theta` about `w` is cut by the
//! great circles of the polygon's edges and, when the second clipping plane is on, by the
//! great circle of `v` (all crossings in closed form); each arc between crossings is inside or
//! outside the region (tested at its midpoint: ray cast onto the polygon's plane, and
//! `u.v >= 0`). The `phi` integral of the second factor `v.u` over an inside arc is exact:
//! `v.u = cos(theta) (v.w) + sin(theta) (v1 cos(phi) + v2 sin(phi))`. The `theta` integrand
//! is analytic between the vertices' `theta`, the tangency angles of the edges' and `v`'s
//! great circles (`beta` and `pi - beta`), where the range is split, each piece integrated with
//! `integrate_smooth_ends`. With no polygon (`verts = None`) the region is the whole sphere
//! (the lune when both planes clip).
#![allow(
    dead_code,
    clippy::too_many_arguments,
    clippy::type_complexity,
    clippy::neg_cmp_op_on_partial_ord
)]

use crate::common::quadrature::{
    add, angle, any_perp, cross, dot, integrate_smooth_ends, newell, norm, normalize,
    point_in_polygon, scale, sub, Arc, Quad, V3,
};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// `integral over R of (w.u)^m f2(u) du`, `R` the projection of `verts` from `p` (or the whole
/// sphere for `None`), intersected with `{u.w >= 0}` if `clip_w` and `{u.v >= 0}` if `clip_v`;
/// `f2(u) = v.u` if `second` else 1. `w`, `v` unit. `tol` absolute.
pub fn moment_by_circles(
    verts: Option<&[V3]>,
    p: V3,
    w: V3,
    v: V3,
    m: u32,
    second: bool,
    clip_w: bool,
    clip_v: bool,
    tol: f64,
    q: &Quad,
) -> f64 {
    let k = normalize(w);
    let v = normalize(v);
    let theta_max = if clip_w { FRAC_PI_2 } else { PI };
    let mut cuts = vec![0.0, theta_max];
    let mut arcs = Vec::new();
    // The polygon's plane frame, for the inside test.
    let mut plane: Option<(V3, f64, V3, V3, Vec<[f64; 2]>)> = None;
    if let Some(verts) = verts {
        let nn = normalize(newell(verts));
        let hs = verts.iter().map(|&x| dot(sub(x, p), nn)).sum::<f64>() / verts.len() as f64;
        if hs == 0.0 {
            return 0.0;
        }
        let (nu, h) = if hs > 0.0 {
            (nn, hs)
        } else {
            (scale(nn, -1.0), -hs)
        };
        let f1 = any_perp(nu);
        let f2 = cross(nu, f1);
        let poly2 = verts
            .iter()
            .map(|&x| {
                let d = sub(x, p);
                [dot(d, f1), dot(d, f2)]
            })
            .collect();
        plane = Some((nu, h, f1, f2, poly2));
        let nv = verts.len();
        for i in 0..nv {
            let ar = sub(verts[i], p);
            let br = sub(verts[(i + 1) % nv], p);
            let ev = sub(verts[(i + 1) % nv], verts[i]);
            let a = normalize(ar);
            cuts.push(angle(k, a));
            let gr = cross(ar, ev);
            if norm(gr) == 0.0 {
                continue;
            }
            let g = normalize(gr);
            let x = angle(a, normalize(br));
            let arc = Arc::new(a, g, x, k);
            cuts.push(arc.beta);
            cuts.push(PI - arc.beta);
            arcs.push(arc);
        }
    }
    if clip_v {
        let a = any_perp(v);
        let arc = Arc::new(a, v, TAU, k);
        cuts.push(arc.beta);
        cuts.push(PI - arc.beta);
        arcs.push(arc);
    }
    let (e1, e2) = {
        let e1 = any_perp(k);
        (e1, cross(k, e1))
    };
    let (vk, v1, v2) = (dot(v, k), dot(v, e1), dot(v, e2));
    let inside = |u: V3| {
        if clip_v && dot(u, v) < 0.0 {
            return false;
        }
        match &plane {
            None => true,
            Some((nu, h, f1, f2, poly2)) => {
                let un = dot(u, *nu);
                if !(un > 0.0) {
                    return false;
                }
                let t = h / un;
                point_in_polygon([t * dot(u, *f1), t * dot(u, *f2)], poly2)
            }
        }
    };
    let dir = |st: f64, ct: f64, phi: f64| {
        let (sp, cp) = phi.sin_cos();
        add(scale(k, ct), scale(add(scale(e1, cp), scale(e2, sp)), st))
    };
    // The phi integral of the second factor over [lo, hi] on the circle of radius theta.
    let piece = |st: f64, ct: f64, lo: f64, hi: f64| {
        if second {
            ct * vk * (hi - lo) + st * (v1 * (hi.sin() - lo.sin()) - v2 * (hi.cos() - lo.cos()))
        } else {
            hi - lo
        }
    };
    let measure = |theta: f64| {
        let (st, ct) = theta.sin_cos();
        let mut xs: Vec<f64> = Vec::with_capacity(12);
        for arc in &arcs {
            if arc.big_r == 0.0 {
                continue;
            }
            let rmc = 2.0 * (0.5 * (theta + arc.beta)).sin() * (0.5 * (theta - arc.beta)).sin();
            let rpc = 2.0 * (0.5 * (theta + arc.beta)).cos() * (0.5 * (theta - arc.beta)).cos();
            if rmc < 0.0 || rpc < 0.0 {
                continue;
            }
            let gamma = (rmc * rpc).sqrt().atan2(ct);
            for t in [arc.t0 - gamma, arc.t0 + gamma] {
                let t = t.rem_euclid(TAU);
                if t <= arc.x {
                    let (s, c) = t.sin_cos();
                    let u = add(scale(arc.a, c), scale(arc.c, s));
                    xs.push(dot(u, e2).atan2(dot(u, e1)));
                }
            }
        }
        if xs.is_empty() {
            return if inside(dir(st, ct, 0.0)) {
                piece(st, ct, 0.0, TAU)
            } else {
                0.0
            };
        }
        xs.sort_by(|x, y| x.partial_cmp(y).unwrap());
        let mut total = 0.0;
        for i in 0..xs.len() {
            let lo = xs[i];
            let hi = if i + 1 < xs.len() {
                xs[i + 1]
            } else {
                xs[0] + TAU
            };
            if hi > lo && inside(dir(st, ct, 0.5 * (lo + hi))) {
                total += piece(st, ct, lo, hi);
            }
        }
        total
    };
    cuts.retain(|&c| (0.0..=theta_max).contains(&c));
    cuts.sort_by(|x, y| x.partial_cmp(y).unwrap());
    cuts.dedup_by(|x, y| (*x - *y).abs() < 1e-15);
    let npieces = (cuts.len() - 1).max(1) as f64;
    let mut total = 0.0;
    for win in cuts.windows(2) {
        total += integrate_smooth_ends(
            |theta: f64| {
                let (st, ct) = theta.sin_cos();
                ct.powi(m as i32) * st * measure(theta)
            },
            win[0],
            win[1],
            tol / npieces,
            q,
        );
    }
    total
}

/// `[axial_moment]` (raw, steradians).
pub fn axial_moment(verts: &[V3], p: V3, w: V3, m: u32, q: &Quad) -> f64 {
    moment_by_circles(Some(verts), p, w, w, m, false, false, false, q.tol, q)
}

/// `[double_axis_moment]` (raw, steradians).
pub fn double_axis_moment(verts: &[V3], p: V3, w: V3, v: V3, m: u32, q: &Quad) -> f64 {
    moment_by_circles(Some(verts), p, w, v, m, true, false, false, q.tol, q)
}

/// The integral over the projection clipped to `u.w >= 0`, `u.v >= 0` of `(w.u)^m (v.u)`.
pub fn clipped_double_axis(verts: &[V3], p: V3, w: V3, v: V3, m: u32, q: &Quad) -> f64 {
    moment_by_circles(Some(verts), p, w, v, m, true, true, true, q.tol, q)
}

/// `[directional_luminaire]`.
pub fn directional_luminaire(verts: &[V3], p: V3, n: V3, axis: V3, m: u32, q: &Quad) -> f64 {
    clipped_double_axis(verts, p, scale(normalize(axis), -1.0), normalize(n), m, q)
}

/// `[glossy_reflection]`.
pub fn glossy_reflection(verts: &[V3], p: V3, n: V3, e: V3, m: u32, q: &Quad) -> f64 {
    let (n, e) = (normalize(n), normalize(e));
    let mr = normalize(sub(scale(n, 2.0 * dot(n, e)), e));
    (m as f64 + 2.0) / TAU * clipped_double_axis(verts, p, mr, n, m, q)
}

/// `[glossy_transmission]`.
pub fn glossy_transmission(verts: &[V3], p: V3, n: V3, e: V3, m: u32, q: &Quad) -> f64 {
    let (n, e) = (normalize(n), normalize(e));
    (m as f64 + 2.0) / TAU * clipped_double_axis(verts, p, scale(e, -1.0), scale(n, -1.0), m, q)
}

/// `[lune_normalization]`.
pub fn lune_normalization(w: V3, v: V3, m: u32, q: &Quad) -> f64 {
    moment_by_circles(None, [0.0; 3], w, v, m, true, true, true, q.tol, q)
}
