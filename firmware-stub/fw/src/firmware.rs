//! wearsim firmware stub: the `wearsim-core` model on a Cortex-M (QEMU `mps2-an386` M4F or
//! `mps2-an385` M3) acting as a virtual accelerometer for hardware-in-the-loop tests.
//!
//! * The main loop runs the model and pushes output samples into a bounded ring
//!   (`heapless::spsc::Queue`); TIMER0 ticks at the output rate and its interrupt moves one
//!   sample per tick to the transmit queue. A tick that finds the ring empty is a missed
//!   deadline: counted, flagged in the frame header, logged, never silent.
//! * Frames (`wearsim-frame`) go out on UART0: a start frame, data frames, an end frame.
//! * defmt logs go out through semihosting (`log.rs`: a logger without a panic path).
//! * Scenario at build time: `WEARSIM_PRESET` (default `thesis-61810`), `WEARSIM_SEED`
//!   (default 1), `WEARSIM_SAMPLES` (default 4000); feature `life` for the accelerated-life
//!   scenario, feature `i16-stream` for 16-bit counts instead of f32.
// `Real` is f32 here; the casts document the wire type.
#![allow(clippy::unnecessary_cast)]

#[path = "hw.rs"]
mod hw;
#[path = "log.rs"]
mod log;
#[path = "sensor_demo.rs"]
mod sensor_demo;

use core::cell::RefCell;
use core::sync::atomic::{AtomicBool, AtomicU32, Ordering};

use cortex_m::peripheral::NVIC;
use cortex_m_rt::{entry, exception, ExceptionFrame};
use critical_section::Mutex;
use heapless::spsc::{Consumer, Queue};
use wearsim_core::sensor::SensorScale;
use wearsim_core::{presets, Model, Real, State};
use wearsim_frame as frame;

/// Preset run by this build.
const PRESET: &str = match option_env!("WEARSIM_PRESET") {
    Some(s) => s,
    None => "thesis-61810",
};
/// Seed of the model's generator.
const SEED: u64 = parse_u64(option_env!("WEARSIM_SEED"), 1);
/// Samples to stream (0 = unbounded).
const SAMPLES: u32 = parse_u64(option_env!("WEARSIM_SAMPLES"), 4000) as u32;
/// Samples timed by the boot-time budget measurement.
const BENCH_SAMPLES: u32 = 1000;
/// Samples per data frame.
const FRAME_SAMPLES: usize = 64;
/// Element capacity of the model state.
const NB: usize = 16;
/// Full scale of the 16-bit counts (g): the reference scenario peaks near 10 g.
pub const FULL_SCALE_G: Real = 16.0;

#[cfg(feature = "i16-stream")]
const FORMAT: frame::Format = frame::Format::I16;
#[cfg(not(feature = "i16-stream"))]
const FORMAT: frame::Format = frame::Format::F32;

/// 1: hard-float M4F, 2: soft-float M3.
#[cfg(target_abi = "eabihf")]
const FLAVOUR: u32 = 1;
#[cfg(not(target_abi = "eabihf"))]
const FLAVOUR: u32 = 2;

const fn parse_u64(s: Option<&str>, default: u64) -> u64 {
    let Some(s) = s else { return default };
    let b = s.as_bytes();
    if b.is_empty() {
        return default;
    }
    let mut v: u64 = 0;
    let mut i = 0;
    while i < b.len() {
        let d = b[i];
        if d < b'0' || d > b'9' {
            return default;
        }
        v = v.wrapping_mul(10).wrapping_add((d - b'0') as u64);
        i += 1;
    }
    v
}

