//! The scene of the board firmware, written once over arealight's scalar trait [`Real`]:
//! `f32` on the STM32F411 (Cortex-M4F), `arealight::Fixed22` on the RP2040 (Cortex-M0+,
//! no FPU).
//!
//! A UV sphere and a tumbling torus, lit by a rectangular area light overhead (a
//! [`PolygonLight`]), a small [`SphereLight`] that orbits the two objects (drawn as a glowing
//! ball) and a faint ambient term; 240x240 pixels, rendered band by band (240x16 RGB565 with a
//! 16-bit depth band) by [`arealight::raster`]. The animation is periodic in
//! [`PERIOD`] frames and depends on the frame number only, so every board shows the same
//! frames, whatever its speed.
//!
//! Everything fits the fixed-point format: every position (camera, lights, vertices, shading
//! points) lies within `[-4, 4]` (`Fixed22::COORDINATE_LIMIT`), colours and exposure well
//! below 512.
//!
//! ```
//! use arealight::raster::{Band, Rgb565, Shading};
//! use demo_scene::{Demo, MeshBuffers, BACKGROUND, BAND_PIXELS, WIDTH};
//!
//! let mut buffers = MeshBuffers::<f32>::new();
//! let demo = Demo::new(&mut buffers, Shading::PerPixel, None)?;
//! let (mut pixels, mut depth) = ([Rgb565(0); BAND_PIXELS], [0u16; BAND_PIXELS]);
//! let mut band = Band::new(&mut pixels, Some(&mut depth), WIDTH, 0)?;
//! let frame = demo.frame(0)?;
//! band.clear(BACKGROUND);
//! let mut stats = Default::default();
//! demo.draw_band(&frame, &mut band, &mut stats)?;
//! # Ok::<(), arealight::raster::RasterError>(())
//! ```
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

use core::cell::{Cell, RefCell};

use arealight::raster::{
    draw, mesh, Affine, Band, Camera, Cull, DrawOptions, DrawStats, Encoding, Lit, Material, Mesh,
    Projection, RasterError, Rgb565, Shader, Shading, Vertex,
};
use arealight::{Ambient, PolygonLight, Real, Rgb, Scene, SceneLight, SphereLight, Vec3};

/// Display width in pixels.
pub const WIDTH: u16 = 240;
/// Display height in pixels.
pub const HEIGHT: u16 = 240;
/// Rows per band.
pub const BAND_ROWS: u16 = 16;
/// Pixels of one band (the length of its colour and depth buffers): 3840, 7.5 KiB each.
pub const BAND_PIXELS: usize = WIDTH as usize * BAND_ROWS as usize;
/// The colour behind the objects (a dark blue-grey).
pub const BACKGROUND: Rgb565 = Rgb565::new(1, 3, 5);
/// Frames per period of the animation (one orbit of the lamp, one tumble of the torus).
pub const PERIOD: u32 = 120;

/// UV sphere resolution (rings of latitude, segments of longitude).
const SPHERE_STACKS: u16 = 10;
const SPHERE_SLICES: u16 = 20;
/// Torus resolution (segments around the axis, around the tube).
const TORUS_MAJOR: u16 = 24;
const TORUS_MINOR: u16 = 10;

/// Vertices of the UV sphere (see `mesh::uv_sphere_counts`).
pub const SPHERE_VERTICES: usize = (SPHERE_STACKS as usize + 1) * (SPHERE_SLICES as usize + 1);
/// Triangles of the UV sphere.
pub const SPHERE_TRIANGLES: usize = 2 * SPHERE_SLICES as usize * (SPHERE_STACKS as usize - 1);
/// Vertices of the torus (see `mesh::torus_counts`).
pub const TORUS_VERTICES: usize = (TORUS_MAJOR as usize + 1) * (TORUS_MINOR as usize + 1);
/// Triangles of the torus.
pub const TORUS_TRIANGLES: usize = 2 * TORUS_MAJOR as usize * TORUS_MINOR as usize;

// The scene, in world units (y up; the camera looks at the origin from +z).
/// The big sphere: centre and radius.
const SPHERE_AT: [f64; 3] = [-0.7, 0.0, 0.0];
const SPHERE_RADIUS: f64 = 0.55;
/// The torus: centre, radius of the tube's centre circle, radius of the tube.
const TORUS_AT: [f64; 3] = [0.75, 0.0, 0.0];
const TORUS_MAJOR_RADIUS: f64 = 0.45;
const TORUS_MINOR_RADIUS: f64 = 0.17;
/// The lamp (sphere light): radius, radius and height of its orbit about the y axis.
const LAMP_RADIUS: f64 = 0.15;
const LAMP_ORBIT: f64 = 1.3;
const LAMP_HEIGHT: f64 = 0.75;

