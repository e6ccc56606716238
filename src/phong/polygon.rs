//! The polygon light's Phong terms (Snyder eq. 25, appendices G-H): the walk round the
//! clipped ring, each edge's `J` terms by the recurrence of [`cos_power_sums`], and for even
//! `m` the clipped solid angle as the fan of Van Oosterom-Strackee triangles. See the module
//! docs of [`crate::phong`].

use crate::lobe::negligible_terms;
use crate::polygon::{
    arc_axis_f, clamp_excursion, cos_power_sums, floats_ball_below, for_each_clipped_edge,
    for_each_clipped_edge_by, near_limit, offset_products, phong_near_log2, phong_negligible_with,
    products_in_range, ClippedEdge, PolygonLight, Uncached, VertexDirections, CROSSING,
    NEGLIGIBLE_HEIGHTS,
};
use crate::unit::Direction;
use crate::{Error, PhongLobe, Real, UnitVec3, Vec3};

/// One polygon edge's Phong terms `(w, j)` for the exponent `m`: `w` the fan's triangle
/// `(r, ua, ub)` (the clipped solid angle, even `m`; 0 for odd `m`) and `j` the edge's `J`
/// terms, from `G = ua x d`, `ua.ub` and the directions of its endpoints (`a = ua/|ua|` with
/// `r.a`, and `r.b`). `None` for an edge seen end-on (`G` without a direction) or whose `|G|`
/// or `ua.ub` leave the range where products are normal and finite ([`products_in_range`]).
#[inline(always)]
fn phong_edge_terms<T: Real>(
    g: Vec3<T>,
    dot: T,
    (ua, ra): (UnitVec3<T>, T),
    rb: T,
    r: UnitVec3<T>,
    m: u32,
) -> Option<(T, T)> {
    // An edge seen end-on (G = 0): x = 0 contributes nothing.
    let (gu, glen) = g.normalize_with_length()?;
    let gu = UnitVec3::new_unchecked(gu);
    // G and ua.ub computed from subnormal or overflowing products (fixed point: too small to
    // keep their precision): rescale (the caller).
    if !products_in_range(glen, dot.abs()) {
        return None;
    }
    // x = angle(ua, ub) with a consistent (cos x, sin x) pair from (ua.ub, |G|), both
    // proportional to |ua| |ub|: the pair normalized.
    // (`unit3` itself, inlined, so that the zero third component folds away where
    // `Vec3::normalize` stays a call: the Cortex-M0 budget's `opt-level = "s"`, about 1.7 %
    // of `phong_polygon`; the same bits.)
    let [cx, cy, _] = T::unit3([dot, glen, T::ZERO])?;
    let cs = Vec3::new(cx, cy, T::ZERO);
    let (cos_x, sin_x) = (
        clamp_excursion(cs.x, |v| v.clamp(-T::ONE, T::ONE)),
        clamp_excursion(cs.y, T::clamp01),
    );
    // x itself (odd m): on a float backend with an arc ratio (f32 and `Fast32` with an FPU)
    // and within a right angle, `R(cos x) sin x` from the pair, as `fan_half_angle` does;
    // elsewhere the arc tangent (fixed point keeps its bits: its unit edges take the ratio in
    // `phong_unit_edge_terms`).
    let angle = || match cos_x.arc_ratio() {
        Some(ratio) if T::RESOLUTION == T::ZERO && cos_x >= T::ZERO => ratio * sin_x,
        _ => glen.atan2(dot),
    };
    let rg = r.dot_unit(gu);
    Some(phong_arc_terms(
        (rg, || r.triple(gu, ua)),
        (cos_x, sin_x),
        angle,
        ra,
        rb,
        m,
    ))
}

/// [`phong_edge_terms`] from `rg = r.gu` (`gu` the edge plane's unit normal), `rp` giving `r.(gu
/// x ua)` (the arc's form, `arc_axis_form`'s `b`; needed for `m > 0`) and the `(cos x, sin
/// x)` pair of the angle `x` the edge subtends; `x` itself, where needed (odd `m`), from
/// `angle`.
#[inline(always)]
fn phong_arc_terms<T: Real>(
    (rg, rp): (T, impl FnOnce() -> T),
    (cos_x, sin_x): (T, T),
    angle: impl FnOnce() -> T,
    ra: T,
    rb: T,
    m: u32,
) -> (T, T) {
    let even = m & 1 == 0;
    let w = if even {
        // Van Oosterom and Strackee's triangle (r, ua, ub), as `ApexFan::add`:
        // r.(ua x ub)/(|ua| |ub|) = (r.gu) sin x over 1 + cos x + r.ua + r.ub.
        // (Twice the angle as a sum: the bits of `2 *`, without a product.)
        let half = fan_half_angle(T::mul_le2(rg, sin_x), T::ONE + cos_x + ra + rb);
        half + half
    } else {
        T::ZERO
    };
    if m == 0 {
        return (w, T::ZERO);
    }
    let rp = rp();
    let f = arc_axis_f(rg, ra, rp);
    // x itself enters only the sums of even order (odd m).
    let x = if even { T::ZERO } else { angle() };
    // T_sum(a, b, m - 1, x) of Snyder appendix G: every T(k), k = m - 1, m - 3, ...
    let (sum, last) = cos_power_sums(m - 1, x, cos_x, sin_x, ra, rp, f, None);
    (w, rg * (sum + last))
}

