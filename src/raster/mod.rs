//! A `no_std`, allocation-free triangle rasterizer that shades with the crate's lights
//! (`raster` feature).
//!
//! ## Method
//!
//! 1. **Vertices.** Each triangle's three vertices (position and normal, [`Vertex`]) go through
//!    the draw call's model transform ([`Affine`]; normals through its cofactor matrix, so
//!    non-uniform scales keep them perpendicular) and the [`Camera`] into homogeneous clip
//!    coordinates `(x, y, z, w)` (`z` the view depth, `w = z` in perspective, 1 in orthographic).
//! 2. **Clipping.** A triangle outside one of the near, far or guard-band planes (four times the
//!    viewport) is dropped; one that crosses them is clipped (Sutherland-Hodgman, at most 9
//!    vertices, a fan of triangles). Every intersection is computed from the inside vertex
//!    toward the outside one, so two triangles that share an edge clip it at the same point.
//! 3. **Edges.** Vertices are snapped to 1/16 pixel (the viewport transform from normalized
//!    device coordinates runs in these sub-pixel integers, [`Real::mul_u32_to_fixed_i32`], so
//!    fixed point, whose range is +-512, draws viewports up to [`MAX_VIEWPORT`] with their
//!    guard band; `tests/raster_fixed.rs` checks Fixed22's frames against f64's up to
//!    1024 x 1024) and the three edge functions are exact
//!    integers ([`edge`]): a pixel is drawn when its centre is inside, or on a top or left
//!    edge. Shared edges have no cracks and no pixel drawn twice, and the pixels and their
//!    weights do not depend on which rows are being drawn, so rendering a frame in bands gives
//!    the same bits as rendering it whole. Back faces (clockwise on screen) can be culled.
//! 4. **Interpolation.** A pixel's barycentric weights are its edge functions over the area;
//!    attributes are interpolated perspective-correctly (weights over `w`, renormalized).
//! 5. **Depth.** With a depth band, the interpolated view depth, mapped linearly from
//!    `[near, far]` to `0..=65535`, must be smaller than the stored one (16 bits, nearer wins,
//!    ties keep the first triangle drawn); it is tested before the pixel is shaded.
//! 6. **Shading.** Per draw call ([`Shading`]): Gouraud (the [`Shader`] at the vertices, colours
//!    interpolated) or per pixel (the shader at the interpolated position and renormalized
//!    normal). [`Lit`] shades a [`Material`] (diffuse colour, specular colour, Phong exponent)
//!    under any [`crate::Illuminant`].
//! 7. **Output.** The colour times the exposure is encoded ([`Encoding`]) into RGB565 or RGB888
//!    ([`PixelFormat`]) in the caller's [`Band`]: a 240x240 display renders in 240x16 strips
//!    with a 7.5 KiB colour band and a 7.5 KiB depth band.
//!
//! Nothing allocates and nothing panics: meshes are validated once ([`Mesh::new`]), invalid
//! geometry (a NaN vertex, a zero normal) is skipped or shaded with a fallback, and every
//! buffer access is checked.
//!
//! ## Cost
//!
//! Per triangle: 3 vertex transforms (~40 multiply-adds each), a band test, (Gouraud) 3 shader
//! calls, setup (~20 integer operations, 1 `f64` division). Per pixel of the triangle's
//! bounding box: 3 integer additions and comparisons; per covered pixel: 3 `i64 -> T`
//! conversions, ~15 multiply-adds and 1 division for the weights and depth, then Gouraud
//! ~10 multiply-adds, or per pixel ~30 multiply-adds, 2 normalizations and the shader.
//!
//! ```
//! use arealight::raster::{
//!     mesh, Affine, Band, Camera, DrawOptions, Lit, Material, Mesh, Projection, Rgb565, Shading,
//!     Vertex,
//! };
//! use arealight::{Rgb, SphereLight, Vec3};
//!
//! // A unit sphere lit by a spherical lamp, 64x64 in 64x16 bands.
//! let (mut verts, mut tris) = ([Vertex::default(); 17 * 9], [[0u16; 3]; 2 * 16 * 7]);
//! let counts = mesh::uv_sphere(1.0f32, 8, 16, &mut verts, &mut tris)?;
//! let sphere = Mesh::new(&verts[..counts.vertices], &tris[..counts.triangles])?;
//! let camera = Camera::new(
//!     Vec3::new(0.0, 0.0, 4.0), Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0),
//!     Projection::Perspective { fov_y: 0.7 }, 64, 64,
//! )?;
//! let lamp = SphereLight::new(Vec3::new(2.0, 2.0, 3.0), 0.5)?;
//! let plastic = Material::new(Rgb::new(0.8, 0.3, 0.2), Rgb::splat(0.5), 16)?;
//! let shader = Lit::new(&lamp, &plastic);
//! let opts = DrawOptions::new(Shading::PerPixel);
//!
//! let (mut pixels, mut depth) = ([Rgb565(0); 64 * 16], [0u16; 64 * 16]);
//! let mut band = Band::new(&mut pixels, Some(&mut depth), 64, 0)?;
//! for y0 in (0..64).step_by(16) {
//!     band.move_to(y0);
//!     band.clear(Rgb565(0));
//!     arealight::raster::draw(&camera, &mut band, &sphere, &Affine::identity(), &shader, &opts)?;
//!     // send band.pixels() to the display's rows y0..y0 + 16 here
//! }
//! # Ok::<(), arealight::raster::RasterError>(())
//! ```

