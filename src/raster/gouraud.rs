//! The Gouraud span loop of [`scan`](super::scan)'s triangles, and the colour table's guards
//! that let most triangles skip its clamp.
//!
//! A Gouraud pixel's colour is three attribute planes' values, each an index into the
//! [`EncodeTable`] with `SHIFT` more fraction bits. The table's clamp (an index below 0 or
//! above 4096 takes the end entry) costs a comparison and a branch a channel, with their
//! constants, in the span loop. With the `encode-guards` feature the table holds copies of its
//! end entries either side (`ENCODE_GUARD`: 2^13 slots in all, 16 KiB), so indices in
//! `[-2047, 6144]` need no clamp.
//! A triangle whose vertex colours are at most `GUARDED_COLOUR_MAX` (1.44, after the
//! exposure) and whose extent is under `GUARDED_EXTENT` pixels has every covered pixel's
//! value within `GUARD_MARGIN` of its vertices' range, so within the guards: its planes are
//! biased and scaled so that each value's top 13 bits are its slot (one shift and one load a
//! channel), and the pixels are those of the clamped lookup, bit for bit. Other triangles
//! take the clamp. On the RP2040 demo (rp2040js, frames 1 to 15) every triangle but a few
//! highlights is guarded: one core 8 100 916 -> 7 925 968 cycles, two cores 4 669 747 ->
//! 4 604 248.

use super::edge::{EdgeTriangle, FixedPoint, SUBPIXEL};
use super::scan::{depth16, Geometry, Plane, COLOUR_FRAC};
use super::target::{
    Band, EncodeTable, PixelFormat, ENCODE_GUARD, ENCODE_GUARDS, ENCODE_INDEX_BITS,
};
use super::DrawStats;

/// Whether the Gouraud span loop takes guarded triangles without the clamp: with the table's
/// guards (`encode-guards`), on ARMv6-M (the Cortex-M0+ of the RP2040: rp2040js frames 1 to
/// 15, one core 8 100 916 -> 7 925 968 cycles), where the clamp's comparisons and constants
/// cost the span loop registers it does not have. Elsewhere the clamped loop alone: on the
/// Cortex-M4F the guarded one measured no faster, and the STM32F411 Gouraud frame 0 (QEMU)
/// took 2 811 206 instructions with the 16 KiB table and both loops against 2 779 784 with
/// the 8 KiB table and the clamped loop (2 772 886 before the guards).
pub(super) const GUARDED_SPANS: bool =
    ENCODE_GUARDS && cfg!(all(target_arch = "arm", not(target_has_atomic = "32")));

/// A covered pixel's Gouraud colour with [`COLOUR_FRAC`] fraction bits as an [`EncodeTable`]
/// index (`>> SHIFT`).
pub(super) const SHIFT: u32 = COLOUR_FRAC - ENCODE_INDEX_BITS;

/// The bias that puts index 0 at the colour table's first entry after its guards
/// ([`EncodeTable::pixel_guarded`]).
const GUARD_BIAS: i32 = (ENCODE_GUARD as i32) << SHIFT;

/// The scale of a guarded triangle's colour planes, `2^GUARD_SCALE`: it moves the 13 bits
/// above [`SHIFT`] (the index and its guards) to the top.
const GUARD_SCALE: u32 = 19 - SHIFT;

/// The largest vertex colour of a guarded triangle, about 1.438 (after the exposure): the
/// values at its covered pixels then lie in `[-GUARD_MARGIN, GUARDED_COLOUR_MAX +
/// GUARD_MARGIN]`, so with the bias in `[0, 2^25)`, whose bits 12 to 24 are the slot.
const GUARDED_COLOUR_MAX: i32 = (1 << (COLOUR_FRAC + 1)) - GUARD_BIAS - GUARD_MARGIN - 1;

/// How far an attribute plane may stray from the exact interpolation of its vertex values at
/// a covered pixel of a guarded triangle (extent below `GUARDED_EXTENT` pixels, weights in
/// `i32`): 2^20 units of 2^-24, 256 of the table's indices (its guards are 2047). Each slope
/// is the floor of two products of a vertex difference (below 2^25) by a weight within a few
/// units of its exact value, so within about 13 units of exact, and the anchor's value within
/// a few thousand: under 2^15 units over the 2048 pixels a covered pixel can lie from the
/// anchor. `the_guarded_span_loop_draws_the_clamped_loops_pixels` checks every covered pixel
/// of 5 411 random guarded triangles against this margin (the worst: 1080 units).
const GUARD_MARGIN: i32 = 1 << 20;

/// The largest extent, in pixels each way, of a guarded triangle.
const GUARDED_EXTENT: i32 = 1024;

