//! Fit spaces: for every candidate effect, which of its parameters the attribution fits,
//! over which range (linear or logarithmic), and which it holds fixed. The catalogue
//! bounds (`wearsim effects`) are the physical limits; a fit space is the part of them a
//! record can tell apart. Each effect declares its space in its own file in the core
//! ([`wearsim_core::effects::FitSpec`], with the reasons); here it is scaled to the record
//! (sample rate, level, mains frequency, the bearing's plausible preload) and clamped to the
//! catalogue bounds.

use super::cells::CellSpec;
use wearsim_core::contact::ElementContact;
use wearsim_core::effects::{EffectKind, Effects, FitBound};
use wearsim_core::model::ModelConfig;

/// The `load-zone` preload's catalogue bound (–, static displacements), the
/// [`Context::preload_max`] of contexts with no bearing to bound it by.
#[allow(clippy::unnecessary_cast)] // Real is f32 in `f32` builds
pub const CATALOGUE_PRELOAD_MAX: f64 = wearsim_core::effects::load_zone::MAX_PRELOAD as f64;

/// One fitted parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct FitParam {
    /// Catalogue parameter name.
    pub name: &'static str,
    /// Lower end of the fitted range (catalogue unit).
    pub lo: f64,
    /// Upper end of the fitted range (catalogue unit).
    pub hi: f64,
    /// Fitted on a logarithmic scale (`lo > 0`).
    pub log: bool,
}

impl FitParam {
    /// Value at normalised coordinate `u` ∈ [0, 1], inside `[lo, hi]`: `lo·(hi/lo)^u`
    /// can round one ulp past `hi` at `u = 1` (a noise floor of 100.00000000000001 where
    /// the catalogue allows 100), which the effect's own range check then refuses.
    pub fn value(&self, u: f64) -> f64 {
        let u = u.clamp(0.0, 1.0);
        let v = if self.log {
            self.lo * (self.hi / self.lo).powf(u)
        } else {
            self.lo + (self.hi - self.lo) * u
        };
        // Not `f64::clamp`, which panics on a NaN bound.
        let (a, b) = (self.lo.min(self.hi), self.lo.max(self.hi));
        if v > b {
            b
        } else if v < a {
            a
        } else {
            v
        }
    }

    /// Normalised coordinate of `v` (clamped to the range).
    pub fn coord(&self, v: f64) -> f64 {
        let u = if self.log {
            (v / self.lo).ln() / (self.hi / self.lo).ln()
        } else {
            (v - self.lo) / (self.hi - self.lo)
        };
        u.clamp(0.0, 1.0)
    }

    /// d(value)/du at `u`: converts an uncertainty in `u` to the catalogue unit.
    pub fn slope(&self, u: f64) -> f64 {
        if self.log {
            self.value(u) * (self.hi / self.lo).ln()
        } else {
            self.hi - self.lo
        }
    }
}

/// What an effect's fit varies and holds.
#[derive(Debug, Clone, PartialEq)]
pub struct FitSpace {
    /// The effect.
    pub kind: EffectKind,
    /// Effect name (catalogue).
    pub effect: &'static str,
    /// Parameters fitted.
    pub fitted: Vec<FitParam>,
    /// Parameters held at a value (everything else takes the catalogue default).
    pub fixed: Vec<(&'static str, f64)>,
    /// Whether the effect needs a localized defect in the record to act at all.
    pub needs_defect: bool,
    /// Why the space is what it is (reported).
    pub note: &'static str,
}

/// What the spaces are scaled to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Context {
    /// Sample rate (Hz).
    pub fs: f64,
    /// Shaft speed (Hz).
    pub shaft_hz: f64,
    /// RMS of the measured record (m/s²): sets the sensor noise and hum ranges.
    pub rms: f64,
    /// Mains frequency (Hz) assumed for hum.
    pub mains_hz: f64,
    /// Largest plausible contact preload of the record's bearing (–, static
    /// displacements): the `load-zone` preload's fitted range ([`preload_limit`]).
    pub preload_max: f64,
}

