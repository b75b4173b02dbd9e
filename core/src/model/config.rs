//! What a simulation run is ([`ModelConfig`] with its [`Structure`] and [`Channels`]) and
//! its validation into a [`Model`]: each part of the configuration is checked by its own
//! small function, then the derived quantities (equilibrium, internal step, phasor
//! tables) are computed once.

use super::{Model, Rotations};
use crate::bearing::{BearingGeometry, MAX_ELEMENTS};
use crate::contact::ElementContact;
use crate::decimate::AntiAlias;
use crate::effects::sensor::SensorChain;
use crate::effects::transfer_path::TransferPath;
use crate::effects::Effects;
use crate::error::{check_range, ConfigError};
use crate::forces::defect::{DefectConfig, DefectLocation};
use crate::forces::imbalance::Imbalance;
use crate::forces::slip::Slip;
use crate::forces::surface::{Roughness, Waviness};
use crate::integrate::{max_eigen_modulus, Discretization, IntegratorKind};
use crate::kinematics::FaultOrders;
use crate::load_zone::{equilibrium, Equilibrium};
use crate::real::{cos, sin, wrap_angle, Real, TAU};
use crate::speed::SpeedProfile;

/// Largest oversampling ratio (internal rate / output rate): 16 with the `oversample-16`
/// feature (the host's), which lets a stiff contact (a large bearing under a heavy load: a
/// 65 mm pitch, 15 mm balls at 10 kN need a 97 kHz internal rate) run at 12 kHz, and the
/// CWRU rig at the 5.12 kHz of a condition-monitoring system; the anti-alias filter's taps
/// grow with it ([`crate::decimate::MAX_TAPS`]).
#[cfg(feature = "oversample-16")]
pub const MAX_OVERSAMPLE: u32 = 16;
/// Largest oversampling ratio (internal rate / output rate): 8 without the `oversample-16`
/// feature (a microcontroller's build: its delay lines stay 256 samples).
#[cfg(not(feature = "oversample-16"))]
pub const MAX_OVERSAMPLE: u32 = 8;
/// Output-rate range (Hz).
pub const OUTPUT_RATE_RANGE: (Real, Real) = (100.0, 1.0e6);
/// Allowed structure mass (kg): 0.1 g (a miniature bearing's share of a light housing) to
/// 100 t.
pub const MASS_RANGE: (Real, Real) = (1e-4, 1e5);

/// Mass, stiffness and damping of the structure (thesis eq. 1: M, K, C).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Structure {
    /// Vibrating mass `M` (kg).
    pub mass: Real,
    /// Structural (outer race/housing) stiffness `K` (N/m).
    pub stiffness: Real,
    /// Viscous damping `C` (N·s/m).
    pub damping: Real,
}

/// Which channels go through the anti-alias filter.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Channels {
    /// Acceleration only (cheapest).
    Acceleration,
    /// Acceleration, velocity and displacement.
    All,
}

/// Everything that defines a simulation run. Validate with [`Model::new_checked`].
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ModelConfig {
    /// Bearing geometry and material.
    pub bearing: BearingGeometry,
    /// M, K, C.
    pub structure: Structure,
    /// Static radial load `W` (N), into the load zone.
    pub radial_load: Real,
    /// Radial clearance `γ` (m).
    pub clearance: Real,
    /// Shaft speed profile.
    pub speed: SpeedProfile,
    /// Imbalance (eq. 3), if any.
    pub imbalance: Option<Imbalance>,
    /// Outer-race waviness (eq. 4–10), if any.
    pub waviness: Option<Waviness>,
    /// Roughness, if any.
    pub roughness: Option<Roughness>,
    /// Localized defect, if any.
    pub defect: Option<DefectConfig>,
    /// Random slip of the element passes, if any.
    pub slip: Option<Slip>,
    /// Integrator.
    pub integrator: IntegratorKind,
    /// Output sample rate (Hz).
    pub output_rate: Real,
    /// Internal steps per output sample; `None` picks the smallest ratio ≥ 2 that the
    /// step validation accepts.
    pub oversample: Option<u32>,
    /// Channels to filter and emit.
    pub channels: Channels,
    /// Candidate effects for the sim-to-real diagnosis ([`crate::effects`]); all off by
    /// default.
    pub effects: Effects,
}

