//! The measured side of a lifetime diagnosis from documented feature tables
//! (`docs/feature-tables.md`, [`crate::io::feature_table`]): one table per life, each read
//! into the same [`MeasuredLife`] an IMS table gives, then the one path of
//! [`super::measured_from`]. A table's operating point must be the one its preset
//! simulates (the simulated life runs the preset, with windows of [`WINDOW_SAMPLES`]
//! samples): a table that differs is refused, naming the field, rather than compared with
//! a life of another bearing.

use super::diagnose::{measured_from, LifeOptions, MeasuredSet};
use super::sim::WINDOW_SAMPLES;
use super::MeasuredLife;
use crate::io::feature_table::{read_feature_table, sidecar_path, FeatureTable};
use std::path::PathBuf;

/// Relative tolerance of a table's `rpm` against its preset's shaft speed.
pub const RPM_TOL: f64 = 0.01;

/// Checks that the simulated life can stand for table `t`: a preset named, the preset's
/// speed within [`RPM_TOL`] of `rpm`, snapshots of [`WINDOW_SAMPLES`] samples at the
/// preset's output rate.
pub fn check_simulable(t: &FeatureTable) -> Result<(), String> {
    let side = sidecar_path(&t.path);
    let s = &t.sidecar;
    let Some(name) = s.bearing.preset.as_deref() else {
        return Err(format!(
            "{}: sidecar field `bearing.preset`: none named; `gap --life` simulates a wearsim preset (see `wearsim presets`), the geometry alone is not a model",
            side.display()
        ));
    };
    let p = wearsim_core::presets::by_name(name).ok_or_else(|| {
        format!(
            "{}: sidecar field `bearing.preset`: unknown preset {name:?}",
            side.display()
        )
    })?;
    let rpm = p.speed.shaft_hz(0.0) * 60.0;
    if (s.rpm - rpm).abs() > RPM_TOL * rpm {
        return Err(format!(
            "{}: sidecar field `rpm`: {} rpm, but preset {name} runs at {rpm} rpm (allowed ±{:.0} %)",
            side.display(),
            s.rpm,
            100.0 * RPM_TOL
        ));
    }
    if s.snapshot_samples != WINDOW_SAMPLES as u64 {
        return Err(format!(
            "{}: sidecar field `snapshot_samples`: {}, but the simulated windows hold {WINDOW_SAMPLES} samples (crest factor and kurtosis depend on the length)",
            side.display(),
            s.snapshot_samples
        ));
    }
    if (s.sample_rate_hz - p.output_rate).abs() > 1e-6 * p.output_rate {
        return Err(format!(
            "{}: sidecar field `sample_rate_hz`: {} Hz, but preset {name} is rendered at {} Hz",
            side.display(),
            s.sample_rate_hz,
            p.output_rate
        ));
    }
    Ok(())
}

/// Reads documented feature tables `paths` (life `k` is `paths[k - 1]`): life `o.train`
/// is trained on, lives `o.holdout` judged. Every problem is one of the input.
pub fn measured_tables(paths: &[PathBuf], o: &LifeOptions) -> Result<MeasuredSet, String> {
    let read = |k: usize| -> Result<MeasuredLife, String> {
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
        check_simulable(&t)?;
        Ok(t.to_life(k))
    };
    let train = read(o.train)?;
    let holdout = o
        .holdout
        .iter()
        .map(|k| read(*k))
        .collect::<Result<Vec<_>, _>>()?;
    measured_from(train, holdout)
}
