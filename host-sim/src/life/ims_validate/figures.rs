//! The per-life figures: onset, trajectory distance, end ratio and life ratio of a
//! simulated life against a measured one.

use super::*;

/// Share of life at the end whose median is the end level (–).
pub const END_SHARE: f64 = 0.05;

/// Figures of one life (see the module docs for what each is).
#[derive(Debug, Clone, Serialize)]
pub struct LifeFigures {
    /// Record id.
    pub id: String,
    /// `calibration` or `held-out`.
    pub role: String,
    /// Onset, fraction of the record.
    pub onset_measured: Option<f64>,
    /// Onset, fraction of the simulated life.
    pub onset_simulated: Option<f64>,
    /// |simulated − measured| onset (fraction).
    pub onset_error: Option<f64>,
    /// Running hours from onset to the end of the record.
    pub onset_to_failure_h_measured: Option<f64>,
    /// Hours (at 2000 rpm) from the simulated onset to failure.
    pub onset_to_failure_h_simulated: Option<f64>,
    /// Trajectory distance (dB RMS).
    pub distance_db_rms: f64,
    /// End value over first-half median, measured.
    pub end_ratio_measured: f64,
    /// The same, simulated.
    pub end_ratio_simulated: f64,
    /// Simulated over measured end ratio.
    pub end_ratio_factor: f64,
    /// Median over the last [`END_SHARE`] of life of the normalised curve, measured (a
    /// figure that does not hang on the one last window; reported, not judged).
    pub end_level_measured: f64,
    /// The same, simulated.
    pub end_level_simulated: f64,
    /// Simulated revolutions over measured running revolutions.
    pub life_ratio: f64,
    /// Measured steady level: median of the first half (record unit, not stated by IMS:
    /// volts or g of a 100 mV/g PCB 353B33).
    pub steady_measured: f64,
    /// Simulated steady level at the sensor (m/s²), the same median.
    pub steady_simulated: f64,
    /// Simulated end level at the sensor (m/s²).
    pub end_simulated_abs: f64,
    /// Measurement floor of the simulated life (m/s² RMS, white).
    pub floor: f64,
    /// Simulated stage onsets (fraction of life).
    pub stages: Vec<(String, f64)>,
}

/// Median of a normalised curve over its last [`END_SHARE`] of life.
pub fn end_level(c: &Curve) -> f64 {
    median(
        c.t.iter()
            .zip(&c.rms)
            .filter(|(t, _)| **t >= 1.0 - END_SHARE)
            .map(|(_, v)| *v)
            .collect(),
    )
}

/// The figures of simulated life `s` against measured `m`.
pub fn figures(m: &MeasuredRecord, s: &SimLife, role: &str) -> LifeFigures {
    let sc = s.curve(m.record.feature);
    let sc_raw = match m.record.feature {
        Feature::Rms => &s.rms,
        Feature::MeanAbs => &s.mean_abs,
    };
    let (om, os) = (onset(&m.curve), onset(&sc));
    let em = m.curve.rms.last().copied().unwrap_or(1.0);
    let es = sc.rms.last().copied().unwrap_or(1.0);
    LifeFigures {
        id: m.record.id.into(),
        role: role.into(),
        onset_measured: om,
        onset_simulated: os,
        onset_error: om.zip(os).map(|(a, b)| (a - b).abs()),
        onset_to_failure_h_measured: om.map(|o| (1.0 - o) * m.running_h),
        onset_to_failure_h_simulated: os.map(|o| (1.0 - o) * s.life / revs_per_hour()),
        distance_db_rms: distance_db(&sc, &m.curve),
        end_ratio_measured: em,
        end_ratio_simulated: es,
        end_ratio_factor: es / em,
        end_level_measured: end_level(&m.curve),
        end_level_simulated: end_level(&sc),
        life_ratio: s.life / (m.running_h * revs_per_hour()),
        steady_measured: m.steady,
        steady_simulated: sc_raw.last().copied().unwrap_or(0.0) / es.max(1e-300),
        end_simulated_abs: sc_raw.last().copied().unwrap_or(0.0),
        floor: 0.0,
        stages: s.stages.clone(),
    }
}

/// Median of `v` (NaN when empty). Unlike [`crate::analysis::stats::median`] it keeps
/// non-finite values (sorted by `total_cmp`): an infinite end factor (a record ending at
/// level 0) must fail the acceptance medians, not drop out of them.
pub(super) fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n == 0 {
        return f64::NAN;
    }
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}
