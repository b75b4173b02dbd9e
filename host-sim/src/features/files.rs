//! Which files of a raw folder are snapshots of a layout, their numbers and their times
//! (the naming half of [`super::convert`]): the listing refuses names that have a layout's
//! pattern but are not valid (an IMS time stamp that is no date, two files of one number),
//! and reports the files it does not read and the gaps in a layout's numbering, for the
//! sidecar's `notes`. The FEMTO clock ([`FemtoClock`]) turns each file's first-row time of
//! day into time since the start of the test.

use std::path::{Path, PathBuf};

use super::{FeaturesError, RawLayout, MAX_FILES, XJTU_INTERVAL_S};
use crate::io::ims::check_ims_name;
use crate::io::IoError;

/// Longest step of the FEMTO clock taken across midnight, s: a clock that steps back is a
/// wrap past midnight only if the step forward it then stands for (the step back plus 24 h)
/// is shorter than 12 h, i.e. the earlier time is late in the day and the later early.
/// Anything else is files out of order (or a pause the time of day cannot tell), refused.
pub const FEMTO_MAX_WRAP_STEP_S: f64 = 12.0 * 3600.0;

/// One snapshot file of a folder.
#[derive(Debug, Clone)]
pub(crate) struct SnapshotFile {
    /// The file.
    pub path: PathBuf,
    /// Its snapshot index in the table: the layout's own number of the file (FEMTO
    /// `acc_NNNNN.csv`, XJTU-SY `N.csv`), or its position in time order (IMS).
    pub index: u64,
    /// Time since the start of the test where the name carries it (IMS, XJTU-SY), s.
    pub time_s: Option<f64>,
}

/// The snapshot files of a folder, in order, and what the listing left out.
#[derive(Debug, Clone, Default)]
pub(crate) struct Listing {
    /// Snapshot files, by number (FEMTO, XJTU-SY) or time (IMS).
    pub files: Vec<SnapshotFile>,
    /// Files of the layout's naming that are not read, with the reason (XJTU-SY `0.csv`).
    pub skipped: Vec<String>,
    /// Gaps in the layout's numbering 1, 2, …: a file name, or a range of them.
    pub missing: Vec<String>,
    /// Names of the folder's other files (not of the layout's snapshot naming), sorted:
    /// not read, and counted in the sidecar's notes so that a folder mixing two layouts
    /// or tests does not pass silently.
    pub others: Vec<String>,
}

fn femto_index(name: &str) -> Option<u64> {
    let digits = name.strip_prefix("acc_")?.strip_suffix(".csv")?;
    digits
        .bytes()
        .all(|b| b.is_ascii_digit())
        .then(|| digits.parse().ok())?
}

fn xjtu_number(name: &str) -> Option<u64> {
    let digits = name.strip_suffix(".csv")?;
    digits
        .bytes()
        .all(|b| b.is_ascii_digit())
        .then(|| digits.parse().ok())?
}

/// The file name of snapshot number `k` of a numbering layout.
fn numbered_name(layout: RawLayout, k: u64) -> String {
    match layout {
        RawLayout::Femto => format!("acc_{k:05}.csv"),
        _ => format!("{k}.csv"),
    }
}

/// The gaps of the sorted, distinct `numbers` in 1..=last, as file names or ranges.
fn gaps(layout: RawLayout, numbers: &[u64]) -> Vec<String> {
    let mut out = vec![];
    let mut next = 1u64;
    for &k in numbers {
        if k > next {
            let (a, b) = (numbered_name(layout, next), numbered_name(layout, k - 1));
            out.push(if k - 1 == next {
                a
            } else {
                format!("{a} … {b} ({} files)", k - next)
            });
        }
        next = next.max(k.saturating_add(1));
    }
    out
}

