//! Spectral peak picking: local maxima with parabolic interpolation, peak
//! search near an expected frequency, and a median noise floor.

use super::spectrum::{Spectrum, SpectrumKind};
use super::stats::median;
use serde::Serialize;

/// Half-width, in bins, of the region around a peak excluded from its noise
/// floor (the main lobe of a Hann window is ±2 bins).
const FLOOR_EXCLUDE_BINS: usize = 2;

/// A spectral peak.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Peak {
    /// Frequency, Hz, refined by parabolic interpolation through the three
    /// bins around the maximum (Smith & Serra 1987), so it can fall between bins.
    pub freq: f64,
    /// Value at the interpolated vertex, in the spectrum's units.
    pub value: f64,
    /// Index of the maximum bin.
    pub bin: usize,
}

/// True if the spectrum's bin spacing is positive (not NaN, not <= 0).
fn usable(s: &Spectrum) -> bool {
    s.df.partial_cmp(&0.0) == Some(std::cmp::Ordering::Greater)
}

/// True if bin `k` (with both neighbours present) is a local maximum:
/// strictly above its left neighbour and not below its right one.
fn is_local_max(v: &[f64], k: usize) -> bool {
    k > 0 && k + 1 < v.len() && v[k] > v[k - 1] && v[k] >= v[k + 1]
}

/// Parabolic interpolation of the local maximum at bin `k`.
fn interpolate(s: &Spectrum, k: usize) -> Peak {
    let (a, b, c) = (s.values[k - 1], s.values[k], s.values[k + 1]);
    let denom = a - 2.0 * b + c;
    let delta = if denom < 0.0 {
        (0.5 * (a - c) / denom).clamp(-0.5, 0.5)
    } else {
        0.0
    };
    Peak {
        freq: (k as f64 + delta) * s.df,
        value: b - 0.25 * (a - c) * delta,
        bin: k,
    }
}

/// Inclusive bin range covering `[fmin, fmax]` Hz (clamped to the spectrum).
fn bin_range(s: &Spectrum, fmin: f64, fmax: f64) -> (usize, usize) {
    let lo = (fmin / s.df).ceil().max(0.0);
    let hi = (fmax / s.df).floor().min(s.len().saturating_sub(1) as f64);
    if lo.is_nan() || hi.is_nan() {
        return (1, 0);
    }
    (lo as usize, if hi < 0.0 { 0 } else { hi as usize })
}

/// Up to `n` largest local maxima of `s` with frequency in `[fmin, fmax]`
/// Hz, largest first, each at least `min_separation_hz` from every larger
/// peak kept. Frequencies and values are parabolically interpolated.
/// Returns an empty vector if there are none (bad ranges included).
pub fn top_peaks(
    s: &Spectrum,
    n: usize,
    fmin: f64,
    fmax: f64,
    min_separation_hz: f64,
) -> Vec<Peak> {
    if s.len() < 3 || !usable(s) {
        return Vec::new();
    }
    let (lo, hi) = bin_range(s, fmin, fmax);
    let mut cands: Vec<Peak> = (lo.max(1)..=hi.min(s.len() - 2))
        .filter(|&k| is_local_max(&s.values, k))
        .map(|k| interpolate(s, k))
        .collect();
    cands.sort_by(|a, b| b.value.total_cmp(&a.value));
    let mut kept: Vec<Peak> = Vec::new();
    for p in cands {
        if kept.len() >= n {
            break;
        }
        if kept
            .iter()
            .all(|q| (q.freq - p.freq).abs() >= min_separation_hz)
        {
            kept.push(p);
        }
    }
    kept
}

/// The largest local maximum within `f ± tol_hz` (the window always covers
/// at least the bin nearest `f`), or `None` if there is no local maximum there.
pub fn peak_near(s: &Spectrum, f: f64, tol_hz: f64) -> Option<Peak> {
    if s.len() < 3 || !usable(s) || !f.is_finite() {
        return None;
    }
    let tol = tol_hz.abs();
    let lo = s.bin_of(f - tol).min(s.bin_of(f));
    let hi = s.bin_of(f + tol).max(s.bin_of(f));
    (lo.max(1)..=hi.min(s.len() - 2))
        .filter(|&k| is_local_max(&s.values, k))
        .map(|k| interpolate(s, k))
        .max_by(|a, b| a.value.total_cmp(&b.value))
}

