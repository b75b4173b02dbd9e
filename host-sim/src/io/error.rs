//! The one error type of the measurement readers and output writers.
//!
//! Every variant carries the path of the file it is about (`path`), so a message such as
//! `data/x.mat: truncated: ...` can be shown to a user without further context. Readers never
//! panic on malformed input; they return one of these.

use std::path::PathBuf;

/// Error of a reader or writer in [`crate::io`]. Every variant names the file (`path`) and the
/// problem; the `Display` text starts with the file path.
#[derive(Debug, thiserror::Error)]
pub enum IoError {
    /// The operating system refused an operation (open, read, write, rename, fsync).
    #[error("{}: {op}: {source}", path.display())]
    Io {
        /// File the operation was about.
        path: PathBuf,
        /// What was being done (e.g. "open", "write", "rename").
        op: &'static str,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },

    /// The file ends before a structure it announces (header, element, row).
    #[error("{}: truncated: {detail}", path.display())]
    Truncated {
        /// File that is too short.
        path: PathBuf,
        /// What was expected where (offsets and sizes in bytes, or rows).
        detail: String,
    },

    /// The file does not start with the signature of its claimed format.
    #[error("{}: bad magic: expected {expected}, found {found}", path.display())]
    BadMagic {
        /// File with the wrong signature.
        path: PathBuf,
        /// Signature the format requires.
        expected: String,
        /// What the file holds instead (escaped).
        found: String,
    },

    /// The requested channel/column/variable does not exist in the file.
    #[error("{}: unknown channel {requested:?}; available: [{}]", path.display(), available.join(", "))]
    UnknownChannel {
        /// File that was searched.
        path: PathBuf,
        /// Channel the caller asked for.
        requested: String,
        /// Channels that the file does hold.
        available: Vec<String>,
    },

    /// A sample is NaN or infinite (or cannot be represented in the target format).
    #[error("{}: non-finite value {value} in channel {channel:?} at sample index {index}", path.display())]
    NonFinite {
        /// File holding (or meant to hold) the value.
        path: PathBuf,
        /// Channel or column name.
        channel: String,
        /// Zero-based sample index.
        index: usize,
        /// The offending value.
        value: f64,
    },

    /// A sample rate outside the plausible range [`MIN_FS`](crate::io::MIN_FS) ..=
    /// [`MAX_FS`](crate::io::MAX_FS) (1 Hz .. 10 MHz), or not a finite number.
    #[error("{}: absurd sample rate {fs} Hz (allowed 1 Hz ..= 10 MHz)", path.display())]
    AbsurdSampleRate {
        /// File that declared the rate (sidecar, header), or the data file when it came from an argument.
        path: PathBuf,
        /// The rejected rate in Hz.
        fs: f64,
    },

    /// Two pieces of information in (or about) the file disagree, e.g. a header length that
    /// exceeds the file size, a sidecar `n_samples` that differs from the data, or a WAV header
    /// rate that differs from the sidecar rate.
    #[error("{}: contradiction: {detail}", path.display())]
    Contradiction {
        /// File (or sidecar) holding the contradicting information.
        path: PathBuf,
        /// Both values and where they came from.
        detail: String,
    },

    /// The file is well-formed as far as checked but uses a format, class or layout these
    /// readers do not handle (unknown extension, complex MAT array, 64-bit float WAV, ...).
    #[error("{}: unsupported format: {detail}", path.display())]
    Unsupported {
        /// File in the unsupported format.
        path: PathBuf,
        /// What exactly is unsupported.
        detail: String,
    },

    /// Text that should be a number, a time stamp or a structure is not (CSV cell, JSON field).
    #[error("{}: malformed: {detail}", path.display())]
    Malformed {
        /// File with the malformed content.
        path: PathBuf,
        /// Where (line/column/field) and what.
        detail: String,
    },

    /// No sample rate is known: the format does not store one and neither a sidecar nor an
    /// argument gave one.
    #[error("{}: sample rate unknown: {detail}; pass `--fs HZ`, or {advice}", path.display())]
    MissingSampleRate {
        /// Data file without a known rate.
        path: PathBuf,
        /// Where the rate was looked for.
        detail: String,
        /// The other way to state the rate for this kind of file (a sidecar's `fs` for CSV,
        /// WAV and NPY; a scalar in the file for MAT, whose sidecar gives only units).
        advice: &'static str,
    },

    /// The output directory is in use by another run (see [`crate::io::lock`]).
    #[error("{}: output directory in use by another wearsim run ({owner}); wait for it to finish or choose another --out", path.display())]
    Locked {
        /// The directory.
        path: PathBuf,
        /// The lock file's content (the owner's pid), as far as readable.
        owner: String,
    },

    /// The file exceeds a documented resource bound (see `docs/reliability.md`): a sample
    /// count, a decompressed size or a buffer that would grow without bound.
    #[error("{}: too large: {what} exceeds the limit of {limit}", path.display())]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// What is too large, with its size.
        what: String,
        /// The limit, with its unit.
        limit: String,
    },

