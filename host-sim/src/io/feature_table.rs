//! The documented per-snapshot feature table of a run-to-failure test (`docs/feature-tables.md`):
//! `<stem>.csv` with one row per snapshot and `<stem>.json`, its sidecar. Any rig's life can
//! be written in it (by a lab, or by `wearsim features` from raw snapshot folders) and read
//! as a [`MeasuredLife`] for `wearsim gap --life`.
//!
//! CSV columns (header row required, any order, comma-separated; cells may be quoted as
//! in RFC 4180, so a text column may hold commas):
//!
//! | column | unit | required | meaning |
//! |---|---|---|---|
//! | `snapshot` | - | yes | snapshot index, strictly increasing integer (gaps allowed) |
//! | `time_s` | s | yes | start of the snapshot since the start of the test, strictly increasing, ≥ 0 |
//! | `rms` | record unit | yes | √(mean x²), > 0 |
//! | `kurtosis` | - | yes | m4/m2² (Gaussian 3, **not** excess), ≥ 1 |
//! | `crest_factor` | - | yes | peak / rms, ≥ 1 |
//! | `skewness` | - | yes | m3/m2^1.5 |
//! | `peak` | record unit | yes | max \|x\| |
//! | `band_<lo>_<hi>_hz` | record unit | no | RMS in the band lo..hi Hz, hi ≤ sample_rate_hz / 2 |
//!
//! Other columns (and bands reaching above the Nyquist frequency) are ignored (listed in [`FeatureTable::ignored_columns`]). The writer
//! and the conversion of an IMS table are in [`super::feature_table_write`].

use std::path::{Path, PathBuf};

use serde::Serialize;

use super::error::IoError;
pub(crate) use super::feature_format::sidecar_err;
pub use super::feature_format::{
    BearingInfo, FeatureSidecar, FeatureTableError, Geometry, CREST_TOL, FAILURE_MODES, FORMAT,
    FORMAT_VERSION, INTERVAL_TOL, MAX_TABLE_BYTES, MIN_SNAPSHOTS, REQUIRED, UNITS,
};
pub(crate) use super::feature_sidecar::check_sidecar;
pub use super::feature_sidecar::{read_sidecar, SIDECAR_KEYS};
use super::ims_life::{LifePoint, MeasuredLife};

/// One snapshot row.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FeatureRow {
    /// Snapshot index.
    pub snapshot: u64,
    /// Time since the start of the test, s.
    pub time_s: f64,
    /// RMS (record unit).
    pub rms: f64,
    /// Kurtosis (Gaussian 3).
    pub kurtosis: f64,
    /// Crest factor peak / rms.
    pub crest_factor: f64,
    /// Skewness.
    pub skewness: f64,
    /// Peak max |x| (record unit).
    pub peak: f64,
}

/// A feature table with its sidecar.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FeatureTable {
    /// The CSV read (empty when built in memory).
    pub path: PathBuf,
    /// The sidecar.
    pub sidecar: FeatureSidecar,
    /// Rows, in time order.
    pub rows: Vec<FeatureRow>,
    /// Band levels `(column name, values)`, one value per row.
    pub bands: Vec<(String, Vec<f64>)>,
    /// Columns present but not part of the format.
    pub ignored_columns: Vec<String>,
}

/// The sidecar path of a table: `<stem>.json` next to `<stem>.csv`.
pub fn sidecar_path(csv: &Path) -> PathBuf {
    csv.with_extension("json")
}

/// Whether `path` is a feature table of this format: a `.csv` with a sidecar whose
/// `format` is [`FORMAT`].
pub fn is_feature_table(path: &Path) -> bool {
    let side = sidecar_path(path);
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("csv"))
        && super::sidecar::read_json(&side).is_ok_and(|v| v["format"] == FORMAT)
}

