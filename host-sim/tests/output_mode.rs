//! Output files follow the user's umask (issue 10): written through temporary files, they
//! used to keep the temporary's mode 0600. One binary of its own, because the umask is
//! process-wide (the tests set it in turn, under one lock).

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

/// The process umask is shared by the tests of this binary.
static UMASK: std::sync::Mutex<()> = std::sync::Mutex::new(());

const CASES: [(u32, u32); 3] = [(0o022, 0o644), (0o077, 0o600), (0o002, 0o664)];

#[test]
fn outputs_are_created_with_the_umask() {
    let _g = UMASK.lock().unwrap_or_else(|e| e.into_inner());
    let x = [0.0, 1.0, -1.0, 0.5];
    for (umask, want) in CASES {
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

/// The other writers: the one every report and table goes through
/// (`life::output::write_atomic`: `gap.json`, `analyze --out`, life sets) and the
/// feature-table writer (`wearsim features`, run as a child, which inherits the umask).
#[test]
fn reports_and_feature_tables_follow_the_umask() {
    let _g = UMASK.lock().unwrap_or_else(|e| e.into_inner());
    let snaps = tempfile::tempdir().unwrap();
    // Twelve IMS-layout snapshots (tab-separated, four channels, named by time stamp).
    for i in 0..12u32 {
        let rows: String = (0..512u32)
            .map(|j| {
                let v = ((i * 512 + j) as f64 * 0.37).sin() * (1.0 + 0.1 * i as f64);
                format!("{v:.4}\t{v:.4}\t{v:.4}\t{v:.4}\n")
            })
            .collect();
        let name = format!("2004.02.12.{:02}.{:02}.39", 10 + i / 6, (i % 6) * 10);
        std::fs::write(snaps.path().join(name), rows).unwrap();
    }
    for (umask, want) in CASES {
        let tmp = tempfile::tempdir().unwrap();
        let old = unsafe { libc::umask(umask) };
        let r = wearsim_host::life::output::write_atomic(&tmp.path().join("r.json"), b"{}");
        let table = tmp.path().join("t.csv");
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_wearsim"))
            // Snapshots shorter than IMS's 20 480 samples: not the ims-za2115 preset's
            // table, so the bearing is given by its geometry.
            .args([
                "features",
                "--layout",
                "ims",
                "--bearing-geometry",
                "elements=16,ball=8.4,pitch=71.5,angle=15.17",
                "--out",
            ])
            .arg(&table)
            .arg(snaps.path())
            .output();
        unsafe { libc::umask(old) };
        r.unwrap();
        let o = o.unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let got = modes(tmp.path());
        assert_eq!(got.len(), 3, "{got:?}");
        for (name, mode) in got {
            assert_eq!(mode, want, "{name} under umask {umask:03o}: {mode:03o}");
        }
    }
}
