//! Time-domain summary statistics of a vibration record.

use super::error::{check_signal, AnalysisError};
use serde::Serialize;

/// Time-domain statistics of a signal. Amplitude quantities are in the
/// signal's units (e.g. g or m/s²); ratios and moments are dimensionless.
/// Moments are population (biased, 1/n) estimates computed in two passes
/// about the mean, on the signal scaled by its peak so that no square or
/// fourth power can overflow.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Stats {
    /// Number of samples.
    pub n: usize,
    /// Mean, signal units.
    pub mean: f64,
    /// Root mean square (including the mean), signal units.
    pub rms: f64,
    /// Standard deviation (1/n), signal units.
    pub std: f64,
    /// Peak, `max |x|`, signal units.
    pub peak: f64,
    /// Crest factor `peak / rms` (√2 for a sine).
    pub crest_factor: f64,
    /// Kurtosis, normalised 4th central moment `m4 / m2²`
    /// (3 for Gaussian noise, 1.5 for a sine; not the excess kurtosis).
    pub kurtosis: f64,
    /// Skewness, normalised 3rd central moment `m3 / m2^1.5`.
    pub skewness: f64,
}

/// Compute [`Stats`] of `x`.
///
/// Errors: empty signal, non-finite sample, or a constant signal (whose
/// kurtosis and skewness are undefined; a constant is detected when the
/// standard deviation is below 1e-12 of the peak).
pub fn stats(x: &[f64]) -> Result<Stats, AnalysisError> {
    check_signal(x, 1, "statistics")?;
    let n = x.len();
    let nf = n as f64;
    let peak = x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    if peak == 0.0 {
        return Err(AnalysisError::Constant {
            value: 0.0,
            what: "kurtosis",
        });
    }
    // Work on x / peak (all values in [-1, 1]) to avoid overflow.
    let scaled_mean = x.iter().map(|v| v / peak).sum::<f64>() / nf;
    let (mut m2, mut m3, mut m4, mut ms) = (0.0, 0.0, 0.0, 0.0);
    for v in x {
        let s = v / peak;
        let d = s - scaled_mean;
        let d2 = d * d;
        m2 += d2;
        m3 += d2 * d;
        m4 += d2 * d2;
        ms += s * s;
    }
    m2 /= nf;
    m3 /= nf;
    m4 /= nf;
    ms /= nf;
    let std_scaled = m2.sqrt();
    if std_scaled <= 1e-12 {
        return Err(AnalysisError::Constant {
            value: x[0],
            what: "kurtosis",
        });
    }
    let rms = ms.sqrt() * peak;
    Ok(Stats {
        n,
        mean: scaled_mean * peak,
        rms,
        std: std_scaled * peak,
        peak,
        crest_factor: 1.0 / ms.sqrt(),
        kurtosis: m4 / (m2 * m2),
        skewness: m3 / (m2 * std_scaled),
    })
}

/// Arithmetic mean of `x` (0 for an empty slice).
pub fn mean(x: &[f64]) -> f64 {
    if x.is_empty() {
        0.0
    } else {
        x.iter().sum::<f64>() / x.len() as f64
    }
}

/// Mean and sample standard deviation (`1/(n−1)`, `1/n` for a single value) of `v`.
/// An empty slice gives `(0, 0)`.
pub fn mean_std(v: &[f64]) -> (f64, f64) {
    let n = v.len().max(1) as f64;
    let m = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1.0).max(1.0);
    (m, var.sqrt())
}

/// Root mean square of `x` about zero, `√(Σx²/n)` (0 for an empty slice). Plain sum of
/// squares, unlike [`Stats::rms`], which scales by the peak first.
pub fn rms(x: &[f64]) -> f64 {
    (x.iter().map(|v| v * v).sum::<f64>() / x.len().max(1) as f64).sqrt()
}

/// The finite values of `v`, sorted ascending.
fn sorted_finite(mut v: Vec<f64>) -> Vec<f64> {
    v.retain(|x| x.is_finite());
    v.sort_by(f64::total_cmp);
    v
}

