//! Scan conversion of [`PreparedMesh`](super::PreparedMesh)'s triangles: the per-triangle
//! setup (the edge functions, then every attribute as an integer plane over pixels) and the
//! span loops of Gouraud and per-pixel shading (see the [`prepared`](super::prepared) module
//! docs for what is computed and what it costs).

use super::edge::{EdgeTriangle, FixedPoint, SUBPIXEL};
use super::gouraud::{is_guarded, Spans, GUARDED_SPANS};
use super::prepared::PreparedVertex;
use super::shade::{Shader, Shading};
use super::target::{Band, EncodeTable, PixelFormat, ENCODE_INDEX_BITS};
use super::{Camera, DrawOptions, DrawStats};
use crate::wide::{dot2_shr24, mul_64, mul_hi_full, recip_core};
use crate::{Real, Rgb, Vec3};

/// Fraction bits of interpolated colours (linear, times the exposure): 1.0 is `1 << 24`.
pub(super) const COLOUR_FRAC: u32 = 24;
/// The largest interpolated colour, in those units (127.99: an `i32` with 24 fraction bits).
const COLOUR_MAX: i32 = i32::MAX;
/// Fraction bits of the depth value `q` in [0, 1] (a 16-bit depth is `q` with 16 bits).
pub(super) const DEPTH_FRAC: u32 = 28;
/// Fraction bits of the barycentric weights of per-pixel shading.
const BARY_FRAC: u32 = 24;

/// A linear colour times `exposure` as integers with [`COLOUR_FRAC`] fraction bits, clamped
/// to `[0, COLOUR_MAX]`.
#[inline]
pub(super) fn colour_bits<T: Real>(c: Rgb<T>, exposure: T) -> [i32; 3] {
    // (The channels times the exposure, `*`'s bits; fixed point without saturation tests
    // where the colour or the exposure lies within (-1, 1].)
    T::mul_each([c.r, c.g, c.b], [exposure; 3])
        .map(|x| x.to_fixed_i32(COLOUR_FRAC).clamp(0, COLOUR_MAX))
}

/// The draw call's fixed inputs.
pub(super) struct Context<'a, T, S: ?Sized, P: PixelFormat> {
    pub(super) camera: &'a Camera<T>,
    pub(super) shader: &'a S,
    pub(super) opts: &'a DrawOptions<T>,
    pub(super) table: &'a EncodeTable<P>,
    pub(super) row0: i32,
    pub(super) row1: i32,
}

/// An attribute plane over pixels: `value(x, y) = base + x sx + (y - yb) sy` in wrapping
/// `i32` arithmetic (exact wherever the value itself fits, which it does inside the
/// triangle).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Plane {
    pub(super) base: i32,
    pub(super) sx: i32,
    pub(super) sy: i32,
}

impl Plane {
    /// The plane through the values `a` at the three vertices (edge-triangle order):
    /// `a0 + (a1 - a0) l1 + (a2 - a0) l2` with the triangle's barycentric planes. Cost: 3
    /// sums of two 32 x 32 -> 64-bit products shifted ([`dot2_shr24`]) when the differences
    /// and the weights fit an `i32` (always on a display; 6 [`mul_64`] otherwise, the same
    /// bits).
    #[inline(always)]
    pub(super) fn new(a: [i32; 3], geo: &Geometry) -> Self {
        let (da1, o1) = a[1].overflowing_sub(a[0]);
        let (da2, o2) = a[2].overflowing_sub(a[0]);
        let (sx, at_b, sy) = match geo.l32 {
            Some((l1, l2)) if !o1 && !o2 => (
                dot2_shr24(da1, l1[0], da2, l2[0]),
                dot2_shr24(da1, l1[2], da2, l2[2]),
                dot2_shr24(da1, l1[1], da2, l2[1]),
            ),
            _ => {
                let (da1, da2) = (a[1] as i64 - a[0] as i64, a[2] as i64 - a[0] as i64);
                let mix = |l1: i64, l2: i64| {
                    (mul_64(da1, l1).wrapping_add(mul_64(da2, l2)) >> BARY_FRAC) as i32
                };
                (
                    mix(geo.l1.0, geo.l2.0),
                    mix(geo.l1.2, geo.l2.2),
                    mix(geo.l1.1, geo.l2.1),
                )
            }
        };
        let at_b = a[0].wrapping_add(at_b);
        Plane {
            base: at_b.wrapping_sub(sx.wrapping_mul(geo.xb)),
            sx,
            sy,
        }
    }
    /// The value at column 0 of the row `dy` rows below the anchor row.
    #[inline(always)]
    pub(super) fn row(&self, dy: i32) -> i32 {
        self.base.wrapping_add(dy.wrapping_mul(self.sy))
    }
}

