//! Criterion benchmark of the dynamic model: one simulated second of the reference
//! scenario (thesis-61810, 20 kHz output) per integrator. Throughput is reported in output
//! samples; the real-time factor is 1 s divided by the measured time.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;
use wearsim_core::integrate::IntegratorKind;
use wearsim_core::{presets, Model, ModelConfig, Sample, State};

fn reference(integrator: IntegratorKind) -> Model {
    let cfg = ModelConfig {
        integrator,
        ..presets::by_name("thesis-61810").expect("preset")
    };
    Model::new_checked(cfg).expect("valid")
}

fn one_second(c: &mut Criterion) {
    let mut g = c.benchmark_group("reference_1s_20kHz");
    g.sample_size(20);
    g.throughput(Throughput::Elements(20_000));
    for (name, kind) in [
        ("exact-foh", IntegratorKind::ExactFoh),
        ("exact-zoh", IntegratorKind::ExactZoh),
        ("rk4", IntegratorKind::Rk4),
    ] {
        let model = reference(kind);
        let mut buf = vec![Sample::default(); 20_000];
        g.bench_function(name, |b| {
            b.iter(|| {
                let mut st: State<32> = State::new(&model, 1).expect("capacity");
                model.fill(&mut st, &mut buf);
                black_box(buf[buf.len() - 1].accel)
            })
        });
    }
    g.finish();
}

criterion_group!(benches, one_second);
criterion_main!(benches);
