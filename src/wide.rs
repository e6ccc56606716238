//! Exact 32 x 32 -> 64-bit products for the integer paths (the rasterizer's edge functions and
//! attribute planes).
//!
//! ARMv6-M (Cortex-M0/M0+) has only a 32 x 32 -> 32-bit `MULS`, and the compiler turns every
//! `i64` product into a call of the 64 x 64-bit `__aeabi_lmul` (about 100 cycles in rp2040js).
//! When both factors fit an `i32`, four 16 x 16-bit products do it inline in about 20
//! instructions. On targets with a widening multiply (`SMULL` on ARMv7-M, x86-64) the plain
//! product is one instruction, and the compiler is given that.

/// `a * b` exactly (`i32 x i32 -> i64`): [`mul_32_by_halves`] on ARMv6-M (recognised by its
/// lack of 32-bit compare-and-swap, which every ARMv7-M and later core has), the plain
/// product elsewhere.
#[inline(always)]
pub(crate) fn mul_32(a: i32, b: i32) -> i64 {
    if cfg!(all(target_arch = "arm", not(target_has_atomic = "32"))) {
        mul_32_by_halves(a, b)
    } else {
        i64::from(a) * i64::from(b)
    }
}

/// `a * b` exactly from four 16 x 16-bit products (each fits the 32-bit `MULS`).
#[inline(always)]
pub(crate) fn mul_32_by_halves(a: i32, b: i32) -> i64 {
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    // |ah|, |bh| <= 2^15 and al, bl < 2^16: the cross products fit an i32, the low one a u32.
    let hh = i64::from(ah * bh);
    let mid = i64::from(ah * bl) + i64::from(al * bh);
    let ll = i64::from((al as u32) * (bl as u32));
    (hh << 32) + (mid << 16) + ll
}

/// `a * b` (wrapping) of two `i64`, through [`mul_32`] when both fit an `i32` (the usual
/// case), through the full 64-bit product otherwise.
#[cfg(feature = "raster")]
#[inline(always)]
pub(crate) fn mul_64(a: i64, b: i64) -> i64 {
    if a == i64::from(a as i32) && b == i64::from(b as i32) {
        mul_32(a as i32, b as i32)
    } else {
        a.wrapping_mul(b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn products_are_exact() {
        let edge = [
            0,
            1,
            -1,
            0xFFFF,
            0x10000,
            -0x10000,
            i32::MAX,
            i32::MIN,
            i32::MIN + 1,
            12345678,
            -87654321,
        ];
        for &a in &edge {
            for &b in &edge {
                assert_eq!(mul_32(a, b), i64::from(a) * i64::from(b), "{a} {b}");
                assert_eq!(
                    mul_32_by_halves(a, b),
                    i64::from(a) * i64::from(b),
                    "{a} {b}"
                );
                #[cfg(feature = "raster")]
                {
                    let (a, b) = (i64::from(a), i64::from(b));
                    assert_eq!(mul_64(a, b), a.wrapping_mul(b));
                    assert_eq!(mul_64(a << 20, b), (a << 20).wrapping_mul(b));
                }
            }
        }
    }
}