/// Whether a triangle (its snapped vertices `fp`, its weights `geo` and its vertices'
/// colours) can be drawn through the colour table's guards: its extent below
/// `GUARDED_EXTENT` pixels each way, its weights in `i32` and every vertex colour at most
/// `GUARDED_COLOUR_MAX`. Then every covered pixel's colour lies within `GUARD_MARGIN` of its
/// vertices' range, so its index within the guards.
#[inline(always)]
pub(super) fn is_guarded(fp: &[FixedPoint; 3], geo: &Geometry, colours: [&[i32; 3]; 3]) -> bool {
    let extent = |c: fn(&FixedPoint) -> i32| {
        let (a, b, d) = (c(&fp[0]), c(&fp[1]), c(&fp[2]));
        a.max(b).max(d) - a.min(b).min(d)
    };
    geo.l32.is_some()
        && extent(|p| p.x) < GUARDED_EXTENT * SUBPIXEL
        && extent(|p| p.y) < GUARDED_EXTENT * SUBPIXEL
        && colours
            .iter()
            .all(|c| c.iter().all(|&c| c <= GUARDED_COLOUR_MAX))
}

/// The per-triangle inputs of the Gouraud span loop.
pub(super) struct Spans<'a, P: PixelFormat> {
    pub(super) depth: Plane,
    pub(super) yb: i32,
    pub(super) table: &'a EncodeTable<P>,
}

impl<P: PixelFormat> Spans<'_, P> {
    /// Draws the triangle's spans: the depth test, then the colour from the table, through
    /// its guards (`GUARDED`: the planes biased, no comparison) or its clamp.
    #[inline(always)]
    pub(super) fn gouraud<const GUARDED: bool>(
        &self,
        tri: &EdgeTriangle,
        bounds: (i32, i32, i32, i32),
        planes: &[Plane; 3],
        band: &mut Band<'_, P>,
        stats: &mut DrawStats,
    ) {
        let (depth, yb, table) = (self.depth, self.yb, self.table);
        let pixel = move |r: i32, g: i32, b: i32| {
            if GUARDED {
                table.pixel_guarded(r as u32, g as u32, b as u32)
            } else {
                table.pixel(r >> SHIFT, g >> SHIFT, b >> SHIFT)
            }
        };
        // (Stepping the four attributes by additions instead of `row + x sx` per pixel,
        // and indexing the band's rows directly, were both measured slower on the
        // Cortex-M0+: more live values than its 8 low registers. So were, in the
        // emulated demo: stepping only the depth, the slopes copied into locals (LLVM
        // then strength-reduces and unrolls the loop, spilling), and one bounds check
        // for the span's slices instead of the row's and the span's.)
        tri.for_each_span_in(bounds, move |y, xs, xe| {
            let Some((px, dp)) = band.row_mut(y as u16) else {
                return;
            };
            let dy = y - yb;
            let (d0, r0, g0, b0) = (
                depth.row(dy),
                planes[0].row(dy),
                planes[1].row(dy),
                planes[2].row(dy),
            );
            let (xs, xe) = (xs as usize, xe as usize);
            let Some(px) = px.get_mut(xs..=xe) else {
                return;
            };
            let mut x = xs as i32;
            let mut written = px.len() as u32;
            match dp.and_then(|d| d.get_mut(xs..=xe)) {
                Some(dp) => {
                    for (p, d) in px.iter_mut().zip(dp.iter_mut()) {
                        let z = depth16(d0.wrapping_add(x.wrapping_mul(depth.sx)));
                        if z < *d {
                            *d = z;
                            *p = pixel(
                                r0.wrapping_add(x.wrapping_mul(planes[0].sx)),
                                g0.wrapping_add(x.wrapping_mul(planes[1].sx)),
                                b0.wrapping_add(x.wrapping_mul(planes[2].sx)),
                            );
                        } else {
                            written -= 1;
                        }
                        x += 1;
                    }
                }
                None => {
                    for p in px.iter_mut() {
                        *p = pixel(
                            r0.wrapping_add(x.wrapping_mul(planes[0].sx)),
                            g0.wrapping_add(x.wrapping_mul(planes[1].sx)),
                            b0.wrapping_add(x.wrapping_mul(planes[2].sx)),
                        );
                        x += 1;
                    }
                }
            }
            stats.pixels = stats.pixels.wrapping_add(written);
        });
    }
}

