//! JSON sidecar files: sample rate, speed and units for formats that do not store them.
//!
//! A sidecar for `data/run.wav` is `data/run.wav.json` or, if that does not exist,
//! `data/run.json` (the name [`crate::io::write::write_outputs`] uses, shared by the `.csv` and
//! `.wav` of one output set). The schema is the one the writer produces (see
//! [`crate::io::write::SIDECAR_FORMAT`]); every key is optional for reading:
//! `fs` (Hz), `rpm`, `n_samples`, `columns`, `units` (column → unit, or one unit for every
//! column as a string; `unit` is read the same way), `bearing`,
//! `wav.{column, unit, scale}` (`scale`: physical units per full scale of an integer WAV, or a
//! factor applied to a float WAV), and `complete` (a sidecar saying `false` is an error).
//!
//! wearsim's own sidecars also carry the resolved model configuration as structured JSON
//! (`model`: the core's `ModelConfig` with the `serde` feature, geometry included; see
//! [`model_metadata`]) and set `bearing` to the preset only when the geometry is the
//! preset's (`"custom"` otherwise). Readers take the geometry from `model` when it is
//! there ([`Sidecar::model`]). Sidecars written before (with `model` as a Rust `Debug`
//! string) are still read for `fs`, `rpm` and the rest; their `model` is ignored, so their
//! geometry is the `bearing` preset's, as before.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde_json::{json, Map, Value};
use wearsim_core::bearing::BearingGeometry;
use wearsim_core::ModelConfig;

use super::error::IoError;
use super::record::{check_fs, check_fs_argument, check_rpm, Record};

/// Largest sidecar accepted, bytes (a sidecar is metadata, not data).
pub const MAX_SIDECAR_BYTES: u64 = 16 << 20;

/// Parsed sidecar.
#[derive(Debug, Clone, Default)]
pub struct Sidecar {
    /// The sidecar file.
    pub path: PathBuf,
    /// Sample rate, Hz (validated: 1 Hz ..= 10 MHz).
    pub fs: Option<f64>,
    /// Shaft speed, rpm (the record's mean speed when it varies).
    pub rpm: Option<f64>,
    /// Lowest and highest shaft speed over the record, rpm (`"rpm_range"`, [`rpm_range`]),
    /// when the sidecar states them.
    pub rpm_range: Option<(f64, f64)>,
    /// Number of samples per channel the data file must hold.
    pub n_samples: Option<u64>,
    /// Data column names (CSV order, without the time column; NPY columns).
    pub columns: Vec<String>,
    /// Column name → unit.
    pub units: BTreeMap<String, String>,
    /// The unit of every column not in `units` (`"units": "g"` or `"unit": "g"`): what a
    /// single-channel file's sidecar says, whatever name the reader gives its channel
    /// (`col0` for a one-dimensional NPY).
    pub unit: Option<String>,
    /// Column written to the WAV.
    pub wav_column: Option<String>,
    /// Unit of the WAV samples.
    pub wav_unit: Option<String>,
    /// Factor applied to WAV samples after integer normalisation to ±1 (default 1).
    pub wav_scale: Option<f64>,
    /// Bearing preset name (`"custom"` when a wearsim run overrode the geometry).
    pub bearing: Option<String>,
    /// The resolved model configuration of a wearsim run (structured `model` key), if the
    /// sidecar has one; its `bearing` is the geometry the samples were simulated with.
    pub model: Option<ModelConfig>,
    /// The whole JSON object.
    pub raw: Value,
}

impl Sidecar {
    /// What a rate or speed taken from this sidecar is reported as (`fs_detail`,
    /// `rpm_detail`): `sidecar `NAME.json``.
    pub fn detail(&self) -> String {
        let name = self.path.file_name().unwrap_or(self.path.as_os_str());
        format!("sidecar `{}`", name.to_string_lossy())
    }

