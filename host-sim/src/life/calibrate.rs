//! Calibration of a simulated life on a measured one.
//!
//! **The life factor alone** ([`calibrate`]; `wearsim ims-compare`, `ims-validate`, and
//! `gap --life` on a training life without an onset): secant steps on the part of the life
//! the factor scales. With `F` the revolutions the factor does not scale (from crack opening to
//! failure, fixed physics) and `L` the simulated life at factor `a`, the next factor is
//! `a · (T − F)/(L − F)` for the target `T`; the fatigue part is close to proportional to
//! the factor, so the steps converge in a few lives. `F = 0` scales the whole life (a plain
//! proportional step), which the lifetime gap uses: its simulated lives already land
//! within 1 % after two or three steps. `wearsim ims-compare` takes `F` from its
//! uncalibrated life. A step ratio is clamped to 1e-9..=1e6 so that a degenerate life
//! cannot drive the factor to 0 or infinity.
//!
//! **The life factor and the propagation limit** ([`calibrate_shape`]; `gap --life` on a
//! training life with an onset of instability): the length and the onset together.

use wearsim_core::wear::material::{MAX_LIFE_FACTOR, MIN_LIFE_FACTOR};

/// Most revolutions a calibrated life may run (far beyond any rating life: the cap only
/// stops a life that would never fail).
pub const CALIBRATED_CAP: f64 = 1e13;

/// The two scales of a simulated life that a measured life calibrates ([`calibrate_shape`];
/// [`calibrate`] sets the first alone).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scales {
    /// `material.life_factor` (–): scales the ISO 281 fatigue part of the life.
    pub life_factor: f64,
    /// `material.propagation_passes` (passes): the propagation limit of the spall's spawns,
    /// the part of the life after its onset.
    pub propagation_passes: f64,
}

impl Scales {
    /// The material's defaults ([`wearsim_core::wear::Material::BEARING_STEEL`]).
    pub fn steel() -> Scales {
        let m = wearsim_core::wear::Material::BEARING_STEEL;
        Scales {
            life_factor: m.life_factor,
            propagation_passes: m.propagation_passes,
        }
    }

    /// The wear configuration of bearing steel at these scales: the material's defaults
    /// with `life_factor` and `propagation_passes` set, the default tribology, and
    /// [`CALIBRATED_CAP`].
    pub fn life(&self) -> wearsim_core::wear::LifeConfig {
        use wearsim_core::wear::{LifeConfig, Material};
        LifeConfig {
            material: Material {
                life_factor: self.life_factor as wearsim_core::Real,
                propagation_passes: self.propagation_passes as wearsim_core::Real,
                ..Material::BEARING_STEEL
            },
            cycle_cap: CALIBRATED_CAP as wearsim_core::Real,
            ..LifeConfig::DEFAULT
        }
    }

