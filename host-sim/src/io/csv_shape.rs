//! What the first lines of a CSV file say about its shape, before [`super::csv`] reads it:
//! whether a file whose rows split on a comma is one column written with decimal commas.

/// How rows that split on a comma read when a file might be one column with decimal
/// commas ([`one_column_commas`]).
#[derive(Debug, PartialEq)]
pub enum OneColumn {
    /// One column of numbers with a decimal comma (`-0,125`).
    DecimalComma,
    /// Comma-separated columns, as any CSV.
    Columns,
    /// Two whole numbers on every row, nothing to tell which: refused (an example row).
    Ambiguous(String),
}

/// Decide [`OneColumn`] from the first complete lines of a file (comments and blank lines
/// left out). A row `[+-]digits[,digits]` is a candidate. When the first line is one field
/// that is not a number (a header, `accel`) and every row below it is a candidate with at
/// least one comma, the file is one column with decimal commas (two fields under a one-field
/// header could be nothing else). Without a header, when every row is a candidate, it is one
/// column when something shows a decimal comma — a fraction with a leading zero (`0,080487`),
/// an integer part `-0`, or a row without a comma — and refused when every fraction has the
/// same length of 3 or more digits with nothing to show which (`12,345` and `67,890`: two
/// integer columns or two numbers?); anything else stays comma-separated (`1,2` / `3,4`).
pub fn one_column_commas(lines: &[&str]) -> OneColumn {
    let Some(first) = lines.first() else {
        return OneColumn::Columns;
    };
    if first.contains([';', '\t']) || lines.len() < 2 {
        return OneColumn::Columns;
    }
    // (integer part, fraction) of a candidate row.
    let parts = |l: &str| -> Option<(String, Option<String>)> {
        let (int, frac) = match l.split_once(',') {
            Some((a, b)) => (a.trim(), Some(b.trim())),
            None => (l, None),
        };
        let digits = |d: &str| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit());
        let unsigned = int.strip_prefix(['-', '+']).unwrap_or(int);
        (digits(unsigned) && frac.is_none_or(digits))
            .then(|| (int.to_string(), frac.map(str::to_string)))
    };
    let header = !first.contains(',') && first.parse::<f64>().is_err();
    let rows = if header { &lines[1..] } else { lines };
    let Some(cand) = rows.iter().map(|l| parts(l)).collect::<Option<Vec<_>>>() else {
        return OneColumn::Columns;
    };
    if !cand.iter().any(|(_, f)| f.is_some()) {
        return OneColumn::Columns;
    }
    if header {
        return OneColumn::DecimalComma;
    }
    let shown = cand.iter().any(|(i, f)| match f {
        None => true,
        Some(f) => (f.len() >= 2 && f.starts_with('0')) || i == "-0" || i == "+0",
    });
    if shown {
        return OneColumn::DecimalComma;
    }
    let len = cand[0].1.as_ref().map_or(0, String::len);
    if len >= 3
        && cand
            .iter()
            .all(|(_, f)| f.as_ref().is_some_and(|f| f.len() == len))
    {
        return OneColumn::Ambiguous(rows[0].to_string());
    }
    OneColumn::Columns
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::csv::read_csv;
    use crate::io::error::IoError;
    use crate::io::ReadOptions;

    /// A vibration-like signal: impacts on noise, never monotonic.
    fn signal(n: usize) -> Vec<f64> {
        (0..n)
            .map(|i| {
                let x = i as f64;
                (x * 0.9).sin() * 0.3 + (x * 2.3).cos() * 0.2 + if i % 37 == 0 { 4.0 } else { 0.0 }
            })
            .collect()
    }

    fn opts(fs: Option<f64>) -> ReadOptions {
        ReadOptions {
            fs,
            ..Default::default()
        }
    }

    /// A time column is found by its content, whatever its header: a headerless `t,a`
    /// file, numpy's `savetxt` (spaces), a German export (`Zeit [s];Beschleunigung
    /// (m/s^2)` with decimal commas), `Temps (s)`, a unit-less `x`. The signal is the other
    /// column (it used to be the ramp: exit 0, wrong answer) and the rate comes from the ramp.
    #[test]
    fn a_ramp_column_is_the_time_axis_whatever_its_header() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("x.csv");
        let a = signal(600);
        let fs = 12_000.0;
        let rows = |sep: &str, dc: bool| -> String {
            a.iter()
                .enumerate()
                .map(|(i, v)| {
                    let row = format!("{:.8}{sep}{v:.6}\n", i as f64 / fs);
                    if dc {
                        row.replace('.', ",")
                    } else {
                        row
                    }
                })
                .collect()
        };
        for (text, by) in [
            (rows(",", false), "content"),
            (rows(" ", false), "content"),
            (
                format!("Zeit [s];Beschleunigung (m/s^2)\n{}", rows(";", true)),
                "header",
            ),
            (format!("Temps (s),acc\n{}", rows(",", false)), "content"),
            (format!("x,y\n{}", rows(",", false)), "content"),
        ] {
            std::fs::write(&p, &text).unwrap();
            let r = read_csv(&p, &opts(None)).unwrap();
            let head = &text[..20];
            assert_eq!(r.meta["column_index"], 1, "{head}");
            for (x, y) in r.samples.iter().zip(&a) {
                assert!((x - y).abs() < 1e-6, "{head}");
            }
            assert!((r.fs - fs).abs() / fs < 1e-6, "{head}: {}", r.fs);
            assert_eq!(r.meta["time_column"]["index"], 0, "{head}");
            assert_eq!(r.meta["time_column"]["found_by"], by, "{head}");
            let detail = r.meta["fs_detail"].as_str().unwrap();
            assert!(detail.starts_with("time column `"), "{detail}");
        }
        // The rate is checked against a sidecar's or --fs, naming the assumed unit.
        std::fs::write(&p, rows(",", false)).unwrap();
        let e = read_csv(&p, &opts(Some(1000.0))).unwrap_err().to_string();
        assert!(e.contains("field fs") && e.contains("taken as s"), "{e}");
    }

    /// Not every rising column is a time axis: a slowly drifting signal with noise is
    /// analysed (and gives no rate), a counter `0, 1, 2, …` (pandas' index) and a ramp in
    /// another unit are not analysed and give no rate, a rising but non-uniform column
    /// (a run-up) is a signal, and so are three rows of anything.
    #[test]
    fn drift_counters_and_other_ramps_are_no_time_axis() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("x.csv");
        let a = signal(400);
        let col = |f: &dyn Fn(usize) -> f64| -> String {
            a.iter()
                .enumerate()
                .map(|(i, v)| format!("{},{v}\n", f(i)))
                .collect()
        };
        // Drift of 1e-3 a row under noise of 1e-2.
        let drift = col(&|i| 1e-3 * i as f64 + 1e-2 * (i as f64 * 1.7).sin());
        std::fs::write(&p, &drift).unwrap();
        assert!(matches!(
            read_csv(&p, &opts(None)),
            Err(IoError::MissingSampleRate { .. })
        ));
        assert_eq!(read_csv(&p, &opts(Some(100.0))).unwrap().channel, "col0");
        for (text, taken_as) in [
            (
                format!(",accel\n{}", col(&|i| i as f64)),
                "a sample counter",
            ),
            (
                format!("Position [mm],accel\n{}", col(&|i| 0.5 * i as f64)),
                "a ramp in mm",
            ),
        ] {
            std::fs::write(&p, &text).unwrap();
            assert!(matches!(
                read_csv(&p, &opts(None)),
                Err(IoError::MissingSampleRate { .. })
            ));
            let r = read_csv(&p, &opts(Some(100.0))).unwrap();
            assert_eq!((r.channel.as_str(), r.fs), ("accel", 100.0));
            assert_eq!(r.meta["ramp_columns_not_analysed"][0]["taken_as"], taken_as);
            assert!(r.meta["time_column"].is_null());
        }
        // Rising steps growing 1 → 400: not uniform, analysed as given.
        std::fs::write(&p, col(&|i| (i * i) as f64)).unwrap();
        assert_eq!(read_csv(&p, &opts(Some(100.0))).unwrap().channel, "col0");
    }

    /// One column with decimal commas: under a header, or without one when a fraction with
    /// a leading zero shows it, read as numbers (the headerless file used to read as two
    /// columns, integer part and fraction). Two whole numbers on every row with nothing to
    /// tell is refused naming the decimal comma; `1,2` rows stay two columns, and a header
    /// over rows of another shape gets the hint.
    #[test]
    fn one_column_with_decimal_commas() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("x.csv");
        let want = vec![-86.678957, 0.080487, 2.368564, -0.5];
        let body = "-86,678957\n0,080487\n2,368564\n-0,500000\n";
        for text in [format!("accel\n{body}"), body.to_string()] {
            std::fs::write(&p, &text).unwrap();
            let r = read_csv(&p, &opts(Some(12_000.0))).unwrap();
            assert_eq!(r.samples, want, "{text:?}");
            assert_eq!(r.meta["n_columns"], 1);
        }
        std::fs::write(&p, "12,345\n67,890\n-11,111\n").unwrap();
        let e = read_csv(&p, &opts(Some(100.0))).unwrap_err().to_string();
        assert!(
            e.contains("decimal comma") && e.contains("\"12,345\""),
            "{e}"
        );
        std::fs::write(&p, "accel\n1,5\n1.5,2\n").unwrap();
        let e = read_csv(&p, &opts(Some(100.0))).unwrap_err().to_string();
        assert!(
            e.contains("row has 2 fields") && e.contains("decimal comma"),
            "{e}"
        );
        let lines = |t: &'static str| t.lines().collect::<Vec<_>>();
        assert_eq!(
            one_column_commas(&lines("1,2\n3,4\n5,6")),
            OneColumn::Columns
        );
        assert_eq!(
            one_column_commas(&lines("a,b\n1,2\n3,4")),
            OneColumn::Columns
        );
        assert_eq!(one_column_commas(&lines("a\n1\n2")), OneColumn::Columns);
        assert_eq!(
            one_column_commas(&lines("a\n1,5\n2")),
            OneColumn::DecimalComma
        );
    }
}
