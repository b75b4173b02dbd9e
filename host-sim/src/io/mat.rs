//! MATLAB level-5 MAT-file reader and the CWRU bearing-data loader.
//!
//! # Why not the `matfile` crate
//!
//! `matfile` 0.5 was evaluated (source read, version 0.5.0) and not used, because on malformed
//! input it can panic or allocate without bound, which the readers of this crate must never do:
//!
//! * numeric matrices: `dimensions.iter().product::<i32>()` overflows (a panic with overflow
//!   checks on, e.g. in test builds) for large or hostile dimensions, and the product is then cast
//!   `as usize`, so negative dimensions turn into huge counts;
//! * `flags.class.numeric_data_type().unwrap()` on the class byte read from the file;
//! * `miCOMPRESSED` elements are inflated with `read_to_end` without any limit (a zlib bomb
//!   allocates until the process dies), and decoder errors are printed with `eprintln!`;
//! * every error is a `nom` `ErrorKind::Tag` without offset or reason, so a user cannot tell
//!   "truncated" from "unsupported"; it also pulls in `nom`, `libflate` and
//!   `enum-primitive-derive` for what is a few hundred lines of format.
//!
//! This module therefore implements the subset of the format the measured data needs
//! (MathWorks, "MAT-File Format", Level 5): the 128-byte header (either byte order, `IM` or
//! `MI`), `miMATRIX` elements of the numeric classes (double, single, int8..uint64; real part
//! only; complex arrays are reported as unsupported), small-data-element tags, `miCOMPRESSED`
//! (zlib, via `flate2`, inflated size capped at 1032 x the compressed size, the deflate maximum),
//! and skips char/cell/struct/sparse/object arrays while still listing them. Every read is
//! bounds-checked against the buffer, sizes are checked against the file size before anything is
//! allocated, and no code path panics on any input (property-tested in `tests/io_fuzz.rs`).
//!
//! # CWRU files
//!
//! [`read_cwru`] loads one channel of a Case Western Reserve University bearing-data file
//! (see `/work/shared/data/cwru/README.md`): variables `Xnnn_DE_time`, `Xnnn_FE_time`,
//! `Xnnn_BA_time` (N x 1 double, acceleration, assumed g) and `XnnnRPM` (1 x 1, rpm). Variables
//! are selected by suffix, preferring the one whose number matches the record number of the file
//! name (some CWRU files hold other records' variables too). The sample rate is not stored in the
//! files; it comes from the name (`12k_` = 12 kHz, `48k_` = 48 kHz, `normal_*` = 48 kHz) or from
//! the caller.

use std::io::Read;
use std::path::{Path, PathBuf};

use serde::Serialize;
use serde_json::json;

use super::error::IoError;
use super::record::{check_finite, check_fs, check_rpm, Record};

// ---------------------------------------------------------------------------------------------
// Generic MAT v5 reader
// ---------------------------------------------------------------------------------------------

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
    fn from_code(c: u8) -> Self {
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

/// One top-level variable of a MAT v5 file.
#[derive(Debug, Clone)]
pub struct MatVariable {
    /// Variable name as stored.
    pub name: String,
    /// MATLAB class.
    pub class: MatClass,
    /// Dimensions (rows, columns, ...).
    pub dims: Vec<usize>,
    /// Real part converted to `f64`, column-major, `dims.iter().product()` long; empty for
    /// non-numeric classes, complex arrays and variables that were not requested.
    pub data: Vec<f64>,
    /// True if the array has an imaginary part (not read).
    pub complex: bool,
}

impl MatVariable {
    /// Number of elements (product of `dims`, saturating).
    pub fn numel(&self) -> usize {
        self.dims
            .iter()
            .fold(1usize, |acc, &d| acc.saturating_mul(d))
    }
}

// MAT v5 data types (miXXX codes).
const MI_INT8: u32 = 1;
const MI_UINT8: u32 = 2;
const MI_INT16: u32 = 3;
const MI_UINT16: u32 = 4;
const MI_INT32: u32 = 5;
const MI_UINT32: u32 = 6;
const MI_SINGLE: u32 = 7;
const MI_DOUBLE: u32 = 9;
const MI_INT64: u32 = 12;
const MI_UINT64: u32 = 13;
const MI_MATRIX: u32 = 14;
const MI_COMPRESSED: u32 = 15;
const MI_UTF8: u32 = 16;

/// Deflate cannot expand by more than about 1032:1; a larger inflated size is a bomb.
const MAX_INFLATE_RATIO: usize = 1032;
/// Absolute cap on one inflated element (1 GiB).
const MAX_INFLATED: usize = 1 << 30;
/// Nesting limit for compressed-in-compressed elements.
const MAX_DEPTH: u32 = 4;

/// Bounds-checked little/big-endian cursor over a byte slice.
struct Cursor<'a> {
    buf: &'a [u8],
    pos: usize,
    big: bool,
    path: &'a Path,
    /// Human-readable context for error messages ("file", "compressed element at 0x..").
    ctx: &'a str,
}

