//! The gap along a whole life (sim-to-real.md, "for lifetime data, the same cells along
//! normalised life, so a gap can also lie in time"): a measured run-to-failure record
//! (per-snapshot statistics of the IMS tests) against a simulated life of the same
//! bearing, whose wear stages come from the core's stress-driven wear machine.
//!
//! **Cells.** Normalised life (time over the failed bearing's life) is cut into the
//! stages of [`STAGES`]. The steady stage (10–50 % of life) carries the absolute level
//! of the statistics (kurtosis, crest factor, skewness; RMS is the unit of the others);
//! every other stage carries its *contrast* to the steady stage: RMS in dB re the steady
//! median, and the differences of kurtosis, crest factor and skewness. A mismatch of the
//! steady level is then counted once, and a gap that lies in time (a running-in bump, a
//! late rise) is counted where it lies. A cell's spread is the standard deviation of the
//! per-snapshot value across the measured snapshots of its stage (the lifetime record's
//! segments are its snapshots), floored at [`floor`]. Each stage is one group of the
//! total gap ([`super::total_weighted`]), so every stage counts equally.
//!
//! **Simulated life.** The record's bearing (`ims-za2115`, 2000 rpm, 6000 lbf) runs its
//! whole life in the wear machine of `wearsim life`; a window of the measured snapshot's
//! length (20 480 samples) is rendered at every block of the schedule ([`SCHEDULE`]:
//! fine early in life, where running-in lives, coarser later) and after every stage
//! transition, and its statistics are computed exactly as the measured ones (kurtosis
//! not excess, crest = max |x| / RMS). The life factor is calibrated once, on the
//! training bearing's measured life (as `wearsim ims-compare` does; stated in the report).
//! Candidate effects are added to the life's model, so running-in decays over the
//! life's revolutions, and the wear responds to the loads they change.
//!
//! **Training and held-out.** Effects are fitted on the training bearing's whole life
//! and judged on held-out bearings of the same test over the stages they share with it
//! before any failure (t < [`HOLDOUT_T_MAX`]): the bearings ran on one shaft, were new
//! together and did not fail, so their late stages carry the failing neighbour's
//! vibration through the shaft rather than their own wear.
//!
//! **The early-life part** is attributed again on the early stages' cells alone (their
//! contrasts to the steady stage), so that the steady level, which dominates the total,
//! cannot decide which effect explains the first hours. **Significance**: a cell compares a
//! stage mean of `n` measured snapshots with one of `m` simulated windows, so a correct
//! model leaves a gap of variance `1/n + 1/m` per cell by sampling alone
//! ([`LifeReference::noise_only`]); a gap counts from [`SIGNIFICANCE`] times that.

use super::attribute::{attribute, leave_one_out, Attribution, LeaveOneOut, Options};
use super::fit::Budget;
use super::matched::{merge, Evaluator, Gaps, Target};
use super::space::{FitParam, FitSpace};
use crate::analysis;
use crate::analysis::stats::{mean_std, upper_median};
use crate::io::ims::read_ims_features;
use crate::life::{LifeRun, LifeSpec};
use serde::Serialize;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use wearsim_core::effects::Effects;
use wearsim_core::wear::{LifeConfig, Material, Stage};

/// A stage of normalised life: `[lo, hi)` (the last one includes 1).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LifeStage {
    /// Name, used in cell names `life:<name>:<stat>`.
    pub name: &'static str,
    /// Start (fraction of life).
    pub lo: f64,
    /// End (fraction of life).
    pub hi: f64,
}

const fn stage(name: &'static str, lo: f64, hi: f64) -> LifeStage {
    LifeStage { name, lo, hi }
}

/// The stages of a life. The first three resolve the early life (a running-in of tens to
/// hundreds of thousands of revolutions is the first 1–3 % of a 2·10⁷-revolution life);
/// the last three the degradation.
pub const STAGES: [LifeStage; 7] = [
    stage("running-in", 0.0, 0.01),
    stage("early", 0.01, 0.03),
    stage("settled", 0.03, 0.1),
    stage("steady", 0.1, 0.5),
    stage("onset", 0.5, 0.7),
    stage("degradation", 0.7, 0.9),
    stage("end", 0.9, 1.0),
];

/// Index of the steady stage in [`STAGES`].
pub const STEADY: usize = 3;

/// Stages before this fraction of life are the "early-life part" of the gap.
pub const EARLY_T_MAX: f64 = 0.1;

/// Held-out bearings are compared on the stages that end at or before this fraction of
/// the test (see the module docs).
pub const HOLDOUT_T_MAX: f64 = 0.5;

/// Fewest measured snapshots a stage needs to have a spread.
pub const MIN_SNAPSHOTS: usize = 3;

/// The statistics of a snapshot that the cells use.
pub const STATS: [&str; 4] = ["rms", "kurtosis", "crest", "skewness"];

/// Smallest spread of a life cell, per statistic: 0.05 dB for RMS, 0.02 for kurtosis and
/// crest factor, 0.005 for skewness. Snapshot scatter of a steady bearing is about 0.1 dB
/// and 0.1 in kurtosis (IMS test 2), far below the 0.5 dB floor of the stationary cells,
/// which would hide every stage.
pub fn floor(stat: &str) -> f64 {
    match stat {
        "rms" => 0.05,
        "skewness" => 0.005,
        _ => 0.02,
    }
}

/// Statistics of one snapshot.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LifePoint {
    /// Fraction of life (0–1).
    pub t: f64,
    /// RMS (record unit).
    pub rms: f64,
    /// Kurtosis (Gaussian = 3).
    pub kurtosis: f64,
    /// Crest factor max |x| / RMS.
    pub crest: f64,
    /// Skewness.
    pub skewness: f64,
}

impl LifePoint {
    fn stat(&self, i: usize, rms_ref: f64) -> f64 {
        match i {
            0 => 20.0 * (self.rms / rms_ref).max(1e-12).log10(),
            1 => self.kurtosis,
            2 => self.crest,
            _ => self.skewness,
        }
    }
}

