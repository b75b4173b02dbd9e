//! Candidate effects for the sim-to-real gap diagnosis (`docs/sim-to-real.md`): physical
//! terms the baseline model leaves out, each switchable and parameterised within bounds.
//!
//! [`Effects`] is part of [`crate::ModelConfig`]; all effects are off by default and an
//! effect that is off costs at most one `Option` check per internal step (the baseline's
//! per-step cost is unchanged). Every effect is deterministic: same configuration and
//! seed, same samples. [`CATALOGUE`] describes every effect and parameter (name, unit,
//! default, bounds) for front ends; [`Effects::set`] switches one on from its parameter
//! values in catalogue order.

pub mod edge_shape;
pub mod load_zone;
pub mod roughness;
pub mod running_in;
pub mod sensor;
pub mod shaft_harmonics;
pub mod slip;
pub mod speed_fluctuation;
pub mod transfer_path;

use crate::error::ConfigError;
use crate::real::Real;

/// The switchable effects; `None` = off.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Effects {
    /// Random slip of the element passes.
    pub slip: Option<slip::Params>,
    /// Stribeck load-zone modulation of the defect impact.
    pub load_zone: Option<load_zone::Params>,
    /// Extra structural modes between bearing and sensor.
    pub transfer_path: Option<transfer_path::Params>,
    /// Sinusoidal and random speed modulation.
    pub speed_fluctuation: Option<speed_fluctuation::Params>,
    /// Sensor noise floor, bandwidth and mains hum.
    pub sensor: Option<sensor::Params>,
    /// Misalignment/looseness harmonics at 2× and 3× shaft.
    pub shaft_harmonics: Option<shaft_harmonics::Params>,
    /// Roughness decaying with revolutions.
    pub running_in: Option<running_in::Params>,
    /// Distributed roughness level.
    pub roughness: Option<roughness::Params>,
    /// Defect edge sharpness.
    pub edge_shape: Option<edge_shape::Params>,
}

/// One parameter of an effect.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParamInfo {
    /// Name as given on the command line (`NAME:PARAM=VALUE`).
    pub name: &'static str,
    /// Unit (`-` for dimensionless).
    pub unit: &'static str,
    /// Value when not given.
    pub default: f64,
    /// Smallest allowed value.
    pub min: f64,
    /// Largest allowed value (some are further limited by the output rate, see `note`).
    pub max: f64,
    /// One-line meaning.
    pub doc: &'static str,
}

/// One effect of the catalogue.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EffectInfo {
    /// Name (`--effect NAME`).
    pub name: &'static str,
    /// One-line description.
    pub summary: &'static str,
    /// Parameters, in the order [`Effects::set`] takes them.
    pub params: &'static [ParamInfo],
}

const fn p(
    name: &'static str,
    unit: &'static str,
    default: f64,
    min: f64,
    max: f64,
    doc: &'static str,
) -> ParamInfo {
    ParamInfo {
        name,
        unit,
        default,
        min,
        max,
        doc,
    }
}

