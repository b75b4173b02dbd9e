//! `wearsim analyze` as a user runs it: synthetic records with a known fault (the answer is
//! set by construction), JSON output, plots, wearsim's own simulate output, and bad input
//! (exit code 2 with a message naming the problem, never a panic).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const FS: f64 = 12_000.0;
const RPM: f64 = 1797.0;
const BEARING: &str = "cwru-6205-de";

fn wearsim(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wearsim"))
        .args(args)
        .output()
        .expect("the wearsim binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// 4 s of an outer-race fault: impulses at the kinematic BPFO of the 6205 at 1797 rpm with
/// 1 % random slip of each interval (real rolling elements slip, Randall & Antoni 2011; a
/// strictly periodic train would be pure discrete lines, which pre-whitening removes), each
/// ringing a 3 kHz resonance (damping ratio 5 %), in white noise.
fn outer_race_signal() -> (Vec<f64>, wearsim_host::analysis::FaultFrequencies) {
    let kin = wearsim_host::kinematics::of_preset(BEARING, RPM).expect("preset exists");
    let n = 4 * FS as usize;
    let mut x = wearsim_host::analysis::synth::gaussian_noise(n, 0.3, 7);
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut uniform = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let (wn, zeta): (f64, f64) = (2.0 * std::f64::consts::PI * 3000.0, 0.05);
    let wd = wn * (1.0 - zeta * zeta).sqrt();
    let ring = (8.0 / (zeta * wn) * FS) as usize;
    let mut t = 0.01;
    while t < n as f64 / FS {
        let i0 = (t * FS).ceil() as usize;
        for (i, v) in x.iter_mut().enumerate().skip(i0).take(ring) {
            let dt = i as f64 / FS - t;
            *v += (-zeta * wn * dt).exp() * (wd * dt).sin();
        }
        t += (1.0 + 0.01 * uniform()) / kin.bpfo;
    }
    (x, kin)
}

fn write_csv(path: &Path, x: &[f64]) {
    let mut s = String::from("accel_g\n");
    for v in x {
        s.push_str(&format!("{v}\n"));
    }
    std::fs::write(path, s).expect("write csv");
}

fn write_wav(path: &Path, x: &[f64]) {
    let spec = hound::WavSpec {
        channels: 1,
        sample_rate: FS as u32,
        bits_per_sample: 32,
        sample_format: hound::SampleFormat::Float,
    };
    let mut w = hound::WavWriter::create(path, spec).expect("create wav");
    for v in x {
        w.write_sample(*v as f32).expect("write sample");
    }
    w.finalize().expect("finalize wav");
}

/// `wearsim simulate --config` of scenario text `toml` (plus `extra` arguments) into
/// `dir/name`; the output folder and its sidecar.
fn simulate_scenario(
    dir: &Path,
    name: &str,
    toml: &str,
    extra: &[&str],
) -> (PathBuf, serde_json::Value) {
    let cfg = dir.join(format!("{name}.toml"));
    std::fs::write(&cfg, toml).unwrap();
    let out = dir.join(name);
    let (cfg_s, out_s) = (cfg.to_string_lossy(), out.to_string_lossy());
    let mut args = vec!["simulate", "--config", &cfg_s, "--out", &out_s, "--json"];
    args.extend_from_slice(extra);
    let o = wearsim(&args);
    assert!(o.status.success(), "simulate failed: {}", stderr(&o));
    let side = serde_json::from_slice(&std::fs::read(out.join("simulate.json")).unwrap())
        .expect("sidecar JSON");
    (out, side)
}

fn json_of(o: &Output) -> serde_json::Value {
    assert!(o.status.success(), "failed: {}", stderr(o));
    serde_json::from_slice(&o.stdout).expect("stdout is one JSON object")
}

#[test]
fn outer_race_csv_is_diagnosed_outer_race() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (x, kin) = outer_race_signal();
    let csv = dir.path().join("or.csv");
    write_csv(&csv, &x);
    let rpm = RPM.to_string();
    let fs = FS.to_string();
    let csv_s = csv.to_string_lossy();
    let args = [
        "analyze",
        &csv_s,
        "--fs",
        &fs,
        "--rpm",
        &rpm,
        "--bearing",
        BEARING,
        "--json",
    ];
    let v = json_of(&wearsim(&args));
    assert_eq!(v["diagnosis"]["family"], "OuterRace", "{v:#}");
    // Evidence: the outer-race family found its harmonics, fitted at the impulse rate.
    let outer = &v["diagnosis"]["evidence"][1];
    assert_eq!(outer["family"], "OuterRace");
    assert!(outer["found"].as_u64().unwrap_or(0) >= 4, "{outer:#}");
    let f0 = outer["fundamental_hz"].as_f64().unwrap_or(0.0);
    assert!(
        (f0 - kin.bpfo).abs() < 0.5,
        "fitted {f0} vs BPFO {}",
        kin.bpfo
    );
    // The kurtogram band contains the 3 kHz resonance the impulses ring.
    let band = &v["kurtogram"]["band_hz"];
    let (lo, hi) = (
        band[0].as_f64().unwrap_or(0.0),
        band[1].as_f64().unwrap_or(0.0),
    );
    assert!(lo < 3000.0 && 3000.0 < hi, "band {lo}-{hi}");
    // Statistics of an impulsive signal; zones present; speed and bearing from arguments.
    assert!(v["stats"]["kurtosis"].as_f64().unwrap_or(0.0) > 3.0);
    assert!(v["zones"]["levels"]["total"].as_f64().unwrap_or(0.0) > 0.0);
    assert_eq!(v["rpm_source"], "argument");
    assert_eq!(v["bearing_source"], "argument");
    assert_eq!(v["samples"], x.len());

    // The human-readable form names the decision.
    let o = wearsim(&args[..args.len() - 1]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("diagnosis: outer race"), "{text}");
    assert!(text.contains("demodulation band"), "{text}");
    assert!(text.contains("| 1797 rpm (argument: --rpm) |"), "{text}");
}

/// The header says where a speed was found when the category "file" would mislead: an
/// XJTU-SY snapshot states none, its folder name does (`35Hz12kN`: 2100 rpm).
#[test]
fn the_header_names_a_folder_names_speed() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path().join("35Hz12kN/Bearing1_1");
    std::fs::create_dir_all(&d).expect("mkdir");
    let (x, _) = outer_race_signal();
    let mut s = String::from("Horizontal_vibration_signals,Vertical_vibration_signals\n");
    for v in &x {
        s.push_str(&format!("{v},{}\n", 0.5 * v));
    }
    let f = d.join("1.csv");
    std::fs::write(&f, s).expect("write");
    let o = wearsim(&["analyze", &f.to_string_lossy()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("| 2100 rpm (file: folder name `35Hz12kN`"),
        "{text}"
    );
}

#[test]
fn wav_plots_are_written() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (x, _) = outer_race_signal();
    let wav = dir.path().join("or.wav");
    write_wav(&wav, &x);
    let plots = dir.path().join("plots");
    let rpm = RPM.to_string();
    let v = json_of(&wearsim(&[
        "analyze",
        &wav.to_string_lossy(),
        "--rpm",
        &rpm,
        "--bearing",
        BEARING,
        "--plot",
        &plots.to_string_lossy(),
        "--json",
    ]));
    assert_eq!(v["diagnosis"]["family"], "OuterRace");
    assert_eq!(v["fs"], FS);
    for name in ["spectrum", "envelope", "kurtogram"] {
        for ext in ["png", "svg"] {
            let p = plots.join(format!("{name}.{ext}"));
            let len = std::fs::metadata(&p).map(|m| m.len()).unwrap_or(0);
            assert!(len > 1000, "{} missing or empty", p.display());
        }
        let svg = std::fs::read_to_string(plots.join(format!("{name}.svg"))).unwrap_or_default();
        assert!(
            svg.contains("frequency (Hz)"),
            "{name}.svg lacks its axis label"
        );
    }
    let svg = std::fs::read_to_string(plots.join("envelope.svg")).unwrap_or_default();
    assert!(
        svg.contains("BPFO") && svg.contains("BPFI"),
        "kinematic labels"
    );
    assert_eq!(v["plots"].as_array().map(Vec::len), Some(6));
}

