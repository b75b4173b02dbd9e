//! Matched simulations (sim-to-real.md, "Terms"): a measured stretch together with the
//! baseline configuration that has its metadata (bearing, speed, sample rate, duration,
//! defect), and the evaluator that simulates it with a set of candidate effects and
//! returns the cell gaps. The evaluator counts every simulation it runs, so a report can
//! say how many were needed and how long they took.

use super::memo::Memo;
use super::{CellSpec, Reference};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use wearsim_core::effects::{EffectKind, Effects};
use wearsim_core::ModelConfig;

pub use super::run::SETTLE_S;

/// One measured stretch and its matched baseline.
#[derive(Debug, Clone)]
pub struct Matched {
    /// What it is (file name and part), for reports.
    pub label: String,
    /// Matched baseline configuration (effects as the baseline has them).
    pub base: ModelConfig,
    /// Measured cells (mean and spread over segments).
    pub reference: Reference,
    /// Samples of the measured stretch (the simulation has as many).
    pub samples: usize,
    /// Seed of the matched simulation (fixed: common random numbers across a fit).
    pub seed: u64,
    /// The measured samples (m/s²), kept for the report's plots (may be empty).
    pub real: Vec<f64>,
    /// Simulated cell means already computed, by the full configuration, seed and length
    /// simulated (so that a changed baseline cannot hit a stale entry); and samples
    /// simulated ahead of need ([`Matched::sim_cells_ahead`]).
    pub memo: Memo<(ModelConfig, u64, usize), Vec<f64>, Vec<f64>>,
}

/// Most samples (all records together) a [`Matched`] keeps of simulations run ahead of
/// need (32 MiB).
pub const AHEAD_SAMPLES: usize = 1 << 22;

/// Most simulations a [`Matched`] remembers (a few hundred bytes each): a fit's grid and
/// search, and the greedy steps' refits, stay within it.
pub const MEMO: usize = 4096;

impl Matched {
    /// The baseline configuration with effects `fx` added.
    fn config(&self, fx: &Effects) -> ModelConfig {
        let mut cfg = self.base.clone();
        merge(&mut cfg.effects, fx);
        cfg
    }

    /// Simulates the matched record with effects `fx` added to the baseline's.
    pub fn simulate(&self, fx: &Effects) -> Result<Vec<f64>, String> {
        super::run::simulate(&self.config(fx), self.seed, self.samples)
    }

    /// Mean simulated cell values with effects `fx`, from the memo when this
    /// configuration was simulated before; `sims` counts the simulations actually run.
    pub fn sim_cells(&self, fx: &Effects, sims: &AtomicUsize) -> Result<Arc<Vec<f64>>, String> {
        let key = (self.config(fx), self.seed, self.samples);
        self.memo.get_or_run(&key, sims, || {
            let x = self.simulate(fx)?;
            self.reference.sim_means(&x).map_err(|e| e.to_string())
        })
    }

    /// [`Matched::sim_cells`] for several effect sets `fxs`, through
    /// [`Matched::sim_cells_ahead`]: those the memo lacks are simulated together (lanes
    /// where the models allow it), each distinct configuration once, and counted in `sims`;
    /// also the guesses `ahead` (effect sets likely asked for next, best first) in lanes
    /// that would otherwise be padding.
    pub fn sim_cells_many_ahead(
        &self,
        fxs: &[Effects],
        ahead: &[Effects],
        sims: &AtomicUsize,
    ) -> Vec<Result<Arc<Vec<f64>>, String>> {
        let cfgs: Vec<ModelConfig> = fxs.iter().map(|fx| self.config(fx)).collect();
        let guesses: Vec<ModelConfig> = ahead.iter().map(|fx| self.config(fx)).collect();
        self.sim_cells_ahead(&cfgs, &guesses, sims)
    }

