//! Held-out validation of the simulated wear life against every failed IMS bearing
//! (`wearsim ims-validate`): calibrate on one measured life, judge on the others, and
//! leave-one-life-out (every life in turn is the calibration life).
//!
//! **Measured lives** (IMS, Qiu et al. 2006; feature tables in `shared/data/ims`, see its
//! README): test 2 bearing 1 (outer-race failure, `B1_rms`), test 1 bearing 3 (inner-race
//! failure, channel x = raw channel 5, `B3_x_rms`), test 1 bearing 4 (roller failure,
//! channel x = raw channel 7, `B4_x_rms`), test 3 bearing 3 (outer-race failure; only mean
//! |x| exists for test 3, `B3_mean_abs` of `DatasetBearingTest_3.csv`, all 6,324 files of
//! the distributed set). Each simulated life runs on the site of its measured failure
//! (`docs/life-sites.md`): outer race, inner race, rolling element. The simulated feature
//! is the measured one (RMS, or mean |x| for test 3), computed from the same window.
//!
//! **Time line.** IMS time stamps have gaps where the rig stood still ("resumption of the
//! test on the next working day", IMS readme): test 1 spans 827 h of clock time of which
//! 486 h are 24 gaps. Life position is therefore *running* time: an interval longer than
//! [`GAP_FACTOR`] × the median interval counts as one median interval. Dead snapshots
//! (machine stopped) are dropped by [`live_snapshots`].
//!
//! **What each figure is** (per life):
//! * *onset* — first snapshot of [`PERSIST`](super::ims::PERSIST) in a row above the steady
//!   band of the part of the record before it ([`super::ims::onset`]), as a fraction of the
//!   record (measured) or of the simulated life; and the *time from onset to failure* in
//!   running hours (simulated: revolutions from onset to failure at 2000 rpm). The IMS
//!   records need not start at a new bearing (test 2 covers 1.96·10⁷ revolutions against
//!   the readme's "more than 100 million"), so the fraction is of the *record*, and the
//!   hours from onset to failure are the figure that does not depend on where the record
//!   started;
//! * *trajectory distance* — RMS over 201 points of the common fraction-of-life grid of
//!   20·log₁₀(simulated / measured), both normalised by the median of their first half;
//! * *end ratio* — last live value over that median, measured and simulated, and their
//!   ratio (simulated / measured);
//! * *life ratio* — simulated revolutions to failure over the measured running
//!   revolutions (the time base carried over from the calibration life).
//!
//! **Calibrated** ([`Calibration`]): `material.life_factor` by the secant steps of
//! [`super::calibrate`] on the calibration life's running revolutions, or with
//! [`Calibration::Shape`] that and the propagation limit `material.propagation_passes` on
//! its measured onset too. Everything else is the model's physics and is not refitted per
//! life.
//!
//! **Time line** ([`Frame`]): each curve on its own fraction of life, or the simulated life
//! on the held-out record's running hours aligned at failure ([`on_record`]).

mod ensemble;
mod figures;
mod floor;
mod record;
mod sim;

pub use ensemble::*;
pub use figures::*;
pub use floor::*;
pub use record::*;
pub use sim::*;

use super::calibrate::{
    calibrate, calibrate_shape, Scales, Secant, Shape, ONSET_TOLERANCE, TOLERANCE,
};
use super::ims::{distance_db, normalise, onset, Curve};
use super::{AtCap, LifeError, LifeRun, LifeSpec};
use crate::io::ims::{read_ims_features, IMS_RPM};
use crate::io::ims_life::live_snapshots;
use serde::Serialize;
use std::path::Path;
use wearsim_core::forces::defect::DefectLocation;
use wearsim_core::wear::{LifeState, Site, Stage};

