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
//!   band of the first half of the record ([`super::ims::onset`]), as a fraction of the
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
//! **Calibrated**: `material.life_factor` only, by the secant steps of
//! [`super::calibrate`] on the calibration life's running revolutions. Everything else is
//! the model's physics and is not refitted per life.

use super::calibrate::{calibrate, Secant};
use super::ims::{distance_db, normalise, onset, Curve};
use super::{LifeError, LifeRun, LifeSpec};
use crate::io::ims::{read_ims_features, IMS_RPM};
use crate::io::ims_life::live_snapshots;
use serde::Serialize;
use std::path::Path;
use wearsim_core::forces::defect::DefectLocation;
use wearsim_core::wear::{LifeState, Site, Stage};

/// An interval longer than this many median intervals is a stop of the rig (counted as
/// one median interval of running time).
pub const GAP_FACTOR: f64 = 2.0;
/// Simulated snapshots per life: windows on a clock of `expected / SIM_SNAPSHOTS`
/// revolutions, as a periodic measurement takes them (windows at transitions are left out
/// of the curve, see [`simulate`]).
pub const SIM_SNAPSHOTS: f64 = 300.0;
/// Share of life at the end whose median is the end level (–).
pub const END_SHARE: f64 = 0.05;

/// Which per-snapshot statistic a record carries.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Feature {
    /// Root mean square (with the DC offset, as the feature tables compute it).
    Rms,
    /// Mean absolute value.
    MeanAbs,
}

/// One failed IMS bearing life.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct LifeRecord {
    /// Short id (`t2b1`, ...).
    pub id: &'static str,
    /// File under the data folder.
    pub file: &'static str,
    /// Canonical column read (see `io::ims::ImsFeatures`).
    pub column: &'static str,
    /// Statistic of the column.
    pub feature: Feature,
    /// Failure found at the end of the test (IMS readme).
    pub failure: &'static str,
    /// Wear site the simulated life runs on.
    #[serde(serialize_with = "site_name")]
    pub site: Site,
}

fn site_name<S: serde::Serializer>(s: &Site, ser: S) -> Result<S::Ok, S::Error> {
    ser.serialize_str(s.name())
}

/// The four IMS bearings that failed (IMS readme, "end-of-test finding").
pub const RECORDS: [LifeRecord; 4] = [
    LifeRecord {
        id: "t2b1",
        file: "ims/features_chocho66/test2_timefeatures.csv",
        column: "B1_rms",
        feature: Feature::Rms,
        failure: "outer race",
        site: Site::OuterRace,
    },
    LifeRecord {
        id: "t1b3",
        file: "ims/features_chocho66/test1_timefeatures.csv",
        column: "B3_x_rms",
        feature: Feature::Rms,
        failure: "inner race",
        site: Site::InnerRace,
    },
    LifeRecord {
        id: "t1b4",
        file: "ims/features_chocho66/test1_timefeatures.csv",
        column: "B4_x_rms",
        feature: Feature::Rms,
        failure: "roller",
        site: Site::Element,
    },
    LifeRecord {
        id: "t3b3",
        file: "ims/features_chocho66/DatasetBearingTest_3.csv",
        column: "B3_mean_abs",
        feature: Feature::MeanAbs,
        failure: "outer race",
        site: Site::OuterRace,
    },
];

/// A measured life on its running-time line.
#[derive(Debug, Clone, Serialize)]
pub struct MeasuredRecord {
    /// The record.
    pub record: LifeRecord,
    /// Normalised curve (fraction of running time, value over first-half median).
    pub curve: Curve,
    /// Running hours from the first to the last live snapshot.
    pub running_h: f64,
    /// Clock hours over the same span.
    pub clock_h: f64,
    /// Intervals counted as stops of the rig.
    pub gaps: usize,
    /// Snapshots dropped as dead.
    pub dropped: usize,
    /// Median of the first half of the record (record unit).
    pub steady: f64,
}

