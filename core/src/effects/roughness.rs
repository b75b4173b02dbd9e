//! Effect `roughness`: the level of distributed roughness. The baseline's effective
//! roughness excitation (a few nm transmitted through the EHL film) is a chosen value;
//! the composite Rq of real races ranges from 0.02 to 0.4 µm and the film carries less
//! of it as the film parameter λ falls (Harris & Kotzalas 2006 ch. 4; thesis §4.1.2 on
//! roughness as the source of the broadband level). This effect scales the roughness RMS
//! by `s` ∈ [0, 20], which raises the broadband (natural-frequency and high-frequency
//! zone) level by `20 log10 s` dB. Needs roughness in the model.

use crate::error::{check_range, ConfigError};
use crate::real::Real;

/// Parameters of the `roughness` effect.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Params {
    /// Scale of the roughness RMS (–), in [0, 20].
    pub scale: Real,
}

impl Params {
    /// Validates the scale in [0, 20].
    pub fn new_checked(p: Params) -> Result<Self, ConfigError> {
        check_range("roughness.scale", p.scale, 0.0, 20.0)?;
        Ok(p)
    }
}
