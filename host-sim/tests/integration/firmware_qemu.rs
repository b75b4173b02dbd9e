//! The firmware stub in QEMU: builds `firmware-stub/` for the Cortex-M4F (`mps2-an386`) and
//! the Cortex-M3 (`mps2-an385`), runs it, decodes the UART stream with `wearsim capture`'s
//! decoder and the defmt log with `defmt-decoder` (through `fwtool`), and checks the samples
//! against host runs of the same scenario and seed.
//!
//! Needs `qemu-system-arm` and the rustup targets `thumbv7em-none-eabihf` and
//! `thumbv7m-none-eabi`. Without them every test prints a skip message and passes, except
//! when `CI=true`, where it fails. Every QEMU run is killed after [`QEMU_TIMEOUT`].

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::{Mutex, OnceLock};
use std::time::{Duration, Instant};

use wearsim_host::capture;

/// Longest a QEMU run may take before it is killed (a hang, not a slow run: the longest run
/// here executes ~0.4 G guest instructions, a few seconds).
const QEMU_TIMEOUT: Duration = Duration::from_secs(300);
const M4F: &str = "thumbv7em-none-eabihf";
const M3: &str = "thumbv7m-none-eabi";
const PRESET: &str = "thesis-61810";
const SEED: u64 = 1;
const SAMPLES: usize = 4000;

fn fw_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../firmware-stub")
}

/// `Some(reason)` when the tools are missing; panics under `CI=true`.
fn missing_tools() -> Option<String> {
    static CHECK: OnceLock<Option<String>> = OnceLock::new();
    let r = CHECK.get_or_init(|| {
        let qemu = Command::new("qemu-system-arm")
            .arg("--version")
            .output()
            .map(|o| o.status.success())
            .unwrap_or(false);
        if !qemu {
            return Some("qemu-system-arm not found".into());
        }
        let targets = Command::new("rustup")
            .args(["target", "list", "--installed"])
            .output()
            .map(|o| String::from_utf8_lossy(&o.stdout).to_string())
            .unwrap_or_default();
        for t in [M4F, M3] {
            if !targets.lines().any(|l| l.trim() == t) {
                return Some(format!("rustup target {t} not installed"));
            }
        }
        None
    });
    if let Some(why) = r {
        if std::env::var("CI").as_deref() == Ok("true") {
            panic!("firmware tests cannot run under CI=true: {why}");
        }
        eprintln!("SKIP firmware QEMU test: {why}");
    }
    r.clone()
}

