//! WAV reader: RIFF/WAVE PCM integer 8/16/24/32-bit (also `WAVE_FORMAT_EXTENSIBLE` with
//! fewer valid bits than its container, 24 in 32, 20 in 24) and IEEE float 32/64-bit, decoded
//! by [`super::wav_decode`] (chunks in any order, odd-sized ones with their pad byte: a
//! Broadcast WAV's `bext`/`iXML`, a `LIST` of odd size).
//!
//! * Integer samples are scaled to ±1 full scale (divided by 2^(container bits − 1); the valid
//!   bits are the container's top bits, so 24 valid bits in 32 read as 24-bit samples do), unit
//!   `"FS"`, unless a sidecar gives `wav.scale` (multiplied after normalisation) and a unit
//!   (`wav.unit` or `units[wav.column]`).
//! * Float samples are taken as they are (times `wav.scale` if given); unit from the sidecar
//!   (`wav.unit`, `units[wav.column]`, else `units[channel]` or the file-wide `units`/`unit`),
//!   else `"unknown"`. The float WAV written by [`crate::io::write_outputs`] holds physical units.
//! * Sample rate: the header rate, cross-checked against a sidecar `fs` when both exist (they must
//!   agree after rounding the sidecar rate to an integer, since WAV stores integer Hz; the exact
//!   sidecar value is then used). An explicit rate argument must agree with both within 0.1 %
//!   (else a contradiction naming the field `fs`) and is then used.
//! * Channel: [`ReadOptions::channel`] as a zero-based index (or the sidecar's `wav.column` name);
//!   default 0.
//!
//! Robustness: every chunk size is checked against the file size before any buffer is sized,
//! and the decoder is called under `catch_unwind`, so a decoder panic on a hostile file
//! becomes an [`IoError::Malformed`] instead of unwinding into the caller.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;

use serde_json::json;

use super::error::IoError;
use super::record::{check_finite, Record};
use super::sidecar::{check_n_samples, resolve_fs, sidecar_for, sidecar_record};
use super::wav_decode::{decode, Decoded};
use super::ReadOptions;

