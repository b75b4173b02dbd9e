//! One defect term, shared by race and ball defects: the contribution of one defect at
//! normalised position `ξ` along it to the element it acts on, for each formulation
//! ([`DefectModel`]; thesis §4.1.3 and publications III–IV, see
//! [`crate::forces::defect`]). Race defects evaluate it for the element passing over the
//! defect, ball defects for the defective element against both races; only `ξ` and the
//! rolling speed differ between them.

use crate::forces::defect::{DefectConfig, DefectLocation, DefectModel, DefectShape};
use crate::forces::Kinematics;
use crate::real::{angle_diff, Real, PI};

/// Adds defect `model`'s term at normalised position `xi` to `terms` = `(unload, extra
/// deflection (m), additive force (N))`. Nothing outside `0 ≤ ξ < 1 + tail`. `theta` is
/// the element's angle (rad; the Sassi force's direction), `speed` the rolling speed over
/// the defect (m/s; only the impulse formulation evaluates it).
#[inline(always)]
pub(super) fn add_term(
    model: DefectModel,
    shape: &DefectShape,
    xi: Real,
    tail: Real,
    theta: Real,
    speed: impl FnOnce() -> Real,
    terms: &mut (Real, Real, Real),
) {
    if xi < 0.0 || xi >= 1.0 + tail {
        return;
    }
    let (unload, dd, add) = terms;
    match model {
        DefectModel::FiveStep => {
            let ls = shape.load.eval(xi);
            *unload += ls.unload;
            *dd += ls.extra_deflection;
        }
        DefectModel::Deflection => *dd -= shape.geometric_drop(xi),
        DefectModel::Sassi => *add += shape.sassi(xi, angle_diff(theta, PI / 2.0)),
        DefectModel::Impulse => *add += shape.impulse(xi, speed()),
    }
}

/// Terms `(unload, extra deflection (m), additive force (N))` of race defect `d` (its
/// `shape`, tail `tail`) on the element at angle `theta` (rad) for kinematics `k`: every
/// one of the shape's defects evaluated at the element's position over it. An inner-race
/// defect turns with the shaft and is rolled over at the speed relative to the inner
/// race; an outer-race one is fixed and rolled over at the cage's speed. Shared by the
/// scalar step and the lanes, so both evaluate the same arithmetic.
#[inline(always)]
pub(super) fn race_terms(
    d: DefectConfig,
    shape: &DefectShape,
    tail: Real,
    k: &Kinematics,
    theta: Real,
) -> (Real, Real, Real) {
    let base = match d.location {
        DefectLocation::InnerRace { angle } => k.shaft_angle + angle,
        DefectLocation::OuterRace { angle } => angle,
        DefectLocation::Ball { .. } => 0.0,
    };
    let inner = matches!(d.location, DefectLocation::InnerRace { .. });
    let speed = || {
        let w_rel = if inner {
            k.shaft_omega - k.cage_omega
        } else {
            k.cage_omega
        };
        w_rel * shape.race_radius
    };
    let mut terms = (0.0, 0.0, 0.0);
    for kd in 0..shape.count {
        let centre = base + kd as Real * shape.spacing_angle;
        let mut psi = angle_diff(theta, centre);
        if inner {
            psi = -psi;
        }
        let xi = psi / shape.length_angle + 0.5;
        add_term(d.model, shape, xi, tail, theta, speed, &mut terms);
    }
    terms
}
