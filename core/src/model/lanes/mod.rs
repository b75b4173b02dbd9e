//! K models stepped together ([`LaneGroup`]): throughput for sweeps and fits (issue 15).
//!
//! Models that share the step and the element geometry — bearing, output rate,
//! oversampling and step, integrator (exact ZOH/FOH), defect location, waviness order,
//! roughness on/off and the contact limit — can be lanes of one group. When they also
//! share the speed profile (and its fluctuation) they move their shaft, cage and elements
//! identically, so the kinematics and each element's `sin θ`, `cos θ` and defect phasor
//! are computed once per step for all lanes; otherwise each lane computes its own
//! (`own.rs`, a slower path: see [`same_kinematics`]). Everything that
//! differs (motion, radial load, structure and its discretisation, contact stiffness and
//! offset, roughness amplitude and generator, defect size/model/shape, waviness amplitude,
//! imbalance, slip (its offsets are per lane), load zone, edge shape, running-in,
//! transfer path, sensor, shaft harmonics, the anti-alias history) lives per lane in `[Real; K]` arrays, and the per-lane
//! arithmetic runs in tight loops over them that the compiler vectorises.
//!
//! Contract: lane `i`'s samples equal, bit for bit, [`Model::step`] of model `i` from
//! `State::new(model_i, seed_i)`: every lane does exactly the arithmetic of the scalar
//! step in the same order (Rust does not contract to FMA). A group the stepper cannot
//! share is refused by [`LaneGroup::new_checked`] with the field that differs, and the
//! caller falls back to the scalar step.

mod check;
mod hertz;
mod own;
mod step;

pub use check::{same_kinematics, shareable, LaneError};
pub use step::{LibmSqrt, SqrtLanes};

use super::{Model, Sample, State, StepStats};
use crate::decimate::{BLOCK, MAX_TAPS};
use crate::effects::sensor::SensorLanes;
use crate::effects::transfer_path::PathLanes;
use crate::real::Real;
use crate::topography::Topography;

/// SoA anti-alias history of one channel: sample `j` of every lane side by side, the
/// buffer doubled like [`crate::decimate::DelayLine`] so the window is contiguous.
#[derive(Debug, Clone)]
struct LaneLine<const K: usize> {
    buf: [[Real; K]; 2 * MAX_TAPS],
    pos: usize,
}

impl<const K: usize> LaneLine<K> {
    fn new() -> Self {
        LaneLine {
            buf: [[0.0; K]; 2 * MAX_TAPS],
            pos: 0,
        }
    }

    /// Appends one sample per lane.
    #[inline(always)]
    fn push(&mut self, x: &[Real; K]) {
        if let Some(v) = self.buf.get_mut(self.pos) {
            *v = *x;
        }
        if let Some(v) = self.buf.get_mut(self.pos + MAX_TAPS) {
            *v = *x;
        }
        self.pos += 1;
        if self.pos >= MAX_TAPS {
            self.pos = 0;
        }
    }

    /// `Σ taps[j]·x[j]` per lane over the last `taps.len()` samples, oldest first and
    /// summed in that order (as [`crate::decimate::AntiAlias::output`]).
    #[inline(always)]
    fn output(&self, taps: &[Real]) -> [Real; K] {
        let end = self.pos + MAX_TAPS;
        let start = end.saturating_sub(taps.len());
        let hist = self.buf.get(start..end).unwrap_or(&[]);
        let mut acc = [0.0; K];
        for (t, x) in taps.iter().zip(hist) {
            for (a, xv) in acc.iter_mut().zip(x) {
                *a += t * xv;
            }
        }
        acc
    }

