//! Octave band levels of a snapshot for feature tables: the RMS in the octaves below
//! the Nyquist frequency, `[fs/2^(k+1), fs/2^k)` for k = 1..=[`OCTAVES`] (edges rounded to
//! whole Hz, which name the column `band_<lo>_<hi>_hz`), from the periodogram of the
//! whole snapshot (rectangular window, Parseval: the bands' squares sum to the snapshot's
//! mean square above the lowest edge). Octaves below Nyquist are the bands of a level-k
//! wavelet-packet or filter-bank energy feature common in run-to-failure prognostics, and
//! need no bearing geometry, so every rig's table has them (`docs/feature-tables.md`).

use super::fft::{one_sided_factor, rfft};

/// Octaves below Nyquist reported (for 25.6 kHz: 6400–12800 Hz down to 200–400 Hz).
pub const OCTAVES: u32 = 6;

/// The band edges (Hz, whole) at sample rate `fs`, highest band first.
pub fn octave_edges(fs: f64) -> Vec<(f64, f64)> {
    (1..=OCTAVES)
        .map(|k| {
            let hi = (fs / f64::from(1u32 << k)).round();
            let lo = (fs / f64::from(1u32 << (k + 1))).round();
            (lo, hi)
        })
        .filter(|(lo, hi)| *lo > 0.0 && lo < hi)
        .collect()
}

/// Column name of band `(lo, hi)`.
pub fn band_name(b: (f64, f64)) -> String {
    format!("band_{}_{}_hz", b.0, b.1)
}

/// RMS of `x` (sampled at `fs`) in each band of `bands` (Hz, `[lo, hi)`; a band whose
/// `hi` is the Nyquist frequency includes it): `sqrt(Σ one-sided |X_k|² / n²)` over the
/// DFT bins in the band. The mean is not removed (it falls in no band above 0 Hz).
pub fn band_levels(x: &[f64], fs: f64, bands: &[(f64, f64)]) -> Vec<f64> {
    let n = x.len();
    if n < 2 || fs.is_nan() || fs <= 0.0 {
        return vec![0.0; bands.len()];
    }
    let spec = rfft(x, 0.0);
    let nyq = fs / 2.0;
    let n2 = (n as f64) * (n as f64);
    bands
        .iter()
        .map(|(lo, hi)| {
            let p: f64 = spec
                .iter()
                .enumerate()
                .filter(|(k, _)| {
                    let f = *k as f64 * fs / n as f64;
                    f >= *lo && (f < *hi || (f >= nyq && *hi >= nyq))
                })
                .map(|(k, c)| one_sided_factor(k, n) * c.norm_sqr() / n2)
                .sum();
            p.max(0.0).sqrt()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sine_is_a_over_root_two_in_its_band_and_nothing_elsewhere() {
        let fs = 25_600.0;
        let b = octave_edges(fs);
        assert_eq!(b[0], (6400.0, 12_800.0));
        assert_eq!(b[5], (200.0, 400.0));
        assert_eq!(band_name(b[1]), "band_3200_6400_hz");
        // IMS's 20 kHz: contiguous after rounding.
        let i = octave_edges(20_000.0);
        assert!(i.windows(2).all(|w| w[0].0 == w[1].1), "{i:?}");
        let n = 2560;
        for (f, a, exact) in [
            (1000.0, 2.0, true),
            (5010.3, 0.7, false),
            (300.0, 1.5, true),
        ] {
            let x: Vec<f64> = (0..n)
                .map(|k| a * (2.0 * std::f64::consts::PI * f * k as f64 / fs).sin() + 0.25)
                .collect();
            let l = band_levels(&x, fs, &b);
            let tol = if exact { 1e-9 } else { 0.02 };
            for (band, v) in b.iter().zip(&l) {
                if f >= band.0 && f < band.1 {
                    assert!(
                        (v / (a / 2f64.sqrt()) - 1.0).abs() < tol,
                        "{f} Hz in {band:?}: {v}"
                    );
                } else {
                    assert!(
                        *v < if exact { 1e-9 } else { 0.05 * a },
                        "{f} Hz leaks into {band:?}: {v}"
                    );
                }
            }
        }
        // Parseval: white noise's bands sum to its power above 200 Hz (about 1 − 200/12800).
        let mut s = 1u64;
        let x: Vec<f64> = (0..n)
            .map(|_| {
                s = s
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
            })
            .collect();
        let ms: f64 = x.iter().map(|v| v * v).sum::<f64>() / n as f64;
        let tot: f64 = band_levels(&x, fs, &b).iter().map(|v| v * v).sum();
        assert!(
            (tot / ms - (1.0 - 200.0 / 12_800.0)).abs() < 0.05,
            "{tot} vs {ms}"
        );
        assert_eq!(band_levels(&[1.0], fs, &b), vec![0.0; 6]);
    }
}
