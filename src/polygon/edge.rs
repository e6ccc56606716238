//! The Lambert edge term of a clipped polygon edge (`theta (G . k)/|G|`, see the module docs
//! of [`crate::polygon`]): the arc-ratio form on backends that have one, the arc-tangent form
//! elsewhere, and the power-of-two rescaling of the cold path that keeps every term scale-free.

use crate::{Real, Vec3};

/// `theta (G . k)/|G|` with `G = ua x d (= ua x ub)` and `theta` the angle between `ua` and
/// `ub`: the edge term of Lambert's formula from unnormalized endpoints. Scale-free, and `G`
/// from the edge vector `d` keeps its accuracy for edges seen nearly end-on.
///
/// On a backend with an arc ratio (f32), an edge within a right angle takes
/// [`edge_ratio_term`], inlined into the caller's loop (no arc tangent, and the edge's
/// vectors stay in registers); every other edge, and every edge on the other backends, takes
/// [`edge_atan_term`] (out of line).
#[inline(always)]
pub(crate) fn edge_angle_term<T: Real>(ua: Vec3<T>, ub: Vec3<T>, d: Vec3<T>, k: Vec3<T>) -> T {
    if T::RESOLUTION == T::ZERO {
        if let Some(term) = edge_ratio_term(ua, ub, ua.cross(d), ua.dot(ub), k) {
            return term;
        }
    }
    edge_atan_term(ua, ub, d, k)
}

/// [`edge_angle_term`] with `theta = atan2(|G|, ua.ub)`: no per-vertex normalization is
/// needed (the form is scale-free).
///
/// Where `G` or `ua.ub` would leave the range in which products are normal and finite
/// ([`products_in_range`]: coordinates beyond about `1/TINY` or below `TINY` in absolute terms,
/// e.g. f32 configurations scaled by `2^64` or `2^-70`) the edge is first scaled by a power of
/// two ([`ClippedEdge::rescaled`](super::ClippedEdge::rescaled), exact), on a cold path: the test costs two comparisons.
#[inline]
pub(super) fn edge_atan_term<T: Real>(ua: Vec3<T>, ub: Vec3<T>, d: Vec3<T>, k: Vec3<T>) -> T {
    let g = ua.cross(d);
    let dot = ua.dot(ub);
    if T::RESOLUTION > T::ZERO {
        return edge_atan_term_fixed(ua, ub, d, k, T::ZERO).0;
    }
    // Floats: where `|G|^2` is a normal, finite number (and `ua.ub` in range), `|G|` and
    // `1/|G|` come from it directly, with no scaling (the hot path: every edge of a scene at
    // any ordinary scale); elsewhere the edge is scaled by a power of two first (cold).
    let gg = g.dot(g);
    let lo = T::TINY * T::TINY;
    let hi = T::ONE / lo;
    if gg >= lo && gg <= hi && dot.abs() <= hi {
        let (s, inv) = gg.sqrt_rsqrt();
        return (s.atan2(dot) * g.dot(k) * inv).finite_or_zero();
    }
    edge_angle_term_rescaled(ua, ub, d, k)
}

/// [`edge_atan_term`] for fixed point, with the test of
/// [`ClippedEdge::lambert_term_resolved`](super::ClippedEdge::lambert_term_resolved):
/// `(term, beside)`, `beside` when the edge subtends more than a right angle (`ua.ub < 0`)
/// and `|G|`'s largest component is below `r_min` times `d`'s: `p` then lies within about
/// `r_min` of the edge's line.
///
/// One exponent, no range to leave; `G` is scaled by its largest component before it is
/// squared. Products too small to keep their relative precision (an edge short and close to
/// `p`) are formed again exactly (cold).
#[inline]
pub(super) fn edge_atan_term_fixed<T: Real>(
    ua: Vec3<T>,
    ub: Vec3<T>,
    d: Vec3<T>,
    k: Vec3<T>,
    r_min: T,
) -> (T, bool) {
    let (g, dot) = offset_products(ua, ub, d);
    let m = g.max_abs();
    let beside = dot < T::ZERO && m < r_min * d.max_abs();
    // One copy of the finish for both paths (flash: the Cortex-M0 budget image).
    let (g, m, dot) = if products_in_range(m, dot.abs()) {
        (g, m, dot)
    } else {
        match rescaled_products(ua, ub, d) {
            Some((g, dot)) => (g, g.max_abs(), dot),
            None => (g, m, dot),
        }
    };
    (edge_angle_finish(g, m, dot, k), beside)
}

