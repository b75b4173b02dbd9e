//! defmt's global logger over ARM semihosting, without a panic path.
//!
//! It replaces `defmt-semihosting`, whose logger panics when it is taken re-entrantly ("defmt
//! logger taken reentrantly": a hard fault or an unexpected interrupt logging while the main
//! loop is inside a log call) and when `write`/`release` come out of context. Those panics
//! were the firmware's own reachable ones (`docs/firmware.md`, "No reachable panic"). Here a
//! nested frame is dropped and counted ([`dropped_frames`]) while the outer frame completes
//! intact, and a call out of context does nothing: a log line may be lost, the stream of
//! frames is never corrupted, and the firmware never panics for a log.
//!
//! Frames are encoded by [`defmt::Encoder`] and written to the host's standard output through
//! `cortex-m-semihosting` (`:tt`, as `defmt-semihosting` did), which QEMU's `-semihosting`
//! forwards to its own standard output, where `fwtool` decodes them.

use core::cell::UnsafeCell;
use core::sync::atomic::{AtomicU32, AtomicU8, Ordering};

use cortex_m_semihosting::hio::{self, HostStream};

#[defmt::global_logger]
struct Logger;

/// Frames dropped because they began inside another frame.
static DROPPED: AtomicU32 = AtomicU32::new(0);

/// Frames dropped so far because a log call began inside another one (a fault handler
/// logging during a log line); each such frame is lost whole, the outer one is kept.
pub fn dropped_frames() -> u32 {
    DROPPED.load(Ordering::Relaxed)
}

/// The logger's state. Every field is touched only inside the critical section taken by the
/// outermost `acquire` (depth 1), or, for `depth`, with that section held by the caller.
struct Encoder {
    /// Nesting depth of `acquire` calls: 0 idle, 1 writing a frame, > 1 inside a nested
    /// (dropped) frame.
    depth: AtomicU8,
    /// The outermost `acquire`'s critical-section state, restored by its `release`.
    restore: UnsafeCell<critical_section::RestoreState>,
    /// defmt's frame encoder.
    encoder: UnsafeCell<defmt::Encoder>,
    /// The host's standard output, opened on first use (`None` if the host refused it).
    out: UnsafeCell<Option<HostStream>>,
}

// SAFETY: the cells are accessed only by the holder of the outermost critical section (see
// the field documentation); on the single-core targets this firmware builds for, that
// excludes every other context.
unsafe impl Sync for Encoder {}

static ENCODER: Encoder = Encoder {
    depth: AtomicU8::new(0),
    restore: UnsafeCell::new(critical_section::RestoreState::invalid()),
    encoder: UnsafeCell::new(defmt::Encoder::new()),
    out: UnsafeCell::new(None),
};

impl Encoder {
    /// Writes encoded bytes to the host; a refused write loses them (nothing to report to).
    fn emit(out: &mut Option<HostStream>, bytes: &[u8]) {
        if let Some(h) = out {
            let _ = h.write_all(bytes);
        }
    }

    fn acquire(&self) {
        // SAFETY: paired with exactly one `critical_section::release` below or in `release`.
        let restore = unsafe { critical_section::acquire() };
        let depth = self.depth.load(Ordering::Relaxed);
        if depth != 0 {
            // Nested: the outer frame holds the section; release ours at once (LIFO holds,
            // as nothing was acquired since) and drop this frame.
            self.depth.store(depth.saturating_add(1), Ordering::Relaxed);
            DROPPED.fetch_add(1, Ordering::Relaxed);
            // SAFETY: the state just returned by the matching `acquire`.
            unsafe { critical_section::release(restore) };
            return;
        }
        self.depth.store(1, Ordering::Relaxed);
        // SAFETY: depth 1 and the critical section held: exclusive access to the cells.
        unsafe {
            self.restore.get().write(restore);
            let out = &mut *self.out.get();
            if out.is_none() {
                *out = hio::hstdout().ok();
            }
            (*self.encoder.get()).start_frame(|b| Self::emit(out, b));
        }
    }

    fn write(&self, bytes: &[u8]) {
        if self.depth.load(Ordering::Relaxed) != 1 {
            return;
        }
        // SAFETY: depth 1: the outermost `acquire` holds the critical section.
        unsafe {
            let out = &mut *self.out.get();
            (*self.encoder.get()).write(bytes, |b| Self::emit(out, b));
        }
    }

    fn release(&self) {
        match self.depth.load(Ordering::Relaxed) {
            0 => {}
            1 => {
                // SAFETY: depth 1: the outermost `acquire` holds the critical section, whose
                // state is released exactly once, here.
                unsafe {
                    let out = &mut *self.out.get();
                    (*self.encoder.get()).end_frame(|b| Self::emit(out, b));
                    let restore = self.restore.get().read();
                    self.depth.store(0, Ordering::Relaxed);
                    critical_section::release(restore);
                }
            }
            d => self.depth.store(d - 1, Ordering::Relaxed),
        }
    }
}

// SAFETY: `acquire`/`release` pair as defmt requires, and `write` writes only inside a frame.
unsafe impl defmt::Logger for Logger {
    fn acquire() {
        ENCODER.acquire();
    }

    unsafe fn flush() {
        // Semihosting writes are blocking: the host has every byte when `write_all` returns.
    }

    unsafe fn release() {
        ENCODER.release();
    }

    unsafe fn write(bytes: &[u8]) {
        ENCODER.write(bytes);
    }
}
