//! The characteristic frequencies of a named bearing preset or of a model configuration at
//! a shaft speed: the host's constructors of the project's one kinematics type,
//! [`wearsim_core::kinematics::FaultFrequencies`] (thesis eq. 17–20 and the natural
//! frequency of the structure).

use wearsim_core::kinematics::FaultFrequencies;
use wearsim_core::{Model, ModelConfig};

/// Frequencies of bearing preset `preset` at `rpm` (rev/min). Errors name the preset and
/// list the valid names.
pub fn of_preset(preset: &str, rpm: f64) -> Result<FaultFrequencies, String> {
    let cfg = wearsim_core::presets::by_name(preset).ok_or_else(|| {
        format!(
            "unknown bearing preset {preset:?} (allowed: {})",
            wearsim_core::presets::NAMES.join(", ")
        )
    })?;
    of_config(&cfg, rpm).map_err(|e| format!("bearing preset {preset}: {e}"))
}

/// Frequencies of the bearing and structure of model configuration `cfg` (e.g. the
/// structured `model` of a wearsim sidecar) at `rpm` (rev/min). Errors: the configuration
/// is invalid (the field named by the core's check).
///
/// The output rate and the internal step change none of these frequencies: a configuration
/// whose step cannot resolve its stiffest contact at its own rate (a small bearing's
/// structure, scaled from a preset at the preset's 12 kHz, needs a far higher internal
/// rate) is checked again at the lowest output rate the step resolves, so that an
/// analysis, which simulates nothing, is not refused for a simulation's limit.
pub fn of_config(cfg: &ModelConfig, rpm: f64) -> Result<FaultFrequencies, String> {
    let model = match Model::new_checked(cfg.clone()) {
        Err(wearsim_core::ConfigError::StepTooLarge {
            min_internal_rate_hz,
            ..
        }) => {
            let mut at = cfg.clone();
            at.oversample = None;
            at.output_rate = (min_internal_rate_hz
                / f64::from(wearsim_core::model::MAX_OVERSAMPLE))
            .ceil()
            .max(at.output_rate + 1.0);
            Model::new_checked(at)
        }
        other => other,
    }
    .map_err(|e| e.to_string())?;
    Ok(model.frequencies_at(rpm / 60.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A miniature bearing (7 balls of 1.588 mm on a 6.5 mm pitch, a 623-size bearing)
    /// whose structure, scaled from a preset, needs an internal rate (≈ 300 kHz) above the
    /// preset's 12 kHz × 16: its frequencies are still given, and they are the closed forms
    /// (thesis eq. 17–19: BPFO = N/2·(1 − d/P)·f, BPFI = N/2·(1 + d/P)·f, FTF = ½(1 − d/P)·f).
    #[test]
    fn a_small_bearings_frequencies_do_not_depend_on_a_simulation_step() {
        let g = crate::geometry::GeometrySpec::parse("elements=7,ball=1.588,pitch=6.5,angle=0")
            .expect("geometry");
        let m = g.model().expect("scaled model").model;
        assert!(
            Model::new_checked(m.clone()).is_err(),
            "the premise: the scaled model is refused at its own rate"
        );
        let f = of_config(&m, 1797.0).expect("frequencies");
        let shaft = 1797.0 / 60.0;
        let r = 1.588 / 6.5;
        for (got, want, what) in [
            (f.bpfo, 3.5 * (1.0 - r) * shaft, "BPFO"),
            (f.bpfi, 3.5 * (1.0 + r) * shaft, "BPFI"),
            (f.ftf, 0.5 * (1.0 - r) * shaft, "FTF"),
        ] {
            assert!((got - want).abs() < 1e-9 * want, "{what}: {got} vs {want}");
        }
        assert!(f.natural_hz > 0.0 && f.natural_hz.is_finite());
    }
}
