//! The TOML scenario file: every key, its unit and its allowed range are listed in the
//! README ("Configuration reference"). A file may start from a preset (`preset = "…"`) and
//! override any key; without a preset, `[bearing]`, `[structure]` and `[speed]` are
//! required in full. Unknown keys are errors. Range checks are the core's
//! (`wearsim_core::ConfigError`), reported with the same dotted key names as here.

use serde::{Deserialize, Serialize};
use std::path::Path;
use wearsim_core::bearing::{BearingGeometry, ContactKind};
use wearsim_core::forces::defect::{DefectConfig, DefectLocation, DefectModel};
use wearsim_core::forces::imbalance::Imbalance;
use wearsim_core::forces::slip::Slip;
use wearsim_core::forces::surface::{Roughness, Waviness};
use wearsim_core::integrate::IntegratorKind;
use wearsim_core::speed::{SpeedPoint, SpeedProfile, MAX_SHAFT_HZ, MAX_SPEED_POINTS};
use wearsim_core::topography::{self, Topography};
use wearsim_core::{presets, Channels, ModelConfig, Structure};

/// A configuration problem, always naming the key.
#[derive(Debug, thiserror::Error)]
pub enum ConfigFileError {
    /// The file could not be read.
    #[error("cannot read configuration {path}: {source}")]
    Read {
        /// File.
        path: String,
        /// Cause.
        source: std::io::Error,
    },
    /// TOML syntax, unknown key or wrong type (the message names the key and line).
    #[error("configuration {path}: {message}")]
    Parse {
        /// File.
        path: String,
        /// toml's message.
        message: String,
    },
    /// A required key is absent.
    #[error("missing key `{0}`: neither the configuration nor its preset gives it")]
    Missing(&'static str),
    /// A key with a value outside its vocabulary.
    #[error("`{key}` = \"{value}\" is not allowed; use one of: {allowed}")]
    Choice {
        /// Key.
        key: &'static str,
        /// Value given.
        value: String,
        /// Allowed values.
        allowed: String,
    },
    /// The core rejected a value.
    #[error("{0}")]
    Core(wearsim_core::ConfigError),
    /// An unknown effect or parameter, or a value outside its bounds.
    #[error("{0}")]
    Effect(String),
    /// A run that would exceed a documented resource limit (the message names it).
    #[error("{0}")]
    Limit(String),
}

mod terms;
pub mod toml_error;

/// The whole file. Every field is optional at this level; see the module docs.
#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ScenarioFile {
    /// Preset to start from (`wearsim presets`).
    pub preset: Option<String>,
    /// Random seed.
    pub seed: Option<u64>,
    /// Recorded duration (s).
    pub duration: Option<f64>,
    /// Output sample rate (Hz).
    pub fs: Option<f64>,
    /// Time simulated and discarded before recording (s).
    pub settle: Option<f64>,
    /// `rk4`, `exact-zoh` or `exact-foh`.
    pub integrator: Option<String>,
    /// Internal steps per output sample (2..=`MAX_OVERSAMPLE`, 16 on the host); absent = automatic.
    pub oversample: Option<u32>,
    /// `acceleration` or `all`.
    pub channels: Option<String>,
    /// Static radial load (N).
    pub radial_load: Option<f64>,
    /// Radial clearance (m).
    pub clearance: Option<f64>,
    /// Bearing geometry.
    pub bearing: Option<BearingSection>,
    /// M, K, C.
    pub structure: Option<StructureSection>,
    /// Shaft speed.
    pub speed: Option<SpeedSection>,
    /// Imbalance.
    pub imbalance: Option<ImbalanceSection>,
    /// Outer-race waviness.
    pub waviness: Option<WavinessSection>,
    /// Roughness.
    pub roughness: Option<RoughnessSection>,
    /// Localized defect.
    pub defect: Option<DefectSection>,
    /// Random slip.
    pub slip: Option<SlipSection>,
    /// Wear-model material constants (`wearsim life`); absent keys keep the defaults.
    pub material: Option<MaterialSection>,
    /// Life-run settings (`wearsim life`).
    pub life: Option<LifeSection>,
    /// Candidate effects (`[[effect]]` tables: `name`, `params = { ... }`); see
    /// `wearsim effects`.
    #[serde(default)]
    pub effect: Vec<crate::effects::EffectSection>,
}

