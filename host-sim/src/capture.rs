//! `wearsim capture`: reads the framed sample stream of the wearsim firmware (a QEMU
//! `-serial file:` capture or a serial device), checks framing and CRC, reports dropped,
//! missing and corrupt frames, optionally compares the samples with a host run of the same
//! preset and seed, and writes the same outputs as `wearsim simulate`.
//!
//! Atomicity: outputs are written (through [`crate::io::write::write_outputs`], itself
//! atomic) only for a **complete** stream: a start frame, every data frame in sequence with
//! contiguous sample indices, an end frame whose totals match, no corrupt or truncated
//! bytes, and (with `--expect-seed`/`--preset`) samples within tolerance of the host run.
//! Otherwise the command prints its report (with `"complete": false` under `--json`), writes
//! nothing, and exits with code 2 (bad stream) or 1 (comparison failed).
//!
//! The frame layout is documented in `docs/firmware.md` and in the `wearsim-frame` crate.

use std::io::Read;
use std::path::Path;

use serde::Serialize;
use wearsim_core::{presets, Model, State};
use wearsim_frame::{self as frame, Event, Format, Kind};

/// Largest stream accepted (bytes): 20 kHz of f32 for about 25 minutes.
pub const MAX_STREAM_BYTES: u64 = 128 * 1024 * 1024;

/// Most corrupt spans and problem lines listed in a report; the rest are counted
/// ([`CaptureReport::corrupt_spans`], [`CaptureReport::unlisted_problems`]), so a flood of
/// sync words or broken frames costs bounded memory.
pub const MAX_LISTED: usize = 100;

/// Tolerance of an f32 target run against the f64 host run: largest sample difference over
/// the first [`COMPARE_PREFIX`] samples, relative to the host RMS over them (see
/// `docs/firmware.md`, "Host versus target": f32 rounding gives ~5e-4 there; later the two
/// trajectories decorrelate and only their statistics agree).
pub const F64_REL_TOLERANCE: f64 = 2e-3;
/// Samples compared one by one with the host run (10 ms at 20 kHz).
pub const COMPARE_PREFIX: usize = 200;
/// Tolerance on the RMS of the whole record, relative to the host's (measured 0.2 %).
pub const RMS_REL_TOLERANCE: f64 = 0.02;

/// Why a capture failed; [`crate::cmd::exit`] maps each kind to its exit code.
#[derive(Debug, Clone, PartialEq)]
pub enum CaptureError {
    /// A bad argument or an unreadable input (exit 2).
    Input(String),
    /// The stream is not complete or not valid; nothing was written (exit 2).
    Stream(String),
    /// The stream is valid but its samples differ from the host run (exit 1).
    Mismatch(String),
    /// Writing the outputs failed after the work (exit 1).
    Write(String),
}

impl std::fmt::Display for CaptureError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CaptureError::Input(m)
            | CaptureError::Stream(m)
            | CaptureError::Mismatch(m)
            | CaptureError::Write(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for CaptureError {}

/// A span of bytes that is not a valid frame.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BadSpan {
    /// Byte offset in the stream.
    pub offset: usize,
    /// Length in bytes.
    pub len: usize,
    /// Why the bytes were rejected.
    pub reason: String,
}

/// Result of the comparison with a host run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Comparison {
    /// Preset of the host run.
    pub preset: String,
    /// Seed of the host run.
    pub seed: u64,
    /// Samples compared one by one (the first ones).
    pub samples: usize,
    /// Largest |target − host| over them (m/s²).
    pub max_abs_error: f64,
    /// RMS of the host signal over them (m/s²).
    pub host_rms: f64,
    /// `max_abs_error / host_rms`.
    pub rel_error: f64,
    /// Tolerance applied to `rel_error`.
    pub tolerance: f64,
    /// Index of the first sample whose difference exceeds `tolerance · host_rms`, over the
    /// whole record (where the trajectories part).
    pub first_divergence: Option<usize>,
    /// RMS of the whole target record over the host's, minus 1.
    pub rms_rel_diff: f64,
    /// Tolerance applied to `|rms_rel_diff|`.
    pub rms_tolerance: f64,
    /// Whether both checks pass.
    pub pass: bool,
}

