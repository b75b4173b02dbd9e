//! `wearsim cwru-benchmark`: diagnose every CWRU 12 kHz drive-end record, print the
//! confusion matrix (or `--json`), write Markdown; exit 2 when a record could not be read
//! or analysed (the report is still whole).

use crate::analysis::chain::{BandRule, Method};
use crate::cmd::args::CliError;
use crate::cmd::report::print_json;
use crate::cwru_benchmark::{
    print_report, run_benchmark_resampled, to_markdown, CwruBenchmarkArgs,
};

/// `wearsim cwru-benchmark`: locate the data, run, print (or `--json`), write Markdown.
pub fn run(args: &CwruBenchmarkArgs) -> Result<(), CliError> {
    let dir = match &args.data {
        Some(d) => d.clone(),
        None => match crate::io::data_dir().map_err(CliError::input)? {
            Some(d) => d,
            None => {
                return Err(CliError::input(format!(
                    "data folder {} not found: pass --data DIR or set {}",
                    crate::io::default_data_dir().display(),
                    crate::io::DATA_ENV
                )))
            }
        },
    };
    if let Some(r) = args
        .resample
        .filter(|r| !(r.is_finite() && (1e3..=1e6).contains(r)))
    {
        return Err(CliError::input(format!(
            "--resample {r} Hz is out of range 1000..=1e6"
        )));
    }
    // The table is written after every record is analysed: its place is checked first.
    if let Some(md) = &args.markdown {
        crate::io::perms::check_output_file("--markdown", md).map_err(CliError::input)?;
    }
    let mut method = Method::default();
    method.squared_envelope |= args.squared_envelope;
    if args.evidence_band {
        method.band_rule = BandRule::Evidence;
    }
    if args.protrugram_band {
        method.band_rule = BandRule::Protrugram;
    }
    let report = run_benchmark_resampled(&dir, &method, !args.no_variants, args.resample)
        .map_err(CliError::input)?;
    if let Some(md) = &args.markdown {
        std::fs::write(md, to_markdown(&report))
            .map_err(|e| CliError::run(format!("{}: cannot write: {e}", md.display())))?;
    }
    if args.json {
        print_json(&report)?;
    } else {
        print_report(&report);
        if let Some(md) = &args.markdown {
            println!("wrote {}", md.display());
        }
    }
    // The report is complete (an unreadable record is a row with its error, counted as
    // not correct); the exit code says that its figures are not the data's.
    let failed = report.files.iter().filter(|f| f.error.is_some()).count();
    if failed > 0 {
        return Err(CliError::input(format!(
            "{failed} of {} records could not be read or analysed (their rows hold the errors; the accuracy counts them as wrong)",
            report.files.len()
        )));
    }
    Ok(())
}
