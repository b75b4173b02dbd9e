//! Recognition of the text layouts of common public bearing data sets **by content** (the
//! first line and the row count), never by file name, and their readers. Each layout supplies
//! its documented sample rate, channels and bearing with source `layout:NAME`; `--fs` and
//! `--channel` still override. MAT layouts (CWRU, MFPT, Paderborn) are recognised in
//! [`crate::io::mat::resolve`].
//!
//! | layout | recognised by | fs | channels | source |
//! |---|---|---|---|---|
//! | `ims` | tab-separated, 4 or 8 numeric columns, exactly 20 480 rows | 20 kHz | `1`..`8` | IMS readme (Lee et al. 2007) |
//! | `femto` | 6 comma/semicolon columns, first four integer hour, minute, second, µs | 25.6 kHz | `horiz`, `vert` (g) | PRONOSTIA (Nectoux et al. 2012) |
//! | `xjtu-sy` | header `Horizontal_vibration_signals,Vertical_vibration_signals` | 25.6 kHz | the two headers | XJTU-SY (Wang et al. 2018) |

use std::path::Path;

use serde_json::json;

use super::error::IoError;
use super::ims::{read_ims_snapshot, IMS_ROWS, MAX_SNAPSHOT_BYTES};
use super::record::{check_finite, check_fs, check_rpm, Record};
use super::ReadOptions;

/// FEMTO/PRONOSTIA accelerometer sample rate, Hz (25.6 kHz; Nectoux et al., IEEE PHM 2012).
pub const FEMTO_FS: f64 = 25_600.0;
/// XJTU-SY sample rate, Hz (25.6 kHz; Wang et al., IEEE Trans. Reliability 69, 2020).
pub const XJTU_FS: f64 = 25_600.0;
/// XJTU-SY column headers.
pub const XJTU_HEADER: [&str; 2] = ["Horizontal_vibration_signals", "Vertical_vibration_signals"];

/// A recognised text layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TextLayout {
    /// IMS raw ASCII snapshot with this many columns.
    Ims(usize),
    /// FEMTO/PRONOSTIA `acc_*.csv` snapshot (the column separator).
    Femto(u8),
    /// XJTU-SY CSV.
    XjtuSy,
}

impl TextLayout {
    /// Layout name as reported (`ims`, `femto`, `xjtu-sy`).
    pub fn name(&self) -> &'static str {
        match self {
            TextLayout::Ims(_) => "ims",
            TextLayout::Femto(_) => "femto",
            TextLayout::XjtuSy => "xjtu-sy",
        }
    }
}

fn femto_time(cells: &[&str]) -> bool {
    let lim = [24.0, 60.0, 61.0, 1e6];
    cells.len() == 6
        && cells.iter().take(4).zip(lim).all(|(c, l)| {
            c.trim()
                .parse::<f64>()
                .is_ok_and(|v| v.fract() == 0.0 && (0.0..l).contains(&v))
        })
        && cells
            .iter()
            .skip(4)
            .all(|c| c.trim().parse::<f64>().is_ok_and(f64::is_finite))
}

/// The first 4096 bytes of `path` (what the layout is recognised from).
fn read_head(path: &Path) -> Result<Vec<u8>, IoError> {
    use std::io::Read;
    let f = std::fs::File::open(path).map_err(|e| IoError::io(path, "open", e))?;
    let mut buf = Vec::with_capacity(4096);
    f.take(4096)
        .read_to_end(&mut buf)
        .map_err(|e| IoError::io(path, "read", e))?;
    Ok(buf)
}

/// The first line of `path` (trimmed, a UTF-8 byte order mark dropped), read from its first
/// 4096 bytes only: what a text layout is recognised from, and what a FEMTO snapshot's clock
/// and separator are taken from, without reading a file of any size whole. Empty for an
/// empty file. The mark is what spreadsheet programs write before a CSV's first cell; the
/// readers behind the layouts (the `csv` crate) skip it too.
pub fn first_line(path: &Path) -> Result<String, IoError> {
    let head = read_head(path)?;
    let body = head.strip_prefix(b"\xef\xbb\xbf").unwrap_or(&head);
    let text = String::from_utf8_lossy(body);
    Ok(text.lines().next().map(str::trim).unwrap_or("").to_string())
}

