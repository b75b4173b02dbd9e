//! Defects found by an outside review that ran `gap`, `features` and `life` on records and
//! tables the project's own tests did not have (other sample rates, other labs' layouts,
//! hand-written tables); one test per defect, each named after what must hold.

use crate::support::{gap_life, noise, refused, s, wearsim};
use wearsim_core::effects::{EffectKind, Effects};
use wearsim_host::gap::space::{space, Context};

/// A record of `m/s^2` at 51.2 kHz with a DC offset made `gap` exit 1 with
/// "sensor.noise = 100.00000000000001 is out of range": the fitted range was clamped to
/// the catalogue's 100, but `lo·(hi/lo)^1` rounded one ulp above it. Every effect's fit
/// space, at both ends, must give values its own range check accepts, whatever the
/// record's level and rate.
#[test]
fn fit_space_ends_stay_inside_the_catalogue_bounds_at_any_level() {
    for fs in [12_000.0, 25_600.0, 48_828.125, 51_200.0, 97_656.25] {
        for k in 0..400 {
            let rms = 10f64.powf(-3.0 + 7.0 * f64::from(k) / 400.0) * 1.000_001_3;
            let ctx = Context {
                fs,
                shaft_hz: 29.95,
                rms,
                mains_hz: 50.0,
                preload_max: 0.5,
            };
            for kind in EffectKind::ALL {
                let sp = space(kind, &ctx);
                for u in [0.0, 1.0] {
                    let coords = vec![u; sp.fitted.len()];
                    let mut fx = Effects::NONE;
                    if let Err(e) = sp.apply(&mut fx, &coords) {
                        panic!("fs {fs}, rms {rms}, u {u}: {e}");
                    }
                }
            }
        }
    }
}

