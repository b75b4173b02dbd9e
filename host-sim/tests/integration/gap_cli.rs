//! `wearsim gap` and `gap-validate` on bad input: exit code 2, a message naming the field
//! and what is allowed, and nothing written.

use std::path::Path;
use std::process::Command;

fn wearsim(args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_wearsim"))
        .args(args)
        .output()
        .expect("run wearsim");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// A CSV record in m/s² of `n` samples of a deterministic broadband signal.
fn csv(dir: &Path, name: &str, n: usize) -> String {
    let mut s = String::from("accel_m_s2\n");
    let mut x: u64 = 12345;
    for _ in 0..n {
        x = x
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        s.push_str(&format!(
            "{}\n",
            ((x >> 33) as f64 / (1u64 << 31) as f64) - 0.5
        ));
    }
    let p = dir.join(name);
    std::fs::write(&p, s).unwrap();
    p.display().to_string()
}

fn bad(args: &[&str], needle: &str, out: &Path) {
    let (code, err) = wearsim(args);
    assert_eq!(code, 2, "{args:?}: exit {code}, stderr {err}");
    assert!(err.contains(needle), "{args:?}: `{needle}` not in: {err}");
    assert!(!out.join("gap.json").exists(), "{args:?} wrote a report");
}

#[test]
fn gap_rejects_bad_input_naming_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = out.display().to_string();
    let long = csv(dir.path(), "noise.csv", 24_000);
    let short = csv(dir.path(), "short.csv", 3_000);
    let common = ["--fs", "12000", "--bearing", "cwru-6205-de", "--out", &o];
    let with = |extra: &[&str], file: &str| -> Vec<String> {
        let mut v = vec!["gap".to_string(), "--real".into(), file.to_string()];
        v.extend(common.iter().map(|s| s.to_string()));
        v.extend(extra.iter().map(|s| s.to_string()));
        v
    };
    let run = |v: Vec<String>, needle: &str| {
        let a: Vec<&str> = v.iter().map(String::as_str).collect();
        bad(&a, needle, &out);
    };
    // Sample rate vs length.
    run(
        with(&["--rpm", "1797"], &short),
        "is the sample rate right?",
    );
    // One record too short for three disjoint parts (1.25 s < 3 × 0.5 s) says how long
    // it must be.
    let mid = csv(dir.path(), "mid.csv", 15_000);
    run(
        with(&["--rpm", "1797"], &mid),
        "must hold at least 1.5 s (18000 samples at 12000 Hz)",
    );
    // Speed missing and not estimable from a broadband record.
    run(with(&[], &long), "not estimable");
    // Unknown defect location, size without unit, out-of-range size; unknown effect;
    // out-of-range arguments: each with the record's speed given.
    for (args, message) in [
        (
            &["--defect", "cage:1mm"][..],
            "the model knows: none, inner",
        ),
        (&["--defect", "inner:0.007"], "needs a unit"),
        (&["--defect", "inner:50mm"], "out of range"),
        (&["--effects", "magic"], "unknown effect `magic`"),
        (&["--seconds", "0.1"], "--seconds 0.1 is out of range"),
        (&["--mains", "100"], "--mains 100 Hz is out of range"),
        (
            &["--significant-gap", "0"],
            "--significant-gap 0 is out of range 0.05..=100",
        ),
        (
            &["--significant-gap", "NaN"],
            "--significant-gap NaN is out of range",
        ),
    ] {
        let mut a = vec!["--rpm", "1797"];
        a.extend_from_slice(args);
        run(with(&a, &long), message);
    }
    run(with(&["--rpm", "-5"], &long), "rpm");
    // A held-out record must not be fitted on (two different records: one given twice is
    // refused before the roles, `gap_roles.rs`).
    let other = csv(dir.path(), "noise2.csv", 24_001);
    let mut v = with(
        &["--rpm", "1797", "--train", "1", "--holdout", "1,2"],
        &long,
    );
    v.insert(3, other);
    run(v, "must not be fitted on");
    // A record of unknown unit: the message names the channel and the sidecar key.
    let mut s = String::from("x\n");
    for i in 0..24_000 {
        s.push_str(&format!("{}\n", ((i * 7919) % 1000) as f64 / 1000.0 - 0.5));
    }
    let raw = dir.path().join("raw.csv");
    std::fs::write(&raw, s).unwrap();
    run(
        with(&["--rpm", "1797"], &raw.display().to_string()),
        r#"channel `x`) cannot be compared with simulated m/s²; allowed units g or m/s^2: give --units g (or m/s^2) when the file states none, or the file a JSON sidecar (`<file>.json`) with `"units": {"x": "g"}`"#,
    );
}