/// Reads one record under the data folder `data`. Errors name the file and the field:
/// a missing column, a non-increasing time stamp, no live snapshot.
pub fn read_record(data: &Path, r: &LifeRecord) -> Result<MeasuredRecord, String> {
    let path = data.join(r.file);
    let f = read_ims_features(&path).map_err(|e| e.to_string())?;
    let v = f.column(r.column).ok_or_else(|| {
        format!(
            "{}: no column {} (the {} life needs it; columns: {})",
            path.display(),
            r.column,
            r.id,
            f.names().join(", ")
        )
    })?;
    if let Some(i) = f.unix_s.windows(2).position(|w| w[1] <= w[0]) {
        return Err(format!(
            "{}: time stamp of row {} ({}) is not after the previous one; time must increase",
            path.display(),
            i + 3,
            f.timestamps.get(i + 1).map(String::as_str).unwrap_or("?")
        ));
    }
    let live = live_snapshots(&f);
    let keep: Vec<usize> = (0..v.len())
        .filter(|i| live.get(*i).copied().unwrap_or(false) && v[*i] > 0.0)
        .collect();
    if keep.len() < 10 {
        return Err(format!(
            "{}: {} live snapshots in {}; at least 10 needed",
            path.display(),
            keep.len(),
            r.column
        ));
    }
    let secs: Vec<f64> = keep.iter().map(|i| f.unix_s[*i] as f64).collect();
    let mut dt: Vec<f64> = secs.windows(2).map(|w| w[1] - w[0]).collect();
    let mut sorted = dt.clone();
    sorted.sort_by(f64::total_cmp);
    let median = sorted[sorted.len() / 2];
    let mut gaps = 0;
    for d in dt.iter_mut() {
        if *d > GAP_FACTOR * median {
            *d = median;
            gaps += 1;
        }
    }
    let mut run = vec![0.0];
    for d in &dt {
        run.push(run.last().copied().unwrap_or(0.0) + d / 3600.0);
    }
    let total = run.last().copied().unwrap_or(0.0);
    let t: Vec<f64> = run.iter().map(|h| h / total).collect();
    let vals: Vec<f64> = keep.iter().map(|i| v[*i]).collect();
    let curve = normalise(t, vals.clone());
    let steady = vals.first().copied().unwrap_or(0.0) / curve.rms.first().copied().unwrap_or(1.0);
    Ok(MeasuredRecord {
        record: *r,
        steady,
        curve,
        running_h: total,
        clock_h: (secs.last().copied().unwrap_or(0.0) - secs[0]) / 3600.0,
        gaps,
        dropped: v.len() - keep.len(),
    })
}

/// A simulated life: its feature at each window.
#[derive(Debug, Clone, Serialize)]
pub struct SimLife {
    /// Revolutions at each window.
    pub revs: Vec<f64>,
    /// RMS of each window (m/s²).
    pub rms: Vec<f64>,
    /// Mean |x| of each window (m/s²).
    pub mean_abs: Vec<f64>,
    /// Revolutions to failure.
    pub life: f64,
    /// Stage onsets (fraction of life).
    pub stages: Vec<(String, f64)>,
    /// Revolutions from crack opening to failure (the part `life_factor` does not scale).
    pub fixed: f64,
}

impl SimLife {
    /// The normalised curve of `feature`.
    pub fn curve(&self, feature: Feature) -> Curve {
        let t = self.revs.iter().map(|c| c / self.life).collect();
        let v = match feature {
            Feature::Rms => self.rms.clone(),
            Feature::MeanAbs => self.mean_abs.clone(),
        };
        normalise(t, v)
    }
}

