//! Which models can share a lane group: the step, the element geometry and the order of
//! the random draws must be equal in every lane; the speed (its profile and fluctuation)
//! may differ — lanes with their own speed take their own kinematics
//! ([`same_kinematics`] decides which stepping a group uses) — and so may the rest.

use super::super::Model;
use crate::error::ConfigError;
use crate::integrate::IntegratorKind;

/// Why a set of models cannot be stepped as one [`super::LaneGroup`]; the caller falls
/// back to the scalar step.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum LaneError {
    /// No lanes (`K = 0`).
    Empty,
    /// Lane `lane` differs from lane 0 in `field`, which all lanes must share.
    Differs {
        /// Configuration field (or derived quantity) that differs.
        field: &'static str,
        /// First lane that differs from lane 0.
        lane: usize,
    },
    /// A configuration the lane stepper does not implement.
    Unsupported {
        /// Configuration field.
        field: &'static str,
        /// What is not supported, in words.
        reason: &'static str,
    },
    /// A lane's initial state was refused (element capacity, defect topography).
    Config(ConfigError),
}

impl core::fmt::Display for LaneError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            LaneError::Empty => write!(f, "lanes: a lane group needs at least one model"),
            LaneError::Differs { field, lane } => write!(
                f,
                "lanes: {field} of lane {lane} differs from lane 0; lanes must share it"
            ),
            LaneError::Unsupported { field, reason } => write!(f, "lanes: {field}: {reason}"),
            LaneError::Config(e) => write!(f, "lanes: {e}"),
        }
    }
}

/// Checks that `models` can share a lane group.
pub(super) fn compatible(models: &[Model]) -> Result<(), LaneError> {
    let Some(m0) = models.first() else {
        return Err(LaneError::Empty);
    };
    for (lane, m) in models.iter().enumerate() {
        shareable(m0, m, lane)?;
    }
    Ok(())
}

/// Checks that `m` can run as lane `lane` of a group whose lane 0 runs `m0` (for a
/// caller that groups models before building a [`super::LaneGroup`]); `Ok` means
/// [`super::LaneGroup::new_checked`] accepts the two together.
pub fn shareable(m0: &Model, m: &Model, lane: usize) -> Result<(), LaneError> {
    if m0.cfg.integrator == IntegratorKind::Rk4 {
        return Err(LaneError::Unsupported {
            field: "integrator",
            reason: "RK4 is not laned (exact-zoh and exact-foh are)",
        });
    }
    let a = &m0.cfg;
    let b = &m.cfg;
    let loc = |m: &Model| m.cfg.defect.map(|d| d.location);
    let fields: [(&'static str, bool); 13] = [
        ("bearing", a.bearing == b.bearing),
        ("integrator", a.integrator == b.integrator),
        ("output_rate", a.output_rate == b.output_rate),
        ("oversample", m0.ratio == m.ratio),
        ("step (h)", m0.h == m.h),
        ("channels", a.channels == b.channels),
        ("defect.location", loc(m0) == loc(m)),
        ("waviness.order", m0.wave_order == m.wave_order),
        (
            "roughness (on/off)",
            a.roughness.is_some() == b.roughness.is_some(),
        ),
        (
            "contact limit (preload: sin_skip)",
            m0.sin_skip == m.sin_skip,
        ),
        ("contact kind", m0.contact.kind == m.contact.kind),
        (
            "defect.location (phasor)",
            m0.defect_offset_cs == m.defect_offset_cs,
        ),
        (
            "defect.location (spin)",
            m0.spin_order == m.spin_order && m0.slip_spin == m.slip_spin,
        ),
    ];
    match fields.iter().find(|(_, same)| !same) {
        Some((field, _)) => Err(LaneError::Differs { field, lane }),
        None => Ok(()),
    }
}

/// Whether `m` moves its shaft, cage and elements exactly as `m0` does (the same speed
/// profile, fluctuation and per-step rotations): a group whose lanes all do computes the
/// kinematics once for all lanes; otherwise every lane computes its own.
pub fn same_kinematics(m0: &Model, m: &Model) -> bool {
    m0.cfg.speed == m.cfg.speed
        && m0.cfg.effects.speed_fluctuation == m.cfg.effects.speed_fluctuation
        && m0.rot == m.rot
}