/// Read one channel of a WAV file as a [`Record`] (see the module doc for the rules).
pub fn read_wav(path: impl AsRef<Path>, opts: &ReadOptions) -> Result<Record, IoError> {
    let path = path.as_ref();
    let sidecar = sidecar_for(path)?;
    let file_len = std::fs::metadata(path)
        .map_err(|e| IoError::io(path, "stat", e))?
        .len();
    if file_len == 0 {
        return Err(IoError::truncated(
            path,
            "empty file (a WAV header is at least 44 bytes)",
        ));
    }
    let decoded = catch_unwind(AssertUnwindSafe(|| decode(path, file_len))).map_err(|_| {
        IoError::malformed(
            path,
            "WAV decoder panicked on this file (corrupt header or data)",
        )
    })??;
    let Decoded {
        format,
        interleaved,
    } = decoded;
    let nch = usize::from(format.channels);

    let available: Vec<String> = (0..nch).map(|i| i.to_string()).collect();
    let index = match opts.channel.as_deref() {
        None => 0,
        Some(req) => {
            let by_name = sidecar
                .as_ref()
                .and_then(|s| s.wav_column.as_deref())
                .filter(|c| *c == req)
                .map(|_| 0);
            match by_name.or_else(|| req.parse::<usize>().ok().filter(|&i| i < nch)) {
                Some(i) => i,
                None => {
                    return Err(IoError::UnknownChannel {
                        path: path.to_path_buf(),
                        requested: req.to_string(),
                        available,
                    })
                }
            }
        }
    };
    let int = !format.float;
    let scale = sidecar.as_ref().and_then(|s| s.wav_scale).unwrap_or(1.0);
    let samples: Vec<f64> = interleaved
        .iter()
        .skip(index)
        .step_by(nch)
        .map(|&x| x * scale)
        .collect();
    if samples.is_empty() {
        return Err(IoError::truncated(path, "no samples in the data chunk"));
    }
    let channel = if nch == 1 {
        sidecar
            .as_ref()
            .and_then(|s| s.wav_column.clone())
            .unwrap_or_else(|| "0".to_string())
    } else {
        index.to_string()
    };
    check_finite(path, &channel, &samples)?;
    check_n_samples(sidecar.as_ref(), path, samples.len())?;

    let header_fs = f64::from(format.sample_rate);
    let fs = resolve_fs(
        path,
        opts.fs,
        sidecar.as_ref(),
        Some((header_fs, "WAV header")),
        &|side, head| side.round() == head,
    )?;
    let full_scale_units = int && scale == 1.0;
    let unit = sidecar
        .as_ref()
        .and_then(|s| {
            s.wav_unit
                .clone()
                .or_else(|| {
                    s.wav_column
                        .as_deref()
                        .and_then(|c| s.unit_of(c))
                        .map(str::to_string)
                })
                // The unit the sidecar gives the channel by its name here (`"units":
                // {"0": "g"}`) or the whole file (`"units": "g"`), as for CSV and NPY; not
                // for integer samples without `wav.scale`, which stay full scale.
                .or_else(|| {
                    (!full_scale_units)
                        .then(|| s.unit_of(&channel).map(str::to_string))
                        .flatten()
                })
        })
        .unwrap_or_else(|| if full_scale_units { "FS" } else { "unknown" }.to_string());
    sidecar_record(
        path,
        samples,
        (channel, unit),
        fs,
        opts.rpm,
        sidecar.as_ref(),
        json!({
            "format": "wav",
            "channels": nch,
            "channel_index": index,
            "bits_per_sample": format.container_bits,
            "valid_bits_per_sample": format.valid_bits,
            "sample_format": if int { "int" } else { "float" },
            "header_sample_rate_hz": format.sample_rate,
            "scale": scale,
        }),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::write_outputs;

    fn write_int_wav(path: &Path, bits: u16, rate: u32, channels: u16, data: &[i32]) {
        let spec = hound::WavSpec {
            channels,
            sample_rate: rate,
            bits_per_sample: bits,
            sample_format: hound::SampleFormat::Int,
        };
        let mut w = hound::WavWriter::create(path, spec).unwrap();
        for &x in data {
            match bits {
                8 => w.write_sample(x as i8).unwrap(),
                16 => w.write_sample(x as i16).unwrap(),
                _ => w.write_sample(x).unwrap(),
            }
        }
        w.finalize().unwrap();
    }

    #[test]
    fn float_round_trip_within_f32() {
        let dir = tempfile::tempdir().unwrap();
        let a: Vec<f64> = (0..4800).map(|i| (i as f64 * 0.01).sin() * 37.5).collect();
        let set = write_outputs(
            dir.path(),
            "w",
            &[("accel_m_s2", &a)],
            48000.0,
            &json!({"rpm": 1772}),
        )
        .unwrap();
        let r = read_wav(&set.wav, &ReadOptions::default()).unwrap();
        assert_eq!(r.samples.len(), a.len());
        for (x, y) in r.samples.iter().zip(&a) {
            assert_eq!(*x, *y as f32 as f64);
            assert!((x - y).abs() <= y.abs() * f32::EPSILON as f64);
        }
        assert_eq!(
            (r.fs, r.rpm, r.unit.as_str()),
            (48000.0, Some(1772.0), "m/s^2")
        );
        assert_eq!(r.channel, "accel_m_s2");
        // Non-integer fs survives via the sidecar.
        let set = write_outputs(dir.path(), "frac", &[("x_g", &a)], 20480.5, &json!({})).unwrap();
        let r = read_wav(&set.wav, &ReadOptions::default()).unwrap();
        assert_eq!(r.fs, 20480.5);
        // A sidecar that contradicts the header.
        let side = dir.path().join("frac.wav.json");
        std::fs::write(&side, r#"{"fs": 44100}"#).unwrap();
        match read_wav(&set.wav, &ReadOptions::default()).unwrap_err() {
            IoError::Contradiction { path, .. } => assert_eq!(path, side),
            e => panic!("{e:?}"),
        }
        // An explicit rate must agree with the header and the sidecar: against the
        // contradicting sidecar, then against the header, it is refused naming the field.
        let at = |fs: f64| {
            read_wav(
                &set.wav,
                &ReadOptions {
                    fs: Some(fs),
                    ..Default::default()
                },
            )
        };
        match at(44_100.0).unwrap_err() {
            IoError::Contradiction { path, detail } => {
                assert_eq!(path, set.wav);
                assert!(detail.contains("field fs") && detail.contains("WAV header"));
            }
            e => panic!("{e:?}"),
        }
        std::fs::remove_file(&side).unwrap();
        match at(1000.0).unwrap_err() {
            IoError::Contradiction { detail, .. } => {
                assert!(
                    detail.contains("field fs") && detail.contains("20480.5"),
                    "{detail}"
                );
            }
            e => panic!("{e:?}"),
        }
        // Agreeing within 0.1 %, it is used as given.
        assert_eq!(at(20_481.0).unwrap().fs, 20_481.0);
    }

    #[test]
    fn integer_scaling_and_channels() {
        let dir = tempfile::tempdir().unwrap();
        for bits in [8u16, 16, 24, 32] {
            let p = dir.path().join(format!("i{bits}.wav"));
            let fsc = 1i64 << (bits - 1);
            let data = [(fsc / 2) as i32, (-fsc) as i32, 0, 1, (fsc - 1) as i32, 5];
            write_int_wav(&p, bits, 8000, 2, &data);
            let r = read_wav(&p, &ReadOptions::default()).unwrap();
            assert_eq!(
                r.samples,
                vec![0.5, 0.0, (fsc - 1) as f64 / fsc as f64],
                "{bits}"
            );
            assert_eq!(r.unit, "FS");
            assert_eq!(r.fs, 8000.0);
            let r = read_wav(
                &p,
                &ReadOptions {
                    channel: Some("1".into()),
                    ..Default::default()
                },
            )
            .unwrap();
            assert_eq!(r.samples[0], -1.0);
            assert!(matches!(
                read_wav(
                    &p,
                    &ReadOptions {
                        channel: Some("2".into()),
                        ..Default::default()
                    }
                ),
                Err(IoError::UnknownChannel { .. })
            ));
        }
        // Sidecar calibration.
        let p = dir.path().join("cal.wav");
        write_int_wav(&p, 16, 12000, 1, &[16384, -8192]);
        std::fs::write(
            dir.path().join("cal.json"),
            r#"{"wav": {"scale": 10.0, "unit": "g"}, "rpm": 1797}"#,
        )
        .unwrap();
        let r = read_wav(&p, &ReadOptions::default()).unwrap();
        assert_eq!(r.samples, vec![5.0, -2.5]);
        assert_eq!((r.unit.as_str(), r.rpm), ("g", Some(1797.0)));
    }

    #[test]
    fn corrupt_wavs_are_errors() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("c.wav");
        write_int_wav(&p, 16, 8000, 1, &[1, 2, 3, 4, 5, 6, 7, 8]);
        let good = std::fs::read(&p).unwrap();
        for len in [0, 3, 12, 20, 43, good.len() - 1] {
            std::fs::write(&p, &good[..len]).unwrap();
            let e = read_wav(&p, &ReadOptions::default()).unwrap_err();
            assert!(e.to_string().contains("c.wav"), "{e}");
        }
        // Data chunk claiming 4 GiB.
        let mut huge = good.clone();
        let n = huge.len();
        huge[40..44].copy_from_slice(&(u32::MAX - 1).to_le_bytes());
        std::fs::write(&p, &huge[..n]).unwrap();
        assert!(read_wav(&p, &ReadOptions::default()).is_err());
        // Not a WAV at all.
        std::fs::write(&p, b"this is not a wav file at all, no sir").unwrap();
        assert!(matches!(
            read_wav(&p, &ReadOptions::default()),
            Err(IoError::BadMagic { .. })
        ));
        // Rate 0 in the header.
        let mut zero = good.clone();
        zero[24..28].copy_from_slice(&0u32.to_le_bytes());
        std::fs::write(&p, &zero).unwrap();
        assert!(read_wav(&p, &ReadOptions::default()).is_err());
    }

    /// A 64-bit float WAV as scipy writes it (format tag 3), or with the extensible header and
    /// an odd-sized chunk before `fmt ` (RIFF pads it to even).
    fn float64_wav(extensible: bool, data: &[f64], channels: u16, rate: u32) -> Vec<u8> {
        let mut fmt = Vec::new();
        let tag: u16 = if extensible { 0xFFFE } else { 3 };
        fmt.extend_from_slice(&tag.to_le_bytes());
        fmt.extend_from_slice(&channels.to_le_bytes());
        fmt.extend_from_slice(&rate.to_le_bytes());
        fmt.extend_from_slice(&(rate * 8 * u32::from(channels)).to_le_bytes());
        fmt.extend_from_slice(&(8 * channels).to_le_bytes());
        fmt.extend_from_slice(&64u16.to_le_bytes());
        if extensible {
            fmt.extend_from_slice(&22u16.to_le_bytes());
            fmt.extend_from_slice(&64u16.to_le_bytes());
            fmt.extend_from_slice(&0u32.to_le_bytes());
            fmt.extend_from_slice(&[
                3, 0, 0, 0, 0, 0, 0x10, 0, 0x80, 0, 0, 0xAA, 0, 0x38, 0x9B, 0x71,
            ]);
        }
        let mut body = b"WAVE".to_vec();
        if extensible {
            body.extend_from_slice(b"LIST");
            body.extend_from_slice(&3u32.to_le_bytes());
            body.extend_from_slice(&[1, 2, 3, 0]);
        }
        body.extend_from_slice(b"fmt ");
        body.extend_from_slice(&(fmt.len() as u32).to_le_bytes());
        body.extend_from_slice(&fmt);
        body.extend_from_slice(b"data");
        body.extend_from_slice(&((data.len() * 8) as u32).to_le_bytes());
        for x in data {
            body.extend_from_slice(&x.to_le_bytes());
        }
        let mut out = b"RIFF".to_vec();
        out.extend_from_slice(&(body.len() as u32).to_le_bytes());
        out.extend_from_slice(&body);
        out
    }

    #[test]
    fn float64_wavs_are_read_exactly() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("f64.wav");
        let data = [0.1, -2.5e-3, 1.0 / 3.0, 7.25, -0.0, 1e-300];
        for ext in [false, true] {
            std::fs::write(&p, float64_wav(ext, &data, 2, 25_600)).unwrap();
            let r = read_wav(&p, &ReadOptions::default()).unwrap();
            assert_eq!(r.samples, vec![0.1, 1.0 / 3.0, -0.0], "extensible {ext}");
            assert_eq!((r.fs, r.unit.as_str()), (25_600.0, "unknown"));
            assert_eq!(r.meta["bits_per_sample"], 64);
            let ch1 = ReadOptions {
                channel: Some("1".into()),
                ..Default::default()
            };
            assert_eq!(
                read_wav(&p, &ch1).unwrap().samples,
                vec![-2.5e-3, 7.25, 1e-300]
            );
        }
        // A data chunk claiming more than the file holds, a NaN sample, a cut file.
        let mut bad = float64_wav(false, &data, 1, 8000);
        let at = bad.len() - data.len() * 8 - 4;
        bad[at..at + 4].copy_from_slice(&4000u32.to_le_bytes());
        std::fs::write(&p, &bad).unwrap();
        assert!(matches!(
            read_wav(&p, &ReadOptions::default()),
            Err(IoError::Truncated { .. })
        ));
        std::fs::write(&p, float64_wav(false, &[1.0, f64::NAN], 1, 8000)).unwrap();
        assert!(read_wav(&p, &ReadOptions::default()).is_err());
        let good = float64_wav(true, &data, 1, 8000);
        for len in [13, 30, 60, good.len() - 3] {
            std::fs::write(&p, &good[..len]).unwrap();
            assert!(read_wav(&p, &ReadOptions::default()).is_err(), "{len}");
        }
    }
}
