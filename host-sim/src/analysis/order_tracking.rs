//! Computed order tracking: a record taken while the shaft speed changes, resampled onto equal
//! increments of shaft angle, so that every shaft-locked frequency (the bearing's defect
//! frequencies are fixed multiples of the shaft speed) becomes one line again in the
//! envelope spectrum (Fyfe & Munck 1997, "Analysis of computed order tracking", MSSP
//! 11(2):187–205; Randall & Antoni 2011, MSSP 25:485–520, §3.4).
//!
//! The shaft angle at each sample is the trapezoidal integral of the known speed profile
//! (exact for the piecewise-linear profiles wearsim simulates); the samples at equal angle
//! steps are interpolated with a cubic (Catmull–Rom) kernel. The result has as many samples as
//! the record, so its sample rate stays `fs` at the *mean* shaft speed: the equivalent
//! constant-speed record whose analysis uses `60 · mean_hz` rpm.

/// A record resampled to equal shaft-angle steps.
#[derive(Debug, Clone, PartialEq)]
pub struct OrderTracked {
    /// The resampled signal: sample `k` at shaft angle `k · revolutions / (n − 1)` turns.
    pub samples: Vec<f64>,
    /// Mean shaft frequency over the record, Hz (revolutions / duration): the constant speed
    /// at which `samples` at the record's `fs` has the same number of revolutions.
    pub mean_hz: f64,
    /// Lowest and highest shaft frequency over the record, Hz.
    pub min_hz: f64,
    /// See `min_hz`.
    pub max_hz: f64,
    /// Shaft revolutions over the record.
    pub revolutions: f64,
}

/// Resample `x` (sample rate `fs`, Hz; sample `i` at time `t0 + i / fs`, s) to equal shaft
/// angle steps given the shaft frequency `shaft_hz(t)` (Hz, positive). `None` for fewer than
/// four samples, a non-positive or non-finite `fs`, or a speed that is not positive and
/// finite at some sample (no angle to track).
pub fn order_track(
    x: &[f64],
    fs: f64,
    t0: f64,
    shaft_hz: impl Fn(f64) -> f64,
) -> Option<OrderTracked> {
    let n = x.len();
    if n < 4 || !(fs.is_finite() && fs > 0.0) {
        return None;
    }
    let speeds: Vec<f64> = (0..n).map(|i| shaft_hz(t0 + i as f64 / fs)).collect();
    if speeds.iter().any(|f| !(f.is_finite() && *f > 0.0)) {
        return None;
    }
    // Shaft angle at each sample, revolutions.
    let mut theta = Vec::with_capacity(n);
    let mut acc = 0.0;
    theta.push(0.0);
    for w in speeds.windows(2) {
        acc += 0.5 * (w[0] + w[1]) / fs;
        theta.push(acc);
    }
    let revolutions = acc;
    let step = revolutions / (n - 1) as f64;
    let mut out = Vec::with_capacity(n);
    let mut j = 0usize;
    for k in 0..n {
        let target = k as f64 * step;
        while j + 2 < n && theta[j + 1] < target {
            j += 1;
        }
        let span = theta[j + 1] - theta[j];
        let u = if span > 0.0 {
            ((target - theta[j]) / span).clamp(0.0, 1.0)
        } else {
            0.0
        };
        out.push(catmull_rom(x, j, u));
    }
    let (min_hz, max_hz) = speeds
        .iter()
        .fold((f64::INFINITY, 0.0_f64), |(lo, hi), &f| {
            (lo.min(f), hi.max(f))
        });
    Some(OrderTracked {
        samples: out,
        mean_hz: revolutions * fs / (n - 1) as f64,
        min_hz,
        max_hz,
        revolutions,
    })
}

/// Catmull–Rom interpolation between `x[j]` and `x[j + 1]` at fraction `u` ∈ [0, 1]; beyond
/// the record's ends the outer neighbour is extrapolated linearly (a clamped one would halve
/// the end slope).
fn catmull_rom(x: &[f64], j: usize, u: f64) -> f64 {
    let last = x.len() - 1;
    let p1 = x[j];
    let p2 = x[(j + 1).min(last)];
    let p0 = if j == 0 { 2.0 * p1 - p2 } else { x[j - 1] };
    let p3 = if j + 2 > last {
        2.0 * p2 - p1
    } else {
        x[j + 2]
    };
    let u2 = u * u;
    let u3 = u2 * u;
    0.5 * (2.0 * p1
        + (p2 - p0) * u
        + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * u2
        + (3.0 * p1 - p0 - 3.0 * p2 + p3) * u3)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;

    /// A tone locked to the shaft (`orders` per revolution) recorded during a run-up becomes a
    /// pure tone at `orders · mean_hz` after tracking: its samples follow the angle exactly,
    /// to the interpolation error of a cubic kernel.
    #[test]
    fn a_shaft_locked_tone_during_a_run_up_becomes_a_constant_tone() {
        let fs = 20_000.0;
        let n = 40_000;
        let orders = 5.3;
        let f = |t: f64| 20.0 + 5.0 * t; // 20 -> 30 Hz over 2 s
        let angle = |t: f64| 20.0 * t + 2.5 * t * t; // revolutions
        let x: Vec<f64> = (0..n)
            .map(|i| (TAU * orders * angle(i as f64 / fs)).sin())
            .collect();
        let o = order_track(&x, fs, 0.0, f).unwrap();
        let dur = (n - 1) as f64 / fs;
        assert!(
            (o.revolutions - angle(dur)).abs() < 1e-9,
            "{}",
            o.revolutions
        );
        assert!((o.mean_hz - angle(dur) / dur).abs() < 1e-9);
        assert_eq!((o.min_hz, o.max_hz), (20.0, f(dur)));
        let step = o.revolutions / (n - 1) as f64;
        let worst = o
            .samples
            .iter()
            .enumerate()
            .map(|(k, y)| (y - (TAU * orders * k as f64 * step).sin()).abs())
            .fold(0.0, f64::max);
        // 5.3 orders at 30 Hz is 159 Hz, 126 samples per period: the Catmull-Rom kernel's
        // error on a sine at ωh = 2π/126 is 2.0e-6 (computed for the kernel alone); a
        // wrong angle (e.g. ω·t at the mean speed) or a linear kernel (3e-4) fails this.
        assert!(worst < 1e-5, "{worst}");
        // Without tracking the same tone drifts by whole periods.
        let drift = (0..n)
            .map(|k| (x[k] - (TAU * orders * k as f64 * step).sin()).abs())
            .fold(0.0, f64::max);
        assert!(drift > 1.0, "{drift}");
    }

    /// At constant speed tracking returns the record itself (the grid falls on the samples).
    #[test]
    fn constant_speed_is_the_identity() {
        let x: Vec<f64> = (0..1000)
            .map(|i| ((i * 7919) % 101) as f64 - 50.0)
            .collect();
        let o = order_track(&x, 1000.0, 3.0, |_| 12.5).unwrap();
        for (a, b) in o.samples.iter().zip(&x) {
            assert!((a - b).abs() < 1e-9, "{a} {b}");
        }
        assert!((o.mean_hz - 12.5).abs() < 1e-12);
        assert!(order_track(&x[..3], 1000.0, 0.0, |_| 1.0).is_none());
        assert!(order_track(&x, 1000.0, 0.0, |t| 0.5 - t).is_none());
    }
}
