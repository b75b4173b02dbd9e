//! Helpers shared by the command-line integration tests.

use std::path::Path;
use std::process::{Command, Output};

/// Runs the `wearsim` binary of this build with `args` and returns what it did.
pub fn wearsim(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wearsim"))
        .args(args)
        .output()
        .expect("the wearsim binary runs")
}

/// A path as a command-line argument (the tests' temporary paths are UTF-8).
pub fn s(p: &Path) -> &str {
    p.to_str().expect("UTF-8 path")
}

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
