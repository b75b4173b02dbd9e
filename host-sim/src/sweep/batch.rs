//! Several shards simulated together: their records pooled before they are grouped into
//! lane groups ([`crate::lanes::run_accel`]), so that records of one grid cell spread over
//! a few shards fill groups of 16 instead of leaving a small remainder group in every
//! shard (a 250-record shard of a 16-cell grid holds ~16 records per cell). The shards are
//! then written one by one in order, as [`shard::run_shard`] would write them: the same
//! bytes, and the same first error.

use super::record::cells;
use super::shard;
use super::spec::SweepSpec;
use super::SweepError;
use std::path::Path;

/// Output samples a batch may hold in memory (f64 while simulating, ~32 MiB): batches are
/// as many shards as fit, at least one.
pub const BATCH_SAMPLES: usize = 1 << 22;

/// Most shards in one batch: a batch's shards are written together at its end, so this
/// bounds what an interruption loses (per thread) and how far progress lags.
pub const MAX_BATCH_SHARDS: usize = 4;

/// Shards per batch for `shards` shards on `threads` threads: [`MAX_BATCH_SHARDS`], but no
/// more than fit in [`BATCH_SAMPLES`] or than an even share per thread (so that every
/// thread has work), at least one.
pub fn batch_len(spec: &SweepSpec, shards: usize, threads: usize) -> usize {
    let shard_samples = (spec.per_shard() as usize)
        .saturating_mul(spec.samples())
        .max(1);
    let fit = (BATCH_SAMPLES / shard_samples).clamp(1, MAX_BATCH_SHARDS);
    shards.div_ceil(threads.max(1)).clamp(1, fit)
}

/// Generates the shards `batch` of `spec` into `dir/shards/` (complete ones skipped),
/// calling `done(s, records)` after each shard in order (records = 0 when skipped). On
/// the first failure in record order the shards before it are written and its error is
/// returned, as one [`shard::run_shard`] call per shard would do.
pub fn run_batch(
    spec: &SweepSpec,
    dir: &Path,
    batch: &[u64],
    mut done: impl FnMut(u64, u64),
) -> Result<(), SweepError> {
    // The shards to generate, up to the first that does not exist.
    let mut todo = Vec::new();
    let mut missing = None;
    for &s in batch {
        if let Err(e) = shard::check_exists(spec, s) {
            missing = Some(e);
            break;
        }
        todo.push(s);
    }
    let cells = cells(spec);
    // Every record's scenario, up to the first that fails to build.
    let mut scs = Vec::new();
    let mut bad = None;
    // Whether each shard is generated, decided once (another process may complete one
    // meanwhile: its records are simulated here all the same).
    let todo: Vec<(u64, bool)> = todo
        .into_iter()
        .map(|s| (s, !shard::is_done(dir, s)))
        .collect();
    'shards: for &(s, generate) in &todo {
        if !generate {
            continue;
        }
        shard::remove_stale_temps(dir, s);
        let (first, end) = shard::range(spec, s);
        for i in first..end {
            match shard::scenario(spec, &cells, i) {
                Ok(sc) => scs.push(sc),
                Err(e) => {
                    bad = Some(e);
                    break 'shards;
                }
            }
        }
    }
    let mut results = crate::lanes::run_accel(&scs).into_iter();
    for &(s, generate) in &todo {
        if !generate {
            done(s, 0);
            continue;
        }
        let (first, end) = shard::range(spec, s);
        let mut records = Vec::with_capacity((end - first) as usize);
        for i in first..end {
            match results.next() {
                Some(Ok(a)) => records.push(a.iter().map(|&x| x as f32).collect()),
                Some(Err(e)) => return Err(SweepError::Run(format!("record {i}: {e}"))),
                // The scenarios stopped at a record that failed to build.
                None => {
                    return Err(bad
                        .unwrap_or_else(|| SweepError::Run(format!("record {i}: not simulated"))))
                }
            }
        }
        let n = shard::write_shard(spec, dir, s, records)?;
        done(s, n);
    }
    match missing {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec() -> SweepSpec {
        crate::sweep::test_spec(
            "seed = 5\nrecords = 12\nrecords_per_shard = 4\nduration = 0.05",
            r#"
[[effect]]
name = "sensor"
probability = 0.5
params = { noise = { uniform = [0.01, 0.2] }, hum = { uniform = [0.0, 0.05] } }
"#,
        )
    }

    /// Three shards pooled into one batch (records of one cell spread over the shards
    /// share lane groups) write the bytes of the shards generated one by one; a shard
    /// already complete is skipped and reported with 0 records.
    #[test]
    fn a_batch_writes_the_shards_run_one_by_one() {
        let spec = spec();
        let one = tempfile::tempdir().expect("tmp");
        let many = tempfile::tempdir().expect("tmp");
        for d in [one.path(), many.path()] {
            crate::sweep::prepare_dir(&spec, d).expect("dir");
        }
        for s in 0..3 {
            assert_eq!(shard::run_shard(&spec, one.path(), s).expect("shard"), 4);
        }
        assert_eq!(shard::run_shard(&spec, many.path(), 1).expect("shard"), 4);
        let mut seen = Vec::new();
        run_batch(&spec, many.path(), &[0, 1, 2], |s, n| seen.push((s, n))).expect("batch");
        assert_eq!(seen, [(0, 4), (1, 0), (2, 4)]);
        for s in 0..3 {
            let name = shard::npy_name(s);
            let a = std::fs::read(one.path().join("shards").join(&name)).expect("one");
            let b = std::fs::read(many.path().join("shards").join(&name)).expect("many");
            assert!(a == b, "shard {s} differs between a batch and one by one");
        }
    }

    /// A shard that does not exist ends the batch with its error after the shards before
    /// it are written.
    #[test]
    fn a_missing_shard_ends_the_batch_after_the_ones_before() {
        let spec = spec();
        let dir = tempfile::tempdir().expect("tmp");
        crate::sweep::prepare_dir(&spec, dir.path()).expect("dir");
        let mut seen = Vec::new();
        let err = run_batch(&spec, dir.path(), &[2, 7], |s, n| seen.push((s, n)))
            .expect_err("shard 7 does not exist");
        assert!(err.to_string().contains("shard 7 does not exist"), "{err}");
        assert_eq!(seen, [(2, 4)]);
        assert!(shard::is_done(dir.path(), 2));
    }

    /// Batches: an even share of the shards per thread, capped by the memory budget and
    /// the shard count.
    #[test]
    fn batch_length_follows_threads_and_budget() {
        let spec = spec(); // 4 records of 600 samples per shard
        assert_eq!(batch_len(&spec, 3, 1), 3);
        assert_eq!(batch_len(&spec, 10, 3), 4);
        assert_eq!(batch_len(&spec, 40, 1), MAX_BATCH_SHARDS);
        assert_eq!(batch_len(&spec, 0, 2), 1);
        let big = SweepSpec {
            duration: 100.0,
            fs: 48_000.0,
            ..spec
        };
        // 4 × 4.8 M samples per shard exceed the budget: one shard per batch.
        assert_eq!(batch_len(&big, 10, 1), 1);
    }
}
