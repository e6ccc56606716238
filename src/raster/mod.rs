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
//! 3. **Edges.** Vertices are snapped to 1/16 pixel and the three edge functions are exact
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

use crate::{Error, Real, Rgb, Vec3};

pub mod edge;
#[cfg(feature = "embedded-graphics")]
pub mod eg;
pub mod mesh;
pub mod prepared;
pub mod shade;
pub mod target;

pub use edge::{Cull, EdgeTriangle, FixedPoint};
pub use mesh::MeshCounts;
pub use prepared::{PreparedMesh, PreparedVertex, VertexColour};
pub use shade::{reflect, Lit, Material, Shader, Shading};
pub use target::{
    encode_pixel, Band, EncodeTable, Encoding, PixelFormat, Rgb565, Rgb888, ToneMap, DEPTH_FAR,
    ENCODE_ENTRIES, ENCODE_INDEX_BITS, TONE_WHITE_MAX_PERCENT,
};

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
/// The guard band: triangles are clipped to `|x|, |y| <= GUARD w` in clip space (four times
/// the viewport), far inside the edge functions' exact range.
const GUARD: f64 = 4.0;

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

/// An affine model transform `p -> M p + t`; normals go through the cofactor matrix of `M`
/// (the inverse transpose up to a positive scale), so they stay perpendicular to surfaces
/// under any invertible `M`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Affine<T> {
    /// Rows of `M`.
    m: [Vec3<T>; 3],
    t: Vec3<T>,
    /// Rows of `sign(det M) cof(M)`.
    nm: [Vec3<T>; 3],
}

impl<T: Real> Affine<T> {
    fn from_parts(m: [Vec3<T>; 3], t: Vec3<T>) -> Self {
        let c = [m[1].cross(m[2]), m[2].cross(m[0]), m[0].cross(m[1])];
        let det = m[0].dot(c[0]);
        let s = if det < T::ZERO { -T::ONE } else { T::ONE };
        // M^-1 has the columns c[i]/det, so M^-T (the normal matrix) has them as rows.
        let nm = [c[0] * s, c[1] * s, c[2] * s];
        Affine { m, t, nm }
    }

    /// The identity.
    pub fn identity() -> Self {
        let (o, l) = (T::ZERO, T::ONE);
        Self::from_parts(
            [Vec3::new(l, o, o), Vec3::new(o, l, o), Vec3::new(o, o, l)],
            Vec3::new(o, o, o),
        )
    }

    /// A translation by `t`.
    ///
    /// # Errors
    /// [`RasterError::Model`] with [`Error::NotFinite`] (`"t"`).
    pub fn translation(t: Vec3<T>) -> Result<Self, RasterError> {
        if !t.is_finite() {
            return Err(Error::NotFinite("t").into());
        }
        let mut a = Self::identity();
        a.t = t;
        Ok(a)
    }

    /// A scale by `s` per axis (non-zero, finite).
    ///
    /// # Errors
    /// [`RasterError::Model`] with [`Error::NotFinite`] (`"scale"`) or
    /// [`RasterError::BadParameter`] (`"scale"`) for a zero component.
    pub fn scale(s: Vec3<T>) -> Result<Self, RasterError> {
        if !s.is_finite() {
            return Err(Error::NotFinite("scale").into());
        }
        if s.x == T::ZERO || s.y == T::ZERO || s.z == T::ZERO {
            return Err(RasterError::BadParameter("scale"));
        }
        let o = T::ZERO;
        Ok(Self::from_parts(
            [
                Vec3::new(s.x, o, o),
                Vec3::new(o, s.y, o),
                Vec3::new(o, o, s.z),
            ],
            Vec3::new(o, o, o),
        ))
    }

    /// A rotation by `angle` (radians, right-handed) about the unit axis `axis` (any length).
    ///
    /// # Errors
    /// [`RasterError::Model`] with [`Error::NotFinite`] / [`Error::ZeroLength`] (`"axis"`) or
    /// [`Error::NotFinite`] (`"angle"`).
    pub fn rotation(axis: Vec3<T>, angle: T) -> Result<Self, RasterError> {
        let a = axis.try_normalize("axis")?;
        if !angle.is_finite() {
            return Err(Error::NotFinite("angle").into());
        }
        let (s, c) = (angle.sin(), angle.cos());
        let k = T::ONE - c;
        let m = [
            Vec3::new(
                c + a.x * a.x * k,
                a.x * a.y * k - a.z * s,
                a.x * a.z * k + a.y * s,
            ),
            Vec3::new(
                a.y * a.x * k + a.z * s,
                c + a.y * a.y * k,
                a.y * a.z * k - a.x * s,
            ),
            Vec3::new(
                a.z * a.x * k - a.y * s,
                a.z * a.y * k + a.x * s,
                c + a.z * a.z * k,
            ),
        ];
        Ok(Self::from_parts(m, Vec3::new(T::ZERO, T::ZERO, T::ZERO)))
    }

