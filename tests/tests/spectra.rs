//! Spectra of simulated signals show what each force diagram must produce
//! (thesis §4.1 and publication IV §3; Harsha 2005 for waviness orders; Randall & Antoni
//! 2011 for slip). The analysis is the host library's, the same code `wearsim analyze` uses.

use wearsim_core::forces::imbalance::Imbalance;
use wearsim_core::forces::slip::Slip;
use wearsim_core::forces::surface::Waviness;
use wearsim_core::{presets, topography, ModelConfig};
use wearsim_host::analysis::{self, FaultFamily, FaultFrequencies, Window};
use wearsim_tests::{bare_reference, simulate};

fn fault_freqs(cfg: &ModelConfig) -> FaultFrequencies {
    let model = wearsim_core::Model::new_checked(cfg.clone()).unwrap();
    model.frequencies_at(cfg.speed.shaft_hz(0.0))
}

/// Imbalance alone: the largest peak of the spectrum is at 1× within one bin.
#[test]
fn imbalance_only_peaks_at_shaft_frequency() {
    let cfg = ModelConfig {
        imbalance: Some(Imbalance {
            mass: 0.005,
            radius: 0.1,
        }),
        ..bare_reference()
    };
    let f1 = cfg.speed.shaft_hz(0.0);
    let (x, fs) = simulate(cfg, 4.0, 1);
    let spec = analysis::amplitude_spectrum(&x, fs, Window::Hann).unwrap();
    let top = analysis::top_peaks(&spec, 1, spec.df, 0.4 * fs, 0.0);
    assert!(
        (top[0].freq - f1).abs() <= spec.df,
        "largest peak {} Hz, 1x = {f1} Hz",
        top[0].freq
    );
}

/// An outer-race defect: the envelope spectrum peaks at BPFO and its harmonics, and the
/// fault detector names the outer race.
#[test]
fn outer_race_defect_envelope_at_bpfo_harmonics() {
    let cfg = ModelConfig {
        defect: Some(presets::outer_race_defect(topography::MEDIUM_DEFECT)),
        ..bare_reference()
    };
    let ff = fault_freqs(&cfg);
    let (x, fs) = simulate(cfg, 2.0, 1);
    let env = analysis::envelope_spectrum(&x, fs, None).unwrap();
    for k in 1..=4 {
        let f = k as f64 * ff.bpfo;
        let (p, db) = analysis::peak_over_floor_db(&env, f, env.df, 0.3 * ff.bpfo).unwrap();
        assert!(
            (p.freq - f).abs() <= env.df,
            "harmonic {k}: {} vs {f}",
            p.freq
        );
        assert!(db > 15.0, "harmonic {k}: only {db:.1} dB over the floor");
    }
    let top = analysis::top_peaks(&env, 1, 1.0, 0.4 * fs, 0.0);
    assert!(
        (top[0].freq - ff.bpfo).abs() <= env.df,
        "largest envelope line {}",
        top[0].freq
    );
    let d = analysis::detect_fault(&env, &ff, &analysis::DetectParams::default());
    assert_eq!(d.family, FaultFamily::OuterRace);
}

/// Outer-race waviness of order N_w with N elements excites only multiples of the ball
/// pass frequency, strongest at the multiple m·BPFO whose order m·N is nearest N_w
/// (Harsha 2005: lines at qN·ω_c with qN = N_w ± p). No line sits at N_w·FTF itself.
#[test]
fn waviness_excites_expected_orders() {
    let cfg = ModelConfig {
        waviness: Some(Waviness {
            amplitude: 0.2e-6,
            wavelength: 0.8e-3,
        }),
        ..bare_reference()
    };
    let model = wearsim_core::Model::new_checked(cfg.clone()).unwrap();
    let nw = model.waviness_order() as f64;
    let n = cfg.bearing.elements as f64;
    let ff = fault_freqs(&cfg);
    let (x, fs) = simulate(cfg, 4.0, 1);
    let spec = analysis::amplitude_spectrum(&x, fs, Window::Hann).unwrap();
    let lo = 0.5 * nw * ff.ftf;
    let hi = (1.5 * nw * ff.ftf).min(0.4 * fs);
    let peaks = analysis::top_peaks(&spec, 5, lo, hi, 3.0 * spec.df);
    let mut orders = vec![];
    for p in &peaks {
        let m = (p.freq / ff.bpfo).round();
        assert!(
            (p.freq - m * ff.bpfo).abs() <= 1.5 * spec.df,
            "peak {} Hz is not a BPFO multiple",
            p.freq
        );
        orders.push(m * n);
    }
    let strongest = orders[0];
    assert!(
        (strongest - nw).abs() <= n,
        "strongest at order {strongest}, N_w = {nw}"
    );
    // Nothing at N_w·FTF unless that is a BPFO multiple.
    if (nw / n - (nw / n).round()).abs() > 0.1 {
        let at = analysis::peak_near(&spec, nw * ff.ftf, spec.df)
            .map(|p| p.value)
            .unwrap_or(0.0);
        assert!(at < 0.05 * peaks[0].value, "line at N_w·FTF: {at}");
    }
}

/// Random slip smears the fault harmonics: the share of each high envelope harmonic's
/// power that stays in its central bins falls with slip (Randall & Antoni 2011).
#[test]
fn slip_broadens_fault_harmonics() {
    let coherence = |fraction: f64| {
        let cfg = ModelConfig {
            defect: Some(presets::outer_race_defect(topography::MEDIUM_DEFECT)),
            slip: Some(Slip { fraction }),
            ..bare_reference()
        };
        let ff = fault_freqs(&cfg);
        let (x, fs) = simulate(cfg, 4.0, 3);
        let env = analysis::envelope_spectrum(&x, fs, None).unwrap();
        let mut share = 0.0;
        for k in 4..=8 {
            let c = env.bin_of(k as f64 * ff.bpfo);
            let w = (0.3 * ff.bpfo / env.df) as usize;
            let p2 = |i: usize| env.values[i] * env.values[i];
            let central: f64 = (c - 2..=c + 2).map(p2).sum();
            let total: f64 = (c - w..=c + w).map(p2).sum();
            share += central / total / 5.0;
        }
        share
    };
    let (clean, slipping) = (coherence(0.0), coherence(0.03));
    assert!(clean > 0.8, "without slip {clean}");
    assert!(slipping < 0.7 * clean, "slip 3 %: {slipping} vs {clean}");
}

/// Varying compliance (Sunnersjö 1978): a radially loaded bearing with clearance and no
/// other excitation vibrates at multiples of the ball pass frequency only.
#[test]
fn varying_compliance_lines_at_bpfo_multiples() {
    let cfg = ModelConfig {
        clearance: 2e-6,
        ..bare_reference()
    };
    let ff = fault_freqs(&cfg);
    let (x, fs) = simulate(cfg, 4.0, 1);
    let spec = analysis::amplitude_spectrum(&x, fs, Window::Hann).unwrap();
    for p in analysis::top_peaks(&spec, 5, spec.df, 0.4 * fs, 3.0 * spec.df) {
        let m = (p.freq / ff.bpfo).round();
        assert!(
            m >= 1.0 && (p.freq - m * ff.bpfo).abs() <= 1.5 * spec.df,
            "line at {} Hz",
            p.freq
        );
    }
}
