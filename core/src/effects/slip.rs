//! Effect `slip`: random slip of the element passes (thesis §4.1.6, publication IV §3
//! case 6). Real rolling elements do not roll perfectly: the cage lags and each element's
//! position at the defect wanders by about 1–2 % of the element pitch (Randall & Antoni
//! 2011, MSSP 25, "Rolling element bearing diagnostics — a tutorial"), which makes the
//! impact train cyclostationary instead of periodic and smears the higher fault-frequency
//! harmonics of the envelope spectrum. This effect exposes the existing
//! [`crate::forces::slip::Slip`] term (it replaces `ModelConfig::slip` when switched on).

use crate::error::{check_range, ConfigError};
use crate::real::Real;

/// Parameters of the `slip` effect.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Params {
    /// Standard deviation of the element position at the defect as a fraction of the
    /// element pitch `2π/N` (–), in [0, 0.2].
    pub fraction: Real,
}

impl Params {
    /// Validates `fraction` in [0, 0.2].
    pub fn new_checked(p: Params) -> Result<Self, ConfigError> {
        check_range("slip.fraction", p.fraction, 0.0, 0.2)?;
        Ok(p)
    }
}
