//! Signature tests of the candidate effects (`wearsim_core::effects`): each effect, added
//! to a baseline, must produce its physical signature (frequency content, sidebands,
//! noise level…) with tolerances that a wrong implementation would fail.
// Written against `Real` (f64 or f32 by package): casts that are no-ops in one precision are
// needed in the other.
#![allow(clippy::unnecessary_cast)]
#![allow(clippy::needless_range_loop)]

mod common;

use common::consts::TAU;
use common::run;
use wearsim_core::effects::transfer_path::{Mode, TransferPath};
use wearsim_core::effects::{self, Effects, CATALOGUE};
use wearsim_core::forces::defect::{DefectConfig, DefectLocation};
use wearsim_core::{presets, ConfigError, Model, ModelConfig, Real, Sample};

fn thesis() -> ModelConfig {
    presets::by_name("thesis-61810").unwrap()
}

/// The thesis bearing with only the given excitations.
fn clean() -> ModelConfig {
    ModelConfig {
        imbalance: None,
        waviness: None,
        roughness: None,
        defect: None,
        slip: None,
        ..thesis()
    }
}

fn with(mut cfg: ModelConfig, name: &str, params: &[(&str, Real)]) -> ModelConfig {
    let info = effects::info(name).unwrap();
    let values: Vec<Real> = info
        .params
        .iter()
        .map(|p| {
            params
                .iter()
                .find(|(n, _)| *n == p.name)
                .map(|(_, v)| *v)
                .unwrap_or(p.default as Real)
        })
        .collect();
    cfg.effects.set_named(name, &values).unwrap();
    cfg
}

fn accel(cfg: ModelConfig, seed: u64, seconds: Real) -> (Model, Vec<Real>) {
    let m = Model::new_checked(cfg).unwrap();
    let n = (seconds * m.config().output_rate) as usize;
    let a = run(&m, seed, n).iter().map(|s: &Sample| s.accel).collect();
    (m, a)
}

/// Joint least-squares amplitudes of sinusoids at `freqs` in `x` sampled at `fs`
/// (leakage between close lines is removed by fitting them together, plus a mean).
fn amplitudes(x: &[Real], fs: Real, freqs: &[Real]) -> Vec<Real> {
    let k = 2 * freqs.len() + 1;
    let mut ata = vec![vec![0.0; k]; k];
    let mut atb = vec![0.0; k];
    let mut row = vec![0.0; k];
    for (i, xi) in x.iter().enumerate() {
        let t = i as Real / fs;
        for (j, f) in freqs.iter().enumerate() {
            let (s, c) = (TAU * f * t).sin_cos();
            row[2 * j] = s;
            row[2 * j + 1] = c;
        }
        row[k - 1] = 1.0;
        for a in 0..k {
            atb[a] += row[a] * xi;
            for b in 0..k {
                ata[a][b] += row[a] * row[b];
            }
        }
    }
    // Gaussian elimination with partial pivoting.
    for c in 0..k {
        let p = (c..k)
            .max_by(|a, b| ata[*a][c].abs().total_cmp(&ata[*b][c].abs()))
            .unwrap();
        ata.swap(c, p);
        atb.swap(c, p);
        for r in 0..k {
            if r != c {
                let f = ata[r][c] / ata[c][c];
                for q in c..k {
                    ata[r][q] -= f * ata[c][q];
                }
                atb[r] -= f * atb[c];
            }
        }
    }
    let sol: Vec<Real> = (0..k).map(|i| atb[i] / ata[i][i]).collect();
    (0..freqs.len())
        .map(|j| sol[2 * j].hypot(sol[2 * j + 1]))
        .collect()
}

fn rms(x: &[Real]) -> Real {
    let m = x.iter().sum::<Real>() / x.len() as Real;
    (x.iter().map(|v| (v - m) * (v - m)).sum::<Real>() / x.len() as Real).sqrt()
}

/// Squared envelope proxy: the squared signal with its mean removed.
fn squared(x: &[Real]) -> Vec<Real> {
    let sq: Vec<Real> = x.iter().map(|v| v * v).collect();
    let m = sq.iter().sum::<Real>() / sq.len() as Real;
    sq.iter().map(|v| v - m).collect()
}

