//! Many lives: `wearsim life --lives N` runs N seeds of one configuration (at one or
//! more load scales) through the one life driver, in parallel on std threads, and
//! reports the distribution of lives and stage onsets, a Weibull fit with bootstrap
//! intervals ([`super::weibull`]), ISO 281's L10 for the same bearing and load, and the
//! life–load exponent across the loads — each for two definitions of life: to failure
//! (the fourth defect) and to the first spall (entry into defect completion: ISO 281's
//! "first evidence of fatigue", the end point of the endurance tests behind the
//! published Weibull slopes).
//!
//! Each life records only what the statistics need: the RMS of every window (for the
//! onset of instability, [`super::ims::onset`]) and the stage event log.

use super::ims::{normalise, onset};
use super::weibull::{fit_with_ci, load_exponent, Estimate, WeibullFit};
use super::{LifeError, LifeRun, LifeSpec};
use crate::analysis::stats::median;
use serde::Serialize;
use wearsim_core::wear::Stage;

/// Bootstrap resamples of the intervals.
pub const BOOTSTRAP: usize = 1000;

/// One simulated life.
#[derive(Debug, Clone, Serialize)]
pub struct LifeOutcome {
    /// Seed.
    pub seed: u64,
    /// Revolutions to failure.
    pub life: f64,
    /// Revolutions to the first spall (entry into defect completion), if reached.
    pub first_spall: Option<f64>,
    /// How the first crack started: at a dent (surface) or under the surface before any
    /// dent formed (subsurface); `None` if no crack opened.
    pub initiation: Option<Initiation>,
    /// Onset of instability of the normalised RMS (fraction of life), if found.
    pub onset: Option<f64>,
    /// Revolutions at which each stage was entered (stage name, revolutions).
    pub stages: Vec<(String, f64)>,
    /// Wall-clock time of this life (s).
    pub wall_s: f64,
}

/// How a life's first crack started (the two competing initiation modes of the wear
/// model, `wearsim_core::wear::LifeState::surface` and `fatigue`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Initiation {
    /// At a dent: the surface-damage sum formed a dent first.
    Surface,
    /// Under the surface: the subsurface fatigue sum opened a crack before any dent.
    Subsurface,
}

impl Initiation {
    /// Name in tables (`surface`, `subsurface`).
    pub fn name(self) -> &'static str {
        match self {
            Initiation::Surface => "surface",
            Initiation::Subsurface => "subsurface",
        }
    }
}

/// Lives at one load.
#[derive(Debug, Clone, Serialize)]
pub struct LoadGroup {
    /// Load scale (multiplier of the preset's radial load).
    pub load_scale: f64,
    /// Radial load (N).
    pub load_n: f64,
    /// ISO 281 basic rating life L10 = (C/P)^p · 10⁶ revolutions with P = radial load.
    pub iso_l10: f64,
    /// The lives, in seed order.
    pub lives: Vec<LifeOutcome>,
    /// Weibull fit of the lives (None when fewer than 3 or degenerate).
    pub weibull: Option<WeibullFit>,
    /// Weibull fit of the revolutions to the first spall (None when fewer than 3 or
    /// degenerate).
    pub first_spall_weibull: Option<WeibullFit>,
    /// Median onset of instability (fraction of life) over the lives where one was found.
    pub onset_median: Option<f64>,
    /// Lives with an onset found.
    pub onset_found: usize,
    /// Median revolutions at which each stage was entered, as a fraction of the life.
    pub stage_onsets: Vec<(String, f64)>,
}

