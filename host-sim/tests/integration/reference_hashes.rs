//! Bit-identity of reference runs across refactors.
//!
//! Each case runs the `wearsim` program on a fixed scenario and hashes the numbers it
//! writes (every numeric CSV field as the bits of its `f64`, FNV-1a 64). The expected
//! hashes were recorded before the architecture refactor of issue 10 (commit `39d0732`
//! plus this test); a refactor that is meant to leave the physics alone must leave them
//! unchanged. A change of physics that moves a hash must say so in its commit and record
//! the new value here, with the reason.
//!
//! Set `WEARSIM_PRINT_HASHES=1` to print the computed hashes instead of failing on the
//! first mismatch (to record new values after a deliberate change of physics).

use std::path::Path;
use std::process::Command;

const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
const FNV_PRIME: u64 = 0x0000_0100_0000_01b3;

fn fnv(mut h: u64, bytes: &[u8]) -> u64 {
    for b in bytes {
        h ^= u64::from(*b);
        h = h.wrapping_mul(FNV_PRIME);
    }
    h
}

/// Hash of every numeric field (parsed as `f64`, hashed by its bits) of the named columns
/// of a CSV file, row by row; a column missing from the header fails the test.
fn hash_csv(path: &Path, columns: &[&str]) -> u64 {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    let header: Vec<&str> = lines
        .next()
        .expect("header")
        .split(',')
        .map(str::trim)
        .collect();
    let idx: Vec<usize> = columns
        .iter()
        .map(|c| {
            header
                .iter()
                .position(|h| h == c)
                .unwrap_or_else(|| panic!("{}: no column {c} in {header:?}", path.display()))
        })
        .collect();
    let mut h = FNV_OFFSET;
    let mut rows = 0usize;
    for line in lines.filter(|l| !l.trim().is_empty()) {
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        for &i in &idx {
            let f = fields[i];
            match f.parse::<f64>() {
                Ok(v) => h = fnv(h, &v.to_bits().to_le_bytes()),
                Err(_) => h = fnv(h, f.as_bytes()),
            }
        }
        rows += 1;
    }
    assert!(rows > 0, "{}: no rows", path.display());
    fnv(h, &(rows as u64).to_le_bytes())
}

