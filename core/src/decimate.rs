//! Anti-alias decimation from the internal rate to the output rate.
//!
//! A linear-phase FIR low-pass (windowed sinc, Kaiser window; Kaiser 1974 design
//! formulas: `β = 0.1102(A − 8.7)`, `N = (A − 7.95)/(2.285 Δω) + 1`) designed for stopband
//! attenuation A = 80 dB with its transition band from 0.4·fs to 0.6·fs of the output rate
//! fs. Everything above 0.6·fs is attenuated ≥ 80 dB before decimation; content between
//! 0.5·fs and 0.6·fs can fold only into 0.4–0.5·fs, so the **usable output band is
//! 0–0.4·fs**, as with any real ADC. The filter is evaluated only at output instants
//! (polyphase), so its cost per internal step is `taps/R`.

use crate::real::Real;

/// Capacity of the filter (taps). 82 dB (80 dB plus margin) needs about `26·R + 1` taps, so
/// every ratio up to `MAX_OVERSAMPLE` meets the specification in full: 512 with the
/// `oversample-16` feature (417 taps at 16, and a block of four outputs 48 samples more),
/// 256 without (209 taps at 8).
#[cfg(feature = "oversample-16")]
pub const MAX_TAPS: usize = 512;
/// Capacity of the filter (taps); see the `oversample-16` feature.
#[cfg(not(feature = "oversample-16"))]
pub const MAX_TAPS: usize = 256;

/// The capacity of a delay line in checkpoints of format versions 1–3 (written when
/// [`MAX_TAPS`] was always 256 and the largest ratio 8); version 4 states its own.
pub const MAX_TAPS_V3: usize = 256;

/// FIR coefficients of one anti-alias design.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AntiAlias {
    taps: [Real; MAX_TAPS],
    len: usize,
    ratio: u32,
}

impl AntiAlias {
    /// Designs the filter for decimation by `ratio` (≥ 1).
    pub fn design(ratio: u32) -> Self {
        let r = if ratio == 0 { 1 } else { ratio } as f64;
        let atten = 82.0; // 2 dB margin over the 80 dB specification (Kaiser's N is approximate)
        let beta = 0.1102 * (atten - 8.7);
        let dw = core::f64::consts::TAU * 0.2 / r; // rad/sample at internal rate
        let mut n = libm::ceil((atten - 7.95) / (2.285 * dw)) as usize + 1;
        if n.is_multiple_of(2) {
            n += 1;
        }
        if n > MAX_TAPS - 1 {
            n = MAX_TAPS - 1;
        }
        let mut taps = [0.0 as Real; MAX_TAPS];
        let fc = 0.5 / r; // cycles/sample at internal rate (output Nyquist)
        let mid = (n - 1) as f64 / 2.0;
        let i0b = bessel_i0(beta);
        let mut sum = 0.0;
        let mut tmp = [0.0f64; MAX_TAPS];
        for (i, t) in tmp.iter_mut().enumerate().take(n) {
            let x = i as f64 - mid;
            let sinc = if x == 0.0 {
                2.0 * fc
            } else {
                libm::sin(core::f64::consts::TAU * fc * x) / (core::f64::consts::PI * x)
            };
            let ratio_w = if mid > 0.0 { x / mid } else { 0.0 };
            let arg = 1.0 - ratio_w * ratio_w;
            let w = bessel_i0(beta * libm::sqrt(if arg > 0.0 { arg } else { 0.0 })) / i0b;
            *t = sinc * w;
            sum += *t;
        }
        for (t, v) in taps.iter_mut().zip(tmp.iter()).take(n) {
            *t = (v / sum) as Real;
        }
        AntiAlias {
            taps,
            len: n,
            ratio: ratio.max(1),
        }
    }

    /// Number of taps.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Always false: a design has at least one tap.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The coefficients, oldest-sample tap first (as [`AntiAlias::output`] applies them).
    pub fn taps(&self) -> &[Real] {
        self.taps.get(..self.len).unwrap_or(&[])
    }

    /// Decimation ratio.
    pub fn ratio(&self) -> u32 {
        self.ratio
    }

    /// Group delay in internal samples (`(len − 1)/2`).
    pub fn delay(&self) -> usize {
        (self.len.saturating_sub(1)) / 2
    }

