//! Host side of the K-lane stepper ([`wearsim_core::model::LaneGroup`]): packed square
//! roots (`sqrtpd`, which the `unsafe`-free core cannot issue) and, where the CPU has
//! AVX2, the whole lane step compiled for it, chosen at run time; and [`run_accel`], which
//! groups scenarios into lane groups (sweeps, the gap's fits). Both keep the scalar
//! step's bits: IEEE-754 square roots are correctly rounded in every form, and AVX2 does
//! not bring fused multiply-add (Rust never contracts `a*b + c` on its own).

use crate::simulate::{self, RunError, Scenario, CAPACITY};
use wearsim_core::model::{LaneGroup, SqrtLanes};
use wearsim_core::{Model, Sample};

/// [`SqrtLanes`] with SSE2's packed square root, two lanes per instruction.
#[derive(Debug, Clone, Copy, Default)]
pub struct PackedSqrt;

impl<const K: usize> SqrtLanes<K> for PackedSqrt {
    #[inline(always)]
    fn sqrt_lanes(&self, x: &mut [f64; K]) {
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::x86_64::{_mm_loadu_pd, _mm_sqrt_pd, _mm_storeu_pd};
            let mut pairs = x.chunks_exact_mut(2);
            for p in &mut pairs {
                // SAFETY: SSE2 is part of the x86_64 baseline; the pointer covers the two
                // f64 of this chunk (unaligned load and store).
                unsafe { _mm_storeu_pd(p.as_mut_ptr(), _mm_sqrt_pd(_mm_loadu_pd(p.as_ptr()))) };
            }
            for v in pairs.into_remainder() {
                *v = v.sqrt();
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        for v in x.iter_mut() {
            *v = v.sqrt();
        }
    }
}

/// Whether [`fill`] uses its AVX2 copy: the CPU has AVX2 and `WEARSIM_LANES_SSE2` is not
/// set (that variable forces the SSE2 baseline, for measuring it).
fn use_avx2() -> bool {
    static AVX2: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *AVX2.get_or_init(|| {
        #[cfg(target_arch = "x86_64")]
        if std::env::var_os("WEARSIM_LANES_SSE2").is_none() {
            return std::arch::is_x86_feature_detected!("avx2");
        }
        false
    })
}

/// Which code path [`fill`] takes on this machine: `"avx2"` or `"sse2"`.
pub fn simd_path() -> &'static str {
    if use_avx2() {
        "avx2"
    } else {
        "sse2"
    }
}

/// [`LaneGroup::fill`] with packed square roots, compiled for AVX2 when the CPU has it
/// (see [`simd_path`]).
pub fn fill<const K: usize, const NB: usize>(
    group: &mut LaneGroup<'_, K, NB>,
    out: &mut [[Sample; K]],
) -> usize {
    #[cfg(target_arch = "x86_64")]
    if use_avx2() {
        // SAFETY: the CPU has AVX2 (`use_avx2` checked it).
        return unsafe { fill_avx2(group, out) };
    }
    group.fill_with(out, &PackedSqrt)
}

/// The lane step inlined into a function compiled with AVX2 (wider vectors, no FMA).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn fill_avx2<const K: usize, const NB: usize>(
    group: &mut LaneGroup<'_, K, NB>,
    out: &mut [[Sample; K]],
) -> usize {
    group.fill_with(out, &PackedSqrt)
}

