//! Each force diagram and physical building block on its own, against published
//! constants and closed forms.
// Written against `Real` (f64 or f32 by package): casts that are no-ops in one precision are
// needed in the other.
#![allow(clippy::unnecessary_cast)]

mod common;

use common::tol;
use wearsim_core::bearing::ContactKind;
use wearsim_core::contact::ElementContact;
use wearsim_core::forces::defect::{DefectLocation, DefectShape, StaticReference};
use wearsim_core::forces::imbalance::Imbalance;
use wearsim_core::forces::load_function::LoadFunction;
use wearsim_core::forces::surface::{Roughness, Waviness};
use wearsim_core::forces::{ForceDiagram, Kinematics};
use wearsim_core::kinematics::FaultOrders;
use wearsim_core::ring_modes::{flexural_mode_rad_s, nsk_outer_ring_hz, ring_frequency_hz};
use wearsim_core::rng::Xoshiro128pp;
use wearsim_core::sensor::SensorScale;
use wearsim_core::topography;
use wearsim_core::{presets, Real};

/// CWRU drive-end bearing (SKF 6205): the published multiples of shaft speed
/// BPFO 3.5848, BPFI 5.4152, BSF 2.3573, FTF 0.39828 (CWRU bearing-information page).
#[test]
fn cwru_fault_orders_match_published() {
    let o = FaultOrders::of(&presets::SKF_6205);
    for (got, want) in [
        (o.bpfo, 3.5848),
        (o.bpfi, 5.4152),
        (o.bsf, 2.3573),
        (o.ftf, 0.39828),
    ] {
        assert!((got - want).abs() < 1e-3, "{got} vs {want}");
    }
    // Fan end (8 balls): BPFO 3.0530, BPFI 4.9469, FTF 0.3817.
    let f = FaultOrders::of(&presets::SKF_6203);
    for (got, want) in [(f.bpfo, 3.0530), (f.bpfi, 4.9469), (f.ftf, 0.3817)] {
        assert!((got - want).abs() < 1e-3, "{got} vs {want}");
    }
    // IMS ZA-2115 (README of the data set): BPFO 7.0921, BPFI 8.9079, FTF 0.4433, BSF 4.1975.
    let i = FaultOrders::of(&presets::REXNORD_ZA2115);
    for (got, want) in [
        (i.bpfo, 7.0921),
        (i.bpfi, 8.9079),
        (i.ftf, 0.4433),
        (i.bsf, 4.1975),
    ] {
        assert!((got - want).abs() < 1e-3, "{got} vs {want}");
    }
    // Identities of eq. 18–19.
    assert!(
        (o.bpfo - 9.0 * o.ftf).abs() < tol(1e-12)
            && (o.bpfi - 9.0 * (1.0 - o.ftf)).abs() < tol(1e-12)
    );
}

/// The thesis reference puts BPFO inside the reported ~170 Hz fault zone at 160 rad/s.
#[test]
fn thesis_bearing_fault_zone() {
    let f = FaultOrders::of(&presets::SKF_61810).at(presets::THESIS_SHAFT_HZ, 0.0);
    assert!((f.shaft_hz - 25.46).abs() < 0.01);
    assert!(f.bpfo > 150.0 && f.bpfo < 190.0, "BPFO {}", f.bpfo);
}

/// Fitted log–log slope of the implemented load–deflection law: 3/2 for point contact,
/// 10/9 for line contact (to 1e-9).
#[test]
fn hertz_exponents_fitted_from_implementation() {
    for (bearing, p) in [
        (presets::SKF_6205, 1.5),
        (presets::REXNORD_ZA2115, 10.0 / 9.0),
    ] {
        let c = ElementContact::of(&bearing);
        assert_eq!(c.kind == ContactKind::Point, p == 1.5);
        let pts: Vec<(Real, Real)> = (0..20)
            .map(|i| {
                let d = 1e-7 * (10.0 as Real).powf(i as Real * 0.12);
                (d.ln(), c.load(d).ln())
            })
            .collect();
        let n = pts.len() as Real;
        let mx = pts.iter().map(|p| p.0).sum::<Real>() / n;
        let my = pts.iter().map(|p| p.1).sum::<Real>() / n;
        let slope = pts.iter().map(|(x, y)| (x - mx) * (y - my)).sum::<Real>()
            / pts.iter().map(|(x, _)| (x - mx) * (x - mx)).sum::<Real>();
        assert!((slope - p).abs() < tol(1e-9), "slope {slope} vs {p}");
        assert_eq!(c.load(-1e-6), 0.0);
    }
}