/// The snapshot files of `dir` for `layout` (not [`RawLayout::Auto`]), ordered, with
/// their snapshot index and, where the name carries it, their time since the start of the
/// test. Refused (exit 2, naming the files): an IMS name of the time-stamp pattern that is
/// no calendar date and time, and two files of one number (`acc_5.csv`, `acc_00005.csv`)
/// or one time stamp (`T`, `T.txt`).
pub(crate) fn list(dir: &Path, layout: RawLayout) -> Result<Listing, FeaturesError> {
    let rd = std::fs::read_dir(dir).map_err(|e| IoError::io(dir, "read directory", e))?;
    // (path, number or time stamp)
    let mut found: Vec<(PathBuf, i64)> = vec![];
    let mut skipped = vec![];
    // Numbers of entries of the layout's naming that are no readable file (a directory, a
    // broken link): listed as skipped, not as missing.
    let mut not_files: Vec<u64> = vec![];
    let mut others: Vec<String> = vec![];
    for e in rd {
        let e = e.map_err(|e| IoError::io(dir, "read directory", e))?;
        let p = e.path();
        let name = e.file_name().to_string_lossy().into_owned();
        if !p.is_file() {
            if has_snapshot_name(layout, &name) {
                skipped.push(format!(
                    "{}: not read: named as a snapshot but no regular file (a directory or a broken link)",
                    p.display()
                ));
                not_files.extend(femto_index(&name).or_else(|| xjtu_number(&name)));
            }
            continue;
        }
        if !has_snapshot_name(layout, &name) {
            others.push(name);
            continue;
        }
        let key = match layout {
            RawLayout::Ims => check_ims_name(name.strip_suffix(".txt").unwrap_or(&name))
                .map_err(|why| {
                    FeaturesError::Input(format!(
                        "{}: named like an IMS snapshot (YYYY.MM.DD.hh.mm.ss) but not a date and time: {why}",
                        p.display()
                    ))
                })?,
            RawLayout::Femto => femto_index(&name).and_then(|k| i64::try_from(k).ok()),
            RawLayout::Xjtu => match xjtu_number(&name).and_then(|k| i64::try_from(k).ok()) {
                Some(0) => {
                    skipped.push(format!(
                        "{}: not read: XJTU-SY files are numbered from 1 (file N starts at (N − 1) · 60 s)",
                        p.display()
                    ));
                    None
                }
                k => k,
            },
            RawLayout::Auto => None,
        };
        if let Some(k) = key {
            found.push((p, k));
        }
        if found.len() > MAX_FILES {
            return Err(FeaturesError::Input(format!(
                "{}: more than {MAX_FILES} snapshot files",
                dir.display()
            )));
        }
    }
    found.sort_by(|a, b| a.1.cmp(&b.1).then_with(|| a.0.cmp(&b.0)));
    if let Some(w) = found.windows(2).find(|w| w[0].1 == w[1].1) {
        let what = match layout {
            RawLayout::Ims => "the same time stamp",
            _ => "the same snapshot number",
        };
        return Err(FeaturesError::Input(format!(
            "{}: {} and {} have {what} ({}); keep one of them",
            dir.display(),
            w[0].0.file_name().unwrap_or_default().to_string_lossy(),
            w[1].0.file_name().unwrap_or_default().to_string_lossy(),
            w[0].1
        )));
    }
    let t0 = found.first().map_or(0, |f| f.1);
    let files = found
        .iter()
        .enumerate()
        .map(|(pos, (path, k))| SnapshotFile {
            path: path.clone(),
            index: match layout {
                RawLayout::Ims => pos as u64,
                _ => *k as u64,
            },
            time_s: match layout {
                RawLayout::Ims => Some((k - t0) as f64),
                RawLayout::Xjtu => Some((k - 1) as f64 * XJTU_INTERVAL_S),
                _ => None,
            },
        })
        .collect();
    let missing = match layout {
        RawLayout::Femto | RawLayout::Xjtu => {
            let mut numbers: Vec<u64> = found.iter().map(|f| f.1 as u64).collect();
            numbers.extend(not_files);
            numbers.sort_unstable();
            numbers.dedup();
            gaps(layout, &numbers)
        }
        _ => vec![],
    };
    skipped.sort();
    others.sort();
    Ok(Listing {
        files,
        skipped,
        missing,
        others,
    })
}

