//! The stationary gap diagnosis (`wearsim gap` on records of seconds): arguments,
//! training/held-out selection, the attribution run, and the "where" cells of the report
//! ([`super::report`] writes it; [`crate::cmd::gap`] runs it).

use super::attribute::{
    attribute_with, Attribution, Options, Recalibrate, Totals, SIGNIFICANT_GAP,
};
use super::error::GapError;
use super::identify;
use super::informed;
use super::matched::{Evaluator, Matched};
use super::nuisance::{self, Calibration, Tolerances};
use super::protocol::judge;
use super::records::{self, Overrides, RealRecord, MIN_PART_S};
use super::roles;
use super::space;
use crate::analysis::stats::rms;
use clap::Args;
use serde::Serialize;
use std::path::PathBuf;
use std::sync::Mutex;
use wearsim_core::effects::Effects;

/// `wearsim gap` arguments.
#[derive(Debug, Clone, Args)]
pub struct GapArgs {
    /// Measured records (CWRU .mat, CSV/WAV/NPY with sidecar, IMS snapshot); repeatable.
    /// With --life: one IMS feature table (`timefeatures.csv`), diagnosed along life,
    /// --train/--holdout then name its bearings (B1, B2, ...); or documented feature
    /// tables (docs/feature-tables.md), one life each, --train/--holdout counting them from 1;
    /// --validation names lives that choose the model, and then --holdout the test lives
    /// (without it the held-out lives both choose and are judged).
    #[arg(long = "real", required = true, num_args = 1..)]
    pub real: Vec<PathBuf>,
    /// Bearing of the records: a model preset (`wearsim presets`) or a catalogue bearing of
    /// a public data set (`mfpt-nice`, `paderborn-6203`, `xjtu-ldk-uer204`; default: from
    /// the file, e.g. CWRU drive end).
    #[arg(long)]
    pub bearing: Option<String>,
    /// Geometry of a bearing that is neither: `elements=N,ball=MM,pitch=MM[,angle=DEG]`
    /// (as for `analyze`); its model is the nearest preset's, scaled by geometric
    /// similitude (an assumption the report states).
    #[arg(long)]
    pub bearing_geometry: Option<String>,
    /// Shaft speed (rpm) of every record (default: from the file, else the spectrum).
    #[arg(long, allow_negative_numbers = true)]
    pub rpm: Option<f64>,
    /// Use the stated speed (`--rpm` or the file's) even when the record's shaft line is
    /// elsewhere (a tachometer's speed). Default: as `analyze`, a stated speed 1–5 % from the
    /// record's own 1× line (with its own 2× or 3×), with no line at the stated 1×, is
    /// replaced by the speed of the line's 1×–5× series (a finding says so;
    /// `analysis::shaft_line::refine`).
    #[arg(long)]
    pub trust_rpm: bool,
    /// Defect of every record: `LOCATION:SIZE[:DEPTH]` with LOCATION none, inner, outer,
    /// outer@3, outer@6, outer@12, ball and sizes with `in` or `mm` (default: the file's
    /// label; depth 0.011 in).
    #[arg(long)]
    pub defect: Option<String>,
    /// Training records: comma-separated 1-based positions in --real or substrings of
    /// their file names (default: one record → its first part; several → the first).
    #[arg(long)]
    pub train: Option<String>,
    /// Test records, on which the reported shrink is measured and nothing is chosen
    /// (same syntax; default: one record → its third part; several → all but the
    /// training and validation ones).
    #[arg(long)]
    pub holdout: Option<String>,
    /// Validation records, on which the model is chosen (ranking, greedy addition,
    /// dropping) (same syntax; default: one record → its second part; with --holdout →
    /// the records neither trained on nor held out; without it, three or more → the
    /// first record not trained on; none left → a part of each training record right
    /// after its training part, disjoint from it). Every record takes one role: with all
    /// three of --train, --validation, --holdout given, a record in none is refused.
    #[arg(long)]
    pub validation: Option<String>,
    /// Seconds of each record (or record part) analysed, 0.5..=30: at most, a record too
    /// short for disjoint parts of this length gives shorter ones, stated in a finding
    /// and `records[].seconds` (the gap's scale depends on the part length).
    #[arg(long, default_value_t = 2.0)]
    pub seconds: f64,
    /// Candidate effects to try, comma-separated (default: all that act on the records).
    #[arg(long, value_delimiter = ',')]
    pub effects: Vec<String>,
    /// Channel (CWRU: DE, FE, BA).
    #[arg(long)]
    pub channel: Option<String>,
    /// Sample rate (Hz): for a file that states none; must agree (within 0.1 %) with a
    /// rate the file or its sidecar states (else exit 2).
    #[arg(long, allow_negative_numbers = true)]
    pub fs: Option<f64>,
    /// Unit of the samples, `g` or `m/s^2`: for a file that states none (NPY, a CSV
    /// without a unit in its header, a MAT file of another lab); must agree with a unit
    /// the file or its sidecar states (else exit 2).
    #[arg(long)]
    pub units: Option<String>,
    /// Mains frequency (Hz) of the hum candidate, 40..=70.
    #[arg(long, default_value_t = 60.0)]
    pub mains: f64,
    /// Seed of the matched simulations.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Worker threads, 1 ..= 256 (default: all cores; 1 for the one-core benchmark).
    #[arg(long)]
    pub jobs: Option<usize>,
    /// Output directory.
    #[arg(long, default_value = "wearsim-gap")]
    pub out: PathBuf,
    /// Also withhold each greedily added effect from the full model and check that the
    /// diagnosis names it (costs one attribution per added effect).
    #[arg(long)]
    pub leave_one_out: bool,
    /// Do not calibrate the rig's nuisances (housing resonance and damping, defect size,
    /// load, speed, within their tolerances: `gap::nuisance`) on the training part before
    /// ranking effects; the diagnosis as it was before the calibration, for comparison.
    /// Records of seconds only: a lifetime diagnosis (--life) fits no rig nuisances.
    #[arg(long)]
    pub no_calibration: bool,
    /// Keep the rig's calibration made with no effect for the whole greedy addition
    /// instead of calibrating it again with the effects kept so far after each addition;
    /// the diagnosis as it was before, for comparison (`docs/sim-to-real-results.md`,
    /// "The rig calibrated again at each greedy step").
    #[arg(long)]
    pub fixed_calibration: bool,
    /// After the greedy additions, try exchanging each kept effect for each effect not
    /// yet tried, the others refitted on top (`gap::exchange`; an experiment, off by
    /// default for its cost: `docs/sim-to-real-results.md`, "Exchanges after the greedy
    /// additions"). With --life: in the whole-life attribution.
    #[arg(long)]
    pub exchange: bool,
    /// Also refit every effect of the chosen model on each record (part) separately and
    /// compare its parameters between records (`gap::stability`): a disagreement beyond
    /// two combined standard deviations is reported as a finding. Costs one lock-step fit
    /// of the kept effects per record.
    #[arg(long)]
    pub stability: bool,
    /// With --life: most pattern-search lives of each fit after its grid (default 48):
    /// bounds the diagnosis's work, e.g. for a quick check of a new rig's tables.
    #[arg(long, value_parser = clap::value_parser!(u16).range(0..=1000))]
    pub life_search: Option<u16>,
    /// Held-out baseline gap from which an effect is named, 0.05..=100 (default 1.0, the
    /// 95th percentile of no-effect twins' gaps of the CWRU 6205 rig: a 5 % false-alarm
    /// level; `wearsim gap-validate --null N` reports the level of its own twins as
    /// `null_threshold`). Records of seconds only: a lifetime diagnosis takes 3× its
    /// computed noise-only gap.
    #[arg(long)]
    pub significant_gap: Option<f64>,
    /// Machine-readable report on stdout.
    #[arg(long)]
    pub json: bool,
    /// Lifetime mode: diagnose the gap along a whole life of one run-to-failure record
    /// (an IMS feature table such as `test2_timefeatures.csv`, or documented feature tables).
    #[arg(long)]
    pub life: bool,
}

