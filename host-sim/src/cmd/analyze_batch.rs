//! `wearsim analyze FILE|DIR...`: many records at once. Directories are walked (sorted,
//! recursively, hidden entries and `.json` sidecars skipped) for readable records; each is
//! analysed with the same options, and one table (CSV, JSON or Markdown) of calls, confidences
//! and evidence per file is written, with a progress line on stderr. A file that cannot be read
//! or analysed is a row with its error, not an abort; the exit code is 2 if any row failed
//! (the table is still complete), else 0.

use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::analyze::{analyze, AnalyzeArgs};
use crate::cmd::args::CliError;

/// Most files one batch run analyses.
pub const MAX_BATCH_FILES: usize = 100_000;
/// Deepest directory level walked.
const MAX_WALK_DEPTH: usize = 16;
/// Extensions of readable records (besides extension-less IMS snapshots).
const RECORD_EXTS: [&str; 5] = ["mat", "csv", "txt", "wav", "npy"];

/// True when `args` ask for a batch run: several inputs, a directory, `--format` or `--out`.
pub fn is_batch(args: &AnalyzeArgs) -> bool {
    !args.more.is_empty() || args.file.is_dir() || args.format.is_some() || args.out.is_some()
}

/// One row of the table.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Row {
    /// The file.
    pub file: PathBuf,
    /// `ok` or `error`.
    pub status: String,
    /// Fault family called (`InnerRace`, `OuterRace`, `Ball`, `None`), if analysed.
    pub family: Option<String>,
    /// Confidence of the call, if the detector reports one.
    pub confidence: Option<f64>,
    /// Detector score (dB per searched harmonic), if analysed.
    pub score: Option<f64>,
    /// Evidence: harmonics found / searched of each family, e.g. `OuterRace 5/5; InnerRace 1/5`.
    pub evidence: Option<String>,
    /// Channel, sample rate (Hz) and its source, speed (rpm), bearing.
    pub channel: Option<String>,
    /// Sample rate, Hz.
    pub fs: Option<f64>,
    /// Where the sample rate came from.
    pub fs_source: Option<String>,
    /// Where exactly the sample rate was found (`Analysis::fs_detail`).
    pub fs_detail: Option<String>,
    /// Shaft speed used, rpm (`Analysis::rpm`).
    pub rpm: Option<f64>,
    /// Bearing used.
    pub bearing: Option<String>,
    /// Whether the shaft line is where `fs` and `rpm` put it (`Analysis::speed_check`;
    /// empty: the record is too short to check).
    pub speed_consistent: Option<bool>,
    /// Whether the record's 1× line replaced the stated speed (`Analysis::speed_refined`).
    pub speed_refined: Option<bool>,
    /// The error, for a failed row.
    pub error: Option<String>,
}

/// Directories and files already taken, by canonical path: a symbolic link back up the
/// tree (`up -> ..`) or two names of one file are walked and analysed once (stop 68: two
/// such links made the walk grow exponentially until the depth limit).
#[derive(Default)]
struct Seen(std::collections::HashSet<PathBuf>);

impl Seen {
    /// Whether `p` is new (and records it); a path that cannot be resolved counts as new.
    fn first(&mut self, p: &Path) -> bool {
        self.0
            .insert(std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf()))
    }
}

