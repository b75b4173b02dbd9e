//! WAV decoding for [`super::wav`]: the RIFF chunk walk and the samples, read here rather
//! than by `hound`.
//!
//! Why not `hound` (3.5): it skips an unknown chunk of odd size without the pad byte RIFF
//! puts after it, so a Broadcast WAV (`bext`, `iXML`) or a `LIST` chunk of odd size before
//! `data` fails with "Failed to read enough bytes"; it takes the low bits of a
//! `WAVE_FORMAT_EXTENSIBLE` container whose valid bits are its top bits (24 valid bits in a
//! 32-bit container read as garbage); and it refuses 64-bit float.
//!
//! Read: chunks in any order (`data` before `fmt ` too), each followed by its pad byte when
//! its size is odd; a writer that left the pad byte out is followed when the byte after the
//! chunk, not the one after the pad, starts a chunk id. Formats: PCM (tag 1) integer in
//! 1–4-byte containers (8-bit unsigned, wider signed, little-endian), IEEE float (tag 3) of
//! 32 or 64 bits, and either inside `WAVE_FORMAT_EXTENSIBLE` (tag 0xFFFE, the sub-format
//! GUID's first two bytes). An integer sample is the whole container: valid bits are its top
//! bits (Microsoft, "WAVEFORMATEXTENSIBLE": the unused low bits are zero), so full scale is
//! 2^(container bits − 1) whatever `valid_bits_per_sample` says, and a 24-in-32 sample reads
//! as the same fraction of full scale as the 24-bit one. A trailing partial frame is
//! dropped. Every refusal names the chunk and the field.

use std::io::{BufReader, Read, Seek, SeekFrom};
use std::path::Path;

use super::error::IoError;

/// WAVE format tags (Microsoft `mmreg.h`).
const WAVE_FORMAT_PCM: u16 = 1;
const WAVE_FORMAT_IEEE_FLOAT: u16 = 3;
const WAVE_FORMAT_EXTENSIBLE: u16 = 0xFFFE;

/// What the `fmt ` chunk says, with the extensible header resolved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WavFormat {
    /// Interleaved channels.
    pub channels: u16,
    /// Frames per second, as stored (integer Hz).
    pub sample_rate: u32,
    /// Bits of one sample's container (`bits_per_sample` of the chunk).
    pub container_bits: u16,
    /// Bits that carry the sample (`valid_bits_per_sample` of the extensible header, else
    /// the container's).
    pub valid_bits: u16,
    /// IEEE float samples (else integer).
    pub float: bool,
}

/// A decoded WAV: its format and the interleaved samples, integers divided by
/// 2^(container bits − 1) (±1 full scale), floats as stored.
#[derive(Debug)]
pub struct Decoded {
    /// The format.
    pub format: WavFormat,
    /// Interleaved samples.
    pub interleaved: Vec<f64>,
}

/// Bytes decoded per read of the data chunk.
const BLOCK: usize = 1 << 16;

