//! Envelope lines locked to the mains: a family whose lines stand at exact multiples of a
//! harmonic of the supply frequency.
//!
//! An induction motor on the grid, a transformer or a single-phase rectifier beside the
//! bearing modulates the vibration at twice the line frequency (the magnetic pull of each
//! half cycle) and its multiples, so the envelope spectrum of a healthy machine can hold a
//! comb at 100 or 120 Hz. Where that comb falls inside a bearing family's slip search —
//! the 6205's BPFO (3.585 orders) is 119.5 Hz at 2 000 rpm — frequency alone fits the
//! family to it, and the family wins with every line it searches (stop 61: a healthy
//! synthetic 6205 at 2 000 rpm with 120 Hz impulses exciting a 3 kHz resonance was called
//! outer race at confidence 1.0 in 10 of 10 seeds, and with a 120 Hz sinusoidal modulation
//! of broadband noise in 1 of 10; `scripts/probe-healthy-sources.py`).
//!
//! A bearing's lines are set by the shaft speed and slip, the mains' by the grid, which
//! holds its frequency within ±0.1 % (the 50 mHz standard band of a 50 Hz grid). Lines of a
//! family that all lie on multiples of one mains harmonic within that tolerance (never
//! below 1.5 bins) are counted for neither, as the lines the shaft explains are
//! ([`super::shaft_comb`]): a wrong family is worse than no call. The cost: a true fault
//! whose fundamental sits within the tolerance of a multiple of 50 or 60 Hz loses its call
//! (with 0.1 Hz bins about 1 % of fundamentals between 60 and 200 Hz; more for short
//! records, whose bins are wider). A family with its modulation sidebands (the shaft's
//! around inner-race lines, the cage's around a ball's) keeps them: the grid does not
//! supply those.

use super::evidence::{FamilyEvidence, FaultFamily};
use super::spectrum::Spectrum;

/// Supply frequencies tried, Hz: the 50 Hz and the 60 Hz grids.
pub const MAINS_HZ: [f64; 2] = [50.0, 60.0];

/// Relative tolerance of a line on a mains harmonic: the ±50 mHz standard frequency band
/// of a 50 Hz grid (ENTSO-E), ±0.1 %.
pub const MAINS_TOL: f64 = 1e-3;

/// Least number of a family's found lines that must lie on one mains comb for the mains
/// to explain them (also never fewer than the family's `min_harmonics`).
const MIN_LOCKED: usize = 3;

/// The mains harmonic `M = m·L` (Hz, `L` in [`MAINS_HZ`]) whose multiples hold every found
/// line of `e` at its order (`f_k ≈ k·M` within [`MAINS_TOL`] of `f_k`, never below 1.5
/// bins of `df`), if any, and at least `min_lines` of them.
pub fn locked_base(e: &FamilyEvidence, df: f64, min_lines: usize) -> Option<f64> {
    let lines: Vec<(f64, f64)> = e
        .harmonics
        .iter()
        .filter(|h| h.found)
        .filter_map(|h| Some((h.order as f64, h.peak?.freq)))
        .collect();
    let (k1, f1) = *lines.first()?;
    if lines.len() < min_lines.max(MIN_LOCKED) || !(f1.is_finite() && f1 > 0.0) {
        return None;
    }
    let on = |base: f64| {
        lines
            .iter()
            .all(|&(k, f)| (f - k * base).abs() <= (MAINS_TOL * f).max(1.5 * df))
    };
    MAINS_HZ.iter().find_map(|&l| {
        let m = (f1 / k1 / l).round();
        let base = m * l;
        (m >= 1.0 && on(base)).then_some(base)
    })
}

/// Whether `e` carries its modulation sidebands: at least half of its found lines with one
/// found on either side (inner race: the shaft; ball: the cage). Outer-race lines have none.
fn modulated(e: &FamilyEvidence) -> bool {
    let found: Vec<usize> = (0..e.harmonics.len())
        .filter(|&i| e.harmonics[i].found)
        .collect();
    e.family != FaultFamily::OuterRace && !found.is_empty() && e.sidebands_on(&found)
}

