//! Issue 11 (5–9): hostile files and in-range settings that cannot run are refused with
//! exit 2 and a message naming the limit; nothing non-finite is ever printed; capture
//! reports duplicates, NaN samples and over-announced streams; an empty `rec.json` does not
//! shadow a record; an unwritable output directory is refused before any work.

use crate::support;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Output;
use support::{refused, s, wearsim};

use wearsim_frame as frame;

// --- MAT files -----------------------------------------------------------------------------

const HEADER_TEXT: &[u8] = b"MATLAB 5.0 MAT-file, Platform: hostile test";

fn header() -> Vec<u8> {
    let mut h = [b' '; 128];
    h[..HEADER_TEXT.len()].copy_from_slice(HEADER_TEXT);
    h[116..124].fill(0);
    h[124..126].copy_from_slice(&0x0100u16.to_le_bytes());
    h[126..128].copy_from_slice(b"IM");
    h.to_vec()
}

fn sub(out: &mut Vec<u8>, ty: u32, bytes: &[u8]) {
    out.extend_from_slice(&ty.to_le_bytes());
    out.extend_from_slice(&(bytes.len() as u32).to_le_bytes());
    out.extend_from_slice(bytes);
    out.resize(out.len().next_multiple_of(8), 0);
}

/// A `miMATRIX` element of `n` zero elements of MAT type `ty` (`width` bytes each, class
/// `class`), streamed through `w` (so a large one is never held in memory).
fn zero_matrix(w: &mut impl Write, name: &str, class: u32, ty: u32, width: usize, n: usize) {
    let mut head = vec![];
    sub(&mut head, 6, &[class as u8, 0, 0, 0, 0, 0, 0, 0]);
    let mut dims = vec![];
    dims.extend_from_slice(&(n as i32).to_le_bytes());
    dims.extend_from_slice(&1i32.to_le_bytes());
    sub(&mut head, 5, &dims);
    sub(&mut head, 1, name.as_bytes());
    let data = n * width;
    let body = head.len() + 8 + data.next_multiple_of(8);
    w.write_all(&14u32.to_le_bytes()).unwrap();
    w.write_all(&(body as u32).to_le_bytes()).unwrap();
    w.write_all(&head).unwrap();
    w.write_all(&ty.to_le_bytes()).unwrap();
    w.write_all(&(data as u32).to_le_bytes()).unwrap();
    let zeros = vec![0u8; 1 << 20];
    let mut left = data.next_multiple_of(8);
    while left > 0 {
        let k = left.min(zeros.len());
        w.write_all(&zeros[..k]).unwrap();
        left -= k;
    }
}

fn compressed(inner: impl FnOnce(&mut flate2::write::ZlibEncoder<Vec<u8>>)) -> Vec<u8> {
    let mut enc = flate2::write::ZlibEncoder::new(vec![], flate2::Compression::fast());
    inner(&mut enc);
    let z = enc.finish().unwrap();
    let mut out = vec![];
    out.extend_from_slice(&15u32.to_le_bytes());
    out.extend_from_slice(&(z.len() as u32).to_le_bytes());
    out.extend_from_slice(&z);
    out
}

fn analyze_mat(dir: &Path, name: &str, bytes: &[u8]) -> Output {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    wearsim(&[
        "analyze",
        s(&p),
        "--fs",
        "12000",
        "--rpm",
        "1797",
        "--bearing",
        "cwru-6205-de",
        "--json",
    ])
}

/// A compressed int8 array of 2²⁶ elements (64 MiB inflated, 512 MiB as f64): refused on
/// the per-file sample bound before the widening allocates.
#[test]
fn mat_widening_is_counted() {
    let dir = tempfile::tempdir().unwrap();
    let mut f = header();
    f.extend(compressed(|w| {
        zero_matrix(w, "X097_DE_time", 8, 1, 1, 1 << 26)
    }));
    assert!(f.len() < 1 << 20, "{} bytes", f.len());
    let o = analyze_mat(dir.path(), "97.mat", &f);
    refused(&o, &["too large", "samples", "per file"]);
}

