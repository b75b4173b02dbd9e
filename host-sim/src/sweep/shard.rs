//! One shard of a sweep: its records simulated in order and written as a float32 `.npy`
//! array `[records, samples]` (acceleration, m/s²) under a temporary name, renamed into
//! place, then marked done by a small JSON marker (also written and renamed), so that a
//! shard is either absent or complete, never half-written.

use super::record::{cells, record, Cells};
use super::spec::SweepSpec;
use super::SweepError;
use crate::simulate::{self, Scenario};
use npyz::WriterBuilder;
use std::path::{Path, PathBuf};

/// File name of shard `s`'s signals.
pub fn npy_name(s: u64) -> String {
    format!("shard-{s:05}.npy")
}

/// File name of shard `s`'s completion marker.
pub fn done_name(s: u64) -> String {
    format!("shard-{s:05}.done.json")
}

/// The records of shard `s`: `[first, end)`.
pub fn range(spec: &SweepSpec, s: u64) -> (u64, u64) {
    let first = s * spec.per_shard();
    (first, (first + spec.per_shard()).min(spec.records))
}

/// True when shard `s` is complete in `dir` (marker and signals both present, and the
/// signals as long as the marker says).
pub fn is_done(dir: &Path, s: u64) -> bool {
    let marker = dir.join("shards").join(done_name(s));
    let Ok(text) = std::fs::read_to_string(&marker) else {
        return false;
    };
    let Ok(v) = serde_json::from_str::<serde_json::Value>(&text) else {
        return false;
    };
    let want = v.get("bytes").and_then(|b| b.as_u64());
    let have = std::fs::metadata(dir.join("shards").join(npy_name(s)))
        .ok()
        .map(|m| m.len());
    want.is_some() && want == have
}

/// The validated scenario of one record.
pub fn scenario(spec: &SweepSpec, cells: &Cells, i: u64) -> Result<Scenario, SweepError> {
    scenario_of(spec, &record(spec, cells, i))
}

/// The scenario of record `rec` (as drawn, or altered as the spec's validation alters it);
/// an error names the record and its grid cell.
pub fn scenario_of(spec: &SweepSpec, rec: &super::record::Record) -> Result<Scenario, SweepError> {
    let i = rec.index;
    let (cfg, run) = rec
        .scenario_file(spec)
        .resolve()
        .map_err(|e| SweepError::Input(format!("record {i} (grid cell {}): {e}", rec.cell)))?;
    Scenario::new(cfg, run)
        .map_err(|e| SweepError::Input(format!("record {i} (grid cell {}): {e}", rec.cell)))
}

/// Simulates record `i`, returning its acceleration as float32.
pub fn simulate_record(spec: &SweepSpec, cells: &Cells, i: u64) -> Result<Vec<f32>, SweepError> {
    let sc = scenario(spec, cells, i)?;
    let out =
        simulate::run(&sc, |_, _| {}).map_err(|e| SweepError::Run(format!("record {i}: {e}")))?;
    Ok(out.accel.iter().map(|&x| x as f32).collect())
}

/// Simulates records `first..end` in order, as [`simulate_record`] would one by one
/// (the same bits: records whose models can share the kinematics run as lanes of
/// [`crate::lanes::run_accel`]). The first failure in record order is returned, as the
/// one-by-one loop would meet it.
pub fn simulate_records(
    spec: &SweepSpec,
    cells: &Cells,
    first: u64,
    end: u64,
) -> Result<Vec<Vec<f32>>, SweepError> {
    let mut scs = Vec::new();
    let mut bad = None;
    for i in first..end {
        match scenario(spec, cells, i) {
            Ok(sc) => scs.push(sc),
            Err(e) => {
                bad = Some(e);
                break;
            }
        }
    }
    let mut out = Vec::with_capacity(scs.len());
    for (i, r) in (first..).zip(crate::lanes::run_accel(&scs)) {
        let a = r.map_err(|e| SweepError::Run(format!("record {i}: {e}")))?;
        out.push(a.iter().map(|&x| x as f32).collect());
    }
    match bad {
        Some(e) => Err(e),
        None => Ok(out),
    }
}

