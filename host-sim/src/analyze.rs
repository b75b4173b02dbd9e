//! `wearsim analyze`: statistics, kurtogram-selected demodulation band, envelope-spectrum
//! fault-family decision and El-Thalji frequency-zone levels of one measured (or simulated)
//! record, with optional plots.
//!
//! The chain (Randall & Antoni 2011, "Rolling element bearing diagnostics — a tutorial",
//! MSSP 25; Borghesani et al. 2013, "Application of cepstrum pre-whitening for the diagnosis
//! of bearing faults under variable speed conditions", MSSP 36):
//!
//! 1. time-domain statistics of the raw record;
//! 2. fast kurtogram (Antoni 2007) of the raw record, restricted to bands that lie above the
//!    fault-frequency zone and are wide enough to hold the fault harmonics that are searched,
//!    to choose the demodulation band (where the impulses dominate);
//! 3. cepstral pre-whitening (CPW): the record's spectrum is divided by its own magnitude,
//!    which removes the discrete machine lines (and the interference harmonics of the CWRU
//!    rig) inside the band while keeping the impulse timing;
//! 4. envelope spectrum of the whitened record in the chosen band and [`detect_fault`]
//!    (common-fundamental harmonic fit within the slip tolerance; lines claimed by two
//!    families count for neither).
//!
//! One parameter set ([`Method::default`]) serves every record: nothing depends on a label.

use crate::analysis::{
    self, detect_fault, welch_psd, zone_levels, DetectParams, FaultDiagnosis, FaultFamily,
    FaultFrequencies, Kurtogram, Spectrum, Stats, WelchParams, Window, ZoneBands, ZoneLevels,
};
use crate::io::{self, ReadOptions, Record};
use crate::kinematics;
use clap::Args;
use realfft::num_complex::Complex;
use serde::Serialize;
use std::path::{Path, PathBuf};
use wearsim_core::model::ModelConfig;

/// `wearsim analyze` arguments.
#[derive(Debug, Clone, Args, Default)]
pub struct AnalyzeArgs {
    /// Measurement file: CWRU .mat, CSV/TXT, WAV, NPY, IMS snapshot, or wearsim's own
    /// `simulate` output (the .csv or .wav beside its JSON sidecar).
    pub file: PathBuf,
    /// Channel: CWRU `DE`/`FE`/`BA`, CSV header name or column index, WAV/NPY column index.
    #[arg(long)]
    pub channel: Option<String>,
    /// Shaft speed (rpm), 0 < rpm < 1e6; overrides the file / sidecar value.
    #[arg(long)]
    pub rpm: Option<f64>,
    /// Sample rate (Hz), 1..=1e7; overrides the file / sidecar value.
    #[arg(long)]
    pub fs: Option<f64>,
    /// Bearing preset giving the geometry (see `wearsim presets`) or a catalogue bearing
    /// (`mfpt-nice`, `paderborn-6203`, `xjtu-ldk-uer204`); overrides the record's.
    #[arg(long)]
    pub bearing: Option<String>,
    /// Any bearing: `elements=N,ball=MM,pitch=MM,angle=DEG` (diameters in mm, contact angle in
    /// degrees, 0 <= angle < 90, pitch > ball, 3..=200 elements); overrides the record's.
    #[arg(
        long = "bearing-geometry",
        value_name = "elements=N,ball=MM,pitch=MM,angle=DEG"
    )]
    pub bearing_geometry: Option<String>,
    /// Scenario TOML (the `simulate --config` format) describing the bearing: its preset and
    /// `[bearing]` give the geometry, its `[structure]` the resonance zone, and its `[speed]`
    /// the shaft speed when neither `--rpm` nor the file gives one. Overrides the record's
    /// bearing; not with `--bearing` or `--bearing-geometry`.
    #[arg(long, value_name = "SCENARIO.toml", conflicts_with_all = ["bearing", "bearing_geometry"])]
    pub config: Option<PathBuf>,
    /// Print everything as one JSON object on standard output.
    #[arg(long)]
    pub json: bool,
    /// Write PNG and SVG plots (spectrum, envelope spectrum, kurtogram) into this directory.
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// More files or directories: with several inputs, a directory, `--format` or `--out`,
    /// every readable record is analysed and one table is written (see `crate::cmd::analyze_batch`).
    #[arg(value_name = "MORE")]
    pub more: Vec<PathBuf>,
    /// Table format of a batch run: `csv`, `json` or `md` (default: from `--out`'s
    /// extension, else `md`).
    #[arg(long)]
    pub format: Option<String>,
    /// Write the batch table to this file (atomically) instead of standard output.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

impl AnalyzeArgs {
    /// Arguments for one file with every option at its default (no overrides, text output):
    /// the starting point for library callers such as the Python package, so a new option
    /// does not break them.
    pub fn for_file(file: PathBuf) -> Self {
        Self {
            file,
            channel: None,
            rpm: None,
            fs: None,
            bearing: None,
            bearing_geometry: None,
            config: None,
            json: false,
            plot: None,
            more: Vec::new(),
            format: None,
            out: None,
        }
    }
}