    /// Mean simulated cell values of this record's stretch for whole configurations
    /// `cfgs` (effect sets made whole, or another baseline, as the rig's calibration tries:
    /// `gap::nuisance`), through the memo; those it lacks are simulated together, in lanes
    /// where the models allow it, each distinct configuration once, and counted in `sims`.
    /// Also simulates those of the configurations
    /// `ahead` (guesses, best first) that fit into lanes the groups would otherwise pad
    /// ([`super::run::simulate_ahead`]): their samples are kept in the memo, uncounted,
    /// and a later call that asks for one takes them instead of simulating it, and counts
    /// it then. Results and counts are the same as without guesses.
    pub fn sim_cells_ahead(
        &self,
        cfgs: &[ModelConfig],
        ahead: &[ModelConfig],
        sims: &AtomicUsize,
    ) -> Vec<Result<Arc<Vec<f64>>, String>> {
        let key = |c: &ModelConfig| (c.clone(), self.seed, self.samples);
        let keys: Vec<(ModelConfig, u64, usize)> = cfgs.iter().map(key).collect();
        let mut todo: Vec<usize> = vec![];
        for (i, k) in keys.iter().enumerate() {
            if self.memo.get(k).is_none() && !todo.iter().any(|&j| keys[j] == *k) {
                todo.push(i);
            }
        }
        // Those simulated ahead are taken; the rest run, with the new guesses.
        let mut got: Vec<Option<Result<Vec<f64>, String>>> = todo
            .iter()
            .map(|&i| self.memo.take_ahead(&keys[i]).map(Ok))
            .collect();
        let run: Vec<usize> = (0..todo.len()).filter(|&t| got[t].is_none()).collect();
        let run_cfgs: Vec<ModelConfig> = run.iter().map(|&t| keys[todo[t]].0.clone()).collect();
        let mut guesses: Vec<(ModelConfig, u64, usize)> = vec![];
        if !run.is_empty() {
            for g in ahead.iter().map(key) {
                if !keys.contains(&g)
                    && !guesses.contains(&g)
                    && self.memo.get(&g).is_none()
                    && !self.memo.has_ahead(&g)
                {
                    guesses.push(g);
                }
            }
        }
        let guess_cfgs: Vec<ModelConfig> = guesses.iter().map(|g| g.0.clone()).collect();
        let (runs, extra) =
            super::run::simulate_ahead(&run_cfgs, &guess_cfgs, self.seed, self.samples);
        for (&t, x) in run.iter().zip(runs) {
            got[t] = Some(x);
        }
        let max = AHEAD_SAMPLES / self.samples.max(1);
        for (g, x) in guesses.into_iter().zip(extra) {
            if let Some(x) = x {
                self.memo.put_ahead(g, x, max);
            }
        }
        let mut errors: Vec<(usize, String)> = vec![];
        for (&i, x) in todo.iter().zip(got) {
            sims.fetch_add(1, Ordering::Relaxed);
            let x = x.unwrap_or_else(|| Err("not simulated".into()));
            match x.and_then(|x| self.reference.sim_means(&x).map_err(|e| e.to_string())) {
                Ok(c) => self.memo.insert(keys[i].clone(), Arc::new(c)),
                Err(e) => errors.push((i, e)),
            }
        }
        keys.iter()
            .map(|k| match self.memo.get(k) {
                Some(c) => Ok(c),
                None => Err(errors
                    .iter()
                    .find(|(j, _)| keys[*j] == *k)
                    .map_or_else(|| "not simulated".to_string(), |(_, e)| e.clone())),
            })
            .collect()
    }

    /// The spec the cells use.
    pub fn spec(&self) -> &CellSpec {
        &self.reference.spec
    }
}

/// Normalised cell gaps and their weights, or why they could not be computed.
pub type GapsResult = Result<(Vec<f64>, Vec<f64>), String>;

/// A measured record that the attribution can hold simulations against: a stretch of a
/// stationary record ([`Matched`]) or a whole measured life
/// ([`super::lifetime::LifeTarget`]). Fits, ranking, greedy addition and leave-one-out
/// only see these gaps, so they work the same on both.
pub trait Target: Sync {
    /// Normalised cell gaps `(sim − real)/spread` with effects `fx` added to the matched
    /// baseline, and each cell's weight in the record's total gap (Σ w² = 1). Every
    /// simulation actually run adds one to `sims`.
    fn gaps(&self, fx: &Effects, sims: &AtomicUsize) -> Result<(Vec<f64>, Vec<f64>), String>;

