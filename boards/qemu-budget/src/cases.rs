//! The measured cases of the cost/accuracy budget, shared by the QEMU firmware and `host-sim`.
//!
//! `no_std`, generic over [`Real`]: the firmware instantiates it for its backends and counts
//! instructions; `host-sim` includes this file (`#[path]`) and evaluates the same kernels in
//! `f64` for the reference values and in every backend for host timing and errors.
//!
//! Every model id of `models.md` has one kernel, `k_<id>`: a non-inlined function taking the
//! prepared light (built once, outside the measurement) and the per-sample inputs, calling the
//! library's per-sample function once. A measured "call" is a call of that kernel. The lights
//! are fixed per model; the per-sample inputs come from a direction source ([`Dirs`]): the
//! firmware uses [`ring`], 16 directions sweeping every case of each formula (lit, terminator,
//! unlit), and `host-sim budget` uses random unit directions.

use arealight::{
    lune_normalization, CapLight, Decay, DistanceFalloff, Environment, HemisphereLight, LineLight,
    OvercastSky, ParallelogramLight, PhongLobe, PolygonLight, Real, Rgb, Sh9, Sh9Irradiance,
    SkyGround, SphereLight, Superellipse, UnitVec3, Vec3,
};

/// The Phong exponent of every Phong-type case.
pub const PHONG_M: u32 = 16;
/// The moment order of Arvo's moment cases (axial, double-axis, luminaire, lune).
pub const MOMENT_M: u32 = 4;
/// Picott's decay exponent of the `line_lambert` case.
pub const LINE_K: u32 = 2;
/// The number of directions of [`ring`].
pub const RING: usize = 16;
/// The vertices of the polygon cases' light: a 2 x 2 square in the plane z = 2, above the
/// shading point (the origin).
pub const QUAD: [[f64; 3]; 4] = [
    [-1.0, -1.0, 2.0],
    [1.0, -1.0, 2.0],
    [1.0, 1.0, 2.0],
    [-1.0, 1.0, 2.0],
];

/// Every model id of `models.md`, in the order of the tables there.
pub const MODELS: [&str; 27] = [
    "hemi_const",
    "hemi_cos",
    "sky_overcast",
    "sky_ground",
    "cap_lambert",
    "cap_lambert_hermite",
    "sphere_lambert",
    "sphere_lambert_hermite",
    "polygon_lambert",
    "line_lambert",
    "phong_hemi_const",
    "phong_hemi_cos",
    "phong_cap",
    "phong_sphere",
    "phong_polygon",
    "line_phong_peak",
    "rect_phong_peak",
    "axial_moment",
    "double_axis_moment",
    "directional_luminaire",
    "glossy_reflection",
    "glossy_transmission",
    "lune_normalization",
    "sh9_irradiance",
    "sh9_disc_irradiance",
    "superellipse_shape",
    "distance_falloff",
];

/// The model ids the fixed-point backend (`arealight::Fixed22`) answers.
pub use arealight::real::fixed22::SUPPORTED_MODELS as FIXED_MODELS;

/// Whether the backend named `backend` evaluates `model` (`fixed`: [`FIXED_MODELS`] only).
pub fn supports(backend: &str, model: &str) -> bool {
    backend != "fixed" || FIXED_MODELS.contains(&model)
}

/// `a == b` for strings, usable in constants (the model lists, `QEMU_BUDGET_PART`).
pub(crate) const fn str_eq(a: &str, b: &str) -> bool {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    if a.len() != b.len() {
        return false;
    }
    let mut i = 0;
    while i < a.len() {
        if a[i] != b[i] {
            return false;
        }
        i += 1;
    }
    true
}