/// Ring from the model (main loop) to the pacing interrupt: wire words (f32 bits or i16).
static mut RING: Queue<u32, 256> = Queue::new();
/// Transmit queue from the pacing interrupt to the main loop: (sample index, word). It
/// holds twice the ring, so that everything the ring can release while the main loop is
/// stalled (a life's model rebuild at a stage transition stalled it past the ring's 12.8 ms at
/// 20 kHz: 18 samples were dropped with a queue of 256) fits: a stall then
/// shows as overruns (deadlines the ring could not meet, reported) and never as dropped
/// samples. heapless queues hold N − 1 items: 511 ≥ 255 in the ring + 256 in flight.
static mut TXQ: Queue<(u32, u32), 512> = Queue::new();
static RING_RX: Mutex<RefCell<Option<Consumer<'static, u32>>>> = Mutex::new(RefCell::new(None));
type TxProducer = heapless::spsc::Producer<'static, (u32, u32)>;
static TXQ_TX: Mutex<RefCell<Option<TxProducer>>> = Mutex::new(RefCell::new(None));
/// Samples released by the pacing timer.
static RELEASED: AtomicU32 = AtomicU32::new(0);
/// Missed deadlines: ticks that found the ring empty.
static OVERRUNS: AtomicU32 = AtomicU32::new(0);
/// Samples the interrupt could not queue for transmission (must stay 0).
static TX_DROPS: AtomicU32 = AtomicU32::new(0);
/// Samples the interrupt may release in total.
static LIMIT: AtomicU32 = AtomicU32::new(0);
static OVERRUN_FLAG: AtomicBool = AtomicBool::new(false);

/// Converts a model sample to its wire word.
#[inline(always)]
fn to_wire(accel: Real) -> u32 {
    match FORMAT {
        frame::Format::I16 => SensorScale {
            full_scale_g: FULL_SCALE_G,
            bits: 16,
        }
        .counts(accel) as u16 as u32,
        _ => (accel as f32).to_bits(),
    }
}

fn scale() -> f32 {
    match FORMAT {
        frame::Format::I16 => {
            (wearsim_core::real::STANDARD_GRAVITY * FULL_SCALE_G / 32768.0) as f32
        }
        _ => 1.0,
    }
}

/// Frame assembly buffer and counters of the main loop.
struct Framer {
    buf: [u8; frame::MAX_FRAME],
    n: usize,
    first: u32,
    seq: u32,
    data_frames: u32,
    sent: u32,
}

impl Framer {
    const fn new() -> Self {
        Framer {
            buf: [0; frame::MAX_FRAME],
            n: 0,
            first: 0,
            seq: 1,
            data_frames: 0,
            sent: 0,
        }
    }
    /// Appends a sample; returns a full frame's bytes when one is complete.
    #[inline(always)]
    fn push(&mut self, index: u32, word: u32) -> Option<usize> {
        if self.n == 0 {
            self.first = index;
        }
        let size = FORMAT.sample_size();
        let at = frame::HEADER_LEN + self.n * size;
        let bytes = word.to_le_bytes();
        if let (Some(dst), Some(src)) = (self.buf.get_mut(at..at + size), bytes.get(..size)) {
            dst.copy_from_slice(src);
        }
        self.n += 1;
        if self.n == FRAME_SAMPLES {
            self.seal()
        } else {
            None
        }
    }
    /// Closes the frame being filled; returns its length (None if empty).
    fn seal(&mut self) -> Option<usize> {
        if self.n == 0 {
            return None;
        }
        let flags = if OVERRUN_FLAG.swap(false, Ordering::Relaxed) {
            frame::FLAG_OVERRUN
        } else {
            0
        };
        let h = frame::Header {
            kind: frame::Kind::Data,
            format: FORMAT,
            flags,
            seq: self.seq,
            first_sample: self.first,
            overruns: OVERRUNS.load(Ordering::Relaxed),
            scale: scale(),
        };
        let plen = self.n * FORMAT.sample_size();
        frame::write_header(&h, plen as u16, &mut self.buf)?;
        let len = frame::seal(&mut self.buf, plen)?;
        self.seq = self.seq.wrapping_add(1);
        self.data_frames += 1;
        self.sent += self.n as u32;
        self.n = 0;
        Some(len)
    }
    fn bytes(&self, len: usize) -> &[u8] {
        self.buf.get(..len).unwrap_or(&[])
    }
}

static mut FRAMER: Framer = Framer::new();
static mut SCRATCH: Framer = Framer::new();
static mut STATE: Option<State<NB>> = None;

/// Reports a fatal error and ends the run with a failure exit code.
fn fatal(what: &str) -> ! {
    defmt::error!("fatal: {=str}", what);
    exit(false)
}