/// One calibration and the lives judged with it.
#[derive(Debug, Clone, Serialize)]
pub struct Fold {
    /// Calibration life id.
    pub calibrated_on: String,
    /// Calibrated `material.life_factor`.
    pub life_factor: f64,
    /// `material.propagation_passes` of the fold's lives: calibrated with
    /// [`Calibration::Shape`], the material's otherwise.
    pub propagation_passes: f64,
    /// What was calibrated.
    pub calibrated: Calibration,
    /// The calibration reached its targets: the simulated life within 1 % of the running
    /// revolutions, and with [`Calibration::Shape`] its onset within 0.02 of the measured
    /// one. A fold that did not is reported as it ended, not dropped.
    pub converged: bool,
    /// Measurement floor (m/s² RMS, white), calibrated on the calibration life's end
    /// ratio, or 0 (bearing only).
    pub floor: f64,
    /// Its figures on the calibration life (in-sample).
    pub calibration: LifeFigures,
    /// Figures on the other lives (held out).
    pub held_out: Vec<LifeFigures>,
    /// Medians over the held-out lives.
    pub median: Medians,
    /// The same medians for the reference prediction that needs no model: the calibration
    /// life's own measured curve taken as every held-out life's ([`copy_calibration`]).
    pub copy_calibration: Medians,
}

/// Medians over held-out lives and the acceptance of issue 14.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Medians {
    /// Median |onset error| (fraction of life); lives without an onset count as 1.
    pub onset_error: f64,
    /// Median of |log₁₀ end-ratio factor| as a factor (≥ 1).
    pub end_ratio_factor: f64,
    /// Median trajectory distance (dB RMS).
    pub distance_db_rms: f64,
    /// onset ≤ 0.1, end factor ≤ 2, distance ≤ 3 dB.
    pub accepted: [bool; 3],
}

impl Medians {
    /// Each figure's median on its own — the end factor through its logarithm, so ×3 and
    /// ×1/3 weigh alike — and issue 14's acceptance judged on them.
    fn of(onsets: Vec<f64>, end_factors: Vec<f64>, distances: Vec<f64>) -> Medians {
        let o = median(onsets);
        let e = 10f64.powf(median(
            end_factors.iter().map(|x| x.log10().abs()).collect(),
        ));
        let d = median(distances);
        Medians {
            onset_error: o,
            end_ratio_factor: e,
            distance_db_rms: d,
            accepted: [o <= 0.1, e <= 2.0, d <= 3.0],
        }
    }
}

/// Medians of a set of held-out figures.
pub fn medians(h: &[LifeFigures]) -> Medians {
    Medians::of(
        h.iter().map(|f| f.onset_error.unwrap_or(1.0)).collect(),
        h.iter().map(|f| f.end_ratio_factor).collect(),
        h.iter().map(|f| f.distance_db_rms).collect(),
    )
}

/// The figures of the reference prediction that needs no model: the measured curve of the
/// calibration life `cal` taken as the prediction of held-out life `m` (its onset, its end
/// ratio, its normalised curve against `m`'s). A model calibrated on `cal` adds something
/// only where it does better than this on the held-out lives: a persistence baseline, as
/// forecasts are judged against the forecast "as last observed".
/// On [`Frame::Record`] the calibration life's curve is carried on running hours before
/// failure ([`on_record`]), as a simulated life is.
pub fn copy_calibration(
    cal: &MeasuredRecord,
    m: &MeasuredRecord,
    frame: Frame,
) -> (Option<f64>, f64, f64) {
    let pred = match frame {
        Frame::Life => cal.curve.clone(),
        Frame::Record => on_record(&cal.curve, cal.running_h, m.running_h),
    };
    let onset_error = onset(&m.curve)
        .zip(onset(&pred))
        .map(|(a, b)| (a - b).abs());
    let last = |c: &Curve| c.rms.last().copied().unwrap_or(1.0);
    (
        onset_error,
        last(&pred) / last(&m.curve),
        distance_db(&pred, &m.curve),
    )
}

