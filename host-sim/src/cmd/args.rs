//! Arguments shared by the `wearsim` subcommands (`simulate`'s scenario arguments, `bench`),
//! the progress display, and the simulate sidecar and summary printing. Part of the command
//! layer: library modules never import it, and its errors are [`CliError`]s that
//! [`crate::cmd::exit`] maps to exit codes.

use crate::config::{self, ScenarioFile};
use crate::simulate::{self, Scenario};
use crate::summary::Summary;
use clap::Args;
use serde::Serialize;
use serde_json::{json, Value};
use std::path::PathBuf;

pub use crate::cmd::exit::CliError;

/// `wearsim simulate` arguments. Command-line values override the configuration file,
/// which overrides the preset.
#[derive(Debug, Clone, Args, Default)]
pub struct SimulateArgs {
    /// Preset to start from (see `wearsim presets`); default thesis-61810.
    #[arg(long, conflicts_with = "config")]
    pub preset: Option<String>,
    /// TOML scenario file (see the README's configuration reference).
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// Recorded duration (s), 0.001..=600.
    #[arg(long)]
    pub duration: Option<f64>,
    /// Output sample rate (Hz), 100..=1e6.
    #[arg(long, allow_negative_numbers = true)]
    pub fs: Option<f64>,
    /// Random seed.
    #[arg(long)]
    pub seed: Option<u64>,
    /// Defect topography: healthy, real-dent, smoothed-dent, mild-defect, medium-defect,
    /// large-defect, smoothed-large-defect, two-large-defects.
    #[arg(long)]
    pub topography: Option<String>,
    /// Shaft speed (rpm), overriding the scenario's speed profile with a constant speed.
    #[arg(long, allow_negative_numbers = true)]
    pub rpm: Option<f64>,
    /// Output directory.
    #[arg(long, default_value = "wearsim-out")]
    pub out: PathBuf,
    /// Print the summary as JSON on stdout (no progress bar).
    #[arg(long)]
    pub json: bool,
    /// Switch a candidate effect on: NAME[:PARAM=VALUE,...] (repeatable; see `wearsim effects`).
    #[arg(long = "effect", value_name = "NAME[:PARAM=VALUE,...]")]
    pub effect: Vec<String>,
}

/// Adds the `--effect` arguments to the scenario file's effects: an argument naming an
/// effect the file already has replaces it; one effect given twice on the command line is
/// refused.
pub fn add_effect_args(file: &mut ScenarioFile, args: &[String]) -> Result<(), CliError> {
    let given = args
        .iter()
        .map(|a| crate::effects::parse_arg(a))
        .collect::<Result<Vec<_>, _>>()
        .map_err(CliError::input)?;
    crate::effects::check_unique(given.iter().map(|e| e.name.as_str()), "--effect", "")
        .map_err(CliError::input)?;
    for g in given {
        file.effect.retain(|e| e.name != g.name);
        file.effect.push(g);
    }
    Ok(())
}

impl SimulateArgs {
    /// Resolves preset, file and arguments into a validated scenario.
    pub fn scenario(&self) -> Result<Scenario, CliError> {
        let mut file = match &self.config {
            Some(p) => ScenarioFile::load(p).map_err(CliError::input)?,
            None => ScenarioFile::default(),
        };
        if file.preset.is_none() && self.config.is_none() {
            file.preset = Some(
                self.preset
                    .clone()
                    .unwrap_or_else(|| config::DEFAULT_PRESET.to_string()),
            );
        }
        if let Some(d) = self.duration {
            file.duration = Some(d);
        }
        if let Some(f) = self.fs {
            file.fs = Some(f);
        }
        if let Some(s) = self.seed {
            file.seed = Some(s);
        }
        if let Some(r) = self.rpm {
            config::check_sim_rpm("--rpm", r).map_err(CliError::input)?;
            file.speed = Some(config::SpeedSection {
                rpm: Some(r),
                ..Default::default()
            });
        }
        if let Some(t) = &self.topography {
            let mut d = file.defect.clone().unwrap_or_default();
            d.topography = Some(t.clone());
            if t != "healthy" {
                d.enabled = Some(true);
            }
            file.defect = Some(d);
        }
        add_effect_args(&mut file, &self.effect)?;
        let (cfg, run) = file.resolve().map_err(CliError::input)?;
        Scenario::new(cfg, run).map_err(CliError::input)
    }
}

