//! One measured life as a target of the attribution ([`Target`]): its cells against the
//! shared simulated life, the noise-only gap, and the fit spaces of the effects that can
//! act along a life.

use super::sim::LifeSim;
use super::{LifePoint, LifeReference, STAGES, STEADY};
use crate::gap::matched::{GapsResult, Target};
use crate::gap::space::{FitParam, FitSpace};
use std::sync::atomic::AtomicUsize;
use std::sync::Arc;
use wearsim_core::effects::{EffectKind, Effects};

/// One measured life held against the shared simulated life.
#[derive(Debug, Clone)]
pub struct LifeTarget {
    /// Measured cells.
    pub reference: LifeReference,
    /// The simulated life (shared).
    pub sim: Arc<LifeSim>,
    /// Only these cells count (indices into the reference), re-weighted so that their
    /// stages count equally; `None`: every cell.
    pub only: Option<Vec<usize>>,
}

impl LifeTarget {
    /// The same life restricted to the stages that end by `t_max` (the early-life part),
    /// or `None` when it has none.
    pub fn early(&self, t_max: f64) -> Option<LifeTarget> {
        let idx: Vec<usize> = self
            .reference
            .names
            .iter()
            .enumerate()
            .filter(|(_, (_, stg, _))| {
                super::stage_named(stg)
                    .is_some_and(|s| s.hi <= t_max + 1e-9 && s.name != STAGES[STEADY].name)
            })
            .map(|(i, _)| i)
            .collect();
        (!idx.is_empty()).then(|| LifeTarget {
            reference: self.reference.clone(),
            sim: self.sim.clone(),
            only: Some(idx),
        })
    }
}

impl LifeTarget {
    /// [`LifeReference::noise_only`] on the cells that count.
    pub fn noise_only(&self, sim: &[LifePoint]) -> f64 {
        let Some(idx) = &self.only else {
            return self.reference.noise_only(sim);
        };
        let pick =
            |v: &[usize]| -> Vec<usize> { idx.iter().filter_map(|i| v.get(*i).copied()).collect() };
        let names: Vec<(String, &'static str, &'static str)> = idx
            .iter()
            .filter_map(|i| self.reference.names.get(*i).cloned())
            .collect();
        let sub = LifeReference {
            weight: crate::gap::group_weights(&names),
            count: pick(&self.reference.count),
            names,
            ..self.reference.clone()
        };
        sub.noise_only(sim)
    }
}

/// Noise-only total gap of a set of lives: root mean square over the lives.
pub(super) fn noise_only(targets: &[LifeTarget], sim: &[LifePoint]) -> f64 {
    let n = targets.len().max(1) as f64;
    (targets
        .iter()
        .map(|t| t.noise_only(sim).powi(2))
        .sum::<f64>()
        / n)
        .sqrt()
}

/// A gap counts as outside the sampling variability when it is at least this many times
/// the noise-only gap (for records of seconds the attribution's
/// [`crate::gap::attribute::SIGNIFICANT_GAP`], 1.0, is about 2.6× their noise-only gap of
/// 0.39, chosen as a 5 % false-alarm level on no-effect twins; this multiple was set
/// before that, at about the 4× the old 1.5 was, and is not re-chosen).
pub const SIGNIFICANCE: f64 = 3.0;

impl LifeTarget {
    /// The cell gaps of the life `p` and their weights.
    fn gaps_of(&self, p: &[LifePoint]) -> Result<(Vec<f64>, Vec<f64>), String> {
        let v = self.reference.values(p)?;
        let r = self.reference.residuals(&v);
        let Some(idx) = &self.only else {
            return Ok((r, self.reference.weight.clone()));
        };
        let names: Vec<(String, &'static str, &'static str)> = idx
            .iter()
            .filter_map(|i| self.reference.names.get(*i).cloned())
            .collect();
        let g = idx.iter().filter_map(|i| r.get(*i).copied()).collect();
        Ok((g, crate::gap::group_weights(&names)))
    }
}

