//! The wear laws' reference pressure under a scaled load (`Life::new_checked_at`): the
//! material's initiation and propagation limits hold at the calibration scenario's load,
//! so the same bearing under a heavier load initiates its crack sooner by the
//! Lundberg–Palmgren stress law, `N ∝ (σ₀/p_ref)⁻⁹` with a fixed `p_ref`. Before, the
//! reference pressure was taken at the run's own (scaled) load and moved with it, which
//! normalised the load away: the dent's crack initiation took the same number of passes
//! at every load, and the life–load exponent of `wearsim life --loads` came from the
//! fatigue and crack-growth phases alone (−1.53 on 200 lives, against −2.53 with this).
//! Scenario: the `cwru-6205-de` preset's 6205 (point contact, Hertz `p ∝ Q^{1/3}`).
// Written against `Real` (f64 or f32 by package): casts that are no-ops in one precision are
// needed in the other.
#![allow(clippy::unnecessary_cast)]

mod common;

use wearsim_core::topography::{self, Topography};
use wearsim_core::wear::{Life, LifeConfig, Site, Stage};
use wearsim_core::Real;

/// Load multiplier of the test.
const SCALE: Real = 1.6;

/// The 6205's bearing and its static most loaded element's load (N) at the preset's load.
fn bearing_and_load() -> (wearsim_core::bearing::BearingGeometry, Real) {
    let (base, q) = common::healthy_static_load("cwru-6205-de");
    (base.bearing, q)
}

/// Revolutions from a dent (its shoulder held at its smoothing floor, so the stress
/// concentration stays constant) to crack opening under constant pass loads at `q`.
fn revolutions_to_crack(life: &Life, q: Real) -> Real {
    let h = 4e-6;
    let mut st = life.initial_state(5);
    st.stage = Stage::Dent;
    st.topography = Some(Topography {
        asperity_height: h,
        ..topography::REAL_DENT
    });
    st.asperity_floor = h;
    st.dent_asperity = h;
    // The fatigue sum far from its end, so that the crack opens by initiation.
    st.scatter = 1e12;
    let loads = common::constant_pass_loads(q);
    let mut revs = 0.0;
    for _ in 0..10_000 {
        let adv = life.advance(&mut st, 1e12, &loads);
        revs += adv.revs;
        if adv.transition.is_some() {
            break;
        }
    }
    assert_eq!(st.stage, Stage::CrackOpening, "after {revs} revolutions");
    revs
}

/// The reference pressure is the outer contact's at the calibration load, whatever the
/// run's load (closed form: Hertz `p ∝ Q^{1/3}`); `new_checked` is `new_checked_at` with
/// the calibration load equal to the run's.
#[test]
fn reference_pressure_stays_at_the_calibration_load() {
    let (b, q) = bearing_and_load();
    let cfg = LifeConfig::DEFAULT;
    let at_q = Life::new_checked(cfg, &b, q, Site::OuterRace).unwrap();
    let scaled = Life::new_checked_at(cfg, &b, SCALE * q, q, Site::OuterRace).unwrap();
    let moved = Life::new_checked(cfg, &b, SCALE * q, Site::OuterRace).unwrap();
    assert_eq!(scaled.reference_pressure(), at_q.reference_pressure());
    let cube_root = (SCALE as f64).powf(1.0 / 3.0);
    let ratio = (moved.reference_pressure() / at_q.reference_pressure()) as f64;
    assert!(
        (ratio / cube_root - 1.0).abs() < 1e-5,
        "{ratio} vs {cube_root}"
    );
    // The contact the loads are read with is the run's either way.
    assert_eq!(
        scaled.contact().max_pressure(q),
        moved.contact().max_pressure(q)
    );
}

/// Under 1.6× the calibration load, the dent's crack opens 1.6³ = 4.1 times sooner with
/// the reference kept at the calibration load than with a reference that moved with the
/// load (pressure ratio to the ninth power: `(1.6^{1/3})⁹`), within 1 %: the steps land
/// on the initiation threshold, and the stress concentration `1 + β√(h/b)` is the same in
/// both lives (same loads, same contact).
#[test]
fn a_heavier_load_opens_the_crack_sooner_by_the_stress_life_law() {
    let (b, q) = bearing_and_load();
    let cfg = LifeConfig::DEFAULT;
    let scaled = Life::new_checked_at(cfg, &b, SCALE * q, q, Site::OuterRace).unwrap();
    let moved = Life::new_checked(cfg, &b, SCALE * q, Site::OuterRace).unwrap();
    let n_scaled = revolutions_to_crack(&scaled, SCALE * q);
    let n_moved = revolutions_to_crack(&moved, SCALE * q);
    let want = (SCALE as f64).powi(3);
    let got = (n_moved / n_scaled) as f64;
    assert!((got / want - 1.0).abs() < 0.01, "{got} vs {want}");
    // And at the calibration load itself nothing changes.
    let at_q = Life::new_checked_at(cfg, &b, q, q, Site::OuterRace).unwrap();
    let plain = Life::new_checked(cfg, &b, q, Site::OuterRace).unwrap();
    assert_eq!(
        revolutions_to_crack(&at_q, q),
        revolutions_to_crack(&plain, q)
    );
}

/// A calibration load outside 1 mN ..= 100 MN is a typed error naming the field.
#[test]
fn calibration_load_is_checked() {
    let (b, q) = bearing_and_load();
    for bad in [0.0, -1.0, Real::NAN, 1e9] {
        let e = Life::new_checked_at(LifeConfig::DEFAULT, &b, q, bad, Site::OuterRace).unwrap_err();
        assert!(format!("{e}").contains("calibration_load"), "{bad}: {e}");
    }
}