    /// [`Target::gaps`] for several effect sets, in order; a target that can simulate
    /// several at once (lanes) overrides it.
    fn gaps_many(&self, fxs: &[Effects], sims: &AtomicUsize) -> Vec<GapsResult> {
        fxs.iter().map(|fx| self.gaps(fx, sims)).collect()
    }

    /// [`Target::gaps_many`], with guesses `ahead` (effect sets likely asked for next,
    /// best first) that a target may simulate now where that costs nothing extra (lanes
    /// that would be padding), without counting them until they are asked for. The
    /// results and counts are those of [`Target::gaps_many`].
    fn gaps_ahead(
        &self,
        fxs: &[Effects],
        ahead: &[Effects],
        sims: &AtomicUsize,
    ) -> Vec<GapsResult> {
        let _ = ahead;
        self.gaps_many(fxs, sims)
    }
}

impl Target for Matched {
    fn gaps(&self, fx: &Effects, sims: &AtomicUsize) -> Result<(Vec<f64>, Vec<f64>), String> {
        let c = self.sim_cells(fx, sims)?;
        Ok((self.reference.residuals(&c), self.reference.weight.clone()))
    }

    fn gaps_many(&self, fxs: &[Effects], sims: &AtomicUsize) -> Vec<GapsResult> {
        self.gaps_ahead(fxs, &[], sims)
    }

    fn gaps_ahead(
        &self,
        fxs: &[Effects],
        ahead: &[Effects],
        sims: &AtomicUsize,
    ) -> Vec<GapsResult> {
        self.sim_cells_many_ahead(fxs, ahead, sims)
            .into_iter()
            .map(|c| c.map(|c| (self.reference.residuals(&c), self.reference.weight.clone())))
            .collect()
    }
}

/// Switches on in `into` every effect that is on in `add` (the added one wins).
pub fn merge(into: &mut Effects, add: &Effects) {
    for k in EffectKind::ALL {
        if add.is_on(k) {
            into.take(add, k);
        }
    }
}

/// Cell gaps of a set of records, concatenated in record and cell order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Gaps {
    /// `(sim − real)/spread` of every cell.
    pub gaps: Vec<f64>,
    /// Each cell's weight in its record's total ([`super::Reference::weight`]).
    pub weights: Vec<f64>,
    /// Records.
    pub records: usize,
}

impl Gaps {
    /// Total gap over the records: root mean square over records of each record's
    /// [`super::total_weighted`].
    pub fn total(&self) -> f64 {
        let s: f64 = self
            .gaps
            .iter()
            .zip(&self.weights)
            .map(|(g, w)| (g * w) * (g * w))
            .sum();
        (s / self.records.max(1) as f64).sqrt()
    }
}

/// `fx` with effect `name` switched off; an unknown name is an error.
pub fn without(fx: &Effects, name: &str) -> Result<Effects, String> {
    let mut out = *fx;
    out.clear(crate::effects::kind(name)?);
    Ok(out)
}

/// Runs simulations against sets of matched records and counts them.
#[derive(Debug, Default)]
pub struct Evaluator {
    sims: AtomicUsize,
    /// Worker threads for independent evaluations (1 = sequential).
    pub jobs: usize,
}

impl Evaluator {
    /// An evaluator using `jobs` threads (at least 1).
    pub fn new(jobs: usize) -> Self {
        Evaluator {
            sims: AtomicUsize::new(0),
            jobs: jobs.max(1),
        }
    }

    /// Simulations run so far.
    pub fn sims(&self) -> usize {
        self.sims.load(Ordering::Relaxed)
    }

    /// The counter itself, for simulations run outside [`Evaluator::residuals`] (a
    /// baseline life simulated to scale the fit spaces).
    pub fn counter(&self) -> &AtomicUsize {
        &self.sims
    }