/// A cell of "where", aggregated over the held-out records.
#[derive(Debug, Clone, Serialize)]
pub struct WhereCell {
    /// Cell name.
    pub cell: String,
    /// Group.
    pub group: String,
    /// Unit.
    pub unit: String,
    /// Simulated value (mean over held-out records).
    pub sim: f64,
    /// Measured value (mean over held-out records).
    pub real: f64,
    /// Measured spread (mean over held-out records).
    pub spread: f64,
    /// Gap of the baseline (mean over held-out records).
    pub gap: f64,
    /// Gap with the greedily added effects.
    pub gap_after: f64,
}

/// The whole `gap` report.
#[derive(Debug, Clone, Serialize)]
pub struct GapOutput {
    /// Records and their roles.
    pub records: Vec<RecordRole>,
    /// Cells ranked by |baseline gap| (where).
    #[serde(rename = "where")]
    pub where_: Vec<WhereCell>,
    /// Effects ranked by held-out shrink (which).
    pub ranking: Vec<super::attribute::Ranked>,
    /// Candidate effects not fitted because the training records cannot inform them.
    pub uninformed: Vec<super::informed::Uninformed>,
    /// Effects added greedily (how far).
    pub greedy: Vec<super::attribute::Step>,
    /// Effects taken out again because a later addition made them redundant.
    pub dropped: Vec<super::attribute::Dropped>,
    /// Exchanges made after the greedy additions (`--exchange`; empty without it).
    pub exchanged: Vec<super::exchange::Exchanged>,
    /// The effects of the final model, in the order they were added.
    pub kept: Vec<String>,
    /// Totals before and after.
    pub totals: Totals,
    /// The effect named first, if any.
    pub identified: Option<String>,
    /// Effects tied with it.
    pub tied_with: Vec<String>,
    /// Findings and limits in words.
    pub findings: Vec<String>,
    /// Leave-one-out checks (with `--leave-one-out`).
    pub leave_one_out: Option<Vec<super::leave_one_out::LeaveOneOut>>,
    /// The rig's nuisances as calibrated on the training part before any effect was
    /// ranked (`null` with `--no-calibration`).
    pub calibration: Option<Calibration>,
    /// The rig's nuisances calibrated again on the training part with the chosen model's
    /// effects on, after each greedy addition: the last of these, on which the final
    /// model's later effects were fitted and chosen and its test gap measured (`null`
    /// with `--no-calibration` or when no effect was added).
    pub recalibration: Option<Calibration>,
    /// The kept effects' parameters refitted on each record separately (`--stability`;
    /// `null` without it).
    pub stability: Option<Vec<super::stability::ParamStability>>,
    /// Simulations run.
    pub simulations: usize,
    /// Part length `--seconds` asked (s); each part's own, which a short record makes
    /// shorter, is `records[].seconds`.
    pub part_seconds: f64,
    /// Wall-clock time of the attribution (s).
    pub seconds: f64,
    /// Files written.
    pub files: Vec<PathBuf>,
}