/// What the decoder found in a stream.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CaptureReport {
    /// Input path.
    pub input: String,
    /// Bytes read.
    pub bytes: usize,
    /// Frames whose CRC matched.
    pub valid_frames: usize,
    /// Valid data frames.
    pub data_frames: usize,
    /// Data frames missing from the sequence numbers.
    pub missing_frames: u64,
    /// Samples missing between data frames (gaps in `first_sample`).
    pub missing_samples: u64,
    /// Data frames repeated (a sequence number already received); their samples are not
    /// used again.
    pub duplicate_frames: u64,
    /// Rejected byte spans (corrupt frames, garbage): the first [`MAX_LISTED`].
    pub corrupt: Vec<BadSpan>,
    /// Rejected byte spans in all.
    pub corrupt_spans: u64,
    /// Rejected bytes in all.
    pub corrupt_bytes: u64,
    /// Whether the stream ends inside a frame.
    pub truncated: bool,
    /// Samples received.
    pub samples: usize,
    /// Sample rate from the start frame (Hz).
    pub rate_hz: Option<f64>,
    /// Preset named by the start frame.
    pub preset: Option<String>,
    /// Seed from the start frame.
    pub seed: Option<u64>,
    /// Firmware flavour: `m4f-hardfloat`, `m3-softfloat` or `other`.
    pub flavour: Option<String>,
    /// Sample format of the data frames.
    pub format: Option<String>,
    /// Missed sample deadlines reported by the firmware (its real-time overruns).
    pub overruns: u32,
    /// Samples the firmware could not queue for transmission (from the end frame).
    pub tx_drops: Option<u32>,
    /// Whether the end frame arrived.
    pub end_frame: bool,
    /// Instructions per output sample of the firmware's timed loop, valid for a QEMU run with
    /// `-icount shift=0` (1 instruction = 1 ns of virtual time).
    pub instructions_per_sample: Option<f64>,
    /// Comparison with the host run, if asked for.
    pub comparison: Option<Comparison>,
    /// Everything that makes the stream incomplete, one line each (the first
    /// [`MAX_LISTED`]).
    pub problems: Vec<String>,
    /// Problems beyond the listed ones.
    pub unlisted_problems: u64,
    /// True when the stream is complete and every check passed.
    pub complete: bool,
}

impl CaptureReport {
    /// Records a problem: listed up to [`MAX_LISTED`], counted beyond.
    fn problem(&mut self, p: String) {
        if self.problems.len() < MAX_LISTED {
            self.problems.push(p);
        } else {
            self.unlisted_problems += 1;
        }
    }
}

/// The samples and report of a decoded stream.
#[derive(Debug, Clone)]
pub struct Decoded {
    /// The report.
    pub report: CaptureReport,
    /// Samples in m/s², in order.
    pub accel: Vec<f64>,
}

