//! Per-pass contact loads measured from the dynamic model: the largest element load in
//! each pass interval of the wear [`Site`], and the largest load of an element over the
//! defect, accumulated as power sums so that the wear laws get the right means without
//! storing the passes. A pass of the site is:
//!
//! * outer race: an element pitch `2π/N` of cage rotation (an element passing a point of
//!   the stationary race), BPFO per shaft revolution;
//! * inner race: an element pitch of shaft rotation relative to the cage, `θ_shaft −
//!   θ_cage`, BPFI per shaft revolution;
//! * element: half a spin turn of the element, `φ_spin = (θ_shaft − θ_cage)(P − B_d cos
//!   φ)/B_d` (a point on it meets the outer, then the inner race), 2·BSF per revolution.

use super::life::PassLoads;
use super::site::Site;
use crate::bearing::{BearingGeometry, ContactKind};
use crate::model::StepStats;
use crate::real::{floor, pow, Real, PI, TAU};

/// Accumulates per-pass peak loads from [`StepStats`] (fixed size, no allocation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PassMeter {
    site: Site,
    /// Passes per turn of the site angle (N for a race, 2 for an element).
    elements: Real,
    /// Element spin per radian of shaft rotation relative to the cage (element site).
    spin_ratio: Real,
    /// Last shaft − cage angle (rad, element site) and the unwrapped spin angle (rad).
    last_relative: Real,
    spin: Real,
    exponent: Real,
    slot: i64,
    started: bool,
    zone_peak: Real,
    edge_peak: Real,
    passes: u32,
    zone_sum_p: Real,
    zone_sum: Real,
    edge_passes: u32,
    edge_sum: Real,
    edge_sum3: Real,
}

impl PassMeter {
    /// A meter of the passes over `site` of `bearing`, with the Lundberg–Palmgren exponent
    /// of its contact (3 balls, 10/3 rollers) for the zone mean.
    pub fn new(site: Site, bearing: &BearingGeometry) -> Self {
        PassMeter {
            site,
            elements: site.passes_per_turn(bearing),
            spin_ratio: Site::spin_ratio(bearing),
            last_relative: 0.0,
            spin: 0.0,
            exponent: match bearing.contact {
                ContactKind::Point => 3.0,
                ContactKind::Line => 10.0 / 3.0,
            },
            slot: 0,
            started: false,
            zone_peak: 0.0,
            edge_peak: 0.0,
            passes: 0,
            zone_sum_p: 0.0,
            zone_sum: 0.0,
            edge_passes: 0,
            edge_sum: 0.0,
            edge_sum3: 0.0,
        }
    }

    /// The site measured.
    pub fn site(&self) -> Site {
        self.site
    }

    /// Feeds one internal step: its contact figures and the shaft and cage angles (rad,
    /// wrapped to [0, 2π) as `State` gives them) after it.
    #[inline]
    pub fn observe(&mut self, stats: StepStats, shaft_angle: Real, cage_angle: Real) {
        let slot = match self.site {
            Site::OuterRace => floor(cage_angle * self.elements / TAU) as i64,
            Site::InnerRace => {
                let mut rel = shaft_angle - cage_angle;
                if rel < 0.0 {
                    rel += TAU;
                }
                floor(rel * self.elements / TAU) as i64
            }
            Site::Element => {
                // The spin angle is a non-integer multiple of the relative angle, so it is
                // unwrapped here: each step adds its relative advance (|Δ| < π per step).
                let rel = shaft_angle - cage_angle;
                if self.started {
                    let mut d = rel - self.last_relative;
                    if d > PI {
                        d -= TAU;
                    } else if d < -PI {
                        d += TAU;
                    }
                    self.spin += d * self.spin_ratio;
                }
                self.last_relative = rel;
                floor(self.spin * self.elements / TAU) as i64
            }
        };
        if !self.started {
            self.started = true;
            self.slot = slot;
        } else if slot != self.slot {
            self.slot = slot;
            self.close_pass();
        }
        if stats.max_load > self.zone_peak {
            self.zone_peak = stats.max_load;
        }
        if stats.defect_load > self.edge_peak {
            self.edge_peak = stats.defect_load;
        }
    }

    fn close_pass(&mut self) {
        if self.zone_peak > 0.0 {
            self.passes += 1;
            self.zone_sum += self.zone_peak;
            self.zone_sum_p += pow(self.zone_peak, self.exponent);
        }
        if self.edge_peak > 0.0 {
            self.edge_passes += 1;
            self.edge_sum += self.edge_peak;
            self.edge_sum3 += self.edge_peak * self.edge_peak * self.edge_peak;
        }
        self.zone_peak = 0.0;
        self.edge_peak = 0.0;
    }

    /// Number of completed passes with a loaded element.
    pub fn passes(&self) -> u32 {
        self.passes
    }

    /// The measured loads (means over completed passes; zeros when none).
    pub fn loads(&self) -> PassLoads {
        let n = self.passes as Real;
        let ne = self.edge_passes as Real;
        PassLoads {
            zone: if n > 0.0 {
                pow(self.zone_sum_p / n, 1.0 / self.exponent)
            } else {
                0.0
            },
            zone_mean: if n > 0.0 { self.zone_sum / n } else { 0.0 },
            edge: if ne > 0.0 { self.edge_sum / ne } else { 0.0 },
            edge_cubic: if ne > 0.0 {
                pow(self.edge_sum3 / ne, 1.0 / 3.0)
            } else {
                0.0
            },
            passes: self.passes,
        }
    }
}