/// `atan2(y, x)`, half the solid angle of a Van Oosterom and Strackee triangle (`y` its triple
/// product, `x` the sum of one and its three cosines). On a float backend with an arc ratio
/// (f32 and `Fast32` with an FPU) and for `x > 0` (a half angle within a right angle), `R(c)
/// s` with `c = x/h`, `s = y/h`, `h = sqrt(x^2 + y^2)` and `R = theta/sin(theta)`
/// ([`Real::arc_ratio`]): one reciprocal square root and the ratio's polynomial instead of the
/// arc tangent's division and polynomial, about 11 Cortex-M4F instructions fewer an edge as
/// compiled (`phong_polygon` at m = 16 1 839 -> 1 797 with a `Vec3`). f32 within a few ULPs as
/// the arc tangent (the ratio 1.58 ULP, `c` and `s` 1.5 each; `tests/phong.rs`: at m = 0 1.0e-7
/// -> 1.8e-7 adversarial, 1.8e-7 -> 1.4e-7 random); `Fast32` about ten times closer than with
/// its 1/1024 arc tangent (at m = 0 2.9e-5 -> 3.1e-6). Elsewhere, and where `h^2` is below `TINY` (then its reciprocal
/// square root might leave the normal range), the arc tangent.
#[inline(always)]
fn fan_half_angle<T: Real>(y: T, x: T) -> T {
    // `x >= TINY` (NaN fails it): `h^2 >= x^2` is then a normal number, and `1/h` finite.
    if T::RESOLUTION == T::ZERO && T::ONE.arc_ratio().is_some() && x >= T::TINY {
        let r = (x * x + y * y).rsqrt();
        if let Some(ratio) = (x * r).arc_ratio() {
            return ratio * (y * r);
        }
    }
    y.atan2(x)
}

/// The smallest `cos x` for which an edge's Phong terms come from its endpoints'
/// unit directions ([`phong_unit_edge_terms`]): `2^-16`, far above the rounding of their dot
/// product, so that such an edge has `ua.ub > 0` (never the test's `beside`, which needs
/// `ua.ub < 0`) and lies away from `G`'s cancellation near the edge's line between its
/// endpoints.
const UNIT_MIN_COS_LOG2: u32 = 16;

/// The largest `m` for which the floats with an arc ratio (f32 and `Fast32` on targets with an
/// FPU) take [`phong_unit_edge_terms`]. Its plane comes from `a x b` of the rounded unit
/// directions, whose direction is off by about `EPSILON/sin x` (the offsets' `ua x d` keeps
/// it to an ULP), and the recurrence raises that to the power `m`: the absolute error of an
/// edge's terms grows as `m EPSILON` where the offsets' form stays near `EPSILON`. Measured
/// against f64 (`tests/phong.rs`, `tests/adversarial.rs`): with every `m` on the unit path,
/// m = 0 to 3 were more accurate (the adversarial m = 0 1.8e-7 -> 1.0e-7), m = 63 and 64 up
/// to 1.2 times less, and a random triangle at m = 255 2.05e-6 (the offsets' 1.2e-6). Up to
/// 32 it is taken: the Cortex-M4F's f32 `phong_polygon` at m = 15 (the bars' quad, in a
/// build of that case alone) 1 715 -> 1 634 instructions, about 27 an edge, from the
/// offsets' products, range test and two normalizations it spares.
const FLOAT_UNIT_EDGE_MAX_M: u32 = 32;

/// Whether a float backend takes [`phong_unit_edge_terms`] at the exponent `m`: one with an
/// arc ratio (decided at compile time), up to [`FLOAT_UNIT_EDGE_MAX_M`].
#[inline(always)]
fn float_unit_edges<T: Real>(m: u32) -> bool {
    T::RESOLUTION == T::ZERO && m <= FLOAT_UNIT_EDGE_MAX_M && T::ONE.arc_ratio().is_some()
}

/// The unit direction `a` of vertex `i` (at `v`) from `p`, and `r.a`.
#[inline(always)]
fn vertex_dir<T: Real, D: VertexDirections<T>>(
    dirs: &mut D,
    i: usize,
    v: Vec3<T>,
    (p, r_min): (Vec3<T>, T),
    r: UnitVec3<T>,
) -> Option<(UnitVec3<T>, T)> {
    let u = v.offset_from(p);
    if T::RESOLUTION > T::ZERO && T::all_within([u.x, u.y, u.z], r_min) {
        return None;
    }
    let a = dirs.get(i, u)?;
    Some((a, r.dot_unit(a)))
}

/// [`unclipped_unit_terms`] as a call (fixed point): inlined, its frame joined the walk's,
/// and the Cortex-M0 scene benchmark of the QEMU budget overflowed the micro:bit's 16 KiB of
/// stack.
#[inline(never)]
fn unclipped_unit_terms_call<T: Real, D: VertexDirections<T>>(
    ring: (&[Vec3<T>], Vec3<T>, T),
    r: UnitVec3<T>,
    m: u32,
    dirs: &mut D,
) -> Option<(T, T)> {
    unclipped_unit_terms(ring, r, m, dirs)
}

