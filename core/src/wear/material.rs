//! Material and tribology constants of the wear model, with their sources. Everything is
//! configurable; [`Material::BEARING_STEEL`] holds the defaults for through-hardened
//! AISI 52100. Constants marked *calibrated* have no literature value for this simplified
//! model and were set once on the thesis's statements, never on measured run-to-failure
//! data.

use crate::error::{check_range, ConfigError};
use crate::real::Real;

/// Material and tribology constants (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Material {
    /// Young's modulus E (Pa): 208 GPa (Harris & Kotzalas 2006).
    pub youngs_modulus: Real,
    /// Yield strength σ_y (Pa): 2.0 GPa for hardened 52100 (Bhadeshia 2012, Prog. Mater.
    /// Sci. 57, bearing-steel review).
    pub yield_strength: Real,
    /// Hardness H (Pa): 7.5 GPa ≈ 750 HV (Bhadeshia 2012).
    pub hardness: Real,
    /// Mode-I threshold stress-intensity range ΔK_th (Pa·√m): 5 MPa√m for hardened
    /// bearing steel (Bhadeshia 2012 reports 3–6).
    pub k_threshold: Real,
    /// Crack-growth coefficient C₀ of `da/dN = C₀ δ_pl^{m₀}` (m^{1−m₀} per cycle);
    /// *calibrated* so that crack propagation in the reference takes a few per cent of
    /// life (Paris-equivalent 1.6·10⁻¹² m/cycle at 10 MPa√m, within the 10⁻¹³–10⁻¹⁰ range
    /// reported for rolling-contact cracks).
    pub crack_c0: Real,
    /// Crack-growth exponent m₀ (–): 1.5, i.e. Paris exponent 3 (δ_pl ∝ ΔK²).
    pub crack_m0: Real,
    /// Lundberg–Palmgren load–life exponent p (–): 3 for point, 10/3 for line contact
    /// (ISO 281). Set from the contact kind; kept here for reference.
    pub life_exponent: Real,
    /// Life factor a_mat on the ISO 281 rating life (–); *calibrated* so that the reference
    /// scenario (61810, 500 N, λ = 2) forms its dent near 3·10⁶ revolutions, half of the
    /// thesis's "e.g. 6 million cycles" life. The 61810 at 500 N has an ISO life of about
    /// 10¹⁰ revolutions: the factor compresses the steady-state fatigue phase only (an
    /// accelerated-life convention); crack and spall phases keep their own laws.
    pub life_factor: Real,
    /// Share of the fatigue life at which the dent forms (–): 0.5, from the thesis ("the
    /// dent appears around the middle of life", Fig. 5).
    pub dent_fraction: Real,
    /// Asperity stress concentration coefficient β in `K_t = 1 + β√(h/b)` (–): 1.0, after
    /// Hannes & Alfredsson 2011 (a shoulder of height h in a contact of half-width b).
    pub asperity_beta: Real,
    /// Fatigue-initiation passes at the reference pressure N_i (–), *calibrated*: with the
    /// dent's shoulder (K_t ≈ 1.3) a crack would open within about 10 % of life, so the
    /// competition with smoothing decides whether it opens at the dent or later. The
    /// median over bearings: each bearing needs `N_i` times its own surface-initiation
    /// scatter factor ([`LifeState::initiation_scatter`](super::LifeState::initiation_scatter)).
    pub initiation_passes: Real,
    /// Over-rolling efficiency c_ol (–): share of eq. 24's elastic-plastic deformation that
    /// stays per pass; *calibrated*: a dent shoulder halves in about 5 % of life.
    pub overrolling: Real,
    /// Shakedown passes of a fresh breakout edge N_sd (–): over-rolling passes in which a
    /// spall's freshly broken-out edge flattens towards its work-hardened residual
    /// ([`SPALL_EDGE_RESIDUAL`](super::life::SPALL_EDGE_RESIDUAL) of its height), its excess over
    /// the residual falling as `exp(−3 n / N_sd)` (95 % gone after `N_sd` passes). 10⁴:
    /// plastic deformation of rough-contact asperities "nearly stops after about 10⁴
    /// contact events" (Jakobsen & Sivebaek 2017, Tribologia 30:60–65; repeated rough
    /// contact turns elastic soon after first loading, Jamari & Schipper 2008, Wear
    /// 264:349–358), applied to the breakout edge as a plastic shoulder under the same
    /// rolling contact. *Chosen from that source before any comparison with measured
    /// lives*; not fitted. The dent's shoulder keeps the over-rolling law
    /// ([`overrolling`](Self::overrolling), the thesis's smoothing competition).
    pub edge_shakedown_passes: Real,
    /// Archard mild-wear coefficient k (–): 1·10⁻⁵ (mild abrasive wear, Masen et al. 2005).
    pub abrasion: Real,
    /// Spall depth at which a crack breaks out (m): 40 µm, about the depth of the maximum
    /// orthogonal shear stress (0.5 b) of heavily loaded ball contacts (Harris & Kotzalas).
    pub spall_depth: Real,
    /// Spall length broken out per completed crack, as a multiple of the spall depth (–):
    /// 7.5, so the first breakout is Table 1's 0.3 mm mild defect at 40 µm depth.
    pub breakout_ratio: Real,
    /// Completed defect length (m): 3 mm (Table 1, large defect).
    pub completed_length: Real,
    /// Number of spawned defects at failure (–): 4.
    pub failure_defects: u8,
    /// Propagation-limit passes N_p (–): the completed defect's trailing edge accumulates
    /// `Σ (σ₀/p_ref)³ / N_p` (the thesis's "accumulated stress reaches the propagation
    /// limit", with the Paris exponent 3 of the crack-growth law) and spawns a new defect
    /// at 1; *calibrated*: the first spawn takes about 2–3 % of life in the reference.
    pub propagation_passes: Real,
    /// Debris added per broken-out spall segment (–).
    pub debris_per_breakout: Real,
    /// Passes for debris to be flushed by a factor e (–).
    pub debris_flush_passes: Real,
}

