//! Run-to-failure records of the IMS bearing tests (per-snapshot feature tables,
//! `features_chocho66/test*_timefeatures.csv`): one bearing's snapshot statistics on the
//! normalised time line of its test, with dead snapshots (machine stopped) dropped by the
//! one rule of [`live_snapshots`].

use super::ims::{read_ims_features, ImsFeatures};
use crate::analysis::stats::upper_median;
use serde::Serialize;
use std::path::Path;

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

/// Whether each snapshot of a feature table is live: dead snapshots (the machine had
/// stopped; IMS README quirk) are those whose mean |x| is below 10 % of the test's
/// [`upper_median`] on *every* bearing channel that has a `B<n>_mean_abs` column. A table
/// without such a column has every snapshot live.
pub fn live_snapshots(f: &ImsFeatures) -> Vec<bool> {
    let n = f.hours.len();
    let mut live = vec![false; n];
    let mut any = false;
    for b in 1..=8 {
        let Some(m) = f.column(&format!("B{b}_mean_abs")) else {
            continue;
        };
        any = true;
        let med = upper_median(m.to_vec()).unwrap_or(0.0);
        for (l, v) in live.iter_mut().zip(m) {
            *l |= *v > 0.1 * med;
        }
    }
    if !any {
        live = vec![true; n];
    }
    live
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
    /// wearsim preset of the bearing, the model its simulated life runs (`ims-za2115` for
    /// an IMS table; a documented feature table's `bearing.preset`).
    pub preset: Option<String>,
    /// How the life ended, in the feature-table vocabulary
    /// ([`super::feature_table::FAILURE_MODES`]): a site (`outer-race`, ...), `none` (it
    /// did not fail) or `unknown` (an IMS table's bearing: the table does not say).
    pub failure_mode: String,
    /// The life ran on one shaft with a bearing that failed (the IMS rigs): once that
    /// neighbour degrades, this life's late stages carry its vibration.
    pub shared_shaft: bool,
    /// Unit of the RMS ([`super::feature_table::UNITS`]; `g` for an IMS table).
    pub unit: String,
    /// Columns of its table that the format does not know and the reader ignored
    /// ([`super::feature_table::FeatureTable::ignored_columns`]; none for an IMS table):
    /// reported, so that a misnamed column (`band_2k_4k_hz`) does not vanish silently.
    pub ignored_columns: Vec<String>,
}

impl MeasuredLife {
    /// Whether the life is stated to have run to failure (a failure site, not `none` or
    /// `unknown`).
    pub fn failed(&self) -> bool {
        !matches!(self.failure_mode.as_str(), "none" | "unknown")
    }
}

/// Reads bearing `bearing` (1–4) of an IMS feature table with per-channel `rms`,
/// `kurtosis` (excess, converted to Gaussian = 3), `crest`, `skew` and `mean_abs`
/// columns (`features_chocho66/test2_timefeatures.csv`). Snapshots whose mean |x| is below
/// 10 % of the test's median on *every* channel are dropped (the machine had stopped;
/// README quirk); time is normalised by the last live snapshot.
pub fn read_life(path: &Path, bearing: usize) -> Result<MeasuredLife, String> {
    let f = read_ims_features(path).map_err(|e| e.to_string())?;
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
    let n = f.hours.len();
    let live = live_snapshots(&f);
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
        preset: Some("ims-za2115".into()),
        failure_mode: "unknown".into(),
        shared_shaft: true,
        unit: "g".into(),
        ignored_columns: vec![],
    })
}
