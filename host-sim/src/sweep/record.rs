//! One record of a sweep: its grid cell (the labels), its drawn effect parameters and its
//! seed, all a pure function of the specification and the record number, so that any
//! record (and so any shard) can be regenerated alone.

use super::spec::{Dist, DistTable, SweepSpec};
use crate::config::{DefectSection, ScenarioFile, SpeedSection};
use crate::effects::EffectSection;

/// SplitMix64 (Steele, Lea & Flood 2014): the seed-derivation mixer.
pub fn splitmix64(x: u64) -> u64 {
    let mut z = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Seed of record `i` of a sweep seeded `seed` (below 2⁶³, so that it is exact in a
/// signed 64-bit Parquet column).
pub fn record_seed(seed: u64, i: u64) -> u64 {
    splitmix64(seed ^ splitmix64(i)) >> 1
}

/// A small deterministic stream for the draws of one record (SplitMix64 sequence).
struct Draws(u64);

impl Draws {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        splitmix64(self.0)
    }
    /// Uniform on [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The labelled cell of the grid a record falls in.
#[derive(Debug, Clone, PartialEq)]
pub struct Cell {
    /// Bearing preset.
    pub preset: String,
    /// Shaft speed (rpm).
    pub rpm: f64,
    /// Radial load (N), `None` = the preset's.
    pub radial_load: Option<f64>,
    /// `healthy`, `outer`, `inner` or `ball`.
    pub fault: String,
    /// Defect stage (topography), `healthy` for a healthy cell.
    pub stage: String,
}

impl std::fmt::Display for Cell {
    /// The cell as the spec's keys: `preset = "…", rpm = …, radial_load = …, fault = "…",
    /// stage = "…"` (the load left out when it is the preset's).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "preset = \"{}\", rpm = {}", self.preset, self.rpm)?;
        if let Some(l) = self.radial_load {
            write!(f, ", radial_load = {l}")?;
        }
        write!(
            f,
            ", fault = \"{}\", stage = \"{}\"",
            self.fault, self.stage
        )
    }
}

/// The grid's cells in a fixed order: preset, rpm, load, fault, stage (a healthy fault
/// is one cell, whatever the stages).
pub fn cells(spec: &SweepSpec) -> Vec<Cell> {
    let g = &spec.grid;
    let loads: Vec<Option<f64>> = match &g.radial_load {
        Some(v) => v.iter().map(|x| Some(*x)).collect(),
        None => vec![None],
    };
    let mut out = Vec::new();
    for p in &g.preset {
        for &rpm in &g.rpm {
            for &load in &loads {
                for f in &g.fault {
                    let stages: Vec<String> = if f == "healthy" {
                        vec!["healthy".into()]
                    } else {
                        g.stage.clone()
                    };
                    for s in stages {
                        out.push(Cell {
                            preset: p.clone(),
                            rpm,
                            radial_load: load,
                            fault: f.clone(),
                            stage: s,
                        });
                    }
                }
            }
        }
    }
    out
}

/// One effect of a record: on or off, with its full parameter vector (drawn whether on
/// or not, so that switching one effect's probability does not move the others' draws).
#[derive(Debug, Clone, PartialEq)]
pub struct EffectValue {
    /// Effect name.
    pub name: String,
    /// Switched on in this record.
    pub on: bool,
    /// Every parameter of the effect (registry order): name and value.
    pub params: Vec<(String, f64)>,
}

/// Everything about record `i`.
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    /// Record number in the sweep.
    pub index: u64,
    /// Simulation seed.
    pub seed: u64,
    /// Labels.
    pub cell: Cell,
    /// Effects of the spec, in spec order.
    pub effects: Vec<EffectValue>,
}

/// Record `i` of `spec` over `cells` (from [`cells`]).
pub fn record(spec: &SweepSpec, cells: &[Cell], i: u64) -> Record {
    let seed = record_seed(spec.seed, i);
    let cell = cells[(i % cells.len() as u64) as usize].clone();
    let mut d = Draws(splitmix64(seed ^ 0x5EED_0FEF_FEC7));
    let mut effects = Vec::with_capacity(spec.effect.len());
    for e in &spec.effect {
        let on = d.unit() < e.probability.unwrap_or(1.0);
        let info = crate::effects::kind(&e.name).map(|k| k.spec());
        let mut params = Vec::new();
        if let Ok(info) = info {
            for p in info.params {
                let v = match e.params.get(p.name) {
                    None => p.default,
                    Some(Dist::Fixed(v)) => *v,
                    Some(Dist::Table(DistTable {
                        uniform: Some([lo, hi]),
                        ..
                    })) => (lo + (hi - lo) * d.unit()).clamp(*lo, *hi),
                    Some(Dist::Table(DistTable {
                        choice: Some(c), ..
                    })) if !c.is_empty() => c[(d.next_u64() % c.len() as u64) as usize],
                    Some(Dist::Table(_)) => p.default,
                };
                params.push((p.name.to_string(), v));
            }
        }
        effects.push(EffectValue {
            name: e.name.clone(),
            on,
            params,
        });
    }
    Record {
        index: i,
        seed,
        cell,
        effects,
    }
}

impl Record {
    /// The record as a scenario file (what `wearsim simulate --config` would run).
    pub fn scenario_file(&self, spec: &SweepSpec) -> ScenarioFile {
        let c = &self.cell;
        let defect = if c.fault == "healthy" {
            DefectSection {
                enabled: Some(false),
                location: Some("none".into()),
                ..Default::default()
            }
        } else {
            DefectSection {
                enabled: Some(true),
                location: Some(c.fault.clone()),
                topography: Some(c.stage.clone()),
                ..Default::default()
            }
        };
        ScenarioFile {
            preset: Some(c.preset.clone()),
            seed: Some(self.seed),
            duration: Some(spec.duration),
            fs: Some(spec.fs),
            settle: spec.settle,
            radial_load: c.radial_load,
            speed: Some(SpeedSection {
                rpm: Some(c.rpm),
                ..Default::default()
            }),
            defect: Some(defect),
            effect: self
                .effects
                .iter()
                .filter(|e| e.on)
                .map(|e| EffectSection {
                    name: e.name.clone(),
                    params: e.params.iter().cloned().collect(),
                })
                .collect(),
            ..Default::default()
        }
    }
}
