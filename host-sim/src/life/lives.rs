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
//! onset of instability, [`super::ims::onset`]) and the stage event log. A life that
//! reaches the cycle cap (`--cycles`) before failing is ended there as a suspension, as
//! an endurance test stopped at a set number of revolutions ends its survivors: the
//! Weibull fits count it as a life longer than the cap ([`super::weibull::fit_units`]),
//! and the onsets and stage fractions, which are fractions of a life to failure, leave it
//! out.

use super::ims::{normalise, onset};
use super::weibull::{fit_with_ci, load_exponent, Estimate, Unit, WeibullFit};
use super::{AtCap, LifeError, LifeRun, LifeSpec};
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
    /// Revolutions to failure, or to the cycle cap when `suspended`.
    pub life: f64,
    /// The life reached the cycle cap before failing and was ended there (right-censored).
    pub suspended: bool,
    /// Revolutions to the first spall (entry into defect completion), if reached.
    pub first_spall: Option<f64>,
    /// How the first crack started: at a dent (surface) or under the surface before any
    /// dent formed (subsurface); `None` if no crack opened.
    pub initiation: Option<Initiation>,
    /// Onset of instability of the normalised RMS (fraction of life), if found (`None`
    /// for a suspended life: its end is not a failure).
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
    /// Weibull fit of the lives to failure, suspended ones as suspensions (None when
    /// fewer than 3 failed, or degenerate).
    pub weibull: Option<WeibullFit>,
    /// Weibull fit of the revolutions to the first spall, lives suspended before it as
    /// suspensions (None when fewer than 3 reached it, or degenerate).
    pub first_spall_weibull: Option<WeibullFit>,
    /// Median onset of instability (fraction of life) over the failed lives where one was
    /// found.
    pub onset_median: Option<f64>,
    /// Lives with an onset found.
    pub onset_found: usize,
    /// Median revolutions at which each stage was entered, as a fraction of the life, over
    /// the failed lives.
    pub stage_onsets: Vec<(String, f64)>,
    /// The shares of the life its crack growth and its post-spall phase take
    /// ([`super::phases`]).
    pub phases: super::phases::PhaseShares,
}