/// [`Medians`] of [`copy_calibration`] over the pairs (calibration life, held-out life)
/// `pairs`.
pub fn copy_calibration_medians(
    pairs: &[(&MeasuredRecord, &MeasuredRecord)],
    frame: Frame,
) -> Medians {
    let v: Vec<(Option<f64>, f64, f64)> = pairs
        .iter()
        .map(|(c, m)| copy_calibration(c, m, frame))
        .collect();
    Medians::of(
        v.iter().map(|x| x.0.unwrap_or(1.0)).collect(),
        v.iter().map(|x| x.1).collect(),
        v.iter().map(|x| x.2).collect(),
    )
}

/// One seed's medians in a validation repeated over seeds.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct SeedMedians {
    /// Seed of every simulated life of this repetition.
    pub seed: u64,
    /// Medians over the primary fold's held-out lives (calibrated on test 2 bearing 1).
    pub primary: Medians,
    /// Leave-one-life-out medians (the primary's with `--primary-only`).
    pub leave_one_out: Medians,
}

/// The validation repeated over seeds: each seed draws each simulated bearing's fatigue and
/// spall-propagation scatter anew and is calibrated on its own, so one seed is one draw of
/// a stochastic life and the figure of a model is their distribution, not one draw.
#[derive(Debug, Clone, Serialize)]
pub struct SeedSweep {
    /// Every seed's medians, in seed order.
    pub seeds: Vec<SeedMedians>,
    /// Median over the seeds of each primary-protocol figure.
    pub primary: Medians,
    /// Median over the seeds of each leave-one-life-out figure.
    pub leave_one_out: Medians,
}

/// Median over seeds of each figure.
fn median_of_medians(v: &[Medians]) -> Medians {
    Medians::of(
        v.iter().map(|m| m.onset_error).collect(),
        v.iter().map(|m| m.end_ratio_factor).collect(),
        v.iter().map(|m| m.distance_db_rms).collect(),
    )
}

/// [`validate_records`] for each seed of `seeds`, on the machine's cores
/// ([`super::parallel`]); the validations in seed order, or the first error.
pub fn validate_seeds(
    recs: &[MeasuredRecord],
    seeds: std::ops::RangeInclusive<u64>,
    all: bool,
    p: Protocol,
) -> Result<Vec<Validation>, String> {
    let seeds: Vec<u64> = seeds.collect();
    super::parallel::map_indexed(
        seeds.len(),
        super::parallel::default_threads(),
        |i| match seeds.get(i) {
            Some(&s) => validate_records(recs, s, all, p),
            None => Err("no such seed".into()),
        },
        &|_| {},
        || Err("a validation thread panicked".into()),
    )
    .into_iter()
    .collect()
}

/// Summarises validations of several seeds (each as returned by [`validate_records`]).
pub fn over_seeds(runs: &[Validation]) -> SeedSweep {
    let seeds: Vec<SeedMedians> = runs
        .iter()
        .map(|v| SeedMedians {
            seed: v.seed,
            primary: v.folds.first().map_or(v.leave_one_out, |f| f.median),
            leave_one_out: v.leave_one_out,
        })
        .collect();
    let pick = |f: fn(&SeedMedians) -> Medians| seeds.iter().map(f).collect::<Vec<_>>();
    SeedSweep {
        primary: median_of_medians(&pick(|s| s.primary)),
        leave_one_out: median_of_medians(&pick(|s| s.leave_one_out)),
        seeds,
    }
}

/// The whole validation.
#[derive(Debug, Clone, Serialize)]
pub struct Validation {
    /// Seed of every simulated life.
    pub seed: u64,
    /// How the measurement floor was set.
    pub floor_mode: FloorMode,
    /// What each fold calibrated (asked for; each fold says what it did).
    pub calibration: Calibration,
    /// The time line of the figures.
    pub frame: Frame,
    /// The measured lives.
    pub records: Vec<MeasuredRecordSummary>,
    /// One fold per calibration life; the first (test 2 bearing 1) is the primary protocol,
    /// all of them together are leave-one-life-out.
    pub folds: Vec<Fold>,
    /// Medians over every held-out figure of every fold (leave-one-life-out).
    pub leave_one_out: Medians,
    /// The same for the reference prediction of [`copy_calibration`] (no model): what
    /// `leave_one_out` must beat for the model to add anything to its calibration life.
    pub leave_one_out_copy: Medians,
    /// With `--seeds N` (N > 1): the validation repeated for seeds `seed .. seed + N`, this
    /// one being the first.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub over_seeds: Option<SeedSweep>,
}

