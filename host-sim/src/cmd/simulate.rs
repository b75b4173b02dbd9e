//! `wearsim simulate`: run a scenario, write CSV, WAV and the JSON sidecar, print the
//! summary (or `--json`).

use crate::cmd::args::{CliError, SimulateArgs};
use crate::{io, simulate, summary};
use serde_json::json;
use std::io::IsTerminal;

/// `wearsim simulate`.
pub fn run(a: SimulateArgs) -> Result<(), CliError> {
    let scenario = a.scenario()?;
    // Exclusive, writable output directory before any work (docs/reliability.md).
    let _lock = io::lock::DirLock::try_acquire(&a.out).map_err(CliError::input)?;
    let fs = scenario.fs();
    let show = !a.json && std::io::stderr().is_terminal();
    let bar = crate::cmd::args::Progress::new(show, "simulating");
    let out =
        simulate::run(&scenario, |done, total| bar.update(done, total)).map_err(CliError::run)?;
    bar.finish();
    let summary = summary::summarize(&out.accel, fs, &scenario.model).map_err(CliError::run)?;
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
    let meta = crate::cmd::args::run_metadata(&scenario, &a, &summary);
    // The directory was checked writable before the work: a failure now is the run's.
    let files =
        io::write::write_outputs(&a.out, "simulate", &columns, fs, &meta).map_err(CliError::run)?;
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
        crate::cmd::report::print_json(&v)?;
    } else {
        crate::cmd::args::print_summary(&scenario, &summary, rtf, &files);
    }
    Ok(())
}
