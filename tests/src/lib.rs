//! Shared helpers for the cross-crate integration tests: scenarios built from presets and
//! a runner that returns the acceleration record.

use wearsim_core::{presets, Model, ModelConfig, Sample, State};

/// The thesis reference with every optional force diagram removed.
pub fn bare_reference() -> ModelConfig {
    ModelConfig {
        imbalance: None,
        waviness: None,
        roughness: None,
        defect: None,
        slip: None,
        ..presets::by_name("thesis-61810").expect("preset exists")
    }
}

/// Simulates `seconds` of `cfg` after 0.1 s of settling and returns (acceleration, fs).
pub fn simulate(cfg: ModelConfig, seconds: f64, seed: u64) -> (Vec<f64>, f64) {
    let model = Model::new_checked(cfg).expect("valid configuration");
    let fs = model.config().output_rate;
    let mut st: State<32> = State::new(&model, seed).expect("capacity");
    let mut settle = vec![Sample::default(); (0.1 * fs) as usize];
    model.fill(&mut st, &mut settle);
    let mut out = vec![Sample::default(); (seconds * fs) as usize];
    model.fill(&mut st, &mut out);
    (out.iter().map(|s| s.accel).collect(), fs)
}