/// Whether every vertex of `verts` lies on or above the horizon of `r` seen from `p`, as the
/// walk tests it (`height`: fixed point's from the negligibility test where it has them).
#[inline(always)]
fn ring_above<T: Real>(
    verts: &[Vec3<T>],
    p: Vec3<T>,
    height: &impl Fn(usize, Vec3<T>) -> T,
    r: UnitVec3<T>,
) -> bool {
    let mut i = 0;
    verts.iter().all(|v| {
        let u = v.offset_from(p);
        if T::RESOLUTION > T::ZERO {
            let h = height(i, u);
            i += 1;
            h >= T::ZERO
        } else {
            T::dot3_small([u.x, u.y, u.z], r.array()) >= T::ZERO
        }
    })
}

/// The `(J sum, fan)` of a ring `verts` wholly above the horizon of `r` (every vertex's
/// height `(v - p).r` at least 0, as the walk tests it: the caller's [`ring_above`]) whose
/// every edge takes [`phong_unit_edge_terms`] (fixed point, and the
/// floats where [`float_unit_edges`]): each vertex's unit direction and `r.a` once, each
/// edge's terms from them, in the walk's order from vertex 0, so the same bits as the clipping
/// walk ([`for_each_clipped_edge`], [`for_each_clipped_edge_by`]) gives such a ring, without
/// its crossing tests, its edge records and the offsets it passes. `None` (the caller walks)
/// where a vertex lies below the horizon, a direction is undefined, an edge is a right angle
/// or wider, or (fixed point) a vertex lies within `r_min` of `p`, which the walk reports.
/// The heights come first ([`ring_above`]), so that a ring the walk must clip costs a height
/// a vertex up to the first below. Measured (QEMU budget, the bars' quad at m = 15, in a build
/// of that case alone): on the Cortex-M4F in f32 a wholly lit call 1 595 -> 1 132
/// instructions (with a `UnitVec3` 1 569 -> 1 097), one the walk clips 22 to 26 more; on the
/// Cortex-M0 in `Fixed22` 8 681 -> 7 900 (with a `UnitVec3` 8 475 -> 7 690), one the walk
/// clips as before (the heights are the negligibility test's), the budget's median 7 936 ->
/// 7 900 and 7 747 -> 7 690. Flash: the copy of the edge terms and the recurrence this path
/// takes (`phong` alone, size probe) 41 492 -> 49 256 bytes on the Cortex-M0 in `Fixed22`,
/// 30 552 -> 34 224 on the Cortex-M4F in f32.
#[inline(always)]
fn unclipped_unit_terms<T: Real, D: VertexDirections<T>>(
    (verts, p, r_min): (&[Vec3<T>], Vec3<T>, T),
    r: UnitVec3<T>,
    m: u32,
    dirs: &mut D,
) -> Option<(T, T)> {
    let (&first, rest) = verts.split_first()?;
    let a0 = vertex_dir(dirs, 0, first, (p, r_min), r)?;
    let (mut a, mut sum, mut fan) = (a0, T::ZERO, T::ZERO);
    let mut i = 0;
    for &v in rest {
        i += 1;
        let b = vertex_dir(dirs, i, v, (p, r_min), r)?;
        let (w, j) = phong_unit_edge_terms(a, b, r, m)?;
        fan += w;
        sum += j;
        a = b;
    }
    let (w, j) = phong_unit_edge_terms(a, a0, r, m)?;
    Some((sum + j, fan + w))
}