    /// Cell gaps of every record in `set` with effects `fx`.
    pub fn residuals<T: Target>(&self, set: &[T], fx: &Effects) -> Result<Gaps, String> {
        let mut out = Gaps::default();
        for m in set {
            let (g, w) = m.gaps(fx, &self.sims)?;
            out.gaps.extend(g);
            out.weights.extend(w);
            out.records += 1;
        }
        Ok(out)
    }

    /// Total gap of `set` with effects `fx`; +∞ when the simulation is rejected (a
    /// parameter combination the model refuses).
    pub fn total<T: Target>(&self, set: &[T], fx: &Effects) -> f64 {
        self.residuals(set, fx)
            .map(|r| r.total())
            .unwrap_or(f64::INFINITY)
    }

    /// [`Evaluator::residuals`] of `set` for every effect set of `fxs` (`None` where a
    /// simulation is rejected): the sets are split over up to `jobs` threads, and each
    /// thread's share is simulated together per record ([`Target::gaps_many`]).
    pub fn residuals_many<T: Target>(&self, set: &[T], fxs: &[Effects]) -> Vec<Option<Gaps>> {
        self.residuals_ahead(set, fxs, &[])
    }

    /// [`Evaluator::residuals_many`] with guesses `ahead` at the next effect sets
    /// ([`Target::gaps_ahead`]): the same results and counts.
    pub fn residuals_ahead<T: Target>(
        &self,
        set: &[T],
        fxs: &[Effects],
        ahead: &[Effects],
    ) -> Vec<Option<Gaps>> {
        let chunks: Vec<&[Effects]> = fxs.chunks(fxs.len().div_ceil(self.jobs).max(1)).collect();
        self.map(&chunks, |chunk| {
            let mut acc: Vec<Option<Gaps>> = vec![Some(Gaps::default()); chunk.len()];
            for m in set {
                for (a, r) in acc.iter_mut().zip(m.gaps_ahead(chunk, ahead, &self.sims)) {
                    match (a.as_mut(), r) {
                        (Some(g), Ok((gaps, w))) => {
                            g.gaps.extend(gaps);
                            g.weights.extend(w);
                            g.records += 1;
                        }
                        _ => *a = None,
                    }
                }
            }
            acc
        })
        .into_iter()
        .flatten()
        .collect()
    }

    /// [`Evaluator::total`] for every effect set of `fxs` (+∞ where a simulation is
    /// rejected), through [`Evaluator::residuals_many`].
    pub fn totals<T: Target>(&self, set: &[T], fxs: &[Effects]) -> Vec<f64> {
        self.totals_ahead(set, fxs, &[])
    }

    /// [`Evaluator::totals`] with guesses `ahead` ([`Evaluator::residuals_ahead`]).
    pub fn totals_ahead<T: Target>(
        &self,
        set: &[T],
        fxs: &[Effects],
        ahead: &[Effects],
    ) -> Vec<f64> {
        self.residuals_ahead(set, fxs, ahead)
            .into_iter()
            .map(|g| g.map_or(f64::INFINITY, |g| g.total()))
            .collect()
    }

    /// `f` applied to every item, on up to `jobs` threads, results in input order.
    pub fn map<T: Sync, R: Send>(&self, items: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
        if self.jobs <= 1 || items.len() <= 1 {
            return items.iter().map(&f).collect();
        }
        let chunk = items.len().div_ceil(self.jobs);
        std::thread::scope(|s| {
            let handles: Vec<_> = items
                .chunks(chunk)
                .map(|c| {
                    let f = &f;
                    let h = crate::lanes::spawn_worker(s, move || c.iter().map(f).collect());
                    (c, h)
                })
                .collect();
            handles
                .into_iter()
                .flat_map(|(c, h)| match h {
                    Ok(h) => h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)),
                    // No thread could start for this chunk: it runs here.
                    Err(_) => c.iter().map(&f).collect::<Vec<R>>(),
                })
                .collect()
        })
    }
}
