//! Candidate effects for the sim-to-real gap diagnosis (`docs/sim-to-real.md`): physical
//! terms the baseline model leaves out, each switchable and parameterised within bounds.
//!
//! [`Effects`] is part of [`crate::ModelConfig`]; all effects are off by default and an
//! effect that is off costs at most one `Option` check per internal step (the baseline's
//! per-step cost is unchanged). Every effect is deterministic: same configuration and
//! seed, same samples.
//!
//! # The registry
//!
//! Each effect lives in its own file (`effects/<name>.rs`) which holds its `Params` and
//! their [`EffectParams`] implementation: the [`EffectSpec`] (name, description, parameter
//! specs with unit, default and bounds, signature, fit space) and the conversion to and
//! from values in spec order. The bounds are written there once: validation
//! ([`EffectParams::checked`]), the catalogue ([`CATALOGUE`], `wearsim effects`), the
//! command line and the gap's fit spaces all read them.
//!
//! The `registry!` list below is the one place that names every effect: from it
//! come the module declaration, [`EffectKind`] and [`EffectKind::ALL`],
//! [`EffectKind::name`]/[`EffectKind::from_name`] (an unknown name is a [`ConfigError`]),
//! the [`Effects`] struct with one `Option<Params>` field per effect, [`Effects::NONE`],
//! [`Effects::get`]/[`Effects::set`]/[`Effects::clear`]/[`Effects::take`] by kind,
//! [`Effects::new_checked`] and [`CATALOGUE`].
//!
//! Adding an effect therefore touches two places in the core's registry: **the effect's
//! own file** and **one registration line** below. Its physics then needs a hook where it
//! acts (the model's step or its derived configuration, e.g. `effects.slip` read in
//! `model.rs`), which is unavoidable: the registry cannot know where a new mechanism acts.
//! The unit test `registry_tests::test_only_effect` registers a test-only effect with one
//! `#[cfg(test)]` line and shows that it is in every derived list.

use crate::error::ConfigError;
use crate::real::Real;

pub mod spec;
pub use spec::{
    CellGroups, EffectParams, EffectSpec, FitBound, FitParamSpec, FitSpec, Mechanism, ParamSpec,
    Signature, MAX_PARAMS,
};

/// Former name of [`ParamSpec`] (one parameter of an effect).
pub type ParamInfo = ParamSpec;
/// Former name of [`EffectSpec`] (one effect of the catalogue).
pub type EffectInfo = EffectSpec;

