//! Output files follow the user's umask (issue 10): written through temporary files, they
//! used to keep the temporary's mode 0600. One test in its own binary, because the umask
//! is process-wide.

#![cfg(unix)]

use serde_json::json;
use std::os::unix::fs::PermissionsExt;
use wearsim_host::io::write_outputs;

fn modes(dir: &std::path::Path) -> Vec<(String, u32)> {
    let mut v: Vec<(String, u32)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            let mode = e.metadata().unwrap().permissions().mode() & 0o777;
            (e.file_name().to_string_lossy().into_owned(), mode)
        })
        .collect();
    v.sort();
    v
}

#[test]
fn outputs_are_created_with_the_umask() {
    let x = [0.0, 1.0, -1.0, 0.5];
    for (umask, want) in [(0o022, 0o644), (0o077, 0o600), (0o002, 0o664)] {
        let tmp = tempfile::tempdir().unwrap();
        // SAFETY-free libc call: umask only swaps the process's file-creation mask.
        let old = unsafe { libc::umask(umask) };
        let r = write_outputs(tmp.path(), "run", &[("accel_g", &x)], 1000.0, &json!({}));
        unsafe { libc::umask(old) };
        r.unwrap();
        let got = modes(tmp.path());
        assert_eq!(got.len(), 3, "{got:?}");
        for (name, mode) in got {
            assert_eq!(mode, want, "{name} under umask {umask:03o}: {mode:03o}");
        }
    }
}
