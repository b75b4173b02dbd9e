//! The simulated life of a validation: the life driver on the site of the measured
//! failure, its feature at windows on a fixed clock, and the part of life after the crack
//! opens.

use super::*;

/// Simulated snapshots per life: windows on a clock of `expected / SIM_SNAPSHOTS`
/// revolutions, as a periodic measurement takes them (windows at transitions are left out
/// of the curve, see [`simulate`]).
pub const SIM_SNAPSHOTS: f64 = 300.0;
/// A simulated life: its feature at each window.
#[derive(Debug, Clone, Serialize)]
pub struct SimLife {
    /// Revolutions at each window.
    pub revs: Vec<f64>,
    /// RMS of each window (m/s²).
    pub rms: Vec<f64>,
    /// Mean |x| of each window (m/s²).
    pub mean_abs: Vec<f64>,
    /// Revolutions to failure.
    pub life: f64,
    /// Stage onsets (fraction of life).
    pub stages: Vec<(String, f64)>,
    /// Revolutions from crack opening to failure (the part `life_factor` does not scale).
    pub fixed: f64,
}

impl SimLife {
    /// The normalised curve of `feature`.
    pub fn curve(&self, feature: Feature) -> Curve {
        let t = self.revs.iter().map(|c| c / self.life).collect();
        let v = match feature {
            Feature::Rms => self.rms.clone(),
            Feature::MeanAbs => self.mean_abs.clone(),
        };
        normalise(t, v)
    }
}

/// The `ims-za2115` model with its defect on `site` (the wear state replaces the
/// topography).
pub fn model_on(site: Site) -> Result<wearsim_core::ModelConfig, String> {
    let mut m = wearsim_core::presets::by_name("ims-za2115").ok_or("preset ims-za2115 missing")?;
    if let Some(d) = m.defect.as_mut() {
        d.location = match site {
            Site::OuterRace => d.location,
            Site::InnerRace => DefectLocation::InnerRace { angle: 0.0 },
            Site::Element => DefectLocation::Ball {
                element: 0,
                phase: 0.0,
            },
        };
    }
    Ok(m)
}

/// Runs a life on `site` at `scales` (life factor and propagation limit), a window every `expected / SIM_SNAPSHOTS`
/// revolutions, with a measurement floor of white noise of RMS `floor` (m/s², the
/// `sensor` effect's `noise`; 0 = the bearing's own vibration only). The floor is
/// independent of the model's random stream, so it leaves the wear history unchanged.
pub fn simulate(
    site: Site,
    scales: Scales,
    seed: u64,
    expected: f64,
    floor: f64,
) -> Result<SimLife, String> {
    let mut model = model_on(site)?;
    if floor > 0.0 {
        model.effects.sensor = Some(wearsim_core::effects::sensor::Params {
            noise: floor,
            corner_hz: 0.0,
            hum: 0.0,
            hum_hz: 50.0,
            hum_harmonics: 0.0,
        });
    }
    let spec = LifeSpec {
        model,
        life: scales.life(),
        seed,
        snapshot_every: (expected / SIM_SNAPSHOTS).max(1000.0),
        window: 0.25,
        settle: 0.05,
        calibration_load: None,
    };
    let run = LifeRun::new(spec).map_err(|e| e.to_string())?;
    let every = run.spec.snapshot_every;
    let (mut revs, mut rms, mut mean_abs) = (vec![], vec![], vec![]);
    // The measurement's clock: a window every `every` revolutions from the start, whatever
    // the wear does between them. Windows the driver renders at a transition (a breakout,
    // a spawned defect, the failure) are simulation-only instants that a periodic
    // measurement does not see, so they feed the wear (their pass loads) but not the curve.
    let d = run
        .drive(
            |st| next_on_grid(st.cycles, every) - st.cycles,
            100_000,
            AtCap::Refuse,
            |w| {
                if !w.scheduled {
                    return Ok(());
                }
                let n = w.samples.len().max(1) as f64;
                revs.push(w.state.cycles);
                rms.push((w.samples.iter().map(|x| x * x).sum::<f64>() / n).sqrt());
                mean_abs.push(w.samples.iter().map(|x| x.abs()).sum::<f64>() / n);
                Ok::<(), LifeError>(())
            },
        )
        .map_err(|e| e.to_string())?;
    let st = &d.state;
    Ok(SimLife {
        revs,
        rms,
        mean_abs,
        life: st.cycles,
        stages: st
            .events
            .iter()
            .map(|e| (e.stage.name().to_string(), e.cycles / st.cycles))
            .collect(),
        fixed: fixed_part(st),
    })
}

/// The first point of the grid `k · every` (k = 1, 2, …) after `cycles`.
fn next_on_grid(cycles: f64, every: f64) -> f64 {
    let k = (cycles / every).floor() + 1.0;
    let next = k * every;
    // A state a hair before a grid point (rounding of the advance) goes to that point, not
    // past it.
    if next - cycles > 1e-9 * every {
        next
    } else {
        next + every
    }
}

fn fixed_part(st: &LifeState) -> f64 {
    let open = st
        .events
        .iter()
        .find(|e| e.stage == Stage::CrackOpening)
        .map(|e| e.cycles)
        .unwrap_or(0.0);
    st.cycles - open
}

/// Revolutions per running hour at the IMS speed.
pub fn revs_per_hour() -> f64 {
    IMS_RPM * 60.0
}