/// Every effect with its parameters.
pub const CATALOGUE: [EffectInfo; 9] = [
    EffectInfo {
        name: "slip",
        summary: "random slip of the element passes (jitter of the impact times)",
        params: &[p("fraction", "-", 0.01, 0.0, 0.2, "std. dev. of the element position at the defect, fraction of the element pitch")],
    },
    EffectInfo {
        name: "load-zone",
        summary: "Stribeck load-zone modulation of the defect impact (inner race: at 1x shaft; ball: at FTF), narrowed by an extra Stribeck factor or widened by a contact preload",
        params: &[
            p("depth", "-", 1.0, 0.0, 1.0, "modulation depth: 0 = baseline, 1 = full Stribeck factor"),
            p("epsilon", "-", 0.5, 0.2, 1.0, "load-distribution factor (0.5 = half-circle load zone)"),
            p("preload", "-", 0.0, 0.0, 4.0, "uniform contact preload in static displacements (0 = none; >= 1 loads every element)"),
        ],
    },
    EffectInfo {
        name: "transfer-path",
        summary: "path from bearing to sensor: broadband gain and up to three structural modes (band-pass resonators on the acceleration)",
        params: &[
            p("f1", "Hz", 2000.0, 100.0, 4.0e5, "mode 1 frequency (at most fs/2.5)"),
            p("zeta1", "-", 0.05, 0.005, 0.2, "mode 1 damping ratio"),
            p("gain1", "-", 1.0, 0.0, 10.0, "mode 1 added peak gain (0 = off)"),
            p("f2", "Hz", 3000.0, 100.0, 4.0e5, "mode 2 frequency (at most fs/2.5)"),
            p("zeta2", "-", 0.05, 0.005, 0.2, "mode 2 damping ratio"),
            p("gain2", "-", 0.0, 0.0, 10.0, "mode 2 added peak gain (0 = off)"),
            p("f3", "Hz", 4000.0, 100.0, 4.0e5, "mode 3 frequency (at most fs/2.5)"),
            p("zeta3", "-", 0.05, 0.005, 0.2, "mode 3 damping ratio"),
            p("gain3", "-", 0.0, 0.0, 10.0, "mode 3 added peak gain (0 = off)"),
            p("path_gain", "-", 1.0, 0.01, 10.0, "broadband gain of the path from bearing to sensor (1 = none)"),
        ],
    },
    EffectInfo {
        name: "speed-fluctuation",
        summary: "sinusoidal and random modulation of the shaft speed (all angles follow it)",
        params: &[
            p("amplitude", "-", 0.01, 0.0, 0.1, "relative amplitude of the sinusoidal modulation"),
            p("freq_hz", "Hz", 1.0, 0.01, 1000.0, "frequency of the sinusoidal modulation"),
            p("jitter", "-", 0.0, 0.0, 0.1, "relative RMS of the random (multisine) modulation"),
            p("jitter_hz", "Hz", 5.0, 0.1, 1000.0, "highest frequency of the random modulation"),
        ],
    },
    EffectInfo {
        name: "sensor",
        summary: "measurement chain: white noise floor, one-pole bandwidth, mains hum with harmonics",
        params: &[
            p("noise", "m/s^2", 0.01, 0.0, 100.0, "RMS of the white noise floor"),
            p("corner_hz", "Hz", 0.0, 0.0, 5.0e5, "one-pole low-pass corner (0 = none; at most fs/2)"),
            p("hum", "m/s^2", 0.0, 0.0, 100.0, "mains fundamental amplitude"),
            p("hum_hz", "Hz", 50.0, 40.0, 70.0, "mains frequency"),
            p("hum_harmonics", "-", 0.3, 0.0, 1.0, "2nd and 3rd harmonic amplitude relative to the fundamental"),
        ],
    },
    EffectInfo {
        name: "shaft-harmonics",
        summary: "misalignment/looseness forces at 2x and 3x shaft, added to the imbalance",
        params: &[
            p("f2", "N", 10.0, 0.0, 1.0e4, "force amplitude at 2x shaft"),
            p("f3", "N", 0.0, 0.0, 1.0e4, "force amplitude at 3x shaft"),
        ],
    },
    EffectInfo {
        name: "running-in",
        summary: "roughness raised by a factor decaying with revolutions (needs roughness)",
        params: &[
            p("factor", "-", 3.0, 1.0, 10.0, "initial roughness factor"),
            p("decay_revs", "rev", 1.0e4, 1.0, 1.0e9, "revolutions over which the excess decays by 1/e"),
            p("start_revs", "rev", 0.0, 0.0, 1.0e12, "revolutions already run when the simulation starts"),
            p("summits", "1/rev", 0.0, 0.0, 1000.0, "summit contacts per shaft revolution at the start (decaying likewise; 0 = none)"),
            p("summit_height", "µm", 1.0, 0.0, 20.0, "height of the summits above the mean surface"),
        ],
    },
    EffectInfo {
        name: "roughness",
        summary: "distributed roughness level: scale of the roughness RMS (needs roughness)",
        params: &[p("scale", "-", 1.0, 0.0, 20.0, "factor on the roughness RMS")],
    },
    EffectInfo {
        name: "edge-shape",
        summary: "defect edge sharpness: scales the five-step entry/impact lengths and the asperity",
        params: &[
            p("length_scale", "-", 1.0, 0.2, 5.0, "factor on the entry and impact lengths (< 1 = sharper)"),
            p("asperity_scale", "-", 1.0, 0.0, 5.0, "factor on the trailing-edge asperity height"),
        ],
    },
];

/// Looks an effect up by name.
pub fn info(name: &str) -> Option<&'static EffectInfo> {
    CATALOGUE.iter().find(|e| e.name == name)
}

fn v(values: &[Real], i: usize) -> Real {
    values.get(i).copied().unwrap_or(0.0)
}

