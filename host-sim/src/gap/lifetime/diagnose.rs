//! The lifetime diagnosis: read the measured lives, calibrate and run the simulated life,
//! attribute the gap to candidate effects on the training life, judge it on the held-out
//! lives, and the early-life part again on the early stages alone.

use super::rig::RigDescription;
use super::sim::{calibrate, failure_site, LifeSim, OnsetBasis, Scales};
use super::target::{life_spaces, noise_only, LifeTarget, SIGNIFICANCE};
use super::{
    stage_points, LifePoint, LifeReference, MeasuredLife, EARLY_T_MAX, HOLDOUT_T_MAX, STAGES,
    STEADY,
};
use crate::analysis::stats::upper_median;
use crate::gap::attribute::{attribute, Attribution, Options, TestTotals};
use crate::gap::fit::Budget;
use crate::gap::identify;
use crate::gap::leave_one_out::{leave_one_out, LeaveOneOut};
use crate::gap::matched::{Evaluator, Gaps};
use crate::gap::protocol::judge;
use crate::gap::roles;
use crate::gap::space::FitSpace;
use crate::io::ims_life::read_life;
use serde::Serialize;
use std::path::Path;
use std::sync::Arc;
use wearsim_core::effects::Effects;

/// Gap of one stage: root mean square of its cells' gaps, before and after.
#[derive(Debug, Clone, Serialize)]
pub struct StageGap {
    /// Stage name.
    pub stage: String,
    /// Its span of normalised life.
    pub span: (f64, f64),
    /// RMS of the cell gaps of the baseline (over the records that have the stage).
    pub before: f64,
    /// RMS of the cell gaps with the final model.
    pub after: f64,
    /// The cell with the largest baseline gap, its simulated and measured value.
    pub worst: (String, f64, f64, f64),
}

/// One cell of one life, before and after ("where").
#[derive(Debug, Clone, Serialize)]
pub struct LifeCell {
    /// The life ([`MeasuredLife::label`]: its bearing id and file).
    pub record: String,
    /// [`roles::TRAIN`], [`roles::VALIDATION`] (chose the model) or [`roles::TEST`]
    /// (judged only).
    pub role: String,
    /// Cell name `life:<stage>:<stat>`.
    pub cell: String,
    /// Stage.
    pub stage: String,
    /// Unit (`dB` or `-`).
    pub unit: String,
    /// Simulated value, baseline.
    pub sim: f64,
    /// Simulated value, final model.
    pub sim_after: f64,
    /// Measured value.
    pub real: f64,
    /// Measured spread (floored).
    pub spread: f64,
    /// Gap of the baseline.
    pub gap: f64,
    /// Gap of the final model.
    pub gap_after: f64,
}

fn life_cells(
    role: &str,
    targets: &[LifeTarget],
    (before, after): (&Effects, &Effects),
    sims: &std::sync::atomic::AtomicUsize,
) -> Vec<LifeCell> {
    let mut out = vec![];
    for t in targets {
        let r = &t.reference;
        // Each life against its own simulated life (its failure site's).
        let (Ok(pb), Ok(pa)) = (t.sim.points(before, sims), t.sim.points(after, sims)) else {
            continue;
        };
        let (Ok(b), Ok(a)) = (r.values(&pb), r.values(&pa)) else {
            continue;
        };
        let (gb, ga) = (r.residuals(&b), r.residuals(&a));
        for (i, (name, stg, unit)) in r.names.iter().enumerate() {
            let get = |v: &[f64]| v.get(i).copied().unwrap_or(f64::NAN);
            out.push(LifeCell {
                record: r.label.clone(),
                role: role.to_string(),
                cell: name.clone(),
                stage: stg.to_string(),
                unit: unit.to_string(),
                sim: get(&b),
                sim_after: get(&a),
                real: get(&r.mean),
                spread: get(&r.spread),
                gap: get(&gb),
                gap_after: get(&ga),
            });
        }
    }
    out
}