/// A struct array with no fields and 2²⁴ elements in a 200-byte file (found by the `mat`
/// fuzz target: its elements take no bytes, so the byte check let it through and the reader
/// reserved 400 MB for the empty rows): refused on the per-file node budget.
#[test]
fn mat_fieldless_struct_elements_are_counted() {
    let mut body = vec![];
    sub(&mut body, 6, &[2, 0, 0, 0, 0, 0, 0, 0]); // mxSTRUCT_CLASS
    let mut dims = vec![];
    dims.extend_from_slice(&1i32.to_le_bytes());
    dims.extend_from_slice(&(1i32 << 24).to_le_bytes());
    sub(&mut body, 5, &dims);
    sub(&mut body, 1, b"bearing");
    sub(&mut body, 5, &32u32.to_le_bytes()); // field name length
    sub(&mut body, 1, &[]); // no field names
    let mut f = header();
    f.extend_from_slice(&14u32.to_le_bytes());
    f.extend_from_slice(&(body.len() as u32).to_le_bytes());
    f.extend_from_slice(&body);
    assert!(f.len() < 256, "{} bytes", f.len());
    let e = wearsim_host::io::mat::parse_mat_tree(&f, Path::new("s.mat"), &|_| true).unwrap_err();
    let msg = e.to_string();
    assert!(
        msg.contains("too large") && msg.contains("16777216 elements"),
        "{msg}"
    );
    let dir = tempfile::tempdir().unwrap();
    refused(
        &analyze_mat(dir.path(), "s.mat", &f),
        &["too large", "elements per MAT file"],
    );
}

/// A double "bomb" (2²⁶ doubles, 512 MiB inflated from ≈0.5 MB): refused on the per-file
/// decompressed budget.
#[test]
fn mat_decompressed_size_is_bounded_per_file() {
    let dir = tempfile::tempdir().unwrap();
    let mut f = header();
    f.extend(compressed(|w| {
        zero_matrix(w, "X097_DE_time", 6, 9, 8, 1 << 26)
    }));
    let o = analyze_mat(dir.path(), "97.mat", &f);
    refused(&o, &["too large", "decompressed per file"]);
}

/// Forty doubly compressed elements of 8 MiB each: the budget is per file, not per element.
#[test]
fn mat_many_compressed_elements_share_one_budget() {
    let dir = tempfile::tempdir().unwrap();
    let mut inner = vec![];
    {
        let mut w = flate2::write::ZlibEncoder::new(vec![], flate2::Compression::fast());
        zero_matrix(&mut w, "pad", 6, 9, 8, 1 << 20);
        let z = w.finish().unwrap();
        inner.extend_from_slice(&15u32.to_le_bytes());
        inner.extend_from_slice(&(z.len() as u32).to_le_bytes());
        inner.extend_from_slice(&z);
    }
    let outer = compressed(|w| w.write_all(&inner).unwrap());
    let mut f = header();
    for _ in 0..40 {
        f.extend_from_slice(&outer);
    }
    let o = analyze_mat(dir.path(), "97.mat", &f);
    refused(&o, &["too large", "decompressed per file"]);
}

/// An NPY record of 2²³ + 1 samples: refused by `analyze` naming the record limit, before
/// the analysis (≈14× the record in memory) starts.
#[test]
fn analysis_record_size_is_bounded() {
    let dir = tempfile::tempdir().unwrap();
    let n = (1usize << 23) + 1;
    let mut h = format!("{{'descr': '<f4', 'fortran_order': False, 'shape': ({n},), }}");
    while (10 + h.len() + 1) % 64 != 0 {
        h.push(' ');
    }
    h.push('\n');
    let p = dir.path().join("long.npy");
    let mut f = std::io::BufWriter::new(std::fs::File::create(&p).unwrap());
    f.write_all(b"\x93NUMPY\x01\x00").unwrap();
    f.write_all(&(h.len() as u16).to_le_bytes()).unwrap();
    f.write_all(h.as_bytes()).unwrap();
    for i in 0..n {
        f.write_all(&((i as f32) * 0.37).sin().to_le_bytes())
            .unwrap();
    }
    drop(f);
    let o = wearsim(&[
        "analyze",
        s(&p),
        "--fs",
        "20000",
        "--rpm",
        "1500",
        "--bearing",
        "thesis-61810",
    ]);
    refused(&o, &["too large", "8388608 samples"]);
}

