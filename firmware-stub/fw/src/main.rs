//! wearsim firmware stub: the `wearsim-core` model on a Cortex-M (QEMU `mps2-an386` M4F or
//! `mps2-an385` M3) acting as a virtual accelerometer; see [`firmware`] and
//! `docs/firmware.md`. Built for any other target (as `cargo clippy --all-targets` in this
//! workspace does), it is a stub that says how to build it.
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]

#[cfg(target_os = "none")]
pub mod firmware;

#[cfg(not(target_os = "none"))]
fn main() {
    eprintln!(
        "wearsim-fw runs on a Cortex-M: build it with --target thumbv7em-none-eabihf or \
         thumbv7m-none-eabi inside firmware-stub/ (see docs/firmware.md)"
    );
    std::process::exit(2);
}
