//! Rotating imbalance, thesis eq. 3 (publication IV eq. 6):
//! `F_imb = m_u r ω² sin(θ_shaft)` (the printed `sin(2π ω t)` is a typo). With a varying
//! speed the tangential term `− m_u r α cos θ` is added, so run-ups are exact.

use super::{ForceDiagram, Kinematics};
use crate::error::{check_range, ConfigError};
use crate::real::Real;

/// Imbalance mass and eccentricity.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Imbalance {
    /// Unbalanced mass `m_u` (kg); thesis: 0.005 kg.
    pub mass: Real,
    /// Its radius `r` (m); thesis: 0.1 m.
    pub radius: Real,
}

impl Imbalance {
    /// Validates mass in [0, 10] kg and radius in [0, 2] m.
    pub fn new_checked(i: Imbalance) -> Result<Self, ConfigError> {
        check_range("imbalance.mass", i.mass, 0.0, 10.0)?;
        check_range("imbalance.radius", i.radius, 0.0, 2.0)?;
        Ok(i)
    }
}

impl ForceDiagram for Imbalance {
    #[inline(always)]
    fn force(&self, k: &Kinematics, _y: Real, _v: Real) -> Real {
        let (c, s) = k.shaft_cs;
        self.mass * self.radius * (k.shaft_omega * k.shaft_omega * s - k.shaft_alpha * c)
    }
}
