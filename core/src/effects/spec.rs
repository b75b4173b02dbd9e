//! What an effect declares about itself: name, description, parameters (unit, default,
//! bounds), its signature (which mechanism it changes and which feature-cell groups it
//! should move) and its fit space for the gap attribution. Every effect's file holds one
//! [`EffectSpec`] as [`EffectParams::SPEC`]; the registry in [`super`] collects them.
//! The bounds are written there once: [`EffectParams::checked`] validates against them,
//! and front ends print them.

use crate::error::{check_range, ConfigError};
use crate::real::Real;

/// Most parameters any effect has (transfer-path: three modes × 3 + path gain).
pub const MAX_PARAMS: usize = 10;

/// One parameter of an effect.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParamSpec {
    /// Name as given on the command line (`NAME:PARAM=VALUE`).
    pub name: &'static str,
    /// Dotted configuration path used in errors (`effect.param`).
    pub field: &'static str,
    /// Unit (`-` for dimensionless).
    pub unit: &'static str,
    /// Value when not given.
    pub default: f64,
    /// Smallest allowed value.
    pub min: f64,
    /// Largest allowed value (some are further limited by the output rate, see `doc`).
    pub max: f64,
    /// One-line meaning.
    pub doc: &'static str,
}

/// The mechanism an effect changes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mechanism {
    /// Timing of the element passes (kinematics of the rolling elements).
    Kinematics,
    /// The shaft speed and every angle that follows it.
    Speed,
    /// The defect's force (its shape or its modulation).
    DefectForce,
    /// Distributed surface excitation (roughness, summits).
    Surface,
    /// Forces from the shaft (misalignment, looseness).
    ShaftForce,
    /// The structural path from bearing to sensor.
    Transmission,
    /// The measurement chain after the structure.
    Measurement,
}

/// Feature-cell groups an effect is expected to move (`docs/sim-to-real.md`, cells).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CellGroups {
    /// Band levels.
    pub level: bool,
    /// Spectral shape (band ratios, centroid).
    pub shape: bool,
    /// Waveform statistics (crest factor, kurtosis).
    pub statistics: bool,
    /// Envelope-spectrum lines and sidebands.
    pub envelope: bool,
}

/// Which mechanism an effect changes and which cell groups it should move (used by the
/// attribution to tell effects apart).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Signature {
    /// Mechanism changed.
    pub mechanism: Mechanism,
    /// Cell groups moved.
    pub moves: CellGroups,
}

/// One end of a fitted range, scaled to the record being fitted.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FitBound {
    /// An absolute value (the parameter's unit).
    Abs(f64),
    /// A fraction of the record's sample rate (Hz).
    Fs(f64),
    /// A fraction of the record's RMS (m/s²).
    Rms(f64),
    /// The mains frequency assumed for the record (Hz).
    Mains,
    /// The largest plausible contact preload of the record's bearing, in static
    /// displacements (–): [`crate::spring_preload::plausible_preload`].
    PlausiblePreload,
}

impl FitBound {
    /// The value for a record with sample rate `fs` (Hz), RMS `rms`, mains `mains_hz` and
    /// a bearing whose plausible contact preload is `preload` (–).
    pub fn resolve(&self, fs: f64, rms: f64, mains_hz: f64, preload: f64) -> f64 {
        match *self {
            FitBound::Abs(v) => v,
            FitBound::Fs(f) => f * fs,
            FitBound::Rms(f) => f * rms,
            FitBound::Mains => mains_hz,
            FitBound::PlausiblePreload => preload,
        }
    }
}

/// One parameter the attribution fits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitParamSpec {
    /// Parameter name (one of the effect's [`ParamSpec::name`]).
    pub name: &'static str,
    /// Lower end of the range.
    pub lo: FitBound,
    /// Upper end of the range.
    pub hi: FitBound,
    /// Fitted on a logarithmic scale.
    pub log: bool,
}