/// A triangle's barycentric planes: the weights `l1`, `l2` of vertices 1 and 2 (vertex 0 has
/// `1 - l1 - l2`) with [`BARY_FRAC`] fraction bits, as `(per pixel in x, per pixel in y, at
/// the anchor)`, the anchor being the centre of the triangle's top-left bounding-box pixel
/// (`xb`, `yb`).
pub(super) struct Geometry {
    l1: (i64, i64, i64),
    l2: (i64, i64, i64),
    /// `l1` and `l2` as `[x, y, anchor]` in `i32` when all six fit (any triangle of display
    /// size).
    pub(super) l32: Option<([i32; 3], [i32; 3])>,
    xb: i32,
}

impl Geometry {
    /// From the snapped vertices (positive orientation), twice the area `d > 0` and the
    /// anchor pixel. `1/d` is one division (a 31-bit reciprocal `r` with `1/d = r 2^-k` to
    /// 2^-30 relative: `recip62`, the crate's reciprocal core and one exact correction, when
    /// `d < 2^32`; a 64-bit division beyond), every weight a product and a shift: `dl1/dX = f2/d`, `dl1/dY =
    /// -e2/d`, `dl2/dX = -f1/d`, `dl2/dY = e1/d` per sub-pixel (16 per pixel), with `(e, f)`
    /// the vertices' offsets from vertex 0; at the anchor `l = dl/dX dx + dl/dY dy` (vertex 0
    /// has `l1 = l2 = 0`).
    pub(super) fn new(fp: [FixedPoint; 3], d: i64, xb: i32, yb: i32) -> Self {
        Self::new_small(fp, d, xb, yb).unwrap_or_else(|| Self::new_wide(fp, d, xb, yb))
    }

