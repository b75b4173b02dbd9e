//! Surface-initiation scatter (issue 14): the crack-initiation sum at a dent,
//! `Σ (σ₀/p_ref)⁹ / N_i` (Lundberg–Palmgren's pressure–life law), carries that theory's
//! scatter: each bearing draws a factor from a Weibull distribution of slope 10/9 and
//! median 1, independent of its subsurface fatigue factor and of its spall-propagation
//! factor, and the dent needs that factor times `N_i` passes. Without it the dent's crack
//! opened after a fixed number of passes in every long life, and in every short one when
//! the subsurface fatigue sum reached 1 — exactly twice the dent's time, a clock.
//! Scenario: `ims-za2115`, outer race, no slip, a real dent whose shoulder sits at its
//! smoothing floor (nothing left to flatten), so the rate is constant and the time has a
//! closed form.
// Written against `Real` (f64 or f32 by package): casts that are no-ops in one precision are
// needed in the other.
#![allow(clippy::unnecessary_cast)]

mod common;

use wearsim_core::topography;
use wearsim_core::wear::life::{INITIATION_WEIBULL_SLOPE, WEIBULL_SLOPE};
use wearsim_core::wear::{Life, LifeState, Stage};
use wearsim_core::Real;

/// A bearing in dent smoothing on Table 1's real dent with its shoulder at the smoothing
/// floor, no fatigue yet, with surface-initiation factor `spread`. Its fatigue factor is made huge so that the subsurface sum cannot win
/// the competition within the test.
fn dent_at_floor(life: &Life, spread: Real) -> LifeState {
    let mut st = life.initial_state(1);
    st.stage = Stage::DentSmoothing;
    st.topography = Some(topography::REAL_DENT);
    st.dent_asperity = topography::REAL_DENT.asperity_height;
    st.asperity_floor = topography::REAL_DENT.asperity_height;
    st.scatter = 1e9;
    st.initiation_scatter = spread;
    st
}

/// Over 4000 seeds: the surface-initiation factor has median 1 and slope 10/9, and its
/// logarithm is uncorrelated with those of the fatigue and propagation factors (|r| below
/// 0.05, about 3 standard errors). Reusing either draw, a fixed factor or a lognormal of
/// the same median would fail.
#[test]
fn initiation_factor_is_an_independent_weibull_of_slope_10_9() {
    let (life, _) = common::za2115_outer_life();
    let n = 4000;
    let states: Vec<LifeState> = (1..=n as u64).map(|s| life.initial_state(s)).collect();
    let factor = |f: fn(&LifeState) -> Real| -> Vec<Real> { states.iter().map(f).collect() };
    let ini = factor(|s| s.initiation_scatter);
    for (name, other) in [
        ("fatigue", factor(|s| s.scatter)),
        ("propagation", factor(|s| s.propagation_scatter)),
    ] {
        let r = common::log_correlation(&ini, &other);
        assert!(
            r.abs() < 0.05,
            "initiation and {name} factors correlate: r = {r}"
        );
    }
    let mut v = ini;
    let (slope, median) = common::quantile_slope(&mut v);
    assert!((median - 1.0).abs() < 0.06, "median {median}");
    assert!(
        (slope / INITIATION_WEIBULL_SLOPE - 1.0).abs() < 0.08,
        "initiation slope {slope}"
    );
    assert!(
        (INITIATION_WEIBULL_SLOPE - 10.0 / 9.0).abs() < 0.01
            && INITIATION_WEIBULL_SLOPE == WEIBULL_SLOPE
    );
}

/// On a dent at its floor under constant loads the initiation sum rises linearly, so the
/// crack opens after exactly `N_i · s / (n_p (σ₀/p_ref)⁹)` revolutions with `σ₀` the
/// edge's Hertz pressure times `K_t = 1 + β√(h/b)`; the factor `s` scales that time.
#[test]
fn crack_opening_at_the_dent_scales_with_the_initiation_factor() {
    let (life, loads) = common::za2115_outer_life();
    let cap = 1e13 as Real;
    let time = |s: Real| {
        let mut st = dent_at_floor(&life, s);
        let t = common::revs_to_transition(&life, &mut st, &loads, cap);
        assert_eq!(st.stage, Stage::CrackOpening, "factor {s}");
        assert!(
            st.fatigue < 0.01,
            "the subsurface sum must not be what opened it"
        );
        t
    };
    let (t1, t2, t_third) = (time(1.0), time(2.0), time(1.0 / 3.0));
    assert!((t2 / t1 - 2.0).abs() < 1e-4, "factor 2: {t2} / {t1}");
    assert!(
        (t_third * 3.0 / t1 - 1.0).abs() < 1e-4,
        "factor 1/3: {t_third} / {t1}"
    );
    let m = life.config().material;
    let c = life.contact();
    let (_, b) = c.semi_axes(loads.zone_mean);
    let h = topography::REAL_DENT.asperity_height;
    let sigma0 = c.max_pressure(loads.edge_cubic) * (1.0 + m.asperity_beta * (h / b).sqrt());
    let r = sigma0 / life.reference_pressure();
    let want = m.initiation_passes / (life.passes_per_rev() * r.powi(9));
    assert!(
        (t1 / want - 1.0).abs() < 1e-3,
        "crack after {t1} rev, closed form {want}"
    );
}
