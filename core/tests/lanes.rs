//! The K-lane stepper's contract: lane `i`'s samples equal, bit for bit, the scalar
//! `Model::step` of model `i` with the same seed, whether the lanes share the kinematics or
//! move at their own speeds; a group that cannot share a step is refused with the field
//! that differs. Cheap (a few thousand steps).
#![allow(clippy::unnecessary_cast)]

use wearsim_core::effects::CATALOGUE;
use wearsim_core::forces::defect::{DefectLocation, DefectModel};
use wearsim_core::integrate::IntegratorKind;
use wearsim_core::model::{LaneError, LaneGroup, LibmSqrt};
use wearsim_core::speed::SpeedProfile;
use wearsim_core::{presets, Channels, Model, ModelConfig, Real, Sample, State};

/// Turns effect `name` on with its defaults, parameter `scale_param` scaled by `scale`.
fn effect(cfg: &mut ModelConfig, name: &str, scale: Real) {
    let spec = CATALOGUE.iter().find(|e| e.name == name).expect("effect");
    let values: Vec<Real> = spec
        .params
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let v = if p.name == "summits" {
                2.0
            } else {
                p.default as Real
            };
            // Scale the first parameter, clamped into its bounds.
            if i == 0 {
                let s = v * scale;
                s.clamp(p.min as Real, p.max as Real)
            } else {
                v
            }
        })
        .collect();
    cfg.effects.set_named(name, &values).expect("in bounds");
}

/// Runs the scalar step for every model and the lane stepper for all of them; asserts
/// every lane's samples (all three channels), contact figures and shaft and cage angles
/// (what a pass meter observes) are bit-identical.
///
/// Runs on a thread with a 64 MiB stack: two groups of 16 lanes are about 800 KB each
/// (every lane's state holds three anti-alias histories of `2·MAX_TAPS` reals), beyond a
/// test thread's 2 MiB in a debug build (the host's workers have 16 MiB,
/// `wearsim_host::lanes::WORKER_STACK`).
fn assert_lanes_match<const K: usize>(cfgs: [ModelConfig; K], seeds: [u64; K], samples: usize) {
    std::thread::Builder::new()
        .stack_size(64 << 20)
        .spawn(move || lanes_match::<K>(cfgs, seeds, samples))
        .expect("test thread")
        .join()
        .expect("lanes match");
}

