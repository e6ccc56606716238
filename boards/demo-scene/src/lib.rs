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
//! A frame ([`Demo::render_frame`]) is done in stages ([`Stage`]): the frame's lights and
//! transforms; every vertex transformed and projected once ([`PreparedMesh::transform`]),
//! but the sphere's, which stands still: it keeps the vertex data of the first frame (the
//! same bits a new transform would give), and its shade skips finding its visible vertices
//! again; with Gouraud shading, the light models at each visible vertex once
//! ([`PreparedMesh::shade`]), but the panel's at the sphere's vertices, which the sphere keeps
//! from the first frame (the panel, the sphere and the camera stand still: [`SplitLit`],
//! [`PreparedMesh::shade_split`]; the same bits); then band by band, scan conversion in integers
//! ([`PreparedMesh::draw`]) and the band handed to the display.
//!
//! Everything fits the fixed-point format: every position (camera, lights, vertices, shading
//! points) lies within `[-4, 4]` (`Fixed22::COORDINATE_LIMIT`), colours and exposure well
//! below 512.
//!
//! ```
//! use arealight::raster::{Band, EncodeTable, Rgb565, Shading};
//! use demo_scene::{Demo, MeshBuffers, BACKGROUND, BAND_PIXELS, WIDTH};
//!
//! let mut buffers = Box::new(MeshBuffers::<f32>::new());
//! let mut table = Box::new(EncodeTable::zeroed());
//! let mut demo = Demo::new(&mut buffers, &mut table, Shading::Gouraud)?;
//! let (mut pixels, mut depth) = ([Rgb565(0); BAND_PIXELS], [0u16; BAND_PIXELS]);
//! let mut band = Band::new(&mut pixels, Some(&mut depth), WIDTH, 0)?;
//! let frame = demo.frame(0)?;
//! demo.prepare(&frame);
//! band.clear(BACKGROUND);
//! let mut stats = Default::default();
//! demo.draw_band(&frame, &mut band, &mut stats)?;
//! # Ok::<(), arealight::raster::RasterError>(())
//! ```
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod calibrate;
#[cfg(feature = "scene-file")]
pub mod scenes;
#[cfg(feature = "scene-file")]
pub mod spec;

use arealight::raster::{
    mesh, Affine, Band, Camera, Cull, DrawOptions, DrawStats, EncodeTable, Encoding, LightSums,
    Lit, Material, Mesh, PreparedMesh, PreparedVertex, Projection, RasterError, Rgb565, Shading,
    SplitLit, TriangleRows, Vertex, VertexColour, VertexScreen,
};
use arealight::{Ambient, PolygonLight, Real, Rgb, Scene, SceneLight, SphereLight, UnitVec3, Vec3};

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
/// The lamp's own UV sphere: about 20 pixels across on screen, where the big sphere's 10 x 20
/// would spend 180 front-facing triangles (a quarter of the frame's triangle setups) on 300
/// pixels. A coarser mesh for the small object (level of detail).
const LAMP_STACKS: u16 = 6;
const LAMP_SLICES: u16 = 10;

/// Torus resolution (segments around the axis, around the tube).
const TORUS_MAJOR: u16 = 24;
const TORUS_MINOR: u16 = 10;

/// Vertices of the UV sphere (see `mesh::uv_sphere_counts`).
pub const SPHERE_VERTICES: usize = (SPHERE_STACKS as usize + 1) * (SPHERE_SLICES as usize + 1);
/// Triangles of the UV sphere.
pub const SPHERE_TRIANGLES: usize = 2 * SPHERE_SLICES as usize * (SPHERE_STACKS as usize - 1);
/// Vertices of the lamp's UV sphere.
pub const LAMP_VERTICES: usize = (LAMP_STACKS as usize + 1) * (LAMP_SLICES as usize + 1);
/// Triangles of the lamp's UV sphere.
pub const LAMP_TRIANGLES: usize = 2 * LAMP_SLICES as usize * (LAMP_STACKS as usize - 1);
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
/// The lights of [`Demo::frame`]'s scene that stand still: the first one, the panel (the
/// sphere keeps their terms at its vertices from frame to frame: [`SplitLit`]).
const PANEL_LIGHTS: usize = 1;
/// The lamp (sphere light): radius, radius and height of its orbit about the y axis.
const LAMP_RADIUS: f64 = 0.15;
const LAMP_ORBIT: f64 = 1.3;
const LAMP_HEIGHT: f64 = 0.75;

/// The caller's storage for the scene (no allocation): a unit UV sphere (the big sphere), a
/// coarser one (the lamp, scaled down) and a torus, their per-frame vertex data (one
/// [`PreparedVertex`] per vertex, one [`TriangleRows`] per triangle, the sphere's kept
/// [`LightSums`]): 61 584 bytes with `f32` or `Fixed22` (the encoding table, 8 200 bytes or
/// 16 390 with arealight's `encode-guards`, is apart: [`Demo::new`]; two cores can share it,
/// [`Demo::sharing`]). Put it in a `static` initialized at link time (it is
/// `const`: e.g. `static_cell::ConstStaticCell`) or on the heap; [`Demo::new`] fills it.
pub struct MeshBuffers<T> {
    sphere_vertices: [Vertex<T>; SPHERE_VERTICES],
    sphere_triangles: [[u16; 3]; SPHERE_TRIANGLES],
    torus_vertices: [Vertex<T>; TORUS_VERTICES],
    torus_triangles: [[u16; 3]; TORUS_TRIANGLES],
    lamp_vertices: [Vertex<T>; LAMP_VERTICES],
    lamp_triangles: [[u16; 3]; LAMP_TRIANGLES],
    sphere_frame: [PreparedVertex<T>; SPHERE_VERTICES],
    torus_frame: [PreparedVertex<T>; TORUS_VERTICES],
    lamp_frame: [PreparedVertex<T>; LAMP_VERTICES],
    sphere_rows: [TriangleRows; SPHERE_TRIANGLES],
    /// The panel's terms at the sphere's vertices, kept from frame to frame (both stand
    /// still: [`SplitLit`]).
    sphere_sums: [LightSums<T>; SPHERE_VERTICES],
    torus_rows: [TriangleRows; TORUS_TRIANGLES],
    lamp_rows: [TriangleRows; LAMP_TRIANGLES],
}

