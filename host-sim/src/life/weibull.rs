//! Two-parameter Weibull fit of a set of lives (maximum likelihood, with suspensions:
//! right-censored lives) with percentile bootstrap confidence intervals, and the
//! life–load exponent from lives at several loads. Used by `wearsim life --lives N`.
//!
//! Source: the Weibull likelihood equations with suspensions as in Abernethy, *The New
//! Weibull Handbook* (5th ed., §5.3) and Nelson, *Applied Life Data Analysis* (1982,
//! ch. 8); L10 = η·(−ln 0.9)^(1/β) (ISO 281's 90 % reliability).

use crate::analysis::stats;
use serde::Serialize;

/// A fitted Weibull distribution of lives.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Weibull {
    /// Shape (slope) β.
    pub shape: f64,
    /// Scale η (characteristic life, same unit as the data: 63.2 % have failed).
    pub scale: f64,
}

impl Weibull {
    /// Life with reliability `r` (0 < r < 1): η·(−ln r)^(1/β).
    pub fn life_at(&self, r: f64) -> f64 {
        self.scale * (-r.ln()).powf(1.0 / self.shape)
    }

    /// L10: life reached by 90 % of the bearings.
    pub fn l10(&self) -> f64 {
        self.life_at(0.9)
    }
}

/// One unit of a life test: its time (revolutions, or any unit > 0) and whether it
/// failed then or was suspended (still running when the test stopped: right-censored).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Unit {
    /// Time at failure or at suspension.
    pub time: f64,
    /// `true`: failed at `time`; `false`: suspended at `time` (its life is longer).
    pub failed: bool,
}

impl Unit {
    /// A unit that failed at `time`.
    pub fn failure(time: f64) -> Self {
        Unit { time, failed: true }
    }
}

/// Maximum-likelihood fit of lives `x` (all failed; all > 0, at least 3, not all equal):
/// [`fit_units`] without suspensions.
pub fn fit(x: &[f64]) -> Option<Weibull> {
    fit_units(&x.iter().copied().map(Unit::failure).collect::<Vec<_>>())
}

/// Maximum-likelihood fit of `units`, failures and suspensions (all times finite and
/// positive, at least 3 failures, not all times equal); `None` otherwise. With `r` failures,
/// β solves the profile equation Σtᵝ ln t / Σtᵝ − 1/β − (1/r)·Σ_failed ln t = 0 (sums
/// over all units; increasing in β), found by bisection on [0.05, 100], and
/// η = (Σtᵝ / r)^(1/β) (Nelson 1982, ch. 8). The powers are taken relative to
/// the largest time (log-sum-exp), so they stay finite for any spread.
pub fn fit_units(units: &[Unit]) -> Option<Weibull> {
    let r = units.iter().filter(|u| u.failed).count();
    if r < 3 || units.iter().any(|u| !(u.time.is_finite() && u.time > 0.0)) {
        return None;
    }
    let ln: Vec<f64> = units.iter().map(|u| u.time.ln()).collect();
    let top = ln.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let low = ln.iter().copied().fold(f64::INFINITY, f64::min);
    if top - low <= 1e-12 {
        return None;
    }
    let r = r as f64;
    // ln t relative to the largest: every term e^{β·d} is in (0, 1].
    let d: Vec<f64> = ln.iter().map(|l| l - top).collect();
    let mean_failed = units
        .iter()
        .zip(&d)
        .filter(|(u, _)| u.failed)
        .map(|(_, d)| d)
        .sum::<f64>()
        / r;
    let sums = |b: f64| {
        let (mut s, mut sl) = (0.0, 0.0);
        for v in &d {
            let p = (b * v).exp();
            s += p;
            sl += p * v;
        }
        (s, sl)
    };
    let f = |b: f64| {
        let (s, sl) = sums(b);
        sl / s - 1.0 / b - mean_failed
    };
    let (mut lo, mut hi) = (0.05_f64, 100.0_f64);
    if !(f(lo) <= 0.0 && f(hi) >= 0.0) {
        return None;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let b = 0.5 * (lo + hi);
    let (s, _) = sums(b);
    Some(Weibull {
        shape: b,
        scale: (top + (s / r).ln() / b).exp(),
    })
}

/// Plotting positions of the failures among `units` for a Weibull probability plot:
/// `(time, unreliability F)` in time order, with Johnson's adjusted ranks for the
/// suspensions (rank_j = (r_rev·rank_{j−1} + n + 1) / (r_rev + 1), r_rev the reverse rank
/// of the unit in the sorted list) and Bernard's median rank F = (rank − 0.3) / (n + 0.4)
/// (Abernethy, *The New Weibull Handbook*, 5th ed., §2.4 and §2.9). Without suspensions
/// the ranks are 1, 2, …, n. Units with a non-finite or non-positive time are left out.
pub fn median_ranks(units: &[Unit]) -> Vec<(f64, f64)> {
    let mut u: Vec<Unit> = units
        .iter()
        .copied()
        .filter(|u| u.time.is_finite() && u.time > 0.0)
        .collect();
    // At equal times failures come first (a suspension at a failure's time outlived it).
    u.sort_by(|a, b| a.time.total_cmp(&b.time).then(b.failed.cmp(&a.failed)));
    let n = u.len() as f64;
    let mut rank = 0.0;
    let mut out = vec![];
    for (i, x) in u.iter().enumerate() {
        if x.failed {
            let rev = n - i as f64;
            rank = (rev * rank + n + 1.0) / (rev + 1.0);
            out.push((x.time, (rank - 0.3) / (n + 0.4)));
        }
    }
    out
}

/// A value with a two-sided 90 % confidence interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Estimate {
    /// Point estimate.
    pub value: f64,
    /// 5th percentile of the bootstrap.
    pub lo: f64,
    /// 95th percentile of the bootstrap.
    pub hi: f64,
}

