//! Drawing a [`PreparedMesh`] into a band: its triangles by the integer scan loop of
//! [`scan`](crate::raster::scan), those that cross a clip plane clipped first.

use super::{corners, faces, project, PreparedMesh, PreparedVertex, NORMAL_DUE};
use crate::raster::edge::SUBPIXEL;
use crate::raster::scan::{colour_bits, raster, Context, COLOUR_FRAC};
use crate::raster::shade::{Shader, Shading};
use crate::raster::target::{Band, EncodeTable, PixelFormat};
use crate::raster::{
    clip_polygon, Camera, ClipVert, DrawOptions, DrawStats, RasterError, MAX_CLIPPED,
};
use crate::{Real, Rgb};

impl<T: Real> PreparedMesh<'_, '_, T> {
    /// Draws the mesh into `band` with this frame's vertices: Gouraud with the colours of
    /// [`PreparedMesh::shade`], or per pixel with `shader` (`opts.shading`); colours encoded
    /// through `table` (`opts.encoding` is not used: the table's encoding is). Depth-tested if
    /// the band has a depth band (see the module docs for the depth value).
    ///
    /// Accuracy: the same pixels as [`draw`](crate::raster::draw) (the same snapped vertices and fill
    /// rule); colours as described in the module docs. Cost: see the module docs.
    ///
    /// # Errors
    /// [`RasterError::BadSize`] (`"band width"`) when the band is not as wide as the camera's
    /// viewport; [`RasterError::Model`] with [`crate::Error::OutOfRange`] (`"vertex"`) when
    /// [`PreparedMesh::transform`] put a vertex beyond [`Real::COORDINATE_LIMIT`] (fixed point
    /// only; nothing is drawn).
    pub fn draw<P, S>(
        &self,
        camera: &Camera<T>,
        band: &mut Band<'_, P>,
        shader: &S,
        opts: &DrawOptions<T>,
        table: &EncodeTable<P>,
    ) -> Result<DrawStats, RasterError>
    where
        P: PixelFormat,
        S: Shader<T> + ?Sized,
    {
        if band.width() != camera.width {
            return Err(RasterError::BadSize("band width"));
        }
        if self.out_of_range {
            return Err(crate::Error::OutOfRange("vertex").into());
        }
        let mut stats = DrawStats {
            triangles: self.mesh.triangles().len() as u32,
            ..DrawStats::default()
        };
        let row0 = band.y0() as i32;
        let row1 = (band.y0() as i32 + band.rows() as i32).min(camera.height as i32);
        if row0 >= row1 || self.rows.1 <= row0 || self.rows.0 >= row1 {
            return Ok(stats);
        }
        // Sub-pixel rows of the band's first and last pixel centres.
        let (sy0, sy1) = (row0 * SUBPIXEL, row1 * SUBPIXEL);
        let ctx = Context {
            camera,
            shader,
            opts,
            table,
            row0,
            row1,
        };
        let tris = self.mesh.triangles();
        if self.rows_cull == Some(opts.cull) {
            for (tri, r) in tris.iter().zip(self.tri_rows.iter()) {
                if r.misses(row0, row1) {
                    continue;
                }
                // Its row and culling tests passed: `None` skips them.
                self.draw_triangle(&ctx, band, tri, None, &mut stats);
            }
        } else {
            for tri in tris {
                self.draw_triangle(&ctx, band, tri, Some((sy0, sy1)), &mut stats);
            }
        }
        Ok(stats)
    }

