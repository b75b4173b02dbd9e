//! `wearsim gap`: the stationary diagnosis of records of seconds, or with `--life` the
//! diagnosis along a whole life of one run-to-failure record; argument checks, the run,
//! the report files and what is printed.

use crate::cmd::args::CliError;
use crate::cmd::report::print_json;
use crate::gap::attribute::Totals;
use crate::gap::lifetime::report::{
    self as life_report, is_life_table, is_two_channel_ims_table, TWO_CHANNEL_NOTE,
};
use crate::gap::lifetime::{self, LifeOptions};
use crate::gap::report;
use crate::gap::roles::{shortened, PartLength};
use crate::gap::stationary::{diagnose, prepare, stability, where_cells, GapArgs, GapOutput};
use crate::io::feature_table::{is_feature_table, sidecar_path, FORMAT};
use std::path::Path;

/// `wearsim gap`: `--life` selects the lifetime diagnosis. A lifetime table given without
/// it is refused with the invocation to use, rather than switching mode on a file name.
pub fn run(a: &GapArgs) -> Result<(), CliError> {
    // Exclusive, writable output directory before any work (docs/reliability.md).
    let _lock = crate::io::lock::DirLock::try_acquire(&a.out).map_err(CliError::input)?;
    if let Some(p) = a.real.iter().find(|p| is_two_channel_ims_table(p)) {
        return Err(CliError::input(format!(
            "--real {}: {TWO_CHANNEL_NOTE}",
            p.display()
        )));
    }
    if a.life {
        return run_life(a);
    }
    if let Some(p) = a
        .real
        .iter()
        .find(|p| is_life_table(p) || is_feature_table(p))
    {
        return Err(CliError::input(format!(
            "--real {}: this is a lifetime record (an IMS feature table with per-bearing B<k>_rms and B<k>_kurtosis columns, or a documented feature table); diagnose it along its life with `wearsim gap --life --real {}`",
            p.display(),
            p.display()
        )));
    }
    run_stationary(a)
}

/// `wearsim gap` on records of seconds.
fn run_stationary(a: &GapArgs) -> Result<(), CliError> {
    if a.life_search.is_some() {
        return Err(CliError::input(
            "--life-search: bounds the fits of a lifetime diagnosis (--life); records of seconds use their own search budget",
        ));
    }
    let mut parts = prepare(a)?;
    let (mut at, spaces, ev) = diagnose(a, &mut parts)?;
    let stability = if a.stability {
        Some(stability(&parts, &mut at, &spaces, &ev)?)
    } else {
        None
    };
    let loo = if a.leave_one_out {
        let added = at.kept.clone();
        Some(
            crate::gap::leave_one_out::leave_one_out(
                &spaces,
                &at.final_effects,
                &added,
                parts.final_parts().0,
                parts.final_parts().2,
                &ev,
                &a.attribution_options(),
            )
            .map_err(CliError::run)?,
        )
    } else {
        None
    };
    let mut findings: Vec<String> = parts
        .roles
        .iter()
        .flat_map(|r| {
            r.meta
                .warnings
                .iter()
                .map(move |w| format!("{}: {w}", r.part))
        })
        .collect();
    findings.dedup();
    let lengths: Vec<PartLength> = parts
        .roles
        .iter()
        .map(|r| PartLength {
            role: &r.role,
            file: &r.meta.file,
            samples: (r.seconds * r.meta.fs).round() as usize,
            fs: r.meta.fs,
        })
        .collect();
    findings.extend(shortened(&lengths, a.seconds));
    findings.extend(at.findings.iter().cloned());
    let mut out = GapOutput {
        records: parts.roles.clone(),
        where_: where_cells(&parts.valid, &at),
        ranking: at.ranking.clone(),
        uninformed: at.uninformed.clone(),
        greedy: at.greedy.clone(),
        dropped: at.dropped.clone(),
        exchanged: at.exchanged.clone(),
        kept: at.kept.clone(),
        totals: Totals::of(&at),
        identified: at.identified.clone(),
        tied_with: at.tied_with.clone(),
        findings,
        leave_one_out: loo,
        calibration: parts.calibration.clone(),
        recalibration: parts.recalibrated.as_ref().map(|r| r.calibration.clone()),
        stability,
        simulations: ev.sims(),
        part_seconds: a.seconds,
        seconds: at.seconds,
        files: vec![],
    };
    crate::cancel::check()?;
    out.files = report::write(&a.out, &out, &parts.valid, &at)?;
    if a.json {
        print_json(&out)?;
    } else {
        print!("{}", report::markdown(&out));
    }
    Ok(())
}