/// The largest local maximum whose interpolated frequency lies within `f ± tol_hz`, or
/// `None`. [`peak_near`]'s window is rounded outward to whole bins (up to half a bin past
/// `tol_hz`) and always holds the bin nearest `f`; here the tolerance is exact, for a
/// tolerance of the order of a bin, where half a bin more is another rule (a ±1 % window at
/// 0.39 Hz bins on a 29 Hz shaft reached 1.67 %).
pub fn peak_within(s: &Spectrum, f: f64, tol_hz: f64) -> Option<Peak> {
    if s.len() < 3 || !usable(s) || !f.is_finite() {
        return None;
    }
    let tol = tol_hz.abs();
    // An interpolated peak lies within half a bin of its bin.
    let lo = s.bin_of(f - tol - s.df).max(1);
    let hi = s.bin_of(f + tol + s.df).min(s.len() - 2);
    (lo..=hi)
        .filter(|&k| is_local_max(&s.values, k))
        .map(|k| interpolate(s, k))
        .filter(|p| (p.freq - f).abs() <= tol)
        .max_by(|a, b| a.value.total_cmp(&b.value))
}

/// Noise floor around `f` Hz: the median of the values within
/// `f ± half_width_hz`, excluding the ±2 bins around the bin nearest `f`
/// (a Hann main lobe). Returns 0 if that neighbourhood is empty.
pub fn noise_floor(s: &Spectrum, f: f64, half_width_hz: f64) -> f64 {
    if s.is_empty() || !usable(s) || !f.is_finite() {
        return 0.0;
    }
    let kc = s.bin_of(f);
    let hw = half_width_hz.abs();
    let lo = s.bin_of(f - hw);
    let hi = s.bin_of(f + hw);
    let v: Vec<f64> = (lo..=hi)
        .filter(|k| k.abs_diff(kc) > FLOOR_EXCLUDE_BINS)
        .map(|k| s.values[k])
        .filter(|v| v.is_finite())
        .collect();
    median(v).unwrap_or(0.0)
}

/// Ratio of a value to a floor in dB: `20 log10` for amplitude-like spectra,
/// `10 log10` for power spectral densities. The floor is clamped to the
/// smallest positive f64, so the result is finite for finite positive values.
pub fn ratio_db(kind: SpectrumKind, value: f64, floor: f64) -> f64 {
    let log_r = value.max(f64::MIN_POSITIVE).log10() - floor.max(f64::MIN_POSITIVE).log10();
    match kind {
        SpectrumKind::Psd => 10.0 * log_r,
        SpectrumKind::Amplitude | SpectrumKind::SpectralKurtosis => 20.0 * log_r,
    }
}

/// The peak near `f` (see [`peak_near`], tolerance `tol_hz`) and its height
/// in dB over the [`noise_floor`] (half-width `floor_half_width_hz`) around
/// the peak's own frequency; `None` if there is no peak within tolerance.
pub fn peak_over_floor_db(
    s: &Spectrum,
    f: f64,
    tol_hz: f64,
    floor_half_width_hz: f64,
) -> Option<(Peak, f64)> {
    Some(over_floor_db(
        s,
        peak_near(s, f, tol_hz)?,
        floor_half_width_hz,
    ))
}

