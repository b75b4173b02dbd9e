//! Twin experiments (issue 6): "measured" records simulated with one candidate effect at
//! random parameters plus a measurement noise floor, diagnosed from the baseline.
//!
//! Two versions of the same check (issue 13, CI time):
//! * `twins_name_the_withheld_effect_ci` (default `cargo test`, ≈ 1–2 min on two cores):
//!   3 trials per effect on seed 7, a different seed from the long run. It can still
//!   fail: every effect must be named (counting the indistinguishable pair as one class)
//!   in at least 2 of its 3 trials, at least 90 % of all trials must be named, the
//!   median held-out gap after adding the named effect must stay within 1.5× the trial's
//!   noise-only gap, and the median shrink above 0.2. A wrong model, a broken fit or a
//!   broken cell fails it.
//! * `twins_name_the_withheld_effect` (`#[ignore]`: `cargo test -p wearsim-host --test
//!   gap_validate -- --ignored --nocapture`, or `wearsim gap-validate --trials 20`):
//!   the long validation, 20 trials per effect (≈ 10 min on two cores); its figures are
//!   recorded in `docs/sim-to-real-results.md` ("Twin experiments").
//!
//! Thresholds of the long run are the acceptance's: every effect ranked first in ≥ 90 % of
//! its trials (counting the one indistinguishable pair, running-in / roughness, as one
//! class, and requiring its misses to stay inside the pair), and a median held-out gap
//! after adding the named effect ≤ 1.5× the trial's noise-only gap. Twins whose withheld
//! effect the baseline cannot see (its held-out gap below 2× the noise-only gap) are
//! redrawn and counted, never scored.

use wearsim_host::gap::validate::{
    same_class, validate, TwinOptions, TwinReport, INDISTINGUISHABLE,
};

fn print(r: &TwinReport) {
    println!(
        "noise-only gap {:.2}; {} simulations in {:.0} s",
        r.noise_only_gap, r.simulations, r.seconds
    );
    for e in &r.rates {
        println!(
            "{:<18} top-1 {:>2}/{} class {:>2} median shrink {:.2} after/noise {:.2}",
            e.effect, e.top1, e.trials, e.top1_class, e.median_shrink, e.median_after_over_noise
        );
    }
    for (l, row) in r.labels.iter().zip(&r.confusion) {
        println!("{l:<18} {row:?}");
    }
    for e in &r.rates {
        println!(
            "{:<18} truth inside the reported set {}/{}, mean set size {:.2}",
            e.effect, e.in_set, e.trials, e.mean_set_size
        );
    }
    if let Some((n, named)) = r.null {
        println!("no-effect twins: {named}/{n} attributed to an effect");
    }
    if let Some((n, any, both)) = r.pairs {
        println!("two-effect twins ({n}): one named first {any:.2}, both added {both:.2}");
    }
}

fn paired(e: &str) -> bool {
    INDISTINGUISHABLE.iter().any(|(a, b, _)| *a == e || *b == e)
}

/// Trials of effect `e` named first (its class for a paired effect).
fn named(e: &wearsim_host::gap::validate::EffectRate) -> usize {
    if paired(&e.effect) {
        e.top1_class
    } else {
        e.top1
    }
}

#[test]
fn twins_name_the_withheld_effect_ci() {
    let trials = 3;
    let opt = TwinOptions {
        trials,
        seed: 7,
        null_trials: 3,
        ..TwinOptions::default()
    };
    let r = validate(&opt, &|_, _| {}).expect("twin experiments run");
    print(&r);
    assert!(
        r.noise_only_gap < 1.0,
        "noise-only gap {}",
        r.noise_only_gap
    );
    let mut all = (0, 0);
    for e in &r.rates {
        assert_eq!(e.trials, trials);
        all.0 += named(e);
        all.1 += e.trials;
        assert!(
            named(e) >= 2,
            "{}: named in {} of {} trials, need 2",
            e.effect,
            named(e),
            e.trials
        );
        assert!(
            e.median_after_over_noise <= 1.5,
            "{}: held-out gap after adding it is {:.2}x the noise-only gap (limit 1.5)",
            e.effect,
            e.median_after_over_noise
        );
        assert!(
            e.median_shrink > 0.2,
            "{}: median shrink {}",
            e.effect,
            e.median_shrink
        );
    }
    assert!(
        all.0 as f64 >= 0.9 * all.1 as f64,
        "named in {} of {} trials, need 90 %",
        all.0,
        all.1
    );
}

#[test]
#[ignore = "long validation (~10 min on two cores); figures in docs/sim-to-real-results.md"]
fn twins_name_the_withheld_effect() {
    let opt = TwinOptions {
        trials: 20,
        null_trials: 20,
        pair_trials: 20,
        ..TwinOptions::default()
    };
    let r = validate(&opt, &|_, _| {}).expect("twin experiments run");
    print(&r);
    assert!(
        r.noise_only_gap < 1.0,
        "noise-only gap {}",
        r.noise_only_gap
    );
    for (e, row) in r.rates.iter().zip(&r.confusion) {
        assert_eq!(e.trials, 20);
        let rate = named(e) as f64 / e.trials as f64;
        assert!(
            rate >= 0.9,
            "{}: ranked first in {:.0} % of trials, need 90 %",
            e.effect,
            100.0 * rate
        );
        assert!(
            e.median_after_over_noise <= 1.5,
            "{}: held-out gap after adding it is {:.2}x the noise-only gap (limit 1.5)",
            e.effect,
            e.median_after_over_noise
        );
        // Misses of a paired effect go to its partner, nowhere else.
        if paired(&e.effect) {
            let outside: usize = row
                .iter()
                .zip(&r.columns)
                .filter(|(_, c)| !same_class(c, &e.effect))
                .map(|(n, _)| n)
                .sum();
            assert!(
                outside <= 2,
                "{}: {outside} misses outside its pair",
                e.effect
            );
        }
        // Whatever is named, the gap must shrink when the withheld effect is real.
        assert!(
            e.median_shrink > 0.2,
            "{}: median shrink {}",
            e.effect,
            e.median_shrink
        );
    }
}
