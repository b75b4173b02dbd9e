//! The dynamic model: validated configuration ([`Model`]) apart from the evolving state
//! ([`State`]), in the style `model.step(&mut state)`.
//!
//! Equation of motion (thesis eq. 1–2, publication III eq. 2), single radial degree of
//! freedom `y` (shaft/inner ring relative to the housing, positive into the load zone):
//!
//! `M y'' + C y' + K y = W + F_imb + F_s(y) + F_d + F_F`
//!
//! with `F_s = −Σ_i Q_i sin θ_i` the Hertz element forces (waviness, roughness and the
//! five-step defect load function with its stiffness change `K_F` act through them),
//! `F_d` the additive defect force of the Sassi or impulse formulations, `W` the static
//! radial load. Output is decimated through [`crate::decimate::AntiAlias`].

use crate::bearing::{BearingGeometry, MAX_ELEMENTS};
use crate::contact::ElementContact;
use crate::decimate::{AntiAlias, DelayLine};
use crate::effects::sensor::{SensorChain, SensorState};
use crate::effects::transfer_path::{PathState, TransferPath};
use crate::effects::Effects;
use crate::error::{check_range, ConfigError};
use crate::forces::defect::{
    DefectConfig, DefectLocation, DefectModel, DefectShape, StaticReference,
};
use crate::forces::imbalance::Imbalance;
use crate::forces::slip::Slip;
use crate::forces::surface::{Roughness, Waviness};
use crate::forces::{ForceDiagram, Kinematics};
use crate::integrate::{max_eigen_modulus, rk4, Discretization, IntegratorKind};
use crate::kinematics::FaultOrders;
use crate::load_zone::{equilibrium, Equilibrium};
use crate::real::{
    advance_angle, angle_diff, cos, sin, sqrt, wrap_angle, Real, PI, STANDARD_GRAVITY, TAU,
};
use crate::rng::Xoshiro128pp;
use crate::speed::SpeedProfile;
use crate::topography::Topography;

/// Steps between two checks of the slip bookkeeping.
const SLIP_CHECK_EVERY: u64 = 8;

/// Largest oversampling ratio (internal rate / output rate).
pub const MAX_OVERSAMPLE: u32 = 8;
/// Output-rate range (Hz).
pub const OUTPUT_RATE_RANGE: (Real, Real) = (100.0, 1.0e6);

/// Mass, stiffness and damping of the structure (thesis eq. 1: M, K, C).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
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
pub enum Channels {
    /// Acceleration only (cheapest).
    Acceleration,
    /// Acceleration, velocity and displacement.
    All,
}

/// Everything that defines a simulation run. Validate with [`Model::new_checked`].
#[derive(Debug, Clone, PartialEq)]
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

/// One output sample.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Sample {
    /// Acceleration (m/s²).
    pub accel: Real,
    /// Velocity (m/s); 0 unless [`Channels::All`].
    pub vel: Real,
    /// Displacement about the static equilibrium (m); 0 unless [`Channels::All`].
    pub disp: Real,
}

impl Sample {
    /// Acceleration in units of standard gravity (g).
    pub fn accel_g(&self) -> Real {
        self.accel / STANDARD_GRAVITY
    }
}

/// Contact figures of the last step, for wear accumulation (thesis §4.2).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct StepStats {
    /// Largest element load in the step (N).
    pub max_load: Real,
    /// Largest load of an element over the defect (N), 0 when none is.
    pub defect_load: Real,
}

/// Per-step rotation of the three phasors for a constant speed.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct Rotations {
    shaft: (Real, Real),
    cage: (Real, Real),
    wave: (Real, Real),
    shaft_half: (Real, Real),
    cage_half: (Real, Real),
    wave_half: (Real, Real),
}

/// A validated model: immutable, shareable, everything derived once.
///
/// Layout: `repr(C)` in declaration order, the step's scalars first and the configuration
/// (read at construction and by a few checks) last, so that a growing configuration (a
/// new effect parameter) cannot move hot fields to offsets that need an extra address
/// instruction on the M4F: two running-in parameters cost 178 instructions per sample
/// with the compiler's own field order, none with this one (`firmware-stub/bench.sh`).
#[derive(Debug, Clone)]
#[repr(C)]
pub struct Model {
    contact: ElementContact,
    orders: FaultOrders,
    eq: Equilibrium,
    /// Contact offset `γ` of the element deflections (m): the radial clearance less a
    /// load-zone preload (negative when preloaded).
    gamma: Real,
    /// Elements with `sin θ` at or below this are out of contact and skipped: 0 without
    /// preload (the upper half), −2 (none) with it.
    sin_skip: Real,
    h: Real,
    ratio: u32,
    disc: Discretization,
    kl_m: Real,
    c_m: Real,
    inv_m: Real,
    elem_cs: [(Real, Real); MAX_ELEMENTS],
    elem_angle: [Real; MAX_ELEMENTS],
    wave_elem_cs: [(Real, Real); MAX_ELEMENTS],
    wave_order: u32,
    aa: AntiAlias,
    rot: Option<Rotations>,
    defect_offset_cs: (Real, Real),
    /// Spin order of a ball defect (BSF, spin angle per shaft angle); 0 without one, which
    /// also skips the spin bookkeeping of the step.
    spin_order: Real,
    /// Spin angle of a ball defect per radian of its element's slip offset: the rolling
    /// distance on the outer race over the ball radius, `R_o/r_b` (–).
    slip_spin: Real,
    outer_radius: Real,
    rough_scale: Real,
    transfer: Option<TransferPath>,
    sensor_chain: Option<SensorChain>,
    /// Whether an effect needs per-step work (transfer path, running-in): one check per
    /// step keeps the baseline's step unchanged.
    per_step_effects: bool,
    /// Whether an effect adds a force outside the element loop (shaft harmonics, the
    /// summits of running-in): one check per force evaluation.
    extra_force: bool,
    /// Whether running-in draws summits (a flag, not `summit_force > 0`: a float compare
    /// per step costs the M4F 40 instructions per sample).
    summits: bool,
    /// Force (N) of one running-in summit contact over a step; 0 without summits (then
    /// no summit is drawn and `State::summit` stays 0).
    summit_force: Real,
    cfg: ModelConfig,
}

