//! The float backends, `f64` (the reference) and `f32`, from one macro over their math
//! functions (`libm`, the hardware square root of [`hw`](super::hw), the crate's polynomial
//! `atan2` and arc ratio), and the lean normalization they share ([`normalize3_lean`]: the
//! squared length directly, rescaled by a power of two only when it under- or overflows).

use super::Real;

/// `true` if every component is finite.
#[inline(always)]
fn finite3<T: Real>(v: [T; 3]) -> bool {
    v[0].is_finite() && v[1].is_finite() && v[2].is_finite()
}

/// The power-of-two bounds of [`normalize3_lean`] for one float type: the squared lengths
/// `[lo, hi]` it takes as they are, and the scale `up` (its inverse `down`) of the cold path.
#[derive(Clone, Copy)]
pub(crate) struct LeanBounds<T> {
    /// Below it, squares of the smaller components may be subnormal with an absolute rounding
    /// that is no longer negligible against the sum (or the sum underflowed).
    lo: T,
    /// The largest finite value: above it the sum overflowed.
    hi: T,
    /// Brings any vector whose squared length is below `lo` (but not zero) into `[lo, hi]`.
    up: T,
    /// `1/up`: brings any finite vector whose squared length overflowed into `[lo, hi]`.
    down: T,
}

/// f32: `lo = 2^-100`, `up = 2^100`. A squared length below `lo` with a nonzero component has
/// its largest component `m` in `[2^-149, 2^-50)`, so `m up` is in `[2^-49, 2^50)` and the new
/// squared length in `[2^-98, 3 2^100]`; one that overflowed has `m` in `[2^63, 2^128)`, and
/// `m down` is in `[2^-37, 2^28)`. In `[lo, hi]` a subnormal square of a smaller component is
/// off by at most `2^-150`, `2^-50` of the sum.
const LEAN_F32: LeanBounds<f32> = LeanBounds {
    lo: f32::from_bits((127 - 100) << 23),
    hi: f32::MAX,
    up: f32::from_bits((127 + 100) << 23),
    down: f32::from_bits((127 - 100) << 23),
};

/// f64: `lo = 2^-960`, `up = 2^600` (the same argument: `m < 2^-480` goes to `[2^-474, 2^120)`,
/// `m >= 2^511` to `[2^-89, 2^424)`; a subnormal square is off by at most `2^-1075`).
const LEAN_F64: LeanBounds<f64> = LeanBounds {
    lo: f64::from_bits((1023 - 960) << 52),
    hi: f64::MAX,
    up: f64::from_bits((1023 + 600) << 52),
    down: f64::from_bits((1023 - 600) << 52),
};

/// The lean normalization of the float types (see [`Real::normalize3`]): `(v / |v|, |v|,
/// 1/|v|)` from the squared length `s2` directly when it lies in `[lo, hi]`; otherwise (a cold
/// path, taken only by vectors whose squared length under- or overflows, and by zero, infinite
/// or NaN ones) `v` is scaled by the power of two `up` or `down` first, exactly, and the length
/// scaled back. [`LeanRoot::root`] returns `(sqrt(s2), 1/sqrt(s2))` for a normal positive
/// `s2`; the reciprocal is the hot path's own (the cold path's `1 / len`), for a caller that needs it
/// too (`Sealed::sphere_ratios`: one division fewer); `Real::normalize3` drops it. `finish`
/// receives the three and whether they came from the hot path, where `len` lies in `[2^-50,
/// 2^64]` (f32; f64 `[2^-480, 2^512]`), so that `1/len` is normal and rounded once: a caller
/// can rely on that there and pay for its cold-path case only on the cold path (the sphere's
/// `r/|v| <= 1`, `LeanFloat::sphere_ratios`). The flag is a constant at each of its two call
/// sites, so the test on it folds away.
///
/// Accuracy: each component within a few ULPs of the exact quotient (3 roundings in the
/// squared length, 1 in the root, 1 in the reciprocal, 1 in the product); the length within
/// 2 ULPs. Cost on the hot path: 3 products and 2 additions, [`LeanRoot::in_range`] (for `f32` and `f64` one
/// unsigned comparison of the bits, which the square root's `VMOV` then reuses: on the
/// Cortex-M4F `hemi_const` 49 -> 47 instructions, `sphere_lambert` with a `UnitVec3` 97 -> 93,
/// and on the soft-float Cortex-M0 two library comparisons fewer), `root`, 3 products (f32 on
/// the Cortex-M4F: one `VSQRT.F32` and one `VDIV.F32`), and no stack frame for the cold path's
/// call (see [`ColdUnit`]).
#[inline(always)]
pub(crate) fn normalize3_lean<T: LeanRoot, R>(
    v: [T; 3],
    finish: impl FnOnce([T; 3], T, T, bool) -> R,
) -> Option<R> {
    let s2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    if T::in_range(s2) {
        let (len, inv) = T::root(s2);
        Some(finish([v[0] * inv, v[1] * inv, v[2] * inv], len, inv, true))
    } else {
        let ColdUnit { u, len } = normalize3_cold::<T>(v[0], v[1], v[2]);
        if len > T::ZERO {
            Some(finish(u, len, T::ONE / len, false))
        } else {
            None
        }
    }
}

