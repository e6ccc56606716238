//! The fuzz targets' bodies, shared by the bit-pattern harness `tests/fuzz_bits.rs` (runs in
//! `cargo test`) and the cargo-fuzz crate `fuzz/` (libFuzzer, nightly): every public
//! constructor and per-sample function of one model family, fed arbitrary f32 bit patterns
//! (NaN, infinities, subnormals, huge values) and exponents, on every backend: f64 (the same
//! values widened), f32, Fast32 and Fixed22 (its positions folded into its coordinate range by
//! a power of two, except where the input asks for the raw value: both paths are fuzzed). A
//! target fails (panics) if the library panics or a per-sample function returns NaN or
//! infinity.
//!
//! Polygons come two ways: raw vertices (rarely planar, so mostly refused), and planar ones
//! built on purpose ([`planar_polygon`]): convex, star-shaped, regular stars, L and U shapes,
//! 3 to 8 vertices (the capacity), placed in an arbitrary plane, optionally near-degenerate
//! (slivers, a vanishing edge, a nearly collinear vertex, tiny or huge), with the shading point
//! anywhere, near the plane or near an edge. The rasterizer is a family too ([`Family::Raster`]):
//! arbitrary cameras, meshes, transforms, band sizes and raw edge-function inputs.
#![allow(dead_code)]

use arealight::raster::edge::{edge_function, is_top_left, MAX_COORD};
use arealight::raster::{
    draw, Affine, Band, Camera, Cull, DrawOptions, EdgeTriangle, EncodeTable, Encoding, FixedPoint,
    Lit, Material, Mesh, PreparedMesh, PreparedVertex, Projection, Rgb565, Shading, Vertex,
};
use arealight::{
    lune_normalization, try_lune_normalization, CapLight, Decay, DistanceFalloff, Fast32, Fixed22,
    HemisphereLight, LightFrame, LineLight, OvercastSky, ParallelogramLight, PhongLobe,
    PolygonLight, Real, Rgb, Sh9, SkyGround, SphereLight, Superellipse, Uberlight, Vec3,
    WorldPoint, WorldPolygonLight, WorldSphereLight,
};

mod rasterizer;
pub use rasterizer::*;

/// The model families, one fuzz target each.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Family {
    Hemisphere,
    Cap,
    Polygon,
    Moments,
    Sh9,
    Line,
    Shaping,
    Raster,
    RasterEdges,
}

pub const FAMILIES: [Family; 9] = [
    Family::Hemisphere,
    Family::Cap,
    Family::Polygon,
    Family::Moments,
    Family::Sh9,
    Family::Line,
    Family::Shaping,
    Family::Raster,
    Family::RasterEdges,
];

/// Reads f32 values (4 little-endian bytes each) and exponents from the fuzz input; past its
/// end it yields 0.
pub struct Input<'a> {
    data: &'a [u8],
    pos: usize,
}

impl<'a> Input<'a> {
    pub fn new(data: &'a [u8]) -> Self {
        Input { data, pos: 0 }
    }
    pub fn u32(&mut self) -> u32 {
        let mut b = [0u8; 4];
        for x in &mut b {
            *x = self.data.get(self.pos).copied().unwrap_or(0);
            self.pos += 1;
        }
        u32::from_le_bytes(b)
    }
    pub fn f32(&mut self) -> f32 {
        f32::from_bits(self.u32())
    }
    /// A fraction in `[0, 1)` from the next word.
    pub fn unit(&mut self) -> f64 {
        (self.u32() >> 8) as f64 / (1u32 << 24) as f64
    }
    /// A choice among `n`.
    pub fn below(&mut self, n: u32) -> u32 {
        self.u32() % n
    }
    /// A Phong exponent: mostly below 2048 (cheap), sometimes MAX_EXPONENT and just above it.
    pub fn m(&mut self) -> u32 {
        let raw = self.u32();
        if raw >= u32::MAX - 3 {
            arealight::phong::MAX_EXPONENT + (raw & 1)
        } else if raw >= u32::MAX - 64 {
            raw
        } else {
            raw % 2048
        }
    }
}

