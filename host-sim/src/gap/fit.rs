//! Fitting one candidate effect's parameters on training records (sim-to-real.md, "Which"):
//! minimise the training total gap over the effect's fit space by a coarse grid followed
//! by a pattern search, then estimate the parameters' uncertainty from the local
//! sensitivity of the cell gaps (nonlinear least squares: `cov = s² (JᵀJ)⁻¹`, `J` the
//! Jacobian of the cell gaps by finite differences, `s²` the residual variance per degree
//! of freedom, at least the variance `2/K` of a gap between two `K`-segment means).
//!
//! The simulation seed is the same for every evaluation of a fit (common random numbers),
//! so the objective is a deterministic function of the parameters and the search does not
//! chase realisation noise.

use super::matched::{merge, Evaluator, Gaps, Target};
use super::space::{FitParam, FitSpace};
use super::SEGMENTS;
use serde::Serialize;
use wearsim_core::effects::Effects;

/// Pattern-search step below which a fit counts as converged (normalised coordinates).
pub const STEP_TOL: f64 = 1.0 / 128.0;
/// Objective evaluations allowed in the pattern search after the grid.
pub const MAX_SEARCH: usize = 240;

/// How far a fit may search: the pattern search stops at step `step_tol` (normalised
/// coordinates) or after `max_search` evaluations. The default suits records of seconds;
/// whole lives, each evaluation a life, use [`Budget::LIFE`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Budget {
    /// Step below which the fit counts as converged.
    pub step_tol: f64,
    /// Evaluations allowed after the grid.
    pub max_search: usize,
    /// Grid points per axis of a fit with two or more parameters (nine for one).
    pub axis: usize,
    /// A fit started from a hint searches from the hint alone, with no grid around it: a
    /// local refit of an effect whose optimum moves little (`gap::exchange`).
    pub local: bool,
}

impl Budget {
    /// For records of seconds: [`STEP_TOL`], [`MAX_SEARCH`].
    pub const DEFAULT: Budget = Budget {
        step_tol: STEP_TOL,
        max_search: MAX_SEARCH,
        axis: 5,
        local: false,
    };
    /// For whole lives: a step of 1/32 of the range (3 % of a decade on a log axis),
    /// 48 evaluations, 4 grid points per axis (64 lives for three parameters).
    pub const LIFE: Budget = Budget {
        step_tol: 1.0 / 32.0,
        max_search: 48,
        axis: 4,
        local: false,
    };
}

impl Default for Budget {
    fn default() -> Self {
        Budget::DEFAULT
    }
}

/// One fitted parameter with its uncertainty.
#[derive(Debug, Clone, Serialize)]
pub struct FittedParam {
    /// Catalogue name.
    pub name: String,
    /// Fitted value (catalogue unit).
    pub value: f64,
    /// One standard deviation (catalogue unit, linearised); `null` when the cells do not
    /// constrain the parameter (singular sensitivity).
    pub std: Option<f64>,
    /// Catalogue unit.
    pub unit: String,
    /// The optimum lies on the edge of the fitted range (whether or not the cells
    /// constrain the parameter: see [`FittedParam::constrained`]).
    pub at_bound: bool,
    /// The cells constrain the parameter: its normalised standard deviation is below
    /// [`CONSTRAINED`] of the fitted range. An unconstrained parameter on its edge says
    /// nothing about the range being too small.
    pub constrained: bool,
}

/// Normalised standard deviation (fraction of the fitted range) below which the cells
/// count as constraining a parameter.
pub const CONSTRAINED: f64 = 0.25;

impl FittedParam {
    /// The report of parameter `f` at normalised coordinate `u` with normalised standard
    /// deviation `s` (None: unconstrained). `at_bound` compares the coordinate with the
    /// ends of the range only: it used to require a constrained parameter too, so a
    /// parameter sitting exactly on its bound with a large std (load-zone `epsilon` =
    /// 1.0 on [0.2, 1], std 34) was reported `at_bound: false` (issue 13).
    pub fn new(f: &FitParam, u: f64, s: Option<f64>, unit: String) -> Self {
        FittedParam {
            name: f.name.to_string(),
            value: f.value(u),
            std: s.map(|s| s * f.slope(u)),
            unit,
            at_bound: u <= 1e-9 || u >= 1.0 - 1e-9,
            constrained: s.is_some_and(|s| s < CONSTRAINED),
        }
    }
}

