//! Helpers shared by the core's integration tests.
// Written against `Real` (f64 or f32 by package): casts that are no-ops in one precision are
// needed in the other.
#![allow(clippy::unnecessary_cast)]
#![allow(dead_code)]

use wearsim_core::integrate::IntegratorKind;
use wearsim_core::presets;
use wearsim_core::speed::SpeedProfile;
use wearsim_core::{Model, ModelConfig, Real, Sample, State, Structure};

/// A linear single-degree-of-freedom oscillator: no element contact (no load, large
/// clearance), no surface, no defect; imbalance optional.
pub fn linear_sdof(
    m: Real,
    k: Real,
    c: Real,
    fs: Real,
    oversample: u32,
    integrator: IntegratorKind,
) -> ModelConfig {
    ModelConfig {
        structure: Structure {
            mass: m,
            stiffness: k,
            damping: c,
        },
        radial_load: 0.0,
        clearance: 1e-3,
        imbalance: None,
        waviness: None,
        roughness: None,
        defect: None,
        slip: None,
        integrator,
        output_rate: fs,
        oversample: Some(oversample),
        ..presets::by_name("thesis-61810").unwrap()
    }
}

/// Runs `model` for `n` output samples from a fresh state with `seed`.
pub fn run(model: &Model, seed: u64, n: usize) -> Vec<Sample> {
    let mut st: State<32> = State::new(model, seed).unwrap();
    let mut out = vec![Sample::default(); n];
    model.fill(&mut st, &mut out);
    out
}

/// Amplitude and phase (of `A sin(ωt + φ)`) of `x` at `f` (Hz) by least squares on sine and
/// cosine over the samples at times `t`.
pub fn sine_fit(x: &[Real], t: &[Real], f: Real) -> (Real, Real) {
    let w = consts::TAU * f;
    let (mut ss, mut sc, mut cc, mut xs, mut xc) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (xi, ti) in x.iter().zip(t) {
        let (s, c) = (w * ti).sin_cos();
        ss += s * s;
        sc += s * c;
        cc += c * c;
        xs += xi * s;
        xc += xi * c;
    }
    let det = ss * cc - sc * sc;
    let a = (xs * cc - xc * sc) / det; // coefficient of sin
    let b = (xc * ss - xs * sc) / det; // coefficient of cos
    ((a * a + b * b).sqrt(), b.atan2(a))
}

/// Constant-speed profile helper.
pub fn constant(hz: Real) -> SpeedProfile {
    SpeedProfile::Constant(hz)
}

/// Whether the tests run against the single-precision build (`wearsim-core-f32`).
pub const SINGLE: bool = wearsim_core::real::SINGLE_PRECISION;

/// A tolerance set for `f64` arithmetic, widened by 10⁶ in single precision (the tests'
/// double-precision tolerances sit a few thousand ε₆₄ above the rounding floor; ×10⁶ puts the
/// single-precision one about ten ε₃₂ above it).
pub fn tol(double: Real) -> Real {
    if SINGLE {
        double * 1e6
    } else {
        double
    }
}

/// The constants the tests use, in the precision under test.
pub mod consts {
    use wearsim_core::Real;
    /// π.
    pub const PI: Real = std::f64::consts::PI as Real;
    /// 2π.
    pub const TAU: Real = std::f64::consts::TAU as Real;
    /// π/2.
    pub const FRAC_PI_2: Real = std::f64::consts::FRAC_PI_2 as Real;
}

/// Preset `name` without its defect, and its static most loaded element's load (N) at the
/// preset's radial load.
pub fn healthy_static_load(name: &str) -> (ModelConfig, Real) {
    let base = ModelConfig {
        defect: None,
        ..presets::by_name(name).unwrap()
    };
    let q = Model::new_checked(base.clone())
        .unwrap()
        .static_reference()
        .q_max;
    (base, q)
}

/// The outer-race life of the `ims-za2115` preset (Rexnord ZA-2115, 6000 lbf) without a
/// defect and without slip (so no abrasion: the wear laws' plastic and fatigue parts
/// alone), with constant pass loads at the static most loaded element's load `q`: zone
/// `q`, defect edge `1.3 q`.
pub fn za2115_outer_life() -> (wearsim_core::wear::Life, wearsim_core::wear::PassLoads) {
    use wearsim_core::wear::{Life, LifeConfig, Site};
    let (base, q) = healthy_static_load("ims-za2115");
    let cfg = LifeConfig {
        slip: 0.0,
        ..LifeConfig::DEFAULT
    };
    let life = Life::new_checked(cfg, &base.bearing, q, Site::OuterRace).unwrap();
    (life, constant_pass_loads(q))
}

/// Pass loads held constant over a life (N): the zone's most loaded element at `q`, 30 %
/// more at the defect edge, 100 passes per window.
pub fn constant_pass_loads(q: Real) -> wearsim_core::wear::PassLoads {
    wearsim_core::wear::PassLoads {
        zone: q,
        zone_mean: q,
        edge: 1.3 * q,
        edge_cubic: 1.3 * q,
        passes: 100,
    }
}

/// Revolutions until the next transition (at most `cap`).
pub fn revs_to_transition(
    life: &wearsim_core::wear::Life,
    st: &mut wearsim_core::wear::LifeState,
    loads: &wearsim_core::wear::PassLoads,
    cap: Real,
) -> Real {
    let mut done = 0.0;
    while done < cap {
        let adv = life.advance(st, cap - done, loads);
        done += adv.revs;
        if adv.transition.is_some() {
            return done;
        }
    }
    panic!("no transition within {cap} revolutions");
}

/// Weibull slope from the 10 % and 90 % quantiles of `v` (sorted in place):
/// `β = [ln(−ln 0.1) − ln(−ln 0.9)] / ln(x₉₀ / x₁₀)`.
pub fn quantile_slope(v: &mut [Real]) -> (Real, Real) {
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let q = |f: Real| v[((v.len() as Real - 1.0) * f).round() as usize];
    let slope = ((-(0.1 as Real).ln()).ln() - (-(0.9 as Real).ln()).ln()) / (q(0.9) / q(0.1)).ln();
    (slope, q(0.5))
}

/// Pearson correlation of the logarithms of `a` and `b` (positive values, same length).
pub fn log_correlation(a: &[Real], b: &[Real]) -> Real {
    let la: Vec<Real> = a.iter().map(|x| x.ln()).collect();
    let lb: Vec<Real> = b.iter().map(|x| x.ln()).collect();
    let mean = |v: &[Real]| v.iter().sum::<Real>() / v.len() as Real;
    let (ma, mb) = (mean(&la), mean(&lb));
    let cov: Real = la.iter().zip(&lb).map(|(x, y)| (x - ma) * (y - mb)).sum();
    let var = |v: &[Real], m: Real| v.iter().map(|x| (x - m) * (x - m)).sum::<Real>();
    cov / (var(&la, ma) * var(&lb, mb)).sqrt()
}