/// Whether file name `name` has `layout`'s snapshot naming (what [`list`] would take as a
/// snapshot, or refuse as a malformed one): an IMS time stamp (with or without `.txt`),
/// FEMTO `acc_NNNNN.csv`, XJTU-SY `N.csv` (`0.csv` included).
fn has_snapshot_name(layout: RawLayout, name: &str) -> bool {
    match layout {
        RawLayout::Ims => !matches!(
            check_ims_name(name.strip_suffix(".txt").unwrap_or(name)),
            Ok(None)
        ),
        RawLayout::Femto => femto_index(name).is_some(),
        RawLayout::Xjtu => xjtu_number(name).is_some(),
        RawLayout::Auto => false,
    }
}

/// `path` with its folder resolved (symbolic links, `..`): the file itself need not exist.
/// `None` when the folder does not exist (nothing can be overwritten there).
fn resolved(path: &Path) -> Option<PathBuf> {
    let name = path.file_name()?;
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    Some(parent.canonicalize().ok()?.join(name))
}

/// Refuses an output table (`out`, and its sidecar `json`) that is one of the snapshot
/// files `listing` holds of folder `dir`, or that lies in `dir` under a name of `layout`'s
/// snapshot naming: writing it would replace a raw snapshot of the test, or add a file the
/// next run over the folder would read as one. Paths are compared resolved (a symbolic
/// link to a snapshot is that snapshot).
pub(crate) fn check_out(
    dir: &Path,
    layout: RawLayout,
    listing: &Listing,
    out: &Path,
    json: &Path,
) -> Result<(), FeaturesError> {
    let dir_real = dir.canonicalize().ok();
    for target in [out, json] {
        let real = resolved(target).unwrap_or_else(|| target.to_path_buf());
        // A link at the file itself is followed too.
        let real = std::fs::canonicalize(&real).unwrap_or(real);
        let what = if target == out {
            "the table".to_string()
        } else {
            format!("its sidecar {}", target.display())
        };
        if let Some(f) = listing
            .files
            .iter()
            .find(|f| f.path.canonicalize().is_ok_and(|p| p == real))
        {
            return Err(FeaturesError::Input(format!(
                "--out {}: {what} would overwrite {}, a snapshot file this command reads from {}; write the table outside the input folder",
                out.display(),
                f.path.display(),
                dir.display()
            )));
        }
        let name = real.file_name().map(|n| n.to_string_lossy().into_owned());
        let inside = dir_real.is_some() && real.parent() == dir_real.as_deref();
        if let Some(name) = name.filter(|n| inside && has_snapshot_name(layout, n)) {
            return Err(FeaturesError::Input(format!(
                "--out {}: {what} would be in the input folder {} under the {} layout's snapshot naming ({name}), read as a snapshot of the test by the next run: write the table outside the folder or under another name",
                out.display(),
                dir.display(),
                format!("{layout:?}").to_lowercase()
            )));
        }
    }
    Ok(())
}

/// The error of a folder in which no file has `layout`'s naming: the naming, and a few of
/// the files seen.
pub(crate) fn no_file_of(dir: &Path, layout: RawLayout) -> FeaturesError {
    let naming = match layout {
        RawLayout::Ims => "files named by time stamp YYYY.MM.DD.hh.mm.ss",
        RawLayout::Femto => "acc_NNNNN.csv",
        RawLayout::Xjtu => "N.csv, N = 1, 2, …",
        RawLayout::Auto => "a known layout",
    };
    let mut seen: Vec<String> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.filter_map(|e| e.ok())
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    seen.sort();
    let n = seen.len();
    let shown: Vec<&str> = seen.iter().take(5).map(String::as_str).collect();
    FeaturesError::Input(format!(
        "{}: no file matches layout {} ({naming}); the folder holds {n} entries{}{}",
        dir.display(),
        format!("{layout:?}").to_lowercase(),
        if n > 0 { ": " } else { "" },
        shown.join(", ") + if n > shown.len() { ", …" } else { "" }
    ))
}