#[test]
fn all_effects_are_deterministic_and_off_means_baseline() {
    let base = thesis();
    let mut all = base.clone();
    for e in CATALOGUE.iter() {
        let d: Vec<Real> = e.params.iter().map(|p| p.default as Real).collect();
        all.effects.set_named(e.name, &d).unwrap();
    }
    let (_, a) = accel(all.clone(), 7, 0.2);
    let (_, b) = accel(all, 7, 0.2);
    assert_eq!(a, b);
    let (_, c) = accel(base.clone(), 7, 0.2);
    assert_ne!(a, c);
    // Effects::NONE is the baseline, bit for bit.
    let (_, d) = accel(
        ModelConfig {
            effects: Effects::NONE,
            ..base
        },
        7,
        0.2,
    );
    assert_eq!(c, d);
}

#[test]
fn slip_smears_the_higher_fault_harmonics() {
    let base = ModelConfig {
        slip: None,
        ..thesis()
    };
    let fr = presets::THESIS_SHAFT_HZ;
    let (m, a0) = accel(base.clone(), 3, 2.0);
    let bpfo = m.orders().bpfo * fr;
    let fs = m.config().output_rate;
    let (m1, a1) = accel(with(base, "slip", &[("fraction", 0.08)]), 3, 2.0);
    assert_eq!(m1.config().slip.map(|s| s.fraction), Some(0.08));
    let h = |a: &[Real]| amplitudes(&squared(a), fs, &[bpfo, 4.0 * bpfo]);
    let (h0, h1) = (h(&a0), h(&a1));
    let (r0, r1) = (h0[1] / h0[0], h1[1] / h1[0]);
    // Gaussian jitter σ = 0.08 pitch attenuates harmonic k by exp(−(2πkσ)²/2): k = 1:
    // 0.88, k = 4: 0.13, so the 4th/1st ratio falls by about 7.
    println!("slip: 4th/1st harmonic {r0:.3} -> {r1:.3}");
    assert!(r1 < 0.35 * r0, "{r0} -> {r1}");
}

/// Squared acceleration averaged synchronously over an inner-race defect's angle ψ from the
/// load-zone centre, in 36 bins of 10° from ψ = 0 (defect angle = shaft angle; centre at
/// π/2), skipping the first 1000 samples.
fn synchronous_energy(m: &Model, a: &[Real], fr: Real) -> Vec<Real> {
    let mut e = [(0.0 as Real); 36];
    let mut n = [0usize; 36];
    for (i, v) in a.iter().enumerate().skip(1000) {
        let ang = TAU * fr * m.output_time(i as u64) - common::consts::FRAC_PI_2;
        let b = (ang.rem_euclid(TAU) / TAU * 36.0) as usize % 36;
        e[b] += v * v;
        n[b] += 1;
    }
    e.iter().zip(n).map(|(x, k)| x / k.max(1) as Real).collect()
}