/// A record in the report.
#[derive(Debug, Clone, Serialize)]
pub struct RecordRole {
    /// [`roles::TRAIN`], [`roles::VALIDATION`] or [`roles::TEST`].
    pub role: String,
    /// Part label.
    pub part: String,
    /// Length of the part actually used (s): `--seconds`, or less when the record does
    /// not hold disjoint parts of that length (a finding then says so).
    pub seconds: f64,
    /// Resolved metadata.
    pub meta: RealRecord,
}

fn select(spec: &str, recs: &[RealRecord]) -> Result<Vec<usize>, String> {
    let mut out = vec![];
    for item in spec.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        if let Ok(i) = item.parse::<usize>() {
            if i == 0 || i > recs.len() {
                return Err(format!(
                    "record position {i} is out of range 1..={}",
                    recs.len()
                ));
            }
            out.push(i - 1);
            continue;
        }
        let hits: Vec<usize> = recs
            .iter()
            .enumerate()
            .filter(|(_, r)| {
                r.file
                    .file_name()
                    .is_some_and(|n| n.to_string_lossy().contains(item))
            })
            .map(|(i, _)| i)
            .collect();
        if hits.is_empty() {
            return Err(format!("`{item}` matches no --real file name"));
        }
        out.extend(hits);
    }
    out.sort_unstable();
    out.dedup();
    Ok(out)
}

