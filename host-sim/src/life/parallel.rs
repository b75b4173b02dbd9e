//! Independent lives on std threads: a shared work queue (the next index taken by whichever
//! thread is free), results in index order. Lives differ in length by an order of
//! magnitude, so a queue keeps every thread busy where fixed chunks would wait for their
//! longest life.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// Threads to use when the caller names none: the machine's available parallelism.
pub fn default_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// `f(0) … f(n − 1)` on at most `threads` threads (at least one); `done(k)` after each
/// result with the number finished so far. Results in index order. A job that panicked
/// yields `lost()` (the panic message still goes to stderr through the panic hook).
pub fn map_indexed<R: Send>(
    n: usize,
    threads: usize,
    f: impl Fn(usize) -> R + Sync,
    done: &(dyn Fn(usize) + Sync),
    lost: impl Fn() -> R + Sync,
) -> Vec<R> {
    let next = AtomicUsize::new(0);
    let finished = AtomicUsize::new(0);
    let out: Mutex<Vec<Option<R>>> = Mutex::new((0..n).map(|_| None).collect());
    std::thread::scope(|s| {
        for _ in 0..threads.clamp(1, n.max(1)) {
            // A job no thread takes (none could start) comes back as `lost()`.
            let worker = crate::lanes::spawn_worker(s, || loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                if i >= n {
                    break;
                }
                // A panicking job becomes `lost()`; the other jobs go on.
                let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| f(i)))
                    .unwrap_or_else(|_| lost());
                if let Ok(mut o) = out.lock() {
                    if let Some(slot) = o.get_mut(i) {
                        *slot = Some(r);
                    }
                }
                done(finished.fetch_add(1, Ordering::Relaxed) + 1);
            });
            if worker.is_err() {
                break;
            }
        }
    });
    let o = out.into_inner().unwrap_or_default();
    let mut v: Vec<R> = o.into_iter().map(|r| r.unwrap_or_else(&lost)).collect();
    v.resize_with(n, lost);
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every index once, in order, whatever the thread count.
    #[test]
    fn results_come_back_in_index_order_once_each() {
        for threads in [1, 2, 7, 64] {
            let calls = AtomicUsize::new(0);
            let v = map_indexed(
                50,
                threads,
                |i| {
                    calls.fetch_add(1, Ordering::Relaxed);
                    i * i
                },
                &|_| {},
                || usize::MAX,
            );
            assert_eq!(v, (0..50).map(|i| i * i).collect::<Vec<_>>());
            assert_eq!(calls.load(Ordering::Relaxed), 50);
        }
        assert!(map_indexed(0, 2, |i| i, &|_| {}, || 0).is_empty());
        // A panicking job is lost alone.
        let v = map_indexed(
            5,
            2,
            |i| {
                assert!(i != 3, "job 3 fails");
                i
            },
            &|_| {},
            || 99,
        );
        assert_eq!(v, vec![0, 1, 2, 99, 4]);
    }
}