/// Median of the finite values of `v`: the middle value, or the mean of the two middle
/// values for an even count. `None` when no value is finite. The statistician's median,
/// used where a figure is reported (twin-experiment summaries, noise floors).
pub fn median(v: Vec<f64>) -> Option<f64> {
    let v = sorted_finite(v);
    let m = v.len() / 2;
    if v.len() % 2 == 1 {
        v.get(m).copied()
    } else {
        Some(0.5 * (*v.get(m.checked_sub(1)?)? + *v.get(m)?))
    }
}

/// Quantile `p` (clamped to [0, 1]) of the ascending-sorted `v`, linear between order
/// statistics (Hyndman & Fan 1996, type 7: R's and NumPy's default); `None` when `v` is
/// empty. The one quantile of the project: the ensemble's bands and the Weibull fits'
/// bootstrap intervals.
pub fn quantile(v: &[f64], p: f64) -> Option<f64> {
    let n = v.len();
    if n == 0 {
        return None;
    }
    let h = (n - 1) as f64 * p.clamp(0.0, 1.0);
    let (i, f) = (h.floor() as usize, h - h.floor());
    let lo = *v.get(i)?;
    Some(match v.get(i + 1) {
        Some(hi) if f > 0.0 => lo + f * (hi - lo),
        _ => lo,
    })
}

/// Upper median of the finite values of `v`: the value at index `n/2` of the sorted
/// values (the median for an odd count, the upper of the two middle values for an even
/// one). `None` when no value is finite. Always one of the values themselves; the life
/// reference levels (steady-stage RMS, early-life RMS, dead-snapshot threshold) were
/// recorded with it, so it is kept distinct from [`median`] to keep those figures.
pub fn upper_median(v: Vec<f64>) -> Option<f64> {
    let v = sorted_finite(v);
    v.get(v.len() / 2).copied()
}