/// `wearsim bench` arguments.
#[derive(Debug, Clone, Args)]
pub struct BenchArgs {
    /// Preset to benchmark.
    #[arg(long, default_value = config::DEFAULT_PRESET)]
    pub preset: String,
    /// Simulated seconds to time (after a 1 s warm-up run), 1..=600.
    #[arg(long, default_value_t = 20.0)]
    pub seconds: f64,
    /// Output sample rate (Hz).
    #[arg(long, default_value_t = 20_000.0)]
    pub fs: f64,
    /// Throughput of K parameter sets stepped together as K lanes against the scalar step
    /// (simulated s per core-second; K in 1, 2, 4, 8, 16).
    #[arg(long, value_name = "K")]
    pub lanes: Option<usize>,
    /// Scenario file for `--lanes` (instead of `--preset`); the scalar bench times the
    /// preset only, so without `--lanes` it is refused rather than ignored.
    #[arg(
        long,
        value_name = "FILE",
        requires = "lanes",
        conflicts_with = "preset"
    )]
    pub config: Option<std::path::PathBuf>,
    /// With `--lanes`: lane `i` at its own constant speed, `1 + 0.01 i` times the
    /// scenario's (the lanes' own-kinematics path that sweeps over speeds take).
    #[arg(long, requires = "lanes")]
    pub own_speed: bool,
    /// Machine-readable output.
    #[arg(long)]
    pub json: bool,
}

/// What `wearsim bench` measures.
#[derive(Debug, Clone, Serialize)]
pub struct BenchReport {
    /// Simulated seconds per wall-clock second, one core.
    pub rtf: f64,
    /// Wall-clock nanoseconds per internal integration step.
    pub ns_per_step: f64,
    /// Wall-clock nanoseconds per output sample.
    pub ns_per_sample: f64,
    /// Preset timed.
    pub preset: String,
    /// Output rate (Hz).
    pub fs: f64,
    /// Internal steps per output sample.
    pub oversample: u32,
    /// Integrator name.
    pub integrator: String,
    /// Simulated seconds timed.
    pub simulated_s: f64,
    /// Wall seconds.
    pub wall_s: f64,
    /// Internal steps timed.
    pub steps: u64,
}

/// Runs the benchmark: a 1 s warm-up, then `seconds` simulated seconds timed.
pub fn bench(a: &BenchArgs) -> Result<BenchReport, CliError> {
    wearsim_core::error::check_range("seconds", a.seconds, 1.0, 600.0).map_err(CliError::input)?;
    let file = ScenarioFile {
        preset: Some(a.preset.clone()),
        fs: Some(a.fs),
        duration: Some(a.seconds),
        settle: Some(1.0),
        ..Default::default()
    };
    let (cfg, run) = file.resolve().map_err(CliError::input)?;
    let sc = Scenario::new(cfg, run).map_err(CliError::input)?;
    // Warm-up run (caches, frequency scaling), then the timed run without settling time.
    simulate::run(
        &Scenario {
            run: config::RunSettings {
                duration: 1.0,
                ..sc.run.clone()
            },
            ..sc.clone()
        },
        |_, _| {},
    )
    .map_err(CliError::run)?;
    let timed = Scenario {
        run: config::RunSettings {
            settle: 0.0,
            ..sc.run.clone()
        },
        ..sc.clone()
    };
    let out = simulate::run(&timed, |_, _| {}).map_err(CliError::run)?;
    let steps = out.steps;
    let integrator = config::INTEGRATORS
        .iter()
        .find(|(_, k)| *k == sc.model.config().integrator)
        .map(|(n, _)| *n)
        .unwrap_or("?");
    Ok(BenchReport {
        rtf: a.seconds / out.wall_s,
        ns_per_step: out.wall_s * 1e9 / steps as f64,
        ns_per_sample: out.wall_s * 1e9 / out.accel.len() as f64,
        preset: a.preset.clone(),
        fs: sc.fs(),
        oversample: sc.model.oversample(),
        integrator: integrator.to_string(),
        simulated_s: a.seconds,
        wall_s: out.wall_s,
        steps,
    })
}

/// A progress bar on standard error that appears only after a run has taken more than a
/// second, and never when `enabled` is false (not a terminal, or `--json`).
pub struct Progress {
    bar: Option<indicatif::ProgressBar>,
    start: std::time::Instant,
    label: &'static str,
}

impl Progress {
    /// A new, not yet visible, progress display.
    pub fn new(enabled: bool, label: &'static str) -> Self {
        let bar = enabled.then(|| {
            let b = indicatif::ProgressBar::with_draw_target(
                Some(0),
                indicatif::ProgressDrawTarget::hidden(),
            );
            b.set_style(
                indicatif::ProgressStyle::with_template("{msg} [{bar:40}] {percent}% eta {eta}")
                    .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar())
                    .progress_chars("=> "),
            );
            b.set_message(label);
            b
        });
        Progress {
            bar,
            start: std::time::Instant::now(),
            label,
        }
    }

    /// Reports `done` of `total`.
    pub fn update(&self, done: usize, total: usize) {
        if let Some(b) = &self.bar {
            b.set_length(total as u64);
            b.set_position(done as u64);
            if b.is_hidden() && self.start.elapsed().as_secs_f64() > 1.0 {
                b.set_draw_target(indicatif::ProgressDrawTarget::stderr());
                b.set_message(self.label);
            }
        }
    }

    /// Removes the bar.
    pub fn finish(&self) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }
}