/// The lean normalization with its reciprocal ([`normalize3_lean`]) of `f32` and `f64`, and
/// their `Sealed::sphere_ratios` built on it.
pub(crate) trait LeanFloat: Sized {
    /// `(v / |v|, |v|, 1/|v|)`, the first two [`Real::normalize3`]'s bits.
    fn normalize3_inv(v: [Self; 3]) -> Option<([Self; 3], Self, Self)>;
    /// `Sealed::sphere_ratios` (see there), with `r/|v|` clamped to 1 on the cold path only.
    /// On the hot path `r < |v|` already keeps `r (1/|v|)` at most 1 without the clamp: `1/|v|`
    /// is normal and rounded to nearest once, so `r fl(1/|v|) <= (r/|v|)(1 + u) < 1 + u` (`u`
    /// the unit roundoff, `2^-24` for f32), and every product below `1 + u`, the midpoint
    /// between 1 and the next float, rounds to at most 1. The cold path's `1/|v|` may be
    /// subnormal (`|v|` above `2^126` in f32), with a larger relative error: there the clamp
    /// stays. The same bits as clamping always (Cortex-M4F f32 `sphere_lambert` 81 -> 76
    /// instructions: a comparison, a status transfer and a conditional move fewer).
    fn sphere_ratios(v: [Self; 3], r: Self) -> Option<super::sealed::SphereRatios<Self>>;
}

/// One float type's parts of [`normalize3_lean`]: its bounds and square root.
pub(crate) trait LeanRoot: Real {
    /// The squared lengths taken as they are, and the cold path's scales.
    const BOUNDS: LeanBounds<Self>;
    /// `lo <= s2 <= hi` (`BOUNDS`).
    fn in_range(s2: Self) -> bool;
    /// `(sqrt(s2), 1/sqrt(s2))` for a normal positive `s2`.
    fn root(s2: Self) -> (Self, Self);
}

/// The cold path's answer, `(v / |v|, |v|)`, with a zero length for no direction. `repr(C)`
/// and four floats: a homogeneous aggregate, which the hard-float C ABI returns in registers
/// (`s0` to `s3` on the Cortex-M4F), where Rust's ABI would return it, or an `Option` of it,
/// in memory and give every caller of the lean normalization a stack frame for it (Cortex-M4F
/// f32 medians, QEMU: `hemi_const` 46 -> 44 instructions, `sky_ground` 61 -> 59, `cap_lambert`
/// 46 -> 44, `phong_polygon` 1844 -> 1839; `line_lambert` and `phong_sphere` one more).
#[repr(C)]
#[derive(Clone, Copy)]
struct ColdUnit<T> {
    u: [T; 3],
    len: T,
}

