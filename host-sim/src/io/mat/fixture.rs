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
