//! One internal step of all lanes: the scalar step's arithmetic (`super::super::step`),
//! lane by lane in the same order, with the kinematics and the per-element geometry
//! computed once.

use super::super::defect_term::race_terms;
use super::super::slip_redraw::{redraw_slips, SLIP_CHECK_EVERY};
use super::super::{Channels, Model, Sample, State, StepStats, ROUGH_DRAW_MARGIN};
use super::hertz::{packed_hertz, pow_3_2_lanes, set_loads, settle_load};
use super::LaneGroup;
use crate::forces::defect::{DefectConfig, DefectLocation};
use crate::forces::{ForceDiagram, Kinematics};
use crate::integrate::IntegratorKind;
use crate::real::{angle_diff, Real, PI};
use crate::rng::{uniform_pm1_lanes, Xoshiro128pp};

/// Square roots of K lanes at once. Every implementation must return IEEE-754's
/// correctly rounded `√x` of each lane (as libm's does), so that the lanes keep the
/// scalar step's bits: a host may supply one that uses packed SIMD instructions
/// (`sqrtpd`), which the core, free of `unsafe`, cannot call.
pub trait SqrtLanes<const K: usize> {
    /// Replaces every element of `x` (≥ 0) by its square root.
    fn sqrt_lanes(&self, x: &mut [Real; K]);
}

/// [`SqrtLanes`] with libm's square root, one lane at a time.
#[derive(Debug, Clone, Copy, Default)]
pub struct LibmSqrt;

impl<const K: usize> SqrtLanes<K> for LibmSqrt {
    #[inline(always)]
    fn sqrt_lanes(&self, x: &mut [Real; K]) {
        for v in x.iter_mut() {
            *v = crate::real::sqrt(*v);
        }
    }
}

/// The defect's terms `(unload, extra deflection (m), additive force (N))` on element `e`
/// (at `elem_angle`) of a lane running `m` with state `st` and kinematics `k`: the scalar
/// step's defect block (`ball`: the ball defect's terms when `is_ball`) before the
/// load-zone gain, which `LaneConsts::zone_scale` applies to all lanes at once. `None`
/// without a defect.
#[inline(always)]
pub(super) fn defect_terms<const NB: usize>(
    m: &Model,
    st: &State<NB>,
    k: &Kinematics,
    e: usize,
    elem_angle: Real,
    is_ball: bool,
    ball: (Real, Real, Real),
) -> Option<(Real, Real, Real)> {
    let d = m.cfg.defect?;
    let slip = st.slip.get(e).copied().unwrap_or(0.0);
    let theta = k.cage_angle + elem_angle + slip;
    Some(if is_ball {
        ball
    } else {
        race_terms(d, &st.shape, st.tail, k, theta)
    })
}

/// `delta += dd` in the lanes that are `inside` the defect's window (the others keep their
/// bits, a `−0` included).
#[inline(always)]
pub(super) fn add_inside<const K: usize>(
    delta: &mut [Real; K],
    dd: &[Real; K],
    inside: &[bool; K],
) {
    for ((d, x), w) in delta.iter_mut().zip(dd).zip(inside) {
        if *w {
            *d += *x;
        }
    }
}

/// Each element's `(cos, sin)` of its angle in the cage, its waviness phasor and its angle
/// (rad).
type ElementTables<'a> = (&'a [(Real, Real)], &'a [(Real, Real)], &'a [Real]);

/// The first `n` rows of the element tables of `m`, shared by every lane.
#[inline(always)]
pub(super) fn element_tables(m: &Model, n: usize) -> ElementTables<'_> {
    (
        m.elem_cs.get(..n).unwrap_or(&[]),
        m.wave_elem_cs.get(..n).unwrap_or(&[]),
        m.elem_angle.get(..n).unwrap_or(&[]),
    )
}

