//! Normalised life curves and the figures computed on them, shared by `wearsim
//! ims-compare` ([`super::ims_compare`]), `wearsim ims-validate` ([`super::ims_validate`])
//! and `wearsim life --lives`: a curve on one normalised time line (fraction of life) with
//! its values over their early-life median; the onset of instability (first time the curve
//! leaves its steady band for [`PERSIST`] consecutive snapshots; band = median + max(5
//! robust σ, 10 %) of the part of the life before the onset, see [`onset`]); and the
//! distance between two curves (RMS and mean absolute difference of 20·log₁₀ over a common
//! grid of [`GRID`] points).

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

/// Fraction of life whose snapshots give the first estimate of the steady band, and before
/// which no onset is searched (–).
pub const BASELINE: f64 = 0.25;

/// Rounds of re-estimating the band from the part before the onset found with the last.
const BAND_ROUNDS: usize = 8;

/// Fewest snapshots a steady band is estimated from (the baseline quarter must hold them).
pub const MIN_BASELINE: usize = 5;

/// The upper edge of the steady band of `values`: median + max(5 robust σ, 10 % of the
/// median); `None` under [`MIN_BASELINE`] values.
fn upper_edge(values: Vec<f64>) -> Option<f64> {
    if values.len() < MIN_BASELINE {
        return None;
    }
    let (m, sigma) = robust_sigma(values)?;
    Some(m + (5.0 * sigma).max(0.1 * m))
}

/// Index of the first of [`PERSIST`] snapshots in a row after fraction [`BASELINE`] that
/// lie above `upper`.
fn first_run_above(c: &Curve, upper: f64) -> Option<usize> {
    let mut run = 0;
    for (i, r) in c.rms.iter().enumerate() {
        if c.t[i] <= BASELINE {
            continue;
        }
        run = if *r > upper { run + 1 } else { 0 };
        if run == PERSIST {
            return Some(i + 1 - PERSIST);
        }
    }
    None
}

/// Onset of instability of a normalised curve (fraction of life): the first of
/// [`PERSIST`] snapshots in a row above the steady band of the snapshots before it.
///
/// The band is first estimated on the first [`BASELINE`] of the life, then re-estimated
/// from every snapshot before the onset it gives, until the onset no longer moves (at most
/// 8 rounds; the last is kept). A steady band taken from a fixed share of the
/// life cannot see an onset inside that share: with the first half (the rule until stop 48)
/// every life that degraded from 0.25–0.5 of its length was read as starting at 0.5, and a
/// life whose damaged part passed half its length lost its onset altogether. The first
/// quarter is the baseline because IMS test 1 shows why a shorter one fails: after a
/// six-day stop at 0.07 of the record every channel (failed bearings and sound ones alike)
/// runs 20 % higher for the rest of the test, a rig event, not wear; a baseline ending at
/// 0.12 or earlier reads it as bearing 3's onset (0.05 and 0.1: bearing 4's as well). `None`: fewer than 5 snapshots in the baseline,
/// or the curve never leaves its band after it.
pub fn onset(c: &Curve) -> Option<f64> {
    let baseline: Vec<f64> =
        c.t.iter()
            .zip(&c.rms)
            .filter(|(t, _)| **t <= BASELINE)
            .map(|(_, r)| *r)
            .collect();
    let mut at = first_run_above(c, upper_edge(baseline)?)?;
    for _ in 0..BAND_ROUNDS {
        let before = c.rms.get(..at)?.to_vec();
        match upper_edge(before).and_then(|u| first_run_above(c, u)) {
            Some(next) if next != at => at = next,
            _ => break,
        }
    }
    c.t.get(at).copied()
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A life of `n` snapshots at 1 with a deterministic ±3 % ripple, `level` from `from`
    /// on (fraction of life), and `rig` (×) from `rig_at` on (a step common to every
    /// channel, not wear).
    fn life(n: usize, from: f64, level: f64, rig_at: f64, rig: f64) -> Curve {
        let t: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
        let r = t
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let ripple = 1.0 + 0.03 * ((i as f64 * 2.399).sin());
                let wear = if *t >= from { level } else { 1.0 };
                let step = if *t >= rig_at { rig } else { 1.0 };
                ripple * wear * step
            })
            .collect();
        normalise(t, r)
    }

    fn near(a: Option<f64>, b: f64) -> bool {
        a.is_some_and(|a| (a - b).abs() < 0.006)
    }

    #[test]
    fn an_onset_in_the_first_half_is_found_where_it_is() {
        // The first-half band read this life as starting at 0.5 (its median and spread
        // are still the steady ones, so the search after 0.5 fired at once).
        for from in [0.3, 0.45, 0.6, 0.9] {
            let c = life(401, from, 3.0, 2.0, 1.0);
            assert!(near(onset(&c), from), "{from}: {:?}", onset(&c));
        }
    }

    #[test]
    fn a_damaged_part_longer_than_half_the_life_keeps_its_onset() {
        // Damaged from 0.27: 46 % of the first half is damaged, 73 % of the life.
        let c = life(401, 0.27, 6.0, 2.0, 1.0);
        assert!(near(onset(&c), 0.27), "{:?}", onset(&c));
    }

    #[test]
    fn a_rig_step_inside_the_baseline_is_not_an_onset() {
        // IMS test 1: +20 % on every channel from 0.07 of the record on.
        let c = life(401, 0.9, 2.0, 0.07, 1.2);
        assert!(near(onset(&c), 0.9), "{:?}", onset(&c));
    }

    #[test]
    fn a_life_that_never_leaves_its_band_has_no_onset() {
        assert_eq!(onset(&life(401, 2.0, 3.0, 2.0, 1.0)), None);
        // A rise inside the 10 % floor of the band is not an onset either.
        assert_eq!(onset(&life(401, 0.5, 1.05, 2.0, 1.0)), None);
        // Too few snapshots in the first quarter to have a band.
        assert_eq!(onset(&life(12, 0.5, 3.0, 2.0, 1.0)), None);
    }
}
