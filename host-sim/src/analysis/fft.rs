//! Shared FFT plumbing: per-thread cached planners and small helpers used by
//! the spectrum, envelope and kurtogram modules.

use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::{Fft, FftPlanner};
use std::cell::RefCell;
use std::sync::Arc;

thread_local! {
    static REAL_PLANNER: RefCell<RealFftPlanner<f64>> = RefCell::new(RealFftPlanner::new());
    static COMPLEX_PLANNER: RefCell<FftPlanner<f64>> = RefCell::new(FftPlanner::new());
}

/// Forward real-to-complex plan of length `n` (cached per thread).
pub(crate) fn plan_r2c(n: usize) -> Arc<dyn RealToComplex<f64>> {
    REAL_PLANNER.with(|p| p.borrow_mut().plan_fft_forward(n))
}

/// Inverse complex-to-real plan of length `n` (cached per thread, unnormalised).
// Used by the `app` modules only.
#[cfg_attr(not(feature = "app"), allow(dead_code))]
pub(crate) fn plan_c2r(n: usize) -> Arc<dyn ComplexToReal<f64>> {
    REAL_PLANNER.with(|p| p.borrow_mut().plan_fft_inverse(n))
}

/// Inverse complex plan of length `n` (cached per thread, unnormalised).
pub(crate) fn plan_inverse(n: usize) -> Arc<dyn Fft<f64>> {
    COMPLEX_PLANNER.with(|p| p.borrow_mut().plan_fft_inverse(n))
}

/// One-sided DFT (`n/2 + 1` bins, unnormalised) of `(x - offset) * w`,
/// where the window `w` (same length as `x`) is optional.
fn rfft_impl(x: &[f64], w: Option<&[f64]>, offset: f64) -> Vec<Complex<f64>> {
    let plan = plan_r2c(x.len());
    let mut input: Vec<f64> = match w {
        Some(w) => x.iter().zip(w).map(|(v, wi)| (v - offset) * wi).collect(),
        None => x.iter().map(|v| v - offset).collect(),
    };
    let mut out = plan.make_output_vec();
    // Lengths come from the plan itself, so this cannot fail.
    plan.process(&mut input, &mut out)
        .expect("realfft buffer lengths match the plan");
    out
}

/// One-sided DFT (`n/2 + 1` bins, unnormalised) of `x` multiplied sample by
/// sample by `w` (same length as `x`), after subtracting `offset`.
pub(crate) fn rfft_windowed(x: &[f64], w: &[f64], offset: f64) -> Vec<Complex<f64>> {
    rfft_impl(x, Some(w), offset)
}

/// One-sided DFT (`n/2 + 1` bins, unnormalised) of `x - offset`.
pub(crate) fn rfft(x: &[f64], offset: f64) -> Vec<Complex<f64>> {
    rfft_impl(x, None, offset)
}

/// Factor turning bin `k` of an `n`-point DFT of a real signal into its
/// one-sided value: 1 for DC and (even `n`) Nyquist, 2 otherwise.
pub(crate) fn one_sided_factor(k: usize, n: usize) -> f64 {
    if k == 0 || 2 * k == n {
        1.0
    } else {
        2.0
    }
}

/// Complex envelope of the band formed by bins `k0..=k1` of the one-sided
/// spectrum `spec` of a real record of `n` samples (DC excluded by the
/// caller). The bins are shifted to base band and inverse-transformed with
/// length `out_len >= k1 - k0 + 1`: `out_len = n` gives the full-rate
/// envelope, a smaller length a decimated one (decimation factor
/// `n / out_len`). The magnitude equals that of the analytic signal of the
/// FFT-domain band-passed record (Randall & Antoni 2011).
pub(crate) fn band_envelope(
    spec: &[Complex<f64>],
    n: usize,
    k0: usize,
    k1: usize,
    out_len: usize,
) -> Vec<Complex<f64>> {
    let mut buf = vec![Complex::new(0.0, 0.0); out_len];
    for (b, k) in buf.iter_mut().zip(k0..=k1) {
        *b = spec[k] * (one_sided_factor(k, n) / n as f64);
    }
    plan_inverse(out_len).process(&mut buf);
    buf
}

/// `|c|` of a spectrum line: `√(re² + im²)`, falling back to `hypot` (which guards
/// against overflow and underflow of the squares) only where the squares leave the
/// normal range. `hypot` on every line was 4 % of a gap run (a library call per line).
#[inline]
pub fn magnitude(c: Complex<f64>) -> f64 {
    let m = (c.re * c.re + c.im * c.im).sqrt();
    if m.is_finite() && m > 1e-150 {
        m
    } else {
        c.norm()
    }
}
