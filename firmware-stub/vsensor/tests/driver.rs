//! The unmodified crates.io `ism330dhcx` driver reads simulated samples through the register
//! model: identity, configuration, data registers and FIFO, in the right units.

use ism330dhcx::fifo::Value;
use ism330dhcx::registers::{BdrXl, FifoMode, FsXl, OdrXl};
use ism330dhcx::{Accelerometer, Fifo, Ism330Dhcx};
use wearsim_core::sensor::SensorScale;
use wearsim_core::{presets, Model, State};
use wearsim_vsensor::{Ism330Model, ADDRESS_SA0_HIGH};

fn samples(n: usize) -> Vec<f32> {
    let model = Model::new_checked(presets::by_name("thesis-61810").unwrap()).unwrap();
    let mut st = State::<16>::new(&model, 1).unwrap();
    let mut v = vec![];
    while v.len() < n {
        if let Some(s) = model.step(&mut st) {
            v.push(s.accel);
        }
    }
    v
}

#[test]
fn identity_and_wrong_address() {
    let mut dev = Ism330Model::new(ADDRESS_SA0_HIGH, 20_000.0);
    assert!(Ism330Dhcx::new(&mut dev).is_ok());
    assert!(Ism330Dhcx::new_with_address(&mut dev, 0x6A).is_err());
}

#[test]
fn configuration_reads_back_through_the_driver() {
    let mut dev = Ism330Model::new(ADDRESS_SA0_HIGH, 20_000.0);
    let mut s = Ism330Dhcx::new(&mut dev).unwrap();
    s.set_accel_scale(&mut dev, FsXl::G16).unwrap();
    s.set_accel_odr(&mut dev, OdrXl::Hz6667).unwrap();
    assert_eq!(s.get_accel_scale(&mut dev).unwrap(), FsXl::G16);
    assert_eq!(s.get_accel_odr(&mut dev).unwrap(), OdrXl::Hz6667);
    assert_eq!(dev.full_scale_g(), 16.0);
    assert_eq!(dev.odr_hz(), 6667.0);
}

#[test]
fn data_registers_give_samples_in_m_s2() {
    let x = samples(300);
    for (fs, code) in [(16.0f32, FsXl::G16), (8.0, FsXl::G8)] {
        let mut dev = Ism330Model::new(ADDRESS_SA0_HIGH, 20_000.0);
        let mut s = Ism330Dhcx::new(&mut dev).unwrap();
        s.set_accel_scale(&mut dev, code).unwrap();
        s.set_accel_odr(&mut dev, OdrXl::Hz6667).unwrap();
        let scale = SensorScale {
            full_scale_g: fs,
            bits: 16,
        };
        let lsb = fs * 9.80665 / 32768.0;
        let mut checked = 0;
        for (i, a) in x.iter().enumerate() {
            dev.push_sample(*a);
            // 20 kHz / 6667 Hz = 3: samples 2, 5, 8, ... reach the output registers.
            if i % 3 != 2 {
                continue;
            }
            let v = s.get_accelerometer(&mut dev).unwrap();
            assert_eq!(v.count(), [0, 0, scale.counts(*a)], "sample {i}");
            let z = v.as_m_ss()[2];
            if a.abs() >= fs * 9.80665 {
                // Beyond full scale the part saturates (the reference peaks near 13 g).
                assert!(v.count()[2] == i16::MIN || v.count()[2] == i16::MAX, "{i}");
                checked += 1;
                continue;
            }
            // The driver's sensitivity is the datasheet's rounded mg/LSB (0.488 for ±16 g,
            // 0.244 for ±8 g) against FS/32768 exactly: 0.06 % apart, plus one LSB.
            let tol = 1e-3 * a.abs() + 1.5 * lsb;
            assert!((z - a).abs() <= tol, "sample {i}: {z} vs {a} (fs {fs})");
            checked += 1;
        }
        assert_eq!(checked, 100);
    }
}

#[test]
fn fifo_batches_tagged_accelerometer_words() {
    let x = samples(3 * 40);
    let mut dev = Ism330Model::new(ADDRESS_SA0_HIGH, 20_000.0);
    let mut s = Ism330Dhcx::new(&mut dev).unwrap();
    s.set_accel_scale(&mut dev, FsXl::G16).unwrap();
    s.set_accel_odr(&mut dev, OdrXl::Hz6667).unwrap();
    s.set_fifo_accel_batch_rate(&mut dev, BdrXl::Hz6667)
        .unwrap();
    s.set_fifo_mode(&mut dev, FifoMode::Continuous).unwrap();
    for a in &x {
        dev.push_sample(*a);
    }
    assert_eq!(s.get_fifo_sample_count(&mut dev).unwrap(), 40);
    let scale = SensorScale {
        full_scale_g: 16.0,
        bits: 16,
    };
    for k in 0..40 {
        match s.fifo_pop(&mut dev).unwrap() {
            Value::Accel(v) => assert_eq!(v.count()[2], scale.counts(x[3 * k + 2]), "word {k}"),
            other => panic!("word {k}: {other:?}"),
        }
    }
    assert_eq!(s.get_fifo_sample_count(&mut dev).unwrap(), 0);
    assert!(matches!(s.fifo_pop(&mut dev).unwrap(), Value::Empty));
}

#[test]
fn fifo_overrun_is_flagged() {
    let mut dev = Ism330Model::new(ADDRESS_SA0_HIGH, 20_000.0);
    let mut s = Ism330Dhcx::new(&mut dev).unwrap();
    s.set_accel_odr(&mut dev, OdrXl::Hz6667).unwrap();
    s.set_fifo_accel_batch_rate(&mut dev, BdrXl::Hz6667)
        .unwrap();
    s.set_fifo_mode(&mut dev, FifoMode::Continuous).unwrap();
    for _ in 0..3 * (wearsim_vsensor::FIFO_WORDS + 5) {
        dev.push_sample(1.0);
    }
    let (_, st2) = s.get_fifo_status(&mut dev).unwrap();
    assert!(st2.fifo_ovr_ia() && st2.fifo_full_ia());
    assert_eq!(dev.fifo_overruns, 5);
}
