//! Dense mode: the continuous vibration of the whole life, streamed to disk in chunks with
//! bounded memory, resumable after an interruption without losing or duplicating samples.
//!
//! Files in the output directory:
//! * `life-dense.f32`: raw little-endian 32-bit float acceleration (m/s²) at `fs`;
//! * `life-dense.json`: manifest — format, fs, samples written, revolutions, the blocks
//!   (sample offset, revolutions, stage, topography) and `"complete"`, which is `true`
//!   only once the life reached failure;
//! * `life-dense.ckpt`: checkpoint (JSON header + the core's encoded dynamic state),
//!   written every [`CHECKPOINT_SAMPLES`] samples and at every block end; removed when
//!   the run completes. It carries the first samples of the interrupted block's window (so
//!   the block's snapshot is not lost) and ends in an FNV-1a 64 checksum of everything
//!   before it: a corrupt checkpoint is refused, never continued.
//!
//! The wear is advanced block by block from the same measurement windows as snapshot mode
//! ([`LifeRun::window`] with the same state and index), so both modes give the same wear
//! history; the dense stream of a block is simulated with the block's starting wear state.
//! A rerun with the same arguments continues from the checkpoint: the data file is cut
//! back to the checkpoint's sample count, the state restored, and the block redone from
//! its recorded start (deterministic), skipping the samples already written.
//!
//! Every invocation first removes the old completion marker (`life-summary.json`) and
//! marks the manifest incomplete, before the data file is touched, so a set is never
//! presented as complete while its data are being rewritten. Exclusive use of the
//! directory is the caller's job (`crate::io::lock::DirLock`).

use super::state_json::LifeStateJson;
use super::{LifeError, LifeRun, Snapshot, CAPACITY};
use serde::{Deserialize, Serialize};
use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use wearsim_core::checkpoint::encoded_len;
use wearsim_core::wear::Stage;
use wearsim_core::{Sample, State};

/// Samples between checkpoints (2²⁰ ≈ 52 s at 20 kHz).
pub const CHECKPOINT_SAMPLES: u64 = 1 << 20;
/// Samples per write.
const CHUNK: usize = 1 << 16;
/// Environment variable that overrides [`CHECKPOINT_SAMPLES`] (1 ..= 2³⁰; also caps the
/// samples per write): the fault-injection tests use it to put checkpoints in the middle
/// of blocks.
pub const CHECKPOINT_ENV: &str = "WEARSIM_CHECKPOINT_SAMPLES";

fn checkpoint_every() -> u64 {
    std::env::var(CHECKPOINT_ENV)
        .ok()
        .and_then(|v| v.parse::<u64>().ok())
        .filter(|n| (1..=1 << 30).contains(n))
        .unwrap_or(CHECKPOINT_SAMPLES)
}
/// Version 2: the window of the interrupted block and a trailing checksum. Version 3:
/// the wear state's surface-damage sum and its two surface scatter factors (stop 33); a
/// version-2 checkpoint holds a state of the older wear model and is refused as such.
const MAGIC: &[u8; 8] = b"WSLDCK3\n";

/// FNV-1a 64-bit hash (checkpoint checksum, configuration hash).
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
        (h ^ u64::from(*b)).wrapping_mul(0x0100_0000_01b3)
    })
}

/// Dense-mode options.
#[derive(Debug, Clone)]
pub struct DenseOptions {
    /// Output directory.
    pub dir: PathBuf,
    /// Stop after this many simulated seconds in this invocation, leaving a checkpoint
    /// (for runs split over several sessions; also used by the tests); 1/fs ..= 1e9 s.
    pub stop_after: Option<f64>,
}

/// One block of the dense stream.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct BlockRecord {
    /// Block index.
    pub block: u64,
    /// First sample of the block in the data file.
    pub first_sample: u64,
    /// Revolutions at the block start.
    pub cycles: f64,
    /// Stage during the block.
    pub stage: String,
    /// Asperity height (m) during the block.
    pub asperity: f64,
    /// Defect length (m) during the block.
    pub length: f64,
}

/// Checkpoint header.
#[derive(Debug, Clone, Serialize, Deserialize)]
struct Checkpoint {
    fingerprint: String,
    block: u64,
    block_start: LifeStateJson,
    samples_total: u64,
    samples_in_block: u64,
    carry: f64,
    snapshots: Vec<Snapshot>,
    blocks: Vec<BlockRecord>,
    /// The first samples (up to the window length) of the current block, from which its
    /// snapshot is computed (m/s², exact f64).
    window: Vec<f64>,
}

