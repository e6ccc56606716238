//! The `f32` arc tangent of [`Real::atan2`](super::Real::atan2): a minimax polynomial chosen
//! for the f32 error target, in place of `libm::atan2f` on targets with a floating-point unit.
//!
//! # Method
//!
//! `t = min(|y|, |x|) / max(|y|, |x|)` in [0, 1] (one division), then `atan t = t + t s Q(s)`
//! with `s = t^2` and `Q` of degree 7: the odd degree-17 polynomial whose coefficients minimize
//! the largest *relative* error on [0, 1] (1.67e-8, fitted by Lawson's iteration on 3000
//! points, then rounded to f32). Writing the leading term as the exact `t` keeps the rounding of
//! the last steps to a fraction of an ULP (the correction `t s Q(s)` is at most a third of the
//! result), and the relative form keeps small angles accurate to an ULP or so, which the edge
//! terms `theta (G.k)/|G|` of the polygon models need. The octant and the sign come from one
//! table lookup indexed by `|y| > |x|` and the sign bits of `x` and `y`: the angle is
//! `hi + (lo + sgn atan t)` with `hi + lo` = 0, +-pi/2 or +-pi in two pieces (one rounding after
//! the small terms, as fdlibm does).
//!
//! Special values are libm's: `atan2(+-0, +0) = +-0`, `atan2(+-0, -0) = +-pi`,
//! `atan2(+-0, x < 0) = +-pi` (the sign of a zero `y` selects the side of the cut, which the
//! models rely on), NaN for a NaN operand; for infinite operands the f32 nearest the exact
//! angle (`+-pi/2`, `+-pi/4`, `+-3 pi/4`; libm returns the f32 just below pi/2 there).
//!
//! # Accuracy (measured in `tests/real_f32_math.rs` against the f64 `atan`/`atan2` of the same
//! f32 inputs)
//!
//! - `atan t` on [0, 1]: at most 1.31 ULP and 7.8e-8 (every f32 in [0, 1], 1.07e9 values;
//!   `libm::atanf`: 0.85 ULP, 5.1e-8);
//! - `atan2(y, x)` over 2^20 angles around the circle at magnitudes 1e-30 to 1e30 and the ratios
//!   `y/x` over the whole f32 range in every quadrant: at most 1.65 ULP and 2.1e-7 rad
//!   (`libm::atan2f`: 1.40 ULP and 2.5e-7 rad), 10 times below the 2e-6 f32 model target.
//!
//! # Cost (exact QEMU instruction counts, `netduinoplus2`, one call through a non-inlined
//! wrapper with its argument moves, 8 inputs, one per octant)
//!
//! - Cortex-M4F: 63 instructions for every octant, against 68 to 97 (median 92) for
//!   `libm::atan2f`. The polynomial is 8 literal loads and 8 `VMLA.F32`, with one `VDIV.F32`,
//!   one NaN test of the quotient (the only branch: zeros, infinities and NaN all give a NaN
//!   quotient) and the table lookup; libm's `atan2f` tests the special cases in integer code
//!   first, and its `atanf` reduces the argument to `|t| < 7/16` with one of four table offsets
//!   (a second division and more branches).
//! - Soft-float targets (Cortex-M0, RISC-V without F): there every float operation is a library
//!   call and libm's shorter polynomial wins (ours: 2443 to 2758 instructions, libm 1702 to 2565),
//!   so `<f32 as Real>::atan2` is `libm::atan2f` there (the `atan2` alias below).

/// `atan t = t + t s Q(s)`, `s = t^2`: `Q`'s coefficients, constant term first (see the module
/// docs).
const Q: [f32; 8] = [
    -0.333_331_53,
    0.199_937_82,
    -0.142_111_44,
    0.106_663_965,
    -0.075_531_47,
    0.043_223_966,
    -0.016_376_032,
    0.002_922_879,
];

/// pi/2 rounded to f32, and the remainder `pi/2 - FRAC_PI_2_HI` rounded to f32.
const FRAC_PI_2_HI: f32 = core::f32::consts::FRAC_PI_2;
const FRAC_PI_2_LO: f32 = (core::f64::consts::FRAC_PI_2 - FRAC_PI_2_HI as f64) as f32;
/// pi rounded to f32, and the remainder.
const PI_HI: f32 = core::f32::consts::PI;
const PI_LO: f32 = (core::f64::consts::PI - PI_HI as f64) as f32;

const SIGN: u32 = 0x8000_0000;

