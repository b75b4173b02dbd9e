//! Fixed-point scaling of acceleration into sensor counts, as a digital accelerometer
//! reports them: a signed Q1.15 fraction of the full-scale range (`fixed::types::I1F15`),
//! i.e. 16-bit two's complement counts, saturating at ± full scale, with the resolution
//! reduced to `bits` significant bits (left-justified, as MEMS sensors with 12- or 14-bit
//! converters present them in 16-bit registers).

use crate::error::{check_range, ConfigError};
use crate::real::{Real, STANDARD_GRAVITY};
use fixed::types::I1F15;

/// Full-scale range and resolution of a virtual accelerometer.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SensorScale {
    /// Full-scale range (g): the counts saturate at ± this acceleration.
    pub full_scale_g: Real,
    /// Significant bits of the converter (8..=16).
    pub bits: u8,
}

impl SensorScale {
    /// Validates full scale in [0.1, 1000] g and bits in 8..=16.
    pub fn new_checked(s: SensorScale) -> Result<Self, ConfigError> {
        check_range("sensor.full_scale_g", s.full_scale_g, 0.1, 1000.0)?;
        check_range("sensor.bits", s.bits as Real, 8.0, 16.0)?;
        Ok(s)
    }

    /// Sensitivity (g per count, 16-bit register LSB).
    pub fn g_per_count(&self) -> Real {
        self.full_scale_g / 32768.0
    }

    /// Counts for acceleration `accel` (m/s²), saturating; NaN maps to 0.
    pub fn counts(&self, accel: Real) -> i16 {
        let frac = accel / (STANDARD_GRAVITY * self.full_scale_g);
        // `checked_from_num` rather than `saturating_from_num`: the latter holds a panic for
        // NaN that the optimiser cannot see past the guard (`firmware-stub/nopanic`); out of
        // range saturates by sign, NaN (neither sign) gives 0 — the same values.
        let q = I1F15::checked_from_num(frac).unwrap_or(if frac > 0.0 {
            I1F15::MAX
        } else if frac < 0.0 {
            I1F15::MIN
        } else {
            I1F15::ZERO
        });
        let shift = 16u32.saturating_sub(self.bits as u32);
        let mask: i16 = !((1i16 << shift) - 1);
        q.to_bits() & mask
    }

    /// Acceleration (m/s²) that `counts` stand for.
    pub fn accel(&self, counts: i16) -> Real {
        I1F15::from_bits(counts).to_num::<Real>() * STANDARD_GRAVITY * self.full_scale_g
    }
}