/// The caller's mesh storage (no allocation): one unit UV sphere (drawn twice: the big sphere
/// and, scaled down, the lamp) and one torus. About 10 KiB with `f32` or `Fixed22` (a vertex
/// is six 4-byte scalars). Put it in a `static` (e.g. `cortex_m::singleton!`) or in `main`'s
/// frame, which never returns.
pub struct MeshBuffers<T> {
    sphere_vertices: [Vertex<T>; SPHERE_VERTICES],
    sphere_triangles: [[u16; 3]; SPHERE_TRIANGLES],
    torus_vertices: [Vertex<T>; TORUS_VERTICES],
    torus_triangles: [[u16; 3]; TORUS_TRIANGLES],
}

impl<T: Real> MeshBuffers<T> {
    const ZERO_VERTEX: Vertex<T> = Vertex::new(
        Vec3::new(T::ZERO, T::ZERO, T::ZERO),
        Vec3::new(T::ZERO, T::ZERO, T::ZERO),
    );
    /// Zeroed buffers ([`Demo::new`] fills them).
    pub fn new() -> Self {
        MeshBuffers {
            sphere_vertices: [Self::ZERO_VERTEX; SPHERE_VERTICES],
            sphere_triangles: [[0; 3]; SPHERE_TRIANGLES],
            torus_vertices: [Self::ZERO_VERTEX; TORUS_VERTICES],
            torus_triangles: [[0; 3]; TORUS_TRIANGLES],
        }
    }
}

impl<T: Real> Default for MeshBuffers<T> {
    fn default() -> Self {
        Self::new()
    }
}

/// Entries of a [`VertexCache`]: twice the lit meshes' vertices, so that the table stays at
/// most half full.
pub const CACHE_ENTRIES: usize = 1024;

/// The colours of the vertices shaded in the current frame (Gouraud shading only).
///
/// Why: `raster::draw` shades the three corners of every triangle it draws, again for each
/// band the triangle touches, so with Gouraud shading each vertex of the mesh is shaded several
/// times per frame (6 triangles share it, each touches one or two bands; since the crate
/// culls back faces before shading, only the front-facing ones count). In fixed point on a
/// Cortex-M0+, where one shader call (the
/// polygon light's Lambert and Phong terms and the sphere light's) costs up to 110 000
/// instructions, that is more than half of the frame. This cache (an open-addressing hash table keyed by
/// the exact bits of the transformed position and normal, which are the same every time a
/// vertex is drawn in a frame) shades each vertex once per frame and returns the identical
/// colour afterwards: the same pixels, about 10 times fewer shader calls. 24 KiB (`f32` or
/// `Fixed22`: a 64-bit key, a 32-bit frame stamp, three 4-byte channels per entry).
pub struct VertexCache<T> {
    entries: [CacheEntry<T>; CACHE_ENTRIES],
}

#[derive(Clone, Copy)]
struct CacheEntry<T> {
    key: u64,
    /// The frame stamp: an entry of an older frame is free (0: never written).
    stamp: u32,
    colour: Rgb<T>,
}

impl<T: Real> VertexCache<T> {
    /// An empty cache.
    pub fn new() -> Self {
        VertexCache {
            entries: [CacheEntry {
                key: 0,
                stamp: 0,
                colour: Rgb::splat(T::ZERO),
            }; CACHE_ENTRIES],
        }
    }
}

impl<T: Real> Default for VertexCache<T> {
    fn default() -> Self {
        Self::new()
    }
}

/// A shader that looks its colours up in a [`VertexCache`] first (see there).
struct Cached<'r, 'c, 's, T, S: ?Sized> {
    shader: &'s S,
    entries: &'r RefCell<&'c mut [CacheEntry<T>]>,
    stamp: u32,
    /// Tells the objects apart (the same point of two objects would have two colours).
    object: u64,
}

