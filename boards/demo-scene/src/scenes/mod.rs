//! The scene files of `host-sim/scenes/` that the boards render (besides the demo), as
//! [`SceneSpec`] constants written by `host-sim budget --scene FILE --emit-spec OUT.rs` (CI
//! regenerates each and fails on a difference). The firmware renders them with
//! [`crate::spec::Player`] so that `host-sim budget --check` can compare its predictions with
//! the emulated frames of more than one scene.

use crate::spec::SceneSpec;

/// A desk under a round lamp: a sphere light, a point light and ambient light over a table
/// top (Gouraud), a box (per pixel) and a torus (Gouraud, Phong exponent 32).
#[rustfmt::skip]
pub mod desk_lamp;
/// Light through a window: a polygon light, the overcast sky and the sun (a cap) over a floor
/// (Gouraud), a sphere (Gouraud, Phong exponent 16) and a box (per pixel).
#[rustfmt::skip]
pub mod window_light;

/// Every scene, in this order.
pub const ALL: [&SceneSpec; 2] = [&desk_lamp::SCENE, &window_light::SCENE];

/// The most vertices of any scene (the size of the players' buffers).
pub const VERTICES: usize = max(desk_lamp::VERTICES, window_light::VERTICES);
/// The most triangles of any scene.
pub const TRIANGLES: usize = max(desk_lamp::TRIANGLES, window_light::TRIANGLES);

const fn max(a: usize, b: usize) -> usize {
    if a > b {
        a
    } else {
        b
    }
}