/// `text` without the UTF-8 byte order mark that spreadsheet programs (Excel's "CSV UTF-8")
/// and Windows editors put first: it is no part of the first column's name or the JSON.
pub fn without_bom(text: &str) -> &str {
    text.strip_prefix('\u{feff}').unwrap_or(text)
}

/// The non-blank records of the CSV `text`, one at a time (RFC 4180: a cell in double
/// quotes may hold commas, line breaks and `""` for a quote; quotes are no part of the
/// value), each cell trimmed. Records may differ in length; the caller checks them
/// against the header.
fn records<'a>(
    path: &'a Path,
    text: &'a str,
) -> impl Iterator<Item = Result<::csv::StringRecord, FeatureTableError>> + 'a {
    ::csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .trim(::csv::Trim::All)
        .from_reader(text.as_bytes())
        .into_records()
        .filter(|r| r.as_ref().map_or(true, |r| !r.iter().all(str::is_empty)))
        .map(move |r| r.map_err(|e| IoError::malformed(path, format!("feature table: {e}")).into()))
}

pub(crate) fn parse_band(name: &str) -> Option<(f64, f64)> {
    let rest = name.strip_prefix("band_")?.strip_suffix("_hz")?;
    let (lo, hi) = rest.split_once('_')?;
    let (lo, hi): (f64, f64) = (lo.parse().ok()?, hi.parse().ok()?);
    (lo.is_finite() && hi.is_finite() && 0.0 <= lo && lo < hi).then_some((lo, hi))
}

