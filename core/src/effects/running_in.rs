//! Effect `running-in`: a new bearing's surfaces are rougher than after a few hours of
//! running; the asperity peaks are plastically flattened and worn off, and the roughness
//! (hence the broadband vibration from it) decays towards its steady level (thesis §2.2
//! on the running-in stage of wear; Kragelsky et al. 1982, *Friction and Wear:
//! Calculation Methods*; Jamari & Schipper 2006 on roughness running-in). Modelled as
//! the roughness RMS multiplied by `1 + (F − 1) exp(−n/n_d)`, `n` the shaft revolutions
//! since the start of the run (plus an optional offset, for example the revolutions
//! already run in a life test), `F` the initial factor and `n_d` the decay length.
//! Needs roughness in the model; the factor is refreshed every 256 internal steps.
//!
//! Running-in also removes the tail of the height distribution: a ground race carries
//! isolated summits well above its RMS roughness, and the first revolutions flatten them
//! plastically (Jamari & Schipper 2006, "Plastic deterministic contact of rough surfaces",
//! and their running-in experiments: the highest summits are deformed first). An element
//! rolling over such a summit gets an extra deflection `s` (the summit height, 0.5–2 µm
//! on a ground race whose RMS roughness is a few tenths of a µm), so its Hertz load rises by
//! `ΔQ = Q_max((1 + s/δ_max)^p − 1)` (thesis eq. 3, `p` = 3/2 point, 10/9 line contact)
//! for the summit's transit time `λ_r/v` — sparse, short impacts that raise the crest
//! factor and kurtosis of the vibration without much energy. Summit contacts arrive as a
//! Poisson process of `S exp(−n/n_d)` per shaft revolution: the summits are flattened
//! over the same decay length as the roughness.

use super::spec::*;
use crate::real::{exp, Real};

/// Parameters of the `running-in` effect.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Params {
    /// Initial roughness factor `F` (–), in [1, 10].
    pub factor: Real,
    /// Decay length `n_d` (revolutions), in [1, 10⁹].
    pub decay_revs: Real,
    /// Revolutions already run before this simulation starts, in [0, 10¹²].
    pub start_revs: Real,
    /// Summit contacts per shaft revolution at the start `S`, in [0, 1000] (0: none).
    pub summits: Real,
    /// Summit height `s` (µm), in [0, 20].
    pub summit_height: Real,
}

impl EffectParams for Params {
    const SPEC: EffectSpec = EffectSpec {
        name: "running-in",
        summary: "roughness raised by a factor decaying with revolutions (needs roughness)",
        params: &[
            param("factor", "running-in.factor", "-", 3.0, 1.0, 10.0, "initial roughness factor"),
            param("decay_revs", "running-in.decay_revs", "rev", 1.0e4, 1.0, 1.0e9, "revolutions over which the excess decays by 1/e"),
            param("start_revs", "running-in.start_revs", "rev", 0.0, 0.0, 1.0e12, "revolutions already run when the simulation starts"),
            param("summits", "running-in.summits", "1/rev", 0.0, 0.0, 1000.0, "summit contacts per shaft revolution at the start (decaying likewise; 0 = none)"),
            param("summit_height", "running-in.summit_height", "µm", 1.0, 0.0, 20.0, "height of the summits above the mean surface"),
        ],
        signature: Signature {
            mechanism: Mechanism::Surface,
            moves: moves(true, false, true, false),
        },
        // In a stationary record of seconds this is a constant roughness factor
        // (identifiable only along life).
        fit: FitSpec {
            fitted: &[fit("factor", FitBound::Abs(1.0), FitBound::Abs(10.0), true)],
            fixed: &[("decay_revs", FitBound::Abs(1.0e4)), ("start_revs", FitBound::Abs(0.0))],
            needs_defect: false,
            note: "roughness raised early in life; constant within a record of seconds",
        },
    };

    fn from_slice(v: &[Real]) -> Self {
        Params {
            factor: at(v, 0),
            decay_revs: at(v, 1),
            start_revs: at(v, 2),
            summits: at(v, 3),
            summit_height: at(v, 4),
        }
    }

    fn write(&self, out: &mut [Real]) {
        put(
            out,
            &[self.factor, self.decay_revs, self.start_revs, self.summits, self.summit_height],
        );
    }
}

impl Params {

    /// Fraction of the initial excess left after `revs` revolutions of this run,
    /// `exp(−(n + n₀)/n_d)`.
    #[inline]
    pub fn decay(&self, revs: Real) -> Real {
        exp(-(revs + self.start_revs) / self.decay_revs)
    }

    /// Roughness multiplier after `revs` revolutions of this run.
    #[inline]
    pub fn scale(&self, revs: Real) -> Real {
        1.0 + (self.factor - 1.0) * self.decay(revs)
    }

    /// Expected summit contacts per shaft revolution after `revs` revolutions.
    #[inline]
    pub fn summit_rate(&self, revs: Real) -> Real {
        self.summits * self.decay(revs)
    }
}

/// Force (N) of one summit contact averaged over an internal step of `h` s: the Hertz
/// load increase `dq` = `Q(δ_max + s) − Q(δ_max)` (N) of the most loaded element, held
/// for the summit's transit time `tau` s (`min(1, τ/h)` of it when the summit passes
/// within the step; the impulse `dq·τ` is kept).
pub fn summit_force(dq: Real, tau: Real, h: Real) -> Real {
    if !(h > 0.0 && dq > 0.0) {
        return 0.0;
    }
    let share = if tau >= h { 1.0 } else { tau / h };
    dq * share
}