impl<T: Real> MeshBuffers<T> {
    const ZERO_VERTEX: Vertex<T> = Vertex::new(
        Vec3::new(T::ZERO, T::ZERO, T::ZERO),
        Vec3::new(T::ZERO, T::ZERO, T::ZERO),
    );
    /// Zeroed buffers ([`Demo::new`] fills them). A `const fn`, so that firmware can place
    /// them in a `static` initialized at link time (all zero bits: `.bss`, no flash), with no
    /// copy through the stack (e.g. `static_cell::ConstStaticCell`).
    pub const fn new() -> Self {
        MeshBuffers {
            sphere_vertices: [Self::ZERO_VERTEX; SPHERE_VERTICES],
            sphere_triangles: [[0; 3]; SPHERE_TRIANGLES],
            torus_vertices: [Self::ZERO_VERTEX; TORUS_VERTICES],
            torus_triangles: [[0; 3]; TORUS_TRIANGLES],
            lamp_vertices: [Self::ZERO_VERTEX; LAMP_VERTICES],
            lamp_triangles: [[0; 3]; LAMP_TRIANGLES],
            sphere_frame: [PreparedVertex::EMPTY; SPHERE_VERTICES],
            torus_frame: [PreparedVertex::EMPTY; TORUS_VERTICES],
            lamp_frame: [PreparedVertex::EMPTY; LAMP_VERTICES],
            sphere_rows: [TriangleRows::EMPTY; SPHERE_TRIANGLES],
            sphere_sums: [LightSums::ZERO; SPHERE_VERTICES],
            torus_rows: [TriangleRows::EMPTY; TORUS_TRIANGLES],
            lamp_rows: [TriangleRows::EMPTY; LAMP_TRIANGLES],
        }
    }
}

impl<T: Real> Default for MeshBuffers<T> {
    fn default() -> Self {
        Self::new()
    }
}

/// The scene: camera, meshes prepared per frame, materials, draw options.
pub struct Demo<'a, T: Real> {
    camera: Camera<T>,
    sphere: PreparedMesh<'a, 'a, T>,
    torus: PreparedMesh<'a, 'a, T>,
    lamp: PreparedMesh<'a, 'a, T>,
    red: Material<T>,
    teal: Material<T>,
    /// The panel light alone in a scene (it does not move: validated, and its reach found,
    /// once, here): each frame's lights start from a copy of it (`setup` 596 -> 293 us a
    /// frame on the RP2040, rp2040js; the same scene as pushing the panel each frame).
    panel: Scene<T, 3, 4>,
    /// Options for the sphere and the torus (the shading mode chosen by the firmware, per
    /// object: [`Demo::set_shading`]).
    lit: [DrawOptions<T>; 2],
    /// Options for the lamp: an emissive colour, Gouraud.
    emissive: DrawOptions<T>,
    /// Gamma 2 (one square root per channel; within 0.05 of sRGB), tabulated.
    table: &'a EncodeTable,
    /// The sphere's transform of the frame its vertex data were computed for (`None`
    /// before the first): it stands still, so a frame with the same transform (every frame:
    /// [`Demo::frame`] builds it from constants, so the same bits) keeps them, and the
    /// sphere's next shade skips finding its visible vertices too (`PreparedMesh::shade`).
    sphere_at: Option<Affine<T>>,
    /// The transforms that do not change from frame to frame, built once: the sphere's (its
    /// scale, then its place) and the lamp's scale (each frame then moves it to its place on
    /// the orbit: [`Affine::then_translation`]). Built every frame, they took about 6 000
    /// of the frame setup's 32 000 cycles on the RP2040 (rp2040js).
    fixed_transforms: [Affine<T>; 2],
    /// The sphere was transformed this frame (by [`Demo::transform_share`]): its screen data
    /// go through the exchange; otherwise both cores already hold them.
    sphere_moved: bool,
    /// Which of the sphere, the torus and the lamp made the visible-vertex pass over this
    /// core's share of the triangles this frame ([`Demo::find_visible_share`]): those whose
    /// marks and rows the cores exchange.
    visible_shared: [bool; 3],
}

/// The scene's lit objects (for [`Demo::set_shading`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Object {
    /// The red sphere (about 5 000 pixels).
    Sphere = 0,
    /// The teal torus (about 6 000 pixels).
    Torus = 1,
}

/// What changes from frame to frame: the lights and the objects' transforms.
pub struct Frame<T> {
    lights: Scene<T, 3, 4>,
    lamp_colour: Rgb<T>,
    /// Model transforms of the sphere, the torus and the lamp.
    transforms: [Affine<T>; 3],
}

/// A share's entries ([`ScreenExchange`]'s vertices, [`VisibleExchange`]'s triangle rows)
/// spread to mesh order for `PreparedMesh::set_screen` and `set_visible`: item `i` of the
/// share (`i = 2 j + core`) is entry `j = i >> 1`; the entries at the other indices are not
/// taken.
fn spread<X: Copy>(share: &[X], empty: X) -> impl Iterator<Item = X> + '_ {
    (0..2 * share.len()).map(move |i| share.get(i >> 1).copied().unwrap_or(empty))
}

