//! The shared definitions of the feature-table format (`docs/feature-tables.md`): its
//! constants, the sidecar's types and the error type, used by the table's reader
//! ([`super::feature_table`], which re-exports them) and the sidecar's
//! ([`super::feature_sidecar`]) without either importing the other's.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::error::IoError;
/// Value of the sidecar key `format`.
pub const FORMAT: &str = "wearsim-feature-table";
/// Value of the sidecar key `format_version`.
pub const FORMAT_VERSION: u64 = 1;
/// Fewest snapshots of a table (a life needs a time line; `gap --life` needs far more,
/// at least 3 in each of its stages).
pub const MIN_SNAPSHOTS: usize = 10;
/// Required CSV columns, in the order [`super::feature_table_write::write_feature_table`] writes them.
pub const REQUIRED: [&str; 7] = [
    "snapshot",
    "time_s",
    "rms",
    "kurtosis",
    "crest_factor",
    "skewness",
    "peak",
];
/// Largest table accepted, bytes (a 10⁵-snapshot life with bands is about 20 MB).
pub const MAX_TABLE_BYTES: u64 = 256 << 20;
/// Relative tolerance of `crest_factor` against `peak / rms`.
pub const CREST_TOL: f64 = 1e-3;
/// Relative tolerance of the median time step against `snapshot_interval_s`.
pub const INTERVAL_TOL: f64 = 0.1;
/// Failure modes a sidecar may name.
pub const FAILURE_MODES: [&str; 6] = [
    "outer-race",
    "inner-race",
    "rolling-element",
    "cage",
    "none",
    "unknown",
];

/// Units a sidecar's `unit` may name. `gap --life` compares RMS only as a ratio to each
/// life's own steady level, so lives in different units compare as they are.
pub const UNITS: [&str; 3] = ["g", "m/s^2", "unknown"];

/// Rolling-element bearing geometry of a sidecar without a preset: the keys of a record
/// sidecar's `bearing_geometry` object ([`crate::geometry::GeometrySpec`]; mm, degrees).
/// Unknown keys are refused ([`super::feature_sidecar::SIDECAR_KEYS`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Geometry {
    /// Rolling elements per row (3..=32, fitting on the pitch circle: the limits of
    /// [`crate::geometry::GeometrySpec::checked`]).
    pub elements: u32,
    /// Rolling-element diameter, mm.
    pub ball_mm: f64,
    /// Pitch diameter, mm.
    pub pitch_mm: f64,
    /// Contact angle, degrees.
    pub angle_deg: f64,
}

/// Which bearing the table describes: a wearsim preset and/or its geometry, its position.
/// Unknown keys are refused ([`super::feature_sidecar::SIDECAR_KEYS`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BearingInfo {
    /// wearsim preset (`wearsim presets`), e.g. `ims-za2115`; required by `gap --life`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preset: Option<String>,
    /// Geometry, when there is no preset.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub geometry: Option<Geometry>,
    /// Which bearing of the rig (free text, e.g. `test 2 bearing 1`).
    pub id: String,
}

/// The JSON sidecar of a feature table (keys as in `docs/feature-tables.md`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FeatureSidecar {
    /// [`FORMAT`].
    pub format: String,
    /// [`FORMAT_VERSION`].
    pub format_version: u64,
    /// Where the data come from (data set, test, URL).
    pub source: String,
    /// The bearing.
    pub bearing: BearingInfo,
    /// Channel the statistics were computed on.
    pub channel: String,
    /// Unit of `rms`, `peak` and band levels (`g`, `m/s^2`, `unknown`).
    pub unit: String,
    /// Shaft speed, rpm (> 0).
    pub rpm: f64,
    /// Radial load on the bearing, N (≥ 0).
    pub radial_load_n: f64,
    /// Sample rate of the raw snapshots, Hz.
    pub sample_rate_hz: f64,
    /// Samples per snapshot.
    pub snapshot_samples: u64,
    /// Nominal time between snapshot starts, s.
    pub snapshot_interval_s: f64,
    /// Failure mode if known, one of [`FAILURE_MODES`].
    pub failure_mode: String,
    /// Rows of the CSV (optional; checked when given).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub n_snapshots: Option<u64>,
    /// Free notes (how dead snapshots were handled, ...).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
}

/// Why a feature table was refused. Every variant names the file and the field.
#[derive(Debug, thiserror::Error)]
pub enum FeatureTableError {
    /// Reading the file failed, or the sidecar is missing.
    #[error(transparent)]
    Io(#[from] IoError),
    /// A required CSV column is absent.
    #[error("{}: missing column `{column}` (required: {})", path.display(), REQUIRED.join(", "))]
    MissingColumn {
        /// The CSV.
        path: PathBuf,
        /// The column.
        column: String,
    },
    /// The header holds another separator than `,` (a spreadsheet of a decimal-comma
    /// locale writes `;`), so no required column is found.
    #[error("{}: the header is separated by `{found}`; a feature table is comma-separated (`,` between cells, `.` as the decimal point): export it with `,` as the separator", path.display())]
    Separator {
        /// The CSV.
        path: PathBuf,
        /// The separator seen.
        found: char,
    },
    /// A column name appears more than once in the header: which one a reader would take
    /// is not defined, so the table is refused.
    #[error("{}: column `{column}` appears more than once in the header (columns {first} and {second}); each column may appear once", path.display())]
    DuplicateColumn {
        /// The CSV.
        path: PathBuf,
        /// The repeated name.
        column: String,
        /// 1-based position of its first occurrence.
        first: usize,
        /// 1-based position of the repeat.
        second: usize,
    },
    /// A cell is not a finite number (or out of its allowed range).
    #[error("{}: column `{column}`, row {row}: {detail}", path.display())]
    BadValue {
        /// The CSV.
        path: PathBuf,
        /// The column.
        column: String,
        /// 1-based data row.
        row: usize,
        /// The value and its allowed range.
        detail: String,
    },
    /// `time_s` or `snapshot` does not strictly increase.
    #[error("{}: column `{column}` is not strictly increasing: row {row} holds {value} after {prev}", path.display())]
    NonMonotonic {
        /// The CSV.
        path: PathBuf,
        /// `time_s` or `snapshot`.
        column: String,
        /// 1-based data row.
        row: usize,
        /// Previous value.
        prev: f64,
        /// This value.
        value: f64,
    },
    /// Fewer rows than [`MIN_SNAPSHOTS`].
    #[error("{}: {n} snapshots; a life needs at least {min}", path.display())]
    TooFewSnapshots {
        /// The CSV.
        path: PathBuf,
        /// Rows found.
        n: usize,
        /// [`MIN_SNAPSHOTS`].
        min: usize,
    },
    /// A sidecar field is missing, malformed, out of range, or contradicts the table.
    #[error("{}: sidecar field `{field}`: {detail}", path.display())]
    Sidecar {
        /// The sidecar.
        path: PathBuf,
        /// The field (`rpm`, `snapshot_interval_s`, ...).
        field: String,
        /// Value, allowed range or the contradiction.
        detail: String,
    },
}

/// A [`FeatureTableError::Sidecar`] of sidecar `path` naming `field`.
pub(crate) fn sidecar_err(
    path: &Path,
    field: &str,
    detail: impl Into<String>,
) -> FeatureTableError {
    FeatureTableError::Sidecar {
        path: path.to_path_buf(),
        field: field.into(),
        detail: detail.into(),
    }
}
