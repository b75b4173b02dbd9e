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
use wearsim_core::{Model, ModelConfig, Sample, State};

/// Settling time simulated and discarded before a matched record (s): the structure's
/// transient and the effects' filters (transfer-path modes at 5 % damping decay by e⁻¹⁰
/// within 0.1 s above 300 Hz) are gone.
pub const SETTLE_S: f64 = 0.1;

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
    /// simulated (so that a changed baseline cannot hit a stale entry).
    pub memo: Memo<(ModelConfig, u64, usize), Vec<f64>>,
}

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
        let model = Model::new_checked(self.config(fx)).map_err(|e| e.to_string())?;
        let fs = model.config().output_rate;
        let mut st: State<{ crate::simulate::CAPACITY }> =
            State::new(&model, self.seed).map_err(|e| e.to_string())?;
        let mut buf = vec![Sample::default(); ((SETTLE_S * fs) as usize).max(1)];
        model.fill(&mut st, &mut buf);
        buf.resize(self.samples, Sample::default());
        model.fill(&mut st, &mut buf);
        let x: Vec<f64> = buf.iter().map(|s| s.accel).collect();
        if x.iter().any(|v| !v.is_finite()) {
            return Err("the model produced a non-finite sample".into());
        }
        Ok(x)
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

    /// The spec the cells use.
    pub fn spec(&self) -> &CellSpec {
        &self.reference.spec
    }
}

/// A measured record that the attribution can hold simulations against: a stretch of a
/// stationary record ([`Matched`]) or a whole measured life
/// ([`super::lifetime::LifeTarget`]). Fits, ranking, greedy addition and leave-one-out
/// only see these gaps, so they work the same on both.
pub trait Target: Sync {
    /// Normalised cell gaps `(sim − real)/spread` with effects `fx` added to the matched
    /// baseline, and each cell's weight in the record's total gap (Σ w² = 1). Every
    /// simulation actually run adds one to `sims`.
    fn gaps(&self, fx: &Effects, sims: &AtomicUsize) -> Result<(Vec<f64>, Vec<f64>), String>;
}

impl Target for Matched {
    fn gaps(&self, fx: &Effects, sims: &AtomicUsize) -> Result<(Vec<f64>, Vec<f64>), String> {
        let c = self.sim_cells(fx, sims)?;
        Ok((self.reference.residuals(&c), self.reference.weight.clone()))
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
                    s.spawn(move || c.iter().map(f).collect::<Vec<R>>())
                })
                .collect();
            handles
                .into_iter()
                .flat_map(|h| h.join().unwrap_or_else(|e| std::panic::resume_unwind(e)))
                .collect()
        })
    }
}
