//! Effect `sensor`: the measurement chain. A real accelerometer record has a noise floor
//! (sensor and conditioning electronics, white; a typical ICP accelerometer has a
//! broadband noise of a few mg, IEPE datasheets), a finite bandwidth (mounting and sensor
//! resonance, anti-alias filters; modelled as a one-pole low-pass with corner `f_c`) and
//! mains interference at the line frequency and its harmonics (ground loops; Randall
//! 2011 §2.3). Applied to the output samples after decimation:
//! `a_out = LP(a) + A_h [sin(2π f_h t) + r (sin(4π f_h t) + sin(6π f_h t))] + σ n`,
//! the harmonics from the fundamental's phasor (`sin 2φ = 2 sin φ cos φ`,
//! `sin 3φ = sin φ (3 − 4 sin² φ)`: one `sincos` per sample instead of three `sin`), with `n` zero-mean unit-variance noise from a generator seeded from the run's seed
//! (independent of the model's own stream, so switching the sensor on leaves the
//! simulated vibration unchanged and only adds the measurement chain).

use super::spec::*;
use crate::error::{check_range, ConfigError};
use crate::real::{exp, sin, sin_cos, Real, TAU};
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

    /// Mains phase (rad, in `[0, 2π)`) of the next output sample.
    pub fn phase(&self) -> Real {
        self.phase
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

    /// Whether the chain adds mains hum (then each sample needs the [`mains_phasor`] of the
    /// memory's phase).
    pub fn has_hum(&self) -> bool {
        self.p.hum > 0.0
    }

    /// Applies the chain to one output sample (out of line: the baseline step only pays
    /// for the check).
    #[inline(never)]
    pub fn apply(&self, st: &mut SensorState, a: Real) -> Real {
        let sc = if self.has_hum() {
            mains_phasor(st.phase)
        } else {
            (0.0, 1.0)
        };
        let rng = &mut st.rng;
        self.sample(&mut st.lp, &mut st.phase, a, sc, || rng.gauss_approx())
    }

    /// Whether the chain adds noise (draws from its generator on every sample).
    pub fn has_noise(&self) -> bool {
        self.p.noise > 0.0
    }

    /// One output sample from the chain's memory (`lp`, `phase`), the mains phasor `sc` and
    /// the noise draw `gauss` (called only when the chain adds noise): the one definition
    /// of the chain's arithmetic, for [`SensorChain::apply`] and [`SensorLanes`].
    #[inline(always)]
    fn sample(
        &self,
        lp: &mut Real,
        phase: &mut Real,
        a: Real,
        sc: (Real, Real),
        gauss: impl FnOnce() -> Real,
    ) -> Real {
        *lp += self.k * (a - *lp);
        *phase = crate::real::wrap_angle(*phase + self.dphi);
        let mut out = *lp;
        if self.p.hum > 0.0 {
            let h = self.p.hum_harmonics;
            let (s, c) = sc;
            let sin2 = 2.0 * s * c;
            let sin3 = s * (3.0 - 4.0 * (s * s));
            out += self.p.hum * (s + h * (sin2 + sin3));
        }
        if self.p.noise > 0.0 {
            out += self.p.noise * gauss();
        }
        out
    }
}

/// The sensor chains of K lanes for the lane stepper (`crate::model::LaneGroup`): the
/// chains' memories side by side and their noise generators word-major, so the noise of
/// all lanes is drawn in one vectorised pass. Lane `l` gives, bit for bit,
/// [`SensorChain::apply`] of its own chain and memory (a lane without a chain passes its
/// input through); the memory lives here, not in the lanes' [`SensorState`].
#[derive(Debug, Clone)]
pub struct SensorLanes<const K: usize> {
    chains: [Option<SensorChain>; K],
    lp: [Real; K],
    phase: [Real; K],
    /// Noise generators, word-major (`words[w][lane]` is word `w` of lane `lane`'s).
    words: [[u32; K]; 4],
    /// Lane `l`'s chain adds noise.
    noisy: [bool; K],
    any_noise: bool,
}

impl<const K: usize> SensorLanes<K> {
    /// The chains of K lanes (`None`: no chain) with their memories.
    pub fn new(chains: [Option<&SensorChain>; K], states: [&SensorState; K]) -> Self {
        let noisy = chains.map(|c| c.is_some_and(|c| c.has_noise()));
        let raw = states.map(|s| s.raw());
        SensorLanes {
            chains: chains.map(|c| c.copied()),
            lp: raw.map(|r| r.1),
            phase: raw.map(|r| r.2),
            words: core::array::from_fn(|w| raw.map(|r| r.0.get(w).copied().unwrap_or(0))),
            noisy,
            any_noise: noisy.iter().any(|n| *n),
        }
    }