/// Reads `<stem>.csv` and its sidecar `<stem>.json` and checks every rule of the format:
/// required columns, finite values in range, strictly increasing `snapshot` and `time_s`,
/// at least [`MIN_SNAPSHOTS`] rows, `crest_factor` = `peak / rms` (within [`CREST_TOL`]),
/// the sidecar's ranges, `n_snapshots` = rows and the median time step within
/// [`INTERVAL_TOL`] of `snapshot_interval_s`.
pub fn read_feature_table(path: &Path) -> Result<FeatureTable, FeatureTableError> {
    let side = sidecar_path(path);
    if !side.is_file() {
        return Err(sidecar_err(
            &side,
            "format",
            format!(
                "no sidecar next to {} (a feature table is the CSV and its JSON sidecar)",
                path.display()
            ),
        ));
    }
    let sidecar = read_sidecar(&side)?;
    let bytes = super::record::read_capped(
        path,
        MAX_TABLE_BYTES,
        "feature table",
        &format!("{MAX_TABLE_BYTES} bytes per feature table"),
    )?;
    let text = String::from_utf8(bytes)
        .map_err(|e| IoError::malformed(path, format!("feature table is not UTF-8 text: {e}")))?;
    let mut lines = records(path, without_bom(&text));
    let header: Vec<String> = lines
        .next()
        .ok_or_else(|| IoError::truncated(path, "no header row"))??
        .iter()
        .map(str::to_string)
        .collect();
    for (j, h) in header.iter().enumerate() {
        if let Some(i) = header[..j].iter().position(|g| g == h) {
            return Err(FeatureTableError::DuplicateColumn {
                path: path.to_path_buf(),
                column: h.clone(),
                first: i + 1,
                second: j + 1,
            });
        }
    }
    let find = |c: &str| header.iter().position(|h| h == c);
    let mut req = [0usize; 7];
    for (k, c) in REQUIRED.iter().enumerate() {
        req[k] = find(c).ok_or_else(|| {
            // A table of another separator is one column named by the whole header.
            if header.iter().any(|h| h.contains(';')) {
                FeatureTableError::Separator {
                    path: path.to_path_buf(),
                    found: ';',
                }
            } else {
                FeatureTableError::MissingColumn {
                    path: path.to_path_buf(),
                    column: (*c).into(),
                }
            }
        })?;
    }
    // A band reaching above the Nyquist frequency holds no level the snapshots can have
    // (the band of a table at another rate): ignored, and so listed.
    let nyquist = 0.5 * sidecar.sample_rate_hz * (1.0 + 1e-9);
    let band_idx: Vec<usize> = (0..header.len())
        .filter(|i| parse_band(&header[*i]).is_some_and(|(_, hi)| hi <= nyquist))
        .collect();
    let ignored_columns: Vec<String> = header
        .iter()
        .enumerate()
        .filter(|(i, _)| !req.contains(i) && !band_idx.contains(i))
        .map(|(_, h)| h.clone())
        .collect();
    let mut rows: Vec<FeatureRow> = vec![];
    let mut bands: Vec<Vec<f64>> = vec![vec![]; band_idx.len()];
    for (r, record) in lines.enumerate() {
        let row = r + 1;
        let cells = record?;
        if cells.len() != header.len() {
            return Err(IoError::malformed(
                path,
                format!(
                    "row {row}: {} cells, the header has {}",
                    cells.len(),
                    header.len()
                ),
            )
            .into());
        }
        let num = |i: usize| -> Result<f64, FeatureTableError> {
            let c = cells.get(i).unwrap_or("");
            match c.parse::<f64>() {
                Ok(v) if v.is_finite() && (v == 0.0 || v.is_normal()) => Ok(v),
                Ok(v) if v.is_finite() => Err(FeatureTableError::BadValue {
                    path: path.to_path_buf(),
                    column: header[i].clone(),
                    row,
                    detail: format!(
                        "{v:e} is below the smallest normal number ({:e}), where its digits are lost; give the table in a unit that keeps it above that",
                        f64::MIN_POSITIVE
                    ),
                }),
                _ => Err(FeatureTableError::BadValue {
                    path: path.to_path_buf(),
                    column: header[i].clone(),
                    row,
                    detail: format!("{c:?} is not a finite number"),
                }),
            }
        };
        let v: Vec<f64> = req.iter().map(|i| num(*i)).collect::<Result<_, _>>()?;
        if v[0] < 0.0 || v[0].fract() != 0.0 || v[0] > 9.0e15 {
            return Err(FeatureTableError::BadValue {
                path: path.to_path_buf(),
                column: "snapshot".into(),
                row,
                detail: format!("{} is not a non-negative integer", v[0]),
            });
        }
        let this = FeatureRow {
            snapshot: v[0] as u64,
            time_s: v[1],
            rms: v[2],
            kurtosis: v[3],
            crest_factor: v[4],
            skewness: v[5],
            peak: v[6],
        };
        check_row(path, row, rows.last(), &this)?;
        for (b, i) in band_idx.iter().enumerate() {
            let x = num(*i)?;
            if x < 0.0 {
                return Err(FeatureTableError::BadValue {
                    path: path.to_path_buf(),
                    column: header[*i].clone(),
                    row,
                    detail: format!("{x} (a band level is ≥ 0)"),
                });
            }
            if let Some(col) = bands.get_mut(b) {
                col.push(x);
            }
        }
        rows.push(this);
    }
    if rows.len() < MIN_SNAPSHOTS {
        return Err(FeatureTableError::TooFewSnapshots {
            path: path.to_path_buf(),
            n: rows.len(),
            min: MIN_SNAPSHOTS,
        });
    }
    check_against_table(path, &side, &sidecar, &rows)?;
    Ok(FeatureTable {
        path: path.to_path_buf(),
        sidecar,
        rows,
        bands: band_idx
            .iter()
            .map(|i| header[*i].clone())
            .zip(bands)
            .collect(),
        ignored_columns,
    })
}

