//! Twin experiments (issues 6 and 13): "measured" bearings simulated with candidate
//! effects at random parameters over their whole range, a measurement noise floor, and a
//! structure, defect size, load and speed that differ from the baseline by realistic
//! random amounts the diagnosis does not know; fitted on one run, chosen on another,
//! strength measured on a third (independent seeds).
//!
//! Two versions of the same check (CI time):
//! * `twins_name_the_withheld_effect_ci` (default `cargo test`, a few minutes on two
//!   cores): 3 trials per effect on seed 7, a different seed from the long run. It can
//!   still fail: at least two detectable trials per effect on average, the truth inside
//!   the reported set in ≥ 75 % of the detectable trials, a median shrink above 0.2 for
//!   every effect, and the strongest trials detected at least as often as the weak ones.
//! * `twins_name_the_withheld_effect` (`#[ignore]`: `cargo test -p wearsim-host --test
//!   gap_validate -- --ignored --nocapture`, or `wearsim gap-validate --trials 20 --null 20
//!   --pairs 20 --triples 20 --outside 20`): the acceptance — truth inside the
//!   reported set in ≥ 90 % of each effect's detectable trials with a mean set size
//!   ≤ 1.5, no-effect twins attributed in ≤ 10 %, out-of-library twins reported as not
//!   closed in ≥ 80 %, two-effect twins with both named in ≥ 80 %. Its figures, met or
//!   not, are recorded in `docs/sim-to-real-results.md` ("Twin experiments").

use wearsim_host::gap::attribute::{false_alarm_threshold, same_class, Options, SIGNIFICANT_GAP};
use wearsim_host::gap::identify::CONFOUND_DEG;
use wearsim_host::gap::validate::{validate, TwinOptions, TwinReport, DETECTABLE};

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
    for b in &r.power {
        println!(
            "strength >= {:.1}: in set {}/{}",
            b.from, b.in_set, b.trials
        );
    }
}

/// Single-effect trials of `e` that were detectable, and of them those whose reported set
/// holds `e`.
fn detected(e: &wearsim_host::gap::validate::EffectRate) -> (usize, usize) {
    (e.detectable, e.in_set_detectable)
}

