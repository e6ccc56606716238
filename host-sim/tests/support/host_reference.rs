//! The host's side of the QEMU budget harness (`qemu_budget.rs`, included with `#[path]`): the
//! backends as the host knows them ([`HostBackend`]: rounding, tolerance, evaluation), and the
//! f64 reference of every model on the firmware's inputs.

use super::*;

/// A backend as the host knows it: its name in the firmware's output, the type name in its
/// kernels' symbols, how inputs are rounded to it, its tolerance, and its f32-exact evaluation
/// on the host. Adding a backend is one entry in [`backends`] (and one in the firmware).
pub(crate) struct HostBackend {
    pub(crate) name: &'static str,
    /// The targets that run it (`m4f`, `m0`, `rv32imc`).
    pub(crate) targets: &'static [&'static str],
    pub(crate) symbol_type: &'static str,
    pub(crate) round: fn(f64) -> f64,
    /// The absolute tolerance against f64 (relative to max(1, |reference|)), per model.
    pub(crate) tolerance: fn(&str) -> f64,
    /// The same backend evaluated on the host (for the bit-identity report).
    pub(crate) host: fn(model: usize) -> Vec<Sample>,
    /// The demo shade evaluated on the host in the same backend.
    pub(crate) demo: fn() -> Vec<DemoShade>,
    /// The bars' `Vec3` case (`bar_cases`) evaluated on the host in the same backend.
    pub(crate) bar: fn() -> Vec<Sample>,
    /// The tolerance of the bars' case (`phong_polygon` at `bar_cases::BAR_PHONG_M`).
    pub(crate) bar_tolerance: fn() -> f64,
}

/// One demo shade on the host: (case, input, colour).
pub(crate) type DemoShade = (usize, usize, [f64; 3]);

pub(crate) fn demo_host<T: Real>() -> Vec<DemoShade> {
    let mut v = Vec::new();
    let _ = demo_shade::run::<T, _>(|x| x, &mut Plain, &mut |c, i, val, _| v.push((c, i, val)));
    v
}

pub(crate) fn round_f32(x: f64) -> f64 {
    x as f32 as f64
}

/// The f32 accuracy targets of the README: 2e-6 where well conditioned, plus m 2^-24 for the
/// Phong-type models (every case here is well conditioned: no point near a polygon's plane
/// or a sphere's surface).
pub(crate) fn tol_f32(model: &str) -> f64 {
    tol_f32_at(model, cases::PHONG_M)
}

/// [`tol_f32`] for the Phong exponent `m`.
pub(crate) fn tol_f32_at(model: &str, m: u32) -> f64 {
    let phong =
        model.starts_with("phong") || model.starts_with("glossy") || model.ends_with("phong_peak");
    2e-6 + if phong {
        f64::from(m) * 2f64.powi(-24)
    } else {
        0.0
    }
}

pub(crate) fn tol_fast(_model: &str) -> f64 {
    1.0 / 1024.0
}

pub(crate) fn round_fixed(x: f64) -> f64 {
    Fixed22::from_f64(x).to_f64()
}

pub(crate) fn host_eval<T: Backend>(model: usize) -> Vec<Sample> {
    let mut v = Vec::new();
    if let Ok(l) = Lights::<T>::new(|x| x) {
        cases::run_model(&l, model, ring_dirs(), |x| x, &mut Plain, &mut |s| {
            v.push(s)
        });
    }
    v
}

pub(crate) fn backends() -> Vec<HostBackend> {
    vec![
        HostBackend {
            name: "f32",
            targets: &["m4f", "m0", "rv32imc"],
            symbol_type: "f32",
            round: round_f32,
            tolerance: tol_f32,
            host: host_eval::<f32>,
            demo: demo_host::<f32>,
            bar: bar_rows::host_eval::<f32>,
            bar_tolerance: || tol_f32_at("phong_polygon", bar_cases::BAR_PHONG_M),
        },
        HostBackend {
            name: "f32-fast",
            targets: &["m4f", "m0", "rv32imc"],
            symbol_type: "Fast32",
            round: round_f32,
            tolerance: tol_fast,
            host: host_eval::<Fast32>,
            demo: demo_host::<Fast32>,
            bar: bar_rows::host_eval::<Fast32>,
            bar_tolerance: || tol_fast("phong_polygon"),
        },
        HostBackend {
            name: "fixed",
            targets: &["m0", "rv32imc"],
            symbol_type: "Fixed22",
            round: round_fixed,
            tolerance: tol_fast,
            host: host_eval::<Fixed22>,
            demo: demo_host::<Fixed22>,
            bar: bar_rows::host_eval::<Fixed22>,
            bar_tolerance: || tol_fast("phong_polygon"),
        },
    ]
}

pub(crate) struct Plain;
impl Meter for Plain {
    fn call<R>(&mut self, f: impl Fn() -> R) -> (R, u32) {
        (f(), 0)
    }
}

pub(crate) use cases::ring_dirs;

/// The f64 reference of every model, with the inputs rounded as `round` does.
pub(crate) fn reference(round: fn(f64) -> f64) -> Result<Vec<Vec<Sample>>, String> {
    let lights = Lights::<f64>::new(round).map_err(|e| format!("f64 lights: {e:?}"))?;
    Ok((0..MODELS.len())
        .map(|m| {
            let mut v = Vec::new();
            cases::run_model(&lights, m, ring_dirs(), round, &mut Plain, &mut |s| {
                v.push(s)
            });
            v
        })
        .collect())
}
