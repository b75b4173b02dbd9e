#![no_main]
//! The MAT v5 parser on arbitrary bytes, every numeric variable converted (the per-file
//! budget bounds inflation and widening).

use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let _ = wearsim_host::io::mat::parse_mat(data, Path::new("fuzz.mat"), &|_| true);
});