/// A float WAV's unit came only from `wav.unit` or `units[wav.column]`: a sidecar with
/// `"units": "g"` or `"units": {"0": "g"}` (what the gap's own error asks for) left it
/// `unknown`, so `gap` refused the record with advice that did not work.
#[test]
fn a_float_wav_takes_the_unit_its_sidecar_gives_the_file_or_the_channel() {
    let dir = tempfile::tempdir().expect("tempdir");
    let x = noise(60_000);
    for (name, side) in [
        ("whole", r#"{"fs": 25600, "rpm": 1797, "units": "g"}"#),
        ("chan", r#"{"fs": 25600, "rpm": 1797, "units": {"0": "g"}}"#),
    ] {
        let wav = dir.path().join(format!("{name}.wav"));
        let spec = hound::WavSpec {
            channels: 1,
            sample_rate: 25_600,
            bits_per_sample: 32,
            sample_format: hound::SampleFormat::Float,
        };
        let mut w = hound::WavWriter::create(&wav, spec).expect("create wav");
        for v in &x {
            w.write_sample(*v as f32).expect("sample");
        }
        w.finalize().expect("finalize");
        std::fs::write(dir.path().join(format!("{name}.json")), side).expect("sidecar");
        let o = wearsim(&["analyze", s(&wav), "--bearing", "cwru-6205-de", "--json"]);
        let out = String::from_utf8_lossy(&o.stdout);
        assert_eq!(
            o.status.code(),
            Some(0),
            "{name}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        assert!(
            out.contains(r#""unit": "g""#),
            "{name}: unit not g in {out}"
        );
    }
    // An integer WAV without `wav.scale` stays full scale, and the gap says how to scale it.
    let wav = dir.path().join("int.wav");
    let spec = hound::WavSpec {
        channels: 1,
        sample_rate: 25_600,
        bits_per_sample: 16,
        sample_format: hound::SampleFormat::Int,
    };
    let mut w = hound::WavWriter::create(&wav, spec).expect("create wav");
    for v in &x {
        w.write_sample((v * 30_000.0) as i16).expect("sample");
    }
    w.finalize().expect("finalize");
    std::fs::write(
        dir.path().join("int.json"),
        r#"{"fs": 25600, "rpm": 1797, "units": "g"}"#,
    )
    .expect("sidecar");
    let out = dir.path().join("gap");
    let o = wearsim(&[
        "gap",
        "--real",
        s(&wav),
        "--bearing",
        "cwru-6205-de",
        "--out",
        s(&out),
    ]);
    refused(&o, &["int.wav", "FS", "wav", "scale"]);
}

/// A MAT file of no known layout (or Paderborn's) had unit `unknown` and no way to set
/// it: `gap` asked for a sidecar that the MAT reader never read. Its sidecar now gives the
/// unit (only the unit; other keys are named in a warning).
#[test]
fn a_generic_mat_file_takes_its_unit_from_a_sidecar() {
    let dir = tempfile::tempdir().expect("tempdir");
    let x = noise(60_000);
    let bytes =
        wearsim_host::io::mat::mat5_bytes(&[("acc", &x), ("fs", &[25_600.0]), ("rpm", &[1797.0])]);
    let mat = dir.path().join("lab.mat");
    std::fs::write(&mat, bytes).expect("write mat");
    let args = ["analyze", s(&mat), "--bearing", "cwru-6205-de", "--json"];
    let o = wearsim(&args);
    assert!(String::from_utf8_lossy(&o.stdout).contains(r#""unit": "unknown""#));
    std::fs::write(
        dir.path().join("lab.json"),
        r#"{"units": {"acc": "m/s^2"}, "fs": 1}"#,
    )
    .expect("sidecar");
    let o = wearsim(&args);
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(out.contains(r#""unit": "m/s^2""#), "{out}");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("`units`/`unit` only") && err.contains("`fs`"),
        "{err}"
    );
}

/// At a rate that is no whole number of Hz (48 828.125 Hz, a common DAQ rate) a record of
/// exactly 1.5 s holds 73 242 samples, and `gap` refused it: "1.500 s is too short …
/// one record must hold at least 1.5 s (73243 samples)". Lengths are counted to the
/// nearest sample.
#[test]
fn a_record_of_exactly_the_minimum_length_passes_at_a_fractional_rate() {
    let dir = tempfile::tempdir().expect("tempdir");
    let fs = 48_828.125;
    let x = noise((1.5 * fs) as usize);
    assert_eq!(x.len(), 73_242);
    let mut csv = String::from("accel\n");
    for v in &x {
        csv.push_str(&format!("{v}\n"));
    }
    let rec = dir.path().join("rec.csv");
    std::fs::write(&rec, csv).expect("csv");
    std::fs::write(
        dir.path().join("rec.json"),
        format!(r#"{{"fs": {fs}, "rpm": 1797, "units": "g"}}"#),
    )
    .expect("sidecar");
    let out = dir.path().join("gap");
    let o = wearsim(&[
        "gap",
        "--real",
        s(&rec),
        "--bearing",
        "cwru-6205-de",
        "--defect",
        "none",
        "--effects",
        "sensor",
        "--no-calibration",
        "--jobs",
        "1",
        "--out",
        s(&out),
        "--json",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!err.contains("too short"), "{err}");
    assert_eq!(o.status.code(), Some(0), "{err}");
}

/// Writes a documented feature table `name.csv` of `n` rows and its sidecar `name.json`
/// (the worked example's rig, 13 balls, 3600 s apart) with `rate` Hz, `bom` before both.
fn bom_table(
    dir: &std::path::Path,
    name: &str,
    n: usize,
    rate: f64,
    bom: bool,
) -> std::path::PathBuf {
    let b = if bom { "\u{feff}" } else { "" };
    let mut csv = format!("{b}snapshot,time_s,rms,kurtosis,crest_factor,skewness,peak\n");
    for k in 0..n {
        let rms = 0.5 + 0.001 * (k % 7) as f64;
        csv.push_str(&format!(
            "{k},{},{rms},3.0,4.5,0.0,{}\n",
            3600.0 * k as f64,
            4.5 * rms
        ));
    }
    let p = dir.join(format!("{name}.csv"));
    std::fs::write(&p, csv).expect("table");
    let side = format!(
        r#"{b}{{"format": "wearsim-feature-table", "format_version": 1, "source": "probe",
 "bearing": {{"geometry": {{"elements": 13, "ball_mm": 3.5, "pitch_mm": 25.6, "angle_deg": 0.0}}, "id": "b1"}},
 "channel": "horiz", "unit": "g", "rpm": 1800.0, "radial_load_n": 4000.0,
 "sample_rate_hz": {rate}, "snapshot_samples": 64, "snapshot_interval_s": 3600.0,
 "failure_mode": "outer-race", "n_snapshots": {n}}}"#
    );
    std::fs::write(dir.join(format!("{name}.json")), side).expect("sidecar");
    p
}

/// A feature table saved by a spreadsheet as "CSV UTF-8" starts with a byte order mark:
/// it was refused as "missing column `snapshot`" (the column was there), and a sidecar
/// with one as "expected value at line 1 column 1".
#[test]
fn a_feature_table_and_sidecar_with_a_byte_order_mark_are_read() {
    let dir = tempfile::tempdir().expect("tempdir");
    let a = bom_table(dir.path(), "a", 12, 25_600.0, true);
    let b = bom_table(dir.path(), "b", 12, 25_600.0, true);
    let out = dir.path().join("gap");
    let o = gap_life(&a, &b, &out, &[]);
    // Read through to the life's own check: 12 snapshots are too few for its stages.
    refused(&o, &["first-tenth stage"]);
}

/// A table's `sample_rate_hz` that the simulator cannot render was refused naming `fs`
/// ("fs = 50 is out of range", "fs: internal step too large … use an internal rate of at
/// least 89824 Hz"), neither the sidecar nor its field, nor a rate a table could have.
#[test]
fn a_table_rate_the_simulator_cannot_render_is_refused_naming_the_sidecar_field() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("gap");
    for (rate, needles) in [
        (
            50.0,
            vec![
                "sidecar field `sample_rate_hz`",
                "50 Hz",
                "100..=1000000 Hz",
            ],
        ),
        (
            1000.0,
            vec![
                "sidecar field `sample_rate_hz`",
                "1000 Hz is too low",
                "at least",
            ],
        ),
    ] {
        let a = bom_table(dir.path(), "a", 400, rate, false);
        let b = bom_table(dir.path(), "b", 400, rate, false);
        let o = gap_life(&a, &b, &out, &[]);
        let mut n = needles.clone();
        n.push("a.json");
        refused(&o, &n);
        assert!(!out.exists(), "{rate} Hz: an output was written");
    }
}

/// `life --lives` over load scales where one life runs into the cycle cap said only "the
/// bearing did not fail within the cycle cap", not which load scale or seed; then (stop
/// 41) it still threw the whole run away. A life still running at the cap is now a
/// suspension (right-censored), as in an endurance test stopped at a set number of
/// revolutions: the run completes, the CSV marks it, and a load where fewer than three
/// lives failed has no Weibull fit instead of a wrong one.
#[test]
fn a_life_statistics_run_keeps_lives_that_reach_the_cap_as_suspensions() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("lives");
    let o = wearsim(&[
        "life",
        "--lives",
        "3",
        "--loads",
        "0.05,1",
        "--cycles",
        "1e7",
        "--snapshot-every",
        "200000",
        "--window",
        "0.05",
        "--out",
        s(&out),
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("json");
    assert_eq!(v["cycle_cap"], 1e7);
    let light = &v["groups"][0];
    assert_eq!(light["load_scale"], 0.05);
    assert_eq!(
        (light["failed"].as_u64(), light["suspended"].as_u64()),
        (Some(0), Some(3))
    );
    assert!(light["weibull"].is_null() && light["first_spall"]["weibull"].is_null());
    assert!(light["onset_median"].is_null(), "{light}");
    let nominal = &v["groups"][1];
    let (f, su) = (nominal["failed"].as_u64(), nominal["suspended"].as_u64());
    assert_eq!(f.zip(su).map(|(a, b)| a + b), Some(3), "{nominal}");
    let csv = std::fs::read_to_string(out.join("lives.csv")).expect("lives.csv");
    let head: Vec<&str> = csv.lines().next().unwrap_or("").split(',').collect();
    let col = |n: &str| head.iter().position(|h| *h == n).expect(n);
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    assert_eq!(rows.len(), 6);
    for r in rows.iter().filter(|r| r[col("load_scale")] == "0.05") {
        assert_eq!(r[col("suspended")], "true", "{r:?}");
        let life: f64 = r[col("life_revs")].parse().expect("life");
        assert!(life >= 1e7, "a suspension before the cap: {r:?}");
        assert_eq!(r[col("onset_fraction")], "", "{r:?}");
    }
}

/// `life --snapshot-every 1` rendered and kept a window per revolution for the whole life
/// (tens of millions, growing memory for hours); a life is now bounded to
/// `MAX_LIFE_WINDOWS` windows and refused (exit 2) naming the flag to raise.
#[test]
fn a_life_needing_more_windows_than_the_bound_is_refused_naming_snapshot_every() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("life");
    let o = wearsim(&[
        "life",
        "--snapshot-every",
        "1",
        "--window",
        "0.02",
        "--out",
        s(&out),
        "--json",
    ]);
    refused(&o, &["100000 windows", "--snapshot-every"]);
    assert!(!out.join("life-summary.json").exists());
}

/// A sidecar whose `bearing` lacks `id` was refused naming `id`, a top-level key the format
/// does not have; a held-out life at another speed than the training life's was refused
/// saying that `rpm` differs, without either value.
#[test]
fn table_sidecar_errors_name_the_dotted_key_and_both_values() {
    let dir = tempfile::tempdir().expect("tempdir");
    let a = bom_table(dir.path(), "a", 400, 25_600.0, false);
    let b = bom_table(dir.path(), "b", 400, 25_600.0, false);
    let out = dir.path().join("gap");
    let run = || gap_life(&a, &b, &out, &[]);
    let edit = |name: &str, from: &str, to: &str| {
        let p = dir.path().join(name);
        let t = std::fs::read_to_string(&p).expect("sidecar");
        assert!(t.contains(from), "{t}");
        std::fs::write(&p, t.replace(from, to)).expect("sidecar");
    };
    edit("b.json", r#""rpm": 1800.0"#, r#""rpm": 1500.0"#);
    refused(&run(), &["b.json", "`rpm` differs", "1500 against 1800"]);
    edit("a.json", r#", "id": "b1""#, "");
    refused(&run(), &["a.json", "`bearing.id`"]);
    assert!(!out.exists(), "an output was written");
}

/// `simulate --fs 1000` (inside the documented 100..=1e6) was refused as "use an internal
/// rate of at least 12072 Hz", a rate no flag sets: the message now gives the output rate
/// that works, and that rate is accepted. (500 Hz since stop 51: with 16 internal steps per
/// sample the reference preset runs at 1 kHz.)
#[test]
fn a_rate_too_low_for_the_bearing_is_refused_with_the_output_rate_that_works() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("sim");
    let run = |fs: &str| {
        wearsim(&[
            "simulate",
            "--fs",
            fs,
            "--duration",
            "0.05",
            "--out",
            s(&out),
        ])
    };
    let o = run("500");
    refused(&o, &["fs", "an output rate fs of at least"]);
    assert!(!out.exists(), "an output was written");
    let msg = String::from_utf8_lossy(&o.stderr).to_string();
    let fs = msg
        .split("an output rate fs of at least ")
        .nth(1)
        .and_then(|t| t.split(' ').next())
        .expect("a rate in the message");
    let ok = run(fs);
    assert_eq!(
        ok.status.code(),
        Some(0),
        "{fs} Hz: {}",
        String::from_utf8_lossy(&ok.stderr)
    );
}
