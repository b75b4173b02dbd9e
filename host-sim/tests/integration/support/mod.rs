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

/// A synthetic run-to-failure life in the documented feature-table format
/// (`docs/feature-tables.md`), for [`rig_table`].
pub struct RigTable<'a> {
    /// Snapshots.
    pub n: usize,
    /// Seed of the snapshot-to-snapshot scatter (varies it between bearings).
    pub seed: u64,
    /// The sidecar's `bearing` object (JSON text).
    pub bearing: &'a str,
    /// Radial load, N (JSON number text).
    pub load: &'a str,
    /// Shaft speed, rpm.
    pub rpm: f64,
    /// Seconds between snapshots.
    pub interval: f64,
    /// The RMS rises from `rise.0` of the life to `1 + rise.1` times its steady level at
    /// the end (`rise.1` = 0: a flat life, with no onset of instability).
    pub rise: (f64, f64),
    /// The sidecar's `source`.
    pub source: &'a str,
}

/// Writes `dir/name.csv` and its sidecar: a bearing whose RMS rises as `t.rise` (kurtosis
/// rising over the last 20 %), with scatter from a fixed xorshift generator seeded by
/// `t.seed`; the sidecar says it failed at the outer race (25.6 kHz snapshots of 2560
/// samples). Returns the CSV's path.
pub fn rig_table(dir: &Path, name: &str, t: &RigTable) -> PathBuf {
    let mut st = t.seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut g = move || {
        // Sum of four uniforms: roughly Gaussian, unit variance.
        (0..4)
            .map(|_| {
                st ^= st << 13;
                st ^= st >> 7;
                st ^= st << 17;
                (st >> 11) as f64 / (1u64 << 53) as f64 - 0.5
            })
            .sum::<f64>()
            * 3f64.sqrt()
    };
    let n = t.n;
    let mut csv = String::from("snapshot,time_s,rms,kurtosis,crest_factor,skewness,peak\n");
    for k in 0..n {
        let u = k as f64 / (n - 1) as f64;
        let rise = if u > t.rise.0 {
            1.0 + t.rise.1 * ((u - t.rise.0) / (1.0 - t.rise.0)).powi(2)
        } else {
            1.0
        };
        let rms = 0.5 * rise * (1.0 + 0.03 * g());
        let kurt = 3.0 + 0.1 * g() + if u > 0.8 { 2.0 * (u - 0.8) / 0.2 } else { 0.0 };
        let crest = 4.5 + 0.2 * g();
        csv.push_str(&format!(
            "{k},{},{rms},{kurt},{crest},{},{}\n",
            t.interval * k as f64,
            0.02 * g(),
            rms * crest
        ));
    }
    let p = dir.join(format!("{name}.csv"));
    std::fs::write(&p, csv).unwrap();
    let side = format!(
        r#"{{
  "format": "wearsim-feature-table",
  "format_version": 1,
  "source": "{}",
  "bearing": {},
  "channel": "horiz",
  "unit": "g",
  "rpm": {:.1},
  "radial_load_n": {},
  "sample_rate_hz": 25600.0,
  "snapshot_samples": 2560,
  "snapshot_interval_s": {},
  "failure_mode": "outer-race",
  "n_snapshots": {n}
}}"#,
        t.source, t.bearing, t.rpm, t.load, t.interval
    );
    std::fs::write(dir.join(format!("{name}.json")), side).unwrap();
    p
}
