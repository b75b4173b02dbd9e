//! The sim-to-real gap (`../shared/docs/sim-to-real.md`): feature cells computed the same
//! way on a simulated and a measured record, and each cell's gap normalised by the
//! measured record's own segment-to-segment spread, so that a gap below about 1 is within
//! the measurement's variability. This module answers "where"; the attribution to
//! candidate effects ("which", "how far") builds on it.

pub mod attribute;
pub mod attribution;
pub mod cells;
pub mod error;
pub mod exchange;
pub mod fit;
pub mod identify;
pub mod informed;
pub mod leave_one_out;
pub mod lifetime;
pub mod matched;
pub mod memo;
pub mod nuisance;
pub mod protocol;
pub mod records;
pub mod report;
pub mod roles;
pub mod run;
pub mod signature;
pub mod significance;
pub mod space;
pub mod stability;
pub mod stationary;
pub mod steps;
pub mod twin;
pub mod twin_report;
pub mod validate;

pub use cells::{cells, CellSpec, CellValue};
pub use error::GapError;

use crate::analysis::stats::mean_std;
use crate::analysis::AnalysisError;
use serde::Serialize;

/// Segments a measured record is split into to estimate each cell's spread.
pub const SEGMENTS: usize = 8;

/// Smallest spread used to normalise a cell, per cell unit: dB cells 0.5 dB, ratios 0.02,
/// so that an implausibly steady measured cell cannot make any difference look huge.
fn spread_floor(unit: &str) -> f64 {
    match unit {
        "dB" => 0.5,
        "%" => 0.05,
        _ => 0.02,
    }
}

/// One cell's gap.
#[derive(Debug, Clone, Serialize)]
pub struct CellGap {
    /// Cell name, e.g. `zone:natural`, `stat:kurtosis`, `env:h3`.
    pub name: String,
    /// Group: `zone`, `shape`, `stat`, `env`.
    pub group: String,
    /// Unit of the values.
    pub unit: String,
    /// Simulated value (mean over the simulated record's segments).
    pub sim: f64,
    /// Measured value (mean over the measured record's segments).
    pub real: f64,
    /// Standard deviation of the measured value across segments (floored).
    pub spread: f64,
    /// `(sim − real) / spread`.
    pub gap: f64,
}

/// The gap between a simulated and a measured record.
#[derive(Debug, Clone, Serialize)]
pub struct GapReport {
    /// Cells ordered by |gap|, largest first ("where").
    pub cells: Vec<CellGap>,
    /// Total gap: root mean square of the cell gaps.
    pub total: f64,
    /// Segments used on each side.
    pub segments: usize,
}

/// The per-segment cell whose segment-to-segment wander is itself a cell: the offset of
/// the measured fault frequency from the kinematic one (%).
const WANDER_OF: &str = "env:slip";

/// Name of the between-segment cell: the standard deviation over the segments of
/// `WANDER_OF`, in dB re 1 % (floored at 0.01 %). A speed that fluctuates slower than a
/// segment moves the fault line from segment to segment without changing the segments'
/// mean, so no mean-based cell sees it; random slip of the element passes (independent
/// from pass to pass) averages out within a segment's 20-odd passes and barely moves it.
pub const WANDER: &str = "env:wander";

/// Spread (dB) the [`WANDER`] cell is normalised by: the sampling standard deviation of a
/// standard deviation estimated from `n` = [`SEGMENTS`] values, in dB,
/// `20/ln 10 · 1/√(2(n−1))` (normal values; 2.3 dB for 8 segments).
pub fn wander_spread_db() -> f64 {
    20.0 / std::f64::consts::LN_10 / (2.0 * (SEGMENTS as f64 - 1.0)).sqrt()
}

/// [`WANDER`] of a record's segment cells (dB re 1 %), `None` when the segments have no
/// [`WANDER_OF`] cell.
fn wander_db(segs: &[Vec<CellValue>]) -> Option<f64> {
    let i = segs.first()?.iter().position(|c| c.name == WANDER_OF)?;
    let v: Vec<f64> = segs
        .iter()
        .filter_map(|s| s.get(i).map(|c| c.value))
        .collect();
    Some(20.0 * mean_std(&v).1.max(0.01).log10())
}

