//! [`Record`]: one channel of measured (or simulated) vibration, as every reader returns it.

use std::path::PathBuf;

use serde::Serialize;

use super::error::IoError;

/// One uniformly sampled channel read from a file.
#[derive(Debug, Clone, Serialize)]
pub struct Record {
    /// The samples, in [`unit`](Record::unit), oldest first. Always finite and non-empty.
    pub samples: Vec<f64>,
    /// Sample rate in Hz (1 Hz ..= 10 MHz).
    pub fs: f64,
    /// Shaft speed in rpm, if the file, its sidecar or the caller gave one.
    pub rpm: Option<f64>,
    /// Channel name as the file calls it (`"DE"`, `"accel_m_s2"`, `"ch3"`, ...).
    pub channel: String,
    /// Physical unit of the samples: `"m/s^2"`, `"g"`, `"FS"` (fraction of full scale, for
    /// integer audio without calibration), or `"unknown"`.
    pub unit: String,
    /// The file the samples came from.
    pub source: PathBuf,
    /// Name of the bearing preset the channel belongs to, if known (e.g. `"cwru-6205-de"`).
    pub bearing: Option<String>,
    /// Everything else known about the record (fault label, sidecar contents, format details).
    pub meta: serde_json::Value,
}

impl Record {
    /// Duration in seconds (`samples.len() / fs`).
    pub fn duration_s(&self) -> f64 {
        self.samples.len() as f64 / self.fs
    }
}

/// Lowest accepted sample rate, Hz.
pub const MIN_FS: f64 = 1.0;
/// Largest record (samples) the MAT reader returns and `analyze` accepts: 2²³ (8.4 M
/// samples, 64 MiB of f64; 7 min at 20 kHz; the longest CWRU record has 0.49 M). The
/// analysis needs about 14× the record in memory (measured: 1.8 GB RSS for 2²⁴ samples),
/// so this keeps any accepted record under 1 GiB.
pub const MAX_RECORD_SAMPLES: usize = 1 << 23;
/// Most samples a text or binary record file (CSV, WAV, NPY) may hold over all its
/// channels: 2²⁶ (eight channels of [`MAX_RECORD_SAMPLES`], 512 MiB as f64), so a reader's
/// memory is bounded by a constant, not only by the file's size.
pub const MAX_FILE_SAMPLES: usize = 1 << 26;

/// Refuses a record file whose channel holds more than [`MAX_RECORD_SAMPLES`] samples or
/// whose channels together hold more than [`MAX_FILE_SAMPLES`] (exit 2, naming the limit),
/// before the samples are allocated.
pub fn check_record_size(
    path: &std::path::Path,
    per_channel: usize,
    total: usize,
) -> Result<(), IoError> {
    let too_large = |what: String, limit: usize| IoError::TooLarge {
        path: path.to_path_buf(),
        what,
        limit: format!("{limit} samples"),
    };
    if per_channel > MAX_RECORD_SAMPLES {
        return Err(too_large(
            format!("{per_channel} samples per channel"),
            MAX_RECORD_SAMPLES,
        ));
    }
    if total > MAX_FILE_SAMPLES {
        return Err(too_large(
            format!("{total} samples in all"),
            MAX_FILE_SAMPLES,
        ));
    }
    Ok(())
}

/// Highest accepted sample rate, Hz (10 MHz).
pub const MAX_FS: f64 = 10.0e6;