macro_rules! material_section {
    ($($field:ident: $ty:ty),* $(,)?) => {
        /// `[material]`: constants of the wear model (see `wearsim_core::wear::Material`).
        #[derive(Debug, Clone, Default, Deserialize, Serialize)]
        #[serde(deny_unknown_fields)]
        pub struct MaterialSection {
            $(#[doc = concat!("`", stringify!($field), "`")] pub $field: Option<$ty>,)*
        }

        impl MaterialSection {
            /// The defaults with the given keys replaced (validated later by the core).
            pub fn apply(&self, mut m: wearsim_core::wear::Material) -> wearsim_core::wear::Material {
                $(if let Some(v) = self.$field { m.$field = v; })*
                m
            }
        }
    };
}

material_section! {
    youngs_modulus: f64, yield_strength: f64, hardness: f64, k_threshold: f64, crack_c0: f64,
    crack_m0: f64, life_exponent: f64, life_factor: f64, dent_fraction: f64, asperity_beta: f64,
    initiation_passes: f64, overrolling: f64, edge_shakedown_passes: f64, abrasion: f64, spall_depth: f64, breakout_ratio: f64,
    completed_length: f64, failure_defects: u8, propagation_passes: f64, debris_per_breakout: f64,
    debris_flush_passes: f64,
}

/// `[life]`: settings of a life run (command-line options override them).
#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LifeSection {
    /// Film parameter λ.
    pub lambda: Option<f64>,
    /// Steady composite roughness (m).
    pub roughness: Option<f64>,
    /// Initial / steady roughness.
    pub running_in: Option<f64>,
    /// Steady-state slip fraction.
    pub slip: Option<f64>,
}

/// `[bearing]`.
#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BearingSection {
    pub elements: Option<u8>,
    pub element_diameter: Option<f64>,
    pub pitch_diameter: Option<f64>,
    pub contact_angle_deg: Option<f64>,
    pub bore: Option<f64>,
    pub outside_diameter: Option<f64>,
    pub contact: Option<String>,
    pub outer_conformity: Option<f64>,
    pub inner_conformity: Option<f64>,
    pub roller_length: Option<f64>,
    pub youngs_modulus: Option<f64>,
    pub poisson: Option<f64>,
    pub density: Option<f64>,
}

/// `[structure]`.
#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct StructureSection {
    pub mass: Option<f64>,
    pub stiffness: Option<f64>,
    pub damping: Option<f64>,
}

/// `[speed]`: exactly one of `shaft_hz`, `rpm`, (`from_hz`, `to_hz`, `ramp_duration`) or
/// `table = [[t_s, hz], …]`.
#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SpeedSection {
    pub shaft_hz: Option<f64>,
    pub rpm: Option<f64>,
    pub from_hz: Option<f64>,
    pub to_hz: Option<f64>,
    pub ramp_duration: Option<f64>,
    #[serde(default, deserialize_with = "time_speed_rows")]
    pub table: Option<Vec<[f64; 2]>>,
}

/// `speed.table` rows, each exactly `[time_s, shaft_hz]`: a fixed-size array reads the first
/// two values of a longer row and drops the rest without a word.
fn time_speed_rows<'de, D: serde::Deserializer<'de>>(
    d: D,
) -> Result<Option<Vec<[f64; 2]>>, D::Error> {
    let rows: Option<Vec<Vec<f64>>> = Deserialize::deserialize(d)?;
    rows.map(|rows| {
        rows.iter()
            .enumerate()
            .map(|(i, r)| {
                <[f64; 2]>::try_from(r.as_slice()).map_err(|_| {
                    serde::de::Error::custom(format!(
                        "row {i} has {} values; each row is [time_s, shaft_hz]",
                        r.len()
                    ))
                })
            })
            .collect()
    })
    .transpose()
}