/// The manifest.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Manifest {
    /// `"wearsim-dense-f32le"`.
    pub format: String,
    /// Output rate (Hz).
    pub fs: f64,
    /// Unit of the samples.
    pub unit: String,
    /// Samples in the data file that belong to the run.
    pub samples: u64,
    /// Revolutions covered.
    pub cycles: f64,
    /// Whether the whole life (to failure) is in the file.
    pub complete: bool,
    /// Blocks.
    pub blocks: Vec<BlockRecord>,
    /// Seed.
    pub seed: u64,
    /// FNV-1a 64 of the run's configuration fingerprint (hex): the manifest, the data
    /// file and the checkpoint belong to one run.
    #[serde(default)]
    pub config_hash: String,
}

/// Result of a dense invocation.
#[derive(Debug, Clone)]
pub struct DenseReport {
    /// Samples in the file.
    pub samples: u64,
    /// Samples generated in this invocation.
    pub generated: u64,
    /// Whether the life is complete.
    pub complete: bool,
    /// Whether this invocation resumed a checkpoint.
    pub resumed: bool,
    /// Snapshots (features of the first window of each block of the stream).
    pub snapshots: Vec<Snapshot>,
    /// Final wear state.
    pub state: wearsim_core::wear::LifeState,
    /// Wall-clock seconds of this invocation.
    pub wall_s: f64,
    /// Output rate (Hz).
    pub fs: f64,
}

/// I/O or format failure of dense mode.
#[derive(Debug, thiserror::Error)]
pub enum DenseError {
    /// The life model failed.
    #[error(transparent)]
    Life(#[from] LifeError),
    /// File I/O.
    #[error("{path}: {source}")]
    Io {
        /// File.
        path: String,
        /// Cause.
        source: std::io::Error,
    },
    /// The output directory is in use by another run, or cannot be written.
    #[error(transparent)]
    Output(#[from] crate::io::IoError),
    /// A checkpoint that is corrupt or belongs to another run.
    #[error("{path}: {reason}")]
    Checkpoint {
        /// File.
        path: String,
        /// What is wrong.
        reason: String,
    },
}

fn io_err(path: &Path) -> impl Fn(std::io::Error) -> DenseError + '_ {
    move |source| DenseError::Io {
        path: path.display().to_string(),
        source,
    }
}

/// Paths of the dense-mode files in `dir`.
pub fn paths(dir: &Path) -> (PathBuf, PathBuf, PathBuf) {
    (
        dir.join("life-dense.f32"),
        dir.join("life-dense.json"),
        dir.join("life-dense.ckpt"),
    )
}

impl LifeRun {
    /// A string that identifies the run's configuration (a checkpoint only resumes the run
    /// it came from).
    pub fn fingerprint(&self) -> String {
        // The parts are in the order of `FINGERPRINT_PARTS`.
        format!(
            "{:?}|{:?}|{}|{}|{}|{}",
            self.spec.model,
            self.spec.life,
            self.spec.seed,
            self.spec.snapshot_every,
            self.spec.window,
            self.spec.settle
        )
    }