/// `x` with its mean removed (signal units): the part's DC offset, which an accelerometer's
/// bias (IEPE, MEMS) adds to a measured record and no simulation has.
pub fn without_mean(x: &[f64]) -> Vec<f64> {
    let m = crate::analysis::stats::mean(x);
    x.iter().map(|v| v - m).collect()
}

/// Cell values of each of `SEGMENTS` equal segments of `x`, after removing the mean of the
/// whole of `x` (as `analyze` does): a sensor's DC offset changes no cell, measured or
/// simulated alike.
pub fn segment_cells(x: &[f64], spec: &CellSpec) -> Result<Vec<Vec<CellValue>>, AnalysisError> {
    let x = match spec.band_hz {
        Some(top) => crate::analysis::content_band::low_pass(&without_mean(x), spec.fs, top),
        None => without_mean(x),
    };
    let len = x.len() / SEGMENTS;
    (0..SEGMENTS)
        .map(|i| cells(&x[i * len..(i + 1) * len], spec))
        .collect()
}

/// Why a part of `samples` samples has no envelope cells, in words with the part length
/// that would give them (`None` when its segments resolve them): each of its [`SEGMENTS`]
/// segments must hold [`cells::MIN_ENVELOPE_PERIODS`] periods of the fault fundamental
/// ([`cells::envelope_resolved`]).
pub fn envelope_note(samples: usize, spec: &CellSpec) -> Option<String> {
    let seg = samples / SEGMENTS;
    let base = cells::fault_base_hz(spec);
    if cells::envelope_resolved(seg, spec.fs, base) {
        return None;
    }
    let need_s = cells::min_envelope_segment_s(spec)? * SEGMENTS as f64;
    let seg_s = seg as f64 / spec.fs;
    Some(format!(
        "no envelope cells: a segment of a part ({:.3} s = 1/{SEGMENTS} of {:.2} s) holds {:.1} periods of the fault frequency ({base:.2} Hz), and a line and its floor need {} (as `analyze` needs of a record): parts of at least {need_s:.2} s (--seconds) resolve them at this speed",
        seg_s,
        samples as f64 / spec.fs,
        seg_s * base,
        cells::MIN_ENVELOPE_PERIODS
    ))
}

/// The measured side of a gap, computed once: each cell's mean and (floored) spread over
/// the measured record's segments. Fits compare many simulations against one reference.
#[derive(Debug, Clone)]
pub struct Reference {
    /// Cell names, groups and units, in cell order.
    pub names: Vec<(String, &'static str, &'static str)>,
    /// Mean of each cell over the measured segments.
    pub mean: Vec<f64>,
    /// Floored standard deviation of each cell across the measured segments.
    pub spread: Vec<f64>,
    /// Weight of each cell in the total gap: `1/√(G·n_g)` for a cell of a group with
    /// `n_g` cells among `G` groups, so that every group counts equally (Σ w² = 1).
    pub weight: Vec<f64>,
    /// The spec the cells were computed with.
    pub spec: CellSpec,
}

impl Reference {
    /// Cells of the measured record `real`, split into [`SEGMENTS`] segments.
    pub fn new(real: &[f64], spec: &CellSpec) -> Result<Self, AnalysisError> {
        let r = segment_cells(real, spec)?;
        let Some(first) = r.first() else {
            return Err(AnalysisError::Empty);
        };
        let mut names = vec![];
        let mut mean = vec![];
        let mut spread = vec![];
        for (i, c) in first.iter().enumerate() {
            let rv: Vec<f64> = r
                .iter()
                .filter_map(|seg| seg.get(i).map(|c| c.value))
                .collect();
            let (m, s) = mean_std(&rv);
            names.push((c.name.clone(), c.group, c.unit));
            mean.push(m);
            spread.push(s.max(spread_floor(c.unit)));
        }
        if let Some(w) = wander_db(&r) {
            names.push((WANDER.to_string(), "env", "dB"));
            mean.push(w);
            spread.push(wander_spread_db());
        }
        let weight = group_weights(&names);
        Ok(Reference {
            names,
            mean,
            spread,
            weight,
            spec: spec.clone(),
        })
    }

