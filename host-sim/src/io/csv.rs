//! Generic CSV reader: one or more numeric columns, optional header row.
//!
//! Format (RFC 4180 as read by the `csv` crate): comma-separated; tab-separated when the
//! first line has tabs and no commas; semicolon-separated when it has semicolons and no tabs
//! (spreadsheet exports of locales that write a decimal comma); separated by spaces when the
//! first line has spaces between values and no comma, semicolon or tab (numpy's `savetxt`,
//! MATLAB's `save -ascii`: runs of spaces count as one, [`super::space_runs`]). Without
//! commas as separators a number may use a decimal comma (`-0,125`); so may the rows of a
//! one-column file when its first lines say so ([`super::csv_shape::one_column_commas`]). Lines starting with `#` are comments; cells are
//! trimmed.
//! The first row is a header if any of its cells is not a number. Every data cell of the chosen
//! column must parse as a finite `f64` (`NaN`/`inf` cells are [`IoError::NonFinite`]).
//!
//! Column choice ([`ReadOptions::channel`]): a header name (exact, then case-insensitive) or a
//! zero-based index. Default: the sidecar's first column, else the first column that is
//! neither a time column by its header (`time`, `t`, `Zeit`, with a unit: `time_s`,
//! `Time (ms)`, `t [us]`; [`super::time_column`]) nor a ramp by its content (strictly rising,
//! uniform steps: [`super::time_column::RampScan`], found in a first pass over the rows), else
//! the first that is not a time column by its header, else column 0. Without a time column
//! by its header, the first ramp beside the chosen column is the time axis
//! ([`super::time_column::ramp_role`]: its header's unit, else seconds; a counter or a ramp in
//! another unit gives no rate). A column taken by its name (the
//! requested, the sidecar's, the default or the time column) whose name appears more than
//! once in the header is refused naming both positions: which one was meant is not known
//! (select it by its index instead).
//!
//! Sample rate: argument (which must agree within 0.1 % with a sidecar `fs` and a time column),
//! else sidecar `fs` (see [`crate::io::sidecar`]), else derived from a time
//! column in seconds, milliseconds, microseconds or nanoseconds (uniform spacing required; a
//! `time` column in another unit is refused naming it); a sidecar and a time column that disagree by more
//! than 1 ppm are a contradiction. The CSV written by [`crate::io::write_outputs`] reads back
//! exactly.

use std::path::Path;

use serde_json::json;

use super::csv_shape::{one_column_commas, OneColumn};
use super::error::IoError;
use super::record::{check_finite, Record};
use super::sidecar::{check_n_samples, resolve_fs, sidecar_for, sidecar_record};
use super::space_runs::{LineCap, MAX_LINE_BYTES};
use super::time_column::{
    decimals, fs_from_time, ramp_role, time_column, time_unit, RampRole, RampScan, TimeUnit,
};
use super::write::unit_from_column_name;
use super::ReadOptions;

