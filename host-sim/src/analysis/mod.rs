//! Signal analysis for rolling-element bearing vibration.
//!
//! - [`stats`](mod@stats): time-domain statistics (RMS, crest factor, kurtosis...).
//! - [`spectrum`]: Welch PSD (Welch 1967) and amplitude spectrum; [`window`].
//! - [`envelope`]: band-pass analytic envelope and envelope spectrum
//!   (Randall & Antoni 2011).
//! - [`kurtogram`]: spectral kurtosis (Antoni 2006) and fast kurtogram
//!   (Antoni 2007) to choose the demodulation band.
//! - [`peaks`]: spectral peaks, noise floor, peak-over-floor in dB.
//! - [`evidence`]: a harmonic family's evidence in an envelope spectrum; fault families.
//! - [`faults`]: fault-family detection from the envelope spectrum.
//! - [`shaft_comb`]: envelope lines at shaft orders, which explain a family on them.
//! - [`mains`]: envelope lines locked to a harmonic of the supply frequency.
//! - [`shaft_line`]: whether the raw spectrum's shaft line is where the rate and speed
//!   put it (a wrong `--fs` or `--rpm`), and the speed it shows when it contradicts them.
//! - [`transients`]: knocks and bursts cut out of a record before it is demodulated.
//! - [`diagnose`]: calibrated confidence and the call / no-call decision.
//! - [`order_tracking`]: computed order tracking of records taken at a varying speed.
//! - [`zones`]: band levels of the four El-Thalji frequency zones.
//! - [`synth`]: seeded synthetic signals with known answers.
//!
//! All functions validate their inputs and return [`AnalysisError`] rather
//! than panicking. Frequencies are in Hz, sampling rates in samples/s,
//! amplitudes in the signal's own units. Typical chain: [`fast_kurtogram`]
//! → [`envelope_spectrum`] in its best band → [`detect_fault`].

pub mod chain;
pub mod content_band;
pub mod diagnose;
pub mod envelope;
pub mod error;
pub mod evidence;
pub mod faults;
pub(crate) mod fft;
pub mod finite;
pub mod kurtogram;
pub mod mains;
pub mod octave_bands;
pub mod order_tracking;
pub mod peaks;
pub mod shaft_comb;
pub mod shaft_line;
pub mod spectrum;
pub mod stats;
pub mod synth;
pub mod transients;
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
