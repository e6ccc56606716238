//! Scene files on the boards: a scene of `host-sim/scenes/*.toml` as plain data
//! ([`SceneSpec`], written by `host-sim budget --scene FILE --emit-spec OUT.rs`), built in any
//! scalar type and rendered by the same frame path as the demo ([`Player::render_frame`]:
//! transform once, shade the Gouraud vertices once, then band by band).
//!
//! It exists so that `host-sim budget`'s predictions can be checked on the emulators for
//! scenes other than the demo: the firmware renders the scene as written (each mesh Gouraud
//! or per pixel as its file says), and reports the same stages and counts as the demo frame.
//!
//! The construction mirrors `host-sim`'s scene files step for step (the same constructors, the
//! same conversions from the file's decimal values, in the same order: a mesh's transform is
//! `scale`, then `rotate`, then `translate`), so that the vertices, the camera and hence every
//! count (shader calls, pixels, triangle setups) are the host's exactly; `host-sim budget
//! --check` requires that equality of every emulated frame. The light colours and the
//! exposure are the file's (the exposure resolved by the host when the file leaves it out).
//!
//! Lights: the kinds of [`arealight::Scene`] (ambient, directional, point, hemisphere,
//! overcast, sky/ground, cap, sphere, polygons of up to [`POLYGON_VERTICES`] vertices); the
//! line and parallelogram lights and SH9 environments of scene files are not supported here
//! (`host-sim` refuses to emit them).
#![allow(clippy::large_enum_variant)]

use arealight::raster::{
    mesh, Affine, Band, Camera, Cull, DrawOptions, DrawStats, EncodeTable, Encoding, Lit, Material,
    Mesh, PreparedMesh, PreparedVertex, Projection, RasterError, Rgb565, Shading, Vertex,
};
use arealight::{
    Ambient, CapLight, DirectionalLight, HemisphereLight, OvercastSky, PointLight, PolygonLight,
    Real, Rgb, Scene, SceneLight, SkyGround, SphereLight, Vec3,
};

use crate::stages::{render_stages, Stages};
use crate::{FrameError, FrameReport, Glow};

/// The most lights of a scene.
pub const MAX_LIGHTS: usize = 8;
/// The most meshes of a scene.
pub const MAX_OBJECTS: usize = 8;
/// The most vertices of a polygon light.
pub const POLYGON_VERTICES: usize = 8;

/// A scene: camera, lights and meshes, as the file gives them (defaults resolved).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneSpec {
    /// The file's name (without `.toml`), for reports.
    pub name: &'static str,
    /// The camera.
    pub camera: CameraSpec,
    /// Multiplies every colour before encoding.
    pub exposure: f64,
    /// The clear colour (8-bit sRGB).
    pub background: [u8; 3],
    /// The output transfer function.
    pub encoding: Encoding,
    /// The lights, in file order.
    pub lights: &'static [LightSpec],
    /// The meshes, in file order (drawn in this order).
    pub objects: &'static [ObjectSpec],
}

/// A perspective camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraSpec {
    /// Where it is.
    pub eye: [f64; 3],
    /// The point it looks at.
    pub target: [f64; 3],
    /// Its roll: the direction that is up on screen.
    pub up: [f64; 3],
    /// Vertical field of view, in degrees.
    pub fov_deg: f64,
    /// Viewport width in pixels.
    pub width: u16,
    /// Viewport height in pixels.
    pub height: u16,
}

/// A light and its colour (per-channel radiance scale).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSpec {
    /// The light.
    pub kind: LightKind,
    /// Its colour.
    pub colour: [f64; 3],
}