impl<const K: usize> super::LaneConsts<K> {
    /// Scales the defect `terms` (unload, extra deflection, additive force) of the lanes
    /// `inside` the defect's window that have the load-zone effect by its gain at `cos ψ =
    /// sin θ` of each lane (`sin_t`): `g = (1 − m) + m·max(0, 1 − (1 − cos ψ)/(2ε))^{3/2}`,
    /// [`crate::effects::load_zone::Params::gain`]'s operations in its order, the square
    /// roots of all lanes at once by `sqrt`, as the scalar step scales each term.
    #[inline(always)]
    pub(super) fn zone_scale<S: SqrtLanes<K>>(
        &self,
        sin_t: &[Real; K],
        inside: &[bool; K],
        terms: [&mut [Real; K]; 3],
        sqrt: &S,
    ) {
        let mut x = [0.0; K];
        for ((xi, s), e2) in x.iter_mut().zip(sin_t).zip(&self.zone_eps2) {
            *xi = 1.0 - (1.0 - *s) / *e2;
        }
        let p = pow_3_2_lanes(&x, sqrt);
        let mut g = [1.0; K];
        for (((((gi, keep), m), pl), on), w) in g
            .iter_mut()
            .zip(&self.zone_keep)
            .zip(&self.zone_depth)
            .zip(&p)
            .zip(&self.zone_on)
            .zip(inside)
        {
            if *on & *w {
                *gi = *keep + *m * *pl;
            }
        }
        for t in terms {
            for ((v, gi), (on, w)) in t.iter_mut().zip(&g).zip(self.zone_on.iter().zip(inside)) {
                if *on & *w {
                    *v *= *gi;
                }
            }
        }
    }
}