#[test]
fn gap_contradicting_label_and_unknown_bearing() {
    let Some(data) = wearsim_host::io::data_dir().unwrap() else {
        return;
    };
    let f = data.join("cwru/12k_Drive_End_IR007_0_105.mat");
    let f = f.display().to_string();
    let dir = tempfile::tempdir().unwrap();
    let o = dir.path().join("out").display().to_string();
    bad(
        &[
            "gap",
            "--real",
            &f,
            "--defect",
            "outer:0.007in",
            "--out",
            &o,
        ],
        "contradicts the file's label",
        &dir.path().join("out"),
    );
    bad(
        &["gap", "--real", &f, "--bearing", "skf-9999", "--out", &o],
        "--bearing: unknown bearing `skf-9999`; give --bearing NAME (a model preset: ",
        &dir.path().join("out"),
    );
    bad(
        &[
            "gap",
            "--real",
            &f,
            "--bearing",
            "cwru-6205-de",
            "--bearing-geometry",
            "elements=9,ball=7.94,pitch=39.04",
            "--out",
            &o,
        ],
        "give either --bearing or --bearing-geometry, not both",
        &dir.path().join("out"),
    );
    bad(
        &[
            "gap",
            "--real",
            &f,
            "--bearing-geometry",
            "elements=9,ball=8,pitch=7.9",
            "--out",
            &o,
        ],
        "bearing-geometry.pitch = 7.9 is impossible",
        &dir.path().join("out"),
    );
}

