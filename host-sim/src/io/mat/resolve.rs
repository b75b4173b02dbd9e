//! One channel of any MAT v5 file as a [`Record`]: the layout is recognised by content (CWRU,
//! MFPT-style struct, Paderborn-style struct, or generic), the channel is resolved from a path
//! inside the file or a layout's shorthand, and metadata stored in the file (sample rate, shaft
//! rate or rpm, load) is used and reported with its source (`file:bearing.sr`,
//! `layout:paderborn`, `file name`, `argument`).
//!
//! Layouts (see `docs/readers.md` for the sources):
//!
//! | layout | recognised by | channel default | fs | speed |
//! |---|---|---|---|---|
//! | `cwru` | a variable `X<n>_(DE\|FE\|BA)_time` | the faulted end's: `FE` for a fan-end fault file (`12k_Fan_End_…`), else `DE` | file name (`12k_`/`48k_`) | `X<n>RPM` |
//! | `mfpt` | a struct with fields `gs` and `sr` | `<struct>.gs` | `<struct>.sr` | `<struct>.rate` (Hz) × 60 |
//! | `paderborn` | a struct with a struct array `Y` of `Name`/`Data` | `vibration_1` | 64 kHz (layout) | `N<nn>` of the variable name × 100 rpm |
//! | `generic` | anything else | the only long numeric vector | a scalar `fs`/`sr`/`sample_rate` | a scalar `rpm` |

use std::path::{Path, PathBuf};

use serde_json::json;

use super::cwru::{cwru_bearing_preset, file_label, pick_by_record};
use super::tree::{find, numeric_arrays, read_mat_tree, walk, ArrayInfo, MatNode, MatValue};
use crate::io::error::IoError;
use crate::io::record::{check_finite, check_fs, check_fs_argument, check_rpm, Record};
use crate::io::selector;
use crate::io::sidecar::{ARGUMENT_FS, ARGUMENT_RPM};
use crate::io::ReadOptions;

/// Paderborn (KAt data center) vibration sample rate, Hz (Lessmeier et al. 2016: 64 kHz).
pub const PADERBORN_FS: f64 = 64_000.0;
pub use crate::io::record::FS_AGREEMENT;

/// The recognised layout of a MAT file.
#[derive(Debug, Clone, PartialEq)]
pub enum MatLayout {
    /// CWRU bearing data center (`X118_DE_time`, `X118RPM`).
    Cwru,
    /// MFPT-style struct (name of the struct, e.g. `bearing`).
    Mfpt(String),
    /// Paderborn-style struct (name of the top variable, e.g. `N15_M07_F10_K001_1`).
    Paderborn(String),
    /// No known layout.
    Generic,
}

impl MatLayout {
    /// Layout name as reported (`cwru`, `mfpt`, `paderborn`, `generic`).
    pub fn name(&self) -> &'static str {
        match self {
            MatLayout::Cwru => "cwru",
            MatLayout::Mfpt(_) => "mfpt",
            MatLayout::Paderborn(_) => "paderborn",
            MatLayout::Generic => "generic",
        }
    }
}

fn is_cwru_time(name: &str) -> bool {
    let Some(rest) = name.strip_prefix('X') else {
        return false;
    };
    let digits = rest.chars().take_while(|c| c.is_ascii_digit()).count();
    digits > 0 && matches!(&rest[digits..], "_DE_time" | "_FE_time" | "_BA_time")
}

fn struct_fields(n: &MatNode) -> Option<&[String]> {
    match &n.value {
        MatValue::Struct { fields, .. } => Some(fields),
        _ => None,
    }
}

