//! Rating life of the bearing (ISO 281:2007) and the lubrication life factor, which set
//! the pace of rolling-contact fatigue in the steady state; the ratings of its two ring
//! contacts ([`RingRatings`], Lundberg–Palmgren via ISO/TS 16281), reported per wear site.

use super::site::Site;
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

/// Basic dynamic load ratings of the two raceway contacts of a single-row radial bearing
/// (Lundberg & Palmgren 1947/1952): the element load `Q_ci` (inner ring) and `Q_ce` (outer
/// ring) for which that ring alone has a basic rating life of 10⁶ revolutions. Derived
/// from the bearing's rating `C` as ISO/TS 16281:2008 does (eq. 19–24 for balls, 47–57 for
/// rollers), so that the rings' lives, combined by the Weibull sum
/// `L^{−e} = L_i^{−e} + L_e^{−e}` (e = 10/9 point, 9/8 line contact; ISO/TR 1281-1,
/// Harris & Kotzalas 2007, *Advanced Concepts of Bearing Technology* ch. 8), give back the
/// bearing's life. Balls, with `γ = D_w cos α / D_pw`, `f = r/D_w` the groove conformities:
///
/// `Q_ci = C/(0.407 Z cos^{0.7}α) [1 + X^{10/3}]^{0.3}`,
/// `Q_ce = C/(0.389 Z cos^{0.7}α) [1 + X^{−10/3}]^{0.3}`,
/// `X = 1.044 ((1 − γ)/(1 + γ))^{1.72} (f_i (2f_e − 1)/(f_e (2f_i − 1)))^{0.41}`,
///
/// so `Q_ci/Q_ce = (0.389/0.407) X`. Rollers (whole rollers, no laminae):
/// `Q_ci = C/(0.83·0.378 Z cos α) [1 + X^{9/2}]^{2/9}`, `Q_ce = C/(0.83·0.364 Z cos α)
/// [1 + X^{−9/2}]^{2/9}`, `X = 1.038 ((1 − γ)/(1 + γ))^{143/108}`; the 1/λν = 1/0.83
/// removes ISO 281's edge-stress reduction, which TS 16281 puts back through its laminae,
/// so whole-roller lives from these ratings are about (1/0.83)⁴ ≈ 2.1 × ISO 281's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RingRatings {
    /// `Q_ci` (N): inner-ring contact.
    pub inner: Real,
    /// `Q_ce` (N): outer-ring contact.
    pub outer: Real,
    /// Load–life exponent of one ring (–): 3 balls, 4 rollers.
    pub ring_exponent: Real,
    /// Equivalent-load exponent of the stationary ring (–): 10/3 balls, 4.5 rollers (the
    /// rotating ring's is `ring_exponent`; ISO/TS 16281 eq. 25–28).
    pub stationary_exponent: Real,
    /// Weibull slope `e` of the combination (–): 10/9 balls, 9/8 rollers.
    pub weibull: Real,
}

impl RingRatings {
    /// The ring ratings of bearing `b` whose basic dynamic rating is `c` (N).
    pub fn of(b: &BearingGeometry, c: Real) -> Self {
        let ca = cos(b.contact_angle);
        let g = b.element_diameter * ca / b.pitch_diameter;
        let z = b.elements as Real;
        let q = (1.0 - g) / (1.0 + g);
        match b.contact {
            ContactKind::Point => {
                let (fi, fe) = (b.inner_conformity, b.outer_conformity);
                let x = 1.044
                    * pow(q, 1.72)
                    * pow(fi * (2.0 * fe - 1.0) / (fe * (2.0 * fi - 1.0)), 0.41);
                let base = c / (z * pow(ca, 0.7));
                RingRatings {
                    inner: base / 0.407 * pow(1.0 + pow(x, 10.0 / 3.0), 0.3),
                    outer: base / 0.389 * pow(1.0 + pow(x, -10.0 / 3.0), 0.3),
                    ring_exponent: 3.0,
                    stationary_exponent: 10.0 / 3.0,
                    weibull: 10.0 / 9.0,
                }
            }
            ContactKind::Line => {
                let x = 1.038 * pow(q, 143.0 / 108.0);
                let base = c / (0.83 * z * ca);
                RingRatings {
                    inner: base / 0.378 * pow(1.0 + pow(x, 4.5), 2.0 / 9.0),
                    outer: base / 0.364 * pow(1.0 + pow(x, -4.5), 2.0 / 9.0),
                    ring_exponent: 4.0,
                    stationary_exponent: 4.5,
                    weibull: 9.0 / 8.0,
                }
            }
        }
    }

    /// Dynamic equivalent element loads `(Q_ei, Q_ee)` (N) of the rotating inner and the
    /// stationary outer ring from the element loads `loads` (N) at one instant, one per
    /// element: power means `(Σ Q_j^p / Z)^{1/p}` with `p` = [`RingRatings::ring_exponent`]
    /// for the rotating ring (every point of it passes every position) and
    /// [`RingRatings::stationary_exponent`] for the stationary one (ISO/TS 16281 eq. 25–28).
    /// Zeros for no loads.
    pub fn equivalent_loads(&self, loads: &[Real]) -> (Real, Real) {
        let n = loads.len() as Real;
        if n == 0.0 {
            return (0.0, 0.0);
        }
        let (pi, pe) = (self.ring_exponent, self.stationary_exponent);
        let (mut si, mut se) = (0.0, 0.0);
        for &q in loads {
            let q = q.max(0.0);
            si += pow(q, pi);
            se += pow(q, pe);
        }
        (pow(si / n, 1.0 / pi), pow(se / n, 1.0 / pe))
    }

    /// Basic rating lives (10⁶ revolutions) of the inner ring, the outer ring and the
    /// bearing for equivalent loads `q_ei`, `q_ee` (N): `L_i = (Q_ci/Q_ei)^p`,
    /// `L_e = (Q_ce/Q_ee)^p`, `L = (L_i^{−e} + L_e^{−e})^{−1/e}` (ISO/TS 16281 eq. 29/65).
    pub fn lives(&self, q_ei: Real, q_ee: Real) -> (Real, Real, Real) {
        let p = self.ring_exponent;
        let li = pow(self.inner / q_ei, p);
        let le = pow(self.outer / q_ee, p);
        let e = self.weibull;
        (li, le, pow(pow(li, -e) + pow(le, -e), -1.0 / e))
    }

    /// The ring rating of wear site `site` (N): `Q_ce` for the outer race, `Q_ci` for the
    /// inner race, none for a rolling element (Lundberg–Palmgren and ISO rate the rings
    /// only; element failures are inside the ring ratings' statistics).
    pub fn of_site(&self, site: Site) -> Option<Real> {
        match site {
            Site::OuterRace => Some(self.outer),
            Site::InnerRace => Some(self.inner),
            Site::Element => None,
        }
    }
}