    /// Unit of `column`: `units[column]`, else the sidecar-wide unit, if given.
    pub fn unit_of(&self, column: &str) -> Option<&str> {
        self.units
            .get(column)
            .or(self.unit.as_ref())
            .map(String::as_str)
    }
}

/// Candidate sidecar paths for a data file: `<file>.json`, then `<stem>.json`.
pub fn sidecar_candidates(data: &Path) -> Vec<PathBuf> {
    let mut v = Vec::new();
    let mut full = data.as_os_str().to_owned();
    full.push(".json");
    v.push(PathBuf::from(full));
    if data.extension().is_some() {
        let stem = data.with_extension("json");
        if stem != data {
            v.push(stem);
        }
    }
    v
}

/// Find and read the sidecar of `data`, if one exists. An empty file (or one holding only
/// white space) is not a sidecar: it is what `wearsim analyze rec.csv --json > rec.json`
/// creates before the command runs; it is skipped with a warning on stderr.
pub fn sidecar_for(data: &Path) -> Result<Option<Sidecar>, IoError> {
    for c in sidecar_candidates(data) {
        if c.is_file() {
            let blank = std::fs::metadata(&c).is_ok_and(|m| m.len() <= 4096)
                && std::fs::read(&c).is_ok_and(|b| b.iter().all(u8::is_ascii_whitespace));
            if blank {
                eprintln!(
                    "wearsim: warning: {}: empty, not read as a sidecar",
                    c.display()
                );
                continue;
            }
            let raw = read_json(&c)?;
            if let Some(kind) = report_kind(&raw) {
                eprintln!(
                    "wearsim: warning: {}: a wearsim {kind} report, not read as a sidecar",
                    c.display()
                );
                continue;
            }
            return parse_sidecar(&c, raw).map(Some);
        }
    }
    Ok(None)
}

/// The command whose `--json` report `raw` is (`analyze`: a `diagnosis`; `gap`: a
/// `ranking`), if it is one: `wearsim analyze rec.npy --json > rec.json` writes exactly the
/// name the reader looks for next to `rec.npy`, and its `fs`, `rpm` and `bearing` must not
/// become the record's on the next run.
fn report_kind(raw: &Value) -> Option<&'static str> {
    let has = |k: &str| raw.get(k).is_some();
    if has("format") {
        return None;
    }
    if has("diagnosis") && has("kurtogram") {
        Some("analyze")
    } else if has("ranking") && has("totals") {
        Some("gap")
    } else {
        None
    }
}

/// The JSON value of a sidecar file (a record's or a feature table's), at most
/// [`MAX_SIDECAR_BYTES`], a UTF-8 byte order mark skipped, every object's keys unique
/// ([`super::unique_json`]).
pub fn read_json(path: &Path) -> Result<Value, IoError> {
    let bytes = super::record::read_capped(
        path,
        MAX_SIDECAR_BYTES,
        "sidecar",
        &format!("{MAX_SIDECAR_BYTES} bytes per sidecar"),
    )?;
    // A UTF-8 byte order mark (Windows editors) is no part of the JSON.
    let body = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(&bytes);
    super::unique_json::from_slice(body)
        .map_err(|e| IoError::malformed(path, format!("sidecar JSON: {e}")))
}

/// Read and validate one sidecar file.
pub fn read_sidecar(path: &Path) -> Result<Sidecar, IoError> {
    parse_sidecar(path, read_json(path)?)
}

fn num(path: &Path, v: &Value, key: &str) -> Result<Option<f64>, IoError> {
    match v.get(key) {
        None | Some(Value::Null) => Ok(None),
        Some(Value::Number(n)) => Ok(n.as_f64()),
        Some(other) => Err(IoError::malformed(
            path,
            format!("sidecar key {key:?} must be a number, found {other}"),
        )),
    }
}

fn string(path: &Path, v: &Value, key: &str) -> Result<Option<String>, IoError> {
    match v.get(key) {
        None | Some(Value::Null) => Ok(None),
        Some(Value::String(s)) => Ok(Some(s.clone())),
        Some(other) => Err(IoError::malformed(
            path,
            format!("sidecar key {key:?} must be a string, found {other}"),
        )),
    }
}

