//! `i64` to `f32` through a 32-bit conversion: the world coordinates' conversion
//! (`Real::from_q60`), where `as` from an `i64` is a library call on Arm.

/// `x as f32` (rounded to nearest, ties to even), bit for bit, from a 32-bit integer
/// conversion: `VCVT.F32.S32` with an FPU, where `as` from an `i64` is a library call
/// (`__aeabi_l2f`, about 34 Cortex-M4F instructions). Beyond `i32`, `x` is shifted right
/// (`floor`) by the `s` that leaves it 31 bits and a sign, and the lowest bit is set if
/// anything was shifted out: that rounds `x / 2^s` to odd, which keeps every bit a rounding to
/// f32's 24 needs (the round bit, and whether anything below it is set), for either sign.
/// The 32-bit value is then converted (one rounding) and scaled back by `2^s`, exactly. In
/// 32-bit halves: no 64-bit shift. Checked against `as` on the host
/// (`real::i64_to_f32::tests::i64_to_f32_is_as`).
#[inline(always)]
pub(crate) fn i64_to_f32(x: i64) -> f32 {
    let (hi, lo) = ((x >> 32) as i32, x as u32);
    if hi == (lo as i32) >> 31 {
        // Within i32.
        return lo as i32 as f32;
    }
    // `x` has 32 to 63 bits besides its sign: `s` in [1, 32] leaves 31.
    let s = 33 - (hi ^ (hi >> 31)).leading_zeros();
    let (t, inexact) = if s >= 32 {
        (hi, lo != 0)
    } else {
        (
            (((hi as u32) << (32 - s)) | (lo >> s)) as i32,
            lo << (32 - s) != 0,
        )
    };
    let f = (t | i32::from(inexact)) as f32;
    // 2^s exactly, from its bits (a normal f32 for s <= 32).
    f * f32::from_bits((127 + s) << 23)
}

#[cfg(test)]
mod tests {
    use super::i64_to_f32;

    /// `i64_to_f32` is `as`, bit for bit: every power of two and its neighbours (the ties and
    /// the carries into the next binade), patterns with a tie bit and a lone sticky bit at
    /// every position, the ends, and four million random values of every magnitude.
    #[test]
    fn i64_to_f32_is_as() {
        let check = |x: i64| assert_eq!(i64_to_f32(x).to_bits(), (x as f32).to_bits(), "{x}");
        for e in 0..63 {
            let p = 1i64 << e;
            for d in -3..=3 {
                for x in [p.wrapping_add(d), p.wrapping_neg().wrapping_add(d)] {
                    check(x);
                }
            }
            // 24 bits, then a tie bit, then a sticky bit `s` positions below it (or none).
            if e >= 26 {
                let top = ((1i64 << 23) | 0x5A5A5A) << (e - 23);
                let tie = 1i64 << (e - 24);
                check(top | tie);
                check(-(top | tie));
                check((top | tie) + (1 << (e - 24)) * 2); // the next odd mantissa, tied
                for s in 1..(e - 24) {
                    check(top | tie | (1 << (e - 24 - s)));
                    check(-(top | tie | (1 << (e - 24 - s))));
                    check(top | (1 << (e - 24 - s)));
                }
            }
        }
        for x in [
            0,
            1,
            -1,
            i64::MAX,
            i64::MIN,
            i64::MIN + 1,
            i32::MAX as i64 + 1,
        ] {
            check(x);
        }
        let mut next = crate::test_rng::xorshift32(0x1234_5679);
        for _ in 0..4_000_000 {
            let raw = (u64::from(next()) << 32) | u64::from(next());
            let x = (raw >> (next() % 64)) as i64;
            check(x);
            check(x.wrapping_neg());
        }
    }
}
