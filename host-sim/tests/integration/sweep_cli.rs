//! `wearsim sweep`: a labelled data set is deterministic (same spec, same bytes, whatever
//! the thread count or `--shard I/N` split), regenerable record by record, resumable, and
//! bad specs exit 2 naming the field with nothing presented as complete.

use std::path::Path;
use std::process::{Command, Output};
use wearsim_host::sweep::{record, shard, SweepSpec};

const SPEC: &str = r#"
seed = 5
records = 10
records_per_shard = 3
duration = 0.05
fs = 12000.0

[grid]
preset = ["cwru-6205-de"]
rpm = [1797.0]
fault = ["healthy", "outer", "inner"]
stage = ["large-defect"]

[[effect]]
name = "sensor"
probability = 0.5
params = { noise = { uniform = [0.01, 0.2] } }
"#;

fn wearsim(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wearsim"))
        .args(args)
        .output()
        .expect("run wearsim")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn sweep(spec: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut a = vec![
        "sweep",
        spec.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--json",
    ];
    a.extend_from_slice(extra);
    wearsim(&a)
}

/// Every file of the data set (relative path, bytes), sorted.
fn files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v = vec![];
    for sub in ["", "shards"] {
        for e in std::fs::read_dir(dir.join(sub)).unwrap() {
            let p = e.unwrap().path();
            if p.is_file() {
                let name = format!("{sub}/{}", p.file_name().unwrap().to_string_lossy());
                v.push((name, std::fs::read(&p).unwrap()));
            }
        }
    }
    v.sort();
    v
}

fn report(o: &Output) -> serde_json::Value {
    assert!(o.status.success(), "{}", stderr(o));
    serde_json::from_slice(&o.stdout).unwrap()
}

