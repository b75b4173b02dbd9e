//! NumPy `.npy` reader: 1-D or 2-D arrays of f64, f32, i16, i32 (also i8/u8/u16/u32/i64/u64),
//! either byte order, C or Fortran order.
//!
//! Format reference: NumPy NEP 1, "A simple file format for NumPy arrays" (magic `\x93NUMPY`,
//! version 1.x/2.x/3.x, little-endian header length, a Python-literal dict with `descr`,
//! `fortran_order`, `shape`, then the raw data).
//!
//! The header is parsed here rather than by `npyz` (which is used in the tests to write
//! fixtures), because `npyz` 0.8 computes the element count as an unchecked `u64` product of the
//! header's shape (a panic with overflow checks on for a hostile header) and trusts it for
//! reading; here the count is a checked product and must match the bytes actually present.
//!
//! For a 2-D array the samples run along the longer axis (a record holds far more samples than
//! channels, so `(N, channels)` as pandas writes it and `(channels, N)` as signal-processing
//! code does are both read as meant); a sidecar whose `columns` count matches exactly one axis
//! makes that axis the channels. A shape that does not tell (square, or both axes long: see
//! [`MAX_SHAPE_CHANNELS`], [`SAMPLES_RATIO`]) is refused unless the sidecar or a selector
//! decides. [`ReadOptions::channel`] picks the channel (zero-based index, or a name from the
//! sidecar's `columns`, or a 1-based selector of the array as stored: `(:,K)` column K,
//! `(K,:)` row K, [`selector`]); default 0. The JSON `meta.sample_axis` says which axis was
//! taken.
//! Integers are converted as they are (no full-scale normalisation); the unit comes from the
//! sidecar (`units`), else `"unknown"`. Sample rate and rpm: argument, else sidecar.

use std::path::Path;

use serde_json::json;

use super::error::IoError;
use super::record::{check_finite, Record};
use super::selector;
use super::sidecar::{check_n_samples, resolve_fs, sidecar_for, sidecar_record};
use super::ReadOptions;

/// Parsed `.npy` header.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct NpyHeader {
    /// Type string, e.g. `<f8`.
    pub descr: String,
    /// True for column-major (Fortran) data order.
    pub fortran_order: bool,
    /// Array shape.
    pub shape: Vec<usize>,
    /// Offset of the first data byte.
    pub data_offset: usize,
}

/// Parse the header of an `.npy` file held in `bytes`.
pub fn parse_npy_header(bytes: &[u8], path: &Path) -> Result<NpyHeader, IoError> {
    if bytes.len() < 10 {
        return Err(IoError::truncated(
            path,
            format!("{} bytes, an .npy preamble is 10", bytes.len()),
        ));
    }
    if &bytes[..6] != b"\x93NUMPY" {
        return Err(IoError::BadMagic {
            path: path.to_path_buf(),
            expected: "\\x93NUMPY".into(),
            found: format!("{:?}", String::from_utf8_lossy(&bytes[..6])),
        });
    }
    let major = bytes[6];
    let (hlen, start) = match major {
        1 => (u16::from_le_bytes([bytes[8], bytes[9]]) as usize, 10usize),
        2 | 3 => {
            if bytes.len() < 12 {
                return Err(IoError::truncated(
                    path,
                    "npy v2/v3 preamble needs 12 bytes",
                ));
            }
            (
                u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize,
                12,
            )
        }
        v => {
            return Err(IoError::unsupported(
                path,
                format!("npy format version {v}"),
            ))
        }
    };
    let end = start
        .checked_add(hlen)
        .filter(|&e| e <= bytes.len())
        .ok_or_else(|| {
            IoError::truncated(
                path,
                format!("npy header claims {hlen} bytes, file has {}", bytes.len()),
            )
        })?;
    let text = std::str::from_utf8(&bytes[start..end])
        .map_err(|_| IoError::malformed(path, "npy header is not UTF-8"))?;
    let descr = dict_value(text, "descr")
        .and_then(quoted)
        .ok_or_else(|| IoError::malformed(path, format!("npy header without 'descr': {text:?}")))?
        .to_string();
    let fortran_order = match dict_value(text, "fortran_order") {
        Some(v) if v.starts_with("True") => true,
        Some(v) if v.starts_with("False") => false,
        _ => {
            return Err(IoError::malformed(
                path,
                format!("npy header without 'fortran_order': {text:?}"),
            ))
        }
    };
    let shape_txt = dict_value(text, "shape")
        .and_then(|v| v.strip_prefix('('))
        .and_then(|v| v.split_once(')'))
        .map(|(inner, _)| inner)
        .ok_or_else(|| IoError::malformed(path, format!("npy header without 'shape': {text:?}")))?;
    let mut shape = Vec::new();
    for part in shape_txt.split(',') {
        let part = part.trim().trim_end_matches('L');
        if part.is_empty() {
            continue;
        }
        let d: usize = part.parse().map_err(|_| {
            IoError::malformed(path, format!("npy shape entry {part:?} is not a size"))
        })?;
        shape.push(d);
    }
    Ok(NpyHeader {
        descr,
        fortran_order,
        shape,
        data_offset: end,
    })
}

