//! Running a scenario: the validated model, its run settings, and the loop that fills
//! sample buffers (with an optional progress callback). Shared by `simulate`, `bench`
//! and the tests, so that every figure comes from the same code path.

use crate::config::{ConfigFileError, RunSettings};
use wearsim_core::{Channels, Model, ModelConfig, Sample, State};

/// Element capacity of the host state (the core's maximum).
pub const CAPACITY: usize = wearsim_core::bearing::MAX_ELEMENTS;

/// A validated scenario.
#[derive(Debug, Clone)]
pub struct Scenario {
    /// The validated model.
    pub model: Model,
    /// Seed, duration, settle time.
    pub run: RunSettings,
}

impl Scenario {
    /// Validates `cfg` in the core and checks the run settings.
    pub fn new(cfg: ModelConfig, run: RunSettings) -> Result<Self, ConfigFileError> {
        crate::config::check_run(&run)?;
        let model = Model::new_checked(cfg)?;
        Ok(Scenario { model, run })
    }

    /// Output sample rate (Hz).
    pub fn fs(&self) -> f64 {
        self.model.config().output_rate
    }

    /// The shaft speed over the recorded part, from the settle time to its end (Hz:
    /// mean and extremes, [`SpeedProfile::over`](wearsim_core::speed::SpeedProfile::over)):
    /// a ramp or table seen after the settle is not at its speed at t = 0.
    #[allow(clippy::unnecessary_cast)] // Real is f32 in `f32` builds
    pub fn record_speed(&self) -> wearsim_core::speed::SpeedSpan {
        let t0 = self.run.settle as wearsim_core::Real;
        let t1 = (self.run.settle + self.run.duration) as wearsim_core::Real;
        self.model.config().speed.over(t0, t1)
    }
}

/// The samples of one run, in SI units.
#[derive(Debug, Clone)]
pub struct SimOutput {
    /// Acceleration (m/s²).
    pub accel: Vec<f64>,
    /// Velocity (m/s) when all channels were requested.
    pub vel: Option<Vec<f64>>,
    /// Displacement about static equilibrium (m) when all channels were requested.
    pub disp: Option<Vec<f64>>,
    /// Output rate (Hz).
    pub fs: f64,
    /// Internal steps taken (settling included).
    pub steps: u64,
    /// Wall-clock time of the simulation loop (s).
    pub wall_s: f64,
}

/// Why a run stopped without a complete result.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// A non-finite sample: a model defect, never presented as output.
    #[error("the model produced a non-finite sample at t = {t:.6} s; nothing was written")]
    NonFinite {
        /// Time of the sample (s).
        t: f64,
    },
    /// The caller's cancel flag was set ([`crate::cancel`]): no output.
    #[error("the run was cancelled; nothing was written")]
    Cancelled,
}

/// Runs `sc`, discarding the settling time, calling `progress(done, total)` between
/// chunks of output samples; stops with [`RunError::Cancelled`] once the thread's cancel
/// flag is set ([`crate::cancel`], checked between chunks of 8192 samples, settling
/// included): an embedding such as the Python package sets it from another thread when
/// the user interrupts.
pub fn run(sc: &Scenario, mut progress: impl FnMut(usize, usize)) -> Result<SimOutput, RunError> {
    let cancelled = crate::cancel::requested;
    let fs = sc.fs();
    let n = (sc.run.duration * fs).round() as usize;
    let settle = (sc.run.settle * fs).round() as usize;
    let all = sc.model.config().channels == Channels::All;
    let mut st: State<CAPACITY> = match State::new(&sc.model, sc.run.seed) {
        Ok(s) => s,
        Err(_) => unreachable_capacity(),
    };
    let t0 = std::time::Instant::now();
    let mut chunk = vec![Sample::default(); 8192];
    let mut left = settle;
    while left > 0 {
        if cancelled() {
            return Err(RunError::Cancelled);
        }
        let k = left.min(chunk.len());
        sc.model.fill(&mut st, &mut chunk[..k]);
        left -= k;
    }
    let mut accel = Vec::with_capacity(n);
    let (mut vel, mut disp) = if all {
        (Vec::with_capacity(n), Vec::with_capacity(n))
    } else {
        (vec![], vec![])
    };
    while accel.len() < n {
        if cancelled() {
            return Err(RunError::Cancelled);
        }
        let k = (n - accel.len()).min(chunk.len());
        sc.model.fill(&mut st, &mut chunk[..k]);
        for (i, s) in chunk[..k].iter().enumerate() {
            if !(s.accel.is_finite() && s.vel.is_finite() && s.disp.is_finite()) {
                return Err(RunError::NonFinite {
                    t: (accel.len() + i) as f64 / fs,
                });
            }
        }
        accel.extend(chunk[..k].iter().map(|s| s.accel));
        if all {
            vel.extend(chunk[..k].iter().map(|s| s.vel));
            disp.extend(chunk[..k].iter().map(|s| s.disp));
        }
        progress(accel.len(), n);
    }
    Ok(SimOutput {
        accel,
        vel: all.then_some(vel),
        disp: all.then_some(disp),
        fs,
        steps: st.steps(),
        wall_s: t0.elapsed().as_secs_f64(),
    })
}

/// `State::new` fails only when the bearing has more elements than `CAPACITY`, which
/// `Model::new_checked` already rules out (its limit is the same constant).
fn unreachable_capacity() -> ! {
    unreachable!("element count exceeds MAX_ELEMENTS after validation")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A set cancel flag stops the run before it simulates anything; an unset one changes
    /// nothing (the same samples as `run`).
    #[test]
    fn a_set_cancel_flag_stops_the_run() {
        let file = crate::config::ScenarioFile::parse(
            "preset = \"cwru-6205-de\"\nduration = 0.05\nsettle = 0.01",
            "test",
        )
        .expect("scenario");
        let (cfg, run_settings) = file.resolve().expect("resolve");
        let sc = Scenario::new(cfg, run_settings).expect("scenario");
        let flag = |set| std::sync::Arc::new(std::sync::atomic::AtomicBool::new(set));
        let r = crate::cancel::scope(flag(true), || run(&sc, |_, _| {}));
        assert!(matches!(r, Err(RunError::Cancelled)), "{r:?}");
        let a = run(&sc, |_, _| {}).expect("run").accel;
        let b = crate::cancel::scope(flag(false), || run(&sc, |_, _| {}))
            .expect("run")
            .accel;
        assert_eq!(a.len(), 600);
        assert!(a.iter().zip(&b).all(|(p, q)| p.to_bits() == q.to_bits()));
    }
}