fn exit(ok: bool) -> ! {
    let code = if ok {
        cortex_m_semihosting::debug::EXIT_SUCCESS
    } else {
        cortex_m_semihosting::debug::EXIT_FAILURE
    };
    cortex_m_semihosting::debug::exit(code);
    loop {
        cortex_m::asm::wfi();
    }
}

#[entry]
fn main() -> ! {
    hw::uart_init();
    hw::ticks_start();
    let Some(cfg) = presets::by_name(PRESET) else {
        fatal("unknown preset")
    };
    #[cfg(feature = "life")]
    let base = cfg.clone();
    #[cfg_attr(not(feature = "life"), allow(unused_mut))]
    let mut model = match Model::new_checked(cfg) {
        Ok(m) => m,
        Err(_) => fatal("preset rejected by validation"),
    };
    let rate = model.config().output_rate;
    let flavour = if FLAVOUR == 1 {
        "m4f-hardfloat"
    } else {
        "m3-softfloat"
    };
    defmt::info!(
        "scenario start: preset={=str} seed={=u64} rate_hz={=f32} oversample={=u32} samples={=u32} flavour={=str}",
        PRESET,
        SEED,
        rate as f32,
        model.oversample(),
        SAMPLES,
        flavour
    );

    // SAFETY: single-threaded init before interrupts are enabled; each static is borrowed once.
    let state: &'static mut Option<State<NB>> = unsafe { &mut *core::ptr::addr_of_mut!(STATE) };
    let framer: &'static mut Framer = unsafe { &mut *core::ptr::addr_of_mut!(FRAMER) };
    let scratch: &'static mut Framer = unsafe { &mut *core::ptr::addr_of_mut!(SCRATCH) };

    // Register-level sensor demo: an unmodified ISM330DHCX driver over the register model.
    sensor_demo::run(&model, SEED, state);

    // Budget: time BENCH_SAMPLES through the whole producer path (model step, wire
    // conversion, framing with CRC) in one span of TIMER1 ticks.
    *state = State::new(&model, SEED).ok();
    let Some(st) = state.as_mut() else {
        fatal("state capacity")
    };
    let t0 = hw::ticks();
    let mut step_count = 0u32;
    for i in 0..BENCH_SAMPLES {
        let s = loop {
            step_count += 1;
            if let Some(s) = model.step(st) {
                break s;
            }
        };
        if let Some(len) = scratch.push(i, to_wire(s.accel)) {
            core::hint::black_box(scratch.bytes(len));
        }
    }
    let bench_ticks = hw::ticks().wrapping_sub(t0);
    core::hint::black_box(step_count);
    defmt::info!(
        "budget: {=u32} samples in {=u32} ticks at {=u32} Hz",
        BENCH_SAMPLES,
        bench_ticks,
        hw::PCLK_HZ
    );

    // The stream proper, from a fresh state.
    *state = State::new(&model, SEED).ok();
    let Some(st) = state.as_mut() else {
        fatal("state capacity")
    };

    #[cfg(feature = "life")]
    let mut wear = life::Wear::new(&base, rate, SEED);
    #[cfg(feature = "life")]
    {
        model = wear.model();
        match State::new(&model, SEED) {
            Ok(s) => *st = s,
            Err(_) => fatal("state capacity"),
        }
    }
    #[cfg(feature = "life")]
    #[allow(unused_mut)]
    let mut total = life::MAX_SAMPLES;
    #[cfg(not(feature = "life"))]
    let total = SAMPLES;

    let mut preset = [0u8; 24];
    for (d, s) in preset.iter_mut().zip(PRESET.as_bytes()) {
        *d = *s;
    }
    // A life ends when its bearing fails, at a count nobody knows at the start: it announces
    // 0 (unbounded) and its end frame carries the count (`capture` checks that one).
    #[cfg(feature = "life")]
    let announced = 0;
    #[cfg(not(feature = "life"))]
    let announced = total;
    let start = frame::StartInfo {
        preset,
        seed: SEED,
        rate_hz: rate as f32,
        oversample: model.oversample(),
        total_samples: announced,
        flavour: FLAVOUR,
    };
    send_control(framer, frame::Kind::Start, 0, &start.to_bytes());

    // SAFETY: the queues are split once, before the interrupt that uses the consumer side
    // is enabled.
    let (mut ring_tx, ring_rx) = unsafe { (*core::ptr::addr_of_mut!(RING)).split() };
    let (txq_tx, mut txq_rx) = unsafe { (*core::ptr::addr_of_mut!(TXQ)).split() };
    // `try_borrow_mut`, not `borrow_ref_mut`: no panic path (`docs/firmware.md`); nothing else
    // borrows the cells inside a critical section, so a refusal cannot happen.
    let handed = critical_section::with(|cs| {
        match (
            RING_RX.borrow(cs).try_borrow_mut(),
            TXQ_TX.borrow(cs).try_borrow_mut(),
        ) {
            (Ok(mut rx), Ok(mut tx)) => {
                *rx = Some(ring_rx);
                *tx = Some(txq_tx);
                true
            }
            _ => false,
        }
    });
    if !handed {
        fatal("queues already borrowed");
    }
    LIMIT.store(total, Ordering::Relaxed);

    let period = (hw::PCLK_HZ as Real / rate + 0.5) as u32;
    let mut produced = 0u32;
    let mut busy: u64 = 0;
    let mut reported_overruns = 0u32;
    hw::pacing_start(period);
    // SAFETY: the handler only touches the statics above through their Mutex/atomics.
    unsafe { NVIC::unmask(hw::Irq(hw::TIMER0_IRQ)) };

    loop {
        let t0 = hw::ticks();
        let mut worked = false;
        // Produce one sample if the ring has room, then serve the transmit queue, so that a
        // model slower than real time (the soft-float M3) still drains the queue.
        if (total == 0 || produced < total) && ring_tx.ready() {
            let s = loop {
                let out = model.step(st);
                #[cfg(feature = "life")]
                wear.observe(st);
                if let Some(s) = out {
                    break s;
                }
            };
            if ring_tx.enqueue(to_wire(s.accel)).is_err() {
                fatal("ring full after ready()");
            }
            produced += 1;
            worked = true;
            #[cfg(feature = "life")]
            if wear.after_sample(&mut model, st, produced) {
                // End of life: the stream ends with the sample that completed it.
                total = produced;
                LIMIT.store(total, Ordering::Relaxed);
            }
        }
        // Transmit what the timer released.
        while let Some((i, w)) = txq_rx.dequeue() {
            if let Some(len) = framer.push(i, w) {
                hw::uart_write(framer.bytes(len));
            }
            worked = true;
        }
        if worked {
            busy += hw::ticks().wrapping_sub(t0) as u64;
        }
        let ov = OVERRUNS.load(Ordering::Relaxed);
        if ov != reported_overruns {
            // First miss and then every power of two: visible, never flooding.
            if reported_overruns == 0 || ov.count_ones() == 1 || ov >> 10 != reported_overruns >> 10
            {
                defmt::warn!(
                    "overrun: {=u32} sample deadlines missed so far (sample {=u32})",
                    ov,
                    RELEASED.load(Ordering::Relaxed)
                );
            }
            reported_overruns = ov;
        }
        if total != 0 && RELEASED.load(Ordering::Relaxed) >= total && txq_rx.is_empty() {
            break;
        }
        cortex_m::interrupt::free(|_| {
            // Sleep unless work arrived between the checks and here.
            if !(txq_rx.ready() || ((total == 0 || produced < total) && ring_tx.ready())) {
                cortex_m::asm::wfi();
            }
        });
    }
    hw::pacing_stop();
    NVIC::mask(hw::Irq(hw::TIMER0_IRQ));
    if let Some(len) = framer.seal() {
        hw::uart_write(framer.bytes(len));
    }
    let overruns = OVERRUNS.load(Ordering::Relaxed);
    let drops = TX_DROPS.load(Ordering::Relaxed);
    let end = frame::EndInfo {
        total_samples: framer.sent,
        data_frames: framer.data_frames,
        overruns,
        busy_ticks: bench_ticks as u64,
        tick_hz: hw::PCLK_HZ,
        measured_samples: BENCH_SAMPLES,
        reserved: drops,
    };
    send_control(framer, frame::Kind::End, overruns, &end.to_bytes());
    defmt::info!(
        "scenario end: samples={=u32} frames={=u32} overruns={=u32} tx_drops={=u32} stream_busy_ticks={=u64} log_frames_dropped={=u32}",
        framer.sent,
        framer.data_frames,
        overruns,
        drops,
        busy,
        log::dropped_frames()
    );
    exit(drops == 0)
}