/// The hot path of [`edge_angle_term`] for a backend with a cheap [`Real::arc_ratio`] (f32):
/// with `r = 1/(|ua| |ub|)` and `c = (ua.ub) r = cos(theta)`, the term `theta (G.k)/|G|` is
/// `R(c) (G.k) r` (`|G| = |ua| |ub| sin(theta)`, `R = theta/sin(theta)`): one reciprocal
/// square root and a short polynomial in place of `|G|`, its reciprocal and an arc tangent.
/// `None` (the caller takes the arc-tangent form) for an edge subtending more than a right
/// angle (`c < 0`, towards `R`'s singularity at `theta = pi`), for squared lengths outside
/// `[TINY, 1/TINY]` (then `|ua|^2 |ub|^2` might leave the normal range) and for a backend
/// without an arc ratio (decided at compile time).
#[inline(always)]
pub(super) fn edge_ratio_term<T: Real>(
    ua: Vec3<T>,
    ub: Vec3<T>,
    g: Vec3<T>,
    dot: T,
    k: Vec3<T>,
) -> Option<T> {
    T::ONE.arc_ratio()?;
    let (la2, lb2) = (ua.dot(ua), ub.dot(ub));
    let (lo, hi) = (T::TINY, T::ONE / T::TINY);
    if !(la2 >= lo && la2 <= hi && lb2 >= lo && lb2 <= hi) {
        return None;
    }
    let r = (la2 * lb2).rsqrt();
    let c = dot * r;
    if !(c >= T::ZERO) {
        return None;
    }
    Some(c.arc_ratio()? * g.dot(k) * r)
}

/// The sum of [`edge_ratio_term`] over every edge of the ring `verts` seen from `p`, for a
/// ring wholly above the horizon of the unit `k` ([`super::for_each_unclipped_edge`]): the sum
/// the clipping walk ([`super::for_each_clipped_edge`], each edge's
/// [`edge_angle_term`](super::ClippedEdge::lambert_term)) makes there, bit for bit (the same
/// edges from the same vertex, the same products in the same order, the same range tests),
/// each vertex's squared length computed once instead of twice. `None` (the caller walks)
/// where a vertex is below the horizon, an edge subtends more than a right angle or a squared
/// length leaves `[TINY, 1/TINY]` (where the walk takes the arc-tangent form), and for a
/// backend without an arc ratio (decided at compile time). Measured on the Cortex-M4F in f32
/// (QEMU, the budget's quad, 16 inputs): 703 -> 545 instructions where the quad is wholly
/// lit, a cost of about 18 (a vertex's offset and height) where it then walks, 224 -> 242
/// unlit and 756..914 -> 771..929 clipped; the Gouraud demo frame 0 3 176 388 -> 3 164 100
/// instructions, the per-pixel frame 34 020 844 -> 33 796 343.
#[inline(always)]
pub(super) fn unclipped_ratio_sum<T: Real>(verts: &[Vec3<T>], p: Vec3<T>, k: Vec3<T>) -> Option<T> {
    T::ONE.arc_ratio()?;
    let (lo, hi) = (T::TINY, T::ONE / T::TINY);
    let in_range = |l2: T| l2 >= lo && l2 <= hi;
    // The first edge's `|ua|^2`; each edge hands its `|ub|^2` to the next.
    let u0 = *verts.first()? - p;
    let mut la = u0.dot(u0);
    // Each squared length tested once: vertex 0's here, every other as an edge's end (an
    // edge's start passed as the previous edge's end; the closing edge ends at vertex 0).
    if !in_range(la) {
        return None;
    }
    let mut sum = T::ZERO;
    let whole = super::for_each_unclipped_edge(
        verts,
        p,
        k,
        #[inline(always)]
        |ua, ub, d| {
            let lb = ub.dot(ub);
            if !in_range(lb) {
                return false;
            }
            let (g, dot) = (ua.cross(d), ua.dot(ub));
            let r = (la * lb).rsqrt();
            let c = dot * r;
            if !(c >= T::ZERO) {
                return false;
            }
            let Some(ratio) = c.arc_ratio() else {
                return false;
            };
            sum += ratio * g.dot(k) * r;
            la = lb;
            true
        },
    );
    whole.then_some(sum)
}

/// The smallest cosine for which [`unit_ratio_term`] answers: `2^-16`, far above the
/// rounding of a dot product of two unit directions (a few `2^-22` on fixed point), so that an
/// edge it answers has `ua.ub > 0` exactly (the arc-tangent form's test of a point beside the
/// edge, [`edge_atan_term_fixed`]'s `beside`, needs `ua.ub < 0`).
const RATIO_MIN_COS_LOG2: u32 = 16;

