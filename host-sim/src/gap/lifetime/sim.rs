//! The simulated life of the lifetime gap: the record's bearing run through the one life
//! driver ([`crate::life::LifeRun::drive`]) with candidate effects, a window of the measured
//! snapshot's length rendered at every block of [`SCHEDULE`], cached per effect set; and
//! the calibration of its life factor to the measured life.

use super::rig::RigDescription;
use super::{LifePoint, EARLY_T_MAX};
use crate::analysis;
use crate::gap::matched::merge;
use crate::gap::memo::Memo;
pub use crate::life::calibrate::Scales;
use crate::life::calibrate::{calibrate as calibrate_life, calibrate_shape, Secant, Shape};
use crate::life::driver::{drive_recorded, DriverWindow};
use crate::life::{AtCap, LifeError, LifeRun, LifeSpec};
use std::cell::RefCell;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use wearsim_core::effects::Effects;
use wearsim_core::forces::defect::{DefectConfig, DefectLocation};
use wearsim_core::wear::{LifeConfig, Site, Stage};

/// Window schedule of a simulated life, as fractions of the expected life: blocks of
/// `step` until `until`. Fine where running-in lives (10 windows in the first 1 % of life,
/// 20 in the next 2 %, so that the simulated stage means are about as precise as the
/// measured ones), then every 2 % of life. Windows the wear machine's transitions add are
/// not statistics of the life (a periodic measurement does not see those instants).
pub const SCHEDULE: [(f64, f64); 3] = [(0.03, 0.001), (0.1, 0.01), (1.0, 0.02)];

/// Most windows of one simulated life (the schedule needs about 90).
pub const MAX_WINDOWS: u64 = 2_000;

/// Samples per simulated window of a preset's life: the IMS snapshot's length (crest
/// factor and kurtosis depend on it). A sidecar bearing's windows have its
/// `snapshot_samples` ([`RigDescription::window_samples`]).
pub const WINDOW_SAMPLES: usize = super::rig::PRESET_WINDOW_SAMPLES;

/// A simulated life of the record's bearing with candidate effects, cached per effect set
/// (the training and held-out bearings share the simulated life of the same seed).
#[derive(Debug)]
pub struct LifeSim {
    /// Dynamic model of the bearing (no effects).
    pub model: wearsim_core::ModelConfig,
    /// Wear configuration (calibrated life factor and propagation limit).
    pub life: LifeConfig,
    /// Seed of the life (Weibull draw, window streams).
    pub seed: u64,
    /// Revolutions of the calibrated baseline life (the schedule's unit).
    pub expected_revs: f64,
    /// Samples of a window (the measured snapshot's length).
    pub window_samples: usize,
    memo: Memo<Effects, Vec<LifePoint>>,
}

/// Most effect sets kept in a [`LifeSim`]'s cache (about 3 KB each): the early-life
/// attribution revisits the whole-life fits' grids.
const CACHE: usize = 1024;

impl LifeSim {
    /// A simulated life of the bearing `rig` describes with the life factor and
    /// propagation limit of `scales`, wearing at `site` ([`failure_site`]; `None`: the
    /// model's own site, the outer race of every preset).
    pub fn new(
        rig: &RigDescription,
        scales: Scales,
        seed: u64,
        expected_revs: f64,
        site: Option<DefectLocation>,
    ) -> Result<Self, String> {
        let mut model = rig.model()?;
        if let Some(loc) = site {
            // Only a different site changes the model: the model's own site stays bit for
            // bit the model.
            if Site::of(model.defect.as_ref().map(|d| &d.location)) != Site::of(Some(&loc)) {
                let d = model
                    .defect
                    .unwrap_or(wearsim_core::presets::outer_race_defect(
                        wearsim_core::topography::MEDIUM_DEFECT,
                    ));
                model.defect = Some(DefectConfig { location: loc, ..d });
            }
        }
        Ok(LifeSim {
            model,
            window_samples: rig.window_samples,
            life: scales.life(),
            seed,
            expected_revs,
            memo: Memo::new(CACHE),
        })
    }

