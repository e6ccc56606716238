//! The `B` lines of the QEMU budget firmware: `phong_polygon` at the bars' exponent m = 15
//! (`bar_cases::BAR_CASES`), with a `Vec3` and with a `UnitVec3` direction. Each `Vec3` answer
//! must be within its backend's bound of f64 at the same (rounded) inputs and m, each
//! `UnitVec3` answer the bits of the `Vec3` answer of the same backend and input, every input
//! must be there once a backend printed any, and their counts become rows
//! `phong_polygon/m15` and `phong_polygon/m15/unit` of `counts.csv`, whose last column counts
//! the answers bit-identical to the same backend on the host (the `Vec3` row) or to the
//! `Vec3` call (the `UnitVec3` row).

use std::collections::{BTreeMap, HashMap};

use super::bar_cases::{run_bar, BarLights, BAR_CASES};
use super::cases::{Backend, Sample, RING};
use super::qemu_output::scalar_call;
use super::{backends, ring_dirs, Plain, Row};

/// Row index of the first bar case (after the world cases).
pub const BAR_ROW: usize = super::world_rows::WORLD_ROW + super::world_cases::WORLD_CASES.len();

/// `(backend, row, input) -> (count, value bits)`.
type Calls = HashMap<(String, String, usize), (u32, u64)>;

/// Parses the `B` lines.
fn lines(out: &str) -> Calls {
    out.lines()
        .filter_map(|l| scalar_call(l, &["B"]))
        .map(|(_, backend, row, input, count, bits)| ((backend, row, input), (count, bits)))
        .collect()
}

/// The `Vec3` case evaluated in `T` with its inputs rounded by `round` (`T = f64`: the
/// reference), on the host.
pub fn eval<T: Backend>(round: fn(f64) -> f64) -> Vec<Sample> {
    let mut v = Vec::new();
    if let Ok(l) = BarLights::<T>::new(round) {
        run_bar(&l, 0, ring_dirs(), round, &mut Plain, &mut |s| v.push(s));
    }
    v
}

/// The `Vec3` case in `T` on the host, the inputs as the firmware has them.
pub fn host_eval<T: Backend>() -> Vec<Sample> {
    eval::<T>(|x| x)
}

/// Checks the `B` lines of one target's output and adds their rows.
pub fn check(
    short: &str,
    out: &str,
    rows: &mut BTreeMap<(String, String, usize), Row>,
    failures: &mut Vec<String>,
) {
    let got = lines(out);
    let mut names: Vec<&String> = got.keys().map(|k| &k.0).collect();
    names.sort();
    names.dedup();
    for name in names {
        let Some(b) = backends().into_iter().find(|b| b.name == name.as_str()) else {
            failures.push(format!(
                "{short} {name}: B lines of a backend with no reference"
            ));
            continue;
        };
        let reference = eval::<f64>(b.round);
        let host = (b.bar)();
        let tol = (b.bar_tolerance)();
        for (case, &(row_name, unit)) in BAR_CASES.iter().enumerate() {
            let row = rows
                .entry((short.to_owned(), name.clone(), BAR_ROW + case))
                .or_default();
            for i in 0..RING {
                let key = |row: &str| (name.clone(), row.to_owned(), i);
                let (Some(&(count, bits)), Some(want)) = (
                    got.get(&key(row_name)),
                    reference.iter().find(|s| s.input == i).map(|s| s.value[0]),
                ) else {
                    failures.push(format!("{short} {name} {row_name}: input {i} missing"));
                    continue;
                };
                let v = f64::from_bits(bits);
                let err = (v - want).abs() / want.abs().max(1.0);
                row.max_err = row.max_err.max(err);
                if err.is_nan() || err > tol {
                    failures.push(format!(
                        "{short} {name} {row_name} input {i}: {v:e} on target, {want:e} in f64: \
                         error {err:.2e} > {tol:.2e}"
                    ));
                }
                let same = if unit {
                    let plain = got.get(&key(BAR_CASES[0].0)).map(|c| c.1);
                    if plain != Some(bits) {
                        failures.push(format!(
                            "{short} {name} {row_name} input {i}: {bits:x} differs from the \
                             call with a Vec3, {plain:x?}"
                        ));
                    }
                    plain == Some(bits)
                } else {
                    host.iter()
                        .any(|s| s.input == i && s.value[0].to_bits() == bits)
                };
                row.bit_identical += usize::from(same);
                row.insns.push(count);
            }
        }
    }
}

/// The row name of bar case `index - BAR_ROW`.
pub fn row_name(index: usize) -> Option<&'static str> {
    BAR_CASES.get(index.checked_sub(BAR_ROW)?).map(|c| c.0)
}
