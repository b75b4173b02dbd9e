//! Shaft speed as a function of time: constant, linear ramp (run-up/coast-down) or a
//! piecewise-linear table. The model integrates shaft, cage and element angles from the
//! instantaneous speed (trapezoidal rule, exact for piecewise-linear profiles), never as
//! `ω·t`, so every force diagram follows speed changes.

use crate::error::{check_range, ConfigError};
use crate::real::Real;
use heapless::Vec;

/// Capacity of a speed table.
pub const MAX_SPEED_POINTS: usize = 16;
/// Highest shaft frequency accepted (Hz); 1000 Hz = 60 000 rpm.
pub const MAX_SHAFT_HZ: Real = 1000.0;

/// One point of a speed table: time (s) and shaft frequency (Hz).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SpeedPoint {
    /// Time (s) from the start of the run.
    pub t: Real,
    /// Shaft rotation frequency (Hz) at `t`.
    pub shaft_hz: Real,
}

/// The shaft frequency over an interval of a run ([`SpeedProfile::over`]), Hz.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpeedSpan {
    /// Time average over the interval (Hz): revolutions per second of the interval.
    pub mean_hz: Real,
    /// Lowest shaft frequency in the interval (Hz).
    pub min_hz: Real,
    /// Highest shaft frequency in the interval (Hz).
    pub max_hz: Real,
}

/// Shaft speed profile.
#[derive(Debug, Clone, PartialEq)]
#[allow(clippy::large_enum_variant)] // fixed capacity on purpose: no heap
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum SpeedProfile {
    /// Constant shaft frequency (Hz).
    Constant(Real),
    /// Linear change from `from_hz` to `to_hz` over `duration` seconds starting at 0,
    /// constant at `to_hz` afterwards.
    Ramp {
        /// Shaft frequency at t = 0 (Hz).
        from_hz: Real,
        /// Shaft frequency from t = `duration` on (Hz).
        to_hz: Real,
        /// Ramp duration (s).
        duration: Real,
    },
    /// Piecewise-linear interpolation between points with increasing time; constant
    /// before the first and after the last point.
    Table(Vec<SpeedPoint, MAX_SPEED_POINTS>),
}

impl SpeedProfile {
    /// Validates the profile: speeds in `(0, MAX_SHAFT_HZ]` (a stopped shaft has no
    /// kinematics: use a small positive speed), durations positive, table times increasing.
    pub fn new_checked(p: SpeedProfile) -> Result<Self, ConfigError> {
        match &p {
            SpeedProfile::Constant(f) => check_range("speed.shaft_hz", *f, 1e-3, MAX_SHAFT_HZ)?,
            SpeedProfile::Ramp {
                from_hz,
                to_hz,
                duration,
            } => {
                check_range("speed.from_hz", *from_hz, 1e-3, MAX_SHAFT_HZ)?;
                check_range("speed.to_hz", *to_hz, 1e-3, MAX_SHAFT_HZ)?;
                check_range("speed.duration", *duration, 1e-6, 1e9)?;
            }
            SpeedProfile::Table(pts) => {
                if pts.len() < 2 {
                    return Err(ConfigError::Inconsistent {
                        field: "speed.table",
                        reason: "a speed table needs at least 2 points",
                    });
                }
                let mut last_t = -1.0;
                for pt in pts.iter() {
                    check_range("speed.table.t", pt.t, 0.0, 1e9)?;
                    check_range("speed.table.shaft_hz", pt.shaft_hz, 1e-3, MAX_SHAFT_HZ)?;
                    if pt.t <= last_t {
                        return Err(ConfigError::Inconsistent {
                            field: "speed.table.t",
                            reason: "times must be strictly increasing",
                        });
                    }
                    last_t = pt.t;
                }
            }
        }
        Ok(p)
    }

