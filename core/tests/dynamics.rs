//! The integrators and the output path against closed-form solutions of the linear
//! single-degree-of-freedom oscillator `m y'' + c y' + k y = F(t)`.
// Written against `Real` (f64 or f32 by package): casts that are no-ops in one precision are
// needed in the other.
#![allow(clippy::unnecessary_cast)]

mod common;

use common::consts::{PI, TAU};
use common::{constant, linear_sdof, run, sine_fit};
use wearsim_core::forces::imbalance::Imbalance;
use wearsim_core::integrate::IntegratorKind;
use wearsim_core::{Model, ModelConfig, Real, State};

const KINDS: [IntegratorKind; 3] = [
    IntegratorKind::Rk4,
    IntegratorKind::ExactZoh,
    IntegratorKind::ExactFoh,
];

/// Free decay: frequency and damping ratio measured from the emitted acceleration agree
/// with `ω_d = ω_n √(1 − ζ²)` and `ζ` within 0.1 % for every integrator.
#[test]
fn free_decay_matches_closed_form() {
    let (m, k, zeta): (Real, Real, Real) = (1.0, 1.0e6, 0.01);
    let c = 2.0 * zeta * (k * m).sqrt();
    let wn: Real = (k / m).sqrt();
    let fd = wn * (1.0 - zeta * zeta).sqrt() / TAU;
    for kind in KINDS {
        let model = Model::new_checked(linear_sdof(m, k, c, 20_000.0, 2, kind)).unwrap();
        let mut st: State<32> = State::new(&model, 1).unwrap();
        st.set_motion(1e-6, 0.0);
        let n = 20_000;
        let mut out = vec![wearsim_core::Sample::default(); n];
        model.fill(&mut st, &mut out);
        let t: Vec<Real> = (0..n as u64).map(|i| model.output_time(i)).collect();
        let a: Vec<Real> = out.iter().map(|s| s.accel).collect();
        // Zero crossings after the filter's start-up (t > 0.05 s).
        let mut crossings = vec![];
        for i in 1..n {
            if t[i - 1] > 0.05 && t[i] < 0.8 && a[i - 1].signum() != a[i].signum() {
                let frac = a[i - 1] / (a[i - 1] - a[i]);
                crossings.push(t[i - 1] + frac * (t[i] - t[i - 1]));
            }
        }
        let half_periods = (crossings.len() - 1) as Real;
        let f_meas = half_periods / 2.0 / (crossings.last().unwrap() - crossings[0]);
        assert!(
            (f_meas / fd - 1.0).abs() < 1e-3,
            "{kind:?}: f_d {f_meas} vs {fd}"
        );
        // Peaks of |a| (parabolic interpolation), log-linear regression of the envelope.
        let (mut ts, mut ls) = (vec![], vec![]);
        for i in 1..n - 1 {
            let (y0, y1, y2) = (a[i - 1].abs(), a[i].abs(), a[i + 1].abs());
            if t[i] > 0.05 && t[i] < 0.8 && y1 > y0 && y1 >= y2 {
                let d = 0.5 * (y0 - y2) / (y0 - 2.0 * y1 + y2);
                let peak = y1 - 0.25 * (y0 - y2) * d;
                ts.push(t[i] + d * (t[i + 1] - t[i]));
                ls.push(peak.ln());
            }
        }
        let nn = ts.len() as Real;
        let (mt, ml) = (ts.iter().sum::<Real>() / nn, ls.iter().sum::<Real>() / nn);
        let slope = ts
            .iter()
            .zip(&ls)
            .map(|(t, l)| (t - mt) * (l - ml))
            .sum::<Real>()
            / ts.iter().map(|t| (t - mt) * (t - mt)).sum::<Real>();
        let sigma = -slope;
        let wd = TAU * f_meas;
        let zeta_meas = sigma / (sigma * sigma + wd * wd).sqrt();
        assert!(
            (zeta_meas / zeta - 1.0).abs() < 1e-3,
            "{kind:?}: zeta {zeta_meas} vs {zeta}"
        );
    }
}

fn forced_config(kind: IntegratorKind, shaft_hz: Real, fs: Real, r: u32) -> ModelConfig {
    ModelConfig {
        imbalance: Some(Imbalance {
            mass: 1e-5,
            radius: 0.1,
        }),
        speed: constant(shaft_hz),
        ..linear_sdof(1.0, 1.0e6, 20.0, fs, r, kind)
    }
}

