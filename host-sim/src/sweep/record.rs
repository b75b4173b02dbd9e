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
/// is one cell, whatever the stages). Cell `k` is computed from `k` when asked for
/// ([`Cells::get`]), never the whole full factorial at once: a grid of `P × R × L` points
/// can be far larger than the records it labels (record `i` takes cell `i mod len`), and
/// holding every cell was about 400 bytes each (4 GB for a 10⁷-cell grid).
#[derive(Debug, Clone)]
pub struct Cells {
    presets: Vec<String>,
    rpms: Vec<f64>,
    loads: Vec<Option<f64>>,
    /// The (fault, stage) pairs of one (preset, rpm, load) point, in order.
    faults: Vec<(String, String)>,
    /// Number of cells (saturated at `u64::MAX`; records never reach it).
    len: u64,
}

impl Cells {
    /// Number of cells of the grid (at least 1 for a checked spec).
    pub fn len(&self) -> u64 {
        self.len
    }

    /// Whether the grid has no cell (an empty axis; a checked spec never has one).
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Cell `k` (`k < len`), in the order documented on [`Cells`].
    pub fn get(&self, k: u64) -> Cell {
        let per = self.faults.len() as u64;
        let (fs, rest) = (k % per, k / per);
        let nl = self.loads.len() as u64;
        let (l, rest) = (rest % nl, rest / nl);
        let nr = self.rpms.len() as u64;
        let (r, p) = (rest % nr, rest / nr);
        let (fault, stage) = &self.faults[fs as usize];
        Cell {
            preset: self.presets[p as usize].clone(),
            rpm: self.rpms[r as usize],
            radial_load: self.loads[l as usize],
            fault: fault.clone(),
            stage: stage.clone(),
        }
    }
}

/// The grid's cells of `spec` (see [`Cells`]).
pub fn cells(spec: &SweepSpec) -> Cells {
    let g = &spec.grid;
    let loads: Vec<Option<f64>> = match &g.radial_load {
        Some(v) => v.iter().map(|x| Some(*x)).collect(),
        None => vec![None],
    };
    let mut faults = Vec::new();
    for f in &g.fault {
        if f == "healthy" {
            faults.push((f.clone(), "healthy".to_string()));
        } else {
            faults.extend(g.stage.iter().map(|s| (f.clone(), s.clone())));
        }
    }
    let len = [g.preset.len(), g.rpm.len(), loads.len(), faults.len()]
        .iter()
        .fold(1u64, |n, &k| n.saturating_mul(k as u64));
    Cells {
        presets: g.preset.clone(),
        rpms: g.rpm.clone(),
        loads,
        faults,
        len,
    }
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
pub fn record(spec: &SweepSpec, cells: &Cells, i: u64) -> Record {
    let seed = record_seed(spec.seed, i);
    let cell = cells.get(i % cells.len());
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
