//! The cycle cap (`life --cycles`): the last block of a life is clipped at the cap, so a
//! life that reaches it is suspended exactly there and a failure beyond it is never
//! counted; a life that fails before the cap is the same, bit for bit, as without it.

use wearsim_core::wear::{LifeConfig, LifeState, Stage};
use wearsim_host::life::lives::one_life;
use wearsim_host::life::{AtCap, LifeError, LifeRun, LifeSpec};

fn spec(seed: u64, every: f64, cap: f64) -> LifeSpec {
    LifeSpec {
        model: wearsim_core::presets::by_name("thesis-61810").unwrap(),
        life: LifeConfig {
            cycle_cap: cap,
            ..LifeConfig::DEFAULT
        },
        seed,
        snapshot_every: every,
        window: 0.05,
        settle: 0.05,
        calibration_load: None,
    }
}

/// The life of `spec` through the driver: (end state, suspended).
fn drive(s: LifeSpec) -> (LifeState, bool) {
    let run = LifeRun::new(s).unwrap();
    let d = run
        .drive(
            |_| run.spec.snapshot_every,
            100_000,
            AtCap::Suspend,
            |_| Ok(()),
        )
        .unwrap();
    (d.state, d.suspended)
}

fn bits(st: &LifeState) -> Vec<(Stage, u64)> {
    st.events
        .iter()
        .map(|e| (e.stage, e.cycles.to_bits()))
        .collect()
}

/// Probe defect: `life --cycles 8.45e6` reported a failure at 8 457 718 revolutions, the
/// cap checked only after the block that passed it. With the cap between the last
/// transition and the failure, the life is now suspended at exactly the cap (its history
/// up to there unchanged), refused as a single life, and with a cap above the failure it
/// is the uncapped life bit for bit.
#[test]
fn a_failure_beyond_the_cap_is_a_suspension_at_the_cap() {
    let every = 200_000.0;
    let (free, suspended) = drive(spec(1, every, LifeConfig::DEFAULT.cycle_cap));
    assert!(!suspended && free.stage == Stage::Failure);
    let end = free.cycles;
    let before = free
        .events
        .iter()
        .rev()
        .find(|e| e.stage != Stage::Failure)
        .unwrap()
        .cycles;
    assert!(before < end);
    let cap = 0.5 * (before + end);

    let (capped, suspended) = drive(spec(1, every, cap));
    assert!(
        suspended,
        "failed at {} with the cap at {cap}",
        capped.cycles
    );
    assert_eq!(
        capped.cycles.to_bits(),
        cap.to_bits(),
        "suspended at {}",
        capped.cycles
    );
    assert_ne!(capped.stage, Stage::Failure);
    let history = bits(&free);
    assert_eq!(bits(&capped), history[..history.len() - 1]);

    // The statistics' life: a suspension at the cap, the fit's censoring time.
    let l = one_life(spec(1, every, cap)).unwrap();
    assert!(l.suspended);
    assert_eq!(l.life.to_bits(), cap.to_bits());

    // One life must fail within the cap: refused, not reported complete.
    let run = LifeRun::new(spec(1, every, cap)).unwrap();
    match run.run_snapshots(|_, _| {}) {
        Err(LifeError::CapReached { cycles, .. }) => assert_eq!(cycles, cap),
        other => panic!("expected the cap to be reached, got {other:?}"),
    }

    // A cap above the failure changes nothing.
    let (above, suspended) = drive(spec(1, every, end * 1.000_001));
    assert!(!suspended);
    assert_eq!(above.cycles.to_bits(), end.to_bits());
    assert_eq!(bits(&above), history);
}

/// Probe defect: `life --lives 5 --cycles 6e6 --snapshot-every 2e6` recorded suspensions
/// at 6.88·10⁶ and 6.63·10⁶ revolutions. With blocks as coarse as a third of the cap,
/// every suspended life ends at exactly the cap and no failure lies beyond it.
#[test]
fn coarse_blocks_suspend_at_the_cap() {
    let cap = 6.0e6;
    let mut suspended = 0;
    for seed in 1..=5 {
        let l = one_life(spec(seed, 2.0e6, cap)).unwrap();
        if l.suspended {
            suspended += 1;
            assert_eq!(l.life, cap, "seed {seed} suspended at {}", l.life);
        } else {
            assert!(
                l.life <= cap,
                "seed {seed} failed at {} beyond the cap",
                l.life
            );
        }
    }
    assert!(
        suspended > 0,
        "no life reached the cap: the test tests nothing"
    );
}

/// Probe defect: `life --cycles 0` was reported as a snapshot-interval problem and
/// `--snapshot-every -5` as "not shorter than the cycle cap". Each argument's own range
/// is named first; only two valid values that do not fit together get the relation.
#[test]
fn each_life_argument_is_checked_against_its_own_range_first() {
    let err = |every: f64, cap: f64| LifeRun::new(spec(1, every, cap)).unwrap_err().to_string();
    let e = err(20_000.0, 0.0);
    assert!(
        e.contains("cycles") && !e.contains("snapshot interval"),
        "{e}"
    );
    let e = err(-5.0, 5.0e7);
    assert!(
        e.contains("snapshot_every") && !e.contains("cycle cap"),
        "{e}"
    );
    let e = err(f64::NAN, 5.0e7);
    assert!(e.contains("snapshot_every"), "{e}");
    let e = err(2.0e6, 1.0e6);
    assert!(e.contains("is not shorter than the cycle cap"), "{e}");
}