    /// `self` followed by `next` (`next(self(p))`).
    pub fn then(&self, next: &Self) -> Self {
        let col = |j: usize| {
            let pick = |v: Vec3<T>| match j {
                0 => v.x,
                1 => v.y,
                _ => v.z,
            };
            Vec3::new(pick(self.m[0]), pick(self.m[1]), pick(self.m[2]))
        };
        let (c0, c1, c2) = (col(0), col(1), col(2));
        let m = core::array::from_fn(|i| {
            let r = next.m[i];
            Vec3::new(r.dot(c0), r.dot(c1), r.dot(c2))
        });
        let t = next.point(self.t);
        Self::from_parts(m, t)
    }

    /// The transformed point `M p + t`. Cost: 9 multiply-adds.
    #[inline]
    pub fn point(&self, p: Vec3<T>) -> Vec3<T> {
        Vec3::new(self.m[0].dot(p), self.m[1].dot(p), self.m[2].dot(p)) + self.t
    }

    /// The transformed normal direction (not normalized). Cost: 9 multiply-adds.
    #[inline]
    pub fn normal(&self, n: Vec3<T>) -> Vec3<T> {
        Vec3::new(self.nm[0].dot(n), self.nm[1].dot(n), self.nm[2].dot(n))
    }
}

/// The camera's projection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection<T> {
    /// Perspective with vertical field of view `fov_y` (radians, in (0, pi)).
    Perspective {
        /// Vertical field of view, radians.
        fov_y: T,
    },
    /// Orthographic, showing `half_height` world units above and below the centre.
    Orthographic {
        /// Half the visible height, world units.
        half_height: T,
    },
}

/// A camera: position, orientation, projection and viewport size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera<T> {
    eye: Vec3<T>,
    right: Vec3<T>,
    up: Vec3<T>,
    forward: Vec3<T>,
    perspective: bool,
    sx: T,
    sy: T,
    width: u16,
    height: u16,
    near: T,
    far: T,
}

impl<T: Real> Camera<T> {
    /// A camera at `eye` looking at `target`, with `up` (any length, not parallel to the view)
    /// giving the roll, for a `width` x `height` viewport. The depth range is
    /// `[d/64, 16 d]`, `d = |target - eye|`; see [`Camera::with_depth_range`].
    ///
    /// # Errors
    /// [`RasterError::Model`] for a non-finite or zero vector, `up` parallel to the view
    /// ([`Error::Parallel`]), a non-finite projection parameter;
    /// [`RasterError::BadParameter`] (`"fov_y"`, `"half_height"`) for one out of range;
    /// [`RasterError::BadSize`] (`"viewport"`) for a side of 0 or above [`MAX_VIEWPORT`].
    pub fn new(
        eye: Vec3<T>,
        target: Vec3<T>,
        up: Vec3<T>,
        projection: Projection<T>,
        width: u16,
        height: u16,
    ) -> Result<Self, RasterError> {
        if width == 0 || height == 0 || width > MAX_VIEWPORT || height > MAX_VIEWPORT {
            return Err(RasterError::BadSize("viewport"));
        }
        if !eye.is_finite() {
            return Err(Error::NotFinite("eye").into());
        }
        if !target.is_finite() {
            return Err(Error::NotFinite("target").into());
        }
        let (forward, dist) = (target - eye)
            .normalize_with_length()
            .ok_or(Error::ZeroLength("target - eye"))?;
        let up = up.try_normalize("up")?;
        let parallel = Error::Parallel {
            a: "up",
            b: "target - eye",
        };
        let side = forward.cross(up);
        if !(side.length() > T::from_f64(1e-6)) {
            return Err(parallel.into());
        }
        let right = side.normalize().ok_or(parallel)?;
        let up = right.cross(forward);
        let aspect = T::from_u32(width as u32) / T::from_u32(height as u32);
        let (perspective, sy) = match projection {
            Projection::Perspective { fov_y } => {
                if !fov_y.is_finite() {
                    return Err(Error::NotFinite("fov_y").into());
                }
                if !(fov_y > T::ZERO && fov_y < T::PI) {
                    return Err(RasterError::BadParameter("fov_y"));
                }
                let half = fov_y * T::HALF;
                (true, half.cos() / half.sin())
            }
            Projection::Orthographic { half_height } => {
                if !half_height.is_finite() {
                    return Err(Error::NotFinite("half_height").into());
                }
                if !(half_height > T::ZERO) {
                    return Err(RasterError::BadParameter("half_height"));
                }
                (false, T::ONE / half_height)
            }
        };
        Ok(Camera {
            eye,
            right,
            up,
            forward,
            perspective,
            sx: sy / aspect,
            sy,
            width,
            height,
            near: dist * T::from_f64(1.0 / 64.0),
            far: dist * T::from_f64(16.0),
        })
    }