#[test]
fn simulate_output_is_analysed_with_its_sidecar() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("sim");
    let o = wearsim(&[
        "simulate",
        "--preset",
        BEARING,
        "--duration",
        "2",
        "--out",
        &out.to_string_lossy(),
        "--json",
    ]);
    assert!(o.status.success(), "simulate failed: {}", stderr(&o));
    for file in ["simulate.csv", "simulate.wav"] {
        let v = json_of(&wearsim(&[
            "analyze",
            &out.join(file).to_string_lossy(),
            "--json",
        ]));
        // Speed and geometry come from the sidecar, not from arguments.
        assert_eq!(v["bearing"], BEARING, "{file}");
        assert_eq!(v["bearing_source"], "file");
        assert_eq!(v["rpm_source"], "file");
        let rpm = v["rpm"].as_f64().unwrap_or(0.0);
        assert!((rpm - 1797.0).abs() < 1.0, "{file}: rpm {rpm}");
        assert!(v["diagnosis"]["family"].is_string());
    }
}

fn assert_input_error(o: &Output, needles: &[&str]) {
    assert_eq!(o.status.code(), Some(2), "stderr: {}", stderr(o));
    let e = stderr(o);
    assert!(!e.contains("panicked"), "{e}");
    for n in needles {
        assert!(e.contains(n), "message lacks {n:?}: {e}");
    }
}

