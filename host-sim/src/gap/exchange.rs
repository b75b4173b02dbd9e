//! The exchange step of the stepwise selection (`gap::attribute`, `--exchange`): once the
//! greedy additions are done, each effect of the current model is, in turn, replaced by
//! each candidate not yet tried: the candidate refitted on the training part on the
//! baseline, the other kept effects refitted on top of it. The best replacement is taken
//! if it shrinks the validation gap by the minimum below both the current model and the
//! same refits without an exchange. Forward selection cannot undo an early choice: a
//! broad effect fitted first can take a second effect's gap, and the effect that belongs
//! there then shrinks little on top of it. The exchange is the usual remedy of stepwise
//! selection (the "sequential replacement" of Miller 2002, *Subset Selection in
//! Regression*, 2nd ed., ch. 3), judged like every greedy step on the validation part,
//! never on the test part.

use super::fit::{fit_many, Budget, Fit, Job};
use super::matched::{Evaluator, Gaps, Target};
use super::space::FitSpace;
use serde::Serialize;
use wearsim_core::effects::Effects;

/// An exchange made: `out` replaced by `added`.
#[derive(Debug, Clone, Serialize)]
pub struct Exchanged {
    /// Effect taken out of the model.
    pub out: String,
    /// Effect put in its place, fitted on top of the others.
    pub added: String,
    /// Validation total gap before the exchange.
    pub before: f64,
    /// Validation total gap after it.
    pub after: f64,
}

/// The best replacement found by [`best`].
pub struct Replacement<'a> {
    /// Effect taken out.
    pub out: String,
    /// The candidate's fit on the baseline (the other kept effects were refitted on top
    /// of it).
    pub fit: Fit,
    /// The candidate's fit space.
    pub space: &'a FitSpace,
    /// The model after the exchange.
    pub effects: Effects,
    /// Its validation cell gaps.
    pub gaps: Gaps,
    /// The other kept effects, refitted on top of the candidate, in order.
    pub others: Vec<(String, Fit)>,
    /// The smallest validation total gap of the current effects rebuilt the same way
    /// (each kept effect refitted first, the others on top): what the refits give without
    /// an exchange.
    pub rebuilt: f64,
}

/// Every effect of `kept` replaced by every space whose effect is not in `used`: the
/// candidate fitted on `train` on top of `base` (the attribution's baseline, starting at
/// its single fit from `hints`), then the other kept effects refitted on top of it one by
/// one in their order (starting at their coordinates in the current model, `kept`'s second
/// element), so that they can give back what they took of the candidate's gap; every
/// stage's fits run in lock step, each a local search from its start ([`Budget::local`]).
/// Returns the replacement with the smallest total gap on
/// `holdout` (`None` when there is nothing to try).
#[allow(clippy::too_many_arguments)]
pub fn best<'a, T: Target>(
    kept: &[(String, Vec<f64>)],
    used: &[String],
    hints: &[(Fit, &FitSpace)],
    spaces: &'a [FitSpace],
    base: &Effects,
    train: &[T],
    holdout: &[T],
    ev: &Evaluator,
    budget: Budget,
) -> Result<Option<Replacement<'a>>, String> {
    let hint = |e: &str| {
        hints
            .iter()
            .find(|(f, _)| f.effect == e)
            .map(|(f, _)| f.coords.as_slice())
    };
    let space = |e: &str| spaces.iter().find(|s| s.effect == e);
    let is_kept = |e: &str| kept.iter().any(|(k, _)| k == e);
    // The candidates, and the kept effects themselves: each kept effect rebuilt first in
    // its own slot is the yardstick (the same refits without an exchange), so that an
    // exchange is not credited with what the refits alone give.
    let cands: Vec<&FitSpace> = spaces
        .iter()
        .filter(|s| !used.iter().any(|u| u == s.effect) || is_kept(s.effect))
        .collect();
    if !cands.iter().any(|s| !is_kept(s.effect)) || kept.is_empty() {
        return Ok(None);
    }
    // The candidates alone, refitted on these parts.
    let jobs: Vec<Job> = cands
        .iter()
        .map(|s| Job {
            space: s,
            base,
            hint: hint(s.effect),
        })
        .collect();
    // Every refit here starts at a known optimum and searches locally from it.
    let local = Budget {
        local: true,
        ..budget
    };
    let alone = fit_many(&jobs, train, ev, local);
    // One model per (replaced effect, candidate).
    #[allow(clippy::type_complexity)]
    let mut models: Vec<(usize, usize, Effects, Vec<(String, Fit)>)> = vec![];
    for (i, (own, _)) in kept.iter().enumerate() {
        for (j, (f, s)) in alone.iter().zip(&cands).enumerate() {
            if !is_kept(s.effect) || s.effect == own.as_str() {
                models.push((i, j, f.effects(s, base), vec![]));
            }
        }
    }
    // The other kept effects on top, one stage per effect, in the model's order.
    for (k, (name, coords)) in kept.iter().enumerate() {
        let Some(sp) = space(name) else { continue };
        let idx: Vec<usize> = (0..models.len())
            .filter(|m| models.get(*m).is_some_and(|(i, _, _, _)| *i != k))
            .collect();
        let fxs: Vec<Effects> = idx
            .iter()
            .filter_map(|m| models.get(*m).map(|x| x.2))
            .collect();
        let jobs: Vec<Job> = fxs
            .iter()
            .map(|fx| Job {
                space: sp,
                base: fx,
                hint: Some(coords.as_slice()),
            })
            .collect();
        let fits = fit_many(&jobs, train, ev, local);
        for ((m, f), fx) in idx.iter().zip(fits).zip(&fxs) {
            if let Some(x) = models.get_mut(*m) {
                x.2 = f.effects(sp, fx);
                x.3.push((name.clone(), f));
            }
        }
    }
    let fxs: Vec<Effects> = models.iter().map(|m| m.2).collect();
    let held = ev.residuals_many(holdout, &fxs);
    let mut best: Option<Replacement<'a>> = None;
    let mut rebuilt = f64::INFINITY;
    for ((i, j, fx, others), r) in models.into_iter().zip(held) {
        let (Some(r), Some((out, _)), Some(f), Some(s)) =
            (r, kept.get(i), alone.get(j), cands.get(j))
        else {
            continue;
        };
        if is_kept(s.effect) {
            rebuilt = rebuilt.min(r.total());
            continue;
        }
        if best.as_ref().is_none_or(|b| r.total() < b.gaps.total()) {
            best = Some(Replacement {
                out: out.clone(),
                fit: f.clone(),
                space: s,
                effects: fx,
                gaps: r,
                others,
                rebuilt: f64::INFINITY,
            });
        }
    }
    Ok(best.map(|b| Replacement { rebuilt, ..b }))
}
