//! The CWRU bearing-data loader (see the parent module's docs).

use std::path::{Path, PathBuf};

use serde::Serialize;
use serde_json::json;

use super::variables::{read_mat, MatVariable};
use crate::io::error::IoError;
use crate::io::record::{check_finite, check_fs, check_rpm, Record};

/// Fault class of a CWRU record, from its file name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CwruFault {
    /// Healthy baseline (`normal_*`).
    Normal,
    /// Inner-race defect (`IR`).
    InnerRace,
    /// Ball (rolling element) defect (`B`).
    Ball,
    /// Outer-race defect (`OR`), at the given clock position relative to the load zone:
    /// 6 = centred, 3 = orthogonal, 12 = opposite.
    OuterRace {
        /// Clock position (3, 6 or 12).
        clock: u8,
    },
}

impl CwruFault {
    /// The `fault_type` string of `inventory.csv`: `normal`, `inner_race`, `ball`, `outer_race`.
    pub fn type_name(&self) -> &'static str {
        match self {
            CwruFault::Normal => "normal",
            CwruFault::InnerRace => "inner_race",
            CwruFault::Ball => "ball",
            CwruFault::OuterRace { .. } => "outer_race",
        }
    }

    /// The `or_position` string of `inventory.csv` (`centred_6`, `orthogonal_3`,
    /// `opposite_12`), or `None` for non-outer-race faults and unknown clock positions.
    pub fn or_position(&self) -> Option<&'static str> {
        match self {
            CwruFault::OuterRace { clock: 6 } => Some("centred_6"),
            CwruFault::OuterRace { clock: 3 } => Some("orthogonal_3"),
            CwruFault::OuterRace { clock: 12 } => Some("opposite_12"),
            _ => None,
        }
    }
}

/// Label parsed from a CWRU file name such as `12k_Drive_End_OR007@6_1_131.mat` or
/// `normal_0_97.mat` (the naming of the `yyxyz/CaseWesternReserveUniversityData` mirror).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CwruLabel {
    /// Sample rate implied by the name, Hz (`12k` = 12000, `48k` = 48000, `normal` = 48000).
    pub fs_hz: f64,
    /// Bearing end carrying the fault: `"DE"` (drive end) or `"FE"` (fan end); `None` for normal.
    pub fault_end: Option<String>,
    /// Fault class.
    pub fault: CwruFault,
    /// Defect diameter in inches (0.007, 0.014, 0.021, 0.028); `None` for normal.
    pub diameter_in: Option<f64>,
    /// Motor load in hp (0..3).
    pub load_hp: u8,
    /// CWRU record number (the original file name, `105.mat` = 105).
    pub record: u32,
}

/// Parse a CWRU file name (with or without directory and `.mat`). Returns `None` for names
/// that do not follow `<12k|48k>_<Drive|Fan>_End_<IR|B|OR><ddd>[@<clock>]_<load>_<record>` or
/// `normal_<load>_<record>`.
pub fn parse_cwru_name(name: &str) -> Option<CwruLabel> {
    let base = name.rsplit(['/', '\\']).next()?;
    let base = base.strip_suffix(".mat").unwrap_or(base);
    let parts: Vec<&str> = base.split('_').collect();
    let small_int = |s: &str| -> Option<u32> {
        if s.is_empty() || s.len() > 6 || !s.bytes().all(|b| b.is_ascii_digit()) {
            None
        } else {
            s.parse().ok()
        }
    };
    if parts.len() == 3 && parts[0].eq_ignore_ascii_case("normal") {
        let load = small_int(parts[1])?;
        return Some(CwruLabel {
            fs_hz: 48_000.0,
            fault_end: None,
            fault: CwruFault::Normal,
            diameter_in: None,
            load_hp: u8::try_from(load).ok().filter(|l| *l <= 3)?,
            record: small_int(parts[2])?,
        });
    }
    if parts.len() != 6 || !parts[2].eq_ignore_ascii_case("End") {
        return None;
    }
    let fs_hz = match parts[0].to_ascii_lowercase().as_str() {
        "12k" => 12_000.0,
        "48k" => 48_000.0,
        _ => return None,
    };
    let fault_end = match parts[1].to_ascii_lowercase().as_str() {
        "drive" => "DE",
        "fan" => "FE",
        _ => return None,
    };
    let code = parts[3];
    let (kind, rest) = if let Some(r) = code.strip_prefix("IR") {
        ("IR", r)
    } else if let Some(r) = code.strip_prefix("OR") {
        ("OR", r)
    } else if let Some(r) = code.strip_prefix('B') {
        ("B", r)
    } else {
        return None;
    };
    let (size, clock) = match rest.split_once('@') {
        Some((s, c)) => (s, Some(small_int(c)?)),
        None => (rest, None),
    };
    if size.len() != 3 {
        return None;
    }
    let diameter_in = small_int(size)? as f64 / 1000.0;
    let fault = match (kind, clock) {
        ("IR", None) => CwruFault::InnerRace,
        ("B", None) => CwruFault::Ball,
        ("OR", Some(c)) if matches!(c, 3 | 6 | 12) => CwruFault::OuterRace { clock: c as u8 },
        _ => return None,
    };
    let load = small_int(parts[4])?;
    Some(CwruLabel {
        fs_hz,
        fault_end: Some(fault_end.to_string()),
        fault,
        diameter_in: Some(diameter_in),
        load_hp: u8::try_from(load).ok().filter(|l| *l <= 3)?,
        record: small_int(parts[5])?,
    })
}

