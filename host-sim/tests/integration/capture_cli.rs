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
    forged(samples, per, |_| {}, |_, _| {}, |_| {})
}

/// [`stream`] with its start frame, each data frame's header (by frame index) and its end
/// frame changed by the given functions, as a forged or damaged stream with valid CRCs.
fn forged(
    samples: &[f32],
    per: usize,
    start_with: impl Fn(&mut frame::StartInfo),
    data_with: impl Fn(usize, &mut frame::Header),
    end_with: impl Fn(&mut frame::EndInfo),
) -> Vec<u8> {
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
    let mut start = start;
    start_with(&mut start);
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
        let mut h = frame::Header {
            kind: frame::Kind::Data,
            format: frame::Format::F32,
            flags: 0,
            seq,
            first_sample: (i * per) as u32,
            overruns: 0,
            scale: 1.0,
        };
        data_with(i, &mut h);
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
    let mut end = end;
    end_with(&mut end);
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
    // The preset's model and speed, as `simulate` writes them: `analyze` reads a capture
    // with no further arguments (the probe of stop 69 found "no bearing geometry").
    let cfg = presets::by_name(PRESET).unwrap();
    let rpm = 60.0 * cfg.speed.shaft_hz(0.0) as f64;
    assert!(
        (side["rpm"].as_f64().unwrap() / rpm - 1.0).abs() < 1e-9,
        "{side}"
    );
    assert_eq!(side["bearing"], PRESET);
    assert_eq!(side["model"]["output_rate"].as_f64(), Some(20_000.0));
    // Long enough for the analysis (10 periods of the slowest defect frequency).
    let long = tempfile::tempdir().unwrap();
    let (code, r) = capture(long.path(), &stream(&host_samples(4000), 64), &[]);
    assert_eq!(code, 0, "{r}");
    let a = Command::new(env!("CARGO_BIN_EXE_wearsim"))
        .args(["analyze", "--json"])
        .arg(long.path().join("out/capture.csv"))
        .output()
        .unwrap();
    assert_eq!(
        a.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&a.stderr)
    );
}

/// Frames with valid CRCs whose fields no firmware sends (probe of stop 69: each was
/// written as a complete capture): every one is a problem, exit 2, nothing written.
#[test]
fn forged_frame_fields_are_problems_and_nothing_is_written() {
    let samples = host_samples(320);
    let preset_bytes = |s: &mut frame::StartInfo| s.preset = [0xFF; 24];
    let cases: Vec<(&str, Vec<u8>)> = vec![
        (
            "scale 0",
            forged(&samples, 64, |_| {}, |_, h| h.scale = 0.0, |_| {}),
        ),
        (
            "scale -1",
            forged(&samples, 64, |_| {}, |_, h| h.scale = -1.0, |_| {}),
        ),
        (
            "changes the scale from 1 to 100",
            forged(
                &samples,
                64,
                |_| {},
                |i, h| {
                    if i == 2 {
                        h.scale = 100.0
                    }
                },
                |_| {},
            ),
        ),
        (
            "beyond the f32 range",
            forged(&samples, 64, |_| {}, |_, h| h.scale = 3.4e38, |_| {}),
        ),
        (
            "overrun counter goes back from 5 to 0",
            forged(
                &samples,
                64,
                |_| {},
                |i, h| {
                    if i == 1 {
                        h.overruns = 5
                    }
                },
                |e| e.overruns = 5,
            ),
        ),
        (
            "end frame counts 0 overruns, the frame headers 1",
            forged(
                &samples,
                64,
                |_| {},
                |i, h| {
                    if i == 4 {
                        h.overruns = 1
                    }
                },
                |_| {},
            ),
        ),
        (
            "oversample 0",
            forged(&samples, 64, |s| s.oversample = 0, |_, _| {}, |_| {}),
        ),
        (
            "unknown firmware flavour 99",
            forged(&samples, 64, |s| s.flavour = 99, |_, _| {}, |_| {}),
        ),
        (
            "names no preset",
            forged(&samples, 64, preset_bytes, |_, _| {}, |_| {}),
        ),
    ];
    for (want, bytes) in cases {
        let dir = tempfile::tempdir().unwrap();
        let (code, r) = capture(dir.path(), &bytes, &[]);
        assert_eq!(code, 2, "{want}: {r}");
        assert_eq!(r["complete"], false, "{want}");
        assert!(
            r["problems"].to_string().contains(want),
            "{want}: {}",
            r["problems"]
        );
        nothing_written(dir.path());
    }
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
    assert!(
        r["problems"]
            .to_string()
            .contains("of preset thesis-61810 seed 7, expected thesis-61810 seed 8"),
        "{}",
        r["problems"]
    );
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
    // With --json, a report on stdout as for every other failure.
    let out = Command::new(env!("CARGO_BIN_EXE_wearsim"))
        .args(["capture", "--json", "--input", "/nonexistent/serial.bin"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let r: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(r["complete"], false);
    assert!(
        r["problems"][0]
            .to_string()
            .contains("/nonexistent/serial.bin"),
        "{r}"
    );
}
