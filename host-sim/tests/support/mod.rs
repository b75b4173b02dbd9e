//! Helpers shared by the command-line integration tests.

use std::process::Output;

/// Asserts that a run was refused as bad input: exit code 2 and a message on standard error
/// that contains every one of `needles` (the field named, the allowed range…).
pub fn refused(o: &Output, needles: &[&str]) {
    let msg = String::from_utf8_lossy(&o.stderr);
    assert_eq!(
        o.status.code(),
        Some(2),
        "exit {:?}: {msg}",
        o.status.code()
    );
    for n in needles {
        assert!(msg.contains(n), "message lacks {n:?}: {msg}");
    }
}
