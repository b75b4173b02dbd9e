//! `wearsim analyze` on the layouts of other rigs (MFPT struct, Paderborn struct) and any
//! bearing: metadata stored in the file is used and reported with its source; bad input
//! (contradicting sample rate, impossible geometry, a record too short to resolve the defect
//! frequencies, no numeric array) exits 2 naming the field and prints no result.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use wearsim_host::io::mat::{self, fixture};

fn wearsim(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wearsim"))
        .args(args)
        .output()
        .expect("run wearsim")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn assert_input_error(o: &Output, needles: &[&str]) {
    assert_eq!(o.status.code(), Some(2), "stderr: {}", stderr(o));
    assert!(o.stdout.is_empty(), "nothing may be printed on stdout");
    let e = stderr(o);
    assert!(!e.contains("panicked"), "{e}");
    for n in needles {
        assert!(e.contains(n), "message lacks {n:?}: {e}");
    }
}

/// `secs` of decaying 4 kHz bursts at `rate` Hz in noise, sampled at `fs`.
fn impulses(fs: f64, secs: f64, rate: f64) -> Vec<f64> {
    let n = (fs * secs) as usize;
    let mut s: u64 = 12345;
    let mut x: Vec<f64> = (0..n)
        .map(|_| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((s >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 0.4
        })
        .collect();
    let w = 2.0 * std::f64::consts::PI * 4000.0;
    let mut t = 0.005;
    while t < secs {
        let i0 = (t * fs).ceil() as usize;
        for (i, v) in x
            .iter_mut()
            .enumerate()
            .skip(i0)
            .take((0.004 * fs) as usize)
        {
            let dt = i as f64 / fs - t;
            *v += (-0.05 * w * dt).exp() * (w * dt).sin();
        }
        t += 1.0 / rate;
    }
    x
}

fn mfpt_file(dir: &Path, secs: f64) -> PathBuf {
    let fs = 48_828.0;
    let x = impulses(fs, secs, 81.125);
    let p = dir.join("OuterRaceFault_vload_1.mat");
    std::fs::write(
        &p,
        mat::mat5_compress(&fixture::mfpt_fixture(&x, fs, 25.0, 50.0)),
    )
    .unwrap();
    p
}

fn json_of(o: &Output) -> serde_json::Value {
    assert!(o.status.success(), "stderr: {}", stderr(o));
    serde_json::from_slice(&o.stdout).expect("JSON on stdout")
}

#[test]
fn mfpt_struct_analyses_with_its_own_metadata_and_catalogue_bearing() {
    let dir = tempfile::tempdir().unwrap();
    let p = mfpt_file(dir.path(), 2.0);
    let v = json_of(&wearsim(&["analyze", &p.to_string_lossy(), "--json"]));
    assert_eq!(v["fs"], 48_828.0);
    assert_eq!(v["fs_source"], "file:bearing.sr");
    assert_eq!(v["rpm"], 1500.0);
    assert_eq!(v["input"]["rpm_source"], "file:bearing.rate");
    assert_eq!(v["input"]["layout"], "mfpt");
    assert_eq!(v["input"]["load"], 50.0);
    assert_eq!(v["bearing"], "mfpt-nice");
    // BPFO of the NICE bearing (8 x 0.235 in on 1.245 in) at 25 Hz: 4 (1 - 0.1888) 25 = 81.12 Hz.
    let bpfo = v["kinematics"]["bpfo"].as_f64().unwrap();
    assert!((bpfo - 81.124).abs() < 0.01, "{bpfo}");
    assert!(v["diagnosis"]["family"].is_string());
    // The same geometry given by hand gives the same frequencies.
    let g = "elements=8,ball=5.969,pitch=31.623,angle=0";
    let w = json_of(&wearsim(&[
        "analyze",
        &p.to_string_lossy(),
        "--json",
        "--bearing-geometry",
        g,
    ]));
    assert_eq!(w["bearing"], "custom");
    assert_eq!(w["bearing_source"], "argument");
    assert!((w["kinematics"]["bpfo"].as_f64().unwrap() - bpfo).abs() < 1e-3);
}

#[test]
fn paderborn_struct_channel_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let x = impulses(64_000.0, 1.0, 76.0);
    let b = fixture::paderborn_fixture(
        "N15_M07_F10_KA01_1",
        &[("force", &[1.0; 10]), ("vibration_1", &x)],
    );
    let p = dir.path().join("N15_M07_F10_KA01_1.mat");
    std::fs::write(&p, mat::mat5_compress(&b)).unwrap();
    let v = json_of(&wearsim(&["analyze", &p.to_string_lossy(), "--json"]));
    assert_eq!(
        (v["fs"].as_f64(), v["rpm"].as_f64()),
        (Some(64_000.0), Some(1500.0))
    );
    assert_eq!(v["fs_source"], "layout:paderborn");
    assert_eq!(v["channel"], "vibration_1");
    assert_eq!(v["bearing"], "paderborn-6203");
    // A wrong channel lists every numeric array with its shape.
    assert_input_error(
        &wearsim(&["analyze", &p.to_string_lossy(), "--channel", "DE"]),
        &[
            "\"DE\"",
            "N15_M07_F10_KA01_1.Y(2).Data [1x64000] single",
            "Y(1).Data [1x10]",
        ],
    );
}

#[test]
fn bad_input_exits_2_naming_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let p = mfpt_file(dir.path(), 2.0);
    let f = p.to_string_lossy().to_string();
    // A --fs that contradicts the rate stored in the file.
    assert_input_error(
        &wearsim(&["analyze", &f, "--fs", "97656"]),
        &["field fs", "file:bearing.sr"],
    );
    // Impossible geometry.
    for (g, field) in [
        (
            "elements=8,ball=6,pitch=5,angle=0",
            "bearing-geometry.pitch",
        ),
        (
            "elements=8,ball=6,pitch=30,angle=95",
            "bearing-geometry.angle",
        ),
        ("elements=2,ball=6,pitch=30", "bearing-geometry.elements"),
    ] {
        assert_input_error(
            &wearsim(&["analyze", &f, "--bearing-geometry", g]),
            &[field],
        );
    }
    // A record too short for its rate to separate the fault families.
    let short = mfpt_file(&dir.path().join(""), 0.02);
    assert_input_error(
        &wearsim(&["analyze", &short.to_string_lossy()]),
        &["record length"],
    );
    // A sample rate too low for the defect frequencies.
    let low = dir.path().join("low.mat");
    let x = impulses(48_828.0, 2.0, 81.125);
    let b = fixture::mfpt_fixture(&x[..2000], 500.0, 25.0, 0.0);
    std::fs::write(&low, b).unwrap();
    assert_input_error(
        &wearsim(&["analyze", &low.to_string_lossy()]),
        &["field fs"],
    );
    // No numeric array at all.
    let none = dir.path().join("none.mat");
    std::fs::write(
        &none,
        mat::mat5_tree_bytes(&[("note", mat::FixtureValue::Char("x".into()))]),
    )
    .unwrap();
    assert_input_error(
        &wearsim(&["analyze", &none.to_string_lossy()]),
        &["no numeric array"],
    );
}

