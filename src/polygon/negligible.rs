//! A proof, before the recurrence, that a polygon's Phong term is negligible: fixed point's
//! early out of [`PolygonLight::try_phong`](crate::PolygonLight::try_phong).
//!
//! # The bound
//! The term is `(m+1)/(2 pi) \int_W (r.u)^m dw` over the directions `u` that the polygon
//! covers as seen from `p` (`W`, its winding region) and above the horizon `r.u >= 0`. If
//! `r.u <= c` on all of it, `W` lies in the band `0 <= r.u <= c`, and the integral over that
//! whole band is `2 pi c^(m+1)/(m+1)`: the term is at most `c^(m+1)`. With
//! `c^(m+1) <= 2^-24`, a quarter of `Fixed22`'s unit, 0 is as good an answer as the
//! recurrence's (whose own error is several units, `docs/accuracy.md`).
//!
//! # Where `r.u` is largest
//! `r.u` has no critical point on the sphere but `r` (its maximum) and `-r`. So if `r` is not
//! in `W`, its maximum over `W` (closed) lies on `W`'s boundary: on the polygon's edges (great
//! circle arcs between the vertex directions `a_i`), or on the horizon, where it is 0.
//! - **`r` outside.** `W` lies in the convex hull of the `a_i` (the winding number is 0 outside
//!   it). An edge's great circle with `r` strictly on one side and every other vertex on the
//!   other separates `r` from that hull. One such edge is looked for (a convex polygon always
//!   has one when `r` is outside; no convexity is assumed).
//! - **On an edge** from `a` to `b` (the arc shorter than 120 degrees here), `r.u` is a
//!   sinusoid of the arc length. Its slope at `a` is proportional to `D_a = r.b - (r.a)(a.b)`
//!   and at `b` to `D_b = (r.b)(a.b) - r.a`; the maximum is inside the arc only if `D_a > 0 >
//!   D_b`, and is then the length of `r`'s projection on the arc's plane:
//!   `|P r|^2 (1 - (a.b)^2) = (r.a)^2 + (r.b)^2 - 2 (r.a)(r.b)(a.b)`, with `1 - (a.b)^2 =
//!   |a x b|^2`. Otherwise it is at a vertex.
//!
//! # A ball first
//! Before the vertices are normalized, a cheaper sufficient test: the polygon lies in a ball
//! (centre and radius computed once by [`PolygonLight::new`](crate::PolygonLight::new), and
//! by `WorldPolygonLight::new` in world units, scaled with the polygon for each sample), so
//! every direction of `W` lies in the cone from `p` around that ball. If the angle between `r` and the cone's axis exceeds
//! the cone's half-angle plus the threshold's angle, `r.u` stays below the threshold on the
//! whole cone ([`cone_below`]: no square root, no normalization).
//!
//! # Rounding
//! The test runs in the type's own arithmetic on rounded unit vectors (errors of a few `2^-22`).
//! Every decision has a margin far above that: the threshold `c` is lowered by `2^-6` of
//! itself (and is at least 1/4, `m >= 11`), the slopes and sides must clear `2^-14`, the
//! tangent test needs `|a x b|^2 >= 2^-5`. Where a margin is not met the test answers "not
//! proven", and the recurrence runs as before: the early out can only skip work, never change
//! an answer by more than `2^-24`.
//!
//! # What it costs and saves
//! Measured on the Cortex-M0 (`Fixed22`, exact QEMU instructions of the budget firmware's
//! `demo_shade` cases: the board demo's shader at 16 points, m = 20 and 48,
//! `QEMU_BUDGET_ONLY=demo_shade`), with the cap's early 0 (`phong.rs`) beside it: 15 of the 32
//! calls skip a recurrence, each 4 700 to 25 500 instructions cheaper; 3 see no vertex above
//! the horizon (74 cheaper); the other 14 pay the quick rejection, 200 to 680. All 32:
//! 859 386 -> 686 951 instructions (-20 %; the polygon's test alone: -13.9 %). The budget
//! table's `phong_polygon` quad (m = 16): 14 320 -> 14 790 at the median, a case the test
//! rejects (its cases: 7 of 16 cheaper, 1 333 -> 1 286 and 10 985 -> 4 921; 9 dearer, by 229
//! to 470). In the RP2040 demo's frames (host render of frames 0 and 1, 553 calls): 179 quick
//! rejections, 114 with nothing above, 258 proven by the whole test, 2 not. Flash: about
//! 1.6 KiB (the edge test's products out of line).
//!
//! The floats (f32, `Fast32`; never f64) try the ball alone ([`floats_ball_below`]), 41
//! Cortex-M4F instructions where it fails: in the M4F demo's Gouraud frame 0 (QEMU,
//! `boards/qemu-frame`) the shading falls from 1.03 M to 0.79 M instructions. Measured on
//! random polygons (this module's tests): 14 530 of 60 000 cases aimed near the threshold
//! proven in f32, each term below `2^-24` in f64.
//!
//! The ball, added later, proves 7 of those 32 calls for about 3 170 instructions less each
//! than the vertex and edge test, and costs about 300 where it does not prove (6 calls): all
//! 32, 616 426 -> 595 197 instructions, every result bit the same. The RP2040 demo's
//! single-core frame 1: shading 48.9 -> 45.5 ms (rp2040js, `boards/rp2040-emu/check.sh`).

