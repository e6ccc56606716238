//! What a user would pick instead of the analytic models: point lights, and each area light
//! approximated by k point samples. Shared by the QEMU firmware and `host-sim budget`
//! (included with `#[path]`); not part of the arealight crate.
//!
//! The lights are those of [`crate::cases`] (a cap of half-angle 0.4 about +z, a unit sphere
//! at (0, 0, 3), a 2 x 2 square at z = 2, a segment from (-1, 0, 2) to (1, 0.5, 2)), seen from
//! the origin. Samples are stratified: a `s x s` grid (k = s^2) of cell centres over the
//! light's parameter domain, which for k = 1 is the light's centre:
//!
//! - cap and sphere: directions uniform in solid angle over the cap (for the sphere, the cap
//!   it subtends from p, rebuilt per call: one square root per sample), each weighted by
//!   the cap's solid angle / k;
//! - square: points on the square, each weighted by its area / k and the cosine at the light
//!   over the squared distance (the solid angle of its patch);
//! - segment: points at the centres of k equal pieces, each weighted 1/k (Picott's integral
//!   over the segment parameter).
//!
//! Lambert sums `(n.u)+` per sample (points below the tangent plane drop out: horizon clipping
//! to sample resolution); Phong sums `((r.u)+)^m`. Every call normalizes its direction first,
//! as the analytic models do.

use arealight::{Real, Vec3};

use super::cases::{Dirs, Meter, Sample};

/// The sample counts of the budget.
pub const KS: [usize; 4] = [1, 4, 16, 64];

/// The largest k.
pub const KMAX: usize = 64;

/// The alternatives: (name, the model id it approximates). `point_*` are single point lights
/// at the sphere's centre (the cost floor); the others take k samples.
pub const ALTERNATIVES: [(&str, &str); 9] = [
    ("point_lambert", "sphere_lambert"),
    ("point_phong", "phong_sphere"),
    ("cap_lambert", "cap_lambert"),
    ("sphere_lambert", "sphere_lambert"),
    ("polygon_lambert", "polygon_lambert"),
    ("line_lambert", "line_lambert"),
    ("phong_cap", "phong_cap"),
    ("phong_sphere", "phong_sphere"),
    ("phong_polygon", "phong_polygon"),
];

const CAP_SIGMA: f64 = 0.4;
const SPHERE_C: [f64; 3] = [0.0, 0.0, 3.0];
const SPHERE_R: f64 = 1.0;
const SQUARE: [[f64; 3]; 3] = [[-1.0, -1.0, 2.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]];
const SEGMENT: [[f64; 3]; 2] = [[-1.0, 0.0, 2.0], [1.0, 0.5, 2.0]];

/// The k-sample versions of the lights, precomputed once (like the analytic lights'
/// constructors).
pub struct Sampled<T: Real> {
    k: usize,
    m: u32,
    /// (m + 1)/(2 pi).
    phong_norm: T,
    /// Cap directions and the weight Omega/(k pi) (Lambert) and Omega/k (Phong).
    cap_dirs: [Vec3<T>; KMAX],
    cap_w: T,
    /// Sphere samples in the cap's frame: (1 - cos theta)/(1 - cos sigma) and (cos phi, sin phi).
    sph_a: [T; KMAX],
    sph_phi: [(T, T); KMAX],
    /// Square sample points, the square's normal and area/k.
    sq_pts: [Vec3<T>; KMAX],
    sq_normal: Vec3<T>,
    sq_w: T,
    /// Segment sample points.
    seg_pts: [Vec3<T>; KMAX],
    center: Vec3<T>,
    radius: T,
    /// The shading point (the origin; subtracted per call as a real caller would).
    p: Vec3<T>,
}