/// `FIXED_OK[i]`: model `MODELS[i]` is one of [`FIXED_MODELS`] (evaluated at compile time, so
/// the fixed-point build links no kernel it does not run).
pub const FIXED_OK: [bool; 27] = {
    let mut out = [false; 27];
    let mut i = 0;
    while i < MODELS.len() {
        let mut j = 0;
        while j < FIXED_MODELS.len() {
            if str_eq(MODELS[i], FIXED_MODELS[j]) {
                out[i] = true;
            }
            j += 1;
        }
        i += 1;
    }
    out
};

/// A backend of the budget: a [`Real`] with its name.
pub trait Backend: Real {
    /// Its name in the harness's output and in the budget.
    const NAME: &'static str;
    /// Fixed point: evaluates [`FIXED_MODELS`] only.
    const FIXED: bool = false;
}

impl Backend for f64 {
    const NAME: &'static str = "f64";
}
impl Backend for f32 {
    const NAME: &'static str = "f32";
}
impl Backend for arealight::Fast32 {
    const NAME: &'static str = "f32-fast";
}
impl Backend for arealight::Fixed22 {
    const NAME: &'static str = "fixed";
    const FIXED: bool = true;
}

/// The `i`-th of [`RING`] directions: a half circle from +z through (0.8, 0.6, 0) to -z,
/// avoiding the poles, so every light's lit side, terminator and unlit side are all sampled.
pub fn ring(i: usize) -> [f64; 3] {
    let t = (i as f64 + 0.5) / RING as f64 * core::f64::consts::PI;
    let (s, c) = (libm::sin(t), libm::cos(t));
    [0.8 * s, 0.6 * s, c]
}

/// A source of per-sample directions: how many, and the `i`-th (unit length).
#[derive(Clone, Copy)]
pub struct Dirs<'a> {
    /// How many directions.
    pub count: usize,
    /// The `i`-th direction.
    pub get: &'a dyn Fn(usize) -> [f64; 3],
}

/// The ring of [`RING`] directions ([`ring`]) as a [`Dirs`]: every run's inputs.
pub fn ring_dirs() -> Dirs<'static> {
    Dirs {
        count: RING,
        get: &ring,
    }
}

/// Counts (or times) one kernel call.
pub trait Meter {
    /// Calls `f` (once on the target; the host may repeat it) and returns its result with the
    /// instructions (or nanoseconds) one call took, or 0 where nothing is counted.
    fn call<R>(&mut self, f: impl Fn() -> R) -> (R, u32);
}

/// One measured call: which case, the value (1 or 3 channels, in f64) and its count.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Index into [`MODELS`].
    pub model: usize,
    /// Index of the input direction.
    pub input: usize,
    /// The result; only the first `channels` entries are meaningful.
    pub value: [f64; 3],
    /// 1 for scalar models, 3 for the RGB ones.
    pub channels: usize,
    /// What the meter reported.
    pub count: u32,
}

/// Why a case could not run: a light's constructor refused its (fixed) parameters. This
/// happens only if the backend cannot represent them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CaseError {
    /// Index into [`MODELS`].
    pub model: usize,
    /// The library's error.
    pub error: arealight::Error,
}

/// The fixed lights of the cases, built once per backend.
pub struct Lights<T: Real> {
    hemi: HemisphereLight<T>,
    sky: OvercastSky<T>,
    sky_ground: SkyGround<T>,
    cap: CapLight<T>,
    sphere: SphereLight<T>,
    quad: PolygonLight<T, 8>,
    line: LineLight<T>,
    rect: ParallelogramLight<T>,
    lobe: PhongLobe<T>,
    sh9: Sh9Irradiance<T>,
    disc: Sh9Irradiance<T>,
    shape: Superellipse<T>,
    falloff: DistanceFalloff<T>,
    /// The shading point of the positional lights (the origin).
    pub p: Vec3<T>,
    /// +z.
    pub z: Vec3<T>,
    /// The eye direction of `glossy_reflection`.
    pub eye: Vec3<T>,
    /// The eye direction of `glossy_transmission` (below the surface).
    pub eye_below: Vec3<T>,
    /// The luminaire axis of `directional_luminaire` (pointing down, at the shading point).
    pub down: Vec3<T>,
}

