//! `wearsim ims-validate`: the failed IMS bearing lives read on their running-time line
//! (data-backed: skips without the data folder, fails without it when CI=true), and bad
//! feature tables refused with exit 2, the field named and nothing written.

use crate::support;
use support::{refused, s, wearsim};
use wearsim_host::io::data_dir;
use wearsim_host::life::ims::{distance_db, Curve};
use wearsim_host::life::ims_validate::{
    copy_calibration, copy_calibration_medians, medians, over_seeds, read_record, read_records,
    validate_ensemble, validate_seeds, Calibration, FloorMode, Frame, LifeFigures, MeasuredRecord,
    Medians, Protocol, Validation, RECORDS,
};

/// The four failed IMS lives, read from the data folder; `None` (with a message) when the
/// folder is absent, a failure when `CI=true`.
fn failed_lives() -> Option<Vec<MeasuredRecord>> {
    let Some(data) = data_dir().expect("data folder required when CI=true") else {
        eprintln!("skipping: measured data folder not found (set WEARSIM_DATA)");
        return None;
    };
    Some(read_records(&data).unwrap())
}

#[test]
fn the_four_failed_lives_are_read_on_running_time() {
    let Some(r) = failed_lives() else {
        return;
    };
    let by = |id: &str| r.iter().find(|m| m.record.id == id).unwrap();
    // Test 2 runs without stops: 2004-02-12 10:32:39 to 02-19 06:02:39 (two dead final
    // snapshots dropped, IMS README quirk) = 163.5 h at 10-min intervals.
    let t2 = by("t2b1");
    assert_eq!((t2.gaps, t2.dropped), (0, 2));
    assert!((t2.running_h - 163.5).abs() < 0.05, "{}", t2.running_h);
    // Test 1: 827.6 clock hours of which 486 h are 24 stops of the rig; what ran is
    // about 349 h (capped intervals of the median 10 min).
    let t1 = by("t1b3");
    assert!((t1.clock_h - 827.56).abs() < 0.05, "{}", t1.clock_h);
    assert_eq!(t1.gaps, 24);
    assert!((330.0..360.0).contains(&t1.running_h), "{}", t1.running_h);
    assert_eq!(by("t1b4").running_h, t1.running_h);
    // Test 3 (6,324 files, last one dead): 1073 clock hours, a few weekend stops.
    let t3 = by("t3b3");
    assert_eq!(t3.dropped, 1);
    assert!((1030.0..1073.3).contains(&t3.running_h), "{}", t3.running_h);
    // Normalised curves: first-half median 1, time from 0 to 1.
    for m in &r {
        let c = &m.curve;
        assert_eq!((c.t[0], *c.t.last().unwrap()), (0.0, 1.0));
        assert!(c.t.windows(2).all(|w| w[1] > w[0]), "{}", m.record.id);
    }
    // Measured end ratios: "5–20× above their steady level" (issue 14) for the outer
    // races, test 1 bearing 3 lower (about 3.7 on channel x).
    for (id, lo, hi) in [("t2b1", 5.0, 8.0), ("t3b3", 5.0, 15.0), ("t1b3", 2.0, 6.0)] {
        let e = *by(id).curve.rms.last().unwrap();
        assert!((lo..hi).contains(&e), "{id}: end ratio {e}");
    }
}

