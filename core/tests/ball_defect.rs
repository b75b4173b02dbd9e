//! Rolling-element (ball) defects: spin kinematics, impact timing, the envelope signature
//! (2×BSF with FTF sidebands, no BPFO/BPFI), the load-zone modulation at FTF, validation
//! and checkpoints. Scenario: the `cwru-6205-de` preset (SKF 6205, 1797 rpm, 12 kHz) with
//! its defect moved onto a ball.
// Written against `Real` (f64 or f32 by package): casts that are no-ops in one precision are
// needed in the other.
#![allow(clippy::unnecessary_cast)]
#![allow(clippy::needless_range_loop)]

mod common;

use common::consts::{PI, TAU};
use wearsim_core::checkpoint::encoded_len;
use wearsim_core::forces::defect::{DefectConfig, DefectLocation, DefectModel};
use wearsim_core::kinematics::FaultOrders;
use wearsim_core::{presets, ConfigError, Model, ModelConfig, Real, Sample, State};

fn cwru() -> ModelConfig {
    presets::by_name("cwru-6205-de").unwrap()
}

/// The CWRU preset with its 0.007 in defect on ball `element` (spin phase `phase`).
fn ball(element: u8, phase: Real) -> ModelConfig {
    let c = cwru();
    ModelConfig {
        defect: Some(DefectConfig {
            location: DefectLocation::Ball { element, phase },
            ..c.defect.unwrap()
        }),
        ..c
    }
}

fn with_effect(mut cfg: ModelConfig, name: &str, values: &[Real]) -> ModelConfig {
    cfg.effects.set_named(name, values).unwrap();
    cfg
}

/// In-place iterative radix-2 FFT (`inverse` without the 1/n scale); `re.len()` a power of 2.
fn fft(re: &mut [Real], im: &mut [Real], inverse: bool) {
    let n = re.len();
    assert!(n.is_power_of_two() && im.len() == n);
    let mut j = 0;
    for i in 1..n {
        let mut bit = n >> 1;
        while j & bit != 0 {
            j ^= bit;
            bit >>= 1;
        }
        j |= bit;
        if i < j {
            re.swap(i, j);
            im.swap(i, j);
        }
    }
    let sign = if inverse { 1.0 } else { -1.0 };
    let mut len = 2;
    while len <= n {
        let ang = sign * TAU / len as Real;
        for start in (0..n).step_by(len) {
            for k in 0..len / 2 {
                let (s, c) = (ang * k as Real).sin_cos();
                let (a, b) = (start + k, start + k + len / 2);
                let tr = re[b] * c - im[b] * s;
                let ti = re[b] * s + im[b] * c;
                re[b] = re[a] - tr;
                im[b] = im[a] - ti;
                re[a] += tr;
                im[a] += ti;
            }
        }
        len <<= 1;
    }
}

/// Envelope spectrum (Randall & Antoni 2011): FFT band-pass to `band` (Hz), analytic
/// signal from the positive frequencies, its magnitude with the mean removed, Hann
/// window, one-sided amplitude spectrum. Returns (bin spacing Hz, amplitudes).
fn envelope_spectrum(x: &[Real], fs: Real, band: (Real, Real)) -> (Real, Vec<Real>) {
    let n = x.len();
    let df = fs / n as Real;
    let mut re = x.to_vec();
    let mut im = vec![0.0; n];
    fft(&mut re, &mut im, false);
    for k in 0..n {
        let f = k as Real * df;
        let keep = k <= n / 2 && f >= band.0 && f <= band.1;
        let g = if keep { 2.0 / n as Real } else { 0.0 };
        re[k] *= g;
        im[k] *= g;
    }
    fft(&mut re, &mut im, true);
    let env: Vec<Real> = re.iter().zip(&im).map(|(a, b)| a.hypot(*b)).collect();
    let mean = env.iter().sum::<Real>() / n as Real;
    let w: Vec<Real> = (0..n)
        .map(|i| 0.5 - 0.5 * (TAU * i as Real / n as Real).cos())
        .collect();
    let wsum: Real = w.iter().sum();
    let mut re: Vec<Real> = env.iter().zip(&w).map(|(e, w)| (e - mean) * w).collect();
    let mut im = vec![0.0; n];
    fft(&mut re, &mut im, false);
    let amp = (0..=n / 2)
        .map(|k| 2.0 * re[k].hypot(im[k]) / wsum)
        .collect();
    (df, amp)
}

/// Largest envelope amplitude within ±1.5 bins of `f`.
fn line(spec: &(Real, Vec<Real>), f: Real) -> Real {
    let (df, a) = spec;
    let k = (f / df).round() as usize;
    (k - 2..=k + 2).map(|i| a[i]).fold(0.0, Real::max)
}