impl GapArgs {
    /// The attribution's settings: the defaults, with `--significant-gap` and `--exchange`
    /// when given.
    pub fn attribution_options(&self) -> Options {
        Options {
            significant_gap: self.significant_gap.unwrap_or(SIGNIFICANT_GAP),
            exchange: self.exchange,
            ..Options::default()
        }
    }

    fn check(&self) -> Result<(), GapError> {
        if !(self.seconds.is_finite() && (MIN_PART_S..=30.0).contains(&self.seconds)) {
            return Err(GapError::input(format!(
                "--seconds {} is out of range {MIN_PART_S}..=30",
                self.seconds
            )));
        }
        if !(self.mains.is_finite() && (40.0..=70.0).contains(&self.mains)) {
            return Err(GapError::input(format!(
                "--mains {} Hz is out of range 40..=70",
                self.mains
            )));
        }
        if let Some(u) = &self.units {
            records::unit_scale(u)
                .ok_or_else(|| GapError::input(format!("--units `{u}`: allowed g or m/s^2")))?;
        }
        crate::lanes::workers("--jobs", self.jobs).map_err(GapError::input)?;
        if let Some(r) = self.rpm {
            // Every record is simulated at this speed.
            crate::config::check_sim_rpm("--rpm", r).map_err(GapError::input)?;
        }
        if let Some(g) = self.significant_gap {
            if !(g.is_finite() && (0.05..=100.0).contains(&g)) {
                return Err(GapError::input(format!(
                    "--significant-gap {g} is out of range 0.05..=100 (total held-out gap)"
                )));
            }
        }
        crate::effects::check_listed(&self.effects, "--effects").map_err(GapError::input)
    }
}

/// The parts of the clean protocol: training (fit), validation (choice), test (report).
#[derive(Debug, Clone)]
pub struct Parts {
    /// Records with their roles.
    pub roles: Vec<RecordRole>,
    /// Training parts: every parameter is fitted on these.
    pub train: Vec<Matched>,
    /// Validation parts: the model is chosen on these.
    pub valid: Vec<Matched>,
    /// Test parts: the reported shrink is measured on these only.
    pub test: Vec<Matched>,
    /// The rig's calibration on the training part, once [`diagnose`] has applied it to
    /// every part's baseline (`None` before, or with `--no-calibration`).
    pub calibration: Option<Calibration>,
    /// The rig calibrated again with the chosen model's effects on
    /// ([`super::attribute::attribute_with`]), and the three parts with it: the final
    /// model was fitted and chosen on these, so its test gap, stability and leave-one-out
    /// are measured on them (`None` with `--no-calibration` or before [`diagnose`]).
    pub recalibrated: Option<Recalibrated>,
}

/// The parts with the rig calibrated for the chosen model's effects.
#[derive(Debug, Clone)]
pub struct Recalibrated {
    /// The calibration.
    pub calibration: Calibration,
    /// Training parts.
    pub train: Vec<Matched>,
    /// Validation parts.
    pub valid: Vec<Matched>,
    /// Test parts.
    pub test: Vec<Matched>,
}

impl Parts {
    /// The parts the chosen model was fitted and chosen on: recalibrated for its effects
    /// when the rig is calibrated, else the parts as prepared. (training, validation, test).
    pub fn final_parts(&self) -> (&[Matched], &[Matched], &[Matched]) {
        match &self.recalibrated {
            Some(r) => (&r.train, &r.valid, &r.test),
            None => (&self.train, &self.valid, &self.test),
        }
    }
}

