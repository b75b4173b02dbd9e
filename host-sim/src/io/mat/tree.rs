//! MAT v5 files as MATLAB writes them, read as a tree of named values: numeric arrays of every
//! class (double, single, int8..uint64; `logical` is uint8 with a flag), char arrays, structs
//! and struct arrays (nested to any depth up to [`MAX_TREE_DEPTH`]), cell arrays, empty fields,
//! and `miCOMPRESSED` elements. Sparse and object arrays are listed and refused when selected.
//!
//! Format: MathWorks, "MAT-File Format" (Level 5), sections "miMATRIX", "Structure MAT-File
//! Data Element", "Cell Array", "Character Array". Every node has a dotted path used by
//! `--channel`: a top-level variable `X118_DE_time`; a field of a 1×1 struct `bearing.gs`; an
//! element of a struct array `Y(7).Data` (1-based, as in MATLAB); a cell element `c{2}`.
//!
//! Bounds (per file, besides [`Budget`]): at most [`MAX_TREE_DEPTH`] levels of struct/cell
//! nesting and [`MAX_TREE_NODES`] nodes; the element count a struct or cell declares is checked
//! against the bytes left before anything is allocated.

use std::path::Path;

use serde::Serialize;

use super::v5::{
    inflate, parse_header, read_file, read_real_part, Budget, Cursor, MatClass, MI_COMPRESSED,
    MI_INT16, MI_INT32, MI_MATRIX, MI_UINT16,
};
use crate::io::error::IoError;

/// Deepest struct/cell nesting read (a variable is level 1).
pub const MAX_TREE_DEPTH: u32 = 16;
/// Most nodes (arrays, fields, cells) read per file: 2²⁰.
pub const MAX_TREE_NODES: usize = 1 << 20;
/// Nesting limit for compressed-in-compressed elements.
const MAX_COMPRESSED_DEPTH: u32 = 4;
/// miUTF16 data type (char arrays as MATLAB 7 writes them).
const MI_UTF16: u32 = 17;

/// Content of one node of a MAT file.
#[derive(Debug, Clone, PartialEq)]
pub enum MatValue {
    /// Numeric or logical array; `data` is the real part as `f64`, column-major, and is empty
    /// when the array was not selected (`converted` false), is complex, or has no elements.
    Numeric {
        /// Real part, converted if selected.
        data: Vec<f64>,
        /// Whether `data` was converted (selected, real).
        converted: bool,
        /// True if the array has an imaginary part (never converted).
        complex: bool,
        /// True for MATLAB `logical` arrays.
        logical: bool,
    },
    /// Character array (UTF-16/UTF-8 decoded; several rows concatenated column-major).
    Char(String),
    /// Struct or struct array: field names, and per element (column-major) its fields in that
    /// order.
    Struct {
        /// Field names.
        fields: Vec<String>,
        /// `elems[i][j]` = field `j` of element `i`.
        elems: Vec<Vec<MatNode>>,
    },
    /// Cell array, elements column-major.
    Cell(Vec<MatNode>),
    /// Sparse array (listed, not read).
    Sparse,
    /// Object or unknown class (listed, not read).
    Other,
}

/// One named array of a MAT file (a variable, a struct field or a cell element).
#[derive(Debug, Clone, PartialEq)]
pub struct MatNode {
    /// Name as stored (empty for cell elements).
    pub name: String,
    /// Path from the file's top level (`bearing.gs`, `Y(7).Data`, `c{2}`).
    pub path: String,
    /// MATLAB class.
    pub class: MatClass,
    /// Dimensions (rows, columns, ...).
    pub dims: Vec<usize>,
    /// Content.
    pub value: MatValue,
}

/// One numeric array of a file, as listed in errors and in the JSON (`path`, `dims`, `class`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ArrayInfo {
    /// Path inside the file.
    pub path: String,
    /// Dimensions.
    pub dims: Vec<usize>,
    /// MATLAB class name (`double`, `single`, `int16`, ..., `logical`).
    pub class: String,
}

impl ArrayInfo {
    /// `path [rows×cols] class`, as error messages list it.
    pub fn label(&self) -> String {
        let d: Vec<String> = self.dims.iter().map(|d| d.to_string()).collect();
        format!("{} [{}] {}", self.path, d.join("x"), self.class)
    }
}

impl MatNode {
    /// Number of elements (product of `dims`, saturating).
    pub fn numel(&self) -> usize {
        self.dims.iter().fold(1usize, |a, &d| a.saturating_mul(d))
    }

    /// The numeric data if this node is a converted real numeric array.
    pub fn numbers(&self) -> Option<&[f64]> {
        match &self.value {
            MatValue::Numeric {
                data,
                converted: true,
                ..
            } => Some(data),
            _ => None,
        }
    }

