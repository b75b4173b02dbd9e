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

    /// The same orders turned into frequencies (Hz) at shaft frequency `shaft_hz`.
    pub fn at(&self, shaft_hz: Real) -> FaultFrequencies {
        FaultFrequencies {
            shaft: shaft_hz,
            ftf: self.ftf * shaft_hz,
            bpfo: self.bpfo * shaft_hz,
            bpfi: self.bpfi * shaft_hz,
            bsf: self.bsf * shaft_hz,
        }
    }
}

/// Characteristic frequencies (Hz) at one shaft speed.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct FaultFrequencies {
    /// Shaft rotation frequency, 1× (Hz).
    pub shaft: Real,
    /// Cage frequency (Hz), eq. 17.
    pub ftf: Real,
    /// Outer-race ball pass frequency (Hz), eq. 18.
    pub bpfo: Real,
    /// Inner-race ball pass frequency (Hz), eq. 19.
    pub bpfi: Real,
    /// Ball spin frequency (Hz), eq. 20.
    pub bsf: Real,
}