impl<'a> Cursor<'a> {
    fn remaining(&self) -> usize {
        self.buf.len() - self.pos
    }

    fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8], IoError> {
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

    fn u32(&mut self, what: &str) -> Result<u32, IoError> {
        let b = self.take(4, what)?;
        let a = [b[0], b[1], b[2], b[3]];
        Ok(if self.big {
            u32::from_be_bytes(a)
        } else {
            u32::from_le_bytes(a)
        })
    }

    /// Read an element tag; returns (data type, byte count, small-format flag).
    fn tag(&mut self, what: &str) -> Result<(u32, usize, bool), IoError> {
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
    fn sub_element(&mut self, what: &str) -> Result<(u32, &'a [u8]), IoError> {
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
}

/// Parse a MAT v5 file from `bytes`. `want(name)` selects the variables whose data are
/// converted; the others are listed with empty `data`.
pub fn parse_mat(
    bytes: &[u8],
    path: &Path,
    want: &dyn Fn(&str) -> bool,
) -> Result<Vec<MatVariable>, IoError> {
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
            return Err(IoError::unsupported(path, "MATLAB 7.3 (HDF5) MAT-file"));
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
    let mut out = Vec::new();
    let mut cur = Cursor {
        buf: bytes,
        pos: 128,
        big,
        path,
        ctx: "file",
    };
    parse_elements(&mut cur, want, 0, &mut out)?;
    Ok(out)
}

fn parse_elements(
    cur: &mut Cursor<'_>,
    want: &dyn Fn(&str) -> bool,
    depth: u32,
    out: &mut Vec<MatVariable>,
) -> Result<(), IoError> {
    while cur.remaining() > 0 {
        if cur.remaining() < 8 {
            // Trailing garbage shorter than a tag: MATLAB never writes this.
            return Err(IoError::truncated(
                cur.path,
                format!(
                    "{} stray bytes at offset {} of {} (shorter than an element tag)",
                    cur.remaining(),
                    cur.pos,
                    cur.ctx
                ),
            ));
        }
        let at = cur.pos;
        let (ty, n, small) = cur.tag("element tag")?;
        if small {
            cur.take(4, "small element")?;
            continue;
        }
        let data = cur.take(n, "element data")?;
        match ty {
            MI_MATRIX => {
                let pad = ((8 - n % 8) % 8).min(cur.remaining());
                cur.pos += pad;
                if let Some(v) = parse_matrix(data, cur, at, want)? {
                    out.push(v);
                }
            }
            MI_COMPRESSED => {
                if depth >= MAX_DEPTH {
                    return Err(IoError::malformed(
                        cur.path,
                        format!(
                            "compressed elements nested deeper than {MAX_DEPTH} at offset {at}"
                        ),
                    ));
                }
                let inflated = inflate(data, cur.path, at)?;
                let ctx = format!("compressed element at offset {at}");
                let mut inner = Cursor {
                    buf: &inflated,
                    pos: 0,
                    big: cur.big,
                    path: cur.path,
                    ctx: &ctx,
                };
                parse_elements(&mut inner, want, depth + 1, out)?;
            }
            _ => {
                // Unknown top-level element: skip it (with padding).
                let pad = ((8 - n % 8) % 8).min(cur.remaining());
                cur.pos += pad;
            }
        }
    }
    Ok(())
}

fn inflate(data: &[u8], path: &Path, at: usize) -> Result<Vec<u8>, IoError> {
    let cap = data
        .len()
        .saturating_mul(MAX_INFLATE_RATIO)
        .saturating_add(1024)
        .min(MAX_INFLATED);
    let mut out = Vec::with_capacity(data.len().saturating_mul(4).min(cap));
    let mut dec = flate2::read::ZlibDecoder::new(data).take(cap as u64 + 1);
    dec.read_to_end(&mut out).map_err(|e| {
        IoError::malformed(
            path,
            format!("compressed element at offset {at}: zlib: {e}"),
        )
    })?;
    if out.len() > cap {
        return Err(IoError::contradiction(
            path,
            format!(
                "compressed element at offset {at} inflates beyond {cap} bytes ({} compressed)",
                data.len()
            ),
        ));
    }
    Ok(out)
}

/// Parse the body of a miMATRIX element. Returns `None` for an empty (0-byte) matrix element.
fn parse_matrix(
    body: &[u8],
    outer: &Cursor<'_>,
    at: usize,
    want: &dyn Fn(&str) -> bool,
) -> Result<Option<MatVariable>, IoError> {
    if body.is_empty() {
        return Ok(None);
    }
    let ctx = format!("matrix element at offset {at} of {}", outer.ctx);
    let mut c = Cursor {
        buf: body,
        pos: 0,
        big: outer.big,
        path: outer.path,
        ctx: &ctx,
    };
    let path = outer.path;
    let (ty, flags) = c.sub_element("array flags")?;
    if ty != MI_UINT32 || flags.len() != 8 {
        return Err(IoError::malformed(
            path,
            format!(
                "{ctx}: array flags sub-element has type {ty} and {} bytes (expected miUINT32, 8)",
                flags.len()
            ),
        ));
    }
    let f0 = if c.big {
        u32::from_be_bytes([flags[0], flags[1], flags[2], flags[3]])
    } else {
        u32::from_le_bytes([flags[0], flags[1], flags[2], flags[3]])
    };
    let class = MatClass::from_code((f0 & 0xFF) as u8);
    let complex = f0 & 0x0800 != 0;

    let (ty, dims_raw) = c.sub_element("dimensions")?;
    if ty != MI_INT32 || dims_raw.len() % 4 != 0 || dims_raw.len() < 8 {
        return Err(IoError::malformed(
            path,
            format!("{ctx}: dimensions sub-element has type {ty} and {} bytes (expected miINT32, >= 8, multiple of 4)", dims_raw.len()),
        ));
    }
    let mut dims = Vec::with_capacity(dims_raw.len() / 4);
    for ch in dims_raw.chunks_exact(4) {
        let a = [ch[0], ch[1], ch[2], ch[3]];
        let d = if c.big {
            i32::from_be_bytes(a)
        } else {
            i32::from_le_bytes(a)
        };
        if d < 0 {
            return Err(IoError::malformed(
                path,
                format!("{ctx}: negative dimension {d}"),
            ));
        }
        dims.push(d as usize);
    }

    let (ty, name_raw) = c.sub_element("array name")?;
    if ty != MI_INT8 && ty != MI_UINT8 && ty != MI_UTF8 {
        return Err(IoError::malformed(
            path,
            format!("{ctx}: array name sub-element has type {ty} (expected miINT8)"),
        ));
    }
    let name = String::from_utf8_lossy(name_raw).into_owned();
    let mut var = MatVariable {
        name,
        class,
        dims,
        data: Vec::new(),
        complex,
    };
    if !class.is_numeric() || complex || !want(&var.name) {
        return Ok(Some(var));
    }
    let numel = var
        .dims
        .iter()
        .try_fold(1usize, |acc, &d| acc.checked_mul(d))
        .ok_or_else(|| {
            IoError::contradiction(path, format!("{ctx}: dimensions {:?} overflow", var.dims))
        })?;
    let (ty, real) = c.sub_element("real part")?;
    let width = match ty {
        MI_INT8 | MI_UINT8 => 1,
        MI_INT16 | MI_UINT16 => 2,
        MI_INT32 | MI_UINT32 | MI_SINGLE => 4,
        MI_DOUBLE | MI_INT64 | MI_UINT64 => 8,
        other => {
            return Err(IoError::unsupported(
                path,
                format!(
                    "{ctx}: variable {:?} stores its data as MAT type {other}",
                    var.name
                ),
            ))
        }
    };
    if real.len() % width != 0 || real.len() / width != numel {
        return Err(IoError::contradiction(
            path,
            format!(
                "{ctx}: variable {:?} has dimensions {:?} ({numel} elements) but {} data bytes of {width}-byte type {ty}",
                var.name,
                var.dims,
                real.len()
            ),
        ));
    }
    let big = c.big;
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
    var.data = data;
    Ok(Some(var))
}

fn read_file(path: &Path) -> Result<Vec<u8>, IoError> {
    std::fs::read(path).map_err(|e| IoError::io(path, "read", e))
}

/// Read every variable of a MAT v5 file, converting the numeric ones selected by `want`.
pub fn read_mat(path: &Path, want: &dyn Fn(&str) -> bool) -> Result<Vec<MatVariable>, IoError> {
    let bytes = read_file(path)?;
    parse_mat(&bytes, path, want)
}

/// List the top-level variables of a MAT v5 file as `(name, number of elements)`, in file order.
/// Non-numeric variables are listed too (their element count is that of their dimensions).
pub fn list_mat_variables(path: impl AsRef<Path>) -> Result<Vec<(String, usize)>, IoError> {
    let path = path.as_ref();
    Ok(read_mat(path, &|_| false)?
        .into_iter()
        .map(|v| {
            let n = v.numel();
            (v.name, n)
        })
        .collect())
}

// ---------------------------------------------------------------------------------------------
// CWRU
// ---------------------------------------------------------------------------------------------

/// Fault class of a CWRU record, from its file name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CwruFault {
    /// Healthy baseline (`normal_*`).
    Normal,
    /// Inner-race defect (`IR`).
    InnerRace,
    /// Ball (rolling element) defect (`B`).
    Ball,
    /// Outer-race defect (`OR`), at the given clock position relative to the load zone:
    /// 6 = centred, 3 = orthogonal, 12 = opposite.
    OuterRace {
        /// Clock position (3, 6 or 12).
        clock: u8,
    },
}

impl CwruFault {
    /// The `fault_type` string of `inventory.csv`: `normal`, `inner_race`, `ball`, `outer_race`.
    pub fn type_name(&self) -> &'static str {
        match self {
            CwruFault::Normal => "normal",
            CwruFault::InnerRace => "inner_race",
            CwruFault::Ball => "ball",
            CwruFault::OuterRace { .. } => "outer_race",
        }
    }

    /// The `or_position` string of `inventory.csv` (`centred_6`, `orthogonal_3`,
    /// `opposite_12`), or `None` for non-outer-race faults and unknown clock positions.
    pub fn or_position(&self) -> Option<&'static str> {
        match self {
            CwruFault::OuterRace { clock: 6 } => Some("centred_6"),
            CwruFault::OuterRace { clock: 3 } => Some("orthogonal_3"),
            CwruFault::OuterRace { clock: 12 } => Some("opposite_12"),
            _ => None,
        }
    }
}

