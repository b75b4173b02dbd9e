//! A failing run leaves no output directory it created (docs: "exit 2, nothing written"):
//! every command that takes an output directory (`--out`, `analyze --plot`) or an output
//! file in a new directory is run on bad input into a directory that does not exist, and
//! the directory must still not exist afterwards. The directory is created by the lock
//! every writer takes first (`io/lock.rs`), which removes it again when the run wrote
//! nothing into it.

use crate::support::{s, wearsim};
use std::path::Path;

/// Runs `args` (with `{out}` replaced by `out`), expects a failure and no `out`.
fn fails_leaving_nothing(args: &[&str], out: &Path) {
    let a: Vec<String> = args.iter().map(|x| x.replace("{out}", s(out))).collect();
    let a: Vec<&str> = a.iter().map(String::as_str).collect();
    let o = wearsim(&a);
    assert!(
        !o.status.success(),
        "{a:?} succeeded: {}",
        String::from_utf8_lossy(&o.stdout)
    );
    assert!(
        !out.exists(),
        "{a:?} failed ({}) but left {}",
        String::from_utf8_lossy(&o.stderr).trim(),
        out.display()
    );
}

#[test]
fn failing_runs_leave_no_output_directory() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let garbage = d.join("garbage.txt");
    std::fs::write(&garbage, "garbage\n").unwrap();
    let bad_csv = d.join("bad.csv");
    std::fs::write(&bad_csv, "a,b\n").unwrap();
    let spec = d.join("spec.toml");
    std::fs::write(&spec, "not a spec\n").unwrap();
    let empty = d.join("empty");
    std::fs::create_dir(&empty).unwrap();
    let missing = d.join("no-such-data");
    let (g, c, sp, e, m) = (s(&garbage), s(&bad_csv), s(&spec), s(&empty), s(&missing));
    let cases: Vec<(&str, Vec<&str>)> = vec![
        ("gap", vec!["gap", "--real", c, "--out", "{out}"]),
        (
            "gap-life",
            vec!["gap", "--life", "--real", c, "--real", c, "--out", "{out}"],
        ),
        (
            "simulate",
            vec!["simulate", "--config", g, "--out", "{out}"],
        ),
        ("life", vec!["life", "--config", g, "--out", "{out}"]),
        (
            "lives",
            vec!["life", "--lives", "3", "--config", g, "--out", "{out}"],
        ),
        (
            "dense",
            vec!["life", "--dense", "--config", g, "--out", "{out}"],
        ),
        (
            "ims-compare",
            vec!["ims-compare", "--data", m, "--out", "{out}"],
        ),
        (
            "ims-validate",
            vec!["ims-validate", "--data", m, "--out", "{out}"],
        ),
        ("capture", vec!["capture", "--input", g, "--out", "{out}"]),
        ("sweep", vec!["sweep", sp, "--out", "{out}"]),
        ("plot", vec!["analyze", c, "--plot", "{out}"]),
    ];
    for (name, args) in &cases {
        // Two levels: neither the directory nor its new parent may be left.
        let parent = d.join(format!("new-{name}"));
        fails_leaving_nothing(args, &parent.join("out"));
        assert!(!parent.exists(), "{name}: left {}", parent.display());
    }
    // Output files in a new directory.
    let out = d.join("new-features");
    fails_leaving_nothing(
        &[
            "features",
            e,
            "--layout",
            "ims",
            "--out",
            &format!("{}/t.csv", s(&out)),
        ],
        &out,
    );
    let out = d.join("new-batch");
    fails_leaving_nothing(
        &["analyze", c, g, "--out", &format!("{}/rows.csv", s(&out))],
        &out,
    );
    // A directory that existed before is left, even though the run wrote nothing.
    let old = d.join("old");
    std::fs::create_dir(&old).unwrap();
    let o = wearsim(&["gap", "--real", c, "--out", s(&old)]);
    assert_eq!(o.status.code(), Some(2));
    assert!(old.is_dir() && std::fs::read_dir(&old).unwrap().next().is_none());
}
