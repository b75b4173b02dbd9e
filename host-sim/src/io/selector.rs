//! One column or one row of a 2-D array named in `--channel`, MATLAB-style and 1-based:
//! `NAME(:,K)` is column K, `NAME(K,:)` is row K (`data(:,2)`, `bearing.gs(:,1)`; an NPY
//! file's array has no name: `(:,2)`). Shared by the MAT reader ([`crate::io::mat`]) and the
//! NPY reader ([`crate::io::npy`]), so both accept and refuse the same selectors with the
//! same messages.
//!
//! A trailing group in parentheses is a selector only when it holds a comma or a colon:
//! `Y(7)` stays a struct array element of a MAT path.

/// The line of a 2-D array a selector picks; the index counts from 1, as written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Line {
    /// `NAME(:,K)`: every row of column K.
    Column(usize),
    /// `NAME(K,:)`: every column of row K.
    Row(usize),
}

impl Line {
    /// The selector as written back: `(:,K)` or `(K,:)`.
    pub fn suffix(self) -> String {
        match self {
            Line::Column(k) => format!("(:,{k})"),
            Line::Row(k) => format!("({k},:)"),
        }
    }

    /// The 0-based index of the column or row.
    pub fn index0(self) -> usize {
        match self {
            Line::Column(k) | Line::Row(k) => k - 1,
        }
    }

    /// Whether the samples run along the array's second axis (a row was picked).
    pub fn is_row(self) -> bool {
        matches!(self, Line::Row(_))
    }
}

/// A `--channel` value with a selector, split: the array it names (`""` for none) and the
/// selector, or the selector's text (`"1,2"`) when it is not `:,K` or `K,:` with K ≥ 1.
pub type Split<'a> = (&'a str, Result<Line, &'a str>);

/// Splits `req` into the array it names and its selector when it ends with a group in
/// parentheses holding a comma or a colon; `None` for a plain name.
pub fn split(req: &str) -> Option<Split<'_>> {
    let body = req.strip_suffix(')')?;
    let open = body.rfind('(')?;
    let (base, inner) = (&body[..open], &body[open + 1..]);
    if !inner.contains([',', ':']) {
        return None;
    }
    let index = |s: &str| s.trim().parse::<usize>().ok().filter(|&k| k >= 1);
    let line = match inner.split_once(',') {
        Some((r, c)) if r.trim() == ":" => index(c).map(Line::Column),
        Some((r, c)) if c.trim() == ":" => index(r).map(Line::Row),
        _ => None,
    };
    Some((base, line.ok_or(inner)))
}

/// How to pick one line of the `dims` array called `name`: `name(:,K)` for column K and
/// `name(K,:)` for row K with the ranges K may take (the advice of every message about a
/// matrix channel).
pub fn advice(name: &str, dims: &[usize]) -> String {
    let (rows, cols) = match dims {
        [r, c] => (*r, *c),
        _ => {
            return format!(
                "a selector picks from a 2-D array, and {name:?} has {} dimensions",
                dims.len()
            )
        }
    };
    format!(
        "pick one column with --channel '{name}(:,K)' (K = 1..={cols}) or one row with --channel '{name}(K,:)' (K = 1..={rows}); 1-based, as in MATLAB"
    )
}

/// Checks selector `sel` (from [`split`]) against the array `name` of shape `dims`: a 2-D
/// array and an index within its columns or rows. The error names the array, its shape and
/// the allowed range.
pub fn check(sel: Result<Line, &str>, name: &str, dims: &[usize]) -> Result<Line, String> {
    let what = |problem: String| {
        format!(
            "--channel: {problem}; {name:?} is a {dims:?} array: {}",
            advice(name, dims)
        )
    };
    let line = sel.map_err(|text| {
        what(format!(
            "malformed selector ({text}): a selector is (:,K) or (K,:) with K counted from 1"
        ))
    })?;
    let [rows, cols] = dims else {
        return Err(what(format!(
            "selector {} needs a 2-D array",
            line.suffix()
        )));
    };
    let (k, n, axis) = match line {
        Line::Column(k) => (k, *cols, "column"),
        Line::Row(k) => (k, *rows, "row"),
    };
    if k > n {
        return Err(what(format!("{axis} {k} is out of range 1..={n}")));
    }
    Ok(line)
}

/// The samples of `line` of a `rows × cols` array whose element `[i, j]` (0-based) is
/// `get(i, j)`; `line` must have passed [`check`].
pub fn extract(
    line: Line,
    rows: usize,
    cols: usize,
    get: impl Fn(usize, usize) -> f64,
) -> Vec<f64> {
    match line {
        Line::Column(k) => (0..rows).map(|i| get(i, k - 1)).collect(),
        Line::Row(k) => (0..cols).map(|j| get(k - 1, j)).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn selectors_are_parsed_and_checked() {
        assert_eq!(split("data(:,2)"), Some(("data", Ok(Line::Column(2)))));
        assert_eq!(
            split("bearing.gs( 3 , : )"),
            Some(("bearing.gs", Ok(Line::Row(3))))
        );
        assert_eq!(split("(:,1)"), Some(("", Ok(Line::Column(1)))));
        assert_eq!(split("Y(7)"), None);
        assert_eq!(split("data"), None);
        assert_eq!(split("data(1,2)"), Some(("data", Err("1,2"))));
        assert_eq!(split("data(:,0)"), Some(("data", Err(":,0"))));
        assert_eq!(split("data(:,:)"), Some(("data", Err(":,:"))));
        assert_eq!(Line::Row(4).suffix(), "(4,:)");
        let e = check(Ok(Line::Column(3)), "data", &[4096, 2]).unwrap_err();
        assert!(
            e.contains("column 3 is out of range 1..=2") && e.contains("[4096, 2]"),
            "{e}"
        );
        let e = check(Err("x"), "data", &[4096, 2]).unwrap_err();
        assert!(
            e.contains("malformed selector (x)") && e.contains("K = 1..=4096"),
            "{e}"
        );
        assert!(check(Ok(Line::Row(1)), "d", &[2, 3, 4]).is_err());
        assert_eq!(check(Ok(Line::Row(2)), "d", &[2, 3]), Ok(Line::Row(2)));
        // Column-major 2 × 3: [[1, 3, 5], [2, 4, 6]].
        let d = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
        let get = |i: usize, j: usize| d[i + 2 * j];
        assert_eq!(extract(Line::Column(2), 2, 3, get), vec![3.0, 4.0]);
        assert_eq!(extract(Line::Row(2), 2, 3, get), vec![2.0, 4.0, 6.0]);
    }
}
