//! Puts the memory map of the target's QEMU machine where cortex-m-rt's `link.x` finds it
//! (ARM), or the whole linker script `link-rv.x` where `-Tlink-rv.x` finds it (RISC-V).

use std::{env, fs, path::PathBuf};

fn main() {
    let target = env::var("TARGET").unwrap_or_default();
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    println!("cargo:rerun-if-changed=link-rv.x");
    if target.starts_with("riscv32") {
        let text = fs::read("link-rv.x").expect("linker script next to Cargo.toml");
        fs::write(out.join("link-rv.x"), text).expect("OUT_DIR is writable");
        println!("cargo:rustc-link-search={}", out.display());
        println!("cargo:rerun-if-changed=build.rs");
        return;
    }
    let map = if target.starts_with("thumbv6m") {
        "memory-m0.x"
    } else {
        "memory-m4f.x"
    };
    let text = fs::read(map).expect("memory map next to Cargo.toml");
    fs::write(out.join("memory.x"), text).expect("OUT_DIR is writable");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory-m0.x");
    println!("cargo:rerun-if-changed=memory-m4f.x");
    println!("cargo:rerun-if-changed=build.rs");
}
