//! The life driver's lanes (`life/driver.rs`): windows rendered ahead and lives driven side
//! by side give, bit for bit, what each window and each life gives alone.

use super::life::accelerated;
use wearsim_core::wear::Stage;
use wearsim_host::life::{LifeRun, LifeSpec};

/// The driver's speculation (`life/driver.rs`): windows rendered ahead as the lanes of one
/// group give, bit for bit, the samples and pass loads of the same windows rendered alone,
/// for a healthy state and for one with a dent (defect pass loads), outer-race and
/// inner-race sites; and the windows differ from each other (each has its own seed).
#[test]
fn windows_rendered_ahead_equal_windows_rendered_alone() {
    for inner in [false, true] {
        let mut spec = accelerated(9);
        if inner {
            if let Some(d) = spec.model.defect.as_mut() {
                d.location = wearsim_core::forces::defect::DefectLocation::InnerRace { angle: 0.0 };
            }
        }
        let run = LifeRun::new(spec).unwrap();
        let mut states = vec![run.life.initial_state(9)];
        run.drive(
            |_| 100.0,
            100_000,
            wearsim_host::life::AtCap::Refuse,
            |w| {
                let dented = w.state.stage.index() >= Stage::Dent.index();
                if dented && w.state.stage != Stage::Failure && states.len() == 1 {
                    states.push(w.state.clone());
                }
                Ok(())
            },
        )
        .unwrap();
        assert_eq!(states.len(), 2, "the life reaches a dent");
        for st in &states {
            let model = run.model_for(st).unwrap();
            let ahead = run.windows_ahead::<4>(&model, 11).expect("lanes run");
            assert_eq!(ahead.len(), 4);
            for (i, (a, loads)) in ahead.iter().enumerate() {
                let (b, alone) = run.window(st, 11 + i as u64).unwrap();
                assert!(!b.is_empty());
                assert_eq!(a.len(), b.len(), "window {i} length");
                assert!(
                    a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()),
                    "window {i} samples (inner race {inner}, stage {:?})",
                    st.stage
                );
                assert_eq!(*loads, alone, "window {i} pass loads");
            }
            assert!(ahead[0].0 != ahead[1].0, "windows share a seed");
        }
    }
}

/// Lives side by side (`life::driver::drive_together`, the lifetime gap's candidate
/// lives): each life's windows (samples to the bit, pass loads, stage, index, whether
/// scheduled), wear history and end are exactly those it has when driven alone, for three
/// outer-race lives of other seeds and block schedules, whose windows after the first dent
/// go through one lane group, and an inner-race life, which cannot share their group and
/// is rendered alone.
#[test]
fn lives_driven_together_equal_lives_driven_alone() {
    type Seen = Vec<(u64, Stage, u64, bool, Vec<u64>, String)>;
    let specs: Vec<LifeSpec> = [9u64, 10, 11, 12]
        .iter()
        .map(|&seed| {
            let mut spec = accelerated(seed);
            if seed == 12 {
                if let Some(d) = spec.model.defect.as_mut() {
                    d.location =
                        wearsim_core::forces::defect::DefectLocation::InnerRace { angle: 0.0 };
                }
            }
            spec
        })
        .collect();
    let runs: Vec<LifeRun> = specs
        .into_iter()
        .map(|s| LifeRun::new(s).unwrap())
        .collect();
    let block = |i: usize| move |_: &wearsim_core::wear::LifeState| 100.0 + 40.0 * i as f64;
    let record = |seen: &mut Seen, w: wearsim_host::life::driver::DriverWindow<'_>| {
        seen.push((
            w.index,
            w.state.stage,
            w.state.cycles.to_bits(),
            w.scheduled,
            w.samples.iter().map(|x| x.to_bits()).collect(),
            format!("{:?}", w.loads),
        ));
        Ok(())
    };
    let alone: Vec<(Seen, String)> = runs
        .iter()
        .enumerate()
        .map(|(i, run)| {
            let mut seen = Seen::new();
            let d = run
                .drive(block(i), 100_000, wearsim_host::life::AtCap::Refuse, |w| {
                    record(&mut seen, w)
                })
                .unwrap();
            (seen, format!("{:?}", d.state))
        })
        .collect();
    let mut seen: Vec<Seen> = runs.iter().map(|_| Seen::new()).collect();
    let mut lives: Vec<_> = runs
        .iter()
        .zip(seen.iter_mut())
        .enumerate()
        .map(|(i, (run, s))| wearsim_host::life::driver::Together {
            run,
            block: block(i),
            observe: move |w: wearsim_host::life::driver::DriverWindow<'_>| record(s, w),
        })
        .collect();
    let together = wearsim_host::life::driver::drive_together(
        &mut lives,
        100_000,
        wearsim_host::life::AtCap::Refuse,
    );
    drop(lives);
    assert_eq!(together.len(), 4);
    for (i, ((a, end), (b, d))) in alone.iter().zip(seen.iter().zip(together)).enumerate() {
        let d = d.unwrap();
        assert!(a.len() > 10, "life {i} has windows");
        assert!(
            a.iter()
                .any(|w| w.1.index() >= Stage::Dent.index() && w.1 != Stage::Failure),
            "life {i} reaches a dent"
        );
        assert_eq!(a.len(), b.len(), "life {i}: windows");
        for (k, (x, y)) in a.iter().zip(b).enumerate() {
            assert!(x == y, "life {i}, window {k} differs (stage {:?})", x.1);
        }
        assert_eq!(*end, format!("{:?}", d.state), "life {i}: end state");
    }
    assert!(seen[0] != seen[1], "lives differ");

    // The lane group itself: one window each of the three outer-race lives at their first
    // state with a spall (three models, padded to four lanes) equals each rendered alone.
    let runs = &runs[..3];
    let dented: Vec<wearsim_core::wear::LifeState> = runs
        .iter()
        .enumerate()
        .map(|(i, run)| {
            let mut first = None;
            run.drive(block(i), 100_000, wearsim_host::life::AtCap::Refuse, |w| {
                let stage = w.state.stage;
                if first.is_none()
                    && stage.index() >= Stage::DefectCompletion.index()
                    && stage != Stage::Failure
                {
                    first = Some(w.state.clone());
                }
                Ok(())
            })
            .unwrap();
            first.expect("a spall")
        })
        .collect();
    let models: Vec<_> = runs
        .iter()
        .zip(&dented)
        .map(|(run, st)| run.model_for(st).unwrap())
        .collect();
    let group: Vec<_> = runs
        .iter()
        .zip(&models)
        .enumerate()
        .map(|(i, (run, m))| (run, m, 3 + i as u64))
        .collect();
    let ws = LifeRun::windows_of_lives(&group).expect("the lanes run the three lives");
    assert_eq!(ws.len(), 3);
    for (i, ((a, loads), (run, st))) in ws.iter().zip(runs.iter().zip(&dented)).enumerate() {
        let (b, alone) = run.window(st, 3 + i as u64).unwrap();
        assert!(!b.is_empty());
        assert!(
            a.len() == b.len() && a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()),
            "life {i}: the lane's window differs from the window alone"
        );
        assert_eq!(*loads, alone, "life {i}: pass loads");
    }
}