fn walk(dir: &Path, depth: usize, seen: &mut Seen, out: &mut Vec<PathBuf>) -> Result<(), String> {
    if depth > MAX_WALK_DEPTH || !seen.first(dir) {
        return Ok(());
    }
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| format!("{}: read directory: {e}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect();
    entries.sort();
    for p in entries {
        let name = p
            .file_name()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        if name.starts_with('.') {
            continue;
        }
        if p.is_dir() {
            walk(&p, depth + 1, seen, out)?;
        } else {
            let ext = p
                .extension()
                .map(|e| e.to_string_lossy().to_ascii_lowercase());
            let readable = match ext.as_deref() {
                Some(e) => RECORD_EXTS.contains(&e),
                None => true,
            };
            if readable && seen.first(&p) {
                out.push(p);
            }
        }
        if out.len() > MAX_BATCH_FILES {
            return Err(format!(
                "inputs: more than {MAX_BATCH_FILES} files (allowed at most {MAX_BATCH_FILES} per run)"
            ));
        }
    }
    Ok(())
}

/// The files of `inputs`: files as given, directories walked (each directory and file once,
/// however many links lead to it), leaving out `skip` (the table being written).
pub fn collect_inputs(inputs: &[PathBuf], skip: Option<&Path>) -> Result<Vec<PathBuf>, String> {
    let mut seen = Seen::default();
    if let Some(s) = skip {
        seen.first(s);
    }
    let mut out = Vec::new();
    for p in inputs {
        if p.is_dir() {
            walk(p, 0, &mut seen, &mut out)?;
        } else {
            out.push(p.clone());
        }
    }
    Ok(out)
}

fn row_of(file: &Path, args: &AnalyzeArgs) -> Row {
    let mut a = args.clone();
    a.file = file.to_path_buf();
    a.more.clear();
    a.plot = None;
    let mut row = Row {
        file: file.to_path_buf(),
        status: "ok".into(),
        family: None,
        confidence: None,
        score: None,
        evidence: None,
        channel: None,
        fs: None,
        fs_source: None,
        fs_detail: None,
        rpm: None,
        bearing: None,
        speed_consistent: None,
        speed_refined: None,
        error: None,
    };
    match analyze(&a) {
        Ok((an, _)) => {
            let d = serde_json::to_value(&an.diagnosis).unwrap_or_default();
            row.family = d.get("family").and_then(|v| v.as_str()).map(str::to_string);
            row.confidence = d.get("confidence").and_then(serde_json::Value::as_f64);
            row.score = d.get("score").and_then(serde_json::Value::as_f64);
            let ev: Vec<String> = d
                .get("evidence")
                .and_then(|v| v.as_array())
                .map(|a| {
                    a.iter()
                        .map(|e| {
                            let n = e
                                .get("harmonics")
                                .and_then(|h| h.as_array())
                                .map_or(0, Vec::len);
                            format!(
                                "{} {}/{}",
                                e.get("family").and_then(|v| v.as_str()).unwrap_or("?"),
                                e.get("found")
                                    .and_then(serde_json::Value::as_u64)
                                    .unwrap_or(0),
                                n
                            )
                        })
                        .collect()
                })
                .unwrap_or_default();
            row.evidence = Some(ev.join("; "));
            row.channel = Some(an.channel);
            row.fs = Some(an.fs);
            row.fs_source = Some(an.fs_source);
            row.fs_detail = Some(an.fs_detail);
            row.rpm = Some(an.rpm);
            row.bearing = Some(an.bearing);
            row.speed_consistent = an.speed_check.map(|c| c.consistent);
            row.speed_refined = Some(an.speed_refined.is_some());
        }
        Err(e) => {
            row.status = "error".into();
            row.error = Some(e.to_string());
        }
    }
    row
}

fn opt<T: ToString>(v: &Option<T>) -> String {
    v.as_ref().map_or(String::new(), T::to_string)
}

const HEADER: [&str; 15] = [
    "file",
    "status",
    "family",
    "confidence",
    "score",
    "evidence",
    "channel",
    "fs",
    "fs_source",
    "fs_detail",
    "rpm",
    "bearing",
    "speed_consistent",
    "speed_refined",
    "error",
];

fn cells(r: &Row) -> [String; 15] {
    [
        r.file.display().to_string(),
        r.status.clone(),
        opt(&r.family),
        opt(&r.confidence),
        opt(&r.score),
        opt(&r.evidence),
        opt(&r.channel),
        opt(&r.fs),
        opt(&r.fs_source),
        opt(&r.fs_detail),
        opt(&r.rpm),
        opt(&r.bearing),
        opt(&r.speed_consistent),
        opt(&r.speed_refined),
        opt(&r.error),
    ]
}

/// Render the table as `csv`, `json` or `md`.
pub fn render(rows: &[Row], format: &str) -> Result<String, String> {
    match format {
        "json" => serde_json::to_string_pretty(rows).map_err(|e| e.to_string()),
        "csv" => {
            let mut w = ::csv::Writer::from_writer(Vec::new());
            w.write_record(HEADER).map_err(|e| e.to_string())?;
            for r in rows {
                w.write_record(cells(r)).map_err(|e| e.to_string())?;
            }
            let b = w.into_inner().map_err(|e| e.to_string())?;
            String::from_utf8(b).map_err(|e| e.to_string())
        }
        "md" => {
            let mut s = format!(
                "| {} |\n|{}\n",
                HEADER.join(" | "),
                "---|".repeat(HEADER.len())
            );
            for r in rows {
                let c: Vec<String> = cells(r)
                    .iter()
                    .map(|c| c.replace('|', "\\|").replace('\n', " "))
                    .collect();
                s.push_str(&format!("| {} |\n", c.join(" | ")));
            }
            Ok(s)
        }
        other => Err(format!(
            "format: {other:?} is not a table format (allowed: csv, json, md)"
        )),
    }
}

/// Run a batch: collect the inputs, analyse each with a progress line on stderr, write the table.
pub fn run(args: &AnalyzeArgs) -> Result<(), CliError> {
    if let Some(r) = args.rpm {
        crate::io::record::check_rpm_argument(r).map_err(CliError::input)?;
    }
    if let Some(f) = args.fs {
        crate::io::record::check_fs_flag(f).map_err(CliError::input)?;
    }
    let format = match (&args.format, &args.out) {
        (Some(f), _) => f.to_ascii_lowercase(),
        (None, Some(o)) => match o
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .as_deref()
        {
            Some("csv") => "csv".into(),
            Some("json") => "json".into(),
            _ => "md".into(),
        },
        (None, None) if args.json => "json".into(),
        (None, None) => "md".into(),
    };
    if !matches!(format.as_str(), "csv" | "json" | "md") {
        return Err(CliError::input(format!(
            "--format: {format:?} is not a table format (allowed: csv, json, md)"
        )));
    }
    if args.plot.is_some() {
        return Err(CliError::input(
            "--plot: plots are written for one file at a time, not in a batch run",
        ));
    }
    // The table's directory must exist and take a file before any record is analysed (a
    // batch can take hours; the table is written last).
    if let Some(o) = &args.out {
        crate::io::perms::check_output_file("--out", o).map_err(CliError::input)?;
    }
    let inputs: Vec<PathBuf> = std::iter::once(args.file.clone())
        .chain(args.more.iter().cloned())
        .collect();
    let files = collect_inputs(&inputs, args.out.as_deref()).map_err(CliError::input)?;
    if files.is_empty() {
        return Err(CliError::input("inputs: no readable record found (allowed: .mat, .csv, .txt, .wav, .npy, extension-less IMS snapshots)"));
    }
    let mut rows = Vec::with_capacity(files.len());
    let n = files.len();
    // The shared bar: only on a terminal (a log or a pipe gets the summary line alone).
    let bar = crate::cmd::args::Progress::new(std::io::stderr().is_terminal(), "analyze");
    for (i, f) in files.iter().enumerate() {
        bar.update(i, n);
        rows.push(row_of(f, args));
    }
    bar.finish();
    let failed = rows.iter().filter(|r| r.status != "ok").count();
    eprintln!(
        "analyze: {n} files, {} analysed, {failed} failed",
        n - failed
    );
    let text = render(&rows, &format).map_err(CliError::run)?;
    match &args.out {
        Some(o) => crate::life::output::write_atomic(o, text.as_bytes())
            .map_err(|e| CliError::run(format!("{}: {e}", o.display())))?,
        None => {
            let mut so = std::io::stdout().lock();
            so.write_all(text.as_bytes()).map_err(CliError::run)?;
        }
    }
    if failed > 0 {
        return Err(CliError::input(format!(
            "{failed} of {n} files could not be analysed (their rows hold the errors)"
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Links back up the tree (two of them grew the walk exponentially) and a second name
    /// of a file give each directory and file once; the table being written is not read
    /// as an input (a second batch run read its own table and failed on it).
    #[cfg(unix)]
    #[test]
    fn links_and_the_table_being_written_are_walked_once_or_not_at_all() {
        let root = tempfile::tempdir().expect("tmp");
        let d = root.path();
        std::fs::create_dir_all(d.join("a/b")).expect("dirs");
        std::fs::write(d.join("a/r.npy"), b"x").expect("file");
        std::fs::write(d.join("table.csv"), b"x").expect("file");
        std::os::unix::fs::symlink("..", d.join("a/b/up")).expect("link");
        std::os::unix::fs::symlink("../..", d.join("a/b/up2")).expect("link");
        std::os::unix::fs::symlink("r.npy", d.join("a/same.npy")).expect("link");
        let files = collect_inputs(&[d.to_path_buf()], Some(&d.join("table.csv"))).expect("walk");
        assert_eq!(files, vec![d.join("a/r.npy")]);
        let files = collect_inputs(&[d.to_path_buf()], None).expect("walk");
        assert_eq!(files, vec![d.join("a/r.npy"), d.join("table.csv")]);
    }
}
