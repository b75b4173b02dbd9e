//! The MAT v5 format: header, elements, compressed elements and numeric matrices, with
//! every size checked before anything is allocated and a per-file [`Budget`].

use std::io::Read;
use std::path::Path;

use serde::Serialize;

use crate::io::error::IoError;

/// MATLAB array class of a MAT v5 variable (`mxCLASS` codes 1..15 of the format).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum MatClass {
    /// Cell array (1); listed, not read.
    Cell,
    /// Structure (2); listed, not read.
    Struct,
    /// Object (3); listed, not read.
    Object,
    /// Character array (4); listed, not read.
    Char,
    /// Sparse array (5); listed, not read.
    Sparse,
    /// Double precision (6).
    Double,
    /// Single precision (7).
    Single,
    /// Signed 8-bit integer (8).
    Int8,
    /// Unsigned 8-bit integer (9).
    UInt8,
    /// Signed 16-bit integer (10).
    Int16,
    /// Unsigned 16-bit integer (11).
    UInt16,
    /// Signed 32-bit integer (12).
    Int32,
    /// Unsigned 32-bit integer (13).
    UInt32,
    /// Signed 64-bit integer (14).
    Int64,
    /// Unsigned 64-bit integer (15).
    UInt64,
    /// Any other code.
    Other(u8),
}

impl MatClass {
    pub(crate) fn from_code(c: u8) -> Self {
        use MatClass::*;
        match c {
            1 => Cell,
            2 => Struct,
            3 => Object,
            4 => Char,
            5 => Sparse,
            6 => Double,
            7 => Single,
            8 => Int8,
            9 => UInt8,
            10 => Int16,
            11 => UInt16,
            12 => Int32,
            13 => UInt32,
            14 => Int64,
            15 => UInt64,
            o => Other(o),
        }
    }

    /// True for the numeric classes whose real part this reader converts to `f64`.
    pub fn is_numeric(self) -> bool {
        use MatClass::*;
        matches!(
            self,
            Double | Single | Int8 | UInt8 | Int16 | UInt16 | Int32 | UInt32 | Int64 | UInt64
        )
    }
}

// MAT v5 data types (miXXX codes).
pub(crate) const MI_INT8: u32 = 1;
pub(crate) const MI_UINT8: u32 = 2;
pub(crate) const MI_INT16: u32 = 3;
pub(crate) const MI_UINT16: u32 = 4;
pub(crate) const MI_INT32: u32 = 5;
pub(crate) const MI_UINT32: u32 = 6;
pub(crate) const MI_SINGLE: u32 = 7;
pub(crate) const MI_DOUBLE: u32 = 9;
pub(crate) const MI_INT64: u32 = 12;
pub(crate) const MI_UINT64: u32 = 13;
pub(crate) const MI_MATRIX: u32 = 14;
pub(crate) const MI_COMPRESSED: u32 = 15;
pub(crate) const MI_UTF8: u32 = 16;

/// Deflate cannot expand by more than about 1032:1; a larger inflated size is a bomb.
const MAX_INFLATE_RATIO: usize = 1032;
/// Most bytes inflated from compressed elements per file, all elements and nesting levels
/// together: 2²⁸ (256 MiB). A file needing more is refused ([`IoError::TooLarge`]) after
/// inflating at most this much, so a zlib bomb costs bounded memory and time.
pub const MAX_DECOMPRESSED_PER_FILE: usize = 1 << 28;
/// Most numeric elements converted to `f64` per file, all selected variables together:
/// [`MAX_RECORD_SAMPLES`](crate::io::record::MAX_RECORD_SAMPLES) (2²³, 64 MiB of f64).
/// Checked on the declared dimensions before the conversion allocates, so widening a
/// compressed int8 array (×8) cannot exceed it.
pub const MAX_SAMPLES_PER_FILE: usize = crate::io::record::MAX_RECORD_SAMPLES;

/// What is left of a file's resource bounds while it is parsed (see
/// [`MAX_DECOMPRESSED_PER_FILE`], [`MAX_SAMPLES_PER_FILE`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Budget {
    /// Bytes that may still be inflated.
    pub decompressed_left: usize,
    /// Elements that may still be converted to `f64`.
    pub samples_left: usize,
}

impl Default for Budget {
    fn default() -> Self {
        Budget {
            decompressed_left: MAX_DECOMPRESSED_PER_FILE,
            samples_left: MAX_SAMPLES_PER_FILE,
        }
    }
}

/// One element of a MAT stream: its offset in the stream, data type and data.
pub(crate) type Element<'a> = (usize, u32, &'a [u8]);