fn lanes_match<const K: usize>(cfgs: [ModelConfig; K], seeds: [u64; K], samples: usize) {
    let models: [Model; K] = cfgs.map(|c| Model::new_checked(c).expect("valid model"));
    let mut group: LaneGroup<K, 16> = LaneGroup::new_checked(&models, &seeds).expect("lanes");
    let mut lane_out = vec![[Sample::default(); K]; samples];
    let mut lane_stats = Vec::new();
    let mut lane_angles = Vec::new();
    for slot in lane_out.iter_mut() {
        loop {
            if let Some(s) = group.step() {
                *slot = s;
                break;
            }
        }
        lane_stats.push(group.stats());
        lane_angles.push(core::array::from_fn::<_, K, _>(|l| {
            group.angles(l).expect("lane in range")
        }));
    }
    assert!(
        group.angles(K).is_none(),
        "a lane out of range has no angles"
    );
    // The fill (blocks of four outputs for groups up to 8 lanes) gives the step's samples,
    // and its observer sees every internal step.
    let mut filled: LaneGroup<K, 16> = LaneGroup::new_checked(&models, &seeds).expect("lanes");
    let mut fill_out = vec![[Sample::default(); K]; samples];
    let mut observed = 0u64;
    filled.fill_observed_with(&mut fill_out, &LibmSqrt, |g| {
        observed += 1;
        assert_eq!(g.steps(), observed, "observed after every step");
    });
    assert_eq!(observed, group.steps());
    for (j, (f, s)) in fill_out.iter().zip(&lane_out).enumerate() {
        for (l, (a, b)) in f.iter().zip(s).enumerate() {
            assert_eq!(
                (a.accel.to_bits(), a.vel.to_bits(), a.disp.to_bits()),
                (b.accel.to_bits(), b.vel.to_bits(), b.disp.to_bits()),
                "lane {l} sample {j}: fill {a:?} vs step {b:?}"
            );
        }
    }
    for (i, m) in models.iter().enumerate() {
        let mut st: State<16> = State::new(m, seeds[i]).expect("state");
        let mut nonzero = 0;
        for (j, lanes) in lane_out.iter().enumerate() {
            let s = loop {
                if let Some(s) = m.step(&mut st) {
                    break s;
                }
            };
            let l = lanes[i];
            assert_eq!(
                (s.accel.to_bits(), s.vel.to_bits(), s.disp.to_bits()),
                (l.accel.to_bits(), l.vel.to_bits(), l.disp.to_bits()),
                "lane {i} sample {j}: scalar {s:?} vs lane {l:?}"
            );
            assert_eq!(st.stats(), lane_stats[j][i], "lane {i} stats at sample {j}");
            let (shaft, cage) = lane_angles[j][i];
            assert_eq!(
                (st.shaft_angle().to_bits(), st.cage_angle().to_bits()),
                (shaft.to_bits(), cage.to_bits()),
                "lane {i} angles at sample {j}"
            );
            if s.accel != 0.0 {
                nonzero += 1;
            }
        }
        assert!(nonzero > samples / 2, "lane {i} is silent");
    }
    // The lanes differ (otherwise the test could not tell lanes apart).
    let last = lane_out.last().expect("samples");
    for i in 1..K {
        assert_ne!(last[0].accel, last[i].accel, "lane {i} equals lane 0");
    }
}

fn thesis() -> ModelConfig {
    let mut c = presets::by_name("thesis-61810").expect("preset");
    // All lanes share the ratio (the structure changes the default choice).
    c.oversample = Some(Model::new_checked(c.clone()).expect("m").oversample());
    c
}

/// Lanes differing in load, defect size, structure, roughness, waviness amplitude, slip
/// and seed; outer-race five-step defect; K = 4.
#[test]
fn outer_race_lanes_equal_the_scalar_step() {
    let base = thesis();
    let cfgs: [ModelConfig; 4] = core::array::from_fn(|i| {
        let mut c = base.clone();
        let f = 1.0 + 0.2 * i as Real;
        c.radial_load *= f;
        c.structure.stiffness *= 1.0 + 0.05 * i as Real;
        c.structure.damping *= f;
        if let Some(d) = c.defect.as_mut() {
            d.topography.length *= f;
            d.topography.depth *= 1.0 + 0.1 * i as Real;
        }
        if let Some(r) = c.roughness.as_mut() {
            r.rms *= f;
        }
        if let Some(w) = c.waviness.as_mut() {
            w.amplitude *= if i == 2 { 0.0 } else { f };
        }
        // Slip per lane: larger, or off.
        c.slip = match i {
            1 => c.slip.map(|mut s| {
                s.fraction *= 3.0;
                s
            }),
            3 => None,
            _ => c.slip,
        };
        c
    });
    assert_lanes_match(cfgs, [1, 2, 3, 4], 1501);
}

