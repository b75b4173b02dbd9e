//! The scalar type of the model and the few transcendental functions it uses.
//!
//! `Real` is `f64` in the `wearsim-core` package and `f32` in `wearsim-core-f32` (Cortex-M4F),
//! a second package compiled from this same source with `cfg(wearsim_f32)` set by its build
//! script: the two precisions are separate types (`wearsim_core::Model`,
//! `wearsim_core_f32::Model`), so every feature stays additive and both can be linked into one
//! program and tested on the host. All
//! transcendental functions go through `libm` (pure Rust, identical results on every
//! target for the same type). With the `fast-math` feature, sine and cosine come from
//! `micromath` (single precision only; max abs error 1.1·10⁻³, measured by `tests/fast_math.rs`); its square root
//! is not used: its 6 % relative error would become a 9 % error of every Hertz force.

/// Floating-point type of every physical quantity in the core (SI units throughout).
#[cfg(not(wearsim_f32))]
pub type Real = f64;
/// Floating-point type of every physical quantity in the core (SI units throughout).
#[cfg(wearsim_f32)]
pub type Real = f32;

/// Whether [`Real`] is `f32` (the `wearsim-core-f32` package): lets precision-specific code
/// paths be chosen by a constant that the compiler folds, instead of a `cfg` outside this file.
pub const SINGLE_PRECISION: bool = cfg!(wearsim_f32);

/// π in [`Real`].
pub const PI: Real = core::f64::consts::PI as Real;
/// 2π in [`Real`].
pub const TAU: Real = core::f64::consts::TAU as Real;
/// √3 (exact to the precision of [`Real`]).
pub const SQRT_3: Real = 1.732_050_807_568_877_3_f64 as Real;
/// √3/2.
pub const HALF_SQRT_3: Real = 0.866_025_403_784_438_6_f64 as Real;
/// Standard gravity g₀ (m/s²), CGPM 1901, used to express acceleration in g.
pub const STANDARD_GRAVITY: Real = 9.806_65;

