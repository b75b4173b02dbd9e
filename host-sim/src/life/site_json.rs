//! The wear site of a life run as output names it: which surface, its pass frequency
//! (name, order and Hz) and the Hertz contact its pressures come from
//! (`wearsim_core::wear::Site`; README "Wear life", docs/life-sites.md).

use super::LifeRun;
use serde_json::json;
use wearsim_core::contact::ElementContact;

/// `{"name", "pass_frequency", "passes_per_rev", "pass_frequency_hz", "contact"}` of
/// `run`'s wear site at its shaft speed.
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
    json!({
        "name": site.name(),
        "pass_frequency": site.pass_frequency_name(),
        "passes_per_rev": run.life.passes_per_rev(),
        "pass_frequency_hz": run.life.passes_per_rev() * run.shaft_hz,
        "contact": name,
    })
}
