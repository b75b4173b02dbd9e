//! The validation against the model's distribution instead of one draw (`wearsim
//! ims-validate --ensemble N`).
//!
//! A simulated life is one draw of its bearing's fatigue, initiation and propagation
//! scatter; a measured life is one draw of the real ones. Comparing one with the other
//! (the per-seed tables of [`super::validate_records`]) mixes the model's error with two
//! draws' scatter: the same model gives 3.9 to 11.2 dB on the primary fold depending on
//! the seed (`docs/ims-validation-seeds.md`). Here one population of `N` seeds stands for
//! the model, as a stochastic degradation model is judged in prognostics (coverage of
//! the predictive band, the probability integral transform of the observation):
//!
//! * **calibration** — one `life_factor` for the population: secant steps
//!   ([`super::super::calibrate`]) until the *median* simulated life of the `N` seeds on
//!   the calibration life's site equals its running revolutions. Nothing else is fitted.
//! * **per life** (calibration and held out), from the `N` simulated lives at that factor
//!   on the life's own failure site:
//!   * [`Spread`]s of the onset (fraction of life), the hours from onset to failure, the
//!     end level (median of the last 5 %), the last value and the simulated life over the
//!     record's running revolutions: 5 %, 50 % and 95 % quantiles over the seeds and the
//!     measured value's rank among them (PIT: the share of simulated values below it,
//!     ties counted half). A model whose distribution holds the measurement gives PITs
//!     spread over 0–1; one that is always too high or too low gives PITs near 0 or 1;
//!   * *coverage*: the share of the [`GRID`] points of the measured normalised curve that
//!     lie inside the pointwise 5–95 % band of the simulated curves — on the
//!     fraction-of-life axis, and on hours before failure over the record's running hours
//!     (the axis a record that need not start at a new bearing can support; a simulated
//!     life shorter than the record holds its first, healthy, value before it starts).
//!     A measured life drawn from the simulated population would be covered at about
//!     90 % of the points;
//!   * the distance (dB RMS) of the measured curve to the pointwise *median* curve on
//!     both axes, and the spread over the seeds of the per-seed distance that the
//!     acceptance of issue 14 judges;
//!   * the same distance for a null model that never degrades (1 throughout): the
//!     measured curves stay near their healthy level for most of the record, so a
//!     distance is only informative where it beats this one;
//!   * the three distances (one seed's, the median curve's, the null curve's) over the
//!     degradation part only — the grid points from the measured onset to failure —
//!     where a flat line is far from the measured climb.
//!
//! Held-out discipline: a fold's factor comes from its calibration life alone; the
//! held-out lives choose nothing. With three held-out lives a PIT is an anecdote, not a
//! test of calibration: the report lists them, and counts how many fall in [`BAND`].

use super::super::parallel::{default_threads, map_indexed};
use super::*;
use crate::analysis::stats::quantile;
use crate::life::ims::{distance_db_from, interp, GRID};

/// The central band of the simulated population (quantiles).
pub const BAND: [f64; 2] = [0.05, 0.95];

/// Smallest and largest population.
pub const ENSEMBLE_RANGE: std::ops::RangeInclusive<u64> = 5..=200;

/// One figure over the simulated population, and the measured value among it.
#[derive(Debug, Clone, Serialize)]
pub struct Spread {
    /// The measured value (none where the record has none, e.g. no onset).
    pub measured: Option<f64>,
    /// [`BAND`]'s lower quantile of the simulated values (none if no life had the figure).
    pub low: Option<f64>,
    /// Median of the simulated values.
    pub median: Option<f64>,
    /// [`BAND`]'s upper quantile.
    pub high: Option<f64>,
    /// Simulated lives that have the figure (a life without an onset has no onset time).
    pub defined: usize,
    /// Share of the simulated values below the measured one, ties counted half (PIT).
    pub pit: Option<f64>,
}