impl Model {
    /// Validates `cfg` and derives everything the step needs. Every rejection names its
    /// field and the allowed range.
    pub fn new_checked(mut cfg: ModelConfig) -> Result<Self, ConfigError> {
        let fx = check_effects(&mut cfg)?;
        let speed_max_factor = fx.speed_fluctuation.map(|f| f.max_factor()).unwrap_or(1.0);
        let bearing = BearingGeometry::new_checked(cfg.bearing)?;
        check_structure(&cfg)?;
        check_excitations(&cfg, &bearing)?;
        check_rates(&cfg)?;

        let contact = ElementContact::of(&bearing);
        let orders = FaultOrders::of(&bearing);
        let s = &cfg.structure;
        let (eq, gamma) = loaded_equilibrium(&cfg, &bearing, &contact, &fx);
        let kl = s.stiffness + eq.contact_stiffness;
        let wave_order = cfg
            .waviness
            .map(|w| w.order(bearing.outer_race_radius()))
            .unwrap_or(0);
        let max_cage_hz = (cfg.speed.max_hz() * speed_max_factor * orders.ftf) as f64;
        let peak = PeakLoad::of(&cfg, &fx, &bearing, &contact, gamma, speed_max_factor);
        let ratio = oversampling(&cfg, &eq, kl, &peak, wave_order as f64 * max_cage_hz)?;
        let m = s.mass as f64;
        let fs = cfg.output_rate as f64;
        let h = 1.0 / (fs * ratio as f64);
        let disc = Discretization::new(kl as f64 / m, s.damping as f64 / m, h);

        let (elem_cs, elem_angle, wave_elem_cs) = element_tables(bearing.elements, wave_order);
        let rot = rotations(&cfg, &fx, h as Real, orders.ftf, wave_order);
        // Race defects: the defect's angle. Ball defects: the defective element's angle
        // in the cage, so that the element loop's window (rotated by the cage) selects it.
        let defect_offset_cs = match cfg.defect.map(|d| d.location) {
            Some(DefectLocation::OuterRace { angle })
            | Some(DefectLocation::InnerRace { angle }) => (cos(angle), sin(angle)),
            Some(DefectLocation::Ball { element, .. }) => {
                elem_cs.get(element as usize).copied().unwrap_or((1.0, 0.0))
            }
            None => (1.0, 0.0),
        };
        let ball = cfg.defect.is_some_and(|d| d.location.is_ball());
        let rb = 0.5 * bearing.element_diameter;
        let summit_force = summit_force(&cfg, &fx, &bearing, &contact, &eq, orders.ftf, h);
        Ok(Model {
            contact,
            orders,
            eq,
            gamma,
            // Without preload the upper half cannot touch (skipped, as in the thesis's
            // model); with it every element is evaluated.
            sin_skip: if gamma < 0.0 { -2.0 } else { 0.0 },
            h: h as Real,
            ratio,
            disc,
            kl_m: kl / s.mass,
            c_m: s.damping / s.mass,
            inv_m: 1.0 / s.mass,
            elem_cs,
            elem_angle,
            wave_elem_cs,
            wave_order,
            aa: AntiAlias::design(ratio),
            rot,
            defect_offset_cs,
            spin_order: if ball { orders.bsf } else { 0.0 },
            slip_spin: if ball {
                bearing.outer_race_radius() / rb
            } else {
                0.0
            },
            outer_radius: bearing.outer_race_radius(),
            rough_scale: fx.roughness.map(|r| r.scale).unwrap_or(1.0),
            transfer: fx
                .transfer_path
                .map(|t| TransferPath::design(&t, h as Real)),
            sensor_chain: fx.sensor.map(|t| SensorChain::design(&t, cfg.output_rate)),
            per_step_effects: fx.transfer_path.is_some() || fx.running_in.is_some(),
            extra_force: fx.shaft_harmonics.is_some() || summit_force > 0.0,
            summits: summit_force > 0.0,
            summit_force,
            cfg: ModelConfig { bearing, ..cfg },
        })
    }
}

