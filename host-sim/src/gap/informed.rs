//! Which candidate effects a record can inform (issue 13, "Bad input": "a requested effect
//! that the record cannot inform — its cells not resolved at this sample rate or length —
//! is reported as such, not fitted").
//!
//! The test is measured, not declared: each effect is simulated on the training records at
//! the two ends of its fit space (every fitted parameter at its lower, then at its upper
//! bound) and compared with the baseline. If across its whole range it moves no cell by
//! [`MIN_CELL_MOVE`] of that cell's own measured spread, nothing in these records can tell
//! one value of it from another (its lines above the Nyquist frequency, sidebands closer
//! than the record's resolution, a level far below the noise), so fitting it would only
//! return its starting point with an uncertainty as wide as its range. An end the model
//! cannot run at all counts as informative (the fit keeps away from it).

use super::matched::{Evaluator, Target};
use super::space::FitSpace;
use serde::Serialize;
use wearsim_core::effects::Effects;

/// Smallest largest-cell move (in units of the cell's measured spread) over an effect's
/// whole fit space for the records to inform it. Half a spread: a move that a correct
/// model's own sampling variability (≈ 1 spread) would hide even at the ends of the range.
pub const MIN_CELL_MOVE: f64 = 0.5;

/// An effect left out because the records cannot inform it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Uninformed {
    /// Effect name (catalogue).
    pub effect: String,
    /// Largest move of any weighted training cell between the baseline and either end of
    /// the effect's fit space, in spreads.
    pub max_cell_move: f64,
    /// The cell that moved most (its name; none when no cell moved at all).
    pub cell: Option<String>,
}

/// Largest |Δgap| over cells that carry weight, and where.
fn largest_move(base: &[f64], weights: &[f64], with: &[f64]) -> (f64, Option<usize>) {
    base.iter()
        .zip(with)
        .zip(weights)
        .enumerate()
        .filter(|(_, (_, w))| **w > 0.0)
        .map(|(i, ((b, g), _))| ((g - b).abs(), i))
        .filter(|(d, _)| d.is_finite())
        .fold(
            (0.0, None),
            |acc, (d, i)| {
                if d > acc.0 {
                    (d, Some(i))
                } else {
                    acc
                }
            },
        )
}

/// Splits `spaces` into those the training records `train` can inform and those they
/// cannot (each with its largest cell move), simulating each effect at both ends of its
/// space on top of `base`. `names` are one record's cell names (records repeat them).
pub fn split<T: Target>(
    spaces: Vec<FitSpace>,
    base: &Effects,
    train: &[T],
    ev: &Evaluator,
    names: &[String],
) -> Result<(Vec<FitSpace>, Vec<Uninformed>), String> {
    let b = ev.residuals(train, base)?;
    // Both ends of every space, simulated in one batch (lanes).
    let mut ends = Vec::with_capacity(2 * spaces.len());
    for s in &spaces {
        for u in [0.0, 1.0] {
            let mut fx = *base;
            s.apply(&mut fx, &vec![u; s.fitted.len()])?;
            ends.push(fx);
        }
    }
    let mut gaps = ev.residuals_many(train, &ends).into_iter();
    let mut keep = vec![];
    let mut left = vec![];
    for s in spaces {
        let mut most = (0.0_f64, None);
        for g in gaps.by_ref().take(2) {
            // An end the model cannot run (a stiffness beyond the internal rate, say)
            // changes it beyond any doubt: not a reason to call the effect uninformed.
            let Some(g) = g else {
                most = (f64::INFINITY, None);
                continue;
            };
            let m = largest_move(&b.gaps, &b.weights, &g.gaps);
            if m.0 > most.0 {
                most = m;
            }
        }
        if most.0 >= MIN_CELL_MOVE {
            keep.push(s);
        } else {
            left.push(Uninformed {
                effect: s.effect.to_string(),
                max_cell_move: most.0,
                cell: most
                    .1
                    .and_then(|i| names.get(i % names.len().max(1)).cloned()),
            });
        }
    }
    Ok((keep, left))
}

/// The report's words for an effect left out.
pub fn finding(u: &Uninformed) -> String {
    format!(
        "`{}` is not fitted: over its whole fit space it moves no cell of the training records by more than {:.2} of the cell's spread (at least {MIN_CELL_MOVE} needed), so these records cannot inform it (its cells unresolved at this sample rate, length or level)",
        u.effect, u.max_cell_move
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gap::space::{spaces, Context};
    use std::sync::atomic::{AtomicUsize, Ordering};
    use wearsim_core::effects::EffectKind;

    /// A record whose cells see only the `roughness` effect: cell 0 moves with its first
    /// parameter (in spreads, the parameter value itself), cell 1 never moves; every other
    /// effect leaves both cells alone, as an effect acting above the record's band would.
    struct OnlyRoughness;

    impl Target for OnlyRoughness {
        fn gaps(&self, fx: &Effects, sims: &AtomicUsize) -> Result<(Vec<f64>, Vec<f64>), String> {
            sims.fetch_add(1, Ordering::Relaxed);
            let r = fx.get(EffectKind::Roughness).map_or(0.0, |p| p[0]);
            Ok((vec![0.3 + r, -1.0], vec![0.8, 0.6]))
        }
    }

    #[test]
    fn effects_that_move_no_cell_are_left_out_with_their_largest_move() {
        let ctx = Context {
            fs: 12_000.0,
            shaft_hz: 30.0,
            rms: 1.0,
            mains_hz: 60.0,
            preload_max: crate::gap::space::CATALOGUE_PRELOAD_MAX,
        };
        let all = spaces(&ctx);
        let n = all.len();
        let ev = Evaluator::new(1);
        let names = vec!["level".to_string(), "kurtosis".to_string()];
        let (keep, left) = split(all, &Effects::NONE, &[OnlyRoughness], &ev, &names).unwrap();
        let kept: Vec<&str> = keep.iter().map(|s| s.effect).collect();
        assert_eq!(kept, ["roughness"]);
        assert_eq!(left.len(), n - 1);
        assert!(left
            .iter()
            .all(|u| u.max_cell_move == 0.0 && u.cell.is_none()));
        assert!(finding(&left[0]).contains("is not fitted"));
        // One baseline and two ends per effect.
        assert_eq!(ev.sims(), 1 + 2 * n);
    }

    #[test]
    fn largest_move_skips_unweighted_and_non_finite_cells() {
        let base = [0.0, 1.0, 2.0, 0.0];
        let w = [1.0, 0.0, 1.0, 1.0];
        let with = [0.3, 9.0, 1.4, f64::NAN];
        let (d, i) = largest_move(&base, &w, &with);
        assert!((d - 0.6).abs() < 1e-12, "{d}");
        assert_eq!(i, Some(2));
        assert_eq!(largest_move(&base, &w, &base), (0.0, None));
    }
}
