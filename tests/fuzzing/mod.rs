//! The fuzz targets' bodies, shared by the bit-pattern harness `tests/fuzz_bits.rs` (runs in
//! `cargo test`) and the cargo-fuzz crate `fuzz/` (libFuzzer, nightly): every public
//! constructor and per-sample function of one model family, fed arbitrary f32 bit patterns
//! (NaN, infinities, subnormals, huge values) and exponents, on f64 (the same values widened),
//! f32 and Fast32. A target fails (panics) if the library panics or a per-sample function
//! returns NaN or infinity.
#![allow(dead_code)]

use arealight::{
    lune_normalization, try_lune_normalization, CapLight, Decay, DistanceFalloff, Fast32,
    HemisphereLight, LightFrame, LineLight, OvercastSky, ParallelogramLight, PhongLobe,
    PolygonLight, Real, Rgb, Sh9, SkyGround, SphereLight, Superellipse, Uberlight, Vec3,
};

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
}

pub const FAMILIES: [Family; 7] = [
    Family::Hemisphere,
    Family::Cap,
    Family::Polygon,
    Family::Moments,
    Family::Sh9,
    Family::Line,
    Family::Shaping,
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

impl Src<'_, '_> {
    fn s<T: Real>(&mut self) -> T {
        T::from_f64(self.inp.f32() as f64)
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
}

pub fn run_t<T: Real>(family: Family, data: &[u8]) {
    let mut inp = Input::new(data);
    let mut s = Src { inp: &mut inp };
    match family {
        Family::Hemisphere => {
            let (axis, n, c) = (s.v::<T>(), s.v::<T>(), s.s::<T>());
            let m = s.inp.m();
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
            let (axis, sigma, n, p) = (s.v::<T>(), s.s::<T>(), s.v::<T>(), s.v::<T>());
            let (center, radius) = (s.v::<T>(), s.s::<T>());
            let m = s.inp.m();
            let lobe = PhongLobe::<T>::new(m).ok();
            if let Ok(c) = CapLight::new(axis, sigma) {
                fin(c.lambert(n), "cap_lambert");
                fin(c.lambert_hermite(n), "cap_lambert_hermite");
                fin(c.lambert_hermite_cos(n), "cap_lambert_hermite_cos");
                if let Some(l) = &lobe {
                    fin(c.phong(l, n), "phong_cap");
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
            let nv = 3 + (s.inp.u32() % 6) as usize;
            let verts: Vec<Vec3<T>> = (0..nv).map(|_| s.v::<T>()).collect();
            let (p, n, w, e) = (s.v::<T>(), s.v::<T>(), s.v::<T>(), s.v::<T>());
            let m = s.inp.m();
            let tol = s.s::<T>();
            let Ok(pl) = PolygonLight::<T, 8>::new(&verts) else {
                // Also the constructor on the raw vertices with a small capacity.
                let _ = PolygonLight::<T, 3>::new(&verts);
                return;
            };
            if family == Family::Polygon {
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
                s.v::<T>(),
                s.s::<T>(),
                s.v::<T>(),
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
            let (a, b, p, n, r) = (s.v::<T>(), s.v::<T>(), s.v::<T>(), s.v::<T>(), s.v::<T>());
            let (eu, ev) = (s.v::<T>(), s.v::<T>());
            let m = s.inp.m();
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
            let se = [s.s::<T>(), s.s::<T>(), s.s::<T>(), s.s::<T>(), s.s::<T>()];
            let fo = [
                s.s::<T>(),
                s.s::<T>(),
                s.s::<T>(),
                s.s::<T>(),
                s.s::<T>(),
                s.s::<T>(),
                s.s::<T>(),
            ];
            let (origin, dir, up, pos) = (s.v::<T>(), s.v::<T>(), s.v::<T>(), s.v::<T>());
            let z = s.s::<T>();
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
    }
}
