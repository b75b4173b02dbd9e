//! Plots of `wearsim analyze` (stub).
use crate::analyze::{Analysis, Spectra};
use crate::cli::CliError;
use std::path::{Path, PathBuf};

/// Write every plot into `dir`; returns the files written.
pub fn write_all(_dir: &Path, _a: &Analysis, _s: &Spectra) -> Result<Vec<PathBuf>, CliError> {
    Ok(vec![])
}