/// Decodes a captured stream and checks it (no comparison, no output).
pub fn decode(input: &str, bytes: &[u8]) -> Decoded {
    let mut r = CaptureReport {
        input: input.to_string(),
        bytes: bytes.len(),
        valid_frames: 0,
        data_frames: 0,
        missing_frames: 0,
        missing_samples: 0,
        duplicate_frames: 0,
        corrupt: vec![],
        corrupt_spans: 0,
        corrupt_bytes: 0,
        truncated: false,
        samples: 0,
        rate_hz: None,
        preset: None,
        seed: None,
        flavour: None,
        format: None,
        overruns: 0,
        tx_drops: None,
        end_frame: false,
        instructions_per_sample: None,
        comparison: None,
        problems: vec![],
        unlisted_problems: 0,
        complete: false,
    };
    let mut accel = Vec::new();
    let mut start: Option<frame::StartInfo> = None;
    let mut end: Option<(frame::EndInfo, u32)> = None;
    let mut next_seq: Option<u32> = None;
    let mut next_sample: u64 = 0;
    let mut format: Option<Format> = None;
    // The stream's scale (fixed per stream: 1 for f32, g₀·FS/32768 for counts) and the
    // cumulative overrun counter so far.
    let mut stream_scale: Option<f32> = None;
    let mut overruns_so_far: u32 = 0;
    for ev in frame::Decoder::new(bytes) {
        match ev {
            Event::Corrupt {
                offset,
                len,
                reason,
            } => {
                r.corrupt_spans += 1;
                r.corrupt_bytes += len as u64;
                if r.corrupt.len() < MAX_LISTED {
                    r.corrupt.push(BadSpan {
                        offset,
                        len,
                        reason: reason.as_str().to_string(),
                    });
                }
            }
            Event::Truncated { offset, len } => {
                r.truncated = true;
                r.problem(format!(
                    "stream ends inside a frame ({len} bytes at offset {offset})"
                ));
            }
            Event::Frame {
                header, payload, ..
            } => {
                r.valid_frames += 1;
                if end.is_some() {
                    r.problem(format!("frame seq {} after the end frame", header.seq));
                }
                match header.kind {
                    Kind::Start => {
                        if start.is_some() {
                            r.problem("second start frame".into());
                        }
                        start = frame::StartInfo::from_bytes(payload);
                        next_seq = Some(1);
                    }
                    Kind::Data | Kind::End => {
                        if let Some(want) = next_seq {
                            // A sequence number already received (within half the
                            // sequence space behind): a repeated frame, not a gap.
                            let behind = want.wrapping_sub(header.seq);
                            if (1..=u32::MAX / 2).contains(&behind) {
                                r.duplicate_frames += 1;
                                r.problem(format!(
                                    "frame seq {} repeated (expected {want}); its samples are not used again",
                                    header.seq
                                ));
                                continue;
                            }
                            if header.seq != want {
                                let lost = header.seq.wrapping_sub(want) as u64;
                                r.missing_frames += lost.min(u32::MAX as u64);
                                r.problem(format!(
                                    "frame sequence jumps from {} to {} ({} frame(s) missing)",
                                    want.wrapping_sub(1),
                                    header.seq,
                                    lost
                                ));
                            }
                        } else {
                            r.problem(format!("frame seq {} before any start frame", header.seq));
                        }
                        next_seq = Some(header.seq.wrapping_add(1));
                        if header.overruns < overruns_so_far {
                            r.problem(format!(
                                "frame seq {}: the cumulative overrun counter goes back from {overruns_so_far} to {}",
                                header.seq, header.overruns
                            ));
                        }
                        overruns_so_far = overruns_so_far.max(header.overruns);
                        r.overruns = r.overruns.max(header.overruns);
                        if header.kind == Kind::End {
                            end = frame::EndInfo::from_bytes(payload).map(|e| (e, header.seq));
                            continue;
                        }
                        r.data_frames += 1;
                        if *format.get_or_insert(header.format) != header.format {
                            r.problem(format!(
                                "frame seq {} changes the sample format",
                                header.seq
                            ));
                        }
                        let first = header.first_sample as u64;
                        if first < next_sample {
                            r.problem(format!(
                                "frame seq {} restarts at sample {first}, {next_sample} already received",
                                header.seq
                            ));
                        } else if first != next_sample {
                            let gap = first.saturating_sub(next_sample);
                            r.missing_samples += gap;
                            r.problem(format!(
                                "samples {next_sample}..{first} missing before frame seq {}",
                                header.seq
                            ));
                        }
                        if !(header.scale.is_finite() && header.scale > 0.0) {
                            r.problem(format!(
                                "frame seq {} has scale {} (m/s² per payload unit: finite and > 0)",
                                header.seq, header.scale
                            ));
                        } else if *stream_scale.get_or_insert(header.scale) != header.scale {
                            r.problem(format!(
                                "frame seq {} changes the scale from {} to {} m/s² per payload unit (fixed for a stream)",
                                header.seq,
                                stream_scale.unwrap_or(header.scale),
                                header.scale
                            ));
                        }
                        let scale = header.scale as f64;
                        let bad_from = accel.len();
                        match header.format {
                            Format::F32 => accel.extend(payload.chunks_exact(4).map(|c| {
                                f32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64 * scale
                            })),
                            Format::I16 => accel.extend(
                                payload
                                    .chunks_exact(2)
                                    .map(|c| i16::from_le_bytes([c[0], c[1]]) as f64 * scale),
                            ),
                            Format::None => {}
                        }
                        // Beyond f32: the outputs (WAV, CSV as f32) could not hold it.
                        let bad = |v: &f64| !(v.is_finite() && v.abs() <= f32::MAX as f64);
                        if let Some(i) = accel[bad_from..].iter().position(bad) {
                            r.problem(format!(
                                "frame seq {} carries a sample of {:e} m/s² at sample index {} (non-finite or beyond the f32 range of the outputs): the stream is corrupt",
                                header.seq,
                                accel[bad_from + i],
                                first + i as u64
                            ));
                        }
                        let n = payload.len() / header.format.sample_size().max(1);
                        next_sample = first + n as u64;
                    }
                }
            }
        }
    }
    r.samples = accel.len();
    r.format = format.map(|f| match f {
        Format::F32 => "f32".to_string(),
        Format::I16 => "i16".to_string(),
        Format::None => "none".to_string(),
    });
    match start {
        Some(s) => {
            r.rate_hz = Some(s.rate_hz as f64);
            r.preset = Some(s.preset_name().to_string());
            if s.preset_name().is_empty() {
                r.problem("start frame names no preset (empty, or not ASCII text)".into());
            }
            if s.oversample == 0 {
                r.problem(
                    "start frame has oversample 0 (internal steps per output sample, ≥ 1)".into(),
                );
            }
            if s.flavour > 2 {
                r.problem(format!(
                    "start frame has an unknown firmware flavour {} (0 other, 1 m4f-hardfloat, 2 m3-softfloat)",
                    s.flavour
                ));
            }
            r.seed = Some(s.seed);
            r.flavour = Some(
                match s.flavour {
                    1 => "m4f-hardfloat",
                    2 => "m3-softfloat",
                    _ => "other",
                }
                .to_string(),
            );
            if s.total_samples != 0 && s.total_samples as usize != r.samples {
                r.problem(format!(
                    "start frame announces {} samples, {} received",
                    s.total_samples, r.samples
                ));
            }
            if !(1.0..=1e7).contains(&(s.rate_hz as f64)) {
                r.problem(format!("start frame has an invalid rate {} Hz", s.rate_hz));
            }
        }
        None => r.problem("no valid start frame".into()),
    }
    match end {
        Some((e, _)) => {
            r.end_frame = true;
            r.tx_drops = Some(e.reserved);
            if e.total_samples as usize != r.samples {
                r.problem(format!(
                    "end frame counts {} samples, {} received",
                    e.total_samples, r.samples
                ));
            }
            if e.data_frames as usize != r.data_frames {
                r.problem(format!(
                    "end frame counts {} data frames, {} received",
                    e.data_frames, r.data_frames
                ));
            }
            if e.overruns != r.overruns {
                r.problem(format!(
                    "end frame counts {} overruns, the frame headers {}",
                    e.overruns, r.overruns
                ));
            }
            if e.reserved != 0 {
                r.problem(format!(
                    "firmware dropped {} sample(s) before transmission",
                    e.reserved
                ));
            }
            if e.measured_samples > 0 && e.tick_hz > 0 {
                r.instructions_per_sample = Some(
                    e.busy_ticks as f64 * (1e9 / e.tick_hz as f64) / e.measured_samples as f64,
                );
            }
        }
        None => r
            .problems
            .push("no end frame: the stream is incomplete".into()),
    }
    if r.corrupt_spans > 0 {
        r.problem(format!(
            "{} corrupt span(s), {} byte(s) rejected",
            r.corrupt_spans, r.corrupt_bytes
        ));
    }
    if r.samples == 0 {
        r.problem("no samples".into());
    }
    r.complete = r.problems.is_empty();
    if r.unlisted_problems > 0 {
        r.problems.push(format!(
            "... and {} more problem(s) not listed",
            r.unlisted_problems
        ));
    }
    Decoded { report: r, accel }
}

