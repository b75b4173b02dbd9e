//! The shaft speed over an interval of a run (`SpeedProfile::over`): time average and
//! extremes of a piecewise-linear profile against their closed forms (the average of a
//! linear segment is the mean of its ends; a table's extremes lie on its knots or on the
//! interval's ends). A record starts at the settle time, so its speed is this span, not
//! the profile's value at 0.
// Written against `Real` (f64 or f32 by package): casts that are no-ops in one precision are
// needed in the other.
#![allow(clippy::unnecessary_cast)]

use wearsim_core::speed::{SpeedPoint, SpeedProfile};
use wearsim_core::Real;

fn close(a: Real, b: Real) -> bool {
    (a - b).abs() <= 1e-5 * b.abs().max(1.0)
}

/// 10 Hz → 30 Hz over 2 s, then 30 Hz.
fn ramp() -> SpeedProfile {
    SpeedProfile::Ramp {
        from_hz: 10.0,
        to_hz: 30.0,
        duration: 2.0,
    }
}

#[test]
fn a_constant_speed_is_its_own_span() {
    // Exactly, over any interval (a sidecar's `rpm` of a constant-speed run is the
    // configured speed, not 1796.9999999999998).
    for (t0, t1) in [(0.5, 1.5), (0.05, 0.95), (0.05, 3.05), (0.0, 1e-3)] {
        let s = SpeedProfile::Constant(29.95).over(t0, t1);
        assert_eq!((s.mean_hz, s.min_hz, s.max_hz), (29.95, 29.95, 29.95));
    }
}

#[test]
fn a_ramp_seen_after_its_start_is_averaged_over_the_record_only() {
    // 10 Hz → 30 Hz over 2 s; a record from 1 s to 3 s sees 20 → 30 Hz then 30 Hz:
    // mean = (1 s · 25 Hz + 1 s · 30 Hz) / 2 s = 27.5 Hz.
    let r = ramp();
    let s = r.over(1.0, 3.0);
    assert!(close(s.mean_hz, 27.5), "{s:?}");
    assert!(close(s.min_hz, 20.0), "{s:?}");
    assert!(close(s.max_hz, 30.0), "{s:?}");
    // Wholly after the ramp: constant, exactly.
    let s = r.over(2.5, 4.1);
    assert_eq!((s.mean_hz, s.min_hz, s.max_hz), (30.0, 30.0, 30.0));
    // Wholly inside: the mean of the ends.
    let s = r.over(0.5, 1.5);
    assert!(close(s.mean_hz, 20.0) && close(s.min_hz, 15.0) && close(s.max_hz, 25.0));
}

#[test]
fn a_table_has_its_extremes_on_knots_inside_the_interval() {
    // 20 Hz at 0 s, up to 40 Hz at 1 s, down to 10 Hz at 3 s; record from 0.5 s to 2 s:
    // 30 → 40 Hz over 0.5 s (mean 35), 40 → 25 Hz over 1 s (mean 32.5):
    // (0.5·35 + 1·32.5)/1.5 = 33.333 Hz; min 25 (the end), max 40 (the knot).
    let mut pts = heapless::Vec::new();
    for (t, f) in [(0.0, 20.0), (1.0, 40.0), (3.0, 10.0)] {
        pts.push(SpeedPoint { t, shaft_hz: f }).unwrap();
    }
    let s = SpeedProfile::Table(pts).over(0.5, 2.0);
    assert!(close(s.mean_hz, 100.0 / 3.0), "{s:?}");
    assert!(close(s.min_hz, 25.0), "{s:?}");
    assert!(close(s.max_hz, 40.0), "{s:?}");
}

#[test]
fn an_empty_interval_gives_the_speed_at_its_start() {
    let r = ramp();
    let s = r.over(1.0, 1.0);
    assert!(close(s.mean_hz, 20.0) && s.min_hz == s.mean_hz && s.max_hz == s.mean_hz);
}