    /// Filter output for the history held in `line` (see [`DelayLine`]).
    #[inline]
    pub fn output(&self, line: &DelayLine) -> Real {
        let hist = line.window(self.len);
        let mut acc = 0.0;
        for (t, x) in self.taps.iter().zip(hist.iter()) {
            acc += t * x;
        }
        acc
    }

    /// Internal samples a block of [`BLOCK`] outputs, `ratio` samples apart, reads: the
    /// oldest output's window and `(BLOCK − 1)·ratio` newer samples. `None` when they do
    /// not fit the delay line's contiguous window ([`MAX_TAPS`]), so the outputs must be
    /// taken one at a time (never for the designs of ratios up to `MAX_OVERSAMPLE`: at most
    /// 417 + 48 samples at 16, 209 + 24 at 8).
    pub fn block_span(&self) -> Option<usize> {
        let span = self.len + (BLOCK - 1) * self.ratio as usize;
        (span <= MAX_TAPS).then_some(span)
    }

    /// The filter outputs of the last [`BLOCK`] output instants, oldest first, the newest
    /// ending at the newest sample of `line` and each earlier one `ratio` samples before
    /// the next: what [`AntiAlias::output`] gave at each instant, bit for bit (every sum
    /// starts from 0 and adds `taps[j]·x[j]` in the same order), but the four sums advance
    /// together, four independent chains of additions instead of one, which a pipelined
    /// FPU overlaps. The samples must still be in `line` (see [`AntiAlias::block_span`]);
    /// zeros otherwise.
    #[inline]
    pub fn outputs_block(&self, line: &DelayLine) -> [Real; BLOCK] {
        let mut acc = [0.0; BLOCK];
        let Some(span) = self.block_span() else {
            return acc;
        };
        let r = self.ratio as usize;
        let hist = line.window(span);
        let w = |j: usize| hist.get(j * r..j * r + self.len).unwrap_or(&[]);
        let taps = self.taps();
        for ((((t, a), b), c), d) in taps.iter().zip(w(0)).zip(w(1)).zip(w(2)).zip(w(3)) {
            let [s0, s1, s2, s3] = &mut acc;
            *s0 += t * a;
            *s1 += t * b;
            *s2 += t * c;
            *s3 += t * d;
        }
        acc
    }
}

/// Output instants [`AntiAlias::outputs_block`] evaluates together.
pub const BLOCK: usize = 4;

/// Modified Bessel function of the first kind, order 0 (power series).
fn bessel_i0(x: f64) -> f64 {
    let mut sum = 1.0;
    let mut term = 1.0;
    let q = x * x / 4.0;
    for k in 1..60 {
        term *= q / ((k * k) as f64);
        sum += term;
        if term < sum * 1e-17 {
            break;
        }
    }
    sum
}

/// Input history of one channel, newest last, stored twice so that the last `len`
/// samples are always one contiguous slice (no modulo in the dot product).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DelayLine {
    buf: [Real; 2 * MAX_TAPS],
    pos: usize,
}

impl Default for DelayLine {
    fn default() -> Self {
        DelayLine {
            buf: [0.0; 2 * MAX_TAPS],
            pos: 0,
        }
    }
}

impl DelayLine {
    /// Appends one sample.
    #[inline(always)]
    pub fn push(&mut self, x: Real) {
        if let Some(v) = self.buf.get_mut(self.pos) {
            *v = x;
        }
        if let Some(v) = self.buf.get_mut(self.pos + MAX_TAPS) {
            *v = x;
        }
        self.pos += 1;
        if self.pos >= MAX_TAPS {
            self.pos = 0;
        }
    }

    /// Raw buffer and position (for checkpoints).
    pub fn raw(&self) -> (&[Real; 2 * MAX_TAPS], usize) {
        (&self.buf, self.pos)
    }

    /// A delay line from a raw buffer and position (for checkpoints); the position is
    /// reduced modulo the capacity.
    pub fn from_raw(buf: [Real; 2 * MAX_TAPS], pos: usize) -> Self {
        DelayLine {
            buf,
            pos: pos % MAX_TAPS,
        }
    }

    /// The newest `len` samples, oldest first.
    #[inline(always)]
    pub fn window(&self, len: usize) -> &[Real] {
        let end = self.pos + MAX_TAPS;
        let start = end.saturating_sub(len);
        self.buf.get(start..end).unwrap_or(&[])
    }
}