#[test]
fn load_zone_preload_widens_the_zone_as_stribeck_harris_says() {
    let base = ModelConfig {
        slip: None,
        defect: Some(DefectConfig {
            location: DefectLocation::InnerRace { angle: 0.0 },
            ..thesis().defect.unwrap()
        }),
        ..clean()
    };
    let m0 = Model::new_checked(base.clone()).unwrap();
    let y0 = m0.equilibrium().y0;
    let pre = with(
        base.clone(),
        "load-zone",
        &[("depth", 0.0), ("preload", 2.0)],
    );
    let m1 = Model::new_checked(pre.clone()).unwrap();
    let y1 = m1.equilibrium().y0;
    // Static balance of the preloaded bearing, element by element (K y + Σ Q_j sin θ_j =
    // W with Q_j = K_h (y sin θ_j + δ_p)^{3/2} over every element, δ_p = 2 y₀), at the two
    // cage positions the equilibrium averages.
    let c = pre.clone();
    let n = c.bearing.elements as usize;
    let dp = 2.0 * y0;
    let mut balance = 0.0;
    for offset in [0.0, 0.5] {
        // Solve this cage position's balance by bisection, as an independent check.
        let net = |y: Real| {
            c.structure.stiffness * y
                + (0..n)
                    .map(|j| {
                        let s = ((j as Real + offset) * TAU / n as Real).sin();
                        m1.contact().load(y * s + dp) * s
                    })
                    .sum::<Real>()
                - c.radial_load
        };
        let (mut lo, mut hi) = (0.0, y0);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if net(mid) < 0.0 {
                lo = mid
            } else {
                hi = mid
            }
        }
        balance += 0.5 * lo;
    }
    println!("preload 2 y0: y {y0:.3e} -> {y1:.3e} m (independent balance {balance:.3e})");
    assert!((y1 - balance).abs() < 1e-3 * balance, "{y1} vs {balance}");
    // Stiffer and wider: the displacement falls and ε = ½(1 + δ_p/y) exceeds 1 (every
    // element loaded; the top element's load ((δ_p − y)/(δ_p + y))^{3/2} of the bottom's).
    let eps = 0.5 * (1.0 + dp / y1);
    assert!(y1 < y0 && eps > 1.0, "y {y0} -> {y1}, eps {eps}");
    // Dynamics: the defect now impacts at the top of the bearing (ψ = 180°), where the
    // half-circle zone of the baseline has no contact at all.
    let fr = presets::THESIS_SHAFT_HZ;
    let (_, a0) = accel(base, 3, 2.0);
    let (_, a1) = accel(pre, 3, 2.0);
    let top = |a: &[Real]| {
        let e = synchronous_energy(&m0, a, fr);
        (e[17] + e[18] + e[19]) / 3.0 / ((e[0] + e[35]) / 2.0)
    };
    let (t0, t1) = (top(&a0), top(&a1));
    println!("preload: energy at the top / centre {t0:.4} -> {t1:.4}");
    // Hertz: Q_top/Q_bottom = ((δ_p − y)/(δ_p + y))^{3/2} ≈ 0.3 here; the impact energy
    // falls faster than the load, but the top must carry a clear fraction of it and far
    // more than without preload.
    assert!(t1 > 0.05 && t1 > 5.0 * t0, "{t0} -> {t1}");
}

#[test]
fn load_zone_modulates_inner_race_impacts_at_shaft_speed() {
    let base = ModelConfig {
        slip: None,
        defect: Some(DefectConfig {
            location: DefectLocation::InnerRace { angle: 0.0 },
            ..thesis().defect.unwrap()
        }),
        ..clean()
    };
    let fr = presets::THESIS_SHAFT_HZ;
    let (m, a0) = accel(base.clone(), 3, 2.0);
    let (_, a1) = accel(
        with(base, "load-zone", &[("depth", 1.0), ("epsilon", 0.25)]),
        3,
        2.0,
    );
    let profile = |a: &[Real]| {
        let e = synchronous_energy(&m, a, fr);
        // Energy on the entering flank, ψ in −70°..−40° (the trailing flank is blurred by
        // the ringing of the impacts), over the energy at |ψ| < 10°.
        (e[29] + e[30] + e[31]) / 3.0 / ((e[0] + e[35]) / 2.0)
    };
    let (p0, p1) = (profile(&a0), profile(&a1));
    println!("load-zone: energy at -70..-40 deg / centre {p0:.4} -> {p1:.4}");
    // Stribeck with ε = 0.25 zeroes the defect force beyond 60° and leaves
    // (1 − 0.29/0.5)^1.5 ≈ 0.27 of it at 45° (energy ≈ 0.07), against the baseline's
    // Hertz modulation alone: the flank energy must fall to well under half.
    assert!(p1 < 0.4 * p0, "{p0} -> {p1}");
    // The Stribeck gain itself.
    let p = effects::load_zone::Params {
        depth: 1.0,
        epsilon: 0.5,
        preload: 0.0,
    };
    assert!((p.gain(1.0) - 1.0).abs() < 1e-12);
    assert!(p.gain(0.0).abs() < 1e-12 && p.gain(-1.0) == 0.0);
    assert!((p.gain(0.5) - (0.5 as Real).powf(1.5)).abs() < 1e-12);
    let half = effects::load_zone::Params { depth: 0.5, ..p };
    assert!((half.gain(0.0) - 0.5).abs() < 1e-12);
}

