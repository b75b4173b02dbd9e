//! The equation of motion advanced by one internal step: kinematics, the force diagrams
//! (imbalance, Hertz element loads with waviness, roughness and the defect, the effects'
//! extra forces), the integrator, the effects' per-step work and the decimation.

use super::defect_term::{add_term, race_terms};
use super::{renorm, rotate, Channels, Model, Sample, State, StepStats, ROUGH_DRAW_MARGIN};
use crate::forces::defect::{DefectConfig, DefectLocation};
use crate::forces::{ForceDiagram, Kinematics};
use crate::integrate::{rk4, IntegratorKind};
use crate::real::{
    advance_angle, angle_diff, cos, sin, small_angle_cos_sin, wrap_angle, Real, PI, TAU,
};
use crate::rng::Xoshiro128pp;
use crate::topography::Topography;

impl Model {
    /// The defect's phasor `(cos, sin)` at kinematics `k`: defect 0's position, turning
    /// with the shaft for an inner-race defect and with the cage for a ball defect (the
    /// defective element's), fixed for an outer-race defect and without one.
    #[inline(always)]
    pub(super) fn defect_phasor(&self, k: &Kinematics) -> (Real, Real) {
        match self.cfg.defect.map(|d| d.location) {
            Some(DefectLocation::InnerRace { .. }) => rotate(k.shaft_cs, self.defect_offset_cs),
            Some(DefectLocation::Ball { .. }) => rotate(k.cage_cs, self.defect_offset_cs),
            _ => self.defect_offset_cs,
        }
    }

    /// Kinematics at the state's current time, advanced by `frac·h` (0, ½ or 1).
    #[inline(always)]
    pub(super) fn kinematics<const NB: usize>(&self, st: &State<NB>, frac: u8) -> Kinematics {
        self.kinematics_next(st, frac).0
    }