/// Validates the effects, lets the slip effect replace the model's slip, and checks what
/// the effects need of the rest (roughness present, frequencies below the output rate's
/// limits).
fn check_effects(cfg: &mut ModelConfig) -> Result<Effects, ConfigError> {
    let fx = Effects::new_checked(cfg.effects)?;
    if let Some(s) = fx.slip {
        cfg.slip = Some(Slip {
            fraction: s.fraction,
        });
    }
    if cfg.roughness.is_none() {
        if fx.roughness.is_some() {
            return Err(ConfigError::Inconsistent {
                field: "effect.roughness",
                reason: "the roughness effect scales the model's roughness, which is off",
            });
        }
        if fx.running_in.is_some() {
            return Err(ConfigError::Inconsistent {
                field: "effect.running-in",
                reason: "running-in raises the model's roughness, which is off",
            });
        }
    }
    if let Some(t) = fx.transfer_path {
        t.check_rate(cfg.output_rate)?;
    }
    if let Some(t) = fx.sensor {
        t.check_rate(cfg.output_rate)?;
    }
    Ok(fx)
}

/// M, K, C, the radial load and the clearance.
fn check_structure(cfg: &ModelConfig) -> Result<(), ConfigError> {
    check_range(
        "structure.mass",
        cfg.structure.mass,
        MASS_RANGE.0,
        MASS_RANGE.1,
    )?;
    check_range("structure.stiffness", cfg.structure.stiffness, 1.0, 1e12)?;
    check_range("structure.damping", cfg.structure.damping, 0.0, 1e9)?;
    check_range("radial_load", cfg.radial_load, 0.0, 1e7)?;
    check_range("clearance", cfg.clearance, 0.0, 1e-3)
}

/// The speed profile and every excitation that is on (the defect must fit the bearing).
fn check_excitations(cfg: &ModelConfig, bearing: &BearingGeometry) -> Result<(), ConfigError> {
    SpeedProfile::new_checked(cfg.speed.clone())?;
    if let Some(i) = cfg.imbalance {
        Imbalance::new_checked(i)?;
    }
    if let Some(w) = cfg.waviness {
        Waviness::new_checked(w)?;
    }
    if let Some(r) = cfg.roughness {
        Roughness::new_checked(r)?;
    }
    if let Some(d) = cfg.defect {
        DefectConfig::new_checked(d)?;
        d.location.check_fit(bearing, &d.topography)?;
    }
    if let Some(s) = cfg.slip {
        Slip::new_checked(s)?;
    }
    Ok(())
}

/// Output rate and a given oversampling ratio.
fn check_rates(cfg: &ModelConfig) -> Result<(), ConfigError> {
    check_range(
        "fs",
        cfg.output_rate,
        OUTPUT_RATE_RANGE.0,
        OUTPUT_RATE_RANGE.1,
    )?;
    if let Some(r) = cfg.oversample {
        check_range("oversample", r as Real, 2.0, MAX_OVERSAMPLE as Real)?;
    }
    Ok(())
}

/// Static equilibrium under the radial load and the contact offset `γ` (m): the
/// clearance less the load-zone effect's preload, a uniform contact deflection in units
/// of the unpreloaded static displacement, i.e. a negative clearance
/// (effects/load_zone.rs).
fn loaded_equilibrium(
    cfg: &ModelConfig,
    bearing: &BearingGeometry,
    contact: &ElementContact,
    fx: &Effects,
) -> (Equilibrium, Real) {
    let k = cfg.structure.stiffness;
    let eq0 = equilibrium(contact, bearing.elements, cfg.radial_load, k, cfg.clearance);
    let preload = fx.load_zone.map_or(0.0, |p| p.preload) * eq0.y0;
    let gamma = cfg.clearance - preload;
    let eq = if preload > 0.0 {
        equilibrium(contact, bearing.elements, cfg.radial_load, k, gamma)
    } else {
        eq0
    };
    (eq, gamma)
}