/// Whether vertex `i` is core `core`'s of `cores` (`i mod cores == core`): with two cores the
/// low bit, no division (an ARMv6-M core has no divide instruction: each `%` by a number
/// known only at run time is a library call, and the shares ask once per vertex several
/// times a frame).
#[inline]
fn share(core: usize, cores: usize) -> impl Fn(usize) -> bool + Copy {
    move |i: usize| {
        if cores == 2 {
            i & 1 == core
        } else {
            i % cores == core
        }
    }
}

/// The lamp's shader: its colour, whatever the normal.
struct Glow<T>(Rgb<T>);

impl<T: Real> arealight::raster::Shader<T> for Glow<T> {
    fn shade(&self, _p: Vec3<T>, _n: UnitVec3<T>, _v: UnitVec3<T>) -> Rgb<T> {
        self.0
    }
}

/// The scene's encoding: gamma 2 (a square root per channel) instead of sRGB (a powf per
/// channel), within 0.05 of sRGB; through a table either way, so only its 4097 entries pay for
/// it.
const ENCODING: Encoding = Encoding::Gamma2;

fn v3<T: Real>(v: [f64; 3]) -> Vec3<T> {
    Vec3::from_f64(v)
}

impl<'a, T: Real> Demo<'a, T> {
    /// Fills `buffers` with the meshes and `table` with the scene's encoding (gamma 2) and
    /// sets up the camera and
    /// materials. `shading`: [`Shading::PerPixel`] (every visible pixel runs both lights'
    /// Lambert and Phong models: the area lights' soft highlights, slow) or
    /// [`Shading::Gouraud`] (the models at the visible vertices only, once per frame each:
    /// much cheaper, coarser).
    ///
    /// # Errors
    /// None with the constants above; the mesh generators' and constructors' errors otherwise.
    pub fn new(
        buffers: &'a mut MeshBuffers<T>,
        table: &'a mut EncodeTable,
        shading: Shading,
    ) -> Result<Self, RasterError> {
        Self::fill_table(table);
        Self::build(buffers, table, shading)
    }

    /// Fills `table` with the scene's encoding (gamma 2, in `T`'s own arithmetic), for
    /// [`Demo::sharing`]: [`Demo::new`] does this, then builds the scene.
    pub fn fill_table(table: &mut EncodeTable) {
        table.fill::<T>(ENCODING);
    }

    /// [`Demo::new`] with an encoding table already filled ([`Demo::fill_table`], or another
    /// `Demo`'s: [`Demo::table`]), shared: the two cores of the RP2040 firmware draw through
    /// one table (16 KiB with its guards).
    ///
    /// # Errors
    /// [`RasterError::BadParameter`] (`"table"`) for a table not filled with the scene's
    /// encoding (e.g. a zeroed one); otherwise as [`Demo::new`].
    pub fn sharing(
        buffers: &'a mut MeshBuffers<T>,
        table: &'a EncodeTable,
        shading: Shading,
    ) -> Result<Self, RasterError> {
        if table.encoding() != ENCODING {
            return Err(RasterError::BadParameter("table"));
        }
        Self::build(buffers, table, shading)
    }

