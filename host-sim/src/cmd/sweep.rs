//! `wearsim sweep SPEC.toml --out DATASET`: a labelled data set from a declarative sweep
//! (see [`crate::sweep`] and docs/datasets.md).

use crate::cmd::args::CliError;
use crate::sweep::{self, SweepError, SweepSpec};
use std::io::IsTerminal;
use std::path::PathBuf;

/// `wearsim sweep` arguments.
#[derive(Debug, Clone, clap::Args)]
pub struct SweepArgs {
    /// Sweep specification (TOML; see docs/datasets.md).
    pub spec: PathBuf,
    /// Output directory of the data set (new, empty, or holding this same sweep to resume).
    #[arg(long)]
    pub out: PathBuf,
    /// Generate only part I of N (0-based; shards with index mod N == I), e.g. a Slurm
    /// array task: `--shard $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT`.
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,
    /// Worker threads, 1 ..= 256; default every local core.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Print the report as JSON on stdout (no progress bar).
    #[arg(long)]
    pub json: bool,
}

impl From<SweepError> for CliError {
    fn from(e: SweepError) -> Self {
        match e {
            SweepError::Input(m) => CliError::input(m),
            SweepError::Run(m) => CliError::run(m),
            e @ SweepError::Cancelled => CliError::run(e.to_string()),
        }
    }
}

/// Parses `I/N` (0 <= I < N).
pub fn parse_part(s: &str) -> Result<(u64, u64), CliError> {
    let bad = || {
        CliError::input(format!(
            "--shard {s}: expected I/N with 0 <= I < N (e.g. 3/16)"
        ))
    };
    let (i, n) = s.split_once('/').ok_or_else(bad)?;
    let i: u64 = i.trim().parse().map_err(|_| bad())?;
    let n: u64 = n.trim().parse().map_err(|_| bad())?;
    if n == 0 || i >= n {
        return Err(bad());
    }
    Ok((i, n))
}

/// `wearsim sweep`.
pub fn run(a: &SweepArgs) -> Result<(), CliError> {
    let text = crate::config::read_config_text(&a.spec).map_err(|e| match e {
        crate::config::ConfigFileError::Read { source, .. } => {
            CliError::input(format!("cannot read {}: {source}", a.spec.display()))
        }
        other => CliError::input(other),
    })?;
    let spec = SweepSpec::parse(&text, &a.spec.display().to_string()).map_err(CliError::input)?;
    let part = a.shard.as_deref().map(parse_part).transpose()?;
    let threads = crate::lanes::workers("--threads", a.threads).map_err(CliError::input)?;
    let shards = sweep::shard_set(&spec, part);
    let show = !a.json && std::io::stderr().is_terminal();
    let bar = crate::cmd::args::Progress::new(show, "sweep (shards)");
    let report = sweep::run(&spec, &a.out, &shards, threads, &|d, t| bar.update(d, t))?;
    bar.finish();
    if a.json {
        crate::cmd::report::print_json(&report)?;
    } else {
        println!(
            "{}: {} records in {} shards generated, {} shards already complete; {:.1} s of signal in {:.2} s wall on {} threads ({:.1} simulated s per core-second)",
            a.out.display(),
            report.records_generated,
            report.shards_written,
            report.shards_skipped,
            report.simulated_s,
            report.wall_s,
            report.threads,
            report.simulated_s / (report.wall_s * report.threads as f64).max(1e-12)
        );
        if report.complete {
            println!(
                "data set complete: index.parquet, manifest.json ({} bytes)",
                report.bytes
            );
        } else {
            println!("data set not complete yet (other shards pending); run again or run the other parts");
        }
    }
    Ok(())
}