    /// Shaft frequency (Hz) at time `t` (s).
    #[inline]
    pub fn shaft_hz(&self, t: Real) -> Real {
        match self {
            SpeedProfile::Constant(f) => *f,
            SpeedProfile::Ramp {
                from_hz,
                to_hz,
                duration,
            } => {
                if t >= *duration {
                    *to_hz
                } else if t <= 0.0 {
                    *from_hz
                } else {
                    from_hz + (to_hz - from_hz) * (t / duration)
                }
            }
            SpeedProfile::Table(pts) => {
                let (Some(first), Some(last)) = (pts.first(), pts.last()) else {
                    return 1.0;
                };
                if t <= first.t {
                    return first.shaft_hz;
                }
                if t >= last.t {
                    return last.shaft_hz;
                }
                for w in pts.windows(2) {
                    if let [a, b] = w {
                        if t <= b.t {
                            let s = (t - a.t) / (b.t - a.t);
                            return a.shaft_hz + (b.shaft_hz - a.shaft_hz) * s;
                        }
                    }
                }
                last.shaft_hz
            }
        }
    }

    /// Highest shaft frequency of the profile (Hz), for step validation.
    pub fn max_hz(&self) -> Real {
        match self {
            SpeedProfile::Constant(f) => *f,
            SpeedProfile::Ramp { from_hz, to_hz, .. } => from_hz.max(*to_hz),
            SpeedProfile::Table(pts) => {
                pts.iter()
                    .fold(0.0, |m, p| if p.shaft_hz > m { p.shaft_hz } else { m })
            }
        }
    }

    /// Largest rate of change of the shaft frequency `|df/dt|` (Hz/s): zero for a constant
    /// speed, the ramp's slope, or the steepest segment of a table (piecewise linear).
    pub fn max_slope_hz_per_s(&self) -> Real {
        match self {
            SpeedProfile::Constant(_) => 0.0,
            SpeedProfile::Ramp {
                from_hz,
                to_hz,
                duration,
            } => (to_hz - from_hz).abs() / duration,
            SpeedProfile::Table(pts) => pts.windows(2).fold(0.0, |m: Real, w| match w {
                [a, b] => m.max((b.shaft_hz - a.shaft_hz).abs() / (b.t - a.t)),
                _ => m,
            }),
        }
    }

    /// The shaft frequency over the interval `[t0, t1]` (s): its time average and its
    /// extremes (Hz), exact for these piecewise-linear profiles (trapezoids between the
    /// interval's ends and the profile's knots inside it). What a recorded part of a run
    /// says about its speed: a record starts at the settle time, so `shaft_hz(0)` is not
    /// its speed when a ramp or table changes it. An empty or reversed interval gives the
    /// speed at `t0`.
    pub fn over(&self, t0: Real, t1: Real) -> SpeedSpan {
        let f0 = self.shaft_hz(t0);
        let mut span = SpeedSpan {
            mean_hz: f0,
            min_hz: f0,
            max_hz: f0,
        };
        if t1 <= t0 || t0.is_nan() || t1.is_nan() {
            return span;
        }
        let mut knots: Vec<Real, { MAX_SPEED_POINTS + 1 }> = Vec::new();
        match self {
            SpeedProfile::Constant(_) => {}
            SpeedProfile::Ramp { duration, .. } => {
                let _ = knots.push(0.0);
                let _ = knots.push(*duration);
            }
            SpeedProfile::Table(pts) => {
                for p in pts {
                    let _ = knots.push(p.t);
                }
            }
        }
        // The area is summed relative to `f0`, so that a speed that does not change over
        // the interval averages to `f0` exactly (no rounding of `f0·T/T`).
        let (mut t, mut f, mut area) = (t0, f0, 0.0);
        for &k in knots.iter().filter(|k| **k > t0 && **k < t1) {
            let fk = self.shaft_hz(k);
            area += 0.5 * ((f - f0) + (fk - f0)) * (k - t);
            span.min_hz = span.min_hz.min(fk);
            span.max_hz = span.max_hz.max(fk);
            (t, f) = (k, fk);
        }
        let f1 = self.shaft_hz(t1);
        area += 0.5 * ((f - f0) + (f1 - f0)) * (t1 - t);
        span.min_hz = span.min_hz.min(f1);
        span.max_hz = span.max_hz.max(f1);
        span.mean_hz = f0 + area / (t1 - t0);
        span
    }

    /// Whether the speed never changes (lets the model skip per-step evaluation).
    pub fn is_constant(&self) -> bool {
        matches!(self, SpeedProfile::Constant(_))
    }
}
