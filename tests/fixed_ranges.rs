//! The scalar conversions and rescalings at the edges of [`Fixed22`]'s range (+-512) against
//! f64, and the float backends against their own operators:
//! - `Real::rescale3` is total in Fixed22: with `m` below the largest component, zero or
//!   negative (the shift used to come from `m` alone and shifted the larger components' bits
//!   out of the top: a silent wrap), the result times the scale is the input to the type's
//!   rounding; the floats divide by `m` as given, as documented;
//! - `Real::mul_u32_to_fixed_i32` is exact in Fixed22 for every input and `n` up to 2^16
//!   (where `from_u32(n)` saturates from 512), and bit-identical to
//!   `(x * from_u32(n)).to_fixed_i32(frac)` for the floats;
//! - `Real::from_u32` is exact below 512 in Fixed22 and saturates from 512 on, as documented.

use arealight::{Fast32, Fixed22, Real};

type F = Fixed22;
const LSB: f64 = 1.0 / 4_194_304.0;

/// A small deterministic generator (xorshift).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    /// Raw Q22 bits: uniform over all bits, or of a random magnitude `2^[0, 31)`.
    fn bits(&mut self) -> i32 {
        let r = self.next();
        if r & 1 == 0 {
            (r >> 32) as i32
        } else {
            let mag = ((r >> 32) as u32) >> ((r >> 8) % 32);
            if r & 2 == 0 {
                mag as i32
            } else {
                (mag as i32).wrapping_neg()
            }
        }
    }
}

fn max_abs_f64(v: &[F; 3]) -> f64 {
    v.iter().map(|x| x.to_f64().abs()).fold(0.0, f64::max)
}

#[test]
fn fixed22_rescale3_is_total_for_any_m() {
    let mut rng = Rng(0x5EED_1234_ABCD_0001);
    let mut checked = 0;
    for case in 0..200_000 {
        let v = [
            F::from_bits(rng.bits()),
            F::from_bits(rng.bits()),
            F::from_bits(rng.bits()),
        ];
        let largest = Ord::max(Ord::max(v[0].abs(), v[1].abs()), v[2].abs());
        // m: the largest component (the documented use), another component, a tiny or a
        // random value, zero, negative, or larger than the largest.
        let m = match case % 6 {
            0 => largest,
            1 => v[case % 3].abs(),
            2 => F::from_bits(1),
            3 => F::from_bits(rng.bits()),
            4 => F::ZERO,
            _ => largest + largest,
        };
        let (s, d) = F::rescale3(v, m);
        let (d64, top) = (d.to_f64(), largest.to_f64().max(m.to_f64()));
        assert!(d64 > 0.0, "{v:?} {m:?}");
        for k in 0..3 {
            // The shift right drops bits below the scale's LSB: floor, so within d LSB.
            let err = (s[k].to_f64() * d64 - v[k].to_f64()).abs();
            assert!(err < d64 * LSB, "{v:?} m {m:?}: {s:?} * {d:?}");
        }
        assert!(max_abs_f64(&s) <= 2.0, "{v:?} m {m:?}: {s:?}");
        if largest > F::ZERO && m <= largest {
            // The largest component lands in [1/2, 2] (the documented normalization).
            assert!(max_abs_f64(&s) >= 0.5, "{v:?} m {m:?}: {s:?}");
        }
        if top == 0.0 {
            assert_eq!((s, d), (v, F::ONE));
        }
        checked += 1;
    }
    assert_eq!(checked, 200_000);
}

/// The floats divide by `m` as given (documented: as their `/`), bit for bit `v * (1 / m)`;
/// an `m` below the largest component gives components above 1, exact to rounding.
#[test]
fn float_rescale3_divides_by_m() {
    let v = [3.0f64, -0.5, 1e-3];
    for m in [3.0, 6.0, 1e-3] {
        let r = 1.0 / m;
        assert_eq!(
            f64::rescale3(v, m),
            ([3.0 * r, -0.5 * r, 1e-3 * r], m),
            "{m}"
        );
    }
    let (s, d) = f32::rescale3([3.0, -0.5, 1e-3], 0.5);
    assert_eq!((s, d), ([6.0, -1.0, 2e-3], 0.5));
}

#[test]
fn mul_u32_to_fixed_i32_is_exact_in_fixed22() {
    let mut rng = Rng(0x0DDC_0FFE_E000_0042);
    let ns = [
        1u32, 2, 3, 239, 240, 480, 511, 512, 800, 1023, 1024, 4096, 65_535,
    ];
    for _ in 0..100_000 {
        let x = F::from_bits(rng.bits());
        for &n in &ns {
            for frac in [0u32, 3, 4, 16, 22] {
                let want = (x.to_f64() * f64::from(n) * f64::from(1u32 << frac) + 0.5).floor();
                let want = want.clamp(f64::from(i32::MIN), f64::from(i32::MAX)) as i32;
                assert_eq!(x.mul_u32_to_fixed_i32(n, frac), want, "{x:?} {n} {frac}");
            }
        }
    }
    // Where the product exceeds Fixed22's range the old form saturated at 512 (4096 / 8).
    let x = F::from_f64(1.25);
    assert_eq!(x.mul_u32_to_fixed_i32(480, 3), 4800);
    assert_eq!((x * F::from_u32(480)).to_fixed_i32(3), 4096);
}

#[test]
fn mul_u32_to_fixed_i32_matches_the_float_operators() {
    let mut rng = Rng(0xF10A_7000_0000_0007);
    for _ in 0..100_000 {
        let u = (rng.next() >> 11) as f64 / (1u64 << 53) as f64; // [0, 1)
        let x = (u - 0.3) * 10.0;
        for n in [1u32, 240, 480, 800, 1024, 4096] {
            for frac in [0u32, 3, 4] {
                let (a, b) = (x, x as f32);
                assert_eq!(
                    a.mul_u32_to_fixed_i32(n, frac),
                    (a * n as f64).to_fixed_i32(frac)
                );
                assert_eq!(
                    b.mul_u32_to_fixed_i32(n, frac),
                    (b * n as f32).to_fixed_i32(frac)
                );
                let c = Fast32::from_f64(x);
                assert_eq!(
                    c.mul_u32_to_fixed_i32(n, frac),
                    (c * Fast32::from_u32(n)).to_fixed_i32(frac)
                );
            }
        }
    }
}

#[test]
fn from_u32_is_exact_below_512_and_saturates_from_512_in_fixed22() {
    for n in 0..512u32 {
        assert_eq!(F::from_u32(n).to_f64(), f64::from(n));
    }
    for n in [512u32, 513, 800, 4096, u32::MAX] {
        assert_eq!(F::from_u32(n), F::MAX, "{n}");
    }
    assert_eq!(F::MAX.to_f64(), 512.0 - LSB);
    assert_eq!(f32::from_u32(1 << 24), 16_777_216.0);
    assert_eq!(f32::from_u32((1 << 24) + 1), 16_777_216.0); // rounded to nearest (even)
    assert_eq!(f64::from_u32(u32::MAX), 4_294_967_295.0);
}
