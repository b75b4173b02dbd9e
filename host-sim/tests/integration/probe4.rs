//! Gaps a probe found and left open (continued from `probe3.rs`): a column or row of a 2-D
//! MAT or NPY array chosen with `--channel NAME(:,K)`, an NPY array whose shape does not say
//! which axis holds the samples, CSV time columns in other units than seconds, and where a
//! rate or speed came from (`fs_detail`, `rpm_detail`), a life whose load moves the resonance
//! past Nyquist, a load that leaves every element unloaded; one test per gap, each named after
//! what must hold.

use crate::support::{analyze_6205, mat, noise, npy, refused, s, wearsim};
use wearsim_host::io::mat::fixture::FixtureValue;

/// A MAT double array of `dims` holding `data` (column by column, as MATLAB stores it).
fn doubles(dims: &[i32], data: &[f64]) -> FixtureValue {
    FixtureValue::Typed {
        class: 6,
        mi: 9,
        dims: dims.to_vec(),
        bytes: data.iter().flat_map(|v| v.to_le_bytes()).collect(),
        logical: false,
    }
}

/// `--channel` could not take one column of a MAT matrix (the message said to re-save the
/// file). `data(:,2)` is column 2, `rig.acc(2,:)` row 2 of a struct field, both the same
/// samples as the vector `ch2` holding them; an index out of range and a malformed
/// selector are refused naming the array, its shape and the range.
#[test]
fn a_mat_matrix_column_or_row_is_chosen_with_a_selector() {
    let dir = tempfile::tempdir().expect("tempdir");
    let x = noise(2 * 4096);
    let ch2 = &x[4096..];
    // rig.acc is 2 × 4096 with row 2 = ch2: column-major, rows interleaved.
    let rows: Vec<f64> = (0..4096).flat_map(|j| [x[j], ch2[j]]).collect();
    let p = mat(
        dir.path(),
        "two.mat",
        &[
            ("data", doubles(&[4096, 2], &x)),
            ("ch2", FixtureValue::Doubles(ch2.to_vec())),
            (
                "rig",
                FixtureValue::Struct {
                    dims: vec![1, 1],
                    fields: vec!["acc".into()],
                    elems: vec![vec![doubles(&[2, 4096], &rows)]],
                },
            ),
            ("fs", FixtureValue::Doubles(vec![25_600.0])),
        ],
    );
    let want = analyze_6205(&p, &["--channel", "ch2"]);
    for sel in ["data(:,2)", "rig.acc(2,:)"] {
        let v = analyze_6205(&p, &["--channel", sel]);
        assert_eq!(v["channel"], sel, "{v}");
        assert_eq!(v["input"]["variable"], sel, "{v}");
        assert_eq!(v["samples"], 4096);
        assert_eq!(v["stats"], want["stats"], "{sel}");
        assert_eq!(v["diagnosis"], want["diagnosis"], "{sel}");
    }
    let run = |sel: &str| {
        wearsim(&[
            "analyze",
            s(&p),
            "--channel",
            sel,
            "--rpm",
            "1797",
            "--bearing",
            "cwru-6205-de",
        ])
    };
    refused(
        &run("data(:,3)"),
        &[
            "--channel: column 3 is out of range 1..=2",
            "\"data\" is a [4096, 2] array",
        ],
    );
    refused(
        &run("rig.acc(3,:)"),
        &["row 3 is out of range 1..=2", "\"rig.acc\" is a [2, 4096]"],
    );
    refused(
        &run("data(2,2)"),
        &[
            "malformed selector (2,2)",
            "[4096, 2]",
            "'data(:,K)' (K = 1..=2)",
            "'data(K,:)' (K = 1..=4096)",
        ],
    );
    refused(
        &run("ch2(:,2)"),
        &["column 2 is out of range 1..=1", "\"ch2\""],
    );
}