/// Recognise the layout of a text file from its content: the first line and, for IMS, the
/// number of rows. `None` if it is none of the layouts (the generic CSV reader applies then).
pub fn sniff_text(path: &Path) -> Result<Option<TextLayout>, IoError> {
    let len = std::fs::metadata(path)
        .map_err(|e| IoError::io(path, "stat", e))?
        .len();
    let first = first_line(path)?;
    if first.is_empty() {
        return Ok(None);
    }
    let cells: Vec<&str> = first.split(',').map(str::trim).collect();
    if cells.len() == 2
        && cells
            .iter()
            .zip(XJTU_HEADER)
            .all(|(c, h)| c.trim_matches('"').eq_ignore_ascii_case(h))
    {
        return Ok(Some(TextLayout::XjtuSy));
    }
    if femto_time(&cells) {
        return Ok(Some(TextLayout::Femto(b',')));
    }
    let semi: Vec<&str> = first.split(';').collect();
    if femto_time(&semi) {
        return Ok(Some(TextLayout::Femto(b';')));
    }
    if first.contains('\t') && !first.contains(',') && len <= MAX_SNAPSHOT_BYTES {
        let cols: Vec<&str> = first.split_whitespace().collect();
        if matches!(cols.len(), 4 | 8) && cols.iter().all(|c| c.parse::<f64>().is_ok()) {
            let bytes = std::fs::read(path).map_err(|e| IoError::io(path, "read", e))?;
            let rows = bytes
                .split(|&b| b == b'\n')
                .filter(|l| l.iter().any(|b| !b.is_ascii_whitespace()))
                .count();
            if rows == IMS_ROWS {
                return Ok(Some(TextLayout::Ims(cols.len())));
            }
        }
    }
    Ok(None)
}

/// Read one channel of a file of a recognised text layout.
pub fn read_layout(path: &Path, layout: TextLayout, opts: &ReadOptions) -> Result<Record, IoError> {
    let mut rec = match layout {
        TextLayout::Ims(ncols) => {
            let ch = match opts.channel.as_deref() {
                None => 1,
                Some(c) => c
                    .strip_prefix("ch")
                    .unwrap_or(c)
                    .parse::<usize>()
                    .ok()
                    .filter(|k| (1..=ncols).contains(k))
                    .ok_or_else(|| IoError::UnknownChannel {
                        path: path.to_path_buf(),
                        requested: c.to_string(),
                        available: (1..=ncols)
                            .map(|k| format!("{k} (IMS channels count from 1)"))
                            .collect(),
                    })?,
            };
            let mut r = read_ims_snapshot(path, ch)?;
            r.bearing = Some("ims-za2115".into());
            r
        }
        TextLayout::Femto(sep) => read_femto(path, sep, opts.channel.as_deref())?,
        TextLayout::XjtuSy => {
            check_xjtu_header(path)?;
            let o = ReadOptions {
                channel: Some(
                    opts.channel
                        .clone()
                        .unwrap_or_else(|| XJTU_HEADER[0].into()),
                ),
                fs: Some(opts.fs.unwrap_or(XJTU_FS)),
                rpm: opts.rpm,
            };
            let mut r = super::csv::read_csv(path, &o)?;
            r.bearing = Some("xjtu-ldk-uer204".into());
            r.unit = "g".into();
            r
        }
    };
    let fs_source = match opts.fs {
        Some(f) => {
            rec.fs = check_fs(path, f)?;
            "argument".to_string()
        }
        None => format!("layout:{}", layout.name()),
    };
    // FEMTO and XJTU-SY files hold no speed or load; the sets' folder names state them
    // (`io::conditions`), used when neither an argument nor a sidecar gave a speed.
    let set = match layout {
        TextLayout::XjtuSy => Some(super::conditions::ConditionSet::Xjtu),
        TextLayout::Femto(_) => Some(super::conditions::ConditionSet::Femto),
        TextLayout::Ims(_) => None,
    };
    let named = match (set, opts.rpm, rec.rpm, path.parent()) {
        (Some(set), None, None, Some(dir)) => super::conditions::from_folder_names(
            &std::fs::canonicalize(dir).unwrap_or(dir.to_path_buf()),
            set,
        ),
        _ => None,
    };
    let rpm_source = match (opts.rpm, &named) {
        (Some(r), _) => {
            rec.rpm = Some(check_rpm(path, r)?);
            Some("argument".to_string())
        }
        (None, Some(n)) => {
            rec.rpm = Some(n.rpm);
            Some(format!("layout:{}(folder name)", layout.name()))
        }
        (None, None) => rec.rpm.map(|_| format!("layout:{}", layout.name())),
    };
    if let Some(m) = rec.meta.as_object_mut() {
        m.insert("layout".into(), json!(layout.name()));
        m.insert("fs_source".into(), json!(fs_source));
        m.insert("rpm_source".into(), json!(rpm_source));
        if let Some(n) = &named {
            m.insert("rpm_detail".into(), json!(n.source));
            m.insert("load".into(), json!(n.load_n));
            m.insert("load_source".into(), json!(n.source));
        }
    }
    set_details(&mut rec, layout.name(), opts);
    Ok(rec)
}