use core::fmt;

use crate::{Error, Real, Rgb, UnitVec3, Vec3};

mod affine;
mod camera;
mod clip;
mod draw;
pub mod edge;
#[cfg(feature = "embedded-graphics")]
pub mod eg;
mod gouraud;
pub mod mesh;
pub mod prepared;
mod scan;
pub mod shade;
pub mod split;
pub mod target;

pub use edge::{Cull, EdgeTriangle, FixedPoint};
pub use mesh::MeshCounts;
pub use prepared::{PreparedMesh, PreparedVertex, TriangleRows, VertexColour, VertexScreen};
pub use shade::{reflect, Lit, Material, Shader, Shading};
pub use split::{LightSums, SplitLit, SplitShader};
pub use target::{
    encode_pixel, Band, EncodeTable, Encoding, PixelFormat, Rgb565, Rgb888, ToneMap, DEPTH_FAR,
    ENCODE_ENTRIES, ENCODE_INDEX_BITS, TONE_WHITE_MAX_PERCENT,
};

pub use affine::Affine;
pub use camera::{Camera, Projection};
use clip::{clip_polygon, plane_distances, ClipVert, MAX_CLIPPED};
pub use draw::{draw, render_in_bands};
use edge::SUBPIXEL;

/// Why the rasterizer refused an input.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum RasterError {
    /// A light, lobe or vector refused by the crate's models.
    Model(Error),
    /// A caller buffer shorter than needed.
    BufferTooSmall {
        /// Which buffer (`"vertices"`, `"triangles"`, `"depth"`).
        what: &'static str,
        /// The length needed.
        needed: usize,
        /// The length given.
        got: usize,
    },
    /// A size that is zero, too large (viewports up to 4096 pixels a side) or inconsistent
    /// (a band whose width is not the camera's); names what.
    BadSize(&'static str),
    /// A mesh parameter out of its range (named: `"stacks"`, `"slices"`, `"radius"`, ...).
    BadParameter(&'static str),
    /// A triangle of a mesh refers to a vertex that does not exist.
    IndexOutOfRange {
        /// The triangle's position in the index buffer.
        triangle: usize,
        /// The offending index.
        index: u16,
    },
    /// A mesh needs more vertices than 16-bit indices can address (65536).
    TooManyVertices {
        /// The number of vertices needed.
        needed: usize,
    },
}

impl From<Error> for RasterError {
    fn from(e: Error) -> Self {
        RasterError::Model(e)
    }
}

impl fmt::Display for RasterError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RasterError::Model(e) => write!(f, "{e}"),
            RasterError::BufferTooSmall { what, needed, got } => {
                write!(f, "{what} buffer too small: {needed} needed, {got} given")
            }
            RasterError::BadSize(what) => write!(f, "bad size: {what}"),
            RasterError::BadParameter(what) => write!(f, "{what} is out of range"),
            RasterError::IndexOutOfRange { triangle, index } => {
                write!(f, "triangle {triangle} refers to missing vertex {index}")
            }
            RasterError::TooManyVertices { needed } => {
                write!(f, "{needed} vertices exceed 16-bit indices (65536)")
            }
        }
    }
}

