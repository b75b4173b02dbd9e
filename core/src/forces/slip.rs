//! Random slippage of the rolling elements (thesis §4.1.6, publication IV §3 case 6):
//! each element's angular position relative to a defect is jittered by a random offset,
//! redrawn once per pass while the element is on the far side of the defect, so that the
//! time between impacts varies randomly. Literature (Randall & Antoni 2011, MSSP 25)
//! reports 1–2 % of the period.

use crate::error::{check_range, ConfigError};
use crate::real::{Real, TAU};
use crate::rng::Xoshiro128pp;

/// Random slip of the element passes.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Slip {
    /// Standard deviation of the element position at the defect, as a fraction of the
    /// element spacing `2π/N` (–). 0.01–0.02 is typical.
    pub fraction: Real,
}

impl Slip {
    /// Validates the fraction in [0, 0.2].
    pub fn new_checked(s: Slip) -> Result<Self, ConfigError> {
        check_range("slip.fraction", s.fraction, 0.0, 0.2)?;
        Ok(s)
    }

    /// Draws a new angular offset (rad) for one element of a bearing with `n` elements.
    #[inline]
    pub fn draw(&self, rng: &mut Xoshiro128pp, n: u8) -> Real {
        self.fraction * (TAU / n as Real) * rng.gauss_approx()
    }
}