/// Recognise the layout of a parsed file by its content (never by its file name).
pub fn recognise(nodes: &[MatNode]) -> MatLayout {
    if nodes.iter().any(|n| is_cwru_time(&n.name)) {
        return MatLayout::Cwru;
    }
    for n in nodes {
        if let Some(f) = struct_fields(n) {
            if f.iter().any(|x| x == "gs") && f.iter().any(|x| x == "sr") {
                return MatLayout::Mfpt(n.name.clone());
            }
            if let Some(y) = n.field(0, "Y") {
                if struct_fields(y)
                    .is_some_and(|g| g.iter().any(|x| x == "Name") && g.iter().any(|x| x == "Data"))
                {
                    return MatLayout::Paderborn(n.name.clone());
                }
            }
        }
    }
    MatLayout::Generic
}

/// [`pick_by_record`] over the tree's nodes (listed by their paths in a message).
fn pick_cwru<'n>(
    path: &Path,
    cands: &[&'n MatNode],
    record: Option<u32>,
    what: &str,
) -> Result<Option<&'n MatNode>, IoError> {
    fn name(v: &MatNode) -> &str {
        &v.name
    }
    fn label(v: &MatNode) -> &str {
        &v.path
    }
    pick_by_record(
        path,
        cands,
        name,
        label,
        record,
        what,
        "; pass the full name with --channel",
    )
}

fn is_numeric(n: &MatNode) -> bool {
    matches!(n.value, MatValue::Numeric { .. })
}

fn is_vector(n: &MatNode) -> bool {
    n.dims.iter().filter(|&&d| d > 1).count() <= 1
}

fn unknown(path: &Path, requested: &str, arrays: &[ArrayInfo]) -> IoError {
    IoError::UnknownChannel {
        path: path.to_path_buf(),
        requested: requested.to_string(),
        available: arrays.iter().map(ArrayInfo::label).collect(),
    }
}

/// Shortest record (samples) a channel chosen without `--channel` may have.
const MIN_SIGNAL: usize = 256;

/// The only numeric vector of at least [`MIN_SIGNAL`] elements at or below `nodes`.
fn only_signal<'n>(nodes: &[&'n MatNode]) -> Option<&'n MatNode> {
    let mut all = Vec::new();
    for n in nodes {
        walk(std::slice::from_ref(*n), &mut all);
    }
    let long: Vec<&MatNode> = all
        .into_iter()
        .filter(|n| is_numeric(n) && is_vector(n) && n.numel() >= MIN_SIGNAL)
        .collect();
    match long.as_slice() {
        [one] => Some(one),
        _ => None,
    }
}