/// Top-level keys a sidecar is read for, and those wearsim's own sidecars add (see the module
/// doc and [`crate::io::write::SIDECAR_FORMAT`]).
const READ_KEYS: &[&str] = &[
    "fs",
    "rpm",
    "n_samples",
    "columns",
    "rpm_range",
    "units",
    "unit",
    "bearing",
    "bearing_geometry",
    "wav",
    "complete",
    "model",
    "format",
    "format_version",
    "time_column",
    "files",
];

/// The key a hand-written sidecar most likely meant by `key`, for the warning about keys that
/// are not read (names other tools and data sets use for the rate and the speed).
fn meant(key: &str) -> Option<&'static str> {
    let k = key.to_ascii_lowercase().replace(['-', ' '], "_");
    match k.as_str() {
        "sample_rate" | "sample_rate_hz" | "samplerate" | "sampling_rate"
        | "sampling_frequency" | "fs_hz" | "sr" | "rate" => Some("fs (Hz)"),
        "speed" | "speed_rpm" | "shaft_rpm" | "shaft_speed" | "rpm_" | "rotational_speed" => {
            Some("rpm")
        }
        "channels" | "column" | "column_names" => Some("columns"),
        "samples" | "length" | "num_samples" => Some("n_samples"),
        _ => None,
    }
}

/// Warn on stderr about the top-level keys of a hand-written sidecar that are not read, so a
/// misspelt rate or speed is not lost silently. wearsim's own sidecars (`format` =
/// [`crate::io::write::SIDECAR_FORMAT`]) carry the scenario's metadata as further keys and
/// are not warned about.
fn warn_unread_keys(path: &Path, raw: &Map<String, Value>) {
    let unread = unread_keys(raw);
    if !unread.is_empty() {
        eprintln!(
            "wearsim: warning: {}: sidecar keys not read: {} (read: {})",
            path.display(),
            unread.join(", "),
            READ_KEYS[..10].join(", ")
        );
    }
}

/// The unread top-level keys of a hand-written sidecar, each with the key it most likely
/// meant (see [`warn_unread_keys`]); none for wearsim's own sidecars.
fn unread_keys(raw: &Map<String, Value>) -> Vec<String> {
    if raw.get("format").and_then(Value::as_str) == Some(super::write::SIDECAR_FORMAT) {
        return Vec::new();
    }
    raw.keys()
        .filter(|k| !READ_KEYS.contains(&k.as_str()))
        .map(|k| match meant(k) {
            Some(m) => format!("{k:?} (did you mean {m}?)"),
            None => format!("{k:?}"),
        })
        .collect()
}