/// `wearsim gap --life`: the gap along the life of one IMS feature table, or of
/// documented feature tables (one life each; `--train`/`--holdout` count them from 1).
fn run_life(a: &GapArgs) -> Result<(), CliError> {
    let o = life_options(a)?;
    let path = a
        .real
        .first()
        .ok_or_else(|| CliError::input("--real: no file"))?;
    let m = if is_feature_table(path) {
        lifetime::measured_tables(&a.real, &o)
    } else {
        lifetime::measured(path, &o)
    }
    .map_err(CliError::input)?;
    // A training life the simulated one cannot reach is a problem of the input.
    let c = lifetime::calibrated(&m, &o).map_err(CliError::input)?;
    let g = lifetime::diagnose_calibrated(&m, &o, &c).map_err(CliError::run)?;
    let mut out = life_report::output(&g);
    crate::cancel::check()?;
    out.files = life_report::write(&a.out, &out, &g)?;
    if a.json {
        print_json(&out)?;
    } else {
        print!("{}", life_report::markdown(&out));
    }
    Ok(())
}

/// Why `p`, which is no IMS lifetime table, is not read as a documented feature table
/// either: the sidecar path looked for and what is wrong with it.
fn why_not_table(p: &Path) -> String {
    if !p.exists() {
        return "no such file".into();
    }
    if !p.extension().is_some_and(|e| e.eq_ignore_ascii_case("csv")) {
        return "a feature table is a .csv file".into();
    }
    let side = sidecar_path(p);
    if !side.exists() {
        return format!(
            "its sidecar {} is missing (a feature table is NAME.csv with NAME.json next to it)",
            side.display()
        );
    }
    match crate::io::sidecar::read_json(&side) {
        Err(e) => format!("its sidecar cannot be read: {e}"),
        Ok(v) => format!(
            "its sidecar {} has `format` {} (a feature table's is {FORMAT:?})",
            side.display(),
            v["format"]
        ),
    }
}

fn bearings(spec: &str, what: &str) -> Result<Vec<usize>, CliError> {
    let mut out = vec![];
    for item in spec.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let digits = item.trim_start_matches(['B', 'b']);
        match digits.parse::<usize>() {
            Ok(b) if (1..=8).contains(&b) => out.push(b),
            _ => {
                return Err(CliError::input(format!(
                    "{what}: `{item}` is not a bearing of a lifetime table; give B1..B8 (or 1..8)"
                )))
            }
        }
    }
    Ok(out)
}