    /// Mean cell values of simulated record `sim` over its segments.
    pub fn sim_means(&self, sim: &[f64]) -> Result<Vec<f64>, AnalysisError> {
        let s = segment_cells(sim, &self.spec)?;
        let per_segment = s.first().map_or(0, Vec::len);
        let mut out: Vec<f64> = (0..per_segment)
            .map(|i| {
                let v: Vec<f64> = s
                    .iter()
                    .filter_map(|seg| seg.get(i).map(|c| c.value))
                    .collect();
                mean_std(&v).0
            })
            .collect();
        if self.names.iter().any(|n| n.0 == WANDER) {
            out.push(wander_db(&s).unwrap_or(-40.0));
        }
        Ok(out)
    }

    /// Normalised gaps `(sim − real)/spread` of simulated cell means `sim`, in cell order.
    pub fn residuals(&self, sim: &[f64]) -> Vec<f64> {
        normalised(sim, &self.mean, &self.spread)
    }

    /// Weighted gaps `w·(sim − real)/spread` (their root sum of squares is the total gap).
    pub fn weighted(&self, sim: &[f64]) -> Vec<f64> {
        self.residuals(sim)
            .iter()
            .zip(&self.weight)
            .map(|(r, w)| r * w)
            .collect()
    }

    /// The full report for simulated cell means `sim`.
    pub fn report(&self, sim: &[f64]) -> GapReport {
        let gaps = self.residuals(sim);
        let mut out: Vec<CellGap> = self
            .names
            .iter()
            .zip(sim)
            .zip(&self.mean)
            .zip(&self.spread)
            .zip(&gaps)
            .map(|((((n, s), r), d), g)| CellGap {
                name: n.0.clone(),
                group: n.1.to_string(),
                unit: n.2.to_string(),
                sim: *s,
                real: *r,
                spread: *d,
                gap: *g,
            })
            .collect();
        let total = total_weighted(&self.weighted(sim));
        out.sort_by(|a, b| b.gap.abs().total_cmp(&a.gap.abs()));
        GapReport {
            cells: out,
            total,
            segments: SEGMENTS,
        }
    }
}

/// Gaps `(sim − real)/spread`, cell by cell.
pub(crate) fn normalised(sim: &[f64], real: &[f64], spread: &[f64]) -> Vec<f64> {
    sim.iter()
        .zip(real)
        .zip(spread)
        .map(|((s, r), d)| (s - r) / d)
        .collect()
}

/// Root mean square of a set of cell gaps (used for subsets such as "where" cells).
pub fn total_gap(gaps: &[f64]) -> f64 {
    (gaps.iter().map(|g| g * g).sum::<f64>() / gaps.len().max(1) as f64).sqrt()
}

/// The total gap (sim-to-real.md: "one documented aggregate"): the root mean square of the
/// cell gaps within each group (zone levels, zone shapes, statistics, envelope cells),
/// averaged over the groups, i.e. `√(Σ (w·gap)²)` with [`Reference::weight`]; for several
/// records, `weighted` holds all their weighted gaps and the result is the root mean
/// square over records. 1 means the simulation is, on average, one measured
/// segment-to-segment standard deviation away from the measurement; every group counts
/// equally however many cells it has (the 1/3-octave shape has far more cells than the
/// statistics).
pub fn total_weighted(weighted: &[f64]) -> f64 {
    weighted.iter().map(|g| g * g).sum::<f64>().sqrt()
}