/// [`phong_edge_terms`] for an edge within a right angle (`cos x` at least
/// [`UNIT_MIN_COS_LOG2`]; fixed point at every `m`, the floats with an arc ratio up to
/// [`FLOAT_UNIT_EDGE_MAX_M`]), from the unit directions `a` and `b` of its endpoints, which the
/// walk normalizes anyway: `cos x = a.b`, `sin x = |G|` with `G = a x b`, and the plane's normal
/// `G/|G|` enters only through `r.G/|G|` and the arc's `r.(G x a)/|G| = (r.b - (a.b)
/// r.a)/|G|`, all three from one reciprocal square root of `G` scaled by a power of two (the
/// sealed `edge_plane_terms`). That spares the offsets' products (`ua x d`, `ua.ub`), the
/// range and near-line tests, the `(cos x, sin x)` pair's own normalization, and the unit
/// normal's three products and its triple product (nine). `None` (the caller takes
/// [`phong_edge_terms`]) for a wider edge or a `G` without a direction.
///
/// Accuracy: `a x b` is within a few `2^-22` absolute (the floats: a few `EPSILON`), and
/// `r.b - (a.b) r.a` likewise, so
/// the plane's two cosines within that over `sin x`; every term they enter is a multiple of
/// `x` (the arc's length), so the error stays a few `2^-22` absolute per edge (against f64,
/// `tests/fixed.rs`: 4.7e-6 -> 5.5e-6 at m = 64, 1.08e-5 -> 1.0e-5 at m = 255 when the
/// triple product went). Cost on the Cortex-M0, `phong_polygon` at m = 16 with a
/// `UnitVec3`: 9 797 -> 9 503 instructions, then 9 367 with `sin x` scaled back by a shift
/// (`fixed22::normalize::unscale_length`) instead of a product.
#[inline(always)]
fn phong_unit_edge_terms<T: Real>(
    (a, ra): (UnitVec3<T>, T),
    (b, rb): (UnitVec3<T>, T),
    r: UnitVec3<T>,
    m: u32,
) -> Option<(T, T)> {
    let (c, g) = a.dot_and_cross(b);
    if !(c >= T::from_fixed_i32(1, UNIT_MIN_COS_LOG2)) {
        return None;
    }
    // `G = a x b` unnormalized: `r.gu`, the arc's `r.(gu x a)` and `sin x = |G|` from one
    // reciprocal square root, the latter as `(r.b - (a.b) r.a)/|G|` (`(a x b) x a = b - (a.b)
    // a`), without `gu` or the triple product (the sealed `edge_plane_terms`).
    let d = rb - T::mul_le2(c, ra);
    let (rg, rp, s) = T::edge_plane_terms([g.x, g.y, g.z], r.array(), d)?;
    let (cos_x, sin_x) = (
        clamp_excursion(c, |v| v.min(T::ONE)),
        clamp_excursion(s, T::clamp01),
    );
    // x = R(cos x) sin x by the arc ratio where the backend has one (fixed point: 3 products
    // for the arc tangent's division and polynomial), else the arc tangent.
    Some(phong_arc_terms(
        (
            rg,
            #[inline(always)]
            || clamp_excursion(rp, |v| v.clamp(-T::ONE, T::ONE)),
        ),
        (cos_x, sin_x),
        || match cos_x.arc_ratio() {
            Some(ratio) => T::mul_le2(ratio, sin_x),
            None => sin_x.atan2(cos_x),
        },
        ra,
        rb,
        m,
    ))
}

/// Fixed point's horizon arc in the Phong walk: [`horizon_unit_angle`] from the unit
/// directions of its ends (the exit's from `last` where the last edge ended there, else its
/// own; the entry's left in `last` for the next edge, which starts there), else
/// [`ClippedEdge::horizon_angle`]. Not inlined: the walk's edges that are not on the horizon
/// then keep their code nearly as it was (inlined, this cost the unclipped cases of the
/// Cortex-M0 budget 20 instructions each; as a call, 7, against about 150 fewer for a clipped
/// one: `phong_polygon` at m = 16 with a `UnitVec3` 9 265 -> 9 105).
#[inline(never)]
fn horizon_arc_fixed<T: Real>(
    e: &ClippedEdge<T>,
    last: &mut Option<(Vec3<T>, UnitVec3<T>, T)>,
    r: UnitVec3<T>,
) -> T {
    // (Its ends are crossings: their directions their own.)
    let a = match *last {
        Some((at, dir, _)) if at == e.ua => Some(dir),
        _ => e.ua.to_unit(),
    };
    let b = e.ub.to_unit();
    // (The entry lies on the horizon: `r.b` is 0, up to the roundings of `b`.)
    *last = b.map(|b| (e.ub, b, T::ZERO));
    match a.zip(b).and_then(|(a, b)| horizon_unit_angle(a, b, r)) {
        Some(angle) => angle,
        None => e.horizon_angle(r.into_inner()),
    }
}

/// A horizon arc's signed angle (as [`ClippedEdge::horizon_angle`] measures it: `r.(a x b)`'s
/// sign) from the unit directions `a`, `b` of its ends, for an arc within a right angle (`a.b
/// >= 0`): `R(a.b) r.(a x b)` with the arc ratio `R(c) = acos(c)/sqrt(1 - c^2)` (the ends lie on
/// the horizon of `r`, so `a x b` is along `r` and `r.(a x b) = +-sin x`). The walk normalizes
/// both ends anyway (the edges beside the arc start and end there), so this takes a cross
/// product, two dot products and the ratio where the offsets' form takes nine exact products
/// and an arc tangent. `None` (the caller takes the offsets' form, which keeps the sign of an
/// arc of nearly pi, whose unit cross product is mostly rounding) for a wider arc or a backend
/// without an arc ratio. Fixed point only: the error is that of `a` and `b` (a few `2^-22`),
/// times at most `pi/2`.
#[inline(always)]
fn horizon_unit_angle<T: Real>(a: UnitVec3<T>, b: UnitVec3<T>, r: UnitVec3<T>) -> Option<T> {
    let (c, g) = a.dot_and_cross(b);
    if !(c >= T::ZERO) {
        return None;
    }
    let ratio = c.min(T::ONE).arc_ratio()?;
    // |r.(a x b)| <= 1 (a few units past it at most), the ratio at most pi/2.
    Some(T::mul_le2(ratio, T::dot3_le2(r.array(), [g.x, g.y, g.z])))
}

