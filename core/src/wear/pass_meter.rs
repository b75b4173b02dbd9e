//! Per-pass contact loads measured from the dynamic model: the largest element load in
//! each element-pitch interval of cage rotation (one element passing a point of the outer
//! race), and the largest load of an element over the defect, accumulated as power sums
//! so that the wear laws get the right means without storing the passes.

use super::life::PassLoads;
use crate::model::StepStats;
use crate::real::{floor, pow, Real, TAU};

/// Accumulates per-pass peak loads from [`StepStats`] (fixed size, no allocation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PassMeter {
    elements: Real,
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
    /// A meter for a bearing with `elements` elements and Lundberg–Palmgren exponent
    /// `exponent` (3 balls, 10/3 rollers) for the zone mean.
    pub fn new(elements: u8, exponent: Real) -> Self {
        PassMeter {
            elements: elements as Real,
            exponent,
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

    /// Feeds one internal step: its contact figures and the cage angle (rad) after it.
    #[inline]
    pub fn observe(&mut self, stats: StepStats, cage_angle: Real) {
        let slot = floor(cage_angle * self.elements / TAU) as i64;
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