/// The primary protocol (`wearsim ims-validate --primary-only --seeds 5`): `life_factor`
/// calibrated on test 2 bearing 1 for each of seeds 1–5, judged on the three held-out
/// failed bearings, the sensor reading the bearing alone; figures are medians over the
/// seeds of the held-out medians (each seed draws its bearing's fatigue and
/// spall-propagation scatter, so one seed is one draw). Asserted is the acceptance item the
/// wear model meets (issue 14): the end-of-life ratio within a factor 2 of the measured. It
/// failed by a factor 18 before fresh breakout edges shook down. The two items still missed
/// are checked as what they are today, so a change that moves them shows: the onset error
/// below 0.15 of life (0.069 over seeds 1–5; acceptance 0.1, reached by this median but not
/// by leave-one-out) and the trajectory distance below 6 dB RMS (4.59; acceptance 3 dB;
/// docs/ims-comparison.md).
#[test]
fn held_out_lives_end_within_a_factor_two_of_measured() {
    let Some(recs) = failed_lives() else {
        return;
    };
    let runs = validate_seeds(&recs, 1..=5, false, Protocol::LENGTH_ON_LIFE).unwrap();
    for v in &runs {
        let fold = &v.folds[0];
        assert_eq!(fold.calibrated_on, "t2b1");
        assert_eq!(fold.held_out.len(), 3);
        for f in &fold.held_out {
            eprintln!(
                "seed {} {}: onset {:?} vs {:?}, end ratio {:.2} vs {:.2} (x{:.2}), distance {:.2} dB",
                v.seed,
                f.id,
                f.onset_simulated,
                f.onset_measured,
                f.end_ratio_simulated,
                f.end_ratio_measured,
                f.end_ratio_factor,
                f.distance_db_rms
            );
        }
    }
    let m = over_seeds(&runs).primary;
    assert!(
        m.end_ratio_factor <= 2.0,
        "held-out end ratio off by x{:.2}",
        m.end_ratio_factor
    );
    assert!(
        m.onset_error < 0.15,
        "held-out onset error {:.3}",
        m.onset_error
    );
    assert!(
        m.distance_db_rms < 6.0,
        "held-out distance {:.2} dB",
        m.distance_db_rms
    );
}

/// The primary protocol with both scales calibrated on test 2 bearing 1 (its running
/// revolutions and its measured onset: `--calibrate shape`) and the held-out lives judged
/// on their records' running hours aligned at failure (`--frame record`), seeds 1 and 2:
/// the calibration life is matched in length (1 %) and onset, its propagation limit is
/// read off it, and the held-out onsets land within 0.1 of their records (0.077 and 0.082
/// today; with the life factor alone on each life's own fraction the same seeds give 0.43
/// and 0.04: calibrating the propagation absorbs the seed's propagation draw). The
/// no-model reference of carrying the calibration life's hours from onset to failure
/// gives 0.053 on this fold, and the trajectory distance (4.1–4.6 dB) stays above 3 dB:
/// both checked as what they are (docs/ims-comparison.md, stop 46).
#[test]
fn held_out_onsets_on_running_hours_after_a_shape_calibration() {
    let Some(recs) = failed_lives() else {
        return;
    };
    let p = Protocol {
        calibration: Calibration::Shape,
        frame: Frame::Record,
        floor: FloorMode::None,
    };
    let runs = validate_seeds(&recs, 1..=2, false, p).unwrap();
    let mut onsets = vec![];
    for v in &runs {
        let fold = &v.folds[0];
        assert_eq!(fold.calibrated, Calibration::Shape);
        assert!(
            fold.converged,
            "seed {}: the shape calibration did not reach its targets",
            v.seed
        );
        let c = &fold.calibration;
        eprintln!("seed {}: {fold:?}", v.seed);
        assert!((c.life_ratio - 1.0).abs() < 0.01, "{c:?}");
        // The onset tolerance of the calibration plus one simulated window (1/300).
        assert!(c.onset_error.unwrap() <= 0.02 + 1.0 / 300.0, "{c:?}");
        // A propagation limit read off the measured life, not the material's 1.5e7.
        assert!(
            (fold.propagation_passes / 1.5e7 - 1.0).abs() > 0.2,
            "{}",
            fold.propagation_passes
        );
        let m = fold.median;
        assert!((0.05..0.1).contains(&m.onset_error), "{m:?}");
        assert!(m.end_ratio_factor <= 2.0, "{m:?}");
        assert!((3.0..6.0).contains(&m.distance_db_rms), "{m:?}");
        assert!((fold.copy_calibration.onset_error - 0.053).abs() < 0.005);
        onsets.push(m.onset_error);
    }
    assert!((onsets[0] - onsets[1]).abs() < 0.03, "{onsets:?}");
}