/// What one effect alone does to the early-life part of the held-out gap.
#[derive(Debug, Clone, Serialize)]
pub struct EarlyShrink {
    /// Effect.
    pub effect: String,
    /// Its parameters fitted on the training life's early stages.
    pub params: Vec<crate::gap::fit::FittedParam>,
    /// Held-out early-life gap (total over the early stages' cells) with the effect.
    pub gap: f64,
    /// `1 − gap / baseline early gap`.
    pub shrink: f64,
    /// Effects that can reproduce its early-life cell signature at the fitted point
    /// (`gap::identify`, as for the whole life): the ranking inside the set is not evidence.
    pub confounded_with: Vec<String>,
    /// Early-life gap of the test lives with it alone (none without a test part).
    pub test_gap: Option<f64>,
    /// `1 − test_gap / the test lives' baseline early gap` (none without a test part).
    pub test_shrink: Option<f64>,
}

/// How one life is compared: over which part of it, against a simulated life of which
/// wear site.
#[derive(Debug, Clone, Serialize)]
pub struct LifeSpan {
    /// The life ([`MeasuredLife::label`]: its bearing id and file).
    pub life: String,
    /// Its role: [`roles::TRAIN`] (fitted on), [`roles::VALIDATION`] (chose the model) or
    /// [`roles::TEST`] (judged only; chose nothing).
    pub role: &'static str,
    /// Its number as `--train`/`--validation`/`--holdout` count lives: the bearing of an
    /// IMS table, a feature table's position among the `--real` tables.
    pub number: usize,
    /// Its file, as given.
    pub path: String,
    /// Which bearing it is (a feature table's sidecar `bearing.id`; IMS: `test N bearing
    /// k`).
    pub id: String,
    /// Where its data come from (a feature table's sidecar `source`).
    pub source: String,
    /// Its failure mode as its source states it (`unknown` for an IMS table).
    pub failure_mode: String,
    /// Compared on the stages that end by this fraction of its life (1: the whole life).
    pub t_max: f64,
    /// Wear site of the simulated life it is compared with (`outer_race`, ...).
    pub simulated_site: String,
    /// It ran on one shaft with a failing bearing (IMS).
    pub shared_shaft: bool,
    /// Unit of its RMS.
    pub unit: String,
    /// The merged early stage that replaced the fine ones (`start` 0–3 % or `first-tenth`
    /// 0–10 %), if its table is too sparse for them; `None`: every stage resolved.
    pub merged_early: Option<&'static str>,
    /// Columns of its table the reader ignored (not part of the format), in table order.
    pub ignored_columns: Vec<String>,
}

/// Why a diagnosis without a test part has no test figure (`test_note`, and a finding);
/// `{lives}` is replaced by the held-out lives.
pub const NO_TEST_PART: &str = "no separate test part: the held-out lives ({lives}) both chose the model (ranking, greedy additions) and were judged, so the held-out totals (`totals.before`/`after`, `early.before`/`after`) are biased upwards by that choice and are no clean test figure; `totals.test_*` and `early.test` are null because no life was kept apart from the choice (give --validation LIST: those lives choose, and the --holdout lives become a test part that chooses nothing)";

/// The part of a held-out life it is judged on: a life that did not fail (`none`), or one
/// not known to have failed that shared its shaft with the bearings of its test (an IMS
/// table of no known test), only on the stages before [`HOLDOUT_T_MAX`] of its test (it
/// has no known end of life, and its late stages may carry a failing neighbour's
/// vibration); any other the whole life.
pub fn holdout_t_max(m: &MeasuredLife) -> f64 {
    if m.failure_mode == "none" || (m.shared_shaft && !m.failed()) {
        HOLDOUT_T_MAX
    } else {
        1.0
    }
}