/// Validate a sidecar JSON value read from `path`.
pub fn parse_sidecar(path: &Path, raw: Value) -> Result<Sidecar, IoError> {
    let Some(obj) = raw.as_object() else {
        return Err(IoError::malformed(path, "sidecar must be a JSON object"));
    };
    warn_unread_keys(path, obj);
    if raw.get("complete") == Some(&Value::Bool(false)) {
        return Err(IoError::contradiction(
            path,
            "sidecar says \"complete\": false (the output set was not finished)",
        ));
    }
    // A wearsim sidecar of another format version may mean its keys otherwise.
    if raw.get("format").and_then(Value::as_str) == Some(super::write::SIDECAR_FORMAT) {
        let known = super::write::SIDECAR_FORMAT_VERSION;
        if let Some(v) = raw
            .get("format_version")
            .filter(|v| v.as_u64() != Some(known))
        {
            return Err(IoError::malformed(
                path,
                format!("sidecar format_version {v} (this reader knows {known})"),
            ));
        }
    }
    let fs = match num(path, &raw, "fs")? {
        Some(f) => Some(check_fs(path, f)?),
        None => None,
    };
    let rpm = match num(path, &raw, "rpm")? {
        Some(r) => Some(check_rpm(path, r)?),
        None => None,
    };
    let rpm_range = rpm_range(&raw).map_err(|e| IoError::malformed(path, e))?;
    if let (Some(r), Some((lo, hi))) = (rpm, rpm_range) {
        if r < lo * (1.0 - 1e-9) || r > hi * (1.0 + 1e-9) {
            return Err(IoError::contradiction(
                path,
                format!("sidecar \"rpm\" = {r} lies outside its \"rpm_range\" [{lo}, {hi}]"),
            ));
        }
    }
    let n_samples = match raw.get("n_samples") {
        None | Some(Value::Null) => None,
        Some(v) => Some(v.as_u64().ok_or_else(|| {
            IoError::malformed(
                path,
                format!("sidecar \"n_samples\" must be a non-negative integer, found {v}"),
            )
        })?),
    };
    let columns = match raw.get("columns") {
        None | Some(Value::Null) => Vec::new(),
        Some(Value::Array(a)) => a
            .iter()
            .map(|c| {
                c.as_str().map(str::to_string).ok_or_else(|| {
                    IoError::malformed(
                        path,
                        format!("sidecar \"columns\" entry {c} is not a string"),
                    )
                })
            })
            .collect::<Result<_, _>>()?,
        Some(other) => {
            return Err(IoError::malformed(
                path,
                format!("sidecar \"columns\" must be an array, found {other}"),
            ))
        }
    };
    let mut units = BTreeMap::new();
    let mut unit = string(path, &raw, "unit")?;
    match raw.get("units") {
        None | Some(Value::Null) => {}
        Some(Value::Object(m)) => {
            for (k, v) in m {
                if let Some(s) = v.as_str() {
                    units.insert(k.clone(), s.to_string());
                }
            }
        }
        Some(Value::String(s)) => {
            // A single unit for every column.
            unit = Some(s.clone());
        }
        Some(other) => {
            return Err(IoError::malformed(
                path,
                format!("sidecar \"units\" must be an object, found {other}"),
            ))
        }
    }
    let (wav_column, wav_unit, wav_scale) = match raw.get("wav") {
        Some(w @ Value::Object(_)) => {
            let scale = num(path, w, "scale")?;
            if let Some(s) = scale {
                if !s.is_finite() || s == 0.0 {
                    return Err(IoError::malformed(
                        path,
                        format!("sidecar \"wav.scale\" must be finite and non-zero, found {s}"),
                    ));
                }
            }
            (string(path, w, "column")?, string(path, w, "unit")?, scale)
        }
        _ => (None, None, None),
    };
    Ok(Sidecar {
        path: path.to_path_buf(),
        fs,
        rpm,
        rpm_range,
        n_samples,
        columns,
        units,
        unit,
        wav_column,
        wav_unit,
        wav_scale,
        bearing: string(path, &raw, "bearing")?,
        model: structured_model(&raw).map_err(|e| IoError::malformed(path, e))?,
        raw,
    })
}

/// The lowest and highest shaft speed over the record that a sidecar states, rpm
/// (`"rpm_range": [min, max]`; wearsim writes it for every run, from the speed profile
/// over the recorded part): `None` without the key; an error naming the key unless it is
/// two speeds in (0, 10⁶) rpm, the lower first.
pub fn rpm_range(raw: &Value) -> Result<Option<(f64, f64)>, String> {
    let v = match raw.get("rpm_range") {
        None | Some(Value::Null) => return Ok(None),
        Some(v) => v,
    };
    let bad = || {
        format!(
            "sidecar \"rpm_range\" must be [lowest, highest] shaft speed over the record in rpm, each in (0, 1e6), the lower first; found {v}"
        )
    };
    let [lo, hi] = v
        .as_array()
        .and_then(|a| match a.as_slice() {
            [a, b] => Some([a.as_f64()?, b.as_f64()?]),
            _ => None,
        })
        .ok_or_else(bad)?;
    let ok = |r: f64| r.is_finite() && r > 0.0 && r < 1.0e6;
    if ok(lo) && ok(hi) && lo <= hi {
        Ok(Some((lo, hi)))
    } else {
        Err(bad())
    }
}