/// Checks one row (1-based `row`) against the format's ranges and the row before it.
fn check_row(
    path: &Path,
    row: usize,
    prev: Option<&FeatureRow>,
    r: &FeatureRow,
) -> Result<(), FeatureTableError> {
    let bad = |column: &str, detail: String| FeatureTableError::BadValue {
        path: path.to_path_buf(),
        column: column.into(),
        row,
        detail,
    };
    for (c, v) in [
        ("time_s", r.time_s),
        ("rms", r.rms),
        ("kurtosis", r.kurtosis),
        ("crest_factor", r.crest_factor),
        ("skewness", r.skewness),
        ("peak", r.peak),
    ] {
        if !v.is_finite() {
            return Err(bad(c, format!("{v} is not a finite number")));
        }
    }
    if r.time_s < 0.0 {
        return Err(bad(
            "time_s",
            format!("{} s is before the start of the test (≥ 0)", r.time_s),
        ));
    }
    for (c, v) in [("rms", r.rms), ("peak", r.peak)] {
        if v <= 0.0 {
            return Err(bad(c, format!("{v} (allowed > 0)")));
        }
    }
    if r.kurtosis < 1.0 {
        return Err(bad(
            "kurtosis",
            format!("{} (allowed ≥ 1; the format's kurtosis is m4/m2², 3 for Gaussian, not the excess kurtosis)", r.kurtosis),
        ));
    }
    if r.crest_factor < 1.0 {
        return Err(bad(
            "crest_factor",
            format!("{} (allowed ≥ 1: peak / rms)", r.crest_factor),
        ));
    }
    let ratio = r.peak / r.rms;
    if (r.crest_factor - ratio).abs() > CREST_TOL * ratio {
        return Err(bad(
            "crest_factor",
            format!(
                "{} contradicts peak / rms = {ratio} (tolerance {CREST_TOL} relative)",
                r.crest_factor
            ),
        ));
    }
    if let Some(prev) = prev {
        for (col, p, t) in [
            ("snapshot", prev.snapshot as f64, r.snapshot as f64),
            ("time_s", prev.time_s, r.time_s),
        ] {
            if t <= p {
                return Err(FeatureTableError::NonMonotonic {
                    path: path.to_path_buf(),
                    column: col.into(),
                    row,
                    prev: p,
                    value: t,
                });
            }
        }
    }
    Ok(())
}

/// Checks every row of `rows` ([`check_row`]).
pub(crate) fn check_rows(path: &Path, rows: &[FeatureRow]) -> Result<(), FeatureTableError> {
    let mut prev = None;
    for (i, r) in rows.iter().enumerate() {
        check_row(path, i + 1, prev, r)?;
        prev = Some(r);
    }
    Ok(())
}

/// Median time step between consecutive snapshots, s.
pub fn median_step(rows: &[FeatureRow]) -> f64 {
    let steps: Vec<f64> = rows.windows(2).map(|w| w[1].time_s - w[0].time_s).collect();
    crate::analysis::stats::upper_median(steps).unwrap_or(0.0)
}