/// A 64-bit hash of the object and the exact bits of `p` and `n` (multiply and fold, per
/// component).
fn vertex_key<T: Real>(object: u64, p: Vec3<T>, n: Vec3<T>) -> u64 {
    let mut h = object.wrapping_mul(0x9E37_79B9_7F4A_7C15);
    for x in [p.x, p.y, p.z, n.x, n.y, n.z] {
        h = (h ^ x.to_f64().to_bits()).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        h ^= h >> 29;
    }
    h
}

impl<T: Real, S: Shader<T> + ?Sized> Shader<T> for Cached<'_, '_, '_, T, S> {
    fn shade(&self, p: Vec3<T>, n: Vec3<T>, v: Vec3<T>) -> Rgb<T> {
        let key = vertex_key(self.object, p, n);
        let mut entries = self.entries.borrow_mut();
        let mask = entries.len() - 1;
        let mut i = key as usize & mask;
        // Linear probing, at most 16 slots; a crowded table just shades without caching.
        for _ in 0..16 {
            let Some(e) = entries.get_mut(i) else { break };
            if e.stamp == self.stamp && e.key == key {
                return e.colour;
            }
            if e.stamp != self.stamp {
                let colour = self.shader.shade(p, n, v);
                *e = CacheEntry {
                    key,
                    stamp: self.stamp,
                    colour,
                };
                return colour;
            }
            i = (i + 1) & mask;
        }
        self.shader.shade(p, n, v)
    }
}

/// What stays the same for every frame: camera, meshes, materials, draw options.
pub struct Demo<'a, T> {
    camera: Camera<T>,
    sphere: Mesh<'a, T>,
    torus: Mesh<'a, T>,
    red: Material<T>,
    teal: Material<T>,
    /// Options for the lit objects (the shading mode chosen by the firmware).
    lit: DrawOptions<T>,
    /// Options for the lamp: an emissive colour, Gouraud (3 closure calls per triangle).
    emissive: DrawOptions<T>,
    /// The vertex colour cache (Gouraud only) and the current frame's stamp.
    cache: Option<RefCell<&'a mut [CacheEntry<T>]>>,
    stamp: Cell<u32>,
}

/// What changes from frame to frame: the lights and the objects' transforms, and which rows of
/// the screen each object can cover (so that bands it cannot reach skip it entirely).
pub struct Frame<T> {
    lights: Scene<T, 3, 4>,
    lamp_colour: Rgb<T>,
    /// This frame's stamp in the vertex cache.
    stamp: u32,
    /// Model transforms of the sphere, the torus and the lamp.
    transforms: [Affine<T>; 3],
    /// Screen rows `[top, bottom)` each object can cover.
    rows: [(i32, i32); 3],
}

fn v3<T: Real>(v: [f64; 3]) -> Vec3<T> {
    Vec3::from_f64(v)
}

impl<'a, T: Real> Demo<'a, T> {
    /// Fills `buffers` with the meshes and sets up the camera and materials. `shading`:
    /// [`Shading::PerPixel`] (every visible pixel runs both lights' Lambert and Phong models:
    /// the area lights' soft highlights, slow) or [`Shading::Gouraud`] (the models at the
    /// vertices only: much cheaper, coarser). With Gouraud shading, a [`VertexCache`] makes
    /// it shade each vertex once per frame instead of about 9 times (see there); it is unused
    /// per pixel.
    ///
    /// # Errors
    /// None with the constants above; the mesh generators' and constructors' errors otherwise.
    pub fn new(
        buffers: &'a mut MeshBuffers<T>,
        shading: Shading,
        cache: Option<&'a mut VertexCache<T>>,
    ) -> Result<Self, RasterError> {
        let sphere = mesh::uv_sphere(
            T::ONE,
            SPHERE_STACKS,
            SPHERE_SLICES,
            &mut buffers.sphere_vertices,
            &mut buffers.sphere_triangles,
        )?;
        let torus = mesh::torus(
            T::from_f64(TORUS_MAJOR_RADIUS),
            T::from_f64(TORUS_MINOR_RADIUS),
            TORUS_MAJOR,
            TORUS_MINOR,
            &mut buffers.torus_vertices,
            &mut buffers.torus_triangles,
        )?;
        // From here on the buffers are only read.
        let buffers: &'a MeshBuffers<T> = buffers;
        let camera = Camera::new(
            v3([0.0, 0.8, 3.3]),
            v3([0.0, 0.05, 0.0]),
            v3([0.0, 1.0, 0.0]),
            Projection::Perspective {
                fov_y: T::from_f64(0.8),
            },
            WIDTH,
            HEIGHT,
        )?
        // The objects lie 2 to 4.5 units away: spend the 16 depth bits there.
        .with_depth_range(T::from_f64(1.0), T::from_f64(6.0))?;
        let mut lit = DrawOptions::new(shading);
        lit.cull = Cull::Back;
        // Gamma 2 (one square root per channel) instead of sRGB (a powf per channel: an exp
        // and a ln, costly in fixed point); within 0.05 of sRGB.
        lit.encoding = Encoding::Gamma2;
        let mut emissive = DrawOptions::new(Shading::Gouraud);
        emissive.encoding = Encoding::Gamma2;
        Ok(Demo {
            camera,
            sphere: Mesh::new(
                &buffers.sphere_vertices[..sphere.vertices],
                &buffers.sphere_triangles[..sphere.triangles],
            )?,
            torus: Mesh::new(
                &buffers.torus_vertices[..torus.vertices],
                &buffers.torus_triangles[..torus.triangles],
            )?,
            // Red plastic with a broad highlight, teal with a tighter one.
            red: Material::new(
                Rgb::from_f64([0.85, 0.22, 0.12]),
                Rgb::from_f64([0.35, 0.35, 0.35]),
                20,
            )?,
            teal: Material::new(
                Rgb::from_f64([0.12, 0.55, 0.5]),
                Rgb::from_f64([0.5, 0.5, 0.5]),
                48,
            )?,
            lit,
            emissive,
            cache: match shading {
                Shading::Gouraud => cache.map(|c| RefCell::new(&mut c.entries[..])),
                Shading::PerPixel => None,
            },
            stamp: Cell::new(0),
        })
    }

