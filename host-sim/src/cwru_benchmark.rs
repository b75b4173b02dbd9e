//! CWRU benchmark: the `wearsim analyze` chain ([`crate::analysis::chain::analyze_signal`], one fixed
//! [`Method`]) on every 12 kHz drive-end record of the CWRU Bearing Data Center and on the
//! normal baseline, with a confusion matrix of the diagnosed fault family against the label
//! (Smith & Randall 2015, "Rolling element bearing diagnostics using the Case Western Reserve
//! University data: a benchmark study", MSSP 64-65).
//!
//! The records are split once, before anything was tuned ([`part_of`], the one place): the
//! drive-end records at 0 and 1 hp are the **development** part (every threshold and the
//! confidence calibration are chosen on them), the drive-end records at 2 and 3 hp the
//! **evaluation** part, the fan-end records (FE channel, `cwru-6203-fe` geometry) a further
//! held-out **other sensor position** set, and the 48 kHz normal baseline checks the healthy
//! call.
//!
//! Only the file's own speed (`XnnnRPM`) and the `cwru-6205-de` geometry enter the analysis;
//! the label parsed from the file name is used only to score the result. The 48 kHz normal
//! baseline is decimated by 4 (ideal FFT-domain anti-alias filter at 6 kHz) so that every
//! record is analysed over the same 0–6 kHz band.

use crate::analysis::chain::{analyze_signal, Method};
use crate::analysis::diagnose::{fit_logistic, Calibration, CALIBRATION};
use crate::analysis::FaultFamily;
use crate::analyze::family_name;
use crate::io::{mat, parse_cwru_name, CwruLabel};
use clap::Args;
use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// `wearsim cwru-benchmark` arguments.
#[derive(Debug, Clone, Args, Default)]
pub struct CwruBenchmarkArgs {
    /// Data folder holding `cwru/` (or the `cwru` folder itself); default `$WEARSIM_DATA`,
    /// else `../shared/data` beside the workspace.
    #[arg(long)]
    pub data: Option<PathBuf>,
    /// Print the report as JSON.
    #[arg(long)]
    pub json: bool,
    /// Also write the report as Markdown to this file (e.g. `docs/cwru-benchmark.md`).
    #[arg(long)]
    pub markdown: Option<PathBuf>,
    /// Skip the per-record comparison of raw, pre-whitened and SK-band envelopes (three
    /// times faster).
    #[arg(long)]
    pub no_variants: bool,
    /// Experiment: run the method with the squared envelope instead of the default; the
    /// figures are then not those of `wearsim analyze`.
    #[arg(long)]
    pub squared_envelope: bool,
    /// Experiment: choose the band by the evidence margin instead of the default; the
    /// figures are then not those of `wearsim analyze`.
    #[arg(long)]
    pub evidence_band: bool,
    /// Experiment: choose the band by the protrugram instead of the default.
    #[arg(long, conflicts_with = "evidence_band")]
    pub protrugram_band: bool,
    /// Experiment (issue 12, sample-rate invariance): resample every record, after its
    /// decimation to 12 kHz, band-limited to this rate (Hz, 1000..=1e6; by FFT: nothing
    /// is added above 6 kHz) before the analysis; the call of each record should not
    /// change.
    #[arg(long, value_name = "HZ")]
    pub resample: Option<f64>,
}

/// Part of the CWRU data a record belongs to (see [`part_of`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Part {
    /// Drive-end records at 0 and 1 hp: every threshold and the calibration are chosen here.
    Development,
    /// Drive-end records at 2 and 3 hp: judge only.
    Evaluation,
    /// Fan-end records on the FE channel: held-out other sensor position and bearing.
    FanEnd,
    /// Normal baseline(s): the healthy call.
    Baseline,
}

