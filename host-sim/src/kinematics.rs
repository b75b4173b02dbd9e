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
pub fn of_config(cfg: &ModelConfig, rpm: f64) -> Result<FaultFrequencies, String> {
    let model = Model::new_checked(cfg.clone()).map_err(|e| e.to_string())?;
    Ok(model.frequencies_at(rpm / 60.0))
}
