//! SH9 irradiance on [`Fixed22`] in 16-bit factors: every term one 32 x 32 -> 32-bit product
//! (one `MULS` on the Cortex-M0), for environments whose error bound stays within `2^-11`.
//!
//! # Method
//!
//! Per channel, `E(n) = k0 + sum k_i m_i(n)` over the eight monomials of the unit normal
//! (`x`, `y`, `z`, `xy`, `yz`, `xz`, `z^2`, `x^2 - y^2`).
//!
//! - **Monomials in Q15**, each rounded half up: `X = round(x 2^15)` from the Q22 components,
//!   the quadratic ones from `X`, `Y`, `Z` by one product each (`X Y` is exact in `i32`,
//!   then rounded to Q15). Their magnitudes are at most `2^15 + 4` (`x`, `y`, `z`, `z^2`,
//!   `x^2 - y^2`) and `2^14 + 4` (`xy`, `yz`, `xz`, because `x^2 + y^2 <= 1`).
//! - **Coefficients as mantissas** `K_i = round(k_i 2^s)`, with one exponent `s`,
//!   made once by [`pack`]: the largest `s <= 30` for which `sum |K_i| w_i <= L` in every
//!   channel (one exponent for the three: one shift per call),
//!   with the weights `w = [2, 2, 2, 2, 1, 1, 1, 2, 2]` (the monomials' bounds in units of
//!   `2^14`; `k0`'s monomial is 1) and `L = 130 560`.
//! - **The sum** `K0 2^15 + 2^(sh - 1) + sum K_i M_i` in `i32`, shifted right by `sh = s -
//!   7` (in `[6, 23]`): the result rounded half up to Q22. Its first term is stored in place
//!   of `K0`. Every term and every partial sum is at most `L (2^14 + 4) + 2^22 < 2^31` in
//!   magnitude, so nothing wraps.
//!
//! # Error bound (per channel, checked by [`pack`] for every environment)
//!
//! `|E_q - E| <= 2^-(s+1) sum |m_i| + sum |k_i| d_i 2^-16 + 2^-23`, with `sum |m_i| <= 8`
//! (counting `k0`'s monomial 1) for the mantissas' rounding (none for `s >= 22`), `d =
//! [0, 1, 1, 1, 3, 3, 3, 3, 4]` for the monomials' (a linear one is within `2^-16`, a
//! product within `2^-15` from its factors plus `2^-16` of its own rounding, `x^2 - y^2`
//! within `(2 sqrt 2 + 1) 2^-16`; each of these to first order, with `2^-10` of slack for
//! the second), and the result's rounding to Q22. The environment takes
//! this path only where the bound is at most `2^-11` in every channel, half the fixed-point
//! budget of 1/1024 (random coefficients up to 1: a bound near `3e-4`, errors measured up to
//! `1.3e-4`, this module's tests); elsewhere the exact fused Q22 sum
//! (`kernels::dot8_split_bits`, within `2^-22` of the Q22 monomials).
//!
//! # Cost
//!
//! 9 single products a channel and 6 for the monomials, where the fused Q22 sum takes 4 a
//! term and its monomials 3 each (measured in the QEMU budget: see
//! `Sh9Irradiance::irradiance`).

use super::Fixed22;
use crate::Rgb;

/// The monomials' bounds in units of `2^14` (`k0`'s monomial first): see the module docs.
const WEIGHT: [i64; 9] = [2, 2, 2, 2, 1, 1, 1, 2, 2];
/// The largest `sum |K_i| WEIGHT_i`: `L (2^14 + 4) + 2^22 < 2^31`.
const LIMIT: i64 = 130_560;
/// The monomials' error bounds in units of `2^-16` (`k0`'s first).
const MONOMIAL_ERROR: [i64; 9] = [0, 1, 1, 1, 3, 3, 3, 3, 4];
/// The error bound a channel may have, `2^-11`, in units of `2^-38`.
const BOUND: u64 = 1 << 27;
/// The smallest and largest exponent `s`: below 13 the mantissas' rounding alone exceeds
/// [`BOUND`]; 30 keeps `sh = s - 7` below 24.
const S_MIN: u32 = 13;
const S_MAX: u32 = 30;

/// One channel's error bound at the exponent `s`, in units of `2^-38` (see the module docs):
/// the mantissas' rounding `8 2^-(s+1)` (none for `s >= 22`, where they are exact), the
/// monomials' `|k_i| d_i 2^-16` with `2^-10` of slack for the second-order terms (a
/// product's factor at `1 + 2^-15`), the result's rounding `2^-23`.
pub(super) fn error_bound(k: [i32; 9], s: u32) -> u64 {
    let mantissas: u64 = if s >= 22 { 0 } else { 1 << (40 - s) };
    let monomials: u64 = (0..9)
        .map(|i| u64::from(k[i].unsigned_abs()) * MONOMIAL_ERROR[i] as u64)
        .sum();
    mantissas + monomials + (monomials >> 10) + 1 + (1 << 15)
}

