//! `wearsim analyze`: reads one or many measured (or simulated) records in any supported
//! layout, resolves the bearing, speed and sample rate (argument, file, sidecar or
//! configuration, each reported with its source), runs the diagnosis chain
//! ([`crate::analysis::chain`]: statistics, kurtogram-selected demodulation band,
//! pre-whitened envelope spectrum, calibrated fault-family decision, El-Thalji zone levels)
//! and reports it as text, JSON, CSV or Markdown, with optional plots.
//!
//! One parameter set ([`Method::default`]) serves every record: nothing depends on a label.

use crate::analysis::chain::{analyze_signal, KurtogramSummary, Method, Spectra, Zones};
use crate::analysis::{self, FaultDiagnosis, FaultFamily, FaultFrequencies, Stats};
use crate::io::{self, ReadOptions, Record};
use crate::kinematics;
use clap::Args;
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
    #[arg(long, allow_negative_numbers = true)]
    pub rpm: Option<f64>,
    /// Use the speed as stated (argument, file, sidecar or configuration) even when the
    /// record's shaft line is elsewhere, e.g. a tachometer's speed. Default: a stated speed
    /// 1–5 % from the record's own 1× line (a line with its own 2× or 3×), with no line at
    /// the stated 1×, is replaced by the speed of the line's 1×–5× series (reported under
    /// `speed_refined`; see `analysis::shaft_line::refine`).
    #[arg(long)]
    pub trust_rpm: bool,
    /// Sample rate (Hz), 1..=1e7: for a file that states none; must agree (within 0.1 %)
    /// with a rate the file or its sidecar states (else exit 2); overrides a layout's or a
    /// file name's rate.
    #[arg(long, allow_negative_numbers = true)]
    pub fs: Option<f64>,
    /// Bearing preset giving the geometry (see `wearsim presets`) or a catalogue bearing
    /// (`mfpt-nice`, `paderborn-6203`, `xjtu-ldk-uer204`); overrides the record's.
    #[arg(long)]
    pub bearing: Option<String>,
    /// Any bearing: `elements=N,ball=MM,pitch=MM,angle=DEG` (diameters in mm, contact angle in
    /// degrees, 0..=45.8, ball 0.1..=500 mm, pitch > 1.5 × ball, 3..=32 elements that fit
    /// on the pitch circle); overrides the record's.
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
    /// every readable record is analysed and one table is written.
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
            trust_rpm: false,
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
    /// Where exactly the rate was found (the reader's words, `fs_source` kept as it was):
    /// `--fs`, `WAV header`, `time column `Time (ms)``, `sidecar `run1.json``, `MAT
    /// variable `fs``, `MAT struct field `bearing.sr``, `CWRU file name `…` (12000 Hz)`,
    /// `xjtu-sy layout (25600 Hz, documented)`; `fs_source` when the reader says no more.
    pub fs_detail: String,
    /// What the reader found: `layout` (`cwru`, `mfpt`, `paderborn`, `ims`, `femto`,
    /// `xjtu-sy`, `generic`), `variable` (path inside a MAT file), `rpm_source` (as `fs_source`),
    /// `load` and `load_source` when the file stores a load; absent keys are unknown.
    pub input: serde_json::Value,
    /// Number of samples.
    pub samples: usize,
    /// Duration, s.
    pub duration_s: f64,
    /// Shaft speed used, rpm: the stated one, or the measured one when `speed_refined` is set.
    pub rpm: f64,
    /// Where the speed came from: `argument`, `file`, `config` (the `--config` scenario's
    /// speed), or `file speed profile` / `config speed profile` when the model's speed
    /// profile gives it over the record's span (its mean when order-tracked), or
    /// [`analysis::shaft_line::REFINED_SOURCE`] when the record's own 1× line replaced a stated speed it
    /// contradicts (`speed_refined`; `rpm_detail` then names the stated speed and its source).
    pub rpm_source: String,
    /// Where exactly the speed was found: `--rpm`, `sidecar `run1.json``, `MAT variable
    /// `X118RPM``, `MAT struct field `bearing.rate` (Hz × 60)`, `Paderborn variable name
    /// `…``, `ims layout (2000 rpm, documented)`, `--config `FILE``, `speed profile of the
    /// sidecar's model` / `speed profile of --config`; `rpm_source` when the reader says no
    /// more.
    pub rpm_detail: String,
    /// Set when the record was taken at a varying shaft speed that its wearsim sidecar's
    /// (or `--config` scenario's) speed profile states: the record was resampled to equal
    /// shaft-angle steps before the analysis and `rpm` is the mean speed (see
    /// [`crate::analysis::order_tracking`]). `None` at constant speed or with `--rpm`.
    pub order_tracking: Option<OrderTracking>,
    /// Bearing preset used for the geometry (`custom`: the geometry of a wearsim
    /// sidecar's structured model that is no preset's).
    pub bearing: String,
    /// Where the bearing came from: `argument`, `file`, `sidecar`, `config` (`--config`)
    /// or `label` (a CWRU file name's faulty end when the channel is the other bearing's:
    /// `12k_Drive_End_…` read on `FE` is diagnosed for the drive-end 6205).
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
    /// Whether the raw spectrum's shaft line is where `fs` and `rpm` put it
    /// ([`crate::analysis::shaft_line`]): `consistent: false` says to check `--fs` and
    /// `--rpm` (the call is not changed). `None`: the record is too short to resolve 2.5 %
    /// of the shaft frequency with seven averaged segments.
    pub speed_check: Option<analysis::shaft_line::ShaftLine>,
    /// Set when the stated speed was replaced by the record's own 1× line (the stated speed
    /// is `stated_hz` × 60; `rpm` is the measured one): no line at the stated 1× and a line
    /// 1–5 % from it ([`analysis::shaft_line::refine`]). `None`: the stated speed is used
    /// (confirmed, not contradicted, not checkable, order-tracked, or `--trust-rpm`).
    pub speed_refined: Option<analysis::shaft_line::Refinement>,
    /// Knocks and bursts cut out before the band was chosen and the record demodulated
    /// (blocks of one revolution standing 20 dB over the median block, with a block on each
    /// side; [`analysis::transients`]). `stats`, the spectrum and `zones` are of the record as
    /// given. `None`: nothing cut.
    pub transients: Option<analysis::transients::Transients>,
}