/// Value of the `bearing` key for a run of `cfg`: the preset's name when the geometry is
/// the preset's, `"custom"` otherwise (a `[bearing]` override, or no preset).
pub fn bearing_label(preset: Option<&str>, cfg: &ModelConfig) -> String {
    let preset_geometry = preset
        .and_then(wearsim_core::presets::by_name)
        .and_then(|p| BearingGeometry::new_checked(p.bearing).ok());
    match (preset, preset_geometry) {
        (Some(name), Some(g)) if g == cfg.bearing => name.to_string(),
        _ => "custom".to_string(),
    }
}

/// The sidecar keys describing the model of a run: `bearing` ([`bearing_label`]) and
/// `model` (the resolved configuration `cfg` as structured JSON, geometry included).
pub fn model_metadata(preset: Option<&str>, cfg: &ModelConfig) -> Map<String, Value> {
    let mut m = Map::new();
    m.insert("bearing".into(), json!(bearing_label(preset, cfg)));
    m.insert(
        "model".into(),
        serde_json::to_value(cfg).unwrap_or(Value::Null),
    );
    m
}

/// The structured model configuration of a wearsim sidecar (`format` is
/// [`super::write::SIDECAR_FORMAT`]): `None` for other sidecars, without a `model` key or
/// when it is an old sidecar's `Debug` string; an error when it is an object that is not a
/// valid configuration.
pub fn structured_model(raw: &Value) -> Result<Option<ModelConfig>, String> {
    if raw.get("format").and_then(Value::as_str) != Some(super::write::SIDECAR_FORMAT) {
        return Ok(None);
    }
    match raw.get("model") {
        Some(m @ Value::Object(_)) => serde_json::from_value::<ModelConfig>(m.clone())
            .map(Some)
            .map_err(|e| format!("sidecar \"model\" is not a wearsim model configuration: {e}")),
        _ => Ok(None),
    }
}

/// Where the sample rate of a record came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum FsSource {
    Argument,
    Sidecar,
    Intrinsic,
}

impl FsSource {
    pub(crate) fn name(self) -> &'static str {
        match self {
            FsSource::Argument => "argument",
            FsSource::Sidecar => "sidecar",
            FsSource::Intrinsic => "file",
        }
    }
}

/// What `fs_detail` says of a rate given as `--fs` (and `rpm_detail` of `--rpm`).
pub const ARGUMENT_FS: &str = "--fs";
/// What `rpm_detail` says of a speed given as `--rpm`.
pub const ARGUMENT_RPM: &str = "--rpm";

/// Decide the sample rate of `data`: an explicit argument must agree with every rate the
/// sidecar and the file state ([`check_fs_argument`], the rule the MAT reader applies) and is
/// then used; it is the only rate of a file that states none. Without it, the sidecar and the
/// file's own value (`intrinsic`, e.g. a WAV header rate, with its name for messages, which
/// is also its `fs_detail`: `WAV header`) must agree (`agree(sidecar_fs, intrinsic_fs)`),
/// and the sidecar's exact value is used. Returns the rate, its source and its detail
/// ([`ARGUMENT_FS`], [`Sidecar::detail`] or the intrinsic rate's name).
pub(crate) fn resolve_fs(
    data: &Path,
    arg: Option<f64>,
    sidecar: Option<&Sidecar>,
    intrinsic: Option<(f64, &str)>,
    agree: &dyn Fn(f64, f64) -> bool,
) -> Result<(f64, FsSource, String), IoError> {
    let (fs, source) = resolve_fs_source(data, arg, sidecar, intrinsic, agree)?;
    let detail = match (source, sidecar, intrinsic) {
        (FsSource::Sidecar, Some(s), _) => s.detail(),
        (FsSource::Intrinsic, _, Some((_, what))) => what.to_string(),
        _ => ARGUMENT_FS.to_string(),
    };
    Ok((fs, source, detail))
}