/// A square 2-D NPY array was read along one axis silently (its columns, whichever the
/// user meant). It is refused naming the shape and the ways to choose; `(:,K)` and `(K,:)`
/// pick a column or a row of the array as stored, the same samples as a 1-D file of them.
/// A long array of a few channels, either way round, is still read by its shape.
#[test]
fn an_npy_array_whose_shape_does_not_tell_its_axes_is_refused_until_chosen() {
    let dir = tempfile::tempdir().expect("tempdir");
    let n = 1024;
    let a = noise(n * n);
    let sq = npy(dir.path(), "square.npy", &[n as u64, n as u64], &a);
    let col2: Vec<f64> = (0..n).map(|i| a[i * n + 1]).collect();
    let row3 = a[2 * n..3 * n].to_vec();
    let one = |name: &str, d: &[f64]| npy(dir.path(), name, &[n as u64], d);
    let (c, r) = (one("col2.npy", &col2), one("row3.npy", &row3));
    let fs = ["--fs", "4096"];
    for ch in [None, Some("1")] {
        let mut args = vec!["analyze", s(&sq), "--fs", "4096", "--rpm", "1797"];
        args.extend(ch.map(|c| ["--channel", c]).into_iter().flatten());
        refused(
            &wearsim(&args),
            &[
                "shape [1024, 1024]",
                "it is square",
                "--channel '(:,K)' (K = 1..=1024)",
                "--channel '(K,:)' (K = 1..=1024)",
                "\"columns\"",
            ],
        );
    }
    for (sel, same) in [("(:,2)", &c), ("(3,:)", &r)] {
        let v = analyze_6205(&sq, &[&fs[..], &["--channel", sel]].concat());
        let w = analyze_6205(same, &fs);
        assert_eq!(v["samples"], n, "{v}");
        assert_eq!(v["stats"], w["stats"], "{sel}");
    }
    refused(
        &wearsim(&["analyze", s(&sq), "--fs", "4096", "--channel", "(:,1025)"]),
        &["column 1025 is out of range 1..=1024", "[1024, 1024]"],
    );
    // Both axes long.
    let wide = npy(dir.path(), "wide.npy", &[1024, 256], &a[..1024 * 256]);
    refused(
        &wearsim(&["analyze", s(&wide), "--fs", "4096", "--rpm", "1797"]),
        &["shape [1024, 256]", "both axes are long"],
    );
    // A few channels, either way round: read by the shape, as before.
    let x = noise(2 * 4096);
    let t: Vec<f64> = (0..4096).flat_map(|i| [x[i], x[4096 + i]]).collect();
    let tall = npy(dir.path(), "tall.npy", &[4096, 2], &t);
    let flat = npy(dir.path(), "flat.npy", &[2, 4096], &x);
    let v = analyze_6205(&tall, &["--fs", "12000", "--channel", "1"]);
    let w = analyze_6205(&flat, &["--fs", "12000", "--channel", "1"]);
    assert_eq!(v["samples"], 4096);
    assert_eq!(v["stats"], w["stats"]);
}

/// A time column in milliseconds or microseconds (`Time (ms)`, `t_ms`, `time [us]`,
/// `Time (µs)`) was not taken as the time axis: it became the analysed channel (a ramp)
/// and the rate was unknown. Each now gives the rate of the same record with a seconds
/// column, and the same report but for the file and where the rate came from. A `time`
/// column in a unit not read (`Time (h)`) is refused naming it and the units read, rather
/// than analysed as a channel.
#[test]
fn a_time_column_in_other_units_gives_the_rate_of_the_seconds_column() {
    let dir = tempfile::tempdir().expect("tempdir");
    // 16 384 Hz: every stamp is exact in binary in s, ms and µs, so the rates are equal.
    let fs = 16_384.0;
    let x = noise(16_384);
    let write = |name: &str, header: &str, per_second: f64| {
        let body = crate::support::timed_rows(&x, fs, ",", |t| format!("{}", t * per_second));
        let p = dir.path().join(name);
        std::fs::write(&p, format!("{header},accel\n{body}")).expect("write");
        p
    };
    let strip = |mut v: serde_json::Value| {
        let o = v.as_object_mut().expect("object");
        for k in ["file", "fs_detail"] {
            o.remove(k);
        }
        v
    };
    let want = analyze_6205(&write("s.csv", "time", 1.0), &[]);
    assert_eq!(want["fs"], fs);
    for (i, (header, per_second)) in [
        ("time_s", 1.0),
        ("Time (ms)", 1e3),
        ("time [ms]", 1e3),
        ("t_ms", 1e3),
        ("time [us]", 1e6),
        ("Time (µs)", 1e6),
    ]
    .into_iter()
    .enumerate()
    {
        let v = analyze_6205(&write(&format!("{i}.csv"), header, per_second), &[]);
        assert_eq!(v["channel"], "accel", "{header}: {v}");
        assert_eq!(v["fs"], fs, "{header}");
        assert_eq!(v["fs_source"], "file", "{header}");
        assert_eq!(strip(v), strip(want.clone()), "{header}");
    }
    let hours = write("h.csv", "Time (h)", 1.0 / 3600.0);
    for extra in [&[][..], &["--fs", "16384"]] {
        let mut args = vec!["analyze", s(&hours), "--rpm", "1797"];
        args.extend(extra);
        refused(
            &wearsim(&args),
            &[
                "time column \"Time (h)\"",
                "unit \"h\" is not a time unit read here",
                "s/sec",
                "ms/msec",
                "us/µs",
            ],
        );
    }
}