/// Small deterministic generator for the bootstrap (SplitMix64).
#[derive(Debug, Clone)]
pub struct SplitMix(pub u64);

impl SplitMix {
    /// Next value in [0, n).
    pub fn below(&mut self, n: usize) -> usize {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        ((z >> 11) as f64 / (1u64 << 53) as f64 * n as f64) as usize % n.max(1)
    }
}

/// Quantile `q` of the bootstrap values `v` ([`stats::quantile`]; NaN when none).
fn percentile(v: &mut [f64], q: f64) -> f64 {
    v.sort_by(f64::total_cmp);
    stats::quantile(v, q).unwrap_or(f64::NAN)
}

fn resample(x: &[Unit], rng: &mut SplitMix) -> Vec<Unit> {
    (0..x.len()).map(|_| x[rng.below(x.len())]).collect()
}

/// Weibull fit with bootstrap intervals of shape and L10 (`reps` resamples, seed
/// `seed`).
#[derive(Debug, Clone, Copy, Serialize)]
pub struct WeibullFit {
    /// Shape β.
    pub shape: Estimate,
    /// Scale η.
    pub scale: Estimate,
    /// L10.
    pub l10: Estimate,
}

/// Fits `x` (failures and suspensions, [`fit_units`]) and bootstraps the intervals
/// (units resampled with their failed/suspended mark; a resample with fewer than 3
/// failures gives no fit and is skipped).
pub fn fit_with_ci(x: &[Unit], reps: usize, seed: u64) -> Option<WeibullFit> {
    let w = fit_units(x)?;
    let mut rng = SplitMix(seed);
    let (mut b, mut s, mut l) = (vec![], vec![], vec![]);
    for _ in 0..reps {
        if let Some(f) = fit_units(&resample(x, &mut rng)) {
            b.push(f.shape);
            s.push(f.scale);
            l.push(f.l10());
        }
    }
    let est = |v: f64, mut bs: Vec<f64>| Estimate {
        value: v,
        lo: percentile(&mut bs, 0.05),
        hi: percentile(&mut bs, 0.95),
    };
    Some(WeibullFit {
        shape: est(w.shape, b),
        scale: est(w.scale, s),
        l10: est(w.l10(), l),
    })
}