impl Spread {
    /// The spread of `sim` (non-finite values are left out) around `measured`.
    pub fn of(measured: Option<f64>, sim: &[Option<f64>]) -> Spread {
        let mut v: Vec<f64> = sim
            .iter()
            .flatten()
            .copied()
            .filter(|x| x.is_finite())
            .collect();
        v.sort_by(f64::total_cmp);
        let q = |p: f64| quantile(&v, p);
        let pit = measured.filter(|_| !v.is_empty()).map(|m| {
            let below = v.iter().filter(|x| **x < m).count() as f64;
            let equal = v.iter().filter(|x| **x == m).count() as f64;
            (below + 0.5 * equal) / v.len() as f64
        });
        Spread {
            measured,
            low: q(BAND[0]),
            median: q(0.5),
            high: q(BAND[1]),
            defined: v.len(),
            pit,
        }
    }

    /// Whether the measured value lies inside the simulated [`BAND`] (none without a
    /// measured value or simulated ones): the same band as the coverage's.
    pub fn inside(&self) -> Option<bool> {
        let (m, lo, hi) = (self.measured?, self.low?, self.high?);
        Some((lo..=hi).contains(&m))
    }
}

/// The figures of one measured life against the simulated population.
#[derive(Debug, Clone, Serialize)]
pub struct EnsembleLife {
    /// Record id.
    pub id: String,
    /// `calibration` or `held-out`.
    pub role: String,
    /// Onset of instability (fraction of record / of simulated life).
    pub onset: Spread,
    /// Running hours from onset to failure.
    pub onset_to_failure_h: Spread,
    /// Median of the normalised curve over its last 5 % ([`END_SHARE`]).
    pub end_level: Spread,
    /// Last value of the normalised curve.
    pub end_ratio: Spread,
    /// Simulated revolutions to failure over the record's running revolutions (measured:
    /// 1, so the PIT is the share of simulated lives shorter than the record).
    pub life_ratio: Spread,
    /// Share of the measured curve's grid points inside the simulated 5–95 % band, on
    /// the fraction-of-life axis.
    pub coverage_life: f64,
    /// The same on hours before failure over the record's running hours.
    pub coverage_hours: f64,
    /// Distance (dB RMS) of the measured curve to the pointwise median curve, fraction of
    /// life.
    pub distance_to_median_db: f64,
    /// The same on hours before failure.
    pub distance_to_median_hours_db: f64,
    /// The per-seed trajectory distance (dB RMS, the acceptance's figure) over the seeds;
    /// no measured value.
    pub distance_db: Spread,
    /// The null model's distance (dB RMS): a curve that never leaves its healthy level
    /// (1 throughout) against the measured one. A simulated curve, or the median of a
    /// population, is only informative where it beats this.
    pub distance_flat_db: f64,
    /// Start of the degradation part (fraction of the record): the measured onset; none
    /// without one (then the three figures below are none too).
    pub late_from: Option<f64>,
    /// The per-seed distance (dB RMS) over the degradation part only, over the seeds:
    /// where a degrading model has to beat the null curve.
    pub distance_late_db: Spread,
    /// The median curve's distance over the degradation part.
    pub distance_late_to_median_db: Option<f64>,
    /// The null curve's distance over the degradation part.
    pub distance_late_flat_db: Option<f64>,
}

/// One fold: a factor calibrated on one life's population, every life judged with it.
#[derive(Debug, Clone, Serialize)]
pub struct EnsembleFold {
    /// Calibration life id.
    pub calibrated_on: String,
    /// Calibrated `material.life_factor`.
    pub life_factor: f64,
    /// `material.propagation_passes`: with [`Calibration::Shape`] calibrated on the
    /// population's median revolutions from onset to failure, otherwise the material's.
    pub propagation_passes: f64,
    /// What was calibrated ([`Calibration::Length`] also when `Shape` was asked for a
    /// calibration life without an onset).
    pub calibrated: Calibration,
    /// The calibration reached its targets ([`CalibratedAs::converged`], on the
    /// population's median life and its median part after the onset); a fold that did not is
    /// reported as it ended.
    pub converged: bool,
    /// Median simulated life over the record's running revolutions on the calibration
    /// life (1 within the calibration tolerance).
    pub calibration_median_ratio: f64,
    /// Populations of `N` lives run by the calibration (the probe at factor 1 included).
    pub calibration_rounds: usize,
    /// The calibrated population's median running hours from onset to failure, each life
    /// read on its own time line (the population's shape: what [`Calibration::Shape`]
    /// calibrates on the measured hours; `None` when fewer than half the lives have an
    /// onset). Read on the record's hours (`calibration.onset_to_failure_h` with
    /// [`Frame::Record`]) a life whose damaged part is longer than the record shows only the
    /// part inside it, so that median can only be shorter.
    pub calibration_median_onset_to_failure_h: Option<f64>,
    /// The calibration life (in sample).
    pub calibration: EnsembleLife,
    /// The other lives (held out).
    pub held_out: Vec<EnsembleLife>,
    /// Summary over the held-out lives.
    pub summary: EnsembleSummary,
}

