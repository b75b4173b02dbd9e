//! `wearsim bench --lanes K`: throughput of several scenarios at once, in simulated
//! seconds per core-second (thread CPU time, so the figure does not depend on what else
//! runs on the machine), one lane against K lanes. The K lanes are K scenarios (seeds
//! 1..=K) on K threads: the K-lane structure-of-arrays stepping of issue 15 is not
//! implemented, so K lanes can at best match one lane per core-second (they add wall-clock
//! throughput on more cores, not per-core throughput).

use crate::cmd::args::{BenchArgs, CliError};
use crate::config::ScenarioFile;
use crate::simulate::{self, Scenario};
use serde_json::{json, Value};

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

fn scenario(a: &BenchArgs, seed: u64) -> Result<Scenario, CliError> {
    let file = ScenarioFile {
        preset: Some(a.preset.clone()),
        fs: Some(a.fs),
        duration: Some(a.seconds),
        seed: Some(seed),
        ..Default::default()
    };
    let (cfg, run) = file.resolve().map_err(CliError::input)?;
    Scenario::new(cfg, run).map_err(CliError::input)
}

/// Runs `scs` on one thread each; returns (simulated s, summed thread CPU s, wall s).
fn run_lanes(scs: &[Scenario]) -> Result<(f64, f64, f64), CliError> {
    let t0 = std::time::Instant::now();
    let results: Vec<Result<(f64, f64), CliError>> = std::thread::scope(|s| {
        let handles: Vec<_> = scs
            .iter()
            .map(|sc| {
                s.spawn(move || {
                    let c0 = thread_cpu_s();
                    let out = simulate::run(sc, |_, _| {}).map_err(CliError::run)?;
                    Ok((out.accel.len() as f64 / out.fs, thread_cpu_s() - c0))
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| {
                h.join()
                    .unwrap_or_else(|_| Err(CliError::run("a bench lane panicked")))
            })
            .collect()
    });
    let wall = t0.elapsed().as_secs_f64();
    let (mut sim, mut cpu) = (0.0, 0.0);
    for r in results {
        let (s, c) = r?;
        sim += s;
        cpu += c;
    }
    Ok((sim, cpu, wall))
}

/// Measures 1 lane and `k` lanes; the report as JSON.
pub fn measure(a: &BenchArgs, k: usize) -> Result<Value, CliError> {
    wearsim_core::error::check_range("seconds", a.seconds, 1.0, 600.0).map_err(CliError::input)?;
    if !(1..=256).contains(&k) {
        return Err(CliError::input(format!("--lanes {k} is outside 1..=256")));
    }
    let one = [scenario(a, 1)?];
    let many = (1..=k as u64)
        .map(|s| scenario(a, s))
        .collect::<Result<Vec<_>, _>>()?;
    let (s1, c1, w1) = run_lanes(&one)?;
    let (sk, ck, wk) = run_lanes(&many)?;
    let per_core_1 = s1 / c1.max(1e-12);
    let per_core_k = sk / ck.max(1e-12);
    Ok(json!({
        "preset": a.preset,
        "fs": a.fs,
        "seconds_per_lane": a.seconds,
        "lanes": k,
        "cores": std::thread::available_parallelism().map_or(1, |n| n.get()),
        "one_lane": {"simulated_s": s1, "cpu_s": c1, "wall_s": w1,
                     "sim_s_per_core_s": per_core_1, "sim_s_per_wall_s": s1 / w1.max(1e-12)},
        "k_lanes": {"simulated_s": sk, "cpu_s": ck, "wall_s": wk,
                    "sim_s_per_core_s": per_core_k, "sim_s_per_wall_s": sk / wk.max(1e-12)},
        "per_core_speedup": per_core_k / per_core_1.max(1e-12),
        "wall_speedup": (sk / wk.max(1e-12)) / (s1 / w1.max(1e-12)).max(1e-12),
        "structure_of_arrays": false,
        "note": "K lanes = K scenarios on K threads; the K-lane structure-of-arrays stepping is not implemented, so per-core throughput cannot exceed one lane's",
    }))
}

/// `wearsim bench --lanes K`.
pub fn run(a: &BenchArgs, k: usize) -> Result<(), CliError> {
    let r = measure(a, k)?;
    if a.json {
        println!("{}", serde_json::to_string_pretty(&r).unwrap_or_default());
    } else {
        println!(
            "{}: 1 lane {:.1} simulated s per core-second; {k} lanes (threads) {:.1} per core-second ({:.2}x), {:.2}x wall-clock throughput on {} cores",
            a.preset,
            r["one_lane"]["sim_s_per_core_s"].as_f64().unwrap_or(0.0),
            r["k_lanes"]["sim_s_per_core_s"].as_f64().unwrap_or(0.0),
            r["per_core_speedup"].as_f64().unwrap_or(0.0),
            r["wall_speedup"].as_f64().unwrap_or(0.0),
            r["cores"]
        );
        println!(
            "note: K-lane structure-of-arrays stepping is not implemented (K lanes are K threads)"
        );
    }
    Ok(())
}