#[cfg(test)]
use super::Uncached;
use super::VertexDirections;
use crate::lobe::PhongLobe;
use crate::{Real, UnitVec3, Vec3};

/// The most vertices [`phong_negligible_with`] tests (a larger polygon is never proven negligible).
const MAX_VERTICES: usize = 8;

/// How many vertices' heights [`phong_negligible_with`] hands the walk (a quad's: zeroing a
/// larger array costs the Cortex-M0 a `memclr` call).
pub(crate) const HEIGHTS: usize = 4;

/// Whether the Phong term of the polygon `verts` at `p` about `r` is provably at most `2^-24`
/// ([`PhongLobe`]'s `negligible_cos`; the module doc derives the test). For the floats, only
/// [`floats_ball_below`]. Not proven (`false`) for f64, `m < 11`, more than [`MAX_VERTICES`]
/// vertices, a vertex within `4 r_min` of `p` (where the recurrence's own tests report
/// [`Error::Unresolved`](crate::Error::Unresolved)), an edge that subtends more than 120
/// degrees, and wherever a margin is not met.
///
/// A quick rejection first, without normalizing: a vertex `u = v - p` above the threshold,
/// `(r.u)^2 >= c^2 |u|^2` with `r.u > 0` (rounding there can only reject a case that might
/// have passed, never pass one). Most shading points that see the polygon in their lobe stop
/// there, at the first such vertex. With no vertex above the horizon the term is 0: `true`
/// unless a vertex is within `r_min` (as the recurrence's clipping answers).
///
/// Cost, measured on the Cortex-M0 (`Fixed22`, QEMU): 200 to 680 instructions where the
/// quick rejection stops it, about 3 000 for the whole test (the module doc).
///
/// The vertices' unit directions from `p` are taken from `dirs` (shared with the Phong walk
/// that follows: `VertexDirs`; or `Uncached`). Fixed point: `*filled` is the number of
/// vertices whose heights `r.(v - p)` (the bits of `Vec3::dot`) the quick rejection computed,
/// from the first; those within [`HEIGHTS`] are left in `heights` for the walk, which then
/// does not compute them again.
#[allow(clippy::too_many_arguments)]
#[inline(never)]
pub(crate) fn phong_negligible_with<T: Real>(
    verts: &[Vec3<T>],
    ball: Option<(Vec3<T>, T)>,
    p: Vec3<T>,
    r: UnitVec3<T>,
    lobe: &PhongLobe<T>,
    r_min: T,
    dirs: &mut impl VertexDirections<T>,
    (heights, filled): (&mut [T; HEIGHTS], &mut usize),
) -> bool {
    let (lim, lim2, _) = lobe.negligible_cos;
    let n = verts.len();
    if !(lim > T::ZERO) || n > MAX_VERTICES {
        return false;
    }
    let rv = [r.x, r.y, r.z];
    if !(T::RESOLUTION > T::ZERO) {
        return floats_ball_below(ball, p, r, lobe);
    }
    let arr = |v: Vec3<T>| [v.x, v.y, v.z];
    // The quick rejection, and the case with no vertex above the horizon, which the
    // recurrence's clipping answers as cheaply: 0, or `Unresolved` for a vertex within `r_min`
    // (the same tests, `r.u`'s sign and `all_within`, so the same answer).
    //
    // The sealed products without saturation tests, which equal `Vec3::dot` and `*` bit for
    // bit here: `u`'s components are differences of coordinates within the type's limit (at
    // most 8 for `Fixed22`), so every factor is below 16 and every product and sum below 256,
    // where `Fixed22`'s 16-bit halves stay within `i32` and nothing saturates.
    //
    // Each height computed is left in `heights` for the walk that follows (which computed
    // each vertex's once or twice more, the first vertex's three times), `filled` the number
    // of them. Measured on the Cortex-M0 (the budget's `phong_polygon` quad at m = 15, with a
    // `UnitVec3`): lit calls 8 315 -> 8 106 at the median (100 to 210 fewer), the calls
    // with no vertex above the horizon 802 -> 861 (the array and its stores; `[T; 8]` took
    // a `memclr` call and cost them 92).
    let mut above = false;
    for (i, v) in verts.iter().enumerate() {
        let u = arr(v.offset_from(p));
        let d = T::dot3_small(rv, u);
        if let Some(h) = heights.get_mut(i) {
            *h = d;
        }
        above |= d >= T::ZERO;
        if d > T::ZERO && !(T::mul_small(d, d) < T::mul_small(lim2, T::dot3_small(u, u))) {
            *filled = i + 1;
            return false;
        }
    }
    *filled = n.min(HEIGHTS);
    if !above {
        return !verts
            .iter()
            .any(|v| T::all_within(arr(v.offset_from(p)), r_min));
    }
    let near = r_min * T::from_u32(4);
    if let Some((c, rho)) = ball {
        if cone_below(c - p, rho + near, rv, lobe.negligible_cos) {
            return true;
        }
    }
    // Every vertex's direction and its cosine, below the threshold.
    let mut unit_dirs = [([T::ZERO; 3], T::ZERO); MAX_VERTICES];
    for (i, (v, entry)) in verts.iter().zip(unit_dirs.iter_mut()).enumerate() {
        let u = v.offset_from(p);
        if T::all_within(arr(u), near) {
            return false;
        }
        let Some(a) = dirs.get(i, u) else {
            return false;
        };
        let c = dot(rv, arr(*a));
        if !(c < lim) {
            return false;
        }
        *entry = (arr(*a), c);
    }
    let unit_dirs = &unit_dirs[..n.min(MAX_VERTICES)];
    edges_below(unit_dirs, rv, lim2)
}

