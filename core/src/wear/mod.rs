//! Wear evolution over the whole life (thesis §4.2, publication III §2.3–2.4 and its
//! Fig. 3 flowchart; model.md §6–§7).
//!
//! The dynamic model's own contact loads, measured per element pass over the wear
//! [`site::Site`] (outer race at BPFO, inner race at BPFI, rolling element at 2·BSF) by
//! [`pass_meter::PassMeter`], are turned into Hertz pressures with the site's contact and
//! accumulated by the stage machine in [`life`]; no transition is scheduled by time:
//!
//! * running-in → steady state: the composite roughness wears down to its steady value
//!   (abrasion per pass, faster at low λ);
//! * steady state → dent: rolling-contact fatigue damage `Σ (P/C)^p` per revolution
//!   (Lundberg–Palmgren / ISO 281) reaches the denting limit (the thesis's yield limit,
//!   Harris), where `P` comes from the measured pass loads;
//! * dent → crack opening: the asperity-induced stress at the dent's trailing edge
//!   (Hannes & Alfredsson 2011: a shoulder of height h concentrates the contact pressure)
//!   accumulates fatigue damage until it reaches 1 and the mode-I stress-intensity factor
//!   of the flaw exceeds its threshold;
//! * crack propagation: `da/dN = C₀ δ_pl^{m₀}` with `δ_pl = ΔK²/(2Eσ_y)` (thesis eq. 26–27,
//!   Navarro & Rios 1988, Sun et al. 1991), summed pass by pass up to the spall depth;
//! * defect completion and growth: each completed crack breaks out a spall segment; the
//!   trailing edge starts the next crack; the defect grows 0.3 → 1 → 3 mm;
//! * defect smoothing and damage growth: at the completed size, smoothing lowers the edge
//!   asperity while stress still accumulates; each time it reaches the propagation limit a
//!   new defect is spawned; failure when the spawned defects reach the failure count.
//!
//! Smoothing competes all the time: over-rolling (Sahoo & Banerjee 2005, eq. 24) and mild
//! abrasion (Masen et al. 2005) remove asperity height while λ says asperities interact.

pub mod events;
pub mod life;
pub mod material;
pub mod pass_meter;
pub mod rating;
pub mod site;
pub mod stages;

pub use events::{Event, EventLog, MAX_EVENTS};
pub use life::{Life, LifeConfig, LifeState, PassLoads};
pub use material::Material;
pub use pass_meter::PassMeter;
pub use rating::RingRatings;
pub use site::Site;
pub use stages::Stage;