/// How a record taken at a varying speed was order-tracked (see [`Analysis::order_tracking`]).
#[derive(Debug, Clone, Serialize)]
pub struct OrderTracking {
    /// Lowest shaft frequency over the record, Hz.
    pub min_hz: f64,
    /// Highest shaft frequency over the record, Hz.
    pub max_hz: f64,
    /// Mean shaft frequency, Hz (revolutions / duration); `rpm` is 60 times it.
    pub mean_hz: f64,
    /// Shaft revolutions over the record.
    pub revolutions: f64,
    /// Model time of the record's first sample, s (the sidecar's `settle_s`).
    pub start_s: f64,
}

/// An order-tracked record's samples and how it was tracked.
type Tracked = (Vec<f64>, OrderTracking);

/// The shaft speed over the record from a model's speed profile, when the profile is not
/// constant: the record's first sample is at model time `settle_s` (a wearsim sidecar's key;
/// 0 without one). Constant over the record: that speed and the record unchanged; varying:
/// the order-tracked record at its mean speed.
fn speed_from_profile(rec: &Record, model: &ModelConfig) -> Option<(f64, Option<Tracked>)> {
    if model.speed.is_constant() {
        return None;
    }
    let start_s = rec
        .meta
        .get("sidecar")
        .and_then(|s| s.get("settle_s"))
        .and_then(serde_json::Value::as_f64)
        .filter(|t| t.is_finite() && *t >= 0.0)
        .unwrap_or(0.0);
    let o = crate::analysis::order_tracking::order_track(&rec.samples, rec.fs, start_s, |t| {
        model.speed.shaft_hz(t)
    })?;
    if o.max_hz - o.min_hz <= 1e-9 * o.max_hz {
        return Some((60.0 * o.min_hz, None));
    }
    let info = OrderTracking {
        min_hz: o.min_hz,
        max_hz: o.max_hz,
        mean_hz: o.mean_hz,
        revolutions: o.revolutions,
        start_s,
    };
    Some((60.0 * o.mean_hz, Some((o.samples, info))))
}

