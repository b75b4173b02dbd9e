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
