//! The one life driver: the loop that renders a measurement window for the wear state,
//! hands it to an observer and advances the wear by the next block with the pass loads
//! measured in that window, until the bearing fails. Snapshot mode
//! ([`LifeRun::run_snapshots`]) and the lifetime gap's simulated life
//! (`gap::lifetime::LifeSim::run`) are this driver with their own block schedule and
//! observer; dense mode streams samples between windows but advances the wear with the
//! same step ([`LifeRun::advance_checked`]).

use super::{LifeError, LifeRun};
use wearsim_core::wear::{LifeState, PassLoads, Stage};

/// One window of a life, as the driver hands it to its observer.
#[derive(Debug)]
pub struct DriverWindow<'a> {
    /// Wear state the window was rendered for.
    pub state: &'a LifeState,
    /// Window index (seeds the window's random stream).
    pub index: u64,
    /// Acceleration samples (m/s²), after the settling time.
    pub samples: Vec<f64>,
    /// Pass loads measured over the window.
    pub loads: &'a PassLoads,
    /// The stage this state entered at the end of the previous block (running-in for the
    /// first window), if it changed there.
    pub entered: Option<Stage>,
    /// Whether the window ends a whole block of the observer's schedule (and the first
    /// window): what a periodic measurement takes. `false` for a window the driver renders
    /// because a transition cut the block short (a breakout, a spawned defect, the
    /// failure): a simulation-only instant, for instance a fresh breakout edge that shakes
    /// down within about 10⁴ passes (`material.edge_shakedown_passes`), which a snapshot
    /// every few minutes almost never sees. Such windows still measure the pass loads that
    /// advance the wear.
    pub scheduled: bool,
}

/// What one block of the driver did ([`LifeRun::advance_checked`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Block {
    /// Revolutions advanced.
    pub revs: f64,
    /// The stage entered, if it changed.
    pub entered: Option<Stage>,
    /// Whether a transition (a stage change or a growth step of the defect) ended the
    /// block before its revolutions were done.
    pub cut: bool,
}

/// The end of a driven life.
#[derive(Debug, Clone)]
pub struct Driven {
    /// Final wear state (stage failure, with the event log).
    pub state: LifeState,
    /// Windows rendered.
    pub windows: u64,
}

impl LifeRun {
    /// Drives the whole life: a window for the current state, `observe` on it, then the
    /// wear advanced by `block(state)` revolutions (or up to the next transition) with the
    /// window's pass loads; stops after the window of the failure state. Fails when the
    /// cycle cap is reached or more than `max_windows` windows would be needed.
    pub fn drive(
        &self,
        mut block: impl FnMut(&LifeState) -> f64,
        max_windows: u64,
        mut observe: impl FnMut(DriverWindow<'_>) -> Result<(), LifeError>,
    ) -> Result<Driven, LifeError> {
        let mut st = self.life.initial_state(self.spec.seed);
        let mut k = 0u64;
        let mut entered: Option<Stage> = Some(Stage::RunningIn);
        let mut scheduled = true;
        loop {
            let (samples, loads) = self.window(&st, k)?;
            observe(DriverWindow {
                state: &st,
                index: k,
                samples,
                loads: &loads,
                entered: entered.take(),
                scheduled,
            })?;
            k += 1;
            if st.stage == Stage::Failure {
                break;
            }
            let revs = block(&st);
            let b = self.advance_checked(&mut st, &loads, revs)?;
            entered = b.entered;
            scheduled = !b.cut;
            if k > max_windows {
                return Err(LifeError::WindowCap {
                    windows: max_windows,
                    cycles: st.cycles,
                    stage: st.stage.name(),
                });
            }
        }
        Ok(Driven {
            state: st,
            windows: k,
        })
    }

    /// The driver's step: advances the wear by up to `revs` revolutions (less when a
    /// stage transition or a growth step of the defect ends the block early) and checks
    /// the cycle cap.
    pub fn advance_checked(
        &self,
        st: &mut LifeState,
        loads: &PassLoads,
        revs: f64,
    ) -> Result<Block, LifeError> {
        let mut remaining = revs;
        let mut b = Block {
            revs: 0.0,
            entered: None,
            cut: false,
        };
        while remaining > 0.0 {
            let before = st.stage;
            let adv = self.life.advance(st, remaining, loads);
            remaining -= adv.revs;
            b.revs += adv.revs;
            if adv.transition.is_some() {
                b.entered = (st.stage != before).then_some(st.stage);
                b.cut = true;
                break;
            }
            if adv.revs <= 0.0 {
                break;
            }
        }
        self.check_cap(st)?;
        Ok(b)
    }
}
