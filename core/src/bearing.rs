//! Bearing geometry: the dimensions every other module derives its numbers from.

use crate::error::{check_range, ConfigError};
use crate::real::Real;

/// Largest number of rolling elements in one row that the fixed-size state can hold.
pub const MAX_ELEMENTS: usize = 32;

/// Kind of rolling-element contact, which sets the Hertz load–deflection exponent
/// (thesis eq. 4–10, after Harsha et al.): `Q = K δ^p`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ContactKind {
    /// Ball on race: point contact, `p = 3/2`.
    Point,
    /// Roller on race: line contact, `p = 10/9`.
    Line,
}

impl ContactKind {
    /// The load–deflection exponent `p`.
    pub fn exponent(self) -> Real {
        match self {
            ContactKind::Point => 1.5,
            ContactKind::Line => 10.0 / 9.0,
        }
    }
}

/// Geometry and material of a rolling-element bearing (SI units: m, rad, Pa, kg/m³).
///
/// Construct with [`BearingGeometry::new_checked`]; every other module may then rely on
/// `pitch > element diameter > 0`, `1 ≤ elements ≤ MAX_ELEMENTS` and finite values.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BearingGeometry {
    /// Number of rolling elements per row, `N` (thesis eq. 18).
    pub elements: u8,
    /// Rolling-element (ball or roller) diameter `B_d` (m).
    pub element_diameter: Real,
    /// Pitch diameter `P` (m).
    pub pitch_diameter: Real,
    /// Contact angle `φ` (rad).
    pub contact_angle: Real,
    /// Bore `d` (m), for the NSK ring-frequency formula (eq. 22).
    pub bore: Real,
    /// Outside diameter `D` (m), for eq. 22.
    pub outside_diameter: Real,
    /// Point (ball) or line (roller) contact.
    pub contact: ContactKind,
    /// Groove radius of the outer race over the ball diameter (≈ 0.52–0.53; Harris).
    pub outer_conformity: Real,
    /// Groove radius of the inner race over the ball diameter (≈ 0.51–0.52; Harris).
    pub inner_conformity: Real,
    /// Effective roller length for line contact (m); ignored for balls.
    pub roller_length: Real,
    /// Young's modulus of the rings and elements (Pa); 208 GPa for AISI 52100.
    pub youngs_modulus: Real,
    /// Poisson's ratio (–); 0.3 for AISI 52100.
    pub poisson: Real,
    /// Density (kg/m³); 7830 for AISI 52100.
    pub density: Real,
}

impl BearingGeometry {
    /// Validates every field and returns the geometry, or the first bad field.
    pub fn new_checked(g: BearingGeometry) -> Result<Self, ConfigError> {
        // Too few elements is a range error, not a capacity one: both ends are named.
        if g.elements < 3 || g.elements as usize > MAX_ELEMENTS {
            return Err(ConfigError::OutOfRange {
                field: "bearing.elements",
                value: g.elements as f64,
                min: 3.0,
                max: MAX_ELEMENTS as f64,
            });
        }
        check_range(
            "bearing.element_diameter",
            g.element_diameter as Real,
            1e-4,
            0.5,
        )?;
        check_range(
            "bearing.pitch_diameter",
            g.pitch_diameter as Real,
            1e-3,
            5.0,
        )?;
        if g.pitch_diameter <= g.element_diameter * 1.5 {
            return Err(ConfigError::Inconsistent {
                field: "bearing.pitch_diameter",
                reason: "must exceed 1.5 x element_diameter",
            });
        }
        // Elements must fit on the pitch circle.
        if (g.elements as Real) * g.element_diameter >= crate::real::PI * g.pitch_diameter {
            return Err(ConfigError::Inconsistent {
                field: "bearing.elements",
                reason: "elements * element_diameter exceeds the pitch circumference",
            });
        }
        check_range("bearing.contact_angle", g.contact_angle, 0.0, 0.8)?;
        check_range("bearing.bore", g.bore, 0.0, g.pitch_diameter as Real)?;
        check_range(
            "bearing.outside_diameter",
            g.outside_diameter as Real,
            g.pitch_diameter as Real,
            10.0,
        )?;
        check_range("bearing.outer_conformity", g.outer_conformity, 0.5005, 0.6)?;
        check_range("bearing.inner_conformity", g.inner_conformity, 0.5005, 0.6)?;
        if g.contact == ContactKind::Line {
            check_range("bearing.roller_length", g.roller_length, 1e-4, 0.5)?;
        } else {
            // Unused by point contacts, but echoed into sidecars: finite and in range.
            check_range("bearing.roller_length", g.roller_length, 0.0, 0.5)?;
        }
        check_range("bearing.youngs_modulus", g.youngs_modulus, 1e9, 1e12)?;
        check_range("bearing.poisson", g.poisson, 0.0, 0.49)?;
        check_range("bearing.density", g.density, 100.0, 30_000.0)?;
        Ok(g)
    }

    /// `B_d cos φ / P`, the ratio that every kinematic frequency uses (eq. 17–20).
    pub fn diameter_ratio(&self) -> Real {
        self.element_diameter * libm_cos(self.contact_angle) / self.pitch_diameter
    }

    /// Mass of one ball (kg) from diameter and density; for rollers, the cylinder mass.
    pub fn element_mass(&self) -> Real {
        let r = 0.5 * self.element_diameter;
        match self.contact {
            ContactKind::Point => 4.0 / 3.0 * crate::real::PI * r * r * r * self.density,
            ContactKind::Line => crate::real::PI * r * r * self.roller_length * self.density,
        }
    }

    /// Radius of the outer-race track at the contact (m): `(P/cos φ + B_d)/2`.
    pub fn outer_race_radius(&self) -> Real {
        0.5 * (self.pitch_diameter + self.element_diameter * libm_cos(self.contact_angle))
    }

    /// Radius of the inner-race track at the contact (m): `(P − B_d cos φ)/2`.
    pub fn inner_race_radius(&self) -> Real {
        0.5 * (self.pitch_diameter - self.element_diameter * libm_cos(self.contact_angle))
    }

    /// Effective modulus `E' = E/(1 − ν²)` for two bodies of the same steel (Pa)
    /// (Hamrock & Brewe 1983 use `E' = 2/((1−ν₁²)/E₁ + (1−ν₂²)/E₂)`).
    pub fn effective_modulus(&self) -> Real {
        self.youngs_modulus / (1.0 - self.poisson * self.poisson)
    }
}

#[inline(always)]
fn libm_cos(x: Real) -> Real {
    crate::real::cos(x)
}