macro_rules! math_fns {
    ($($(#[$doc:meta])* $name:ident($($arg:ident),+) => $f64:path, $f32:path, $fast:path;)*) => {
        $(
            $(#[$doc])*
            #[inline(always)]
            pub fn $name($($arg: Real),+) -> Real {
                #[cfg(not(wearsim_f32))]
                { $f64($($arg),+) }
                #[cfg(all(wearsim_f32, not(feature = "fast-math")))]
                { $f32($($arg),+) }
                #[cfg(all(wearsim_f32, feature = "fast-math"))]
                { $fast($($arg),+) }
            }
        )*
    };
}

#[cfg(all(wearsim_f32, feature = "fast-math"))]
mod fast {
    use super::Real;
    use micromath::F32Ext;
    pub fn sin(x: Real) -> Real {
        F32Ext::sin(x)
    }
    pub fn cos(x: Real) -> Real {
        F32Ext::cos(x)
    }
}

math_fns! {
    /// Square root.
    sqrt(x) => libm::sqrt, libm::sqrtf, libm::sqrtf;
    /// Sine (argument in rad).
    sin(x) => libm::sin, libm::sinf, fast::sin;
    /// Cosine (argument in rad).
    cos(x) => libm::cos, libm::cosf, fast::cos;
    /// Exponential.
    exp(x) => libm::exp, libm::expf, libm::expf;
    /// Natural logarithm.
    ln(x) => libm::log, libm::logf, libm::logf;
    /// `x^y`.
    pow(x, y) => libm::pow, libm::powf, libm::powf;
    /// Cube root.
    cbrt(x) => libm::cbrt, libm::cbrtf, libm::cbrtf;
    /// Arc sine (rad).
    asin(x) => libm::asin, libm::asinf, libm::asinf;
    /// Largest integer not above `x`.
    floor(x) => libm::floor, libm::floorf, libm::floorf;
}

/// Sine and cosine of `x` (rad) from one argument reduction (libm's `sincos`; with
/// `fast-math` the two `micromath` functions).
#[inline(always)]
pub fn sin_cos(x: Real) -> (Real, Real) {
    #[cfg(not(wearsim_f32))]
    {
        libm::sincos(x)
    }
    #[cfg(all(wearsim_f32, not(feature = "fast-math")))]
    {
        libm::sincosf(x)
    }
    #[cfg(all(wearsim_f32, feature = "fast-math"))]
    {
        (fast::sin(x), fast::cos(x))
    }
}

/// `x^{3/2}` for `x ≥ 0` as `x·√x` (Hertz point contact), 0 for `x ≤ 0`.
#[inline(always)]
pub fn pow_3_2(x: Real) -> Real {
    if x > 0.0 {
        x * sqrt(x)
    } else {
        0.0
    }
}

#[cfg(not(wearsim_f32))]
mod ninth_root;

/// `x^{10/9}` for `x ≥ 0` (Lundberg/Palmgren line contact), 0 for `x ≤ 0`: `x·x^{1/9}`, the
/// root in `f64` by one range-reduced ninth root (`real/ninth_root.rs`: within 2 ulp, a
/// third of the cost of two cube roots) and as `∛(∛x)` in `f32`.
#[inline(always)]
pub fn pow_10_9(x: Real) -> Real {
    if x > 0.0 {
        #[cfg(not(wearsim_f32))]
        {
            x * ninth_root::ninth_root(x)
        }
        #[cfg(wearsim_f32)]
        {
            x * cbrt(cbrt(x))
        }
    } else {
        0.0
    }
}

/// Wraps an angle (rad) into `[0, 2π)`; keeps accumulated angles exact enough in `f32`.
#[inline(always)]
pub fn wrap_angle(a: Real) -> Real {
    let q = a / TAU;
    // floor(q) without the call in the common cases (angles advance by less than a turn
    // per step): identical results, a fifth fewer instructions per step on a Cortex-M4F.
    let turns = if (0.0..1.0).contains(&q) {
        0.0
    } else if (1.0..2.0).contains(&q) {
        1.0
    } else {
        floor(q)
    };
    let w = a - TAU * turns;
    if !(0.0..TAU).contains(&w) {
        0.0
    } else {
        w
    }
}

/// Largest angle (rad) [`small_angle_cos_sin`] evaluates by its polynomials.
pub const SMALL_ANGLE: Real = 0.0625;

/// `(cos x, sin x)` of a small angle — one step's advance of a shaft, cage or waviness
/// angle — by their Taylor polynomials to `x⁸`/`x⁷` in Horner form for `|x| ≤`
/// [`SMALL_ANGLE`] (the first omitted terms, `x¹⁰/10!` and `x⁹/9!`, are below 3·10⁻¹⁷ of
/// the value there: within double rounding), else libm's [`cos`] and [`sin`]. A few
/// multiplications instead of two library calls; deterministic, so host and target agree.
#[inline(always)]
pub fn small_angle_cos_sin(x: Real) -> (Real, Real) {
    if !(-SMALL_ANGLE..=SMALL_ANGLE).contains(&x) {
        return (cos(x), sin(x));
    }
    let x2 = x * x;
    let c = 1.0 + x2 * (-0.5 + x2 * (1.0 / 24.0 + x2 * (-1.0 / 720.0 + x2 * (1.0 / 40_320.0))));
    let s = x * (1.0 + x2 * (-1.0 / 6.0 + x2 * (1.0 / 120.0 + x2 * (-1.0 / 5_040.0))));
    (c, s)
}

/// Adds a step `d ∈ [0, 2π)` to an angle in `[0, 2π)` and wraps with one conditional
/// subtraction (cheaper than [`wrap_angle`] on the per-step path; falls back to it for
/// negative steps of a decelerating run and for any out-of-range input).
#[inline(always)]
pub fn advance_angle(a: Real, d: Real) -> Real {
    let s = a + d;
    if (0.0..TAU).contains(&s) {
        s
    } else if (TAU..2.0 * TAU).contains(&s) {
        s - TAU
    } else {
        wrap_angle(s)
    }
}

/// Signed angular difference `a − b` wrapped into `[−π, π)` (rad).
#[inline(always)]
pub fn angle_diff(a: Real, b: Real) -> Real {
    wrap_angle(a - b + PI) - PI
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The polynomials equal libm's cosine and sine within a few units in the last place
    /// (Horner's roundings: 2 for the cosine, 4 relative for the sine) over the whole small
    /// range, and libm's values exactly beyond it.
    #[test]
    fn small_angle_cos_sin_equals_libm() {
        let ulp = Real::EPSILON;
        let n = 20_000;
        for i in -n..=n {
            let x = SMALL_ANGLE * i as Real / n as Real;
            let (c, s) = small_angle_cos_sin(x);
            assert!(
                (c - cos(x)).abs() <= 2.0 * ulp,
                "cos {x}: {c} vs {}",
                cos(x)
            );
            assert!(
                (s - sin(x)).abs() <= 4.0 * ulp * x.abs().max(ulp),
                "sin {x}: {s} vs {}",
                sin(x)
            );
        }
        for x in [0.07, -0.2, 1.0, 3.0] {
            assert_eq!(small_angle_cos_sin(x), (cos(x), sin(x)));
        }
    }
}