fn resolve_fs_source(
    data: &Path,
    arg: Option<f64>,
    sidecar: Option<&Sidecar>,
    intrinsic: Option<(f64, &str)>,
    agree: &dyn Fn(f64, f64) -> bool,
) -> Result<(f64, FsSource), IoError> {
    let side = sidecar.and_then(|s| s.fs.map(|f| (f, &s.path)));
    if let Some(f) = arg {
        if let Some((sf, sp)) = side {
            check_fs_argument(sp, f, sf, &format!("the sidecar {}", sp.display()))?;
        }
        if let Some((inf, what)) = intrinsic {
            check_fs_argument(data, f, inf, &format!("the file ({what})"))?;
        }
        return Ok((check_fs(data, f)?, FsSource::Argument));
    }
    match (side, intrinsic) {
        (Some((sf, sp)), Some((inf, what))) => {
            if agree(sf, inf) {
                Ok((sf, FsSource::Sidecar))
            } else {
                Err(IoError::contradiction(
                    sp,
                    format!(
                        "sidecar fs {sf} Hz contradicts {what} {inf} Hz of {}",
                        data.display()
                    ),
                ))
            }
        }
        (Some((sf, _)), None) => Ok((sf, FsSource::Sidecar)),
        (None, Some((inf, _))) => Ok((check_fs(data, inf)?, FsSource::Intrinsic)),
        (None, None) => Err(IoError::MissingSampleRate {
            path: data.to_path_buf(),
            detail: format!(
                "no sidecar ({}) with \"fs\" and no explicit rate given",
                sidecar_candidates(data)
                    .iter()
                    .map(|p| p.display().to_string())
                    .collect::<Vec<_>>()
                    .join(" or ")
            ),
            advice: super::error::SIDECAR_FS_ADVICE,
        }),
    }
}

/// Check a sidecar's `n_samples` against the samples per channel actually found.
pub(crate) fn check_n_samples(
    sidecar: Option<&Sidecar>,
    data: &Path,
    found: usize,
) -> Result<(), IoError> {
    if let Some(s) = sidecar {
        if let Some(n) = s.n_samples {
            if n != found as u64 {
                return Err(IoError::contradiction(
                    &s.path,
                    format!("sidecar n_samples {n} but {} holds {found}", data.display()),
                ));
            }
        }
    }
    Ok(())
}

/// Shaft speed: explicit argument, else sidecar; with its `rpm_detail` ([`ARGUMENT_RPM`]
/// or [`Sidecar::detail`]).
pub(crate) fn resolve_rpm(
    data: &Path,
    arg: Option<f64>,
    sidecar: Option<&Sidecar>,
) -> Result<Option<(f64, String)>, IoError> {
    match arg {
        Some(r) => Ok(Some((check_rpm(data, r)?, ARGUMENT_RPM.to_string()))),
        None => Ok(sidecar.and_then(|s| s.rpm.map(|r| (r, s.detail())))),
    }
}

