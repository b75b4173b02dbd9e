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

    /// Whether the speed never changes (lets the model skip per-step evaluation).
    pub fn is_constant(&self) -> bool {
        matches!(self, SpeedProfile::Constant(_))
    }
}
