//! Throughput of the analysis chain on a 10 s, 48 kHz synthetic record with
//! an outer-race fault: stats + Welch PSD + fast kurtogram + envelope
//! spectrum + fault detection. Run: `cargo bench -p wearsim-host --bench analysis`.

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use wearsim_host::analysis::synth::FaultSignal;
use wearsim_host::analysis::{
    detect_fault, envelope_spectrum, fast_kurtogram, stats, welch_psd, DetectParams, FaultFamily,
    FaultFrequencies, WelchParams,
};

const FS: f64 = 48_000.0;
const N: usize = 480_000;
const MAX_LEVEL: usize = 6;

fn record(ff: &FaultFrequencies) -> Vec<f64> {
    FaultSignal {
        fs: FS,
        fault_hz: ff.bpfo,
        mod_hz: 0.0,
        mod_depth: 0.0,
        resonance_hz: 3000.0,
        damping: 0.05,
        impulse_amp: 1.0,
        noise_sigma: 0.5,
        seed: 1,
        // 1 % slip: an exactly periodic train is whitened away by the chain's cepstral
        // pre-whitening (`tests/integration/slip_jitter.rs`).
        jitter: 0.01,
    }
    .generate(N)
}

fn bench(c: &mut Criterion) {
    let cfg = wearsim_core::presets::by_name("cwru-6205-de").unwrap();
    let ff: FaultFrequencies =
        wearsim_core::kinematics::FaultOrders::of(&cfg.bearing).at(29.95, 3000.0);
    let x = record(&ff);
    let mut g = c.benchmark_group("analysis_10s_48k");
    g.throughput(Throughput::Elements(N as u64));
    g.sample_size(10);
    g.bench_function("stats", |b| b.iter(|| stats(black_box(&x)).unwrap()));
    g.bench_function("welch_psd", |b| {
        b.iter(|| welch_psd(black_box(&x), FS, &WelchParams::default()).unwrap())
    });
    g.bench_function("fast_kurtogram", |b| {
        b.iter(|| fast_kurtogram(black_box(&x), FS, MAX_LEVEL).unwrap())
    });
    g.bench_function("envelope_spectrum", |b| {
        b.iter(|| envelope_spectrum(black_box(&x), FS, Some((2000.0, 4000.0))).unwrap())
    });
    let env = envelope_spectrum(&x, FS, Some((2000.0, 4000.0))).unwrap();
    g.bench_function("detect_fault", |b| {
        b.iter(|| detect_fault(black_box(&env), &ff, &DetectParams::default()))
    });
    g.bench_function("full_chain", |b| {
        b.iter(|| {
            let x = black_box(&x);
            let s = stats(x).unwrap();
            let psd = welch_psd(x, FS, &WelchParams::default()).unwrap();
            let kg = fast_kurtogram(x, FS, MAX_LEVEL).unwrap();
            let env = envelope_spectrum(x, FS, Some(kg.best_band)).unwrap();
            let d = detect_fault(&env, &ff, &DetectParams::default());
            assert_eq!(d.family, FaultFamily::OuterRace);
            (s.kurtosis, psd.len(), d.score)
        })
    });
    // The whole `wearsim analyze` decision chain (normalisation, kurtogram at the level set
    // by the physical band width, pre-whitening, envelope, calibrated detector, zones).
    let kin = wearsim_host::kinematics::of_preset("cwru-6205-de", 29.95 * 60.0).unwrap();
    let method = wearsim_host::analysis::chain::Method::default();
    g.bench_function("analyze_signal", |b| {
        b.iter(|| {
            // Timing; the call is asserted by `tests/integration/slip_jitter.rs`.
            let a = wearsim_host::analysis::chain::analyze_signal(black_box(&x), FS, &kin, &method)
                .unwrap();
            (a.diagnosis.family, a.diagnosis.confidence)
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
