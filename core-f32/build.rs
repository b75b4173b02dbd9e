//! Compiles `../core/src` in single precision: `Real = f32` (see `core/src/real.rs`).
fn main() {
    println!("cargo::rustc-check-cfg=cfg(wearsim_f32)");
    println!("cargo::rustc-cfg=wearsim_f32");
    println!("cargo::rerun-if-changed=build.rs");
}
