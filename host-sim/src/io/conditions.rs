//! The operating point a public run-to-failure set states in its folder names.
//!
//! Neither FEMTO/PRONOSTIA nor XJTU-SY snapshot files hold the shaft speed or the radial
//! load; both sets state them in the names of their folders, one operating condition per
//! folder, so a user who runs `wearsim features` on the folder as distributed need not
//! look them up:
//!
//! | layout | folder name | speed, load | source |
//! |---|---|---|---|
//! | XJTU-SY | `35Hz12kN`, `37.5Hz11kN`, `40Hz10kN` (any `<f>Hz<l>kN`) | `f` × 60 rpm, `l` × 1000 N | the name itself |
//! | XJTU-SY | `Bearing1_k` … `Bearing3_k` (no such parent) | 35 Hz / 12 kN, 37.5 Hz / 11 kN, 40 Hz / 10 kN | Wang, Lei, Li, Li 2020, IEEE T-Rel 69(1):401–412 |
//! | FEMTO | `Bearing1_k` … `Bearing3_k` | 1800 rpm / 4000 N, 1650 rpm / 4200 N, 1500 rpm / 5000 N | Nectoux et al. 2012, IEEE PHM (`shared/docs/life-physics-sources.md` §5) |
//!
//! Only the folder and its two nearest parents are read. An explicit speed or load wins
//! (`--rpm`, `--load-n`, a sidecar); the source of what was used is reported (`features`:
//! summary and sidecar notes; `analyze`: `input.rpm_source`, `rpm_detail`, `input.load`).

use std::path::Path;

/// The data sets whose folder names state an operating condition.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ConditionSet {
    /// XJTU-SY (`35Hz12kN/Bearing1_1`).
    Xjtu,
    /// FEMTO/PRONOSTIA (`Bearing1_1`).
    Femto,
}

/// Speed and load read from a folder name, with where they came from.
#[derive(Debug, Clone, PartialEq)]
pub struct NamedCondition {
    /// Shaft speed, rpm.
    pub rpm: f64,
    /// Radial load, N.
    pub load_n: f64,
    /// The folder name and the convention it follows, for the report.
    pub source: String,
}

/// XJTU-SY operating conditions 1–3 (Wang et al. 2020): shaft rate (Hz), radial load (kN).
const XJTU_CONDITIONS: [(f64, f64); 3] = [(35.0, 12.0), (37.5, 11.0), (40.0, 10.0)];
/// FEMTO/PRONOSTIA operating conditions 1–3 (Nectoux et al. 2012): speed (rpm), load (N).
const FEMTO_CONDITIONS: [(f64, f64); 3] = [(1800.0, 4000.0), (1650.0, 4200.0), (1500.0, 5000.0)];

/// Largest shaft rate a folder name is read as, Hz (60 000 rpm: above it a name like
/// `5000Hz1kN` is more likely a sample rate than a test condition).
const MAX_NAMED_HZ: f64 = 1000.0;
/// Largest load a folder name is read as, kN.
const MAX_NAMED_KN: f64 = 10_000.0;

/// `<f>Hz<l>kN` (case-insensitive, decimal numbers): shaft rate `f` Hz and load `l` kN, each
/// positive and at most [`MAX_NAMED_HZ`] / [`MAX_NAMED_KN`].
fn hz_kn(name: &str) -> Option<(f64, f64)> {
    let lower = name.to_ascii_lowercase();
    let (f, rest) = lower.split_once("hz")?;
    let l = rest.strip_suffix("kn")?;
    let num = |s: &str| {
        (!s.is_empty() && s.chars().all(|c| c.is_ascii_digit() || c == '.'))
            .then(|| s.parse::<f64>().ok())
            .flatten()
            .filter(|v| v.is_finite() && *v > 0.0)
    };
    let (f, l) = (num(f)?, num(l)?);
    (f <= MAX_NAMED_HZ && l <= MAX_NAMED_KN).then_some((f, l))
}

/// `Bearing<c>_<k>` with condition `c` in 1..=3: `c`.
fn bearing_condition(name: &str) -> Option<usize> {
    let rest = name.strip_prefix("Bearing")?;
    let (c, k) = rest.split_once('_')?;
    let digits = |s: &str| !s.is_empty() && s.chars().all(|ch| ch.is_ascii_digit());
    if !digits(c) || !digits(k) {
        return None;
    }
    let c: usize = c.parse().ok()?;
    (1..=3).contains(&c).then_some(c)
}

