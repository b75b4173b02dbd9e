//! `wearsim bench --lanes K`: throughput of K parameter sets at once, in simulated
//! seconds per core-second (thread CPU time of the one thread that runs them, so the
//! figure does not depend on what else runs on the machine). The same K models — the
//! preset (or `--config` scenario) with seeds 1..=K and defect lengths 1, 1.02, … × the
//! configured one — run once one after the other through the scalar `Model::step`, and
//! once together through the K-lane structure-of-arrays stepper
//! (`wearsim_core::model::LaneGroup`). Both runs simulate the same K × `--seconds`; the
//! report checks that the lanes' samples equal the scalar ones bit for bit. With
//! `--own-speed` every lane turns at its own constant speed (1 % apart), which the lane
//! group steps with per-lane kinematics.

use crate::cmd::args::{BenchArgs, CliError};
use crate::config::ScenarioFile;
use crate::simulate::CAPACITY;
use serde_json::{json, Value};
use wearsim_core::model::LaneGroup;
use wearsim_core::{Model, Sample, State};

/// Lane counts the bench is compiled for.
pub const LANE_COUNTS: [usize; 5] = [1, 2, 4, 8, 16];

/// CPU time of the calling thread (s).
fn thread_cpu_s() -> f64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime writes one timespec into the valid pointer given.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    if rc != 0 {
        return 0.0;
    }
    ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
}

/// The K models of the bench: the scenario with the defect length scaled per lane (and,
/// with `--own-speed`, its constant speed).
fn models(a: &BenchArgs, k: usize) -> Result<Vec<Model>, CliError> {
    let mut file = match &a.config {
        Some(p) => ScenarioFile::load(p).map_err(CliError::input)?,
        None => ScenarioFile {
            preset: Some(a.preset.clone()),
            ..Default::default()
        },
    };
    file.fs = Some(a.fs);
    file.duration = Some(a.seconds);
    let (cfg, _) = file.resolve().map_err(CliError::input)?;
    (0..k)
        .map(|i| {
            let mut c = cfg.clone();
            if let Some(d) = c.defect.as_mut() {
                d.topography.length *= 1.0 + 0.02 * i as f64;
            }
            if a.own_speed {
                match &mut c.speed {
                    wearsim_core::speed::SpeedProfile::Constant(f) => *f *= 1.0 + 0.01 * i as f64,
                    _ => {
                        return Err(CliError::input(
                            "--own-speed: the scenario's speed must be constant (speed.shaft_hz)",
                        ))
                    }
                }
            }
            Model::new_checked(c).map_err(CliError::input)
        })
        .collect()
}

