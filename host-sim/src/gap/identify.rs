//! Identifiability (issue 13; sim-to-real.md, "confounded sets"): can the cells tell two
//! candidate effects apart on this record?
//!
//! At each effect's fitted point the fit leaves its Jacobian `J` (cell gaps, in units of
//! each cell's measured spread, by the normalised parameters; [`super::fit::Fit`]) and its
//! signature `d` — the change of the training cell gaps from the baseline to the fitted
//! effect. Both are weighted as the total gap weights the cells (every group counts
//! equally). Effect `b` can *reproduce* effect `a` when `a`'s signature lies close to
//! `b`'s signature subspace `span(J_b, d_b)` at this record's noise: the angle between
//! `d_a` and its projection on that subspace is below [`CONFOUND_DEG`], **and** the part
//! of `d_a` the subspace leaves (`|d_a| sin angle`, total-gap units) is below the
//! finest difference the validation part resolves for `a` ([`resolution`]: the
//! diagnosis's significance level `significant_gap`, the level below which a gap is within
//! the measurement's own variability, or the validation gap `a` itself leaves when that is
//! larger) — the gap that would be left if `b` stood in for `a` is one the record could not
//! show. An effect whose fitted change is large is told apart from another at a smaller
//! angle than a weak one (stop 67: on twins the angle alone put strong transfer-path and
//! sensor fits in sets of two whose difference was several times the noise). Effect `a`'s
//! ranking is evidence for `a` only if no other effect that also shrinks the gap by at
//! least the minimum shrink can reproduce what `a` did; those that can are `a`'s
//! **confounded set**: the report names it and does not rank inside it.
//!
//! The relation is read in that one direction (stop 28; before, a pair counted when
//! *either* effect reproduced the other). `b` reproducing `a` undermines the evidence for
//! `a`; `a` reproducing `b` does not: a sensor whose fitted change is a noise floor is not
//! put in doubt by a shaft-harmonics effect just because the sensor's hum (60 Hz) could
//! mimic the 2× shaft line (59.9 Hz at 1797 rpm). The shaft-harmonics effect, ranked first,
//! still names the sensor, because the hum can reproduce its line.
//!
//! Method: principal angles between subspaces (Björck & Golub 1973, "Numerical methods for
//! computing angles between linear subspaces", Math. Comp. 27) reduced to one vector and a
//! subspace; the linearisation is the local sensitivity analysis of nonlinear least
//! squares (the same Jacobian as the parameters' uncertainty).

use super::attribution::Attribution;
use super::signature::{Reach, Signature};
use std::collections::BTreeMap;

/// Angle (degrees) between one effect's signature and another's signature subspace
/// below which the second can reproduce the first. 25°: the part the other effect
/// cannot reproduce is then under sin 25° ≈ 42 % of the signature's norm, i.e. under
/// ≈ 18 % of its energy. A prior, stated choice, measured on twin batches at stop 36
/// (`gap-validate`'s `set_angles`): a development batch (seed 45) chose 15°, the judging
/// batch (seed 43) lost 4 of 103 hits there and met neither target at any angle from 5°
/// to 45°, so it stays (docs/sim-to-real-results.md, "The confounded sets' angle").
pub const CONFOUND_DEG: f64 = 25.0;