    /// The camera.
    pub fn camera(&self) -> &Camera<T> {
        &self.camera
    }

    /// The lights and transforms of frame `n` (periodic in [`PERIOD`]). Cost: a few dozen
    /// `T` operations and the lights' constructors (which validate in f64), once per frame.
    ///
    /// # Errors
    /// None with the constants above; the lights' constructors' errors otherwise.
    pub fn frame(&self, n: u32) -> Result<Frame<T>, RasterError> {
        // The phase t in [0, 2 pi), from the frame number. (The fraction first: `TAU * n`
        // would saturate in fixed point, whose range ends at 512.)
        let t = T::TAU * (T::from_u32(n % PERIOD) / T::from_u32(PERIOD));
        let (c, s) = (t.cos(), t.sin());

        // The lamp orbits the y axis, counter-clockwise seen from above.
        let lamp_at = Vec3::new(
            T::from_f64(LAMP_ORBIT) * s,
            T::from_f64(LAMP_HEIGHT),
            T::from_f64(LAMP_ORBIT) * c,
        );
        let lamp = SphereLight::new(lamp_at, T::from_f64(LAMP_RADIUS))?;
        // The panel: 2 x 1.4 units, 1.9 above the floor-less ground, facing down (a polygon
        // light emits from both faces).
        let panel = PolygonLight::<T, 4>::new(&[
            v3([-1.0, 1.9, -1.0]),
            v3([1.0, 1.9, -1.0]),
            v3([1.0, 1.9, 0.4]),
            v3([-1.0, 1.9, 0.4]),
        ])?;
        // Colours scale the models' normalized irradiance (unit radiance): the panel subtends
        // about 0.3 sr from the objects, the lamp much less, hence the large factors.
        let lamp_colour = Rgb::from_f64([1.0, 0.8, 0.55]);
        let mut lights: Scene<T, 3, 4> = Scene::new();
        // Three pushes into a scene of capacity 3 with finite colours: cannot fail.
        let _ = lights.push(SceneLight::Polygon(panel), Rgb::from_f64([2.6, 2.7, 3.0]));
        let _ = lights.push(
            SceneLight::Sphere(lamp),
            lamp_colour.scale(T::from_f64(14.0)),
        );
        let _ = lights.push(
            SceneLight::Ambient(Ambient(Rgb::from_f64([0.03, 0.035, 0.05]))),
            Rgb::splat(T::ONE),
        );

        // The sphere stands still (its rotation would not show); the torus tumbles about two
        // axes, once per period about x, twice about y.
        let sphere = Affine::scale(Vec3::new(
            T::from_f64(SPHERE_RADIUS),
            T::from_f64(SPHERE_RADIUS),
            T::from_f64(SPHERE_RADIUS),
        ))?
        .then(&Affine::translation(v3(SPHERE_AT))?);
        let torus = Affine::rotation(v3([1.0, 0.0, 0.0]), t)?
            .then(&Affine::rotation(v3([0.0, 1.0, 0.0]), t + t)?)
            .then(&Affine::translation(v3(TORUS_AT))?);
        let lamp_scale = T::from_f64(LAMP_RADIUS);
        let lamp = Affine::scale(Vec3::new(lamp_scale, lamp_scale, lamp_scale))?
            .then(&Affine::translation(lamp_at)?);

        let rows = [
            self.rows_of(v3(SPHERE_AT), SPHERE_RADIUS),
            self.rows_of(v3(TORUS_AT), TORUS_MAJOR_RADIUS + TORUS_MINOR_RADIUS),
            self.rows_of(lamp_at, LAMP_RADIUS),
        ];
        // A new stamp: every cached colour of the previous frames is stale (0 is never used).
        let stamp = match self.stamp.get().wrapping_add(1) {
            0 => 1,
            s => s,
        };
        self.stamp.set(stamp);
        Ok(Frame {
            lights,
            lamp_colour,
            stamp,
            transforms: [sphere, torus, lamp],
            rows,
        })
    }