/// The result of fitting one effect.
#[derive(Debug, Clone, Serialize)]
pub struct Fit {
    /// Effect name.
    pub effect: String,
    /// Fitted parameters.
    pub params: Vec<FittedParam>,
    /// Normalised coordinates of the optimum.
    #[serde(skip)]
    pub coords: Vec<f64>,
    /// Training total gap at the optimum.
    pub train_gap: f64,
    /// The pattern search reached its step tolerance within its budget.
    pub converged: bool,
    /// Objective evaluations (each simulates every training record once).
    pub evaluations: usize,
    /// Training cell gaps at the optimum (empty when the simulation was refused).
    #[serde(skip)]
    pub train_gaps: Gaps,
    /// Jacobian of the training cell gaps (already in units of each cell's measured
    /// spread) by the normalised coordinates at the optimum, one column per fitted
    /// parameter (finite differences, step 0.02; empty when not computable): the
    /// effect's signature subspace for the identifiability analysis
    /// ([`super::identify`]).
    #[serde(skip)]
    pub jacobian: Vec<Vec<f64>>,
}

impl Fit {
    /// The effect with its fitted values added to `fx`.
    pub fn effects(&self, space: &FitSpace, fx: &Effects) -> Effects {
        let mut out = *fx;
        let mut one = Effects::NONE;
        if space.apply(&mut one, &self.coords).is_ok() {
            merge(&mut out, &one);
        }
        out
    }
}

fn with(space: &FitSpace, base: &Effects, u: &[f64]) -> Option<Effects> {
    let mut one = Effects::NONE;
    space.apply(&mut one, u).ok()?;
    let mut fx = *base;
    merge(&mut fx, &one);
    Some(fx)
}

fn grid(p: usize, axis: usize) -> Vec<Vec<f64>> {
    match p {
        0 => vec![vec![]],
        1 => grid_k(1, 9),
        _ => grid_k(p, axis),
    }
}

/// `k` points per axis (k ≥ 2), every combination.
fn grid_k(p: usize, k: usize) -> Vec<Vec<f64>> {
    match p {
        0 => vec![vec![]],
        _ => {
            let k = k.max(2);
            let axis: Vec<f64> = (0..k).map(|i| i as f64 / (k - 1) as f64).collect();
            let mut out = vec![vec![]];
            for _ in 0..p {
                out = out
                    .into_iter()
                    .flat_map(|v: Vec<f64>| {
                        axis.iter().map(move |a| {
                            let mut w = v.clone();
                            w.push(*a);
                            w
                        })
                    })
                    .collect();
            }
            out
        }
    }
}

/// Fits `space` on `train`, on top of the effects `base` already switched on.
pub fn fit<T: Target>(space: &FitSpace, base: &Effects, train: &[T], ev: &Evaluator) -> Fit {
    fit_from(space, base, train, ev, None, Budget::DEFAULT)
}

/// [`fit`] started from a known optimum `hint` (normalised coordinates, e.g. the
/// effect's fit alone on the baseline, when it is refitted on top of other effects): the
/// coarse grid shrinks to three points per axis plus the hint, and the pattern search
/// refines as before. Multi-start instead of a fine grid: a greedy step refits every
/// remaining effect, and the grid is most of a fit's simulations.
pub fn fit_from<T: Target>(
    space: &FitSpace,
    base: &Effects,
    train: &[T],
    ev: &Evaluator,
    hint: Option<&[f64]>,
    budget: Budget,
) -> Fit {
    let mut fits = fit_many(&[Job { space, base, hint }], train, ev, budget);
    fits.pop().unwrap_or_else(|| Fit {
        effect: space.effect.to_string(),
        params: vec![],
        coords: vec![],
        train_gap: f64::INFINITY,
        converged: false,
        evaluations: 0,
        train_gaps: Gaps::default(),
        jacobian: vec![],
    })
}