    /// The encoding table this scene draws through (for [`Demo::sharing`]).
    pub fn table(&self) -> &'a EncodeTable {
        self.table
    }

    /// [`Demo::new`]'s work once the table is filled.
    fn build(
        buffers: &'a mut MeshBuffers<T>,
        table: &'a EncodeTable,
        shading: Shading,
    ) -> Result<Self, RasterError> {
        let MeshBuffers {
            sphere_vertices,
            sphere_triangles,
            torus_vertices,
            torus_triangles,
            lamp_vertices,
            lamp_triangles,
            sphere_frame,
            torus_frame,
            lamp_frame,
            sphere_rows,
            torus_rows,
            lamp_rows,
            sphere_sums,
        } = buffers;
        let sphere = mesh::uv_sphere(
            T::ONE,
            SPHERE_STACKS,
            SPHERE_SLICES,
            sphere_vertices,
            sphere_triangles,
        )?;
        let torus = mesh::torus(
            T::from_f64(TORUS_MAJOR_RADIUS),
            T::from_f64(TORUS_MINOR_RADIUS),
            TORUS_MAJOR,
            TORUS_MINOR,
            torus_vertices,
            torus_triangles,
        )?;
        let lamp = mesh::uv_sphere(
            T::ONE,
            LAMP_STACKS,
            LAMP_SLICES,
            lamp_vertices,
            lamp_triangles,
        )?;
        let sphere = Mesh::new(
            &sphere_vertices[..sphere.vertices],
            &sphere_triangles[..sphere.triangles],
        )?;
        let lamp = Mesh::new(
            &lamp_vertices[..lamp.vertices],
            &lamp_triangles[..lamp.triangles],
        )?;
        let torus = Mesh::new(
            &torus_vertices[..torus.vertices],
            &torus_triangles[..torus.triangles],
        )?;
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
        lit.encoding = ENCODING;
        let mut emissive = DrawOptions::new(Shading::Gouraud);
        emissive.encoding = ENCODING;
        // The panel: 2 x 1.4 units, 1.9 above the floor-less ground, facing down (a
        // polygon light emits from both faces).
        let panel = PolygonLight::new(&[
            v3([-1.0, 1.9, -1.0]),
            v3([1.0, 1.9, -1.0]),
            v3([1.0, 1.9, 0.4]),
            v3([-1.0, 1.9, 0.4]),
        ])?;
        let mut panel_scene = Scene::new();
        // One push into an empty scene with a finite colour: cannot fail.
        let _ = panel_scene.push(SceneLight::Polygon(panel), Rgb::from_f64([2.6, 2.7, 3.0]));
        let panel = panel_scene;
        let sphere_transform = Affine::scale(Vec3::new(
            T::from_f64(SPHERE_RADIUS),
            T::from_f64(SPHERE_RADIUS),
            T::from_f64(SPHERE_RADIUS),
        ))?
        .then_translation(v3(SPHERE_AT))?;
        let lamp_scale = T::from_f64(LAMP_RADIUS);
        let lamp_scale = Affine::scale(Vec3::new(lamp_scale, lamp_scale, lamp_scale))?;
        Ok(Demo {
            camera,
            sphere: PreparedMesh::with_triangle_rows(sphere, sphere_frame, sphere_rows)?
                .with_fixed_sums(sphere_sums)?,
            torus: PreparedMesh::with_triangle_rows(torus, torus_frame, torus_rows)?,
            lamp: PreparedMesh::with_triangle_rows(lamp, lamp_frame, lamp_rows)?,
            // The panel: 2 x 1.4 units, 1.9 above the floor-less ground, facing down (a
            // polygon light emits from both faces).
            panel,
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
            lit: [lit, lit],
            emissive,
            table,
            sphere_at: None,
            fixed_transforms: [sphere_transform, lamp_scale],
            sphere_moved: false,
            visible_shared: [false; 3],
        })
    }

    /// Chooses the shading of one lit object (the lamp is always its flat colour): Gouraud
    /// where the chip must, per pixel where it can afford the area lights' exact highlights.
    pub fn set_shading(&mut self, object: Object, shading: Shading) {
        self.lit[object as usize].shading = shading;
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
        // Colours scale the models' normalized irradiance (unit radiance): the panel subtends
        // about 0.3 sr from the objects, the lamp much less, hence the large factors.
        let lamp_colour = Rgb::from_f64([1.0, 0.8, 0.55]);
        let mut lights = self.panel.clone();
        // Two more pushes into a scene of capacity 3 with finite colours: cannot fail.
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
        let [sphere, lamp_scale] = self.fixed_transforms;
        let torus = Affine::rotation(v3([1.0, 0.0, 0.0]), t)?
            .then(&Affine::rotation(v3([0.0, 1.0, 0.0]), t + t)?)
            .then_translation(v3(TORUS_AT))?;
        let lamp = lamp_scale.then_translation(lamp_at)?;
        Ok(Frame {
            lights,
            lamp_colour,
            transforms: [sphere, torus, lamp],
        })
    }

    /// Transforms and projects every vertex of the three objects for `frame` ([`Stage::Transform`]),
    /// but the sphere's where its transform is the one its vertex data already hold (it
    /// stands still: from the second frame on; the same pixels, its data being those a new
    /// transform would give).
    pub fn transform(&mut self, frame: &Frame<T>) {
        let [s, t, l] = &frame.transforms;
        if self.sphere_moves(s) {
            self.sphere.transform(&self.camera, s);
        }
        self.torus.transform(&self.camera, t);
        // The lamp's shader is its colour alone: no normals.
        self.lamp.transform_unlit(&self.camera, l);
    }

    /// [`Demo::transform`] of this core's share of the vertices: those whose index is `core`
    /// modulo `cores` (the same share as [`Demo::shade_share`]'s, so that each core shades the
    /// vertices it transformed). With two cores, each transforms its half, then each takes the
    /// other's screen data through a [`ScreenExchange`] ([`Demo::export_screen`],
    /// [`Demo::import_screen`]): every vertex is transformed once per frame.
    pub fn transform_share(&mut self, frame: &Frame<T>, core: usize, cores: usize) {
        let [s, t, l] = &frame.transforms;
        let cores = cores.max(1);
        let mine = share(core, cores);
        // (Every core decides the same from the same frames: each skips the sphere, and the
        // exchange leaves it out, in the same frames.)
        if self.sphere_moves(s) {
            self.sphere.transform_some(&self.camera, s, true, mine);
        }
        self.torus.transform_some(&self.camera, t, true, mine);
        self.lamp.transform_some(&self.camera, l, false, mine);
    }

    /// Whether the sphere needs the transform `s` (not the one its vertex data hold); records
    /// `s` as the one they will hold.
    fn sphere_moves(&mut self, s: &Affine<T>) -> bool {
        self.sphere_moved = self.sphere_at.as_ref() != Some(s);
        self.sphere_at = Some(*s);
        self.sphere_moved
    }

    /// Writes the screen data of core `core`'s share of the vertices (of two cores: those of
    /// index `core` modulo 2) into `exchange` (after [`Demo::transform_share`] with the same
    /// `core` and 2 cores), in vertex order, for the other core to take.
    pub fn export_screen(&self, exchange: &mut ScreenExchange<T>, core: usize) {
        let core = core.min(1);
        let copy = |dst: &mut [VertexScreen<T>], src: &PreparedMesh<'_, '_, T>| {
            for (d, v) in dst.iter_mut().zip(src.screen().skip(core).step_by(2)) {
                *d = v;
            }
        };
        if self.sphere_moved {
            copy(&mut exchange.sphere, &self.sphere);
        }
        copy(&mut exchange.torus, &self.torus);
        copy(&mut exchange.lamp, &self.lamp);
    }

    /// Takes from `exchange` the screen data of the vertices that core `core` of two
    /// transformed (what it exported this frame).
    pub fn import_screen(&mut self, exchange: &ScreenExchange<T>, core: usize) {
        let theirs = share(core.min(1), 2);
        let camera = &self.camera;
        if self.sphere_moved {
            self.sphere.set_screen(
                camera,
                spread(&exchange.sphere, VertexScreen::EMPTY),
                theirs,
            );
        }
        self.torus
            .set_screen(camera, spread(&exchange.torus, VertexScreen::EMPTY), theirs);
        self.lamp
            .set_screen(camera, spread(&exchange.lamp, VertexScreen::EMPTY), theirs);
    }

    /// The visible-vertex pass of the shading ([`PreparedMesh::find_visible_some`]) over this
    /// core's share of each object's triangles: those whose index is `core` modulo `cores`,
    /// for each object whose pass is due (every frame for the torus and the lamp; for the
    /// sphere, which stands still, only when its screen data are new). With two cores, after
    /// [`Demo::import_screen`]: each makes the pass over its half, then each takes the
    /// other's marks and rows through a [`VisibleExchange`] ([`Demo::export_visible`],
    /// [`Demo::import_visible`]), and [`Demo::shade_share`] goes straight to its shader
    /// calls: every triangle is visited once per frame instead of once on each core. Both
    /// cores decide alike which objects take part. Returns how many did (0 once the
    /// exchange has completed every pass).
    pub fn find_visible_share(&mut self, core: usize, cores: usize) -> usize {
        let mine = share(core, cores.max(1));
        let camera = &self.camera;
        self.visible_shared = [
            self.sphere
                .find_visible_some(camera, self.lit[0].cull, mine),
            self.torus.find_visible_some(camera, self.lit[1].cull, mine),
            self.lamp
                .find_visible_some(camera, self.emissive.cull, mine),
        ];
        self.visible_shared.iter().filter(|&&s| s).count()
    }

    /// Writes core `core`'s visible-vertex marks and its triangles' rows (of two cores: the
    /// triangles of index `core` modulo 2) into `exchange` (after
    /// [`Demo::find_visible_share`] with the same `core` and 2 cores), for the other core to
    /// take.
    pub fn export_visible(&self, exchange: &mut VisibleExchange, core: usize) {
        let core = core.min(1);
        let objects: [(&PreparedMesh<'_, '_, T>, &mut [bool], &mut [TriangleRows]); 3] = [
            (
                &self.sphere,
                &mut exchange.marks.sphere,
                &mut exchange.rows.sphere,
            ),
            (
                &self.torus,
                &mut exchange.marks.torus,
                &mut exchange.rows.torus,
            ),
            (
                &self.lamp,
                &mut exchange.marks.lamp,
                &mut exchange.rows.lamp,
            ),
        ];
        for ((mesh, marks, rows), shared) in objects.into_iter().zip(self.visible_shared) {
            if !shared {
                continue;
            }
            for (d, m) in marks.iter_mut().zip(mesh.visible_marks()) {
                *d = m;
            }
            for (d, r) in rows
                .iter_mut()
                .zip(mesh.triangle_rows().skip(core).step_by(2))
            {
                *d = r;
            }
        }
    }

    /// Takes from `exchange` the marks and triangle rows that core `core` of two wrote this
    /// frame, completing each shared object's visible-vertex pass.
    pub fn import_visible(&mut self, exchange: &VisibleExchange, core: usize) {
        let theirs = share(core.min(1), 2);
        let marks = &exchange.marks;
        let rows = &exchange.rows;
        let camera = &self.camera;
        let [sphere, torus, lamp] = self.visible_shared;
        if sphere {
            self.sphere.set_visible(
                camera,
                self.lit[0].cull,
                marks.sphere.iter().copied(),
                spread(&rows.sphere, TriangleRows::EMPTY),
                theirs,
            );
        }
        if torus {
            self.torus.set_visible(
                camera,
                self.lit[1].cull,
                marks.torus.iter().copied(),
                spread(&rows.torus, TriangleRows::EMPTY),
                theirs,
            );
        }
        if lamp {
            self.lamp.set_visible(
                camera,
                self.emissive.cull,
                marks.lamp.iter().copied(),
                spread(&rows.lamp, TriangleRows::EMPTY),
                theirs,
            );
        }
    }

    /// Gouraud: shades the visible vertices of the three objects once each
    /// ([`Stage::Shade`]); per pixel: only the lamp's (its constant colour). Returns the
    /// number of shader calls.
    pub fn shade(&mut self, frame: &Frame<T>) -> u32 {
        self.shade_share(frame, 0, 1)
    }

    /// [`Demo::shade`] of this core's share of the visible vertices: those whose index is
    /// `core` modulo `cores`. With two cores, each shades its half, then each takes the
    /// other's colours through a [`ColourExchange`] ([`Demo::export_colours`],
    /// [`Demo::import_colours`]): every visible vertex is shaded once per frame.
    pub fn shade_share(&mut self, frame: &Frame<T>, core: usize, cores: usize) -> u32 {
        let cores = cores.max(1);
        self.shade_where(frame, share(core, cores))
    }

    /// [`Demo::shade_share`], calling `poll` before each of this core's shader calls (one
    /// every 20 000 to 40 000 cycles on the RP2040): a two-core firmware sends the frame's
    /// empty bands from there while the display link would otherwise idle
    /// ([`Demo::band_is_empty`]). The same colours.
    pub fn shade_share_polling(
        &mut self,
        frame: &Frame<T>,
        core: usize,
        cores: usize,
        poll: impl FnMut(),
    ) -> u32 {
        let ours = share(core, cores.max(1));
        // (`shade_some` takes a `Fn` filter: the poll behind a `RefCell`.)
        let poll = core::cell::RefCell::new(poll);
        self.shade_where(frame, |i| {
            let mine = ours(i);
            if mine {
                if let Ok(mut poll) = poll.try_borrow_mut() {
                    (*poll)();
                }
            }
            mine
        })
    }

    /// The shading of the visible vertices whose index `mine` accepts, every object's.
    fn shade_where(&mut self, frame: &Frame<T>, mine: impl Fn(usize) -> bool + Copy) -> u32 {
        let camera = &self.camera;
        // The panel (the first light) and the sphere's material never change: version 0.
        let red = SplitLit::new(&frame.lights, &self.red, PANEL_LIGHTS, 0);
        let teal = Lit::new(&frame.lights, &self.teal);
        let glow = Glow(frame.lamp_colour);
        self.sphere
            .shade_split_some(camera, &red, &self.lit[0], mine)
            + self.torus.shade_some(camera, &teal, &self.lit[1], mine)
            + self.lamp.shade_some(camera, &glow, &self.emissive, mine)
    }

    /// Whether no object can reach the band of `rows` rows from frame row `y0` this frame
    /// (after the transform: [`Demo::transform`], or on two cores [`Demo::transform_share`]
    /// and [`Demo::import_screen`]): every object's screen rows miss it, so
    /// [`Demo::draw_band`] draws nothing there and the band stays as cleared. (A band that
    /// an object's rows reach may still come out empty: `false` then.)
    pub fn band_is_empty(&self, y0: u16, rows: u16) -> bool {
        let (r0, r1) = (i32::from(y0), i32::from(y0) + i32::from(rows));
        [self.sphere.rows(), self.torus.rows(), self.lamp.rows()]
            .iter()
            .all(|&(top, bottom)| bottom <= r0 || top >= r1)
    }

    /// Writes this frame's vertex colours into `exchange` (after [`Demo::shade_share`]).
    pub fn export_colours(&self, exchange: &mut ColourExchange) {
        let copy = |dst: &mut [VertexColour], src: &PreparedMesh<'_, '_, T>| {
            for (d, c) in dst.iter_mut().zip(src.colours()) {
                *d = c;
            }
        };
        copy(&mut exchange.sphere, &self.sphere);
        copy(&mut exchange.torus, &self.torus);
        copy(&mut exchange.lamp, &self.lamp);
    }

    /// Takes from `exchange` the colours of the vertices that core `core` of `cores` shaded
    /// (what it exported this frame).
    pub fn import_colours(&mut self, exchange: &ColourExchange, core: usize, cores: usize) {
        let cores = cores.max(1);
        let theirs = share(core, cores);
        self.sphere
            .set_colours(exchange.sphere.iter().copied(), theirs);
        self.torus
            .set_colours(exchange.torus.iter().copied(), theirs);
        self.lamp.set_colours(exchange.lamp.iter().copied(), theirs);
    }

    /// [`Demo::transform`] then [`Demo::shade`].
    pub fn prepare(&mut self, frame: &Frame<T>) -> u32 {
        self.transform(frame);
        self.shade(frame)
    }

    /// Draws the prepared frame (after [`Demo::prepare`] with the same `frame`) into `band`
    /// (cleared by the caller), adding what the draw calls did to `stats`. Objects whose rows
    /// miss the band are skipped without touching a triangle.
    ///
    /// # Errors
    /// [`RasterError::BadSize`] if the band is not [`WIDTH`] wide.
    pub fn draw_band(
        &self,
        frame: &Frame<T>,
        band: &mut Band<'_, Rgb565>,
        stats: &mut DrawStats,
    ) -> Result<(), RasterError> {
        let mut add = |s: DrawStats| {
            stats.triangles += s.triangles;
            stats.rasterized += s.rasterized;
            stats.shaded += s.shaded;
            stats.pixels += s.pixels;
        };
        let camera = &self.camera;
        let red = Lit::new(&frame.lights, &self.red);
        let teal = Lit::new(&frame.lights, &self.teal);
        add(self
            .sphere
            .draw(camera, band, &red, &self.lit[0], self.table)?);
        add(self
            .torus
            .draw(camera, band, &teal, &self.lit[1], self.table)?);
        let glow = Glow(frame.lamp_colour);
        add(self
            .lamp
            .draw(camera, band, &glow, &self.emissive, self.table)?);
        Ok(())
    }
}