/// The largest radial force the configuration can put on the bearing and the contact
/// stiffness it brings: the step must stay stable there, not only at the static load.
struct PeakLoad {
    /// Linearised contact stiffness at the peak force (N/m), as [`Equilibrium`] defines it.
    contact_stiffness: Real,
    /// Configuration field of the largest dynamic contribution, named if the step fails.
    field: &'static str,
}

impl PeakLoad {
    /// Bounds the radial force by `|W| + m_u r √(ω⁴ + α²) + |F₂| + |F₃|` with the highest
    /// shaft speed `ω` and angular acceleration `α` the speed profile and the
    /// speed-fluctuation effect can reach (imbalance: thesis eq. 3 with its tangential
    /// term), and solves the load distribution (Harris & Kotzalas ch. 7) under it.
    fn of(
        cfg: &ModelConfig,
        fx: &Effects,
        bearing: &BearingGeometry,
        contact: &ElementContact,
        gamma: Real,
        speed_max_factor: Real,
    ) -> Self {
        let base_hz = cfg.speed.max_hz();
        let omega = TAU * base_hz * speed_max_factor;
        let fluct_rate = fx.speed_fluctuation.map_or(0.0, |p| p.max_rate());
        let alpha =
            TAU * (cfg.speed.max_slope_hz_per_s() * speed_max_factor + base_hz * fluct_rate);
        let (mut field, mut largest) = ("fs", 0.0);
        let mut force = cfg.radial_load.abs();
        if let Some(i) = cfg.imbalance {
            let mr = (i.mass * i.radius).abs();
            let (centrifugal, tangential) = (mr * omega * omega, mr * alpha);
            force +=
                libm::sqrt((centrifugal * centrifugal + tangential * tangential) as f64) as Real;
            (field, largest) = if tangential > centrifugal && fx.speed_fluctuation.is_some() {
                ("speed-fluctuation.freq_hz", tangential)
            } else {
                ("imbalance.mass", centrifugal.max(tangential))
            };
        }
        if let Some(h) = fx.shaft_harmonics {
            let f = h.f2.abs() + h.f3.abs();
            force += f;
            if f > largest {
                field = "shaft-harmonics.f2";
            }
        }
        let k = cfg.structure.stiffness;
        let eq = equilibrium(contact, bearing.elements, force, k, gamma);
        PeakLoad {
            contact_stiffness: eq.contact_stiffness,
            field,
        }
    }
}

/// Step validation: the internal steps per output sample, the given ratio or the
/// smallest that resolves the stiffest frequency of the model (`ω_max·h` within the
/// integrator's limit) and keeps the waviness frequency `wave_hz` below 0.45 of the
/// internal rate. The stiffest contact tangent is the larger of twice the static one
/// (the margin every configuration gets) and the tangent at the peak force `peak`.
fn oversampling(
    cfg: &ModelConfig,
    eq: &Equilibrium,
    kl: Real,
    peak: &PeakLoad,
    wave_hz: f64,
) -> Result<u32, ConfigError> {
    let s = &cfg.structure;
    let m = s.mass as f64;
    let static_margin = 2.0 * eq.contact_stiffness as f64;
    let peak_sets_step = peak.contact_stiffness as f64 > static_margin;
    let (contact_k, full_k) = if peak_sets_step {
        let k_peak = peak.contact_stiffness as f64;
        (k_peak, s.stiffness as f64 + k_peak)
    } else {
        (static_margin, (kl + eq.contact_stiffness) as f64)
    };
    let omega = match cfg.integrator {
        IntegratorKind::Rk4 => max_eigen_modulus(full_k / m, s.damping as f64 / m),
        _ => libm::sqrt(contact_k / m),
    };
    // Named in an error: the peak force when it, not the static load, sets the step.
    let fs_field = if peak_sets_step { peak.field } else { "fs" };
    let limit = cfg.integrator.omega_h_limit() as f64;
    let fs = cfg.output_rate as f64;
    let accepts = |r: u32| -> bool {
        let h = 1.0 / (fs * r as f64);
        omega * h <= limit && wave_hz < 0.45 * fs * r as f64
    };
    match cfg.oversample {
        Some(r) => {
            if !accepts(r) {
                let waviness = wave_hz >= 0.45 * fs * r as f64;
                return Err(ConfigError::StepTooLarge {
                    field: "oversample",
                    omega_h: omega / (fs * r as f64),
                    limit,
                    min_internal_rate_hz: (omega / limit).max(wave_hz / 0.45),
                    max_oversample: None,
                    waviness_hz: waviness.then_some(wave_hz),
                });
            }
            Ok(r)
        }
        None => match (2..=MAX_OVERSAMPLE).find(|r| accepts(*r)) {
            Some(r) => Ok(r),
            None => Err(ConfigError::StepTooLarge {
                field: fs_field,
                omega_h: omega / (fs * MAX_OVERSAMPLE as f64),
                limit,
                min_internal_rate_hz: (omega / limit).max(wave_hz / 0.45),
                max_oversample: Some(MAX_OVERSAMPLE),
                waviness_hz: (wave_hz / 0.45 > omega / limit).then_some(wave_hz),
            }),
        },
    }
}

