//! The one life driver: the loop that renders a measurement window for the wear state,
//! hands it to an observer and advances the wear by the next block with the pass loads
//! measured in that window, until the bearing fails. Snapshot mode
//! ([`LifeRun::run_snapshots`]) and the lifetime gap's simulated life
//! (`gap::lifetime::LifeSim::run`) are this driver with their own block schedule and
//! observer; dense mode streams samples between windows but advances the wear with the
//! same step ([`LifeRun::advance_checked`]). While the wear leaves the dynamic model
//! unchanged from window to window (the fatigue accumulation before the first dent), the
//! driver renders the next windows together as lanes (`Ahead`): the same bits, faster.

use super::{AtCap, LifeError, LifeRun};
use wearsim_core::wear::{LifeState, PassLoads, Stage};

/// Relative rounding of the wear's revolutions within which a block clipped at the cycle
/// cap is taken to have reached it ([`LifeRun::advance_checked`]): the core's steps sum
/// to the clipped block within a few ulp.
const CAP_ROUNDING: f64 = 1e-12;

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
    /// Final wear state (stage failure, with the event log; with [`AtCap::Suspend`], the
    /// state at the cycle cap when `suspended`).
    pub state: LifeState,
    /// Windows rendered.
    pub windows: u64,
    /// The life reached the cycle cap before failing and was ended there
    /// ([`AtCap::Suspend`]).
    pub suspended: bool,
}

impl LifeRun {
    /// Drives the whole life: a window for the current state, `observe` on it, then the
    /// wear advanced by `block(state)` revolutions (or up to the next transition) with the
    /// window's pass loads; stops after the window of the failure state (or, with
    /// [`AtCap::Suspend`], when the wear reaches the cycle cap first). Fails when the
    /// cycle cap is reached or more than `max_windows` windows would be needed.
    pub fn drive(
        &self,
        mut block: impl FnMut(&LifeState) -> f64,
        max_windows: u64,
        at_cap: AtCap,
        mut observe: impl FnMut(DriverWindow<'_>) -> Result<(), LifeError>,
    ) -> Result<Driven, LifeError> {
        let mut d = Drive::new(self);
        loop {
            if crate::cancel::requested() {
                return Err(LifeError::Interrupted);
            }
            let model = self.model_for(&d.st)?;
            let w = d.window(&model)?;
            if let Some(done) = d.after(w, &mut block, max_windows, at_cap, &mut observe)? {
                return Ok(done);
            }
        }
    }

    /// Windows `k ..` for `model`, `depth` of them as the lanes of one group (the
    /// speculation of [`Ahead`]); `None` for a depth of 1, with the lanes off
    /// (`WEARSIM_LANES_OFF`) or when the lanes cannot run them.
    fn render_ahead(
        &self,
        model: &wearsim_core::Model,
        k: u64,
        depth: usize,
    ) -> Option<Vec<(Vec<f64>, PassLoads)>> {
        if !crate::lanes::lanes_on() {
            return None;
        }
        match depth {
            16.. => self.windows_ahead::<16>(model, k),
            8.. => self.windows_ahead::<8>(model, k),
            4.. => self.windows_ahead::<4>(model, k),
            2.. => self.windows_ahead::<2>(model, k),
            _ => None,
        }
    }

    /// The revolutions of the next block for a schedule asking `scheduled`: that, ended
    /// early while a fresh breakout edge shakes down, whose pass loads hold for a fraction
    /// of its shakedown only ([`wearsim_core::wear::Life::representative_revs`]); the next
    /// window re-measures them. Snapshot and dense mode both take their blocks from here,
    /// so they keep one wear history.
    pub fn block_revs(&self, st: &LifeState, scheduled: f64) -> f64 {
        scheduled.min(self.life.representative_revs(st))
    }

    /// The driver's step: advances the wear by up to `revs` revolutions (less when a
    /// stage transition or a growth step of the defect ends the block early) and checks
    /// the cycle cap. A block that would pass the cap is clipped there: the wear then
    /// stands exactly at the cap ([`LifeError::CapReached`], a suspension at the cap with
    /// [`AtCap::Suspend`]) unless it failed within the clipped block, i.e. at or before the
    /// cap. A failure beyond the cap is never reached, and a life that fails before the
    /// cap runs the same steps as without it (the core's steps are bounded by the block's
    /// revolutions only in the step that would reach the cap).
    pub fn advance_checked(
        &self,
        st: &mut LifeState,
        loads: &PassLoads,
        revs: f64,
    ) -> Result<Block, LifeError> {
        let cap = self.spec.life.cycle_cap;
        let to_cap = cap - st.cycles;
        // `revs > to_cap` is false for a NaN block, which advances nothing, as before.
        let clipped = revs > to_cap;
        let mut remaining = if clipped { to_cap.max(0.0) } else { revs };
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
        // The clipped block ran to the cap: the sum of the core's steps is the cap within
        // its rounding, and the life stands exactly there.
        if clipped && st.stage != Stage::Failure && st.cycles >= cap * (1.0 - CAP_ROUNDING) {
            st.cycles = cap;
        }
        self.check_cap(st)?;
        Ok(b)
    }
}

/// A rendered window: its acceleration samples (m/s²) and the pass loads measured in it.
type Rendered = (Vec<f64>, PassLoads);

/// One life on its way through the driver: the wear state and the window count, the
/// stage to report with the next window, and the speculation. [`LifeRun::drive`] runs one
/// to its end; [`drive_together`] runs several side by side.
struct Drive<'r> {
    run: &'r LifeRun,
    st: LifeState,
    k: u64,
    entered: Option<Stage>,
    scheduled: bool,
    ahead: Ahead,
}

