//! What a twin experiment reports ([`super::validate::validate`]): each trial, the
//! per-effect rates, detection power against strength, and the confounded sets' angle as a
//! trade-off ([`AngleRow`]).

use super::nuisance::Calibration;
use serde::Serialize;

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
    /// The twin's mismatch factors (name, factor; empty without mismatch).
    pub mismatch: Vec<(String, f64)>,
    /// The rig as the diagnosis calibrated it on the training run (compare with
    /// `mismatch`); `null` without calibration.
    pub calibration: Option<Calibration>,
    /// The out-of-library mechanism's parameters, when the twin has one.
    pub outside: Option<Vec<(String, f64)>>,
    /// Strength of what was withheld: the total gap between a third, independent run of
    /// the twin and the twin's own configuration without the withheld effects (or the
    /// out-of-library mechanism), over the noise-only gap. For the report only: nothing
    /// is redrawn or chosen on it.
    pub strength: f64,
    /// Each withheld effect's own strength, in the order of `withheld`: the total gap
    /// between the third run and the twin's configuration with the *other* withheld
    /// effects at their true values (× the noise-only gap), i.e. what is left for this
    /// effect to explain once the others are known. Equal to `strength` for one effect.
    pub strengths: Vec<f64>,
    /// Every other ranked effect against the first-ranked one: the angle of the first's
    /// signature to its subspace (degrees; below [`super::identify::CONFOUND_DEG`] and
    /// with both shrinks at least the minimum it joins the reported set) and its own
    /// validation shrink, so that the sets another angle would give can be recomputed
    /// from the report. Empty when nothing is ranked first.
    pub first_angles: Vec<Reproducer>,
    /// Effects the greedy addition kept.
    pub kept: Vec<String>,
    /// Each kept effect's reported set: the effect and the candidates confounded with it
    /// where it was added (the first: its ranking entry's `confounded_with`; a later one:
    /// its greedy step's, [`super::identify::step_set`]), in the order of [`Self::kept`].
    pub kept_sets: Vec<Vec<String>>,
    /// Exchanges made after the greedy additions (`--exchange`; empty without it).
    pub exchanged: Vec<super::exchange::Exchanged>,
    /// Held-out total gap of the final (greedy) model.
    pub final_gap: f64,
    /// The final model closes the gap: its held-out total is within [`DETECTABLE`] × the
    /// noise-only gap.
    pub closed: bool,
    /// Draws before this one that the model refused (a configuration outside what it
    /// can integrate at the scenario's rate); such draws are drawn again.
    pub refused: usize,
}

/// Another ranked effect seen from the first-ranked one ([`Trial::first_angles`]).
#[derive(Debug, Clone, Serialize)]
pub struct Reproducer {
    /// Effect name.
    pub effect: String,
    /// Angle (degrees) between the first-ranked effect's signature and this effect's
    /// signature subspace.
    pub angle_deg: f64,
    /// This effect's validation shrink, alone on the baseline.
    pub shrink: f64,
    /// Norm of the part of the first-ranked effect's signature that this effect's
    /// subspace leaves (total-gap units, `|d| · sin angle`): this effect reproduces the
    /// first only when it is under the first's resolution (`identify::resolution`: the
    /// significance level, or the first's own validation gap when larger).
    pub residual: f64,
}

/// A withheld effect counts as detectable when its strength ([`Trial::strength`]) is at
/// least this multiple of the noise-only gap
/// ([`TwinReport::noise_only_gap`]); the same multiple of the noise-only gap left after
/// the final model counts as a gap the library did not close.
pub const DETECTABLE: f64 = 2.0;

/// Edges of the strength bins of the detection-power table (multiples of the noise-only
/// gap).
pub const STRENGTH_BINS: [f64; 5] = [0.0, 1.0, 2.0, 4.0, 8.0];