/// The lights a board scene can hold (the file's keys).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightKind {
    /// Constant ambient light.
    Ambient,
    /// A light at infinity: the direction towards it.
    Directional([f64; 3]),
    /// A point light, with or without inverse-square falloff.
    Point {
        /// Where it is.
        position: [f64; 3],
        /// Inverse-square falloff.
        inverse_square: bool,
    },
    /// A constant hemisphere about an axis.
    Hemisphere([f64; 3]),
    /// The CIE overcast sky about its zenith axis.
    Overcast([f64; 3]),
    /// Sky and ground hemispheres.
    SkyGround {
        /// The sky's zenith.
        axis: [f64; 3],
        /// Sky radiance.
        sky: [f64; 3],
        /// Ground radiance.
        ground: [f64; 3],
    },
    /// A cap of directions (a distant disc).
    Cap {
        /// Its centre direction.
        axis: [f64; 3],
        /// Its half-angle in degrees.
        sigma_deg: f64,
    },
    /// A sphere light.
    Sphere {
        /// Its centre.
        center: [f64; 3],
        /// Its radius.
        radius: f64,
    },
    /// A planar polygon light (3 to [`POLYGON_VERTICES`] vertices).
    Polygon(&'static [[f64; 3]]),
}

/// A mesh of `arealight::raster::mesh`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MeshSpec {
    /// A UV sphere.
    Sphere {
        /// Radius.
        radius: f64,
        /// Rings of latitude.
        stacks: u16,
        /// Segments of longitude.
        slices: u16,
    },
    /// A plane in y = 0 facing +y.
    Plane {
        /// Extent in x and z.
        size: [f64; 2],
        /// Cells in x and z.
        cells: [u16; 2],
    },
    /// A box.
    Box {
        /// Half-extents.
        half: [f64; 3],
    },
    /// A torus about y.
    Torus {
        /// Radius of the tube's centre circle.
        major: f64,
        /// Radius of the tube.
        minor: f64,
        /// Segments around the axis and around the tube.
        segments: [u16; 2],
    },
}

impl MeshSpec {
    /// Vertices and triangles of the mesh.
    pub fn counts(&self) -> mesh::MeshCounts {
        match *self {
            MeshSpec::Sphere { stacks, slices, .. } => mesh::uv_sphere_counts(stacks, slices),
            MeshSpec::Plane { cells, .. } => mesh::plane_counts(cells[0], cells[1]),
            MeshSpec::Box { .. } => mesh::cuboid_counts(),
            MeshSpec::Torus { segments, .. } => mesh::torus_counts(segments[0], segments[1]),
        }
    }
}

/// How a mesh is coloured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SurfaceSpec {
    /// Lit by the scene's lights: diffuse and specular reflectance, Phong exponent.
    Lit {
        /// Diffuse reflectance.
        diffuse: [f64; 3],
        /// Specular reflectance.
        specular: [f64; 3],
        /// Phong exponent.
        exponent: u32,
    },
    /// Its own constant radiance (a visible lamp; always Gouraud).
    Emissive([f64; 3]),
}

/// A mesh placed in the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObjectSpec {
    /// The mesh.
    pub mesh: MeshSpec,
    /// Scale (first).
    pub scale: Option<[f64; 3]>,
    /// Rotation `[axis x, axis y, axis z, degrees]` (second).
    pub rotate: Option<[f64; 4]>,
    /// Translation (last).
    pub translate: Option<[f64; 3]>,
    /// Its colour.
    pub surface: SurfaceSpec,
    /// Gouraud (else per pixel).
    pub gouraud: bool,
    /// Drawn from both sides.
    pub two_sided: bool,
}

/// Why a scene cannot be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpecError {
    /// The rasterizer or a light's constructor refused a value.
    Raster(RasterError),
    /// More than [`MAX_LIGHTS`] lights or [`MAX_OBJECTS`] meshes, or a polygon of more than
    /// [`POLYGON_VERTICES`] vertices.
    Capacity(&'static str),
    /// The buffers hold fewer vertices or triangles than the meshes need.
    Buffers {
        /// Vertices needed.
        vertices: usize,
        /// Triangles needed.
        triangles: usize,
    },
}

impl From<RasterError> for SpecError {
    fn from(e: RasterError) -> Self {
        SpecError::Raster(e)
    }
}

impl From<arealight::Error> for SpecError {
    fn from(e: arealight::Error) -> Self {
        SpecError::Raster(e.into())
    }
}

/// The caller's storage for a scene of up to `V` vertices and `F` triangles in all (no
/// allocation): the meshes, their per-frame vertex data and the encoding table. A `const fn`
/// constructor, for a `static`.
pub struct SpecBuffers<T, const V: usize, const F: usize> {
    vertices: [Vertex<T>; V],
    triangles: [[u16; 3]; F],
    prepared: [PreparedVertex<T>; V],
    table: EncodeTable,
}