/// The fixed analysis method (one parameter set for every record).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Method {
    /// Cepstral pre-whitening of the record before the envelope (default true; the
    /// kurtogram always sees the raw record).
    pub prewhiten: bool,
    /// Demodulate in the band chosen by the kurtogram (default true); false: in the whole
    /// admissible band above the fault zone (`top`..fs/2), as a plain envelope analysis.
    pub kurtogram_band: bool,
    /// Bounds the candidate-band grid (default 6): at most `2 × max_level` band widths, the
    /// narrowest kept. The grid is fixed in Hz
    /// ([`analysis::kurtogram::hz_grid_kurtogram`]: widths 1000 or 1500 Hz × 2^k, cells at
    /// multiples of the width), its widths at least `min_band_factor × top` Hz and wide
    /// enough for 32 envelope samples, so the same record sees the same candidate bands at
    /// every sample rate.
    pub max_level: usize,
    /// Narrowest admissible demodulation band, as a multiple of the highest fault harmonic
    /// searched (`top = harmonics × max(BPFI, 2×BSF)`), so that the envelope can hold every
    /// harmonic the detector looks for (default 1.2). Admissible bands also start at or
    /// above `top` (the carrier lies above the fault-frequency zone it modulates), unless the
    /// record's bandwidth leaves no room for that.
    pub min_band_factor: f64,
    /// Envelope of the demodulated band: `false` (default) the envelope `|analytic signal|`,
    /// `true` the squared envelope (Randall & Antoni 2011, section 3.2).
    pub squared_envelope: bool,
    /// How the demodulation band is chosen among the admissible kurtogram cells (default
    /// [`BandRule::Kurtosis`]).
    pub band_rule: BandRule,
    /// Detector thresholds ([`DetectParams::default`]).
    pub detect: DetectParams,
}

/// Rule choosing the demodulation band among the admissible cells of the fast kurtogram
/// (the same cells, in Hz, at every sample rate; see [`Method::min_band_factor`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum BandRule {
    /// The cell of largest spectral kurtosis (Antoni 2007, fast kurtogram).
    Kurtosis,
    /// The cell whose envelope spectrum gives the leading fault family the largest evidence
    /// margin (the target-frequency band selection of the envelope-spectrum "gram" methods:
    /// Barszcz & Jabłoński 2011, protrugram, MSSP 25; Smith, Borghesani, Ni, Wang & Peng 2019,
    /// "Optimal demodulation-band selection for envelope-based diagnostics", MSSP 134);
    /// the kurtosis cell when no cell has a leading family.
    Evidence,
    /// The cell whose envelope spectrum is the most peaky over the searched fault-frequency
    /// range `(0, top × (1 + slip)]` Hz: the largest kurtosis of the envelope-spectrum
    /// amplitudes there (the protrugram, Barszcz & Jabłoński 2011, MSSP 25), which favours
    /// bands with discrete envelope lines without looking at which family they belong to.
    Protrugram,
}

/// Pearson kurtosis (Gaussian 3) of the envelope-spectrum amplitudes of `env` in
/// `(0, hi]` Hz; 0 with fewer than 4 values or a constant spectrum.
fn spectrum_kurtosis(env: &analysis::Spectrum, hi: f64) -> f64 {
    if env.df <= 0.0 || !hi.is_finite() {
        return 0.0;
    }
    let k1 = ((hi / env.df).floor() as usize).min(env.values.len().saturating_sub(1));
    let v = env.values.get(1..=k1).unwrap_or(&[]);
    if v.len() < 4 {
        return 0.0;
    }
    let (m, sd) = analysis::stats::mean_std(v);
    if sd.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return 0.0;
    }
    let k = v.iter().map(|x| ((x - m) / sd).powi(4)).sum::<f64>() / v.len() as f64;
    if k.is_finite() {
        k
    } else {
        0.0
    }
}

impl Default for Method {
    fn default() -> Self {
        Method {
            prewhiten: true,
            kurtogram_band: true,
            max_level: 6,
            min_band_factor: 1.2,
            squared_envelope: false,
            band_rule: BandRule::Kurtosis,
            detect: DetectParams::default(),
        }
    }
}

/// Summary of the fast kurtogram.
#[derive(Debug, Clone, Serialize)]
pub struct KurtogramSummary {
    /// Depth of the grid: `ceil(log2(fs/2 / narrowest cell width))` (a label; the cells
    /// are fixed in Hz, see [`analysis::kurtogram::hz_grid_kurtogram`]).
    pub max_level: usize,
    /// Narrowest admissible band width, Hz (see [`Method::min_band_factor`]).
    pub min_band_hz: f64,
    /// Upper limit of the candidate bands, Hz: the lowest of the record's content edge
    /// (`analysis::kurtogram::content_edge_hz`), its Nyquist frequency and
    /// `analysis::kurtogram::MAX_BAND_HZ` (20 kHz).
    pub span_hz: f64,
    /// Chosen demodulation band `(lo, hi)`, Hz: the admissible band of largest kurtosis.
    pub band_hz: (f64, f64),
    /// Kurtosis of the complex envelope in that band (0 for Gaussian noise).
    pub kurtosis: f64,
    /// Level of the chosen band, `log2(fs/2 / its width)` (a label, as `max_level`).
    pub level: f64,
    /// Band of largest kurtosis over the whole kurtogram (admissible or not), Hz.
    pub unrestricted_band_hz: (f64, f64),
    /// Its kurtosis.
    pub unrestricted_kurtosis: f64,
}

