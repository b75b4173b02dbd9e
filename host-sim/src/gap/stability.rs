//! Stability on real records (issue 13, "Stability on real records"): every effect of the
//! chosen model refitted on each record (or part) separately, on top of the rest of the
//! model, and its parameters compared between records. An effect that stands for one
//! physical mechanism of one rig should give the same parameters at every load and defect
//! size within their uncertainty (a housing's transfer path does not change with the motor
//! load); where two records disagree by more than [`Z_LIMIT`] combined standard deviations,
//! the report says so as a finding: the effect's parameter follows the operating point, or
//! it absorbs a mechanism that does.
//!
//! Uncertainties are the fits' linearised standard deviations (`gap::fit`, nonlinear least
//! squares); a parameter that a record does not constrain (no standard deviation) is
//! reported and left out of the comparison.

use super::fit::{fit_many, Budget, Job};
use super::matched::{without, Evaluator, Matched};
use super::space::FitSpace;
use serde::Serialize;
use wearsim_core::effects::Effects;

/// Combined standard deviations beyond which two records' fits of one parameter disagree
/// (fixed a priori: about a 95 % two-sided band for Gaussian errors).
pub const Z_LIMIT: f64 = 2.0;

/// One record's separate fit of one parameter.
#[derive(Debug, Clone, Serialize)]
pub struct PerRecord {
    /// Record (file and part) the parameter was fitted on.
    pub record: String,
    /// Fitted value (catalogue unit).
    pub value: f64,
    /// One standard deviation (catalogue unit); `null` when the record does not constrain
    /// the parameter.
    pub std: Option<f64>,
}

impl PerRecord {
    /// `record value ± std`, or `record value (not constrained)`.
    pub fn describe(&self) -> String {
        match self.std {
            Some(s) => format!("{} {:.4} ± {:.4}", self.record, self.value, s),
            None => format!("{} {:.4} (not constrained)", self.record, self.value),
        }
    }
}

/// One parameter of a kept effect, fitted on each record separately.
#[derive(Debug, Clone, Serialize)]
pub struct ParamStability {
    /// Effect.
    pub effect: String,
    /// Parameter (catalogue name).
    pub param: String,
    /// Catalogue unit.
    pub unit: String,
    /// Its fit on each record.
    pub per_record: Vec<PerRecord>,
    /// Largest |difference| / combined standard deviation over the pairs of records that
    /// both constrain it (`null` when fewer than two do).
    pub worst_z: Option<f64>,
    /// Every constrained pair agrees within [`Z_LIMIT`].
    pub agree: bool,
}

/// Refits every effect of `kept` (in `full`, the chosen model) on each record of `records`
/// alone, on top of the rest of `full`, starting from its value in the chosen model
/// (`hints`: normalised coordinates per kept effect); the fits of one record run in lock
/// step. Returns one row per fitted parameter.
pub fn stability(
    spaces: &[FitSpace],
    full: &Effects,
    kept: &[(String, Vec<f64>)],
    records: &[Matched],
    ev: &Evaluator,
) -> Result<Vec<ParamStability>, String> {
    let mut bases = vec![];
    let mut used: Vec<(&FitSpace, &[f64])> = vec![];
    for (name, hint) in kept {
        let Some(space) = spaces.iter().find(|s| s.effect == name) else {
            continue;
        };
        bases.push(without(full, name)?);
        used.push((space, hint.as_slice()));
    }
    let jobs: Vec<Job> = used
        .iter()
        .zip(&bases)
        .map(|((space, hint), base)| Job {
            space,
            base,
            hint: Some(hint),
        })
        .collect();
    let mut rows: Vec<ParamStability> = used
        .iter()
        .flat_map(|(space, _)| {
            space.fitted.iter().map(|f| ParamStability {
                effect: space.effect.to_string(),
                param: f.name.to_string(),
                unit: String::new(),
                per_record: vec![],
                worst_z: None,
                agree: true,
            })
        })
        .collect();
    for m in records {
        let fits = fit_many(&jobs, std::slice::from_ref(m), ev, Budget::DEFAULT);
        let params = fits.iter().flat_map(|f| f.params.iter());
        for (row, p) in rows.iter_mut().zip(params) {
            row.unit.clone_from(&p.unit);
            row.per_record.push(PerRecord {
                record: m.label.clone(),
                value: p.value,
                std: p.std,
            });
        }
    }
    for row in &mut rows {
        row.worst_z = worst_z(&row.per_record);
        row.agree = row.worst_z.is_none_or(|z| z <= Z_LIMIT);
    }
    Ok(rows)
}

/// Largest `|a − b| / √(σa² + σb²)` over the pairs of fits that both have a standard
/// deviation; `None` when fewer than two have one.
pub fn worst_z(fits: &[PerRecord]) -> Option<f64> {
    let c: Vec<(f64, f64)> = fits
        .iter()
        .filter_map(|r| r.std.filter(|s| s.is_finite()).map(|s| (r.value, s)))
        .collect();
    let mut worst: Option<f64> = None;
    for (i, a) in c.iter().enumerate() {
        for b in c.iter().skip(i + 1) {
            let s = (a.1 * a.1 + b.1 * b.1).sqrt();
            let z = if s > 0.0 {
                (a.0 - b.0).abs() / s
            } else if a.0 == b.0 {
                0.0
            } else {
                f64::INFINITY
            };
            worst = Some(worst.map_or(z, |w: f64| w.max(z)));
        }
    }
    worst
}

/// The report's sentence for a parameter whose records disagree.
pub fn finding(r: &ParamStability) -> String {
    let fits: Vec<String> = r.per_record.iter().map(PerRecord::describe).collect();
    format!(
        "{}.{} fitted on each record separately disagrees beyond {Z_LIMIT} combined standard deviations (worst z = {:.1}): {}; the parameter follows the operating point (load, defect size) or the effect absorbs a mechanism that does",
        r.effect,
        r.param,
        r.worst_z.unwrap_or(f64::NAN),
        fits.join(", ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rec(v: f64, s: Option<f64>) -> PerRecord {
        PerRecord {
            record: "r".into(),
            value: v,
            std: s,
        }
    }

    #[test]
    fn z_is_the_largest_pairwise_difference_over_the_combined_deviation() {
        // Pairs: (1, 0.3)–(2, 0.4): 1/0.5 = 2; (2, 0.4)–(2.5, 0.3): 0.5/0.5 = 1;
        // (1, 0.3)–(2.5, 0.3): 1.5/√0.18 = 3.54, the largest.
        let z = worst_z(&[
            rec(1.0, Some(0.3)),
            rec(2.0, Some(0.4)),
            rec(2.5, Some(0.3)),
        ]);
        let z = z.expect("three constrained fits");
        assert!((z - 1.5 / (0.18f64).sqrt()).abs() < 1e-12, "{z}");
    }

    #[test]
    fn unconstrained_fits_are_left_out_and_one_fit_says_nothing() {
        assert_eq!(worst_z(&[rec(1.0, Some(0.1)), rec(5.0, None)]), None);
        assert_eq!(worst_z(&[]), None);
        assert_eq!(
            worst_z(&[rec(1.0, Some(0.0)), rec(1.0, Some(0.0))]),
            Some(0.0)
        );
        assert_eq!(
            worst_z(&[rec(1.0, Some(0.0)), rec(2.0, Some(0.0))]),
            Some(f64::INFINITY)
        );
    }
}
