//! `wearsim capture` on synthetic firmware streams (no QEMU needed): a valid stream is
//! written like `wearsim simulate`; flipped bits, truncation, garbage and lost frames are
//! detected and reported, and nothing is written as if complete.

use std::path::Path;
use std::process::Command;

use serde_json::Value;
use wearsim_core::{presets, Model, State};
use wearsim_frame as frame;

const PRESET: &str = "thesis-61810";
const SEED: u64 = 7;

/// A firmware-like stream of `samples` (f32 m/s²), `per` samples per frame.
fn stream(samples: &[f32], per: usize) -> Vec<u8> {
    let mut out = vec![];
    let mut buf = [0u8; frame::MAX_FRAME];
    let mut preset = [0u8; 24];
    preset[..PRESET.len()].copy_from_slice(PRESET.as_bytes());
    let start = frame::StartInfo {
        preset,
        seed: SEED,
        rate_hz: 20_000.0,
        oversample: 2,
        total_samples: samples.len() as u32,
        flavour: 1,
    };
    let ctl = |kind, seq| frame::Header {
        kind,
        format: frame::Format::None,
        flags: 0,
        seq,
        first_sample: 0,
        overruns: 0,
        scale: 0.0,
    };
    let n = frame::encode(&ctl(frame::Kind::Start, 0), &start.to_bytes(), &mut buf).unwrap();
    out.extend_from_slice(&buf[..n]);
    let mut seq = 1;
    for (i, chunk) in samples.chunks(per).enumerate() {
        let payload: Vec<u8> = chunk.iter().flat_map(|x| x.to_le_bytes()).collect();
        let h = frame::Header {
            kind: frame::Kind::Data,
            format: frame::Format::F32,
            flags: 0,
            seq,
            first_sample: (i * per) as u32,
            overruns: 0,
            scale: 1.0,
        };
        let n = frame::encode(&h, &payload, &mut buf).unwrap();
        out.extend_from_slice(&buf[..n]);
        seq += 1;
    }
    let end = frame::EndInfo {
        total_samples: samples.len() as u32,
        data_frames: samples.len().div_ceil(per) as u32,
        overruns: 0,
        busy_ticks: 1000,
        tick_hz: 25_000_000,
        measured_samples: 10,
        reserved: 0,
    };
    let n = frame::encode(&ctl(frame::Kind::End, seq), &end.to_bytes(), &mut buf).unwrap();
    out.extend_from_slice(&buf[..n]);
    out
}

/// The first `n` host (f64) samples of the reference, as f32.
fn host_samples(n: usize) -> Vec<f32> {
    let model = Model::new_checked(presets::by_name(PRESET).unwrap()).unwrap();
    let mut st = State::<16>::new(&model, SEED).unwrap();
    let mut v = vec![];
    while v.len() < n {
        if let Some(s) = model.step(&mut st) {
            v.push(s.accel as f32);
        }
    }
    v
}

fn capture(dir: &Path, bytes: &[u8], extra: &[&str]) -> (i32, Value) {
    let input = dir.join("serial.bin");
    std::fs::write(&input, bytes).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_wearsim"))
        .args(["capture", "--json", "--input"])
        .arg(&input)
        .arg("--out")
        .arg(dir.join("out"))
        .args(extra)
        .output()
        .unwrap();
    let report: Value = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "no JSON report ({e}): stdout {} stderr {}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        )
    });
    (out.status.code().unwrap_or(-1), report)
}

fn nothing_written(dir: &Path) {
    let out = dir.join("out");
    let entries: Vec<_> = std::fs::read_dir(&out)
        .map(|r| r.flatten().map(|e| e.file_name()).collect())
        .unwrap_or_default();
    assert!(
        entries.is_empty(),
        "an incomplete stream must write nothing, found {entries:?}"
    );
}

