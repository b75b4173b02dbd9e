//! Twin experiments (sim-to-real.md, "Checked on data whose effect is withheld"): a
//! "measured" bearing is simulated with zero to three candidate effects switched on at
//! random parameter values over their whole range, or with a mechanism outside the
//! library ([`super::twin::Outside`]), plus white measurement noise, and (by default) a
//! structure, defect size, load and speed that differ from the baseline by realistic
//! random amounts ([`super::twin::Mismatch`]). The diagnosis starts from the nominal
//! baseline, fits on one run of the twin and chooses on another (independent seeds); a
//! third run measures how strong the withheld effect is, for the report only (nothing is
//! redrawn or selected on it). Over many trials this gives, per effect, the top-1 rate, the
//! truth inside the reported confounded set and the set's size, against the effect's
//! strength (detection power); the false-attribution rate on no-effect twins; the
//! not-closed rate on out-of-library twins; and how often two or three withheld effects
//! are all named.

pub use super::attribute::{same_class, INDISTINGUISHABLE};
pub use super::twin_report::{
    AngleRow, EffectRate, PowerBin, Reproducer, Trial, TwinReport, DETECTABLE, SET_ANGLES,
    STRENGTH_BINS,
};

use super::attribute::{attribute_with, Options, Recalibrate};
use super::matched::{merge, without, Evaluator, Matched, MEMO};
use super::memo::Memo;
use super::nuisance::{calibrate, Tolerances};
use super::space::{self, FitSpace};
use super::twin::{Mismatch, Outside};
use super::twin_report::{angle_curve, detectable, holds, mean_size, single};
use super::{CellSpec, Reference};
use crate::analysis::stats::{self, rms};
use crate::analysis::FaultFamily;
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
    /// Also run trials with three effects withheld at once (this many).
    pub triple_trials: usize,
    /// Also run trials whose twin has a mechanism outside the library (this many).
    pub outside_trials: usize,
    /// How the twins differ from the baseline beyond the withheld effects.
    pub mismatch: Mismatch,
    /// The tolerances within which the diagnosis calibrates the rig on the training run
    /// before ranking effects ([`super::nuisance`]; [`Tolerances::NONE`]: no calibration).
    pub calibrate: Tolerances,
    /// Also diagnose this many twins with no effect withheld (noise floor only): the
    /// false-attribution rate.
    pub null_trials: usize,
    /// Seed of the parameter draws and realisations.
    pub seed: u64,
    /// Length of each twin record (training, held-out, strength) (s).
    pub half_s: f64,
    /// White measurement noise, as a fraction of the twin record's RMS.
    pub noise: f64,
    /// Worker threads.
    pub jobs: usize,
    /// The greedy steps refit the effects kept before ([`Options::backfit`]).
    pub backfit: bool,
    /// Keep the rig calibrated with no effect through the greedy addition instead of
    /// calibrating it again after each addition ([`super::attribute::attribute_with`]).
    pub fixed_calibration: bool,
    /// Exchange kept effects when the greedy additions stall ([`Options::exchange`]).
    pub exchange: bool,
}

impl Default for TwinOptions {
    fn default() -> Self {
        TwinOptions {
            trials: 20,
            effects: vec![],
            pair_trials: 0,
            triple_trials: 0,
            outside_trials: 0,
            mismatch: Mismatch::RIG,
            calibrate: Tolerances::CALIBRATE,
            null_trials: 0,
            seed: 1,
            half_s: 1.0,
            noise: 0.01,
            jobs: std::thread::available_parallelism().map_or(1, |n| n.get()),
            backfit: false,
            fixed_calibration: false,
            exchange: false,
        }
    }
}

/// Refused twin draws allowed per trial.
pub const MAX_REFUSED: usize = 20;

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
        band_hz: None,
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