/// The [`Record`] of `samples` (channel and unit) read from `path` beside an optional
/// `sidecar`: its rate as [`resolve_fs`] resolved it, its speed from the argument `rpm` or the
/// sidecar ([`resolve_rpm`]), its bearing from the sidecar, and `meta` (the format's own
/// fields, a JSON object) with the rate's and speed's sources and the sidecar's contents
/// added. One place for what the CSV, NPY and WAV readers return.
pub(crate) fn sidecar_record(
    path: &Path,
    samples: Vec<f64>,
    (channel, unit): (String, String),
    (fs, fs_source, fs_detail): (f64, FsSource, String),
    rpm: Option<f64>,
    sidecar: Option<&Sidecar>,
    mut meta: Value,
) -> Result<Record, IoError> {
    let rpm = resolve_rpm(path, rpm, sidecar)?;
    if let Value::Object(m) = &mut meta {
        m.insert("fs_source".into(), json!(fs_source.name()));
        m.insert("fs_detail".into(), json!(fs_detail));
        m.insert("rpm_detail".into(), json!(rpm.as_ref().map(|r| &r.1)));
        m.insert("sidecar".into(), json!(sidecar.map(|s| &s.raw)));
    }
    Ok(Record {
        samples,
        fs,
        rpm: rpm.map(|r| r.0),
        channel,
        unit,
        source: path.to_path_buf(),
        bearing: sidecar.and_then(|s| s.bearing.clone()),
        meta,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_speed_range_is_two_ordered_speeds_that_hold_the_stated_rpm() {
        let p = Path::new("r.json");
        let ok = parse_sidecar(p, json!({"rpm": 1750, "rpm_range": [1600, 1800]})).unwrap();
        assert_eq!(ok.rpm_range, Some((1600.0, 1800.0)));
        for (bad, needle) in [
            (json!({"rpm_range": [1800, 1600]}), "the lower first"),
            (json!({"rpm_range": [1600]}), "[lowest, highest]"),
            (json!({"rpm_range": [0, 1600]}), "(0, 1e6)"),
            (json!({"rpm_range": "1600-1800"}), "\"rpm_range\""),
            (
                json!({"rpm": 1900, "rpm_range": [1600, 1800]}),
                "outside its \"rpm_range\"",
            ),
        ] {
            let e = parse_sidecar(p, bad.clone()).unwrap_err().to_string();
            assert!(e.contains(needle), "{bad}: {e}");
        }
    }

    #[test]
    fn unread_keys_of_hand_written_sidecars_are_named_with_what_they_likely_meant() {
        let raw = json!({"sample_rate": 12000, "rpm": 1797, "Speed": 1800, "operator": "x"});
        let mut u = unread_keys(raw.as_object().unwrap());
        u.sort();
        assert_eq!(
            u,
            vec![
                "\"Speed\" (did you mean rpm?)".to_string(),
                "\"operator\"".to_string(),
                "\"sample_rate\" (did you mean fs (Hz)?)".to_string(),
            ]
        );
        // A wearsim sidecar of a later format version is refused (probe of stop 69).
        let newer = json!({"format": crate::io::write::SIDECAR_FORMAT, "format_version": 99});
        let e = parse_sidecar(Path::new("r.json"), newer)
            .unwrap_err()
            .to_string();
        assert!(e.contains("format_version 99 (this reader knows 1)"), "{e}");
        // wearsim's own sidecars carry the scenario's metadata: no warning.
        let own = json!({"format": crate::io::write::SIDECAR_FORMAT, "scenario": "x"});
        assert!(unread_keys(own.as_object().unwrap()).is_empty());
        let known = json!({"fs": 1, "units": "g", "wav": {}, "complete": true});
        assert!(unread_keys(known.as_object().unwrap()).is_empty());
    }

    #[test]
    fn an_analyze_report_saved_beside_its_record_is_not_its_sidecar() {
        let dir = tempfile::tempdir().unwrap();
        let rec = dir.path().join("rec.npy");
        std::fs::write(&rec, b"").unwrap();
        let report = json!({"fs": 12000, "rpm": 1797, "bearing": {"elements": 9},
            "diagnosis": {"family": "None"}, "kurtogram": {}});
        std::fs::write(dir.path().join("rec.json"), report.to_string()).unwrap();
        assert!(sidecar_for(&rec).unwrap().is_none());
        assert_eq!(
            report_kind(&json!({"ranking": [], "totals": {}})),
            Some("gap")
        );
        // A sidecar stays a sidecar.
        std::fs::write(dir.path().join("rec.json"), r#"{"fs": 12000}"#).unwrap();
        assert_eq!(sidecar_for(&rec).unwrap().unwrap().fs, Some(12000.0));
    }
}
