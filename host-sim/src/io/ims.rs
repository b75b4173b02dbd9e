//! IMS / NASA bearing run-to-failure data (Lee, Qiu, Yu, Lin & Rexnord, 2007; NASA Ames
//! Prognostics Data Repository): raw ASCII snapshots and the third-party feature tables in
//! `shared/data/ims/` (see its README for provenance and column definitions).
//!
//! * Raw snapshot ([`read_ims_snapshot`]): a file named by its time stamp
//!   (`2004.02.12.10.32.39`, no extension) holding 20,480 rows of 4 (tests 2, 3) or 8 (test 1)
//!   tab-separated acceleration values, one 1-s snapshot "at 20 kHz" (the IMS readme also says
//!   20,480 points per second, i.e. 20.48 kHz; this reader uses 20,000 Hz and notes the ambiguity
//!   in `meta`). Shaft speed 2000 rpm (held constant). Channels are numbered **from 1** as in the
//!   IMS readme (test 1: bearing k = channels 2k-1, 2k).
//! * Feature tables ([`read_ims_features`]): the per-snapshot statistics computed by
//!   `ChoCho66/PM-NASA-Bearing-Datas-IMS` (`DatasetBearingTest_n.csv`, `testn_timefeatures.csv`)
//!   and `vaibhavmalik05/IMX_Bearing_dataset` (`Test1.csv`, `Test2.csv`, long form). All three
//!   layouts are returned in one wide form with canonical column names
//!   `B<k>[_<x|y>]_<feature>`, see [`ImsFeatures`].

use std::path::{Path, PathBuf};

use serde::Serialize;
use serde_json::json;

use super::error::IoError;
use super::record::{check_finite, Record};

/// Nominal sample rate of the raw IMS snapshots, Hz (IMS readme: "sampling rate set at 20 kHz").
pub const IMS_FS: f64 = 20_000.0;
/// Shaft speed of all IMS tests, rpm.
pub const IMS_RPM: f64 = 2000.0;
/// Rows per raw snapshot.
pub const IMS_ROWS: usize = 20_480;
/// Largest raw snapshot file accepted, bytes (real files are 0.5-1.1 MB).
pub const MAX_SNAPSHOT_BYTES: u64 = 64 << 20;

/// Time stamp of an IMS file name `YYYY.MM.DD.hh.mm.ss`, as seconds since 1970-01-01 (the
/// clock of the test rig, time zone unknown). `None` if the name has another form or is not
/// a calendar date and time ([`check_ims_name`] tells the two apart).
pub fn parse_ims_name(name: &str) -> Option<i64> {
    check_ims_name(name).ok().flatten()
}

/// Like [`parse_ims_name`], but a name of the snapshot pattern (four digits, then five
/// two-digit fields, dot-separated) that is no calendar date and time (30 February, minute
/// 70) is an error saying which field is wrong: `Ok(None)` only for names of another form.
pub fn check_ims_name(name: &str) -> Result<Option<i64>, String> {
    let Some(base) = name.rsplit(['/', '\\']).next() else {
        return Ok(None);
    };
    let parts: Vec<&str> = base.split('.').collect();
    if parts.len() != 6 {
        return Ok(None);
    }
    let mut v = [0i64; 6];
    for (i, p) in parts.iter().enumerate() {
        let want = if i == 0 { 4 } else { 2 };
        if p.len() != want || !p.bytes().all(|b| b.is_ascii_digit()) {
            return Ok(None);
        }
        v[i] = p.parse().map_err(|_| format!("{p:?} is not a number"))?;
    }
    civil_to_unix(v[0], v[1], v[2], v[3], v[4], v[5]).map(Some)
}

/// Days of month `mo` (1..=12) of year `y`, proleptic Gregorian.
fn days_in_month(y: i64, mo: i64) -> i64 {
    match mo {
        2 if (y % 4 == 0 && y % 100 != 0) || y % 400 == 0 => 29,
        2 => 28,
        4 | 6 | 9 | 11 => 30,
        _ => 31,
    }
}