impl Model {
    /// Validates `cfg` and derives everything the step needs. Every rejection names its
    /// field and the allowed range.
    pub fn new_checked(mut cfg: ModelConfig) -> Result<Self, ConfigError> {
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
        let speed_max_factor = fx.speed_fluctuation.map(|f| f.max_factor()).unwrap_or(1.0);
        let bearing = BearingGeometry::new_checked(cfg.bearing)?;
        check_range("structure.mass", cfg.structure.mass, 1e-4, 1e5)?;
        check_range("structure.stiffness", cfg.structure.stiffness, 1.0, 1e12)?;
        check_range("structure.damping", cfg.structure.damping, 0.0, 1e9)?;
        check_range("radial_load", cfg.radial_load, 0.0, 1e7)?;
        check_range("clearance", cfg.clearance, 0.0, 1e-3)?;
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
            d.location.check_fit(&bearing, &d.topography)?;
        }
        if let Some(s) = cfg.slip {
            Slip::new_checked(s)?;
        }
        check_range(
            "fs",
            cfg.output_rate,
            OUTPUT_RATE_RANGE.0,
            OUTPUT_RATE_RANGE.1,
        )?;
        if let Some(r) = cfg.oversample {
            check_range("oversample", r as Real, 2.0, MAX_OVERSAMPLE as Real)?;
        }

        let contact = ElementContact::of(&bearing);
        let orders = FaultOrders::of(&bearing);
        let s = &cfg.structure;
        let eq0 = equilibrium(
            &contact,
            bearing.elements,
            cfg.radial_load,
            s.stiffness,
            cfg.clearance,
        );
        // Load-zone preload: a uniform contact deflection in units of the unpreloaded
        // static displacement, i.e. a negative clearance (effects/load_zone.rs).
        let preload = fx.load_zone.map_or(0.0, |p| p.preload) * eq0.y0;
        let gamma = cfg.clearance - preload;
        let eq = if preload > 0.0 {
            equilibrium(
                &contact,
                bearing.elements,
                cfg.radial_load,
                s.stiffness,
                gamma,
            )
        } else {
            eq0
        };
        let kl = s.stiffness + eq.contact_stiffness;
        let wave_order = cfg
            .waviness
            .map(|w| w.order(bearing.outer_race_radius()))
            .unwrap_or(0);

        // Step validation: the stiffest frequency against the internal step.
        let m = s.mass as f64;
        let full_k = (kl + eq.contact_stiffness) as f64; // tangent of the contacts up to 2·k_c0
        let omega = match cfg.integrator {
            IntegratorKind::Rk4 => max_eigen_modulus(full_k / m, s.damping as f64 / m),
            _ => libm::sqrt(2.0 * eq.contact_stiffness as f64 / m),
        };
        let limit = cfg.integrator.omega_h_limit() as f64;
        let fs = cfg.output_rate as f64;
        let max_cage_hz = (cfg.speed.max_hz() * speed_max_factor * orders.ftf) as f64;
        let wave_hz = wave_order as f64 * max_cage_hz;
        let accepts = |r: u32| -> bool {
            let h = 1.0 / (fs * r as f64);
            omega * h <= limit && wave_hz < 0.45 * fs * r as f64
        };
        let ratio = match cfg.oversample {
            Some(r) => {
                if !accepts(r) {
                    let min_rate = if wave_hz >= 0.45 * fs * r as f64 {
                        wave_hz / 0.45
                    } else {
                        omega / limit
                    };
                    return Err(ConfigError::StepTooLarge {
                        field: "oversample",
                        omega_h: omega / (fs * r as f64),
                        limit,
                        min_internal_rate_hz: min_rate,
                    });
                }
                r
            }
            None => match (2..=MAX_OVERSAMPLE).find(|r| accepts(*r)) {
                Some(r) => r,
                None => {
                    return Err(ConfigError::StepTooLarge {
                        field: "fs",
                        omega_h: omega / (fs * MAX_OVERSAMPLE as f64),
                        limit,
                        min_internal_rate_hz: (omega / limit).max(wave_hz / 0.45),
                    })
                }
            },
        };
        let h = 1.0 / (fs * ratio as f64);
        let disc = Discretization::new(kl as f64 / m, s.damping as f64 / m, h);

        let n = bearing.elements;
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
        let rot = if let (SpeedProfile::Constant(f), None) = (&cfg.speed, fx.speed_fluctuation) {
            let f = *f;
            let ds = TAU * f * h as Real;
            let dc = ds * orders.ftf;
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
        };
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
        // Running-in summits: the Hertz load increase of the most loaded element for a
        // summit `s` µm high, over its transit time `λ_r/v` (effects::running_in).
        let summit_force = match (fx.running_in, cfg.roughness) {
            (Some(p), Some(r)) if p.summits > 0.0 => {
                let q = &eq.reference;
                let s = p.summit_height * 1e-6;
                let v = TAU * cfg.speed.shaft_hz(0.0) * orders.ftf * bearing.outer_race_radius();
                let tau = if v > 0.0 { r.wavelength / v } else { h as Real };
                let dq = contact.load(q.delta_max + s) - contact.load(q.delta_max);
                crate::effects::running_in::summit_force(dq, tau, h as Real)
            }
            _ => 0.0,
        };
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