/// Floor: median envelope amplitude over 20–400 Hz, excluding ±3 bins around the lines of
/// every combination `i·2BSF + j·FTF + l·f_r` that the impacts and the rotor can make.
fn floor(spec: &(Real, Vec<Real>), o: &FaultOrders, fr: Real) -> Real {
    let (df, a) = spec;
    let mut lines = vec![];
    for i in 0..=3 {
        for j in -8..=8 {
            for l in -3..=3 {
                lines.push(i as Real * 2.0 * o.bsf * fr + j as Real * o.ftf * fr + l as Real * fr);
            }
        }
    }
    let mut v: Vec<Real> = (0..a.len())
        .filter(|k| {
            let f = *k as Real * df;
            (20.0..=400.0).contains(&f) && lines.iter().all(|l| (f - l).abs() > 3.0 * df)
        })
        .map(|k| a[k])
        .collect();
    assert!(v.len() > 100);
    v.sort_by(Real::total_cmp);
    v[v.len() / 2]
}

/// Simulates 2^15 samples (2.73 s at 12 kHz) after 0.1 s of settling.
fn accel(cfg: ModelConfig, seed: u64) -> (Model, Vec<Real>) {
    let m = Model::new_checked(cfg).unwrap();
    let mut st: State<16> = State::new(&m, seed).unwrap();
    let mut settle = vec![Sample::default(); (0.1 * m.config().output_rate) as usize];
    m.fill(&mut st, &mut settle);
    let mut out = vec![Sample::default(); 1 << 15];
    m.fill(&mut st, &mut out);
    (m, out.iter().map(|s| s.accel).collect())
}

/// Envelope band: around the preset's housing mode (natural frequency ≈ 3.3 kHz).
fn band(m: &Model) -> (Real, Real) {
    let fnat = m.natural_frequency_hz();
    (0.5 * fnat, (1.6 * fnat).min(0.45 * m.config().output_rate))
}

/// The ball's spin angle relative to the cage is `(θ_shaft − θ_cage)(P − B_d cos φ)/B_d`
/// (inner race rolling on the ball); with `θ_cage = FTF·θ_shaft` this is `BSF·θ_shaft`,
/// BSF of eq. 20. The state's spin angle follows it.
#[test]
fn spin_angle_advances_at_the_ball_spin_order() {
    let cfg = ball(0, 0.3);
    let b = cfg.bearing;
    let o = FaultOrders::of(&b);
    let p = b.pitch_diameter;
    let bd = b.element_diameter * b.contact_angle.cos();
    let rolling = (p - bd) / bd * (1.0 - o.ftf);
    assert!(
        (rolling - o.bsf).abs() < 1e-12 * o.bsf,
        "{rolling} vs {}",
        o.bsf
    );
    // 6205: BSF = 2.357 orders (CWRU's published 4.7135 × f_r is 2×BSF).
    assert!(
        (2.0 * o.bsf - 4.7135).abs() < 0.002,
        "2 BSF = {}",
        2.0 * o.bsf
    );

    let m = Model::new_checked(cfg).unwrap();
    let mut st: State<16> = State::new(&m, 1).unwrap();
    assert!((st.spin_angle() - 0.3).abs() < common::tol(1e-15));
    let steps = 40_000u64;
    for _ in 0..steps {
        m.step(&mut st);
    }
    let shaft = TAU * m.config().speed.shaft_hz(0.0) * m.step_size() * steps as Real;
    let expect = (0.3 + o.bsf * shaft).rem_euclid(TAU);
    let err = (st.spin_angle() - expect + PI).rem_euclid(TAU) - PI;
    println!(
        "spin after {steps} steps: {} vs {expect} (err {err:e})",
        st.spin_angle()
    );
    // f32: the spin angle accumulates one rounding of ~2π·ε₃₂ per step over 40 000 steps
    // (measured 2.3·10⁻³ rad); a wrong spin order would be off by radians.
    let limit = if common::SINGLE { 1e-2 } else { 1e-9 };
    assert!(err.abs() < limit, "{err}");
    // Race defects do not spin.
    let r = Model::new_checked(cwru()).unwrap();
    let mut s: State<16> = State::new(&r, 1).unwrap();
    for _ in 0..100 {
        r.step(&mut s);
    }
    assert_eq!(s.spin_angle(), 0.0);
}

