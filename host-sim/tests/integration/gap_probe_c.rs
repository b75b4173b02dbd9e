//! `wearsim gap` on records an outside user made (probe C): a 300 rpm record cut into 1 s
//! parts (envelope cells whose floor had no bins read 5 384–6 157 "dB"; a speed check that
//! took twice the BPFO for the shaft line), and a record sampled at 5 120 Hz (the
//! structure's resonance at 3.35 kHz, above the Nyquist frequency, calibrated to its
//! bound). Each test builds the parts with the library, as the command does, without the
//! attribution's hundreds of simulations.

use std::path::{Path, PathBuf};

use wearsim_core::effects::Effects;
use wearsim_host::gap::matched::Evaluator;
use wearsim_host::gap::nuisance::{self, Tolerances};
use wearsim_host::gap::records::{self, Overrides};

use super::support::{s, wearsim};

/// `wearsim simulate --preset cwru-6205-de` (outer-race defect) at `rpm`, `fs` Hz for
/// `seconds`, seed 4, into `dir/NAME`; returns the WAV.
fn simulated(dir: &Path, name: &str, rpm: &str, fs: &str, seconds: &str) -> PathBuf {
    let out = dir.join(name);
    let o = wearsim(&[
        "simulate",
        "--preset",
        "cwru-6205-de",
        "--rpm",
        rpm,
        "--fs",
        fs,
        "--duration",
        seconds,
        "--seed",
        "4",
        "--out",
        s(&out),
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    out.join("simulate.wav")
}

#[test]
fn gap_at_300_rpm_in_1_s_parts_has_no_envelope_cells_and_no_false_speed_finding() {
    let dir = tempfile::tempdir().expect("tempdir");
    let wav = simulated(dir.path(), "sim300", "300", "12000", "7");
    let r = records::load(&wav, &Overrides::default()).expect("load");
    // The record is a true 300 rpm record: twice its BPFO (35.9 Hz, within ±25 % of the
    // preset's 1797 rpm) is no shaft line, and 7 s are too short for `analyze`'s check.
    assert!((r.rpm - 300.0).abs() < 1e-9, "{}", r.rpm);
    assert!(
        r.warnings
            .iter()
            .all(|w| !w.contains("contradicts") && !w.contains("speed check")),
        "{:?}",
        r.warnings
    );
    // A 1 s part: segments of 0.125 s hold 2.2 periods of the 17.9 Hz BPFO, whose floor
    // of ±40 % has no bins beside the line's main lobe.
    let m = records::part(&r, 0, 12_000, 4, "train").expect("part");
    let names: Vec<&str> = m.reference.names.iter().map(|n| n.0.as_str()).collect();
    assert!(names.iter().all(|n| !n.starts_with("env:")), "{names:?}");
    assert!(
        m.reference
            .mean
            .iter()
            .all(|v| v.is_finite() && v.abs() < 300.0),
        "{:?}",
        m.reference.mean
    );
    let note = wearsim_host::gap::envelope_note(m.samples, m.spec()).expect("a note");
    assert!(note.contains("4.46 s"), "{note}");
    // A 5 s part resolves them (0.625 s segments hold 11 periods), every value bounded.
    let m = records::part(&r, 0, 60_000, 4, "train").expect("part");
    let env: Vec<f64> = m
        .reference
        .names
        .iter()
        .zip(&m.reference.mean)
        .filter(|(n, _)| n.0.starts_with("env:h"))
        .map(|(_, v)| *v)
        .collect();
    assert_eq!(env.len(), 5, "{:?}", m.reference.names);
    assert!(env.iter().all(|v| v.abs() < 100.0), "{env:?}");
    assert_eq!(wearsim_host::gap::envelope_note(m.samples, m.spec()), None);
}

#[test]
fn gap_leaves_a_resonance_above_nyquist_uncalibrated() {
    let dir = tempfile::tempdir().expect("tempdir");
    let wav = simulated(dir.path(), "sim5120", "1797", "5120", "3.2");
    let r = records::load(&wav, &Overrides::default()).expect("load");
    let m = records::part(&r, 0, 5_120, 4, "train").expect("part");
    let why = nuisance::structure_uninformed(std::slice::from_ref(&m), &Tolerances::CALIBRATE)
        .expect("the resonance is not informed at 5120 Hz");
    assert!(why.contains("2560 Hz"), "{why}");
    let cal = nuisance::calibrate(
        &[m],
        &Effects::NONE,
        &Tolerances::CALIBRATE,
        &Evaluator::new(1),
    );
    let fitted: Vec<&str> = cal.fitted.iter().map(|f| f.name).collect();
    assert!(
        !fitted.contains(&"resonance") && !fitted.contains(&"damping"),
        "{fitted:?}"
    );
    let left: Vec<&str> = cal.not_informed.iter().map(|n| n.name).collect();
    assert_eq!(left, ["resonance", "damping"]);
    // At 12 kHz the same rig's resonance is in the record: it is calibrated.
    let wav = simulated(dir.path(), "sim12k", "1797", "12000", "3");
    let r = records::load(&wav, &Overrides::default()).expect("load");
    let m = records::part(&r, 0, 12_000, 4, "train").expect("part");
    assert_eq!(
        nuisance::structure_uninformed(&[m], &Tolerances::CALIBRATE),
        None
    );
}

/// The same 300 rpm record with the speed taken out of its sidecar: the strongest line
/// within ±25 % of the preset's 1797 rpm is twice the BPFO (35.9 Hz), whose fundamental
/// stands at half of it. The gap used to take 2 154 rpm from it and attribute the whole
/// record at that speed; the estimate now has to pass the shaft-line check, and fails here
/// with a message that asks for `--rpm`.
#[test]
fn a_speed_read_from_a_bearing_line_is_refused_and_rpm_asked_for() {
    let dir = tempfile::tempdir().expect("tempdir");
    let wav = simulated(dir.path(), "sim300", "300", "12000", "7");
    let side = wav.with_extension("json");
    let mut meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&side).expect("sidecar")).expect("json");
    let obj = meta.as_object_mut().expect("object");
    assert!(obj.remove("rpm").is_some() && obj.remove("rpm_range").is_some());
    std::fs::write(&side, meta.to_string()).expect("write sidecar");
    let e = records::load(&wav, &Overrides::default()).expect_err("a wrong speed is refused");
    assert!(
        e.contains("fails the shaft-line check") && e.contains("1/2x") && e.contains("give --rpm"),
        "{e}"
    );
    // Stated, the same record loads at its true speed.
    let r = records::load(
        &wav,
        &Overrides {
            rpm: Some(300.0),
            ..Overrides::default()
        },
    )
    .expect("load with --rpm");
    assert!((r.rpm - 300.0).abs() < 1e-9, "{}", r.rpm);
}
