//! The generic draw path ([`draw`]): every triangle transformed, clipped, set up and filled
//! per band, with per-pixel or Gouraud shading; and [`render_in_bands`].

use super::clip::{clip_polygon, ClipVert, MAX_CLIPPED};
use super::*;

/// A vertex normal as the renderer stores it (normalized after the transform, or zero where
/// the transformed normal has no direction, or the mesh has none) as the unit normal the
/// shader gets: the normal itself, or for a zero normal the view direction (the surface faces
/// the viewer). Cost: one comparison; no normalization.
#[inline(always)]
pub(super) fn unit_or_view<T: Real>(n: Vec3<T>, view: UnitVec3<T>) -> UnitVec3<T> {
    if n.x == T::ZERO && n.y == T::ZERO && n.z == T::ZERO {
        view
    } else {
        // Nonzero: the result of a normalization (`transform.normal(..).normalize()`).
        UnitVec3::new_unchecked(n)
    }
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
            let ys: [i32; 3] = core::array::from_fn(|k| camera.screen_fixed(&cv[k].c).0.y);
            let (lo, hi) = (ys[0].min(ys[1]).min(ys[2]), ys[0].max(ys[1]).max(ys[2]));
            if hi < (row0 - 1) * SUBPIXEL || lo > (row1 + 1) * SUBPIXEL {
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
                    fp[k] = camera.screen_fixed(&cv[k].c).0;
                }
                if EdgeTriangle::new(fp, opts.cull).is_none() {
                    continue;
                }
            }
            for v in cv.iter_mut() {
                let view = camera.view_dir(v.p);
                let n = unit_or_view(v.n, view);
                let n = if opts.two_sided && n.dot(*view) < T::ZERO {
                    -n
                } else {
                    n
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
pub(super) fn raster_triangle<T, P, S>(
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
        let (p, w, finite) = camera.screen_fixed(&c);
        if !finite {
            return;
        }
        fp[k] = p;
        iw[k] = w;
    }
    let Some(tri) = EdgeTriangle::new(fp, opts.cull) else {
        return;
    };
    let Some(bounds) = tri.pixel_bounds(camera.width as i32, row0, row1) else {
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
    // Barycentric weights: exact (from the integer edge functions, through f64) at the first
    // covered pixel of each row, then stepped by a per-triangle increment along the row, so a
    // pixel costs 3 additions in `T` instead of 3 double-precision products (soft-float on
    // Cortex-M0 and M4F). Every row starts afresh, so a band renders exactly its rows of the
    // full frame; the drift along a row is at most its length times the rounding of the step
    // (f32: 240 x 6e-8 relative; Fixed22: 240 x 2^-22).
    let mut row: Option<(i32, i32, [i64; 3], [T; 3])> = None;
    let mut dl: Option<[T; 3]> = None;
    tri.for_each_covered_in(bounds, |x, y, e| {
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
                    .to_unit()
                    .unwrap_or(view);
                let n = if opts.two_sided && n.dot(*view) < T::ZERO {
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
