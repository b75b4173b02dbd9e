//! JSON form of the core's wear state (for dense-mode checkpoints and the event log).

use serde::{Deserialize, Serialize};
use wearsim_core::topography::Topography;
use wearsim_core::wear::{Event, EventLog, LifeState, Stage};

/// A topography in JSON (m).
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq)]
pub struct TopographyJson {
    /// Asperity height (m).
    pub asperity_height: f64,
    /// Length (m).
    pub length: f64,
    /// Width (m).
    pub width: f64,
    /// Depth (m).
    pub depth: f64,
    /// Count.
    pub count: u8,
    /// Debris (–).
    pub debris: f64,
}

impl From<Topography> for TopographyJson {
    fn from(t: Topography) -> Self {
        TopographyJson {
            asperity_height: t.asperity_height,
            length: t.length,
            width: t.width,
            depth: t.depth,
            count: t.count,
            debris: t.debris,
        }
    }
}

impl From<TopographyJson> for Topography {
    fn from(t: TopographyJson) -> Self {
        Topography {
            asperity_height: t.asperity_height,
            length: t.length,
            width: t.width,
            depth: t.depth,
            count: t.count,
            debris: t.debris,
        }
    }
}

/// One event in JSON.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct EventJson {
    /// Stage entered (kebab-case name).
    pub stage: String,
    /// Revolutions.
    pub cycles: f64,
    /// Topography then.
    pub topography: TopographyJson,
    /// Crack depth then (m).
    pub crack: f64,
}

impl From<&Event> for EventJson {
    fn from(e: &Event) -> Self {
        EventJson {
            stage: e.stage.name().into(),
            cycles: e.cycles,
            topography: e.topography.into(),
            crack: e.crack,
        }
    }
}

/// The whole wear state in JSON.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct LifeStateJson {
    /// Revolutions.
    pub cycles: f64,
    /// Stage name.
    pub stage: String,
    /// Topography.
    pub topography: Option<TopographyJson>,
    /// Roughness (m).
    pub roughness: f64,
    /// Fatigue damage.
    pub fatigue: f64,
    /// Surface damage (dent at `dent_fraction`).
    pub surface: f64,
    /// Initiation / propagation accumulator.
    pub initiation: f64,
    /// Crack depth (m).
    pub crack: f64,
    /// Crack start depth (m).
    pub crack_start: f64,
    /// Dent asperity at formation (m).
    pub dent_asperity: f64,
    /// Smoothing floor (m).
    pub asperity_floor: f64,
    /// Debris.
    pub debris: f64,
    /// Fatigue-life Weibull scatter.
    pub scatter: f64,
    /// Spall-propagation Weibull scatter.
    pub propagation_scatter: f64,
    /// Surface-initiation (dent crack) Weibull scatter.
    pub initiation_scatter: f64,
    /// Surface-damage (dent) Weibull scatter.
    pub dent_scatter: f64,
    /// Events.
    pub events: Vec<EventJson>,
    /// Events that did not fit the log.
    pub lost_events: u16,
}

fn stage_of(name: &str) -> Option<Stage> {
    Stage::ALL.iter().copied().find(|s| s.name() == name)
}

impl From<&LifeState> for LifeStateJson {
    fn from(s: &LifeState) -> Self {
        LifeStateJson {
            cycles: s.cycles,
            stage: s.stage.name().into(),
            topography: s.topography.map(Into::into),
            roughness: s.roughness,
            fatigue: s.fatigue,
            surface: s.surface,
            initiation: s.initiation,
            crack: s.crack,
            crack_start: s.crack_start,
            dent_asperity: s.dent_asperity,
            asperity_floor: s.asperity_floor,
            debris: s.debris,
            scatter: s.scatter,
            propagation_scatter: s.propagation_scatter,
            initiation_scatter: s.initiation_scatter,
            dent_scatter: s.dent_scatter,
            events: s.events.iter().map(Into::into).collect(),
            lost_events: s.lost_events,
        }
    }
}

impl LifeStateJson {
    /// Back to the core's state; `None` if a stage name is unknown or a scatter factor is
    /// not a positive finite number (corrupt checkpoint: the wear rates divide by them).
    pub fn to_state(&self) -> Option<LifeState> {
        let factor_ok = |v: f64| v.is_finite() && v > 0.0;
        if !factor_ok(self.scatter)
            || !factor_ok(self.propagation_scatter)
            || !factor_ok(self.initiation_scatter)
            || !factor_ok(self.dent_scatter)
        {
            return None;
        }
        let mut events = EventLog::new();
        for e in &self.events {
            let ev = Event {
                stage: stage_of(&e.stage)?,
                cycles: e.cycles,
                topography: e.topography.into(),
                crack: e.crack,
            };
            events.push(ev).ok()?;
        }
        Some(LifeState {
            cycles: self.cycles,
            stage: stage_of(&self.stage)?,
            topography: self.topography.map(Into::into),
            roughness: self.roughness,
            fatigue: self.fatigue,
            surface: self.surface,
            initiation: self.initiation,
            crack: self.crack,
            crack_start: self.crack_start,
            dent_asperity: self.dent_asperity,
            asperity_floor: self.asperity_floor,
            debris: self.debris,
            scatter: self.scatter,
            propagation_scatter: self.propagation_scatter,
            initiation_scatter: self.initiation_scatter,
            dent_scatter: self.dent_scatter,
            events,
            lost_events: self.lost_events,
        })
    }
}
