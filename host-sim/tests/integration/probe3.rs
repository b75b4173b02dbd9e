//! Defects found by an outside review that ran `wearsim analyze` on files of other rigs and
//! public data sets the project's own tests did not have (spreadsheet exports with a byte
//! order mark, DAQ exports with comment lines and rounded time stamps, MAT files of other
//! labs); one test per defect, each named after what must hold.

use std::path::Path;

use crate::support::{analyze_6205, json_ok, mat, noise, refused, s, timed_rows, wearsim};
use wearsim_host::io::mat::fixture::FixtureValue;

/// An XJTU-SY (or FEMTO) CSV saved by a spreadsheet program starts with a UTF-8 byte order
/// mark. The layout was recognised from the raw first line, so the mark hid the header:
/// the file fell to the generic CSV reader and `analyze` exited 2 with "sample rate
/// unknown" instead of reading it at the layout's 25.6 kHz.
#[test]
fn a_layout_file_with_a_byte_order_mark_is_recognised_by_content() {
    let dir = tempfile::tempdir().expect("tempdir");
    let x = noise(8192);
    let mut xjtu =
        String::from("\u{feff}Horizontal_vibration_signals,Vertical_vibration_signals\r\n");
    for v in &x {
        xjtu.push_str(&format!("{v},{}\r\n", -v));
    }
    let p = dir.path().join("1.csv");
    std::fs::write(&p, xjtu).expect("write");
    let v = json_ok(&wearsim(&["analyze", s(&p), "--rpm", "2100", "--json"]));
    assert_eq!(v["fs_source"], "layout:xjtu-sy", "{v}");
    assert_eq!(v["input"]["layout"], "xjtu-sy");
    assert_eq!(v["bearing"], "xjtu-ldk-uer204");
    assert_eq!(v["samples"], 8192);

    let femto: String = x[..2560]
        .iter()
        .enumerate()
        .map(|(i, v)| format!("9,39,39,{},{v:.3},{:.3}\n", 65664 + 39 * i, -v))
        .collect();
    let p = dir.path().join("acc_00001.csv");
    std::fs::write(&p, format!("\u{feff}{femto}")).expect("write");
    let o = wearsim(&[
        "analyze",
        s(&p),
        "--rpm",
        "1800",
        "--bearing-geometry",
        "elements=13,ball=3.5,pitch=25.6,angle=0",
        "--json",
    ]);
    let v = json_ok(&o);
    assert_eq!(v["fs_source"], "layout:femto", "{v}");
    assert_eq!(v["channel"], "horiz");
}

/// A DAQ export opening with a `#` comment that holds a comma (`# exported by X, fs=25600`)
/// above a tab-separated table: the separator was decided on that comment, so every row
/// was one cell and `analyze` exited 2 with `"0\t-0.14" is not a number`. The comment is
/// skipped when the separator is chosen, as the reader skips it.
#[test]
fn a_comment_line_does_not_decide_the_separator() {
    let dir = tempfile::tempdir().expect("tempdir");
    let x = noise(25_600);
    let body = timed_rows(&x, 25_600.0, "\t", |t| format!("{t}"));
    let p = dir.path().join("daq.csv");
    std::fs::write(
        &p,
        format!("# exported by DAQ, channel 1, units g\ntime\taccel\n{body}"),
    )
    .expect("write");
    let v = analyze_6205(&p, &[]);
    assert_eq!(v["channel"], "accel", "{v}");
    let fs = v["fs"].as_f64().expect("fs");
    assert!((fs - 25_600.0).abs() < 1e-6 * 25_600.0, "{fs}");
}

/// A hand-written sidecar's `bearing_geometry` (documented, and used: `bearing_source` is
/// `sidecar`) was named on stderr among the "sidecar keys not read".
#[test]
fn a_sidecar_bearing_geometry_is_not_called_unread() {
    let dir = tempfile::tempdir().expect("tempdir");
    let body: String = noise(25_600).iter().map(|v| format!("{v}\n")).collect();
    let p = dir.path().join("run1.csv");
    std::fs::write(&p, format!("accel\n{body}")).expect("write");
    std::fs::write(
        dir.path().join("run1.json"),
        r#"{"fs": 25600, "rpm": 2100, "units": "g",
            "bearing_geometry": "elements=8,ball=7.92,pitch=34.55,angle=0"}"#,
    )
    .expect("sidecar");
    let o = wearsim(&["analyze", s(&p), "--json"]);
    let v = json_ok(&o);
    assert_eq!(v["bearing_source"], "sidecar", "{v}");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!err.contains("not read"), "{err}");
}

