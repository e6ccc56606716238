//! [`Fixed22`](super::Fixed22)'s crate-internal arithmetic (the sealed trait of
//! [`Real`](crate::Real)): products and sums without saturation tests where the callers'
//! bounds make them exact, the normalizations' ratios, the exact products of the polygon
//! edges near their lines, and SH9's fused dot product. Each is `*`'s and `+`'s bits
//! wherever its precondition holds (`tests.rs`).

use super::kernels::*;
use super::normalize::*;
use super::{Fixed22, FRAC};
use crate::real::sealed::SphereRatios;
use crate::Real;

impl crate::real::sealed::Sealed for Fixed22 {
    #[cfg(feature = "raster")]
    type KeptNormals = Option<([crate::Vec3<Self>; 3], bool)>;
    #[cfg(feature = "raster")]
    const NO_KEPT_NORMALS: Self::KeptNormals = None;
    #[cfg(feature = "raster")]
    #[inline(always)]
    fn keep_normals(rows: [crate::Vec3<Self>; 3], small: bool) -> Self::KeptNormals {
        Some((rows, small))
    }
    #[cfg(feature = "raster")]
    #[inline(always)]
    fn kept_normals(kept: &Self::KeptNormals) -> Option<([crate::Vec3<Self>; 3], bool)> {
        *kept
    }
    /// Each component rounded half up to Q15 (`kernels::q15`), held in the raw bits.
    #[inline(always)]
    fn prepare_axis(b: [Self; 3]) -> [Self; 3] {
        b.map(|x| Fixed22::from_bits(q15(x.to_bits())))
    }
    /// `-r < c < r` for each component as `(c + r) as u32 < 2r - 1` (wrapping: a component
    /// at `i32::MIN` or `MAX` falls outside for any `r` below 256; `r <= 0`: `false`).
    #[cfg(any(feature = "polygon", feature = "raster"))]
    #[inline(always)]
    fn all_within(v: [Self; 3], r: Self) -> bool {
        let r = r.to_bits();
        let span = (2 * r as u32).wrapping_sub(1);
        let inside = |c: Self| (c.to_bits().wrapping_add(r) as u32).wrapping_sub(1) < span;
        r > 0 && inside(v[0]) && inside(v[1]) && inside(v[2])
    }
    /// The sign from the estimate `E = sum (a_i >> 11) (b_i >> 8)` (each `|a_i >> 11| <=
    /// 2^15` for `|a_i| < 16`, each `|b_i >> 8| <= 2^14 + 1` for a unit `b`: every product
    /// below `2^29 + 2^15`, the sum inside `i32`), `2^-19` of `sum a_i b_i` in raw units up to
    /// the shifts' remainders (`0 <= r < 2^11` and `2^8`: at most `2^11 2^15 2^8 + 2^8 2^11
    /// (2^14 + 1) + 2^19` a product, below `2^36.2` for the three). `dot3_small` is the sum
    /// of the products' floors, within 3 units of `2^22` below `sum a_i b_i / 2^22`. So
    /// beyond `|E| >= 2^18` (a height of `2^-7`; `2^37` raw, well beyond both errors) the
    /// sign of `E` is `dot3_small`'s; nearer the horizon `dot3_small` itself decides. 3
    /// `MULS` and 6 shifts where `dot3_small` takes 12 `MULS` (3 products of 4): measured on
    /// the Cortex-M0 (QEMU budget, `polygon_lambert` quad, wholly lit) 2 182 -> 2 038
    /// instructions (unlit 1 049 -> 1 015), the same values.
    #[cfg(feature = "polygon")]
    #[inline(always)]
    fn height_nonneg(a: [Self; 3], b: [Self; 3]) -> bool {
        let p = |i: usize| (a[i].to_bits() >> 11).wrapping_mul(b[i].to_bits() >> 8);
        let e = p(0).wrapping_add(p(1)).wrapping_add(p(2));
        if e >= 1 << 18 {
            true
        } else if e <= -(1 << 18) {
            false
        } else {
            Self::dot3_small(a, b) >= Fixed22::ZERO
        }
    }
    /// In 16-bit form throughout (see `normalize::unit_q15`).
    #[cfg(feature = "polygon")]
    #[inline(always)]
    fn unit3_q15(v: [Self; 3]) -> Option<[i32; 3]> {
        unit_q15(v)
    }
    /// One power of two for `g` and `d`, one reciprocal square root (see
    /// `normalize::edge_plane_terms`).
    #[cfg(all(feature = "polygon", feature = "phong"))]
    #[inline(always)]
    fn edge_plane_terms(g: [Self; 3], r: [Self; 3], d: Self) -> Option<(Self, Self, Self)> {
        edge_plane_terms(g, r, d)
    }
    /// The same pieces as `arc_ratio`, in 32-bit products (see
    /// `elementary::arc_ratio_q30_to_q15`).
    #[cfg(feature = "polygon")]
    #[inline(always)]
    fn arc_ratio_q15(c: i32) -> Option<i32> {
        Some(super::elementary::arc_ratio_q30_to_q15(c))
    }
    /// Exact products and sums in `i64` (every coordinate below `2^7` in magnitude, as the
    /// kernels' are: products below `2^58`, sums below `2^60`; larger coordinates: `None`, and
    /// the caller keeps its rounded products), then one shift that puts the largest magnitude's
    /// leading bit at bit 22 (`[1, 2)`): truncated, relative `2^-22`. Not inlined: the cold
    /// path of the polygon edges where `G` is small (a point near an edge's line, a short edge).
    #[cfg(feature = "polygon")]
    #[inline(never)]
    fn cross_dot_scaled(ua: [Self; 3], ub: [Self; 3], d: [Self; 3]) -> Option<([Self; 3], Self)> {
        const LIM: u32 = 1 << 29;
        let fits = |v: &[Self; 3]| v.iter().all(|c| c.to_bits().unsigned_abs() < LIM);
        if !(fits(&ua) && fits(&ub) && fits(&d)) {
            return None;
        }
        let p = |a: Self, b: Self| a.to_bits() as i64 * b.to_bits() as i64;
        let g = [
            p(ua[1], d[2]) - p(ua[2], d[1]),
            p(ua[2], d[0]) - p(ua[0], d[2]),
            p(ua[0], d[1]) - p(ua[1], d[0]),
        ];
        let dot = p(ua[0], ub[0]) + p(ua[1], ub[1]) + p(ua[2], ub[2]);
        let top = g
            .iter()
            .fold(dot.unsigned_abs(), |m, v| m | v.unsigned_abs());
        if top == 0 {
            return None;
        }
        // Leading bit of `top` at 63 - lz (at most 59); move it to bit 22.
        let sh = 63 - top.leading_zeros() as i32 - 22;
        let f = |v: i64| {
            let b = if sh >= 0 { v >> sh } else { v << -sh };
            Fixed22::from_bits(b as i32)
        };
        Some(([f(g[0]), f(g[1]), f(g[2])], f(dot)))
    }
    /// `x 2^-60` to I10F22: `x 2^-38` rounded half up, from the shifted bits (`|x| <= 2^62`
    /// gives at most `2^24`, 4.0; beyond, saturated).
    #[inline(always)]
    fn from_q60(x: i64) -> Self {
        let bits = ((x >> 37) + 1) >> 1;
        Fixed22::from_bits(bits.clamp(i32::MIN as i64, i32::MAX as i64) as i32)
    }
    /// `from_q60(x << k)`: `floor(x 2^(k - 37))`, then the same rounding, in 32-bit halves
    /// (no 64-bit shift, a library call on the M0): `x << k` within an `i64` puts it within
    /// `2^26`, so the halves' shifts keep every bit it has.
    #[inline(always)]
    fn from_q60_shl(x: i64, k: u32) -> Self {
        let (hi, lo) = ((x >> 32) as i32, x as u32);
        let y = if k >= 37 {
            // |x| < 2^(63 - k) <= 2^26: within `lo`.
            (lo as i32) << (k - 37).min(31)
        } else if k >= 5 {
            // A right shift by 32 - (k - 5), in [1, 32]: bits of both halves.
            let s = 37 - k; // in [1, 32]
            if s >= 32 {
                hi
            } else {
                ((hi as u32) << (32 - s) | (lo >> s)) as i32
            }
        } else {
            // A right shift by 33 to 37: `hi` alone.
            hi >> (5 - k)
        };
        Fixed22::from_bits((y >> 1) + (y & 1))
    }
    /// `normalize3`'s unit vector and length, bit for bit, and the ratios in its rescaled
    /// space: with `v = V 2^-k` (`V` the rescaled vector, `S` its sum of squares and `1/|V|`
    /// the reciprocal square root the normalization computes anyway), `r / |v| = (r 2^k)/|V|`
    /// and `sqrt(|v|^2 - r^2)/|v| = sqrt(S - (r 2^k)^2)/|V|`: no division, and `|V|` near 1
    /// keeps the 22 fractional bits for short vectors (whose `|v|` would lose the shift).
    /// `r 2^k < |V|` (at most 3.5) once `|v| > r`: no overflow.
    #[inline(always)]
    fn sphere_ratios(v: [Self; 3], r: Self) -> Option<SphereRatios<Self>> {
        let top = magnitude_top(v, Self::TINY)?;
        let ([x, y, z], k) = rescale_for_unit(v, top);
        let s2 = unit_scale(x, y, z);
        let (len, inv) = unit_sqrt_rsqrt(s2);
        let sc = |c: Self| Fixed22::from_bits(mul_bits_le2_round(c.to_bits(), inv.to_bits()));
        let u = [sc(x), sc(y), sc(z)];
        // `len * d` for `d = 2^-k`: `*`'s floor (an arithmetic shift right) or its saturation
        // to MAX (a shift left of `len < 2^24` by at most 8, then the clamp), the same bits.
        let len = len.to_bits();
        let d = Fixed22::from_bits(if k >= 0 {
            len >> k
        } else {
            ((len as u32) << (-k)).min(i32::MAX as u32) as i32
        });
        if d <= r {
            return Some((u, d, Self::ZERO, [Self::ZERO; 3]));
        }
        // 0 <= r < d: `r 2^k` below `|V|`.
        let rb = r.to_bits();
        let rs = Fixed22::from_bits(if k >= 0 { rb << k } else { rb >> (-k) });
        // cos sigma = sqrt(S - (r 2^k)^2) / |V|: left to the caller (`sphere_cos`). The
        // rounded `1/|V|` may take `r/|v|` above 1: clamped. Both factors are small (`r 2^k <
        // |V| < 2 sqrt 3`, `1/|V| <= 1`): `mul_bits_small`, `*`'s bits without its saturation
        // test.
        let ss = Fixed22::from_bits(mul_bits_small(rs.to_bits(), inv.to_bits()));
        Some((u, d, Real::min(ss, Self::ONE), [s2, rs, inv]))
    }
    /// `sqrt(S - (r 2^k)^2) / |V|` from `sphere_ratios`' parts `[S, r 2^k, 1/|V|]`.
    #[inline(always)]
    fn sphere_cos(parts: [Self; 3]) -> Self {
        let [s2, rs, inv] = parts;
        (s2 - rs * rs).sqrt() * inv
    }
    /// Each product by `mul_bits_small` (exact `floor(a b / 2^22)` for factors below 16, no
    /// saturation test), the sum (below 512 by the precondition) by wrapping additions: the
    /// same bits as `Vec3::dot` (whose saturating additions never saturate there). About 40
    /// instead of 95 instructions on the M0.
    #[inline(always)]
    fn dot3_small(a: [Self; 3], b: [Self; 3]) -> Self {
        let p = |k: usize| mul_bits_small(a[k].to_bits(), b[k].to_bits());
        Fixed22::from_bits(p(0).wrapping_add(p(1)).wrapping_add(p(2)))
    }
    /// `kernels::dot3_unit_round`: the exact sum rounded once (the axes are unit vectors).
    #[cfg(feature = "raster")]
    #[inline(always)]
    fn dot3_axis(d: [Self; 3], axis: [Self; 3]) -> Self {
        Fixed22::from_bits(dot3_unit_round(
            d.map(Fixed22::to_bits),
            axis.map(Fixed22::to_bits),
        ))
    }
    /// `kernels::mul_bits_round`.
    #[cfg(feature = "raster")]
    #[inline(always)]
    fn mul_nearest(a: Self, b: Self) -> Self {
        Fixed22::from_bits(mul_bits_round(a.to_bits(), b.to_bits()))
    }
    /// `|x| <= L` for the limit's raw bits `L = 2^24` as `(x + L) as u32 <= 2 L`: one
    /// unsigned comparison a component (`i32::MIN`, the saturated `-512`, wraps to `2^31 +
    /// 2^24`, beyond), where the largest magnitude takes three saturating absolute values
    /// and two maxima: about 20 Cortex-M0 instructions fewer in every positional call.
    #[inline(always)]
    fn within_coordinate_limit(v: [Self; 3]) -> bool {
        const L: i32 = (Fixed22::COORDINATE_LIMIT as i32) << FRAC;
        let ok = |c: Self| (c.to_bits().wrapping_add(L) as u32) <= 2 * L as u32;
        ok(v[0]) && ok(v[1]) && ok(v[2])
    }
    /// Through Q15, one 32-bit product a component (`kernels::cos_unit_q15`).
    #[inline(always)]
    fn cos_unit(a: [Self; 3], b: [Self; 3]) -> Self {
        Fixed22::from_bits(cos_unit_q15(
            a.map(Fixed22::to_bits),
            b.map(Fixed22::to_bits),
        ))
    }
    /// With `b`'s components rounded to Q15 once (`kernels::cos_prepared_q15`).
    #[inline(always)]
    fn cos_axis(a: [Self; 3], bq: [Self; 3]) -> Self {
        Fixed22::from_bits(cos_prepared_q15(
            a.map(Fixed22::to_bits),
            bq.map(Fixed22::to_bits),
        ))
    }
    /// The cosine in Q15 (`kernels::cos_prepared_q15_clamped`), each product from two 32-bit
    /// products, the sums without saturation test (`kernels::mix_by_cos`).
    #[cfg(feature = "hemisphere")]
    #[inline(always)]
    fn mix_by_cos(mid: [Self; 3], half: [Self; 3], a: [Self; 3], bq: [Self; 3]) -> [Self; 3] {
        let c = cos_prepared_q15_clamped(a.map(Fixed22::to_bits), bq.map(Fixed22::to_bits));
        let e = |k: usize| Fixed22::from_bits(mix_by_cos(mid[k].to_bits(), half[k].to_bits(), c));
        // Written out (not `map`, which the M0 build turned into a loop through the stack).
        [e(0), e(1), e(2)]
    }
    /// Wrapping subtractions: exact (and so the saturating `-`'s bits) for differences within
    /// the format's range, which positions within the coordinate limit keep.
    #[inline(always)]
    fn sub3_small(a: [Self; 3], b: [Self; 3]) -> [Self; 3] {
        let d = |i: usize| Fixed22::from_bits(a[i].to_bits().wrapping_sub(b[i].to_bits()));
        [d(0), d(1), d(2)]
    }
    /// `mul_bits_small`: exact `floor(a b / 2^22)`, no saturation test.
    #[inline(always)]
    fn mul_small(a: Self, b: Self) -> Self {
        Fixed22::from_bits(mul_bits_small(a.to_bits(), b.to_bits()))
    }
    /// `mul_bits_le2`: exact `floor(a b / 2^22)` from three 32-bit products.
    #[inline(always)]
    fn mul_le2(a: Self, b: Self) -> Self {
        Fixed22::from_bits(mul_bits_le2(a.to_bits(), b.to_bits()))
    }
    /// As `dot3_small`, each product by `mul_bits_le2`.
    #[inline(always)]
    fn dot3_le2(a: [Self; 3], b: [Self; 3]) -> Self {
        let p = |k: usize| mul_bits_le2(a[k].to_bits(), b[k].to_bits());
        Fixed22::from_bits(p(0).wrapping_add(p(1)).wrapping_add(p(2)))
    }
    /// As `cross3_small`, each product by `mul_bits_le2`.
    #[inline(always)]
    fn cross3_le2(a: [Self; 3], b: [Self; 3]) -> [Self; 3] {
        let p = |i: usize, j: usize| mul_bits_le2(a[i].to_bits(), b[j].to_bits());
        [
            Fixed22::from_bits(p(1, 2).wrapping_sub(p(2, 1))),
            Fixed22::from_bits(p(2, 0).wrapping_sub(p(0, 2))),
            Fixed22::from_bits(p(0, 1).wrapping_sub(p(1, 0))),
        ]
    }
    /// As `dot3_small`: each component a difference of two exact products (below 512 by the
    /// precondition).
    #[inline(always)]
    fn cross3_small(a: [Self; 3], b: [Self; 3]) -> [Self; 3] {
        let p = |i: usize, j: usize| mul_bits_small(a[i].to_bits(), b[j].to_bits());
        [
            Fixed22::from_bits(p(1, 2).wrapping_sub(p(2, 1))),
            Fixed22::from_bits(p(2, 0).wrapping_sub(p(0, 2))),
            Fixed22::from_bits(p(0, 1).wrapping_sub(p(1, 0))),
        ]
    }
    /// By `mul_bits_unit` when either triple lies within `(-1, 1]` (one unsigned comparison
    /// a component), with the other triple's components as `a`: exact `floor(a c
    /// / 2^22)` that cannot saturate, about 14 instead of 27 Cortex-M0 instructions a product;
    /// by `*` otherwise. The same bits either way. Inlined with both orders written out:
    /// about 3.4 KiB of the Cortex-M0 budget image (`opt-level = "s"`; when it was one image,
    /// 260 504 of the micro:bit's 262 144
    /// bytes), where one shared unit path saved 1 KiB and an out-of-line call 4.5 KiB; but
    /// the RP2040 demo's frame (`opt-level = 3`) was then 0.4 % (shared path) and 1.4 % (call:
    /// no faster than the saturating products) slower than with this.
    #[inline(always)]
    fn mul_each(a: [Self; 3], b: [Self; 3]) -> [Self; 3] {
        // -1 < c <= 1 for each component (1 itself: an exposure or a model's full value;
        // not -1, whose product with the most negative value leaves the range): one
        // unsigned comparison each.
        let within = |v: [Self; 3]| {
            let inside = |c: Self| (c.to_bits().wrapping_add((1 << FRAC) - 1) as u32) < 2 << FRAC;
            inside(v[0]) && inside(v[1]) && inside(v[2])
        };
        let unit = |x: [Self; 3], c: [Self; 3]| {
            let p = |k: usize| Fixed22::from_bits(mul_bits_unit(x[k].to_bits(), c[k].to_bits()));
            [p(0), p(1), p(2)]
        };
        if within(a) {
            unit(b, a)
        } else if within(b) {
            unit(a, b)
        } else {
            [a[0] * b[0], a[1] * b[1], a[2] * b[2]]
        }
    }
    /// `mul_bits_unit`: exact `floor(a c / 2^22)` without the saturation test (`|c| <= 1`).
    #[inline(always)]
    fn mul_unit(a: Self, c: Self) -> Self {
        Fixed22::from_bits(mul_bits_unit(a.to_bits(), c.to_bits()))
    }
    /// The 16-bit mantissas of the fast path in place of `k`, and their shift, where `fast`
    /// and the environment's error bound allow it (`sh9_q15`); else 0.
    #[cfg(feature = "sh9")]
    fn sh9_pack(k: &mut [crate::Rgb<Self>; 9], fast: bool) -> u8 {
        if fast {
            super::sh9_q15::pack(k).unwrap_or(0)
        } else {
            0
        }
    }
    /// The fast path (`sh9_q15`: single 32-bit products of 16-bit factors, within `2^-11`)
    /// where the environment has one; else one fused dot product per channel
    /// (`dot8_split_bits`): every term's exact product summed in integers and rounded down
    /// once, where `*` and `+` round each of the 8 products down (up to 8 LSB) and saturate
    /// each partial sum. Its result is `floor(k0 + sum k m)` of the Q22 monomials,
    /// saturated: within 1 LSB of their exact value. Each monomial is split once for the
    /// three channels. 4 `MULS` and no saturation test a term. Both measured in the QEMU
    /// budget (see `Sh9Irradiance::irradiance`).
    #[cfg(feature = "sh9")]
    #[inline(always)]
    fn sh9_dot(
        k: &[crate::Rgb<Self>; 9],
        shift: u8,
        n: crate::UnitVec3<Self>,
    ) -> Option<crate::Rgb<Self>> {
        if shift != 0 {
            return Some(super::sh9_q15::irradiance(k, shift, n.array()));
        }
        let [xy, yz, xz, zz, xx_yy] = n.quadratic_monomials();
        let m = [n.x, n.y, n.z, xy, yz, xz, zz, xx_yy];
        // Written out (the M0 build at opt-level "s" keeps loops, through the stack).
        let s = |i: usize| split_11(m[i].to_bits());
        let [s0, s1, s2, s3, s4, s5, s6, s7] = [s(0), s(1), s(2), s(3), s(4), s(5), s(6), s(7)];
        let mh = [s0.0, s1.0, s2.0, s3.0, s4.0, s5.0, s6.0, s7.0];
        let ml = [s0.1, s1.1, s2.1, s3.1, s4.1, s5.1, s6.1, s7.1];
        let ch = |f: fn(&crate::Rgb<Self>) -> Self| {
            let b = |i: usize| f(&k[i]).to_bits();
            let rest = [b(1), b(2), b(3), b(4), b(5), b(6), b(7), b(8)];
            Fixed22::from_bits(dot8_split_bits(b(0), rest, &mh, &ml))
        };
        Some(crate::Rgb::new(ch(|c| c.r), ch(|c| c.g), ch(|c| c.b)))
    }
}
