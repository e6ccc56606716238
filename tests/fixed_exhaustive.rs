//! Exhaustive sweeps of [`Fixed22`]'s elementary kernels (issue 13), each against f64 computed
//! from the exact input value (`bits 2^-22`, exact in f64), asserting the bounds and the
//! saturation/fallback values documented in the module docs of `src/real/fixed22.rs`:
//!
//! - `sqrt`, `rsqrt`, `sqrt_rsqrt`, `ln`: every one of the 2^32 bit patterns (the 2^31 - 1
//!   positive ones against f64; 0 and the negatives give the documented fallback exactly);
//! - `sin`, `cos`: every bit pattern (within `[-1, 1]` + 2 LSB everywhere, 1 LSB for `|x| <= 64`
//!   against f64; beyond 64 measured against f64 on a stride, which is not a documented bound);
//! - `exp`: every bit pattern (MAX above `9 ln 2`, 0 below -17, `(1 + e^x)` LSB between);
//! - `/` and `atan2`: dense grids (a stride over all 2^32 numerators against every divisor of
//!   an edge-rich list, every saturation boundary, and every pair of small integers).
//!
//! Each sweep prints one `[sweep]` line (not `[maxerr]`: `boards/test-tables.mjs` would put
//! those into `docs/accuracy.md`). The sweeps spread over every core (`std::thread::scope`) and
//! run in the test profile, with overflow checks on: an overflow in a kernel panics here, so
//! the unary sweeps also show that no input overflows the kernels' integer arithmetic.
//!
//! The two grids run with the suite (about 8 s of CPU). The four sweeps over all 2^32 inputs
//! and grids 8 times as dense take about 6 minutes of CPU (measured on a 2-core EPYC, user
//! time: sqrt/rsqrt/sqrt_rsqrt 83 s, ln 65 s, sin/cos 131 s, exp 21 s, the grids 60 s) and
//! are `#[ignore]`d; CI runs them in a step of their own:
//! `cargo test -p arealight --test fixed_exhaustive -- --ignored --nocapture`.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use arealight::{Fixed22, Real};
use std::ops::Range;
use std::sync::atomic::{AtomicI64, Ordering};
use std::sync::Mutex;
use std::time::Instant;

type F = Fixed22;
/// `2^-22`.
const LSB: f64 = 1.0 / 4_194_304.0;
/// The value of `Fixed22::MAX`, `512 - 2^-22`.
const MAX_VALUE: f64 = i32::MAX as f64 * LSB;
/// Every `i32`, as a range of indices.
const ALL: Range<i64> = i32::MIN as i64..i32::MAX as i64 + 1;

fn fx(bits: i32) -> F {
    F::from_bits(bits)
}

/// The exact value of the bits.
fn val(bits: i32) -> f64 {
    bits as f64 * LSB
}

/// The largest error of one sweep (in the unit of its bound), where it was, and every
/// violation: of the bound, or (`wrong`) of a documented exact value.
#[derive(Clone, Copy, Debug)]
struct Stat {
    bound: f64,
    worst: f64,
    worst_at: (i64, (i32, i32)),
    cases: u64,
    fails: u64,
    first_fail: Option<(i64, (i32, i32), f64)>,
    exact: u64,
    wrong: u64,
    first_wrong: Option<(i64, (i32, i32))>,
}

impl Stat {
    fn new(bound: f64) -> Self {
        Stat {
            bound,
            worst: 0.0,
            worst_at: (i64::MAX, (0, 0)),
            cases: 0,
            fails: 0,
            first_fail: None,
            exact: 0,
            wrong: 0,
            first_wrong: None,
        }
    }

    /// An error `err` (in the bound's unit) at sweep index `i`, input `at`.
    #[inline(always)]
    fn add(&mut self, i: i64, at: (i32, i32), err: f64) {
        self.cases += 1;
        if !(err <= self.bound) {
            self.fails += 1;
            if self.first_fail.is_none_or(|f| i < f.0) {
                self.first_fail = Some((i, at, err));
            }
        }
        if err > self.worst || (err == self.worst && i < self.worst_at.0) {
            self.worst = err;
            self.worst_at = (i, at);
        }
    }

    /// A documented exact value: `ok` when it was returned.
    #[inline(always)]
    fn expect(&mut self, i: i64, at: (i32, i32), ok: bool) {
        self.exact += 1;
        if !ok {
            self.wrong += 1;
            if self.first_wrong.is_none_or(|f| i < f.0) {
                self.first_wrong = Some((i, at));
            }
        }
    }