/// One fit of [`fit_many`]: the effect's space, the effects already switched on beneath
/// it, and an optional start ([`fit_from`]'s `hint`).
#[derive(Clone, Copy)]
pub struct Job<'a> {
    /// The effect's fit space.
    pub space: &'a FitSpace,
    /// Effects already on.
    pub base: &'a Effects,
    /// Known optimum to start from (normalised coordinates).
    pub hint: Option<&'a [f64]>,
}

/// A pattern search in progress ([`fit_many`]).
struct Search {
    best_u: Vec<f64>,
    best: f64,
    step: f64,
    searched: usize,
    evaluations: usize,
}

impl Search {
    fn active(&self, p: usize, budget: &Budget) -> bool {
        p > 0 && self.step >= budget.step_tol && self.searched < budget.max_search
    }

    /// Poll ±step along every axis that stays inside [0, 1].
    fn polls(&self) -> Vec<Vec<f64>> {
        let p = self.best_u.len();
        let mut out = vec![];
        for i in 0..p {
            for s in [-1.0, 1.0] {
                let mut u = self.best_u.clone();
                let x = u.get(i).copied().unwrap_or(0.5) + s * self.step;
                if !(0.0..=1.0).contains(&x) {
                    continue;
                }
                if let Some(c) = u.get_mut(i) {
                    *c = x;
                }
                out.push(u);
            }
        }
        out
    }

    /// Moves to the best improving poll, or halves the step when none improves.
    fn update(&mut self, polls: &[Vec<f64>], v: &[f64]) {
        self.searched += polls.len();
        self.evaluations += polls.len();
        match polls
            .iter()
            .zip(v)
            .filter(|(_, v)| **v < self.best - 1e-9)
            .min_by(|a, b| a.1.total_cmp(b.1))
        {
            Some((u, v)) => {
                self.best_u = u.clone();
                self.best = *v;
            }
            None => self.step *= 0.5,
        }
    }
}