/// Decode the WAV file at `path` (`file_len` bytes long); see the module doc.
pub fn decode(path: &Path, file_len: u64) -> Result<Decoded, IoError> {
    let f = std::fs::File::open(path).map_err(|e| IoError::io(path, "open", e))?;
    let mut r = BufReader::new(f);
    let mut head = [0u8; 12];
    if file_len < 12 {
        return Err(IoError::truncated(
            path,
            format!("WAV: {file_len} bytes, less than the 12 of a RIFF/WAVE header"),
        ));
    }
    r.read_exact(&mut head)
        .map_err(|e| IoError::io(path, "read", e))?;
    if &head[0..4] != b"RIFF" || &head[8..12] != b"WAVE" {
        let found = String::from_utf8_lossy(&head[0..4]).into_owned();
        if matches!(&head[0..4], b"RF64" | b"BW64" | b"RIFX") {
            return Err(IoError::unsupported(
                path,
                format!("WAV: {found} container (64-bit or big-endian RIFF) is not read; save it as RIFF/WAVE"),
            ));
        }
        return Err(IoError::BadMagic {
            path: path.to_path_buf(),
            expected: "RIFF....WAVE".into(),
            found: format!(
                "{found}....{}",
                String::from_utf8_lossy(&head[8..12]).into_owned()
            ),
        });
    }
    let mut pos = 12u64;
    let mut fmt: Option<WavFormat> = None;
    let mut data: Option<(u64, u64)> = None; // offset, size
    let mut seen: Vec<String> = Vec::new();
    while fmt.is_none() || data.is_none() {
        if pos + 8 > file_len {
            let what = if fmt.is_none() { "`fmt `" } else { "`data`" };
            let after = if seen.is_empty() {
                "no chunk".to_string()
            } else {
                format!("chunks {}", seen.join(", "))
            };
            let detail = if pos < file_len {
                format!("WAV: no {what} chunk (the file ends inside a chunk header at byte {pos}, after {after})")
            } else {
                format!("WAV: no {what} chunk (read {after})")
            };
            return Err(IoError::truncated(path, detail));
        }
        let mut ch = [0u8; 8];
        r.seek(SeekFrom::Start(pos))
            .and_then(|_| r.read_exact(&mut ch))
            .map_err(|e| IoError::io(path, "read", e))?;
        let id = [ch[0], ch[1], ch[2], ch[3]];
        let name = String::from_utf8_lossy(&id).into_owned();
        let size = u64::from(u32::from_le_bytes([ch[4], ch[5], ch[6], ch[7]]));
        let body = pos + 8;
        let left = file_len - body;
        seen.push(format!("`{name}`"));
        match &id {
            b"fmt " => {
                if size > left {
                    return Err(IoError::truncated(
                        path,
                        format!("WAV `fmt ` chunk claims {size} bytes, {left} remain in the file"),
                    ));
                }
                let mut b = vec![0u8; usize::try_from(size.min(64)).unwrap_or(64)];
                r.read_exact(&mut b)
                    .map_err(|e| IoError::io(path, "read", e))?;
                fmt = Some(parse_fmt(path, &b)?);
            }
            b"data" => {
                if size > left {
                    return Err(IoError::truncated(
                        path,
                        format!("WAV `data` chunk claims {size} bytes, {left} remain in the file"),
                    ));
                }
                data = Some((body, size));
            }
            _ => {}
        }
        let padded = body.saturating_add(size + (size & 1));
        pos = if size & 1 == 1 && !chunk_id_at(&mut r, padded) && chunk_id_at(&mut r, padded - 1) {
            // The writer left out the pad byte.
            padded - 1
        } else {
            padded
        };
    }
    let (Some(format), Some((offset, size))) = (fmt, data) else {
        unreachable!("the walk ends with both chunks");
    };
    let bytes = usize::from(format.container_bits / 8);
    let frame = bytes * usize::from(format.channels);
    let frames = size / frame as u64;
    let claimed = frames * u64::from(format.channels);
    super::record::check_record_size(
        path,
        usize::try_from(frames).unwrap_or(usize::MAX),
        usize::try_from(claimed).unwrap_or(usize::MAX),
    )?;
    let n = usize::try_from(claimed).unwrap_or(0);
    let mut interleaved = Vec::with_capacity(n);
    let full_scale = 2f64.powi(i32::from(format.container_bits) - 1);
    r.seek(SeekFrom::Start(offset))
        .map_err(|e| IoError::io(path, "seek", e))?;
    let mut buf = vec![0u8; BLOCK - BLOCK % frame];
    let mut remaining = n * bytes;
    while remaining > 0 {
        let chunk = &mut buf[..remaining.min(BLOCK - BLOCK % frame)];
        r.read_exact(chunk)
            .map_err(|e| IoError::truncated(path, format!("WAV `data` chunk ends early: {e}")))?;
        remaining -= chunk.len();
        for s in chunk.chunks_exact(bytes) {
            interleaved.push(match (format.float, bytes) {
                (true, 4) => f64::from(f32::from_le_bytes([s[0], s[1], s[2], s[3]])),
                (true, _) => f64::from_le_bytes([s[0], s[1], s[2], s[3], s[4], s[5], s[6], s[7]]),
                (false, 1) => f64::from(i32::from(s[0]) - 128) / full_scale,
                (false, 2) => f64::from(i16::from_le_bytes([s[0], s[1]])) / full_scale,
                (false, 3) => {
                    f64::from(i32::from_le_bytes([0, s[0], s[1], s[2]]) >> 8) / full_scale
                }
                (false, _) => f64::from(i32::from_le_bytes([s[0], s[1], s[2], s[3]])) / full_scale,
            });
        }
    }
    Ok(Decoded {
        format,
        interleaved,
    })
}

