//! The f32 square root: `libm::sqrtf` (the fallback) is correctly rounded for every one of the
//! 2^32 f32 inputs, checked against an exact integer reference, so it returns the same bits as
//! the hardware `VSQRT.F32` that `<f32 as Real>::sqrt` uses on FPU targets (IEEE 754 requires
//! it to be correctly rounded; `arealight::real::hw`). The QEMU budget checks the hardware
//! instruction itself against `libm::sqrtf` on the emulated Cortex-M4F.

use arealight::Real;

/// The correctly rounded (to nearest, ties to even) square root of a positive finite f32, in
/// integers: `x = m 2^e` with `e` even, `M = m 4^k` in [2^48, 2^50), `s = isqrt(M)` has 25
/// bits; the last one and the remainder round it to 24.
fn reference_sqrt(bits: u32) -> u32 {
    let (exp, frac) = ((bits >> 23) & 0xFF, bits & 0x7F_FFFF);
    let (mut m, mut e) = if exp == 0 {
        (u64::from(frac), -149i32)
    } else {
        (u64::from(frac | 1 << 23), exp as i32 - 150)
    };
    if e & 1 != 0 {
        m <<= 1;
        e -= 1;
    }
    let mut k = 0;
    while m < 1 << 48 {
        m <<= 2;
        k += 1;
    }
    // m in [2^48, 2^50): exact in f64, so the estimate is within one of isqrt.
    let mut s = (m as f64).sqrt() as u64;
    while s * s > m {
        s -= 1;
    }
    while (s + 1) * (s + 1) <= m {
        s += 1;
    }
    let sticky = s * s != m;
    let (mut q, guard) = (s >> 1, s & 1 == 1);
    if guard && (sticky || q & 1 == 1) {
        q += 1;
    }
    // sqrt(x) = q 2^(e/2 - k + 1), always a normal f32: exact through f64.
    let v = q as f64 * 2f64.powi(e / 2 - k + 1);
    (v as f32).to_bits()
}

#[test]
fn libm_sqrtf_is_correctly_rounded_for_all_inputs() {
    let threads = std::thread::available_parallelism()
        .map_or(2, |n| n.get())
        .min(8) as u64;
    let chunk = (1u64 << 32) / threads;
    let bad: u64 = std::thread::scope(|sc| {
        let handles: Vec<_> = (0..threads)
            .map(|t| {
                sc.spawn(move || {
                    let mut bad = 0u64;
                    for b in (t * chunk)..((t + 1) * chunk) {
                        let bits = b as u32;
                        let x = f32::from_bits(bits);
                        let got = libm::sqrtf(x);
                        let ok = if x.is_nan() || x < 0.0 {
                            got.is_nan()
                        } else if x == 0.0 || x.is_infinite() {
                            got.to_bits() == bits
                        } else {
                            got.to_bits() == reference_sqrt(bits)
                        };
                        if !ok {
                            if bad < 5 {
                                eprintln!("sqrtf({x:e}) = {got:e}, bits {bits:#010x}");
                            }
                            bad += 1;
                        }
                    }
                    bad
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).sum()
    });
    println!("[maxerr] libm::sqrtf vs the exact reference over all 2^32 inputs: {bad} mismatches");
    assert_eq!(bad, 0);
}

#[test]
fn real_sqrt_of_f32_is_libm_on_the_host() {
    const { assert!(!arealight::real::hw::HARDWARE_SQRT_F32) };
    for x in [
        1e-45f32,
        1e-38,
        0.5,
        2.0,
        3.0,
        1e30,
        f32::MAX,
        f32::INFINITY,
    ] {
        assert_eq!(Real::sqrt(x).to_bits(), libm::sqrtf(x).to_bits());
    }
    // The Real contract: 0 for negative input and NaN.
    assert_eq!(Real::sqrt(-1.0f32), 0.0);
    assert_eq!(Real::sqrt(f32::NAN), 0.0);
}
