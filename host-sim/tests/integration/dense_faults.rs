//! Fault injection for dense life mode (issue 11): a `wearsim life --dense` process killed
//! with SIGKILL at random moments and resumed, or stopped with `--stop-after` in the middle
//! of blocks, ends with exactly the files of an uninterrupted run (f32 stream, manifest,
//! snapshots/features, events, timeline); concurrent runs into one directory never mix;
//! stale completion markers, corrupt checkpoints and bad `--stop-after` values are refused.
//!
//! The lives use the accelerated material (a whole life in ≈4 000 revolutions at 5 kHz) and
//! a checkpoint every 6 007 samples (`WEARSIM_CHECKPOINT_SAMPLES`), so that kills and stops
//! land in the middle of blocks. `WEARSIM_FAULT_TRIALS` sets the number of kills per life
//! (default 5; the acceptance run uses 20).

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

const CKPT: &str = "6007";
/// Files that must be identical to the uninterrupted run's.
const COMPARED: &[&str] = &[
    "life-dense.f32",
    "life-dense.json",
    "life-features.csv",
    "life-features.json",
    "life-events.csv",
    "life-events.json",
    "life-timeline.csv",
];

const CONFIG: &str = "preset = \"thesis-61810\"\nfs = 5000.0\n[material]\nlife_factor = 1e-8\ninitiation_passes = 2e3\npropagation_passes = 2e3\noverrolling = 0.05\ncrack_c0 = 300.0\n[life]\nrunning_in = 1.2\n";

const EFFECTS: &[&str] = &[
    "slip",
    "load-zone",
    "transfer-path",
    "speed-fluctuation",
    "sensor",
    "shaft-harmonics",
    "running-in",
    "roughness",
    "edge-shape",
];