fn table(dir: &std::path::Path, rows: &[&str]) {
    let d = dir.join("ims/features_chocho66");
    std::fs::create_dir_all(&d).unwrap();
    let mut text = String::from(",Bearing 1,Bearing 2,Bearing 3,Bearing 4\n");
    for r in rows {
        text.push_str(r);
        text.push('\n');
    }
    std::fs::write(d.join("DatasetBearingTest_3.csv"), text).unwrap();
}

#[test]
fn a_table_without_the_column_or_with_time_going_back_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let t3 = &RECORDS[3];
    let rows: Vec<String> = (0..20)
        .map(|i| format!("2004-03-04 09:{:02}:00,0.1,0.1,0.1,0.1", i * 2))
        .collect();
    let rows: Vec<&str> = rows.iter().map(String::as_str).collect();
    table(dir.path(), &rows);
    assert!(read_record(dir.path(), t3).is_ok());
    // Time going back at row 6 (the fifth data row).
    let mut back = rows.clone();
    back[4] = "2004-03-04 09:01:00,0.1,0.1,0.1,0.1";
    table(dir.path(), &back);
    let e = read_record(dir.path(), t3).unwrap_err();
    assert!(e.contains("row 6") && e.contains("time"), "{e}");
    // A value whose digits are gone (subnormal) is refused: a table scaled by 1e-310 was
    // read, and its end ratio came out as 4.8e-11 (232 dB).
    let mut tiny = rows.clone();
    tiny[7] = "2004-03-04 09:14:00,0.1,0.1,1e-310,0.1";
    table(dir.path(), &tiny);
    let e = read_record(dir.path(), t3).unwrap_err();
    assert!(e.contains("row 9") && e.contains("smallest normal"), "{e}");
    // IMS test 3's own table (known by its first snapshot) cut to 20 rows is not a life
    // to failure: a probe's cut tables were validated and calibrated on without a word.
    let cut: Vec<String> = std::iter::once("2004-03-04 09:27:46,0.1,0.1,0.1,0.1".to_string())
        .chain((1..20).map(|i| {
            format!(
                "2004-03-04 1{}:{:02}:00,0.1,0.1,0.1,0.1",
                i / 10,
                (i % 10) * 5
            )
        }))
        .collect();
    table(
        dir.path(),
        &cut.iter().map(String::as_str).collect::<Vec<_>>(),
    );
    let e = read_record(dir.path(), t3).unwrap_err();
    assert!(e.contains("IMS test 3") && e.contains("cut short"), "{e}");
    // No bearing 3 column.
    let d = dir
        .path()
        .join("ims/features_chocho66/DatasetBearingTest_3.csv");
    std::fs::write(
        &d,
        ",Bearing 1,Bearing 2\n2004-03-04 09:00:00,0.1,0.1\n2004-03-04 09:10:00,0.1,0.1\n",
    )
    .unwrap();
    let e = read_record(dir.path(), t3).unwrap_err();
    assert!(e.contains("B3_mean_abs"), "{e}");
}

#[test]
fn the_command_refuses_a_bad_table_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    // The data folder lacks the test 2 table: exit 2 naming the file.
    let o = wearsim(&[
        "ims-validate",
        "--data",
        s(dir.path()),
        "--out",
        s(&out),
        "--json",
    ]);
    refused(&o, &["test2_timefeatures.csv"]);
    assert!(!out.exists(), "nothing may be written");
}

