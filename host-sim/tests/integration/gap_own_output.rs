//! `wearsim gap` on wearsim's own simulated output: the defect the samples were simulated
//! with is read from the sidecar's model when `--defect` is not given (it was once ignored,
//! the record matched as healthy, and the test gap was 35 instead of under 1).

use std::path::{Path, PathBuf};

use wearsim_host::gap::records::{self, Overrides};

use super::support::{s, wearsim};

/// `wearsim simulate --preset cwru-6205-de` (an outer-race defect at 6 o'clock) for 3 s at
/// 12 kHz into `dir/sim`; returns the CSV and the sidecar's `model.defect`.
fn simulated(dir: &Path) -> (PathBuf, serde_json::Value) {
    let out = dir.join("sim");
    let o = wearsim(&[
        "simulate",
        "--preset",
        "cwru-6205-de",
        "--duration",
        "3",
        "--fs",
        "12000",
        "--out",
        s(&out),
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let side: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("simulate.json")).expect("sidecar"))
            .expect("sidecar JSON");
    let defect = side["model"]["defect"].clone();
    assert!(defect.is_object(), "the preset simulates a defect: {side}");
    (out.join("simulate.csv"), defect)
}

#[test]
fn gap_takes_the_defect_of_its_own_simulation_from_the_sidecar() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (csv, defect) = simulated(dir.path());
    let out = dir.path().join("gap");
    let o = wearsim(&[
        "gap",
        "--real",
        s(&csv),
        "--jobs",
        "1",
        "--out",
        s(&out),
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("gap JSON");
    let meta = &v["records"][0]["meta"];
    assert_eq!(meta["defect_source"], "sidecar", "{meta}");
    // Exactly the simulated defect: location with its angle, formulation, topography.
    assert_eq!(meta["defect_model"], defect, "{meta}");
    assert_eq!(meta["defect"]["location"], "outer@6", "{meta}");
    let size = defect["topography"]["length"].as_f64().expect("length");
    assert_eq!(meta["defect"]["size"].as_f64(), Some(size), "{meta}");
    let warnings = meta["warnings"].to_string();
    assert!(!warnings.contains("healthy"), "{warnings}");
    // The record is its own model: the test part's gap before calibration is small (it was
    // 35 when the record was matched as healthy).
    let before = v["totals"]["test_before"].as_f64().expect("test_before");
    assert!(before < 2.0, "test gap before calibration {before}: {v}");
}

#[test]
fn gap_prefers_an_explicit_defect_over_the_sidecar_and_says_so() -> Result<(), String> {
    let dir = tempfile::tempdir().expect("tempdir");
    let (csv, defect) = simulated(dir.path());
    let size_mm = 1e3 * defect["topography"]["length"].as_f64().expect("length");
    let depth_mm = 1e3 * defect["topography"]["depth"].as_f64().expect("depth");
    let load = |d: &str| {
        records::load(
            &csv,
            &Overrides {
                defect: Some(records::parse_defect(d)?),
                ..Overrides::default()
            },
        )
    };
    // The same defect as the simulation: no warning.
    let same = load(&format!("outer@6:{size_mm}mm:{depth_mm}mm"))?;
    assert_eq!(same.defect_source, "argument");
    assert!(same.defect_model.is_none());
    assert!(
        same.warnings.iter().all(|w| !w.contains("--defect")),
        "{:?}",
        same.warnings
    );
    // Another location: the argument is used, with a warning naming both.
    let other = load("inner:0.007in")?;
    assert_eq!(other.defect_source, "argument");
    assert_eq!(other.defect.map(|d| d.location), Some("inner"));
    let w = other.warnings.join(" | ");
    assert!(
        w.contains("--defect inner") && w.contains("outer@6") && w.contains("sidecar"),
        "{w}"
    );
    // `none` against a simulated defect is a difference too.
    let none = load("none")?;
    assert!(none.defect.is_none());
    assert!(
        none.warnings.iter().any(|w| w.contains("--defect none")),
        "{:?}",
        none.warnings
    );
    Ok(())
}

/// A run whose speed ramps during the recorded part: the sidecar states the recorded part's
/// mean speed and range (it once stated the speed at t = 0, before the settle), and the gap,
/// which simulates one constant speed, refuses the record unless `--rpm` chooses that speed.
#[test]
fn a_record_whose_speed_varies_gives_its_range_and_the_gap_asks_for_rpm() -> Result<(), String> {
    let dir = tempfile::tempdir().expect("tempdir");
    let cfg = dir.path().join("ramp.toml");
    std::fs::write(
        &cfg,
        "preset = \"cwru-6205-de\"\nduration = 2.0\nsettle = 0.5\n[speed]\nfrom_hz = 25.0\nto_hz = 30.0\nramp_duration = 1.5\n",
    )
    .expect("write config");
    let out = dir.path().join("sim");
    let o = wearsim(&["simulate", "--config", s(&cfg), "--out", s(&out)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let side: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("simulate.json")).expect("sidecar"))
            .expect("sidecar JSON");
    // Recorded from 0.5 s to 2.5 s: 25 + 5·t/1.5 Hz rises from 26.667 to 30 Hz by 1.5 s,
    // then 30 Hz: mean (1 s · 28.333 + 1 s · 30)/2 s = 29.1667 Hz = 1750 rpm.
    let rpm = side["rpm"].as_f64().expect("rpm");
    assert!((rpm - 1750.0).abs() < 1e-6, "{side}");
    let range = &side["rpm_range"];
    let (lo, hi) = (range[0].as_f64(), range[1].as_f64());
    assert!(
        (lo.unwrap_or(0.0) - 1600.0).abs() < 1e-6 && (hi.unwrap_or(0.0) - 1800.0).abs() < 1e-6,
        "{side}"
    );

    let csv = out.join("simulate.csv");
    let gap_out = dir.path().join("gap");
    let o = wearsim(&["gap", "--real", s(&csv), "--out", s(&gap_out)]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("varies over the record, 1600-1800 rpm") && err.contains("give --rpm"),
        "{err}"
    );
    assert!(!gap_out.exists(), "nothing is written for a refused record");

    // With --rpm the record is read, and the report says the speed varied.
    let rec = records::load(
        &csv,
        &Overrides {
            rpm: Some(1750.0),
            ..Overrides::default()
        },
    )?;
    assert_eq!(rec.rpm, 1750.0);
    assert!(
        rec.warnings.iter().any(|w| w.contains("1600-1800 rpm")),
        "{:?}",
        rec.warnings
    );
    Ok(())
}