/// Zone bands and levels (El-Thalji 2016 frequency zones), from a Welch PSD of the raw record.
#[derive(Debug, Clone, Serialize)]
pub struct Zones {
    /// Band edges, Hz.
    pub bands: ZoneBands,
    /// RMS levels, signal units.
    pub levels: ZoneLevels,
}

/// Everything `wearsim analyze` reports (the `--json` object).
#[derive(Debug, Clone, Serialize)]
pub struct Analysis {
    /// File analysed.
    pub file: PathBuf,
    /// Channel name as the file calls it.
    pub channel: String,
    /// Unit of the samples (`g`, `m/s^2`, ...).
    pub unit: String,
    /// Sample rate, Hz.
    pub fs: f64,
    /// Where the sample rate came from: `argument`, `file:PATH` (stored in the file, e.g.
    /// `file:bearing.sr`), `layout:NAME` (the data set's documented rate), `file name`,
    /// `sidecar`, `header`.
    pub fs_source: String,
    /// What the reader found: `layout` (`cwru`, `mfpt`, `paderborn`, `ims`, `femto`,
    /// `xjtu-sy`, `generic`), `variable` (path inside a MAT file), `rpm_source` (as `fs_source`),
    /// `load` and `load_source` when the file stores a load; absent keys are unknown.
    pub input: serde_json::Value,
    /// Number of samples.
    pub samples: usize,
    /// Duration, s.
    pub duration_s: f64,
    /// Shaft speed used, rpm.
    pub rpm: f64,
    /// Where the speed came from: `argument`, `file` or `config` (the `--config` scenario's speed).
    pub rpm_source: String,
    /// Bearing preset used for the geometry (`custom`: the geometry of a wearsim
    /// sidecar's structured model that is no preset's).
    pub bearing: String,
    /// Where the bearing came from: `argument`, `file`, `sidecar` or `config` (`--config`).
    pub bearing_source: String,
    /// Characteristic frequencies at `rpm`, Hz.
    pub kinematics: FaultFrequencies,
    /// The method's parameters.
    pub method: Method,
    /// RMS, peak, crest factor, kurtosis, skewness of the raw record (signal units).
    pub stats: Stats,
    /// Demodulation band chosen by the kurtogram.
    pub kurtogram: KurtogramSummary,
    /// Fault-family decision with the evidence of every family.
    pub diagnosis: FaultDiagnosis,
    /// Zone levels, or `None` when a zone falls outside (0, fs/2) (see `zones_note`).
    pub zones: Option<Zones>,
    /// Why the zones are missing, if they are.
    pub zones_note: Option<String>,
}

/// The spectra behind an [`Analysis`], for plots.
#[derive(Debug, Clone)]
pub struct Spectra {
    /// Amplitude spectrum of the raw record (Hann window, whole record), signal units.
    pub spectrum: Spectrum,
    /// Envelope spectrum in the chosen band (of the pre-whitened record if
    /// [`Method::prewhiten`]); signal units, or unit-less when pre-whitened.
    pub envelope: Spectrum,
    /// The fast kurtogram of the raw record.
    pub kurtogram: Kurtogram,
}

/// Result of [`analyze_signal`]: the figures that depend only on the samples.
#[derive(Debug, Clone)]
pub struct SignalAnalysis {
    /// Statistics of the raw signal.
    pub stats: Stats,
    /// Demodulation band.
    pub kurtogram: KurtogramSummary,
    /// Fault decision.
    pub diagnosis: FaultDiagnosis,
    /// Zones, or the reason they are missing.
    pub zones: Result<Zones, String>,
    /// Spectra for plots.
    pub spectra: Spectra,
}

/// Cepstral pre-whitening (Sawalhi & Randall 2011; Borghesani et al. 2013): the inverse FFT
/// of `X(f) / |X(f)|` of the mean-removed record, i.e. the record with its real cepstrum set
/// to zero except at quefrency 0. The mean and bins of zero magnitude become zero. The output
/// has the input's length and a flat (unit-less) magnitude spectrum: every bin has magnitude
/// 1 before the inverse FFT's 1/n scaling. Fewer than 2 samples give zeros.
pub fn prewhiten(x: &[f64]) -> Vec<f64> {
    let n = x.len();
    if n < 2 {
        return vec![0.0; n];
    }
    prewhiten_spectrum(analysis::fft::rfft(x, analysis::stats::mean(x)), n)
}

