//! Linker inputs of the no-panic image: a memory map large enough for both precisions of the
//! whole core API (the image is linked, never loaded, so the map is not a real part's), and
//! an empty `defmt.x` — `firmware-stub/.cargo/config.toml` passes `-Tdefmt.x` to every ARM
//! image of this workspace, and this one logs nothing.
use std::{env, fs, path::PathBuf};

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("OUT_DIR is set by cargo"));
    fs::write(
        out.join("memory.x"),
        "MEMORY\n{\n  FLASH : ORIGIN = 0x00000000, LENGTH = 16M\n  RAM   : ORIGIN = 0x20000000, LENGTH = 16M\n}\n",
    )
    .expect("write memory.x");
    fs::write(out.join("defmt.x"), "/* no defmt in this image */\n").expect("write defmt.x");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=build.rs");
}
