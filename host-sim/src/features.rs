//! `wearsim features`: a folder of raw snapshots of a run-to-failure test (IMS, FEMTO /
//! PRONOSTIA or XJTU-SY layout) turned into the documented per-snapshot feature table
//! ([`crate::io::feature_table`], `docs/feature-tables.md`). Each snapshot is read by the
//! layout readers of [`crate::io::layout`] / [`crate::io::ims`] and its statistics are
//! [`crate::analysis::stats()`] (kurtosis m4/m2², crest = peak / RMS).
//!
//! Time of each snapshot since the start of the test, per layout:
//!
//! | layout | files | time |
//! |---|---|---|
//! | `ims` | named by time stamp `YYYY.MM.DD.hh.mm.ss` | the name, less the first |
//! | `femto` | `acc_NNNNN.csv` (others, e.g. `temp_*.csv`, ignored) | first row's hour, minute, s, µs (a wrap past midnight adds a day, [`FEMTO_MAX_WRAP_STEP_S`]) |
//! | `xjtu` | `N.csv`, N = 1, 2, ... (one a minute, Wang et al. 2020) | (N − 1) · 60 s |

use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::analysis::octave_bands::{band_levels, band_name, octave_edges};
use crate::analysis::stats::stats;
use crate::gap::lifetime::rig::{RigDescription, RPM_TOL};
use crate::geometry::{catalogue, named_geometry, GeometrySpec};
use crate::io::conditions::{from_folder_names, ConditionSet, NamedCondition};
use crate::io::feature_table::{
    check_against_table, check_rows, check_sidecar, median_step, sidecar_path, BearingInfo,
    FeatureRow, FeatureSidecar, FeatureTableError, Geometry, FAILURE_MODES, FORMAT, FORMAT_VERSION,
    MIN_SNAPSHOTS,
};
use crate::io::feature_table_write::write_feature_table;
use crate::io::ims::{read_ims_snapshot, IMS_FS, IMS_RPM};
use crate::io::layout::{read_femto, read_layout, sniff_text, TextLayout, FEMTO_FS, XJTU_FS};
use crate::io::{IoError, ReadOptions};

mod files;
pub use files::FEMTO_MAX_WRAP_STEP_S;

/// Interval between XJTU-SY snapshots, s (one 1.28-s record a minute; Wang et al. 2020).
pub const XJTU_INTERVAL_S: f64 = 60.0;
/// IMS radial load, N (6000 lbf on the shaft and bearings; IMS readme).
pub const IMS_LOAD_N: f64 = 6000.0 * 4.448_221_6;
/// The preset of the IMS layout's bearing (Rexnord ZA-2115 at 2000 rpm, 6000 lbf).
pub const IMS_PRESET: &str = "ims-za2115";
/// Most snapshot files of one folder (IMS test 1 has 2 156).
pub const MAX_FILES: usize = 100_000;

/// A raw snapshot layout (`--layout`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum RawLayout {
    /// IMS / NASA raw ASCII snapshots.
    Ims,
    /// FEMTO / PRONOSTIA `acc_*.csv`.
    Femto,
    /// XJTU-SY `N.csv`.
    Xjtu,
    /// Recognised from the content of the first snapshot file.
    Auto,
}

/// What the caller knows that the files do not hold.
#[derive(Debug, Clone, Default)]
pub struct FeatureOptions {
    /// Channel (layout-specific: IMS `1`..`8`, FEMTO `horiz`/`vert`, XJTU header).
    pub channel: Option<String>,
    /// Shaft speed, rpm (IMS: 2000 by default; FEMTO/XJTU: the folder names' condition
    /// ([`crate::io::conditions`]), else required).
    pub rpm: Option<f64>,
    /// Radial load, N (IMS: 6000 lbf by default; else required).
    pub load_n: Option<f64>,
    /// wearsim preset of the bearing (IMS: `ims-za2115` by default, unless a geometry,
    /// speed or load of the user's replaces it).
    pub preset: Option<String>,
    /// Geometry `elements=N,ball=D,pitch=P,angle=DEG` (mm, degrees; XJTU-SY: the
    /// catalogue's LDK UER204 by default).
    pub geometry: Option<String>,
    /// Which bearing (free text; default: the folder name).
    pub bearing_id: Option<String>,
    /// Failure mode, one of [`FAILURE_MODES`] (default `unknown`).
    pub failure_mode: Option<String>,
}

