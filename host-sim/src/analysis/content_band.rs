//! The band a measured record actually holds. A record whose acquisition low-pass sits far
//! below its Nyquist frequency — a 12 kHz record resampled to 48 kHz to share a data set's
//! rate, or a converter whose anti-alias corner was set low — has nothing above that
//! corner: its spectrum falls there by the filter's stop-band attenuation (60 dB and more
//! within a fraction of an octave), which no vibration spectrum does on its own (a
//! structure's response above its modes falls by tens of dB per *octave*). A simulation at
//! the record's rate has content up to its Nyquist frequency, so comparing the two over
//! the whole band would count the missing band as a gap that no bearing effect explains.
//! [`content_edge`] finds such an edge; [`low_pass`] removes what lies above it, from the
//! record and the simulation alike, so that they are compared where the record can inform.
//!
//! Rule (a stated prior, not fitted on any record): 1/6-octave band levels of a Welch PSD
//! (Hann, 4096 points or the record's length); the edge is the lowest band edge above which
//! *every* band lies at least [`EMPTY_DB`] below the strongest band of the octave just under
//! the edge, and it counts only when it lies below [`MAX_EDGE_FRACTION`] of the Nyquist
//! frequency (a converter's own anti-alias roll-off, from about 0.45 fs, never qualifies).

use super::fft::{plan_c2r, rfft};
use super::{welch_psd, zones::band_rms, WelchParams};

/// How far (dB) every band above the edge must lie below the octave under it: the
/// stop-band attenuation of a resampling or anti-alias filter (60 dB and more) against a
/// structure's roll-off of at most a few tens of dB per octave.
pub const EMPTY_DB: f64 = 60.0;

/// An edge counts only below this fraction of the Nyquist frequency: the top fifth of the
/// band must be empty, so a converter's own anti-alias roll-off near fs/2 never qualifies.
pub const MAX_EDGE_FRACTION: f64 = 0.8;

/// Bands per octave of the level scan.
const PER_OCTAVE: f64 = 6.0;

/// Lowest band edge of the scan (Hz): below it a record's content is shaft lines, not the
/// broadband level a low-pass acts on.
const LOWEST_HZ: f64 = 100.0;

/// The upper edge (Hz) of what record `x` (sampled at `fs`) holds, when everything above
/// it is empty by the rule of this module; `None` when the record has content up to near
/// its Nyquist frequency (the usual case) or is too short to tell.
pub fn content_edge(x: &[f64], fs: f64) -> Option<f64> {
    let nyquist = fs / 2.0;
    let nperseg = x.len().min(4096);
    if !(fs.is_finite() && fs > 0.0) || nperseg < 256 {
        return None;
    }
    let psd = welch_psd(
        x,
        fs,
        &WelchParams {
            nperseg,
            ..WelchParams::default()
        },
    )
    .ok()?;
    // Bands of 1/6 octave from LOWEST_HZ (at least a few bins wide) to Nyquist.
    let step = 2f64.powf(1.0 / PER_OCTAVE);
    let mut lo = LOWEST_HZ.max(4.0 * psd.df);
    let mut bands: Vec<(f64, f64)> = vec![];
    while lo < nyquist {
        let hi = (lo * step).min(nyquist);
        let db = 20.0 * band_rms(&psd, (lo, hi)).max(1e-300).log10();
        bands.push((lo, db));
        lo = hi;
    }
    let per_octave = PER_OCTAVE as usize;
    let mut edge = None;
    for k in (per_octave..bands.len()).rev() {
        let under = bands[k - per_octave..k]
            .iter()
            .map(|b| b.1)
            .fold(f64::NEG_INFINITY, f64::max);
        let above = bands[k..]
            .iter()
            .map(|b| b.1)
            .fold(f64::NEG_INFINITY, f64::max);
        if above <= under - EMPTY_DB {
            edge = Some(bands[k].0);
        }
    }
    edge.filter(|e| *e < MAX_EDGE_FRACTION * nyquist)
}

