//! Twin experiments (issue 6): "measured" records simulated with one candidate effect at
//! random parameters plus a measurement noise floor, diagnosed from the baseline, 20
//! trials per effect. Asserted: the identification rate per effect, counting an
//! indistinguishable pair (named by `INDISTINGUISHABLE`, with its reason) as one class,
//! and the held-out gap after adding the named effect relative to the trial's noise-only
//! gap (the exactly right model on another realisation).
//!
//! Thresholds are the acceptance's: every effect ranked first in ≥ 90 % of its trials
//! (counting the one indistinguishable pair, running-in / roughness, as one class, and
//! requiring its misses to stay inside the pair), and a median held-out gap after adding
//! the named effect ≤ 1.5× the trial's noise-only gap. Twins whose withheld effect the
//! baseline cannot see (its held-out gap below 2× the noise-only gap) are redrawn and
//! counted, never scored.

use wearsim_host::gap::validate::{same_class, validate, TwinOptions, INDISTINGUISHABLE};

#[test]
fn twins_name_the_withheld_effect() {
    let opt = TwinOptions {
        trials: 20,
        ..TwinOptions::default()
    };
    let r = validate(&opt, &|_, _| {}).expect("twin experiments run");
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
    assert!(
        r.noise_only_gap < 1.0,
        "noise-only gap {}",
        r.noise_only_gap
    );
    let paired = |e: &str| INDISTINGUISHABLE.iter().any(|(a, b, _)| *a == e || *b == e);
    for (e, row) in r.rates.iter().zip(&r.confusion) {
        assert_eq!(e.trials, 20);
        let rate = if paired(&e.effect) {
            e.top1_class
        } else {
            e.top1
        } as f64
            / e.trials as f64;
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
