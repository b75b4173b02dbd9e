//! Atomic writer of a simulation (or processed measurement) output set: CSV + WAV + JSON sidecar.
//!
//! [`write_outputs`] writes, in directory `dir`:
//!
//! * `<stem>.csv`: header `time_s,<name1>,<name2>,...`, one row per sample, `time_s = i / fs`;
//!   every number in shortest round-trip form (`ryu`), so parsing the text gives back the exact
//!   `f64` bits.
//! * `<stem>.wav`: RIFF/WAVE, mono, 32-bit IEEE float (`WAVE_FORMAT_IEEE_FLOAT`), the **first**
//!   column in its physical unit (not normalised; values beyond ±1 are legal in float WAV), the
//!   sample rate rounded to an integer Hz (the exact rate is in the sidecar).
//! * `<stem>.json`: the sidecar, see [`SIDECAR_FORMAT`] for its keys. It is written last and holds
//!   `"complete": true`, so a set with a sidecar is a complete set.
//!
//! Atomicity: each file is written to a temporary file in `dir` (`.<stem>.*.tmp`), flushed and
//! fsynced; only after all three succeeded is any old `<stem>.json` removed and the three renamed
//! into place (CSV, WAV, then JSON), followed by an fsync of the directory. On any error the
//! temporary files are removed, so nothing is left that looks complete.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use serde_json::{json, Map, Value};

use super::error::IoError;
use super::record::check_fs;

/// Value of the sidecar key `"format"` written by [`write_outputs`].
///
/// Sidecar keys (all written by [`write_outputs`]; readers accept any subset, see
/// [`crate::io::sidecar`]):
///
/// | key | type | meaning |
/// |---|---|---|
/// | `format` | string | `"wearsim-output"` |
/// | `format_version` | integer | `1` |
/// | `fs` | number | sample rate, Hz (exact) |
/// | `n_samples` | integer | rows of the CSV = samples of the WAV |
/// | `columns` | array of strings | data column names, in CSV order (without `time_s`) |
/// | `units` | object | column name → unit (`"m/s^2"`, `"g"`, ... or `"unknown"`) |
/// | `time_column` | string | `"time_s"` (seconds, `i / fs`) |
/// | `files` | object | `{"csv": ..., "wav": ..., "json": ...}` file names (no directory) |
/// | `wav` | object | `{"column", "unit", "sample_format": "float", "bits_per_sample": 32, "sample_rate_hz", "scale": 1.0}` |
/// | `rpm` | number | optional, copied from `meta` if the caller put it there (`simulate`: the recorded part's mean speed) |
/// | `rpm_range` | array | optional, from `meta` (`simulate`: `[lowest, highest]` speed over the recorded part, rpm) |
/// | `complete` | bool | `true` |
///
/// Any other keys of the caller's `meta` object are kept as they are (the keys above win).
pub const SIDECAR_FORMAT: &str = "wearsim-output";

/// The `format_version` of [`SIDECAR_FORMAT`] sidecars this build writes and reads.
pub const SIDECAR_FORMAT_VERSION: u64 = 1;

/// Name of the time column of the CSV written by [`write_outputs`] (seconds).
pub const TIME_COLUMN: &str = "time_s";

/// Paths of the three files written by [`write_outputs`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OutputSet {
    /// `<dir>/<stem>.csv`: `time_s` and all columns, full precision.
    pub csv: PathBuf,
    /// `<dir>/<stem>.wav`: 32-bit float mono, first column, physical units.
    pub wav: PathBuf,
    /// `<dir>/<stem>.json`: sidecar (meta + fs, n_samples, columns, units, files, `"complete": true`).
    pub json: PathBuf,
}

