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
//! (which must have failed: its length calibrates the life factor) and judged on the
//! held-out lives. A held-out life that failed, or whose end is unknown, is judged over
//! its whole life, against a simulated life of its own failure site where the wear machine
//! grows it ([`sim::failure_site`]: outer race, inner race, rolling element). A life that
//! did not fail (`failure_mode` `none`) has no end of life: its time line is its test's,
//! not a life's, so it is judged only on the stages before [`HOLDOUT_T_MAX`] of its test.
//! On a table of a known IMS test ([`crate::io::ims_life::IMS_FAILURES`]) each bearing
//! is known to have failed or not: one that did not fail is refused as the training life
//! and, held out, is such a life (it ran on one shaft with the failed one, was new with it,
//! so its late stages carry the failing neighbour's vibration rather than its own wear);
//! the failed one held out is judged over its whole life. On a table of the IMS layout
//! from no known test, a held-out bearing's end is not known: it is judged on the stages
//! before [`HOLDOUT_T_MAX`] as well (its late stages may carry a neighbour's failure), and
//! the report does not say it did not fail.
//!
//! **The early-life part** is attributed again on the early stages' cells alone (their
//! contrasts to the steady stage), so that the steady level, which dominates the total,
//! cannot decide which effect explains the first hours. **Significance**: a cell compares a
//! stage mean of `n` measured snapshots with one of `m` simulated windows, so a correct
//! model leaves a gap of variance `1/n + 1/m` per cell by sampling alone
//! ([`LifeReference::noise_only`]); a gap counts from [`SIGNIFICANCE`] times that.

pub mod diagnose;
pub mod report;
pub mod rig;
pub mod sim;
pub mod tables;
pub mod target;

pub use crate::io::ims_life::{LifePoint, MeasuredLife};
pub use diagnose::{
    calibrated, diagnose, diagnose_calibrated, holdout_t_max, measured, measured_from, Calibration,
    EarlyShrink, LifeCell, LifeGap, LifeOptions, LifeSpan, MeasuredSet, StageGap,
};
pub use rig::RigDescription;
pub use sim::{LifeSim, MAX_WINDOWS, SCHEDULE, WINDOW_SAMPLES};
pub use tables::measured_tables;
pub use target::{life_spaces, LifeTarget, SIGNIFICANCE};

use crate::analysis::stats::{mean_std, upper_median};
use serde::Serialize;

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

/// Coarser early stages for a table too sparse for the fine ones (fewer than
/// [`MIN_SNAPSHOTS`] snapshots in the first 1 % or 3 % of its life: under 300 or 100
/// snapshots over the life, as most XJTU-SY lives): `start` (0–3 %) replaces running-in and
/// early, `first-tenth` (0–10 %) replaces those and settled. The stages from steady on
/// never merge ([`LifeReference::new`]).
pub const MERGED_EARLY: [LifeStage; 2] =
    [stage("start", 0.0, 0.03), stage("first-tenth", 0.0, 0.1)];

/// The stage called `name`, fine ([`STAGES`]) or merged ([`MERGED_EARLY`]).
pub fn stage_named(name: &str) -> Option<&'static LifeStage> {
    STAGES.iter().chain(&MERGED_EARLY).find(|s| s.name == name)
}

/// Stages before this fraction of life are the "early-life part" of the gap.
pub const EARLY_T_MAX: f64 = 0.1;

/// Held-out lives that did not fail are compared on the stages that end at or before
/// this fraction of the test (see the module docs).
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

/// Onset of instability of a life's snapshots, measured or simulated
/// ([`crate::life::ims::onset`] of their RMS over its early-life median; fraction of life).
pub fn onset(points: &[LifePoint]) -> Option<f64> {
    use crate::life::ims;
    ims::onset(&ims::normalise(
        points.iter().map(|p| p.t).collect(),
        points.iter().map(|p| p.rms).collect(),
    ))
}

fn in_stage(p: &LifePoint, s: &LifeStage) -> bool {
    p.t >= s.lo && (p.t < s.hi || (s.hi >= 1.0 && p.t <= 1.0))
}