    /// The same camera with the depth range `[near, far]` (view distances along the view
    /// direction; geometry outside is clipped; the 16-bit depth is linear in it).
    ///
    /// # Errors
    /// [`RasterError::BadParameter`] (`"near"`, `"far"`) unless `0 < near < far`, finite.
    pub fn with_depth_range(mut self, near: T, far: T) -> Result<Self, RasterError> {
        if !(near > T::ZERO) || !near.is_finite() {
            return Err(RasterError::BadParameter("near"));
        }
        if !(far > near) || !far.is_finite() {
            return Err(RasterError::BadParameter("far"));
        }
        self.near = near;
        self.far = far;
        Ok(self)
    }

    /// The same camera (eye, orientation, vertical field of view or height) for a `width` x
    /// `height` viewport: for supersampling, `k` times each side.
    ///
    /// # Errors
    /// [`RasterError::BadSize`] (`"viewport"`) for a side of 0 or above [`MAX_VIEWPORT`].
    pub fn with_viewport(mut self, width: u16, height: u16) -> Result<Self, RasterError> {
        if width == 0 || height == 0 || width > MAX_VIEWPORT || height > MAX_VIEWPORT {
            return Err(RasterError::BadSize("viewport"));
        }
        self.sx = self.sy / (T::from_u32(width as u32) / T::from_u32(height as u32));
        self.width = width;
        self.height = height;
        Ok(self)
    }

    /// The viewport width in pixels.
    pub fn width(&self) -> u16 {
        self.width
    }
    /// The viewport height in pixels.
    pub fn height(&self) -> u16 {
        self.height
    }
    /// The eye position.
    pub fn eye(&self) -> Vec3<T> {
        self.eye
    }
    /// The unit view direction.
    pub fn forward(&self) -> Vec3<T> {
        self.forward
    }

    /// Clip coordinates `(x, y, z, w)` of a world point (`z` the view depth).
    #[inline]
    fn clip(&self, p: Vec3<T>) -> [T; 4] {
        let d = p - self.eye;
        let z = d.dot(self.forward);
        [
            d.dot(self.right) * self.sx,
            d.dot(self.up) * self.sy,
            z,
            if self.perspective { z } else { T::ONE },
        ]
    }

    /// The unit direction from `p` toward the eye (the view direction itself for an
    /// orthographic camera). Cost: 1 normalization (perspective).
    #[inline]
    pub fn view_dir(&self, p: Vec3<T>) -> Vec3<T> {
        if self.perspective {
            (self.eye - p).normalize().unwrap_or(-self.forward)
        } else {
            -self.forward
        }
    }

    /// The pixel coordinates `(x, y)` (`y` down, pixel centres at `i + 0.5`) of a world point
    /// in front of the camera, or `None` behind the near plane.
    pub fn project(&self, p: Vec3<T>) -> Option<(T, T)> {
        let c = self.clip(p);
        if !(c[2] >= self.near) {
            return None;
        }
        Some(self.screen_xy(c))
    }