impl<'r> Drive<'r> {
    fn new(run: &'r LifeRun) -> Self {
        Drive {
            run,
            st: run.life.initial_state(run.spec.seed),
            k: 0,
            entered: Some(Stage::RunningIn),
            scheduled: true,
            ahead: Ahead::default(),
        }
    }

    /// The window rendered ahead for `model` (the state's), if one is held; counts the
    /// run of unchanged models either way ([`Ahead::take`]).
    fn held(&mut self, model: &wearsim_core::Model) -> Option<Rendered> {
        self.ahead.take(model.config())
    }

    /// The next window when none was held: with the speculation's depth as lanes of its
    /// own, else alone.
    fn render(&mut self, model: &wearsim_core::Model) -> Result<Rendered, LifeError> {
        match self.run.render_ahead(model, self.k, self.ahead.depth()) {
            Some(ws) => self.ahead.fill(model.config(), ws),
            None => None,
        }
        .map_or_else(|| self.run.window_of(model, &self.st, self.k), Ok)
    }

    /// The next window for `model` (the state's): held, or rendered.
    fn window(&mut self, model: &wearsim_core::Model) -> Result<Rendered, LifeError> {
        match self.held(model) {
            Some(w) => Ok(w),
            None => self.render(model),
        }
    }

    /// Hands the window `w` of the current state to `observe`, then advances the wear by
    /// the next block; `Some` when the life has ended (failed, or suspended at the cap).
    fn after(
        &mut self,
        (samples, loads): Rendered,
        block: &mut impl FnMut(&LifeState) -> f64,
        max_windows: u64,
        at_cap: AtCap,
        observe: &mut impl FnMut(DriverWindow<'_>) -> Result<(), LifeError>,
    ) -> Result<Option<Driven>, LifeError> {
        observe(DriverWindow {
            state: &self.st,
            index: self.k,
            samples,
            loads: &loads,
            entered: self.entered.take(),
            scheduled: self.scheduled,
        })?;
        self.k += 1;
        if self.st.stage == Stage::Failure {
            return Ok(Some(Driven {
                state: self.st.clone(),
                windows: self.k,
                suspended: false,
            }));
        }
        let scheduled_revs = block(&self.st);
        let revs = self.run.block_revs(&self.st, scheduled_revs);
        let b = match self.run.advance_checked(&mut self.st, &loads, revs) {
            Err(LifeError::CapReached { .. }) if at_cap == AtCap::Suspend => {
                return Ok(Some(Driven {
                    state: self.st.clone(),
                    windows: self.k,
                    suspended: true,
                }))
            }
            b => b?,
        };
        self.entered = b.entered;
        // A block ended early for a fresh edge is followed by a simulation-only window,
        // like one at a transition.
        self.scheduled = !b.cut && revs >= scheduled_revs;
        if self.k > max_windows {
            return Err(LifeError::WindowCap {
                windows: max_windows,
                cycles: self.st.cycles,
                stage: self.st.stage.name(),
            });
        }
        Ok(None)
    }
}

/// One life for [`drive_together`]: its run, its block schedule and its observer, as
/// [`LifeRun::drive`] takes them.
pub struct Together<'r, B, O> {
    /// The life.
    pub run: &'r LifeRun,
    /// Revolutions of the next block for a state.
    pub block: B,
    /// Sees every window.
    pub observe: O,
}

