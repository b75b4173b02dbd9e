//! Helpers shared by the command-line integration tests (each test crate uses a subset).
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use wearsim_host::io::mat::fixture::{mat5_tree_bytes, FixtureValue};

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

/// A broadband test signal of `n` samples (deterministic xorshift), peak about 0.5.
pub fn noise(n: usize) -> Vec<f64> {
    let mut x: u64 = 0x2545_F491_4F6C_DD1D;
    (0..n)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        })
        .collect()
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

/// Runs `wearsim life --json` on `thesis-61810` with the TOML `defect` table body
/// (`location = "…"`, …) written to `dir/NAME.toml`: seed 4, a snapshot every 5·10⁵
/// revolutions, 0.05 s windows, at most 10⁹ cycles, output in `dir/NAME`. Asserts success;
/// returns the JSON on stdout, `life-summary.json` and the output directory.
pub fn thesis_life(
    dir: &Path,
    name: &str,
    defect: &str,
) -> (serde_json::Value, serde_json::Value, std::path::PathBuf) {
    let cfg = dir.join(format!("{name}.toml"));
    std::fs::write(
        &cfg,
        format!("preset = \"thesis-61810\"\n[defect]\n{defect}\n"),
    )
    .expect("scenario written");
    let out = dir.join(name);
    let o = wearsim(&[
        "life",
        "--config",
        s(&cfg),
        "--seed",
        "4",
        "--snapshot-every",
        "500000",
        "--window",
        "0.05",
        "--cycles",
        "1e9",
        "--out",
        s(&out),
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = serde_json::from_slice(&o.stdout).expect("JSON on stdout");
    let summary =
        serde_json::from_slice(&std::fs::read(out.join("life-summary.json")).expect("summary"))
            .expect("summary JSON");
    (stdout, summary, out)
}

/// `features` flags for a FEMTO (PRONOSTIA) folder that its files do not hold: speed, load
/// and the bearing's geometry (13 balls of 3.5 mm on a 25.6 mm pitch).
pub const FEMTO_FLAGS: [&str; 6] = [
    "--rpm",
    "1800",
    "--load-n",
    "4000",
    "--bearing-geometry",
    "elements=13,ball=3.5,pitch=25.6,angle=0",
];

/// `wearsim gap --life` of the training table `a` and the held-out table `b` into `out`,
/// with `extra` arguments after them.
pub fn gap_life(a: &Path, b: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "gap",
        "--life",
        "--real",
        s(a),
        "--real",
        s(b),
        "--out",
        s(out),
    ];
    args.extend_from_slice(extra);
    wearsim(&args)
}

/// `analyze FILE --rpm 1797 --bearing cwru-6205-de --json` and `extra`; its JSON, the run
/// having succeeded.
pub fn analyze_6205(p: &Path, extra: &[&str]) -> serde_json::Value {
    let mut a = vec![
        "analyze",
        s(p),
        "--rpm",
        "1797",
        "--bearing",
        "cwru-6205-de",
        "--json",
    ];
    a.extend(extra);
    json_ok(&wearsim(&a))
}

/// The `--json` object of a run that must have succeeded.
pub fn json_ok(o: &Output) -> serde_json::Value {
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).expect("analyze --json prints one JSON object")
}

/// Lines `time,value` of `x` at `fs` Hz, the time printed by `time` (seconds → cell).
pub fn timed_rows(x: &[f64], fs: f64, sep: &str, time: impl Fn(f64) -> String) -> String {
    x.iter()
        .enumerate()
        .map(|(i, v)| format!("{}{sep}{v}\n", time(i as f64 / fs)))
        .collect()
}

/// Writes `vars` as a MAT v5 file `dir/name`.
pub fn mat(dir: &Path, name: &str, vars: &[(&str, FixtureValue)]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, mat5_tree_bytes(vars)).expect("write mat");
    p
}

/// Writes a little-endian f64 `.npy` file `dir/name` of `shape` holding `data` in C order.
pub fn npy(dir: &Path, name: &str, shape: &[u64], data: &[f64]) -> PathBuf {
    use npyz::WriterBuilder;
    let mut buf = Vec::new();
    let mut w = npyz::WriteOptions::new()
        .default_dtype()
        .shape(shape)
        .writer(&mut buf)
        .begin_nd()
        .expect("npy header");
    w.extend(data.iter().copied()).expect("npy data");
    w.finish().expect("npy end");
    let p = dir.join(name);
    std::fs::write(&p, buf).expect("write npy");
    p
}
