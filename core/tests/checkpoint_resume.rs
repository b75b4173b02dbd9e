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

/// A checkpoint of format version 3 (lines of 256 samples, before the capacity depended on
/// the build) resumes bit-identically at a ratio ≤ 8 whatever this build's capacity: its
/// lines are read into the newest places of this build's lines, all that such a filter
/// reads. The version-3 bytes are made from a version-4 checkpoint by rewriting the version,
/// dropping the stated capacity and cutting each line to its newest 256 samples.
#[test]
fn a_version_3_checkpoint_still_resumes_bit_identically() {
    const NB: usize = 16;
    const OLD: usize = 256;
    let mut cfg = wearsim_core::presets::by_name("cwru-6205-de").unwrap();
    cfg.oversample = Some(8);
    let model = Model::new_checked(cfg).unwrap();
    assert!(model.anti_alias().len() <= OLD);
    let mut a: State<NB> = State::new(&model, 5).unwrap();
    let mut buf = vec![Sample::default(); 1001];
    model.fill(&mut a, &mut buf);
    let mut bytes = vec![0u8; encoded_len(NB)];
    let n = a.encode(&mut bytes).unwrap();
    let new = wearsim_core::decimate::MAX_TAPS;
    // Bytes before the delay lines (as `encoded_len` counts them); version 4 then states the
    // lines' capacity, which version 3 did not.
    let head = 12 + 8 * 10 + 8 * 6 + 1 + 8 + 16 + 8 * 2 * NB + 8 + 1 + 8 * 5 + 1;
    assert_eq!(
        u32::from_le_bytes(bytes[head..head + 4].try_into().unwrap()) as usize,
        new
    );
    let line_len = 8 * 2 * new + 4;
    let mut old = bytes[..head].to_vec();
    old[4..8].copy_from_slice(&3u32.to_le_bytes());
    for l in 0..3 {
        let at = head + 4 + l * line_len;
        let reals: Vec<f64> = (0..2 * new)
            .map(|i| f64::from_le_bytes(bytes[at + 8 * i..at + 8 * i + 8].try_into().unwrap()))
            .collect();
        let pos = u32::from_le_bytes(bytes[at + 16 * new..at + 16 * new + 4].try_into().unwrap())
            as usize;
        // The newest 256 samples, oldest first, stored twice, position 0.
        let hist = &reals[pos + new - OLD..pos + new];
        for x in hist.iter().chain(hist) {
            old.extend_from_slice(&x.to_le_bytes());
        }
        old.extend_from_slice(&0u32.to_le_bytes());
    }
    old.extend_from_slice(&bytes[head + 4 + 3 * line_len..n]);
    let mut b: State<NB> = State::decode(&model, &old).unwrap();
    let mut ra = vec![Sample::default(); 3000];
    let mut rb = ra.clone();
    model.fill(&mut a, &mut ra);
    model.fill(&mut b, &mut rb);
    assert!(
        identical(&ra, &rb),
        "a version-3 checkpoint resumed differently"
    );
    // Not trivially equal: the samples move.
    assert!(ra.iter().any(|s| s.accel != 0.0));
}