/// `theta (G.k)/|G|` from the unit directions `a` and `b` of an edge's endpoints (fixed
/// point's unclipped ring, [`crate::polygon`]'s `lambert_fixed`): `R(c) (a x b).k` with `c =
/// a.b` and `R` the arc ratio (`|a x b| = sin(theta)`): two dot products, a cross product and
/// the ratio's polynomial, where the arc-tangent form takes a rescaling, a square root and
/// its reciprocal and an arc tangent. Each direction is normalized once for its two edges.
/// `None` (the caller takes the arc-tangent form) for an edge subtending a right angle or
/// more (`c` below [`RATIO_MIN_COS_LOG2`]) and for a backend without an arc ratio.
///
/// The directions come in 16-bit form (issue 13's format per quantity): `a` and `b` are unit
/// vectors in Q15 normalized in that form (the sealed `unit3_q15`), `k` the normal's Q22
/// components rounded to Q15 ([`unit_q15`]), so that every product is one 32 x 32 -> 32-bit
/// product (one `MULS` on the Cortex-M0, where a Q22 product takes four and about 12
/// instructions): the cosine and `a x b` in Q30, `(a x b).k` and the ratio (the sealed
/// `arc_ratio_q15`, the same cubic pieces in 32-bit products) in Q15, the term in Q30.
/// Bounds (nothing wraps): the components are at most `2^15 + 1`, so each product is below
/// `2^30 + 2^17`; a dot product or a cross-product component (and each partial sum of one) is
/// at most the lengths' product, below `2^30 (1 + 2^-12)`; the ratio is at most `pi/2`
/// (for `c` at least 0), below `1.6 2^15`, and `(a x b).k` below `2^15 (1 + 2^-11)`: the
/// term below `1.6 2^30`.
///
/// Measured on the Cortex-M0 (QEMU budget, `polygon_lambert` on a quad, wholly lit): 3 832
/// instructions with Q22 products, 3 265 with Q15 products from the Q22 directions, 2 507
/// with the directions normalized in 16-bit form, 2 182 with the ratio in 32-bit products
/// (2 038 with the horizon test's sign from 16-bit products too; 1 744 with a `UnitVec3`
/// normal; later 1 938 and 1 686, the 16-bit normalization's exponent from comparisons in
/// the common band, `fixed22::normalize::top_bit`).
///
/// Accuracy on `Fixed22`: the directions (within 1.1e-4 a component, 5.2e-5 measured; see
/// `unit_q15` of `fixed22::normalize`) and the ratio (within `2^-16 + 4.2e-6`) leave the sum
/// within 6.5e-5 of f64 over `tests/fixed/`'s 10 756 polygon cases (5.5e-6 with Q22
/// directions and products; 6.9e-5 for the world-coordinate lights of `tests/world.rs`, 2.0e-6
/// with Q22): far inside the 1/1024 that `tests/fixed/`, `tests/world.rs` and
/// `tests/fixed_near.rs` hold it to.
#[inline(always)]
pub(crate) fn unit_ratio_term<T: Real>(a: [i32; 3], b: [i32; 3], k: [i32; 3]) -> Option<T> {
    let dot = |x: [i32; 3], y: [i32; 3]| {
        x[0].wrapping_mul(y[0])
            .wrapping_add(x[1].wrapping_mul(y[1]))
            .wrapping_add(x[2].wrapping_mul(y[2]))
    };
    let c = dot(a, b); // Q30
    if c < 1 << (30 - RATIO_MIN_COS_LOG2) {
        return None;
    }
    let cross = |i: usize, j: usize| {
        a[i].wrapping_mul(b[j])
            .wrapping_sub(a[j].wrapping_mul(b[i]))
            >> 15
    };
    // `a x b` and `(a x b).k` in Q15; the ratio of `c` in Q15 (rounded).
    let g = [cross(1, 2), cross(2, 0), cross(0, 1)];
    let kg = dot(k, g) >> 15;
    let ratio = T::arc_ratio_q15(c)?;
    let term = kg.wrapping_mul(ratio); // Q30
    Some(T::from_fixed_i32((term + (1 << 7)) >> 8, 22))
}

/// A unit vector's components (fixed point, Q22 in `T`) rounded to Q15 for
/// [`unit_ratio_term`]: `(x 2^22 + 2^6) >> 7`, at most `2^15` in magnitude.
#[inline(always)]
pub(crate) fn unit_q15<T: Real>(v: [T; 3]) -> [i32; 3] {
    v.map(|x| x.to_fixed_i32(22).wrapping_add(1 << 6) >> 7)
}

