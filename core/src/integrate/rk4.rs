//! Classical fourth-order Runge–Kutta step for `y'' = f(stage, y, y')`.

use crate::real::Real;

/// Stage at which the right-hand side is evaluated: start, midpoint or end of the step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    /// `t`.
    Start,
    /// `t + h/2`.
    Mid,
    /// `t + h`.
    End,
}

/// One RK4 step of length `h` for `(y, v)`; `f(stage, y, v)` returns the acceleration.
/// Returns `(y, v, a₀)` with `a₀` the acceleration at the start of the step.
#[inline(always)]
pub fn step<F: FnMut(Stage, Real, Real) -> Real>(
    y: Real,
    v: Real,
    h: Real,
    mut f: F,
) -> (Real, Real, Real) {
    let a1 = f(Stage::Start, y, v);
    let (y2, v2) = (y + 0.5 * h * v, v + 0.5 * h * a1);
    let a2 = f(Stage::Mid, y2, v2);
    let (y3, v3) = (y + 0.5 * h * v2, v + 0.5 * h * a2);
    let a3 = f(Stage::Mid, y3, v3);
    let (y4, v4) = (y + h * v3, v + h * a3);
    let a4 = f(Stage::End, y4, v4);
    (
        y + h / 6.0 * (v + 2.0 * v2 + 2.0 * v3 + v4),
        v + h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4),
        a1,
    )
}
