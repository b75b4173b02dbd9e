//! Whole-life runs: the wear state machine of the core driven by contact loads measured
//! in windows of the dynamic model. Snapshot mode renders a window every
//! `snapshot_every` revolutions (and at every transition), the way condition monitoring
//! samples a machine; dense mode (module `dense`) streams the continuous vibration of
//! the whole life. Both advance the wear from the same measurement windows, so the same
//! seed gives the same wear history in both.

use crate::analysis::{self, WelchParams, Window, ZoneBands};
use serde::{Deserialize, Serialize};
use wearsim_core::wear::{Life, LifeConfig, LifeState, PassLoads, PassMeter, Site, Stage};

pub mod calibrate;
pub mod dense;
pub mod driver;
pub mod ims;
pub mod ims_compare;
pub mod ims_validate;
pub mod lives;
pub mod output;
pub mod parallel;
pub mod phases;
pub mod plot;
pub mod site_json;
pub mod state_json;
pub mod weibull;
pub mod weibull_plot;
use wearsim_core::{Model, ModelConfig, Sample, State};

/// Capacity of the dynamic state.
pub const CAPACITY: usize = wearsim_core::bearing::MAX_ELEMENTS;

/// Most windows of one life in snapshot mode and in `life --lives` (a window every
/// `--snapshot-every` revolutions and at every transition): each keeps its snapshot in
/// memory, so `--snapshot-every 1` would otherwise grow the run with the life, to
/// gigabytes and days. A default run has a few thousand.
pub const MAX_LIFE_WINDOWS: u64 = 100_000;

/// A life-run configuration (validated by [`LifeRun::new`]).
#[derive(Debug, Clone)]
pub struct LifeSpec {
    /// Dynamic model of the bearing (its defect, if any, is replaced by the wear state).
    pub model: ModelConfig,
    /// Wear configuration.
    pub life: LifeConfig,
    /// Seed (wear scatter, windows' random streams).
    pub seed: u64,
    /// Revolutions between snapshots.
    pub snapshot_every: f64,
    /// Recorded window length (s), after a settling time of `settle` (s).
    pub window: f64,
    /// Settling time before each window (s).
    pub settle: f64,
    /// Radial load (N) of the scenario the material's wear limits hold for, when the
    /// model's load was scaled away from it (`wearsim life --load-scale`, `--loads`): the
    /// initiation and propagation laws take their reference pressure there
    /// ([`Life::new_checked_at`]), so a heavier load wears faster through them too. `None`:
    /// the model's own radial load.
    pub calibration_load: Option<f64>,
}

/// What the driver does when the wear reaches the cycle cap (`LifeConfig::cycle_cap`,
/// revolutions) before the bearing fails.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AtCap {
    /// Refuse the life with [`LifeError::CapReached`]: one life, a calibration or a
    /// comparison needs the whole life to failure.
    Refuse,
    /// End the life there as a *suspension* (right-censored: still running when the test
    /// stopped), as an endurance test stopped at a set number of revolutions does; life
    /// statistics fit such lives as suspensions (Abernethy, *The New Weibull Handbook*,
    /// 5th ed., ch. 2 and 5; [`weibull`]).
    Suspend,
}