fn wearsim(args: &[&str], dir: &Path) {
    let out = Command::new(env!("CARGO_BIN_EXE_wearsim"))
        .args(args)
        .arg("--out")
        .arg(dir)
        .output()
        .expect("run wearsim");
    assert!(
        out.status.success(),
        "wearsim {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

fn check(name: &str, got: u64, want: u64, failures: &mut Vec<String>) {
    if std::env::var_os("WEARSIM_PRINT_HASHES").is_some() {
        println!("{name}: 0x{got:016x}");
    }
    if got != want {
        failures.push(format!("{name}: got 0x{got:016x}, recorded 0x{want:016x}"));
    }
}

fn simulate_case(name: &str, args: &[&str], want: u64, failures: &mut Vec<String>) {
    let dir = tempfile::tempdir().unwrap();
    let mut a = vec!["simulate"];
    a.extend_from_slice(args);
    wearsim(&a, dir.path());
    let h = hash_csv(&dir.path().join("simulate.csv"), &["time_s", "accel_m_s2"]);
    check(name, h, want, failures);
}

/// Every preset, inner-race and ball defects, every effect on at once: the samples written
/// by `wearsim simulate`, bit for bit.
#[test]
fn simulated_samples_match_the_recorded_hashes() {
    let dir = tempfile::tempdir().unwrap();
    let inner = dir.path().join("inner.toml");
    std::fs::write(
        &inner,
        "preset = \"cwru-6205-de\"\nduration = 0.2\n[defect]\nlocation = \"inner\"\ntopography = \"mild-defect\"\n",
    )
    .unwrap();
    let ball = dir.path().join("ball.toml");
    std::fs::write(
        &ball,
        "preset = \"cwru-6205-de\"\nduration = 0.2\n[defect]\nlocation = \"ball\"\nelement = 2\ntopography = \"mild-defect\"\n",
    )
    .unwrap();
    let inner = inner.to_str().unwrap();
    let ball = ball.to_str().unwrap();
    let mut failures = Vec::new();
    for (name, args, want) in [
        (
            "thesis-61810",
            &["--duration", "0.2"][..],
            0x75c3eabf556a9186u64,
        ),
        (
            "thesis-as-printed",
            &["--preset", "thesis-as-printed", "--duration", "0.1"][..],
            0x6adb97fea446d834,
        ),
        (
            "cwru-6205-de",
            &["--preset", "cwru-6205-de", "--duration", "0.2"][..],
            0xca972d23fac30bf0,
        ),
        (
            "cwru-6203-fe",
            &["--preset", "cwru-6203-fe", "--duration", "0.2"][..],
            0x382d30e6640501f6,
        ),
        // The line contact's δ^{1/9} became one ninth root (≤ 2 ulp from cube root of cube
        // root, commit f7263a9): only the roller preset moves.
        (
            "ims-za2115",
            &["--preset", "ims-za2115", "--duration", "0.1"][..],
            0xe3b151257ad0e28f,
        ),
        ("inner", &["--config", inner][..], 0x9a202f77812ceae0),
        (
            "ball",
            &[
                "--config",
                ball,
                "--effect",
                "load-zone:depth=0.7,epsilon=0.4",
            ][..],
            0x647c90535fbd0425,
        ),
        (
            "all-effects",
            &[
                "--preset",
                "cwru-6205-de",
                "--duration",
                "0.2",
                "--seed",
                "7",
                "--effect",
                "slip:fraction=0.02",
                "--effect",
                "load-zone:depth=0.8,epsilon=0.4,preload=0.5",
                "--effect",
                "transfer-path:f1=3200,zeta1=0.03,gain1=4,f2=4500,gain2=1,path_gain=0.5",
                "--effect",
                "speed-fluctuation:amplitude=0.01,freq_hz=3,jitter=0.005",
                "--effect",
                "sensor:noise=0.05,corner_hz=5000,hum=0.02",
                "--effect",
                "shaft-harmonics:f2=20,f3=5",
                "--effect",
                "running-in:factor=3,decay_revs=1000,summits=2,summit_height=0.5",
                "--effect",
                "roughness:scale=2",
                "--effect",
                "edge-shape:length_scale=0.7,asperity_scale=1.3",
            ][..],
            0x1872218f3c48dfa7,
        ),
    ] {
        simulate_case(name, args, want, &mut failures);
    }
    assert!(
        failures.is_empty(),
        "hashes moved:\n{}",
        failures.join("\n")
    );
}

/// A whole life in snapshot mode: the features of every snapshot and the event log.
#[test]
fn life_matches_the_recorded_hashes() {
    let mut failures = Vec::new();
    for (seed, want_features, want_events) in [
        // Stop 52: a fresh breakout edge's loads are re-measured within its shakedown
        // (`Life::representative_revs`), which changes every window after the first spall.
        ("3", 0x800567bf9ea4ba40u64, 0x8de1094bc7074ced),
        ("11", 0xf67cdfea57a92126, 0xa4a754bc631a9f20),
    ] {
        let dir = tempfile::tempdir().unwrap();
        wearsim(&["life", "--seed", seed, "--json"], dir.path());
        for (file, what, want) in [
            ("life-features.csv", "features", want_features),
            ("life-events.csv", "events", want_events),
        ] {
            let path = dir.path().join(file);
            let text = std::fs::read_to_string(&path).unwrap();
            let cols: Vec<&str> = text
                .lines()
                .next()
                .unwrap()
                .split(',')
                .map(str::trim)
                .collect();
            let name = format!("life {seed} {what}");
            check(&name, hash_csv(&path, &cols), want, &mut failures);
        }
    }
    assert!(
        failures.is_empty(),
        "hashes moved:\n{}",
        failures.join("\n")
    );
}