/// The cold path of [`normalize3_lean`]: a zero length for a zero or non-finite vector, else
/// the vector scaled by a power of two into the hot range, normalized, and its length scaled
/// back. `extern "C"` for its return in registers ([`ColdUnit`]); its arguments are the
/// components one by one, not an array, which would be passed in memory (the hot path would
/// store it before its test).
#[cold]
#[inline(never)]
extern "C" fn normalize3_cold<T: LeanRoot>(x: T, y: T, z: T) -> ColdUnit<T> {
    let none = ColdUnit {
        u: [T::ZERO; 3],
        len: T::ZERO,
    };
    let v = [x, y, z];
    if !finite3(v) {
        return none;
    }
    let m = v[0].abs().max(v[1].abs()).max(v[2].abs());
    if !(m > T::ZERO) {
        return none;
    }
    let k = T::BOUNDS;
    let (f, back) = if m < T::ONE {
        (k.up, k.down)
    } else {
        (k.down, k.up)
    };
    let w = [v[0] * f, v[1] * f, v[2] * f];
    let s2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    // Always true by the bounds' argument (see `LEAN_F32`); kept so that no input can reach
    // `root` outside its domain.
    if !(s2 >= k.lo && s2 <= k.hi) {
        return none;
    }
    let (len, inv) = T::root(s2);
    ColdUnit {
        u: [w[0] * inv, w[1] * inv, w[2] * inv],
        len: len * back,
    }
}

#[cfg(not(feature = "libm"))]
compile_error!(
    "arealight needs a math backend for f32/f64: enable the `libm` feature \
     (it is on by default; with `default-features = false` add `features = [\"libm\"]`)"
);