    #[inline]
    fn screen_xy(&self, c: [T; 4]) -> (T, T) {
        let iw = T::ONE / c[3];
        let hw = T::from_u32(self.width as u32) * T::HALF;
        let hh = T::from_u32(self.height as u32) * T::HALF;
        ((c[0] * iw + T::ONE) * hw, (T::ONE - c[1] * iw) * hh)
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
    /// Triangles (after clipping, fan pieces counted) set up for scan conversion in this band.
    pub rasterized: u32,
    /// Shader calls.
    pub shaded: u32,
    /// Pixels written.
    pub pixels: u32,
}

/// A vertex in clip space with its interpolated attributes.
#[derive(Clone, Copy, Debug)]
struct ClipVert<T> {
    c: [T; 4],
    p: Vec3<T>,
    n: Vec3<T>,
    col: Rgb<T>,
}

impl<T: Real> ClipVert<T> {
    fn lerp(&self, o: &Self, t: T) -> Self {
        let l = |a: T, b: T| a + (b - a) * t;
        ClipVert {
            c: core::array::from_fn(|i| l(self.c[i], o.c[i])),
            p: self.p + (o.p - self.p) * t,
            n: self.n + (o.n - self.n) * t,
            col: Rgb::new(
                l(self.col.r, o.col.r),
                l(self.col.g, o.col.g),
                l(self.col.b, o.col.b),
            ),
        }
    }
}

const MAX_CLIPPED: usize = 9;

/// Signed distances to the six clip planes (inside >= 0): near, far, and the guard band.
#[inline]
fn plane_distances<T: Real>(c: &[T; 4], near: T, far: T) -> [T; 6] {
    let g = T::from_f64(GUARD) * c[3];
    [
        c[2] - near,
        far - c[2],
        g - c[0],
        g + c[0],
        g - c[1],
        g + c[1],
    ]
}

/// Sutherland-Hodgman against the six planes; returns the number of vertices written.
fn clip_polygon<T: Real>(
    tri: [ClipVert<T>; 3],
    near: T,
    far: T,
    out: &mut [ClipVert<T>; MAX_CLIPPED],
) -> usize {
    let mut a = [tri[0]; MAX_CLIPPED];
    a[..3].copy_from_slice(&tri);
    let mut na = 3;
    let mut b = [tri[0]; MAX_CLIPPED];
    for plane in 0..6 {
        let mut nb = 0;
        for i in 0..na {
            let (p, q) = (a[i], a[(i + 1) % na]);
            let dp = plane_distances(&p.c, near, far)[plane];
            let dq = plane_distances(&q.c, near, far)[plane];
            let (pin, qin) = (dp >= T::ZERO, dq >= T::ZERO);
            if pin && nb < MAX_CLIPPED {
                b[nb] = p;
                nb += 1;
            }
            if pin != qin && nb < MAX_CLIPPED {
                // From the inside vertex toward the outside one: the same point for both
                // triangles that share this edge.
                let (i_v, o_v, di, dout) = if pin { (p, q, dp, dq) } else { (q, p, dq, dp) };
                let t = (di / (di - dout)).clamp01();
                b[nb] = i_v.lerp(&o_v, t);
                nb += 1;
            }
        }
        a = b;
        na = nb;
        if na < 3 {
            return 0;
        }
    }
    out[..na].copy_from_slice(&a[..na]);
    na
}

/// `floor(x)` of an `f64` that fits an `i32` (the pipeline's screen coordinates do).
#[inline]
fn floor_i32(x: f64) -> i32 {
    let t = x as i32;
    if (t as f64) > x {
        t - 1
    } else {
        t
    }
}

#[inline]
fn snap<T: Real>(x: T) -> i32 {
    floor_i32(x.to_f64() * SUBPIXEL as f64 + 0.5)
}

/// Draws `mesh` (through `transform`) with `shader` into `band`: every triangle clipped to the
/// band's rows, depth-tested if the band has a depth band.
///
/// Accuracy: exact coverage (see [`edge`]); attributes interpolated perspective-correctly to
/// the backend's rounding; colours quantized to the pixel format. Cost: see the module docs.
///
/// # Errors
/// [`RasterError::BadSize`] (`"band width"`) when the band is not as wide as the camera's
/// viewport. Nothing else fails: degenerate or non-finite triangles are skipped.
pub fn draw<T, P, S>(
    camera: &Camera<T>,
    band: &mut Band<'_, P>,
    mesh: &Mesh<'_, T>,
    transform: &Affine<T>,
    shader: &S,
    opts: &DrawOptions<T>,
) -> Result<DrawStats, RasterError>
where
    T: Real,
    P: PixelFormat,
    S: Shader<T> + ?Sized,
{
    if band.width() != camera.width {
        return Err(RasterError::BadSize("band width"));
    }
    let mut stats = DrawStats {
        triangles: mesh.triangles.len() as u32,
        ..DrawStats::default()
    };
    let row0 = band.y0() as i32;
    let row1 = (band.y0() as i32 + band.rows() as i32).min(camera.height as i32);
    if row0 >= row1 {
        return Ok(stats);
    }
    let (near, far) = (camera.near, camera.far);
    for tri in mesh.triangles {
        let mut cv = [ClipVert {
            c: [T::ZERO; 4],
            p: Vec3::new(T::ZERO, T::ZERO, T::ZERO),
            n: Vec3::new(T::ZERO, T::ZERO, T::ZERO),
            col: Rgb::splat(T::ZERO),
        }; 3];
        let mut ok = true;
        for k in 0..3 {
            let Some(v) = mesh.vertices.get(tri[k] as usize) else {
                ok = false;
                break;
            };
            let p = transform.point(v.position);
            if !p.is_finite() {
                ok = false;
                break;
            }
            let n = transform.normal(v.normal).normalize().unwrap_or(Vec3::new(
                T::ZERO,
                T::ZERO,
                T::ZERO,
            ));
            cv[k] = ClipVert {
                c: camera.clip(p),
                p,
                n,
                col: Rgb::splat(T::ZERO),
            };
        }
        if !ok {
            continue;
        }
        // Trivial reject: all three vertices outside one plane.
        let d: [[T; 6]; 3] = core::array::from_fn(|k| plane_distances(&cv[k].c, near, far));
        if (0..6).any(|pl| (0..3).all(|k| d[k][pl] < T::ZERO)) {
            continue;
        }
        let all_in = (0..3).all(|k| (0..6).all(|pl| d[k][pl] >= T::ZERO));
        // Band test on the screen rows (conservative by a pixel), before any shading.
        if d.iter().all(|dk| dk[0] >= T::ZERO) {
            let ys: [f64; 3] = core::array::from_fn(|k| camera.screen_xy(cv[k].c).1.to_f64());
            let (lo, hi) = (ys[0].min(ys[1]).min(ys[2]), ys[0].max(ys[1]).max(ys[2]));
            if hi < row0 as f64 - 1.0 || lo > row1 as f64 + 1.0 {
                continue;
            }
        }
        if opts.shading == Shading::Gouraud {
            // Shade no vertex of a triangle that will not be drawn: an unclipped triangle that
            // is culled (back-facing) or degenerate is rejected here exactly as
            // `raster_triangle` would reject it.
            if all_in {
                let mut fp = [FixedPoint::default(); 3];
                for k in 0..3 {
                    let (x, y) = camera.screen_xy(cv[k].c);
                    fp[k] = FixedPoint::new(snap(x), snap(y));
                }
                if EdgeTriangle::new(fp, opts.cull).is_none() {
                    continue;
                }
            }
            for v in cv.iter_mut() {
                let view = camera.view_dir(v.p);
                let n = if opts.two_sided && v.n.dot(view) < T::ZERO {
                    -v.n
                } else {
                    v.n
                };
                v.col = shader.shade(v.p, n, view).finite_or_zero();
                stats.shaded = stats.shaded.wrapping_add(1);
            }
        }
        let mut poly = [cv[0]; MAX_CLIPPED];
        let count = if all_in {
            poly[..3].copy_from_slice(&cv);
            3
        } else {
            clip_polygon(cv, near, far, &mut poly)
        };
        for i in 1..count.saturating_sub(1) {
            raster_triangle(
                camera,
                band,
                [&poly[0], &poly[i], &poly[i + 1]],
                shader,
                opts,
                row0,
                row1,
                &mut stats,
            );
        }
    }
    Ok(stats)
}

#[allow(clippy::too_many_arguments)]
fn raster_triangle<T, P, S>(
    camera: &Camera<T>,
    band: &mut Band<'_, P>,
    v: [&ClipVert<T>; 3],
    shader: &S,
    opts: &DrawOptions<T>,
    row0: i32,
    row1: i32,
    stats: &mut DrawStats,
) where
    T: Real,
    P: PixelFormat,
    S: Shader<T> + ?Sized,
{
    let mut fp = [FixedPoint::default(); 3];
    let mut iw = [T::ZERO; 3];
    for k in 0..3 {
        let c = v[k].c;
        if !(c[3] > T::ZERO) {
            return;
        }
        let (x, y) = camera.screen_xy(c);
        if !(x.is_finite() && y.is_finite()) {
            return;
        }
        fp[k] = FixedPoint::new(snap(x), snap(y));
        iw[k] = T::ONE / c[3];
    }
    let Some(tri) = EdgeTriangle::new(fp, opts.cull) else {
        return;
    };
    stats.rasterized = stats.rasterized.wrapping_add(1);
    let order = if tri.swapped() { [0, 2, 1] } else { [0, 1, 2] };
    let vs = [v[order[0]], v[order[1]], v[order[2]]];
    let iw = [iw[order[0]], iw[order[1]], iw[order[2]]];
    let inv_area = 1.0 / tri.area2() as f64;
    // Attributes divided by w (perspective-correct interpolation).
    let zw: [T; 3] = core::array::from_fn(|k| vs[k].c[2] * iw[k]);
    let pw: [Vec3<T>; 3] = core::array::from_fn(|k| vs[k].p * iw[k]);
    let nw: [Vec3<T>; 3] = core::array::from_fn(|k| vs[k].n * iw[k]);
    let cw: [Rgb<T>; 3] = core::array::from_fn(|k| vs[k].col.scale(iw[k]));
    let (near, far) = (camera.near, camera.far);
    let depth_scale = T::ONE / (far - near);
    let has_depth = band.has_depth();
    let width = camera.width as i32;
    // Barycentric weights: exact (from the integer edge functions, through f64) at the first
    // covered pixel of each row, then stepped by a per-triangle increment along the row, so a
    // pixel costs 3 additions in `T` instead of 3 double-precision products (soft-float on
    // Cortex-M0 and M4F). Every row starts afresh, so a band renders exactly its rows of the
    // full frame; the drift along a row is at most its length times the rounding of the step
    // (f32: 240 x 6e-8 relative; Fixed22: 240 x 2^-22).
    let mut row: Option<(i32, i32, [i64; 3], [T; 3])> = None;
    let mut dl: Option<[T; 3]> = None;
    tri.for_each_covered(width, row0, row1, |x, y, e| {
        let l: [T; 3] = match row {
            Some((ry, rx, re, rl)) if ry == y && rx + 1 == x => {
                let d = *dl.get_or_insert_with(|| {
                    core::array::from_fn(|k| T::from_f64((e[k] - re[k]) as f64 * inv_area))
                });
                [rl[0] + d[0], rl[1] + d[1], rl[2] + d[2]]
            }
            _ => core::array::from_fn(|k| T::from_f64(e[k] as f64 * inv_area)),
        };
        row = Some((y, x, e, l));
        let s = l[0] * iw[0] + l[1] * iw[1] + l[2] * iw[2];
        if !(s > T::ZERO) {
            return;
        }
        let inv = T::ONE / s;
        let Some(i) = band.index(x as u16, y as u16) else {
            return;
        };
        if has_depth {
            let z = (l[0] * zw[0] + l[1] * zw[1] + l[2] * zw[2]) * inv;
            let q = target::quantize((z - near) * depth_scale, u16::MAX as u32) as u16;
            if !band.depth_test(i, q) {
                return;
            }
        }
        let colour = match opts.shading {
            Shading::Gouraud => cw[0]
                .scale(l[0])
                .add(cw[1].scale(l[1]))
                .add(cw[2].scale(l[2]))
                .scale(inv),
            Shading::PerPixel => {
                let p = (pw[0] * l[0] + pw[1] * l[1] + pw[2] * l[2]) * inv;
                let view = camera.view_dir(p);
                let n = (nw[0] * l[0] + nw[1] * l[1] + nw[2] * l[2])
                    .normalize()
                    .unwrap_or(view);
                let n = if opts.two_sided && n.dot(view) < T::ZERO {
                    -n
                } else {
                    n
                };
                stats.shaded = stats.shaded.wrapping_add(1);
                shader.shade(p, n, view)
            }
        };
        band.put(
            i,
            encode_pixel(colour.finite_or_zero(), opts.exposure, opts.encoding),
        );
        stats.pixels = stats.pixels.wrapping_add(1);
    });
}

/// Renders a whole frame band by band through one band buffer: for each band (top to bottom)
/// moves `band` there, clears it to `background`, calls `draw_band` (which draws the scene
/// into it) and then `flush` (which sends its rows to the display or a frame buffer).
///
/// # Errors
/// The first error of `draw_band` or `flush`.
pub fn render_in_bands<P, E, D, F>(
    band: &mut Band<'_, P>,
    height: u16,
    background: P,
    mut draw_band: D,
    mut flush: F,
) -> Result<(), E>
where
    P: PixelFormat,
    D: FnMut(&mut Band<'_, P>) -> Result<(), E>,
    F: FnMut(&Band<'_, P>) -> Result<(), E>,
{
    let rows = band.rows();
    let mut y0: u16 = 0;
    while y0 < height {
        band.move_to(y0);
        band.clear(background);
        draw_band(band)?;
        flush(band)?;
        y0 = y0.saturating_add(rows);
        if rows == 0 {
            break;
        }
    }
    Ok(())
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