fn in_stage(p: &LifePoint, s: &LifeStage) -> bool {
    p.t >= s.lo && (p.t < s.hi || (s.hi >= 1.0 && p.t <= 1.0))
}

/// Points of `pts` in stage `s`; when none falls inside (a sparse simulated schedule), the
/// one nearest to the stage's centre.
fn stage_points<'a>(pts: &'a [LifePoint], s: &LifeStage) -> Vec<&'a LifePoint> {
    let v: Vec<&LifePoint> = pts.iter().filter(|p| in_stage(p, s)).collect();
    if !v.is_empty() {
        return v;
    }
    let c = 0.5 * (s.lo + s.hi);
    pts.iter()
        .min_by(|a, b| (a.t - c).abs().total_cmp(&(b.t - c).abs()))
        .into_iter()
        .collect()
}

/// Cell values of a series: per stage and statistic, the stage mean (steady: absolute;
/// others: contrast to the steady mean), and the per-snapshot values (for the spread).
fn stage_values(pts: &[LifePoint], stages: &[LifeStage]) -> Option<Vec<(f64, Vec<f64>)>> {
    let steady = STAGES.get(STEADY)?;
    let sp = stage_points(pts, steady);
    let rms_ref = upper_median(sp.iter().map(|p| p.rms).collect())?;
    if rms_ref.is_nan() || rms_ref <= 0.0 {
        return None;
    }
    let steady_mean: Vec<f64> = (0..STATS.len())
        .map(|i| mean_std(&sp.iter().map(|p| p.stat(i, rms_ref)).collect::<Vec<_>>()).0)
        .collect();
    let mut out = vec![];
    for s in stages {
        let is_steady = s.name == steady.name;
        let p = stage_points(pts, s);
        for (i, m0) in steady_mean.iter().enumerate() {
            if is_steady && i == 0 {
                continue; // RMS is the unit of the other stages.
            }
            let off = if is_steady { 0.0 } else { *m0 };
            let v: Vec<f64> = p.iter().map(|q| q.stat(i, rms_ref) - off).collect();
            out.push((mean_std(&v).0, v));
        }
    }
    Some(out)
}

/// The measured side of a life gap: cells, their means and floored spreads, weights.
#[derive(Debug, Clone, Serialize)]
pub struct LifeReference {
    /// What it is (file and bearing).
    pub label: String,
    /// Stages compared (those with enough measured snapshots, before `t_max`).
    pub stages: Vec<LifeStage>,
    /// Cell names `life:<stage>:<stat>`, with the stage as group.
    pub names: Vec<(String, &'static str, &'static str)>,
    /// Measured cell values.
    pub mean: Vec<f64>,
    /// Floored spreads.
    pub spread: Vec<f64>,
    /// Weight of each cell in the total (each stage one group; Σ w² = 1).
    pub weight: Vec<f64>,
    /// Measured snapshots in each cell's stage.
    pub count: Vec<usize>,
}

impl LifeReference {
    /// Cells of the measured series `pts` over the stages that start before `t_max`
    /// (and end by it) and hold at least [`MIN_SNAPSHOTS`] snapshots.
    pub fn new(label: &str, pts: &[LifePoint], t_max: f64) -> Result<Self, String> {
        let stages: Vec<LifeStage> = STAGES
            .iter()
            .filter(|s| s.hi <= t_max + 1e-9)
            .copied()
            .collect();
        for s in &stages {
            let n = pts.iter().filter(|p| in_stage(p, s)).count();
            if n < MIN_SNAPSHOTS {
                let what = if s.name == STAGES[STEADY].name {
                    " (the reference of every other stage)"
                } else {
                    ""
                };
                return Err(format!(
                    "{label}: fewer than {MIN_SNAPSHOTS} snapshots in the {} stage ({:.0}-{:.0} % of life){what}: it holds {n}; a life gap needs at least {MIN_SNAPSHOTS} in every stage, i.e. a few hundred snapshots spread over the life",
                    s.name,
                    100.0 * s.lo,
                    100.0 * s.hi
                ));
            }
        }
        let vals = stage_values(pts, &stages)
            .ok_or_else(|| format!("{label}: no positive RMS in the steady stage"))?;
        let mut names = vec![];
        for s in &stages {
            for (i, st) in STATS.iter().enumerate() {
                if s.name == STAGES[STEADY].name && i == 0 {
                    continue;
                }
                let unit = if i == 0 { "dB" } else { "-" };
                names.push((format!("life:{}:{st}", s.name), s.name, unit));
            }
        }
        let (mut mean, mut spread, mut count) = (vec![], vec![], vec![]);
        for ((m, v), (n, _, _)) in vals.iter().zip(&names) {
            let stat = n.rsplit(':').next().unwrap_or("");
            mean.push(*m);
            spread.push(mean_std(v).1.max(floor(stat)));
            count.push(v.len());
        }
        let weight = super::group_weights(&names);
        Ok(LifeReference {
            label: label.to_string(),
            stages,
            names,
            mean,
            spread,
            weight,
            count,
        })
    }

    /// The total gap a correct model would leave on these cells by sampling alone: each
    /// cell compares a stage mean over `n_m` measured snapshots with one over `n_s`
    /// simulated windows (the simulated series `sim`), both with the measured spread, so
    /// its gap has variance `1/n_m + 1/n_s`; the total weights them like the gaps.
    pub fn noise_only(&self, sim: &[LifePoint]) -> f64 {
        let n_sim = |stage: &str| {
            STAGES
                .iter()
                .find(|s| s.name == stage)
                .map_or(1, |s| stage_points(sim, s).len().max(1))
        };
        self.names
            .iter()
            .zip(&self.count)
            .zip(&self.weight)
            .map(|(((_, stg, _), n), w)| {
                w * w * (1.0 / (*n).max(1) as f64 + 1.0 / n_sim(stg) as f64)
            })
            .sum::<f64>()
            .sqrt()
    }

