//! Fixed-point edge functions with the top-left fill rule.
//!
//! Vertices are snapped to a grid of [`SUBPIXEL`] steps per pixel (4 bits), pixel `(x, y)` is
//! sampled at its centre `(16 x + 8, 16 y + 8)` and every edge function is an exact `i64`
//! integer, so two triangles that share an edge (the same two snapped vertices) evaluate
//! exactly opposite edge functions there. A pixel centre exactly on an edge belongs to the
//! triangle for which that edge is a *top* edge (horizontal, the triangle below it) or a
//! *left* edge (the triangle to its right): of two triangles sharing the edge exactly one
//! qualifies, so shared edges leave no crack and draw no pixel twice (`tests/raster.rs`
//! checks it exhaustively on small grids).
//!
//! Coordinates are limited to `|x|, |y| <= MAX_COORD` sub-pixel units (the pipeline clips to a
//! guard band inside it), so every product below fits an `i64` with room to spare.

use crate::wide::mul_32;

/// Sub-pixel bits of the snapped vertex coordinates.
pub const SUBPIXEL_BITS: u32 = 4;
/// Sub-pixel steps per pixel (`1 << SUBPIXEL_BITS`).
pub const SUBPIXEL: i32 = 1 << SUBPIXEL_BITS;
/// The largest snapped coordinate magnitude accepted by [`EdgeTriangle::new`] (2^24 sub-pixel
/// units, a million pixels): edge products stay below 2^51.
pub const MAX_COORD: i32 = 1 << 24;

/// A vertex snapped to the sub-pixel grid: `x`, `y` in 1/[`SUBPIXEL`] pixel, `y` down.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FixedPoint {
    /// Column, in sub-pixel units (pixel `i` spans `[16 i, 16 i + 16)`).
    pub x: i32,
    /// Row, in sub-pixel units, growing downward.
    pub y: i32,
}

impl FixedPoint {
    /// `(x, y)` in sub-pixel units.
    pub const fn new(x: i32, y: i32) -> Self {
        FixedPoint { x, y }
    }
    /// The centre of pixel `(px, py)` (saturating for pixels beyond `i32::MAX / 16`).
    pub const fn pixel_centre(px: i32, py: i32) -> Self {
        FixedPoint {
            x: px.saturating_mul(SUBPIXEL).saturating_add(SUBPIXEL / 2),
            y: py.saturating_mul(SUBPIXEL).saturating_add(SUBPIXEL / 2),
        }
    }
}

/// `true` for a top or left edge from `a` to `b` of a triangle with positive
/// [`edge_function`] orientation (clockwise on screen, `y` down): a top edge is horizontal and
/// runs right (`dy = 0, dx > 0`), a left edge runs up (`dy < 0`).
#[inline]
pub const fn is_top_left(a: FixedPoint, b: FixedPoint) -> bool {
    // Compared, not subtracted: total for every pair of coordinates.
    (b.y == a.y && b.x > a.x) || b.y < a.y
}

/// The edge function of `a -> b` at `p`: `(b.x - a.x)(p.y - a.y) - (b.y - a.y)(p.x - a.x)`,
/// exact for coordinates within [`MAX_COORD`] (saturated beyond: never a panic or a wrong
/// sign). Positive on the right of the edge seen on screen (`y` down). Cost: two 32 x 32 ->
/// 64-bit products.
#[inline]
pub fn edge_function(a: FixedPoint, b: FixedPoint, p: FixedPoint) -> i64 {
    // Differences of coordinates within MAX_COORD fit an i32: 32 x 32 -> 64-bit products
    // (inline on Cortex-M0, where an i64 product is a library call).
    let d = |u: i32, v: i32| u.wrapping_sub(v);
    if [a, b, p]
        .iter()
        .all(|q| q.x.unsigned_abs() <= MAX_COORD as u32 && q.y.unsigned_abs() <= MAX_COORD as u32)
    {
        mul_32(d(b.x, a.x), d(p.y, a.y)) - mul_32(d(b.y, a.y), d(p.x, a.x))
    } else {
        // Beyond the rasterizer's range (EdgeTriangle refuses it): exact in i128, saturated
        // to i64 (the sign, which is what a coverage test reads, is kept).
        let w = |u: i32, v: i32| u as i128 - v as i128;
        let e = w(b.x, a.x) * w(p.y, a.y) - w(b.y, a.y) * w(p.x, a.x);
        e.clamp(i64::MIN as i128, i64::MAX as i128) as i64
    }
}