#[test]
fn same_spec_same_bytes_any_threads_or_split_and_records_regenerate_alone() {
    let tmp = tempfile::tempdir().unwrap();
    let spec_path = tmp.path().join("spec.toml");
    std::fs::write(&spec_path, SPEC).unwrap();
    let a = tmp.path().join("a");
    let b = tmp.path().join("b");
    let r = report(&sweep(&spec_path, &a, &["--threads", "2"]));
    assert_eq!(r["complete"], true);
    assert_eq!(r["records_generated"], 10);
    // Split in two "array tasks": the first part alone is not complete.
    let r1 = report(&sweep(
        &spec_path,
        &b,
        &["--shard", "0/2", "--threads", "1"],
    ));
    assert_eq!(r1["complete"], false);
    assert!(!b.join("manifest.json").exists() && !b.join("index.parquet").exists());
    let r2 = report(&sweep(
        &spec_path,
        &b,
        &["--shard", "1/2", "--threads", "1"],
    ));
    assert_eq!(r2["complete"], true);
    let fa = files(&a);
    assert_eq!(fa, files(&b), "threads=2 and --shard 0/2 + 1/2 differ");
    // 4 shards: npy + marker each, plus sweep.json, index.parquet, manifest.json.
    assert_eq!(fa.len(), 11);
    let index = std::fs::read(a.join("index.parquet")).unwrap();
    assert_eq!(&index[..4], b"PAR1");
    // Record 7 (shard 2, row 1) regenerated alone matches its row, byte for byte.
    let spec = SweepSpec::parse(SPEC, "test").unwrap();
    let cells = record::cells(&spec);
    let x = shard::simulate_record(&spec, &cells, 7).unwrap();
    let npy = std::fs::read(a.join("shards").join(shard::npy_name(2))).unwrap();
    let n = spec.samples();
    assert_eq!(n, 600);
    let data = &npy[npy.len() - 3 * n * 4..];
    let row: Vec<f32> = data[n * 4..2 * n * 4]
        .chunks(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    assert_eq!(row, x);
    // Labels cycle through the grid: a defect makes a record impulsive, healthy is not.
    let rms =
        |v: &[f32]| (v.iter().map(|a| (*a as f64).powi(2)).sum::<f64>() / v.len() as f64).sqrt();
    let healthy = shard::simulate_record(&spec, &cells, 0).unwrap();
    let outer = shard::simulate_record(&spec, &cells, 1).unwrap();
    assert_eq!(record::record(&spec, &cells, 1).cell.fault, "outer");
    assert!(
        rms(&outer) > 2.0 * rms(&healthy),
        "{} vs {}",
        rms(&outer),
        rms(&healthy)
    );
}

#[test]
fn resume_regenerates_only_missing_shards() {
    let tmp = tempfile::tempdir().unwrap();
    let spec_path = tmp.path().join("spec.toml");
    std::fs::write(&spec_path, SPEC).unwrap();
    let a = tmp.path().join("a");
    report(&sweep(&spec_path, &a, &[]));
    let before = files(&a);
    // An interrupted run: shard 1's signals half-written, its marker never written.
    std::fs::remove_file(a.join("shards").join(shard::done_name(1))).unwrap();
    std::fs::remove_file(a.join("manifest.json")).unwrap();
    std::fs::write(a.join("shards").join(shard::npy_name(1)), b"half").unwrap();
    let r = report(&sweep(&spec_path, &a, &[]));
    assert_eq!(r["shards_written"], 1);
    assert_eq!(r["shards_skipped"], 3);
    assert_eq!(r["records_generated"], 3);
    assert_eq!(files(&a), before);
    // Nothing left to do.
    let r = report(&sweep(&spec_path, &a, &[]));
    assert_eq!(r["shards_written"], 0);
}

fn bad(spec: &str, expect: &[&str]) {
    let tmp = tempfile::tempdir().unwrap();
    let spec_path = tmp.path().join("spec.toml");
    std::fs::write(&spec_path, spec).unwrap();
    let out = tmp.path().join("out");
    let o = sweep(&spec_path, &out, &[]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    for e in expect {
        assert!(stderr(&o).contains(e), "`{e}` not in: {}", stderr(&o));
    }
    assert!(!out.exists(), "a bad spec created the output directory");
}

#[test]
fn bad_specs_exit_2_naming_the_field() {
    bad(&SPEC.replace("seed = 5", "seed = 5\nsead = 1"), &["sead"]);
    bad(
        &SPEC.replace("rpm = [1797.0]", "rpm = []"),
        &["grid.rpm", "empty"],
    );
    bad(
        &SPEC.replace("[0.01, 0.2]", "[0.01, 200.0]"),
        &["effect[0].params.noise", "[0, 100]"],
    );
    bad(
        &SPEC.replace("name = \"sensor\"", "name = \"sensr\""),
        &["effect[0].name", "sensr"],
    );
    bad(
        &SPEC.replace("\"inner\"", "\"cage\""),
        &["grid.fault", "cage"],
    );
    bad(
        &SPEC.replace("records = 10", "records = 0"),
        &["records", "1..="],
    );
    bad(&SPEC.replace("rpm = [1797.0]", "rpm = [-5.0]"), &["rpm"]);
    // A record the core refuses is named by its grid cell in the spec's own terms.
    bad(
        &SPEC.replace("duration = 0.05", "duration = -1.0"),
        &["record 0 (grid cell preset = \"cwru-6205-de\", rpm = 1797"],
    );
    // Repeats: an effect listed twice (two parameter sets for one effect, and duplicate
    // index columns) and a grid value listed twice.
    bad(
        &format!("{SPEC}\n[[effect]]\nname = \"sensor\"\nparams = {{ noise = 5.0 }}\n"),
        &["effect[1].name", "repeats `effect[0]`"],
    );
    // A NaN end is named as such, not as an order (it was told "lo must not exceed hi").
    bad(
        &SPEC.replace("[0.01, 0.2]", "[nan, 0.2]"),
        &[
            "effect[0].params.noise.uniform",
            "both ends must be numbers",
            "[0, 100]",
        ],
    );
    bad(
        &SPEC.replace("[0.01, 0.2]", "[0.01, 0.1, 0.2]"),
        &["noise", "{ uniform = [lo, hi] } (two numbers)"],
    );
    bad(
        &SPEC.replace("rpm = [1797.0]", "rpm = [1797.0, 1797.0]"),
        &["grid.rpm", "1797 twice"],
    );
    bad(
        &SPEC.replace("\"inner\"]", "\"inner\", \"outer\"]"),
        &["grid.fault", "outer twice"],
    );
    // A distribution inside the registry's bounds whose top the sample rate refuses (a
    // transfer-path mode above fs/2.5 = 4800 Hz at 12 kHz): refused before anything is
    // written, not at the first record that draws it (the probe's sweep wrote 12 shards
    // and stopped at record 50, and a resume stopped there again).
    bad(
        &format!(
            "{SPEC}\n[[effect]]\nname = \"transfer-path\"\nparams = {{ f1 = {{ uniform = [1000.0, 4850.0] }} }}\n"
        ),
        &["effect[1].params.f1 (transfer-path)", "reaches 4850", "4800"],
    );
    // Each parameter is checked with its effect alone on: a sensor corner above fs/2 is
    // named as itself, not as the transfer-path mode checked before it (the probe's spec,
    // and this one, blamed `effect[0].params.f1` for the drawn corner of record 0).
    bad(
        &SPEC.replace("seed = 5", "seed = 7").replace(
            "name = \"sensor\"\nprobability = 0.5\nparams = { noise = { uniform = [0.01, 0.2] } }",
            "name = \"transfer-path\"\nparams = { f1 = { uniform = [500.0, 4000.0] } }\n[[effect]]\nname = \"sensor\"\nparams = { corner_hz = { uniform = [1000.0, 20000.0] } }",
        ),
        &["effect[1].params.corner_hz (sensor)", "reaches 20000"],
    );
    // The same through a choice's largest value.
    bad(
        &format!(
            "{SPEC}\n[[effect]]\nname = \"transfer-path\"\nparams = {{ f1 = {{ choice = [4900.0, 1000.0] }} }}\n"
        ),
        &["effect[1].params.f1 (transfer-path)", "reaches 4900"],
    );
}

#[test]
fn output_dir_of_another_sweep_or_foreign_files_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let spec_path = tmp.path().join("spec.toml");
    std::fs::write(&spec_path, SPEC.replace("records = 10", "records = 2")).unwrap();
    let a = tmp.path().join("a");
    report(&sweep(&spec_path, &a, &[]));
    let other = tmp.path().join("other.toml");
    std::fs::write(
        &other,
        SPEC.replace("records = 10", "records = 2")
            .replace("seed = 5", "seed = 6"),
    )
    .unwrap();
    let o = sweep(&other, &a, &[]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("another sweep"), "{}", stderr(&o));
    let foreign = tmp.path().join("foreign");
    std::fs::create_dir_all(&foreign).unwrap();
    std::fs::write(foreign.join("x.csv"), "1\n").unwrap();
    let o = sweep(&spec_path, &foreign, &[]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("not empty"), "{}", stderr(&o));
    let o = sweep(&spec_path, &a, &["--shard", "2/2"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--shard"), "{}", stderr(&o));
}