/// Without slip, the defect enters a contact every half spin turn, `1/(2 BSF f_r)`, and
/// only while its own element is in the load zone; the other elements never carry it.
#[test]
fn impacts_every_half_spin_turn_on_the_defective_element_only() {
    let element = 4u8;
    let cfg = ModelConfig {
        slip: None,
        ..ball(element, 1.0)
    };
    let m = Model::new_checked(cfg).unwrap();
    let o = m.orders();
    let fr = m.config().speed.shaft_hz(0.0);
    let n = m.config().bearing.elements as Real;
    let h = m.step_size();
    let mut st: State<16> = State::new(&m, 2).unwrap();
    let mut entries = vec![];
    let mut was = false;
    for _ in 0..(0.5 / h) as usize {
        let (t, cage) = (st.time(), st.cage_angle());
        m.step(&mut st);
        let on = st.stats().defect_load > 0.0;
        if on && !was {
            entries.push(t);
            // The defective element's angle θ = θ_cage + 2πj/N is in the load zone.
            let s = (cage + TAU * element as Real / n).sin();
            assert!(s > 0.0, "entry at t = {t} with the element at sin θ = {s}");
        }
        was = on;
    }
    let half_turn = 1.0 / (2.0 * o.bsf * fr);
    let gaps: Vec<Real> = entries.windows(2).map(|w| w[1] - w[0]).collect();
    // Within a load-zone pass every gap is one half spin turn (to one step); between
    // passes the gap is a whole number of half turns.
    let mut within = 0;
    for g in &gaps {
        let k = (g / half_turn).round();
        assert!(k >= 1.0, "gap {g}");
        assert!(
            (g - k * half_turn).abs() < 2.0 * h * k,
            "gap {g} vs {k} × {half_turn}"
        );
        if k == 1.0 {
            within += 1;
        }
    }
    // 0.5 s is 6 cage turns; the loaded half of each holds ~0.5/FTF·2BSF/2 ≈ 6 impacts.
    println!(
        "{} entries, {within} one half-turn apart, half turn {half_turn:.6} s",
        entries.len()
    );
    assert!(entries.len() > 25 && within > 20, "{entries:?}");
}

/// The envelope spectrum of a ball defect: a line at 2×BSF with FTF sidebands well above
/// the floor; nothing at BPFO or BPFI (where race defects would put their lines).
#[test]
fn envelope_shows_twice_bsf_with_ftf_sidebands_not_bpfo_or_bpfi() {
    let (m, x) = accel(ball(0, 0.0), 11);
    let fs = m.config().output_rate;
    let fr = m.config().speed.shaft_hz(0.0);
    let o = m.orders();
    let spec = envelope_spectrum(&x, fs, band(&m));
    let fl = floor(&spec, &o, fr);
    let bsf2 = line(&spec, 2.0 * o.bsf * fr) / fl;
    let lower = line(&spec, (2.0 * o.bsf - o.ftf) * fr) / fl;
    let upper = line(&spec, (2.0 * o.bsf + o.ftf) * fr) / fl;
    let ftf = line(&spec, o.ftf * fr) / fl;
    let bpfo = line(&spec, o.bpfo * fr) / fl;
    let bpfi = line(&spec, o.bpfi * fr) / fl;
    let bsf1 = line(&spec, o.bsf * fr) / fl;
    println!(
        "over floor: 2BSF {bsf2:.1}, -FTF {lower:.1}, +FTF {upper:.1}, FTF {ftf:.1}, \
         BPFO {bpfo:.1}, BPFI {bpfi:.1}, 1BSF {bsf1:.1}"
    );
    // Measured (seed 11): 2BSF ≈ 380, sidebands ≈ 350–380, FTF ≈ 415, BPFO ≈ 4.5,
    // BPFI ≈ 8 (the slip-smeared skirt between the FTF sidebands), 1×BSF ≈ 4.
    assert!(bsf2 > 100.0, "2xBSF {bsf2}");
    assert!(lower > 50.0 && upper > 50.0, "sidebands {lower} {upper}");
    assert!(ftf > 50.0, "FTF {ftf}");
    // Both contacts see the same defect: the spin line itself stays small.
    assert!(bsf1 < 0.05 * bsf2, "1xBSF {bsf1}");
    assert!(bpfo < 15.0 && bpfi < 15.0, "BPFO {bpfo} BPFI {bpfi}");
    assert!(bpfo.max(bpfi) < 0.04 * bsf2, "BPFO {bpfo} BPFI {bpfi}");

    // The same defect on the outer race puts its line at BPFO instead.
    let (m, x) = accel(cwru(), 11);
    let spec = envelope_spectrum(&x, fs, band(&m));
    let fl = floor(&spec, &o, fr);
    let (race_bpfo, race_bsf2) = (
        line(&spec, o.bpfo * fr) / fl,
        line(&spec, 2.0 * o.bsf * fr) / fl,
    );
    println!("outer race over floor: BPFO {race_bpfo:.1}, 2BSF {race_bsf2:.1}");
    assert!(
        race_bpfo > 100.0 && race_bsf2 < 15.0,
        "{race_bpfo} {race_bsf2}"
    );
}

