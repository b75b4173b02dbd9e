//! Cooperative cancellation of a long run started in-process, the one mechanism for every
//! call of the Python package that Ctrl-C stops (`python/src/interrupt.rs`): `simulate`,
//! `sweep`, and `life` and `gap`, which run the commands through [`crate::cmd::dispatch`].
//! The caller runs the work inside [`scope`] with a flag; every worker thread the work
//! starts inherits it ([`crate::lanes::spawn_worker`]); the loops that take long — a
//! simulation's chunks of samples (`simulate::run`), a sweep's batches of shards
//! (`sweep::run`), a life's windows (`life::LifeRun::drive`), the gap's simulations
//! (`gap::run`) — ask [`requested`] and stop, and the commands write no report once it is
//! set ([`check`]); a dense life stops as at `--stop-after`, with a checkpoint to resume
//! from. The `wearsim` program never sets one: Ctrl-C ends its process, and the
//! files it writes are renamed into place whole.

use std::cell::RefCell;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

thread_local! {
    static FLAG: RefCell<Option<Arc<AtomicBool>>> = const { RefCell::new(None) };
}

/// The message of an interrupted command.
pub const MESSAGE: &str = "interrupted: stopped before its report was written";

/// Restores the thread's previous flag when the scope ends (also on a panic).
struct Restore(Option<Arc<AtomicBool>>);

impl Drop for Restore {
    fn drop(&mut self) {
        let previous = self.0.take();
        FLAG.with(|f| *f.borrow_mut() = previous);
    }
}

/// Runs `f` with `flag` as this thread's cancel flag (and that of the workers it starts).
pub fn scope<T>(flag: Arc<AtomicBool>, f: impl FnOnce() -> T) -> T {
    let previous = FLAG.with(|c| c.borrow_mut().replace(flag));
    let _restore = Restore(previous);
    f()
}

/// This thread's cancel flag, if it runs inside [`scope`].
pub fn current() -> Option<Arc<AtomicBool>> {
    FLAG.with(|f| f.borrow().clone())
}

/// Whether this thread's work has been asked to stop.
pub fn requested() -> bool {
    FLAG.with(|f| {
        f.borrow()
            .as_ref()
            .is_some_and(|a| a.load(Ordering::Relaxed))
    })
}

/// A run stopped by its caller (exit code [`crate::cmd::exit::INTERRUPTED`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Interrupted;

impl std::fmt::Display for Interrupted {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(MESSAGE)
    }
}

/// `Err` once the work has been asked to stop: called before a command writes its report.
pub fn check() -> Result<(), Interrupted> {
    if requested() {
        Err(Interrupted)
    } else {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_scope_sets_the_flag_for_its_workers_and_restores_the_previous_one() {
        assert!(!requested() && current().is_none());
        let flag = Arc::new(AtomicBool::new(false));
        scope(flag.clone(), || {
            assert!(!requested());
            flag.store(true, Ordering::Relaxed);
            assert!(requested() && check().is_err());
            let in_worker = std::thread::scope(|s| {
                crate::lanes::spawn_worker(s, requested)
                    .map(|h| h.join().ok())
                    .ok()
                    .flatten()
            });
            assert_eq!(in_worker, Some(true), "a worker inherits the flag");
            let inner = Arc::new(AtomicBool::new(false));
            scope(inner, || {
                assert!(!requested(), "an inner scope has its own")
            });
            assert!(requested(), "the outer flag is back");
        });
        assert!(!requested() && current().is_none() && check().is_ok());
    }
}