/// Steady-state response to the imbalance force `m_u r ω² sin ωt`: acceleration amplitude
/// `ω² F/√((k − mω²)² + (cω)²)` and phase lag `atan2(cω, k − mω²)` at, below and above
/// resonance, within 0.2 % and 2 mrad, for RK4 and the exact/FOH integrator. (The ZOH
/// integrator holds the force half a step late, a first-order phase error of `ωh/2` on the
/// force that the acceleration shows amplified below resonance; its order is checked in
/// `convergence_orders`.)
#[test]
fn forced_response_amplitude_and_phase() {
    let (m, k, c): (Real, Real, Real) = (1.0, 1.0e6, 20.0);
    let fn_ = (k / m).sqrt() / TAU;
    for kind in [IntegratorKind::Rk4, IntegratorKind::ExactFoh] {
        for f in [50.0, fn_, 400.0] {
            let model = Model::new_checked(forced_config(kind, f, 20_000.0, 2)).unwrap();
            let n = 40_000; // 2 s; transient decays as e^{-10 t}
            let out = run(&model, 1, n);
            let t: Vec<Real> = (n as u64 / 2..n as u64)
                .map(|i| model.output_time(i))
                .collect();
            let a: Vec<Real> = out[n / 2..].iter().map(|s| s.accel).collect();
            let (amp, phase) = sine_fit(&a, &t, f);
            let w = TAU * f;
            let force = 1e-5 * 0.1 * w * w;
            let x = force / ((k - m * w * w).powi(2) + (c * w).powi(2)).sqrt();
            let lag = (c * w).atan2(k - m * w * w);
            // a = −ω² X sin(ωt − lag) = ω² X sin(ωt − lag + π)
            let expect_phase = (PI - lag).rem_euclid(TAU);
            let dphi = (phase.rem_euclid(TAU) - expect_phase + PI).rem_euclid(TAU) - PI;
            assert!(
                (amp / (w * w * x) - 1.0).abs() < 2e-3,
                "{kind:?} f={f}: amp {amp} vs {}",
                w * w * x
            );
            // f32: the imbalance's shaft angle accumulates roundings over 80 000 steps
            // (measured 3.3 mrad); a wrong phase model is off by tenths of a radian.
            let limit = if common::SINGLE { 1e-2 } else { 2e-3 };
            assert!(dphi.abs() < limit, "{kind:?} f={f}: phase error {dphi}");
        }
    }
}

/// Global error at a fixed time against the closed-form forced solution, halving the step:
/// the measured orders are 4 (RK4), 1 (exact + ZOH) and 2 (exact + FOH), ±0.3.
#[test]
fn convergence_orders() {
    let (m, k, c): (Real, Real, Real) = (1.0, 1.0e6, 20.0);
    let f = 100.0;
    let w = TAU * f;
    let force = 1e-5 * 0.1 * w * w;
    let wn: Real = (k / m).sqrt();
    let sigma = c / (2.0 * m);
    let wd = (wn * wn - sigma * sigma).sqrt();
    let x = force / ((k - m * w * w).powi(2) + (c * w).powi(2)).sqrt();
    let lag = (c * w).atan2(k - m * w * w);
    let exact = |t: Real| {
        let a = x * lag.sin();
        let b = (sigma * a - x * w * lag.cos()) / wd;
        x * (w * t - lag).sin() + (-sigma * t).exp() * (a * (wd * t).cos() + b * (wd * t).sin())
    };
    let t_end = 0.05;
    for (kind, order) in [
        (IntegratorKind::Rk4, 4.0),
        (IntegratorKind::ExactZoh, 1.0),
        (IntegratorKind::ExactFoh, 2.0),
    ] {
        let mut errs = vec![];
        // In f32 the finest steps hit the rounding floor (RK4 at 16 kHz: 2·10⁻¹¹ m against
        // 3·10⁻¹³ at 8 kHz) and RK4's coarsest is not yet asymptotic: measure lower.
        let rates: &[Real] = match (common::SINGLE, kind) {
            (false, _) => &[2_000.0, 4_000.0, 8_000.0, 16_000.0],
            (true, IntegratorKind::Rk4) => &[1_000.0, 2_000.0, 4_000.0],
            (true, _) => &[500.0, 1_000.0, 2_000.0, 4_000.0],
        };
        for &fs in rates {
            let model = Model::new_checked(forced_config(kind, f, fs, 2)).unwrap();
            let mut st: State<32> = State::new(&model, 1).unwrap();
            st.set_motion(0.0, 0.0);
            let steps = (t_end / model.step_size()).round() as u64;
            for _ in 0..steps {
                let _ = model.step(&mut st);
            }
            errs.push((st.motion().0 - exact(t_end)).abs());
        }
        let orders: Vec<Real> = errs.windows(2).map(|e| (e[0] / e[1]).log2()).collect();
        let mean = orders.iter().sum::<Real>() / orders.len() as Real;
        assert!(
            (mean - order).abs() < 0.3,
            "{kind:?}: measured orders {orders:?}, errors {errs:?}"
        );
    }
}