impl<T: Real> Lights<T> {
    /// Builds every light; parameters pass through `round` first (the host rounds them to the
    /// backend under test so that its f64 reference sees the same inputs).
    ///
    /// # Errors
    /// The first constructor that refuses its parameters, with its model.
    pub fn new(round: fn(f64) -> f64) -> Result<Self, CaseError> {
        let s = |x: f64| T::from_f64(round(x));
        let v = |x: f64, y: f64, z: f64| Vec3::new(s(x), s(y), s(z));
        let rgb = |r: f64, g: f64, b: f64| Rgb::from_f64([round(r), round(g), round(b)]);
        let err = |model: &str| {
            let model = MODELS.iter().position(|m| *m == model).unwrap_or(0);
            move |error| CaseError { model, error }
        };
        let z = v(0.0, 0.0, 1.0);
        let quad = QUAD.map(|[x, y, z]| v(x, y, z));
        let sh9 = Sh9::<T>::environment(Environment::GraceCathedral).prepare();
        Ok(Lights {
            hemi: HemisphereLight::new(z).map_err(err("hemi_const"))?,
            sky: OvercastSky::new(z, s(1.0)).map_err(err("sky_overcast"))?,
            sky_ground: SkyGround::new(z, rgb(0.5, 0.5, 1.0), rgb(0.2, 1.0, 0.2))
                .map_err(err("sky_ground"))?,
            cap: CapLight::new(z, s(0.4)).map_err(err("cap_lambert"))?,
            sphere: SphereLight::new(v(0.0, 0.0, 3.0), s(1.0)).map_err(err("sphere_lambert"))?,
            quad: PolygonLight::new(&quad).map_err(err("polygon_lambert"))?,
            line: LineLight::new(v(-1.0, 0.0, 2.0), v(1.0, 0.5, 2.0))
                .map_err(err("line_lambert"))?,
            rect: ParallelogramLight::new(v(-1.0, -1.0, 2.0), v(2.0, 0.0, 0.0), v(0.0, 2.0, 0.0))
                .map_err(err("rect_phong_peak"))?,
            lobe: PhongLobe::new(PHONG_M).map_err(err("phong_cap"))?,
            sh9,
            disc: Sh9::disc(z, s(0.5), Rgb::splat(T::ONE))
                .map_err(err("sh9_disc_irradiance"))?
                .prepare(),
            shape: Superellipse::new(s(0.3), s(0.2), s(0.5), s(0.4), s(0.5))
                .map_err(err("superellipse_shape"))?,
            falloff: DistanceFalloff::new(s(2.0), s(1.0), s(2.0), s(0.5), s(8.0), s(0.25), s(2.0))
                .map_err(err("distance_falloff"))?,
            p: v(0.0, 0.0, 0.0),
            z,
            eye: v(0.3, 0.0, 1.0),
            eye_below: v(0.1, 0.2, -1.0),
            down: v(0.0, 0.0, -1.0),
        })
    }
}

// The kernels: one per model, never inlined, so that a call is a call and each has a symbol
// (`k_<id>::<T>`) whose size the harness reads.

macro_rules! kernel {
    ($name:ident, |$l:ident, $d:ident| -> $out:ty $body:block) => {
        #[doc = concat!("One call of the `", stringify!($name), "` case (see the module docs).")]
        #[inline(never)]
        pub fn $name<T: Real>($l: &Lights<T>, $d: Vec3<T>) -> $out $body
    };
}

