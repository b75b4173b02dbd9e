//! A MAT v5 file's top-level variables, flat (name, class, dimensions, real data), as the
//! CWRU loader and the variable listing see them: the top level of [`super::tree`]'s parse,
//! so the format is walked by one parser.

use std::path::Path;

use super::tree::{parse_mat_tree, MatValue};
use super::v5::{read_file, MatClass};
use crate::io::error::IoError;

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

/// Parse the top-level variables of a MAT v5 file from `bytes`. `want(name)` selects the
/// numeric variables whose data are converted; the others are listed with empty `data`.
/// Structs and cells are listed (their contents are parsed, within the tree's bounds, but
/// not returned).
pub fn parse_mat(
    bytes: &[u8],
    path: &Path,
    want: &dyn Fn(&str) -> bool,
) -> Result<Vec<MatVariable>, IoError> {
    Ok(parse_mat_tree(bytes, path, want)?
        .into_iter()
        .map(|n| {
            let (data, complex) = match n.value {
                MatValue::Numeric {
                    data,
                    converted,
                    complex,
                    ..
                } => (if converted { data } else { Vec::new() }, complex),
                _ => (Vec::new(), false),
            };
            MatVariable {
                name: n.name,
                class: n.class,
                dims: n.dims,
                data,
                complex,
            }
        })
        .collect())
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
