//! Deterministic synthetic test signals with known analytic answers, used by
//! the unit tests and the benchmark (and usable to check the CLI end to end).

use std::f64::consts::PI;

/// Fault frequencies (Hz) of the CWRU drive-end bearing (SKF 6205) at 1797 rpm, with a
/// 3 kHz structural resonance: the unit tests' common case.
#[cfg(test)]
pub(crate) fn cwru_6205_1797rpm() -> wearsim_core::kinematics::FaultFrequencies {
    wearsim_core::kinematics::FaultFrequencies {
        shaft_hz: 29.95,
        ftf: 11.93,
        bpfo: 107.36,
        bpfi: 162.19,
        bsf: 70.58,
        natural_hz: 3000.0,
    }
}

/// Small seeded pseudo-random generator (SplitMix64, Steele et al. 2014)
/// with Box-Muller Gaussian deviates. Not cryptographic; reproducible.
#[derive(Debug, Clone)]
pub struct Rng {
    state: u64,
    spare: Option<f64>,
}

impl Rng {
    /// New generator from a seed.
    pub fn new(seed: u64) -> Self {
        Rng {
            state: seed,
            spare: None,
        }
    }

    /// Next uniform 64-bit integer.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform deviate in the open interval (0, 1).
    pub fn uniform(&mut self) -> f64 {
        ((self.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }

    /// Standard normal deviate (Box-Muller).
    pub fn gaussian(&mut self) -> f64 {
        if let Some(s) = self.spare.take() {
            return s;
        }
        let r = (-2.0 * self.uniform().ln()).sqrt();
        let theta = 2.0 * PI * self.uniform();
        self.spare = Some(r * theta.sin());
        r * theta.cos()
    }
}

/// `n` samples of zero-mean Gaussian white noise of standard deviation
/// `sigma` (signal units), reproducible from `seed`.
pub fn gaussian_noise(n: usize, sigma: f64, seed: u64) -> Vec<f64> {
    let mut rng = Rng::new(seed);
    (0..n).map(|_| sigma * rng.gaussian()).collect()
}

/// `n` samples at `fs` Hz of `amp * sin(2 pi freq t + phase)`.
pub fn sine(n: usize, fs: f64, freq: f64, amp: f64, phase: f64) -> Vec<f64> {
    (0..n)
        .map(|i| amp * (2.0 * PI * freq * i as f64 / fs + phase).sin())
        .collect()
}

/// Parameters of a localised-fault vibration model (McFadden & Smith 1984):
/// a train of impulses at `fault_hz`, each exciting a structural resonance
/// (a decaying sinusoid), with the impulse amplitudes modulated as
/// `1 + mod_depth * cos(2 pi mod_hz t)` (load-zone / rotation effects),
/// plus white Gaussian noise.
#[derive(Debug, Clone, Copy)]
pub struct FaultSignal {
    /// Sampling frequency, Hz.
    pub fs: f64,
    /// Impulse repetition frequency, Hz (BPFO, BPFI, 2×BSF...).
    pub fault_hz: f64,
    /// Modulation frequency of the impulse amplitudes, Hz.
    pub mod_hz: f64,
    /// Modulation depth (0 = constant amplitude, 1 = full).
    pub mod_depth: f64,
    /// Resonance frequency excited by each impulse, Hz.
    pub resonance_hz: f64,
    /// Damping ratio of the resonance (e.g. 0.05).
    pub damping: f64,
    /// Peak amplitude of one ringing response, signal units.
    pub impulse_amp: f64,
    /// Standard deviation of the additive white noise, signal units.
    pub noise_sigma: f64,
    /// Noise seed.
    pub seed: u64,
    /// Standard deviation of each impulse's time about `k / fault_hz`, as a fraction of the
    /// period (–): the elements' random slip, which makes a real bearing's impulse train
    /// pseudo-cyclostationary rather than periodic (Randall & Antoni 2011, "Rolling element
    /// bearing diagnostics — A tutorial", §2: 1–2 % typical). 0 gives an exactly periodic
    /// train, whose spectrum is discrete lines; the offsets are drawn from `seed + 1`.
    pub jitter: f64,
}

impl FaultSignal {
    /// Generate `n` samples. Impulse `k` falls at the (non-integer) time `k / fault_hz`
    /// plus its slip offset (`jitter` periods × a standard normal deviate), so the mean
    /// repetition frequency is exact and, with `jitter` = 0, so is every interval.
    pub fn generate(&self, n: usize) -> Vec<f64> {
        let mut x = gaussian_noise(n, self.noise_sigma, self.seed);
        let wn = 2.0 * PI * self.resonance_hz;
        let decay = self.damping * wn;
        let wd = wn * (1.0 - self.damping * self.damping).max(0.0).sqrt();
        // Ring until the envelope is 1e-4 of its start.
        let ring = ((9.2 / decay) * self.fs).ceil() as usize + 1;
        let period = 1.0 / self.fault_hz;
        let duration = n as f64 / self.fs;
        let mut slip = Rng::new(self.seed.wrapping_add(1));
        let mut k = 0usize;
        loop {
            let tk = k as f64 * period + self.jitter * period * slip.gaussian();
            if tk >= duration {
                break;
            }
            let a = self.impulse_amp * (1.0 + self.mod_depth * (2.0 * PI * self.mod_hz * tk).cos());
            let first = (tk.max(0.0) * self.fs).ceil() as usize;
            for (i, xi) in x.iter_mut().enumerate().skip(first).take(ring) {
                let t = i as f64 / self.fs - tk;
                *xi += a * (-decay * t).exp() * (wd * t).sin();
            }
            k += 1;
        }
        x
    }
}