/// A summary over held-out lives.
#[derive(Debug, Clone, Serialize)]
pub struct EnsembleSummary {
    /// Lives summarised.
    pub lives: usize,
    /// Mean coverage on the fraction-of-life axis.
    pub mean_coverage_life: f64,
    /// Mean coverage on hours before failure.
    pub mean_coverage_hours: f64,
    /// Median distance to the median curve (dB RMS, fraction of life).
    pub median_distance_to_median_db: f64,
    /// Median over lives of the per-seed distance's median (dB RMS): what one seed gives
    /// typically.
    pub median_seed_distance_db: f64,
    /// Median of the null model's distance (dB RMS, [`EnsembleLife::distance_flat_db`]).
    pub median_distance_flat_db: f64,
    /// Over the degradation part (after the measured onset): the median curve's distance
    /// (median over lives, dB RMS).
    pub median_late_to_median_db: f64,
    /// The same for one seed (median over lives of the per-seed median).
    pub median_late_seed_db: f64,
    /// The same for the null curve.
    pub median_late_flat_db: f64,
    /// Onset-to-failure hours: measured values inside the simulated [`BAND`] / lives with
    /// both.
    pub onset_to_failure_inside: [usize; 2],
    /// End level: the same.
    pub end_level_inside: [usize; 2],
    /// Onset fraction: the same.
    pub onset_inside: [usize; 2],
}

/// The ensemble validation.
#[derive(Debug, Clone, Serialize)]
pub struct EnsembleValidation {
    /// First seed of the population.
    pub first_seed: u64,
    /// Seeds in the population.
    pub n: u64,
    /// What each fold was asked to calibrate.
    pub calibration: Calibration,
    /// The time line of the per-seed figures and the degradation part.
    pub frame: Frame,
    /// One fold per calibration life (the first is the primary protocol).
    pub folds: Vec<EnsembleFold>,
    /// Summary over every held-out life of every fold (leave-one-life-out).
    pub leave_one_out: EnsembleSummary,
}

/// `N` lives on `site` at `scales`, seeds `first ..`, windows every `expected /`
/// [`SIM_SNAPSHOTS`] revolutions: the seeds in one contiguous part per core, each part's
/// lives side by side ([`simulate_seeds`]).
fn population(
    site: Site,
    scales: Scales,
    seeds: &[u64],
    expected: f64,
) -> Result<Vec<SimLife>, String> {
    let parts = default_threads().clamp(1, seeds.len().max(1));
    let chunks: Vec<&[u64]> = seeds.chunks(seeds.len().div_ceil(parts).max(1)).collect();
    map_indexed(
        chunks.len(),
        parts,
        |i| {
            simulate_seeds(
                site,
                scales,
                chunks.get(i).copied().unwrap_or(&[]),
                expected,
                0.0,
            )
        },
        &|_| {},
        || vec![Err("a simulation thread panicked".to_string())],
    )
    .into_iter()
    .flatten()
    .collect()
}

fn median_of(v: impl Iterator<Item = f64>) -> f64 {
    median(v.collect())
}

/// The population's typical shape: its median life, and an onset placed so that the part
/// after it is the median of the lives' revolutions from onset to failure (over the lives
/// that have an onset; none when fewer than half do). The part after the onset is what the
/// propagation limit scales and what a record read on its hours before failure compares,
/// so the median of that part, not of the onset fractions, is what is calibrated.
fn population_shape(p: &[SimLife], feature: Feature) -> Shape {
    let life = median_of(p.iter().map(|s| s.life));
    let post: Vec<f64> = p
        .iter()
        .filter_map(|s| onset(&s.curve(feature)).map(|u| (1.0 - u) * s.life))
        .collect();
    let onset = (2 * post.len() >= p.len() && !post.is_empty() && life > 0.0)
        .then(|| (1.0 - median_of(post.into_iter()) / life).clamp(0.0, 1.0));
    Shape { life, onset }
}