/// Detection power in one band of effect strength (single-effect trials).
#[derive(Debug, Clone, Serialize)]
pub struct PowerBin {
    /// Lower edge of the strength band (× noise-only gap; the band ends at the next edge).
    pub from: f64,
    /// Trials whose strength is in the band.
    pub trials: usize,
    /// Of them, trials whose reported set holds the withheld effect.
    pub in_set: usize,
}

/// The detectable single-effect trials' figures had the confounded sets been formed at
/// another angle ([`TwinReport::set_angles`]; the sets recomputed from each trial's
/// [`Trial::first_angles`], the rule of [`super::identify::reproducers`]).
#[derive(Debug, Clone, Serialize)]
pub struct AngleRow {
    /// Angle (degrees) below which an effect joins the first-ranked one's set.
    pub angle_deg: f64,
    /// Detectable single-effect trials whose set would hold the truth, of `detectable`.
    pub in_set: usize,
    /// Detectable single-effect trials.
    pub detectable: usize,
    /// The lowest per-effect fraction in the set.
    pub worst_effect_in_set: f64,
    /// The largest per-effect mean set size.
    pub largest_mean_set_size: f64,
}

/// Angles of the [`AngleRow`] curve (degrees); 25 is [`super::identify::CONFOUND_DEG`].
pub const SET_ANGLES: [f64; 9] = [5.0, 10.0, 12.5, 15.0, 17.5, 20.0, 25.0, 35.0, 45.0];

/// The set a trial would report with the angle `deg`: the first-ranked effect and every
/// other effect within `deg` of reproducing it, leaving less of its signature than its
/// resolution from the significance level `level` (`identify::resolution`), that shrinks
/// the validation gap by at least `min_shrink` (the first one's shrink is at least that
/// whenever it is named).
fn set_at(t: &Trial, deg: f64, min_shrink: f64, level: f64) -> Vec<&str> {
    let Some(first) = t.ranked_first.as_deref() else {
        return vec![];
    };
    let level = super::identify::resolution(level, t.after);
    let mut v = vec![first];
    v.extend(
        t.first_angles
            .iter()
            .filter(|r| r.angle_deg < deg && r.residual < level && r.shrink >= min_shrink)
            .map(|r| r.effect.as_str()),
    );
    v
}

/// The single-effect trials that withheld `effect`.
pub(super) fn single<'a>(trials: &'a [Trial], effect: &str) -> Vec<&'a Trial> {
    trials
        .iter()
        .filter(|t| t.withheld.len() == 1 && t.withheld.first().map(String::as_str) == Some(effect))
        .collect()
}

/// Those of `ts` whose withheld effect was detectable ([`DETECTABLE`]).
pub(super) fn detectable<'a>(ts: &[&'a Trial]) -> Vec<&'a Trial> {
    ts.iter()
        .copied()
        .filter(|t| t.strength >= DETECTABLE)
        .collect()
}

/// [`AngleRow`] for every angle of [`SET_ANGLES`] over the detectable single-effect trials
/// of `labels`.
pub(super) fn angle_curve(
    trials: &[Trial],
    labels: &[String],
    min_shrink: f64,
    level: f64,
) -> Vec<AngleRow> {
    SET_ANGLES
        .iter()
        .map(|&deg| {
            let (mut in_set, mut counted) = (0, 0);
            let (mut worst, mut largest) = (1.0f64, 0.0f64);
            for l in labels {
                let seen = detectable(&single(trials, l));
                if seen.is_empty() {
                    continue;
                }
                let sets: Vec<Vec<&str>> = seen
                    .iter()
                    .map(|t| set_at(t, deg, min_shrink, level))
                    .collect();
                let held = sets.iter().filter(|s| s.contains(&l.as_str())).count();
                in_set += held;
                counted += seen.len();
                worst = worst.min(held as f64 / seen.len() as f64);
                let size = sets.iter().map(Vec::len).sum::<usize>() as f64 / seen.len() as f64;
                largest = largest.max(size);
            }
            AngleRow {
                angle_deg: deg,
                in_set,
                detectable: counted,
                worst_effect_in_set: worst,
                largest_mean_set_size: largest,
            }
        })
        .collect()
}

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
    /// Trials whose reported set (first-ranked effect and its confounded set) holds it.
    pub in_set: usize,
    /// Mean size of the reported set over its trials (0 when nothing was named).
    pub mean_set_size: f64,
    /// Trials in which it was detectable ([`DETECTABLE`]).
    pub detectable: usize,
    /// Of those, trials whose reported set holds it.
    pub in_set_detectable: usize,
    /// Mean reported set size over the detectable trials.
    pub mean_set_size_detectable: f64,
}

