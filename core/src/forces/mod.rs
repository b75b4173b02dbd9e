//! Force diagrams of the equation of motion (thesis eq. 1–2, publication III eq. 2):
//! `M y'' + C y' + (K + K_F(t)) y = F_imb + F_s + F_d + F_F(t)`.
//!
//! Each physical effect is its own small component implementing [`ForceDiagram`]; the
//! model (`crate::model`) composes them. The rolling-element contact sum (waviness,
//! roughness, defect load function and its stiffness change `K_F`) is evaluated in one
//! pass over the elements because every term there acts through the same Hertz contact.

pub mod defect;
pub mod imbalance;
pub mod load_function;
pub mod slip;
pub mod surface;

use crate::real::Real;

/// Instantaneous kinematics shared by every force diagram in one evaluation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kinematics {
    /// Shaft angle (rad, wrapped to [0, 2π)).
    pub shaft_angle: Real,
    /// `(cos, sin)` of the shaft angle.
    pub shaft_cs: (Real, Real),
    /// Shaft angular speed ω (rad/s).
    pub shaft_omega: Real,
    /// Shaft angular acceleration (rad/s²).
    pub shaft_alpha: Real,
    /// Cage angle (rad, wrapped), eq. 7: `θ_i = 2π(i−1)/N + θ_cage`.
    pub cage_angle: Real,
    /// `(cos, sin)` of the cage angle.
    pub cage_cs: (Real, Real),
    /// Cage angular speed (rad/s).
    pub cage_omega: Real,
    /// `(cos, sin)` of `N_w · θ_cage` (outer-race waviness phase).
    pub wave_cs: (Real, Real),
}

/// A force diagram: one term of the right-hand side, as a force on the radial degree of
/// freedom `y` (N, positive into the load zone).
pub trait ForceDiagram {
    /// Force (N) at displacement `y` (m) and velocity `v` (m/s) with kinematics `k`.
    fn force(&self, k: &Kinematics, y: Real, v: Real) -> Real;
}