// --- non-finite figures --------------------------------------------------------------------

/// A record near 1e200 (finite) gives no NaN/inf/null: it is refused naming the range.
#[test]
fn huge_but_finite_record_is_refused_not_nan() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("big.csv");
    let mut text = String::from("accel_m_s2\n");
    for i in 0..4096 {
        text.push_str(&format!("{:e}\n", 1e200 * ((i as f64) * 0.37).sin()));
    }
    std::fs::write(&p, text).unwrap();
    let o = wearsim(&[
        "analyze",
        s(&p),
        "--fs",
        "20000",
        "--rpm",
        "1500",
        "--bearing",
        "thesis-61810",
        "--json",
    ]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        !out.contains("null") && !out.contains("NaN") && !out.contains("inf"),
        "{out}"
    );
    refused(&o, &["analysable range"]);
}

#[test]
fn finite_guard_finds_nested_non_finite_numbers() {
    let v = serde_json::json!({"a": [1.0, {"b": 2.0}]});
    assert_eq!(wearsim_host::analysis::finite::first_non_finite(&v), None);
    let bad: Vec<Option<f64>> = vec![Some(1.0), Some(f64::INFINITY)];
    let (path, _) = wearsim_host::analysis::finite::first_non_finite(&bad).unwrap();
    assert_eq!(path, "[1]");
}

// --- in-range settings that cannot run -----------------------------------------------------

#[test]
fn settings_that_cannot_run_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    let o = wearsim(&[
        "simulate",
        "--fs",
        "1e6",
        "--duration",
        "600",
        "--out",
        s(&out),
    ]);
    refused(&o, &["in-memory limit", "33554432"]);
    assert!(!out.exists(), "work started before the refusal");
    // A rate out of its own range is told that range, not the memory it would need; a rate
    // too low for a transfer-path mode is told the rate it needs (stop 68: `allowed 100 ..=
    // 40`).
    for fs in ["1e9", "inf"] {
        let o = wearsim(&[
            "simulate",
            "--fs",
            fs,
            "--duration",
            "0.01",
            "--out",
            s(&out),
        ]);
        refused(&o, &["fs = ", "100 ..= 1000000"]);
    }
    let o = wearsim(&[
        "simulate",
        "--preset",
        "cwru-6205-de",
        "--duration",
        "0.05",
        "--fs",
        "100",
        "--effect",
        "transfer-path:f1=100",
        "--out",
        s(&out),
    ]);
    refused(&o, &["transfer-path.f1", "fs must be at least 250 Hz"]);
    assert!(!out.exists(), "work started before the refusal");

    for (i, (toml, field)) in [
        ("[bearing]\nroller_length = nan\n", "roller_length"),
        ("[bearing]\nroller_length = inf\n", "roller_length"),
        ("[bearing]\nroller_length = -1.0\n", "roller_length"),
        ("[material]\nyield_strength = -1.0\n", "yield_strength"),
        ("[life]\nrunning_in = 0.5\n", "running_in"),
        ("[life]\nslip = 7.0\n", "slip"),
        // A speed-table row longer than [time_s, shaft_hz] (its extra values were dropped).
        (
            "[speed]\ntable = [[0.0, 10.0, 5.0], [1.0, 20.0]]\n",
            "row 0 has 3 values",
        ),
    ]
    .iter()
    .enumerate()
    {
        let p = dir.path().join(format!("c{i}.toml"));
        std::fs::write(&p, format!("preset = \"thesis-61810\"\n{toml}")).unwrap();
        let o = wearsim(&["simulate", "--config", s(&p), "--out", s(&out)]);
        refused(&o, &[field]);
    }
}