impl<T: Real, const V: usize, const F: usize> SpecBuffers<T, V, F> {
    const ZERO_VERTEX: Vertex<T> = Vertex::new(
        Vec3::new(T::ZERO, T::ZERO, T::ZERO),
        Vec3::new(T::ZERO, T::ZERO, T::ZERO),
    );
    /// Zeroed buffers ([`Player::new`] fills them).
    pub const fn new() -> Self {
        SpecBuffers {
            vertices: [Self::ZERO_VERTEX; V],
            triangles: [[0; 3]; F],
            prepared: [PreparedVertex::EMPTY; V],
            table: EncodeTable::zeroed(),
        }
    }
}

impl<T: Real, const V: usize, const F: usize> Default for SpecBuffers<T, V, F> {
    fn default() -> Self {
        Self::new()
    }
}

/// How one object is shaded.
enum Finish<T> {
    Lit(Material<T>),
    Emissive(Glow<T>),
}

/// One object of a built scene.
struct Placed<'a, T: Real> {
    mesh: PreparedMesh<'a, 'a, T>,
    transform: Affine<T>,
    finish: Finish<T>,
    options: DrawOptions<T>,
}

/// A scene built in `T`, ready to render.
pub struct Player<'a, T: Real> {
    camera: Camera<T>,
    lights: Scene<T, MAX_LIGHTS, POLYGON_VERTICES>,
    objects: [Option<Placed<'a, T>>; MAX_OBJECTS],
    background: Rgb565,
    table: &'a EncodeTable,
}

fn v3<T: Real>(v: [f64; 3]) -> Vec3<T> {
    Vec3::from_f64(v)
}

fn light<T: Real>(kind: &LightKind) -> Result<SceneLight<T, POLYGON_VERTICES>, SpecError> {
    Ok(match *kind {
        LightKind::Ambient => SceneLight::Ambient(Ambient(Rgb::splat(T::ONE))),
        LightKind::Directional(d) => SceneLight::Directional(DirectionalLight::new(v3(d))?),
        LightKind::Point {
            position,
            inverse_square,
        } => SceneLight::Point(if inverse_square {
            PointLight::inverse_square(v3(position))?
        } else {
            PointLight::new(v3(position))?
        }),
        LightKind::Hemisphere(a) => SceneLight::Hemisphere(HemisphereLight::new(v3(a))?),
        LightKind::Overcast(a) => SceneLight::Overcast(OvercastSky::new(v3(a), T::ONE)?),
        LightKind::SkyGround { axis, sky, ground } => SceneLight::SkyGround(SkyGround::new(
            v3(axis),
            Rgb::from_f64(sky),
            Rgb::from_f64(ground),
        )?),
        LightKind::Cap { axis, sigma_deg } => SceneLight::Cap(CapLight::new(
            v3(axis),
            T::from_f64(sigma_deg.to_radians().min(core::f64::consts::FRAC_PI_2)),
        )?),
        LightKind::Sphere { center, radius } => {
            SceneLight::Sphere(SphereLight::new(v3(center), T::from_f64(radius))?)
        }
        LightKind::Polygon(vs) => {
            if vs.len() > POLYGON_VERTICES {
                return Err(SpecError::Capacity("polygon vertices"));
            }
            let mut at = [Vec3::new(T::ZERO, T::ZERO, T::ZERO); POLYGON_VERTICES];
            for (a, &v) in at.iter_mut().zip(vs) {
                *a = v3(v);
            }
            SceneLight::Polygon(PolygonLight::new(&at[..vs.len()])?)
        }
    })
}

