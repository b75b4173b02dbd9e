//! Approximation error of the `fast-math` feature (micromath), measured against libm's
//! single-precision functions. Run with `cargo test -p wearsim-core-f32 --features fast-math
//! --test fast_math`; the figures printed are the ones the README reports.
#![cfg(feature = "fast-math")]

use wearsim_core_f32::real;

fn max_err(
    f: impl Fn(f32) -> f32,
    g: impl Fn(f32) -> f32,
    lo: f32,
    hi: f32,
    relative: bool,
) -> f32 {
    let n = 100_000;
    (0..=n)
        .map(|i| {
            let x = lo + (hi - lo) * i as f32 / n as f32;
            let (a, b) = (f(x), g(x));
            if relative {
                ((a - b) / b).abs()
            } else {
                (a - b).abs()
            }
        })
        .fold(0.0, f32::max)
}

#[test]
fn micromath_errors_are_bounded() {
    let tau = core::f32::consts::TAU;
    let sin = max_err(real::sin, libm::sinf, 0.0, tau, false);
    let cos = max_err(real::cos, libm::cosf, 0.0, tau, false);
    let micromath_sqrt = max_err(micromath::F32Ext::sqrt, libm::sqrtf, 1e-9, 1e-3, true);
    println!("fast-math max errors: sin {sin:.2e} (abs), cos {cos:.2e} (abs); micromath sqrt {micromath_sqrt:.2e} (rel, not used)");
    // The bounds are the measured values rounded up, so a regression shows.
    assert!(sin < 1.2e-3, "sin {sin}");
    assert!(cos < 1.2e-3, "cos {cos}");
    // micromath's sqrt is too coarse for the Hertz law (F ∝ δ^1.5): the core keeps libm's.
    assert!(micromath_sqrt > 1e-2);
    assert_eq!(real::sqrt(2.0e-6).to_bits(), libm::sqrtf(2.0e-6).to_bits());
}