    /// The validated configuration.
    pub fn config(&self) -> &ModelConfig {
        &self.cfg
    }
    /// Kinematic orders of the bearing (eq. 17–20).
    pub fn orders(&self) -> FaultOrders {
        self.orders
    }
    /// Hertz constants of one element (both races in series).
    pub fn contact(&self) -> &ElementContact {
        &self.contact
    }
    /// Static equilibrium under the radial load.
    pub fn equilibrium(&self) -> &Equilibrium {
        &self.eq
    }
    /// Internal step `h` (s).
    pub fn step_size(&self) -> Real {
        self.h
    }
    /// Internal steps per output sample.
    pub fn oversample(&self) -> u32 {
        self.ratio
    }
    /// Outer-race waviness order `N_w` (0 without waviness).
    pub fn waviness_order(&self) -> u32 {
        self.wave_order
    }
    /// The anti-alias filter.
    pub fn anti_alias(&self) -> &AntiAlias {
        &self.aa
    }
    /// Time (s) that output sample `k` (0-based) stands for: the sample leaves the
    /// filter after internal step `kR + R − 1` and the linear-phase filter delays it by
    /// `(taps − 1)/2` internal steps.
    pub fn output_time(&self, k: u64) -> Real {
        let r = self.ratio as u64;
        let n = (k * r + r - 1) as Real - self.aa.delay() as Real;
        n * self.h
    }
    /// Linearised natural frequency `√((K + k_c0)/M)/2π` (Hz) about static equilibrium.
    pub fn natural_frequency_hz(&self) -> Real {
        sqrt(self.kl_m) / TAU
    }
    /// Damping ratio `ζ = C/(2√((K + k_c0)M))` (–).
    pub fn damping_ratio(&self) -> Real {
        0.5 * self.c_m / sqrt(self.kl_m)
    }

    /// Defect geometry derived for topography `t` (none without a configured defect).
    pub fn defect_shape(&self, t: &Topography) -> DefectShape {
        match self.cfg.defect {
            Some(d) => {
                let mut s = DefectShape::derive(
                    t,
                    &d.location,
                    &self.cfg.bearing,
                    &self.eq.reference,
                    d.defect_sassi_k(),
                );
                if let Some(e) = self.cfg.effects.edge_shape {
                    e.apply(&mut s);
                }
                s
            }
            None => DefectShape::default(),
        }
    }

    /// Static reference of the most loaded element.
    pub fn static_reference(&self) -> &StaticReference {
        &self.eq.reference
    }

    /// Kinematics at the state's current time, advanced by `frac·h` (0, ½ or 1).
    #[inline(always)]
    fn kinematics<const NB: usize>(&self, st: &State<NB>, frac: u8) -> Kinematics {
        let f0 = st.shaft_hz;
        let (shaft_hz, dshaft, rot) = match (frac, self.rot) {
            (0, _) => (f0, 0.0, None),
            (1, Some(r)) => (f0, 0.0, Some((r.shaft_half, r.cage_half, r.wave_half))),
            (_, Some(r)) => (f0, 0.0, Some((r.shaft, r.cage, r.wave))),
            (fr, None) => {
                let dt = if fr == 1 { 0.5 * self.h } else { self.h };
                let f1 = self.speed_hz(st.time + dt);
                (f1, PI * (f0 + f1) * dt, None)
            }
        };
        let omega = TAU * shaft_hz;
        let alpha = match self.rot {
            Some(_) => 0.0,
            None => {
                let f2 = self.speed_hz(st.time + self.h);
                TAU * (f2 - f0) / self.h
            }
        };
        let mut k = Kinematics {
            shaft_angle: st.shaft_angle,
            shaft_cs: st.shaft_cs,
            shaft_omega: omega,
            shaft_alpha: alpha,
            cage_angle: st.cage_angle,
            cage_cs: st.cage_cs,
            cage_omega: omega * self.orders.ftf,
            wave_cs: st.wave_cs,
        };
        if let Some((rs, rc, rw)) = rot {
            let half = if frac == 1 { 0.5 } else { 1.0 };
            let ds = TAU * f0 * self.h * half;
            k.shaft_angle = wrap_angle(k.shaft_angle + ds);
            k.cage_angle = wrap_angle(k.cage_angle + ds * self.orders.ftf);
            k.shaft_cs = rotate(k.shaft_cs, rs);
            k.cage_cs = rotate(k.cage_cs, rc);
            k.wave_cs = rotate(k.wave_cs, rw);
        } else if dshaft != 0.0 {
            let dc = dshaft * self.orders.ftf;
            k.shaft_angle = wrap_angle(k.shaft_angle + dshaft);
            k.cage_angle = wrap_angle(k.cage_angle + dc);
            k.shaft_cs = (cos(k.shaft_angle), sin(k.shaft_angle));
            k.cage_cs = (cos(k.cage_angle), sin(k.cage_angle));
            let wa = wrap_angle(k.cage_angle * self.wave_order as Real);
            k.wave_cs = (cos(wa), sin(wa));
        }
        k
    }

    /// Sum of all force diagrams (N) at kinematics `k`, displacement `y`, velocity `v`.
    #[inline(always)]
    fn total_force<const NB: usize>(
        &self,
        st: &State<NB>,
        k: &Kinematics,
        y: Real,
        v: Real,
        stats: &mut StepStats,
        draw: Option<(&mut Xoshiro128pp, Real)>,
    ) -> Real {
        let mut f = self.cfg.radial_load;
        if let Some(imb) = &self.cfg.imbalance {
            f += imb.force(k, y, v);
        }
        if self.extra_force {
            f += self.extra_force(st, k);
        }
        f + self.element_forces(st, k, y, stats, draw)
    }