/// [`fill`], calling `observe` with the group after every internal step
/// ([`LaneGroup::fill_observed_with`]): for callers that look at the lanes after every
/// step (a life's pass meters).
pub fn fill_observed<const K: usize, const NB: usize>(
    group: &mut LaneGroup<'_, K, NB>,
    out: &mut [[Sample; K]],
    observe: impl FnMut(&LaneGroup<'_, K, NB>),
) -> usize {
    #[cfg(target_arch = "x86_64")]
    if use_avx2() {
        // SAFETY: the CPU has AVX2 (`use_avx2` checked it).
        return unsafe { fill_observed_avx2(group, out, observe) };
    }
    group.fill_observed_with(out, &PackedSqrt, observe)
}

/// The observed lane fill inlined into a function compiled with AVX2 (see [`fill_avx2`]).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn fill_observed_avx2<const K: usize, const NB: usize>(
    group: &mut LaneGroup<'_, K, NB>,
    out: &mut [[Sample; K]],
    observe: impl FnMut(&LaneGroup<'_, K, NB>),
) -> usize {
    group.fill_observed_with(out, &PackedSqrt, observe)
}

/// Largest lane group [`run_accel`] forms (the bench's best per-core figure; see
/// `docs/python.md`).
pub const MAX_LANES: usize = 16;

/// Stack size of a worker thread that may run lane groups (16 MiB). A
/// `LaneGroup<16, _>` is built on the stack before it is boxed, and in a less optimised
/// build (the Python extension's CI build is `opt-level = 1`) that needs more than std's
/// 2 MiB thread default: a 16-record sweep killed its Python process with SIGSEGV. A
/// worker builds its groups on its own stack (`on_worker_stack`), one after another.
pub const WORKER_STACK: usize = 16 << 20;

/// Most worker threads one command takes (`--jobs`, `--threads`): each reserves a
/// [`WORKER_STACK`], and past the cores more only add memory (a probe's `--jobs 100000`
/// took 2.4× the time and memory of `--jobs 1` for the same result).
pub const MAX_WORKERS: usize = 256;

/// The worker threads for a flag's value `n`: `n` when in 1..=[`MAX_WORKERS`], the
/// machine's available parallelism when not given; otherwise a message naming `flag`.
pub fn workers(flag: &str, n: Option<usize>) -> Result<usize, String> {
    match n {
        Some(t) if (1..=MAX_WORKERS).contains(&t) => Ok(t),
        Some(t) => Err(format!(
            "{flag} {t} is out of range: allowed 1 ..= {MAX_WORKERS}"
        )),
        None => Ok(std::thread::available_parallelism().map_or(1, |n| n.get())),
    }
}

/// Spawns `f` on a scoped worker thread with a [`WORKER_STACK`] stack and the caller's
/// cancel flag ([`crate::cancel`]): every thread that runs simulations (sweeps, lives, the
/// gap's fits) starts through here.
pub fn spawn_worker<'scope, T: Send + 'scope>(
    scope: &'scope std::thread::Scope<'scope, '_>,
    f: impl FnOnce() -> T + Send + 'scope,
) -> std::io::Result<std::thread::ScopedJoinHandle<'scope, T>> {
    let flag = crate::cancel::current();
    std::thread::Builder::new()
        .stack_size(WORKER_STACK)
        .spawn_scoped(scope, move || {
            ON_WORKER.set(true);
            match flag {
                Some(flag) => crate::cancel::scope(flag, f),
                None => f(),
            }
        })
}

