//! Localized defect on a race or a rolling element (thesis eq. 11–16, publication III
//! eq. 4–12): where it is, which published formulation turns it into a force, and the
//! geometry derived from its topography. The element loop in `crate::model` asks
//! [`DefectShape`] what an element at normalised position `ξ` along the defect experiences.
//!
//! Formulations ([`DefectModel`]):
//! * `FiveStep` (default; thesis Fig. 3): see [`super::load_function`];
//! * `Deflection` (Tadina & Boltežar 2011): extra clearance equal to the geometric drop of
//!   the element into the defect, `s(x) = min(depth, r_b − √(r_b² − x²))`, `x` the distance
//!   to the nearer edge (publication III: `δ_o = ρ_j + ρ_b − (R_o + D_d)`), scaled by `w_f`;
//! * `Sassi` (Sassi et al. 2007): while the element is over the defect an extra force
//!   `F_static (1 + K_impact ΔV²)`, `F_static = Q_max (1 − (1 − cos Ψ)/(2ε))^{1.5}` (Stribeck
//!   load zone, `Ψ` angle from the load-zone centre, ε = 0.5), `ΔV² = (10/28) g (L/B_d)²`;
//! * `Impulse` (publication III §2.1): at the trailing edge a half-sine pulse carrying the
//!   radial momentum `∫F_y dt = m w₁ (1 − 5h/(7r)) L/2`, `w₁ = v/r_b`, over the asperity
//!   crossing length.
//!
//! Ball (rolling-element) defects. The defect sits on the surface of one ball, which spins
//! relative to the cage; neglecting slip the inner race (contact radius
//! `r_i = (P − B_d cos φ)/2`) rolls on the ball (radius `r_b = B_d/2`), so the spin angle is
//! `φ_spin = (θ_shaft − θ_cage)(P − B_d cos φ)/B_d`. With `θ_cage = FTF·θ_shaft` this is
//! `φ_spin = BSF·θ_shaft`, BSF the spin order of thesis eq. 20 (Harris 1966,
//! [`crate::kinematics::FaultOrders::bsf`]). The defect point meets the outer race when
//! `φ_spin + φ₀ ≡ 0 (mod 2π)` and the inner race when it is ≡ π: one over-rolling per race
//! per spin turn, impacts at 2×BSF (Randall & Antoni 2011, MSSP 25 §2.1). Every formulation
//! above applies unchanged with the angles measured on the ball: `ξ = ψ/(L/r_b) + ½`, `ψ`
//! the spin angle from the contact point. In the single-degree-of-freedom model both
//! contacts of a ball are in series in one deflection `δ`, so a defect at either contact
//! changes that ball's `δ` in the same way. The ball orbits with the cage, so its Hertz
//! load (in and out of the load zone) modulates the impacts at FTF.

use crate::bearing::BearingGeometry;
use crate::error::{check_range, ConfigError};
use crate::forces::load_function::LoadFunction;
use crate::real::{cos, sin, sqrt, Real, PI};
use crate::topography::Topography;

/// Where the defect sits.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum DefectLocation {
    /// On the stationary outer race at `angle` (rad; π/2 = centre of the load zone).
    OuterRace {
        /// Angular position (rad).
        angle: Real,
    },
    /// On the rotating inner race at `angle` relative to the shaft at t = 0 (rad).
    InnerRace {
        /// Angular position at t = 0 (rad).
        angle: Real,
    },
    /// On the surface of one rolling element (see the module docs for the kinematics).
    Ball {
        /// Index of the defective element, `0 ..= elements − 1`; element `j` sits at cage
        /// angle `2πj/N` (thesis eq. 7).
        element: u8,
        /// Initial spin phase `φ₀` of the defect on the ball (rad): 0 = at the outer-race
        /// contact at t = 0, π = at the inner-race contact.
        phase: Real,
    },
}

