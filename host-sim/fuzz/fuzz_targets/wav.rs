#![no_main]
//! `io::wav::read_wav` on arbitrary bytes (with `--fs` given, so the parser runs past the rate).

use libfuzzer_sys::fuzz_target;
use wearsim_host::io::{wav::read_wav, ReadOptions};

mod common;

fuzz_target!(|data: &[u8]| {
    let p = common::scratch("record.wav", data);
    let opts = ReadOptions {
        fs: Some(1000.0),
        ..Default::default()
    };
    let _ = read_wav(&p, &opts);
});