/// Whether the 4 bytes at `at` look like a chunk id (printable ASCII), the file position
/// left wherever; false past the end.
fn chunk_id_at<R: Read + Seek>(r: &mut R, at: u64) -> bool {
    let mut id = [0u8; 4];
    r.seek(SeekFrom::Start(at)).is_ok()
        && r.read_exact(&mut id).is_ok()
        && id.iter().all(|b| (0x20..0x7f).contains(b))
}

/// The format of a `fmt ` chunk's first bytes `b` (at most 64), checked field by field.
fn parse_fmt(path: &Path, b: &[u8]) -> Result<WavFormat, IoError> {
    let bad = |m: String| IoError::malformed(path, format!("WAV `fmt ` chunk: {m}"));
    if b.len() < 16 {
        return Err(bad(format!("{} bytes, at least 16 needed", b.len())));
    }
    let u16_at = |i: usize| u16::from_le_bytes([b[i], b[i + 1]]);
    let tag = u16_at(0);
    let channels = u16_at(2);
    let sample_rate = u32::from_le_bytes([b[4], b[5], b[6], b[7]]);
    let block_align = u16_at(12);
    let container_bits = u16_at(14);
    let (tag, valid_bits) = if tag == WAVE_FORMAT_EXTENSIBLE {
        if b.len() < 40 {
            return Err(bad(format!(
                "WAVE_FORMAT_EXTENSIBLE needs 40 bytes, the chunk has {}",
                b.len()
            )));
        }
        // valid_bits_per_sample 0: not stated, the whole container.
        let valid = match u16_at(18) {
            0 => container_bits,
            v => v,
        };
        (u16_at(24), valid)
    } else {
        (tag, container_bits)
    };
    if channels == 0 {
        return Err(bad("channels is 0".into()));
    }
    if sample_rate == 0 {
        return Err(bad("sample_rate is 0".into()));
    }
    let float = match tag {
        WAVE_FORMAT_PCM => false,
        WAVE_FORMAT_IEEE_FLOAT => true,
        t => {
            return Err(IoError::unsupported(
                path,
                format!("WAV `fmt ` chunk: format tag {t:#06x} (read: 1 = PCM integer, 3 = IEEE float, either inside 0xFFFE extensible)"),
            ))
        }
    };
    // A PCM `bits_per_sample` that is no whole number of bytes (12) sits in the next
    // larger container, as the block alignment says.
    let container_bits = if float {
        container_bits
    } else {
        // Saturating: a `bits_per_sample` near 65535 (fuzzed) overflowed; any such value
        // is refused as unsupported just below.
        container_bits.div_ceil(8).saturating_mul(8)
    };
    let supported: &[u16] = if float { &[32, 64] } else { &[8, 16, 24, 32] };
    if !supported.contains(&container_bits) {
        return Err(IoError::unsupported(
            path,
            format!(
                "WAV `fmt ` chunk: bits_per_sample {} for {} samples (read: {})",
                u16_at(14),
                if float { "float" } else { "integer" },
                if float { "32, 64" } else { "8, 16, 24, 32" }
            ),
        ));
    }
    if valid_bits > container_bits {
        return Err(bad(format!(
            "valid_bits_per_sample {valid_bits} exceeds the {container_bits}-bit container (bits_per_sample)"
        )));
    }
    if float && valid_bits != container_bits {
        return Err(bad(format!(
            "valid_bits_per_sample {valid_bits} in a {container_bits}-bit float container"
        )));
    }
    let want = u32::from(channels) * u32::from(container_bits / 8);
    if u32::from(block_align) != want {
        return Err(bad(format!(
            "block_align {block_align}, {channels} channels of {container_bits} bits need {want}"
        )));
    }
    Ok(WavFormat {
        channels,
        sample_rate,
        container_bits,
        valid_bits,
        float,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::{wav::read_wav, ReadOptions};

    /// A chunk: id, size, body and, for an odd size, the pad byte when `pad`.
    fn chunk(id: &[u8; 4], body: &[u8], pad: bool) -> Vec<u8> {
        let mut c = id.to_vec();
        c.extend_from_slice(&(body.len() as u32).to_le_bytes());
        c.extend_from_slice(body);
        if pad && body.len() % 2 == 1 {
            c.push(0);
        }
        c
    }

    fn riff(chunks: &[Vec<u8>]) -> Vec<u8> {
        let body: Vec<u8> = b"WAVE"
            .iter()
            .chain(chunks.iter().flatten())
            .copied()
            .collect();
        let mut out = b"RIFF".to_vec();
        out.extend_from_slice(&(body.len() as u32).to_le_bytes());
        out.extend_from_slice(&body);
        out
    }

    /// A `fmt ` body: PCM (`valid` = None) or extensible PCM with `valid` bits.
    fn fmt(channels: u16, rate: u32, bits: u16, valid: Option<u16>) -> Vec<u8> {
        let align = channels * bits / 8;
        let tag: u16 = if valid.is_some() { 0xFFFE } else { 1 };
        let mut f = Vec::new();
        for v in [tag, channels] {
            f.extend_from_slice(&v.to_le_bytes());
        }
        f.extend_from_slice(&rate.to_le_bytes());
        f.extend_from_slice(&(rate * u32::from(align)).to_le_bytes());
        for v in [align, bits] {
            f.extend_from_slice(&v.to_le_bytes());
        }
        if let Some(v) = valid {
            for x in [22u16, v] {
                f.extend_from_slice(&x.to_le_bytes());
            }
            f.extend_from_slice(&4u32.to_le_bytes());
            f.extend_from_slice(&[
                1, 0, 0, 0, 0, 0, 0x10, 0, 0x80, 0, 0, 0xAA, 0, 0x38, 0x9B, 0x71,
            ]);
        }
        f
    }

    fn pcm16(x: &[i16]) -> Vec<u8> {
        x.iter().flat_map(|v| v.to_le_bytes()).collect()
    }

    fn read(bytes: &[u8]) -> Result<crate::io::Record, IoError> {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("x.wav");
        std::fs::write(&p, bytes).unwrap();
        read_wav(&p, &ReadOptions::default())
    }

    /// Odd-sized chunks before `data` (Broadcast WAV `iXML` after `fmt `, `bext` before it,
    /// `LIST`), padded as RIFF requires or, from a writer that forgot, not; and `data`
    /// before `fmt `: all read the same samples (hound failed on the first three with
    /// "Failed to read enough bytes").
    #[test]
    fn odd_chunks_and_any_order_read_the_samples() {
        let x = [16384i16, -32768, 0, 1, 32767, -3];
        let want: Vec<f64> = x.iter().map(|&v| f64::from(v) / 32768.0).collect();
        let f = chunk(b"fmt ", &fmt(1, 12_000, 16, None), true);
        let d = chunk(b"data", &pcm16(&x), true);
        let ixml = b"<?xml version=\"1.0\"?><BWFXML />";
        assert_eq!(ixml.len() % 2, 1);
        let bext = vec![7u8; 603];
        for pad in [true, false] {
            for file in [
                riff(&[f.clone(), chunk(b"iXML", ixml, pad), d.clone()]),
                riff(&[chunk(b"bext", &bext, pad), f.clone(), d.clone()]),
                riff(&[
                    f.clone(),
                    chunk(b"LIST", b"INFOISFT\x03\0\0\0abc", pad),
                    d.clone(),
                ]),
                riff(&[d.clone(), chunk(b"junk", b"odd", pad), f.clone()]),
            ] {
                let r = read(&file).unwrap();
                assert_eq!(r.samples, want, "pad {pad}");
                assert_eq!((r.fs, r.unit.as_str()), (12_000.0, "FS"));
            }
        }
    }

    /// `WAVE_FORMAT_EXTENSIBLE` with fewer valid bits than the container: the valid bits are
    /// the top bits, so 24 in 32 and 20 in 24 read as the same fraction of full scale as
    /// plain 24-bit samples (hound took the low bits: garbage). Impossible fields are named.
    #[test]
    fn valid_bits_are_the_top_bits_of_the_container() {
        let v24 = [4_194_304i32, -8_388_608, 1, -1, 8_388_607];
        let want: Vec<f64> = v24.iter().map(|&v| f64::from(v) / 8_388_608.0).collect();
        let in32: Vec<u8> = v24.iter().flat_map(|v| (v << 8).to_le_bytes()).collect();
        let r = read(&riff(&[
            chunk(b"fmt ", &fmt(1, 8000, 32, Some(24)), true),
            chunk(b"data", &in32, true),
        ]))
        .unwrap();
        assert_eq!(r.samples, want);
        assert_eq!(r.meta["bits_per_sample"], 32);
        assert_eq!(r.meta["valid_bits_per_sample"], 24);
        // 20 valid bits in a 24-bit container: the low 4 bits zero.
        let v20 = [262_144i32, -524_288, 1, 524_287];
        let in24: Vec<u8> = v20
            .iter()
            .flat_map(|v| (v << 4).to_le_bytes()[..3].to_vec())
            .collect();
        let r = read(&riff(&[
            chunk(b"fmt ", &fmt(1, 8000, 24, Some(20)), true),
            chunk(b"data", &in24, true),
        ]))
        .unwrap();
        let want: Vec<f64> = v20.iter().map(|&v| f64::from(v) / 524_288.0).collect();
        assert_eq!(r.samples, want);
        // 24 valid bits in a 24-bit container: plain 24-bit.
        let plain: Vec<u8> = v24
            .iter()
            .flat_map(|v| v.to_le_bytes()[..3].to_vec())
            .collect();
        let r = read(&riff(&[
            chunk(b"fmt ", &fmt(1, 8000, 24, Some(24)), true),
            chunk(b"data", &plain, true),
        ]))
        .unwrap();
        assert_eq!(r.samples[4], 8_388_607.0 / 8_388_608.0);
        // More valid bits than the container, a block alignment that does not fit.
        let e = read(&riff(&[
            chunk(b"fmt ", &fmt(1, 8000, 24, Some(28)), true),
            chunk(b"data", &in24, true),
        ]))
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("valid_bits_per_sample 28") && e.contains("`fmt `"),
            "{e}"
        );
        let mut f = fmt(1, 8000, 16, None);
        f[12] = 4;
        let e = read(&riff(&[
            chunk(b"fmt ", &f, true),
            chunk(b"data", &pcm16(&[1]), true),
        ]))
        .unwrap_err()
        .to_string();
        assert!(e.contains("block_align 4"), "{e}");
    }

    /// Refusals name the chunk: a `data` or `fmt ` chunk longer than the file, no `fmt `,
    /// an unread format tag.
    #[test]
    fn refusals_name_the_chunk_and_field() {
        let f = chunk(b"fmt ", &fmt(1, 8000, 16, None), true);
        let d = chunk(b"data", &pcm16(&[1, 2, 3]), true);
        let mut long = riff(&[f.clone(), d.clone()]);
        let n = long.len();
        long[n - 10..n - 6].copy_from_slice(&100u32.to_le_bytes());
        let e = read(&long).unwrap_err().to_string();
        assert!(e.contains("`data` chunk claims 100 bytes"), "{e}");
        let e = read(&riff(std::slice::from_ref(&d)))
            .unwrap_err()
            .to_string();
        assert!(e.contains("no `fmt ` chunk") && e.contains("`data`"), "{e}");
        let mut alaw = fmt(1, 8000, 8, None);
        alaw[0] = 6;
        let e = read(&riff(&[chunk(b"fmt ", &alaw, true), d.clone()]))
            .unwrap_err()
            .to_string();
        assert!(e.contains("format tag 0x0006"), "{e}");
        let e = read(&riff(&[
            chunk(b"fmt ", &fmt(1, 8000, 16, None)[..14], true),
            d,
        ]))
        .unwrap_err()
        .to_string();
        assert!(e.contains("`fmt ` chunk: 14 bytes"), "{e}");
        // The fuzzer's find: a PCM `bits_per_sample` of 65535 overflowed the rounding to a
        // whole container (a panic); it is an unsupported size.
        let mut huge = fmt(1, 8000, 16, None);
        huge[14..16].copy_from_slice(&u16::MAX.to_le_bytes());
        let e = read(&riff(&[
            chunk(b"fmt ", &huge, true),
            chunk(b"data", &pcm16(&[1, 2, 3]), true),
        ]))
        .unwrap_err()
        .to_string();
        assert!(e.contains("bits_per_sample 65535"), "{e}");
    }
}