impl<T: Real> Sampled<T> {
    /// The lights with `k` samples each (k a square, at most [`KMAX`]; other values are
    /// rounded down to a square) and Phong exponent `m`.
    pub fn new(k: usize, m: u32) -> Self {
        let mut s = 1;
        while (s + 1) * (s + 1) <= k.min(KMAX) {
            s += 1;
        }
        let k = s * s;
        let f = T::from_f64;
        let v = |a: [f64; 3]| Vec3::from_f64(a);
        let zero = Vec3::new(T::ZERO, T::ZERO, T::ZERO);
        let mut cap_dirs = [zero; KMAX];
        let mut sph_a = [T::ZERO; KMAX];
        let mut sph_phi = [(T::ONE, T::ZERO); KMAX];
        let mut sq_pts = [zero; KMAX];
        let mut seg_pts = [zero; KMAX];
        let one_minus_cos = 1.0 - libm::cos(CAP_SIGMA);
        for i in 0..s {
            for j in 0..s {
                let idx = i * s + j;
                // The grid cell's centre in [0, 1]^2; k = 1 is the light's centre.
                let (a, b) = if k == 1 {
                    (0.0, 0.0)
                } else {
                    ((i as f64 + 0.5) / s as f64, (j as f64 + 0.5) / s as f64)
                };
                let phi = b * core::f64::consts::TAU;
                let ct = 1.0 - one_minus_cos * a;
                let st = libm::sqrt((1.0 - ct) * (1.0 + ct));
                cap_dirs[idx] = v([st * libm::cos(phi), st * libm::sin(phi), ct]);
                sph_a[idx] = f(a);
                sph_phi[idx] = (f(libm::cos(phi)), f(libm::sin(phi)));
                let (u, w) = if k == 1 {
                    (0.5, 0.5)
                } else {
                    ((i as f64 + 0.5) / s as f64, (j as f64 + 0.5) / s as f64)
                };
                sq_pts[idx] = v([
                    SQUARE[0][0] + u * SQUARE[1][0] + w * SQUARE[2][0],
                    SQUARE[0][1] + u * SQUARE[1][1] + w * SQUARE[2][1],
                    SQUARE[0][2] + u * SQUARE[1][2] + w * SQUARE[2][2],
                ]);
                let t = (idx as f64 + 0.5) / k as f64;
                seg_pts[idx] = v([
                    SEGMENT[0][0] + t * (SEGMENT[1][0] - SEGMENT[0][0]),
                    SEGMENT[0][1] + t * (SEGMENT[1][1] - SEGMENT[0][1]),
                    SEGMENT[0][2] + t * (SEGMENT[1][2] - SEGMENT[0][2]),
                ]);
            }
        }
        let omega = core::f64::consts::TAU * one_minus_cos;
        Sampled {
            k,
            m,
            phong_norm: f((f64::from(m) + 1.0) / core::f64::consts::TAU),
            cap_dirs,
            cap_w: f(omega / k as f64),
            sph_a,
            sph_phi,
            sq_pts,
            sq_normal: v([0.0, 0.0, 1.0]),
            sq_w: f(4.0 / k as f64),
            seg_pts,
            center: v(SPHERE_C),
            radius: f(SPHERE_R),
            p: zero,
        }
    }

    /// The number of samples.
    pub fn k(&self) -> usize {
        self.k
    }
}

fn unit<T: Real>(d: Vec3<T>) -> Vec3<T> {
    d.normalize()
        .unwrap_or(Vec3::new(T::ZERO, T::ZERO, T::ZERO))
}

fn pos<T: Real>(x: T) -> T {
    if x > T::ZERO {
        x
    } else {
        T::ZERO
    }
}

/// The cap a sphere subtends from the origin: its axis, a frame, and 1 - cos(sigma), its
/// solid angle / (2 pi).
fn sphere_cap<T: Real>(l: &Sampled<T>) -> (Vec3<T>, Vec3<T>, Vec3<T>, T) {
    let c = l.center - l.p;
    let d2 = c.dot(c);
    let d = d2.sqrt();
    let axis = c * (T::ONE / d);
    let cos_s = ((d2 - l.radius * l.radius) / d2).sqrt();
    let t1 = axis.any_perpendicular();
    let t2 = axis.cross(t1);
    (axis, t1, t2, T::ONE - cos_s)
}

macro_rules! sampler {
    ($name:ident, $doc:expr, |$l:ident, $d:ident| $body:block) => {
        #[doc = $doc]
        #[inline(never)]
        pub fn $name<T: Real>($l: &Sampled<T>, $d: Vec3<T>) -> T $body
    };
}

sampler!(
    s_point_lambert,
    "A point light of intensity R^2 at the sphere's centre: `R^2 (n.u)+ / d^2`.",
    |l, n| {
        let n = unit(n);
        let v = l.center - l.p;
        let d2 = v.dot(v);
        let d = d2.sqrt();
        l.radius * l.radius * pos(n.dot(v)) / (d2 * d)
    }
);

sampler!(
    s_point_phong,
    "A point light standing for the sphere's solid angle pi R^2/d^2: \
     `(m+1)/(2 pi) Omega ((r.u)+)^m`.",
    |l, r| {
        let r = unit(r);
        let v = l.center - l.p;
        let d2 = v.dot(v);
        let d = d2.sqrt();
        let omega = T::PI * l.radius * l.radius / d2;
        l.phong_norm * omega * pos(r.dot(v) / d).powu(l.m)
    }
);

sampler!(
    s_cap_lambert,
    "The cap by k directions: `Omega/(k pi) sum (n.u_j)+`.",
    |l, n| {
        let n = unit(n);
        let mut acc = T::ZERO;
        for u in &l.cap_dirs[..l.k] {
            acc += pos(n.dot(*u));
        }
        acc * l.cap_w * T::FRAC_1_PI
    }
);