/// Read one numeric column of a CSV file as a [`Record`] (see the module doc for the rules).
pub fn read_csv(path: impl AsRef<Path>, opts: &ReadOptions) -> Result<Record, IoError> {
    let path = path.as_ref();
    let sidecar = sidecar_for(path)?;
    let head = {
        use std::io::Read;
        let mut f = std::fs::File::open(path).map_err(|e| IoError::io(path, "open", e))?;
        let mut buf = vec![0u8; 4096];
        let mut n = 0;
        while n < buf.len() {
            match f.read(&mut buf[n..]) {
                Ok(0) => break,
                Ok(k) => n += k,
                Err(e) => return Err(IoError::io(path, "read", e)),
            }
        }
        buf.truncate(n);
        buf
    };
    if head.is_empty() {
        return Err(IoError::truncated(path, "empty file (no rows)"));
    }
    // The separator is decided on the first line that is data or header: a `#` comment
    // above it (a DAQ's "# exported by X, fs=25600") is free text, skipped like the reader
    // skips it.
    let mut content = head
        .split(|&b| b == b'\n')
        .map(|l| l.strip_prefix(b"\xef\xbb\xbf").unwrap_or(l))
        .filter(|l| !l.starts_with(b"#") && l.iter().any(|b| !b.is_ascii_whitespace()));
    let first_line = content.next().unwrap_or(&[]);
    let has = |b: u8| first_line.contains(&b);
    // Values separated by spaces only (numpy's `savetxt`, MATLAB's `save -ascii`): the
    // first two lines have no comma, semicolon or tab and two or more words each (a
    // one-column file whose header has a space, `Accel (g)`, stays one column). Runs of
    // spaces become one space before the `csv` crate sees them.
    let words = |l: &[u8]| {
        !l.iter().any(|b| matches!(b, b',' | b';' | b'\t'))
            && l.split(|b| b.is_ascii_whitespace())
                .filter(|w| !w.is_empty())
                .count()
                >= 2
    };
    let spaced = words(first_line) && content.next().is_none_or(words);
    // A one-column file written with decimal commas (`-0,125`): its rows would split on the
    // comma into an integer part and a fraction. Read them as one column of numbers when
    // the rows say so, refuse when they cannot tell ([`one_column_commas`]).
    // (A `;` anywhere, even on a line not decoded here, rules it out: `;` is then the
    // separator, and one column uses `;` as its no-separator.)
    let one_column_dc = !spaced
        && !has(b';')
        && {
            let complete = if head.len() == 4096 {
                &head[..head.iter().rposition(|&b| b == b'\n').unwrap_or(0)]
            } else {
                &head[..]
            };
            let lines: Vec<&str> = complete
                .split(|&b| b == b'\n')
                .map(|l| l.strip_prefix(b"\xef\xbb\xbf").unwrap_or(l))
                .filter_map(|l| std::str::from_utf8(l).ok())
                .map(str::trim)
                .filter(|l| !l.starts_with('#') && !l.is_empty())
                .collect();
            match one_column_commas(&lines) {
            OneColumn::DecimalComma => true,
            OneColumn::Columns => false,
            OneColumn::Ambiguous(example) => {
                return Err(IoError::malformed(
                    path,
                    format!(
                        "every row is two whole numbers joined by a comma ({example:?}): a column of numbers with a decimal comma, or two integer columns? Add a header line: one name (`accel`) reads one column with decimal commas, two names (`a,b`) two columns"
                    ),
                ))
            }
        }
        };
    let delim = if one_column_dc {
        // No separator: each row is one cell, its comma the decimal mark.
        b';'
    } else if spaced {
        b' '
    } else if has(b'\t') && !has(b',') {
        b'\t'
    } else if has(b';') && !has(b'\t') {
        b';'
    } else {
        b','
    };
    // A decimal comma cannot be told from a separator in a comma-separated file.
    let decimal_comma = delim != b',';
    debug_assert!(!one_column_dc || (decimal_comma && !has(b';')));
    let number = |cell: &str| -> Option<f64> {
        match cell.parse::<f64>() {
            Ok(v) => Some(v),
            Err(_) if decimal_comma && cell.matches(',').count() == 1 && !cell.contains('.') => {
                cell.replace(',', ".").parse().ok()
            }
            Err(_) => None,
        }
    };
    let open = || -> Result<_, IoError> {
        let file = std::fs::File::open(path).map_err(|e| IoError::io(path, "open", e))?;
        let file = LineCap::new(file, MAX_LINE_BYTES);
        let source: Box<dyn std::io::Read> = if spaced {
            Box::new(super::space_runs::SpaceRuns::new(file))
        } else {
            Box::new(file)
        };
        Ok(::csv::ReaderBuilder::new()
            .has_headers(false)
            .delimiter(delim)
            .comment(Some(b'#'))
            .trim(::csv::Trim::All)
            .flexible(false)
            .from_reader(std::io::BufReader::new(source)))
    };
    let scans = scan_ramps(path, open()?, &number)?;
    let ramp = |i: usize| scans.get(i).is_some_and(RampScan::is_ramp);
    let mut rdr = open()?;

    let mut rec = ::csv::StringRecord::new();
    let mut header: Option<Vec<String>> = None;
    let mut ncols = 0usize;
    let mut col = usize::MAX;
    let mut time_col: Option<(usize, TimeUnit)> = None;
    // How the time column was found (`header` or `content`) and whether its unit (seconds)
    // was assumed; ramp columns neither analysed nor the time axis.
    let mut time_found: Option<(&str, bool)> = None;
    let mut ramps_skipped: Vec<serde_json::Value> = Vec::new();
    let mut samples: Vec<f64> = Vec::new();
    let mut times: Vec<f64> = Vec::new();
    // Most decimals printed in a time cell (`None` once one is in exponent form: full
    // precision), for the rounding the spacing check allows.
    let mut time_decimals: Option<usize> = Some(0);
    let mut first = true;
    loop {
        match rdr.read_record(&mut rec) {
            Ok(false) => break,
            Ok(true) => {}
            Err(e) => return Err(csv_err(path, e)),
        }
        let line = rec.position().map(|p| p.line()).unwrap_or(0);
        if first {
            first = false;
            ncols = rec.len();
            let all_numeric = rec.iter().all(|c| number(c).is_some());
            let names: Vec<String> = if all_numeric {
                (0..ncols).map(|i| format!("col{i}")).collect()
            } else {
                rec.iter().map(str::to_string).collect()
            };
            col = choose_column(path, &names, !all_numeric, opts, sidecar.as_ref(), &ramp)?;
            // A requested column that its header names a time axis is no signal (probe of
            // stop 69: `--channel 0` on simulate.csv analysed `time_s`).
            if let (Some(req), false) = (opts.channel.as_deref(), all_numeric) {
                if time_column(path, &names[col]).ok().flatten().is_some() {
                    return Err(IoError::malformed(
                        path,
                        format!(
                            "--channel {req}: column {:?} is the time axis (by its header), not a signal; choose a signal column",
                            names[col]
                        ),
                    ));
                }
            }
            if !all_numeric {
                for (i, n) in names.iter().enumerate().filter(|&(i, _)| i != col) {
                    if let (Some(u), None) = (time_column(path, n)?, time_col) {
                        time_col = Some((unique(path, &names, i)?, u));
                        time_found = Some(("header", false));
                    }
                }
            }
            // Ramps found by content: the first one in a time unit is the time axis when no
            // header names one; the others are reported as not analysed.
            for i in (0..ncols).filter(|&i| i != col && ramp(i)) {
                if time_col.is_some_and(|(t, _)| t == i) {
                    continue;
                }
                let taken_as = match (ramp_role(&names[i], &scans[i]), time_col) {
                    (RampRole::Time { unit, assumed }, None) => {
                        time_col = Some((i, unit));
                        time_found = Some(("content", assumed));
                        continue;
                    }
                    (RampRole::Time { unit, .. }, Some(_)) => {
                        format!("a second time axis ({})", unit.symbol)
                    }
                    (RampRole::Counter, _) => "a sample counter".to_string(),
                    (RampRole::Other(u), _) => format!("a ramp in {u}"),
                };
                ramps_skipped.push(json!({"index": i, "name": names[i], "taken_as": taken_as}));
            }
            header = Some(names);
            if !all_numeric {
                continue;
            }
        }
        let names = header.as_deref().unwrap_or(&[]);
        let cell = &rec[col];
        let v: f64 = number(cell).ok_or_else(|| {
            IoError::malformed(
                path,
                format!(
                    "line {line}, column {:?}: {cell:?} is not a number",
                    names[col]
                ),
            )
        })?;
        samples.push(v);
        // Rows are streamed: refuse past the limit instead of growing with the file.
        let kept = if time_col.is_some() { 2 } else { 1 };
        super::record::check_record_size(path, samples.len(), kept * samples.len())?;
        if let Some((t, _)) = time_col {
            let cell = &rec[t];
            let tv: f64 = number(cell).ok_or_else(|| {
                IoError::malformed(
                    path,
                    format!(
                        "line {line}, column {:?}: {cell:?} is not a number",
                        names[t]
                    ),
                )
            })?;
            times.push(tv);
            time_decimals = time_decimals.zip(decimals(cell)).map(|(a, b)| a.max(b));
        }
    }
    if samples.is_empty() {
        // A header alone may be a file cut short after its first line, or a text file that
        // is no CSV at all: the message shows the line it read as the header.
        return Err(IoError::truncated(
            path,
            match &header {
                Some(h) => format!(
                    "no data rows after the header line {:?} (a CSV holds one sample per row, a number in each column)",
                    h.join(",")
                ),
                None => "no data rows".into(),
            },
        ));
    }
    let names = header.unwrap_or_default();
    let channel = names[col].clone();
    check_finite(path, &channel, &samples)?;
    check_n_samples(sidecar.as_ref(), path, samples.len())?;

    let how = |assumed: bool| match (time_found, assumed) {
        (Some(("content", _)), true) => {
            " (found by content: strictly rising, uniform steps; no unit stated, taken as s)"
        }
        (Some(("content", _)), false) => " (found by content: strictly rising, uniform steps)",
        _ => "",
    };
    let from_time = match time_col {
        Some((t, unit)) => fs_from_time(path, &names[t], &times, time_decimals, unit)?.map(|f| {
            let assumed = time_found.is_some_and(|(_, a)| a);
            (f, format!("time column `{}`{}", names[t], how(assumed)))
        }),
        None => None,
    };
    let time_meta = time_col.map(|(t, unit)| {
        json!({
            "index": t,
            "name": names[t],
            "unit": unit.symbol,
            "found_by": time_found.map_or("header", |(f, _)| f),
            "unit_assumed": time_found.is_some_and(|(_, a)| a),
        })
    });
    let fs = resolve_fs(
        path,
        opts.fs,
        sidecar.as_ref(),
        from_time.as_ref().map(|(f, what)| (*f, what.as_str())),
        &|a, b| ((a - b) / a).abs() <= 1e-6,
    )?;
    let unit = sidecar
        .as_ref()
        .and_then(|s| s.unit_of(&channel))
        .unwrap_or_else(|| unit_from_column_name(&channel))
        .to_string();
    sidecar_record(
        path,
        samples,
        (channel, unit),
        fs,
        opts.rpm,
        sidecar.as_ref(),
        json!({
            "format": "csv",
            "columns": names,
            "column_index": col,
            "n_columns": ncols,
            "time_column": time_meta,
            "ramp_columns_not_analysed": ramps_skipped,
        }),
    )
}