/// [`edge_function`] for points known to be within [`MAX_COORD`] of the origin, or of
/// pixel centres of a viewport (every difference then fits an `i32`): two 32 x 32 -> 64-bit
/// products, no range checks. What [`EdgeTriangle`] uses on its own (checked) vertices.
#[inline(always)]
fn edge_in_range(a: FixedPoint, b: FixedPoint, p: FixedPoint) -> i64 {
    mul_32(b.x.wrapping_sub(a.x), p.y.wrapping_sub(a.y))
        - mul_32(b.y.wrapping_sub(a.y), p.x.wrapping_sub(a.x))
}

/// [`edge_in_range`] in plain `i32` products when the four differences are under 2^15 (any
/// triangle of display size: the products below 2^30, their difference below 2^31), its
/// 32 x 32 -> 64-bit products otherwise. The same value.
#[inline(always)]
pub(super) fn edge_small_or_in_range(a: FixedPoint, b: FixedPoint, p: FixedPoint) -> i64 {
    let d = [
        b.x.wrapping_sub(a.x),
        p.y.wrapping_sub(a.y),
        b.y.wrapping_sub(a.y),
        p.x.wrapping_sub(a.x),
    ];
    if d.iter().all(|c| c.unsigned_abs() < 1 << 15) {
        i64::from(d[0] * d[1] - d[2] * d[3])
    } else {
        edge_in_range(a, b, p)
    }
}

/// Which faces to skip.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Cull {
    /// Draw both faces.
    None,
    /// Skip triangles whose vertices run clockwise on screen when given counter-clockwise in
    /// the mesh (the usual back faces: counter-clockwise seen from outside is the front).
    Back,
}

/// A triangle set up for scan conversion: three snapped vertices in positive orientation and
/// their three edge functions. Edge `k` is the one opposite vertex `k`, so its value at a point
/// is `area` times the point's barycentric weight of vertex `k`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct EdgeTriangle {
    v: [FixedPoint; 3],
    /// Twice the signed area (positive), in sub-pixel units squared.
    area: i64,
    /// 0 for a top-left edge, -1 otherwise: `E + bias >= 0` is the fill rule.
    bias: [i32; 3],
    /// Whether the input's vertices 1 and 2 were swapped to make the orientation positive.
    swapped: bool,
}

impl EdgeTriangle {
    /// Sets up `v` (any orientation). Returns `None` for a triangle of zero area, one culled by
    /// `cull`, or one with a coordinate beyond [`MAX_COORD`]. In the mesh convention
    /// (counter-clockwise front faces, seen with `y` up) a front face has a negative
    /// [`edge_function`] area on the `y`-down grid; it and (with [`Cull::None`]) a back face
    /// are reordered to positive orientation, which [`EdgeTriangle::swapped`] reports.
    ///
    /// Cost: 2 multiplications for the area, 3 comparisons.
    pub fn new(v: [FixedPoint; 3], cull: Cull) -> Option<Self> {
        if v.iter()
            .any(|p| p.x.unsigned_abs() > MAX_COORD as u32 || p.y.unsigned_abs() > MAX_COORD as u32)
        {
            return None;
        }
        let area = edge_small_or_in_range(v[0], v[1], v[2]);
        if area == 0 {
            return None;
        }
        let front = area < 0;
        if !front && cull == Cull::Back {
            return None;
        }
        let (v, area, swapped) = if area < 0 {
            ([v[0], v[2], v[1]], -area, true)
        } else {
            (v, area, false)
        };
        let bias = core::array::from_fn(|k| {
            let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
            if is_top_left(a, b) {
                0
            } else {
                -1
            }
        });
        Some(EdgeTriangle {
            v,
            area,
            bias,
            swapped,
        })
    }

    /// The vertices in positive orientation.
    pub fn vertices(&self) -> [FixedPoint; 3] {
        self.v
    }
    /// Twice the area, in sub-pixel units squared (> 0).
    pub fn area2(&self) -> i64 {
        self.area
    }
    /// `true` if vertices 1 and 2 were swapped (the input was a front face in the mesh
    /// convention): barycentric weight `k` of [`EdgeTriangle::for_each_covered`] then belongs
    /// to input vertex `[0, 2, 1][k]`.
    pub fn swapped(&self) -> bool {
        self.swapped
    }