fn send_control(framer: &mut Framer, kind: frame::Kind, overruns: u32, payload: &[u8]) {
    let seq = match kind {
        frame::Kind::Start => 0,
        _ => framer.seq,
    };
    let h = frame::Header {
        kind,
        format: frame::Format::None,
        flags: 0,
        seq,
        first_sample: 0,
        overruns,
        scale: 0.0,
    };
    match frame::encode(&h, payload, &mut framer.buf) {
        Some(len) => hw::uart_write(framer.bytes(len)),
        None => fatal("control frame"),
    }
}

/// TIMER0: one output-sample deadline.
fn on_tick() {
    hw::pacing_ack();
    critical_section::with(|cs| {
        let released = RELEASED.load(Ordering::Relaxed);
        let limit = LIMIT.load(Ordering::Relaxed);
        if limit != 0 && released >= limit {
            return;
        }
        // Only this handler borrows the cells after start-up, inside its critical section:
        // a refusal cannot happen (and `borrow_ref_mut` would be a panic path).
        let (Ok(mut rx), Ok(mut tx)) = (
            RING_RX.borrow(cs).try_borrow_mut(),
            TXQ_TX.borrow(cs).try_borrow_mut(),
        ) else {
            return;
        };
        let (Some(rx), Some(tx)) = (rx.as_mut(), tx.as_mut()) else {
            return;
        };
        match rx.dequeue() {
            Some(w) => {
                if tx.enqueue((released, w)).is_err() {
                    TX_DROPS.fetch_add(1, Ordering::Relaxed);
                }
                RELEASED.store(released + 1, Ordering::Relaxed);
            }
            None => {
                OVERRUNS.fetch_add(1, Ordering::Relaxed);
                OVERRUN_FLAG.store(true, Ordering::Relaxed);
            }
        }
    });
}