    /// The first element of a converted numeric scalar/array, if any.
    pub fn scalar(&self) -> Option<f64> {
        self.numbers().and_then(|d| d.first().copied())
    }

    /// The text of a char array.
    pub fn text(&self) -> Option<&str> {
        match &self.value {
            MatValue::Char(s) => Some(s),
            _ => None,
        }
    }

    /// Field `name` of element `i` (0-based) of a struct.
    pub fn field(&self, i: usize, name: &str) -> Option<&MatNode> {
        match &self.value {
            MatValue::Struct { fields, elems } => {
                let j = fields.iter().position(|f| f == name)?;
                elems.get(i)?.get(j)
            }
            _ => None,
        }
    }

    /// The direct children (struct fields of every element, cell elements).
    pub fn children(&self) -> Vec<&MatNode> {
        match &self.value {
            MatValue::Struct { elems, .. } => elems.iter().flatten().collect(),
            MatValue::Cell(items) => items.iter().collect(),
            _ => vec![],
        }
    }
}

/// MATLAB class name of a node (`double`, ..., `logical`, `char`, `struct`, `cell`, `sparse`).
pub fn class_name(class: MatClass, logical: bool) -> String {
    use MatClass::*;
    if logical {
        return "logical".into();
    }
    match class {
        Cell => "cell",
        Struct => "struct",
        Object => "object",
        Char => "char",
        Sparse => "sparse",
        Double => "double",
        Single => "single",
        Int8 => "int8",
        UInt8 => "uint8",
        Int16 => "int16",
        UInt16 => "uint16",
        Int32 => "int32",
        UInt32 => "uint32",
        Int64 => "int64",
        UInt64 => "uint64",
        Other(_) => "unknown",
    }
    .into()
}

/// Every node of `nodes` and below, depth first, in file order.
pub fn walk<'n>(nodes: &'n [MatNode], out: &mut Vec<&'n MatNode>) {
    for n in nodes {
        out.push(n);
        for c in n.children() {
            walk(std::slice::from_ref(c), out);
        }
    }
}

/// Every numeric (or logical) array of the tree with its path, shape and class.
pub fn numeric_arrays(nodes: &[MatNode]) -> Vec<ArrayInfo> {
    let mut all = Vec::new();
    walk(nodes, &mut all);
    all.into_iter()
        .filter_map(|n| match &n.value {
            MatValue::Numeric { logical, .. } => Some(ArrayInfo {
                path: n.path.clone(),
                dims: n.dims.clone(),
                class: class_name(n.class, *logical),
            }),
            _ => None,
        })
        .collect()
}

/// Find the node at `path` (`a.b`, `a(2).b`, `c{1}`; a 1×1 struct's element may be written
/// with or without `(1)`).
pub fn find<'n>(nodes: &'n [MatNode], path: &str) -> Option<&'n MatNode> {
    let mut all = Vec::new();
    walk(nodes, &mut all);
    all.iter()
        .find(|n| n.path == path)
        .or_else(|| {
            let alt = path.replace("(1).", ".");
            all.iter().find(|n| n.path == alt)
        })
        .copied()
}

/// Shared state of one file's parse.
struct Ctx<'w> {
    want: &'w dyn Fn(&str) -> bool,
    budget: Budget,
    nodes_left: usize,
}

/// Parse a MAT v5 file into its tree. `want(path)` selects the numeric arrays whose data are
/// converted (others are listed with empty data); the per-file [`Budget`] and the tree bounds
/// apply.
pub fn parse_mat_tree(
    bytes: &[u8],
    path: &Path,
    want: &dyn Fn(&str) -> bool,
) -> Result<Vec<MatNode>, IoError> {
    let big = parse_header(bytes, path)?;
    let mut cur = Cursor {
        buf: bytes,
        pos: 128,
        big,
        path,
        ctx: "file",
    };
    let mut ctx = Ctx {
        want,
        budget: Budget::default(),
        nodes_left: MAX_TREE_NODES,
    };
    let mut out = Vec::new();
    top_elements(&mut cur, 0, &mut ctx, &mut out)?;
    Ok(out)
}

/// Read a MAT v5 file into its tree (see [`parse_mat_tree`]).
pub fn read_mat_tree(path: &Path, want: &dyn Fn(&str) -> bool) -> Result<Vec<MatNode>, IoError> {
    let bytes = read_file(path)?;
    parse_mat_tree(&bytes, path, want)
}