#[test]
fn transfer_path_impulse_response_peaks_at_the_modes() {
    let h = 1.0 / 80_000.0;
    let modes = [
        Mode {
            freq_hz: 1500.0,
            zeta: 0.02,
            gain: 4.0,
        },
        Mode {
            freq_hz: 4000.0,
            zeta: 0.03,
            gain: 2.0,
        },
        Mode {
            freq_hz: 7000.0,
            zeta: 0.05,
            gain: 1.0,
        },
    ];
    let tp = TransferPath::design(
        &effects::transfer_path::Params {
            modes,
            path_gain: 1.0,
        },
        h,
    );
    let mut st = Default::default();
    let ir: Vec<Real> = (0..40_000)
        .map(|i| tp.filter(&mut st, if i == 0 { 1.0 } else { 0.0 }))
        .collect();
    // The broadband path gain scales the whole response, modes included, and nothing else.
    let quiet = TransferPath::design(
        &effects::transfer_path::Params {
            modes,
            path_gain: 0.125,
        },
        h,
    );
    let mut sq = Default::default();
    for (i, v) in ir.iter().enumerate() {
        let q = quiet.filter(&mut sq, if i == 0 { 1.0 } else { 0.0 });
        assert!(
            (q - 0.125 * v).abs() <= 1e-12 * v.abs().max(1e-300),
            "{i}: {q} vs {v}"
        );
    }
    let mag = |f: Real| {
        let (mut re, mut im) = (0.0, 0.0);
        for (i, v) in ir.iter().enumerate() {
            let (s, c) = (TAU * f * i as Real * h).sin_cos();
            re += v * c;
            im -= v * s;
        }
        re.hypot(im)
    };
    let spectrum: Vec<(Real, Real)> = (10..1000)
        .map(|k| (k as Real * 10.0, mag(k as Real * 10.0)))
        .collect();
    let peaks: Vec<(Real, Real)> = spectrum
        .windows(3)
        .filter(|w| w[1].1 > w[0].1 && w[1].1 > w[2].1 && w[1].1 > 1.2)
        .map(|w| w[1])
        .collect();
    println!("transfer-path peaks {peaks:?}");
    assert_eq!(peaks.len(), 3, "{peaks:?}");
    for (p, m) in peaks.iter().zip(modes) {
        assert!((p.0 - m.freq_hz).abs() <= 10.0, "{p:?} vs {m:?}");
        // Peak magnitude 1 + g (the neighbouring modes add a little).
        assert!(
            (mag(m.freq_hz) - (1.0 + m.gain)).abs() < 0.08 * (1.0 + m.gain),
            "{m:?}"
        );
    }
    // Far from the modes the path is transparent.
    assert!((mag(200.0) - 1.0).abs() < 0.03 && (mag(20_000.0) - 1.0).abs() < 0.05);
}