/// Resolve the channel's path in the tree (listing pass, data not converted).
fn channel_path(
    path: &Path,
    nodes: &[MatNode],
    layout: &MatLayout,
    requested: Option<&str>,
    record_no: Option<u32>,
    cwru_default: &str,
) -> Result<(String, String), IoError> {
    let arrays = numeric_arrays(nodes);
    if arrays.is_empty() {
        return Err(IoError::unsupported(
            path,
            "no numeric array in the file (nothing to analyse)",
        ));
    }
    let req = match (requested, layout) {
        (Some(r), _) => r.to_string(),
        (None, MatLayout::Cwru) => cwru_default.into(),
        (None, MatLayout::Mfpt(s)) => format!("{s}.gs"),
        (None, MatLayout::Paderborn(_)) => "vibration_1".into(),
        (None, MatLayout::Generic) => {
            let top: Vec<&MatNode> = nodes.iter().collect();
            return match only_signal(&top) {
                Some(n) => Ok((n.path.clone(), n.path.clone())),
                None => Err(unknown(
                    path,
                    "(none given; the file holds no single signal of >= 256 samples, pass --channel PATH)",
                    &arrays,
                )),
            };
        }
    };
    // 1. A path inside the file.
    if let Some(n) = find(nodes, &req) {
        if is_numeric(n) {
            return Ok((n.path.clone(), req));
        }
        if matches!(n.value, MatValue::Struct { .. } | MatValue::Cell(_)) {
            return match only_signal(&[n]) {
                Some(s) => Ok((s.path.clone(), req)),
                None => Err(IoError::unsupported(
                    path,
                    format!(
                        "{req:?} is a {} without a recognisable signal (no single numeric vector of >= {MIN_SIGNAL} samples inside); available: [{}]",
                        if matches!(n.value, MatValue::Struct { .. }) { "struct" } else { "cell" },
                        arrays.iter().map(ArrayInfo::label).collect::<Vec<_>>().join(", ")
                    ),
                )),
            };
        }
        if matches!(n.value, MatValue::Sparse) {
            return Err(IoError::unsupported(
                path,
                format!("{req:?} is a sparse array; sparse arrays are not read (store it with full() in MATLAB)"),
            ));
        }
    }
    let mut all = Vec::new();
    walk(nodes, &mut all);
    // 2. CWRU shorthand DE / FE / BA.
    let up = req.to_ascii_uppercase();
    if matches!(up.as_str(), "DE" | "FE" | "BA") {
        let suffix = format!("_{up}_time");
        let cands: Vec<&MatNode> = nodes
            .iter()
            .filter(|n| is_numeric(n) && n.name.ends_with(&suffix))
            .collect();
        if let Some(n) = pick_cwru(path, &cands, record_no, &suffix)? {
            return Ok((n.path.clone(), up));
        }
    }
    // 3. A Paderborn channel name (`Y(i).Name`).
    if let MatLayout::Paderborn(top) = layout {
        if let Some(y) = nodes
            .iter()
            .find(|n| &n.name == top)
            .and_then(|t| t.field(0, "Y"))
        {
            if let MatValue::Struct { elems, .. } = &y.value {
                for i in 0..elems.len() {
                    if y.field(i, "Name").and_then(MatNode::text) == Some(req.as_str()) {
                        if let Some(d) = y.field(i, "Data").filter(|d| is_numeric(d)) {
                            return Ok((d.path.clone(), req));
                        }
                    }
                }
            }
        }
    }
    // 4. A unique leaf name (case-insensitive).
    let leaf: Vec<&&MatNode> = all
        .iter()
        .filter(|n| is_numeric(n) && n.name.eq_ignore_ascii_case(&req))
        .collect();
    if let [one] = leaf.as_slice() {
        return Ok((one.path.clone(), req));
    }
    Err(unknown(path, &req, &arrays))
}

/// A scalar numeric node named one of `names` (case-insensitive): first among the siblings of
/// `channel` (same parent path), else the only one in the file.
fn find_scalar<'n>(all: &[&'n MatNode], channel: &str, names: &[&str]) -> Option<&'n MatNode> {
    let parent = channel.rsplit_once('.').map(|(p, _)| p).unwrap_or("");
    let hits: Vec<&MatNode> = all
        .iter()
        .copied()
        .filter(|n| {
            is_numeric(n) && n.numel() == 1 && names.iter().any(|k| n.name.eq_ignore_ascii_case(k))
        })
        .collect();
    let sib = hits
        .iter()
        .find(|n| n.path.rsplit_once('.').map(|(p, _)| p).unwrap_or("") == parent);
    match (sib, hits.as_slice()) {
        (Some(s), _) => Some(s),
        (None, [one]) => Some(one),
        _ => None,
    }
}

/// The nodes named one of `names` (case-insensitive) that are no numeric scalar, as
/// `; `bearing.sr` is a char array "48828"` / `is a 1x2 double`, for a message saying why
/// a rate or speed stored there was not taken; empty when there are none.
fn not_scalar(all: &[&MatNode], names: &[&str]) -> String {
    all.iter()
        .filter(|n| names.iter().any(|k| n.name.eq_ignore_ascii_case(k)))
        .filter(|n| !(is_numeric(n) && n.numel() == 1))
        .map(|n| {
            let dims: Vec<String> = n.dims.iter().map(usize::to_string).collect();
            let what = match &n.value {
                MatValue::Char(t) => {
                    format!("a char array {:?}", t.chars().take(40).collect::<String>())
                }
                MatValue::Numeric { .. } => format!("a {} numeric array", dims.join("x")),
                MatValue::Struct { .. } => "a struct".into(),
                MatValue::Cell(_) => "a cell array".into(),
                MatValue::Sparse | MatValue::Other => "not a numeric array".into(),
            };
            format!("; `{}` is {what}, not a numeric scalar", n.path)
        })
        .collect()
}