fn mat_file(dir: &Path) -> PathBuf {
    let x: Vec<f64> = outer_race_signal().0.into_iter().take(40_000).collect();
    let bytes = wearsim_host::io::mat::mat5_bytes(&[("X100_DE_time", &x), ("X100RPM", &[1797.0])]);
    let p = dir.join("12k_Drive_End_OR007@6_0_100.mat");
    std::fs::write(&p, bytes).expect("write mat");
    p
}

#[test]
fn bad_input_exits_2_naming_the_problem() {
    let dir = tempfile::tempdir().expect("tempdir");
    // Missing file.
    let missing = dir.path().join("nope.csv");
    assert_input_error(
        &wearsim(&["analyze", &missing.to_string_lossy()]),
        &["nope.csv"],
    );
    // A valid .mat analyses (speed and bearing from the file) ...
    let mat = mat_file(dir.path());
    let v = json_of(&wearsim(&["analyze", &mat.to_string_lossy(), "--json"]));
    assert_eq!(v["diagnosis"]["family"], "OuterRace");
    // ... an unknown channel is named with the ones available ...
    assert_input_error(
        &wearsim(&["analyze", &mat.to_string_lossy(), "--channel", "FE"]),
        &["FE", "DE", "12k_Drive_End_OR007@6_0_100.mat"],
    );
    // ... and the same file cut in half is a truncation error naming it.
    let bytes = std::fs::read(&mat).expect("read mat");
    let cut = dir.path().join("12k_Drive_End_IR007_0_101.mat");
    std::fs::write(&cut, &bytes[..bytes.len() / 2]).expect("write cut");
    assert_input_error(
        &wearsim(&["analyze", &cut.to_string_lossy()]),
        &["12k_Drive_End_IR007_0_101.mat"],
    );
    // No speed anywhere: say so and how to give it.
    let wav = dir.path().join("norpm.wav");
    write_wav(&wav, &outer_race_signal().0);
    assert_input_error(
        &wearsim(&["analyze", &wav.to_string_lossy(), "--bearing", BEARING]),
        &["norpm.wav", "--rpm"],
    );
    // No geometry: name the presets.
    let rpm = RPM.to_string();
    assert_input_error(
        &wearsim(&["analyze", &wav.to_string_lossy(), "--rpm", &rpm]),
        &["--bearing", BEARING],
    );
    // Unknown preset, absurd speed, NaN in a CSV.
    assert_input_error(
        &wearsim(&[
            "analyze",
            &wav.to_string_lossy(),
            "--rpm",
            &rpm,
            "--bearing",
            "6205",
        ]),
        &["6205", "thesis-61810"],
    );
    assert_input_error(
        &wearsim(&[
            "analyze",
            &wav.to_string_lossy(),
            "--rpm=-5",
            "--bearing",
            BEARING,
        ]),
        &["rpm"],
    );
    let nan = dir.path().join("nan.csv");
    std::fs::write(&nan, "x\n1\n2\nNaN\n3\n").expect("write csv");
    assert_input_error(
        &wearsim(&[
            "analyze",
            &nan.to_string_lossy(),
            "--fs",
            "1000",
            "--rpm",
            &rpm,
            "--bearing",
            BEARING,
        ]),
        &["nan.csv"],
    );
    // A record too short for the analysis is bad input too, not a crash.
    let short = dir.path().join("short.csv");
    std::fs::write(&short, "x\n1\n2\n3\n4\n5\n").expect("write csv");
    assert_input_error(
        &wearsim(&[
            "analyze",
            &short.to_string_lossy(),
            "--fs",
            "1000",
            "--rpm",
            &rpm,
            "--bearing",
            BEARING,
        ]),
        &["short.csv"],
    );
}