    fn merge(&mut self, o: &Stat) {
        self.cases += o.cases;
        self.exact += o.exact;
        self.fails += o.fails;
        self.wrong += o.wrong;
        if o.worst > self.worst || (o.worst == self.worst && o.worst_at.0 < self.worst_at.0) {
            self.worst = o.worst;
            self.worst_at = o.worst_at;
        }
        if let Some(f) = o.first_fail {
            if self.first_fail.is_none_or(|g| f.0 < g.0) {
                self.first_fail = Some(f);
            }
        }
        if let Some(f) = o.first_wrong {
            if self.first_wrong.is_none_or(|g| f.0 < g.0) {
                self.first_wrong = Some(f);
            }
        }
    }

    /// Prints the `[sweep]` line and fails on any violation (with the first one's inputs).
    fn finish(&self, name: &str, unit: &str, secs: f64) {
        let at = self.worst_at.1;
        let measured = if self.cases == 0 {
            String::new()
        } else {
            format!(
                "max {:.3} {unit} at bits {at:?} over {} cases (bound {}); ",
                self.worst, self.cases, self.bound
            )
        };
        println!(
            "[sweep] Fixed22 {name}: {measured}{} documented exact values checked, {} wrong; \
             {secs:.1} s",
            self.exact, self.wrong
        );
        assert!(
            self.fails == 0,
            "{name}: {} cases beyond the bound {}; the first at bits {:?} ({:.4} {unit})",
            self.fails,
            self.bound,
            self.first_fail.map(|f| f.1),
            self.first_fail.map_or(0.0, |f| f.2),
        );
        assert!(
            self.wrong == 0,
            "{name}: {} documented exact values wrong; the first at bits {:?}",
            self.wrong,
            self.first_wrong.map(|f| f.1),
        );
    }
}

/// Runs `body(i, stats)` for every `i` in `range` on every core (chunks of 2^20 handed out
/// in turn) and merges the threads' statistics.
fn sweep<const N: usize>(
    range: Range<i64>,
    bounds: [f64; N],
    body: impl Fn(i64, &mut [Stat; N]) + Sync,
) -> ([Stat; N], f64) {
    const CHUNK: i64 = 1 << 20;
    let start = Instant::now();
    let next = AtomicI64::new(range.start);
    let total = Mutex::new(bounds.map(Stat::new));
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    std::thread::scope(|s| {
        for _ in 0..threads {
            s.spawn(|| {
                let mut st = bounds.map(Stat::new);
                loop {
                    let lo = next.fetch_add(CHUNK, Ordering::Relaxed);
                    if lo >= range.end {
                        break;
                    }
                    for i in lo..(lo + CHUNK).min(range.end) {
                        body(i, &mut st);
                    }
                }
                let mut t = total.lock().unwrap();
                for (t, s) in t.iter_mut().zip(&st) {
                    t.merge(s);
                }
            });
        }
    });
    (total.into_inner().unwrap(), start.elapsed().as_secs_f64())
}

#[test]
#[ignore = "exhaustive over all 2^32 inputs (minutes of CPU): run with `-- --ignored`"]
fn sqrt_rsqrt_every_input() {
    // [sqrt, rsqrt, sqrt_rsqrt and the fallbacks (exact values only)]
    let (st, secs) = sweep(ALL, [1.0, 1.0, 0.0], |i, st| {
        let b = i as i32;
        let x = fx(b);
        let (s, r) = (x.sqrt(), x.rsqrt());
        let pair = x.sqrt_rsqrt();
        st[2].expect(i, (b, 0), pair == (s, r));
        if b <= 0 {
            // Documented: 0 for x <= 0 (both).
            st[2].expect(i, (b, 0), s == F::ZERO && r == F::ZERO);
            return;
        }
        // sqrt within 1 LSB: sqrt(b 2^-22) / 2^-22 = sqrt(b 2^22).
        let w = (b as f64 * 4_194_304.0).sqrt();
        st[0].add(i, (b, 0), (s.to_bits() as f64 - w).abs());
        // rsqrt within 1 LSB + 2^-28 relative, of the value clamped to the range; MAX below
        // 2^-18 (b < 16).
        let want = (1.0 / val(b).sqrt()).min(MAX_VALUE);
        let e = (val(r.to_bits()) - want).abs() / (LSB + want * 2f64.powi(-28));
        st[1].add(i, (b, 0), e);
        if b < 16 {
            st[1].expect(i, (b, 0), r == F::MAX);
        }
    });
    st[0].finish("sqrt (every x > 0)", "LSB", secs);
    st[1].finish("rsqrt (every x > 0)", "x (1 LSB + 2^-28 relative)", secs);
    st[2].finish(
        "sqrt_rsqrt == (sqrt, rsqrt), every x; 0 for x <= 0",
        "",
        secs,
    );
}