/// The `ims-za2115` model with its defect on `site` (the wear state replaces the
/// topography).
pub fn model_on(site: Site) -> Result<wearsim_core::ModelConfig, String> {
    let mut m = wearsim_core::presets::by_name("ims-za2115").ok_or("preset ims-za2115 missing")?;
    if let Some(d) = m.defect.as_mut() {
        d.location = match site {
            Site::OuterRace => d.location,
            Site::InnerRace => DefectLocation::InnerRace { angle: 0.0 },
            Site::Element => DefectLocation::Ball {
                element: 0,
                phase: 0.0,
            },
        };
    }
    Ok(m)
}

/// Runs a life on `site` at `life_factor`, a window every `expected / SIM_SNAPSHOTS`
/// revolutions, with a measurement floor of white noise of RMS `floor` (m/s², the
/// `sensor` effect's `noise`; 0 = the bearing's own vibration only). The floor is
/// independent of the model's random stream, so it leaves the wear history unchanged.
pub fn simulate(
    site: Site,
    life_factor: f64,
    seed: u64,
    expected: f64,
    floor: f64,
) -> Result<SimLife, String> {
    let mut model = model_on(site)?;
    if floor > 0.0 {
        model.effects.sensor = Some(wearsim_core::effects::sensor::Params {
            noise: floor,
            corner_hz: 0.0,
            hum: 0.0,
            hum_hz: 50.0,
            hum_harmonics: 0.0,
        });
    }
    let spec = LifeSpec {
        model,
        life: crate::life::calibrate::steel_life(life_factor),
        seed,
        snapshot_every: (expected / SIM_SNAPSHOTS).max(1000.0),
        window: 0.25,
        settle: 0.05,
        calibration_load: None,
    };
    let run = LifeRun::new(spec).map_err(|e| e.to_string())?;
    let every = run.spec.snapshot_every;
    let (mut revs, mut rms, mut mean_abs) = (vec![], vec![], vec![]);
    // The measurement's clock: a window every `every` revolutions from the start, whatever
    // the wear does between them. Windows the driver renders at a transition (a breakout,
    // a spawned defect, the failure) are simulation-only instants that a periodic
    // measurement does not see, so they feed the wear (their pass loads) but not the curve.
    let d = run
        .drive(
            |st| next_on_grid(st.cycles, every) - st.cycles,
            100_000,
            |w| {
                if !w.scheduled {
                    return Ok(());
                }
                let n = w.samples.len().max(1) as f64;
                revs.push(w.state.cycles);
                rms.push((w.samples.iter().map(|x| x * x).sum::<f64>() / n).sqrt());
                mean_abs.push(w.samples.iter().map(|x| x.abs()).sum::<f64>() / n);
                Ok::<(), LifeError>(())
            },
        )
        .map_err(|e| e.to_string())?;
    let st = &d.state;
    Ok(SimLife {
        revs,
        rms,
        mean_abs,
        life: st.cycles,
        stages: st
            .events
            .iter()
            .map(|e| (e.stage.name().to_string(), e.cycles / st.cycles))
            .collect(),
        fixed: fixed_part(st),
    })
}

/// The first point of the grid `k · every` (k = 1, 2, …) after `cycles`.
fn next_on_grid(cycles: f64, every: f64) -> f64 {
    let k = (cycles / every).floor() + 1.0;
    let next = k * every;
    // A state a hair before a grid point (rounding of the advance) goes to that point, not
    // past it.
    if next - cycles > 1e-9 * every {
        next
    } else {
        next + every
    }
}

fn fixed_part(st: &LifeState) -> f64 {
    let open = st
        .events
        .iter()
        .find(|e| e.stage == Stage::CrackOpening)
        .map(|e| e.cycles)
        .unwrap_or(0.0);
    st.cycles - open
}

/// Revolutions per running hour at the IMS speed.
pub fn revs_per_hour() -> f64 {
    IMS_RPM * 60.0
}

