//! Twin experiments (sim-to-real.md, "Checked on data whose effect is withheld"): a
//! "measured" record is simulated with one (or two) candidate effects switched on at
//! random parameter values, plus white measurement noise and a different random
//! realisation; the diagnosis starts from the baseline, which lacks them, fits on the
//! first half of the record and judges on the second. Over many trials per effect this
//! gives the top-1 identification rate, the confusion matrix, and the held-out shrink
//! relative to the noise-only gap (the baseline against a twin with no effect at all).

pub use super::attribute::{same_class, INDISTINGUISHABLE};

use super::attribute::{attribute, Options};
use super::matched::{merge, Evaluator, Matched, MEMO};
use super::memo::Memo;
use super::space::{self, FitSpace};
use super::{CellSpec, Reference};
use crate::analysis::stats::{self, rms};
use crate::analysis::FaultFamily;
use serde::Serialize;
use std::time::Instant;
use wearsim_core::effects::Effects;
use wearsim_core::forces::defect::{DefectConfig, DefectLocation, DefectModel};
use wearsim_core::rng::Xoshiro128pp;
use wearsim_core::{presets, topography::Topography, Model, ModelConfig};

/// Twin-experiment settings.
#[derive(Debug, Clone)]
pub struct TwinOptions {
    /// Trials per effect.
    pub trials: usize,
    /// Effects withheld (one per trial); empty = every catalogue effect that acts on the
    /// scenario.
    pub effects: Vec<String>,
    /// Also run trials with two effects withheld at once (this many).
    pub pair_trials: usize,
    /// Also diagnose this many twins with no effect withheld (noise floor only): the
    /// false-attribution rate.
    pub null_trials: usize,
    /// Seed of the parameter draws and realisations.
    pub seed: u64,
    /// Length of each half (training, held-out) of a twin record (s).
    pub half_s: f64,
    /// White measurement noise, as a fraction of the twin record's RMS.
    pub noise: f64,
    /// Worker threads.
    pub jobs: usize,
}

impl Default for TwinOptions {
    fn default() -> Self {
        TwinOptions {
            trials: 20,
            effects: vec![],
            pair_trials: 0,
            null_trials: 0,
            seed: 1,
            half_s: 1.0,
            noise: 0.01,
            jobs: std::thread::available_parallelism().map_or(1, |n| n.get()),
        }
    }
}

/// One trial.
#[derive(Debug, Clone, Serialize)]
pub struct Trial {
    /// Effects withheld (switched on in the "measured" twin).
    pub withheld: Vec<String>,
    /// Their parameter values (catalogue units).
    pub params: Vec<Vec<(String, f64)>>,
    /// The effect the diagnosis ranked first (none: no effect shrank the gap).
    pub ranked_first: Option<String>,
    /// The reported set: the first-ranked effect and those confounded with it
    /// ([`super::identify`]); empty when none shrank the gap.
    pub reported_set: Vec<String>,
    /// Parameters of the first-ranked effect as fitted.
    pub fitted: Vec<super::fit::FittedParam>,
    /// Held-out total gap of the baseline.
    pub before: f64,
    /// Held-out total gap with the first-ranked effect added.
    pub after: f64,
    /// Held-out total gap of the exactly right model (the withheld effects at their true
    /// parameters, another realisation): what remains from noise alone in this trial.
    pub oracle: f64,
    /// Simulations this trial ran.
    pub simulations: usize,
    /// Parameter draws rejected before this one because the baseline's held-out gap to
    /// the twin was below [`DETECTABLE`] × the noise-only gap (within the measurement's
    /// own variability: nothing to identify).
    pub redraws: usize,
}

/// A twin counts only when the baseline's held-out gap to it is at least this multiple
/// of the noise-only gap ([`TwinReport::noise_only_gap`]); weaker draws are redrawn (at
/// most [`MAX_REDRAWS`] times) and counted, so that the identification rate is measured on
/// effects the cells can see at all, and how often a random level could not be seen is
/// reported rather than hidden.
pub const DETECTABLE: f64 = 2.0;

/// Redraws allowed per trial before the last draw is kept however weak.
pub const MAX_REDRAWS: usize = 20;