/// Runs the lives of `specs` (one spec per seed) on `threads` threads.
pub fn run_lives(
    specs: Vec<LifeSpec>,
    threads: usize,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<Vec<LifeOutcome>, LifeError> {
    let lives = super::parallel::map_indexed(
        specs.len(),
        threads,
        |i| match specs.get(i) {
            Some(spec) => one_life(spec.clone()),
            None => Err(LifeError::NonFinite { cycles: f64::NAN }),
        },
        progress,
        || Err(LifeError::NonFinite { cycles: f64::NAN }),
    );
    lives.into_iter().collect()
}

/// One life through the driver, recording the window RMS.
pub fn one_life(spec: LifeSpec) -> Result<LifeOutcome, LifeError> {
    let t0 = std::time::Instant::now();
    let seed = spec.seed;
    let run = LifeRun::new(spec)?;
    let every = run.spec.snapshot_every;
    let mut pts: Vec<(f64, f64)> = vec![];
    let d = run.drive(
        |_| every,
        u64::MAX,
        |w| {
            // The onset is read as a periodic measurement would: transition windows left out.
            if w.scheduled {
                let n = w.samples.len().max(1) as f64;
                let rms = (w.samples.iter().map(|x| x * x).sum::<f64>() / n).sqrt();
                pts.push((w.state.cycles, rms));
            }
            Ok(())
        },
    )?;
    let end = d.state.cycles.max(1.0);
    let curve = normalise(
        pts.iter().map(|(c, _)| c / end).collect(),
        pts.iter().map(|(_, r)| *r).collect(),
    );
    let at = |stage: Stage| d.state.events.iter().find(|e| e.stage == stage);
    let first_spall = at(Stage::DefectCompletion).map(|e| e.cycles);
    let initiation = at(Stage::CrackOpening).map(|_| match at(Stage::Dent) {
        Some(_) => Initiation::Surface,
        None => Initiation::Subsurface,
    });
    Ok(LifeOutcome {
        seed,
        life: d.state.cycles,
        first_spall,
        initiation,
        onset: onset(&curve),
        stages: d
            .state
            .events
            .iter()
            .map(|e| (e.stage.name().to_string(), e.cycles))
            .collect(),
        wall_s: t0.elapsed().as_secs_f64(),
    })
}

/// Summarises the lives at one load.
pub fn summarise(load_scale: f64, load_n: f64, iso_l10: f64, lives: Vec<LifeOutcome>) -> LoadGroup {
    let x: Vec<f64> = lives.iter().map(|l| l.life).collect();
    let spall: Vec<f64> = lives.iter().filter_map(|l| l.first_spall).collect();
    let onsets: Vec<f64> = lives.iter().filter_map(|l| l.onset).collect();
    let stage_onsets = Stage::ALL
        .iter()
        .filter_map(|s| {
            let v: Vec<f64> = lives
                .iter()
                .filter_map(|l| {
                    l.stages
                        .iter()
                        .find(|(n, _)| n == s.name())
                        .map(|(_, c)| c / l.life.max(1.0))
                })
                .collect();
            median(v).map(|m| (s.name().to_string(), m))
        })
        .collect();
    LoadGroup {
        load_scale,
        load_n,
        iso_l10,
        weibull: fit_with_ci(&x, BOOTSTRAP, 0x11FE),
        first_spall_weibull: fit_with_ci(&spall, BOOTSTRAP, 0x5BA1),
        onset_found: onsets.len(),
        onset_median: median(onsets),
        stage_onsets,
        lives,
    }
}

/// The life–load exponent across the groups (slope of ln η against ln load), of the
/// lives to failure (`first_spall` false) or to the first spall (true).
pub fn exponent(groups: &[LoadGroup], first_spall: bool) -> Option<Estimate> {
    let g: Vec<(f64, Vec<f64>)> = groups
        .iter()
        .map(|g| {
            let x = g.lives.iter();
            let x = if first_spall {
                x.filter_map(|l| l.first_spall).collect()
            } else {
                x.map(|l| l.life).collect()
            };
            (g.load_n, x)
        })
        .collect();
    load_exponent(&g, BOOTSTRAP, 0x10AD)
}

/// Published Weibull slopes to compare with (value, source).
pub const PUBLISHED_SLOPES: [(f64, &str); 4] = [
    (
        10.0 / 9.0,
        "ISO 281 design slope, ball bearings (via SKF/third-party note)",
    ),
    (
        1.483,
        "Shigley (Budynas–Nisbett) catalogue 3-parameter Weibull shape",
    ),
    (
        1.24,
        "Nelson 1990 load-accelerated bearing data, common shape (derived)",
    ),
    (
        1.1,
        "Hoeprich 1992 spall propagation time, median (via Kotzalas & Harris 2001)",
    ),
];
