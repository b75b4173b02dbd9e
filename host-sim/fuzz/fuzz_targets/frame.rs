#![no_main]
//! The firmware frame decoder and the capture report built on it, on arbitrary bytes: the
//! report stays bounded (at most `MAX_LISTED` spans and problems listed) and consistent.

use libfuzzer_sys::fuzz_target;
use wearsim_host::capture::{decode, MAX_LISTED};

fuzz_target!(|data: &[u8]| {
    let d = decode("fuzz", data);
    let r = &d.report;
    assert!(r.corrupt.len() <= MAX_LISTED);
    assert!(r.problems.len() <= MAX_LISTED + 1);
    assert_eq!(r.samples, d.accel.len());
    assert!(!r.complete || d.accel.iter().all(|v| v.is_finite()));
});