/// A tone above the output Nyquist frequency (750 Hz at fs = 1 kHz) leaves less than
/// −80 dB of its in-band amplitude at its alias (250 Hz); an in-band tone passes within
/// 0.1 %.
#[test]
fn anti_alias_filter_removes_out_of_band_tone() {
    let kind = IntegratorKind::ExactFoh;
    let reference = Model::new_checked(forced_config(kind, 750.0, 8_000.0, 2)).unwrap();
    let n = 16_000;
    let out = run(&reference, 1, n);
    let t: Vec<Real> = (n as u64 / 2..n as u64)
        .map(|i| reference.output_time(i))
        .collect();
    let a: Vec<Real> = out[n / 2..].iter().map(|s| s.accel).collect();
    let (amp_true, _) = sine_fit(&a, &t, 750.0);
    assert!(amp_true > 0.0);

    let model = Model::new_checked(forced_config(kind, 750.0, 1_000.0, 4)).unwrap();
    let n = 2_000;
    let out = run(&model, 1, n);
    let t: Vec<Real> = (n as u64 / 2..n as u64)
        .map(|i| model.output_time(i))
        .collect();
    let a: Vec<Real> = out[n / 2..].iter().map(|s| s.accel).collect();
    let (alias, _) = sine_fit(&a, &t, 250.0);
    assert!(alias < 1e-4 * amp_true, "alias {alias} vs tone {amp_true}");

    // In band (300 Hz at fs = 1 kHz, below 0.4 fs): the closed-form amplitude within 0.1 %
    // (RK4, so that the integrator's own error stays far below the tolerance).
    let model = Model::new_checked(forced_config(IntegratorKind::Rk4, 300.0, 1_000.0, 8)).unwrap();
    let n = 2_000;
    let out = run(&model, 1, n);
    let t: Vec<Real> = (n as u64 / 2..n as u64)
        .map(|i| model.output_time(i))
        .collect();
    let a: Vec<Real> = out[n / 2..].iter().map(|s| s.accel).collect();
    let (amp, _) = sine_fit(&a, &t, 300.0);
    let w = TAU * 300.0;
    let expect =
        w * w * (1e-5 * 0.1 * w * w) / ((1.0e6 - w * w).powi(2) + (20.0 * w).powi(2)).sqrt();
    assert!(
        (amp / expect - 1.0).abs() < 1e-3,
        "in-band {amp} vs {expect}"
    );
}

/// The anti-alias FIR itself: passband 0–0.4 fs flat within ±0.1 %, stopband from 0.6 fs
/// down by at least 80 dB, for every oversampling ratio.
#[test]
fn anti_alias_frequency_response() {
    use wearsim_core::decimate::AntiAlias;
    for r in 2..=wearsim_core::model::MAX_OVERSAMPLE {
        let aa = AntiAlias::design(r);
        // Impulse response, read tap by tap through the public delay line.
        let mut h = vec![];
        for k in 0..aa.len() {
            let mut l = wearsim_core::decimate::DelayLine::default();
            for i in 0..aa.len() {
                l.push(if i == k { 1.0 } else { 0.0 });
            }
            h.push(aa.output(&l));
        }
        let resp = |f_over_fs_out: Real| {
            let w = TAU * f_over_fs_out / r as Real;
            let (mut re, mut im) = (0.0, 0.0);
            for (n, c) in h.iter().enumerate() {
                re += c * (w * n as Real).cos();
                im -= c * (w * n as Real).sin();
            }
            (re * re + im * im).sqrt()
        };
        for i in 0..=40 {
            let f = 0.4 * i as Real / 40.0;
            assert!(
                (resp(f) - 1.0).abs() < 1e-3,
                "R={r}: passband |H({f})| = {}",
                resp(f)
            );
        }
        for i in 0..=200 {
            let f = 0.6 + (r as Real / 2.0 - 0.6) * i as Real / 200.0;
            assert!(resp(f) < 1e-4, "R={r}: stopband |H({f})| = {}", resp(f));
        }
    }
}

