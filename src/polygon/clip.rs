//! The horizon clipping shared by the polygon models: the walk round the ring of vertices seen
//! from `p` ([`for_each_clipped_edge`]), its edges ([`ClippedEdge`]: the Lambert term, the
//! horizon arc's angle, the power-of-two rescaling) and the solid angle of the clipped ring as
//! a fan of triangles ([`ApexFan`]). See the module docs of [`crate::polygon`].

use super::edge::{
    self, edge_angle_term, edge_atan_term_fixed, products_in_range, rescaled_products,
    scaled_to_unit,
};
use crate::{Real, Vec3};

/// One edge of the clipped ring seen from `p`: from `ua` to `ub` (points relative to `p`, not
/// normalized), `d = ub - ua` computed from the polygon's own edge vector (no cancellation
/// through `p`), and whether it is an arc of the horizon.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ClippedEdge<T> {
    pub(crate) ua: Vec3<T>,
    pub(crate) ub: Vec3<T>,
    pub(crate) d: Vec3<T>,
    pub(crate) horizon: bool,
    /// The index of the vertex `ua` is the offset of, or [`CROSSING`] (a horizon crossing;
    /// always for the floats, whose walks do not read it).
    #[allow(dead_code)] // read by the Phong walk only
    pub(crate) ia: usize,
    /// The same for `ub`.
    #[allow(dead_code)]
    pub(crate) ib: usize,
}

/// [`ClippedEdge`]'s vertex index of a point that is no vertex (a horizon crossing).
pub(crate) const CROSSING: usize = usize::MAX;

impl<T: Real> ClippedEdge<T> {
    /// The signed angle of a horizon arc about `k`, in (-pi, pi]: the projection of the
    /// straight segment `ua -> ub` in the horizon plane, positive when it runs
    /// counter-clockwise about `k`. (For a non-convex polygon the clipped ring may run along the
    /// horizon in both directions; the arcs then cancel, so each keeps its own sign.) The sign
    /// comes from the unnormalized `ua x ub`, which keeps its relative accuracy when the arc
    /// nearly spans pi (the polygon seen nearly edge-on), where the cross product of
    /// normalized directions is mostly rounding.
    /// An arc whose products leave the normal range ([`products_in_range`]) is first scaled
    /// by a power of two (cold path).
    ///
    /// `k` is a unit vector and the edge's points within the coordinate limit's offsets (every
    /// caller's: [`edge::offset_products`]): `G = ua x d` then has components of at most 256
    /// and `G.k` at most `|G|`, so fixed point forms them without saturation tests (the same
    /// bits as `Vec3::cross` and `Vec3::dot`).
    #[inline]
    pub(crate) fn horizon_angle(&self, k: Vec3<T>) -> T {
        let (g, mut x) = edge::offset_products(self.ua, self.ub, self.d);
        let mut y = T::mul_unit(g.x, k.x) + T::mul_unit(g.y, k.y) + T::mul_unit(g.z, k.z);
        let m = y.abs().max(x.abs());
        if !products_in_range(m, m) {
            let Some((g, dot)) = rescaled_products(self.ua, self.ub, self.d) else {
                return T::ZERO;
            };
            (y, x) = (g.dot(k), dot);
        }
        y.atan2(x)
    }

    /// The edge's term of Lambert's formula about the unit normal `n`: the horizon arc's
    /// signed angle, or [`edge_angle_term`]. (Inlined into the caller's walk.)
    #[inline(always)]
    pub(crate) fn lambert_term(&self, n: Vec3<T>) -> T {
        if self.horizon {
            self.horizon_angle(n)
        } else {
            edge_angle_term(self.ua, self.ub, self.d, n)
        }
    }

    /// [`ClippedEdge::lambert_term`] and, for fixed point, whether the edge subtends more than
    /// a right angle (`p` beside it) and `p` lies within about `r_min` of its line: `|G|`'s
    /// largest component below `r_min` times `|d|`'s (the second half of the test of
    /// [`near_limit`](super::near_limit); beside the edge, `|d|` is at least its ends' distances). The floats:
    /// never.
    #[inline(always)]
    pub(crate) fn lambert_term_resolved(&self, n: Vec3<T>, r_min: T) -> (T, bool) {
        if !(T::RESOLUTION > T::ZERO) {
            return (self.lambert_term(n), false);
        }
        if self.horizon {
            return (self.horizon_angle(n), false);
        }
        edge_atan_term_fixed(self.ua, self.ub, self.d, n, r_min)
    }

