//! Frequency spectra: Welch power spectral density and single-FFT amplitude
//! spectrum, on a uniform one-sided frequency grid.

use super::error::{bad, check_fs, check_signal, AnalysisError};
use super::fft::{one_sided_factor, rfft_windowed};
use super::stats::mean;
use super::window::Window;
use serde::{Deserialize, Serialize};

/// What the values of a [`Spectrum`] are.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum SpectrumKind {
    /// One-sided power spectral density, units²/Hz (integrates to the variance).
    Psd,
    /// Peak amplitude of a sinusoid centred on the bin, signal units.
    Amplitude,
    /// Spectral kurtosis, dimensionless (0 for Gaussian noise; Antoni 2006).
    SpectralKurtosis,
}

/// A one-sided spectrum on a uniform grid: bin `k` is at `k * df` Hz.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Spectrum {
    /// Bin spacing, Hz per bin.
    pub df: f64,
    /// Values; bin `k` is at frequency `k * df` (units depend on `kind`).
    pub values: Vec<f64>,
    /// Units / meaning of `values`.
    pub kind: SpectrumKind,
}

impl Spectrum {
    /// Frequency of bin `k`, Hz.
    pub fn freq(&self, k: usize) -> f64 {
        k as f64 * self.df
    }

    /// Index of the bin nearest to `f` Hz, clamped to the spectrum
    /// (negative or NaN frequencies give 0).
    pub fn bin_of(&self, f: f64) -> usize {
        let last = self.values.len().saturating_sub(1);
        let k = (f / self.df).round();
        if k.is_nan() || k <= 0.0 {
            0
        } else if k >= last as f64 {
            last
        } else {
            k as usize
        }
    }

    /// Number of bins.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// True if the spectrum has no bins.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// Highest frequency represented, Hz.
    pub fn f_max(&self) -> f64 {
        self.freq(self.len().saturating_sub(1))
    }
}

/// Parameters of Welch's averaged modified periodogram.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct WelchParams {
    /// Segment length, samples (>= 2).
    pub nperseg: usize,
    /// Overlap between segments as a fraction of `nperseg`, in [0, 0.95].
    pub overlap: f64,
    /// Window applied to each segment.
    pub window: Window,
}

impl Default for WelchParams {
    /// 4096-sample Hann segments with 50 % overlap.
    fn default() -> Self {
        WelchParams {
            nperseg: 4096,
            overlap: 0.5,
            window: Window::Hann,
        }
    }
}

/// One-sided power spectral density by Welch's method (Welch 1967, "The use
/// of fast Fourier transform for the estimation of power spectra").
///
/// Each segment has its mean removed, is windowed and transformed; the
/// periodograms are averaged with density scaling `|X|² / (fs Σw²)`, doubled
/// for bins other than DC and Nyquist, so that `Σ PSD·df` equals the variance
/// of the signal (Parseval). Units: signal units²/Hz; `df = fs / nperseg`.
pub fn welch_psd(x: &[f64], fs: f64, p: &WelchParams) -> Result<Spectrum, AnalysisError> {
    check_fs(fs)?;
    if p.nperseg < 2 {
        return Err(bad("nperseg", ">= 2", p.nperseg));
    }
    if !(0.0..=0.95).contains(&p.overlap) {
        return Err(bad("overlap", "a fraction in [0, 0.95]", p.overlap));
    }
    let n = p.nperseg;
    check_signal(x, n, &format!("nperseg={n}"))?;
    let step = (n - (p.overlap * n as f64).round() as usize).max(1);
    let w = p.window.cached(n);
    let s2: f64 = w.iter().map(|v| v * v).sum();
    let mut acc = vec![0.0; n / 2 + 1];
    let mut segments = 0usize;
    let mut start = 0;
    while start + n <= x.len() {
        let seg = &x[start..start + n];
        let spec = rfft_windowed(seg, &w, mean(seg));
        for (a, c) in acc.iter_mut().zip(&spec) {
            *a += c.norm_sqr();
        }
        segments += 1;
        start += step;
    }
    let scale = 1.0 / (fs * s2 * segments as f64);
    for (k, a) in acc.iter_mut().enumerate() {
        let one_sided = one_sided_factor(k, n);
        *a *= scale * one_sided;
    }
    Ok(Spectrum {
        df: fs / n as f64,
        values: acc,
        kind: SpectrumKind::Psd,
    })
}