impl<const K: usize, const NB: usize> LaneGroup<'_, K, NB> {
    /// Lane `l`'s generator as a scalar [`Xoshiro128pp`].
    fn lane_rng(&self, l: usize) -> Xoshiro128pp {
        let w = |i: usize| self.rng.get(i).and_then(|a| a.get(l)).copied().unwrap_or(0);
        Xoshiro128pp::from_state_words([w(0), w(1), w(2), w(3)])
    }

    /// Stores `r` as lane `l`'s generator.
    fn set_lane_rng(&mut self, l: usize, r: &Xoshiro128pp) {
        for (w, v) in self.rng.iter_mut().zip(r.state_words()) {
            if let Some(x) = w.get_mut(l) {
                *x = v;
            }
        }
    }

    /// Runs `f` on the state of every lane whose model passes `want`, with that lane's
    /// generator in `State::rng` (summit and slip draws use the scalar code).
    fn with_lane_rngs(
        &mut self,
        want: impl Fn(&super::super::Model) -> bool,
        f: impl Fn(&super::super::Model, &mut super::State<NB>),
    ) {
        self.sync_kinematics();
        let models = self.models;
        for (l, m) in models.iter().enumerate() {
            if !want(m) {
                continue;
            }
            let r = self.lane_rng(l);
            let Some(st) = self.states.get_mut(l) else {
                continue;
            };
            st.rng = r;
            f(m, st);
            let r = st.rng.clone();
            self.set_lane_rng(l, &r);
        }
    }

    /// Advances every lane by one internal step; returns one sample per lane every
    /// [`super::super::Model::oversample`] steps (lane `i`'s equals `Model::step`'s).
    pub fn step(&mut self) -> Option<[Sample; K]> {
        self.step_with(&LibmSqrt)
    }

    /// [`LaneGroup::step`] with the square roots of the Hertz loads taken by `sqrt`.
    #[inline(always)]
    pub fn step_with<S: SqrtLanes<K>>(&mut self, sqrt: &S) -> Option<[Sample; K]> {
        if self.shared {
            self.step_as::<S, false>(sqrt)
        } else {
            self.step_as::<S, true>(sqrt)
        }
    }

    /// One step with the kinematics computed once for all lanes (`OWN = false`) or by every
    /// lane for itself (`OWN = true`, `super::own`): two copies of the step, so that the
    /// shared one carries none of the other's code.
    #[inline(always)]
    pub(super) fn step_as<S: SqrtLanes<K>, const OWN: bool>(
        &mut self,
        sqrt: &S,
    ) -> Option<[Sample; K]> {
        if !self.advance_as::<S, OWN>(sqrt) {
            return None;
        }
        let taps = self.models.first()?.aa.taps();
        let [l_acc, l_vel, l_disp] = &self.lines;
        let accel = l_acc.output(taps);
        let (vel, disp) = if self.all_channels() {
            (l_vel.output(taps), l_disp.output(taps))
        } else {
            ([0.0; K], [0.0; K])
        };
        Some(self.samples(&accel, &vel, &disp))
    }

    /// [`LaneGroup::step_as`] without the output: advances every lane by one internal step
    /// and returns whether the step ends an output period (the samples are then in the
    /// delay lines).
    #[inline(always)]
    pub(super) fn advance_as<S: SqrtLanes<K>, const OWN: bool>(&mut self, sqrt: &S) -> bool {
        let models = self.models;
        let Some(m0) = models.first() else {
            return false;
        };
        if models.iter().any(|m| m.summits) {
            self.with_lane_rngs(|m| m.summits, |m, st| m.draw_summit(st));
        }
        let Some(st0) = self.states.first() else {
            return false;
        };
        let (k0, f_end0) = m0.kinematics_next(st0, 0);
        // Lanes at their own speed take their own kinematics (`super::own`).
        let own = OWN.then(|| self.own_kinematics((k0, f_end0)));
        let (y, v) = (self.y, self.v);

        // Forces outside the element loop (load, imbalance, effects), lane by lane.
        if models.iter().any(|m| m.extra_force) {
            self.sync_kinematics();
        }
        let mut f = self.c.radial_load;
        for (l, (((fl, m), st), (yl, vl))) in f
            .iter_mut()
            .zip(models)
            .zip(&self.states)
            .zip(y.iter().zip(&v))
            .enumerate()
        {
            let k = own.as_ref().and_then(|o| o.get(l)).map_or(&k0, |(k, _)| k);
            if let Some(imb) = &m.cfg.imbalance {
                *fl += imb.force(k, *yl, *vl);
            }
            if m.extra_force {
                *fl += m.extra_force(st, k);
            }
        }
        let mut stats = [StepStats::default(); K];
        let fe = match &own {
            None => self.element_forces(&k0, &mut stats, sqrt),
            Some(o) => self.element_forces_own(o, &mut stats, sqrt),
        };

        // Exact ZOH/FOH integrator, per lane.
        let c = &self.c;
        let mut g = [0.0; K];
        for l in 0..K {
            let (Some(gl), Some(fl), Some(fel), Some(kc), Some(yl), Some(im)) = (
                g.get_mut(l),
                f.get(l),
                fe.get(l),
                c.k_c0.get(l),
                y.get(l),
                c.inv_m.get(l),
            ) else {
                continue;
            };
            *gl = (*fl + *fel + *kc * *yl) * *im;
        }
        let foh = self.has_prev && m0.cfg.integrator == IntegratorKind::ExactFoh;
        let mut slope = [0.0; K];
        if foh {
            for ((s, gl), gp) in slope.iter_mut().zip(&g).zip(&self.g_prev) {
                *s = *gl - *gp;
            }
        }
        self.g_prev = g;
        self.has_prev = true;
        let mut y1 = [0.0; K];
        let mut v1 = [0.0; K];
        let mut a0 = [0.0; K];
        for l in 0..K {
            let (Some(o_y), Some(o_v), Some(o_a)) = (y1.get_mut(l), v1.get_mut(l), a0.get_mut(l))
            else {
                continue;
            };
            let get = |a: &[Real; K]| a.get(l).copied().unwrap_or(0.0);
            let (yl, vl, gl, sl) = (get(&y), get(&v), get(&g), get(&slope));
            *o_y = get(&c.p00) * yl + get(&c.p01) * vl + get(&c.g00) * gl + get(&c.g10) * sl;
            *o_v = get(&c.p10) * yl + get(&c.p11) * vl + get(&c.g01) * gl + get(&c.g11) * sl;
            *o_a = -get(&c.kl_m) * yl - get(&c.c_m) * vl + gl;
        }
        for (st, s) in self.states.iter_mut().zip(stats) {
            st.stats = s;
        }
        if models.iter().any(|m| m.cfg.slip.is_some())
            && m0.cfg.defect.is_some()
            && self
                .states
                .first()
                .is_some_and(|s| s.steps.is_multiple_of(SLIP_CHECK_EVERY))
        {
            if OWN {
                self.with_lane_rngs(|m| m.cfg.slip.is_some(), |m, st| m.update_slip(st));
            } else {
                self.update_slips();
            }
        }
        match &own {
            None => self.advance_kinematics(f_end0),
            Some(o) => self.advance_own_kinematics(o),
        }
        self.y = y1;
        self.v = v1;

        // The scalar step's `effects_step`: the transfer path for all lanes at once, then
        // running-in lane by lane.
        let a0 = self.path.filter(&a0);
        if self.run_in {
            self.sync_kinematics();
            for (m, st) in models.iter().zip(self.states.iter_mut()) {
                m.running_in_step(st);
            }
        }
        let [l_acc, l_vel, l_disp] = &mut self.lines;
        l_acc.push(&a0);
        let all = m0.cfg.channels == Channels::All;
        if all {
            l_vel.push(&v);
            let mut d = [0.0; K];
            for ((dl, yl), y0) in d.iter_mut().zip(&y).zip(&self.c.y0) {
                *dl = *yl - *y0;
            }
            l_disp.push(&d);
        }
        self.phase += 1;
        if self.phase < m0.ratio {
            return false;
        }
        self.phase = 0;
        true
    }

    /// Whether the lanes emit all three channels ([`Channels::All`]).
    #[inline(always)]
    pub(super) fn all_channels(&self) -> bool {
        self.models
            .first()
            .is_some_and(|m| m.cfg.channels == Channels::All)
    }

    /// Every lane's sample from the anti-alias outputs (acceleration, velocity,
    /// displacement), the acceleration through the lanes' sensor chains (stateful: samples
    /// come here in their order), as [`Model::sample`](super::super::Model) does per lane.
    #[inline(always)]
    pub(super) fn samples(
        &mut self,
        accel: &[Real; K],
        vel: &[Real; K],
        disp: &[Real; K],
    ) -> [Sample; K] {
        let accel = self.sensor.apply(accel);
        let mut out = [Sample::default(); K];
        for (l, o) in out.iter_mut().enumerate() {
            let get = |a: &[Real; K]| a.get(l).copied().unwrap_or(0.0);
            *o = Sample {
                accel: get(&accel),
                vel: get(vel),
                disp: get(disp),
            };
        }
        out
    }

    /// [`Model::update_slip`] of every lane with slip, for lanes that share their
    /// kinematics: which elements enter the arming region (`cos_rel > 0.5`) and which the
    /// far half-plane (`cos_rel < −0.5`) is the same for every lane, so it is decided once
    /// from lane 0's angles; each lane then updates its armed bits, and only a lane with a
    /// redraw takes its generator out of the word-major state (the scalar step's draws in
    /// the same element order, the same bits). Before, every lane synchronised its
    /// kinematics and took its generator out on every check.
    fn update_slips(&mut self) {
        let models = self.models;
        let (Some(m0), Some(first)) = (models.first(), self.states.first()) else {
            return;
        };
        let Some(regions) = m0.slip_regions(first.shaft_cs, first.cage_cs) else {
            return;
        };
        let n = m0.cfg.bearing.elements;
        for (l, m) in models.iter().enumerate() {
            let Some(slip) = m.cfg.slip else {
                continue;
            };
            let Some(armed) = self.states.get(l).map(|st| st.armed) else {
                continue;
            };
            // Only a lane with a redraw takes its generator out.
            if armed & regions.1 != 0 {
                let mut r = self.lane_rng(l);
                if let Some(st) = self.states.get_mut(l) {
                    st.armed = redraw_slips(&slip, &mut r, &mut st.slip, n, armed, regions);
                }
                self.set_lane_rng(l, &r);
            } else if let Some(st) = self.states.get_mut(l) {
                st.armed = armed | regions.0;
            }
        }
    }

    /// Moves lane 0's time, angles and phasors on (`f_end`: its shaft rate at the end of
    /// the step, when `Model::kinematics_next` evaluated it) and counts the step; the
    /// other lanes get them from [`LaneGroup::sync_kinematics`] (shared kinematics evolve
    /// identically).
    fn advance_kinematics(&mut self, f_end: Option<Real>) {
        let Some(m0) = self.models.first() else {
            return;
        };
        let Some(first) = self.states.first_mut() else {
            return;
        };
        m0.advance_kinematics_to(first, f_end);
        first.steps += 1;
        self.stale = true;
    }

    /// Copies lane 0's time, angles, phasors and step count to the other lanes if they
    /// are behind: called before any code that reads a lane's own state (summit and slip
    /// draws, effect forces and per-step effects, a ball defect's terms, the roughness
    /// level at a varying speed, a topography change), so that every such read sees
    /// what copying after each step would have given, without the copies on steps where
    /// nothing reads them.
    pub(super) fn sync_kinematics(&mut self) {
        if !self.stale {
            return;
        }
        self.stale = false;
        let Some((first, rest)) = self.states.split_first_mut() else {
            return;
        };
        for st in rest {
            st.time = first.time;
            st.shaft_hz = first.shaft_hz;
            st.shaft_angle = first.shaft_angle;
            st.cage_angle = first.cage_angle;
            st.wave_angle = first.wave_angle;
            st.spin_angle = first.spin_angle;
            st.shaft_cs = first.shaft_cs;
            st.cage_cs = first.cage_cs;
            st.wave_cs = first.wave_cs;
            st.steps = first.steps;
        }
    }

    /// Every lane's roughness amplitude of this step (m): the state's at a constant speed,
    /// else from the lane's shaft rate and topography, scaled by running-in.
    pub(super) fn rough_sigmas<S: SqrtLanes<K>>(&self, sqrt: &S) -> [Real; K] {
        // At a varying speed the amplitude's square root is taken for all lanes at once
        // (one per lane and step, lane by lane, was most of a varying-speed group's time on
        // an Intel Xeon: libm's legacy-SSE `sqrtsd` inside AVX code, docs/python.md).
        let mut root = [1.0; K];
        for ((r, m), st) in root.iter_mut().zip(self.models).zip(&self.states) {
            if m.rot.is_none() {
                *r = m.rough_ratio(st.shaft_hz);
            }
        }
        sqrt.sqrt_lanes(&mut root);
        let mut sigma = [0.0; K];
        for (((s, m), st), r) in sigma
            .iter_mut()
            .zip(self.models)
            .zip(&self.states)
            .zip(&root)
        {
            *s = if m.rot.is_some() {
                st.rough_sigma
            } else {
                m.rough_sigma_from_root(st.topography, *r) * st.run_in
            };
        }
        sigma
    }

    /// Every lane's ball-defect terms this step ([`Model::ball_defect`], zero for a lane
    /// whose defective ball is outside its window), or `None` when no lane's is in use or
    /// the defect is not on a ball. For lanes that share their kinematics: the ball's
    /// position and its spin before slip are computed once, from lane 0's state (the other
    /// lanes' kinematic fields equal it once synchronised, so nothing is copied), and only
    /// the window test and the per-lane terms lane by lane — the scalar expressions in the
    /// same order, so the same bits.
    #[inline(always)]
    fn ball_terms(
        &self,
        k: &Kinematics,
        dcs: (Real, Real),
        sin_skip: Real,
    ) -> Option<[(Real, Real, Real); K]> {
        let m0 = self.models.first()?;
        let d = m0.cfg.defect.filter(|d| d.location.is_ball())?;
        // As `Model::ball_in_use`: an element index out of range counts as in use.
        let pos = m0.ball_position(k, d, dcs);
        let used =
            |st: &State<NB>| pos.is_none_or(|(sin_t, rel)| sin_t > sin_skip && rel > st.window_cos);
        if !self.states.iter().any(used) {
            return None;
        }
        let base = m0.ball_spin_base(self.states.first()?, k);
        if self.ball_far(d, base) {
            return None;
        }
        Some(core::array::from_fn(|l| {
            match (self.models.get(l), self.states.get(l)) {
                (Some(m), Some(st)) if used(st) => match m.cfg.defect {
                    Some(dl) => m.ball_defect_from(st, k, dl, base),
                    None => (0.0, 0.0, 0.0),
                },
                _ => (0.0, 0.0, 0.0),
            }
        }))
    }

    /// Whether no lane's ball-defect term can be non-zero this step, decided once from the
    /// spin base `base` ([`Model::ball_spin_base`]) — a conservative test, so the terms the
    /// lanes do evaluate keep the scalar bits. Lane `l`'s term from its defect `kd` at
    /// contact `c` is non-zero only when `angle_diff(spin_l, c + kd·s_l)` lies in
    /// `[−L_l/2, (1/2 + tail_l)·L_l)` (`L` the defect's length angle, `s` its spacing;
    /// `add_term`'s `0 ≤ ξ < 1 + tail`), with `spin_l = base + o_l` (`o_l` its slip offset).
    /// So with `r_l = max(1/2, 1/2 + tail_l)·L_l + |o_l|`, `R = max r_l` and `S = max (n_l −
    /// 1)·s_l`, every non-zero term needs `angle_diff(base, c)` within `[−R, S + R]`
    /// (mod 2π); outside it by a margin far above the rounding of these few operations
    /// (10⁻⁶ rad against ~10⁻¹⁵), at both contacts, no lane's term is evaluated. `false`
    /// (evaluate) when a length angle is not finite and positive, or the arc comes near a
    /// whole turn.
    #[inline(always)]
    fn ball_far(&self, d: DefectConfig, base: Real) -> bool {
        const MARGIN: Real = 1e-6;
        let e = match d.location {
            DefectLocation::Ball { element, .. } => element as usize,
            _ => 0,
        };
        let (mut reach, mut arc): (Real, Real) = (0.0, 0.0);
        for (m, st) in self.models.iter().zip(&self.states) {
            let l = st.shape.length_angle;
            if l <= 0.0 || !l.is_finite() {
                return false;
            }
            let half = if st.tail > 0.0 { 0.5 + st.tail } else { 0.5 };
            let slip = st.slip.get(e).copied().unwrap_or(0.0);
            reach = reach.max(l * half + (m.slip_spin * slip).abs());
            arc = arc.max(Real::from(st.shape.count.saturating_sub(1)) * st.shape.spacing_angle);
        }
        let (lo, hi) = (reach + MARGIN, arc + reach + MARGIN);
        if lo.is_nan() || hi.is_nan() || lo >= PI || lo + hi >= 2.0 * PI {
            return false;
        }
        [0.0, PI].into_iter().all(|contact| {
            // `angle_diff` is in [−π, π); move it into [−lo, 2π − lo).
            let a = angle_diff(base, contact);
            let a = if a < -lo { a + 2.0 * PI } else { a };
            a > hi
        })
    }

    /// Hertz element forces of every lane (N), as the scalar `element_forces` with the
    /// roughness drawn in the loop: the geometry of each element once, the per-lane work
    /// in loops over the lanes.
    #[inline(always)]
    fn element_forces<S: SqrtLanes<K>>(
        &mut self,
        k: &Kinematics,
        stats: &mut [StepStats; K],
        sqrt: &S,
    ) -> [Real; K] {
        let models = self.models;
        let mut fy = [0.0; K];
        let Some(m0) = models.first() else {
            return fy;
        };
        let n = m0.cfg.bearing.elements as usize;
        let sin_skip = m0.sin_skip;
        let (cc, sc) = k.cage_cs;
        let (cw, sw) = k.wave_cs;
        let location = m0.cfg.defect.map(|d| d.location);
        let (dc, ds) = m0.defect_phasor(k);
        let ball = self
            .ball_terms(k, (dc, ds), sin_skip)
            .unwrap_or([(0.0, 0.0, 0.0); K]);
        let rough_on = m0.cfg.roughness.is_some();
        if rough_on && models.iter().any(|m| m.rot.is_none()) {
            self.sync_kinematics();
        }
        let is_ball = location.is_some_and(|l| l.is_ball());
        let sigma = if rough_on {
            self.rough_sigmas(sqrt)
        } else {
            [0.0; K]
        };
        let window_min = self
            .states
            .iter()
            .map(|s| s.window_cos)
            .fold(Real::INFINITY, |a, b| if b < a { b } else { a });
        let fast_hertz = packed_hertz(m0);
        let y = self.y;
        let c = &self.c;
        let mut max_load = [0.0; K];
        let mut defect_load = [0.0; K];
        let (ecs_all, wcs_all, ang_all) = element_tables(m0, n);
        // The generators in a local for the loop: drawn in place in the group, each lane's
        // words went through memory between two elements with stores and loads of unequal
        // widths (a store-forwarding stall per draw, the sweep's hottest instruction).
        let mut rng = self.rng;
        for (e, ((ecs, wcs), elem_angle)) in ecs_all.iter().zip(wcs_all).zip(ang_all).enumerate() {
            let (ce, se) = *ecs;
            let sin_t = sc * ce + cc * se;
            let rough = if rough_on && sin_t > sin_skip - ROUGH_DRAW_MARGIN {
                let u = uniform_pm1_lanes(&mut rng);
                let mut r = [0.0; K];
                for ((ri, s), ui) in r.iter_mut().zip(&sigma).zip(&u) {
                    *ri = *s * *ui;
                }
                r
            } else {
                [0.0; K]
            };
            if sin_t <= sin_skip {
                continue;
            }
            let (cwe, swe) = *wcs;
            let wave = sw * cwe + cw * swe;
            let mut delta = [0.0; K];
            for ((((d, yl), g), r), wa) in delta
                .iter_mut()
                .zip(&y)
                .zip(&c.gamma)
                .zip(&rough)
                .zip(&c.wave_amp)
            {
                let x = *yl * sin_t - *g - *r;
                *d = if *wa != 0.0 { x - *wa * wave } else { x };
            }
            let mut unload = [0.0; K];
            let mut add = [0.0; K];
            if location.is_some() {
                let cos_t = cc * ce - sc * se;
                let cos_rel = cos_t * dc + sin_t * ds;
                if cos_rel > window_min {
                    let mut dd = [0.0; K];
                    let mut inside = [false; K];
                    for l in 0..K {
                        let (Some(m), Some(st), Some(bt)) =
                            (models.get(l), self.states.get(l), ball.get(l))
                        else {
                            continue;
                        };
                        if cos_rel <= st.window_cos {
                            continue;
                        }
                        let (Some((u, d, a)), Some(ul), Some(dl), Some(al), Some(w), Some(x)) = (
                            defect_terms(m, st, k, e, *elem_angle, is_ball, *bt),
                            unload.get_mut(l),
                            dd.get_mut(l),
                            add.get_mut(l),
                            inside.get_mut(l),
                            delta.get_mut(l),
                        ) else {
                            continue;
                        };
                        (*ul, *al, *w) = (u, a, true);
                        // Without a load zone in the group the extra deflection goes in
                        // at once (the gains would all be 1).
                        if c.zone_any {
                            *dl = d;
                        } else {
                            *x += d;
                        }
                    }
                    if c.zone_any {
                        c.zone_scale(&[sin_t; K], &inside, [&mut unload, &mut dd, &mut add], sqrt);
                        add_inside(&mut delta, &dd, &inside);
                    }
                }
            }
            let mut q = self.hertz_loads(&delta, e, &[true; K], fast_hertz, sqrt);
            for (((((ql, ul), al), ml), dl), fl) in q
                .iter_mut()
                .zip(&unload)
                .zip(&add)
                .zip(max_load.iter_mut())
                .zip(defect_load.iter_mut())
                .zip(fy.iter_mut())
            {
                *fl -= settle_load(*ql, *ul, *al, ml, dl) * sin_t;
            }
        }
        self.rng = rng;
        set_loads(stats, max_load, defect_load);
        fy
    }
}