/// Robust centre and scale of `v`: the [`upper_median`] `m` and the normal-consistent
/// median absolute deviation `1.4826 · upper_median(|v − m|)` (Rousseeuw & Croux 1993).
/// `None` when no value is finite.
pub fn robust_sigma(v: Vec<f64>) -> Option<(f64, f64)> {
    let m = upper_median(v.clone())?;
    let dev = upper_median(v.iter().map(|x| (x - m).abs()).collect())?;
    Some((m, 1.4826 * dev))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::synth::{gaussian_noise, sine};
    use proptest::prelude::*;

    #[test]
    fn type_7_quantiles_by_hand() {
        let v = [1.0, 2.0, 3.0, 4.0, 5.0];
        assert_eq!(quantile(&v, 0.5), Some(3.0));
        assert_eq!(quantile(&v, 0.25), Some(2.0));
        assert!((quantile(&v, 0.05).unwrap() - 1.2).abs() < 1e-12);
        assert_eq!(quantile(&v, 1.0), Some(5.0));
        assert_eq!(quantile(&v, 1.5), Some(5.0));
        assert_eq!(quantile(&[], 0.5), None);
    }

    #[test]
    fn medians_of_odd_and_even_counts() {
        assert_eq!(median(vec![3.0, 1.0, 2.0]), Some(2.0));
        assert_eq!(median(vec![4.0, 1.0, 3.0, 2.0]), Some(2.5));
        assert_eq!(upper_median(vec![4.0, 1.0, 3.0, 2.0]), Some(3.0));
        assert_eq!(upper_median(vec![3.0, 1.0, 2.0]), Some(2.0));
        assert_eq!(median(vec![f64::NAN, 1.0, f64::INFINITY]), Some(1.0));
        assert_eq!(median(vec![]), None);
        assert_eq!(upper_median(vec![f64::NAN]), None);
    }

    #[test]
    fn robust_sigma_of_normal_deviations() {
        // Deviations 0, 1, 1, 2, 2 about the centre 10: MAD 1, sigma 1.4826.
        let (m, s) = robust_sigma(vec![8.0, 9.0, 10.0, 11.0, 12.0]).unwrap_or((0.0, 0.0));
        assert_eq!(m, 10.0);
        assert!((s - 1.4826).abs() < 1e-12);
    }

    #[test]
    fn mean_std_and_rms() {
        let (m, s) = mean_std(&[1.0, 2.0, 3.0, 4.0]);
        assert!((m - 2.5).abs() < 1e-15);
        assert!((s - (5.0f64 / 3.0).sqrt()).abs() < 1e-15);
        assert!((rms(&[3.0, -4.0]) - (12.5f64).sqrt()).abs() < 1e-15);
        assert_eq!(mean(&[]), 0.0);
    }

    #[test]
    fn gaussian_noise_moments() {
        let x = gaussian_noise(100_000, 2.0, 42);
        let s = stats(&x).unwrap();
        assert_eq!(s.n, 100_000);
        assert!((s.kurtosis - 3.0).abs() < 0.1, "kurtosis {}", s.kurtosis);
        assert!(s.skewness.abs() < 0.05, "skewness {}", s.skewness);
        assert!((s.std - 2.0).abs() < 0.02, "std {}", s.std);
        assert!(s.mean.abs() < 0.03);
    }

    #[test]
    fn sine_moments() {
        // 50 whole periods of 200 samples.
        let x: Vec<f64> = sine(10_000, 1000.0, 5.0, 3.0, 0.3)
            .iter()
            .map(|v| v + 1.0)
            .collect();
        let s = stats(&x).unwrap();
        assert!((s.mean - 1.0).abs() < 1e-9);
        assert!((s.std - 3.0 / 2f64.sqrt()).abs() < 1e-9);
        assert!((s.rms - (4.5f64 + 1.0).sqrt()).abs() < 1e-9);
        assert!((s.kurtosis - 1.5).abs() < 1e-6, "kurtosis {}", s.kurtosis);
        assert!(s.skewness.abs() < 1e-9);
        let pure = stats(&sine(10_000, 1000.0, 5.0, 3.0, 0.0)).unwrap();
        assert!((pure.crest_factor - 2f64.sqrt()).abs() < 1e-6);
        assert!((pure.peak - 3.0).abs() < 1e-6);
    }

    #[test]
    fn skewness_sign() {
        // Mostly zeros with rare positive spikes: positively skewed.
        let x: Vec<f64> = (0..1000)
            .map(|i| if i % 50 == 0 { 10.0 } else { 0.0 })
            .collect();
        assert!(stats(&x).unwrap().skewness > 5.0);
        let neg: Vec<f64> = x.iter().map(|v| -v).collect();
        assert!(stats(&neg).unwrap().skewness < -5.0);
        assert!(stats(&x).unwrap().kurtosis > 40.0);
    }

    #[test]
    fn bad_inputs_are_errors() {
        assert_eq!(stats(&[]).unwrap_err(), AnalysisError::Empty);
        assert!(matches!(
            stats(&[1.0, f64::INFINITY]),
            Err(AnalysisError::NonFinite { index: 1, .. })
        ));
        assert!(matches!(
            stats(&[0.1; 77]),
            Err(AnalysisError::Constant { .. })
        ));
        assert!(matches!(
            stats(&[0.0; 3]),
            Err(AnalysisError::Constant { .. })
        ));
        // Huge values do not overflow.
        let s = stats(&[1e300, -1e300, 5e299]).unwrap();
        assert!(s.rms.is_finite() && s.kurtosis.is_finite());
    }

    proptest! {
        #[test]
        fn finite_input_gives_finite_stats(x in prop::collection::vec(-1e6f64..1e6, 1..300)) {
            match stats(&x) {
                Ok(s) => {
                    prop_assert!(s.kurtosis.is_finite() && s.skewness.is_finite());
                    prop_assert!(s.kurtosis >= 1.0 - 1e-9);
                    prop_assert!(s.crest_factor >= 1.0 - 1e-9);
                }
                Err(e) => {
                    let expected = matches!(e, AnalysisError::Constant { .. });
                    prop_assert!(expected, "unexpected error {}", e);
                }
            }
        }
    }
}
