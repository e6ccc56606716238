//! cargo-fuzz target: the rasterizer (`arealight::raster`) on arbitrary input: cameras, meshes,
//! transforms, materials, options and band sizes, drawn by `draw` and the prepared path
//! (tests/fuzzing/mod.rs), f64, f32, Fast32 and Fixed22.
#![no_main]
use libfuzzer_sys::fuzz_target;

#[path = "../../tests/fuzzing/mod.rs"]
mod fuzzing;

fuzz_target!(|data: &[u8]| {
    fuzzing::run(fuzzing::Family::Raster, data);
});
