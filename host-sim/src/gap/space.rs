//! Fit spaces: for every candidate effect, which of its parameters the attribution fits,
//! over which range (linear or logarithmic), and which it holds fixed. The catalogue
//! bounds (`wearsim effects`) are the physical limits; a fit space is the part of them a
//! record can tell apart, chosen per effect and scaled to the record (sample rate, level,
//! shaft speed), and documented here because the ranking depends on it.

use super::cells::CellSpec;
use wearsim_core::effects::{self, Effects};

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
    /// Value at normalised coordinate `u` ∈ [0, 1].
    pub fn value(&self, u: f64) -> f64 {
        let u = u.clamp(0.0, 1.0);
        if self.log {
            self.lo * (self.hi / self.lo).powf(u)
        } else {
            self.lo + (self.hi - self.lo) * u
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
}

impl FitSpace {
    /// Parameter values in catalogue order for normalised coordinates `u` (one per fitted
    /// parameter); unfitted parameters take their fixed value or the catalogue default.
    pub fn values(&self, u: &[f64]) -> Vec<f64> {
        let Some(info) = effects::info(self.effect) else {
            return vec![];
        };
        info.params
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
        fx.set(self.effect, &vals)
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

fn fp(name: &'static str, lo: f64, hi: f64, log: bool) -> FitParam {
    FitParam { name, lo, hi, log }
}

/// The fit space of every catalogue effect for a record described by `ctx`.
///
/// Choices (each effect fits at most three parameters, so a fit costs tens to a hundred
/// and fifty simulations):
/// * `slip`: fraction 0.2–10 % of the pitch, log (below 0.2 % the envelope lines do not
///   broaden at the record's resolution).
/// * `load-zone`: depth 0–1, ε 0.2–1 and preload 0–4 static displacements, linear: the
///   zone narrowed by the extra Stribeck factor or widened by the preload (a measured
///   inner race modulated less than the half-circle zone needs the preload).
/// * `transfer-path`: broadband path gain 0.01–10 (log) and one mode, frequency 5–40 % of
///   fs (log) and added gain 0.2–10 (log), damping held at 5 % (a second and third mode
///   are not fitted: with the gain they trade off against each other and make the fit
///   ill-posed).
/// * `speed-fluctuation`: random multisine jitter 0.05–10 % RMS up to 20 Hz (log); the
///   sinusoidal part is off. Slower modulation moves the whole spectrum between segments
///   without changing any segment's cells, so the mean-based gap cannot see it.
/// * `sensor`: white noise 0.3–100 % of the record RMS (log) and mains hum at `mains_hz`
///   0.1–30 % of the record RMS (log); no bandwidth limit (the records' own anti-alias
///   filter is not distinguishable from the model's).
/// * `shaft-harmonics`: 2× and 3× forces 0.5–500 N (log).
/// * `running-in`: initial roughness factor 1–10 decaying over 10⁴ revolutions from the
///   record's start; in a stationary record of seconds this is a constant roughness factor
///   (identifiable only along life).
/// * `roughness`: scale 0.1–20 (log).
/// * `edge-shape`: entry/impact length scale 0.2–5 (log) and asperity scale 0–5.
pub fn spaces(ctx: &Context) -> Vec<FitSpace> {
    let mut v = raw_spaces(ctx);
    // Keep every range inside the catalogue bounds (a loud record could ask for a noise
    // floor above the sensor's limit).
    for s in &mut v {
        if let Some(info) = effects::info(s.effect) {
            for f in &mut s.fitted {
                if let Some(p) = info.params.iter().find(|p| p.name == f.name) {
                    f.hi = f.hi.clamp(p.min, p.max);
                    f.lo = f.lo.clamp(p.min, f.hi);
                }
            }
        }
    }
    v
}

fn raw_spaces(ctx: &Context) -> Vec<FitSpace> {
    let nyq = 0.5 * ctx.fs;
    vec![
        FitSpace {
            effect: "slip",
            fitted: vec![fp("fraction", 0.002, 0.1, true)],
            fixed: vec![],
            needs_defect: true,
            note: "jitter of the element passes: broadens the envelope harmonics",
        },
        FitSpace {
            effect: "load-zone",
            fitted: vec![
                fp("depth", 0.0, 1.0, false),
                fp("epsilon", 0.2, 1.0, false),
                fp("preload", 0.0, 4.0, false),
            ],
            fixed: vec![],
            needs_defect: true,
            note: "load zone of the defect's impacts: narrowed by an extra Stribeck factor (depth, epsilon) or widened by a contact preload; 1x sidebands (inner race), FTF (ball); a level only for a stationary outer-race defect",
        },
        FitSpace {
            effect: "transfer-path",
            fitted: vec![
                fp("path_gain", 0.01, 10.0, true),
                fp("f1", 0.05 * ctx.fs, 0.8 * nyq, true),
                fp("gain1", 0.2, 10.0, true),
            ],
            fixed: vec![("zeta1", 0.05), ("gain2", 0.0), ("gain3", 0.0)],
            needs_defect: false,
            note: "path from bearing to sensor: broadband gain and one structural mode (frequency, gain; 5 % damping)",
        },
        FitSpace {
            effect: "speed-fluctuation",
            fitted: vec![fp("jitter", 5e-4, 0.1, true)],
            fixed: vec![("amplitude", 0.0), ("jitter_hz", 20.0)],
            needs_defect: false,
            note: "random speed modulation up to 20 Hz (drive torque ripple)",
        },
        FitSpace {
            effect: "sensor",
            fitted: vec![
                fp("noise", 0.003 * ctx.rms, ctx.rms, true),
                fp("hum", 0.001 * ctx.rms, 0.3 * ctx.rms, true),
            ],
            fixed: vec![
                ("corner_hz", 0.0),
                ("hum_hz", ctx.mains_hz),
                ("hum_harmonics", 0.3),
            ],
            needs_defect: false,
            note: "white noise floor and mains hum, scaled to the record's RMS",
        },
        FitSpace {
            effect: "shaft-harmonics",
            fitted: vec![fp("f2", 0.5, 500.0, true), fp("f3", 0.5, 500.0, true)],
            fixed: vec![],
            needs_defect: false,
            note: "misalignment/looseness forces at 2x and 3x shaft",
        },
        FitSpace {
            effect: "running-in",
            fitted: vec![fp("factor", 1.0, 10.0, true)],
            fixed: vec![("decay_revs", 1.0e4), ("start_revs", 0.0)],
            needs_defect: false,
            note: "roughness raised early in life; constant within a record of seconds",
        },
        FitSpace {
            effect: "roughness",
            fitted: vec![fp("scale", 0.1, 20.0, true)],
            fixed: vec![],
            needs_defect: false,
            note: "distributed roughness level",
        },
        FitSpace {
            effect: "edge-shape",
            fitted: vec![
                fp("length_scale", 0.2, 5.0, true),
                fp("asperity_scale", 0.0, 5.0, false),
            ],
            fixed: vec![],
            needs_defect: true,
            note: "sharpness of the defect edges: impact length and trailing-edge asperity",
        },
    ]
}

/// The spaces that can act on a record: without a defect the defect effects are dropped.
pub fn applicable(ctx: &Context, has_defect: bool, only: Option<&[String]>) -> Vec<FitSpace> {
    spaces(ctx)
        .into_iter()
        .filter(|s| has_defect || !s.needs_defect)
        .filter(|s| only.is_none_or(|o| o.iter().any(|n| n == s.effect)))
        .collect()
}

/// Context for a spec and a record level.
pub fn context(spec: &CellSpec, rms: f64, mains_hz: f64) -> Context {
    Context {
        fs: spec.fs,
        shaft_hz: spec.ff.shaft_hz,
        rms,
        mains_hz,
    }
}
