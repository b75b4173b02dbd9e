use wearsim_core::wear::LifeConfig;
use wearsim_host::life::{LifeRun, LifeSpec};
fn main() {
    let model = wearsim_core::presets::by_name("thesis-61810").unwrap();
    let spec = LifeSpec {
        model,
        life: LifeConfig::DEFAULT,
        seed: 1,
        snapshot_every: 20_000.0,
        window: 0.25,
        settle: 0.05,
    };
    let run = LifeRun::new(spec).unwrap();
    println!("C = {:.0} N", run.life.rating());
    let r = run.run_snapshots(|_, _| {}).unwrap();
    println!(
        "windows {} wall {:.2}s scatter {:.3}",
        r.windows, r.wall_s, r.state.scatter
    );
    for e in &r.state.events {
        println!(
            "{:>12.0} {:?} h={:.2e} L={:.2e} n={} crack={:.2e}",
            e.cycles,
            e.stage,
            e.topography.asperity_height,
            e.topography.length,
            e.topography.count,
            e.crack
        );
    }
    for s in r.snapshots.iter().step_by((r.snapshots.len() / 40).max(1)) {
        println!("{:>10.0} {:<18} rms {:.4} kurt {:.2} nat {:.4} fault {:.4} zoneQ {:.1} edgeQ {:.1} h {:.2e}", s.cycles, s.stage, s.features.rms, s.features.kurtosis, s.features.zone_natural, s.features.fault_peak, s.zone_load, s.edge_load, s.asperity);
    }
}
