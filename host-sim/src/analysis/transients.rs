//! Transients that are not the bearing: a knock on the housing, a cable struck, a burst of
//! interference or a saturated stretch of the acquisition.
//!
//! One such event can hold more energy than the rest of the record. The fast kurtogram then
//! chooses its band (a burst is as impulsive as anything in the record), and the envelope of
//! a lone burst of duration D is a rectangle whose spectrum has lobes every 1/D Hz, lines
//! the detector reads as some family's harmonics: an outside probe (stop 54, probe F) put
//! 0.2 s of clipped noise at 10 × the record's peak before or after the shared CWRU IR/OR
//! records and got 53 wrong families in 80 drive-end runs (ball 0.99 for inner-race
//! records). An analyst cuts such an event out before demodulating; so does [`excise`].
//!
//! The record is cut into blocks of one shaft revolution (the period of the load-zone
//! modulation, so a stationary fault gives steady block powers); a block whose mean square
//! stands [`OUTLIER_DB`] over the median block's is a transient, and it is cut out with one
//! block on each side (the event's onset and ring-down), the rest joined. Set before any
//! record was read: 20 dB (100 × in power) lies far above what bearing impacts do on their
//! own — the largest block on any CWRU development record (drive end 0–1 hp) stands 11.8 dB
//! over its median (`B014_0`, a ball fault's intermittent impacts; evaluation 11.1 dB, fan
//! end 13.9 dB, normal 0.7 dB), so no record of the benchmark is touched. When more than
//! [`MAX_FRACTION`] of the blocks stand out, the record is not a steady one with an event
//! in it (a run-up, an intermittent machine) and nothing is cut.

use serde::Serialize;

/// Power of a transient block over the median block's, dB.
pub const OUTLIER_DB: f64 = 20.0;
/// Largest fraction of the blocks (neighbours included) that may be cut.
pub const MAX_FRACTION: f64 = 0.1;
/// Fewest blocks a record needs for its median block to be the steady level.
pub const MIN_BLOCKS: usize = 20;
/// Fewest samples in a block (a fast shaft at a low rate).
const MIN_BLOCK_SAMPLES: usize = 32;

/// What [`excise`] cut out of a record.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Transients {
    /// Block length (one shaft revolution), s.
    pub block_s: f64,
    /// Spans cut out, `(start, end)` in seconds of the record as given.
    pub spans_s: Vec<(f64, f64)>,
    /// Seconds cut out in all.
    pub seconds: f64,
    /// Power of the strongest block over the median block's, dB.
    pub peak_db: f64,
}