/// Per-effect summary.
#[derive(Debug, Clone, Serialize)]
pub struct EffectRate {
    /// Effect withheld.
    pub effect: String,
    /// Trials.
    pub trials: usize,
    /// Trials in which it was ranked first.
    pub top1: usize,
    /// `top1 / trials`.
    pub rate: f64,
    /// Trials in which the first-ranked effect was it or one it cannot be told apart from.
    pub top1_class: usize,
    /// Median over trials of the held-out total gap after adding the first-ranked
    /// effect, divided by the trial's noise-only gap ([`Trial::oracle`]).
    pub median_after_over_noise: f64,
    /// Median held-out shrink of the total gap.
    pub median_shrink: f64,
    /// Parameter draws rejected as undetectable over all its trials ([`Trial::redraws`]).
    pub redraws: usize,
    /// Trials whose reported set (first-ranked effect and its confounded set) holds it.
    pub in_set: usize,
    /// Mean size of the reported set over its trials (0 when nothing was named).
    pub mean_set_size: f64,
}

/// The result of `gap-validate`.
#[derive(Debug, Clone, Serialize)]
pub struct TwinReport {
    /// Scenario the twins are built on.
    pub scenario: String,
    /// Held-out total gap of the baseline against twins without any withheld effect
    /// (median over trials): the floor of the gap measure itself.
    pub noise_only_gap: f64,
    /// Per-effect identification.
    pub rates: Vec<EffectRate>,
    /// Confusion matrix: `confusion[i][j]` = trials withholding `labels[i]` whose first
    /// ranked effect was `labels[j]` (last column: none).
    pub confusion: Vec<Vec<usize>>,
    /// Row labels of the confusion matrix (effects withheld).
    pub labels: Vec<String>,
    /// Column labels (effects ranked first, and `none`).
    pub columns: Vec<String>,
    /// Pairs the cells cannot tell apart, with the reason.
    pub indistinguishable: Vec<(String, String, String)>,
    /// Two-effect trials: fraction whose first-ranked effect is one of the two withheld,
    /// and fraction whose two greedy additions are exactly the two.
    pub pairs: Option<(usize, f64, f64)>,
    /// No-effect twins: trials, and how many the diagnosis attributed to an effect
    /// (the false-attribution rate is their ratio).
    pub null: Option<(usize, usize)>,
    /// Every trial.
    pub trials: Vec<Trial>,
    /// Simulations run.
    pub simulations: usize,
    /// Wall-clock time (s).
    pub seconds: f64,
}

/// The twin scenario: the CWRU drive-end bearing (cwru-6205-de) with a 0.007 in inner-race
/// defect (EDM seeded, 0.011 in deep) at 1797 rpm, 12 kHz — the inner race so that every
/// candidate effect, the load zone included, has something to act on.
pub fn scenario() -> Option<ModelConfig> {
    let mut cfg = presets::by_name("cwru-6205-de")?;
    let inch = 0.0254;
    cfg.defect = Some(DefectConfig {
        location: DefectLocation::InnerRace { angle: 0.0 },
        model: DefectModel::FiveStep,
        topography: Topography {
            asperity_height: 5e-6,
            length: 0.007 * inch,
            width: 0.007 * inch,
            depth: 0.011 * inch,
            count: 1,
            debris: 0.0,
        },
        sassi_k_impact: 0.0,
    });
    Some(cfg)
}

/// Cell spec of a model at its configured speed.
pub fn spec_of(cfg: &ModelConfig) -> Result<CellSpec, String> {
    let model = Model::new_checked(cfg.clone()).map_err(|e| e.to_string())?;
    let family = match cfg.defect.map(|d| d.location) {
        Some(DefectLocation::InnerRace { .. }) => FaultFamily::InnerRace,
        Some(DefectLocation::Ball { .. }) => FaultFamily::Ball,
        _ => FaultFamily::OuterRace,
    };
    Ok(CellSpec {
        fs: cfg.output_rate,
        ff: model.frequencies_at(cfg.speed.shaft_hz(0.0)),
        family,
    })
}

