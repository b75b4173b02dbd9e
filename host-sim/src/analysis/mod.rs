//! Signal analysis for bearing vibration: time-domain statistics, spectra
//! (Welch PSD, amplitude spectrum), envelope analysis, spectral kurtosis and the fast kurtogram,
//! spectral peaks, bearing fault-family detection,
//! frequency-zone levels.
//!
//! All functions validate their inputs and return [`AnalysisError`] rather
//! than panicking. Frequencies are in Hz, sampling rates in samples/s,
//! amplitudes in the signal's own units.

pub mod envelope;
pub mod error;
pub mod faults;
mod fft;
pub mod kurtogram;
pub mod peaks;
pub mod spectrum;
pub mod stats;
pub mod synth;
pub mod window;
pub mod zones;

pub use envelope::{bandpass_analytic_envelope, envelope_spectrum};
pub use error::AnalysisError;
pub use faults::{
    detect_fault, DetectParams, FamilyEvidence, FaultDiagnosis, FaultFamily, FaultFrequencies,
};
pub use kurtogram::{fast_kurtogram, spectral_kurtosis, Kurtogram};
pub use peaks::{noise_floor, peak_near, peak_over_floor_db, top_peaks, Peak};
pub use spectrum::{amplitude_spectrum, welch_psd, Spectrum, SpectrumKind, WelchParams};
pub use stats::{stats, Stats};
pub use window::Window;
pub use zones::{zone_levels, ZoneBands, ZoneLevels};
