//! The sweep specification (`SPEC.toml`): the grid of labelled conditions (bearing preset,
//! speed, load, fault location, defect stage), the candidate effects with the distributions
//! their parameters are drawn from, and the record settings. Unknown keys, empty axes and
//! distributions reaching outside an effect's bounds (the core's effect registry) are
//! errors naming the key.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Largest number of records one sweep may hold.
pub const MAX_RECORDS: u64 = 10_000_000;
/// Largest number of records in one shard.
pub const MAX_RECORDS_PER_SHARD: u64 = 100_000;
/// Default number of records per shard.
pub const DEFAULT_RECORDS_PER_SHARD: u64 = 256;
/// Most samples one shard may hold (2^27: 512 MiB as float32, twice that as f64 while its
/// records are simulated): a shard is generated whole in memory, then written.
pub const MAX_SHARD_SAMPLES: u64 = 1 << 27;

/// A sweep specification problem (always names the key); exit code 2.
#[derive(Debug, thiserror::Error)]
#[error("sweep spec: {0}")]
pub struct SpecError(pub String);

fn err<T>(m: impl Into<String>) -> Result<T, SpecError> {
    Err(SpecError(m.into()))
}

/// The whole specification.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SweepSpec {
    /// Sweep seed: record `i`'s seed is derived from it and `i` ([`super::record_seed`]).
    pub seed: u64,
    /// Number of records, 1..=10 000 000.
    pub records: u64,
    /// Records per shard (one `.npy` file each), 1..=100 000; default 256.
    #[serde(default)]
    pub records_per_shard: Option<u64>,
    /// Recorded length of each record (s).
    pub duration: f64,
    /// Output sample rate (Hz).
    pub fs: f64,
    /// Settling time simulated and discarded before each record (s); default the
    /// scenario default.
    #[serde(default)]
    pub settle: Option<f64>,
    /// The labelled conditions (full factorial; record `i` takes cell `i mod cells`).
    pub grid: Grid,
    /// Candidate effects, each switched on with its probability, parameters drawn.
    #[serde(default)]
    pub effect: Vec<EffectDraw>,
}

/// `[grid]`: every axis is a non-empty list.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Grid {
    /// Bearing presets (`wearsim presets`).
    pub preset: Vec<String>,
    /// Constant shaft speeds (rpm).
    pub rpm: Vec<f64>,
    /// Static radial loads (N); absent = each preset's own load.
    #[serde(default)]
    pub radial_load: Option<Vec<f64>>,
    /// Fault locations: `healthy`, `outer`, `inner`, `ball`.
    pub fault: Vec<String>,
    /// Defect stages along a life (Table 1 topographies, e.g. `mild-defect`,
    /// `medium-defect`, `large-defect`); a healthy cell has stage `healthy`.
    pub stage: Vec<String>,
}

/// `[[effect]]`: an effect, the probability that a record has it, and its parameters'
/// distributions (parameters not named take their default).
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct EffectDraw {
    /// Effect name (`wearsim effects`).
    pub name: String,
    /// Probability that a record has the effect on, 0..=1; default 1.
    #[serde(default)]
    pub probability: Option<f64>,
    /// Parameter distributions.
    #[serde(default)]
    pub params: BTreeMap<String, Dist>,
}

/// A parameter's distribution.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(untagged)]
pub enum Dist {
    /// A fixed value.
    Fixed(f64),
    /// `{ uniform = [lo, hi] }` or `{ choice = [a, b, …] }`.
    Table(DistTable),
}

impl Dist {
    /// The ends of the range a distribution draws from (`uniform`'s bounds, `choice`'s
    /// smallest and largest value); none for a fixed value, which every record takes.
    pub fn ends(&self) -> Vec<f64> {
        match self {
            Dist::Fixed(_) => vec![],
            Dist::Table(DistTable {
                uniform: Some([lo, hi]),
                ..
            }) => vec![*lo, *hi],
            Dist::Table(DistTable {
                choice: Some(c), ..
            }) => {
                let lo = c.iter().copied().fold(f64::INFINITY, f64::min);
                let hi = c.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                [lo, hi].into_iter().filter(|v| v.is_finite()).collect()
            }
            Dist::Table(_) => vec![],
        }
    }
}