/// A sidecar naming a bearing and giving a geometry of another was analysed with the
/// geometry, silently; now refused naming both (the same bearing twice is accepted).
#[test]
fn a_sidecar_naming_two_different_bearings_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    let body: String = noise(25_600).iter().map(|v| format!("{v}\n")).collect();
    let p = dir.path().join("run2.csv");
    std::fs::write(&p, format!("accel\n{body}")).expect("write");
    let side = |g: &str| {
        std::fs::write(
            dir.path().join("run2.json"),
            format!(
                r#"{{"fs": 25600, "rpm": 1797, "units": "g", "bearing": "cwru-6205-de", "bearing_geometry": "{g}"}}"#
            ),
        )
        .expect("sidecar");
    };
    side("elements=8,ball=7.92,pitch=34.55,angle=0");
    let o = wearsim(&["analyze", s(&p), "--json"]);
    refused(
        &o,
        &[
            "`bearing` = \"cwru-6205-de\"",
            "`bearing_geometry`",
            "different bearings",
        ],
    );
    side("elements=9,ball=7.94,pitch=39.04,angle=0");
    let v = json_ok(&wearsim(&["analyze", s(&p), "--json"]));
    assert_eq!(v["bearing_source"], "sidecar", "{v}");
}

/// A MAT file without a usable rate was told to "write a sidecar with `"fs": HZ`", which a
/// MAT file's sidecar is not read for (one sitting beside it gave the same error), and an
/// MFPT struct whose `sr` was a char array or a vector was said to store "none". The
/// message now names the field that is there and why it is not used, and the ways that work.
#[test]
fn a_mat_file_without_a_usable_rate_is_told_what_works() {
    let dir = tempfile::tempdir().expect("tempdir");
    let x = noise(60_000);
    let p = mat(
        dir.path(),
        "lab.mat",
        &[
            ("acc", FixtureValue::Doubles(x.clone())),
            ("rpm", FixtureValue::Doubles(vec![1797.0])),
        ],
    );
    std::fs::write(dir.path().join("lab.json"), r#"{"fs": 25600}"#).expect("sidecar");
    let o = wearsim(&["analyze", s(&p), "--bearing", "cwru-6205-de"]);
    refused(&o, &["sample rate unknown", "--fs HZ", "numeric scalar"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!err.contains("write a sidecar"), "{err}");

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
                    FixtureValue::Char("48828".into()),
                    FixtureValue::Doubles(vec![25.0]),
                ]],
            },
        )],
    );
    let o = wearsim(&["analyze", s(&p)]);
    refused(
        &o,
        &["`bearing.sr` is a char array \"48828\", not a numeric scalar"],
    );
}