/// Text after `'key':` (or `"key":`) in a Python dict literal, left-trimmed.
fn dict_value<'t>(text: &'t str, key: &str) -> Option<&'t str> {
    for q in ['\'', '"'] {
        let pat = format!("{q}{key}{q}");
        if let Some(i) = text.find(&pat) {
            let rest = text[i + pat.len()..].trim_start();
            return rest.strip_prefix(':').map(str::trim_start);
        }
    }
    None
}

/// The content of a leading `'...'` or `"..."`.
fn quoted(v: &str) -> Option<&str> {
    let q = v.chars().next().filter(|c| *c == '\'' || *c == '"')?;
    let rest = &v[1..];
    rest.find(q).map(|e| &rest[..e])
}

/// Most channels the shorter axis of a 2-D array may hold for the shape alone to say it is
/// the channels' axis (unless the other axis is [`SAMPLES_RATIO`] times longer).
pub const MAX_SHAPE_CHANNELS: usize = 64;
/// How many times longer than the other the samples' axis must be for the shape alone to
/// decide when both axes are longer than [`MAX_SHAPE_CHANNELS`].
pub const SAMPLES_RATIO: usize = 16;

/// Whether the samples of a 2-D array of `shape` run along its second axis (channels
/// first), and the line a `--channel` selector ([`selector`]: `(:,K)`, `(K,:)`) picks.
/// Without a selector: a sidecar whose `columns` count matches exactly one axis makes it the
/// channels; else the shape decides when it is unambiguous (the axes differ, and the shorter
/// holds at most [`MAX_SHAPE_CHANNELS`] or the longer is [`SAMPLES_RATIO`] times longer);
/// a square array or two long axes are refused saying how to choose.
fn sample_axis(
    path: &Path,
    shape: &[usize],
    columns: usize,
    channel: Option<&str>,
) -> Result<(bool, Option<selector::Line>), IoError> {
    let dims = match shape {
        [n] => [*n, 1],
        [n, m] => [*n, *m],
        _ => [0, 0],
    };
    if let Some((base, sel)) = channel.and_then(selector::split) {
        if base.is_empty() {
            let line = selector::check(sel, "", &dims).map_err(|e| IoError::malformed(path, e))?;
            return Ok((line.is_row(), Some(line)));
        }
    }
    let [n, m] = dims;
    if shape.len() != 2 {
        return Ok((false, None));
    }
    if columns > 0 && (columns == n) != (columns == m) {
        return Ok((columns == n, None));
    }
    let (short, long) = (n.min(m), n.max(m));
    if short > 1 && (short == long || (short > MAX_SHAPE_CHANNELS && long < SAMPLES_RATIO * short))
    {
        return Err(IoError::malformed(
            path,
            format!(
                "--channel: the npy array of shape {shape:?} could hold its samples along either axis ({}); {}, or give a sidecar whose \"columns\" lists one name per channel",
                if short == long { "it is square" } else { "both axes are long" },
                selector::advice("", &dims)
            ),
        ));
    }
    Ok((m > n, None))
}