/// Which published formulation turns the defect into a force.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum DefectModel {
    /// Five-step load function through the Hertz contact (thesis Fig. 3).
    FiveStep,
    /// Geometric deflection (Tadina & Boltežar 2011).
    Deflection,
    /// Additive static + dynamic force (Sassi et al. 2007).
    Sassi,
    /// Trailing-edge momentum impulse (publication III).
    Impulse,
}

/// Configuration of a localized defect.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct DefectConfig {
    /// Location.
    pub location: DefectLocation,
    /// Formulation.
    pub model: DefectModel,
    /// Initial topography (Table 1).
    pub topography: Topography,
    /// Impact factor `K_impact` of the Sassi formulation (s²/m).
    pub sassi_k_impact: Real,
}

impl DefectConfig {
    /// Validates the defect against the bearing.
    pub fn new_checked(d: DefectConfig) -> Result<Self, ConfigError> {
        Topography::new_checked(d.topography)?;
        check_range("defect.sassi_k_impact", d.sassi_k_impact, 0.0, 1e3)?;
        match d.location {
            DefectLocation::OuterRace { angle }
            | DefectLocation::InnerRace { angle }
            | DefectLocation::Ball { phase: angle, .. } => {
                check_range("defect.angle", angle, -10.0, 10.0)?;
            }
        }
        Ok(d)
    }
}

impl DefectLocation {
    /// Checks what depends on the bearing and the topography `t`: a ball defect's
    /// `element` must be in `0 ..= elements − 1` (`defect.element`), and its extent along
    /// the ball, `L (1 + 1.5 (count − 1))` (defects at the pitch of [`DefectShape`]), at
    /// most half the ball's circumference `π r_b` (`defect.length`, maximum
    /// `π r_b / (1 + 1.5 (count − 1))`): a longer defect would be under both races at once,
    /// which is no longer a localized defect. Race defects have no such limits here.
    pub fn check_fit(&self, bearing: &BearingGeometry, t: &Topography) -> Result<(), ConfigError> {
        if let DefectLocation::Ball { element, .. } = *self {
            let n = bearing.elements;
            check_range(
                "defect.element",
                element as Real,
                0.0,
                n.saturating_sub(1) as Real,
            )?;
            let max = ball_defect_max_length(bearing.element_diameter, t.count);
            check_range("defect.length", t.length, 1e-7, max)?;
        }
        Ok(())
    }

    /// `t` fitted to the location on `bearing`: on a ball, the length is cut to
    /// [`ball_defect_max_length`] for its count (so that [`DefectLocation::check_fit`]
    /// accepts it); on a race, `t` unchanged. A guard for topographies not grown by the wear
    /// life, whose own growth rule already stays within the limit
    /// (`crate::wear::Life::completed_length`).
    pub fn fit(&self, bearing: &BearingGeometry, t: Topography) -> Topography {
        match self {
            DefectLocation::Ball { .. } => {
                let max = ball_defect_max_length(bearing.element_diameter, t.count);
                if t.length > max {
                    Topography { length: max, ..t }
                } else {
                    t
                }
            }
            DefectLocation::OuterRace { .. } | DefectLocation::InnerRace { .. } => t,
        }
    }

    /// Whether the defect is on a rolling element.
    #[inline(always)]
    pub fn is_ball(&self) -> bool {
        matches!(self, DefectLocation::Ball { .. })
    }
}

/// Longest defect (m) that fits on a rolling element of diameter `element_diameter` (m) as
/// `count` equal defects at the pitch of [`DefectShape`] (1.5 lengths): their extent along
/// the ball, `L (1 + 1.5 (count − 1))`, at most half the ball's circumference `π r_b`, i.e.
/// `π r_b / (1 + 1.5 (count − 1))`. A longer pattern would be under both races at once,
/// which is no longer a localized defect. The one definition of the limit, used by
/// [`DefectLocation::check_fit`], [`DefectLocation::fit`] and the wear life.
pub fn ball_defect_max_length(element_diameter: Real, count: u8) -> Real {
    let spread = 1.0 + 1.5 * count.saturating_sub(1) as Real;
    PI * 0.5 * element_diameter / spread
}

