//! Surface waviness and roughness of the outer race, thesis eq. 4–10 (Harsha et al.):
//! element `i` sees the race surface displaced by `Π_i = Π_p sin(N_w θ_i) + r_i(t)`,
//! which enters its Hertz deflection `δ_i = y sin θ_i − (γ + Π_i)`.
//!
//! * Waviness: `N_w = 2π R_o / λ` waves around the outer track, rounded to an integer
//!   (a closed race holds a whole number of waves). The thesis's "order about 80" is for a
//!   10 mm example; here it is computed from the real track radius.
//! * Roughness: the wavelength λ_r = 20 µm is shorter than one internal step of travel,
//!   so roughness is modelled as band-limited random height per element with RMS `σ` and
//!   correlation length λ_r: per step its variance is `σ² min(1, τ_c/h)` with
//!   `τ_c = λ_r/v`, which keeps its power spectral density independent of the step `h`.
//!   Debris (topography `debris` ∈ [0, 1]) multiplies σ by `1 + debris_gain·debris`.

use crate::error::{check_range, ConfigError};
use crate::real::{Real, TAU};

/// Outer-race waviness.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Waviness {
    /// Wave amplitude `Π_p` (m).
    pub amplitude: Real,
    /// Wavelength λ along the track (m); the thesis uses 0.8 mm.
    pub wavelength: Real,
}

impl Waviness {
    /// Validates amplitude in [0, 20 µm] and wavelength in [10 µm, 1 m].
    pub fn new_checked(w: Waviness) -> Result<Self, ConfigError> {
        check_range("waviness.amplitude", w.amplitude, 0.0, 20e-6)?;
        check_range("waviness.wavelength", w.wavelength, 10e-6, 1.0)?;
        Ok(w)
    }

    /// Number of waves around a track of radius `race_radius` (m): `round(2πR/λ)`, ≥ 1.
    pub fn order(&self, race_radius: Real) -> u32 {
        let n = crate::real::floor(TAU * race_radius / self.wavelength + 0.5);
        if n < 1.0 {
            1
        } else if n > 1.0e6 {
            1_000_000
        } else {
            n as u32
        }
    }
}

/// Surface roughness (random, per element).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Roughness {
    /// RMS height σ (m) of the composite surface.
    pub rms: Real,
    /// Correlation length λ_r (m); the thesis uses 0.02 mm.
    pub wavelength: Real,
    /// Multiplier of σ per unit debris level (–).
    pub debris_gain: Real,
}

impl Roughness {
    /// Validates σ in [0, 5 µm], λ_r in [0.1 µm, 10 mm], gain in [0, 100].
    pub fn new_checked(r: Roughness) -> Result<Self, ConfigError> {
        check_range("roughness.rms", r.rms, 0.0, 5e-6)?;
        check_range("roughness.wavelength", r.wavelength, 1e-7, 1e-2)?;
        check_range("roughness.debris_gain", r.debris_gain, 0.0, 100.0)?;
        Ok(r)
    }

    /// Per-step standard deviation of the roughness height (m) at internal step `h` (s),
    /// rolling speed `v` (m/s) and debris level `debris`.
    pub fn step_sigma(&self, h: Real, v: Real, debris: Real) -> Real {
        self.sigma_from_root(debris, crate::real::sqrt(self.step_ratio(h, v)))
    }

    /// The correlation ratio under [`Roughness::step_sigma`]'s square root: `τ/h` with
    /// `τ = λ/v` the time to roll one wavelength, at most 1.
    pub fn step_ratio(&self, h: Real, v: Real) -> Real {
        let tau = if v > 0.0 { self.wavelength / v } else { h };
        if tau >= h {
            1.0
        } else {
            tau / h
        }
    }

    /// [`Roughness::step_sigma`] from the square root `root` of its [`Roughness::step_ratio`].
    pub fn sigma_from_root(&self, debris: Real, root: Real) -> Real {
        self.rms * (1.0 + self.debris_gain * debris) * root
    }
}