fn fin<T: Real>(x: T, what: &str) {
    assert!(x.is_finite(), "{what}: non-finite output {x:?}");
}
fn fin_rgb<T: Real>(c: Rgb<T>, what: &str) {
    assert!(c.is_finite(), "{what}: non-finite output {c:?}");
}

struct Src<'a, 'b> {
    inp: &'b mut Input<'a>,
}

/// `x` brought within the backend's coordinate limit (Fixed22: [-4, 4]) by a power of two,
/// when it is finite and beyond it; unchanged for the float backends.
fn fold<T: Real>(x: f64) -> f64 {
    let lim = T::COORDINATE_LIMIT;
    if !x.is_finite() || x.abs() <= lim {
        return x;
    }
    let k = (x.abs() / lim).log2().ceil() as i32;
    x * 2f64.powi(-k.min(1000))
}

impl Src<'_, '_> {
    fn s<T: Real>(&mut self) -> T {
        T::from_f64(self.inp.f32() as f64)
    }
    /// A position coordinate: the f32 value, folded into the backend's coordinate range
    /// unless its lowest bit is set (the raw value, out of range for Fixed22: refused by the
    /// constructors, saturated in the per-sample functions).
    fn ps<T: Real>(&mut self) -> T {
        let x = self.inp.f32();
        if x.to_bits() & 1 == 1 {
            T::from_f64(x as f64)
        } else {
            T::from_f64(fold::<T>(x as f64))
        }
    }
    /// A position.
    fn p<T: Real>(&mut self) -> Vec3<T> {
        Vec3::new(self.ps(), self.ps(), self.ps())
    }
    /// A Phong exponent for `T`: mostly within its limit (Fixed22: 255), sometimes above.
    fn m<T: Real>(&mut self) -> u32 {
        let m = self.inp.m();
        if m > T::MAX_PHONG_EXPONENT && m & 2 == 0 {
            m % (T::MAX_PHONG_EXPONENT + 1)
        } else {
            m
        }
    }
    fn v<T: Real>(&mut self) -> Vec3<T> {
        Vec3::new(self.s(), self.s(), self.s())
    }
    fn c<T: Real>(&mut self) -> Rgb<T> {
        Rgb::new(self.s(), self.s(), self.s())
    }
}

/// Runs one family on one input, for every backend.
pub fn run(family: Family, data: &[u8]) {
    run_t::<f64>(family, data);
    run_t::<f32>(family, data);
    run_t::<Fast32>(family, data);
    run_t::<Fixed22>(family, data);
}

std::thread_local! {
    /// Polygons that passed the constructor and reached the shading code on this thread, f64
    /// and Fixed22 runs, by vertex count (index 8: 8 or more).
    static SHADED: std::cell::Cell<[[usize; 9]; 2]> = const { std::cell::Cell::new([[0; 9]; 2]) };
}

/// The polygons of the polygon and moments families that reached the shading code on this
/// thread so far, `[f64, Fixed22]`, by vertex count (index 8: 8 or more).
pub fn shaded_counts() -> [[usize; 9]; 2] {
    SHADED.with(|c| c.get())
}

