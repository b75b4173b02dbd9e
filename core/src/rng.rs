//! A small seeded no_std random generator behind the `rand_core` traits.
//!
//! xoshiro128++ (Blackman & Vigna 2018, "Scrambled linear pseudorandom number
//! generators"): 128 bits of state, 32-bit operations only, so it runs as fast on a
//! Cortex-M0/M3 as on the host and produces the same sequence everywhere.

use crate::real::Real;
use rand_core::{RngCore, SeedableRng};

/// One xoshiro128++ step: the next state and the output word. The one definition of the
/// algorithm, for [`Xoshiro128pp`] and for the lanes' word-major generators.
#[inline(always)]
pub(crate) fn next_state(s: [u32; 4]) -> ([u32; 4], u32) {
    let [s0, s1, s2, s3] = s;
    let result = s0.wrapping_add(s3).rotate_left(7).wrapping_add(s0);
    let t = s1 << 9;
    let mut n2 = s2 ^ s0;
    let mut n3 = s3 ^ s1;
    let n1 = s1 ^ n2;
    let n0 = s0 ^ n3;
    n2 ^= t;
    n3 = n3.rotate_left(11);
    ([n0, n1, n2, n3], result)
}

/// Uniform number in `[−1, 1)` from the top 24 bits of `word`, exactly representable and
/// identical in `f32` and `f64`.
#[inline(always)]
pub(crate) fn to_pm1(word: u32) -> Real {
    ((word >> 8) as Real) * (2.0 / 16_777_216.0) - 1.0
}

/// xoshiro128++ generator (period 2¹²⁸ − 1).
#[derive(Debug, Clone, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Xoshiro128pp {
    s: [u32; 4],
}

impl Xoshiro128pp {
    /// Generator from a 64-bit seed, expanded with SplitMix64 (Vigna) so that nearby
    /// seeds give unrelated streams and no seed gives the all-zero state.
    pub fn from_u64(seed: u64) -> Self {
        let mut z = seed;
        let mut next = || {
            z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut x = z;
            x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            x ^ (x >> 31)
        };
        let a = next();
        let b = next();
        let mut s = [a as u32, (a >> 32) as u32, b as u32, (b >> 32) as u32];
        if s == [0; 4] {
            s[0] = 1;
        }
        Xoshiro128pp { s }
    }

    #[inline(always)]
    fn step(&mut self) -> u32 {
        let (next, result) = next_state(self.s);
        self.s = next;
        result
    }

    /// The raw state words (for checkpoints).
    pub fn state_words(&self) -> [u32; 4] {
        self.s
    }

    /// A generator from raw state words (for checkpoints); the all-zero state is replaced
    /// by a valid one.
    pub fn from_state_words(s: [u32; 4]) -> Self {
        Xoshiro128pp {
            s: if s == [0; 4] { [1, 0, 0, 0] } else { s },
        }
    }

    /// Uniform number in `[−1, 1)` built from the top 24 bits, so the value is exactly
    /// representable and identical in `f32` and `f64`.
    #[inline(always)]
    pub fn uniform_pm1(&mut self) -> Real {
        to_pm1(self.step())
    }

    /// Zero-mean, unit-variance approximately Gaussian number (Irwin–Hall sum of four
    /// uniforms, rescaled): cheap, bounded (|x| ≤ 2√3), identical on every target.
    #[inline(always)]
    pub fn gauss_approx(&mut self) -> Real {
        let u = [
            self.uniform_pm1(),
            self.uniform_pm1(),
            self.uniform_pm1(),
            self.uniform_pm1(),
        ];
        irwin_hall_4(u)
    }
}

/// Four uniforms on `[−1, 1)` summed in order and rescaled to unit variance
/// (Var(U[−1, 1)) = 1/3, four of them 4/3): [`Xoshiro128pp::gauss_approx`] and its lane
/// form [`gauss_approx_where`].
#[inline(always)]
fn irwin_hall_4(u: [Real; 4]) -> Real {
    let [a, b, c, d] = u;
    (a + b + c + d) * crate::real::HALF_SQRT_3
}

