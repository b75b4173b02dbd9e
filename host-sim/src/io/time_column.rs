//! The time column of a text record: which header names one, in which unit, and the sample
//! rate its stamps give ([`crate::io::csv`], and the layouts read through it).
//!
//! A time column is headed `time`, `t` or `Zeit`, alone (seconds) or with a unit in brackets
//! (`Time (ms)`, `time [us]`, `t(s)`) or after an underscore (`time_s`, `t_ms`); spaces and
//! case are ignored. Units: seconds (`s`, `sec`, `second(s)`), milliseconds (`ms`, `msec`),
//! microseconds (`us`, `µs`, `μs`, `usec`) and nanoseconds (`ns`, `nsec`). A `time` header
//! with another unit in brackets (`Time (h)`, `time [samples]`) is refused naming the column
//! and the units read, rather than taken as a data channel; `t` with another unit (`T (°C)`)
//! and `_` suffixes that are no unit (`time_stamp`, `t_max`) are data columns.
//!
//! A column is also a time axis by its content, whatever its header ([`RampScan`],
//! [`ramp_role`]): values that rise strictly on every row, with steps within a factor 2 of
//! each other, over at least [`MIN_RAMP_ROWS`] rows. No vibration signal does that (noise
//! alone breaks it), so such a column is never analysed by default. Its unit is the one its
//! header states (`Temps (s)`, `tiempo_ms`); a header that states none, or no header, is
//! taken as seconds, and a column of whole numbers rising by exactly 1 is a sample counter
//! (`0, 1, 2, …`, pandas' index), which gives no rate.

use std::path::Path;

use super::error::IoError;
use super::record::check_finite;

/// The unit of a time column.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeUnit {
    /// The unit's symbol as messages print it (`s`, `ms`, `µs`, `ns`).
    pub symbol: &'static str,
    /// Units per second (1 for `s`, 1000 for `ms`).
    pub per_second: f64,
}

/// Accepted spellings of each time unit (compared lower-case), with the unit.
const UNITS: &[(&[&str], TimeUnit)] = &[
    (
        &["s", "sec", "secs", "second", "seconds"],
        TimeUnit {
            symbol: "s",
            per_second: 1.0,
        },
    ),
    (
        &["ms", "msec", "msecs", "millisecond", "milliseconds"],
        TimeUnit {
            symbol: "ms",
            per_second: 1e3,
        },
    ),
    (
        &[
            "us",
            "µs",
            "μs",
            "usec",
            "usecs",
            "microsecond",
            "microseconds",
        ],
        TimeUnit {
            symbol: "µs",
            per_second: 1e6,
        },
    ),
    (
        &["ns", "nsec", "nsecs", "nanosecond", "nanoseconds"],
        TimeUnit {
            symbol: "ns",
            per_second: 1e9,
        },
    ),
];

/// Seconds, the unit of a bare `time` or `t` column.
pub const SECONDS: TimeUnit = UNITS[0].1;