#[test]
fn twins_name_the_withheld_effect_ci() {
    let trials = 3;
    let opt = TwinOptions {
        trials,
        seed: 7,
        ..TwinOptions::default()
    };
    let r = validate(&opt, &|_, _| {}).expect("twin experiments run");
    print(&r);
    // The angle curve recomputes the sets from each trial's angles: at the shipped angle it
    // must give the report's own sets, and wider angles can only add to them.
    let own = r
        .set_angles
        .iter()
        .find(|a| a.angle_deg == CONFOUND_DEG)
        .expect("the shipped angle is on the curve");
    let in_set: usize = r.rates.iter().map(|e| e.in_set_detectable).sum();
    let detectable: usize = r.rates.iter().map(|e| e.detectable).sum();
    assert_eq!((own.in_set, own.detectable), (in_set, detectable));
    let largest = r
        .rates
        .iter()
        .filter(|e| e.detectable > 0)
        .map(|e| e.mean_set_size_detectable)
        .fold(0.0, f64::max);
    assert!((own.largest_mean_set_size - largest).abs() < 1e-12);
    for w in r.set_angles.windows(2) {
        assert!(w[0].in_set <= w[1].in_set);
        assert!(w[0].largest_mean_set_size <= w[1].largest_mean_set_size);
    }
    assert!(
        r.noise_only_gap < 1.0,
        "noise-only gap {}",
        r.noise_only_gap
    );
    // A trial counts when its withheld effect is detectable (strength ≥ DETECTABLE × the
    // noise-only gap) *and* the gap it leaves on the validation run is one the diagnosis
    // may attribute at all (≥ `significant_gap`; below it the report names no effect by
    // design; a 5 % false-alarm level on no-effect twins, `SIGNIFICANT_GAP`). Since the rig
    // is calibrated before ranking, a mismatch no longer lifts a weak effect's gap over that
    // threshold: weak twins that stay under it are not named, which is the significance
    // rule working, not a missed effect. Both counts are printed.
    let significant = Options::default().significant_gap;
    let mut all = (0, 0);
    for e in &r.rates {
        assert_eq!(e.trials, trials);
        let counted: Vec<_> = r
            .trials
            .iter()
            .filter(|t| t.withheld == [e.effect.clone()] && t.strength >= DETECTABLE)
            .filter(|t| t.before >= significant)
            .collect();
        let held = counted
            .iter()
            .filter(|t| t.reported_set.iter().any(|s| same_class(s, &e.effect)))
            .count();
        println!(
            "{:<18} detectable {} (in set {}), of them with a significant gap {} (in set {held})",
            e.effect,
            e.detectable,
            e.in_set_detectable,
            counted.len()
        );
        all.0 += held;
        all.1 += counted.len();
        let mut shrink: Vec<f64> = counted.iter().map(|t| 1.0 - t.after / t.before).collect();
        shrink.sort_by(f64::total_cmp);
        if let Some(m) = shrink.get(shrink.len() / 2) {
            assert!(
                *m > 0.2,
                "{}: median shrink {m} over its detectable trials with a significant gap",
                e.effect
            );
        }
    }
    // Twins differ from the baseline by a realistic mismatch the diagnosis does not know
    // and effects are drawn over their whole range; still, where the withheld effect is
    // detectable and its gap significant, the reported set must hold it in at least three
    // quarters of the trials (the long run's acceptance is 90 % per effect). A broken fit,
    // cell, calibration or model fails.
    // At least one counted trial per effect on average (slip, running-in and roughness
    // rarely leave a significant gap over their ranges).
    assert!(
        all.1 >= r.rates.len(),
        "only {} detectable trials with a significant gap",
        all.1
    );
    assert!(
        all.0 as f64 >= 0.75 * all.1 as f64,
        "truth inside the reported set in {} of {} detectable trials with a significant gap, need 75 %",
        all.0,
        all.1
    );
    // Strength orders detection: the strongest band is detected at least as often as the
    // trials below the detectability threshold.
    let rate = |b: &wearsim_host::gap::validate::PowerBin| b.in_set as f64 / b.trials.max(1) as f64;
    let weak: Vec<_> = r
        .power
        .iter()
        .filter(|b| b.from < 2.0 && b.trials > 0)
        .collect();
    if let (Some(strong), false) = (r.power.last().filter(|b| b.trials > 0), weak.is_empty()) {
        for w in weak {
            assert!(rate(strong) >= rate(w), "power {:?} below {:?}", strong, w);
        }
    }
}

#[test]
#[ignore = "long validation (~45 min on two cores); figures in docs/sim-to-real-results.md"]
fn twins_name_the_withheld_effect() {
    let opt = TwinOptions {
        trials: 20,
        null_trials: 20,
        pair_trials: 20,
        triple_trials: 20,
        outside_trials: 20,
        ..TwinOptions::default()
    };
    let r = validate(&opt, &|_, _| {}).expect("twin experiments run");
    print(&r);
    // The acceptance, with realistic mismatch.
    for e in &r.rates {
        let (n, held) = detected(e);
        assert!(
            held as f64 >= 0.9 * n as f64,
            "{}: truth inside the reported set in {held} of {n} detectable trials, need 90 %",
            e.effect
        );
        assert!(
            e.mean_set_size_detectable <= 1.5,
            "{}: mean set size {:.2}, limit 1.5",
            e.effect,
            e.mean_set_size_detectable
        );
    }
    let (n, named) = r.null.expect("no-effect twins");
    assert!(
        named as f64 <= 0.1 * n as f64,
        "no-effect twins attributed {named}/{n}"
    );
    let (n, open) = r.outside.expect("out-of-library twins");
    assert!(
        open as f64 >= 0.8 * n as f64,
        "out-of-library not closed {open}/{n}"
    );
    let (_, _, both) = r.pairs.expect("two-effect twins");
    assert!(both >= 0.8, "two-effect twins both named {both:.2}");
}