/// `[imbalance]`.
#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ImbalanceSection {
    pub enabled: Option<bool>,
    pub mass: Option<f64>,
    pub radius: Option<f64>,
}

/// `[waviness]`.
#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct WavinessSection {
    pub enabled: Option<bool>,
    pub amplitude: Option<f64>,
    pub wavelength: Option<f64>,
}

/// `[roughness]`.
#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RoughnessSection {
    pub enabled: Option<bool>,
    pub rms: Option<f64>,
    pub wavelength: Option<f64>,
    pub debris_gain: Option<f64>,
}

/// `[defect]`. `location = "ball"` puts the defect on rolling element `element` (index
/// 0 ..= N − 1, default 0); its `angle_deg` is then the defect's spin phase on the ball at
/// t = 0 (0° = at the outer-race contact, 180° = at the inner-race contact; default 0).
#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct DefectSection {
    pub enabled: Option<bool>,
    pub location: Option<String>,
    pub angle_deg: Option<f64>,
    /// Defective element of a ball defect (`location = "ball"` only).
    pub element: Option<u8>,
    pub model: Option<String>,
    pub topography: Option<String>,
    pub asperity_height: Option<f64>,
    pub length: Option<f64>,
    pub width: Option<f64>,
    pub depth: Option<f64>,
    pub count: Option<u8>,
    pub debris: Option<f64>,
    pub sassi_k_impact: Option<f64>,
}

/// `[slip]`.
#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SlipSection {
    pub enabled: Option<bool>,
    pub fraction: Option<f64>,
}

/// Run parameters that are not part of the physical model.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunSettings {
    /// Preset the scenario started from, if any.
    pub preset: Option<String>,
    /// Seed.
    pub seed: u64,
    /// Recorded duration (s).
    pub duration: f64,
    /// Discarded settling time (s).
    pub settle: f64,
}

/// Default recorded duration (s).
pub const DEFAULT_DURATION: f64 = 1.0;
/// Default settling time (s): the start transient of the reference decays by e⁻⁶ in it.
pub const DEFAULT_SETTLE: f64 = 0.05;
/// Longest duration `simulate` keeps in memory (s); longer runs stream (`life --dense`).
pub const MAX_DURATION: f64 = 600.0;
/// Most samples (`(settle + duration) × fs`) a `simulate` run keeps in memory: 2²⁵
/// (33.5 M, 268 MB per f64 column; e.g. 600 s at 55.9 kHz). Longer runs are refused with
/// this limit named (`life --dense` streams without a limit).
pub const MAX_SIMULATE_SAMPLES: f64 = (1u64 << 25) as f64;
/// Default preset.
pub const DEFAULT_PRESET: &str = "thesis-61810";

/// Names accepted for `[defect] topography` and `--topography`.
pub fn topography_names() -> Vec<&'static str> {
    let mut v = vec!["healthy"];
    v.extend(topography::TABLE_1.iter().map(|(n, _)| *n));
    v
}

fn choice<T: Copy>(
    key: &'static str,
    value: &str,
    table: &[(&str, T)],
) -> Result<T, ConfigFileError> {
    table
        .iter()
        .find(|(n, _)| *n == value)
        .map(|(_, t)| *t)
        .ok_or_else(|| ConfigFileError::Choice {
            key,
            value: value.to_string(),
            allowed: table.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(", "),
        })
}

fn req<T>(v: Option<T>, base: Option<T>, key: &'static str) -> Result<T, ConfigFileError> {
    v.or(base).ok_or(ConfigFileError::Missing(key))
}