    /// The same edge scaled by a power of two that brings its largest coordinate into [1, 2)
    /// ([`scaled_to_unit`]); `None` for an edge with no finite non-zero coordinate. Every term of an edge is scale-free, so this is the cold path of the edge
    /// terms whose products would leave the normal range.
    #[inline]
    pub(crate) fn rescaled(&self) -> Option<Self> {
        let [ua, ub, d] = scaled_to_unit([self.ua, self.ub, self.d])?;
        Some(ClippedEdge {
            ua,
            ub,
            d,
            horizon: self.horizon,
            // (Scaled: no longer the vertices' own offsets.)
            ia: CROSSING,
            ib: CROSSING,
        })
    }
}

/// An edge's endpoint directions and lengths and `ua x d`, for [`ApexFan::add`].
type FanEnds<T> = (Vec3<T>, T, Vec3<T>, T, Vec3<T>);

/// The signed solid angle of a ring clipped to the hemisphere `u.k >= 0`, as a fan of spherical
/// triangles `(k, a, b)` with apex `k`, one per clipped edge `(a, b)` (Arvo 5.1 sums the same
/// signed areas). Every clipped point has `u.k >= 0`, so every fan triangle is proper and the
/// back-and-forth bridges of a non-convex clip cancel exactly. A polygon edge's triangle comes
/// from Van Oosterom and Strackee's `tan(W/2) = k.(a x b)/(1 + a.b + k.a + k.b)`; a horizon
/// arc's triangle has two vertices on the equator of `k`, so its area is exactly the arc's
/// signed angle ([`ClippedEdge::horizon_angle`]): that is the case (a polygon seen nearly
/// edge-on, the arc spanning nearly pi) where the general formula would divide tiny by tiny.
pub(crate) struct ApexFan<T> {
    apex: Vec3<T>,
    sum: T,
}

impl<T: Real> ApexFan<T> {
    pub(crate) fn new(apex: Vec3<T>) -> Self {
        ApexFan { apex, sum: T::ZERO }
    }

    /// Adds the triangle (apex, ua, ub) of the clipped edge `e`.
    ///
    /// An edge whose products leave the normal range ([`products_in_range`]: lengths below
    /// `TINY` or beyond `1/TINY`) is first scaled by a power of two (cold path).
    #[inline]
    pub(crate) fn add(&mut self, e: &ClippedEdge<T>) {
        let k = self.apex;
        if e.horizon {
            self.sum += e.horizon_angle(k);
            return;
        }
        let ends = |e: &ClippedEdge<T>| -> Option<FanEnds<T>> {
            let (a, la) = e.ua.normalize_with_length()?;
            let (b, lb) = e.ub.normalize_with_length()?;
            let l = la.max(lb);
            products_in_range(la * lb, l * l).then_some((a, la, b, lb, e.ua.cross(e.d)))
        };
        let Some((a, la, b, lb, g)) = ends(e).or_else(|| Self::rescaled_ends(e)) else {
            return;
        };
        let num = k.dot(g) / (la * lb);
        let den = T::ONE + a.dot(b) + k.dot(a) + k.dot(b);
        self.sum += T::TWO * num.atan2(den);
    }

    /// The fan triangle's inputs from the edge scaled by a power of two (cold path; see
    /// [`ClippedEdge::rescaled`]).
    #[cold]
    #[inline(never)]
    fn rescaled_ends(e: &ClippedEdge<T>) -> Option<FanEnds<T>> {
        let s = e.rescaled()?;
        let (a, la) = s.ua.normalize_with_length()?;
        let (b, lb) = s.ub.normalize_with_length()?;
        Some((a, la, b, lb, s.ua.cross(s.d)))
    }

    /// The signed solid angle (positive for a ring counter-clockwise seen from outside, the
    /// convention of the boundary integrals).
    pub(crate) fn total(&self) -> T {
        self.sum
    }
}