macro_rules! impl_real_float {
    ($t:ty, $sqrt:path, $atan2:path, $ratio:path, $sin:path, $cos:path, $exp:path, $ln:path, $tiny:expr, $lean:expr) => {
        impl Real for $t {
            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const TWO: Self = 2.0;
            const HALF: Self = 0.5;
            const PI: Self = core::f64::consts::PI as $t;
            const FRAC_PI_2: Self = core::f64::consts::FRAC_PI_2 as $t;
            const TAU: Self = core::f64::consts::TAU as $t;
            const FRAC_1_PI: Self = core::f64::consts::FRAC_1_PI as $t;
            const FRAC_1_TAU: Self = (0.5 * core::f64::consts::FRAC_1_PI) as $t;
            const EPSILON: Self = <$t>::EPSILON;
            const TINY: Self = $tiny;

            #[inline(always)]
            fn from_f64(x: f64) -> Self {
                x as $t
            }
            #[inline(always)]
            fn from_u32(x: u32) -> Self {
                x as $t
            }
            #[inline(always)]
            fn to_f64(self) -> f64 {
                self as f64
            }
            /// The sign bit cleared: one `VABS.F32` with an FPU, one `AND` in soft float (the
            /// comparison and negation it replaced were 5 Cortex-M4F instructions, and a
            /// library call in soft float). `-0.0` gives `+0.0`.
            #[inline(always)]
            fn abs(self) -> Self {
                Self::from_bits(self.to_bits() & !(-0.0 as Self).to_bits())
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                if self > 0.0 {
                    $sqrt(self)
                } else {
                    0.0
                }
            }
            #[inline(always)]
            fn atan2(self, x: Self) -> Self {
                $atan2(self, x)
            }
            #[inline(always)]
            fn arc_ratio(self) -> Option<Self> {
                $ratio(self)
            }
            #[inline(always)]
            fn sin(self) -> Self {
                $sin(self)
            }
            #[inline(always)]
            fn cos(self) -> Self {
                $cos(self)
            }
            #[inline(always)]
            fn exp(self) -> Self {
                $exp(self)
            }
            #[inline(always)]
            fn ln(self) -> Self {
                $ln(self)
            }
            #[inline(always)]
            fn is_finite(self) -> bool {
                <$t>::is_finite(self)
            }
            /// In the type's own arithmetic (scaling by a power of two is exact).
            #[inline(always)]
            fn to_fixed_i32(self, frac: u32) -> i32 {
                let v = self * (1u32 << frac.min(30)) as $t + 0.5;
                let t = v as i32; // saturating, NaN -> 0
                if (t as $t) > v {
                    t.saturating_sub(1)
                } else {
                    t
                }
            }
            #[inline(always)]
            fn from_fixed_i32(x: i32, frac: u32) -> Self {
                x as $t * (1.0 / (1u32 << frac.min(30)) as $t)
            }
            /// In the type's own arithmetic: `as` saturates (and maps NaN to 0).
            #[inline(always)]
            fn unit_to_u32(self, max: u32) -> u32 {
                ((self.clamp01() * max as $t + 0.5) as u32).min(max)
            }
            /// The lean form (`normalize3_lean`, its reciprocal dropped): squared length, one
            /// square root, one division, three products; a power-of-two rescaling only on the
            /// cold path.
            #[inline(always)]
            fn normalize3(v: [Self; 3]) -> Option<([Self; 3], Self)> {
                <Self as LeanFloat>::normalize3_inv(v).map(|(u, len, _)| (u, len))
            }
            /// [`Real::normalize3`] without the length (the same operations).
            #[inline(always)]
            fn unit3(v: [Self; 3]) -> Option<[Self; 3]> {
                Self::normalize3(v).map(|(u, _)| u)
            }
        }
        impl LeanFloat for $t {
            #[inline(always)]
            fn normalize3_inv(v: [Self; 3]) -> Option<([Self; 3], Self, Self)> {
                normalize3_lean(v, |u, len, inv, _| (u, len, inv))
            }
            #[inline(always)]
            fn sphere_ratios(v: [Self; 3], r: Self) -> Option<super::sealed::SphereRatios<Self>> {
                normalize3_lean(v, |u, d, inv, hot| {
                    let ss = r * inv;
                    (u, d, if hot { ss } else { Real::min(ss, 1.0) }, [d, r, inv])
                })
            }
        }
        impl LeanRoot for $t {
            const BOUNDS: LeanBounds<Self> = $lean;
            /// `lo <= s2 <= hi` as one unsigned comparison of the bits (the same answer for
            /// every `s2`: positive floats order as their bits, and a negative or NaN `s2`
            /// falls outside, as it does the float comparisons).
            #[inline(always)]
            fn in_range(s2: Self) -> bool {
                let (lo, hi) = ($lean.lo.to_bits(), $lean.hi.to_bits());
                s2.to_bits().wrapping_sub(lo) <= hi - lo
            }
            #[inline(always)]
            fn root(s2: Self) -> (Self, Self) {
                let r = $sqrt(s2);
                (r, 1.0 / r)
            }
        }
    };
}

// TINY: about the square root of the smallest normal, so squares of lengths above it are normal.
impl_real_float!(
    f64,
    libm::sqrt,
    libm::atan2,
    super::arc_ratio::no_arc_ratio,
    libm::sin,
    libm::cos,
    libm::exp,
    libm::log,
    1.0e-150,
    LEAN_F64
);
// The hardware square root where the target has one (`hw`), else libm's: the same bits.
impl_real_float!(
    f32,
    super::hw::sqrtf,
    super::f32_math::atan2,
    super::arc_ratio::arc_ratio_f32,
    libm::sinf,
    libm::cosf,
    libm::expf,
    libm::logf,
    1.0e-18,
    LEAN_F32
);

#[cfg(test)]
mod tests {
    extern crate std;
    use super::LeanFloat;
    use crate::Real;