/// The ball half of [`phong_negligible_with`]'s test: whether every direction from `p` into the
/// ball of centre `p + w` and radius `rho` makes an angle of at least `gamma` with `r`,
/// `cos gamma = lim` and `sin gamma <= sin_lim`. The directions into the ball fill a cone of
/// half-angle `beta`, `sin beta = rho/|w|` (`p` outside it); the angle `alpha` between `r`
/// and `w` must be at least `gamma + beta`, i.e. `cos alpha <= cos(gamma + beta)`, which is
/// multiplied by `|w|`: `r.w + sin(gamma) rho <= lim S`, `S = sqrt(|w|^2 - rho^2)`. A larger
/// `sin_lim` only raises the left side. With `L` the left side plus a margin of `2^-10`:
/// true at once for `L <= 0`, else `L^2 < lim^2 S^2`, no square root.
///
/// Rounding: `S^2` must be at least 1/4 (so `lim S > 0.12`: `lim > 0.24` from `m = 11`).
/// Each side of the squared comparison is then off by less than `2^-14` (products of factors
/// below 16 truncated to `2^-22`, `S^2` below 192), which moves the comparison of `L` with
/// `lim S` by less than `2^-13 / (2 lim S) < 2^-10.9`, inside the margin with the few units
/// of `L`'s own roundings. Larger `L` (from 16): not proven.
///
/// `rho` is the polygon's ball raised by `4 r_min`, so that a `p` it accepts is at least that
/// far from every point of the polygon: where the recurrence would report
/// [`Error::Unresolved`](crate::Error::Unresolved), this never answers (the same rule as the
/// vertex test's `near`). Cost, measured on the Cortex-M0 (`Fixed22`, the budget's
/// `demo_shade` cases): about 300 instructions, against about 3 470 for the vertex and
/// edge test it spares where it succeeds.
#[inline(never)]
fn cone_below<T: Real>(w: Vec3<T>, rho: T, rv: [T; 3], (_, lim2, sin_lim): (T, T, T)) -> bool {
    let w = [w.x, w.y, w.z];
    // `w` and `rho` below 16 (`p` and the centre within the coordinate limit; a radius
    // beyond 8 fails the first test anyway): the products without saturation tests.
    if !(rho < T::from_u32(8)) {
        return false;
    }
    let s2 = T::dot3_small(w, w) - T::mul_small(rho, rho);
    if !(s2 >= T::from_fixed_i32(1, 2)) {
        return false;
    }
    let l = T::dot3_small(rv, w) + T::mul_small(sin_lim, rho) + T::from_fixed_i32(1, 10);
    if !(l > T::ZERO) {
        return true;
    }
    l < T::from_u32(16) && T::mul_small(l, l) < T::mul_unit(s2, lim2)
}