/// Names of a sample-rate scalar.
const FS_NAMES: &[&str] = &[
    "sr",
    "fs",
    "sample_rate",
    "samplerate",
    "sampling_rate",
    "sampling_frequency",
    "Fsamp",
];
/// Names of a shaft-speed scalar in rpm.
const RPM_NAMES: &[&str] = &["rpm", "speed_rpm", "shaft_rpm"];
/// Names of a shaft-rate scalar in Hz (MFPT `rate`).
const RATE_NAMES: &[&str] = &["rate", "shaft_hz", "shaft_rate"];

/// Shaft speed of a Paderborn variable name `N<nn>_M<mm>_F<ff>_...`: `nn` × 100 rpm
/// (N09 = 900 rpm, N15 = 1500 rpm; Lessmeier et al. 2016).
pub fn paderborn_rpm(var: &str) -> Option<f64> {
    let rest = var.strip_prefix('N')?;
    let (d, tail) = rest.split_at_checked(2)?;
    if !tail.starts_with("_M") || !d.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    d.parse::<f64>().ok().map(|n| n * 100.0)
}

/// Bearing catalogue name of a layout, when the data set documents its bearing (see
/// [`crate::geometry`]).
fn layout_bearing(layout: &MatLayout, channel: &str) -> Option<String> {
    match layout {
        MatLayout::Cwru => cwru_bearing_preset(channel).map(str::to_string),
        MatLayout::Mfpt(_) => Some("mfpt-nice".into()),
        MatLayout::Paderborn(_) => Some("paderborn-6203".into()),
        MatLayout::Generic => None,
    }
}

