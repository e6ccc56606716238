//! The `W` lines of the QEMU budget firmware: the positional lights in world coordinates
//! (`world_cases::WORLD_CASES`: the plain cases' lights 64 times as large, 1000 units from the
//! origin). Each answer must be within its backend's bound of the plain case's f64 reference
//! (the same light, translated and scaled: the same exact value), every input of a case must
//! be there once a backend printed any, and their counts become rows `<model>/world` of
//! `counts.csv`, whose last column counts the answers bit-identical to the plain call's (the
//! `V` line of the same backend, model and input).

use std::collections::{BTreeMap, HashMap};

use super::cases::{Sample, MODELS, RING};
use super::qemu_output::scalar_call;
use super::world_cases::WORLD_CASES;
use super::Row;

/// Row index of the first world case (after the unit cases).
pub const WORLD_ROW: usize = super::unit_rows::UNIT_ROW + super::cases::UNIT_CASES.len();

/// `(kind, backend, model, input) -> (count, value)`.
type Calls = HashMap<(String, String, String, usize), (u32, f64)>;

/// Parses the `V` and `W` lines (one channel: every world case is scalar).
fn lines(out: &str) -> Calls {
    out.lines()
        .filter_map(|l| scalar_call(l, &["V", "W"]))
        .map(|(kind, backend, model, input, count, bits)| {
            ((kind, backend, model, input), (count, f64::from_bits(bits)))
        })
        .collect()
}

/// Checks the `W` lines of one target's output against the plain cases' f64 references
/// (`refs[backend][model]`, within `tolerance(backend, model)`) and adds their rows.
pub fn check(
    short: &str,
    out: &str,
    refs: &HashMap<&'static str, Vec<Vec<Sample>>>,
    tolerance: &dyn Fn(&str, &str) -> f64,
    rows: &mut BTreeMap<(String, String, usize), Row>,
    failures: &mut Vec<String>,
) {
    let got = lines(out);
    let mut backends: Vec<&String> = got.keys().filter(|k| k.0 == "W").map(|k| &k.1).collect();
    backends.sort();
    backends.dedup();
    for backend in backends {
        let Some(refs) = refs.get(backend.as_str()) else {
            failures.push(format!(
                "{short} {backend}: W lines of a backend with no reference"
            ));
            continue;
        };
        for (case, &(_, model)) in WORLD_CASES.iter().enumerate() {
            let id = MODELS[model];
            let tol = tolerance(backend, id);
            let row = rows
                .entry((short.to_owned(), backend.clone(), WORLD_ROW + case))
                .or_default();
            for i in 0..RING {
                let key = |kind: &str| (kind.to_owned(), backend.clone(), id.to_owned(), i);
                let (Some(&(count, v)), Some(want)) = (
                    got.get(&key("W")),
                    refs.get(model)
                        .and_then(|r| r.iter().find(|s| s.input == i))
                        .map(|s| s.value[0]),
                ) else {
                    failures.push(format!("{short} {backend} {id}/world: input {i} missing"));
                    continue;
                };
                let err = (v - want).abs() / want.abs().max(1.0);
                row.max_err = row.max_err.max(err);
                if err.is_nan() || err > tol {
                    failures.push(format!(
                        "{short} {backend} {id}/world input {i}: {v:e} on target, {want:e} in \
                         f64 (the plain case's): error {err:.2e} > {tol:.2e}"
                    ));
                }
                if got
                    .get(&key("V"))
                    .is_some_and(|&(_, plain)| plain.to_bits() == v.to_bits())
                {
                    row.bit_identical += 1;
                }
                row.insns.push(count);
            }
        }
    }
}

/// The row name of world case `index - WORLD_ROW`.
pub fn row_name(index: usize) -> Option<&'static str> {
    WORLD_CASES.get(index.checked_sub(WORLD_ROW)?).map(|c| c.0)
}
