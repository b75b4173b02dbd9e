#![no_main]
//! `io::csv::read_csv` on arbitrary bytes (with `--fs` given, so the parser runs past the rate).

use libfuzzer_sys::fuzz_target;
use wearsim_host::io::{csv::read_csv, ReadOptions};

mod common;

fuzz_target!(|data: &[u8]| {
    let p = common::scratch("record.csv", data);
    let opts = ReadOptions {
        fs: Some(1000.0),
        ..Default::default()
    };
    let _ = read_csv(&p, &opts);
});