/// [`phong_edge_terms`] from the edge's offsets: `G = ua x d` and `ua.ub` (fixed point: with
/// the test of a `p` beside the edge, which sets `beside`, and where `G` is small its products
/// again, exact or scaled; cold).
#[inline(always)]
fn offset_edge_terms<T: Real>(
    e: &ClippedEdge<T>,
    a: (UnitVec3<T>, T),
    rb: T,
    r: UnitVec3<T>,
    m: u32,
    r_min: T,
    beside: &mut bool,
) -> Option<(T, T)> {
    // (`p` and the vertices are within the coordinate limit: the offsets' products without
    // fixed point's saturation tests, the same bits.)
    let (g, dot) = offset_products(e.ua, e.ub, e.d);
    let (g, dot) = if T::RESOLUTION > T::ZERO {
        let gm = g.max_abs();
        *beside |= dot < T::ZERO && gm < r_min * e.d.max_abs();
        if gm < T::from_fixed_i32(1, EXACT_NEAR_LINE_LOG2) {
            small_g_products(e, g, dot, gm)
        } else {
            (g, dot)
        }
    } else {
        (g, dot)
    };
    phong_edge_terms(g, dot, a, rb, r, m)
}

/// `(G, ua.ub)` of an edge for [`phong_edge_terms`] whose `G` (largest component `gm`) is below
/// `2^-4`, from its own products `g` and `dot`, except where fixed point would lose `G`'s
/// direction to rounding: with `p` near the edge's line, `|G|` below `2^-4 |d|`
/// ([`EXACT_NEAR_LINE_LOG2`]), `G` and `ua.ub` are formed exactly and scaled
/// ([`Real`]'s sealed `cross_dot_scaled`; the terms are scale-free); a short edge elsewhere
/// (products below 1/64) is scaled up by shifts first. Measured on points near the boundary of
/// random polygons (`tests/fixed_near.rs`): at `m = 128..255`, 1.8e-3 with the
/// rounded `G` against 4.3e-4 exact, `p` 2^-8 from the boundary.
#[cold]
#[inline(never)]
fn small_g_products<T: Real>(e: &ClippedEdge<T>, g: Vec3<T>, dot: T, gm: T) -> (Vec3<T>, T) {
    if gm < T::from_fixed_i32(1, EXACT_NEAR_LINE_LOG2) * e.d.max_abs() {
        if let Some(([x, y, z], dot)) = T::cross_dot_scaled(
            [e.ua.x, e.ua.y, e.ua.z],
            [e.ub.x, e.ub.y, e.ub.z],
            [e.d.x, e.d.y, e.d.z],
        ) {
            return (Vec3::new(x, y, z), dot);
        }
    } else if !products_in_range(gm, dot.abs()) {
        // A short edge, not near its line: the products of the edge scaled up (shifts) keep
        // their precision (and stay in range for `phong_edge_terms`).
        if let Some(s) = e.rescaled() {
            return (s.ua.cross(s.d), s.ua.dot(s.ub));
        }
    }
    (g, dot)
}

/// [`small_g_products`]' thresholds, `2^-4`: a `G` that small, and `p` within about `|d|/16`
/// of the edge's line.
const EXACT_NEAR_LINE_LOG2: u32 = 4;

/// [`phong_edge_terms`] from the edge scaled by a power of two (exact; the terms are
/// scale-free): the cold path for an edge whose coordinates or products leave the normal range
/// at its own scale. `None` for an endpoint or `G` that still has no direction.
#[cold]
#[inline(never)]
fn phong_edge_terms_rescaled<T: Real>(
    e: &ClippedEdge<T>,
    r: UnitVec3<T>,
    m: u32,
) -> Option<(T, T)> {
    let s = e.rescaled()?;
    let a = s.ua.to_unit()?;
    let b = s.ub.to_unit()?;
    phong_edge_terms(
        s.ua.cross(s.d),
        s.ua.dot(s.ub),
        (a, r.dot_unit(a)),
        r.dot_unit(b),
        r,
        m,
    )
}

impl<T: Real, const N: usize> PolygonLight<T, N> {
    /// `[phong_polygon]` with precise errors: see [`PolygonLight::phong`].
    ///
    /// # Errors
    /// [`Error::NotFinite`] for `p` or `r`, [`Error::ZeroLength`] for `r`,
    /// [`Error::Unresolved`] for a fixed-point `p` within the type's rounding of the plane, over
    /// the face or near its edges, and for a fixed-point `p` within `2^-8` (`m < 128`) or
    /// `2^-7` of a vertex or of an edge beside it (see [`PolygonLight::try_lambert`]).
    pub fn try_phong(
        &self,
        lobe: &PhongLobe<T>,
        p: Vec3<T>,
        r: impl Direction<T>,
    ) -> Result<T, Error> {
        p.check_position("p")?;
        self.phong_at(lobe, p, r, self.in_plane(p))
    }

    /// [`PolygonLight::try_phong`] for a `p` within the coordinate limit whose
    /// [`PolygonLight::in_plane`] test is `plane` (computed once for both terms by the
    /// polygon's [`Illuminant::diffuse_and_phong`](crate::Illuminant::diffuse_and_phong)).
    #[inline]
    pub(crate) fn phong_at(
        &self,
        lobe: &PhongLobe<T>,
        p: Vec3<T>,
        r: impl Direction<T>,
        plane: bool,
    ) -> Result<T, Error> {
        self.phong_at_with(lobe, p, r, plane, &mut Uncached)
    }