/// Simulates `cfg` for `samples` after the settling time.
pub fn record(cfg: &ModelConfig, seed: u64, samples: usize) -> Result<Vec<f64>, String> {
    let m = Matched {
        label: String::new(),
        base: cfg.clone(),
        reference: Reference {
            names: vec![],
            mean: vec![],
            spread: vec![],
            weight: vec![],
            spec: spec_of(cfg)?,
        },
        samples,
        seed,
        real: vec![],
        memo: Memo::new(MEMO),
    };
    m.simulate(&Effects::NONE)
}

/// Normalised coordinates drawn for a twin: the part of each fitted range that differs
/// detectably from the baseline (the lower ends of slip, jitter, noise, hum and shaft
/// harmonics, a roughness scale near 1 and an edge shape near the baseline's are the
/// baseline within the measurement's variability, and would test nothing).
fn draw(space: &FitSpace, rng: &mut Xoshiro128pp) -> Vec<f64> {
    #[allow(clippy::unnecessary_cast)] // Real is f32 in `f32` builds
    let mut u01 = || 0.5 * (rng.uniform_pm1() as f64 + 1.0);
    space
        .fitted
        .iter()
        .map(|p| {
            let (lo, hi) = match (space.effect, p.name) {
                ("load-zone", "depth") => (0.6, 1.0),
                ("load-zone", "epsilon") => (0.0, 0.6),
                // Half the twins narrow the zone only, half also preload it (the
                // coordinate is clamped at 0 below the range).
                ("load-zone", "preload") => (-0.5, 0.5),
                ("roughness", _) => (0.65, 1.0),
                ("running-in", _) => (0.5, 1.0),
                ("edge-shape", "length_scale") => (0.0, 0.3),
                ("edge-shape", "asperity_scale") => (0.4, 1.0),
                ("sensor", "hum") => (0.3, 1.0),
                ("transfer-path", "path_gain") => (0.2, 0.9),
                ("slip", _) => (0.55, 1.0),
                ("speed-fluctuation", _) => (0.65, 1.0),
                _ => (0.4, 1.0),
            };
            lo + (hi - lo) * u01()
        })
        .collect()
}

/// Median of the finite values (NaN when there is none: reported as such).
fn median(v: Vec<f64>) -> f64 {
    stats::median(v).unwrap_or(f64::NAN)
}

struct TwinSetup {
    base: ModelConfig,
    spec: CellSpec,
    half: usize,
    /// The measurement noise floor every twin has and the diagnosis knows (instrument
    /// specification): the `sensor` effect with white noise only.
    floor: Effects,
}

impl TwinSetup {
    /// A twin record with effects `fx`, split into matched training and held-out halves.
    fn halves(&self, fx: &Effects, seed: u64) -> Result<(Matched, Matched), String> {
        let mut cfg = self.base.clone();
        cfg.effects = self.floor;
        merge(&mut cfg.effects, fx);
        let x = record(
            &cfg,
            seed.wrapping_mul(7919).wrapping_add(13),
            2 * self.half,
        )?;
        let (a, b) = x.split_at(self.half);
        let m = |part: &[f64], k: u64, label: &str| -> Result<Matched, String> {
            Ok(Matched {
                label: label.to_string(),
                base: self.base.clone(),
                reference: Reference::new(part, &self.spec).map_err(|e| e.to_string())?,
                samples: part.len(),
                seed: seed.wrapping_add(k),
                real: vec![],
                memo: Memo::new(MEMO),
            })
        };
        Ok((m(a, 101, "train")?, m(b, 202, "holdout")?))
    }
}