/// Static reference of the loaded bearing, used to size the defect's effect.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StaticReference {
    /// Load of the most loaded element (N).
    pub q_max: Real,
    /// Its deflection (m).
    pub delta_max: Real,
    /// Transverse semi-axis of its contact ellipse (m).
    pub a: Real,
    /// Rolling-direction semi-axis (m).
    pub b: Real,
}

/// Everything derived from one topography on one bearing; recomputed whenever the
/// topography changes (wear evolution), never per step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DefectShape {
    /// Defect length as an angle on the surface carrying it (rad): `L/R` on a race of
    /// radius `R`, `L/r_b` on a ball.
    pub length_angle: Real,
    /// Angular pitch between successive defects of a multi-defect topography (rad): 1.5
    /// defect lengths on the same surface.
    pub spacing_angle: Real,
    /// Number of defects.
    pub count: u8,
    /// Five-step function (used by `FiveStep`).
    pub load: LoadFunction,
    /// Width factor `w_f` (–).
    pub width_factor: Real,
    /// Maximum geometric drop `s` (m), before the width factor.
    pub drop: Real,
    /// Element radius (m).
    pub element_radius: Real,
    /// Defect depth (m).
    pub depth: Real,
    /// Defect length (m).
    pub length: Real,
    /// Radius of the surface the defect sits on (m): the race radius of a race defect,
    /// the element radius `r_b` of a ball defect. Rolling speed over the defect =
    /// relative angular speed of that surface × this radius.
    pub race_radius: Real,
    /// Sassi: `Q_max (1 + K_impact ΔV²)` (N).
    pub sassi_force: Real,
    /// Impulse: `m (1 − 5h/(7r)) L/2 / r_b` (kg), times `v` gives the impulse (N·s).
    pub impulse_per_speed: Real,
    /// Impulse pulse length, normalised to the defect length (–).
    pub pulse: Real,
}

impl DefectShape {
    /// Derives the shape of topography `t` at `location` on `bearing`.
    ///
    /// Ball defects: the angles are measured on the ball (`length_angle = L/r_b`,
    /// `race_radius = r_b`); every other quantity is the race defect's. The geometric drop
    /// `s` of two bodies into a pit of length `L` depends on their relative curvature in the
    /// rolling direction, not on which of them carries the pit (Harris & Kotzalas 2006:
    /// the contact geometry enters through the curvature sum only), so the project's race-defect
    /// approximation with the ball radius alone, `r_b − √(r_b² − L²/4)`, is kept; so are the
    /// descent and asperity-crossing lengths `√(2 r_b s)` and `2b + √(2 r_b h)`. The Sassi
    /// velocity change `(10/28) g (L/B_d)²` is written for any defect length over the ball
    /// diameter (Sassi et al. 2007 model ball defects with it too), and the impulse keeps the
    /// ball's mass and radius (publication III: the radial momentum of the ball's centre as
    /// it climbs the trailing edge, the same whether the edge is on the race or on the
    /// ball).
    pub fn derive(
        t: &Topography,
        location: &DefectLocation,
        bearing: &BearingGeometry,
        sref: &StaticReference,
        sassi_k_impact: Real,
    ) -> Self {
        let rb = 0.5 * bearing.element_diameter;
        let race_radius = match location {
            DefectLocation::InnerRace { .. } => bearing.inner_race_radius(),
            DefectLocation::OuterRace { .. } => bearing.outer_race_radius(),
            DefectLocation::Ball { .. } => rb,
        };
        let l = t.length;
        let half = 0.5 * l;
        let geo = if half < rb {
            rb - sqrt(rb * rb - half * half)
        } else {
            rb
        };
        let drop = if t.depth < geo { t.depth } else { geo };
        let wf = if sref.a > 0.0 {
            let r = t.width / (2.0 * sref.a);
            if r > 1.0 {
                1.0
            } else {
                r
            }
        } else {
            1.0
        };
        let unload = if sref.delta_max > 0.0 {
            let r = drop / sref.delta_max;
            wf * if r > 1.0 { 1.0 } else { r }
        } else {
            0.0
        };
        let entry = (sqrt(2.0 * rb * drop) / l).clamp(1e-3, 0.5);
        let crossing = 2.0 * sref.b + sqrt(2.0 * rb * t.asperity_height);
        let impact = if crossing > 0.0 { crossing / l } else { 0.0 };
        let load = LoadFunction {
            unload,
            entry,
            asperity: wf * t.asperity_height,
            impact,
        };
        let dv2 = (10.0 / 28.0)
            * crate::real::STANDARD_GRAVITY
            * (l / bearing.element_diameter)
            * (l / bearing.element_diameter);
        let m = bearing.element_mass();
        let h = t.asperity_height;
        let impulse_per_speed = m * (1.0 - 5.0 * h / (7.0 * rb)) * half / rb;
        DefectShape {
            length_angle: l / race_radius,
            spacing_angle: 1.5 * l / race_radius,
            count: t.count,
            load,
            width_factor: wf,
            drop,
            element_radius: rb,
            depth: t.depth,
            length: l,
            race_radius,
            sassi_force: sref.q_max * (1.0 + sassi_k_impact * dv2),
            impulse_per_speed,
            pulse: impact,
        }
    }