    /// [`Model::kinematics`], with the shaft rate at the end of the step (Hz) when the
    /// speed profile had to be evaluated there (a varying speed), for
    /// [`Model::advance_kinematics_to`]: the profile (a speed fluctuation is nine `sin`)
    /// is evaluated once per time instead of up to three times, with the same bits.
    #[inline(always)]
    pub(super) fn kinematics_next<const NB: usize>(
        &self,
        st: &State<NB>,
        frac: u8,
    ) -> (Kinematics, Option<Real>) {
        let f0 = st.shaft_hz;
        let mut f_end = None;
        let (shaft_hz, dshaft, rot) = match (frac, self.rot) {
            (0, _) => (f0, 0.0, None),
            (1, Some(r)) => (f0, 0.0, Some((r.shaft_half, r.cage_half, r.wave_half))),
            (_, Some(r)) => (f0, 0.0, Some((r.shaft, r.cage, r.wave))),
            (fr, None) => {
                let dt = if fr == 1 { 0.5 * self.h } else { self.h };
                let f1 = self.speed_hz(st.time + dt);
                if fr != 1 {
                    f_end = Some(f1);
                }
                (f1, PI * (f0 + f1) * dt, None)
            }
        };
        let omega = TAU * shaft_hz;
        let alpha = match self.rot {
            Some(_) => 0.0,
            None => {
                let f2 = match f_end {
                    Some(f) => f,
                    None => self.speed_hz(st.time + self.h),
                };
                f_end = Some(f2);
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
        (k, f_end)
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
        let (dc, ds) = self.defect_phasor(k);
        // A ball defect's terms are computed out of line before the loop (a call inside it
        // would cost the race defects' path registers), and only on steps where the loop
        // will use them.
        let ball = match defect {
            Some(d) if d.location.is_ball() => {
                Some(if self.ball_in_use(st, k, d, (dc, ds), sin_skip) {
                    self.ball_defect(st, k, d)
                } else {
                    (0.0, 0.0, 0.0)
                })
            }
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
                Some((rng, sigma)) if sin_t > sin_skip - ROUGH_DRAW_MARGIN => {
                    *sigma * rng.uniform_pm1()
                }
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
                    // Only the defective element of a ball defect is in the window (half
                    // an element pitch wide).
                    let mut dd;
                    (unload, dd, add) = match ball {
                        Some(terms) => terms,
                        None => race_terms(d, shape, st.tail, k, theta),
                    };
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

    /// Whether the element loop applies ball defect `d`'s terms this step: its element is
    /// loaded (`sin θ > sin_skip`) and inside the window about the defect phasor `dcs`,
    /// by the loop's own expressions. Only that element can be in the window (half a
    /// pitch wide), so on other steps [`Model::ball_defect`] need not be evaluated.
    #[inline(always)]
    pub(super) fn ball_in_use<const NB: usize>(
        &self,
        st: &State<NB>,
        k: &Kinematics,
        d: DefectConfig,
        dcs: (Real, Real),
        sin_skip: Real,
    ) -> bool {
        self.ball_position(k, d, dcs)
            .is_none_or(|(sin_t, rel)| sin_t > sin_skip && rel > st.window_cos)
    }

    /// The defective ball's `(sin θ, cos of its angle to the defect phasor dcs)` for
    /// kinematics `k`, by the element loop's own expressions: the geometric part of
    /// [`Model::ball_in_use`], the same for lanes that share their kinematics. `None` for an
    /// element index out of range.
    #[inline(always)]
    pub(super) fn ball_position(
        &self,
        k: &Kinematics,
        d: DefectConfig,
        dcs: (Real, Real),
    ) -> Option<(Real, Real)> {
        let e = match d.location {
            DefectLocation::Ball { element, .. } => element as usize,
            _ => 0,
        };
        let (ce, se) = self.elem_cs.get(e).copied()?;
        let (cc, sc) = k.cage_cs;
        let sin_t = sc * ce + cc * se;
        let cos_t = cc * ce - sc * se;
        Some((sin_t, cos_t * dcs.0 + sin_t * dcs.1))
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
    pub(super) fn ball_defect<const NB: usize>(
        &self,
        st: &State<NB>,
        k: &Kinematics,
        d: DefectConfig,
    ) -> (Real, Real, Real) {
        self.ball_defect_from(st, k, d, self.ball_spin_base(st, k))
    }

    /// The ball's spin angle at this evaluation before its slip offset (rad): the state's,
    /// advanced by BSF × the shaft's advance within the step. The kinematic part of
    /// [`Model::ball_defect`], the same for lanes that share their kinematics.
    #[inline(always)]
    pub(super) fn ball_spin_base<const NB: usize>(&self, st: &State<NB>, k: &Kinematics) -> Real {
        st.spin_angle + self.spin_order * angle_diff(k.shaft_angle, st.shaft_angle)
    }

    /// [`Model::ball_defect`] from the spin base `base` ([`Model::ball_spin_base`]): the
    /// per-lane part (the element's slip, the defect's shape and tail).
    #[inline(always)]
    pub(super) fn ball_defect_from<const NB: usize>(
        &self,
        st: &State<NB>,
        k: &Kinematics,
        d: DefectConfig,
        base: Real,
    ) -> (Real, Real, Real) {
        let shape = &st.shape;
        let e = match d.location {
            DefectLocation::Ball { element, .. } => element as usize,
            _ => 0,
        };
        let slip = st.slip.get(e).copied().unwrap_or(0.0);
        let theta = k.cage_angle + self.elem_angle.get(e).copied().unwrap_or(0.0) + slip;
        let spin = base + self.slip_spin * slip;
        let mut terms = (0.0, 0.0, 0.0);
        for contact in [0.0, PI] {
            for kd in 0..shape.count {
                let centre = contact + kd as Real * shape.spacing_angle;
                let xi = angle_diff(spin, centre) / shape.length_angle + 0.5;
                let speed = || self.spin_order * k.shaft_omega * shape.race_radius;
                add_term(d.model, shape, xi, st.tail, theta, speed, &mut terms);
            }
        }
        terms
    }

    /// Hertz element load `K δ^p` (N). In `f32` builds point contacts use `δ²·(1/√δ)` with
    /// the inverse square root refined by two Newton steps from the element's value of
    /// the previous evaluation (cached in `rsqrt`; libm's `sqrtf` only when the cache is
    /// cold or off by more than 10 %): libm's software `sqrtf` dominated the Cortex-M4F's
    /// step, and the two Newton steps from a < 5·10⁻³ start are exact to f32 rounding.
    /// Deterministic, so a host `f32` run and the target stay bit-identical.
    #[inline(always)]
    pub(super) fn hertz(&self, delta: Real, rsqrt: &core::cell::Cell<Real>) -> Real {
        if !crate::real::SINGLE_PRECISION {
            return self.contact.load(delta);
        }
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
                1.0 / crate::real::sqrt(delta)
            };
            rsqrt.set(r);
            return self.contact.stiffness * delta * delta * r;
        }
        self.contact.load(delta)
    }

    /// Advances the state by one internal step; returns a sample every
    /// [`Model::oversample`] steps.
    #[inline]
    pub fn step<const NB: usize>(&self, st: &mut State<NB>) -> Option<Sample> {
        if !self.advance(st) {
            return None;
        }
        let vel_disp = if self.cfg.channels == Channels::All {
            (self.aa.output(&st.lines[1]), self.aa.output(&st.lines[2]))
        } else {
            (0.0, 0.0)
        };
        Some(self.sample(st, self.aa.output(&st.lines[0]), vel_disp))
    }

    /// The output sample from the anti-alias filter's outputs (acceleration, and velocity
    /// and displacement for [`Channels::All`]): the acceleration through the sensor chain,
    /// which keeps state, so samples must come here in their order.
    #[inline(always)]
    pub(super) fn sample<const NB: usize>(
        &self,
        st: &mut State<NB>,
        accel: Real,
        (vel, disp): (Real, Real),
    ) -> Sample {
        let accel = match &self.sensor_chain {
            Some(chain) => chain.apply(&mut st.sensor, accel),
            None => accel,
        };
        Sample { accel, vel, disp }
    }

    /// [`Model::step`] without the output: advances the state by one internal step and
    /// returns whether the step ends an output period (every [`Model::oversample`] steps),
    /// whose sample the caller takes from the delay lines ([`Model::step`], or
    /// `Model::fill`'s blocks).
    #[inline]
    pub(super) fn advance<const NB: usize>(&self, st: &mut State<NB>) -> bool {
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
        let f_end: Option<Real>;
        let (y1, v1, a0) = match self.cfg.integrator {
            IntegratorKind::Rk4 => {
                let k0 = self.kinematics(st, 0);
                let kh = self.kinematics(st, 1);
                let (k1, f) = self.kinematics_next(st, 2);
                f_end = f;
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
                let (k0, f) = self.kinematics_next(st, 0);
                f_end = f;
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
        self.advance_kinematics_to(st, f_end);
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
            return false;
        }
        st.phase = 0;
        true
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
            *rough = if sin_t > self.sin_skip - ROUGH_DRAW_MARGIN {
                sigma * st.rng.uniform_pm1()
            } else {
                0.0
            };
        }
    }

    /// Amplitude of the per-step roughness draw (m) at shaft speed `shaft_hz` with the
    /// debris of `topography` (see [`Roughness::step_sigma`]); constant-speed models cache it
    /// in the state, because its square root costs more than the draw on an M4F.
    pub(super) fn rough_sigma(&self, shaft_hz: Real, topography: Option<Topography>) -> Real {
        self.rough_sigma_from_root(topography, crate::real::sqrt(self.rough_ratio(shaft_hz)))
    }

    /// The ratio whose square root [`Model::rough_sigma`] takes ([`Roughness::step_ratio`]
    /// at the rolling speed of `shaft_hz`); 1 without roughness.
    pub(super) fn rough_ratio(&self, shaft_hz: Real) -> Real {
        let Some(r) = self.cfg.roughness else {
            return 1.0;
        };
        r.step_ratio(self.h, TAU * shaft_hz * self.orders.ftf * self.outer_radius)
    }

    /// [`Model::rough_sigma`] from the square root `root` of its [`Model::rough_ratio`] (the
    /// lanes take the roots of all lanes at once).
    pub(super) fn rough_sigma_from_root(&self, topography: Option<Topography>, root: Real) -> Real {
        let Some(r) = self.cfg.roughness else {
            return 0.0;
        };
        let debris = topography.map(|t| t.debris).unwrap_or(0.0);
        r.sigma_from_root(debris, root) * crate::real::SQRT_3 * self.rough_scale
    }

    /// Shaft frequency (Hz) at time `t` (s): the speed profile, modulated by the
    /// speed-fluctuation effect when it is on.
    #[inline(always)]
    pub(super) fn speed_hz(&self, t: Real) -> Real {
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
    pub(super) fn extra_force<const NB: usize>(&self, st: &State<NB>, k: &Kinematics) -> Real {
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
    pub(super) fn draw_summit<const NB: usize>(&self, st: &mut State<NB>) {
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
    pub(super) fn effects_step<const NB: usize>(&self, st: &mut State<NB>, a0: Real) -> Real {
        let a = match &self.transfer {
            Some(t) => t.filter(&mut st.path, a0),
            None => a0,
        };
        self.running_in_step(st);
        a
    }

    /// Running-in's per-step work: the revolutions rolled and, every 256 steps, the
    /// roughness scale (part of [`Model::effects_step`]; the lanes call it on its own, as
    /// they filter the transfer path for all lanes at once).
    #[inline(always)]
    pub(super) fn running_in_step<const NB: usize>(&self, st: &mut State<NB>) {
        if let Some(p) = self.cfg.effects.running_in {
            st.revs += st.shaft_hz * self.h;
            if st.steps.is_multiple_of(256) {
                st.run_in = p.scale(st.revs);
                st.rough_sigma = self.rough_sigma(st.shaft_hz, st.topography) * st.run_in;
            }
        }
    }

    /// Moves time, angles and phasors one step on; `f_end` is the shaft rate at the new
    /// time (Hz) when it is already known ([`Model::kinematics_next`] evaluated the
    /// profile at the same `time + h`), else (`None`) the profile is evaluated here.
    #[inline(always)]
    pub(super) fn advance_kinematics_to<const NB: usize>(
        &self,
        st: &mut State<NB>,
        f_end: Option<Real>,
    ) {
        let f0 = st.shaft_hz;
        st.time += self.h;
        let (f1, ds) = match self.rot {
            Some(_) => (f0, TAU * f0 * self.h),
            None => {
                let f1 = match f_end {
                    Some(f) => f,
                    None => self.speed_hz(st.time),
                };
                (f1, PI * (f0 + f1) * self.h)
            }
        };
        st.shaft_hz = f1;
        let dc = ds * self.orders.ftf;
        st.shaft_angle = advance_angle(st.shaft_angle, ds);
        st.cage_angle = advance_angle(st.cage_angle, dc);
        let dw = wrap_angle(dc * self.wave_order as Real);
        st.wave_angle = advance_angle(st.wave_angle, dw);
        if self.spin_order != 0.0 {
            st.spin_angle = advance_angle(st.spin_angle, ds * self.spin_order);
        }
        // The phasors follow the angles by rotations (renormalised), and are taken afresh
        // from the angles every 1024 steps so that rounding cannot accumulate: at a
        // constant speed by the precomputed rotations, at a varying speed by this step's
        // advances (small angles: `small_angle_cos_sin`'s polynomials, not libm).
        let fresh = st.steps.is_multiple_of(1024);
        match self.rot {
            Some(r) if !fresh => {
                st.shaft_cs = renorm(rotate(st.shaft_cs, r.shaft));
                st.cage_cs = renorm(rotate(st.cage_cs, r.cage));
                st.wave_cs = renorm(rotate(st.wave_cs, r.wave));
            }
            None if !fresh => {
                st.shaft_cs = renorm(rotate(st.shaft_cs, small_angle_cos_sin(ds)));
                st.cage_cs = renorm(rotate(st.cage_cs, small_angle_cos_sin(dc)));
                st.wave_cs = renorm(rotate(st.wave_cs, small_angle_cos_sin(dw)));
            }
            _ => {
                st.shaft_cs = (cos(st.shaft_angle), sin(st.shaft_angle));
                st.cage_cs = (cos(st.cage_angle), sin(st.cage_angle));
                st.wave_cs = (cos(st.wave_angle), sin(st.wave_angle));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::effects::speed_fluctuation::Params;
    use crate::error::ConfigError;
    use crate::real::{cos, sin, Real};
    use crate::speed::SpeedProfile;
    use crate::{presets, Model, State};

    /// At a varying speed (a ramp with a strong speed fluctuation) the phasors that the
    /// step rotates by its small-angle advances stay on the angles they stand for: within
    /// 1e-13 of `(cos θ, sin θ)` over 5 000 steps, i.e. across several fresh restarts every
    /// 1024 steps. In f32 up to 1024 roundings accumulate between restarts, as at a
    /// constant speed: within 1e-4 (3·10⁻⁵ measured, an angle error of 30 µrad).
    #[test]
    fn phasors_follow_the_angles_at_a_varying_speed() -> Result<(), ConfigError> {
        let Some(mut cfg) = presets::by_name("thesis-61810") else {
            return Err(ConfigError::Inconsistent {
                field: "preset",
                reason: "thesis-61810 is missing",
            });
        };
        cfg.speed = SpeedProfile::Ramp {
            from_hz: 10.0,
            to_hz: 40.0,
            duration: 0.05,
        };
        cfg.effects.speed_fluctuation = Some(Params {
            amplitude: 0.05,
            freq_hz: 30.0,
            jitter: 0.05,
            jitter_hz: 40.0,
        });
        let model = Model::new_checked(cfg)?;
        assert!(!model.constant_speed());
        let mut st: State<16> = State::new(&model, 3)?;
        let tol: Real = if core::mem::size_of::<Real>() == 4 {
            1e-4
        } else {
            1e-13
        };
        let mut worst: Real = 0.0;
        for _ in 0..5000 {
            model.step(&mut st);
            for (a, cs) in [
                (st.shaft_angle, st.shaft_cs),
                (st.cage_angle, st.cage_cs),
                (st.wave_angle, st.wave_cs),
            ] {
                worst = worst.max((cs.0 - cos(a)).abs()).max((cs.1 - sin(a)).abs());
            }
        }
        assert!(worst < tol, "largest phasor error {worst}");
        assert!(st.steps > 4096);
        Ok(())
    }
}