/// Per column, whether its values form a ramp ([`RampScan`]): one pass over the data rows
/// (the first row is left out when it is a header), before the column is chosen. Stops past
/// the record size limit, which the reading pass then refuses.
fn scan_ramps<R: std::io::Read>(
    path: &Path,
    mut rdr: ::csv::Reader<R>,
    number: &dyn Fn(&str) -> Option<f64>,
) -> Result<Vec<RampScan>, IoError> {
    let mut rec = ::csv::StringRecord::new();
    let mut scans: Vec<RampScan> = Vec::new();
    let mut rows = 0usize;
    let mut first = true;
    while rdr.read_record(&mut rec).map_err(|e| csv_err(path, e))? {
        if first {
            first = false;
            // One column has no time column beside it.
            if rec.len() < 2 {
                return Ok(Vec::new());
            }
            scans = vec![RampScan::default(); rec.len()];
            if !rec.iter().all(|c| number(c).is_some()) {
                continue;
            }
        }
        rows += 1;
        if rows > super::record::MAX_RECORD_SAMPLES {
            break;
        }
        for (s, c) in scans.iter_mut().zip(rec.iter()) {
            s.push(number(c));
        }
    }
    Ok(scans)
}

fn csv_err(path: &Path, e: ::csv::Error) -> IoError {
    let pos = e
        .position()
        .map(|p| format!("line {}: ", p.line()))
        .unwrap_or_default();
    match e.into_kind() {
        ::csv::ErrorKind::Io(io) if io.kind() == std::io::ErrorKind::FileTooLarge => {
            IoError::TooLarge {
                path: path.to_path_buf(),
                what: format!("{pos}{io}"),
                limit: format!("{MAX_LINE_BYTES} bytes per line"),
            }
        }
        ::csv::ErrorKind::Io(io) => IoError::io(path, "read", io),
        ::csv::ErrorKind::UnequalLengths {
            expected_len, len, ..
        } => {
            // One field in the first row, two below: `-86,678957` under `accel`.
            let hint = if expected_len == 1 && len == 2 {
                " (a decimal comma? a one-column file is read with decimal commas when every row of its first 4 KiB is `digits,digits`)"
            } else {
                ""
            };
            IoError::malformed(
                path,
                format!("{pos}row has {len} fields, the first row has {expected_len}{hint}"),
            )
        }
        ::csv::ErrorKind::Utf8 { err, .. } => {
            IoError::malformed(path, format!("{pos}not UTF-8: {err}"))
        }
        other => IoError::malformed(path, format!("{pos}{other:?}")),
    }
}