/// FEMTO clock of a snapshot's first row, s since midnight.
pub(crate) fn femto_clock(path: &Path) -> Result<f64, FeaturesError> {
    let first = crate::io::layout::first_line(path)?;
    let sep = if first.contains(';') { ';' } else { ',' };
    let c: Vec<f64> = first
        .split(sep)
        .take(4)
        .map(|x| x.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| {
            FeaturesError::Input(format!(
                "{}: row 1: hour, minute, second, µs are not numbers",
                path.display()
            ))
        })?;
    match c.as_slice() {
        [h, m, s, us] => Ok(h * 3600.0 + m * 60.0 + s + us * 1e-6),
        _ => Err(FeaturesError::Input(format!(
            "{}: row 1: fewer than 4 time cells",
            path.display()
        ))),
    }
}

/// `hh:mm:ss.ffffff` of a FEMTO clock value (s since midnight).
fn clock_text(c: f64) -> String {
    let us = (c * 1e6).round() as i64;
    let (s, f) = (us.div_euclid(1_000_000), us.rem_euclid(1_000_000));
    format!("{:02}:{:02}:{:02}.{f:06}", s / 3600, (s / 60) % 60, s % 60)
}

/// A step of `s` seconds as `1 h 2 min 3 s`.
fn span_text(s: f64) -> String {
    let t = s.round() as i64;
    let (h, m, sec) = (t / 3600, (t / 60) % 60, t % 60);
    match (h, m) {
        (0, 0) => format!("{sec} s"),
        (0, _) => format!("{m} min {sec} s"),
        _ => format!("{h} h {m} min {sec} s"),
    }
}

/// Time since the start of a FEMTO test from the time of day of each file's first row, in
/// file order: a step back is a wrap past midnight (adds a day) only under the rule of
/// [`FEMTO_MAX_WRAP_STEP_S`]; any other step back, or two files at one time, is refused
/// naming both files and their times.
#[derive(Debug, Default)]
pub(crate) struct FemtoClock {
    /// First clock, s since midnight.
    start: Option<f64>,
    /// Days added by wraps, s.
    days: f64,
    /// The previous file and its clock.
    last: Option<(PathBuf, f64)>,
}

