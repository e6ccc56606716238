//! The hardware square root of FPU-equipped Cortex-M cores: the crate's only `unsafe` code.
//!
//! # Which targets get which `f32` square root
//!
//! | target | `<f32 as Real>::sqrt` |
//! |---|---|
//! | `thumbv7em-none-eabihf` (Cortex-M4F, M7 with single precision), any `arm` target with `target_abi = "eabihf"` | `VSQRT.F32`: one instruction (14 cycles on the M4F) |
//! | everything else (`thumbv6m`, `thumbv7em-none-eabi`, RISC-V, the host) | `libm::sqrtf` (about 50 instructions of integer code on the M4F) |
//!
//! `libm` 0.2.16 has no hardware path for ARM (its arch module covers x86, aarch64 and wasm), and
//! `f32::sqrt` is not in `core`. Both square roots are correctly rounded (IEEE 754 requires it of
//! `VSQRT.F32`; `libm::sqrtf` is checked to be, over all 2^32 inputs, against an exact integer
//! reference in `tests/hw_sqrt.rs`), so they return the same bits for every input, and the
//! models' results do not depend on the target. The QEMU budget (`boards/qemu-budget`) checks
//! `VSQRT.F32` against `libm::sqrtf` on the emulated M4F over a strided sweep of bit patterns.
//!
//! One caveat: with the FPSCR's flush-to-zero bit set (not the reset state, and not something
//! this crate does), `VSQRT.F32` flushes subnormal inputs to zero where `libm::sqrtf` does not.
//!
//! # Safety argument
//!
//! The `asm!` block moves the argument from a core register into `s0`, runs `VSQRT.F32` on it
//! and moves the result back to a core register. It
//! - reads and writes only the registers it declares: its input and output core registers and
//!   `s0`, declared clobbered (`out("s0") _`; the `sreg` class needs the `vfp2` feature, which
//!   `thumbv7em-none-eabihf` does not enable, so the value travels through core registers);
//! - touches no memory and no stack (`nomem`, `nostack`) and leaves the condition flags alone
//!   (`preserves_flags`: `VMOV` and `VSQRT` write no APSR bits; `VSQRT` may set the FPSCR's
//!   cumulative exception bits, as every compiled `f32` operation does);
//! - cannot fault: the instructions exist on every core with `target_abi = "eabihf"` (the ABI
//!   passes floats in FPU registers, so the FPU is present and enabled before any Rust code
//!   runs), and the Cortex-M FPU has no trapping floating-point exceptions;
//! - is `pure`: its output depends only on its input.

#[cfg(all(target_arch = "arm", target_abi = "eabihf"))]
#[allow(unsafe_code)]
mod imp {
    /// `sqrt(x)` by `VSQRT.F32` (see the module docs).
    #[inline(always)]
    pub(crate) fn sqrtf(x: f32) -> f32 {
        let r: u32;
        // SAFETY: see the module docs: registers only, no memory, no stack, cannot fault.
        unsafe {
            core::arch::asm!(
                "vmov s0, {x}",
                "vsqrt.f32 s0, s0",
                "vmov {r}, s0",
                x = in(reg) x.to_bits(),
                r = lateout(reg) r,
                out("s0") _,
                options(pure, nomem, nostack, preserves_flags),
            );
        }
        f32::from_bits(r)
    }
}

#[cfg(not(all(target_arch = "arm", target_abi = "eabihf")))]
mod imp {
    /// `libm::sqrtf` (no hardware square root on this target).
    #[inline(always)]
    pub(crate) fn sqrtf(x: f32) -> f32 {
        libm::sqrtf(x)
    }
}

pub(crate) use imp::sqrtf;

/// `true` where `<f32 as Real>::sqrt` is the hardware `VSQRT.F32` (see the module docs).
pub const HARDWARE_SQRT_F32: bool = cfg!(all(target_arch = "arm", target_abi = "eabihf"));
