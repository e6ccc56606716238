//! The seal of [`Real`](super::Real), and the crate-internal arithmetic that only the crate may call: its
//! preconditions are kept by the crate's types (a [`UnitVec3`](crate::UnitVec3) is unit), so
//! it is not part of the public trait.

use core::ops::{Add, Mul, Sub};

/// [`Sealed::sphere_ratios`]' answer: `(v / |v|, |v|, min(r / |v|, 1), parts)`, `cos sigma
/// = Sealed::sphere_cos(parts)`.
pub type SphereRatios<T> = ([T; 3], T, T, [T; 3]);

pub trait Sealed: Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> {
    /// What a `PreparedMesh` keeps of its last transform to compute its vertices' normals
    /// where first needed: in fixed point, whose normalization makes the normal the
    /// costly part of a vertex's transform, the normal matrix's rows and whether they are
    /// small (`Affine::is_small`); nothing for the floats, which compute the normals in
    /// the transform. (Kept as 44 bytes with `f32` too, the field had cost the STM32F411's
    /// Gouraud frame 0 about 1 800 instructions, by the demo's layout alone.)
    #[cfg(feature = "raster")]
    type KeptNormals: Copy + core::fmt::Debug;
    /// Nothing kept.
    #[cfg(feature = "raster")]
    const NO_KEPT_NORMALS: Self::KeptNormals;
    /// Keeps `rows` and `small` (the floats: nothing).
    #[cfg(feature = "raster")]
    fn keep_normals(rows: [crate::Vec3<Self>; 3], small: bool) -> Self::KeptNormals;
    /// What [`Sealed::keep_normals`] kept (the floats: `None`).
    #[cfg(feature = "raster")]
    fn kept_normals(kept: &Self::KeptNormals) -> Option<([crate::Vec3<Self>; 3], bool)>;
    /// `a.x b.x + a.y b.y + a.z b.z` for vectors whose components are below 16 in
    /// magnitude and whose products and their sum are below 512 (unit vectors and the
    /// cross product of two; offsets between positions within the fixed-point coordinate
    /// limit, at most 8, and their differences): the value of
    /// [`Vec3::dot`](crate::Vec3::dot), bit for bit. Fixed point leaves out the saturation
    /// tests its products and sums need elsewhere (its override: each product exact
    /// there, with no intermediate overflow); outside that range its result is
    /// unspecified, so only callers that keep the bounds call it.
    #[inline(always)]
    fn dot3_small(a: [Self; 3], b: [Self; 3]) -> Self {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }
    /// The camera's clip coordinates: an offset `d` from the eye (components below 16 in
    /// magnitude, as between points within the coordinate limit) along one of its unit axes.
    /// The floats: [`dot3_small`](Sealed::dot3_small)'s bits. [`Fixed22`](super::Fixed22)
    /// sums the three exact products and rounds once, to within 7/8 of a unit of `2^-22`
    /// (`kernels::dot3_unit_round`), where `dot3_small`'s three floors lose up to 3 units.
    #[cfg(feature = "raster")]
    #[inline(always)]
    fn dot3_axis(d: [Self; 3], axis: [Self; 3]) -> Self {
        Self::dot3_small(d, axis)
    }
    /// `a * b` rounded to nearest: the floats' product; [`Fixed22`](super::Fixed22) rounds
    /// half up where `*` rounds down (both saturate). The camera's projection scales.
    #[cfg(feature = "raster")]
    #[inline(always)]
    fn mul_nearest(a: Self, b: Self) -> Self {
        a * b
    }
    /// [`mul_small`](Sealed::mul_small) for factors of at most 2 in magnitude, plus `2^-6`
    /// (unit vectors' components, their cross products and quadratic monomials, cosines and
    /// sines and `1 +- c` of them): the same bits;
    /// [`Fixed22`](super::Fixed22) takes three 32-bit products where `mul_small` takes four
    /// (`kernels::mul_bits_le2`).
    #[inline(always)]
    fn mul_le2(a: Self, b: Self) -> Self {
        Self::mul_small(a, b)
    }
    /// [`dot3_small`](Sealed::dot3_small) for components of at most 2 in magnitude (unit
    /// vectors and the cross product of two): the same bits, by [`mul_le2`](Sealed::mul_le2)
    /// on [`Fixed22`](super::Fixed22).
    #[inline(always)]
    fn dot3_le2(a: [Self; 3], b: [Self; 3]) -> Self {
        Self::dot3_small(a, b)
    }
    /// [`cross3_small`](Sealed::cross3_small) for components of at most 2 in magnitude: the
    /// same bits, by [`mul_le2`](Sealed::mul_le2) on [`Fixed22`](super::Fixed22).
    #[inline(always)]
    fn cross3_le2(a: [Self; 3], b: [Self; 3]) -> [Self; 3] {
        Self::cross3_small(a, b)
    }
    /// `max |v_i| <= COORDINATE_LIMIT`: [`Vec3::check_position`](crate::Vec3::check_position)'s
    /// range test, for the backends with a limit (fixed point; the floats have none and never
    /// call it). This default compares the largest magnitude;
    /// [`Fixed22`](super::Fixed22) tests each component's raw bits against the limit's with
    /// one unsigned comparison, the same answer (a saturated component is beyond it).
    #[inline(always)]
    fn within_coordinate_limit(v: [Self; 3]) -> bool
    where
        Self: super::Real,
    {
        use super::Real as R;
        let m = R::max(R::max(R::abs(v[0]), R::abs(v[1])), R::abs(v[2]));
        m <= <Self as R>::from_f64(<Self as R>::COORDINATE_LIMIT)
    }
    /// The cosine `a . b` of two unit vectors (each component at most `1 + 2^-16` in
    /// magnitude, which every `UnitVec3` keeps) for the Lambert-type terms, whose value moves no
    /// more than the cosine does (`hemi_const`, `sky_ground`, the exact cap and the sphere):
    /// [`dot3_small`](Sealed::dot3_small)'s bits on the floats. [`Fixed22`](super::Fixed22)
    /// rounds both vectors to Q15 and takes the three products as single 32-bit products
    /// (one `MULS` each on the Cortex-M0, where `dot3_small` takes four), the sum rounded
    /// from Q30 to Q22: within `2^-16 (|a|_1 + |b|_1) + 2^-23` (at most 5.3e-5 + 1.2e-7) of
    /// the exact `a . b` of its inputs (`fixed22::kernels::cos_unit_q15`, tested there).
    /// The Phong terms keep `dot3_small`: their sensitivity to the cosine grows with `m`.
    #[inline(always)]
    fn cos_unit(a: [Self; 3], b: [Self; 3]) -> Self {
        Self::dot3_small(a, b)
    }
    /// A light's fixed unit axis `b` in the form [`cos_axis`](Sealed::cos_axis) takes, made
    /// once at the light's construction: on the floats `b` itself; on
    /// [`Fixed22`](super::Fixed22) its components rounded to Q15 (held in the raw bits), the
    /// rounding that `cos_unit` makes of `b` on every call (about 6 Cortex-M0 instructions).
    #[inline(always)]
    fn prepare_axis(b: [Self; 3]) -> [Self; 3] {
        b
    }
    /// [`cos_unit`](Sealed::cos_unit)`(a, b)`, bit for bit, from `bq =
    /// prepare_axis(b)`.
    #[inline(always)]
    fn cos_axis(a: [Self; 3], bq: [Self; 3]) -> Self {
        Self::cos_unit(a, bq)
    }
    /// `mid + half c` componentwise, for the cosine `c = a . b` of two unit vectors clamped to
    /// `[-1, 1]` (`b` a light's axis, `bq = prepare_axis(b)`):
    /// `sky_ground`'s irradiance. Precondition: `mid = s + g` and `half = s - g` for `s` and
    /// `g` each within half the type's range (`SkyGround::new` makes them so from its
    /// colours: `s = sky/2`, `g = ground/2`), so that `mid + half c` lies between `2 s` and
    /// `2 g` for every `|c| <= 1`. On the floats `c` is [`cos_unit`](Sealed::cos_unit)'s and
    /// each product [`mul_unit`](Sealed::mul_unit)'s, the sum `+`: the same bits as before;
    /// [`Fixed22`](super::Fixed22) keeps `c` in Q15, takes each product from two 32-bit
    /// products (`kernels::cos_prepared_q15_clamped`, `kernels::mul_q15`: within `(5.3e-5 +
    /// 2^-16) |half_i| + 2^-22` of `half_i` times the exact cosine of its inputs) and adds
    /// without the saturation test, which the precondition makes unreachable
    /// (`kernels::mix_by_cos`).
    #[cfg(feature = "hemisphere")]
    #[inline(always)]
    fn mix_by_cos(mid: [Self; 3], half: [Self; 3], a: [Self; 3], bq: [Self; 3]) -> [Self; 3]
    where
        Self: super::Real,
    {
        let one = <Self as super::Real>::ONE;
        let c = <Self as super::Real>::clamp(Self::cos_axis(a, bq), -one, one);
        [
            mid[0] + Self::mul_unit(half[0], c),
            mid[1] + Self::mul_unit(half[1], c),
            mid[2] + Self::mul_unit(half[2], c),
        ]
    }
    /// `a - b` componentwise for positions within the fixed-point coordinate limit (each
    /// difference at most 8 in magnitude): the value of [`Vec3`]'s `-`, bit for bit (fixed
    /// point without its saturation tests, which cannot trigger there).
    #[inline(always)]
    fn sub3_small(a: [Self; 3], b: [Self; 3]) -> [Self; 3] {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }
    /// `a b` under the same precondition (factors below 16, the product below 512): the
    /// value of `*`, bit for bit (fixed point without its saturation test).
    #[inline(always)]
    fn mul_small(a: Self, b: Self) -> Self {
        a * b
    }
    /// The cross product under the same precondition: the value of
    /// [`Vec3::cross`](crate::Vec3::cross), bit for bit.
    #[inline(always)]
    fn cross3_small(a: [Self; 3], b: [Self; 3]) -> [Self; 3] {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }
    /// The channel-wise product `[a0 b0, a1 b1, a2 b2]` of any two triples (colours): the
    /// value of `*`, bit for bit. Fixed point skips the saturation tests when either triple
    /// lies within `(-1, 1]` (a model's normalized value, a reflectance), where a product
    /// cannot saturate.
    #[inline(always)]
    fn mul_each(a: [Self; 3], b: [Self; 3]) -> [Self; 3] {
        [a[0] * b[0], a[1] * b[1], a[2] * b[2]]
    }
    /// `a c` for a factor `c` of at most 1 in magnitude (and `a` above the most negative
    /// value of the type when `c = -1`): the value of `*`, bit for bit (fixed point without
    /// its saturation test, which such a product never needs: `|a c| <= |a|`).
    #[inline(always)]
    fn mul_unit(a: Self, c: Self) -> Self {
        a * c
    }
    /// The ratios of a sphere of radius `r` seen along `v` (its centre minus the point):
    /// `Some((v / |v|, |v|, min(r / |v|, 1), parts))` for a finite nonzero `v`, the second
    /// ratio `sqrt(|v|^2 - r^2) / |v|` being [`Sealed::sphere_cos`]`(parts)` (the ratios
    /// unspecified unless `|v| > r`, where the first lies in `[0, 1]`), `None` otherwise.
    /// That second ratio is left to the caller, which needs it only where the cap straddles
    /// the horizon or for Phong. This default is [`Real::normalize3`], `1 / |v|` and the
    /// products `r (1/|v|)` (clamped to 1: rounding may take it above) and `sqrt((|v| -
    /// r)(|v| + r)) (1/|v|)` (near the sphere `r/|v|` is close to 1 and `1 - (r/|v|)^2`
    /// would keep only its rounding). `f32` and `f64` give the same bits with one division
    /// fewer (the normalization's own reciprocal) and the clamp on their normalization's
    /// cold path only (`float::LeanFloat::sphere_ratios`, which proves it needless on the
    /// hot one); [`Fixed22`](super::Fixed22) computes both ratios in its normalization's
    /// rescaled space from the reciprocal square root it computes anyway (no division).
    #[inline(always)]
    fn sphere_ratios(v: [Self; 3], r: Self) -> Option<SphereRatios<Self>>
    where
        Self: super::Real,
    {
        let (u, d) = <Self as super::Real>::normalize3(v)?;
        let inv_d = <Self as super::Real>::ONE / d;
        let ss = <Self as super::Real>::min(r * inv_d, <Self as super::Real>::ONE);
        Some((u, d, ss, [d, r, inv_d]))
    }
    /// `cos sigma` from [`Sealed::sphere_ratios`]' parts: the floats' `sqrt((d - r)(d +
    /// r)) (1/d)` from `[d, r, 1/d]`.
    #[inline(always)]
    fn sphere_cos(parts: [Self; 3]) -> Self
    where
        Self: super::Real,
    {
        let [d, r, inv_d] = parts;
        <Self as super::Real>::sqrt((d - r) * (d + r)) * inv_d
    }
    /// The per-channel sums of SH9 irradiance, `k0 + sum k[i+1] m[i]`, for the eight
    /// non-constant monomials `m` of a unit vector (each at most 1 in magnitude, within
    /// rounding), where the backend has a cheaper form than 9 products and additions in
    /// its own arithmetic. `None` (the default: the floats) lets the caller run the
    /// generic loop; [`Fixed22`](super::Fixed22) answers one exact fused dot product per
    /// channel, rounded down once (see its override).
    /// `(ua x d, ua.ub)` scaled by one positive factor (a power of two), where the backend
    /// can form them exactly: `None` (the default: the floats, whose products are
    /// relative anyway) lets the caller take its own products. [`Fixed22`](super::Fixed22)
    /// forms every product and sum exactly in 64 bits (coordinates below `2^7`; beyond,
    /// `None`), then keeps the 23 bits from the largest's leading bit: `G` and `ua.ub` to a
    /// relative `2^-22` however much the differences cancel (a point near an edge's line,
    /// where `G` is small).
    #[cfg(feature = "polygon")]
    #[inline(always)]
    fn cross_dot_scaled(ua: [Self; 3], ub: [Self; 3], d: [Self; 3]) -> Option<([Self; 3], Self)> {
        let _ = (ua, ub, d);
        None
    }
    /// `true` if every component of `v` is below `r` in magnitude (`r > 0`): the polygon
    /// kernels' test of a point's distance ([`crate::polygon`]'s `near_limit`). This
    /// default compares the largest magnitude; [`Fixed22`](super::Fixed22) tests each
    /// component's raw bits against `(-r, r)` with one unsigned comparison (a saturated
    /// component counts as far).
    #[cfg(any(feature = "polygon", feature = "raster"))]
    #[inline(always)]
    fn all_within(v: [Self; 3], r: Self) -> bool
    where
        Self: super::Real,
    {
        let m = <Self as super::Real>::max(
            <Self as super::Real>::max(
                <Self as super::Real>::abs(v[0]),
                <Self as super::Real>::abs(v[1]),
            ),
            <Self as super::Real>::abs(v[2]),
        );
        m < r
    }
    /// `dot3_small(a, b) >= 0` under its precondition with `b` a unit vector: whether a
    /// vertex at offset `a` lies above the horizon of the normal `b` (the polygon walks'
    /// test). This default is that comparison; [`Fixed22`](super::Fixed22) decides it from
    /// 16-bit products where their error cannot change the sign, the same answer for about a
    /// third of the Cortex-M0 instructions (`fixed22::sealed`).
    #[cfg(feature = "polygon")]
    #[inline(always)]
    fn height_nonneg(a: [Self; 3], b: [Self; 3]) -> bool
    where
        Self: super::Real,
    {
        Self::dot3_small(a, b) >= <Self as super::Real>::ZERO
    }
    /// The unit vector of `v` in Q15 (`i32` components of at most `2^15` in magnitude), `None`
    /// exactly where [`Real::unit3`](super::Real::unit3) is: the directions of the polygon
    /// Lambert edge terms in 16-bit form (`polygon::edge::unit_ratio_term`). This default
    /// rounds `unit3`'s components to Q15; [`Fixed22`](super::Fixed22) normalizes in 16-bit
    /// form directly (`fixed22::normalize::unit_q15`: about 130 instead of about 330
    /// Cortex-M0 instructions as inlined in the polygon Lambert term, within 1.1e-4 a
    /// component, 5.2e-5 measured, instead of `2^-16`).
    #[cfg(feature = "polygon")]
    #[inline(always)]
    fn unit3_q15(v: [Self; 3]) -> Option<[i32; 3]>
    where
        Self: super::Real,
    {
        let u = <Self as super::Real>::unit3(v)?;
        Some(u.map(|c| <Self as super::Real>::to_fixed_i32(c, 15)))
    }
    /// The Phong edge terms' plane quantities from an edge's unit end directions `a`, `b`:
    /// given `g = a x b` (not normalized; `|g| = sin x <= 1`), a unit `r` and `d = r.b - (a.b)
    /// (r.a)` (which is `r.(g x a)`, as `(a x b) x a = b - (a.b) a`), returns `(r.g/|g|,
    /// d/|g|, |g|)`: the plane normal's cosine `r.gu`, the arc's `r.(gu x a)` without the
    /// normalized `gu` or its triple product, and `sin x`. `None` exactly where
    /// [`Real::normalize3`](super::Real::normalize3) of `g` is. This default normalizes `g`
    /// and divides `d` by `|g|` (the floats never call it: the edge terms from unit
    /// directions are fixed point's); [`Fixed22`](super::Fixed22) scales `g` and `d` by the
    /// same power of two and takes one reciprocal square root
    /// (`fixed22::normalize::edge_plane_terms`).
    #[cfg(all(feature = "polygon", feature = "phong"))]
    #[inline(always)]
    fn edge_plane_terms(g: [Self; 3], r: [Self; 3], d: Self) -> Option<(Self, Self, Self)>
    where
        Self: super::Real,
    {
        let (gu, s) = <Self as super::Real>::normalize3(g)?;
        Some((Self::dot3_le2(r, gu), d / s, s))
    }
    /// The arc ratio `R(c) = acos(c)/sqrt(1 - c^2)` in Q15 (rounded) of a cosine `c` in Q30
    /// in `[0, 1]`, for the 16-bit polygon edge terms (`polygon::edge::unit_ratio_term`);
    /// `None` where the backend has no [`Real::arc_ratio`](super::Real::arc_ratio). This
    /// default goes through `arc_ratio` (`c` rounded to Q22, the ratio rounded to Q15);
    /// [`Fixed22`](super::Fixed22) evaluates the same pieces in 32-bit products
    /// (`fixed22::elementary::arc_ratio_q30_to_q15`: within 4.2e-6 before the rounding).
    #[cfg(feature = "polygon")]
    #[inline(always)]
    fn arc_ratio_q15(c: i32) -> Option<i32>
    where
        Self: super::Real,
    {
        let c = <Self as super::Real>::from_fixed_i32((c + (1 << 7)) >> 8, 22);
        let ratio = <Self as super::Real>::arc_ratio(c)?;
        Some((<Self as super::Real>::to_fixed_i32(ratio, 22) + (1 << 6)) >> 7)
    }
    /// `x 2^-60` rounded to the type (to nearest; fixed point half up), for `|x| <= 2^62`:
    /// a coordinate of [`crate::world`]'s rescaled differences, whose largest magnitude is
    /// in `[2, 4]`. Every backend overrides it (no f64 on the way).
    fn from_q60(x: i64) -> Self;
    /// `from_q60(x << k)`, for `k <= 61` and `x << k` within an `i64` (what
    /// [`crate::world`]'s scaling leaves), without the 64-bit shift where the type can do
    /// without: the floats
    /// round `x` and scale the result by `2^(k - 60)` (exact: rounding commutes with a power
    /// of two), fixed point shifts right by `37 - k` before its rounding. The same bits as
    /// the default, `from_q60(x << k)` (`world::tests::the_shifted_conversions_are_the_shifts`).
    #[inline(always)]
    fn from_q60_shl(x: i64, k: u32) -> Self {
        Self::from_q60(x << k)
    }
    /// Packs the irradiance polynomial `k` into the type's own form, in place, and returns
    /// what the evaluation needs besides (`fast`: fixed point's 16-bit fast path where the
    /// environment allows it, `fixed22::sh9_q15`: `k` becomes its mantissas and the result
    /// their shift; otherwise `k` is left as it is and the result is 0).
    #[cfg(feature = "sh9")]
    #[inline(always)]
    fn sh9_pack(k: &mut [crate::Rgb<Self>; 9], fast: bool) -> u8 {
        let _ = (k, fast);
        0
    }
    /// The packed polynomial `k` (with [`sh9_pack`](Sealed::sh9_pack)'s `shift`) at the unit
    /// normal `n` in the type's own evaluation; `None` for the generic one (the floats:
    /// products and sums in order).
    #[cfg(feature = "sh9")]
    #[inline(always)]
    fn sh9_dot(
        k: &[crate::Rgb<Self>; 9],
        shift: u8,
        n: crate::UnitVec3<Self>,
    ) -> Option<crate::Rgb<Self>> {
        let _ = (k, shift, n);
        None
    }
}
/// The floats' [`Sealed::KeptNormals`]: nothing (they compute the normals in the
/// transform).
macro_rules! floats_keep_no_normals {
    () => {
        #[cfg(feature = "raster")]
        type KeptNormals = ();
        #[cfg(feature = "raster")]
        const NO_KEPT_NORMALS: () = ();
        #[cfg(feature = "raster")]
        #[inline(always)]
        fn keep_normals(_: [crate::Vec3<Self>; 3], _: bool) {}
        #[cfg(feature = "raster")]
        #[inline(always)]
        fn kept_normals(_: &()) -> Option<([crate::Vec3<Self>; 3], bool)> {
            None
        }
    };
}
impl Sealed for f32 {
    floats_keep_no_normals!();
    #[inline(always)]
    fn sphere_ratios(v: [Self; 3], r: Self) -> Option<SphereRatios<Self>> {
        <f32 as super::float::LeanFloat>::sphere_ratios(v, r)
    }
    /// `x as f32` (one rounding to nearest), then an exact product by a power of two; the
    /// conversion through [`i64_to_f32`], the same bits as `as` from the FPU's 32-bit
    /// conversion.
    #[inline(always)]
    fn from_q60(x: i64) -> Self {
        super::i64_to_f32(x) * (1.0 / (1u64 << 60) as f32)
    }
    #[inline(always)]
    fn from_q60_shl(x: i64, k: u32) -> Self {
        // 2^(k - 60) from its bits (k <= 61: a normal f32).
        super::i64_to_f32(x) * f32::from_bits((127 + k.min(61) - 60) << 23)
    }
}
impl Sealed for f64 {
    floats_keep_no_normals!();
    #[inline(always)]
    fn sphere_ratios(v: [Self; 3], r: Self) -> Option<SphereRatios<Self>> {
        <f64 as super::float::LeanFloat>::sphere_ratios(v, r)
    }
    #[inline(always)]
    fn from_q60(x: i64) -> Self {
        x as f64 * (1.0 / (1u64 << 60) as f64)
    }
    #[inline(always)]
    fn from_q60_shl(x: i64, k: u32) -> Self {
        x as f64 * f64::from_bits(u64::from(1023 + k.min(61) - 60) << 52)
    }
}
impl Sealed for super::Fast32 {
    floats_keep_no_normals!();
    #[inline(always)]
    fn from_q60(x: i64) -> Self {
        super::Fast32(<f32 as Sealed>::from_q60(x))
    }
    #[inline(always)]
    fn from_q60_shl(x: i64, k: u32) -> Self {
        super::Fast32(<f32 as Sealed>::from_q60_shl(x, k))
    }
}
