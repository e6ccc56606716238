//! cargo-fuzz target: the rasterizer's integer geometry (edge functions, the top-left rule,
//! pixel centres, the triangle setup and its queries) on arbitrary `i32` sub-pixel
//! coordinates (tests/fuzzing/mod.rs).
#![no_main]
use libfuzzer_sys::fuzz_target;

#[path = "../../tests/fuzzing/mod.rs"]
mod fuzzing;

fuzz_target!(|data: &[u8]| {
    fuzzing::run(fuzzing::Family::RasterEdges, data);
});