/// Why a folder could not be converted (all are bad input, exit 2).
#[derive(Debug, thiserror::Error)]
pub enum FeaturesError {
    /// A reader or the table writer refused.
    #[error(transparent)]
    Table(#[from] FeatureTableError),
    /// The folder, an argument or a snapshot is unusable.
    #[error("{0}")]
    Input(String),
}

impl From<IoError> for FeaturesError {
    fn from(e: IoError) -> Self {
        FeaturesError::Table(e.into())
    }
}

/// Summary of a conversion (`--json`).
#[derive(Debug, Clone, Serialize)]
pub struct FeaturesSummary {
    /// Layout used.
    pub layout: RawLayout,
    /// Table written.
    pub csv: PathBuf,
    /// Its sidecar.
    pub sidecar: PathBuf,
    /// Snapshots in the table.
    pub snapshots: usize,
    /// Snapshot files not in the table, with the reason: a constant signal (a stopped
    /// machine), or a name outside the layout's numbering (XJTU-SY `0.csv`).
    pub skipped: Vec<String>,
    /// Gaps in the layout's file numbering 1, 2, … (FEMTO, XJTU-SY): a file name, or a
    /// range `first … last (n files)`. The table keeps each file's number as its snapshot
    /// index, so the rows show the gaps too.
    pub missing: Vec<String>,
    /// Span of the table, h.
    pub hours: f64,
    /// RMS of the first and the last snapshot (record unit).
    pub rms_first_last: (f64, f64),
    /// Where the table's speed came from: `--rpm`, the IMS readme, or a folder name
    /// ([`crate::io::conditions`]).
    pub rpm_source: String,
    /// Where the table's radial load came from (as `rpm_source`).
    pub load_source: String,
    /// The sidecar written.
    pub meta: FeatureSidecar,
}

/// Recognises the layout of `dir` from the content of its first snapshot file (by the
/// naming of each layout, the first that names any file).
pub fn detect(dir: &Path) -> Result<RawLayout, FeaturesError> {
    for l in [RawLayout::Ims, RawLayout::Femto, RawLayout::Xjtu] {
        let f = files::list(dir, l)?;
        let Some(first) = f.files.first() else {
            continue;
        };
        let found = sniff_text(&first.path)?;
        let ok = matches!(
            (l, found),
            (RawLayout::Ims, Some(TextLayout::Ims(_)))
                | (RawLayout::Femto, Some(TextLayout::Femto(_)))
                | (RawLayout::Xjtu, Some(TextLayout::XjtuSy))
        );
        if ok {
            return Ok(l);
        }
    }
    Err(FeaturesError::Input(format!(
        "--layout auto: {} holds no snapshot of a known layout (IMS time-stamp files of 20 480 rows, FEMTO acc_NNNNN.csv, XJTU-SY N.csv); give --layout",
        dir.display()
    )))
}

/// The sidecar's notes: files not read (with the reason) and gaps in the layout's numbering.
fn notes(
    layout: RawLayout,
    skipped: &[String],
    missing: &[String],
    others: &[String],
) -> Vec<String> {
    let mut n: Vec<String> = skipped.iter().map(|s| format!("skipped: {s}")).collect();
    if !others.is_empty() {
        const SHOWN: usize = 5;
        n.push(format!(
            "not read: {} file(s) not named as {} snapshots ({}{})",
            others.len(),
            format!("{layout:?}").to_lowercase(),
            others
                .iter()
                .take(SHOWN)
                .cloned()
                .collect::<Vec<_>>()
                .join(", "),
            if others.len() > SHOWN { ", …" } else { "" }
        ));
    }
    if !missing.is_empty() {
        n.push(format!(
            "missing: {} (no such file; the layout numbers its files from 1 and each row's snapshot index is its file's number{})",
            missing.join(", "),
            if layout == RawLayout::Xjtu {
                ", its time (N − 1) · 60 s"
            } else {
                ""
            }
        ));
    }
    n
}

/// One quantity of the operating point (speed or load) and where it came from: the flag's
/// value, else the IMS readme's, else what a folder name states ([`crate::io::conditions`]);
/// with none of them, an error naming the flag.
fn operating_value(
    flag: &str,
    what: &str,
    given: Option<f64>,
    ims: Option<(f64, &str)>,
    named: Option<(f64, &str)>,
) -> Result<(f64, String), FeaturesError> {
    match (given, ims.or(named)) {
        (Some(v), _) => Ok((v, flag.to_string())),
        (None, Some((v, source))) => Ok((v, source.to_string())),
        (None, None) => Err(FeaturesError::Input(format!(
            "{flag}: the FEMTO and XJTU-SY files do not hold the {what}, and no folder name states it (XJTU-SY `35Hz12kN`, `Bearing1_1`; PRONOSTIA `Bearing1_1`); give it"
        ))),
    }
}

/// Notes on a folder-name operating point ([`crate::io::conditions`]): used (for speed, load or
/// both), or contradicted by the flag that replaced it.
fn named_notes(named: Option<&NamedCondition>, rpm: f64, load_n: f64) -> Vec<String> {
    let Some(n) = named else {
        return vec![];
    };
    let same = |a: f64, b: f64| (a - b).abs() <= RPM_TOL * b;
    let mut out = vec![];
    for (what, used, stated, flag) in [
        ("rpm", rpm, n.rpm, "--rpm"),
        ("radial_load_n", load_n, n.load_n, "--load-n"),
    ] {
        out.push(if same(used, stated) {
            format!("{what} {stated} from the {}; {flag} overrides", n.source)
        } else {
            format!(
                "{what} {used} from {flag}; the {} states {stated}",
                n.source
            )
        });
    }
    out
}

/// A note for a table that the format holds but a simulated life cannot take (`gap
/// --life`): a speed outside [`crate::config::MIN_SIM_RPM`]..=[`crate::config::MAX_SIM_RPM`],
/// or no load (the load wears the bearing). The table is still written: it is data.
fn simulation_limits(rpm: f64, load_n: f64) -> Vec<String> {
    use crate::config::{MAX_SIM_RPM, MIN_SIM_RPM};
    let mut n = vec![];
    if !(MIN_SIM_RPM..=MAX_SIM_RPM).contains(&rpm) {
        n.push(format!(
            "rpm {rpm} is outside what a simulated life takes ({MIN_SIM_RPM}..={MAX_SIM_RPM} rpm): `gap --life` will refuse this table"
        ));
    }
    if load_n <= 0.0 {
        n.push(
            "radial_load_n 0: a simulated life needs the load that wears the bearing: `gap --life` will refuse this table".into(),
        );
    }
    n
}

/// A check of the table made from folder `dir` failed: the error names the flag whose
/// value the sidecar field holds, or else the folder.
fn about_input(dir: &Path, e: FeatureTableError) -> FeaturesError {
    match e {
        FeatureTableError::Sidecar { field, detail, .. } => {
            let flag = match field.as_str() {
                "rpm" => Some("--rpm"),
                "radial_load_n" => Some("--load-n"),
                "bearing.geometry" => Some("--bearing-geometry"),
                "bearing.preset" => Some("--preset"),
                _ => None,
            };
            FeaturesError::Input(match flag {
                Some(f) => format!("{f}: {detail}"),
                None => format!(
                    "{}: `{field}` of the table made from this folder: {detail}",
                    dir.display()
                ),
            })
        }
        e => FeaturesError::Input(e.to_string()),
    }
}

/// Converts folder `dir` of layout `layout` into the table `out` (`.csv`) and its sidecar.
/// Nothing is written unless every snapshot was read and the table passes the format's
/// checks.
pub fn convert(
    dir: &Path,
    layout: RawLayout,
    out: &Path,
    o: &FeatureOptions,
) -> Result<FeaturesSummary, FeaturesError> {
    if !dir.is_dir() {
        return Err(FeaturesError::Input(format!(
            "DIR {}: not a folder of snapshot files",
            dir.display()
        )));
    }
    let layout = match layout {
        RawLayout::Auto => detect(dir)?,
        l => l,
    };
    let failure_mode = o.failure_mode.clone().unwrap_or_else(|| "unknown".into());
    if !FAILURE_MODES.contains(&failure_mode.as_str()) {
        return Err(FeaturesError::Input(format!(
            "--failure-mode {failure_mode}: one of {}",
            FAILURE_MODES.join(", ")
        )));
    }
    let ims = layout == RawLayout::Ims;
    // Speed and load: the flags, else the IMS readme's, else what the data set's folder
    // names state (FEMTO, XJTU-SY), reported with their source.
    let set = match layout {
        RawLayout::Xjtu => Some(ConditionSet::Xjtu),
        RawLayout::Femto => Some(ConditionSet::Femto),
        RawLayout::Ims | RawLayout::Auto => None,
    };
    let named = set.and_then(|set| {
        from_folder_names(
            &std::fs::canonicalize(dir).unwrap_or(dir.to_path_buf()),
            set,
        )
    });
    let (rpm, rpm_source) = operating_value(
        "--rpm",
        "shaft speed (rpm)",
        o.rpm,
        ims.then_some((IMS_RPM, "IMS readme (2000 rpm)")),
        named.as_ref().map(|n| (n.rpm, n.source.as_str())),
    )?;
    if o.rpm.is_some() {
        crate::io::record::check_rpm_argument(rpm).map_err(FeaturesError::Input)?;
    }
    let (load_n, load_source) = operating_value(
        "--load-n",
        "radial load (N)",
        o.load_n,
        ims.then_some((IMS_LOAD_N, "IMS readme (6000 lbf)")),
        named.as_ref().map(|n| (n.load_n, n.source.as_str())),
    )?;
    // Explicit flags override the layout's defaults. The IMS layout's preset stands for
    // its bearing at its speed and load: a geometry, speed or load of the user's drops it
    // (the table then names the bearing by its geometry). An explicit --preset replaces
    // the layout's geometry.
    let user_geometry = match &o.geometry {
        Some(g) => Some(
            GeometrySpec::parse(g)
                .map_err(|e| FeaturesError::Input(format!("--bearing-geometry: {e}")))?,
        ),
        None => None,
    };
    let differs = |a: f64, b: f64| (a - b).abs() > RPM_TOL * b;
    let overridden = user_geometry.is_some()
        || o.rpm.is_some_and(|r| differs(r, IMS_RPM))
        || o.load_n.is_some_and(|l| differs(l, IMS_LOAD_N));
    let preset = o
        .preset
        .clone()
        .or((ims && !overridden).then(|| IMS_PRESET.to_string()));
    let geometry = match (user_geometry, layout) {
        (Some(g), _) => Some(g),
        (None, _) if o.preset.is_some() => None,
        (None, RawLayout::Xjtu) => catalogue("xjtu-ldk-uer204").map(|e| e.geometry),
        (None, RawLayout::Ims) if preset.is_none() => named_geometry(IMS_PRESET),
        _ => None,
    };
    // Contradictory explicit flags are an error.
    if let (Some(p), Some(g)) = (&o.preset, &geometry) {
        if let Some(n) = named_geometry(p).filter(|n| !n.same_as(g)) {
            return Err(FeaturesError::Input(format!(
                "--preset {p} and --bearing-geometry contradict: {p} is {}, the flag {}; give one of them",
                n.describe(),
                g.describe()
            )));
        }
    }
    if preset.is_none() && geometry.is_none() {
        return Err(FeaturesError::Input(
            "--preset or --bearing-geometry: the table's sidecar names its bearing; the FEMTO/PRONOSTIA documentation gives no geometry, pass elements=N,ball=D,pitch=P,angle=DEG (mm, degrees)".into(),
        ));
    }
    let listing = files::list(dir, layout)?;
    if listing.files.is_empty() {
        return Err(files::no_file_of(dir, layout));
    }
    files::check_out(dir, layout, &listing, out, &sidecar_path(out))?;
    let mut rows: Vec<FeatureRow> = vec![];
    let mut skipped = listing.skipped.clone();
    let mut fs = match layout {
        RawLayout::Femto => FEMTO_FS,
        RawLayout::Xjtu => XJTU_FS,
        _ => IMS_FS,
    };
    let mut samples_per = None;
    let mut columns: Option<u64> = None;
    let mut unit = String::from("unknown");
    let mut channel = String::new();
    let mut clock = files::FemtoClock::default();
    // Octave band levels (analysis::octave_bands), at the first snapshot's sample rate.
    let mut bands: Vec<((f64, f64), Vec<f64>)> = vec![];
    for f in &listing.files {
        let path = &f.path;
        let rec =
            match layout {
                RawLayout::Ims => {
                    let ch =
                        match o.channel.as_deref() {
                            None => 1,
                            Some(c) => c.strip_prefix("ch").unwrap_or(c).parse::<usize>().map_err(
                                |_| {
                                    FeaturesError::Input(format!(
                                        "--channel {c}: IMS channels are numbered 1..8"
                                    ))
                                },
                            )?,
                        };
                    read_ims_snapshot(path, ch)?
                }
                RawLayout::Femto => {
                    let sep = if crate::io::layout::first_line(path)?.contains(';') {
                        b';'
                    } else {
                        b','
                    };
                    read_femto(path, sep, o.channel.as_deref())?
                }
                _ => read_layout(
                    path,
                    TextLayout::XjtuSy,
                    &ReadOptions {
                        channel: o.channel.clone(),
                        ..ReadOptions::default()
                    },
                )?,
            };
        fs = rec.fs;
        unit = rec.unit.clone();
        channel = rec.channel.clone();
        // A channel number means one sensor only while every snapshot has the same columns
        // (IMS test 1 has 8, tests 2 and 3 have 4): a file of another width is another
        // recording (stop 68: one 8-column file among 4-column ones was read silently).
        let width = rec
            .meta
            .get("n_channels")
            .and_then(serde_json::Value::as_u64);
        match (columns, width) {
            (None, w) => columns = w,
            (Some(n), Some(w)) if n != w => {
                return Err(FeaturesError::Input(format!(
                    "{}: {w} columns, the first snapshot has {n}; a channel number names one sensor only if every snapshot has the same columns",
                    path.display()
                )))
            }
            _ => {}
        }
        match samples_per {
            None => samples_per = Some(rec.samples.len()),
            Some(n) if n != rec.samples.len() => {
                return Err(FeaturesError::Input(format!(
                "{}: {} samples, the first snapshot has {n}; a table's snapshots share one length",
                path.display(),
                rec.samples.len()
            )))
            }
            _ => {}
        }
        let time_s = match f.time_s {
            Some(t) => t,
            None => clock.time(dir, path, files::femto_clock(path)?)?,
        };
        let s = match stats(&rec.samples) {
            Ok(s) => s,
            Err(e) => {
                skipped.push(format!("{}: {e}", path.display()));
                continue;
            }
        };
        if bands.is_empty() {
            bands = octave_edges(rec.fs)
                .into_iter()
                .map(|b| (b, vec![]))
                .collect();
        }
        let edges: Vec<(f64, f64)> = bands.iter().map(|(b, _)| *b).collect();
        for ((_, col), v) in bands
            .iter_mut()
            .zip(band_levels(&rec.samples, rec.fs, &edges))
        {
            col.push(v);
        }
        rows.push(FeatureRow {
            snapshot: f.index,
            time_s,
            rms: s.rms,
            kurtosis: s.kurtosis,
            crest_factor: s.crest_factor,
            skewness: s.skewness,
            peak: s.peak,
        });
    }
    let id = o.bearing_id.clone().unwrap_or_else(|| {
        dir.file_name().map_or_else(
            || dir.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        )
    });
    let sidecar = FeatureSidecar {
        format: FORMAT.into(),
        format_version: FORMAT_VERSION,
        source: format!(
            "wearsim features {} --layout {}",
            dir.display(),
            format!("{layout:?}").to_lowercase()
        ),
        bearing: BearingInfo {
            preset,
            geometry: geometry.map(|g| Geometry {
                elements: g.elements,
                ball_mm: g.ball_mm,
                pitch_mm: g.pitch_mm,
                angle_deg: g.angle_deg,
            }),
            id,
        },
        channel,
        unit,
        rpm,
        radial_load_n: load_n,
        sample_rate_hz: fs,
        snapshot_samples: samples_per.unwrap_or(0) as u64,
        snapshot_interval_s: median_step(&rows),
        failure_mode,
        n_snapshots: Some(rows.len() as u64),
        notes: notes(layout, &skipped, &listing.missing, &listing.others)
            .into_iter()
            .chain(named_notes(named.as_ref(), rpm, load_n))
            .chain(simulation_limits(rpm, load_n))
            .collect(),
    };
    // The table's own checks, made here on the input so that a refusal names the folder
    // (and the flag or the files at fault), not the table that was never written.
    if rows.len() < MIN_SNAPSHOTS {
        return Err(FeaturesError::Input(format!(
            "{}: {} snapshots ({} files of layout {}{}); a life needs at least {MIN_SNAPSHOTS}",
            dir.display(),
            rows.len(),
            listing.files.len(),
            format!("{layout:?}").to_lowercase(),
            if skipped.is_empty() {
                String::new()
            } else {
                format!(", {} skipped: {}", skipped.len(), skipped.join("; "))
            }
        )));
    }
    check_rows(dir, &rows)
        .and_then(|()| check_sidecar(dir, &sidecar))
        .and_then(|()| check_against_table(dir, dir, &sidecar, &rows))
        .map_err(|e| about_input(dir, e))?;
    // A sidecar that names a model preset must describe the preset's operating point
    // (the one check `gap --life` makes): refuse it here rather than write it.
    if sidecar
        .bearing
        .preset
        .as_deref()
        .is_some_and(|p| wearsim_core::presets::by_name(p).is_some())
    {
        RigDescription::from_sidecar(&sidecar, out).map_err(|e| {
            let side = format!("{}: ", sidecar_path(out).display());
            FeaturesError::Input(format!(
                "--preset {} does not describe this table ({}); leave --preset out and give --bearing-geometry to describe the bearing at its own operating point",
                sidecar.bearing.preset.as_deref().unwrap_or(""),
                e.strip_prefix(&side).unwrap_or(&e)
            ))
        })?;
    }
    let band_cols: Vec<(String, Vec<f64>)> =
        bands.into_iter().map(|(b, v)| (band_name(b), v)).collect();
    let side = write_feature_table(out, &sidecar, &rows, &band_cols)?;
    let first = rows.first().map_or(0.0, |r| r.rms);
    let last = rows.last().map_or(0.0, |r| r.rms);
    Ok(FeaturesSummary {
        layout,
        csv: out.to_path_buf(),
        sidecar: side,
        snapshots: rows.len(),
        skipped,
        missing: listing.missing,
        // The span of the table, first to last row: the first file of the numbering may be
        // missing or skipped, so the first row need not be at 0.
        hours: rows
            .first()
            .zip(rows.last())
            .map_or(0.0, |(a, b)| b.time_s - a.time_s)
            / 3600.0,
        rms_first_last: (first, last),
        rpm_source,
        load_source,
        meta: sidecar,
    })
}