/// Calibrates the population on `cal` as `how` says ([`calibrate_as`]: the life factor
/// on its median life, and with [`Calibration::Shape`] the propagation limit on its
/// median revolutions from onset to failure, [`population_shape`]), on `cal`'s site.
fn calibrate_population(
    cal: &MeasuredRecord,
    seeds: &[u64],
    how: Calibration,
) -> Result<CalibratedAs<Vec<SimLife>>, String> {
    let target = cal.running_h * revs_per_hour();
    let site = cal.record.site;
    let first = population(site, Scales::with_factor(1.0), seeds, 5e8)?;
    let feature = cal.record.feature;
    calibrate_as(
        cal,
        how,
        first,
        |p: &Vec<SimLife>| population_shape(p, feature),
        |p| median_of(p.iter().map(|s| s.fixed)),
        |scales| population(site, scales, seeds, target),
    )
}

/// Coverage of `meas` by the pointwise band of `sims` over the common grid, and the
/// pointwise median curve of `sims` on that grid.
fn band_figures(meas: &Curve, sims: &[Curve]) -> (f64, Curve) {
    let mut inside = 0usize;
    let (mut t, mut mid) = (Vec::with_capacity(GRID), Vec::with_capacity(GRID));
    for i in 0..GRID {
        let ti = i as f64 / (GRID - 1) as f64;
        let mut v: Vec<f64> = sims.iter().map(|c| interp(c, ti)).collect();
        v.sort_by(f64::total_cmp);
        let m = interp(meas, ti);
        let (lo, hi) = (
            quantile(&v, BAND[0]).unwrap_or(f64::NAN),
            quantile(&v, BAND[1]).unwrap_or(f64::NAN),
        );
        if (lo..=hi).contains(&m) {
            inside += 1;
        }
        t.push(ti);
        mid.push(quantile(&v, 0.5).unwrap_or(f64::NAN));
    }
    (inside as f64 / GRID as f64, Curve { t, rms: mid })
}

/// The figures of record `m` against population `pop` (its own site, one calibration),
/// each simulated life read on `frame` for the per-seed figures (onset, hours, distance,
/// end) and the degradation part. On [`Frame::Life`] the hours axis is [`on_hours`] and
/// the degradation part is read on the fraction of life, as before the record frame; on
/// [`Frame::Record`] both are [`on_record`], the per-seed figures' own reading.
pub fn ensemble_life(
    m: &MeasuredRecord,
    pop: &[SimLife],
    role: &str,
    frame: Frame,
) -> EnsembleLife {
    let figs: Vec<LifeFigures> = pop.iter().map(|s| figures(m, s, role, frame)).collect();
    let curves: Vec<Curve> = pop.iter().map(|s| s.curve(m.record.feature)).collect();
    let span = m.running_h;
    let hours: Vec<Curve> = curves
        .iter()
        .zip(pop)
        .map(|(c, s)| {
            let life_h = s.life / revs_per_hour();
            match frame {
                Frame::Life => on_hours(c, life_h, span),
                Frame::Record => on_record(c, life_h, span),
            }
        })
        .collect();
    let (coverage_life, median_life) = band_figures(&m.curve, &curves);
    let (coverage_hours, median_hours) = band_figures(&m.curve, &hours);
    // The degradation part: from the measured onset to failure, on the frame's time line.
    let late_from = onset(&m.curve);
    let late = |c: &Curve| late_from.map(|from| distance_db_from(c, &m.curve, from));
    let (late_curves, late_median) = match frame {
        Frame::Life => (&curves, &median_life),
        Frame::Record => (&hours, &median_hours),
    };
    let col = |f: fn(&LifeFigures) -> Option<f64>| figs.iter().map(f).collect::<Vec<_>>();
    let first = figs.first();
    EnsembleLife {
        id: m.record.id.into(),
        role: role.into(),
        onset: Spread::of(
            first.and_then(|f| f.onset_measured),
            &col(|f| f.onset_simulated),
        ),
        onset_to_failure_h: Spread::of(
            first.and_then(|f| f.onset_to_failure_h_measured),
            &col(|f| f.onset_to_failure_h_simulated),
        ),
        end_level: Spread::of(
            first.map(|f| f.end_level_measured),
            &col(|f| Some(f.end_level_simulated)),
        ),
        end_ratio: Spread::of(
            first.map(|f| f.end_ratio_measured),
            &col(|f| Some(f.end_ratio_simulated)),
        ),
        life_ratio: Spread::of(Some(1.0), &col(|f| Some(f.life_ratio))),
        coverage_life,
        coverage_hours,
        distance_to_median_db: distance_db(&median_life, &m.curve),
        distance_to_median_hours_db: distance_db(&median_hours, &m.curve),
        distance_db: Spread::of(None, &col(|f| Some(f.distance_db_rms))),
        distance_flat_db: distance_db(&flat(), &m.curve),
        late_from,
        distance_late_db: Spread::of(None, &late_curves.iter().map(late).collect::<Vec<_>>()),
        distance_late_to_median_db: late(late_median),
        distance_late_flat_db: late(&flat()),
    }
}