/// The split, decided before any tuning: drive-end 0–1 hp development, drive-end 2–3 hp
/// evaluation, fan end held out, normal baseline.
pub fn part_of(label: &CwruLabel) -> Part {
    match (&label.fault, label.fault_end.as_deref()) {
        (mat::CwruFault::Normal, _) => Part::Baseline,
        (_, Some("FE")) => Part::FanEnd,
        _ if label.load_hp <= 1 => Part::Development,
        _ => Part::Evaluation,
    }
}

/// Outcome of one envelope variant on one record, as in Smith & Randall (2015) Table 3:
/// `Y` the true family is called; `P` the true family leads the evidence but is not called
/// (confidence below one half); `N` otherwise (another family, or nothing).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Outcome {
    /// Diagnosed.
    Y,
    /// Partially diagnosed: leading, not called.
    P,
    /// Not diagnosed.
    N,
}

/// Sample rate at which every record is analysed, Hz.
pub const ANALYSIS_FS: f64 = 12_000.0;
/// Bearing preset of the CWRU drive end (SKF 6205-2RS JEM).
pub const BEARING: &str = "cwru-6205-de";
/// Bearing preset of the CWRU fan end (SKF 6203-2RS JEM).
pub const BEARING_FE: &str = "cwru-6203-fe";

/// The benchmark's classes, in confusion-matrix order.
pub const CLASSES: [FaultFamily; 4] = [
    FaultFamily::InnerRace,
    FaultFamily::OuterRace,
    FaultFamily::Ball,
    FaultFamily::None,
];

/// One analysed file.
#[derive(Debug, Clone, Serialize)]
pub struct FileResult {
    /// File name.
    pub file: String,
    /// CWRU record number.
    pub record: u32,
    /// True family from the label (`None` for the normal baseline).
    pub truth: FaultFamily,
    /// Defect diameter, inches (`None` for normal).
    pub diameter_in: Option<f64>,
    /// Outer-race clock position (3, 6, 12) if any.
    pub or_clock: Option<u8>,
    /// Motor load, hp.
    pub load_hp: u8,
    /// Part of the split.
    pub part: Part,
    /// Channel analysed (`DE` or `FE`).
    pub channel: String,
    /// Speed stored in the file, rpm.
    pub rpm: f64,
    /// Speed analysed at when the record's 1× line replaced the stored one
    /// ([`crate::analysis::shaft_line::refine`]), rpm; `None`: the stored speed.
    pub rpm_refined: Option<f64>,
    /// Diagnosed family (`None` also when the analysis failed, see `error`).
    pub predicted: FaultFamily,
    /// Calibrated confidence of the call, [0, 1].
    pub confidence: f64,
    /// Leading family before the confidence gate.
    pub candidate: FaultFamily,
    /// Evidence margin of the leading family, dB per harmonic.
    pub margin_db: f64,
    /// Score of the diagnosed family, dB per harmonic.
    pub score: f64,
    /// Exclusive scores of inner, outer, ball (dB per searched harmonic).
    pub family_scores: [f64; 3],
    /// Harmonics found for inner, outer, ball.
    pub family_found: [usize; 3],
    /// Demodulation band, Hz.
    pub band_hz: (f64, f64),
    /// Kurtosis of the demodulated band.
    pub band_kurtosis: f64,
    /// Whether `predicted == truth`.
    pub correct: bool,
    /// Outcomes of the raw envelope (whole band above the fault zone, no pre-whitening),
    /// the pre-whitened envelope (same band, cepstral pre-whitening) and the SK-band envelope
    /// (kurtogram band, pre-whitened: the method), if computed.
    pub variants: Option<[Outcome; 3]>,
    /// Read or analysis error, if any.
    pub error: Option<String>,
}

/// Accuracy of one group of files.
#[derive(Debug, Clone, Serialize)]
pub struct Accuracy {
    /// What the group is.
    pub group: String,
    /// Files correctly classified.
    pub correct: usize,
    /// Files in the group.
    pub total: usize,
    /// Files called as a wrong fault family (worse than no call).
    pub wrong_family: usize,
    /// `correct / total` (0 for an empty group).
    pub fraction: f64,
}

