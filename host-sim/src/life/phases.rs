//! The share of a life each damage phase takes, and how it moves with the load
//! (`wearsim life --lives N --loads a,b`).
//!
//! A life–load exponent to failure is a blend of the phases' own load laws: a phase
//! whose duration falls more slowly with the load than the others takes a larger share
//! of the life at a heavier load and flattens the blended exponent. Two shares are
//! reported per load, each as a median over the lives with a 90 % bootstrap interval:
//!
//! * **crack share** — of the revolutions to the first spall (entry into defect
//!   completion), the part from the crack's opening to the spall: the crack-growth
//!   phase of the "crack-to-spall" life. A 3-D finite-element damage model over
//!   2–4.5 GPa with 33 random microstructures (J. Tribol. 136(1):011402, 2014, as
//!   summarised in `shared/docs/life-physics-sources.md` §1) finds that a higher load
//!   leaves a **smaller** share of that life to propagation: the published direction.
//! * **post-spall share** — of the revolutions to failure, the part from the first spall
//!   on (the spall's growth and the spawning of new defects). No published number or
//!   direction was found for it (same source, "share of life in propagation, and its
//!   load dependence: no number confirmed"); Rosado et al. 2010 (Tribol. Trans.,
//!   doi:10.1080/10402000903226366) report only that the time to the rapid growth rate
//!   shortens with stress, a statement about its length, not its share.
//!
//! Across loads the direction is called only where the two extreme loads' intervals do
//! not overlap ([`Trend::Undecided`] otherwise), so a direction is never read from
//! scatter.

use super::weibull::{Estimate, SplitMix};
use crate::analysis::stats::{median, quantile};
use serde::Serialize;

/// The published direction of the crack share with load and its source.
pub const CRACK_SHARE_PUBLISHED: (Trend, &str) = (
    Trend::Falls,
    "3-D FE damage model, 2–4.5 GPa, 33 random microstructures (J. Tribol. 136(1):011402, 2014): a higher load leaves a smaller share of the crack-to-spall life to propagation",
);

/// Why the post-spall share has no published direction.
pub const POST_SPALL_SHARE_UNPUBLISHED: &str = "no published share or direction found (shared/docs/life-physics-sources.md §1); Rosado et al. 2010 report only that the time to the rapid spall-growth rate shortens with stress";

/// The shares of one load's lives.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PhaseShares {
    /// Crack share (–): median over the lives that reached their first spall of
    /// `(first spall − crack opening) / first spall`, with its 90 % bootstrap interval;
    /// `None` without such lives.
    pub crack: Option<Estimate>,
    /// Lives the crack share is taken over.
    pub crack_lives: usize,
    /// Post-spall share (–): median over the failed lives of
    /// `(failure − first spall) / failure`, with its interval; `None` without such lives.
    pub post_spall: Option<Estimate>,
    /// Lives the post-spall share is taken over.
    pub post_spall_lives: usize,
}

/// Direction of a share from the lightest load to the heaviest.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Trend {
    /// The heaviest load's interval lies wholly below the lightest's.
    Falls,
    /// The heaviest load's interval lies wholly above the lightest's.
    Rises,
    /// The intervals overlap: no direction can be read.
    Undecided,
}

/// A share's movement across the loads, against the published direction if there is one.
#[derive(Debug, Clone, Serialize)]
pub struct ShareTrend {
    /// Lightest and heaviest radial load (N).
    pub loads_n: [f64; 2],
    /// The share at the lightest and at the heaviest load.
    pub shares: [Estimate; 2],
    /// Direction from the lightest to the heaviest load.
    pub direction: Trend,
    /// The published direction, if any.
    pub published: Option<Trend>,
    /// Its source, or why there is none.
    pub source: &'static str,
    /// Whether the model's direction is the published one (`None` when either is
    /// undecided or unpublished).
    pub agrees: Option<bool>,
}

/// The phase shares of one load's lives from each life's `crack` and `post_spall` share
/// (`life::lives` takes them from the stage times), each summarised by its median with a
/// bootstrap interval (`reps` resamples seeded by `seed`).
pub fn shares(crack: &[f64], post_spall: &[f64], reps: usize, seed: u64) -> PhaseShares {
    PhaseShares {
        crack_lives: crack.len(),
        crack: median_with_ci(crack, reps, seed),
        post_spall_lives: post_spall.len(),
        post_spall: median_with_ci(post_spall, reps, seed ^ 0x5A11),
    }
}

