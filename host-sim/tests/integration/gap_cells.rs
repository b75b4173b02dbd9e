//! The feature cells and the gap of sim-to-real.md on simulated records: a record against
//! another realisation of itself stays within its own spread, an unmodelled transfer-path
//! mode shows up as a large gap located in the zone and band of the mode.

use wearsim_core::{presets, Model, ModelConfig, Sample, State};
use wearsim_host::analysis::FaultFamily;
use wearsim_host::effects::{build, parse_arg};
use wearsim_host::gap::{gap, CellSpec};

fn record(cfg: ModelConfig, seed: u64, seconds: f64) -> Vec<f64> {
    let model = Model::new_checked(cfg).unwrap();
    let fs = model.config().output_rate;
    let mut st: State<32> = State::new(&model, seed).unwrap();
    let mut settle = vec![Sample::default(); (0.1 * fs) as usize];
    model.fill(&mut st, &mut settle);
    let mut out = vec![Sample::default(); (seconds * fs) as usize];
    model.fill(&mut st, &mut out);
    out.iter().map(|s| s.accel).collect()
}

fn spec(cfg: &ModelConfig) -> CellSpec {
    let model = Model::new_checked(cfg.clone()).unwrap();
    CellSpec {
        fs: cfg.output_rate,
        ff: model.frequencies_at(cfg.speed.shaft_hz(0.0)),
        family: FaultFamily::OuterRace,
    }
}

#[test]
fn twin_records_are_within_their_spread_and_a_missing_mode_is_located() {
    let base = presets::by_name("cwru-6205-de").unwrap();
    let s = spec(&base);
    let sim = record(base.clone(), 1, 4.0);
    let twin = record(base.clone(), 2, 4.0);
    let same = gap(&sim, &twin, &s).unwrap();
    println!(
        "twin total gap {:.2}, largest {} {:.2}",
        same.total, same.cells[0].name, same.cells[0].gap
    );
    assert!(same.total < 2.0, "twin total gap {}", same.total);

    // "Measured": the same bearing seen through an extra structural mode at 4.5 kHz.
    let fx =
        build(&[parse_arg("transfer-path:f1=4500,zeta1=0.03,gain1=6,gain2=0,gain3=0").unwrap()])
            .unwrap();
    let real = record(
        ModelConfig {
            effects: fx,
            ..base
        },
        2,
        4.0,
    );
    let g = gap(&sim, &real, &s).unwrap();
    println!(
        "mode total gap {:.2}; top cells {:?}",
        g.total,
        g.cells
            .iter()
            .take(4)
            .map(|c| (&c.name, c.gap))
            .collect::<Vec<_>>()
    );
    assert!(
        g.total > 3.0 * same.total.max(0.5),
        "{} vs {}",
        g.total,
        same.total
    );
    // The mode rings after every impact: the largest gaps are the impulsiveness (kurtosis,
    // crest) and the level of the zone that holds 4.5 kHz, all negative (the simulation
    // lacks the mode's energy); within the high zone the 1/6-octave shape then puts the
    // simulation's relative energy away from the mode (a positive shape gap elsewhere).
    let top: Vec<&str> = g.cells.iter().take(4).map(|c| c.name.as_str()).collect();
    assert!(top.contains(&"zone:high"), "top cells {top:?}");
    let high = g.cells.iter().find(|c| c.name == "zone:high").unwrap();
    assert!(high.gap < -10.0, "zone:high gap {}", high.gap);
    assert!(g
        .cells
        .iter()
        .filter(|c| c.group != "shape")
        .take(3)
        .all(|c| c.gap < 0.0));
    // Zones the mode does not reach stay close.
    let rot = g.cells.iter().find(|c| c.name == "zone:rotating").unwrap();
    assert!(rot.gap.abs() < 3.0, "zone:rotating gap {}", rot.gap);
}