fn cargo(args: &[&str]) {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = Command::new(cargo)
        .args(args)
        .current_dir(fw_dir())
        .env_remove("RUSTFLAGS")
        .env_remove("CARGO_ENCODED_RUSTFLAGS")
        .env_remove("CARGO_BUILD_TARGET")
        .env("CARGO_TARGET_DIR", fw_dir().join("target"))
        .output()
        .expect("run cargo");
    assert!(
        out.status.success(),
        "cargo {args:?} failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

fn host_triple() -> String {
    let out = Command::new("rustc")
        .arg("-vV")
        .output()
        .expect("rustc -vV");
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .find_map(|l| l.strip_prefix("host: ").map(str::to_string))
        .expect("host triple")
}

/// Builds (once per test binary) and returns the ELF path of a firmware build.
fn firmware(target: &str, features: &str) -> PathBuf {
    static BUILT: Mutex<Vec<(String, String)>> = Mutex::new(Vec::new());
    let mut built = BUILT.lock().unwrap_or_else(|e| e.into_inner());
    // Each feature set gets its own target directory so that builds do not evict each other.
    let dir = if features.is_empty() {
        fw_dir().join("target")
    } else {
        fw_dir().join("target").join(features.replace(',', "-"))
    };
    let key = (target.to_string(), features.to_string());
    if !built.contains(&key) {
        let d = dir.display().to_string();
        let mut args = vec!["build", "--release", "-p", "wearsim-fw", "--target", target];
        args.extend(["--target-dir", &d]);
        if !features.is_empty() {
            args.extend(["--features", features]);
        }
        cargo(&args);
        built.push(key);
    }
    dir.join(target).join("release/wearsim-fw")
}

fn fwtool() -> PathBuf {
    static TOOL: OnceLock<PathBuf> = OnceLock::new();
    TOOL.get_or_init(|| {
        let host = host_triple();
        cargo(&[
            "build",
            "--profile",
            "host",
            "-p",
            "wearsim-fwtool",
            "--target",
            &host,
        ]);
        fw_dir().join("target").join(host).join("host/fwtool")
    })
    .clone()
}

struct Run {
    serial: Vec<u8>,
    defmt: Vec<String>,
    ok: bool,
}

/// Runs an ELF in QEMU with deterministic instruction counting; kills it after the timeout.
fn qemu(machine: &str, elf: &Path) -> Run {
    let dir = tempfile::tempdir().unwrap();
    let serial = dir.path().join("serial.bin");
    let log = dir.path().join("defmt.bin");
    let mut child = Command::new("qemu-system-arm")
        .args(["-M", machine, "-display", "none", "-monitor", "none"])
        .args(["-icount", "shift=0,sleep=off", "-kernel"])
        .arg(elf)
        .args(["-semihosting-config", "enable=on,target=native", "-serial"])
        .arg(format!("file:{}", serial.display()))
        .stdin(Stdio::null())
        .stdout(std::fs::File::create(&log).unwrap())
        .stderr(Stdio::inherit())
        .spawn()
        .expect("start qemu-system-arm");
    let deadline = Instant::now() + QEMU_TIMEOUT;
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            let _ = child.wait();
            panic!(
                "QEMU {machine} {} hung: killed after {QEMU_TIMEOUT:?}",
                elf.display()
            );
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let out = Command::new(fwtool())
        .arg("defmt")
        .arg(elf)
        .arg(&log)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "defmt decoding failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    Run {
        serial: std::fs::read(&serial).unwrap_or_default(),
        defmt: String::from_utf8_lossy(&out.stdout)
            .lines()
            .map(str::to_string)
            .collect(),
        ok: status.success(),
    }
}

/// Host f32 reference samples (wire format f32) from the same f32 core build.
fn reference_f32(n: usize) -> Vec<f32> {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("ref.bin");
    let st = Command::new(fwtool())
        .args(["reference", PRESET, &SEED.to_string(), &n.to_string()])
        .arg(&out)
        .status()
        .unwrap();
    assert!(st.success());
    std::fs::read(&out)
        .unwrap()
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

fn check_stream(run: &Run, flavour: &str) -> capture::Decoded {
    assert!(run.ok, "firmware exit code: failure; log {:#?}", run.defmt);
    let d = capture::decode("qemu", &run.serial);
    let r = &d.report;
    assert!(r.complete, "incomplete stream: {:#?}", r.problems);
    assert_eq!(r.samples, SAMPLES);
    assert_eq!(r.missing_frames, 0);
    assert_eq!(r.missing_samples, 0);
    assert!(r.corrupt.is_empty() && !r.truncated);
    assert_eq!(r.tx_drops, Some(0));
    assert_eq!(r.preset.as_deref(), Some(PRESET));
    assert_eq!(r.seed, Some(SEED));
    assert_eq!(r.flavour.as_deref(), Some(flavour));
    assert!(
        run.defmt
            .iter()
            .any(|l| l.starts_with("INFO scenario start: preset=thesis-61810 seed=1")),
        "{:#?}",
        run.defmt
    );
    d
}

fn bit_identical(d: &capture::Decoded, reference: &[f32]) {
    let mismatches: Vec<usize> = d
        .accel
        .iter()
        .zip(reference)
        .enumerate()
        .filter(|(_, (a, b))| (**a as f32).to_bits() != b.to_bits())
        .map(|(i, _)| i)
        .take(5)
        .collect();
    assert!(
        mismatches.is_empty(),
        "target and host f32 differ at {mismatches:?}"
    );
}

#[test]
fn m4f_stream_is_complete_and_bit_identical_to_host_f32() {
    if missing_tools().is_some() {
        return;
    }
    let run = qemu("mps2-an386", &firmware(M4F, ""));
    let d = check_stream(&run, "m4f-hardfloat");
    assert_eq!(d.report.overruns, 0, "the M4F keeps up with 20 kHz");
    bit_identical(&d, &reference_f32(SAMPLES));
    // Against the f64 host: within the derived tolerance over the first 200 samples, RMS
    // within 2 % over the record.
    let c = capture::compare(&d.accel, PRESET, SEED, capture::F64_REL_TOLERANCE).unwrap();
    assert!(c.pass, "{c:#?}");
}

#[test]
fn m3_softfloat_stream_is_bit_identical_and_reports_its_overruns() {
    if missing_tools().is_some() {
        return;
    }
    let run = qemu("mps2-an385", &firmware(M3, ""));
    let d = check_stream(&run, "m3-softfloat");
    bit_identical(&d, &reference_f32(SAMPLES));
    // ~60 k instructions per sample do not fit the 50 k of a 20 kHz period at 1 GHz virtual:
    // the missed deadlines must be counted in the frames and logged, never silent.
    assert!(d.report.overruns > 0);
    assert!(
        run.defmt.iter().any(|l| l.starts_with("WARN overrun:")),
        "{:#?}",
        run.defmt
    );
    let end = run
        .defmt
        .iter()
        .find(|l| l.starts_with("INFO scenario end:"))
        .expect("end log");
    assert!(
        end.contains(&format!("overruns={}", d.report.overruns)),
        "{end}"
    );
    // The overrun warnings come from the main loop, never from inside another log line: the
    // logger (fw/src/log.rs) dropped no frame.
    assert!(end.contains("log_frames_dropped=0"), "{end}");
}

#[test]
fn m3_fixed_point_counts_match_the_host_within_one_lsb() {
    if missing_tools().is_some() {
        return;
    }
    let run = qemu("mps2-an385", &firmware(M3, "i16-stream"));
    let d = check_stream(&run, "m3-softfloat");
    assert_eq!(d.report.format.as_deref(), Some("i16"));
    // Counts are Q1.15 of ±16 g: host f32 counts must agree exactly; the f64 host within the
    // f64 tolerance plus one LSB of quantisation.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("ref16.bin");
    let st = Command::new(fwtool())
        .args(["reference", PRESET, &SEED.to_string(), &SAMPLES.to_string()])
        .arg(&out)
        .args(["i16", "16"])
        .status()
        .unwrap();
    assert!(st.success());
    let lsb = wearsim_core::real::STANDARD_GRAVITY * 16.0 / 32768.0;
    let host16: Vec<f64> = std::fs::read(&out)
        .unwrap()
        .chunks_exact(2)
        .map(|c| i16::from_le_bytes([c[0], c[1]]) as f64 * lsb)
        .collect();
    let max_diff = d
        .accel
        .iter()
        .zip(&host16)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(max_diff < 1e-3 * lsb, "counts differ from host f32 counts");
    let c = capture::compare(&d.accel, PRESET, SEED, capture::F64_REL_TOLERANCE).unwrap();
    assert!(c.max_abs_error <= c.tolerance * c.host_rms + lsb, "{c:#?}");
}

#[test]
fn accelerated_life_logs_its_stage_transitions_in_order() {
    if missing_tools().is_some() {
        return;
    }
    // The firmware runs the core's stress-driven wear (Material::ACCELERATED): transitions
    // come from the contact loads it measures, not from a schedule.
    let run = qemu("mps2-an386", &firmware(M4F, "life"));
    assert!(run.ok, "{:#?}", run.defmt);
    let stages: Vec<&str> = run
        .defmt
        .iter()
        .filter_map(|l| l.strip_prefix("INFO stage transition: "))
        .collect();
    assert!(stages.len() >= 5, "{:#?}", run.defmt);
    let mut last = (None::<usize>, None::<u32>);
    for line in &stages {
        let mut words = line.split(' ');
        let idx: usize = words.next().and_then(|w| w.parse().ok()).unwrap();
        let name = words.next().unwrap();
        assert_eq!(wearsim_core::wear::Stage::ALL[idx].name(), name, "{line}");
        let at: u32 = line
            .split(" at sample ")
            .nth(1)
            .and_then(|s| s.split(' ').next())
            .and_then(|s| s.parse().ok())
            .unwrap();
        if let (Some(pi), Some(pa)) = last {
            assert!(idx > pi, "stage order violated: {line} after index {pi}");
            assert!(at >= pa, "{line} before sample {pa}");
        }
        last = (Some(idx), Some(at));
    }
    assert!(
        stages.last().unwrap().starts_with("9 failure"),
        "{stages:#?}"
    );
    // The stream carries the whole scenario.
    let d = capture::decode("qemu", &run.serial);
    assert!(d.report.complete, "{:#?}", d.report.problems);
}

#[test]
fn register_interface_gives_identity_config_and_samples_through_the_driver() {
    if missing_tools().is_some() {
        return;
    }
    // The firmware runs the unmodified ism330dhcx driver against the register model at boot
    // and logs what the driver read; the host recomputes it.
    let run = qemu("mps2-an386", &firmware(M4F, ""));
    assert!(run.ok);
    assert!(
        run.defmt
            .iter()
            .any(|l| l == "INFO sensor: ism330dhcx who_am_i ok, fs=16g odr_hz=6667.0"),
        "{:#?}",
        run.defmt
    );
    let reference = reference_f32(1000);
    let scale = wearsim_core::sensor::SensorScale {
        full_scale_g: 16.0,
        bits: 16,
    };
    let lsb = 16.0 * 9.80665 / 32768.0;
    let mut seen = vec![];
    for l in &run.defmt {
        let Some(rest) = l.strip_prefix("INFO sensor sample ") else {
            continue;
        };
        // "<index>: z_counts=<c> z_m_s2=<a>"
        let (idx, rest) = rest.split_once(": z_counts=").unwrap();
        let (counts, ms2) = rest.split_once(" z_m_s2=").unwrap();
        let (idx, counts, ms2): (usize, i16, f64) = (
            idx.parse().unwrap(),
            counts.parse().unwrap(),
            ms2.parse().unwrap(),
        );
        let want = reference[idx];
        assert_eq!(counts, scale.counts(want as f64), "sample {idx}");
        assert!(
            (ms2 - want as f64).abs() <= 1e-3 * (want as f64).abs() + 1.5 * lsb,
            "sample {idx}: driver {ms2} m/s^2, model {want}"
        );
        seen.push((idx, counts));
    }
    assert_eq!(seen.len(), 8, "{:#?}", run.defmt);
    // 20 kHz / 6667 Hz: every third simulator sample.
    assert!(seen.windows(2).all(|w| w[1].0 == w[0].0 + 3));
    assert!(
        seen.iter().any(|(_, c)| c.unsigned_abs() > 1000),
        "{seen:?}"
    );
    let fifo = format!("INFO sensor fifo: 8 words, first z_counts={}", seen[0].1);
    assert!(run.defmt.contains(&fifo), "{:#?}", run.defmt);
}

#[test]
fn m4f_ram_and_flash_within_limits() {
    if missing_tools().is_some() {
        return;
    }
    let elf = firmware(M4F, "");
    let out = Command::new(fwtool())
        .args(["size"])
        .arg(&elf)
        .arg("--json")
        .output()
        .unwrap();
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let ram = v["ram_bytes"].as_u64().unwrap();
    let flash = v["flash_bytes"].as_u64().unwrap();
    assert!(ram > 1000 && ram <= 32 * 1024, "static RAM {ram} bytes");
    assert!(flash > 10_000 && flash <= 128 * 1024, "flash {flash} bytes");
}

/// The target: ≤ 4000 instructions per output sample on the M4F, so that an 80 MHz
/// part sustains 20 kHz (measured 3845; see docs/firmware.md). A regression fails CI.
#[test]
fn m4f_instructions_per_sample_at_most_4000() {
    if missing_tools().is_some() {
        return;
    }
    let run = qemu("mps2-an386", &firmware(M4F, ""));
    let d = capture::decode("qemu", &run.serial);
    let ips = d.report.instructions_per_sample.expect("end frame");
    assert!(ips <= 4000.0, "{ips:.0} instructions per sample");
}

#[test]
fn budget_is_measured_deterministically() {
    if missing_tools().is_some() {
        return;
    }
    // Two runs of the same ELF under -icount give the same instruction count, and the count
    // is in a plausible range for the model (so the measurement is not vacuous).
    let elf = firmware(M4F, "");
    let a = capture::decode("qemu", &qemu("mps2-an386", &elf).serial);
    let b = capture::decode("qemu", &qemu("mps2-an386", &elf).serial);
    let (ia, ib) = (
        a.report.instructions_per_sample.unwrap(),
        b.report.instructions_per_sample.unwrap(),
    );
    assert_eq!(ia, ib);
    assert!((1000.0..20_000.0).contains(&ia), "{ia}");
}

#[test]
fn firmware_workspace_host_tests_pass() {
    if missing_tools().is_some() {
        return;
    }
    let host = host_triple();
    cargo(&[
        "test",
        "--profile",
        "host",
        "-p",
        "wearsim-frame",
        "-p",
        "wearsim-vsensor",
        "--target",
        &host,
    ]);
}
