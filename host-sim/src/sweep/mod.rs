//! Labelled data sets: a declarative sweep ([`spec`]) expanded into records ([`record`]),
//! simulated shard by shard into float32 `.npy` files ([`shard`]) with a Parquet index
//! ([`index`]). Deterministic (record `i`'s seed derives from the sweep seed and `i`),
//! resumable (complete shards are skipped), and shardable across processes (`--shard I/N`,
//! or one shard per task from Python/Dask); see docs/datasets.md.
//!
//! Data set layout: `sweep.json` (the spec, canonical), `shards/shard-NNNNN.npy` and
//! `shards/shard-NNNNN.done.json` (completion marker), and, once every shard is done,
//! `index.parquet` and `manifest.json` (`"complete": true`). A data set without
//! `manifest.json` is not complete.

pub mod batch;
pub mod index;
pub mod record;
pub mod shard;
pub mod spec;

pub use record::record_seed;
pub use spec::{SpecError, SweepSpec};

use std::path::Path;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};

/// Why a sweep stopped.
#[derive(Debug, thiserror::Error)]
pub enum SweepError {
    /// Bad spec, argument or output directory (exit code 2); the message names the field.
    #[error("{0}")]
    Input(String),
    /// The run failed (I/O while writing, a numerical failure; exit code 1).
    #[error("{0}")]
    Run(String),
    /// The caller's cancel flag was set ([`crate::cancel`]): the shards finished before
    /// are complete on disk, nothing else was presented as written; run again to resume.
    #[error(
        "the sweep was interrupted; the shards finished so far are kept, run it again to resume"
    )]
    Cancelled,
}

impl From<SpecError> for SweepError {
    fn from(e: SpecError) -> Self {
        SweepError::Input(e.to_string())
    }
}

const SPEC_FILE: &str = "sweep.json";
const MANIFEST: &str = "manifest.json";
const INDEX: &str = "index.parquet";

/// Checks that every grid cell resolves to a valid scenario (records `0 .. cells`, with
/// their drawn effects), and that every effect parameter's distribution stays inside what
/// each cell accepts at both ends of its range (one parameter at a time, its effect alone
/// on with its other parameters as drawn, so that another effect's draw is never blamed
/// on it), before anything is written: some bounds depend on the sample
/// rate or the bearing (a transfer-path mode below fs/2.5, a sensor corner below fs/2, a
/// preload the step resolves), which the spec check alone cannot know, and a draw beyond
/// one would stop the sweep part-way with its later records never regenerable.
pub fn validate(spec: &SweepSpec) -> Result<(), SweepError> {
    let cells = record::cells(spec);
    for i in 0..spec.records.min(cells.len()) {
        let rec = record::record(spec, &cells, i);
        // The cell with every effect off first: what it refuses is no distribution's doing.
        let mut bare = rec.clone();
        for fx in bare.effects.iter_mut() {
            fx.on = false;
        }
        shard::scenario_of(spec, &bare)?;
        for (j, spec_e) in spec.effect.iter().enumerate() {
            for (name, dist) in &spec_e.params {
                let mut alone = bare.clone();
                let Some(fx) = alone.effects.get_mut(j) else {
                    continue;
                };
                fx.on = true;
                for v in dist.ends() {
                    let mut r = alone.clone();
                    for (n, x) in r.effects[j].params.iter_mut() {
                        if n == name {
                            *x = v;
                        }
                    }
                    if let Err(e) = shard::scenario_of(spec, &r) {
                        // Blamed on this end when the error names this parameter
                        // (`sensor.corner_hz = …`) or the effect as drawn passes: a failing
                        // draw of one of its other parameters is that one's end to name
                        // (or, if none reaches it, the record's own error below).
                        let names_it = e.to_string().contains(&format!("{}.{name} =", spec_e.name));
                        if names_it || shard::scenario_of(spec, &alone).is_ok() {
                            return Err(SweepError::Input(format!(
                                "effect[{j}].params.{name} ({}): its distribution reaches {v}, which {e}; narrow the distribution",
                                spec_e.name
                            )));
                        }
                    }
                }
            }
        }
        // After the ends, so that a distribution reaching too far is named as such even
        // where this record's draw already does.
        shard::scenario_of(spec, &rec)?;
    }
    Ok(())
}