/// The rig's calibration (`gap::nuisance`) on twins that differ from the baseline only by
/// a random rig mismatch within the documented tolerances (no effect withheld, seeds not
/// used elsewhere): it must bring the training gap down to the level of another
/// realisation, and recover the nuisances the cells identify — the structural damping
/// (resonance width and level) and the defect size (impulse energy) — to within a third of
/// their tolerance. The speed is not calibrated (confounded with slip), so the twins here
/// turn at the nominal speed. The resonance and the load trade
/// off against each other through the contact stiffness in series with the structure and
/// are not asserted (measured on seed 21: errors up to 0.07 and 0.04 against tolerances
/// 0.1 and 0.2).
#[test]
fn calibration_recovers_a_rig_mismatch() {
    use wearsim_core::effects::Effects;
    use wearsim_core::rng::Xoshiro128pp;
    use wearsim_host::gap::matched::{Evaluator, Matched, MEMO};
    use wearsim_host::gap::memo::Memo;
    use wearsim_host::gap::nuisance::{calibrate, Tolerances};
    use wearsim_host::gap::validate::{record, scenario, spec_of};
    use wearsim_host::gap::Reference;

    let base = scenario().expect("the cwru-6205-de preset");
    let spec = spec_of(&base).expect("spec");
    let n = spec.fs as usize;
    let ev = Evaluator::new(2);
    let mut rng = Xoshiro128pp::from_u64(31);
    for trial in 0..3u64 {
        let (twin, truth) = Tolerances::CALIBRATE.draw(&base, &mut rng);
        let matched = |seed: u64| -> Matched {
            let x = record(&twin, seed, n).expect("twin record");
            Matched {
                label: format!("twin {trial}"),
                base: base.clone(),
                reference: Reference::new(&x, &spec).expect("cells"),
                samples: n,
                seed: seed + 17,
                real: vec![],
                memo: Memo::new(MEMO),
            }
        };
        let train = matched(100 + trial);
        let cal = calibrate(
            std::slice::from_ref(&train),
            &Effects::NONE,
            &Tolerances::CALIBRATE,
            &ev,
        );
        // The same twin's own configuration against its training run: what remains from
        // the realisation alone.
        let own = Matched {
            base: twin.clone(),
            memo: Memo::new(MEMO),
            ..train.clone()
        };
        let floor = ev.total(std::slice::from_ref(&own), &Effects::NONE);
        println!(
            "trial {trial}: train gap {:.2} -> {:.2} (own configuration {floor:.2}); truth {truth:?}; fitted {:?}",
            cal.train_before,
            cal.train_after,
            cal.fitted
                .iter()
                .map(|f| (f.name, f.factor))
                .collect::<Vec<_>>()
        );
        assert!(
            cal.train_after <= (2.0 * floor).max(0.5 * cal.train_before),
            "trial {trial}: calibrated gap {:.2} (from {:.2}; own configuration {floor:.2})",
            cal.train_after,
            cal.train_before
        );
        let tol = Tolerances::CALIBRATE;
        for (name, range) in [("damping", tol.damping), ("defect_size", tol.defect_size)] {
            let want = truth
                .iter()
                .find(|(n, _)| n == name)
                .map(|(_, v)| *v)
                .expect("drawn");
            let got = cal
                .fitted
                .iter()
                .find(|f| f.name == name)
                .map(|f| f.factor)
                .expect("fitted");
            assert!(
                (got - want).abs() <= range / 3.0,
                "trial {trial}: {name} fitted {got:.4}, true {want:.4}, tolerance ±{range}"
            );
        }
    }
}

/// The significance threshold's provenance, re-run: 40 no-effect twins of seed 41 (the
/// batch that chose it, and reports nothing) give [`SIGNIFICANT_GAP`] by its rule (95th
/// percentile of their held-out gaps, rounded up to 0.1). About a minute on two cores.
#[test]
#[ignore = "re-derives the significance threshold (~1-2 min on two cores); docs/sim-to-real-results.md"]
fn significance_threshold_comes_from_no_effect_twins() {
    let opt = TwinOptions {
        trials: 1,
        effects: vec!["slip".into()],
        null_trials: 40,
        seed: 41,
        ..TwinOptions::default()
    };
    let r = validate(&opt, &|_, _| {}).expect("twin experiments run");
    let null: Vec<f64> = r
        .trials
        .iter()
        .filter(|t| t.withheld.is_empty() && t.outside.is_none())
        .map(|t| t.before)
        .collect();
    assert_eq!(null.len(), 40);
    println!("no-effect held-out gaps: {null:.2?}");
    assert_eq!(false_alarm_threshold(&null, 0.05), Some(SIGNIFICANT_GAP));
    assert_eq!(r.null_threshold, Some(SIGNIFICANT_GAP));
}

