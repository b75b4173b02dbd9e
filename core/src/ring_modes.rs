//! Natural frequencies of the bearing ring: thesis eq. 21–23 (publication IV eq. 2–4).

use crate::real::{sqrt, Real, PI};

/// Flexural mode `n ≥ 2` of a thin ring, thesis eq. 21 (Sassi et al. 2007):
/// `ω_n = n(n²−1)/√(1+n²) · √(EI/(μR⁴))` in rad/s, with `E` Young's modulus (Pa), `I` the
/// second moment of the cross-section (m⁴), `μ` mass per unit length (kg/m), `R` the ring
/// radius (m). Modes 0 and 1 are rigid-body modes; `n < 2` returns 0.
pub fn flexural_mode_rad_s(n: u32, e: Real, i: Real, mu: Real, r: Real) -> Real {
    if n < 2 || mu <= 0.0 || r <= 0.0 {
        return 0.0;
    }
    let nf = n as Real;
    nf * (nf * nf - 1.0) / sqrt(1.0 + nf * nf) * sqrt(e * i / (mu * r * r * r * r))
}

/// Radial natural frequency of an outer ring after NSK (2013), thesis eq. 22, **in its
/// correct form**: `f_n = 9.41·10⁵ · K(D−d)/{D − K(D−d)}² · n(n²−1)/√(n²+1)` Hz with `d`
/// bore and `D` outside diameter in **mm** and `K` the cross-section constant (0.15 for the
/// outer ring of an open bearing). The thesis prints `√(n²−1)` in the denominator; the
/// mode-number factor must be the one of eq. 21, `n(n²−1)/√(n²+1)`, which is what NSK's
/// catalogue gives and what makes eq. 21 and 22 agree on mode ratios.
pub fn nsk_outer_ring_hz(n: u32, bore_mm: Real, outside_mm: Real, k: Real) -> Real {
    if n < 2 || outside_mm <= bore_mm || bore_mm < 0.0 {
        return 0.0;
    }
    let nf = n as Real;
    let w = k * (outside_mm - bore_mm);
    let dm = outside_mm - w;
    9.41e5 * w / (dm * dm) * nf * (nf * nf - 1.0) / sqrt(nf * nf + 1.0)
}

/// Ring frequency after Irvine (2014), thesis eq. 23: `f = c/(πD)` in **Hz** (the thesis
/// labels it ω in rad/s, which is a unit slip), with `c` the longitudinal speed of sound in
/// the ring material (m/s; ≈ 5900 for bearing steel) and `D` the ring diameter (m).
pub fn ring_frequency_hz(speed_of_sound: Real, diameter: Real) -> Real {
    if diameter <= 0.0 {
        return 0.0;
    }
    speed_of_sound / (PI * diameter)
}