/// The lifetime diagnosis.
#[derive(Debug, Clone, Serialize)]
pub struct LifeGap {
    /// Training life ([`roles::TRAIN`]): every parameter is fitted on it.
    pub train: Vec<String>,
    /// Validation lives ([`roles::VALIDATION`]): the model is chosen on them (ranking,
    /// greedy additions), and `stages_holdout` and the held-out totals are theirs. Without
    /// a test part these are all the held-out lives, which then both choose and are judged.
    pub validation: Vec<String>,
    /// Test lives ([`roles::TEST`]): judged with the chosen model only, nothing fitted or
    /// chosen on them; empty without a test part (`--validation` not given).
    pub test: Vec<String>,
    /// Every life not trained on: the validation lives, then the test lives (the order of
    /// `holdout_spans`).
    pub holdout: Vec<String>,
    /// Why there is no test figure, when there is none: the held-out lives chose the model
    /// and were judged, so their totals are no clean test figure.
    pub test_note: Option<String>,
    /// The simulated bearing (from the preset or the sidecar) and its assumptions.
    pub rig: RigDescription,
    /// Its closed-form defect frequencies.
    pub kinematics: wearsim_core::kinematics::FaultFrequencies,
    /// Calibrated life factor.
    pub life_factor: f64,
    /// Calibrated propagation limit (passes; the material's default when the training life
    /// has no onset).
    pub propagation_passes: f64,
    /// Onset of instability of the measured training life (fraction of life).
    pub measured_onset: Option<f64>,
    /// Onset of instability of the calibrated simulated life (fraction of life).
    pub simulated_onset: Option<f64>,
    /// What the simulated onset was read from: its RMS, or (where the RMS never leaves its
    /// steady band) its wear stages.
    pub simulated_onset_basis: OnsetBasis,
    /// Revolutions of the measured (training) life.
    pub measured_revs: f64,
    /// How the training life is compared (whole life, its failure site).
    pub train_span: LifeSpan,
    /// How each held-out life is compared.
    pub holdout_spans: Vec<LifeSpan>,
    /// Stages ranked by their baseline gap on the training life ("where along life").
    pub stages_train: Vec<StageGap>,
    /// Stages of the validation lives (those that chose the model).
    pub stages_holdout: Vec<StageGap>,
    /// Stages of the test lives (empty without a test part).
    pub stages_test: Vec<StageGap>,
    /// Held-out early-life gap of the baseline (total over the cells of the stages
    /// before [`EARLY_T_MAX`]).
    pub early_before: f64,
    /// Held-out early-life gap of the final model.
    pub early_after: f64,
    /// Each effect alone on the early-life part, best first.
    pub early: Vec<EarlyShrink>,
    /// The effect that closes the early-life part (largest early shrink ≥ 5 %, on an
    /// early gap outside the variability), if any.
    pub early_effect: Option<String>,
    /// Findings of the early-life attribution.
    pub early_findings: Vec<String>,
    /// The early-life part judged on the test lives (none without a test part): the
    /// baseline's and the final early-life model's early gap there.
    pub early_test: Option<TestTotals>,
    /// Noise-only held-out gap of the whole life and of its early part: what a correct
    /// model would leave by sampling alone ([`LifeReference::noise_only`]).
    pub noise_only: (f64, f64),
    /// Every cell of every life, ranked by |baseline gap| ("where").
    pub cells: Vec<LifeCell>,
    /// Ranking, greedy addition, totals (held-out over the shared stages).
    pub attribution: Attribution,
    /// Leave-one-out checks on the final model.
    pub leave_one_out: Vec<LeaveOneOut>,
    /// Baseline and final simulated series (for the plots).
    pub series: Vec<(String, Vec<LifePoint>)>,
    /// Measured series (training first).
    pub measured: Vec<(String, Vec<LifePoint>)>,
    /// Lives simulated in all.
    pub simulations: usize,
    /// Wall-clock time (s).
    pub seconds: f64,
}

