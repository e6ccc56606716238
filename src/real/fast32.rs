//! `Fast32`: f32 with the crate's own cheap arctangent (and f32's square root).
//!
//! The per-sample work of every model is a handful of square roots (normalizing directions) and
//! arctangents (edge angles, cap boundaries). [`fast_atan2`] replaces `atan2f` by a few dozen
//! float operations and keeps every model within 1/1024 of the f64 reference (asserted in
//! `tests/`). The square root is f32's: `VSQRT.F32` on the Cortex-M4F and `libm::sqrtf`
//! elsewhere, correctly rounded, and cheaper than this module's [`fast_sqrt`] on both kinds of
//! target (measured, the QEMU budget, median instructions per call: `polygon_lambert` 914 -> 692
//! on the Cortex-M4F and 32 149 -> 28 448 on the Cortex-M0 when `Fast32` took f32's; no model
//! dearer on either). [`fast_sqrt`] and [`fast_rsqrt`] remain as standalone approximations.
//! `Fast32` now costs what `f32` does (1.00 to 1.02 times its instructions on the Cortex-M4F,
//! 0.92 to 1.00 on the Cortex-M0; 1.00 to 1.42 and 0.99 to 1.22 with [`fast_sqrt`]); use `f32`,
//! or [`crate::Fixed22`] on chips without an FPU.
//!
//! Why not micromath: its `atan2` is off by up to 2.8e-3 rad and its `sqrt` by several
//! percent (measured in this module's tests), which puts a four-edge polygon light past the
//! 1/1024 model budget. The functions here:
//!
//! | function | method | max error (measured over the test sweep) |
//! |---|---|---|
//! | [`fast_rsqrt`] | bit-level initial guess (magic 0x5f375a86) + 2 Newton steps | 4.8e-6 relative (4.76e-6 measured) |
//! | [`fast_sqrt`] | `x * fast_rsqrt(x)` | 4.8e-6 relative |
//! | [`fast_atan2`] | octant reduction, odd minimax polynomial of degree 9 (Abramowitz & Stegun 4.4.49) | 1.2e-5 rad (1.17e-5 measured: the polynomial's 1e-5 plus f32 rounding) |
//!
//! `sin`/`cos` are only used when a light is built, never per sample, so `Fast32` uses libm's
//! there; `exp`/`ln` (the shaping functions) are libm's too for now. Vector normalization is
//! f32's ([`Real::normalize3`]: the squared length, f32's square root, one division): on the
//! Cortex-M4F its `VSQRT.F32` is cheaper than the rescaled form with [`fast_rsqrt`] (42
//! against 119 instructions a call; 1761 against 3509 on the Cortex-M0), and exact to a few
//! ULPs.

use super::Real;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

/// An `f32` whose `sqrt` and `atan2` are the crate's cheap approximations (see the module docs).
///
/// Convert with `Fast32(x)` / `.0`, or `From`.
#[derive(Clone, Copy, Debug, Default, PartialEq, PartialOrd)]
#[repr(transparent)]
pub struct Fast32(pub f32);

impl From<f32> for Fast32 {
    #[inline(always)]
    fn from(x: f32) -> Self {
        Fast32(x)
    }
}
impl From<Fast32> for f32 {
    #[inline(always)]
    fn from(x: Fast32) -> Self {
        x.0
    }
}

macro_rules! binop {
    ($tr:ident, $f:ident, $atr:ident, $af:ident, $op:tt) => {
        impl $tr for Fast32 {
            type Output = Fast32;
            #[inline(always)]
            fn $f(self, o: Fast32) -> Fast32 {
                Fast32(self.0 $op o.0)
            }
        }
        impl $atr for Fast32 {
            #[inline(always)]
            fn $af(&mut self, o: Fast32) {
                self.0 = self.0 $op o.0;
            }
        }
    };
}
binop!(Add, add, AddAssign, add_assign, +);
binop!(Sub, sub, SubAssign, sub_assign, -);
binop!(Mul, mul, MulAssign, mul_assign, *);
impl Div for Fast32 {
    type Output = Fast32;
    #[inline(always)]
    fn div(self, o: Fast32) -> Fast32 {
        Fast32(self.0 / o.0)
    }
}
impl Neg for Fast32 {
    type Output = Fast32;
    #[inline(always)]
    fn neg(self) -> Fast32 {
        Fast32(-self.0)
    }
}