/// Marks the found lines of `evidence` that the mains explain
/// ([`super::evidence::HarmonicEvidence::mains`]). A family whose found lines all stand on
/// one mains comb ([`locked_base`]) and that lacks its modulation sidebands establishes that
/// comb; then every found line of a family without its sidebands that lies on an
/// established comb (within the same tolerance) is the mains' too — the comb's lines do not
/// become a bearing's for standing in another family's search. Returns, per family with
/// lines so marked, the family and the mains harmonic (Hz) whose comb holds them.
pub fn mark_mains_lines(
    env: &Spectrum,
    evidence: &mut [FamilyEvidence],
    min_harmonics: usize,
) -> Vec<(FaultFamily, f64)> {
    let mut bases: Vec<f64> = evidence
        .iter()
        .filter(|e| !modulated(e))
        .filter_map(|e| locked_base(e, env.df, min_harmonics))
        .collect();
    bases.dedup();
    let mut explained = Vec::new();
    for e in evidence.iter_mut().filter(|e| !modulated(e)) {
        let mut on: Option<f64> = None;
        for h in e.harmonics.iter_mut().filter(|h| h.found) {
            let Some(f) = h.peak.map(|q| q.freq) else {
                continue;
            };
            let tol = (MAINS_TOL * f).max(1.5 * env.df);
            if let Some(&b) = bases
                .iter()
                .find(|&&b| (f - (f / b).round().max(1.0) * b).abs() <= tol)
            {
                h.mains = true;
                on.get_or_insert(b);
            }
        }
        if let Some(b) = on {
            explained.push((e.family, b));
        }
    }
    explained
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::faults::{detect_fault, DetectParams};
    use crate::analysis::spectrum::SpectrumKind;
    use wearsim_core::kinematics::{FaultFrequencies, FaultOrders};

    /// Envelope spectrum with 0.1 Hz bins (a 10 s record), floor 0.01, and lines of
    /// amplitude 1 at `k·f0`, `k = 1..=5`.
    fn comb(f0: f64) -> Spectrum {
        let df = 0.1;
        let mut values = vec![0.01; 20_000];
        for k in 1..=5 {
            values[(k as f64 * f0 / df).round() as usize] += 1.0;
        }
        Spectrum {
            df,
            values,
            kind: SpectrumKind::Amplitude,
        }
    }

    /// The CWRU drive-end 6205 at 2 000 rpm: BPFO 3.585 orders, 119.5 Hz.
    fn de_6205_2000() -> FaultFrequencies {
        let cfg = wearsim_core::presets::by_name("cwru-6205-de").expect("preset");
        FaultOrders::of(&cfg.bearing).at(2000.0 / 60.0, 12_000.0)
    }

    /// A comb at twice a 60 Hz grid (120.0 Hz and its multiples) inside the outer race's
    /// slip search is no bearing fault: the mains explain every line and nothing is
    /// called. Without the rule it was an outer-race call.
    #[test]
    fn a_comb_at_twice_the_line_frequency_is_no_outer_race_fault() {
        let ff = de_6205_2000();
        assert!((ff.bpfo - 119.5).abs() < 0.1, "{ff:?}");
        let d = detect_fault(&comb(120.0), &ff, &DetectParams::default());
        assert!(
            d.mains.contains(&crate::analysis::faults::MainsComb {
                family: FaultFamily::OuterRace,
                base_hz: 120.0
            }),
            "{d:#?}"
        );
        assert_eq!(d.family, FaultFamily::None, "{d:#?}");
        assert_eq!(d.candidate, FaultFamily::None, "{d:#?}");
        let outer = &d.evidence[1];
        assert!(outer.found >= 3 && outer.bearing_lines() == 0, "{outer:#?}");
    }

    /// A true outer-race fault 0.6 % below the kinematic BPFO (119.3 Hz: 0.7 Hz, seven bins,
    /// from 120 Hz) is called: its lines are not on the mains comb.
    #[test]
    fn a_fault_beside_the_mains_comb_is_called() {
        let ff = de_6205_2000();
        let d = detect_fault(&comb(119.3), &ff, &DetectParams::default());
        assert!(d.mains.is_empty(), "{:?}", d.mains);
        assert_eq!(d.family, FaultFamily::OuterRace, "{d:#?}");
    }

    /// The lock: every found line within ±0.1 % (never below 1.5 bins) of its order times
    /// one supply harmonic, at least three lines; 50 Hz grids' harmonics too.
    #[test]
    fn locked_base_needs_every_line_on_one_supply_harmonic() {
        let ff = de_6205_2000();
        let p = DetectParams::default();
        let e = |f0: f64| detect_fault(&comb(f0), &ff, &p).evidence[1].clone();
        assert_eq!(locked_base(&e(120.0), 0.1, 3), Some(120.0));
        // 0.05 % off (a grid at 60.03 Hz) is still the grid's.
        assert_eq!(locked_base(&e(120.06), 0.1, 3), Some(120.0));
        assert_eq!(locked_base(&e(119.3), 0.1, 3), None);
        // A 50 Hz grid's fourth harmonic against a 6205 at 1 674 rpm (BPFO 100.0 Hz).
        let ff50 = {
            let cfg = wearsim_core::presets::by_name("cwru-6205-de").expect("preset");
            FaultOrders::of(&cfg.bearing).at(100.0 / 3.5848, 12_000.0)
        };
        let e50 = detect_fault(&comb(100.0), &ff50, &p).evidence[1].clone();
        assert_eq!(locked_base(&e50, 0.1, 3), Some(100.0));
        // A family that must have more lines than it found never locks.
        assert_eq!(locked_base(&e(120.0), 0.1, 6), None);
    }
}
