//! CWRU benchmark (Smith & Randall 2015 data set) with the held-out split of
//! `cwru_benchmark::part_of`: the evaluation part (drive end, 2-3 hp), which chose nothing,
//! must keep the inner+outer-race figure measured when the method was fixed, the normal
//! baseline must be called healthy, no race fault may be called as the other race, and the
//! confidence calibration in force must be the one that code fits on the development part
//! (drive end, 0-1 hp) only. Skips with a message when the data folder is absent, fails when
//! it is absent and `CI=true` (see `io::data_dir`).

use wearsim_host::analysis::chain::Method;
use wearsim_host::analysis::diagnose::CALIBRATION;
use wearsim_host::analysis::FaultFamily;
use wearsim_host::cwru_benchmark::{print_report, run_benchmark, to_markdown, Part};

/// Evaluation-part inner+outer-race records called correctly when the method was fixed
/// (`wearsim cwru-benchmark`, docs/cwru-benchmark.md), out of 20.
const EVAL_CORRECT: usize = 18;
/// Allowed regression, records (one record = 5 %).
const EVAL_SLACK: usize = 1;

/// The CWRU folder of the measured data, `None` (with a message) when it is missing
/// outside CI; with `CI=true` a missing folder is an error.
fn cwru_dir() -> Result<Option<std::path::PathBuf>, Box<dyn std::error::Error>> {
    let Some(dir) = wearsim_host::io::data_dir()? else {
        eprintln!("skipping: CWRU data not found (set WEARSIM_DATA)");
        return Ok(None);
    };
    let cwru = dir.join("cwru");
    if !cwru.is_dir() {
        if std::env::var("CI").is_ok_and(|v| v == "true" || v == "1") {
            return Err(format!("{} is missing", cwru.display()).into());
        }
        eprintln!("skipping: {} not found", cwru.display());
        return Ok(None);
    }
    Ok(Some(cwru))
}

#[test]
fn cwru_held_out_figures_hold() -> Result<(), Box<dyn std::error::Error>> {
    let Some(dir) = wearsim_host::io::data_dir()? else {
        eprintln!("skipping: CWRU data not found (set WEARSIM_DATA)");
        return Ok(());
    };
    if !dir.join("cwru").is_dir() {
        if std::env::var("CI").is_ok_and(|v| v == "true" || v == "1") {
            return Err(format!("{}/cwru is missing", dir.display()).into());
        }
        eprintln!("skipping: {}/cwru not found", dir.display());
        return Ok(());
    }
    let variants = std::env::var("WEARSIM_BENCH_VARIANTS").is_ok();
    let r = run_benchmark(&dir, &Method::default(), variants)?;
    print_report(&r);
    // Opt-in: write the Markdown report (the same text as `wearsim cwru-benchmark --markdown`,
    // from an optimised build; with WEARSIM_BENCH_VARIANTS=1 for the per-record table).
    if let Ok(path) = std::env::var("WEARSIM_BENCH_MARKDOWN") {
        std::fs::write(&path, to_markdown(&r))?;
    }
    let group = |g: &str| r.accuracy_of(g).ok_or(format!("no group {g}"));
    let eval = group("evaluation IR+OR")?;
    let dev = group("development IR+OR")?;
    let normal = group("normal")?;
    assert_eq!(dev.total, 20, "expected 20 development IR/OR records");
    assert_eq!(eval.total, 20, "expected 20 evaluation IR/OR records");
    assert_eq!(normal.total, 1, "expected the normal baseline");
    assert!(
        eval.correct + EVAL_SLACK >= EVAL_CORRECT,
        "evaluation IR+OR {}/{} < recorded {EVAL_CORRECT} - {EVAL_SLACK}: {:?}",
        eval.correct,
        eval.total,
        r.confusion
    );
    assert_eq!(normal.correct, 1, "normal baseline diagnosed as a fault");
    assert!(r.files.iter().all(|f| f.error.is_none()));
    assert!(r.files.iter().all(|f| (0.0..=1.0).contains(&f.confidence)));
    let total: usize = r.confusion.iter().flatten().sum();
    assert_eq!(total, r.files.len());
    // On the drive end no race fault is taken for the other race, and no record of either
    // part is called as a wrong family (fan-end figures are reported, not asserted: one
    // fan-end outer-race record is called inner race, docs/cwru-benchmark.md).
    let de = |f: &&wearsim_host::cwru_benchmark::FileResult| {
        matches!(f.part, Part::Development | Part::Evaluation)
            && matches!(f.truth, FaultFamily::InnerRace | FaultFamily::OuterRace)
    };
    let wrong: Vec<&str> = r
        .files
        .iter()
        .filter(de)
        .filter(|f| !f.correct && f.predicted != FaultFamily::None)
        .map(|f| f.file.as_str())
        .collect();
    assert!(
        wrong.is_empty(),
        "race records called as a wrong family: {wrong:?}"
    );
    // The calibration in force is the one fitted on the development part only.
    let fitted = r.calibration_fitted.ok_or("no calibration fit")?;
    assert!(
        (fitted.slope - CALIBRATION.slope).abs() < 1e-3
            && (fitted.centre - CALIBRATION.centre).abs() < 1e-2,
        "recorded {CALIBRATION:?} but the development part fits {fitted:?}"
    );
    Ok(())
}