impl FitSpace {
    /// Parameter values in catalogue order for normalised coordinates `u` (one per fitted
    /// parameter); unfitted parameters take their fixed value or the catalogue default.
    pub fn values(&self, u: &[f64]) -> Vec<f64> {
        self.kind
            .spec()
            .params
            .iter()
            .map(|p| {
                if let Some((i, f)) = self
                    .fitted
                    .iter()
                    .enumerate()
                    .find(|(_, f)| f.name == p.name)
                {
                    f.value(u.get(i).copied().unwrap_or(0.5))
                } else if let Some((_, v)) = self.fixed.iter().find(|(n, _)| *n == p.name) {
                    *v
                } else {
                    p.default
                }
            })
            .map(|v| v.clamp(f64::MIN, f64::MAX))
            .collect()
    }

    /// Adds the effect with coordinates `u` to `fx`; the message names the bad value.
    pub fn apply(&self, fx: &mut Effects, u: &[f64]) -> Result<(), String> {
        let vals: Vec<wearsim_core::Real> = self
            .values(u)
            .iter()
            .map(|v| *v as wearsim_core::Real)
            .collect();
        fx.set(self.kind, &vals)
            .map_err(|e| format!("effect `{}`: {e}", self.effect))
    }

    /// Fitted parameter names and values for coordinates `u`.
    pub fn named(&self, u: &[f64]) -> Vec<(&'static str, f64)> {
        self.fitted
            .iter()
            .zip(u)
            .map(|(f, u)| (f.name, f.value(*u)))
            .collect()
    }
}

/// The fit space of every registered effect for a record described by `ctx`: each
/// effect's [`wearsim_core::effects::FitSpec`] (the choices and their reasons are in the
/// effect's file) resolved to the record and kept inside the catalogue bounds (a loud
/// record could ask for a noise floor above the sensor's limit).
pub fn spaces(ctx: &Context) -> Vec<FitSpace> {
    EffectKind::ALL.iter().map(|k| space(*k, ctx)).collect()
}

/// The fit space of effect `kind` for a record described by `ctx`.
pub fn space(kind: EffectKind, ctx: &Context) -> FitSpace {
    let spec = kind.spec();
    let r = |b: &FitBound| b.resolve(ctx.fs, ctx.rms, ctx.mains_hz, ctx.preload_max);
    let fitted = spec
        .fit
        .fitted
        .iter()
        .map(|f| {
            let mut p = FitParam {
                name: f.name,
                lo: r(&f.lo),
                hi: r(&f.hi),
                log: f.log,
            };
            if let Some(q) = spec.param(f.name) {
                p.hi = p.hi.clamp(q.min, q.max);
                p.lo = p.lo.clamp(q.min, p.hi);
            }
            p
        })
        .collect();
    FitSpace {
        kind,
        effect: spec.name,
        fitted,
        fixed: spec.fit.fixed.iter().map(|(n, b)| (*n, r(b))).collect(),
        needs_defect: spec.fit.needs_defect,
        note: spec.fit.note,
    }
}

/// The spaces that can act on a record: without a defect the defect effects are dropped.
pub fn applicable(ctx: &Context, has_defect: bool, only: Option<&[String]>) -> Vec<FitSpace> {
    spaces(ctx)
        .into_iter()
        .filter(|s| has_defect || !s.needs_defect)
        .filter(|s| only.is_none_or(|o| o.iter().any(|n| n == s.effect)))
        .collect()
}

/// Context for a spec, a record level and the matched simulation's configuration `base`.
pub fn context(spec: &CellSpec, rms: f64, mains_hz: f64, base: &ModelConfig) -> Context {
    Context {
        fs: spec.fs,
        shaft_hz: spec.ff.shaft_hz,
        rms,
        mains_hz,
        preload_max: preload_limit(base),
    }
}

/// The largest plausible `load-zone` preload for the bearing, load, clearance and
/// structure of `cfg` (–): its spring preload over its static displacement
/// ([`wearsim_core::spring_preload::plausible_preload`]), at most the effect's catalogue
/// bound.
pub fn preload_limit(cfg: &ModelConfig) -> f64 {
    let contact = ElementContact::of(&cfg.bearing);
    wearsim_core::spring_preload::plausible_preload(
        &cfg.bearing,
        &contact,
        cfg.clearance,
        cfg.radial_load,
        cfg.structure.stiffness,
        CATALOGUE_PRELOAD_MAX,
    )
}