    /// Dense mode (see the module docs).
    pub fn run_dense(
        &self,
        opts: &DenseOptions,
        mut progress: impl FnMut(f64, f64),
    ) -> Result<DenseReport, DenseError> {
        let t0 = std::time::Instant::now();
        if let Some(s) = opts.stop_after {
            // At least one sample, at most 30 years of signal.
            let fs = self.spec.model.output_rate;
            wearsim_core::error::check_range("stop_after", s, 1.0 / fs, 1e9)
                .map_err(LifeError::from)?;
        }
        let (data_path, manifest_path, ckpt_path) = paths(&opts.dir);
        let _lock = crate::io::lock::DirLock::try_acquire(&opts.dir)?;
        let fs = self.spec.model.output_rate;
        let fingerprint = self.fingerprint();
        // The old completion marker goes first: from here on the set is incomplete.
        super::output::invalidate(&opts.dir).map_err(io_err(&opts.dir))?;

        // Start or resume.
        let resumed = ckpt_path.exists();
        let (
            mut k,
            mut st,
            mut samples_total,
            mut samples_in_block,
            mut carry,
            mut snapshots,
            mut blocks,
            mut window,
            dyn_bytes,
        ) = if resumed {
            let (c, bytes) = read_checkpoint(&ckpt_path)?;
            if c.fingerprint != fingerprint {
                return Err(DenseError::Checkpoint {
                    path: ckpt_path.display().to_string(),
                    reason: format!(
                        "belongs to a run with other settings ({}); use another --out, the same settings, or remove it",
                        fingerprint_difference(&c.fingerprint, &fingerprint)
                    ),
                });
            }
            let st = c
                .block_start
                .to_state()
                .ok_or_else(|| DenseError::Checkpoint {
                    path: ckpt_path.display().to_string(),
                    reason: "corrupt wear state".into(),
                })?;
            (
                c.block,
                st,
                c.samples_total,
                c.samples_in_block,
                c.carry,
                c.snapshots,
                c.blocks,
                c.window,
                Some(bytes),
            )
        } else {
            (
                0,
                self.life.initial_state(self.spec.seed),
                0,
                0,
                0.0,
                vec![],
                vec![],
                vec![],
                None,
            )
        };

        // The manifest says "incomplete" before the data file is cut back or extended.
        write_manifest(
            &manifest_path,
            &self.manifest(fs, samples_total, st.cycles, false, &blocks),
        )?;
        // The data file holds exactly `samples_total` samples from here on.
        let mut file = OpenOptions::new()
            .create(true)
            .truncate(false)
            .read(true)
            .write(true)
            .open(&data_path)
            .map_err(io_err(&data_path))?;
        let have = file.metadata().map_err(io_err(&data_path))?.len() / 4;
        if have < samples_total {
            return Err(DenseError::Checkpoint {
                path: data_path.display().to_string(),
                reason: format!("holds {have} samples but the checkpoint counts {samples_total}"),
            });
        }
        file.set_len(samples_total * 4)
            .map_err(io_err(&data_path))?;
        file.seek(SeekFrom::End(0)).map_err(io_err(&data_path))?;
        let mut out = BufWriter::new(file);

        let first_model = self.model_for(&st)?;
        let mut dynamic: State<CAPACITY> = match &dyn_bytes {
            Some(b) => State::decode(&first_model, b).map_err(LifeError::from)?,
            None => {
                let mut s = State::new(&first_model, self.spec.seed).map_err(LifeError::from)?;
                let mut settle = vec![Sample::default(); (self.spec.settle * fs) as usize];
                first_model.fill(&mut s, &mut settle);
                s
            }
        };

        let mut generated: u64 = 0;
        let budget = opts.stop_after.map(|s| (s * fs).round() as u64);
        let mut buf = vec![Sample::default(); CHUNK];
        let mut f32buf: Vec<u8> = Vec::with_capacity(CHUNK * 4);
        let mut since_ckpt: u64 = 0;
        let ckpt_every = checkpoint_every();
        let chunk = CHUNK.min(ckpt_every as usize);
        loop {
            let start = st.clone();
            let (_, loads) = self.window(&st, k)?;
            if st.stage == Stage::Failure {
                break;
            }
            let block = self.block_revs(&st, self.spec.snapshot_every);
            let revs = self.advance_checked(&mut st, &loads, block)?.revs;
            let exact = revs / self.shaft_hz * fs + carry;
            let n_block = exact.floor() as u64;
            let next_carry = exact - n_block as f64;
            let model = self.model_for(&start)?;
            if samples_in_block == 0 {
                // A block starts: its topography (a resumed block has it already, with
                // the running values of the checkpoint).
                if let Some(t) = start.topography {
                    dynamic.set_topography(&model, t).map_err(LifeError::from)?;
                }
                window.clear();
                blocks.push(BlockRecord {
                    block: k,
                    first_sample: samples_total,
                    cycles: start.cycles,
                    stage: start.stage.name().into(),
                    asperity: start.topography.map(|t| t.asperity_height).unwrap_or(0.0),
                    length: start.topography.map(|t| t.length).unwrap_or(0.0),
                });
            }
            let window_n = (self.spec.window * fs) as u64;
            while samples_in_block < n_block {
                // A write ends at the block end, the next checkpoint or the budget of
                // this invocation, whichever comes first.
                let to_stop = budget.map_or(u64::MAX, |b| b.saturating_sub(generated).max(1));
                let n = (n_block - samples_in_block)
                    .min(ckpt_every - since_ckpt)
                    .min(to_stop)
                    .min(chunk as u64) as usize;
                model.fill(&mut dynamic, &mut buf[..n]);
                f32buf.clear();
                for s in &buf[..n] {
                    if !s.accel.is_finite() {
                        return Err(LifeError::NonFinite {
                            cycles: start.cycles,
                        }
                        .into());
                    }
                    f32buf.extend_from_slice(&(s.accel as f32).to_le_bytes());
                    if (window.len() as u64) < window_n {
                        window.push(s.accel);
                    }
                }
                out.write_all(&f32buf).map_err(io_err(&data_path))?;
                samples_in_block += n as u64;
                samples_total += n as u64;
                generated += n as u64;
                since_ckpt += n as u64;
                // The caller's stop (crate::cancel) ends the run as a budget does: with a
                // checkpoint to resume from.
                let stop = budget.is_some_and(|b| generated >= b) || crate::cancel::requested();
                if since_ckpt >= ckpt_every || stop {
                    since_ckpt = 0;
                    out.flush().map_err(io_err(&data_path))?;
                    out.get_ref().sync_data().map_err(io_err(&data_path))?;
                    let c = Checkpoint {
                        fingerprint: fingerprint.clone(),
                        block: k,
                        block_start: (&start).into(),
                        samples_total,
                        samples_in_block,
                        carry,
                        snapshots: snapshots.clone(),
                        blocks: blocks.clone(),
                        window: window.clone(),
                    };
                    write_checkpoint(&ckpt_path, &c, &dynamic)?;
                    write_manifest(
                        &manifest_path,
                        &self.manifest(fs, samples_total, start.cycles, false, &blocks),
                    )?;
                    if stop {
                        return Ok(DenseReport {
                            samples: samples_total,
                            generated,
                            complete: false,
                            resumed,
                            snapshots,
                            state: start,
                            wall_s: t0.elapsed().as_secs_f64(),
                            fs,
                        });
                    }
                }
            }
            if window.len() as u64 == window_n && window_n > 0 {
                snapshots.push(self.snapshot(&start, &window, &loads)?);
            }
            progress(st.cycles, self.spec.life.cycle_cap);
            carry = next_carry;
            samples_in_block = 0;
            window.clear();
            k += 1;
        }
        out.flush().map_err(io_err(&data_path))?;
        out.get_ref().sync_all().map_err(io_err(&data_path))?;
        write_manifest(
            &manifest_path,
            &self.manifest(fs, samples_total, st.cycles, true, &blocks),
        )?;
        let _ = std::fs::remove_file(&ckpt_path);
        Ok(DenseReport {
            samples: samples_total,
            generated,
            complete: true,
            resumed,
            snapshots,
            state: st,
            wall_s: t0.elapsed().as_secs_f64(),
            fs,
        })
    }