/// The population check (`wearsim ims-validate --ensemble 5 --primary-only`): one
/// `life_factor` puts the median of seeds 1–5 on test 2 bearing 1's running revolutions,
/// chosen by that life alone (the same bits with the held-out lives absent; this check
/// guards the one calibration call both calibrations share, so the shape test below does
/// not repeat it), and the held-out lives are judged against the five simulated lives. Asserted as well are the
/// two gaps this view shows on every held-out life (docs/ims-comparison.md, "Against the
/// simulated population"), so that a change that closes or reverses one shows: the
/// simulated end level is above the measured one, and the simulated time from onset to
/// failure is shorter.
#[test]
fn the_population_is_calibrated_on_its_median_and_judged_on_held_out_lives() {
    let Some(recs) = failed_lives() else {
        return;
    };
    let v = validate_ensemble(&recs, 1, 5, false, Calibration::Length, Frame::Life).unwrap();
    assert_eq!(v.folds.len(), 1);
    let fold = &v.folds[0];
    assert_eq!(fold.calibrated_on, "t2b1");
    assert!(fold.converged);
    assert!(
        (fold.calibration_median_ratio - 1.0).abs() <= 0.01,
        "median life / record {}",
        fold.calibration_median_ratio
    );
    // The calibration life's own PIT of the life ratio: its record sits at the
    // population's median (3 of 5 below or equal, so 0.4–0.6).
    let pit = fold.calibration.life_ratio.pit.unwrap();
    assert!((0.39..=0.61).contains(&pit), "calibration life PIT {pit}");
    let alone =
        validate_ensemble(&recs[..1], 1, 5, false, Calibration::Length, Frame::Life).unwrap();
    assert_eq!(
        alone.folds[0].life_factor.to_bits(),
        fold.life_factor.to_bits(),
        "the held-out lives must not move the calibration"
    );
    assert!(alone.folds[0].held_out.is_empty());
    assert_eq!(fold.held_out.len(), 3);
    for l in &fold.held_out {
        eprintln!(
            "{}: end level {:?} in [{:?}, {:?}], onset->failure h {:?} vs median {:?}, coverage {:.2}/{:.2}",
            l.id,
            l.end_level.measured,
            l.end_level.low,
            l.end_level.high,
            l.onset_to_failure_h.measured,
            l.onset_to_failure_h.median,
            l.coverage_life,
            l.coverage_hours
        );
        for sp in [
            &l.onset,
            &l.onset_to_failure_h,
            &l.end_level,
            &l.end_ratio,
            &l.life_ratio,
        ] {
            if let (Some(lo), Some(m), Some(hi)) = (sp.low, sp.median, sp.high) {
                assert!(lo <= m && m <= hi, "{}: {lo} {m} {hi}", l.id);
            }
        }
        assert!((0.0..=1.0).contains(&l.coverage_life) && (0.0..=1.0).contains(&l.coverage_hours));
        assert!(l.distance_to_median_db.is_finite() && l.distance_to_median_db >= 0.0);
        assert!(l.distance_flat_db.is_finite() && l.distance_flat_db > 0.0);
        // The measured curve climbs after its onset, so the never-degrading null curve is
        // farther from it there than over the whole record (where the healthy part dilutes
        // it): the degradation part is where a model can be told from none.
        let late_flat = l
            .distance_late_flat_db
            .expect("every failed IMS life has an onset");
        assert!(
            late_flat > l.distance_flat_db,
            "{}: null curve {late_flat:.2} dB after the onset, {:.2} dB over the record",
            l.id,
            l.distance_flat_db
        );
        let end = &l.end_level;
        assert!(
            end.median.unwrap() > end.measured.unwrap(),
            "{}: the simulated end level is no longer above the measured one",
            l.id
        );
        let h = &l.onset_to_failure_h;
        assert!(
            h.median.unwrap() < h.measured.unwrap(),
            "{}: the simulated onset-to-failure time is no longer shorter than the measured",
            l.id
        );
    }
}