/// What is reported of a measured life.
#[derive(Debug, Clone, Serialize)]
pub struct MeasuredRecordSummary {
    /// The record.
    pub record: LifeRecord,
    /// Running hours.
    pub running_h: f64,
    /// Clock hours.
    pub clock_h: f64,
    /// Stops.
    pub gaps: usize,
    /// Dead snapshots dropped.
    pub dropped: usize,
    /// Live snapshots.
    pub snapshots: usize,
}

/// Reads every record of [`RECORDS`] under `data`.
pub fn read_records(data: &Path) -> Result<Vec<MeasuredRecord>, String> {
    RECORDS.iter().map(|r| read_record(data, r)).collect()
}

/// Reads every record, then validates ([`validate_records`]).
pub fn validate(data: &Path, seed: u64, all: bool, p: Protocol) -> Result<Validation, String> {
    validate_records(&read_records(data)?, seed, all, p)
}

/// What a fold calibrates on its calibration life.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum Calibration {
    /// `material.life_factor` alone, on the running revolutions (secant steps with the
    /// crack-to-failure part held fixed).
    Length,
    /// The life factor and the propagation limit `material.propagation_passes` together, on
    /// the running revolutions and the measured onset of instability (the
    /// part before the onset and the running hours after it). The propagation limit
    /// is the wear model's one constant with neither a literature value nor a confirmed
    /// stress dependence (`shared/docs/life-physics-sources.md` §1); a measured life says
    /// how long its spall grows. A calibration life without an onset falls back to
    /// `length`, which the fold's `calibration` records.
    Shape,
}

/// The time line on which a simulated life is judged against a measured record.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum Frame {
    /// The simulated life on its own fraction of life against the record's fraction of
    /// record: both start at 0 and fail at 1.
    Life,
    /// The simulated life on the record's running time, aligned at failure: the record's
    /// end is the failure, its start is where the measurement began, which need not be a
    /// new bearing (IMS test 2 ran 1.96·10⁷ revolutions against the readme's "more than
    /// 100 million"). The simulated window `h` running hours before its failure sits at
    /// `1 − h / record hours`; a simulated life shorter than the record is read at its own
    /// steady level before its start, a longer one is cut at the record's
    /// start. Only the failure is a shared reference point, so the onset, the hours after
    /// it and the climb are compared where the record can support them.
    Record,
}

/// How a validation is run: the calibration, the time line of the figures and the
/// measurement floor.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Protocol {
    /// What each fold calibrates.
    pub calibration: Calibration,
    /// The time line of the figures.
    pub frame: Frame,
    /// How the measurement floor is set.
    pub floor: FloorMode,
}

impl Protocol {
    /// The validation as it ran before the shape calibration and the record frame: the
    /// life factor alone, fraction of life, the bearing alone.
    pub const LENGTH_ON_LIFE: Protocol = Protocol {
        calibration: Calibration::Length,
        frame: Frame::Life,
        floor: FloorMode::None,
    };
}

/// A simulated life calibrated on a measured one.
#[derive(Debug, Clone)]
pub struct Calibrated {
    /// Calibrated scales (`material.life_factor`, and with [`Calibration::Shape`]
    /// `material.propagation_passes`; otherwise the material's).
    pub scales: Scales,
    /// What was calibrated ([`Calibration::Length`] also when `Shape` was asked for a
    /// calibration life without an onset).
    pub calibration: Calibration,
    /// Revolutions to failure of the uncalibrated life (ISO 281 fatigue, factor 1).
    pub uncalibrated_life: f64,
    /// The calibration reached its targets ([`CalibratedAs::converged`]).
    pub converged: bool,
    /// The simulated life at `scales` (bearing only, no floor).
    pub life: SimLife,
}

