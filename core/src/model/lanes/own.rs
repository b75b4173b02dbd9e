//! Lanes that move at their own speed (their own speed profile or speed fluctuation, as the
//! fits of a speed fluctuation and sweeps over speeds have): each lane computes its own
//! kinematics, its elements' `sin θ`, `cos θ` and its defect phasor, and the element loop
//! takes its decisions — draw a roughness height, element in contact, element in the
//! defect window — lane by lane, as lane `i`'s scalar step takes them. The per-lane
//! arithmetic is the scalar step's in the same order (`super::step` shares its pieces), so
//! every lane keeps [`super::super::Model::step`]'s bits. Groups whose lanes share the
//! kinematics take the cheaper path of `super::step`, which computes them once.

use super::super::{StepStats, ROUGH_DRAW_MARGIN};
use super::hertz::{packed_hertz, set_loads, settle_load};
use super::step::{add_inside, defect_terms, element_tables, SqrtLanes};
use super::LaneGroup;
use crate::forces::Kinematics;
use crate::real::Real;
use crate::rng::uniform_pm1_where;

/// Each lane's kinematics at the start of the step and, for a varying speed, its shaft
/// rate at the end of the step (Hz; see `Model::kinematics_next`).
pub(super) type OwnKinematics<const K: usize> = [(Kinematics, Option<Real>); K];