/// Fills `verts` and `tris` with the mesh (as `host-sim`'s scene files build it).
fn build_mesh<T: Real>(
    m: &MeshSpec,
    verts: &mut [Vertex<T>],
    tris: &mut [[u16; 3]],
) -> Result<mesh::MeshCounts, RasterError> {
    match *m {
        MeshSpec::Sphere {
            radius,
            stacks,
            slices,
        } => mesh::uv_sphere(T::from_f64(radius), stacks, slices, verts, tris),
        MeshSpec::Plane { size, cells } => mesh::plane(
            T::from_f64(size[0]),
            T::from_f64(size[1]),
            cells[0],
            cells[1],
            verts,
            tris,
        ),
        MeshSpec::Box { half } => mesh::cuboid(v3(half), verts, tris),
        MeshSpec::Torus {
            major,
            minor,
            segments,
        } => mesh::torus(
            T::from_f64(major),
            T::from_f64(minor),
            segments[0],
            segments[1],
            verts,
            tris,
        ),
    }
}

/// The object's model transform: scale, then rotate, then translate.
fn transform<T: Real>(o: &ObjectSpec) -> Result<Affine<T>, RasterError> {
    let mut xf = Affine::identity();
    if let Some(s) = o.scale {
        xf = xf.then(&Affine::scale(v3(s))?);
    }
    if let Some([x, y, z, deg]) = o.rotate {
        xf = xf.then(&Affine::rotation(
            v3([x, y, z]),
            T::from_f64(deg.to_radians()),
        )?);
    }
    if let Some(t) = o.translate {
        xf = xf.then(&Affine::translation(v3(t))?);
    }
    Ok(xf)
}

impl<'a, T: Real> Player<'a, T> {
    /// Builds `spec` in `T` into `buffers`. Cost: the meshes' generators and the lights'
    /// constructors, once.
    ///
    /// # Errors
    /// [`SpecError`]: a value the library refuses in `T` (e.g. beyond Fixed22's coordinate
    /// range), too many lights or meshes, or buffers too small.
    pub fn new<const V: usize, const F: usize>(
        spec: &SceneSpec,
        buffers: &'a mut SpecBuffers<T, V, F>,
    ) -> Result<Self, SpecError> {
        if spec.lights.len() > MAX_LIGHTS {
            return Err(SpecError::Capacity("lights"));
        }
        if spec.objects.len() > MAX_OBJECTS {
            return Err(SpecError::Capacity("meshes"));
        }
        let (vertices, triangles) = spec.objects.iter().fold((0, 0), |(v, t), o| {
            let c = o.mesh.counts();
            (v + c.vertices, t + c.triangles)
        });
        if vertices > V || triangles > F {
            return Err(SpecError::Buffers {
                vertices,
                triangles,
            });
        }
        let c = &spec.camera;
        let camera = Camera::new(
            v3(c.eye),
            v3(c.target),
            v3(c.up),
            Projection::Perspective {
                fov_y: T::from_f64(c.fov_deg.to_radians()),
            },
            c.width,
            c.height,
        )?;
        let mut lights = Scene::new();
        for l in spec.lights {
            lights
                .push(light(&l.kind)?, Rgb::from_f64(l.colour))
                .map_err(|_| SpecError::Capacity("lights"))?;
        }
        let SpecBuffers {
            vertices: all_verts,
            triangles: all_tris,
            prepared,
            table,
        } = buffers;
        table.fill::<T>(spec.encoding);
        let table: &'a EncodeTable = table;
        // The meshes, one after another in the buffers.
        let (mut vs, mut ts) = (&mut all_verts[..], &mut all_tris[..]);
        for o in spec.objects {
            let n = o.mesh.counts();
            let (v, vrest) = core::mem::take(&mut vs).split_at_mut(n.vertices);
            let (t, trest) = core::mem::take(&mut ts).split_at_mut(n.triangles);
            build_mesh(&o.mesh, v, t)?;
            (vs, ts) = (vrest, trest);
        }
        let (all_verts, all_tris): (&'a [Vertex<T>], &'a [[u16; 3]]) = (all_verts, all_tris);
        let mut objects = [const { None }; MAX_OBJECTS];
        let (mut at_v, mut at_t, mut store) = (0, 0, &mut prepared[..]);
        let exposure = T::from_f64(spec.exposure) * table.exposure_scale::<T>();
        for (slot, o) in objects.iter_mut().zip(spec.objects) {
            let n = o.mesh.counts();
            let mesh = Mesh::new(
                &all_verts[at_v..at_v + n.vertices],
                &all_tris[at_t..at_t + n.triangles],
            )?;
            let (s, rest) = core::mem::take(&mut store).split_at_mut(n.vertices);
            store = rest;
            (at_v, at_t) = (at_v + n.vertices, at_t + n.triangles);
            let (finish, shading) = match o.surface {
                SurfaceSpec::Lit {
                    diffuse,
                    specular,
                    exponent,
                } => (
                    Finish::Lit(Material::new(
                        Rgb::from_f64(diffuse),
                        Rgb::from_f64(specular),
                        exponent,
                    )?),
                    if o.gouraud {
                        Shading::Gouraud
                    } else {
                        Shading::PerPixel
                    },
                ),
                SurfaceSpec::Emissive(c) => {
                    (Finish::Emissive(Glow(Rgb::from_f64(c))), Shading::Gouraud)
                }
            };
            let mut options = DrawOptions::new(shading);
            options.exposure = exposure;
            options.encoding = spec.encoding;
            if o.two_sided {
                options.cull = Cull::None;
                options.two_sided = true;
            } else {
                options.cull = Cull::Back;
            }
            *slot = Some(Placed {
                mesh: PreparedMesh::new(mesh, s)?,
                transform: transform(o)?,
                finish,
                options,
            });
        }
        let [r, g, b] = spec.background;
        Ok(Player {
            camera,
            lights,
            objects,
            background: Rgb565::new(r >> 3, g >> 2, b >> 3),
            table,
        })
    }

