//! `wearsim analyze`: read, analyse, print (or `--json`), plot.

use crate::analyze::{analyze, print_analysis, AnalyzeArgs};
use crate::cmd::args::CliError;
use crate::cmd::report::print_json;

/// `wearsim analyze`: read, analyse, print (or `--json`), plot.
pub fn run(args: &AnalyzeArgs) -> Result<(), CliError> {
    if super::analyze_batch::is_batch(args) {
        return super::analyze_batch::run(args);
    }
    // Exclusive, writable plot directory before any work (docs/reliability.md).
    let _lock = match &args.plot {
        Some(dir) => Some(crate::io::lock::DirLock::try_acquire(dir).map_err(CliError::input)?),
        None => None,
    };
    let (a, spectra) = analyze(args)?;
    let plots = match &args.plot {
        Some(dir) => crate::plot::write_all(dir, &a, &spectra)?,
        None => vec![],
    };
    if args.json {
        let mut v = serde_json::to_value(&a).map_err(CliError::run)?;
        if let Some(obj) = v.as_object_mut() {
            obj.insert("plots".into(), serde_json::json!(plots));
        }
        print_json(&v)?;
    } else {
        print_analysis(&a);
        for p in &plots {
            println!("wrote {}", p.display());
        }
    }
    Ok(())
}
