#![no_main]
//! The IMS raw ASCII snapshot reader on arbitrary bytes (channel 1).

use libfuzzer_sys::fuzz_target;

mod common;

fuzz_target!(|data: &[u8]| {
    let p = common::scratch("2004.02.12.10.32.39", data);
    let _ = wearsim_host::io::read_ims_snapshot(&p, 1);
});