/// Read `args.file` and analyse it; errors name the file (exit 2 for bad input).
pub fn analyze(args: &AnalyzeArgs) -> Result<(Analysis, Spectra), AnalyzeError> {
    if let Some(r) = args.rpm {
        io::record::check_rpm_argument(r).map_err(AnalyzeError::input)?;
    }
    if let Some(f) = args.fs {
        io::record::check_fs_flag(f).map_err(AnalyzeError::input)?;
    }
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
    let config_detail = args
        .config
        .as_ref()
        .map(|c| format!("--config `{}`", c.display()));
    if let (true, Some((m, _)), Some(d)) = (rpm_from_config, &scenario, &config_detail) {
        rec.rpm = Some(60.0 * m.speed.shaft_hz(0.0));
        // Named as the stated speed's source should the record's 1× line replace it.
        if let Some(meta) = rec.meta.as_object_mut() {
            meta.insert("rpm_detail".into(), d.clone().into());
        }
    }
    let (mut a, spectra) = analyze_chosen(
        &rec,
        BearingChoice {
            preset: args.bearing.as_deref(),
            geometry: args.bearing_geometry.as_deref(),
            scenario: scenario.as_ref().map(|(m, l)| (m, l.as_str())),
        },
        Speed {
            from_argument: args.rpm.is_some(),
            refine: !args.trust_rpm,
        },
        &Method::default(),
    )?;
    if rpm_from_config && a.rpm_source == "file" {
        a.rpm_source = "config".into();
        if let Some(d) = config_detail {
            a.rpm_detail = d;
        }
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
    let speed = Speed {
        from_argument: rpm_from_argument,
        refine: true,
    };
    analyze_chosen(rec, choice, speed, method)
}

/// How the stated speed is taken.
#[derive(Debug, Clone, Copy)]
struct Speed {
    /// It came from `--rpm` (labels `rpm_source`; a model's speed profile is then ignored).
    from_argument: bool,
    /// Replace it by the record's 1× line when the record contradicts it
    /// ([`analysis::shaft_line::refine`]); `false` with `--trust-rpm`.
    refine: bool,
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
    speed: Speed,
    method: &Method,
) -> Result<(Analysis, Spectra), AnalyzeError> {
    let rpm_from_argument = speed.from_argument;
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
    // A labelled CWRU fault sits in the bearing its file name names, whichever channel
    // recorded it (a drive-end fault seen by the fan-end sensor is still the 6205's); the
    // channel's own bearing otherwise (as `gap` matches it).
    let labelled = crate::io::mat::cwru_faulty_bearing(&rec.source);
    let file_bearing = labelled.or(rec.bearing.as_deref());
    let (bearing, bearing_source, file_model) =
        match (&custom, bearing, choice.scenario, file_model, file_bearing) {
            (_, _, Some((m, label)), _, _) => (label.to_string(), "config", Some(m.clone())),
            (Some(c), _, None, _, _) => (c.0.clone(), c.1, None),
            (None, Some(b), None, _, _) => (b.to_string(), "argument", None),
            (None, None, None, Some(m), label) => {
                (label.unwrap_or("custom").to_string(), "file", Some(m))
            }
            (None, None, None, None, Some(b)) if wearsim_core::presets::by_name(b).is_some() => {
                let source = if labelled.is_some() && labelled != rec.bearing.as_deref() {
                    "label"
                } else {
                    "file"
                };
                (b.to_string(), source, None)
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
    // A model whose speed varies gives the speed over the record (and order-tracks it),
    // unless `--rpm` says otherwise.
    let profile = file_model.as_ref().and_then(|m| speed_from_profile(rec, m));
    if let (true, Some((_, Some((_, o))))) = (rpm_from_argument, &profile) {
        eprintln!(
            "wearsim: warning: {file}: the model's shaft speed varies over the record ({:.3}-{:.3} Hz); --rpm analyses it as constant, without order tracking",
            o.min_hz, o.max_hz
        );
    }
    let profile = profile.filter(|_| !rpm_from_argument);
    let from_profile = profile.is_some();
    let (rpm, tracked) = match profile {
        Some((rpm, tracked)) => (Some(rpm), tracked),
        None => (rec.rpm, None),
    };
    let samples: &[f64] = tracked.as_ref().map_or(&rec.samples, |t| &t.0);
    let Some(stated_rpm) = rpm else {
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
    // A constant speed the record contradicts: its own 1× line (an order-tracked record's
    // speed is the model's, exact).
    let stated_spectrum =
        analysis::shaft_line::ShaftSpectrum::new(samples, rec.fs, stated_rpm / 60.0);
    let speed_refined = (speed.refine && tracked.is_none())
        .then(|| stated_spectrum.as_ref().and_then(|s| s.refine()))
        .flatten();
    let rpm = speed_refined.map_or(stated_rpm, |r| r.rpm());
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
        samples.len(),
        rec.fs,
        kin.shaft_hz,
        [kin.bpfo, kin.bpfi, 2.0 * kin.bsf],
    )
    .map_err(|e| AnalyzeError::input(format!("{file}: channel {}: {e}", rec.channel)))?;
    let a = analyze_signal(samples, rec.fs, &kin, method)
        .map_err(|e| AnalyzeError::input(format!("{file}: channel {}: {e}", rec.channel)))?;
    let (zones, zones_note) = match a.zones {
        Ok(z) => (Some(z), None),
        Err(e) => (None, Some(e)),
    };
    let meta_str = |k: &str| rec.meta.get(k).and_then(|v| v.as_str()).map(str::to_string);
    let fs_source = meta_str("fs_source").unwrap_or_else(|| "file".to_string());
    let stated_source = match (rpm_from_argument, from_profile) {
        (true, _) => "argument".to_string(),
        (false, true) => format!("{bearing_source} speed profile"),
        (false, false) => "file".to_string(),
    };
    let stated_detail = match (rpm_from_argument, from_profile) {
        (true, _) => io::sidecar::ARGUMENT_RPM.to_string(),
        (false, true) if bearing_source == "config" => "speed profile of --config".to_string(),
        (false, true) => "speed profile of the sidecar's model".to_string(),
        (false, false) => meta_str("rpm_detail").unwrap_or_else(|| stated_source.clone()),
    };
    let (rpm_source, rpm_detail) = match &speed_refined {
        None => (stated_source, stated_detail),
        Some(r) => (
            analysis::shaft_line::REFINED_SOURCE.to_string(),
            format!(
                "shaft at {:.3} Hz (fitted to {} of its 1x-{}x lines; the 1x line {:.1} dB); the stated {stated_rpm:.0} rpm ({stated_source}: {stated_detail}) is {:+.1} % from it",
                r.measured_hz,
                r.harmonics,
                analysis::shaft_line::SERIES_HARMONICS,
                r.line_db,
                -100.0 * r.offset / (1.0 + r.offset)
            ),
        ),
    };
    // At the stated speed the refinement's spectrum is the check's (one Welch, not two).
    let speed_check = match &stated_spectrum {
        Some(s) if s.shaft_hz() == kin.shaft_hz => Some(s.check()),
        _ => analysis::shaft_line::check(samples, rec.fs, kin.shaft_hz),
    };
    let analysis = Analysis {
        file: rec.source.clone(),
        channel: rec.channel.clone(),
        unit: rec.unit.clone(),
        fs: rec.fs,
        fs_detail: meta_str("fs_detail").unwrap_or_else(|| fs_source.clone()),
        fs_source,
        input: input_provenance(rec),
        samples: rec.samples.len(),
        duration_s: rec.duration_s(),
        rpm,
        rpm_source,
        rpm_detail,
        order_tracking: tracked.map(|t| t.1),
        bearing,
        bearing_source: bearing_source.into(),
        kinematics: kin,
        method: *method,
        stats: a.stats,
        transients: a.transients,
        kurtogram: a.kurtogram,
        diagnosis: a.diagnosis,
        zones,
        zones_note,
        speed_check,
        speed_refined,
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
    // Where the speed was found, when that says more than its category (a MAT variable, a
    // folder name's condition): a folder name is not the file's own statement. A refined
    // speed's detail is the warning line below.
    let rpm_from =
        if a.speed_refined.is_some() || a.rpm_detail.is_empty() || a.rpm_detail == a.rpm_source {
            a.rpm_source.clone()
        } else {
            format!("{}: {}", a.rpm_source, a.rpm_detail)
        };
    println!(
        "{} [{}] | fs {} Hz | {} samples ({:.2} s) | {:.0} rpm ({rpm_from}) | bearing {} ({})",
        a.file.display(),
        a.channel,
        a.fs,
        a.samples,
        a.duration_s,
        a.rpm,
        a.bearing,
        a.bearing_source
    );
    if let Some(r) = &a.speed_refined {
        println!(
            "warning: speed refined: no shaft line at the stated {:.0} rpm; the record's 1x line ({:.1} dB) is at {:.0} rpm ({:+.1} %), used below (--trust-rpm keeps the stated speed)",
            60.0 * r.stated_hz,
            r.line_db,
            a.rpm,
            100.0 * r.offset
        );
    }
    if let Some(t) = &a.transients {
        let spans: Vec<String> = t
            .spans_s
            .iter()
            .map(|(a, b)| format!("{a:.3}-{b:.3} s"))
            .collect();
        println!(
            "warning: transients cut out before demodulation: {} ({:.3} s; strongest block {:.1} dB over the median)",
            spans.join(", "),
            t.seconds,
            t.peak_db
        );
    }
    if let Some(r) = a.speed_check.as_ref().and_then(|c| c.reason.as_ref()) {
        println!(
            "warning: speed check: {r}; check --fs and --rpm, the diagnosis below assumes them"
        );
    }
    if let Some(o) = &a.order_tracking {
        println!(
            "order-tracked: the shaft speed varies {:.3}-{:.3} Hz over the record (model time from {:.3} s); resampled to equal shaft angle, {:.1} revolutions, analysed at the mean {:.3} Hz",
            o.min_hz, o.max_hz, o.start_s, o.revolutions, o.mean_hz
        );
    }
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
    if let Some(why) = &kg.no_content {
        println!("no demodulation band: {why}");
    }
    let d = &a.diagnosis;
    println!(
        "diagnosis: {} (confidence {:.2}; leading family {}, margin {:.1} dB{}; exclusive score {:.1} dB per searched harmonic; +found =shared ~shaft [sidebands dB])",
        family_name(d.family),
        d.confidence,
        family_name(d.candidate),
        d.margin_db,
        if d.candidate == d.margin_family {
            String::new()
        } else {
            format!(" of the best partial family, {}", family_name(d.margin_family))
        },
        d.score
    );
    for e in &d.evidence {
        let mut parts = vec![];
        for h in &e.harmonics {
            let mut s = format!(
                "{}x {:.1}Hz:{}{:.1}dB",
                h.order,
                h.peak.map_or(h.expected_hz, |p| p.freq),
                match (h.found, h.shared, h.explained()) {
                    (true, _, true) => "~",
                    (true, true, false) => "=",
                    (true, false, false) => "+",
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
    let comb = &d.shaft_comb;
    if !comb.explains.is_empty() {
        let names: Vec<&str> = comb.explains.iter().map(|f| family_name(*f)).collect();
        println!(
            "  shaft orders {:?} found; they explain the lines marked ~ of {} (fundamental on a shaft order)",
            comb.orders,
            names.join(", ")
        );
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
