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
                    value: degrees(value),
                    min: degrees(min),
                    max: degrees(max),
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

/// `rad` in degrees to 12 significant digits: the file's degrees went to radians and back,
/// and a message echoed `angle_deg = 1e9` as `1000000000.0000001`.
fn degrees(rad: f64) -> f64 {
    let d = rad.to_degrees();
    if d == 0.0 || !d.is_finite() {
        return d;
    }
    // |d| is at most 1.8e310 / π, so the exponent stays far inside i32.
    let scale = 10f64.powi(11 - d.abs().log10().floor() as i32);
    let r = (d * scale).round() / scale;
    if r.is_finite() && scale.is_finite() && scale > 0.0 {
        r
    } else {
        d
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

#[cfg(test)]
mod tests {
    use super::degrees;

    #[test]
    fn degrees_come_back_as_written() {
        for d in [1e9, 95.3, -572.9577951308232, 45.0, 1e-300, 1e300] {
            let back = degrees(f64::to_radians(d));
            assert!((back - d).abs() <= 1e-11 * d.abs(), "{d} -> {back}");
        }
        assert_eq!(degrees(f64::to_radians(1e9)), 1e9);
        assert_eq!(degrees(0.0), 0.0);
        assert!(degrees(f64::INFINITY).is_infinite() && degrees(f64::NAN).is_nan());
    }
}
