//! The `U` lines of the QEMU budget firmware: the calls that take a normal or a reflection
//! direction, counted with a `UnitVec3` (`cases::UNIT_CASES`). Each must answer exactly the bits
//! of the `V` line of the same backend, model and input (the call normalizes a `Vec3` and then
//! runs the same code), every input of a case must be there once a backend printed any, and
//! their counts become rows `<model>/unit` of `counts.csv`.

use std::collections::{BTreeMap, HashMap};

use super::cases::{MODELS, RING, UNIT_CASES};
use super::Row;

/// Row index of the first unit case (after the models, the alternatives and the demo shade).
pub const UNIT_ROW: usize = super::DEMO_ROW + super::demo_shade::CASES.len();

/// `(kind, backend, model, input) -> (count, value bits)`.
type Calls = HashMap<(String, String, String, usize), (u32, Vec<u64>)>;

/// Parses the `V` and `U` lines.
fn lines(out: &str) -> Calls {
    let mut got = HashMap::new();
    for l in out.lines() {
        let f: Vec<&str> = l.split_whitespace().collect();
        if f.len() < 6 || !(f[0] == "V" || f[0] == "U") {
            continue;
        }
        let (Ok(input), Ok(count)) = (f[3].parse::<usize>(), f[4].parse::<u32>()) else {
            continue;
        };
        let bits: Vec<u64> = f[5..]
            .iter()
            .filter_map(|h| u64::from_str_radix(h, 16).ok())
            .collect();
        got.insert(
            (f[0].to_owned(), f[1].to_owned(), f[2].to_owned(), input),
            (count, bits),
        );
    }
    got
}

/// Checks the `U` lines of one target's output against its `V` lines and adds their rows.
pub fn check(
    short: &str,
    out: &str,
    rows: &mut BTreeMap<(String, String, usize), Row>,
    failures: &mut Vec<String>,
) {
    let got = lines(out);
    let mut backends: Vec<&String> = got.keys().filter(|k| k.0 == "U").map(|k| &k.1).collect();
    backends.sort();
    backends.dedup();
    for backend in backends {
        for (case, &(_, model)) in UNIT_CASES.iter().enumerate() {
            let id = MODELS[model];
            let row = rows
                .entry((short.to_owned(), backend.clone(), UNIT_ROW + case))
                .or_default();
            for i in 0..RING {
                let key = |kind: &str| (kind.to_owned(), backend.clone(), id.to_owned(), i);
                let (Some((count, bits)), Some((_, want))) =
                    (got.get(&key("U")), got.get(&key("V")))
                else {
                    failures.push(format!("{short} {backend} {id}/unit: input {i} missing"));
                    continue;
                };
                if bits != want {
                    failures.push(format!(
                        "{short} {backend} {id}/unit input {i}: {bits:x?} differs from the call \
                         with a Vec3, {want:x?}"
                    ));
                } else {
                    row.bit_identical += 1;
                }
                row.insns.push(*count);
            }
        }
    }
}

/// The row name of unit case `index - UNIT_ROW`.
pub fn row_name(index: usize) -> Option<&'static str> {
    UNIT_CASES.get(index.checked_sub(UNIT_ROW)?).map(|c| c.0)
}