/// [`for_each_clipped_edge`] for a ring wholly above the horizon (every `(v - p).k >= 0`, the
/// walk's own test): calls `edge(ua, ub, d)` for each edge in the walk's order (the polygon's
/// own edges from vertex 0, `d` its edge vector) with no state for horizon crossings, and
/// returns `true`; `false` as soon as a vertex is below the horizon or `edge` returns `false`
/// (the caller then walks, discarding what it summed). Each vertex's offset is taken once.
#[inline(always)]
pub(crate) fn for_each_unclipped_edge<T: Real>(
    verts: &[Vec3<T>],
    p: Vec3<T>,
    k: Vec3<T>,
    mut edge: impl FnMut(Vec3<T>, Vec3<T>, Vec3<T>) -> bool,
) -> bool {
    let kv = [k.x, k.y, k.z];
    let above = |u: Vec3<T>| T::height_nonneg([u.x, u.y, u.z], kv);
    let sub = |a: Vec3<T>, b: Vec3<T>| a.offset_from(b);
    // Fixed point, whose edge terms cost about 500 Cortex-M0 instructions: every vertex's
    // height first, so that no term is computed for a ring the walk must clip (measured: the
    // RP2040 demo's frame 1 11 820 558 -> 11 811 113 cycles; 11 840 841 with the walk alone).
    // The floats' terms are cheaper than the heights' second pass: each vertex tested as it
    // comes (a build of the Cortex-M4F budget's quad alone, wholly lit, 609 -> 581
    // instructions).
    let all_first = T::RESOLUTION > T::ZERO;
    if all_first && !verts.iter().all(|&v| above(sub(v, p))) {
        return false;
    }
    let Some((&first, rest)) = verts.split_first() else {
        return false;
    };
    let u0 = sub(first, p);
    if !(all_first || above(u0)) {
        return false;
    }
    let (mut va, mut ua) = (first, u0);
    for &vb in rest {
        let ub = sub(vb, p);
        if !((all_first || above(ub)) && edge(ua, ub, sub(vb, va))) {
            return false;
        }
        (va, ua) = (vb, ub);
    }
    // The closing edge, back to vertex 0.
    edge(ua, u0, sub(first, va))
}

/// Walks the ring `verts` seen from `p`, clipped to the half-space `(v - p).k >= 0`, and calls
/// `f` with each clipped edge in ring order (see [`ClippedEdge`]); horizon arcs run between a
/// crossing down and the next crossing up. Nothing is called if no vertex is above the
/// horizon. No buffer and no normalization. A vertex exactly on the horizon counts as above.
///
/// Returns, for fixed point, whether a vertex (above the horizon or not) or a horizon
/// crossing lies within `r_min` of `p` by its largest coordinate (the first half of the test
/// of [`near_limit`](super::near_limit); the caller tests the edges beside `p`); for the floats `false`.
///
/// `k` is a unit vector, and `p` and the vertices lie within [`Real::COORDINATE_LIMIT`]
/// (every caller checks them): the offsets `v - p` are then at most 8 in magnitude on fixed
/// point, and their products with `k` need no saturation test (the sealed `dot3_small`, the
/// bits of `Vec3::dot`).
#[inline(always)]
pub(crate) fn for_each_clipped_edge<T: Real, F>(
    verts: &[Vec3<T>],
    p: Vec3<T>,
    k: Vec3<T>,
    r_min: T,
    f: F,
) -> bool
where
    F: FnMut(ClippedEdge<T>),
{
    let kv = [k.x, k.y, k.z];
    for_each_clipped_edge_by(
        verts,
        p,
        r_min,
        |_, u| T::dot3_small([u.x, u.y, u.z], kv),
        f,
    )
}