/// Checks the sidecar `s` (read from `side`) against the rows of `table`: the snapshot
/// count, the interval, moments that `snapshot_samples` samples can give, and snapshots
/// that do not overlap.
pub(crate) fn check_against_table(
    table: &Path,
    side: &Path,
    s: &FeatureSidecar,
    rows: &[FeatureRow],
) -> Result<(), FeatureTableError> {
    if let Some(n) = s.n_snapshots {
        if n != rows.len() as u64 {
            return Err(sidecar_err(
                side,
                "n_snapshots",
                format!("{n}, but the table has {} rows", rows.len()),
            ));
        }
    }
    let step = median_step(rows);
    if (step - s.snapshot_interval_s).abs() > INTERVAL_TOL * s.snapshot_interval_s {
        return Err(sidecar_err(
            side,
            "snapshot_interval_s",
            format!(
                "{} s, but the median step of the time_s column is {step} s (tolerance {:.0} %)",
                s.snapshot_interval_s,
                100.0 * INTERVAL_TOL
            ),
        ));
    }
    // A standardised moment of n samples is bounded by n: kurtosis m4/m2² ≤ n and
    // |skewness| ≤ √n (equality for one sample apart from the rest; bias-corrected
    // estimators a little above, hence the margin). Past that the column is not of these
    // snapshots (a conversion error, a sum instead of a mean), however finite.
    let n = s.snapshot_samples as f64;
    for (i, r) in rows.iter().enumerate() {
        for (column, v, most) in [
            ("kurtosis", r.kurtosis, 1.01 * n + 3.0),
            ("skewness", r.skewness.abs(), 1.01 * n.sqrt() + 1.0),
        ] {
            if v > most {
                return Err(FeatureTableError::BadValue {
                    path: table.to_path_buf(),
                    column: column.into(),
                    row: i + 1,
                    detail: format!(
                        "{} is beyond what {} samples per snapshot (the sidecar's snapshot_samples) can give: at most {most:.4e}",
                        if column == "skewness" { r.skewness } else { v },
                        s.snapshot_samples
                    ),
                });
            }
        }
    }
    let length = s.snapshot_samples as f64 / s.sample_rate_hz;
    let min_gap = rows
        .windows(2)
        .map(|w| w[1].time_s - w[0].time_s)
        .fold(f64::INFINITY, f64::min);
    if min_gap < length * (1.0 - 1e-9) {
        return Err(sidecar_err(
            side,
            "snapshot_samples",
            format!(
                "{} samples at {} Hz last {length} s, longer than the shortest time step {min_gap} s of the table (snapshots would overlap)",
                s.snapshot_samples, s.sample_rate_hz
            ),
        ));
    }
    Ok(())
}