kernel!(k_hemi_const, |l, d| -> T { l.hemi.lambert_const(d) });
kernel!(k_hemi_cos, |l, d| -> T { l.hemi.lambert_cos(d) });
kernel!(k_sky_overcast, |l, d| -> T { l.sky.lambert(d) });
kernel!(k_sky_ground, |l, d| -> Rgb<T> {
    l.sky_ground.irradiance(d)
});
kernel!(k_cap_lambert, |l, d| -> T { l.cap.lambert(d) });
kernel!(k_cap_lambert_hermite, |l, d| -> T {
    l.cap.lambert_hermite(d)
});
kernel!(k_sphere_lambert, |l, d| -> T { l.sphere.lambert(l.p, d) });
kernel!(k_sphere_lambert_hermite, |l, d| -> T {
    l.sphere.lambert_hermite(l.p, d)
});
kernel!(k_polygon_lambert, |l, d| -> T { l.quad.lambert(l.p, d) });
kernel!(k_line_lambert, |l, d| -> T {
    match Decay::new(LINE_K) {
        Ok(k) => l.line.lambert(l.p, d, k),
        Err(_) => T::ZERO,
    }
});
kernel!(k_phong_hemi_const, |l, d| -> T {
    l.hemi.phong_const(&l.lobe, d)
});
kernel!(k_phong_hemi_cos, |l, d| -> T {
    l.hemi.phong_cos(&l.lobe, d)
});
kernel!(k_phong_cap, |l, d| -> T { l.cap.phong(&l.lobe, d) });
kernel!(k_phong_sphere, |l, d| -> T {
    l.sphere.phong(&l.lobe, l.p, d)
});
kernel!(k_phong_polygon, |l, d| -> T {
    l.quad.phong(&l.lobe, l.p, d)
});
kernel!(k_line_phong_peak, |l, d| -> T {
    l.line.phong_peak(&l.lobe, l.p, d)
});
kernel!(k_rect_phong_peak, |l, d| -> T {
    l.rect.phong_peak(&l.lobe, l.p, d)
});
kernel!(k_axial_moment, |l, d| -> T {
    l.quad.axial_moment(l.p, d, MOMENT_M)
});
kernel!(k_double_axis_moment, |l, d| -> T {
    l.quad.double_axis_moment(l.p, d, l.z, MOMENT_M)
});
kernel!(k_directional_luminaire, |l, d| -> T {
    l.quad.directional_luminaire(l.p, d, l.down, MOMENT_M)
});
kernel!(k_glossy_reflection, |l, d| -> T {
    l.quad.glossy_reflection(l.p, d, l.eye, PHONG_M)
});
kernel!(k_glossy_transmission, |l, d| -> T {
    l.quad.glossy_transmission(l.p, d, l.eye_below, PHONG_M)
});
kernel!(k_lune_normalization, |l, d| -> T {
    lune_normalization(d, l.z, MOMENT_M)
});
kernel!(k_sh9_irradiance, |l, d| -> Rgb<T> { l.sh9.irradiance(d) });
kernel!(k_sh9_disc_irradiance, |l, d| -> T {
    l.disc.irradiance(d).r
});
// The shaping cases map the direction to a point in front of the light / a distance.
kernel!(k_superellipse_shape, |l, d| -> T { l.shape.shape(d) });
kernel!(k_distance_falloff, |l, d| -> T { l.falloff.falloff(d.z) });

/// The per-sample input of model `model` for direction `d`: the direction itself (a normal,
/// a reflection direction or a moment axis), except for the shaping models, which take a
/// point in front of the light (`superellipse_shape`, up to 45 degrees off the beam) and a
/// distance along the beam in [0.05, 10] (`distance_falloff`, carried in z).
pub fn input<T: Real>(model: usize, d: [f64; 3], round: fn(f64) -> f64) -> Vec3<T> {
    let d = match MODELS.get(model).copied() {
        Some("superellipse_shape") => [d[0], d[1], 1.0],
        Some("distance_falloff") => [0.0, 0.0, 0.05 + 9.95 * 0.5 * (d[2] + 1.0)],
        _ => d,
    };
    Vec3::from_f64(d.map(round))
}