pub(crate) fn group_weights(names: &[(String, &'static str, &'static str)]) -> Vec<f64> {
    let mut groups: Vec<(&str, usize)> = vec![];
    for (_, g, _) in names {
        match groups.iter_mut().find(|(n, _)| n == g) {
            Some((_, c)) => *c += 1,
            None => groups.push((g, 1)),
        }
    }
    let ng = groups.len().max(1) as f64;
    names
        .iter()
        .map(|(_, g, _)| {
            let n = groups.iter().find(|(x, _)| x == g).map_or(1, |(_, c)| *c) as f64;
            1.0 / (ng * n).sqrt()
        })
        .collect()
}

/// The gap of simulated record `sim` against measured record `real`, both at the spec's
/// sample rate and kinematics.
pub fn gap(sim: &[f64], real: &[f64], spec: &CellSpec) -> Result<GapReport, AnalysisError> {
    let r = Reference::new(real, spec)?;
    let s = r.sim_means(sim)?;
    Ok(r.report(&s))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::synth::{gaussian_noise, sine};
    use crate::analysis::FaultFrequencies;

    fn spec(shaft_hz: f64) -> CellSpec {
        let s = shaft_hz;
        CellSpec {
            fs: 12_000.0,
            ff: FaultFrequencies {
                shaft_hz: s,
                ftf: 0.398 * s,
                bpfo: 3.585 * s,
                bpfi: 5.415 * s,
                bsf: 2.357 * s,
                natural_hz: 3350.0,
            },
            family: crate::analysis::FaultFamily::OuterRace,
            band_hz: None,
        }
    }

    /// Noise with a 30 Hz line and bursts at the BPFO (a crest and a kurtosis above
    /// Gaussian), 2 s at 12 kHz.
    fn record() -> Vec<f64> {
        let n = 24_000;
        let period = (12_000.0 / (3.585 * 29.95)) as usize;
        gaussian_noise(n, 1.0, 5)
            .iter()
            .zip(sine(n, 12_000.0, 29.95, 0.5, 0.2))
            .enumerate()
            .map(|(i, (a, b))| a + b + if i % period < 12 { 6.0 } else { 0.0 })
            .collect()
    }

    #[test]
    fn a_dc_offset_changes_no_cell() {
        for band in [None, Some(4000.0)] {
            let sp = CellSpec {
                band_hz: band,
                ..spec(29.95)
            };
            let x = record();
            let offset: Vec<f64> = x.iter().map(|v| v + 4.9).collect();
            let a = segment_cells(&x, &sp).unwrap();
            let b = segment_cells(&offset, &sp).unwrap();
            for (sa, sb) in a.iter().zip(&b) {
                assert_eq!(sa.len(), sb.len());
                for (ca, cb) in sa.iter().zip(sb) {
                    assert_eq!(ca.name, cb.name);
                    assert!(
                        (ca.value - cb.value).abs() < 1e-6 * (1.0 + ca.value.abs()),
                        "{band:?} {}: {} vs {}",
                        ca.name,
                        ca.value,
                        cb.value
                    );
                }
            }
        }
    }

    #[test]
    fn envelope_cells_need_ten_fault_periods_per_segment() {
        let x = record();
        // 1797 rpm: 0.25 s segments hold 27 BPFO periods; 300 rpm: 4.5.
        let fast = segment_cells(&x, &spec(29.95)).unwrap();
        assert!(fast[0].iter().any(|c| c.name == "env:h1"));
        assert_eq!(envelope_note(x.len(), &spec(29.95)), None);
        let slow = segment_cells(&x, &spec(5.0)).unwrap();
        for seg in &slow {
            assert!(seg.iter().all(|c| c.group != "env"), "{seg:?}");
            assert!(seg.iter().all(|c| c.value.abs() < 300.0), "{seg:?}");
        }
        let note = envelope_note(x.len(), &spec(5.0)).unwrap();
        assert!(note.contains("4.46 s"), "{note}");
        // Exactly ten periods resolve, a sample fewer does not.
        let n = (10.0 / 17.925 * 12_000.0_f64).ceil() as usize;
        assert!(cells::envelope_resolved(n, 12_000.0, 17.925));
        assert!(!cells::envelope_resolved(n - 1, 12_000.0, 17.925));
    }
}