/// Unit implied by a column-name suffix: `_m_s2` → `m/s^2`, `_g` → `g`, `_mm_s` → `mm/s`,
/// `_um` → `um`, `_m` → `m` (simulate's `disp_m`), `_n` → `N`, `_s` → `s`; or by a unit in brackets at the end, as DAQ and
/// spreadsheet headers write it (`Acc [g]`, `accel (m/s^2)`, `a [m/s²]`); otherwise
/// `"unknown"`.
pub fn unit_from_column_name(name: &str) -> &'static str {
    let n = name.to_ascii_lowercase();
    let trimmed = n.trim_end();
    let bracketed = [('[', ']'), ('(', ')')].iter().find_map(|&(open, close)| {
        let inner = trimmed.strip_suffix(close)?;
        inner.rsplit_once(open).map(|(_, u)| u.trim())
    });
    if let Some(u) = bracketed {
        let unit = match u.replace(' ', "").as_str() {
            "g" => Some("g"),
            "m/s^2" | "m/s2" | "m/s²" | "ms^-2" | "m*s^-2" => Some("m/s^2"),
            "mm/s" => Some("mm/s"),
            "m/s" => Some("m/s"),
            "um" | "µm" | "μm" => Some("um"),
            "mm" => Some("mm"),
            "m" => Some("m"),
            "n" => Some("N"),
            "s" => Some("s"),
            "hz" => Some("Hz"),
            _ => None,
        };
        if let Some(unit) = unit {
            return unit;
        }
    }
    const TABLE: &[(&str, &str)] = &[
        ("_m_s2", "m/s^2"),
        ("_mm_s", "mm/s"),
        ("_m_s", "m/s"),
        ("_um", "um"),
        ("_mm", "mm"),
        ("_m", "m"),
        ("_g", "g"),
        ("_n", "N"),
        ("_s", "s"),
        ("_hz", "Hz"),
    ];
    for (suffix, unit) in TABLE {
        if n.ends_with(suffix) {
            return unit;
        }
    }
    "unknown"
}

/// Write `<stem>.csv`, `<stem>.wav` and `<stem>.json` into `dir` (created if missing), atomically.
///
/// * `columns`: `(name, samples)` pairs, all of equal, non-zero length; the first column goes to
///   the WAV. Units are taken from `meta["units"][name]` if present, else from the name suffix
///   ([`unit_from_column_name`]).
/// * `fs`: sample rate in Hz, 1 Hz ..= 10 MHz.
/// * `meta`: a JSON object merged into the sidecar (or `null`; any other value is stored under
///   the key `"meta"`).
///
/// Errors (nothing is written in any of these cases): non-finite sample (names the column and
/// index), value beyond the f32 range in the first column, unequal lengths, empty or duplicate
/// column names, a name equal to `time_s`, absurd `fs`, `stem` that is empty or contains a path
/// separator, and any I/O error.
pub fn write_outputs(
    dir: &Path,
    stem: &str,
    columns: &[(&str, &[f64])],
    fs: f64,
    meta: &Value,
) -> Result<OutputSet, IoError> {
    let set = OutputSet {
        csv: dir.join(format!("{stem}.csv")),
        wav: dir.join(format!("{stem}.wav")),
        json: dir.join(format!("{stem}.json")),
    };
    validate(&set, stem, columns, fs)?;
    let n = columns[0].1.len();

    // Exclusive use of `dir` while the set is replaced (a no-op if the caller holds it).
    let _lock = super::lock::DirLock::try_acquire(dir)?;
    remove_stale_temps(dir, stem);

    let sidecar = build_sidecar(stem, columns, fs, n, meta);

    // 1. Write the three temporaries (removed on drop unless persisted).
    let tmp_csv = temp_in(dir, stem, ".csv.tmp")?;
    write_csv(tmp_csv.as_file(), &set.csv, columns, fs)?;
    let tmp_wav = temp_in(dir, stem, ".wav.tmp")?;
    write_wav(tmp_wav.as_file(), &set.wav, columns[0], fs)?;
    let tmp_json = temp_in(dir, stem, ".json.tmp")?;
    write_json(tmp_json.as_file(), &set.json, &sidecar)?;

    // 2. Move into place. Remove an old sidecar first so that a partially replaced set never
    //    carries a "complete" sidecar; the new sidecar is renamed last.
    match std::fs::remove_file(&set.json) {
        Ok(()) => {}
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
        Err(e) => return Err(IoError::io(&set.json, "remove old sidecar", e)),
    }
    tmp_csv
        .persist(&set.csv)
        .map_err(|e| IoError::io(&set.csv, "rename", e.error))?;
    if let Err(e) = tmp_wav.persist(&set.wav) {
        let _ = std::fs::remove_file(&set.csv);
        return Err(IoError::io(&set.wav, "rename", e.error));
    }
    if let Err(e) = tmp_json.persist(&set.json) {
        let _ = std::fs::remove_file(&set.csv);
        let _ = std::fs::remove_file(&set.wav);
        return Err(IoError::io(&set.json, "rename", e.error));
    }
    sync_dir(dir);
    Ok(set)
}