/// Points of `pts` in stage `s`; when none falls inside (a sparse simulated schedule), the
/// one nearest to the stage's centre.
pub(super) fn stage_points<'a>(pts: &'a [LifePoint], s: &LifeStage) -> Vec<&'a LifePoint> {
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
    /// The merged early stage ([`MERGED_EARLY`]) that replaced the fine ones, if the table
    /// was too sparse for them.
    pub merged: Option<&'static str>,
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
    /// Cells of the measured series `pts` over the stages that end by `t_max`. Each needs
    /// at least [`MIN_SNAPSHOTS`] snapshots: where the first 1 % (or 3 %) of the life holds
    /// fewer, the early stages merge into [`MERGED_EARLY`]'s `start` (or `first-tenth`) and
    /// [`LifeReference::merged`] says so; a stage from steady on, or the first tenth, with
    /// fewer is an error naming it.
    pub fn new(label: &str, pts: &[LifePoint], t_max: f64) -> Result<Self, String> {
        let count = |s: &LifeStage| pts.iter().filter(|p| in_stage(p, s)).count();
        let mut stages: Vec<LifeStage> = STAGES
            .iter()
            .filter(|s| s.hi <= t_max + 1e-9)
            .copied()
            .collect();
        let mut merged = None;
        for m in MERGED_EARLY {
            let fine = stages.iter().take_while(|s| s.hi <= m.hi + 1e-12).count();
            let sparse = stages[..fine].iter().any(|s| count(s) < MIN_SNAPSHOTS);
            if sparse && fine >= 2 {
                stages.splice(..fine, [m]);
                merged = Some(m.name);
            }
        }
        for s in &stages {
            let n = count(s);
            if n < MIN_SNAPSHOTS {
                let what = if s.name == STAGES[STEADY].name {
                    " (the reference of every other stage)"
                } else {
                    ""
                };
                return Err(format!(
                    "{label}: fewer than {MIN_SNAPSHOTS} snapshots in the {} stage ({:.0}-{:.0} % of life){what}: it holds {n}; a life gap needs at least {MIN_SNAPSHOTS} in every stage from the first tenth of the life on (the finer early stages merge when the table cannot resolve them), i.e. at least about {} snapshots spread evenly over the life",
                    s.name,
                    100.0 * s.lo,
                    100.0 * s.hi,
                    (MIN_SNAPSHOTS as f64 / (s.hi - s.lo)).ceil()
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
            merged,
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
        let n_sim =
            |stage: &str| stage_named(stage).map_or(1, |s| stage_points(sim, s).len().max(1));
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

#[cfg(test)]
mod tests {
    use super::target::life_spaces;
    use super::*;
    use wearsim_core::effects::Effects;

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

    /// Stage names of a reference, in order.
    fn stage_names(r: &LifeReference) -> Vec<&'static str> {
        r.stages.iter().map(|s| s.name).collect()
    }

    #[test]
    fn a_sparse_table_merges_its_early_stages_and_keeps_the_rest() {
        let all = [
            "running-in",
            "early",
            "settled",
            "steady",
            "onset",
            "degradation",
            "end",
        ];
        let fine = LifeReference::new("fine", &series(400, 0.0, 0.0), 1.0).expect("cells");
        assert_eq!((stage_names(&fine), fine.merged), (all.to_vec(), None));
        // 150 snapshots: 2 in the first 1 % (an XJTU-SY life of that length).
        let r = LifeReference::new("xjtu", &series(150, 0.0, 0.0), 1.0).expect("cells");
        assert_eq!(r.merged, Some("start"));
        assert_eq!(stage_names(&r)[..2], ["start", "settled"]);
        assert_eq!(stage_names(&r)[2..], all[3..]);
        // 60 snapshots: 2 in the first 3 %.
        let r = LifeReference::new("short", &series(60, 0.0, 0.0), 1.0).expect("cells");
        assert_eq!(r.merged, Some("first-tenth"));
        assert_eq!(stage_names(&r)[0], "first-tenth");
        assert_eq!(stage_names(&r)[1..], all[3..]);
        // The merged stage carries the early bump as the fine ones did: +6 dB on the 2
        // snapshots of the first 1 %, 2 of the 5 in 0–3 %, is +2.4 dB on the stage mean.
        let r = LifeReference::new("bump", &series(150, 6.0, 0.0), 1.0).expect("cells");
        let i = r.names.iter().position(|(n, _, _)| n == "life:start:rms");
        let start = i.and_then(|i| r.mean.get(i)).copied().unwrap_or(f64::NAN);
        assert!((start - 6.0 * 2.0 / 5.0).abs() < 0.1, "{start}");
        // The held-out span of a life that did not fail merges the same way.
        let r = LifeReference::new("none", &series(150, 0.0, 0.0), 0.5).expect("cells");
        assert_eq!(stage_names(&r), ["start", "settled", "steady"]);
    }

    #[test]
    fn too_few_snapshots_in_a_stage_is_an_error_naming_it() {
        // 20 snapshots: 2 in the first tenth, which does not merge further.
        let e = LifeReference::new("short", &series(20, 0.0, 0.0), 1.0).unwrap_err();
        assert!(
            e.contains("first-tenth stage") && e.contains("about 30"),
            "{e}"
        );
        // A late stage never merges: a life whose last tenth holds 2 snapshots.
        let mut gap = series(1000, 0.0, 0.0);
        gap.retain(|p| p.t < 0.9 || p.t > 0.998);
        let e = LifeReference::new("gap", &gap, 1.0).unwrap_err();
        assert!(e.contains("end stage"), "{e}");
    }

    #[test]
    fn life_spaces_are_the_four_effects_that_act_along_a_life() {
        let s = life_spaces(1.0, 20_000.0, 2000.0 / 60.0);
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
