//! Normalised life curves and the figures computed on them, shared by `wearsim
//! ims-compare` ([`super::ims_compare`]), `wearsim ims-validate` ([`super::ims_validate`])
//! and `wearsim life --lives`: a curve on one normalised time line (fraction of life) with
//! its values over their early-life median; the onset of instability (first time the curve
//! leaves its steady band for [`PERSIST`] consecutive snapshots; band = median ± max(5
//! robust σ, 10 %) of the first half of life); and the distance between two curves (RMS
//! and mean absolute difference of 20·log₁₀ over a common grid of [`GRID`] points).

use crate::analysis::stats::{robust_sigma, upper_median};
use serde::Serialize;

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

/// Points of the common fraction-of-life grid of the distances.
pub const GRID: usize = 201;

/// The curve's value at fraction `t`, linear between its points and held at its ends.
pub fn interp(c: &Curve, t: f64) -> f64 {
    let i = c.t.partition_point(|x| *x < t);
    let last = c.rms.len().saturating_sub(1);
    if i == 0 {
        return c.rms.first().copied().unwrap_or(1.0);
    }
    if i > last {
        return c.rms.get(last).copied().unwrap_or(1.0);
    }
    let (t0, t1, r0, r1) = (c.t[i - 1], c.t[i], c.rms[i - 1], c.rms[i]);
    if t1 > t0 {
        r0 + (r1 - r0) * (t - t0) / (t1 - t0)
    } else {
        r1
    }
}

/// 20·log₁₀(`sim` / `meas`) at the [`GRID`] points of the common fraction-of-life grid.
fn db_differences<'a>(sim: &'a Curve, meas: &'a Curve) -> impl Iterator<Item = f64> + 'a {
    (0..GRID).map(move |i| {
        let t = i as f64 / (GRID - 1) as f64;
        20.0 * (interp(sim, t) / interp(meas, t)).log10()
    })
}

/// RMS over the common grid of the dB difference between two normalised curves.
pub fn distance_db(sim: &Curve, meas: &Curve) -> f64 {
    distance_db_from(sim, meas, 0.0)
}

/// [`distance_db`] over the grid points at or after fraction `from` of life only (`from`
/// clamped to 0–1; the last point, 1, is always in).
pub fn distance_db_from(sim: &Curve, meas: &Curve, from: f64) -> f64 {
    let from = from.clamp(0.0, 1.0);
    let (mut sq, mut n) = (0.0, 0usize);
    for (i, d) in db_differences(sim, meas).enumerate() {
        if i as f64 / (GRID - 1) as f64 >= from {
            sq += d * d;
            n += 1;
        }
    }
    (sq / n.max(1) as f64).sqrt()
}

/// Mean absolute dB difference between two normalised curves over the common grid.
pub fn distance_db_mean_abs(sim: &Curve, meas: &Curve) -> f64 {
    db_differences(sim, meas).map(f64::abs).sum::<f64>() / GRID as f64
}
