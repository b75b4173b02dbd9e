//! Hertz contact between a rolling element and the races: load–deflection law
//! `Q = K δ^p` (thesis eq. 4–10 after Harsha et al.; publication III §2.1) and contact
//! pressure.
//!
//! For point contact the stiffness constant comes from the Hamrock & Brewe (1983)
//! closed-form approximations of Hertz theory ("Simplified solution for stresses and
//! deformations", J. Lubr. Technol. 105): with curvature sums `1/R_x`, `1/R_y`,
//! `α_r = R_y/R_x`, `k = α_r^{2/π}`, `ℰ = 1 + (π/2 − 1)/α_r`, `ℱ = π/2 + (π/2 − 1) ln α_r`,
//! `δ = ℱ [9/(2ℰR) (Q/(πkE'))²]^{1/3}`, hence `K = πkE'√(2ℰR/(9ℱ³))`,
//! `a = (6k²ℰQR/(πE'))^{1/3}`, `b = (6ℰQR/(πkE'))^{1/3}`, `p_max = 3Q/(2πab)`.
//! For line contact, Palmgren's `δ = 3.84·10⁻⁵ Q^{0.9}/l^{0.8}` (mm, N) gives `p = 10/9`.

use crate::bearing::{BearingGeometry, ContactKind};
use crate::real::{cbrt, ln, pow, sqrt, Real, PI};

/// Hertz constants of one race contact (point contact) or of the whole element (line).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct HertzContact {
    /// Load–deflection constant `K` (N/m^p).
    pub stiffness: Real,
    /// Exponent `p` (3/2 point, 10/9 line).
    pub exponent: Real,
    /// Effective radius `R = (1/R_x + 1/R_y)⁻¹` (m), point contact only.
    pub radius: Real,
    /// Ellipticity `k = a/b` (–), point contact only.
    pub ellipticity: Real,
    /// Approximate elliptic integral of the second kind `ℰ` (–).
    pub e2: Real,
    /// Effective modulus `E'` (Pa).
    pub modulus: Real,
    /// Contact length `l` (m) for line contact; 0 for point contact.
    pub length: Real,
}

impl HertzContact {
    /// Point contact from the two curvature radii (m; negative for a concave surface is
    /// already folded into the sums): `rx`, `ry` are the effective radii in rolling and
    /// transverse direction, `e_eff` the effective modulus `E'` (Pa).
    pub fn point(rx: Real, ry: Real, e_eff: Real) -> Self {
        // Hamrock & Brewe use α_r = R_y/R_x ≥ 1; swap if needed.
        let (rx, ry) = if ry >= rx { (rx, ry) } else { (ry, rx) };
        let alpha = ry / rx;
        let r = 1.0 / (1.0 / rx + 1.0 / ry);
        let k = pow(alpha, 2.0 / PI);
        let e2 = 1.0 + (PI / 2.0 - 1.0) / alpha;
        let f1 = PI / 2.0 + (PI / 2.0 - 1.0) * ln(alpha);
        let stiffness = PI * k * e_eff * sqrt(2.0 * e2 * r / (9.0 * f1 * f1 * f1));
        HertzContact {
            stiffness,
            exponent: 1.5,
            radius: r,
            ellipticity: k,
            e2,
            modulus: e_eff,
            length: 0.0,
        }
    }

    /// Semi-axes `(a, b)` of the contact ellipse (m) under load `q` (N); `a` transverse.
    /// For line contact `a = l/2` and `b = √(8QR/(πlE'))` (Johnson 1985, §4.2).
    pub fn semi_axes(&self, q: Real) -> (Real, Real) {
        if q <= 0.0 {
            return (0.0, 0.0);
        }
        if self.length > 0.0 {
            return (
                0.5 * self.length,
                sqrt(8.0 * q * self.radius / (PI * self.length * self.modulus)),
            );
        }
        let k = self.ellipticity;
        let a = cbrt(6.0 * k * k * self.e2 * q * self.radius / (PI * self.modulus));
        let b = cbrt(6.0 * self.e2 * q * self.radius / (PI * k * self.modulus));
        (a, b)
    }

    /// Maximum Hertz pressure (Pa) under load `q` (N): `3Q/(2πab)` for point contact,
    /// `2Q/(πbl)` for line contact.
    pub fn max_pressure(&self, q: Real) -> Real {
        let (a, b) = self.semi_axes(q);
        if a <= 0.0 || b <= 0.0 {
            0.0
        } else if self.length > 0.0 {
            2.0 * q / (PI * b * self.length)
        } else {
            1.5 * q / (PI * a * b)
        }
    }
}

