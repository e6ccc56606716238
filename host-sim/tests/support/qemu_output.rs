//! What the QEMU budget's firmware prints: the parsed `V`/`A` lines (the `U` and `W` lines:
//! `unit_rows.rs`, `world_rows.rs`), the counter's self-check, and the test that no count
//! wrapped.

use crate::{qemu_binary, qemu_version};

/// One parsed `V` line, or `A` line (then `k` is its sample count).
pub struct Line {
    pub k: Option<usize>,
    pub backend: String,
    pub model: String,
    pub input: usize,
    pub count: u32,
    pub value: Vec<f64>,
}

/// The `key=value` pairs of the `SELF` line.
pub type SelfCheck = Vec<(String, u32)>;

pub fn parse(out: &str) -> Result<(Vec<Line>, Option<SelfCheck>), String> {
    let mut lines = Vec::new();
    let mut selfcheck = None;
    let mut done = false;
    for l in out.lines() {
        let f: Vec<&str> = l.split_whitespace().collect();
        match f.first().copied() {
            Some("V") if f.len() >= 6 => {
                let num = |s: &str| s.parse::<u32>().map_err(|e| format!("{l}: {e}"));
                let value = f[5..]
                    .iter()
                    .map(|h| u64::from_str_radix(h, 16).map(f64::from_bits))
                    .collect::<Result<Vec<_>, _>>()
                    .map_err(|e| format!("{l}: {e}"))?;
                lines.push(Line {
                    k: None,
                    backend: f[1].to_owned(),
                    model: f[2].to_owned(),
                    input: num(f[3])? as usize,
                    count: num(f[4])?,
                    value,
                });
            }
            Some("A") if f.len() == 7 => {
                let num = |s: &str| s.parse::<u32>().map_err(|e| format!("{l}: {e}"));
                let value = u64::from_str_radix(f[6], 16)
                    .map(f64::from_bits)
                    .map_err(|e| format!("{l}: {e}"))?;
                lines.push(Line {
                    k: Some(num(f[3])? as usize),
                    backend: f[1].to_owned(),
                    model: f[2].to_owned(),
                    input: num(f[4])? as usize,
                    count: num(f[5])?,
                    value: vec![value],
                });
            }
            Some("SELF") => {
                selfcheck = Some(
                    f[1..]
                        .iter()
                        .filter_map(|kv| {
                            let (k, v) = kv.split_once('=')?;
                            Some((k.to_owned(), v.parse().ok()?))
                        })
                        .collect(),
                );
            }
            Some("FAIL") => return Err(format!("the firmware failed: {l}")),
            Some("DONE") => done = true,
            _ => {}
        }
    }
    if !done {
        return Err("the firmware did not print DONE".into());
    }
    Ok((lines, selfcheck))
}

/// The counter self-check, from the firmware's numbers: `base` is the two TIM2 loads alone,
/// `n<N>` the same loads around N iterations of `subs`/`bne` (all in assembly). Each must be
/// exactly `base + 2N`, and the loop lengths must include a long one. On RISC-V the same with
/// two `csrr instret` around `addi`/`bnez` (`triple` says which).
///
/// `empty` is the count of an empty measured region in Rust (`Tim2::empty`), which the
/// firmware subtracts from every count: the same two loads plus at most a re-materialized
/// address of TIM2_CNT (a literal load on the M0, `movw`/`movt` on the M4F; nothing on
/// RISC-V), so it must be `base` to `base + 2` (`counter::EMPTY_SLACK`). Below `base` the loads
/// themselves would not be counted; above, the empty region holds code that a measured call
/// does not, and every count would be short by the difference.
pub fn check_counter(triple: &str, s: &[(String, u32)]) -> Result<String, String> {
    let (counter, looped) = if triple.starts_with("riscv32") {
        ("instret", "addi/bnez")
    } else {
        ("TIM2", "subs/bne")
    };
    let get = |key: &str| s.iter().find(|(k, _)| k == key).map(|kv| kv.1);
    let (base, empty) = (get("base"), get("empty"));
    let loops: Vec<(u32, u32)> = s
        .iter()
        .filter_map(|(k, v)| Some((k.strip_prefix('n')?.parse().ok()?, *v)))
        .collect();
    let shown = s
        .iter()
        .map(|(k, v)| format!("{k}={v}"))
        .collect::<Vec<_>>()
        .join(" ");
    match (base, empty) {
        (Some(b), Some(e))
            if (1..=2).contains(&b)
                && (b..=b + EMPTY_SLACK).contains(&e)
                && loops.iter().any(|&(n, _)| n >= 1000)
                && loops.iter().all(|&(n, c)| c == b + 2 * n) =>
        {
            Ok(format!(
                "loads alone {b}, empty region {e} (subtracted from every count; {b} to {b} + \
                 {EMPTY_SLACK}), loops {} (each exactly 2n + {b})",
                loops
                    .iter()
                    .map(|(n, c)| format!("n={n}: {c}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ))
        }
        _ => Err(format!(
            "counter self-check FAILED ({shown}): a loop of n {looped} iterations must read \
             exactly 2n more on {counter} than the loads alone (base), and the empty region \
             (empty, subtracted from every count) must read base to base + {EMPTY_SLACK}; \
             {counter} does not count executed instructions exactly on this QEMU ({}), so no \
             instruction count can be trusted",
            qemu_version(qemu_binary(triple))
        )),
    }
}

/// The slack of the empty region over the two loads (see [`check_counter`]); the firmware's
/// `counter::EMPTY_SLACK`.
pub const EMPTY_SLACK: u32 = 2;

/// The fields of a one-value call line `<kind> <backend> <name> <input> <count> <value bits
/// as hex>` (the `V`, `W` and `B` lines of a scalar case) whose kind is one of `kinds`: `(kind,
/// backend, name, input, count, bits)`, or `None` for any other line.
pub fn scalar_call(l: &str, kinds: &[&str]) -> Option<(String, String, String, usize, u32, u64)> {
    let f: Vec<&str> = l.split_whitespace().collect();
    if f.len() != 6 || !kinds.contains(&f[0]) {
        return None;
    }
    Some((
        f[0].to_owned(),
        f[1].to_owned(),
        f[2].to_owned(),
        f[3].parse().ok()?,
        f[4].parse().ok()?,
        u64::from_str_radix(f[5], 16).ok()?,
    ))
}

/// No count wrapped: the firmware subtracts the empty region's count from each raw TIM2
/// difference and stops with a `FAIL` line if a region reads less; were it to wrap instead,
/// the count would be within `empty` of 2^32. No call here comes near 2^31 instructions, so
/// every count of a `V`, `U`, `W`, `B`, `A`, `D`, `S` or `Q` line must be below it.
pub fn check_no_wrap(short: &str, out: &str, failures: &mut Vec<String>) {
    for l in out.lines() {
        let f: Vec<&str> = l.split_whitespace().collect();
        let fields: &[usize] = match f.first().copied() {
            Some("V") | Some("D") | Some("U") | Some("W") | Some("B") => &[4],
            Some("A") => &[5],
            Some("S") => &[3],
            Some("Q") => &[5, 6],
            _ => continue,
        };
        for &i in fields {
            match f.get(i).map(|x| x.parse::<u64>()) {
                Some(Ok(n)) if n < 1 << 31 => {}
                _ => failures.push(format!(
                    "{short}: count field {i} of `{l}` is not a count below 2^31 (wrapped?)"
                )),
            }
        }
    }
}