/// [`LifeRun::drive`] for several lives side by side, with the same results: each life's
/// windows, wear and errors are exactly those it has alone. In every round each life that
/// has not ended takes its next window; the windows of lives whose model keeps changing
/// from window to window (the wear after the first dent: asperities, growth steps,
/// roughness) — which the speculation of one life cannot batch — are rendered together as
/// the lanes of one group (the lanes give the scalar step's bits), the rest as they would
/// be alone. Lives of one bearing at one speed (the lifetime gap's candidate effect sets)
/// share a group; where the lanes cannot run a round's windows together, each is rendered
/// alone.
pub fn drive_together<B, O>(
    lives: &mut [Together<'_, B, O>],
    max_windows: u64,
    at_cap: AtCap,
) -> Vec<Result<Driven, LifeError>>
where
    B: FnMut(&LifeState) -> f64,
    O: FnMut(DriverWindow<'_>) -> Result<(), LifeError>,
{
    let mut drives: Vec<Drive<'_>> = lives.iter().map(|l| Drive::new(l.run)).collect();
    let mut out: Vec<Option<Result<Driven, LifeError>>> = lives.iter().map(|_| None).collect();
    while out.iter().any(Option::is_none) {
        if crate::cancel::requested() {
            for o in out.iter_mut().filter(|o| o.is_none()) {
                *o = Some(Err(LifeError::Interrupted));
            }
            break;
        }
        // This round's window of every life still running: held, or to be rendered.
        let mut round: Vec<(usize, wearsim_core::Model, Option<Rendered>)> = vec![];
        for (i, (d, o)) in drives.iter_mut().zip(&mut out).enumerate() {
            if o.is_some() {
                continue;
            }
            match d.run.model_for(&d.st) {
                Ok(model) => {
                    let held = d.held(&model);
                    round.push((i, model, held));
                }
                Err(e) => *o = Some(Err(e)),
            }
        }
        // Lives whose model changed since their last window go together.
        let changing: Vec<usize> = round
            .iter()
            .enumerate()
            .filter(|(_, (i, _, held))| {
                held.is_none() && drives.get(*i).is_some_and(|d| d.ahead.depth() == 1)
            })
            .map(|(r, _)| r)
            .collect();
        // Grouped as the sweeps group records (`lanes::plan`): lives whose models can share
        // a lane group and whose windows have one length.
        let window = |c: usize| {
            let (i, m, _) = changing.get(c).and_then(|r| round.get(*r))?;
            drives.get(*i).map(|d| (d.run, m, d.k))
        };
        let share = |a: usize, b: usize| match (window(a), window(b)) {
            (Some((ra, ma, _)), Some((rb, mb, _)))
                if ra.window_samples(ma) == rb.window_samples(mb) =>
            {
                crate::lanes::sharing(ma, mb)
            }
            _ => crate::lanes::Sharing::No,
        };
        let mut rendered: Vec<(usize, Rendered)> = vec![];
        for (k, part) in crate::lanes::plan(changing.len(), share) {
            if k < 2 {
                continue;
            }
            let group: Vec<(&LifeRun, &wearsim_core::Model, u64)> =
                part.iter().filter_map(|&c| window(c)).collect();
            if let Some(ws) = LifeRun::windows_of_lives(&group) {
                rendered.extend(
                    part.iter()
                        .filter_map(|&c| changing.get(c).copied())
                        .zip(ws),
                );
            }
        }
        for (r, w) in rendered {
            if let Some(slot) = round.get_mut(r) {
                slot.2 = Some(w);
            }
        }
        for (i, model, held) in round {
            let (Some(d), Some(o), Some(l)) = (drives.get_mut(i), out.get_mut(i), lives.get_mut(i))
            else {
                continue;
            };
            let w = match held {
                Some(w) => Ok(w),
                None => d.render(&model),
            };
            let step =
                w.and_then(|w| d.after(w, &mut l.block, max_windows, at_cap, &mut l.observe));
            match step {
                Ok(None) => {}
                Ok(Some(done)) => *o = Some(Ok(done)),
                Err(e) => *o = Some(Err(e)),
            }
        }
    }
    out.into_iter()
        .map(|o| o.unwrap_or(Err(LifeError::Interrupted)))
        .collect()
}

/// [`drive_together`] for runs that may have failed to be built, each life's windows seen
/// by a recorder of its own (`R::default()`) through `observe`, each life's blocks from
/// `block(run)`: per run, in order, its recorder and its end, or its error (the build's, or
/// the drive's as text).
pub fn drive_recorded<R: Default, B>(
    runs: &[Result<LifeRun, String>],
    block: impl Fn(&LifeRun) -> B,
    observe: impl Fn(&mut R, DriverWindow<'_>) -> Result<(), LifeError>,
    max_windows: u64,
    at_cap: AtCap,
) -> Vec<Result<(R, Driven), String>>
where
    B: FnMut(&LifeState) -> f64,
{
    let built: Vec<&LifeRun> = runs.iter().filter_map(|r| r.as_ref().ok()).collect();
    let mut recs: Vec<R> = built.iter().map(|_| R::default()).collect();
    let observe = &observe;
    let mut lives: Vec<Together<'_, B, _>> = built
        .iter()
        .zip(recs.iter_mut())
        .map(|(&run, rec)| Together {
            run,
            block: block(run),
            observe: move |w: DriverWindow<'_>| observe(rec, w),
        })
        .collect();
    let mut driven = drive_together(&mut lives, max_windows, at_cap).into_iter();
    drop(lives);
    let mut recs = recs.into_iter();
    runs.iter()
        .map(|r| {
            r.as_ref().map_err(Clone::clone)?;
            let (Some(d), Some(rec)) = (driven.next(), recs.next()) else {
                return Err(LifeError::Interrupted.to_string());
            };
            Ok((rec, d.map_err(|e| e.to_string())?))
        })
        .collect()
}

/// The driver's speculation. A window depends on the wear state only through the dynamic
/// model built for it (`LifeRun::model_for`), and through most of a life (the fatigue
/// accumulation before the first dent, with roughness at its floor, no defect and a
/// constant slip) that model does not change from one window to the next. So after a run
/// of unchanged models the driver renders the next windows together, as the lanes of one
/// group, each with its own seed and pass meter, and keeps them while the model stays the
/// same: the lanes give the scalar step's bits, so the life is the same as when every
/// window is rendered alone, only faster. A window whose model changed (a stage, a growth
/// step, a roughness, debris or asperity change) drops what was rendered ahead.
#[derive(Debug, Default)]
struct Ahead {
    /// Windows rendered ahead for `model`, the next one first.
    windows: std::collections::VecDeque<(Vec<f64>, PassLoads)>,
    /// The model configuration they were rendered for.
    model: Option<wearsim_core::ModelConfig>,
    /// The previous window's model configuration.
    last: Option<wearsim_core::ModelConfig>,
    /// Windows in a row (before this one) whose model equalled the previous window's.
    streak: usize,
}

impl Ahead {
    /// The next window rendered ahead when it was rendered for `model`; otherwise drops
    /// what is held. Counts the run of unchanged models either way.
    fn take(&mut self, model: &wearsim_core::ModelConfig) -> Option<Rendered> {
        self.streak = if self.last.as_ref() == Some(model) {
            self.streak + 1
        } else {
            0
        };
        self.last = Some(model.clone());
        if self.model.as_ref() != Some(model) {
            self.windows.clear();
            self.model = None;
        }
        self.windows.pop_front()
    }

    /// How many windows to render at once: 1 (no speculation) until the model has stayed
    /// the same for a window, then doubling with the run, at most 16 (the widest lane
    /// group). A run that ends wastes at most the windows rendered in its last group.
    fn depth(&self) -> usize {
        match self.streak {
            0 => 1,
            1..=2 => 2,
            3..=6 => 4,
            7..=14 => 8,
            _ => 16,
        }
    }

    /// Holds `windows`, rendered for `model`, and hands out the first.
    fn fill(
        &mut self,
        model: &wearsim_core::ModelConfig,
        windows: Vec<(Vec<f64>, PassLoads)>,
    ) -> Option<Rendered> {
        self.windows = windows.into();
        self.model = Some(model.clone());
        self.windows.pop_front()
    }
}