    fn manifest(
        &self,
        fs: f64,
        samples: u64,
        cycles: f64,
        complete: bool,
        blocks: &[BlockRecord],
    ) -> Manifest {
        Manifest {
            format: "wearsim-dense-f32le".into(),
            fs,
            unit: "m/s^2".into(),
            samples,
            cycles,
            complete,
            blocks: blocks.to_vec(),
            seed: self.spec.seed,
            config_hash: format!("{:016x}", fnv1a64(self.fingerprint().as_bytes())),
        }
    }
}

fn write_manifest(path: &Path, m: &Manifest) -> Result<(), DenseError> {
    let text = serde_json::to_vec_pretty(m).map_err(|e| DenseError::Io {
        path: path.display().to_string(),
        source: e.into(),
    })?;
    super::output::write_atomic(path, &text).map_err(io_err(path))
}

fn write_checkpoint(
    path: &Path,
    c: &Checkpoint,
    dynamic: &State<CAPACITY>,
) -> Result<(), DenseError> {
    let header = serde_json::to_vec(c).map_err(|e| DenseError::Io {
        path: path.display().to_string(),
        source: e.into(),
    })?;
    let mut state = vec![0u8; encoded_len(CAPACITY)];
    let n = dynamic
        .encode(&mut state)
        .map_err(|e| DenseError::Checkpoint {
            path: path.display().to_string(),
            reason: e.to_string(),
        })?;
    let mut bytes = Vec::with_capacity(header.len() + n + 24);
    bytes.extend_from_slice(MAGIC);
    bytes.extend_from_slice(&(header.len() as u64).to_le_bytes());
    bytes.extend_from_slice(&header);
    bytes.extend_from_slice(&(n as u64).to_le_bytes());
    bytes.extend_from_slice(state.get(..n).unwrap_or(&[]));
    let sum = fnv1a64(&bytes);
    bytes.extend_from_slice(&sum.to_le_bytes());
    super::output::write_atomic(path, &bytes).map_err(io_err(path))
}

fn read_checkpoint(path: &Path) -> Result<(Checkpoint, Vec<u8>), DenseError> {
    let bad = |reason: &str| DenseError::Checkpoint {
        path: path.display().to_string(),
        reason: reason.into(),
    };
    let mut bytes = vec![];
    File::open(path)
        .and_then(|mut f| f.read_to_end(&mut bytes))
        .map_err(io_err(path))?;
    if bytes.get(..8) != Some(MAGIC.as_slice()) {
        return Err(bad(
            "not a wearsim dense checkpoint of this version; remove it to start over",
        ));
    }
    let body_len = bytes
        .len()
        .checked_sub(8)
        .ok_or_else(|| bad("truncated checkpoint"))?;
    let (body, sum) = bytes.split_at(body_len);
    if fnv1a64(body).to_le_bytes() != sum {
        return Err(bad(
            "checksum mismatch: the checkpoint is corrupt; remove it (and the data) to start over",
        ));
    }
    let bytes = body;
    let len = |at: usize| -> Option<usize> {
        Some(u64::from_le_bytes(bytes.get(at..at + 8)?.try_into().ok()?) as usize)
    };
    let hl = len(8).ok_or_else(|| bad("truncated header"))?;
    let header = bytes
        .get(16..16usize.saturating_add(hl))
        .ok_or_else(|| bad("truncated header"))?;
    let c: Checkpoint =
        serde_json::from_slice(header).map_err(|e| bad(&format!("corrupt header: {e}")))?;
    let sl = len(16 + hl).ok_or_else(|| bad("truncated state"))?;
    let state = bytes
        .get(24 + hl..(24 + hl).saturating_add(sl))
        .ok_or_else(|| bad("truncated state"))?;
    Ok((c, state.to_vec()))
}

/// What the parts of [`LifeRun::fingerprint`] stand for, in its order.
const FINGERPRINT_PARTS: [&str; 6] = [
    "the model (preset or configuration, load)",
    "the life settings (--cycles, --lambda, material)",
    "--seed",
    "--snapshot-every",
    "--window",
    "the settling time",
];

/// Which settings differ between a checkpoint's fingerprint `old` and this run's `new`:
/// the parts by name, with both values where they are one number.
fn fingerprint_difference(old: &str, new: &str) -> String {
    let (a, b): (Vec<&str>, Vec<&str>) = (old.split('|').collect(), new.split('|').collect());
    if a.len() != b.len() || a.len() != FINGERPRINT_PARTS.len() {
        return "written by another version of wearsim".into();
    }
    let diff: Vec<String> = FINGERPRINT_PARTS
        .iter()
        .zip(a.iter().zip(&b))
        .filter(|(_, (x, y))| x != y)
        .map(
            |(name, (x, y))| match (x.parse::<f64>(), y.parse::<f64>()) {
                (Ok(_), Ok(_)) => format!("{name}: {x} in the checkpoint, {y} now"),
                _ => format!("{name} changed"),
            },
        )
        .collect();
    diff.join("; ")
}

#[cfg(test)]
mod fingerprint_tests {
    use super::fingerprint_difference;

    #[test]
    fn a_differing_setting_is_named_with_both_values() {
        let old = "M|L|1|20000|0.25|0.05";
        assert_eq!(
            fingerprint_difference(old, "M|L|7|20000|0.25|0.05"),
            "--seed: 1 in the checkpoint, 7 now"
        );
        assert_eq!(
            fingerprint_difference(old, "N|L|1|20000|0.5|0.05"),
            "the model (preset or configuration, load) changed; --window: 0.25 in the checkpoint, 0.5 now"
        );
        assert_eq!(
            fingerprint_difference(old, "M|L|1"),
            "written by another version of wearsim"
        );
    }
}