/// Issue 11 (7): the largest in-range imbalance with the fastest speed fluctuation either
/// runs with finite samples (a finer internal step, thesis-61810) or is refused up front
/// naming the field that sets the step (cwru-6205-de): never exit 1 after a non-finite sample.
#[test]
fn largest_imbalance_with_fastest_fluctuation_runs_or_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let fluct = "speed-fluctuation:amplitude=0.1,freq_hz=1000,jitter=0.1,jitter_hz=1000";
    for (preset, runs) in [("thesis-61810", true), ("cwru-6205-de", false)] {
        let p = dir.path().join(format!("{preset}.toml"));
        let toml = format!("preset = \"{preset}\"\n[imbalance]\nmass = 10\nradius = 2\n");
        std::fs::write(&p, toml).unwrap();
        let out = dir.path().join(preset);
        let args = ["simulate", "--config", s(&p), "--duration", "0.05"];
        let o = wearsim(&[&args[..], &["--effect", fluct, "--out", s(&out)]].concat());
        if runs {
            let msg = String::from_utf8_lossy(&o.stderr);
            assert!(o.status.success(), "{preset}: {msg}");
            let csv = std::fs::read_to_string(out.join("simulate.csv")).unwrap();
            let lines = csv.lines().skip(1).filter(|l| !l.is_empty());
            let n = lines
                .inspect(|l| assert!(!l.contains("NaN") && !l.contains("inf"), "{l}"))
                .count();
            assert!(n >= 900, "{preset}: {n} rows");
        } else {
            refused(&o, &["speed-fluctuation.freq_hz", "internal rate"]);
            assert!(
                !out.join("simulate.csv").exists(),
                "{preset}: output written"
            );
        }
    }
}

/// Issue 11 (5): CSV, WAV and NPY readers refuse a record over 2²³ samples per channel before
/// allocating it (they were bounded only by the file's size): an 8-bit WAV and an int8 NPY
/// of 2²³ + 1 samples (8 MiB each) exit 2 naming the limit.
#[test]
fn binary_records_over_the_sample_limit_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let n: u32 = (1 << 23) + 1;
    // 8-bit mono PCM WAV at 20 kHz.
    let mut wav = Vec::new();
    wav.extend_from_slice(b"RIFF");
    wav.extend_from_slice(&(36 + n).to_le_bytes());
    wav.extend_from_slice(b"WAVEfmt ");
    wav.extend_from_slice(&16u32.to_le_bytes());
    wav.extend_from_slice(&1u16.to_le_bytes()); // PCM
    wav.extend_from_slice(&1u16.to_le_bytes()); // mono
    wav.extend_from_slice(&20_000u32.to_le_bytes());
    wav.extend_from_slice(&20_000u32.to_le_bytes());
    wav.extend_from_slice(&1u16.to_le_bytes());
    wav.extend_from_slice(&8u16.to_le_bytes());
    wav.extend_from_slice(b"data");
    wav.extend_from_slice(&n.to_le_bytes());
    wav.resize(wav.len() + n as usize, 128);
    // int8 NPY of shape (n,).
    let mut head = format!("{{'descr': '|i1', 'fortran_order': False, 'shape': ({n},), }}");
    while (10 + head.len() + 1) % 64 != 0 {
        head.push(' ');
    }
    head.push('\n');
    let mut npy = b"\x93NUMPY\x01\x00".to_vec();
    npy.extend_from_slice(&(head.len() as u16).to_le_bytes());
    npy.extend_from_slice(head.as_bytes());
    npy.resize(npy.len() + n as usize, 1);
    for (name, bytes) in [("big.wav", wav), ("big.npy", npy)] {
        let p = dir.path().join(name);
        std::fs::write(&p, bytes).unwrap();
        // The reader itself refuses (before, it returned the record and only `analyze`
        // refused it, after the allocation).
        let opts = wearsim_host::io::ReadOptions {
            fs: Some(20_000.0),
            ..Default::default()
        };
        match wearsim_host::io::read_any(&p, &opts) {
            Err(wearsim_host::io::error::IoError::TooLarge { what, .. }) => {
                assert!(what.contains("8388609"), "{name}: {what}")
            }
            other => panic!("{name}: {:?}", other.map(|r| r.samples.len())),
        }
        let o = wearsim(&["analyze", s(&p), "--fs", "20000", "--rpm", "1800", "--json"]);
        refused(&o, &["too large", "8388608 samples"]);
    }
}

