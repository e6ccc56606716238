//! cargo-fuzz target: every constructor and per-sample function of the `hemisphere` family on
//! arbitrary f32 bit patterns (tests/fuzzing/mod.rs), f64, f32, Fast32 and Fixed22.
#![no_main]
use libfuzzer_sys::fuzz_target;

#[path = "../../tests/fuzzing/mod.rs"]
mod fuzzing;

fuzz_target!(|data: &[u8]| {
    fuzzing::run(fuzzing::Family::Hemisphere, data);
});