    /// Hertz element forces with waviness, roughness and the defect (N). With `draw`, the
    /// roughness heights are drawn here (generator, amplitude) in the order and for the
    /// elements [`Model::draw_random`] would use, saving its second pass; without it they
    /// come from the state (drawn once per step for RK4's four stages).
    #[inline(always)]
    fn element_forces<const NB: usize>(
        &self,
        st: &State<NB>,
        k: &Kinematics,
        y: Real,
        stats: &mut StepStats,
        mut draw: Option<(&mut Xoshiro128pp, Real)>,
    ) -> Real {
        let n = self.cfg.bearing.elements as usize;
        let gamma = self.gamma;
        let sin_skip = self.sin_skip;
        let wave_amp = self.cfg.waviness.map(|w| w.amplitude).unwrap_or(0.0);
        let (cc, sc) = k.cage_cs;
        let (cw, sw) = k.wave_cs;
        let defect = self.cfg.defect;
        let shape = &st.shape;
        // Defect phasor (position of defect 0; of the defective element for a ball
        // defect) and the candidate window.
        let (dc, ds) = match defect.map(|d| d.location) {
            Some(DefectLocation::InnerRace { .. }) => rotate(k.shaft_cs, self.defect_offset_cs),
            Some(DefectLocation::Ball { .. }) => rotate(k.cage_cs, self.defect_offset_cs),
            _ => self.defect_offset_cs,
        };
        // A ball defect's terms are computed out of line before the loop (a call inside it
        // would cost the race defects' path registers).
        let ball = match defect {
            Some(d) if d.location.is_ball() => Some(self.ball_defect(st, k, d)),
            _ => None,
        };
        let mut fy = 0.0;
        // Equal-length slices zipped without `take`, so the loop compiles to plain indexed
        // loads (no per-iteration iterator bookkeeping, no bounds checks).
        let ecs_all = self.elem_cs.get(..n).unwrap_or(&[]);
        let wcs_all = self.wave_elem_cs.get(..n).unwrap_or(&[]);
        let ang_all = self.elem_angle.get(..n).unwrap_or(&[]);
        let rough_all = st.rough.get(..n).unwrap_or(&[]);
        let slip_all = st.slip.get(..n).unwrap_or(&[]);
        let cache_all = st.rsqrt.get(..n).unwrap_or(&[]);
        for (((((ecs, wcs), elem_angle), rough), slip), rsqrt) in ecs_all
            .iter()
            .zip(wcs_all)
            .zip(ang_all)
            .zip(rough_all)
            .zip(slip_all)
            .zip(cache_all)
        {
            let (ce, se) = *ecs;
            let sin_t = sc * ce + cc * se;
            let rough = match draw.as_mut() {
                Some((rng, sigma)) if sin_t > sin_skip - 0.05 => *sigma * rng.uniform_pm1(),
                Some(_) => 0.0,
                None => *rough,
            };
            if sin_t <= sin_skip {
                continue;
            }
            let mut delta = y * sin_t - gamma - rough;
            if wave_amp != 0.0 {
                let (cwe, swe) = *wcs;
                delta -= wave_amp * (sw * cwe + cw * swe);
            }
            let mut unload = 0.0;
            let mut add = 0.0;
            if let Some(d) = defect {
                let cos_t = cc * ce - sc * se;
                let cos_rel = cos_t * dc + sin_t * ds;
                if cos_rel > st.window_cos {
                    let theta = k.cage_angle + *elem_angle + *slip;
                    let mut dd = 0.0;
                    if let Some(terms) = ball {
                        // Only the defective element is in the window (half an element pitch
                        // wide).
                        (unload, dd, add) = terms;
                    } else {
                        let base = match d.location {
                            DefectLocation::InnerRace { angle } => k.shaft_angle + angle,
                            DefectLocation::OuterRace { angle } => angle,
                            DefectLocation::Ball { .. } => 0.0,
                        };
                        let inner = matches!(d.location, DefectLocation::InnerRace { .. });
                        for kd in 0..shape.count {
                            let centre = base + kd as Real * shape.spacing_angle;
                            let mut psi = angle_diff(theta, centre);
                            if inner {
                                psi = -psi;
                            }
                            let xi = psi / shape.length_angle + 0.5;
                            if xi < 0.0 || xi >= 1.0 + st.tail {
                                continue;
                            }
                            match d.model {
                                DefectModel::FiveStep => {
                                    let ls = shape.load.eval(xi);
                                    unload += ls.unload;
                                    dd += ls.extra_deflection;
                                }
                                DefectModel::Deflection => dd -= shape.geometric_drop(xi),
                                DefectModel::Sassi => {
                                    add += shape.sassi(xi, angle_diff(theta, PI / 2.0))
                                }
                                DefectModel::Impulse => {
                                    let w_rel = if inner {
                                        k.shaft_omega - k.cage_omega
                                    } else {
                                        k.cage_omega
                                    };
                                    add += shape.impulse(xi, w_rel * shape.race_radius);
                                }
                            }
                        }
                    }
                    // Load-zone effect: the element's angle from the load-zone centre (π/2)
                    // has cos ψ = sin θ; the defect's whole force term is scaled (for a ball
                    // defect the element orbits with the cage: modulation at FTF).
                    if let Some(p) = &self.cfg.effects.load_zone {
                        let g = p.gain(sin_t);
                        unload *= g;
                        add *= g;
                        dd *= g;
                    }
                    delta += dd;
                }
            }
            let mut q = self.hertz(delta, rsqrt);
            if unload > 0.0 {
                q *= if unload < 1.0 { 1.0 - unload } else { 0.0 };
            }
            if q > stats.max_load {
                stats.max_load = q;
            }
            if (unload > 0.0 || add != 0.0) && q + add > stats.defect_load {
                stats.defect_load = q + add;
            }
            fy -= (q + add) * sin_t;
        }
        fy
    }

    /// Terms `(unload, extra deflection (m), additive force (N))` of ball defect `d` on the
    /// defective element for kinematics `k` (see [`crate::forces::defect`]); the element
    /// loop applies them to that element. The spin angle of
    /// this evaluation is the state's, advanced by BSF × the shaft's advance within the
    /// step; the element's slip offset shifts it by the rolling distance on the outer race,
    /// `slip·R_o/r_b`. The defect point is under the outer race at spin phase 0 and under
    /// the inner race at π; each of the `count` defects is evaluated against both contacts.
    /// Rolling speed over either contact: `BSF·ω_shaft·r_b`.
    #[inline(never)]
    fn ball_defect<const NB: usize>(
        &self,
        st: &State<NB>,
        k: &Kinematics,
        d: DefectConfig,
    ) -> (Real, Real, Real) {
        let shape = &st.shape;
        let e = match d.location {
            DefectLocation::Ball { element, .. } => element as usize,
            _ => 0,
        };
        let slip = st.slip.get(e).copied().unwrap_or(0.0);
        let theta = k.cage_angle + self.elem_angle.get(e).copied().unwrap_or(0.0) + slip;
        let spin = st.spin_angle
            + self.spin_order * angle_diff(k.shaft_angle, st.shaft_angle)
            + self.slip_spin * slip;
        let (mut unload, mut dd, mut add) = (0.0, 0.0, 0.0);
        for contact in [0.0, PI] {
            for kd in 0..shape.count {
                let centre = contact + kd as Real * shape.spacing_angle;
                let xi = angle_diff(spin, centre) / shape.length_angle + 0.5;
                if xi < 0.0 || xi >= 1.0 + st.tail {
                    continue;
                }
                match d.model {
                    DefectModel::FiveStep => {
                        let ls = shape.load.eval(xi);
                        unload += ls.unload;
                        dd += ls.extra_deflection;
                    }
                    DefectModel::Deflection => dd -= shape.geometric_drop(xi),
                    DefectModel::Sassi => add += shape.sassi(xi, angle_diff(theta, PI / 2.0)),
                    DefectModel::Impulse => {
                        let v = self.spin_order * k.shaft_omega * shape.race_radius;
                        add += shape.impulse(xi, v);
                    }
                }
            }
        }
        (unload, dd, add)
    }