    /// `normalize3_inv` is `normalize3`'s unit vector and length, bit for bit, and `1 / len`,
    /// on the hot path and on both sides of the cold one (squares that under- and overflow),
    /// for zero, infinite and NaN vectors alike (`None`).
    #[test]
    fn normalize3_inv_is_normalize3_and_the_reciprocal() {
        fn check<T: Real + LeanFloat + core::fmt::Debug>(vs: &[[T; 3]]) {
            for &v in vs {
                let a = <T as LeanFloat>::normalize3_inv(v);
                let b = T::normalize3(v);
                match (a, b) {
                    (Some((u, len, inv)), Some((w, l))) => {
                        assert_eq!((u, len), (w, l), "{v:?}");
                        assert_eq!(inv, T::ONE / len, "{v:?}");
                    }
                    (None, None) => {}
                    _ => panic!("{v:?}: {a:?} against {b:?}"),
                }
            }
        }
        let mut state = crate::test_rng::xorshift32(0x9E37_79B9);
        let mut next = move || f64::from(state()) / f64::from(u32::MAX) * 2.0 - 1.0;
        let mut v64 = std::vec::Vec::new();
        for scale in [1.0, 1e-30, 1e-170, 1e30, 1e170, 1e300, 0.0] {
            for _ in 0..200 {
                v64.push([next() * scale, next() * scale, next() * scale]);
            }
        }
        v64.push([f64::INFINITY, 0.0, 1.0]);
        v64.push([f64::NAN, 1.0, 1.0]);
        let v32: std::vec::Vec<[f32; 3]> = v64.iter().map(|v| v.map(|x| x as f32)).collect();
        check(&v64);
        check(&v32);
    }

    /// The floats' below, and the default `Sealed::sphere_ratios` (normalize, divide, clamp
    /// always) written out: `sphere_ratios` gives its bits on both paths, the clamp being
    /// needless on the hot one (`LeanFloat::sphere_ratios`' argument) and needed on the cold
    /// one, where `1/|v|` is subnormal (at least one case there clamps).
    #[test]
    fn sphere_ratios_is_the_always_clamped_quotient() {
        trait Next: Real + LeanFloat + core::fmt::Debug {
            /// The largest value below `self` (positive normal `self`).
            fn below(self) -> Self;
        }
        impl Next for f32 {
            fn below(self) -> Self {
                f32::from_bits(self.to_bits() - 1)
            }
        }
        impl Next for f64 {
            fn below(self) -> Self {
                f64::from_bits(self.to_bits() - 1)
            }
        }
        fn check<T: Next>(vs: &[[T; 3]]) -> usize {
            let mut clamped = 0;
            for &v in vs {
                let Some((u, d)) = T::normalize3(v) else {
                    assert!(
                        <T as LeanFloat>::sphere_ratios(v, T::ONE).is_none(),
                        "{v:?}"
                    );
                    continue;
                };
                let inv = T::ONE / d;
                let half = d * T::from_f64(0.5);
                for r in [
                    d.below(),
                    d.below().below(),
                    d * T::from_f64(0.999_999),
                    half,
                ] {
                    let got = <T as LeanFloat>::sphere_ratios(v, r);
                    let ss = (r * inv).min(T::ONE);
                    assert_eq!(got, Some((u, d, ss, [d, r, inv])), "{v:?}, r = {r:?}");
                    assert!(ss <= T::ONE && ss > T::ZERO, "{v:?}, r = {r:?}");
                    clamped += usize::from(r * inv > T::ONE);
                }
            }
            clamped
        }
        let mut state = crate::test_rng::xorshift32(0x2545_F491);
        let mut next = move || f64::from(state()) / f64::from(u32::MAX) * 2.0 - 1.0;
        let mut v32 = std::vec::Vec::new();
        let mut v64 = std::vec::Vec::new();
        for (scale32, scale64) in [(1.0, 1.0), (1e-30, 1e-170), (1e30, 1e170), (1.9e38, 1e308)] {
            for _ in 0..2000 {
                let w = [next(), next(), next()];
                v32.push(w.map(|x| (x * scale32) as f32));
                v64.push(w.map(|x| x * scale64));
            }
        }
        v32.push([0.0; 3]);
        v64.push([f64::NAN, 0.0, 1.0]);
        assert!(check(&v32) > 0, "no f32 case needed the cold path's clamp");
        assert!(check(&v64) > 0, "no f64 case needed the cold path's clamp");
    }
}
