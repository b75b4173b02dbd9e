//! Measurement readers and output writers.
//!
//! * [`write::write_outputs`]: atomic CSV + 32-bit float WAV + JSON sidecar output set.
//! * [`Record`]: one channel of samples with sample rate, speed, unit and provenance.
//! * [`IoError`]: every error names the file and the problem; readers never panic on bad input.
//! * [`data_dir`]: where the measured data (`/work/shared/data` layout) lives, for tests.

pub mod error;
pub mod mat;
pub mod record;
pub mod write;

use std::path::PathBuf;

pub use error::IoError;
pub use record::{Record, MAX_FS, MIN_FS};
pub use write::{write_outputs, OutputSet};

/// Environment variable naming the measured-data folder (the folder holding `cwru/`, `ims/`).
pub const DATA_ENV: &str = "WEARSIM_DATA";

/// Locate the measured-data folder for tests and examples.
///
/// The folder is `$WEARSIM_DATA` if that variable is set and non-empty, else
/// `<workspace root>/../shared/data` (computed from this crate's `CARGO_MANIFEST_DIR`).
///
/// * Found: `Ok(Some(dir))`.
/// * Missing and env `CI` is `true` (or `1`): `Err(IoError::DataDirMissing)`, so a test that
///   propagates it fails on CI instead of silently passing.
/// * Missing otherwise: prints `skipping: data folder <dir> not found` to stderr and returns
///   `Ok(None)`; the caller should return early.
///
/// Typical use in a test: `let Some(dir) = wearsim_host::io::data_dir()? else { return Ok(()) };`
pub fn data_dir() -> Result<Option<PathBuf>, IoError> {
    let dir = match std::env::var_os(DATA_ENV) {
        Some(v) if !v.is_empty() => PathBuf::from(v),
        _ => default_data_dir(),
    };
    if dir.is_dir() {
        return Ok(Some(dir));
    }
    let ci = std::env::var("CI")
        .map(|v| v.eq_ignore_ascii_case("true") || v == "1")
        .unwrap_or(false);
    if ci {
        Err(IoError::DataDirMissing { path: dir })
    } else {
        eprintln!("skipping: data folder {} not found", dir.display());
        Ok(None)
    }
}

/// `<workspace root>/../shared/data`, where the workspace root is the parent of this crate.
pub fn default_data_dir() -> PathBuf {
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let root = manifest.parent().map(PathBuf::from).unwrap_or(manifest);
    root.join("..").join("shared").join("data")
}
