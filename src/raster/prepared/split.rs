//! Gouraud shading with [`SplitShader`]s: each vertex's fixed part kept from frame to frame
//! (see the [`split`](crate::raster::split) module docs).

use super::{PreparedMesh, KEPT, NEEDED};
use crate::raster::scan::colour_bits;
use crate::raster::shade::Shading;
use crate::raster::split::{LightSums, SplitShader};
use crate::raster::{Camera, DrawOptions, RasterError};
use crate::Real;

impl<'m, 's, T: Real> PreparedMesh<'m, 's, T> {
    /// This mesh with `sums` for each vertex's fixed part of a [`SplitShader`] (at least one
    /// entry per vertex, 24 bytes each with `f32` or `Fixed22`): then
    /// [`PreparedMesh::shade_split`] computes a vertex's fixed part only when it may have
    /// changed. Without them, `shade_split` computes both parts at every vertex.
    ///
    /// # Errors
    /// [`RasterError::BufferTooSmall`] (`"fixed sums"`).
    pub fn with_fixed_sums(mut self, sums: &'s mut [LightSums<T>]) -> Result<Self, RasterError> {
        let needed = self.verts.len();
        let got = sums.len();
        let sums = sums.get_mut(..needed).ok_or(RasterError::BufferTooSmall {
            what: "fixed sums",
            needed,
            got,
        })?;
        for v in self.verts.iter_mut() {
            v.flags &= !KEPT;
        }
        self.fixed_sums = sums;
        self.fixed_key = None;
        Ok(self)
    }

    /// [`PreparedMesh::shade`] with a [`SplitShader`]: the same colours as a
    /// [`Shader`](crate::raster::Shader) computing `shader.finish(shader.fixed_part(..), ..)` at every
    /// vertex, the fixed part taken from the mesh's fixed sums
    /// ([`PreparedMesh::with_fixed_sums`]) where it was computed for this vertex since its last
    /// transform (or [`PreparedMesh::set_screen`]), with this shader's
    /// [`SplitShader::fixed_version`] and `opts.two_sided`. Returns the number of vertices
    /// shaded.
    ///
    /// Cost: as [`PreparedMesh::shade`], less the fixed part's at each vertex that keeps it
    /// (the load of 6 values instead).
    pub fn shade_split<S: SplitShader<T> + ?Sized>(
        &mut self,
        camera: &Camera<T>,
        shader: &S,
        opts: &DrawOptions<T>,
    ) -> u32 {
        self.shade_split_some(camera, shader, opts, |_| true)
    }

    /// [`PreparedMesh::shade_split`] of only the vertices whose index `mine` accepts, as
    /// [`PreparedMesh::shade_some`] (for two cores: each core keeps the fixed parts of the
    /// vertices it shades).
    pub fn shade_split_some<S, W>(
        &mut self,
        camera: &Camera<T>,
        shader: &S,
        opts: &DrawOptions<T>,
        mine: W,
    ) -> u32
    where
        S: SplitShader<T> + ?Sized,
        W: Fn(usize) -> bool,
    {
        if opts.shading != Shading::Gouraud {
            // Per pixel, the drawing interpolates the normals: all of them now, once.
            self.settle_normals();
            return 0;
        }
        self.update_visible(camera, opts.cull);
        let key = Some((shader.fixed_version(), opts.two_sided));
        if self.fixed_key != key {
            for v in self.verts.iter_mut() {
                v.flags &= !KEPT;
            }
            self.fixed_key = key;
        }
        let mut calls = 0u32;
        let mut sums = self.fixed_sums.iter_mut();
        let src = self.mesh.vertices();
        for (i, v) in self.verts.iter_mut().enumerate() {
            // (The sums run beside the vertices: none when there are no fixed sums.)
            let kept = sums.next();
            if v.flags & NEEDED == 0 || !mine(i) {
                continue;
            }
            Self::settle_normal(v, src.get(i), &self.normals);
            let (n, view) = Self::shading_frame(camera, v, opts.two_sided);
            let col = match kept {
                Some(k) => {
                    if v.flags & KEPT == 0 {
                        *k = shader.fixed_part(v.p, n, view);
                        v.flags |= KEPT;
                    }
                    shader.finish(k, v.p, n, view)
                }
                None => shader.finish(&shader.fixed_part(v.p, n, view), v.p, n, view),
            };
            v.colour = colour_bits(col.finite_or_zero(), opts.exposure);
            calls = calls.wrapping_add(1);
        }
        calls
    }
}

#[cfg(all(test, feature = "cap", feature = "polygon", feature = "phong"))]
mod tests {
    use super::{LightSums, PreparedMesh, SplitShader, NEEDED};
    use crate::raster::split::SplitLit;
    use crate::raster::{
        mesh, Affine, Camera, Cull, DrawOptions, Lit, Material, Mesh, PreparedVertex, Projection,
        Shader, Shading, Vertex,
    };
    use crate::{Ambient, PolygonLight, Real, Rgb, Scene, SceneLight, SphereLight, UnitVec3, Vec3};
    use core::cell::Cell;