fn top_elements(
    cur: &mut Cursor<'_>,
    depth: u32,
    ctx: &mut Ctx<'_>,
    out: &mut Vec<MatNode>,
) -> Result<(), IoError> {
    while let Some((at, ty, data)) = cur.next_element()? {
        match ty {
            MI_MATRIX => {
                cur.skip_padding(data.len());
                let where_ = format!("matrix element at offset {at} of {}", cur.ctx);
                if let Some(node) = matrix(data, cur.big, cur.path, &where_, None, 1, ctx)? {
                    out.push(node);
                }
            }
            MI_COMPRESSED => {
                if depth >= MAX_COMPRESSED_DEPTH {
                    return Err(IoError::malformed(
                        cur.path,
                        format!("compressed elements nested deeper than {MAX_COMPRESSED_DEPTH} at offset {at}"),
                    ));
                }
                let inflated = inflate(data, cur.path, at, &mut ctx.budget)?;
                let c = format!("compressed element at offset {at}");
                top_elements(&mut cur.inner(&inflated, &c), depth + 1, ctx, out)?;
            }
            _ => cur.skip_padding(data.len()),
        }
    }
    Ok(())
}

/// Refuses a struct or cell array of `numel` elements when they exceed the nodes left in the
/// per-file budget ([`MAX_TREE_NODES`]), before anything is allocated for them.
fn check_element_budget(
    path: &Path,
    where_: &str,
    name: &str,
    kind: &str,
    numel: usize,
    ctx: &Ctx<'_>,
) -> Result<(), IoError> {
    if numel > ctx.nodes_left {
        return Err(IoError::TooLarge {
            path: path.to_path_buf(),
            what: format!("{where_}: {kind} {name:?} of {numel} elements"),
            limit: format!("{MAX_TREE_NODES} arrays, fields, cells and elements per MAT file"),
        });
    }
    Ok(())
}

fn u32_of(b: &[u8], big: bool) -> u32 {
    let a = [
        b.first().copied().unwrap_or(0),
        b.get(1).copied().unwrap_or(0),
        b.get(2).copied().unwrap_or(0),
        b.get(3).copied().unwrap_or(0),
    ];
    if big {
        u32::from_be_bytes(a)
    } else {
        u32::from_le_bytes(a)
    }
}

