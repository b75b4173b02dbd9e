//! `wearsim ims-compare`: the simulated life held against IMS test 2, bearing 1 (outer-race
//! failure, `B1_rms` of `features_chocho66/test2_timefeatures.csv`) in full — both
//! normalised curves for the overlay plot, the onsets, the distance and the end ratios.
//!
//! It is the calibration life of `wearsim ims-validate`'s primary fold
//! ([`super::ims_validate`]): the same measured record on its running-time line, the same
//! simulated life of the `ims-za2115` preset on the outer race, read on the measurement's
//! clock, and the same calibration of one parameter, `material.life_factor`, on this
//! bearing's measured time to failure. The figures are therefore **in-sample**; the
//! held-out figures are `ims-validate`'s. Everything else is the physics of the wear model;
//! the timeline is not fitted.

use super::ims::{distance_db, distance_db_mean_abs, onset, Curve};
use super::ims_validate::{
    calibrate_on, read_record, revs_per_hour, Calibration, Feature, RECORDS,
};
use serde::Serialize;
use std::path::Path;

/// The comparison.
#[derive(Debug, Clone, Serialize)]
pub struct ImsComparison {
    /// Measured curve.
    pub measured: Curve,
    /// Simulated curve.
    pub simulated: Curve,
    /// Onset of instability, measured (fraction of life).
    pub onset_measured: Option<f64>,
    /// Onset of instability, simulated.
    pub onset_simulated: Option<f64>,
    /// |simulated − measured| onset.
    pub onset_error: Option<f64>,
    /// RMS of the dB difference between the curves over the common grid.
    pub distance_db_rms: f64,
    /// Mean absolute dB difference.
    pub distance_db_mean_abs: f64,
    /// End-of-life RMS over early-life median, measured and simulated.
    pub end_ratio: (f64, f64),
    /// Measured life: running hours from the first to the last live snapshot.
    pub measured_life_h: f64,
    /// Measured life in revolutions at 2000 rpm.
    pub measured_life_revs: f64,
    /// Simulated life with the uncalibrated ISO 281 fatigue (life_factor 1), revolutions.
    pub uncalibrated_life_revs: f64,
    /// Calibrated life factor.
    pub life_factor: f64,
    /// The calibration reached the measured life (within
    /// [`crate::life::calibrate::TOLERANCE`]); `false` when it stopped at a bound of the
    /// factor's range or after its steps with the life elsewhere (for some seeds the part
    /// of the life the factor does not scale, crack opening to failure, is already longer
    /// than the measured life).
    pub calibrated: bool,
    /// Simulated life after calibration, revolutions.
    pub simulated_life_revs: f64,
    /// Simulated stage timeline (fractions of life at each transition).
    pub stages: Vec<(String, f64)>,
}

/// Runs the comparison with measured data under `data` (the shared data folder).
pub fn compare(data: &Path, seed: u64) -> Result<ImsComparison, String> {
    let record = RECORDS
        .iter()
        .find(|r| r.id == "t2b1")
        .ok_or("the IMS test 2 bearing 1 record is missing")?;
    let m = read_record(data, record)?;
    let c = calibrate_on(&m, seed, Calibration::Length)?;
    let simulated = c.life.curve(Feature::Rms);
    let measured = m.curve;
    let (om, os) = (onset(&measured), onset(&simulated));
    Ok(ImsComparison {
        onset_error: om.zip(os).map(|(a, b)| (a - b).abs()),
        onset_measured: om,
        onset_simulated: os,
        distance_db_rms: distance_db(&simulated, &measured),
        distance_db_mean_abs: distance_db_mean_abs(&simulated, &measured),
        end_ratio: (
            measured.rms.last().copied().unwrap_or(1.0),
            simulated.rms.last().copied().unwrap_or(1.0),
        ),
        measured_life_h: m.running_h,
        measured_life_revs: m.running_h * revs_per_hour(),
        uncalibrated_life_revs: c.uncalibrated_life,
        life_factor: c.scales.life_factor,
        calibrated: c.converged,
        simulated_life_revs: c.life.life,
        stages: c.life.stages,
        measured,
        simulated,
    })
}