/// Inner-race defect on the CWRU bearing, K = 8, with a shared speed fluctuation and
/// per-lane load zone, edge shape, sensor, transfer path, shaft harmonics, running-in;
/// all three channels; two lanes with the Sassi and deflection formulations.
#[test]
fn inner_race_lanes_with_effects_equal_the_scalar_step() {
    let mut base = presets::by_name("cwru-6205-de").expect("preset");
    if let Some(d) = base.defect.as_mut() {
        d.location = DefectLocation::InnerRace { angle: 0.3 };
    }
    base.channels = Channels::All;
    base.speed = SpeedProfile::Constant(29.95);
    effect(&mut base, "speed-fluctuation", 1.0);
    base.oversample = Some(Model::new_checked(base.clone()).expect("m").oversample() + 1);
    let cfgs: [ModelConfig; 8] = core::array::from_fn(|i| {
        let mut c = base.clone();
        let f = 1.0 + 0.15 * i as Real;
        c.radial_load *= f;
        if let Some(d) = c.defect.as_mut() {
            d.topography.length *= f;
            d.model = match i {
                3 => DefectModel::Sassi,
                5 => DefectModel::Deflection,
                _ => DefectModel::FiveStep,
            };
        }
        // One lane without the load zone, the others each with its own depth and
        // zone width: the gains are taken for all lanes at once.
        if i != 6 {
            effect(&mut c, "load-zone", f);
            if let Some(p) = c.effects.load_zone.as_mut() {
                p.depth = 0.3 + 0.1 * i as Real;
                p.epsilon = 0.25 + 0.1 * i as Real;
            }
        }
        effect(&mut c, "edge-shape", f);
        effect(&mut c, "sensor", f);
        if i % 2 == 0 {
            effect(&mut c, "transfer-path", f);
            effect(&mut c, "shaft-harmonics", f);
        } else {
            effect(&mut c, "running-in", f);
        }
        c
    });
    assert_lanes_match(cfgs, core::array::from_fn(|i| 100 + i as u64), 1200);
}

/// Mains hum on the outer-race CWRU bearing, K = 8: lanes at 50 and 60 Hz interleaved,
/// one lane without hum and one without the sensor, so lanes share the hum's phasor
/// only where their phases are equal.
#[test]
fn mains_hum_lanes_equal_the_scalar_step() {
    let base = presets::by_name("cwru-6205-de").expect("preset");
    let cfgs: [ModelConfig; 8] = core::array::from_fn(|i| {
        let mut c = base.clone();
        if i != 7 {
            let hum = if i == 6 { 0.0 } else { 0.01 * (1 + i) as Real };
            let hz = if i % 2 == 0 { 50.0 } else { 60.0 };
            c.effects
                .set_named("sensor", &[0.02, 0.0, hum, hz, 0.3])
                .expect("in bounds");
        }
        c
    });
    assert_lanes_match(cfgs, core::array::from_fn(|i| 40 + i as u64), 1200);
}

/// Transfer paths and sensor chains that differ in shape from lane to lane, K = 8 (the
/// lanes filter them side by side): 0 to 3 active modes (a gap in the middle included),
/// path gains, and sensors with and without noise, hum and low-pass, so a lane whose
/// chain draws no noise must keep its generator while its neighbours draw.
#[test]
fn transfer_paths_and_sensors_of_every_shape_equal_the_scalar_step() {
    let mut base = presets::by_name("cwru-6205-de").expect("preset");
    base.channels = Channels::All;
    let cfgs: [ModelConfig; 8] = core::array::from_fn(|i| {
        let mut c = base.clone();
        let g = |on: bool, v: Real| if on { v } else { 0.0 };
        if i != 0 {
            let gains = [g(i % 2 == 1, 1.5), g(i % 4 >= 2, 0.7), g(i >= 4, 2.0)];
            c.effects
                .set_named(
                    "transfer-path",
                    &[
                        1800.0,
                        0.04,
                        gains[0],
                        2600.0,
                        0.06,
                        gains[1],
                        3900.0,
                        0.08,
                        gains[2],
                        0.5 + 0.25 * i as Real,
                    ],
                )
                .expect("in bounds");
        }
        if i != 3 {
            let noise = g(i % 3 != 0, 0.01 * (1 + i) as Real);
            let hum = g(i % 2 == 0, 0.02);
            let corner = g(i >= 5, 3000.0);
            c.effects
                .set_named("sensor", &[noise, corner, hum, 50.0, 0.3])
                .expect("in bounds");
        }
        c
    });
    assert_lanes_match(cfgs, core::array::from_fn(|i| 70 + i as u64), 1500);
}