/// Integrator names.
pub const INTEGRATORS: [(&str, IntegratorKind); 3] = [
    ("rk4", IntegratorKind::Rk4),
    ("exact-zoh", IntegratorKind::ExactZoh),
    ("exact-foh", IntegratorKind::ExactFoh),
];
/// Defect formulation names.
pub const DEFECT_MODELS: [(&str, DefectModel); 4] = [
    ("five-step", DefectModel::FiveStep),
    ("deflection", DefectModel::Deflection),
    ("sassi", DefectModel::Sassi),
    ("impulse", DefectModel::Impulse),
];

/// Largest configuration file (scenario TOML or sweep spec) read, bytes (1 MiB: the
/// longest real one is a sweep grid of a few thousand values, tens of kB; the TOML parser
/// holds about 60 bytes per byte of a long array, so a 14 MB speed table took 894 MB before
/// its 17th row was refused).
pub const MAX_CONFIG_BYTES: u64 = 1 << 20;

/// The text of the configuration file `path` (a scenario or a sweep spec), read only up to
/// [`MAX_CONFIG_BYTES`]: a larger, endless (`/dev/zero`) or non-UTF-8 file is refused
/// without holding more than the limit.
pub fn read_config_text(path: &Path) -> Result<String, ConfigFileError> {
    let bytes = crate::io::record::read_capped(
        path,
        MAX_CONFIG_BYTES,
        "configuration file",
        &format!("{MAX_CONFIG_BYTES} bytes per configuration file"),
    )
    .map_err(|e| match e {
        crate::io::IoError::Io { source, .. } => ConfigFileError::Read {
            path: path.display().to_string(),
            source,
        },
        other => ConfigFileError::Limit(other.to_string()),
    })?;
    String::from_utf8(bytes).map_err(|e| ConfigFileError::Parse {
        path: path.display().to_string(),
        message: format!("not UTF-8 text ({e})"),
    })
}

impl ScenarioFile {
    /// Reads and parses a TOML file (syntax, types and unknown keys are checked here).
    pub fn load(path: &Path) -> Result<Self, ConfigFileError> {
        Self::parse(&read_config_text(path)?, &path.display().to_string())
    }

    /// Parses TOML text; `origin` names it in errors.
    pub fn parse(text: &str, origin: &str) -> Result<Self, ConfigFileError> {
        let file: Self = toml::from_str(text).map_err(|e| ConfigFileError::Parse {
            path: origin.to_string(),
            message: toml_error::describe(text, &e),
        })?;
        crate::effects::check_unique(
            file.effect.iter().map(|e| e.name.as_str()),
            "effect",
            ".name",
        )
        .map_err(ConfigFileError::Effect)?;
        Ok(file)
    }