#[test]
fn many_files_one_table_errors_are_rows() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path().join("in");
    std::fs::create_dir_all(d.join("sub")).unwrap();
    let a = mfpt_file(&d, 1.0);
    let b = mfpt_file(&d.join("sub"), 1.0);
    std::fs::write(d.join("broken.mat"), b"MATLAB 5.0 MAT-file but cut").unwrap();
    std::fs::write(d.join("notes.json"), b"{}").unwrap();
    let out = dir.path().join("table.csv");
    let o = wearsim(&[
        "analyze",
        &d.to_string_lossy(),
        "--out",
        &out.to_string_lossy(),
    ]);
    assert_eq!(
        o.status.code(),
        Some(2),
        "one unreadable file: exit 2: {}",
        stderr(&o)
    );
    assert!(stderr(&o).contains("1 of 3 files"), "{}", stderr(&o));
    let t = std::fs::read_to_string(&out).unwrap();
    let lines: Vec<&str> = t.lines().collect();
    assert_eq!(lines.len(), 4, "{t}");
    assert!(lines[0].starts_with("file,status,family,confidence"));
    let broken: Vec<&&str> = lines.iter().filter(|l| l.contains("broken.mat")).collect();
    assert_eq!(broken.len(), 1, "{t}");
    assert!(
        broken[0].contains(",error,") && broken[0].contains("truncated"),
        "{t}"
    );
    let ok = lines
        .iter()
        .filter(|l| l.contains(",ok,") && l.contains("file:bearing.sr"));
    assert_eq!(ok.count(), 2, "{t}");
    // Two files given, all readable: exit 0, JSON rows in order.
    let o = wearsim(&[
        "analyze",
        &a.to_string_lossy(),
        &b.to_string_lossy(),
        "--format",
        "json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v.as_array().unwrap().len(), 2);
    assert_eq!(v[0]["status"], "ok");
    assert!(v[0]["family"].is_string());
    // Markdown to stdout.
    let o = wearsim(&["analyze", &a.to_string_lossy(), "--format", "md"]);
    let md = String::from_utf8_lossy(&o.stdout);
    assert!(md.starts_with("| file | status | family |"));
    // A GFM table: the delimiter row and every data row have the header's cell count.
    let cells = |l: &str| l.trim().trim_matches('|').split('|').count();
    let rows: Vec<&str> = md.lines().collect();
    assert!(rows.len() >= 3, "{md}");
    assert!(
        rows[1]
            .split('|')
            .all(|c| c.is_empty() || c.trim() == "---"),
        "{md}"
    );
    for r in &rows[1..] {
        assert_eq!(cells(r), cells(rows[0]), "{r}");
    }
    assert_input_error(
        &wearsim(&["analyze", &a.to_string_lossy(), "--format", "xls"]),
        &["--format"],
    );
}

/// `--fs` against a rate a sidecar or the file states (a CSV's time column, a WAV header)
/// is held to the rule of a rate stored in a MAT file: agreeing within 0.1 % it is used,
/// contradicting it is refused naming the field and both rates (it once silently won);
/// a file that states no rate takes it.
#[test]
fn an_fs_contradicting_a_sidecar_or_header_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("sim");
    let o = wearsim(&[
        "simulate",
        "--preset",
        "cwru-6205-de",
        "--fs",
        "25600",
        "--duration",
        "2",
        "--out",
        &out.to_string_lossy(),
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = out.join("simulate.csv").to_string_lossy().into_owned();
    let wav = out.join("simulate.wav").to_string_lossy().into_owned();
    for (f, src) in [(&csv, "simulate.json"), (&wav, "simulate.json")] {
        assert_input_error(
            &wearsim(&["analyze", f, "--fs", "48828"]),
            &["field fs", "48828", "25600", src],
        );
        let ok = wearsim(&["analyze", f, "--fs", "25600", "--json"]);
        assert!(ok.status.success(), "{f}: {}", stderr(&ok));
    }
    // Without the sidecar: the CSV's time column and the WAV header still state the rate.
    let bare = dir.path().join("bare");
    std::fs::create_dir(&bare).unwrap();
    let text = std::fs::read_to_string(&csv).unwrap();
    let timed = bare.join("timed.csv");
    std::fs::write(&timed, &text).unwrap();
    let bare_wav = bare.join("rec.wav");
    std::fs::copy(&wav, &bare_wav).unwrap();
    for (f, src) in [(&timed, "time column"), (&bare_wav, "WAV header")] {
        assert_input_error(
            &wearsim(&[
                "analyze",
                &f.to_string_lossy(),
                "--fs",
                "48828",
                "--bearing",
                "cwru-6205-de",
                "--rpm",
                "1797",
            ]),
            &["field fs", "48828", "25600", src],
        );
    }
    // A file that states no rate: --fs is the rate.
    let plain = bare.join("plain.csv");
    let column: String = text
        .lines()
        .skip(1)
        .map(|l| format!("{}\n", l.split(',').nth(1).unwrap_or("")))
        .collect();
    std::fs::write(&plain, format!("x\n{column}")).unwrap();
    let ok = wearsim(&[
        "analyze",
        &plain.to_string_lossy(),
        "--fs",
        "48828",
        "--bearing",
        "cwru-6205-de",
        "--rpm",
        "1797",
        "--json",
    ]);
    assert!(ok.status.success(), "{}", stderr(&ok));
    let v: serde_json::Value = serde_json::from_slice(&ok.stdout).unwrap();
    assert_eq!(v["fs"].as_f64(), Some(48828.0));
    assert_eq!(v["fs_source"], "argument");
}
