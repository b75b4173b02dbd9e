//! `wearsim bench`: the real-time factor of the reference scenario on one core.

use crate::cmd::args::{BenchArgs, CliError};

/// `wearsim bench`.
pub fn run(a: BenchArgs) -> Result<(), CliError> {
    if let Some(k) = a.lanes {
        return super::bench_lanes::run(&a, k);
    }
    let report = crate::cmd::args::bench(&a)?;
    if a.json {
        crate::cmd::report::print_json(&report)?;
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
