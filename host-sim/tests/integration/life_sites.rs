//! `wearsim life` per wear site (issue 14): the JSON on stdout and `life-summary.json` name
//! the site, its pass frequency (order and Hz) and its contact. In the dynamic runs the
//! inner-race defect turns with the shaft through the load zone, so the element loads
//! measured over it are lower than over an outer-race defect held at the load-zone centre:
//! that competes with the inner race's higher pass rate and pressure (core/tests/life_sites.rs
//! isolates those at equal loads), and the inner life is not necessarily the shorter one.

use crate::support;
use std::path::Path;
use wearsim_core::kinematics::FaultOrders;

/// Runs a life with the defect at `location`; returns stdout JSON, the summary and the
/// mean defect-edge load (N) of the dent-smoothing snapshots.
fn life(dir: &Path, location: &str) -> (serde_json::Value, serde_json::Value, f64) {
    let (stdout, summary, out) =
        support::thesis_life(dir, location, &format!("location = \"{location}\""));
    let text = std::fs::read_to_string(out.join("life-features.csv")).unwrap();
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |n: &str| head.iter().position(|h| *h == n).unwrap();
    let (stage, edge) = (col("stage"), col("edge_load_n"));
    let loads: Vec<f64> = lines
        .map(|l| l.split(',').collect::<Vec<_>>())
        .filter(|r| r[stage] == "dent-smoothing")
        .map(|r| r[edge].parse().unwrap())
        .collect();
    assert!(loads.len() >= 3, "{location}: {} snapshots", loads.len());
    let mean = loads.iter().sum::<f64>() / loads.len() as f64;
    (stdout, summary, mean)
}

#[test]
fn life_names_its_site_and_measures_its_own_defect_loads() {
    let dir = tempfile::tempdir().unwrap();
    let model = wearsim_core::presets::by_name("thesis-61810").unwrap();
    let orders = FaultOrders::of(&model.bearing);
    let f_r = model.speed.shaft_hz(0.0);
    let (outer, outer_summary, edge_o) = life(dir.path(), "outer");
    let (inner, inner_summary, edge_i) = life(dir.path(), "inner");
    for (v, summary, name, freq, order, contact) in [
        (
            &outer,
            &outer_summary,
            "outer_race",
            "BPFO",
            orders.bpfo,
            "outer",
        ),
        (
            &inner,
            &inner_summary,
            "inner_race",
            "BPFI",
            orders.bpfi,
            "inner",
        ),
    ] {
        let s = &v["site"];
        assert_eq!(s, &summary["site"]);
        assert_eq!(s["name"], name);
        assert_eq!(s["pass_frequency"], freq);
        assert_eq!(s["contact"], contact);
        // The site's own ring rating (reported; the fatigue sum uses the bearing's).
        let r = &s["ratings"];
        assert_eq!(r["site"], r[contact]);
        assert_eq!(r["fatigue_uses"], "bearing");
        // The initiation laws' reference: the outer contact at the preset's own load (no
        // load scale), in the GPa range of a loaded ball contact.
        assert_eq!(s["calibration_load_n"].as_f64(), Some(model.radial_load));
        let p_ref = s["reference_pressure_pa"].as_f64().unwrap();
        assert!((0.3e9..5e9).contains(&p_ref), "{name}: {p_ref} Pa");
        assert_eq!(
            s["reference_pressure_pa"],
            outer["site"]["reference_pressure_pa"]
        );
        assert!(r["inner"].as_f64().unwrap() < r["outer"].as_f64().unwrap());
        let n = s["passes_per_rev"].as_f64().unwrap();
        assert!((n / order - 1.0).abs() < 1e-9, "{name}: {n} vs {order}");
        let hz = s["pass_frequency_hz"].as_f64().unwrap();
        assert!((hz / (order * f_r) - 1.0).abs() < 1e-9, "{name}: {hz}");
    }
    let life_o = outer["cycles_to_failure"].as_f64().unwrap();
    let life_i = inner["cycles_to_failure"].as_f64().unwrap();
    println!(
        "thesis-61810 seed 4: outer race {life_o:.4e}, inner race {life_i:.4e} revolutions; \
         dent-smoothing edge load outer {edge_o:.1} N, inner {edge_i:.1} N"
    );
    // Measured 68 N (outer) against 47–55 N (inner): the inner defect is loaded only over
    // the load zone's part of each revolution.
    assert!(edge_i < 0.9 * edge_o, "inner {edge_i} N, outer {edge_o} N");
    assert!(life_o > 1e6 && life_i > 1e6, "{life_o} {life_i}");
}