/// [`prewhiten`] from `spec`, the one-sided spectrum (`n/2 + 1` bins) of the mean-removed
/// record of `n >= 2` samples (the spectrum the fast kurtogram cuts its bands from; plans
/// cached per thread).
fn prewhiten_spectrum(mut spec: Vec<Complex<f64>>, n: usize) -> Vec<f64> {
    let inv = analysis::fft::plan_c2r(n);
    if spec.len() != n / 2 + 1 {
        return vec![0.0; n];
    }
    for (k, c) in spec.iter_mut().enumerate() {
        let m = c.norm();
        // DC and (even n) Nyquist must stay real for the inverse real FFT.
        if k == 0 || m == 0.0 || !m.is_finite() {
            *c = Complex::new(0.0, 0.0);
        } else {
            *c /= m;
        }
    }
    if n.is_multiple_of(2) {
        if let Some(last) = spec.last_mut() {
            *last = Complex::new(last.re, 0.0);
        }
    }
    let mut out = inv.make_output_vec();
    if inv.process(&mut spec, &mut out).is_err() {
        return vec![0.0; n];
    }
    let scale = 1.0 / n as f64;
    out.iter_mut().for_each(|v| *v *= scale);
    out
}

/// Band edges `(lo, hi)` Hz of cell `i` of kurtogram row `r`.
pub fn kurtogram_band(kg: &Kurtogram, r: usize, i: usize) -> (f64, f64) {
    let w = kg.row_width_hz.get(r).copied().unwrap_or(kg.fs / 2.0);
    (i as f64 * w, (i + 1) as f64 * w)
}

/// Analyse samples `x` at `fs` Hz of a bearing with frequencies `kin` using `method`.
/// Errors (signal too short, constant, non-finite, bad fs) come from [`analysis`].
pub fn analyze_signal(
    raw: &[f64],
    fs: f64,
    kin: &FaultFrequencies,
    method: &Method,
) -> Result<SignalAnalysis, analysis::AnalysisError> {
    let stats = analysis::stats(raw)?;
    analysis::error::check_magnitude(raw)?;
    // DC and level removed: every decision below depends on the record's shape only, not
    // on its units, gain or offset.
    let normalised: Vec<f64> = if stats.std > 0.0 {
        raw.iter().map(|v| (v - stats.mean) / stats.std).collect()
    } else {
        raw.to_vec()
    };
    let x = normalised.as_slice();
    let top = method.detect.harmonics.max(1) as f64 * kin.bpfi.max(2.0 * kin.bsf);
    analysis::error::check_signal(x, 128, "kurtogram")?;
    analysis::kurtogram::check_not_constant(x)?;
    let spec = analysis::fft::rfft(x, analysis::stats::mean(x));
    // Candidate bands on a grid fixed in Hz (issue 12: cells in fractions of fs/2 moved with
    // the sample rate and so changed the call of a record resampled with no new content),
    // up to where the record holds content, its Nyquist frequency and `MAX_BAND_HZ`.
    let span = analysis::kurtogram::content_edge_hz(&spec, x.len(), fs)
        .min(fs / 2.0)
        .min(analysis::kurtogram::MAX_BAND_HZ);
    let min_band_hz = (method.min_band_factor * top).min(span);
    // The narrowest cells need 32 envelope samples (32 / duration Hz wide).
    let min_width = min_band_hz.max(32.0 * fs / x.len() as f64);
    let kg = analysis::kurtogram::hz_grid_kurtogram(
        &spec,
        x.len(),
        fs,
        min_width,
        span,
        2 * method.max_level.clamp(1, 16),
    )?;
    let level = kg.levels;
    let lowest = top.min(span - min_band_hz).max(0.0);
    let mut admissible: Vec<(f64, usize, usize)> = Vec::new();
    let mut best: Option<(f64, usize, usize)> = None;
    for (r, row) in kg.grid.iter().enumerate() {
        let width = kg.row_width_hz[r];
        if width + 1e-9 < min_band_hz {
            continue;
        }
        for (i, &k) in row.iter().enumerate() {
            // The carrier band must lie above the fault harmonics it is to reveal.
            if (i as f64) * width + 1e-9 < lowest {
                continue;
            }
            admissible.push((k, r, i));
            if best.is_none_or(|b| k > b.0) {
                best = Some((k, r, i));
            }
        }
    }
    // No grid cell fits above the fault zone: the band (lowest, span), as without the kurtogram.
    let fallback = best.is_none();
    let fallback_kurtosis = if fallback {
        analysis::kurtogram::band_kurtosis(&spec, x.len(), fs, (lowest, span))
    } else {
        0.0
    };
    // Cepstral pre-whitening from the same spectrum of the mean-removed record (the
    // record has been checked: finite, not constant, long enough).
    let white;
    let y: &[f64] = if method.prewhiten {
        white = prewhiten_spectrum(spec, x.len());
        &white
    } else {
        x
    };
    let (mut kurtosis, mut r, mut i) = best.unwrap_or((0.0, 0, 0));
    // One forward FFT of the record to be demodulated, shared by every band tried.
    let yspec = analysis::fft::rfft(y, 0.0);
    let env_of = |band: (f64, f64)| {
        analysis::envelope::envelope_spectrum_of_spectrum(
            &yspec,
            y.len(),
            fs,
            band,
            method.squared_envelope,
        )
    };
    if method.kurtogram_band && method.band_rule == BandRule::Evidence {
        // The cell whose envelope spectrum gives the leading family the largest margin.
        let mut lead: Option<(f64, f64, usize, usize)> = None;
        for &(k, rr, ii) in &admissible {
            let d = detect_fault(&env_of(kurtogram_band(&kg, rr, ii))?, kin, &method.detect);
            if d.candidate != FaultFamily::None
                && lead.is_none_or(|l| d.margin_db > l.0 || (d.margin_db == l.0 && k > l.1))
            {
                lead = Some((d.margin_db, k, rr, ii));
            }
        }
        if let Some((_, k, rr, ii)) = lead {
            (kurtosis, r, i) = (k, rr, ii);
        }
    }
    if method.kurtogram_band && method.band_rule == BandRule::Protrugram {
        let hi = top * (1.0 + method.detect.slip);
        let mut peaky: Option<(f64, f64, usize, usize)> = None;
        for &(k, rr, ii) in &admissible {
            let p = spectrum_kurtosis(&env_of(kurtogram_band(&kg, rr, ii))?, hi);
            if peaky.is_none_or(|l| p > l.0 || (p == l.0 && k > l.1)) {
                peaky = Some((p, k, rr, ii));
            }
        }
        if let Some((_, k, rr, ii)) = peaky {
            (kurtosis, r, i) = (k, rr, ii);
        }
    }
    let band = if method.kurtogram_band && !fallback {
        kurtogram_band(&kg, r, i)
    } else {
        (lowest, span)
    };
    if fallback {
        kurtosis = fallback_kurtosis;
    }
    let summary = KurtogramSummary {
        max_level: level,
        min_band_hz,
        band_hz: band,
        kurtosis,
        level: if fallback {
            (fs / 2.0 / (band.1 - band.0).max(1e-9)).log2()
        } else {
            kg.level_values.get(r).copied().unwrap_or(0.0)
        },
        span_hz: span,
        unrestricted_band_hz: kg.best_band,
        unrestricted_kurtosis: kg.best_kurtosis,
    };
    let env = env_of(band)?;
    let diagnosis = detect_fault(&env, kin, &method.detect);
    let spectrum = analysis::amplitude_spectrum(raw, fs, Window::Hann)?;
    let zones = zones(raw, fs, kin);
    Ok(SignalAnalysis {
        stats,
        kurtogram: summary,
        diagnosis,
        zones,
        spectra: Spectra {
            spectrum,
            envelope: env,
            kurtogram: kg,
        },
    })
}