    /// The material's propagation limit with `life_factor`.
    pub fn with_factor(life_factor: f64) -> Scales {
        Scales {
            life_factor,
            ..Scales::steel()
        }
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
        // Inside the factors a material accepts; pinned at a bound, another life at the
        // same factor would only repeat the last (the caller reports the miss).
        let next = (a * ((target - s.fixed) / (life - s.fixed)).clamp(1e-9, 1e6))
            .clamp(MIN_LIFE_FACTOR, MAX_LIFE_FACTOR);
        if next == a {
            break;
        }
        a = next;
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

/// What [`calibrate_shape`] matches of a life: its length and its onset of instability.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shape {
    /// Revolutions to failure.
    pub life: f64,
    /// Onset of instability, fraction of life ([`super::ims::onset`]); `None` when the RMS
    /// never leaves its steady band.
    pub onset: Option<f64>,
}

/// Tolerance on the onset (fraction of life) of [`calibrate_shape`]: one window of the
/// lifetime schedule late in life (`gap::lifetime::SCHEDULE`, 2 % of life).
pub const ONSET_TOLERANCE: f64 = 0.02;

/// Least share of a simulated life counted as after its onset in a step of
/// [`calibrate_shape`] (a life without an onset, or with one in its last window, would
/// otherwise give an unbounded step).
const MIN_POST: f64 = 0.02;

/// Most lives [`calibrate_shape`] runs to match the length alone after its joint steps.
pub const LENGTH_STEPS: usize = 4;

/// Bounds of the propagation limit `material.propagation_passes` (`Material::new_checked`).
pub const PROPAGATION_BOUNDS: (f64, f64) = (1.0, 1e12);

/// The next value of a scale `x` whose part `y` of a life should become `want`, given the
/// last step's `(x, y)`: a secant through both when their slope is positive (a part is
/// close to affine in its scale: a scaled share plus a share the scale does not touch,
/// which proportional steps approach only geometrically), bounded to a factor 10 of `x`;
/// otherwise (first step, a slope the onset's window grid made flat or negative) the
/// proportional step `x·want/y`.
fn next_scale(x: f64, y: f64, prev: Option<(f64, f64)>, want: f64) -> f64 {
    let proportional = x * (want / y).clamp(1e-9, 1e6);
    prev.and_then(|(x0, y0)| {
        let k = (y - y0) / (x - x0);
        let v = x + (want - y) / k;
        (k.is_finite() && k > 0.0 && v.is_finite()).then(|| v.clamp(x / 10.0, x * 10.0))
    })
    .unwrap_or(proportional)
}

/// A life calibrated in both scales.
#[derive(Debug, Clone)]
pub struct ShapeCalibrated<T> {
    /// Life factor of the last life run.
    pub factor: f64,
    /// Propagation limit (passes) of the last life run.
    pub propagation_passes: f64,
    /// Its length and onset.
    pub shape: Shape,
    /// Lives run by the steps (the first life is not counted).
    pub steps: usize,
    /// What the last run returned besides its shape.
    pub last: T,
}

/// Calibrates two scales of a life on a measured one: its length `target` (revolutions)
/// and its onset of instability `onset` (fraction of life). The life factor scales the
/// part before the onset (ISO 281 fatigue; the dent and crack stages it does not scale),
/// the propagation limit `material.propagation_passes` the part after it (the spall's
/// spawns, `wear::life`): steps on each part towards `u T` and `(1 − u) T`
/// (`next_scale`: proportional first, `a ← a·(u T)/(u_s L)`, then secant), until both
/// are within tolerance or after `max_steps`; then, if the length is still off (an onset
/// out of reach), up to [`LENGTH_STEPS`] more with the propagation limit held and the part
/// before the onset aiming at what the part after it leaves,
/// `a ← a·(T − (1 − u_s) L)/(u_s L)`: the length is matched, the onset comes earlier than
/// measured. The caller judges the last life, which is returned either way. `first` is
/// the shape and result at the scales `start`; `run(a, n_p)` runs a life.
///
/// The propagation limit is the one constant of the wear model with neither a literature
/// value nor a stress dependence confirmed by a source
/// (`../shared/docs/life-physics-sources.md` §1), and its default was set on the thesis's
/// reference bearing: a measured life says how long its bearing's spall grows, and this
/// calibration reads that off the training life only.
pub fn calibrate_shape<T, E>(
    target: f64,
    onset: f64,
    start: Scales,
    first: (Shape, T),
    max_steps: usize,
    mut run: impl FnMut(f64, f64) -> Result<(Shape, T), E>,
) -> Result<ShapeCalibrated<T>, E> {
    let within = |s: &Shape| {
        (s.life / target - 1.0).abs() < TOLERANCE
            && s.onset
                .is_some_and(|u| (u - onset).abs() <= ONSET_TOLERANCE)
    };
    let (mut shape, mut last) = first;
    let (mut a, mut n_p) = (start.life_factor, start.propagation_passes);
    let mut steps = 0;
    let min_factor = MIN_LIFE_FACTOR;
    let split = |s: &Shape| {
        let u_s = s.onset.unwrap_or(1.0).min(1.0 - MIN_POST);
        (u_s * s.life, (1.0 - u_s) * s.life)
    };
    let mut prev: Option<(f64, f64, f64, f64)> = None;
    while steps < max_steps && !within(&shape) {
        let (pre_s, post_s) = split(&shape);
        let (a_new, n_new) = (
            next_scale(a, pre_s, prev.map(|p| (p.0, p.2)), onset * target)
                .clamp(min_factor, MAX_LIFE_FACTOR),
            next_scale(
                n_p,
                post_s,
                prev.map(|p| (p.1, p.3)),
                (1.0 - onset) * target,
            )
            .clamp(PROPAGATION_BOUNDS.0, PROPAGATION_BOUNDS.1),
        );
        prev = Some((a, n_p, pre_s, post_s));
        (a, n_p) = (a_new, n_new);
        (shape, last) = run(a, n_p)?;
        steps += 1;
    }
    // Where the onset could not be reached (the part after it cannot shrink to the
    // measured one: its crack growth after the first spall runs on absolute stresses), the
    // length comes first: the propagation limit held, the part before the onset takes what
    // the part after it leaves of the target.
    let mut extra = 0;
    while extra < LENGTH_STEPS && (shape.life / target - 1.0).abs() >= TOLERANCE {
        let (pre_s, post_s) = split(&shape);
        let want = (target - post_s).max(1e-3 * target);
        let next = (a * (want / pre_s).clamp(1e-9, 1e6)).clamp(min_factor, MAX_LIFE_FACTOR);
        if next == a {
            break;
        }
        a = next;
        (shape, last) = run(a, n_p)?;
        steps += 1;
        extra += 1;
    }
    Ok(ShapeCalibrated {
        factor: a,
        propagation_passes: n_p,
        shape,
        steps,
        last,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A target past the largest life factor (probe of stop 69: a table 10⁹ s per snapshot
    /// ended in "material.life_factor = 507513 is out of range"): the factor stops at the
    /// bound, one life there, and the miss is returned for the caller to report.
    #[test]
    fn a_target_beyond_the_largest_factor_stops_at_it() {
        let run = |a: f64| -> Result<(f64, ()), String> {
            if (MIN_LIFE_FACTOR..=MAX_LIFE_FACTOR).contains(&a) {
                Ok((1e7 * a, ()))
            } else {
                Err(format!("factor {a} outside the material's range"))
            }
        };
        let s = Secant {
            fixed: 0.0,
            min_steps: 0,
            max_steps: 8,
        };
        let c = calibrate(1e13, (1e7, ()), &s, run).unwrap();
        assert_eq!(c.factor, MAX_LIFE_FACTOR);
        assert_eq!(c.steps, 1);
        let c = calibrate(1e-6, (1e7, ()), &s, run).unwrap();
        assert_eq!(c.factor, MIN_LIFE_FACTOR);
    }

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

    /// The scales of the model lives' first run.
    const START: Scales = Scales {
        life_factor: 1.0,
        propagation_passes: 1.5e7,
    };

    /// The steps start from the scales of the first life, whatever they are: a life whose
    /// parts are proportional to their scales lands in one step from the material's own
    /// factor (4.3·10⁻⁴), as it does from 1. A step taken as if the first life had run at
    /// factor 1 overshoots by 1/4.3·10⁻⁴ and needs more.
    #[test]
    fn the_first_step_is_proportional_from_the_first_lifes_scales() {
        let shape = |a: f64, n_p: f64| {
            let (pre, post) = (a * 1.0e7, n_p / 1.5e7 * 4.0e6);
            Shape {
                life: pre + post,
                onset: Some(pre / (pre + post)),
            }
        };
        let run = |a: f64, n_p: f64| -> Result<(Shape, ()), ()> { Ok((shape(a, n_p), ())) };
        for start in [START, Scales::steel()] {
            let (a0, n0) = (start.life_factor, start.propagation_passes);
            let c = calibrate_shape(3.0e4, 0.6, start, (shape(a0, n0), ()), 12, run).unwrap();
            assert_eq!(c.steps, 1, "{start:?}: {c:?}");
            assert!((c.factor - 1.8e-3).abs() < 1e-12, "{c:?}");
            assert!((c.propagation_passes - 45_000.0).abs() < 1e-6, "{c:?}");
        }
    }

    /// A model life: the part before the onset `a·F + C` (fatigue scaled by the factor,
    /// crack stages fixed), after it `N_p·P + D` (spawns scaled by the limit, the crack
    /// growth after the first spall fixed).
    fn model(a: f64, n_p: f64) -> Shape {
        let (pre, post) = (a * 1.0e7 + 2.0e4, n_p / 1.5e7 * 4.0e6 + 1.0e4);
        Shape {
            life: pre + post,
            onset: Some(pre / (pre + post)),
        }
    }

    #[test]
    fn both_scales_reach_a_length_and_an_onset() {
        let run = |a: f64, n_p: f64| -> Result<(Shape, ()), ()> { Ok((model(a, n_p), ())) };
        for (target, onset) in [(4.0e7, 0.69), (1.2e5, 0.6), (3.0e9, 0.9)] {
            let c =
                calibrate_shape(target, onset, START, (model(1.0, 1.5e7), ()), 12, run).unwrap();
            assert!(
                (c.shape.life / target - 1.0).abs() < TOLERANCE,
                "{target}: {c:?}"
            );
            let u = c.shape.onset.unwrap();
            assert!((u - onset).abs() <= ONSET_TOLERANCE, "{target}: {c:?}");
        }
    }

    /// An onset so late that the part after it is shorter than the fixed crack growth `D`:
    /// the limit ends at its least and the length is still matched.
    #[test]
    fn a_late_onset_out_of_reach_still_matches_the_length() {
        let run = |a: f64, n_p: f64| -> Result<(Shape, ()), ()> { Ok((model(a, n_p), ())) };
        let (target, onset) = (1.2e5, 0.95); // 6·10³ after the onset, D = 10⁴
        let c = calibrate_shape(target, onset, START, (model(1.0, 1.5e7), ()), 12, run).unwrap();
        assert!(c.propagation_passes < 1e3, "{c:?}");
        assert!((c.shape.life / target - 1.0).abs() < TOLERANCE, "{c:?}");
        assert!(c.shape.onset.unwrap() < onset - 0.02, "{c:?}");
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