/// Figures of one life (see the module docs for what each is).
#[derive(Debug, Clone, Serialize)]
pub struct LifeFigures {
    /// Record id.
    pub id: String,
    /// `calibration` or `held-out`.
    pub role: String,
    /// Onset, fraction of the record.
    pub onset_measured: Option<f64>,
    /// Onset, fraction of the simulated life.
    pub onset_simulated: Option<f64>,
    /// |simulated − measured| onset (fraction).
    pub onset_error: Option<f64>,
    /// Running hours from onset to the end of the record.
    pub onset_to_failure_h_measured: Option<f64>,
    /// Hours (at 2000 rpm) from the simulated onset to failure.
    pub onset_to_failure_h_simulated: Option<f64>,
    /// Trajectory distance (dB RMS).
    pub distance_db_rms: f64,
    /// End value over first-half median, measured.
    pub end_ratio_measured: f64,
    /// The same, simulated.
    pub end_ratio_simulated: f64,
    /// Simulated over measured end ratio.
    pub end_ratio_factor: f64,
    /// Median over the last [`END_SHARE`] of life of the normalised curve, measured (a
    /// figure that does not hang on the one last window; reported, not judged).
    pub end_level_measured: f64,
    /// The same, simulated.
    pub end_level_simulated: f64,
    /// Simulated revolutions over measured running revolutions.
    pub life_ratio: f64,
    /// Measured steady level: median of the first half (record unit, not stated by IMS:
    /// volts or g of a 100 mV/g PCB 353B33).
    pub steady_measured: f64,
    /// Simulated steady level at the sensor (m/s²), the same median.
    pub steady_simulated: f64,
    /// Simulated end level at the sensor (m/s²).
    pub end_simulated_abs: f64,
    /// Measurement floor of the simulated life (m/s² RMS, white).
    pub floor: f64,
    /// Simulated stage onsets (fraction of life).
    pub stages: Vec<(String, f64)>,
}

/// Median of a normalised curve over its last [`END_SHARE`] of life.
pub fn end_level(c: &Curve) -> f64 {
    median(
        c.t.iter()
            .zip(&c.rms)
            .filter(|(t, _)| **t >= 1.0 - END_SHARE)
            .map(|(_, v)| *v)
            .collect(),
    )
}

/// The figures of simulated life `s` against measured `m`.
pub fn figures(m: &MeasuredRecord, s: &SimLife, role: &str) -> LifeFigures {
    let sc = s.curve(m.record.feature);
    let sc_raw = match m.record.feature {
        Feature::Rms => &s.rms,
        Feature::MeanAbs => &s.mean_abs,
    };
    let (om, os) = (onset(&m.curve), onset(&sc));
    let em = m.curve.rms.last().copied().unwrap_or(1.0);
    let es = sc.rms.last().copied().unwrap_or(1.0);
    LifeFigures {
        id: m.record.id.into(),
        role: role.into(),
        onset_measured: om,
        onset_simulated: os,
        onset_error: om.zip(os).map(|(a, b)| (a - b).abs()),
        onset_to_failure_h_measured: om.map(|o| (1.0 - o) * m.running_h),
        onset_to_failure_h_simulated: os.map(|o| (1.0 - o) * s.life / revs_per_hour()),
        distance_db_rms: distance_db(&sc, &m.curve),
        end_ratio_measured: em,
        end_ratio_simulated: es,
        end_ratio_factor: es / em,
        end_level_measured: end_level(&m.curve),
        end_level_simulated: end_level(&sc),
        life_ratio: s.life / (m.running_h * revs_per_hour()),
        steady_measured: m.steady,
        steady_simulated: sc_raw.last().copied().unwrap_or(0.0) / es.max(1e-300),
        end_simulated_abs: sc_raw.last().copied().unwrap_or(0.0),
        floor: 0.0,
        stages: s.stages.clone(),
    }
}