/// Label parsed from a CWRU file name such as `12k_Drive_End_OR007@6_1_131.mat` or
/// `normal_0_97.mat` (the naming of the `yyxyz/CaseWesternReserveUniversityData` mirror).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CwruLabel {
    /// Sample rate implied by the name, Hz (`12k` = 12000, `48k` = 48000, `normal` = 48000).
    pub fs_hz: f64,
    /// Bearing end carrying the fault: `"DE"` (drive end) or `"FE"` (fan end); `None` for normal.
    pub fault_end: Option<String>,
    /// Fault class.
    pub fault: CwruFault,
    /// Defect diameter in inches (0.007, 0.014, 0.021, 0.028); `None` for normal.
    pub diameter_in: Option<f64>,
    /// Motor load in hp (0..3).
    pub load_hp: u8,
    /// CWRU record number (the original file name, `105.mat` = 105).
    pub record: u32,
}

/// Parse a CWRU file name (with or without directory and `.mat`). Returns `None` for names
/// that do not follow `<12k|48k>_<Drive|Fan>_End_<IR|B|OR><ddd>[@<clock>]_<load>_<record>` or
/// `normal_<load>_<record>`.
pub fn parse_cwru_name(name: &str) -> Option<CwruLabel> {
    let base = name.rsplit(['/', '\\']).next()?;
    let base = base.strip_suffix(".mat").unwrap_or(base);
    let parts: Vec<&str> = base.split('_').collect();
    let small_int = |s: &str| -> Option<u32> {
        if s.is_empty() || s.len() > 6 || !s.bytes().all(|b| b.is_ascii_digit()) {
            None
        } else {
            s.parse().ok()
        }
    };
    if parts.len() == 3 && parts[0].eq_ignore_ascii_case("normal") {
        let load = small_int(parts[1])?;
        return Some(CwruLabel {
            fs_hz: 48_000.0,
            fault_end: None,
            fault: CwruFault::Normal,
            diameter_in: None,
            load_hp: u8::try_from(load).ok().filter(|l| *l <= 3)?,
            record: small_int(parts[2])?,
        });
    }
    if parts.len() != 6 || !parts[2].eq_ignore_ascii_case("End") {
        return None;
    }
    let fs_hz = match parts[0].to_ascii_lowercase().as_str() {
        "12k" => 12_000.0,
        "48k" => 48_000.0,
        _ => return None,
    };
    let fault_end = match parts[1].to_ascii_lowercase().as_str() {
        "drive" => "DE",
        "fan" => "FE",
        _ => return None,
    };
    let code = parts[3];
    let (kind, rest) = if let Some(r) = code.strip_prefix("IR") {
        ("IR", r)
    } else if let Some(r) = code.strip_prefix("OR") {
        ("OR", r)
    } else if let Some(r) = code.strip_prefix('B') {
        ("B", r)
    } else {
        return None;
    };
    let (size, clock) = match rest.split_once('@') {
        Some((s, c)) => (s, Some(small_int(c)?)),
        None => (rest, None),
    };
    if size.len() != 3 {
        return None;
    }
    let diameter_in = small_int(size)? as f64 / 1000.0;
    let fault = match (kind, clock) {
        ("IR", None) => CwruFault::InnerRace,
        ("B", None) => CwruFault::Ball,
        ("OR", Some(c)) if matches!(c, 3 | 6 | 12) => CwruFault::OuterRace { clock: c as u8 },
        _ => return None,
    };
    let load = small_int(parts[4])?;
    Some(CwruLabel {
        fs_hz,
        fault_end: Some(fault_end.to_string()),
        fault,
        diameter_in: Some(diameter_in),
        load_hp: u8::try_from(load).ok().filter(|l| *l <= 3)?,
        record: small_int(parts[5])?,
    })
}