    /// [`PolygonLight::phong_at`] with the vertices' unit directions from `p` taken from (and
    /// added to) `dirs`, which the negligibility test shares ([`VertexDirs`]; the Lambert
    /// term takes its own, in 16-bit form).
    #[inline(always)]
    pub(crate) fn phong_at_with<D: VertexDirections<T>>(
        &self,
        lobe: &PhongLobe<T>,
        p: Vec3<T>,
        r: impl Direction<T>,
        plane: bool,
        dirs: &mut D,
    ) -> Result<T, Error> {
        let ru = r.try_unit("r")?;
        let r = ru.into_inner();
        let m = lobe.m;
        let r_min = near_limit::<T>(phong_near_log2(m));
        if plane {
            self.resolved_in_plane(p, r_min)?;
            return Ok(T::ZERO);
        }
        // Fixed point, f32 and Fast32: a term provably below 2^-24 is 0
        // (`polygon/negligible.rs`).
        // (Fixed point: the vertices' heights, which the test leaves for the walk below.)
        let mut heights = [T::ZERO; NEGLIGIBLE_HEIGHTS];
        let mut have_heights = 0;
        if T::RESOLUTION > T::ZERO {
            if phong_negligible_with(
                self.vertices(),
                self.ball(),
                p,
                ru,
                lobe,
                r_min,
                dirs,
                (&mut heights, &mut have_heights),
            ) {
                return Ok(T::ZERO);
            }
        } else if negligible_terms::<T>() && floats_ball_below(self.ball(), p, ru, lobe) {
            return Ok(T::ZERO);
        }
        let even = m & 1 == 0;
        let rv = [r.x, r.y, r.z];
        let height = |i: usize, u: Vec3<T>| match heights.get(i) {
            Some(&h) if i < have_heights => h,
            _ => T::dot3_small([u.x, u.y, u.z], rv),
        };
        // A ring wholly above the horizon with every edge within a right angle: the edges'
        // terms from the vertices' unit directions, without the clipping walk (the same bits
        // as the walk).
        if (T::RESOLUTION > T::ZERO || float_unit_edges::<T>(m))
            && ring_above(self.vertices(), p, &height, ru)
        {
            let ring = (self.vertices(), p, r_min);
            let terms = if T::RESOLUTION > T::ZERO {
                unclipped_unit_terms_call(ring, ru, m, dirs)
            } else {
                unclipped_unit_terms(ring, ru, m, dirs)
            };
            if let Some((sum, fan)) = terms {
                let total = if even { sum + fan } else { sum };
                return Ok((total.abs() * T::FRAC_1_TAU).clamp01());
            }
        }
        let mut beside = false;
        let mut sum = T::ZERO;
        // The solid angle of the clipped projection (even m), as `ApexFan` sums it, from the
        // quantities the Phong terms compute anyway.
        let mut fan = T::ZERO;
        // The last edge's end, its direction and r . direction: the next edge starts there
        // unless a horizon arc came between, so each vertex is normalized once.
        let mut last: Option<(Vec3<T>, UnitVec3<T>, T)> = None;
        // (Fixed point) the walk's first vertex: its index, direction and r . direction, for
        // the edge that closes the ring there, which would normalize it a second time (with
        // `Uncached` directions: `phong_polygon` 9 351 -> 9 104 Cortex-M0 and 7 337 -> 7 118
        // RV32IMC instructions, the same bits). The floats keep the second normalization: with
        // this alone the Cortex-M4F's f32 went 1 803 -> 1 806 (1 821 with the test on their
        // walk too; 1 803 again after the walk took the heights, `for_each_clipped_edge_by`).
        let mut first: Option<(usize, (UnitVec3<T>, T))> = None;
        let edge = |e: ClippedEdge<T>| {
            if e.horizon {
                // On the horizon r.u = 0: only the k = 0 term survives, x (r.G) = +-x; for even
                // m the fan's triangle is the same signed arc. Fixed point takes an arc within a
                // right angle from its ends' unit directions (`horizon_unit_angle`): the exit's
                // from the last edge, the entry's kept for the next, which starts there.
                // (The floats' two calls as they were: with one call site the Cortex-M4F took 13
                // instructions more; as written, 6.)
                if T::RESOLUTION > T::ZERO {
                    let angle = horizon_arc_fixed(&e, &mut last, ru);
                    if even {
                        fan += angle;
                    } else {
                        sum += angle;
                    }
                } else if even {
                    fan += e.horizon_angle(r);
                } else {
                    sum += e.horizon_angle(r);
                }
                return;
            }
            // (A vertex's direction from `dirs`, which the negligibility test may have
            // normalized already; a crossing's its own.)
            // (Without a cache the call of `to_unit`, as before it: measured cheaper in this
            // walk than the inlined normalization.)
            let mut unit = |i: usize, u: Vec3<T>| {
                if D::CACHED && i != CROSSING {
                    dirs.get(i, u)
                } else {
                    u.to_unit()
                }
            };
            let start = match last {
                Some((at, dir, rd)) if at == e.ua => Some((dir, rd)),
                _ => unit(e.ia, e.ua).map(|a| (a, ru.dot_unit(a))),
            };
            // Fixed point: the first vertex's direction kept for the edge that ends there
            // (the ring's last; a vertex ends one edge of the walk, so a later start does no
            // harm).
            let end = if T::RESOLUTION > T::ZERO {
                if first.is_none() && e.ia != CROSSING {
                    first = start.map(|a| (e.ia, a));
                }
                match first {
                    Some((i, b)) if i == e.ib => Some(b),
                    // (A crossing lies on the horizon: `r.b` is 0, up to the roundings of
                    // `b`; its dot product spared.)
                    _ if e.ib == CROSSING => unit(e.ib, e.ub).map(|b| (b, T::ZERO)),
                    _ => unit(e.ib, e.ub).map(|b| (b, ru.dot_unit(b))),
                }
            } else {
                unit(e.ib, e.ub).map(|b| (b, ru.dot_unit(b)))
            };
            last = end.map(|(b, rb)| (e.ub, b, rb));
            // An edge whose coordinates or products leave the normal range at this scale
            // (below TINY or beyond 1/TINY in absolute terms): the same edge scaled by a power
            // of two (cold; the terms are scale-free). What still has no direction then (an
            // edge shorter than TINY relative to its distance, seen end-on) is dropped from
            // the J terms and the fan alike.
            let terms = match (start, end) {
                (Some(a), Some(b)) => {
                    let unit = if T::RESOLUTION > T::ZERO || float_unit_edges::<T>(m) {
                        phong_unit_edge_terms(a, b, ru, m)
                    } else {
                        None
                    };
                    match unit {
                        Some(terms) => Some(terms),
                        None => offset_edge_terms(&e, a, b.1, ru, m, r_min, &mut beside),
                    }
                }
                _ => None,
            };
            // (Fixed point never needs it: `exact_if_small` hands it `G` and `ua.ub` in range.)
            let Some((w, j)) = terms.or_else(|| {
                if T::RESOLUTION > T::ZERO {
                    None
                } else {
                    phong_edge_terms_rescaled(&e, ru, m)
                }
            }) else {
                return;
            };
            if even {
                fan += w;
            }
            sum += j;
        };
        // (The floats' walk computes its own heights: through the closure above the Cortex-M4F
        // demo's per-pixel frame 0 took 19.89 M instructions where it takes 19.99 M,
        // `boards/qemu-frame`.)
        let near = if T::RESOLUTION > T::ZERO {
            for_each_clipped_edge_by(self.vertices(), p, r_min, height, edge)
        } else {
            for_each_clipped_edge(self.vertices(), p, r, r_min, edge)
        };
        if T::RESOLUTION > T::ZERO && (near || beside) {
            return Err(Error::Unresolved("p"));
        }
        if even {
            sum += fan;
        }
        Ok((sum.abs() * T::FRAC_1_TAU).clamp01())
    }