/// Compares `accel` with the first samples of a host run of `preset` with `seed`.
pub fn compare(
    accel: &[f64],
    preset: &str,
    seed: u64,
    tolerance: f64,
) -> Result<Comparison, CaptureError> {
    let cfg = presets::by_name(preset)
        .ok_or_else(|| CaptureError::Input(format!("unknown preset {preset:?}")))?;
    let model =
        Model::new_checked(cfg).map_err(|e| CaptureError::Input(format!("{preset}: {e}")))?;
    let mut st = State::<32>::new(&model, seed)
        .map_err(|e| CaptureError::Input(format!("{preset}: {e}")))?;
    let mut host = Vec::with_capacity(accel.len());
    while host.len() < accel.len() {
        if let Some(s) = model.step(&mut st) {
            host.push(s.accel);
        }
    }
    let rms = |x: &[f64]| (x.iter().map(|v| v * v).sum::<f64>() / x.len().max(1) as f64).sqrt();
    let n = accel.len().min(COMPARE_PREFIX);
    let max_err = accel[..n]
        .iter()
        .zip(&host[..n])
        .map(|(a, h)| (a - h).abs())
        .fold(0.0f64, f64::max);
    let host_rms = rms(&host[..n]);
    let rel = if host_rms > 0.0 {
        max_err / host_rms
    } else {
        max_err
    };
    let first_divergence = accel
        .iter()
        .zip(&host)
        .position(|(a, h)| (a - h).abs() > tolerance * host_rms);
    let (rt, rh) = (rms(accel), rms(&host));
    let rms_rel_diff = if rh > 0.0 { rt / rh - 1.0 } else { rt };
    Ok(Comparison {
        preset: preset.to_string(),
        seed,
        samples: n,
        max_abs_error: max_err,
        host_rms,
        rel_error: rel,
        tolerance,
        first_divergence,
        rms_rel_diff,
        rms_tolerance: RMS_REL_TOLERANCE,
        pass: rel <= tolerance && rms_rel_diff.abs() <= RMS_REL_TOLERANCE,
    })
}

