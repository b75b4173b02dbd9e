//! Writers of small MAT v5 files for tests and fixtures.

use super::v5::{MI_COMPRESSED, MI_DOUBLE, MI_INT32, MI_INT8, MI_MATRIX, MI_UINT32};

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

/// A value for [`mat5_tree_bytes`]: the MAT v5 layouts MATLAB writes, for tests and fuzz seeds.
#[derive(Debug, Clone, PartialEq)]
pub enum FixtureValue {
    /// Column vector of doubles (N x 1).
    Doubles(Vec<f64>),
    /// Numeric array of MATLAB class code `class` (6 double .. 15 uint64) with `dims`, stored as
    /// MAT type `mi` (`bytes` already encoded little-endian); `logical` sets the logical flag.
    Typed {
        /// mxCLASS code.
        class: u8,
        /// miTYPE of the stored data.
        mi: u32,
        /// Dimensions.
        dims: Vec<i32>,
        /// Encoded data.
        bytes: Vec<u8>,
        /// Logical flag.
        logical: bool,
    },
    /// Char array (1 x N, UTF-16 as MATLAB 7 writes it).
    Char(String),
    /// Struct array of `dims` with `fields`; `elems[i][j]` = field `j` of element `i`.
    Struct {
        /// Dimensions.
        dims: Vec<i32>,
        /// Field names.
        fields: Vec<String>,
        /// Values.
        elems: Vec<Vec<FixtureValue>>,
    },
    /// Cell array (1 x N).
    Cell(Vec<FixtureValue>),
    /// 0 x 0 double (an empty field).
    Empty,
    /// A sparse 1 x 1 array (class 5), header only.
    Sparse,
}

fn push_sub(body: &mut Vec<u8>, ty: u32, bytes: &[u8]) {
    body.extend_from_slice(&ty.to_le_bytes());
    body.extend_from_slice(&(bytes.len() as u32).to_le_bytes());
    body.extend_from_slice(bytes);
    body.resize(body.len().next_multiple_of(8), 0);
}

fn matrix_element(name: &str, v: &FixtureValue) -> Vec<u8> {
    let (class, dims, logical): (u8, Vec<i32>, bool) = match v {
        FixtureValue::Doubles(d) => (6, vec![d.len() as i32, 1], false),
        FixtureValue::Typed {
            class,
            dims,
            logical,
            ..
        } => (*class, dims.clone(), *logical),
        FixtureValue::Char(s) => (4, vec![1, s.encode_utf16().count() as i32], false),
        FixtureValue::Struct { dims, .. } => (2, dims.clone(), false),
        FixtureValue::Cell(items) => (1, vec![1, items.len() as i32], false),
        FixtureValue::Empty => (6, vec![0, 0], false),
        FixtureValue::Sparse => (5, vec![1, 1], false),
    };
    let mut body = Vec::new();
    let f0 = class as u32 | if logical { 0x0200 } else { 0 };
    let mut flags = f0.to_le_bytes().to_vec();
    flags.extend_from_slice(&0u32.to_le_bytes());
    push_sub(&mut body, MI_UINT32, &flags);
    let d: Vec<u8> = dims.iter().flat_map(|x| x.to_le_bytes()).collect();
    push_sub(&mut body, MI_INT32, &d);
    push_sub(&mut body, MI_INT8, name.as_bytes());
    match v {
        FixtureValue::Doubles(d) => {
            let raw: Vec<u8> = d.iter().flat_map(|x| x.to_le_bytes()).collect();
            push_sub(&mut body, MI_DOUBLE, &raw);
        }
        FixtureValue::Typed { mi, bytes, .. } => push_sub(&mut body, *mi, bytes),
        FixtureValue::Char(s) => {
            let raw: Vec<u8> = s.encode_utf16().flat_map(|u| u.to_le_bytes()).collect();
            push_sub(&mut body, 4, &raw);
        }
        FixtureValue::Struct { fields, elems, .. } => {
            let fl = fields.iter().map(|f| f.len() + 1).max().unwrap_or(1).max(8);
            push_sub(&mut body, MI_INT32, &(fl as i32).to_le_bytes());
            let mut names = Vec::new();
            for f in fields {
                let mut b = f.as_bytes().to_vec();
                b.resize(fl, 0);
                names.extend_from_slice(&b);
            }
            push_sub(&mut body, MI_INT8, &names);
            for row in elems {
                for x in row {
                    body.extend_from_slice(&matrix_element("", x));
                }
            }
        }
        FixtureValue::Cell(items) => {
            for x in items {
                body.extend_from_slice(&matrix_element("", x));
            }
        }
        FixtureValue::Empty => push_sub(&mut body, MI_DOUBLE, &[]),
        FixtureValue::Sparse => {}
    }
    let mut out = MI_MATRIX.to_le_bytes().to_vec();
    out.extend_from_slice(&(body.len() as u32).to_le_bytes());
    out.extend_from_slice(&body);
    out
}

