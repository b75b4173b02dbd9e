//! Error type of the analysis functions and the argument checks they share.

use thiserror::Error;

/// Error returned by the analysis functions when an argument is outside its
/// allowed range. Every variant names the offending argument, the allowed
/// range and the value received, so that the message alone is actionable.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum AnalysisError {
    /// The input signal has no samples.
    #[error("signal is empty")]
    Empty,
    /// The input signal is shorter than the analysis requires.
    #[error("signal has {len} samples, need at least {need} for {what}")]
    TooShort {
        /// Number of samples received.
        len: usize,
        /// Minimum number of samples needed.
        need: usize,
        /// What needs them, e.g. `nperseg=256`.
        what: String,
    },
    /// The signal contains a NaN or an infinity.
    #[error("signal contains {value} at index {index}")]
    NonFinite {
        /// Index of the first non-finite sample.
        index: usize,
        /// The sample (NaN, inf or -inf).
        value: f64,
    },
    /// The signal is constant, so the requested normalised quantity
    /// (kurtosis, skewness, spectral kurtosis...) is undefined.
    /// A sample beyond ±[`MAX_MAGNITUDE`]: its square in a spectrum would overflow.
    #[error("signal value {value:e} at index {index} is beyond the analysable range ±{max:e} (squares in the spectra would overflow)")]
    TooLarge {
        /// Zero-based index of the first such sample.
        index: usize,
        /// The value.
        value: f64,
        /// The limit ([`MAX_MAGNITUDE`]).
        max: f64,
    },
    #[error("signal is constant (value {value}), {what} is undefined")]
    Constant {
        /// The constant value.
        value: f64,
        /// The undefined quantity.
        what: &'static str,
    },
    /// A scalar parameter is outside its allowed range.
    #[error("{name} must be {allowed}, got {value}")]
    BadParameter {
        /// Parameter name, e.g. `fs`.
        name: &'static str,
        /// Allowed range in words, e.g. `finite and > 0`.
        allowed: String,
        /// The value received, formatted.
        value: String,
    },
    /// A frequency band is not inside `[0, fs/2]`, is empty, or is narrower
    /// than the frequency resolution.
    #[error("band ({lo}, {hi}) Hz must satisfy 0 <= lo < hi <= fs/2 = {nyquist} Hz{extra}")]
    BadBand {
        /// Lower edge, Hz.
        lo: f64,
        /// Upper edge, Hz.
        hi: f64,
        /// Nyquist frequency fs/2, Hz.
        nyquist: f64,
        /// Extra explanation (may be empty).
        extra: String,
    },
}

/// Build a [`AnalysisError::BadParameter`].
pub(crate) fn bad(
    name: &'static str,
    allowed: &str,
    value: impl std::fmt::Display,
) -> AnalysisError {
    AnalysisError::BadParameter {
        name,
        allowed: allowed.to_string(),
        value: value.to_string(),
    }
}

/// Check that the sampling frequency is finite and positive.
pub(crate) fn check_fs(fs: f64) -> Result<(), AnalysisError> {
    if fs.is_finite() && fs > 0.0 {
        Ok(())
    } else {
        Err(bad("fs", "finite and > 0", fs))
    }
}

/// Check that `x` is non-empty, has at least `need` samples (`what` says
/// why) and contains only finite values.
/// Largest sample magnitude the analysis accepts (any unit): 1e100, so that a spectrum of
/// up to 2⁶⁴ samples (N² · x² ≤ 1e140 · 1e200 … far below f64's 1.8e308) stays finite. A
/// vibration record anywhere near it is corrupt.
pub const MAX_MAGNITUDE: f64 = 1e100;

pub(crate) fn check_signal(x: &[f64], need: usize, what: &str) -> Result<(), AnalysisError> {
    if x.is_empty() {
        return Err(AnalysisError::Empty);
    }
    if x.len() < need {
        return Err(AnalysisError::TooShort {
            len: x.len(),
            need,
            what: what.to_string(),
        });
    }
    match x.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(AnalysisError::NonFinite {
            index,
            value: x[index],
        }),
        None => Ok(()),
    }
}

/// Refuses a signal with a sample beyond ±[`MAX_MAGNITUDE`] (the spectra square it; the
/// time-domain statistics alone scale it and need no such bound).
pub fn check_magnitude(x: &[f64]) -> Result<(), AnalysisError> {
    match x.iter().position(|v| v.abs() > MAX_MAGNITUDE) {
        Some(index) => Err(AnalysisError::TooLarge {
            index,
            value: x[index],
            max: MAX_MAGNITUDE,
        }),
        None => Ok(()),
    }
}

/// Check a band `(lo, hi)` in Hz against `0 <= lo < hi <= fs/2`.
pub(crate) fn check_band(band: (f64, f64), fs: f64) -> Result<(), AnalysisError> {
    let (lo, hi) = band;
    let nyquist = fs / 2.0;
    if lo.is_finite() && hi.is_finite() && lo >= 0.0 && lo < hi && hi <= nyquist {
        Ok(())
    } else {
        Err(AnalysisError::BadBand {
            lo,
            hi,
            nyquist,
            extra: String::new(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_argument_and_range() {
        assert_eq!(
            check_fs(-3.0).unwrap_err().to_string(),
            "fs must be finite and > 0, got -3"
        );
        let e = check_signal(&[0.0; 10], 256, "nperseg=256").unwrap_err();
        assert_eq!(
            e.to_string(),
            "signal has 10 samples, need at least 256 for nperseg=256"
        );
        let mut x = vec![0.0; 20];
        x[17] = f64::NAN;
        assert_eq!(
            check_signal(&x, 1, "").unwrap_err().to_string(),
            "signal contains NaN at index 17"
        );
        assert_eq!(check_signal(&[], 1, ""), Err(AnalysisError::Empty));
        assert!(check_band((10.0, 5.0), 100.0).is_err());
        assert!(check_band((10.0, 51.0), 100.0).is_err());
        assert!(check_band((-1.0, 5.0), 100.0).is_err());
        assert!(check_band((f64::NAN, 5.0), 100.0).is_err());
        assert!(check_band((0.0, 50.0), 100.0).is_ok());
    }
}
