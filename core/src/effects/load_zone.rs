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

use crate::error::{check_range, ConfigError};
use crate::real::{pow_3_2, Real};

/// Largest accepted [`Params::preload`] (–): four static displacements load every element
/// of any radially loaded bearing.
pub const MAX_PRELOAD: Real = 4.0;

/// Parameters of the `load-zone` effect.
#[derive(Debug, Clone, Copy, PartialEq)]
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
    /// rises). 0 = the baseline's contacts.
    pub preload: Real,
}

impl Params {
    /// Validates depth in [0, 1] and epsilon in [0.2, 1].
    pub fn new_checked(p: Params) -> Result<Self, ConfigError> {
        check_range("load-zone.depth", p.depth, 0.0, 1.0)?;
        check_range("load-zone.epsilon", p.epsilon, 0.2, 1.0)?;
        check_range("load-zone.preload", p.preload, 0.0, MAX_PRELOAD)?;
        Ok(p)
    }

    /// Gain `g(ψ)` for an element with `cos ψ = cos_psi` (ψ from the load-zone centre).
    #[inline]
    pub fn gain(&self, cos_psi: Real) -> Real {
        let x = 1.0 - (1.0 - cos_psi) / (2.0 * self.epsilon);
        let s = pow_3_2(x);
        (1.0 - self.depth) + self.depth * s
    }
}
