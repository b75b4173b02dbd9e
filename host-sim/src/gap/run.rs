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
/// [`SETTLE_S`]; an error when the model refuses the configuration, a sample is not
/// finite, or the caller has asked the run to stop ([`crate::cancel`]).
pub fn simulate(cfg: &ModelConfig, seed: u64, samples: usize) -> Result<Vec<f64>, String> {
    if crate::cancel::requested() {
        return Err(crate::cancel::MESSAGE.into());
    }
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
    simulate_ahead(cfgs, &[], seed, samples).0
}

/// [`simulate_many`] of `cfgs`, and also of those configurations of `ahead` (guesses at
/// what will be asked next, best first) that fit into lanes the groups of `cfgs` would
/// otherwise pad: a padding lane costs as much as a real one, so these come at no extra
/// stepping. The second list has, per configuration of `ahead`, its samples when it was
/// simulated (a lane that shares the kinematics of a group's lanes; non-finite samples are
/// dropped) — bit for bit [`simulate`]'s, as every lane is.
#[allow(clippy::type_complexity)]
pub fn simulate_ahead(
    cfgs: &[ModelConfig],
    ahead: &[ModelConfig],
    seed: u64,
    samples: usize,
) -> (Vec<Result<Vec<f64>, String>>, Vec<Option<Vec<f64>>>) {
    let mut out: Vec<Option<Result<Vec<f64>, String>>> = (0..cfgs.len()).map(|_| None).collect();
    let mut extra: Vec<Option<Vec<f64>>> = vec![None; ahead.len()];
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
    // The guesses, built once each when a group has a free lane, and taken in order.
    let mut guesses: Vec<Option<Option<Model>>> = vec![None; ahead.len()];
    for (k, now) in plan {
        if crate::cancel::requested() {
            for &j in &now {
                out[models[j].0] = Some(Err(crate::cancel::MESSAGE.into()));
            }
            continue;
        }
        let mut lanes: Vec<&Model> = now.iter().map(|&j| &models[j].1).collect();
        let mut taken: Vec<usize> = vec![];
        if k > 1 {
            for (g, cfg) in ahead.iter().enumerate() {
                if lanes.len() + taken.len() >= k {
                    break;
                }
                let slot = &mut guesses[g];
                if slot.is_none() {
                    *slot = Some(Model::new_checked(cfg.clone()).ok());
                }
                if let (Some(Some(m)), Some(lead)) = (slot.as_ref(), lanes.first()) {
                    if extra[g].is_none()
                        && !taken.contains(&g)
                        && crate::lanes::sharing(lead, m) == crate::lanes::Sharing::Kinematics
                    {
                        taken.push(g);
                    }
                }
            }
            for &g in &taken {
                if let Some(Some(Some(m))) = guesses.get(g) {
                    lanes.push(m);
                }
            }
        }
        let res = match k {
            16 => group::<16>(&lanes, seed, samples),
            8 => group::<8>(&lanes, seed, samples),
            4 => group::<4>(&lanes, seed, samples),
            2 => group::<2>(&lanes, seed, samples),
            _ => None,
        };
        match res {
            Some(mut r) => {
                for (&g, x) in taken.iter().zip(r.split_off(now.len())) {
                    extra[g] = x.ok();
                }
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
    let out = out
        .into_iter()
        .map(|r| r.unwrap_or_else(|| Err("not simulated".into())))
        .collect();
    (out, extra)
}

/// `lanes` (at most K; padded) as one lane group with seed `seed`, [`SETTLE_S`] and then
/// `samples`; a lane with a non-finite acceleration comes back as `Err(())` (rerun alone).
#[allow(clippy::type_complexity)]
fn group<const K: usize>(
    lanes: &[&Model],
    seed: u64,
    samples: usize,
) -> Option<Vec<Result<Vec<f64>, ()>>> {
    let last = lanes.len().checked_sub(1)?;
    if lanes.len() > K {
        return None;
    }
    // Padding lanes (beyond `lanes`) repeat the last setting; their output is dropped.
    let ms: [Model; K] = std::array::from_fn(|l| lanes[l.min(last)].clone());
    let fs = ms[0].config().output_rate;
    let settle = ((SETTLE_S * fs) as usize).max(1);
    let out = lane_accel(&ms, &[seed; K], settle, samples)?;
    Some(
        out.into_iter()
            .take(lanes.len())
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

    /// The CWRU preset with an inner-race defect, no effects.
    fn preset() -> ModelConfig {
        let mut base = wearsim_core::presets::by_name("cwru-6205-de").expect("preset");
        if let Some(d) = base.defect.as_mut() {
            d.location = DefectLocation::InnerRace { angle: 0.0 };
        }
        base
    }

    /// [`preset`] with effect `name` at `scale` × its default first parameter.
    fn with_effect(name: &str, scale: f64) -> ModelConfig {
        let mut base = preset();
        let spec = wearsim_core::effects::info(name).expect("effect");
        let v: Vec<f64> = spec
            .params
            .iter()
            .enumerate()
            .map(|(i, p)| match i {
                0 => (p.default * scale).clamp(p.min, p.max),
                _ => p.default,
            })
            .collect();
        let mut fx = Effects::NONE;
        fx.set_named(name, &v).expect("in bounds");
        merge(&mut base.effects, &fx);
        base
    }

    /// Guesses fill a group's padding lanes, in order, with [`simulate`]'s samples, and
    /// change nothing of the configurations asked for; those beyond the free lanes are
    /// not simulated.
    #[test]
    fn guesses_take_the_padding_lanes_with_the_scalar_bits() {
        let cfgs: Vec<ModelConfig> = [1.0, 1.5, 3.0]
            .iter()
            .map(|s| with_effect("sensor", *s))
            .collect();
        let ahead = [with_effect("sensor", 2.0), with_effect("sensor", 2.5)];
        let (got, extra) = simulate_ahead(&cfgs, &ahead, 5, 600);
        let same = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits());
        for (r, cfg) in got.iter().zip(&cfgs) {
            let one = simulate(cfg, 5, 600).expect("simulate");
            assert!(same(r.as_ref().expect("laned"), &one));
        }
        // Three configurations make a 4-lane group: one free lane, for the first guess.
        let first = extra[0]
            .as_ref()
            .expect("the first guess fills the free lane");
        assert_eq!(first.len(), 600);
        assert!(same(first, &simulate(&ahead[0], 5, 600).expect("simulate")));
        assert!(extra[1].is_none(), "no lane was left for the second guess");
    }

    /// Lanes give [`simulate`]'s samples for every setting: six settings that
    /// share the kinematics (load zone, sensor, transfer path at different strengths:
    /// groups of 4 and 2) and one that does not (speed fluctuation: alone).
    #[test]
    fn simulate_many_equals_simulate_one_at_a_time() {
        // `None`: the preset's model without effects.
        let settings = [
            Some(("load-zone", 1.0)),
            Some(("load-zone", 1.5)),
            Some(("sensor", 1.0)),
            Some(("speed-fluctuation", 1.0)),
            Some(("transfer-path", 1.0)),
            Some(("sensor", 2.0)),
            None,
        ];
        let cfgs: Vec<ModelConfig> = settings
            .iter()
            .map(|s| match s {
                Some((name, scale)) => with_effect(name, *scale),
                None => preset(),
            })
            .collect();
        let many = simulate_many(&cfgs, 3, 1200);
        assert_eq!(many.len(), cfgs.len());
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
