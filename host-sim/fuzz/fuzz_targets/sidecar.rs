#![no_main]
//! The JSON sidecar reader on arbitrary bytes.

use libfuzzer_sys::fuzz_target;

mod common;

fuzz_target!(|data: &[u8]| {
    let p = common::scratch("record.json", data);
    let _ = wearsim_host::io::sidecar::read_sidecar(&p);
});
