//! One defect term, shared by race and ball defects: the contribution of one defect at
//! normalised position `ξ` along it to the element it acts on, for each formulation
//! ([`DefectModel`]; thesis §4.1.3 and publications III–IV, see
//! [`crate::forces::defect`]). Race defects evaluate it for the element passing over the
//! defect, ball defects for the defective element against both races; only `ξ` and the
//! rolling speed differ between them.

use crate::forces::defect::{DefectModel, DefectShape};
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