/// Same configuration and seed: bit-identical samples; another seed: different samples.
#[test]
fn determinism() {
    let model =
        Model::new_checked(wearsim_core::presets::by_name("thesis-61810").unwrap()).unwrap();
    let a = run(&model, 42, 20_000);
    let b = run(&model, 42, 20_000);
    let c = run(&model, 43, 20_000);
    assert!(a
        .iter()
        .zip(&b)
        .all(|(x, y)| x.accel.to_bits() == y.accel.to_bits()));
    assert!(a.iter().zip(&c).any(|(x, y)| x.accel != y.accel));
}

/// Shaft angle integrated from the instantaneous speed: a 10 → 31 Hz ramp over 1 s turns
/// the shaft 20.5 revolutions, so the angle ends at π (an `ω·t` phase would not).
#[test]
fn ramp_angle_is_integrated_from_speed() {
    use wearsim_core::speed::SpeedProfile;
    for kind in [IntegratorKind::ExactFoh, IntegratorKind::Rk4] {
        let cfg = ModelConfig {
            speed: SpeedProfile::Ramp {
                from_hz: 10.0,
                to_hz: 31.0,
                duration: 1.0,
            },
            ..linear_sdof(1.0, 1.0e6, 20.0, 10_000.0, 2, kind)
        };
        let model = Model::new_checked(cfg).unwrap();
        let mut st: State<32> = State::new(&model, 1).unwrap();
        let steps = (1.0 / model.step_size()).round() as u64;
        for _ in 0..steps {
            let _ = model.step(&mut st);
        }
        assert!(
            // f32: 20 000 angle advances, each rounded (measured 4.6 mrad); an ω·t phase
            // would end radians away.
            (st.shaft_angle() - PI).abs() < if common::SINGLE { 1e-2 } else { 1e-6 },
            "{kind:?}: angle {}",
            st.shaft_angle()
        );
        assert!((st.shaft_hz() - 31.0).abs() < 1e-9);
    }
}

/// The state has a fixed, documented size: three anti-alias delay lines of
/// `2·MAX_TAPS` reals (24 KiB in `f64`, 12 KiB in `f32`, since ratios up to 16) and under
/// 2.5 KiB of everything else.
#[test]
fn state_size_is_fixed() {
    let size = core::mem::size_of::<State<16>>();
    let lines =
        3 * 2 * wearsim_core::decimate::MAX_TAPS * core::mem::size_of::<wearsim_core::Real>();
    assert!(size < lines + 2560, "State<16> is {size} bytes");
}

/// A state encoded mid-run and decoded continues with exactly the samples of the
/// uninterrupted run (dense life mode resumes from such checkpoints).
#[test]
fn checkpoint_round_trip_continues_bit_identically() {
    use wearsim_core::checkpoint::encoded_len;
    let model =
        Model::new_checked(wearsim_core::presets::by_name("thesis-61810").unwrap()).unwrap();
    let mut a: State<16> = State::new(&model, 5).unwrap();
    let mut first = vec![wearsim_core::Sample::default(); 3001];
    model.fill(&mut a, &mut first);
    let mut bytes = vec![0u8; encoded_len(16)];
    let n = a.encode(&mut bytes).unwrap();
    assert!(n <= bytes.len());
    let mut b: State<16> = State::decode(&model, &bytes[..n]).unwrap();
    let mut ra = vec![wearsim_core::Sample::default(); 5000];
    let mut rb = ra.clone();
    model.fill(&mut a, &mut ra);
    model.fill(&mut b, &mut rb);
    assert!(ra
        .iter()
        .zip(&rb)
        .all(|(x, y)| x.accel.to_bits() == y.accel.to_bits()));
    // Corrupt and truncated checkpoints are errors, not panics.
    assert!(State::<16>::decode(&model, &bytes[..n / 2]).is_err());
    let mut bad = bytes.clone();
    bad[0] ^= 0xFF;
    assert!(State::<16>::decode(&model, &bad).is_err());
    assert!(State::<8>::decode(&model, &bytes).is_err());
}
