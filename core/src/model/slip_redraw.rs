//! Element slip (publication III; `forces::slip`): each element's offset redrawn once per
//! pass, while it is opposite the defect, so that an offset never jumps on an impact. The
//! scalar step's bookkeeping and the part the lanes share (`lanes::step`).

use super::{rotate, Model, State};
use crate::forces::defect::DefectLocation;
use crate::real::Real;
use crate::rng::Xoshiro128pp;

/// Internal steps between two checks of the slip bookkeeping (scalar step and lanes).
pub(super) const SLIP_CHECK_EVERY: u64 = 8;

impl Model {
    /// Redraws an element's slip offset once per pass, while it is opposite the defect.
    #[inline(always)]
    pub(super) fn update_slip<const NB: usize>(&self, st: &mut State<NB>) {
        let Some(slip) = self.cfg.slip else {
            return;
        };
        // A pass is detected by the element entering the far half-plane; checking every
        // 8th step is ample (8 steps move the cage less than the 120° arming region even at
        // the highest speed and coarsest step) and saves most of the bookkeeping.
        if !st.steps.is_multiple_of(SLIP_CHECK_EVERY) {
            return;
        }
        let Some((arm, far)) = self.slip_regions(st.shaft_cs, st.cage_cs) else {
            return;
        };
        let n = self.cfg.bearing.elements;
        st.armed = redraw_slips(&slip, &mut st.rng, &mut st.slip, n, st.armed, (arm, far));
    }

    /// The elements (one bit each, element `i` at bit `i`) in the arming region opposite
    /// the defect's far side (`cos_rel > 0.5`) and in the far half-plane (`cos_rel < −0.5`),
    /// at shaft and cage angles `shaft_cs`, `cage_cs` (cos, sin); `None` without a defect.
    /// A ball defect travels with its element: its offset is redrawn once per cage turn,
    /// when the element is opposite the load-zone centre (unloaded), so that the jump in
    /// its spin phase never falls on an impact. Shared by the scalar step and the lanes
    /// (`lanes::step`), which decide it once for lanes with the same kinematics.
    #[inline(always)]
    pub(super) fn slip_regions(
        &self,
        shaft_cs: (Real, Real),
        cage_cs: (Real, Real),
    ) -> Option<(u32, u32)> {
        let d = self.cfg.defect?;
        let (dc, ds) = match d.location {
            DefectLocation::InnerRace { .. } => rotate(shaft_cs, self.defect_offset_cs),
            DefectLocation::Ball { .. } => (0.0, 1.0),
            DefectLocation::OuterRace { .. } => self.defect_offset_cs,
        };
        let (cc, sc) = cage_cs;
        let n = self.cfg.bearing.elements as usize;
        // Iterators instead of indexing keep this per-step loop free of bounds checks (it is
        // a sixth of the step on a Cortex-M4F); the arithmetic is unchanged.
        let (mut arm, mut far) = (0u32, 0u32);
        let mut bit = 1u32;
        for (ce, se) in self.elem_cs.get(..n).unwrap_or(&[]) {
            let cos_rel = (cc * ce - sc * se) * dc + (sc * ce + cc * se) * ds;
            if cos_rel > 0.5 {
                arm |= bit;
            } else if cos_rel < -0.5 {
                far |= bit;
            }
            bit = bit.rotate_left(1);
        }
        Some((arm, far))
    }
}

/// Slip bookkeeping of one model with `n` elements: the armed elements that entered the
/// far half-plane (`regions` from [`Model::slip_regions`]: arming, far) redraw their slip
/// offsets (rad) from `rng` in element order and disarm; elements in the arming region
/// arm. Returns the new armed bits.
#[inline(always)]
pub(super) fn redraw_slips(
    slip: &crate::forces::slip::Slip,
    rng: &mut Xoshiro128pp,
    offsets: &mut [Real],
    n: u8,
    armed: u32,
    (arm, far): (u32, u32),
) -> u32 {
    let fire = armed & far;
    if fire != 0 {
        let mut bit = 1u32;
        for s in offsets.iter_mut().take(n as usize) {
            if fire & bit != 0 {
                *s = slip.draw(rng, n);
            }
            bit = bit.rotate_left(1);
        }
    }
    (armed | arm) & !fire
}