    /// Applies every lane's chain to its output sample `a[l]`; lanes whose mains phases are
    /// equal share one phasor evaluation ([`MainsMemo`]).
    #[inline(always)]
    pub fn apply(&mut self, a: &[Real; K]) -> [Real; K] {
        let g = if self.any_noise {
            crate::rng::gauss_approx_where(&mut self.words, &self.noisy)
        } else {
            [0.0; K]
        };
        let mut out = *a;
        let mut mains = MainsMemo::default();
        for ((((o, c), lp), phase), gl) in out
            .iter_mut()
            .zip(&self.chains)
            .zip(self.lp.iter_mut())
            .zip(self.phase.iter_mut())
            .zip(g)
        {
            let Some(chain) = c else { continue };
            let sc = if chain.has_hum() {
                mains.phasor(*phase)
            } else {
                (0.0, 1.0)
            };
            *o = chain.sample(lp, phase, *o, sc, || gl);
        }
        out
    }
}

/// Mains phasor `(sin φ, cos φ)` at phase `φ` (rad): the fundamental and, through the
/// double- and triple-angle identities, the two harmonics of the hum.
#[inline(always)]
pub fn mains_phasor(phase: Real) -> (Real, Real) {
    sin_cos(phase)
}

/// Phasors of the last few distinct mains phases met during one output sample, so that
/// lanes with the same phase (the same mains frequency and output rate, started together)
/// evaluate [`mains_phasor`] once: the same bits as evaluating it per lane.
#[derive(Debug, Clone, Copy, Default)]
pub struct MainsMemo {
    /// `(phase, (sin, cos))`, the first `len` valid (phases compared bit for bit).
    seen: [(Real, (Real, Real)); 4],
    len: usize,
}

impl MainsMemo {
    /// [`mains_phasor`] of `phase`, from the memo when this exact phase was met before.
    pub fn phasor(&mut self, phase: Real) -> (Real, Real) {
        let seen = self.seen.get(..self.len).unwrap_or(&[]);
        if let Some((_, sc)) = seen.iter().find(|(p, _)| p.to_bits() == phase.to_bits()) {
            return *sc;
        }
        let sc = mains_phasor(phase);
        let slot = self.len % self.seen.len();
        if let Some(e) = self.seen.get_mut(slot) {
            *e = (phase, sc);
        }
        self.len = (self.len + 1).min(self.seen.len());
        sc
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::real::wrap_angle;

    /// The harmonics from the phasor equal the three sines they replace (to rounding, far
    /// below any hum amplitude), over whole mains periods at both frequencies.
    #[test]
    fn phasor_hum_equals_three_sines() {
        let p = Params {
            noise: 0.0,
            corner_hz: 0.0,
            hum: 1.0,
            hum_hz: 50.0,
            hum_harmonics: 0.3,
        };
        for hz in [50.0, 60.0] {
            let chain = SensorChain::design(&Params { hum_hz: hz, ..p }, 12_000.0);
            let mut st = SensorState::new(1);
            let mut worst: Real = 0.0;
            for _ in 0..1200 {
                let ph = st.phase;
                let want = sin(ph)
                    + 0.3 * (sin(wrap_angle(2.0 * ph)) + sin(wrap_angle(3.0 * ph)));
                let got = chain.apply(&mut st, 0.0);
                worst = worst.max((got - want).abs());
            }
            let tol = if crate::real::SINGLE_PRECISION { 2e-6 } else { 1e-14 };
            assert!(worst < tol, "{hz} Hz: hum differs by {worst}");
        }
    }

    /// The memo gives the bits of a fresh evaluation for each phase, including after more
    /// distinct phases than it holds.
    #[test]
    fn memo_returns_the_evaluated_bits() {
        let mut memo = MainsMemo::default();
        for i in 0..20 {
            let ph = (i % 7) as Real * 0.9;
            let (s, c) = memo.phasor(ph);
            let (ws, wc) = mains_phasor(ph);
            assert_eq!((s.to_bits(), c.to_bits()), (ws.to_bits(), wc.to_bits()));
        }
        assert_ne!(mains_phasor(0.9), mains_phasor(1.8));
    }
}
