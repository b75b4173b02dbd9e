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

use super::spec::*;
use crate::error::{check_range, ConfigError};
use crate::real::{cos, sin, Real, PI, TAU};

/// Number of modes.
pub const MODES: usize = 3;

/// One structural mode.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
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
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Params {
    /// The modes.
    pub modes: [Mode; MODES],
    /// Broadband path gain `G` (–), in [0.01, 10]; 1 = none.
    pub path_gain: Real,
}

impl EffectParams for Params {
    const SPEC: EffectSpec = EffectSpec {
        name: "transfer-path",
        summary: "path from bearing to sensor: broadband gain and up to three structural modes (band-pass resonators on the acceleration)",
        params: &[
            param("f1", "transfer-path.f1", "Hz", 2000.0, 100.0, 4.0e5, "mode 1 frequency (at most fs/2.5)"),
            param("zeta1", "transfer-path.zeta1", "-", 0.05, 0.005, 0.2, "mode 1 damping ratio"),
            param("gain1", "transfer-path.gain1", "-", 1.0, 0.0, 10.0, "mode 1 added peak gain (0 = off)"),
            param("f2", "transfer-path.f2", "Hz", 3000.0, 100.0, 4.0e5, "mode 2 frequency (at most fs/2.5)"),
            param("zeta2", "transfer-path.zeta2", "-", 0.05, 0.005, 0.2, "mode 2 damping ratio"),
            param("gain2", "transfer-path.gain2", "-", 0.0, 0.0, 10.0, "mode 2 added peak gain (0 = off)"),
            param("f3", "transfer-path.f3", "Hz", 4000.0, 100.0, 4.0e5, "mode 3 frequency (at most fs/2.5)"),
            param("zeta3", "transfer-path.zeta3", "-", 0.05, 0.005, 0.2, "mode 3 damping ratio"),
            param("gain3", "transfer-path.gain3", "-", 0.0, 0.0, 10.0, "mode 3 added peak gain (0 = off)"),
            param("path_gain", "transfer-path.path_gain", "-", 1.0, 0.01, 10.0, "broadband gain of the path from bearing to sensor (1 = none)"),
        ],
        signature: Signature {
            mechanism: Mechanism::Transmission,
            moves: moves(true, true, false, false),
        },
        // One mode only: with the gain a second and third mode trade off against each
        // other and make the fit ill-posed. Mode 1 between 5 % of fs and 0.8 of Nyquist.
        fit: FitSpec {
            fitted: &[
                fit("path_gain", FitBound::Abs(0.01), FitBound::Abs(10.0), true),
                fit("f1", FitBound::Fs(0.05), FitBound::Fs(0.4), true),
                fit("gain1", FitBound::Abs(0.2), FitBound::Abs(10.0), true),
            ],
            fixed: &[
                ("zeta1", FitBound::Abs(0.05)),
                ("gain2", FitBound::Abs(0.0)),
                ("gain3", FitBound::Abs(0.0)),
            ],
            needs_defect: false,
            note: "path from bearing to sensor: broadband gain and one structural mode (frequency, gain; 5 % damping)",
        },
    };

    fn from_slice(v: &[Real]) -> Self {
        let mode = |i: usize| Mode {
            freq_hz: at(v, 3 * i),
            zeta: at(v, 3 * i + 1),
            gain: at(v, 3 * i + 2),
        };
        Params {
            modes: [mode(0), mode(1), mode(2)],
            path_gain: at(v, 3 * MODES),
        }
    }

    fn write(&self, out: &mut [Real]) {
        for (m, o) in self.modes.iter().zip(out.chunks_mut(3)) {
            put(o, &[m.freq_hz, m.zeta, m.gain]);
        }
        if let Some(o) = out.get_mut(3 * MODES) {
            *o = self.path_gain;
        }
    }
}

