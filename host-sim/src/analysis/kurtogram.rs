//! Spectral kurtosis (Antoni 2006) and the fast kurtogram (Antoni 2007),
//! used to pick the demodulation band for envelope analysis.

use super::envelope::band_bins;
use super::error::{bad, check_fs, check_signal, AnalysisError};
use super::fft::{band_envelope, rfft, rfft_windowed};
use super::spectrum::{Spectrum, SpectrumKind};
use super::stats::mean;
use super::window::Window;
use realfft::num_complex::Complex;
use serde::Serialize;

/// Minimum number of samples of the (decimated) complex envelope of the
/// narrowest kurtogram band, so that its kurtosis is meaningful.
const MIN_BAND_SAMPLES: usize = 32;
/// Largest accepted `max_level` of the fast kurtogram.
const MAX_LEVEL: usize = 16;

/// Kurtosis of a complex signal, `E|c|⁴ / (E|c|²)² - 2`: 0 for circular
/// complex Gaussian noise, -1 for a constant-modulus signal (a pure tone),
/// large and positive for an impulsive one (Antoni 2006). 0 if all zero.
fn complex_kurtosis(c: &[Complex<f64>]) -> f64 {
    let (mut m2, mut m4) = (0.0, 0.0);
    for v in c {
        let p = v.norm_sqr();
        m2 += p;
        m4 += p * p;
    }
    if m2 == 0.0 {
        return 0.0;
    }
    let nf = c.len() as f64;
    (m4 / nf) / (m2 / nf).powi(2) - 2.0
}

/// Error unless `x` has at least two distinct values.
pub(crate) fn check_not_constant(x: &[f64]) -> Result<(), AnalysisError> {
    if x.iter().all(|v| *v == x[0]) {
        Err(AnalysisError::Constant {
            value: x[0],
            what: "spectral kurtosis",
        })
    } else {
        Ok(())
    }
}

/// Spectral kurtosis by the short-time Fourier transform (Antoni 2006, "The
/// spectral kurtosis: a useful tool for characterising non-stationary
/// signals"): `SK(f) = <|X(t,f)|⁴> / <|X(t,f)|²>² - 2` over Hann-windowed
/// segments of `nperseg` samples with 75 % overlap (hop `nperseg/4`).
/// Dimensionless, one-sided, `df = fs / nperseg`: ≈ 0 for Gaussian noise,
/// -1 for a stationary tone, positive where the signal is impulsive.
/// The DC and Nyquist bins are real-valued and use the real normalisation
/// `<X⁴>/<X²>² - 3`, also 0 for Gaussian noise.
/// Errors: bad `fs`, `nperseg < 4`, fewer than `nperseg` samples,
/// non-finite or constant signal.
pub fn spectral_kurtosis(x: &[f64], fs: f64, nperseg: usize) -> Result<Spectrum, AnalysisError> {
    check_fs(fs)?;
    if nperseg < 4 {
        return Err(bad("nperseg", ">= 4", nperseg));
    }
    check_signal(x, nperseg, &format!("nperseg={nperseg}"))?;
    check_not_constant(x)?;
    let w = Window::Hann.cached(nperseg);
    let hop = nperseg / 4;
    let offset = mean(x);
    let bins = nperseg / 2 + 1;
    let (mut m2, mut m4) = (vec![0.0; bins], vec![0.0; bins]);
    let mut start = 0;
    while start + nperseg <= x.len() {
        let spec = rfft_windowed(&x[start..start + nperseg], &w, offset);
        for (k, c) in spec.iter().enumerate() {
            let p = c.norm_sqr();
            m2[k] += p;
            m4[k] += p * p;
        }
        start += hop;
    }
    let segments = (1 + (x.len() - nperseg) / hop) as f64;
    let values = m2
        .iter()
        .zip(&m4)
        .enumerate()
        .map(|(k, (&a, &b))| {
            // DC and Nyquist bins are real: Gaussian kurtosis 3, not 2.
            let gaussian = if k == 0 || 2 * k == nperseg { 3.0 } else { 2.0 };
            if a > 0.0 {
                (b / segments) / (a / segments).powi(2) - gaussian
            } else {
                0.0
            }
        })
        .collect();
    Ok(Spectrum {
        df: fs / nperseg as f64,
        values,
        kind: SpectrumKind::SpectralKurtosis,
    })
}