/// FNV-1a over the bits of the acceleration samples.
fn fnv(h: &mut u64, x: f64) {
    for b in x.to_bits().to_le_bytes() {
        *h ^= u64::from(b);
        *h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
}

/// Runs every model alone for `n` samples through `Model::step`; (CPU s, per-model hash).
fn run_scalar(models: &[Model], n: usize) -> Result<(f64, Vec<u64>), CliError> {
    let c0 = thread_cpu_s();
    let mut chunk = vec![Sample::default(); 4096];
    let mut hashes = Vec::with_capacity(models.len());
    for (i, m) in models.iter().enumerate() {
        let mut st: State<CAPACITY> =
            State::new(m, 1 + i as u64).map_err(|e| CliError::run(e.to_string()))?;
        let mut h = 0xcbf2_9ce4_8422_2325u64;
        let mut left = n;
        while left > 0 {
            let k = left.min(chunk.len());
            m.fill(&mut st, &mut chunk[..k]);
            for s in &chunk[..k] {
                fnv(&mut h, s.accel);
            }
            left -= k;
        }
        hashes.push(h);
    }
    Ok((thread_cpu_s() - c0, hashes))
}

/// Runs the models as one K-lane group for `n` samples; (CPU s, per-lane hash).
fn run_lanes<const K: usize>(models: &[Model], n: usize) -> Result<(f64, Vec<u64>), CliError> {
    let group: &[Model; K] = models
        .try_into()
        .map_err(|_| CliError::run(format!("lane bench: {} models for K = {K}", models.len())))?;
    let seeds: [u64; K] = core::array::from_fn(|i| 1 + i as u64);
    let c0 = thread_cpu_s();
    let mut lanes: Box<LaneGroup<K, CAPACITY>> = Box::new(
        LaneGroup::new_checked(group, &seeds).map_err(|e| CliError::input(e.to_string()))?,
    );
    // On the heap: 1024 rows of K samples would be 384 KB of stack at K = 16.
    let mut chunk: Vec<[Sample; K]> = std::iter::repeat_n([Sample::default(); K], 1024).collect();
    let mut hashes = vec![0xcbf2_9ce4_8422_2325u64; K];
    let mut left = n;
    while left > 0 {
        let k = left.min(chunk.len());
        crate::lanes::fill(&mut lanes, &mut chunk[..k]);
        for row in &chunk[..k] {
            for (h, s) in hashes.iter_mut().zip(row) {
                fnv(h, s.accel);
            }
        }
        left -= k;
    }
    Ok((thread_cpu_s() - c0, hashes))
}

/// `run_lanes` for a lane count known at run time.
fn run_lanes_k(models: &[Model], n: usize) -> Result<(f64, Vec<u64>), CliError> {
    match models.len() {
        1 => run_lanes::<1>(models, n),
        2 => run_lanes::<2>(models, n),
        4 => run_lanes::<4>(models, n),
        8 => run_lanes::<8>(models, n),
        16 => run_lanes::<16>(models, n),
        k => Err(CliError::input(format!(
            "--lanes {k}: the lane bench is built for K in {LANE_COUNTS:?}"
        ))),
    }
}

/// Measures the K models through the scalar step and as K lanes; the report as JSON.
pub fn measure(a: &BenchArgs, k: usize) -> Result<Value, CliError> {
    wearsim_core::error::check_range("seconds", a.seconds, 1.0, 600.0).map_err(CliError::input)?;
    if !LANE_COUNTS.contains(&k) {
        return Err(CliError::input(format!(
            "--lanes {k}: the lane bench is built for K in {LANE_COUNTS:?}"
        )));
    }
    let models = models(a, k)?;
    let n = (a.seconds * a.fs).round() as usize;
    // Warm-up (caches, page faults of the lane group), not timed.
    let warm = (0.05 * a.fs).round() as usize;
    run_scalar(&models[..1], warm)?;
    run_lanes_k(&models, warm)?;
    let (c1, h1) = run_scalar(&models, n)?;
    let (ck, hk) = run_lanes_k(&models, n)?;
    let simulated = k as f64 * n as f64 / a.fs;
    let per_core_1 = simulated / c1.max(1e-12);
    let per_core_k = simulated / ck.max(1e-12);
    let m0 = &models[0];
    Ok(json!({
        "preset": if a.config.is_some() { None } else { Some(&a.preset) },
        "config": a.config.as_ref().map(|p| p.display().to_string()),
        "fs": a.fs,
        "oversample": m0.oversample(),
        "elements": m0.config().bearing.elements,
        "defect": m0.config().defect.map(|d| format!("{:?}", d.location)),
        "effects_on": wearsim_core::effects::EffectKind::ALL
            .iter()
            .filter(|e| m0.config().effects.is_on(**e))
            .map(|e| e.name())
            .collect::<Vec<_>>(),
        "seconds_per_lane": a.seconds,
        "lanes": k,
        "own_speed": a.own_speed,
        "one_lane": {"simulated_s": simulated, "cpu_s": c1, "sim_s_per_core_s": per_core_1},
        "k_lanes": {"simulated_s": simulated, "cpu_s": ck, "sim_s_per_core_s": per_core_k},
        "per_core_speedup": per_core_k / per_core_1.max(1e-12),
        "bit_identical": h1 == hk,
        "structure_of_arrays": true,
        "simd": crate::lanes::simd_path(),
    }))
}

/// `wearsim bench --lanes K`.
pub fn run(a: &BenchArgs, k: usize) -> Result<(), CliError> {
    let r = measure(a, k)?;
    if r["bit_identical"] != json!(true) {
        return Err(CliError::run(
            "lane bench: the K-lane samples differ from the scalar step's",
        ));
    }
    if a.json {
        crate::cmd::report::print_json(&r)?;
    } else {
        println!(
            "{}: scalar step {:.1} simulated s per core-second; {k} lanes (structure of arrays, one thread) {:.1} per core-second: {:.2}x per core (samples bit-identical)",
            a.config
                .as_ref()
                .map_or(a.preset.clone(), |p| p.display().to_string()),
            r["one_lane"]["sim_s_per_core_s"].as_f64().unwrap_or(0.0),
            r["k_lanes"]["sim_s_per_core_s"].as_f64().unwrap_or(0.0),
            r["per_core_speedup"].as_f64().unwrap_or(0.0),
        );
    }
    Ok(())
}
