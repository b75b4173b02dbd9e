//! The simulated life held against a real run-to-failure test: IMS test 2, bearing 1
//! (outer-race failure), per-snapshot RMS from `features_chocho66/test2_timefeatures.csv`,
//! against a life of the `ims-za2115` preset (Rexnord ZA-2115, 2000 rpm, 6000 lbf), on one
//! normalised time line (fraction of life) with RMS normalised by its early-life median.
//!
//! Figures: the onset of instability in both (first time the RMS leaves its steady band for
//! [`PERSIST`] consecutive snapshots; band = median ± max(5 robust σ, 10 %) of the first
//! half of life), the error between the onsets, and the distance between the two curves
//! (RMS and mean absolute difference of 20·log₁₀ over a common grid).
//!
//! Calibrated: one parameter, `material.life_factor`, on the measured time to failure of
//! the same bearing (in-sample), so that the simulated life lasts as long in revolutions.
//! Everything else is the physics of the wear model; the timeline is not fitted.

use super::calibrate::{calibrate, Secant};
use super::{LifeRun, LifeSpec};
use crate::analysis::stats::{robust_sigma, upper_median};
use crate::io::ims::read_ims_features;
use crate::io::ims_life::live_snapshots;
use serde::Serialize;
use std::path::Path;

/// Snapshots above the band in a row that make an onset.
pub const PERSIST: usize = 3;

/// A normalised life curve.
#[derive(Debug, Clone, Serialize)]
pub struct Curve {
    /// Fraction of life (0–1).
    pub t: Vec<f64>,
    /// RMS over its early-life median.
    pub rms: Vec<f64>,
}

/// The comparison.
#[derive(Debug, Clone, Serialize)]
pub struct ImsComparison {
    /// Measured curve.
    pub measured: Curve,
    /// Simulated curve.
    pub simulated: Curve,
    /// Onset of instability, measured (fraction of life).
    pub onset_measured: Option<f64>,
    /// Onset of instability, simulated.
    pub onset_simulated: Option<f64>,
    /// |simulated − measured| onset.
    pub onset_error: Option<f64>,
    /// RMS of the dB difference between the curves over the common grid.
    pub distance_db_rms: f64,
    /// Mean absolute dB difference.
    pub distance_db_mean_abs: f64,
    /// End-of-life RMS over early-life median, measured and simulated.
    pub end_ratio: (f64, f64),
    /// Measured life (h, revolutions).
    pub measured_life_h: f64,
    /// Measured life in revolutions at 2000 rpm.
    pub measured_life_revs: f64,
    /// Simulated life with the uncalibrated ISO 281 fatigue (life_factor 1), revolutions.
    pub uncalibrated_life_revs: f64,
    /// Calibrated life factor.
    pub life_factor: f64,
    /// Simulated life after calibration, revolutions.
    pub simulated_life_revs: f64,
    /// Simulated stage timeline (fractions of life at each transition).
    pub stages: Vec<(String, f64)>,
}

/// Reads the measured curve of IMS test 2, bearing 1.
pub fn measured_curve(data: &Path) -> Result<(Curve, f64), String> {
    let path = data.join("ims/features_chocho66/test2_timefeatures.csv");
    let f = read_ims_features(&path).map_err(|e| e.to_string())?;
    let rms = f
        .column("B1_rms")
        .ok_or_else(|| format!("{}: no B1_rms column", path.display()))?;
    // Dead final snapshots (machine stopped; README quirk): the one rule of the IMS reader.
    let live = live_snapshots(&f);
    let keep: Vec<usize> = (0..rms.len())
        .filter(|i| live.get(*i).copied().unwrap_or(false))
        .collect();
    let (Some(&first), Some(&last)) = (keep.first(), keep.last()) else {
        return Err(format!("{}: no valid snapshots", path.display()));
    };
    let (h0, h1) = (f.hours[first], f.hours[last]);
    let t: Vec<f64> = keep
        .iter()
        .map(|i| (f.hours[*i] - h0) / (h1 - h0))
        .collect();
    let r: Vec<f64> = keep.iter().map(|i| rms[*i]).collect();
    Ok((normalise(t, r), h1 - h0))
}

/// A curve on the time line `t` (fraction of life) with RMS `r` over its median of the
/// first half of life.
pub fn normalise(t: Vec<f64>, r: Vec<f64>) -> Curve {
    let early: Vec<f64> = t
        .iter()
        .zip(&r)
        .filter(|(t, _)| **t <= 0.5)
        .map(|(_, r)| *r)
        .collect();
    let m = upper_median(early).unwrap_or(1.0).max(1e-300);
    Curve {
        t,
        rms: r.iter().map(|x| x / m).collect(),
    }
}