impl core::error::Error for RasterError {}

/// The largest viewport side, in pixels.
pub const MAX_VIEWPORT: u16 = 4096;

/// A mesh vertex: position and normal (object space; the normal need not be unit length).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vertex<T> {
    /// Position.
    pub position: Vec3<T>,
    /// Normal (normalized by the renderer after the transform).
    pub normal: Vec3<T>,
}

impl<T: Real> Vertex<T> {
    /// A vertex at `position` with `normal`.
    pub const fn new(position: Vec3<T>, normal: Vec3<T>) -> Self {
        Vertex { position, normal }
    }
}

/// A validated indexed triangle mesh borrowing the caller's buffers. Triangles are
/// counter-clockwise seen from the front.
#[derive(Clone, Copy, Debug)]
pub struct Mesh<'a, T> {
    vertices: &'a [Vertex<T>],
    triangles: &'a [[u16; 3]],
}

impl<'a, T: Real> Mesh<'a, T> {
    /// Checks every index once. Cost: O(triangles).
    ///
    /// # Errors
    /// [`RasterError::IndexOutOfRange`] for the first triangle with a missing vertex.
    pub fn new(vertices: &'a [Vertex<T>], triangles: &'a [[u16; 3]]) -> Result<Self, RasterError> {
        for (t, tri) in triangles.iter().enumerate() {
            for &i in tri {
                if i as usize >= vertices.len() {
                    return Err(RasterError::IndexOutOfRange {
                        triangle: t,
                        index: i,
                    });
                }
            }
        }
        Ok(Mesh {
            vertices,
            triangles,
        })
    }
    /// The vertices.
    pub fn vertices(&self) -> &'a [Vertex<T>] {
        self.vertices
    }
    /// The triangles.
    pub fn triangles(&self) -> &'a [[u16; 3]] {
        self.triangles
    }
}

/// Per draw call options.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DrawOptions<T> {
    /// Gouraud or per pixel.
    pub shading: Shading,
    /// Which faces to skip.
    pub cull: Cull,
    /// Shade back faces with the normal flipped toward the viewer (for open surfaces seen
    /// from both sides; use with [`Cull::None`]).
    pub two_sided: bool,
    /// Multiplies the linear colour before encoding.
    pub exposure: T,
    /// The transfer function into the pixel format.
    pub encoding: Encoding,
}

impl<T: Real> DrawOptions<T> {
    /// `shading` with back faces culled, one-sided, exposure 1, sRGB encoding.
    pub fn new(shading: Shading) -> Self {
        DrawOptions {
            shading,
            cull: Cull::Back,
            two_sided: false,
            exposure: T::ONE,
            encoding: Encoding::Srgb,
        }
    }
}

/// What a draw call did (for budgets and tests).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct DrawStats {
    /// Triangles of the mesh.
    pub triangles: u32,
    /// Triangles (after clipping, fan pieces counted) set up for scan conversion in this band:
    /// those whose pixel box meets the band's rows (a triangle that covers no pixel centre
    /// there is dropped before its setup).
    pub rasterized: u32,
    /// Shader calls.
    pub shaded: u32,
    /// Pixels written.
    pub pixels: u32,
}

#[cfg(feature = "defmt")]
mod defmt_impls {
    use super::*;

