//! The polygons' integrals (see the parent module's "Polygons"): the circles method about the
//! weight axis ([`polygon_by_circles`], the reference) and the fan method over the clipped
//! polygon ([`polygon_integral`]), and the models' integrals built on them.

use super::*;

/// Newell's normal (unnormalized, length = twice the area for a planar polygon).
pub fn newell(verts: &[V3]) -> V3 {
    let o = verts[0];
    let mut nn = [0.0; 3];
    for i in 0..verts.len() {
        let a = sub(verts[i], o);
        let b = sub(verts[(i + 1) % verts.len()], o);
        nn = add(nn, cross(a, b));
    }
    nn
}

/// Sutherland-Hodgman: the ring `verts` clipped to `(x - p).k >= 0`.
pub fn clip_polygon(verts: &[V3], p: V3, k: V3) -> Vec<V3> {
    let n = verts.len();
    let d: Vec<f64> = verts.iter().map(|&v| dot(sub(v, p), k)).collect();
    let mut out = Vec::with_capacity(2 * n);
    for i in 0..n {
        let j = (i + 1) % n;
        let (a, b) = (verts[i], verts[j]);
        let (da, db) = (d[i], d[j]);
        if da >= 0.0 {
            out.push(a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            let t = da / (da - db);
            out.push(add(a, scale(sub(b, a), t)));
        }
    }
    out
}

/// `integral over the projection of the planar polygon, clipped to u.k >= 0, of f(u) du`,
/// where `f` must be smooth on the whole sphere (e.g. `(u.k)^m` without the `max(0, .)`; see the
/// module docs). 0 when `p` is in the plane. `tol` absolute in raw units.
pub fn polygon_integral<F: Fn(V3) -> f64>(
    verts: &[V3],
    p: V3,
    k: V3,
    f: F,
    tol: f64,
    q: &Quad,
) -> f64 {
    let k = normalize(k);
    let nn = newell(verts);
    let nu0 = normalize(nn);
    // Height of p above the plane, by the mean over the vertices (robust to tiny non-planarity).
    let hsum: f64 = verts.iter().map(|&v| dot(sub(v, p), nu0)).sum::<f64>();
    let h_signed = hsum / verts.len() as f64;
    if h_signed == 0.0 {
        return 0.0;
    }
    let (nu, h) = if h_signed > 0.0 {
        (nu0, h_signed)
    } else {
        (scale(nu0, -1.0), -h_signed)
    };
    let e1 = any_perp(nu);
    let e2 = cross(nu, e1);
    let foot = add(p, scale(nu, h));
    let clipped = clip_polygon(verts, p, k);
    if clipped.len() < 3 {
        return 0.0;
    }
    // 2D coordinates about the foot q.
    let pts: Vec<[f64; 2]> = clipped
        .iter()
        .map(|&x| {
            let r = sub(x, foot);
            [dot(r, e1), dot(r, e2)]
        })
        .collect();
    let ne = pts.len();
    let edge_tol = tol / ne as f64;
    // The integrand (u.k)^m peaks at u = k and (odd m, negatively) at u = -k, with a width of
    // about 1/sqrt(m): both the azimuth psi and the polar angle alpha are split there, so no
    // rule can step over a narrow peak.
    let k_polar = angle(nu, k);
    let k_azimuth = if norm(cross(nu, k)) > 1e-12 {
        Some(dot(k, e2).atan2(dot(k, e1)))
    } else {
        None
    };
    let alpha_cuts = [k_polar, PI - k_polar];
    let wrap = |x: f64| {
        let y = (x + PI).rem_euclid(TAU) - PI;
        if y <= -PI {
            y + TAU
        } else {
            y
        }
    };
    let mut total = 0.0;
    for i in 0..ne {
        let a = pts[i];
        let b = pts[(i + 1) % ne];
        let dv = [b[0] - a[0], b[1] - a[1]];
        let len2 = dv[0] * dv[0] + dv[1] * dv[1];
        if len2 == 0.0 {
            continue;
        }
        // x0: the point of the edge's line nearest q, at distance d, azimuth psi_perp.
        let s0 = -(a[0] * dv[0] + a[1] * dv[1]) / len2;
        let mut x0 = [a[0] + s0 * dv[0], a[1] + s0 * dv[1]];
        let corr = (x0[0] * dv[0] + x0[1] * dv[1]) / len2;
        x0 = [x0[0] - corr * dv[0], x0[1] - corr * dv[1]];
        let d = (x0[0] * x0[0] + x0[1] * x0[1]).sqrt();
        if d <= 1e-14 * len2.sqrt() {
            // q on the edge's line (to rounding): a fan triangle of zero area, whose azimuth
            // psi_perp would be noise.
            continue;
        }
        let psi_perp = x0[1].atan2(x0[0]);
        let psi_a = a[1].atan2(a[0]);
        let sweep = wrap(b[1].atan2(b[0]) - psi_a);
        if sweep == 0.0 {
            continue;
        }
        // Along the ray from q at azimuth psi the edge is at distance d / cos(psi - psi_perp).
        let outer = |tau: f64| {
            let psi = psi_a + tau;
            let cosd = (psi - psi_perp).cos();
            let alpha_e = if cosd > 0.0 {
                d.atan2(h * cosd)
            } else {
                FRAC_PI_2
            };
            let (sp, cp) = psi.sin_cos();
            let dir = add(scale(e1, cp), scale(e2, sp));
            let g = |al: f64| {
                let (sa, ca) = al.sin_cos();
                f(add(scale(nu, ca), scale(dir, sa))) * sa
            };
            let mut cuts = vec![0.0, alpha_e];
            for &c in &alpha_cuts {
                if c > 1e-12 && c < alpha_e - 1e-12 {
                    cuts.push(c);
                }
            }
            cuts.sort_by(|x, y| x.partial_cmp(y).unwrap());
            let mut inner = 0.0;
            for w in cuts.windows(2) {
                inner += integrate(g, w[0], w[1], edge_tol / (4.0 * TAU), q);
            }
            inner
        };
        let (lo, hi) = if sweep > 0.0 {
            (0.0, sweep)
        } else {
            (sweep, 0.0)
        };
        let mut cuts = vec![lo, hi];
        let mut targets = vec![psi_perp];
        // When d < h, alpha_e(psi) = atan2(d, h cos(psi - psi_perp)) climbs from about d/h to
        // about pi/2 in a thin layer at the ends of a long edge: split where it passes pi/4.
        if d < h {
            let t = (d / h).acos();
            targets.push(psi_perp + t);
            targets.push(psi_perp - t);
        }
        if let Some(az) = k_azimuth {
            targets.push(az);
            targets.push(az + PI);
        }
        for t in targets {
            let tau = wrap(t - psi_a);
            if tau > lo + 1e-12 && tau < hi - 1e-12 {
                cuts.push(tau);
            }
        }
        cuts.sort_by(|x, y| x.partial_cmp(y).unwrap());
        let mut edge = 0.0;
        let npieces = (cuts.len() - 1) as f64;
        for w in cuts.windows(2) {
            edge += integrate(outer, w[0], w[1], edge_tol / npieces, &q.outer());
        }
        total += sweep.signum() * edge;
    }
    total.abs()
}

/// Crossing-number test of a 2D point against a 2D polygon.
pub fn point_in_polygon(pt: [f64; 2], poly: &[[f64; 2]]) -> bool {
    let mut inside = false;
    let n = poly.len();
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        if (a[1] > pt[1]) != (b[1] > pt[1]) {
            let x = a[0] + (pt[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if pt[0] < x {
                inside = !inside;
            }
        }
    }
    inside
}

/// One edge of a polygon seen from p: its great-circle arc `u(t) = cos(t) a + sin(t) c`,
/// `t` in [0, x], and where it stands relative to the weight axis k.
pub struct Arc {
    pub a: V3,
    pub c: V3,
    pub x: f64,
    /// `|u.k|` is at most `big_r` on the great circle, reached at `t = t0`.
    pub big_r: f64,
    pub t0: f64,
    /// Angle between k and the great circle's plane (`cos beta = big_r`).
    pub beta: f64,
}

impl Arc {
    /// The arc from unit `a` of length `x` on the great circle of unit normal `g`, seen about `k`.
    pub fn new(a: V3, g: V3, x: f64, k: V3) -> Arc {
        let c = cross(g, a);
        let (ak, ck) = (dot(a, k), dot(c, k));
        let big_r = ak.hypot(ck);
        Arc {
            a,
            c,
            x,
            big_r,
            t0: ck.atan2(ak),
            beta: dot(k, g).abs().atan2(big_r),
        }
    }
}

/// `integral over the projection of the planar polygon, clipped to u.k >= 0, of w(u.k) du`,
/// in polar coordinates `(theta, phi)` about `k` (the second polygon method; see the module
/// docs). For each `theta` the circle of radius `theta` about `k` is cut by the edges' great
/// circles (closed-form crossings); the arcs between crossings lie inside or outside the
/// projection (tested at their midpoints by casting the ray onto the plane), so the inner
/// integral is the total inside arc length. The `theta` integrand is analytic between the
/// vertices' `theta` and the edges' tangency angles, where the range is split, each piece
/// integrated with [`integrate_smooth_ends`].
pub fn polygon_by_circles<W: Fn(f64) -> f64>(
    verts: &[V3],
    p: V3,
    k: V3,
    w: W,
    tol: f64,
    q: &Quad,
) -> f64 {
    polygon_by_circles_cuts(verts, p, k, w, tol, q, &[])
}

/// [`polygon_by_circles`] with extra panel ends `extra` (angles from `k`) in the `theta` range.
pub fn polygon_by_circles_cuts<W: Fn(f64) -> f64>(
    verts: &[V3],
    p: V3,
    k: V3,
    w: W,
    tol: f64,
    q: &Quad,
    extra: &[f64],
) -> f64 {
    let k = normalize(k);
    let nn = normalize(newell(verts));
    let h_signed = verts.iter().map(|&v| dot(sub(v, p), nn)).sum::<f64>() / verts.len() as f64;
    if h_signed == 0.0 {
        return 0.0;
    }
    let (nu, h) = if h_signed > 0.0 {
        (nn, h_signed)
    } else {
        (scale(nn, -1.0), -h_signed)
    };
    let (f1, f2) = {
        let f1 = any_perp(nu);
        (f1, cross(nu, f1))
    };
    let poly2: Vec<[f64; 2]> = verts
        .iter()
        .map(|&v| {
            let d = sub(v, p);
            [dot(d, f1), dot(d, f2)]
        })
        .collect();
    let (e1, e2) = {
        let e1 = any_perp(k);
        (e1, cross(k, e1))
    };
    let nv = verts.len();
    let mut arcs = Vec::with_capacity(nv);
    let mut cuts = vec![0.0, FRAC_PI_2];
    for i in 0..nv {
        let ar = sub(verts[i], p);
        let br = sub(verts[(i + 1) % nv], p);
        let ev = sub(verts[(i + 1) % nv], verts[i]);
        let a = normalize(ar);
        let bh = normalize(br);
        cuts.push(angle(k, a));
        let gr = cross(ar, ev);
        if norm(gr) == 0.0 {
            continue; // p on the edge's line: the arc has no width.
        }
        let arc = Arc::new(a, normalize(gr), angle(a, bh), k);
        cuts.push(arc.beta);
        arcs.push(arc);
    }
    let inside = |u: V3| {
        let un = dot(u, nu);
        if !(un > 0.0) {
            return false;
        }
        let t = h / un;
        point_in_polygon([t * dot(u, f1), t * dot(u, f2)], &poly2)
    };
    let dir = |st: f64, ct: f64, phi: f64| {
        let (sp, cp) = phi.sin_cos();
        add(scale(k, ct), scale(add(scale(e1, cp), scale(e2, sp)), st))
    };
    // Inside arc length of the circle of radius theta about k.
    let measure = |theta: f64| {
        let (st, ct) = theta.sin_cos();
        let mut xs: Vec<f64> = Vec::with_capacity(8);
        for arc in &arcs {
            if arc.big_r == 0.0 {
                continue;
            }
            // big_r - cos(theta) = cos(beta) - cos(theta), as a product (no cancellation).
            let rmc = 2.0 * (0.5 * (theta + arc.beta)).sin() * (0.5 * (theta - arc.beta)).sin();
            if rmc < 0.0 {
                continue;
            }
            let gamma = (rmc * (arc.big_r + ct)).sqrt().atan2(ct);
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
            return if inside(dir(st, ct, 0.0)) { TAU } else { 0.0 };
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
                total += hi - lo;
            }
        }
        total
    };
    cuts.extend_from_slice(extra);
    cuts.retain(|&c| (0.0..=FRAC_PI_2).contains(&c));
    cuts.sort_by(|x, y| x.partial_cmp(y).unwrap());
    cuts.dedup_by(|x, y| (*x - *y).abs() < 1e-15);
    let npieces = (cuts.len() - 1).max(1) as f64;
    let mut total = 0.0;
    for win in cuts.windows(2) {
        total += integrate_smooth_ends(
            |theta: f64| {
                let (st, ct) = theta.sin_cos();
                w(ct) * st * measure(theta)
            },
            win[0],
            win[1],
            tol / npieces,
            q,
        );
    }
    total
}

/// `[polygon_lambert]`, normalized.
pub fn polygon_lambert(verts: &[V3], p: V3, n: V3, q: &Quad) -> f64 {
    polygon_by_circles(verts, p, n, |c| c, q.tol * PI, q) / PI
}

/// `[phong_polygon]`, normalized.
pub fn phong_polygon(verts: &[V3], p: V3, r: V3, m: u32, q: &Quad) -> f64 {
    let norm = (m as f64 + 1.0) / TAU;
    polygon_by_circles(verts, p, r, |c| c.powi(m as i32), q.tol / norm, q) * norm
}

/// [`phong_polygon`] with the lobe's panel ends ([`lobe_cuts`]): the reference for sharp lobes.
pub fn phong_polygon_sharp(verts: &[V3], p: V3, r: V3, m: u32, q: &Quad) -> f64 {
    let norm = (m as f64 + 1.0) / TAU;
    let w = |c: f64| c.powi(m as i32);
    polygon_by_circles_cuts(verts, p, r, w, q.tol / norm, q, &lobe_cuts(m)) * norm
}

/// `[polygon_lambert]` by the fan method ([`polygon_integral`]), for cross-checks.
pub fn polygon_lambert_fan(verts: &[V3], p: V3, n: V3, q: &Quad) -> f64 {
    let n = normalize(n);
    polygon_integral(verts, p, n, |u| dot(u, n), q.tol * PI, q) / PI
}

/// `[phong_polygon]` by the fan method ([`polygon_integral`]), for cross-checks.
pub fn phong_polygon_fan(verts: &[V3], p: V3, r: V3, m: u32, q: &Quad) -> f64 {
    let r = normalize(r);
    let norm = (m as f64 + 1.0) / TAU;
    polygon_integral(verts, p, r, |u| dot(u, r).powi(m as i32), q.tol / norm, q) * norm
}