impl Effects {
    /// All effects off.
    pub const NONE: Effects = Effects {
        slip: None,
        load_zone: None,
        transfer_path: None,
        speed_fluctuation: None,
        sensor: None,
        shaft_harmonics: None,
        running_in: None,
        roughness: None,
        edge_shape: None,
    };

    /// Whether any effect is on.
    pub fn any(&self) -> bool {
        *self != Effects::NONE
    }

    /// Switches effect `name` on with parameter `values` in catalogue order (as many as
    /// the catalogue lists). Unknown names, a wrong count and out-of-range values are
    /// rejected, naming the field and its bounds.
    pub fn set(&mut self, name: &str, values: &[Real]) -> Result<(), ConfigError> {
        let Some(e) = info(name) else {
            return Err(ConfigError::Unsupported {
                field: "effect",
                what: "unknown effect name (see `wearsim effects`)",
            });
        };
        if values.len() != e.params.len() {
            return Err(ConfigError::Inconsistent {
                field: "effect",
                reason: "wrong number of parameter values for the effect",
            });
        }
        match e.name {
            "slip" => {
                self.slip = Some(slip::Params::new_checked(slip::Params {
                    fraction: v(values, 0),
                })?)
            }
            "load-zone" => {
                self.load_zone = Some(load_zone::Params::new_checked(load_zone::Params {
                    depth: v(values, 0),
                    epsilon: v(values, 1),
                    preload: v(values, 2),
                })?)
            }
            "transfer-path" => {
                let mode = |i: usize| transfer_path::Mode {
                    freq_hz: v(values, 3 * i),
                    zeta: v(values, 3 * i + 1),
                    gain: v(values, 3 * i + 2),
                };
                self.transfer_path =
                    Some(transfer_path::Params::new_checked(transfer_path::Params {
                        modes: [mode(0), mode(1), mode(2)],
                        path_gain: v(values, 9),
                    })?)
            }
            "speed-fluctuation" => {
                self.speed_fluctuation = Some(speed_fluctuation::Params::new_checked(
                    speed_fluctuation::Params {
                        amplitude: v(values, 0),
                        freq_hz: v(values, 1),
                        jitter: v(values, 2),
                        jitter_hz: v(values, 3),
                    },
                )?)
            }
            "sensor" => {
                self.sensor = Some(sensor::Params::new_checked(sensor::Params {
                    noise: v(values, 0),
                    corner_hz: v(values, 1),
                    hum: v(values, 2),
                    hum_hz: v(values, 3),
                    hum_harmonics: v(values, 4),
                })?)
            }
            "shaft-harmonics" => {
                self.shaft_harmonics = Some(shaft_harmonics::Params::new_checked(
                    shaft_harmonics::Params {
                        f2: v(values, 0),
                        f3: v(values, 1),
                    },
                )?)
            }
            "running-in" => {
                self.running_in = Some(running_in::Params::new_checked(running_in::Params {
                    factor: v(values, 0),
                    decay_revs: v(values, 1),
                    start_revs: v(values, 2),
                    summits: v(values, 3),
                    summit_height: v(values, 4),
                })?)
            }
            "roughness" => {
                self.roughness = Some(roughness::Params::new_checked(roughness::Params {
                    scale: v(values, 0),
                })?)
            }
            _ => {
                self.edge_shape = Some(edge_shape::Params::new_checked(edge_shape::Params {
                    length_scale: v(values, 0),
                    asperity_scale: v(values, 1),
                })?)
            }
        }
        Ok(())
    }

    /// Validates every effect that is on (ranges only; the model adds the checks that
    /// depend on the output rate and on roughness being present).
    pub fn new_checked(e: Effects) -> Result<Self, ConfigError> {
        if let Some(p) = e.slip {
            slip::Params::new_checked(p)?;
        }
        if let Some(p) = e.load_zone {
            load_zone::Params::new_checked(p)?;
        }
        if let Some(p) = e.transfer_path {
            transfer_path::Params::new_checked(p)?;
        }
        if let Some(p) = e.speed_fluctuation {
            speed_fluctuation::Params::new_checked(p)?;
        }
        if let Some(p) = e.sensor {
            sensor::Params::new_checked(p)?;
        }
        if let Some(p) = e.shaft_harmonics {
            shaft_harmonics::Params::new_checked(p)?;
        }
        if let Some(p) = e.running_in {
            running_in::Params::new_checked(p)?;
        }
        if let Some(p) = e.roughness {
            roughness::Params::new_checked(p)?;
        }
        if let Some(p) = e.edge_shape {
            edge_shape::Params::new_checked(p)?;
        }
        Ok(e)
    }
}