/// Sets `fs_detail` and `rpm_detail` in the `meta` of a record of the data set `name`
/// (`ims`, `femto`, `xjtu-sy`) read at its documented rate and speed: `--fs`/`--rpm` when
/// `opts` gives them, else `NAME layout (RATE Hz, documented)` (a speed the reader found
/// elsewhere, e.g. a sidecar's, keeps its own detail).
pub(crate) fn set_details(rec: &mut Record, name: &str, opts: &ReadOptions) {
    use super::sidecar::{ARGUMENT_FS, ARGUMENT_RPM};
    let fs = match opts.fs {
        Some(_) => ARGUMENT_FS.to_string(),
        None => format!("{name} layout ({} Hz, documented)", rec.fs),
    };
    let found = rec.meta.get("rpm_detail").filter(|d| !d.is_null()).cloned();
    let rpm = match (opts.rpm, rec.rpm, found) {
        (Some(_), _, _) => json!(ARGUMENT_RPM),
        (None, _, Some(d)) => d,
        (None, Some(r), None) => json!(format!("{name} layout ({r} rpm, documented)")),
        (None, None, None) => json!(null),
    };
    if let Some(m) = rec.meta.as_object_mut() {
        m.insert("fs_detail".into(), json!(fs));
        m.insert("rpm_detail".into(), rpm);
    }
}

/// FEMTO/PRONOSTIA `acc_NNNNN.csv`: rows of hour, minute, second, microsecond, horizontal and
/// vertical acceleration (g); 2 560 rows = 0.1 s at [`FEMTO_FS`]. Channel `horiz` (default) or
/// `vert` (also `4`/`5`, zero-based columns).
pub fn read_femto(path: &Path, sep: u8, channel: Option<&str>) -> Result<Record, IoError> {
    let col = match channel.map(|c| c.to_ascii_lowercase()) {
        None => 4,
        Some(c) if matches!(c.as_str(), "horiz" | "horizontal" | "h" | "4") => 4,
        Some(c) if matches!(c.as_str(), "vert" | "vertical" | "v" | "5") => 5,
        Some(c) => {
            return Err(IoError::UnknownChannel {
                path: path.to_path_buf(),
                requested: c,
                available: vec!["horiz".into(), "vert".into()],
            })
        }
    };
    let bytes = super::record::read_capped(
        path,
        MAX_SNAPSHOT_BYTES,
        "FEMTO snapshot",
        &format!("{MAX_SNAPSHOT_BYTES} bytes (a FEMTO snapshot is about 100 kB)"),
    )?;
    let text = String::from_utf8_lossy(&bytes);
    let mut samples = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        let cells: Vec<&str> = line.split(sep as char).collect();
        if cells.len() != 6 {
            return Err(IoError::malformed(
                path,
                format!(
                    "line {}: {} columns, the FEMTO layout has 6 (hour, min, s, µs, horiz, vert)",
                    i + 1,
                    cells.len()
                ),
            ));
        }
        let cell = cells.get(col).map_or("", |c| c.trim());
        let v: f64 = cell
            .parse()
            .map_err(|_| femto_not_a_number(path, i + 1, &cells, samples.is_empty()))?;
        samples.push(v);
    }
    if samples.is_empty() {
        return Err(IoError::truncated(path, "no data rows"));
    }
    let name = if col == 4 { "horiz" } else { "vert" };
    check_finite(path, name, &samples)?;
    let rows = samples.len();
    Ok(Record {
        samples,
        fs: FEMTO_FS,
        rpm: None,
        channel: name.into(),
        unit: "g".into(),
        source: path.to_path_buf(),
        bearing: None,
        meta: json!({
            "format": "femto-csv",
            "n_rows": rows,
            "rows_note": "a PRONOSTIA snapshot has 2560 rows (0.1 s at 25.6 kHz); the speed (1800/1650/1500 rpm by operating condition) is not in the file: pass --rpm",
        }),
    })
}