/// Bearing preset name for a CWRU channel: `DE` → `cwru-6205-de` (SKF 6205-2RS JEM),
/// `FE` → `cwru-6203-fe` (SKF 6203-2RS JEM); `BA` (base plate) has none.
pub fn cwru_bearing_preset(channel: &str) -> Option<&'static str> {
    match channel {
        "DE" => Some("cwru-6205-de"),
        "FE" => Some("cwru-6203-fe"),
        _ => None,
    }
}

/// Numeric prefix of a CWRU variable name: `X118_DE_time` → 118, `X097RPM` → 97.
fn var_record(name: &str) -> Option<u32> {
    let rest = name.strip_prefix('X')?;
    let digits: String = rest.chars().take_while(|c| c.is_ascii_digit()).collect();
    digits.parse().ok()
}

/// Among `candidates` (variable names), pick the one whose record number matches `record`,
/// else the only candidate; several candidates and no match is a contradiction.
fn pick<'v>(
    path: &Path,
    candidates: &[&'v MatVariable],
    record: Option<u32>,
    what: &str,
) -> Result<Option<&'v MatVariable>, IoError> {
    if let Some(r) = record {
        if let Some(v) = candidates.iter().find(|v| var_record(&v.name) == Some(r)) {
            return Ok(Some(v));
        }
    }
    match candidates {
        [] => Ok(None),
        [one] => Ok(Some(one)),
        many => Err(IoError::contradiction(
            path,
            format!(
                "several {what} variables ({}) and none matches record {:?} of the file name",
                many.iter()
                    .map(|v| v.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", "),
                record
            ),
        )),
    }
}