thread_local! {
    /// Whether this thread was started by [`spawn_worker`] (a [`WORKER_STACK`] stack).
    static ON_WORKER: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Runs `f` with a [`WORKER_STACK`] stack and returns its result: on this thread when
/// [`spawn_worker`] started it, else on a scoped worker thread (`None` when that thread
/// cannot be started or panics). A lane group of 16 lanes is about 800 KB (every lane's
/// state holds three anti-alias histories of `2·MAX_TAPS` reals since oversampling ratios
/// up to 16), built on the stack before it is boxed: on a caller's thread of std's 2 MiB
/// default (a test, a library user's thread) it overflowed. A thread per group cost little
/// time to start but a fresh stack whose pages the kernel maps and zeroes on first touch,
/// about 3 MB per group: a laned sweep took 247 000 minor page faults in 281 groups and
/// 0.4–0.6 s of system time against 1.9 s of user time (stop 58); a worker's own stack is
/// touched once.
fn on_worker_stack<T: Send>(f: impl FnOnce() -> Option<T> + Send) -> Option<T> {
    if ON_WORKER.get() {
        return f();
    }
    std::thread::scope(|s| spawn_worker(s, f).ok()?.join().ok()?)
}

/// Whether [`plan`] forms lane groups: true unless `WEARSIM_LANES_OFF` is set (that
/// variable forces the scalar step for every run, to measure the lanes' gain; the output
/// is the same bits either way).
pub(crate) fn lanes_on() -> bool {
    static ON: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *ON.get_or_init(|| std::env::var_os("WEARSIM_LANES_OFF").is_none())
}

/// Lanes of the next group for `n` shareable runs left: 16 for 16 or more, else the
/// next power of two when at most 3/8 of it would be padding (a padded 16-lane group
/// costs about 4 scalar runs, a 13-run split into 8 + 4 + 1 about 5.5: see
/// `docs/python.md`), else the power of two below; 1 means the scalar step.
pub fn group_size(n: usize) -> usize {
    if n >= MAX_LANES {
        return MAX_LANES;
    }
    let up = n.next_power_of_two();
    if (up - n) * 8 <= up * 3 {
        up
    } else {
        up / 2
    }
}

/// Lanes of the next group of `n` runs left that each move at their own speed: 16 or 8
/// without padding, else 1 (alone). Measured with `wearsim bench --lanes K --own-speed`
/// (`docs/python.md`): such groups gain 1.6× at K = 16 and 1.3× at 8, nothing at 4 and
/// lose at 2, so a padded or small group would be slower than running alone.
pub fn own_group_size(n: usize) -> usize {
    match n {
        16.. => 16,
        8.. => 8,
        _ => 1,
    }
}

/// How two runs can share a lane group.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sharing {
    /// Not at all: each runs in another group, or alone.
    No,
    /// As lanes that each move at their own speed (the core's slower own-kinematics path).
    OwnSpeed,
    /// As lanes that share the kinematics (computed once for the group).
    Kinematics,
}

/// How the models `a` and `b` can share a lane group (see [`Sharing`]). Lanes at their own
/// varying speed (each record's own speed fluctuation) pool too: each lane evaluates its
/// own speed profile every step, as the scalar step does. Until stop 60 such lanes ran
/// alone because they measured no faster; with the lanes' roughness and load-zone roots
/// packed (no longer paying Intel's legacy-SSE penalty, stop 59), sweeps whose records
/// carry a speed fluctuation took 5–20 % less CPU with them pooled (`docs/python.md`).
pub fn sharing(a: &Model, b: &Model) -> Sharing {
    use wearsim_core::model::lanes::{same_kinematics, shareable};
    match (shareable(a, b, 1).is_ok(), same_kinematics(a, b)) {
        (false, _) => Sharing::No,
        (true, false) => Sharing::OwnSpeed,
        (true, true) => Sharing::Kinematics,
    }
}

/// How scenario `b` can share a lane group led by `a`: the models' [`sharing`], provided
/// the runs record and discard the same lengths.
pub fn can_share(a: &Scenario, b: &Scenario) -> Sharing {
    if a.run.duration == b.run.duration && a.run.settle == b.run.settle {
        sharing(&a.model, &b.model)
    } else {
        Sharing::No
    }
}

/// Acceleration (m/s², settling time discarded) of every scenario in `scs`, in order,
/// bit for bit what [`simulate::run`] gives: scenarios that can share a lane group run
/// in groups of up to [`MAX_LANES`] (sizes from [`group_size`], padded), the rest alone. A lane that
/// produces a non-finite sample is re-run alone, so its error is the scalar run's.
pub fn run_accel(scs: &[Scenario]) -> Vec<Result<Vec<f64>, RunError>> {
    let mut out: Vec<Option<Result<Vec<f64>, RunError>>> = (0..scs.len()).map(|_| None).collect();
    for (k, now) in plan(scs.len(), |a, b| can_share(&scs[a], &scs[b])) {
        let res = match k {
            16 => run_group::<16>(scs, &now),
            8 => run_group::<8>(scs, &now),
            4 => run_group::<4>(scs, &now),
            2 => run_group::<2>(scs, &now),
            _ => now.iter().map(|&i| scalar_accel(&scs[i])).collect(),
        };
        for (&i, r) in now.iter().zip(res) {
            out[i] = Some(r);
        }
    }
    out.into_iter()
        .map(|r| r.unwrap_or_else(|| Ok(Vec::new())))
        .collect()
}

