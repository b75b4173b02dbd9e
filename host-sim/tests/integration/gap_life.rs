//! The sim-to-real gap along a life (issue 6, "Lifetime"): IMS test 2 against a simulated
//! life of the ZA-2115 whose stages come from the core's stress-driven wear. Effects are
//! fitted on bearing 1 (the one that failed) and judged on bearings 2–4 of the same test
//! (new at the same time, no failure) over the stages they share before 50 % of the test.
//!
//! Asserted, each a statement about the physics rather than a figure:
//! * where: the bare simulated bearing is sub-Gaussian in its steady stage (its periodic
//!   waviness lines dominate), the housing accelerometer is not: the steady stage's worst
//!   cell is its kurtosis, far below the measured; and the SDOF model's spall impacts
//!   end the life far louder than measured (end-stage RMS gap above +3 spreads);
//! * the early-life part lies outside the sampling variability (≥ 3× the gap a correct
//!   model would leave) and is closed by running-in (not in the thesis's model), ranked
//!   first on the held-out lives;
//! * the whole-life held-out gap shrinks by at least a third with the greedy additions.
//!
//! CI runs the two candidates these statements are about (running-in and roughness: the
//! early-life pair and the whole-life greedy choice) to stay within its time budget;
//! `WEARSIM_LIFE_ALL_EFFECTS=1` tries all four lifetime candidates, as
//! `wearsim gap --life` does for the figures in docs/sim-to-real-results.md.

use wearsim_host::gap::lifetime::{diagnose, measured, LifeOptions, SIGNIFICANCE};

#[test]
fn ims_test2_gap_along_life_and_the_effect_that_closes_early_life(
) -> Result<(), Box<dyn std::error::Error>> {
    let Some(data) = wearsim_host::io::data_dir()? else {
        return Ok(());
    };
    let path = data.join("ims/features_chocho66/test2_timefeatures.csv");
    let o = LifeOptions {
        train: 1,
        holdout: vec![2, 3, 4],
        test: vec![],
        seed: 1,
        jobs: std::thread::available_parallelism().map_or(1, |n| n.get()),
        effects: if std::env::var_os("WEARSIM_LIFE_ALL_EFFECTS").is_some() {
            vec![]
        } else {
            vec!["running-in".into(), "roughness".into()]
        },
        leave_one_out: false,
        max_search: None,
        exchange: false,
    };
    let m = measured(&path, &o)?;
    let g = diagnose(&m, &o)?;
    println!(
        "{} lives in {:.0} s; life factor {:.3e}",
        g.simulations, g.seconds, g.life_factor
    );
    for s in &g.stages_train {
        println!(
            "  train {:<12} gap {:.2} -> {:.2}  worst {} (sim {:.3}, real {:.3}, gap {:+.2})",
            s.stage, s.before, s.after, s.worst.0, s.worst.1, s.worst.2, s.worst.3
        );
    }
    for s in &g.stages_holdout {
        println!(
            "  held-out {:<9} gap {:.2} -> {:.2}",
            s.stage, s.before, s.after
        );
    }
    let at = &g.attribution;
    for r in &at.ranking {
        println!(
            "  alone: {:<12} shrink {:+.0} %",
            r.effect,
            100.0 * r.shrink
        );
    }
    for e in &g.early {
        println!(
            "  early: {:<12} shrink {:+.0} %",
            e.effect,
            100.0 * e.shrink
        );
    }
    println!(
        "  held-out total {:.2} -> {:.2}; early {:.2} (noise-only {:.2}) closed by {:?}",
        at.baseline_holdout, at.final_holdout, g.early_before, g.noise_only.1, g.early_effect
    );

    // Where along life. The steady stage held the largest gap of all while the spall's
    // propagation was deterministic; with its Hoeprich scatter, seed 1's bearing spalls
    // early (its simulated RMS is up in the measured onset stage, +18.8 spreads), so
    // which stage is largest depends on the draw. The physics asserted is the steady
    // stage's: its worst cell is the kurtosis, far below the measured.
    let steady = g
        .stages_train
        .iter()
        .find(|s| s.stage == "steady")
        .ok_or("no steady stage")?;
    assert!(
        steady.worst.0.ends_with(":kurtosis") && steady.worst.3 < -5.0,
        "steady stage: {:?}",
        steady.worst
    );
    let end = g
        .stages_train
        .iter()
        .find(|s| s.stage == "end")
        .ok_or("no end stage")?;
    assert!(
        end.worst.0.ends_with(":rms") && end.worst.3 > 3.0,
        "end of life: {:?}",
        end.worst
    );
    // The early-life part: real, and closed by running-in.
    assert!(
        g.early_before >= SIGNIFICANCE * g.noise_only.1,
        "early-life gap {:.2} is within sampling ({:.2})",
        g.early_before,
        g.noise_only.1
    );
    // Which effect closes it was a tie on this record before the propagation scatter
    // (running-in 13 % against roughness 11 %, inside the report's 2 % tie rule; issue
    // 13; now 14 % against -1 % on seed 1, one draw): asserted is only that running-in
    // shrinks it and is not beaten beyond the tie, not that it ranks first.
    let top = g.early.first().ok_or("no early ranking")?;
    let ri = g
        .early
        .iter()
        .find(|r| r.effect == "running-in")
        .ok_or("running-in not ranked on the early part")?;
    assert!(
        ri.shrink >= 0.10,
        "running-in early shrink {:.2}",
        ri.shrink
    );
    assert!(
        top.shrink - ri.shrink <= 0.02 + 1e-9,
        "early part: `{}` {:.3} beats running-in {:.3} beyond the tie",
        top.effect,
        top.shrink,
        ri.shrink
    );
    // Where each effect acts: its held-out shrink per stage. The held-out bearings did not
    // fail, so only the stages before 50 % count, and roughness acts in the steady stage
    // (its sub-Gaussian kurtosis above), not in the early ones.
    for r in &at.ranking {
        let stages: Vec<&str> = r.group_shrink.keys().map(String::as_str).collect();
        assert_eq!(
            stages,
            ["early", "running-in", "settled", "steady"],
            "{}",
            r.effect
        );
    }
    let rough = at
        .ranking
        .iter()
        .find(|r| r.effect == "roughness")
        .ok_or("roughness not ranked")?;
    let steady = rough.group_shrink.get("steady").copied().unwrap_or(0.0);
    assert!(
        steady > 0.4 && steady > rough.shrink,
        "roughness per stage {:?}",
        rough.group_shrink
    );
    // Whole life.
    assert!(
        at.final_holdout < (2.0 / 3.0) * at.baseline_holdout,
        "held-out {:.2} -> {:.2}",
        at.baseline_holdout,
        at.final_holdout
    );
    Ok(())
}