/// The table forms of [`Dist`].
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct DistTable {
    /// Uniform on `[lo, hi]`.
    #[serde(default)]
    pub uniform: Option<[f64; 2]>,
    /// One of the values, equally likely.
    #[serde(default)]
    pub choice: Option<Vec<f64>>,
}

/// Fault locations the grid accepts.
pub const FAULTS: [&str; 4] = ["healthy", "outer", "inner", "ball"];

impl SweepSpec {
    /// Parses and checks a specification; `origin` names it in messages.
    pub fn parse(text: &str, origin: &str) -> Result<Self, SpecError> {
        let spec: SweepSpec = toml::from_str(text).map_err(|e| {
            // serde's message for a value no form of `Dist` takes names the Rust type.
            let m = crate::config::toml_error::describe(text, &e).replace(
                "data did not match any variant of untagged enum Dist",
                "a parameter's distribution is a number, { uniform = [lo, hi] } (two numbers) or { choice = [a, b, …] } (numbers)",
            );
            SpecError(format!("{origin}: {m}"))
        })?;
        spec.check()?;
        Ok(spec)
    }

    /// Records per shard (the default applied).
    pub fn per_shard(&self) -> u64 {
        self.records_per_shard.unwrap_or(DEFAULT_RECORDS_PER_SHARD)
    }

    /// Number of shards.
    pub fn shards(&self) -> u64 {
        self.records.div_ceil(self.per_shard())
    }

    /// Samples per record.
    pub fn samples(&self) -> usize {
        (self.duration * self.fs).round() as usize
    }

    /// Checks every key that the scenario resolution does not check itself.
    pub fn check(&self) -> Result<(), SpecError> {
        if !(1..=MAX_RECORDS).contains(&self.records) {
            return err(format!(
                "`records` = {} is outside 1..={MAX_RECORDS}",
                self.records
            ));
        }
        if !(1..=MAX_RECORDS_PER_SHARD).contains(&self.per_shard()) {
            return err(format!(
                "`records_per_shard` = {} is outside 1..={MAX_RECORDS_PER_SHARD}",
                self.per_shard()
            ));
        }
        // Infinite or NaN sizes are left to the scenario checks, which name `duration`/`fs`.
        let shard_samples = self.per_shard() as f64 * self.duration * self.fs;
        if shard_samples.is_finite() && shard_samples > MAX_SHARD_SAMPLES as f64 {
            return err(format!(
                "`records_per_shard` × duration × fs = {} × {} s × {} Hz = {shard_samples:.0} samples exceeds the limit of {MAX_SHARD_SAMPLES} samples per shard (2^27: a shard is held in memory until it is written); lower `records_per_shard`",
                self.per_shard(),
                self.duration,
                self.fs
            ));
        }
        let g = &self.grid;
        let axes: [(&str, usize); 4] = [
            ("grid.preset", g.preset.len()),
            ("grid.rpm", g.rpm.len()),
            ("grid.fault", g.fault.len()),
            ("grid.stage", g.stage.len()),
        ];
        for (k, n) in axes {
            if n == 0 {
                return err(format!("`{k}` is empty: give at least one value"));
            }
        }
        if g.radial_load.as_ref().is_some_and(Vec::is_empty) {
            return err("`grid.radial_load` is empty: give at least one value or leave it out");
        }
        // A repeated value would generate its grid cells twice under two labels that
        // cannot be told apart in the index.
        let text = |v: &[String]| v.to_vec();
        let num = |v: &[f64]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>();
        let lists = [
            ("grid.preset", text(&g.preset)),
            ("grid.rpm", num(&g.rpm)),
            ("grid.fault", text(&g.fault)),
            ("grid.stage", text(&g.stage)),
            (
                "grid.radial_load",
                num(g.radial_load.as_deref().unwrap_or(&[])),
            ),
        ];
        for (k, v) in lists {
            if let Some(d) = first_repeat(&v) {
                return err(format!(
                    "`{k}` lists {d} twice: each value is one grid axis point; remove the repeat"
                ));
            }
        }
        for p in &g.preset {
            if wearsim_core::presets::by_name(p).is_none() {
                return err(format!(
                    "`grid.preset` = \"{p}\" is not a preset; use one of: {}",
                    wearsim_core::presets::NAMES.join(", ")
                ));
            }
        }
        for f in &g.fault {
            if !FAULTS.contains(&f.as_str()) {
                return err(format!(
                    "`grid.fault` = \"{f}\" is not allowed; use one of: {}",
                    FAULTS.join(", ")
                ));
            }
        }
        for s in &g.stage {
            if wearsim_core::topography::by_name(s).is_none() {
                let names: Vec<&str> = wearsim_core::topography::TABLE_1
                    .iter()
                    .map(|(n, _)| *n)
                    .collect();
                return err(format!(
                    "`grid.stage` = \"{s}\" is not a defect stage; use one of: {}",
                    names.join(", ")
                ));
            }
        }
        for (i, e) in self.effect.iter().enumerate() {
            check_effect(i, e)?;
        }
        crate::effects::check_unique(
            self.effect.iter().map(|e| e.name.as_str()),
            "effect",
            ".name",
        )
        .map_err(SpecError)?;
        Ok(())
    }
}