/// Phasor tables of the `n` elements: `(cos, sin)` of each element's angle in the cage,
/// the angles, and the phasors of `N_w` times the angles (waviness).
#[allow(clippy::type_complexity)]
fn element_tables(
    n: u8,
    wave_order: u32,
) -> (
    [(Real, Real); MAX_ELEMENTS],
    [Real; MAX_ELEMENTS],
    [(Real, Real); MAX_ELEMENTS],
) {
    let mut elem_cs = [(1.0, 0.0); MAX_ELEMENTS];
    let mut elem_angle = [0.0; MAX_ELEMENTS];
    let mut wave_elem_cs = [(1.0, 0.0); MAX_ELEMENTS];
    for (j, ((cs, a), wcs)) in elem_cs
        .iter_mut()
        .zip(elem_angle.iter_mut())
        .zip(wave_elem_cs.iter_mut())
        .enumerate()
        .take(n as usize)
    {
        let ang = TAU * j as Real / n as Real;
        *cs = (cos(ang), sin(ang));
        *a = ang;
        let wa = wrap_angle(ang * wave_order as Real);
        *wcs = (cos(wa), sin(wa));
    }
    (elem_cs, elem_angle, wave_elem_cs)
}

/// Per-step rotations of the shaft, cage and waviness phasors at constant speed (`None`
/// when the speed varies: the step then evaluates the angles).
fn rotations(
    cfg: &ModelConfig,
    fx: &Effects,
    h: Real,
    ftf: Real,
    wave_order: u32,
) -> Option<Rotations> {
    if let (SpeedProfile::Constant(f), None) = (&cfg.speed, fx.speed_fluctuation) {
        let f = *f;
        let ds = TAU * f * h;
        let dc = ds * ftf;
        let dw = wrap_angle(dc * wave_order as Real);
        Some(Rotations {
            shaft: (cos(ds), sin(ds)),
            cage: (cos(dc), sin(dc)),
            wave: (cos(dw), sin(dw)),
            shaft_half: (cos(0.5 * ds), sin(0.5 * ds)),
            cage_half: (cos(0.5 * dc), sin(0.5 * dc)),
            wave_half: (cos(0.5 * dw), sin(0.5 * dw)),
        })
    } else {
        None
    }
}

/// Running-in summits: the Hertz load increase of the most loaded element for a summit
/// `s` µm high, over its transit time `λ_r/v` (effects::running_in); 0 without summits.
fn summit_force(
    cfg: &ModelConfig,
    fx: &Effects,
    bearing: &BearingGeometry,
    contact: &ElementContact,
    eq: &Equilibrium,
    ftf: Real,
    h: f64,
) -> Real {
    match (fx.running_in, cfg.roughness) {
        (Some(p), Some(r)) if p.summits > 0.0 => {
            let q = &eq.reference;
            let s = p.summit_height * 1e-6;
            let v = TAU * cfg.speed.shaft_hz(0.0) * ftf * bearing.outer_race_radius();
            let tau = if v > 0.0 { r.wavelength / v } else { h as Real };
            let dq = contact.load(q.delta_max + s) - contact.load(q.delta_max);
            crate::effects::running_in::summit_force(dq, tau, h as Real)
        }
        _ => 0.0,
    }
}