/// Zone levels from a Welch PSD (segments of about 1 Hz resolution, at most the record).
fn zones(x: &[f64], fs: f64, kin: &FaultFrequencies) -> Result<Zones, String> {
    let bands = ZoneBands::new(kin, fs).map_err(|e| format!("frequency zones undefined: {e}"))?;
    let mut nperseg = 4096usize;
    while nperseg > x.len() && nperseg > 64 {
        nperseg /= 2;
    }
    let psd = welch_psd(
        x,
        fs,
        &WelchParams {
            nperseg,
            ..WelchParams::default()
        },
    )
    .map_err(|e| format!("zone PSD: {e}"))?;
    Ok(Zones {
        levels: zone_levels(&psd, &bands),
        bands,
    })
}

/// Read `args.file` and analyse it; errors name the file (exit 2 for bad input).
pub fn analyze(args: &AnalyzeArgs) -> Result<(Analysis, Spectra), AnalyzeError> {
    let opts = ReadOptions {
        channel: args.channel.clone(),
        fs: args.fs,
        rpm: args.rpm,
    };
    let mut rec = io::read_any(&args.file, &opts).map_err(AnalyzeError::input)?;
    let scenario = match &args.config {
        Some(path) => Some(scenario_bearing(path).map_err(AnalyzeError::input)?),
        None => None,
    };
    // The speed: `--rpm`, else the file's, else the scenario's.
    let rpm_from_config = scenario.is_some() && rec.rpm.is_none();
    if let (true, Some((m, _))) = (rpm_from_config, &scenario) {
        rec.rpm = Some(60.0 * m.speed.shaft_hz(0.0));
    }
    let (mut a, spectra) = analyze_chosen(
        &rec,
        BearingChoice {
            preset: args.bearing.as_deref(),
            geometry: args.bearing_geometry.as_deref(),
            scenario: scenario.as_ref().map(|(m, l)| (m, l.as_str())),
        },
        args.rpm.is_some(),
        &Method::default(),
    )?;
    if rpm_from_config {
        a.rpm_source = "config".into();
    }
    Ok((a, spectra))
}

/// The resolved model configuration of scenario file `path` (for `--config`) and the
/// bearing's label: its preset's name when the geometry is the preset's, else `custom`.
fn scenario_bearing(path: &Path) -> Result<(wearsim_core::model::ModelConfig, String), String> {
    let file = crate::config::ScenarioFile::load(path).map_err(|e| format!("--config: {e}"))?;
    let (model, _) = file.resolve().map_err(|e| format!("--config: {e}"))?;
    let label = crate::io::sidecar::bearing_label(file.preset.as_deref(), &model);
    Ok((model, label))
}