/// Read one channel of any MAT v5 file (see the module doc). `opts.channel` is a path inside
/// the file or a layout shorthand; `opts.fs` must agree with a rate the file states (within
/// [`FS_AGREEMENT`]); `opts.rpm` overrides the file's speed.
pub fn read_mat_record(path: impl AsRef<Path>, opts: &ReadOptions) -> Result<Record, IoError> {
    let path = path.as_ref();
    let listing = read_mat_tree(path, &|_| false)?;
    let layout = recognise(&listing);
    let (label, record_no) = file_label(path);
    // A CWRU fan-end fault file is analysed on the accelerometer at the faulted bearing (and so
    // with its geometry, `cwru-6203-fe`), as the data center's own file naming says.
    let cwru_default = match label.as_ref().and_then(|l| l.fault_end.as_deref()) {
        Some("FE") => "FE",
        _ => "DE",
    };
    // `NAME(:,K)` / `NAME(K,:)`: one line of a 2-D array (`crate::io::selector`).
    let (requested, selected) = match opts.channel.as_deref().map(|c| (c, selector::split(c))) {
        Some((_, Some((base, sel)))) => (Some(base), Some(sel)),
        Some((c, None)) => (Some(c), None),
        None => (None, None),
    };
    let (chan_path, chan_name) =
        channel_path(path, &listing, &layout, requested, record_no, cwru_default)?;
    let mut all = Vec::new();
    walk(&listing, &mut all);
    let fs_node = find_scalar(&all, &chan_path, FS_NAMES).map(|n| n.path.clone());
    let rpm_node = find_scalar(&all, &chan_path, RPM_NAMES).map(|n| n.path.clone());
    let rate_node = find_scalar(&all, &chan_path, RATE_NAMES).map(|n| n.path.clone());
    let load_node = find_scalar(&all, &chan_path, &["load"]).map(|n| n.path.clone());
    let cwru_rpm: Vec<String> = if layout == MatLayout::Cwru {
        let c: Vec<&MatNode> = listing
            .iter()
            .filter(|n| is_numeric(n) && n.name.ends_with("RPM"))
            .collect();
        pick_cwru(path, &c, record_no, "RPM")?
            .map(|n| vec![n.path.clone()])
            .unwrap_or_default()
    } else {
        vec![]
    };
    let wanted: Vec<String> = [
        Some(chan_path.clone()),
        fs_node.clone(),
        rpm_node.clone(),
        rate_node.clone(),
        load_node.clone(),
    ]
    .into_iter()
    .flatten()
    .chain(cwru_rpm.iter().cloned())
    // Every rate and speed the file states, to check they agree with the ones taken.
    .chain(
        all.iter()
            .filter(|n| is_numeric(n) && n.numel() == 1)
            .filter(|n| {
                [FS_NAMES, RPM_NAMES, RATE_NAMES]
                    .iter()
                    .any(|names| names.iter().any(|k| n.name.eq_ignore_ascii_case(k)))
            })
            .map(|n| n.path.clone()),
    )
    .collect();
    let tree = read_mat_tree(path, &|p: &str| wanted.iter().any(|w| w == p))?;
    let get = |p: &str| find(&tree, p);
    let chan = get(&chan_path).ok_or_else(|| unknown(path, &chan_path, &numeric_arrays(&tree)))?;
    if let MatValue::Numeric { complex: true, .. } = chan.value {
        return Err(IoError::unsupported(
            path,
            format!("{chan_path:?} is complex; only real signals are analysed"),
        ));
    }
    let data = chan.numbers().unwrap_or(&[]);
    let (samples, line) = match selected {
        Some(sel) => {
            let line = selector::check(sel, &chan_path, &chan.dims)
                .map_err(|e| IoError::malformed(path, e))?;
            let rows = chan.dims[0];
            // MAT arrays are stored column by column.
            let get = |i: usize, j: usize| data.get(i + j * rows).copied().unwrap_or(f64::NAN);
            (selector::extract(line, rows, chan.dims[1], get), Some(line))
        }
        None if !is_vector(chan) => {
            return Err(IoError::unsupported(
                path,
                format!(
                    "{chan_path:?} is a {:?} matrix, expected a vector: {}",
                    chan.dims,
                    selector::advice(&chan_path, &chan.dims)
                ),
            ))
        }
        None => (data.to_vec(), None),
    };
    let suffix = line.map(selector::Line::suffix).unwrap_or_default();
    if samples.is_empty() {
        return Err(IoError::truncated(
            path,
            format!("{chan_path:?} holds no samples"),
        ));
    }
    check_finite(path, &chan_path, &samples)?;

    // Sample rate: stated in the file, else the layout's, else the CWRU file name; `--fs` must
    // agree with a stated rate and overrides the others.
    let stated = fs_node.as_deref().and_then(|p| {
        get(p)
            .and_then(MatNode::scalar)
            .map(|v| (v, format!("file:{p}")))
    });
    if let (None, Some((v, src))) = (opts.fs, &stated) {
        let stated_at = src.strip_prefix("file:").unwrap_or(src);
        STATED_RATE.check(path, &all, &get, &chan_path, stated_at, *v)?;
    }
    let implied = match (&layout, &label) {
        (MatLayout::Paderborn(_), _) => Some((PADERBORN_FS, "layout:paderborn".to_string())),
        (MatLayout::Cwru, Some(l)) => Some((l.fs_hz, "file name".to_string())),
        _ => None,
    };
    let implied_only = implied
        .as_ref()
        .map(|(s, _)| *s)
        .filter(|_| stated.is_none());
    let (fs, fs_source) = match (opts.fs, stated, implied) {
        (Some(a), Some((s, src)), _) => (
            check_fs_argument(path, a, s, &format!("the file ({src})"))?,
            "argument".to_string(),
        ),
        (Some(a), None, _) => (a, "argument".to_string()),
        (None, Some(s), _) | (None, None, Some(s)) => s,
        (None, None, None) => {
            return Err(IoError::MissingSampleRate {
                path: path.to_path_buf(),
                detail: format!(
                    "the {} layout stores none (no numeric scalar named {}{}) and the file name does not give one",
                    layout.name(),
                    FS_NAMES.join("/"),
                    not_scalar(&all, FS_NAMES)
                ),
                advice: crate::io::error::MAT_FS_ADVICE,
            })
        }
    };
    let fs = check_fs(path, fs)?;
    // An argument that overrides the rate a layout or a file name implies is allowed (a
    // renamed or resampled file), but said: a wrong `--fs` moves every fault frequency.
    let overridden = match (opts.fs, implied_only) {
        (Some(a), Some(s)) if (a - s).abs() > 1e-3 * s => {
            let what = match (&layout, &label) {
                (MatLayout::Paderborn(_), _) => "the Paderborn layout's".to_string(),
                _ => format!(
                    "the CWRU file name `{}`'s",
                    path.file_name().unwrap_or_default().to_string_lossy()
                ),
            };
            eprintln!(
                "wearsim: warning: {}: --fs {a} Hz overrides {what} {s} Hz",
                path.display()
            );
            Some(format!(" (overrides {what} {s} Hz)"))
        }
        _ => None,
    };
    let fs_detail = match (fs_source.as_str(), &label) {
        ("argument", _) => format!("{ARGUMENT_FS}{}", overridden.unwrap_or_default()),
        ("file name", Some(l)) => format!(
            "CWRU file name `{}` ({} Hz)",
            path.file_name().unwrap_or_default().to_string_lossy(),
            l.fs_hz
        ),
        ("layout:paderborn", _) => format!("Paderborn layout ({PADERBORN_FS} Hz, documented)"),
        (s, _) => s.strip_prefix("file:").map_or(s.to_string(), stored_at),
    };

    // Shaft speed.
    let from_file = |p: &Option<String>, scale: f64| -> Option<(f64, String)> {
        let p = p.as_deref()?;
        get(p)
            .and_then(MatNode::scalar)
            .map(|v| (v * scale, format!("file:{p}")))
    };
    let file_rpm = cwru_rpm
        .first()
        .cloned()
        .and_then(|p| from_file(&Some(p), 1.0))
        .or_else(|| from_file(&rpm_node, 1.0))
        .or_else(|| from_file(&rate_node, 60.0))
        .or_else(|| match &layout {
            MatLayout::Paderborn(v) => {
                paderborn_rpm(v).map(|r| (r, "layout:paderborn(variable name)".to_string()))
            }
            _ => None,
        });
    if let (None, Some((v, src))) = (opts.rpm, &file_rpm) {
        if let Some(stated_at) = src.strip_prefix("file:") {
            STATED_SPEED.check(path, &all, &get, &chan_path, stated_at, *v)?;
        }
    }
    let (rpm, rpm_source) = match (opts.rpm, file_rpm) {
        (Some(r), _) => (Some(check_rpm(path, r)?), Some("argument".to_string())),
        (None, Some((r, s))) => (Some(check_rpm(path, r)?), Some(s)),
        (None, None) => (None, None),
    };
    let rpm_detail = rpm_source.as_deref().map(|s| match s {
        "argument" => ARGUMENT_RPM.to_string(),
        s if s.starts_with("layout:paderborn") => match &layout {
            MatLayout::Paderborn(v) => format!("Paderborn variable name `{v}` (N<nn> × 100 rpm)"),
            _ => s.to_string(),
        },
        s => match s.strip_prefix("file:") {
            Some(p) if rate_node.as_deref() == Some(p) => format!("{} (Hz × 60)", stored_at(p)),
            Some(p) => stored_at(p),
            None => s.to_string(),
        },
    });
    let load = from_file(&load_node, 1.0);
    let channel = match layout {
        MatLayout::Cwru => ["DE", "FE", "BA"]
            .into_iter()
            .find(|c| chan_path.ends_with(&format!("_{c}_time")))
            .map_or(chan_name, str::to_string),
        _ => chan_name,
    };
    let selected_name = format!("{channel}{suffix}");
    let (unit, unit_source) = match layout {
        MatLayout::Cwru | MatLayout::Mfpt(_) => ("g".to_string(), "layout".to_string()),
        MatLayout::Paderborn(_) => match sidecar_unit(path, &selected_name, &chan_path)? {
            (u, _) if u == "unknown" => {
                paderborn_unit(&listing, &chan_path).unwrap_or((u, "none".into()))
            }
            stated => stated,
        },
        MatLayout::Generic => sidecar_unit(path, &selected_name, &chan_path)?,
    };
    let meta = json!({
        "format": if layout == MatLayout::Cwru { "cwru-mat5" } else { "mat5" },
        "layout": layout.name(),
        "variable": format!("{chan_path}{suffix}"),
        "arrays": numeric_arrays(&tree),
        "fs_source": fs_source,
        "fs_detail": fs_detail,
        "rpm_source": rpm_source,
        "rpm_detail": rpm_detail,
        "load": load.as_ref().map(|l| l.0),
        "load_source": load.as_ref().map(|l| l.1.clone()),
        "unit_note": match layout {
            MatLayout::Cwru => "CWRU does not state units; g is the common assumption",
            MatLayout::Mfpt(_) => "MFPT stores acceleration in g (field gs)",
            MatLayout::Paderborn(_) => "Paderborn states each channel's unit in Y(i).Unit; a sidecar's unit overrides it",
            _ => "the file does not state units",
        },
        "unit_source": unit_source,
        "label": if layout == MatLayout::Cwru { json!(label) } else { json!(null) },
    });
    Ok(Record {
        samples,
        fs,
        rpm,
        bearing: layout_bearing(&layout, &channel),
        channel: selected_name,
        unit,
        source: PathBuf::from(path),
        meta,
    })
}