impl Accuracy {
    fn of<'a>(group: &str, rows: impl Iterator<Item = &'a FileResult>) -> Self {
        let (mut correct, mut total, mut wrong_family) = (0, 0, 0);
        for r in rows {
            total += 1;
            correct += usize::from(r.correct);
            wrong_family += usize::from(!r.correct && r.predicted != FaultFamily::None);
        }
        Accuracy {
            group: group.into(),
            correct,
            total,
            wrong_family,
            fraction: if total > 0 {
                correct as f64 / total as f64
            } else {
                0.0
            },
        }
    }
}

/// The benchmark report.
#[derive(Debug, Clone, Serialize)]
pub struct BenchmarkReport {
    /// The CWRU folder analysed.
    pub data_dir: PathBuf,
    /// The fixed method.
    pub method: Method,
    /// One row per file, sorted by class, size, clock, load.
    pub files: Vec<FileResult>,
    /// `confusion[t][p]`: files of true class `CLASSES[t]` diagnosed as `CLASSES[p]`.
    pub confusion: [[usize; 4]; 4],
    /// Accuracy per group (per part and for the whole set).
    pub accuracy: Vec<Accuracy>,
    /// Calibration in force ([`CALIBRATION`]).
    pub calibration: Calibration,
    /// Calibration refitted now on the development records only ([`fit_development`]);
    /// equal to `calibration` unless the chain changed since it was recorded.
    pub calibration_fitted: Option<Calibration>,
}

/// Fit the confidence calibration on the development records only: one pair (margin, the
/// top family is the true one) per development record with any evidence. The top family is
/// the leading family where there is one, else the family of highest exclusive score (the
/// best partial evidence, whose margin `margin_db` then is); a record whose families all
/// score 0 says nothing and is left out. Partial leads are included since the detector's
/// harmonic thresholds became false-alarm thresholds (stop 31): no development record's
/// leading family is then wrong, and a fit on leads alone has no wrong case to place its
/// centre (it diverges to "every lead is right").
pub fn fit_development(rows: &[FileResult]) -> Option<Calibration> {
    let pairs: Vec<(f64, bool)> = rows
        .iter()
        .filter(|r| r.part == Part::Development)
        .filter_map(|r| {
            let top = if r.candidate != FaultFamily::None {
                Some(r.candidate)
            } else {
                r.family_scores
                    .iter()
                    .zip(CLASSES)
                    .filter(|(s, _)| **s > 0.0)
                    .max_by(|a, b| a.0.total_cmp(b.0))
                    .map(|(_, f)| f)
            };
            top.map(|f| (r.margin_db, f == r.truth))
        })
        .collect();
    fit_logistic(&pairs)
}

impl BenchmarkReport {
    /// Accuracy of the named group (`"development IR+OR"`, `"evaluation IR+OR"`,
    /// `"drive end IR+OR"`, `"development ball"`, `"evaluation ball"`, `"fan end IR+OR"`,
    /// `"fan end ball"`, `"normal"`, `"all"`).
    pub fn accuracy_of(&self, group: &str) -> Option<&Accuracy> {
        self.accuracy.iter().find(|a| a.group == group)
    }
}

/// Index of a family in [`CLASSES`].
fn class_index(f: FaultFamily) -> usize {
    CLASSES.iter().position(|c| *c == f).unwrap_or(3)
}

/// True family of a label.
fn truth(label: &CwruLabel) -> FaultFamily {
    match label.fault {
        mat::CwruFault::Normal => FaultFamily::None,
        mat::CwruFault::InnerRace => FaultFamily::InnerRace,
        mat::CwruFault::Ball => FaultFamily::Ball,
        mat::CwruFault::OuterRace { .. } => FaultFamily::OuterRace,
    }
}