/// `fs_source` said `file` alike for a WAV header and a CSV time column (and `argument`,
/// `sidecar` without naming which): `fs_detail` and `rpm_detail` now say where exactly,
/// beside the unchanged `fs_source` and `rpm_source`; the batch table has `fs_detail` too.
#[test]
fn the_report_says_where_the_rate_and_speed_were_found() {
    let dir = tempfile::tempdir().expect("tempdir");
    let x = noise(16_384);
    let wav = dir.path().join("rec.wav");
    let spec = hound::WavSpec {
        channels: 1,
        sample_rate: 16_000,
        bits_per_sample: 32,
        sample_format: hound::SampleFormat::Float,
    };
    let mut w = hound::WavWriter::create(&wav, spec).expect("wav");
    for v in &x {
        w.write_sample(*v as f32).expect("sample");
    }
    w.finalize().expect("wav end");
    let v = analyze_6205(&wav, &[]);
    assert_eq!(
        (&v["fs_source"], &v["fs_detail"]),
        (&"file".into(), &"WAV header".into())
    );
    assert_eq!(
        (&v["rpm_source"], &v["rpm_detail"]),
        (&"argument".into(), &"--rpm".into())
    );
    let v = analyze_6205(&wav, &["--fs", "16000"]);
    assert_eq!(
        (&v["fs_source"], &v["fs_detail"]),
        (&"argument".into(), &"--fs".into())
    );

    let body = crate::support::timed_rows(&x, 16_384.0, ",", |t| format!("{}", t * 1e3));
    let csv = dir.path().join("run1.csv");
    std::fs::write(&csv, format!("Time (ms),accel\n{body}")).expect("csv");
    let v = analyze_6205(&csv, &[]);
    assert_eq!(
        (&v["fs_source"], &v["fs_detail"]),
        (&"file".into(), &"time column `Time (ms)`".into())
    );
    std::fs::write(
        dir.path().join("run1.json"),
        r#"{"fs": 16384, "rpm": 1797}"#,
    )
    .expect("sidecar");
    let o = wearsim(&["analyze", s(&csv), "--bearing", "cwru-6205-de", "--json"]);
    let v = crate::support::json_ok(&o);
    assert_eq!(v["fs_source"], "sidecar");
    assert_eq!(v["fs_detail"], "sidecar `run1.json`");
    assert_eq!(
        (&v["rpm_source"], &v["rpm_detail"]),
        (&"file".into(), &"sidecar `run1.json`".into())
    );

    let p = mat(
        dir.path(),
        "lab.mat",
        &[
            ("acc", FixtureValue::Doubles(x.clone())),
            ("fs", FixtureValue::Doubles(vec![16_384.0])),
            ("rpm", FixtureValue::Doubles(vec![1797.0])),
        ],
    );
    let v = crate::support::json_ok(&wearsim(&[
        "analyze",
        s(&p),
        "--bearing",
        "cwru-6205-de",
        "--json",
    ]));
    assert_eq!(
        (&v["fs_source"], &v["fs_detail"]),
        (&"file:fs".into(), &"MAT variable `fs`".into())
    );
    assert_eq!(v["input"]["rpm_source"], "file:rpm");
    assert_eq!(v["rpm_detail"], "MAT variable `rpm`");
    let p = mat(
        dir.path(),
        "mfpt.mat",
        &[(
            "bearing",
            FixtureValue::Struct {
                dims: vec![1, 1],
                fields: vec!["gs".into(), "sr".into(), "rate".into()],
                elems: vec![vec![
                    FixtureValue::Doubles(x),
                    FixtureValue::Doubles(vec![16_384.0]),
                    FixtureValue::Doubles(vec![25.0]),
                ]],
            },
        )],
    );
    let v = crate::support::json_ok(&wearsim(&["analyze", s(&p), "--json"]));
    assert_eq!(v["fs_source"], "file:bearing.sr");
    assert_eq!(v["fs_detail"], "MAT struct field `bearing.sr`");
    assert_eq!(v["rpm_detail"], "MAT struct field `bearing.rate` (Hz × 60)");

    let table = dir.path().join("t.csv");
    let o = wearsim(&[
        "analyze",
        s(&wav),
        s(&csv),
        "--rpm",
        "1797",
        "--bearing",
        "cwru-6205-de",
        "--out",
        s(&table),
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let text = std::fs::read_to_string(&table).expect("table");
    assert!(
        text.lines()
            .next()
            .unwrap_or("")
            .contains(",fs_source,fs_detail,rpm,"),
        "{text}"
    );
    assert!(
        text.contains("WAV header") && text.contains("sidecar `run1.json`"),
        "{text}"
    );
}

/// A CWRU record's rate comes from its file name and its speed from its `X<n>RPM`
/// variable; the details name both (skipped without the data folder, failing on CI).
#[test]
fn a_cwru_record_names_its_file_name_and_rpm_variable() -> Result<(), wearsim_host::io::IoError> {
    let Some(data) = wearsim_host::io::data_dir()? else {
        return Ok(());
    };
    let p = data.join("cwru").join("12k_Drive_End_B007_0_118.mat");
    let v = crate::support::json_ok(&wearsim(&["analyze", s(&p), "--json"]));
    assert_eq!(v["fs_source"], "file name");
    assert_eq!(
        v["fs_detail"],
        "CWRU file name `12k_Drive_End_B007_0_118.mat` (12000 Hz)"
    );
    assert_eq!(v["rpm_source"], "file");
    assert_eq!(v["rpm_detail"], "MAT variable `X118RPM`");
    // `--fs` may override the file name's rate (a renamed or resampled file), but says so
    // on stderr and in the JSON: it was silent (probe F).
    let o = wearsim(&["analyze", s(&p), "--fs", "48000", "--json"]);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(
        err.contains(
            "--fs 48000 Hz overrides the CWRU file name `12k_Drive_End_B007_0_118.mat`'s 12000 Hz"
        ),
        "{err}"
    );
    let v = crate::support::json_ok(&o);
    assert_eq!(v["fs_source"], "argument");
    assert!(
        v["fs_detail"]
            .as_str()
            .is_some_and(|d| d.contains("overrides")),
        "{}",
        v["fs_detail"]
    );
    // The same rate given again is no override.
    let o = wearsim(&["analyze", s(&p), "--fs", "12000", "--json"]);
    assert!(!String::from_utf8_lossy(&o.stderr).contains("overrides"));
    Ok(())
}

/// `life --preset cwru-6205-de --load-scale 20` (inside the documented 0.05..=20) exited 1
/// after its first window: "band (6993.95, 6000) Hz must satisfy … (zone empty below fs/2)".
/// Twenty times the load stiffens the contacts and moves the structure's resonance to
/// about 5.4 kHz, so its high-frequency zone (from 1.3× the resonance) lies beyond the
/// 12 kHz record's Nyquist. The zone is then empty and its level 0 (nothing of it is in the
/// record), as `resonance_peak` is 0 without a peak; the life runs to failure.
#[test]
fn a_load_that_moves_the_resonance_past_nyquist_still_gives_a_whole_life() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("life");
    let o = wearsim(&[
        "life",
        "--preset",
        "cwru-6205-de",
        "--load-scale",
        "20",
        "--cycles",
        "1e9",
        "--out",
        s(&out),
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).expect("json");
    assert_eq!(j["complete"], true);
    let text = std::fs::read_to_string(out.join("life-features.csv")).expect("features");
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().expect("header").split(',').collect();
    let col = |n: &str| head.iter().position(|h| *h == n).expect(n);
    let (stage, natural, high, rms) = (
        col("stage"),
        col("zone_natural"),
        col("zone_high"),
        col("rms"),
    );
    let mut n = 0;
    for line in lines {
        let r: Vec<&str> = line.split(',').collect();
        let num = |c: usize| r[c].parse::<f64>().expect(r[c]);
        let numbers = (0..r.len()).filter(|c| *c != stage).map(num);
        assert!(numbers.clone().all(f64::is_finite), "{line}");
        assert_eq!(num(high), 0.0, "the high zone lies beyond fs/2: {line}");
        // The resonance below fs/2 carries most of the signal (a Welch band level, so it
        // can read a few % above the time-domain RMS).
        let share = num(natural) / num(rms);
        assert!((0.5..1.1).contains(&share), "{share}: {line}");
        n += 1;
    }
    assert!(n > 10, "{n} snapshots");
}

/// `life --preset ims-za2115 --load-scale 0.3` ran to the cycle cap and said "the bearing
/// did not fail within the cycle cap …; raise --cycles or the load": at 4003 N no rolling
/// element touches (the model's structure spring, 10⁹ N/m, carries up to 5000 N within the
/// 5 µm clearance), every wear rate is zero, and no cap would ever be enough. Such a load
/// is refused before any window, naming the load and why; `--lives --loads` too.
#[test]
fn a_load_that_leaves_every_element_unloaded_is_refused_saying_why() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("life");
    for extra in [
        &["--load-scale", "0.3"][..],
        &["--lives", "3", "--loads", "1,0.3"],
    ] {
        let mut args = vec!["life", "--preset", "ims-za2115", "--out", s(&out)];
        args.extend_from_slice(extra);
        let o = wearsim(&args);
        refused(
            &o,
            &[
                "radial load 4003 N",
                "no rolling element carries load",
                "up to 5000 N within the radial clearance (5.0 µm)",
                "--load-scale",
            ],
        );
        assert!(!out.exists(), "{extra:?}: nothing is written");
    }
}