fn stage_gaps(targets: &[LifeTarget], g: &Gaps, after: &Gaps, sims: &[Vec<f64>]) -> Vec<StageGap> {
    let mut out: Vec<StageGap> = vec![];
    let mut off = 0;
    for (k, t) in targets.iter().enumerate() {
        let r = &t.reference;
        for (i, (name, stg, _)) in r.names.iter().enumerate() {
            let (Some(b), Some(a)) = (g.gaps.get(off + i), after.gaps.get(off + i)) else {
                continue;
            };
            let sim = sims
                .get(k)
                .and_then(|s| s.get(i))
                .copied()
                .unwrap_or(f64::NAN);
            let real = r.mean.get(i).copied().unwrap_or(f64::NAN);
            let span = super::stage_named(stg).map_or((0.0, 1.0), |s| (s.lo, s.hi));
            match out.iter_mut().find(|s| s.stage == *stg) {
                Some(s) => {
                    s.before += b * b;
                    s.after += a * a;
                    if b.abs() > s.worst.3.abs() {
                        s.worst = (name.clone(), sim, real, *b);
                    }
                }
                None => out.push(StageGap {
                    stage: stg.to_string(),
                    span,
                    before: b * b,
                    after: a * a,
                    worst: (name.clone(), sim, real, *b),
                }),
            }
        }
        off += r.names.len();
    }
    // Mean square → root mean square over the stage's cells of every record.
    for s in &mut out {
        let n = targets
            .iter()
            .map(|t| {
                t.reference
                    .names
                    .iter()
                    .filter(|(_, g, _)| *g == s.stage)
                    .count()
            })
            .sum::<usize>()
            .max(1) as f64;
        s.before = (s.before / n).sqrt();
        s.after = (s.after / n).sqrt();
    }
    out.sort_by(|a, b| b.before.total_cmp(&a.before));
    out
}

/// Options of the lifetime diagnosis.
#[derive(Debug, Clone)]
pub struct LifeOptions {
    /// Training bearing (1-based).
    pub train: usize,
    /// Held-out bearings.
    pub holdout: Vec<usize>,
    /// Of the held-out bearings, those of the test part: judged with the chosen model
    /// only, nothing chosen on them (`totals.test_*`); the others choose the model
    /// (ranking, greedy additions). Empty: every held-out life chooses and is judged (a
    /// two-part protocol).
    pub test: Vec<usize>,
    /// Seed of the simulated life.
    pub seed: u64,
    /// Worker threads.
    pub jobs: usize,
    /// Candidate effects to try (empty: all of [`life_spaces`]).
    pub effects: Vec<String>,
    /// Withhold each added effect from the final model and diagnose again.
    pub leave_one_out: bool,
    /// Most pattern-search lives of each fit after its grid (`None`: [`Budget::LIFE`]'s).
    pub max_search: Option<usize>,
    /// After the greedy additions of the whole-life attribution, try exchanging kept
    /// effects ([`Options::exchange`], `--exchange`).
    pub exchange: bool,
}

/// The measured side of a lifetime diagnosis, read and checked before any simulation:
/// every problem here is one of the input (a bearing not in the table, too few snapshots).
#[derive(Debug, Clone)]
pub struct MeasuredSet {
    /// Training life.
    pub train: MeasuredLife,
    /// Its cells over the whole life.
    pub train_ref: LifeReference,
    /// Held-out lives.
    pub holdout: Vec<MeasuredLife>,
    /// Their cells ([`holdout_t_max`]: a life that did not fail before
    /// [`HOLDOUT_T_MAX`], any other over its whole life).
    pub holdout_ref: Vec<LifeReference>,
    /// The simulated bearing all lives share.
    pub rig: RigDescription,
}