/// Hertz constants of handbook size: a 6205-size ball contact (both races in series) has a
/// load–deflection constant of order 10¹⁰ N/m^1.5, and 800 N on one ball of the 6205
/// inner race gives a maximum pressure of 2–4.5 GPa (the range of Harris & Kotzalas's
/// worked examples for heavily loaded ball bearings); `p_max ∝ Q^{1/3}` exactly.
#[test]
fn hertz_constants_are_of_handbook_size() {
    let c = ElementContact::of(&presets::SKF_6205);
    assert!(
        c.stiffness > 5e9 && c.stiffness < 2e10,
        "K = {}",
        c.stiffness
    );
    let p = c.inner.max_pressure(800.0);
    assert!(p > 2.0e9 && p < 4.5e9, "p_max(800 N) = {p}");
    // p_max grows with Q^{1/3}.
    let r = c.inner.max_pressure(8000.0) / p;
    assert!((r - (10.0 as Real).powf(1.0 / 3.0)).abs() < tol(1e-9));
}

/// Eq. 21 and the corrected eq. 22 give the same mode ratios n(n²−1)/√(n²+1); the printed
/// √(n²−1) form would give 8/√8·… and fail. Eq. 23 in Hz.
#[test]
fn ring_mode_formulas_agree() {
    for n in 2..6u32 {
        let r21 = flexural_mode_rad_s(n + 1, 2e11, 1e-10, 0.1, 0.03)
            / flexural_mode_rad_s(n, 2e11, 1e-10, 0.1, 0.03);
        let r22 =
            nsk_outer_ring_hz(n + 1, 50.0, 65.0, 0.15) / nsk_outer_ring_hz(n, 50.0, 65.0, 0.15);
        assert!((r21 - r22).abs() < tol(1e-12));
    }
    let f2 = nsk_outer_ring_hz(2, 50.0, 65.0, 0.15);
    assert!(f2 > 1000.0 && f2 < 2000.0, "61810 outer ring n=2: {f2} Hz");
    assert!(
        (ring_frequency_hz(5900.0, 0.065) - 5900.0 / (wearsim_core::real::PI * 0.065)).abs()
            < tol(1e-9)
    );
    assert_eq!(flexural_mode_rad_s(1, 2e11, 1e-10, 0.1, 0.03), 0.0);
}

fn kin(shaft_angle: Real, omega: Real) -> Kinematics {
    Kinematics {
        shaft_angle,
        shaft_cs: (shaft_angle.cos(), shaft_angle.sin()),
        shaft_omega: omega,
        shaft_alpha: 0.0,
        cage_angle: 0.0,
        cage_cs: (1.0, 0.0),
        cage_omega: 0.0,
        wave_cs: (1.0, 0.0),
    }
}

/// Thesis eq. 3: 0.005 kg at 0.1 m and 160 rad/s gives 12.8 N, along sin θ.
#[test]
fn imbalance_force_magnitude() {
    let imb = Imbalance {
        mass: 0.005,
        radius: 0.1,
    };
    let f = imb.force(&kin(wearsim_core::real::PI / 2.0, 160.0), 0.0, 0.0);
    assert!((f - 12.8).abs() < tol(1e-9));
    assert!(imb.force(&kin(0.0, 160.0), 0.0, 0.0).abs() < tol(1e-12));
}

/// Waviness order from the track radius (not the thesis's 10 mm example's "80"), and the
/// roughness step variance keeping the PSD level independent of the step.
#[test]
fn surface_parameters() {
    let w = Waviness {
        amplitude: 1e-7,
        wavelength: 0.8e-3,
    };
    let r_o = presets::SKF_61810.outer_race_radius();
    let n = w.order(r_o);
    assert_eq!(n, (wearsim_core::real::TAU * r_o / 0.8e-3).round() as u32);
    assert!(n > 200, "61810 track holds {n} waves, not 80");
    let r = Roughness {
        rms: 1e-7,
        wavelength: 2e-5,
        debris_gain: 4.0,
    };
    // White regime: σ_step² · h constant.
    let (h1, h2) = (2.5e-5, 1.25e-5);
    let v = 0.1; // τ = 2e-4 > h: correlated regime → σ itself
    assert!((r.step_sigma(h1, v, 0.0) - 1e-7).abs() < tol(1e-20));
    let v = 10.0; // τ = 2e-6 < h
    let p1 = r.step_sigma(h1, v, 0.0).powi(2) * h1;
    let p2 = r.step_sigma(h2, v, 0.0).powi(2) * h2;
    assert!((p1 / p2 - 1.0).abs() < tol(1e-12));
    assert!((r.step_sigma(h1, v, 1.0) / r.step_sigma(h1, v, 0.0) - 5.0).abs() < tol(1e-12));
}

/// The five-step load function: nominal, linear unloading, flat traverse, half-sine
/// asperity overload at the trailing edge, linear recovery, nominal.
#[test]
fn five_step_load_function_shape() {
    let lf = LoadFunction {
        unload: 0.6,
        entry: 0.2,
        asperity: 10e-6,
        impact: 0.1,
    };
    assert_eq!(lf.eval(-0.01).unload, 0.0);
    assert!((lf.eval(0.1).unload - 0.3).abs() < tol(1e-12)); // half-way down the entry ramp
    assert!((lf.eval(0.5).unload - 0.6).abs() < tol(1e-12)); // traverse
    assert_eq!(lf.eval(0.5).extra_deflection, 0.0);
    let peak = lf.eval(1.05);
    assert!((peak.extra_deflection - 10e-6).abs() < tol(1e-15)); // crest of the half-sine
    assert!((peak.unload - 0.6 * 0.75).abs() < tol(1e-12)); // recovering
    assert_eq!(lf.eval(1.25).unload, 0.0);
    assert_eq!(lf.eval(1.25).extra_deflection, 0.0);
    assert!((lf.tail() - 0.2).abs() < tol(1e-15));
}