/// Loads the records and builds the disjoint training, validation and test parts.
pub fn prepare(a: &GapArgs) -> Result<Parts, GapError> {
    a.check()?;
    let defect = match &a.defect {
        Some(d) => Some(records::parse_defect(d).map_err(GapError::input)?),
        None => None,
    };
    let o = Overrides {
        bearing: a.bearing.clone(),
        geometry: a.bearing_geometry.clone(),
        rpm: a.rpm,
        trust_rpm: a.trust_rpm,
        defect,
        channel: a.channel.clone(),
        fs: a.fs,
        units: a.units.clone(),
    };
    let recs: Vec<RealRecord> = a
        .real
        .iter()
        .map(|p| records::load(p, &o))
        .collect::<Result<_, _>>()
        .map_err(GapError::input)?;
    roles::distinct(&recs).map_err(GapError::input)?;
    roles::one_bearing(&recs).map_err(GapError::input)?;
    let mut p = Parts {
        roles: vec![],
        train: vec![],
        valid: vec![],
        test: vec![],
        calibration: None,
        recalibrated: None,
    };
    let push = |p: &mut Parts, r: &RealRecord, start: usize, len: usize, seed: u64, tag: &str| {
        let m = records::part(r, start, len, seed, tag).map_err(GapError::input)?;
        p.roles.push(RecordRole {
            role: tag.into(),
            part: m.label.clone(),
            seconds: len as f64 / r.fs,
            meta: r.clone(),
        });
        match tag {
            roles::TRAIN => p.train.push(m),
            roles::VALIDATION => p.valid.push(m),
            _ => p.test.push(m),
        }
        Ok::<(), GapError>(())
    };
    if recs.len() == 1 && a.train.is_none() && a.holdout.is_none() && a.validation.is_none() {
        let Some(r) = recs.first() else {
            return Err(GapError::input("--real: no file"));
        };
        let need = records::min_samples(3.0 * MIN_PART_S, r.fs);
        if r.accel.len() < need {
            return Err(GapError::input(format!(
                "{}: {:.4} s is too short for three disjoint parts (training, validation, test); one record must hold at least {:.1} s ({} samples at {} Hz), or give several records",
                r.file.display(),
                r.accel.len() as f64 / r.fs,
                3.0 * MIN_PART_S,
                need,
                r.fs
            )));
        }
        let third = r.accel.len() / 3;
        let len = third.min((a.seconds * r.fs).round() as usize);
        for (k, tag) in [roles::TRAIN, roles::VALIDATION, roles::TEST]
            .iter()
            .enumerate()
        {
            let start = k * third;
            push(&mut p, r, start, len, a.seed + start as u64, tag)?;
        }
        return Ok(p);
    }
    let pick = |spec: &Option<String>, flag: &str| -> Result<Option<Vec<usize>>, GapError> {
        spec.as_deref()
            .map(|s| select(s, &recs).map_err(|e| GapError::input(format!("{flag}: {e}"))))
            .transpose()
    };
    let r = roles::assign(
        recs.len(),
        pick(&a.train, "--train")?,
        pick(&a.validation, "--validation")?,
        pick(&a.holdout, "--holdout")?,
        |i| {
            recs.get(i)
                .map_or_else(String::new, |r| r.file.display().to_string())
        },
    )
    .map_err(GapError::input)?;
    let (ti, vi, hi) = (r.train, r.validation, r.test);
    let window = |r: &RealRecord| r.accel.len().min((a.seconds * r.fs).round() as usize);
    for (k, i) in ti.iter().enumerate() {
        let Some(r) = recs.get(*i) else { continue };
        let seed = a.seed + 1000 * k as u64 + 7 * *i as u64;
        if vi.is_empty() {
            // Validation from the training record itself, right after the training part.
            let half = r.accel.len() / 2;
            let len = window(r).min(half);
            push(&mut p, r, 0, len, seed, roles::TRAIN)?;
            push(&mut p, r, half, len, seed + 500, roles::VALIDATION)?;
        } else {
            push(&mut p, r, 0, window(r), seed, roles::TRAIN)?;
        }
    }
    for (idx, tag) in [(&vi, roles::VALIDATION), (&hi, roles::TEST)] {
        for (k, i) in idx.iter().enumerate() {
            let Some(r) = recs.get(*i) else { continue };
            let seed = a.seed + 1000 * k as u64 + 7 * *i as u64;
            push(&mut p, r, 0, window(r), seed, tag)?;
        }
    }
    Ok(p)
}

