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
//!
//! The model is split after what each part holds: [`config`] (what a run is, and its
//! validation into a [`Model`]), [`state`] (what evolves, with the one field list the
//! checkpoint reuses), `step` (the equation of motion advanced by one internal step),
//! `slip_redraw` (the elements' slip offsets, redrawn once per pass) and `defect_term` (the
//! defect formulations, one term shared by race and ball defects).

pub mod config;
mod defect_term;
pub mod lanes;
mod output;
mod slip_redraw;
pub mod state;
mod step;

pub use config::{Channels, ModelConfig, Structure, MASS_RANGE, MAX_OVERSAMPLE, OUTPUT_RATE_RANGE};
pub use lanes::{LaneError, LaneGroup, LibmSqrt, SqrtLanes};
pub use state::State;
pub(crate) use state::StateParts;

use crate::bearing::MAX_ELEMENTS;
use crate::contact::ElementContact;
use crate::decimate::AntiAlias;
use crate::effects::sensor::SensorChain;
use crate::effects::transfer_path::TransferPath;
use crate::forces::defect::{DefectShape, StaticReference};
use crate::integrate::Discretization;
use crate::kinematics::{FaultFrequencies, FaultOrders};
use crate::load_zone::Equilibrium;
use crate::real::{sqrt, Real, STANDARD_GRAVITY, TAU};
use crate::topography::Topography;

/// Margin (in `sin θ`) below the contact limit [`Model`]`::sin_skip` within which an
/// element still gets a roughness draw: the draw and the element loop must agree on it,
/// so it is one constant.
const ROUGH_DRAW_MARGIN: Real = 0.05;

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
    /// The validated configuration.
    pub fn config(&self) -> &ModelConfig {
        &self.cfg
    }
    /// Kinematic orders of the bearing (eq. 17–20).
    pub fn orders(&self) -> FaultOrders {
        self.orders
    }
    /// Characteristic frequencies (Hz) of this bearing and structure at shaft frequency
    /// `shaft_hz` (Hz): eq. 17–20 and [`Model::natural_frequency_hz`].
    pub fn frequencies_at(&self, shaft_hz: Real) -> FaultFrequencies {
        self.orders.at(shaft_hz, self.natural_frequency_hz())
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
    /// Whether the shaft turns at a constant rate (no speed profile change, no speed
    /// fluctuation): its angles then advance by fixed rotations per step, without a sine
    /// or cosine (the cheap kinematics that lanes at their own speed can afford).
    pub fn constant_speed(&self) -> bool {
        self.rot.is_some()
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
                    d.sassi_k_impact,
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