/// [`Xoshiro128pp::uniform_pm1`] on K generators at once, state word-major (`rng[w][lane]`
/// is word `w` of lane `lane`'s generator): every lane advances. The same words and bits
/// as K scalar generators.
#[inline(always)]
pub(crate) fn uniform_pm1_lanes<const K: usize>(rng: &mut [[u32; K]; 4]) -> [Real; K] {
    uniform_pm1_where(rng, &[true; K])
}

/// [`uniform_pm1_lanes`] advancing only the lanes whose `draw` is set (the others keep
/// their state; their output is meaningless): lane `l`'s generator moves exactly when its
/// scalar code draws.
#[inline(always)]
pub(crate) fn uniform_pm1_where<const K: usize>(
    rng: &mut [[u32; K]; 4],
    draw: &[bool; K],
) -> [Real; K] {
    let [s0, s1, s2, s3] = rng;
    let mut out = [0.0; K];
    for (((((o, a0), a1), a2), a3), d) in out
        .iter_mut()
        .zip(s0.iter_mut())
        .zip(s1.iter_mut())
        .zip(s2.iter_mut())
        .zip(s3.iter_mut())
        .zip(draw)
    {
        let ([n0, n1, n2, n3], result) = next_state([*a0, *a1, *a2, *a3]);
        // A bit mask instead of a branch: the compiler would make the conditional stores
        // masked stores, which are slow on some CPUs.
        let keep_new = (*d as u32).wrapping_neg();
        let pick = |new: u32, old: u32| (new & keep_new) | (old & !keep_new);
        (*a0, *a1, *a2, *a3) = (pick(n0, *a0), pick(n1, *a1), pick(n2, *a2), pick(n3, *a3));
        *o = to_pm1(result);
    }
    out
}

/// [`Xoshiro128pp::gauss_approx`] on the lanes whose `draw` is set (word-major state as
/// [`uniform_pm1_where`]; the others keep their state and get 0).
#[inline(always)]
pub(crate) fn gauss_approx_where<const K: usize>(
    rng: &mut [[u32; K]; 4],
    draw: &[bool; K],
) -> [Real; K] {
    let u0 = uniform_pm1_where(rng, draw);
    let u1 = uniform_pm1_where(rng, draw);
    let u2 = uniform_pm1_where(rng, draw);
    let u3 = uniform_pm1_where(rng, draw);
    let mut out = [0.0; K];
    for (l, (o, d)) in out.iter_mut().zip(draw).enumerate() {
        let at = |u: &[Real; K]| u.get(l).copied().unwrap_or(0.0);
        *o = if *d {
            irwin_hall_4([at(&u0), at(&u1), at(&u2), at(&u3)])
        } else {
            0.0
        };
    }
    out
}

impl RngCore for Xoshiro128pp {
    fn next_u32(&mut self) -> u32 {
        self.step()
    }
    fn next_u64(&mut self) -> u64 {
        let lo = self.step() as u64;
        let hi = self.step() as u64;
        (hi << 32) | lo
    }
    fn fill_bytes(&mut self, dst: &mut [u8]) {
        for chunk in dst.chunks_mut(4) {
            let v = self.step().to_le_bytes();
            for (d, s) in chunk.iter_mut().zip(v.iter()) {
                *d = *s;
            }
        }
    }
}

impl SeedableRng for Xoshiro128pp {
    type Seed = [u8; 16];
    fn from_seed(seed: [u8; 16]) -> Self {
        let mut s = [0u32; 4];
        for (i, c) in seed.chunks_exact(4).enumerate() {
            if let (Some(d), [a, b, cc, dd]) = (s.get_mut(i), c) {
                *d = u32::from_le_bytes([*a, *b, *cc, *dd]);
            }
        }
        if s == [0; 4] {
            s[0] = 1;
        }
        Xoshiro128pp { s }
    }
    fn seed_from_u64(state: u64) -> Self {
        Self::from_u64(state)
    }
}