/// A Paderborn file states each channel's unit in `Y(i).Unit`; it was ignored, so
/// `vibration_1` was `unknown` unless a sidecar repeated it.
#[test]
fn a_paderborn_file_gives_the_unit_it_states() {
    let dir = tempfile::tempdir().expect("tempdir");
    let x = noise(64_000);
    let channel = |name: &str, unit: &str, d: &[f64]| {
        vec![
            FixtureValue::Char(name.into()),
            FixtureValue::Char("Signal".into()),
            FixtureValue::Char(unit.into()),
            FixtureValue::Doubles(d.to_vec()),
            FixtureValue::Char("HostService".into()),
        ]
    };
    let y = FixtureValue::Struct {
        dims: vec![1, 2],
        fields: ["Name", "Type", "Unit", "Data", "Raster"]
            .iter()
            .map(|f| f.to_string())
            .collect(),
        elems: vec![
            channel("force", "N", &[1.0; 300]),
            channel("vibration_1", "m/s^2", &x),
        ],
    };
    let name = "N15_M07_F10_KA01_1";
    let p = mat(
        dir.path(),
        "record.mat",
        &[(
            name,
            FixtureValue::Struct {
                dims: vec![1, 1],
                fields: vec!["Info".into(), "Y".into()],
                elems: vec![vec![FixtureValue::Empty, y]],
            },
        )],
    );
    let v = json_ok(&wearsim(&["analyze", s(&p), "--json"]));
    assert_eq!(v["input"]["layout"], "paderborn", "{v}");
    assert_eq!(v["unit"], "m/s^2", "{v}");
    // A sidecar's unit still overrides the file's.
    std::fs::write(dir.path().join("record.json"), r#"{"units": "g"}"#).expect("sidecar");
    let v = json_ok(&wearsim(&["analyze", s(&p), "--json"]));
    assert_eq!(v["unit"], "g", "{v}");
}

/// A MAT variable holding several channels as columns was refused with "pick one column
/// with --channel", which no `--channel` value could do; the message now says what works:
/// the selector `data(:,K)` / `data(K,:)` with the ranges of this array (probe4 tests it).
#[test]
fn a_mat_matrix_channel_is_refused_with_advice_that_works() {
    let dir = tempfile::tempdir().expect("tempdir");
    let x = noise(2 * 4096);
    let p = mat(
        dir.path(),
        "two.mat",
        &[
            (
                "data",
                FixtureValue::Typed {
                    class: 6,
                    mi: 9,
                    dims: vec![4096, 2],
                    bytes: x.iter().flat_map(|v| v.to_le_bytes()).collect(),
                    logical: false,
                },
            ),
            ("fs", FixtureValue::Doubles(vec![25_600.0])),
        ],
    );
    let o = wearsim(&[
        "analyze",
        s(&p),
        "--channel",
        "data",
        "--rpm",
        "1797",
        "--bearing",
        "cwru-6205-de",
    ]);
    refused(
        &o,
        &[
            "[4096, 2] matrix",
            "--channel 'data(:,K)' (K = 1..=2)",
            "--channel 'data(K,:)' (K = 1..=4096)",
        ],
    );
}

/// A time column headed `Time (s)` (a space before the unit, as many DAQ programs write
/// it) was not taken as the time axis: it became the analysed channel (a ramp), and the
/// rate was unknown. A unit in brackets in a header (`Accel (g)`) now gives the unit.
#[test]
fn a_time_column_with_its_unit_in_brackets_is_the_time_axis() {
    let dir = tempfile::tempdir().expect("tempdir");
    let body = timed_rows(&noise(25_600), 25_600.0, ",", |t| format!("{t}"));
    let p = dir.path().join("export.csv");
    std::fs::write(&p, format!("Time (s),Accel (g)\n{body}")).expect("write");
    let v = analyze_6205(&p, &[]);
    assert_eq!(v["channel"], "Accel (g)", "{v}");
    assert_eq!(v["unit"], "g", "{v}");
    let fs = v["fs"].as_f64().expect("fs");
    assert!((fs - 25_600.0).abs() < 1e-6 * 25_600.0, "{fs}");
}

/// At 25.6 kHz, time stamps printed to the microsecond (`0.000039`, `0.000078`, …; what
/// `%.6f` writes) are off the grid by up to 0.5 µs, and the record was refused as "not
/// uniformly spaced", with no way round it (`--fs` must agree with the column). The
/// rounding of the printed digits is allowed (stamps exact at their digits, 1 kHz to the
/// millisecond, stay exact); stamps too coarse to tell samples apart are refused saying so.
#[test]
fn time_stamps_rounded_to_the_microsecond_give_the_rate() {
    let dir = tempfile::tempdir().expect("tempdir");
    let x = noise(25_600);
    let p = dir.path().join("us.csv");
    let body = timed_rows(&x, 25_600.0, ",", |t| format!("{t:.6}"));
    std::fs::write(&p, format!("time,accel\n{body}")).expect("write");
    let args = [
        "analyze",
        s(&p),
        "--rpm",
        "1797",
        "--bearing",
        "cwru-6205-de",
        "--json",
    ];
    let v = json_ok(&wearsim(&args));
    let fs = v["fs"].as_f64().expect("fs");
    assert!((fs - 25_600.0).abs() < 1e-4 * 25_600.0, "{fs}");

    let body = timed_rows(&x, 25_600.0, ",", |t| format!("{t:.4}"));
    std::fs::write(&p, format!("time,accel\n{body}")).expect("write");
    refused(
        &wearsim(&args),
        &["time column \"time\"", "4 decimals", "too coarse"],
    );
}

/// `--bearing mfpt-nice` is accepted, but a misspelt name was refused listing only the
/// model presets ("unknown bearing preset … (allowed: thesis-61810, …, ims-za2115)"),
/// hiding the catalogue bearings `--bearing` also takes.
#[test]
fn an_unknown_bearing_lists_every_name_bearing_takes() {
    let dir = tempfile::tempdir().expect("tempdir");
    let body: String = noise(25_600).iter().map(|v| format!("{v}\n")).collect();
    let p = dir.path().join("rec.csv");
    std::fs::write(&p, format!("accel\n{body}")).expect("write");
    let o = wearsim(&[
        "analyze",
        s(&p),
        "--fs",
        "25600",
        "--rpm",
        "1500",
        "--bearing",
        "mfpt",
    ]);
    refused(
        &o,
        &[
            "--bearing: unknown bearing `mfpt`",
            "cwru-6205-de",
            "mfpt-nice",
            "paderborn-6203",
            "xjtu-ldk-uer204",
            "--bearing-geometry",
        ],
    );
}

/// A batch with `--out` into a directory that does not exist analysed every file first and
/// then exited 1 with an error about a temporary file (`…/.tmpXXXX: No such file or
/// directory`). It is refused before any work, naming `--out`.
#[test]
fn a_batch_out_in_a_missing_directory_is_refused_first() {
    let dir = tempfile::tempdir().expect("tempdir");
    let body: String = noise(25_600).iter().map(|v| format!("{v}\n")).collect();
    let p = dir.path().join("rec.csv");
    std::fs::write(&p, format!("accel\n{body}")).expect("write");
    let out = dir.path().join("missing").join("table.csv");
    let o = wearsim(&[
        "analyze",
        s(&p),
        "--fs",
        "25600",
        "--rpm",
        "1797",
        "--bearing",
        "cwru-6205-de",
        "--out",
        s(&out),
    ]);
    refused(&o, &["--out", "directory does not exist"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !err.contains("analysed"),
        "no file is analysed first: {err}"
    );
}

/// Text written by numpy's `savetxt` (one space between values) or MATLAB's `save -ascii`
/// (values right-aligned in 16-character fields: runs of spaces, a leading space) was read
/// as one column whose first row is a header, and refused with "column "0.0 -0.14" … is
/// not a number". Both now read as columns, the same samples as the comma-separated file;
/// a one-column file whose header has a space stays one column.
#[test]
fn space_separated_text_is_read_as_columns() {
    let dir = tempfile::tempdir().expect("tempdir");
    let x = noise(4096);
    let write = |name: &str, text: String| {
        let p = dir.path().join(name);
        std::fs::write(&p, text).expect("write");
        p
    };
    let comma = write(
        "comma.csv",
        x.iter().map(|v| format!("{v:.7e},{:.7e}\n", -v)).collect(),
    );
    let numpy = write(
        "numpy.txt",
        x.iter()
            .map(|v| format!("{v:.18e} {:.18e}\n", -v))
            .collect(),
    );
    let matlab = write(
        "matlab.txt",
        x.iter()
            .map(|v| format!("{v:16.7e}{:16.7e}\r\n", -v))
            .collect(),
    );
    let header = write(
        "one.csv",
        std::iter::once("Accel (g)\n".to_string())
            .chain(x.iter().map(|v| format!("{v:.7e}\n")))
            .collect(),
    );
    let run = |p: &Path, ch: &str| analyze_6205(p, &["--fs", "12000", "--channel", ch]);
    let want = run(&comma, "1");
    for p in [&numpy, &matlab] {
        let v = run(p, "1");
        assert_eq!(v["samples"], 4096, "{}", p.display());
        for k in ["rms", "kurtosis", "crest_factor"] {
            let (a, b) = (v["stats"][k].as_f64(), want["stats"][k].as_f64());
            assert!(
                a.zip(b)
                    .is_some_and(|(a, b)| (a - b).abs() <= 1e-6 * b.abs()),
                "{}: {k} {a:?} against {b:?}",
                p.display()
            );
        }
    }
    let v = run(&header, "Accel (g)");
    assert_eq!(v["samples"], 4096, "{v}");
}