/// Runs the lives of `specs` (one spec per seed) on `threads` threads. An error comes
/// with the seed of the life that failed (of several, the first in `specs`' order), so
/// that a message can say which of the lives it is about.
pub fn run_lives(
    specs: Vec<LifeSpec>,
    threads: usize,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<Vec<LifeOutcome>, (u64, LifeError)> {
    let seed = |i: usize| specs.get(i).map_or(0, |s| s.seed);
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
    lives
        .into_iter()
        .enumerate()
        .map(|(i, r)| r.map_err(|e| (seed(i), e)))
        .collect()
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
        super::MAX_LIFE_WINDOWS,
        AtCap::Suspend,
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
        suspended: d.suspended,
        first_spall,
        initiation,
        onset: onset(&curve).filter(|_| !d.suspended),
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
    let x: Vec<Unit> = lives.iter().map(to_failure).collect();
    let spall: Vec<Unit> = lives.iter().map(to_first_spall).collect();
    let onsets: Vec<f64> = lives.iter().filter_map(|l| l.onset).collect();
    let stage_onsets = Stage::ALL
        .iter()
        .filter_map(|s| {
            let v: Vec<f64> = lives
                .iter()
                .filter(|l| !l.suspended)
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
        phases: phase_shares(&lives),
        lives,
    }
}

/// The shares of life of the crack growth and of the post-spall phase
/// ([`super::phases`]): per life that opened a crack and reached its first spall,
/// `(first spall − crack opening) / first spall`; per failed life with a first spall,
/// `(failure − first spall) / failure`.
fn phase_shares(lives: &[LifeOutcome]) -> super::phases::PhaseShares {
    let at = |l: &LifeOutcome, s: Stage| {
        l.stages
            .iter()
            .find(|(n, _)| n == s.name())
            .map(|(_, c)| *c)
    };
    let crack: Vec<f64> = lives
        .iter()
        .filter_map(|l| {
            let (open, spall) = (at(l, Stage::CrackOpening)?, at(l, Stage::DefectCompletion)?);
            (spall > 0.0 && open <= spall).then(|| (spall - open) / spall)
        })
        .collect();
    let post: Vec<f64> = lives
        .iter()
        .filter(|l| !l.suspended)
        .filter_map(|l| {
            let s = l.first_spall?;
            (l.life > 0.0).then(|| (l.life - s) / l.life)
        })
        .collect();
    super::phases::shares(&crack, &post, BOOTSTRAP, 0x5AA3)
}

/// A life as a unit of a test to failure: failed at its life, or suspended at the cap.
pub(crate) fn to_failure(l: &LifeOutcome) -> Unit {
    Unit {
        time: l.life,
        failed: !l.suspended,
    }
}

/// A life as a unit of a test to the first spall: failed there, or suspended at its end
/// (a life that fails always passes its first spall first).
pub(crate) fn to_first_spall(l: &LifeOutcome) -> Unit {
    match l.first_spall {
        Some(t) => Unit::failure(t),
        None => Unit {
            time: l.life,
            failed: false,
        },
    }
}

/// The life–load exponent across the groups (slope of ln η against ln load), of the
/// lives to failure (`first_spall` false) or to the first spall (true), suspensions
/// included as such.
pub fn exponent(groups: &[LoadGroup], first_spall: bool) -> Option<Estimate> {
    let unit = if first_spall {
        to_first_spall
    } else {
        to_failure
    };
    let g: Vec<(f64, Vec<Unit>)> = groups
        .iter()
        .map(|g| (g.load_n, g.lives.iter().map(unit).collect()))
        .collect();
    load_exponent(&g, BOOTSTRAP, 0x10AD)
}

/// Published life–load exponents of **ball** (point-contact) bearings (value, source):
/// the two ends of the published range. `L ∝ σ_max^{−n}` with `σ_max ∝ Q^{1/3}` (Hertz,
/// point contact) gives `L ∝ Q^{−n/3}`: Lundberg–Palmgren's stress–life exponent n = 9
/// (ISO 281) gives −3; the n ≈ 12 measured on post-1960 vacuum-processed bearing steels
/// gives −4 (derived here from n; the 12 is in the abstracts of Zaretsky, Poplawski &
/// Root 2008, NASA/TM-2008-214265, and of Zaretsky 1974, J. Lubr. Technol. 96(3):391, whose
/// M-50 tests at 500 °F kept n = 9). Line contact: ISO's −10/3 only (no range sourced).
pub const PUBLISHED_LOAD_EXPONENTS_BALL: [(f64, &str); 2] = [
    (
        -3.0,
        "ISO 281 / Lundberg–Palmgren, stress–life exponent 9",
    ),
    (
        -4.0,
        "stress–life exponent 12 of vacuum-processed steels (Zaretsky, Poplawski & Root 2008, NASA/TM-2008-214265), p = n/3 derived",
    ),
];

/// How a fitted life–load exponent `e` sits against the published range `[lo, hi]`
/// (most negative first): whether its value lies inside, and whether its bootstrap
/// interval overlaps the range at all.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AgainstRange {
    /// The range (–), most negative first.
    pub range: [f64; 2],
    /// The point estimate lies inside the range (ends included).
    pub value_inside: bool,
    /// The bootstrap interval `[lo, hi]` lies entirely inside the range.
    pub interval_inside: bool,
    /// The bootstrap interval and the range share a point.
    pub interval_overlaps: bool,
}

/// [`AgainstRange`] of `e` for the published range of a bearing with `point` contact
/// ([`PUBLISHED_LOAD_EXPONENTS_BALL`]); `None` for line contact (no sourced range).
pub fn against_published(e: &Estimate, point: bool) -> Option<AgainstRange> {
    if !point {
        return None;
    }
    let [(a, _), (b, _)] = PUBLISHED_LOAD_EXPONENTS_BALL;
    let (lo, hi) = (a.min(b), a.max(b));
    let inside = |x: f64| (lo..=hi).contains(&x);
    Some(AgainstRange {
        range: [lo, hi],
        value_inside: inside(e.value),
        interval_inside: inside(e.lo) && inside(e.hi),
        interval_overlaps: e.lo <= hi && e.hi >= lo,
    })
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

#[cfg(test)]
mod tests {
    use super::*;

    fn est(value: f64, lo: f64, hi: f64) -> Estimate {
        Estimate { value, lo, hi }
    }

    fn life(seed: u64, open: f64, spall: f64, end: f64, suspended: bool) -> LifeOutcome {
        LifeOutcome {
            seed,
            life: end,
            suspended,
            first_spall: Some(spall),
            initiation: None,
            onset: None,
            stages: vec![
                ("crack-opening".into(), open),
                ("defect-completion".into(), spall),
                ("failure".into(), end),
            ],
            wall_s: 0.0,
        }
    }

    /// The phase shares are the stated ratios of the stage times; a suspended life has no
    /// post-spall share, a life without a spall neither share.
    #[test]
    fn phase_shares_are_the_ratios_of_the_stage_times() {
        let mut lives: Vec<LifeOutcome> =
            (0..5).map(|i| life(i, 60.0, 80.0, 100.0, false)).collect();
        lives.push(life(9, 10.0, 20.0, 1e3, true));
        lives.push(LifeOutcome {
            first_spall: None,
            stages: vec![("crack-opening".into(), 5.0)],
            ..life(10, 5.0, 5.0, 50.0, true)
        });
        let s = phase_shares(&lives);
        // Crack share: (80 − 60)/80 = 0.25 for five lives, 0.5 for the suspended one.
        assert_eq!(s.crack_lives, 6);
        let c = s.crack.unwrap();
        assert!((c.value - 0.25).abs() < 1e-12, "{c:?}");
        assert!(c.lo <= c.value && c.value <= c.hi && c.hi <= 0.5, "{c:?}");
        // Post-spall share: (100 − 80)/100 = 0.2, failed lives only.
        assert_eq!(s.post_spall_lives, 5);
        let p = s.post_spall.unwrap();
        assert_eq!((p.value, p.lo, p.hi), (0.2, 0.2, 0.2));
    }

    /// The published ball-bearing range is [−4, −3] (n = 9 and 12 over the Hertz point
    /// contact's 1/3); the comparison distinguishes value, interval inside and overlap.
    #[test]
    fn exponents_against_the_published_ball_range() {
        let r = against_published(&est(-3.73, -4.15, -3.30), true).unwrap();
        assert_eq!(r.range, [-4.0, -3.0]);
        assert!(r.value_inside && !r.interval_inside && r.interval_overlaps);
        let r = against_published(&est(-2.40, -2.78, -2.06), true).unwrap();
        assert!(!r.value_inside && !r.interval_inside && !r.interval_overlaps);
        let r = against_published(&est(-3.5, -3.9, -3.1), true).unwrap();
        assert!(r.value_inside && r.interval_inside);
        let r = against_published(&est(-2.9, -3.2, -2.6), true).unwrap();
        assert!(!r.value_inside && r.interval_overlaps);
        assert_eq!(against_published(&est(-3.3, -3.5, -3.1), false), None);
    }
}