    /// Hertz element load `K δ^p` (N). In `f32` builds point contacts use `δ²·(1/√δ)` with
    /// the inverse square root refined by two Newton steps from the element's value of
    /// the previous evaluation (cached in `rsqrt`; libm's `sqrtf` only when the cache is
    /// cold or off by more than 10 %): libm's software `sqrtf` dominated the Cortex-M4F's
    /// step, and the two Newton steps from a < 5·10⁻³ start are exact to f32 rounding.
    /// Deterministic, so a host `f32` run and the target stay bit-identical.
    #[inline(always)]
    fn hertz(&self, delta: Real, rsqrt: &core::cell::Cell<Real>) -> Real {
        #[cfg(feature = "f32")]
        {
            if delta <= 0.0 {
                return 0.0;
            }
            if self.contact.kind == crate::bearing::ContactKind::Point {
                let r0 = rsqrt.get();
                let e = delta * r0 * r0;
                let r = if r0 > 0.0 && e > 0.9 && e < 1.1 {
                    let r1 = r0 * (1.5 - 0.5 * e);
                    r1 * (1.5 - 0.5 * delta * r1 * r1)
                } else {
                    1.0 / sqrt(delta)
                };
                rsqrt.set(r);
                return self.contact.stiffness * delta * delta * r;
            }
            self.contact.load(delta)
        }
        #[cfg(not(feature = "f32"))]
        {
            let _ = rsqrt;
            self.contact.load(delta)
        }
    }

    /// Advances the state by one internal step; returns a sample every
    /// [`Model::oversample`] steps.
    #[inline]
    pub fn step<const NB: usize>(&self, st: &mut State<NB>) -> Option<Sample> {
        if self.cfg.integrator == IntegratorKind::Rk4 {
            self.draw_random(st);
        }
        if self.summits {
            self.draw_summit(st);
        }
        let mut stats = StepStats::default();
        let (y, v) = (st.y, st.v);
        let kl_m = self.kl_m;
        let c_m = self.c_m;
        let k_c0 = self.eq.contact_stiffness;
        let inv_m = self.inv_m;
        let (y1, v1, a0) = match self.cfg.integrator {
            IntegratorKind::Rk4 => {
                let k0 = self.kinematics(st, 0);
                let kh = self.kinematics(st, 1);
                let k1 = self.kinematics(st, 2);
                let mut first = true;
                let stref: &State<NB> = st;
                rk4::step(y, v, self.h, |stage, yy, vv| {
                    let kin = match stage {
                        rk4::Stage::Start => &k0,
                        rk4::Stage::Mid => &kh,
                        rk4::Stage::End => &k1,
                    };
                    let mut s = StepStats::default();
                    let f = self.total_force(stref, kin, yy, vv, &mut s, None);
                    if first {
                        stats = s;
                        first = false;
                    }
                    (f - self.cfg.structure.stiffness * yy - self.cfg.structure.damping * vv)
                        * inv_m
                })
            }
            kind => {
                let k0 = self.kinematics(st, 0);
                let mut rng = st.rng.clone();
                let draw = self.cfg.roughness.map(|_| {
                    let sigma = if self.rot.is_some() {
                        st.rough_sigma
                    } else {
                        self.rough_sigma(st.shaft_hz, st.topography) * st.run_in
                    };
                    (&mut rng, sigma)
                });
                let g = (self.total_force(st, &k0, y, v, &mut stats, draw) + k_c0 * y) * inv_m;
                st.rng = rng;
                let slope = if st.has_prev && kind == IntegratorKind::ExactFoh {
                    g - st.g_prev
                } else {
                    0.0
                };
                st.g_prev = g;
                st.has_prev = true;
                let (y1, v1) = self.disc.step(y, v, g, slope);
                (y1, v1, -kl_m * y - c_m * v + g)
            }
        };
        st.stats = stats;
        self.update_slip(st);
        self.advance_kinematics(st);
        st.y = y1;
        st.v = v1;
        st.steps += 1;

        let a0 = if self.per_step_effects {
            self.effects_step(st, a0)
        } else {
            a0
        };
        st.lines[0].push(a0);
        if self.cfg.channels == Channels::All {
            if let Some(l) = st.lines.get_mut(1) {
                l.push(v);
            }
            if let Some(l) = st.lines.get_mut(2) {
                l.push(y - self.eq.y0);
            }
        }
        st.phase += 1;
        if st.phase < self.ratio {
            return None;
        }
        st.phase = 0;
        let mut accel = self.aa.output(&st.lines[0]);
        if let Some(chain) = &self.sensor_chain {
            accel = chain.apply(&mut st.sensor, accel);
        }
        let (vel, disp) = if self.cfg.channels == Channels::All {
            (self.aa.output(&st.lines[1]), self.aa.output(&st.lines[2]))
        } else {
            (0.0, 0.0)
        };
        Some(Sample { accel, vel, disp })
    }

    /// Fills `out` with output samples; returns how many were written (all of them).
    pub fn fill<const NB: usize>(&self, st: &mut State<NB>, out: &mut [Sample]) -> usize {
        let mut written = 0;
        for slot in out.iter_mut() {
            loop {
                if let Some(s) = self.step(st) {
                    *slot = s;
                    break;
                }
            }
            written += 1;
        }
        written
    }

