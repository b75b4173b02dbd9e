//! The wear site of a life run as output names it: which surface, its pass frequency
//! (name, order and Hz) and the Hertz contact its pressures come from
//! (`wearsim_core::wear::Site`; README "Wear life", docs/life-sites.md), with the ring
//! ratings of the bearing's two raceway contacts (`wearsim_core::wear::RingRatings`).

use super::LifeRun;
use serde_json::json;
use wearsim_core::contact::ElementContact;
use wearsim_core::wear::RingRatings;

/// `{"name", "pass_frequency", "passes_per_rev", "pass_frequency_hz", "contact",
/// "reference_pressure_pa", "calibration_load_n", "ratings"}` of `run`'s wear site at its shaft speed. `ratings` (N): the bearing's ISO 281
/// rating `bearing` (the one the fatigue sum uses, for every site), the ring ratings
/// `inner` (`Q_ci`) and `outer` (`Q_ce`), and `site`, the site's own ring's (null for an
/// element); docs/life-sites.md "Ring ratings". `reference_pressure_pa`: the outer contact's
/// static pressure at the calibration load, which normalises the initiation laws, and
/// `calibration_load_n`: the radial load it is taken at (the model's own unless a load
/// scale moved it; docs/life-statistics.md, stop 26).
pub fn site_json(run: &LifeRun) -> serde_json::Value {
    let site = run.life.site();
    let bearing = &run.spec.model.bearing;
    let contact = ElementContact::of(bearing);
    // The element's contact is the more stressed of its two (`Site::contact`).
    let name = if run.life.contact() == contact.outer {
        "outer"
    } else {
        "inner"
    };
    let rings = RingRatings::of(bearing, run.life.rating());
    json!({
        "name": site.name(),
        "pass_frequency": site.pass_frequency_name(),
        "passes_per_rev": run.life.passes_per_rev(),
        "pass_frequency_hz": run.life.passes_per_rev() * run.shaft_hz,
        "contact": name,
        "reference_pressure_pa": run.life.reference_pressure(),
        "calibration_load_n": run.spec.calibration_load.unwrap_or(run.spec.model.radial_load),
        "ratings": {
            "bearing": run.life.rating(),
            "inner": rings.inner,
            "outer": rings.outer,
            "site": rings.of_site(site),
            "fatigue_uses": "bearing",
        },
    })
}