    /// [`Geometry::new`] in 32-bit integers (no 64-bit shift or library call on a Cortex-M0)
    /// for a triangle whose vertex offsets are under 2^15 sub-pixels (any of display size):
    /// the same values, or `None` when one does not fit an `i32` (then
    /// [`Geometry::new_wide`]). With `d < 2^31` and `r = rh 2^16 + rl`, each weight `floor(x
    /// r / 2^s)` is put together from `x rh` and `x rl` (both fit an `i32`).
    fn new_small(fp: [FixedPoint; 3], d: i64, xb: i32, yb: i32) -> Option<Self> {
        // Coordinates within MAX_COORD: the differences fit an i32.
        let off = |k: usize| (fp[k].x.wrapping_sub(fp[0].x), fp[k].y.wrapping_sub(fp[0].y));
        let ((e1, f1), (e2, f2)) = (off(1), off(2));
        if [e1, f1, e2, f2].iter().any(|c| c.unsigned_abs() >= 1 << 15) {
            return None;
        }
        // `d = |e1 f2 - e2 f1| < 2^31`, in `[2^(n-1), 2^n)`; `r = 2^(n + 30) / d`, in `(2^30,
        // 2^31]`. Per pixel with BARY_FRAC bits: `floor(x r / 2^s)`, `s = n + 30 - 4 -
        // BARY_FRAC`.
        let d = u32::try_from(d).ok().filter(|&d| d > 0)?;
        let n = 32 - d.leading_zeros();
        let r = recip62(d << (32 - n));
        let s = n + 26 - BARY_FRAC;
        let (rh, rl) = ((r >> 16) as i32, (r & 0xFFFF) as i32); // rh <= 2^15
        let scale = |x: i32| {
            // |x| < 2^15: |x rh| < 2^30, |x rl| < 2^31.
            let (a, b) = (x * rh, x * rl);
            if s >= 16 {
                Some((a + (b >> 16)) >> (s - 16))
            } else {
                // a 2^(16 - s) and floor(b / 2^s) have the sign of x: an overflow of the
                // first (the shift does not come back) means the sum does not fit either.
                let up = a << (16 - s);
                if up >> (16 - s) != a {
                    return None;
                }
                up.checked_add(b >> s)
            }
        };
        let dx = xb * SUBPIXEL + SUBPIXEL / 2 - fp[0].x;
        let dy = yb * SUBPIXEL + SUBPIXEL / 2 - fp[0].y;
        // `floor((gx dx + gy dy) / 16)` if it fits an i32. The anchor lies less than a pixel
        // right of (below) the leftmost (topmost) vertex, so `-2^15 < dx, dy < 16`: with
        // `g = gh 2^16 + gl`, `gh dx + gh' dy` fits an i32 (each below 2^30), and so does
        // each `gl dx` (below 2^31); the sum is `h 2^16 + l1 + l2` and its floor by 16 is
        // `h 2^12 + floor(l1 / 16) + floor(l2 / 16) + carry`, no 64-bit product or sum (the
        // same values: `the_32_bit_geometry_equals_the_64_bit_one`).
        let anchor = |gx: i32, gy: i32| {
            let h = (gx >> 16) * dx + (gy >> 16) * dy;
            let (l1, l2) = ((gx & 0xFFFF) * dx, (gy & 0xFFFF) * dy);
            let low = (l1 >> 4) + (l2 >> 4) + (((l1 & 15) + (l2 & 15)) >> 4);
            let high = h << 12;
            if high >> 12 == h {
                high.checked_add(low)
            } else {
                // `h 2^12` beyond an i32, the sum perhaps not (rare: exactly, in an i64).
                i32::try_from((i64::from(h) << 12) + i64::from(low)).ok()
            }
        };
        let (g1x, g1y) = (scale(f2)?, scale(-e2)?);
        let (g2x, g2y) = (scale(-f1)?, scale(e1)?);
        let l1 = [g1x, g1y, anchor(g1x, g1y)?];
        let l2 = [g2x, g2y, anchor(g2x, g2y)?];
        let wide = |l: [i32; 3]| (l[0] as i64, l[1] as i64, l[2] as i64);
        Some(Geometry {
            l1: wide(l1),
            l2: wide(l2),
            l32: Some((l1, l2)),
            xb,
        })
    }