/// The whole of file `path`, read only if it is at most `max_bytes` long (checked on its
/// size before anything is allocated). `what` names the file's kind and `limit` describes
/// the bound in the [`IoError::TooLarge`] message (e.g. "524288 bytes per sidecar"). The one
/// size-checked read of the readers that take a file whole (MAT, IMS and FEMTO snapshots,
/// sidecars, feature tables, configuration files and sweep specs). The bound holds while
/// reading too: a device, pipe or growing file (`/dev/zero` states 0 bytes) is read to at
/// most one byte past the limit and refused.
pub fn read_capped(
    path: &std::path::Path,
    max_bytes: u64,
    what: &str,
    limit: &str,
) -> Result<Vec<u8>, IoError> {
    use std::io::Read;
    let len = std::fs::metadata(path)
        .map_err(|e| IoError::io(path, "stat", e))?
        .len();
    let too_large = |what: String| IoError::TooLarge {
        path: path.to_path_buf(),
        what,
        limit: limit.to_string(),
    };
    if len > max_bytes {
        return Err(too_large(format!("{what} of {len} bytes")));
    }
    let file = std::fs::File::open(path).map_err(|e| IoError::io(path, "open", e))?;
    let mut bytes = Vec::with_capacity(len as usize);
    file.take(max_bytes.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(|e| IoError::io(path, "read", e))?;
    if bytes.len() as u64 > max_bytes {
        return Err(too_large(format!("{what} of more than {max_bytes} bytes")));
    }
    Ok(bytes)
}

/// Check that `fs` (Hz) lies in [`MIN_FS`] ..= [`MAX_FS`]; `path` names the file that declared it.
pub fn check_fs(path: &std::path::Path, fs: f64) -> Result<f64, IoError> {
    if fs.is_finite() && (MIN_FS..=MAX_FS).contains(&fs) {
        Ok(fs)
    } else {
        Err(IoError::AbsurdSampleRate {
            path: path.to_path_buf(),
            fs,
        })
    }
}

/// Check a sample rate given as `--fs` (the readers' range, [`MIN_FS`]..=[`MAX_FS`]),
/// naming the flag rather than a file: a NaN was blamed on the record's sidecar.
pub fn check_fs_flag(fs: f64) -> Result<f64, String> {
    if fs.is_finite() && (MIN_FS..=MAX_FS).contains(&fs) {
        Ok(fs)
    } else {
        Err(format!(
            "--fs {fs} is out of range: allowed {MIN_FS} ..= {MAX_FS} Hz (samples per second)"
        ))
    }
}

/// Relative difference above which a sample rate stored in a file (or its sidecar) and `--fs`
/// contradict each other.
pub const FS_AGREEMENT: f64 = 1e-3;

/// An explicit `--fs` against a rate the file or its sidecar states (`where_`, e.g. `"the file
/// (file:bearing.sr)"`): they must agree within [`FS_AGREEMENT`], else the `--fs` is refused
/// (exit 2, `field fs`, both values named) rather than silently analysing at another rate.
/// Returns the checked argument. `path` is the file holding the stated rate.
pub fn check_fs_argument(
    path: &std::path::Path,
    arg: f64,
    stated: f64,
    where_: &str,
) -> Result<f64, IoError> {
    if (arg - stated).abs() > FS_AGREEMENT * stated.abs().max(arg.abs()) {
        return Err(IoError::contradiction(
            path,
            format!("field fs: --fs {arg} Hz contradicts the sample rate {stated} Hz stored in {where_}; drop --fs or fix the file"),
        ));
    }
    check_fs(path, arg)
}

/// Check that every sample is finite; the error names `path`, `channel` and the first bad index.
pub fn check_finite(path: &std::path::Path, channel: &str, samples: &[f64]) -> Result<(), IoError> {
    match samples.iter().position(|x| !x.is_finite()) {
        None => Ok(()),
        Some(index) => Err(IoError::NonFinite {
            path: path.to_path_buf(),
            channel: channel.to_string(),
            index,
            value: samples[index],
        }),
    }
}

/// Check a shaft speed given as `--rpm` (the analysis's range, (0, 1e6) rpm), naming the
/// flag rather than a file: the value is the user's, not the file's.
pub fn check_rpm_argument(rpm: f64) -> Result<f64, String> {
    if rpm.is_finite() && rpm > 0.0 && rpm < 1.0e6 {
        Ok(rpm)
    } else {
        Err(format!(
            "--rpm {rpm} is out of range: allowed 0 < rpm < 1e6 (shaft speed in revolutions per minute)"
        ))
    }
}

/// Check a shaft speed in rpm: finite and in (0, 1e6).
pub fn check_rpm(path: &std::path::Path, rpm: f64) -> Result<f64, IoError> {
    if rpm.is_finite() && rpm > 0.0 && rpm < 1.0e6 {
        Ok(rpm)
    } else {
        Err(IoError::malformed(
            path,
            format!("implausible shaft speed {rpm} rpm (allowed 0 < rpm < 1e6)"),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Flags are checked as flags: the message names `--fs`/`--rpm` and the range, not a
    /// file (probe of stop 69: `--fs nan` was reported as the sidecar's absurd rate).
    #[test]
    fn flag_values_out_of_range_name_the_flag() {
        for bad in [f64::NAN, f64::INFINITY, 0.0, -1.0, 2.0e7] {
            let e = check_fs_flag(bad).unwrap_err();
            assert!(
                e.starts_with("--fs ") && e.contains("allowed 1 ..= 10000000 Hz"),
                "{e}"
            );
            assert!(check_rpm_argument(bad * 1e3).is_err());
        }
        assert_eq!(check_fs_flag(12_000.0), Ok(12_000.0));
    }
}
