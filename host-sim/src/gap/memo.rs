//! The memo of simulations a fit has already run. Every simulation of the gap uses the
//! same seed for a given target (common random numbers), so a simulation is a
//! deterministic function of its configuration: a pattern search that polls back to the
//! point it just left, a greedy step that re-simulates the effect set it chose, a
//! backward step that removes an effect again, all ask for a simulation that exists. The
//! memo returns it, and only simulations actually run are counted.
//!
//! It also holds results run ahead of need (`S`: a fit's guesses at its next
//! simulations, run in lanes that would otherwise be padding): those are not counted until
//! they are asked for, so the counts are the same as without them.
//!
//! A clone starts empty: the owner's key does not say everything a result depends on
//! (the cell spec, the measured stretch), so a memo is never shared between owners.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

/// A bounded first-in-first-out memo from `K` to shared results `V`, and of raw results
/// `S` run ahead of need.
pub struct Memo<K, V, S = ()> {
    entries: Mutex<Vec<(K, Arc<V>)>>,
    capacity: usize,
    ahead: Mutex<Vec<(K, S)>>,
}

impl<K: PartialEq + Clone, V, S> Memo<K, V, S> {
    /// An empty memo keeping at most `capacity` results (at least 1).
    pub fn new(capacity: usize) -> Self {
        Memo {
            entries: Mutex::new(vec![]),
            capacity: capacity.max(1),
            ahead: Mutex::new(vec![]),
        }
    }

    /// Keeps `s`, run ahead of need for `key` and not counted yet, among at most `max`
    /// such results (the oldest goes).
    pub fn put_ahead(&self, key: K, s: S, max: usize) {
        if let Ok(mut a) = self.ahead.lock() {
            if a.iter().any(|(k, _)| *k == key) {
                return;
            }
            while !a.is_empty() && a.len() >= max.max(1) {
                a.remove(0);
            }
            a.push((key, s));
        }
    }

    /// The result run ahead for `key`, taken out (the caller counts it now).
    pub fn take_ahead(&self, key: &K) -> Option<S> {
        let mut a = self.ahead.lock().ok()?;
        let i = a.iter().position(|(k, _)| k == key)?;
        Some(a.remove(i).1)
    }

    /// Whether a result run ahead is held for `key`.
    pub fn has_ahead(&self, key: &K) -> bool {
        self.ahead
            .lock()
            .is_ok_and(|a| a.iter().any(|(k, _)| k == key))
    }

    /// The result for `key`: the memo's when it holds one, else `run()`'s, which is kept
    /// (the oldest entry goes when the memo is full) and counted in `sims`. Errors are not
    /// kept: a refused configuration is refused again, cheaply.
    pub fn get_or_run(
        &self,
        key: &K,
        sims: &AtomicUsize,
        run: impl FnOnce() -> Result<V, String>,
    ) -> Result<Arc<V>, String> {
        if let Some(v) = self.get(key) {
            return Ok(v);
        }
        sims.fetch_add(1, Ordering::Relaxed);
        let v = Arc::new(run()?);
        self.insert(key.clone(), v.clone());
        Ok(v)
    }

    /// The result for `key`, when the memo holds one.
    pub fn get(&self, key: &K) -> Option<Arc<V>> {
        let c = self.entries.lock().ok()?;
        c.iter().find(|(k, _)| k == key).map(|(_, v)| v.clone())
    }

    /// Keeps `v` for `key` (the oldest entry goes when the memo is full); the caller ran
    /// it and counts it.
    pub fn insert(&self, key: K, v: Arc<V>) {
        if let Ok(mut c) = self.entries.lock() {
            if c.iter().any(|(k, _)| *k == key) {
                return;
            }
            if c.len() >= self.capacity {
                c.remove(0);
            }
            c.push((key, v));
        }
    }

    /// Results held.
    pub fn len(&self) -> usize {
        self.entries.lock().map(|c| c.len()).unwrap_or(0)
    }

    /// Whether the memo holds nothing.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl<K: PartialEq + Clone, V, S> Clone for Memo<K, V, S> {
    /// An empty memo of the same capacity (see the module documentation).
    fn clone(&self) -> Self {
        Memo::new(self.capacity)
    }
}

impl<K, V, S> std::fmt::Debug for Memo<K, V, S> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let n = self.entries.lock().map(|c| c.len()).unwrap_or(0);
        write!(f, "Memo({n}/{})", self.capacity)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_result_is_run_once_and_counted_once() {
        let m: Memo<u32, u32> = Memo::new(2);
        let sims = AtomicUsize::new(0);
        let runs = AtomicUsize::new(0);
        let run = |x: u32| {
            runs.fetch_add(1, Ordering::Relaxed);
            Ok(x * 10)
        };
        assert_eq!(*m.get_or_run(&1, &sims, || run(1)).unwrap(), 10);
        assert_eq!(*m.get_or_run(&1, &sims, || run(1)).unwrap(), 10);
        assert_eq!(sims.load(Ordering::Relaxed), 1);
        assert_eq!(runs.load(Ordering::Relaxed), 1);
        // Full: the oldest goes.
        m.get_or_run(&2, &sims, || run(2)).unwrap();
        m.get_or_run(&3, &sims, || run(3)).unwrap();
        assert_eq!(m.len(), 2);
        m.get_or_run(&1, &sims, || run(1)).unwrap();
        assert_eq!(runs.load(Ordering::Relaxed), 4);
    }

    /// Results run ahead are held apart, uncounted, taken once, the oldest dropped beyond
    /// the bound.
    #[test]
    fn results_run_ahead_are_taken_once_and_bounded() {
        let m: Memo<u32, u32, u32> = Memo::new(4);
        m.put_ahead(1, 10, 2);
        m.put_ahead(2, 20, 2);
        m.put_ahead(3, 30, 2);
        assert!(!m.has_ahead(&1) && m.has_ahead(&2) && m.has_ahead(&3));
        assert!(m.is_empty(), "results run ahead are not memo entries");
        assert_eq!(m.take_ahead(&2), Some(20));
        assert_eq!(m.take_ahead(&2), None);
        assert!(m.get(&3).is_none());
    }

    #[test]
    fn errors_are_not_kept_and_clones_start_empty() {
        let m: Memo<u32, u32> = Memo::new(4);
        let sims = AtomicUsize::new(0);
        assert!(m.get_or_run(&1, &sims, || Err("refused".into())).is_err());
        assert!(m.is_empty());
        m.get_or_run(&2, &sims, || Ok(5)).unwrap();
        assert_eq!(m.len(), 1);
        assert!(m.clone().is_empty());
    }
}