/// Bounds-checked little/big-endian cursor over a byte slice.
pub(crate) struct Cursor<'a> {
    pub(crate) buf: &'a [u8],
    pub(crate) pos: usize,
    pub(crate) big: bool,
    pub(crate) path: &'a Path,
    /// Human-readable context for error messages ("file", "compressed element at 0x..").
    pub(crate) ctx: &'a str,
}

impl<'a> Cursor<'a> {
    pub(crate) fn remaining(&self) -> usize {
        self.buf.len() - self.pos
    }

    pub(crate) fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8], IoError> {
        if n > self.remaining() {
            return Err(IoError::truncated(
                self.path,
                format!(
                    "{what} needs {n} bytes at offset {} of {}, only {} left",
                    self.pos,
                    self.ctx,
                    self.remaining()
                ),
            ));
        }
        let s = &self.buf[self.pos..self.pos + n];
        self.pos += n;
        Ok(s)
    }

    pub(crate) fn u32(&mut self, what: &str) -> Result<u32, IoError> {
        let b = self.take(4, what)?;
        let a = [b[0], b[1], b[2], b[3]];
        Ok(if self.big {
            u32::from_be_bytes(a)
        } else {
            u32::from_le_bytes(a)
        })
    }

    /// The next element of the stream: `(offset, data type, data)`, its padding not yet
    /// skipped ([`Cursor::skip_padding`]; compressed elements have none); small elements
    /// (data inside the tag) are passed over; `None` at the end. Trailing bytes shorter than
    /// a tag are an error: MATLAB never writes them.
    pub(crate) fn next_element(&mut self) -> Result<Option<Element<'a>>, IoError> {
        loop {
            match self.remaining() {
                0 => return Ok(None),
                r if r < 8 => {
                    return Err(IoError::truncated(
                        self.path,
                        format!(
                            "{r} stray bytes at offset {} of {} (shorter than an element tag)",
                            self.pos, self.ctx
                        ),
                    ))
                }
                _ => {}
            }
            let at = self.pos;
            let (ty, n, small) = self.tag("element tag")?;
            if small {
                self.take(4, "small element")?;
                continue;
            }
            return Ok(Some((at, ty, self.take(n, "element data")?)));
        }
    }

    /// Skips the padding that aligns an uncompressed element of `n` bytes to 8 bytes (as
    /// much of it as the stream holds).
    pub(crate) fn skip_padding(&mut self, n: usize) {
        self.pos += ((8 - n % 8) % 8).min(self.remaining());
    }

    /// A cursor over `buf` (an inflated compressed element, described by `ctx`) with this
    /// one's byte order and file.
    pub(crate) fn inner<'b>(&self, buf: &'b [u8], ctx: &'b str) -> Cursor<'b>
    where
        'a: 'b,
    {
        Cursor {
            buf,
            pos: 0,
            big: self.big,
            path: self.path,
            ctx,
        }
    }

    /// Read an element tag; returns (data type, byte count, small-format flag).
    pub(crate) fn tag(&mut self, what: &str) -> Result<(u32, usize, bool), IoError> {
        let first = self.u32(what)?;
        if first >> 16 != 0 {
            // Small data element: type in the low half, byte count in the high half, data in
            // the next 4 bytes.
            let ty = first & 0xFFFF;
            let n = (first >> 16) as usize;
            if n > 4 {
                return Err(IoError::malformed(
                    self.path,
                    format!(
                        "{what}: small element claims {n} bytes (max 4) in {}",
                        self.ctx
                    ),
                ));
            }
            Ok((ty, n, true))
        } else {
            let n = self.u32(what)? as usize;
            Ok((first, n, false))
        }
    }

    /// Read one sub-element (tag + data + padding); returns (type, data bytes).
    pub(crate) fn sub_element(&mut self, what: &str) -> Result<(u32, &'a [u8]), IoError> {
        let (ty, n, small) = self.tag(what)?;
        if small {
            let four = self.take(4, what)?;
            Ok((ty, &four[..n]))
        } else {
            let data = self.take(n, what)?;
            let pad = (8 - n % 8) % 8;
            // The final padding of the last sub-element may be missing in some writers.
            let pad = pad.min(self.remaining());
            self.pos += pad;
            Ok((ty, data))
        }
    }

    /// Read a matrix's array-flags sub-element (miUINT32, 8 bytes); returns its first word
    /// (class in the low byte, the complex and logical bits above it).
    pub(crate) fn array_flags(&mut self) -> Result<u32, IoError> {
        let (ty, flags) = self.sub_element("array flags")?;
        if ty != MI_UINT32 || flags.len() != 8 {
            return Err(IoError::malformed(
                self.path,
                format!(
                    "{}: array flags sub-element has type {ty} and {} bytes (expected miUINT32, 8)",
                    self.ctx,
                    flags.len()
                ),
            ));
        }
        let word = [flags[0], flags[1], flags[2], flags[3]];
        Ok(if self.big {
            u32::from_be_bytes(word)
        } else {
            u32::from_le_bytes(word)
        })
    }

    /// Read a matrix's array-name sub-element (miINT8, miUINT8 or miUTF8), decoded as UTF-8
    /// (invalid bytes replaced).
    pub(crate) fn array_name(&mut self) -> Result<String, IoError> {
        let (ty, name_raw) = self.sub_element("array name")?;
        if ty != MI_INT8 && ty != MI_UINT8 && ty != MI_UTF8 {
            return Err(IoError::malformed(
                self.path,
                format!(
                    "{}: array name sub-element has type {ty} (expected miINT8)",
                    self.ctx
                ),
            ));
        }
        Ok(String::from_utf8_lossy(name_raw).into_owned())
    }
}