    /// Draws the per-step random quantities (roughness heights) once per step, so every
    /// integrator stage sees the same surface.
    #[inline(always)]
    fn draw_random<const NB: usize>(&self, st: &mut State<NB>) {
        if self.cfg.roughness.is_none() {
            return;
        }
        let sigma = if self.rot.is_some() {
            st.rough_sigma
        } else {
            self.rough_sigma(st.shaft_hz, st.topography) * st.run_in
        };
        let (cc, sc) = st.cage_cs;
        let n = self.cfg.bearing.elements as usize;
        let rough_all = st.rough.get_mut(..n).unwrap_or(&mut []);
        for (rough, (ce, se)) in rough_all
            .iter_mut()
            .zip(self.elem_cs.get(..n).unwrap_or(&[]))
        {
            let sin_t = sc * ce + cc * se;
            *rough = if sin_t > self.sin_skip - 0.05 {
                sigma * st.rng.uniform_pm1()
            } else {
                0.0
            };
        }
    }

    /// Amplitude of the per-step roughness draw (m) at shaft speed `shaft_hz` with the
    /// debris of `topography` (see [`Roughness::step_sigma`]); constant-speed models cache it
    /// in the state, because its square root costs more than the draw on an M4F.
    fn rough_sigma(&self, shaft_hz: Real, topography: Option<Topography>) -> Real {
        let Some(r) = self.cfg.roughness else {
            return 0.0;
        };
        let v = TAU * shaft_hz * self.orders.ftf * self.outer_radius;
        let debris = topography.map(|t| t.debris).unwrap_or(0.0);
        r.step_sigma(self.h, v, debris) * crate::real::SQRT_3 * self.rough_scale
    }

    /// Shaft frequency (Hz) at time `t` (s): the speed profile, modulated by the
    /// speed-fluctuation effect when it is on.
    #[inline(always)]
    fn speed_hz(&self, t: Real) -> Real {
        let f = self.cfg.speed.shaft_hz(t);
        match &self.cfg.effects.speed_fluctuation {
            Some(p) => f * p.factor(t),
            None => f,
        }
    }

    /// Forces of the effects outside the element loop (N): shaft harmonics and the
    /// running-in summit contact of this step; out of line so that the baseline's force
    /// sum only pays for the check.
    #[inline(never)]
    fn extra_force<const NB: usize>(&self, st: &State<NB>, k: &Kinematics) -> Real {
        let harmonics = self
            .cfg
            .effects
            .shaft_harmonics
            .map(|p| p.force(k))
            .unwrap_or(0.0);
        harmonics + st.summit
    }

    /// Decides whether a running-in summit passes through a contact during this step
    /// (Poisson, `S exp(−n/n_d)` per revolution) and sets the step's summit force: the
    /// load increase of the most loaded element, scaled by a uniform draw in [½, 1] for
    /// where in the load zone it happens, pushing the shaft like an element load (the
    /// element forces are `−Σ Q_i sin θ_i`). Decided at the start of the step that uses it
    /// from the state's generator, so a checkpoint between steps loses nothing.
    #[inline(never)]
    fn draw_summit<const NB: usize>(&self, st: &mut State<NB>) {
        st.summit = 0.0;
        let Some(p) = self.cfg.effects.running_in else {
            return;
        };
        let rate = p.summit_rate(st.revs) * st.shaft_hz * self.h;
        let u = 0.5 * (st.rng.uniform_pm1() + 1.0);
        if u < rate {
            let w = 0.75 + 0.25 * st.rng.uniform_pm1();
            st.summit = -self.summit_force * w;
        }
    }

    /// Per-step work of the effects that need it, kept out of line so that the baseline
    /// step stays as it was: the transfer path filters the internal-rate acceleration
    /// `a0`; running-in counts revolutions and refreshes the roughness factor every 256
    /// internal steps (an exponential per step would cost more than the draw).
    #[inline(never)]
    fn effects_step<const NB: usize>(&self, st: &mut State<NB>, a0: Real) -> Real {
        let a = match &self.transfer {
            Some(t) => t.filter(&mut st.path, a0),
            None => a0,
        };
        if let Some(p) = self.cfg.effects.running_in {
            st.revs += st.shaft_hz * self.h;
            if st.steps.is_multiple_of(256) {
                st.run_in = p.scale(st.revs);
                st.rough_sigma = self.rough_sigma(st.shaft_hz, st.topography) * st.run_in;
            }
        }
        a
    }

    /// Redraws an element's slip offset once per pass, while it is opposite the defect.
    #[inline(always)]
    fn update_slip<const NB: usize>(&self, st: &mut State<NB>) {
        let (Some(slip), Some(d)) = (self.cfg.slip, self.cfg.defect) else {
            return;
        };
        // A pass is detected by the element entering the far half-plane; checking every
        // 8th step is ample (8 steps move the cage less than the 120° arming region even at
        // the highest speed and coarsest step) and saves most of the bookkeeping.
        if !st.steps.is_multiple_of(SLIP_CHECK_EVERY) {
            return;
        }
        // A ball defect travels with its element: its offset is redrawn once per cage turn,
        // when the element is opposite the load-zone centre (unloaded), so that the jump in
        // its spin phase never falls on an impact.
        let (dc, ds) = match d.location {
            DefectLocation::InnerRace { .. } => rotate(st.shaft_cs, self.defect_offset_cs),
            DefectLocation::Ball { .. } => (0.0, 1.0),
            DefectLocation::OuterRace { .. } => self.defect_offset_cs,
        };
        let (cc, sc) = st.cage_cs;
        let n = self.cfg.bearing.elements;
        // Iterators instead of indexing keep this per-step loop free of bounds checks (it is
        // a sixth of the step on a Cortex-M4F); the arithmetic is unchanged.
        let mut armed = st.armed;
        let mut bit = 1u32;
        let elems = self.elem_cs.get(..n as usize).unwrap_or(&[]);
        for ((ce, se), s) in elems.iter().zip(st.slip.iter_mut()) {
            let cos_rel = (cc * ce - sc * se) * dc + (sc * ce + cc * se) * ds;
            if cos_rel > 0.5 {
                armed |= bit;
            } else if cos_rel < -0.5 && armed & bit != 0 {
                armed &= !bit;
                *s = slip.draw(&mut st.rng, n);
            }
            bit = bit.rotate_left(1);
        }
        st.armed = armed;
    }

