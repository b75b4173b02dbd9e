//! Where the wear happens: the surface whose life is computed — a point of the outer race,
//! a point of the inner race or a point on a rolling element. Each site is over-rolled at
//! its own rate and carries its own Hertz contact:
//!
//! * outer race (stationary): one pass per element, `BPFO/f_r = N/2 (1 − B_d/P cos φ)`
//!   passes per shaft revolution (thesis eq. 18), outer-race contact;
//! * inner race (rotating): one pass per element per turn of the shaft relative to the cage,
//!   `BPFI/f_r = N/2 (1 + B_d/P cos φ)` (thesis eq. 19), inner-race contact — the convex
//!   track curvature gives it the smaller contact and the higher pressure (Harris &
//!   Kotzalas 2007, *Essential Concepts of Bearing Technology* §6);
//! * rolling element: a point of the element surface meets the outer race once and the
//!   inner race once per spin revolution, `2·BSF/f_r` passes (thesis eq. 20 for BSF; the
//!   factor 2: Randall & Antoni 2011, MSSP 25 §2.1, "ball faults strike both races");
//!   of its two contacts the more heavily stressed one governs its fatigue, chosen by the
//!   larger Hertz pressure at the reference load — the inner contact for a ball or roller
//!   bearing (Harris & Kotzalas 2007 §6: the inner contact has the smaller conformity /
//!   equivalent radius and the higher pressure).

use crate::bearing::BearingGeometry;
use crate::contact::{ElementContact, HertzContact};
use crate::forces::defect::DefectLocation;
use crate::kinematics::{FaultFrequencies, FaultOrders};
use crate::real::Real;

/// The surface whose wear life is computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Site {
    /// A point of the stationary outer race (the default: the life's defect preset).
    #[default]
    OuterRace,
    /// A point of the rotating inner race.
    InnerRace,
    /// A point on a rolling element's surface.
    Element,
}

impl Site {
    /// The site of a defect at `location`; no defect means the outer race (the wear life
    /// then places its defect with [`crate::presets::outer_race_defect`]).
    pub fn of(location: Option<&DefectLocation>) -> Site {
        match location {
            None | Some(DefectLocation::OuterRace { .. }) => Site::OuterRace,
            Some(DefectLocation::InnerRace { .. }) => Site::InnerRace,
            Some(DefectLocation::Ball { .. }) => Site::Element,
        }
    }

    /// Short name for output: `outer_race`, `inner_race`, `element`.
    pub fn name(self) -> &'static str {
        match self {
            Site::OuterRace => "outer_race",
            Site::InnerRace => "inner_race",
            Site::Element => "element",
        }
    }

    /// Name of the pass frequency: `BPFO`, `BPFI`, `2BSF`.
    pub fn pass_frequency_name(self) -> &'static str {
        match self {
            Site::OuterRace => "BPFO",
            Site::InnerRace => "BPFI",
            Site::Element => "2BSF",
        }
    }

    /// Passes over the site per shaft revolution (–): BPFO, BPFI or 2·BSF over `f_r`
    /// (thesis eq. 18–20; factor 2 of the element: Randall & Antoni 2011 §2.1).
    pub fn passes_per_rev(self, orders: &FaultOrders) -> Real {
        match self {
            Site::OuterRace => orders.bpfo,
            Site::InnerRace => orders.bpfi,
            Site::Element => 2.0 * orders.bsf,
        }
    }

    /// The site's pass frequency (Hz) among the bearing's frequencies `ff`: BPFO, BPFI or
    /// 2·BSF (where a defect on the site shows in the envelope spectrum).
    pub fn pass_frequency_hz(self, ff: &FaultFrequencies) -> Real {
        match self {
            Site::OuterRace => ff.bpfo,
            Site::InnerRace => ff.bpfi,
            Site::Element => 2.0 * ff.bsf,
        }
    }

    /// The Hertz contact of the site: outer → outer, inner → inner, element → whichever of
    /// its two contacts has the larger maximum pressure at `load` (N) (the inner one for
    /// ball and roller bearings; Harris & Kotzalas 2007 §6).
    pub fn contact(self, contact: &ElementContact, load: Real) -> HertzContact {
        match self {
            Site::OuterRace => contact.outer,
            Site::InnerRace => contact.inner,
            Site::Element => {
                if contact.inner.max_pressure(load) >= contact.outer.max_pressure(load) {
                    contact.inner
                } else {
                    contact.outer
                }
            }
        }
    }

    /// Passes per turn of the site's reference angle (see [`Site::spin_ratio`]): one per
    /// element for a race (`N`), two for an element (one per race per spin turn).
    pub fn passes_per_turn(self, bearing: &BearingGeometry) -> Real {
        match self {
            Site::OuterRace | Site::InnerRace => bearing.elements as Real,
            Site::Element => 2.0,
        }
    }

    /// Element spin angle per radian of shaft rotation relative to the cage (–):
    /// `(P − B_d cos φ)/B_d`, so that `φ_spin = (θ_shaft − θ_cage)(P − B_d cos φ)/B_d =
    /// BSF·θ_shaft` without slip (see `crate::forces::defect`, Harris 1966).
    pub fn spin_ratio(bearing: &BearingGeometry) -> Real {
        bearing.pitch_diameter * (1.0 - bearing.diameter_ratio()) / bearing.element_diameter
    }
}
