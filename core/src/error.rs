//! The typed error every fallible constructor of the core returns.

/// Why a configuration was rejected. Every variant names the offending field (a dotted
/// path as in the TOML configuration, e.g. `"bearing.ball_diameter"`) so that a front end
/// can print it unchanged.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum ConfigError {
    /// A number outside its allowed closed range `[min, max]` (NaN and ±inf land here too).
    OutOfRange {
        /// Configuration field.
        field: &'static str,
        /// Value given.
        value: f64,
        /// Smallest allowed value.
        min: f64,
        /// Largest allowed value.
        max: f64,
    },
    /// A count or table longer than the fixed capacity compiled into the core.
    TooMany {
        /// Configuration field.
        field: &'static str,
        /// Count given.
        count: usize,
        /// Capacity.
        max: usize,
    },
    /// Two fields that are each valid but contradict each other.
    Inconsistent {
        /// Configuration field.
        field: &'static str,
        /// What is wrong, in words.
        reason: &'static str,
    },
    /// The internal integration step cannot resolve the stiffest frequency of the model
    /// (`ω_max·h` above the integrator's limit): raise the internal rate.
    StepTooLarge {
        /// Configuration field that sets the step.
        field: &'static str,
        /// `ω_max·h` of the requested step.
        omega_h: f64,
        /// Allowed maximum of `ω_max·h` for the chosen integrator.
        limit: f64,
        /// Smallest internal rate (Hz) that would be accepted.
        min_internal_rate_hz: f64,
        /// The largest automatic oversample (internal steps per output sample) when the
        /// oversample was automatic and even it was too coarse: the output rate `fs` must
        /// then be at least `min_internal_rate_hz / max_oversample`. `None` when the
        /// configuration fixed the oversample.
        max_oversample: Option<u32>,
        /// The races' waviness passing frequency (Hz) when it, not the stiffest mode, sets
        /// `min_internal_rate_hz` (it must stay below 0.45 of the internal rate; it grows
        /// with the shaft speed). `None`: the stiffest mode sets it.
        waviness_hz: Option<f64>,
    },
    /// A feature of the model that this version does not implement.
    Unsupported {
        /// Configuration field.
        field: &'static str,
        /// What is unsupported.
        what: &'static str,
    },
}

impl ConfigError {
    /// The configuration field the error is about.
    pub fn field(&self) -> &'static str {
        match *self {
            ConfigError::OutOfRange { field, .. }
            | ConfigError::TooMany { field, .. }
            | ConfigError::Inconsistent { field, .. }
            | ConfigError::StepTooLarge { field, .. }
            | ConfigError::Unsupported { field, .. } => field,
        }
    }
}

impl core::fmt::Display for ConfigError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            ConfigError::OutOfRange {
                field,
                value,
                min,
                max,
            } => write!(
                f,
                "{field} = {value} is out of range: allowed {min} ..= {max} (finite)"
            ),
            ConfigError::TooMany { field, count, max } => {
                write!(
                    f,
                    "{field} has {count} entries; at most {max} are supported"
                )
            }
            ConfigError::Inconsistent { field, reason } => write!(f, "{field}: {reason}"),
            ConfigError::StepTooLarge {
                field,
                omega_h,
                limit,
                min_internal_rate_hz,
                max_oversample,
                waviness_hz,
            } => {
                match waviness_hz {
                    Some(w) => write!(
                        f,
                        "{field}: internal step too large for the races' waviness, which \
                         passes at {w:.0} Hz at this shaft speed and must stay below 0.45 of \
                         the internal rate (the stiffest mode's omega*h = {omega_h:.3} {} \
                         {limit}); use an internal rate of at least \
                         {min_internal_rate_hz:.0} Hz",
                        if omega_h <= limit {
                            "is within its limit"
                        } else {
                            "exceeds its limit too,"
                        }
                    )?,
                    None => write!(
                        f,
                        "{field}: internal step too large for the stiffest mode (omega*h = \
                         {omega_h:.3}, limit {limit}); use an internal rate of at least \
                         {min_internal_rate_hz:.0} Hz"
                    )?,
                }
                match max_oversample {
                    Some(r) if r > 0 => write!(
                        f,
                        ": an output rate fs of at least {:.0} Hz (at most {r} internal steps \
                         per sample)",
                        libm::ceil(min_internal_rate_hz / r as f64)
                    ),
                    _ => Ok(()),
                }
            }
            ConfigError::Unsupported { field, what } => {
                write!(f, "{field}: {what} is not supported by this version")
            }
        }
    }
}

/// Checks that `value` is finite and in `[min, max]`, naming `field` otherwise.
#[inline]
#[allow(clippy::unnecessary_cast)]
pub fn check_range(
    field: &'static str,
    value: crate::real::Real,
    min: crate::real::Real,
    max: crate::real::Real,
) -> Result<(), ConfigError> {
    if value.is_finite() && value >= min && value <= max {
        Ok(())
    } else {
        Err(ConfigError::OutOfRange {
            field,
            value: value as f64,
            min: min as f64,
            max: max as f64,
        })
    }
}

impl core::error::Error for ConfigError {}