/// The population with both scales on the record's hours (`--ensemble 5 --calibrate
/// shape --frame record --primary-only`): the propagation limit puts the population's
/// median revolutions from onset to failure on test 2 bearing 1's measured ones (the life
/// factor its median life on the running revolutions), chosen by that life alone (the
/// calibration call the test above checks): that median, each life on its own time line,
/// is the measured one within 0.02 of the record (the calibration's onset tolerance). Read
/// on the record's hours a life whose damaged part is longer than the record shows only
/// the part inside it (seed 3's 185 h against the record's 163.5 h), so the median there
/// is at most the calibrated one (plus 0.02 of the record: the frame's own steady band can
/// move an onset by a window or two), and still past the record's first quarter.
#[test]
fn a_population_calibrated_in_both_scales_is_read_on_the_records_hours() {
    let Some(recs) = failed_lives() else {
        return;
    };
    let v = validate_ensemble(&recs, 1, 5, false, Calibration::Shape, Frame::Record).unwrap();
    assert_eq!(
        (v.calibration, v.frame),
        (Calibration::Shape, Frame::Record)
    );
    let fold = &v.folds[0];
    assert_eq!(fold.calibrated, Calibration::Shape);
    assert!(
        fold.converged,
        "the primary fold's calibration must reach its targets"
    );
    assert!(
        (fold.calibration_median_ratio - 1.0).abs() <= 0.01,
        "median life / record {}",
        fold.calibration_median_ratio
    );
    let on = &fold.calibration.onset;
    let (m, sim) = (on.measured.unwrap(), on.median.unwrap());
    assert!((m - 0.558).abs() < 0.001, "measured onset {m}");
    let h = &fold.calibration.onset_to_failure_h;
    let span = h.measured.unwrap() / (1.0 - m);
    let (hm, hs) = (h.measured.unwrap(), h.median.unwrap());
    let own = fold
        .calibration_median_onset_to_failure_h
        .expect("the population has onsets");
    assert!(
        (own - hm).abs() <= 0.02 * span,
        "calibrated median {own} h against {hm} h measured"
    );
    assert!(
        hs <= own + 0.02 * span && sim > 0.25,
        "on the record's hours: median {hs} h (onset {sim}) against {own} h calibrated"
    );
    assert_eq!(fold.held_out.len(), 3);
    for l in &fold.held_out {
        assert!(l.distance_to_median_hours_db.is_finite() && l.distance_late_flat_db.is_some());
        eprintln!(
            "{}: onset {:?} vs median {:?}; onset->failure h {:?} vs {:?}; coverage hours {:.2}; after onset: median {:?} seed {:?} null {:?} dB",
            l.id, l.onset.measured, l.onset.median, l.onset_to_failure_h.measured,
            l.onset_to_failure_h.median, l.coverage_hours, l.distance_late_to_median_db,
            l.distance_late_db.median, l.distance_late_flat_db
        );
    }
}

#[test]
fn a_bad_ensemble_is_refused_before_anything_is_read() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let run = |extra: &[&str]| {
        let mut a = vec!["ims-validate", "--data", s(dir.path()), "--out", s(&out)];
        a.extend_from_slice(extra);
        wearsim(&a)
    };
    for n in ["4", "201"] {
        refused(&run(&["--ensemble", n]), &["--ensemble", "5..=200"]);
    }
    refused(
        &run(&["--ensemble", "5", "--seeds", "2"]),
        &["--ensemble", "--seeds"],
    );
    refused(
        &run(&["--ensemble", "5", "--seed", "18446744073709551614"]),
        &["--ensemble", "overflows"],
    );
    refused(
        &run(&["--ensemble", "5", "--floor"]),
        &["--ensemble", "--floor"],
    );
    // The population takes both calibrations and time lines: the empty data folder, not
    // the flags, is what stops this one.
    refused(
        &run(&[
            "--ensemble",
            "5",
            "--calibrate",
            "shape",
            "--frame",
            "record",
        ]),
        &["test2_timefeatures.csv"],
    );
    refused(&run(&["--frame", "clock"]), &["--frame", "life", "record"]);
    refused(
        &run(&["--calibrate", "onset"]),
        &["--calibrate", "length", "shape"],
    );
    assert!(!out.exists(), "nothing may be written");
}

/// `--seeds` outside 1..=64: exit 2 naming it, before any file is read, nothing written.
#[test]
fn a_bad_seed_count_is_refused_before_anything_is_read() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    for n in ["0", "65"] {
        let o = wearsim(&[
            "ims-validate",
            "--data",
            s(dir.path()),
            "--seeds",
            n,
            "--out",
            s(&out),
        ]);
        refused(&o, &["--seeds", "1..=64"]);
        assert!(!out.exists(), "nothing may be written");
    }
}

