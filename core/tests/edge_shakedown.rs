//! Shakedown of a spall's fresh breakout edge (issue 14): the edge's excess over its
//! work-hardened residual (4/30 of its height, Table 1's smoothed large defect over the
//! large defect) falls as `exp(−3 n / N_sd)` over `n` over-rolling passes, N_sd =
//! `material.edge_shakedown_passes` (10⁴, after Jakobsen & Sivebaek 2017: asperity
//! deformation nearly stops after about 10⁴ contact events). A dent's shoulder keeps the
//! slower over-rolling law of eq. 24. Scenario: the `ims-za2115` preset (Rexnord ZA-2115,
//! 6000 lbf), outer race, no slip (so no abrasion: the decay is the plastic part alone).
// Written against `Real` (f64 or f32 by package): casts that are no-ops in one precision are
// needed in the other.
#![allow(clippy::unnecessary_cast)]

mod common;

use wearsim_core::topography::{self, Topography};
use wearsim_core::wear::life::SPALL_EDGE_RESIDUAL;
use wearsim_core::wear::{Life, LifeState, PassLoads, Stage};
use wearsim_core::Real;

fn setup() -> (Life, PassLoads) {
    common::za2115_outer_life()
}

/// A state in `stage` whose defect has an edge of height `h` over a floor `floor`.
fn with_edge(life: &Life, stage: Stage, h: Real, floor: Real) -> LifeState {
    let mut st = life.initial_state(1);
    st.stage = stage;
    st.topography = Some(Topography {
        asperity_height: h,
        ..topography::LARGE_DEFECT
    });
    st.asperity_floor = floor;
    st.crack = 5e-6;
    st.crack_start = 5e-6;
    st
}

/// Advances by `revs` revolutions, failing on any transition (none is due in so short a
/// span).
fn run(life: &Life, st: &mut LifeState, revs: Real, loads: &PassLoads) {
    let mut done = 0.0;
    while done < revs {
        let adv = life.advance(st, revs - done, loads);
        assert!(adv.transition.is_none(), "unexpected {:?}", adv.transition);
        done += adv.revs;
    }
}

/// The breakout edge of a large defect (30 µm) after N_sd/3, N_sd and 2 N_sd passes: its
/// excess equals the closed form `e₀ exp(−3 n/N_sd)` within 1 % (the decay is integrated
/// exactly within each step), and after N_sd passes 95 % of it is gone.
#[test]
fn a_breakout_edge_shakes_down_within_its_passes() {
    let (life, loads) = setup();
    let m = life.config().material;
    let h0 = topography::LARGE_DEFECT.asperity_height;
    let floor = h0 * SPALL_EDGE_RESIDUAL;
    assert!(
        (floor - 4e-6).abs() < 1e-9,
        "Table 1: 4 µm of 30 µm, got {floor}"
    );
    let n_p = life.passes_per_rev();
    for passes in [
        m.edge_shakedown_passes / 3.0,
        m.edge_shakedown_passes,
        2.0 * m.edge_shakedown_passes,
    ] {
        let mut st = with_edge(&life, Stage::DefectSmoothing, h0, floor);
        run(&life, &mut st, passes / n_p, &loads);
        let got = st.topography.unwrap().asperity_height - floor;
        let want = (h0 - floor) * (-3.0 * passes / m.edge_shakedown_passes).exp();
        assert!(
            (got / want - 1.0).abs() < 0.01,
            "after {passes} passes: excess {got:e} m, closed form {want:e} m"
        );
    }
}

/// The same 30 µm shoulder as a dent (stage `Dent`, floor 0) flattens far more slowly: the
/// over-rolling law of eq. 24, calibrated on the thesis's "a dent shoulder halves in about
/// 5 % of life", keeps more than 90 % of it after the N_sd passes in which a breakout edge
/// loses 95 %. Without the stage distinction both would follow one law.
#[test]
fn a_dent_shoulder_keeps_the_slower_overrolling_law() {
    let (life, loads) = setup();
    let m = life.config().material;
    let h0 = topography::LARGE_DEFECT.asperity_height;
    let mut dent = with_edge(&life, Stage::Dent, h0, 0.0);
    dent.dent_asperity = h0;
    run(
        &life,
        &mut dent,
        m.edge_shakedown_passes / life.passes_per_rev(),
        &loads,
    );
    let kept = dent.topography.unwrap().asperity_height / h0;
    assert!(kept > 0.9, "dent shoulder kept {kept}");
}

/// The block over which a window's pass loads hold (`Life::representative_revs`): a
/// sixth of the shakedown passes while a breakout edge is fresh, unbounded once it has
/// shaken down (after N_sd passes its excess is under a quarter of its height) and for a
/// dent shoulder, which the slower law of eq. 24 flattens.
#[test]
fn a_fresh_edge_bounds_the_block_until_it_has_shaken_down() {
    let (life, loads) = setup();
    let m = life.config().material;
    let n_p = life.passes_per_rev();
    let h0 = topography::LARGE_DEFECT.asperity_height;
    let floor = h0 * SPALL_EDGE_RESIDUAL;
    let mut st = with_edge(&life, Stage::DefectSmoothing, h0, floor);
    let fresh = life.representative_revs(&st);
    let want = m.edge_shakedown_passes / (6.0 * n_p);
    assert!(
        (fresh / want - 1.0).abs() < 1e-6,
        "fresh edge: {fresh} revolutions, want N_sd/(6 n_p) = {want}"
    );
    run(&life, &mut st, 0.5 * m.edge_shakedown_passes / n_p, &loads);
    assert_eq!(
        life.representative_revs(&st),
        fresh,
        "half-way through its shakedown the edge is still fresh"
    );
    run(&life, &mut st, 0.6 * m.edge_shakedown_passes / n_p, &loads);
    assert!(
        life.representative_revs(&st).is_infinite(),
        "after 1.1 N_sd passes the edge has shaken down"
    );
    let dent = with_edge(&life, Stage::Dent, h0, 0.0);
    assert!(life.representative_revs(&dent).is_infinite());
}