/// One calibration and the lives judged with it.
#[derive(Debug, Clone, Serialize)]
pub struct Fold {
    /// Calibration life id.
    pub calibrated_on: String,
    /// Calibrated `material.life_factor`.
    pub life_factor: f64,
    /// Measurement floor (m/s² RMS, white), calibrated on the calibration life's end
    /// ratio, or 0 (bearing only).
    pub floor: f64,
    /// Its figures on the calibration life (in-sample).
    pub calibration: LifeFigures,
    /// Figures on the other lives (held out).
    pub held_out: Vec<LifeFigures>,
    /// Medians over the held-out lives.
    pub median: Medians,
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

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n == 0 {
        return f64::NAN;
    }
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
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

/// [`validate_records`] for each seed of `seeds`, one thread per seed and at most the
/// machine's cores at a time; the validations in seed order, or the first error.
pub fn validate_seeds(
    recs: &[MeasuredRecord],
    seeds: std::ops::RangeInclusive<u64>,
    all: bool,
    mode: FloorMode,
) -> Result<Vec<Validation>, String> {
    let seeds: Vec<u64> = seeds.collect();
    let width = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut runs = Vec::with_capacity(seeds.len());
    for chunk in seeds.chunks(width) {
        let done: Vec<Result<Validation, String>> = std::thread::scope(|sc| {
            let hs: Vec<_> = chunk
                .iter()
                .map(|&s| sc.spawn(move || validate_records(recs, s, all, mode)))
                .collect();
            hs.into_iter()
                .map(|h| {
                    h.join()
                        .unwrap_or_else(|_| Err("a validation thread panicked".into()))
                })
                .collect()
        });
        for r in done {
            runs.push(r?);
        }
    }
    Ok(runs)
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
    /// The measured lives.
    pub records: Vec<MeasuredRecordSummary>,
    /// One fold per calibration life; the first (test 2 bearing 1) is the primary protocol,
    /// all of them together are leave-one-life-out.
    pub folds: Vec<Fold>,
    /// Medians over every held-out figure of every fold (leave-one-life-out).
    pub leave_one_out: Medians,
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
pub fn validate(data: &Path, seed: u64, all: bool, mode: FloorMode) -> Result<Validation, String> {
    validate_records(&read_records(data)?, seed, all, mode)
}

/// The measurement floor (m/s²) that gives the simulated life `s` the end ratio
/// `target` of a calibration life. Noise independent of the vibration adds in power:
/// a window of bearing RMS `r` reads `√(r² + N²)`; the median over the first half is the
/// floored median `√(m² + N²)` (the map is monotonic), so
/// `N² = (r_end² − E² m²)/(E² − 1)`. 0 when the bearing alone ends below the target
/// (a floor can only lower the ratio). For a mean-|x| record the RMS ratio stands in for
/// the mean-|x| ratio (equal for Gaussian windows, `mean|x| = √(2/π) RMS`).
pub fn floor_for_end_ratio(s: &SimLife, target: f64) -> f64 {
    let c = s.curve(Feature::Rms);
    let Some(&end) = s.rms.last() else {
        return 0.0;
    };
    let ratio = c.rms.last().copied().unwrap_or(1.0);
    if target.is_nan() || target <= 1.0 || ratio <= target || ratio <= 0.0 {
        return 0.0;
    }
    let m = end / ratio;
    let e2 = target * target;
    ((end * end - e2 * m * m) / (e2 - 1.0)).max(0.0).sqrt()
}

/// How the simulated sensor reading gets its background.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FloorMode {
    /// The bearing's own vibration only (the model on main).
    None,
    /// A white floor calibrated on the calibration life's end ratio
    /// ([`floor_for_end_ratio`]) and carried to the held-out lives.
    Calibrated,
    /// Each life's own background from its measured steady level read in physical units
    /// ([`measured_floor`]): nothing fitted, but it rests on the unit of the record.
    Measured {
        /// Record units per m/s² (IMS does not state its unit: 1/9.80665 if g,
        /// 0.1/9.80665 if volts of the 100 mV/g PCB 353B33).
        units_per_ms2: f64,
    },
}

/// The background (m/s² RMS) a life's sensor reads besides the bearing: the measured
/// steady level in m/s² (RMS; a mean-|x| record's level times √(π/2), the Gaussian ratio)
/// minus, in power, the simulated bearing's own steady RMS `bare`; 0 when the bearing alone
/// is already as loud.
pub fn measured_floor(m: &MeasuredRecord, bare: &SimLife, units_per_ms2: f64) -> f64 {
    let level = m.steady / units_per_ms2
        * match m.record.feature {
            Feature::Rms => 1.0,
            Feature::MeanAbs => (std::f64::consts::PI / 2.0).sqrt(),
        };
    let c = bare.curve(Feature::Rms);
    let own = bare.rms.last().copied().unwrap_or(0.0) / c.rms.last().copied().unwrap_or(1.0);
    (level * level - own * own).max(0.0).sqrt()
}

/// A simulated life calibrated on a measured one.
#[derive(Debug, Clone)]
pub struct Calibrated {
    /// Calibrated `material.life_factor`.
    pub factor: f64,
    /// Revolutions to failure of the uncalibrated life (ISO 281 fatigue, factor 1).
    pub uncalibrated_life: f64,
    /// The simulated life at `factor` (bearing only, no floor).
    pub life: SimLife,
}

/// Calibrates `material.life_factor` on the running revolutions of `cal` (secant steps of
/// [`super::calibrate`] on the part of life the factor scales), simulating on the site of
/// its failure.
pub fn calibrate_on(cal: &MeasuredRecord, seed: u64) -> Result<Calibrated, String> {
    let target = cal.running_h * revs_per_hour();
    let site = cal.record.site;
    let first = simulate(site, 1.0, seed, 5e8, 0.0)?;
    let uncalibrated_life = first.life;
    let step = Secant {
        fixed: first.fixed,
        min_steps: 1,
        max_steps: 6,
    };
    let c = calibrate(target, (first.life, first), &step, |a| {
        let s = simulate(site, a, seed, target, 0.0)?;
        Ok::<_, String>((s.life, s))
    })?;
    Ok(Calibrated {
        factor: c.factor,
        uncalibrated_life,
        life: c.last,
    })
}

/// For each calibration life (all of them when `all`, else only the first, test 2
/// bearing 1) calibrates `life_factor` on its running revolutions and sets the floor by
/// `mode`, then judges the others.
pub fn validate_records(
    recs: &[MeasuredRecord],
    seed: u64,
    all: bool,
    mode: FloorMode,
) -> Result<Validation, String> {
    let mut folds = vec![];
    let n_cal = if all { recs.len() } else { 1 };
    for cal in recs.iter().take(n_cal) {
        let site = cal.record.site;
        let c = calibrate_on(cal, seed)?;
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
                simulate(m.record.site, c.factor, seed, c.life.life, 0.0)?
            };
            let f = match mode {
                FloorMode::Measured { units_per_ms2 } => measured_floor(m, &bare, units_per_ms2),
                _ => floor,
            };
            if f > 0.0 {
                Ok((simulate(m.record.site, c.factor, seed, c.life.life, f)?, f))
            } else {
                Ok((bare, 0.0))
            }
        };
        let (own, f) = run(cal)?;
        let mut calibration = figures(cal, &own, "calibration");
        calibration.floor = f;
        let mut held_out = vec![];
        for m in recs.iter().filter(|m| m.record.id != cal.record.id) {
            let (s, f) = run(m)?;
            let mut fig = figures(m, &s, "held-out");
            fig.floor = f;
            held_out.push(fig);
        }
        folds.push(Fold {
            calibrated_on: cal.record.id.into(),
            life_factor: c.factor,
            floor,
            calibration,
            median: medians(&held_out),
            held_out,
        });
    }
    let all_held: Vec<LifeFigures> = folds.iter().flat_map(|f| f.held_out.clone()).collect();
    Ok(Validation {
        seed,
        floor_mode: mode,
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
        folds,
        over_seeds: None,
    })
}