/// Makes `dir` this sweep's output directory: creates it with `sweep.json`, or accepts it
/// when it already holds the same spec; a directory holding another sweep, or anything
/// else, is refused (exit 2).
pub fn prepare_dir(spec: &SweepSpec, dir: &Path) -> Result<(), SweepError> {
    let spec_path = dir.join(SPEC_FILE);
    let text = serde_json::to_string_pretty(spec).map_err(|e| SweepError::Run(e.to_string()))?;
    if spec_path.exists() {
        return holds_this_spec(spec, dir).and_then(|()| check_writable(dir));
    }
    if dir.exists() {
        // What a run starting at the same moment into the same new directory has made so
        // far (an empty `shards`, the spec or its temporary file) does not make it busy: the
        // spec is compared below.
        let starting = |name: &str| {
            name == "shards"
                && dir
                    .join(name)
                    .read_dir()
                    .is_ok_and(|mut d| d.next().is_none())
                || name == SPEC_FILE
                || name.starts_with(&format!(".{SPEC_FILE}.tmp-"))
        };
        let busy = std::fs::read_dir(dir)
            .map_err(|e| SweepError::Input(format!("--out {}: {e}", dir.display())))?
            .flatten()
            .any(|e| !starting(&e.file_name().to_string_lossy()));
        // A spec that appeared meanwhile is compared below: what made the directory busy
        // may be its run's first files (its write check in `shards`).
        if busy && !spec_path.exists() {
            return Err(SweepError::Input(format!(
                "--out {}: the directory is not empty and holds no sweep; choose an empty or new directory",
                dir.display()
            )));
        }
    }
    std::fs::create_dir_all(dir.join("shards"))
        .map_err(|e| SweepError::Input(format!("--out {}: {e}", dir.display())))?;
    // Two runs started together into one new directory both find it empty: only one
    // `sweep.json` is created, the other run then compares it with its own spec (stop 68:
    // two different specs raced in were both accepted and left one data set of both).
    if !shard::create_atomic(&spec_path, text.as_bytes())? {
        holds_this_spec(spec, dir)?;
    }
    check_writable(dir)
}

/// Whether `dir`'s `sweep.json` is this spec; another sweep's is refused (exit 2).
fn holds_this_spec(spec: &SweepSpec, dir: &Path) -> Result<(), SweepError> {
    let old = crate::config::read_config_text(&dir.join(SPEC_FILE))
        .map_err(|e| SweepError::Input(format!("--out {}: {e}", dir.display())))?;
    if serde_json::from_str::<SweepSpec>(&old).is_ok_and(|o| &o == spec) {
        Ok(())
    } else {
        Err(SweepError::Input(format!(
            "--out {}: the directory holds another sweep (its sweep.json differs from this spec); choose another output directory",
            dir.display()
        )))
    }
}

/// Creates `dir/shards` if missing and checks that this run can write there.
fn check_writable(dir: &Path) -> Result<(), SweepError> {
    std::fs::create_dir_all(dir.join("shards"))
        .map_err(|e| SweepError::Input(format!("--out {}: {e}", dir.display())))?;
    // A data set being resumed may sit in a directory this run cannot write (read-only
    // mount, another user's): say so before simulating anything, as bad input.
    crate::io::perms::output_builder()
        .prefix(".write-check.")
        .tempfile_in(dir.join("shards"))
        .map_err(|e| {
            SweepError::Input(format!(
                "--out {}: the directory cannot be written ({e}); choose a writable output directory",
                dir.display()
            ))
        })?;
    Ok(())
}

/// The shards of `--shard I/N` (0-based `I` of `N`): shards `s` with `s mod N == I`.
pub fn shard_set(spec: &SweepSpec, part: Option<(u64, u64)>) -> Vec<u64> {
    match part {
        None => (0..spec.shards()).collect(),
        Some((i, n)) => (0..spec.shards()).filter(|s| s % n == i).collect(),
    }
}

/// What a sweep run did.
#[derive(Debug, Clone, serde::Serialize)]
pub struct SweepReport {
    /// Records simulated by this run.
    pub records_generated: u64,
    /// Shards written by this run.
    pub shards_written: u64,
    /// Shards skipped because already complete.
    pub shards_skipped: u64,
    /// Every shard of the sweep is complete (index and manifest written).
    pub complete: bool,
    /// Simulated seconds of recorded signal generated by this run.
    pub simulated_s: f64,
    /// Wall-clock time (s).
    pub wall_s: f64,
    /// Worker threads.
    pub threads: usize,
    /// Bytes of the data set (shards + index) when complete.
    pub bytes: u64,
}