impl Plane {
    /// A guarded triangle's colour plane ([`is_guarded`]): biased by the colour table's
    /// guards and scaled by `2^GUARD_SCALE` (wrapping: the same values modulo 2^32), so that
    /// each covered pixel's value has its table slot in its top 13 bits
    /// ([`EncodeTable::pixel_guarded`]).
    #[inline(always)]
    pub(super) fn guarded(self) -> Self {
        Plane {
            base: self.base.wrapping_add(GUARD_BIAS) << GUARD_SCALE,
            sx: self.sx << GUARD_SCALE,
            sy: self.sy << GUARD_SCALE,
        }
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::raster::edge::Cull;
    use crate::raster::target::{Encoding, Rgb565};
    use std::vec;

    /// Random triangles of up to `GUARDED_EXTENT` pixels reaching into a 192 x 160 band, with
    /// vertex colours from 0 to `GUARDED_COLOUR_MAX` (many at either end) and random depths:
    /// where a triangle is guarded, every covered pixel's colour plane lies within
    /// `GUARD_MARGIN` of its vertices' range (the bound the guards rest on), and the guarded
    /// span loop draws the clamped one's pixels and depths, bit for bit, with the same
    /// statistics.
    #[test]
    fn the_guarded_span_loop_draws_the_clamped_loops_pixels() {
        let (w, h) = (192i32, 160i32);
        let table = EncodeTable::<Rgb565>::new::<f64>(Encoding::Srgb);
        let mut next = crate::test_rng::xorshift32(0x1234_5679);
        let (mut guarded, mut pixels, mut worst) = (0u32, 0u64, 0i64);
        for case in 0..6000u32 {
            // Vertices within a box of 8 to 1023 pixels placed around the band (sub-pixels).
            let size = [8, 40, 200, 1023][case as usize % 4] * SUBPIXEL;
            let (ox, oy) = (
                (next() % (w as u32 * 16 + 1)) as i32 - size / 2,
                (next() % (h as u32 * 16 + 1)) as i32 - size / 2,
            );
            let mut p = || {
                FixedPoint::new(
                    ox + (next() % size as u32) as i32,
                    oy + (next() % size as u32) as i32,
                )
            };
            let Some(tri) = EdgeTriangle::new([p(), p(), p()], Cull::None) else {
                continue;
            };
            let Some(bounds) = tri.pixel_bounds(w, 0, h) else {
                continue;
            };
            let fp = tri.vertices();
            let (xb, yb) = crate::raster::scan::anchor_pixel(&fp);
            let geo = Geometry::new(fp, tri.area2(), xb, yb);
            let mut colour = || match next() % 4 {
                0 => 0,
                1 => GUARDED_COLOUR_MAX,
                _ => (next() % (GUARDED_COLOUR_MAX as u32 + 1)) as i32,
            };
            let colours = [
                [colour(), colour(), colour()],
                [colour(), colour(), colour()],
                [colour(), colour(), colour()],
            ];
            if !is_guarded(&fp, &geo, [&colours[0], &colours[1], &colours[2]]) {
                continue;
            }
            guarded += 1;
            let planes: [Plane; 3] = core::array::from_fn(|k| {
                Plane::new([colours[0][k], colours[1][k], colours[2][k]], &geo)
            });
            let depth = Plane::new([0, 1, 2].map(|_| (next() % (1 << 28)) as i32), &geo);
            // The bound: each plane within the margin of its vertex range at every covered pixel.
            tri.for_each_span_in(bounds, |y, xs, xe| {
                for x in xs..=xe {
                    for (k, pl) in planes.iter().enumerate() {
                        let c = [colours[0][k], colours[1][k], colours[2][k]];
                        let (lo, hi) = (*c.iter().min().unwrap(), *c.iter().max().unwrap());
                        let v = pl.row(y - yb).wrapping_add(x.wrapping_mul(pl.sx));
                        let off = (i64::from(lo) - i64::from(v)).max(i64::from(v) - i64::from(hi));
                        worst = worst.max(off);
                        assert!(
                            off <= i64::from(GUARD_MARGIN),
                            "case {case}: {v} outside [{lo}, {hi}]"
                        );
                    }
                }
            });
            // Both loops into a band each, over the same background and depths.
            let draw = |guard: bool| {
                let mut px = vec![Rgb565(0x1234); (w * h) as usize];
                let mut dp = vec![0u16; (w * h) as usize];
                let mut d = crate::test_rng::xorshift32(case + 1);
                dp.iter_mut().for_each(|z| *z = (d() >> 16) as u16 | 0x8000);
                let mut stats = DrawStats::default();
                let spans = Spans {
                    depth,
                    yb,
                    table: &table,
                };
                {
                    let mut band = Band::new(&mut px, Some(&mut dp), w as u16, 0).unwrap();
                    if guard {
                        spans.gouraud::<true>(
                            &tri,
                            bounds,
                            &planes.map(Plane::guarded),
                            &mut band,
                            &mut stats,
                        );
                    } else {
                        spans.gouraud::<false>(&tri, bounds, &planes, &mut band, &mut stats);
                    }
                }
                (px, dp, stats)
            };
            let (a, b) = (draw(true), draw(false));
            pixels += u64::from(b.2.pixels);
            assert!(a == b, "case {case}: the guarded loop drew other pixels");
        }
        assert!(
            guarded > 3000 && pixels > 1_000_000,
            "{guarded} guarded triangles, {pixels} pixels"
        );
        // The margin is far from tight: the worst plane measured 1080 units of 2^-24 beyond
        // its vertex range (5 411 guarded triangles, 11.8 M pixels).
        assert!(worst < 1 << 12, "worst {worst}");
    }
}