/// Life–load exponent: the slope of ln(characteristic life η) against ln(load) by least
/// squares over the load groups `(load, lives)` (≥ 2 loads, each fitted with its
/// suspensions, [`fit_units`]), with a bootstrap interval (lives resampled within each
/// load). ISO 281 gives −3 for ball bearings, −10/3 for roller bearings.
pub fn load_exponent(groups: &[(f64, Vec<Unit>)], reps: usize, seed: u64) -> Option<Estimate> {
    if groups.len() < 2 {
        return None;
    }
    let slope = |etas: &[(f64, f64)]| {
        let n = etas.len() as f64;
        let mx = etas.iter().map(|(p, _)| p.ln()).sum::<f64>() / n;
        let my = etas.iter().map(|(_, e)| e.ln()).sum::<f64>() / n;
        let sxy: f64 = etas
            .iter()
            .map(|(p, e)| (p.ln() - mx) * (e.ln() - my))
            .sum();
        let sxx: f64 = etas.iter().map(|(p, _)| (p.ln() - mx).powi(2)).sum();
        (sxx > 0.0).then(|| sxy / sxx)
    };
    let etas: Option<Vec<(f64, f64)>> = groups
        .iter()
        .map(|(p, x)| fit_units(x).map(|w| (*p, w.scale)))
        .collect();
    let value = slope(&etas?)?;
    let mut rng = SplitMix(seed);
    let mut bs = vec![];
    for _ in 0..reps {
        let e: Option<Vec<(f64, f64)>> = groups
            .iter()
            .map(|(p, x)| fit_units(&resample(x, &mut rng)).map(|w| (*p, w.scale)))
            .collect();
        if let Some(s) = e.and_then(|e| slope(&e)) {
            bs.push(s);
        }
    }
    Some(Estimate {
        value,
        lo: percentile(&mut bs.clone(), 0.05),
        hi: percentile(&mut bs, 0.95),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Weibull lives by inversion on a regular probability grid (no randomness).
    fn sample(shape: f64, scale: f64, n: usize) -> Vec<f64> {
        let mut rng = SplitMix(7);
        (0..n)
            .map(|_| {
                let u = (rng.below(1_000_000) as f64 + 0.5) / 1e6;
                scale * (-(1.0 - u).ln()).powf(1.0 / shape)
            })
            .collect()
    }

    #[test]
    fn recovers_shape_and_scale() {
        for (b, e) in [(1.11, 1e8), (3.0, 5.0), (0.8, 2e3)] {
            let x = sample(b, e, 4000);
            let w = fit(&x).unwrap();
            assert!((w.shape / b - 1.0).abs() < 0.05, "{b}: {w:?}");
            assert!((w.scale / e - 1.0).abs() < 0.06, "{e}: {w:?}");
        }
    }

    #[test]
    fn l10_is_the_tenth_percentile() {
        let w = Weibull {
            shape: 1.5,
            scale: 10.0,
        };
        let cdf = 1.0 - (-(w.l10() / w.scale).powf(w.shape)).exp();
        assert!((cdf - 0.1).abs() < 1e-12);
    }

    fn failures(x: Vec<f64>) -> Vec<Unit> {
        x.into_iter().map(Unit::failure).collect()
    }

    /// A Type-I censored test: units still running at `stop` are suspended there.
    fn stopped_at(x: &[f64], stop: f64) -> Vec<Unit> {
        x.iter()
            .map(|&t| Unit {
                time: t.min(stop),
                failed: t <= stop,
            })
            .collect()
    }

    /// With a test stopped at η (63 % failed) or at 0.3 η (27 % at β = 1.11), the fit with the
    /// suspensions recovers shape and scale; dropping the suspensions, or counting them as
    /// failures at the stop, is far off (so the test can fail).
    #[test]
    fn suspensions_are_fitted_as_longer_lives() {
        // Stopped at η: 63 % failed; at 0.3 η with β = 1.11: 27 %.
        for (b, e, stop) in [(1.11, 1e7, 1e7), (1.11, 1e7, 3e6), (3.0, 5.0, 5.0)] {
            let x = sample(b, e, 4000);
            let u = stopped_at(&x, stop);
            let w = fit_units(&u).unwrap();
            assert!((w.shape / b - 1.0).abs() < 0.04, "{b} {stop}: {w:?}");
            assert!((w.scale / e - 1.0).abs() < 0.04, "{e} {stop}: {w:?}");
            let dropped: Vec<f64> = u.iter().filter(|u| u.failed).map(|u| u.time).collect();
            let d = fit(&dropped).unwrap();
            assert!(d.scale < 0.8 * e, "failures alone: {d:?}");
            let all: Vec<f64> = u.iter().map(|u| u.time).collect();
            assert!(
                fit(&all).is_none_or(|a| a.scale < 0.9 * e),
                "suspensions as failures"
            );
        }
    }

    /// Without suspensions the fit is the classic one: β from Σxᵝ ln x / Σxᵝ − 1/β =
    /// mean ln x, η = (mean xᵝ)^{1/β} (checked against those equations directly).
    #[test]
    fn complete_data_solve_the_classic_equations() {
        let x = sample(1.4, 3e6, 200);
        let w = fit(&x).unwrap();
        let n = x.len() as f64;
        let ml = x.iter().map(|v| v.ln()).sum::<f64>() / n;
        let s: f64 = x.iter().map(|v| v.powf(w.shape)).sum();
        let sl: f64 = x.iter().map(|v| v.powf(w.shape) * v.ln()).sum();
        assert!((sl / s - 1.0 / w.shape - ml).abs() < 1e-9, "{w:?}");
        assert!(
            (w.scale / (s / n).powf(1.0 / w.shape) - 1.0).abs() < 1e-9,
            "{w:?}"
        );
    }

    /// Johnson's adjusted ranks on the handbook's pattern F, S, F, F, S (n = 5): ranks 1,
    /// 2.25, 3.5; without suspensions 1..n; Bernard's approximation on top.
    #[test]
    fn median_ranks_adjust_for_suspensions() {
        let u = |time, failed| Unit { time, failed };
        let pts = median_ranks(&[
            u(40.0, false),
            u(10.0, true),
            u(30.0, true),
            u(20.0, false),
            u(35.0, true),
        ]);
        let ranks: Vec<f64> = pts.iter().map(|(_, f)| f * 5.4 + 0.3).collect();
        let times: Vec<f64> = pts.iter().map(|(t, _)| *t).collect();
        assert_eq!(times, [10.0, 30.0, 35.0]);
        for (r, want) in ranks.iter().zip([1.0, 2.25, 3.5]) {
            assert!((r - want).abs() < 1e-12, "{ranks:?}");
        }
        let all = median_ranks(&failures(vec![3.0, 1.0, 2.0]));
        assert_eq!(all.iter().map(|p| p.0).collect::<Vec<_>>(), [1.0, 2.0, 3.0]);
        assert!((all[0].1 - 0.7 / 3.4).abs() < 1e-12);
    }

    /// Fewer than 3 failures give no fit, whatever the suspensions.
    #[test]
    fn fewer_than_three_failures_give_no_fit() {
        let mut u = vec![Unit::failure(1.0), Unit::failure(2.0)];
        u.extend((0..20).map(|_| Unit {
            time: 5.0,
            failed: false,
        }));
        assert!(fit_units(&u).is_none());
        u.push(Unit::failure(3.0));
        assert!(fit_units(&u).is_some());
    }

    #[test]
    fn intervals_contain_the_truth_and_narrow_with_n() {
        let small = fit_with_ci(&failures(sample(1.5, 1.0, 40)), 300, 1).unwrap();
        let big = fit_with_ci(&failures(sample(1.5, 1.0, 800)), 300, 1).unwrap();
        assert!(big.shape.lo < 1.5 && 1.5 < big.shape.hi, "{big:?}");
        assert!(big.shape.hi - big.shape.lo < 0.5 * (small.shape.hi - small.shape.lo));
    }

    #[test]
    fn load_exponent_of_cubic_lives_is_minus_three() {
        let groups: Vec<(f64, Vec<Unit>)> = [1.0, 2.0]
            .iter()
            .map(|p: &f64| (*p, failures(sample(1.2, 1e6 * p.powf(-3.0), 500))))
            .collect();
        let e = load_exponent(&groups, 200, 3).unwrap();
        assert!((e.value + 3.0).abs() < 1e-9, "{e:?}");
        assert!(e.lo < -3.0 + 1e-9 && e.hi > -3.0 - 1e-9);
    }

    #[test]
    fn degenerate_sets_are_refused() {
        assert!(fit(&[1.0, 2.0]).is_none());
        assert!(fit(&[2.0, 2.0, 2.0]).is_none());
        assert!(fit(&[1.0, f64::NAN, 2.0]).is_none());
        assert!(fit(&[1.0, 0.0, 2.0]).is_none());
    }
}