/// Onset of instability of a normalised curve (see the module docs).
pub fn onset(c: &Curve) -> Option<f64> {
    let early: Vec<f64> =
        c.t.iter()
            .zip(&c.rms)
            .filter(|(t, _)| **t <= 0.5)
            .map(|(_, r)| *r)
            .collect();
    if early.len() < 5 {
        return None;
    }
    let (m, sigma) = robust_sigma(early)?;
    let upper = m + (5.0 * sigma).max(0.1 * m);
    let mut run = 0;
    for (i, r) in c.rms.iter().enumerate() {
        if c.t[i] <= 0.5 {
            continue;
        }
        run = if *r > upper { run + 1 } else { 0 };
        if run == PERSIST {
            return Some(c.t[i + 1 - PERSIST]);
        }
    }
    None
}

fn interp(c: &Curve, t: f64) -> f64 {
    let i = c.t.partition_point(|x| *x < t);
    if i == 0 {
        return c.rms[0];
    }
    if i >= c.t.len() {
        return *c.rms.last().unwrap_or(&1.0);
    }
    let (t0, t1, r0, r1) = (c.t[i - 1], c.t[i], c.rms[i - 1], c.rms[i]);
    if t1 > t0 {
        r0 + (r1 - r0) * (t - t0) / (t1 - t0)
    } else {
        r1
    }
}

fn simulate(
    life_factor: f64,
    seed: u64,
    every_fraction: f64,
    expected: f64,
) -> Result<(super::LifeResult, LifeRun), String> {
    let model = wearsim_core::presets::by_name("ims-za2115").ok_or("preset ims-za2115 missing")?;
    let spec = LifeSpec {
        model,
        life: super::calibrate::steel_life(life_factor),
        seed,
        snapshot_every: (expected * every_fraction).max(1000.0),
        window: 0.25,
        settle: 0.05,
    };
    let run = LifeRun::new(spec).map_err(|e| e.to_string())?;
    let r = run.run_snapshots(|_, _| {}).map_err(|e| e.to_string())?;
    Ok((r, run))
}

/// Runs the comparison with measured data under `data` (the shared data folder).
pub fn compare(data: &Path, seed: u64) -> Result<ImsComparison, String> {
    let (measured, hours) = measured_curve(data)?;
    let target = hours * 3600.0 * 2000.0 / 60.0;
    // Uncalibrated: ISO 281 life (factor 1). Then calibrate the factor by secant steps on
    // the part of life it scales (fatigue up to crack opening); the rest is fixed physics.
    let (r1, _) = simulate(1.0, seed, 1.0 / 300.0, 5e8)?;
    let uncalibrated = r1.state.cycles;
    let step = Secant {
        fixed: fixed_part(&r1.state),
        min_steps: 1,
        max_steps: 6,
    };
    let c = calibrate(target, (uncalibrated, r1), &step, |a| {
        let (r, _) = simulate(a, seed, 1.0 / 300.0, target)?;
        Ok::<_, String>((r.state.cycles, r))
    })?;
    let (a, r) = (c.factor, c.last);
    let t: Vec<f64> = r
        .snapshots
        .iter()
        .map(|s| s.cycles / r.state.cycles)
        .collect();
    let rms: Vec<f64> = r.snapshots.iter().map(|s| s.features.rms).collect();
    let simulated = normalise(t, rms);
    let (om, os) = (onset(&measured), onset(&simulated));
    let grid: Vec<f64> = (0..=200).map(|i| i as f64 / 200.0).collect();
    let diffs: Vec<f64> = grid
        .iter()
        .map(|t| 20.0 * (interp(&simulated, *t) / interp(&measured, *t)).log10())
        .collect();
    let n = diffs.len() as f64;
    Ok(ImsComparison {
        onset_error: om.zip(os).map(|(a, b)| (a - b).abs()),
        onset_measured: om,
        onset_simulated: os,
        distance_db_rms: (diffs.iter().map(|d| d * d).sum::<f64>() / n).sqrt(),
        distance_db_mean_abs: diffs.iter().map(|d| d.abs()).sum::<f64>() / n,
        end_ratio: (
            *measured.rms.last().unwrap_or(&1.0),
            *simulated.rms.last().unwrap_or(&1.0),
        ),
        measured_life_h: hours,
        measured_life_revs: target,
        uncalibrated_life_revs: uncalibrated,
        life_factor: a,
        simulated_life_revs: r.state.cycles,
        stages: r
            .state
            .events
            .iter()
            .map(|e| (e.stage.name().to_string(), e.cycles / r.state.cycles))
            .collect(),
        measured,
        simulated,
    })
}

/// Revolutions of the life not scaled by the life factor: from crack opening to failure.
fn fixed_part(st: &wearsim_core::wear::LifeState) -> f64 {
    let open = st
        .events
        .iter()
        .find(|e| e.stage == wearsim_core::wear::Stage::CrackOpening)
        .map(|e| e.cycles)
        .unwrap_or(0.0);
    st.cycles - open
}
