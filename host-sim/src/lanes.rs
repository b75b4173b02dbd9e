//! Host side of the K-lane stepper ([`wearsim_core::model::LaneGroup`]): packed square
//! roots (`sqrtpd`, which the `unsafe`-free core cannot issue) and, where the CPU has
//! AVX2, the whole lane step compiled for it, chosen at run time. Both keep the scalar
//! step's bits: IEEE-754 square roots are correctly rounded in every form, and AVX2 does
//! not bring fused multiply-add (Rust never contracts `a*b + c` on its own).

use wearsim_core::model::{LaneGroup, SqrtLanes};
use wearsim_core::Sample;

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

/// Which code path [`fill`] takes on this CPU: `"avx2"` or `"sse2"`.
pub fn simd_path() -> &'static str {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        return "avx2";
    }
    "sse2"
}

/// [`LaneGroup::fill`] with packed square roots, compiled for AVX2 when the CPU has it.
pub fn fill<const K: usize, const NB: usize>(
    group: &mut LaneGroup<'_, K, NB>,
    out: &mut [[Sample; K]],
) -> usize {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU has AVX2 (checked just above).
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