/// The operating point the folder `dir` (or one of its two nearest parents) states by the
/// naming of data set `set`; `None` when no name follows the convention.
pub fn from_folder_names(dir: &Path, set: ConditionSet) -> Option<NamedCondition> {
    let names: Vec<String> = dir
        .ancestors()
        .take(3)
        .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
        .collect();
    match set {
        ConditionSet::Xjtu => {
            if let Some((name, (f, l))) = names.iter().find_map(|n| hz_kn(n).map(|v| (n, v))) {
                return Some(NamedCondition {
                    rpm: f * 60.0,
                    load_n: l * 1000.0,
                    source: format!(
                        "folder name `{name}`, XJTU-SY's naming of shaft rate and load"
                    ),
                });
            }
            let (name, c) = names
                .iter()
                .find_map(|n| bearing_condition(n).map(|c| (n, c)))?;
            let (f, l) = XJTU_CONDITIONS[c - 1];
            Some(NamedCondition {
                rpm: f * 60.0,
                load_n: l * 1000.0,
                source: format!(
                    "folder name `{name}`: XJTU-SY condition {c}, {f} Hz and {l} kN (Wang et al. 2020)"
                ),
            })
        }
        ConditionSet::Femto => {
            let (name, c) = names
                .iter()
                .find_map(|n| bearing_condition(n).map(|c| (n, c)))?;
            let (rpm, load_n) = FEMTO_CONDITIONS[c - 1];
            Some(NamedCondition {
                rpm,
                load_n,
                source: format!(
                    "folder name `{name}`: PRONOSTIA condition {c}, {rpm} rpm and {load_n} N (Nectoux et al. 2012)"
                ),
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn xjtu_folder_names_state_their_condition() {
        let c = from_folder_names(
            Path::new("/data/XJTU-SY_Bearing_Datasets/37.5Hz11kN/Bearing2_3"),
            ConditionSet::Xjtu,
        )
        .unwrap();
        assert_eq!((c.rpm, c.load_n), (2250.0, 11000.0));
        assert!(c.source.contains("37.5Hz11kN"), "{}", c.source);
        // Without the condition folder, the bearing's number names the condition.
        let c = from_folder_names(Path::new("x/Bearing3_1"), ConditionSet::Xjtu).unwrap();
        assert_eq!((c.rpm, c.load_n), (2400.0, 10000.0));
        // The explicit name wins over the bearing number (a renamed copy).
        let c = from_folder_names(Path::new("40Hz10kN/Bearing1_1"), ConditionSet::Xjtu).unwrap();
        assert_eq!((c.rpm, c.load_n), (2400.0, 10000.0));
    }

    #[test]
    fn femto_bearing_folders_state_their_condition() {
        let c =
            from_folder_names(Path::new("Learning_set/Bearing2_1"), ConditionSet::Femto).unwrap();
        assert_eq!((c.rpm, c.load_n), (1650.0, 4200.0));
        let c =
            from_folder_names(Path::new("Full_Test_Set/Bearing3_3"), ConditionSet::Femto).unwrap();
        assert_eq!((c.rpm, c.load_n), (1500.0, 5000.0));
    }

    #[test]
    fn other_names_state_nothing() {
        for (dir, layout) in [
            ("runs/Bearing4_1", ConditionSet::Femto),
            ("runs/Bearing1_", ConditionSet::Femto),
            ("runs/bearing1_1", ConditionSet::Femto),
            ("runs/35Hz", ConditionSet::Xjtu),
            ("runs/Hz12kN", ConditionSet::Xjtu),
            ("runs/-35Hz12kN", ConditionSet::Xjtu),
            ("runs/0Hz12kN", ConditionSet::Xjtu),
            ("runs/1001Hz12kN", ConditionSet::Xjtu),
            ("runs/35Hz10001kN", ConditionSet::Xjtu),
            ("runs/3.5.1Hz12kN", ConditionSet::Xjtu),
        ] {
            assert_eq!(from_folder_names(Path::new(dir), layout), None, "{dir}");
        }
        // A condition three levels up is not read.
        assert_eq!(
            from_folder_names(Path::new("35Hz12kN/a/b/c"), ConditionSet::Xjtu),
            None
        );
    }
}