fn validate(
    set: &OutputSet,
    stem: &str,
    columns: &[(&str, &[f64])],
    fs: f64,
) -> Result<(), IoError> {
    if stem.is_empty() || stem.contains(['/', '\\']) || stem == "." || stem == ".." {
        return Err(IoError::unsupported(
            &set.csv,
            format!("output stem {stem:?} must be a plain, non-empty file name"),
        ));
    }
    check_fs(&set.json, fs)?;
    let Some(first) = columns.first() else {
        return Err(IoError::unsupported(&set.csv, "no columns to write"));
    };
    let n = first.1.len();
    if n == 0 {
        return Err(IoError::unsupported(&set.csv, "zero samples to write"));
    }
    for (k, (name, data)) in columns.iter().enumerate() {
        if name.is_empty() || name.contains(['\n', '\r']) {
            return Err(IoError::unsupported(
                &set.csv,
                format!("column {k} has an empty or multi-line name {name:?}"),
            ));
        }
        if *name == TIME_COLUMN {
            return Err(IoError::unsupported(
                &set.csv,
                format!("column name {TIME_COLUMN:?} is reserved for the time column"),
            ));
        }
        if columns[..k].iter().any(|(other, _)| other == name) {
            return Err(IoError::unsupported(
                &set.csv,
                format!("duplicate column name {name:?}"),
            ));
        }
        if data.len() != n {
            return Err(IoError::contradiction(
                &set.csv,
                format!(
                    "column {name:?} has {} samples, column {:?} has {n}",
                    data.len(),
                    first.0
                ),
            ));
        }
        super::record::check_finite(&set.csv, name, data)?;
    }
    if let Some(index) = first.1.iter().position(|x| (*x as f32).is_infinite()) {
        return Err(IoError::NonFinite {
            path: set.wav.clone(),
            channel: format!("{} (beyond f32 range for the float WAV)", first.0),
            index,
            value: first.1[index],
        });
    }
    Ok(())
}