    /// Resolves the file into a validated-ready model configuration and run settings.
    pub fn resolve(&self) -> Result<(ModelConfig, RunSettings), ConfigFileError> {
        let base = match &self.preset {
            Some(name) => Some(
                presets::by_name(name).ok_or_else(|| ConfigFileError::Choice {
                    key: "preset",
                    value: name.clone(),
                    allowed: presets::NAMES.join(", "),
                })?,
            ),
            None => None,
        };
        let b0 = base.as_ref().map(|c| c.bearing);
        let bs = self.bearing.clone().unwrap_or_default();
        let contact = match &bs.contact {
            Some(c) => choice(
                "bearing.contact",
                c,
                &[("point", ContactKind::Point), ("line", ContactKind::Line)],
            )?,
            None => b0.map(|b| b.contact).unwrap_or(ContactKind::Point),
        };
        let elements = req(bs.elements, b0.map(|b| b.elements), "bearing.elements")?;
        let element_diameter = req(
            bs.element_diameter,
            b0.map(|b| b.element_diameter),
            "bearing.element_diameter",
        )?;
        let pitch_diameter = req(
            bs.pitch_diameter,
            b0.map(|b| b.pitch_diameter),
            "bearing.pitch_diameter",
        )?;
        // Bore and outside diameter not given: the preset's while its pitch and ball
        // diameters stand, else the section rule of a bearing that is no preset (a
        // resized bearing must not inherit the preset's rings).
        let rings = match b0 {
            Some(b)
                if b.pitch_diameter == pitch_diameter && b.element_diameter == element_diameter =>
            {
                (b.bore, b.outside_diameter)
            }
            _ => crate::geometry::section_diameters(pitch_diameter, element_diameter),
        };
        let bearing = BearingGeometry {
            elements,
            element_diameter,
            pitch_diameter,
            contact_angle: req(
                bs.contact_angle_deg.map(f64::to_radians),
                b0.map(|b| b.contact_angle),
                "bearing.contact_angle_deg",
            )?,
            bore: bs.bore.unwrap_or(rings.0),
            outside_diameter: bs.outside_diameter.unwrap_or(rings.1),
            contact,
            outer_conformity: bs
                .outer_conformity
                .or(b0.map(|b| b.outer_conformity))
                .unwrap_or(0.52),
            inner_conformity: bs
                .inner_conformity
                .or(b0.map(|b| b.inner_conformity))
                .unwrap_or(0.515),
            roller_length: bs
                .roller_length
                .or(b0.map(|b| b.roller_length))
                .unwrap_or(0.0),
            youngs_modulus: bs
                .youngs_modulus
                .or(b0.map(|b| b.youngs_modulus))
                .unwrap_or(208e9),
            poisson: bs.poisson.or(b0.map(|b| b.poisson)).unwrap_or(0.3),
            density: bs.density.or(b0.map(|b| b.density)).unwrap_or(7830.0),
        };
        BearingGeometry::new_checked(bearing)?;
        let s0 = base.as_ref().map(|c| c.structure);
        let ss = self.structure.clone().unwrap_or_default();
        let structure = Structure {
            mass: req(ss.mass, s0.map(|s| s.mass), "structure.mass")?,
            stiffness: req(ss.stiffness, s0.map(|s| s.stiffness), "structure.stiffness")?,
            damping: req(ss.damping, s0.map(|s| s.damping), "structure.damping")?,
        };
        let speed = match &self.speed {
            Some(sp) => speed_from(sp)?,
            None => base
                .as_ref()
                .map(|c| c.speed.clone())
                .ok_or(ConfigFileError::Missing("speed.shaft_hz"))?,
        };
        let integrator = match &self.integrator {
            Some(s) => choice("integrator", s, &INTEGRATORS)?,
            None => base
                .as_ref()
                .map(|c| c.integrator)
                .unwrap_or(IntegratorKind::ExactFoh),
        };
        let channels = match &self.channels {
            Some(s) => choice(
                "channels",
                s,
                &[
                    ("acceleration", Channels::Acceleration),
                    ("all", Channels::All),
                ],
            )?,
            None => Channels::Acceleration,
        };
        let imbalance = section(
            self.imbalance.as_ref().map(|s| s.enabled),
            base.as_ref().and_then(|c| c.imbalance),
            || {
                let s = self.imbalance.clone().unwrap_or_default();
                let b = base.as_ref().and_then(|c| c.imbalance);
                Ok(Imbalance {
                    mass: req(s.mass, b.map(|x| x.mass), "imbalance.mass")?,
                    radius: req(s.radius, b.map(|x| x.radius), "imbalance.radius")?,
                })
            },
            self.imbalance.is_some(),
        )?;
        let waviness = section(
            self.waviness.as_ref().map(|s| s.enabled),
            base.as_ref().and_then(|c| c.waviness),
            || {
                let s = self.waviness.clone().unwrap_or_default();
                let b = base.as_ref().and_then(|c| c.waviness);
                Ok(Waviness {
                    amplitude: req(s.amplitude, b.map(|x| x.amplitude), "waviness.amplitude")?,
                    wavelength: req(
                        s.wavelength,
                        b.map(|x| x.wavelength).or(Some(0.8e-3)),
                        "waviness.wavelength",
                    )?,
                })
            },
            self.waviness.is_some(),
        )?;
        let roughness = section(
            self.roughness.as_ref().map(|s| s.enabled),
            base.as_ref().and_then(|c| c.roughness),
            || {
                let s = self.roughness.clone().unwrap_or_default();
                let b = base.as_ref().and_then(|c| c.roughness);
                Ok(Roughness {
                    rms: req(s.rms, b.map(|x| x.rms), "roughness.rms")?,
                    wavelength: req(
                        s.wavelength,
                        b.map(|x| x.wavelength).or(Some(0.02e-3)),
                        "roughness.wavelength",
                    )?,
                    debris_gain: s.debris_gain.or(b.map(|x| x.debris_gain)).unwrap_or(4.0),
                })
            },
            self.roughness.is_some(),
        )?;
        let slip = section(
            self.slip.as_ref().map(|s| s.enabled),
            base.as_ref().and_then(|c| c.slip),
            || {
                let s = self.slip.clone().unwrap_or_default();
                let b = base.as_ref().and_then(|c| c.slip);
                Ok(Slip {
                    fraction: req(s.fraction, b.map(|x| x.fraction), "slip.fraction")?,
                })
            },
            self.slip.is_some(),
        )?;
        let defect = self.defect_config(base.as_ref().and_then(|c| c.defect))?;
        let cfg = ModelConfig {
            bearing,
            structure,
            radial_load: req(
                self.radial_load,
                base.as_ref().map(|c| c.radial_load),
                "radial_load",
            )?,
            clearance: self
                .clearance
                .or(base.as_ref().map(|c| c.clearance))
                .unwrap_or(0.0),
            speed,
            imbalance,
            waviness,
            roughness,
            defect,
            slip,
            integrator,
            output_rate: self
                .fs
                .or(base.as_ref().map(|c| c.output_rate))
                .unwrap_or(20_000.0),
            oversample: self.oversample.or(base.as_ref().and_then(|c| c.oversample)),
            channels,
            effects: crate::effects::build(&self.effect).map_err(ConfigFileError::Effect)?,
        };
        let run = RunSettings {
            preset: self.preset.clone(),
            seed: self.seed.unwrap_or(1),
            duration: self.duration.unwrap_or(DEFAULT_DURATION),
            settle: self.settle.unwrap_or(DEFAULT_SETTLE),
        };
        check_run(&run)?;
        // The rate's own range first: a rate out of it is the error, not the memory its
        // samples would need (stop 68: `--fs 1e9` and `--fs inf` were told the memory limit).
        let (lo, hi) = wearsim_core::model::OUTPUT_RATE_RANGE;
        wearsim_core::error::check_range("fs", cfg.output_rate, lo, hi)
            .map_err(ConfigFileError::Core)?;
        let samples = (run.settle + run.duration) * cfg.output_rate;
        if samples > MAX_SIMULATE_SAMPLES {
            return Err(ConfigFileError::Limit(format!(
                "(settle + duration) × fs = ({} + {}) s × {} Hz = {samples:.0} samples exceeds the in-memory limit of {MAX_SIMULATE_SAMPLES} samples (2^25); shorten duration or lower fs (`life --dense` streams)",
                run.settle, run.duration, cfg.output_rate
            )));
        }
        // `[material]` and `[life]` are validated even by commands that do not use them.
        if self.material.is_some() || self.life.is_some() {
            wearsim_core::wear::Life::new_checked(
                self.life_config(None, wearsim_core::wear::LifeConfig::DEFAULT.cycle_cap),
                &cfg.bearing,
                1.0,
                wearsim_core::wear::Site::of(cfg.defect.as_ref().map(|d| &d.location)),
            )?;
        }
        Ok((cfg, run))
    }

