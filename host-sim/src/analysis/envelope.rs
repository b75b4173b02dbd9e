//! Envelope analysis: band-pass analytic envelope and envelope spectrum
//! (Randall & Antoni 2011, "Rolling element bearing diagnostics—A tutorial").

use super::error::{check_band, check_fs, check_signal, AnalysisError};
use super::fft::{band_envelope, rfft};
use super::spectrum::{amplitude_spectrum_unchecked, Spectrum};
use super::window::Window;

/// Envelope (magnitude of the analytic signal) of `x` band-passed to
/// `band = (lo, hi)` Hz, at the input's sample rate; signal units.
///
/// The band-pass is ideal (brick-wall) in the FFT domain over the whole
/// record, and the analytic signal is formed by keeping only the positive
/// frequencies, as recommended by Randall & Antoni (2011). The DC bin is
/// never passed. Requires `0 <= lo < hi <= fs/2` and at least one FFT bin
/// (spacing `fs / x.len()`) inside the band; at least 4 samples.
pub fn bandpass_analytic_envelope(
    x: &[f64],
    fs: f64,
    band: (f64, f64),
) -> Result<Vec<f64>, AnalysisError> {
    check_fs(fs)?;
    check_signal(x, 4, "an envelope")?;
    check_band(band, fs)?;
    let n = x.len();
    let (k0, k1) = band_bins(band, fs, n)?;
    let spec = rfft(x, 0.0);
    Ok(band_envelope(&spec, n, k0, k1, n)
        .iter()
        .map(|c| super::fft::magnitude(*c))
        .collect())
}

/// Envelope spectrum of `x`: amplitude spectrum (Hann window, whole record,
/// `df = fs / x.len()`, signal units) of the band-pass analytic envelope
/// with its mean removed (Randall & Antoni 2011). `band = None` uses the
/// whole band (0, fs/2], i.e. the Hilbert envelope of the full signal.
/// A line of amplitude `a` at frequency `f` means the envelope contains
/// `a cos(2 pi f t)`.
pub fn envelope_spectrum(
    x: &[f64],
    fs: f64,
    band: Option<(f64, f64)>,
) -> Result<Spectrum, AnalysisError> {
    let mut env = bandpass_analytic_envelope(x, fs, band.unwrap_or((0.0, fs / 2.0)))?;
    let m = env.iter().sum::<f64>() / env.len() as f64;
    env.iter_mut().for_each(|v| *v -= m);
    Ok(amplitude_spectrum_unchecked(&env, fs, Window::Hann))
}

/// Envelope spectrum in `band` Hz of a record of `n` samples at `fs` Hz given its one-sided
/// spectrum `spec` (`n/2 + 1` bins, as [`super::fft`]'s `rfft`), so that several bands of one
/// record share one forward FFT. `squared`: the spectrum of the squared envelope
/// (Randall & Antoni 2011, section 3.2: the squared envelope, whose spectrum is the one the
/// spectral-kurtosis theory refers to) instead of the envelope; units are signal units
/// (squared with `squared`). The mean of the (squared) envelope is removed and the amplitude
/// spectrum is taken with a Hann window over the whole record, as in [`envelope_spectrum`],
/// which this equals for `squared = false`.
// Used by the `app` modules only.
#[cfg_attr(not(feature = "app"), allow(dead_code))]
pub(crate) fn envelope_spectrum_of_spectrum(
    spec: &[realfft::num_complex::Complex<f64>],
    n: usize,
    fs: f64,
    band: (f64, f64),
    squared: bool,
) -> Result<Spectrum, AnalysisError> {
    envelope_spectrum_and_modulation(spec, n, fs, band, squared).map(|(s, _)| s)
}