/// Why the OR014@6 drive-end bearing is missed (issue 12; development records 197 and 198,
/// 0 and 1 hp, the only records of that bearing the method may be studied on): none of the
/// file's three accelerometers (DE, FE, BA) shows an outer-race harmonic family. With the
/// method's own chain and the 6205 geometry, at most one of the five BPFO harmonics clears
/// the detector's threshold on any channel, no channel supports any call, and the raw record
/// is not impulsive (kurtosis below 3.5, where a Gaussian record has 3 and the clearly
/// diagnosed CWRU drive-end faults have 5 to 22). Fusing channels or demodulating elsewhere therefore cannot
/// call these records outer race from evidence; if this test starts to fail, a change has
/// made the detector find a family where there was none, or the data changed.
#[test]
fn or014_at_6_development_records_hold_no_outer_race_family_on_any_channel(
) -> Result<(), Box<dyn std::error::Error>> {
    let Some(cwru) = cwru_dir()? else {
        return Ok(());
    };
    for file in [
        "12k_Drive_End_OR014@6_0_197.mat",
        "12k_Drive_End_OR014@6_1_198.mat",
    ] {
        for channel in ["DE", "FE", "BA"] {
            let rec = wearsim_host::io::read_cwru(cwru.join(file), channel, None)?;
            let rpm = rec.rpm.ok_or("no rpm")?;
            let kin = wearsim_host::kinematics::of_preset("cwru-6205-de", rpm)?;
            let a = wearsim_host::analysis::chain::analyze_signal(
                &rec.samples,
                rec.fs,
                &kin,
                &Method::default(),
            )?;
            let outer = a
                .diagnosis
                .evidence
                .iter()
                .find(|e| e.family == FaultFamily::OuterRace)
                .ok_or("no outer-race evidence")?;
            assert!(
                outer.found <= 1,
                "{file} {channel}: {} BPFO harmonics found",
                outer.found
            );
            assert_eq!(
                a.diagnosis.family,
                FaultFamily::None,
                "{file} {channel}: a call without evidence"
            );
            assert!(
                a.stats.kurtosis < 3.5,
                "{file} {channel}: kurtosis {}",
                a.stats.kurtosis
            );
        }
    }
    Ok(())
}