/// [`edge_angle_term`] for an edge whose products leave the normal range (fixed point: are too
/// small to keep their relative precision): the same term from the edge scaled by a power of
/// two (0 if it has no finite, non-zero coordinate).
#[cold]
#[inline(never)]
pub(super) fn edge_angle_term_rescaled<T: Real>(
    ua: Vec3<T>,
    ub: Vec3<T>,
    d: Vec3<T>,
    k: Vec3<T>,
) -> T {
    match rescaled_products(ua, ub, d) {
        Some((g, dot)) => edge_angle_finish(g, g.max_abs(), dot, k),
        None => T::ZERO,
    }
}

/// `atan2(|G|, dot) (G . k)/|G|` from `G`, its largest component `m` and `dot = ua.ub`.
#[inline(always)]
pub(super) fn edge_angle_finish<T: Real>(g: Vec3<T>, m: T, dot: T, k: Vec3<T>) -> T {
    if !(m > T::ZERO) || !m.is_finite() {
        return T::ZERO;
    }
    // Scale to avoid overflow of |G|^2 for large coordinates.
    let (g, d) = g.rescale(m);
    // |G| and 1/|G| together (fixed point: one rsqrt, no division). After the rescaling every
    // component of `G` is at most 2 and `k` is a unit vector: the products without fixed
    // point's saturation tests, the bits of `Vec3::dot`.
    let g = [g.x, g.y, g.z];
    let (s, inv) = T::dot3_small(g, g).sqrt_rsqrt();
    let theta = (s * d).atan2(dot);
    // theta <= pi, |G.k| <= |G| <= 2 sqrt(3) and 1/|G| <= 2 (the largest component is at
    // least 1/2): factors below 16 and products below 22, the bits of `*` without fixed
    // point's saturation tests.
    T::mul_small(T::mul_small(theta, T::dot3_small(g, [k.x, k.y, k.z])), inv).finite_or_zero()
}

/// `(ua x d, ua.ub)` of a clipped edge, bit for bit [`Vec3::cross`] and [`Vec3::dot`], for the
/// offsets of positions within [`Real::COORDINATE_LIMIT`] from a point within it (every
/// caller checks both: the light's constructor its vertices, the model function `p`): then
/// `ua` and `ub` (vertices or horizon crossings, between two vertices) have coordinates of at
/// most 8 in magnitude on fixed point, and `d` (their difference) of at most 16. Every product
/// is then below 128 and every sum below 256, where `Fixed22`'s products need no saturation
/// test (its sealed `cross3_small` and `dot3_small`, exact for factors below 16 and results
/// below 512): about 90 fewer Cortex-M0 instructions an edge. The floats: the same operations.
#[inline(always)]
pub(crate) fn offset_products<T: Real>(ua: Vec3<T>, ub: Vec3<T>, d: Vec3<T>) -> (Vec3<T>, T) {
    let a = [ua.x, ua.y, ua.z];
    let [x, y, z] = T::cross3_small(a, [d.x, d.y, d.z]);
    (Vec3::new(x, y, z), T::dot3_small(a, [ub.x, ub.y, ub.z]))
}

/// `(ua x d, ua.ub)` from the edge scaled by a power of two ([`scaled_to_unit`]): the cold
/// path of the edge terms whose products leave the normal range. `None` where
/// [`scaled_to_unit`] has no scale.
#[inline(always)]
pub(crate) fn rescaled_products<T: Real>(
    ua: Vec3<T>,
    ub: Vec3<T>,
    d: Vec3<T>,
) -> Option<(Vec3<T>, T)> {
    // Fixed point: the products exact, then scaled (no rounding before the cancellation).
    if let Some(([x, y, z], dot)) =
        T::cross_dot_scaled([ua.x, ua.y, ua.z], [ub.x, ub.y, ub.z], [d.x, d.y, d.z])
    {
        return Some((Vec3::new(x, y, z), dot));
    }
    if T::RESOLUTION > T::ZERO {
        return None;
    }
    rescaled_products_float(ua, ub, d)
}

/// [`rescaled_products`] for the floats: out of line, so the hot paths that may take it keep
/// their registers (inlined, the Cortex-M4F f32 quad took 12 instructions more).
#[cold]
#[inline(never)]
fn rescaled_products_float<T: Real>(ua: Vec3<T>, ub: Vec3<T>, d: Vec3<T>) -> Option<(Vec3<T>, T)> {
    let [ua, ub, d] = scaled_to_unit_float([ua, ub, d])?;
    Some((ua.cross(d), ua.dot(ub)))
}

