//! Which record takes which role in the clean protocol of records of seconds (training,
//! validation, test; [`super::protocol`]), and the checks on the set of records that the
//! roles rest on: no record given twice, one bearing for all, and the part length actually
//! used stated when it is shorter than `--seconds` asked.

use super::records::RealRecord;
use crate::geometry::GeometrySpec;
use std::path::Path;

/// Role of the data every parameter is fitted on (`records[].role`, lifetime
/// `where[].role`, `train_span.role`). The three role names are defined here once, for
/// records of seconds and lives alike.
pub const TRAIN: &str = "train";
/// Role of the data the model is chosen on (ranking, greedy addition, dropping): its
/// totals (`totals.before`/`after`) are biased upwards by that choice.
pub const VALIDATION: &str = "validation";
/// Role of the data the reported figure is measured on, which chose nothing
/// (`totals.test_before`/`test_after`).
pub const TEST: &str = "test";

/// Record indices (0-based, in `--real` order) of each role.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Roles {
    /// Training records: every parameter is fitted on them.
    pub train: Vec<usize>,
    /// Validation records: the model is chosen on them. Empty: a part of each training
    /// record right after its training part validates.
    pub validation: Vec<usize>,
    /// Test records: the reported shrink is measured on them only.
    pub test: Vec<usize>,
}

/// The roles of `n` records from the selections `--train`, `--validation`, `--holdout`
/// (`None`: not given), `name(i)` naming record `i` in messages. Defaults: training the
/// first record; validation, when not given, the records neither trained on nor held out
/// (without `--holdout` and with three or more records: the first of them only, the rest
/// being the test); test, when not given, the records in neither other role. Every record
/// takes exactly one role: one in two roles, or in none (all three selections given and
/// a record left out), is refused.
pub fn assign(
    n: usize,
    train: Option<Vec<usize>>,
    validation: Option<Vec<usize>>,
    holdout: Option<Vec<usize>>,
    name: impl Fn(usize) -> String,
) -> Result<Roles, String> {
    let ti = train.unwrap_or_else(|| vec![0]);
    let rest = |a: &[usize], b: &[usize]| -> Vec<usize> {
        (0..n)
            .filter(|i| !a.contains(i) && !b.contains(i))
            .collect()
    };
    let vi = match (&validation, &holdout) {
        (Some(v), _) => v.clone(),
        (None, Some(h)) => rest(&ti, h),
        (None, None) if n >= 3 => rest(&ti, &[]).into_iter().take(1).collect(),
        (None, None) => vec![],
    };
    let hi = holdout.unwrap_or_else(|| rest(&ti, &vi));
    let clash = |x: &[usize], y: &[usize], what: &str| {
        match x.iter().find(|i| y.contains(i)) {
        Some(i) => Err(format!(
            "{what} both hold {}: a held-out record must not be fitted on, nor the test part chosen on (one role per record: training, validation or test)",
            name(*i)
        )),
        None => Ok(()),
    }
    };
    clash(&ti, &hi, "--train and --holdout")?;
    clash(&ti, &vi, "--train and --validation")?;
    clash(&vi, &hi, "--validation and --holdout")?;
    if ti.is_empty() || hi.is_empty() {
        return Err(
            "--train/--holdout: give at least one training and one held-out (test) record".into(),
        );
    }
    let all: Vec<usize> = ti.iter().chain(&vi).chain(&hi).copied().collect();
    let left: Vec<String> = (0..n).filter(|i| !all.contains(i)).map(&name).collect();
    if !left.is_empty() {
        return Err(format!(
            "--real {}: in no role (--train, --validation and --holdout name the others); every record given takes part: name it in one of them, or leave it out of --real",
            left.join(", ")
        ));
    }
    Ok(Roles {
        train: ti,
        validation: vi,
        test: hi,
    })
}

/// `--real` argument `i` (0-based) with its path, for messages: `#2 (a/b.mat)`.
pub fn arg_name(i: usize, p: &Path) -> String {
    format!("#{} ({})", i + 1, p.display())
}

/// Refuses a record given twice: the same file (resolved path) or two files whose samples
/// (in m/s², at the same rate) are identical. Its part in one role would be another
/// role's data: a test part that is the training part is no out-of-sample test.
pub fn distinct(recs: &[RealRecord]) -> Result<(), String> {
    let real: Vec<_> = recs
        .iter()
        .map(|r| r.file.canonicalize().unwrap_or_else(|_| r.file.clone()))
        .collect();
    for (j, b) in recs.iter().enumerate() {
        for (i, a) in recs.iter().enumerate().take(j) {
            let what = if real.get(i) == real.get(j) {
                "are the same file"
            } else if a.fs == b.fs && a.accel == b.accel {
                "have identical contents"
            } else {
                continue;
            };
            return Err(format!(
                "--real {} and --real {} {what}: one record given twice; the training, validation and test parts must come from different data (a test part that is the training part is no out-of-sample test)",
                arg_name(i, &a.file),
                arg_name(j, &b.file)
            ));
        }
    }
    Ok(())
}