/// Sample-rate invariance on measured records (issue 12): every development inner/outer-race
/// record (drive end, 0-1 hp) and the normal baseline (48 kHz, decimated to 12 kHz as in the
/// benchmark), resampled band-limited from 12 kHz to 25.6, 48 and 97.656 kHz (rates of the
/// owner's other rigs; `cwru_benchmark::resample_fft`, nothing added above 6 kHz), keep the
/// family they get at 12 kHz. The simulated invariance test cannot show this: here the
/// record's content stays below 6 kHz while the rate moves. With demodulation bands cut in
/// fractions of fs/2 (before the grid fixed in Hz), evaluation record 200 (OR014@6, 3 hp) was
/// called inner race at 25.6 and 97.656 kHz though `None` at 12 kHz; the evaluation records
/// are judged with `wearsim cwru-benchmark --resample HZ` (docs/cwru-detector.md), not here.
///
/// The same for a window cut from each record (what an acquisition of a longer stream is),
/// whose ends do not meet, with the confidence of a call within 0.05 at 25.6 and 48 kHz.
/// Measured (stop 54): whole records within 0.0004 of their 12 kHz confidence; windows
/// within 0.05 at every rate (97.656 kHz included) except the one missed record OR014@6
/// 1 hp, `None` at every rate with the confidence of its weak partial family 0.21 → 0.72 at
/// 25.6 and 48 kHz. Before the chain chose its band on the record with faded ends, the
/// windows' nearly empty upper bands held nothing but the step where their ends meet, which
/// the kurtogram chose: 5-9 of these 20 records stayed right at 25.6-97.656 kHz, some called
/// ball at confidence 1.00 (probe F).
#[test]
fn development_race_calls_survive_resampling() -> Result<(), Box<dyn std::error::Error>> {
    let Some(cwru) = cwru_dir()? else {
        return Ok(());
    };
    let (mut checked, mut baselines) = (0, 0);
    let mut worst = 0.0f64;
    let mut window_worst = 0.0f64;
    for entry in std::fs::read_dir(&cwru)? {
        let path = entry?.path();
        let name = wearsim_host::analyze::short_name(&path);
        let Some(label) = wearsim_host::io::parse_cwru_name(&name) else {
            continue;
        };
        let race = matches!(
            label.fault,
            wearsim_host::io::mat::CwruFault::InnerRace
                | wearsim_host::io::mat::CwruFault::OuterRace { .. }
        );
        let part = wearsim_host::cwru_benchmark::part_of(&label);
        let baseline = part == Part::Baseline;
        if !(baseline || race && part == Part::Development) {
            continue;
        }
        let rec = wearsim_host::io::read_cwru(&path, "DE", None)?;
        let factor = (rec.fs / 12_000.0).round() as usize;
        let samples = wearsim_host::cwru_benchmark::decimate_fft(&rec.samples, factor);
        let fs0 = rec.fs / factor as f64;
        let kin = wearsim_host::kinematics::of_preset("cwru-6205-de", rec.rpm.ok_or("no rpm")?)?;
        let call = |x: &[f64], fs: f64| -> Result<(FaultFamily, f64), Box<dyn std::error::Error>> {
            let d = wearsim_host::analysis::chain::analyze_signal(x, fs, &kin, &Method::default())?
                .diagnosis;
            Ok((d.family, d.confidence))
        };
        let (reference, confidence) = call(&samples, fs0)?;
        if baseline {
            assert_eq!(reference, FaultFamily::None, "{name} at {fs0} Hz");
        }
        for fs in [25_600.0, 48_000.0, 97_656.25] {
            let m = (samples.len() as f64 * fs / fs0).round() as usize;
            let x = wearsim_host::cwru_benchmark::resample_fft(&samples, m);
            let (got, c) = call(&x, fs)?;
            eprintln!("{name}, whole at {fs} Hz: {got:?} {c:.3} against {confidence:.3}");
            assert_eq!(got, reference, "{name} at {fs} Hz");
            worst = worst.max((c - confidence).abs());
        }
        // A window of a longer stream: the same stretch (0.3 s off the start, 0.2 s off
        // the end) at 12 kHz and resampled, whose ends do not meet.
        let cut = |x: &[f64], fs: f64| -> Vec<f64> {
            let (a, b) = ((0.3 * fs) as usize, (0.2 * fs) as usize);
            x[a..x.len() - b].to_vec()
        };
        let (window_call, window_confidence) = call(&cut(&samples, fs0), fs0)?;
        for fs in [25_600.0, 48_000.0, 97_656.25] {
            let m = (samples.len() as f64 * fs / fs0).round() as usize;
            let x = cut(&wearsim_host::cwru_benchmark::resample_fft(&samples, m), fs);
            let (got, c) = call(&x, fs)?;
            eprintln!("{name}, a window at {fs} Hz: {got:?} {c:.3} against {window_confidence:.3}");
            assert_eq!(got, window_call, "{name}, a window at {fs} Hz");
            if fs < 60_000.0 && window_call != FaultFamily::None {
                assert!(
                    (c - window_confidence).abs() <= 0.05,
                    "{name}, a window at {fs} Hz: confidence {c} against {window_confidence} at {fs0} Hz"
                );
            }
            window_worst = window_worst.max((c - window_confidence).abs());
        }
        if baseline {
            baselines += 1;
        } else {
            checked += 1;
        }
    }
    eprintln!("largest confidence change over the rates: {worst:.4}, windows {window_worst:.4}");
    assert_eq!(checked, 20, "expected the 20 development IR/OR records");
    assert_eq!(baselines, 1, "expected the normal baseline");
    Ok(())
}

