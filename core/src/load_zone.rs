//! Static load distribution over the elements under a radial load (Stribeck load zone,
//! Harris & Kotzalas 2006 ch. 7): the shaft settles where the structural spring and the
//! Hertz contacts carry the radial load `W`:
//! `K y + Σ_j K_h (y sin θ_j − γ)^p sin θ_j = W`.

use crate::bearing::MAX_ELEMENTS;
use crate::contact::ElementContact;
use crate::forces::defect::StaticReference;
use crate::real::{sin, Real, TAU};

/// Static equilibrium of the loaded bearing.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Equilibrium {
    /// Static radial displacement `y₀` (m), averaged over two cage positions.
    pub y0: Real,
    /// Linearised contact stiffness `Σ_j pK_hδ_j^{p−1} sin²θ_j` (N/m), averaged likewise.
    pub contact_stiffness: Real,
    /// Most loaded element at equilibrium.
    pub reference: StaticReference,
}

/// Solves the equilibrium for `n` elements, radial load `w` (N), structural stiffness `k`
/// (N/m) and radial clearance `gamma` (m) by bisection (the left side is monotonic in y).
/// A negative `gamma` is a uniform preload: every element with positive deflection counts.
pub fn equilibrium(contact: &ElementContact, n: u8, w: Real, k: Real, gamma: Real) -> Equilibrium {
    let mut y_sum = 0.0;
    let mut k_sum = 0.0;
    let mut q_max: Real = 0.0;
    for offset in [0.0, 0.5] {
        let angle = |j: u8| (j as Real + offset) * TAU / n as Real;
        // The elements' sines once per cage position, not once per bisection step (the
        // same values; beyond the table, as for an unvalidated `n`, computed in place).
        let mut sines = [0.0; MAX_ELEMENTS];
        for (j, s) in (0..n).zip(sines.iter_mut()) {
            *s = sin(angle(j));
        }
        let sine = |j: u8| match sines.get(j as usize) {
            Some(s) => *s,
            None => sin(angle(j)),
        };
        let net = |y: Real| -> Real {
            let mut f = k * y;
            for j in 0..n {
                let s = sine(j);
                // Without preload (γ ≥ 0) only the lower half can touch; with it (γ < 0)
                // every element whose deflection is positive carries load.
                if s > 0.0 || gamma < 0.0 {
                    f += contact.load(y * s - gamma) * s;
                }
            }
            f - w
        };
        let (mut lo, mut hi) = (0.0 as Real, gamma.max(0.0) + 1e-9);
        let mut guard = 0;
        while net(hi) < 0.0 && guard < 200 {
            hi *= 2.0;
            guard += 1;
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            // Once `lo` and `hi` are adjacent (or infinite) the midpoint is one of them
            // and no further step changes either: stop (the same result as all 200).
            if mid <= lo || mid >= hi {
                break;
            }
            if net(mid) < 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let y = 0.5 * (lo + hi);
        y_sum += y;
        for j in 0..n {
            let s = sine(j);
            if s > 0.0 || gamma < 0.0 {
                let d = y * s - gamma;
                k_sum += contact.tangent_stiffness(d) * s * s;
                let q = contact.load(d);
                if q > q_max {
                    q_max = q;
                }
            }
        }
    }
    let delta_max = contact.deflection(q_max);
    let (a, b) = contact.outer.semi_axes(q_max);
    Equilibrium {
        y0: 0.5 * y_sum,
        contact_stiffness: 0.5 * k_sum,
        reference: StaticReference {
            q_max,
            delta_max,
            a,
            b,
        },
    }
}