#[test]
fn transfer_path_in_the_model_lifts_its_band() {
    let base = ModelConfig {
        slip: None,
        ..thesis()
    };
    let (m, a0) = accel(base.clone(), 5, 1.0);
    let fs = m.config().output_rate;
    let (_, a1) = accel(
        with(
            base,
            "transfer-path",
            &[("f1", 3000.0), ("zeta1", 0.02), ("gain1", 5.0)],
        ),
        5,
        1.0,
    );
    let band = |a: &[Real], f0: Real| -> Real {
        (0..41)
            .map(|k| f0 - 20.0 + k as Real)
            .map(|f| amplitudes(a, fs, &[f])[0].powi(2))
            .sum()
    };
    let r_mode = (band(&a1, 3000.0) / band(&a0, 3000.0)).sqrt();
    let r_off = (band(&a1, 6000.0) / band(&a0, 6000.0)).sqrt();
    println!("transfer-path: band gain at 3 kHz {r_mode:.2}, at 6 kHz {r_off:.2}");
    // |1 + g·BP| over ±20 Hz of a ζ = 0.02 (±60 Hz half-power) mode: 4.5..6.
    assert!(r_mode > 4.0 && r_mode < 6.2, "{r_mode}");
    assert!((r_off - 1.0).abs() < 0.1, "{r_off}");
    // Above fs/2.5 the frequency is rejected, naming the field.
    let bad = with(thesis(), "transfer-path", &[("f1", 9000.0)]);
    match Model::new_checked(bad) {
        Err(ConfigError::OutOfRange { field, max, .. }) => {
            assert_eq!(field, "transfer-path.f1");
            assert_eq!(max, 20_000.0 / 2.5);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn speed_fluctuation_puts_sidebands_on_the_shaft_line() {
    let base = ModelConfig {
        imbalance: thesis().imbalance,
        ..clean()
    };
    let fr = presets::THESIS_SHAFT_HZ;
    let (a, fm) = (0.05, 5.0);
    let freqs = [fr - fm, fr, fr + fm];
    let (m, a0) = accel(base.clone(), 1, 4.0);
    let fs = m.config().output_rate;
    let (m1, a1) = accel(
        with(
            base,
            "speed-fluctuation",
            &[("amplitude", a), ("freq_hz", fm)],
        ),
        1,
        4.0,
    );
    // Skip the settling transient.
    let h0 = amplitudes(&a0[4000..], fs, &freqs);
    let h1 = amplitudes(&a1[4000..], fs, &freqs);
    // Reference: the imbalance force ω² sin θ with the same modulated speed, its lines
    // weighted by the accelerance ∝ f² well below resonance.
    let fsr = 20_000.0;
    let reference: Vec<Real> = (0..80_000)
        .map(|i| {
            let t = i as Real / fsr;
            let w = TAU * fr * (1.0 + a * (TAU * fm * t).sin());
            let th = TAU * fr * t - a * fr / fm * (TAU * fm * t).cos();
            w * w * th.sin()
        })
        .collect();
    let hr = amplitudes(&reference, fsr, &freqs);
    let wgt = |i: usize| (freqs[i] / fr).powi(2);
    let expect = (hr[0] * wgt(0) + hr[2] * wgt(2)) / hr[1];
    let got = (h1[0] + h1[2]) / h1[1];
    let before = (h0[0] + h0[2]) / h0[1];
    println!("speed-fluctuation: sidebands/carrier {before:.4} -> {got:.4} (expected {expect:.4})");
    assert!(before < 0.01, "{before}");
    assert!((got - expect).abs() < 0.15 * expect, "{got} vs {expect}");
    assert!(m1.oversample() >= m.oversample());
}

#[test]
fn sensor_adds_noise_hum_and_bandwidth() {
    let base = thesis();
    let (m, a0) = accel(base.clone(), 9, 1.0);
    let fs = m.config().output_rate;
    let (_, a1) = accel(
        with(
            base.clone(),
            "sensor",
            &[
                ("noise", 0.5),
                ("hum", 0.2),
                ("hum_hz", 50.0),
                ("hum_harmonics", 0.25),
            ],
        ),
        9,
        1.0,
    );
    let d: Vec<Real> = a1.iter().zip(&a0).map(|(x, y)| x - y).collect();
    let h = amplitudes(&d, fs, &[50.0, 100.0, 150.0]);
    println!("sensor: hum {h:?}");
    assert!((h[0] - 0.2).abs() < 0.01 && (h[1] - 0.05).abs() < 0.01 && (h[2] - 0.05).abs() < 0.01);
    let noise_rms =
        (rms(&d).powi(2) - 0.5 * ((0.2 as Real).powi(2) + 2.0 * (0.05 as Real).powi(2))).sqrt();
    assert!((noise_rms - 0.5).abs() < 0.02, "{noise_rms}");
    // Low-pass: the output's lines are the input's times |H(f)| of a one-pole at 500 Hz.
    let p = effects::sensor::Params {
        noise: 0.0,
        corner_hz: 500.0,
        hum: 0.0,
        hum_hz: 50.0,
        hum_harmonics: 0.0,
    };
    let (_, a2) = accel(
        with(base, "sensor", &[("noise", 0.0), ("corner_hz", 500.0)]),
        9,
        1.0,
    );
    let chain = effects::sensor::SensorChain::design(&p, fs);
    let fr = presets::THESIS_SHAFT_HZ;
    let bpfo = m.orders().bpfo * fr;
    for f in [bpfo * 10.0, bpfo * 20.0] {
        let f = f.round();
        let g = amplitudes(&a2[200..], fs, &[f])[0] / amplitudes(&a0[200..], fs, &[f])[0];
        let want = chain.lowpass_gain(f, fs);
        println!("sensor low-pass at {f} Hz: {g:.4} (|H| {want:.4})");
        assert!((g - want).abs() < 0.1 * want, "{f}: {g} vs {want}");
    }
    assert!(chain.lowpass_gain(5000.0, fs) < 0.12);
}

#[test]
fn shaft_harmonics_give_lines_at_2x_and_3x() {
    let fr = presets::THESIS_SHAFT_HZ;
    let base = clean();
    let (m, a0) = accel(base.clone(), 1, 2.0);
    let fs = m.config().output_rate;
    let (_, a1) = accel(
        with(base, "shaft-harmonics", &[("f2", 100.0), ("f3", 50.0)]),
        1,
        2.0,
    );
    let fn_ = m.natural_frequency_hz();
    let zeta = m.damping_ratio();
    let mass = m.config().structure.mass;
    let expect = |f: Real, amp: Real| {
        let r = f / fn_;
        amp / mass * r * r / ((1.0 - r * r).powi(2) + (2.0 * zeta * r).powi(2)).sqrt()
    };
    let h0 = amplitudes(&a0[2000..], fs, &[2.0 * fr, 3.0 * fr]);
    let h1 = amplitudes(&a1[2000..], fs, &[2.0 * fr, 3.0 * fr]);
    let (e2, e3) = (expect(2.0 * fr, 100.0), expect(3.0 * fr, 50.0));
    println!(
        "shaft-harmonics: 2x {:.4e} (exp {e2:.4e}), 3x {:.4e} (exp {e3:.4e}); off {h0:?}",
        h1[0], h1[1]
    );
    assert!((h1[0] - e2).abs() < 0.05 * e2);
    assert!((h1[1] - e3).abs() < 0.05 * e3);
    assert!(h0[0] < 0.01 * e2 && h0[1] < 0.01 * e3);
}

#[test]
fn running_in_raises_roughness_early_then_decays() {
    let base = ModelConfig {
        roughness: thesis().roughness,
        ..clean()
    };
    let (m, a0) = accel(base.clone(), 2, 2.0);
    let fs = m.config().output_rate;
    let (_, a1) = accel(
        with(
            base.clone(),
            "running-in",
            &[("factor", 5.0), ("decay_revs", 5.0)],
        ),
        2,
        2.0,
    );
    let w = |a: &[Real], t0: Real, t1: Real| rms(&a[(t0 * fs) as usize..(t1 * fs) as usize]);
    let fr = presets::THESIS_SHAFT_HZ;
    let early = w(&a1, 0.02, 0.06) / w(&a0, 0.02, 0.06);
    // Mean factor over 0.02..0.06 s.
    let expect: Real = (0..40)
        .map(|i| 1.0 + 4.0 * (-(0.02 + i as Real * 1e-3) * fr / 5.0).exp())
        .sum::<Real>()
        / 40.0;
    let late = w(&a1, 1.5, 2.0) / w(&a0, 1.5, 2.0);
    println!("running-in: early ratio {early:.3} (expected {expect:.3}), late {late:.3}");
    assert!(
        (early - expect).abs() < 0.15 * expect,
        "{early} vs {expect}"
    );
    assert!((late - 1.0).abs() < 0.05, "{late}");
    // Needs roughness.
    let no_rough = with(clean(), "running-in", &[]);
    assert!(matches!(
        Model::new_checked(no_rough),
        Err(ConfigError::Inconsistent {
            field: "effect.running-in",
            ..
        })
    ));
}

/// Separate events in `x`: runs of samples above `thr`, a new event when more than `gap`
/// samples passed since the last sample above it (an impact's ringing is one event).
fn events(x: &[Real], thr: Real, gap: usize) -> Vec<usize> {
    let mut out: Vec<usize> = vec![];
    let mut last: Option<usize> = None;
    for (i, v) in x.iter().enumerate() {
        if v.abs() > thr {
            if last.is_none_or(|l| i - l > gap) {
                out.push(i);
            }
            last = Some(i);
        }
    }
    out
}

fn kurtosis(x: &[Real]) -> Real {
    let m = x.iter().sum::<Real>() / x.len() as Real;
    let v = x.iter().map(|a| (a - m).powi(2)).sum::<Real>() / x.len() as Real;
    x.iter().map(|a| (a - m).powi(4)).sum::<Real>() / x.len() as Real / (v * v)
}

#[test]
fn running_in_summits_arrive_as_a_decaying_poisson_stream_of_impacts() {
    let base = ModelConfig {
        roughness: thesis().roughness,
        ..clean()
    };
    let fr = presets::THESIS_SHAFT_HZ;
    let seconds = 8.0;
    let (m, a0) = accel(base.clone(), 3, seconds);
    let fs = m.config().output_rate;
    // Steady stream (decay far beyond the record): S contacts per revolution, sparse
    // enough (5 a second) that two rarely fall within one impact's ringing.
    let s = 0.2;
    let (_, a1) = accel(
        with(
            base.clone(),
            "running-in",
            &[
                ("factor", 1.0),
                ("decay_revs", 1e9),
                ("summits", s),
                ("summit_height", 3.0),
            ],
        ),
        3,
        seconds,
    );
    // Each impact rings the structure for a few ms: 3 ms below the threshold end one.
    let thr = 6.0 * rms(&a0);
    let gap = (0.003 * fs) as usize;
    let skip = (0.05 * fs) as usize;
    let n0 = events(&a0[skip..], thr, gap).len();
    let n1 = events(&a1[skip..], thr, gap).len() as Real;
    let expect = s * fr * (seconds - 0.05);
    println!("summits: {n1} impacts (expected {expect:.1}), {n0} without");
    assert_eq!(n0, 0, "the baseline has no impacts above {thr}");
    assert!(
        (n1 - expect).abs() < 4.0 * expect.sqrt() + 2.0,
        "{n1} impacts against a Poisson mean of {expect}"
    );
    // Sparse impacts raise crest factor and kurtosis far faster than the level (a
    // Gaussian level change leaves both unchanged).
    let crest = |x: &[Real]| x.iter().fold(0.0 as Real, |a, v| a.max(v.abs())) / rms(x);
    let (k0, k1) = (kurtosis(&a0[skip..]), kurtosis(&a1[skip..]));
    let (c0, c1) = (crest(&a0[skip..]), crest(&a1[skip..]));
    let r = rms(&a1[skip..]) / rms(&a0[skip..]);
    println!("summits: kurtosis {k0:.2} -> {k1:.2}, crest {c0:.2} -> {c1:.2}, rms x{r:.3}");
    assert!(k1 / k0 > 10.0 * r && c1 / c0 > 2.0 * r, "not impulsive");

    // Decaying: S·n_d·(1 − e^(−n/n_d)) contacts in the first n revolutions, none late.
    let nd = 20.0;
    let s = 1.0;
    let (_, a2) = accel(
        with(
            base,
            "running-in",
            &[
                ("factor", 1.0),
                ("decay_revs", nd),
                ("summits", s),
                ("summit_height", 3.0),
            ],
        ),
        4,
        seconds,
    );
    let ev = events(&a2[skip..], thr, gap);
    let t = |i: &usize| (i + skip) as Real / fs;
    let early = ev.iter().filter(|i| t(i) < 1.0).count() as Real;
    let late = ev.iter().filter(|i| t(i) >= 3.0 && t(i) < 4.0).count();
    let revs = |t: Real| fr * t;
    let expect = s * nd * ((-revs(0.05) / nd).exp() - (-revs(1.0) / nd).exp());
    let expect_late = s * nd * ((-revs(3.0) / nd).exp() - (-revs(4.0) / nd).exp());
    println!("summits decaying: {early} in the first second (expected {expect:.1}), {late} in 3-4 s (expected {expect_late:.2})");
    assert!((early - expect).abs() < 4.0 * expect.sqrt() + 2.0);
    assert!(late <= 2, "{late} impacts late in the run");
}

#[test]
fn roughness_scales_the_broadband_level() {
    let base = ModelConfig {
        roughness: thesis().roughness,
        ..clean()
    };
    let (_, a0) = accel(base.clone(), 4, 0.5);
    let (_, a1) = accel(with(base.clone(), "roughness", &[("scale", 3.0)]), 4, 0.5);
    let r = rms(&a1[500..]) / rms(&a0[500..]);
    println!("roughness: RMS ratio {r:.3}");
    assert!((r - 3.0).abs() < 0.15, "{r}");
    // Scale 0 leaves only the parametric (varying-compliance) excitation: the level of
    // the model without roughness.
    let (_, a2) = accel(with(base, "roughness", &[("scale", 0.0)]), 4, 0.5);
    let (_, a3) = accel(clean(), 4, 0.5);
    let r0 = rms(&a2[500..]) / rms(&a3[500..]);
    assert!((r0 - 1.0).abs() < 0.01, "{r0}");
    assert!(matches!(
        Model::new_checked(with(clean(), "roughness", &[])),
        Err(ConfigError::Inconsistent {
            field: "effect.roughness",
            ..
        })
    ));
}

#[test]
fn edge_shape_scales_the_five_step_function_and_the_impact() {
    let base = ModelConfig {
        slip: None,
        ..thesis()
    };
    let topo = base.defect.unwrap().topography;
    let m0 = Model::new_checked(base.clone()).unwrap();
    let sharp = with(
        base.clone(),
        "edge-shape",
        &[("length_scale", 0.5), ("asperity_scale", 2.0)],
    );
    let m1 = Model::new_checked(sharp.clone()).unwrap();
    let (s0, s1) = (m0.defect_shape(&topo), m1.defect_shape(&topo));
    assert!((s1.load.entry - (0.5 * s0.load.entry).min(0.5)).abs() < 1e-12);
    assert!((s1.load.impact - 0.5 * s0.load.impact).abs() < 1e-12);
    assert!((s1.load.asperity - 2.0 * s0.load.asperity).abs() < 1e-18);
    // Dynamic signature: a sharper, higher edge gives a larger impact (peak and kurtosis).
    let (_, a0) = accel(base, 6, 1.0);
    let (_, a1) = accel(sharp, 6, 1.0);
    let peak = |a: &[Real]| a[500..].iter().fold(0.0 as Real, |m, v| m.max(v.abs()));
    let kurt = |a: &[Real]| {
        let a = &a[500..];
        let m = a.iter().sum::<Real>() / a.len() as Real;
        let v = a.iter().map(|x| (x - m).powi(2)).sum::<Real>() / a.len() as Real;
        a.iter().map(|x| (x - m).powi(4)).sum::<Real>() / a.len() as Real / (v * v)
    };
    println!(
        "edge-shape: peak {:.3} -> {:.3}, kurtosis {:.2} -> {:.2}",
        peak(&a0),
        peak(&a1),
        kurt(&a0),
        kurt(&a1)
    );
    assert!(peak(&a1) > 1.3 * peak(&a0));
}

/// With every effect on, a checkpoint mid-run continues with exactly the samples of the
/// uninterrupted run (the transfer-path, sensor and running-in memories are saved).
#[test]
fn checkpoint_with_all_effects_continues_bit_identically() {
    use wearsim_core::checkpoint::encoded_len;
    use wearsim_core::State;
    let mut cfg = thesis();
    for e in CATALOGUE.iter() {
        let d: Vec<Real> = e.params.iter().map(|p| p.default as Real).collect();
        cfg.effects.set_named(e.name, &d).unwrap();
    }
    let cfg = with(cfg, "sensor", &[("corner_hz", 3000.0), ("hum", 0.1)]);
    let cfg = with(cfg, "running-in", &[("decay_revs", 3.0)]);
    let model = Model::new_checked(cfg).unwrap();
    let mut a: State<16> = State::new(&model, 5).unwrap();
    let mut first = vec![Sample::default(); 3001];
    model.fill(&mut a, &mut first);
    let mut bytes = vec![0u8; encoded_len(16)];
    let n = a.encode(&mut bytes).unwrap();
    let mut b: State<16> = State::decode(&model, &bytes[..n]).unwrap();
    let mut ra = vec![Sample::default(); 5000];
    let mut rb = ra.clone();
    model.fill(&mut a, &mut ra);
    model.fill(&mut b, &mut rb);
    assert!(ra
        .iter()
        .zip(&rb)
        .all(|(x, y)| x.accel.to_bits() == y.accel.to_bits()));
}
