//! The cases of every model id: generic inputs (non-unit directions, every parameter away
//! from its special values) as eval input lines, each with its reference value from the
//! independent quadratures of `tests/common` or a transcription of its definition.

use super::*;

/// One case: the eval input line, the reference (one value, or three for the RGB models) and
/// the f64 budget row it is held to.
pub(crate) struct Case {
    pub(crate) line: Value,
    pub(crate) want: Vec<f64>,
    pub(crate) row: &'static str,
    /// Hermite cases: the largest error of the approximation allowed against the exact model
    /// (0 outside the fillet), and the least (inside the fillet at a large cap: it must not be
    /// the exact model).
    pub(crate) hermite: Option<(f64, f64)>,
}

pub(crate) fn j(v: V3) -> Value {
    json!(v)
}

/// A random direction at an angle in `[lo, hi]` from the unit `axis`, randomly scaled.
pub(crate) fn tilt(rng: &mut Rng, axis: V3, lo: f64, hi: f64) -> V3 {
    let w = rng.range(lo, hi);
    let d = rng.dir_at(axis, w);
    rng.stretch(d)
}

/// A random vector in the box `[-s, s]^3`.
pub(crate) fn rbox(rng: &mut Rng, s: f64) -> V3 {
    [rng.range(-s, s), rng.range(-s, s), rng.range(-s, s)]
}

/// A planar polygon: an L-shape (i odd) or a convex pentagon, of size about 1, centred at
/// `center`, in a random plane.
pub(crate) fn polygon(rng: &mut Rng, i: usize, center: V3) -> Vec<V3> {
    let pts: Vec<[f64; 2]> = if i % 2 == 1 {
        common::l_shape()
    } else {
        (0..5)
            .map(|k| {
                let a = std::f64::consts::TAU * (k as f64 + rng.range(0.0, 0.4)) / 5.0;
                [0.6 * a.cos(), 0.6 * a.sin()]
            })
            .collect()
    };
    let size = rng.range(0.8, 1.4);
    common::place(rng, &pts, center, size)
}

/// GLSL smoothstep.
pub(crate) fn smoothstep(e0: f64, e1: f64, x: f64) -> f64 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// `[superellipse_shape]` transcribed from `models.md`.
pub(crate) fn superellipse(pos: V3, a: f64, b: f64, aa: f64, bb: f64, d: f64) -> f64 {
    let [x, y, z] = pos;
    if z <= 0.0 {
        return 0.0;
    }
    let (xx, yy) = ((x / z).abs(), (y / z).abs());
    if xx == 0.0 && yy == 0.0 {
        return 1.0;
    }
    let q = a * b * ((b * xx).powf(2.0 / d) + (a * yy).powf(2.0 / d)).powf(-d / 2.0);
    let r = aa * bb * ((bb * xx).powf(2.0 / d) + (aa * yy).powf(2.0 / d)).powf(-d / 2.0);
    1.0 - smoothstep(q, r, 1.0)
}

/// `[distance_falloff]` transcribed from `models.md`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn falloff(
    z: f64,
    m: f64,
    d0: f64,
    alpha: f64,
    zn: f64,
    zf: f64,
    ne: f64,
    fe: f64,
) -> f64 {
    let g = if z > d0 {
        (d0 / z).powf(alpha)
    } else {
        let s = (1.0 / m).ln();
        let beta = -alpha / s;
        m * (s * (z / d0).powf(beta)).exp()
    };
    smoothstep(zn - ne, zn, z) * (1.0 - smoothstep(zf, zf + fe, z)) * g
}

