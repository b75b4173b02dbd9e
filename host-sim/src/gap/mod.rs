//! The sim-to-real gap (`../shared/docs/sim-to-real.md`): feature cells computed the same
//! way on a simulated and a measured record, and each cell's gap normalised by the
//! measured record's own segment-to-segment spread, so that a gap below about 1 is within
//! the measurement's variability. This module answers "where"; the attribution to
//! candidate effects ("which", "how far") builds on it.

pub mod cells;

pub use cells::{cells, CellSpec, CellValue};

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

fn mean_std(v: &[f64]) -> (f64, f64) {
    let n = v.len().max(1) as f64;
    let m = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1.0).max(1.0);
    (m, var.sqrt())
}

/// Cell values of each of `SEGMENTS` equal segments of `x`.
pub fn segment_cells(x: &[f64], spec: &CellSpec) -> Result<Vec<Vec<CellValue>>, AnalysisError> {
    let len = x.len() / SEGMENTS;
    (0..SEGMENTS)
        .map(|i| cells(&x[i * len..(i + 1) * len], spec))
        .collect()
}

/// The gap of simulated record `sim` against measured record `real`, both at the spec's
/// sample rate and kinematics.
pub fn gap(sim: &[f64], real: &[f64], spec: &CellSpec) -> Result<GapReport, AnalysisError> {
    let s = segment_cells(sim, spec)?;
    let r = segment_cells(real, spec)?;
    let Some(first) = r.first() else {
        return Err(AnalysisError::Empty);
    };
    let mut out = vec![];
    for (i, c) in first.iter().enumerate() {
        let rv: Vec<f64> = r
            .iter()
            .filter_map(|seg| seg.get(i).map(|c| c.value))
            .collect();
        let sv: Vec<f64> = s
            .iter()
            .filter_map(|seg| seg.get(i).map(|c| c.value))
            .collect();
        let (rm, rs) = mean_std(&rv);
        let (sm, _) = mean_std(&sv);
        let spread = rs.max(spread_floor(c.unit));
        out.push(CellGap {
            name: c.name.clone(),
            group: c.group.to_string(),
            unit: c.unit.to_string(),
            sim: sm,
            real: rm,
            spread,
            gap: (sm - rm) / spread,
        });
    }
    let total = (out.iter().map(|c| c.gap * c.gap).sum::<f64>() / out.len().max(1) as f64).sqrt();
    out.sort_by(|a, b| b.gap.abs().total_cmp(&a.gap.abs()));
    Ok(GapReport {
        cells: out,
        total,
        segments: SEGMENTS,
    })
}