/// The units a time column may state, as a message lists them.
pub fn accepted_units() -> String {
    UNITS
        .iter()
        .map(|(names, _)| names.join("/"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// `name` without whitespace, in lower case: how a header is compared.
fn compact(name: &str) -> String {
    name.chars()
        .filter(|c| !c.is_whitespace())
        .flat_map(char::to_lowercase)
        .collect()
}

/// What header `name` says of its column: `None` for a data column, `Some(Ok(unit))` for
/// a time column in a unit read here, `Some(Err(unit))` for a `time` column in another unit
/// (see the module doc).
pub fn time_unit(name: &str) -> Option<Result<TimeUnit, String>> {
    let compact = compact(name);
    let known = |u: &str| UNITS.iter().find(|(n, _)| n.contains(&u)).map(|(_, t)| *t);
    for base in ["time", "t", "zeit"] {
        let Some(rest) = compact.strip_prefix(base) else {
            continue;
        };
        if rest.is_empty() {
            return Some(Ok(SECONDS));
        }
        let bracketed = [('(', ')'), ('[', ']')]
            .iter()
            .find_map(|&(o, c)| rest.strip_prefix(o)?.strip_suffix(c));
        match (bracketed, rest.strip_prefix('_')) {
            (Some(u), _) => match known(u) {
                Some(t) => return Some(Ok(t)),
                None if base != "t" => return Some(Err(u.to_string())),
                None => return None,
            },
            (None, Some(u)) => return known(u).map(Ok),
            (None, None) => {}
        }
    }
    None
}

/// The unit a header states for its column, whatever its name: the last group in brackets
/// (`Zeit [s]`, `Tiempo (ms)`), else the part after the last underscore (`tiempo_ms`),
/// spaces and case ignored. `None` when the header states no unit, `Some(Ok)` for a time
/// unit read here, `Some(Err(text))` for any other (`Position [mm]`, `acc_g`).
pub fn stated_unit(name: &str) -> Option<Result<TimeUnit, String>> {
    let compact = compact(name);
    let bracketed = [('(', ')'), ('[', ']')].iter().find_map(|&(o, c)| {
        let inner = compact.strip_suffix(c)?;
        inner
            .rfind(o)
            .map(|i| inner[i + o.len_utf8()..].to_string())
    });
    let unit = bracketed.or_else(|| {
        compact
            .rsplit_once('_')
            .map(|(_, u)| u.to_string())
            .filter(|u| !u.is_empty())
    })?;
    Some(
        UNITS
            .iter()
            .find(|(n, _)| n.contains(&unit.as_str()))
            .map(|(_, t)| *t)
            .ok_or(unit),
    )
}

/// Fewest rows a column needs before its content can make it a time axis (a record too
/// short for that is too short to analyse anyway).
pub const MIN_RAMP_ROWS: usize = 16;

/// What the values of one column show, pushed row by row: whether they rise strictly on
/// every row with steps within a factor 2 of each other (a ramp: a time axis or a sample
/// counter, never a vibration signal).
#[derive(Debug, Clone)]
pub struct RampScan {
    rows: usize,
    prev: f64,
    min_step: f64,
    max_step: f64,
    rising: bool,
    counter: bool,
}

impl Default for RampScan {
    fn default() -> Self {
        Self {
            rows: 0,
            prev: f64::NEG_INFINITY,
            min_step: f64::INFINITY,
            max_step: 0.0,
            rising: true,
            counter: true,
        }
    }
}

impl RampScan {
    /// Take the next row's value (`None`: the cell is not a number, so no ramp).
    pub fn push(&mut self, v: Option<f64>) {
        self.rows += 1;
        let Some(v) = v.filter(|v| v.is_finite()) else {
            self.rising = false;
            return;
        };
        if self.rows > 1 {
            let step = v - self.prev;
            // Both values are finite, so the step is.
            if step <= 0.0 {
                self.rising = false;
            }
            self.min_step = self.min_step.min(step);
            self.max_step = self.max_step.max(step);
            self.counter &= step == 1.0;
        }
        self.counter &= v.fract() == 0.0;
        self.prev = v;
    }

    /// Strictly rising on every row, steps within a factor 2, at least [`MIN_RAMP_ROWS`].
    pub fn is_ramp(&self) -> bool {
        self.rising && self.rows >= MIN_RAMP_ROWS && self.max_step <= 2.0 * self.min_step
    }

    /// A ramp of whole numbers rising by exactly 1 (a sample counter or index).
    pub fn is_counter(&self) -> bool {
        self.is_ramp() && self.counter
    }
}

/// How a ramp column ([`RampScan::is_ramp`]) with header `name` is taken.
#[derive(Debug, Clone, PartialEq)]
pub enum RampRole {
    /// A time axis in this unit; `assumed` when the header states none (seconds taken).
    Time {
        /// The unit of its stamps.
        unit: TimeUnit,
        /// True when no unit is stated and seconds are assumed.
        assumed: bool,
    },
    /// Whole numbers rising by 1 with no unit stated: a sample counter, no rate.
    Counter,
    /// The header states a unit that is not one of time (`Position [mm]`): not analysed by
    /// default, no rate.
    Other(String),
}

/// The role of a ramp column with header `name` (see the module doc). A header that names a
/// time column ([`time_unit`]) is read by that rule before this one.
pub fn ramp_role(name: &str, scan: &RampScan) -> RampRole {
    match stated_unit(name) {
        Some(Ok(unit)) => RampRole::Time {
            unit,
            assumed: false,
        },
        Some(Err(u)) => RampRole::Other(u),
        None if scan.is_counter() => RampRole::Counter,
        None => RampRole::Time {
            unit: SECONDS,
            assumed: true,
        },
    }
}

/// The [`time_unit`] of column `name` of `path` when it is a time column; a `time` column in
/// a unit not read here is an error naming the column and the units accepted.
pub fn time_column(path: &Path, name: &str) -> Result<Option<TimeUnit>, IoError> {
    match time_unit(name) {
        None => Ok(None),
        Some(Ok(u)) => Ok(Some(u)),
        Some(Err(u)) => Err(IoError::malformed(
            path,
            format!(
                "time column {name:?}: unit {u:?} is not a time unit read here (accepted: {}); rename the column with one of them, or remove it and pass --fs",
                accepted_units()
            ),
        )),
    }
}

/// Digits after the decimal point (or comma) of a number cell as printed; `None` for the
/// exponent form (`3.9e-5`), taken as printed to full precision.
pub fn decimals(cell: &str) -> Option<usize> {
    if cell.contains(['e', 'E']) {
        return None;
    }
    Some(cell.rsplit_once(['.', ',']).map_or(0, |(_, f)| f.len()))
}

/// Sample rate (Hz) from the stamps `t` of time column `name` in `unit`; `None` for fewer
/// than 2 rows. Non-uniform or non-increasing times are an error. A time printed with
/// `decimals` digits after the point is off by up to half a unit of the last digit (a
/// 25.6 kHz record's stamps printed to the microsecond are 0.000039, 0.000078, …): each stamp
/// must lie within twice that rounding (its own and the first stamp's), plus 10⁻³ of the
/// spacing, of the uniform grid, and the rate is taken from the whole span. Whole numbers are
/// rounded to their last digit the same way (a 25.6 kHz record stamped in whole
/// microseconds: 0, 39, 78, 117, …). The allowance is at most a quarter of the spacing, so every stamp still
/// lies nearest its own sample; stamps printed too coarsely to meet it are refused saying so.
/// The check runs in the column's unit; the rate is `unit.per_second` over the spacing.
pub fn fs_from_time(
    path: &Path,
    name: &str,
    t: &[f64],
    decimals: Option<usize>,
    unit: TimeUnit,
) -> Result<Option<f64>, IoError> {
    if t.len() < 2 {
        return Ok(None);
    }
    check_finite(path, name, t)?;
    let n = t.len();
    let span = t[n - 1] - t[0];
    if span <= 0.0 {
        return Err(IoError::malformed(
            path,
            format!("time column {name:?} does not increase"),
        ));
    }
    let dt = span / (n - 1) as f64;
    let u = unit.symbol;
    // Half a unit of the last printed digit (0 for full precision and for whole numbers;
    // 10^-d underflows to 0 past f64's exponent range, also full precision).
    // Whole numbers (`time_us` 0, 39, 78, …) are rounded to their last digit like any
    // other printed stamp: half a unit.
    let rounding = decimals.map_or(0.0, |d| {
        0.5 * 10f64.powi(-i32::try_from(d).unwrap_or(i32::MAX))
    });
    let tol = dt * 1e-3 + (2.0 * rounding).min(0.25 * dt);
    for (i, &ti) in t.iter().enumerate() {
        if (ti - (t[0] + i as f64 * dt)).abs() > tol {
            let coarse = match decimals {
                Some(d) if 2.0 * rounding > 0.25 * dt => format!(
                    "; printed {}, the stamps are too coarse for a spacing of {dt:e} {u}: print more decimals (or a finer unit), or drop the column and pass --fs",
                    if d == 0 { "as whole numbers".to_string() } else { format!("to {d} decimals") }
                ),
                _ => String::new(),
            };
            return Err(IoError::malformed(
                path,
                format!(
                    "time column {name:?} is not uniformly spaced (row {i}: {ti} {u}, expected {} {u}){coarse}",
                    t[0] + i as f64 * dt
                ),
            ));
        }
    }
    Ok(Some(unit.per_second / dt))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn time_headers_and_their_units() {
        let unit = |n: &str| time_unit(n).map(|r| r.map(|u| u.symbol));
        for (name, want) in [
            ("time", "s"),
            ("T", "s"),
            ("time_s", "s"),
            ("Time (s)", "s"),
            ("time [sec]", "s"),
            ("Time (ms)", "ms"),
            ("time [ms]", "ms"),
            ("t_ms", "ms"),
            ("Time (us)", "µs"),
            ("Time (µs)", "µs"),
            ("time [μs]", "µs"),
            ("time_ns", "ns"),
        ] {
            assert_eq!(unit(name), Some(Ok(want)), "{name}");
        }
        for name in ["accel", "T (°C)", "time_stamp", "t_max", "Temp", "times"] {
            assert_eq!(unit(name), None, "{name}");
        }
        assert_eq!(unit("Time (h)"), Some(Err("h".into())));
        assert_eq!(unit("time [samples]"), Some(Err("samples".into())));
        let e = time_column(Path::new("x.csv"), "Time (h)").unwrap_err();
        let e = e.to_string();
        assert!(e.contains("\"Time (h)\"") && e.contains("ms/msec"), "{e}");
    }

    #[test]
    fn a_millisecond_column_gives_the_rate_of_the_seconds_column() {
        let p = Path::new("x.csv");
        // 16384 Hz: every stamp is exact in binary, in seconds and in milliseconds.
        let s: Vec<f64> = (0..100).map(|i| i as f64 / 16384.0).collect();
        let ms: Vec<f64> = s.iter().map(|t| t * 1000.0).collect();
        let unit_ms = time_unit("t_ms").unwrap().unwrap();
        let a = fs_from_time(p, "t", &s, None, SECONDS).unwrap();
        let b = fs_from_time(p, "t_ms", &ms, None, unit_ms).unwrap();
        assert_eq!((a, b), (Some(16384.0), Some(16384.0)));
    }

    /// Whole-number stamps are rounded to their last digit like printed decimals: a
    /// 25.6 kHz record stamped in whole microseconds (0, 39, 78, …) and a 12 kHz one (0, 83,
    /// 167, …) give their rates; a stamp off by more than the rounding is still refused, and
    /// a 1024 Hz record in whole milliseconds is too coarse, said so.
    #[test]
    fn whole_number_stamps_are_rounded_to_their_last_digit() {
        let p = Path::new("x.csv");
        let us = time_unit("time_us").unwrap().unwrap();
        for fs in [25_600.0, 12_000.0] {
            let t: Vec<f64> = (0..25_600).map(|i| (i as f64 / fs * 1e6).round()).collect();
            let got = fs_from_time(p, "time_us", &t, Some(0), us)
                .unwrap()
                .unwrap();
            assert!((got - fs).abs() / fs < 1e-6, "{fs}: {got}");
        }
        let mut t: Vec<f64> = (0..1000)
            .map(|i| (i as f64 / 25_600.0 * 1e6).round())
            .collect();
        t[500] += 2.0;
        let e = fs_from_time(p, "time_us", &t, Some(0), us)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("not uniformly spaced") && e.contains("row 500"),
            "{e}"
        );
        let ms = time_unit("time_ms").unwrap().unwrap();
        let t: Vec<f64> = (0..1000)
            .map(|i| (i as f64 / 1024.0 * 1e3).round())
            .collect();
        let e = fs_from_time(p, "time_ms", &t, Some(0), ms)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("as whole numbers") && e.contains("too coarse"),
            "{e}"
        );
    }

    /// Units a header states, whatever its name; ramps, counters and what is neither.
    #[test]
    fn stated_units_and_ramps() {
        let unit = |n: &str| stated_unit(n).map(|r| r.map(|u| u.symbol));
        assert_eq!(unit("Zeit [s]"), Some(Ok("s")));
        assert_eq!(unit("Tiempo (ms)"), Some(Ok("ms")));
        assert_eq!(unit("tiempo_us"), Some(Ok("µs")));
        assert_eq!(unit("Position [mm]"), Some(Err("mm".into())));
        assert_eq!(unit("Beschleunigung (m/s^2)"), Some(Err("m/s^2".into())));
        for name in ["", "x", "col0", "Unnamed: 0"] {
            assert_eq!(unit(name), None, "{name}");
        }
        assert_eq!(
            time_unit("Zeit").map(|r| r.map(|u| u.symbol)),
            Some(Ok("s"))
        );
        let scan = |v: &[f64]| {
            let mut s = RampScan::default();
            for &x in v {
                s.push(Some(x));
            }
            s
        };
        let ramp: Vec<f64> = (0..MIN_RAMP_ROWS).map(|i| i as f64 * 0.25).collect();
        assert!(scan(&ramp).is_ramp() && !scan(&ramp).is_counter());
        assert!(!scan(&ramp[1..]).is_ramp(), "too few rows");
        let counter: Vec<f64> = (0..100).map(f64::from).collect();
        assert!(scan(&counter).is_counter());
        let mut flat = counter.clone();
        flat[50] = flat[49];
        assert!(!scan(&flat).is_ramp(), "a repeated value");
        let mut s = scan(&counter);
        s.push(None);
        assert!(!s.is_ramp(), "a cell that is no number");
        assert_eq!(ramp_role("", &scan(&counter)), RampRole::Counter);
        assert_eq!(
            ramp_role("x", &scan(&ramp)),
            RampRole::Time {
                unit: SECONDS,
                assumed: true
            }
        );
    }
}