/// Defect shapes derived from Table 1 grow as the thesis orders them: the geometric drop
/// grows with length, the unloading with drop and width; smoothing lowers the asperity.
#[test]
fn defect_shapes_follow_table_1() {
    let sref = StaticReference {
        q_max: 54.0,
        delta_max: 3.9e-6,
        a: 3.8e-4,
        b: 5e-5,
    };
    let loc = DefectLocation::OuterRace { angle: 1.57 };
    let shape = |t| DefectShape::derive(&t, &loc, &presets::SKF_61810, &sref, 1.0);
    let dent = shape(topography::REAL_DENT);
    let smooth = shape(topography::SMOOTHED_DENT);
    let medium = shape(topography::MEDIUM_DEFECT);
    let large = shape(topography::LARGE_DEFECT);
    let smoothed_large = shape(topography::SMOOTHED_LARGE_DEFECT);
    assert!(dent.load.asperity > 0.0 && smooth.load.asperity == 0.0);
    assert!(dent.load.unload < medium.load.unload && medium.load.unload <= large.load.unload);
    assert!(smoothed_large.load.asperity < large.load.asperity / 5.0);
    // Geometric drop of a 50 µm dent under a 3.97 mm ball: L²/(8 r_b) ≈ 0.16 µm.
    let expect = (50e-6 as Real).powi(2) / (8.0 * 3.969e-3 / 2.0);
    assert!(
        (dent.drop / expect - 1.0).abs() < 1e-3,
        "{} vs {expect}",
        dent.drop
    );
    assert_eq!(dent.geometric_drop(-0.1), 0.0);
    assert!(large.geometric_drop(0.5) > large.geometric_drop(0.05));
    assert_eq!(topography::TWO_LARGE_DEFECTS.count, 2);
}

/// The generator: reproducible, uniform on [−1, 1) (mean 0, variance 1/3), and its
/// approximate Gaussian has unit variance.
#[test]
fn rng_statistics() {
    let mut a = Xoshiro128pp::from_u64(7);
    let mut b = Xoshiro128pp::from_u64(7);
    let n = 200_000;
    let (mut s, mut s2, mut g2) = (0.0, 0.0, 0.0);
    for _ in 0..n {
        let x = a.uniform_pm1();
        assert_eq!(x.to_bits(), b.uniform_pm1().to_bits());
        assert!((-1.0..1.0).contains(&x));
        s += x;
        s2 += x * x;
        let g = a.gauss_approx();
        let _ = b.gauss_approx();
        g2 += g * g;
    }
    assert!((s / n as Real).abs() < 0.005);
    assert!((s2 / n as Real - 1.0 / 3.0).abs() < 0.005);
    assert!((g2 / n as Real - 1.0).abs() < 0.01);
}

/// Sensor counts: Q1.15 of the full scale, saturating, with left-justified resolution.
#[test]
fn sensor_counts() {
    let s = SensorScale {
        full_scale_g: 2.0,
        bits: 16,
    };
    assert_eq!(s.counts(9.80665), 16384);
    assert_eq!(s.counts(-9.80665), -16384);
    assert_eq!(s.counts(1e6), i16::MAX);
    assert_eq!(s.counts(-1e6), i16::MIN);
    assert_eq!(s.counts(Real::NAN), 0);
    assert_eq!(s.counts(Real::INFINITY), i16::MAX);
    assert_eq!(s.counts(Real::NEG_INFINITY), i16::MIN);
    // The same counts as `fixed`'s saturating conversion (round to nearest, ties to even)
    // over the range and its edges, ties included: `counts` avoids that conversion only
    // because its NaN panic stays reachable to the optimiser (firmware-stub/nopanic).
    let full = 9.80665 * 2.0;
    for i in -70_000i32..=70_000 {
        for frac in [i as Real / 65_536.0, (i as Real + 0.5) / 32_768.0] {
            let accel = frac * full;
            let want = fixed::types::I1F15::saturating_from_num(accel / full).to_bits();
            assert_eq!(s.counts(accel), want, "fraction {frac}");
        }
    }
    assert!((s.accel(16384) - 9.80665).abs() < tol(1e-12));
    let s12 = SensorScale {
        full_scale_g: 2.0,
        bits: 12,
    };
    assert_eq!(s12.counts(9.80665 * 0.3) & 0xF, 0);
    assert!(SensorScale::new_checked(SensorScale {
        full_scale_g: 0.0,
        bits: 16
    })
    .is_err());
}