/// Bearing preset name for a CWRU channel: `DE` → `cwru-6205-de` (SKF 6205-2RS JEM),
/// `FE` → `cwru-6203-fe` (SKF 6203-2RS JEM); `BA` (base plate) has none.
pub fn cwru_bearing_preset(channel: &str) -> Option<&'static str> {
    match channel {
        "DE" => Some("cwru-6205-de"),
        "FE" => Some("cwru-6203-fe"),
        _ => None,
    }
}

/// The bearing preset holding the defect of a CWRU record, from its file name's label
/// (`12k_Drive_End_…` → the drive-end bearing, whichever channel recorded it); `None` for
/// a file without such a label, or a healthy one (`normal_…`).
pub fn cwru_faulty_bearing(path: &Path) -> Option<&'static str> {
    let name = path.file_name()?.to_string_lossy().into_owned();
    let label = parse_cwru_name(&name)?;
    if matches!(label.fault, CwruFault::Normal) {
        return None;
    }
    cwru_bearing_preset(label.fault_end.as_deref()?)
}

/// Numeric prefix of a CWRU variable name: `X118_DE_time` → 118, `X097RPM` → 97.
fn var_record(name: &str) -> Option<u32> {
    let rest = name.strip_prefix('X')?;
    let digits: String = rest.chars().take_while(|c| c.is_ascii_digit()).collect();
    digits.parse().ok()
}

/// Among `candidates` (named by `name`; `label` is what a message shows of each), pick the
/// one whose CWRU record number matches `record` (the file name's), else the only candidate;
/// several candidates and no match is a contradiction naming them, with `hint` appended.
/// Shared by the flat CWRU reader and the tree resolver (`super::resolve`).
pub(crate) fn pick_by_record<'v, T>(
    path: &Path,
    candidates: &[&'v T],
    name: impl Fn(&T) -> &str,
    label: impl Fn(&T) -> &str,
    record: Option<u32>,
    what: &str,
    hint: &str,
) -> Result<Option<&'v T>, IoError> {
    if let Some(r) = record {
        if let Some(v) = candidates.iter().find(|v| var_record(name(v)) == Some(r)) {
            return Ok(Some(v));
        }
    }
    match candidates {
        [] => Ok(None),
        [one] => Ok(Some(one)),
        many => Err(IoError::contradiction(
            path,
            format!(
                "several {what} variables ({}) and none matches record {record:?} of the file name{hint}",
                many.iter().map(|v| label(v)).collect::<Vec<_>>().join(", ")
            ),
        )),
    }
}

/// The CWRU label of `path`'s file name ([`parse_cwru_name`]) and the record number to prefer
/// among its variables: the label's, else a bare numeric name (`118.mat`).
/// Shared by the flat CWRU reader and the tree resolver (`super::resolve`).
pub(crate) fn file_label(path: &Path) -> (Option<CwruLabel>, Option<u32>) {
    let file_name = path
        .file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let label = parse_cwru_name(&file_name);
    let record_no = label
        .as_ref()
        .map(|l| l.record)
        .or_else(|| file_name.strip_suffix(".mat").and_then(|s| s.parse().ok()));
    (label, record_no)
}