    /// [`LaneLine::output`] at the last [`BLOCK`] output instants, `ratio` samples apart,
    /// oldest first (`span` = [`AntiAlias::block_span`](crate::decimate::AntiAlias::block_span)):
    /// the same sums in the same order, four of them advancing together, as
    /// [`AntiAlias::outputs_block`](crate::decimate::AntiAlias::outputs_block).
    #[inline(always)]
    fn outputs_block(&self, taps: &[Real], ratio: usize, span: usize) -> [[Real; K]; BLOCK] {
        let end = self.pos + MAX_TAPS;
        let start = end.saturating_sub(span);
        let hist = self.buf.get(start..end).unwrap_or(&[]);
        let n = taps.len();
        let w = |j: usize| hist.get(j * ratio..j * ratio + n).unwrap_or(&[]);
        let mut acc = [[0.0; K]; BLOCK];
        for ((((t, a), b), c), d) in taps.iter().zip(w(0)).zip(w(1)).zip(w(2)).zip(w(3)) {
            let [s0, s1, s2, s3] = &mut acc;
            for (((((x0, x1), x2), x3), ((y0, y1), y2)), y3) in s0
                .iter_mut()
                .zip(s1.iter_mut())
                .zip(s2.iter_mut())
                .zip(s3.iter_mut())
                .zip(a.iter().zip(b).zip(c))
                .zip(d)
            {
                *x0 += t * y0;
                *x1 += t * y1;
                *x2 += t * y2;
                *x3 += t * y3;
            }
        }
        acc
    }
}

/// Widest group whose outputs [`LaneGroup::fill_with`] takes in blocks of [`BLOCK`]
/// output instants; wider groups take them one instant at a time.
const BLOCK_LANES: usize = 8;

/// Per-lane constants of the step, gathered from the models once.
#[derive(Debug, Clone)]
struct LaneConsts<const K: usize> {
    radial_load: [Real; K],
    gamma: [Real; K],
    stiffness: [Real; K],
    wave_amp: [Real; K],
    k_c0: [Real; K],
    inv_m: [Real; K],
    kl_m: [Real; K],
    c_m: [Real; K],
    y0: [Real; K],
    /// Discretisation `Φ`, `Γ₀`, `Γ₁` per lane.
    p00: [Real; K],
    p01: [Real; K],
    p10: [Real; K],
    p11: [Real; K],
    g00: [Real; K],
    g01: [Real; K],
    g10: [Real; K],
    g11: [Real; K],
    /// The load-zone effect's gain per lane (`effects::load_zone::Params::gain`, Harris &
    /// Kotzalas 2006 eq. 7.26): whether the lane has the effect, `1 − depth`, `depth` and
    /// `2ε` (1 without the effect); and whether any lane has it.
    zone_on: [bool; K],
    zone_keep: [Real; K],
    zone_depth: [Real; K],
    zone_eps2: [Real; K],
    zone_any: bool,
}

/// The load-zone effect of model `m`, if on.
fn zone(m: &Model) -> Option<&crate::effects::load_zone::Params> {
    m.cfg.effects.load_zone.as_ref()
}

/// K models stepped together (see the module documentation). `NB` is the element
/// capacity of each lane's [`State`]. About `K × (size_of::<State<NB>>() + 12 KB)` bytes
/// (the lanes' own anti-alias histories: 3 channels × 512 samples × 8 B per lane): hold
/// it in a `Box` on the host for large K.
#[derive(Debug, Clone)]
pub struct LaneGroup<'a, const K: usize, const NB: usize> {
    models: &'a [Model; K],
    /// Per-lane state of everything the SoA arrays below do not hold (angles are kept
    /// equal across lanes; motion, generator and filter history live in the arrays).
    states: [State<NB>; K],
    c: LaneConsts<K>,
    y: [Real; K],
    v: [Real; K],
    g_prev: [Real; K],
    has_prev: bool,
    /// xoshiro128++ state words, word-major: `rng[w][lane]`.
    rng: [[u32; K]; 4],
    lines: [LaneLine<K>; 3],
    /// The lanes' transfer paths and their memories (the states' `path` is not used).
    path: PathLanes<K>,
    /// The lanes' sensor chains and their memories (the states' `sensor` is not used).
    sensor: SensorLanes<K>,
    /// Some lane runs in (its per-step work reads the lane's own state).
    run_in: bool,
    phase: u32,
    /// Every lane moves as lane 0 ([`check::same_kinematics`]): the kinematics are computed
    /// once for all lanes; otherwise each lane computes its own (`own`).
    shared: bool,
    /// Lanes 1.. have not yet been given lane 0's latest time, angles and phasors (they
    /// are copied only before code that reads a lane's own state: see
    /// `step::sync_kinematics`).
    stale: bool,
}

