//! The measured side of a lifetime diagnosis from documented feature tables
//! (`docs/feature-tables.md`, [`crate::io::feature_table`]): one table per life, each read
//! into the same [`MeasuredLife`] an IMS table gives, then the one path of
//! [`super::measured_from`]. The simulated bearing is built from each table's sidecar
//! ([`RigDescription::from_sidecar`]: its preset, or its geometry and operating point);
//! all lives of one diagnosis must describe the same bearing, or the field that differs
//! is named. The training life must have failed (its length calibrates the life
//! factor); a held-out life is judged over its whole life unless it did not fail
//! ([`super::diagnose::holdout_t_max`]).

use super::diagnose::{measured_from, LifeOptions, MeasuredSet};
use super::rig::RigDescription;
use super::MeasuredLife;
use crate::io::feature_table::{read_feature_table, sidecar_path};
use std::path::PathBuf;

/// Reads documented feature tables `paths` (life `k` is `paths[k - 1]`): life `o.train`
/// is trained on, lives `o.holdout` judged. Every problem is one of the input.
pub fn measured_tables(paths: &[PathBuf], o: &LifeOptions) -> Result<MeasuredSet, String> {
    let read = |k: usize| -> Result<(MeasuredLife, RigDescription), String> {
        let p = k
            .checked_sub(1)
            .and_then(|i| paths.get(i))
            .ok_or_else(|| {
                format!(
                    "life {k}: only {} feature tables were given (--train/--holdout count the --real tables from 1)",
                    paths.len()
                )
            })?;
        let t = read_feature_table(p).map_err(|e| e.to_string())?;
        let rig = RigDescription::from_sidecar(&t.sidecar, p)?;
        Ok((t.to_life(k), rig))
    };
    let (train, rig) = read(o.train)?;
    if !train.failed() {
        return Err(format!(
            "{}: sidecar field `failure_mode`: {:?}, but the training life must have run to failure ({}): its length calibrates the life factor, and a life that did not fail (or is not known to have) would set it to a life that never ended",
            sidecar_path(std::path::Path::new(&train.file)).display(),
            train.failure_mode,
            crate::io::feature_table::FAILURE_MODES
                .iter()
                .filter(|m| !matches!(**m, "none" | "unknown"))
                .copied()
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    let mut holdout = vec![];
    for k in &o.holdout {
        let (life, r) = read(*k)?;
        if let Some((f, ours, theirs)) = rig.differs(&r) {
            return Err(format!(
                "{}: sidecar field `{f}` differs from the training life's ({}): {theirs} against {ours}; the lives of one diagnosis share one simulated bearing",
                sidecar_path(std::path::Path::new(&life.file)).display(),
                sidecar_path(std::path::Path::new(&train.file)).display()
            ));
        }
        holdout.push(life);
    }
    measured_from(train, holdout, rig)
}