/// Analyse a record already read. `bearing` overrides the record's bearing preset;
/// `rpm_from_argument` only labels where the speed came from.
pub fn analyze_record(
    rec: &Record,
    bearing: Option<&str>,
    rpm_from_argument: bool,
    method: &Method,
) -> Result<(Analysis, Spectra), AnalyzeError> {
    analyze_record_with(rec, bearing, None, rpm_from_argument, method)
}

/// [`analyze_record`] with an optional `--bearing-geometry` (see [`crate::geometry`]).
pub fn analyze_record_with(
    rec: &Record,
    bearing: Option<&str>,
    geometry: Option<&str>,
    rpm_from_argument: bool,
    method: &Method,
) -> Result<(Analysis, Spectra), AnalyzeError> {
    let choice = BearingChoice {
        preset: bearing,
        geometry,
        scenario: None,
    };
    analyze_chosen(rec, choice, rpm_from_argument, method)
}

/// Where the user said the bearing is described (each overrides the record's own).
#[derive(Debug, Clone, Copy, Default)]
struct BearingChoice<'a> {
    /// `--bearing NAME`: a preset or catalogue bearing.
    preset: Option<&'a str>,
    /// `--bearing-geometry elements=..`.
    geometry: Option<&'a str>,
    /// `--config SCENARIO.toml`: its resolved model and bearing label.
    scenario: Option<(&'a ModelConfig, &'a str)>,
}

fn analyze_chosen(
    rec: &Record,
    choice: BearingChoice,
    rpm_from_argument: bool,
    method: &Method,
) -> Result<(Analysis, Spectra), AnalyzeError> {
    let file = rec.source.display().to_string();
    let bearing = choice.preset;
    let custom = crate::geometry::choose(rec, bearing, choice.geometry)
        .map_err(|e| AnalyzeError::input(format!("{file}: {e}")))?;
    // A scenario file, or a wearsim sidecar's structured model, carries the whole model (a
    // `[bearing]` override included); other files name a preset.
    let file_model = rec
        .meta
        .get("sidecar")
        .and_then(|s| crate::io::sidecar::structured_model(s).ok().flatten());
    let (bearing, bearing_source, file_model) =
        match (&custom, bearing, choice.scenario, file_model, rec.bearing.as_deref()) {
            (_, _, Some((m, label)), _, _) => (label.to_string(), "config", Some(m.clone())),
            (Some(c), _, None, _, _) => (c.0.clone(), c.1, None),
            (None, Some(b), None, _, _) => (b.to_string(), "argument", None),
            (None, None, None, Some(m), label) => {
                (label.unwrap_or("custom").to_string(), "file", Some(m))
            }
            (None, None, None, None, Some(b)) if wearsim_core::presets::by_name(b).is_some() => {
                (b.to_string(), "file", None)
            }
            (None, None, None, None, other) => {
                return Err(AnalyzeError::input(format!(
                "{file}: no bearing geometry{}: pass --bearing-geometry elements=N,ball=MM,pitch=MM,angle=DEG, --bearing NAME (one of {}, {}) or --config SCENARIO.toml",
                other.map_or(String::new(), |b| format!(
                    " (the file names {b:?}, which is not a preset)"
                )),
                wearsim_core::presets::NAMES.join(", "),
                crate::geometry::CATALOGUE.map(|e| e.name).join(", ")
            )))
            }
        };
    let Some(rpm) = rec.rpm else {
        return Err(AnalyzeError::input(format!(
            "{file}: no shaft speed: the file and its sidecar give none; pass --rpm R (0 < R < 1e6)"
        )));
    };
    if rec.samples.len() > crate::io::record::MAX_RECORD_SAMPLES {
        return Err(AnalyzeError::input(crate::io::IoError::TooLarge {
            path: rec.source.clone(),
            what: format!("record of {} samples", rec.samples.len()),
            limit: format!(
                "{} samples (2^23) per analysed record (analysis memory is about 14x the record)",
                crate::io::record::MAX_RECORD_SAMPLES
            ),
        }));
    }
    let kin = match (&custom, &file_model) {
        (Some(c), None) => {
            c.2.model()
                .and_then(|m| kinematics::of_config(&m.model, rpm))
                .map_err(|e| format!("{file}: {e}"))
        }
        (_, Some(m)) => kinematics::of_config(m, rpm)
            .map_err(|e| format!("{file}: {bearing_source} model: {e}")),
        (None, None) => kinematics::of_preset(&bearing, rpm).map_err(|e| format!("{file}: {e}")),
    }
    .map_err(AnalyzeError::input)?;
    crate::resolvable::check_resolvable(
        rec.samples.len(),
        rec.fs,
        kin.shaft_hz,
        [kin.bpfo, kin.bpfi, 2.0 * kin.bsf],
    )
    .map_err(|e| AnalyzeError::input(format!("{file}: channel {}: {e}", rec.channel)))?;
    let a = analyze_signal(&rec.samples, rec.fs, &kin, method)
        .map_err(|e| AnalyzeError::input(format!("{file}: channel {}: {e}", rec.channel)))?;
    let (zones, zones_note) = match a.zones {
        Ok(z) => (Some(z), None),
        Err(e) => (None, Some(e)),
    };
    let analysis = Analysis {
        file: rec.source.clone(),
        channel: rec.channel.clone(),
        unit: rec.unit.clone(),
        fs: rec.fs,
        fs_source: rec
            .meta
            .get("fs_source")
            .and_then(|v| v.as_str())
            .unwrap_or("file")
            .to_string(),
        input: input_provenance(rec),
        samples: rec.samples.len(),
        duration_s: rec.duration_s(),
        rpm,
        rpm_source: if rpm_from_argument {
            "argument"
        } else {
            "file"
        }
        .into(),
        bearing,
        bearing_source: bearing_source.into(),
        kinematics: kin,
        method: *method,
        stats: a.stats,
        kurtogram: a.kurtogram,
        diagnosis: a.diagnosis,
        zones,
        zones_note,
    };
    // The last guard: no NaN/inf (JSON `null`) is ever presented as a result.
    if let Some((path, v)) = analysis::finite::first_non_finite(&analysis) {
        return Err(AnalyzeError::Run(format!(
            "{file}: channel {}: the analysis produced a non-finite figure ({path} = {v}); nothing is reported",
            rec.channel
        )));
    }
    Ok((analysis, a.spectra))
}