/// Decimate `x` by the integer `factor` with an ideal anti-alias low-pass (FFT of the whole
/// record, bins at or above the new Nyquist frequency dropped, inverse FFT of the kept bins).
/// The output has `x.len() / factor` samples (remainder dropped before the FFT).
pub fn decimate_fft(x: &[f64], factor: usize) -> Vec<f64> {
    if factor <= 1 {
        return x.to_vec();
    }
    let m = x.len() / factor;
    if m < 2 {
        return Vec::new();
    }
    let n = m * factor;
    let mut planner = RealFftPlanner::<f64>::new();
    let fwd = planner.plan_fft_forward(n);
    let inv = planner.plan_fft_inverse(m);
    let mut input = x[..n].to_vec();
    let mut spec = fwd.make_output_vec();
    if fwd.process(&mut input, &mut spec).is_err() {
        return Vec::new();
    }
    let mut small = inv.make_input_vec();
    let keep = small.len();
    small.copy_from_slice(&spec[..keep]);
    // Drop the new Nyquist bin (it would alias) and keep DC real.
    small[0] = Complex::new(small[0].re, 0.0);
    if m.is_multiple_of(2) {
        small[keep - 1] = Complex::new(0.0, 0.0);
    }
    inverse_scaled(inv.as_ref(), &mut small, n)
}

/// Band-limited resampling of `x` to `m` samples (ideal FFT interpolation or decimation:
/// the spectrum is zero-padded or truncated, so nothing is added above the lower of the two
/// Nyquist frequencies; the Nyquist bin of the lower rate is dropped), amplitude kept.
/// Empty if `x` or `m` has fewer than 2 samples.
pub fn resample_fft(x: &[f64], m: usize) -> Vec<f64> {
    let n = x.len();
    if n < 2 || m < 2 {
        return Vec::new();
    }
    let mut planner = RealFftPlanner::<f64>::new();
    let fwd = planner.plan_fft_forward(n);
    let inv = planner.plan_fft_inverse(m);
    let mut input = x.to_vec();
    let mut spec = fwd.make_output_vec();
    if fwd.process(&mut input, &mut spec).is_err() {
        return Vec::new();
    }
    let mut big = inv.make_input_vec();
    let keep = spec.len().min(big.len()) - 1;
    big[..keep].copy_from_slice(&spec[..keep]);
    big[0].im = 0.0;
    inverse_scaled(inv.as_ref(), &mut big, n)
}

/// Inverse real FFT of `spec` by `inv`, scaled by `1 / n` (`n` the forward FFT's length, so
/// the amplitude is kept); empty if the FFT fails.
fn inverse_scaled(inv: &dyn ComplexToReal<f64>, spec: &mut [Complex<f64>], n: usize) -> Vec<f64> {
    let mut out = inv.make_output_vec();
    if inv.process(spec, &mut out).is_err() {
        return Vec::new();
    }
    let scale = 1.0 / n as f64;
    out.iter_mut().for_each(|v| *v *= scale);
    out
}

/// The CWRU folder of a data folder: `dir/cwru` if it exists, else `dir`.
pub fn cwru_dir(dir: &Path) -> PathBuf {
    let sub = dir.join("cwru");
    if sub.is_dir() {
        sub
    } else {
        dir.to_path_buf()
    }
}