fn build_sidecar(stem: &str, columns: &[(&str, &[f64])], fs: f64, n: usize, meta: &Value) -> Value {
    let mut obj: Map<String, Value> = match meta {
        Value::Object(m) => m.clone(),
        Value::Null => Map::new(),
        other => {
            let mut m = Map::new();
            m.insert("meta".into(), other.clone());
            m
        }
    };
    let given_units = obj.get("units").and_then(Value::as_object).cloned();
    let mut units = Map::new();
    for (name, _) in columns {
        let unit = given_units
            .as_ref()
            .and_then(|u| u.get(*name))
            .and_then(Value::as_str)
            .map(str::to_string)
            .unwrap_or_else(|| unit_from_column_name(name).to_string());
        units.insert((*name).to_string(), Value::String(unit));
    }
    let first = columns[0].0;
    let wav_unit = units.get(first).cloned().unwrap_or(Value::Null);
    obj.insert("format".into(), json!(SIDECAR_FORMAT));
    obj.insert("format_version".into(), json!(SIDECAR_FORMAT_VERSION));
    obj.insert("fs".into(), json!(fs));
    obj.insert("n_samples".into(), json!(n));
    obj.insert(
        "columns".into(),
        Value::Array(columns.iter().map(|(c, _)| json!(c)).collect()),
    );
    obj.insert("units".into(), Value::Object(units));
    obj.insert("time_column".into(), json!(TIME_COLUMN));
    obj.insert(
        "files".into(),
        json!({"csv": format!("{stem}.csv"), "wav": format!("{stem}.wav"), "json": format!("{stem}.json")}),
    );
    obj.insert(
        "wav".into(),
        json!({
            "column": first,
            "unit": wav_unit,
            "sample_format": "float",
            "bits_per_sample": 32,
            "sample_rate_hz": wav_rate(fs),
            "scale": 1.0,
        }),
    );
    obj.insert("complete".into(), json!(true));
    Value::Object(obj)
}

/// Integer WAV header rate for `fs` (rounded; `fs` is already checked to be in range).
pub(crate) fn wav_rate(fs: f64) -> u32 {
    fs.round().clamp(1.0, u32::MAX as f64) as u32
}

/// Removes the temporaries of `stem`'s set ([`temp_in`]'s names) that a run killed before it
/// could drop them left in `dir` (a `kill -9` left a hidden 129 MB CSV that later runs
/// kept). Called with the directory's lock held: no other run is writing them.
fn remove_stale_temps(dir: &Path, stem: &str) {
    let Ok(rd) = std::fs::read_dir(dir) else {
        return;
    };
    let prefix = format!(".{stem}.");
    for e in rd.flatten() {
        let name = e.file_name().to_string_lossy().into_owned();
        let ours = name.starts_with(&prefix)
            && [".csv.tmp", ".wav.tmp", ".json.tmp"]
                .iter()
                .any(|s| name.ends_with(s));
        if ours && e.path().is_file() {
            let _ = std::fs::remove_file(e.path());
        }
    }
}

fn temp_in(dir: &Path, stem: &str, suffix: &str) -> Result<tempfile::NamedTempFile, IoError> {
    super::perms::output_builder()
        .prefix(&format!(".{stem}."))
        .suffix(suffix)
        .tempfile_in(dir)
        .map_err(|e| IoError::io(dir, "create temporary file", e))
}

fn write_csv(
    file: &File,
    target: &Path,
    columns: &[(&str, &[f64])],
    fs: f64,
) -> Result<(), IoError> {
    let werr = |e: std::io::Error| IoError::io(target, "write", e);
    let mut w = ::csv::WriterBuilder::new().from_writer(BufWriter::with_capacity(1 << 16, file));
    let mut header: Vec<&str> = Vec::with_capacity(columns.len() + 1);
    header.push(TIME_COLUMN);
    header.extend(columns.iter().map(|(c, _)| *c));
    w.write_record(&header).map_err(|e| werr(e.into()))?;
    let n = columns[0].1.len();
    let mut bufs: Vec<ryu::Buffer> = (0..=columns.len()).map(|_| ryu::Buffer::new()).collect();
    let mut row: Vec<String> = vec![String::new(); columns.len() + 1];
    for i in 0..n {
        row[0].clear();
        row[0].push_str(bufs[0].format_finite(i as f64 / fs));
        for (k, (_, data)) in columns.iter().enumerate() {
            row[k + 1].clear();
            row[k + 1].push_str(bufs[k + 1].format_finite(data[i]));
        }
        w.write_record(&row).map_err(|e| werr(e.into()))?;
    }
    let inner = w.into_inner().map_err(|e| werr(e.into_error()))?;
    finish(inner, target)
}