    /// The wear configuration of this file: the defaults with `[material]` and `[life]`
    /// applied, `lambda` (an argument) overriding the file's, and the cycle cap.
    pub fn life_config(
        &self,
        lambda: Option<f64>,
        cycle_cap: f64,
    ) -> wearsim_core::wear::LifeConfig {
        let d = wearsim_core::wear::LifeConfig::DEFAULT;
        let ls = self.life.clone().unwrap_or_default();
        wearsim_core::wear::LifeConfig {
            material: self
                .material
                .as_ref()
                .map(|m| m.apply(d.material))
                .unwrap_or(d.material),
            lambda: lambda.or(ls.lambda).unwrap_or(d.lambda),
            roughness: ls.roughness.unwrap_or(d.roughness),
            running_in: ls.running_in.unwrap_or(d.running_in),
            slip: ls.slip.unwrap_or(d.slip),
            cycle_cap,
        }
    }

    fn defect_config(
        &self,
        base: Option<DefectConfig>,
    ) -> Result<Option<DefectConfig>, ConfigFileError> {
        let Some(s) = &self.defect else {
            return Ok(base);
        };
        if s.enabled == Some(false)
            || s.topography.as_deref() == Some("healthy")
            || s.location.as_deref() == Some("none")
        {
            return Ok(None);
        }
        let b = base.unwrap_or(presets::outer_race_defect(topography::MEDIUM_DEFECT));
        let angle = s.angle_deg.map(f64::to_radians);
        let location = match s.location.as_deref() {
            Some("outer") => DefectLocation::OuterRace {
                angle: angle.unwrap_or(std::f64::consts::FRAC_PI_2),
            },
            Some("inner") => DefectLocation::InnerRace {
                angle: angle.unwrap_or(0.0),
            },
            Some("ball") => DefectLocation::Ball {
                element: s.element.unwrap_or(0),
                phase: angle.unwrap_or(0.0),
            },
            Some(other) => {
                return Err(ConfigFileError::Choice {
                    key: "defect.location",
                    value: other.into(),
                    allowed: "outer, inner, ball, none".into(),
                })
            }
            None => match (b.location, angle) {
                (DefectLocation::OuterRace { .. }, Some(a)) => {
                    DefectLocation::OuterRace { angle: a }
                }
                (DefectLocation::InnerRace { .. }, Some(a)) => {
                    DefectLocation::InnerRace { angle: a }
                }
                (DefectLocation::Ball { element, phase }, a) => DefectLocation::Ball {
                    element: s.element.unwrap_or(element),
                    phase: a.unwrap_or(phase),
                },
                (l, _) => l,
            },
        };
        if s.element.is_some() && !location.is_ball() {
            return Err(ConfigFileError::Core(
                wearsim_core::ConfigError::Inconsistent {
                    field: "defect.element",
                    reason: "applies to a ball defect only (location = \"ball\")",
                },
            ));
        }
        let model = match &s.model {
            Some(m) => choice("defect.model", m, &DEFECT_MODELS)?,
            None => b.model,
        };
        let mut t = match &s.topography {
            Some(name) => topography::by_name(name).ok_or_else(|| ConfigFileError::Choice {
                key: "defect.topography",
                value: name.clone(),
                allowed: topography_names().join(", "),
            })?,
            None => b.topography,
        };
        t = Topography {
            asperity_height: s.asperity_height.unwrap_or(t.asperity_height),
            length: s.length.unwrap_or(t.length),
            width: s.width.unwrap_or(t.width),
            depth: s.depth.unwrap_or(t.depth),
            count: s.count.unwrap_or(t.count),
            debris: s.debris.unwrap_or(t.debris),
        };
        Ok(Some(DefectConfig {
            location,
            model,
            topography: t,
            sassi_k_impact: s.sassi_k_impact.unwrap_or(b.sassi_k_impact),
        }))
    }
}