/// [`phong_negligible_with`] for the floats: the ball's test alone, in a scale-free form of
/// [`cone_below`]'s (whose thresholds are for fixed point's range). With `w` the ball's
/// centre from `p`, `S^2 = |w|^2 - rho^2` at least `|w|^2/16` (the cone's half-angle at most
/// 75 degrees, so `lim S > 0.06 |w|`, far above f32's rounding of `|w|` times a few `2^-24`),
/// `L = r.w + sin(gamma) rho` must be below `lim S`: true for `L <= 0`, else `L^2 < lim^2
/// S^2 (1 - 2^-10)`. The vertex and edge test is left out: on the Cortex-M4F it would cost
/// about 1 100 instructions where the term itself costs about 1 500, and its quick rejection
/// more than the clipping it would spare. `None` (no ball): not proven.
#[inline(always)]
pub(crate) fn floats_ball_below<T: Real>(
    ball: Option<(Vec3<T>, T)>,
    p: Vec3<T>,
    r: UnitVec3<T>,
    lobe: &PhongLobe<T>,
) -> bool {
    let (lim, lim2, sin_lim) = lobe.negligible_cos;
    let Some((c, rho)) = ball else {
        return false;
    };
    if !(lim > T::ZERO) {
        return false;
    }
    let w = c - p;
    let ww = w.dot(w);
    let s2 = ww - rho * rho;
    if !(s2 * T::from_u32(16) >= ww) {
        return false;
    }
    let l = r.dot(w) + sin_lim * rho;
    !(l > T::ZERO) || l * l < lim2 * s2 * T::from_f64(1.0 - 1.0 / 1024.0)
}

/// The edge half of [`phong_negligible_with`]'s test on every vertex's `(a, r.a)` in ring order:
/// each edge's own maximum of `r.a` below the threshold (squared, `lim2`), and one edge whose
/// great circle separates `r` from the other vertices.
fn edges_below<T: Real>(dirs: &[([T; 3], T)], rv: [T; 3], lim2: T) -> bool {
    let n = dirs.len();
    let margin = T::from_fixed_i32(1, 14);
    let min_cross_sq = T::from_fixed_i32(1, 5);
    let minus_half = -T::HALF;
    let mut separated = false;
    for i in 0..n {
        let j = if i + 1 == n { 0 } else { i + 1 };
        let (Some(&(av, ca)), Some(&(bv, cb))) = (dirs.get(i), dirs.get(j)) else {
            return false;
        };
        let e = dot(av, bv);
        if e < minus_half {
            return false;
        }
        let g = cross(av, bv);
        // The arc's own maximum, where its slopes say it is inside.
        let slope_a = cb - mul(ca, e);
        let slope_b = mul(cb, e) - ca;
        if slope_a > -margin && slope_b < margin {
            let gg = dot(g, g);
            if gg < min_cross_sq {
                return false;
            }
            let lhs = mul(ca, ca) + mul(cb, cb) - mul(T::TWO * ca, mul(cb, e));
            if !(lhs < mul(lim2, gg)) {
                return false;
            }
        }
        // A great circle between r and the other vertices.
        if !separated {
            let rg = dot(rv, g);
            if rg.abs() > margin {
                let out = rg > T::ZERO;
                separated = dirs.iter().enumerate().all(|(k, &(d, _))| {
                    let s = dot(g, d);
                    k == i || k == j || if out { s < -margin } else { s > margin }
                });
            }
        }
    }
    separated
}