/// Two speeds a file states for one channel that differ by more than this fraction (rpm
/// against a shaft rate in Hz × 60 rounded to a few digits agree far better) are two answers.
const SPEED_AGREEMENT: f64 = 0.01;

/// A quantity a file may state more than once (sample rate, shaft speed), for
/// [`Stated::check`].
struct Stated {
    what: &'static str,
    flag: &'static str,
    unit: &'static str,
    tolerance: f64,
    /// The scalars' names that state it, each with its factor to `unit`.
    names: &'static [(&'static [&'static str], f64)],
}

/// The sample rate, Hz.
const STATED_RATE: Stated = Stated {
    what: "sample rate",
    flag: "--fs",
    unit: "Hz",
    tolerance: FS_AGREEMENT,
    names: &[(FS_NAMES, 1.0)],
};

/// The shaft speed, rpm: in rpm, or as a shaft rate in Hz.
const STATED_SPEED: Stated = Stated {
    what: "shaft speed",
    flag: "--rpm",
    unit: "rpm",
    tolerance: SPEED_AGREEMENT,
    names: &[(RPM_NAMES, 1.0), (RATE_NAMES, 60.0)],
};

impl Stated {
    /// Checks the value `v` taken from `stated_at` against every other numeric scalar of
    /// the file that states it (`names`). One beside the
    /// channel (same struct) that disagrees makes the file ambiguous: refused, both named,
    /// with the flag that settles it (stop 68: `fs` = 12000 and `sample_rate` = 24000, `rpm`
    /// = 900 and `rate` = 29.95 Hz were resolved silently). One elsewhere that disagrees is
    /// warned about: the value beside the channel is taken.
    fn check<'t>(
        &self,
        path: &Path,
        all: &[&MatNode],
        get: &dyn Fn(&str) -> Option<&'t MatNode>,
        chan_path: &str,
        stated_at: &str,
        v: f64,
    ) -> Result<(), IoError> {
        let parent = |p: &str| p.rsplit_once('.').map_or("", |(a, _)| a).to_string();
        let Stated {
            what,
            flag,
            unit,
            tolerance,
            names: others,
        } = self;
        for n in all
            .iter()
            .filter(|n| n.path != stated_at && is_numeric(n) && n.numel() == 1)
        {
            let Some(scale) = others
                .iter()
                .find(|(names, _)| names.iter().any(|k| n.name.eq_ignore_ascii_case(k)))
                .map(|(_, f)| *f)
            else {
                continue;
            };
            let Some(w) = get(&n.path).and_then(MatNode::scalar).map(|x| x * scale) else {
                continue;
            };
            if (w - v).abs() <= tolerance * v.abs().max(w.abs()) {
                continue;
            }
            let other = if scale == 1.0 {
                format!("`{}` = {w} {unit}", n.path)
            } else {
                format!("`{}` = {} ({w} {unit})", n.path, w / scale)
            };
            if parent(&n.path) == parent(chan_path) {
                return Err(IoError::malformed(
                    path,
                    format!(
                        "the file states two {what}s for `{chan_path}`: `{stated_at}` = {v} {unit} and {other}; give {flag} to say which is right"
                    ),
                ));
            }
            eprintln!(
                "wearsim: warning: {}: {other} states another {what} than `{stated_at}` = {v} {unit}, which is beside `{chan_path}` and is taken",
                path.display()
            );
        }
        Ok(())
    }
}

