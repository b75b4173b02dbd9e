//! The measured IMS lives: which bearing, channel and feature each is, and reading a
//! feature table into a running-time curve (rig stops folded, dead snapshots dropped).

use super::*;

/// An interval longer than this many median intervals is a stop of the rig (counted as
/// one median interval of running time).
pub const GAP_FACTOR: f64 = 2.0;
/// Which per-snapshot statistic a record carries.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Feature {
    /// Root mean square (with the DC offset, as the feature tables compute it).
    Rms,
    /// Mean absolute value.
    MeanAbs,
}

/// One failed IMS bearing life.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct LifeRecord {
    /// Short id (`t2b1`, ...).
    pub id: &'static str,
    /// File under the data folder.
    pub file: &'static str,
    /// Canonical column read (see `io::ims::ImsFeatures`).
    pub column: &'static str,
    /// Statistic of the column.
    pub feature: Feature,
    /// Failure found at the end of the test (IMS readme).
    pub failure: &'static str,
    /// Wear site the simulated life runs on.
    #[serde(serialize_with = "site_name")]
    pub site: Site,
}

fn site_name<S: serde::Serializer>(s: &Site, ser: S) -> Result<S::Ok, S::Error> {
    ser.serialize_str(s.name())
}

/// The four IMS bearings that failed (IMS readme, "end-of-test finding").
pub const RECORDS: [LifeRecord; 4] = [
    LifeRecord {
        id: "t2b1",
        file: "ims/features_chocho66/test2_timefeatures.csv",
        column: "B1_rms",
        feature: Feature::Rms,
        failure: "outer race",
        site: Site::OuterRace,
    },
    LifeRecord {
        id: "t1b3",
        file: "ims/features_chocho66/test1_timefeatures.csv",
        column: "B3_x_rms",
        feature: Feature::Rms,
        failure: "inner race",
        site: Site::InnerRace,
    },
    LifeRecord {
        id: "t1b4",
        file: "ims/features_chocho66/test1_timefeatures.csv",
        column: "B4_x_rms",
        feature: Feature::Rms,
        failure: "roller",
        site: Site::Element,
    },
    LifeRecord {
        id: "t3b3",
        file: "ims/features_chocho66/DatasetBearingTest_3.csv",
        column: "B3_mean_abs",
        feature: Feature::MeanAbs,
        failure: "outer race",
        site: Site::OuterRace,
    },
];

/// A measured life on its running-time line.
#[derive(Debug, Clone, Serialize)]
pub struct MeasuredRecord {
    /// The record.
    pub record: LifeRecord,
    /// Normalised curve (fraction of running time, value over first-half median).
    pub curve: Curve,
    /// Running hours from the first to the last live snapshot.
    pub running_h: f64,
    /// Clock hours over the same span.
    pub clock_h: f64,
    /// Intervals counted as stops of the rig.
    pub gaps: usize,
    /// Snapshots dropped as dead.
    pub dropped: usize,
    /// Median of the first half of the record (record unit).
    pub steady: f64,
}

/// Reads one record under the data folder `data`. Errors name the file and the field:
/// a missing column, a non-increasing time stamp, no live snapshot.
pub fn read_record(data: &Path, r: &LifeRecord) -> Result<MeasuredRecord, String> {
    let path = data.join(r.file);
    let f = read_ims_features(&path).map_err(|e| e.to_string())?;
    if let Some(e) = crate::io::ims_life::cut_short(&f) {
        return Err(e);
    }
    let v = f.column(r.column).ok_or_else(|| {
        format!(
            "{}: no column {} (the {} life needs it; columns: {})",
            path.display(),
            r.column,
            r.id,
            f.names().join(", ")
        )
    })?;
    if let Some(i) = f.unix_s.windows(2).position(|w| w[1] <= w[0]) {
        return Err(format!(
            "{}: time stamp of row {} ({}) is not after the previous one; time must increase",
            path.display(),
            i + 3,
            f.timestamps.get(i + 1).map(String::as_str).unwrap_or("?")
        ));
    }
    let live = live_snapshots(&f);
    let keep: Vec<usize> = (0..v.len())
        .filter(|i| live.get(*i).copied().unwrap_or(false) && v[*i] > 0.0)
        .collect();
    if keep.len() < 10 {
        return Err(format!(
            "{}: {} live snapshots in {}; at least 10 needed",
            path.display(),
            keep.len(),
            r.column
        ));
    }
    let secs: Vec<f64> = keep.iter().map(|i| f.unix_s[*i] as f64).collect();
    let mut dt: Vec<f64> = secs.windows(2).map(|w| w[1] - w[0]).collect();
    let mut sorted = dt.clone();
    sorted.sort_by(f64::total_cmp);
    let median = sorted[sorted.len() / 2];
    let mut gaps = 0;
    for d in dt.iter_mut() {
        if *d > GAP_FACTOR * median {
            *d = median;
            gaps += 1;
        }
    }
    let mut run = vec![0.0];
    for d in &dt {
        run.push(run.last().copied().unwrap_or(0.0) + d / 3600.0);
    }
    let total = run.last().copied().unwrap_or(0.0);
    let t: Vec<f64> = run.iter().map(|h| h / total).collect();
    let vals: Vec<f64> = keep.iter().map(|i| v[*i]).collect();
    let curve = normalise(t, vals.clone());
    let steady = vals.first().copied().unwrap_or(0.0) / curve.rms.first().copied().unwrap_or(1.0);
    Ok(MeasuredRecord {
        record: *r,
        steady,
        curve,
        running_h: total,
        clock_h: (secs.last().copied().unwrap_or(0.0) - secs[0]) / 3600.0,
        gaps,
        dropped: v.len() - keep.len(),
    })
}