#[exception]
unsafe fn DefaultHandler(irqn: i16) {
    if irqn == hw::TIMER0_IRQ as i16 {
        on_tick();
    } else {
        defmt::error!("unexpected interrupt {=i16}", irqn);
        exit(false);
    }
}

#[exception]
unsafe fn HardFault(ef: &ExceptionFrame) -> ! {
    defmt::error!("hard fault at pc={=u32:#x}", ef.pc());
    exit(false)
}

/// The proof's panic handler (feature `panic-proof`): a call to a symbol defined nowhere, so
/// the image links only if no panic is reachable.
#[cfg(feature = "panic-proof")]
#[panic_handler]
fn panic(_info: &core::panic::PanicInfo) -> ! {
    extern "Rust" {
        fn __wearsim_fw_reachable_panic() -> !;
    }
    // SAFETY: never called in an image that links; see the feature's documentation.
    unsafe { __wearsim_fw_reachable_panic() }
}

#[cfg(not(feature = "panic-proof"))]
#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    match info.location() {
        Some(l) => defmt::error!("panic at {=str}:{=u32}", l.file(), l.line()),
        None => defmt::error!("panic"),
    }
    exit(false)
}

#[cfg(feature = "life")]
mod life {
    //! Accelerated-life scenario on the core's stress-driven wear model (`core::wear`): the
    //! contact loads of the running model are measured pass by pass (`PassMeter`), the wear
    //! state is advanced every [`BLOCK_REVS`] shaft revolutions with them, and each stage
    //! transition rebuilds the model for the new topography and is logged. The material is
    //! `Material::ACCELERATED` (a whole life in about 300 revolutions, ~12 s at 20 kHz).
    use super::{fatal, State, NB};
    use wearsim_core::wear::{Life, LifeConfig, LifeState, Material, PassMeter, Site, Stage};
    use wearsim_core::{Model, ModelConfig, Real};