/// One core's share of the vertices' screen data of a frame, as two cores exchange them (see
/// [`Demo::transform_share`]): the vertices of index `core` modulo 2, in order (entry `j` is
/// vertex `2 j + core`). Each core writes its own and reads the other core's, so the two
/// can copy at once (9 KiB each in `Fixed22`).
#[derive(Clone, Debug)]
pub struct ScreenExchange<T> {
    sphere: [VertexScreen<T>; SPHERE_VERTICES.div_ceil(2)],
    torus: [VertexScreen<T>; TORUS_VERTICES.div_ceil(2)],
    lamp: [VertexScreen<T>; LAMP_VERTICES.div_ceil(2)],
}

impl<T: Real> ScreenExchange<T> {
    /// All placeholders (a `const fn`, for a `static`; all zero bits).
    pub const fn new() -> Self {
        ScreenExchange {
            sphere: [VertexScreen::EMPTY; SPHERE_VERTICES.div_ceil(2)],
            torus: [VertexScreen::EMPTY; TORUS_VERTICES.div_ceil(2)],
            lamp: [VertexScreen::EMPTY; LAMP_VERTICES.div_ceil(2)],
        }
    }
}

impl<T: Real> Default for ScreenExchange<T> {
    fn default() -> Self {
        Self::new()
    }
}

