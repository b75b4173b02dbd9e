//! Link-time proof that the core has no reachable panic (`README.md`, "no_std discipline").
//!
//! This image is built, never run: its panic handler calls a function that exists nowhere, so
//! the link fails with `undefined symbol: __wearsim_core_reachable_panic` if any path from
//! the entry point can reach a panic after the optimiser (fat LTO, `firmware-stub`'s release
//! profile) has removed every provably dead one. The entry point drives the core's public
//! API — every preset, every effect, validation, the fixed-step model one sample at a time
//! and in blocks, the sensor's counts, checkpoints, lanes, and the wear life with its stage
//! transitions — in both precisions (`wearsim-core` f64 and `wearsim-core-f32`), on inputs
//! hidden from the optimiser by [`core::hint::black_box`], so that no check can be folded
//! away by a constant the firmware happens to use. It is the technique of the `panic-never`
//! crate; a failing link names the function that still holds a panic path
//! (`llvm-objdump -d` of the normal build shows its callers of `core::panicking`).
//!
//! Build (inside `firmware-stub/`): `cargo build --release -p wearsim-nopanic --target
//! thumbv7em-none-eabihf` (and `thumbv6m-none-eabi`, the M0); `scripts/test-all.sh` does both.
#![cfg_attr(target_os = "none", no_std)]
#![cfg_attr(target_os = "none", no_main)]

#[cfg(target_os = "none")]
mod image {
    use core::hint::black_box;
    use cortex_m_rt::entry;

