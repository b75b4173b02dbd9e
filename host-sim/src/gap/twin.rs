//! Twins that resemble real use (issue 13; sim-to-real.md, "Checked on data whose effect is
//! withheld"): how a twin "measured" record differs from the baseline the diagnosis starts
//! from, beyond the withheld effects.
//!
//! * **Mismatch** ([`Mismatch`]): the twin's structure (resonance, damping), defect size,
//!   load and speed differ from the baseline by random amounts the diagnosis does not know.
//!   The realistic amounts are the rig's tolerances, [`Tolerances::RIG`] (sources in
//!   `gap::nuisance`), which the diagnosis may calibrate the rig within.
//! * **Independent records**: the training and held-out records are two runs of the same
//!   twin bearing (one mismatch draw: one physical bearing) with independent seeds, not
//!   halves of one run.
//! * **Out of library** ([`Outside`]): a mechanism no candidate effect models, added to the
//!   twin's signal: a gear-mesh tone of a random tooth count with its 1× sidebands (a
//!   gearbox on the same housing), at 20–100 % of the record's RMS. The library should
//!   leave such a gap open, and the report should say it is not closed.

use super::nuisance::{self, Tolerances, NAMES};
use crate::analysis::stats::rms;
use wearsim_core::rng::Xoshiro128pp;
use wearsim_core::ModelConfig;

/// Relative half-ranges of the twin's random differences from the baseline: the rig's
/// tolerances ([`Tolerances`], the one definition, shared with the diagnosis's calibration
/// of the rig, `gap::nuisance`); each factor is drawn uniformly in `1 ± range`.
pub type Mismatch = Tolerances;

impl Tolerances {
    /// `base` with factors drawn from `rng` within these tolerances; returns the twin's
    /// configuration and the factors (name, factor) for the report. With
    /// [`Tolerances::NONE`] the generator is not touched and `base` is returned unchanged.
    pub fn draw(
        &self,
        base: &ModelConfig,
        rng: &mut Xoshiro128pp,
    ) -> (ModelConfig, Vec<(String, f64)>) {
        if self.is_none() {
            return (base.clone(), vec![]);
        }
        #[allow(clippy::unnecessary_cast)] // Real is f32 in `f32` builds
        let u: [f64; 5] = std::array::from_fn(|_| rng.uniform_pm1() as f64);
        let f = self.factors(&u);
        (
            nuisance::apply(base, &f),
            NAMES
                .iter()
                .zip(f)
                .map(|(n, v)| (n.to_string(), v))
                .collect(),
        )
    }
}

/// A mechanism outside the effect library, added to a twin's signal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Outside {
    /// Gear teeth on the shaft: the mesh tone's order (×shaft speed).
    pub teeth: u32,
    /// Amplitude of the mesh tone, as a fraction of the record's RMS; each 1× sideband
    /// has half of it.
    pub level: f64,
    /// Phase of the mesh tone (rad).
    pub phase: f64,
}

impl Outside {
    /// A random gear mesh: 13–37 teeth, 20–100 % of the RMS.
    pub fn draw(rng: &mut Xoshiro128pp) -> Outside {
        #[allow(clippy::unnecessary_cast)] // Real is f32 in `f32` builds
        let mut u01 = || 0.5 * (rng.uniform_pm1() as f64 + 1.0);
        let teeth = 13 + (25.0 * u01()).floor().min(24.0) as u32;
        Outside {
            teeth,
            level: 0.2 + 0.8 * u01(),
            phase: std::f64::consts::TAU * u01(),
        }
    }

    /// Adds the mesh tone and its sidebands (shaft frequency `shaft_hz`, sample rate
    /// `fs`) to `x`, scaled to `x`'s own RMS.
    pub fn add(&self, x: &mut [f64], shaft_hz: f64, fs: f64) {
        let a = self.level * rms(x) * std::f64::consts::SQRT_2;
        let fm = self.teeth as f64 * shaft_hz;
        let w = std::f64::consts::TAU / fs;
        for (n, v) in x.iter_mut().enumerate() {
            let t = n as f64;
            *v += a
                * ((w * fm * t + self.phase).sin()
                    + 0.5 * (w * (fm - shaft_hz) * t).sin()
                    + 0.5 * (w * (fm + shaft_hz) * t).sin());
        }
    }

    /// Its parameters for the report.
    pub fn named(&self) -> Vec<(String, f64)> {
        vec![
            ("teeth".into(), self.teeth as f64),
            ("level".into(), self.level),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::stats::rms;

    #[test]
    fn no_mismatch_is_the_baseline_and_a_realistic_one_stays_in_its_ranges() {
        let base = crate::gap::validate::scenario().expect("preset");
        let mut rng = Xoshiro128pp::from_u64(3);
        let (same, f) = Mismatch::NONE.draw(&base, &mut rng);
        assert_eq!(same, base);
        assert!(f.is_empty());
        for _ in 0..50 {
            let (cfg, f) = Mismatch::RIG.draw(&base, &mut rng);
            let k = cfg.structure.stiffness / base.structure.stiffness;
            assert!((0.9f64.powi(2)..=1.1f64.powi(2)).contains(&k), "{k}");
            for (name, v) in &f {
                let r = match name.as_str() {
                    "resonance" => 0.1,
                    "damping" => 0.3,
                    "defect_size" => 0.15,
                    "load" => 0.2,
                    _ => 0.005,
                };
                assert!((v - 1.0).abs() <= r + 1e-12, "{name} {v}");
            }
        }
    }

    #[test]
    fn the_gear_mesh_adds_its_level_at_the_mesh_order() {
        let fs = 12_000.0;
        let shaft = 30.0;
        let mut x: Vec<f64> = (0..12_000).map(|n| (0.37 * n as f64).sin()).collect();
        let before = rms(&x);
        let o = Outside {
            teeth: 20,
            level: 0.5,
            phase: 0.0,
        };
        o.add(&mut x, shaft, fs);
        // Tone RMS = level·RMS, each sideband half of it: total added power
        // (0.5² + 2·0.25²)·RMS² = 0.375·RMS², uncorrelated with the signal.
        let after = rms(&x);
        let want = before * (1.0f64 + 0.375).sqrt();
        assert!((after / want - 1.0).abs() < 0.01, "{after} vs {want}");
    }
}