/// Most lives [`Calibration::Shape`] runs after its first (both scales, then the length).
pub const SHAPE_STEPS: usize = 12;

/// Calibrates on the running revolutions of `cal` (and with [`Calibration::Shape`] on its
/// measured onset), simulating on the site of its failure: [`Calibration`] says how.
pub fn calibrate_on(
    cal: &MeasuredRecord,
    seed: u64,
    how: Calibration,
) -> Result<Calibrated, String> {
    let target = cal.running_h * revs_per_hour();
    let site = cal.record.site;
    // The uncalibrated life: ISO 281 fatigue at factor 1, the material's propagation limit.
    let first = simulate(site, Scales::with_factor(1.0), seed, 5e8, 0.0)?;
    let uncalibrated_life = first.life;
    let feature = cal.record.feature;
    let c = calibrate_as(
        cal,
        how,
        first,
        |s: &SimLife| Shape {
            life: s.life,
            onset: onset(&s.curve(feature)),
        },
        |s| s.fixed,
        |scales| simulate(site, scales, seed, target, 0.0),
    )?;
    Ok(Calibrated {
        scales: c.scales,
        calibration: c.calibration,
        converged: c.converged,
        uncalibrated_life,
        life: c.last,
    })
}

/// What [`calibrate_as`] returns.
#[derive(Debug, Clone)]
pub struct CalibratedAs<T> {
    /// The calibrated scales.
    pub scales: Scales,
    /// What was calibrated ([`Calibration::Length`] also when `Shape` was asked for a
    /// calibration life without an onset).
    pub calibration: Calibration,
    /// The last run, at `scales`.
    pub last: T,
    /// Runs made, the first (at life factor 1) included.
    pub runs: usize,
    /// The last run reached the targets: its length within [`TOLERANCE`] of the running
    /// revolutions and, with [`Calibration::Shape`], its onset within [`ONSET_TOLERANCE`]
    /// of the measured one.
    pub converged: bool,
}

/// The one calibration of `ims-validate`, whatever a run is (one simulated life, or a
/// population of them): `first` ran at life factor 1 and the material's propagation
/// limit; `shape` gives a run's length and onset, `fixed` its revolutions the life factor
/// does not scale (from crack opening to failure), `run` runs at given scales. With
/// [`Calibration::Shape`] and a measured onset, both scales on the length and the onset
/// ([`calibrate_shape`], up to [`SHAPE_STEPS`]); otherwise the life factor alone on the
/// length ([`calibrate`]: secant steps with the fixed part held, up to 6).
pub fn calibrate_as<T>(
    cal: &MeasuredRecord,
    how: Calibration,
    first: T,
    shape: impl Fn(&T) -> Shape,
    fixed: impl Fn(&T) -> f64,
    mut run: impl FnMut(Scales) -> Result<T, String>,
) -> Result<CalibratedAs<T>, String> {
    let target = cal.running_h * revs_per_hour();
    if let (Calibration::Shape, Some(u)) = (how, onset(&cal.curve)) {
        let c = calibrate_shape(
            target,
            u,
            Scales::with_factor(1.0),
            (shape(&first), first),
            SHAPE_STEPS,
            |a, n_p| {
                let t = run(Scales {
                    life_factor: a,
                    propagation_passes: n_p,
                })?;
                Ok::<_, String>((shape(&t), t))
            },
        )?;
        let converged = (c.shape.life / target - 1.0).abs() < TOLERANCE
            && c.shape
                .onset
                .is_some_and(|v| (v - u).abs() <= ONSET_TOLERANCE);
        return Ok(CalibratedAs {
            scales: Scales {
                life_factor: c.factor,
                propagation_passes: c.propagation_passes,
            },
            calibration: Calibration::Shape,
            last: c.last,
            runs: c.steps + 1,
            converged,
        });
    }
    let step = Secant {
        fixed: fixed(&first),
        min_steps: 1,
        max_steps: 6,
    };
    let c = calibrate(target, (shape(&first).life, first), &step, |a| {
        let t = run(Scales::with_factor(a))?;
        Ok::<_, String>((shape(&t).life, t))
    })?;
    Ok(CalibratedAs {
        scales: Scales::with_factor(c.factor),
        calibration: Calibration::Length,
        converged: (c.life / target - 1.0).abs() < TOLERANCE,
        last: c.last,
        runs: c.steps + 1,
    })
}