/// `[hi, lo, sgn, 0]` per octant (16 bytes: one shifted index), indexed by
/// `swap | x_neg << 1 | y_neg << 2` (`swap`: `|y| > |x|`, the quotient was `|x|/|y|`): the angle
/// is `hi + (lo + sgn atan t)`. The entries for a negative `y` are those for a positive one
/// negated (exactly), so `atan2(-0, x >= 0) = -0`.
const OCTANT: [[f32; 4]; 8] = [
    [0.0, 0.0, 1.0, 0.0],                    // |y| <= |x|, x >= 0: t
    [FRAC_PI_2_HI, FRAC_PI_2_LO, -1.0, 0.0], // |y| > |x|,  x >= 0: pi/2 - t
    [PI_HI, PI_LO, -1.0, 0.0],               // |y| <= |x|, x < 0: pi - t
    [FRAC_PI_2_HI, FRAC_PI_2_LO, 1.0, 0.0],  // |y| > |x|,  x < 0: pi/2 + t
    [-0.0, -0.0, -1.0, 0.0],
    [-FRAC_PI_2_HI, -FRAC_PI_2_LO, 1.0, 0.0],
    [-PI_HI, -PI_LO, 1.0, 0.0],
    [-FRAC_PI_2_HI, -FRAC_PI_2_LO, -1.0, 0.0],
];

/// `atan t` for `t` in [0, 1] (see the module docs): 1.31 ULP.
#[inline(always)]
pub(crate) fn atan_unit(t: f32) -> f32 {
    let s = t * t;
    let mut q = Q[7];
    q = q * s + Q[6];
    q = q * s + Q[5];
    q = q * s + Q[4];
    q = q * s + Q[3];
    q = q * s + Q[2];
    q = q * s + Q[1];
    q = q * s + Q[0];
    t + (t * s) * q
}

/// `<f32 as Real>::atan2`: [`atan2_poly`] where the target has a floating-point unit (or is
/// not a soft-float microcontroller), `libm::atan2f` on soft-float ARM and RISC-V targets,
/// where it costs fewer float operations (see the module docs).
#[cfg(not(any(
    all(target_arch = "arm", not(target_abi = "eabihf")),
    all(
        any(target_arch = "riscv32", target_arch = "riscv64"),
        not(target_feature = "f")
    )
)))]
pub(crate) use atan2_poly as atan2;
#[cfg(any(
    all(target_arch = "arm", not(target_abi = "eabihf")),
    all(
        any(target_arch = "riscv32", target_arch = "riscv64"),
        not(target_feature = "f")
    )
))]
pub(crate) use libm::atan2f as atan2;

/// Four-quadrant arc tangent of `y / x` in [-pi, pi] with libm's special values (see the
/// module docs for the method, the error and the cost).
#[inline]
#[cfg_attr(
    any(
        all(target_arch = "arm", not(target_abi = "eabihf")),
        all(
            any(target_arch = "riscv32", target_arch = "riscv64"),
            not(target_feature = "f")
        )
    ),
    allow(dead_code)
)]
pub(crate) fn atan2_poly(y: f32, x: f32) -> f32 {
    let (xb, yb) = (x.to_bits(), y.to_bits());
    let (xa, ya) = (xb & !SIGN, yb & !SIGN);
    // |y| > |x|, compared as integers (the magnitudes order as their bits; a NaN compares
    // above everything, which the quotient's NaN test below catches either way).
    let swap = ya > xa;
    let (num, den) = if swap { (xa, ya) } else { (ya, xa) };
    // `num <= den`, so the quotient is in [0, 1], or NaN for 0/0, inf/inf and a NaN operand:
    // one test of the quotient keeps the special cases off the common path.
    let (num, den) = (f32::from_bits(num), f32::from_bits(den));
    let mut t = num / den;
    if t.is_nan() {
        t = special_quotient(num, den);
    }
    let p = atan_unit(t);
    // The octant and the sign in one table lookup: `hi + (lo + sgn p)` (p, pi/2 -+ p, pi - p,
    // each negated for a negative `y`), with one rounding after the small terms.
    let i = (u32::from(swap) | ((xb >> 30) & 2) | ((yb >> 29) & 4)) as usize;
    let [hi, lo, sgn, _] = OCTANT[i];
    hi + (lo + p * sgn)
}

/// The quotient `num / den` (`num <= den`) where the division gives NaN: 0 for two zeros
/// (the angle of a zero vector is 0 before the quadrant fix-up, as in libm), 1 for two
/// infinities (pi/4), NaN for a NaN operand.
#[inline(always)]
fn special_quotient(num: f32, den: f32) -> f32 {
    if num == den {
        if num == 0.0 {
            0.0
        } else {
            1.0
        }
    } else {
        f32::NAN
    }
}
