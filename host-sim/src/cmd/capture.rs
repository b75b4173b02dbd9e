//! `wearsim capture`: arguments, the report printed for a human or as JSON, and the
//! handler that decodes, compares and writes only a complete stream
//! ([`crate::capture`] holds the decoding and comparison).

use std::path::PathBuf;

use clap::Args;
use serde_json::json;

use crate::capture::{
    compare, decode, read_input, CaptureError, CaptureReport, Decoded, F64_REL_TOLERANCE,
};

/// `wearsim capture` arguments.
#[derive(Debug, Clone, Args)]
pub struct CaptureArgs {
    /// Captured stream: a file written by QEMU `-serial file:PATH`, or a serial device
    /// (read until the end frame arrives).
    #[arg(long)]
    pub input: PathBuf,
    /// Output directory for capture.csv / capture.wav / capture.json.
    #[arg(long, default_value = "wearsim-out")]
    pub out: PathBuf,
    /// Print the report as JSON on stdout.
    #[arg(long)]
    pub json: bool,
    /// Compare with a host (f64) run of `--preset` with this seed.
    #[arg(long, requires = "preset")]
    pub expect_seed: Option<u64>,
    /// Preset of the host run to compare with (see `wearsim presets`).
    #[arg(long, requires = "expect_seed")]
    pub preset: Option<String>,
    /// Largest difference over the first 200 samples, relative to the host RMS over them.
    #[arg(long, default_value_t = F64_REL_TOLERANCE)]
    pub tolerance: f64,
}

fn print_report(
    r: &CaptureReport,
    files: Option<&crate::io::write::OutputSet>,
    json: bool,
) -> Result<(), CaptureError> {
    let failed = |e: String| CaptureError::Write(format!("printing the report: {e}"));
    if json {
        let mut v = serde_json::to_value(r).map_err(|e| failed(e.to_string()))?;
        if let (Some(f), Some(o)) = (files, v.as_object_mut()) {
            o.insert(
                "files".into(),
                json!({"csv": f.csv, "wav": f.wav, "json": f.json}),
            );
        }
        let text = serde_json::to_string_pretty(&v).map_err(|e| failed(e.to_string()))?;
        println!("{text}");
        return Ok(());
    }
    println!(
        "capture {}: {} bytes, {} valid frames ({} data), {} samples at {} Hz, preset {} seed {}, {}",
        r.input,
        r.bytes,
        r.valid_frames,
        r.data_frames,
        r.samples,
        r.rate_hz.map(|x| x.to_string()).unwrap_or("?".into()),
        r.preset.as_deref().unwrap_or("?"),
        r.seed.map(|x| x.to_string()).unwrap_or("?".into()),
        r.flavour.as_deref().unwrap_or("?"),
    );
    println!(
        "missing frames {}, missing samples {}, corrupt spans {}, truncated {}, overruns {}",
        r.missing_frames,
        r.missing_samples,
        r.corrupt.len(),
        r.truncated,
        r.overruns
    );
    if let Some(ips) = r.instructions_per_sample {
        println!("firmware: {ips:.0} instructions per sample (valid under QEMU -icount shift=0)");
    }
    if let Some(c) = &r.comparison {
        println!(
            "host {} seed {}: first {} samples max |error| {:.3e} m/s^2 = {:.3e} of RMS {:.3e} (tolerance {:.1e}); record RMS {:+.2e} (tolerance {:.0e}): {}",
            c.preset,
            c.seed,
            c.samples,
            c.max_abs_error,
            c.rel_error,
            c.host_rms,
            c.tolerance,
            c.rms_rel_diff,
            c.rms_tolerance,
            if c.pass { "pass" } else { "FAIL" }
        );
    }
    for p in &r.problems {
        println!("problem: {p}");
    }
    if let Some(f) = files {
        println!(
            "wrote {}, {}, {}",
            f.csv.display(),
            f.wav.display(),
            f.json.display()
        );
    }
    Ok(())
}