/// The FEMTO columns, in file order.
const FEMTO_COLUMNS: [&str; 6] = ["hour", "minute", "second", "µs", "horiz", "vert"];

/// The error of a FEMTO row whose channel cell is not a number: the first cell of the row
/// that is not a number, its column, and why it may not be: a decimal comma, or, for the
/// first row of the file, a header row the layout does not have.
fn femto_not_a_number(path: &Path, line: usize, cells: &[&str], first_row: bool) -> IoError {
    let (k, cell) = cells
        .iter()
        .map(|c| c.trim())
        .enumerate()
        .find(|(_, c)| c.parse::<f64>().is_err())
        .unwrap_or((0, ""));
    // `0,0346` in a `;`-separated file: a spreadsheet of a decimal-comma locale.
    let decimal_comma = cell.contains(',') && cell.replacen(',', ".", 1).parse::<f64>().is_ok();
    let header = if decimal_comma {
        "; it has a decimal comma: FEMTO numbers take `.` as the decimal point (write 0.0346, not 0,0346)"
    } else if first_row {
        "; a header row? FEMTO files have none: every row is hour, minute, second, µs, horiz, vert, all numbers"
    } else {
        ""
    };
    IoError::malformed(
        path,
        format!(
            "line {line}: {cell:?} ({}, column {}) is not a number{header}",
            FEMTO_COLUMNS.get(k).copied().unwrap_or("?"),
            k + 1
        ),
    )
}

