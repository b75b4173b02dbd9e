//! Effect `transfer-path`: extra structural modes between the bearing and the sensor.
//!
//! The baseline has one radial degree of freedom; a real accelerometer sits on a housing
//! (CWRU: the motor end shield) whose own modes amplify bands of the bearing's vibration
//! (Randall 2011, *Vibration-based Condition Monitoring* §2.2: the measured signal is the
//! source convolved with the transmission path). This effect passes the internal-rate
//! acceleration through `a_out = a + Σ_i g_i · BP_i(a)` before decimation, with `BP_i` a
//! second-order band-pass resonator of unit peak gain at `f_i` and damping ratio `ζ_i`
//! (bandwidth `2ζ_i f_i`), discretised by the bilinear transform with the centre
//! frequency pre-warped (RBJ audio-EQ cookbook), so the peak is exactly at `f_i` with
//! magnitude `1 + g_i`. Up to three modes; a gain of 0 switches a mode off.
//! A broadband path gain `G` multiplies the result, `a_out = G (a + Σ g_i BP_i(a))`: the
//! model's output is the acceleration of the bearing's outer ring, the sensor sits on a
//! housing behind joints and mass that attenuate (or, rarely, amplify) it as a whole
//! (transmission loss across bolted joints, Randall 2011 §2.2; McFadden & Smith 1984 for
//! the path from outer race to transducer).
//! Frequencies must lie in [100 Hz, fs/2.5] (fs the output rate) so that the modes stay
//! inside the anti-alias pass band.

use crate::error::{check_range, ConfigError};
use crate::real::{cos, sin, Real, PI, TAU};

/// Number of modes.
pub const MODES: usize = 3;

/// One structural mode.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mode {
    /// Centre frequency (Hz), in [100, fs/2.5].
    pub freq_hz: Real,
    /// Damping ratio ζ (–), in [0.005, 0.2].
    pub zeta: Real,
    /// Peak gain added at the centre (–), in [0, 10]; 0 = mode off.
    pub gain: Real,
}

/// Parameters of the `transfer-path` effect.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Params {
    /// The modes.
    pub modes: [Mode; MODES],
    /// Broadband path gain `G` (–), in [0.01, 10]; 1 = none.
    pub path_gain: Real,
}

const FIELDS: [[&str; 3]; MODES] = [
    [
        "transfer-path.f1",
        "transfer-path.zeta1",
        "transfer-path.gain1",
    ],
    [
        "transfer-path.f2",
        "transfer-path.zeta2",
        "transfer-path.gain2",
    ],
    [
        "transfer-path.f3",
        "transfer-path.zeta3",
        "transfer-path.gain3",
    ],
];

impl Params {
    /// Validates each mode: frequency in [100, 4·10⁵] Hz (the model further limits it to
    /// fs/2.5), ζ in [0.005, 0.2], gain in [0, 10].
    pub fn new_checked(p: Params) -> Result<Self, ConfigError> {
        for (m, [f, z, g]) in p.modes.iter().zip(FIELDS) {
            check_range(f, m.freq_hz, 100.0, 4.0e5)?;
            check_range(z, m.zeta, 0.005, 0.2)?;
            check_range(g, m.gain, 0.0, 10.0)?;
        }
        check_range("transfer-path.path_gain", p.path_gain, 0.01, 10.0)?;
        Ok(p)
    }

    /// Checks the frequencies against the output rate `fs` (Hz): at most fs/2.5.
    pub fn check_rate(&self, fs: Real) -> Result<(), ConfigError> {
        for (m, [f, _, _]) in self.modes.iter().zip(FIELDS) {
            if m.gain > 0.0 {
                check_range(f, m.freq_hz, 100.0, fs / 2.5)?;
            }
        }
        Ok(())
    }
}

/// One discretised resonator (transposed direct form II), band-pass part only:
/// `BP(z) = (b0 − b0 z⁻²) / (1 + a1 z⁻¹ + a2 z⁻²)`, scaled by the mode gain.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Resonator {
    b0: Real,
    a1: Real,
    a2: Real,
}

impl Resonator {
    /// Designs the resonator of `m` at internal step `h` (s). Bilinear transform with
    /// pre-warping: `w0 = 2π f h`, `α = sin(w0)·ζ` (Q = 1/(2ζ), `α = sin w0/(2Q)`).
    pub fn design(m: &Mode, h: Real) -> Self {
        let w0 = TAU * m.freq_hz * h;
        let w0 = if w0 < PI { w0 } else { PI * 0.999 };
        let alpha = sin(w0) * m.zeta;
        let a0 = 1.0 + alpha;
        Resonator {
            b0: m.gain * alpha / a0,
            a1: -2.0 * cos(w0) / a0,
            a2: (1.0 - alpha) / a0,
        }
    }
}

/// The filter of all active modes.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TransferPath {
    res: [Resonator; MODES],
    active: usize,
    gain: Real,
}

/// Filter memory (two values per mode).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PathState {
    z: [(Real, Real); MODES],
}

impl PathState {
    /// The memory as plain numbers (checkpoints).
    pub fn raw(&self) -> [Real; 2 * MODES] {
        let mut out = [0.0; 2 * MODES];
        for (o, z) in out.chunks_exact_mut(2).zip(self.z.iter()) {
            if let [a, b] = o {
                *a = z.0;
                *b = z.1;
            }
        }
        out
    }

    /// The memory from [`PathState::raw`].
    pub fn from_raw(r: [Real; 2 * MODES]) -> Self {
        let mut z = [(0.0, 0.0); MODES];
        for (zi, c) in z.iter_mut().zip(r.chunks_exact(2)) {
            if let [a, b] = c {
                *zi = (*a, *b);
            }
        }
        PathState { z }
    }
}

impl TransferPath {
    /// Designs the filter for `p` at internal step `h` (s); modes with zero gain are
    /// dropped.
    pub fn design(p: &Params, h: Real) -> Self {
        let mut res = [Resonator::default(); MODES];
        let mut active = 0;
        for m in p.modes.iter().filter(|m| m.gain > 0.0) {
            if let Some(r) = res.get_mut(active) {
                *r = Resonator::design(m, h);
                active += 1;
            }
        }
        TransferPath {
            res,
            active,
            gain: p.path_gain,
        }
    }

    /// Filters one internal-rate sample.
    #[inline]
    pub fn filter(&self, st: &mut PathState, x: Real) -> Real {
        let mut y = x;
        for (r, z) in self.res.iter().zip(st.z.iter_mut()).take(self.active) {
            let out = r.b0 * x + z.0;
            z.0 = -r.a1 * out + z.1;
            z.1 = -r.b0 * x - r.a2 * out;
            y += out;
        }
        self.gain * y
    }
}