/// Runs `wearsim capture`.
pub fn run(a: CaptureArgs) -> Result<(), CaptureError> {
    if !(a.tolerance.is_finite() && a.tolerance >= 0.0) {
        return Err(CaptureError::Input(format!(
            "--tolerance {} must be a finite number ≥ 0",
            a.tolerance
        )));
    }
    // Exclusive, writable output directory before any work (docs/reliability.md).
    let _lock = crate::io::lock::DirLock::try_acquire(&a.out)
        .map_err(|e| CaptureError::Input(e.to_string()))?;
    let bytes = match read_input(&a.input) {
        Ok(b) => b,
        Err(e) => {
            // A report on stdout with `--json`, as for every other failure of the stream.
            if a.json {
                println!(
                    "{}",
                    json!({"input": a.input.display().to_string(), "complete": false, "problems": [e.to_string()]})
                );
            }
            return Err(e);
        }
    };
    let Decoded { mut report, accel } = decode(&a.input.display().to_string(), &bytes);
    let mut mismatch = false;
    if let (Some(seed), Some(preset)) = (a.expect_seed, a.preset.as_deref()) {
        if report.complete {
            let c = compare(&accel, preset, seed, a.tolerance)?;
            if report.preset.as_deref() != Some(preset) || report.seed != Some(seed) {
                report.problems.push(format!(
                    "the stream is of preset {} seed {}, expected {preset} seed {seed}",
                    report.preset.as_deref().unwrap_or("(none)"),
                    report.seed.map_or("(none)".to_string(), |s| s.to_string())
                ));
                mismatch = true;
            }
            if !c.pass {
                report.problems.push(format!(
                    "samples differ from the host run: {:.3e} of its RMS over the first {} (tolerance {:.1e}), record RMS {:+.2e} (tolerance {:.0e})",
                    c.rel_error, c.samples, c.tolerance, c.rms_rel_diff, c.rms_tolerance
                ));
                mismatch = true;
            }
            report.comparison = Some(c);
            report.complete = report.problems.is_empty();
        }
    }
    if !report.complete {
        print_report(&report, None, a.json)?;
        let first = report.problems.first().cloned().unwrap_or_default();
        let message = format!(
            "{}: {}, nothing written ({} problem(s); first: {first})",
            a.input.display(),
            if mismatch {
                "the stream does not match the host run"
            } else {
                "stream not complete"
            },
            report.problems.len()
        );
        return Err(if mismatch {
            CaptureError::Mismatch(message)
        } else {
            CaptureError::Stream(message)
        });
    }
    let fs = report.rate_hz.unwrap_or(0.0);
    let g: Vec<f64> = accel
        .iter()
        .map(|x| x / wearsim_core::real::STANDARD_GRAVITY)
        .collect();
    let columns: Vec<(&str, &[f64])> = vec![("accel_m_s2", &accel), ("accel_g", &g)];
    let mut meta = json!({
        "generator": "wearsim capture",
        "version": crate::VERSION,
        "source": a.input.display().to_string(),
        "preset": report.preset,
        "seed": report.seed,
        "firmware_flavour": report.flavour,
        "sample_format": report.format,
        "frames": report.data_frames,
        "overruns": report.overruns,
        "instructions_per_sample": report.instructions_per_sample,
        "comparison": report.comparison,
    });
    // The preset's model at the stream's rate, as `simulate` describes its runs: `analyze`
    // then finds the bearing and the shaft speed of a capture in its sidecar.
    let model = report
        .preset
        .as_deref()
        .and_then(|p| wearsim_core::presets::by_name(p).map(|c| (p, c)));
    if let (Some((name, mut cfg)), Some(m)) = (model, meta.as_object_mut()) {
        cfg.output_rate = fs as wearsim_core::Real;
        let speed = cfg
            .speed
            .over(0.0, (accel.len() as f64 / fs) as wearsim_core::Real);
        m.insert("rpm".into(), json!(60.0 * speed.mean_hz));
        m.insert(
            "rpm_range".into(),
            json!([60.0 * speed.min_hz, 60.0 * speed.max_hz]),
        );
        m.extend(crate::io::sidecar::model_metadata(Some(name), &cfg));
    }
    let files = crate::io::write::write_outputs(&a.out, "capture", &columns, fs, &meta)
        .map_err(|e| CaptureError::Write(e.to_string()))?;
    print_report(&report, Some(&files), a.json)?;
    Ok(())
}