/// Analyse one file; `Err` carries a message naming the file.
fn analyse_file(
    path: &Path,
    label: &CwruLabel,
    method: &Method,
    variants: bool,
    resample: Option<f64>,
) -> Result<FileResult, String> {
    let name = crate::analyze::short_name(path);
    let part = part_of(label);
    let (channel, bearing) = if part == Part::FanEnd {
        ("FE", BEARING_FE)
    } else {
        ("DE", BEARING)
    };
    let rec = mat::read_cwru(path, channel, None).map_err(|e| e.to_string())?;
    let rpm = rec
        .rpm
        .ok_or_else(|| format!("{name}: no RPM variable in the file"))?;
    let factor = (rec.fs / ANALYSIS_FS).round() as usize;
    let (x, fs) = if factor > 1 && (rec.fs - factor as f64 * ANALYSIS_FS).abs() < 1e-6 {
        (decimate_fft(&rec.samples, factor), ANALYSIS_FS)
    } else {
        (rec.samples.clone(), rec.fs)
    };
    let (x, fs) = match resample {
        Some(rate) if rate.is_finite() && (1e3..=1e6).contains(&rate) => {
            let m = (x.len() as f64 * rate / fs).round() as usize;
            (resample_fft(&x, m), rate)
        }
        Some(rate) => return Err(format!("{name}: resample rate {rate} Hz not in 1000..=1e6")),
        None => (x, fs),
    };
    // As `analyze` does: a stored speed the record's own 1× line contradicts is replaced.
    let refined = crate::analysis::shaft_line::refine(&x, fs, rpm / 60.0);
    let rpm_used = refined.map_or(rpm, |r| r.rpm());
    let kin =
        crate::kinematics::of_preset(bearing, rpm_used).map_err(|e| format!("{name}: {e}"))?;
    let a = analyze_signal(&x, fs, &kin, method).map_err(|e| format!("{name}: {e}"))?;
    let d = &a.diagnosis;
    let t = truth(label);
    let outcome = |d: &crate::analysis::FaultDiagnosis| {
        if d.family == t {
            Outcome::Y
        } else if d.candidate == t {
            Outcome::P
        } else {
            Outcome::N
        }
    };
    let variants = if variants {
        let mut out = [Outcome::N; 3];
        for (i, (prewhiten, kurtogram_band)) in [(false, false), (true, false), (true, true)]
            .into_iter()
            .enumerate()
        {
            let m = Method {
                prewhiten,
                kurtogram_band,
                ..*method
            };
            out[i] = if m == *method {
                outcome(d)
            } else {
                let v = analyze_signal(&x, fs, &kin, &m).map_err(|e| format!("{name}: {e}"))?;
                outcome(&v.diagnosis)
            };
        }
        Some(out)
    } else {
        None
    };
    let mut scores = [0.0; 3];
    let mut found = [0; 3];
    for (i, e) in d.evidence.iter().take(3).enumerate() {
        scores[i] = e.exclusive_score;
        found[i] = e.found;
    }
    Ok(FileResult {
        file: name,
        record: label.record,
        truth: t,
        diameter_in: label.diameter_in,
        or_clock: match label.fault {
            mat::CwruFault::OuterRace { clock } => Some(clock),
            _ => None,
        },
        load_hp: label.load_hp,
        part,
        channel: channel.into(),
        rpm,
        rpm_refined: refined.map(|_| rpm_used),
        predicted: d.family,
        confidence: d.confidence,
        candidate: d.candidate,
        margin_db: d.margin_db,
        score: d.score,
        family_scores: scores,
        family_found: found,
        band_hz: a.kurtogram.band_hz,
        band_kurtosis: a.kurtogram.kurtosis,
        correct: d.family == t,
        variants,
        error: None,
    })
}

/// Run the benchmark on the CWRU files of `dir` (the data folder or its `cwru/`): every
/// 12 kHz drive-end fault record and the normal baseline(s). Files whose names are not CWRU
/// names, and other rates or ends, are skipped. A file that fails to read or analyse counts as
/// diagnosed `None` with its error recorded. Error if the folder cannot be listed or holds no
/// such file.
pub fn run_benchmark(
    dir: &Path,
    method: &Method,
    variants: bool,
) -> Result<BenchmarkReport, String> {
    run_benchmark_resampled(dir, method, variants, None)
}