/// Check the 128-byte MAT v5 header of `bytes`; returns true for big-endian (`MI`) files.
pub(crate) fn parse_header(bytes: &[u8], path: &Path) -> Result<bool, IoError> {
    if bytes.is_empty() {
        return Err(IoError::truncated(
            path,
            "empty file (a MAT v5 file has a 128-byte header)",
        ));
    }
    if bytes.len() < 128 {
        return Err(IoError::truncated(
            path,
            format!("{} bytes, a MAT v5 header alone is 128", bytes.len()),
        ));
    }
    let text = &bytes[..116];
    if !text.starts_with(b"MATLAB 5.0 MAT-file") {
        let shown: String = text[..text.len().min(20)]
            .iter()
            .map(|&b| {
                if b.is_ascii_graphic() || b == b' ' {
                    b as char
                } else {
                    '.'
                }
            })
            .collect();
        if text.starts_with(b"MATLAB 7.3") || bytes.starts_with(b"\x89HDF") {
            return Err(IoError::unsupported(
                path,
                "MATLAB 7.3 (HDF5) MAT-file; none of the public layouts read here needs it: re-save it as level 5 in MATLAB (`save(f, '-v7')`) or Octave (`save -v7 f`), or write the channel to CSV/NPY",
            ));
        }
        return Err(IoError::BadMagic {
            path: path.to_path_buf(),
            expected: "\"MATLAB 5.0 MAT-file\" header text".into(),
            found: format!("{shown:?}"),
        });
    }
    let big = match &bytes[126..128] {
        b"IM" => false,
        b"MI" => true,
        other => {
            return Err(IoError::BadMagic {
                path: path.to_path_buf(),
                expected: "endian indicator \"IM\" or \"MI\" at offset 126".into(),
                found: format!("{:?}", String::from_utf8_lossy(other)),
            })
        }
    };
    Ok(big)
}

pub(crate) fn inflate(
    data: &[u8],
    path: &Path,
    at: usize,
    budget: &mut Budget,
) -> Result<Vec<u8>, IoError> {
    let ratio_cap = data
        .len()
        .saturating_mul(MAX_INFLATE_RATIO)
        .saturating_add(1024);
    let cap = ratio_cap.min(budget.decompressed_left);
    let mut out = Vec::with_capacity(data.len().saturating_mul(4).min(cap));
    let mut dec = flate2::read::ZlibDecoder::new(data).take(cap as u64 + 1);
    dec.read_to_end(&mut out).map_err(|e| {
        IoError::malformed(
            path,
            format!("compressed element at offset {at}: zlib: {e}"),
        )
    })?;
    if out.len() > cap && cap < ratio_cap {
        return Err(IoError::TooLarge {
            path: path.to_path_buf(),
            what: format!(
                "decompressed data (compressed element at offset {at} inflates past the {} bytes left)",
                budget.decompressed_left
            ),
            limit: format!("{MAX_DECOMPRESSED_PER_FILE} bytes (256 MiB) decompressed per file"),
        });
    }
    if out.len() > cap {
        return Err(IoError::contradiction(
            path,
            format!(
                "compressed element at offset {at} inflates beyond {cap} bytes ({} compressed)",
                data.len()
            ),
        ));
    }
    budget.decompressed_left -= out.len();
    Ok(out)
}

