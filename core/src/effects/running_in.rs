//! Effect `running-in`: a new bearing's surfaces are rougher than after a few hours of
//! running; the asperity peaks are plastically flattened and worn off, and the roughness
//! (hence the broadband vibration from it) decays towards its steady level (thesis §2.2
//! on the running-in stage of wear; Kragelsky et al. 1982, *Friction and Wear:
//! Calculation Methods*; Jamari & Schipper 2006 on roughness running-in). Modelled as
//! the roughness RMS multiplied by `1 + (F − 1) exp(−n/n_d)`, `n` the shaft revolutions
//! since the start of the run (plus an optional offset, for example the revolutions
//! already run in a life test), `F` the initial factor and `n_d` the decay length.
//! Needs roughness in the model; the factor is refreshed every 256 internal steps.

use crate::error::{check_range, ConfigError};
use crate::real::{exp, Real};

/// Parameters of the `running-in` effect.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Params {
    /// Initial roughness factor `F` (–), in [1, 10].
    pub factor: Real,
    /// Decay length `n_d` (revolutions), in [1, 10⁹].
    pub decay_revs: Real,
    /// Revolutions already run before this simulation starts, in [0, 10¹²].
    pub start_revs: Real,
}

impl Params {
    /// Validates the parameters (see the fields).
    pub fn new_checked(p: Params) -> Result<Self, ConfigError> {
        check_range("running-in.factor", p.factor, 1.0, 10.0)?;
        check_range("running-in.decay_revs", p.decay_revs, 1.0, 1.0e9)?;
        check_range("running-in.start_revs", p.start_revs, 0.0, 1.0e12)?;
        Ok(p)
    }

    /// Roughness multiplier after `revs` revolutions of this run.
    #[inline]
    pub fn scale(&self, revs: Real) -> Real {
        1.0 + (self.factor - 1.0) * exp(-(revs + self.start_revs) / self.decay_revs)
    }
}
