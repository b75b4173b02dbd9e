//! The simulated life of a validation: the life driver on the site of the measured
//! failure, its feature at windows on a fixed clock, and the part of life after the crack
//! opens.

use super::*;
use crate::life::driver::{drive_recorded, DriverWindow};

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

/// Runs a life on `site` at `scales` (life factor and propagation limit), a window every
/// `expected /` [`SIM_SNAPSHOTS`] revolutions, with a measurement floor of white noise of
/// RMS `floor` (m/s², the `sensor` effect's `noise`; 0 = the bearing's own vibration
/// only). The floor is independent of the model's random stream, so it leaves the wear
/// history unchanged.
pub fn simulate(
    site: Site,
    scales: Scales,
    seed: u64,
    expected: f64,
    floor: f64,
) -> Result<SimLife, String> {
    simulate_seeds(site, scales, &[seed], expected, floor)
        .pop()
        .unwrap_or_else(|| Err(LifeError::Interrupted.to_string()))
}

/// [`simulate`] for each of `seeds`, the lives side by side
/// ([`drive_together`](crate::life::driver::drive_together): their windows whose model
/// changed, after the first dent, as the lanes of one group), each with the result it has
/// alone.
pub fn simulate_seeds(
    site: Site,
    scales: Scales,
    seeds: &[u64],
    expected: f64,
    floor: f64,
) -> Vec<Result<SimLife, String>> {
    let runs: Vec<Result<LifeRun, String>> = seeds
        .iter()
        .map(|&seed| life_run(site, scales, seed, expected, floor))
        .collect();
    drive_recorded(
        &runs,
        |run| {
            let every = run.spec.snapshot_every;
            move |st: &LifeState| next_on_grid(st.cycles, every) - st.cycles
        },
        Snapshots::observe,
        MAX_WINDOWS,
        AtCap::Refuse,
    )
    .into_iter()
    .map(|r| r.map(|(curve, d)| curve.life(&d.state)))
    .collect()
}

/// Most windows of one simulated life (the clock asks for about [`SIM_SNAPSHOTS`] per
/// expected life; an uncalibrated life can run far longer).
const MAX_WINDOWS: u64 = 100_000;

/// The life run of [`simulate`]: the model on `site` with the floor as its sensor noise,
/// the wear at `scales`, the window clock of `expected`.
fn life_run(
    site: Site,
    scales: Scales,
    seed: u64,
    expected: f64,
    floor: f64,
) -> Result<LifeRun, String> {
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
    LifeRun::new(spec).map_err(|e| e.to_string())
}

/// What a simulated life keeps of its windows: the features of those on the
/// measurement's clock.
#[derive(Debug, Default)]
struct Snapshots {
    revs: Vec<f64>,
    rms: Vec<f64>,
    mean_abs: Vec<f64>,
}

impl Snapshots {
    /// The driver's observer. The measurement's clock is a window every `every`
    /// revolutions from the start, whatever the wear does between them. Windows the driver
    /// renders at a transition (a breakout, a spawned defect, the failure) are
    /// simulation-only instants that a periodic measurement does not see, so they feed the
    /// wear (their pass loads) but not the curve.
    fn observe(&mut self, w: DriverWindow<'_>) -> Result<(), LifeError> {
        if !w.scheduled {
            return Ok(());
        }
        let n = w.samples.len().max(1) as f64;
        self.revs.push(w.state.cycles);
        self.rms
            .push((w.samples.iter().map(|x| x * x).sum::<f64>() / n).sqrt());
        self.mean_abs
            .push(w.samples.iter().map(|x| x.abs()).sum::<f64>() / n);
        Ok(())
    }

    /// The simulated life that ended in `st`.
    fn life(self, st: &LifeState) -> SimLife {
        SimLife {
            revs: self.revs,
            rms: self.rms,
            mean_abs: self.mean_abs,
            life: st.cycles,
            stages: st
                .events
                .iter()
                .map(|e| (e.stage.name().to_string(), e.cycles / st.cycles))
                .collect(),
            fixed: fixed_part(st),
        }
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Everything a simulated life reports, to the bit (JSON writes the shortest decimal
    /// that reads back as the same double).
    fn bits(l: &SimLife) -> String {
        serde_json::to_string(l).unwrap()
    }

    /// A population's lives side by side are, seed by seed and in order, the lives run
    /// alone: short inner-race lives (life factor and propagation limit a hundredth of
    /// steel's) of three seeds, whose windows after the first dent go to one lane group.
    #[test]
    fn seeds_side_by_side_are_the_seeds_alone() {
        let steel = Scales::steel();
        let scales = Scales {
            life_factor: steel.life_factor / 100.0,
            propagation_passes: steel.propagation_passes / 100.0,
        };
        let seeds = [3, 1, 2];
        let expected = 3e7;
        let together = simulate_seeds(Site::InnerRace, scales, &seeds, expected, 0.0);
        assert_eq!(together.len(), seeds.len());
        let mut lives = vec![];
        for (&seed, t) in seeds.iter().zip(together) {
            let alone = simulate(Site::InnerRace, scales, seed, expected, 0.0).unwrap();
            let t = t.unwrap();
            assert!(
                alone.rms.len() >= 5,
                "seed {seed}: {} windows",
                alone.rms.len()
            );
            assert_eq!(bits(&t), bits(&alone), "seed {seed}");
            lives.push(alone.life);
        }
        // The seeds draw different lives, so a life handed to the wrong seed shows.
        assert!(lives.windows(2).all(|w| w[0] != w[1]), "lives {lives:?}");
    }
}
