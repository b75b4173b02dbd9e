//! The `wearsim` command: simulate scenarios, benchmark the model, list presets.
//! Exit codes: 0 success, 1 run failure, 2 bad input (arguments, configuration, files).

use clap::{Parser, Subcommand};
use serde_json::json;
use std::io::IsTerminal;
use std::process::ExitCode;
use wearsim_host::simulate;
use wearsim_host::summary::{self, KinematicFrequencies};
use wearsim_host::{cli, io};

#[derive(Parser)]
#[command(
    name = "wearsim",
    version,
    about = "Rolling-bearing vibration over the wear life (El-Thalji 2016)"
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Simulate a scenario (the built-in reference without arguments) and write CSV, WAV and a JSON sidecar.
    #[command(allow_negative_numbers = true)]
    Simulate(cli::SimulateArgs),
    /// Run a whole wear life: stage timeline, per-snapshot features, events (snapshot or dense mode).
    #[command(allow_negative_numbers = true)]
    Life(wearsim_host::life::cli::LifeArgs),
    /// Hold a simulated life against the IMS run-to-failure test 2, bearing 1.
    ImsCompare(wearsim_host::life::cli::ImsCompareArgs),
    /// Measure the real-time factor of the reference scenario on one core.
    Bench(cli::BenchArgs),
    /// Read a firmware sample stream (QEMU serial capture or device), check it, write outputs.
    Capture(wearsim_host::capture::CaptureArgs),
    /// Analyse a measurement: statistics, kurtogram band, envelope-spectrum fault family, zones.
    Analyze(wearsim_host::analyze::AnalyzeArgs),
    /// Diagnose every CWRU 12 kHz drive-end record and print the confusion matrix.
    CwruBenchmark(wearsim_host::cwru_benchmark::CwruBenchmarkArgs),
    /// Diagnose the sim-to-real gap of measured records: where it lies, which candidate effect closes it, how far.
    #[command(allow_negative_numbers = true)]
    Gap(wearsim_host::gap::cli::GapArgs),
    /// Twin experiments: withhold candidate effects from simulated "measurements" and check that the gap diagnosis names them.
    GapValidate(wearsim_host::gap::validate_cli::GapValidateArgs),
    /// List the candidate effects (sim-to-real) with their parameters, units, defaults and bounds.
    Effects {
        /// Machine-readable output.
        #[arg(long)]
        json: bool,
    },
    /// List the presets with their derived frequencies.
    Presets {
        /// Machine-readable output.
        #[arg(long)]
        json: bool,
    },
}

fn main() -> ExitCode {
    // Like other Unix filters, end quietly when the reader of our output goes away
    // (`wearsim … | head`) instead of failing a write to a closed pipe.
    #[cfg(unix)]
    // SAFETY: restoring the default disposition of SIGPIPE before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let args = match Cli::try_parse() {
        Ok(a) => a,
        Err(e) => {
            let code = if e.use_stderr() { 2 } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    let result = match args
        .command
        .unwrap_or(Command::Simulate(cli::SimulateArgs::default()))
    {
        Command::Simulate(a) => simulate_cmd(a),
        Command::Bench(a) => bench_cmd(a),
        Command::Capture(a) => wearsim_host::capture::run(a),
        Command::Life(a) => wearsim_host::life::cli::life_cmd(&a),
        Command::ImsCompare(a) => wearsim_host::life::cli::ims_compare_cmd(&a),
        Command::Presets { json } => presets_cmd(json),
        Command::Gap(a) => wearsim_host::gap::cli::run(&a),
        Command::GapValidate(a) => wearsim_host::gap::validate_cli::run(&a),
        Command::Effects { json } => {
            if json {
                println!(
                    "{}",
                    serde_json::to_string_pretty(&wearsim_host::effects::catalogue_json())
                        .unwrap_or_default()
                );
            } else {
                print!("{}", wearsim_host::effects::catalogue_text());
            }
            Ok(())
        }
        Command::Analyze(a) => wearsim_host::analyze::run(&a),
        Command::CwruBenchmark(a) => wearsim_host::cwru_benchmark::run(&a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(cli::CliError { code, message }) => {
            eprintln!("wearsim: error: {message}");
            ExitCode::from(code)
        }
    }
}

fn simulate_cmd(a: cli::SimulateArgs) -> Result<(), cli::CliError> {
    let scenario = a.scenario()?;
    // Exclusive, writable output directory before any work (docs/reliability.md).
    let _lock = io::lock::DirLock::try_acquire(&a.out).map_err(cli::CliError::input)?;
    let fs = scenario.fs();
    let show = !a.json && std::io::stderr().is_terminal();
    let bar = cli::Progress::new(show, "simulating");
    let out = simulate::run(&scenario, |done, total| bar.update(done, total))
        .map_err(cli::CliError::run)?;
    bar.finish();
    let summary =
        summary::summarize(&out.accel, fs, &scenario.model).map_err(cli::CliError::run)?;
    let g: Vec<f64> = out
        .accel
        .iter()
        .map(|x| x / wearsim_core::real::STANDARD_GRAVITY)
        .collect();
    let mut columns: Vec<(&str, &[f64])> = vec![("accel_m_s2", &out.accel), ("accel_g", &g)];
    if let (Some(v), Some(d)) = (&out.vel, &out.disp) {
        columns.push(("vel_m_s", v));
        columns.push(("disp_m", d));
    }
    let meta = cli::run_metadata(&scenario, &a, &summary);
    let files = io::write::write_outputs(&a.out, "simulate", &columns, fs, &meta)
        .map_err(cli::CliError::input)?;
    let rtf = scenario.run.duration / out.wall_s.max(1e-12);
    if a.json {
        let v = json!({
            "files": {"csv": files.csv, "wav": files.wav, "json": files.json},
            "fs": fs,
            "duration_s": scenario.run.duration,
            "seed": scenario.run.seed,
            "preset": scenario.run.preset,
            "summary": summary,
            "rtf": rtf,
        });
        println!("{}", serde_json::to_string_pretty(&v).unwrap_or_default());
    } else {
        cli::print_summary(&scenario, &summary, rtf, &files);
    }
    Ok(())
}

fn bench_cmd(a: cli::BenchArgs) -> Result<(), cli::CliError> {
    let report = cli::bench(&a)?;
    if a.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&report).unwrap_or_default()
        );
    } else {
        println!(
            "{}: {:.1} s simulated at fs = {} Hz (oversample {}, {} integrator) in {:.3} s wall",
            report.preset,
            report.simulated_s,
            report.fs,
            report.oversample,
            report.integrator,
            report.wall_s
        );
        println!(
            "real-time factor: {:.1} x   ({:.1} ns per internal step, one core)",
            report.rtf, report.ns_per_step
        );
    }
    Ok(())
}