/// One channel's mantissas at the exponent `s` (in `[13, 30]`), `k0`'s as `K0 2^15 +
/// 2^(s - 8)` (the result's rounding folded in); `None` where they exceed [`LIMIT`] or the
/// channel's error bound exceeds [`BOUND`].
fn pack_channel(k: [i32; 9], s: u32) -> Option<[i32; 9]> {
    let mant = |c: i32| -> i64 {
        let c = i64::from(c);
        if s >= 22 {
            c << (s - 22)
        } else {
            (c + (1 << (21 - s))) >> (22 - s)
        }
    };
    let m: [i64; 9] = core::array::from_fn(|i| mant(k[i]));
    let weighted: i64 = (0..9).map(|i| m[i].abs() * WEIGHT[i]).sum();
    if weighted > LIMIT {
        return None;
    }
    if error_bound(k, s) > BOUND {
        return None;
    }
    let mut out: [i32; 9] = core::array::from_fn(|i| m[i] as i32);
    out[0] = ((m[0] << 15) + (1 << (s - 8))) as i32;
    Some(out)
}

/// `k` (the irradiance polynomial, `k0` first) replaced by its mantissas at the largest
/// exponent `s` (in `[13, 30]`) at which every channel's fit (one exponent for the three
/// channels: one shift per call), and the shift `sh = s - 7` (in `[6, 23]`); `None` (and `k`
/// unchanged) where no exponent keeps every channel within [`LIMIT`] and its error bound
/// within `2^-11` (see the module docs).
pub fn pack(k: &mut [Rgb<Fixed22>; 9]) -> Option<u8> {
    let channel = |f: fn(&Rgb<Fixed22>) -> Fixed22| k.map(|c| f(&c).to_bits());
    let (r, g, b) = (channel(|c| c.r), channel(|c| c.g), channel(|c| c.b));
    // The channels' limits hold at every exponent below one at which they hold, and the
    // mantissas' error grows as the exponent falls: the first exponent that fits is the best.
    let (s, (r, g, b)) = (S_MIN..=S_MAX).rev().find_map(|s| {
        let packed = (pack_channel(r, s), pack_channel(g, s), pack_channel(b, s));
        match packed {
            (Some(r), Some(g), Some(b)) => Some((s, (r, g, b))),
            _ => None,
        }
    })?;
    let bits = Fixed22::from_bits;
    for (i, c) in k.iter_mut().enumerate() {
        *c = Rgb::new(bits(r[i]), bits(g[i]), bits(b[i]));
    }
    Some((s - 7) as u8)
}

/// `E(n)` per channel from [`pack`]'s mantissas `k` (`k0`'s as `K0 2^15 + 2^(sh - 1)`) and
/// shift `sh` (in `[6, 23]`), for a unit `n` (each component at most `1 + 2^-16`, `x^2 + y^2` at most `1 + 2^-13`, as
/// every `UnitVec3` keeps): within the bound [`pack`] checked.
#[inline(always)]
pub fn irradiance(k: &[Rgb<Fixed22>; 9], sh: u8, n: [Fixed22; 3]) -> Rgb<Fixed22> {
    // Half up to Q15: |X| <= 2^15 + 1.
    let q = |c: Fixed22| c.to_bits().wrapping_add(1 << 6) >> 7;
    let (x, y, z) = (q(n[0]), q(n[1]), q(n[2]));
    // A Q30 product (at most 2^30 + 2^16 + 1) rounded half up to Q15.
    let r = |p: i32| p.wrapping_add(1 << 14) >> 15;
    let mul = i32::wrapping_mul;
    let m = [
        x,
        y,
        z,
        r(mul(x, y)),
        r(mul(y, z)),
        r(mul(x, z)),
        r(mul(z, z)),
        r(mul(x, x).wrapping_sub(mul(y, y))),
    ];
    let sh = u32::from(sh) & 31;
    let ch = |f: fn(&Rgb<Fixed22>) -> Fixed22| {
        let b = |i: usize| f(&k[i]).to_bits();
        // Written out (a loop on the Cortex-M0 at opt-level "s" goes through the stack).
        let e = b(0)
            .wrapping_add(mul(b(1), m[0]))
            .wrapping_add(mul(b(2), m[1]))
            .wrapping_add(mul(b(3), m[2]))
            .wrapping_add(mul(b(4), m[3]))
            .wrapping_add(mul(b(5), m[4]))
            .wrapping_add(mul(b(6), m[5]))
            .wrapping_add(mul(b(7), m[6]))
            .wrapping_add(mul(b(8), m[7]));
        Fixed22::from_bits(e >> sh)
    };
    Rgb::new(ch(|c| c.r), ch(|c| c.g), ch(|c| c.b))
}