/// The lane groups of items `0..n`, each as its lane count K (16, 8, 4, 2; 1 = every
/// item alone) and its items in order. Items first join the first open group whose leader
/// they share the kinematics with (`share(leader, item)` is [`Sharing::Kinematics`]);
/// the items that this leaves alone then join the first open group of such items whose
/// leader they can share a group with at their own speed ([`Sharing::OwnSpeed`]), so a
/// lane at its own speed never slows a group that could share its kinematics. Groups
/// hold up to [`MAX_LANES`] and each is cut into runs of [`group_size`] lanes (padded by
/// the caller), or of [`own_group_size`] for lanes at their own speed. With `WEARSIM_LANES_OFF` set, every item is alone. Shared by
/// [`run_accel`] (sweeps) and the gap's matched simulations.
pub fn plan(n: usize, share: impl Fn(usize, usize) -> Sharing) -> Vec<(usize, Vec<usize>)> {
    let join = |groups: &mut Vec<Vec<usize>>, i: usize, at_least: Sharing| {
        let fits = |l: usize| {
            matches!(
                (share(l, i), at_least),
                (Sharing::Kinematics, _) | (Sharing::OwnSpeed, Sharing::OwnSpeed)
            )
        };
        match groups
            .iter_mut()
            .find(|g| g.len() < MAX_LANES && g.first().is_some_and(|&l| fits(l)))
        {
            Some(g) => g.push(i),
            None => groups.push(vec![i]),
        }
    };
    let mut same: Vec<Vec<usize>> = Vec::new();
    for i in 0..n {
        join(&mut same, i, Sharing::Kinematics);
    }
    let (alone, mut groups): (Vec<Vec<usize>>, Vec<Vec<usize>>) =
        same.into_iter().partition(|g| g.len() == 1);
    let mut own: Vec<Vec<usize>> = Vec::new();
    for i in alone.into_iter().flatten() {
        join(&mut own, i, Sharing::OwnSpeed);
    }
    let shared = groups.len();
    groups.extend(own);
    let mut out = vec![];
    for (j, g) in groups.iter().enumerate() {
        let mut rest: &[usize] = g;
        while !rest.is_empty() {
            let k = match (lanes_on(), j < shared) {
                (false, _) => 1,
                (true, true) => group_size(rest.len()),
                (true, false) => own_group_size(rest.len()),
            };
            let (now, later) = rest.split_at(k.min(rest.len()));
            out.push((k, now.to_vec()));
            rest = later;
        }
    }
    out
}

/// One scenario through the scalar step.
fn scalar_accel(sc: &Scenario) -> Result<Vec<f64>, RunError> {
    simulate::run(sc, |_, _| {}).map(|o| o.accel)
}

/// Scenarios `idx` of `scs` (at most K, shareable) as one lane group; padding lanes
/// repeat the last scenario and are dropped.
fn run_group<const K: usize>(scs: &[Scenario], idx: &[usize]) -> Vec<Result<Vec<f64>, RunError>> {
    let scalar = || idx.iter().map(|&i| scalar_accel(&scs[i])).collect();
    let Some(last) = idx.len().checked_sub(1) else {
        return Vec::new();
    };
    if idx.len() > K {
        return scalar();
    }
    let sc0 = &scs[idx[0]];
    let fs = sc0.fs();
    let n = (sc0.run.duration * fs).round() as usize;
    let settle = (sc0.run.settle * fs).round() as usize;
    let models: [Model; K] = std::array::from_fn(|l| scs[idx[l.min(last)]].model.clone());
    let seeds: [u64; K] = std::array::from_fn(|l| scs[idx[l.min(last)]].run.seed);
    let Some(lanes) = lane_accel(&models, &seeds, settle, n) else {
        return scalar();
    };
    lanes
        .into_iter()
        .zip(idx)
        .map(|(r, &i)| match r {
            Ok(a) => Ok(a),
            Err(_) => scalar_accel(&scs[i]),
        })
        .collect()
}