pub(super) fn tmp_path(final_path: &Path) -> PathBuf {
    let name = final_path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    final_path.with_file_name(format!(".{name}.tmp-{}", std::process::id()))
}

/// Writes `bytes` to `path` through a temporary file in the same folder and a rename.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), SweepError> {
    let tmp = tmp_path(path);
    std::fs::write(&tmp, bytes)
        .and_then(|_| std::fs::rename(&tmp, path))
        .map_err(|e| SweepError::Run(format!("cannot write {}: {e}", path.display())))
}

/// Creates `path` holding `bytes` unless a file of that name exists, with the name
/// appearing only once the content is complete: a temporary file in the same folder, then a
/// hard link to the name, which fails if the name exists (on a file system without hard
/// links, an exclusive create). Returns `false` when `path` already existed (nothing
/// written).
pub fn create_atomic(path: &Path, bytes: &[u8]) -> Result<bool, SweepError> {
    use std::io::{ErrorKind, Write};
    let err = |e: std::io::Error| SweepError::Run(format!("cannot write {}: {e}", path.display()));
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
    let prefix = format!(".{}.tmp-", name.unwrap_or_default());
    // A name of its own per call (two threads of one process may race too); removed on drop.
    let mut tmp = crate::io::perms::output_builder()
        .prefix(&prefix)
        .tempfile_in(path.parent().unwrap_or(Path::new(".")))
        .map_err(err)?;
    tmp.write_all(bytes).map_err(err)?;
    match std::fs::hard_link(tmp.path(), path) {
        Ok(()) => Ok(true),
        Err(e) if e.kind() == ErrorKind::AlreadyExists => Ok(false),
        Err(_) => match std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(path)
        {
            Ok(mut f) => f.write_all(bytes).map(|()| true).map_err(err),
            Err(e) if e.kind() == ErrorKind::AlreadyExists => Ok(false),
            Err(e) => Err(err(e)),
        },
    }
}

/// Removes temporary files of shard `s` left by an interrupted run (only this shard's:
/// the process generating a shard owns its temporaries).
pub(super) fn remove_stale_temps(dir: &Path, s: u64) {
    let prefixes = [
        format!(".{}.tmp-", npy_name(s)),
        format!(".{}.tmp-", done_name(s)),
    ];
    if let Ok(rd) = std::fs::read_dir(dir.join("shards")) {
        for e in rd.flatten() {
            let name = e.file_name().to_string_lossy().into_owned();
            if prefixes.iter().any(|p| name.starts_with(p.as_str())) {
                let _ = std::fs::remove_file(e.path());
            }
        }
    }
}

/// Generates shard `s` of `spec` into `dir/shards/` unless it is already complete;
/// returns the number of records generated (0 when skipped).
pub fn run_shard(spec: &SweepSpec, dir: &Path, s: u64) -> Result<u64, SweepError> {
    check_exists(spec, s)?;
    if is_done(dir, s) {
        return Ok(0);
    }
    remove_stale_temps(dir, s);
    let cells = cells(spec);
    let (first, end) = range(spec, s);
    write_shard(spec, dir, s, simulate_records(spec, &cells, first, end)?)
}

/// An error naming the sweep's shards unless shard `s` is one of them.
pub(super) fn check_exists(spec: &SweepSpec, s: u64) -> Result<(), SweepError> {
    if s >= spec.shards() {
        return Err(SweepError::Input(format!(
            "shard {s} does not exist: the sweep has {} shards (0..={})",
            spec.shards(),
            spec.shards() - 1
        )));
    }
    Ok(())
}