/// For each calibration life (all of them when `all`, else only the first, test 2
/// bearing 1) calibrates as `p.calibration` says and sets the floor by `p.floor`, then
/// judges the others on `p.frame`.
pub fn validate_records(
    recs: &[MeasuredRecord],
    seed: u64,
    all: bool,
    p: Protocol,
) -> Result<Validation, String> {
    let mode = p.floor;
    let mut folds = vec![];
    let mut copies: Vec<(&MeasuredRecord, &MeasuredRecord)> = vec![];
    let n_cal = if all { recs.len() } else { 1 };
    for cal in recs.iter().take(n_cal) {
        let site = cal.record.site;
        let c = calibrate_on(cal, seed, p.calibration)?;
        let floor = match mode {
            FloorMode::Calibrated => {
                floor_for_end_ratio(&c.life, cal.curve.rms.last().copied().unwrap_or(1.0))
            }
            FloorMode::None | FloorMode::Measured { .. } => 0.0,
        };
        // The life `m` with the fold's factor and its floor: the fold's floor, or with
        // `Measured` the record's own background.
        let run = |m: &MeasuredRecord| -> Result<(SimLife, f64), String> {
            let bare = if m.record.site == site {
                c.life.clone()
            } else {
                simulate(m.record.site, c.scales, seed, c.life.life, 0.0)?
            };
            let f = match mode {
                FloorMode::Measured { units_per_ms2 } => measured_floor(m, &bare, units_per_ms2),
                _ => floor,
            };
            if f > 0.0 {
                Ok((simulate(m.record.site, c.scales, seed, c.life.life, f)?, f))
            } else {
                Ok((bare, 0.0))
            }
        };
        let (own, f) = run(cal)?;
        let mut calibration = figures(cal, &own, "calibration", p.frame);
        calibration.floor = f;
        let mut held_out = vec![];
        let others: Vec<&MeasuredRecord> = recs
            .iter()
            .filter(|m| m.record.id != cal.record.id)
            .collect();
        let pairs: Vec<(&MeasuredRecord, &MeasuredRecord)> =
            others.iter().map(|m| (cal, *m)).collect();
        copies.extend(pairs.iter().copied());
        for m in others {
            let (s, f) = run(m)?;
            let mut fig = figures(m, &s, "held-out", p.frame);
            fig.floor = f;
            held_out.push(fig);
        }
        folds.push(Fold {
            calibrated_on: cal.record.id.into(),
            life_factor: c.scales.life_factor,
            propagation_passes: c.scales.propagation_passes,
            calibrated: c.calibration,
            converged: c.converged,
            floor,
            calibration,
            median: medians(&held_out),
            copy_calibration: copy_calibration_medians(&pairs, p.frame),
            held_out,
        });
    }
    let all_held: Vec<LifeFigures> = folds.iter().flat_map(|f| f.held_out.clone()).collect();
    Ok(Validation {
        seed,
        floor_mode: mode,
        calibration: p.calibration,
        frame: p.frame,
        records: recs
            .iter()
            .map(|m| MeasuredRecordSummary {
                record: m.record,
                running_h: m.running_h,
                clock_h: m.clock_h,
                gaps: m.gaps,
                dropped: m.dropped,
                snapshots: m.curve.t.len(),
            })
            .collect(),
        leave_one_out: medians(&all_held),
        leave_one_out_copy: copy_calibration_medians(&copies, p.frame),
        folds,
        over_seeds: None,
    })
}