impl<'a, const K: usize, const NB: usize> LaneGroup<'a, K, NB> {
    /// Lane `i` runs `models[i]` from `State::new(&models[i], seeds[i])`. Refuses (with
    /// the field) models that do not share their kinematics, an RK4 integrator, `K = 0`
    /// and a capacity `NB` below the bearing's element count.
    pub fn new_checked(models: &'a [Model; K], seeds: &[u64; K]) -> Result<Self, LaneError> {
        check::compatible(models)?;
        let Some(m0) = models.first() else {
            return Err(LaneError::Empty);
        };
        // Placeholders (cannot fail), each replaced by its lane's checked initial state.
        let mut states: [State<NB>; K] = core::array::from_fn(|_| State::fresh(m0, 0, 0.0));
        for ((s, m), seed) in states.iter_mut().zip(models).zip(seeds) {
            *s = State::new(m, *seed).map_err(LaneError::Config)?;
        }
        let c = LaneConsts {
            radial_load: models.each_ref().map(|m| m.cfg.radial_load),
            gamma: models.each_ref().map(|m| m.gamma),
            stiffness: models.each_ref().map(|m| m.contact.stiffness),
            wave_amp: models
                .each_ref()
                .map(|m| m.cfg.waviness.map(|w| w.amplitude).unwrap_or(0.0)),
            k_c0: models.each_ref().map(|m| m.eq.contact_stiffness),
            inv_m: models.each_ref().map(|m| m.inv_m),
            kl_m: models.each_ref().map(|m| m.kl_m),
            c_m: models.each_ref().map(|m| m.c_m),
            y0: models.each_ref().map(|m| m.eq.y0),
            p00: models.each_ref().map(|m| m.disc.phi[0][0]),
            p01: models.each_ref().map(|m| m.disc.phi[0][1]),
            p10: models.each_ref().map(|m| m.disc.phi[1][0]),
            p11: models.each_ref().map(|m| m.disc.phi[1][1]),
            g00: models.each_ref().map(|m| m.disc.gamma0[0]),
            g01: models.each_ref().map(|m| m.disc.gamma0[1]),
            g10: models.each_ref().map(|m| m.disc.gamma1[0]),
            g11: models.each_ref().map(|m| m.disc.gamma1[1]),
            zone_on: models.each_ref().map(|m| zone(m).is_some()),
            zone_keep: models
                .each_ref()
                .map(|m| zone(m).map_or(1.0, |p| 1.0 - p.depth)),
            zone_depth: models.each_ref().map(|m| zone(m).map_or(0.0, |p| p.depth)),
            zone_eps2: models
                .each_ref()
                .map(|m| zone(m).map_or(1.0, |p| 2.0 * p.epsilon)),
            zone_any: models.iter().any(|m| zone(m).is_some()),
        };
        let y = states.each_ref().map(|s| s.y);
        let words = states.each_ref().map(|s| s.rng.state_words());
        let rng = core::array::from_fn(|w| words.map(|s| s.get(w).copied().unwrap_or(0)));
        let path = PathLanes::new(
            models.each_ref().map(|m| m.transfer.as_ref()),
            states.each_ref().map(|s| &s.path),
        );
        let sensor = SensorLanes::new(
            models.each_ref().map(|m| m.sensor_chain.as_ref()),
            states.each_ref().map(|s| &s.sensor),
        );
        Ok(LaneGroup {
            models,
            states,
            c,
            y,
            v: [0.0; K],
            g_prev: [0.0; K],
            has_prev: false,
            rng,
            lines: [LaneLine::new(), LaneLine::new(), LaneLine::new()],
            path,
            sensor,
            run_in: models.iter().any(|m| m.cfg.effects.running_in.is_some()),
            phase: 0,
            shared: models.iter().all(|m| check::same_kinematics(m0, m)),
            stale: false,
        })
    }

