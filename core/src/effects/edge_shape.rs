//! Effect `edge-shape`: the shape of a defect's edges. Fresh spalls and EDM notches
//! (CWRU) have sharp edges; edges round off as the defect wears, which lengthens the
//! element's entry and lowers and lengthens the exit impact (Sawalhi & Randall 2011,
//! MSSP 25, "Vibration response of spalled rolling element bearings: observations,
//! simulations and signal processing techniques to track the spall size"; thesis §4.1.3
//! Fig. 3 and the five-step function [`crate::forces::load_function`]). The effect
//! scales the five-step function's normalised entry length `ξ_e` and asperity-crossing
//! length `Δξ_a` by `L` ∈ [0.2, 5] (< 1 = sharper, faster transitions, more high-frequency
//! content), and the effective asperity height by `A` ∈ [0, 5]. The entry length stays
//! at most ½ (two entries cannot overlap). Only the five-step and impulse formulations
//! have edges; the others are unchanged.

use crate::error::{check_range, ConfigError};
use crate::forces::defect::DefectShape;
use crate::real::Real;

/// Parameters of the `edge-shape` effect.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Params {
    /// Scale of the entry and impact lengths (–), in [0.2, 5].
    pub length_scale: Real,
    /// Scale of the trailing-edge asperity height (–), in [0, 5].
    pub asperity_scale: Real,
}

impl Params {
    /// Validates both scales.
    pub fn new_checked(p: Params) -> Result<Self, ConfigError> {
        check_range("edge-shape.length_scale", p.length_scale, 0.2, 5.0)?;
        check_range("edge-shape.asperity_scale", p.asperity_scale, 0.0, 5.0)?;
        Ok(p)
    }

    /// Applies the scales to a derived defect shape.
    pub fn apply(&self, s: &mut DefectShape) {
        let e = s.load.entry * self.length_scale;
        s.load.entry = if e > 0.5 { 0.5 } else { e };
        s.load.impact *= self.length_scale;
        s.pulse *= self.length_scale;
        s.load.asperity *= self.asperity_scale;
    }
}
