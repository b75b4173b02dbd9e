//! The `wearsim` binary: the default scenario, machine-readable output, determinism, and
//! the documented errors for bad input (exit code 2, a message naming the field, no
//! output that looks complete).

use std::path::Path;
use std::process::{Command, Output};

fn wearsim(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wearsim"))
        .args(args)
        .output()
        .expect("run wearsim")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn write_config(dir: &Path, text: &str) -> String {
    let p = dir.join("scenario.toml");
    std::fs::write(&p, text).unwrap();
    p.display().to_string()
}

#[test]
fn simulate_default_scenario_json() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    let o = wearsim(&[
        "simulate",
        "--duration",
        "0.5",
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["preset"], "thesis-61810");
    assert_eq!(v["fs"], 20000.0);
    let rms = v["summary"]["stats"]["rms"].as_f64().unwrap();
    assert!(rms > 0.0 && rms.is_finite());
    // The envelope's strongest line is the outer-race ball pass frequency of the default
    // medium outer-race defect.
    let bpfo = v["summary"]["kinematics"]["bpfo"].as_f64().unwrap();
    let env0 = v["summary"]["envelope_peaks"][0]["freq"].as_f64().unwrap();
    assert!(
        (env0 - bpfo).abs() < 2.0,
        "envelope peak {env0} vs BPFO {bpfo}"
    );
    let side: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("simulate.json")).unwrap()).unwrap();
    assert_eq!(side["complete"], true);
    assert_eq!(side["n_samples"], 10_000);
    assert_eq!(side["seed"], 1);
    assert!(out.join("simulate.wav").exists() && out.join("simulate.csv").exists());
}

