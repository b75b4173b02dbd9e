//! The lanes' Hertz contact loads (`Q = K·δ^p`, thesis eq. 4–10 after Harsha et al.;
//! `p` = 3/2 for point contacts): the loads of one element in every lane, with the scalar
//! step's unloading, additive force and contact figures, and the same bits as
//! [`super::super::Model::step`]'s.

use super::super::{Model, StepStats};
use super::step::SqrtLanes;
use super::LaneGroup;
use crate::real::Real;

/// `x^{3/2}` per lane (`x·√x` for `x > 0`, else 0), as [`crate::real::pow_3_2`], with
/// the square roots taken by `sqrt`.
#[inline(always)]
pub(super) fn pow_3_2_lanes<const K: usize, S: SqrtLanes<K>>(x: &[Real; K], sqrt: &S) -> [Real; K] {
    let mut s = [0.0; K];
    for (si, xi) in s.iter_mut().zip(x) {
        *si = if *xi > 0.0 { *xi } else { 0.0 };
    }
    sqrt.sqrt_lanes(&mut s);
    let mut out = [0.0; K];
    for ((o, xi), si) in out.iter_mut().zip(x).zip(&s) {
        *o = if *xi > 0.0 { *xi * *si } else { 0.0 };
    }
    out
}

/// An element's Hertz load `q` (N) after the defect's unloading `unload` and additive force
/// `add`, with the step's largest load `max_load` and defect load `defect_load` updated:
/// the scalar step's conditionals in branch-free form (same values). Returns the load that
/// pushes the shaft (`q·(1 − unload) + add`).
#[inline(always)]
pub(super) fn settle_load(
    q: Real,
    unload: Real,
    add: Real,
    max_load: &mut Real,
    defect_load: &mut Real,
) -> Real {
    let keep = if unload < 1.0 { 1.0 - unload } else { 0.0 };
    let qv = if unload > 0.0 { q * keep } else { q };
    *max_load = if qv > *max_load { qv } else { *max_load };
    let qa = qv + add;
    // `&`/`|` on the conditions (no short circuit): the scalar step's decision without
    // branches.
    let on = (unload > 0.0) | (add != 0.0);
    *defect_load = if on & (qa > *defect_load) {
        qa
    } else {
        *defect_load
    };
    qa
}

/// Whether the lanes' Hertz loads take their roots packed: `f64` point contacts (else each
/// lane's [`Model::hertz`], whose `f32` point contacts keep a cached inverse root).
#[inline(always)]
pub(super) fn packed_hertz(m0: &Model) -> bool {
    !crate::real::SINGLE_PRECISION && m0.contact.kind == crate::bearing::ContactKind::Point
}

/// The step's largest element load and defect load per lane into the lanes' contact
/// figures (N).
#[inline(always)]
pub(super) fn set_loads<const K: usize>(
    stats: &mut [StepStats; K],
    max_load: [Real; K],
    defect_load: [Real; K],
) {
    for ((s, m), d) in stats.iter_mut().zip(max_load).zip(defect_load) {
        s.max_load = m;
        s.defect_load = d;
    }
}

impl<const K: usize, const NB: usize> LaneGroup<'_, K, NB> {
    /// The Hertz loads (N) of element `e` at the deflections `delta` (m) in the lanes that
    /// are `on` (0 in the others): with the roots packed where `packed` ([`packed_hertz`]),
    /// else by each lane's [`Model::hertz`], whose cached inverse root of `f32` builds
    /// moves only where the scalar step evaluates the load.
    #[inline(always)]
    pub(super) fn hertz_loads<S: SqrtLanes<K>>(
        &self,
        delta: &[Real; K],
        e: usize,
        on: &[bool; K],
        packed: bool,
        sqrt: &S,
    ) -> [Real; K] {
        let mut q = [0.0; K];
        if packed {
            let p = pow_3_2_lanes(delta, sqrt);
            for ((qi, s), pi) in q.iter_mut().zip(&self.c.stiffness).zip(&p) {
                *qi = *s * *pi;
            }
        } else {
            for ((((qi, dl), m), st), on) in q
                .iter_mut()
                .zip(delta)
                .zip(self.models)
                .zip(&self.states)
                .zip(on)
            {
                if let (true, Some(cell)) = (*on, st.rsqrt.get(e)) {
                    *qi = m.hertz(*dl, cell);
                }
            }
        }
        q
    }
}