/// One-line description of each preset (with where its values come from).
pub fn preset_description(name: &str) -> &'static str {
    match name {
        "thesis-61810" => "reference of the thesis: SKF 61810, 160 rad/s, 500 N; M chosen for the 1100 Hz zone, zeta 3 %; medium outer-race defect",
        "thesis-as-printed" => "thesis ch. 4 values as printed: M 11 kg, K 5.96e7 N/m, C 5e7 N s/m -- grossly over-damped (zeta >> 1), no resonance",
        "cwru-6205-de" => "CWRU drive end: SKF 6205, 9 x 7.94 mm on 39.04 mm, 1797 rpm, gravity load; housing mode chosen near 3.3 kHz; 0.007 in outer-race defect",
        "cwru-6203-fe" => "CWRU fan end: SKF 6203, 8 x 6.75 mm on 28.50 mm, 1797 rpm; healthy",
        "ims-za2115" => "IMS run-to-failure: Rexnord ZA-2115, 16 rollers 0.331 in on 2.815 in, 15.17 deg, 2000 rpm, 6000 lbf; line contact",
        _ => "",
    }
}

/// Sidecar metadata of a simulation run.
pub fn run_metadata(sc: &Scenario, a: &SimulateArgs, summary: &Summary) -> Value {
    let cfg = sc.model.config();
    let speed = sc.record_speed();
    let mut v = json!({
        "generator": "wearsim simulate",
        "version": crate::VERSION,
        "preset": sc.run.preset,
        "config_file": a.config,
        "seed": sc.run.seed,
        "duration_s": sc.run.duration,
        "settle_s": sc.run.settle,
        // The recorded part's mean speed, and its range when a ramp or table varies it.
        "rpm": 60.0 * speed.mean_hz,
        "rpm_range": [60.0 * speed.min_hz, 60.0 * speed.max_hz],
        "oversample": sc.model.oversample(),
        "internal_step_s": sc.model.step_size(),
        "integrator": crate::config::INTEGRATORS
            .iter()
            .find(|(_, k)| *k == cfg.integrator)
            .map(|(name, _)| *name),
        // Table 1's name, or the custom topography's dimensions.
        "topography": cfg.defect.map(|d| {
            wearsim_core::topography::TABLE_1
                .iter()
                .find(|(_, t)| *t == d.topography)
                .map_or_else(|| json!(d.topography), |(name, _)| json!(name))
        }),
        "effects": sc_effects(sc, a),
        "summary": summary,
        "usable_band_hz": [0.0, 0.4 * cfg.output_rate],
    });
    if let Value::Object(m) = &mut v {
        m.extend(crate::io::sidecar::model_metadata(
            sc.run.preset.as_deref(),
            cfg,
        ));
    }
    v
}

/// The effects switched on (command line after file), for the sidecar.
fn sc_effects(sc: &Scenario, a: &SimulateArgs) -> Value {
    json!({
        "arguments": a.effect,
        "resolved": sc.model.config().effects,
    })
}

/// Human-readable summary of a simulation.
pub fn print_summary(sc: &Scenario, s: &Summary, rtf: f64, files: &crate::io::write::OutputSet) {
    let k = &s.kinematics;
    println!(
        "scenario: {} | fs {} Hz | {:.3} s | seed {} | shaft {:.2} Hz | real-time factor {:.0}x",
        sc.run.preset.as_deref().unwrap_or("custom"),
        sc.fs(),
        sc.run.duration,
        sc.run.seed,
        k.shaft_hz,
        rtf
    );
    println!(
        "kinematics: FTF {:.2}  BPFO {:.2}  BPFI {:.2}  BSF {:.2}  natural {:.0} Hz",
        k.ftf, k.bpfo, k.bpfi, k.bsf, k.natural_hz
    );
    let st = &s.stats;
    println!(
        "acceleration: RMS {:.4} m/s^2 ({:.4} g)  peak {:.4}  crest {:.2}  kurtosis {:.2}  skewness {:.2}",
        st.rms,
        st.rms / wearsim_core::real::STANDARD_GRAVITY,
        st.peak,
        st.crest_factor,
        st.kurtosis,
        st.skewness
    );
    // A peak within the tolerance of a line is named by it; another says only what is
    // nearest (`summary::LabelledPeak::matched`).
    let line = |p: &crate::summary::LabelledPeak| {
        if p.matched {
            format!("{} ({:.2})", p.nearest, p.nearest_hz)
        } else {
            format!("- (nearest: {} at {:.2})", p.nearest, p.nearest_hz)
        }
    };
    println!("spectrum peaks (Hz, m/s^2, line):");
    for p in &s.peaks {
        println!("  {:>9.2} {:>10.4}  {}", p.freq, p.amplitude, line(p));
    }
    println!("envelope-spectrum peaks:");
    for p in s.envelope_peaks.iter().take(5) {
        println!("  {:>9.2} {:>10.4}  {}", p.freq, p.amplitude, line(p));
    }
    println!(
        "wrote {} , {} , {}",
        files.csv.display(),
        files.wav.display(),
        files.json.display()
    );
}