/// Read one channel of a CWRU `.mat` file.
///
/// * `channel`: `"DE"`, `"FE"` or `"BA"` (case-insensitive), selecting the variable ending in
///   `_DE_time`, `_FE_time` or `_BA_time`; an absent channel is [`IoError::UnknownChannel`]
///   listing the channels the file has.
/// * `fs_override`: sample rate in Hz; otherwise taken from the file name via
///   [`parse_cwru_name`] (no recognisable name and no override → [`IoError::MissingSampleRate`]).
///
/// The record has unit `"g"` (assumed; CWRU does not state it), `rpm` from the `XnnnRPM`
/// variable (if present), `bearing` from [`cwru_bearing_preset`], and `meta` with the parsed
/// label (`"label"`), the variable name, the list of variables and the source of `fs`.
pub fn read_cwru(
    path: impl AsRef<Path>,
    channel: &str,
    fs_override: Option<f64>,
) -> Result<Record, IoError> {
    let path = path.as_ref();
    let ch = channel.to_ascii_uppercase();
    let suffix = format!("_{ch}_time");
    let vars = read_mat(path, &|name: &str| {
        name.ends_with(&suffix) || name.ends_with("RPM")
    })?;
    let file_name = path
        .file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let label = parse_cwru_name(&file_name);
    let record_no = label
        .as_ref()
        .map(|l| l.record)
        .or_else(|| file_name.strip_suffix(".mat").and_then(|s| s.parse().ok()));

    let numeric = |v: &&MatVariable| v.class.is_numeric() && !v.complex;
    let time_vars: Vec<&MatVariable> = vars
        .iter()
        .filter(numeric)
        .filter(|v| v.name.ends_with(&suffix))
        .collect();
    let Some(var) = pick(path, &time_vars, record_no, &suffix)? else {
        let mut available: Vec<String> = vars
            .iter()
            .filter(numeric)
            .filter_map(|v| {
                let stem = v.name.strip_suffix("_time")?;
                Some(stem.rsplit('_').next()?.to_string())
            })
            .collect();
        available.sort();
        available.dedup();
        return Err(IoError::UnknownChannel {
            path: path.to_path_buf(),
            requested: channel.to_string(),
            available,
        });
    };
    if var.data.is_empty() {
        return Err(IoError::truncated(
            path,
            format!("variable {} holds no samples", var.name),
        ));
    }
    if var.dims.iter().filter(|&&d| d > 1).count() > 1 {
        return Err(IoError::unsupported(
            path,
            format!(
                "variable {} is a {:?} matrix, expected a vector",
                var.name, var.dims
            ),
        ));
    }
    check_finite(path, &var.name, &var.data)?;

    let (fs, fs_source) = match (fs_override, &label) {
        (Some(fs), _) => (fs, "argument"),
        (None, Some(l)) => (l.fs_hz, "file name"),
        (None, None) => {
            return Err(IoError::MissingSampleRate {
                path: path.to_path_buf(),
                detail: "CWRU files do not store it and the file name is not of the form \
                         12k_Drive_End_IR007_0_105.mat / normal_0_97.mat; pass it explicitly"
                    .into(),
            })
        }
    };
    let fs = check_fs(path, fs)?;

    let rpm_vars: Vec<&MatVariable> = vars
        .iter()
        .filter(numeric)
        .filter(|v| v.name.ends_with("RPM"))
        .collect();
    let rpm = match pick(path, &rpm_vars, record_no, "RPM")? {
        Some(v) => match v.data.first() {
            Some(&r) => Some(check_rpm(path, r)?),
            None => None,
        },
        None => None,
    };

    let meta = json!({
        "format": "cwru-mat5",
        "variable": var.name,
        "variables": vars.iter().map(|v| json!({"name": v.name, "dims": v.dims})).collect::<Vec<_>>(),
        "fs_source": fs_source,
        "unit_note": "CWRU does not state units; g is the common assumption",
        "label": label,
    });
    Ok(Record {
        samples: var.data.clone(),
        fs,
        rpm,
        channel: ch.clone(),
        unit: "g".into(),
        source: PathBuf::from(path),
        bearing: cwru_bearing_preset(&ch).map(str::to_string),
        meta,
    })
}

