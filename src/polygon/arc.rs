//! One arc of a boundary on the unit sphere, as `[phong_polygon]`'s `J` terms and Arvo's
//! moments both integrate it: the arc from the unit direction `s` through the angle `x` about
//! the unit pole `g`, `u(t) = s cos t + (g x s) sin t`, against an axis `w`:
//! `w.u(t) = a cos t + b sin t`. [`arc_axis_form`] sets the form up, [`cos_power_sums`]
//! integrates its powers along the arc.

use crate::{Real, Vec3};

/// The axis `w`'s form `w.u(t) = a cos t + b sin t` along the arc from the unit direction `s`
/// about the unit pole `g`, given `wg = w.g` and `a = w.s`: returns `(b, f)`, `b = w.(g x s)`
/// and `f = a^2 + b^2 = 1 - (w.g)^2`, the latter in the form exact near 1 (to an ULP), where
/// [`cos_power_sums`] raises `f` to the power `n/2`. Cost: a cross product, a dot product,
/// 1 or 2 products.
#[inline(always)]
pub(crate) fn arc_axis_form<T: Real>(w: Vec3<T>, g: Vec3<T>, s: Vec3<T>, wg: T, a: T) -> (T, T) {
    let b = w.dot(g.cross(s));
    let f = if wg.abs() < T::HALF {
        (T::ONE - wg) * (T::ONE + wg)
    } else {
        (a * a + b * b).min(T::ONE)
    };
    (b, f)
}

/// The recurrence `T(k)` of Snyder's appendix G for one arc of a boundary: `T(k)` is the
/// integral from 0 to `x` of `(a cos t + b sin t)^k dt`, `f = a^2 + b^2`, run upward from
/// `k = n mod 2` in steps of 2. Returns `(T(n mod 2) + ... + T(n - 2), T(n))`. One
/// implementation for `[phong_polygon]`'s `J` terms (which sum all of them) and Arvo's
/// moments (which weigh the last apart). With `stop = Some((coef, budget))` it stops after
/// `T(k)` once `coef c^(k+2) <= budget` (`c = sqrt(f)`) and returns `T(n) = 0` (the tail
/// dropped: the moments' early termination); with `None` that bound costs nothing.
///
/// Cost: 3 products, 2 additions, [`Real::mul_u32`] and [`Real::div_u32`] per step (the
/// latter a table lookup on `Fixed22`, bit-identical to the division).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn cos_power_sums<T: Real>(
    n: u32,
    x: T,
    cos_x: T,
    sin_x: T,
    a: T,
    b: T,
    f: T,
    stop: Option<(T, T)>,
) -> (T, T) {
    let g = (a * cos_x + b * sin_x).clamp(-T::ONE, T::ONE);
    let g2 = g * g;
    let a2 = a * a;
    let h = a * sin_x - b * cos_x;
    let odd = n & 1 == 1;
    // t = T(k); l = G^(k+1) H, l2 = beta alpha^(k+1): ready for k + 2.
    let (mut t, mut l, mut l2, mut k) = if odd {
        (h + b, g2 * h, b * a2, 1)
    } else {
        (x, g * h, b * a, 0)
    };
    // c^(k+2), for the early-termination bound (only when asked for).
    let mut cpow = match stop {
        Some(_) if odd => f * f.sqrt(),
        Some(_) => f,
        None => T::ZERO,
    };
    let mut sum = T::ZERO;
    while k < n {
        sum += t;
        if let Some((coef, budget)) = stop {
            if coef * cpow <= budget {
                return (sum, T::ZERO);
            }
            cpow *= f;
        }
        k += 2;
        t = (l + l2 + f.mul_u32(k - 1) * t).div_u32(k);
        l *= g2;
        l2 *= a2;
    }
    (sum, t)
}