/// Ball defect, K = 4, lanes differing in seed, defect size and load; exact ZOH.
#[test]
fn ball_defect_lanes_equal_the_scalar_step() {
    let mut base = thesis();
    base.integrator = IntegratorKind::ExactZoh;
    if let Some(d) = base.defect.as_mut() {
        d.location = DefectLocation::Ball {
            element: 3,
            phase: 0.4,
        };
    }
    let cfgs: [ModelConfig; 4] = core::array::from_fn(|i| {
        let mut c = base.clone();
        let f = 1.0 + 0.25 * i as Real;
        c.radial_load *= f;
        if let Some(d) = c.defect.as_mut() {
            d.topography.length *= f;
        }
        // The load zone's gain follows the defective ball (at FTF) in lanes 1 and 2.
        if i == 1 || i == 2 {
            effect(&mut c, "load-zone", f);
        }
        c
    });
    assert_lanes_match(cfgs, [7, 8, 9, 10], 1500);
}

/// Ball defects whose lanes skip the terms together (`LaneGroup::ball_far`, a shared
/// conservative test on the spin): K = 4 with two defects each, lengths ×1–×0.4 and slip
/// ×12–×0 per lane (so the longest defect's slip offset sets the reach), then counts 1 and
/// 3 mixed (the arc of the lanes' defects). Each lane's defect must actually be rolled over
/// in the run (a non-zero defect load on some step), so a wrong skip would change its
/// samples: leaving out the slip offset, the tail, the arc or most of the length each
/// fails this test.
#[test]
fn ball_defect_lanes_skip_together_and_keep_the_scalar_bits() {
    let mut base = thesis();
    base.integrator = IntegratorKind::ExactFoh;
    if let Some(d) = base.defect.as_mut() {
        d.location = DefectLocation::Ball {
            element: 5,
            phase: 1.3,
        };
    }
    let make = |counts: [u8; 4]| -> [ModelConfig; 4] {
        core::array::from_fn(|i| {
            let mut c = base.clone();
            if let Some(d) = c.defect.as_mut() {
                d.topography.length *= 1.0 - 0.2 * i as Real;
                d.topography.count = counts[i];
            }
            // The longest defect with the largest slip, so that its offset sets the reach.
            c.slip = c.slip.map(|mut s| {
                s.fraction *= [12.0, 6.0, 3.0, 0.0][i];
                s
            });
            c
        })
    };
    for counts in [[2, 2, 2, 2], [1, 3, 1, 3]] {
        let cfgs = make(counts);
        let models: [Model; 4] = cfgs
            .clone()
            .map(|c| Model::new_checked(c).expect("valid model"));
        let mut g: LaneGroup<4, 16> =
            LaneGroup::new_checked(&models, &[3, 4, 5, 6]).expect("lanes");
        let mut hit = [false; 4];
        for _ in 0..4000 {
            while g.step().is_none() {}
            for (h, s) in hit.iter_mut().zip(g.stats()) {
                *h |= s.defect_load > 0.0;
            }
        }
        assert_eq!(
            hit, [true; 4],
            "every lane's ball defect is rolled over ({counts:?})"
        );
        assert_lanes_match(cfgs, [3, 4, 5, 6], 4000);
    }
}

/// Lanes at their own speed (`lanes/own.rs`), K = 4: constant speeds of 20–35 Hz, one
/// ramp, on the roughened, wavy thesis bearing (so the roughness draws, the contact and the
/// defect window are decided lane by lane), with per-lane load and slip as well.
#[test]
fn lanes_at_their_own_speed_equal_the_scalar_step() {
    let base = thesis();
    let cfgs: [ModelConfig; 4] = core::array::from_fn(|i| {
        let mut c = base.clone();
        c.speed = match i {
            2 => SpeedProfile::Ramp {
                from_hz: 22.0,
                to_hz: 34.0,
                duration: 0.05,
            },
            _ => SpeedProfile::Constant(20.0 + 7.5 * i as Real),
        };
        c.radial_load *= 1.0 + 0.1 * i as Real;
        if i == 3 {
            c.slip = c.slip.map(|mut s| {
                s.fraction *= 2.0;
                s
            });
        }
        c
    });
    assert_lanes_match(cfgs, [11, 12, 13, 14], 1500);
}

