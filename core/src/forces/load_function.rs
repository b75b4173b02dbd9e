//! The five-step load function of a localized defect (thesis §4.1.3 and Fig. 3,
//! publication IV Fig. 5). The figure is not in the text; the text says the changes are
//! at the leading and trailing edge, the entry of the element produces the
//! fault-frequency content and the trailing-edge impact the natural-frequency content
//! (Epps 1991). This project defines the five steps on the element's normalised
//! position `ξ` along the defect (0 = leading edge, 1 = trailing edge):
//!
//! 1. **nominal** (`ξ < 0`): the element carries its Hertz load;
//! 2. **unloading** (`0 ≤ ξ < ξ_e`): the element descends into the defect; its load falls
//!    linearly to `(1 − u)` of nominal. `ξ_e = min(½, √(2 r_b s)/L)` is the length over
//!    which a ball of radius `r_b` drops by `s`;
//! 3. **traverse** (`ξ_e ≤ ξ < 1`): reduced load `(1 − u)`;
//! 4. **impact** (`1 ≤ ξ < 1 + Δξ_a`): the element climbs the trailing edge and rolls over
//!    its asperity of height `h`: the contact deflection grows by `h_eff sin(π(ξ−1)/Δξ_a)`
//!    (a half-sine overload through the Hertz law, so it grows with `h` and with the
//!    element load), `Δξ_a = (2b + √(2 r_b h))/L` the asperity-crossing length;
//! 5. **recovery** (`1 ≤ ξ < 1 + ξ_e`): the unloading fraction returns linearly to 0.
//!
//! `u = w_f · min(1, s/δ_ref)` with `s = min(depth, r_b − √(r_b² − L²/4))` the geometric
//! drop, `δ_ref` the static deflection of the most loaded element and `w_f = min(1, w/2a)`
//! the share of the contact ellipse width `2a` that the defect width `w` spans;
//! `h_eff = w_f·h`. Because the steps act through the element's Hertz contact, they carry
//! the stiffness change `K_F(t)` of §5.5 with them.

use crate::real::{sin, Real, PI};

/// Parameters of the five-step function for one topography and bearing.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LoadFunction {
    /// Maximum unloading fraction `u` ∈ [0, 1] (–).
    pub unload: Real,
    /// Normalised descent length `ξ_e` (–).
    pub entry: Real,
    /// Effective asperity height `h_eff` (m).
    pub asperity: Real,
    /// Normalised asperity-crossing length `Δξ_a` (–).
    pub impact: Real,
}

/// Value of the five-step function at one position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoadStep {
    /// Fraction of the nominal element load that is removed (–).
    pub unload: Real,
    /// Extra contact deflection from the trailing-edge asperity (m).
    pub extra_deflection: Real,
}

impl LoadFunction {
    /// Normalised length past the trailing edge over which the function is non-nominal.
    pub fn tail(&self) -> Real {
        if self.entry > self.impact {
            self.entry
        } else {
            self.impact
        }
    }

    /// Evaluates the five steps at normalised position `xi` (see module docs).
    #[inline]
    pub fn eval(&self, xi: Real) -> LoadStep {
        let mut unload = 0.0;
        let mut extra = 0.0;
        if xi >= 0.0 {
            if xi < self.entry {
                unload = self.unload * xi / self.entry;
            } else if xi < 1.0 {
                unload = self.unload;
            } else if xi < 1.0 + self.entry {
                unload = self.unload * (1.0 - (xi - 1.0) / self.entry);
            }
            if xi >= 1.0 && xi < 1.0 + self.impact && self.impact > 0.0 {
                extra = self.asperity * sin(PI * (xi - 1.0) / self.impact);
            }
        }
        LoadStep {
            unload,
            extra_deflection: extra,
        }
    }
}
