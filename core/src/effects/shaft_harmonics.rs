//! Effect `shaft-harmonics`: misalignment and mechanical looseness. Imbalance gives a
//! force at 1× shaft; angular/parallel misalignment of the coupling gives a dominant 2×
//! (and 1×) component and looseness a series of harmonics, 3× and above (Randall 2011,
//! *Vibration-based Condition Monitoring* §1.2 and Table 1.1; ISO 13373-3). The effect
//! adds radial forces `F_2 sin(2θ_s) + F_3 sin(3θ_s)` (N), θ_s the shaft angle, to the
//! existing imbalance term; amplitudes are taken as independent of speed (kinematic
//! misalignment forces set by the coupling stiffness and the offset).

use super::spec::*;
use crate::forces::Kinematics;
use crate::real::Real;

/// Parameters of the `shaft-harmonics` effect.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Params {
    /// Force amplitude at 2× shaft (N), in [0, 10⁴].
    pub f2: Real,
    /// Force amplitude at 3× shaft (N), in [0, 10⁴].
    pub f3: Real,
}

impl EffectParams for Params {
    const SPEC: EffectSpec = EffectSpec {
        name: "shaft-harmonics",
        summary: "misalignment/looseness forces at 2x and 3x shaft, added to the imbalance",
        params: &[
            param("f2", "shaft-harmonics.f2", "N", 10.0, 0.0, 1.0e4, "force amplitude at 2x shaft"),
            param("f3", "shaft-harmonics.f3", "N", 0.0, 0.0, 1.0e4, "force amplitude at 3x shaft"),
        ],
        signature: Signature {
            mechanism: Mechanism::ShaftForce,
            moves: moves(true, false, false, true),
        },
        fit: FitSpec {
            fitted: &[
                fit("f2", FitBound::Abs(0.5), FitBound::Abs(500.0), true),
                fit("f3", FitBound::Abs(0.5), FitBound::Abs(500.0), true),
            ],
            fixed: &[],
            needs_defect: false,
            note: "misalignment/looseness forces at 2x and 3x shaft",
        },
    };

    fn from_slice(v: &[Real]) -> Self {
        Params {
            f2: at(v, 0),
            f3: at(v, 1),
        }
    }

    fn write(&self, out: &mut [Real]) {
        put(out, &[self.f2, self.f3]);
    }
}

impl Params {

    /// Radial force (N) at kinematics `k`, from the shaft phasor (no trigonometric calls):
    /// `sin 2θ = 2 s c`, `sin 3θ = s (3 − 4 s²)`.
    #[inline]
    pub fn force(&self, k: &Kinematics) -> Real {
        let (c, s) = k.shaft_cs;
        self.f2 * 2.0 * s * c + self.f3 * s * (3.0 - 4.0 * s * s)
    }
}