/// Runs the attribution on prepared parts (the rig calibrated and every parameter fitted
/// on training, the model chosen on validation) and judges it on the test part; returns it
/// with the fit spaces and the evaluator (for further checks on the same records). Unless
/// `--no-calibration`, every part's baseline is replaced by the rig calibrated on the
/// training part ([`nuisance::calibrate`], recorded in `p.calibration`).
pub fn diagnose(
    a: &GapArgs,
    p: &mut Parts,
) -> Result<(Attribution, Vec<space::FitSpace>, Evaluator), GapError> {
    let first = p
        .train
        .first()
        .ok_or_else(|| GapError::input("no training record"))?;
    let level = p
        .roles
        .iter()
        .find(|r| r.role == roles::TRAIN)
        // About the mean: a sensor's DC offset does not scale the fit spaces.
        .map_or(1.0, |r| rms(&super::without_mean(&r.meta.accel)));
    let ctx = space::context(first.spec(), level, a.mains, &first.base);
    let has_defect = p
        .train
        .iter()
        .chain(&p.valid)
        .chain(&p.test)
        .any(|m| m.base.defect.is_some());
    let only = (!a.effects.is_empty()).then_some(a.effects.as_slice());
    let spaces = space::applicable(&ctx, has_defect, only);
    if spaces.is_empty() {
        return Err(GapError::input(
            "--effects: none of the chosen effects acts on these records (slip, load-zone and edge-shape need a defect)",
        ));
    }
    let ev = Evaluator::new(crate::lanes::workers("--jobs", a.jobs).map_err(GapError::input)?);
    let names: Vec<String> = first.reference.names.iter().map(|n| n.0.clone()).collect();
    let envelope = super::envelope_note(first.samples, first.spec());
    // The parts on the nominal rig, kept for the calibrations with effects on.
    let nominal = (!a.no_calibration && p.calibration.is_none())
        .then(|| (p.train.clone(), p.valid.clone(), p.test.clone()));
    if let Some((train, valid, test)) = &nominal {
        let cal = nuisance::calibrate(train, &Effects::NONE, &Tolerances::CALIBRATE, &ev);
        p.train = cal.applied(train);
        p.valid = cal.applied(valid);
        p.test = cal.applied(test);
        p.calibration = Some(cal);
    }
    let (spaces, uninformed) =
        informed::split(spaces, &Effects::NONE, &p.train, &ev, &names).map_err(GapError::run)?;
    if spaces.is_empty() {
        return Err(GapError::input(format!(
            "--effects: these records cannot inform any of the chosen effects: {}",
            uninformed
                .iter()
                .map(informed::finding)
                .collect::<Vec<_>>()
                .join("; ")
        )));
    }
    let opt = a.attribution_options();
    let last: Mutex<Option<Calibration>> = Mutex::new(None);
    let recal = |fx: &Effects| -> Result<(Vec<Matched>, Vec<Matched>), String> {
        let (train, valid, _) = nominal.as_ref().ok_or("no nominal parts")?;
        let cal = nuisance::calibrate(train, fx, &Tolerances::CALIBRATE, &ev);
        let out = (cal.applied(train), cal.applied(valid));
        *last.lock().map_err(|_| "calibration lock poisoned")? = Some(cal);
        Ok(out)
    };
    let mut at = attribute_with(
        &spaces,
        &Effects::NONE,
        &p.train,
        &p.valid,
        &ev,
        &opt,
        (nominal.is_some() && !a.fixed_calibration).then_some(&recal as Recalibrate<Matched>),
    )
    .map_err(GapError::run)?;
    let last = last.into_inner().ok().flatten();
    if let (Some((train, valid, test)), Some(cal)) = (&nominal, last) {
        p.recalibrated = Some(Recalibrated {
            train: cal.applied(train),
            valid: cal.applied(valid),
            test: cal.applied(test),
            calibration: cal,
        });
    }
    at.findings.extend(uninformed.iter().map(informed::finding));
    at.findings.extend(envelope);
    if let Some(c) = &p.calibration {
        // One finding for the nuisances the record cannot inform (they share the reason).
        if let Some(n) = c.not_informed.first() {
            let names: Vec<&str> = c.not_informed.iter().map(|n| n.name).collect();
            at.findings.push(format!(
                "rig calibration: {} not informed: {}",
                names.join(" and "),
                n.reason
            ));
        }
        at.findings.extend(c.fitted.iter().filter(|f| f.at_bound).map(|f| {
            format!(
                "the rig's {} calibrated to the end of its tolerance (factor {:.3}, allowed 1 ± {}): the rig differs from its description by more than that, or an unmodelled mechanism acts through it; effects that act on the same cells may be fitted to make up the rest",
                f.name, f.factor, f.tolerance
            )
        }));
    }
    at.uninformed = uninformed;
    identify::confounded(&mut at, opt.min_shrink, opt.significant_gap);
    if let Some(v) = p.valid.first() {
        let groups: Vec<String> = v
            .reference
            .names
            .iter()
            .map(|(_, g, _)| g.to_string())
            .collect();
        identify::group_shrink(&mut at, &groups);
    }
    let (_, _, test_final) = p.final_parts();
    judge(
        &mut at,
        &Effects::NONE,
        &p.test,
        test_final,
        &ev,
        (opt.significant_gap, opt.variability),
    )
    .map_err(GapError::run)?;
    Ok((at, spaces, ev))
}