    /// The measured-data folder is missing while `CI=true` demands it (see [`crate::io::data_dir`]).
    #[error("{}: data folder not found (CI=true requires it; set WEARSIM_DATA)", path.display())]
    DataDirMissing {
        /// The folder that was looked for.
        path: PathBuf,
    },
}

/// [`IoError::MissingSampleRate`]'s advice for a file whose sidecar may give the rate.
pub const SIDECAR_FS_ADVICE: &str = "write a sidecar with `\"fs\": HZ` (`<file>.json`)";
/// [`IoError::MissingSampleRate`]'s advice for a MAT file (its sidecar is read for units only).
pub const MAT_FS_ADVICE: &str = "store the rate in the file as a numeric scalar (`fs`, `sr` or `sample_rate`, beside the signal); a MAT file's sidecar is read for its units only";

impl IoError {
    /// The file this error is about.
    pub fn path(&self) -> &std::path::Path {
        match self {
            IoError::Io { path, .. }
            | IoError::Truncated { path, .. }
            | IoError::BadMagic { path, .. }
            | IoError::UnknownChannel { path, .. }
            | IoError::NonFinite { path, .. }
            | IoError::AbsurdSampleRate { path, .. }
            | IoError::Contradiction { path, .. }
            | IoError::Unsupported { path, .. }
            | IoError::Malformed { path, .. }
            | IoError::MissingSampleRate { path, .. }
            | IoError::Locked { path, .. }
            | IoError::TooLarge { path, .. }
            | IoError::DataDirMissing { path } => path,
        }
    }

    /// Shorthand for [`IoError::Io`].
    pub(crate) fn io(path: impl Into<PathBuf>, op: &'static str, source: std::io::Error) -> Self {
        IoError::Io {
            path: path.into(),
            op,
            source,
        }
    }

    /// Shorthand for [`IoError::Truncated`].
    pub(crate) fn truncated(path: impl Into<PathBuf>, detail: impl Into<String>) -> Self {
        IoError::Truncated {
            path: path.into(),
            detail: detail.into(),
        }
    }

    /// Shorthand for [`IoError::Contradiction`].
    pub(crate) fn contradiction(path: impl Into<PathBuf>, detail: impl Into<String>) -> Self {
        IoError::Contradiction {
            path: path.into(),
            detail: detail.into(),
        }
    }

    /// Shorthand for [`IoError::Unsupported`].
    pub(crate) fn unsupported(path: impl Into<PathBuf>, detail: impl Into<String>) -> Self {
        IoError::Unsupported {
            path: path.into(),
            detail: detail.into(),
        }
    }

    /// Shorthand for [`IoError::Malformed`].
    pub(crate) fn malformed(path: impl Into<PathBuf>, detail: impl Into<String>) -> Self {
        IoError::Malformed {
            path: path.into(),
            detail: detail.into(),
        }
    }
}