#[test]
fn valid_stream_is_written_like_simulate() {
    let dir = tempfile::tempdir().unwrap();
    let samples = host_samples(500);
    let (code, r) = capture(
        dir.path(),
        &stream(&samples, 64),
        &["--expect-seed", "7", "--preset", PRESET],
    );
    assert_eq!(code, 0, "{r}");
    assert_eq!(r["complete"], true);
    assert_eq!(r["samples"], 500);
    assert_eq!(r["data_frames"], 8);
    assert_eq!(r["comparison"]["pass"], true);
    // f32 rounding of the host's own samples only.
    assert!(r["comparison"]["rel_error"].as_f64().unwrap() < 1e-6, "{r}");
    let side: Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("out/capture.json")).unwrap())
            .unwrap();
    assert_eq!(side["complete"], true);
    assert_eq!(side["n_samples"], 500);
    assert_eq!(side["fs"], 20_000.0);
    assert_eq!(side["seed"], 7);
    let csv = std::fs::read_to_string(dir.path().join("out/capture.csv")).unwrap();
    let second: Vec<&str> = csv.lines().nth(2).unwrap().split(',').collect();
    assert_eq!(second[1].parse::<f64>().unwrap(), samples[1] as f64);
}

#[test]
fn flipped_bit_is_a_corrupt_frame_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let mut s = stream(&host_samples(300), 64);
    let at = 80 + frame::HEADER_LEN + 10; // inside the first data frame's payload
    s[at] ^= 0x04;
    let (code, r) = capture(dir.path(), &s, &[]);
    assert_eq!(code, 2, "{r}");
    assert_eq!(r["complete"], false);
    assert_eq!(r["corrupt"][0]["reason"], "CRC mismatch");
    assert_eq!(r["missing_samples"], 64, "{r}");
    nothing_written(dir.path());
}

#[test]
fn truncated_stream_is_reported_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let s = stream(&host_samples(300), 64);
    for cut in [s.len() - 1, s.len() - 40, s.len() / 2, 3] {
        let (code, r) = capture(dir.path(), &s[..cut], &[]);
        assert_eq!(code, 2, "cut at {cut}: {r}");
        assert_eq!(r["complete"], false);
        assert_eq!(r["end_frame"], false, "cut at {cut}");
        nothing_written(dir.path());
    }
}

#[test]
fn garbage_and_lost_frames_are_counted() {
    let dir = tempfile::tempdir().unwrap();
    let s = stream(&host_samples(300), 64);
    // Garbage in the middle (with a fake sync word) and at the start.
    let mut g = b"noise\xA5\x5A\x57\x53junk".to_vec();
    g.extend_from_slice(&s[..400]);
    g.extend_from_slice(b"\x00\xff\xA5\x5A\x57\x53\x01\x02garbage");
    g.extend_from_slice(&s[400..]);
    let (code, r) = capture(dir.path(), &g, &[]);
    assert_eq!(code, 2, "{r}");
    assert!(r["corrupt"].as_array().unwrap().len() >= 2, "{r}");
    nothing_written(dir.path());

    // A whole data frame removed: sequence and sample gaps.
    let frame_len = frame::HEADER_LEN + 64 * 4 + frame::CRC_LEN;
    let first_data = 28 + frame::START_LEN + 4;
    let mut lost = s[..first_data + frame_len].to_vec();
    lost.extend_from_slice(&s[first_data + 2 * frame_len..]);
    let (code, r) = capture(dir.path(), &lost, &[]);
    assert_eq!(code, 2, "{r}");
    assert_eq!(r["missing_frames"], 1, "{r}");
    assert_eq!(r["missing_samples"], 64, "{r}");
    assert!(r["corrupt"].as_array().unwrap().is_empty());
    nothing_written(dir.path());
}

#[test]
fn samples_that_differ_from_the_host_run_fail_the_comparison() {
    let dir = tempfile::tempdir().unwrap();
    let mut samples = host_samples(400);
    samples[123] += 1.0; // well above 1e-3 of the RMS
    let (code, r) = capture(
        dir.path(),
        &stream(&samples, 64),
        &["--expect-seed", "7", "--preset", PRESET],
    );
    assert_eq!(code, 1, "{r}");
    assert_eq!(r["comparison"]["pass"], false);
    nothing_written(dir.path());
    // The wrong seed fails too.
    let (code, r) = capture(
        dir.path(),
        &stream(&host_samples(400), 64),
        &["--expect-seed", "8", "--preset", PRESET],
    );
    assert_eq!(code, 1, "{r}");
    nothing_written(dir.path());
}

#[test]
fn missing_input_is_a_clear_error() {
    let out = Command::new(env!("CARGO_BIN_EXE_wearsim"))
        .args(["capture", "--input", "/nonexistent/serial.bin"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("/nonexistent/serial.bin"), "{err}");
}