    /// The models, lane by lane.
    pub fn models(&self) -> &'a [Model; K] {
        self.models
    }

    /// Replaces lane `lane`'s defect topography (wear evolution); see
    /// [`State::set_topography`]. A lane index out of range is an error naming `lane`.
    pub fn set_topography(&mut self, lane: usize, t: Topography) -> Result<(), LaneError> {
        self.sync_kinematics();
        let (Some(st), Some(m)) = (self.states.get_mut(lane), self.models.get(lane)) else {
            return Err(LaneError::Config(crate::error::ConfigError::TooMany {
                field: "lane",
                count: lane,
                max: K,
            }));
        };
        st.set_topography(m, t).map_err(LaneError::Config)
    }

    /// Contact figures of the last step, per lane.
    pub fn stats(&self) -> [StepStats; K] {
        self.states.each_ref().map(|s| s.stats)
    }

    /// Shaft and cage angle (rad, in `[0, 2π)`) of lane `lane` after the last step: its
    /// scalar state's [`State::shaft_angle`] and [`State::cage_angle`] (lanes that share
    /// their kinematics read lane 0's, which the others copy only when needed). `None` for a
    /// lane out of range.
    pub fn angles(&self, lane: usize) -> Option<(Real, Real)> {
        let own = if self.shared { 0 } else { lane };
        let st = self.states.get(own).filter(|_| lane < K)?;
        Some((st.shaft_angle, st.cage_angle))
    }

    /// Internal steps taken (the same in every lane).
    pub fn steps(&self) -> u64 {
        self.states.first().map_or(0, |s| s.steps)
    }

    /// Fills `out` with output samples, lane by lane (`out[j][i]` is lane `i`'s sample `j`);
    /// returns how many were written (all of them).
    pub fn fill(&mut self, out: &mut [[Sample; K]]) -> usize {
        self.fill_with(out, &LibmSqrt)
    }

    /// [`LaneGroup::fill`] with the square roots of the Hertz loads taken by `sqrt` (see
    /// [`SqrtLanes`]).
    #[inline(always)]
    pub fn fill_with<S: SqrtLanes<K>>(&mut self, out: &mut [[Sample; K]], sqrt: &S) -> usize {
        self.fill_observed_with(out, sqrt, |_| {})
    }

    /// [`LaneGroup::fill_with`], calling `observe` with the group after every internal
    /// step (for per-lane meters that read [`LaneGroup::stats`] and the angles, as a
    /// life's pass meters do).
    #[inline(always)]
    pub fn fill_observed_with<S: SqrtLanes<K>>(
        &mut self,
        out: &mut [[Sample; K]],
        sqrt: &S,
        observe: impl FnMut(&Self),
    ) -> usize {
        if self.shared {
            self.fill_as::<S, false>(out, sqrt, observe)
        } else {
            self.fill_as::<S, true>(out, sqrt, observe)
        }
    }

    /// [`LaneGroup::fill_with`] through one of the two copies of the step (see
    /// `step::step_as`).
    #[inline(always)]
    fn fill_as<S: SqrtLanes<K>, const OWN: bool>(
        &mut self,
        out: &mut [[Sample; K]],
        sqrt: &S,
        mut observe: impl FnMut(&Self),
    ) -> usize {
        let models = self.models;
        let Some(m0) = models.first() else {
            return 0;
        };
        // Wide groups sum enough lanes side by side to keep the FPU busy, and four
        // instants' sums of 16 lanes (64 accumulators) would not stay in registers.
        let span = m0.aa.block_span().filter(|_| K <= BLOCK_LANES);
        let (taps, ratio) = (m0.aa.taps(), m0.ratio as usize);
        let all = self.all_channels();
        let mut written = 0;
        for chunk in out.chunks_mut(BLOCK) {
            match span {
                // Four output periods stepped, then their four outputs together (the
                // filter does not feed back; `super::super::output` explains the gain).
                Some(span) if chunk.len() == BLOCK => {
                    for _ in 0..BLOCK {
                        while !self.advance_as::<S, OWN>(sqrt) {
                            observe(self);
                        }
                        observe(self);
                    }
                    let [l_acc, l_vel, l_disp] = &self.lines;
                    let accel = l_acc.outputs_block(taps, ratio, span);
                    let (vel, disp) = if all {
                        (
                            l_vel.outputs_block(taps, ratio, span),
                            l_disp.outputs_block(taps, ratio, span),
                        )
                    } else {
                        ([[0.0; K]; BLOCK], [[0.0; K]; BLOCK])
                    };
                    for (((slot, a), v), d) in chunk.iter_mut().zip(&accel).zip(&vel).zip(&disp) {
                        *slot = self.samples(a, v, d);
                    }
                }
                _ => {
                    for slot in chunk.iter_mut() {
                        loop {
                            let s = self.step_as::<S, OWN>(sqrt);
                            observe(self);
                            if let Some(s) = s {
                                *slot = s;
                                break;
                            }
                        }
                    }
                }
            }
            written += chunk.len();
        }
        written
    }
}