/// The `load-zone` effect gates a ball defect's impacts by its element's angle from the
/// load-zone centre as the element orbits with the cage: a deeper, narrower modulation at
/// FTF than the Hertz load alone gives. Seen in the envelope spectrum as higher-order FTF
/// sidebands of 2×BSF relative to the carrier, and in the time domain as the vibration
/// energy synchronously averaged over the defective element's orbit angle ψ (from the
/// load-zone centre) leaving the flanks. Were the effect blind to ball defects, both
/// records would be identical (ratios exactly 1).
#[test]
fn load_zone_effect_deepens_the_ftf_modulation_of_a_ball_defect() {
    let element = 2u8;
    let base = ModelConfig {
        slip: None,
        ..ball(element, 0.0)
    };
    let (m, x0) = accel(base.clone(), 5);
    // Full Stribeck gain with ε = 0.25: zero beyond |ψ| = 60°, 0.27 at 45°.
    let (_, x1) = accel(with_effect(base, "load-zone", &[1.0, 0.25, 0.0]), 5);
    let fs = m.config().output_rate;
    let fr = m.config().speed.shaft_hz(0.0);
    let o = m.orders();
    let n = m.config().bearing.elements as Real;
    let settle = (0.1 * fs) as u64;
    let measures = |x: &[Real]| {
        let s = envelope_spectrum(x, fs, band(&m));
        let c = line(&s, 2.0 * o.bsf * fr);
        let sb = |k: Real| {
            (line(&s, (2.0 * o.bsf - k * o.ftf) * fr) + line(&s, (2.0 * o.bsf + k * o.ftf) * fr))
                / c
        };
        // Squared acceleration averaged over ψ = θ_cage + 2πj/N − π/2 in 10° bins.
        let mut e = [(0.0 as Real); 36];
        let mut cnt = [0usize; 36];
        for (i, v) in x.iter().enumerate() {
            let t = m.output_time(settle + i as u64);
            let psi = TAU * o.ftf * fr * t + TAU * element as Real / n - PI / 2.0;
            let b = (psi.rem_euclid(TAU) / TAU * 36.0) as usize % 36;
            e[b] += v * v;
            cnt[b] += 1;
        }
        let e: Vec<Real> = e
            .iter()
            .zip(cnt)
            .map(|(a, k)| a / k.max(1) as Real)
            .collect();
        // Flanks 40°–60° on both sides over the centre |ψ| < 10°.
        let flank = (e[4] + e[5] + e[30] + e[31]) / (e[0] + e[35]);
        (sb(1.0), sb(2.0) + sb(3.0), flank)
    };
    let (sb1_0, sb23_0, flank0) = measures(&x0);
    let (sb1_1, sb23_1, flank1) = measures(&x1);
    println!(
        "sidebands ±1 FTF / 2BSF {sb1_0:.3} -> {sb1_1:.3}; ±2,3 FTF {sb23_0:.3} -> {sb23_1:.3}; \
         flank/centre energy {flank0:.3} -> {flank1:.3}"
    );
    // Measured: ±1 1.92 -> 2.17, ±2,3 1.16 -> 2.75, flank 0.52 -> 0.03.
    assert!(sb1_1 > 1.05 * sb1_0, "±FTF sidebands {sb1_0} -> {sb1_1}");
    assert!(
        sb23_1 > 1.8 * sb23_0,
        "±2,3 FTF sidebands {sb23_0} -> {sb23_1}"
    );
    assert!(flank1 < 0.25 * flank0, "flank energy {flank0} -> {flank1}");
}