#[test]
fn same_seed_same_bytes_other_seed_differs() {
    let dir = tempfile::tempdir().unwrap();
    let run = |name: &str, seed: &str| {
        let out = dir.path().join(name);
        let o = wearsim(&[
            "simulate",
            "--duration",
            "0.2",
            "--seed",
            seed,
            "--out",
            out.to_str().unwrap(),
            "--json",
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        std::fs::read(out.join("simulate.csv")).unwrap()
    };
    let (a, b, c) = (run("a", "7"), run("b", "7"), run("c", "8"));
    assert_eq!(a, b);
    assert_ne!(a, c);
}

/// Each bad input: exit code 2, the message names the field (and range where there is
/// one), and no sidecar is left that says "complete".
#[test]
fn bad_inputs_are_named_and_leave_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let cases: Vec<(&str, Vec<&str>, &str)> = vec![
        (
            "unknown key",
            vec!["preset = \"thesis-61810\"\nspeeed = 3\n"],
            "unknown field `speeed`",
        ),
        (
            "unknown nested key",
            vec!["preset = \"thesis-61810\"\n[structure]\nmas = 1.0\n"],
            "unknown field `mas`",
        ),
        (
            "missing key",
            vec!["radial_load = 100.0\n"],
            "bearing.elements",
        ),
        (
            "zero mass",
            vec!["preset = \"thesis-61810\"\n[structure]\nmass = 0.0\n"],
            "structure.mass = 0 is out of range",
        ),
        (
            "nan stiffness",
            vec!["preset = \"thesis-61810\"\n[structure]\nstiffness = nan\n"],
            "structure.stiffness",
        ),
        (
            "negative fs",
            vec!["preset = \"thesis-61810\"\nfs = -5.0\n"],
            "fs = -5 is out of range",
        ),
        (
            "step too large",
            vec!["preset = \"thesis-61810\"\nfs = 1000.0\noversample = 2\n"],
            "internal step too large",
        ),
        ("bad preset", vec!["preset = \"nope\"\n"], "thesis-61810"),
        (
            "bad topography",
            vec!["preset = \"thesis-61810\"\n[defect]\ntopography = \"huge\"\n"],
            "defect.topography",
        ),
        (
            "bad integrator",
            vec!["preset = \"thesis-61810\"\nintegrator = \"euler\"\n"],
            "rk4, exact-zoh, exact-foh",
        ),
        (
            "duration",
            vec!["preset = \"thesis-61810\"\nduration = 1e9\n"],
            "duration",
        ),
        (
            "two speeds",
            vec!["preset = \"thesis-61810\"\n[speed]\nrpm = 100.0\nshaft_hz = 3.0\n"],
            "exactly one of",
        ),
        ("toml syntax", vec!["preset = \n"], "scenario.toml"),
        (
            "ball element out of range",
            vec!["preset = \"cwru-6205-de\"\n[defect]\nlocation = \"ball\"\nelement = 9\n"],
            "defect.element = 9 is out of range: allowed 0 ..= 8",
        ),
        (
            "element of a race defect",
            vec!["preset = \"cwru-6205-de\"\n[defect]\nlocation = \"outer\"\nelement = 1\n"],
            "defect.element: applies to a ball defect only",
        ),
        (
            "bad location",
            vec!["preset = \"cwru-6205-de\"\n[defect]\nlocation = \"cage\"\n"],
            "outer, inner, ball, none",
        ),
        (
            "rpm out of range",
            vec!["preset = \"thesis-61810\"\n[speed]\nrpm = 1e9\n"],
            "speed.rpm = 1000000000 rpm is out of range: allowed 0.06..=60000 rpm",
        ),
    ];
    for (what, text, needle) in cases {
        let cfg = write_config(dir.path(), text[0]);
        let out = dir.path().join(format!("out-{}", what.replace(' ', "-")));
        let mut args = vec!["simulate", "--config", &cfg, "--out", out.to_str().unwrap()];
        if what != "duration" {
            args.extend(["--duration", "0.1"]); // the command line overrides the file
        }
        let o = wearsim(&args);
        assert_eq!(o.status.code(), Some(2), "{what}: {}", stderr(&o));
        assert!(
            stderr(&o).contains(needle),
            "{what}: message {:?} lacks {needle:?}",
            stderr(&o)
        );
        assert!(
            !out.join("simulate.json").exists(),
            "{what}: output written"
        );
    }
    // Bad arguments.
    let gap_out = dir.path().join("gap-out");
    let gap_out = gap_out.to_str().unwrap();
    for (args, needle) in [
        (vec!["simulate", "--fs", "abc"], "invalid value"),
        (
            vec!["simulate", "--topography", "crater", "--duration", "0.1"],
            "defect.topography",
        ),
        (vec!["simulate", "--preset", "x"], "preset"),
        (vec!["simulate", "--duration", "-1"], "duration"),
        (vec!["frobnicate"], "unrecognized subcommand"),
        // A speed typed in rpm is checked in rpm, naming the flag (it was answered with
        // `speed.shaft_hz = 16666666.67 … 0.001 ..= 1000`).
        (
            vec!["simulate", "--rpm", "1e9"],
            "--rpm = 1000000000 rpm is out of range: allowed 0.06..=60000 rpm",
        ),
        (vec!["simulate", "--rpm", "0.01"], "--rpm = 0.01 rpm"),
        (
            vec![
                "gap",
                "--real",
                "x.csv",
                "--rpm",
                "100000",
                "--bearing",
                "cwru-6205-de",
                "--out",
                gap_out,
            ],
            "--rpm = 100000 rpm is out of range: allowed 0.06..=60000 rpm",
        ),
        (
            vec!["analyze", "x.wav", "--rpm", "1e9"],
            "--rpm 1000000000 is out of range",
        ),
    ] {
        let o = wearsim(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(needle), "{args:?}: {:?}", stderr(&o));
    }
}

#[test]
fn a_complete_config_without_preset_runs() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = write_config(
        dir.path(),
        r#"
seed = 3
duration = 0.2
fs = 10000.0
radial_load = 300.0
[bearing]
elements = 9
element_diameter = 7.94e-3
pitch_diameter = 39.04e-3
contact_angle_deg = 0.0
bore = 25e-3
outside_diameter = 52e-3
contact = "point"
[structure]
mass = 1.0
stiffness = 5e7
damping = 500.0
[speed]
rpm = 1797.0
[defect]
location = "inner"
topography = "mild-defect"
"#,
    );
    let out = dir.path().join("o");
    let o = wearsim(&[
        "simulate",
        "--config",
        &cfg,
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(
        (v["summary"]["kinematics"]["bpfi"].as_f64().unwrap() - 5.4152 * 1797.0 / 60.0).abs() < 0.1
    );
}

#[test]
fn presets_and_bench_json() {
    let o = wearsim(&["presets", "--json"]);
    assert!(o.status.success());
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let cwru = v
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == "cwru-6205-de")
        .unwrap();
    assert!((cwru["orders"]["bpfo"].as_f64().unwrap() - 3.5848).abs() < 1e-3);
    // The catalogue bearings are listed too (they were named only in error messages): the
    // MFPT rig's BPFO, 81.125 Hz at 25 Hz in its readme, is 3.2450 orders.
    let o = wearsim(&["presets"]);
    let text = String::from_utf8_lossy(&o.stdout);
    let mfpt = text.lines().find(|l| l.starts_with("mfpt-nice")).unwrap();
    assert!(
        mfpt.contains(" 3.2450 ") && text.contains("xjtu-ldk-uer204"),
        "{text}"
    );
    let o = wearsim(&["bench", "--seconds", "1", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(v["rtf"].as_f64().unwrap() > 0.0);
    assert!(v["ns_per_step"].as_f64().unwrap() > 0.0);
    assert_eq!(v["oversample"], 2);
}

/// `bench --lanes` on the two documented lane configurations (inner race with three
/// effects; ball defect with slip and the sensor, whose lanes skip their ball terms
/// together): the host's lane path (packed square roots, AVX2 where the CPU has it) gives
/// the scalar step's samples bit for bit. The speed figures are not asserted.
#[test]
fn lane_bench_configs_are_bit_identical_to_the_scalar_step() {
    let docs = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/");
    for (cfg, k) in [
        ("bench-lanes-cwru-inner.toml", "4"),
        ("bench-lanes-cwru-ball.toml", "16"),
    ] {
        let path = format!("{docs}{cfg}");
        let o = wearsim(&[
            "bench",
            "--lanes",
            k,
            "--config",
            &path,
            "--fs",
            "12000",
            "--seconds",
            "1",
            "--json",
        ]);
        assert!(o.status.success(), "{cfg}: {}", stderr(&o));
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        assert_eq!(v["bit_identical"], true, "{cfg}: {v}");
        assert_eq!(v["lanes"].as_u64(), k.parse().ok(), "{cfg}");
    }
}

/// `[defect] location = "ball"`: the element and the spin phase (`angle_deg`) reach the core,
/// and the simulation's envelope spectrum is labelled with the ball's lines.
#[test]
fn a_ball_defect_config_runs() {
    use wearsim_core::forces::defect::DefectLocation;
    let text = r#"
preset = "cwru-6205-de"
duration = 1.0
[defect]
location = "ball"
element = 3
angle_deg = 90.0
"#;
    let (cfg, _) = wearsim_host::config::ScenarioFile::parse(text, "ball.toml")
        .unwrap()
        .resolve()
        .unwrap();
    match cfg.defect.unwrap().location {
        DefectLocation::Ball { element, phase } => {
            assert_eq!(element, 3);
            assert!((phase - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        }
        other => panic!("{other:?}"),
    }
    // The element and the phase default to 0.
    let (cfg, _) = wearsim_host::config::ScenarioFile::parse(
        "preset = \"cwru-6205-de\"\n[defect]\nlocation = \"ball\"\n",
        "ball0.toml",
    )
    .unwrap()
    .resolve()
    .unwrap();
    assert_eq!(
        cfg.defect.unwrap().location,
        DefectLocation::Ball {
            element: 0,
            phase: 0.0
        }
    );

    let dir = tempfile::tempdir().unwrap();
    let path = write_config(dir.path(), text);
    let out = dir.path().join("o");
    let o = wearsim(&[
        "simulate",
        "--config",
        &path,
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let labels: Vec<&str> = v["summary"]["envelope_peaks"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["matched"] == true)
        .map(|p| p["nearest"].as_str().unwrap())
        .collect();
    println!("envelope peaks: {labels:?}");
    assert!(labels.contains(&"2x BSF"), "{labels:?}");
    assert!(
        !labels
            .iter()
            .any(|l| l.ends_with("BPFO") || l.ends_with("BPFI")),
        "{labels:?}"
    );
}

/// The sidecar names the integrator and the topography as the configuration file does
/// (`exact-foh`, `real-dent`), a custom topography by its dimensions, and the resolved
/// effects as structured JSON: nothing is a Rust `Debug` string a reader would have to parse.
#[test]
fn sidecar_fields_are_names_and_structures_not_debug_strings() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    let cfg = write_config(
        dir.path(),
        "preset = \"thesis-61810\"\nintegrator = \"rk4\"\n",
    );
    let o = wearsim(&[
        "simulate",
        "--config",
        &cfg,
        "--duration",
        "0.01",
        "--topography",
        "real-dent",
        "--effect",
        "slip:fraction=0.02",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(out.join("simulate.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["integrator"], "rk4");
    assert_eq!(v["topography"], "real-dent");
    assert_eq!(v["effects"]["resolved"]["slip"]["fraction"], 0.02);
    assert!(v["effects"]["resolved"]["load_zone"].is_null());
    assert!(!text.contains("Some("), "a Debug string in the sidecar");
}

/// A tiny or huge value is named in exponent form, not as the 300-digit decimal `{}`
/// gives (`cmd::exit::compact_numbers`).
#[test]
fn a_tiny_or_huge_value_is_named_in_exponent_form() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    for (arg, value, shown) in [
        ("--duration", "1e-300", "1e-300"),
        ("--rpm", "1e300", "1e300"),
    ] {
        let o = wearsim(&["simulate", arg, value, "--out", out.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(2));
        let e = stderr(&o);
        assert!(e.contains(shown) && e.len() < 300, "{arg} {value}: {e}");
        assert!(!out.exists(), "{arg} {value}: output written");
    }
}

/// A preset resized in `[bearing]` (a 6308's 8 × 15.081 mm on 65 mm over `cwru-6205-de`)
/// does not inherit the 6205's rings, which no longer fit round its pitch circle: bore and
/// outside diameter follow the section rule `pitch ∓ 1.7·ball` unless given; an unresized
/// preset keeps its own, and given values win.
#[test]
fn a_resized_preset_gets_rings_that_fit_its_pitch_circle() {
    let resolve = |text: &str| {
        wearsim_host::config::ScenarioFile::parse(text, "b.toml")
            .unwrap()
            .resolve()
            .map(|(cfg, _)| cfg.bearing)
    };
    let b = resolve(
        "preset = \"cwru-6205-de\"\n[bearing]\nelements = 8\nelement_diameter = 15.081e-3\npitch_diameter = 65e-3\n",
    )
    .unwrap();
    assert!(
        (b.bore - (65e-3 - 1.7 * 15.081e-3)).abs() < 1e-12,
        "{}",
        b.bore
    );
    assert!((b.outside_diameter - (65e-3 + 1.7 * 15.081e-3)).abs() < 1e-12);
    // Unresized: the preset's own rings (SKF 6205: 25 mm bore, 52 mm outside).
    let b = resolve("preset = \"cwru-6205-de\"\n[bearing]\nelements = 9\n").unwrap();
    assert_eq!((b.bore, b.outside_diameter), (25e-3, 52e-3));
    // Given values win, and a ring that does not fit is still refused by name.
    let b = resolve(
        "preset = \"cwru-6205-de\"\n[bearing]\npitch_diameter = 65e-3\nelement_diameter = 15.081e-3\nbore = 40e-3\n",
    )
    .unwrap();
    assert_eq!(b.bore, 40e-3);
    let e = resolve(
        "preset = \"cwru-6205-de\"\n[bearing]\npitch_diameter = 65e-3\nelement_diameter = 15.081e-3\noutside_diameter = 52e-3\n",
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("bearing.outside_diameter"), "{e}");
    // No preset: the section rule, not a missing-key error.
    let b = resolve(
        "radial_load = 1000.0\nclearance = 0.0\n[bearing]\nelements = 8\nelement_diameter = 15.081e-3\npitch_diameter = 65e-3\ncontact_angle_deg = 0.0\n[structure]\nmass = 1.0\nstiffness = 1e8\ndamping = 100.0\n[speed]\nrpm = 1500.0\n",
    );
    assert!(b.is_ok(), "{b:?}");
}
