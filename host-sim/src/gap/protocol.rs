//! The clean held-out protocol (sim-to-real.md, "three disjoint parts"; issue 13): the
//! attribution fits every parameter on a training part and chooses the model (ranking,
//! greedy addition, dropping) on a validation part ([`super::attribute::attribute`]); the
//! shrink reported as the result is measured here, only on a test part used for neither.
//! A shrink measured on the part that chose the model is biased upwards (the choice
//! picked whatever fitted that part's realisation best).

use super::attribute::{Attribution, TestTotals};
use super::matched::{Evaluator, Target};
use wearsim_core::effects::Effects;

/// Judges a finished attribution on the test part `test` (never seen by the fit or the
/// choice): the baseline `base`, every ranked effect alone at its training fit, and the
/// final model. Fills [`super::attribute::Ranked::test_shrink`] and
/// [`Attribution::test`].
pub fn judge<T: Target>(
    at: &mut Attribution,
    base: &Effects,
    test: &[T],
    ev: &Evaluator,
) -> Result<TestTotals, String> {
    let before = ev.residuals(test, base)?.total();
    for r in &mut at.ranking {
        let g = ev.residuals(test, &r.effects)?.total();
        r.test_gap = Some(g);
        r.test_shrink = Some(1.0 - g / before);
    }
    let after = ev.residuals(test, &at.final_effects)?.total();
    let t = TestTotals {
        before,
        after,
        shrink: 1.0 - after / before,
    };
    at.test = Some(t);
    Ok(t)
}