/// Several independent fits ([`fit_from`] each) run in lock step, so that every round's
/// evaluations of all of them — the grids, then each pattern-search poll, then the
/// finite differences — are simulated together ([`Evaluator::totals`], lanes where the
/// models allow it). Each fit's result is exactly what it gives alone: the fits do not
/// share any decision, only the batches.
pub fn fit_many<T: Target>(jobs: &[Job], train: &[T], ev: &Evaluator, budget: Budget) -> Vec<Fit> {
    let effects =
        |(j, u): &(usize, Vec<f64>)| jobs.get(*j).and_then(|job| with(job.space, job.base, u));
    // The objective at many (job, point) pairs at once: +∞ where the point is outside
    // the model's accepted configurations; `ahead`: points likely asked for next
    // (simulated where a lane is free, see `Evaluator::totals_ahead`).
    let objective = |pts: &[(usize, Vec<f64>)], ahead: &[(usize, Vec<f64>)]| -> Vec<f64> {
        let fxs: Vec<Option<Effects>> = pts.iter().map(effects).collect();
        let ok: Vec<Effects> = fxs.iter().flatten().copied().collect();
        let guesses: Vec<Effects> = ahead.iter().filter_map(effects).collect();
        let mut totals = ev.totals_ahead(train, &ok, &guesses).into_iter();
        fxs.iter()
            .map(|f| match f {
                Some(_) => totals.next().unwrap_or(f64::INFINITY),
                None => f64::INFINITY,
            })
            .collect()
    };
    // Coarse grids (or sparser ones around hints).
    let grids: Vec<Vec<Vec<f64>>> = jobs
        .iter()
        .map(|job| {
            let p = job.space.fitted.len();
            match job.hint.filter(|h| h.len() == p) {
                Some(h) if budget.local => vec![h.to_vec()],
                Some(h) => {
                    let mut v = grid_k(p, 3);
                    v.push(h.to_vec());
                    v
                }
                None => grid(p, budget.axis),
            }
        })
        .collect();
    let flat: Vec<(usize, Vec<f64>)> = grids
        .iter()
        .enumerate()
        .flat_map(|(j, g)| g.iter().map(move |u| (j, u.clone())))
        .collect();
    let mut vals = objective(&flat, &[]).into_iter();
    let mut searches: Vec<Search> = jobs
        .iter()
        .zip(&grids)
        .map(|(job, pts)| {
            let p = job.space.fitted.len();
            let v: Vec<f64> = vals.by_ref().take(pts.len()).collect();
            let (best_u, best) = pts
                .iter()
                .zip(&v)
                .min_by(|a, b| a.1.total_cmp(b.1))
                .map(|(u, v)| (u.clone(), *v))
                .unwrap_or((vec![0.5; p], f64::INFINITY));
            Search {
                best_u,
                best,
                step: if p == 1 { 1.0 / 16.0 } else { 1.0 / 8.0 },
                searched: 0,
                evaluations: pts.len(),
            }
        })
        .collect();
    // Pattern searches: every active fit's polls in one batch per round.
    loop {
        let rounds: Vec<(usize, Vec<Vec<f64>>)> = searches
            .iter()
            .enumerate()
            .filter(|(j, s)| {
                jobs.get(*j)
                    .is_some_and(|job| s.active(job.space.fitted.len(), &budget))
            })
            .map(|(j, s)| (j, s.polls()))
            .collect();
        if rounds.is_empty() {
            break;
        }
        let flat: Vec<(usize, Vec<f64>)> = rounds
            .iter()
            .flat_map(|(j, polls)| polls.iter().map(move |u| (*j, u.clone())))
            .collect();
        let mut v = objective(&flat, &guesses(&rounds, &searches, &budget)).into_iter();
        for (j, polls) in &rounds {
            let vj: Vec<f64> = v.by_ref().take(polls.len()).collect();
            if let Some(s) = searches.get_mut(*j) {
                s.update(polls, &vj);
            }
        }
    }
    // Local analyses at the optima, all finite differences in one batch.
    let pts: Vec<Vec<Vec<f64>>> = searches.iter().map(|s| local_points(&s.best_u)).collect();
    let fxs: Vec<Option<Effects>> = jobs
        .iter()
        .zip(&pts)
        .flat_map(|(job, ps)| ps.iter().map(move |u| with(job.space, job.base, u)))
        .collect();
    let ok: Vec<Effects> = fxs.iter().flatten().copied().collect();
    let mut many = ev.residuals_many(train, &ok).into_iter();
    let mut r = fxs
        .iter()
        .map(|f| f.and_then(|_| many.next().flatten()))
        .collect::<Vec<Option<Gaps>>>()
        .into_iter();
    jobs.iter()
        .zip(searches)
        .zip(&pts)
        .map(|((job, s), ps)| {
            let space = job.space;
            let p = space.fitted.len();
            let rj: Vec<Option<Gaps>> = r.by_ref().take(ps.len()).collect();
            let converged = p == 0 || (s.step < budget.step_tol && s.best.is_finite());
            let Local {
                stds,
                evaluations: extra,
                gaps: train_gaps,
                jacobian,
            } = uncertainty(&s.best_u, ps, &rj);
            let info = wearsim_core::effects::info(space.effect);
            let params = space
                .fitted
                .iter()
                .zip(&s.best_u)
                .zip(&stds)
                .map(|((f, u), sd)| {
                    let unit = info
                        .and_then(|i| i.params.iter().find(|q| q.name == f.name))
                        .map(|q| q.unit.to_string())
                        .unwrap_or_default();
                    FittedParam::new(f, *u, *sd, unit)
                })
                .collect();
            Fit {
                effect: space.effect.to_string(),
                params,
                coords: s.best_u,
                train_gap: s.best,
                converged,
                evaluations: s.evaluations + extra,
                train_gaps,
                jacobian,
            }
        })
        .collect()
}