    /// Shaft revolutions between wear updates.
    pub const BLOCK_REVS: Real = 2.0;
    /// Upper bound of the stream (samples); the run ends at failure, normally far earlier.
    pub const MAX_SAMPLES: u32 = 1_000_000;

    /// The wear state and its measurement.
    pub struct Wear {
        life: Life,
        state: LifeState,
        meter: PassMeter,
        base: ModelConfig,
        rate: Real,
        shaft_hz: Real,
        block: u32,
        since: u32,
    }

    impl Wear {
        /// Wear of `base` (its defect is replaced by the wear state) at output `rate`.
        pub fn new(base: &ModelConfig, rate: Real, seed: u64) -> Self {
            if Life::check_base(base).is_err() {
                fatal("life: the base model's defect location is not on its bearing")
            }
            let Ok(probe) = Model::new_checked(ModelConfig {
                defect: None,
                ..base.clone()
            }) else {
                fatal("life: base model rejected")
            };
            let cfg = LifeConfig {
                material: Material::ACCELERATED,
                running_in: 1.0,
                ..LifeConfig::DEFAULT
            };
            let site = Site::of(base.defect.as_ref().map(|d| &d.location));
            let Ok(life) =
                Life::new_checked(cfg, &base.bearing, probe.static_reference().q_max, site)
            else {
                fatal("life: configuration rejected")
            };
            let shaft_hz = base.speed.shaft_hz(0.0);
            Wear {
                state: life.initial_state(seed),
                life,
                meter: PassMeter::new(site, &base.bearing),
                base: base.clone(),
                rate,
                shaft_hz,
                block: (BLOCK_REVS / shaft_hz * rate + 0.5) as u32,
                since: 0,
            }
        }

        /// The model for the current wear state.
        pub fn model(&self) -> Model {
            match Model::new_checked(self.life.model_config(&self.base, &self.state)) {
                Ok(m) => m,
                Err(_) => fatal("life: model for the wear state rejected"),
            }
        }

        /// Feeds one internal step's contact loads.
        #[inline]
        pub fn observe(&mut self, st: &State<NB>) {
            self.meter
                .observe(st.stats(), st.shaft_angle(), st.cage_angle());
        }

        /// After output sample `k`: every block, advance the wear with the measured loads;
        /// on a transition log it and switch `model`/`st` to the new topography. Returns
        /// true once the bearing has failed.
        pub fn after_sample(&mut self, model: &mut Model, st: &mut State<NB>, k: u32) -> bool {
            self.since += 1;
            if self.since < self.block {
                return false;
            }
            let mut revs = self.since as Real / self.rate * self.shaft_hz;
            self.since = 0;
            let loads = self.meter.loads();
            self.meter = PassMeter::new(self.life.site(), &self.base.bearing);
            let mut guard = 0;
            while revs > 0.0 && guard < 64 {
                guard += 1;
                let before = self.state.stage;
                let adv = self.life.advance(&mut self.state, revs, &loads);
                revs -= adv.revs;
                if adv.transition.is_some() {
                    *model = self.model();
                    if let Some(t) = self.state.topography {
                        if st.set_topography(model, t).is_err() {
                            fatal("life: topography rejected");
                        }
                    }
                    if self.state.stage != before {
                        let t = self
                            .state
                            .topography
                            .unwrap_or(wearsim_core::topography::SMOOTHED_DENT);
                        defmt::info!(
                            "stage transition: {=u8} {=str} at sample {=u32} (revolution {=f32}, asperity {=f32} um, length {=f32} um, count {=u8})",
                            self.state.stage.index() as u8,
                            self.state.stage.name(),
                            k,
                            self.state.cycles as f32,
                            t.asperity_height as f32 * 1e6,
                            t.length as f32 * 1e6,
                            t.count
                        );
                    }
                }
                if adv.revs <= 0.0 || self.state.stage == Stage::Failure {
                    break;
                }
            }
            self.state.stage == Stage::Failure
        }
    }
}