sampler!(
    s_phong_cap,
    "The cap by k directions: `(m+1)/(2 pi) Omega/k sum ((r.u_j)+)^m`.",
    |l, r| {
        let r = unit(r);
        let mut acc = T::ZERO;
        for u in &l.cap_dirs[..l.k] {
            acc += pos(r.dot(*u)).powu(l.m);
        }
        acc * l.cap_w * l.phong_norm
    }
);

/// The sum over the sphere's k sample directions of `f(u)`, times the cap's solid angle / k.
#[inline(always)]
fn sphere_sum<T: Real>(l: &Sampled<T>, f: impl Fn(Vec3<T>) -> T) -> T {
    let (axis, t1, t2, omc) = sphere_cap(l);
    let mut acc = T::ZERO;
    for j in 0..l.k {
        let ct = T::ONE - omc * l.sph_a[j];
        let st = ((T::ONE - ct) * (T::ONE + ct)).sqrt();
        let (cp, sp) = l.sph_phi[j];
        let u = axis * ct + (t1 * cp + t2 * sp) * st;
        acc += f(u);
    }
    acc * T::TAU * omc / T::from_u32(l.k as u32)
}

sampler!(
    s_sphere_lambert,
    "The sphere by k directions over the cap it subtends: `Omega/(k pi) sum (n.u_j)+`.",
    |l, n| {
        let n = unit(n);
        sphere_sum(l, |u| pos(n.dot(u))) * T::FRAC_1_PI
    }
);

sampler!(
    s_phong_sphere,
    "The sphere by k directions: `(m+1)/(2 pi) Omega/k sum ((r.u_j)+)^m`.",
    |l, r| {
        let r = unit(r);
        sphere_sum(l, |u| pos(r.dot(u)).powu(l.m)) * l.phong_norm
    }
);

sampler!(
    s_polygon_lambert,
    "The square by k points: `1/pi sum A/k (n.v)+ |N.v| / |v|^4` (v from p to the point).",
    |l, n| {
        let n = unit(n);
        let mut acc = T::ZERO;
        for q in &l.sq_pts[..l.k] {
            let q = &(*q - l.p);
            let d2 = q.dot(*q);
            acc += pos(n.dot(*q)) * l.sq_normal.dot(*q).abs() / (d2 * d2);
        }
        acc * l.sq_w * T::FRAC_1_PI
    }
);

sampler!(
    s_phong_polygon,
    "The square by k points: `(m+1)/(2 pi) sum A/k |N.v| / |v|^3 ((r.v/|v|)+)^m`.",
    |l, r| {
        let r = unit(r);
        let mut acc = T::ZERO;
        for q in &l.sq_pts[..l.k] {
            let q = &(*q - l.p);
            let d2 = q.dot(*q);
            let d = d2.sqrt();
            acc += l.sq_normal.dot(*q).abs() / (d2 * d) * pos(r.dot(*q) / d).powu(l.m);
        }
        acc * l.sq_w * l.phong_norm
    }
);

sampler!(
    s_line_lambert,
    "The segment by k points (decay k = 2): `1/k sum (L.n)+ / |L|^3`.",
    |l, n| {
        let n = unit(n);
        let mut acc = T::ZERO;
        for q in &l.seg_pts[..l.k] {
            let q = &(*q - l.p);
            let d2 = q.dot(*q);
            acc += pos(n.dot(*q)) / (d2 * d2.sqrt());
        }
        acc / T::from_u32(l.k as u32)
    }
);

/// Runs alternative `alt` (an index into [`ALTERNATIVES`]) over every direction of `dirs`,
/// each call through `meter`, and hands each sample (`model` = `alt`) to `out`.
pub fn run_alt<T: Real, M: Meter>(
    l: &Sampled<T>,
    alt: usize,
    dirs: Dirs,
    round: fn(f64) -> f64,
    meter: &mut M,
    out: &mut impl FnMut(Sample),
) {
    macro_rules! go {
        ($k:ident) => {
            for i in 0..dirs.count {
                let d = core::hint::black_box(Vec3::<T>::from_f64((dirs.get)(i).map(round)));
                let lr = core::hint::black_box(l);
                let (r, count) = meter.call(|| $k(lr, d));
                out(Sample {
                    model: alt,
                    input: i,
                    value: [r.to_f64(), 0.0, 0.0],
                    channels: 1,
                    count,
                });
            }
        };
    }
    match alt {
        0 => go!(s_point_lambert),
        1 => go!(s_point_phong),
        2 => go!(s_cap_lambert),
        3 => go!(s_sphere_lambert),
        4 => go!(s_polygon_lambert),
        5 => go!(s_line_lambert),
        6 => go!(s_phong_cap),
        7 => go!(s_phong_sphere),
        8 => go!(s_phong_polygon),
        _ => {}
    }
}