/// The chosen model's effects refitted on every record of every part separately
/// ([`super::stability::stability`]), each started from its value in the chosen model;
/// disagreements are added to the attribution's findings.
pub fn stability(
    p: &Parts,
    at: &mut Attribution,
    spaces: &[space::FitSpace],
    ev: &Evaluator,
) -> Result<Vec<super::stability::ParamStability>, GapError> {
    let kept: Vec<(String, Vec<f64>)> = at
        .kept
        .iter()
        .filter_map(|name| {
            let space = spaces.iter().find(|s| s.effect == name)?;
            let step = at.greedy.iter().rev().find(|s| &s.effect == name)?;
            let hint = space
                .fitted
                .iter()
                .map(|f| {
                    step.params
                        .iter()
                        .find(|q| q.name == f.name)
                        .map_or(0.5, |q| f.coord(q.value))
                })
                .collect();
            Some((name.clone(), hint))
        })
        .collect();
    let (train, valid, test) = p.final_parts();
    let records: Vec<Matched> = train.iter().chain(valid).chain(test).cloned().collect();
    let rows = super::stability::stability(spaces, &at.final_effects, &kept, &records, ev)
        .map_err(GapError::run)?;
    at.findings.extend(
        rows.iter()
            .filter(|r| !r.agree)
            .map(super::stability::finding),
    );
    Ok(rows)
}

/// "Where", aggregated over the validation records (where the model was chosen).
pub fn where_cells(hold: &[Matched], at: &Attribution) -> Vec<WhereCell> {
    let Some(first) = hold.first() else {
        return vec![];
    };
    let n = first.reference.names.len();
    let mut out: Vec<WhereCell> = (0..n)
        .filter_map(|i| {
            let (name, group, unit) = first.reference.names.get(i)?;
            let mut acc = (0.0, 0.0, 0.0, 0.0, 0.0, 0usize);
            for (k, m) in hold.iter().enumerate() {
                let j = k * n + i;
                let (Some(g0), Some(g1), Some(r), Some(s)) = (
                    at.holdout_before.gaps.get(j),
                    at.holdout_after.gaps.get(j),
                    m.reference.mean.get(i),
                    m.reference.spread.get(i),
                ) else {
                    continue;
                };
                acc.0 += r + g0 * s;
                acc.1 += r;
                acc.2 += s;
                acc.3 += g0;
                acc.4 += g1;
                acc.5 += 1;
            }
            let c = acc.5.max(1) as f64;
            Some(WhereCell {
                cell: name.clone(),
                group: group.to_string(),
                unit: unit.to_string(),
                sim: acc.0 / c,
                real: acc.1 / c,
                spread: acc.2 / c,
                gap: acc.3 / c,
                gap_after: acc.4 / c,
            })
        })
        .collect();
    out.sort_by(|a, b| b.gap.abs().total_cmp(&a.gap.abs()));
    out
}
