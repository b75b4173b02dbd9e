//! The per-life figures: onset, trajectory distance, end ratio and life ratio of a
//! simulated life against a measured one.

use super::*;
use crate::life::ims::GRID;

/// Share of life at the end whose median is the end level (–).
pub const END_SHARE: f64 = 0.05;

/// Figures of one life (see the module docs for what each is).
#[derive(Debug, Clone, Serialize)]
pub struct LifeFigures {
    /// Record id.
    pub id: String,
    /// `calibration` or `held-out`.
    pub role: String,
    /// Onset, fraction of the record.
    pub onset_measured: Option<f64>,
    /// Onset, fraction of the simulated life ([`Frame::Life`]) or of the record
    /// ([`Frame::Record`]).
    pub onset_simulated: Option<f64>,
    /// |simulated − measured| onset (fraction).
    pub onset_error: Option<f64>,
    /// Running hours from onset to the end of the record.
    pub onset_to_failure_h_measured: Option<f64>,
    /// Hours (at 2000 rpm) from the simulated onset to failure (on [`Frame::Record`], an
    /// onset before the simulated life's start reads as the record's start).
    pub onset_to_failure_h_simulated: Option<f64>,
    /// Trajectory distance (dB RMS).
    pub distance_db_rms: f64,
    /// End value over first-half median, measured.
    pub end_ratio_measured: f64,
    /// The same, simulated.
    pub end_ratio_simulated: f64,
    /// Simulated over measured end ratio.
    pub end_ratio_factor: f64,
    /// Median over the last [`END_SHARE`] of life of the normalised curve, measured (a
    /// figure that does not hang on the one last window; reported, not judged).
    pub end_level_measured: f64,
    /// The same, simulated.
    pub end_level_simulated: f64,
    /// Simulated revolutions over measured running revolutions.
    pub life_ratio: f64,
    /// Measured steady level: median of the first half (record unit, not stated by IMS:
    /// volts or g of a 100 mV/g PCB 353B33).
    pub steady_measured: f64,
    /// Simulated steady level at the sensor (m/s²), the same median.
    pub steady_simulated: f64,
    /// Simulated end level at the sensor (m/s²).
    pub end_simulated_abs: f64,
    /// Measurement floor of the simulated life (m/s² RMS, white).
    pub floor: f64,
    /// Simulated stage onsets (fraction of life).
    pub stages: Vec<(String, f64)>,
}

/// Median of a normalised curve over its last [`END_SHARE`] of life.
pub fn end_level(c: &Curve) -> f64 {
    median(
        c.t.iter()
            .zip(&c.rms)
            .filter(|(t, _)| **t >= 1.0 - END_SHARE)
            .map(|(_, v)| *v)
            .collect(),
    )
}

/// A curve on hours before failure, mapped to `1 − h / span` so that the fraction-of-life
/// tools read it (0 = `span` hours before failure, 1 = failure); `life_h` is the hours of
/// the life `c` spans from 0 to 1. Points before the span's start keep their place (t < 0).
pub fn on_hours(c: &Curve, life_h: f64, span: f64) -> Curve {
    let t =
        c.t.iter()
            .map(|t| 1.0 - (1.0 - t) * life_h / span)
            .collect();
    Curve {
        t,
        rms: c.rms.clone(),
    }
}

/// Normalised curve `c` of a life of `life_h` hours on a record of `span_h` running hours
/// that ends at the same failure ([`Frame::Record`]): [`on_hours`], cut at the record's
/// start; a life shorter than the record is read at its own steady level (1 on `c`, the
/// median of its first half) before its start, at its own window spacing (at least
/// [`GRID`] points' worth), so that the record's early part has a steady band to test
/// the onset against; then normalised again on the record's first half.
pub fn on_record(c: &Curve, life_h: f64, span_h: f64) -> Curve {
    let h = on_hours(c, life_h, span_h);
    let (mut t, mut v): (Vec<f64>, Vec<f64>) =
        h.t.iter()
            .zip(&h.rms)
            .filter(|(t, _)| **t >= 0.0)
            .map(|(t, v)| (*t, *v))
            .unzip();
    let start = t.first().copied().unwrap_or(1.0);
    if start > 0.0 {
        let spacing = t
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(f64::INFINITY, f64::min)
            .max(start / GRID as f64);
        let n = ((start / spacing).ceil() as usize).clamp(1, 100 * GRID);
        let mut pt: Vec<f64> = (0..n).map(|i| start * i as f64 / n as f64).collect();
        let mut pv = vec![1.0; n];
        pt.append(&mut t);
        pv.append(&mut v);
        (t, v) = (pt, pv);
    }
    normalise(t, v)
}