impl Params {
    /// Checks the frequencies of the modes that are on against the output rate `fs`
    /// (Hz): at most fs/2.5, so that they stay inside the anti-alias pass band.
    pub fn check_rate(&self, fs: Real) -> Result<(), ConfigError> {
        for (m, f) in self.modes.iter().zip(Self::SPEC.params.iter().step_by(3)) {
            if m.gain > 0.0 {
                // An empty range (fs below 2.5 × the lowest mode frequency) is the rate's
                // fault, not the mode's: said so rather than `allowed 100 ..= 40`.
                if fs / 2.5 < f.min as Real {
                    return Err(ConfigError::Inconsistent {
                        field: f.field,
                        reason: "the output rate fs is too low for a transfer-path mode: a mode lies between 100 Hz and fs / 2.5, so fs must be at least 250 Hz",
                    });
                }
                check_range(f.field, m.freq_hz, f.min as Real, fs / 2.5)?;
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
            y += resonate((r.b0, r.a1, r.a2), &mut z.0, &mut z.1, x);
        }
        self.gain * y
    }
}

/// One resonator's output for input `x`, its memory `(z0, z1)` moved on (transposed
/// direct form II): the one definition of the arithmetic, for [`TransferPath::filter`]
/// and the lanes' [`PathLanes::filter`].
#[inline(always)]
fn resonate(r: (Real, Real, Real), z0: &mut Real, z1: &mut Real, x: Real) -> Real {
    let (b0, a1, a2) = r;
    let out = b0 * x + *z0;
    *z0 = -a1 * out + *z1;
    *z1 = -b0 * x - a2 * out;
    out
}

/// K transfer paths side by side for the lane stepper (`crate::model::LaneGroup`): each
/// coefficient and memory of mode `i` of every lane in one array, so the resonators of
/// all lanes run in one vectorised loop. Lane `l` gives, bit for bit,
/// [`TransferPath::filter`] of its own path (a lane without a path passes its input
/// through); the memory lives here, not in the lanes' [`PathState`].
#[derive(Debug, Clone)]
pub struct PathLanes<const K: usize> {
    b0: [[Real; K]; MODES],
    a1: [[Real; K]; MODES],
    a2: [[Real; K]; MODES],
    z0: [[Real; K]; MODES],
    z1: [[Real; K]; MODES],
    /// Mode `i` is active in lane `l` (`on[i][l]`).
    on: [[bool; K]; MODES],
    gain: [Real; K],
    /// Lane `l` has a path.
    has: [bool; K],
    /// Some lane has a path.
    any: bool,
}

impl<const K: usize> PathLanes<K> {
    /// The paths of K lanes (`None`: no path) with their memories.
    pub fn new(paths: [Option<&TransferPath>; K], states: [&PathState; K]) -> Self {
        let mut p = PathLanes {
            b0: [[0.0; K]; MODES],
            a1: [[0.0; K]; MODES],
            a2: [[0.0; K]; MODES],
            z0: [[0.0; K]; MODES],
            z1: [[0.0; K]; MODES],
            on: [[false; K]; MODES],
            gain: [1.0; K],
            has: [false; K],
            any: false,
        };
        let put = |a: &mut [[Real; K]; MODES], i: usize, l: usize, v: Real| {
            if let Some(x) = a.get_mut(i).and_then(|m| m.get_mut(l)) {
                *x = v;
            }
        };
        for (l, (path, st)) in paths.iter().zip(states).enumerate() {
            let Some(t) = path else { continue };
            if let (Some(h), Some(g)) = (p.has.get_mut(l), p.gain.get_mut(l)) {
                (*h, *g) = (true, t.gain);
            }
            for (i, (r, z)) in t.res.iter().zip(&st.z).enumerate().take(t.active) {
                put(&mut p.b0, i, l, r.b0);
                put(&mut p.a1, i, l, r.a1);
                put(&mut p.a2, i, l, r.a2);
                put(&mut p.z0, i, l, z.0);
                put(&mut p.z1, i, l, z.1);
                if let Some(o) = p.on.get_mut(i).and_then(|m| m.get_mut(l)) {
                    *o = true;
                }
            }
        }
        p.any = p.has.iter().any(|h| *h);
        p
    }

    /// Filters one internal-rate sample of every lane. An inactive mode's coefficients and
    /// memory are zeros and its output is not added, so its lane keeps the scalar bits.
    #[inline(always)]
    pub fn filter(&mut self, x: &[Real; K]) -> [Real; K] {
        if !self.any {
            return *x;
        }
        let mut y = *x;
        for i in 0..MODES {
            let (Some(b0), Some(a1), Some(a2), Some(z0), Some(z1), Some(on)) = (
                self.b0.get(i),
                self.a1.get(i),
                self.a2.get(i),
                self.z0.get_mut(i),
                self.z1.get_mut(i),
                self.on.get(i),
            ) else {
                continue;
            };
            for l in 0..K {
                let (Some(yl), Some(xl), Some(b), Some(p), Some(q), Some(za), Some(zb), Some(o)) = (
                    y.get_mut(l),
                    x.get(l),
                    b0.get(l),
                    a1.get(l),
                    a2.get(l),
                    z0.get_mut(l),
                    z1.get_mut(l),
                    on.get(l),
                ) else {
                    continue;
                };
                let out = resonate((*b, *p, *q), za, zb, *xl);
                *yl = if *o { *yl + out } else { *yl };
            }
        }
        for (((yl, xl), g), h) in y.iter_mut().zip(x).zip(&self.gain).zip(&self.has) {
            *yl = if *h { *g * *yl } else { *xl };
        }
        y
    }
}