    /// Drives one precision's core through its public API on opaque inputs.
    macro_rules! exercise {
        ($core:ident, $nb:expr) => {{
            use $core::effects::{EffectKind, MAX_PARAMS};
            use $core::forces::defect::{DefectLocation, DefectModel};
            use $core::integrate::IntegratorKind;
            use $core::model::LaneGroup;
            use $core::sensor::SensorScale;
            use $core::speed::{SpeedPoint, SpeedProfile, MAX_SPEED_POINTS};
            use $core::wear::{Life, LifeConfig, PassMeter, Site};
            use $core::{presets, Channels, Model, Real, Sample, State};

            let names = presets::NAMES;
            let name = names
                .get(black_box(0usize) % names.len())
                .copied()
                .unwrap_or("");
            let Some(mut cfg) = presets::by_name(black_box(name)) else {
                return 1;
            };
            cfg.output_rate = black_box(cfg.output_rate);
            cfg.radial_load = black_box(cfg.radial_load);
            cfg.clearance = black_box(cfg.clearance);
            cfg.structure.mass = black_box(cfg.structure.mass);
            cfg.structure.stiffness = black_box(cfg.structure.stiffness);
            cfg.structure.damping = black_box(cfg.structure.damping);
            cfg.oversample = black_box(cfg.oversample);
            cfg.integrator = match black_box(0u8) {
                0 => IntegratorKind::Rk4,
                1 => IntegratorKind::ExactZoh,
                _ => IntegratorKind::ExactFoh,
            };
            cfg.channels = if black_box(true) {
                Channels::All
            } else {
                Channels::Acceleration
            };
            let hz = black_box(cfg.speed.shaft_hz(0.0));
            cfg.speed = match black_box(0u8) {
                0 => SpeedProfile::Constant(hz),
                1 => SpeedProfile::Ramp {
                    from_hz: hz,
                    to_hz: black_box(2.0 * hz),
                    duration: black_box(1.0),
                },
                _ => {
                    let mut table = heapless::Vec::new();
                    for i in 0..black_box(MAX_SPEED_POINTS) {
                        let point = SpeedPoint {
                            t: black_box(i as Real),
                            shaft_hz: black_box(hz),
                        };
                        if table.push(point).is_err() {
                            break;
                        }
                    }
                    SpeedProfile::Table(table)
                }
            };
            if let Some(d) = cfg.defect.as_mut() {
                let angle = black_box(1.0);
                d.location = match black_box(0u8) {
                    0 => DefectLocation::OuterRace { angle },
                    1 => DefectLocation::InnerRace { angle },
                    _ => DefectLocation::Ball {
                        element: black_box(0),
                        phase: angle,
                    },
                };
                d.model = match black_box(0u8) {
                    0 => DefectModel::FiveStep,
                    1 => DefectModel::Deflection,
                    2 => DefectModel::Sassi,
                    _ => DefectModel::Impulse,
                };
                d.topography.length = black_box(d.topography.length);
            }
            for kind in EffectKind::ALL {
                if black_box(true) {
                    let spec = kind.spec();
                    let mut values: [Real; MAX_PARAMS] = [0.0; MAX_PARAMS];
                    for (v, p) in values.iter_mut().zip(spec.params.iter()) {
                        *v = black_box(p.default as Real);
                    }
                    let n = black_box(spec.params.len()).min(MAX_PARAMS);
                    let _ = cfg.effects.set(kind, values.get(..n).unwrap_or(&[]));
                }
            }
            let base = cfg.clone();
            let Ok(model) = Model::new_checked(cfg) else {
                return 2;
            };
            let Ok(mut st) = State::<$nb>::new(&model, black_box(1)) else {
                return 3;
            };
            let mut acc: Real = 0.0;
            for _ in 0..black_box(64u32) {
                if let Some(s) = model.step(&mut st) {
                    acc += s.accel;
                }
            }
            let mut block = [Sample::default(); 64];
            let n = black_box(64usize).min(block.len());
            let mut observed: u32 = 0;
            let filled =
                model.fill_observed(&mut st, block.get_mut(..n).unwrap_or(&mut []), |_| {
                    observed += 1
                });
            acc += observed as Real;
            for s in block.iter().take(filled) {
                acc += s.accel + s.vel + s.disp;
            }
            if let Ok(scale) = SensorScale::new_checked(SensorScale {
                full_scale_g: black_box(16.0),
                bits: black_box(16),
            }) {
                acc += scale.counts(black_box(acc)) as Real;
                acc += scale.accel(black_box(7));
            }

            // Checkpoint round trip.
            static mut BYTES: [u8; 65536] = [0; 65536];
            // SAFETY: the only reference to BYTES, taken once in a single-threaded image.
            let bytes: &mut [u8; 65536] = unsafe { &mut *core::ptr::addr_of_mut!(BYTES) };
            let cap = black_box(bytes.len()).min(bytes.len());
            if let Ok(len) = st.encode(bytes.get_mut(..cap).unwrap_or(&mut [])) {
                if let Ok(mut back) = State::<$nb>::decode(&model, bytes.get(..len).unwrap_or(&[]))
                {
                    if let Some(s) = model.step(&mut back) {
                        acc += s.accel;
                    }
                }
            }

            // Four lanes stepped together.
            // The last lane at its own speed when the optimiser cannot rule it out (the
            // per-lane kinematics path).
            let mut own = base.clone();
            if black_box(true) {
                own.speed = SpeedProfile::Constant(black_box(1.01) * base.speed.shaft_hz(0.0));
            }
            let last = Model::new_checked(own).unwrap_or_else(|_| model.clone());
            let models = [model.clone(), model.clone(), model.clone(), last];
            let seeds = [black_box(1), 2, 3, 4];
            if let Ok(mut group) = LaneGroup::<4, $nb>::new_checked(&models, &seeds) {
                let mut out = [[Sample::default(); 4]; 16];
                let k = group.fill(&mut out);
                for row in out.iter().take(k) {
                    for s in row {
                        acc += s.accel;
                    }
                }
                if let Some(row) = group.step() {
                    acc += row[0].accel;
                }
            }

            // The wear life: measured pass loads advance the stages; each transition
            // rebuilds the model for the new topography.
            if Life::check_base(&base).is_ok() {
                let site = Site::of(base.defect.as_ref().map(|d| &d.location));
                let q = model.static_reference().q_max;
                let cfg = LifeConfig {
                    running_in: black_box(1.0),
                    ..LifeConfig::DEFAULT
                };
                if let Ok(life) = Life::new_checked(cfg, &base.bearing, q, site) {
                    let mut ls = life.initial_state(black_box(5));
                    let mut meter = PassMeter::new(site, &base.bearing);
                    for _ in 0..black_box(256u32) {
                        let _ = model.step(&mut st);
                        meter.observe(st.stats(), st.shaft_angle(), st.cage_angle());
                    }
                    let loads = meter.loads();
                    for _ in 0..black_box(8u32) {
                        let adv = life.advance(&mut ls, black_box(1.0e6), &loads);
                        acc += adv.revs;
                        if adv.transition.is_some() {
                            if let Ok(m) = Model::new_checked(life.model_config(&base, &ls)) {
                                if let Some(t) = ls.topography {
                                    let _ = st.set_topography(&m, t);
                                }
                                if let Some(s) = m.step(&mut st) {
                                    acc += s.accel;
                                }
                            }
                        }
                    }
                    acc += life.lambda_now(&ls) + life.rating();
                }
            }
            black_box(acc);
            0u32
        }};
    }

    fn f64_core() -> u32 {
        exercise!(wearsim_core_f64, 16)
    }

    fn f32_core() -> u32 {
        exercise!(wearsim_core, 16)
    }

    #[entry]
    fn main() -> ! {
        black_box(f64_core());
        black_box(f32_core());
        loop {
            cortex_m::asm::wfi();
        }
    }

    #[panic_handler]
    fn panic(_info: &core::panic::PanicInfo) -> ! {
        extern "Rust" {
            // Defined nowhere: linking fails if a panic is reachable.
            fn __wearsim_core_reachable_panic() -> !;
        }
        // SAFETY: never called in an image that links; see the module documentation.
        unsafe { __wearsim_core_reachable_panic() }
    }
}

#[cfg(not(target_os = "none"))]
fn main() {
    eprintln!(
        "wearsim-nopanic is a link-time check for a Cortex-M target: build it with \
         --release --target thumbv7em-none-eabihf inside firmware-stub/ (see its doc comment)"
    );
    std::process::exit(2);
}
