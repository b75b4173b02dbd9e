//! Effect `speed-fluctuation`: the shaft speed is never quite constant. Motor slip
//! varying with load, belt/coupling eccentricity and the control loop modulate it
//! periodically; load torque ripple adds a random part. Either smears the fault lines
//! (their frequency is proportional to speed) and puts sidebands at ± the modulation
//! frequency around every order line (Randall 2011, *Vibration-based Condition
//! Monitoring* §3.6 on order tracking; Borghesani et al. 2013, MSSP 38, "Application of
//! cepstrum pre-whitening for the diagnosis of bearing faults under variable speed").
//!
//! The speed profile is multiplied by
//! `1 + a sin(2π f_m t) + j Σ_{k=1}^{8} √(2/8) sin(2π (k/8) f_j t + φ_k)`:
//! a sinusoidal part (relative amplitude `a`, frequency `f_m`) and a random-phase
//! multisine of relative RMS `j` spread uniformly up to `f_j` (fixed pseudo-random phases
//! φ_k, so runs stay deterministic). The model integrates every angle (shaft, cage,
//! elements, waviness) from this speed, and the imbalance follows its ω² and the
//! tangential α term.

use super::spec::*;
use crate::real::{cos, sin, Real, TAU};

/// Components of the random-phase multisine.
pub const JITTER_LINES: usize = 8;
/// `(cos φ_k, sin φ_k)` of the multisine's fixed phases φ_k = 0, 3.883, 1.483, 5.366,
/// 2.966, 0.566, 4.449, 2.049 rad (a golden-ratio sequence; the test below checks the
/// values). The lines are summed as `sin(kθ) cos φ_k + cos(kθ) sin φ_k`, with `sin kθ`,
/// `cos kθ` from the angle-addition recurrence on one `sin`/`cos` pair: two library calls
/// per evaluation instead of eight (a fluctuating speed is evaluated every step).
#[allow(clippy::excessive_precision)] // f64 digits; the f32 build rounds them
const PHASE_CS: [(Real, Real); JITTER_LINES] = [
    (1.0, 0.0),
    (-0.7375188710568421, -0.6753265246049803),
    (0.08768357839015435, 0.9961483775425716),
    (0.6080571280521836, -0.7938932730694539),
    (-0.9846231801613953, 0.1746917087009583),
    (0.8440527624023131, 0.5362601367629563),
    (-0.2603541459950443, -0.9655131892745905),
    (-0.46018509861964674, 0.8878229975667594),
];

/// Parameters of the `speed-fluctuation` effect.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Params {
    /// Relative amplitude `a` of the sinusoidal modulation (–), in [0, 0.1].
    pub amplitude: Real,
    /// Its frequency `f_m` (Hz), in [0.01, 1000].
    pub freq_hz: Real,
    /// Relative RMS `j` of the random part (–), in [0, 0.1].
    pub jitter: Real,
    /// Highest frequency `f_j` of the random part (Hz), in [0.1, 1000].
    pub jitter_hz: Real,
}

impl EffectParams for Params {
    const SPEC: EffectSpec = EffectSpec {
        name: "speed-fluctuation",
        summary: "sinusoidal and random modulation of the shaft speed (all angles follow it)",
        params: &[
            param("amplitude", "speed-fluctuation.amplitude", "-", 0.01, 0.0, 0.1, "relative amplitude of the sinusoidal modulation"),
            param("freq_hz", "speed-fluctuation.freq_hz", "Hz", 1.0, 0.01, 1000.0, "frequency of the sinusoidal modulation"),
            param("jitter", "speed-fluctuation.jitter", "-", 0.0, 0.0, 0.1, "relative RMS of the random (multisine) modulation"),
            param("jitter_hz", "speed-fluctuation.jitter_hz", "Hz", 5.0, 0.1, 1000.0, "highest frequency of the random modulation"),
        ],
        signature: Signature {
            mechanism: Mechanism::Speed,
            moves: moves(false, true, false, true),
        },
        // The sinusoidal part is off: slower modulation moves the whole spectrum between
        // segments without changing any segment's cells, so the mean-based gap cannot see it.
        fit: FitSpec {
            fitted: &[fit("jitter", FitBound::Abs(5e-4), FitBound::Abs(0.1), true)],
            fixed: &[("amplitude", FitBound::Abs(0.0)), ("jitter_hz", FitBound::Abs(20.0))],
            needs_defect: false,
            note: "random speed modulation up to 20 Hz (drive torque ripple)",
        },
    };