impl Target for LifeTarget {
    fn gaps(&self, fx: &Effects, sims: &AtomicUsize) -> Result<(Vec<f64>, Vec<f64>), String> {
        self.gaps_of(&self.sim.points(fx, sims)?)
    }

    /// The lives not in the cache run side by side ([`LifeSim::points_many`]).
    fn gaps_many(&self, fxs: &[Effects], sims: &AtomicUsize) -> Vec<GapsResult> {
        self.sim
            .points_many(fxs, sims)
            .into_iter()
            .map(|p| self.gaps_of(&p?))
            .collect()
    }
}

fn fp(name: &'static str, lo: f64, hi: f64, log: bool) -> FitParam {
    FitParam { name, lo, hi, log }
}

/// The candidate effects whose signature can lie along a life, with their fit spaces.
/// `steady_rms` is the baseline life's steady RMS (m/s²), the scale of the sensor floor.
///
/// * `running-in`: summit contacts 0.01–300 per revolution (log), summit height 0.1–5 µm
///   (log), decaying over 10⁴–2·10⁶ revolutions (log; at most a tenth of the
///   2·10⁷-revolution life, so that it stays an early-life effect and is not a constant
///   level in disguise); the roughness factor is held at 1. The measured early excess of
///   IMS test 2 is impulsive — crest factor +0.5–0.7 and kurtosis +0.1–0.6 in the first
///   1 % on all four bearings, RMS unchanged on three of them — which the summits give
///   and a scaled Gaussian roughness cannot (it raises RMS first).
/// * `roughness`: scale 0.1–20 (log), the whole life.
/// * `sensor`: a background floor (other machinery, the sensor) of 1–300 % of the
///   bearing's steady RMS (log), no hum: it sets how far a defect rises above the rest.
/// * `edge-shape`: length scale 0.2–5 (log) and asperity scale 0–5 of every defect the
///   wear machine grows: how impulsive the late life is.
///
/// Effects that act within a snapshot only (slip, speed fluctuation, shaft harmonics,
/// transfer path, load zone) change no statistic along life that these cells resolve;
/// they are diagnosed on the raw records (`wearsim gap` on CWRU files). `fs` (Hz) and
/// `shaft_hz` are the simulated bearing's sample rate and shaft speed.
pub fn life_spaces(steady_rms: f64, fs: f64, shaft_hz: f64) -> Vec<FitSpace> {
    let r = steady_rms.max(1e-6);
    // Roughness and edge-shape as for records of seconds (their ranges do not depend on
    // the record); a life grows its own defects, so edge-shape needs none to start with.
    let stationary = crate::gap::space::spaces(&crate::gap::space::Context {
        fs,
        shaft_hz,
        rms: r,
        mains_hz: 60.0,
        preload_max: crate::gap::space::CATALOGUE_PRELOAD_MAX,
    });
    let shared = |kind: EffectKind| {
        stationary
            .iter()
            .find(|s| s.kind == kind)
            .cloned()
            .map(|s| FitSpace {
                needs_defect: false,
                ..s
            })
    };
    let running_in = FitSpace {
        kind: EffectKind::RunningIn,
        effect: EffectKind::RunningIn.name(),
        fitted: vec![
            fp("summits", 0.01, 300.0, true),
            fp("summit_height", 0.1, 5.0, true),
            fp("decay_revs", 1.0e4, 2.0e6, true),
        ],
        fixed: vec![("factor", 1.0), ("start_revs", 0.0)],
        needs_defect: false,
        note: "summits of the new surface, flattened over the first revolutions",
    };
    let sensor = FitSpace {
        kind: EffectKind::Sensor,
        effect: EffectKind::Sensor.name(),
        fitted: vec![fp("noise", 0.01 * r, 3.0 * r, true)],
        fixed: vec![("hum", 0.0), ("corner_hz", 0.0)],
        needs_defect: false,
        note: "background floor (other machinery, sensor), scaled to the bearing's steady RMS",
    };
    [
        Some(running_in),
        shared(EffectKind::Roughness),
        Some(sensor),
        shared(EffectKind::EdgeShape),
    ]
    .into_iter()
    .flatten()
    .collect()
}