    /// A [`SplitLit`] that counts its fixed parts.
    struct Counting<'a, T: Real>(SplitLit<'a, T, 3, 4>, &'a Cell<u32>);

    impl<T: Real> SplitShader<T> for Counting<'_, T> {
        fn fixed_version(&self) -> u32 {
            self.0.fixed_version()
        }
        fn fixed_part(&self, p: Vec3<T>, n: UnitVec3<T>, v: UnitVec3<T>) -> LightSums<T> {
            self.1.set(self.1.get() + 1);
            self.0.fixed_part(p, n, v)
        }
        fn finish(&self, k: &LightSums<T>, p: Vec3<T>, n: UnitVec3<T>, v: UnitVec3<T>) -> Rgb<T> {
            self.0.finish(k, p, n, v)
        }
    }

    fn v3<T: Real>(x: f64, y: f64, z: f64) -> Vec3<T> {
        Vec3::new(T::from_f64(x), T::from_f64(y), T::from_f64(z))
    }

    /// A panel overhead (fixed, moved at `panel_dy`), an orbiting lamp (at `phase`) and an
    /// ambient term, in that order.
    fn scene<T: Real>(panel_dy: f64, phase: f64) -> Scene<T, 3, 4> {
        let y = 1.9 + panel_dy;
        let panel = PolygonLight::new(&[
            v3(-1.0, y, -1.0),
            v3(1.0, y, -1.0),
            v3(1.0, y, 0.4),
            v3(-1.0, y, 0.4),
        ])
        .unwrap();
        let (s, c) = phase.sin_cos();
        let lamp = SphereLight::new(v3(1.3 * s, 0.75, 1.3 * c), T::from_f64(0.15)).unwrap();
        let mut scene = Scene::new();
        scene
            .push(SceneLight::Polygon(panel), Rgb::from_f64([2.6, 2.7, 3.0]))
            .unwrap();
        scene
            .push(SceneLight::Sphere(lamp), Rgb::from_f64([14.0, 11.2, 7.7]))
            .unwrap();
        let ambient = Ambient(Rgb::from_f64([0.03, 0.035, 0.05]));
        scene
            .push(SceneLight::Ambient(ambient), Rgb::splat(T::ONE))
            .unwrap();
        scene
    }

    /// Frame by frame (the lamp moving; the mesh moved, the panel changed with a new
    /// version, the shading made two-sided, screen data taken from another mesh, at some
    /// frames), a mesh that keeps its fixed sums shades every visible vertex with the colours
    /// of [`Lit`] over the whole scene on a fresh mesh, bit for bit, and computes the fixed
    /// parts only where they changed.
    fn split_shading_is_lit_shading<T: Real>() {
        let zero = Vec3::new(T::ZERO, T::ZERO, T::ZERO);
        let mut verts = [Vertex::new(zero, zero); 17 * 9];
        let mut tris = [[0u16; 3]; 2 * 16 * 7];
        let counts = mesh::uv_sphere(T::from_f64(0.6), 8, 16, &mut verts, &mut tris).unwrap();
        let sphere = Mesh::new(&verts[..counts.vertices], &tris[..counts.triangles]).unwrap();
        let camera = Camera::new(
            v3(0.0, 0.8, 3.3),
            v3(0.0, 0.05, 0.0),
            v3(0.0, 1.0, 0.0),
            Projection::Perspective {
                fov_y: T::from_f64(0.8),
            },
            96,
            96,
        )
        .unwrap();
        let plastic =
            Material::new(Rgb::from_f64([0.8, 0.3, 0.2]), Rgb::from_f64([0.5; 3]), 20).unwrap();
        let matte = Material::matte(Rgb::from_f64([0.3, 0.7, 0.6])).unwrap();
        let mut storage = [PreparedVertex::EMPTY; 17 * 9];
        let mut sums = [LightSums::ZERO; 17 * 9];
        let mut kept = PreparedMesh::new(sphere, &mut storage)
            .unwrap()
            .with_fixed_sums(&mut sums)
            .unwrap();
        let mut other_storage = [PreparedVertex::EMPTY; 17 * 9];
        let mut other = PreparedMesh::new(sphere, &mut other_storage).unwrap();
        let at = |dx: f64| Affine::translation(v3(dx, 0.0, 0.0)).unwrap();
        let visible = counts.vertices as u32 / 3;
        // (frame, the mesh's offset if transformed, the panel's offset and version, the
        // material, two-sided, whether the screen data come from `other`, the fixed parts
        // computed: all visible ones or none.)
        let steps = [
            (0, Some(0.0), 0.0, 0, &plastic, false, false, true),
            (1, None, 0.0, 0, &plastic, false, false, false),
            (2, None, 0.0, 0, &plastic, false, false, false),
            (3, Some(0.3), 0.0, 0, &plastic, false, false, true),
            (4, None, 0.0, 0, &plastic, false, false, false),
            (5, None, 0.2, 1, &plastic, false, false, true),
            (6, None, 0.2, 1, &plastic, false, false, false),
            (7, None, 0.2, 1, &plastic, true, false, true),
            (8, None, 0.2, 2, &matte, true, false, true),
            (9, None, 0.2, 2, &matte, true, false, false),
            (10, None, 0.2, 2, &matte, true, true, true),
            (11, None, 0.2, 2, &matte, true, false, false),
        ];
        let mut offset = 0.0;
        for (frame, moved, panel_dy, version, material, two_sided, exchanged, computes) in steps {
            let lights = scene::<T>(panel_dy, 0.4 * frame as f64);
            let mut opts = DrawOptions::new(Shading::Gouraud);
            opts.cull = if two_sided { Cull::None } else { Cull::Back };
            opts.two_sided = two_sided;
            if let Some(dx) = moved {
                offset = dx;
                kept.transform(&camera, &at(offset));
            }
            if exchanged {
                other.transform(&camera, &at(offset));
                kept.set_screen(&camera, other.screen(), |i| i % 2 == 0);
            }
            let fixed_parts = Cell::new(0);
            let split = Counting(SplitLit::new(&lights, material, 1, version), &fixed_parts);
            let calls = kept.shade_split(&camera, &split, &opts);
            let mut fresh_storage = [PreparedVertex::EMPTY; 17 * 9];
            let mut fresh = PreparedMesh::new(sphere, &mut fresh_storage).unwrap();
            fresh.transform(&camera, &at(offset));
            let lit = Lit::new(&lights, material);
            assert_eq!(calls, fresh.shade(&camera, &lit, &opts), "frame {frame}");
            assert!(calls > visible, "frame {frame}: {calls}");
            let mut compared = 0;
            for (a, b) in kept.verts.iter().zip(fresh.verts.iter()) {
                if b.flags & NEEDED != 0 {
                    assert_eq!(a.colour, b.colour, "frame {frame}");
                    assert_ne!(a.colour, [0; 3], "frame {frame}");
                    compared += 1;
                    // Both parts at once (`Shader`, for per-pixel shading): `Lit`'s colour.
                    let (n, view) = PreparedMesh::shading_frame(&camera, b, two_sided);
                    let plain = SplitLit::new(&lights, material, 1, version);
                    let want = lit.shade(b.p, n, view);
                    assert_eq!(plain.shade(b.p, n, view), want, "frame {frame}");
                }
            }
            assert_eq!(compared, calls, "frame {frame}");
            let want = match (computes, exchanged) {
                (true, false) => calls,
                // The vertices whose screen data came from `other`: every other one.
                (true, true) => kept
                    .verts
                    .iter()
                    .enumerate()
                    .filter(|(i, v)| i % 2 == 0 && v.flags & NEEDED != 0)
                    .count() as u32,
                (false, _) => 0,
            };
            assert_eq!(fixed_parts.get(), want, "frame {frame}");
        }
        // Without fixed sums: both parts at every vertex, the same colours, however many of
        // the lights are fixed (none to more than all).
        let lights = scene::<T>(0.0, 1.0);
        let opts = DrawOptions::new(Shading::Gouraud);
        let mut a_storage = [PreparedVertex::EMPTY; 17 * 9];
        let mut b_storage = [PreparedVertex::EMPTY; 17 * 9];
        let mut a = PreparedMesh::new(sphere, &mut a_storage).unwrap();
        let mut b = PreparedMesh::new(sphere, &mut b_storage).unwrap();
        for fixed in [0, 1, 2, 3, 9, usize::MAX] {
            a.transform(&camera, &at(0.0));
            b.transform(&camera, &at(0.0));
            let fixed_parts = Cell::new(0);
            let split = Counting(SplitLit::new(&lights, &plastic, fixed, 0), &fixed_parts);
            let calls = a.shade_split(&camera, &split, &opts);
            assert_eq!(calls, b.shade(&camera, &Lit::new(&lights, &plastic), &opts));
            assert_eq!(fixed_parts.get(), calls);
            assert!(a.colours().eq(b.colours()));
        }
    }

    #[test]
    fn split_shading_is_lit_shading_f64() {
        split_shading_is_lit_shading::<f64>();
    }

    #[test]
    fn split_shading_is_lit_shading_f32() {
        split_shading_is_lit_shading::<f32>();
    }

    #[cfg(feature = "fixed")]
    #[test]
    fn split_shading_is_lit_shading_fixed22() {
        split_shading_is_lit_shading::<crate::Fixed22>();
    }
}