fn write_wav(file: &File, target: &Path, column: (&str, &[f64]), fs: f64) -> Result<(), IoError> {
    let spec = hound::WavSpec {
        channels: 1,
        sample_rate: wav_rate(fs),
        bits_per_sample: 32,
        sample_format: hound::SampleFormat::Float,
    };
    let herr = |e: hound::Error| match e {
        hound::Error::IoError(io) => IoError::io(target, "write", io),
        other => IoError::unsupported(target, format!("WAV encoder: {other}")),
    };
    let mut w =
        hound::WavWriter::new(BufWriter::with_capacity(1 << 16, file), spec).map_err(herr)?;
    for &x in column.1 {
        w.write_sample(x as f32).map_err(herr)?;
    }
    w.finalize().map_err(herr)?;
    file.sync_all().map_err(|e| IoError::io(target, "fsync", e))
}

fn write_json(file: &File, target: &Path, sidecar: &Value) -> Result<(), IoError> {
    let mut w = BufWriter::new(file);
    serde_json::to_writer_pretty(&mut w, sidecar)
        .map_err(|e| IoError::io(target, "write", std::io::Error::other(e)))?;
    w.write_all(b"\n")
        .map_err(|e| IoError::io(target, "write", e))?;
    finish(w, target)
}

fn finish(w: BufWriter<&File>, target: &Path) -> Result<(), IoError> {
    let file = w
        .into_inner()
        .map_err(|e| IoError::io(target, "write", e.into_error()))?;
    file.sync_all().map_err(|e| IoError::io(target, "fsync", e))
}