/// [`run_benchmark`] with every record resampled band-limited to `resample` Hz (after its
/// decimation to 12 kHz; [`resample_fft`]) before the analysis, when given: the
/// sample-rate invariance experiment of issue 12.
pub fn run_benchmark_resampled(
    dir: &Path,
    method: &Method,
    variants: bool,
    resample: Option<f64>,
) -> Result<BenchmarkReport, String> {
    let cwru = cwru_dir(dir);
    let entries = std::fs::read_dir(&cwru)
        .map_err(|e| format!("{}: cannot list the folder: {e}", cwru.display()))?;
    let mut files: Vec<(PathBuf, CwruLabel)> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("mat")))
        .filter_map(|p| {
            let label = parse_cwru_name(&crate::analyze::short_name(&p))?;
            let keep = matches!(label.fault, mat::CwruFault::Normal)
                || (label.fs_hz == ANALYSIS_FS
                    && matches!(label.fault_end.as_deref(), Some("DE") | Some("FE")));
            keep.then_some((p, label))
        })
        .collect();
    if files.is_empty() {
        return Err(format!(
            "{}: no CWRU 12 kHz drive-end, fan-end or normal .mat files found",
            cwru.display()
        ));
    }
    let key = |l: &CwruLabel| {
        (
            u8::from(part_of(l) == Part::FanEnd),
            class_index(truth(l)),
            (l.diameter_in.unwrap_or(0.0) * 1000.0).round() as u32,
            match l.fault {
                mat::CwruFault::OuterRace { clock } => clock,
                _ => 0,
            },
            l.load_hp,
        )
    };
    files.sort_by_key(|(_, l)| key(l));
    let rows: Vec<FileResult> = files
        .iter()
        .map(|(p, label)| {
            analyse_file(p, label, method, variants, resample).unwrap_or_else(|error| FileResult {
                file: crate::analyze::short_name(p),
                record: label.record,
                truth: truth(label),
                diameter_in: label.diameter_in,
                or_clock: None,
                load_hp: label.load_hp,
                part: part_of(label),
                channel: String::new(),
                rpm: 0.0,
                rpm_refined: None,
                predicted: FaultFamily::None,
                confidence: 0.0,
                candidate: FaultFamily::None,
                margin_db: 0.0,
                score: 0.0,
                family_scores: [0.0; 3],
                family_found: [0; 3],
                band_hz: (0.0, 0.0),
                band_kurtosis: 0.0,
                correct: false,
                variants: None,
                error: Some(error),
            })
        })
        .collect();
    let mut confusion = [[0usize; 4]; 4];
    for r in &rows {
        confusion[class_index(r.truth)][class_index(r.predicted)] += 1;
    }
    let race = |r: &&FileResult| matches!(r.truth, FaultFamily::InnerRace | FaultFamily::OuterRace);
    let ball = |r: &&FileResult| r.truth == FaultFamily::Ball;
    let de = |r: &&FileResult| matches!(r.part, Part::Development | Part::Evaluation);
    let in_part = |p: Part| move |r: &&FileResult| r.part == p;
    let dev = in_part(Part::Development);
    let eval = in_part(Part::Evaluation);
    let fe = in_part(Part::FanEnd);
    let accuracy = vec![
        Accuracy::of("development IR+OR", rows.iter().filter(dev).filter(race)),
        Accuracy::of("evaluation IR+OR", rows.iter().filter(eval).filter(race)),
        Accuracy::of("drive end IR+OR", rows.iter().filter(de).filter(race)),
        Accuracy::of("development ball", rows.iter().filter(dev).filter(ball)),
        Accuracy::of("evaluation ball", rows.iter().filter(eval).filter(ball)),
        Accuracy::of("fan end IR+OR", rows.iter().filter(fe).filter(race)),
        Accuracy::of("fan end ball", rows.iter().filter(fe).filter(ball)),
        Accuracy::of("normal", rows.iter().filter(in_part(Part::Baseline))),
        Accuracy::of("all", rows.iter()),
    ];
    let calibration_fitted = fit_development(&rows);
    Ok(BenchmarkReport {
        data_dir: cwru,
        method: *method,
        files: rows,
        confusion,
        accuracy,
        calibration: CALIBRATION,
        calibration_fitted,
    })
}

