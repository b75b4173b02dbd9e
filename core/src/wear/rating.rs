//! Rating life of the bearing (ISO 281:2007) and the lubrication life factor, which set
//! the pace of rolling-contact fatigue in the steady state.

use crate::bearing::{BearingGeometry, ContactKind};
use crate::real::{cos, pow, Real};

/// ISO 281 Table 2 (radial ball bearings, single row deep groove): `f_c` against
/// `γ = D_w cos α / D_pw`.
const BALL_FC: [(Real, Real); 20] = [
    (0.01, 29.1),
    (0.02, 35.8),
    (0.03, 40.3),
    (0.04, 43.8),
    (0.05, 46.7),
    (0.06, 49.1),
    (0.07, 51.1),
    (0.08, 52.8),
    (0.09, 54.3),
    (0.10, 55.5),
    (0.12, 57.5),
    (0.14, 58.8),
    (0.16, 59.6),
    (0.18, 59.9),
    (0.20, 59.9),
    (0.22, 59.6),
    (0.24, 59.0),
    (0.26, 58.2),
    (0.28, 57.1),
    (0.30, 56.0),
];

/// ISO 281 Table 7 (radial roller bearings): `f_c` against `γ`.
const ROLLER_FC: [(Real, Real); 16] = [
    (0.01, 52.1),
    (0.02, 60.8),
    (0.03, 66.5),
    (0.04, 70.7),
    (0.05, 74.1),
    (0.06, 76.9),
    (0.07, 79.2),
    (0.08, 81.2),
    (0.09, 82.8),
    (0.10, 84.2),
    (0.12, 86.4),
    (0.14, 87.7),
    (0.16, 88.5),
    (0.18, 88.8),
    (0.20, 88.7),
    (0.30, 83.8),
];

/// Piecewise-linear interpolation in a table sorted by x, clamped at both ends.
pub fn interpolate(table: &[(Real, Real)], x: Real) -> Real {
    let (Some(first), Some(last)) = (table.first(), table.last()) else {
        return 0.0;
    };
    if x <= first.0 {
        return first.1;
    }
    if x >= last.0 {
        return last.1;
    }
    for w in table.windows(2) {
        if let [a, b] = w {
            if x <= b.0 {
                return a.1 + (b.1 - a.1) * (x - a.0) / (b.0 - a.0);
            }
        }
    }
    last.1
}

/// Basic dynamic radial load rating `C_r` (N) of one row, ISO 281:2007 eq. (2)/(7):
/// balls `C = b_m f_c (cos α)^{0.7} Z^{2/3} D_w^{1.8}` (b_m = 1.3, D_w in mm ≤ 25.4),
/// rollers `C = b_m f_c (L_we cos α)^{7/9} Z^{3/4} D_we^{29/27}` (b_m = 1.1).
/// For the SKF 6205 this gives 14.0 kN (catalogues: 14.0–14.8 kN).
pub fn dynamic_load_rating(b: &BearingGeometry) -> Real {
    let dw = b.element_diameter * 1e3;
    let ca = cos(b.contact_angle);
    let gamma = dw * ca / (b.pitch_diameter * 1e3);
    let z = b.elements as Real;
    match b.contact {
        ContactKind::Point => {
            1.3 * interpolate(&BALL_FC, gamma) * pow(ca, 0.7) * pow(z, 2.0 / 3.0) * pow(dw, 1.8)
        }
        ContactKind::Line => {
            let l = b.roller_length * 1e3;
            1.1 * interpolate(&ROLLER_FC, gamma)
                * pow(l * ca, 7.0 / 9.0)
                * pow(z, 0.75)
                * pow(dw, 29.0 / 27.0)
        }
    }
}

/// Lubrication life factor against the film parameter λ (film thickness over composite
/// roughness), read from the life-adjustment curve of Harris & Kotzalas (2006, vol. 2,
/// ch. 8) — below 1 surface distress shortens life, above 3 full separation lengthens it.
const LAMBDA_FACTOR: [(Real, Real); 8] = [
    (0.1, 0.1),
    (0.4, 0.15),
    (0.6, 0.25),
    (1.0, 0.6),
    (1.5, 1.2),
    (2.0, 1.8),
    (3.0, 2.6),
    (4.0, 3.0),
];

/// Life factor `a_λ` for film parameter `lambda` (–).
pub fn lubrication_factor(lambda: Real) -> Real {
    interpolate(&LAMBDA_FACTOR, lambda)
}

/// Stribeck's factor relating the most loaded element to the radial load:
/// `F_r = Z Q_max / k` with k = 4.37 (balls, zero clearance) or 4.08 (rollers)
/// (Harris & Kotzalas 2006, ch. 7).
pub fn stribeck_factor(kind: ContactKind) -> Real {
    match kind {
        ContactKind::Point => 4.37,
        ContactKind::Line => 4.08,
    }
}