/// [`for_each_clipped_edge`] with each vertex's height `(v - p).k` from `height(i, v - p)`
/// for the vertex of index `i`: the fixed-point Phong walk's, which takes them from the
/// negligibility test that computed them (the same bits), where the walk itself computes
/// each vertex's height once or twice more (the first vertex's three times).
pub(crate) fn for_each_clipped_edge_by<T: Real, F>(
    verts: &[Vec3<T>],
    p: Vec3<T>,
    r_min: T,
    height: impl Fn(usize, Vec3<T>) -> T,
    mut f: F,
) -> bool
where
    F: FnMut(ClippedEdge<T>),
{
    let near_point = |u: Vec3<T>| T::RESOLUTION > T::ZERO && T::all_within([u.x, u.y, u.z], r_min);
    let nv = verts.len();
    // An edge scaled by a fraction `t` in [0, 1]: `edge * t`, bit for bit, without fixed
    // point's saturation tests (`mul_unit`: the product is at most the edge).
    let scaled = |e: Vec3<T>, t: T| {
        Vec3::new(
            T::mul_unit(e.x, t),
            T::mul_unit(e.y, t),
            T::mul_unit(e.z, t),
        )
    };
    // (The index counted by hand: through `enumerate` the Cortex-M4F demo's per-pixel frame
    // 0 took 19.99 M instructions where it takes 19.89 M, `boards/qemu-frame`.)
    let mut i = 0;
    let Some(start) = verts.iter().position(|&v| {
        let above = height(i, v.offset_from(p)) >= T::ZERO;
        i += 1;
        above
    }) else {
        // Nothing above: only the vertices' distances to test (fixed point).
        return T::RESOLUTION > T::ZERO && verts.iter().any(|&v| near_point(v.offset_from(p)));
    };
    // The ring from `start` round to `start` again: `v0` the edge's first vertex, `v1` its
    // second, the index stepped with a wrap (no division: a library call on the M0; `get`, so
    // no bounds check can panic).
    let Some(&first) = verts.get(start) else {
        return false;
    };
    let (mut v0, mut i1) = (first, start);
    let mut u0 = v0.offset_from(p);
    let mut d0 = height(start, u0);
    // The start of the current clipped edge (a vertex or a crossing up), and its vertex
    // index (or `CROSSING`).
    let mut a0 = u0;
    let mut ia0 = start;
    // (The floats' walks read no index: a constant there, so that none is carried.)
    let index = |i: usize| if T::RESOLUTION > T::ZERO { i } else { CROSSING };
    let mut below0 = false;
    let mut exit: Option<Vec3<T>> = None;
    // (Every vertex is `u1` once, the start last.)
    let mut near = false;
    for _ in 0..nv {
        i1 = if i1 + 1 == nv { 0 } else { i1 + 1 };
        let Some(&v1) = verts.get(i1) else {
            break;
        };
        let u1 = v1.offset_from(p);
        near |= near_point(u1);
        let d1 = height(i1, u1);
        let below1 = d1 < T::ZERO;
        let edge = v1.offset_from(v0);
        v0 = v1;
        match (below0, below1) {
            (false, false) => {
                // Here a0 is the vertex u0, so d is the polygon's own edge.
                f(ClippedEdge {
                    ua: a0,
                    ub: u1,
                    d: edge,
                    horizon: false,
                    ia: index(ia0),
                    ib: index(i1),
                });
                (a0, ia0) = (u1, i1);
            }
            (false, true) => {
                let t = (d0 / (d0 - d1)).clamp01();
                let et = scaled(edge, t);
                let x = u0 + et;
                near |= near_point(x);
                f(ClippedEdge {
                    ua: a0,
                    ub: x,
                    d: et,
                    horizon: false,
                    ia: index(ia0),
                    ib: CROSSING,
                });
                exit = Some(x);
            }
            (true, false) => {
                let t = (d0 / (d0 - d1)).clamp01();
                let x = u0 + scaled(edge, t);
                near |= near_point(x);
                if let Some(e) = exit.take() {
                    f(ClippedEdge {
                        ua: e,
                        ub: x,
                        d: x - e,
                        horizon: true,
                        ia: CROSSING,
                        ib: CROSSING,
                    });
                }
                f(ClippedEdge {
                    ua: x,
                    ub: u1,
                    d: scaled(edge, T::ONE - t),
                    horizon: false,
                    ia: CROSSING,
                    ib: index(i1),
                });
                (a0, ia0) = (u1, i1);
            }
            (true, true) => {}
        }
        u0 = u1;
        d0 = d1;
        below0 = below1;
    }
    near
}