/// Runs `models` (seeds `seeds`) as one lane group: `settle` output samples discarded,
/// then `n` kept; per lane its acceleration, or `Err(accel)` when a sample of any
/// channel is non-finite (the caller reruns that lane alone for the scalar error).
/// `None` when the core refuses the group.
#[allow(clippy::type_complexity)]
pub fn lane_accel<const K: usize>(
    models: &[Model; K],
    seeds: &[u64; K],
    settle: usize,
    n: usize,
) -> Option<Vec<Result<Vec<f64>, Vec<f64>>>> {
    on_worker_stack(|| lane_accel_here(models, seeds, settle, n))
}

/// [`lane_accel`] on the calling thread's stack.
#[allow(clippy::type_complexity)]
fn lane_accel_here<const K: usize>(
    models: &[Model; K],
    seeds: &[u64; K],
    settle: usize,
    n: usize,
) -> Option<Vec<Result<Vec<f64>, Vec<f64>>>> {
    let group = LaneGroup::<K, CAPACITY>::new_checked(models, seeds).ok()?;
    let mut group = Box::new(group);
    let mut chunk: Vec<[Sample; K]> = std::iter::repeat_n([Sample::default(); K], 1024).collect();
    let mut left = settle;
    while left > 0 {
        let k = left.min(chunk.len());
        fill(&mut group, &mut chunk[..k]);
        left -= k;
    }
    let mut accel: Vec<Vec<f64>> = (0..K).map(|_| Vec::with_capacity(n)).collect();
    let mut finite = [true; K];
    let mut done = 0;
    while done < n {
        let k = (n - done).min(chunk.len());
        fill(&mut group, &mut chunk[..k]);
        for row in &chunk[..k] {
            for ((a, s), ok) in accel.iter_mut().zip(row).zip(finite.iter_mut()) {
                *ok &= s.accel.is_finite() && s.vel.is_finite() && s.disp.is_finite();
                a.push(s.accel);
            }
        }
        done += k;
    }
    Some(
        accel
            .into_iter()
            .zip(finite)
            .map(|(a, ok)| if ok { Ok(a) } else { Err(a) })
            .collect(),
    )
}