    /// [`Geometry::new`] in 64-bit integers (any triangle within `MAX_COORD`).
    fn new_wide(fp: [FixedPoint; 3], d: i64, xb: i32, yb: i32) -> Self {
        let off = |k: usize| {
            (
                fp[k].x as i64 - fp[0].x as i64,
                fp[k].y as i64 - fp[0].y as i64,
            )
        };
        let ((e1, f1), (e2, f2)) = (off(1), off(2));
        let d = d.max(1) as u64;
        let n = 64 - d.leading_zeros(); // d in [2^(n-1), 2^n)
        let r = if n <= 32 {
            // 2^(n + 30) / d = 2^62 / (d 2^(32 - n)): 32-bit steps (any triangle of display
            // size; the 64-bit division is a library call on a Cortex-M0).
            recip62((d as u32) << (32 - n)) as i64
        } else {
            let sh = n.saturating_sub(33);
            let nn = n - sh; // <= 33
            ((1u64 << (nn + 30)) / (d >> sh)) as i64 // in (2^29, 2^31]
        };
        // 1/d = r 2^-(n + 30); per pixel (16 sub-pixels) with BARY_FRAC bits: x r 2^(4 +
        // BARY_FRAC - n - 30).
        let k = n + 30;
        let scale = |x: i64| {
            let p = mul_64(x, r);
            let up = 4 + BARY_FRAC;
            if k >= up {
                p >> (k - up)
            } else {
                p.wrapping_shl(up - k)
            }
        };
        // The anchor's offset from vertex 0, in sub-pixels (the weights are per pixel: / 16).
        let dx = (xb * SUBPIXEL + SUBPIXEL / 2 - fp[0].x) as i64;
        let dy = (yb * SUBPIXEL + SUBPIXEL / 2 - fp[0].y) as i64;
        let plane = |gx: i64, gy: i64| (gx, gy, (mul_64(gx, dx).wrapping_add(mul_64(gy, dy))) >> 4);
        let (l1, l2) = (plane(scale(f2), scale(-e2)), plane(scale(-f1), scale(e1)));
        let narrow = |l: (i64, i64, i64)| {
            Some([
                i32::try_from(l.0).ok()?,
                i32::try_from(l.1).ok()?,
                i32::try_from(l.2).ok()?,
            ])
        };
        Geometry {
            l1,
            l2,
            l32: narrow(l1).zip(narrow(l2)),
            xb,
        }
    }
}

/// `floor(2^62 / d)` for `d` in `[2^31, 2^32)` (in `(2^30, 2^31]`), exactly: half of
/// [`recip_core`]'s `2^63 / d` (a table start and one Newton step, up to 3 units below the
/// floor), corrected by the remainder `2^62 - q d` (one full product, at most two
/// subtractions). No division instruction or call, about a third of the 31 restoring steps
/// it replaces on a Cortex-M0.
fn recip62(d: u32) -> u32 {
    // y = floor(2^63 / d) - k, k in [0, 3]: q = floor(y / 2) is Q = floor(2^62 / d) or up to 2
    // below it, and the remainder 2^62 - q d (in [0, 3 d), below 2^34) corrects it.
    let mut q = recip_core(d) >> 1;
    let qd = (u64::from(mul_hi_full(q, d)) << 32) | u64::from(q.wrapping_mul(d));
    let mut r = (1u64 << 62).wrapping_sub(qd);
    let d64 = u64::from(d);
    while r >= d64 {
        r -= d64;
        q += 1;
    }
    q
}