    fn from_slice(v: &[Real]) -> Self {
        Params {
            amplitude: at(v, 0),
            freq_hz: at(v, 1),
            jitter: at(v, 2),
            jitter_hz: at(v, 3),
        }
    }

    fn write(&self, out: &mut [Real]) {
        put(out, &[self.amplitude, self.freq_hz, self.jitter, self.jitter_hz]);
    }
}

impl Params {

    /// Speed factor at time `t` (s).
    #[inline]
    pub fn factor(&self, t: Real) -> Real {
        let mut f = 1.0;
        if self.amplitude != 0.0 {
            f += self.amplitude * sin(crate::real::wrap_angle(TAU * self.freq_hz * t));
        }
        if self.jitter > 0.0 {
            let a = self.jitter * 0.5; // √(2/8)
            let th = crate::real::wrap_angle(TAU * (self.jitter_hz / JITTER_LINES as Real) * t);
            let (s1, c1) = (sin(th), cos(th));
            let (mut s, mut c) = (s1, c1);
            for (cp, sp) in PHASE_CS.iter() {
                f += a * (s * cp + c * sp);
                (s, c) = (s * c1 + c * s1, c * c1 - s * s1);
            }
        }
        f
    }

    /// Largest rate of change of the factor `|d factor/dt|` (1/s): the sum of each
    /// component's amplitude times its angular frequency.
    pub fn max_rate(&self) -> Real {
        let mut r = self.amplitude * TAU * self.freq_hz;
        if self.jitter > 0.0 {
            let a = self.jitter * 0.5;
            for k in 0..JITTER_LINES {
                r += a * TAU * self.jitter_hz * (k as Real + 1.0) / JITTER_LINES as Real;
            }
        }
        r
    }

    /// Largest factor the modulation can reach.
    pub fn max_factor(&self) -> Real {
        1.0 + self.amplitude + self.jitter * 0.5 * JITTER_LINES as Real
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The multisine's phases (rad).
    const PHASES: [Real; JITTER_LINES] = [0.0, 3.883, 1.483, 5.366, 2.966, 0.566, 4.449, 2.049];

    /// The tabulated phasors are those of the phases, and the recurrence gives the
    /// factor of the direct sum `1 + a sin(2π f_m t) + j/2 Σ sin(2π (k/8) f_j t + φ_k)`
    /// to rounding over a minute of evaluation times.
    #[test]
    fn recurrence_equals_the_direct_multisine() {
        let tol = if core::mem::size_of::<Real>() == 4 { 2e-6 } else { 1e-13 };
        for ((c, s), ph) in PHASE_CS.iter().zip(PHASES) {
            assert!((c - cos(ph)).abs() < tol && (s - sin(ph)).abs() < tol);
        }
        let p = Params {
            amplitude: 0.02,
            freq_hz: 3.0,
            jitter: 0.05,
            jitter_hz: 20.0,
        };
        let mut worst: Real = 0.0;
        for i in 0..6000 {
            let t = i as Real * 0.0101;
            let mut direct = 1.0 + p.amplitude * sin(crate::real::wrap_angle(TAU * p.freq_hz * t));
            for (k, ph) in PHASES.iter().enumerate() {
                let fk = p.jitter_hz * (k as Real + 1.0) / JITTER_LINES as Real;
                direct += p.jitter * 0.5 * sin(crate::real::wrap_angle(TAU * fk * t + ph));
            }
            worst = worst.max((p.factor(t) - direct).abs());
        }
        assert!(worst < 50.0 * tol, "largest difference {worst}");
        // Off when both parts are off.
        let off = Params { amplitude: 0.0, jitter: 0.0, ..p };
        assert_eq!(off.factor(1.234), 1.0);
    }
}