/// Inner-race CWRU lanes, K = 8, each with its own speed fluctuation (the fits of that
/// effect) or none, and per-lane load zone, running-in (summit draws), transfer path and
/// sensor; all three channels. Then a ball defect at three speeds, K = 4.
#[test]
fn lanes_with_their_own_speed_fluctuation_equal_the_scalar_step() {
    let mut base = presets::by_name("cwru-6205-de").expect("preset");
    if let Some(d) = base.defect.as_mut() {
        d.location = DefectLocation::InnerRace { angle: 0.3 };
    }
    base.channels = Channels::All;
    base.speed = SpeedProfile::Constant(29.95);
    base.oversample = Some(Model::new_checked(base.clone()).expect("m").oversample() + 1);
    let cfgs: [ModelConfig; 8] = core::array::from_fn(|i| {
        let mut c = base.clone();
        let f = 1.0 + 0.15 * i as Real;
        c.radial_load *= f;
        if i != 5 {
            effect(&mut c, "speed-fluctuation", 0.5 + 0.3 * i as Real);
        }
        if i != 2 {
            effect(&mut c, "load-zone", f);
        }
        effect(&mut c, "sensor", f);
        if i % 2 == 0 {
            effect(&mut c, "transfer-path", f);
        } else {
            effect(&mut c, "running-in", f);
        }
        c
    });
    assert_lanes_match(cfgs, core::array::from_fn(|i| 200 + i as u64), 1200);

    let mut ball = thesis();
    ball.integrator = IntegratorKind::ExactZoh;
    if let Some(d) = ball.defect.as_mut() {
        d.location = DefectLocation::Ball {
            element: 3,
            phase: 0.4,
        };
    }
    let cfgs: [ModelConfig; 4] = core::array::from_fn(|i| {
        let mut c = ball.clone();
        c.speed = SpeedProfile::Constant(if i == 3 { 25.0 } else { 18.0 + 6.0 * i as Real });
        c.radial_load *= 1.0 + 0.2 * i as Real;
        c
    });
    assert_lanes_match(cfgs, [7, 8, 9, 10], 1500);
}

#[test]
fn mismatched_groups_are_refused_with_the_field() {
    let a = thesis();
    let mut b = a.clone();
    b.output_rate *= 2.0;
    let models = [a.clone(), a.clone(), b].map(|c| Model::new_checked(c).expect("m"));
    match LaneGroup::<3, 16>::new_checked(&models, &[1, 2, 3]) {
        Err(LaneError::Differs { field, lane }) => assert_eq!((field, lane), ("output_rate", 2)),
        other => panic!("expected an output-rate mismatch, got {other:?}"),
    }
    let mut c = a.clone();
    if let Some(d) = c.defect.as_mut() {
        d.location = DefectLocation::InnerRace { angle: 0.0 };
    }
    let models = [a.clone(), c].map(|c| Model::new_checked(c).expect("m"));
    match LaneGroup::<2, 16>::new_checked(&models, &[1, 2]) {
        Err(LaneError::Differs { field, lane }) => {
            assert_eq!((field, lane), ("defect.location", 1))
        }
        other => panic!("expected a defect-location mismatch, got {other:?}"),
    }
    let mut r = a.clone();
    r.integrator = IntegratorKind::Rk4;
    let models = [r.clone(), r].map(|c| Model::new_checked(c).expect("m"));
    assert!(matches!(
        LaneGroup::<2, 16>::new_checked(&models, &[1, 2]),
        Err(LaneError::Unsupported {
            field: "integrator",
            ..
        })
    ));
    // Too small an element capacity for the bearing (14 elements).
    let models = [a.clone(), a].map(|c| Model::new_checked(c).expect("m"));
    assert!(matches!(
        LaneGroup::<2, 8>::new_checked(&models, &[1, 2]),
        Err(LaneError::Config(_))
    ));
}