/// Refuses records of different bearings: one diagnosis calibrates one rig and fits one
/// set of effect parameters on the training part and judges them on the others, so a
/// validation or test record of another bearing (other kinematics, structure and rig)
/// judges a model that was never its own. The message names each record's bearing.
pub fn one_bearing(recs: &[RealRecord]) -> Result<(), String> {
    let Some(first) = recs.first() else {
        return Ok(());
    };
    // By name and by geometry: two records whose sidecars give different geometries are
    // both `custom`.
    let geometry = |r: &RealRecord| GeometrySpec::of(&r.base.bearing);
    if recs
        .iter()
        .all(|r| r.bearing == first.bearing && geometry(r).same_as(&geometry(first)))
    {
        return Ok(());
    }
    let each: Vec<String> = recs
        .iter()
        .enumerate()
        .map(|(i, r)| {
            format!(
                "{} is {} ({})",
                arg_name(i, &r.file),
                r.bearing,
                geometry(r).describe()
            )
        })
        .collect();
    Err(format!(
        "--real: the records are of different bearings ({}); one diagnosis fits one rig and one set of effect parameters on the training part and judges them on the others, so all its records must be of one bearing: diagnose each bearing separately (or give --bearing if a file names its bearing wrongly)",
        each.join("; ")
    ))
}

/// A part as built: its role, its record's file and its length (samples) at the record's
/// rate (Hz).
#[derive(Debug, Clone)]
pub struct PartLength<'a> {
    /// `train`, `validation` or `test`.
    pub role: &'a str,
    /// The record's file.
    pub file: &'a Path,
    /// Samples of the part.
    pub samples: usize,
    /// The record's sample rate (Hz).
    pub fs: f64,
}

/// The finding for parts shorter than `--seconds` asked (`requested`, s): each such part
/// with its length (s), and why it matters. `None` when every part has the asked length.
/// A record too short for its disjoint parts at the asked length is not refused — the
/// length is a fact of the data, and a batch of records of different lengths runs with
/// one command — but the length used is stated, because the gap's scale depends on it
/// (each cell's mean and spread come from the part's segments).
pub fn shortened(parts: &[PartLength<'_>], requested: f64) -> Option<String> {
    let short: Vec<String> = parts
        .iter()
        .filter(|p| p.samples < super::records::min_samples(requested, p.fs))
        .map(|p| {
            format!(
                "{} {}: {:.2} s",
                p.file
                    .file_name()
                    .map_or_else(String::new, |n| n.to_string_lossy().into_owned()),
                p.role,
                p.samples as f64 / p.fs
            )
        })
        .collect();
    (!short.is_empty()).then(|| {
        format!(
            "--seconds {requested}: parts shorter than asked were used ({}): the record does not hold disjoint parts of that length (one record: three parts in its thirds; a training record that also gives the validation part: two in its halves). The gap's scale depends on the part length (each cell's mean and spread come from its segments), so totals are comparable only between diagnoses on parts of equal length (`records[].seconds`)",
            short.join(", ")
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn roles(
        n: usize,
        t: Option<&[usize]>,
        v: Option<&[usize]>,
        h: Option<&[usize]>,
    ) -> Result<Roles, String> {
        let own = |x: Option<&[usize]>| x.map(<[usize]>::to_vec);
        assign(n, own(t), own(v), own(h), |i| format!("r{i}"))
    }

    /// Probe defect: with three records and `--holdout 3` (four and `--holdout 3,4`) the
    /// second record took no role and no finding said so. It now validates, as `--help`
    /// says the second record does for three or more records.
    #[test]
    fn every_record_takes_a_role() {
        let r = roles(3, None, None, Some(&[2])).unwrap();
        assert_eq!((r.train, r.validation, r.test), (vec![0], vec![1], vec![2]));
        let r = roles(4, None, None, Some(&[2, 3])).unwrap();
        assert_eq!(
            (r.train, r.validation, r.test),
            (vec![0], vec![1], vec![2, 3])
        );
        // Defaults: three or more → the second validates, the rest are the test.
        let r = roles(4, None, None, None).unwrap();
        assert_eq!(
            (r.train, r.validation, r.test),
            (vec![0], vec![1], vec![2, 3])
        );
        // Two records: the training record validates itself (empty validation).
        let r = roles(2, None, None, None).unwrap();
        assert_eq!((r.train, r.validation, r.test), (vec![0], vec![], vec![1]));
        // All three given and a record left out: refused, naming it.
        let e = roles(4, Some(&[0]), Some(&[1]), Some(&[2])).unwrap_err();
        assert!(e.starts_with("--real r3: in no role"), "{e}");
        let e = roles(3, Some(&[0]), None, Some(&[0, 1])).unwrap_err();
        assert!(e.contains("--train and --holdout both hold r0"), "{e}");
    }

    /// A record of `bearing` with the model `preset`'s rig and its bearing's `elements`.
    fn record(file: &str, bearing: &str, elements: u8) -> RealRecord {
        let mut base = wearsim_core::presets::by_name("cwru-6205-de").expect("preset");
        base.bearing.elements = elements;
        RealRecord {
            file: file.into(),
            accel: vec![],
            fs: 12_000.0,
            rpm: 1797.0,
            rpm_source: "argument".into(),
            bearing: bearing.into(),
            base,
            defect: None,
            defect_source: "none",
            defect_model: None,
            unit: "g".into(),
            content_hz: None,
            warnings: vec![],
        }
    }

    /// Probe finding (stop 52, left then): two records whose sidecars give different
    /// geometries are both `custom`, and the names alone let them through as one bearing.
    #[test]
    fn records_of_one_name_and_two_geometries_are_refused() {
        let same = [record("a.wav", "custom", 9), record("b.wav", "custom", 9)];
        assert!(one_bearing(&same).is_ok());
        let two = [record("a.wav", "custom", 9), record("b.wav", "custom", 8)];
        let e = one_bearing(&two).unwrap_err();
        assert!(e.contains("elements=9") && e.contains("elements=8"), "{e}");
        let names = [record("a.wav", "custom", 9), record("b.wav", "6205", 9)];
        assert!(one_bearing(&names).is_err());
    }
}
