//! How the significance level of a gap is stated: what variability it measures, in the
//! findings' words, and how a level prints. One place, so that records of seconds and lives,
//! the attribution and the protocol's judgement say one level one way.

/// What the significance level of records of seconds measures, in the findings' words:
/// the cells' spread across a record part's segments.
pub const SEGMENT_VARIABILITY: &str = "the measurement's own segment-to-segment variability";

/// What the significance level of lives measures, in the findings' words: stage means of
/// a few measured snapshots against a few simulated windows
/// ([`super::lifetime::SIGNIFICANCE`] times the noise-only gap).
pub const LIFE_VARIABILITY: &str = "the sampling variability of the lives' stage means";

/// A significance level (total gap, no unit) as every finding prints it: two decimals,
/// so that one level never reads as two (1.45 and 1.5).
pub fn level(x: f64) -> String {
    format!("{x:.2}")
}