/// `x` (sampled at `fs`) without its content above `edge_hz`: the DFT of the whole record
/// with every bin above the edge set to zero (the record is compared over the band it
/// holds; the mean is kept).
pub fn low_pass(x: &[f64], fs: f64, edge_hz: f64) -> Vec<f64> {
    let n = x.len();
    if n < 2 || !(edge_hz > 0.0 && edge_hz < fs / 2.0) {
        return x.to_vec();
    }
    let mut spec = rfft(x, 0.0);
    let df = fs / n as f64;
    for (k, c) in spec.iter_mut().enumerate() {
        if k as f64 * df > edge_hz {
            *c = Default::default();
        }
    }
    // The inverse of a real signal's spectrum: DC and (even n) Nyquist bins are real.
    if let Some(c) = spec.first_mut() {
        c.im = 0.0;
    }
    if n.is_multiple_of(2) {
        if let Some(c) = spec.last_mut() {
            c.im = 0.0;
        }
    }
    let plan = plan_c2r(n);
    let mut out = plan.make_output_vec();
    match plan.process(&mut spec, &mut out) {
        Ok(()) => out.iter().map(|v| v / n as f64).collect(),
        Err(_) => x.to_vec(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Broadband noise with a resonance, as a 12 kHz accelerometer record holds.
    fn record(n: usize, seed: u64) -> Vec<f64> {
        let mut s = seed.wrapping_mul(6364136223846793005).wrapping_add(1);
        let mut y = [0.0f64; 2];
        (0..n)
            .map(|_| {
                s = s
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let u = (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
                // A lightly damped two-pole resonator near fs/5 on white noise.
                let v = u + 1.6 * y[0] - 0.9 * y[1];
                y[1] = y[0];
                y[0] = v;
                v + 0.3 * u
            })
            .collect()
    }

    /// Band-limited interpolation by `up` (zero-padded spectrum).
    fn upsample(x: &[f64], up: usize) -> Vec<f64> {
        let n = x.len();
        let spec = rfft(x, 0.0);
        let m = n * up;
        let mut big = vec![realfft::num_complex::Complex::<f64>::default(); m / 2 + 1];
        for (b, c) in big.iter_mut().zip(&spec) {
            *b = *c * up as f64;
        }
        if let Some(c) = big.get_mut(n / 2) {
            c.im = 0.0;
        }
        big[0].im = 0.0;
        let plan = plan_c2r(m);
        let mut out = plan.make_output_vec();
        plan.process(&mut big, &mut out).expect("lengths");
        out.iter().map(|v| v / m as f64).collect()
    }

    #[test]
    fn a_full_band_record_has_no_edge() {
        for seed in 1..4 {
            assert_eq!(content_edge(&record(48_000, seed), 12_000.0), None);
        }
    }

    /// A 12 kHz record resampled to 48 kHz holds nothing above 6 kHz: the edge is found
    /// within one band of 6 kHz, and the low-pass leaves the record as it was.
    #[test]
    fn a_resampled_record_ends_at_its_old_nyquist() {
        let x = upsample(&record(24_000, 7), 4);
        let e = content_edge(&x, 48_000.0).expect("an edge");
        let sixth = 2f64.powf(1.0 / 6.0);
        assert!(e > 6000.0 / sixth && e < 6000.0 * sixth, "{e}");
        let y = low_pass(&x, 48_000.0, e);
        let err = x
            .iter()
            .zip(&y)
            .map(|(a, b)| (a - b).powi(2))
            .sum::<f64>()
            .sqrt();
        let norm = x.iter().map(|a| a * a).sum::<f64>().sqrt();
        assert!(err < 1e-3 * norm, "{err} vs {norm}");
    }

    /// The low-pass removes a tone above the edge and keeps one below it.
    #[test]
    fn low_pass_keeps_the_band_below_the_edge() {
        let fs = 10_000.0;
        let n = 10_000;
        let tone = |f: f64| -> Vec<f64> {
            (0..n)
                .map(|i| (2.0 * std::f64::consts::PI * f * i as f64 / fs).sin())
                .collect()
        };
        let (lo, hi) = (tone(500.0), tone(3000.0));
        let x: Vec<f64> = lo.iter().zip(&hi).map(|(a, b)| a + b).collect();
        let y = low_pass(&x, fs, 1000.0);
        let worst = y
            .iter()
            .zip(&lo)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(worst < 1e-9, "{worst}");
    }
}
