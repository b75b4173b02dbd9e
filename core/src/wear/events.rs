//! The bounded log of stage transitions.

use super::stages::Stage;
use crate::real::Real;
use crate::topography::Topography;

/// Capacity of the event log: one entry per stage plus spawned defects.
pub const MAX_EVENTS: usize = 24;

/// A stage transition with the moment it happened.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Event {
    /// Stage entered.
    pub stage: Stage,
    /// Shaft revolutions at the transition.
    pub cycles: Real,
    /// Topography at that moment.
    pub topography: Topography,
    /// Crack depth at that moment (m).
    pub crack: Real,
}

/// Fixed-capacity event log (`heapless`); when full, further events are counted but not
/// stored.
pub type EventLog = heapless::Vec<Event, MAX_EVENTS>;