/// Median of `v` with the 5th and 95th percentiles of its bootstrap (`reps` resamples);
/// `None` for no finite values.
pub fn median_with_ci(v: &[f64], reps: usize, seed: u64) -> Option<Estimate> {
    let v: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
    let value = median(v.clone())?;
    let mut rng = SplitMix(seed);
    let mut boot: Vec<f64> = (0..reps)
        .filter_map(|_| median((0..v.len()).map(|_| v[rng.below(v.len())]).collect()))
        .collect();
    boot.sort_by(f64::total_cmp);
    Some(Estimate {
        value,
        lo: quantile(&boot, 0.05).unwrap_or(value),
        hi: quantile(&boot, 0.95).unwrap_or(value),
    })
}

/// The direction from `light` to `heavy`: only where their intervals do not overlap.
pub fn trend(light: &Estimate, heavy: &Estimate) -> Trend {
    if heavy.hi < light.lo {
        Trend::Falls
    } else if heavy.lo > light.hi {
        Trend::Rises
    } else {
        Trend::Undecided
    }
}

/// The movement of one share (`pick`) between the lightest and the heaviest of `groups`
/// (load in N, shares); `None` with fewer than two loads or a share missing at either end.
pub fn share_trend(
    groups: &[(f64, PhaseShares)],
    pick: fn(&PhaseShares) -> Option<Estimate>,
    published: Option<Trend>,
    source: &'static str,
) -> Option<ShareTrend> {
    let light = groups.iter().min_by(|a, b| a.0.total_cmp(&b.0))?;
    let heavy = groups.iter().max_by(|a, b| a.0.total_cmp(&b.0))?;
    if light.0 == heavy.0 {
        return None;
    }
    let (a, b) = (pick(&light.1)?, pick(&heavy.1)?);
    let direction = trend(&a, &b);
    let agrees = match (direction, published) {
        (Trend::Undecided, _) | (_, None) => None,
        (d, Some(p)) => Some(d == p),
    };
    Some(ShareTrend {
        loads_n: [light.0, heavy.0],
        shares: [a, b],
        direction,
        published,
        source,
        agrees,
    })
}

/// The crack share's trend against [`CRACK_SHARE_PUBLISHED`].
pub fn crack_trend(groups: &[(f64, PhaseShares)]) -> Option<ShareTrend> {
    let (dir, src) = CRACK_SHARE_PUBLISHED;
    share_trend(groups, |s| s.crack, Some(dir), src)
}

/// The post-spall share's trend (no published direction).
pub fn post_spall_trend(groups: &[(f64, PhaseShares)]) -> Option<ShareTrend> {
    share_trend(groups, |s| s.post_spall, None, POST_SPALL_SHARE_UNPUBLISHED)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bootstrap interval of the median holds the sample median and narrows as the
    /// sample grows.
    #[test]
    fn the_medians_interval_narrows_with_more_lives() {
        let v = |n: usize| -> Vec<f64> { (0..n).map(|i| (i as f64 + 0.5) / n as f64).collect() };
        let small = median_with_ci(&v(20), 1000, 7).unwrap();
        let large = median_with_ci(&v(400), 1000, 7).unwrap();
        for e in [small, large] {
            assert!(
                (e.value - 0.5).abs() < 1e-12 && e.lo < 0.5 && e.hi > 0.5,
                "{e:?}"
            );
        }
        assert!(
            large.hi - large.lo < 0.4 * (small.hi - small.lo),
            "{small:?} {large:?}"
        );
        assert_eq!(median_with_ci(&[f64::NAN], 10, 1), None);
    }

    /// A direction is read only from intervals that do not overlap, and compared with
    /// the published one only where both exist.
    #[test]
    fn a_direction_needs_separate_intervals() {
        let e = |value, lo, hi| Estimate { value, lo, hi };
        assert_eq!(
            trend(&e(0.3, 0.25, 0.35), &e(0.2, 0.15, 0.24)),
            Trend::Falls
        );
        assert_eq!(trend(&e(0.3, 0.25, 0.35), &e(0.6, 0.5, 0.7)), Trend::Rises);
        assert_eq!(
            trend(&e(0.3, 0.25, 0.35), &e(0.33, 0.3, 0.4)),
            Trend::Undecided
        );
        let at = |c: Estimate| PhaseShares {
            crack: Some(c),
            crack_lives: 10,
            post_spall: Some(c),
            post_spall_lives: 10,
        };
        let g = [
            (800.0, at(e(0.6, 0.5, 0.7))),
            (500.0, at(e(0.3, 0.25, 0.35))),
        ];
        let t = crack_trend(&g).unwrap();
        assert_eq!(t.loads_n, [500.0, 800.0]);
        assert_eq!(
            (t.direction, t.published, t.agrees),
            (Trend::Rises, Some(Trend::Falls), Some(false))
        );
        let t = post_spall_trend(&g).unwrap();
        assert_eq!(
            (t.direction, t.published, t.agrees),
            (Trend::Rises, None, None)
        );
        assert!(crack_trend(&g[..1]).is_none());
    }
}