/// The smallest product of an edge's coordinates (`|G|`, `|ua.ub|`, `|ua| |ub|`) that fixed
/// point takes as it is: below it the edge is scaled up by a power of two first
/// ([`scaled_to_unit`]). A product's rounding is absolute (`2^-22` in `Fixed22`), so at
/// `1/64` it keeps 16 significant bits; an edge that short lies close to `p` (a few hundredths
/// of the light's largest coordinate, the case of a point near a vertex or a clipped corner),
/// and scaled up its products keep 22 bits more of the coordinates' own precision. Measured
/// (`tests/world.rs`, points near a vertex): without it `polygon_lambert` answered 0.07 for
/// 0.049 at `1e-4` of the polygon's size, 1.0 for 0.001 at `1e-3`.
const FIXED_PRODUCT_MIN: f64 = 1.0 / 64.0;

/// `true` if products of an edge's coordinates are safe.
///
/// Floats: `m` (the largest component of a product such as `G = ua x d`) in
/// `[TINY^2, 1/TINY^2]` and `big` (another product's magnitude, e.g. `|ua.ub|`) at most
/// `1/TINY^2`. Then every product that matters is a normal float (its rounding relative, as at
/// unit scale) and no square of them overflows, so the result is the unit-scale result to the
/// last bit or so.
///
/// Fixed point (one exponent: no range to leave, but an absolute rounding): the larger of `m`
/// and `big` at least [`FIXED_PRODUCT_MIN`], so that the products keep their relative
/// precision.
#[inline(always)]
pub(crate) fn products_in_range<T: Real>(m: T, big: T) -> bool {
    if T::RESOLUTION > T::ZERO {
        return !(m.max(big) < T::from_f64(FIXED_PRODUCT_MIN));
    }
    let lo = T::TINY * T::TINY;
    let hi = T::ONE / lo;
    m >= lo && m <= hi && big <= hi
}

/// `vs` scaled by one power of two, `2^-e` with `2^e <= m < 2^(e+1)` for `m` their largest
/// component, so that `m` lands in [1, 2): exact (only exponents change; fixed point: a left
/// shift of every component), so a configuration and its scaled copies give the same bits.
/// The cold path of the polygon terms (the terms are scale-free). `None` if `m` is 0 or not
/// finite. Cost: floats, a conversion to f64 and back, 6 products per vector; fixed point, the
/// largest component's leading bit and 3 shifts per vector.
#[inline(always)]
pub(crate) fn scaled_to_unit<T: Real, const K: usize>(vs: [Vec3<T>; K]) -> Option<[Vec3<T>; K]> {
    if T::RESOLUTION > T::ZERO {
        return scaled_to_unit_fixed(vs);
    }
    scaled_to_unit_float(vs)
}

/// [`scaled_to_unit`] for fixed point: [`Real::rescale3`] of each vector by the largest
/// component of them all (its power of two from that component's leading bit: the same shift
/// for every vector; up, exact, for the short edges this path takes).
#[cold]
#[inline(never)]
fn scaled_to_unit_fixed<T: Real, const K: usize>(vs: [Vec3<T>; K]) -> Option<[Vec3<T>; K]> {
    let m = vs.iter().fold(T::ZERO, |acc, v| acc.max(v.max_abs()));
    if !(m > T::ZERO) {
        return None;
    }
    Some(vs.map(|v| {
        let ([x, y, z], _) = T::rescale3([v.x, v.y, v.z], m);
        Vec3::new(x, y, z)
    }))
}

#[cold]
#[inline(never)]
pub(super) fn scaled_to_unit_float<T: Real, const K: usize>(
    vs: [Vec3<T>; K],
) -> Option<[Vec3<T>; K]> {
    let m = vs
        .iter()
        .fold(T::ZERO, |acc, v| acc.max(v.max_abs()))
        .to_f64();
    if !(m > 0.0) || !m.is_finite() {
        return None;
    }
    // Two factors, each representable in T (f32: 2^-e reaches 2^149).
    let e = libm::ilogb(m);
    let e1 = -e / 2;
    let f1 = T::from_f64(libm::ldexp(1.0, e1));
    let f2 = T::from_f64(libm::ldexp(1.0, -e - e1));
    Some(vs.map(|v| v * f1 * f2))
}