/// Approximate `1/sqrt(x)` for `x > 0` (finite, normal): relative error <= 4.8e-6.
/// Returns 0 for `x <= 0` or NaN, and 0 for `+inf`.
#[inline]
pub fn fast_rsqrt(x: f32) -> f32 {
    if !(x > 0.0) || x == f32::INFINITY {
        return 0.0;
    }
    // Subnormals: scale up by 2^64 so the bit-level guess sees a normal number.
    let (x, scale) = if x < f32::MIN_POSITIVE {
        (x * 18_446_744_073_709_551_616.0, 4_294_967_296.0)
    } else {
        (x, 1.0)
    };
    let half = 0.5 * x;
    let mut y = f32::from_bits(0x5f37_5a86 - (x.to_bits() >> 1));
    y *= 1.5 - half * y * y;
    y *= 1.5 - half * y * y;
    y * scale
}

/// Approximate `sqrt(x)`: relative error <= 4.8e-6; 0 for `x <= 0` or NaN; `+inf` for `+inf`.
#[inline]
pub fn fast_sqrt(x: f32) -> f32 {
    if x == f32::INFINITY {
        return x;
    }
    if !(x > 0.0) {
        return 0.0;
    }
    x * fast_rsqrt(x)
}

/// Approximate `atan2(y, x)` in [-pi, pi]: absolute error <= 1.2e-5 rad for all finite inputs;
/// `atan2(0, 0) = 0`; NaN input gives NaN (callers sanitize with `finite_or_zero`).
///
/// Cost: one division, a degree-9 odd polynomial (5 multiply-adds) and sign fix-ups.
#[inline]
pub fn fast_atan2(y: f32, x: f32) -> f32 {
    let ax = x.abs();
    let ay = y.abs();
    let (num, den, swap) = if ay > ax {
        (ax, ay, true)
    } else {
        (ay, ax, false)
    };
    if !(den > 0.0) {
        // Both zero (or NaN): atan2(+-0, x>=0) = 0 is the convention used by the models.
        return if den.is_nan() { f32::NAN } else { 0.0 };
    }
    let t = if den == f32::INFINITY {
        if num == f32::INFINITY {
            1.0
        } else {
            0.0
        }
    } else {
        num / den
    };
    let s = t * t;
    // Abramowitz & Stegun 4.4.49 on [0, 1]: |error| <= 1e-5.
    let p =
        t * (0.999_866 + s * (-0.330_299_5 + s * (0.180_141 + s * (-0.085_133 + s * 0.020_835_1))));
    let mut a = if swap {
        core::f32::consts::FRAC_PI_2 - p
    } else {
        p
    };
    if x < 0.0 {
        a = core::f32::consts::PI - a;
    }
    // The sign bit, so atan2(-0, x < 0) = -pi as in libm.
    if y.is_sign_negative() {
        -a
    } else {
        a
    }
}