// --- capture -------------------------------------------------------------------------------

struct Stream {
    announce: u32,
    frames: Vec<(u32, u32, Vec<f32>)>, // seq, first sample, samples
}

fn encode(st: &Stream) -> Vec<u8> {
    let mut out = vec![];
    let mut buf = [0u8; frame::MAX_FRAME];
    let mut preset = [0u8; 24];
    preset[..12].copy_from_slice(b"thesis-61810");
    let start = frame::StartInfo {
        preset,
        seed: 7,
        rate_hz: 20_000.0,
        oversample: 2,
        total_samples: st.announce,
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
    let mut last = 0;
    let mut total = 0;
    for (seq, first, x) in &st.frames {
        let payload: Vec<u8> = x.iter().flat_map(|v| v.to_le_bytes()).collect();
        let h = frame::Header {
            kind: frame::Kind::Data,
            format: frame::Format::F32,
            flags: 0,
            seq: *seq,
            first_sample: *first,
            overruns: 0,
            scale: 1.0,
        };
        let n = frame::encode(&h, &payload, &mut buf).unwrap();
        out.extend_from_slice(&buf[..n]);
        last = *seq;
        total += x.len();
    }
    let end = frame::EndInfo {
        total_samples: total as u32,
        data_frames: st.frames.len() as u32,
        overruns: 0,
        busy_ticks: 1000,
        tick_hz: 25_000_000,
        measured_samples: 10,
        reserved: 0,
    };
    let n = frame::encode(&ctl(frame::Kind::End, last + 1), &end.to_bytes(), &mut buf).unwrap();
    out.extend_from_slice(&buf[..n]);
    out
}

fn capture(dir: &Path, bytes: &[u8]) -> (Output, serde_json::Value) {
    let input = dir.join("serial.bin");
    std::fs::write(&input, bytes).unwrap();
    let out: PathBuf = dir.join("out");
    let o = wearsim(&["capture", "--json", "--input", s(&input), "--out", s(&out)]);
    let v = serde_json::from_slice(&o.stdout).unwrap_or_else(|e| {
        panic!(
            "no JSON report ({e}): {}",
            String::from_utf8_lossy(&o.stderr)
        )
    });
    (o, v)
}

fn ramp(from: usize, n: usize) -> Vec<f32> {
    (from..from + n).map(|i| (i as f32 * 0.01).sin()).collect()
}

#[test]
fn capture_reports_duplicates_nan_and_short_streams() {
    let dir = tempfile::tempdir().unwrap();
    // A repeated frame: a duplicate, not 4294967295 missing frames.
    let dup = Stream {
        announce: 192,
        frames: vec![
            (1, 0, ramp(0, 64)),
            (2, 64, ramp(64, 64)),
            (2, 64, ramp(64, 64)),
            (3, 128, ramp(128, 64)),
        ],
    };
    let (o, r) = capture(dir.path(), &encode(&dup));
    assert_ne!(o.status.code(), Some(0));
    assert_eq!(r["duplicate_frames"], 1, "{r}");
    assert_eq!(r["missing_frames"], 0, "{r}");
    assert_eq!(r["complete"], false);
    assert!(r.to_string().contains("repeated"), "{r}");

    // CRC-valid NaN samples: the stream is blamed (frame and sample), a report is printed.
    let mut x = ramp(0, 64);
    x[5] = f32::NAN;
    let nan = Stream {
        announce: 64,
        frames: vec![(1, 0, x)],
    };
    let (o, r) = capture(dir.path(), &encode(&nan));
    assert_eq!(o.status.code(), Some(2));
    let problems = r["problems"].to_string();
    assert!(
        problems.contains("non-finite") && problems.contains("sample index 5"),
        "{problems}"
    );
    assert!(!dir.path().join("out").join("capture.json").exists());

    // A start frame announcing 100 000 samples when 640 arrive.
    let short = Stream {
        announce: 100_000,
        frames: (0..10)
            .map(|k| (k + 1, k * 64, ramp(k as usize * 64, 64)))
            .collect(),
    };
    let (o, r) = capture(dir.path(), &encode(&short));
    assert_ne!(o.status.code(), Some(0));
    assert_eq!(r["complete"], false);
    assert!(
        r["problems"].to_string().contains("announces 100000"),
        "{r}"
    );
}

/// A flood of sync words: bounded report (the first 100 spans listed, all counted).
#[test]
fn capture_sync_flood_is_bounded() {
    let dir = tempfile::tempdir().unwrap();
    let flood: Vec<u8> = frame::SYNC.iter().copied().cycle().take(16 << 20).collect();
    let (o, r) = capture(dir.path(), &flood);
    assert_eq!(o.status.code(), Some(2));
    assert!(r["corrupt"].as_array().unwrap().len() <= 100);
    assert!(r["corrupt_bytes"].as_u64().unwrap() > 1 << 20, "{r}");
    assert!(r["problems"].as_array().unwrap().len() <= 101);
}

// --- consistency ---------------------------------------------------------------------------

/// `wearsim analyze rec.csv --json > rec.json`: the empty `rec.json` the shell creates is
/// not read as the record's sidecar.
#[test]
fn empty_json_does_not_shadow_the_record() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("sim");
    let o = wearsim(&["simulate", "--duration", "0.5", "--out", s(&out)]);
    assert!(o.status.success());
    let csv = out.join("simulate.csv");
    let rec = dir.path().join("rec.csv");
    std::fs::copy(&csv, &rec).unwrap();
    std::fs::write(dir.path().join("rec.json"), "").unwrap();
    let o = wearsim(&[
        "analyze",
        s(&rec),
        "--fs",
        "20000",
        "--rpm",
        "1500",
        "--bearing",
        "thesis-61810",
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stderr).contains("empty"));
}

