//! What the firmware and the host render, and the only code that calls `demo_scene`'s API:
//! shared by `src/main.rs` and `host-sim/tests/qemu_frame.rs` (included there with `#[path]`),
//! so both sides render the same frames the same way, and a change of that API is adapted here
//! once.
//!
//! It names the scene `crate::demo_scene`: the firmware's `extern crate`, the host test's
//! module (of demo-scene's source, included with `#[path]`).

use crate::demo_scene::{Demo, FrameError, FrameReport, MeshBuffers, Object};
use arealight::raster::{Band, EncodeTable, RasterError, Rgb565, Shading};

/// The frames rendered, in this order, in every mode.
pub const FRAMES: [u32; 2] = [0, 30];

/// The shading modes, by their name in the output, as the shading of the sphere and of the
/// torus: Gouraud (the light models at the vertices: the firmware's mode), per pixel on the
/// sphere alone (its broad highlight is where Gouraud shows its facets), per pixel throughout.
pub const MODES: [(&str, [Shading; 2]); 3] = [
    ("gouraud", [Shading::Gouraud, Shading::Gouraud]),
    ("sphere_per_pixel", [Shading::PerPixel, Shading::Gouraud]),
    ("per_pixel", [Shading::PerPixel, Shading::PerPixel]),
];

/// The storage a [`Demo`] borrows: the meshes and their per-frame data (61 584 bytes in
/// `f32`) and the encoding table (8 200 bytes). The firmware keeps it in a `static` with the
/// constant initializer `Storage::new()`.
pub struct Storage {
    meshes: MeshBuffers<f32>,
    table: EncodeTable,
}

impl Storage {
    /// Zeroed storage ([`demo`] fills it).
    pub const fn new() -> Self {
        Storage {
            meshes: MeshBuffers::new(),
            table: EncodeTable::zeroed(),
        }
    }
}

/// The demo scene in `f32` with `shading` for the sphere and the torus.
///
/// # Errors
/// `Demo::new`'s (none with the scene's constants).
pub fn demo(storage: &mut Storage, shading: [Shading; 2]) -> Result<Demo<'_, f32>, RasterError> {
    let mut demo = Demo::new(&mut storage.meshes, &mut storage.table, shading[0])?;
    demo.set_shading(Object::Sphere, shading[0]);
    demo.set_shading(Object::Torus, shading[1]);
    Ok(demo)
}

/// Renders frame `n` of `demo` through `band`, as every board does: `clock` is read between
/// the stages, `flush` gets each finished band, top to bottom.
///
/// # Errors
/// The first error of the rasterizer or of `flush`.
pub fn render<E>(
    demo: &mut Demo<'_, f32>,
    n: u32,
    band: &mut Band<'_, Rgb565>,
    clock: &mut impl FnMut() -> u32,
    flush: impl FnMut(&Band<'_, Rgb565>) -> Result<(), E>,
) -> Result<FrameReport, FrameError<E>> {
    demo.render_frame(n, band, clock, flush)
}
