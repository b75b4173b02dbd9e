//! Measurement readers and output writers.
//!
//! * [`write::write_outputs`]: atomic CSV + 32-bit float WAV + JSON sidecar output set.
//! * [`Record`]: one channel of samples with sample rate, speed, unit and provenance.
//! * [`IoError`]: every error names the file and the problem; readers never panic on bad input.
//! * [`data_dir`]: where the measured data (`/work/shared/data` layout) lives, for tests.
//! * [`read_any`]: one entry point for every reader, dispatching on the file name:
//!   [`mat::read_cwru`] (CWRU MAT v5), [`csv::read_csv`], [`wav::read_wav`], [`npy::read_npy`],
//!   [`ims::read_ims_snapshot`] (IMS raw ASCII), with sample rate and speed from the file, a
//!   JSON sidecar ([`sidecar`]) or [`ReadOptions`].
//! * [`ims::read_ims_features`]: the IMS per-snapshot feature tables.
//! * [`feature_table`]: the documented per-snapshot feature table of any run-to-failure test.

pub mod conditions;
pub mod csv;
pub mod csv_shape;
pub mod error;
pub mod feature_format;
pub mod feature_sidecar;
pub mod feature_table;
pub mod feature_table_write;
pub mod ims;
pub mod ims_life;
pub mod layout;
pub mod lock;
pub mod mat;
pub mod npy;
pub mod perms;
pub mod record;
pub mod selector;
pub mod sidecar;
pub mod space_runs;
pub mod time_column;
pub mod unique_json;
pub mod wav;
pub mod wav_decode;
pub mod write;

use std::path::{Path, PathBuf};

pub use error::IoError;
pub use ims::{read_ims_features, read_ims_snapshot, ImsFeatures};
pub use mat::{list_mat_variables, parse_cwru_name, read_cwru, CwruLabel};
pub use record::{Record, MAX_FS, MIN_FS};
pub use write::{write_outputs, OutputSet};

/// Caller's choices for [`read_any`] and the generic readers.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ReadOptions {
    /// Channel to read. CWRU `.mat`: `"DE"` (default), `"FE"`, `"BA"`. CSV: header name or
    /// zero-based column index. WAV: zero-based channel index (or the sidecar's `wav.column`).
    /// NPY: zero-based column or sidecar column name. IMS snapshot: channel number **from 1**
    /// (`"3"` or `"ch3"`; default 1).
    pub channel: Option<String>,
    /// Sample rate in Hz; overrides the file name / header / sidecar value.
    pub fs: Option<f64>,
    /// Shaft speed in rpm; overrides the file / sidecar value.
    pub rpm: Option<f64>,
}

/// Read one channel of any supported file. Text files of the IMS, FEMTO/PRONOSTIA and XJTU-SY
/// layouts are recognised by content first ([`layout::sniff_text`]); otherwise the reader is
/// chosen from the file name:
///
/// | name | reader |
/// |---|---|
/// | IMS time stamp `YYYY.MM.DD.hh.mm.ss` (also with `.txt`) | [`ims::read_ims_snapshot`] |
/// | `*.mat` | [`mat::read_mat_record`] (CWRU, MFPT, Paderborn or any MAT v5 layout) |
/// | `*.csv`, other `*.txt` | [`csv::read_csv`] |
/// | `*.wav` | [`wav::read_wav`] |
/// | `*.npy` | [`npy::read_npy`] |
///
/// Anything else is [`IoError::Unsupported`]. A file whose content does not match its extension
/// fails in the chosen reader (typically [`IoError::BadMagic`]).
pub fn read_any(path: impl AsRef<Path>, opts: &ReadOptions) -> Result<Record, IoError> {
    let path = path.as_ref();
    let name = path
        .file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    // Text layouts of the public data sets are recognised by content (IMS, FEMTO, XJTU-SY).
    if !matches!(ext.as_str(), "mat" | "wav" | "npy" | "json") {
        if let Some(l) = layout::sniff_text(path)? {
            return layout::read_layout(path, l, opts);
        }
    }
    let ims_name = name.strip_suffix(".txt").unwrap_or(&name);
    if ims::parse_ims_name(ims_name).is_some() {
        let ch = match opts.channel.as_deref() {
            None => 1,
            Some(c) => {
                let digits = c.strip_prefix("ch").unwrap_or(c);
                digits
                    .parse::<usize>()
                    .map_err(|_| IoError::UnknownChannel {
                        path: path.to_path_buf(),
                        requested: c.to_string(),
                        available: vec!["1..=N (IMS channels are numbered from 1)".into()],
                    })?
            }
        };
        let mut r = ims::read_ims_snapshot(path, ch)?;
        if let Some(fs) = opts.fs {
            r.fs = record::check_fs(path, fs)?;
        }
        if let Some(rpm) = opts.rpm {
            r.rpm = Some(record::check_rpm(path, rpm)?);
        }
        layout::set_details(&mut r, "ims", opts);
        return Ok(r);
    }
    match ext.as_str() {
        "mat" => mat::read_mat_record(path, opts),
        "csv" | "txt" => csv::read_csv(path, opts),
        "wav" => wav::read_wav(path, opts),
        "npy" => npy::read_npy(path, opts),
        "json" => Err(IoError::unsupported(
            path,
            "a .json sidecar is metadata; pass the data file (.csv/.wav/.npy) it describes",
        )),
        other => Err(IoError::unsupported(
            path,
            format!(
                "unknown file type {:?} (supported: .mat, .csv, .txt, .wav, .npy, IMS time-stamp names)",
                other
            ),
        )),
    }
}

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
    let ci = std::env::var("CI")
        .map(|v| v.eq_ignore_ascii_case("true") || v == "1")
        .unwrap_or(false);
    resolve_data_dir(std::env::var_os(DATA_ENV), ci)
}

/// The rule behind [`data_dir`] with the environment passed in: `env` is the value of
/// `WEARSIM_DATA` (unset or empty: [`default_data_dir`]), `ci` whether a missing folder is an
/// error.
pub fn resolve_data_dir(
    env: Option<std::ffi::OsString>,
    ci: bool,
) -> Result<Option<PathBuf>, IoError> {
    let dir = match env {
        Some(v) if !v.is_empty() => PathBuf::from(v),
        _ => default_data_dir(),
    };
    if dir.is_dir() {
        Ok(Some(dir))
    } else if ci {
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