/// The reader's findings that `analyze` reports under `input` (see [`Analysis::input`]).
fn input_provenance(rec: &Record) -> serde_json::Value {
    let mut m = serde_json::Map::new();
    for k in ["layout", "variable", "rpm_source", "load", "load_source"] {
        if let Some(v) = rec.meta.get(k).filter(|v| !v.is_null()) {
            m.insert(k.into(), v.clone());
        }
    }
    serde_json::Value::Object(m)
}

/// Human-readable name of a family.
pub fn family_name(f: FaultFamily) -> &'static str {
    match f {
        FaultFamily::InnerRace => "inner race",
        FaultFamily::OuterRace => "outer race",
        FaultFamily::Ball => "ball",
        FaultFamily::None => "none",
    }
}

/// Print the analysis for a person.
pub fn print_analysis(a: &Analysis) {
    let k = &a.kinematics;
    println!(
        "{} [{}] | fs {} Hz | {} samples ({:.2} s) | {:.0} rpm ({}) | bearing {} ({})",
        a.file.display(),
        a.channel,
        a.fs,
        a.samples,
        a.duration_s,
        a.rpm,
        a.rpm_source,
        a.bearing,
        a.bearing_source
    );
    println!(
        "kinematics: 1x {:.2} Hz  FTF {:.2}  BPFO {:.2}  BPFI {:.2}  BSF {:.2} (2xBSF {:.2})  natural {:.0} Hz",
        k.shaft_hz,
        k.ftf,
        k.bpfo,
        k.bpfi,
        k.bsf,
        2.0 * k.bsf,
        k.natural_hz
    );
    let s = &a.stats;
    println!(
        "statistics ({}): RMS {:.4}  peak {:.4}  crest {:.2}  kurtosis {:.2}  skewness {:.3}",
        a.unit, s.rms, s.peak, s.crest_factor, s.kurtosis, s.skewness
    );
    let kg = &a.kurtogram;
    println!(
        "demodulation band (fast kurtogram, level {:.1}, bands >= {:.0} Hz above the fault zone): {:.0}-{:.0} Hz, kurtosis {:.2}{}",
        kg.level,
        kg.min_band_hz,
        kg.band_hz.0,
        kg.band_hz.1,
        kg.kurtosis,
        if a.method.prewhiten { "; envelope of the pre-whitened record" } else { "" }
    );
    let d = &a.diagnosis;
    println!(
        "diagnosis: {} (confidence {:.2}; leading family {}, margin {:.1} dB; exclusive score {:.1} dB per searched harmonic; +found =shared [sidebands dB])",
        family_name(d.family),
        d.confidence,
        family_name(d.candidate),
        d.margin_db,
        d.score
    );
    for e in &d.evidence {
        let mut parts = vec![];
        for h in &e.harmonics {
            let mut s = format!(
                "{}x {:.1}Hz:{}{:.1}dB",
                h.order,
                h.peak.map_or(h.expected_hz, |p| p.freq),
                match (h.found, h.shared) {
                    (true, true) => "=",
                    (true, false) => "+",
                    _ => "",
                },
                h.over_floor_db
            );
            if let Some([lo, hi]) = h.sidebands_db {
                s.push_str(&format!(" [sb {lo:.0}/{hi:.0}]"));
            }
            parts.push(s);
        }
        println!(
            "  {:<10} base {:>7.2} Hz fitted {:>7.2} Hz  found {}/{}  score {:>5.1}  exclusive {:>5.1}",
            family_name(e.family),
            e.base_hz,
            e.fundamental_hz,
            e.found,
            e.harmonics.len(),
            e.score,
            e.exclusive_score,
        );
        println!("    {}", parts.join("  "));
    }
    match (&a.zones, &a.zones_note) {
        (Some(z), _) => {
            let (b, l) = (&z.bands, &z.levels);
            println!("zone levels (RMS, {}):", a.unit);
            for (name, band, v) in [
                ("rotating", b.rotating, l.rotating),
                ("fault", b.fault, l.fault),
                ("natural", b.natural, l.natural),
                ("high", b.high, l.high),
            ] {
                println!("  {name:<9} {:>8.1}-{:<8.1} Hz  {v:.4e}", band.0, band.1);
            }
            println!("  total     {:.4e}", l.total);
        }
        (None, Some(n)) => println!("zone levels: {n}"),
        (None, None) => {}
    }
}