/// Seconds since 1970-01-01 00:00:00 for a proleptic-Gregorian civil time; an error naming
/// the field if one is out of range (a day the month does not have, hour 24, minute 60;
/// second 60 is a leap second and allowed).
fn civil_to_unix(y: i64, mo: i64, d: i64, h: i64, mi: i64, s: i64) -> Result<i64, String> {
    if !(1..=12).contains(&mo) {
        return Err(format!("month {mo} is not 1..12"));
    }
    let dim = days_in_month(y, mo);
    if !(1..=dim).contains(&d) {
        return Err(format!("day {d}: {y}-{mo:02} has days 1..{dim}"));
    }
    if !(0..=23).contains(&h) {
        return Err(format!("hour {h} is not 0..23"));
    }
    if !(0..=59).contains(&mi) {
        return Err(format!("minute {mi} is not 0..59"));
    }
    if !(0..=60).contains(&s) {
        return Err(format!("second {s} is not 0..60"));
    }
    // Howard Hinnant's days_from_civil.
    let y = if mo <= 2 { y - 1 } else { y };
    let era = y.div_euclid(400);
    let yoe = y - era * 400;
    let mp = (mo + 9) % 12;
    let doy = (153 * mp + 2) / 5 + d - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    let days = era * 146_097 + doe - 719_468;
    Ok(days * 86_400 + h * 3600 + mi * 60 + s)
}

/// Parse `YYYY-MM-DD hh:mm:ss` (the feature tables' time stamps) to Unix seconds.
pub fn parse_feature_timestamp(s: &str) -> Option<i64> {
    let (date, time) = s.trim().split_once(' ')?;
    let d: Vec<&str> = date.split('-').collect();
    let t: Vec<&str> = time.split(':').collect();
    if d.len() != 3 || t.len() != 3 {
        return None;
    }
    let n = |x: &str| -> Option<i64> {
        if x.is_empty() || x.len() > 4 || !x.bytes().all(|b| b.is_ascii_digit()) {
            None
        } else {
            x.parse().ok()
        }
    };
    civil_to_unix(n(d[0])?, n(d[1])?, n(d[2])?, n(t[0])?, n(t[1])?, n(t[2])?).ok()
}

/// Read one channel (numbered from 1) of a raw IMS ASCII snapshot.
///
/// Every row must hold the same number of whitespace-separated numbers; the row count is
/// recorded in `meta` (`n_rows`, expected 20,480). The record has `fs` = [`IMS_FS`],
/// `rpm` = [`IMS_RPM`], unit `"unknown"` (the readme does not state it), and `meta` with the
/// time stamp from the file name.
pub fn read_ims_snapshot(path: impl AsRef<Path>, channel: usize) -> Result<Record, IoError> {
    let path = path.as_ref();
    let bytes = super::record::read_capped(
        path,
        MAX_SNAPSHOT_BYTES,
        "IMS snapshot",
        &format!("{MAX_SNAPSHOT_BYTES} bytes (an IMS snapshot is about 1 MB)"),
    )?;
    // A UTF-8 byte order mark (an editor's) is no part of the first value.
    let body = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(&bytes);
    let text = std::str::from_utf8(body)
        .map_err(|e| IoError::malformed(path, format!("not ASCII text: {e}")))?;
    let mut ncols = 0usize;
    let mut samples = Vec::with_capacity(IMS_ROWS);
    let mut rows = 0usize;
    for (lineno, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        let mut k = 0usize;
        for cell in line.split_whitespace() {
            k += 1;
            if k == channel {
                let v: f64 = cell.parse().map_err(|_| {
                    IoError::malformed(
                        path,
                        format!("line {}: {cell:?} is not a number", lineno + 1),
                    )
                })?;
                samples.push(v);
            }
        }
        if rows == 0 {
            ncols = k;
            if channel == 0 || channel > ncols {
                return Err(IoError::UnknownChannel {
                    path: path.to_path_buf(),
                    requested: channel.to_string(),
                    available: (1..=ncols).map(|c| c.to_string()).collect(),
                });
            }
        } else if k != ncols {
            return Err(IoError::malformed(
                path,
                format!(
                    "line {} has {k} columns, the first row has {ncols}",
                    lineno + 1
                ),
            ));
        }
        rows += 1;
    }
    if rows == 0 {
        return Err(IoError::truncated(path, "no data rows"));
    }
    let name = format!("ch{channel}");
    check_finite(path, &name, &samples)?;
    let file_name = path
        .file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    Ok(Record {
        samples,
        fs: IMS_FS,
        rpm: Some(IMS_RPM),
        channel: name,
        unit: "unknown".into(),
        source: path.to_path_buf(),
        bearing: None,
        meta: json!({
            "format": "ims-ascii",
            "timestamp_unix_s": parse_ims_name(&file_name),
            "n_rows": rows,
            "n_channels": ncols,
            "channel_number": channel,
            "bearing_model": "Rexnord ZA-2115",
            "fs_note": "IMS readme: 20 kHz, but also 20,480 points per 1-s snapshot (20.48 kHz)",
        }),
    })
}