    /// Cell values of a simulated series, in cell order.
    pub fn values(&self, pts: &[LifePoint]) -> Result<Vec<f64>, String> {
        let v = stage_values(pts, &self.stages)
            .ok_or("the simulated life has no positive RMS in its steady stage")?;
        Ok(v.into_iter().map(|(m, _)| m).collect())
    }

    /// `(sim − real)/spread` of simulated cell values.
    pub fn residuals(&self, sim: &[f64]) -> Vec<f64> {
        super::normalised(sim, &self.mean, &self.spread)
    }
}

/// A measured life: one bearing's snapshots on the normalised time line of the test.
#[derive(Debug, Clone, Serialize)]
pub struct MeasuredLife {
    /// File read.
    pub file: String,
    /// Bearing (1-based, test 2: channel = bearing).
    pub bearing: usize,
    /// Snapshots (dead final snapshots dropped).
    pub points: Vec<LifePoint>,
    /// Duration of the test up to its last live snapshot (h).
    pub hours: f64,
    /// Snapshots dropped as dead (machine stopped).
    pub dropped: usize,
}

/// Reads bearing `bearing` (1–4) of an IMS feature table with per-channel `rms`,
/// `kurtosis` (excess, converted to Gaussian = 3), `crest`, `skew` and `mean_abs`
/// columns (`features_chocho66/test2_timefeatures.csv`). Snapshots whose mean |x| is below
/// 10 % of the test's median on *every* channel are dropped (the machine had stopped;
/// README quirk); time is normalised by the last live snapshot.
pub fn read_life(path: &Path, bearing: usize) -> Result<MeasuredLife, String> {
    let f = read_ims_features(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let col = |b: usize, name: &str| -> Result<&[f64], String> {
        f.column(&format!("B{b}_{name}")).ok_or_else(|| {
            format!(
                "{}: no column B{b}_{name}; a lifetime record needs per-bearing rms, kurtosis, crest, skew and mean columns (an IMS timefeatures table)",
                path.display()
            )
        })
    };
    let bearings: Vec<usize> = (1..=8)
        .filter(|b| f.column(&format!("B{b}_rms")).is_some())
        .collect();
    if !bearings.contains(&bearing) {
        return Err(format!(
            "{}: bearing {bearing} is not in the table (it has {:?})",
            path.display(),
            bearings
        ));
    }
    // Dead snapshots: all channels quiet.
    let n = f.hours.len();
    let mut live = vec![false; n];
    for b in &bearings {
        let m = col(*b, "mean_abs")?;
        let med = upper_median(m.to_vec()).unwrap_or(0.0);
        for (l, v) in live.iter_mut().zip(m) {
            *l |= *v > 0.1 * med;
        }
    }
    let keep: Vec<usize> = (0..n).filter(|i| live[*i]).collect();
    let (Some(&first), Some(&last)) = (keep.first(), keep.last()) else {
        return Err(format!("{}: no live snapshots", path.display()));
    };
    let (h0, h1) = (f.hours[first], f.hours[last]);
    if h1.is_nan() || h0.is_nan() || h1 <= h0 {
        return Err(format!(
            "{}: the snapshots span no time (first and last at {h0} h)",
            path.display()
        ));
    }
    let (rms, kurt, crest, skew) = (
        col(bearing, "rms")?,
        col(bearing, "kurtosis")?,
        col(bearing, "crest")?,
        col(bearing, "skew")?,
    );
    let mut points = vec![];
    for i in &keep {
        let p = LifePoint {
            t: (f.hours[*i] - h0) / (h1 - h0),
            rms: rms[*i],
            kurtosis: kurt[*i] + 3.0,
            crest: crest[*i],
            skewness: skew[*i],
        };
        if [p.t, p.rms, p.kurtosis, p.crest, p.skewness]
            .iter()
            .all(|v| v.is_finite())
            && p.rms > 0.0
        {
            points.push(p);
        }
    }
    Ok(MeasuredLife {
        file: path.display().to_string(),
        bearing,
        points,
        hours: h1 - h0,
        dropped: n - keep.len(),
    })
}

/// Window schedule of a simulated life, as fractions of the expected life: blocks of
/// `step` until `until`. Fine where running-in lives (10 windows in the first 1 % of life,
/// 20 in the next 2 %, so that the simulated stage means are about as precise as the
/// measured ones), coarser where the wear machine's own transitions add windows anyway.
pub const SCHEDULE: [(f64, f64); 3] = [(0.03, 0.001), (0.1, 0.01), (1.0, 0.02)];

/// Most windows of one simulated life (the schedule needs about 90).
pub const MAX_WINDOWS: u64 = 2_000;

/// Samples per simulated window: the measured snapshot's length (crest factor and
/// kurtosis depend on it).
pub const WINDOW_SAMPLES: usize = 20_480;

/// A simulated life of the record's bearing with candidate effects, cached per effect set
/// (the training and held-out bearings share the simulated life of the same seed).
#[derive(Debug)]
pub struct LifeSim {
    /// Dynamic model of the bearing (no effects).
    pub model: wearsim_core::ModelConfig,
    /// Wear configuration (calibrated life factor).
    pub life: LifeConfig,
    /// Seed of the life (Weibull draw, window streams).
    pub seed: u64,
    /// Revolutions of the calibrated baseline life (the schedule's unit).
    pub expected_revs: f64,
    cache: Mutex<Vec<(Effects, Arc<Vec<LifePoint>>)>>,
}

/// Most effect sets kept in a [`LifeSim`]'s cache (about 3 KB each): the early-life
/// attribution revisits the whole-life fits' grids.
const CACHE: usize = 1024;

impl LifeSim {
    /// A simulated life of preset `preset` with life factor `life_factor`.
    pub fn new(
        preset: &str,
        life_factor: f64,
        seed: u64,
        expected_revs: f64,
    ) -> Result<Self, String> {
        let model = wearsim_core::presets::by_name(preset)
            .ok_or_else(|| format!("preset {preset} missing"))?;
        Ok(LifeSim {
            model,
            life: LifeConfig {
                material: Material {
                    life_factor,
                    ..Material::BEARING_STEEL
                },
                cycle_cap: 1e13,
                ..LifeConfig::DEFAULT
            },
            seed,
            expected_revs,
            cache: Mutex::new(vec![]),
        })
    }

    /// Revolutions to the next window after `cycles`: the [`SCHEDULE`] step of the
    /// expected life; past the early part, of the revolutions run when the life outlasts
    /// its expectation (an uncalibrated life can run 30× longer; the windows then grow
    /// geometrically instead of running into the thousands).
    fn block(&self, cycles: f64) -> f64 {
        let e = self.expected_revs.max(1.0);
        let u = cycles / e;
        let step = SCHEDULE
            .iter()
            .find(|(until, _)| u < *until)
            .map_or(0.02, |(_, s)| *s);
        let scale = if u < EARLY_T_MAX { e } else { e.max(cycles) };
        (step * scale).max(1.0)
    }

    /// Runs the life with effects `fx`: snapshot statistics on the normalised time line
    /// and the revolutions to failure.
    pub fn run(&self, fx: &Effects) -> Result<(Vec<LifePoint>, f64), String> {
        let mut model = self.model.clone();
        merge(&mut model.effects, fx);
        let fs = model.output_rate;
        let run = LifeRun::new(LifeSpec {
            model,
            life: self.life,
            seed: self.seed,
            snapshot_every: self.block(0.0),
            window: WINDOW_SAMPLES as f64 / fs,
            settle: 0.05,
        })
        .map_err(|e| e.to_string())?;
        let mut st = run.life.initial_state(self.seed);
        let mut raw: Vec<(f64, analysis::Stats)> = vec![];
        let mut k = 0u64;
        loop {
            let (x, loads) = run.window(&st, k).map_err(|e| e.to_string())?;
            k += 1;
            let s = analysis::stats(&x).map_err(|e| e.to_string())?;
            raw.push((st.cycles, s));
            if st.stage == Stage::Failure {
                break;
            }
            let mut remaining = self.block(st.cycles);
            while remaining > 0.0 {
                let adv = run.life.advance(&mut st, remaining, &loads);
                remaining -= adv.revs;
                if adv.transition.is_some() || adv.revs <= 0.0 {
                    break;
                }
            }
            run.check_cap(&st).map_err(|e| e.to_string())?;
            if k > MAX_WINDOWS {
                return Err(format!(
                    "the simulated life did not fail within {MAX_WINDOWS} windows ({:.3e} revolutions, stage {})",
                    st.cycles,
                    st.stage.name()
                ));
            }
        }
        let end = st.cycles.max(1.0);
        let pts = raw
            .into_iter()
            .map(|(c, s)| LifePoint {
                t: c / end,
                rms: s.rms,
                kurtosis: s.kurtosis,
                crest: s.crest_factor,
                skewness: s.skewness,
            })
            .collect();
        Ok((pts, end))
    }

    /// The life with effects `fx`, from the cache when it was run before; `sims` counts
    /// the lives actually run.
    pub fn points(&self, fx: &Effects, sims: &AtomicUsize) -> Result<Arc<Vec<LifePoint>>, String> {
        if let Ok(c) = self.cache.lock() {
            if let Some((_, p)) = c.iter().find(|(e, _)| e == fx) {
                return Ok(p.clone());
            }
        }
        sims.fetch_add(1, Ordering::Relaxed);
        let (p, _) = self.run(fx)?;
        let p = Arc::new(p);
        if let Ok(mut c) = self.cache.lock() {
            if c.len() >= CACHE {
                c.remove(0);
            }
            c.push((*fx, p.clone()));
        }
        Ok(p)
    }
}

/// One measured life held against the shared simulated life.
#[derive(Debug, Clone)]
pub struct LifeTarget {
    /// Measured cells.
    pub reference: LifeReference,
    /// The simulated life (shared).
    pub sim: Arc<LifeSim>,
    /// Only these cells count (indices into the reference), re-weighted so that their
    /// stages count equally; `None`: every cell.
    pub only: Option<Vec<usize>>,
}

impl LifeTarget {
    /// The same life restricted to the stages that end by `t_max` (the early-life part),
    /// or `None` when it has none.
    pub fn early(&self, t_max: f64) -> Option<LifeTarget> {
        let idx: Vec<usize> = self
            .reference
            .names
            .iter()
            .enumerate()
            .filter(|(_, (_, stg, _))| {
                STAGES.iter().any(|s| {
                    s.name == *stg && s.hi <= t_max + 1e-9 && s.name != STAGES[STEADY].name
                })
            })
            .map(|(i, _)| i)
            .collect();
        (!idx.is_empty()).then(|| LifeTarget {
            reference: self.reference.clone(),
            sim: self.sim.clone(),
            only: Some(idx),
        })
    }
}

impl LifeTarget {
    /// [`LifeReference::noise_only`] on the cells that count.
    pub fn noise_only(&self, sim: &[LifePoint]) -> f64 {
        let Some(idx) = &self.only else {
            return self.reference.noise_only(sim);
        };
        let pick =
            |v: &[usize]| -> Vec<usize> { idx.iter().filter_map(|i| v.get(*i).copied()).collect() };
        let names: Vec<(String, &'static str, &'static str)> = idx
            .iter()
            .filter_map(|i| self.reference.names.get(*i).cloned())
            .collect();
        let sub = LifeReference {
            weight: super::group_weights(&names),
            count: pick(&self.reference.count),
            names,
            ..self.reference.clone()
        };
        sub.noise_only(sim)
    }
}

/// Noise-only total gap of a set of lives: root mean square over the lives.
fn noise_only(targets: &[LifeTarget], sim: &[LifePoint]) -> f64 {
    let n = targets.len().max(1) as f64;
    (targets
        .iter()
        .map(|t| t.noise_only(sim).powi(2))
        .sum::<f64>()
        / n)
        .sqrt()
}

/// A gap counts as outside the sampling variability when it is at least this many times
/// the noise-only gap (as 1.5 is for records of seconds, about 4× their measured
/// noise-only gap of 0.38).
pub const SIGNIFICANCE: f64 = 3.0;

impl Target for LifeTarget {
    fn gaps(&self, fx: &Effects, sims: &AtomicUsize) -> Result<(Vec<f64>, Vec<f64>), String> {
        let p = self.sim.points(fx, sims)?;
        let v = self.reference.values(&p)?;
        let r = self.reference.residuals(&v);
        let Some(idx) = &self.only else {
            return Ok((r, self.reference.weight.clone()));
        };
        let names: Vec<(String, &'static str, &'static str)> = idx
            .iter()
            .filter_map(|i| self.reference.names.get(*i).cloned())
            .collect();
        let g = idx.iter().filter_map(|i| r.get(*i).copied()).collect();
        Ok((g, super::group_weights(&names)))
    }
}

fn fp(name: &'static str, lo: f64, hi: f64, log: bool) -> FitParam {
    FitParam { name, lo, hi, log }
}

/// The candidate effects whose signature can lie along a life, with their fit spaces.
/// `steady_rms` is the baseline life's steady RMS (m/s²), the scale of the sensor floor.
///
/// * `running-in`: summit contacts 0.01–300 per revolution (log), summit height 0.1–5 µm
///   (log), decaying over 10⁴–2·10⁶ revolutions (log; at most a tenth of the
///   2·10⁷-revolution life, so that it stays an early-life effect and is not a constant
///   level in disguise); the roughness factor is held at 1. The measured early excess of
///   IMS test 2 is impulsive — crest factor +0.5–0.7 and kurtosis +0.1–0.6 in the first
///   1 % on all four bearings, RMS unchanged on three of them — which the summits give
///   and a scaled Gaussian roughness cannot (it raises RMS first).
/// * `roughness`: scale 0.1–20 (log), the whole life.
/// * `sensor`: a background floor (other machinery, the sensor) of 1–300 % of the
///   bearing's steady RMS (log), no hum: it sets how far a defect rises above the rest.
/// * `edge-shape`: length scale 0.2–5 (log) and asperity scale 0–5 of every defect the
///   wear machine grows: how impulsive the late life is.
///
/// Effects that act within a snapshot only (slip, speed fluctuation, shaft harmonics,
/// transfer path, load zone) change no statistic along life that these cells resolve;
/// they are diagnosed on the raw records (`wearsim gap` on CWRU files).
pub fn life_spaces(steady_rms: f64) -> Vec<FitSpace> {
    let r = steady_rms.max(1e-6);
    // Roughness and edge-shape as for records of seconds (their ranges do not depend on
    // the record); a life grows its own defects, so edge-shape needs none to start with.
    let stationary = super::space::spaces(&super::space::Context {
        fs: 20_000.0,
        shaft_hz: 2000.0 / 60.0,
        rms: r,
        mains_hz: 60.0,
    });
    let shared = |name: &str| {
        stationary
            .iter()
            .find(|s| s.effect == name)
            .cloned()
            .map(|s| FitSpace {
                needs_defect: false,
                ..s
            })
    };
    let running_in = FitSpace {
        effect: "running-in",
        fitted: vec![
            fp("summits", 0.01, 300.0, true),
            fp("summit_height", 0.1, 5.0, true),
            fp("decay_revs", 1.0e4, 2.0e6, true),
        ],
        fixed: vec![("factor", 1.0), ("start_revs", 0.0)],
        needs_defect: false,
        note: "summits of the new surface, flattened over the first revolutions",
    };
    let sensor = FitSpace {
        effect: "sensor",
        fitted: vec![fp("noise", 0.01 * r, 3.0 * r, true)],
        fixed: vec![("hum", 0.0), ("corner_hz", 0.0)],
        needs_defect: false,
        note: "background floor (other machinery, sensor), scaled to the bearing's steady RMS",
    };
    [
        Some(running_in),
        shared("roughness"),
        Some(sensor),
        shared("edge-shape"),
    ]
    .into_iter()
    .flatten()
    .collect()
}

/// Calibrates the life factor so that the simulated baseline life lasts `target`
/// revolutions within 1 %: proportional steps (the factor scales the fatigue part, most of
/// the life; the rest makes the steps converge geometrically), as `wearsim ims-compare`
/// calibrates its life. Returns the factor, the life's revolutions and the lives run.
pub fn calibrate(preset: &str, seed: u64, target: f64) -> Result<(f64, f64, usize), String> {
    let mut a = 1.0;
    let mut runs = 0;
    // The schedule needs an expected life; the first run uses the target.
    let mut life = {
        let s = LifeSim::new(preset, a, seed, target)?;
        runs += 1;
        s.run(&Effects::NONE)?.1
    };
    for _ in 0..8 {
        if (life / target - 1.0).abs() < 0.01 {
            break;
        }
        // The factor scales fatigue up to crack opening; the rest is about a tenth of a
        // calibrated life. Scale the whole life, then refine.
        a *= (target / life).clamp(1e-6, 1e6);
        let s = LifeSim::new(preset, a, seed, target)?;
        runs += 1;
        life = s.run(&Effects::NONE)?.1;
    }
    if (life / target - 1.0).abs() > 0.05 {
        return Err(format!(
            "the life factor did not converge: {life:.3e} revolutions against the measured {target:.3e}"
        ));
    }
    Ok((a, life, runs))
}

/// Gap of one stage: root mean square of its cells' gaps, before and after.
#[derive(Debug, Clone, Serialize)]
pub struct StageGap {
    /// Stage name.
    pub stage: String,
    /// Its span of normalised life.
    pub span: (f64, f64),
    /// RMS of the cell gaps of the baseline (over the records that have the stage).
    pub before: f64,
    /// RMS of the cell gaps with the final model.
    pub after: f64,
    /// The cell with the largest baseline gap, its simulated and measured value.
    pub worst: (String, f64, f64, f64),
}

/// One cell of one life, before and after ("where").
#[derive(Debug, Clone, Serialize)]
pub struct LifeCell {
    /// Record (file and bearing).
    pub record: String,
    /// `train` or `holdout`.
    pub role: String,
    /// Cell name `life:<stage>:<stat>`.
    pub cell: String,
    /// Stage.
    pub stage: String,
    /// Unit (`dB` or `-`).
    pub unit: String,
    /// Simulated value, baseline.
    pub sim: f64,
    /// Simulated value, final model.
    pub sim_after: f64,
    /// Measured value.
    pub real: f64,
    /// Measured spread (floored).
    pub spread: f64,
    /// Gap of the baseline.
    pub gap: f64,
    /// Gap of the final model.
    pub gap_after: f64,
}

fn life_cells(
    role: &str,
    targets: &[LifeTarget],
    before: &[LifePoint],
    after: &[LifePoint],
) -> Vec<LifeCell> {
    let mut out = vec![];
    for t in targets {
        let r = &t.reference;
        let (Ok(b), Ok(a)) = (r.values(before), r.values(after)) else {
            continue;
        };
        let (gb, ga) = (r.residuals(&b), r.residuals(&a));
        for (i, (name, stg, unit)) in r.names.iter().enumerate() {
            let get = |v: &[f64]| v.get(i).copied().unwrap_or(f64::NAN);
            out.push(LifeCell {
                record: r.label.clone(),
                role: role.to_string(),
                cell: name.clone(),
                stage: stg.to_string(),
                unit: unit.to_string(),
                sim: get(&b),
                sim_after: get(&a),
                real: get(&r.mean),
                spread: get(&r.spread),
                gap: get(&gb),
                gap_after: get(&ga),
            });
        }
    }
    out
}

/// What one effect alone does to the early-life part of the held-out gap.
#[derive(Debug, Clone, Serialize)]
pub struct EarlyShrink {
    /// Effect.
    pub effect: String,
    /// Its parameters fitted on the training life's early stages.
    pub params: Vec<super::fit::FittedParam>,
    /// Held-out early-life gap (total over the early stages' cells) with the effect.
    pub gap: f64,
    /// `1 − gap / baseline early gap`.
    pub shrink: f64,
}

/// The lifetime diagnosis.
#[derive(Debug, Clone, Serialize)]
pub struct LifeGap {
    /// Training life.
    pub train: Vec<String>,
    /// Held-out lives.
    pub holdout: Vec<String>,
    /// Calibrated life factor and what it was calibrated on.
    pub life_factor: f64,
    /// Revolutions of the measured (training) life.
    pub measured_revs: f64,
    /// Stages ranked by their baseline gap on the training life ("where along life").
    pub stages_train: Vec<StageGap>,
    /// Stages of the held-out lives.
    pub stages_holdout: Vec<StageGap>,
    /// Held-out early-life gap of the baseline (total over the cells of the stages
    /// before [`EARLY_T_MAX`]).
    pub early_before: f64,
    /// Held-out early-life gap of the final model.
    pub early_after: f64,
    /// Each effect alone on the early-life part, best first.
    pub early: Vec<EarlyShrink>,
    /// The effect that closes the early-life part (largest early shrink ≥ 5 %, on an
    /// early gap outside the variability), if any.
    pub early_effect: Option<String>,
    /// Findings of the early-life attribution.
    pub early_findings: Vec<String>,
    /// Noise-only held-out gap of the whole life and of its early part: what a correct
    /// model would leave by sampling alone ([`LifeReference::noise_only`]).
    pub noise_only: (f64, f64),
    /// Every cell of every life, ranked by |baseline gap| ("where").
    pub cells: Vec<LifeCell>,
    /// Ranking, greedy addition, totals (held-out over the shared stages).
    pub attribution: Attribution,
    /// Leave-one-out checks on the final model.
    pub leave_one_out: Vec<LeaveOneOut>,
    /// Baseline and final simulated series (for the plots).
    pub series: Vec<(String, Vec<LifePoint>)>,
    /// Measured series (training first).
    pub measured: Vec<(String, Vec<LifePoint>)>,
    /// Lives simulated in all.
    pub simulations: usize,
    /// Wall-clock time (s).
    pub seconds: f64,
}

fn stage_gaps(targets: &[LifeTarget], g: &Gaps, after: &Gaps, sims: &[Vec<f64>]) -> Vec<StageGap> {
    let mut out: Vec<StageGap> = vec![];
    let mut off = 0;
    for (k, t) in targets.iter().enumerate() {
        let r = &t.reference;
        for (i, (name, stg, _)) in r.names.iter().enumerate() {
            let (Some(b), Some(a)) = (g.gaps.get(off + i), after.gaps.get(off + i)) else {
                continue;
            };
            let sim = sims
                .get(k)
                .and_then(|s| s.get(i))
                .copied()
                .unwrap_or(f64::NAN);
            let real = r.mean.get(i).copied().unwrap_or(f64::NAN);
            let span = STAGES
                .iter()
                .find(|s| s.name == *stg)
                .map_or((0.0, 1.0), |s| (s.lo, s.hi));
            match out.iter_mut().find(|s| s.stage == *stg) {
                Some(s) => {
                    s.before += b * b;
                    s.after += a * a;
                    if b.abs() > s.worst.3.abs() {
                        s.worst = (name.clone(), sim, real, *b);
                    }
                }
                None => out.push(StageGap {
                    stage: stg.to_string(),
                    span,
                    before: b * b,
                    after: a * a,
                    worst: (name.clone(), sim, real, *b),
                }),
            }
        }
        off += r.names.len();
    }
    // Mean square → root mean square over the stage's cells of every record.
    for s in &mut out {
        let n = targets
            .iter()
            .map(|t| {
                t.reference
                    .names
                    .iter()
                    .filter(|(_, g, _)| *g == s.stage)
                    .count()
            })
            .sum::<usize>()
            .max(1) as f64;
        s.before = (s.before / n).sqrt();
        s.after = (s.after / n).sqrt();
    }
    out.sort_by(|a, b| b.before.total_cmp(&a.before));
    out
}

/// Options of the lifetime diagnosis.
#[derive(Debug, Clone)]
pub struct LifeOptions {
    /// Training bearing (1-based).
    pub train: usize,
    /// Held-out bearings.
    pub holdout: Vec<usize>,
    /// Seed of the simulated life.
    pub seed: u64,
    /// Worker threads.
    pub jobs: usize,
    /// Candidate effects to try (empty: all of [`life_spaces`]).
    pub effects: Vec<String>,
    /// Withhold each added effect from the final model and diagnose again.
    pub leave_one_out: bool,
}

/// The measured side of a lifetime diagnosis, read and checked before any simulation:
/// every problem here is one of the input (a bearing not in the table, too few snapshots).
#[derive(Debug, Clone)]
pub struct MeasuredSet {
    /// Training life.
    pub train: MeasuredLife,
    /// Its cells over the whole life.
    pub train_ref: LifeReference,
    /// Held-out lives.
    pub holdout: Vec<MeasuredLife>,
    /// Their cells before [`HOLDOUT_T_MAX`].
    pub holdout_ref: Vec<LifeReference>,
}

fn label(m: &MeasuredLife) -> String {
    format!(
        "{} bearing {}",
        Path::new(&m.file)
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned()),
        m.bearing
    )
}

