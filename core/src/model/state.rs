//! What evolves during a run ([`State`]): motion, angles, random generator, per-element
//! slip and roughness, the current defect topography and the anti-alias history.
//!
//! The fields are listed once, in `state_fields!` below, each tagged `[saved]` (restored
//! from a checkpoint) or `[derived]` (re-derived from the model and the saved fields).
//! The list generates the struct (in the listed order: field order sets offsets that the
//! M4F pays for), its initial value, and the plain `StateParts` of the saved fields with
//! `parts`/`restore` that `crate::checkpoint` uses; adding a state field is one line here
//! (plus, for a saved one, its bytes in the checkpoint's encoding).

use super::{Model, StepStats};
use crate::decimate::DelayLine;
use crate::effects::sensor::SensorState;
use crate::effects::transfer_path::PathState;
use crate::error::ConfigError;
use crate::forces::defect::{DefectLocation, DefectShape};
use crate::real::{cos, wrap_angle, Real, PI, TAU};
use crate::rng::Xoshiro128pp;
use crate::topography::Topography;

/// Generates [`State`], its initial value and [`StateParts`] from one tagged field list.
macro_rules! state_fields {
    (
        $fresh:ident($model:ident, $seed:ident, $f0:ident);
        $( #[doc = $doc:literal] [$tag:ident] $f:ident : $t:ty = $init:expr, )*
    ) => {

        /// The evolving state of one run: motion, angles, random generator, per-element slip and
        /// roughness, the current defect topography and the anti-alias history. `NB` is the
        /// element capacity (≥ the bearing's element count). Its size is fixed at compile time:
        /// with `f64` and `NB = 16` it is about 12.8 KB (three filter delay lines of
        /// 2 × 256 samples dominate; 6.4 KB with `f32`); see `size_of::<State<16>>()` in the tests.
        #[derive(Debug, Clone)]
        pub struct State<const NB: usize> {
            $( #[doc = $doc] pub(super) $f: $t, )*
        }

        impl<const NB: usize> State<NB> {
            /// The initial value of every field.
            pub(super) fn $fresh($model: &Model, $seed: u64, $f0: Real) -> Self {
                State { $( $f: $init, )* }
            }
        }

        state_fields!(@saved [] $( [$tag] $f : $t, )*);
    };
    (@saved [$($acc:tt)*] [saved] $f:ident : $t:ty, $($rest:tt)*) => {
        state_fields!(@saved [$($acc)* $f : $t,] $($rest)*);
    };
    (@saved [$($acc:tt)*] [derived] $f:ident : $t:ty, $($rest:tt)*) => {
        state_fields!(@saved [$($acc)*] $($rest)*);
    };
    (@saved [$($f:ident : $t:ty,)*]) => {
        /// The saved fields of a [`State`], for checkpoints (`crate::checkpoint`).
        #[derive(Debug, Clone)]
        pub(crate) struct StateParts<const NB: usize> {
            $( pub $f: $t, )*
        }

        impl<const NB: usize> State<NB> {
            /// The saved fields.
            #[allow(clippy::clone_on_copy)]
            pub(crate) fn parts(&self) -> StateParts<NB> {
                StateParts { $( $f: self.$f.clone(), )* }
            }

            /// Sets the saved fields (the derived ones are re-derived by the caller).
            pub(crate) fn restore(&mut self, p: StateParts<NB>) {
                $( self.$f = p.$f; )*
            }
        }
    };
}

state_fields! {
    fresh(model, seed, f0);
    /// Displacement `y` (m).
    [saved] y: Real = model.eq.y0,
    /// Velocity (m/s).
    [saved] v: Real = 0.0,
    /// Acceleration term of the previous step (first-order-hold integrator).
    [saved] g_prev: Real = 0.0,
    /// Whether `g_prev` holds a value.
    [saved] has_prev: bool = false,
    /// Internal steps taken.
    [saved] steps: u64 = 0,
    /// Simulated time (s).
    [saved] time: Real = 0.0,
    /// Shaft frequency (Hz).
    [saved] shaft_hz: Real = f0,
    /// Shaft angle (rad).
    [saved] shaft_angle: Real = 0.0,
    /// Cage angle (rad).
    [saved] cage_angle: Real = 0.0,
    /// Waviness angle (rad).
    [saved] wave_angle: Real = 0.0,
    /// Spin angle of a ball defect (rad).
    [saved] spin_angle: Real = match model.cfg.defect.map(|d| d.location) {
        Some(DefectLocation::Ball { phase, .. }) => wrap_angle(phase),
        _ => 0.0,
    },
    /// Shaft phasor `(cos, sin)`.
    [saved] shaft_cs: (Real, Real) = (1.0, 0.0),
    /// Cage phasor.
    [saved] cage_cs: (Real, Real) = (1.0, 0.0),
    /// Waviness phasor.
    [saved] wave_cs: (Real, Real) = (1.0, 0.0),
    /// The model's random generator.
    [saved] rng: Xoshiro128pp = Xoshiro128pp::from_u64(seed),
    /// Roughness height of each element this step (m).
    [saved] rough: [Real; NB] = [0.0; NB],
    /// Slip offset of each element (rad).
    [saved] slip: [Real; NB] = [0.0; NB],
    /// Cached inverse square roots of the element deflections (f32 Hertz load).
    [saved] rsqrt: [core::cell::Cell<Real>; NB] = core::array::from_fn(|_| core::cell::Cell::new(0.0)),
    /// Amplitude of the roughness draw (m), cached for constant speed.
    [saved] rough_sigma: Real = model.rough_sigma(f0, None),
    /// Slip bookkeeping: elements armed for a redraw (one bit each).
    [saved] armed: u32 = 0,
    /// Current defect topography.
    [saved] topography: Option<Topography> = None,
    /// Defect shape derived from the topography.
    [derived] shape: DefectShape = DefectShape::default(),
    /// Cosine of the half-width of the defect's candidate window.
    [derived] window_cos: Real = 2.0,
    /// Length of the defect's tail in defect lengths.
    [derived] tail: Real = 0.0,
    /// Anti-alias delay lines (acceleration, velocity, displacement).
    [saved] lines: [DelayLine; 3] = [DelayLine::default(); 3],
    /// Internal step within the current output sample.
    [saved] phase: u32 = 0,
    /// Contact figures of the last step.
    [derived] stats: StepStats = StepStats::default(),
    /// Transfer-path filter memory.
    [saved] path: PathState = PathState::default(),
    /// Sensor-chain memory.
    [saved] sensor: SensorState = SensorState::new(seed),
    /// Shaft revolutions of this run (running-in).
    [saved] revs: Real = 0.0,
    /// Running-in roughness factor.
    [saved] run_in: Real = 1.0,
    /// Running-in summit force of the current step (N); set at the step's start.
    [derived] summit: Real = 0.0,
}

impl<const NB: usize> State<NB> {
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
        let mut st = State::fresh(model, seed, f0);
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