/// Why a life run cannot be done.
#[derive(Debug, thiserror::Error)]
pub enum LifeError {
    /// A configuration value is out of range.
    #[error("{0}")]
    Config(#[from] wearsim_core::ConfigError),
    /// The snapshot interval is not shorter than the cap.
    #[error("snapshot interval {every} revolutions is not shorter than the cycle cap {cap}; allowed 1 ..< cycles")]
    SnapshotInterval {
        /// Interval.
        every: f64,
        /// Cap.
        cap: f64,
    },
    /// The life did not finish within the cap.
    #[error("the bearing did not fail within the cycle cap of {cap} revolutions (reached stage {stage} at {cycles:.0}); raise --cycles or the load")]
    CapReached {
        /// Cap.
        cap: f64,
        /// Stage reached.
        stage: &'static str,
        /// Revolutions run.
        cycles: f64,
    },
    /// No rolling element carries load in the model's static equilibrium: the bearing
    /// cannot wear, so its life would never end.
    #[error("radial load {load:.0} N: no rolling element carries load in the static equilibrium{why}; an unloaded bearing does not wear (no loaded pass, no fatigue) and its life never ends: raise the load (--load-scale, --loads, or `radial_load` in the configuration) or reduce the radial clearance")]
    Unloaded {
        /// The (scaled) radial load (N).
        load: f64,
        /// Why, where the structure explains it.
        why: String,
    },
    /// The life needed more windows than its observer allows.
    #[error("the simulated life did not fail within {windows} windows ({cycles:.3e} revolutions, stage {stage})")]
    WindowCap {
        /// Most windows.
        windows: u64,
        /// Revolutions run.
        cycles: f64,
        /// Stage reached.
        stage: &'static str,
    },
    /// Signal analysis of a window failed.
    #[error("analysis of the window at {cycles:.0} revolutions failed: {source}")]
    Analysis {
        /// Where.
        cycles: f64,
        /// Cause.
        source: analysis::AnalysisError,
    },
    /// The model produced a non-finite sample.
    #[error("non-finite sample in the window at {cycles:.0} revolutions")]
    NonFinite {
        /// Where.
        cycles: f64,
    },
    /// The caller asked the run to stop ([`crate::cancel`]).
    #[error("{}", crate::cancel::MESSAGE)]
    Interrupted,
}

/// Features of one window (acceleration, m/s²).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Features {
    /// RMS.
    pub rms: f64,
    /// Kurtosis.
    pub kurtosis: f64,
    /// Crest factor.
    pub crest_factor: f64,
    /// RMS in the rotating zone.
    pub zone_rotating: f64,
    /// RMS in the fault-frequency zone.
    pub zone_fault: f64,
    /// RMS in the natural-frequency zone; 0 when the zone lies beyond fs/2
    /// ([`ZoneBands::new_clipped`]).
    pub zone_natural: f64,
    /// RMS in the high-frequency zone; 0 when it lies beyond fs/2.
    pub zone_high: f64,
    /// Envelope-spectrum amplitude at the wear site's pass frequency (BPFO, BPFI or 2·BSF;
    /// `wearsim_core::wear::Site::pass_frequency_hz`).
    pub fault_peak: f64,
    /// Amplitude-spectrum peak near the natural frequency.
    pub resonance_peak: f64,
}

/// One snapshot of the life.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Snapshot {
    /// Revolutions at the window.
    pub cycles: f64,
    /// Stage name.
    pub stage: String,
    /// Features.
    pub features: Features,
    /// Asperity height (m), defect length (m), count, crack depth (m).
    pub asperity: f64,
    /// Defect length (m).
    pub length: f64,
    /// Defect count.
    pub count: u8,
    /// Crack depth (m).
    pub crack: f64,
    /// Debris level.
    pub debris: f64,
    /// Measured pass loads: zone power mean (N).
    pub zone_load: f64,
    /// Measured pass loads: defect-edge cubic mean (N).
    pub edge_load: f64,
}

/// A rendered window at a transition (publication IV's sampled events).
#[derive(Debug, Clone)]
pub struct EventWindow {
    /// Stage entered.
    pub stage: Stage,
    /// Revolutions.
    pub cycles: f64,
    /// Acceleration samples (m/s²).
    pub samples: Vec<f64>,
}

/// Result of a life run.
#[derive(Debug, Clone)]
pub struct LifeResult {
    /// Snapshots in order.
    pub snapshots: Vec<Snapshot>,
    /// Final wear state (with the event log).
    pub state: LifeState,
    /// Windows rendered at transitions.
    pub event_windows: Vec<EventWindow>,
    /// Output rate of the windows (Hz).
    pub fs: f64,
    /// Dynamic windows simulated.
    pub windows: usize,
    /// Wall-clock time (s).
    pub wall_s: f64,
}

/// A validated life run.
#[derive(Debug, Clone)]
pub struct LifeRun {
    /// The specification.
    pub spec: LifeSpec,
    /// The core's life model.
    pub life: Life,
    /// Shaft speed (Hz).
    pub shaft_hz: f64,
}

