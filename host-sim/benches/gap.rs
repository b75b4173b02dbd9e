//! Cost of one objective evaluation of the sim-to-real fits (issue 6): a matched
//! simulation of 1 s of the CWRU 6205 drive-end bearing with a 0.007 in inner-race defect
//! at 12 kHz (after its settling time), and the feature cells of its 8 segments against a
//! reference. A `wearsim gap` run costs a few thousand of these (its JSON says how many);
//! the whole-run figure is `scripts/bench-gap.sh`.
//! Run: `cargo bench -p wearsim-host --bench gap`.

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use wearsim_core::effects::Effects;
use wearsim_host::gap::matched::{Matched, MEMO};
use wearsim_host::gap::memo::Memo;
use wearsim_host::gap::validate::{record, scenario, spec_of};
use wearsim_host::gap::Reference;

fn bench(c: &mut Criterion) {
    let cfg = scenario().expect("cwru-6205-de preset");
    let spec = spec_of(&cfg).expect("spec");
    let n = spec.fs as usize;
    let real = record(&cfg, 7, n).expect("reference record");
    let m = Matched {
        label: "bench".into(),
        base: cfg,
        reference: Reference::new(&real, &spec).expect("reference cells"),
        samples: n,
        seed: 1,
        real: vec![],
        memo: Memo::new(MEMO),
    };
    let mut g = c.benchmark_group("gap_1s_12k");
    g.throughput(Throughput::Elements(n as u64));
    g.sample_size(20);
    g.bench_function("simulate", |b| {
        b.iter(|| m.simulate(black_box(&Effects::NONE)).expect("simulation"))
    });
    g.bench_function("cells_8_segments", |b| {
        b.iter(|| m.reference.sim_means(black_box(&real)).expect("cells"))
    });
    // Simulation and cells, past the memo (which would answer every repeat).
    g.bench_function("evaluation", |b| {
        b.iter(|| {
            let x = m.simulate(black_box(&Effects::NONE)).expect("simulation");
            m.reference.sim_means(&x).expect("cells")
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