/// The shaded vertex colours of one frame, as one core hands them to another (see
/// [`Demo::shade_share`]): 7 KiB.
#[derive(Clone, Debug)]
pub struct ColourExchange {
    sphere: [VertexColour; SPHERE_VERTICES],
    torus: [VertexColour; TORUS_VERTICES],
    lamp: [VertexColour; LAMP_VERTICES],
}

impl ColourExchange {
    /// All black (a `const fn`, for a `static`).
    pub const fn new() -> Self {
        ColourExchange {
            sphere: [VertexColour::BLACK; SPHERE_VERTICES],
            torus: [VertexColour::BLACK; TORUS_VERTICES],
            lamp: [VertexColour::BLACK; LAMP_VERTICES],
        }
    }
}

impl Default for ColourExchange {
    fn default() -> Self {
        Self::new()
    }
}

/// One core's share of a frame's visible-vertex pass, as two cores exchange them (see
/// [`Demo::find_visible_share`]): its marks of every vertex and the rows of its triangles (of
/// index `core` modulo 2, in order). Each core writes its own and reads the other core's, so
/// the two can copy at once (2.5 KiB each).
#[derive(Clone, Debug)]
pub struct VisibleExchange {
    marks: VisibleMarks,
    rows: ExchangedRows,
}

/// Each object's vertices as one core's pass marked them.
#[derive(Clone, Debug)]
struct VisibleMarks {
    sphere: [bool; SPHERE_VERTICES],
    torus: [bool; TORUS_VERTICES],
    lamp: [bool; LAMP_VERTICES],
}