/// A wearsim run whose `[bearing]` overrides the preset's geometry: the sidecar says
/// `custom` and carries the resolved model as structured JSON, and `analyze` takes the
/// geometry from it, so the fault frequencies are the simulated bearing's, not the preset's.
#[test]
fn simulate_output_with_a_bearing_override_is_analysed_with_its_geometry() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (out, side) = simulate_scenario(
        dir.path(),
        "sim",
        &format!("preset = \"{BEARING}\"\nduration = 1.0\n[bearing]\nelements = 12\n"),
        &[],
    );
    assert_eq!(side["bearing"], "custom");
    assert_eq!(side["model"]["bearing"]["elements"], 12);
    let model: wearsim_core::ModelConfig =
        serde_json::from_value(side["model"].clone()).expect("structured model");
    let preset = wearsim_host::kinematics::of_preset(BEARING, RPM).unwrap();
    let v = json_of(&wearsim(&[
        "analyze",
        &out.join("simulate.csv").to_string_lossy(),
        "--json",
    ]));
    assert_eq!(v["bearing"], "custom");
    assert_eq!(v["bearing_source"], "file");
    let rpm = v["rpm"].as_f64().unwrap();
    let want = wearsim_core::kinematics::FaultOrders::of(&model.bearing).at(rpm / 60.0, 0.0);
    let got = |k: &str| v["kinematics"][k].as_f64().unwrap();
    for (k, w) in [("bpfo", want.bpfo), ("bpfi", want.bpfi), ("ftf", want.ftf)] {
        assert!((got(k) - w).abs() < 1e-9 * w, "{k}: {} vs {w}", got(k));
    }
    // 12 elements instead of 9: BPFI is a third higher than the preset's.
    assert!(
        got("bpfi") > 1.3 * preset.bpfi,
        "{} vs {}",
        got("bpfi"),
        preset.bpfi
    );
    // The preset's own run still names the preset (its geometry is the preset's).
    let out2 = dir.path().join("sim2");
    let o = wearsim(&[
        "simulate",
        "--preset",
        BEARING,
        "--duration",
        "0.5",
        "--out",
        &out2.to_string_lossy(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let side: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out2.join("simulate.json")).unwrap()).unwrap();
    assert_eq!(side["bearing"], BEARING);
    assert!(side["model"].is_object());
}

/// A sidecar written before the structured model (`model` as a Rust `Debug` string) is
/// still read for fs and rpm; its geometry is its `bearing` preset's.
#[test]
fn old_sidecar_with_a_debug_model_string_is_read() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (x, _) = outer_race_signal();
    let csv = dir.path().join("old.csv");
    let mut text = String::from("time_s,accel_m_s2\n");
    for (i, v) in x.iter().enumerate() {
        text.push_str(&format!("{},{v}\n", i as f64 / FS));
    }
    std::fs::write(&csv, text).unwrap();
    std::fs::write(
        dir.path().join("old.json"),
        format!(
            r#"{{"fs": {FS}, "rpm": {RPM}, "bearing": "{BEARING}", "model": "ModelConfig {{ bearing: BearingGeometry {{ .. }} }}"}}"#
        ),
    )
    .unwrap();
    let v = json_of(&wearsim(&["analyze", &csv.to_string_lossy(), "--json"]));
    assert_eq!(v["bearing"], BEARING);
    assert_eq!(v["fs"], FS);
    assert_eq!(v["diagnosis"]["family"], "OuterRace");
}