/// The speed check (`analysis::shaft_line`) on measured records: at their own rate every
/// development record's shaft line is where rate and speed put it; analysed as if sampled
/// at half their rate (the true 1× on ½×) or at 0.8 of it, each is flagged. Thresholds
/// were set before any record was read; `docs/cwru-detector.md` has every part's figures.
#[test]
fn the_speed_check_accepts_the_true_rate_and_flags_wrong_ones(
) -> Result<(), Box<dyn std::error::Error>> {
    use wearsim_host::analysis::shaft_line::check;
    let Some(cwru) = cwru_dir()? else {
        return Ok(());
    };
    for name in [
        "12k_Drive_End_IR007_0_105.mat",
        "12k_Drive_End_B014_1_186.mat",
        "12k_Drive_End_OR007@6_0_130.mat",
        "12k_Drive_End_OR021@12_1_259.mat",
    ] {
        let rec = wearsim_host::io::read_any(
            cwru.join(name),
            &wearsim_host::io::ReadOptions {
                channel: Some("DE".into()),
                ..Default::default()
            },
        )?;
        let shaft = rec.rpm.ok_or("rpm")? / 60.0;
        let own = check(&rec.samples, rec.fs, shaft).ok_or("checkable")?;
        assert!(own.consistent, "{name}: {own:?}");
        for k in [0.5, 0.8] {
            let c = check(&rec.samples, k * rec.fs, shaft).ok_or("checkable")?;
            assert!(!c.consistent, "{name} at {k} x fs: {c:?}");
        }
    }
    Ok(())
}

/// A speed a few percent off (`analysis::shaft_line::refine`): development records given
/// 0.97 × and 1.03 × their stored speed are analysed at their own 1× line (within 0.5 % of
/// the stored speed) and keep their family — at the stated speed they were called ball or
/// nothing (probe F). `--trust-rpm` keeps the stated speed. Record 279 stores the 3 hp
/// speed, 1 732 rpm, for a 1 hp run; the data README measures its 1× line at 1 774 rpm, and
/// so does `analyze` (within 0.1 %: the speed is fitted to the shaft's series). Stored
/// speeds the record confirms are kept.
#[test]
fn a_speed_a_few_percent_off_is_measured_from_the_shaft_line(
) -> Result<(), Box<dyn std::error::Error>> {
    use wearsim_host::analysis::shaft_line::REFINED_SOURCE;
    use wearsim_host::analyze::{analyze, AnalyzeArgs};
    let Some(cwru) = cwru_dir()? else {
        return Ok(());
    };
    let run = |name: &str, rpm: Option<f64>, trust: bool| {
        let mut a = AnalyzeArgs::for_file(cwru.join(name));
        a.rpm = rpm;
        a.trust_rpm = trust;
        analyze(&a).map(|(an, _)| an)
    };
    for (name, stored, family) in [
        (
            "12k_Drive_End_IR007_0_105.mat",
            1797.0,
            FaultFamily::InnerRace,
        ),
        (
            "12k_Drive_End_OR021@6_1_235.mat",
            1771.0,
            FaultFamily::OuterRace,
        ),
        // At 0.98 × its stored speed the true 1× is 1.6–2 % away, inside the ±1 % window
        // once rounded to whole 0.39 Hz bins: it "confirmed" the wrong speed and the call
        // was ball 0.92 (stop 55); the window is exact since stop 56.
        (
            "12k_Drive_End_OR021@6_0_234.mat",
            1796.0,
            FaultFamily::OuterRace,
        ),
    ] {
        let own = run(name, None, false)?;
        assert_eq!((own.speed_refined, own.rpm), (None, stored), "{name}");
        for k in [0.97, 0.98, 1.03] {
            let a = run(name, Some(k * stored), false)?;
            let r = a.speed_refined.ok_or(format!("{name} x{k}: not refined"))?;
            assert!((a.rpm / stored - 1.0).abs() < 0.005, "{name} x{k}: {r:?}");
            assert_eq!(a.rpm_source, REFINED_SOURCE);
            assert!(a.rpm_detail.contains("argument"), "{}", a.rpm_detail);
            assert_eq!(a.diagnosis.family, family, "{name} x{k}: {:?}", a.diagnosis);
            let kept = run(name, Some(k * stored), true)?;
            assert_eq!(kept.speed_refined, None);
            assert_eq!(
                (kept.rpm, kept.rpm_source.as_str()),
                (k * stored, "argument")
            );
        }
    }
    let a = run("12k_Fan_End_IR007_1_279.mat", None, false)?;
    let r = a.speed_refined.ok_or("279: not refined")?;
    assert!((60.0 * r.stated_hz - 1732.0).abs() < 1e-9, "{r:?}");
    assert!((a.rpm / 1774.0 - 1.0).abs() < 0.001, "{r:?}");
    assert_eq!(a.diagnosis.family, FaultFamily::InnerRace);
    // Record 158 stores 1 773 rpm; its full spectrum's shaft series says 1 796 and its BPFO
    // line 1 803 (`docs/cwru-detector.md`). The 1× line alone read a stronger line beside it
    // (1 810, 0.8 % over); the series' fit lands within 0.3 % (stop 57).
    let a = run("12k_Drive_End_OR007@12_1_158.mat", None, false)?;
    let r = a.speed_refined.ok_or("158: not refined")?;
    assert!((a.rpm / 1796.0 - 1.0).abs() < 0.003, "{r:?}");
    assert!(r.harmonics >= 3, "{r:?}");
    assert_eq!(a.diagnosis.family, FaultFamily::OuterRace);
    assert_eq!(run("normal_0_97.mat", None, false)?.speed_refined, None);
    Ok(())
}

