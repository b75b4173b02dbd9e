//! Defects found by an outside review that ran `gap`, `features` and `life` on records and
//! tables the project's own tests did not have (other sample rates, other labs' layouts,
//! hand-written tables); one test per defect, each named after what must hold.

use wearsim_core::effects::{EffectKind, Effects};
use wearsim_host::gap::space::{space, Context};

/// A record of `m/s^2` at 51.2 kHz with a DC offset made `gap` exit 1 with
/// "sensor.noise = 100.00000000000001 is out of range": the fitted range was clamped to
/// the catalogue's 100, but `lo·(hi/lo)^1` rounded one ulp above it. Every effect's fit
/// space, at both ends, must give values its own range check accepts, whatever the
/// record's level and rate.
#[test]
fn fit_space_ends_stay_inside_the_catalogue_bounds_at_any_level() {
    for fs in [12_000.0, 25_600.0, 48_828.125, 51_200.0, 97_656.25] {
        for k in 0..400 {
            let rms = 10f64.powf(-3.0 + 7.0 * f64::from(k) / 400.0) * 1.000_001_3;
            let ctx = Context {
                fs,
                shaft_hz: 29.95,
                rms,
                mains_hz: 50.0,
                preload_max: 0.5,
            };
            for kind in EffectKind::ALL {
                let sp = space(kind, &ctx);
                for u in [0.0, 1.0] {
                    let coords = vec![u; sp.fitted.len()];
                    let mut fx = Effects::NONE;
                    if let Err(e) = sp.apply(&mut fx, &coords) {
                        panic!("fs {fs}, rms {rms}, u {u}: {e}");
                    }
                }
            }
        }
    }
}