    /// Normalised length after the trailing edge during which an element is still
    /// affected (the window of the element loop is `ξ ∈ [0, 1 + tail)`).
    pub fn tail(&self, model: DefectModel) -> Real {
        match model {
            DefectModel::FiveStep => self.load.tail(),
            DefectModel::Impulse => self.pulse,
            DefectModel::Deflection | DefectModel::Sassi => 0.0,
        }
    }

    /// Geometric drop (m) of an element at `xi` (Tadina & Boltežar), width factor applied.
    #[inline]
    pub fn geometric_drop(&self, xi: Real) -> Real {
        if !(0.0..1.0).contains(&xi) {
            return 0.0;
        }
        let near = if xi < 0.5 { xi } else { 1.0 - xi } * self.length;
        let rb = self.element_radius;
        let s = if near < rb {
            rb - sqrt(rb * rb - near * near)
        } else {
            rb
        };
        self.width_factor * if s < self.depth { s } else { self.depth }
    }

    /// Sassi et al. force (N) on an element at `xi` whose angle from the load-zone centre
    /// is `psi` (rad); acts along the element direction, positive = pushes the shaft back.
    #[inline]
    pub fn sassi(&self, xi: Real, psi: Real) -> Real {
        if !(0.0..1.0).contains(&xi) {
            return 0.0;
        }
        let base = 1.0 - (1.0 - cos(psi)) / (2.0 * 0.5);
        if base <= 0.0 {
            return 0.0;
        }
        self.sassi_force * base * sqrt(base)
    }

    /// Momentum-impulse force (N) at `xi` for rolling speed `v` (m/s): a half-sine of
    /// impulse `v·impulse_per_speed` over the normalised pulse length.
    #[inline]
    pub fn impulse(&self, xi: Real, v: Real) -> Real {
        if self.pulse <= 0.0 || !(1.0..1.0 + self.pulse).contains(&xi) {
            return 0.0;
        }
        // Pulse duration τ = pulse·L/v; half-sine of impulse J has peak Jπ/(2τ).
        let tau_v = self.pulse * self.length; // τ·v (m)
        let j = v * self.impulse_per_speed;
        j * PI * v / (2.0 * tau_v) * sin(PI * (xi - 1.0) / self.pulse)
    }
}
