//! The largest contact preload a deep-groove ball bearing of a motor plausibly carries: an
//! axial spring preload (a wave spring on one outer ring), the preload source of the
//! bearing class. It bounds the `load-zone` effect's `preload`
//! ([`crate::effects::load_zone`]), whose contact stiffening otherwise lets that effect
//! stand in for a resonance shift (issue 13: "one mechanism per effect").
//!
//! * **Force.** SKF, *Rolling bearings* catalogue, "Preloading with springs": for
//!   deep-groove ball bearings in small electric motors the spring force is `F = k d`
//!   (F in kN, bore `d` in mm) with `k` between 0.005 and 0.01 depending on the motor
//!   design; `k = 0.02` only to protect a *stationary* bearing from external vibration.
//!   The bound takes the running motor's upper end, [`MOTOR_SPRING_FACTOR`].
//! * **Contact.** Under a pure thrust `F_a` the `Z` balls of a deep-groove bearing with
//!   diametral clearance `P_d` share the load equally at the contact angle `β` of
//!   `F_a = Z K (B D)^{3/2} sin β (cos β₀ / cos β − 1)^{3/2}`, with the total curvature
//!   `B = f_o + f_i − 1`, the free contact angle `cos β₀ = 1 − P_d/(2 B D)` and the normal
//!   approach `δ_n = B D (cos β₀ / cos β − 1)` (Harris & Kotzalas 2006, *Essential
//!   Concepts of Bearing Technology*, ch. 7, thrust-loaded ball bearings; `K` the
//!   combined Hertz constant of both contacts, [`ElementContact::stiffness`]).
//! * **In the radial plane** (the model's plane) the spring loads every ball by the same
//!   normal approach `δ_n`, which is what the effect's uniform preload `δ_p` is; the
//!   bound in the effect's unit is `δ_n / y₀`, `y₀` the static radial displacement
//!   without preload. The projection of the contact onto the radial plane (`cos β`, a
//!   few per cent at these angles) is neglected.
//!
//! Line contacts (roller bearings) are not spring-preloaded in this way: their bound is 0.

use crate::bearing::{BearingGeometry, ContactKind};
use crate::contact::ElementContact;
use crate::load_zone::equilibrium;
use crate::real::Real;

/// SKF's spring factor `k` for deep-groove ball bearings of running electric motors, the
/// upper end of its 0.005–0.01 range, as newtons per metre of bore (0.01 kN/mm = 10⁴ N/m).
pub const MOTOR_SPRING_FACTOR: f64 = 1.0e4;

/// The thrust-loaded contact of a ball bearing (Harris & Kotzalas 2006 ch. 7).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThrustContact {
    /// Loaded contact angle `β` (rad).
    pub angle: f64,
    /// Normal approach of each ball's two contacts `δ_n` (m).
    pub approach: f64,
    /// Normal load of each ball `Q = K δ_n^{3/2}` (N).
    pub element_load: f64,
}

/// The largest plausible spring preload of `bearing` (N): [`MOTOR_SPRING_FACTOR`] × bore.
pub fn spring_force(bearing: &BearingGeometry) -> f64 {
    MOTOR_SPRING_FACTOR * bearing.bore as f64
}

/// The contact of `bearing` (Hertz constants `contact`, radial clearance `clearance`, m)
/// under a pure thrust `thrust` (N), by bisection on the contact angle of the thrust
/// balance in the module documentation. `None` for line contacts, a non-positive or
/// non-finite thrust, or a groove geometry without curvature (`B ≤ 0`).
pub fn thrust_contact(
    bearing: &BearingGeometry,
    contact: &ElementContact,
    clearance: Real,
    thrust: f64,
) -> Option<ThrustContact> {
    if bearing.contact != ContactKind::Point || !(thrust > 0.0 && thrust.is_finite()) {
        return None;
    }
    let d = bearing.element_diameter as f64;
    let b = (bearing.outer_conformity + bearing.inner_conformity) as f64 - 1.0;
    let k = contact.stiffness as f64;
    let z = bearing.elements as f64;
    if !(b > 0.0 && d > 0.0 && k > 0.0 && z > 0.0) {
        return None;
    }
    let bd = b * d;
    let pd = 2.0 * (clearance as f64).max(0.0);
    let cos0 = (1.0 - pd / (2.0 * bd)).clamp(0.0, 1.0);
    let beta0 = libm::acos(cos0);
    let target = thrust / (z * k * libm::pow(bd, 1.5));
    let balance = |beta: f64| {
        let s = (cos0 / libm::cos(beta) - 1.0).max(0.0);
        libm::sin(beta) * s * libm::sqrt(s)
    };
    // `balance` rises from 0 at β₀ to infinity at 90°.
    let (mut lo, mut hi) = (beta0, 0.5 * core::f64::consts::PI - 1e-9);
    if balance(hi) < target {
        return None;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if balance(mid) < target {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo < 1e-15 {
            break;
        }
    }
    let angle = 0.5 * (lo + hi);
    let approach = bd * (cos0 / libm::cos(angle) - 1.0);
    Some(ThrustContact {
        angle,
        approach,
        element_load: k * approach * libm::sqrt(approach),
    })
}

/// The largest plausible `load-zone` preload of a bearing (–, static displacements `y₀`):
/// the normal approach under [`spring_force`] over the static radial displacement under
/// `radial_load` (N) with the structural stiffness `structure_k` (N/m) and the radial
/// clearance `clearance` (m). 0 when [`thrust_contact`] has no contact (line contacts, a
/// groove without curvature); `limit` when the bearing carries no radial load (`y₀ = 0`:
/// the effect's unit is undefined); at most `limit`.
pub fn plausible_preload(
    bearing: &BearingGeometry,
    contact: &ElementContact,
    clearance: Real,
    radial_load: Real,
    structure_k: Real,
    limit: f64,
) -> f64 {
    let Some(t) = thrust_contact(bearing, contact, clearance, spring_force(bearing)) else {
        return 0.0;
    };
    let y0 = equilibrium(
        contact,
        bearing.elements,
        radial_load,
        structure_k,
        clearance,
    )
    .y0 as f64;
    if y0.is_nan() || y0 <= 0.0 {
        return limit;
    }
    (t.approach / y0).max(0.0).min(limit)
}