/// Generates `shards` of `spec` into `dir` on `threads` threads (complete shards are
/// skipped), calling `progress(done, total)` after each shard; then finalises the data
/// set if every shard is complete. Once the thread's cancel flag is set
/// ([`crate::cancel`]) each thread finishes the batch of shards it is on (at most
/// [`batch::MAX_BATCH_SHARDS`] shards, written complete with their markers), takes no
/// other, and the run returns [`SweepError::Cancelled`] without writing the index or the
/// manifest; a later run resumes from the complete shards. An embedding such as the Python
/// package sets the flag from another thread when the user interrupts.
pub fn run(
    spec: &SweepSpec,
    dir: &Path,
    shards: &[u64],
    threads: usize,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<SweepReport, SweepError> {
    validate(spec)?;
    prepare_dir(spec, dir)?;
    let t0 = std::time::Instant::now();
    let next = AtomicUsize::new(0);
    let done = AtomicUsize::new(0);
    let generated = AtomicU64::new(0);
    let written = AtomicU64::new(0);
    let threads = threads.clamp(1, shards.len().max(1));
    let per_batch = batch::batch_len(spec, shards.len(), threads);
    let first_err: std::sync::Mutex<Option<SweepError>> = std::sync::Mutex::new(None);
    std::thread::scope(|sc| {
        for _ in 0..threads {
            let worker = crate::lanes::spawn_worker(sc, || loop {
                if crate::cancel::requested()
                    || first_err.lock().map(|e| e.is_some()).unwrap_or(true)
                {
                    return;
                }
                // A few shards at a time, their records pooled into lane groups.
                let k = next.fetch_add(per_batch, Ordering::Relaxed);
                let Some(b) = shards.get(k..(k + per_batch).min(shards.len())) else {
                    return;
                };
                let r = batch::run_batch(spec, dir, b, |_, n| {
                    generated.fetch_add(n, Ordering::Relaxed);
                    if n > 0 {
                        written.fetch_add(1, Ordering::Relaxed);
                    }
                    let d = done.fetch_add(1, Ordering::Relaxed) + 1;
                    progress(d, shards.len());
                });
                if let Err(e) = r {
                    if let Ok(mut g) = first_err.lock() {
                        g.get_or_insert(e);
                    }
                    return;
                }
            });
            if let Err(e) = worker {
                if let Ok(mut g) = first_err.lock() {
                    g.get_or_insert(SweepError::Run(format!(
                        "cannot start a worker thread: {e}"
                    )));
                }
            }
        }
    });
    if let Some(e) = first_err.into_inner().ok().flatten() {
        return Err(e);
    }
    if crate::cancel::requested() {
        return Err(SweepError::Cancelled);
    }
    let gen = generated.into_inner();
    let wr = written.into_inner();
    let (complete, bytes) = finalize(spec, dir)?;
    Ok(SweepReport {
        records_generated: gen,
        shards_written: wr,
        shards_skipped: shards.len() as u64 - wr,
        complete,
        simulated_s: gen as f64 * spec.duration,
        wall_s: t0.elapsed().as_secs_f64(),
        threads,
        bytes,
    })
}

/// Writes the index of `spec` to `path` through a temporary file and a rename (row group
/// by row group, [`index::write_parquet`]); returns its size in bytes.
fn write_index(spec: &SweepSpec, path: &Path) -> Result<u64, SweepError> {
    let tmp = shard::tmp_path(path);
    let io = |e: std::io::Error| SweepError::Run(format!("cannot write {}: {e}", path.display()));
    let written = std::fs::File::create(&tmp).map_err(io).and_then(|f| {
        let mut out = std::io::BufWriter::new(f);
        index::write_parquet(spec, &mut out)?;
        std::io::Write::flush(&mut out).map_err(io)?;
        Ok(())
    });
    if let Err(e) = written {
        let _ = std::fs::remove_file(&tmp);
        return Err(e);
    }
    std::fs::rename(&tmp, path).map_err(io)?;
    Ok(std::fs::metadata(path).map(|m| m.len()).unwrap_or(0))
}

/// When every shard is complete, writes `index.parquet` and then `manifest.json` (each
/// through a temporary file and a rename); returns whether the set is complete and its
/// size in bytes.
pub fn finalize(spec: &SweepSpec, dir: &Path) -> Result<(bool, u64), SweepError> {
    if !(0..spec.shards()).all(|s| shard::is_done(dir, s)) {
        return Ok((false, 0));
    }
    let mut bytes = write_index(spec, &dir.join(INDEX))?;
    for s in 0..spec.shards() {
        bytes += std::fs::metadata(dir.join("shards").join(shard::npy_name(s)))
            .map(|m| m.len())
            .unwrap_or(0);
    }
    let manifest = serde_json::json!({
        "complete": true,
        "records": spec.records,
        "shards": spec.shards(),
        "records_per_shard": spec.per_shard(),
        "samples_per_record": spec.samples(),
        "fs": spec.fs,
        "signal": "acceleration (m/s^2), float32, shards/shard-NNNNN.npy shape [records, samples]",
        "index": INDEX,
        "bytes": bytes,
        "bytes_per_record": bytes as f64 / spec.records as f64,
        "wearsim_version": crate::VERSION,
    });
    shard::write_atomic(
        &dir.join(MANIFEST),
        serde_json::to_string_pretty(&manifest)
            .unwrap_or_default()
            .as_bytes(),
    )?;
    Ok((true, bytes))
}

/// A sweep spec for the module's tests: `head` (seed, records, records per shard,
/// duration), 12 kHz, the grid the tests share (the 6205 at 1797 rpm, inner and outer
/// race, large defects), then `tail` (effects).
#[cfg(test)]
pub(crate) fn test_spec(head: &str, tail: &str) -> SweepSpec {
    let text = format!(
        "{head}\nfs = 12000.0\n\n[grid]\npreset = [\"cwru-6205-de\"]\nrpm = [1797.0]\nfault = [\"inner\", \"outer\"]\nstage = [\"large-defect\"]\n{tail}"
    );
    SweepSpec::parse(&text, "test").expect("test spec")
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicBool;
    use std::sync::Arc;

    /// Runs of two different specs started together into one new directory: whichever
    /// creates `sweep.json` first owns it, every run of the other spec is refused, every run
    /// of the same spec is accepted (stop 68: both were accepted in 6 of 20 races of two
    /// processes, leaving shards of both under one spec marked complete).
    #[test]
    fn runs_of_two_specs_racing_into_a_new_directory_leave_one_spec() {
        let a = test_spec("seed = 1\nrecords = 4\nduration = 0.02", "");
        let b = test_spec("seed = 2\nrecords = 4\nduration = 0.02", "");
        for round in 0..20 {
            let root = tempfile::tempdir().expect("tmp");
            let dir = root.path().join("set");
            let barrier = std::sync::Barrier::new(8);
            let results: Vec<(bool, bool)> = std::thread::scope(|sc| {
                let handles: Vec<_> = (0..8)
                    .map(|t| {
                        let (spec, dir, barrier) =
                            (if t % 2 == 0 { &a } else { &b }, &dir, &barrier);
                        sc.spawn(move || {
                            barrier.wait();
                            (t % 2 == 0, prepare_dir(spec, dir).is_ok())
                        })
                    })
                    .collect();
                handles
                    .into_iter()
                    .map(|h| h.join().expect("thread"))
                    .collect()
            });
            let text = std::fs::read_to_string(dir.join(SPEC_FILE)).expect("sweep.json");
            let owner: SweepSpec = serde_json::from_str(&text).expect("complete spec");
            let owner_is_a = owner == a;
            assert!(owner_is_a || owner == b, "round {round}");
            for (is_a, ok) in results {
                assert_eq!(
                    ok,
                    is_a == owner_is_a,
                    "round {round}: spec a {is_a}, accepted {ok}"
                );
            }
        }
    }

    /// A cancelled run keeps the batch it was on (complete shards with their markers),
    /// takes no other, writes neither index nor manifest, and a later run resumes from the
    /// complete shards; a flag set before the run writes no shard at all.
    #[test]
    fn a_cancelled_sweep_keeps_finished_shards_and_resumes() {
        let spec = test_spec(
            "seed = 5\nrecords = 40\nrecords_per_shard = 2\nduration = 0.02",
            "",
        );
        let dir = tempfile::tempdir().expect("tmp");
        let shards = shard_set(&spec, None);
        let done = |d: &Path| (0..spec.shards()).filter(|&s| shard::is_done(d, s)).count();
        let set = Arc::new(AtomicBool::new(true));
        let err = crate::cancel::scope(set, || run(&spec, dir.path(), &shards, 1, &|_, _| {}))
            .expect_err("cancelled before it starts");
        assert!(matches!(err, SweepError::Cancelled), "{err}");
        assert_eq!(done(dir.path()), 0);
        // Cancelled after the first shard: the rest of its batch is written, nothing more.
        let cancel = Arc::new(AtomicBool::new(false));
        let err = crate::cancel::scope(cancel.clone(), || {
            let stop = |_, _| cancel.store(true, Ordering::Relaxed);
            run(&spec, dir.path(), &shards, 1, &stop)
        })
        .expect_err("cancelled after the first shard");
        assert!(matches!(err, SweepError::Cancelled), "{err}");
        let per_batch = batch::batch_len(&spec, shards.len(), 1);
        assert_eq!(done(dir.path()), per_batch);
        assert!(per_batch < shards.len());
        assert!(!dir.path().join(MANIFEST).exists() && !dir.path().join(INDEX).exists());
        let r = run(&spec, dir.path(), &shards, 1, &|_, _| {}).expect("resumed");
        assert!(r.complete);
        assert_eq!(r.shards_skipped, per_batch as u64);
        assert_eq!(done(dir.path()), shards.len());
    }
}
