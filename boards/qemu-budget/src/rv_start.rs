//! The start-up of the RISC-V image on QEMU's `virt` machine, run with `-bios none`: QEMU's
//! reset code jumps to the start of RAM (0x8000_0000) in machine mode, where `link-rv.x`
//! places `_start`. QEMU's ELF loader has put every loadable section at its address, so only
//! `.bss` is cleared; then the stack pointer is set, `mtvec` pointed at a trap handler that
//! reports the trap and fails, and the firmware's `main` called. No interrupts are enabled.
//!
//! Hand-written rather than `riscv-rt`: this is the whole of it for a single hart under QEMU
//! (no `.data` copy, no interrupt vectors, no hart selection), and it keeps the image free of
//! dependencies whose updates would move the measured code.

use crate::counter::{fail, Line};

core::arch::global_asm!(
    ".section .text.start, \"ax\"",
    ".globl _start",
    "_start:",
    "    la sp, _stack_top",
    "    la t0, _sbss",
    "    la t1, _ebss",
    "1:  bgeu t0, t1, 2f",
    "    sw zero, 0(t0)",
    "    addi t0, t0, 4",
    "    j 1b",
    "2:  la t0, _trap",
    "    csrw mtvec, t0",
    "    call rv_main",
    "3:  j 3b",
    // Direct-mode trap vector: 4-byte aligned. The stack is reset (the trap ends the run).
    ".balign 4",
    "_trap:",
    "    la sp, _stack_top",
    "    call rv_trap",
    "4:  j 4b",
);

/// Called by `_start`.
#[no_mangle]
extern "C" fn rv_main() -> ! {
    crate::main()
}

/// Called on any trap (an exception: no interrupts are enabled): a `FAIL` line with the
/// cause and the faulting address, then exit status 1.
#[no_mangle]
extern "C" fn rv_trap() -> ! {
    let (cause, epc, tval): (u32, u32, u32);
    // SAFETY: reads of machine-mode trap CSRs into registers; nothing else.
    unsafe {
        core::arch::asm!(
            "csrr {0}, mcause",
            "csrr {1}, mepc",
            "csrr {2}, mtval",
            out(reg) cause,
            out(reg) epc,
            out(reg) tval,
            options(nomem, nostack),
        );
    }
    let mut line = Line::new();
    fail(
        &mut line,
        format_args!("trap: mcause={cause:#x} mepc={epc:#010x} mtval={tval:#x}"),
    )
}