    /// The three edge functions at `p` (edge `k` opposite vertex `k`).
    #[inline]
    pub fn weights_at(&self, p: FixedPoint) -> [i64; 3] {
        let v = self.v;
        if p.x.unsigned_abs() <= MAX_COORD as u32 && p.y.unsigned_abs() <= MAX_COORD as u32 {
            [
                edge_in_range(v[1], v[2], p),
                edge_in_range(v[2], v[0], p),
                edge_in_range(v[0], v[1], p),
            ]
        } else {
            [
                edge_function(v[1], v[2], p),
                edge_function(v[2], v[0], p),
                edge_function(v[0], v[1], p),
            ]
        }
    }

    /// `true` if the fill rule assigns point `p` to this triangle.
    #[inline]
    pub fn covers(&self, p: FixedPoint) -> bool {
        let e = self.weights_at(p);
        (0..3).all(|k| e[k] + i64::from(self.bias[k]) >= 0)
    }

    /// The pixel rectangle `(x0, y0, x1, y1)` (inclusive) whose centres may be covered,
    /// clipped to columns `[0, width)` and rows `[row0, row1)`; `None` if empty.
    pub fn pixel_bounds(&self, width: i32, row0: i32, row1: i32) -> Option<(i32, i32, i32, i32)> {
        let v = self.v;
        let lo = |a: i32, b: i32, c: i32| a.min(b).min(c);
        let hi = |a: i32, b: i32, c: i32| a.max(b).max(c);
        // Pixel i has its centre at 16 i + 8: the first centre >= m is ceil((m - 8)/16).
        let first = |m: i32| (m - SUBPIXEL / 2 + SUBPIXEL - 1).div_euclid(SUBPIXEL);
        let last = |m: i32| (m - SUBPIXEL / 2).div_euclid(SUBPIXEL);
        let x0 = first(lo(v[0].x, v[1].x, v[2].x)).max(0);
        let x1 = last(hi(v[0].x, v[1].x, v[2].x)).min(width.saturating_sub(1));
        let y0 = first(lo(v[0].y, v[1].y, v[2].y)).max(row0);
        let y1 = last(hi(v[0].y, v[1].y, v[2].y)).min(row1.saturating_sub(1));
        if x0 > x1 || y0 > y1 {
            None
        } else {
            Some((x0, y0, x1, y1))
        }
    }

    /// Calls `f(y, first, last)` for every row of `[row0, row1)` that has covered pixels
    /// (columns `[0, width)`), with the first and last covered column: the pixels
    /// [`EdgeTriangle::for_each_covered`] visits, row by row, as spans (a triangle is convex,
    /// so a row's covered pixels are contiguous). The same exact integer tests, each edge's
    /// bounding pixel carried from row to row. Cost: 6 multiplications; per row 4 additions
    /// and, per column an edge's bound moves (its slope: about one for the small triangles of
    /// a mesh), 1 addition and 1 comparison; nothing per pixel of the span. Measured with the
    /// demo's Gouraud frame (`boards/qemu-frame`, Cortex-M4F, 2 959 spans of 586 triangles):
    /// about 135 instructions a row, against 180 when each row walked from the box's left edge.
    pub fn for_each_span<F: FnMut(i32, i32, i32)>(&self, width: i32, row0: i32, row1: i32, f: F) {
        if let Some(bounds) = self.pixel_bounds(width, row0, row1) {
            self.for_each_span_in(bounds, f);
        }
    }

    /// [`EdgeTriangle::for_each_span`] over the pixel box `(x0, y0, x1, y1)` that
    /// [`EdgeTriangle::pixel_bounds`] gave (for a caller that has it already).
    #[inline(always)]
    pub(crate) fn for_each_span_in<F: FnMut(i32, i32, i32)>(
        &self,
        (x0, y0, x1, y1): (i32, i32, i32, i32),
        f: F,
    ) {
        let v = self.v;
        // A triangle within 1024 pixels each way (any on a display) has every edge function
        // over its bounding box below 2^29 in magnitude (and one pixel beyond it, where a
        // bound that finds no pixel rests, below 2^30): step in i32 (one register each on a
        // 32-bit core) rather than i64.
        let lo = |a: i32, b: i32, c: i32| a.min(b).min(c);
        let hi = |a: i32, b: i32, c: i32| a.max(b).max(c);
        let small = hi(v[0].x, v[1].x, v[2].x) - lo(v[0].x, v[1].x, v[2].x) < 1024 * SUBPIXEL
            && hi(v[0].y, v[1].y, v[2].y) - lo(v[0].y, v[1].y, v[2].y) < 1024 * SUBPIXEL;
        let p = FixedPoint::pixel_centre(x0, y0);
        if small {
            // The box's first pixel centre lies within the vertices' range, so every
            // difference below is under 2^14 + 8 in magnitude: the edge functions there in
            // plain i32 products (exact: below 2^29), not 32 x 32 -> 64-bit ones.
            let start = core::array::from_fn(|k| {
                let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
                (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)
            });
            self.scan::<i32, F>((x0, y0, x1, y1), start, f);
        } else {
            self.scan::<i64, F>((x0, y0, x1, y1), self.weights_at(p), f);
        }
    }

