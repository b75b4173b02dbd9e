//! Effect `speed-fluctuation`: the shaft speed is never quite constant. Motor slip
//! varying with load, belt/coupling eccentricity and the control loop modulate it
//! periodically; load torque ripple adds a random part. Either smears the fault lines
//! (their frequency is proportional to speed) and puts sidebands at ± the modulation
//! frequency around every order line (Randall 2011, *Vibration-based Condition
//! Monitoring* §3.6 on order tracking; Borghesani et al. 2013, MSSP 38, "Application of
//! cepstrum pre-whitening for the diagnosis of bearing faults under variable speed").
//!
//! The speed profile is multiplied by
//! `1 + a sin(2π f_m t) + j Σ_{k=1}^{8} √(2/8) sin(2π (k/8) f_j t + φ_k)`:
//! a sinusoidal part (relative amplitude `a`, frequency `f_m`) and a random-phase
//! multisine of relative RMS `j` spread uniformly up to `f_j` (fixed pseudo-random phases
//! φ_k, so runs stay deterministic). The model integrates every angle (shaft, cage,
//! elements, waviness) from this speed, and the imbalance follows its ω² and the
//! tangential α term.

use crate::error::{check_range, ConfigError};
use crate::real::{sin, Real, TAU};

/// Components of the random-phase multisine.
pub const JITTER_LINES: usize = 8;
/// Fixed phases of the multisine (rad), from a golden-ratio sequence.
const PHASES: [Real; JITTER_LINES] = [0.0, 3.883, 1.483, 5.366, 2.966, 0.566, 4.449, 2.049];

/// Parameters of the `speed-fluctuation` effect.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Params {
    /// Relative amplitude `a` of the sinusoidal modulation (–), in [0, 0.1].
    pub amplitude: Real,
    /// Its frequency `f_m` (Hz), in [0.01, 1000].
    pub freq_hz: Real,
    /// Relative RMS `j` of the random part (–), in [0, 0.1].
    pub jitter: Real,
    /// Highest frequency `f_j` of the random part (Hz), in [0.1, 1000].
    pub jitter_hz: Real,
}

impl Params {
    /// Validates the four parameters (see the fields).
    pub fn new_checked(p: Params) -> Result<Self, ConfigError> {
        check_range("speed-fluctuation.amplitude", p.amplitude, 0.0, 0.1)?;
        check_range("speed-fluctuation.freq_hz", p.freq_hz, 0.01, 1000.0)?;
        check_range("speed-fluctuation.jitter", p.jitter, 0.0, 0.1)?;
        check_range("speed-fluctuation.jitter_hz", p.jitter_hz, 0.1, 1000.0)?;
        Ok(p)
    }

    /// Speed factor at time `t` (s).
    #[inline]
    pub fn factor(&self, t: Real) -> Real {
        let mut f = 1.0 + self.amplitude * sin(crate::real::wrap_angle(TAU * self.freq_hz * t));
        if self.jitter > 0.0 {
            let a = self.jitter * 0.5; // √(2/8)
            for (k, ph) in PHASES.iter().enumerate() {
                let fk = self.jitter_hz * (k as Real + 1.0) / JITTER_LINES as Real;
                f += a * sin(crate::real::wrap_angle(TAU * fk * t + ph));
            }
        }
        f
    }

    /// Largest factor the modulation can reach.
    pub fn max_factor(&self) -> Real {
        1.0 + self.amplitude + self.jitter * 0.5 * JITTER_LINES as Real
    }
}