/// Fills `confounded_with` of every ranked effect `a`: the other effects, both shrinking
/// the validation gap by at least `min_shrink`, that can reproduce `a`'s signature at its
/// [`resolution`] from the significance level `level` (total gap). Adds a finding naming
/// the confounded set of the first-ranked effect, and returns the reach of every pair
/// (`a → b`: `a`'s signature against `b`'s subspace) for the report.
pub fn confounded(at: &mut Attribution, min_shrink: f64, level: f64) -> BTreeMap<String, Reach> {
    let sigs: Vec<&Signature> = at.ranking.iter().map(|r| &r.signature).collect();
    let pairs = reaches(&sigs);
    let mut reach = BTreeMap::new();
    for (a, row) in at.ranking.iter().zip(&pairs) {
        for (b, r) in at.ranking.iter().zip(row) {
            if let Some(r) = r {
                reach.insert(format!("{} -> {}", a.effect, b.effect), *r);
            }
        }
    }
    let shrink: Vec<f64> = at.ranking.iter().map(|r| r.shrink).collect();
    let levels: Vec<f64> = at
        .ranking
        .iter()
        .map(|r| resolution(level, r.holdout_gap))
        .collect();
    let sets = reproducers(&pairs, &shrink, min_shrink, &levels);
    let names: Vec<String> = at.ranking.iter().map(|r| r.effect.clone()).collect();
    for (r, set) in at.ranking.iter_mut().zip(sets) {
        r.confounded_with = set
            .into_iter()
            .filter_map(|j| names.get(j).cloned())
            .collect();
    }
    if let Some(first) = at.ranking.first().filter(|r| r.shrink >= min_shrink) {
        if !first.confounded_with.is_empty() {
            let mut set = vec![first.effect.clone()];
            set.extend(first.confounded_with.iter().cloned());
            at.findings.push(format!(
                "confounded set {{{}}}: at the fitted point the others can each reproduce the first's cell signature (angle below {CONFOUND_DEG}°, leaving less of it than {}, the larger of the significance level and the gap the first leaves itself); the ranking inside the set is not evidence for either",
                set.iter().map(|e| format!("`{e}`")).collect::<Vec<_>>().join(", "),
                super::significance::level(resolution(level, first.holdout_gap))
            ));
        }
    }
    reach
}

/// The confounded set of one greedy step (stop 69): the step added candidate `chosen` of
/// `sigs` (every candidate's signature at its fit on top of the effects kept so far, against
/// that model's training gaps) with validation gap `gap`; the other candidates that also
/// shrink the validation gap by at least `min_shrink` (`shrink`, relative to the model
/// before the step) and can reproduce the chosen one's signature at its [`resolution`]
/// from `level` ([`reproduces`]). The relation [`confounded`] applies to effects alone,
/// applied where the step is: a second effect is judged beside the first it joins, not on
/// the baseline the first effect's gap dominates.
pub fn step_set(
    sigs: &[&Signature],
    shrink: &[f64],
    chosen: usize,
    gap: f64,
    min_shrink: f64,
    level: f64,
) -> Vec<usize> {
    let Some(a) = sigs.get(chosen) else {
        return vec![];
    };
    if shrink.get(chosen).is_none_or(|s| *s < min_shrink) {
        return vec![];
    }
    let level = resolution(level, gap);
    sigs.iter()
        .enumerate()
        .filter(|&(j, b)| {
            j != chosen
                && shrink.get(j).is_some_and(|s| *s >= min_shrink)
                && reproduces(a.against(b), level)
        })
        .map(|(j, _)| j)
        .collect()
}

/// Shrink of the validation gap of every ranked effect per cell group: `1 − rms(gaps with
/// the effect) / rms(baseline gaps)` over the cells of each group; `group[i]` names the
/// group of cell `i` of one record (cells repeat per record).
pub fn group_shrink(at: &mut Attribution, group: &[String]) {
    let n = group.len();
    if n == 0 {
        return;
    }
    let mut names: Vec<&String> = group.iter().collect();
    names.sort();
    names.dedup();
    let rms = |g: &[f64], name: &str| -> f64 {
        let v: Vec<f64> = g
            .iter()
            .enumerate()
            .filter(|(i, _)| group.get(i % n).is_some_and(|x| x == name))
            .map(|(_, x)| *x)
            .collect();
        super::total_gap(&v)
    };
    let base = at.holdout_before.gaps.clone();
    for r in &mut at.ranking {
        r.group_shrink = names
            .iter()
            .map(|g| {
                let b = rms(&base, g);
                let e = rms(&r.holdout.gaps, g);
                (g.to_string(), if b > 0.0 { 1.0 - e / b } else { 0.0 })
            })
            .collect();
    }
}

