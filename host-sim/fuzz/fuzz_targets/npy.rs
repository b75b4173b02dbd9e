#![no_main]
//! `io::npy::read_npy` on arbitrary bytes (with `--fs` given, so the parser runs past the rate).

use libfuzzer_sys::fuzz_target;
use wearsim_host::io::{npy::read_npy, ReadOptions};

mod common;

fuzz_target!(|data: &[u8]| {
    let p = common::scratch("record.npy", data);
    let opts = ReadOptions {
        fs: Some(1000.0),
        ..Default::default()
    };
    let _ = read_npy(&p, &opts);
});