    /// Revolutions to the next window after `cycles`: the [`SCHEDULE`] step of the
    /// expected life; past the early part, of the revolutions run when the life outlasts
    /// its expectation (an uncalibrated life can run 30× longer; the windows then grow
    /// geometrically instead of running into the thousands).
    fn block(&self, cycles: f64) -> f64 {
        let e = self.expected_revs.max(1.0);
        let u = cycles / e;
        let step = SCHEDULE
            .iter()
            .find(|(until, _)| u < *until)
            .map_or(0.02, |(_, s)| *s);
        let scale = if u < EARLY_T_MAX { e } else { e.max(cycles) };
        (step * scale).max(1.0)
    }

    /// The surface whose wear ends this life.
    pub fn site(&self) -> Site {
        Site::of(self.model.defect.as_ref().map(|d| &d.location))
    }

    /// Runs the life with effects `fx`: snapshot statistics on the normalised time line
    /// and the revolutions to failure.
    pub fn run(&self, fx: &Effects) -> Result<(Vec<LifePoint>, f64), String> {
        let l = self.run_life(fx)?;
        Ok((l.points, l.revs))
    }

    /// [`LifeSim::run`] with the revolutions at which the life's wear entered each of
    /// [`ONSET_STAGES`].
    pub fn run_life(&self, fx: &Effects) -> Result<SimulatedLife, String> {
        self.run_lives(&[*fx])
            .pop()
            .unwrap_or_else(|| Err(LifeError::Interrupted.to_string()))
    }

    /// [`LifeSim::run_life`] for several effect sets, the lives side by side
    /// ([`drive_together`](crate::life::driver::drive_together): their windows after the
    /// first dent as the lanes of one group), each with the result it has alone.
    pub fn run_lives(&self, fxs: &[Effects]) -> Vec<Result<SimulatedLife, String>> {
        let runs: Vec<Result<LifeRun, String>> = fxs.iter().map(|fx| self.life_run(fx)).collect();
        drive_recorded(
            &runs,
            |_| |st: &wearsim_core::wear::LifeState| self.block(st.cycles),
            Recorder::observe,
            MAX_WINDOWS,
            AtCap::Refuse,
        )
        .into_iter()
        .map(|r| r.map(|(rec, d)| rec.life(&d.state)))
        .collect()
    }

    /// The life run of effects `fx` added to the model.
    fn life_run(&self, fx: &Effects) -> Result<LifeRun, String> {
        let mut model = self.model.clone();
        merge(&mut model.effects, fx);
        let fs = model.output_rate;
        LifeRun::new(LifeSpec {
            model,
            life: self.life,
            seed: self.seed,
            snapshot_every: self.block(0.0),
            window: self.window_samples as f64 / fs,
            settle: 0.05,
            calibration_load: None,
        })
        .map_err(|e| e.to_string())
    }

    /// The lives of effects `fxs`, each from the cache when it was run before; the others
    /// run side by side ([`LifeSim::run_lives`]) and are counted in `sims`, once per
    /// distinct effect set.
    pub fn points_many(
        &self,
        fxs: &[Effects],
        sims: &AtomicUsize,
    ) -> Vec<Result<Arc<Vec<LifePoint>>, String>> {
        let mut missing: Vec<Effects> = vec![];
        for fx in fxs {
            if self.memo.get(fx).is_none() && !missing.contains(fx) {
                missing.push(*fx);
            }
        }
        let mut errors: Vec<(Effects, String)> = vec![];
        if missing.len() >= 2 {
            for (fx, life) in missing.iter().zip(self.run_lives(&missing)) {
                sims.fetch_add(1, Ordering::Relaxed);
                match life {
                    Ok(l) => self.memo.insert(*fx, Arc::new(l.points)),
                    Err(e) => errors.push((*fx, e)),
                }
            }
        }
        fxs.iter()
            .map(|fx| match errors.iter().find(|(f, _)| f == fx) {
                Some((_, e)) => Err(e.clone()),
                None => self.points(fx, sims),
            })
            .collect()
    }

