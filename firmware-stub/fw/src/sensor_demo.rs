//! Register-level demo at boot: the unmodified crates.io `ism330dhcx` driver configures the
//! virtual ISM330DHCX (`wearsim-vsensor`) over `embedded-hal` I2C and reads simulated samples
//! through the data registers and the FIFO. Results go to the defmt log, where the host test
//! checks them against the host run.
use super::{fatal, State, NB};
use ism330dhcx::fifo::Value;
use ism330dhcx::registers::{BdrXl, FifoMode, FsXl, OdrXl};
use ism330dhcx::{Accelerometer, Fifo, Ism330Dhcx};
use wearsim_core::Model;
use wearsim_vsensor::{Ism330Model, ADDRESS_SA0_HIGH};

/// Samples read through the data registers.
const READS: u32 = 8;
/// Simulator samples fed before reading (past the start-up transient, 30 ms).
pub const WARMUP: u32 = 600;

/// Runs the demo with a fresh model state (left in `state`, to be replaced by the caller).
pub fn run(model: &Model, seed: u64, state: &mut Option<State<NB>>) {
    *state = State::new(model, seed).ok();
    let Some(st) = state.as_mut() else {
        fatal("state capacity")
    };
    let mut dev = Ism330Model::new(ADDRESS_SA0_HIGH, model.config().output_rate);
    let mut s = match Ism330Dhcx::new(&mut dev) {
        Ok(s) => s,
        Err(_) => fatal("sensor: WHO_AM_I rejected by the driver"),
    };
    let configured = s.set_accel_scale(&mut dev, FsXl::G16).is_ok()
        && s.set_accel_odr(&mut dev, OdrXl::Hz6667).is_ok()
        && s.set_fifo_accel_batch_rate(&mut dev, BdrXl::Hz6667).is_ok();
    if !configured {
        fatal("sensor: configuration failed");
    }
    let fs = match s.get_accel_scale(&mut dev) {
        Ok(FsXl::G16) => 16u8,
        Ok(FsXl::G8) => 8,
        Ok(FsXl::G4) => 4,
        Ok(FsXl::G2) => 2,
        Err(_) => 0,
    };
    defmt::info!(
        "sensor: ism330dhcx who_am_i ok, fs={=u8}g odr_hz={=f32}",
        fs,
        dev.odr_hz() as f32
    );
    let mut index = 0u32;
    let mut reads = 0u32;
    while index < WARMUP {
        if let Some(x) = model.step(st) {
            dev.push_sample(x.accel);
            index += 1;
        }
    }
    // Batch into the FIFO from here on (continuous mode).
    if s.set_fifo_mode(&mut dev, FifoMode::Continuous).is_err() {
        fatal("sensor: FIFO configuration failed");
    }
    let base = dev.output_samples;
    while reads < READS {
        let sample = loop {
            if let Some(x) = model.step(st) {
                break x;
            }
        };
        dev.push_sample(sample.accel);
        index += 1;
        if dev.output_samples > base + reads {
            let Ok(v) = s.get_accelerometer(&mut dev) else {
                fatal("sensor: data read failed")
            };
            defmt::info!(
                "sensor sample {=u32}: z_counts={=i16} z_m_s2={=f32}",
                index - 1,
                v.count()[2],
                v.as_m_ss()[2]
            );
            reads += 1;
        }
    }
    let n = s.get_fifo_sample_count(&mut dev).unwrap_or(0);
    let first = match s.fifo_pop(&mut dev) {
        Ok(Value::Accel(v)) => v.count()[2],
        _ => fatal("sensor: FIFO word is not an accelerometer word"),
    };
    defmt::info!("sensor fifo: {=u16} words, first z_counts={=i16}", n, first);
}
