//! The tests of [`Fixed22`](super::super::Fixed22)'s `edge_plane_terms` (the Phong polygon's
//! edge plane from its ends' unit directions): against f64 of the same inputs, on edges of
//! every length down to `2^-18`, and its clamp.

extern crate std;

use super::super::*;
use super::random_unit as unit;
use crate::real::sealed::Sealed;

fn f64s(v: [Fixed22; 3]) -> [f64; 3] {
    v.map(|c| c.to_f64())
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `(r.g/|g|, d/|g|, |g|)` within its roundings of the f64 values of the same `g`, `r` and
/// `d`, in units of `2^-22`, each case against its own bound. With `g' = g 2^k` (exact for
/// nonnegative `k`; for `k = -1` each component within a unit), `S = |g'|^2` in `[1/4, 3]`
/// from three products rounded down (within 3 units), so the reciprocal `1/sqrt S` (at most
/// 2) is within `e = 1.5 S^(-3/2) + 1/2` units (its rounding the half) and `sqrt S` within
/// `1.5 S^(-1/2) + 1/2`:
/// - `r.g/|g| = (r.g') (1/|g'|)`: the dot product's three floors times the reciprocal, `|r.g'|
///   e`, and the product's floor: `3/sqrt S + |r.g'| e + 1` (plus `2 e` for `k = -1`);
/// - `d/|g| = (d 2^k) (1/|g'|)`: `d 2^k` exact (within a unit for `k = -1`, times the
///   reciprocal), `|d 2^k| e`, the floor: `|d 2^k| e + 1` (plus 2);
/// - `|g|`: the length's error scaled back by `2^-k`, and the shift's floor: `(1.5 S^(-1/2) +
///   1/2) 2^-k + 1` (plus 2 for `k = -1`).
///
/// Edges (`b` near `a`) from `2^-1` down to `2^-18`, and `r` at random.
#[test]
fn edge_plane_terms_are_within_their_roundings() {
    let mut next = crate::test_rng::xorshift32(0x00ED_6E01);
    let ulp = 1.0 / 4_194_304.0;
    let (mut worst_rg, mut worst_rp, mut worst_s) = (0f64, 0f64, 0f64);
    let mut count = 0;
    for i in 0..200_000u32 {
        let a = unit(&mut next);
        let r = unit(&mut next);
        // b: a random direction, or a step of 2^-e from a.
        let b = if i % 4 == 0 {
            unit(&mut next)
        } else {
            let e = 1 + next() % 18;
            let step = unit(&mut next);
            let v =
                [0, 1, 2].map(|j| Fixed22::from_bits(a[j].to_bits() + (step[j].to_bits() >> e)));
            match Fixed22::unit3(v) {
                Some(b) => b,
                None => continue,
            }
        };
        let g = Fixed22::cross3_le2(a, b);
        let c = Fixed22::dot3_le2(a, b);
        let (ra, rb) = (Fixed22::dot3_le2(r, a), Fixed22::dot3_le2(r, b));
        let d = rb - Fixed22::mul_le2(c, ra);
        let Some((rg, rp, s)) = Fixed22::edge_plane_terms(g, r, d) else {
            assert!(
                g.iter()
                    .all(|v| v.to_bits().unsigned_abs() <= Fixed22::TINY.to_bits() as u32),
                "{g:?} has a direction"
            );
            continue;
        };
        let (gf, rf) = (f64s(g), f64s(r));
        let len = dot(gf, gf).sqrt();
        let (want_rg, want_rp) = (dot(rf, gf) / len, d.to_f64() / len);
        // d/|g| beyond 2 in magnitude is clamped there (roundings of a nearly zero g).
        let want_rp = want_rp.clamp(-2.0, 2.0);
        let e_rg = (rg.to_f64() - want_rg).abs() / ulp;
        let e_rp = (rp.to_f64() - want_rp).abs() / ulp;
        let e_s = (s.to_f64() - len).abs() / ulp;
        // The bounds above, from this case's scale.
        let top = g.iter().fold(0u32, |t, c| t | c.to_bits().unsigned_abs());
        let k = super::super::normalize::top_exponent(top);
        let scale = 2f64.powi(k);
        let sq = len * len * scale * scale;
        let e = 1.5 * sq.powf(-1.5) + 0.5;
        let extra = if k < 0 { 2.0 * e } else { 0.0 };
        let b_rg = 3.0 / sq.sqrt() + (dot(rf, gf) * scale).abs() * e + 1.0 + extra;
        let b_rp = (d.to_f64() * scale).abs().min(2.0) * e + 1.0 + extra;
        let b_s = (1.5 / sq.sqrt() + 0.5) / scale + 1.0 + extra;
        assert!(
            e_rg <= b_rg,
            "r.g/|g|: {e_rg} units (bound {b_rg}), g {g:?}"
        );
        assert!(
            e_rp <= b_rp,
            "d/|g|: {e_rp} units (bound {b_rp}), g {g:?} d {d:?}"
        );
        assert!(e_s <= b_s, "|g|: {e_s} units of {len} (bound {b_s})");
        worst_rg = worst_rg.max(e_rg / b_rg);
        worst_rp = worst_rp.max(e_rp / b_rp);
        worst_s = worst_s.max(e_s / b_s);
        count += 1;
    }
    assert!(count > 150_000, "{count} cases");
    std::println!(
        "[maxerr] Fixed22 edge_plane_terms over {count} edges, the worst error over its bound: \
         r.g/|g| {worst_rg:.2}, d/|g| {worst_rp:.2}, |g| {worst_s:.2}"
    );
}