/// Write a minimal uncompressed little-endian MAT v5 file holding `vars` as N x 1 double
/// column vectors. For tests and fixtures (the format reference: MathWorks "MAT-File Format").
pub fn mat5_bytes(vars: &[(&str, &[f64])]) -> Vec<u8> {
    let mut out = Vec::new();
    let mut header = [b' '; 128];
    let text = b"MATLAB 5.0 MAT-file, Platform: wearsim test fixture";
    header[..text.len()].copy_from_slice(text);
    header[116..124].fill(0);
    header[124..126].copy_from_slice(&0x0100u16.to_le_bytes());
    header[126..128].copy_from_slice(b"IM");
    out.extend_from_slice(&header);
    for (name, data) in vars {
        let mut body = Vec::new();
        let push_sub = |body: &mut Vec<u8>, ty: u32, bytes: &[u8]| {
            body.extend_from_slice(&ty.to_le_bytes());
            body.extend_from_slice(&(bytes.len() as u32).to_le_bytes());
            body.extend_from_slice(bytes);
            body.resize(body.len().next_multiple_of(8), 0);
        };
        let mut flags = Vec::new();
        flags.extend_from_slice(&6u32.to_le_bytes());
        flags.extend_from_slice(&0u32.to_le_bytes());
        push_sub(&mut body, MI_UINT32, &flags);
        let mut dims = Vec::new();
        dims.extend_from_slice(&(data.len() as i32).to_le_bytes());
        dims.extend_from_slice(&1i32.to_le_bytes());
        push_sub(&mut body, MI_INT32, &dims);
        push_sub(&mut body, MI_INT8, name.as_bytes());
        let raw: Vec<u8> = data.iter().flat_map(|x| x.to_le_bytes()).collect();
        push_sub(&mut body, MI_DOUBLE, &raw);
        out.extend_from_slice(&MI_MATRIX.to_le_bytes());
        out.extend_from_slice(&(body.len() as u32).to_le_bytes());
        out.extend_from_slice(&body);
    }
    out
}