/// Runs model `model` over every direction of `dirs`, with each call going through `meter`,
/// and hands each sample to `out`. Does nothing for a model the backend does not support.
pub fn run_model<T: Backend, M: Meter>(
    lights: &Lights<T>,
    model: usize,
    dirs: Dirs,
    round: fn(f64) -> f64,
    meter: &mut M,
    out: &mut impl FnMut(Sample),
) {
    macro_rules! go {
        ($k:ident) => {
            go!($k, |r: T| ([r.to_f64(), 0.0, 0.0], 1))
        };
        ($k:ident, rgb) => {
            go!($k, |r: Rgb<T>| (r.to_f64(), 3))
        };
        ($k:ident, $conv:expr) => {
            for i in 0..dirs.count {
                // A constant per instantiation and arm: unsupported kernels are never linked.
                if T::FIXED && !FIXED_OK[ARM] {
                    break;
                }
                let d = core::hint::black_box(input::<T>(model, (dirs.get)(i), round));
                let l = core::hint::black_box(lights);
                let (r, count) = meter.call(|| $k(l, d));
                let (value, channels) = ($conv)(r);
                out(Sample {
                    model,
                    input: i,
                    value,
                    channels,
                    count,
                });
            }
        };
    }
    match model {
        0 => {
            const ARM: usize = 0;
            go!(k_hemi_const)
        }
        1 => {
            const ARM: usize = 1;
            go!(k_hemi_cos)
        }
        2 => {
            const ARM: usize = 2;
            go!(k_sky_overcast)
        }
        3 => {
            const ARM: usize = 3;
            go!(k_sky_ground, rgb)
        }
        4 => {
            const ARM: usize = 4;
            go!(k_cap_lambert)
        }
        5 => {
            const ARM: usize = 5;
            go!(k_cap_lambert_hermite)
        }
        6 => {
            const ARM: usize = 6;
            go!(k_sphere_lambert)
        }
        7 => {
            const ARM: usize = 7;
            go!(k_sphere_lambert_hermite)
        }
        8 => {
            const ARM: usize = 8;
            go!(k_polygon_lambert)
        }
        9 => {
            const ARM: usize = 9;
            go!(k_line_lambert)
        }
        10 => {
            const ARM: usize = 10;
            go!(k_phong_hemi_const)
        }
        11 => {
            const ARM: usize = 11;
            go!(k_phong_hemi_cos)
        }
        12 => {
            const ARM: usize = 12;
            go!(k_phong_cap)
        }
        13 => {
            const ARM: usize = 13;
            go!(k_phong_sphere)
        }
        14 => {
            const ARM: usize = 14;
            go!(k_phong_polygon)
        }
        15 => {
            const ARM: usize = 15;
            go!(k_line_phong_peak)
        }
        16 => {
            const ARM: usize = 16;
            go!(k_rect_phong_peak)
        }
        17 => {
            const ARM: usize = 17;
            go!(k_axial_moment)
        }
        18 => {
            const ARM: usize = 18;
            go!(k_double_axis_moment)
        }
        19 => {
            const ARM: usize = 19;
            go!(k_directional_luminaire)
        }
        20 => {
            const ARM: usize = 20;
            go!(k_glossy_reflection)
        }
        21 => {
            const ARM: usize = 21;
            go!(k_glossy_transmission)
        }
        22 => {
            const ARM: usize = 22;
            go!(k_lune_normalization)
        }
        23 => {
            const ARM: usize = 23;
            go!(k_sh9_irradiance, rgb)
        }
        24 => {
            const ARM: usize = 24;
            go!(k_sh9_disc_irradiance)
        }
        25 => {
            const ARM: usize = 25;
            go!(k_superellipse_shape)
        }
        26 => {
            const ARM: usize = 26;
            go!(k_distance_falloff)
        }
        _ => {}
    }
}