/// Reads the training and held-out lives of `path` and builds their cells. Where the
/// table is one of the IMS tests ([`crate::io::ims_life::IMS_FAILURES`]), each bearing is
/// known to have failed or not: a training bearing that did not fail is refused (its
/// length would calibrate the life factor to a life that never ended), and a held-out
/// bearing that failed is judged as a failed life.
pub fn measured(path: &Path, o: &LifeOptions) -> Result<MeasuredSet, String> {
    let train = read_life(path, o.train)?;
    if train.failure_mode == "none" {
        let failed = crate::io::ims_life::failures_of(path);
        let names: Vec<String> = failed
            .iter()
            .map(|f| format!("B{} ({})", f.bearing, f.mode))
            .collect();
        return Err(format!(
            "--train B{}: bearing {} of {} did not fail (IMS test {}, end-of-test finding: failed {}); the training life must have run to failure: its length calibrates the life factor, and a life that did not fail would set it to a life that never ended; give --train B{}",
            o.train,
            o.train,
            path.display(),
            failed.first().map_or(0, |f| f.test),
            names.join(", "),
            failed.first().map_or(1, |f| f.bearing)
        ));
    }
    let holdout: Vec<MeasuredLife> = o
        .holdout
        .iter()
        .map(|b| read_life(path, *b))
        .collect::<Result<_, _>>()?;
    let rig = RigDescription::preset(train.preset.as_deref().unwrap_or("ims-za2115"))?;
    measured_from(train, holdout, rig)
}

/// Builds the cells of a training life and its held-out lives, whichever reader read
/// them (an IMS table, [`measured`]; documented feature tables,
/// [`super::tables::measured_tables`]), all of which share the simulated bearing `rig`.
pub fn measured_from(
    train: MeasuredLife,
    holdout: Vec<MeasuredLife>,
    rig: RigDescription,
) -> Result<MeasuredSet, String> {
    if holdout.is_empty() {
        return Err("--holdout: give at least one held-out life (an IMS table: another bearing, e.g. --holdout B2; feature tables: a second --real table) — a lifetime diagnosis fits on one life and judges on another".into());
    }
    let train_ref = LifeReference::new(&train.label(), &train.points, 1.0)?;
    let holdout_ref = holdout
        .iter()
        .map(|m| LifeReference::new(&m.label(), &m.points, holdout_t_max(m)))
        .collect::<Result<_, _>>()?;
    Ok(MeasuredSet {
        train,
        train_ref,
        holdout,
        holdout_ref,
        rig,
    })
}

/// The scales of a diagnosis's simulated life, calibrated on the training life at its
/// failure site.
#[derive(Debug, Clone, Copy)]
pub struct Calibration {
    /// Calibrated life factor and propagation limit.
    pub scales: Scales,
    /// Revolutions of the calibrated simulated life.
    pub revs: f64,
    /// Lives run to calibrate.
    pub runs: usize,
    /// Revolutions of the measured training life.
    pub measured_revs: f64,
    /// Onset of instability of the measured training life (fraction of life,
    /// [`crate::life::ims::onset`]); `None`: its RMS never left its steady band, and only
    /// the life factor was calibrated.
    pub measured_onset: Option<f64>,
    /// Onset of instability of the calibrated simulated life.
    pub simulated_onset: Option<f64>,
    /// What [`Calibration::simulated_onset`] was read from.
    pub simulated_onset_basis: OnsetBasis,
}

/// Calibrates the scales of `m`'s simulated life on its training life ([`calibrate`]: its
/// length and, when it has one, its onset of instability). A failure means the training
/// life cannot be reached by the simulated one: a problem of the input, which the message
/// sizes.
pub fn calibrated(m: &MeasuredSet, o: &LifeOptions) -> Result<Calibration, String> {
    let measured_revs = m.train.hours * 3600.0 * m.rig.shaft_hz;
    let site = failure_site(&m.train.failure_mode);
    let measured_onset = super::onset(&m.train.points);
    let c = calibrate(&m.rig, o.seed, measured_revs, measured_onset, site)?;
    Ok(Calibration {
        scales: c.scales,
        revs: c.revs,
        runs: c.runs,
        measured_revs,
        measured_onset,
        simulated_onset: c.onset,
        simulated_onset_basis: c.onset_basis,
    })
}

/// Diagnoses the gap along life of measured lives `m` (see the module docs).
pub fn diagnose(m: &MeasuredSet, o: &LifeOptions) -> Result<LifeGap, String> {
    let c = calibrated(m, o)?;
    diagnose_calibrated(m, o, &c)
}