impl FeatureTable {
    /// The life of this table on its own normalised time line (time over the span from
    /// the first to the last snapshot), for `gap --life`. `bearing` is the life's number
    /// in the diagnosis (its position among the tables given); the bearing it is, is the
    /// sidecar's `bearing.id` ([`MeasuredLife::id`]).
    pub fn to_life(&self, bearing: usize) -> MeasuredLife {
        let hours: Vec<f64> = self.rows.iter().map(|r| r.time_s / 3600.0).collect();
        let h0 = hours.first().copied().unwrap_or(0.0);
        let h1 = hours.last().copied().unwrap_or(0.0);
        let points = self
            .rows
            .iter()
            .zip(&hours)
            .map(|(r, h)| LifePoint {
                t: (h - h0) / (h1 - h0),
                rms: r.rms,
                kurtosis: r.kurtosis,
                crest: r.crest_factor,
                skewness: r.skewness,
            })
            .collect();
        MeasuredLife {
            file: self.path.display().to_string(),
            bearing,
            id: self.sidecar.bearing.id.clone(),
            source: self.sidecar.source.clone(),
            points,
            hours: h1 - h0,
            dropped: 0,
            preset: self.sidecar.bearing.preset.clone(),
            failure_mode: self.sidecar.failure_mode.clone(),
            shared_shaft: false,
            ignored_columns: self.ignored_columns.clone(),
            unit: self.sidecar.unit.clone(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SIDECAR: &str = r#"{"format": "wearsim-feature-table", "format_version": 1, "source": "test",
        "bearing": {"geometry": {"elements": 13, "ball_mm": 3.5, "pitch_mm": 25.6, "angle_deg": 0.0}, "id": "b1"},
        "channel": "horiz", "unit": "g", "rpm": 1800.0, "radial_load_n": 4000.0,
        "sample_rate_hz": 25600.0, "snapshot_samples": 2560, "snapshot_interval_s": 60.0,
        "failure_mode": "outer-race"}"#;

    /// Writes `csv` with a valid sidecar into `dir` and reads it.
    fn read(dir: &Path, csv: &str) -> Result<FeatureTable, FeatureTableError> {
        let p = dir.join("t.csv");
        std::fs::write(&p, csv).unwrap();
        std::fs::write(sidecar_path(&p), SIDECAR).unwrap();
        read_feature_table(&p)
    }

    /// Ten rows of a valid table, each cell through `cell`, `extra` a last cell per row.
    fn table(header: &str, cell: impl Fn(String) -> String, extra: Option<&str>) -> String {
        let mut s = format!("{header}\n");
        for k in 0..10 {
            let cells: Vec<String> = [
                k.to_string(),
                (60 * k).to_string(),
                "0.5".into(),
                "3".into(),
                "4".into(),
                "0.1".into(),
                "2".into(),
            ]
            .into_iter()
            .map(&cell)
            .chain(extra.map(str::to_string))
            .collect();
            s.push_str(&cells.join(","));
            s.push('\n');
        }
        s
    }

    const HEADER: &str = "snapshot,time_s,rms,kurtosis,crest_factor,skewness,peak";

    /// Probe defects: quotes were stripped from the header only, so a fully quoted CSV
    /// failed, and a quoted text column holding a comma failed with a cell count. Cells
    /// are now read as RFC 4180 fields; the rows are those of the unquoted table, and
    /// the text column is an ignored column.
    #[test]
    fn quoted_cells_are_read_as_csv_fields() {
        let dir = tempfile::tempdir().unwrap();
        let plain = read(dir.path(), &table(HEADER, |c| c, None)).unwrap();
        let quoted_header = HEADER
            .split(',')
            .map(|h| format!("\"{h}\""))
            .collect::<Vec<_>>()
            .join(",");
        let quoted = read(
            dir.path(),
            &table(&quoted_header, |c| format!("\"{c}\""), None),
        )
        .unwrap();
        assert_eq!(quoted.rows, plain.rows);
        let noted = read(
            dir.path(),
            &table(
                &format!("{HEADER},note"),
                |c| c,
                Some("\"rig stopped, restarted \"\"cold\"\"\""),
            ),
        )
        .unwrap();
        assert_eq!(noted.rows, plain.rows);
        assert_eq!(noted.ignored_columns, ["note"]);
        // A row of another length is still refused, naming the row.
        let mut short = table(HEADER, |c| c, None);
        short.push_str("10,600,0.5,3,4\n");
        let e = read(dir.path(), &short).unwrap_err().to_string();
        assert!(e.contains("row 11: 5 cells, the header has 7"), "{e}");
    }

    /// Probe finding (stop 53): a band reaching above the Nyquist frequency of the
    /// sidecar's rate (`band_0_20000_hz` at 25.6 kHz) was read as a band. It is ignored and
    /// listed; a band up to Nyquist is read.
    #[test]
    fn a_band_above_nyquist_is_ignored_and_listed() {
        let dir = tempfile::tempdir().unwrap();
        let t = read(
            dir.path(),
            &table(
                &format!("{HEADER},band_0_20000_hz,band_6400_12800_hz"),
                |c| c,
                Some("0.1,0.2"),
            ),
        )
        .unwrap();
        assert_eq!(t.ignored_columns, ["band_0_20000_hz"]);
        assert_eq!(t.bands.len(), 1);
        assert_eq!(t.bands[0].0, "band_6400_12800_hz");
    }

    /// Probe defect: a `;`-separated table was refused only with "missing column
    /// `snapshot`". The separator is named; a comma table missing a column still names
    /// the column.
    #[test]
    fn a_semicolon_table_is_told_the_separator() {
        let dir = tempfile::tempdir().unwrap();
        let semi = table(HEADER, |c| c, None).replace(',', ";");
        match read(dir.path(), &semi) {
            Err(e @ FeatureTableError::Separator { found: ';', .. }) => {
                let m = e.to_string();
                assert!(m.contains("comma-separated (`,`"), "{m}");
            }
            other => panic!("expected a separator error, got {other:?}"),
        }
        let no_peak = table(HEADER, |c| c, None).replace(",peak", ",pk");
        assert!(matches!(
            read(dir.path(), &no_peak),
            Err(FeatureTableError::MissingColumn { ref column, .. }) if column == "peak"
        ));
    }
}