/// The first value of `v` that occurs again later, if any (one pass: an axis may list
/// 10⁵ values, and comparing every pair of them took minutes).
fn first_repeat(v: &[String]) -> Option<&str> {
    let mut seen = std::collections::HashMap::with_capacity(v.len());
    let mut first: Option<usize> = None;
    for (i, x) in v.iter().enumerate() {
        if let Some(&j) = seen.get(x.as_str()) {
            first = Some(first.map_or(j, |f: usize| f.min(j)));
        } else {
            seen.insert(x.as_str(), i);
        }
    }
    first.map(|j| v[j].as_str())
}

fn check_effect(i: usize, e: &EffectDraw) -> Result<(), SpecError> {
    let kind =
        crate::effects::kind(&e.name).map_err(|m| SpecError(format!("`effect[{i}].name`: {m}")))?;
    let spec = kind.spec();
    if let Some(p) = e.probability {
        if !(0.0..=1.0).contains(&p) {
            return err(format!(
                "`effect[{i}].probability` = {p} is outside [0, 1] (effect `{}`)",
                e.name
            ));
        }
    }
    for (name, d) in &e.params {
        let key = format!("effect[{i}].params.{name}");
        let Some(p) = spec.params.iter().find(|p| p.name == name) else {
            let known: Vec<&str> = spec.params.iter().map(|p| p.name).collect();
            return err(format!(
                "`{key}`: effect `{}` has no parameter `{name}`; its parameters: {}",
                e.name,
                known.join(", ")
            ));
        };
        let values: Vec<f64> = match d {
            Dist::Fixed(v) => vec![*v],
            Dist::Table(DistTable {
                uniform: Some([lo, hi]),
                choice: None,
            }) => {
                if lo.is_nan() || hi.is_nan() {
                    return err(format!(
                        "`{key}.uniform` = [{lo}, {hi}]: both ends must be numbers within the parameter's bounds [{}, {}] {}",
                        p.min, p.max, p.unit
                    ));
                }
                if lo > hi {
                    return err(format!("`{key}.uniform` = [{lo}, {hi}]: lo must not exceed hi"));
                }
                vec![*lo, *hi]
            }
            Dist::Table(DistTable {
                uniform: None,
                choice: Some(c),
            }) if !c.is_empty() => c.clone(),
            Dist::Table(_) => {
                return err(format!(
                    "`{key}`: give a number, {{ uniform = [lo, hi] }} or a non-empty {{ choice = [...] }}"
                ))
            }
        };
        for v in values {
            if !(v >= p.min && v <= p.max) {
                return err(format!(
                    "`{key}`: {v} is outside the bounds of effect `{}` parameter `{name}`: [{}, {}] {}",
                    e.name, p.min, p.max, p.unit
                ));
            }
        }
    }
    Ok(())
}