/// [`lane_accel`] that also shows the group to `observe` after every internal step once
/// `settle` output samples are done, up to the step that gives the last kept sample (the
/// steps a scalar run observes when it checks `emitted >= settle` after each step): a
/// life's windows measure their pass loads this way. `None` when the core refuses the
/// group or any lane gives a non-finite acceleration (the caller runs those scalar).
pub fn lane_accel_observed<const K: usize>(
    models: &[Model; K],
    seeds: &[u64; K],
    settle: usize,
    n: usize,
    observe: impl FnMut(&LaneGroup<'_, K, CAPACITY>) + Send,
) -> Option<Vec<Vec<f64>>> {
    on_worker_stack(|| lane_accel_observed_here(models, seeds, settle, n, observe))
}

/// [`lane_accel_observed`] on the calling thread's stack.
fn lane_accel_observed_here<const K: usize>(
    models: &[Model; K],
    seeds: &[u64; K],
    settle: usize,
    n: usize,
    observe: impl FnMut(&LaneGroup<'_, K, CAPACITY>),
) -> Option<Vec<Vec<f64>>> {
    let group = LaneGroup::<K, CAPACITY>::new_checked(models, seeds).ok()?;
    let mut group = Box::new(group);
    // The settling samples unobserved, then the window observed after every step.
    let mut rows = vec![[Sample::default(); K]; settle.max(n)];
    let finite = |r: &[[Sample; K]]| r.iter().flatten().all(|x| x.accel.is_finite());
    let settled = rows.get_mut(..settle)?;
    fill(&mut group, settled);
    if !finite(settled) {
        return None;
    }
    let kept = rows.get_mut(..n)?;
    fill_observed(&mut group, kept, observe);
    if !finite(kept) {
        return None;
    }
    Some(
        (0..K)
            .map(|l| {
                kept.iter()
                    .map(|r| r.get(l).map_or(0.0, |x| x.accel))
                    .collect()
            })
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Items keyed by (kind, speed): the same key shares the kinematics, the same kind at
    /// another speed shares a group at its own speed, another kind shares nothing.
    fn relation(keys: &[(u8, u8)]) -> impl Fn(usize, usize) -> Sharing + '_ {
        move |a, b| match (keys[a], keys[b]) {
            (x, y) if x == y => Sharing::Kinematics,
            ((ka, _), (kb, _)) if ka == kb => Sharing::OwnSpeed,
            _ => Sharing::No,
        }
    }

    /// Every item is planned exactly once; groups that share the kinematics form first and
    /// are cut by `group_size`; only the items they leave alone pool at their own speed, in
    /// runs of 16 or 8, and fewer than 8 such items run alone.
    #[test]
    fn plan_shares_kinematics_first_and_pools_the_rest_at_their_own_speed() {
        // Kind 0: 20 items at speed 0, then 11 items each at its own speed.
        // Kind 1: 3 items at speed 0, 5 items each at its own speed.
        let mut keys: Vec<(u8, u8)> = vec![(0, 0); 20];
        keys.extend((1..=11).map(|s| (0, s)));
        keys.extend([(1, 0); 3]);
        keys.extend((1..=5).map(|s| (1, s)));
        let plan = plan(keys.len(), relation(&keys));
        let mut seen: Vec<usize> = plan.iter().flat_map(|(_, g)| g.clone()).collect();
        seen.sort_unstable();
        assert_eq!(seen, (0..keys.len()).collect::<Vec<_>>());
        let sizes: Vec<(usize, usize)> = plan.iter().map(|(k, g)| (*k, g.len())).collect();
        // 20 shared: 16 + 4; 3 shared: one 4-lane group (1 padding lane); kind 0's 11 own
        // speeds: 8 together, 3 alone; kind 1's 5 own speeds: alone.
        let shared: Vec<(usize, usize)> = sizes.iter().copied().filter(|(k, _)| *k > 1).collect();
        assert_eq!(shared, vec![(16, 16), (4, 4), (4, 3), (8, 8)]);
        assert_eq!(sizes.iter().filter(|(k, _)| *k == 1).count(), 3 + 5);
        for (k, g) in &plan {
            if *k > 1 {
                let lead = keys[g[0]];
                let own = g.iter().any(|&i| keys[i] != lead);
                assert!(g.iter().all(|&i| keys[i].0 == lead.0), "kinds mix in {g:?}");
                assert!(!own || *k >= 8, "a small group at own speeds: {g:?}");
            }
        }
    }

    /// A thread [`spawn_worker`] started runs its groups on its own stack (touched once,
    /// not a fresh thread's per group); any other thread hands them to a worker.
    #[test]
    fn a_worker_runs_its_groups_on_its_own_stack() {
        let here = std::thread::current().id();
        let id = || Some(std::thread::current().id());
        assert_ne!(on_worker_stack(id), Some(here));
        std::thread::scope(|s| {
            let worker = spawn_worker(s, || (std::thread::current().id(), on_worker_stack(id)));
            let (me, ran_on) = worker.unwrap().join().unwrap();
            assert_eq!(ran_on, Some(me));
        });
    }
}
