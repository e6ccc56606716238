//! The sine-power integral `S(n, x) = integral from 0 to x of sin^n(t) dt` (Snyder section 3.1,
//! appendix B).
//!
//! Integrating `sin^n t = sin^(n-1) t * sin t` by parts gives the recurrence
//!
//! ```text
//! S(n, x) = ((n - 1) S(n - 2, x) - sin^(n-1)(x) cos(x)) / n,   S(0, x) = x,  S(1, x) = 1 - cos x
//! ```
//!
//! run upward from `S(0)` (even `n`) or `S(1)` (odd `n`). Each step multiplies the error already
//! made by `(n - 1)/n < 1`, so the upward recurrence is stable; the error after `n` steps is a
//! few ULPs times `sqrt(n)` (measured in `tests/phong.rs`). Only odd `n` avoids `x` itself
//! (an arc cosine when only `cos x` is known).
//!
//! At `x = pi` the recurrence collapses to `S(n, pi) = (n - 1)/n S(n - 2, pi)` with `S(0, pi) = pi`,
//! `S(1, pi) = 2`, and `S(n, pi) S(n + 1, pi) = 2 pi/(n + 1)` (Snyder eq. 13).

use crate::Real;

/// `S(n, x)` from `x`, `sin x` and `cos x` (`x` is only read for even `n`).
///
/// Accuracy: a few ULPs times `sqrt(n)` for `x` in [0, pi]. Cost: `n/2` steps of 2 multiplies,
/// 1 division and 2 additions.
#[inline]
pub fn sine_power_integral<T: Real>(n: u32, x: T, sin_x: T, cos_x: T) -> T {
    let sin_sq = sin_x * sin_x;
    // g = sin^(i-1) x cos x for the current i.
    let (mut s, mut g, start) = if n & 1 == 1 {
        (T::ONE - cos_x, sin_sq * cos_x, 1)
    } else {
        (x, sin_x * cos_x, 0)
    };
    let mut i = start + 2;
    while i <= n {
        s = (s.mul_u32(i - 1) - g).div_u32(i);
        g *= sin_sq;
        i += 2;
    }
    s
}

/// `S(n, pi)`, by the product `prod (i - 1)/i` over `i = n, n - 2, ...` down to `S(0)` or `S(1)`.
///
/// Accuracy: `n/2` roundings (relative error below `n * EPSILON`). Computed once per material.
pub fn sine_power_integral_pi<T: Real>(n: u32) -> T {
    let (mut s, start) = if n & 1 == 1 { (T::TWO, 1) } else { (T::PI, 0) };
    let mut i = start + 2;
    while i <= n {
        s = s.mul_u32(i - 1).div_u32(i);
        i += 2;
    }
    s
}