impl LifeRun {
    /// Validates the specification.
    pub fn new(spec: LifeSpec) -> Result<Self, LifeError> {
        Life::check_base(&spec.model)?;
        let base = Model::new_checked(ModelConfig {
            defect: None,
            ..spec.model.clone()
        })?;
        // Each argument's own range first, then how they relate: a cap of 0 is a cap
        // problem, a negative interval an interval problem.
        wearsim_core::error::check_range("cycles", spec.life.cycle_cap, 1.0, 1e13)?;
        wearsim_core::error::check_range("snapshot_every", spec.snapshot_every, 1.0, 1e13)?;
        if !(spec.snapshot_every >= 1.0 && spec.snapshot_every < spec.life.cycle_cap) {
            return Err(LifeError::SnapshotInterval {
                every: spec.snapshot_every,
                cap: spec.life.cycle_cap,
            });
        }
        wearsim_core::error::check_range("window", spec.window, 0.02, 10.0)?;
        wearsim_core::error::check_range("settle", spec.settle, 0.0, 10.0)?;
        let q_max = base.static_reference().q_max;
        if q_max.is_nan() || q_max <= 0.0 {
            let cfg = base.config();
            let (k, c) = (cfg.structure.stiffness, cfg.clearance);
            let why = if k * c >= cfg.radial_load {
                format!(
                    ": the structure's support stiffness ({k:.3e} N/m) carries up to {:.0} N within the radial clearance ({:.1} µm) before any element touches",
                    k * c,
                    c * 1e6
                )
            } else {
                String::new()
            };
            return Err(LifeError::Unloaded {
                load: cfg.radial_load,
                why,
            });
        }
        let static_load = q_max.max(1e-3);
        let calibration_load = match spec.calibration_load {
            Some(radial) => {
                // The calibration load is the scenario's own `radial_load` (before
                // `--load-scale`): named as the user wrote it. A life needs a load.
                wearsim_core::error::check_range("radial_load", radial, 1e-3, 1e8)?;
                Model::new_checked(ModelConfig {
                    defect: None,
                    radial_load: radial,
                    ..spec.model.clone()
                })?
                .static_reference()
                .q_max
                .max(1e-3)
            }
            None => static_load,
        };
        let life = Life::new_checked_at(
            spec.life,
            &base.config().bearing,
            static_load,
            calibration_load,
            Site::of(spec.model.defect.as_ref().map(|d| &d.location)),
        )?;
        let shaft_hz = spec.model.speed.shaft_hz(0.0);
        Ok(LifeRun {
            spec,
            life,
            shaft_hz,
        })
    }

    /// The dynamic model for wear state `st` (see `Life::model_config`).
    pub fn model_for(&self, st: &LifeState) -> Result<Model, LifeError> {
        let mut cfg = self.life.model_config(&self.spec.model, st);
        // The running-in effect decays over the life: a window starts at the revolutions
        // the wear model has run.
        if let Some(r) = cfg.effects.running_in.as_mut() {
            r.start_revs += st.cycles;
        }
        Ok(Model::new_checked(cfg)?)
    }

    /// Renders one window for state `st` (index `k` seeds its random stream): returns the
    /// samples and the pass loads measured over it.
    pub fn window(&self, st: &LifeState, k: u64) -> Result<(Vec<f64>, PassLoads), LifeError> {
        self.window_of(&self.model_for(st)?, st, k)
    }

    /// Seed of window `k`'s random stream.
    fn window_seed(&self, k: u64) -> u64 {
        self.spec.seed ^ k.wrapping_mul(0x9E37_79B9_7F4A_7C15)
    }

    /// Output samples `(settle, kept)` of a window of `model`.
    fn window_samples(&self, model: &Model) -> (usize, usize) {
        let fs = model.config().output_rate;
        (
            (self.spec.settle * fs) as usize,
            (self.spec.window * fs) as usize,
        )
    }

    /// [`LifeRun::window`] with the model of `st` already built.
    fn window_of(
        &self,
        model: &Model,
        st: &LifeState,
        k: u64,
    ) -> Result<(Vec<f64>, PassLoads), LifeError> {
        let seed = self.window_seed(k);
        let mut ds: State<CAPACITY> = State::new(model, seed)?;
        let (settle, n) = self.window_samples(model);
        let mut meter = PassMeter::new(self.life.site(), &model.config().bearing);
        // The settling samples unobserved, then the window with the meter reading every
        // internal step.
        let mut buf = vec![Sample::default(); settle.max(n)];
        let finite = |b: &[Sample]| b.iter().all(|s| s.accel.is_finite());
        let settled = buf.get_mut(..settle).unwrap_or_default();
        model.fill(&mut ds, settled);
        if !finite(settled) {
            return Err(LifeError::NonFinite { cycles: st.cycles });
        }
        let kept = buf.get_mut(..n).unwrap_or_default();
        model.fill_observed(&mut ds, kept, |s| {
            meter.observe(s.stats(), s.shaft_angle(), s.cage_angle())
        });
        if !finite(kept) {
            return Err(LifeError::NonFinite { cycles: st.cycles });
        }
        Ok((kept.iter().map(|s| s.accel).collect(), meter.loads()))
    }

