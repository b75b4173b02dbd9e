#![no_main]
//! The documented feature-table reader (`io::feature_table`, docs/feature-tables.md) on
//! arbitrary bytes: the input up to its first NUL byte is the JSON sidecar, the rest the
//! CSV table (no NUL: the whole input is the CSV and the sidecar is empty).

use libfuzzer_sys::fuzz_target;

mod common;

fuzz_target!(|data: &[u8]| {
    let (side, table) = match data.iter().position(|b| *b == 0) {
        Some(i) => (&data[..i], &data[i + 1..]),
        None => (&data[..0], data),
    };
    let _ = common::scratch("life.json", side);
    let p = common::scratch("life.csv", table);
    let _ = wearsim_host::io::feature_table::read_feature_table(&p);
});