/// A bearing that is no model preset — a catalogue bearing of a public data set, a
/// geometry given on the command line or in the sidecar — is matched with the one rule for
/// such bearings (`GeometrySpec::model`): its own geometry and kinematics, the nearest
/// preset's structure scaled by similitude, and a warning that says so; a preset named by
/// the file keeps the preset.
#[test]
fn gap_matches_a_bearing_that_is_no_preset() {
    use wearsim_host::gap::records::{load, matched_config, Overrides};
    use wearsim_host::geometry::{catalogue, GeometrySpec};
    let dir = tempfile::tempdir().unwrap();
    let f = std::path::PathBuf::from(csv(dir.path(), "rig.csv", 24_000));
    let fs_rpm = r#""fs": 12000, "rpm": 1500, "units": "m/s^2""#;
    let side = |extra: &str| {
        std::fs::write(dir.path().join("rig.json"), format!("{{{fs_rpm}{extra}}}")).unwrap()
    };
    let o = |bearing: Option<&str>, geometry: Option<&str>| Overrides {
        bearing: bearing.map(String::from),
        geometry: geometry.map(String::from),
        defect: Some(None),
        ..Default::default()
    };
    // A catalogue bearing by name (Paderborn's 6203).
    side("");
    let r = load(&f, &o(Some("paderborn-6203"), None)).expect("catalogue bearing");
    let g = catalogue("paderborn-6203").unwrap().geometry;
    let want = g.model().unwrap();
    assert_eq!(r.bearing, "paderborn-6203");
    assert_eq!(r.base, want.model);
    assert_eq!(r.base.bearing.elements, 8);
    assert!((r.base.bearing.pitch_diameter - 28.55e-3).abs() < 1e-12);
    assert!(
        r.warnings
            .iter()
            .any(|w| w.contains("is no model preset") && w.contains(&format!("`{}`", want.base))),
        "{:?}",
        r.warnings
    );
    let m = matched_config(&r).expect("matched");
    assert!((m.speed.shaft_hz(0.0) - 25.0).abs() < 1e-12);
    // A geometry on the command line, and the same in the sidecar.
    let geo = "elements=12,ball=9.5,pitch=52,angle=0";
    let r = load(&f, &o(None, Some(geo))).expect("geometry");
    assert_eq!(
        r.base,
        GeometrySpec::parse(geo).unwrap().model().unwrap().model
    );
    assert_eq!(r.bearing, "custom");
    side(r#", "bearing_geometry": "elements=12,ball=9.5,pitch=52,angle=0""#);
    let s = load(&f, &o(None, None)).expect("sidecar geometry");
    assert_eq!(s.base, r.base);
    // A preset the sidecar names is the preset.
    side(r#", "bearing": "cwru-6205-de""#);
    let p = load(&f, &o(None, None)).expect("preset");
    assert_eq!(
        p.base,
        wearsim_core::presets::by_name("cwru-6205-de").unwrap()
    );
    assert!(!p.warnings.iter().any(|w| w.contains("is no model preset")));
    // The 6205's geometry typed on the command line (to 0.03 %, as a user copies it from a
    // catalogue) is the 6205 preset, not a bearing scaled from it (the probe's run said
    // "no model preset ... s = 1.000" and gave another gap).
    side("");
    let typed = load(
        &f,
        &o(None, Some("elements=9,ball=7.94,pitch=39.04,angle=0")),
    )
    .expect("the 6205's geometry");
    assert_eq!(typed.bearing, "cwru-6205-de");
    assert_eq!(typed.base, p.base);
    assert!(
        typed
            .warnings
            .iter()
            .any(|w| w.contains("model preset `cwru-6205-de`'s geometry")),
        "{:?}",
        typed.warnings
    );
    // A name that is neither, from the file.
    side(r#", "bearing": "skf-6310""#);
    let e = load(&f, &o(None, None)).unwrap_err();
    assert!(
        e.contains("the file names the bearing `skf-6310`, which is no model preset"),
        "{e}"
    );
}

#[test]
fn gap_validate_rejects_bad_arguments() {
    let dir = tempfile::tempdir().unwrap();
    for (args, needle) in [
        (
            vec!["gap-validate", "--trials", "0"],
            "--trials 0 is out of range",
        ),
        (
            vec!["gap-validate", "--noise", "2"],
            "--noise 2 is out of range",
        ),
        (
            vec!["gap-validate", "--effects", "warp"],
            "unknown effect `warp`",
        ),
        (
            vec!["gap-validate", "--half", "0.1"],
            "--half 0.1 s is out of range",
        ),
    ] {
        bad(&args, needle, dir.path());
    }
}

/// A lifetime table in the layout of IMS `test2_timefeatures.csv` (12 features for each
/// of 4 bearings, a time stamp every 10 minutes), `rows` snapshots of a steady bearing.
fn life_table(dir: &Path, name: &str, rows: usize) -> String {
    let feats = [
        "mean",
        "std",
        "skew",
        "kurtosis",
        "entropy",
        "rms",
        "max",
        "p2p",
        "crest",
        "clearence",
        "shape",
        "impulse",
    ];
    let mut s = String::new();
    for b in 1..=4 {
        for f in feats {
            s.push_str(&format!(",B{b}_{f}"));
        }
    }
    s.push('\n');
    for r in 0..rows {
        let (d, m) = (r / 144, r % 144);
        s.push_str(&format!(
            "2004-02-{:02} {:02}:{:02}:00",
            12 + d,
            m / 6,
            10 * (m % 6)
        ));
        for _ in 1..=4 {
            let w = 1.0 + 0.01 * ((r * 7919 % 13) as f64 - 6.0) / 6.0;
            let v = [
                0.06 * w,
                0.075 * w,
                0.0,
                0.4,
                4.8,
                0.075 * w,
                0.4,
                0.8,
                5.3,
                0.05,
                1.25,
                6.6,
            ];
            for x in v {
                s.push_str(&format!(",{x}"));
            }
        }
        s.push('\n');
    }
    let p = dir.join(name);
    std::fs::write(&p, s).unwrap();
    p.display().to_string()
}

#[test]
fn gap_on_a_lifetime_table_rejects_bad_input_naming_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = out.display().to_string();
    let life = life_table(dir.path(), "test2_timefeatures.csv", 400);
    let few = life_table(dir.path(), "few_timefeatures.csv", 8);
    let cwru = csv(dir.path(), "noise.csv", 24_000);
    let run = |extra: &[&str], file: &str, needle: &str| {
        let mut v = vec!["gap", "--life", "--real", file, "--out", &o];
        v.extend(extra);
        bad(&v, needle, &out);
    };
    run(&["--rpm", "1800"], &life, "--rpm: a lifetime record");
    run(
        &["--significant-gap", "2"],
        &life,
        "--significant-gap: a lifetime diagnosis takes 3× its own computed noise-only gap",
    );
    run(&["--defect", "outer:0.007in"], &life, "--defect");
    run(&["--train", "B9"], &life, "--train: `B9` is not a bearing");
    run(&["--train", "B1,B2"], &life, "trains on one bearing");
    run(
        &["--train", "B1", "--holdout", "B2,B1"],
        &life,
        "both hold bearing 1",
    );
    run(&["--effects", "slip"], &life, "acts within a snapshot");
    run(&["--effects", "warp"], &life, "unknown effect `warp`");
    run(&["--jobs", "0"], &life, "--jobs 0");
    // Flags of records of seconds are refused with --life rather than ignored (they were
    // accepted and did nothing), and --life-search without --life.
    run(&["--stability"], &life, "--stability: a lifetime diagnosis");
    run(
        &["--no-calibration"],
        &life,
        "--no-calibration: a lifetime diagnosis fits no rig",
    );
    run(&["--fixed-calibration"], &life, "--fixed-calibration");
    // --validation names the lives that choose the model (the --holdout lives are then a
    // test part): a life may not be in two parts.
    run(
        &["--validation", "B1"],
        &life,
        "--train and --validation both hold bearing 1",
    );
    run(
        &["--validation", "B2", "--holdout", "B2,B3"],
        &life,
        "--validation and --holdout both hold bearing 2",
    );
    bad(
        &[
            "gap",
            "--real",
            &cwru,
            "--fs",
            "12000",
            "--life-search",
            "4",
            "--out",
            &o,
        ],
        "--life-search: bounds the fits of a lifetime diagnosis",
        &out,
    );
    // A bearing the table does not have, and too short a life: input errors found before
    // any simulation runs.
    let five = [
        "gap",
        "--life",
        "--real",
        &life,
        "--out",
        &o,
        "--train",
        "B1",
        "--holdout",
        "5",
    ];
    bad(&five, "bearing 5 is not in the table", &out);
    run(&[], &few, "fewer than 3 snapshots in the first-tenth stage");
    // A lifetime table is diagnosed alone.
    let two = [
        "gap", "--life", "--real", &life, "--real", &cwru, "--out", &o,
    ];
    bad(&two, "diagnosed alone", &out);
    // The lifetime mode is chosen explicitly, not by the file's name or content: a
    // lifetime table without --life is refused with the invocation to use, and --life on
    // a record of seconds names what it needs.
    bad(
        &["gap", "--real", &life, "--out", &o],
        "wearsim gap --life --real",
        &out,
    );
    bad(
        &["gap", "--real", &cwru, "--real", &life, "--out", &o],
        "is a lifetime record",
        &out,
    );
    bad(
        &["gap", "--life", "--real", &cwru, "--out", &o],
        "not a lifetime record",
        &out,
    );
    // IMS test 1's layout (two accelerometers per bearing) is refused saying so, with or
    // without --life (it was "its sidecar is missing", or a time stamp that "is not a
    // number").
    let two = dir.path().join("test1_timefeatures.csv");
    std::fs::write(
        &two,
        ",B1_x_mean,B1_x_rms,B1_x_kurtosis,B1_y_rms\n2003-10-22 12:06:24,0.1,0.1,0.1,0.1\n",
    )
    .unwrap();
    let two = two.display().to_string();
    for life in [true, false] {
        let mut v = vec!["gap", "--real", &two, "--out", &o];
        if life {
            v.push("--life");
        }
        bad(&v, "two accelerometers per bearing (test 1's layout", &out);
    }
}

/// The faulty bearing of a CWRU record is the one its label names, whichever channel
/// recorded it: a drive-end fault at the fan-end or base-plate accelerometer is matched to
/// the drive-end bearing (with a finding), a fan-end fault to the fan-end bearing; a
/// channel that sits on the faulty bearing gives no finding. Data-backed.
#[test]
fn gap_matches_the_faulty_bearing_whatever_the_channel() {
    use wearsim_host::gap::records::{load, Overrides};
    let Some(data) = wearsim_host::io::data_dir().expect("data folder required when CI=true")
    else {
        return;
    };
    let de = data.join("cwru/12k_Drive_End_IR007_1_106.mat");
    let fe = data.join("cwru/12k_Fan_End_IR007_1_279.mat");
    for (file, channel, bearing, finding) in [
        (&de, "DE", "cwru-6205-de", false),
        (&de, "FE", "cwru-6205-de", true),
        (&de, "BA", "cwru-6205-de", true),
        (&fe, "FE", "cwru-6203-fe", false),
        (&fe, "DE", "cwru-6203-fe", true),
    ] {
        let r = load(
            file,
            &Overrides {
                channel: Some(channel.into()),
                ..Default::default()
            },
        )
        .expect("record");
        let said = r
            .warnings
            .iter()
            .any(|w| w.contains("the label puts the defect in the"));
        assert_eq!(
            (r.bearing.as_str(), said),
            (bearing, finding),
            "{} {channel}: {:?}",
            file.display(),
            r.warnings
        );
        assert_eq!(r.base, wearsim_core::presets::by_name(bearing).unwrap());
        assert_eq!(r.defect.map(|d| d.location), Some("inner"));
    }
}

/// The gap simulates a record at the speed `analyze` reads it at: record 279 stores the
/// 3 hp speed (1 732 rpm) for a 1 hp run whose 1× line stands at 1 774 rpm (data README),
/// and is matched at its line's speed with a finding; `--trust-rpm` keeps the stored one. A
/// record whose stored speed its line confirms is not touched. Data-backed.
#[test]
fn gap_simulates_a_record_at_the_speed_its_shaft_line_shows() {
    use wearsim_host::gap::records::{load, Overrides};
    let Some(data) = wearsim_host::io::data_dir().expect("data folder required when CI=true")
    else {
        return;
    };
    let fe = data.join("cwru/12k_Fan_End_IR007_1_279.mat");
    let channel = |c: &str| Overrides {
        channel: Some(c.into()),
        ..Default::default()
    };
    let r = load(&fe, &channel("FE")).expect("record");
    assert_eq!(r.rpm_source, "shaft line");
    assert!((r.rpm / 1774.0 - 1.0).abs() < 0.005, "{}", r.rpm);
    assert!(
        r.warnings.iter().any(|w| w.contains("speed refined")),
        "{:?}",
        r.warnings
    );
    let trusted = Overrides {
        trust_rpm: true,
        ..channel("FE")
    };
    let kept = load(&fe, &trusted).expect("record");
    assert_eq!((kept.rpm, kept.rpm_source.as_str()), (1732.0, "file"));
    let de = load(
        &data.join("cwru/12k_Drive_End_IR007_1_106.mat"),
        &channel("DE"),
    )
    .expect("record");
    assert_eq!((de.rpm, de.rpm_source.as_str()), (1772.0, "file"));
}

/// `gap --fs` against a record whose sidecar states another rate is refused like
/// `analyze`'s (it was once used silently, matching the record at the wrong rate).
#[test]
fn gap_refuses_an_fs_contradicting_the_sidecar() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let rec = csv(dir.path(), "rec.csv", 24_000);
    std::fs::write(
        dir.path().join("rec.json"),
        r#"{"fs": 12000, "units": "m/s^2"}"#,
    )
    .unwrap();
    let o = out.display().to_string();
    let args = [
        "gap",
        "--real",
        &rec,
        "--bearing",
        "cwru-6205-de",
        "--defect",
        "inner:0.007in",
        "--fs",
        "48000",
        "--out",
        &o,
    ];
    bad(
        &args,
        "field fs: --fs 48000 Hz contradicts the sample rate 12000 Hz",
        &out,
    );
}

/// `--units`: a record that states no unit (an NPY array, a CSV column named `accel`) takes
/// the argument's — g scaled by 9.80665 to m/s² — and one that states a unit keeps it: an
/// argument that disagrees is refused by name, an unknown unit too.
#[test]
fn units_argument_fills_a_missing_unit_and_never_overrides_a_stated_one() {
    use wearsim_host::gap::records::{load, Overrides};
    let dir = tempfile::tempdir().unwrap();
    let body = std::fs::read_to_string(csv(dir.path(), "x.csv", 24_000))
        .unwrap()
        .replace("accel_m_s2\n", "accel\n");
    let f = dir.path().join("plain.csv");
    std::fs::write(&f, body).unwrap();
    std::fs::write(
        dir.path().join("plain.json"),
        r#"{"fs": 12000, "rpm": 1500}"#,
    )
    .unwrap();
    let o = |units: Option<&str>| Overrides {
        bearing: Some("cwru-6205-de".into()),
        defect: Some(None),
        units: units.map(String::from),
        ..Default::default()
    };
    let e = load(&f, &o(None)).unwrap_err();
    assert!(
        e.contains("unit `unknown`") && e.contains("--units g"),
        "{e}"
    );
    let g = load(&f, &o(Some("g"))).expect("--units g");
    let ms2 = load(&f, &o(Some("m/s^2"))).expect("--units m/s^2");
    assert_eq!(g.accel.len(), ms2.accel.len());
    for (a, b) in g.accel.iter().zip(&ms2.accel).take(100) {
        assert!(
            (a - 9.80665 * b).abs() <= 1e-12 * a.abs().max(1.0),
            "{a} {b}"
        );
    }
    let e = load(&f, &o(Some("furlongs"))).unwrap_err();
    assert!(
        e.contains("--units `furlongs`") && e.contains("g or m/s^2"),
        "{e}"
    );
    // The sidecar states g: the same unit is accepted, another refused.
    std::fs::write(
        dir.path().join("plain.json"),
        r#"{"fs": 12000, "rpm": 1500, "units": "g"}"#,
    )
    .unwrap();
    let stated = load(&f, &o(Some("g"))).expect("agreeing --units");
    assert_eq!(stated.accel, g.accel);
    let e = load(&f, &o(Some("m/s^2"))).unwrap_err();
    assert!(
        e.contains("--units m/s^2 contradicts the file's unit `g`"),
        "{e}"
    );
}