#[test]
#[ignore = "exhaustive over all 2^32 inputs (minutes of CPU): run with `-- --ignored`"]
fn ln_every_input() {
    let (st, secs) = sweep(ALL, [1.0], |i, st| {
        let b = i as i32;
        let l = fx(b).ln();
        if b <= 0 {
            // Documented: -512 (MIN) for x <= 0.
            st[0].expect(i, (b, 0), l == F::MIN);
        } else {
            st[0].add(
                i,
                (b, 0),
                (f64::from(l.to_bits()) - val(b).ln() / LSB).abs(),
            );
        }
    });
    st[0].finish("ln (every x > 0; MIN for x <= 0)", "LSB", secs);
}

/// Every `BEYOND`-th input with `|x| > 64` is also measured against f64 (no documented
/// bound there: reported, not asserted).
const BEYOND: i64 = 7;

#[test]
#[ignore = "exhaustive over all 2^32 inputs (minutes of CPU): run with `-- --ignored`"]
fn sin_cos_every_input() {
    // [sin |x| <= 64, cos |x| <= 64, sin beyond 64, cos beyond 64]
    let inf = f64::INFINITY;
    let (st, secs) = sweep(ALL, [1.0, 1.0, inf, inf], |i, st| {
        let b = i as i32;
        let x = fx(b);
        let (s, c) = (x.sin(), x.cos());
        // Everywhere: within [-1, 1] plus 2 LSB.
        let one = (1 << 22) + 2;
        let inside = s.to_bits().abs() <= one && c.to_bits().abs() <= one;
        let k = if b.unsigned_abs() <= 64 << 22 { 0 } else { 2 };
        st[k].expect(i, (b, 0), inside);
        if k == 2 && i % BEYOND != 0 {
            return;
        }
        let v = val(b);
        st[k].add(i, (b, 0), (f64::from(s.to_bits()) - v.sin() / LSB).abs());
        st[k + 1].add(i, (b, 0), (f64::from(c.to_bits()) - v.cos() / LSB).abs());
    });
    st[0].finish(
        "sin (every |x| <= 64; every x within [-1, 1] + 2 LSB)",
        "LSB",
        secs,
    );
    st[1].finish("cos (every |x| <= 64)", "LSB", secs);
    st[2].finish(
        &format!("sin (every {BEYOND}th |x| > 64, not a documented bound; every x within [-1, 1] + 2 LSB)"),
        "LSB",
        secs,
    );
    st[3].finish(
        &format!("cos (every {BEYOND}th |x| > 64, not a documented bound)"),
        "LSB",
        secs,
    );
}

#[test]
#[ignore = "exhaustive over all 2^32 inputs (minutes of CPU): run with `-- --ignored`"]
fn exp_every_input() {
    let top = 9.0 * std::f64::consts::LN_2;
    let (st, secs) = sweep(ALL, [1.0], |i, st| {
        let b = i as i32;
        let e = fx(b).exp();
        let x = val(b);
        // Documented: MAX above 9 ln 2, 0 below -17; (1 + e^x) LSB (of the value clamped to
        // the range) between.
        if x > top {
            st[0].expect(i, (b, 0), e == F::MAX);
        } else if x < -17.0 {
            st[0].expect(i, (b, 0), e == F::ZERO);
        } else {
            let want = x.exp().min(MAX_VALUE);
            st[0].add(
                i,
                (b, 0),
                (val(e.to_bits()) - want).abs() / (LSB * (1.0 + want)),
            );
        }
    });
    st[0].finish(
        "exp (every x; MAX above 9 ln 2, 0 below -17)",
        "x (1 + e^x) LSB",
        secs,
    );
}

// ---------------------------------------------------------------------------------------------
// Division and atan2: dense grids.
// ---------------------------------------------------------------------------------------------