/// The cases whose per-sample direction is a normal or a reflection direction, counted a
/// second time with that direction as a [`UnitVec3`] (normalized once, before the count, as a
/// renderer hands it to every light): `(row name, index into MODELS)`. The answers are the
/// same bits as the `V` lines' (the call normalizes a `Vec3` and then runs the same code).
pub const UNIT_CASES: [(&str, usize); 9] = [
    ("hemi_const/unit", 0),
    ("sky_ground/unit", 3),
    ("cap_lambert/unit", 4),
    ("cap_lambert_hermite/unit", 5),
    ("sphere_lambert/unit", 6),
    ("polygon_lambert/unit", 8),
    ("phong_cap/unit", 12),
    ("phong_polygon/unit", 14),
    ("sh9_irradiance/unit", 23),
];

macro_rules! unit_kernel {
    ($name:ident, |$l:ident, $d:ident| -> $out:ty $body:block) => {
        #[doc = concat!("One call of `", stringify!($name), "` with a unit direction.")]
        #[inline(never)]
        pub fn $name<T: Real>($l: &Lights<T>, $d: UnitVec3<T>) -> $out $body
    };
}

unit_kernel!(u_hemi_const, |l, d| -> T { l.hemi.lambert_const(d) });
unit_kernel!(u_sky_ground, |l, d| -> Rgb<T> {
    l.sky_ground.irradiance(d)
});
unit_kernel!(u_cap_lambert, |l, d| -> T { l.cap.lambert(d) });
unit_kernel!(u_cap_lambert_hermite, |l, d| -> T {
    l.cap.lambert_hermite(d)
});
unit_kernel!(u_sphere_lambert, |l, d| -> T { l.sphere.lambert(l.p, d) });
unit_kernel!(u_polygon_lambert, |l, d| -> T { l.quad.lambert(l.p, d) });
unit_kernel!(u_phong_cap, |l, d| -> T { l.cap.phong(&l.lobe, d) });
unit_kernel!(u_phong_polygon, |l, d| -> T {
    l.quad.phong(&l.lobe, l.p, d)
});
unit_kernel!(u_sh9_irradiance, |l, d| -> Rgb<T> { l.sh9.irradiance(d) });

/// Runs unit case `case` (an index into [`UNIT_CASES`]) over every direction of `dirs` as
/// [`run_model`] does, the direction normalized into a [`UnitVec3`] before the count; the
/// samples carry the model's index.
pub fn run_unit<T: Backend, M: Meter>(
    lights: &Lights<T>,
    case: usize,
    dirs: Dirs,
    round: fn(f64) -> f64,
    meter: &mut M,
    out: &mut impl FnMut(Sample),
) {
    let Some(&(_, model)) = UNIT_CASES.get(case) else {
        return;
    };
    macro_rules! go {
        ($k:ident) => {
            go!($k, |r: T| ([r.to_f64(), 0.0, 0.0], 1))
        };
        ($k:ident, rgb) => {
            go!($k, |r: Rgb<T>| (r.to_f64(), 3))
        };
        ($k:ident, $conv:expr) => {
            for i in 0..dirs.count {
                let d = input::<T>(model, (dirs.get)(i), round);
                // The ring's directions are nonzero: every one has a unit vector.
                let Some(u) = d.to_unit() else {
                    continue;
                };
                let u = core::hint::black_box(u);
                let l = core::hint::black_box(lights);
                let (r, count) = meter.call(|| $k(l, u));
                let (value, channels) = ($conv)(r);
                out(Sample {
                    model,
                    input: i,
                    value,
                    channels,
                    count,
                });
            }
        };
    }
    match case {
        0 => go!(u_hemi_const),
        1 => go!(u_sky_ground, rgb),
        2 => go!(u_cap_lambert),
        3 => go!(u_cap_lambert_hermite),
        4 => go!(u_sphere_lambert),
        5 => go!(u_polygon_lambert),
        6 => go!(u_phong_cap),
        7 => go!(u_phong_polygon),
        8 => go!(u_sh9_irradiance, rgb),
        _ => {}
    }
}