/// An optional physical section: `enabled = false` removes it; present keys override the
/// base; a section given without a base must be complete.
fn section<T, F: FnOnce() -> Result<T, ConfigFileError>>(
    enabled: Option<Option<bool>>,
    base: Option<T>,
    build: F,
    given: bool,
) -> Result<Option<T>, ConfigFileError> {
    match enabled {
        Some(Some(false)) => Ok(None),
        _ if given => build().map(Some),
        _ => Ok(base),
    }
}

/// Slowest shaft speed a simulation runs at, rpm (the core's 0.001 Hz).
pub const MIN_SIM_RPM: f64 = 0.06;
/// Fastest shaft speed a simulation runs at, rpm (the core's `MAX_SHAFT_HZ`).
#[allow(clippy::unnecessary_cast)] // `Real` is f32 in the f32 build of the core.
pub const MAX_SIM_RPM: f64 = 60.0 * MAX_SHAFT_HZ as f64;

/// Checks a shaft speed given in rpm against the simulation's range, in rpm, so that a
/// user who typed rpm is not answered in Hz; `what` names where it came from (`--rpm`,
/// `speed.rpm`, a file).
pub fn check_sim_rpm(what: &str, rpm: f64) -> Result<f64, String> {
    if rpm.is_finite() && (MIN_SIM_RPM..=MAX_SIM_RPM).contains(&rpm) {
        Ok(rpm)
    } else {
        Err(format!(
            "{what} = {rpm} rpm is out of range: allowed {MIN_SIM_RPM}..={MAX_SIM_RPM} rpm (shaft speed 0.001..={MAX_SHAFT_HZ} Hz)"
        ))
    }
}

