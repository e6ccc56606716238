//! The world-coordinate cases of the budget (issue 13): the positional lights of [`cases`]
//! as [`WorldSphereLight`] and [`WorldPolygonLight`], 1000 units from the origin and 64
//! times as large, counted on the targets as the `W` lines.
//!
//! Each case is the same light as its model's case (`cases::Lights`) in world coordinates:
//! the shading point at [`OFFSET`], the light at `OFFSET + 64 x` (its plain geometry `x`), so
//! that the exact answer is the plain case's for every input and the plain case's f64
//! reference checks it (`host-sim/tests/support/world_rows.rs`). Per sample the call takes
//! the light's points minus `p` in 64-bit integers, scales them by a power of two into the
//! kernels' range (here `2^-6`: back to the plain geometry) and runs the plain model there
//! (`src/world.rs`): a row `<model>/world` against the row `<model>` is what world
//! coordinates cost.
//!
//! Included by the firmware (`mod world_cases`) and by `host-sim` (`#[path]`), beside
//! [`cases`].

use arealight::{PhongLobe, Real, Vec3, WorldPoint, WorldPolygonLight, WorldSphereLight};

use super::cases::{self, Backend, Dirs, Meter, Sample, MODELS, PHONG_M};

/// Where the shading point is (exact in the world format, `2^-32` units).
pub const OFFSET: [f64; 3] = [1000.0, -1000.0, 1000.0];
/// How much larger than the plain case the world case's light is (a power of two: the
/// world path scales it back exactly).
pub const SCALE: f64 = 64.0;

/// The world cases: `(row name, index into MODELS)`. Each answers within its backend's
/// bound of the plain case's f64 reference (the same light, translated and scaled).
pub const WORLD_CASES: [(&str, usize); 5] = [
    ("sphere_lambert/world", 6),
    ("sphere_lambert_hermite/world", 7),
    ("polygon_lambert/world", 8),
    ("phong_sphere/world", 13),
    ("phong_polygon/world", 14),
];

/// The world lights of the cases and their shading point, built once per backend.
pub struct WorldLights<T: Real> {
    sphere: WorldSphereLight<T>,
    quad: WorldPolygonLight<T, 8>,
    lobe: PhongLobe<T>,
    /// The shading point, [`OFFSET`].
    pub p: WorldPoint,
}

impl<T: Real> WorldLights<T> {
    /// The plain cases' sphere (centre `(0, 0, 3)`, radius 1) and quad (`(+-1, +-1, 2)`),
    /// scaled by [`SCALE`] about the shading point and moved to [`OFFSET`].
    ///
    /// # Errors
    /// The first constructor that refuses its parameters (never, for these).
    pub fn new() -> Result<Self, arealight::Error> {
        let at = |x: f64, y: f64, z: f64| {
            WorldPoint::from_f64(
                [
                    OFFSET[0] + SCALE * x,
                    OFFSET[1] + SCALE * y,
                    OFFSET[2] + SCALE * z,
                ],
                "case",
            )
        };
        let quad = [
            at(-1.0, -1.0, 2.0)?,
            at(1.0, -1.0, 2.0)?,
            at(1.0, 1.0, 2.0)?,
            at(-1.0, 1.0, 2.0)?,
        ];
        Ok(WorldLights {
            sphere: WorldSphereLight::new(at(0.0, 0.0, 3.0)?, SCALE)?,
            quad: WorldPolygonLight::new(&quad)?,
            lobe: PhongLobe::new(PHONG_M)?,
            p: at(0.0, 0.0, 0.0)?,
        })
    }
}

macro_rules! world_kernel {
    ($name:ident, |$l:ident, $d:ident| $body:block) => {
        #[doc = concat!("One call of the `", stringify!($name), "` world case.")]
        #[inline(never)]
        pub fn $name<T: Real>($l: &WorldLights<T>, $d: Vec3<T>) -> T $body
    };
}

world_kernel!(w_sphere_lambert, |l, d| { l.sphere.lambert(l.p, d) });
world_kernel!(w_sphere_lambert_hermite, |l, d| {
    l.sphere.lambert_hermite(l.p, d)
});
world_kernel!(w_polygon_lambert, |l, d| { l.quad.lambert(l.p, d) });
world_kernel!(w_phong_sphere, |l, d| { l.sphere.phong(&l.lobe, l.p, d) });
world_kernel!(w_phong_polygon, |l, d| { l.quad.phong(&l.lobe, l.p, d) });

/// Runs world case `case` (an index into [`WORLD_CASES`]) over every direction of `dirs` as
/// `cases::run_model` does; the samples carry the plain model's index. Nothing for a
/// backend that does not support the model.
pub fn run_world<T: Backend, M: Meter>(
    lights: &WorldLights<T>,
    case: usize,
    dirs: Dirs,
    round: fn(f64) -> f64,
    meter: &mut M,
    out: &mut impl FnMut(Sample),
) {
    let Some(&(_, model)) = WORLD_CASES.get(case) else {
        return;
    };
    if !cases::supports(T::NAME, MODELS[model]) {
        return;
    }
    macro_rules! go {
        ($k:ident) => {
            for i in 0..dirs.count {
                let d = core::hint::black_box(cases::input::<T>(model, (dirs.get)(i), round));
                let l = core::hint::black_box(lights);
                let (r, count) = meter.call(|| $k(l, d));
                out(Sample {
                    model,
                    input: i,
                    value: [r.to_f64(), 0.0, 0.0],
                    channels: 1,
                    count,
                });
            }
        };
    }
    match case {
        0 => go!(w_sphere_lambert),
        1 => go!(w_sphere_lambert_hermite),
        2 => go!(w_polygon_lambert),
        3 => go!(w_phong_sphere),
        4 => go!(w_phong_polygon),
        _ => {}
    }
}