/// The figures of simulated life `s` against measured `m` on time line `frame`.
pub fn figures(m: &MeasuredRecord, s: &SimLife, role: &str, frame: Frame) -> LifeFigures {
    let life_h = s.life / revs_per_hour();
    let (sc, span_h) = match frame {
        Frame::Life => (s.curve(m.record.feature), life_h),
        Frame::Record => (
            on_record(&s.curve(m.record.feature), life_h, m.running_h),
            m.running_h,
        ),
    };
    let sc_raw = match m.record.feature {
        Feature::Rms => &s.rms,
        Feature::MeanAbs => &s.mean_abs,
    };
    let (om, os) = (onset(&m.curve), onset(&sc));
    let em = m.curve.rms.last().copied().unwrap_or(1.0);
    let es = sc.rms.last().copied().unwrap_or(1.0);
    LifeFigures {
        id: m.record.id.into(),
        role: role.into(),
        onset_measured: om,
        onset_simulated: os,
        onset_error: om.zip(os).map(|(a, b)| (a - b).abs()),
        onset_to_failure_h_measured: om.map(|o| (1.0 - o) * m.running_h),
        onset_to_failure_h_simulated: os.map(|o| (1.0 - o) * span_h),
        distance_db_rms: distance_db(&sc, &m.curve),
        end_ratio_measured: em,
        end_ratio_simulated: es,
        end_ratio_factor: es / em,
        end_level_measured: end_level(&m.curve),
        end_level_simulated: end_level(&sc),
        life_ratio: s.life / (m.running_h * revs_per_hour()),
        steady_measured: m.steady,
        steady_simulated: sc_raw.last().copied().unwrap_or(0.0) / es.max(1e-300),
        end_simulated_abs: sc_raw.last().copied().unwrap_or(0.0),
        floor: 0.0,
        stages: s.stages.clone(),
    }
}

/// Median of `v` (NaN when empty). Unlike [`crate::analysis::stats::median`] it keeps
/// non-finite values (sorted by `total_cmp`): an infinite end factor (a record ending at
/// level 0) must fail the acceptance medians, not drop out of them.
pub(super) fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n == 0 {
        return f64::NAN;
    }
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A life of `life_h` hours at level 1 that steps to 5 at `onset` of its life, one
    /// window every 1 % of life.
    fn stepped(onset: f64) -> Curve {
        let t: Vec<f64> = (1..=100).map(|i| i as f64 / 100.0).collect();
        let r = t
            .iter()
            .map(|t| if *t >= onset { 5.0 } else { 1.0 })
            .collect();
        normalise(t, r)
    }

    /// Aligned at failure, the hours from onset to failure carry over: a 100 h life that
    /// climbs 20 h before failure reads on a 400 h record as an onset at 1 − 20/400, on an
    /// 80 h record (the life cut at the record's start) at 1 − 20/80; the steady level
    /// before a short life's start is its own, so the record's normalisation stays 1.
    #[test]
    fn a_life_on_the_record_keeps_its_hours_before_failure() {
        let c = stepped(0.8);
        for (span, want) in [(400.0, 0.95), (80.0, 0.75), (100.0, 0.8)] {
            let r = on_record(&c, 100.0, span);
            assert_eq!(r.t.first().copied(), Some(0.0), "{span}");
            assert_eq!(r.t.last().copied(), Some(1.0), "{span}");
            assert!(r.t.windows(2).all(|w| w[1] > w[0]), "{span}");
            let o = onset(&r).unwrap();
            // One window of the life (1 h) on the record's scale.
            assert!((o - want).abs() <= 1.0 / span + 1e-12, "{span}: {o}");
            assert_eq!(r.rms.last().copied(), Some(5.0), "{span}");
            assert_eq!(end_level(&r), 5.0, "{span}");
        }
        // The part of a long record before a short life is read at the life's steady level.
        let r = on_record(&c, 100.0, 400.0);
        assert!(r.t.iter().zip(&r.rms).all(|(t, v)| *t >= 0.95 || *v == 1.0));
        assert!(r.t.iter().filter(|t| **t < 0.75).count() >= 100);
    }
}