    /// The life with effects `fx`, from the cache when it was run before; `sims` counts
    /// the lives actually run.
    pub fn points(&self, fx: &Effects, sims: &AtomicUsize) -> Result<Arc<Vec<LifePoint>>, String> {
        self.memo.get_or_run(fx, sims, || Ok(self.run(fx)?.0))
    }
}

/// The wear stages whose start a simulated life's RMS shows as its onset of instability
/// where its defect's impacts stand out of the steady vibration: the first spall (defect
/// completion) and the spawns of new defects (damage growth). On the 8-ball rig of
/// 7.92/34.55 mm at 2100 rpm and 12 kN the RMS onset followed the start of the first of
/// them after the first quarter of the life by 0.007–0.03 of life (one or two windows of
/// the late schedule) in every life of its calibration. The propagation limit scales the life from the completed
/// spall on, the life factor the part before the first spall.
pub const ONSET_STAGES: [Stage; 2] = [Stage::DefectCompletion, Stage::DamageGrowth];

/// What a simulated life keeps of its windows: the statistics of the scheduled ones and
/// the revolutions at which the wear entered each of [`ONSET_STAGES`].
#[derive(Debug, Default)]
struct Recorder {
    raw: Vec<(f64, analysis::Stats)>,
    stage_starts: [Option<f64>; ONSET_STAGES.len()],
}

impl Recorder {
    /// The driver's observer.
    fn observe(&mut self, w: DriverWindow<'_>) -> Result<(), LifeError> {
        // A transition ends its block, so the first window in a stage is rendered at the
        // revolution the stage began.
        for (start, st) in self.stage_starts.iter_mut().zip(ONSET_STAGES) {
            if start.is_none() && w.state.stage >= st {
                *start = Some(w.state.cycles);
            }
        }
        // Stage means of a periodic measurement: windows at transitions feed the wear only
        // (see `DriverWindow::scheduled`).
        if !w.scheduled {
            return Ok(());
        }
        let cycles = w.state.cycles;
        let s =
            analysis::stats(&w.samples).map_err(|source| LifeError::Analysis { cycles, source })?;
        self.raw.push((cycles, s));
        Ok(())
    }

    /// The life that ended in `end` (its final wear state).
    fn life(self, end: &wearsim_core::wear::LifeState) -> SimulatedLife {
        let end = end.cycles.max(1.0);
        let points = self
            .raw
            .into_iter()
            .map(|(c, s)| LifePoint {
                t: c / end,
                rms: s.rms,
                kurtosis: s.kurtosis,
                crest: s.crest_factor,
                skewness: s.skewness,
            })
            .collect();
        SimulatedLife {
            points,
            revs: end,
            stage_starts: self.stage_starts,
        }
    }
}

/// A simulated life ([`LifeSim::run_life`]).
#[derive(Debug, Clone)]
pub struct SimulatedLife {
    /// Snapshot statistics on the normalised time line.
    pub points: Vec<LifePoint>,
    /// Revolutions to failure (at least 1).
    pub revs: f64,
    /// Revolutions at which the wear entered each of [`ONSET_STAGES`] (`None`: never).
    pub stage_starts: [Option<f64>; ONSET_STAGES.len()],
}

impl SimulatedLife {
    /// The onset of instability of the life's wear (fraction of life): the start of the
    /// first of [`ONSET_STAGES`] after the first quarter of the life
    /// ([`crate::life::ims::BASELINE`], before which the RMS rule looks for no onset
    /// either); `None` when both began before it or never. Where the simulated RMS shows
    /// an onset, it comes one or two windows after this one ([`ONSET_STAGES`]).
    pub fn wear_onset(&self) -> Option<f64> {
        self.stage_starts
            .iter()
            .flatten()
            .map(|c| c / self.revs)
            .find(|u| *u > crate::life::ims::BASELINE && *u < 1.0)
    }

    /// The life's onset of instability (fraction of life) and what it was read from: its
    /// RMS ([`super::onset`], the rule the measured life is read with), or, where the RMS
    /// never leaves its steady band, its wear stages ([`SimulatedLife::wear_onset`]).
    pub fn onset(&self) -> (Option<f64>, OnsetBasis) {
        match super::onset(&self.points) {
            Some(u) => (Some(u), OnsetBasis::Rms),
            None => match self.wear_onset() {
                Some(u) => (Some(u), OnsetBasis::WearStages),
                None => (None, OnsetBasis::Rms),
            },
        }
    }
}