/// Points the searches of `rounds` (job, polls) may ask for after this round, best guesses
/// first: for each search the polls after a round without improvement (half the step),
/// or the points of the local analysis where that ends the search; then the local
/// analysis at every search's current best. Only guesses: the searches' paths do not
/// depend on them.
fn guesses(
    rounds: &[(usize, Vec<Vec<f64>>)],
    searches: &[Search],
    budget: &Budget,
) -> Vec<(usize, Vec<f64>)> {
    let mut out = vec![];
    let mut later = vec![];
    for (j, _) in rounds {
        let Some(s) = searches.get(*j) else {
            continue;
        };
        let half = Search {
            best_u: s.best_u.clone(),
            best: s.best,
            step: s.step * 0.5,
            searched: s.searched,
            evaluations: 0,
        };
        let local = local_points(&s.best_u);
        if half.step >= budget.step_tol {
            out.extend(half.polls().into_iter().map(|u| (*j, u)));
            later.extend(local.into_iter().map(|u| (*j, u)));
        } else {
            out.extend(local.into_iter().map(|u| (*j, u)));
        }
    }
    out.extend(later);
    out
}

/// Finite-difference step of the local analysis (normalised coordinates).
const FD_STEP: f64 = 0.02;

/// The points of the local analysis at `u`: `u` itself, then `u ∓ FD_STEP` along each
/// axis (clamped to [0, 1]); none when nothing is fitted.
fn local_points(u: &[f64]) -> Vec<Vec<f64>> {
    if u.is_empty() {
        return vec![];
    }
    let mut pts = vec![u.to_vec()];
    for i in 0..u.len() {
        for s in [-FD_STEP, FD_STEP] {
            let mut w = u.to_vec();
            if let Some(c) = w.get_mut(i) {
                *c = (*c + s).clamp(0.0, 1.0);
            }
            pts.push(w);
        }
    }
    pts
}

/// The local analysis at an optimum.
struct Local {
    /// Standard deviation of each normalised coordinate (None: unconstrained).
    stds: Vec<Option<f64>>,
    /// Evaluations spent.
    evaluations: usize,
    /// Cell gaps at the optimum.
    gaps: Gaps,
    /// Jacobian columns (one per coordinate).
    jacobian: Vec<Vec<f64>>,
}

/// Standard deviation of each normalised coordinate at `u` (None: unconstrained), the
/// evaluations spent, the cell gaps at `u` and the Jacobian, from the cell gaps `r` at
/// the points `pts` of [`local_points`] (`None` where a simulation was refused).
fn uncertainty(u: &[f64], pts: &[Vec<f64>], r: &[Option<Gaps>]) -> Local {
    let p = u.len();
    let none = |n: usize, gaps: Gaps, jacobian: Vec<Vec<f64>>| Local {
        stds: vec![None; p],
        evaluations: n,
        gaps,
        jacobian,
    };
    if p == 0 {
        return none(0, Gaps::default(), vec![]);
    }
    let n = pts.len();
    let Some(Some(r0)) = r.first() else {
        return none(n, Gaps::default(), vec![]);
    };
    // Jacobian columns by central (or one-sided at a bound) differences.
    let mut jac: Vec<Vec<f64>> = vec![];
    for i in 0..p {
        let (Some(Some(lo)), Some(Some(hi)), Some(ulo), Some(uhi)) = (
            r.get(1 + 2 * i),
            r.get(2 + 2 * i),
            pts.get(1 + 2 * i).and_then(|w| w.get(i)),
            pts.get(2 + 2 * i).and_then(|w| w.get(i)),
        ) else {
            return none(n, r0.clone(), vec![]);
        };
        let du = uhi - ulo;
        if du <= 0.0 {
            return none(n, r0.clone(), vec![]);
        }
        jac.push(
            lo.gaps
                .iter()
                .zip(&hi.gaps)
                .map(|(a, b)| (b - a) / du)
                .collect(),
        );
    }
    // Weighted least squares (weights W = w² of the total gap) with every cell gap of
    // variance s² (the mean square residual, at least that of a gap between two
    // K-segment means): cov = s² (JᵀWJ)⁻¹ (JᵀW²J) (JᵀWJ)⁻¹.
    let m = r0.gaps.len().max(1);
    let s2 = (r0.gaps.iter().map(|x| x * x).sum::<f64>() / m as f64).max(2.0 / SEGMENTS as f64);
    let w2: Vec<f64> = r0.weights.iter().map(|w| w * w).collect();
    let gram = |pow: i32| -> Vec<Vec<f64>> {
        (0..p)
            .map(|i| {
                (0..p)
                    .map(|j| match (jac.get(i), jac.get(j)) {
                        (Some(x), Some(y)) => x
                            .iter()
                            .zip(y)
                            .zip(&w2)
                            .map(|((a, b), w)| a * b * w.powi(pow))
                            .sum(),
                        _ => 0.0,
                    })
                    .collect()
            })
            .collect()
    };
    let mut a = gram(1);
    let b = gram(2);
    let Some(inv) = invert(&mut a) else {
        return none(n, r0.clone(), jac);
    };
    let cov = mul(&mul(&inv, &b), &inv);
    Local {
        stds: (0..p)
            .map(|i| {
                cov.get(i)
                    .and_then(|row| row.get(i))
                    .filter(|d| d.is_finite() && **d > 0.0)
                    .map(|d| (s2 * d).sqrt())
            })
            .collect(),
        evaluations: n,
        gaps: r0.clone(),
        jacobian: jac,
    }
}