/// Reads the training and held-out lives of `path` and builds their cells.
pub fn measured(path: &Path, o: &LifeOptions) -> Result<MeasuredSet, String> {
    let train = read_life(path, o.train)?;
    let holdout: Vec<MeasuredLife> = o
        .holdout
        .iter()
        .map(|b| read_life(path, *b))
        .collect::<Result<_, _>>()?;
    if holdout.is_empty() {
        return Err("--holdout: give at least one held-out bearing".into());
    }
    let train_ref = LifeReference::new(&label(&train), &train.points, 1.0)?;
    let holdout_ref = holdout
        .iter()
        .map(|m| LifeReference::new(&label(m), &m.points, HOLDOUT_T_MAX))
        .collect::<Result<_, _>>()?;
    Ok(MeasuredSet {
        train,
        train_ref,
        holdout,
        holdout_ref,
    })
}

/// Diagnoses the gap along life of measured lives `m` (see the module docs).
pub fn diagnose(m: &MeasuredSet, o: &LifeOptions) -> Result<LifeGap, String> {
    let t0 = std::time::Instant::now();
    let (train_life, hold_lives) = (&m.train, &m.holdout);
    let shaft_hz = wearsim_core::presets::by_name("ims-za2115")
        .ok_or("preset ims-za2115 missing")?
        .speed
        .shaft_hz(0.0);
    let measured_revs = train_life.hours * 3600.0 * shaft_hz;
    let (factor, revs, cal_runs) = calibrate("ims-za2115", o.seed, measured_revs)?;
    let sim = Arc::new(LifeSim::new("ims-za2115", factor, o.seed, revs)?);
    let train = vec![LifeTarget {
        reference: m.train_ref.clone(),
        sim: sim.clone(),
        only: None,
    }];
    let hold: Vec<LifeTarget> = m
        .holdout_ref
        .iter()
        .map(|r| LifeTarget {
            reference: r.clone(),
            sim: sim.clone(),
            only: None,
        })
        .collect();
    let ev = Evaluator::new(o.jobs);
    let base = sim.points(&Effects::NONE, ev.counter())?;
    let steady = stage_points(&base, &STAGES[STEADY]);
    let steady_rms = upper_median(steady.iter().map(|p| p.rms).collect()).unwrap_or(1.0);
    let spaces: Vec<FitSpace> = life_spaces(steady_rms)
        .into_iter()
        .filter(|s| o.effects.is_empty() || o.effects.iter().any(|e| e == s.effect))
        .collect();
    if spaces.is_empty() {
        return Err(format!(
            "--effects: none of {:?} acts along a life; the lifetime candidates are running-in, roughness, sensor, edge-shape",
            o.effects
        ));
    }
    let noise_whole = noise_only(&hold, &base);
    let opt = Options {
        budget: Budget::LIFE,
        significant_gap: SIGNIFICANCE * noise_whole,
        ..Options::default()
    };
    let at = attribute(&spaces, &Effects::NONE, &train, &hold, &ev, &opt)?;
    // The early-life part: the same attribution on the early stages' cells only (their
    // contrasts to the steady stage), fitted on the training life's early stages and
    // judged on the held-out lives' — ranked by the shrink in the cells where that part
    // of the gap lies.
    let train_e: Vec<LifeTarget> = train.iter().filter_map(|t| t.early(EARLY_T_MAX)).collect();
    let hold_e: Vec<LifeTarget> = hold.iter().filter_map(|t| t.early(EARLY_T_MAX)).collect();
    if train_e.is_empty() || hold_e.is_empty() {
        return Err("the lives have no early stages with enough snapshots".into());
    }
    let noise_early = noise_only(&hold_e, &base);
    let early_opt = Options {
        max_effects: 1,
        significant_gap: SIGNIFICANCE * noise_early,
        ..opt
    };
    let early_at = attribute(&spaces, &Effects::NONE, &train_e, &hold_e, &ev, &early_opt)?;
    let early_before = early_at.baseline_holdout;
    let early: Vec<EarlyShrink> = early_at
        .ranking
        .iter()
        .map(|r| EarlyShrink {
            effect: r.effect.clone(),
            params: r.params.clone(),
            gap: r.holdout_gap,
            shrink: r.shrink,
        })
        .collect();
    // An early life within the snapshots' own variability needs no effect: naming one
    // would be a ranking with false confidence.
    let early_effect = early_at
        .identified
        .clone()
        .filter(|_| early_before >= early_opt.significant_gap);
    let early_findings = early_at.findings.clone();
    let loo = if o.leave_one_out {
        leave_one_out(
            &spaces,
            &at.final_effects,
            &at.kept,
            &train,
            &hold,
            &ev,
            &opt,
        )?
    } else {
        vec![]
    };
    let train_before = ev.residuals(&train, &Effects::NONE)?;
    let train_after = ev.residuals(&train, &at.final_effects)?;
    let fin = sim.points(&at.final_effects, ev.counter())?;
    let vals = |ts: &[LifeTarget], p: &[LifePoint]| -> Vec<Vec<f64>> {
        ts.iter()
            .map(|t| t.reference.values(p).unwrap_or_default())
            .collect()
    };
    let mut cells = life_cells("train", &train, &base, &fin);
    cells.extend(life_cells("holdout", &hold, &base, &fin));
    cells.sort_by(|a, b| b.gap.abs().total_cmp(&a.gap.abs()));
    let hold_e_final = ev.residuals(&hold_e, &at.final_effects)?;
    let early_after = hold_e_final.total();
    let mut at = at;
    at.simulations = ev.sims();
    Ok(LifeGap {
        train: vec![label(train_life)],
        holdout: hold_lives.iter().map(label).collect(),
        life_factor: factor,
        measured_revs,
        stages_train: stage_gaps(&train, &train_before, &train_after, &vals(&train, &base)),
        stages_holdout: stage_gaps(
            &hold,
            &at.holdout_before,
            &at.holdout_after,
            &vals(&hold, &base),
        ),
        early_before,
        early_after,
        early,
        early_effect,
        early_findings,
        noise_only: (noise_whole, noise_early),
        cells,
        attribution: at,
        leave_one_out: loo,
        series: vec![
            ("baseline".into(), base.to_vec()),
            ("final model".into(), fin.to_vec()),
        ],
        measured: std::iter::once(train_life)
            .chain(hold_lives)
            .map(|m| (label(m), m.points.clone()))
            .collect(),
        simulations: ev.sims() + cal_runs,
        seconds: t0.elapsed().as_secs_f64(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A steady life of `n` snapshots with RMS 1, kurtosis 3, crest 4, skewness 0, and a
    /// bump `db` dB, `dk` in kurtosis in the first 1 %.
    fn series(n: usize, db: f64, dk: f64) -> Vec<LifePoint> {
        (0..n)
            .map(|i| {
                let t = i as f64 / (n - 1) as f64;
                let early = t < 0.01;
                // A small deterministic scatter so that spreads are defined.
                let w = 1.0 + 0.01 * ((i * 7919 % 13) as f64 - 6.0) / 6.0;
                LifePoint {
                    t,
                    rms: w * if early { 10f64.powf(db / 20.0) } else { 1.0 },
                    kurtosis: 3.0 * w + if early { dk } else { 0.0 },
                    crest: 4.0 * w,
                    skewness: 0.0,
                }
            })
            .collect()
    }

    #[test]
    fn stage_cells_hold_the_steady_level_and_contrasts_elsewhere() {
        let r = LifeReference::new("synthetic", &series(1000, 1.0, 0.5), 1.0).expect("cells");
        let get = |name: &str| {
            r.names
                .iter()
                .position(|(n, _, _)| n == name)
                .map(|i| r.mean[i])
                .expect(name)
        };
        // 7 stages × 4 statistics, less the steady stage's RMS (the unit of the others).
        assert_eq!(r.names.len(), 27);
        assert!((get("life:running-in:rms") - 1.0).abs() < 0.05);
        assert!((get("life:running-in:kurtosis") - 0.5).abs() < 0.02);
        assert!(get("life:early:rms").abs() < 0.05);
        assert!((get("life:steady:kurtosis") - 3.0).abs() < 0.02);
        assert!((r.weight.iter().map(|w| w * w).sum::<f64>() - 1.0).abs() < 1e-12);
        // A simulation equal to the measurement has no gap.
        let v = r.values(&series(1000, 1.0, 0.5)).expect("values");
        assert!(r.residuals(&v).iter().all(|g| g.abs() < 1e-9));
    }

    #[test]
    fn noise_only_gap_is_the_sampling_error_of_stage_means() {
        let m = series(1000, 0.0, 0.0);
        let r = LifeReference::new("synthetic", &m, 1.0).expect("cells");
        // Same number of simulated windows as measured snapshots in every stage: each
        // cell's gap variance is 2/n, so the total is √(Σ w² · 2/n).
        let expect: f64 = r
            .weight
            .iter()
            .zip(&r.count)
            .map(|(w, n)| w * w * 2.0 / *n as f64)
            .sum::<f64>()
            .sqrt();
        assert!((r.noise_only(&m) - expect).abs() < 1e-12);
        // A sparser simulation leaves more.
        let sparse: Vec<LifePoint> = m.iter().step_by(10).copied().collect();
        assert!(r.noise_only(&sparse) > 2.0 * expect);
    }

    #[test]
    fn too_few_snapshots_in_a_stage_is_an_error_naming_it() {
        let e = LifeReference::new("short", &series(150, 0.0, 0.0), 1.0).unwrap_err();
        assert!(e.contains("running-in stage"), "{e}");
    }

    #[test]
    fn life_spaces_are_the_four_effects_that_act_along_a_life() {
        let s = life_spaces(1.0);
        let names: Vec<&str> = s.iter().map(|s| s.effect).collect();
        assert_eq!(names, ["running-in", "roughness", "sensor", "edge-shape"]);
        assert!(s.iter().all(|s| !s.needs_defect));
        let rough = &s[1].fitted[0];
        assert_eq!(
            (rough.name, rough.lo, rough.hi, rough.log),
            ("scale", 0.1, 20.0, true)
        );
        let edge: Vec<(&str, f64, f64)> =
            s[3].fitted.iter().map(|f| (f.name, f.lo, f.hi)).collect();
        assert_eq!(
            edge,
            [("length_scale", 0.2, 5.0), ("asperity_scale", 0.0, 5.0)]
        );
        // Every space applies cleanly at both ends of its ranges.
        for sp in &s {
            for u in [0.0, 1.0] {
                let mut fx = Effects::NONE;
                sp.apply(&mut fx, &vec![u; sp.fitted.len()])
                    .expect(sp.effect);
            }
        }
    }
}