/// What a simulated life's onset of instability was read from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum OnsetBasis {
    /// Its RMS, by the rule of the measured life ([`super::onset`]).
    Rms,
    /// Its wear stages ([`SimulatedLife::wear_onset`]): the RMS never left its steady
    /// band (at a low speed the defect's impacts stay within the steady vibration).
    WearStages,
}

impl OnsetBasis {
    /// The JSON name (`rms`, `wear-stages`).
    pub fn name(self) -> &'static str {
        match self {
            OnsetBasis::Rms => "rms",
            OnsetBasis::WearStages => "wear-stages",
        }
    }
}

/// The wear site the life model grows for a failure mode of the feature-table vocabulary
/// ([`crate::io::feature_table::FAILURE_MODES`]), as the defect location that selects it
/// ([`Site::of`]): `outer-race` at the load-zone centre, `inner-race`, `rolling-element`
/// (element 0). `None` for a mode the model has no site for (`cage`) and for `none` and
/// `unknown`: the life then wears at the model's own site (the outer race).
pub fn failure_site(mode: &str) -> Option<DefectLocation> {
    match mode {
        "outer-race" => Some(DefectLocation::OuterRace {
            angle: std::f64::consts::FRAC_PI_2,
        }),
        "inner-race" => Some(DefectLocation::InnerRace { angle: 0.0 }),
        "rolling-element" => Some(DefectLocation::Ball {
            element: 0,
            phase: 0.0,
        }),
        _ => None,
    }
}

/// A calibrated simulated life.
#[derive(Debug, Clone, Copy)]
pub struct Calibrated {
    /// Its scales.
    pub scales: Scales,
    /// Its revolutions to failure.
    pub revs: f64,
    /// Its onset of instability (fraction of life), `None` if neither its RMS nor its wear
    /// stages show one ([`SimulatedLife::onset`]).
    pub onset: Option<f64>,
    /// What [`Calibrated::onset`] was read from.
    pub onset_basis: OnsetBasis,
    /// Lives run to calibrate it.
    pub runs: usize,
}

/// Most lives the shape calibration runs after its first.
const SHAPE_STEPS: usize = 12;

/// One life run by [`calibrate`]: its scales, revolutions and onset (fraction of life).
#[derive(Debug, Clone, Copy)]
struct Tried {
    scales: Scales,
    revs: f64,
    onset: Option<f64>,
}

/// The range the calibration's lives covered, for a message that says what was tried:
/// life factor, propagation limit (passes), simulated lives (revolutions) and how many
/// had an onset of instability.
fn bracket(tried: &[Tried]) -> String {
    let range = |f: &dyn Fn(&Tried) -> f64| {
        let lo = tried.iter().map(f).fold(f64::INFINITY, f64::min);
        let hi = tried.iter().map(f).fold(f64::NEG_INFINITY, f64::max);
        format!("{lo:.3e} … {hi:.3e}")
    };
    format!(
        "bracket tried over {} lives: life factor {}, propagation limit {} passes, simulated lives {} revolutions, {} of them with an onset of instability",
        tried.len(),
        range(&|t| t.scales.life_factor),
        range(&|t| t.scales.propagation_passes),
        range(&|t| t.revs),
        tried.iter().filter(|t| t.onset.is_some()).count()
    )
}

