//! Spectral-analysis windows (periodic, "DFT-even" form; Harris 1978).

use serde::{Deserialize, Serialize};
use std::cell::RefCell;
use std::f64::consts::PI;
use std::rc::Rc;

/// Windows kept by [`Window::cached`] per thread (a record's Hann window, the Welch and
/// spectral-kurtosis segment windows).
const CACHED_WINDOWS: usize = 4;

/// One cached window: kind, length, coefficients.
type CachedWindow = (Window, usize, Rc<[f64]>);

thread_local! {
    /// Most recently used windows, newest last.
    static WINDOW_CACHE: RefCell<Vec<CachedWindow>> = const { RefCell::new(Vec::new()) };
}

/// Data window applied before an FFT. The periodic (DFT-even) form is used,
/// as is usual for spectral analysis (Harris 1978, "On the use of windows
/// for harmonic analysis with the discrete Fourier transform").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum Window {
    /// Hann (raised cosine): `0.5 - 0.5 cos(2 pi n / N)`.
    #[default]
    Hann,
    /// Hamming: `0.54 - 0.46 cos(2 pi n / N)`.
    Hamming,
    /// Rectangular (no window).
    Rectangular,
    /// 4-term Blackman-Harris (-92 dB side lobes; Harris 1978).
    BlackmanHarris,
}

impl Window {
    /// The `n` window coefficients (dimensionless).
    pub fn coefficients(self, n: usize) -> Vec<f64> {
        let cosine_sum = |a: &[f64]| -> Vec<f64> {
            (0..n)
                .map(|i| {
                    let x = 2.0 * PI * i as f64 / n as f64;
                    a.iter()
                        .enumerate()
                        .map(|(k, &ak)| {
                            let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
                            sign * ak * (k as f64 * x).cos()
                        })
                        .sum()
                })
                .collect()
        };
        match self {
            Window::Hann => cosine_sum(&[0.5, 0.5]),
            Window::Hamming => cosine_sum(&[0.54, 0.46]),
            Window::Rectangular => vec![1.0; n],
            Window::BlackmanHarris => cosine_sum(&[0.35875, 0.48829, 0.14128, 0.01168]),
        }
    }

    /// [`Window::coefficients`], shared from a small per-thread cache: the same values, bit
    /// for bit, without recomputing `n` cosines when the same window is asked for again
    /// (the analysis chain windows the record and its envelope, of equal length, and
    /// repeats segment windows).
    pub(crate) fn cached(self, n: usize) -> Rc<[f64]> {
        WINDOW_CACHE.with(|c| {
            let mut c = c.borrow_mut();
            if let Some(i) = c.iter().position(|(w, m, _)| *w == self && *m == n) {
                let hit = c.remove(i);
                let w = Rc::clone(&hit.2);
                c.push(hit);
                return w;
            }
            let w: Rc<[f64]> = self.coefficients(n).into();
            if c.len() >= CACHED_WINDOWS {
                c.remove(0);
            }
            c.push((self, n, Rc::clone(&w)));
            w
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coherent_gains() {
        let n = 1024;
        let mean = |w: Window| w.coefficients(n).iter().sum::<f64>() / n as f64;
        assert!((mean(Window::Hann) - 0.5).abs() < 1e-12);
        assert!((mean(Window::Hamming) - 0.54).abs() < 1e-12);
        assert!((mean(Window::Rectangular) - 1.0).abs() < 1e-12);
        assert!((mean(Window::BlackmanHarris) - 0.35875).abs() < 1e-12);
        let hann = Window::Hann.coefficients(n);
        assert!(hann[0].abs() < 1e-15);
        assert!((hann[n / 2] - 1.0).abs() < 1e-15);
    }

    #[test]
    fn cached_windows_are_the_computed_ones() {
        // More distinct windows than the cache holds, asked for twice: every answer equals
        // the freshly computed coefficients, bit for bit.
        for _ in 0..2 {
            for (w, n) in [
                (Window::Hann, 1000),
                (Window::Hamming, 1000),
                (Window::Hann, 64),
                (Window::BlackmanHarris, 333),
                (Window::Rectangular, 7),
                (Window::Hann, 1000),
            ] {
                assert_eq!(&*w.cached(n), w.coefficients(n).as_slice(), "{w:?} {n}");
            }
        }
    }
}