/// `i`, unless the name of column `i` appears again in the header: then which column the
/// name means is not known, and the record is refused naming both 0-based positions.
fn unique(path: &Path, names: &[String], i: usize) -> Result<usize, IoError> {
    match (0..names.len()).find(|&j| j != i && names[j] == names[i]) {
        None => Ok(i),
        Some(j) => Err(IoError::malformed(
            path,
            format!(
                "column name {:?} appears more than once in the header (columns {} and {}, counted from 0); rename one, or select the column by its index (--channel {})",
                names[i],
                i.min(j),
                i.max(j),
                i.min(j)
            ),
        )),
    }
}

fn choose_column(
    path: &Path,
    names: &[String],
    has_header: bool,
    opts: &ReadOptions,
    sidecar: Option<&super::sidecar::Sidecar>,
    ramp: &dyn Fn(usize) -> bool,
) -> Result<usize, IoError> {
    let unknown = |req: &str| IoError::UnknownChannel {
        path: path.to_path_buf(),
        requested: req.to_string(),
        available: names.to_vec(),
    };
    if let Some(req) = opts.channel.as_deref() {
        if let Some(i) = names.iter().position(|n| n == req) {
            return unique(path, names, i);
        }
        let folded: Vec<usize> = (0..names.len())
            .filter(|&i| names[i].eq_ignore_ascii_case(req))
            .collect();
        match folded.as_slice() {
            [i] => return Ok(*i),
            [a, b, ..] => {
                return Err(IoError::malformed(
                    path,
                    format!(
                        "--channel {req:?} matches columns {} ({:?}) and {} ({:?}) when case is ignored; give the exact name or the 0-based index",
                        a,
                        names[*a],
                        b,
                        names[*b]
                    ),
                ))
            }
            [] => {}
        }
        if let Ok(i) = req.parse::<usize>() {
            if i < names.len() {
                return Ok(i);
            }
        }
        return Err(unknown(req));
    }
    if has_header {
        if let Some(first) = sidecar.and_then(|s| s.columns.first()) {
            if let Some(i) = names.iter().position(|n| n == first) {
                return unique(path, names, i);
            }
        }
    }
    // Neither a time column by its header nor a ramp by its content (a time axis or a
    // counter, whatever it is called); else not one by its header.
    let time_named = |i: usize| has_header && time_unit(&names[i]).is_some();
    if let Some(i) = (0..names.len()).find(|&i| !time_named(i) && !ramp(i)) {
        return unique(path, names, i);
    }
    if has_header {
        if let Some(i) = (0..names.len()).find(|&i| !time_named(i)) {
            return unique(path, names, i);
        }
    }
    if names.is_empty() {
        return Err(unknown("0"));
    }
    Ok(0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::write_outputs;

    /// A requested channel that is the file's time axis is refused, by name or index.
    #[test]
    fn the_time_axis_is_no_channel() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("t.csv");
        std::fs::write(&p, "time_s,accel\n0.0,1\n0.5,-1\n1.0,2\n1.5,0\n").unwrap();
        for c in ["0", "time_s"] {
            let e = read_csv(&p, &opts(Some(c), None)).unwrap_err().to_string();
            assert!(e.contains("is the time axis"), "{e}");
        }
        assert_eq!(
            read_csv(&p, &opts(Some("1"), None)).unwrap().channel,
            "accel"
        );
    }

    fn opts(channel: Option<&str>, fs: Option<f64>) -> ReadOptions {
        ReadOptions {
            channel: channel.map(str::to_string),
            fs,
            rpm: None,
        }
    }

    #[test]
    fn round_trip_exact() {
        let dir = tempfile::tempdir().unwrap();
        let a: Vec<f64> = (0..1000)
            .map(|i| (i as f64 * 0.37).sin() * 1e-3 + 1e-310 * i as f64)
            .collect();
        let g: Vec<f64> = a.iter().map(|x| x / 9.80665).collect();
        let set = write_outputs(
            dir.path(),
            "rt",
            &[("accel_m_s2", &a), ("accel_g", &g)],
            25600.0,
            &json!({"rpm": 1500.0, "bearing": "cwru-6205-de"}),
        )
        .unwrap();
        let r = read_csv(&set.csv, &ReadOptions::default()).unwrap();
        assert_eq!(r.channel, "accel_m_s2");
        assert_eq!(r.samples, a);
        assert_eq!(r.fs, 25600.0);
        assert_eq!(r.rpm, Some(1500.0));
        assert_eq!(r.unit, "m/s^2");
        assert_eq!(r.bearing.as_deref(), Some("cwru-6205-de"));
        let r = read_csv(&set.csv, &opts(Some("accel_g"), None)).unwrap();
        assert_eq!(r.samples, g);
        assert_eq!(r.unit, "g");
        let r = read_csv(&set.csv, &opts(Some("2"), None)).unwrap();
        assert_eq!(r.samples, g);
        match read_csv(&set.csv, &opts(Some("nope"), None)).unwrap_err() {
            IoError::UnknownChannel { available, .. } => {
                assert_eq!(available, vec!["time_s", "accel_m_s2", "accel_g"])
            }
            e => panic!("{e:?}"),
        }
        // Without the sidecar the rate comes from the time column.
        std::fs::remove_file(&set.json).unwrap();
        let r = read_csv(&set.csv, &ReadOptions::default()).unwrap();
        assert!((r.fs - 25600.0).abs() < 1e-6, "{}", r.fs);
        assert_eq!(r.rpm, None);
    }

    /// Spreadsheet exports of decimal-comma locales: semicolon-separated with `-0,125`,
    /// tab-separated likewise; the same numbers as the comma-separated file. In a
    /// comma-separated file `1,5` stays two cells.
    #[test]
    fn semicolons_and_decimal_commas() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("x.csv");
        let want = vec![0.5, -0.125, 2.0, 1e-3];
        for text in [
            "time;acc\n0;0,5\n0,001;-0,125\n0,002;2\n0,003;1e-3\n",
            "time\tacc\n0\t0,5\n0,001\t-0,125\n0,002\t2\n0,003\t1e-3\n",
            "time;acc\n0;0.5\n0.001;-0.125\n0.002;2\n0.003;1e-3\n",
        ] {
            std::fs::write(&p, text).unwrap();
            let r = read_csv(&p, &ReadOptions::default()).unwrap();
            assert_eq!(r.samples, want, "{text:?}");
            assert_eq!(r.channel, "acc");
            assert!((r.fs - 1000.0).abs() < 1e-6, "{}", r.fs);
        }
        std::fs::write(&p, "a,b\n1,5\n2,5\n").unwrap();
        let r = read_csv(&p, &opts(Some("b"), Some(10.0))).unwrap();
        assert_eq!(r.samples, vec![5.0, 5.0]);
        // A cell that is not a number with either mark is still named.
        std::fs::write(&p, "a;b\n1,5;2\n1,5,5;3\n").unwrap();
        let e = read_csv(&p, &opts(Some("a"), Some(10.0))).unwrap_err();
        assert!(e.to_string().contains("\"1,5,5\" is not a number"), "{e}");
    }

    #[test]
    fn headerless_and_errors() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("x.csv");
        std::fs::write(&p, "1,2\n3,4\n5,6\n").unwrap();
        assert!(matches!(
            read_csv(&p, &ReadOptions::default()),
            Err(IoError::MissingSampleRate { .. })
        ));
        let r = read_csv(&p, &opts(Some("1"), Some(100.0))).unwrap();
        assert_eq!(r.samples, vec![2.0, 4.0, 6.0]);
        // NaN cell.
        std::fs::write(&p, "a,b\n1,2\nNaN,4\n").unwrap();
        match read_csv(&p, &opts(None, Some(1.0))).unwrap_err() {
            IoError::NonFinite {
                index,
                channel,
                path,
                ..
            } => {
                assert_eq!((index, channel.as_str()), (1, "a"));
                assert_eq!(path, p);
            }
            e => panic!("{e:?}"),
        }
        // Text cell, ragged row, empty file.
        std::fs::write(&p, "a,b\n1,2\nx,4\n").unwrap();
        assert!(matches!(
            read_csv(&p, &opts(None, Some(1.0))),
            Err(IoError::Malformed { .. })
        ));
        std::fs::write(&p, "a,b\n1,2\n3\n").unwrap();
        assert!(matches!(
            read_csv(&p, &opts(None, Some(1.0))),
            Err(IoError::Malformed { .. })
        ));
        std::fs::write(&p, "").unwrap();
        assert!(matches!(
            read_csv(&p, &opts(None, Some(1.0))),
            Err(IoError::Truncated { .. })
        ));
        std::fs::write(&p, "a,b\n").unwrap();
        assert!(matches!(
            read_csv(&p, &opts(None, Some(1.0))),
            Err(IoError::Truncated { .. })
        ));
        // A word of text alone: the message shows the line read as the header (the probe's
        // `notes.txt` said only "truncated: no data rows").
        std::fs::write(&p, "hello\n").unwrap();
        let e = read_csv(&p, &opts(None, Some(1.0)))
            .unwrap_err()
            .to_string();
        assert!(e.contains("after the header line \"hello\""), "{e}");
        // Absurd fs in the sidecar names the sidecar.
        std::fs::write(&p, "a\n1\n2\n").unwrap();
        let side = dir.path().join("x.json");
        std::fs::write(&side, r#"{"fs": 1e12}"#).unwrap();
        match read_csv(&p, &ReadOptions::default()).unwrap_err() {
            IoError::AbsurdSampleRate { path, .. } => assert_eq!(path, side),
            e => panic!("{e:?}"),
        }
        std::fs::write(&side, r#"{"fs": 100, "n_samples": 3}"#).unwrap();
        assert!(matches!(
            read_csv(&p, &ReadOptions::default()),
            Err(IoError::Contradiction { .. })
        ));
        std::fs::write(&side, r#"{"fs": 100, "complete": false}"#).unwrap();
        assert!(matches!(
            read_csv(&p, &ReadOptions::default()),
            Err(IoError::Contradiction { .. })
        ));
        std::fs::write(&side, r#"{"fs": "fast"}"#).unwrap();
        assert!(matches!(
            read_csv(&p, &ReadOptions::default()),
            Err(IoError::Malformed { .. })
        ));
        std::fs::write(&side, r#"{"fs": 100, "n_samples": 2, "rpm": 1200}"#).unwrap();
        let r = read_csv(&p, &ReadOptions::default()).unwrap();
        assert_eq!((r.fs, r.rpm), (100.0, Some(1200.0)));
        // Tab-separated.
        std::fs::write(&p, "t\tv\n0\t1\n0.5\t2\n1.0\t3\n").unwrap();
        std::fs::remove_file(&side).unwrap();
        let r = read_csv(&p, &ReadOptions::default()).unwrap();
        assert_eq!((r.fs, r.samples.len(), r.channel.as_str()), (2.0, 3, "v"));
    }

    /// A repeated column name taken by name is refused (the first one used to win
    /// silently); by index it is unambiguous, and a repeat of a column not taken is fine.
    #[test]
    fn repeated_column_names_are_refused_when_taken_by_name() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("x.csv");
        std::fs::write(&p, "t,acc,acc\n0,1,5\n0.5,2,6\n1.0,3,7\n").unwrap();
        for ch in [None, Some("acc"), Some("ACC")] {
            let e = read_csv(&p, &opts(ch, None)).unwrap_err().to_string();
            let named = e.contains("more than once") || e.contains("case is ignored");
            assert!(e.contains("\"acc\"") && named, "{e}");
        }
        let r = read_csv(&p, &opts(Some("2"), None)).unwrap();
        assert_eq!(r.samples, vec![5.0, 6.0, 7.0]);
        // Two names equal when case is ignored: the exact one is taken, a folded request
        // is ambiguous.
        std::fs::write(&p, "t,Acc,ACC\n0,1,5\n0.5,2,6\n1.0,3,7\n").unwrap();
        assert_eq!(
            read_csv(&p, &opts(Some("ACC"), None)).unwrap().samples[0],
            5.0
        );
        let e = read_csv(&p, &opts(Some("acc"), None))
            .unwrap_err()
            .to_string();
        assert!(e.contains("case is ignored"), "{e}");
        // A repeated time column.
        std::fs::write(&p, "t,t,acc\n0,0,1\n0.5,0.5,2\n1.0,1.0,3\n").unwrap();
        let e = read_csv(&p, &opts(Some("acc"), None))
            .unwrap_err()
            .to_string();
        assert!(e.contains("\"t\""), "{e}");
        // A repeat of a column nobody takes by name.
        std::fs::write(&p, "t,acc,x,x\n0,1,0,0\n0.5,2,0,0\n1.0,3,0,0\n").unwrap();
        assert_eq!(read_csv(&p, &opts(None, None)).unwrap().channel, "acc");
    }
}