    /// The span loop of [`EdgeTriangle::for_each_span`] over the pixel box `(x0, y0, x1, y1)`
    /// in integers `E` (which must hold every edge value over the box and one pixel beyond),
    /// from the edge functions `start` at its first pixel.
    ///
    /// The edges are split by the sign of their step along a row: a *left* edge (growing to
    /// the right) is met at the first pixel of a row where it is `>= 0`, a *right* edge
    /// (shrinking, or constant) at the last. A triangle of positive area has at most two of
    /// each (the three row steps sum to zero, and two constant edges would make it flat). Each
    /// edge keeps that pixel from row to row ([`Bound`]), clamped to the box, with its exact
    /// value there: a new row adds the edge's row step and moves the pixel the few columns the
    /// edge's slope takes it (at most the box's width). The row's span runs from the larger of
    /// the left edges' pixels to the smaller of the right edges': the same pixels as testing
    /// all three edges at every pixel of the box, with a cost per row that does not grow with
    /// the span ([`scan_rows`], one loop for two left edges and one for two right ones).
    #[inline(always)]
    fn scan<E: EdgeInt, F: FnMut(i32, i32, i32)>(
        &self,
        (x0, y0, x1, y1): (i32, i32, i32, i32),
        start: [E; 3],
        f: F,
    ) {
        let v = self.v;
        let zero = E::from_i32(0);
        let unused = Bound {
            x: x0,
            value: zero,
            step: zero,
            row: zero,
        };
        let mut left = [unused; 2];
        let mut right = [Bound { x: x1, ..unused }; 2];
        let (mut nl, mut nr) = (0usize, 0usize);
        for k in 0..3 {
            let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
            // d/dx (one pixel = SUBPIXEL units) -(b.y - a.y) SUBPIXEL, d/dy (b.x - a.x)
            // SUBPIXEL: exact integer steps, in i32 (coordinates within MAX_COORD = 2^24:
            // below 2^29 in magnitude), not in 64-bit arithmetic on a 32-bit core.
            let step = -(b.y - a.y) * SUBPIXEL;
            let edge = Bound {
                x: x0,
                // (The bias is 0 or -1: exact in any `E`.)
                value: start[k] + E::from_i32(self.bias[k]),
                step: E::from_i32(step),
                row: E::from_i32((b.x - a.x) * SUBPIXEL),
            };
            let (slots, n) = if step > 0 {
                (&mut left, &mut nl)
            } else {
                (&mut right, &mut nr)
            };
            if let Some(slot) = slots.get_mut(*n) {
                *slot = edge;
            }
            *n += 1;
        }
        // (A triangle of positive area has one or two of each: two loops, each with its three
        // edges, not one with a fourth that is never met.)
        let [l0, l1] = left;
        let [r0, r1] = right;
        let boxed = (x0, y0, x1, y1);
        if nl >= 2 {
            scan_rows::<E, F, true>(boxed, [l0, l1, r0], f);
        } else {
            scan_rows::<E, F, false>(boxed, [l0, r0, r1], f);
        }
    }

    /// Calls `f(x, y, weights)` for every pixel of columns `[0, width)` and rows
    /// `[row0, row1)` whose centre the fill rule assigns to the triangle, row by row, left to
    /// right; `weights` are the three edge functions at the centre (each >= 0, summing to
    /// [`EdgeTriangle::area2`]).
    ///
    /// Exact integer arithmetic: the set of pixels, and the weights of each, do not depend on
    /// the row range asked for (a band gets exactly its rows of the full frame). Cost per
    /// pixel of the bounding box: 3 additions and 3 comparisons; per row: 6 multiplications.
    pub fn for_each_covered<F: FnMut(i32, i32, [i64; 3])>(
        &self,
        width: i32,
        row0: i32,
        row1: i32,
        f: F,
    ) {
        if let Some(bounds) = self.pixel_bounds(width, row0, row1) {
            self.for_each_covered_in(bounds, f);
        }
    }