/// Each object's rows of one core's triangles.
#[derive(Clone, Debug)]
struct ExchangedRows {
    sphere: [TriangleRows; SPHERE_TRIANGLES.div_ceil(2)],
    torus: [TriangleRows; TORUS_TRIANGLES.div_ceil(2)],
    lamp: [TriangleRows; LAMP_TRIANGLES.div_ceil(2)],
}

impl VisibleExchange {
    /// Nothing marked, no rows (a `const fn`, for a `static`).
    pub const fn new() -> Self {
        VisibleExchange {
            marks: VisibleMarks {
                sphere: [false; SPHERE_VERTICES],
                torus: [false; TORUS_VERTICES],
                lamp: [false; LAMP_VERTICES],
            },
            rows: ExchangedRows {
                sphere: [TriangleRows::EMPTY; SPHERE_TRIANGLES.div_ceil(2)],
                torus: [TriangleRows::EMPTY; TORUS_TRIANGLES.div_ceil(2)],
                lamp: [TriangleRows::EMPTY; LAMP_TRIANGLES.div_ceil(2)],
            },
        }
    }
}

impl Default for VisibleExchange {
    fn default() -> Self {
        Self::new()
    }
}

/// The stages of a frame, as the boards time them (each firmware reads its own cycle counter
/// between them: SysTick on the RP2040, DWT on the STM32F411, TIM2 instructions under QEMU).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// The frame's lights and transforms ([`Demo::frame`]).
    Setup = 0,
    /// Vertices through the model transform and the camera, once per frame.
    Transform = 1,
    /// The light models at the vertices (Gouraud), once per frame.
    Shade = 2,
    /// Scan conversion, interpolation, depth test, per-pixel shading (if chosen) and encoding,
    /// band by band.
    Raster = 3,
    /// Sending the bands to the display.
    Flush = 4,
}

impl Stage {
    /// Every stage, in frame order.
    pub const ALL: [Stage; 5] = [
        Stage::Setup,
        Stage::Transform,
        Stage::Shade,
        Stage::Raster,
        Stage::Flush,
    ];
    /// The stage's name in logs and tables.
    pub const fn name(self) -> &'static str {
        match self {
            Stage::Setup => "setup",
            Stage::Transform => "transform",
            Stage::Shade => "shade",
            Stage::Raster => "raster",
            Stage::Flush => "flush",
        }
    }
}

/// What [`Demo::render_frame`] measured: the clock's ticks per [`Stage`] (indexed by
/// `Stage as usize`) and the draw calls' statistics.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameReport {
    /// Clock ticks spent in each stage.
    pub ticks: [u32; 5],
    /// What the draw calls did.
    pub stats: DrawStats,
}

impl FrameReport {
    /// The sum of all stages.
    pub fn total(&self) -> u32 {
        self.ticks.iter().fold(0u32, |a, &t| a.wrapping_add(t))
    }
}

/// Why a frame failed: the rasterizer refused something or the display did not answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameError<E> {
    /// The rasterizer's error.
    Raster(RasterError),
    /// The flush callback's error (the display's).
    Flush(E),
}

impl<E> From<RasterError> for FrameError<E> {
    fn from(e: RasterError) -> Self {
        FrameError::Raster(e)
    }
}

/// The stages of a frame, as [`render_stages`] runs them: what a scene does per frame (the
/// demo, and the scene-file player of [`spec`]).
pub(crate) trait Stages {
    /// What the setup computes for the frame (lights, transforms).
    type Frame;
    /// The frame's setup ([`Stage::Setup`]).
    fn setup(&self, n: u32) -> Result<Self::Frame, RasterError>;
    /// Every vertex transformed ([`Stage::Transform`]).
    fn transform(&mut self, frame: &Self::Frame);
    /// The Gouraud vertices shaded ([`Stage::Shade`]); the shader calls.
    fn shade(&mut self, frame: &Self::Frame) -> u32;
    /// One band drawn (cleared by the caller) ([`Stage::Raster`]).
    fn draw_band(
        &self,
        frame: &Self::Frame,
        band: &mut Band<'_, Rgb565>,
        stats: &mut DrawStats,
    ) -> Result<(), RasterError>;
    /// The frame's height in pixels.
    fn height(&self) -> u16;
    /// The clear colour.
    fn background(&self) -> Rgb565;
    /// Whether no object reaches rows `y0..y0 + rows` this frame (after the transform); `false`
    /// when not known.
    fn band_is_empty(&self, _y0: u16, _rows: u16) -> bool {
        false
    }
}

/// What [`Demo::render_frame_carrying`] hands its caller.
#[derive(Debug)]
pub enum Output<'a, 'b> {
    /// A finished band, to send (mutable: a sender may swap its pixel buffer for another,
    /// [`Band::replace_pixels`], instead of copying it).
    Band(&'a mut Band<'b, Rgb565>),
    /// The frame's last band, `rows` rows from `y0`, which no object reaches: not drawn; the
    /// caller sends it as [`BACKGROUND`] at the next [`Output::Carried`] (or now), instead of
    /// waiting for its turn at the display.
    Keep {
        /// Its first row.
        y0: u16,
        /// Its rows.
        rows: u16,
    },
    /// The frame's transform is done (the last frame's bands long handed to the display): a
    /// band [`Output::Keep`] left can be sent now, while this frame is shaded.
    Carried,
}

