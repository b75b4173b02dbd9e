//! Test-only effect `probe` (compiled only for the core's unit tests): the whole of what a
//! new effect needs in the registry — this file and one `#[cfg(test)]` line in
//! [`super`]'s registration list. It has no physics hook, so it changes no sample.

use super::spec::*;
use crate::real::Real;

/// Parameters of the `probe` effect.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Params {
    /// A dimensionless level (–), in [0, 2].
    pub level: Real,
}

impl EffectParams for Params {
    const SPEC: EffectSpec = EffectSpec {
        name: "probe",
        summary: "test-only effect with one parameter and no physics",
        params: &[param("level", "probe.level", "-", 1.0, 0.0, 2.0, "a level")],
        signature: Signature {
            mechanism: Mechanism::Measurement,
            moves: moves(true, false, false, false),
        },
        fit: FitSpec {
            fitted: &[fit("level", FitBound::Abs(0.0), FitBound::Abs(2.0), false)],
            fixed: &[],
            needs_defect: false,
            note: "test-only",
        },
    };

    fn from_slice(v: &[Real]) -> Self {
        Params { level: at(v, 0) }
    }

    fn write(&self, out: &mut [Real]) {
        put(out, &[self.level]);
    }
}