    impl defmt::Format for RasterError {
        fn format(&self, f: defmt::Formatter<'_>) {
            match self {
                RasterError::Model(e) => defmt::write!(f, "Model({})", defmt::Display2Format(e)),
                RasterError::BufferTooSmall { what, needed, got } => defmt::write!(
                    f,
                    "BufferTooSmall {{ what: {=str}, needed: {}, got: {} }}",
                    what,
                    needed,
                    got
                ),
                RasterError::BadSize(w) => defmt::write!(f, "BadSize({=str})", w),
                RasterError::BadParameter(w) => defmt::write!(f, "BadParameter({=str})", w),
                RasterError::IndexOutOfRange { triangle, index } => defmt::write!(
                    f,
                    "IndexOutOfRange {{ triangle: {}, index: {} }}",
                    triangle,
                    index
                ),
                RasterError::TooManyVertices { needed } => {
                    defmt::write!(f, "TooManyVertices {{ needed: {} }}", needed)
                }
            }
        }
    }

    impl<T: Real> defmt::Format for Vertex<T> {
        fn format(&self, f: defmt::Formatter<'_>) {
            defmt::write!(
                f,
                "Vertex {{ position: {}, normal: {} }}",
                self.position.to_f64(),
                self.normal.to_f64()
            )
        }
    }

    impl<T: Real> defmt::Format for Mesh<'_, T> {
        fn format(&self, f: defmt::Formatter<'_>) {
            defmt::write!(
                f,
                "Mesh {{ vertices: {}, triangles: {} }}",
                self.vertices.len(),
                self.triangles.len()
            )
        }
    }

    impl<T: Real> defmt::Format for Affine<T> {
        fn format(&self, f: defmt::Formatter<'_>) {
            defmt::write!(
                f,
                "Affine {{ m: [{}, {}, {}], t: {} }}",
                self.m[0].to_f64(),
                self.m[1].to_f64(),
                self.m[2].to_f64(),
                self.t.to_f64()
            )
        }
    }

    impl<T: Real> defmt::Format for Projection<T> {
        fn format(&self, f: defmt::Formatter<'_>) {
            match self {
                Projection::Perspective { fov_y } => {
                    defmt::write!(f, "Perspective {{ fov_y: {} }}", fov_y.to_f64())
                }
                Projection::Orthographic { half_height } => defmt::write!(
                    f,
                    "Orthographic {{ half_height: {} }}",
                    half_height.to_f64()
                ),
            }
        }
    }

    impl<T: Real> defmt::Format for Camera<T> {
        fn format(&self, f: defmt::Formatter<'_>) {
            defmt::write!(
                f,
                "Camera {{ eye: {}, forward: {}, {}x{}, depth: [{}, {}] }}",
                self.eye.to_f64(),
                self.forward.to_f64(),
                self.width,
                self.height,
                self.near.to_f64(),
                self.far.to_f64()
            )
        }
    }

    impl<T: Real> defmt::Format for DrawOptions<T> {
        fn format(&self, f: defmt::Formatter<'_>) {
            defmt::write!(
                f,
                "DrawOptions {{ shading: {}, cull: {}, two_sided: {}, exposure: {}, encoding: {} }}",
                self.shading,
                self.cull,
                self.two_sided,
                self.exposure.to_f64(),
                self.encoding
            )
        }
    }

    impl<T: Real> defmt::Format for Material<T> {
        fn format(&self, f: defmt::Formatter<'_>) {
            defmt::write!(
                f,
                "Material {{ diffuse: {}, specular: {}, m: {} }}",
                self.diffuse.to_f64(),
                self.specular.to_f64(),
                self.lobe.exponent()
            )
        }
    }

    impl<P: PixelFormat> defmt::Format for Band<'_, P> {
        fn format(&self, f: defmt::Formatter<'_>) {
            defmt::write!(
                f,
                "Band {{ width: {}, rows: {}, y0: {}, depth: {} }}",
                self.width(),
                self.rows(),
                self.y0(),
                self.depth().is_some()
            )
        }
    }
}