    /// `[phong_polygon]`: Phong illumination at `p` from the polygon (Snyder eq. 25), clipped to
    /// the hemisphere around `r`, in [0, 1].
    ///
    /// Accuracy: measured, below. Cost per clipped edge: 2 cross products, 3
    /// normalizations (the edge's end vertex, reused as the next edge's start; the edge's
    /// plane normal; the `(cos x, sin x)` pair), ~5 dot products, 1 atan2 (`x` for odd m, the
    /// solid-angle triangle for even m), no division, and `m/2` recurrence steps of 3 products
    /// and a division by the step's integer (on fixed point, 4 products in
    /// Q28 integers and a reciprocal from a table: `polygon/arc.rs`). For `m >= 11`, fixed
    /// point, f32 and Fast32 first try to prove the term below `2^-24` and answer 0 at once
    /// (`polygon/negligible.rs`; fixed point: a quick rejection of 200 to 680 instructions on
    /// the M0, then a test against the polygon's bounding ball of about 300, about 3 500 for
    /// the whole test; the floats: the ball's test alone, 41 M4F instructions, which proves 6
    /// of the budget's 16 cases, 256 -> 172 and 1 490 -> 180; a
    /// [`WorldPolygonLight`](crate::world::WorldPolygonLight) scales its own ball with the
    /// polygon).
    /// On `Fixed22` an edge within a right angle takes `cos x`, `sin x` and the plane's normal
    /// from its ends' unit directions instead of the offsets' products and the pair's
    /// normalization (and, for odd `m`, `x` by the arc ratio: `phong_unit_edge_terms`); so do
    /// f32 and `Fast32` on targets with an FPU up to m = 32, beyond which the offsets' form is
    /// the more accurate (`FLOAT_UNIT_EDGE_MAX_M`).
    /// Measured on the Cortex-M0, `Fixed22`, a quad at m = 16: 8 394 instructions (with a
    /// `UnitVec3` 8 193; at the bars' m = 15 7 900 and 7 690; the median a clipped call) since a
    /// ring wholly above the horizon skips the walk (`unclipped_unit_terms`), 8 397 (8 203;
    /// at m = 15 7 936 and 7 747) before, after the normalizations' cheaper reciprocal square
    /// root;
    /// 8 664 instructions (median of the budget's 16 cases, a clipped case the test does not
    /// prove; 8 664 to 10 720 where the reflection meets the quad; at m = 15, in a build of
    /// the budget at that exponent, 8 219; with a `UnitVec3` 8 436 and, at m = 15, 7 991;
    /// 9 104 (m = 15: 8 647) before the walk took the vertices' heights from the
    /// negligibility test, a crossing's `r.b` as 0 and an arc from or to the horizon the
    /// recurrence with one geometric sequence (`polygon::arc`); 9 351 (m = 15: 8 894) before
    /// the walk kept its first vertex's direction for the ring's closing edge;
    /// 9 511 before a horizon arc within a right angle came
    /// from its ends' unit directions, `horizon_unit_angle`; 9 611 before the recurrence's
    /// `g^2` came from three `MULS`; 10 043 before the unit edges' plane came from one
    /// reciprocal square root without its unit normal and triple product,
    /// `phong_unit_edge_terms`; 10 154 before the recurrence's first products took the unit
    /// inputs in Q22; 10 737 (m = 15: 10 677) before the recurrence's products
    /// took three `MULS` instead of four and its `1/k` one table for either parity; 10 812 before the rescaling's
    /// exponent came from comparisons in the common band, `normalize::top_exponent`; 11 074 before the normalizations'
    /// products took three 32-bit products instead of four, 11 508 before the products of
    /// unit vectors' components did, the crate-internal `mul_le2`, `dot3_le2` and
    /// `cross3_le2`; 11 841 before the recurrence's
    /// products kept the middle partial product whole, `wide::mul_q32`; 11 861 before the positions'
    /// range test went to one unsigned comparison a coordinate, the sealed
    /// `within_coordinate_limit`; 11 857 before the clipped edges
    /// carried their vertices' indices for `polygon::VertexDirs`, which spared a polygon
    /// light's two terms one normalization of each vertex's direction in
    /// `Illuminant::diffuse_and_phong` until the Lambert term's went to 16-bit form; 12 107 before the fan triangle's
    /// and the horizon crossings' products lost their saturation tests; 13 448 with every edge from
    /// the offsets' products; in a build of the cases alone, at m = 15, 12 826 against 13 303
    /// with `x` by the arc tangent and 14 545 from the offsets' products; 13 696 with the `(cos x, sin x)` pair through the `Vec3::normalize` call;
    /// 14 790 with the offsets' products saturating, `polygon::edge::offset_products`; 14 320
    /// before the test, 20 419 with the recurrence in the type's own arithmetic and the unit
    /// vectors' products saturating); on the Cortex-M4F in f32, 1 195 (at m = 15, the bars'
    /// `PolygonLight<_, 4>`, 1 097, with a `UnitVec3` 1 068; 1 231 and, at m = 15, 1 132
    /// before the recurrence took two steps an iteration, `polygon::arc`; 1 613 and, at m = 15,
    /// 1 519
    /// before a ring wholly above the horizon skipped the clipping walk,
    /// `unclipped_unit_terms`; 1 809 and, at m = 15, 1 714 before the edges within a right
    /// angle took the unit directions' form and the arc's clamps went off the floats' path,
    /// `polygon::clamp_excursion`; 1 803 before the
    /// fixed-point walk took its heights from the negligibility test, whose code it shares;
    /// 1 797 before the fixed-point horizon arcs did; 1 839 before the fan
    /// triangles' half angles went from the arc tangent to the arc ratio, `fan_half_angle`; at
    /// m = 15, in a build of the budget at that exponent, 1 702, 1 772 with `x` by the arc
    /// tangent where `R(cos x) sin x` now gives it; 1 894 before later changes, 1 941 before the plane
    /// test's maximum went off the hot path and `abs` became `VABS.F32`; 1 933 before the plane
    /// test moved ahead of `r`'s normalization, 1 892 without the
    /// ball's test, which that case fails; 1 943 with the step's integers converted to floats
    /// at every step). Scale-free on the float types: an edge whose coordinates or products would leave the normal range (beyond
    /// about `1/TINY` or below `TINY`, e.g. an f32 scene scaled by `2^70` or `2^-40`) is
    /// scaled by a power of two first, on a cold path that costs nothing when not taken.
    /// Fallback: 0 for a zero or non-finite input, and 0 when `p` is in the polygon's plane or
    /// where [`PolygonLight::try_phong`] reports [`Error::Unresolved`].
    ///
    /// <!-- BEGIN acc-phong_polygon: target/accuracy/model-phong_polygon.md -->
    /// Measured: f64 within 3.1e-13 of its reference (the independent quadrature, adversarial);
    /// against f64, f32 1.6e-6 at m = 255 (ill-conditioned: 1.8e-6 at m = 255; near boundary:
    /// 1.2e-4 at m = 255), Fast32 5.2e-6 at m = 255 (ill-conditioned: 3.8e-6 at m = 63; near
    /// boundary: 1.2e-4 at m = 255), Fixed22 1.3e-5 at m = 255; 61 089 cases in all
    /// (`docs/accuracy.md`).
    /// <!-- END acc-phong_polygon -->
    #[inline]
    pub fn phong(&self, lobe: &PhongLobe<T>, p: Vec3<T>, r: impl Direction<T>) -> T {
        self.try_phong(lobe, p, r).unwrap_or(T::ZERO)
    }
}