fn span(
    m: &MeasuredLife,
    role: &'static str,
    r: &LifeReference,
    t_max: f64,
    sim: &LifeSim,
) -> LifeSpan {
    LifeSpan {
        life: m.label(),
        role,
        number: m.bearing,
        path: m.file.clone(),
        id: m.id.clone(),
        source: m.source.clone(),
        failure_mode: m.failure_mode.clone(),
        t_max,
        simulated_site: sim.site().name().to_string(),
        shared_shaft: m.shared_shaft,
        unit: m.unit.clone(),
        merged_early: r.merged,
        ignored_columns: m.ignored_columns.clone(),
    }
}

/// [`diagnose`] with the life factor already calibrated ([`calibrated`]). Every life is
/// compared with a simulated life of its own failure site where the model grows it
/// ([`failure_site`]); the others (`none`, `unknown`, `cage`) with the training life's.
pub fn diagnose_calibrated(
    m: &MeasuredSet,
    o: &LifeOptions,
    c: &Calibration,
) -> Result<LifeGap, String> {
    let t0 = std::time::Instant::now();
    let (train_life, hold_lives) = (&m.train, &m.holdout);
    let kinematics = m.rig.kinematics()?;
    let (scales, revs, cal_runs, measured_revs) = (c.scales, c.revs, c.runs, c.measured_revs);
    let train_site = failure_site(&train_life.failure_mode);
    let sim = Arc::new(LifeSim::new(&m.rig, scales, o.seed, revs, train_site)?);
    let mut sims: Vec<Arc<LifeSim>> = vec![sim.clone()];
    let train = vec![LifeTarget {
        reference: m.train_ref.clone(),
        sim: sim.clone(),
        only: None,
    }];
    let mut hold: Vec<LifeTarget> = vec![];
    let mut holdout_spans = vec![];
    for (life, r) in hold_lives.iter().zip(&m.holdout_ref) {
        let own = match failure_site(&life.failure_mode) {
            None => sim.clone(),
            Some(loc) => {
                let s = Arc::new(LifeSim::new(&m.rig, scales, o.seed, revs, Some(loc))?);
                match sims.iter().find(|x| x.site() == s.site()) {
                    Some(x) => x.clone(),
                    None => {
                        sims.push(s.clone());
                        s
                    }
                }
            }
        };
        let role = if o.test.contains(&life.bearing) {
            roles::TEST
        } else {
            roles::VALIDATION
        };
        holdout_spans.push(span(life, role, r, holdout_t_max(life), &own));
        hold.push(LifeTarget {
            reference: r.clone(),
            sim: own,
            only: None,
        });
    }
    // The test part (issue 13's three parts along lives): set apart before anything is
    // fitted or chosen.
    let (mut test, mut choose): (Vec<LifeTarget>, Vec<LifeTarget>) = (vec![], vec![]);
    for (life, t) in hold_lives.iter().zip(hold) {
        if o.test.contains(&life.bearing) {
            test.push(t);
        } else {
            choose.push(t);
        }
    }
    let hold = choose;
    let labels = |role: &str| -> Vec<String> {
        hold_lives
            .iter()
            .zip(&holdout_spans)
            .filter(|(_, sp)| sp.role == role)
            .map(|(l, _)| l.label())
            .collect()
    };
    let (validation_lives, test_lives) = (labels(roles::VALIDATION), labels(roles::TEST));
    if hold.is_empty() {
        return Err("--validation: the lives that choose the model are all in the test part; give at least one".into());
    }
    let ev = Evaluator::new(o.jobs);
    let base = sim.points(&Effects::NONE, ev.counter())?;
    let steady = stage_points(&base, &STAGES[STEADY]);
    let steady_rms = upper_median(steady.iter().map(|p| p.rms).collect()).unwrap_or(1.0);
    let spaces: Vec<FitSpace> = life_spaces(steady_rms, m.rig.sample_rate_hz, m.rig.shaft_hz)
        .into_iter()
        .filter(|s| o.effects.is_empty() || o.effects.iter().any(|e| e == s.effect))
        .collect();
    if spaces.is_empty() {
        return Err(format!(
            "--effects: none of {:?} acts along a life; the lifetime candidates are running-in, roughness, sensor, edge-shape",
            o.effects
        ));
    }
    let noise_whole = noise_only(&hold, &base);
    let opt = Options {
        budget: Budget {
            max_search: o.max_search.unwrap_or(Budget::LIFE.max_search),
            ..Budget::LIFE
        },
        significant_gap: SIGNIFICANCE * noise_whole,
        variability: crate::gap::significance::LIFE_VARIABILITY,
        exchange: o.exchange,
        ..Options::default()
    };
    let mut at = attribute(&spaces, &Effects::NONE, &train, &hold, &ev, &opt)?;
    // Identifiability as for records of seconds (`gap::identify`): effects whose cell
    // signatures along the training life another effect can reproduce form a confounded
    // set, and each effect's held-out shrink is reported per stage (where it acts).
    identify::confounded(&mut at, opt.min_shrink, opt.significant_gap);
    identify::group_shrink(&mut at, &stage_of_cells(&hold));
    if !test.is_empty() {
        let noise_test = noise_only(&test, &base);
        judge(
            &mut at,
            &Effects::NONE,
            &test,
            &test,
            &ev,
            (SIGNIFICANCE * noise_test, opt.variability),
        )?;
        at.findings.push(format!(
            "test part: {} — nothing was fitted or chosen on it; `totals.test_before`/`test_after` are measured there only (a correct model would leave {noise_test:.2} by sampling alone); the model was chosen on the validation lives {}",
            test_lives.join(", "),
            validation_lives.join(", ")
        ));
    }
    let test_note = test
        .is_empty()
        .then(|| NO_TEST_PART.replace("{lives}", &validation_lives.join(", ")));
    if let Some(n) = &test_note {
        at.findings.push(n.clone());
    }
    // The early-life part: the same attribution on the early stages' cells only (their
    // contrasts to the steady stage), fitted on the training life's early stages and
    // judged on the held-out lives' — ranked by the shrink in the cells where that part
    // of the gap lies.
    let train_e: Vec<LifeTarget> = train.iter().filter_map(|t| t.early(EARLY_T_MAX)).collect();
    let hold_e: Vec<LifeTarget> = hold.iter().filter_map(|t| t.early(EARLY_T_MAX)).collect();
    if train_e.is_empty() || hold_e.is_empty() {
        return Err("the lives have no early stages with enough snapshots".into());
    }
    let noise_early = noise_only(&hold_e, &base);
    let early_opt = Options {
        max_effects: 1,
        significant_gap: SIGNIFICANCE * noise_early,
        ..opt
    };
    let mut early_at = attribute(&spaces, &Effects::NONE, &train_e, &hold_e, &ev, &early_opt)?;
    // The same identifiability and test part as the whole life: the confounded sets on
    // the early stages' signatures, and the early-life shrink measured on the test lives'
    // early stages, which chose nothing.
    identify::confounded(
        &mut early_at,
        early_opt.min_shrink,
        early_opt.significant_gap,
    );
    let test_e: Vec<LifeTarget> = test.iter().filter_map(|t| t.early(EARLY_T_MAX)).collect();
    let early_test = if test_e.is_empty() {
        None
    } else {
        let significant = SIGNIFICANCE * noise_only(&test_e, &base);
        let t = judge(
            &mut early_at,
            &Effects::NONE,
            &test_e,
            &test_e,
            &ev,
            (significant, early_opt.variability),
        )?;
        Some(t)
    };
    let early_before = early_at.baseline_holdout;
    let early: Vec<EarlyShrink> = early_at
        .ranking
        .iter()
        .map(|r| EarlyShrink {
            effect: r.effect.clone(),
            params: r.params.clone(),
            gap: r.holdout_gap,
            shrink: r.shrink,
            confounded_with: r.confounded_with.clone(),
            test_gap: r.test_gap,
            test_shrink: r.test_shrink,
        })
        .collect();
    // An early life within the snapshots' own variability needs no effect: naming one
    // would be a ranking with false confidence.
    let early_effect = early_at
        .identified
        .clone()
        .filter(|_| early_before >= early_opt.significant_gap);
    let early_findings = early_at.findings.clone();
    let loo = if o.leave_one_out {
        leave_one_out(
            &spaces,
            &at.final_effects,
            &at.kept,
            &train,
            &hold,
            &ev,
            &opt,
        )?
    } else {
        vec![]
    };
    let train_before = ev.residuals(&train, &Effects::NONE)?;
    let train_after = ev.residuals(&train, &at.final_effects)?;
    let fin = sim.points(&at.final_effects, ev.counter())?;
    // Each life's baseline values against its own simulated life.
    let vals = |ts: &[LifeTarget]| -> Vec<Vec<f64>> {
        ts.iter()
            .map(|t| {
                t.sim
                    .points(&Effects::NONE, ev.counter())
                    .ok()
                    .and_then(|p| t.reference.values(&p).ok())
                    .unwrap_or_default()
            })
            .collect()
    };
    let fx = (&Effects::NONE, &at.final_effects);
    let mut cells = life_cells(roles::TRAIN, &train, fx, ev.counter());
    cells.extend(life_cells(roles::VALIDATION, &hold, fx, ev.counter()));
    cells.extend(life_cells(roles::TEST, &test, fx, ev.counter()));
    cells.sort_by(|a, b| b.gap.abs().total_cmp(&a.gap.abs()));
    let stages_test = if test.is_empty() {
        vec![]
    } else {
        let (tb, ta) = (
            ev.residuals(&test, &Effects::NONE)?,
            ev.residuals(&test, &at.final_effects)?,
        );
        stage_gaps(&test, &tb, &ta, &vals(&test))
    };
    let hold_e_final = ev.residuals(&hold_e, &at.final_effects)?;
    let early_after = hold_e_final.total();
    at.simulations = ev.sims();
    Ok(LifeGap {
        train: vec![train_life.label()],
        validation: validation_lives,
        test: test_lives,
        holdout: holdout_spans.iter().map(|sp| sp.life.clone()).collect(),
        test_note,
        rig: m.rig.clone(),
        kinematics,
        life_factor: scales.life_factor,
        propagation_passes: scales.propagation_passes,
        measured_onset: c.measured_onset,
        simulated_onset: c.simulated_onset,
        simulated_onset_basis: c.simulated_onset_basis,
        measured_revs,
        train_span: span(train_life, roles::TRAIN, &m.train_ref, 1.0, &sim),
        holdout_spans,
        stages_train: stage_gaps(&train, &train_before, &train_after, &vals(&train)),
        stages_holdout: stage_gaps(&hold, &at.holdout_before, &at.holdout_after, &vals(&hold)),
        stages_test,
        early_before,
        early_after,
        early,
        early_effect,
        early_findings,
        early_test,
        noise_only: (noise_whole, noise_early),
        cells,
        attribution: at,
        leave_one_out: loo,
        series: vec![
            ("baseline".into(), base.to_vec()),
            ("final model".into(), fin.to_vec()),
        ],
        measured: std::iter::once(train_life)
            .chain(hold_lives)
            .map(|m| (m.label(), m.points.clone()))
            .collect(),
        simulations: ev.sims() + cal_runs,
        seconds: t0.elapsed().as_secs_f64(),
    })
}

/// The stage of every cell that counts, over `lives` in order (the order of their gaps in
/// an attribution): the groups of [`identify::group_shrink`] along a life.
fn stage_of_cells(lives: &[LifeTarget]) -> Vec<String> {
    lives
        .iter()
        .flat_map(|t| {
            let names = &t.reference.names;
            let idx: Vec<usize> = match &t.only {
                Some(i) => i.clone(),
                None => (0..names.len()).collect(),
            };
            idx.into_iter()
                .filter_map(|i| names.get(i).map(|(_, stage, _)| stage.to_string()))
                .collect::<Vec<_>>()
        })
        .collect()
}