/// [`Real`]'s sealed `dot3_small`, out of line: the edge test's products, called once each
/// where inlining them would cost the M0 budget firmware's flash about 1.5 KiB for a path that
/// runs only for the candidates.
#[inline(never)]
fn dot<T: Real>(a: [T; 3], b: [T; 3]) -> T {
    T::dot3_small(a, b)
}

/// `mul_small`, out of line (as [`dot`]).
#[inline(never)]
fn mul<T: Real>(a: T, b: T) -> T {
    T::mul_small(a, b)
}

/// `cross3_small`, out of line (as [`dot`]).
#[inline(never)]
fn cross<T: Real>(a: [T; 3], b: [T; 3]) -> [T; 3] {
    T::cross3_small(a, b)
}

#[cfg(all(test, feature = "fixed"))]
mod tests {
    use super::*;
    use crate::test_rng::uniform;
    use crate::{Fixed22, PolygonLight};

    /// Every case the test proves negligible is: f64's term (the reference, validated against
    /// quadrature by `tests/`) below `2^-24` at the same (rounded) inputs, on random
    /// rectangles, concave darts and triangles, with `r` aimed near the polygon's edges and
    /// vertices at about the threshold's angle (where the arcs' maxima decide), and the
    /// exponents from 11 to 255. The count of proven cases keeps the test from passing
    /// vacuously, and Fixed22's `try_phong` answers exactly 0 for each.
    /// `(cases, proven, above the horizon, proven by the ball)` of the check below for `T`,
    /// every position multiplied by `scale`.
    fn proofs_hold<T: Real>(scale: f64) -> (u32, u32, u32, u32) {
        let mut rnd = uniform(0x2545_F491);
        let coord = |rnd: &mut dyn FnMut() -> f64, s: f64| (rnd() * 2.0 - 1.0) * s;
        let to64 = |v: Vec3<T>| Vec3::<f64>::from_f64(v.to_f64());
        // Cases, those proven, and those proven with part of the polygon above the horizon.
        let (mut cases, mut proven, mut above) = (0u32, 0u32, 0u32);
        // Those proven by the polygon's bounding ball (`cone_below`).
        let mut by_ball = 0u32;
        for i in 0..60_000u32 {
            // A plane frame: a random unit normal and two axes in the plane.
            let n = Vec3::<f64>::new(
                coord(&mut rnd, 1.0),
                coord(&mut rnd, 1.0),
                coord(&mut rnd, 1.0),
            );
            let Some(n) = n.normalize() else { continue };
            let ax = n.any_perpendicular();
            let Some(ax) = ax.normalize() else { continue };
            let ay = n.cross(ax);
            let c = Vec3::new(
                coord(&mut rnd, 2.0),
                coord(&mut rnd, 2.0),
                coord(&mut rnd, 2.0),
            );
            let (w, h) = (0.05 + rnd() * 1.5, 0.05 + rnd() * 1.5);
            let shape: &[(f64, f64)] = match i % 3 {
                0 => &[(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)],
                1 => &[(-1.0, -1.0), (1.0, 0.0), (-1.0, 1.0), (-0.3, 0.0)],
                _ => &[(-1.0, -1.0), (1.0, -0.5), (0.0, 1.0)],
            };
            let mut verts = heapless::Vec::<Vec3<T>, 8>::new();
            for &(x, y) in shape {
                let v = (c + ax * (x * w) + ay * (y * h)) * scale;
                let _ = verts.push(Vec3::from_f64(v.to_f64()));
            }
            let Ok(light) = PolygonLight::<T, 8>::new(&verts) else {
                continue;
            };
            let p = Vec3::<f64>::new(
                coord(&mut rnd, 3.5),
                coord(&mut rnd, 3.5),
                coord(&mut rnd, 3.5),
            );
            let p = p * scale;
            let pf = Vec3::<T>::from_f64(p.to_f64());
            let m = [11, 12, 16, 20, 33, 48, 64, 128, 200, 255][(rnd() * 10.0) as usize % 10];
            // r: towards a vertex or an edge's midpoint, tilted by about the threshold angle.
            let k = (rnd() * 8.0) as usize % verts.len();
            let a = verts[k].to_f64();
            let b = verts[(k + 1) % verts.len()].to_f64();
            let t = if i % 2 == 0 { 0.0 } else { 0.5 };
            let target = Vec3::new(
                a[0] + (b[0] - a[0]) * t,
                a[1] + (b[1] - a[1]) * t,
                a[2] + (b[2] - a[2]) * t,
            );
            let Some(to) = (target - to64(pf)).normalize() else {
                continue;
            };
            // (One case in four farther off, where the ball's cone decides.)
            let spread = if i % 4 == 3 {
                1.2 + rnd() * 1.2
            } else {
                0.8 + rnd() * 0.5
            };
            let angle = libm::acos(libm::pow(2.0, -24.0 / (m as f64 + 1.0))) * spread;
            let side = Vec3::new(
                coord(&mut rnd, 1.0),
                coord(&mut rnd, 1.0),
                coord(&mut rnd, 1.0),
            );
            let Some(perp) = (side - to * side.dot(to)).normalize() else {
                continue;
            };
            let rd = to * libm::cos(angle) + perp * libm::sin(angle);
            let Some(ru) = Vec3::<T>::from_f64(rd.to_f64()).to_unit() else {
                continue;
            };
            let Ok(lobe) = PhongLobe::<T>::new(m) else {
                continue;
            };
            cases += 1;
            let r_min = crate::polygon::near_limit::<T>(crate::polygon::phong_near_log2(m));
            if !phong_negligible_with(
                light.vertices(),
                light.ball(),
                pf,
                ru,
                &lobe,
                r_min,
                &mut Uncached,
                (&mut [T::ZERO; HEIGHTS], &mut 0),
            ) {
                continue;
            }
            proven += 1;
            let r = ru.into_inner();
            let ball = if T::RESOLUTION > T::ZERO {
                light.ball().is_some_and(|(c, rho)| {
                    let near = r_min * T::from_u32(4);
                    cone_below(c - pf, rho + near, [r.x, r.y, r.z], lobe.negligible_cos)
                })
            } else {
                floats_ball_below(light.ball(), pf, ru, &lobe)
            };
            by_ball += u32::from(ball);
            let vf: heapless::Vec<Vec3<f64>, 8> =
                verts.iter().map(|v| Vec3::from_f64(v.to_f64())).collect();
            let Ok(reference) = PolygonLight::<f64, 8>::new(&vf) else {
                continue;
            };
            let Ok(lobe64) = PhongLobe::<f64>::new(m) else {
                continue;
            };
            let r64 = Vec3::<f64>::from_f64(ru.into_inner().to_f64());
            let exact = reference.phong(&lobe64, to64(pf), r64);
            if verts.iter().any(|v| (to64(*v) - to64(pf)).dot(r64) > 0.0) {
                above += 1;
            }
            assert!(
                exact < 1.0 / 16_777_216.0,
                "case {i}: m = {m}, term {exact:e}"
            );
            assert_eq!(light.try_phong(&lobe, pf, ru), Ok(T::ZERO), "case {i}");
        }
        (cases, proven, above, by_ball)
    }

    #[test]
    fn every_proven_term_is_below_2_pow_minus_24() {
        let (cases, proven, above, by_ball) = proofs_hold::<Fixed22>(1.0);
        // Not vacuous: a good share of the cases aimed at the threshold are proven, most of
        // them with a term that is not 0, and many by the ball (measured: 23 435 of 60 000
        // proven, 17 609 with part of the polygon above the horizon, 11 273 by the ball).
        assert!(above * 10 > cases, "{proven} of {cases} ({above} above)");
        assert!(
            by_ball * 8 > cases,
            "{by_ball} of {cases} proven by the ball"
        );
    }

    /// The same for f32 (whose `try_phong` answers 0 where the proof holds, as fixed point's).
    #[test]
    fn every_proven_f32_term_is_below_2_pow_minus_24() {
        // (The floats try the ball alone: every proof is the ball's. Scale-free: the same
        // share proven at every scale, measured 14 530 of 60 000 at scale 1.)
        for scale in [1.0, 1e-3, 1e3] {
            let (cases, proven, above, by_ball) = proofs_hold::<f32>(scale);
            assert!(
                by_ball == proven && above * 10 > cases && by_ball * 8 > cases,
                "scale {scale}: {proven} of {cases} ({above} above)"
            );
        }
    }
}