    /// Moves time, angles and phasors one step on.
    #[inline(always)]
    fn advance_kinematics<const NB: usize>(&self, st: &mut State<NB>) {
        let f0 = st.shaft_hz;
        st.time += self.h;
        let (f1, ds) = match self.rot {
            Some(_) => (f0, TAU * f0 * self.h),
            None => {
                let f1 = self.speed_hz(st.time);
                (f1, PI * (f0 + f1) * self.h)
            }
        };
        st.shaft_hz = f1;
        let dc = ds * self.orders.ftf;
        st.shaft_angle = advance_angle(st.shaft_angle, ds);
        st.cage_angle = advance_angle(st.cage_angle, dc);
        st.wave_angle = advance_angle(st.wave_angle, wrap_angle(dc * self.wave_order as Real));
        if self.spin_order != 0.0 {
            st.spin_angle = advance_angle(st.spin_angle, ds * self.spin_order);
        }
        match self.rot {
            Some(r) if !st.steps.is_multiple_of(1024) => {
                st.shaft_cs = renorm(rotate(st.shaft_cs, r.shaft));
                st.cage_cs = renorm(rotate(st.cage_cs, r.cage));
                st.wave_cs = renorm(rotate(st.wave_cs, r.wave));
            }
            _ => {
                st.shaft_cs = (cos(st.shaft_angle), sin(st.shaft_angle));
                st.cage_cs = (cos(st.cage_angle), sin(st.cage_angle));
                st.wave_cs = (cos(st.wave_angle), sin(st.wave_angle));
            }
        }
    }
}

impl DefectConfig {
    fn defect_sassi_k(&self) -> Real {
        self.sassi_k_impact
    }
}

#[inline(always)]
fn rotate(a: (Real, Real), b: (Real, Real)) -> (Real, Real) {
    (a.0 * b.0 - a.1 * b.1, a.1 * b.0 + a.0 * b.1)
}

#[inline(always)]
fn renorm(a: (Real, Real)) -> (Real, Real) {
    let k = 1.5 - 0.5 * (a.0 * a.0 + a.1 * a.1);
    (a.0 * k, a.1 * k)
}

/// The evolving state of one run: motion, angles, random generator, per-element slip and
/// roughness, the current defect topography and the anti-alias history. `NB` is the
/// element capacity (≥ the bearing's element count). Its size is fixed at compile time:
/// with `f64` and `NB = 16` it is about 12.8 KB (three filter delay lines of
/// 2 × 256 samples dominate; 6.4 KB with `f32`); see `size_of::<State<16>>()` in the tests.
#[derive(Debug, Clone)]
pub struct State<const NB: usize> {
    y: Real,
    v: Real,
    g_prev: Real,
    has_prev: bool,
    steps: u64,
    time: Real,
    shaft_hz: Real,
    shaft_angle: Real,
    cage_angle: Real,
    wave_angle: Real,
    spin_angle: Real,
    shaft_cs: (Real, Real),
    cage_cs: (Real, Real),
    wave_cs: (Real, Real),
    rng: Xoshiro128pp,
    rough: [Real; NB],
    slip: [Real; NB],
    rsqrt: [core::cell::Cell<Real>; NB],
    rough_sigma: Real,
    armed: u32,
    topography: Option<Topography>,
    shape: DefectShape,
    window_cos: Real,
    tail: Real,
    lines: [DelayLine; 3],
    phase: u32,
    stats: StepStats,
    path: PathState,
    sensor: SensorState,
    revs: Real,
    run_in: Real,
    /// Running-in summit force of the current step (N); set at the step's start.
    summit: Real,
}

/// The plain fields of a [`State`], for checkpoints (`crate::checkpoint`).
#[derive(Debug, Clone)]
pub(crate) struct StateParts<const NB: usize> {
    pub y: Real,
    pub v: Real,
    pub g_prev: Real,
    pub has_prev: bool,
    pub steps: u64,
    pub time: Real,
    pub shaft_hz: Real,
    pub shaft_angle: Real,
    pub cage_angle: Real,
    pub wave_angle: Real,
    pub spin_angle: Real,
    pub shaft_cs: (Real, Real),
    pub cage_cs: (Real, Real),
    pub wave_cs: (Real, Real),
    pub rng: Xoshiro128pp,
    pub rough: [Real; NB],
    pub slip: [Real; NB],
    pub armed: u32,
    pub topography: Option<Topography>,
    pub lines: [DelayLine; 3],
    pub phase: u32,
    pub path: PathState,
    pub sensor: SensorState,
    pub revs: Real,
    pub run_in: Real,
    /// The cached roughness amplitude: refreshed only at block starts and every 256
    /// running-in steps, so it is running state, not derivable from the model.
    pub rough_sigma: Real,
    /// The `f32` builds' inverse-square-root cache of the Hertz loads.
    pub rsqrt: [Real; NB],
}

impl<const NB: usize> State<NB> {
    pub(crate) fn parts(&self) -> StateParts<NB> {
        StateParts {
            y: self.y,
            v: self.v,
            g_prev: self.g_prev,
            has_prev: self.has_prev,
            steps: self.steps,
            time: self.time,
            shaft_hz: self.shaft_hz,
            shaft_angle: self.shaft_angle,
            cage_angle: self.cage_angle,
            wave_angle: self.wave_angle,
            spin_angle: self.spin_angle,
            shaft_cs: self.shaft_cs,
            cage_cs: self.cage_cs,
            wave_cs: self.wave_cs,
            rng: self.rng.clone(),
            rough: self.rough,
            slip: self.slip,
            armed: self.armed,
            topography: self.topography,
            lines: self.lines,
            phase: self.phase,
            path: self.path,
            sensor: self.sensor.clone(),
            revs: self.revs,
            run_in: self.run_in,
            rough_sigma: self.rough_sigma,
            rsqrt: core::array::from_fn(|i| self.rsqrt.get(i).map(|c| c.get()).unwrap_or(0.0)),
        }
    }