impl Real for Fast32 {
    const ZERO: Self = Fast32(0.0);
    const ONE: Self = Fast32(1.0);
    const TWO: Self = Fast32(2.0);
    const HALF: Self = Fast32(0.5);
    const PI: Self = Fast32(core::f32::consts::PI);
    const FRAC_PI_2: Self = Fast32(core::f32::consts::FRAC_PI_2);
    const TAU: Self = Fast32(core::f32::consts::TAU);
    const FRAC_1_PI: Self = Fast32(core::f32::consts::FRAC_1_PI);
    const FRAC_1_TAU: Self = Fast32((0.5 * core::f64::consts::FRAC_1_PI) as f32);
    const EPSILON: Self = Fast32(f32::EPSILON);
    const TINY: Self = Fast32(1.0e-18);

    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        Fast32(x as f32)
    }
    #[inline(always)]
    fn from_u32(x: u32) -> Self {
        Fast32(x as f32)
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self.0 as f64
    }
    #[inline(always)]
    fn to_fixed_i32(self, frac: u32) -> i32 {
        self.0.to_fixed_i32(frac)
    }
    #[inline(always)]
    fn from_fixed_i32(x: i32, frac: u32) -> Self {
        Fast32(f32::from_fixed_i32(x, frac))
    }
    #[inline(always)]
    fn abs(self) -> Self {
        Fast32(<f32 as Real>::abs(self.0))
    }
    /// f32's square root (`VSQRT.F32` on the Cortex-M4F, `libm::sqrtf` elsewhere): correctly
    /// rounded, and cheaper than [`fast_sqrt`] on both kinds of target (see the module docs).
    #[inline(always)]
    fn sqrt(self) -> Self {
        Fast32(<f32 as Real>::sqrt(self.0))
    }
    #[inline(always)]
    fn atan2(self, x: Self) -> Self {
        Fast32(fast_atan2(self.0, x.0))
    }
    /// f32's arc ratio (its degree-9 polynomial where the target has an FPU): far inside the
    /// 1/1024 budget, and cheaper than the arc tangent the polygon edge terms would take.
    #[inline(always)]
    fn arc_ratio(self) -> Option<Self> {
        <f32 as Real>::arc_ratio(self.0).map(Fast32)
    }
    #[inline(always)]
    fn sin(self) -> Self {
        Fast32(libm::sinf(self.0))
    }
    #[inline(always)]
    fn cos(self) -> Self {
        Fast32(libm::cosf(self.0))
    }
    #[inline(always)]
    fn exp(self) -> Self {
        Fast32(libm::expf(self.0))
    }
    #[inline(always)]
    fn ln(self) -> Self {
        Fast32(libm::logf(self.0))
    }
    #[inline(always)]
    fn is_finite(self) -> bool {
        self.0.is_finite()
    }
    /// f32's lean normalization (the squared length directly, `sqrt` (`VSQRT.F32` on the
    /// Cortex-M4F), one division; a power-of-two rescaling only when the squared length under-
    /// or overflows), not the trait's rescaled default with [`fast_rsqrt`]: measured, a
    /// non-inlined `Vec3::normalize` takes 42 instructions instead of 119 on the Cortex-M4F
    /// and 1761 instead of 3509 on the Cortex-M0, and every finite nonzero vector has a
    /// direction, as in f32.
    #[inline(always)]
    fn normalize3(v: [Self; 3]) -> Option<([Self; 3], Self)> {
        <f32 as Real>::normalize3(v.map(|x| x.0)).map(|(u, len)| (u.map(Fast32), Fast32(len)))
    }
    /// [`Real::normalize3`] without the length (f32's, as there).
    #[inline(always)]
    fn unit3(v: [Self; 3]) -> Option<[Self; 3]> {
        <f32 as Real>::unit3(v.map(|x| x.0)).map(|u| u.map(Fast32))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    extern crate std;

    /// Deterministic sweep: every 97th f32 bit pattern in [2^-40, 2^40] (about 1.1e6 values).
    fn sweep() -> impl Iterator<Item = f32> {
        let lo = (2.0f32).powi(-40).to_bits();
        let hi = (2.0f32).powi(40).to_bits();
        (lo..hi).step_by(97).map(f32::from_bits)
    }

    #[test]
    fn rsqrt_and_sqrt_within_bound() {
        let mut worst = 0.0f64;
        for x in sweep() {
            let exact = 1.0 / (x as f64).sqrt();
            let rel = ((fast_rsqrt(x) as f64 - exact) / exact).abs();
            worst = worst.max(rel);
            let exact = (x as f64).sqrt();
            let rel = ((fast_sqrt(x) as f64 - exact) / exact).abs();
            worst = worst.max(rel);
        }
        std::println!("fast_rsqrt/fast_sqrt worst relative error {worst:e}");
        assert!(worst <= 4.8e-6, "worst relative error {worst:e}");
        // Edge inputs.
        assert_eq!(fast_sqrt(0.0), 0.0);
        assert_eq!(fast_sqrt(-1.0), 0.0);
        assert_eq!(fast_sqrt(f32::NAN), 0.0);
        assert_eq!(fast_sqrt(f32::INFINITY), f32::INFINITY);
        let sub = f32::from_bits(1);
        let rel = (fast_sqrt(sub) as f64 / (sub as f64).sqrt() - 1.0).abs();
        assert!(rel <= 4.8e-6, "subnormal {rel:e}");
        let m = f32::MAX;
        assert!((fast_sqrt(m) as f64 / (m as f64).sqrt() - 1.0).abs() <= 4.8e-6);
    }

    #[test]
    fn atan2_within_bound() {
        let mut worst = 0.0f64;
        let n = 2000;
        for i in 0..n {
            let phi = (i as f64 / n as f64) * core::f64::consts::TAU - core::f64::consts::PI;
            for r in [1e-30f64, 1e-3, 1.0, 7.5, 1e30] {
                let (y, x) = ((r * phi.sin()) as f32, (r * phi.cos()) as f32);
                let exact = (y as f64).atan2(x as f64);
                let err = (fast_atan2(y, x) as f64 - exact).abs();
                worst = worst.max(err);
            }
        }
        for t in sweep().step_by(7) {
            for (y, x) in [(t, 1.0f32), (1.0, t), (-t, -1.0), (t, -1.0)] {
                let err = (fast_atan2(y, x) as f64 - (y as f64).atan2(x as f64)).abs();
                worst = worst.max(err);
            }
        }
        std::println!("fast_atan2 worst error {worst:e} rad");
        assert!(worst <= 1.2e-5, "worst atan2 error {worst:e}");
        assert_eq!(fast_atan2(0.0, 0.0), 0.0);
        assert_eq!(fast_atan2(0.0, -1.0), core::f32::consts::PI);
        assert!((fast_atan2(f32::INFINITY, 1.0) - core::f32::consts::FRAC_PI_2).abs() < 1e-6);
        assert!(
            (fast_atan2(f32::INFINITY, f32::INFINITY) - core::f32::consts::FRAC_PI_4).abs() < 2e-5
        );
    }

    /// The measurement behind choosing our own functions over micromath's (see module docs).
    #[test]
    fn micromath_errors_exceed_the_budget() {
        use micromath::F32Ext;
        let mut atan_worst = 0.0f64;
        for i in 0..20_000 {
            let phi = (i as f64 / 20_000.0) * core::f64::consts::TAU - core::f64::consts::PI;
            let (y, x) = (phi.sin() as f32, phi.cos() as f32);
            let err = (F32Ext::atan2(y, x) as f64 - (y as f64).atan2(x as f64)).abs();
            atan_worst = atan_worst.max(err);
        }
        let mut sqrt_worst = 0.0f64;
        for x in sweep().step_by(13) {
            let rel = (F32Ext::sqrt(x) as f64 / (x as f64).sqrt() - 1.0).abs();
            sqrt_worst = sqrt_worst.max(rel);
        }
        // Ours: 1.2e-5 rad and 4.8e-6 relative. micromath's are two and three orders larger.
        assert!(atan_worst > 1e-3, "micromath atan2 worst {atan_worst:e}");
        assert!(sqrt_worst > 1e-2, "micromath sqrt worst {sqrt_worst:e}");
    }
}
