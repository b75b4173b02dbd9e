//! The core's range errors in the scenario file's terms: [`ConfigFileError`] from
//! `wearsim_core::ConfigError`, with the field renamed to the file's key (and converted to
//! degrees where the file gives degrees).

use super::ConfigFileError;

impl From<wearsim_core::ConfigError> for ConfigFileError {
    /// A core error in the file's terms (the key from `file_field`).
    fn from(e: wearsim_core::ConfigError) -> Self {
        use wearsim_core::ConfigError as E;
        ConfigFileError::Core(match e {
            E::OutOfRange {
                field,
                value,
                min,
                max,
            } => match file_field(field) {
                (key, true) => E::OutOfRange {
                    field: key,
                    value: value.to_degrees(),
                    min: min.to_degrees(),
                    max: max.to_degrees(),
                },
                (key, false) => E::OutOfRange {
                    field: key,
                    value,
                    min,
                    max,
                },
            },
            E::TooMany { field, count, max } => E::TooMany {
                field: file_field(field).0,
                count,
                max,
            },
            E::Inconsistent { field, reason } => E::Inconsistent {
                field: file_field(field).0,
                reason,
            },
            other => other,
        })
    }
}

/// The scenario-file key of a field the core names in its own terms, and whether the core
/// checks it in radians where the file gives degrees: the core's `bearing.contact_angle`
/// and `defect.angle` (radians) are the file's `bearing.contact_angle_deg` and
/// `defect.angle_deg`, its ramp `speed.duration` is `speed.ramp_duration`, and its
/// `topography.*` are the `[defect]` keys. Other fields are the file's keys already.
fn file_field(core: &'static str) -> (&'static str, bool) {
    match core {
        "bearing.contact_angle" => ("bearing.contact_angle_deg", true),
        "defect.angle" => ("defect.angle_deg", true),
        "speed.duration" => ("speed.ramp_duration", false),
        "topography.asperity_height" => ("defect.asperity_height", false),
        "topography.length" => ("defect.length", false),
        "topography.width" => ("defect.width", false),
        "topography.depth" => ("defect.depth", false),
        "topography.count" => ("defect.count", false),
        "topography.debris" => ("defect.debris", false),
        other => (other, false),
    }
}
