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

use super::spec::*;
use crate::forces::defect::DefectShape;
use crate::real::Real;

/// Parameters of the `edge-shape` effect.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Params {
    /// Scale of the entry and impact lengths (–), in [0.2, 5].
    pub length_scale: Real,
    /// Scale of the trailing-edge asperity height (–), in [0, 5].
    pub asperity_scale: Real,
}

impl EffectParams for Params {
    const SPEC: EffectSpec = EffectSpec {
        name: "edge-shape",
        summary: "defect edge sharpness: scales the five-step entry/impact lengths and the asperity",
        params: &[
            param("length_scale", "edge-shape.length_scale", "-", 1.0, 0.2, 5.0, "factor on the entry and impact lengths (< 1 = sharper)"),
            param("asperity_scale", "edge-shape.asperity_scale", "-", 1.0, 0.0, 5.0, "factor on the trailing-edge asperity height"),
        ],
        signature: Signature {
            mechanism: Mechanism::DefectForce,
            moves: moves(true, true, true, false),
        },
        fit: FitSpec {
            fitted: &[
                fit("length_scale", FitBound::Abs(0.2), FitBound::Abs(5.0), true),
                fit("asperity_scale", FitBound::Abs(0.0), FitBound::Abs(5.0), false),
            ],
            fixed: &[],
            needs_defect: true,
            note: "sharpness of the defect edges: impact length and trailing-edge asperity",
        },
    };

    fn from_slice(v: &[Real]) -> Self {
        Params {
            length_scale: at(v, 0),
            asperity_scale: at(v, 1),
        }
    }

    fn write(&self, out: &mut [Real]) {
        put(out, &[self.length_scale, self.asperity_scale]);
    }
}

impl Params {

    /// Applies the scales to a derived defect shape.
    pub fn apply(&self, s: &mut DefectShape) {
        let e = s.load.entry * self.length_scale;
        s.load.entry = if e > 0.5 { 0.5 } else { e };
        s.load.impact *= self.length_scale;
        s.pulse *= self.length_scale;
        s.load.asperity *= self.asperity_scale;
    }
}