/// What the attribution fits of an effect, over which range, and what it holds fixed
/// (everything else takes the default). The catalogue bounds are the physical limits; a
/// fit space is the part of them a record can tell apart.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitSpec {
    /// Parameters fitted (at most three: a fit costs tens to a hundred and fifty runs).
    pub fitted: &'static [FitParamSpec],
    /// Parameters held at a value.
    pub fixed: &'static [(&'static str, FitBound)],
    /// Whether the effect needs a localized defect in the record to act at all.
    pub needs_defect: bool,
    /// Why the space is what it is (reported).
    pub note: &'static str,
}

/// Everything an effect declares about itself.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EffectSpec {
    /// Name (`--effect NAME`).
    pub name: &'static str,
    /// One-line description.
    pub summary: &'static str,
    /// Parameters, in the order [`super::Effects::set`] takes them.
    pub params: &'static [ParamSpec],
    /// Mechanism and the cell groups it moves.
    pub signature: Signature,
    /// Fit space of the gap attribution.
    pub fit: FitSpec,
}

impl EffectSpec {
    /// Looks a parameter up by name.
    pub fn param(&self, name: &str) -> Option<&'static ParamSpec> {
        self.params.iter().find(|p| p.name == name)
    }

    /// Checks a count and every value against the bounds, naming the first bad field.
    pub fn check(&self, values: &[Real]) -> Result<(), ConfigError> {
        if values.len() != self.params.len() {
            return Err(ConfigError::Inconsistent {
                field: "effect",
                reason: "wrong number of parameter values for the effect",
            });
        }
        for (p, v) in self.params.iter().zip(values) {
            check_range(p.field, *v, p.min as Real, p.max as Real)?;
        }
        Ok(())
    }
}

/// The parameters of one effect, convertible to and from values in [`EffectSpec::params`]
/// order.
pub trait EffectParams: Copy + Sized {
    /// The effect's declaration.
    const SPEC: EffectSpec;

    /// Builds the parameters from values in spec order (missing values read as 0; use
    /// [`EffectParams::from_values`] for validated construction).
    fn from_slice(values: &[Real]) -> Self;

    /// Writes the values in spec order into `out` (at least as long as the spec's list).
    fn write(&self, out: &mut [Real]);

    /// Validated construction from values in spec order.
    fn from_values(values: &[Real]) -> Result<Self, ConfigError> {
        Self::SPEC.check(values)?;
        Ok(Self::from_slice(values))
    }

    /// The values in spec order (trailing entries beyond the spec's count are 0).
    fn values(&self) -> [Real; MAX_PARAMS] {
        let mut out = [0.0; MAX_PARAMS];
        self.write(&mut out);
        out
    }

    /// Validates every value against the spec's bounds.
    fn checked(self) -> Result<Self, ConfigError> {
        let v = self.values();
        Self::SPEC.check(v.get(..Self::SPEC.params.len()).unwrap_or(&[]))?;
        Ok(self)
    }
}

/// Value `i` of `values`, 0 when missing (for [`EffectParams::from_slice`]).
#[inline]
pub fn at(values: &[Real], i: usize) -> Real {
    values.get(i).copied().unwrap_or(0.0)
}

/// Writes `src` into the front of `out` (as far as both reach).
#[inline]
pub fn put(out: &mut [Real], src: &[Real]) {
    for (o, s) in out.iter_mut().zip(src) {
        *o = *s;
    }
}

/// A parameter spec (`const` helper for the effects' tables).
pub const fn param(
    name: &'static str,
    field: &'static str,
    unit: &'static str,
    default: f64,
    min: f64,
    max: f64,
    doc: &'static str,
) -> ParamSpec {
    ParamSpec {
        name,
        field,
        unit,
        default,
        min,
        max,
        doc,
    }
}

/// A fitted-parameter spec (`const` helper).
pub const fn fit(name: &'static str, lo: FitBound, hi: FitBound, log: bool) -> FitParamSpec {
    FitParamSpec { name, lo, hi, log }
}

/// Cell groups (`const` helper): level, shape, statistics, envelope.
pub const fn moves(level: bool, shape: bool, statistics: bool, envelope: bool) -> CellGroups {
    CellGroups {
        level,
        shape,
        statistics,
        envelope,
    }
}