    /// [`EdgeTriangle::for_each_covered`] over the pixel box `(x0, y0, x1, y1)` that
    /// [`EdgeTriangle::pixel_bounds`] gave (for a caller that has it already).
    pub(crate) fn for_each_covered_in<F: FnMut(i32, i32, [i64; 3])>(
        &self,
        (x0, y0, x1, y1): (i32, i32, i32, i32),
        mut f: F,
    ) {
        let v = self.v;
        // d/dx of edge k (one pixel = SUBPIXEL units): -(b.y - a.y) SUBPIXEL.
        let step: [i64; 3] = core::array::from_fn(|k| {
            let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
            -(b.y as i64 - a.y as i64) * SUBPIXEL as i64
        });
        let bias = self.bias.map(i64::from);
        for y in y0..=y1 {
            let mut e = self.weights_at(FixedPoint::pixel_centre(x0, y));
            for x in x0..=x1 {
                if e[0] + bias[0] >= 0 && e[1] + bias[1] >= 0 && e[2] + bias[2] >= 0 {
                    f(x, y, e);
                }
                e[0] += step[0];
                e[1] += step[1];
                e[2] += step[2];
            }
        }
    }
}

/// The rows of [`EdgeTriangle::scan`] with its three edges `[a, b, c]`: `a` a left edge, `c` a
/// right one, `b` a left edge if `TWO_LEFT`, else a right one.
#[inline(always)]
fn scan_rows<E: EdgeInt, F: FnMut(i32, i32, i32), const TWO_LEFT: bool>(
    (x0, y0, x1, y1): (i32, i32, i32, i32),
    [mut a, mut b, mut c]: [Bound<E>; 3],
    mut f: F,
) {
    for y in y0..=y1 {
        if y > y0 {
            a.value = a.value + a.row;
            b.value = b.value + b.row;
            c.value = c.value + c.row;
        }
        a.settle_left(x0, x1);
        if TWO_LEFT {
            b.settle_left(x0, x1);
        } else {
            b.settle_right(x0, x1);
        }
        c.settle_right(x0, x1);
        let (first, last) = if TWO_LEFT {
            (a.x.max(b.x), c.x)
        } else {
            (a.x, b.x.min(c.x))
        };
        if first <= last {
            f(y, first, last);
        }
    }
}

/// One edge of [`EdgeTriangle::scan`] on the current row: `x` its bounding pixel, clamped
/// to the box (for a left edge the first pixel where it is `>= 0`, or `x1 + 1` for none; for
/// a right edge the last, or `x0 - 1`), `value` the edge function there, `step` its change
/// per pixel along the row and `row` per row down.
#[derive(Clone, Copy)]
struct Bound<E> {
    x: i32,
    value: E,
    step: E,
    row: E,
}

impl<E: EdgeInt> Bound<E> {
    /// Moves a left edge's pixel (`step > 0`) to the first of `[x0, x1 + 1]` where the edge is
    /// `>= 0` (`x1 + 1`: none in the box), from where it was: right while it is negative,
    /// then left while the pixel before is not.
    #[inline(always)]
    fn settle_left(&mut self, x0: i32, x1: i32) {
        let zero = E::from_i32(0);
        while self.value < zero && self.x <= x1 {
            self.value = self.value + self.step;
            self.x += 1;
        }
        while self.x > x0 && !(self.value - self.step < zero) {
            self.value = self.value - self.step;
            self.x -= 1;
        }
    }

    /// Moves a right edge's pixel (`step <= 0`) to the last of `[x0 - 1, x1]` where the edge
    /// is `>= 0` (`x0 - 1`: none in the box): left while it is negative, then right while the
    /// next pixel is not.
    #[inline(always)]
    fn settle_right(&mut self, x0: i32, x1: i32) {
        let zero = E::from_i32(0);
        while self.value < zero && self.x >= x0 {
            self.value = self.value - self.step;
            self.x -= 1;
        }
        while self.x < x1 && !(self.value + self.step < zero) {
            self.value = self.value + self.step;
            self.x += 1;
        }
    }
}

/// The integers edge functions are stepped in: `i32` for triangles of display size, `i64`
/// beyond.
trait EdgeInt:
    Copy + PartialOrd + core::ops::Add<Output = Self> + core::ops::Sub<Output = Self>
{
    /// From an `i32` (exact).
    fn from_i32(x: i32) -> Self;
}

impl EdgeInt for i32 {
    #[inline(always)]
    fn from_i32(x: i32) -> Self {
        x
    }
}

impl EdgeInt for i64 {
    #[inline(always)]
    fn from_i32(x: i32) -> Self {
        i64::from(x)
    }
}