impl<const K: usize, const NB: usize> LaneGroup<'_, K, NB> {
    /// Every lane's [`OwnKinematics`] from its own state (`first`: lane 0's, already
    /// computed).
    pub(super) fn own_kinematics(&self, first: (Kinematics, Option<Real>)) -> OwnKinematics<K> {
        core::array::from_fn(|l| match (l, self.models.get(l), self.states.get(l)) {
            (1.., Some(m), Some(st)) => m.kinematics_next(st, 0),
            _ => first,
        })
    }

    /// Moves every lane's time, angles and phasors on by its own speed and counts the step
    /// (the end-of-step shaft rates `own` computed are reused, as the scalar step does).
    pub(super) fn advance_own_kinematics(&mut self, own: &OwnKinematics<K>) {
        for ((m, st), (_, f_end)) in self.models.iter().zip(self.states.iter_mut()).zip(own) {
            m.advance_kinematics_to(st, *f_end);
            st.steps += 1;
        }
    }

    /// Hertz element forces of every lane (N) with each lane's own kinematics `own`: the
    /// scalar `element_forces` per lane, the Hertz loads and the sums in loops over the
    /// lanes. An element is skipped only when it is out of contact in every lane.
    #[inline(always)]
    pub(super) fn element_forces_own<S: SqrtLanes<K>>(
        &mut self,
        own: &OwnKinematics<K>,
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
        let location = m0.cfg.defect.map(|d| d.location);
        let is_ball = location.is_some_and(|l| l.is_ball());
        // Per lane: cage and waviness phasors, and the defect phasor.
        let cage = own.each_ref().map(|(k, _)| k.cage_cs);
        let wave = own.each_ref().map(|(k, _)| k.wave_cs);
        let dcs: [(Real, Real); K] = core::array::from_fn(|l| match (own.get(l), models.get(l)) {
            (Some((k, _)), Some(m)) => m.defect_phasor(k),
            _ => (0.0, 0.0),
        });
        let ball: [(Real, Real, Real); K] = core::array::from_fn(|l| {
            match (models.get(l), self.states.get(l), own.get(l), dcs.get(l)) {
                (Some(m), Some(st), Some((k, _)), Some(dc)) => match m.cfg.defect {
                    Some(d) if is_ball && m.ball_in_use(st, k, d, *dc, sin_skip) => {
                        m.ball_defect(st, k, d)
                    }
                    _ => (0.0, 0.0, 0.0),
                },
                _ => (0.0, 0.0, 0.0),
            }
        });
        let rough_on = m0.cfg.roughness.is_some();
        let sigma = if rough_on {
            self.rough_sigmas(sqrt)
        } else {
            [0.0; K]
        };
        let window_cos = self.states.each_ref().map(|s| s.window_cos);
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
            let mut sin_t = [0.0; K];
            for (s, (cc, sc)) in sin_t.iter_mut().zip(&cage) {
                *s = sc * ce + cc * se;
            }
            let mut rough = [0.0; K];
            if rough_on {
                let draw = sin_t.map(|s| s > sin_skip - ROUGH_DRAW_MARGIN);
                if draw.iter().any(|d| *d) {
                    let u = uniform_pm1_where(&mut rng, &draw);
                    for (((r, s), ui), d) in rough.iter_mut().zip(&sigma).zip(&u).zip(&draw) {
                        *r = if *d { *s * *ui } else { 0.0 };
                    }
                }
            }
            let active = sin_t.map(|s| s > sin_skip);
            if !active.iter().any(|a| *a) {
                continue;
            }
            let (cwe, swe) = *wcs;
            let mut delta = [0.0; K];
            for (((((d, yl), g), r), wa), (st_, (cw, sw))) in delta
                .iter_mut()
                .zip(&y)
                .zip(&c.gamma)
                .zip(&rough)
                .zip(&c.wave_amp)
                .zip(sin_t.iter().zip(&wave))
            {
                let x = *yl * *st_ - *g - *r;
                *d = if *wa != 0.0 {
                    x - *wa * (sw * cwe + cw * swe)
                } else {
                    x
                };
            }
            let mut unload = [0.0; K];
            let mut add = [0.0; K];
            if location.is_some() {
                // In the defect's window (the scalar step's test, lane by lane).
                let mut inside = [false; K];
                for (((((w, on), s), (cc, sc)), (dc, ds)), wc) in inside
                    .iter_mut()
                    .zip(&active)
                    .zip(&sin_t)
                    .zip(&cage)
                    .zip(&dcs)
                    .zip(&window_cos)
                {
                    let cos_t = cc * ce - sc * se;
                    let cos_rel = cos_t * dc + s * ds;
                    *w = *on & (cos_rel > *wc);
                }
                if inside.iter().any(|w| *w) {
                    let mut dd = [0.0; K];
                    for l in 0..K {
                        let (Some(m), Some(st), Some((k, _)), Some(w)) = (
                            models.get(l),
                            self.states.get(l),
                            own.get(l),
                            inside.get_mut(l),
                        ) else {
                            continue;
                        };
                        if !*w {
                            continue;
                        }
                        let bt = ball.get(l).copied().unwrap_or_default();
                        match (
                            defect_terms(m, st, k, e, *elem_angle, is_ball, bt),
                            unload.get_mut(l),
                            dd.get_mut(l),
                            add.get_mut(l),
                        ) {
                            (Some((u, d, a)), Some(ul), Some(dl), Some(al)) => {
                                (*ul, *dl, *al) = (u, d, a);
                            }
                            _ => *w = false,
                        }
                    }
                    if c.zone_any {
                        c.zone_scale(&sin_t, &inside, [&mut unload, &mut dd, &mut add], sqrt);
                    }
                    add_inside(&mut delta, &dd, &inside);
                }
            }
            let mut q = self.hertz_loads(&delta, e, &active, fast_hertz, sqrt);
            // A lane out of contact adds a zero load (its unload and add are zero): the
            // largest loads keep their values and `fy − 0·sin θ` is `fy` (never −0 here), so
            // the sums equal skipping the element in that lane, without a branch per lane.
            for (qi, on) in q.iter_mut().zip(&active) {
                *qi = if *on { *qi } else { 0.0 };
            }
            for ((((((ql, ul), al), ml), dl), fl), s) in q
                .iter()
                .zip(&unload)
                .zip(&add)
                .zip(max_load.iter_mut())
                .zip(defect_load.iter_mut())
                .zip(fy.iter_mut())
                .zip(&sin_t)
            {
                *fl -= settle_load(*ql, *ul, *al, ml, dl) * *s;
            }
        }
        self.rng = rng;
        set_loads(stats, max_load, defect_load);
        fy
    }
}