/// Short label of a family for tables.
fn short(f: FaultFamily) -> &'static str {
    match f {
        FaultFamily::InnerRace => "IR",
        FaultFamily::OuterRace => "OR",
        FaultFamily::Ball => "ball",
        FaultFamily::None => "none",
    }
}

/// Case label of a file (`IR 0.007`, `OR 0.021 @3`, `normal`).
fn case(r: &FileResult) -> String {
    match (r.truth, r.diameter_in) {
        (FaultFamily::None, _) => "normal".into(),
        (t, Some(d)) => match r.or_clock {
            Some(c) => format!("{} {d:.3} @{c}", short(t)),
            None => format!("{} {d:.3}", short(t)),
        },
        (t, None) => short(t).into(),
    }
}

/// Outcome letters of a row's variants (`Y P N`), or `-`.
fn variant_letters(f: &FileResult) -> [&'static str; 3] {
    f.variants.map_or(["-"; 3], |v| {
        v.map(|o| match o {
            Outcome::Y => "Y",
            Outcome::P => "P",
            Outcome::N => "N",
        })
    })
}

/// Name of a part for tables.
fn part_name(p: Part) -> &'static str {
    match p {
        Part::Development => "dev",
        Part::Evaluation => "eval",
        Part::FanEnd => "FE",
        Part::Baseline => "base",
    }
}

/// The report as Markdown (the content of `docs/cwru-benchmark.md`).
pub fn to_markdown(r: &BenchmarkReport) -> String {
    let mut s = String::new();
    s.push_str("# CWRU benchmark of `wearsim analyze`\n\n");
    s.push_str(
        "Generated by `wearsim cwru-benchmark --markdown docs/cwru-benchmark.md` (do not edit by \
         hand; method, split and the \"before\" figures are in `docs/cwru-detector.md`). Every \
         12 kHz drive-end and fan-end record of the CWRU Bearing Data Center in the data folder \
         and the normal baseline (48 kHz, decimated to 12 kHz) go through the same chain with \
         one fixed parameter set. Inputs per file: its stored speed (`XnnnRPM`) and the \
         `cwru-6205-de` (drive end, DE channel) or `cwru-6203-fe` (fan end, FE channel) \
         geometry; the label in the file name is used only for scoring.\n\n\
         **Split** (`cwru_benchmark::part_of`, decided before tuning): drive end 0-1 hp = \
         development (chose every threshold and the confidence calibration); drive end 2-3 hp = \
         evaluation (judges only); fan end = held-out other sensor position and bearing; \
         normal baseline = healthy check.\n\n",
    );
    s.push_str(&format!(
        "Confidence calibration in force: slope {:.4} /dB, centre {:.3} dB; refitted now on the \
         development records: {}.\n\n",
        r.calibration.slope,
        r.calibration.centre,
        r.calibration_fitted.map_or("no fit".into(), |c| format!(
            "slope {:.4} /dB, centre {:.3} dB",
            c.slope, c.centre
        ))
    ));
    s.push_str(
        "## Accuracy\n\n`wrong family`: records called as another fault family (worse than no \
         call).\n\n| group | correct | files | accuracy | wrong family |\n|---|---:|---:|---:|---:|\n",
    );
    for a in &r.accuracy {
        s.push_str(&format!(
            "| {} | {} | {} | {:.1} % | {} |\n",
            a.group,
            a.correct,
            a.total,
            100.0 * a.fraction,
            a.wrong_family
        ));
    }
    s.push_str(
        "\n## Confusion matrix (all records)\n\nRows: true class; columns: diagnosed family.\n\n\
         | true \\ diagnosed | IR | OR | ball | none |\n|---|---:|---:|---:|---:|\n",
    );
    for (t, row) in r.confusion.iter().enumerate() {
        s.push_str(&format!(
            "| {} | {} | {} | {} | {} |\n",
            short(CLASSES[t]),
            row[0],
            row[1],
            row[2],
            row[3]
        ));
    }
    s.push_str(
        "\n## Per file (Smith & Randall 2015 style)\n\n`raw` / `CPW` / `SK`: outcome of the raw \
         envelope (whole band above the fault zone, no pre-whitening), the cepstrally \
         pre-whitened envelope (same band) and the SK-band envelope (kurtogram band, \
         pre-whitened: the method). Y = the true family is called (confidence >= 0.5); P = the \
         true family leads the evidence but is not called; N = another family or nothing. \
         `margin`: the leading family's exclusive score minus the best other's, dB per \
         searched harmonic; `conf`: calibrated confidence of the call; `rpm`: the stored \
         speed, `stored->used` where the record's own 1x line replaced it (as `analyze` \
         does).\n\n\
         | file | part | case | hp | rpm | band Hz | diagnosed | conf | leading | margin | raw | CPW | SK | ok |\n\
         |---|---|---|---:|---:|---|---|---:|---|---:|---|---|---|---|\n",
    );
    for f in &r.files {
        let v = variant_letters(f);
        s.push_str(&format!(
            "| {} | {} | {} | {} | {} | {:.0}-{:.0} | {} | {:.2} | {} | {:.1} | {} | {} | {} | {} |\n",
            f.file,
            part_name(f.part),
            case(f),
            f.load_hp,
            match f.rpm_refined {
                Some(u) => format!("{:.0}->{u:.0}", f.rpm),
                None => format!("{:.0}", f.rpm),
            },
            f.band_hz.0,
            f.band_hz.1,
            family_name(f.predicted),
            f.confidence,
            family_name(f.candidate),
            f.margin_db,
            v[0],
            v[1],
            v[2],
            if f.correct { "yes" } else { "**no**" }
        ));
        if let Some(e) = &f.error {
            s.push_str(&format!("|  | error: {e} | | | | | | | | | | | | |\n"));
        }
    }
    s
}

