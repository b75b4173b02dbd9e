#![no_main]
//! The MAT v5 parsers on arbitrary bytes, every numeric variable converted (the per-file
//! budget bounds inflation and widening): the flat variable reader and the tree reader
//! (structs, cells, chars), then layout recognition on the tree.

use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let _ = wearsim_host::io::mat::parse_mat(data, Path::new("fuzz.mat"), &|_| true);
    if let Ok(tree) = wearsim_host::io::mat::parse_mat_tree(data, Path::new("fuzz.mat"), &|_| true) {
        let _ = wearsim_host::io::mat::recognise(&tree);
        let _ = wearsim_host::io::mat::numeric_arrays(&tree);
    }
});