/// Scan-converts one triangle into the band (see the [`prepared`](super::prepared) module docs).
pub(super) fn raster<T, P, S>(
    ctx: &Context<'_, T, S, P>,
    band: &mut Band<'_, P>,
    v: [&PreparedVertex<T>; 3],
    stats: &mut DrawStats,
) where
    T: Real,
    P: PixelFormat,
    S: Shader<T> + ?Sized,
{
    let opts = ctx.opts;
    let Some(tri) = EdgeTriangle::new([v[0].fp, v[1].fp, v[2].fp], opts.cull) else {
        return;
    };
    let v = if tri.swapped() { [v[0], v[2], v[1]] } else { v };
    let width = ctx.camera.width as i32;
    let (row0, row1) = (ctx.row0, ctx.row1);
    // No pixel centre of the band within the triangle's box: no setup (20 of the RP2040
    // demo's 527 a frame, one core). The box is the one the span walk needs: computed once
    // (rp2040js frames 1 to 15, 8 631 895 -> 8 609 126 cycles one core, 4 858 028 ->
    // 4 834 540 two cores, when the walk stopped computing it again).
    let Some(bounds) = tri.pixel_bounds(width, row0, row1) else {
        return;
    };
    stats.rasterized = stats.rasterized.wrapping_add(1);
    let fp = tri.vertices();
    let (xb, yb) = anchor_pixel(&fp);
    let geo = Geometry::new(fp, tri.area2(), xb, yb);
    let depth = Plane::new([v[0].depth, v[1].depth, v[2].depth], &geo);
    match opts.shading {
        Shading::Gouraud => {
            let mut planes: [Plane; 3] = core::array::from_fn(|k| {
                Plane::new([v[0].colour[k], v[1].colour[k], v[2].colour[k]], &geo)
            });
            let guarded =
                GUARDED_SPANS && is_guarded(&fp, &geo, [&v[0].colour, &v[1].colour, &v[2].colour]);
            let spans = Spans {
                depth,
                yb,
                table: ctx.table,
            };
            if guarded {
                for p in &mut planes {
                    *p = p.guarded();
                }
                spans.gouraud::<true>(&tri, bounds, &planes, band, stats);
            } else {
                spans.gouraud::<false>(&tri, bounds, &planes, band, stats);
            }
        }
        Shading::PerPixel => {
            let one = 1i32 << BARY_FRAC;
            let l1 = Plane::new([0, one, 0], &geo);
            let l2 = Plane::new([0, 0, one], &geo);
            let iw = [v[0].iw, v[1].iw, v[2].iw];
            let pw: [Vec3<T>; 3] = core::array::from_fn(|k| v[k].p * iw[k]);
            let nw: [Vec3<T>; 3] = core::array::from_fn(|k| v[k].n * iw[k]);
            let camera = ctx.camera;
            tri.for_each_span_in(bounds, |y, xs, xe| {
                let dy = y - yb;
                let (d0, a0, b0) = (depth.row(dy), l1.row(dy), l2.row(dy));
                for x in xs..=xe {
                    let z = depth16(d0.wrapping_add(x.wrapping_mul(depth.sx)));
                    let Some((px, dp)) = band.row_mut(y as u16) else {
                        return;
                    };
                    if let Some(d) = dp.and_then(|d| d.get_mut(x as usize)) {
                        if z >= *d {
                            continue;
                        }
                        *d = z;
                    }
                    let w1 = a0.wrapping_add(x.wrapping_mul(l1.sx)).clamp(0, one);
                    let w2 = b0.wrapping_add(x.wrapping_mul(l2.sx)).clamp(0, one);
                    let (w1, w2) = (
                        T::from_fixed_i32(w1, BARY_FRAC),
                        T::from_fixed_i32(w2, BARY_FRAC),
                    );
                    let w0 = (T::ONE - w1 - w2).max(T::ZERO);
                    let s = w0 * iw[0] + w1 * iw[1] + w2 * iw[2];
                    let inv = if s > T::ZERO { T::ONE / s } else { T::ZERO };
                    let p = (pw[0] * w0 + pw[1] * w1 + pw[2] * w2) * inv;
                    let view = camera.view_dir(p);
                    let n = (nw[0] * w0 + nw[1] * w1 + nw[2] * w2)
                        .to_unit()
                        .unwrap_or(view);
                    let n = if opts.two_sided && n.dot(*view) < T::ZERO {
                        -n
                    } else {
                        n
                    };
                    stats.shaded = stats.shaded.wrapping_add(1);
                    let col = ctx.shader.shade(p, n, view).finite_or_zero();
                    let c = colour_bits(col, opts.exposure);
                    let shift = COLOUR_FRAC - ENCODE_INDEX_BITS;
                    if let Some(p) = px.get_mut(x as usize) {
                        *p = ctx.table.pixel(c[0] >> shift, c[1] >> shift, c[2] >> shift);
                        stats.pixels = stats.pixels.wrapping_add(1);
                    }
                }
            });
        }
    }
}

/// A triangle's anchor pixel `(xb, yb)` from its snapped vertices: the first pixel centre at
/// or right of / below its leftmost / topmost vertex (pixel i has its centre at 16 i + 8),
/// independent of the band.
#[inline(always)]
pub(super) fn anchor_pixel(fp: &[FixedPoint; 3]) -> (i32, i32) {
    let first = |m: i32| (m - SUBPIXEL / 2 + SUBPIXEL - 1).div_euclid(SUBPIXEL);
    (
        first(fp[0].x.min(fp[1].x).min(fp[2].x)),
        first(fp[0].y.min(fp[1].y).min(fp[2].y)),
    )
}