    pub(crate) fn restore(&mut self, p: StateParts<NB>) {
        self.y = p.y;
        self.v = p.v;
        self.g_prev = p.g_prev;
        self.has_prev = p.has_prev;
        self.steps = p.steps;
        self.time = p.time;
        self.shaft_hz = p.shaft_hz;
        self.shaft_angle = p.shaft_angle;
        self.cage_angle = p.cage_angle;
        self.wave_angle = p.wave_angle;
        self.spin_angle = p.spin_angle;
        self.shaft_cs = p.shaft_cs;
        self.cage_cs = p.cage_cs;
        self.wave_cs = p.wave_cs;
        self.rng = p.rng;
        self.rough = p.rough;
        self.slip = p.slip;
        self.armed = p.armed;
        self.topography = p.topography;
        self.lines = p.lines;
        self.phase = p.phase;
        self.path = p.path;
        self.sensor = p.sensor;
        self.revs = p.revs;
        self.run_in = p.run_in;
        self.rough_sigma = p.rough_sigma;
        for (c, v) in self.rsqrt.iter().zip(p.rsqrt) {
            c.set(v);
        }
    }

    /// After a restore: the cached roughness amplitude with the restored running-in factor.
    pub(crate) fn refresh_rough(&mut self, model: &Model) {
        self.rough_sigma = model.rough_sigma(self.shaft_hz, self.topography) * self.run_in;
    }

    /// Initial state at static equilibrium, at rest relative to it, with `seed` for the
    /// random generator. Fails if `NB` is smaller than the bearing's element count.
    pub fn new(model: &Model, seed: u64) -> Result<Self, ConfigError> {
        let n = model.cfg.bearing.elements as usize;
        if n > NB || NB > 32 {
            return Err(ConfigError::TooMany {
                field: "bearing.elements",
                count: n,
                max: if NB > 32 { 32 } else { NB },
            });
        }
        let f0 = model.speed_hz(0.0);
        let mut st = State {
            y: model.eq.y0,
            v: 0.0,
            g_prev: 0.0,
            has_prev: false,
            steps: 0,
            time: 0.0,
            shaft_hz: f0,
            shaft_angle: 0.0,
            cage_angle: 0.0,
            wave_angle: 0.0,
            spin_angle: match model.cfg.defect.map(|d| d.location) {
                Some(DefectLocation::Ball { phase, .. }) => wrap_angle(phase),
                _ => 0.0,
            },
            shaft_cs: (1.0, 0.0),
            cage_cs: (1.0, 0.0),
            wave_cs: (1.0, 0.0),
            rng: Xoshiro128pp::from_u64(seed),
            rough: [0.0; NB],
            slip: [0.0; NB],
            rsqrt: core::array::from_fn(|_| core::cell::Cell::new(0.0)),
            rough_sigma: model.rough_sigma(f0, None),
            armed: 0,
            topography: None,
            shape: DefectShape::default(),
            window_cos: 2.0,
            tail: 0.0,
            lines: [DelayLine::default(); 3],
            phase: 0,
            stats: StepStats::default(),
            path: PathState::default(),
            sensor: SensorState::new(seed),
            revs: 0.0,
            run_in: 1.0,
            summit: 0.0,
        };
        if let Some(p) = model.cfg.effects.running_in {
            st.run_in = p.scale(0.0);
            st.rough_sigma *= st.run_in;
        }
        if let Some(d) = model.cfg.defect {
            st.set_topography(model, d.topography)?;
        }
        Ok(st)
    }

    /// Replaces the defect topography (wear evolution) and re-derives its shape.
    pub fn set_topography(&mut self, model: &Model, t: Topography) -> Result<(), ConfigError> {
        let Some(d) = model.cfg.defect else {
            return Err(ConfigError::Inconsistent {
                field: "defect",
                reason: "the model has no defect to give a topography to",
            });
        };
        let t = Topography::new_checked(t)?;
        d.location.check_fit(&model.cfg.bearing, &t)?;
        let shape = model.defect_shape(&t);
        let tail = shape.tail(d.model);
        let slip_margin = model
            .cfg
            .slip
            .map(|s| 3.5 * s.fraction * TAU / model.cfg.bearing.elements as Real)
            .unwrap_or(0.0);
        let span = shape.length_angle * (0.5 + tail)
            + shape.spacing_angle * (shape.count.saturating_sub(1)) as Real
            + slip_margin;
        // A ball defect's window selects its element alone: half an element pitch about
        // it (the element loop compares the unslipped element angles).
        self.window_cos = if d.location.is_ball() {
            cos(PI / model.cfg.bearing.elements as Real)
        } else if span >= PI {
            -2.0
        } else {
            cos(span)
        };
        self.rough_sigma = model.rough_sigma(self.shaft_hz, Some(t)) * self.run_in;
        self.tail = tail;
        self.shape = shape;
        self.topography = Some(t);
        Ok(())
    }

    /// Current topography of the defect, if the model has one.
    pub fn topography(&self) -> Option<Topography> {
        self.topography
    }
    /// Contact figures of the last step.
    pub fn stats(&self) -> StepStats {
        self.stats
    }
    /// Simulated time (s).
    pub fn time(&self) -> Real {
        self.time
    }
    /// Internal steps taken.
    pub fn steps(&self) -> u64 {
        self.steps
    }
    /// Current displacement `y` (m) and velocity (m/s).
    pub fn motion(&self) -> (Real, Real) {
        (self.y, self.v)
    }
    /// Sets displacement `y` (m) and velocity (m/s), e.g. for a free-decay run.
    pub fn set_motion(&mut self, y: Real, v: Real) {
        self.y = y;
        self.v = v;
        self.has_prev = false;
    }
    /// Current shaft frequency (Hz).
    pub fn shaft_hz(&self) -> Real {
        self.shaft_hz
    }
    /// Cage angle (rad), wrapped to [0, 2π).
    pub fn cage_angle(&self) -> Real {
        self.cage_angle
    }
    /// Shaft angle (rad), wrapped to [0, 2π).
    pub fn shaft_angle(&self) -> Real {
        self.shaft_angle
    }
    /// Spin angle of a ball defect (rad), wrapped to [0, 2π): `φ₀ + BSF·θ_shaft` (without
    /// the slip offset); 0 for other defects.
    pub fn spin_angle(&self) -> Real {
        self.spin_angle
    }
}