/// Lifetime options from the arguments; options that only make sense for raw records
/// are refused rather than ignored.
fn life_options(a: &GapArgs) -> Result<LifeOptions, CliError> {
    // Without an IMS table among them, a file that is neither kind is refused first,
    // saying why it is not a feature table (usually its sidecar is missing), rather than
    // as a mix of kinds.
    let ims = a.real.iter().any(|p| is_life_table(p));
    let bad: Vec<String> = a
        .real
        .iter()
        .filter(|p| !ims && (p.is_file() || !p.exists()) && !is_feature_table(p))
        .map(|p| {
            format!(
                "--life --real {}: not a lifetime record: {}",
                p.display(),
                why_not_table(p)
            )
        })
        .collect();
    if !bad.is_empty() {
        return Err(CliError::input(format!(
            "{}; --life needs an IMS feature table with per-bearing B<k>_rms and B<k>_kurtosis columns (e.g. test2_timefeatures.csv) or documented feature tables, each with its JSON sidecar (docs/feature-tables.md)",
            bad.join("; ")
        )));
    }
    let tables = a.real.iter().filter(|p| is_feature_table(p)).count();
    if tables > 0 && tables != a.real.len() {
        return Err(CliError::input(
            "--real: documented feature tables (docs/feature-tables.md) and IMS tables cannot be mixed in one lifetime diagnosis",
        ));
    }
    let lives = if tables > 0 { tables } else { 4 };
    if tables == 0 && a.real.len() != 1 {
        return Err(CliError::input(format!(
            "--real: a lifetime record (IMS feature table) is diagnosed alone; got {} files",
            a.real.len()
        )));
    }
    for (flag, given) in [
        ("--bearing", a.bearing.is_some()),
        ("--bearing-geometry", a.bearing_geometry.is_some()),
        ("--rpm", a.rpm.is_some()),
        ("--trust-rpm", a.trust_rpm),
        ("--defect", a.defect.is_some()),
        ("--channel", a.channel.is_some()),
        ("--fs", a.fs.is_some()),
    ] {
        if given {
            return Err(CliError::input(format!(
                "{flag}: a lifetime record is matched to its preset (IMS tables: ims-za2115, Rexnord ZA-2115, 2000 rpm, 6000 lbf, 20 480 samples a snapshot; documented tables: their sidecar) and its life; {flag} does not apply"
            )));
        }
    }
    if a.significant_gap.is_some() {
        return Err(CliError::input(
            "--significant-gap: a lifetime diagnosis takes 3× its own computed noise-only gap; the flag applies to records of seconds",
        ));
    }
    for (flag, given, why) in [
        (
            "--no-calibration",
            a.no_calibration,
            "a lifetime diagnosis fits no rig nuisances",
        ),
        (
            "--fixed-calibration",
            a.fixed_calibration,
            "a lifetime diagnosis fits no rig nuisances",
        ),
        (
            "--stability",
            a.stability,
            "a lifetime diagnosis has one training life to refit on",
        ),
    ] {
        if given {
            return Err(CliError::input(format!(
                "{flag}: {why}; the flag applies to records of seconds"
            )));
        }
    }
    let jobs = crate::lanes::workers("--jobs", a.jobs).map_err(CliError::input)?;
    let train = match &a.train {
        Some(s) => bearings(s, "--train")?,
        None => vec![1],
    };
    let [train] = train.as_slice() else {
        return Err(CliError::input(
            "--train: a lifetime diagnosis trains on one bearing (the one whose life defines the time line)",
        ));
    };
    // With --validation the lives named there choose the model and --holdout names the
    // test part (nothing chosen on it), as for records of seconds; without it the
    // held-out lives both choose and are judged (two parts).
    let validation = match &a.validation {
        Some(s) => bearings(s, "--validation")?,
        None => vec![],
    };
    if validation.contains(train) {
        return Err(CliError::input(format!(
            "--train and --validation both hold bearing {train}: a life that chooses the model must not be fitted on"
        )));
    }
    let holdout = match &a.holdout {
        Some(s) => bearings(s, "--holdout")?,
        None => (1..=lives)
            .filter(|b| b != train && !validation.contains(b))
            .collect(),
    };
    if holdout.contains(train) {
        return Err(CliError::input(format!(
            "--train and --holdout both hold bearing {train}: a held-out life must not be fitted on"
        )));
    }
    if let Some(b) = validation.iter().find(|b| holdout.contains(b)) {
        return Err(CliError::input(format!(
            "--validation and --holdout both hold bearing {b}: the test part must not choose the model"
        )));
    }
    if holdout.is_empty() {
        return Err(CliError::input(if lives < 2 {
            "--real: the input holds one life; the lifetime diagnosis fits on one life and judges on another: give a second table (--real), another bearing of the rig run to failure".to_string()
        } else {
            format!("--holdout: give at least one held-out bearing (of 1..={lives}, not the training one)")
        }));
    }
    let (holdout, test) = if validation.is_empty() {
        (holdout, vec![])
    } else {
        let test = holdout.clone();
        (validation.into_iter().chain(holdout).collect(), test)
    };
    let known = ["running-in", "roughness", "sensor", "edge-shape"];
    crate::effects::check_listed(&a.effects, "--effects").map_err(CliError::input)?;
    for e in &a.effects {
        if !known.contains(&e.as_str()) {
            return Err(CliError::input(format!(
                "--effects: `{e}` acts within a snapshot and changes no statistic along a life; the lifetime candidates are {}",
                known.join(", ")
            )));
        }
    }
    Ok(LifeOptions {
        train: *train,
        holdout,
        test,
        seed: a.seed,
        jobs,
        effects: a.effects.clone(),
        leave_one_out: a.leave_one_out,
        max_search: a.life_search.map(usize::from),
        exchange: a.exchange,
    })
}