/// A depth value with [`DEPTH_FRAC`] fraction bits as the band's 16 bits (clamped).
#[inline(always)]
pub(super) fn depth16(q: i32) -> u16 {
    let z = q >> (DEPTH_FRAC - 16);
    // One unsigned comparison on the common path, the clamp out of line (as the colour
    // table's index: `EncodeTable::pixel`).
    if (z as u32) <= u32::from(u16::MAX) {
        z as u16
    } else {
        depth_out_of_range(z)
    }
}

/// [`depth16`] of a depth below 0 or beyond the 16 bits, clamped (cold).
#[cold]
#[inline(never)]
fn depth_out_of_range(z: i32) -> u16 {
    z.clamp(0, u16::MAX as i32) as u16
}

#[cfg(test)]
mod tests {
    use super::{recip62, Geometry};
    use crate::raster::edge::{Cull, EdgeTriangle, FixedPoint};

    #[test]
    fn the_32_bit_geometry_equals_the_64_bit_one() {
        let mut state = crate::test_rng::xorshift32(0x2545_F491);
        let mut next = |m: u32| state() % m;
        let (mut small, mut total) = (0, 0);
        for case in 0..200_000u32 {
            let span = [8, 64, 600, 5_000, 40_000, 70_000][case as usize % 6];
            let mut p = || {
                FixedPoint::new(
                    next(span) as i32 - next(span / 2 + 1) as i32,
                    next(span) as i32 - next(span / 2 + 1) as i32,
                )
            };
            let v = [p(), p(), p()];
            let Some(t) = EdgeTriangle::new(v, Cull::None) else {
                continue;
            };
            let fp = t.vertices();
            let (xb, yb) = super::anchor_pixel(&fp);
            let wide = Geometry::new_wide(fp, t.area2(), xb, yb);
            total += 1;
            if let Some(g) = Geometry::new_small(fp, t.area2(), xb, yb) {
                small += 1;
                assert_eq!((g.l1, g.l2, g.l32), (wide.l1, wide.l2, wide.l32), "{v:?}");
            } else {
                // Only when a weight does not fit (or the offsets are too large).
                let big = fp.iter().any(|q| {
                    (q.x - fp[0].x).unsigned_abs() >= 1 << 15
                        || (q.y - fp[0].y).unsigned_abs() >= 1 << 15
                });
                assert!(big || wide.l32.is_none(), "{v:?}");
            }
        }
        assert!(small > total / 2 && total > 150_000, "{small} of {total}");
    }

    /// `recip62(d)` is exactly `floor(2^62 / d)`: a stride of `d` (`step`), 4096 either side of
    /// each edge of [`recip_core`](crate::wide::recip_core)'s 16 table intervals, the ends,
    /// and a million random `d`.
    fn recip62_exact(step: usize) {
        let check = |d: u32| {
            assert_eq!(u64::from(recip62(d)), (1u64 << 62) / u64::from(d), "{d}");
        };
        for d in ((1u32 << 31)..=u32::MAX).step_by(step) {
            check(d);
        }
        for k in 0..=16u32 {
            let edge = (1u64 << 31) + (u64::from(k) << 27);
            let lo = edge.saturating_sub(4096).max(1 << 31);
            let hi = (edge + 4096).min(u64::from(u32::MAX));
            for d in lo..=hi {
                check(d as u32);
            }
        }
        for d in [(1 << 31) + 1, u32::MAX - 1, 0xC000_0000, 0xAAAA_AAAB] {
            check(d);
        }
        let mut next = crate::test_rng::xorshift32(0x9E37_79B9);
        for _ in 0..1_000_000 {
            check(next() | (1 << 31));
        }
    }

    #[test]
    fn the_32_bit_reciprocal_equals_the_64_bit_division() {
        recip62_exact(97);
    }

    #[test]
    #[ignore = "every d in [2^31, 2^32): run with `-- --ignored`"]
    fn the_32_bit_reciprocal_equals_the_64_bit_division_everywhere() {
        recip62_exact(1);
    }
}