/// [`envelope_spectrum_of_spectrum`] and the envelope's modulation: the power of the
/// (squared) envelope about its mean over its mean-square, `var / E[e²]` (0 for a constant
/// envelope, about 0.27 for the envelope of Gaussian noise); 0 for an envelope of zeros.
#[cfg_attr(not(feature = "app"), allow(dead_code))]
pub(crate) fn envelope_spectrum_and_modulation(
    spec: &[realfft::num_complex::Complex<f64>],
    n: usize,
    fs: f64,
    band: (f64, f64),
    squared: bool,
) -> Result<(Spectrum, f64), AnalysisError> {
    check_fs(fs)?;
    check_band(band, fs)?;
    if n < 4 || spec.len() != n / 2 + 1 {
        return Err(AnalysisError::TooShort {
            len: n,
            need: 4,
            what: "an envelope".to_string(),
        });
    }
    let (k0, k1) = band_bins(band, fs, n)?;
    let mut env: Vec<f64> = band_envelope(spec, n, k0, k1, n)
        .iter()
        .map(|c| {
            let m = super::fft::magnitude(*c);
            if squared {
                m * m
            } else {
                m
            }
        })
        .collect();
    let m = env.iter().sum::<f64>() / env.len() as f64;
    let mean_square = env.iter().map(|v| v * v).sum::<f64>() / env.len() as f64;
    env.iter_mut().for_each(|v| *v -= m);
    let var = env.iter().map(|v| v * v).sum::<f64>() / env.len() as f64;
    let modulation = if mean_square > 0.0 {
        var / mean_square
    } else {
        0.0
    };
    Ok((
        amplitude_spectrum_unchecked(&env, fs, Window::Hann),
        modulation,
    ))
}

