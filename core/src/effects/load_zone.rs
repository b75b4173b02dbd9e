//! Effect `load-zone`: explicit Stribeck load-zone modulation of the defect impact.
//!
//! Under a radial load only the elements in the load zone carry load; Stribeck's
//! distribution (Harris & Kotzalas 2006, *Rolling Bearing Analysis* ch. 7, eq. 7.26) is
//! `Q(ψ) = Q_max (1 − (1 − cos ψ)/(2ε))^{1.5}` (ball bearings) with ψ the element angle
//! from the load-zone centre and ε the load-distribution factor (0.5 for zero clearance).
//! The baseline's Hertz contacts already modulate the defect force through the element
//! load; measured records (e.g. CWRU inner-race faults) often show a deeper modulation
//! because the transmission path and the defect geometry add their own. This effect
//! multiplies the defect's impact term (five-step asperity deflection, Sassi/impulse
//! force, geometric drop) of an element at angle ψ by
//! `g(ψ) = (1 − m) + m · max(0, 1 − (1 − cos ψ)/(2ε))^{1.5}` with depth `m` ∈ [0, 1].
//!
//! * Outer-race defects are stationary: `g` is a constant (no new frequency content,
//!   only a level change when the defect sits off the load-zone centre).
//! * Inner-race defects rotate with the shaft: the impacts are modulated at 1× shaft,
//!   giving sidebands at BPFI ± k·f_shaft in the envelope spectrum.
//! * Ball defects orbit with the cage: the gain follows the defective element's angle,
//!   so the impacts (at 2×BSF) are modulated at FTF, giving sidebands at 2×BSF ± k·FTF and
//!   a stronger FTF line in the envelope spectrum.

use super::spec::*;
use crate::real::{pow_3_2, Real};

/// Largest accepted [`Params::preload`] (–): four static displacements load every element
/// of any radially loaded bearing.
pub const MAX_PRELOAD: Real = 4.0;

/// Parameters of the `load-zone` effect.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Params {
    /// Modulation depth `m` (–), in [0, 1]: 0 = baseline, 1 = full Stribeck factor.
    pub depth: Real,
    /// Load-distribution factor ε (–), in [0.2, 1]: the load zone spans
    /// `|ψ| ≤ arccos(1 − 2ε)`; ε = 0.5 is a half-circle.
    pub epsilon: Real,
    /// Uniform contact preload `δ_p/y₀` (–), in [0, 4]: every element's contact deflection
    /// is raised by `δ_p`, `y₀` being the static radial displacement of the bearing without
    /// it (a negative internal clearance: an interference fit, or an axial spring preload
    /// seen in the radial plane). The contacts then carry load beyond the half-circle, the
    /// Stribeck–Harris factor becomes `ε = ½(1 + δ_p/y)` (Harris & Kotzalas 2006, eq. 7.24
    /// with `P_d = −2δ_p`; `y` the new, smaller displacement), and at `δ_p ≥ y` every
    /// element is loaded: an inner-race defect's impacts are then modulated far less than
    /// the half-circle's on/off at 1× shaft. The contacts also stiffen (the resonance
    /// rises). 0 = the baseline's contacts. The attribution fits it only up to the
    /// bearing's plausible spring preload ([`crate::spring_preload::plausible_preload`]).
    pub preload: Real,
}

impl EffectParams for Params {
    const SPEC: EffectSpec = EffectSpec {
        name: "load-zone",
        summary: "Stribeck load-zone modulation of the defect impact (inner race: at 1x shaft; ball: at FTF), narrowed by an extra Stribeck factor or widened by a contact preload",
        params: &[
            param("depth", "load-zone.depth", "-", 1.0, 0.0, 1.0, "modulation depth: 0 = baseline, 1 = full Stribeck factor"),
            param("epsilon", "load-zone.epsilon", "-", 0.5, 0.2, 1.0, "load-distribution factor (0.5 = half-circle load zone)"),
            param("preload", "load-zone.preload", "-", 0.0, 0.0, MAX_PRELOAD as f64, "uniform contact preload in static displacements (0 = none; >= 1 loads every element; gap fits at most the bearing's spring preload)"),
        ],
        signature: Signature {
            mechanism: Mechanism::DefectForce,
            moves: moves(true, false, true, true),
        },
        // Linear: the zone narrowed by the extra Stribeck factor or widened by the preload
        // (a measured inner race modulated less than the half-circle zone needs the preload).
        fit: FitSpec {
            fitted: &[
                fit("depth", FitBound::Abs(0.0), FitBound::Abs(1.0), false),
                fit("epsilon", FitBound::Abs(0.2), FitBound::Abs(1.0), false),
                // At most the motor's spring preload (`crate::spring_preload`): beyond it the
                // preload's contact stiffening moves the resonance, which is the rig's
                // calibration and the transfer path's, not the load zone's.
                fit("preload", FitBound::Abs(0.0), FitBound::PlausiblePreload, false),
            ],
            fixed: &[],
            needs_defect: true,
            note: "load zone of the defect's impacts: narrowed by an extra Stribeck factor (depth, epsilon) or widened by a contact preload; 1x sidebands (inner race), FTF (ball); a level only for a stationary outer-race defect",
        },
    };

    fn from_slice(v: &[Real]) -> Self {
        Params {
            depth: at(v, 0),
            epsilon: at(v, 1),
            preload: at(v, 2),
        }
    }

    fn write(&self, out: &mut [Real]) {
        put(out, &[self.depth, self.epsilon, self.preload]);
    }
}

impl Params {

    /// Gain `g(ψ)` for an element with `cos ψ = cos_psi` (ψ from the load-zone centre).
    #[inline]
    pub fn gain(&self, cos_psi: Real) -> Real {
        let x = 1.0 - (1.0 - cos_psi) / (2.0 * self.epsilon);
        let s = pow_3_2(x);
        (1.0 - self.depth) + self.depth * s
    }
}