/// Result of [`fast_kurtogram`].
#[derive(Debug, Clone, Serialize)]
pub struct Kurtogram {
    /// Number of dyadic levels analysed (`max_level`); the grid has
    /// `2 * levels` rows.
    pub levels: usize,
    /// Band with the largest kurtosis, `(lo, hi)` Hz.
    pub best_band: (f64, f64),
    /// Kurtosis of the complex envelope in `best_band` (dimensionless, 0 for
    /// Gaussian noise).
    pub best_kurtosis: f64,
    /// Level of the best band, `log2(number of bands in its row)`.
    pub best_level: f64,
    /// Kurtosis per band, one row per level in increasing order of level
    /// (see `level_values`); row `r` splits (0, fs/2) into `grid[r].len()`
    /// equal bands, lowest frequency first.
    pub grid: Vec<Vec<f64>>,
    /// Level of each row: 0, 1, log2 3 ≈ 1.6, 2, log2 6 ≈ 2.6, 3, ... `levels`
    /// (`log2(fs/2 / row width)`; for [`hz_grid_kurtogram`] a label only).
    pub level_values: Vec<f64>,
    /// Width of the cells of each row, Hz: cell `i` of row `r` is
    /// `(i · row_width_hz[r], (i + 1) · row_width_hz[r])`.
    pub row_width_hz: Vec<f64>,
    /// Upper limit of the grid, Hz (`fs/2` for [`fast_kurtogram`]; see
    /// [`hz_grid_kurtogram`]): no cell ends above it.
    pub span_hz: f64,
    /// Sampling frequency, Hz.
    pub fs: f64,
}

/// Cell widths of the rate-independent grid are `GRID_BASE_HZ[j] · 2^k` Hz (any integer
/// `k`): the 1/3-binary widths of Antoni's (2007) tree on (0, 6 kHz), i.e. the fast
/// kurtogram of a 12 kHz record, on which the detector was fixed (and also that of 24, 48
/// and 96 kHz records), but fixed in Hz instead of in fractions of `fs/2`.
pub const GRID_BASE_HZ: [f64; 2] = [1000.0, 1500.0];

/// Highest frequency a demodulation band may reach, Hz. General-purpose accelerometers
/// are specified flat (±3 dB) up to about 10-20 kHz, with the mounted resonance and the
/// acquisition's anti-alias roll-off above; the bearing resonances used in envelope
/// analysis lie in the kHz range below that (Randall & Antoni 2011, MSSP 25, section 3).
/// A record's cells next to its Nyquist frequency (e.g. 23-24 kHz at 48 kHz, where the
/// CWRU baseline's FE channel shows a band kurtosis of 1484, an artefact) are so excluded.
pub const MAX_BAND_HZ: f64 = 20_000.0;

/// Power below this fraction of a reference (the whole record's, for a band; the mean bin's,
/// for one bin) is nothing but rounding (-120 dB: double-precision FFT round-off lies near
/// -300 dB, float32 storage near -140 dB, any real acquisition's noise far above). A
/// kurtogram cell holding no more is not admissible (its kurtosis is that of round-off),
/// and cepstral pre-whitening sets such a bin to zero instead of raising it to unit
/// magnitude.
pub const ROUNDING_FLOOR: f64 = 1e-12;