    /// One triangle of [`PreparedMesh::draw`]. `sy`: the sub-pixel rows of the band's first
    /// and last pixel centres for the row and culling tests of an unclipped triangle, or
    /// `None` when its [`TriangleRows`] has passed them.
    #[inline(always)]
    fn draw_triangle<P, S>(
        &self,
        ctx: &Context<'_, T, S, P>,
        band: &mut Band<'_, P>,
        tri: &[u16; 3],
        sy: Option<(i32, i32)>,
        stats: &mut DrawStats,
    ) where
        P: PixelFormat,
        S: Shader<T> + ?Sized,
    {
        let Some([a, b, c]) = corners(self.verts, tri) else {
            return;
        };
        if a.outside & b.outside & c.outside != 0 {
            return;
        }
        // Per pixel without a shade since the transform (which computes the normals first,
        // in fixed point): this triangle's normals computed here, the same bits. (One call
        // of the rest below: a second would copy the per-pixel loop, 33 KiB on the M0.)
        let settled: [PreparedVertex<T>; 3];
        let [a, b, c] = if Self::defers_normals()
            && ctx.opts.shading == Shading::PerPixel
            && (a.flags | b.flags | c.flags) & NORMAL_DUE != 0
        {
            settled = self.settled_corners(tri, [a, b, c]);
            [&settled[0], &settled[1], &settled[2]]
        } else {
            [a, b, c]
        };
        if (a.outside | b.outside | c.outside) == 0 {
            if let Some((sy0, sy1)) = sy {
                let lo = a.fp.y.min(b.fp.y).min(c.fp.y);
                let hi = a.fp.y.max(b.fp.y).max(c.fp.y);
                if hi < sy0 || lo > sy1 || !faces(&[a.fp, b.fp, c.fp], ctx.opts.cull) {
                    return;
                }
            }
            raster(ctx, band, [a, b, c], stats);
        } else {
            self.draw_clipped(ctx, band, [a, b, c], stats);
        }
    }

    /// Copies of a triangle's vertices `v` (of indices `tri`) with their normals computed:
    /// [`PreparedMesh::draw_triangle`]'s rare case, out of line so that the drawing's code
    /// stays as it was (inline, the RP2040 firmware's flash grew by 34 KiB).
    #[cold]
    #[inline(never)]
    fn settled_corners(
        &self,
        tri: &[u16; 3],
        v: [&PreparedVertex<T>; 3],
    ) -> [PreparedVertex<T>; 3] {
        let src = self.mesh.vertices();
        core::array::from_fn(|k| {
            let mut s = *v[k];
            let i = tri.get(k).map_or(usize::MAX, |&i| usize::from(i));
            Self::settle_normal(&mut s, src.get(i), &self.normals);
            s
        })
    }

    /// A triangle that crosses a clip plane: clipped as [`draw`](crate::raster::draw) clips, its fan
    /// drawn by the same integer loop.
    fn draw_clipped<P, S>(
        &self,
        ctx: &Context<'_, T, S, P>,
        band: &mut Band<'_, P>,
        v: [&PreparedVertex<T>; 3],
        stats: &mut DrawStats,
    ) where
        P: PixelFormat,
        S: Shader<T> + ?Sized,
    {
        let camera = ctx.camera;
        let cv = v.map(|v| ClipVert {
            // The clip coordinates again (rare: only clipped triangles need them; `p` within
            // the coordinate limit, as `transform` checked it or left the origin).
            c: camera.clip_within(v.p),
            p: v.p,
            n: v.n,
            col: Rgb::new(
                T::from_fixed_i32(v.colour[0], COLOUR_FRAC),
                T::from_fixed_i32(v.colour[1], COLOUR_FRAC),
                T::from_fixed_i32(v.colour[2], COLOUR_FRAC),
            ),
        });
        let mut poly = [cv[0]; MAX_CLIPPED];
        let count = clip_polygon(cv, camera.near, camera.far, &mut poly);
        let range = camera.far - camera.near;
        let (a, b, inv_range) = (
            camera.far / range,
            camera.far * camera.near / range,
            T::ONE / range,
        );
        let mut sv = [PreparedVertex::<T>::EMPTY; MAX_CLIPPED];
        for (s, cv) in sv.iter_mut().zip(&poly[..count]) {
            if !(cv.c[3] > T::ZERO) {
                return;
            }
            let (fp, depth, iw) = project(camera, &cv.c, a, b, inv_range);
            *s = PreparedVertex {
                fp,
                depth,
                colour: colour_bits(cv.col, T::ONE),
                p: cv.p,
                n: cv.n,
                iw,
                ..PreparedVertex::EMPTY
            };
        }
        for i in 1..count.saturating_sub(1) {
            raster(ctx, band, [&sv[0], &sv[i], &sv[i + 1]], stats);
        }
    }
}
