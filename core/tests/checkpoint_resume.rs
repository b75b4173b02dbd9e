//! Checkpoints carry every running value of the state: a state that ran under one model
//! and continues under another (a dense life switches models at each block start, and the
//! cached roughness amplitude is only refreshed at block starts and by running-in) resumes
//! bit-identically from its checkpoint.

use wearsim_core::checkpoint::encoded_len;
use wearsim_core::{Model, ModelConfig, Sample, State};

fn with_roughness_scale(cfg: &ModelConfig, k: f64) -> ModelConfig {
    let mut c = cfg.clone();
    if let Some(r) = c.roughness.as_mut() {
        r.rms *= k as wearsim_core::real::Real;
    }
    c
}

fn identical(a: &[Sample], b: &[Sample]) -> bool {
    a.iter()
        .zip(b)
        .all(|(x, y)| x.accel.to_bits() == y.accel.to_bits())
}

/// Issue 11 (1): the roughness amplitude of a state that ran under a rougher model was
/// re-derived from the resuming model, so a resumed dense life drifted from the
/// uninterrupted one (≈1e-6 relative at once, growing).
#[test]
fn resume_keeps_the_cached_roughness_amplitude() {
    let base = wearsim_core::presets::by_name("thesis-61810").unwrap();
    assert!(base.roughness.is_some());
    let rough = Model::new_checked(with_roughness_scale(&base, 1.5)).unwrap();
    let smooth = Model::new_checked(with_roughness_scale(&base, 0.8)).unwrap();
    let mut a: State<16> = State::new(&rough, 7).unwrap();
    let mut buf = vec![Sample::default(); 2000];
    rough.fill(&mut a, &mut buf);
    // Continue under the smoother model without a topography change (as a dense life
    // does in its running-in blocks), then checkpoint mid-way.
    smooth.fill(&mut a, &mut buf);
    let mut bytes = vec![0u8; encoded_len(16)];
    let n = a.encode(&mut bytes).unwrap();
    let mut b: State<16> = State::decode(&smooth, &bytes[..n]).unwrap();
    let mut ra = vec![Sample::default(); 4000];
    let mut rb = ra.clone();
    smooth.fill(&mut a, &mut ra);
    smooth.fill(&mut b, &mut rb);
    assert!(identical(&ra, &rb), "resumed samples differ");
}

/// The same with every effect on (transfer path, sensor, running-in summits and their
/// roughness factor).
#[test]
fn resume_with_every_effect_is_bit_identical() {
    let base = wearsim_core::presets::by_name("thesis-61810").unwrap();
    let mut all = base.clone();
    for e in wearsim_core::effects::CATALOGUE {
        let vals: Vec<wearsim_core::real::Real> = e.params.iter().map(|p| p.default as _).collect();
        all.effects.set_named(e.name, &vals).unwrap();
    }
    let m1 = Model::new_checked(with_roughness_scale(&all, 1.3)).unwrap();
    let m2 = Model::new_checked(all.clone()).unwrap();
    let mut a: State<16> = State::new(&m1, 11).unwrap();
    let mut buf = vec![Sample::default(); 1777];
    m1.fill(&mut a, &mut buf);
    m2.fill(&mut a, &mut buf);
    let mut bytes = vec![0u8; encoded_len(16)];
    let n = a.encode(&mut bytes).unwrap();
    let mut b: State<16> = State::decode(&m2, &bytes[..n]).unwrap();
    let mut ra = vec![Sample::default(); 4000];
    let mut rb = ra.clone();
    m2.fill(&mut a, &mut ra);
    m2.fill(&mut b, &mut rb);
    assert!(identical(&ra, &rb), "resumed samples differ");
}