/// Write an uncompressed little-endian MAT v5 file holding the named values `vars` (structs,
/// cells, chars, every numeric class). Compress with [`mat5_compress`]. For tests and fuzz seeds.
pub fn mat5_tree_bytes(vars: &[(&str, FixtureValue)]) -> Vec<u8> {
    let mut out = mat5_bytes(&[]);
    for (name, v) in vars {
        out.extend_from_slice(&matrix_element(name, v));
    }
    out
}

/// An MFPT-style file: struct `bearing` with `gs` (signal, g), `sr` (Hz), `rate` (shaft Hz) and
/// `load` (lbs), as the MFPT fault data sets store it.
pub fn mfpt_fixture(gs: &[f64], sr: f64, rate: f64, load: f64) -> Vec<u8> {
    mat5_tree_bytes(&[(
        "bearing",
        FixtureValue::Struct {
            dims: vec![1, 1],
            fields: vec!["sr".into(), "gs".into(), "load".into(), "rate".into()],
            elems: vec![vec![
                FixtureValue::Doubles(vec![sr]),
                FixtureValue::Doubles(gs.to_vec()),
                FixtureValue::Doubles(vec![load]),
                FixtureValue::Doubles(vec![rate]),
            ]],
        },
    )])
}

/// A Paderborn-style file: variable `name` (e.g. `N15_M07_F10_K001_1`) is a 1 x 1 struct with
/// `Info`, `X`, `Y` and `Description`; `Y` is a 1 x k struct array with fields `Name`, `Type`,
/// `Unit`, `Data`, `Raster`, one element per `channels` entry `(name, samples)`.
pub fn paderborn_fixture(name: &str, channels: &[(&str, &[f64])]) -> Vec<u8> {
    let y = FixtureValue::Struct {
        dims: vec![1, channels.len() as i32],
        fields: ["Name", "Type", "Unit", "Data", "Raster"]
            .iter()
            .map(|s| s.to_string())
            .collect(),
        elems: channels
            .iter()
            .map(|(n, d)| {
                vec![
                    FixtureValue::Char(n.to_string()),
                    FixtureValue::Char("Signal".into()),
                    FixtureValue::Empty,
                    FixtureValue::Typed {
                        class: 7,
                        mi: 7,
                        dims: vec![1, d.len() as i32],
                        bytes: d.iter().flat_map(|x| (*x as f32).to_le_bytes()).collect(),
                        logical: false,
                    },
                    FixtureValue::Char("Mech_64kHz".into()),
                ]
            })
            .collect(),
    };
    mat5_tree_bytes(&[(
        name,
        FixtureValue::Struct {
            dims: vec![1, 1],
            fields: vec!["Info".into(), "X".into(), "Y".into(), "Description".into()],
            elems: vec![vec![
                FixtureValue::Empty,
                FixtureValue::Empty,
                y,
                FixtureValue::Char("fixture".into()),
            ]],
        },
    )])
}