    /// The screen rows a sphere of `radius` about `centre` can cover: the projections of the
    /// 8 corners of its bounding cube (a convex hull containing the sphere's), one pixel of
    /// margin; all rows if a corner is behind the near plane.
    fn rows_of(&self, centre: Vec3<T>, radius: f64) -> (i32, i32) {
        let r = T::from_f64(radius);
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for k in 0..8 {
            let pick = |bit: u32| if k & bit != 0 { r } else { -r };
            let corner = centre + Vec3::new(pick(1), pick(2), pick(4));
            match self.camera.project(corner) {
                Some((_, y)) => {
                    let y = y.to_f64();
                    lo = lo.min(y);
                    hi = hi.max(y);
                }
                None => return (0, HEIGHT as i32),
            }
        }
        // A NaN (a degenerate projection) or no corner: every row.
        if lo.is_nan() || hi.is_nan() || lo > hi {
            return (0, HEIGHT as i32);
        }
        ((lo - 1.0) as i32, (hi + 2.0) as i32)
    }

    /// Draws frame `frame` into `band` (cleared by the caller), adding what the draw calls did
    /// to `stats`. Objects whose rows miss the band are skipped without touching a vertex.
    ///
    /// # Errors
    /// [`RasterError::BadSize`] if the band is not [`WIDTH`] wide.
    pub fn draw_band(
        &self,
        frame: &Frame<T>,
        band: &mut Band<'_, Rgb565>,
        stats: &mut DrawStats,
    ) -> Result<(), RasterError> {
        let (top, bottom) = (band.y0() as i32, band.y0() as i32 + band.rows() as i32);
        let touches = |i: usize| frame.rows[i].0 < bottom && frame.rows[i].1 > top;
        let mut add = |s: DrawStats| {
            stats.triangles += s.triangles;
            stats.rasterized += s.rasterized;
            stats.shaded += s.shaded;
            stats.pixels += s.pixels;
        };
        let objects = [(&self.sphere, &self.red), (&self.torus, &self.teal)];
        for (i, (mesh, material)) in objects.into_iter().enumerate() {
            if !touches(i) {
                continue;
            }
            let lit = Lit::new(&frame.lights, material);
            let s = match &self.cache {
                Some(entries) => {
                    let cached = Cached {
                        shader: &lit,
                        entries,
                        stamp: frame.stamp,
                        object: i as u64,
                    };
                    draw(
                        &self.camera,
                        band,
                        mesh,
                        &frame.transforms[i],
                        &cached,
                        &self.lit,
                    )?
                }
                None => draw(
                    &self.camera,
                    band,
                    mesh,
                    &frame.transforms[i],
                    &lit,
                    &self.lit,
                )?,
            };
            add(s);
        }
        if touches(2) {
            // The lamp itself: its colour, whatever the normal.
            let glow = frame.lamp_colour;
            let shader = move |_p: Vec3<T>, _n: Vec3<T>, _v: Vec3<T>| glow;
            add(draw(
                &self.camera,
                band,
                &self.sphere,
                &frame.transforms[2],
                &shader,
                &self.emissive,
            )?);
        }
        Ok(())
    }
}