/// The null model's normalised curve: the healthy level, 1, over the whole life.
fn flat() -> Curve {
    Curve {
        t: vec![0.0, 1.0],
        rms: vec![1.0, 1.0],
    }
}

/// Summary over `lives`.
pub fn summarise(lives: &[EnsembleLife]) -> EnsembleSummary {
    let n = lives.len().max(1) as f64;
    let count = |f: fn(&EnsembleLife) -> &Spread| {
        let with: Vec<bool> = lives.iter().filter_map(|l| f(l).inside()).collect();
        [with.iter().filter(|b| **b).count(), with.len()]
    };
    // Median over the lives of one figure, a missing one as NaN (`figures::median` keeps
    // non-finite values, so missing figures show rather than drop out).
    let med = |f: fn(&EnsembleLife) -> Option<f64>| {
        median_of(lives.iter().map(|l| f(l).unwrap_or(f64::NAN)))
    };
    EnsembleSummary {
        lives: lives.len(),
        mean_coverage_life: lives.iter().map(|l| l.coverage_life).sum::<f64>() / n,
        mean_coverage_hours: lives.iter().map(|l| l.coverage_hours).sum::<f64>() / n,
        median_distance_to_median_db: med(|l| Some(l.distance_to_median_db)),
        median_seed_distance_db: med(|l| l.distance_db.median),
        median_distance_flat_db: med(|l| Some(l.distance_flat_db)),
        median_late_to_median_db: med(|l| l.distance_late_to_median_db),
        median_late_seed_db: med(|l| l.distance_late_db.median),
        median_late_flat_db: med(|l| l.distance_late_flat_db),
        onset_to_failure_inside: count(|l| &l.onset_to_failure_h),
        end_level_inside: count(|l| &l.end_level),
        onset_inside: count(|l| &l.onset),
    }
}