/// Reads a captured stream: a whole file (at most [`MAX_STREAM_BYTES`]), or a device or
/// pipe until an end frame arrives.
pub fn read_input(path: &Path) -> Result<Vec<u8>, CaptureError> {
    let meta = std::fs::metadata(path)
        .map_err(|e| CaptureError::Input(format!("{}: {e}", path.display())))?;
    let mut f = std::fs::File::open(path)
        .map_err(|e| CaptureError::Input(format!("{}: {e}", path.display())))?;
    let mut buf = Vec::new();
    if meta.is_file() {
        if meta.len() > MAX_STREAM_BYTES {
            return Err(CaptureError::Input(format!(
                "{}: {} bytes is over the {MAX_STREAM_BYTES}-byte limit",
                path.display(),
                meta.len()
            )));
        }
        f.read_to_end(&mut buf)
            .map_err(|e| CaptureError::Input(format!("{}: {e}", path.display())))?;
        return Ok(buf);
    }
    // A device or pipe: read until an end frame has arrived, EOF, or the size limit.
    let mut chunk = [0u8; 4096];
    loop {
        let n = f
            .read(&mut chunk)
            .map_err(|e| CaptureError::Input(format!("{}: {e}", path.display())))?;
        if n == 0 {
            break;
        }
        buf.extend_from_slice(&chunk[..n]);
        if buf.len() as u64 > MAX_STREAM_BYTES {
            return Err(CaptureError::Input(format!(
                "{}: more than {MAX_STREAM_BYTES} bytes without an end frame",
                path.display()
            )));
        }
        let tail_from = buf.len().saturating_sub(n + frame::MAX_FRAME);
        let seen_end = frame::Decoder::new(&buf[tail_from..]).any(|e| {
            matches!(
                e,
                Event::Frame {
                    header: frame::Header {
                        kind: Kind::End,
                        ..
                    },
                    ..
                }
            )
        });
        if seen_end {
            break;
        }
    }
    Ok(buf)
}
