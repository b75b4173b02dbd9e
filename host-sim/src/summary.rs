//! The figures `wearsim simulate` prints: time-domain statistics and the largest
//! spectral peaks, each labelled with the nearest kinematic frequency.

use crate::analysis::{self, Stats, Window};
use serde::Serialize;
use wearsim_core::Model;

/// Characteristic frequencies of a scenario (Hz), at its initial shaft speed.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct KinematicFrequencies {
    /// Shaft, 1×.
    pub shaft: f64,
    /// Cage (eq. 17).
    pub ftf: f64,
    /// Outer-race ball pass (eq. 18).
    pub bpfo: f64,
    /// Inner-race ball pass (eq. 19).
    pub bpfi: f64,
    /// Ball spin (eq. 20).
    pub bsf: f64,
    /// Linearised natural frequency of the structure with its contacts.
    pub natural: f64,
    /// Outer-race waviness passing frequency `N_w·FTF` (0 without waviness).
    pub waviness: f64,
}

impl KinematicFrequencies {
    /// Frequencies of `model` at its speed at t = 0.
    pub fn of(model: &Model) -> Self {
        let f = model.config().speed.shaft_hz(0.0);
        let k = model.orders().at(f);
        KinematicFrequencies {
            shaft: f,
            ftf: k.ftf,
            bpfo: k.bpfo,
            bpfi: k.bpfi,
            bsf: k.bsf,
            natural: model.natural_frequency_hz(),
            waviness: model.waviness_order() as f64 * k.ftf,
        }
    }

    /// Nearest labelled frequency to `f`: harmonics 1–10 of the shaft, 1–20 of BPFO, BPFI
    /// and BSF, 1–3 of FTF, the natural and the waviness frequency. Returns (label, Hz).
    pub fn nearest(&self, f: f64) -> (String, f64) {
        let mut best = (String::from("-"), f64::INFINITY);
        let mut consider = |label: String, c: f64| {
            if c > 0.0 && (c - f).abs() < (best.1 - f).abs() {
                best = (label, c);
            }
        };
        // Fault families up to 20 harmonics: impacts ring the structure, so the largest
        // lines of a defective bearing are high BPFO/BPFI harmonics near the resonance.
        for k in 1..=20 {
            let kf = k as f64;
            if k <= 10 {
                consider(format!("{k}x shaft"), kf * self.shaft);
            }
            consider(format!("{k}x BPFO"), kf * self.bpfo);
            consider(format!("{k}x BPFI"), kf * self.bpfi);
            consider(format!("{k}x BSF"), kf * self.bsf);
            if k <= 3 {
                consider(format!("{k}x FTF"), kf * self.ftf);
            }
        }
        consider("natural".into(), self.natural);
        consider("waviness".into(), self.waviness);
        best
    }
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
}

/// The printed summary.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// RMS, peak, crest factor, kurtosis, skewness of the acceleration.
    pub stats: Stats,
    /// Largest peaks of the amplitude spectrum (Hann window, whole record).
    pub peaks: Vec<LabelledPeak>,
    /// Largest peaks of the envelope spectrum (whole band), labelled likewise.
    pub envelope_peaks: Vec<LabelledPeak>,
    /// The scenario's characteristic frequencies.
    pub kinematics: KinematicFrequencies,
}

/// Number of peaks reported.
pub const PEAKS: usize = 8;

/// Summarises acceleration `x` sampled at `fs` from `model`.
pub fn summarize(x: &[f64], fs: f64, model: &Model) -> Result<Summary, analysis::AnalysisError> {
    let stats = analysis::stats(x)?;
    let kin = KinematicFrequencies::of(model);
    let label = |peaks: Vec<analysis::Peak>| -> Vec<LabelledPeak> {
        peaks
            .into_iter()
            .map(|p| {
                let (nearest, nearest_hz) = kin.nearest(p.freq);
                LabelledPeak {
                    freq: p.freq,
                    amplitude: p.value,
                    nearest,
                    nearest_hz,
                }
            })
            .collect()
    };
    let spec = analysis::amplitude_spectrum(x, fs, Window::Hann)?;
    let sep = 3.0 * spec.df;
    let peaks = label(analysis::top_peaks(&spec, PEAKS, spec.df, 0.4 * fs, sep));
    let env = analysis::envelope_spectrum(x, fs, None)?;
    let envelope_peaks = label(analysis::top_peaks(
        &env,
        PEAKS,
        env.df,
        0.4 * fs,
        3.0 * env.df,
    ));
    Ok(Summary {
        stats,
        peaks,
        envelope_peaks,
        kinematics: kin,
    })
}