/// Pairs of withheld effects report each effect's own strength (the gap left with the
/// other at its true value): one per effect, detectable for these two strong effects of
/// seed 11 (3.9–41 × the noise-only gap; with neither effect taken out of the truth it
/// would sit at the exact model's ≈ 1), and not the pair's strength (both taken out),
/// while the single-effect trials' own strength is their strength. Two pair trials.
#[test]
fn pair_trials_report_each_effects_own_strength() {
    let opt = TwinOptions {
        trials: 1,
        effects: vec!["edge-shape".into(), "sensor".into()],
        pair_trials: 2,
        seed: 11,
        ..TwinOptions::default()
    };
    let r = validate(&opt, &|_, _| {}).expect("twin experiments run");
    let mut pairs = 0;
    for t in &r.trials {
        assert_eq!(t.strengths.len(), t.withheld.len(), "{t:?}");
        if t.withheld.len() == 1 {
            assert_eq!(t.strengths, vec![t.strength]);
            continue;
        }
        pairs += 1;
        for (w, s) in t.withheld.iter().zip(&t.strengths) {
            assert!(
                s.is_finite() && *s >= DETECTABLE,
                "{w}: own strength {s:.2}, the exact model's {:.2}",
                t.oracle / r.noise_only_gap
            );
        }
        assert!(
            t.strengths
                .iter()
                .any(|s| (s - t.strength).abs() > 0.01 * t.strength),
            "own strengths {:?} are the pair's {}",
            t.strengths,
            t.strength
        );
    }
    assert_eq!(pairs, 2);
    let (n, named) = r.pairs_detectable.expect("pair figures");
    assert!(named <= n && n <= 2, "{named}/{n}");
}

/// The exchange step (`gap::exchange`, `--exchange`) repairs an early choice of forward
/// selection, measured on development seed 101 (the seed the step was developed on; the
/// judging seeds are in `docs/sim-to-real-results.md`, "Exchanges after the greedy
/// additions"). Its second pair trial withholds a load zone and a transfer path:
/// edge-shape, which alone shrinks the validation gap most, enters first, the transfer
/// path second, and the load zone then has too little left to enter. With exchanges,
/// edge-shape is replaced by the load zone once the transfer path is refitted on top of
/// it, and both withheld effects are named. The first pair (slip and load zone), named
/// without an exchange, stays named. Eight single-effect trials precede the pairs
/// (they draw from the same generator).
#[test]
fn an_exchange_repairs_an_early_choice_of_forward_selection() {
    let opt = TwinOptions {
        trials: 1,
        pair_trials: 2,
        seed: 101,
        exchange: true,
        ..TwinOptions::default()
    };
    let r = validate(&opt, &|_, _| {}).expect("twin experiments run");
    let pairs: Vec<_> = r.trials.iter().filter(|t| t.withheld.len() == 2).collect();
    assert_eq!(pairs.len(), 2);
    for t in &pairs {
        println!(
            "{:?}: kept {:?}, exchanged {:?}, final {:.2} (exact model {:.2})",
            t.withheld,
            t.kept,
            t.exchanged
                .iter()
                .map(|x| format!("{} -> {}", x.out, x.added))
                .collect::<Vec<_>>(),
            t.final_gap,
            t.oracle
        );
        let named = t.kept.len() == 2
            && t.withheld
                .iter()
                .all(|w| t.kept.iter().any(|k| same_class(w, k)));
        assert!(named, "{:?} not both named: kept {:?}", t.withheld, t.kept);
    }
    let t = pairs[1];
    assert_eq!(t.withheld, ["load-zone", "transfer-path"]);
    assert!(
        t.exchanged
            .iter()
            .any(|x| x.out == "edge-shape" && x.added == "load-zone" && x.after < x.before),
        "{:?}",
        t.exchanged
    );
}
