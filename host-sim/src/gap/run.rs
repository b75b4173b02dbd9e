//! Matched simulations of the gap's fits: one configuration ([`simulate`]), or several of
//! one matched record at once ([`simulate_many`]). The fits evaluate many effect settings
//! against the same baseline and seed; those that leave the kinematics alone run as lanes
//! of one [`wearsim_core::model::LaneGroup`] (see [`crate::lanes`]), bit for bit what
//! [`simulate`] gives one at a time.

use crate::lanes::lane_accel;
use wearsim_core::{Model, ModelConfig, Sample, State};

/// Settling time simulated and discarded before a matched record (s): the structure's
/// transient and the effects' filters (transfer-path modes at 5 % damping decay by e⁻¹⁰
/// within 0.1 s above 300 Hz) are gone.
pub const SETTLE_S: f64 = 0.1;

/// `samples` accelerations (m/s²) of `cfg` with generator seed `seed`, after
/// [`SETTLE_S`]; an error when the model refuses the configuration or a sample is not
/// finite.
pub fn simulate(cfg: &ModelConfig, seed: u64, samples: usize) -> Result<Vec<f64>, String> {
    let model = Model::new_checked(cfg.clone()).map_err(|e| e.to_string())?;
    let fs = model.config().output_rate;
    let mut st: State<{ crate::simulate::CAPACITY }> =
        State::new(&model, seed).map_err(|e| e.to_string())?;
    let mut buf = vec![Sample::default(); ((SETTLE_S * fs) as usize).max(1)];
    model.fill(&mut st, &mut buf);
    buf.resize(samples, Sample::default());
    model.fill(&mut st, &mut buf);
    let x: Vec<f64> = buf.iter().map(|s| s.accel).collect();
    if x.iter().any(|v| !v.is_finite()) {
        return Err("the model produced a non-finite sample".into());
    }
    Ok(x)
}

/// [`simulate`] of every configuration in `cfgs` (same seed and length), in order, with
/// the same results (samples and errors); configurations whose models can share the
/// kinematics run in lane groups of up to [`crate::lanes::MAX_LANES`] (sizes from
/// [`crate::lanes::group_size`]), the others alone.
pub fn simulate_many(
    cfgs: &[ModelConfig],
    seed: u64,
    samples: usize,
) -> Vec<Result<Vec<f64>, String>> {
    let mut out: Vec<Option<Result<Vec<f64>, String>>> = (0..cfgs.len()).map(|_| None).collect();
    let mut models: Vec<(usize, Model)> = Vec::new();
    for (i, cfg) in cfgs.iter().enumerate() {
        match Model::new_checked(cfg.clone()) {
            Ok(model) => models.push((i, model)),
            Err(e) => out[i] = Some(Err(e.to_string())),
        }
    }
    let alone = |i: usize| simulate(&cfgs[i], seed, samples);
    let plan = crate::lanes::plan(models.len(), |a, b| {
        crate::lanes::sharing(&models[a].1, &models[b].1)
    });
    for (k, now) in plan {
        let res = match k {
            16 => group::<16>(&models, &now, seed, samples),
            8 => group::<8>(&models, &now, seed, samples),
            4 => group::<4>(&models, &now, seed, samples),
            2 => group::<2>(&models, &now, seed, samples),
            _ => None,
        };
        match res {
            Some(r) => {
                for (&j, x) in now.iter().zip(r) {
                    let i = models[j].0;
                    out[i] = Some(x.or_else(|_| alone(i)));
                }
            }
            None => {
                for &j in &now {
                    let i = models[j].0;
                    out[i] = Some(alone(i));
                }
            }
        }
    }
    out.into_iter()
        .map(|r| r.unwrap_or_else(|| Err("not simulated".into())))
        .collect()
}

/// Models `idx` of `models` (at most K; padded) as one lane group with seed `seed`,
/// [`SETTLE_S`] and then `samples`; a lane with a non-finite acceleration comes back as `Err(())`
/// (rerun alone).
#[allow(clippy::type_complexity)]
fn group<const K: usize>(
    models: &[(usize, Model)],
    idx: &[usize],
    seed: u64,
    samples: usize,
) -> Option<Vec<Result<Vec<f64>, ()>>> {
    let last = idx.len().checked_sub(1)?;
    if idx.len() > K {
        return None;
    }
    // Padding lanes (beyond `idx`) repeat the last setting; their output is dropped.
    let ms: [Model; K] = std::array::from_fn(|l| models[idx[l.min(last)]].1.clone());
    let fs = ms[0].config().output_rate;
    let settle = ((SETTLE_S * fs) as usize).max(1);
    let lanes = lane_accel(&ms, &[seed; K], settle, samples)?;
    Some(
        lanes
            .into_iter()
            .take(idx.len())
            .map(|r| match r {
                Ok(a) if a.iter().all(|v| v.is_finite()) => Ok(a),
                Ok(_) => Err(()),
                Err(a) if a.iter().all(|v| v.is_finite()) => Ok(a),
                Err(_) => Err(()),
            })
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gap::matched::merge;
    use wearsim_core::effects::Effects;
    use wearsim_core::forces::defect::DefectLocation;

    /// Lanes give [`simulate`]'s samples for every setting: six settings that
    /// share the kinematics (load zone, sensor, transfer path at different strengths:
    /// groups of 4 and 2) and one that does not (speed fluctuation: alone).
    #[test]
    fn simulate_many_equals_simulate_one_at_a_time() {
        let mut base = wearsim_core::presets::by_name("cwru-6205-de").expect("preset");
        if let Some(d) = base.defect.as_mut() {
            d.location = DefectLocation::InnerRace { angle: 0.0 };
        }
        let setting = |name: &str, scale: f64| {
            let mut fx = Effects::NONE;
            let spec = wearsim_core::effects::info(name).expect("effect");
            let v: Vec<f64> = spec
                .params
                .iter()
                .enumerate()
                .map(|(i, p)| {
                    let d = p.default;
                    if i == 0 {
                        (d * scale).clamp(p.min, p.max)
                    } else {
                        d
                    }
                })
                .collect();
            fx.set_named(name, &v).expect("in bounds");
            fx
        };
        let fxs = [
            setting("load-zone", 1.0),
            setting("load-zone", 1.5),
            setting("sensor", 1.0),
            setting("speed-fluctuation", 1.0),
            setting("transfer-path", 1.0),
            setting("sensor", 2.0),
            Effects::NONE,
        ];
        let cfgs: Vec<ModelConfig> = fxs
            .iter()
            .map(|fx| {
                let mut c = base.clone();
                merge(&mut c.effects, fx);
                c
            })
            .collect();
        let many = simulate_many(&cfgs, 3, 1200);
        assert_eq!(many.len(), fxs.len());
        for (i, (r, cfg)) in many.iter().zip(&cfgs).enumerate() {
            let one = simulate(cfg, 3, 1200).expect("simulate");
            let laned = r.as_ref().expect("laned");
            assert_eq!(laned.len(), 1200);
            assert!(
                laned
                    .iter()
                    .zip(&one)
                    .all(|(a, b)| a.to_bits() == b.to_bits()),
                "setting {i} differs"
            );
        }
        // The settings are told apart (sensor noise 1x vs 2x, and load zone vs none).
        assert!(
            many[2].as_ref().ok() != many[5].as_ref().ok(),
            "sensor 1x = 2x"
        );
        assert!(
            many[0].as_ref().ok() != many[6].as_ref().ok(),
            "load zone = none"
        );
    }
}
