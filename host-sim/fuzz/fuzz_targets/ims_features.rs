#![no_main]
//! The IMS per-snapshot feature-table reader on arbitrary bytes.

use libfuzzer_sys::fuzz_target;

mod common;

fuzz_target!(|data: &[u8]| {
    let p = common::scratch("features.csv", data);
    let _ = wearsim_host::io::read_ims_features(&p);
});