impl FemtoClock {
    /// The time of the file `path` whose first row's clock is `c` (s since midnight).
    pub(crate) fn time(&mut self, dir: &Path, path: &Path, c: f64) -> Result<f64, FeaturesError> {
        let name = |p: &Path| {
            p.file_name()
                .unwrap_or_default()
                .to_string_lossy()
                .into_owned()
        };
        if let Some((prev, lc)) = &self.last {
            if c == *lc {
                return Err(FeaturesError::Input(format!(
                    "{}: {} and {} both start at {}: two snapshots at one time (a copied file?); a table's times strictly increase",
                    dir.display(),
                    name(prev),
                    name(path),
                    clock_text(c)
                )));
            }
            if c < *lc {
                let wrapped = c + 86_400.0 - lc;
                if wrapped >= FEMTO_MAX_WRAP_STEP_S {
                    return Err(FeaturesError::Input(format!(
                        "{}: {} starts at {}, before {} at {} (a step back of {}): the files are out of order or misnumbered; a step back is taken as a wrap past midnight only if the step it then stands for is under 12 h (here {})",
                        dir.display(),
                        name(path),
                        clock_text(c),
                        name(prev),
                        clock_text(*lc),
                        span_text(lc - c),
                        span_text(wrapped)
                    )));
                }
                self.days += 86_400.0;
            }
        }
        let c0 = *self.start.get_or_insert(c);
        self.last = Some((path.to_path_buf(), c));
        Ok(c + self.days - c0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_step_back_is_a_midnight_wrap_only_when_the_wrapped_step_is_short() {
        let dir = Path::new("run");
        let (a, b) = (
            Path::new("run/acc_00001.csv"),
            Path::new("run/acc_00002.csv"),
        );
        // 23:59:50 then 00:00:00: a wrap, 10 s later.
        let mut c = FemtoClock::default();
        assert_eq!(c.time(dir, a, 86_390.0).unwrap(), 0.0);
        assert_eq!(c.time(dir, b, 0.0).unwrap(), 10.0);
        // 09:00:40 then 09:00:30: not a wrap (it would be a step of 23 h 59 min 50 s).
        let mut c = FemtoClock::default();
        c.time(dir, a, 32_440.0).unwrap();
        let e = c.time(dir, b, 32_430.0).unwrap_err().to_string();
        for want in [
            "run:",
            "acc_00001.csv at 09:00:40.000000",
            "acc_00002.csv starts at 09:00:30.000000",
            "step back of 10 s",
            "23 h 59 min 50 s",
        ] {
            assert!(e.contains(want), "{want:?} not in {e}");
        }
        // 20:00 then 07:59: an 11 h 59 min step across midnight is a wrap; 20:00 then
        // 08:00 (12 h) is not.
        let mut c = FemtoClock::default();
        c.time(dir, a, 72_000.0).unwrap();
        assert_eq!(c.time(dir, b, 28_740.0).unwrap(), 43_140.0);
        let mut c = FemtoClock::default();
        c.time(dir, a, 72_000.0).unwrap();
        assert!(c.time(dir, b, 28_800.0).is_err());
        // One time twice.
        let mut c = FemtoClock::default();
        c.time(dir, a, 100.0).unwrap();
        let e = c.time(dir, b, 100.0).unwrap_err().to_string();
        assert!(e.contains("acc_00001.csv and acc_00002.csv both start at 00:01:40"));
    }

    /// Probe defect: `features DIR --layout xjtu --out DIR/1.csv` replaced raw snapshot
    /// `1.csv`. An output that is a snapshot read, or that has the layout's snapshot naming
    /// in the input folder, is refused naming `--out`; a table beside the snapshots under
    /// another name, or in another folder, is not.
    #[test]
    fn an_output_over_the_input_snapshots_is_refused() {
        let dir = std::env::temp_dir().join(format!("wearsim-out-check-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        for n in ["1.csv", "2.csv"] {
            std::fs::write(dir.join(n), "x").unwrap();
        }
        let listing = list(&dir, RawLayout::Xjtu).unwrap();
        let check = |out: PathBuf| {
            let json = out.with_extension("json");
            check_out(&dir, RawLayout::Xjtu, &listing, &out, &json)
        };
        let e = check(dir.join("1.csv")).unwrap_err().to_string();
        assert!(e.starts_with("--out "), "{e}");
        assert!(e.contains("would overwrite") && e.contains("1.csv"), "{e}");
        // The same file reached through `sub/..`.
        let e = check(dir.join("sub").join("..").join("2.csv"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("would overwrite"), "{e}");
        // Not a file yet, but of the naming: the next run would read it.
        let e = check(dir.join("7.csv")).unwrap_err().to_string();
        assert!(e.contains("snapshot naming (7.csv)"), "{e}");
        assert!(check(dir.join("features.csv")).is_ok());
        assert!(check(dir.join("sub").join("1.csv")).is_ok());
        // Another layout's naming in the folder is no snapshot of this one.
        assert!(check_out(
            &dir,
            RawLayout::Femto,
            &Listing::default(),
            &dir.join("1.csv"),
            &dir.join("1.json")
        )
        .is_ok());
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn gaps_in_the_numbering_are_named() {
        assert_eq!(gaps(RawLayout::Femto, &[1, 2, 3]), Vec::<String>::new());
        assert_eq!(gaps(RawLayout::Femto, &[1, 2, 4]), ["acc_00003.csv"]);
        assert_eq!(
            gaps(RawLayout::Xjtu, &[2, 3, 9]),
            ["1.csv", "4.csv … 8.csv (5 files)"]
        );
        assert_eq!(gaps(RawLayout::Femto, &[0, 1]), Vec::<String>::new());
    }
}