/// Smallest life factor a material accepts: the fatigue part of a life scales with it, the
/// crack-to-failure part does not, so a life at this factor is about the shortest the wear
/// machine can run.
pub const MIN_LIFE_FACTOR: Real = 1e-9;

/// Largest life factor a material accepts (a fatigue life 1000× ISO 281's: past any
/// measured life-modification factor).
pub const MAX_LIFE_FACTOR: Real = 1e3;

impl Material {
    /// Defaults for AISI 52100 (see each field).
    pub const BEARING_STEEL: Material = Material {
        youngs_modulus: 208e9,
        yield_strength: 2.0e9,
        hardness: 7.5e9,
        k_threshold: 5.0e6,
        crack_c0: 2.0,
        crack_m0: 1.5,
        life_exponent: 3.0,
        life_factor: 4.3e-4,
        dent_fraction: 0.5,
        asperity_beta: 1.0,
        initiation_passes: 4.0e7,
        overrolling: 2.0e-4,
        edge_shakedown_passes: 1.0e4,
        abrasion: 1.0e-5,
        spall_depth: 40e-6,
        breakout_ratio: 7.5,
        completed_length: 3e-3,
        failure_defects: 4,
        propagation_passes: 1.5e7,
        debris_per_breakout: 0.25,
        debris_flush_passes: 2.0e5,
    };

    /// Accelerated constants for demonstrations and tests (firmware, dense-mode tests): the
    /// same laws with the fatigue, initiation and propagation limits, the over-rolling and the edge shakedown
    /// scaled so that a whole life of the reference takes about 300 revolutions (12 s at
    /// 160 rad/s) instead of millions. Not a physical material.
    pub const ACCELERATED: Material = Material {
        life_factor: 1e-8,
        initiation_passes: 2e3,
        propagation_passes: 2e3,
        overrolling: 0.05,
        edge_shakedown_passes: 10.0,
        crack_c0: 300.0,
        ..Material::BEARING_STEEL
    };

    /// Validates every constant against a physically possible range.
    pub fn new_checked(m: Material) -> Result<Self, ConfigError> {
        check_range("material.youngs_modulus", m.youngs_modulus, 1e9, 1e12)?;
        check_range("material.yield_strength", m.yield_strength, 1e7, 1e10)?;
        check_range("material.hardness", m.hardness, 1e8, 3e10)?;
        check_range("material.k_threshold", m.k_threshold, 1e5, 1e8)?;
        check_range("material.crack_c0", m.crack_c0, 1e-12, 1e6)?;
        check_range("material.crack_m0", m.crack_m0, 0.5, 4.0)?;
        check_range("material.life_exponent", m.life_exponent, 1.0, 6.0)?;
        check_range(
            "material.life_factor",
            m.life_factor,
            MIN_LIFE_FACTOR,
            MAX_LIFE_FACTOR,
        )?;
        check_range("material.dent_fraction", m.dent_fraction, 0.01, 0.99)?;
        check_range("material.asperity_beta", m.asperity_beta, 0.0, 10.0)?;
        check_range("material.initiation_passes", m.initiation_passes, 1.0, 1e12)?;
        check_range("material.overrolling", m.overrolling, 0.0, 1.0)?;
        check_range(
            "material.edge_shakedown_passes",
            m.edge_shakedown_passes,
            1.0,
            1e12,
        )?;
        check_range("material.abrasion", m.abrasion, 0.0, 1e-2)?;
        check_range("material.spall_depth", m.spall_depth, 1e-6, 1e-3)?;
        check_range("material.breakout_ratio", m.breakout_ratio, 0.5, 20.0)?;
        check_range("material.completed_length", m.completed_length, 1e-4, 2e-2)?;
        check_range(
            "material.failure_defects",
            m.failure_defects as Real,
            2.0,
            8.0,
        )?;
        check_range(
            "material.propagation_passes",
            m.propagation_passes,
            1.0,
            1e12,
        )?;
        check_range(
            "material.debris_per_breakout",
            m.debris_per_breakout,
            0.0,
            1.0,
        )?;
        check_range(
            "material.debris_flush_passes",
            m.debris_flush_passes,
            1.0,
            1e12,
        )?;
        Ok(m)
    }
}