/// Runs the twin experiments.
pub fn validate(opt: &TwinOptions, progress: &dyn Fn(usize, usize)) -> Result<TwinReport, String> {
    let t0 = Instant::now();
    let base = scenario().ok_or("the cwru-6205-de preset is missing")?;
    let spec = spec_of(&base)?;
    let half = (opt.half_s * spec.fs).round() as usize;
    let level = rms(&record(&base, 1, half)?);
    let mut floor = Effects::NONE;
    floor
        .set(
            wearsim_core::effects::EffectKind::Sensor,
            &[
                (opt.noise * level) as wearsim_core::Real,
                0.0,
                0.0,
                60.0,
                0.0,
            ],
        )
        .map_err(|e| format!("--noise: {e}"))?;
    let setup = TwinSetup {
        half,
        spec: spec.clone(),
        base: base.clone(),
        floor,
    };
    let ctx = space::context(&spec, level, 60.0);
    let all = space::applicable(&ctx, true, None);
    let chosen: Vec<FitSpace> = if opt.effects.is_empty() {
        all.clone()
    } else {
        let mut v = vec![];
        for name in &opt.effects {
            match all.iter().find(|s| s.effect == name) {
                Some(s) => v.push(s.clone()),
                None => {
                    return Err(format!(
                        "--effects: unknown effect `{name}`; known: {}",
                        all.iter().map(|s| s.effect).collect::<Vec<_>>().join(", ")
                    ))
                }
            }
        }
        v
    };
    let ev = Evaluator::new(opt.jobs);
    let aopt = Options {
        max_effects: 1,
        ..Options::default()
    };
    let mut rng = Xoshiro128pp::from_u64(opt.seed);
    let total = chosen.len() * opt.trials + opt.trials + opt.pair_trials + opt.null_trials;
    let mut done = 0;
    // Noise-only twins: the floor every shrink is compared with.
    let mut noise_only = vec![];
    for t in 0..opt.trials {
        let (_, ho) = setup.halves(&Effects::NONE, opt.seed * 1000 + t as u64)?;
        noise_only.push(ev.total(&[ho], &setup.floor));
        done += 1;
        progress(done, total);
    }
    let noise_gap = median(noise_only);
    let mut trials = vec![];
    let run = |withheld: &[&FitSpace],
               seed: u64,
               rng: &mut Xoshiro128pp,
               max_effects: usize|
     -> Result<(Trial, Vec<String>), String> {
        let sims0 = ev.sims();
        let mut redraws = 0;
        let (fx, params, tr, ho) = loop {
            let mut fx = Effects::NONE;
            let mut params: Vec<Vec<(String, f64)>> = vec![];
            for s in withheld {
                let u = draw(s, rng);
                s.apply(&mut fx, &u)?;
                params.push(
                    s.named(&u)
                        .into_iter()
                        .map(|(n, v)| (n.to_string(), v))
                        .collect(),
                );
            }
            let (tr, ho) = setup.halves(&fx, seed.wrapping_add(31 * redraws as u64))?;
            let seen = ev.total(std::slice::from_ref(&ho), &setup.floor);
            if withheld.is_empty() || seen >= DETECTABLE * noise_gap || redraws >= MAX_REDRAWS {
                break (fx, params, tr, ho);
            }
            redraws += 1;
        };
        let mut truth = setup.floor;
        merge(&mut truth, &fx);
        let oracle = ev.total(std::slice::from_ref(&ho), &truth);
        let mut a = attribute(
            &all,
            &setup.floor,
            &[tr],
            &[ho],
            &ev,
            &Options {
                max_effects,
                ..aopt
            },
        )?;
        super::identify::confounded(&mut a, aopt.min_shrink);
        let first = a.ranking.first().filter(|r| r.shrink >= aopt.min_shrink);
        let reported_set: Vec<String> = first
            .map(|r| {
                let mut v = vec![r.effect.clone()];
                v.extend(r.confounded_with.iter().cloned());
                v
            })
            .unwrap_or_default();
        let added: Vec<String> = a.kept.clone();
        Ok((
            Trial {
                withheld: withheld.iter().map(|s| s.effect.to_string()).collect(),
                params,
                ranked_first: first.map(|r| r.effect.clone()),
                reported_set,
                fitted: first.map(|r| r.params.clone()).unwrap_or_default(),
                before: a.baseline_holdout,
                after: first.map_or(a.baseline_holdout, |r| r.holdout_gap),
                oracle,
                simulations: ev.sims() - sims0,
                redraws,
            },
            added,
        ))
    };
    for (i, s) in chosen.iter().enumerate() {
        for t in 0..opt.trials {
            let seed = opt.seed * 1_000_003 + (i * 1000 + t) as u64;
            trials.push(run(&[s], seed, &mut rng, 1)?.0);
            done += 1;
            progress(done, total);
        }
    }
    // No effect withheld: anything named is a false attribution.
    let mut null = None;
    if opt.null_trials > 0 {
        let mut named = 0;
        for t in 0..opt.null_trials {
            let (tr, _) = run(&[], opt.seed * 5_000_011 + t as u64, &mut rng, 1)?;
            named += usize::from(tr.ranked_first.is_some());
            trials.push(tr);
            done += 1;
            progress(done, total);
        }
        null = Some((opt.null_trials, named));
    }
    // Two withheld effects at once.
    let mut pairs = None;
    if opt.pair_trials > 0 && chosen.len() >= 2 {
        let (mut any, mut both) = (0, 0);
        for t in 0..opt.pair_trials {
            let i = t % chosen.len();
            let j = (i + 1 + (t / chosen.len()) % (chosen.len() - 1)) % chosen.len();
            let (Some(a), Some(b)) = (chosen.get(i), chosen.get(j)) else {
                continue;
            };
            let (tr, added) = run(&[a, b], opt.seed * 7_000_003 + t as u64, &mut rng, 2)?;
            if tr
                .ranked_first
                .as_ref()
                .is_some_and(|f| tr.withheld.iter().any(|w| same_class(w, f)))
            {
                any += 1;
            }
            if added.len() == 2
                && tr
                    .withheld
                    .iter()
                    .all(|w| added.iter().any(|x| same_class(w, x)))
            {
                both += 1;
            }
            trials.push(tr);
            done += 1;
            progress(done, total);
        }
        let n = opt.pair_trials as f64;
        pairs = Some((opt.pair_trials, any as f64 / n, both as f64 / n));
    }
    // Summaries.
    let labels: Vec<String> = chosen.iter().map(|s| s.effect.to_string()).collect();
    let cols: Vec<String> = all.iter().map(|s| s.effect.to_string()).collect();
    let mut confusion = vec![vec![0usize; cols.len() + 1]; labels.len()];
    let mut rates = vec![];
    for (i, l) in labels.iter().enumerate() {
        let mine: Vec<&Trial> = trials
            .iter()
            .filter(|t| t.withheld.len() == 1 && t.withheld.first() == Some(l))
            .collect();
        for t in &mine {
            let j = t
                .ranked_first
                .as_ref()
                .and_then(|f| cols.iter().position(|c| c == f))
                .unwrap_or(cols.len());
            if let Some(c) = confusion.get_mut(i).and_then(|row| row.get_mut(j)) {
                *c += 1;
            }
        }
        let top1 = mine
            .iter()
            .filter(|t| t.ranked_first.as_deref() == Some(l.as_str()))
            .count();
        let top1_class = mine
            .iter()
            .filter(|t| t.ranked_first.as_deref().is_some_and(|f| same_class(f, l)))
            .count();
        rates.push(EffectRate {
            effect: l.clone(),
            trials: mine.len(),
            top1,
            rate: top1 as f64 / mine.len().max(1) as f64,
            top1_class,
            median_after_over_noise: median(mine.iter().map(|t| t.after / t.oracle).collect()),
            median_shrink: median(mine.iter().map(|t| 1.0 - t.after / t.before).collect()),
            redraws: mine.iter().map(|t| t.redraws).sum(),
            in_set: mine
                .iter()
                .filter(|t| t.reported_set.iter().any(|e| e == l))
                .count(),
            mean_set_size: mine.iter().map(|t| t.reported_set.len()).sum::<usize>() as f64
                / mine.len().max(1) as f64,
        });
    }
    let mut columns = cols;
    columns.push("none".into());
    Ok(TwinReport {
        scenario: "cwru-6205-de, 0.007 in inner-race defect, 1797 rpm, 12 kHz".into(),
        noise_only_gap: noise_gap,
        rates,
        confusion,
        labels,
        columns,
        indistinguishable: INDISTINGUISHABLE
            .iter()
            .map(|(a, b, c)| (a.to_string(), b.to_string(), c.to_string()))
            .collect(),
        pairs,
        null,
        trials,
        simulations: ev.sims(),
        seconds: t0.elapsed().as_secs_f64(),
    })
}