/// Wrap every element of an uncompressed MAT v5 file (as produced by [`mat5_bytes`]) in a
/// `miCOMPRESSED` element, as MATLAB 7 does by default. For tests.
pub fn mat5_compress(uncompressed: &[u8]) -> Vec<u8> {
    use std::io::Write;
    let mut out = uncompressed[..128.min(uncompressed.len())].to_vec();
    let mut pos = 128;
    while pos + 8 <= uncompressed.len() {
        let n = u32::from_le_bytes([
            uncompressed[pos + 4],
            uncompressed[pos + 5],
            uncompressed[pos + 6],
            uncompressed[pos + 7],
        ]) as usize;
        let end = (pos + 8 + n).min(uncompressed.len());
        let mut enc = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
        let _ = enc.write_all(&uncompressed[pos..end]);
        let z = enc.finish().unwrap_or_default();
        out.extend_from_slice(&MI_COMPRESSED.to_le_bytes());
        out.extend_from_slice(&(z.len() as u32).to_le_bytes());
        out.extend_from_slice(&z);
        pos = end;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tmp_file(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
        let p = dir.join(name);
        std::fs::write(&p, bytes).unwrap();
        p
    }

    #[test]
    fn parses_names() {
        let l = parse_cwru_name("12k_Drive_End_OR007@12_1_158.mat").unwrap();
        assert_eq!(l.fault, CwruFault::OuterRace { clock: 12 });
        assert_eq!(l.fault.or_position(), Some("opposite_12"));
        assert_eq!(l.diameter_in, Some(0.007));
        assert_eq!((l.load_hp, l.record, l.fs_hz), (1, 158, 12000.0));
        let n = parse_cwru_name("/x/y/normal_0_97.mat").unwrap();
        assert_eq!(
            (n.fault, n.fs_hz, n.record),
            (CwruFault::Normal, 48000.0, 97)
        );
        let b = parse_cwru_name("12k_Drive_End_B021_3_225").unwrap();
        assert_eq!((b.fault, b.diameter_in), (CwruFault::Ball, Some(0.021)));
        for bad in [
            "105.mat",
            "12k_Drive_End_IR7_0_1.mat",
            "12k_Drive_End_OR007_0_1.mat",
            "x",
            "",
            "12k_Drive_End_IR007_9_1.mat",
            "96k_Drive_End_IR007_0_1.mat",
            "12k_Drive_End_OR007@5_0_1.mat",
        ] {
            assert!(parse_cwru_name(bad).is_none(), "{bad}");
        }
    }

    #[test]
    fn reads_synthetic_file_plain_and_compressed() {
        let dir = tempfile::tempdir().unwrap();
        let de: Vec<f64> = (0..100).map(|i| (i as f64 * 0.1).sin()).collect();
        let fe: Vec<f64> = (0..100).map(|i| i as f64).collect();
        let other = [9.0; 100];
        let bytes = mat5_bytes(&[
            ("X099_DE_time", &other),
            ("X105_DE_time", &de),
            ("X105_FE_time", &fe),
            ("X105RPM", &[1797.0]),
        ]);
        for (k, b) in [bytes.clone(), mat5_compress(&bytes)].iter().enumerate() {
            let sub = dir.path().join(k.to_string());
            std::fs::create_dir(&sub).unwrap();
            let p = tmp_file(&sub, "12k_Drive_End_IR007_0_105.mat", b);
            let r = read_cwru(&p, "de", None).unwrap();
            assert_eq!(r.samples, de);
            assert_eq!(r.fs, 12000.0);
            assert_eq!(r.rpm, Some(1797.0));
            assert_eq!(r.bearing.as_deref(), Some("cwru-6205-de"));
            assert_eq!(r.meta["label"]["fault"], json!("inner_race"));
            let r = read_cwru(&p, "FE", Some(48000.0)).unwrap();
            assert_eq!(r.samples, fe);
            assert_eq!(r.fs, 48000.0);
            assert_eq!(r.bearing.as_deref(), Some("cwru-6203-fe"));
            match read_cwru(&p, "BA", None).unwrap_err() {
                IoError::UnknownChannel { available, .. } => {
                    assert_eq!(available, vec!["DE", "FE"])
                }
                e => panic!("{e:?}"),
            }
            let vars = list_mat_variables(&p).unwrap();
            assert_eq!(vars.len(), 4);
            assert_eq!(vars[1], ("X105_DE_time".to_string(), 100));
            // No recognisable name and no override: no sample rate.
            let q = tmp_file(&sub, "105.mat", b);
            assert!(matches!(
                read_cwru(&q, "DE", None),
                Err(IoError::MissingSampleRate { .. })
            ));
            assert_eq!(read_cwru(&q, "DE", Some(12000.0)).unwrap().samples, de);
        }
    }

    #[test]
    fn rejects_corrupt_files() {
        let dir = tempfile::tempdir().unwrap();
        let good = mat5_bytes(&[("X105_DE_time", &[1.0, 2.0, 3.0])]);
        let name = "12k_Drive_End_IR007_0_105.mat";
        // Empty, short, bad magic, bad endian.
        for (bytes, want) in [
            (Vec::new(), "truncated"),
            (good[..100].to_vec(), "truncated"),
            (b"hello world".repeat(20), "bad magic"),
        ] {
            let p = tmp_file(dir.path(), name, &bytes);
            let e = read_cwru(&p, "DE", None).unwrap_err();
            assert!(e.to_string().contains(want), "{e}");
            assert!(e.to_string().contains(name), "{e}");
        }
        // Truncated in the data.
        let p = tmp_file(dir.path(), name, &good[..good.len() - 9]);
        assert!(matches!(
            read_cwru(&p, "DE", None),
            Err(IoError::Truncated { .. })
        ));
        // Element claiming 4 GiB.
        let mut huge = good.clone();
        huge[132..136].copy_from_slice(&u32::MAX.to_le_bytes());
        let p = tmp_file(dir.path(), name, &huge);
        assert!(matches!(
            read_cwru(&p, "DE", None),
            Err(IoError::Truncated { .. })
        ));
        // Dimensions that disagree with the data.
        let mut dims = good.clone();
        // dims sub-element data starts at 128 + 8 (tag) + 16 (flags) + 8 (dims tag)
        dims[160..164].copy_from_slice(&1_000_000i32.to_le_bytes());
        let p = tmp_file(dir.path(), name, &dims);
        assert!(matches!(
            read_cwru(&p, "DE", None),
            Err(IoError::Contradiction { .. })
        ));
        // NaN sample.
        let nan = mat5_bytes(&[("X105_DE_time", &[1.0, f64::NAN, 3.0])]);
        let p = tmp_file(dir.path(), name, &nan);
        match read_cwru(&p, "DE", None).unwrap_err() {
            IoError::NonFinite { index, .. } => assert_eq!(index, 1),
            e => panic!("{e:?}"),
        }
        // Absurd override.
        let p = tmp_file(dir.path(), name, &good);
        assert!(matches!(
            read_cwru(&p, "DE", Some(1e9)),
            Err(IoError::AbsurdSampleRate { .. })
        ));
        // Zlib bomb-ish: compressed element claiming garbage.
        let mut z = good[..128].to_vec();
        z.extend_from_slice(&MI_COMPRESSED.to_le_bytes());
        z.extend_from_slice(&16u32.to_le_bytes());
        z.extend_from_slice(&[0x78, 0x9c, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14]);
        let p = tmp_file(dir.path(), name, &z);
        assert!(read_cwru(&p, "DE", None).is_err());
    }

    /// Every `.mat` of the CWRU folder: DE present, fs from the name, plausible length and rpm,
    /// finite values, and the parsed label equals the inventory row.
    #[test]
    fn real_cwru_files_match_inventory() -> Result<(), IoError> {
        let Some(dir) = crate::io::data_dir()? else {
            return Ok(());
        };
        let cwru = dir.join("cwru");
        let inv_path = cwru.join("inventory.csv");
        let mut inv = ::csv::Reader::from_path(&inv_path).expect("inventory.csv");
        let headers = inv.headers().unwrap().clone();
        let col = |name: &str| headers.iter().position(|h| h == name).unwrap();
        let (c_file, c_rec, c_fs, c_end, c_type, c_dia, c_or, c_load, c_rpm, c_n) = (
            col("file"),
            col("cwru_record"),
            col("sample_rate_hz"),
            col("fault_end"),
            col("fault_type"),
            col("fault_diameter_in"),
            col("or_position"),
            col("load_hp"),
            col("rpm_in_file"),
            col("de_samples"),
        );
        let mut seen = 0;
        for row in inv.records() {
            let row = row.unwrap();
            let file = &row[c_file];
            let path = cwru.join(file);
            let label = parse_cwru_name(file).unwrap_or_else(|| panic!("name {file}"));
            assert_eq!(label.record.to_string(), &row[c_rec], "{file}");
            assert_eq!(label.fs_hz, row[c_fs].parse::<f64>().unwrap(), "{file}");
            assert_eq!(
                label.fault_end.as_deref().unwrap_or(""),
                &row[c_end],
                "{file}"
            );
            assert_eq!(label.fault.type_name(), &row[c_type], "{file}");
            assert_eq!(
                label.fault.or_position().unwrap_or(""),
                &row[c_or],
                "{file}"
            );
            assert_eq!(label.load_hp.to_string(), &row[c_load], "{file}");
            match label.diameter_in {
                Some(d) => assert_eq!(d, row[c_dia].parse::<f64>().unwrap(), "{file}"),
                None => assert_eq!(&row[c_dia], "", "{file}"),
            }
            let r = read_cwru(&path, "DE", None)?;
            assert_eq!(
                r.fs,
                if file.starts_with("normal") {
                    48000.0
                } else {
                    12000.0
                }
            );
            assert!(r.samples.len() > 100_000, "{file}: {}", r.samples.len());
            assert_eq!(r.samples.len().to_string(), &row[c_n], "{file}");
            assert!(r.samples.iter().all(|x| x.is_finite()));
            let rpm = r.rpm.expect("rpm");
            assert!((1700.0..=1800.0).contains(&rpm), "{file}: {rpm}");
            assert_eq!(rpm, row[c_rpm].parse::<f64>().unwrap(), "{file}");
            let fe = read_cwru(&path, "FE", None)?;
            assert_eq!(fe.samples.len(), r.samples.len());
            seen += 1;
        }
        // Every .mat in the folder is in the inventory.
        let mats = std::fs::read_dir(&cwru)
            .unwrap()
            .filter(|e| {
                e.as_ref()
                    .unwrap()
                    .path()
                    .extension()
                    .is_some_and(|x| x == "mat")
            })
            .count();
        assert_eq!(seen, mats);
        assert!(seen > 0);
        Ok(())
    }
}