/// Calibrates the simulated baseline life on the training life: its length `target`
/// (revolutions) within 1 %, and, when the training life has an onset of instability
/// `onset` (fraction of life, [`super::onset`]), that onset within
/// [`crate::life::calibrate::ONSET_TOLERANCE`] ([`calibrate_shape`]: the life factor scales
/// the part before the onset, the propagation limit the part after it; the onset may stay
/// off when the part after it cannot shrink to the measured one, which the report says;
/// the length may not stay off by more than 5 %). The simulated onset is read from the
/// simulated RMS by the measured life's rule, or, where that RMS never leaves its steady
/// band (a slow rig: at 60 rpm the defect's impacts stay within the steady vibration), from
/// the life's wear stages ([`SimulatedLife::onset`]). Without an onset
/// only the life factor is calibrated (secant steps with no fixed part, up to 8; its
/// crack-to-failure part then does not scale, so a life shorter than it is refused with
/// the length it needs). `wearsim ims-compare` calibrates the life factor alone, with the
/// crack-to-failure part held fixed. An error starts `calibration: not converged` and names
/// the reason and the bracket of scales and lives tried: the last life is never returned
/// as a calibration unless it is within 5 % of the length.
pub fn calibrate(
    rig: &RigDescription,
    seed: u64,
    target: f64,
    onset: Option<f64>,
    site: Option<DefectLocation>,
) -> Result<Calibrated, String> {
    // The first life: ISO 281 fatigue at factor 1 and the material's propagation limit,
    // the scales both calibrations step from.
    let steel = Scales::with_factor(1.0);
    let tried: RefCell<Vec<Tried>> = RefCell::new(vec![]);
    // The schedule needs an expected life; every run uses the target.
    let run = |sc: Scales| -> Result<(Shape, OnsetBasis), String> {
        let l = LifeSim::new(rig, sc, seed, target, site)?.run_life(&Effects::NONE)?;
        let (onset, basis) = l.onset();
        tried.borrow_mut().push(Tried {
            scales: sc,
            revs: l.revs,
            onset,
        });
        Ok((
            Shape {
                life: l.revs,
                onset,
            },
            basis,
        ))
    };
    let hours = |revs: f64| revs / (3600.0 * rig.shaft_hz);
    let first = run(steel)?;
    // The shortest life the scales can give: the smallest life factor and, with an onset,
    // the smallest propagation limit (the crack stages, which neither scale shortens, are
    // left). A training life shorter than the first life is checked against it at once, so
    // that one the model cannot reach is refused after two lives, not after the search.
    let floor_scales = Scales {
        life_factor: wearsim_core::wear::material::MIN_LIFE_FACTOR,
        propagation_passes: if onset.is_some() {
            crate::life::calibrate::PROPAGATION_BOUNDS.0
        } else {
            steel.propagation_passes
        },
    };
    let floor_life = std::cell::OnceCell::new();
    let floor = || -> Result<f64, String> {
        if let Some(&f) = floor_life.get() {
            return Ok(f);
        }
        let f = run(floor_scales)?.0.life;
        Ok(*floor_life.get_or_init(|| f))
    };
    let must_span = |floor: f64| {
        format!(
            "a training life must span at least {:.3} h at this speed (the first to the last snapshot of its table)",
            hours(floor)
        )
    };
    if target < first.0.life && floor()? > target * 1.05 {
        let f = floor()?;
        return Err(format!(
            "calibration: not converged: the training life lasts {target:.3e} revolutions ({:.3} h at {:.0} rpm), but the simulated life of this bearing lasts at least {f:.3e} revolutions (life factor {:.3e}, propagation limit {:.3e} passes: its crack stages, which neither scale shortens, at this bearing's load); {}; {}",
            hours(target),
            60.0 * rig.shaft_hz,
            floor_scales.life_factor,
            floor_scales.propagation_passes,
            must_span(f),
            bracket(&tried.borrow())
        ));
    }
    // A training life past the largest life factor (a time column in other units, a
    // wrong speed or load): said in the table's terms, not as a material's range.
    let max_factor = wearsim_core::wear::material::MAX_LIFE_FACTOR;
    let too_long = |factor: f64| {
        (factor >= max_factor).then(|| format!(
            "the training life ({:.3} h at this speed) is longer than the simulated life at the largest life factor, {max_factor:.0e} (a fatigue life that many times ISO 281's): check the table's time_s and the sidecar's rpm and radial_load_n",
            hours(target)
        ))
    };
    if let Some(u) = onset {
        let c = calibrate_shape(target, u, steel, first, SHAPE_STEPS, |a, n_p| {
            run(Scales {
                life_factor: a,
                propagation_passes: n_p,
            })
        })?;
        if (c.shape.life / target - 1.0).abs() > 0.05 {
            let tried_so_far = bracket(&tried.borrow());
            let with_onset = tried.borrow().iter().any(|t| t.onset.is_some());
            // Most likely too short for the crack stages, which neither scale shortens:
            // say how long the training life must be.
            let floor = floor()?;
            let why = if let Some(t) = too_long(c.factor) {
                t
            } else if target < floor {
                format!(
                    "the simulated life of this bearing lasts at least {floor:.3e} revolutions at the smallest life factor and propagation limit (its crack stages, which neither scale shortens, at this bearing's load): {}",
                    must_span(floor)
                )
            } else if !with_onset {
                format!(
                    "no simulated life had an onset of instability to step on (its RMS never left its steady band, and its wear reached neither a spall nor new defects after the first quarter of its life), so the two scales could not be told apart; the shortest simulated life is {floor:.3e} revolutions"
                )
            } else {
                format!("the steps did not converge (the shortest simulated life is {floor:.3e} revolutions)")
            };
            return Err(format!(
                "calibration: not converged: the simulated life did not reach the training life's length and onset of instability ({target:.3e} revolutions, {:.3} h at {:.0} rpm, onset at {u:.3} of life) in {} lives: it lasts {:.3e} revolutions with its onset at {} (life factor {:.3e}, propagation limit {:.3e} passes); {why}; {tried_so_far}",
                hours(target),
                60.0 * rig.shaft_hz,
                c.steps,
                c.shape.life,
                c.shape.onset.map_or("none".to_string(), |v| format!("{v:.3}")),
                c.factor,
                c.propagation_passes,
            ));
        }
        return Ok(Calibrated {
            scales: Scales {
                life_factor: c.factor,
                propagation_passes: c.propagation_passes,
            },
            revs: c.shape.life,
            onset: c.shape.onset,
            onset_basis: c.last,
            runs: c.steps + 1 + usize::from(floor_life.get().is_some()),
        });
    }
    let run = |a: f64| -> Result<(f64, (Option<f64>, OnsetBasis)), String> {
        let (s, basis) = run(Scales {
            life_factor: a,
            ..steel
        })?;
        Ok((s.life, (s.onset, basis)))
    };
    let first = (first.0.life, (first.0.onset, first.1));
    let context = |e: String| {
        format!(
            "calibrating the life factor to the training life's {target:.3e} revolutions (the training life has no onset of instability, so its propagation limit stays the material's; the simulated life lasts {:.3e} at factor 1; its crack-to-failure part does not scale with the factor, so a measured life shorter than that part cannot be reached): {e}",
            first.0
        )
    };
    let step = Secant {
        fixed: 0.0,
        min_steps: 0,
        max_steps: 8,
    };
    let short = |e: String| {
        // Below the crack-to-failure part: say how long the training life must be.
        match floor() {
            Ok(floor) if target < floor => format!(
                "the training life lasts {target:.3e} revolutions ({:.3} h at {:.0} rpm), but the simulated life of this bearing lasts at least {floor:.3e} revolutions at any life factor (its crack-to-failure part does not scale with the factor): {}; {}",
                hours(target),
                60.0 * rig.shaft_hz,
                must_span(floor),
                context(e)
            ),
            _ => context(e),
        }
    };
    let c = calibrate_life(target, first, &step, run)
        .map_err(|e| format!("calibration: not converged: {}", short(e)))?;
    if (c.life / target - 1.0).abs() > 0.05 {
        let why = too_long(c.factor).map_or(String::new(), |t| t + "; ");
        return Err(format!("calibration: not converged: {}", context(format!(
            "{why}the life factor did not converge: {:.3e} revolutions against the measured {target:.3e}; {}",
            c.life,
            bracket(&tried.borrow())
        ))));
    }
    Ok(Calibrated {
        scales: Scales {
            life_factor: c.factor,
            ..steel
        },
        revs: c.life,
        onset: c.last.0,
        onset_basis: c.last.1,
        runs: c.steps + 1 + usize::from(floor_life.get().is_some()),
    })
}