/// A planar polygon made on purpose from the input, with its shading point: the shape (convex
/// k-gon, star-shaped, regular star, L, U), the vertex count (3 to 8), an optional
/// near-degeneracy (sliver, a vanishing edge, a nearly collinear extra vertex, tiny, huge), an
/// arbitrary plane (origin, orientation, in-plane rotation, size) and the shading point
/// (anywhere, near the plane over the polygon, or near an edge). Computed in f64, then the
/// whole configuration scaled by a power of two into the backend's coordinate range and
/// rounded to `T` (planar to the constructor's tolerance, except where a degeneracy goes below
/// `T`'s resolution: then the constructor refuses, which is fine too).
pub fn planar_polygon<T: Real>(inp: &mut Input<'_>) -> (Vec<Vec3<T>>, Vec3<T>) {
    use std::f64::consts::{PI, TAU};
    let shape = inp.below(5);
    let k = 3 + inp.below(6) as usize; // 3..=8
    let mut pts: Vec<[f64; 2]> = match shape {
        // Convex: k angles with jitter.
        0 => (0..k)
            .map(|j| {
                let a = TAU * (j as f64 + 0.8 * inp.unit()) / k as f64;
                [a.cos(), a.sin()]
            })
            .collect(),
        // Star-shaped about the origin: random radii, may be non-convex.
        1 => (0..k)
            .map(|j| {
                let a = TAU * (j as f64 + 0.8 * inp.unit()) / k as f64;
                let r = 0.05 + 0.95 * inp.unit();
                [r * a.cos(), r * a.sin()]
            })
            .collect(),
        // A regular star of k / 2 spikes (k even, 6 or 8; else 4 vertices: a 2-spike "bow").
        2 => {
            let spikes = (k / 2).max(2);
            let ri = 0.05 + 0.9 * inp.unit();
            (0..2 * spikes)
                .map(|j| {
                    let a = PI * j as f64 / spikes as f64;
                    let r = if j % 2 == 0 { 1.0 } else { ri };
                    [r * a.cos(), r * a.sin()]
                })
                .collect()
        }
        // L-shape (6 vertices), the notch's depth from the input.
        3 => {
            let t = 0.05 + 0.9 * inp.unit();
            vec![
                [-0.5, -0.5],
                [0.7, -0.5],
                [0.7, -0.5 + t],
                [-0.5 + t, -0.5 + t],
                [-0.5 + t, 0.6],
                [-0.5, 0.6],
            ]
        }
        // U-shape (8 vertices, two reflex corners).
        _ => {
            let t = 0.05 + 0.9 * inp.unit();
            vec![
                [-0.6, -0.5],
                [0.6, -0.5],
                [0.6, 0.6],
                [0.3, 0.6],
                [0.3, -0.5 + t],
                [-0.3, -0.5 + t],
                [-0.3, 0.6],
                [-0.6, 0.6],
            ]
        }
    };
    // Near-degeneracies, at a scale 10^-e, e in 1..=12.
    let tiny = 10f64.powi(-(1 + inp.below(12) as i32));
    let mut scale_all = 1.0;
    match inp.below(8) {
        0 => pts.iter_mut().for_each(|q| q[1] *= tiny), // sliver
        1 => {
            // Vertex j moved to within `tiny` of vertex j + 1 (a vanishing edge).
            let j = inp.below(pts.len() as u32) as usize;
            let nx = pts[(j + 1) % pts.len()];
            pts[j] = [
                nx[0] + tiny * (pts[j][0] - nx[0]),
                nx[1] + tiny * (pts[j][1] - nx[1]),
            ];
        }
        2 if pts.len() < 8 => {
            // An extra vertex on an edge, `tiny` off the line (nearly collinear).
            let j = inp.below(pts.len() as u32) as usize;
            let (a, b) = (pts[j], pts[(j + 1) % pts.len()]);
            let mid = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
            let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
            pts.insert(j + 1, [mid[0] - tiny * dy, mid[1] + tiny * dx]);
        }
        3 => scale_all = tiny,       // tiny polygon
        4 => scale_all = 1.0 / tiny, // huge polygon (beyond f32 for e > 38: not here)
        _ => {}
    }
    // The plane: an orthonormal frame from an input direction, an in-plane rotation, origin,
    // size.
    let dir = [inp.f32() as f64, inp.f32() as f64, inp.f32() as f64];
    let len = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
    let nrm = if len.is_finite() && len > 1e-30 {
        [dir[0] / len, dir[1] / len, dir[2] / len]
    } else {
        [0.0, 0.0, 1.0]
    };
    let helper = if nrm[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let cr = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let e1 = {
        let c = cr(nrm, helper);
        let l = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
        [c[0] / l, c[1] / l, c[2] / l]
    };
    let e2 = cr(nrm, e1);
    let rot = TAU * inp.unit();
    let (c, sn) = (rot.cos(), rot.sin());
    let size = scale_all * 10f64.powf(4.0 * inp.unit() - 2.0);
    let origin = [
        size * (8.0 * inp.unit() - 4.0),
        size * (8.0 * inp.unit() - 4.0),
        size * (8.0 * inp.unit() - 4.0),
    ];
    let place = |x: f64, y: f64, h: f64| {
        let (x, y) = (c * x - sn * y, sn * x + c * y);
        [
            origin[0] + size * (x * e1[0] + y * e2[0] + h * nrm[0]),
            origin[1] + size * (x * e1[1] + y * e2[1] + h * nrm[1]),
            origin[2] + size * (x * e1[2] + y * e2[2] + h * nrm[2]),
        ]
    };
    let verts: Vec<[f64; 3]> = pts.iter().map(|q| place(q[0], q[1], 0.0)).collect();
    // The shading point: off the plane at a height from 10^-9 to 10 sizes, over the polygon's
    // first vertex, near an edge's midpoint, or anywhere near.
    let h = 10f64.powf(10.0 * inp.unit() - 9.0) * if inp.below(2) == 0 { 1.0 } else { -1.0 };
    let p = match inp.below(4) {
        0 => place(0.0, 0.0, h),
        1 => place(pts[0][0], pts[0][1], h),
        2 => {
            let (a, b) = (pts[0], pts[1 % pts.len()]);
            place(0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), h)
        }
        _ => place(
            4.0 * inp.unit() - 2.0,
            4.0 * inp.unit() - 2.0,
            4.0 * inp.unit() - 2.0,
        ),
    };
    // The whole configuration into the backend's coordinate range (a power of two: exact).
    let big = verts
        .iter()
        .chain(std::iter::once(&p))
        .flat_map(|q| q.iter())
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let k2 = if big > T::COORDINATE_LIMIT && big.is_finite() {
        2f64.powi(-((big / T::COORDINATE_LIMIT).log2().ceil() as i32))
    } else {
        1.0
    };
    let to_t = |q: [f64; 3]| {
        Vec3::new(
            T::from_f64(q[0] * k2),
            T::from_f64(q[1] * k2),
            T::from_f64(q[2] * k2),
        )
    };
    (verts.iter().map(|&q| to_t(q)).collect(), to_t(p))
}

