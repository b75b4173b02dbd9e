use wearsim_core::*;
fn main() {
    for name in presets::NAMES {
        let cfg = presets::by_name(name).unwrap();
        match Model::new_checked(cfg.clone()) {
            Ok(m) => {
                let eq = m.equilibrium();
                println!("{name}: y0={:.3e} kc0={:.3e} fn={:.1} zeta={:.3} R={} h={:.2e} Nw={} qmax={:.1} dmax={:.2e} a={:.2e} b={:.2e} K={:.3e}",
                    eq.y0, eq.contact_stiffness, m.natural_frequency_hz(), m.damping_ratio(), m.oversample(), m.step_size(), m.waviness_order(),
                    eq.reference.q_max, eq.reference.delta_max, eq.reference.a, eq.reference.b, m.contact().stiffness);
                let o = m.orders();
                println!(
                    "   orders ftf {:.5} bpfo {:.4} bpfi {:.4} bsf {:.4}",
                    o.ftf, o.bpfo, o.bpfi, o.bsf
                );
                if let Some(d) = cfg.defect {
                    let s = m.defect_shape(&d.topography);
                    println!("   shape {:?}", s);
                }
                let mut st: State<32> = State::new(&m, 1).unwrap();
                let n = (cfg.output_rate * 2.0) as usize;
                let mut buf = vec![Sample::default(); n];
                let t0 = std::time::Instant::now();
                m.fill(&mut st, &mut buf);
                let el = t0.elapsed().as_secs_f64();
                let rms = (buf.iter().map(|s| s.accel * s.accel).sum::<f64>() / n as f64).sqrt();
                println!(
                    "   2 s sim in {:.3}s rtf={:.1} ns/step={:.1} rms={:.4} max={:.4}",
                    el,
                    2.0 / el,
                    el * 1e9 / (st.steps() as f64),
                    rms,
                    buf.iter().map(|s| s.accel.abs()).fold(0.0, f64::max)
                );
            }
            Err(e) => println!("{name}: ERR {e}"),
        }
    }
}