/// `x` (sampled at `fs` Hz, shaft at `shaft_hz`) with its transients cut out, and what was
/// cut; `x` unchanged and `None` when nothing stands [`OUTLIER_DB`] over the median block,
/// when more than [`MAX_FRACTION`] of the record would go, or when the record holds fewer
/// than [`MIN_BLOCKS`] blocks.
pub fn excise(x: Vec<f64>, fs: f64, shaft_hz: f64) -> (Vec<f64>, Option<Transients>) {
    let block = if fs.is_finite() && shaft_hz.is_finite() && shaft_hz > 0.0 {
        ((fs / shaft_hz).round() as usize).max(MIN_BLOCK_SAMPLES)
    } else {
        return (x, None);
    };
    let n_blocks = x.len() / block;
    if n_blocks < MIN_BLOCKS {
        return (x, None);
    }
    let power: Vec<f64> = x
        .chunks_exact(block)
        .map(|b| b.iter().map(|v| v * v).sum::<f64>() / block as f64)
        .collect();
    let mut sorted = power.clone();
    sorted.sort_by(f64::total_cmp);
    let median = sorted[sorted.len() / 2];
    let peak = sorted.last().copied().unwrap_or(0.0);
    if !(median > 0.0 && peak.is_finite()) {
        return (x, None);
    }
    let limit = median * 10f64.powf(OUTLIER_DB / 10.0);
    // Flagged blocks and their neighbours; the partial block at the end goes with the last.
    let mut cut = vec![false; n_blocks];
    for (i, p) in power.iter().enumerate() {
        if *p > limit {
            for c in cut.iter_mut().take(i + 2).skip(i.saturating_sub(1)) {
                *c = true;
            }
        }
    }
    let n_cut = cut.iter().filter(|c| **c).count();
    if n_cut == 0 || n_cut as f64 > MAX_FRACTION * n_blocks as f64 {
        return (x, None);
    }
    let tail_cut = cut.last().copied().unwrap_or(false);
    let mut kept = Vec::with_capacity(x.len());
    let mut spans: Vec<(f64, f64)> = Vec::new();
    for (i, chunk) in x.chunks(block).enumerate() {
        let gone = cut.get(i).copied().unwrap_or(tail_cut);
        if !gone {
            kept.extend_from_slice(chunk);
            continue;
        }
        let (t0, t1) = (
            (i * block) as f64 / fs,
            (i * block + chunk.len()) as f64 / fs,
        );
        match spans.last_mut() {
            Some(last) if (last.1 - t0).abs() < 0.5 / fs => last.1 = t1,
            _ => spans.push((t0, t1)),
        }
    }
    let seconds = (x.len() - kept.len()) as f64 / fs;
    let found = Transients {
        block_s: block as f64 / fs,
        spans_s: spans,
        seconds,
        peak_db: 10.0 * (peak / median).log10(),
    };
    (kept, Some(found))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::synth::gaussian_noise;

    const FS: f64 = 12_000.0;
    const SHAFT: f64 = 30.0;

    #[test]
    fn a_burst_is_cut_out_with_its_neighbours_and_nothing_else() {
        let mut x = gaussian_noise(120_000, 1.0, 5);
        // 0.2 s at 10 times the level from 3 s: 25 % louder in amplitude than 20 dB.
        for v in &mut x[36_000..38_400] {
            *v *= 12.5;
        }
        let (y, t) = excise(x.clone(), FS, SHAFT);
        let t = t.expect("the burst is found");
        assert_eq!(t.spans_s.len(), 1, "{t:?}");
        let (a, b) = t.spans_s[0];
        // Blocks of 400 samples: the burst covers blocks 90..96, cut 89..=96.
        assert!((a - 89.0 * 400.0 / FS).abs() < 1e-9 && (b - 97.0 * 400.0 / FS).abs() < 1e-9);
        assert_eq!(y.len(), x.len() - 8 * 400);
        assert!((t.seconds - 8.0 * 400.0 / FS).abs() < 1e-9);
        assert!(t.peak_db > 20.0 && t.peak_db < 23.0, "{t:?}");
        // What is kept is the record without those blocks, in order.
        assert_eq!(&y[..35_600], &x[..35_600]);
        assert_eq!(&y[35_600..], &x[38_800..]);
    }

    #[test]
    fn steady_records_and_too_many_events_are_left_alone() {
        let x = gaussian_noise(120_000, 1.0, 6);
        let (y, t) = excise(x.clone(), FS, SHAFT);
        assert_eq!((y, t), (x.clone(), None));
        // 19 dB over the median: not a transient.
        let mut quiet = x.clone();
        for v in &mut quiet[36_000..38_400] {
            *v *= 8.9;
        }
        assert_eq!(excise(quiet, FS, SHAFT).1, None);
        // Bursts over more than a tenth of the record: not a steady record with events.
        let mut many = x.clone();
        for k in 0..12 {
            for v in &mut many[k * 10_000..k * 10_000 + 400] {
                *v *= 20.0;
            }
        }
        assert_eq!(excise(many, FS, SHAFT).1, None);
        // Too short for a median (19 blocks), or no shaft speed.
        assert_eq!(excise(x[..7_600].to_vec(), FS, SHAFT).1, None);
        assert_eq!(excise(x.clone(), FS, f64::NAN).1, None);
    }
}