/// The finest difference (total gap) the validation part can resolve for an effect that
/// leaves a validation gap `gap` with its fit: the significance level `level` (the
/// measurement's own variability), or the effect's own misfit when that is larger — an
/// alternative that differs from the fitted effect by less than what the fitted effect
/// itself leaves unexplained cannot be ruled out by it (stop 67: twins whose rig mismatch
/// the fit absorbs).
pub fn resolution(level: f64, gap: f64) -> f64 {
    if gap.is_finite() {
        level.max(gap)
    } else {
        level
    }
}

/// Whether an effect whose signature has `reach` to another's subspace can be reproduced
/// by it at the resolution `level` ([`resolution`]): within [`CONFOUND_DEG`], leaving less
/// than `level` of the signature.
pub fn reproduces(reach: Reach, level: f64) -> bool {
    reach.angle_deg < CONFOUND_DEG && reach.residual < level
}

/// Every ordered pair's [`Reach`]: `reach[i][j]` is `sig[i]`'s signature against
/// `sig[j]`'s subspace ([`Signature::against`]); `None` on the diagonal.
pub fn reaches(sig: &[&Signature]) -> Vec<Vec<Option<Reach>>> {
    sig.iter()
        .enumerate()
        .map(|(i, a)| {
            sig.iter()
                .enumerate()
                .map(|(j, b)| (i != j).then(|| a.against(b)))
                .collect()
        })
        .collect()
}