/// Best-effort fsync of a directory so the renames are durable (no-op where unsupported).
fn sync_dir(dir: &Path) {
    if let Ok(d) = File::open(dir) {
        let _ = d.sync_all();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir_entries(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn writes_three_files_and_sidecar() {
        let tmp = tempfile::tempdir().unwrap();
        let a = [0.0, 1.5, -2.25e-9, 12345.678];
        let g: Vec<f64> = a.iter().map(|x| x / 9.80665).collect();
        let meta = json!({"scenario": "test", "rpm": 1797.0});
        let set = write_outputs(
            tmp.path(),
            "run",
            &[("accel_m_s2", &a), ("accel_g", &g)],
            12000.0,
            &meta,
        )
        .unwrap();
        assert_eq!(
            dir_entries(tmp.path()),
            vec!["run.csv", "run.json", "run.wav"]
        );
        let side: Value = serde_json::from_slice(&std::fs::read(&set.json).unwrap()).unwrap();
        assert_eq!(side["complete"], json!(true));
        assert_eq!(side["fs"], json!(12000.0));
        assert_eq!(side["n_samples"], json!(4));
        assert_eq!(side["units"]["accel_m_s2"], json!("m/s^2"));
        assert_eq!(side["units"]["accel_g"], json!("g"));
        assert_eq!(side["scenario"], json!("test"));
        assert_eq!(side["rpm"], json!(1797.0));
        assert_eq!(side["files"]["wav"], json!("run.wav"));
        let text = std::fs::read_to_string(&set.csv).unwrap();
        let mut lines = text.lines();
        assert_eq!(lines.next(), Some("time_s,accel_m_s2,accel_g"));
        let row: Vec<f64> = lines
            .nth(2)
            .unwrap()
            .split(',')
            .map(|s| s.parse().unwrap())
            .collect();
        assert_eq!(row[1], -2.25e-9);
        assert_eq!(row[2], -2.25e-9 / 9.80665);
        assert_eq!(row[0], 2.0 / 12000.0);
        let mut r = hound::WavReader::open(&set.wav).unwrap();
        assert_eq!(r.spec().sample_rate, 12000);
        assert_eq!(r.spec().sample_format, hound::SampleFormat::Float);
        let w: Vec<f32> = r.samples::<f32>().map(|s| s.unwrap()).collect();
        assert_eq!(w, a.iter().map(|&x| x as f32).collect::<Vec<_>>());
    }

    /// Temporaries of this stem left by a killed run are removed by the next run into the
    /// directory; another stem's, and the user's files, are not.
    #[test]
    fn a_killed_runs_temporaries_are_removed_by_the_next() {
        let tmp = tempfile::tempdir().unwrap();
        for f in [
            ".run.Ab12Cd.csv.tmp",
            ".run.Xy34Zw.wav.tmp",
            ".other.Ab12Cd.csv.tmp",
            "notes.tmp",
        ] {
            std::fs::write(tmp.path().join(f), b"x").unwrap();
        }
        write_outputs(
            tmp.path(),
            "run",
            &[("accel_m_s2", &[0.0, 1.0])],
            12000.0,
            &Value::Null,
        )
        .unwrap();
        assert_eq!(
            dir_entries(tmp.path()),
            vec![
                ".other.Ab12Cd.csv.tmp",
                "notes.tmp",
                "run.csv",
                "run.json",
                "run.wav"
            ]
        );
    }

    #[test]
    fn rejects_non_finite_and_leaves_nothing() {
        let tmp = tempfile::tempdir().unwrap();
        let a = [0.0, 1.0, f64::NAN];
        let b = [0.0, 1.0, 2.0];
        let err = write_outputs(
            tmp.path(),
            "bad",
            &[("b", &b), ("a_g", &a)],
            1000.0,
            &Value::Null,
        )
        .unwrap_err();
        match &err {
            IoError::NonFinite { channel, index, .. } => {
                assert_eq!(channel, "a_g");
                assert_eq!(*index, 2);
            }
            other => panic!("unexpected {other:?}"),
        }
        assert!(err.to_string().contains("bad.csv"), "{err}");
        assert!(dir_entries(tmp.path()).is_empty());
    }

    #[test]
    fn rejects_bad_arguments() {
        let tmp = tempfile::tempdir().unwrap();
        let a = [1.0, 2.0];
        let short = [1.0];
        let d = tmp.path();
        assert!(matches!(
            write_outputs(d, "x", &[("a", &a)], 0.5, &Value::Null),
            Err(IoError::AbsurdSampleRate { .. })
        ));
        assert!(matches!(
            write_outputs(d, "x", &[("a", &a)], f64::NAN, &Value::Null),
            Err(IoError::AbsurdSampleRate { .. })
        ));
        assert!(matches!(
            write_outputs(d, "x", &[("a", &a), ("b", &short)], 10.0, &Value::Null),
            Err(IoError::Contradiction { .. })
        ));
        assert!(write_outputs(d, "x", &[("a", &a), ("a", &a)], 10.0, &Value::Null).is_err());
        assert!(write_outputs(d, "x", &[("time_s", &a)], 10.0, &Value::Null).is_err());
        assert!(write_outputs(d, "x", &[], 10.0, &Value::Null).is_err());
        assert!(write_outputs(d, "../x", &[("a", &a)], 10.0, &Value::Null).is_err());
        assert!(write_outputs(d, "x", &[("a", &[1e300])], 10.0, &Value::Null).is_err());
        assert!(dir_entries(d).is_empty());
    }

    #[test]
    fn overwrite_replaces_set() {
        let tmp = tempfile::tempdir().unwrap();
        let a = [1.0, 2.0, 3.0];
        write_outputs(tmp.path(), "s", &[("a", &a)], 100.0, &Value::Null).unwrap();
        let b = [4.0, 5.0];
        let set = write_outputs(tmp.path(), "s", &[("b", &b)], 200.0, &json!({"k": 1})).unwrap();
        assert_eq!(dir_entries(tmp.path()), vec!["s.csv", "s.json", "s.wav"]);
        let side: Value = serde_json::from_slice(&std::fs::read(&set.json).unwrap()).unwrap();
        assert_eq!(side["n_samples"], json!(2));
        assert_eq!(side["k"], json!(1));
    }
}