/// Which feature table layout a file has.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum ImsLayout {
    /// `features_chocho66/DatasetBearingTest_n.csv`: mean(|x|) per channel (`Bearing 1x` ...).
    ChoChoMeanAbs,
    /// `features_chocho66/testn_timefeatures.csv`: 12 features per channel (`B1_x_mean` ...).
    ChoChoTimeFeatures,
    /// `features_vaibhavmalik05/TestN.csv`: long form, 4 blocks (one per bearing) of rows.
    VaibhavLong,
}

/// A feature table in wide form.
///
/// Column names are canonical: `B<k>_<feature>` (one channel per bearing) or
/// `B<k>_<x|y>_<feature>` (test 1). Features of the ChoCho tables: `mean_abs` (their `mean`,
/// which is mean(|x|)), `std`, `skew`, `kurtosis` (excess), `entropy`, `rms`, `max_abs` (their
/// `max`), `p2p`, `crest` (max/rms), `clearance` (their `clearence`), `shape`, `impulse`.
/// Features of the Vaibhav tables: `min`, `max`, `range`, `mean` (signed), `rms`, `std`
/// (ddof 1), `skew`, `kurtosis` (excess), `max_over_mean` (their "crest factor"),
/// `rms_over_mean` (their "form factor"); the `fault` label column goes to [`ImsFeatures::labels`].
#[derive(Debug, Clone, Serialize)]
pub struct ImsFeatures {
    /// The file read.
    pub source: PathBuf,
    /// Its layout.
    pub layout: ImsLayout,
    /// Snapshot time stamps as written (`2004-02-12 10:32:39`), one per row of every column.
    pub timestamps: Vec<String>,
    /// Snapshot time, Unix seconds (rig clock).
    pub unix_s: Vec<i64>,
    /// Hours since the first snapshot.
    pub hours: Vec<f64>,
    /// `(canonical name, values)`, all as long as `timestamps`.
    pub columns: Vec<(String, Vec<f64>)>,
    /// Original header name of each entry of `columns`, same order.
    pub original_names: Vec<String>,
    /// Per-channel text labels (Vaibhav `fault` column): `(B<k>[_<x|y>], labels)`.
    pub labels: Vec<(String, Vec<String>)>,
}

impl ImsFeatures {
    /// Values of the column with canonical name `name`.
    pub fn column(&self, name: &str) -> Option<&[f64]> {
        self.columns
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_slice())
    }

    /// Canonical column names, in order.
    pub fn names(&self) -> Vec<&str> {
        self.columns.iter().map(|(n, _)| n.as_str()).collect()
    }
}

fn canonical_chocho_feature(f: &str) -> String {
    match f {
        "mean" => "mean_abs".into(),
        "max" => "max_abs".into(),
        "clearence" => "clearance".into(),
        other => other.to_string(),
    }
}

fn canonical_vaibhav_feature(f: &str) -> Option<&'static str> {
    Some(match f.trim() {
        "min" => "min",
        "max" => "max",
        "range" => "range",
        "mean" => "mean",
        "RMS" => "rms",
        "standard deviation" => "std",
        "skewness" => "skew",
        "kurtosis" => "kurtosis",
        "crest factor" => "max_over_mean",
        "form factor" => "rms_over_mean",
        _ => return None,
    })
}

/// Number of bearings in every IMS test.
const IMS_BEARINGS: usize = 4;

