//! The command layer of `wearsim`: the command line ([`Cli`]), one module per subcommand
//! holding its handler (arguments are checked there, or by the library function they are
//! handed to), and [`exit`], the one place where an error becomes a message and an exit
//! code. `bin/wearsim.rs` only calls [`main`].

pub mod analyze;
pub mod analyze_batch;
pub mod args;
pub mod bench;
pub mod bench_lanes;
pub mod capture;
pub mod cwru_benchmark;
pub mod exit;
pub mod features;
pub mod gap;
pub mod gap_validate;
pub mod ims;
pub mod ims_ensemble;
pub mod life;
pub mod presets;
pub mod report;
pub mod simulate;
pub mod sweep;

use crate::cmd::args::CliError;
use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// The `wearsim` command line.
#[derive(Parser)]
#[command(
    name = "wearsim",
    version,
    about = "Rolling-bearing vibration over the wear life (El-Thalji 2016)"
)]
pub struct Cli {
    /// The subcommand (`simulate` when none is given).
    #[command(subcommand)]
    pub command: Option<Command>,
}

/// The subcommands.
#[derive(Subcommand)]
pub enum Command {
    /// Simulate a scenario (the built-in reference without arguments) and write CSV, WAV and a JSON sidecar.
    #[command(allow_negative_numbers = true)]
    Simulate(crate::cmd::args::SimulateArgs),
    /// Run a whole wear life: stage timeline, per-snapshot features, events (snapshot or dense mode).
    #[command(allow_negative_numbers = true)]
    Life(life::LifeArgs),
    /// Hold a simulated life against the IMS run-to-failure test 2, bearing 1.
    #[command(allow_negative_numbers = true)]
    ImsCompare(ims::ImsCompareArgs),
    /// Hold simulated lives against every failed IMS bearing: calibrate on one life, judge
    /// on the others, leave-one-life-out.
    #[command(allow_negative_numbers = true)]
    ImsValidate(ims::ImsValidateArgs),
    /// Measure the real-time factor of the reference scenario on one core.
    #[command(allow_negative_numbers = true)]
    Bench(crate::cmd::args::BenchArgs),
    /// Read a firmware sample stream (QEMU serial capture or device), check it, write outputs.
    #[command(allow_negative_numbers = true)]
    Capture(capture::CaptureArgs),
    /// Analyse a measurement: statistics, kurtogram band, envelope-spectrum fault family, zones.
    Analyze(crate::analyze::AnalyzeArgs),
    /// Turn a folder of raw run-to-failure snapshots (IMS, FEMTO, XJTU-SY) into the documented feature table + sidecar.
    #[command(allow_negative_numbers = true)]
    Features(features::FeaturesArgs),
    /// Diagnose every CWRU 12 kHz drive-end record and print the confusion matrix.
    #[command(allow_negative_numbers = true)]
    CwruBenchmark(crate::cwru_benchmark::CwruBenchmarkArgs),
    /// Diagnose the sim-to-real gap of measured records: where it lies, which candidate effect closes it, how far.
    #[command(allow_negative_numbers = true)]
    Gap(crate::gap::stationary::GapArgs),
    /// Twin experiments: withhold candidate effects from simulated "measurements" and check that the gap diagnosis names them.
    #[command(allow_negative_numbers = true)]
    GapValidate(gap_validate::GapValidateArgs),
    /// Generate a labelled data set from a sweep spec: float32 .npy shards and a Parquet index.
    #[command(allow_negative_numbers = true)]
    Sweep(sweep::SweepArgs),
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

/// Runs one subcommand.
pub fn dispatch(command: Command) -> Result<(), CliError> {
    let result = run(command);
    // A run its caller stopped ([`crate::cancel`]) is reported as such, whatever error its
    // cut-short simulations left.
    match result {
        Err(_) if crate::cancel::requested() => Err(CliError::interrupted()),
        r => r,
    }
}

/// Runs one subcommand.
fn run(command: Command) -> Result<(), CliError> {
    match command {
        Command::Simulate(a) => simulate::run(a),
        Command::Bench(a) => bench::run(a),
        Command::Capture(a) => capture::run(a).map_err(CliError::from),
        Command::Life(a) => life::life_cmd(&a),
        Command::ImsCompare(a) => ims::ims_compare_cmd(&a),
        Command::ImsValidate(a) => ims::ims_validate_cmd(&a),
        Command::Presets { json } => presets::run(json),
        Command::Gap(a) => gap::run(&a),
        Command::GapValidate(a) => gap_validate::run(&a),
        Command::Effects { json } => presets::effects(json),
        Command::Analyze(a) => analyze::run(&a),
        Command::CwruBenchmark(a) => cwru_benchmark::run(&a),
        Command::Sweep(a) => sweep::run(&a),
        Command::Features(a) => features::run(&a),
    }
}

/// Parses the command line, runs the subcommand (`simulate` with its defaults when none
/// is given), prints any error and returns the exit code ([`exit`]). The subcommand runs
/// on a worker thread ([`crate::lanes::spawn_worker`]), so that its lane groups are built
/// on one stack touched once instead of a fresh thread's each (`gap --jobs 1`: 111 400
/// minor page faults before, 20 900 after), as the Python package's calls run.
pub fn main() -> ExitCode {
    let args = match Cli::try_parse() {
        Ok(a) => a,
        Err(e) => return exit::usage(&e),
    };
    let command = args
        .command
        .unwrap_or(Command::Simulate(crate::cmd::args::SimulateArgs::default()));
    let result = std::thread::scope(|s| {
        let worker = crate::lanes::spawn_worker(s, || dispatch(command));
        match worker {
            Ok(h) => h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)),
            Err(e) => Err(CliError::run(format!("cannot start a worker thread: {e}"))),
        }
    });
    exit::finish(result)
}