/// The real part of a numeric array of `numel` elements (dimensions `dims`), decoded to
/// `f64`: the next sub-element of `c`, checked to be an integer or float MAT type whose byte
/// count holds exactly `numel` elements, and charged to the per-file conversion `budget`
/// ([`MAX_SAMPLES_PER_FILE`]). `what` names the array in the messages (the tree's numeric
/// arrays, `super::tree`).
pub(crate) fn read_real_part(
    c: &mut Cursor<'_>,
    path: &Path,
    what: &str,
    dims: &[usize],
    numel: usize,
    budget: &mut Budget,
) -> Result<Vec<f64>, IoError> {
    let (ty, real) = c.sub_element("real part")?;
    let width = match ty {
        MI_INT8 | MI_UINT8 => 1,
        MI_INT16 | MI_UINT16 => 2,
        MI_INT32 | MI_UINT32 | MI_SINGLE => 4,
        MI_DOUBLE | MI_INT64 | MI_UINT64 => 8,
        other => {
            return Err(IoError::unsupported(
                path,
                format!("{what} stores its data as MAT type {other}"),
            ))
        }
    };
    if real.len() % width != 0 || real.len() / width != numel {
        return Err(IoError::contradiction(
            path,
            format!(
                "{what} has dimensions {dims:?} ({numel} elements) but {} data bytes of {width}-byte type {ty}",
                real.len()
            ),
        ));
    }
    if numel > budget.samples_left {
        return Err(IoError::TooLarge {
            path: path.to_path_buf(),
            what: format!(
                "{what} with {numel} elements ({} bytes as f64)",
                numel.saturating_mul(8)
            ),
            limit: format!(
                "{MAX_SAMPLES_PER_FILE} samples (2^23, 64 MiB of f64) converted per file"
            ),
        });
    }
    budget.samples_left -= numel;
    Ok(decode_numeric(ty, width, real, c.big))
}

/// Convert the real-part bytes `real` of MAT type `ty` (element width `width` bytes) to
/// `f64`. The caller has checked `real.len()` against the declared element count.
pub(crate) fn decode_numeric(ty: u32, width: usize, real: &[u8], big: bool) -> Vec<f64> {
    let numel = real.len() / width.max(1);
    let mut data = Vec::with_capacity(numel);
    for ch in real.chunks_exact(width) {
        let v = match (ty, width) {
            (MI_INT8, _) => ch[0] as i8 as f64,
            (MI_UINT8, _) => ch[0] as f64,
            (MI_INT16, _) => {
                let a = [ch[0], ch[1]];
                (if big {
                    i16::from_be_bytes(a)
                } else {
                    i16::from_le_bytes(a)
                }) as f64
            }
            (MI_UINT16, _) => {
                let a = [ch[0], ch[1]];
                (if big {
                    u16::from_be_bytes(a)
                } else {
                    u16::from_le_bytes(a)
                }) as f64
            }
            (_, 4) => {
                let a = [ch[0], ch[1], ch[2], ch[3]];
                match ty {
                    MI_INT32 => {
                        (if big {
                            i32::from_be_bytes(a)
                        } else {
                            i32::from_le_bytes(a)
                        }) as f64
                    }
                    MI_UINT32 => {
                        (if big {
                            u32::from_be_bytes(a)
                        } else {
                            u32::from_le_bytes(a)
                        }) as f64
                    }
                    _ => {
                        (if big {
                            f32::from_be_bytes(a)
                        } else {
                            f32::from_le_bytes(a)
                        }) as f64
                    }
                }
            }
            _ => {
                let a = [ch[0], ch[1], ch[2], ch[3], ch[4], ch[5], ch[6], ch[7]];
                match ty {
                    MI_INT64 => {
                        (if big {
                            i64::from_be_bytes(a)
                        } else {
                            i64::from_le_bytes(a)
                        }) as f64
                    }
                    MI_UINT64 => {
                        (if big {
                            u64::from_be_bytes(a)
                        } else {
                            u64::from_le_bytes(a)
                        }) as f64
                    }
                    _ => {
                        if big {
                            f64::from_be_bytes(a)
                        } else {
                            f64::from_le_bytes(a)
                        }
                    }
                }
            }
        };
        data.push(v);
    }
    data
}

/// Largest MAT file read (bytes): 2²⁹ (512 MiB), twice what [`MAX_SAMPLES_PER_FILE`]
/// doubles take uncompressed.
pub const MAX_FILE_BYTES: u64 = 1 << 29;

pub(crate) fn read_file(path: &Path) -> Result<Vec<u8>, IoError> {
    crate::io::record::read_capped(
        path,
        MAX_FILE_BYTES,
        "file",
        &format!("{MAX_FILE_BYTES} bytes (512 MiB) per MAT file"),
    )
}