/// The cases of one model id.
pub(crate) fn cases_of(id: &'static str, rng: &mut Rng, q: &Quad) -> Vec<Case> {
    let mut out = Vec::new();
    let ms = [0u32, 1, 7, 16];
    for i in 0..PER_ID {
        let tag = format!("{id}#{i}");
        // A source axis and a normal (or r) at up to 2 rad from it: the source in view.
        let axis = rng.sdir();
        let n = tilt(rng, normalize(axis), 0.0, 2.0);
        let m = ms[i % ms.len()];
        let one = |line: Value, want: f64, row: &'static str| Case {
            line,
            want: vec![want],
            row,
            hermite: None,
        };
        let case = match id {
            "hemi_const" => one(
                json!({"id": tag, "model": id, "n": j(n), "axis": j(axis)}),
                qd::hemi_const(normalize(axis), normalize(n), q),
                id,
            ),
            "hemi_cos" => one(
                json!({"id": tag, "model": id, "n": j(n), "axis": j(axis)}),
                qd::hemi_cos(normalize(axis), normalize(n), q),
                id,
            ),
            "sky_overcast" => {
                let c = rng.range(0.5, 3.0);
                one(
                    json!({"id": tag, "model": id, "n": j(n), "zenith": j(axis), "c": c}),
                    qd::sky_overcast(normalize(axis), c, normalize(n), q),
                    id,
                )
            }
            "sky_ground" => {
                let sky = [rng.unit(), rng.unit(), rng.unit()];
                let ground = [rng.unit(), rng.unit(), rng.unit()];
                Case {
                    line: json!({"id": tag, "model": id, "n": j(n), "up": j(axis),
                                 "sky": j(sky), "ground": j(ground)}),
                    want: qd::sky_ground(normalize(axis), sky, ground, normalize(n), q).to_vec(),
                    row: id,
                    hermite: None,
                }
            }
            "cap_lambert" => {
                let sigma = rng.range(0.1, 1.4);
                let n = tilt(rng, normalize(axis), 0.0, FRAC_PI_2 + sigma - 0.05);
                one(
                    json!({"id": tag, "model": id, "n": j(n), "axis": j(axis), "sigma": sigma}),
                    qd::cap_lambert(normalize(axis), sigma, normalize(n), q),
                    id,
                )
            }
            "cap_lambert_hermite" => {
                // Cases 0, 1: outside the fillet (exact there); 2: inside, sigma = pi/8 (Snyder's
                // approximation within 2.2e-4 of the exact model); 3: inside, sigma = pi/4, in
                // the middle of the first segment (within 1.8e-3, and at least 1e-5 off).
                let (sigma, w, hermite) = match i {
                    0 => (0.5, rng.range(0.0, FRAC_PI_2 - 0.6), (0.0, 0.0)),
                    1 => (0.3, rng.range(FRAC_PI_2 + 0.35, PI), (0.0, 0.0)),
                    2 => (PI / 8.0, FRAC_PI_2 + 0.1, (2.5e-4, 0.0)),
                    _ => (PI / 4.0, FRAC_PI_2 - PI / 8.0, (2e-3, 1e-5)),
                };
                let a = normalize(axis);
                let nn = tilt(rng, a, w, w);
                Case {
                    line: json!({"id": tag, "model": id, "n": j(nn), "axis": j(axis),
                                 "sigma": sigma}),
                    want: vec![qd::cap_lambert(a, sigma, normalize(nn), q)],
                    row: "cap_lambert",
                    hermite: Some(hermite),
                }
            }
            "sphere_lambert" | "sphere_lambert_hermite" | "phong_sphere" => {
                // Inside the fixed backend's coordinate range [-4, 4].
                let center = rbox(rng, 1.0);
                let radius = rng.range(0.3, 0.8);
                let p = add(center, scale(rng.dir(), radius * rng.range(1.5, 3.0)));
                let (ax, sigma) = qd::sphere_cap(center, radius, p);
                let n = tilt(rng, ax, 0.0, if id == "phong_sphere" { 0.5 } else { 1.5 });
                if id == "phong_sphere" {
                    one(
                        json!({"id": tag, "model": id, "p": j(p), "r": j(n), "center": j(center),
                               "radius": radius, "m": m}),
                        qd::phong_sphere(center, radius, p, normalize(n), m, q),
                        id,
                    )
                } else if id == "sphere_lambert" {
                    one(
                        json!({"id": tag, "model": id, "p": j(p), "n": j(n), "center": j(center),
                               "radius": radius}),
                        qd::sphere_lambert(center, radius, p, normalize(n), q),
                        id,
                    )
                } else {
                    // n outside the fillet (cases 0, 1: exact) or in it (within the measured
                    // error of the approximation at this sigma, below pi/4).
                    let w = if i < 2 {
                        rng.range(0.0, (FRAC_PI_2 - sigma - 0.05).max(0.0))
                    } else {
                        FRAC_PI_2 - 0.5 * sigma
                    };
                    let nn = tilt(rng, ax, w, w);
                    let tol = if i < 2 { 0.0 } else { 2e-3 };
                    Case {
                        line: json!({"id": tag, "model": id, "p": j(p), "n": j(nn),
                                     "center": j(center), "radius": radius}),
                        want: vec![qd::cap_lambert(ax, sigma, normalize(nn), q)],
                        row: "sphere_lambert",
                        hermite: Some((tol, 0.0)),
                    }
                }
            }
            "polygon_lambert" | "phong_polygon" => {
                let center = scale(rng.dir(), rng.range(1.8, 2.5));
                let verts = polygon(rng, i, center);
                let p = rbox(rng, 0.3);
                // The weight axis toward the light, tilted (so the horizon clips some cases).
                let spread = if id == "phong_polygon" { 0.3 } else { 1.3 };
                let k = tilt(rng, normalize(sub(center, p)), 0.0, spread);
                let vj: Vec<Value> = verts.iter().map(|&x| j(x)).collect();
                if id == "polygon_lambert" {
                    one(
                        json!({"id": tag, "model": id, "p": j(p), "n": j(k), "verts": vj}),
                        qd::polygon_lambert(&verts, p, normalize(k), q),
                        id,
                    )
                } else {
                    one(
                        json!({"id": tag, "model": id, "p": j(p), "r": j(k), "verts": vj, "m": m}),
                        qd::phong_polygon(&verts, p, normalize(k), m, q),
                        id,
                    )
                }
            }
            "line_lambert" => {
                let (a, b, p) = (rbox(rng, 2.0), rbox(rng, 2.0), rbox(rng, 2.0));
                let mid = scale(add(a, b), 0.5);
                let n = tilt(rng, normalize(sub(mid, p)), 0.0, 1.2);
                let k = i as u32;
                let (want, _) = lq::line_lambert(a, b, p, normalize(n), k);
                one(
                    json!({"id": tag, "model": id, "p": j(p), "n": j(n), "a": j(a), "b": j(b),
                           "k": k}),
                    want,
                    id,
                )
            }
            "phong_hemi_const" => one(
                json!({"id": tag, "model": id, "r": j(n), "axis": j(axis), "m": m}),
                qd::phong_hemi_const(normalize(axis), normalize(n), m, q),
                id,
            ),
            "phong_hemi_cos" => one(
                json!({"id": tag, "model": id, "r": j(n), "axis": j(axis), "m": m}),
                qd::phong_hemi_cos(normalize(axis), normalize(n), m, q),
                id,
            ),
            "phong_cap" => {
                let sigma = rng.range(0.1, 1.4);
                // r near the cap half the time (the lobe then sees it at every m).
                let r = if i % 2 == 0 {
                    tilt(rng, normalize(axis), 0.0, sigma + 0.3)
                } else {
                    n
                };
                one(
                    json!({"id": tag, "model": id, "r": j(r), "axis": j(axis), "sigma": sigma,
                           "m": m}),
                    qd::phong_cap(normalize(axis), sigma, normalize(r), m, q),
                    id,
                )
            }
            "line_phong_peak" => {
                let (a, b, p) = (rbox(rng, 2.0), rbox(rng, 2.0), rbox(rng, 2.0));
                let t = rng.unit();
                let toward = normalize(sub(add(a, scale(sub(b, a), t)), p));
                let r = tilt(rng, toward, 0.0, 0.4);
                let want = lq::lobe(lq::line_max_cos(a, b, p, normalize(r)), m);
                one(
                    json!({"id": tag, "model": id, "p": j(p), "r": j(r), "a": j(a), "b": j(b),
                           "m": m}),
                    want,
                    id,
                )
            }
            "rect_phong_peak" => {
                let o = rbox(rng, 1.5);
                let eu = scale(rng.dir(), rng.range(0.5, 1.5));
                let ev = scale(normalize(cross(eu, rng.dir())), rng.range(0.5, 1.5));
                let nu = normalize(cross(eu, ev));
                let x = add(o, add(scale(eu, rng.unit()), scale(ev, rng.unit())));
                let p = add(
                    x,
                    scale(
                        nu,
                        rng.range(0.5, 2.0) * if i % 2 == 0 { 1.0 } else { -1.0 },
                    ),
                );
                // r toward a point of the light or beyond its boundary.
                let y = add(
                    o,
                    add(
                        scale(eu, rng.range(-0.3, 1.3)),
                        scale(ev, rng.range(-0.3, 1.3)),
                    ),
                );
                let r = tilt(rng, normalize(sub(y, p)), 0.0, 0.2);
                let want = lq::lobe(lq::rect_max_cos(o, eu, ev, p, normalize(r)), m);
                one(
                    json!({"id": tag, "model": id, "p": j(p), "r": j(r), "origin": j(o),
                           "eu": j(eu), "ev": j(ev), "m": m}),
                    want,
                    id,
                )
            }
            "axial_moment"
            | "double_axis_moment"
            | "directional_luminaire"
            | "glossy_reflection"
            | "glossy_transmission" => {
                let center = scale(rng.dir(), rng.range(1.8, 2.5));
                let verts = polygon(rng, i, center);
                let p = rbox(rng, 0.3);
                let vj: Vec<Value> = verts.iter().map(|&x| j(x)).collect();
                let toward = normalize(sub(center, p));
                let w = tilt(rng, toward, 0.0, 1.0);
                let nn = tilt(rng, toward, 0.0, 1.0);
                let (wn, nnn) = (normalize(w), normalize(nn));
                match id {
                    "axial_moment" => one(
                        json!({"id": tag, "model": id, "p": j(p), "verts": vj, "w": j(w), "m": m}),
                        mq::axial_moment(&verts, p, wn, m, q),
                        id,
                    ),
                    "double_axis_moment" => one(
                        json!({"id": tag, "model": id, "p": j(p), "verts": vj, "w": j(w),
                               "v": j(nn), "m": m}),
                        mq::double_axis_moment(&verts, p, wn, nnn, m, q),
                        id,
                    ),
                    "directional_luminaire" => {
                        // The luminaire's axis points from the light toward p.
                        let ax = tilt(rng, scale(toward, -1.0), 0.0, 0.8);
                        one(
                            json!({"id": tag, "model": id, "p": j(p), "n": j(nn), "verts": vj,
                                   "axis": j(ax), "m": m}),
                            mq::directional_luminaire(&verts, p, nnn, normalize(ax), m, q),
                            id,
                        )
                    }
                    "glossy_reflection" => {
                        // The eye on the mirror side of n: mr = 2 (n.e) n - e near the light.
                        let e = tilt(rng, nnn, 0.0, 1.0);
                        one(
                            json!({"id": tag, "model": id, "p": j(p), "n": j(nn), "e": j(e),
                                   "verts": vj, "m": m}),
                            mq::glossy_reflection(&verts, p, nnn, normalize(e), m, q),
                            id,
                        )
                    }
                    _ => {
                        // Transmission: the eye below the surface, the light above.
                        let e = tilt(rng, scale(toward, -1.0), 0.0, 0.8);
                        let nt = scale(nn, -1.0);
                        one(
                            json!({"id": tag, "model": id, "p": j(p), "n": j(nt), "e": j(e),
                                   "verts": vj, "m": m}),
                            mq::glossy_transmission(&verts, p, normalize(nt), normalize(e), m, q),
                            id,
                        )
                    }
                }
            }
            "lune_normalization" => one(
                json!({"id": tag, "model": id, "w": j(n), "v": j(axis), "m": m}),
                mq::lune_normalization(normalize(n), normalize(axis), m, q),
                id,
            ),
            "sh9_irradiance" => {
                let coeffs: Vec<V3> = (0..9)
                    .map(|k| {
                        let lo = if k == 0 { 0.0 } else { -0.5 };
                        [rng.range(lo, 1.0), rng.range(lo, 1.0), rng.range(lo, 1.0)]
                    })
                    .collect();
                let want = (0..3)
                    .map(|ch| {
                        let c: [f64; 9] = std::array::from_fn(|k| coeffs[k][ch]);
                        qd::sh9_irradiance(&c, normalize(n), q)
                    })
                    .collect();
                Case {
                    line: json!({"id": tag, "model": id, "n": j(n), "coeffs": coeffs}),
                    want,
                    row: id,
                    hermite: None,
                }
            }
            "sh9_disc_irradiance" => {
                let alpha = rng.range(0.1, 3.0);
                one(
                    json!({"id": tag, "model": id, "n": j(n), "axis": j(axis), "alpha": alpha}),
                    qd::sh9_disc_irradiance(normalize(axis), alpha, normalize(n), q),
                    id,
                )
            }
            "superellipse_shape" => {
                let (a, b) = (rng.range(0.2, 0.6), rng.range(0.2, 0.6));
                let (aa, bb) = (a + rng.range(0.1, 0.5), b + rng.range(0.1, 0.5));
                let d = rng.range(0.3, 2.0);
                // Along a ray of light space at angle theta: inside the inner curve, twice in
                // the soft band between the curves, outside the outer one (the curves' points
                // at theta: (a cos^d, b sin^d) and (A cos^d, B sin^d)).
                let th = rng.range(0.1, FRAC_PI_2 - 0.1);
                let (c, sn) = (th.cos().powf(d), th.sin().powf(d));
                let t = [-0.4, 0.3, 0.7, 1.4][i];
                let (x, y) = (a * c + t * (aa - a) * c, b * sn + t * (bb - b) * sn);
                let z = rng.range(0.5, 3.0);
                let pos = [x * z, -y * z, z];
                one(
                    json!({"id": tag, "model": id, "pos": j(pos), "a": a, "b": b, "A": aa,
                           "B": bb, "d": d}),
                    superellipse(pos, a, b, aa, bb, d),
                    id,
                )
            }
            "distance_falloff" => {
                let mm = rng.range(1.5, 4.0);
                let d0 = rng.range(0.3, 1.5);
                let alpha = rng.range(0.5, 3.0);
                let zn = rng.range(0.3, 1.0);
                let zf = zn + rng.range(1.0, 3.0);
                let (ne, fe) = (rng.range(0.1, 0.3), rng.range(0.2, 1.0));
                // In the near ramp, below d0, beyond d0, in the far ramp.
                let z = [
                    zn - 0.5 * ne,
                    0.5 * d0.min(zn) + 0.5 * zn,
                    zf - 0.1,
                    zf + 0.5 * fe,
                ][i]
                    .max(0.05);
                one(
                    json!({"id": tag, "model": id, "z": z, "M": mm, "d0": d0, "alpha": alpha,
                           "znear": zn, "zfar": zf, "near_edge": ne, "far_edge": fe}),
                    falloff(z, mm, d0, alpha, zn, zf, ne, fe),
                    id,
                )
            }
            _ => panic!("no cases for {id}"),
        };
        out.push(case);
    }
    out
}

/// Every id's cases (deterministic).
pub(crate) fn all_cases() -> Vec<Case> {
    let q = Quad::STD;
    let mut rng = Rng::new(0x0e7a_19ad);
    IDS.iter()
        .flat_map(|id| cases_of(id, &mut rng, &q))
        .collect()
}