/// Amplitude spectrum of the whole record from a single windowed FFT (no
/// zero padding; `df = fs / x.len()`), amplitude-corrected by the window's
/// coherent gain so that a sinusoid of amplitude `A` centred on a bin reads
/// `A` (the DC bin reads the mean). Units: signal units (peak).
/// Needs at least 4 samples.
pub fn amplitude_spectrum(x: &[f64], fs: f64, window: Window) -> Result<Spectrum, AnalysisError> {
    check_fs(fs)?;
    check_signal(x, 4, "an amplitude spectrum")?;
    Ok(amplitude_spectrum_unchecked(x, fs, window))
}

/// [`amplitude_spectrum`] without argument checks (callers have checked).
pub(crate) fn amplitude_spectrum_unchecked(x: &[f64], fs: f64, window: Window) -> Spectrum {
    let n = x.len();
    let w = window.cached(n);
    let gain: f64 = w.iter().sum();
    let spec = rfft_windowed(x, &w, 0.0);
    let values = spec
        .iter()
        .enumerate()
        .map(|(k, c)| {
            let one_sided = one_sided_factor(k, n);
            one_sided * super::fft::magnitude(*c) / gain
        })
        .collect();
    Spectrum {
        df: fs / n as f64,
        values,
        kind: SpectrumKind::Amplitude,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::synth::{gaussian_noise, sine};
    use proptest::prelude::*;

    fn argmax(v: &[f64]) -> usize {
        (0..v.len()).fold(0, |b, k| if v[k] > v[b] { k } else { b })
    }

    #[test]
    fn welch_parseval_noise() {
        let x = gaussian_noise(200_000, 1.5, 7);
        let var = {
            let m = mean(&x);
            x.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / x.len() as f64
        };
        for window in [
            Window::Hann,
            Window::Hamming,
            Window::BlackmanHarris,
            Window::Rectangular,
        ] {
            let p = WelchParams {
                nperseg: 1024,
                overlap: 0.5,
                window,
            };
            let s = welch_psd(&x, 1000.0, &p).unwrap();
            assert_eq!(s.len(), 513);
            assert!((s.df - 1000.0 / 1024.0).abs() < 1e-12);
            let power: f64 = s.values.iter().sum::<f64>() * s.df;
            assert!(
                (power / var - 1.0).abs() < 0.01,
                "{window:?}: {power} vs {var}"
            );
            // White noise: flat PSD at var / (fs/2).
            let mid = s.values[100..400].iter().sum::<f64>() / 300.0;
            assert!((mid / (var / 500.0) - 1.0).abs() < 0.03);
        }
    }

    #[test]
    fn welch_parseval_odd_segments_no_overlap() {
        // Odd nperseg has no Nyquist bin; every non-DC bin is doubled.
        let x = gaussian_noise(255 * 400, 0.7, 8);
        let p = WelchParams {
            nperseg: 255,
            overlap: 0.0,
            window: Window::Rectangular,
        };
        let s = welch_psd(&x, 2.0, &p).unwrap();
        assert_eq!(s.len(), 128);
        // Without overlap or window, Σ PSD·df is exactly the mean of the
        // per-segment variances.
        let seg_var: f64 = x
            .chunks(255)
            .map(|c| {
                let m = mean(c);
                c.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / 255.0
            })
            .sum::<f64>()
            / 400.0;
        let power: f64 = s.values.iter().sum::<f64>() * s.df;
        assert!((power / seg_var - 1.0).abs() < 1e-9, "{power} vs {seg_var}");
    }

    #[test]
    fn welch_sine_power_and_frequency() {
        let fs = 12_000.0;
        let f0 = 1234.5;
        let x = sine(120_000, fs, f0, 2.0, 0.1);
        let s = welch_psd(&x, fs, &WelchParams::default()).unwrap();
        let power: f64 = s.values.iter().sum::<f64>() * s.df;
        assert!((power - 2.0).abs() < 0.02, "power {power}");
        let k = argmax(&s.values);
        assert!((s.freq(k) - f0).abs() <= s.df);
        assert_eq!(s.kind, SpectrumKind::Psd);
    }

    #[test]
    fn amplitude_of_bin_centred_sines() {
        let fs = 10_000.0;
        let n = 10_000; // df = 1 Hz
        let x: Vec<f64> = sine(n, fs, 250.0, 3.0, 0.4)
            .iter()
            .zip(sine(n, fs, 1700.0, 0.5, 1.0))
            .map(|(a, b)| a + b + 0.25)
            .collect();
        for window in [
            Window::Hann,
            Window::Hamming,
            Window::BlackmanHarris,
            Window::Rectangular,
        ] {
            let s = amplitude_spectrum(&x, fs, window).unwrap();
            assert!((s.values[250] - 3.0).abs() < 0.01 * 3.0, "{window:?}");
            assert!((s.values[1700] - 0.5).abs() < 0.01 * 0.5, "{window:?}");
            assert!((s.values[0] - 0.25).abs() < 0.01 * 0.25, "{window:?}");
            assert_eq!(s.bin_of(250.2), 250);
        }
        // Odd length (non power of two) works too.
        let s = amplitude_spectrum(&x[..9_999], fs, Window::Hann).unwrap();
        let k = argmax(&s.values);
        assert!((s.freq(k) - 250.0).abs() <= s.df);
    }

    #[test]
    fn spectrum_accessors() {
        let s = Spectrum {
            df: 0.5,
            values: vec![0.0; 11],
            kind: SpectrumKind::Amplitude,
        };
        assert_eq!(s.freq(4), 2.0);
        assert_eq!(s.bin_of(-3.0), 0);
        assert_eq!(s.bin_of(f64::NAN), 0);
        assert_eq!(s.bin_of(100.0), 10);
        assert_eq!(s.bin_of(1.26), 3);
        assert_eq!(s.f_max(), 5.0);
    }

    #[test]
    fn bad_arguments_are_errors() {
        let x = vec![0.0; 100];
        let p = WelchParams {
            nperseg: 256,
            ..Default::default()
        };
        assert_eq!(
            welch_psd(&x, 1.0, &p).unwrap_err().to_string(),
            "signal has 100 samples, need at least 256 for nperseg=256"
        );
        assert!(welch_psd(&x, -3.0, &p).is_err());
        assert!(welch_psd(&x, f64::NAN, &p).is_err());
        let p = WelchParams {
            nperseg: 16,
            overlap: 0.99,
            ..Default::default()
        };
        assert!(welch_psd(&x, 1.0, &p).is_err());
        assert!(amplitude_spectrum(&[], 1.0, Window::Hann).is_err());
        assert!(amplitude_spectrum(&[1.0, f64::NAN, 0.0, 0.0], 1.0, Window::Hann).is_err());
        // A constant signal is a valid input: zero PSD.
        let p = WelchParams {
            nperseg: 16,
            ..Default::default()
        };
        let s = welch_psd(&[2.0; 64], 1.0, &p).unwrap();
        assert!(s.values.iter().all(|v| v.abs() < 1e-20));
    }

    proptest! {
        #[test]
        fn finite_input_gives_finite_spectra(
            x in prop::collection::vec(-1e3f64..1e3, 64..400),
            nperseg in 2usize..64,
            overlap in 0.0f64..0.95,
        ) {
            let p = WelchParams { nperseg, overlap, window: Window::Hann };
            let s = welch_psd(&x, 100.0, &p).unwrap();
            prop_assert!(s.values.iter().all(|v| v.is_finite() && *v >= 0.0));
            let a = amplitude_spectrum(&x, 100.0, Window::BlackmanHarris).unwrap();
            prop_assert!(a.values.iter().all(|v| v.is_finite()));
        }
    }
}