/// [`pick_by_record`] over the flat reader's variables.
fn pick<'v>(
    path: &Path,
    candidates: &[&'v MatVariable],
    record: Option<u32>,
    what: &str,
) -> Result<Option<&'v MatVariable>, IoError> {
    fn name(v: &MatVariable) -> &str {
        &v.name
    }
    pick_by_record(path, candidates, name, name, record, what, "")
}

/// Read one channel of a CWRU `.mat` file.
///
/// * `channel`: `"DE"`, `"FE"` or `"BA"` (case-insensitive), selecting the variable ending in
///   `_DE_time`, `_FE_time` or `_BA_time`; an absent channel is [`IoError::UnknownChannel`]
///   listing the channels the file has.
/// * `fs_override`: sample rate in Hz; otherwise taken from the file name via
///   [`parse_cwru_name`] (no recognisable name and no override → [`IoError::MissingSampleRate`]).
///
/// The record has unit `"g"` (assumed; CWRU does not state it), `rpm` from the `XnnnRPM`
/// variable (if present), `bearing` from [`cwru_bearing_preset`], and `meta` with the parsed
/// label (`"label"`), the variable name, the list of variables and the source of `fs`.
pub fn read_cwru(
    path: impl AsRef<Path>,
    channel: &str,
    fs_override: Option<f64>,
) -> Result<Record, IoError> {
    let path = path.as_ref();
    let ch = channel.to_ascii_uppercase();
    let suffix = format!("_{ch}_time");
    let vars = read_mat(path, &|name: &str| {
        name.ends_with(&suffix) || name.ends_with("RPM")
    })?;
    let (label, record_no) = file_label(path);

    let numeric = |v: &&MatVariable| v.class.is_numeric() && !v.complex;
    let time_vars: Vec<&MatVariable> = vars
        .iter()
        .filter(numeric)
        .filter(|v| v.name.ends_with(&suffix))
        .collect();
    let Some(var) = pick(path, &time_vars, record_no, &suffix)? else {
        let mut available: Vec<String> = vars
            .iter()
            .filter(numeric)
            .filter_map(|v| {
                let stem = v.name.strip_suffix("_time")?;
                Some(stem.rsplit('_').next()?.to_string())
            })
            .collect();
        available.sort();
        available.dedup();
        return Err(IoError::UnknownChannel {
            path: path.to_path_buf(),
            requested: channel.to_string(),
            available,
        });
    };
    if var.data.is_empty() {
        return Err(IoError::truncated(
            path,
            format!("variable {} holds no samples", var.name),
        ));
    }
    if var.dims.iter().filter(|&&d| d > 1).count() > 1 {
        return Err(IoError::unsupported(
            path,
            format!(
                "variable {} is a {:?} matrix, expected a vector",
                var.name, var.dims
            ),
        ));
    }
    check_finite(path, &var.name, &var.data)?;

    let (fs, fs_source) = match (fs_override, &label) {
        (Some(fs), _) => (fs, "argument"),
        (None, Some(l)) => (l.fs_hz, "file name"),
        (None, None) => {
            return Err(IoError::MissingSampleRate {
                path: path.to_path_buf(),
                detail: "CWRU files do not store it and the file name is not of the form \
                         12k_Drive_End_IR007_0_105.mat / normal_0_97.mat"
                    .into(),
                advice: crate::io::error::MAT_FS_ADVICE,
            })
        }
    };
    let fs = check_fs(path, fs)?;

    let rpm_vars: Vec<&MatVariable> = vars
        .iter()
        .filter(numeric)
        .filter(|v| v.name.ends_with("RPM"))
        .collect();
    let rpm = match pick(path, &rpm_vars, record_no, "RPM")? {
        Some(v) => match v.data.first() {
            Some(&r) => Some(check_rpm(path, r)?),
            None => None,
        },
        None => None,
    };

    let meta = json!({
        "format": "cwru-mat5",
        "variable": var.name,
        "variables": vars.iter().map(|v| json!({"name": v.name, "dims": v.dims})).collect::<Vec<_>>(),
        "fs_source": fs_source,
        "unit_note": "CWRU does not state units; g is the common assumption",
        "label": label,
    });
    Ok(Record {
        samples: var.data.clone(),
        fs,
        rpm,
        channel: ch.clone(),
        unit: "g".into(),
        source: PathBuf::from(path),
        bearing: cwru_bearing_preset(&ch).map(str::to_string),
        meta,
    })
}