/// The contact of one rolling element with both races in series, as the model uses it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct ElementContact {
    /// Inner-race contact (point contact) or the per-race line contact.
    pub inner: HertzContact,
    /// Outer-race contact.
    pub outer: HertzContact,
    /// Combined constant `K` of both contacts in series (N/m^p):
    /// `K = (K_i^{−1/p} + K_o^{−1/p})^{−p}`.
    pub stiffness: Real,
    /// Contact kind (sets `p`).
    pub kind: ContactKind,
}

impl ElementContact {
    /// Hertz constants of `bearing` from its geometry and material.
    pub fn of(bearing: &BearingGeometry) -> Self {
        let e_eff = bearing.effective_modulus();
        match bearing.contact {
            ContactKind::Point => {
                let rb = 0.5 * bearing.element_diameter;
                let ro = bearing.outer_race_radius();
                let ri = bearing.inner_race_radius();
                // Rolling direction: ball (convex) against the concave outer track and the
                // convex inner track. Transverse: ball in a concave groove of radius f·B_d.
                let rx_o = 1.0 / (1.0 / rb - 1.0 / ro);
                let rx_i = 1.0 / (1.0 / rb + 1.0 / ri);
                let ry_o =
                    1.0 / (1.0 / rb - 1.0 / (bearing.outer_conformity * bearing.element_diameter));
                let ry_i =
                    1.0 / (1.0 / rb - 1.0 / (bearing.inner_conformity * bearing.element_diameter));
                let outer = HertzContact::point(rx_o, ry_o, e_eff);
                let inner = HertzContact::point(rx_i, ry_i, e_eff);
                let p = 1.5;
                let stiffness = series(inner.stiffness, outer.stiffness, p);
                ElementContact {
                    inner,
                    outer,
                    stiffness,
                    kind: ContactKind::Point,
                }
            }
            ContactKind::Line => {
                // Palmgren: δ[mm] = 3.84e-5 Q^0.9 / l^0.8  ⇒  Q = (δ l^0.8 / 3.84e-5)^(10/9)
                // with δ in mm, l in mm; converted to SI (N/m^(10/9)).
                let l_mm = bearing.roller_length * 1e3;
                let k_mm = pow(pow(l_mm, 0.8) / 3.84e-5, 10.0 / 9.0); // N/mm^(10/9)
                let k_si = k_mm * pow(1e3, 10.0 / 9.0);
                let rb = 0.5 * bearing.element_diameter;
                let race = |track: Real| HertzContact {
                    stiffness: k_si,
                    exponent: 10.0 / 9.0,
                    radius: 1.0 / (1.0 / rb + 1.0 / track),
                    ellipticity: 1.0,
                    e2: 1.0,
                    modulus: e_eff,
                    length: bearing.roller_length,
                };
                ElementContact {
                    inner: race(bearing.inner_race_radius()),
                    outer: race(-bearing.outer_race_radius()),
                    stiffness: series(k_si, k_si, 10.0 / 9.0),
                    kind: ContactKind::Line,
                }
            }
        }
    }

    /// Element load `Q = K δ^p` (N) for a total deflection `delta` (m); 0 when `δ ≤ 0`
    /// (the element is out of contact).
    #[inline(always)]
    pub fn load(&self, delta: Real) -> Real {
        match self.kind {
            ContactKind::Point => self.stiffness * crate::real::pow_3_2(delta),
            ContactKind::Line => self.stiffness * crate::real::pow_10_9(delta),
        }
    }

    /// Tangent stiffness `dQ/dδ = pKδ^{p−1}` (N/m) at deflection `delta`.
    pub fn tangent_stiffness(&self, delta: Real) -> Real {
        if delta <= 0.0 {
            return 0.0;
        }
        let p = self.kind.exponent();
        p * self.stiffness * pow(delta, p - 1.0)
    }

    /// Deflection (m) that carries load `q` (N): `δ = (Q/K)^{1/p}`.
    pub fn deflection(&self, q: Real) -> Real {
        if q <= 0.0 {
            return 0.0;
        }
        pow(q / self.stiffness, 1.0 / self.kind.exponent())
    }
}

/// Two contacts in series sharing one load: `δ = (Q/K₁)^{1/p} + (Q/K₂)^{1/p}`, so
/// `K = (K₁^{−1/p} + K₂^{−1/p})^{−p}`.
fn series(k1: Real, k2: Real, p: Real) -> Real {
    let s = pow(k1, -1.0 / p) + pow(k2, -1.0 / p);
    pow(s, -p)
}