/// Edge bit patterns: 0, the extremes, every power of two and its neighbours, both signs.
fn edge_bits() -> Vec<i32> {
    let mut e = vec![
        0,
        1,
        -1,
        2,
        -2,
        3,
        -3,
        i32::MAX,
        i32::MIN,
        i32::MAX - 1,
        i32::MIN + 1,
    ];
    for k in 1..31 {
        let p = 1i32 << k;
        e.extend([p, p - 1, p + 1, -p, -p + 1, -p - 1]);
    }
    e.sort_unstable();
    e.dedup();
    e
}

/// splitmix64, for the low bits of the grids' values (seeded: the same grid on every run).
fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The divisors (and atan2's `x`): the edge patterns and, for every magnitude `2^k`
/// (k = 0..30), `per` values in `[2^k, 2^(k+1))` with seeded low bits, both signs.
fn grid_values(per: u64) -> Vec<i32> {
    let mut v = edge_bits();
    for k in 0..31u32 {
        for j in 0..per {
            let low = (mix(u64::from(k) << 32 | j) as u32) & ((1u32 << k) - 1);
            let m = ((1u32 << k) | low) as i32;
            v.extend([m, -m]);
        }
    }
    v.sort_unstable();
    v.dedup();
    v
}

/// `count` numerators spread over all 2^32 patterns by an odd stride (every high and low
/// bit varies), and the edge patterns.
fn stride_values(count: u32) -> Vec<i32> {
    let stride = (u32::MAX / count) | 1;
    let mut v: Vec<i32> = (0..count).map(|i| i.wrapping_mul(stride) as i32).collect();
    v.extend(edge_bits());
    v.sort_unstable();
    v.dedup();
    v
}

/// The correctly rounded quotient's bits (ties away from zero), saturated; `x / 0` is MAX or
/// MIN by the sign of `x`, `0 / 0` = 0 (the documented values). Exact, in `i64`.
fn div_exact(a: i32, b: i32) -> i32 {
    if b == 0 {
        return match a.signum() {
            0 => 0,
            1 => i32::MAX,
            _ => i32::MIN,
        };
    }
    let (n, d) = (i64::from(a) << 22, i64::from(b));
    let (q, r) = (n / d, n % d);
    let q = if 2 * r.abs() >= d.abs() {
        q + if (n < 0) != (d < 0) { -1 } else { 1 }
    } else {
        q
    };
    q.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
}

/// Numerators and divisors per binade of the division and atan2 grids run with the suite
/// (about 4.7e7 pairs each); the `--ignored` step's grids have 4 times the numerators and
/// twice the divisors.
const NUMERATORS: u32 = 1 << 15;
const PER_BINADE: u64 = 24;

#[test]
fn division_on_a_dense_grid() {
    division_grid(NUMERATORS, PER_BINADE);
}

#[test]
#[ignore = "a grid 8 times as dense (a minute of CPU): run with `-- --ignored`"]
fn division_on_a_denser_grid() {
    division_grid(4 * NUMERATORS, 2 * PER_BINADE);
}

/// Division on `numerators x divisors` (see [`stride_values`], [`grid_values`]) and at every
/// divisor's saturation boundary: exactly the correctly rounded quotient.
fn division_grid(numerators: u32, per_binade: u64) {
    let (nums, dens) = (stride_values(numerators), grid_values(per_binade));
    // Every divisor's saturation boundary: |a| around |b| 2^9 (the quotient's 2^31 LSB).
    let mut pairs: Vec<(i32, i32)> = Vec::new();
    for &b in &dens {
        let edge = i64::from(b).abs() << 9;
        for a in edge - 3..=edge + 3 {
            if a <= i64::from(i32::MAX) {
                pairs.extend([(a as i32, b), (-a as i32, b)]);
            }
        }
    }
    let (nd, np) = (dens.len() as i64, pairs.len() as i64);
    let grid = nums.len() as i64 * nd;
    let (st, secs) = sweep(0..grid + np, [0.5], |i, st| {
        let (a, b) = if i < grid {
            (nums[(i / nd) as usize], dens[(i % nd) as usize])
        } else {
            pairs[(i - grid) as usize]
        };
        let got = (fx(a) / fx(b)).to_bits();
        let want = div_exact(a, b);
        st[0].expect(i, (a, b), got == want);
        // The error against the exact (clamped) quotient, in LSB (f64: exact at the ties).
        let exact = if b == 0 {
            f64::from(want)
        } else {
            (f64::from(a) * 4_194_304.0 / f64::from(b))
                .clamp(f64::from(i32::MIN), f64::from(i32::MAX))
        };
        st[0].add(i, (a, b), (f64::from(got) - exact).abs());
    });
    st[0].finish(
        &format!(
            "a / b ({} numerators x {} divisors, {} at the saturation boundaries; \
             exact = correctly rounded, ties away from zero)",
            nums.len(),
            dens.len(),
            np
        ),
        "LSB",
        secs,
    );
}

#[test]
fn atan2_on_a_dense_grid() {
    atan2_grid(NUMERATORS, PER_BINADE);
}

#[test]
#[ignore = "a grid 8 times as dense (a minute of CPU): run with `-- --ignored`"]
fn atan2_on_a_denser_grid() {
    atan2_grid(4 * NUMERATORS, 2 * PER_BINADE);
}

/// `atan2(y, x)` on `y x x` (see [`stride_values`], [`grid_values`]) and on every pair of
/// small integers, within 1 LSB, with the quadrant (the sign of `y`) exact.
fn atan2_grid(numerators: u32, per_binade: u64) {
    let (ys, xs) = (stride_values(numerators), grid_values(per_binade));
    // And every pair of small integers (every direction at that scale, every quadrant).
    const SMALL: i32 = 512;
    let (nx, ny) = (xs.len() as i64, ys.len() as i64);
    let grid = ny * nx;
    let small = i64::from(2 * SMALL).pow(2);
    let (st, secs) = sweep(0..grid + small, [1.0], |i, st| {
        let (y, x) = if i < grid {
            (ys[(i / nx) as usize], xs[(i % nx) as usize])
        } else {
            let j = i - grid;
            (
                (j / i64::from(2 * SMALL)) as i32 - SMALL,
                (j % i64::from(2 * SMALL)) as i32 - SMALL,
            )
        };
        let got = fx(y).atan2(fx(x)).to_bits();
        // The quadrant: the sign of y (atan2(0, x < 0) = pi, atan2(0, x >= 0) = 0).
        let sign_ok = match y.signum() {
            1 => got >= 0,
            -1 => got <= 0,
            _ => got == if x < 0 { F::PI.to_bits() } else { 0 },
        };
        st[0].expect(i, (y, x), sign_ok);
        let want = f64::from(y).atan2(f64::from(x)) / LSB;
        st[0].add(i, (y, x), (f64::from(got) - want).abs());
    });
    st[0].finish(
        &format!(
            "atan2 ({} y x {} x, and every (y, x) in [-{SMALL}, {SMALL})^2 bits; \
             exact: the sign of y, atan2(0, x) = 0 or pi)",
            ys.len(),
            xs.len()
        ),
        "LSB",
        secs,
    );
}

/// `Real::arc_ratio` (`acos(c)/sqrt(1 - c^2)`, the polygon Lambert edge term's ratio): every
/// `c` in [0, 1] within its documented 3.9e-7 (1.62 LSB) of f64; outside, the documented
/// clamp (exactly 1 above 1, the value at 0 below 0) on every 61st bit pattern.
#[test]
fn arc_ratio_every_input_of_the_unit_interval() {
    let reference = |c: f64| {
        let s = ((1.0 - c) * (1.0 + c)).sqrt();
        if s == 0.0 {
            1.0
        } else {
            s.atan2(c) / s
        }
    };
    let at_zero = fx(0).arc_ratio();
    let (st, secs) = sweep(ALL, [1.62, 0.0], |i, st| {
        let b = i as i32;
        if (0..=1 << 22).contains(&b) {
            let got = fx(b)
                .arc_ratio()
                .map_or(f64::NAN, |r| f64::from(r.to_bits()));
            st[0].add(i, (b, 0), (got - reference(val(b)) / LSB).abs());
        } else if i % 61 == 0 {
            let want = if b > 0 { Some(F::ONE) } else { at_zero };
            st[1].expect(i, (b, 0), fx(b).arc_ratio() == want);
        }
    });
    st[0].finish("arc_ratio (every c in [0, 1])", "LSB", secs);
    st[1].finish("arc_ratio clamped outside [0, 1] (every 61st)", "", secs);
}