/// Parse one miMATRIX body. `name` is the field name a struct gives its element (the stored
/// name is empty there); `prefix` paths are built by the caller through `name`.
fn matrix(
    body: &[u8],
    big: bool,
    path: &Path,
    where_: &str,
    given: Option<(String, String)>,
    depth: u32,
    ctx: &mut Ctx<'_>,
) -> Result<Option<MatNode>, IoError> {
    if ctx.nodes_left == 0 {
        return Err(IoError::TooLarge {
            path: path.to_path_buf(),
            what: format!("{where_}: more than {MAX_TREE_NODES} arrays, fields and cells"),
            limit: format!("{MAX_TREE_NODES} nodes per MAT file"),
        });
    }
    ctx.nodes_left -= 1;
    if depth > MAX_TREE_DEPTH {
        return Err(IoError::malformed(
            path,
            format!("{where_}: structs/cells nested deeper than {MAX_TREE_DEPTH} levels"),
        ));
    }
    let (name_given, path_given) = given.unzip();
    if body.is_empty() {
        // An empty miMATRIX (some writers use it for an empty field).
        return Ok(Some(MatNode {
            name: name_given.unwrap_or_default(),
            path: path_given.unwrap_or_default(),
            class: MatClass::Double,
            dims: vec![0, 0],
            value: MatValue::Numeric {
                data: vec![],
                converted: true,
                complex: false,
                logical: false,
            },
        }));
    }
    let mut c = Cursor {
        buf: body,
        pos: 0,
        big,
        path,
        ctx: where_,
    };
    let f0 = c.array_flags()?;
    let class = MatClass::from_code((f0 & 0xFF) as u8);
    let complex = f0 & 0x0800 != 0;
    let logical = f0 & 0x0200 != 0;
    let (ty, dims_raw) = c.sub_element("dimensions")?;
    if ty != MI_INT32 || dims_raw.len() % 4 != 0 || dims_raw.len() < 8 || dims_raw.len() > 4 * 32 {
        return Err(IoError::malformed(
            path,
            format!("{where_}: dimensions sub-element has type {ty} and {} bytes (expected miINT32, 8..=128 bytes, multiple of 4)", dims_raw.len()),
        ));
    }
    let mut dims = Vec::with_capacity(dims_raw.len() / 4);
    for ch in dims_raw.chunks_exact(4) {
        let d = u32_of(ch, big) as i32;
        if d < 0 {
            return Err(IoError::malformed(
                path,
                format!("{where_}: negative dimension {d}"),
            ));
        }
        dims.push(d as usize);
    }
    let numel = dims
        .iter()
        .try_fold(1usize, |a, &d| a.checked_mul(d))
        .ok_or_else(|| {
            IoError::contradiction(path, format!("{where_}: dimensions {dims:?} overflow"))
        })?;
    let stored = c.array_name()?;
    let name = name_given.unwrap_or(stored.clone());
    let node_path = path_given.unwrap_or(stored);
    let mut node = MatNode {
        name,
        path: node_path,
        class,
        dims,
        value: MatValue::Other,
    };
    let index_path = |i: usize, open: char, close: char, base: &str| -> String {
        if numel == 1 && open == '(' {
            base.to_string()
        } else {
            format!("{base}{open}{}{close}", i + 1)
        }
    };
    node.value = match class {
        c_ if c_.is_numeric() => {
            let selected = (ctx.want)(&node.path) && !complex;
            let mut data = Vec::new();
            if selected && numel > 0 {
                let what = format!("{where_}: array {:?}", node.path);
                data = read_real_part(&mut c, path, &what, &node.dims, numel, &mut ctx.budget)?;
            }
            MatValue::Numeric {
                data,
                converted: selected,
                complex,
                logical,
            }
        }
        MatClass::Char => {
            if numel == 0 || c.remaining() == 0 {
                MatValue::Char(String::new())
            } else {
                let (ty, raw) = c.sub_element("char data")?;
                let text = match ty {
                    MI_UINT16 | MI_UTF16 | MI_INT16 => {
                        let units: Vec<u16> = raw
                            .chunks_exact(2)
                            .map(|b| {
                                if big {
                                    u16::from_be_bytes([b[0], b[1]])
                                } else {
                                    u16::from_le_bytes([b[0], b[1]])
                                }
                            })
                            .collect();
                        String::from_utf16_lossy(&units)
                    }
                    _ => String::from_utf8_lossy(raw).into_owned(),
                };
                MatValue::Char(text)
            }
        }
        MatClass::Struct => {
            let (_, fl_raw) = c.sub_element("field name length")?;
            let fl = u32_of(fl_raw, big) as usize;
            let (_, names_raw) = c.sub_element("field names")?;
            let fields: Vec<String> = if fl == 0 {
                vec![]
            } else {
                names_raw
                    .chunks(fl)
                    .map(|ch| {
                        let end = ch.iter().position(|&b| b == 0).unwrap_or(ch.len());
                        String::from_utf8_lossy(&ch[..end]).into_owned()
                    })
                    .collect()
            };
            // Every element counts against the per-file node budget, so a struct with no
            // fields (whose elements take no bytes) cannot declare millions of them.
            check_element_budget(path, where_, &node.path, "struct", numel, ctx)?;
            let count = numel.saturating_mul(fields.len());
            if count > c.remaining() / 8 {
                return Err(IoError::truncated(
                    path,
                    format!(
                        "{where_}: struct {:?} of {numel} elements x {} fields needs {count} sub-elements, only {} bytes left",
                        node.path, fields.len(), c.remaining()
                    ),
                ));
            }
            let mut elems = Vec::with_capacity(numel);
            for i in 0..numel {
                let base = index_path(i, '(', ')', &node.path);
                let mut row = Vec::with_capacity(fields.len());
                for f in &fields {
                    let (ty, sub) = c.sub_element("struct field")?;
                    if ty != MI_MATRIX {
                        return Err(IoError::malformed(
                            path,
                            format!("{where_}: field {f:?} of struct {:?} has MAT type {ty} (expected miMATRIX)", node.path),
                        ));
                    }
                    let p = format!("{base}.{f}");
                    let w = format!("{where_}, field {p}");
                    if let Some(n) =
                        matrix(sub, big, path, &w, Some((f.clone(), p)), depth + 1, ctx)?
                    {
                        row.push(n);
                    }
                }
                elems.push(row);
            }
            MatValue::Struct { fields, elems }
        }
        MatClass::Cell => {
            check_element_budget(path, where_, &node.path, "cell", numel, ctx)?;
            if numel > c.remaining() / 8 {
                return Err(IoError::truncated(
                    path,
                    format!(
                        "{where_}: cell {:?} of {numel} elements, only {} bytes left",
                        node.path,
                        c.remaining()
                    ),
                ));
            }
            let mut items = Vec::with_capacity(numel);
            for i in 0..numel {
                let (ty, sub) = c.sub_element("cell element")?;
                if ty != MI_MATRIX {
                    return Err(IoError::malformed(
                        path,
                        format!("{where_}: element {} of cell {:?} has MAT type {ty} (expected miMATRIX)", i + 1, node.path),
                    ));
                }
                let p = index_path(i, '{', '}', &node.path);
                let w = format!("{where_}, cell {p}");
                if let Some(n) =
                    matrix(sub, big, path, &w, Some((String::new(), p)), depth + 1, ctx)?
                {
                    items.push(n);
                }
            }
            MatValue::Cell(items)
        }
        MatClass::Sparse => MatValue::Sparse,
        _ => MatValue::Other,
    };
    Ok(Some(node))
}