/// A burst that is not the bearing (`analysis::transients`): 0.2 s of noise clipped at
/// 10 × the record's peak, before or after development records, made the chain call ball
/// or another race at up to 0.99 (probe F: 53 wrong families in 80 drive-end runs). Cut out
/// with a block on each side, the records keep their family; the record as given is what the
/// statistics describe.
#[test]
fn a_burst_before_or_after_a_record_is_cut_out_and_the_call_kept(
) -> Result<(), Box<dyn std::error::Error>> {
    use wearsim_host::analysis::chain::analyze_signal;
    let Some(cwru) = cwru_dir()? else {
        return Ok(());
    };
    for (name, family) in [
        ("12k_Drive_End_IR007_0_105.mat", FaultFamily::InnerRace),
        ("12k_Drive_End_OR007@6_1_131.mat", FaultFamily::OuterRace),
    ] {
        let rec = wearsim_host::io::read_cwru(cwru.join(name), "DE", None)?;
        let kin = wearsim_host::kinematics::of_preset("cwru-6205-de", rec.rpm.ok_or("no rpm")?)?;
        let peak = rec.samples.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let n = (0.2 * rec.fs) as usize;
        let burst: Vec<f64> = wearsim_host::analysis::synth::gaussian_noise(n, 30.0 * peak, 1)
            .into_iter()
            .map(|v| v.clamp(-10.0 * peak, 10.0 * peak))
            .collect();
        let own = analyze_signal(&rec.samples, rec.fs, &kin, &Method::default())?;
        assert_eq!((own.diagnosis.family, &own.transients), (family, &None));
        let before = [burst.as_slice(), &rec.samples].concat();
        let after = [rec.samples.as_slice(), &burst].concat();
        for (at, x) in [("before", before), ("after", after)] {
            let a = analyze_signal(&x, rec.fs, &kin, &Method::default())?;
            assert_eq!(
                a.diagnosis.family, family,
                "{name}, burst {at}: {:?}",
                a.diagnosis
            );
            let t = a
                .transients
                .ok_or(format!("{name}, burst {at}: nothing cut"))?;
            let block = 60.0 / rec.rpm.ok_or("rpm")?;
            assert!(t.seconds >= 0.2 && t.seconds <= 0.2 + 3.0 * block, "{t:?}");
            assert_eq!(t.spans_s.len(), 1, "{t:?}");
            // The statistics are of the record as given, burst and all.
            assert!(a.stats.rms > 3.0 * own.stats.rms, "{:?}", a.stats);
        }
    }
    Ok(())
}

/// A CWRU fault read on the other end's channel is diagnosed for the faulty bearing its
/// file name names (as `gap` matches it): `12k_Drive_End_IR007_0` on `FE` for the drive-end
/// 6205 (`bearing_source` `label`) — an inner-race call, where the fan-end 6203's
/// frequencies gave none; a fan-end fault on `FE` and the normal record keep the channel's
/// bearing. Measured on all 40 drive-end IR/OR records' `FE` channels in
/// `docs/cwru-detector.md`.
#[test]
fn a_fault_read_on_the_other_channel_is_diagnosed_for_the_faulty_bearing(
) -> Result<(), Box<dyn std::error::Error>> {
    use wearsim_host::analyze::{analyze, AnalyzeArgs};
    let Some(cwru) = cwru_dir()? else {
        return Ok(());
    };
    let run = |name: &str| {
        let mut a = AnalyzeArgs::for_file(cwru.join(name));
        a.channel = Some("FE".into());
        analyze(&a).map(|(an, _)| an)
    };
    let de = run("12k_Drive_End_IR007_0_105.mat")?;
    assert_eq!(
        (de.bearing.as_str(), de.bearing_source.as_str()),
        ("cwru-6205-de", "label")
    );
    assert_eq!(
        de.diagnosis.family,
        FaultFamily::InnerRace,
        "{:?}",
        de.diagnosis
    );
    let fe = run("12k_Fan_End_IR007_1_279.mat")?;
    assert_eq!(
        (fe.bearing.as_str(), fe.bearing_source.as_str()),
        ("cwru-6203-fe", "file")
    );
    let normal = run("normal_0_97.mat")?;
    assert_eq!(normal.bearing, "cwru-6203-fe");
    Ok(())
}