fn trials() -> usize {
    std::env::var("WEARSIM_FAULT_TRIALS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(5)
}

/// xorshift64*: reproducible kill times (seed from `WEARSIM_FAULT_SEED`, default fixed).
struct Rng(u64);
impl Rng {
    fn new() -> Self {
        let s = std::env::var("WEARSIM_FAULT_SEED")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(0x2545_F491_4F6C_DD1D_u64);
        Rng(s.max(1))
    }
    fn unit(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn life_command(config: &Path, out: &Path, seed: u64, effects: bool, extra: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_wearsim"));
    c.args(["life", "--dense", "--config"])
        .arg(config)
        .args([
            "--cycles",
            "20000",
            "--snapshot-every",
            "100",
            "--window",
            "0.1",
            "--seed",
            &seed.to_string(),
            "--out",
        ])
        .arg(out)
        .args(extra)
        .env("WEARSIM_CHECKPOINT_SAMPLES", CKPT)
        .stdin(Stdio::null());
    if effects {
        for e in EFFECTS {
            c.args(["--effect", e]);
        }
    }
    c
}

fn run(mut c: Command) -> Output {
    c.output().unwrap()
}

fn ok(o: &Output) {
    assert!(
        o.status.success(),
        "exit {:?}: {}",
        o.status.code(),
        String::from_utf8_lossy(&o.stderr)
    );
}

fn write_config(dir: &Path) -> PathBuf {
    let p = dir.join("life.toml");
    std::fs::write(&p, CONFIG).unwrap();
    p
}

fn assert_same_set(reference: &Path, other: &Path, what: &str) {
    for f in COMPARED {
        let a = std::fs::read(reference.join(f)).unwrap();
        let b = std::fs::read(other.join(f))
            .unwrap_or_else(|e| panic!("{what}: {f} missing in the resumed set: {e}"));
        if a != b {
            let first = a.iter().zip(&b).position(|(x, y)| x != y);
            panic!(
                "{what}: {f} differs from the uninterrupted run ({} vs {} bytes, first difference at byte {first:?})",
                a.len(),
                b.len()
            );
        }
    }
    assert!(
        other.join("life-summary.json").exists(),
        "{what}: no summary"
    );
    assert!(
        !other.join("life-dense.ckpt").exists(),
        "{what}: checkpoint left"
    );
}

/// Runs the uninterrupted reference; returns its wall time.
fn reference(config: &Path, out: &Path, effects: bool) -> Duration {
    let t0 = Instant::now();
    ok(&run(life_command(config, out, 1, effects, &[])));
    t0.elapsed()
}

/// Kills the run `n` times at random moments (SIGKILL) and resumes it each time, then
/// lets it finish.
fn killed_and_resumed(config: &Path, out: &Path, effects: bool, span: Duration, n: usize) {
    let mut rng = Rng::new();
    let mut kills = 0;
    let mut attempts = 0;
    // Until `n` kills have landed in a running process (a run that finishes before its
    // kill time does not count; it is removed and the next attempt starts afresh).
    while kills < n && attempts < 3 * n {
        attempts += 1;
        let mut child = life_command(config, out, 1, effects, &[])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let delay = span.mul_f64(0.05 + 0.75 * rng.unit());
        let t0 = Instant::now();
        loop {
            if child.try_wait().unwrap().is_some() {
                break;
            }
            if t0.elapsed() >= delay {
                child.kill().unwrap(); // SIGKILL
                kills += 1;
                break;
            }
            std::thread::sleep(Duration::from_millis(5));
        }
        let _ = child.wait();
        if out.join("life-summary.json").exists() {
            // The life finished before the kill: start over for the next trial.
            std::fs::remove_dir_all(out).unwrap();
        }
    }
    ok(&run(life_command(config, out, 1, effects, &[])));
    println!("{kills} kills landed in a running process ({attempts} attempts)");
    assert_eq!(
        kills, n,
        "only {kills} of {n} kills landed in {attempts} attempts"
    );
}

/// Issue 11 (1): stopped in the middle of blocks (`--stop-after`, repeatedly) and killed
/// at random moments, the reference life resumes bit-identically, snapshots included.
#[test]
fn reference_life_resumes_bit_identically() {
    let dir = tempfile::tempdir().unwrap();
    let config = write_config(dir.path());
    let whole = dir.path().join("whole");
    let span = reference(&config, &whole, false);

    let split = dir.path().join("split");
    let mut runs = 0;
    while !split.join("life-summary.json").exists() {
        ok(&run(life_command(
            &config,
            &split,
            1,
            false,
            &["--stop-after", "7.3"],
        )));
        runs += 1;
        assert!(runs < 100, "no completion after {runs} invocations");
    }
    assert!(runs > 5, "only {runs} invocations");
    assert_same_set(&whole, &split, "--stop-after 7.3 chain");

    let killed = dir.path().join("killed");
    killed_and_resumed(&config, &killed, false, span, trials());
    assert_same_set(&whole, &killed, "random SIGKILL");
}

/// The same with every effect on (transfer-path and sensor memories, running-in, speed
/// fluctuation).
#[test]
fn every_effect_life_resumes_bit_identically() {
    let dir = tempfile::tempdir().unwrap();
    let config = write_config(dir.path());
    let whole = dir.path().join("whole");
    let span = reference(&config, &whole, true);
    let killed = dir.path().join("killed");
    killed_and_resumed(&config, &killed, true, span, trials());
    assert_same_set(&whole, &killed, "random SIGKILL, every effect");
}

/// Issue 11 (2): a second dense life (another seed) into a directory in use is refused
/// with exit 2 naming the directory; afterwards it is refused again because the
/// checkpoint belongs to another run; the set stays the first run's.
#[test]
fn concurrent_dense_lives_never_mix() {
    let dir = tempfile::tempdir().unwrap();
    let config = write_config(dir.path());
    let out = dir.path().join("shared");
    let first = life_command(&config, &out, 1, false, &["--stop-after", "40"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    while !out.join("life-dense.json").exists() && t0.elapsed() < Duration::from_secs(60) {
        std::thread::sleep(Duration::from_millis(5));
    }
    let second = run(life_command(
        &config,
        &out,
        2,
        false,
        &["--stop-after", "1"],
    ));
    let a = first.wait_with_output().unwrap();
    ok(&a);
    assert_eq!(second.status.code(), Some(2));
    let msg = String::from_utf8_lossy(&second.stderr);
    assert!(
        msg.contains("in use") && msg.contains("shared"),
        "message: {msg}"
    );
    let again = run(life_command(
        &config,
        &out,
        2,
        false,
        &["--stop-after", "1"],
    ));
    assert_eq!(again.status.code(), Some(2));
    let manifest: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("life-dense.json")).unwrap()).unwrap();
    assert_eq!(manifest["seed"], 1);
    let samples = manifest["samples"].as_u64().unwrap();
    assert_eq!(samples, 200_000);
    assert_eq!(
        std::fs::metadata(out.join("life-dense.f32")).unwrap().len(),
        4 * samples
    );
}

/// Issue 11 (2): two `simulate` runs into one directory at once: one is refused (exit 2,
/// naming the directory) or they run one after the other; the set is always one run's.
#[test]
fn concurrent_simulations_never_mix() {
    let dir = tempfile::tempdir().unwrap();
    let sim = |seed: &str, out: &Path| {
        let mut c = Command::new(env!("CARGO_BIN_EXE_wearsim"));
        c.args(["simulate", "--duration", "1", "--seed", seed, "--out"])
            .arg(out)
            .stdout(Stdio::null())
            .stderr(Stdio::piped());
        c
    };
    let solo: Vec<PathBuf> = ["1", "2"]
        .iter()
        .map(|s| {
            let d = dir.path().join(format!("solo{s}"));
            ok(&sim(s, &d).output().unwrap());
            d
        })
        .collect();
    let mut refused = 0;
    for trial in 0..4 {
        let out = dir.path().join(format!("shared{trial}"));
        let a = sim("1", &out).spawn().unwrap();
        let b = sim("2", &out).spawn().unwrap();
        let (a, b) = (a.wait_with_output().unwrap(), b.wait_with_output().unwrap());
        for o in [&a, &b] {
            match o.status.code() {
                Some(0) => {}
                Some(2) => {
                    refused += 1;
                    let msg = String::from_utf8_lossy(&o.stderr);
                    assert!(msg.contains("in use"), "{msg}");
                }
                c => panic!("exit {c:?}: {}", String::from_utf8_lossy(&o.stderr)),
            }
        }
        let csv = std::fs::read(out.join("simulate.csv")).unwrap();
        let wav = std::fs::read(out.join("simulate.wav")).unwrap();
        let side: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join("simulate.json")).unwrap()).unwrap();
        let k = solo
            .iter()
            .position(|d| std::fs::read(d.join("simulate.csv")).unwrap() == csv)
            .expect("the CSV is neither run's");
        assert_eq!(
            wav,
            std::fs::read(solo[k].join("simulate.wav")).unwrap(),
            "mixed set"
        );
        assert_eq!(side["seed"], serde_json::json!(k as u64 + 1), "mixed set");
        assert!(!out.join(".wearsim.lock").exists());
    }
    println!("{refused} of 8 runs refused");
}

/// Issue 11 (3, 4, 7): a rerun into a complete set removes its completion marker before
/// touching the data; a corrupt checkpoint is refused (exit 2, naming the file) and
/// never continued; `--stop-after` must be a positive number of seconds.
#[test]
fn stale_markers_corrupt_checkpoints_and_bad_stops() {
    let dir = tempfile::tempdir().unwrap();
    let config = write_config(dir.path());
    let out = dir.path().join("set");
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join("life-summary.json"), "{\"complete\": true}").unwrap();
    std::fs::write(out.join("life-dense.f32"), [0u8; 4000]).unwrap();
    ok(&run(life_command(
        &config,
        &out,
        1,
        false,
        &["--stop-after", "0.5"],
    )));
    assert!(
        !out.join("life-summary.json").exists(),
        "stale completion marker kept"
    );
    let manifest: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("life-dense.json")).unwrap()).unwrap();
    assert_eq!(manifest["complete"], false);

    // Zero the encoded state (the checkpoint's tail, before the checksum).
    let ckpt = out.join("life-dense.ckpt");
    let mut bytes = std::fs::read(&ckpt).unwrap();
    let n = bytes.len();
    bytes[n - 800..n - 8].fill(0);
    std::fs::write(&ckpt, &bytes).unwrap();
    let data_before = std::fs::read(out.join("life-dense.f32")).unwrap();
    let o = run(life_command(&config, &out, 1, false, &[]));
    assert_eq!(o.status.code(), Some(2));
    let msg = String::from_utf8_lossy(&o.stderr);
    assert!(
        msg.contains("life-dense.ckpt") && msg.contains("corrupt"),
        "{msg}"
    );
    assert_eq!(
        std::fs::read(out.join("life-dense.f32")).unwrap(),
        data_before
    );
    assert!(!out.join("life-summary.json").exists());

    for bad in ["nan", "-1", "0", "inf"] {
        let o = run(life_command(
            &config,
            &dir.path().join("bad"),
            1,
            false,
            &["--stop-after", bad],
        ));
        assert_eq!(o.status.code(), Some(2), "--stop-after {bad}");
        let msg = String::from_utf8_lossy(&o.stderr);
        assert!(msg.contains("stop_after"), "--stop-after {bad}: {msg}");
    }
}