fn presets_cmd(json: bool) -> Result<(), cli::CliError> {
    let mut rows = vec![];
    for name in wearsim_core::presets::NAMES {
        let Some(cfg) = wearsim_core::presets::by_name(name) else {
            continue;
        };
        let model = wearsim_core::Model::new_checked(cfg.clone())
            .map_err(|e| cli::CliError::run(format!("preset {name}: {e}")))?;
        let k = KinematicFrequencies::of(&model);
        let o = model.orders();
        rows.push(json!({
            "name": name,
            "description": cli::preset_description(name),
            "elements": cfg.bearing.elements,
            "element_diameter_m": cfg.bearing.element_diameter,
            "pitch_diameter_m": cfg.bearing.pitch_diameter,
            "contact_angle_deg": cfg.bearing.contact_angle.to_degrees(),
            "shaft_hz": k.shaft,
            "orders": {"ftf": o.ftf, "bpfo": o.bpfo, "bpfi": o.bpfi, "bsf": o.bsf},
            "hz": {"ftf": k.ftf, "bpfo": k.bpfo, "bpfi": k.bpfi, "bsf": k.bsf, "waviness": k.waviness},
            "natural_hz": k.natural,
            "damping_ratio": model.damping_ratio(),
            "fs": cfg.output_rate,
            "oversample": model.oversample(),
        }));
    }
    if json {
        println!(
            "{}",
            serde_json::to_string_pretty(&rows).unwrap_or_default()
        );
        return Ok(());
    }
    println!(
        "{:<18} {:>3} {:>8} {:>8} {:>6} {:>8} {:>8} {:>8} {:>8} {:>8} {:>9} {:>7}",
        "preset",
        "N",
        "Bd mm",
        "P mm",
        "deg",
        "1x Hz",
        "FTF",
        "BPFO",
        "BPFI",
        "BSF",
        "fn Hz",
        "zeta"
    );
    for r in &rows {
        println!(
            "{:<18} {:>3} {:>8.3} {:>8.2} {:>6.2} {:>8.2} {:>8.2} {:>8.2} {:>8.2} {:>8.2} {:>9.1} {:>7.3}",
            r["name"].as_str().unwrap_or(""),
            r["elements"],
            r["element_diameter_m"].as_f64().unwrap_or(0.0) * 1e3,
            r["pitch_diameter_m"].as_f64().unwrap_or(0.0) * 1e3,
            r["contact_angle_deg"].as_f64().unwrap_or(0.0),
            r["shaft_hz"].as_f64().unwrap_or(0.0),
            r["hz"]["ftf"].as_f64().unwrap_or(0.0),
            r["hz"]["bpfo"].as_f64().unwrap_or(0.0),
            r["hz"]["bpfi"].as_f64().unwrap_or(0.0),
            r["hz"]["bsf"].as_f64().unwrap_or(0.0),
            r["natural_hz"].as_f64().unwrap_or(0.0),
            r["damping_ratio"].as_f64().unwrap_or(0.0),
        );
    }
    for r in &rows {
        println!(
            "  {}: {}",
            r["name"].as_str().unwrap_or(""),
            r["description"].as_str().unwrap_or("")
        );
    }
    Ok(())
}