/// Refuses an XJTU-SY file whose first line is not its header row
/// `Horizontal_vibration_signals,Vertical_vibration_signals` (the channels are named by it),
/// saying whether the row is missing or another one.
fn check_xjtu_header(path: &Path) -> Result<(), IoError> {
    if sniff_text(path)? == Some(TextLayout::XjtuSy) {
        return Ok(());
    }
    let first = first_line(path)?;
    let first = first.as_str();
    let numbers = !first.is_empty()
        && first
            .split(',')
            .all(|c| c.trim().parse::<f64>().is_ok_and(f64::is_finite));
    let shown: String = first.chars().take(80).collect();
    let header = XJTU_HEADER.join(",");
    Err(IoError::malformed(
        path,
        if numbers {
            format!("the file lacks the XJTU-SY header row `{header}` (its first line is data: {shown:?}); the layout names its two channels by it")
        } else if first.is_empty() {
            format!("the first line is empty, not the XJTU-SY header row `{header}`")
        } else {
            format!("the first line {shown:?} is not the XJTU-SY header row `{header}`")
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::read_any;

    /// The first line comes from the file's head only: a FEMTO clock row followed by a
    /// 64 MiB line (no newline) is read as that row, and an empty file gives "".
    #[test]
    fn first_line_reads_the_head_of_a_file_of_any_size() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("acc_00001.csv");
        let mut body = b"9;39;39;65664;0.552;-0.146\n".to_vec();
        body.resize(body.len() + (64 << 20), b'1');
        std::fs::write(&p, &body).unwrap();
        assert_eq!(first_line(&p).unwrap(), "9;39;39;65664;0.552;-0.146");
        let e = dir.path().join("empty.csv");
        std::fs::write(&e, b"").unwrap();
        assert_eq!(first_line(&e).unwrap(), "");
        assert!(first_line(&dir.path().join("missing.csv")).is_err());
    }

    /// Probe defect: a `;`-separated FEMTO file with decimal commas was answered "a
    /// header row? FEMTO files have none". The decimal comma is named; a word in the first
    /// row still gets the header hint.
    #[test]
    fn a_decimal_comma_is_named_not_taken_for_a_header() {
        let p = Path::new("acc_00001.csv");
        let e = femto_not_a_number(p, 1, &["9", "0", "0", "0", "0,0346", "0,0892"], true);
        let e = e.to_string();
        assert!(e.contains("\"0,0346\" (horiz, column 5)"), "{e}");
        assert!(e.contains("decimal comma") && !e.contains("header"), "{e}");
        let e = femto_not_a_number(p, 1, &["hour", "min"], true).to_string();
        assert!(
            e.contains("a header row?") && !e.contains("decimal comma"),
            "{e}"
        );
    }

    fn opts(ch: Option<&str>) -> ReadOptions {
        ReadOptions {
            channel: ch.map(str::to_string),
            ..ReadOptions::default()
        }
    }

    #[test]
    fn recognised_by_content_not_name() {
        let dir = tempfile::tempdir().unwrap();
        // FEMTO: hour, min, s, µs, horiz, vert.
        let femto: String = (0..2560)
            .map(|i| {
                format!(
                    "9,39,39,{},{:.3},{:.3}\n",
                    65664 + i * 39,
                    (i as f64).sin(),
                    -0.5
                )
            })
            .collect();
        let p = dir.path().join("data1.csv");
        std::fs::write(&p, &femto).unwrap();
        let r = read_any(&p, &opts(None)).unwrap();
        assert_eq!(
            (r.fs, r.channel.as_str(), r.samples.len()),
            (FEMTO_FS, "horiz", 2560)
        );
        assert_eq!(r.meta["fs_source"], "layout:femto");
        assert_eq!(read_any(&p, &opts(Some("vert"))).unwrap().samples[0], -0.5);
        // XJTU-SY.
        let mut x = String::from("Horizontal_vibration_signals,Vertical_vibration_signals\n");
        for i in 0..1000 {
            x.push_str(&format!("{},{}\n", (i as f64 * 0.1).sin(), i));
        }
        let p = dir.path().join("1.csv");
        std::fs::write(&p, &x).unwrap();
        let r = read_any(&p, &opts(None)).unwrap();
        assert_eq!((r.fs, r.samples.len()), (XJTU_FS, 1000));
        assert_eq!(r.meta["layout"], "xjtu-sy");
        assert_eq!(r.bearing.as_deref(), Some("xjtu-ldk-uer204"));
        let r = read_any(&p, &opts(Some("Vertical_vibration_signals"))).unwrap();
        assert_eq!(r.samples[3], 3.0);
        // IMS: 20 480 rows of 4 tab-separated values, any name.
        let ims: String = (0..IMS_ROWS)
            .map(|i| format!("{:.3}\t0.1\t-0.2\t{}\n", (i as f64).cos(), i % 7))
            .collect();
        let p = dir.path().join("snapshot.txt");
        std::fs::write(&p, &ims).unwrap();
        let r = read_any(&p, &opts(Some("4"))).unwrap();
        assert_eq!((r.fs, r.rpm, r.samples[8]), (20_000.0, Some(2000.0), 1.0));
        assert_eq!(r.bearing.as_deref(), Some("ims-za2115"));
        assert!(read_any(&p, &opts(Some("5"))).is_err());
        // One row fewer is not an IMS snapshot: the generic CSV reader wants a rate.
        let short: String = ims.lines().skip(1).map(|l| format!("{l}\n")).collect();
        std::fs::write(&p, &short).unwrap();
        assert!(sniff_text(&p).unwrap().is_none());
    }

    /// The sets' folder names give the speed and load their files lack (`io::conditions`);
    /// an argument wins, and a file elsewhere has none.
    #[test]
    fn xjtu_and_femto_files_take_speed_and_load_from_their_folder_names() {
        let dir = tempfile::tempdir().unwrap();
        let x = dir.path().join("37.5Hz11kN/Bearing2_1");
        std::fs::create_dir_all(&x).unwrap();
        let mut text = String::from("Horizontal_vibration_signals,Vertical_vibration_signals\n");
        for i in 0..1000 {
            text.push_str(&format!("{},0.5\n", (i as f64 * 0.1).sin()));
        }
        std::fs::write(x.join("7.csv"), &text).unwrap();
        let r = read_any(x.join("7.csv"), &opts(None)).unwrap();
        assert_eq!(r.rpm, Some(2250.0));
        assert_eq!(r.meta["load"], 11000.0);
        assert_eq!(r.meta["rpm_source"], "layout:xjtu-sy(folder name)");
        assert!(r.meta["rpm_detail"]
            .as_str()
            .unwrap()
            .contains("`37.5Hz11kN`"));
        let given = ReadOptions {
            rpm: Some(2000.0),
            ..ReadOptions::default()
        };
        let r = read_any(x.join("7.csv"), &given).unwrap();
        assert_eq!((r.rpm, r.meta.get("load")), (Some(2000.0), None));
        std::fs::write(dir.path().join("7.csv"), &text).unwrap();
        assert_eq!(
            read_any(dir.path().join("7.csv"), &opts(None)).unwrap().rpm,
            None
        );
        let f = dir.path().join("Learning_set/Bearing3_1");
        std::fs::create_dir_all(&f).unwrap();
        let femto: String = (0..2560)
            .map(|i| format!("9,39,39,{},{:.3},-0.5\n", 65664 + i * 39, (i as f64).sin()))
            .collect();
        std::fs::write(f.join("acc_00001.csv"), femto).unwrap();
        let r = read_any(f.join("acc_00001.csv"), &opts(None)).unwrap();
        assert_eq!(
            (r.rpm, r.meta["load"].as_f64()),
            (Some(1500.0), Some(5000.0))
        );
    }

    #[test]
    fn a_femto_header_row_is_named_as_such() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("acc_00001.csv");
        std::fs::write(&p, "hour,min,sec,usec,horiz,vert\n9,0,0,0.0,0.5,0.25\n").unwrap();
        let e = read_femto(&p, b',', None).unwrap_err().to_string();
        // The first cell that is not a number is `hour`, not the channel's `horiz`.
        assert!(
            e.contains("line 1: \"hour\" (hour, column 1) is not a number"),
            "{e}"
        );
        assert!(
            e.contains("header row") && e.contains("FEMTO files have none"),
            "{e}"
        );
        // A bad cell further down is not called a header.
        std::fs::write(&p, "9,0,0,0.0,0.5,0.25\n9,0,0,39.0,x,0.25\n").unwrap();
        let e = read_femto(&p, b',', None).unwrap_err().to_string();
        assert!(
            e.contains("line 2: \"x\" (horiz, column 5)") && !e.contains("header"),
            "{e}"
        );
    }

    #[test]
    fn an_xjtu_file_without_its_header_row_says_so() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("3.csv");
        std::fs::write(&p, "0.5,0.25\n-0.5,0.125\n").unwrap();
        let e = read_layout(&p, TextLayout::XjtuSy, &opts(None))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("lacks the XJTU-SY header row `Horizontal_vibration_signals,Vertical_vibration_signals`"),
            "{e}"
        );
        std::fs::write(&p, "horizontal,vertical\n-0.5,0.125\n").unwrap();
        let e = read_layout(&p, TextLayout::XjtuSy, &opts(None))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("\"horizontal,vertical\" is not the XJTU-SY header row"),
            "{e}"
        );
    }
}