    /// Windows `k .. k + K` rendered for one model (`model`, the state's) as the lanes of
    /// one group: what [`LifeRun::window`] gives for each of them while the wear state keeps
    /// this model (the driver's speculation, `driver.rs`), bit for bit (the lanes keep the
    /// scalar step's bits; each window has its own seed and pass meter). `None` when the
    /// lanes cannot run them (the caller renders scalar windows, which also report errors).
    pub fn windows_ahead<const K: usize>(
        &self,
        model: &Model,
        k: u64,
    ) -> Option<Vec<(Vec<f64>, PassLoads)>> {
        let windows: Vec<(&LifeRun, &Model, u64)> =
            (0..K as u64).map(|l| (self, model, k + l)).collect();
        Self::windows_in_lanes::<K>(&windows)
    }

    /// One window each of several lives, `(run, model, k)`: the life, the model of its
    /// state and the window's index, rendered as the lanes of one group of the fewest
    /// lanes (2, 4, 8 or 16) that holds them, the last padding the rest: what
    /// [`LifeRun::window`] gives each, bit for bit (the driver's lives side by side,
    /// [`driver::drive_together`]). `None` for fewer than 2 or more than 16 windows, with
    /// the lanes off (`WEARSIM_LANES_OFF`) or when the lanes cannot run them together
    /// (windows of other lengths, other speeds): the caller renders each alone.
    pub fn windows_of_lives(
        windows: &[(&LifeRun, &Model, u64)],
    ) -> Option<Vec<(Vec<f64>, PassLoads)>> {
        if !crate::lanes::lanes_on() {
            return None;
        }
        match windows.len() {
            2 => Self::windows_in_lanes::<2>(windows),
            3..=4 => Self::windows_in_lanes::<4>(windows),
            5..=8 => Self::windows_in_lanes::<8>(windows),
            9..=16 => Self::windows_in_lanes::<16>(windows),
            _ => None,
        }
    }

    /// The windows `(run, model, k)` as the lanes of one `K`-lane group, the last window
    /// repeated as padding; each lane with its own seed and pass meter.
    fn windows_in_lanes<const K: usize>(
        windows: &[(&LifeRun, &Model, u64)],
    ) -> Option<Vec<(Vec<f64>, PassLoads)>> {
        let &(run, model, _) = windows.first()?;
        let (settle, n) = run.window_samples(model);
        if windows.len() > K
            || windows
                .iter()
                .any(|(r, m, _)| r.window_samples(m) != (settle, n))
        {
            return None;
        }
        let pad = windows.last()?;
        let lane = |l: usize| windows.get(l).unwrap_or(pad);
        let models: [Model; K] = std::array::from_fn(|l| lane(l).1.clone());
        let seeds: [u64; K] = std::array::from_fn(|l| lane(l).0.window_seed(lane(l).2));
        let mut meters: Vec<PassMeter> = (0..K)
            .map(|l| PassMeter::new(lane(l).0.life.site(), &lane(l).1.config().bearing))
            .collect();
        let accel = crate::lanes::lane_accel_observed(&models, &seeds, settle, n, |g| {
            let stats = g.stats();
            for (l, (m, s)) in meters.iter_mut().zip(stats).enumerate() {
                if let Some((shaft, cage)) = g.angles(l) {
                    m.observe(s, shaft, cage);
                }
            }
        })?;
        Some(
            accel
                .into_iter()
                .zip(meters)
                .take(windows.len())
                .map(|(a, m)| (a, m.loads()))
                .collect(),
        )
    }