/// `--config SCENARIO.toml` describes the bearing (and, for a file without one, the speed)
/// of a record, in the `simulate --config` format: the outer-race record is diagnosed with
/// the scenario's preset and speed, a `[bearing]` override moves the defect frequencies by
/// its closed form, and the option refuses company it cannot keep.
#[test]
fn a_scenario_file_describes_the_bearing_and_speed_of_a_plain_record() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (x, kin) = outer_race_signal();
    let csv = dir.path().join("or.csv");
    write_csv(&csv, &x);
    let (csv_s, fs) = (csv.to_string_lossy().into_owned(), FS.to_string());
    // `analyze or.csv --fs FS --config <a scenario holding `toml`> [extra…]`.
    let with_scenario = |name: &str, toml: String, extra: &[&str]| {
        let path = dir.path().join(name);
        std::fs::write(&path, toml).expect("write scenario");
        let path = path.to_string_lossy().into_owned();
        let mut args = vec!["analyze", &csv_s, "--fs", &fs, "--config", &path];
        args.extend_from_slice(extra);
        wearsim(&args)
    };
    let rig = format!("preset = \"{BEARING}\"\n[speed]\nrpm = {RPM}\n");
    let v = json_of(&with_scenario("rig.toml", rig.clone(), &["--json"]));
    assert_eq!(v["diagnosis"]["family"], "OuterRace", "{v:#}");
    assert_eq!(v["bearing"], BEARING);
    assert_eq!(v["bearing_source"], "config");
    assert_eq!(v["rpm_source"], "config");
    assert!((v["rpm"].as_f64().unwrap() - RPM).abs() < 1e-9);
    let bpfo = v["kinematics"]["bpfo"].as_f64().unwrap();
    assert!(
        (bpfo - kin.bpfo).abs() < 1e-9 * kin.bpfo,
        "{bpfo} vs {}",
        kin.bpfo
    );

    // `--rpm` still wins over the scenario's speed.
    let v = json_of(&with_scenario(
        "rig.toml",
        rig.clone(),
        &["--rpm", "1500", "--json"],
    ));
    assert_eq!(v["rpm_source"], "argument");
    assert!((v["rpm"].as_f64().unwrap() - 1500.0).abs() < 1e-9);

    // 12 elements instead of 9: BPFO = (n/2)(1 − d/D cos α) f_r scales by exactly 12/9.
    let twelve = format!("{rig}[bearing]\nelements = 12\n");
    let v = json_of(&with_scenario("twelve.toml", twelve, &["--json"]));
    assert_eq!(v["bearing"], "custom");
    let bpfo12 = v["kinematics"]["bpfo"].as_f64().unwrap();
    let want = kin.bpfo * 12.0 / 9.0;
    assert!((bpfo12 - want).abs() < 1e-9 * want, "{bpfo12} vs {want}");

    // Refusals: exit 2, the problem named.
    let o = with_scenario("rig.toml", rig, &["--bearing", BEARING]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--bearing"), "{}", stderr(&o));
    let o = with_scenario("bad.toml", "[bearing]\nballs = 9\n".into(), &[]);
    assert_input_error(&o, &["--config", "balls"]);
    let negative = format!("preset = \"{BEARING}\"\n[speed]\nrpm = -5\n");
    let o = with_scenario("range.toml", negative, &[]);
    // A speed given in rpm is answered in rpm.
    assert_input_error(&o, &["speed.rpm = -5 rpm", "allowed 0.06..=60000 rpm"]);
}

/// A run-up recorded by `simulate` (20 -> 30 Hz over the record, inner-race defect): the
/// sidecar's model states the speed profile, so `analyze` order-tracks the record and finds
/// the inner race at the mean speed; analysed at the start speed (what the sidecar's `rpm`
/// says) the harmonics of a line sweeping over ±20 % smear into nothing, which is what the
/// analysis did before. `--rpm` keeps the constant-speed analysis, with a warning.
#[test]
fn a_run_up_is_order_tracked_from_the_sidecar_speed_profile() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (out, side) = simulate_scenario(
        dir.path(),
        "ramp",
        &format!(
            "preset = \"{BEARING}\"\n[speed]\nfrom_hz = 20.0\nto_hz = 30.0\nramp_duration = 2.0\n[defect]\nlocation = \"inner\"\n"
        ),
        &["--duration", "2", "--fs", "20000"],
    );
    let settle = side["settle_s"].as_f64().expect("settle_s in the sidecar");
    let csv = out.join("simulate.csv");
    let v = json_of(&wearsim(&["analyze", &csv.to_string_lossy(), "--json"]));
    let o = &v["order_tracking"];
    let at = |t: f64| 20.0 + 5.0 * t.min(2.0);
    assert_eq!(o["start_s"].as_f64(), Some(settle));
    assert!(
        (o["min_hz"].as_f64().unwrap() - at(settle)).abs() < 1e-9,
        "{o}"
    );
    assert!((o["max_hz"].as_f64().unwrap() - 30.0).abs() < 1e-3, "{o}");
    // Mean over the record: the ramp from `settle` to 2 s, then 30 Hz.
    let end = settle + 39_999.0 / 20_000.0;
    let revs = (2.0 - settle) * (at(settle) + 30.0) / 2.0 + (end - 2.0) * 30.0;
    let mean = revs / (end - settle);
    assert!(
        (o["mean_hz"].as_f64().unwrap() - mean).abs() < 1e-6 * mean,
        "{o} vs {mean}"
    );
    assert!((v["rpm"].as_f64().unwrap() - 60.0 * mean).abs() < 1e-4);
    assert_eq!(v["rpm_source"], "file speed profile");
    assert_eq!(v["diagnosis"]["family"], "InnerRace", "{}", v["diagnosis"]);
    // The start speed as a constant: no inner race (the smeared lines), and a warning.
    let start_rpm = format!("{}", 60.0 * at(settle));
    let o = wearsim(&[
        "analyze",
        &csv.to_string_lossy(),
        "--rpm",
        &start_rpm,
        "--json",
    ]);
    assert!(
        stderr(&o).contains("varies over the record"),
        "{}",
        stderr(&o)
    );
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(v["order_tracking"].is_null());
    assert_ne!(v["diagnosis"]["family"], "InnerRace", "{}", v["diagnosis"]);
}