/// Power `Σ|X_k|²` of the bins of `band` (Hz) in `spec`, the one-sided spectrum of `n`
/// samples at `fs` Hz (0 if the band holds no bin).
pub(crate) fn band_power(spec: &[Complex<f64>], n: usize, fs: f64, band: (f64, f64)) -> f64 {
    match band_bins(band, fs, n) {
        Ok((k0, k1)) => spec
            .get(k0..=k1.min(spec.len().saturating_sub(1)))
            .map_or(0.0, |b| b.iter().map(Complex::norm_sqr).sum()),
        Err(_) => 0.0,
    }
}

/// Width of the chunks in which [`content_edge_hz`] measures the spectrum, Hz.
pub const CONTENT_CHUNK_HZ: f64 = 100.0;
/// A chunk whose mean power is below this fraction of the largest chunk's (-80 dB) holds
/// no content (e.g. above the original Nyquist frequency of a resampled record).
const CONTENT_FLOOR: f64 = 1e-8;

/// Upper edge, Hz, of the record's spectral content: the upper edge of the highest
/// 100 Hz chunk (chunks aligned at 0 Hz, so the same edges at every sample rate) whose mean
/// power `|X|²` is at least 1e-8 of the largest chunk's, capped at `fs/2`. For a record
/// band-limited below `fs/2` (upsampled, or behind a steep anti-alias filter) this is
/// where the content ends; otherwise `fs/2`. `spec`: one-sided spectrum of `n` samples.
pub fn content_edge_hz(spec: &[Complex<f64>], n: usize, fs: f64) -> f64 {
    let nyquist = fs / 2.0;
    if n < 2 || spec.is_empty() || fs.is_nan() || fs <= 0.0 {
        return nyquist.max(0.0);
    }
    let df = fs / n as f64;
    let chunks = (nyquist / CONTENT_CHUNK_HZ).ceil().max(1.0) as usize;
    let (mut sum, mut count) = (vec![0.0f64; chunks], vec![0usize; chunks]);
    for (k, c) in spec.iter().enumerate().skip(1) {
        let i = ((k as f64 * df / CONTENT_CHUNK_HZ) as usize).min(chunks - 1);
        sum[i] += c.norm_sqr();
        count[i] += 1;
    }
    let mean: Vec<f64> = sum
        .iter()
        .zip(&count)
        .map(|(s, &c)| if c > 0 { s / c as f64 } else { 0.0 })
        .collect();
    let peak = mean
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max);
    if peak <= 0.0 {
        return nyquist;
    }
    match mean.iter().rposition(|&m| m >= CONTENT_FLOOR * peak) {
        Some(i) => ((i + 1) as f64 * CONTENT_CHUNK_HZ).min(nyquist),
        None => nyquist,
    }
}

