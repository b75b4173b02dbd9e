//! Effect `sensor`: the measurement chain. A real accelerometer record has a noise floor
//! (sensor and conditioning electronics, white; a typical ICP accelerometer has a
//! broadband noise of a few mg, IEPE datasheets), a finite bandwidth (mounting and sensor
//! resonance, anti-alias filters; modelled as a one-pole low-pass with corner `f_c`) and
//! mains interference at the line frequency and its harmonics (ground loops; Randall
//! 2011 §2.3). Applied to the output samples after decimation:
//! `a_out = LP(a) + A_h [sin(2π f_h t) + r (sin(4π f_h t) + sin(6π f_h t))] + σ n`,
//! with `n` zero-mean unit-variance noise from a generator seeded from the run's seed
//! (independent of the model's own stream, so switching the sensor on leaves the
//! simulated vibration unchanged and only adds the measurement chain).

use super::spec::*;
use crate::error::{check_range, ConfigError};
use crate::real::{exp, sin, Real, TAU};
use crate::rng::Xoshiro128pp;

/// Parameters of the `sensor` effect.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Params {
    /// RMS of the white noise floor (m/s²), in [0, 100].
    pub noise: Real,
    /// Corner of the one-pole low-pass (Hz), in [0, 5·10⁵], at most fs/2; 0 = no low-pass.
    pub corner_hz: Real,
    /// Amplitude of the mains fundamental (m/s²), in [0, 100].
    pub hum: Real,
    /// Mains frequency (Hz), in [40, 70] (50 or 60 in practice).
    pub hum_hz: Real,
    /// Amplitude of the 2nd and 3rd mains harmonics relative to the fundamental (–),
    /// in [0, 1].
    pub hum_harmonics: Real,
}

impl EffectParams for Params {
    const SPEC: EffectSpec = EffectSpec {
        name: "sensor",
        summary: "measurement chain: white noise floor, one-pole bandwidth, mains hum with harmonics",
        params: &[
            param("noise", "sensor.noise", "m/s^2", 0.01, 0.0, 100.0, "RMS of the white noise floor"),
            param("corner_hz", "sensor.corner_hz", "Hz", 0.0, 0.0, 5.0e5, "one-pole low-pass corner (0 = none; at most fs/2)"),
            param("hum", "sensor.hum", "m/s^2", 0.0, 0.0, 100.0, "mains fundamental amplitude"),
            param("hum_hz", "sensor.hum_hz", "Hz", 50.0, 40.0, 70.0, "mains frequency"),
            param("hum_harmonics", "sensor.hum_harmonics", "-", 0.3, 0.0, 1.0, "2nd and 3rd harmonic amplitude relative to the fundamental"),
        ],
        signature: Signature {
            mechanism: Mechanism::Measurement,
            moves: moves(true, true, true, false),
        },
        // No bandwidth limit is fitted: the records' own anti-alias filter is not
        // distinguishable from the model's.
        fit: FitSpec {
            fitted: &[
                fit("noise", FitBound::Rms(0.003), FitBound::Rms(1.0), true),
                fit("hum", FitBound::Rms(0.001), FitBound::Rms(0.3), true),
            ],
            fixed: &[
                ("corner_hz", FitBound::Abs(0.0)),
                ("hum_hz", FitBound::Mains),
                ("hum_harmonics", FitBound::Abs(0.3)),
            ],
            needs_defect: false,
            note: "white noise floor and mains hum, scaled to the record's RMS",
        },
    };

    fn from_slice(v: &[Real]) -> Self {
        Params {
            noise: at(v, 0),
            corner_hz: at(v, 1),
            hum: at(v, 2),
            hum_hz: at(v, 3),
            hum_harmonics: at(v, 4),
        }
    }

    fn write(&self, out: &mut [Real]) {
        put(
            out,
            &[self.noise, self.corner_hz, self.hum, self.hum_hz, self.hum_harmonics],
        );
    }
}

impl Params {

    /// Checks the corner against the output rate `fs` (Hz): at most fs/2.
    pub fn check_rate(&self, fs: Real) -> Result<(), ConfigError> {
        check_range("sensor.corner_hz", self.corner_hz, 0.0, fs / 2.0)
    }
}

/// The measurement chain designed for one output rate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SensorChain {
    p: Params,
    /// Low-pass coefficient `1 − exp(−2π f_c/fs)` (1 = pass-through).
    k: Real,
    /// Mains phase step per output sample (rad).
    dphi: Real,
}

/// Memory of the chain.
#[derive(Debug, Clone, PartialEq)]
pub struct SensorState {
    rng: Xoshiro128pp,
    lp: Real,
    phase: Real,
}

impl SensorState {
    /// Generator words, low-pass memory and mains phase (checkpoints).
    pub fn raw(&self) -> ([u32; 4], Real, Real) {
        (self.rng.state_words(), self.lp, self.phase)
    }

    /// The memory from [`SensorState::raw`].
    pub fn from_raw(words: [u32; 4], lp: Real, phase: Real) -> Self {
        SensorState {
            rng: Xoshiro128pp::from_state_words(words),
            lp,
            phase,
        }
    }

    /// Fresh memory; the generator is derived from the run's `seed` but distinct from the
    /// model's stream.
    pub fn new(seed: u64) -> Self {
        SensorState {
            rng: Xoshiro128pp::from_u64(seed ^ 0x5EA5_0A11_D00D_F00D),
            lp: 0.0,
            phase: 0.0,
        }
    }
}

impl SensorChain {
    /// Designs the chain for output rate `fs` (Hz).
    pub fn design(p: &Params, fs: Real) -> Self {
        let k = if p.corner_hz > 0.0 {
            1.0 - exp(-TAU * p.corner_hz / fs)
        } else {
            1.0
        };
        SensorChain {
            p: *p,
            k,
            dphi: TAU * p.hum_hz / fs,
        }
    }

    /// Low-pass gain `|H(f)|` of the chain at `f` (Hz) and output rate `fs` (Hz).
    pub fn lowpass_gain(&self, f: Real, fs: Real) -> Real {
        let w = TAU * f / fs;
        let a = 1.0 - self.k;
        let re = 1.0 - a * crate::real::cos(w);
        let im = a * sin(w);
        self.k / crate::real::sqrt(re * re + im * im)
    }

    /// Applies the chain to one output sample (out of line: the baseline step only pays
    /// for the check).
    #[inline(never)]
    pub fn apply(&self, st: &mut SensorState, a: Real) -> Real {
        st.lp += self.k * (a - st.lp);
        let ph = st.phase;
        st.phase = crate::real::wrap_angle(ph + self.dphi);
        let mut out = st.lp;
        if self.p.hum > 0.0 {
            let h = self.p.hum_harmonics;
            out += self.p.hum
                * (sin(ph)
                    + h * (sin(crate::real::wrap_angle(2.0 * ph))
                        + sin(crate::real::wrap_angle(3.0 * ph))));
        }
        if self.p.noise > 0.0 {
            out += self.p.noise * st.rng.gauss_approx();
        }
        out
    }
}
