//! The polygon's Phong term as issues 12 and 13 set their bars, `PolygonLight::<_, 4>::phong`
//! at m = 15 (the budget table's Phong cases run at [`cases::PHONG_M`], 16, and hold their
//! quad in a `PolygonLight<_, 8>`), counted on the targets as the `B` lines: the
//! `phong_polygon` case's quad, shading point and directions, with the direction as a `Vec3`
//! (normalized by the call) and as a [`UnitVec3`] (normalized before the count).
//!
//! An odd exponent takes other paths than an even one (the edges' angles, the recurrence from
//! `k = 1`), so the bars are measured at their own exponent rather than inferred from the
//! table's. The firmware runs these cases as an image of their own (`QEMU_BUDGET_PART=bar`),
//! so that the polygon's functions keep the callers they have in the models' image (a second
//! caller changes what LLVM inlines). The host checks every answer against f64 at the same
//! inputs (`host-sim/tests/support/bar_rows.rs`) and `host-sim budget` puts the medians in
//! `budget-bar.md`.
//!
//! Included by the firmware (`mod bar_cases`) and by `host-sim` (`#[path]`), beside
//! [`cases`].

use arealight::{PhongLobe, PolygonLight, Real, UnitVec3, Vec3};

use super::cases::{self, Backend, Dirs, Meter, Sample, MODELS, QUAD};

/// The exponent of the bars: `PolygonLight::<_, 4>::phong` on a quad at m = 15 (issue 12:
/// 600 Cortex-M4F instructions in f32; issue 13: 8 000 Cortex-M0 instructions in `Fixed22`).
pub const BAR_PHONG_M: u32 = 15;

/// The model these cases measure (`phong_polygon`), an index into [`MODELS`].
pub const BAR_MODEL: usize = 14;

/// The cases: `(row name, whether the direction is a UnitVec3)`.
pub const BAR_CASES: [(&str, bool); 2] = [
    ("phong_polygon/m15", false),
    ("phong_polygon/m15/unit", true),
];

/// The light and lobe of the cases, built once per backend: the bars' `PolygonLight<_, 4>`
/// (the table's cases hold their quad in a `PolygonLight<_, 8>`, whose call the Cortex-M0
/// executes in 9 to 38 instructions more at the median: the capacity changes the code LLVM
/// generates).
pub struct BarLights<T: Real> {
    quad: PolygonLight<T, 4>,
    lobe: PhongLobe<T>,
    p: Vec3<T>,
}

impl<T: Real> BarLights<T> {
    /// The `phong_polygon` case's quad ([`QUAD`]) and a lobe of exponent [`BAR_PHONG_M`];
    /// coordinates pass through `round` first (as `cases::Lights::new`).
    ///
    /// # Errors
    /// The first constructor that refuses its parameters (never, for these).
    pub fn new(round: fn(f64) -> f64) -> Result<Self, arealight::Error> {
        let v = |[x, y, z]: [f64; 3]| {
            Vec3::new(
                T::from_f64(round(x)),
                T::from_f64(round(y)),
                T::from_f64(round(z)),
            )
        };
        Ok(BarLights {
            quad: PolygonLight::new(&QUAD.map(v))?,
            lobe: PhongLobe::new(BAR_PHONG_M)?,
            p: Vec3::new(T::ZERO, T::ZERO, T::ZERO),
        })
    }
}

/// One call of `phong_polygon` at m = 15 with the direction as a `Vec3`.
#[inline(never)]
pub fn b_phong_polygon<T: Real>(l: &BarLights<T>, d: Vec3<T>) -> T {
    l.quad.phong(&l.lobe, l.p, d)
}

/// One call of `phong_polygon` at m = 15 with the direction as a `UnitVec3`.
#[inline(never)]
pub fn b_phong_polygon_unit<T: Real>(l: &BarLights<T>, d: UnitVec3<T>) -> T {
    l.quad.phong(&l.lobe, l.p, d)
}

/// Runs bar case `case` (an index into [`BAR_CASES`]) over every direction of `dirs` as
/// `cases::run_model` and `cases::run_unit` do; the samples carry [`BAR_MODEL`]. Nothing for a
/// backend that does not support the model.
pub fn run_bar<T: Backend, M: Meter>(
    lights: &BarLights<T>,
    case: usize,
    dirs: Dirs,
    round: fn(f64) -> f64,
    meter: &mut M,
    out: &mut impl FnMut(Sample),
) {
    let Some(&(_, unit)) = BAR_CASES.get(case) else {
        return;
    };
    if !cases::supports(T::NAME, MODELS[BAR_MODEL]) {
        return;
    }
    for i in 0..dirs.count {
        let d = cases::input::<T>(BAR_MODEL, (dirs.get)(i), round);
        let l = core::hint::black_box(lights);
        let (r, count) = if unit {
            // The ring's directions are nonzero: every one has a unit vector.
            let Some(u) = d.to_unit() else {
                continue;
            };
            let u = core::hint::black_box(u);
            meter.call(|| b_phong_polygon_unit(l, u))
        } else {
            let d = core::hint::black_box(d);
            meter.call(|| b_phong_polygon(l, d))
        };
        out(Sample {
            model: BAR_MODEL,
            input: i,
            value: [r.to_f64(), 0.0, 0.0],
            channels: 1,
            count,
        });
    }
}