/// The ensemble validation of `recs` with seeds `first .. first + n`: every life in turn
/// calibrates (only the first, test 2 bearing 1, unless `all`).
pub fn validate_ensemble(
    recs: &[MeasuredRecord],
    first: u64,
    n: u64,
    all: bool,
    how: Calibration,
    frame: Frame,
) -> Result<EnsembleValidation, String> {
    if !ENSEMBLE_RANGE.contains(&n) {
        return Err(format!(
            "ensemble of {n} seeds: allowed {}..={}",
            ENSEMBLE_RANGE.start(),
            ENSEMBLE_RANGE.end()
        ));
    }
    let seeds: Vec<u64> = (0..n)
        .map(|i| first.checked_add(i).ok_or("the last seed overflows u64"))
        .collect::<Result<_, _>>()?;
    let mut folds = vec![];
    for cal in recs.iter().take(if all { recs.len() } else { 1 }) {
        let c = calibrate_population(cal, &seeds, how)?;
        let (scales, own) = (c.scales, c.last);
        let target = cal.running_h * revs_per_hour();
        let mut held_out = vec![];
        for m in recs.iter().filter(|m| m.record.id != cal.record.id) {
            let pop = if m.record.site == cal.record.site {
                own.clone()
            } else {
                population(m.record.site, scales, &seeds, target)?
            };
            held_out.push(ensemble_life(m, &pop, "held-out", frame));
        }
        folds.push(EnsembleFold {
            calibrated_on: cal.record.id.into(),
            life_factor: scales.life_factor,
            propagation_passes: scales.propagation_passes,
            calibrated: c.calibration,
            converged: c.converged,
            calibration_median_ratio: median_of(own.iter().map(|s| s.life)) / target,
            calibration_rounds: c.runs,
            calibration_median_onset_to_failure_h: {
                let s = population_shape(&own, cal.record.feature);
                s.onset.map(|u| (1.0 - u) * s.life / revs_per_hour())
            },
            calibration: ensemble_life(cal, &own, "calibration", frame),
            summary: summarise(&held_out),
            held_out,
        });
    }
    let all_held: Vec<EnsembleLife> = folds.iter().flat_map(|f| f.held_out.clone()).collect();
    Ok(EnsembleValidation {
        first_seed: first,
        n,
        calibration: how,
        frame,
        folds,
        leave_one_out: summarise(&all_held),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A spread's band (type-7 quantiles of the defined values) and its PIT with ties, on
    /// values whose answers are known.
    #[test]
    fn spread_band_and_pit_by_hand() {
        let sim: Vec<Option<f64>> = vec![
            Some(1.0),
            Some(2.0),
            Some(2.0),
            None,
            Some(f64::NAN),
            Some(4.0),
        ];
        let s = Spread::of(Some(2.0), &sim);
        assert_eq!(s.defined, 4);
        assert_eq!(s.pit, Some(0.5), "one below, two equal of four");
        assert_eq!(s.inside(), Some(true));
        let near = |x: Option<f64>, y: f64| (x.unwrap() - y).abs() < 1e-12;
        assert!(
            near(s.low, 1.15) && near(s.median, 2.0) && near(s.high, 3.7),
            "{s:?}"
        );
        let s = Spread::of(Some(9.0), &sim);
        assert_eq!((s.pit, s.inside()), (Some(1.0), Some(false)));
        assert_eq!(Spread::of(None, &sim).pit, None);
        assert_eq!(Spread::of(Some(1.0), &[None]).pit, None);
    }

    /// A measured curve drawn from the band is covered; one 20 dB above the whole band is
    /// not, and its distance to the median curve is 20 dB.
    #[test]
    fn coverage_and_distance_to_the_median_curve() {
        let t: Vec<f64> = (0..=10).map(|i| i as f64 / 10.0).collect();
        let flat = |k: f64| Curve {
            t: t.clone(),
            rms: vec![k; t.len()],
        };
        let sims: Vec<Curve> = (1..=21).map(|i| flat(0.9 + 0.01 * i as f64)).collect();
        let (cov, mid) = band_figures(&flat(1.0), &sims);
        assert_eq!(cov, 1.0);
        let d = distance_db(&mid, &flat(1.0));
        assert!(d.abs() < 0.5, "{d}");
        let (cov, mid) = band_figures(&flat(10.0), &sims);
        assert_eq!(cov, 0.0);
        let d = distance_db(&mid, &flat(10.0));
        assert!((d - 20.0).abs() < 0.1, "{d}");
        // Over the late part only: a curve that is 20 dB off after 0.5 and on before.
        let step = Curve {
            t: vec![0.0, 0.5, 0.5000001, 1.0],
            rms: vec![1.0, 1.0, 10.0, 10.0],
        };
        let late = distance_db_from(&flat(1.0), &step, 0.6);
        assert!((late - 20.0).abs() < 1e-9, "{late}");
        assert!(distance_db(&flat(1.0), &step) < late);
    }

    /// Hours before failure: a life twice the span puts its midpoint at the span's start.
    #[test]
    fn hours_axis_aligns_lives_at_failure() {
        let c = Curve {
            t: vec![0.0, 0.5, 1.0],
            rms: vec![1.0, 2.0, 3.0],
        };
        let h = on_hours(&c, 200.0, 100.0);
        assert_eq!(h.t, vec![-1.0, 0.0, 1.0]);
        assert_eq!(interp(&h, 0.0), 2.0);
        assert_eq!(interp(&h, 0.5), 2.5);
    }
}