/// Normalised coordinates drawn for a twin: uniform over the whole fitted range. Draws
/// the baseline cannot tell from noise are kept and scored against their strength
/// ([`Trial::strength`]), not redrawn.
fn draw(space: &FitSpace, rng: &mut Xoshiro128pp) -> Vec<f64> {
    #[allow(clippy::unnecessary_cast)] // Real is f32 in `f32` builds
    let mut u01 = || 0.5 * (rng.uniform_pm1() as f64 + 1.0);
    space.fitted.iter().map(|_| u01()).collect()
}

/// `k` distinct indices below `n` for trial `t` (k ≤ n): every combination is visited in
/// turn as `t` grows, starting at `t mod n` with a stride that changes every `n` trials.
fn distinct(t: usize, k: usize, n: usize) -> Vec<usize> {
    let n = n.max(1);
    let stride = 1 + (t / n) % (n - 1).max(1);
    let mut out = vec![];
    let mut i = t % n;
    while out.len() < k.min(n) {
        if out.contains(&i) {
            i = (i + 1) % n;
            continue;
        }
        out.push(i);
        i = (i + stride) % n;
    }
    out
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

/// The three runs of one twin bearing, matched against the nominal baseline.
struct TwinRuns {
    /// Fitted on.
    train: Matched,
    /// Chosen on (the held-out run).
    holdout: Matched,
    /// Only measures the strength of what was withheld: a third run matched against the
    /// twin's true configuration without the withheld effects (the mismatch is not part
    /// of the strength).
    strength: Matched,
    /// The held-out run matched against the twin's true configuration (mismatch
    /// included): the "exactly right model" for the oracle gap.
    truth: Matched,
}

impl TwinSetup {
    /// Three independent runs (seeds derived from `seed`) of the twin `cfg` with effects
    /// `fx` and the floor, with the out-of-library mechanism `outside` added to each.
    fn runs(
        &self,
        cfg: &ModelConfig,
        fx: &Effects,
        outside: Option<&Outside>,
        seed: u64,
    ) -> Result<TwinRuns, String> {
        let mut twin = cfg.clone();
        twin.effects = self.floor;
        merge(&mut twin.effects, fx);
        #[allow(clippy::unnecessary_cast)] // Real is f32 in `f32` builds
        let shaft_hz = twin.speed.shaft_hz(0.0) as f64;
        let run = |k: u64, label: &str| -> Result<Matched, String> {
            let mut x = record(
                &twin,
                seed.wrapping_mul(7919).wrapping_add(13 + 1_000_003 * k),
                self.half,
            )?;
            if let Some(o) = outside {
                o.add(&mut x, shaft_hz, self.spec.fs);
            }
            Ok(Matched {
                label: label.to_string(),
                base: self.base.clone(),
                reference: Reference::new(&x, &self.spec).map_err(|e| e.to_string())?,
                samples: x.len(),
                seed: seed.wrapping_add(101 * (k + 1)),
                real: vec![],
                memo: Memo::new(MEMO),
            })
        };
        let holdout = run(1, "holdout")?;
        let mut truth = holdout.clone();
        truth.base = cfg.clone();
        let mut strength = run(2, "strength")?;
        strength.base = cfg.clone();
        Ok(TwinRuns {
            train: run(0, "train")?,
            holdout,
            strength,
            truth,
        })
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
    let ctx = space::context(&spec, level, 60.0, &base);
    let all = space::applicable(&ctx, true, None);
    let chosen: Vec<FitSpace> = if opt.effects.is_empty() {
        all.clone()
    } else {
        crate::effects::check_listed(&opt.effects, "--effects")?;
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
        backfit: opt.backfit,
        exchange: opt.exchange,
        ..Options::default()
    };
    let mut rng = Xoshiro128pp::from_u64(opt.seed);
    let total = chosen.len() * opt.trials
        + opt.trials
        + opt.pair_trials
        + opt.triple_trials
        + opt.outside_trials
        + opt.null_trials;
    let mut done = 0;
    // Noise-only twins (the baseline itself, another realisation): the floor every gap
    // is compared with.
    let mut noise_only = vec![];
    for t in 0..opt.trials {
        let r = setup.runs(&base, &Effects::NONE, None, opt.seed * 1000 + t as u64)?;
        noise_only.push(ev.total(&[r.holdout], &setup.floor));
        done += 1;
        progress(done, total);
    }
    let noise_gap = median(noise_only);
    let mut trials = vec![];
    let run = |withheld: &[&FitSpace],
               outside: bool,
               seed: u64,
               rng: &mut Xoshiro128pp,
               max_effects: usize|
     -> Result<Trial, String> {
        let sims0 = ev.sims();
        // A draw the model refuses (a stiffer, more loaded twin can need a finer internal
        // step than the scenario's) is drawn again and counted; nothing else is redrawn.
        let mut refused = 0;
        let (mismatch, out, fx, params, r) = loop {
            let (cfg, mismatch) = opt.mismatch.draw(&base, rng);
            let out = outside.then(|| Outside::draw(rng));
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
            match setup.runs(&cfg, &fx, out.as_ref(), seed) {
                Ok(r) => break (mismatch, out, fx, params, r),
                Err(e) if refused >= MAX_REFUSED => {
                    return Err(format!(
                        "{MAX_REFUSED} twin draws refused by the model, the last: {e}"
                    ))
                }
                Err(_) => refused += 1,
            }
        };
        let strength = ev.total(std::slice::from_ref(&r.strength), &setup.floor) / noise_gap;
        let mut truth = setup.floor;
        merge(&mut truth, &fx);
        // Each withheld effect's own strength: the gap the others at their true values
        // leave (for one effect, the strength itself).
        let strengths = if withheld.len() < 2 {
            vec![strength; withheld.len()]
        } else {
            withheld
                .iter()
                .map(|s| {
                    without(&truth, s.effect)
                        .map(|rest| ev.total(std::slice::from_ref(&r.strength), &rest) / noise_gap)
                })
                .collect::<Result<Vec<_>, _>>()?
        };
        let oracle = ev.total(std::slice::from_ref(&r.truth), &truth);
        let (calibration, train, holdout) = if opt.calibrate.is_none() {
            (None, vec![r.train.clone()], vec![r.holdout.clone()])
        } else {
            let cal = calibrate(
                std::slice::from_ref(&r.train),
                &setup.floor,
                &opt.calibrate,
                &ev,
            );
            let train = cal.applied(std::slice::from_ref(&r.train));
            let holdout = cal.applied(std::slice::from_ref(&r.holdout));
            (Some(cal), train, holdout)
        };
        let recal = |fx: &Effects| -> Result<(Vec<Matched>, Vec<Matched>), String> {
            let cal = calibrate(std::slice::from_ref(&r.train), fx, &opt.calibrate, &ev);
            Ok((
                cal.applied(std::slice::from_ref(&r.train)),
                cal.applied(std::slice::from_ref(&r.holdout)),
            ))
        };
        let recal_on = !opt.calibrate.is_none() && !opt.fixed_calibration;
        let mut a = attribute_with(
            &all,
            &setup.floor,
            &train,
            &holdout,
            &ev,
            &Options {
                max_effects,
                ..aopt
            },
            recal_on.then_some(&recal as Recalibrate<Matched>),
        )?;
        let reach = super::identify::confounded(&mut a, aopt.min_shrink, aopt.significant_gap);
        let first = a
            .identified
            .as_ref()
            .and_then(|e| a.ranking.iter().find(|r| &r.effect == e));
        let reported_set: Vec<String> = first
            .map(|r| {
                let mut v = vec![r.effect.clone()];
                v.extend(r.confounded_with.iter().cloned());
                v
            })
            .unwrap_or_default();
        Ok(Trial {
            withheld: withheld.iter().map(|s| s.effect.to_string()).collect(),
            params,
            ranked_first: first.map(|r| r.effect.clone()),
            reported_set,
            fitted: first.map(|r| r.params.clone()).unwrap_or_default(),
            before: a.baseline_holdout,
            after: first.map_or(a.baseline_holdout, |r| r.holdout_gap),
            oracle,
            simulations: ev.sims() - sims0,
            mismatch,
            calibration,
            outside: out.map(|o| o.named()),
            strength,
            strengths,
            first_angles: first
                .map(|f| {
                    a.ranking
                        .iter()
                        .filter(|b| b.effect != f.effect)
                        .filter_map(|b| {
                            let r = reach.get(&format!("{} -> {}", f.effect, b.effect))?;
                            Some(Reproducer {
                                effect: b.effect.clone(),
                                angle_deg: r.angle_deg,
                                shrink: b.shrink,
                                residual: r.residual,
                            })
                        })
                        .collect()
                })
                .unwrap_or_default(),
            kept_sets: a
                .kept
                .iter()
                .map(|k| {
                    let at_step = a.greedy.iter().rposition(|g| &g.effect == k);
                    let others = match at_step {
                        Some(0) | None => a
                            .ranking
                            .iter()
                            .find(|r| &r.effect == k)
                            .map(|r| r.confounded_with.clone())
                            .unwrap_or_default(),
                        Some(i) => a.greedy[i].confounded_with.clone(),
                    };
                    std::iter::once(k.clone()).chain(others).collect()
                })
                .collect(),
            kept: a.kept.clone(),
            exchanged: a.exchanged.clone(),
            final_gap: a.final_holdout,
            closed: a.final_holdout <= DETECTABLE * noise_gap,
            refused,
        })
    };
    for (i, s) in chosen.iter().enumerate() {
        for t in 0..opt.trials {
            let seed = opt.seed * 1_000_003 + (i * 1000 + t) as u64;
            trials.push(run(&[s], false, seed, &mut rng, 1)?);
            done += 1;
            progress(done, total);
        }
    }
    // No effect withheld: anything named is a false attribution.
    let mut null = None;
    let mut null_gaps = Vec::with_capacity(opt.null_trials);
    if opt.null_trials > 0 {
        let mut named = 0;
        for t in 0..opt.null_trials {
            let tr = run(&[], false, opt.seed * 5_000_011 + t as u64, &mut rng, 1)?;
            named += usize::from(tr.ranked_first.is_some());
            null_gaps.push(tr.before);
            trials.push(tr);
            done += 1;
            progress(done, total);
        }
        null = Some((opt.null_trials, named));
    }
    // A mechanism outside the library: the full greedy model should leave the gap open.
    let mut outside = None;
    if opt.outside_trials > 0 {
        let mut open = 0;
        for t in 0..opt.outside_trials {
            let tr = run(
                &[],
                true,
                opt.seed * 9_000_011 + t as u64,
                &mut rng,
                Options::default().max_effects,
            )?;
            open += usize::from(!tr.closed);
            trials.push(tr);
            done += 1;
            progress(done, total);
        }
        outside = Some((opt.outside_trials, open));
    }
    // Two and three withheld effects at once: all of them named by the greedy additions.
    let mut pairs = None;
    let mut triples = None;
    let (mut pairs_detectable, mut triples_detectable) = (None, None);
    let mut pairs_in_sets_detectable = None;
    for (k, n, seed0) in [
        (2, opt.pair_trials, 7_000_003),
        (3, opt.triple_trials, 8_000_009),
    ] {
        if n == 0 || chosen.len() < k {
            continue;
        }
        let (mut any, mut all_named, mut seen, mut seen_named) = (0, 0, 0, 0);
        let (mut seen_in_sets, mut set_sizes) = (0, 0.0);
        for t in 0..n {
            let picked: Vec<&FitSpace> = distinct(t, k, chosen.len())
                .into_iter()
                .filter_map(|i| chosen.get(i))
                .collect();
            let tr = run(&picked, false, opt.seed * seed0 + t as u64, &mut rng, k)?;
            if tr
                .ranked_first
                .as_ref()
                .is_some_and(|f| tr.withheld.iter().any(|w| same_class(w, f)))
            {
                any += 1;
            }
            let named = tr.kept.len() == k
                && tr
                    .withheld
                    .iter()
                    .all(|w| tr.kept.iter().any(|x| same_class(w, x)));
            let detectable = tr.strengths.iter().all(|s| *s >= DETECTABLE);
            // Both in the reported sets of the two additions, as a single effect is
            // counted in its first-ranked effect's set.
            let in_sets = tr.kept.len() == k
                && tr.withheld.iter().all(|w| {
                    tr.kept_sets
                        .iter()
                        .any(|set| set.iter().any(|x| same_class(w, x)))
                });
            if detectable {
                seen_in_sets += usize::from(in_sets);
                set_sizes += tr.kept_sets.iter().map(Vec::len).sum::<usize>() as f64
                    / tr.kept_sets.len().max(1) as f64;
            }
            all_named += usize::from(named);
            seen += usize::from(detectable);
            seen_named += usize::from(detectable && named);
            trials.push(tr);
            done += 1;
            progress(done, total);
        }
        let nf = n as f64;
        if k == 2 {
            pairs = Some((n, any as f64 / nf, all_named as f64 / nf));
            pairs_detectable = Some((seen, seen_named));
            pairs_in_sets_detectable = Some((seen, seen_in_sets, set_sizes / seen.max(1) as f64));
        } else {
            triples = Some((n, all_named as f64 / nf));
            triples_detectable = Some((seen, seen_named));
        }
    }
    // Summaries.
    let labels: Vec<String> = chosen.iter().map(|s| s.effect.to_string()).collect();
    let cols: Vec<String> = all.iter().map(|s| s.effect.to_string()).collect();
    let mut confusion = vec![vec![0usize; cols.len() + 1]; labels.len()];
    let mut rates = vec![];
    for (i, l) in labels.iter().enumerate() {
        let mine = single(&trials, l);
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
        let seen = detectable(&mine);
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
            in_set: mine.iter().filter(|t| holds(t, l)).count(),
            mean_set_size: mean_size(&mine),
            detectable: seen.len(),
            in_set_detectable: seen.iter().filter(|t| holds(t, l)).count(),
            mean_set_size_detectable: mean_size(&seen),
        });
    }
    let power = STRENGTH_BINS
        .iter()
        .enumerate()
        .map(|(b, from)| {
            let to = STRENGTH_BINS.get(b + 1).copied().unwrap_or(f64::INFINITY);
            let band: Vec<&Trial> = trials
                .iter()
                .filter(|t| t.withheld.len() == 1 && t.outside.is_none())
                .filter(|t| (*from..to).contains(&t.strength))
                .collect();
            PowerBin {
                from: *from,
                trials: band.len(),
                in_set: band
                    .iter()
                    .filter(|t| t.withheld.first().is_some_and(|w| holds(t, w)))
                    .count(),
            }
        })
        .collect();
    let set_angles = angle_curve(&trials, &labels, aopt.min_shrink, aopt.significant_gap);
    let mut columns = cols;
    columns.push("none".into());
    Ok(TwinReport {
        scenario: "cwru-6205-de, 0.007 in inner-race defect, 1797 rpm, 12 kHz".into(),
        noise_only_gap: noise_gap,
        null_threshold: super::attribute::false_alarm_threshold(&null_gaps, 0.05),
        rates,
        confusion,
        labels,
        columns,
        indistinguishable: INDISTINGUISHABLE
            .iter()
            .map(|(a, b, c)| (a.to_string(), b.to_string(), c.to_string()))
            .collect(),
        pairs,
        pairs_detectable,
        pairs_in_sets_detectable,
        null,
        triples,
        triples_detectable,
        outside,
        power,
        set_angles,
        mismatch: format!("{:?}", opt.mismatch),
        trials,
        simulations: ev.sims(),
        seconds: t0.elapsed().as_secs_f64(),
    })
}