/// An output directory that cannot be created or written (here: below a regular file, so
/// that it holds for root too) is refused (exit 2, naming it) before any work, by every
/// command that writes one.
#[test]
fn unwritable_output_directory_is_refused_first() {
    let dir = tempfile::tempdir().unwrap();
    let blocker = dir.path().join("blocker");
    std::fs::write(&blocker, "not a directory").unwrap();
    let sub = blocker.join("x");
    let rec = dir.path().join("r.csv");
    let text: String = (0..4096)
        .map(|i| format!("{}\n", (i as f64 * 0.3).sin()))
        .collect();
    std::fs::write(&rec, format!("a\n{text}")).unwrap();
    let analyze = |flag: &'static str, to: &Path| -> Output {
        let args = [
            "analyze",
            s(&rec),
            "--fs",
            "1000",
            "--rpm",
            "600",
            "--bearing",
            "thesis-61810",
            flag,
            s(to),
        ];
        wearsim(&args)
    };
    for args in [
        vec!["simulate", "--out", s(&sub)],
        vec!["life", "--dense", "--cycles", "1e6", "--out", s(&sub)],
        vec!["life", "--cycles", "1e6", "--out", s(&sub)],
    ] {
        let o = wearsim(&args);
        refused(&o, &["blocker"]);
    }
    refused(&analyze("--plot", &sub), &["blocker"]);
    // A batch table named as an existing directory is refused before any record is read
    // (it was exit 1 after the analysis, when the table could not replace the directory).
    let o = analyze("--out", dir.path());
    refused(&o, &["is a directory"]);
    assert!(
        !String::from_utf8_lossy(&o.stderr).contains("1 files"),
        "a record was analysed before the refusal"
    );
}

/// A MATLAB 7.3 file (an HDF5 container behind a 512-byte MAT header) is refused as such,
/// with the way to a readable file, not as a corrupt level-5 file.
#[test]
fn mat_v73_hdf5_is_refused_with_the_way_out() {
    let mut f = vec![b' '; 512];
    let text =
        b"MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: Mon Nov 23 2026 HDF5 schema 1.00 .";
    f[..text.len()].copy_from_slice(text);
    f.extend_from_slice(b"\x89HDF\r\n\x1a\n");
    f.extend_from_slice(&[0u8; 64]);
    let dir = tempfile::tempdir().unwrap();
    refused(
        &analyze_mat(dir.path(), "v73.mat", &f),
        &["MATLAB 7.3 (HDF5)", "-v7"],
    );
}