/// Generates everything that lists the effects from one list of
/// `Kind => field: module` lines (see the module documentation).
macro_rules! registry {
    ($( $(#[$attr:meta])* $kind:ident => $field:ident : $module:ident, $doc:literal; )*) => {
        $( $(#[$attr])* pub mod $module; )*

        /// Number of registered effects.
        pub const COUNT: usize = [$( $(#[$attr])* stringify!($kind), )*].len();

        /// One candidate effect (one per effect file).
        #[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
        pub enum EffectKind {
            $( $(#[$attr])* #[doc = $doc] $kind, )*
        }

        impl EffectKind {
            /// Every effect, in registry order.
            pub const ALL: [EffectKind; COUNT] = [$( $(#[$attr])* EffectKind::$kind, )*];

            /// The effect's declaration (name, parameters, bounds, signature, fit space).
            pub const fn spec(self) -> &'static EffectSpec {
                match self {
                    $( $(#[$attr])* EffectKind::$kind => &<$module::Params as EffectParams>::SPEC, )*
                }
            }
        }

        /// The switchable effects; `None` = off.
        #[derive(Debug, Clone, Copy, PartialEq, Default)]
        #[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
        #[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
        pub struct Effects {
            $( $(#[$attr])* #[doc = $doc] pub $field: Option<$module::Params>, )*
        }

        impl Effects {
            /// All effects off.
            pub const NONE: Effects = Effects {
                $( $(#[$attr])* $field: None, )*
            };

            /// Whether effect `kind` is on.
            pub fn is_on(&self, kind: EffectKind) -> bool {
                match kind {
                    $( $(#[$attr])* EffectKind::$kind => self.$field.is_some(), )*
                }
            }

            /// The parameter values of effect `kind` in spec order (trailing entries beyond
            /// its parameter count are 0), `None` when it is off.
            pub fn get(&self, kind: EffectKind) -> Option<[Real; MAX_PARAMS]> {
                match kind {
                    $( $(#[$attr])* EffectKind::$kind => self.$field.map(|p| p.values()), )*
                }
            }

            /// Switches effect `kind` on with parameter values in spec order (as many as
            /// the spec lists). A wrong count and out-of-range values are rejected,
            /// naming the field and its bounds.
            pub fn set(&mut self, kind: EffectKind, values: &[Real]) -> Result<(), ConfigError> {
                match kind {
                    $( $(#[$attr])* EffectKind::$kind => {
                        self.$field = Some(<$module::Params as EffectParams>::from_values(values)?)
                    } )*
                }
                Ok(())
            }

            /// Switches effect `kind` off.
            pub fn clear(&mut self, kind: EffectKind) {
                match kind {
                    $( $(#[$attr])* EffectKind::$kind => self.$field = None, )*
                }
            }

            /// Sets effect `kind` as it is in `other` (on with its parameters, or off).
            pub fn take(&mut self, other: &Effects, kind: EffectKind) {
                match kind {
                    $( $(#[$attr])* EffectKind::$kind => self.$field = other.$field, )*
                }
            }

            /// Validates every effect that is on against its spec's bounds (the model adds
            /// the checks that depend on the output rate and on roughness being present).
            pub fn new_checked(e: Effects) -> Result<Self, ConfigError> {
                $( $(#[$attr])* if let Some(p) = e.$field { p.checked()?; } )*
                Ok(e)
            }
        }

        /// Every effect's declaration, in registry order.
        pub const CATALOGUE: [EffectSpec; COUNT] = [
            $( $(#[$attr])* <$module::Params as EffectParams>::SPEC, )*
        ];
    };
}

registry! {
    Slip => slip: slip, "Random slip of the element passes.";
    LoadZone => load_zone: load_zone, "Stribeck load-zone modulation of the defect impact.";
    TransferPath => transfer_path: transfer_path, "Extra structural modes between bearing and sensor.";
    SpeedFluctuation => speed_fluctuation: speed_fluctuation, "Sinusoidal and random speed modulation.";
    Sensor => sensor: sensor, "Sensor noise floor, bandwidth and mains hum.";
    ShaftHarmonics => shaft_harmonics: shaft_harmonics, "Misalignment/looseness harmonics at 2× and 3× shaft.";
    RunningIn => running_in: running_in, "Roughness decaying with revolutions.";
    Roughness => roughness: roughness, "Distributed roughness level.";
    EdgeShape => edge_shape: edge_shape, "Defect edge sharpness.";
    #[cfg(test)] Probe => probe: probe, "Test-only effect: shows what adding an effect takes.";
}

impl EffectKind {
    /// The effect's name (`--effect NAME`).
    pub const fn name(self) -> &'static str {
        self.spec().name
    }

    /// The effect called `name`; an unknown name is an error.
    pub fn from_name(name: &str) -> Result<EffectKind, ConfigError> {
        EffectKind::ALL
            .iter()
            .copied()
            .find(|k| k.name() == name)
            .ok_or(ConfigError::Unsupported {
                field: "effect",
                what: "unknown effect name (see `wearsim effects`)",
            })
    }
}

/// Looks an effect's declaration up by name (`None` for an unknown name).
pub fn info(name: &str) -> Option<&'static EffectSpec> {
    EffectKind::from_name(name).ok().map(EffectKind::spec)
}

impl Effects {
    /// Whether any effect is on.
    pub fn any(&self) -> bool {
        *self != Effects::NONE
    }

    /// Switches the effect called `name` on (see [`Effects::set`]); an unknown name is an
    /// error.
    pub fn set_named(&mut self, name: &str, values: &[Real]) -> Result<(), ConfigError> {
        self.set(EffectKind::from_name(name)?, values)
    }
}

#[cfg(test)]
mod registry_tests {
    use super::*;

    /// A test-only effect registered with its own file (`probe.rs`) and one line shows up
    /// in every list the registry derives.
    #[test]
    fn test_only_effect() {
        assert_eq!(COUNT, 10);
        assert!(EffectKind::ALL.contains(&EffectKind::Probe));
        assert_eq!(EffectKind::from_name("probe"), Ok(EffectKind::Probe));
        assert!(CATALOGUE.iter().any(|e| e.name == "probe"));
        let mut fx = Effects::NONE;
        assert!(!fx.is_on(EffectKind::Probe));
        assert!(fx.set(EffectKind::Probe, &[1.5]).is_ok());
        assert_eq!(fx.probe.map(|p| p.level), Some(1.5));
        assert_eq!(
            fx.get(EffectKind::Probe).and_then(|v| v.first().copied()),
            Some(1.5)
        );
        assert!(matches!(
            fx.set(EffectKind::Probe, &[2.5]),
            Err(ConfigError::OutOfRange {
                field: "probe.level",
                ..
            })
        ));
        let mut other = Effects::NONE;
        other.take(&fx, EffectKind::Probe);
        assert!(other.any());
        other.clear(EffectKind::Probe);
        assert_eq!(other, Effects::NONE);
        assert!(Effects::new_checked(fx).is_ok());
    }
}
