//! Effect `roughness`: the level of distributed roughness. The baseline's effective
//! roughness excitation (a few nm transmitted through the EHL film) is a chosen value;
//! the composite Rq of real races ranges from 0.02 to 0.4 µm and the film carries less
//! of it as the film parameter λ falls (Harris & Kotzalas 2006 ch. 4; thesis §4.1.2 on
//! roughness as the source of the broadband level). This effect scales the roughness RMS
//! by `s` ∈ [0, 20], which raises the broadband (natural-frequency and high-frequency
//! zone) level by `20 log10 s` dB. Needs roughness in the model.

use super::spec::*;
use crate::real::Real;

/// Parameters of the `roughness` effect.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Params {
    /// Scale of the roughness RMS (–), in [0, 20].
    pub scale: Real,
}

impl EffectParams for Params {
    const SPEC: EffectSpec = EffectSpec {
        name: "roughness",
        summary: "distributed roughness level: scale of the roughness RMS (needs roughness)",
        params: &[param("scale", "roughness.scale", "-", 1.0, 0.0, 20.0, "factor on the roughness RMS")],
        signature: Signature {
            mechanism: Mechanism::Surface,
            moves: moves(true, true, false, false),
        },
        fit: FitSpec {
            fitted: &[fit("scale", FitBound::Abs(0.1), FitBound::Abs(20.0), true)],
            fixed: &[],
            needs_defect: false,
            note: "distributed roughness level",
        },
    };

    fn from_slice(v: &[Real]) -> Self {
        Params { scale: at(v, 0) }
    }

    fn write(&self, out: &mut [Real]) {
        put(out, &[self.scale]);
    }
}