/// Kurtogram on a band grid fixed in Hz (issue 12: the same record at any sample rate
/// sees the same candidate bands). Rows are the widths `w = GRID_BASE_HZ[j] · 2^k` with
/// `min_width_hz <= w <= span_hz`, narrowest `max_rows` kept, in decreasing order of width
/// (as the fast kurtogram's levels); row `r` holds the cells `(i·w, (i+1)·w)` that end at or
/// below `span_hz` Hz. Each cell's kurtosis is that of its complex envelope, computed
/// exactly as in [`fast_kurtogram`] (ideal FFT-domain band, decimated envelope) from
/// `spec`, the one-sided spectrum of the mean-removed record of `n` samples at `fs` Hz.
/// Cells with no FFT bin get kurtosis 0. `level_values[r] = log2(fs/2 / w)`.
/// No width in `[min_width_hz, span_hz]` gives an empty grid (best band `(0, span)`,
/// kurtosis 0). Errors: bad `fs`, `n < 2`, a `spec` of other than `n/2 + 1` bins,
/// non-positive or non-finite `min_width_hz` or `span_hz`.
pub fn hz_grid_kurtogram(
    spec: &[Complex<f64>],
    n: usize,
    fs: f64,
    min_width_hz: f64,
    span_hz: f64,
    max_rows: usize,
) -> Result<Kurtogram, AnalysisError> {
    check_fs(fs)?;
    if n < 2 || spec.len() != n / 2 + 1 {
        return Err(bad(
            "spectrum length",
            "n/2 + 1 bins of n >= 2 samples",
            spec.len(),
        ));
    }
    let nyquist = fs / 2.0;
    let span = span_hz.min(nyquist);
    if !(min_width_hz > 0.0 && min_width_hz.is_finite() && span > 0.0 && span.is_finite()) {
        return Err(bad(
            "band widths, Hz",
            "0 < min width, span finite",
            min_width_hz,
        ));
    }
    // Every grid width in [min_width_hz, span], narrowest first.
    let mut widths = Vec::new();
    for base in GRID_BASE_HZ {
        let mut w = base;
        while w / 2.0 >= min_width_hz - 1e-9 {
            w /= 2.0;
        }
        while w < min_width_hz - 1e-9 {
            w *= 2.0;
        }
        while w <= span + 1e-9 {
            widths.push(w);
            w *= 2.0;
        }
    }
    widths.sort_by(f64::total_cmp);
    widths.truncate(max_rows.max(1));
    widths.reverse();
    let mut grid = Vec::with_capacity(widths.len());
    let mut best = (f64::NEG_INFINITY, 0usize, 0usize);
    // Cell `i` of width `w`, its top edge at most the span: a span a rounding below a
    // whole number of widths (a rate of 11 999.999 999 999 998 Hz, read from a time
    // column) keeps its top cell, which must not reach past Nyquist.
    let cell = |i: usize, w: f64| (i as f64 * w, ((i + 1) as f64 * w).min(span));
    for (r, &w) in widths.iter().enumerate() {
        let cells = ((span + 1e-9) / w).floor() as usize;
        let row: Vec<f64> = (0..cells)
            .map(|i| band_kurtosis(spec, n, fs, cell(i, w)))
            .collect();
        best = best_cell(best, r, &row);
        grid.push(row);
    }
    let (best_kurtosis, r, i) = best;
    let w = widths.get(r).copied().unwrap_or(span);
    let narrowest = widths.last().copied().unwrap_or(span);
    Ok(Kurtogram {
        levels: (nyquist / narrowest).log2().ceil().max(0.0) as usize,
        best_band: cell(i, w),
        best_kurtosis: if best_kurtosis.is_finite() {
            best_kurtosis
        } else {
            0.0
        },
        best_level: (nyquist / w).log2(),
        level_values: widths.iter().map(|w| (nyquist / w).log2()).collect(),
        row_width_hz: widths,
        span_hz: span,
        grid,
        fs,
    })
}

/// Fast kurtogram (Antoni 2007, "Fast computation of the kurtogram for the
/// detection of transient faults", MSSP 21) on the 1/3-binary tree of bands:
/// level 0 is the whole band (0, fs/2), level k splits it into 2^k equal
/// bands, and the intermediate levels k + log2(3) - 1 (≈ k.6) into 3·2^(k-1).
///
/// Implementation (documented simplification): instead of Antoni's cascade
/// of quasi-analytic FIR filters, each band is cut by an ideal FFT-domain
/// filter from one FFT of the whole record and its complex envelope is
/// obtained, critically decimated, by an inverse FFT of the band's bins
/// (zero-padded to a fast length). The kurtosis of that complex envelope,
/// `E|c|⁴/(E|c|²)² - 2`, fills the grid. Cost: one FFT of the record plus
/// FFTs totalling about n/2 points per row.
///
/// Errors: bad `fs`, `max_level` outside 1..=16, a signal too short for the
/// narrowest band to have 32 envelope samples (`32 · 2^(max_level+1)`
/// samples), non-finite or constant signal.
pub fn fast_kurtogram(x: &[f64], fs: f64, max_level: usize) -> Result<Kurtogram, AnalysisError> {
    fast_kurtogram_and_spectrum(x, fs, max_level).map(|(kg, _)| kg)
}

