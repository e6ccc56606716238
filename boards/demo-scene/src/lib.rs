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
mod share;
#[cfg(feature = "scene-file")]
pub mod spec;
mod stages;

pub use share::{ColourExchange, ScreenExchange, VisibleExchange};
pub use stages::{FrameError, FrameReport, Output, Stage};

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

    /// Whether the sphere needs the transform `s` (not the one its vertex data hold); records
    /// `s` as the one they will hold.
    fn sphere_moves(&mut self, s: &Affine<T>) -> bool {
        self.sphere_moved = self.sphere_at.as_ref() != Some(s);
        self.sphere_at = Some(*s);
        self.sphere_moved
    }

    /// Gouraud: shades the visible vertices of the three objects once each
    /// ([`Stage::Shade`]); per pixel: only the lamp's (its constant colour). Returns the
    /// number of shader calls.
    pub fn shade(&mut self, frame: &Frame<T>) -> u32 {
        self.shade_share(frame, 0, 1)
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
