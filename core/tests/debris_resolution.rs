//! Debris in the life's dynamic model (`Life::model_config`): debris acts only through the
//! roughness multiplier `1 + debris_gain·debris` (`Roughness::step_sigma`), so once the
//! flushing has taken it below what that multiplier resolves in the number type the model
//! is, bit for bit, the one without debris, and the life passes it as 0 (successive windows
//! then compare equal and the host renders them together). Scenario: the outer-race life of
//! the `cwru-6205-de` preset grown to damage growth (a spall with its debris).
// Written against `Real` (f64 or f32 by package): casts that are no-ops in one precision are
// needed in the other.
#![allow(clippy::unnecessary_cast)]

mod common;

use wearsim_core::wear::{Life, LifeConfig, LifeState, Site, Stage};
use wearsim_core::{Model, ModelConfig, Real};

/// The preset with its defect (the life's topography replaces it), the life, and a state
/// in damage growth.
fn damaged() -> (ModelConfig, Life, LifeState) {
    let (healthy, q) = common::healthy_static_load("cwru-6205-de");
    let base = wearsim_core::presets::by_name("cwru-6205-de").unwrap();
    let life =
        Life::new_checked(LifeConfig::DEFAULT, &healthy.bearing, q, Site::OuterRace).unwrap();
    let mut st = life.initial_state(3);
    let l = common::constant_pass_loads(q);
    let mut guard = 0;
    while st.stage < Stage::DamageGrowth && guard < 100_000 {
        guard += 1;
        life.advance(&mut st, 1e7, &l);
    }
    assert_eq!(st.stage, Stage::DamageGrowth, "{st:?}");
    (base, life, st)
}

fn debris_of(cfg: &ModelConfig) -> Real {
    cfg.defect
        .expect("a damaged state has a defect")
        .topography
        .debris
}

/// Accelerations of `cfg` (m/s²), 3 000 samples from seed 5.
fn accel(cfg: ModelConfig) -> Vec<Real> {
    let model = Model::new_checked(cfg).unwrap();
    common::run(&model, 5, 3_000)
        .iter()
        .map(|s| s.accel)
        .collect()
}

/// A debris level the multiplier cannot resolve is passed as 0 and gives the samples of
/// the raw level bit for bit; a resolvable one is passed unchanged and changes the samples
/// (so the comparison can fail).
#[test]
fn unresolvable_debris_is_passed_as_none_and_changes_no_sample() {
    let (base, life, mut st) = damaged();
    let gain = base
        .roughness
        .expect("the preset has roughness")
        .debris_gain;
    assert!(gain > 0.0);

    // Far below the resolution: 10⁻³⁰ (f64 resolves 1 + 4·d for d ≳ 3·10⁻¹⁷, f32 for
    // d ≳ 1.5·10⁻⁸).
    st.debris = 1e-30;
    let cfg = life.model_config(&base, &st);
    assert_eq!(
        debris_of(&cfg),
        0.0,
        "unresolvable debris reaches the model"
    );
    let mut raw = cfg.clone();
    if let Some(d) = raw.defect.as_mut() {
        d.topography.debris = 1e-30;
    }
    let (a, b) = (accel(cfg), accel(raw));
    assert!(a.iter().any(|x| *x != 0.0));
    assert!(
        a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()),
        "the model with 1e-30 debris differs from the one with none"
    );

    // Resolvable: kept, and it roughens the signal.
    st.debris = 0.25;
    let kept = life.model_config(&base, &st);
    assert_eq!(debris_of(&kept), 0.25);
    let mut none = kept.clone();
    if let Some(d) = none.defect.as_mut() {
        d.topography.debris = 0.0;
    }
    let (c, n) = (accel(kept), accel(none));
    assert!(
        c.iter().zip(&n).any(|(x, y)| x.to_bits() != y.to_bits()),
        "debris 0.25 changes no sample"
    );

    // At the edge: the largest level whose multiplier rounds to 1 is dropped, twice it
    // is kept.
    let edge = Real::EPSILON / (4.0 * gain);
    st.debris = edge;
    assert_eq!(debris_of(&life.model_config(&base, &st)), 0.0);
    st.debris = 4.0 * edge;
    assert_eq!(debris_of(&life.model_config(&base, &st)), 4.0 * edge);
}
