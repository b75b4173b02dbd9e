//! The figures `wearsim simulate` prints: time-domain statistics and the largest
//! spectral peaks, each labelled with the nearest kinematic frequency.

use crate::analysis::{self, Stats, Window};
use serde::Serialize;
use wearsim_core::kinematics::FaultFrequencies;
use wearsim_core::Model;

/// Nearest labelled line to `f` (Hz) among the characteristic frequencies `k` of a scenario
/// and its outer-race waviness passing frequency `waviness_hz` (0 without waviness):
/// harmonics 1–10 of the shaft, 1–20 of BPFO, BPFI and BSF, 1–3 of FTF, the natural and the
/// waviness frequency. Returns (label, Hz).
pub fn nearest_line(k: &FaultFrequencies, waviness_hz: f64, f: f64) -> (String, f64) {
    let mut best = (String::from("-"), f64::INFINITY);
    let mut consider = |label: String, c: f64| {
        if c > 0.0 && (c - f).abs() < (best.1 - f).abs() {
            best = (label, c);
        }
    };
    // Fault families up to 20 harmonics: impacts ring the structure, so the largest
    // lines of a defective bearing are high BPFO/BPFI harmonics near the resonance.
    for n in 1..=20 {
        let nf = n as f64;
        if n <= 10 {
            consider(format!("{n}x shaft"), nf * k.shaft_hz);
        }
        consider(format!("{n}x BPFO"), nf * k.bpfo);
        consider(format!("{n}x BPFI"), nf * k.bpfi);
        consider(format!("{n}x BSF"), nf * k.bsf);
        if n <= 3 {
            consider(format!("{n}x FTF"), nf * k.ftf);
        }
    }
    consider("natural".into(), k.natural_hz);
    consider("waviness".into(), waviness_hz);
    best
}

/// Outer-race waviness passing frequency `N_w·FTF` (Hz) of `model` at shaft frequency
/// `shaft_hz` (0 without waviness; thesis section on waviness, `[surface] waviness_order`).
pub fn waviness_hz(model: &Model, shaft_hz: f64) -> f64 {
    model.waviness_order() as f64 * model.orders().ftf * shaft_hz
}

/// One labelled spectral peak.
#[derive(Debug, Clone, Serialize)]
pub struct LabelledPeak {
    /// Frequency (Hz).
    pub freq: f64,
    /// Amplitude (m/s², peak) of the sinusoid at that frequency.
    pub amplitude: f64,
    /// Nearest kinematic frequency's label.
    pub nearest: String,
    /// Its frequency (Hz).
    pub nearest_hz: f64,
    /// Whether the peak is that line: within [`LINE_TOLERANCE`] of it or three spectral
    /// bins, whichever is wider (slip moves rolling-element lines by 1–2 %); otherwise the
    /// peak is no characteristic line and `nearest` only says what is closest.
    pub matched: bool,
}

/// Relative distance within which a peak is labelled as a characteristic line.
pub const LINE_TOLERANCE: f64 = 0.03;

/// The printed summary.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// RMS, peak, crest factor, kurtosis, skewness of the acceleration.
    pub stats: Stats,
    /// Largest peaks of the amplitude spectrum (Hann window, whole record).
    pub peaks: Vec<LabelledPeak>,
    /// Largest peaks of the envelope spectrum (whole band), labelled likewise.
    pub envelope_peaks: Vec<LabelledPeak>,
    /// The scenario's characteristic frequencies at its initial shaft speed.
    pub kinematics: FaultFrequencies,
    /// Outer-race waviness passing frequency `N_w·FTF` (Hz; 0 without waviness).
    pub waviness_hz: f64,
}

/// Number of peaks reported.
pub const PEAKS: usize = 8;

/// Summarises acceleration `x` sampled at `fs` from `model`.
pub fn summarize(x: &[f64], fs: f64, model: &Model) -> Result<Summary, analysis::AnalysisError> {
    let stats = analysis::stats(x)?;
    let shaft_hz = model.config().speed.shaft_hz(0.0);
    let kin = model.frequencies_at(shaft_hz);
    let waviness_hz = waviness_hz(model, shaft_hz);
    let label = |peaks: Vec<analysis::Peak>, df: f64| -> Vec<LabelledPeak> {
        peaks
            .into_iter()
            .map(|p| {
                let (nearest, nearest_hz) = nearest_line(&kin, waviness_hz, p.freq);
                let tol = (LINE_TOLERANCE * nearest_hz).max(3.0 * df);
                LabelledPeak {
                    freq: p.freq,
                    amplitude: p.value,
                    nearest,
                    nearest_hz,
                    matched: (p.freq - nearest_hz).abs() <= tol,
                }
            })
            .collect()
    };
    let spec = analysis::amplitude_spectrum(x, fs, Window::Hann)?;
    let sep = 3.0 * spec.df;
    let peaks = label(
        analysis::top_peaks(&spec, PEAKS, spec.df, 0.4 * fs, sep),
        spec.df,
    );
    let env = analysis::envelope_spectrum(x, fs, None)?;
    let envelope_peaks = label(
        analysis::top_peaks(&env, PEAKS, env.df, 0.4 * fs, 3.0 * env.df),
        env.df,
    );
    Ok(Summary {
        stats,
        peaks,
        envelope_peaks,
        kinematics: kin,
        waviness_hz,
    })
}