/// [`fast_kurtogram`] and the one-sided spectrum it was cut from (`rfft(x, mean(x))`,
/// `n/2 + 1` bins, unnormalised), for a caller that needs that spectrum too.
pub(crate) fn fast_kurtogram_and_spectrum(
    x: &[f64],
    fs: f64,
    max_level: usize,
) -> Result<(Kurtogram, Vec<Complex<f64>>), AnalysisError> {
    check_fs(fs)?;
    if !(1..=MAX_LEVEL).contains(&max_level) {
        return Err(bad("max_level", &format!("in 1..={MAX_LEVEL}"), max_level));
    }
    let need = MIN_BAND_SAMPLES << (max_level + 1);
    check_signal(x, need, &format!("max_level={max_level}"))?;
    check_not_constant(x)?;
    let n = x.len();
    let spec = rfft(x, mean(x));
    // Number of bands per row: 1, 2, 3, 4, 6, 8, ..., 2^max_level.
    let mut row_bands = vec![1usize];
    for k in 1..=max_level {
        if k >= 2 {
            row_bands.push(3 << (k - 2));
        }
        row_bands.push(1 << k);
    }
    let nyquist = fs / 2.0;
    let mut grid = Vec::with_capacity(row_bands.len());
    let mut best = (f64::NEG_INFINITY, 0usize, 0usize);
    for (r, &nb) in row_bands.iter().enumerate() {
        let width = nyquist / nb as f64;
        let row: Vec<f64> = (0..nb)
            .map(|i| {
                let band = (i as f64 * width, ((i + 1) as f64 * width).min(nyquist));
                band_kurtosis(&spec, n, fs, band)
            })
            .collect();
        best = best_cell(best, r, &row);
        grid.push(row);
    }
    let (best_kurtosis, r, i) = best;
    let width = nyquist / row_bands[r] as f64;
    let kg = Kurtogram {
        levels: max_level,
        best_band: (i as f64 * width, (i + 1) as f64 * width),
        best_kurtosis,
        best_level: (row_bands[r] as f64).log2(),
        grid,
        level_values: row_bands.iter().map(|&b| (b as f64).log2()).collect(),
        row_width_hz: row_bands.iter().map(|&b| nyquist / b as f64).collect(),
        span_hz: nyquist,
        fs,
    };
    Ok((kg, spec))
}

/// Kurtosis of the complex envelope of `band` (Hz) cut from `spec`, the one-sided spectrum
/// of `n` samples at `fs` Hz, as in the kurtogram's cells; 0 if the band holds no bin.
pub(crate) fn band_kurtosis(spec: &[Complex<f64>], n: usize, fs: f64, band: (f64, f64)) -> f64 {
    match band_bins(band, fs, n) {
        Ok((k0, k1)) if k1 < spec.len() => {
            let k = complex_kurtosis(&band_envelope(spec, n, k0, k1, fast_len(k1 - k0 + 1)));
            if k.is_finite() {
                k
            } else {
                0.0
            }
        }
        _ => 0.0,
    }
}

/// `best` (kurtosis, row, cell) updated with the cells of `row` (row index `r`): the first
/// strictly larger kurtosis wins, as the grids scan.
fn best_cell(mut best: (f64, usize, usize), r: usize, row: &[f64]) -> (f64, usize, usize) {
    for (i, &k) in row.iter().enumerate() {
        if k > best.0 {
            best = (k, r, i);
        }
    }
    best
}