/// Where in a MAT file a value is stored, as `fs_detail`/`rpm_detail` say it: `MAT
/// variable `X118RPM`` for a variable, `MAT struct field `bearing.sr`` for a path into one.
fn stored_at(p: &str) -> String {
    let kind = if p.contains('{') {
        "cell element"
    } else if p.contains(['.', '(']) {
        "struct field"
    } else {
        "variable"
    };
    format!("MAT {kind} `{p}`")
}

/// The unit a Paderborn file states for the channel at `chan_path` (`….Y(i).Data`): the
/// char array `….Y(i).Unit` beside it, when not blank; with its path as the source
/// (`file:N15_M07_F10_KA01_1.Y(7).Unit`).
fn paderborn_unit(listing: &[MatNode], chan_path: &str) -> Option<(String, String)> {
    let unit_path = format!("{}.Unit", chan_path.strip_suffix(".Data")?);
    let unit = find(listing, &unit_path)?.text()?.trim();
    (!unit.is_empty()).then(|| (unit.to_string(), format!("file:{unit_path}")))
}

/// The unit of a MAT file whose layout states none (Paderborn, generic): the one its JSON
/// sidecar (`<file>.json`, else `<stem>.json`) gives the channel (`"units": {"acc": "g"}`
/// by its name or its path in the file) or the whole file (`"units": "g"`), else
/// `unknown`; with the sidecar that gave it. Only the unit is read from a MAT file's
/// sidecar (the file and the flags give the rate and the speed): a sidecar that also
/// states other keys gets a warning that they are not read.
fn sidecar_unit(path: &Path, channel: &str, chan_path: &str) -> Result<(String, String), IoError> {
    let Some(side) = crate::io::sidecar::sidecar_for(path)? else {
        return Ok(("unknown".into(), "none".into()));
    };
    let ignored: Vec<&String> = side
        .raw
        .as_object()
        .map(|o| {
            o.keys()
                .filter(|k| !matches!(k.as_str(), "units" | "unit"))
                .collect()
        })
        .unwrap_or_default();
    if !ignored.is_empty() {
        eprintln!(
            "wearsim: warning: {}: a MAT file's sidecar is read for `units`/`unit` only; not read: {}",
            side.path.display(),
            ignored
                .iter()
                .map(|k| format!("`{k}`"))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    let unit = side
        .units
        .get(channel)
        .or_else(|| side.units.get(chan_path))
        .or(side.unit.as_ref())
        .cloned();
    Ok(match unit {
        Some(u) => (u, format!("sidecar:{}", side.path.display())),
        None => ("unknown".into(), "none".into()),
    })
}