/// Read one of the IMS feature CSVs (layout detected from the header; see [`ImsFeatures`]).
pub fn read_ims_features(path: impl AsRef<Path>) -> Result<ImsFeatures, IoError> {
    let path = path.as_ref();
    let mut rdr = ::csv::ReaderBuilder::new()
        .has_headers(false)
        .trim(::csv::Trim::All)
        .from_path(path)
        .map_err(|e| IoError::io(path, "open", std::io::Error::other(e)))?;
    let mut rows: Vec<::csv::StringRecord> = Vec::new();
    for r in rdr.records() {
        let r = r.map_err(|e| {
            let line = e.position().map(|p| p.line()).unwrap_or(0);
            IoError::malformed(path, format!("line {line}: {e}"))
        })?;
        rows.push(r);
    }
    let Some((header, body)) = rows.split_first() else {
        return Err(IoError::truncated(path, "empty file"));
    };
    if body.is_empty() {
        return Err(IoError::truncated(path, "header only, no rows"));
    }
    let h: Vec<&str> = header.iter().collect();
    let layout = if h.first() == Some(&"Timestamp") {
        ImsLayout::VaibhavLong
    } else if h.first() == Some(&"") && h.len() > 1 && h[1].starts_with("Bearing ") {
        ImsLayout::ChoChoMeanAbs
    } else if h.first() == Some(&"") && h.len() > 1 && h[1].starts_with('B') && h[1].contains('_') {
        ImsLayout::ChoChoTimeFeatures
    } else {
        return Err(IoError::unsupported(
            path,
            format!(
                "header {:?} is not one of the known IMS feature layouts (`ims-compare` and `ims-validate` read the IMS tests' tables only; a run-to-failure test of another rig enters as a documented feature table, docs/feature-tables.md, through `gap --life`){}",
                header.iter().take(4).collect::<Vec<_>>(),
                if h.first() == Some(&"snapshot") { " — this looks like such a table" } else { "" }
            ),
        ));
    };
    let cell_num = |r: &::csv::StringRecord, row: usize, c: usize| -> Result<f64, IoError> {
        let s = r.get(c).unwrap_or("");
        let v: f64 = s.parse().map_err(|_| {
            IoError::malformed(
                path,
                format!(
                    "row {}, column {:?}: {s:?} is not a number",
                    row + 2,
                    h.get(c).unwrap_or(&"?")
                ),
            )
        })?;
        if !v.is_finite() {
            return Err(IoError::NonFinite {
                path: path.to_path_buf(),
                channel: h.get(c).unwrap_or(&"?").to_string(),
                index: row,
                value: v,
            });
        }
        if v != 0.0 && !v.is_normal() {
            // A table scaled by 1e-310 gave an end ratio of 4.8e-11 (232 dB): the digits
            // of a subnormal number are gone.
            return Err(IoError::malformed(
                path,
                format!(
                    "row {}, column {:?}: {v:e} is below the smallest normal number ({:e}), where its digits are lost; give the table in a unit that keeps it above that",
                    row + 2,
                    h.get(c).unwrap_or(&"?"),
                    f64::MIN_POSITIVE
                ),
            ));
        }
        Ok(v)
    };

    let mut out = ImsFeatures {
        source: path.to_path_buf(),
        layout,
        timestamps: Vec::new(),
        unix_s: Vec::new(),
        hours: Vec::new(),
        columns: Vec::new(),
        original_names: Vec::new(),
        labels: Vec::new(),
    };
    match layout {
        ImsLayout::ChoChoMeanAbs | ImsLayout::ChoChoTimeFeatures => {
            for (c, name) in h.iter().enumerate().skip(1) {
                let canon = if layout == ImsLayout::ChoChoMeanAbs {
                    // "Bearing 1x" -> B1_x_mean_abs, "Bearing 1" -> B1_mean_abs
                    let id = name.trim_start_matches("Bearing ").trim();
                    let (num, axis) =
                        id.split_at(id.find(|ch: char| !ch.is_ascii_digit()).unwrap_or(id.len()));
                    if num.is_empty() {
                        return Err(IoError::malformed(
                            path,
                            format!("column {name:?} names no bearing"),
                        ));
                    }
                    if axis.is_empty() {
                        format!("B{num}_mean_abs")
                    } else {
                        format!("B{num}_{axis}_mean_abs")
                    }
                } else {
                    match name.rsplit_once('_') {
                        Some((chan, feat)) => format!("{chan}_{}", canonical_chocho_feature(feat)),
                        None => name.to_string(),
                    }
                };
                let mut v = Vec::with_capacity(body.len());
                for (i, r) in body.iter().enumerate() {
                    v.push(cell_num(r, i, c)?);
                }
                out.columns.push((canon, v));
                out.original_names.push(name.to_string());
            }
            out.timestamps = body
                .iter()
                .map(|r| r.get(0).unwrap_or("").to_string())
                .collect();
        }
        ImsLayout::VaibhavLong => {
            let n = body.len();
            let two = n >= 2 && body[0].get(0) == body[1].get(0);
            let cpb = if two { 2 } else { 1 };
            let per_bearing = n / IMS_BEARINGS;
            if n % (IMS_BEARINGS * cpb) != 0 {
                return Err(IoError::contradiction(
                    path,
                    format!("{n} rows cannot be {IMS_BEARINGS} bearing blocks of {cpb} channel(s)"),
                ));
            }
            let t = per_bearing / cpb;
            let ts = |i: usize| body[i].get(0).unwrap_or("");
            // Every block must carry the same time stamps (each twice in a row for x/y).
            for b in 0..IMS_BEARINGS {
                for k in 0..t {
                    for a in 0..cpb {
                        let i = b * per_bearing + k * cpb + a;
                        if ts(i) != ts(k * cpb) {
                            return Err(IoError::contradiction(
                                path,
                                format!(
                                    "row {} has time stamp {:?}, expected {:?} (bearing block {} of the long layout)",
                                    i + 2,
                                    ts(i),
                                    ts(k * cpb),
                                    b + 1
                                ),
                            ));
                        }
                    }
                }
            }
            let fault_col = h.iter().position(|c| *c == "fault");
            for b in 0..IMS_BEARINGS {
                for a in 0..cpb {
                    let chan = if cpb == 2 {
                        format!("B{}_{}", b + 1, if a == 0 { "x" } else { "y" })
                    } else {
                        format!("B{}", b + 1)
                    };
                    for (c, name) in h.iter().enumerate().skip(1) {
                        let Some(feat) = canonical_vaibhav_feature(name) else {
                            continue;
                        };
                        let mut v = Vec::with_capacity(t);
                        for k in 0..t {
                            let i = b * per_bearing + k * cpb + a;
                            v.push(cell_num(&body[i], i, c)?);
                        }
                        out.columns.push((format!("{chan}_{feat}"), v));
                        out.original_names.push(name.to_string());
                    }
                    if let Some(fc) = fault_col {
                        let labels = (0..t)
                            .map(|k| {
                                body[b * per_bearing + k * cpb + a]
                                    .get(fc)
                                    .unwrap_or("")
                                    .to_string()
                            })
                            .collect();
                        out.labels.push((chan, labels));
                    }
                }
            }
            out.timestamps = (0..t).map(|k| ts(k * cpb).to_string()).collect();
        }
    }
    // Columns are looked up by canonical name: a repeat would silently lose to the first.
    for (j, (name, _)) in out.columns.iter().enumerate() {
        if let Some(i) = out.columns[..j].iter().position(|(n, _)| n == name) {
            return Err(IoError::malformed(
                path,
                format!(
                    "columns {:?} and {:?} are both {name}; each column may appear once",
                    out.original_names[i], out.original_names[j]
                ),
            ));
        }
    }
    for (i, s) in out.timestamps.iter().enumerate() {
        let u = parse_feature_timestamp(s).ok_or_else(|| {
            IoError::malformed(
                path,
                format!("row {}: time stamp {s:?} is not YYYY-MM-DD hh:mm:ss", i + 2),
            )
        })?;
        out.unix_s.push(u);
    }
    let t0 = out.unix_s.first().copied().unwrap_or(0);
    out.hours = out
        .unix_s
        .iter()
        .map(|&u| (u - t0) as f64 / 3600.0)
        .collect();
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Probe finding (stop 53): a lab's own feature table given to `ims-compare` was
    /// refused as "not one of the known IMS feature layouts", with no word that these
    /// commands are IMS-only or of the way in for another rig.
    #[test]
    fn a_documented_feature_table_is_pointed_to_gap_life() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("t.csv");
        std::fs::write(
            &p,
            "snapshot,time_s,rms,kurtosis,crest_factor,skewness,peak
0,0,1,3,4,0,4
",
        )
        .unwrap();
        let e = read_ims_features(&p).unwrap_err().to_string();
        assert!(
            e.contains("gap --life") && e.contains("looks like such a table"),
            "{e}"
        );
    }

    #[test]
    fn names_and_timestamps() {
        let a = parse_ims_name("2004.02.12.10.32.39").unwrap();
        let b = parse_feature_timestamp("2004-02-12 10:32:39").unwrap();
        assert_eq!(a, b);
        assert_eq!(parse_feature_timestamp("1970-01-01 00:00:00"), Some(0));
        assert_eq!(
            parse_feature_timestamp("2000-03-01 00:00:00"),
            Some(951_868_800)
        );
        assert!(parse_ims_name("2004.02.12.10.32").is_none());
        assert!(parse_ims_name("2004.13.12.10.32.39").is_none());
        assert!(parse_ims_name("x.mat").is_none());
    }

    #[test]
    fn names_of_the_pattern_that_are_no_date_are_errors() {
        // 30 February used to be read as 1 March, minute 70 as no snapshot name at all.
        let e = check_ims_name("2004.02.30.11.50.39").unwrap_err();
        assert!(e.contains("day 30") && e.contains("2004-02"), "{e}");
        let e = check_ims_name("2004.02.12.11.70.39").unwrap_err();
        assert!(e.contains("minute 70"), "{e}");
        assert!(check_ims_name("2004.02.12.24.00.00").is_err());
        assert!(check_ims_name("2003.02.29.00.00.00").is_err());
        assert!(check_ims_name("2004.02.29.00.00.00").unwrap().is_some());
        assert!(check_ims_name("2000.02.29.00.00.00").unwrap().is_some());
        assert!(check_ims_name("1900.02.29.00.00.00").is_err());
        assert_eq!(check_ims_name("2004.02.12.11.50").unwrap(), None);
        assert_eq!(check_ims_name("acc_00001.csv").unwrap(), None);
        assert!(parse_ims_name("2004.02.30.11.50.39").is_none());
        assert!(parse_feature_timestamp("2004-02-30 11:50:39").is_none());
    }

    #[test]
    fn snapshot_written_by_test() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("2004.02.12.10.32.39");
        let mut text = String::new();
        let mut ch3 = Vec::new();
        for i in 0..IMS_ROWS {
            let v = ((i % 97) as f64 - 48.0) * 0.001;
            ch3.push(v);
            text.push_str(&format!("{:.3}\t{:.3}\t{v}\t{:.3}\r\n", -0.1, 0.2, 0.05));
        }
        std::fs::write(&p, &text).unwrap();
        let r = read_ims_snapshot(&p, 3).unwrap();
        assert_eq!(r.samples, ch3);
        assert_eq!(
            (r.fs, r.rpm, r.channel.as_str()),
            (IMS_FS, Some(IMS_RPM), "ch3")
        );
        assert_eq!(r.meta["n_rows"], json!(IMS_ROWS));
        assert_eq!(
            r.meta["timestamp_unix_s"],
            json!(parse_feature_timestamp("2004-02-12 10:32:39").unwrap())
        );
        for bad in [0, 5] {
            match read_ims_snapshot(&p, bad).unwrap_err() {
                IoError::UnknownChannel { available, .. } => {
                    assert_eq!(available, vec!["1", "2", "3", "4"])
                }
                e => panic!("{e:?}"),
            }
        }
        std::fs::write(&p, "1\t2\n3\n").unwrap();
        assert!(matches!(
            read_ims_snapshot(&p, 1),
            Err(IoError::Malformed { .. })
        ));
        std::fs::write(&p, "1\t2\nnan\t3\n").unwrap();
        assert!(matches!(
            read_ims_snapshot(&p, 1),
            Err(IoError::NonFinite { index: 1, .. })
        ));
        std::fs::write(&p, "").unwrap();
        assert!(matches!(
            read_ims_snapshot(&p, 1),
            Err(IoError::Truncated { .. })
        ));
        std::fs::write(&p, [0xff, 0xfe, 0x00]).unwrap();
        assert!(read_ims_snapshot(&p, 1).is_err());
    }

    #[test]
    fn synthetic_long_layout() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("Test1.csv");
        let mut s = String::from("Timestamp,min,max,range,mean,RMS,standard deviation,skewness,kurtosis,crest factor,form factor,fault\n");
        for b in 0..4 {
            for t in 0..3 {
                for a in 0..2 {
                    let rms = (b * 100 + t * 10 + a) as f64;
                    s.push_str(&format!(
                        "2003-10-22 12:0{t}:00,-1,1,2,0,{rms},1,0,0,1,1,normal\n"
                    ));
                }
            }
        }
        std::fs::write(&p, &s).unwrap();
        let f = read_ims_features(&p).unwrap();
        assert_eq!(f.layout, ImsLayout::VaibhavLong);
        assert_eq!(f.timestamps.len(), 3);
        assert_eq!(f.column("B3_y_rms").unwrap(), &[201.0, 211.0, 221.0]);
        assert_eq!(f.hours, vec![0.0, 1.0 / 60.0, 2.0 / 60.0]);
        assert_eq!(f.labels.len(), 8);
        // Broken block structure.
        std::fs::write(&p, s.replacen("12:01:00", "12:05:00", 1)).unwrap();
        assert!(matches!(
            read_ims_features(&p),
            Err(IoError::Contradiction { .. })
        ));
        // A repeated feature column is refused rather than the first one taken.
        std::fs::write(&p, s.replacen("form factor", "RMS", 1)).unwrap();
        let e = read_ims_features(&p).unwrap_err().to_string();
        assert!(e.contains("both B1_x_rms"), "{e}");
    }

    #[test]
    fn real_feature_tables() -> Result<(), IoError> {
        let Some(dir) = crate::io::data_dir()? else {
            return Ok(());
        };
        let ims = dir.join("ims");
        let t2 = read_ims_features(ims.join("features_chocho66/test2_timefeatures.csv"))?;
        assert_eq!(t2.layout, ImsLayout::ChoChoTimeFeatures);
        assert_eq!(t2.timestamps.len(), 984);
        assert_eq!(t2.columns.len(), 48);
        assert!(t2.column("B1_kurtosis").is_some() && t2.column("B4_clearance").is_some());
        assert_eq!(t2.timestamps[0], "2004-02-12 10:32:39");
        let t1 = read_ims_features(ims.join("features_chocho66/test1_timefeatures.csv"))?;
        assert_eq!((t1.timestamps.len(), t1.columns.len()), (2156, 96));
        assert!(t1.column("B3_y_rms").is_some());
        for (n, rows, cols) in [(1, 2156, 8), (2, 984, 4), (3, 6324, 4)] {
            let f = read_ims_features(
                ims.join(format!("features_chocho66/DatasetBearingTest_{n}.csv")),
            )?;
            assert_eq!(f.layout, ImsLayout::ChoChoMeanAbs);
            assert_eq!(
                (f.timestamps.len(), f.columns.len()),
                (rows, cols),
                "test {n}"
            );
        }
        let v2 = read_ims_features(ims.join("features_vaibhavmalik05/Test2.csv"))?;
        assert_eq!(v2.timestamps, t2.timestamps);
        // README: Vaibhav RMS agrees with ChoCho rms within 1.3e-4 on every row.
        for b in 1..=4 {
            let a = v2.column(&format!("B{b}_rms")).unwrap();
            let c = t2.column(&format!("B{b}_rms")).unwrap();
            assert!(
                a.iter().zip(c).all(|(x, y)| (x - y).abs() < 2e-4),
                "bearing {b}"
            );
        }
        let v1 = read_ims_features(ims.join("features_vaibhavmalik05/Test1.csv"))?;
        assert_eq!(v1.timestamps, t1.timestamps);
        for ch in ["B1_x", "B3_y", "B4_x"] {
            let a = v1.column(&format!("{ch}_rms")).unwrap();
            let c = t1.column(&format!("{ch}_rms")).unwrap();
            assert!(a.iter().zip(c).all(|(x, y)| (x - y).abs() < 2e-4), "{ch}");
        }
        let hrs = *v1.hours.last().unwrap();
        assert!(hrs > 24.0 * 30.0 && hrs < 24.0 * 40.0, "{hrs}");
        Ok(())
    }
}