/// Print the report for a person.
pub fn print_report(r: &BenchmarkReport) {
    println!("CWRU benchmark on {}", r.data_dir.display());
    println!(
        "{:<34} {:<4} {:<12} {:>2} {:>11} {:<10} {:>5} {:<10} {:>6}  raw CPW SK  ok",
        "file", "part", "case", "hp", "band Hz", "diagnosed", "conf", "leading", "margin"
    );
    for f in &r.files {
        let v = variant_letters(f);
        println!(
            "{:<34} {:<4} {:<12} {:>2} {:>5.0}-{:<5.0} {:<10} {:>5.2} {:<10} {:>6.1}  {}   {}   {}   {}",
            f.file,
            part_name(f.part),
            case(f),
            f.load_hp,
            f.band_hz.0,
            f.band_hz.1,
            family_name(f.predicted),
            f.confidence,
            family_name(f.candidate),
            f.margin_db,
            v[0],
            v[1],
            v[2],
            if f.correct { "yes" } else { "NO" }
        );
        if let Some(e) = &f.error {
            println!("    error: {e}");
        }
    }
    println!("\nconfusion matrix (rows true, columns diagnosed):");
    println!(
        "{:<6} {:>5} {:>5} {:>5} {:>5}",
        "", "IR", "OR", "ball", "none"
    );
    for (t, row) in r.confusion.iter().enumerate() {
        println!(
            "{:<6} {:>5} {:>5} {:>5} {:>5}",
            short(CLASSES[t]),
            row[0],
            row[1],
            row[2],
            row[3]
        );
    }
    println!();
    for a in &r.accuracy {
        println!(
            "{:<18} {:>3}/{:<3} {:>5.1} %  wrong family {}",
            a.group,
            a.correct,
            a.total,
            100.0 * a.fraction,
            a.wrong_family
        );
    }
    println!(
        "calibration in force: slope {:.4} /dB centre {:.3} dB; fitted on development: {:?}",
        r.calibration.slope, r.calibration.centre, r.calibration_fitted
    );
}