/// Read one column of a `.npy` file as a [`Record`] (see the module doc for the rules).
pub fn read_npy(path: impl AsRef<Path>, opts: &ReadOptions) -> Result<Record, IoError> {
    let path = path.as_ref();
    let sidecar = sidecar_for(path)?;
    // The whole file is read: bound it by the largest array accepted (8-byte samples)
    // plus the largest header (npy format 2/3: 4-byte header length).
    let file_len = std::fs::metadata(path)
        .map_err(|e| IoError::io(path, "stat", e))?
        .len();
    let max_bytes = (super::record::MAX_FILE_SAMPLES as u64) * 8 + (1 << 16);
    if file_len > max_bytes {
        return Err(IoError::TooLarge {
            path: path.to_path_buf(),
            what: format!("{file_len} bytes"),
            limit: format!("{max_bytes} bytes"),
        });
    }
    let bytes = std::fs::read(path).map_err(|e| IoError::io(path, "read", e))?;
    let h = parse_npy_header(&bytes, path)?;
    let data = &bytes[h.data_offset..];

    let (big, ty) = match h.descr.as_bytes().first() {
        Some(b'<') | Some(b'=') | Some(b'|') => (false, &h.descr[1..]),
        Some(b'>') => (true, &h.descr[1..]),
        _ => (false, h.descr.as_str()),
    };
    let width = match ty {
        "f8" | "i8" | "u8" => 8,
        "f4" | "i4" | "u4" => 4,
        "i2" | "u2" => 2,
        "i1" | "u1" | "b1" => 1,
        _ => {
            return Err(IoError::unsupported(
                path,
                format!(
                    "npy dtype {:?} (supported: f8, f4, i1..i8, u1..u8)",
                    h.descr
                ),
            ))
        }
    };
    let (n, m) = match h.shape.as_slice() {
        [n] => (*n, 1),
        [n, m] => (*n, *m),
        other => {
            return Err(IoError::unsupported(
                path,
                format!("npy array of shape {other:?} (supported: 1-D or 2-D)"),
            ))
        }
    };
    let numel = n.checked_mul(m).ok_or_else(|| {
        IoError::contradiction(path, format!("npy shape {:?} overflows", h.shape))
    })?;
    let columns = sidecar.as_ref().map_or(0, |s| s.columns.len());
    let (channels_first, line) = sample_axis(path, &h.shape, columns, opts.channel.as_deref())?;
    // (samples, channels) whatever the layout on disk.
    let (len, m) = if channels_first { (m, n) } else { (n, m) };
    super::record::check_record_size(path, len, numel)?;
    let need = numel.checked_mul(width).ok_or_else(|| {
        IoError::contradiction(path, format!("npy shape {:?} overflows", h.shape))
    })?;
    if need > data.len() {
        return Err(IoError::truncated(
            path,
            format!(
                "shape {:?} of {} needs {need} data bytes, file has {}",
                h.shape,
                h.descr,
                data.len()
            ),
        ));
    }
    if need < data.len() {
        return Err(IoError::contradiction(
            path,
            format!(
                "shape {:?} of {} needs {need} data bytes, file has {} (trailing data)",
                h.shape,
                h.descr,
                data.len()
            ),
        ));
    }
    if numel == 0 {
        return Err(IoError::truncated(
            path,
            format!("npy array of shape {:?} is empty", h.shape),
        ));
    }

    let names: Vec<String> = match sidecar.as_ref() {
        Some(s) if s.columns.len() == m => s.columns.clone(),
        _ => (0..m).map(|i| format!("col{i}")).collect(),
    };
    let col = match (line, opts.channel.as_deref()) {
        (Some(line), _) => line.index0(),
        (None, None) => 0,
        (None, Some(req)) => names
            .iter()
            .position(|c| c == req)
            .or_else(|| req.parse::<usize>().ok().filter(|&i| i < m))
            .ok_or_else(|| IoError::UnknownChannel {
                path: path.to_path_buf(),
                requested: req.to_string(),
                available: names.clone(),
            })?,
    };
    let get = |k: usize| -> f64 {
        let b = &data[k * width..(k + 1) * width];
        macro_rules! conv {
            ($t:ty, $w:literal) => {{
                let mut a = [0u8; $w];
                a.copy_from_slice(b);
                (if big {
                    <$t>::from_be_bytes(a)
                } else {
                    <$t>::from_le_bytes(a)
                }) as f64
            }};
        }
        match ty {
            "f8" => conv!(f64, 8),
            "i8" => conv!(i64, 8),
            "u8" => conv!(u64, 8),
            "f4" => conv!(f32, 4),
            "i4" => conv!(i32, 4),
            "u4" => conv!(u32, 4),
            "i2" => conv!(i16, 2),
            "u2" => conv!(u16, 2),
            "i1" => b[0] as i8 as f64,
            _ => b[0] as f64,
        }
    };
    // Element [i, col] of the logical (samples, channels) array: the flat index of the axis
    // order on disk (C: last axis fastest; Fortran: first axis fastest).
    let samples: Vec<f64> = (0..len)
        .map(|i| {
            get(match (channels_first, h.fortran_order) {
                (false, false) => i * m + col,
                (false, true) => col * len + i,
                (true, false) => col * len + i,
                (true, true) => i * m + col,
            })
        })
        .collect();
    let channel = names[col].clone();
    check_finite(path, &channel, &samples)?;
    check_n_samples(sidecar.as_ref(), path, samples.len())?;
    let fs = resolve_fs(path, opts.fs, sidecar.as_ref(), None, &|_, _| true)?;
    let unit = sidecar
        .as_ref()
        .and_then(|s| s.unit_of(&channel))
        .unwrap_or("unknown")
        .to_string();
    sidecar_record(
        path,
        samples,
        (channel, unit),
        fs,
        opts.rpm,
        sidecar.as_ref(),
        json!({
            "format": "npy",
            "descr": h.descr,
            "shape": h.shape,
            "fortran_order": h.fortran_order,
            "column_index": col,
            "sample_axis": usize::from(channels_first),
            "selector": line.map(selector::Line::suffix),
        }),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use npyz::WriterBuilder;

    fn write_npy<T: npyz::AutoSerialize + Copy>(
        shape: &[u64],
        fortran: bool,
        data: &[T],
    ) -> Vec<u8> {
        let mut buf = Vec::new();
        {
            let order = if fortran {
                npyz::Order::Fortran
            } else {
                npyz::Order::C
            };
            let mut w = npyz::WriteOptions::new()
                .default_dtype()
                .shape(shape)
                .order(order)
                .writer(&mut buf)
                .begin_nd()
                .unwrap();
            w.extend(data.iter().copied()).unwrap();
            w.finish().unwrap();
        }
        buf
    }

    fn o(ch: Option<&str>) -> ReadOptions {
        ReadOptions {
            channel: ch.map(str::to_string),
            fs: Some(1000.0),
            rpm: None,
        }
    }

    #[test]
    fn reads_dtypes_and_orders() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("a.npy");
        std::fs::write(&p, write_npy(&[4], false, &[1.5f64, -2.0, 3.25, 1e-300])).unwrap();
        assert_eq!(
            read_npy(&p, &o(None)).unwrap().samples,
            vec![1.5, -2.0, 3.25, 1e-300]
        );
        std::fs::write(&p, write_npy(&[3], false, &[1.5f32, -2.0, 0.1])).unwrap();
        assert_eq!(
            read_npy(&p, &o(None)).unwrap().samples,
            vec![1.5, -2.0, 0.1f32 as f64]
        );
        std::fs::write(&p, write_npy(&[3], false, &[1i16, -32768, 7])).unwrap();
        assert_eq!(
            read_npy(&p, &o(None)).unwrap().samples,
            vec![1.0, -32768.0, 7.0]
        );
        // 2-D (3 rows x 2 columns), C order: rows (1,10) (2,20) (3,30).
        std::fs::write(&p, write_npy(&[3, 2], false, &[1i32, 10, 2, 20, 3, 30])).unwrap();
        assert_eq!(
            read_npy(&p, &o(Some("1"))).unwrap().samples,
            vec![10.0, 20.0, 30.0]
        );
        // Same matrix in Fortran order.
        std::fs::write(&p, write_npy(&[3, 2], true, &[1i32, 2, 3, 10, 20, 30])).unwrap();
        assert_eq!(
            read_npy(&p, &o(Some("1"))).unwrap().samples,
            vec![10.0, 20.0, 30.0]
        );
        assert_eq!(read_npy(&p, &o(None)).unwrap().samples, vec![1.0, 2.0, 3.0]);
        assert!(matches!(
            read_npy(&p, &o(Some("2"))),
            Err(IoError::UnknownChannel { .. })
        ));
        // Channels first, (2 channels x 3 samples), in both orders: the longer axis holds the
        // samples, so the same two channels come out.
        std::fs::write(&p, write_npy(&[2, 3], false, &[1i32, 2, 3, 10, 20, 30])).unwrap();
        let r = read_npy(&p, &o(Some("1"))).unwrap();
        assert_eq!(
            (r.samples, &r.meta["sample_axis"]),
            (vec![10.0, 20.0, 30.0], &json!(1))
        );
        std::fs::write(&p, write_npy(&[2, 3], true, &[1i32, 10, 2, 20, 3, 30])).unwrap();
        assert_eq!(read_npy(&p, &o(None)).unwrap().samples, vec![1.0, 2.0, 3.0]);
        assert_eq!(
            read_npy(&p, &o(Some("1"))).unwrap().samples,
            vec![10.0, 20.0, 30.0]
        );
        // A sidecar naming three columns makes the axis of length 3 the channels.
        let c = dir.path().join("c.npy");
        std::fs::write(&c, write_npy(&[2, 3], false, &[1i32, 2, 3, 10, 20, 30])).unwrap();
        std::fs::write(dir.path().join("c.json"), r#"{"columns": ["a", "b", "z"]}"#).unwrap();
        assert_eq!(
            read_npy(&c, &o(Some("z"))).unwrap().samples,
            vec![3.0, 30.0]
        );
        // Back to (3 samples x 2 channels) in Fortran order for the sidecar checks.
        std::fs::write(&p, write_npy(&[3, 2], true, &[1i32, 2, 3, 10, 20, 30])).unwrap();
        // Sidecar names, rate and unit.
        std::fs::write(
            dir.path().join("a.json"),
            r#"{"fs": 20000, "columns": ["x", "y"], "units": {"y": "g"}, "n_samples": 3}"#,
        )
        .unwrap();
        let r = read_npy(
            &p,
            &ReadOptions {
                channel: Some("y".into()),
                ..Default::default()
            },
        )
        .unwrap();
        assert_eq!(
            (r.fs, r.unit.as_str(), r.channel.as_str()),
            (20000.0, "g", "y")
        );
        // One unit for the whole file (`"unit"` or `"units"` as a string) reaches a
        // one-dimensional array, whose channel the reader names `col0`; a column's own
        // entry in `units` wins over it.
        let q = dir.path().join("b.npy");
        std::fs::write(&q, write_npy(&[3], false, &[1.0f64, 2.0, 3.0])).unwrap();
        for (side, unit) in [
            (r#"{"fs": 1000, "unit": "g"}"#, "g"),
            (r#"{"fs": 1000, "units": "m/s^2"}"#, "m/s^2"),
            (
                r#"{"fs": 1000, "unit": "g", "units": {"col0": "m/s^2"}}"#,
                "m/s^2",
            ),
            (r#"{"fs": 1000}"#, "unknown"),
        ] {
            std::fs::write(dir.path().join("b.json"), side).unwrap();
            let r = read_npy(&q, &o(None)).unwrap();
            assert_eq!(
                (r.channel.as_str(), r.unit.as_str()),
                ("col0", unit),
                "{side}"
            );
        }
        std::fs::write(dir.path().join("b.json"), r#"{"fs": 48000, "unit": 9.81}"#).unwrap();
        let e = read_npy(&q, &o(None)).unwrap_err().to_string();
        assert!(e.contains("\"unit\"") && e.contains("string"), "{e}");
    }

    /// The shape decides the axes when it tells them (a few channels, or one axis 16 times
    /// longer); a square array or two long axes need a selector or a sidecar's `columns`.
    #[test]
    fn the_shape_decides_the_sample_axis_only_when_it_tells() {
        let p = Path::new("x.npy");
        let axis = |shape: &[usize], columns: usize, ch: Option<&str>| {
            sample_axis(p, shape, columns, ch).map(|(first, line)| (first, line.is_some()))
        };
        assert_eq!(axis(&[3, 2], 0, None).unwrap(), (false, false));
        assert_eq!(axis(&[2, 3], 0, None).unwrap(), (true, false));
        assert_eq!(axis(&[64, 8192], 0, None).unwrap(), (true, false));
        assert_eq!(axis(&[20_000, 1000], 0, None).unwrap(), (false, false));
        assert_eq!(axis(&[1, 1], 0, None).unwrap(), (false, false));
        for shape in [[2, 2], [1000, 1000], [4096, 1000], [100, 1000]] {
            let e = axis(&shape, 0, Some("0")).unwrap_err().to_string();
            assert!(
                e.contains(&format!("{shape:?}")) && e.contains("'(:,K)'"),
                "{e}"
            );
        }
        assert_eq!(axis(&[3, 3], 0, Some("(2,:)")).unwrap(), (true, true));
        assert_eq!(axis(&[4096, 1000], 1000, None).unwrap(), (false, false));
        assert_eq!(axis(&[4096], 0, Some("(:,1)")).unwrap(), (false, true));
        assert!(axis(&[4096], 0, Some("(:,2)")).is_err());
    }

    #[test]
    fn corrupt_npy_are_errors() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("c.npy");
        let good = write_npy(&[4], false, &[1.0f64, 2.0, 3.0, 4.0]);
        for len in [0, 5, 9, 30, good.len() - 1] {
            std::fs::write(&p, &good[..len]).unwrap();
            let e = read_npy(&p, &o(None)).unwrap_err();
            assert!(e.to_string().contains("c.npy"), "{e}");
        }
        // Huge shape: must not allocate or overflow.
        let mut hostile = good.clone();
        let pos = hostile.windows(2).position(|w| w == b"(4").unwrap();
        hostile[pos + 1] = b'9';
        std::fs::write(&p, &hostile).unwrap();
        assert!(matches!(
            read_npy(&p, &o(None)),
            Err(IoError::Truncated { .. })
        ));
        let h2 = String::from_utf8_lossy(&good[..pos]).to_string()
            + "(4294967296, 4294967296"
            + &String::from_utf8_lossy(&good[pos + 2..]);
        std::fs::write(&p, h2.as_bytes()).unwrap();
        assert!(read_npy(&p, &o(None)).is_err());
        // NaN value.
        std::fs::write(&p, write_npy(&[2], false, &[1.0f64, f64::INFINITY])).unwrap();
        assert!(matches!(
            read_npy(&p, &o(None)),
            Err(IoError::NonFinite { index: 1, .. })
        ));
        // No rate.
        std::fs::write(&p, &good).unwrap();
        let e = read_npy(&p, &ReadOptions::default()).unwrap_err();
        assert!(matches!(e, IoError::MissingSampleRate { .. }));
        // The message says how to give one: the flag and the sidecar key.
        let msg = e.to_string();
        assert!(msg.contains("--fs HZ") && msg.contains("\"fs\""), "{msg}");
    }
}