/// Why a record cannot be analysed.
#[derive(Debug, thiserror::Error)]
pub enum AnalyzeError {
    /// Bad input: the file, its metadata, an argument (names the field and its range).
    #[error("{0}")]
    Input(String),
    /// The analysis itself failed (a non-finite figure from finite input).
    #[error("{0}")]
    Run(String),
}

impl AnalyzeError {
    /// Bad input.
    pub fn input(e: impl std::fmt::Display) -> Self {
        AnalyzeError::Input(e.to_string())
    }
}

/// The file name `path` without directories, for messages.
pub fn short_name(path: &Path) -> String {
    path.file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::synth::gaussian_noise;
    use std::f64::consts::PI;

    const FS: f64 = 12_000.0;

    use crate::analysis::synth::cwru_6205_1797rpm as cwru;

    /// Outer-race fault record: impulses at BPFO with 1 % random slip between impacts
    /// (uniform, Randall & Antoni 2011 report 1-2 %; a jitter-free train would be a purely
    /// periodic signal, which cepstral pre-whitening flattens away with the machine lines),
    /// each ringing a 3.5 kHz resonance (damping 0.05), in white noise of sigma 0.3.
    fn outer_race_record(n: usize) -> Vec<f64> {
        let mut x = gaussian_noise(n, 0.3, 7);
        let (wn, zeta) = (2.0 * PI * 3500.0, 0.05);
        let ring = ((9.2 / (zeta * wn)) * FS).ceil() as usize + 1;
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut t = 0.0;
        while t * FS < n as f64 {
            let first = (t * FS).ceil() as usize;
            for (i, xi) in x.iter_mut().enumerate().skip(first).take(ring) {
                let dt = i as f64 / FS - t;
                *xi += (-zeta * wn * dt).exp() * (wn * dt).sin();
            }
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let u = (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
            t += (1.0 + 0.02 * u) / cwru().bpfo;
        }
        x
    }

    #[test]
    fn every_band_rule_keeps_to_admissible_cells() -> Result<(), analysis::AnalysisError> {
        let ff = cwru();
        let x = outer_race_record(48_000);
        let base = Method::default();
        let top = base.detect.harmonics as f64 * ff.bpfi.max(2.0 * ff.bsf);
        let mut margins = Vec::new();
        for rule in [BandRule::Kurtosis, BandRule::Evidence, BandRule::Protrugram] {
            let a = analyze_signal(
                &x,
                FS,
                &ff,
                &Method {
                    band_rule: rule,
                    ..base
                },
            )?;
            let (lo, hi) = a.kurtogram.band_hz;
            // Above the searched fault zone and at least the narrowest admissible width.
            assert!(
                lo + 1e-9 >= top,
                "{rule:?}: band {lo}-{hi} starts below {top} Hz"
            );
            assert!(
                hi - lo + 1e-9 >= a.kurtogram.min_band_hz,
                "{rule:?}: {lo}-{hi}"
            );
            assert_eq!(a.diagnosis.family, FaultFamily::OuterRace, "{rule:?}");
            margins.push(a.diagnosis.margin_db);
        }
        // The evidence rule maximises the margin over the same cells the kurtosis rule
        // chooses from, so it can never give less.
        assert!(margins[1] + 1e-9 >= margins[0], "{margins:?}");
        Ok(())
    }
    #[test]
    fn noise_is_healthy_under_every_band_rule() -> Result<(), analysis::AnalysisError> {
        let ff = cwru();
        for seed in [11, 12] {
            let x = gaussian_noise(48_000, 1.0, seed);
            for rule in [BandRule::Kurtosis, BandRule::Evidence, BandRule::Protrugram] {
                for squared_envelope in [false, true] {
                    let m = Method {
                        band_rule: rule,
                        squared_envelope,
                        ..Method::default()
                    };
                    let d = analyze_signal(&x, FS, &ff, &m)?.diagnosis;
                    assert_eq!(d.family, FaultFamily::None, "seed {seed} {m:?}: {d:?}");
                    assert!(d.confidence.is_finite() && d.margin_db.is_finite());
                }
            }
        }
        Ok(())
    }
}