/// For each effect `i`, the effects `j ≠ i` that can reproduce it: both shrink the
/// validation gap by at least `min_shrink` (`shrink[i]`, `shrink[j]`) and `i`'s signature
/// [`reproduces`] by `j`'s subspace (`reach[i][j]`, [`reaches`]) at `levels[i]`.
pub fn reproducers(
    reach: &[Vec<Option<Reach>>],
    shrink: &[f64],
    min_shrink: f64,
    levels: &[f64],
) -> Vec<Vec<usize>> {
    let strong = |i: usize| shrink.get(i).is_some_and(|s| *s >= min_shrink);
    reach
        .iter()
        .enumerate()
        .map(|(i, row)| {
            let level = levels.get(i).copied().unwrap_or(0.0);
            row.iter()
                .enumerate()
                .filter(|&(j, r)| strong(i) && strong(j) && r.is_some_and(|r| reproduces(r, level)))
                .map(|(j, _)| j)
                .collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sensor-like effect (fitted change: a noise floor, cell 0; its subspace also holds
    /// a hum line, cell 1) and a shaft-harmonics-like effect (change and subspace: the line,
    /// cell 1). The line can be reproduced by the sensor's hum, the noise floor not by the
    /// line: the sensor stands alone, the harmonics are confounded with the sensor.
    #[test]
    fn an_effect_is_confounded_only_with_the_effects_that_reproduce_it() {
        let sensor = Signature {
            d: vec![1.0, 0.05, 0.0],
            cols: vec![vec![1.0, 0.0, 0.0], vec![0.0, 1.0, 0.0]],
            records: 1,
        };
        let harmonics = Signature {
            d: vec![0.0, 1.0, 0.1],
            cols: vec![vec![0.0, 1.0, 0.0]],
            records: 1,
        };
        let weak = Signature {
            d: vec![1.0, 0.0, 0.0],
            cols: vec![vec![1.0, 0.0, 0.0]],
            records: 1,
        };
        let sets = reproducers(
            &reaches(&[&sensor, &harmonics, &weak]),
            &[0.5, 0.3, 0.01],
            0.05,
            &[1.5; 3],
        );
        assert_eq!(sets, vec![Vec::<usize>::new(), vec![0], vec![]]);
        // The weak effect reproduces the sensor exactly but shrinks too little to count;
        // with a lower minimum it joins the sensor's set (and the sensor its).
        let sets = reproducers(
            &reaches(&[&sensor, &harmonics, &weak]),
            &[0.5, 0.3, 0.01],
            0.0,
            &[1.5; 3],
        );
        assert_eq!(sets, vec![vec![2], vec![0], vec![0]]);
    }

    /// An effect 20° from another's subspace is reproduced by it while what the subspace
    /// leaves (|d| sin 20° = 0.34 |d|) is under the significance level, and told apart once
    /// its fitted change is large enough for the record to show that part: |d| = 2 leaves
    /// 0.68 (confounded at 1.5), |d| = 10 leaves 3.42 (not). The part is in total-gap units:
    /// over four training records it counts half (÷ √4).
    #[test]
    fn a_strong_signature_is_told_apart_at_an_angle_a_weak_one_is_not() {
        let (c, s) = (20f64.to_radians().cos(), 20f64.to_radians().sin());
        let at = |norm: f64, records: usize| Signature {
            d: vec![norm * c, norm * s, 0.0],
            cols: vec![vec![1.0, 0.0, 0.0]],
            records,
        };
        let other = Signature {
            d: vec![1.0, 0.0, 0.0],
            cols: vec![vec![1.0, 0.0, 0.0]],
            records: 1,
        };
        let r = at(10.0, 1).against(&other);
        assert!((r.angle_deg - 20.0).abs() < 1e-9, "{r:?}");
        assert!((r.residual - 10.0 * s).abs() < 1e-9, "{r:?}");
        let shrink = [0.3, 0.3];
        let pair = |a: &Signature| {
            reproducers(&reaches(&[a, &other]), &shrink, 0.05, &[1.5; 2])[0].clone()
        };
        assert_eq!(pair(&at(2.0, 1)), vec![1]);
        assert_eq!(pair(&at(10.0, 1)), Vec::<usize>::new());
        assert!((at(10.0, 4).against(&other).residual - 5.0 * s).abs() < 1e-9);
        // At 30° no strength makes it reproducible.
        let wide = Signature {
            d: vec![30f64.to_radians().cos(), 30f64.to_radians().sin(), 0.0],
            cols: vec![],
            records: 1,
        };
        assert_eq!(
            reproducers(&reaches(&[&wide, &other]), &shrink, 0.05, &[1.5; 2])[0],
            Vec::<usize>::new()
        );
        // An effect that leaves a validation gap of 4 cannot rule out what differs from it
        // by 3.42: its resolution is its own misfit.
        assert_eq!(resolution(1.5, 4.0), 4.0);
        assert_eq!(resolution(1.5, 0.5), 1.5);
        assert_eq!(resolution(1.5, f64::INFINITY), 1.5);
        let strong = at(10.0, 1);
        assert_eq!(
            reproducers(
                &reaches(&[&strong, &other]),
                &shrink,
                0.05,
                &[resolution(1.5, 4.0), 1.5]
            )[0],
            vec![1]
        );
    }

    /// A greedy step's set: the chosen candidate's signature is reproduced by a second
    /// candidate on top of the same model (10° away, its residual under the level), not by
    /// a third that shrinks the gap too little, nor by a fourth 60° away; a step whose own
    /// shrink is under the minimum has no set.
    #[test]
    fn a_greedy_step_names_the_candidates_that_reproduce_it_on_the_same_model() {
        let sig = |deg: f64| {
            let r = deg.to_radians();
            Signature {
                d: vec![r.cos(), r.sin(), 0.0],
                cols: vec![vec![r.cos(), r.sin(), 0.0]],
                records: 1,
            }
        };
        let (a, b, c, d) = (sig(0.0), sig(10.0), sig(5.0), sig(60.0));
        let sigs = [&a, &b, &c, &d];
        let shrink = [0.3, 0.25, 0.01, 0.2];
        assert_eq!(step_set(&sigs, &shrink, 0, 0.5, 0.05, 1.0), vec![1]);
        // The level is the larger of the significance level and the step's own gap: a
        // signature 10 times larger leaves 1.7 outside b's span, resolved at level 1.
        let big = Signature {
            d: vec![10.0, 0.0, 0.0],
            cols: vec![vec![1.0, 0.0, 0.0]],
            records: 1,
        };
        let sigs = [&big, &b, &c, &d];
        assert!(step_set(&sigs, &shrink, 0, 0.5, 0.05, 1.0).is_empty());
        assert_eq!(step_set(&sigs, &shrink, 0, 2.0, 0.05, 1.0), vec![1]);
        assert!(step_set(&sigs, &[0.01, 0.25, 0.01, 0.2], 0, 0.5, 0.05, 1.0).is_empty());
    }
}
