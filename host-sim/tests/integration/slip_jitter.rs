//! Why the detector needs the elements' slip: the cepstral pre-whitening (Sawalhi & Randall
//! 2011) sets every spectral line to the same magnitude, so an *exactly* periodic impulse
//! train — discrete lines at the harmonics of its rate — is flattened into the noise, while
//! a real bearing's train, whose impulses wander by 1–2 % of a period because the elements
//! slip (Randall & Antoni 2011, "Rolling element bearing diagnostics — A tutorial", §2), is
//! pseudo-cyclostationary: its energy is spread over bands the whitening keeps, and its
//! envelope shows the fault rate. Synthetic McFadden & Smith trains
//! (`analysis::synth::FaultSignal`) at four sample rates: with 1 % jitter the outer- and
//! inner-race trains are called with confidence ≥ 0.95; the same outer-race train without
//! jitter is not called (measured; `docs/cwru-detector.md`).

use wearsim_host::analysis::chain::{analyze_signal, Method};
use wearsim_host::analysis::synth::FaultSignal;
use wearsim_host::analysis::{FaultFamily, FaultFrequencies};

/// Sample rates checked, Hz (the CWRU, XJTU/FEMTO, CWRU 48 k and MFPT rates).
const RATES: [f64; 4] = [12_000.0, 25_600.0, 48_000.0, 97_656.0];
/// Record length, s.
const SECONDS: f64 = 5.0;
/// Shaft rate, Hz (CWRU 0 hp).
const SHAFT_HZ: f64 = 29.95;

fn kinematics() -> FaultFrequencies {
    let cfg = wearsim_core::presets::by_name("cwru-6205-de").expect("preset");
    wearsim_core::kinematics::FaultOrders::of(&cfg.bearing).at(SHAFT_HZ, 3000.0)
}

/// The call and confidence for a train at `fault_hz`, amplitude-modulated at `mod_hz` (depth
/// `depth`), ringing at 3 kHz, noise σ = 0.5 of the impulse amplitude, with `jitter`.
fn call(fs: f64, fault_hz: f64, mod_hz: f64, depth: f64, jitter: f64) -> (FaultFamily, f64) {
    let x = FaultSignal {
        fs,
        fault_hz,
        mod_hz,
        mod_depth: depth,
        resonance_hz: 3000.0,
        damping: 0.05,
        impulse_amp: 1.0,
        noise_sigma: 0.5,
        seed: 5,
        jitter,
    }
    .generate((fs * SECONDS) as usize);
    let a = analyze_signal(&x, fs, &kinematics(), &Method::default()).expect("analysis");
    (a.diagnosis.family, a.diagnosis.confidence)
}

#[test]
fn slipping_outer_and_inner_race_trains_are_called_at_every_rate() {
    let ff = kinematics();
    for fs in RATES {
        let (f, c) = call(fs, ff.bpfo, 0.0, 0.0, 0.01);
        eprintln!("outer race, 1 % jitter, {fs} Hz: {f:?} {c:.4}");
        assert!(
            f == FaultFamily::OuterRace && c >= 0.95,
            "{fs} Hz: {f:?} {c}"
        );
        // An inner-race defect passes through the load zone once per shaft turn.
        let (f, c) = call(fs, ff.bpfi, SHAFT_HZ, 0.8, 0.01);
        eprintln!("inner race, 1 % jitter, {fs} Hz: {f:?} {c:.4}");
        assert!(
            f == FaultFamily::InnerRace && c >= 0.95,
            "{fs} Hz: {f:?} {c}"
        );
    }
}

#[test]
fn an_exactly_periodic_train_is_whitened_away() {
    let ff = kinematics();
    for fs in [12_000.0, 48_000.0] {
        let (f, c) = call(fs, ff.bpfo, 0.0, 0.0, 0.0);
        eprintln!("outer race, no jitter, {fs} Hz: {f:?} {c:.4}");
        assert_eq!(f, FaultFamily::None, "{fs} Hz: confidence {c}");
    }
}
