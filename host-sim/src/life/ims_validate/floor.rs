//! The measurement floor a sensor adds to the simulated bearing's vibration: from a
//! calibration life's end ratio, or from a measured level in the record's units.

use super::*;

/// The measurement floor (m/s²) that gives the simulated life `s` the end ratio
/// `target` of a calibration life. Noise independent of the vibration adds in power:
/// a window of bearing RMS `r` reads `√(r² + N²)`; the median over the first half is the
/// floored median `√(m² + N²)` (the map is monotonic), so
/// `N² = (r_end² − E² m²)/(E² − 1)`. 0 when the bearing alone ends below the target
/// (a floor can only lower the ratio). For a mean-|x| record the RMS ratio stands in for
/// the mean-|x| ratio (equal for Gaussian windows, `mean|x| = √(2/π) RMS`).
pub fn floor_for_end_ratio(s: &SimLife, target: f64) -> f64 {
    let c = s.curve(Feature::Rms);
    let Some(&end) = s.rms.last() else {
        return 0.0;
    };
    let ratio = c.rms.last().copied().unwrap_or(1.0);
    if target.is_nan() || target <= 1.0 || ratio <= target || ratio <= 0.0 {
        return 0.0;
    }
    let m = end / ratio;
    let e2 = target * target;
    ((end * end - e2 * m * m) / (e2 - 1.0)).max(0.0).sqrt()
}

/// How the simulated sensor reading gets its background.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FloorMode {
    /// The bearing's own vibration only (the model on main).
    None,
    /// A white floor calibrated on the calibration life's end ratio
    /// ([`floor_for_end_ratio`]) and carried to the held-out lives.
    Calibrated,
    /// Each life's own background from its measured steady level read in physical units
    /// ([`measured_floor`]): nothing fitted, but it rests on the unit of the record.
    Measured {
        /// Record units per m/s² (IMS does not state its unit: 1/9.80665 if g,
        /// 0.1/9.80665 if volts of the 100 mV/g PCB 353B33).
        units_per_ms2: f64,
    },
}

/// A life's measured steady level as an RMS in m/s², read with `units_per_ms2` record units
/// per m/s² (a mean-|x| record's level times √(π/2), the Gaussian ratio).
pub fn steady_rms(m: &MeasuredRecord, units_per_ms2: f64) -> f64 {
    m.steady / units_per_ms2
        * match m.record.feature {
            Feature::Rms => 1.0,
            Feature::MeanAbs => (std::f64::consts::PI / 2.0).sqrt(),
        }
}

/// The background (m/s² RMS) a life's sensor reads besides the bearing: the measured
/// steady level in m/s² (RMS; a mean-|x| record's level times √(π/2), the Gaussian ratio)
/// minus, in power, the simulated bearing's own steady RMS `bare`; 0 when the bearing alone
/// is already as loud.
pub fn measured_floor(m: &MeasuredRecord, bare: &SimLife, units_per_ms2: f64) -> f64 {
    let level = steady_rms(m, units_per_ms2);
    let c = bare.curve(Feature::Rms);
    let own = bare.rms.last().copied().unwrap_or(0.0) / c.rms.last().copied().unwrap_or(1.0);
    (level * level - own * own).max(0.0).sqrt()
}