/// Smallest `2^a 3^b 5^c >= m` (a length rustfft transforms quickly).
fn fast_len(m: usize) -> usize {
    let mut best = m.next_power_of_two();
    let mut p5 = 1;
    while p5 < best {
        let mut p35 = p5;
        while p35 < best {
            let mut len = p35;
            while len < m {
                len *= 2;
            }
            best = best.min(len);
            p35 *= 3;
        }
        p5 *= 5;
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::synth::{gaussian_noise, sine, FaultSignal};
    use proptest::prelude::*;

    fn impulsive(fs: f64, n: usize) -> Vec<f64> {
        FaultSignal {
            fs,
            fault_hz: 100.0,
            mod_hz: 0.0,
            mod_depth: 0.0,
            resonance_hz: 3000.0,
            damping: 0.03,
            impulse_amp: 1.0,
            noise_sigma: 0.1,
            seed: 11,
            jitter: 0.0,
        }
        .generate(n)
    }

    #[test]
    fn fast_len_is_smooth_and_minimal() {
        assert_eq!(fast_len(1), 1);
        assert_eq!(fast_len(7), 8);
        assert_eq!(fast_len(11), 12);
        assert_eq!(fast_len(7501), 7680);
        assert_eq!(fast_len(1024), 1024);
    }

    #[test]
    fn sk_of_noise_tone_and_impulses() {
        let fs = 12_000.0;
        let noise = gaussian_noise(120_000, 1.0, 5);
        let sk = spectral_kurtosis(&noise, fs, 256).unwrap();
        assert_eq!(sk.kind, SpectrumKind::SpectralKurtosis);
        assert!(sk.values.iter().all(|v| v.abs() < 0.3));
        let mid = &sk.values[5..124];
        assert!(mid.iter().all(|v| v.abs() < 0.15), "{mid:?}");
        // Tone at a bin centre (1500 Hz = bin 32 of 256): constant modulus.
        let x: Vec<f64> = sine(120_000, fs, 1500.0, 5.0, 0.2)
            .iter()
            .zip(&noise)
            .map(|(a, b)| a + 0.01 * b)
            .collect();
        let sk = spectral_kurtosis(&x, fs, 256).unwrap();
        assert!((sk.values[32] + 1.0).abs() < 0.01, "{}", sk.values[32]);
        // Impulsive resonance: SK maximal near 3 kHz.
        // Impulses every 10 ms: 64-sample (5.3 ms) segments hold 0 or 1 each.
        let sk = spectral_kurtosis(&impulsive(fs, 120_000), fs, 64).unwrap();
        let k = (0..sk.len()).fold(0, |b, k| if sk.values[k] > sk.values[b] { k } else { b });
        // SK is flat-topped over the resonance, where the impulses dominate.
        assert!(
            (sk.freq(k) - 3000.0).abs() <= 2.5 * sk.df,
            "max at {}",
            sk.freq(k)
        );
        assert!(sk.values[k] > 1.0, "{:?}", sk.values);
        // Far from the resonance the noise dominates: SK near 0.
        assert!(sk.values[..4].iter().all(|v| v.abs() < 0.15));
    }

    #[test]
    fn kurtogram_finds_the_resonance_band() {
        let fs = 12_000.0;
        // Strong tones at 500 Hz and 4.7 kHz mask the impulses in wide bands.
        let x: Vec<f64> = impulsive(fs, 48_000)
            .iter()
            .zip(sine(48_000, fs, 500.0, 2.0, 0.0))
            .zip(sine(48_000, fs, 4700.0, 1.0, 0.0))
            .map(|((a, b), c)| a + b + c)
            .collect();
        let kg = fast_kurtogram(&x, fs, 5).unwrap();
        assert_eq!(kg.grid.len(), 10);
        assert_eq!(kg.level_values.len(), 10);
        assert_eq!(
            kg.grid.iter().map(Vec::len).collect::<Vec<_>>(),
            [1, 2, 3, 4, 6, 8, 12, 16, 24, 32]
        );
        let (lo, hi) = kg.best_band;
        assert!(lo < 3000.0 && 3000.0 < hi, "best band {lo}..{hi}");
        // 3 kHz lies on a band edge at levels >= 1.6, so (2, 4) kHz is the
        // narrowest band centred on it.
        assert!(hi - lo <= 2000.0, "best band too wide: {lo}..{hi}");
        // Noise-free, a ringing of time constant tau every T gives T/tau - 2 = 3.6.
        assert!(kg.best_kurtosis > 2.0, "{}", kg.best_kurtosis);
        assert!(kg.grid[0][0] < 0.5, "whole band {}", kg.grid[0][0]);
        assert!(
            (kg.best_level - 3f64.log2()).abs() < 1e-12,
            "{}",
            kg.best_level
        );
    }

    #[test]
    fn kurtogram_of_noise_and_tone() {
        let fs = 10_000.0;
        let noise = gaussian_noise(100_000, 1.0, 9);
        let kg = fast_kurtogram(&noise, fs, 4).unwrap();
        assert!(kg.grid[0][0].abs() < 0.05, "{}", kg.grid[0][0]);
        assert!(kg.grid.iter().flatten().all(|k| k.abs() < 0.4));
        // A pure tone has a constant complex envelope: kurtosis -1.
        let tone = sine(100_000, fs, 1234.0, 1.0, 0.0);
        let kg = fast_kurtogram(&tone, fs, 3).unwrap();
        for (row, level) in kg.grid.iter().zip(&kg.level_values) {
            let i = (1234.0 / (fs / 2.0) * row.len() as f64) as usize;
            assert!((row[i] + 1.0).abs() < 1e-6, "level {level}: {}", row[i]);
        }
    }

    #[test]
    fn bad_arguments_are_errors() {
        let x = gaussian_noise(1000, 1.0, 1);
        assert!(matches!(
            fast_kurtogram(&x, 1000.0, 5),
            Err(AnalysisError::TooShort { need: 2048, .. })
        ));
        assert!(fast_kurtogram(&x, 1000.0, 0).is_err());
        assert!(fast_kurtogram(&x, 1000.0, 99).is_err());
        assert!(fast_kurtogram(&x, f64::INFINITY, 2).is_err());
        assert!(matches!(
            fast_kurtogram(&[1.0; 5000], 1000.0, 2),
            Err(AnalysisError::Constant { .. })
        ));
        assert!(spectral_kurtosis(&x, 1000.0, 2).is_err());
        assert!(spectral_kurtosis(&x[..100], 1000.0, 256).is_err());
        assert!(spectral_kurtosis(&[0.0; 500], 1000.0, 64).is_err());
    }

    #[test]
    fn hz_grid_at_12_khz_is_the_fast_kurtograms_grid() -> Result<(), AnalysisError> {
        let fs = 12_000.0;
        let x = impulsive(fs, 48_000);
        let old = fast_kurtogram(&x, fs, 3)?;
        let spec = rfft(&x, mean(&x));
        let kg = hz_grid_kurtogram(&spec, x.len(), fs, 1000.0, 6000.0, 12)?;
        // The 4000 Hz row has one cell, (0, 4000), which is never admissible (it starts in
        // the fault zone); every other row is a row of the fast kurtogram.
        assert_eq!(
            kg.row_width_hz,
            [6000.0, 4000.0, 3000.0, 2000.0, 1500.0, 1000.0]
        );
        assert_eq!(kg.grid[1].len(), 1);
        let mut compared = 0;
        for (row, w) in kg.grid.iter().zip(&kg.row_width_hz) {
            let Some(r) = old.row_width_hz.iter().position(|v| (v - w).abs() < 1e-9) else {
                continue;
            };
            assert_eq!(row.len(), old.grid[r].len());
            for (a, b) in row.iter().zip(&old.grid[r]) {
                assert!((a - b).abs() < 1e-12, "{w} Hz: {a} {b}");
            }
            compared += 1;
        }
        assert_eq!(compared, 5);
        Ok(())
    }

    /// A rate a rounding below a whole number (as a time column gives it: 11 999.999 999 999
    /// 998 Hz) keeps the grid of the whole number, and its top cell ends at Nyquist, not a
    /// rounding beyond it (the envelope band of such a record was refused, exit 2). With a
    /// smallest width of 6 kHz the grid is that one cell, so it is the best band.
    #[test]
    fn a_rate_a_rounding_below_a_whole_number_keeps_its_top_cell_inside_nyquist(
    ) -> Result<(), AnalysisError> {
        let fs = 11_999.999_999_999_998;
        let x = impulsive(12_000.0, 48_000);
        let spec = rfft(&x, mean(&x));
        let kg = hz_grid_kurtogram(&spec, x.len(), fs, 1000.0, fs / 2.0, 12)?;
        assert_eq!(
            kg.row_width_hz,
            [6000.0, 4000.0, 3000.0, 2000.0, 1500.0, 1000.0]
        );
        let top = hz_grid_kurtogram(&spec, x.len(), fs, 6000.0, fs / 2.0, 12)?;
        assert_eq!(top.row_width_hz, [6000.0]);
        assert_eq!(top.best_band, (0.0, fs / 2.0));
        crate::analysis::error::check_band(top.best_band, fs)
    }

    #[test]
    #[cfg(feature = "app")] // the FFT resampler is in cwru_benchmark
    fn hz_grid_and_content_edge_do_not_move_with_the_rate() -> Result<(), AnalysisError> {
        let fs = 12_000.0;
        let x = impulsive(fs, 48_000);
        let spec = rfft(&x, mean(&x));
        assert_eq!(content_edge_hz(&spec, x.len(), fs), 6000.0);
        let kg = hz_grid_kurtogram(&spec, x.len(), fs, 1000.0, 6000.0, 12)?;
        for rate in [25_600.0, 48_000.0, 97_656.25] {
            let m = (x.len() as f64 * rate / fs).round() as usize;
            let y = crate::cwru_benchmark::resample_fft(&x, m);
            let sy = rfft(&y, mean(&y));
            // Nothing above 6 kHz: the content ends where the 12 kHz record's Nyquist was.
            let edge = content_edge_hz(&sy, m, rate);
            assert_eq!(edge, 6000.0, "at {rate} Hz");
            let ky = hz_grid_kurtogram(&sy, m, rate, 1000.0, edge, 12)?;
            assert_eq!(ky.row_width_hz, kg.row_width_hz, "at {rate} Hz");
            assert_eq!(ky.best_band, kg.best_band, "at {rate} Hz");
            for (r, (ra, rb)) in ky.grid.iter().zip(&kg.grid).enumerate() {
                let w = kg.row_width_hz[r];
                for (i, (a, b)) in ra.iter().zip(rb).enumerate() {
                    // Cells ending at 6 kHz lose the 12 kHz record's Nyquist bin, which the
                    // resampling drops (measured: up to 0.055 on kurtoses of 0.1-2.5).
                    let tol = if ((i + 1) as f64 * w - 6000.0).abs() < 1e-9 {
                        0.1
                    } else {
                        1e-9 * (1.0 + b.abs())
                    };
                    assert!(
                        (a - b).abs() < tol,
                        "at {rate} Hz, {w} Hz cell {i}: {a} {b}"
                    );
                }
            }
        }
        // No width fits: an empty grid, not an error; bad spectra are errors.
        let empty = hz_grid_kurtogram(&spec, x.len(), fs, 5000.0, 5500.0, 12)?;
        assert!(empty.grid.is_empty() && empty.best_kurtosis == 0.0);
        assert!(hz_grid_kurtogram(&spec[1..], x.len(), fs, 1000.0, 6000.0, 12).is_err());
        assert!(hz_grid_kurtogram(&spec, x.len(), fs, f64::NAN, 6000.0, 12).is_err());
        Ok(())
    }

    proptest! {
        #[test]
        fn finite_input_gives_finite_kurtogram(x in prop::collection::vec(-1e3f64..1e3, 256..600)) {
            if let Ok(kg) = fast_kurtogram(&x, 1000.0, 2) {
                prop_assert!(kg.grid.iter().flatten().all(|k| k.is_finite()));
                prop_assert!(kg.best_kurtosis.is_finite());
            }
            if let Ok(sk) = spectral_kurtosis(&x, 1000.0, 32) {
                prop_assert!(sk.values.iter().all(|k| k.is_finite()));
            }
        }
    }
}
