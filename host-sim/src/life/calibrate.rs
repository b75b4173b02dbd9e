//! Calibration of the life factor (the material's `life_factor`, which scales the fatigue
//! part of a life) so that a simulated life lasts a measured number of revolutions.
//!
//! **Method** (the one used by every caller): secant steps on the part of the life the
//! factor scales. With `F` the revolutions the factor does not scale (from crack opening to
//! failure, fixed physics) and `L` the simulated life at factor `a`, the next factor is
//! `a · (T − F)/(L − F)` for the target `T`; the fatigue part is close to proportional to
//! the factor, so the steps converge in a few lives. `F = 0` scales the whole life (a plain
//! proportional step), which the lifetime gap uses: its simulated lives already land
//! within 1 % after two or three steps. `wearsim ims-compare` takes `F` from its
//! uncalibrated life. A step ratio is clamped to 1e-9..=1e6 so that a degenerate life
//! cannot drive the factor to 0 or infinity.

/// Most revolutions a calibrated life may run (far beyond any rating life: the cap only
/// stops a life that would never fail).
pub const CALIBRATED_CAP: f64 = 1e13;

/// The life configuration of bearing steel with its fatigue scaled by `life_factor` (the
/// one parameter the callers calibrate), the default tribology, and [`CALIBRATED_CAP`].
pub fn steel_life(life_factor: f64) -> wearsim_core::wear::LifeConfig {
    use wearsim_core::wear::{LifeConfig, Material};
    LifeConfig {
        material: Material {
            life_factor: life_factor as wearsim_core::Real,
            ..Material::BEARING_STEEL
        },
        cycle_cap: CALIBRATED_CAP as wearsim_core::Real,
        ..LifeConfig::DEFAULT
    }
}

/// Relative tolerance on the life: calibration stops within 1 % of the target.
pub const TOLERANCE: f64 = 0.01;

/// How the secant steps run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Secant {
    /// Revolutions of the life the factor does not scale (`F` above).
    pub fixed: f64,
    /// Steps taken before the tolerance is checked (1: the first life is only a probe).
    pub min_steps: usize,
    /// Most steps (lives run after the first).
    pub max_steps: usize,
}

/// A calibrated life.
#[derive(Debug, Clone)]
pub struct Calibrated<T> {
    /// Life factor of the last life run.
    pub factor: f64,
    /// Its revolutions to failure.
    pub life: f64,
    /// Lives run by the steps (the first life is not counted).
    pub steps: usize,
    /// What the last run returned besides its life.
    pub last: T,
}

/// Calibrates the life factor: `first` is the life (revolutions) and result of a run at
/// factor 1, `run(a)` runs a life at factor `a` and returns its revolutions and result.
/// Stops within [`TOLERANCE`] of `target` (after `min_steps`) or after `max_steps`; the
/// caller decides whether the last life is close enough (it is returned either way).
pub fn calibrate<T, E>(
    target: f64,
    first: (f64, T),
    s: &Secant,
    mut run: impl FnMut(f64) -> Result<(f64, T), E>,
) -> Result<Calibrated<T>, E> {
    let (mut life, mut last) = first;
    let mut a = 1.0;
    let mut steps = 0;
    for i in 0..s.max_steps {
        if i >= s.min_steps && (life / target - 1.0).abs() < TOLERANCE {
            break;
        }
        a *= ((target - s.fixed) / (life - s.fixed)).clamp(1e-9, 1e6);
        (life, last) = run(a)?;
        steps += 1;
    }
    Ok(Calibrated {
        factor: a,
        life,
        steps,
        last,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A life whose fatigue part is proportional to the factor: one secant step lands on
    /// the target exactly, a proportional step does not (it also scales the fixed part).
    #[test]
    fn secant_step_on_the_scaled_part_converges_in_one_step() {
        let (fatigue, fixed, target) = (1.0e7, 2.0e6, 3.0e7);
        let life = |a: f64| fatigue * a + fixed;
        let run = |a: f64| -> Result<(f64, ()), ()> { Ok((life(a), ())) };
        let s = Secant {
            fixed,
            min_steps: 1,
            max_steps: 6,
        };
        let c = calibrate(target, (life(1.0), ()), &s, run).unwrap();
        assert_eq!(c.steps, 1);
        assert!((c.life / target - 1.0).abs() < 1e-12);
        assert!((c.factor - 2.8).abs() < 1e-12);
        let p = Secant {
            fixed: 0.0,
            min_steps: 0,
            max_steps: 8,
        };
        let c = calibrate(target, (life(1.0), ()), &p, run).unwrap();
        assert!(
            c.steps >= 2,
            "the proportional step needs more: {}",
            c.steps
        );
        assert!((c.life / target - 1.0).abs() < TOLERANCE);
    }

    #[test]
    fn a_life_already_on_target_needs_no_step_unless_probed() {
        let run = |_a: f64| -> Result<(f64, ()), ()> { Err(()) };
        let p = Secant {
            fixed: 0.0,
            min_steps: 0,
            max_steps: 8,
        };
        let c = calibrate(1.0e7, (1.0e7, ()), &p, run).unwrap();
        assert_eq!((c.steps, c.factor), (0, 1.0));
    }
}
