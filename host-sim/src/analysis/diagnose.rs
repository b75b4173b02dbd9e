//! Calibrated decision on top of the harmonic-family evidence of [`super::faults`]: the
//! *evidence margin* of the leading family (its exclusive score minus the best other family's,
//! dB per searched harmonic — a ratio of spectral heights, so independent of gain, units,
//! DC offset and sample rate) is mapped to a probability that the leading family is the true
//! one by a logistic curve (Platt 1999, "Probabilistic outputs for support vector machines")
//! fitted on the development part of the CWRU data only ([`CALIBRATION`],
//! [`fit_logistic`]). A family is called only when that probability is at least
//! [`CALL_MIN`]; otherwise the call is `None`: a wrong family is worse than no call.

use serde::{Deserialize, Serialize};

/// Logistic calibration `P(correct | margin) = 1 / (1 + exp(-slope (margin - centre)))`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Calibration {
    /// Slope, 1/dB (per dB of evidence margin per searched harmonic).
    pub slope: f64,
    /// Margin at which the leading family is as likely right as wrong, dB per harmonic.
    pub centre: f64,
}

/// The calibration in force: fitted by [`fit_logistic`] on the development part of the CWRU
/// data (drive-end records at 0 and 1 hp, see `crate::cwru_benchmark::Part`), printed by
/// `wearsim cwru-benchmark` as `calibration fitted on development`, and checked against that
/// fit by `host-sim/tests/cwru_benchmark.rs`.
pub const CALIBRATION: Calibration = Calibration {
    slope: 2.195_5,
    centre: 2.209_8,
};

/// Least confidence for which a family is called (fixed a priori, not tuned: a call is made
/// when it is more likely right than wrong).
pub const CALL_MIN: f64 = 0.5;

/// Ridge weight on the slope in [`fit_logistic`] (keeps the fit finite when the development
/// records are separable; fixed a priori).
pub const RIDGE: f64 = 0.05;

/// The logistic probability of `margin` under `cal`, in [0, 1].
pub fn probability(margin: f64, cal: &Calibration) -> f64 {
    let z = cal.slope * (margin - cal.centre);
    if !z.is_finite() {
        return if z > 0.0 { 1.0 } else { 0.0 };
    }
    1.0 / (1.0 + (-z).exp())
}

/// The calibrated call: `(family, confidence)` (`None`: no family called). A leading family whose probability of being
/// right is at least [`CALL_MIN`] is called with that probability as confidence; otherwise
/// the call is `None` with confidence `1 - P` (the probability that calling the leading
/// family, or the best partial evidence, would have been wrong).
pub fn call<F: Copy>(lead: Option<F>, margin: f64, cal: &Calibration) -> (Option<F>, f64) {
    let p = probability(margin, cal);
    match lead {
        Some(f) if p >= CALL_MIN => (Some(f), p),
        _ => (None, 1.0 - p),
    }
}

/// Fit the logistic calibration to `(margin, leading family was right)` pairs by Newton's
/// method on the log-loss plus [`RIDGE`]` × slope²`. Deterministic; fewer than two pairs or a
/// non-finite margin give `None`.
pub fn fit_logistic(samples: &[(f64, bool)]) -> Option<Calibration> {
    if samples.len() < 2 || samples.iter().any(|(m, _)| !m.is_finite()) {
        return None;
    }
    // Parameters z = a m + c; centre = -c / a.
    let (mut a, mut c) = (0.5_f64, 0.0_f64);
    for _ in 0..200 {
        let (mut ga, mut gc) = (2.0 * RIDGE * a, 0.0);
        let (mut haa, mut hac, mut hcc) = (2.0 * RIDGE, 0.0, 1e-9);
        for &(m, y) in samples {
            let p = 1.0 / (1.0 + (-(a * m + c)).exp());
            let r = p - f64::from(u8::from(y));
            ga += r * m;
            gc += r;
            let w = p * (1.0 - p);
            haa += w * m * m;
            hac += w * m;
            hcc += w;
        }
        let det = haa * hcc - hac * hac;
        if !det.is_finite() || det.abs() < 1e-300 {
            break;
        }
        let da = (hcc * ga - hac * gc) / det;
        let dc = (haa * gc - hac * ga) / det;
        a -= da;
        c -= dc;
        if da.abs() < 1e-12 && dc.abs() < 1e-12 {
            break;
        }
    }
    (a.is_finite() && c.is_finite() && a > 0.0).then(|| Calibration {
        slope: a,
        centre: -c / a,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn probability_is_monotone_and_bounded() {
        let cal = Calibration {
            slope: 1.0,
            centre: 3.0,
        };
        assert!((probability(3.0, &cal) - 0.5).abs() < 1e-12);
        assert!(probability(10.0, &cal) > 0.99);
        assert!(probability(-10.0, &cal) < 0.01);
        assert_eq!(probability(f64::INFINITY, &cal), 1.0);
    }

    #[test]
    fn weak_lead_is_not_called() {
        let cal = Calibration {
            slope: 1.0,
            centre: 3.0,
        };
        assert_eq!(call(Some("inner"), 1.0, &cal).0, None);
        assert_eq!(call::<&str>(None, 9.0, &cal).0, None);
        let (f, c) = call(Some("outer"), 8.0, &cal);
        assert_eq!(f, Some("outer"));
        assert!(c > 0.99);
    }

    #[test]
    fn fit_recovers_a_known_curve() {
        // Right above 4 dB, wrong below, with overlap: the centre lands between.
        let s: Vec<(f64, bool)> = (0..40)
            .map(|i| {
                let m = i as f64 * 0.25;
                (m, (m > 4.0) ^ (i % 7 == 0))
            })
            .collect();
        let cal = fit_logistic(&s).expect("fit");
        assert!(cal.centre > 2.5 && cal.centre < 5.5, "{cal:?}");
        assert!(cal.slope > 0.1, "{cal:?}");
        assert!(fit_logistic(&s[..1]).is_none());
    }
}
