//! The bit-pattern fuzzer that always runs in `cargo test`: proptest feeds every model family
//! (tests/fuzzing: every public constructor and per-sample function) with arbitrary f32 bit
//! patterns, biased toward NaN, infinities, zeros of both signs, subnormals, the extremes of
//! the range and values near the geometric degeneracies (tiny, huge, 1 +- ULP), on f64, f32 and
//! Fast32. No panic and no NaN or infinity out, ever.
//!
//! Cases per family: `AREALIGHT_FUZZ_CASES` (default 2000; STABILITY.md gives the counts of
//! the longer local runs). The cargo-fuzz targets in `fuzz/` run the same bodies under
//! libFuzzer. Crash inputs found by either are kept below as regression tests.

mod fuzzing;

use fuzzing::{run, Family, FAMILIES};
use proptest::prelude::*;

fn cases() -> u32 {
    std::env::var("AREALIGHT_FUZZ_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2000)
}

/// One 32-bit word of fuzz input: raw bits, a special value, or an ordinary-looking value.
fn word() -> impl Strategy<Value = u32> {
    let specials: Vec<u32> = [
        f32::NAN,
        -f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        0.0,
        -0.0,
        f32::MIN_POSITIVE,
        -f32::MIN_POSITIVE,
        f32::from_bits(1),
        f32::from_bits(0x8000_0001),
        f32::from_bits(0x007f_ffff),
        f32::MAX,
        f32::MIN,
        1.0,
        -1.0,
        1.0 + f32::EPSILON,
        1.0 - f32::EPSILON / 2.0,
        1e-20,
        1e-10,
        1e10,
        1e19,
        1e30,
        std::f32::consts::FRAC_PI_2,
        std::f32::consts::PI,
    ]
    .iter()
    .map(|x| x.to_bits())
    .chain([u32::MAX, u32::MAX - 1, u32::MAX - 2, 0, 1, 2, 3, 64, 1001])
    .collect();
    prop_oneof![
        3 => any::<u32>(),
        3 => proptest::sample::select(specials),
        4 => (-4.0f32..4.0).prop_map(f32::to_bits),
        1 => (-30i32..30, -1.0f32..1.0).prop_map(|(e, x)| (x * 10f32.powi(e)).to_bits()),
    ]
}

fn bytes() -> impl Strategy<Value = Vec<u8>> {
    prop::collection::vec(word(), 0..64)
        .prop_map(|ws| ws.iter().flat_map(|w| w.to_le_bytes()).collect())
}

macro_rules! fuzz_family {
    ($name:ident, $fam:expr) => {
        proptest! {
            #![proptest_config(ProptestConfig {
                cases: cases(),
                failure_persistence: None,
                ..ProptestConfig::default()
            })]
            #[test]
            fn $name(data in bytes()) {
                run($fam, &data);
            }
        }
    };
}

fuzz_family!(fuzz_hemisphere, Family::Hemisphere);
fuzz_family!(fuzz_cap, Family::Cap);
fuzz_family!(fuzz_polygon, Family::Polygon);
fuzz_family!(fuzz_moments, Family::Moments);
fuzz_family!(fuzz_sh9, Family::Sh9);
fuzz_family!(fuzz_line, Family::Line);
fuzz_family!(fuzz_shaping, Family::Shaping);

/// Every family on the empty input, all-ones bits (NaN everywhere) and all zeros.
#[test]
fn fuzz_fixed_inputs() {
    for fam in FAMILIES {
        run(fam, &[]);
        run(fam, &[0xff; 256]);
        run(fam, &[0; 256]);
        run(fam, &[0x7f; 256]); // 3.39e38, near f32::MAX
    }
}