/// Renders frame `n` of `scene` through `band`, calling `flush` with each finished band, top to
/// bottom, and `clock` between the stages, whose ticks it returns (the one frame loop of
/// [`Demo::render_frame`] and `spec::Player::render_frame`).
pub(crate) fn render_stages<S: Stages, E>(
    scene: &mut S,
    n: u32,
    band: &mut Band<'_, Rgb565>,
    clock: &mut impl FnMut() -> u32,
    mut flush: impl FnMut(&Band<'_, Rgb565>) -> Result<(), E>,
) -> Result<FrameReport, FrameError<E>> {
    render_stages_carrying(scene, n, band, clock, false, |out| match out {
        Output::Band(b) => flush(&*b),
        Output::Keep { .. } | Output::Carried => Ok(()),
    })
}

/// [`render_stages`] handing the caller [`Output`]s: with `carry`, the last band is kept
/// when no object reaches it, and [`Output::Carried`] follows every transform.
pub(crate) fn render_stages_carrying<'b, S: Stages, E>(
    scene: &mut S,
    n: u32,
    band: &mut Band<'b, Rgb565>,
    clock: &mut impl FnMut() -> u32,
    carry: bool,
    mut flush: impl FnMut(Output<'_, 'b>) -> Result<(), E>,
) -> Result<FrameReport, FrameError<E>> {
    let mut report = FrameReport::default();
    let mut last = clock();
    let mut lap = |stage: Stage, ticks: &mut [u32; 5]| {
        let now = clock();
        let t = &mut ticks[stage as usize];
        *t = t.wrapping_add(now.wrapping_sub(last));
        last = now;
    };
    let frame = scene.setup(n)?;
    lap(Stage::Setup, &mut report.ticks);
    scene.transform(&frame);
    lap(Stage::Transform, &mut report.ticks);
    if carry {
        flush(Output::Carried).map_err(FrameError::Flush)?;
        lap(Stage::Flush, &mut report.ticks);
    }
    let mut stats = DrawStats {
        shaded: scene.shade(&frame),
        ..DrawStats::default()
    };
    lap(Stage::Shade, &mut report.ticks);
    let rows = band.rows().max(1);
    let (height, background) = (scene.height(), scene.background());
    let mut y0: u16 = 0;
    while y0 < height {
        let out = if carry && y0.saturating_add(rows) >= height && scene.band_is_empty(y0, rows) {
            Output::Keep { y0, rows }
        } else {
            band.move_to(y0);
            band.clear(background);
            scene.draw_band(&frame, band, &mut stats)?;
            lap(Stage::Raster, &mut report.ticks);
            Output::Band(band)
        };
        flush(out).map_err(FrameError::Flush)?;
        lap(Stage::Flush, &mut report.ticks);
        y0 = y0.saturating_add(rows);
    }
    report.stats = stats;
    Ok(report)
}

impl<T: Real> Stages for Demo<'_, T> {
    type Frame = Frame<T>;
    fn setup(&self, n: u32) -> Result<Frame<T>, RasterError> {
        self.frame(n)
    }
    fn transform(&mut self, frame: &Frame<T>) {
        Demo::transform(self, frame);
    }
    fn shade(&mut self, frame: &Frame<T>) -> u32 {
        Demo::shade(self, frame)
    }
    fn draw_band(
        &self,
        frame: &Frame<T>,
        band: &mut Band<'_, Rgb565>,
        stats: &mut DrawStats,
    ) -> Result<(), RasterError> {
        Demo::draw_band(self, frame, band, stats)
    }
    fn height(&self) -> u16 {
        HEIGHT
    }
    fn background(&self) -> Rgb565 {
        BACKGROUND
    }
    fn band_is_empty(&self, y0: u16, rows: u16) -> bool {
        Demo::band_is_empty(self, y0, rows)
    }
}

impl<'a, T: Real> Demo<'a, T> {
    /// Renders frame `n` through `band` (a [`WIDTH`]-wide band of any height), calling `flush`
    /// with each finished band, top to bottom, and `clock` (any free-running tick counter:
    /// core cycles, instructions, microseconds; wrapping) between the stages, whose ticks it
    /// returns. This is the whole frame of every board and of the host reference.
    ///
    /// # Errors
    /// The first error of the rasterizer or of `flush`.
    pub fn render_frame<E>(
        &mut self,
        n: u32,
        band: &mut Band<'_, Rgb565>,
        clock: &mut impl FnMut() -> u32,
        flush: impl FnMut(&Band<'_, Rgb565>) -> Result<(), E>,
    ) -> Result<FrameReport, FrameError<E>> {
        render_stages(self, n, band, clock, flush)
    }

    /// [`Demo::render_frame`] for a display that keeps what it was sent and a sender that
    /// need not wait: a last band that no object reaches is not drawn but handed to `flush` as
    /// [`Output::Keep`], and after each frame's transform `flush` gets [`Output::Carried`], when
    /// the caller sends such a band as [`BACKGROUND`] (its turn at the display has long come:
    /// the frame before it ended during the transform). So the frame's end does not wait for
    /// the transfer of the band before the last, and the last band's transfer overlaps the next
    /// frame's shading; the display still receives each frame whole before the next one. The
    /// one-core RP2040 firmware's loop (`boards/rp2040-st7789/src/bin/lit_scene.rs`).
    ///
    /// # Errors
    /// The first error of the rasterizer or of `flush`.
    pub fn render_frame_carrying<'b, E>(
        &mut self,
        n: u32,
        band: &mut Band<'b, Rgb565>,
        clock: &mut impl FnMut() -> u32,
        flush: impl FnMut(Output<'_, 'b>) -> Result<(), E>,
    ) -> Result<FrameReport, FrameError<E>> {
        render_stages_carrying(self, n, band, clock, true, flush)
    }
}
