//! The steps of the greedy model building ([`super::attribute`]): an effect added, the
//! kept effects refitted with it, an effect taken out again.

use super::fit::FittedParam;
use serde::Serialize;

/// One greedy step.
#[derive(Debug, Clone, Serialize)]
pub struct Step {
    /// Effect added.
    pub effect: String,
    /// Its parameters, fitted on top of the effects added before.
    pub params: Vec<FittedParam>,
    /// Held-out total gap before the step.
    pub before: f64,
    /// Held-out total gap after the step.
    pub after: f64,
    /// `1 − after/before`.
    pub shrink: f64,
    /// The effects kept before, refitted with this one on ([`super::attribute::Options::backfit`], or an
    /// exchange, [`super::attribute::Options::exchange`]): their parameters in the model from this step on
    /// (empty otherwise).
    pub refitted: Vec<Refitted>,
    /// The other candidates of this step that can reproduce its effect's cell signature at
    /// the record's resolution, fitted on top of the same model ([`super::identify::step_set`];
    /// empty for the first step, whose set is its ranking entry's `confounded_with`).
    pub confounded_with: Vec<String>,
}

/// An earlier effect's parameters refitted at a greedy step.
#[derive(Debug, Clone, Serialize)]
pub struct Refitted {
    /// Effect name.
    pub effect: String,
    /// Its parameters refitted with the step's effect on.
    pub params: Vec<FittedParam>,
}

/// An effect taken out again after a later one made it redundant (stepwise selection).
#[derive(Debug, Clone, Serialize)]
pub struct Dropped {
    /// Effect removed.
    pub effect: String,
    /// The addition after which it stopped mattering.
    pub after: String,
    /// Held-out total gap with it.
    pub with: f64,
    /// Held-out total gap without it.
    pub without: f64,
}