/// A `--measured-floor` that reads a life's steady level as more background than the
/// sensor can add (1e-4 units per m/s² puts test 2 bearing 1 at about 770 m/s²) is refused
/// naming the flag before any life is simulated (it was exit 1 naming `sensor.noise`).
#[test]
fn a_measured_floor_beyond_the_sensor_is_refused_naming_the_flag() {
    let Some(data) = data_dir().expect("data folder required when CI=true") else {
        eprintln!("skipping: measured data folder not found (set WEARSIM_DATA)");
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    for u in ["1e-4", "1e-300"] {
        let o = wearsim(&[
            "ims-validate",
            "--data",
            s(&data),
            "--measured-floor",
            u,
            "--primary-only",
            "--out",
            s(&out),
        ]);
        refused(&o, &["--measured-floor", "t2b1", "0 ..= 100 m/s²"]);
        assert!(!out.exists(), "nothing may be written");
    }
}

/// Over seeds, each figure's median is taken on its own (the end factor through its
/// logarithm, so ×3 and ×1/3 weigh alike), and acceptance is judged on those medians.
#[test]
fn medians_over_seeds_take_each_figure_apart() {
    let m = |o: f64, e: f64, d: f64| Medians {
        onset_error: o,
        end_ratio_factor: e,
        distance_db_rms: d,
        accepted: [o <= 0.1, e <= 2.0, d <= 3.0],
    };
    let run = |seed: u64, med: Medians| Validation {
        seed,
        floor_mode: FloorMode::None,
        calibration: Calibration::Length,
        frame: Frame::Life,
        records: vec![],
        folds: vec![],
        leave_one_out: med,
        leave_one_out_copy: med,
        over_seeds: None,
    };
    let sw = over_seeds(&[
        run(1, m(0.05, 1.5, 2.0)),
        run(2, m(0.3, 3.0, 4.0)),
        run(3, m(0.1, 1.8, 3.5)),
    ]);
    assert_eq!(
        sw.seeds.iter().map(|s| s.seed).collect::<Vec<_>>(),
        [1, 2, 3]
    );
    let l = sw.leave_one_out;
    assert!((l.onset_error - 0.1).abs() < 1e-12, "{l:?}");
    assert!((l.end_ratio_factor - 1.8).abs() < 1e-9, "{l:?}");
    assert!((l.distance_db_rms - 3.5).abs() < 1e-12, "{l:?}");
    assert_eq!(l.accepted, [true, true, false]);
}

fn curve(v: &[f64]) -> Curve {
    let n = v.len() as f64 - 1.0;
    Curve {
        t: (0..v.len()).map(|i| i as f64 / n).collect(),
        rms: v.to_vec(),
    }
}

/// A curve twice the other everywhere is 6.02 dB away; identical curves 0 dB.
#[test]
fn distance_of_a_constant_factor_is_its_decibels() {
    let a = curve(&[1.0, 1.0, 2.0, 4.0]);
    let b = curve(&[2.0, 2.0, 4.0, 8.0]);
    assert!((distance_db(&b, &a) - 20.0 * 2f64.log10()).abs() < 1e-9);
    assert!(distance_db(&a, &a).abs() < 1e-12);
}

/// Medians: an end factor of ×4 and ×1/4 both count as 4; no onset counts as an
/// error of 1.
#[test]
fn medians_are_symmetric_in_the_end_factor() {
    let f = |e: f64, o: Option<f64>| LifeFigures {
        id: "x".into(),
        role: "held-out".into(),
        onset_measured: Some(0.5),
        onset_simulated: o,
        onset_error: o.map(|o| (o - 0.5).abs()),
        onset_to_failure_h_measured: None,
        onset_to_failure_h_simulated: None,
        distance_db_rms: 2.0,
        end_ratio_measured: 1.0,
        end_ratio_simulated: e,
        end_ratio_factor: e,
        end_level_measured: 1.0,
        end_level_simulated: e,
        floor: 0.0,
        life_ratio: 1.0,
        steady_measured: 1.0,
        steady_simulated: 1.0,
        end_simulated_abs: 1.0,
        stages: vec![],
    };
    let m = medians(&[f(4.0, Some(0.55)), f(0.25, None), f(4.0, Some(0.6))]);
    assert!((m.end_ratio_factor - 4.0).abs() < 1e-9);
    assert!((m.onset_error - 0.1).abs() < 1e-9);
    assert_eq!(m.accepted, [true, false, true]);
}

/// The floor that brings a simulated life to a target end ratio: noise adds in power, so
/// a bearing going from 1 to 130 m/s² reads 6.26 × its floored steady level with
/// `N² = (130² − 6.26²·1²)/(6.26² − 1)`; a floor cannot raise a ratio (0 when the bearing
/// alone ends below the target).
#[test]
fn the_floor_for_an_end_ratio_follows_from_power_addition() {
    use wearsim_host::life::ims_validate::{floor_for_end_ratio, SimLife};
    let mut rms = vec![1.0; 10];
    rms.push(130.0);
    let s = SimLife {
        revs: (0..11).map(|i| i as f64).collect(),
        mean_abs: rms.clone(),
        rms,
        life: 10.0,
        stages: vec![],
        fixed: 0.0,
    };
    let n = floor_for_end_ratio(&s, 6.26);
    let floored = |r: f64| (r * r + n * n).sqrt();
    assert!((floored(130.0) / floored(1.0) - 6.26).abs() < 1e-9, "{n}");
    assert_eq!(floor_for_end_ratio(&s, 200.0), 0.0);
}

/// A measured background: the record's steady level in m/s² less, in power, the bearing's
/// own; a mean-|x| level is converted by √(π/2) (Gaussian). 0.077 V of a 100 mV/g sensor
/// is 7.551 m/s²; with a bearing of 1 m/s² the background is √(7.551² − 1).
#[test]
fn the_measured_floor_is_the_steady_level_less_the_bearing() {
    use wearsim_host::life::ims_validate::{measured_floor, MeasuredRecord, SimLife};
    let bare = SimLife {
        revs: vec![0.0, 1.0, 2.0],
        rms: vec![1.0, 1.0, 50.0],
        mean_abs: vec![0.8, 0.8, 40.0],
        life: 2.0,
        stages: vec![],
        fixed: 0.0,
    };
    let m = |i: usize| MeasuredRecord {
        record: RECORDS[i],
        curve: Curve {
            t: vec![0.0, 1.0],
            rms: vec![1.0, 6.0],
        },
        running_h: 1.0,
        clock_h: 1.0,
        gaps: 0,
        dropped: 0,
        steady: 0.077,
    };
    let v_per_ms2: f64 = 0.1 / 9.80665;
    let level = 0.077 / v_per_ms2;
    assert!((level - 7.5515).abs() < 1e-3);
    let f = measured_floor(&m(0), &bare, v_per_ms2);
    assert!((f - (level * level - 1.0).sqrt()).abs() < 1e-9, "{f}");
    let l3 = level * (std::f64::consts::PI / 2.0).sqrt();
    let f3 = measured_floor(&m(3), &bare, v_per_ms2);
    assert!((f3 - (l3 * l3 - 1.0).sqrt()).abs() < 1e-9, "{f3}");
    // Read in g the level is 0.755 m/s², below the bearing's own: no background.
    assert_eq!(measured_floor(&m(0), &bare, 1.0 / 9.80665), 0.0);
}

fn measured(v: &[f64]) -> MeasuredRecord {
    MeasuredRecord {
        record: RECORDS[0],
        curve: curve(v),
        running_h: 100.0,
        clock_h: 100.0,
        gaps: 0,
        dropped: 0,
        steady: 1.0,
    }
}

/// The reference prediction without a model: a life against itself is exact (onset error
/// 0, end factor 1, 0 dB); against another it is the other's onset, end ratio and curve:
/// flat at 1, one rising to 3 from snapshot 24 of 40 and one to 6 from snapshot 32.
#[test]
fn the_calibration_life_as_the_prediction_gives_its_own_figures() {
    let step = |at: usize, to: f64| -> Vec<f64> {
        (0..40).map(|i| if i < at { 1.0 } else { to }).collect()
    };
    let (cal, held) = (measured(&step(24, 3.0)), measured(&step(32, 6.0)));
    let (o, e, d) = copy_calibration(&cal, &cal, Frame::Life);
    assert_eq!((o, e, d), (Some(0.0), 1.0, 0.0));
    let (o, e, d) = copy_calibration(&cal, &held, Frame::Life);
    assert!((o.unwrap() - 8.0 / 39.0).abs() < 1e-12, "{o:?}");
    assert!((e - 0.5).abs() < 1e-12, "{e}");
    assert!((d - distance_db(&cal.curve, &held.curve)).abs() < 1e-12);
    // 9.54 dB (×3) over about 0.2 of life and 6.02 dB (×2) over the last 0.18, 0 before:
    // √(0.2·91 + 0.18·36.2) ≈ 5.0 dB RMS.
    assert!((4.5..5.5).contains(&d), "{d}");
    // Medians take the end factor symmetrically: ×0.5 and ×2 both count as 2.
    let m = copy_calibration_medians(&[(&cal, &held), (&held, &cal)], Frame::Life);
    assert!((m.end_ratio_factor - 2.0).abs() < 1e-9, "{m:?}");
    assert!((m.onset_error - 8.0 / 39.0).abs() < 1e-12, "{m:?}");
    // On the record's running hours the calibration life's hours from onset to failure
    // carry over: 15/39 of its 100 h = 38.5 h, on a held-out record of 200 h an onset at
    // 1 − 38.5/200 = 0.808 against that record's 32/39 = 0.821.
    let held = MeasuredRecord {
        running_h: 200.0,
        ..held
    };
    let (o, e, _) = copy_calibration(&cal, &held, Frame::Record);
    let want: f64 = 32.0 / 39.0 - (1.0 - 100.0 * 15.0 / 39.0 / 200.0);
    // The onset snaps to the carried curve's windows (100/39 h apart, 1/78 of the record).
    assert!(
        (o.unwrap() - want).abs() <= 1.0 / 78.0 + 1e-12,
        "{o:?} vs {want}"
    );
    assert!((e - 0.5).abs() < 1e-12, "{e}");
}

/// The reference prediction on the measured lives, leave-one-life-out (every failed IMS
/// life predicted by each other one's measured curve, no model): its median trajectory
/// distance is below issue 14's 3 dB (2.29 dB; the simulated lives give 3.1-6.7 dB), so
/// that target does not tell a model from none, and its onset error is about 0.2 of life
/// (0.199), which the model does not beat either (docs/ims-comparison.md).
#[test]
fn another_measured_life_predicts_a_held_out_life_within_three_decibels() {
    let Some(recs) = failed_lives() else {
        return;
    };
    let pairs: Vec<(&MeasuredRecord, &MeasuredRecord)> = recs
        .iter()
        .flat_map(|c| {
            recs.iter()
                .filter(move |m| m.record.id != c.record.id)
                .map(move |m| (c, m))
        })
        .collect();
    assert_eq!(pairs.len(), 12);
    let m = copy_calibration_medians(&pairs, Frame::Life);
    eprintln!("copy-calibration leave-one-life-out: {m:?}");
    assert!((2.0..2.6).contains(&m.distance_db_rms), "{m:?}");
    assert!((0.15..0.25).contains(&m.onset_error), "{m:?}");
    assert!((2.0..3.0).contains(&m.end_ratio_factor), "{m:?}");
    // On running hours aligned at failure, the calibration life's hours from onset to
    // failure predict a held-out onset within 0.086 of the record (median of 12): the
    // hours carry over between these lives better than the fraction of record does.
    let r = copy_calibration_medians(&pairs, Frame::Record);
    eprintln!("copy-calibration on the record's hours: {r:?}");
    assert!((0.06..0.11).contains(&r.onset_error), "{r:?}");
    assert!(r.onset_error < m.onset_error - 0.05, "{r:?} vs {m:?}");
}