    /// Features of a window.
    pub fn features(&self, x: &[f64], cycles: f64) -> Result<Features, LifeError> {
        let err = |source| LifeError::Analysis { cycles, source };
        let base = Model::new_checked(ModelConfig {
            defect: None,
            ..self.spec.model.clone()
        })?;
        let fs = base.config().output_rate;
        let ff = base.frequencies_at(self.shaft_hz);
        let st = analysis::stats(x).map_err(err)?;
        let nperseg = (x.len() / 4).next_power_of_two().clamp(256, 4096);
        let psd = analysis::welch_psd(
            x,
            fs,
            &WelchParams {
                nperseg,
                ..WelchParams::default()
            },
        )
        .map_err(err)?;
        // A heavy load stiffens the contacts and can move the resonance beyond fs/2: its
        // zones are then empty, level 0, as `resonance_peak` is 0 with no peak.
        let zones = ZoneBands::new_clipped(&ff, fs).map_err(err)?;
        let z = analysis::zone_levels(&psd, &zones);
        let env = analysis::envelope_spectrum(x, fs, None).map_err(err)?;
        let f_site = self.life.site().pass_frequency_hz(&ff);
        let fault_peak = analysis::peak_near(&env, f_site, 0.02 * f_site + env.df)
            .map(|p| p.value)
            .unwrap_or(0.0);
        let spec = analysis::amplitude_spectrum(x, fs, Window::Hann).map_err(err)?;
        let fnat = base.natural_frequency_hz();
        let resonance_peak = analysis::top_peaks(&spec, 1, 0.7 * fnat, 1.3 * fnat, 0.0)
            .first()
            .map(|p| p.value)
            .unwrap_or(0.0);
        Ok(Features {
            rms: st.rms,
            kurtosis: st.kurtosis,
            crest_factor: st.crest_factor,
            zone_rotating: z.rotating,
            zone_fault: z.fault,
            zone_natural: z.natural,
            zone_high: z.high,
            fault_peak,
            resonance_peak,
        })
    }

    /// Snapshot mode: the whole life, a window every `snapshot_every` revolutions and at
    /// every transition. `progress(cycles, cap)` is called after each window.
    pub fn run_snapshots(
        &self,
        mut progress: impl FnMut(f64, f64),
    ) -> Result<LifeResult, LifeError> {
        let t0 = std::time::Instant::now();
        let mut snapshots = vec![];
        let mut event_windows = vec![];
        let every = self.spec.snapshot_every;
        let cap = self.spec.life.cycle_cap;
        let d = self.drive(
            |_| every,
            MAX_LIFE_WINDOWS,
            AtCap::Refuse,
            |w| {
                snapshots.push(self.snapshot(w.state, &w.samples, w.loads)?);
                if let Some(stage) = w.entered {
                    event_windows.push(EventWindow {
                        stage,
                        cycles: w.state.cycles,
                        samples: w.samples,
                    });
                }
                progress(w.state.cycles, cap);
                Ok(())
            },
        )?;
        Ok(LifeResult {
            snapshots,
            state: d.state,
            event_windows,
            fs: self.spec.model.output_rate,
            windows: d.windows as usize,
            wall_s: t0.elapsed().as_secs_f64(),
        })
    }

    /// Checks the cycle cap.
    pub fn check_cap(&self, st: &LifeState) -> Result<(), LifeError> {
        if st.cycles >= self.spec.life.cycle_cap && st.stage != Stage::Failure {
            return Err(LifeError::CapReached {
                cap: self.spec.life.cycle_cap,
                stage: st.stage.name(),
                cycles: st.cycles,
            });
        }
        Ok(())
    }

    /// The snapshot record of a window.
    pub fn snapshot(
        &self,
        st: &LifeState,
        x: &[f64],
        loads: &PassLoads,
    ) -> Result<Snapshot, LifeError> {
        let t = st.topography;
        Ok(Snapshot {
            cycles: st.cycles,
            stage: st.stage.name().to_string(),
            features: self.features(x, st.cycles)?,
            asperity: t.map(|t| t.asperity_height).unwrap_or(0.0),
            length: t.map(|t| t.length).unwrap_or(0.0),
            count: t.map(|t| t.count).unwrap_or(0),
            crack: st.crack,
            debris: st.debris,
            zone_load: loads.zone,
            edge_load: loads.edge_cubic,
        })
    }
}