/// The result of `gap-validate`.
#[derive(Debug, Clone, Serialize)]
pub struct TwinReport {
    /// Scenario the twins are built on.
    pub scenario: String,
    /// Held-out total gap of the baseline against twins without any withheld effect
    /// (median over trials): the floor of the gap measure itself.
    pub noise_only_gap: f64,
    /// The significance level this batch's no-effect twins imply
    /// ([`super::attribute::false_alarm_threshold`] at 5 %: the 95th percentile of their
    /// held-out gaps, rounded up to 0.1), to compare with the one in force
    /// ([`super::attribute::SIGNIFICANT_GAP`]) or to pass to `gap --significant-gap` for a
    /// rig of one's own; `null` with fewer than two no-effect twins.
    pub null_threshold: Option<f64>,
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
    /// Two-effect trials in which each withheld effect is detectable on its own
    /// ([`Trial::strengths`] ≥ [`DETECTABLE`]), and how many of them the greedy additions
    /// name exactly: the pair figure on the footing of the single-effect
    /// `in_set_detectable`.
    pub pairs_detectable: Option<(usize, usize)>,
    /// The detectable pairs of [`Self::pairs_detectable`] whose two greedy additions hold
    /// both withheld effects in their reported sets ([`Trial::kept_sets`]), as the
    /// single-effect `in_set_detectable` reads one, with the mean size of those sets per
    /// named effect over the detectable pairs.
    pub pairs_in_sets_detectable: Option<(usize, usize, f64)>,
    /// No-effect twins: trials, and how many the diagnosis attributed to an effect
    /// (the false-attribution rate is their ratio).
    pub null: Option<(usize, usize)>,
    /// Three-effect trials: trials, and the fraction whose greedy additions hold all three
    /// (the indistinguishable pair counted as one class).
    pub triples: Option<(usize, f64)>,
    /// Three-effect trials with every withheld effect detectable on its own, and how many
    /// of them the greedy additions name exactly.
    pub triples_detectable: Option<(usize, usize)>,
    /// Out-of-library twins: trials, and how many the final model left not closed.
    pub outside: Option<(usize, usize)>,
    /// Detection power against strength, over the single-effect trials.
    pub power: Vec<PowerBin>,
    /// The confounded sets' angle as a trade-off: the single-effect figures at each angle
    /// of [`SET_ANGLES`] (the report's own sets are those at
    /// [`super::identify::CONFOUND_DEG`]).
    pub set_angles: Vec<AngleRow>,
    /// The mismatch ranges the twins were drawn with.
    pub mismatch: String,
    /// Every trial.
    pub trials: Vec<Trial>,
    /// Simulations run.
    pub simulations: usize,
    /// Wall-clock time (s).
    pub seconds: f64,
}

/// Whether trial `t`'s reported set holds effect `e`.
pub(super) fn holds(t: &Trial, e: &str) -> bool {
    t.reported_set.iter().any(|x| x == e)
}

/// Mean reported set size over `ts` (0 for none).
pub(super) fn mean_size(ts: &[&Trial]) -> f64 {
    ts.iter().map(|t| t.reported_set.len()).sum::<usize>() as f64 / ts.len().max(1) as f64
}