    /// The camera.
    pub fn camera(&self) -> &Camera<T> {
        &self.camera
    }

    /// Renders the scene through `band` (as wide as the camera's viewport, any height), calling
    /// `flush` with each finished band and `clock` between the stages, as
    /// [`crate::Demo::render_frame`] does (the same loop; the setup stage is empty: the scene
    /// does not move).
    ///
    /// # Errors
    /// The first error of the rasterizer or of `flush`.
    pub fn render_frame<E>(
        &mut self,
        band: &mut Band<'_, Rgb565>,
        clock: &mut impl FnMut() -> u32,
        flush: impl FnMut(&Band<'_, Rgb565>) -> Result<(), E>,
    ) -> Result<FrameReport, FrameError<E>> {
        render_stages(self, 0, band, clock, flush)
    }
}

impl<T: Real> Stages for Player<'_, T> {
    type Frame = ();
    fn setup(&self, _n: u32) -> Result<(), RasterError> {
        Ok(())
    }
    fn transform(&mut self, _frame: &()) {
        let camera = &self.camera;
        for p in self.objects.iter_mut().flatten() {
            match p.finish {
                Finish::Lit(_) => p.mesh.transform(camera, &p.transform),
                Finish::Emissive(_) => p.mesh.transform_unlit(camera, &p.transform),
            }
        }
    }
    fn shade(&mut self, _frame: &()) -> u32 {
        let camera = &self.camera;
        let mut calls = 0;
        for p in self.objects.iter_mut().flatten() {
            calls += match &p.finish {
                Finish::Lit(m) => p.mesh.shade(camera, &Lit::new(&self.lights, m), &p.options),
                Finish::Emissive(g) => p.mesh.shade(camera, g, &p.options),
            };
        }
        calls
    }
    fn draw_band(
        &self,
        _frame: &(),
        band: &mut Band<'_, Rgb565>,
        stats: &mut DrawStats,
    ) -> Result<(), RasterError> {
        let camera = &self.camera;
        for p in self.objects.iter().flatten() {
            let s = match &p.finish {
                Finish::Lit(m) => p.mesh.draw(
                    camera,
                    band,
                    &Lit::new(&self.lights, m),
                    &p.options,
                    self.table,
                )?,
                Finish::Emissive(g) => p.mesh.draw(camera, band, g, &p.options, self.table)?,
            };
            stats.triangles += s.triangles;
            stats.rasterized += s.rasterized;
            stats.shaded += s.shaded;
            stats.pixels += s.pixels;
        }
        Ok(())
    }
    fn height(&self) -> u16 {
        self.camera.height()
    }
    fn background(&self) -> Rgb565 {
        self.background
    }
}
