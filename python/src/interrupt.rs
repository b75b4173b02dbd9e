//! Long calls that Ctrl-C (a Jupyter "interrupt kernel") can stop. Python runs signal
//! handlers only when the interpreter gets control on its main thread; a call that does
//! its work inside `py.detach` gave it none until the work ended (a 20 000-record sweep
//! interrupted at 2 s ran to completion, then raised and lost its report). Here the work
//! runs on a worker thread while the calling thread, GIL released, wakes every
//! [`POLL`] to run the handlers (`Python::check_signals`); when one raises, the work's
//! cancel flag is set, the worker is waited for (it stops at its next check: a chunk of
//! samples, a batch of shards) and the handler's exception (KeyboardInterrupt) is raised.

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

/// How often the calling thread looks for a pending signal.
pub const POLL: Duration = Duration::from_millis(50);

/// Sets `done` and wakes `waiter` when dropped: on the worker's return or its panic.
struct Finished<'a> {
    done: &'a AtomicBool,
    waiter: std::thread::Thread,
}

impl Drop for Finished<'_> {
    fn drop(&mut self) {
        self.done.store(true, Ordering::Release);
        self.waiter.unpark();
    }
}

/// Runs `work` on a worker thread (host-sim's worker stack size) with the GIL released,
/// inside a cancel scope ([`wearsim_host::cancel`], inherited by the threads it starts),
/// and returns its result; a signal handler's exception (KeyboardInterrupt) is returned
/// instead once `work` has stopped, its cancel flag having been set for it to stop early.
/// A panic in `work` is resumed here (PyO3 turns it into PanicException).
pub fn run<T: Send>(py: Python<'_>, work: impl FnOnce() -> T + Send) -> PyResult<T> {
    let cancel = Arc::new(AtomicBool::new(false));
    let done = AtomicBool::new(false);
    let waiter = std::thread::current();
    std::thread::scope(|s| {
        let (flag, done) = (cancel.clone(), &done);
        let handle = wearsim_host::lanes::spawn_worker(s, move || {
            let _finished = Finished { done, waiter };
            wearsim_host::cancel::scope(flag, work)
        })
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start a worker thread: {e}")))?;
        let mut raised = None;
        while !done.load(Ordering::Acquire) {
            py.detach(|| {
                if !done.load(Ordering::Acquire) {
                    std::thread::park_timeout(POLL);
                }
            });
            if done.load(Ordering::Acquire) {
                break;
            }
            if let Err(e) = py.check_signals() {
                cancel.store(true, Ordering::Relaxed);
                raised = Some(e);
                break;
            }
        }
        let joined = py.detach(|| handle.join());
        match (joined, raised) {
            (Err(panic), _) => std::panic::resume_unwind(panic),
            (Ok(_), Some(e)) => Err(e),
            (Ok(v), None) => Ok(v),
        }
    })
}