/// A negative number after a flag reaches that flag's range check (exit 2, naming the flag)
/// in every subcommand that takes numbers; before, clap read `-1` as an unknown argument and
/// the message named no field (`unexpected argument '-1'`).
#[test]
fn negative_values_are_told_their_flags_range() {
    let o = wearsim(&["bench", "--seconds", "-1"]);
    refused(&o, &["seconds = -1", "1 ..= 600"]);
    let o = wearsim(&["gap-validate", "--noise", "-0.1"]);
    refused(&o, &["--noise -0.1", "0..=0.5"]);
    let o = wearsim(&["gap-validate", "--half", "-1"]);
    refused(&o, &["--half -1", "0.5..=10"]);
    // An unsigned count is told by clap that its value is invalid, naming the flag.
    let o = wearsim(&["gap-validate", "--trials", "-1"]);
    refused(&o, &["'-1'", "--trials"]);
}

/// `cwru-benchmark` on a folder whose record cannot be read reports it as a row with its
/// error and exits 2 (it was exit 0 with every such record counted as a wrong call); a bad
/// `--resample` and an unwritable `--markdown` are refused before any record is read.
#[test]
fn cwru_benchmark_says_when_a_record_could_not_be_read() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("cwru");
    std::fs::create_dir(&data).unwrap();
    std::fs::write(data.join("12k_Drive_End_IR007_0_105.mat"), "garbage\n").unwrap();
    let d = s(dir.path());
    let o = wearsim(&["cwru-benchmark", "--data", d, "--no-variants", "--json"]);
    refused(&o, &["1 of 1 records could not be read"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("the report is whole");
    assert!(v["files"][0]["error"].is_string(), "{v}");
    for r in ["999", "nan"] {
        let o = wearsim(&["cwru-benchmark", "--data", d, "--resample", r]);
        refused(&o, &["--resample", "1000..=1e6"]);
        assert!(o.stdout.is_empty(), "work started before the refusal");
    }
    let o = wearsim(&["cwru-benchmark", "--data", d, "--markdown", d]);
    refused(&o, &["--markdown", "is a directory"]);
    assert!(o.stdout.is_empty(), "work started before the refusal");
}

/// `gap-validate` refuses up front what it would otherwise run wrongly or skip without a
/// word: an effect listed twice (was exit 1), `--pairs`/`--triples` with fewer effects than
/// they withhold (were skipped, `"pairs": null`), `--jobs` beyond 256 (as `life --threads`).
#[test]
fn gap_validate_refuses_requests_it_would_skip() {
    for (args, needles) in [
        (
            vec!["--effects", "slip,slip"],
            vec!["`slip` is listed twice"],
        ),
        (
            vec!["--effects", "slip", "--pairs", "1"],
            vec!["--pairs 1", "lists 1"],
        ),
        (
            vec!["--effects", "slip,sensor", "--triples", "1"],
            vec!["--triples 1", "at least 3"],
        ),
        (vec!["--jobs", "100000"], vec!["--jobs 100000", "1 ..= 256"]),
    ] {
        let mut a = vec!["gap-validate", "--trials", "1", "--half", "0.5"];
        a.extend(args);
        refused(&wearsim(&a), &needles);
    }
}

/// `bench --config` is the lanes' scenario: without `--lanes`, or beside `--preset`, it is
/// refused (it was ignored, and the preset timed instead of the file).
#[test]
fn bench_refuses_a_config_it_would_ignore() {
    let o = wearsim(&["bench", "--config", "missing.toml", "--seconds", "1"]);
    refused(&o, &["--lanes"]);
    let o = wearsim(&[
        "bench",
        "--config",
        "x.toml",
        "--preset",
        "cwru-6205-de",
        "--lanes",
        "2",
    ]);
    refused(&o, &["--config", "--preset"]);
}
