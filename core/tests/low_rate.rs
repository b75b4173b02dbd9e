//! Output rates below the stiffest mode's internal rate ÷ 8 (with the `oversample-16`
//! feature): the CWRU 6205 needs a 46 kHz internal rate (its contact mode), so a
//! condition-monitoring system's 5.12 kHz takes 9 internal steps per sample, and the
//! anti-alias filter of that ratio (238 taps).
//! The record must be the same machine as one sampled faster, in the band both resolve,
//! and must hold nothing folded down from above its Nyquist frequency: the housing mode
//! at 3.35 kHz would fold to 5120 − 3348 = 1772 Hz, inside the usable band 0–2048 Hz.

use wearsim_core::{presets, Model};
#[cfg(feature = "oversample-16")]
use wearsim_core::{Sample, State};

/// Mean power (m²/s⁴) of `x` (rate `fs`) between `f0` and `f1` Hz: a Hann-windowed DFT
/// evaluated at every bin in the band (`fs/len` Hz apart), one-sided and scaled so that a
/// sine of amplitude A gives A²/2 and white noise of variance σ² gives σ²·(f1 − f0)/(fs/2).
#[cfg(feature = "oversample-16")]
fn band_power(x: &[f64], fs: f64, f0: f64, f1: f64) -> f64 {
    let n = x.len();
    let w: Vec<f64> = (0..n)
        .map(|i| 0.5 - 0.5 * (std::f64::consts::TAU * i as f64 / n as f64).cos())
        .collect();
    let norm: f64 = w.iter().map(|v| v * v).sum();
    let (k0, k1) = ((f0 * n as f64 / fs) as usize, (f1 * n as f64 / fs) as usize);
    (k0..=k1)
        .map(|k| {
            let (mut re, mut im) = (0.0, 0.0);
            let step = std::f64::consts::TAU * k as f64 / n as f64;
            for (i, (v, wi)) in x.iter().zip(&w).enumerate() {
                let a = step * i as f64;
                re += v * wi * a.cos();
                im -= v * wi * a.sin();
            }
            2.0 * (re * re + im * im) / (norm * n as f64)
        })
        .sum()
}

/// `seconds` of the CWRU drive-end preset (outer-race defect) at `fs`, after 0.2 s of
/// settling; returns the samples and the oversampling ratio the model chose.
#[cfg(feature = "oversample-16")]
fn record(fs: f64, seconds: f64) -> (Vec<f64>, u32) {
    let mut cfg = presets::by_name("cwru-6205-de").expect("preset");
    cfg.output_rate = fs as _;
    let model = Model::new_checked(cfg).expect("accepted");
    let mut st: State<16> = State::new(&model, 3).expect("state");
    let mut settle = vec![Sample::default(); (0.2 * fs) as usize];
    model.fill(&mut st, &mut settle);
    let mut out = vec![Sample::default(); (seconds * fs) as usize];
    model.fill(&mut st, &mut out);
    (out.iter().map(|s| s.accel).collect(), model.oversample())
}

/// Without the `oversample-16` feature (a microcontroller's build, at most 8 steps per
/// sample) 5.12 kHz is refused, naming `fs` and the rate that works.
#[cfg(not(feature = "oversample-16"))]
#[test]
fn a_low_output_rate_is_refused_without_the_longer_filters() {
    let mut cfg = presets::by_name("cwru-6205-de").expect("preset");
    cfg.output_rate = 5120.0;
    match Model::new_checked(cfg) {
        Err(e @ wearsim_core::ConfigError::StepTooLarge { field: "fs", .. }) => {
            assert!(e.to_string().contains("output rate fs of at least"), "{e}")
        }
        other => panic!("expected StepTooLarge naming fs, got {other:?}"),
    }
}

#[cfg(feature = "oversample-16")]
#[test]
fn a_low_output_rate_is_the_same_machine_with_nothing_folded() {
    let (slow, r_slow) = record(5120.0, 2.0);
    let (fast, r_fast) = record(10240.0, 2.0);
    assert!(
        r_slow > 8,
        "5.12 kHz should need more than 8 steps per sample: {r_slow}"
    );
    assert!(r_fast <= 8, "{r_fast}");
    assert!(slow.iter().all(|v| v.is_finite()));
    // Bands: the outer-race line and its second harmonic (BPFO 107.4 Hz), the fault zone,
    // and the band the housing mode would fold into.
    for (f0, f1, what) in [
        (95.0, 120.0, "BPFO"),
        (200.0, 230.0, "2×BPFO"),
        (300.0, 1000.0, "fault zone"),
        (1700.0, 1850.0, "fold of the 3.35 kHz mode"),
    ] {
        let a = band_power(&slow, 5120.0, f0, f1);
        let b = band_power(&fast, 10240.0, f0, f1);
        let db = 10.0 * (a / b).log10();
        assert!(
            db.abs() < 1.0,
            "{what} ({f0}-{f1} Hz): 5.12 kHz record {db:+.2} dB against 10.24 kHz"
        );
    }
    // The mode itself is out of the 5.12 kHz record's band; in the 10.24 kHz one it stands
    // well above the band it would fold into (so a fold would have shown above).
    let mode = band_power(&fast, 10240.0, 3250.0, 3450.0);
    let fold = band_power(&fast, 10240.0, 1700.0, 1850.0);
    assert!(10.0 * (mode / fold).log10() > 10.0);
}
