//! Spall-propagation scatter (issue 14): each bearing draws, besides its ISO 281 fatigue
//! scatter, an independent propagation factor from a Weibull distribution of slope 1.1 and
//! median 1 (Hoeprich 1992, via Kotzalas & Harris 2001: the propagation time from the
//! first spall to failure is Weibull with median slope 1.1). From the first spall on — the
//! trailing-edge breakouts of defect completion and the propagation limit that spawns new
//! defects — the growth laws take `propagation_scatter` times as many passes; the
//! subsurface crack before the first spall does not. Scenario: `ims-za2115` (Rexnord
//! ZA-2115), outer race, no slip, the edge at its work-hardened floor so that every rate is
//! constant and the times have closed forms.
// Written against `Real` (f64 or f32 by package): casts that are no-ops in one precision are
// needed in the other.
#![allow(clippy::unnecessary_cast)]

mod common;

use wearsim_core::topography::{self, Topography};
use wearsim_core::wear::life::{PROPAGATION_WEIBULL_SLOPE, SPALL_EDGE_RESIDUAL, WEIBULL_SLOPE};
use wearsim_core::wear::{Life, LifeState, PassLoads, Stage};
use wearsim_core::Real;

fn setup() -> (Life, PassLoads) {
    common::za2115_outer_life()
}

/// A state in `stage` with a large defect whose edge sits at its floor (no shakedown left,
/// so the edge stress is constant), a crack of `crack` m and propagation factor `spread`.
fn state(life: &Life, stage: Stage, crack: Real, spread: Real) -> LifeState {
    let floor = topography::LARGE_DEFECT.asperity_height * SPALL_EDGE_RESIDUAL;
    let mut st = life.initial_state(1);
    st.stage = stage;
    st.topography = Some(Topography {
        asperity_height: floor,
        ..topography::LARGE_DEFECT
    });
    st.asperity_floor = floor;
    st.crack = crack;
    st.crack_start = crack;
    st.initiation = 0.0;
    st.debris = 0.0;
    st.propagation_scatter = spread;
    st
}

/// Over 4000 seeds: the propagation factor has median 1 and slope 1.1, the fatigue factor
/// keeps its ISO slope 1.11, and the two are uncorrelated (|r| of their logarithms below
/// 0.05, about 3 standard errors). A factor drawn from the fatigue draw, a fixed factor or
/// a lognormal of the same median would fail one of these.
#[test]
fn propagation_factor_is_an_independent_weibull_of_slope_1_1() {
    let (life, _) = setup();
    let n = 4000;
    let mut fat = Vec::with_capacity(n);
    let mut prop = Vec::with_capacity(n);
    for seed in 1..=n as u64 {
        let st = life.initial_state(seed);
        fat.push(st.scatter);
        prop.push(st.propagation_scatter);
    }
    let r = common::log_correlation(&fat, &prop);
    assert!(
        r.abs() < 0.05,
        "fatigue and propagation factors correlate: r = {r}"
    );

    let (slope_p, median_p) = common::quantile_slope(&mut prop);
    let (slope_f, median_f) = common::quantile_slope(&mut fat);
    assert!(
        (median_p - 1.0).abs() < 0.06 && (median_f - 1.0).abs() < 0.06,
        "medians {median_p}, {median_f}"
    );
    assert!(
        (slope_p / PROPAGATION_WEIBULL_SLOPE - 1.0).abs() < 0.08,
        "propagation slope {slope_p}"
    );
    assert!(
        (slope_f / WEIBULL_SLOPE - 1.0).abs() < 0.08,
        "fatigue slope {slope_f}"
    );
}

/// The propagation limit in damage growth: with constant loads and edge the accumulator
/// rises linearly, so the revolutions to the next spawned defect are exactly
/// `N_p · s / (n_p (σ₀/p_ref)³)`; doubling the factor `s` doubles them.
#[test]
fn spawn_time_scales_with_the_propagation_factor() {
    let (life, loads) = setup();
    let cap = 1e12 as Real;
    let t1 = common::revs_to_transition(
        &life,
        &mut state(&life, Stage::DamageGrowth, 0.0, 1.0),
        &loads,
        cap,
    );
    let t2 = common::revs_to_transition(
        &life,
        &mut state(&life, Stage::DamageGrowth, 0.0, 2.0),
        &loads,
        cap,
    );
    let t_half = common::revs_to_transition(
        &life,
        &mut state(&life, Stage::DamageGrowth, 0.0, 0.5),
        &loads,
        cap,
    );
    assert!((t2 / t1 - 2.0).abs() < 1e-4, "factor 2: {t2} / {t1}");
    assert!(
        (t_half / t1 - 0.5).abs() < 1e-4,
        "factor 0.5: {t_half} / {t1}"
    );
    // The closed form at factor 1.
    let m = life.config().material;
    let c = life.contact();
    let (_, b) = c.semi_axes(loads.zone_mean);
    let h = topography::LARGE_DEFECT.asperity_height * SPALL_EDGE_RESIDUAL;
    let sigma0 = c.max_pressure(loads.edge_cubic) * (1.0 + m.asperity_beta * (h / b).sqrt());
    let r = sigma0 / life.reference_pressure();
    let want = m.propagation_passes / (life.passes_per_rev() * r * r * r);
    assert!(
        (t1 / want - 1.0).abs() < 1e-3,
        "spawn after {t1} rev, closed form {want}"
    );
}

/// A breakout during defect completion (the trailing-edge crack growing from a fresh flaw
/// to the spall depth) takes `s` times as long; the subsurface crack before the first
/// spall (crack propagation) does not depend on `s` at all.
#[test]
fn breakouts_scale_and_the_first_spall_does_not() {
    let (life, loads) = setup();
    let cap = 1e12 as Real;
    let flaw = 5e-6 as Real;
    let b1 = common::revs_to_transition(
        &life,
        &mut state(&life, Stage::DefectCompletion, flaw, 1.0),
        &loads,
        cap,
    );
    let b3 = common::revs_to_transition(
        &life,
        &mut state(&life, Stage::DefectCompletion, flaw, 3.0),
        &loads,
        cap,
    );
    assert!((b3 / b1 - 3.0).abs() < 3e-3, "breakout: {b3} / {b1}");
    let c1 = common::revs_to_transition(
        &life,
        &mut state(&life, Stage::CrackPropagation, 2.0 * flaw, 1.0),
        &loads,
        cap,
    );
    let c3 = common::revs_to_transition(
        &life,
        &mut state(&life, Stage::CrackPropagation, 2.0 * flaw, 3.0),
        &loads,
        cap,
    );
    assert_eq!(
        c1, c3,
        "the crack before the first spall must not carry the factor"
    );
}
