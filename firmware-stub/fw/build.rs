//! Picks the linker memory map of the QEMU machine the target runs on: `mps2-an386` for the
//! Cortex-M4F (`thumbv7em-none-eabihf`), `mps2-an385` for the Cortex-M3 (`thumbv7m-none-eabi`).
use std::{env, fs, path::PathBuf};

fn main() {
    let target = env::var("TARGET").unwrap_or_default();
    let machine = if target.starts_with("thumbv7m") {
        "mps2-an385"
    } else {
        "mps2-an386"
    };
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("OUT_DIR is set by cargo"));
    let src = PathBuf::from("memory").join(format!("{machine}.x"));
    let text = fs::read(&src).expect("memory map of the machine");
    fs::write(out.join("memory.x"), text).expect("write memory.x");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory");
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-env-changed=WEARSIM_PRESET");
    println!("cargo:rerun-if-env-changed=WEARSIM_SEED");
    println!("cargo:rerun-if-env-changed=WEARSIM_SAMPLES");
}