/// Peak `p` and its height in dB over the [`noise_floor`] (half-width
/// `floor_half_width_hz`) around its own frequency.
pub fn over_floor_db(s: &Spectrum, p: Peak, floor_half_width_hz: f64) -> (Peak, f64) {
    let floor = noise_floor(s, p.freq, floor_half_width_hz);
    (p, ratio_db(s.kind, p.value, floor))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::spectrum::amplitude_spectrum;
    use crate::analysis::synth::{gaussian_noise, sine};
    use crate::analysis::window::Window;
    use proptest::prelude::*;

    fn tones() -> Spectrum {
        let fs = 1000.0;
        let n = 4000; // df = 0.25 Hz
        let x: Vec<f64> = sine(n, fs, 100.1, 1.0, 0.0)
            .iter()
            .zip(sine(n, fs, 230.0, 2.0, 0.5))
            .zip(sine(n, fs, 231.5, 0.5, 0.5))
            .zip(gaussian_noise(n, 0.01, 1))
            .map(|(((a, b), c), d)| a + b + c + d)
            .collect();
        amplitude_spectrum(&x, fs, Window::Hann).unwrap()
    }

    #[test]
    fn peak_within_keeps_its_tolerance_exactly_where_peak_near_rounds_it_out() {
        // 0.25 Hz bins; a line at 100.1 Hz. Around 99.8 Hz with ±0.2 Hz: the window of
        // `peak_near` rounds out to bins 399..=400 (99.75..100.0 Hz) and 400 is the line's
        // own bin, a local maximum interpolated at 100.1 Hz, 0.3 Hz away.
        let s = tones();
        let near = peak_near(&s, 99.8, 0.2).expect("the line's bin is in the rounded window");
        assert!((near.freq - 100.1).abs() < 0.05, "{near:?}");
        assert_eq!(peak_within(&s, 99.8, 0.2), None);
        // Within 0.35 Hz it is found, at its interpolated frequency.
        let p = peak_within(&s, 99.8, 0.35).expect("in tolerance");
        assert!((p.freq - 100.1).abs() < 0.05, "{p:?}");
        assert_eq!(peak_within(&s, f64::NAN, 1.0), None);
    }

    #[test]
    fn top_peaks_sorted_interpolated_separated() {
        let s = tones();
        let p = top_peaks(&s, 3, 0.0, 500.0, 5.0);
        assert_eq!(p.len(), 3);
        assert!((p[0].freq - 230.0).abs() < 0.01);
        assert!((p[0].value - 2.0).abs() < 0.02);
        // 100.1 Hz lies between bins (100.0, 100.25): interpolation helps.
        assert!((p[1].freq - 100.1).abs() < 0.05, "{}", p[1].freq);
        assert!((p[1].value - 1.0).abs() < 0.1);
        // The 231.5 Hz tone is within 5 Hz of 230: suppressed.
        assert!(p[2].value < 0.05);
        let close = top_peaks(&s, 3, 0.0, 500.0, 1.0);
        assert!((close[2].freq - 231.5).abs() < 0.01);
        let limited = top_peaks(&s, 5, 150.0, 300.0, 1.0);
        assert!(limited.iter().all(|p| (150.0..=300.0).contains(&p.freq)));
        assert!(top_peaks(&s, 0, 0.0, 500.0, 1.0).is_empty());
        assert!(top_peaks(&s, 3, 400.0, 100.0, 1.0).is_empty());
    }

    #[test]
    fn peak_near_and_floor() {
        let s = tones();
        let p = peak_near(&s, 101.0, 2.0).unwrap();
        assert!((p.freq - 100.1).abs() < 0.05);
        assert!(peak_near(&s, 101.0, 0.1).is_none_or(|p| p.value < 0.05));
        let floor = noise_floor(&s, 100.1, 10.0);
        assert!(floor > 1e-4 && floor < 2e-3, "floor {floor}");
        let (_, db) = peak_over_floor_db(&s, 100.0, 1.0, 10.0).unwrap();
        assert!(db > 50.0, "{db}");
        assert_eq!(noise_floor(&s, 100.0, 0.0), 0.0);
    }

    #[test]
    fn ratio_db_scales() {
        assert!((ratio_db(SpectrumKind::Amplitude, 10.0, 1.0) - 20.0).abs() < 1e-12);
        assert!((ratio_db(SpectrumKind::Psd, 10.0, 1.0) - 10.0).abs() < 1e-12);
        assert!(ratio_db(SpectrumKind::Psd, 1.0, 0.0).is_finite());
    }

    proptest! {
        #[test]
        fn peaks_never_panic(
            v in prop::collection::vec(0.0f64..1e3, 0..200),
            f in -10.0f64..300.0,
            tol in 0.0f64..50.0,
        ) {
            let s = Spectrum { df: 1.0, values: v, kind: SpectrumKind::Amplitude };
            let peaks = top_peaks(&s, 5, f, f + tol, tol);
            prop_assert!(peaks.windows(2).all(|w| w[0].value >= w[1].value));
            prop_assert!(peaks.iter().all(|p| p.freq.is_finite() && p.value.is_finite()));
            let _ = peak_near(&s, f, tol);
            prop_assert!(noise_floor(&s, f, tol).is_finite());
            if let Some((_, db)) = peak_over_floor_db(&s, f, tol, 3.0 * tol) {
                prop_assert!(db.is_finite());
            }
        }
    }
}