/// FFT bins `(k0, k1)` (inclusive, DC excluded) of a record of `n` samples
/// at `fs` Hz lying in `band`; error if there are none.
pub(crate) fn band_bins(
    band: (f64, f64),
    fs: f64,
    n: usize,
) -> Result<(usize, usize), AnalysisError> {
    let df = fs / n as f64;
    let k0 = ((band.0 / df).ceil() as usize).max(1);
    let k1 = ((band.1 / df).floor() as usize).min(n / 2);
    if k0 > k1 {
        return Err(AnalysisError::BadBand {
            lo: band.0,
            hi: band.1,
            nyquist: fs / 2.0,
            extra: format!(", and contain at least one FFT bin (spacing {df} Hz)"),
        });
    }
    Ok((k0, k1))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::f64::consts::PI;

    /// Carrier at `fc` modulated by 1 + 0.5 cos(2 pi 50 t) + 0.2 cos(2 pi 100 t + 0.3).
    fn am_signal(fs: f64, n: usize, fc: f64) -> (Vec<f64>, Vec<f64>) {
        let env: Vec<f64> = (0..n)
            .map(|i| {
                let t = i as f64 / fs;
                1.0 + 0.5 * (2.0 * PI * 50.0 * t).cos() + 0.2 * (2.0 * PI * 100.0 * t + 0.3).cos()
            })
            .collect();
        let x = env
            .iter()
            .enumerate()
            .map(|(i, e)| e * (2.0 * PI * fc * i as f64 / fs + 0.7).cos())
            .collect();
        (x, env)
    }

    #[test]
    fn envelope_from_a_shared_spectrum_matches_and_squares() {
        // The shared-spectrum path gives the same envelope spectrum bit for bit, and its
        // squared envelope is the spectrum of env² (lines at 50 and 100 Hz of the known
        // modulation, mean removed): a missing or wrong squaring changes those lines by far
        // more than the tolerance.
        let (fs, n) = (10_000.0, 10_000);
        let (x, env) = am_signal(fs, n, 2000.0);
        let band = (1500.0, 2500.0);
        let spec = rfft(&x, 0.0);
        let plain = envelope_spectrum_of_spectrum(&spec, n, fs, band, false).unwrap();
        let direct = envelope_spectrum(&x, fs, Some(band)).unwrap();
        assert_eq!(plain.df, direct.df);
        assert_eq!(plain.values, direct.values);
        let sq = envelope_spectrum_of_spectrum(&spec, n, fs, band, true).unwrap();
        let e2: Vec<f64> = env.iter().map(|v| v * v).collect();
        let m = e2.iter().sum::<f64>() / n as f64;
        let e2: Vec<f64> = e2.iter().map(|v| v - m).collect();
        let want = amplitude_spectrum_unchecked(&e2, fs, Window::Hann);
        for f in [50.0, 100.0, 150.0, 200.0] {
            let k = (f / sq.df).round() as usize;
            let (got, exp) = (sq.values[k], want.values[k]);
            assert!(
                (got - exp).abs() <= 1e-3 * exp.max(1e-3),
                "{f} Hz: {got} vs {exp}"
            );
        }
        // (1 + 0.5 cos wt + 0.2 cos(2wt + 0.3))² has at 50 Hz the phasor 1.0 + 0.1 e^{0.3i}
        // (from 2 x 0.5 and from the 0.5 x 0.2 cross term), amplitude 1.0959, where the
        // plain envelope has 0.5.
        let k50 = (50.0 / sq.df).round() as usize;
        assert!((sq.values[k50] - 1.0959).abs() < 0.01, "{}", sq.values[k50]);
        assert!(
            (plain.values[k50] - 0.5).abs() < 0.01,
            "{}",
            plain.values[k50]
        );
        assert!(envelope_spectrum_of_spectrum(&spec[..10], n, fs, band, true).is_err());
    }

    #[test]
    fn envelope_of_am_carrier_is_exact() {
        let (x, env) = am_signal(10_000.0, 10_000, 2000.0);
        let e = bandpass_analytic_envelope(&x, 10_000.0, (1500.0, 2500.0)).unwrap();
        let err = e
            .iter()
            .zip(&env)
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(err < 1e-9, "max error {err}");
    }

    #[test]
    fn envelope_spectrum_lines_and_ratio() {
        let fs = 10_000.0;
        let (x, _) = am_signal(fs, 10_000, 2000.0);
        for band in [Some((1500.0, 2500.0)), None] {
            let s = envelope_spectrum(&x, fs, band).unwrap();
            assert!((s.df - 1.0).abs() < 1e-12);
            assert!((s.values[50] - 0.5).abs() < 0.005, "{:?}", s.values[50]);
            assert!((s.values[100] - 0.2).abs() < 0.002, "{:?}", s.values[100]);
            assert!((s.values[50] / s.values[100] - 2.5).abs() < 0.025);
            assert!(s.values[0].abs() < 1e-9, "mean removed");
            let max_other = s
                .values
                .iter()
                .enumerate()
                .filter(|(k, _)| ![49, 50, 51, 99, 100, 101].contains(k))
                .fold(0.0_f64, |m, (_, v)| m.max(*v));
            assert!(max_other < 1e-6, "spurious line {max_other}");
        }
    }

    #[test]
    fn out_of_band_noise_is_rejected() {
        let fs = 10_000.0;
        let (x, env) = am_signal(fs, 10_000, 2000.0);
        // Tone at 4000 Hz outside the band (1500, 2500).
        let y: Vec<f64> = x
            .iter()
            .enumerate()
            .map(|(i, v)| v + 3.0 * (2.0 * PI * 4000.0 * i as f64 / fs).sin())
            .collect();
        let e = bandpass_analytic_envelope(&y, fs, (1500.0, 2500.0)).unwrap();
        let err = e
            .iter()
            .zip(&env)
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(err < 1e-9);
    }

    #[test]
    fn bad_bands_are_errors() {
        let x = vec![1.0; 100];
        assert!(bandpass_analytic_envelope(&x, 100.0, (10.0, 60.0)).is_err());
        assert!(bandpass_analytic_envelope(&x, 100.0, (-1.0, 20.0)).is_err());
        assert!(bandpass_analytic_envelope(&x, 100.0, (20.0, 10.0)).is_err());
        // No bin between 10.2 and 10.8 Hz with df = 1 Hz.
        let e = bandpass_analytic_envelope(&x, 100.0, (10.2, 10.8)).unwrap_err();
        assert!(e.to_string().contains("at least one FFT bin"), "{e}");
        assert!(envelope_spectrum(&[], 100.0, None).is_err());
        assert!(envelope_spectrum(&x, 0.0, None).is_err());
        // Constant signal: zero envelope, zero spectrum.
        let s = envelope_spectrum(&x, 100.0, None).unwrap();
        assert!(s.values.iter().all(|v| v.abs() < 1e-12));
    }

    proptest! {
        #[test]
        fn finite_input_gives_finite_envelope(
            x in prop::collection::vec(-1e3f64..1e3, 4..300),
            lo in 0.0f64..0.5,
            width in 0.01f64..0.5,
        ) {
            let fs = 1000.0;
            let band = (lo * 500.0, ((lo + width) * 500.0).min(500.0));
            match envelope_spectrum(&x, fs, Some(band)) {
                Ok(s) => prop_assert!(s.values.iter().all(|v| v.is_finite())),
                Err(e) => {
                    let expected = matches!(e, AnalysisError::BadBand { .. });
                    prop_assert!(expected, "unexpected error {}", e);
                }
            }
            let s = envelope_spectrum(&x, fs, None).unwrap();
            prop_assert!(s.values.iter().all(|v| v.is_finite()));
        }
    }
}