pub fn run_t<T: Real>(family: Family, data: &[u8]) {
    let mut inp = Input::new(data);
    let mut s = Src { inp: &mut inp };
    match family {
        Family::Hemisphere => {
            let (axis, n, c) = (s.v::<T>(), s.v::<T>(), s.s::<T>());
            let m = s.m::<T>();
            if let Ok(h) = HemisphereLight::new(axis) {
                fin(h.lambert_const(n), "hemi_const");
                fin(h.lambert_cos(n), "hemi_cos");
                if let Ok(l) = PhongLobe::<T>::new(m) {
                    fin(h.phong_const(&l, n), "phong_hemi_const");
                    fin(h.phong_cos(&l, n), "phong_hemi_cos");
                }
            }
            if let Ok(sky) = OvercastSky::new(axis, c) {
                fin(sky.lambert(n), "sky_overcast");
            }
            let (a, b) = (s.c::<T>(), s.c::<T>());
            if let Ok(sg) = SkyGround::new(axis, a, b) {
                fin_rgb(sg.irradiance(n), "sky_ground");
            }
        }
        Family::Cap => {
            let (axis, sigma, n, p) = (s.v::<T>(), s.s::<T>(), s.v::<T>(), s.p::<T>());
            let (center, radius) = (s.p::<T>(), s.ps::<T>());
            let m = s.m::<T>();
            let lobe = PhongLobe::<T>::new(m).ok();
            if let Ok(c) = CapLight::new(axis, sigma) {
                fin(c.lambert(n), "cap_lambert");
                fin(c.lambert_hermite(n), "cap_lambert_hermite");
                fin(c.lambert_hermite_cos(n), "cap_lambert_hermite_cos");
                if let Some(l) = &lobe {
                    fin(c.phong(l, n), "phong_cap");
                }
            }
            // The same sphere in world coordinates (any finite radius below 2^30).
            let world = (
                WorldPoint::from_vec3(center, "center"),
                WorldPoint::from_vec3(p, "p"),
            );
            if let (Ok(c), Ok(pw)) = world {
                if let Ok(sp) = WorldSphereLight::<T>::new(c, radius.to_f64()) {
                    fin(sp.lambert(pw, n), "world sphere_lambert");
                    fin(sp.lambert_hermite(pw, n), "world sphere_lambert_hermite");
                    if let Ok(x) = sp.try_lambert(pw, n) {
                        fin(x, "world try_lambert");
                    }
                    if let Some(l) = &lobe {
                        fin(sp.phong(l, pw, n), "world phong_sphere");
                    }
                }
            }
            if let Ok(sp) = SphereLight::new(center, radius) {
                fin(sp.lambert(p, n), "sphere_lambert");
                fin(sp.lambert_hermite(p, n), "sphere_lambert_hermite");
                if let Ok(x) = sp.try_lambert(p, n) {
                    fin(x, "try_lambert");
                }
                if let Some(l) = &lobe {
                    fin(sp.phong(l, p, n), "phong_sphere");
                    if let Ok(x) = sp.try_phong(l, p, n) {
                        fin(x, "try_phong");
                    }
                }
            }
        }
        Family::Polygon | Family::Moments => {
            // Raw vertices (one case in four), else a planar polygon made on purpose.
            let (verts, p) = if s.inp.below(4) == 0 {
                let nv = 3 + s.inp.below(6) as usize;
                let verts: Vec<Vec3<T>> = (0..nv).map(|_| s.p::<T>()).collect();
                (verts, s.p::<T>())
            } else {
                planar_polygon::<T>(s.inp)
            };
            let (n, w, e) = (s.v::<T>(), s.v::<T>(), s.v::<T>());
            let m = s.m::<T>();
            let tol = s.s::<T>();
            let Ok(pl) = PolygonLight::<T, 8>::new(&verts) else {
                // Also the constructor on the raw vertices with a small capacity.
                let _ = PolygonLight::<T, 3>::new(&verts);
                return;
            };
            let backend = match std::any::type_name::<T>() {
                "f64" => Some(0),
                "arealight::real::fixed22::Fixed22" => Some(1),
                _ => None,
            };
            if let Some(b) = backend {
                SHADED.with(|c| {
                    let mut n = c.get();
                    n[b][verts.len().min(8)] += 1;
                    c.set(n);
                });
            }
            if family == Family::Polygon {
                // The same polygon in world coordinates.
                let wv: Result<Vec<WorldPoint>, _> = verts
                    .iter()
                    .map(|&v| WorldPoint::from_vec3(v, "verts"))
                    .collect();
                if let (Ok(wv), Ok(pw)) = (wv, WorldPoint::from_vec3(p, "p")) {
                    if let Ok(wl) = WorldPolygonLight::<T, 8>::new(&wv) {
                        fin(wl.lambert(pw, n), "world polygon_lambert");
                        if let Ok(x) = wl.try_lambert(pw, n) {
                            fin(x, "world try_lambert");
                        }
                        if let Ok(l) = PhongLobe::<T>::new(m) {
                            fin(wl.phong(&l, pw, n), "world phong_polygon");
                        }
                    }
                }
                fin(pl.lambert(p, n), "polygon_lambert");
                fin(pl.clipped_solid_angle(p, n), "clipped_solid_angle");
                if let Ok(x) = pl.try_lambert(p, n) {
                    fin(x, "try_lambert");
                }
                if let Ok(l) = PhongLobe::<T>::new(m) {
                    fin(pl.phong(&l, p, n), "phong_polygon");
                    // odd_only(m) evaluates m | 1, which may exceed the backend's limit.
                    if let Ok(l2) = PhongLobe::<T>::odd_only(m) {
                        fin(pl.phong(&l2, p, n), "phong_polygon odd_only");
                    }
                }
            } else {
                // Keep the cost bounded (m <= 4096); exponents above MAX_EXPONENT are refused.
                let m = if m > arealight::phong::MAX_EXPONENT {
                    m
                } else {
                    m.min(4096)
                };
                fin(pl.axial_moment(p, w, m), "axial_moment");
                fin(pl.axial_moment_within(p, w, m, tol), "axial_moment_within");
                fin(pl.double_axis_moment(p, w, e, m), "double_axis_moment");
                fin(
                    pl.double_axis_moment_within(p, w, e, m, tol),
                    "double_axis_moment_within",
                );
                fin(
                    pl.directional_luminaire(p, n, w, m),
                    "directional_luminaire",
                );
                fin(pl.glossy_reflection(p, n, e, m), "glossy_reflection");
                fin(pl.glossy_transmission(p, n, e, m), "glossy_transmission");
                fin(lune_normalization(w, e, m), "lune_normalization");
                if let Ok(x) = try_lune_normalization(w, e, m) {
                    fin(x, "try_lune_normalization");
                }
            }
        }
        Family::Sh9 => {
            let coeffs: [Rgb<T>; 9] = core::array::from_fn(|_| s.c::<T>());
            let (dir, axis, alpha, center, radius, p, n) = (
                s.v::<T>(),
                s.v::<T>(),
                s.s::<T>(),
                s.p::<T>(),
                s.ps::<T>(),
                s.p::<T>(),
                s.v::<T>(),
            );
            let col = s.c::<T>();
            let mut envs = Vec::new();
            envs.extend(Sh9::new(coeffs).ok());
            envs.extend(Sh9::directional(dir, col).ok());
            envs.extend(Sh9::disc(axis, alpha, col).ok());
            envs.extend(Sh9::sphere(center, radius, p, col).ok());
            envs.extend(Sh9::hemisphere(axis, col).ok());
            envs.extend(Sh9::sky_ground(axis, col, coeffs[0]).ok());
            for env in &envs {
                fin_rgb(env.prepare().irradiance(n), "sh9_irradiance");
                fin_rgb(env.plus(env).prepare().irradiance(n), "sh9 plus");
            }
        }
        Family::Line => {
            let (a, b, p, n, r) = (s.p::<T>(), s.p::<T>(), s.p::<T>(), s.v::<T>(), s.v::<T>());
            let (eu, ev) = (s.p::<T>(), s.p::<T>());
            let m = s.m::<T>();
            let k = s.inp.u32() % 6;
            let _ = Decay::new(k);
            let lobe = PhongLobe::<T>::new(m).ok();
            if let Ok(line) = LineLight::new(a, b) {
                for d in [
                    Decay::Constant,
                    Decay::Inverse,
                    Decay::InverseSquare,
                    Decay::InverseCube,
                ] {
                    fin(line.lambert(p, n, d), "line_lambert");
                    if let Ok(x) = line.try_lambert(p, n, d) {
                        fin(x, "try line_lambert");
                    }
                }
                if let Some(l) = &lobe {
                    fin(line.phong_peak(l, p, r), "line_phong_peak");
                }
            }
            if let (Ok(pg), Some(l)) = (ParallelogramLight::new(a, eu, ev), &lobe) {
                fin(pg.phong_peak(l, p, r), "rect_phong_peak");
            }
        }
        Family::Shaping => {
            let se = [
                s.ps::<T>(),
                s.ps::<T>(),
                s.ps::<T>(),
                s.ps::<T>(),
                s.ps::<T>(),
            ];
            let fo = [
                s.ps::<T>(),
                s.ps::<T>(),
                s.ps::<T>(),
                s.ps::<T>(),
                s.ps::<T>(),
                s.ps::<T>(),
                s.ps::<T>(),
            ];
            let (origin, dir, up, pos) = (s.p::<T>(), s.v::<T>(), s.v::<T>(), s.p::<T>());
            let z = s.ps::<T>();
            let shape = Superellipse::new(se[0], se[1], se[2], se[3], se[4]);
            if let Ok(sh) = &shape {
                fin(sh.shape(pos), "superellipse_shape");
            }
            let falloff = DistanceFalloff::new(fo[0], fo[1], fo[2], fo[3], fo[4], fo[5], fo[6]);
            if let Ok(f) = &falloff {
                fin(f.falloff(z), "distance_falloff");
            }
            let frame = LightFrame::new(origin, dir, up);
            if let Ok(fr) = &frame {
                let l = fr.to_light(pos);
                let _ = l;
            }
            if let (Ok(fr), Ok(sh), Ok(f)) = (frame, shape, falloff) {
                fin(Uberlight::new(fr, sh, f).factor(pos), "uberlight factor");
            }
        }
        Family::Raster => raster::<T>(&mut s),
        // Integer only: once per input, not per backend.
        Family::RasterEdges if T::EPSILON.to_f64() < 1e-10 => raster_edges(s.inp),
        Family::RasterEdges => {}
    }
}