/// An out-of-range element is rejected naming `defect.element` and the allowed range
/// 0 ..= N − 1; so is a defect longer than half the ball's circumference.
#[test]
fn ball_defect_validation() {
    let n = cwru().bearing.elements;
    assert!(Model::new_checked(ball(n - 1, 0.0)).is_ok());
    match Model::new_checked(ball(n, 0.0)) {
        Err(ConfigError::OutOfRange {
            field,
            value,
            min,
            max,
        }) => {
            assert_eq!(field, "defect.element");
            assert_eq!((value, min, max), (n as f64, 0.0, (n - 1) as f64));
        }
        other => panic!("{other:?}"),
    }
    let err = Model::new_checked(ball(200, 0.0)).unwrap_err();
    assert_eq!(err.field(), "defect.element");
    assert!(err.to_string().contains("0 ..= 8"), "{err}");

    let mut long = ball(0, 0.0);
    let d = long.defect.as_mut().unwrap();
    d.topography.length = 0.6 * PI * 0.5 * long.bearing.element_diameter;
    assert!(Model::new_checked(long.clone()).is_ok());
    long.defect.as_mut().unwrap().topography.count = 2;
    assert_eq!(
        Model::new_checked(long).unwrap_err().field(),
        "defect.length"
    );
    let mut bad_phase = ball(0, 0.0);
    bad_phase.defect.as_mut().unwrap().location = DefectLocation::Ball {
        element: 0,
        phase: Real::NAN,
    };
    assert_eq!(
        Model::new_checked(bad_phase).unwrap_err().field(),
        "defect.angle"
    );
}

/// Every formulation works on a ball: against the healthy bearing, the defect raises the
/// envelope line at 2×BSF and not those at BPFO or BPFI (the healthy bearing's BPFO line is
/// the varying compliance of the ball passage); a checkpoint mid-run continues
/// bit-identically (the spin angle is saved).
#[test]
fn every_formulation_and_checkpoints() {
    let lines = |cfg: ModelConfig| {
        let (m, x) = accel(cfg, 9);
        let fr = m.config().speed.shaft_hz(0.0);
        let o = m.orders();
        let spec = envelope_spectrum(&x, m.config().output_rate, band(&m));
        [o.bsf * 2.0, o.bpfo, o.bpfi].map(|k| line(&spec, k * fr))
    };
    let healthy = lines(ModelConfig {
        defect: None,
        ..cwru()
    });
    for model in [
        DefectModel::FiveStep,
        DefectModel::Deflection,
        DefectModel::Sassi,
        DefectModel::Impulse,
    ] {
        let mut cfg = ball(1, 0.5);
        cfg.defect.as_mut().unwrap().model = model;
        let l = lines(cfg.clone());
        let gain = [0, 1, 2].map(|i| l[i] / healthy[i]);
        println!(
            "{model:?}: line gain over healthy 2BSF {:.1}, BPFO {:.2}, BPFI {:.2}",
            gain[0], gain[1], gain[2]
        );
        // Measured: five-step 360, deflection 18, Sassi 830, impulse 3.8 at 2BSF; BPFO
        // 0.4–0.85, BPFI 0.8–16 (Sassi: the skirt of its strong 2BSF + 2FTF sideband).
        assert!(gain[0] > 3.0, "{model:?}: {gain:?}");
        assert!(gain[0] > 3.0 * gain[1].max(gain[2]), "{model:?}: {gain:?}");

        let m = Model::new_checked(cfg).unwrap();
        let mut a: State<16> = State::new(&m, 9).unwrap();
        let mut first = vec![Sample::default(); 2001];
        m.fill(&mut a, &mut first);
        let mut bytes = vec![0u8; encoded_len(16)];
        let len = a.encode(&mut bytes).unwrap();
        let mut b: State<16> = State::decode(&m, &bytes[..len]).unwrap();
        assert_eq!(a.spin_angle(), b.spin_angle());
        let mut ra = vec![Sample::default(); 3000];
        let mut rb = ra.clone();
        m.fill(&mut a, &mut ra);
        m.fill(&mut b, &mut rb);
        assert!(
            ra.iter()
                .zip(&rb)
                .all(|(x, y)| x.accel.to_bits() == y.accel.to_bits()),
            "{model:?}"
        );
    }
}

/// The wear life carries a ball defect (its topographies are fitted to the ball,
/// `Life::completed_length`): `check_base` accepts a ball defect as it accepts race defects
/// and healthy bases (before issue 14's ball lives it refused it with `defect.location`),
/// and still refuses a ball the bearing does not have, naming `defect.element` and its range.
#[test]
fn wear_life_carries_a_ball_defect() {
    use wearsim_core::wear::Life;
    assert_eq!(Life::check_base(&ball(0, 0.0)), Ok(()));
    assert_eq!(Life::check_base(&ball(8, 1.0)), Ok(()));
    match Life::check_base(&ball(9, 0.0)) {
        Err(ConfigError::OutOfRange {
            field, min, max, ..
        }) => {
            assert_eq!(field, "defect.element");
            assert_eq!((min, max), (0.0, 8.0));
        }
        other => panic!("{other:?}"),
    }
    assert!(Life::check_base(&cwru()).is_ok());
    assert!(Life::check_base(&ModelConfig {
        defect: None,
        ..cwru()
    })
    .is_ok());
}