fn speed_from(sp: &SpeedSection) -> Result<SpeedProfile, ConfigFileError> {
    let kinds = [
        sp.shaft_hz.is_some(),
        sp.rpm.is_some(),
        sp.from_hz.is_some() || sp.to_hz.is_some(),
        sp.table.is_some(),
    ];
    if kinds.iter().filter(|k| **k).count() != 1 {
        return Err(ConfigFileError::Choice {
            key: "speed",
            value: "(several or none)".into(),
            allowed: "exactly one of shaft_hz, rpm, from_hz+to_hz+ramp_duration, table".into(),
        });
    }
    if let Some(f) = sp.shaft_hz {
        return Ok(SpeedProfile::Constant(f));
    }
    if let Some(r) = sp.rpm {
        let r = check_sim_rpm("speed.rpm", r).map_err(ConfigFileError::Limit)?;
        return Ok(SpeedProfile::Constant(r / 60.0));
    }
    if let Some(table) = &sp.table {
        let mut pts = heapless::Vec::<SpeedPoint, MAX_SPEED_POINTS>::new();
        for [t, hz] in table {
            pts.push(SpeedPoint {
                t: *t,
                shaft_hz: *hz,
            })
            .map_err(|_| {
                ConfigFileError::Core(wearsim_core::ConfigError::TooMany {
                    field: "speed.table",
                    count: table.len(),
                    max: MAX_SPEED_POINTS,
                })
            })?;
        }
        return Ok(SpeedProfile::Table(pts));
    }
    Ok(SpeedProfile::Ramp {
        from_hz: req(sp.from_hz, None, "speed.from_hz")?,
        to_hz: req(sp.to_hz, None, "speed.to_hz")?,
        duration: req(sp.ramp_duration, None, "speed.ramp_duration")?,
    })
}

/// Checks the run settings' ranges.
pub fn check_run(run: &RunSettings) -> Result<(), ConfigFileError> {
    wearsim_core::error::check_range("duration", run.duration, 1e-3, MAX_DURATION)?;
    wearsim_core::error::check_range("settle", run.settle, 0.0, 60.0)?;
    Ok(())
}
