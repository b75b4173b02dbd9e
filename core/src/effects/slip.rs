//! Effect `slip`: random slip of the element passes (thesis §4.1.6, publication IV §3
//! case 6). Real rolling elements do not roll perfectly: the cage lags and each element's
//! position at the defect wanders by about 1–2 % of the element pitch (Randall & Antoni
//! 2011, MSSP 25, "Rolling element bearing diagnostics — a tutorial"), which makes the
//! impact train cyclostationary instead of periodic and smears the higher fault-frequency
//! harmonics of the envelope spectrum. This effect exposes the existing
//! [`crate::forces::slip::Slip`] term (it replaces `ModelConfig::slip` when switched on).

use super::spec::*;
use crate::real::Real;

/// Parameters of the `slip` effect.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Params {
    /// Standard deviation of the element position at the defect as a fraction of the
    /// element pitch `2π/N` (–), in [0, 0.2].
    pub fraction: Real,
}

impl EffectParams for Params {
    const SPEC: EffectSpec = EffectSpec {
        name: "slip",
        summary: "random slip of the element passes (jitter of the impact times)",
        params: &[param("fraction", "slip.fraction", "-", 0.01, 0.0, 0.2, "std. dev. of the element position at the defect, fraction of the element pitch")],
        signature: Signature {
            mechanism: Mechanism::Kinematics,
            moves: moves(false, false, false, true),
        },
        // Below 0.2 % of the pitch the envelope lines do not broaden at a record's
        // resolution.
        fit: FitSpec {
            fitted: &[fit("fraction", FitBound::Abs(0.002), FitBound::Abs(0.1), true)],
            fixed: &[],
            needs_defect: true,
            note: "jitter of the element passes: broadens the envelope harmonics",
        },
    };

    fn from_slice(v: &[Real]) -> Self {
        Params { fraction: at(v, 0) }
    }

    fn write(&self, out: &mut [Real]) {
        put(out, &[self.fraction]);
    }
}