/// Writes shard `s` from its records' signals `records` (in record order): the signals
/// and then the marker, each through a temporary file and a rename; returns the number of
/// records written.
pub(super) fn write_shard(
    spec: &SweepSpec,
    dir: &Path,
    s: u64,
    records: Vec<Vec<f32>>,
) -> Result<u64, SweepError> {
    let (first, end) = range(spec, s);
    let n = spec.samples();
    if records.len() as u64 != end - first {
        return Err(SweepError::Run(format!(
            "shard {s}: {} records, expected {}",
            records.len(),
            end - first
        )));
    }
    let mut data: Vec<f32> = Vec::with_capacity((end - first) as usize * n);
    for (i, x) in (first..end).zip(records) {
        if x.len() != n {
            return Err(SweepError::Run(format!(
                "record {i}: {} samples, expected {n}",
                x.len()
            )));
        }
        data.extend_from_slice(&x);
    }
    let mut buf = Vec::with_capacity(data.len() * 4 + 128);
    {
        let shape = [end - first, n as u64];
        let io = |e: std::io::Error| SweepError::Run(format!("shard {s}: {e}"));
        let mut w = npyz::WriteOptions::new()
            .default_dtype()
            .shape(&shape)
            .writer(&mut buf)
            .begin_nd()
            .map_err(io)?;
        w.extend(data.iter().copied()).map_err(io)?;
        w.finish().map_err(io)?;
    }
    let shards = dir.join("shards");
    write_atomic(&shards.join(npy_name(s)), &buf)?;
    let marker = serde_json::json!({
        "shard": s,
        "first_record": first,
        "records": end - first,
        "samples_per_record": n,
        "bytes": buf.len(),
    });
    write_atomic(
        &shards.join(done_name(s)),
        serde_json::to_string_pretty(&marker)
            .unwrap_or_default()
            .as_bytes(),
    )?;
    Ok(end - first)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::record::cells;

    /// Records run as lanes give the bytes of records run one by one (ten records, two
    /// faults alternating: two lane groups of 4 and two records alone; seeds and a
    /// per-record sensor effect differ within a group).
    #[test]
    fn laned_records_equal_records_run_alone() {
        let spec = crate::sweep::test_spec(
            "seed = 11\nrecords = 10\nrecords_per_shard = 10\nduration = 0.05",
            r#"
[[effect]]
name = "sensor"
probability = 0.5
params = { noise = { uniform = [0.01, 0.2] } }
"#,
        );
        let cells = cells(&spec);
        let a = scenario(&spec, &cells, 0).expect("record 0");
        let b = scenario(&spec, &cells, 2).expect("record 2");
        assert!(
            crate::lanes::can_share(&a, &b) != crate::lanes::Sharing::No,
            "records 0 and 2 should share lanes: {:?}",
            wearsim_core::model::lanes::shareable(&a.model, &b.model, 1)
        );
        assert_laned_equal_alone(&spec, 10);
    }

    /// Simulates records `0..n` of `spec` together and one by one; asserts the bits agree.
    fn assert_laned_equal_alone(spec: &SweepSpec, n: u64) {
        let cells = cells(spec);
        let laned = simulate_records(spec, &cells, 0, n).expect("laned");
        assert_eq!(laned.len() as u64, n);
        for (i, x) in laned.iter().enumerate() {
            let alone = simulate_record(spec, &cells, i as u64).expect("alone");
            assert_eq!(x.len(), 600);
            assert!(
                x.iter()
                    .zip(&alone)
                    .all(|(p, q)| p.to_bits() == q.to_bits()),
                "record {i} differs between lanes and alone"
            );
        }
    }

    /// Records that each carry their own speed fluctuation (every record at its own varying
    /// speed) pool in a lane group at their own speeds and give the bytes of records run one
    /// by one (twenty records, two faults alternating: per fault one group of 8 and two
    /// records alone).
    #[test]
    fn records_at_their_own_varying_speed_pool_and_equal_records_run_alone() {
        let spec = crate::sweep::test_spec(
            "seed = 13\nrecords = 20\nrecords_per_shard = 20\nduration = 0.05",
            r#"
[[effect]]
name = "speed-fluctuation"
probability = 1.0
params = { amplitude = { uniform = [0.001, 0.01] }, jitter = { uniform = [0.0, 0.01] } }
"#,
        );
        let cells = cells(&spec);
        let scs: Vec<_> = (0..20)
            .map(|i| scenario(&spec, &cells, i).expect("record"))
            .collect();
        let share = |a: usize, b: usize| crate::lanes::can_share(&scs[a], &scs[b]);
        assert_eq!(share(0, 2), crate::lanes::Sharing::OwnSpeed);
        let plan = crate::lanes::plan(scs.len(), share);
        assert!(
            plan.iter().any(|(k, g)| *k == 8 && g.len() == 8),
            "no group of 8 at their own speeds: {plan:?}"
        );
        assert_laned_equal_alone(&spec, 20);
    }
}