fn mul(a: &[Vec<f64>], b: &[Vec<f64>]) -> Vec<Vec<f64>> {
    a.iter()
        .map(|row| {
            (0..b.first().map_or(0, |r| r.len()))
                .map(|j| {
                    row.iter()
                        .zip(b)
                        .map(|(x, brow)| x * brow.get(j).copied().unwrap_or(0.0))
                        .sum()
                })
                .collect()
        })
        .collect()
}

/// Inverse of a small symmetric matrix by Gauss–Jordan with partial pivoting; `None` when
/// it is numerically singular (a parameter the cells do not see).
fn invert(a: &mut [Vec<f64>]) -> Option<Vec<Vec<f64>>> {
    let n = a.len();
    let scale = a
        .iter()
        .enumerate()
        .map(|(i, r)| r.get(i).copied().unwrap_or(0.0).abs())
        .fold(0.0, f64::max);
    if scale <= 0.0 {
        return None;
    }
    let mut inv: Vec<Vec<f64>> = (0..n)
        .map(|i| (0..n).map(|j| if i == j { 1.0 } else { 0.0 }).collect())
        .collect();
    for c in 0..n {
        let piv = (c..n).max_by(|&x, &y| {
            let vx = a
                .get(x)
                .and_then(|r| r.get(c))
                .copied()
                .unwrap_or(0.0)
                .abs();
            let vy = a
                .get(y)
                .and_then(|r| r.get(c))
                .copied()
                .unwrap_or(0.0)
                .abs();
            vx.total_cmp(&vy)
        })?;
        a.swap(c, piv);
        inv.swap(c, piv);
        let d = a.get(c).and_then(|r| r.get(c)).copied().unwrap_or(0.0);
        if d.abs() <= 1e-10 * scale {
            return None;
        }
        let (ra, ri) = (a.get(c)?.clone(), inv.get(c)?.clone());
        for r in 0..n {
            let f = a.get(r).and_then(|row| row.get(c)).copied().unwrap_or(0.0) / d;
            let (Some(row_a), Some(row_i)) = (a.get_mut(r), inv.get_mut(r)) else {
                continue;
            };
            if r == c {
                row_a.iter_mut().for_each(|x| *x /= d);
                row_i.iter_mut().for_each(|x| *x /= d);
            } else {
                row_a.iter_mut().zip(&ra).for_each(|(x, y)| *x -= f * y);
                row_i.iter_mut().zip(&ri).for_each(|(x, y)| *x -= f * y);
            }
        }
    }
    Some(inv)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gap::space::{spaces, Context};
    use std::sync::atomic::AtomicUsize;

    /// A target whose cells are a smooth bowl in every fitted coordinate of `spaces`
    /// (minimum at `0.3 + 0.1 i` for the i-th, with a cross term), so that fits need no
    /// simulation.
    struct Bowl(Vec<FitSpace>);

    impl Target for Bowl {
        fn gaps(&self, fx: &Effects, _: &AtomicUsize) -> Result<(Vec<f64>, Vec<f64>), String> {
            let mut g = vec![];
            for s in &self.0 {
                let Some(vals) = fx.get(s.kind) else {
                    continue;
                };
                let spec = s.kind.spec();
                let us: Vec<f64> = s
                    .fitted
                    .iter()
                    .map(|f| {
                        let i = spec
                            .params
                            .iter()
                            .position(|q| q.name == f.name)
                            .unwrap_or(0);
                        f.coord(vals[i])
                    })
                    .collect();
                for (i, u) in us.iter().enumerate() {
                    g.push(3.0 * (u - 0.3 - 0.1 * i as f64) + us.iter().sum::<f64>().powi(2));
                }
            }
            g.push(0.5);
            let w = vec![1.0 / (g.len() as f64).sqrt(); g.len()];
            Ok((g, w))
        }
    }

    /// Fits in lock step give each fit's result alone: coordinates, objective,
    /// evaluations, standard deviations (a batch split off by one value fails this).
    #[test]
    fn fits_in_lock_step_equal_fits_alone() {
        let ctx = Context {
            fs: 12_000.0,
            shaft_hz: 29.95,
            rms: 1.0,
            mains_hz: 60.0,
            preload_max: crate::gap::space::CATALOGUE_PRELOAD_MAX,
        };
        let all: Vec<FitSpace> = spaces(&ctx)
            .into_iter()
            .filter(|s| !s.fitted.is_empty())
            .take(4)
            .collect();
        assert!(all.len() >= 3 && all.iter().any(|s| s.fitted.len() >= 2));
        let train = [Bowl(all.clone())];
        let ev = Evaluator::new(1);
        let base = Effects::NONE;
        let hint = [0.9, 0.1, 0.5];
        let jobs: Vec<Job> = all
            .iter()
            .enumerate()
            .map(|(i, space)| Job {
                space,
                base: &base,
                hint: (i == 1).then(|| &hint[..space.fitted.len().min(3)]),
            })
            .collect();
        let together = fit_many(&jobs, &train, &ev, Budget::DEFAULT);
        assert_eq!(together.len(), jobs.len());
        for (job, t) in jobs.iter().zip(&together) {
            let alone = fit_from(job.space, job.base, &train, &ev, job.hint, Budget::DEFAULT);
            assert_eq!(t.coords, alone.coords, "{}", t.effect);
            assert_eq!(t.train_gap, alone.train_gap);
            assert_eq!(t.evaluations, alone.evaluations);
            assert_eq!(t.converged, alone.converged);
            let sd = |f: &Fit| f.params.iter().map(|p| p.std).collect::<Vec<_>>();
            assert_eq!(sd(t), sd(&alone));
            assert!(t.converged && t.train_gap.is_finite(), "{}", t.effect);
        }
    }

    /// Issue 13: load-zone `epsilon` fitted to 1.0 on [0.2, 1] with std 34 was reported
    /// `at_bound: false` because the edge flag also required a constrained parameter.
    #[test]
    fn a_parameter_on_its_bound_is_at_bound_even_unconstrained() {
        let f = FitParam {
            name: "epsilon",
            lo: 0.2,
            hi: 1.0,
            log: false,
        };
        let p = FittedParam::new(&f, 1.0, Some(34.0 / 0.8), String::new());
        assert_eq!(p.value, 1.0);
        assert!(p.at_bound, "epsilon = 1.0 on [0.2, 1] must be at its bound");
        assert!(!p.constrained);
        assert!((p.std.unwrap_or(0.0) - 34.0).abs() < 1e-9);
        let lo = FittedParam::new(&f, 0.0, None, String::new());
        assert!(lo.at_bound && !lo.constrained);
        let mid = FittedParam::new(&f, 0.5, Some(0.05), String::new());
        assert!(!mid.at_bound && mid.constrained);
        let near = FittedParam::new(&f, 1.0 - 1.0 / 128.0, Some(0.01), String::new());
        assert!(!near.at_bound);
    }
}
