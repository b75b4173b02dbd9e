//! Rolling-bearing kinematic frequencies: thesis eq. 17–20 (Harris 1966), publication IV
//! eq. 14–17. Outer race stationary, inner race rotating with the shaft.

use crate::bearing::BearingGeometry;
use crate::real::Real;

/// Characteristic frequencies as multiples of the shaft rotation frequency (orders, –).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FaultOrders {
    /// Fundamental train (cage) frequency, eq. 17: `½ (1 − B_d/P cos φ)`.
    pub ftf: Real,
    /// Ball pass frequency, outer race, eq. 18: `N/2 (1 − B_d/P cos φ) = N·FTF`.
    pub bpfo: Real,
    /// Ball pass frequency, inner race, eq. 19: `N/2 (1 + B_d/P cos φ) = N (1 − FTF)`.
    pub bpfi: Real,
    /// Ball spin frequency, eq. 20: `P/(2B_d) (1 − (B_d/P cos φ)²)`.
    pub bsf: Real,
}

impl FaultOrders {
    /// The orders of `bearing` (eq. 17–20).
    pub fn of(bearing: &BearingGeometry) -> Self {
        let r = bearing.diameter_ratio();
        let n = bearing.elements as Real;
        let ftf = 0.5 * (1.0 - r);
        FaultOrders {
            ftf,
            bpfo: 0.5 * n * (1.0 - r),
            bpfi: 0.5 * n * (1.0 + r),
            bsf: bearing.pitch_diameter / (2.0 * bearing.element_diameter) * (1.0 - r * r),
        }
    }

    /// The same orders turned into frequencies (Hz) at shaft frequency `shaft_hz`, for a
    /// bearing whose structure has the linearised natural frequency `natural_hz` (Hz; see
    /// [`crate::Model::frequencies_at`], which supplies it).
    pub fn at(&self, shaft_hz: Real, natural_hz: Real) -> FaultFrequencies {
        FaultFrequencies {
            shaft_hz,
            ftf: self.ftf * shaft_hz,
            bpfo: self.bpfo * shaft_hz,
            bpfi: self.bpfi * shaft_hz,
            bsf: self.bsf * shaft_hz,
            natural_hz,
        }
    }
}

/// Characteristic frequencies (Hz) of a bearing in its structure at one shaft speed: the
/// one kinematics type of the project (the simulator's summary, the detector, the zone
/// bands, the life runs and the gap all use it).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FaultFrequencies {
    /// Shaft rotation frequency, 1× (Hz).
    pub shaft_hz: Real,
    /// Cage frequency (Hz), eq. 17.
    pub ftf: Real,
    /// Outer-race ball pass frequency (Hz), eq. 18.
    pub bpfo: Real,
    /// Inner-race ball pass frequency (Hz), eq. 19.
    pub bpfi: Real,
    /// Ball spin frequency (Hz), eq. 20; a ball defect strikes both races, so it shows at
    /// 2×BSF.
    pub bsf: Real,
    /// Linearised natural frequency of the structure with its contacts at static equilibrium,
    /// `√((K + k_c0)/M)/2π` (Hz; [`crate::Model::natural_frequency_hz`]): the centre of the
    /// resonance zone.
    pub natural_hz: Real,
}
