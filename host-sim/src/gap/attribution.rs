//! The result of an attribution (issue 13; sim-to-real.md, "attribution"): each
//! candidate effect alone on top of the baseline ([`Ranked`]), the model built from them
//! ([`Attribution`]) and its totals on the validation and test parts ([`Totals`]). The
//! types apart from the search that fills them (`gap::attribute`), so that the analyses
//! reading a finished attribution (`gap::identify`, `gap::protocol`) do not depend on
//! the search.

use super::fit::FittedParam;
use super::matched::Gaps;
use super::steps::{Dropped, Step};
use serde::Serialize;
use wearsim_core::effects::Effects;

/// One effect alone on top of the baseline.
#[derive(Debug, Clone, Serialize)]
pub struct Ranked {
    /// Effect name.
    pub effect: String,
    /// Fitted parameters with uncertainty.
    pub params: Vec<FittedParam>,
    /// Total gap on the training records with the effect.
    pub train_gap: f64,
    /// Total gap on the held-out records with the effect.
    pub holdout_gap: f64,
    /// `1 − holdout_gap / baseline held-out gap` (negative: the effect makes it worse).
    pub shrink: f64,
    /// The same shrink over the cells where the baseline's held-out gap lies (its
    /// [`WHERE_CELLS`] largest cells).
    pub where_shrink: f64,
    /// Total gap on the test part with the effect alone (set by
    /// `gap::protocol::judge`; `null` when there is no test part).
    pub test_gap: Option<f64>,
    /// `1 − test_gap / baseline test gap`: the shrink to report (the test part chose
    /// nothing).
    pub test_shrink: Option<f64>,
    /// The fit converged.
    pub converged: bool,
    /// Effects the cells cannot tell apart from this one at this record's noise (a
    /// confounded set, `gap::identify`); empty when it stands alone.
    pub confounded_with: Vec<String>,
    /// Validation shrink per cell group (`zone`, `shape`, `stat`, `env`): where it acts.
    pub group_shrink: std::collections::BTreeMap<String, f64>,
    /// The baseline with this effect alone at its fitted parameters.
    #[serde(skip)]
    pub effects: Effects,
    /// Its weighted cell signature and subspace at the fitted point.
    #[serde(skip)]
    pub signature: super::signature::Signature,
    /// Validation cell gaps with the effect.
    #[serde(skip)]
    pub holdout: Gaps,
    /// Objective evaluations of the fit.
    pub evaluations: usize,
}

/// The answer to "which" and "how far".
#[derive(Debug, Clone, Serialize)]
pub struct Attribution {
    /// Candidate effects left out because the training records cannot inform them
    /// (filled by the caller that checked, [`super::informed::split`]).
    pub uninformed: Vec<super::informed::Uninformed>,
    /// Baseline total gap on the training records.
    pub baseline_train: f64,
    /// Baseline total gap on the held-out records.
    pub baseline_holdout: f64,
    /// Effects ranked by held-out shrink, best first.
    pub ranking: Vec<Ranked>,
    /// Effects added greedily, in order.
    pub greedy: Vec<Step>,
    /// Effects removed again because a later addition made them redundant: withholding
    /// them from the model no longer grew the held-out gap by the minimum shrink.
    pub dropped: Vec<Dropped>,
    /// Exchanges made once the greedy additions were done, stalled or the model full
    /// ([`super::attribute::Options::exchange`]); each added effect also has its [`Step`].
    pub exchanged: Vec<super::exchange::Exchanged>,
    /// The effects of the final model, in the order they were added.
    pub kept: Vec<String>,
    /// Held-out total gap after the greedy additions.
    pub final_holdout: f64,
    /// The effect the diagnosis names first, if any effect shrinks the gap meaningfully.
    pub identified: Option<String>,
    /// Effects whose shrink ties with the first one (not told apart by the cells).
    pub tied_with: Vec<String>,
    /// Conclusions and limits in words (what could not be determined, and why).
    pub findings: Vec<String>,
    /// Simulations run.
    pub simulations: usize,
    /// Wall-clock time (s).
    pub seconds: f64,
    /// The effects switched on at the end.
    #[serde(skip)]
    pub final_effects: Effects,
    /// Totals on the test part, when one was judged (`gap::protocol::judge`).
    pub test: Option<TestTotals>,
    /// Held-out cell gaps of the baseline.
    #[serde(skip)]
    pub holdout_before: Gaps,
    /// Held-out cell gaps at the end.
    #[serde(skip)]
    pub holdout_after: Gaps,
}

/// Cells that define "where the gap lies" for [`Ranked::where_shrink`].
pub const WHERE_CELLS: usize = 5;

/// Total gaps on the test part.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct TestTotals {
    /// Baseline total gap on the test part.
    pub before: f64,
    /// Total gap of the chosen model (the kept effects) on the test part.
    pub after: f64,
    /// `1 − after/before`.
    pub shrink: f64,
    /// The chosen model closes the gap: `after` is below [`super::attribute::Options::significant_gap`],
    /// within the measurement's own segment-to-segment variability.
    pub closed: bool,
}

/// Total gaps. `before`/`after` are on the validation part, which chose the model (a
/// shrink there is biased upwards); `test_before`/`test_after` on the test part, which
/// chose nothing: the figure to report (`null` when no test part was judged).
#[derive(Debug, Clone, Serialize)]
pub struct Totals {
    /// Baseline, training records.
    pub train_before: f64,
    /// Baseline, validation (held-out) records.
    pub before: f64,
    /// Validation after the greedy additions.
    pub after: f64,
    /// `1 − after/before` (validation).
    pub shrink: f64,
    /// Baseline, test part.
    pub test_before: Option<f64>,
    /// Test part, chosen model.
    pub test_after: Option<f64>,
    /// `1 − test_after/test_before`.
    pub test_shrink: Option<f64>,
    /// Whether the chosen model closes the test gap ([`TestTotals::closed`]); when it
    /// does not, a mechanism outside the library remains.
    pub closed_by_library: Option<bool>,
}

impl Totals {
    /// The totals of an attribution.
    pub fn of(at: &Attribution) -> Self {
        Totals {
            train_before: at.baseline_train,
            before: at.baseline_holdout,
            after: at.final_holdout,
            shrink: 1.0 - at.final_holdout / at.baseline_holdout,
            test_before: at.test.map(|t| t.before),
            test_after: at.test.map(|t| t.after),
            test_shrink: at.test.map(|t| t.shrink),
            closed_by_library: at.test.map(|t| t.closed),
        }
    }
}
