//! Bearing fault detection from an envelope spectrum: search the harmonic
//! families of the characteristic defect frequencies and their modulation
//! sidebands (Randall & Antoni 2011, section 3).

use super::evidence::family_evidence;
pub use super::evidence::{
    false_alarm_db, DetectParams, FamilyEvidence, FaultFamily, HarmonicEvidence,
};
use super::mains::mark_mains_lines;
use super::shaft_comb::{mark_shaft_lines, ShaftComb};
use super::spectrum::Spectrum;
use serde::Serialize;

/// The project's one kinematics type (thesis eq. 17–20 and the structure's natural
/// frequency, Hz), defined in the core.
pub use wearsim_core::kinematics::FaultFrequencies;

/// Result of [`detect_fault`].
#[derive(Debug, Clone, Serialize)]
pub struct FaultDiagnosis {
    /// Diagnosed family: `candidate` when its calibrated confidence is at least
    /// [`super::diagnose::CALL_MIN`], else `None`.
    pub family: FaultFamily,
    /// Confidence in `family`, in [0, 1]: for a family, the probability that it is right
    /// given `margin_db` (logistic calibration fitted on the development part of the CWRU
    /// data, [`super::diagnose::CALIBRATION`]); for `None`, one minus that probability.
    pub confidence: f64,
    /// Leading family before the confidence gate: the family of highest `exclusive_score`
    /// among those with at least `min_harmonics` harmonics found that neither the shaft nor the
    /// mains explain, or `None`.
    pub candidate: FaultFamily,
    /// Evidence margin of `margin_family`: its exclusive score minus the best other family's,
    /// dB per searched harmonic (see `leading`). The confidence is computed from it.
    pub margin_db: f64,
    /// Family whose margin `margin_db` is: the candidate, or, when no family has
    /// `min_harmonics` found (candidate `None`), the family of highest exclusive score (the
    /// best partial one); `None` when no family has any exclusive evidence.
    pub margin_family: FaultFamily,
    /// Exclusive score of the diagnosed family (0 for `None`).
    pub score: f64,
    /// Evidence for every family (inner, outer, ball).
    pub evidence: Vec<FamilyEvidence>,
    /// The envelope's comb of shaft orders, which explains the lines of a family whose
    /// fundamental lies on a shaft order ([`super::shaft_comb`]).
    pub shaft_comb: ShaftComb,
    /// Families whose lines all stand on a comb of a mains harmonic (and lack their
    /// modulation sidebands): counted for no family ([`super::mains`]).
    pub mains: Vec<MainsComb>,
}

/// A family whose lines the mains explain ([`super::mains::mark_mains_lines`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MainsComb {
    /// The family.
    pub family: FaultFamily,
    /// The supply harmonic whose multiples hold its lines, Hz (e.g. 120: twice a 60 Hz grid).
    pub base_hz: f64,
}

/// Diagnose the fault family from an envelope spectrum `env` (e.g. from
/// [`super::envelope_spectrum`] in the band chosen by the kurtogram).
///
/// For each family — inner race (BPFI, sidebands ±shaft), outer race (BPFO)
/// and ball (2×BSF, sidebands ±FTF) — a common fundamental is fitted within
/// the slip tolerance and its harmonics 1..=H are searched within
/// `harmonic_tol`; each peak is rated in dB above the median noise floor
/// around it. A line found by two families (e.g. 2×BPFI and 3×BPFO, 0.7 %
/// apart on a 6205) counts for neither, and the family with the highest
/// exclusive score among those with at least `min_harmonics` harmonics found (not counting lines the shaft or the mains explain, [`super::shaft_comb`], [`super::mains`])
/// is the candidate (Randall & Antoni 2011); it is called when its calibrated confidence
/// ([`super::diagnose`]) is at least one half, otherwise the call is `None`.
/// Non-positive or non-finite characteristic frequencies yield no evidence.
pub fn detect_fault(env: &Spectrum, ff: &FaultFrequencies, p: &DetectParams) -> FaultDiagnosis {
    let mut evidence = vec![
        family_evidence(env, FaultFamily::InnerRace, ff.bpfi, Some(ff.shaft_hz), p),
        family_evidence(env, FaultFamily::OuterRace, ff.bpfo, None, p),
        family_evidence(env, FaultFamily::Ball, 2.0 * ff.bsf, Some(ff.ftf), p),
    ];
    let shaft_comb = mark_shaft_lines(env, ff.shaft_hz, &mut evidence, p);
    let mains = mark_mains_lines(env, &mut evidence, p.min_harmonics)
        .into_iter()
        .map(|(family, base_hz)| MainsComb { family, base_hz })
        .collect();
    mark_shared(&mut evidence, env.df, p);
    let (candidate, margin_family, margin_db) = leading(&evidence, p.min_harmonics);
    let lead = (candidate != FaultFamily::None).then_some(candidate);
    let (family, confidence) =
        super::diagnose::call(lead, margin_db, &super::diagnose::CALIBRATION);
    let family = family.unwrap_or(FaultFamily::None);
    let score = evidence
        .iter()
        .find(|e| e.family == family)
        .map_or(0.0, |e| e.exclusive_score);
    FaultDiagnosis {
        family,
        confidence,
        candidate,
        margin_db,
        margin_family,
        score,
        evidence,
        shaft_comb,
        mains,
    }
}

/// The leading family of the evidence and its margin: the family of highest exclusive score
/// among those with at least `min_harmonics` [`FamilyEvidence::bearing_lines`] (or `None`), and its exclusive
/// score minus the highest exclusive score of the other families (dB per harmonic). With no
/// leading family the margin is the largest exclusive score of any family minus the second
/// (the strength of the best partial evidence).
fn leading(evidence: &[FamilyEvidence], min_harmonics: usize) -> (FaultFamily, FaultFamily, f64) {
    let lead = evidence
        .iter()
        .filter(|e| e.bearing_lines() >= min_harmonics.max(1) && e.exclusive_score > 0.0)
        .max_by(|a, b| a.exclusive_score.total_cmp(&b.exclusive_score));
    let top = |skip: Option<FaultFamily>| {
        evidence
            .iter()
            .filter(|e| Some(e.family) != skip)
            .map(|e| e.exclusive_score)
            .fold(0.0_f64, f64::max)
    };
    match lead {
        Some(l) => (l.family, l.family, l.exclusive_score - top(Some(l.family))),
        None => {
            let best = evidence
                .iter()
                .filter(|e| e.exclusive_score > 0.0)
                .max_by(|a, b| a.exclusive_score.total_cmp(&b.exclusive_score));
            match best {
                Some(b) => (
                    FaultFamily::None,
                    b.family,
                    b.exclusive_score - top(Some(b.family)),
                ),
                None => (FaultFamily::None, FaultFamily::None, 0.0),
            }
        }
    }
}

/// Mark the found harmonics that another family also claims (a found harmonic of another
/// family, or an order `H+1..=2H` of the fitted fundamental of another family with at least
/// `min_harmonics` found, within `max(2 bins, harmonic_tol × f)`) and compute every family's
/// `exclusive_score`: its score without those harmonics, without the harmonics the shaft
/// explains ([`HarmonicEvidence::shaft`]) and without sidebands that fall on another
/// family's found harmonics. A line that two families explain is evidence for
/// neither; the decision rests on the lines only one family explains.
fn mark_shared(evidence: &mut [FamilyEvidence], df: f64, p: &DetectParams) {
    let mut claimed: Vec<(usize, f64)> = evidence
        .iter()
        .enumerate()
        .flat_map(|(i, e)| {
            e.harmonics
                .iter()
                .filter(|h| h.found)
                .filter_map(move |h| h.peak.map(|q| (i, q.freq)))
        })
        .collect();
    // A diagnosable family's comb goes on beyond the harmonics searched (6×BPFO lies 0.7 %
    // from 4×BPFI on a 6205): extend it to twice as many orders.
    for (i, e) in evidence.iter().enumerate() {
        if e.found >= p.min_harmonics.max(1) {
            for order in p.harmonics + 1..=2 * p.harmonics {
                claimed.push((i, order as f64 * e.fundamental_hz));
            }
        }
    }
    let near_other = |i: usize, f: f64| {
        let tol = (p.harmonic_tol * f.abs()).max(2.0 * df);
        claimed.iter().any(|&(j, g)| j != i && (g - f).abs() <= tol)
    };
    for (i, e) in evidence.iter_mut().enumerate() {
        let mut score = 0.0;
        let s = e.sideband_hz.unwrap_or(0.0);
        for h in e.harmonics.iter_mut().filter(|h| h.found) {
            let f = h.peak.map_or(h.expected_hz, |q| q.freq);
            h.shared = near_other(i, f);
            if !h.shared && !h.explained() {
                score += h.over_floor_db;
            }
            if let Some(sb) = h.sidebands_db {
                for (db, fsb) in sb.iter().zip([f - s, f + s]) {
                    if *db > 0.0 && !near_other(i, fsb) {
                        score += p.sideband_weight * db;
                    }
                }
            }
        }
        e.exclusive_score = score / p.harmonics.max(1) as f64;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::envelope::envelope_spectrum;
    use crate::analysis::kurtogram::fast_kurtogram;
    use crate::analysis::spectrum::SpectrumKind;
    use crate::analysis::synth::{gaussian_noise, FaultSignal};
    use proptest::prelude::*;

    const FS: f64 = 12_000.0;
    const N: usize = 36_000;

    use crate::analysis::synth::cwru_6205_1797rpm as cwru;

    /// The false-alarm threshold's closed form: one bin at `p = 2^{-10}` (a Rayleigh
    /// magnitude 10 dB over its median has probability `exp(−10 ln 2)`) gives 10 dB; more
    /// bins or a smaller `p` a higher threshold; and on Gaussian noise the largest of `W`
    /// bins of a power spectrum exceeds it in about `p` of the records.
    #[test]
    fn false_alarm_threshold_has_its_closed_form_and_rate() {
        let one = false_alarm_db(1.0, (-10.0 * core::f64::consts::LN_2).exp());
        assert!((one - 10.0).abs() < 1e-9, "{one}");
        assert!(false_alarm_db(100.0, 0.05) > false_alarm_db(10.0, 0.05));
        assert!(false_alarm_db(100.0, 0.01) > false_alarm_db(100.0, 0.05));
        assert_eq!(false_alarm_db(10.0, 0.0), f64::INFINITY);
        assert_eq!(false_alarm_db(10.0, 1.0), 0.0);
        assert!(false_alarm_db(f64::NAN, 0.05).is_finite());
        // Monte Carlo: periodograms of white noise (independent bins, exponential powers),
        // the largest of W = 64 bins against the median of the record.
        let (w, p, records) = (64usize, 0.05, 2000usize);
        let t = 10f64.powf(false_alarm_db(w as f64, p) / 10.0);
        let mut rng = crate::analysis::synth::Rng::new(3);
        let mut over = 0;
        for _ in 0..records {
            let max = (0..w)
                .map(|_| {
                    let (a, b) = (rng.gaussian(), rng.gaussian());
                    a * a + b * b
                })
                .fold(0.0, f64::max);
            // The median of the exponential distribution: ln 2 times its mean (2 here).
            if max > t * 2.0 * core::f64::consts::LN_2 {
                over += 1;
            }
        }
        let rate = over as f64 / records as f64;
        // Binomial standard error at p = 0.05 over 2000 records: 0.005.
        assert!((rate - p).abs() < 0.02, "rate {rate}");
    }

    fn signal(fault_hz: f64, mod_hz: f64, mod_depth: f64, seed: u64) -> Vec<f64> {
        FaultSignal {
            fs: FS,
            fault_hz,
            mod_hz,
            mod_depth,
            resonance_hz: 3000.0,
            damping: 0.05,
            impulse_amp: 1.0,
            noise_sigma: 0.5,
            seed,
            jitter: 0.0,
        }
        .generate(N)
    }

    /// Kurtogram band selection, envelope spectrum, detection.
    fn diagnose(x: &[f64]) -> FaultDiagnosis {
        let kg = fast_kurtogram(x, FS, 5).unwrap();
        let env = envelope_spectrum(x, FS, Some(kg.best_band)).unwrap();
        detect_fault(&env, &cwru(), &DetectParams::default())
    }

    /// The diagnosed family's score is at least `ratio` times every other's.
    fn assert_margin(d: &FaultDiagnosis, ratio: f64) {
        for e in d.evidence.iter().filter(|e| e.family != d.family) {
            assert!(d.score >= ratio * e.exclusive_score, "{d:#?}");
        }
    }

    #[test]
    fn geometry_matches_cwru_table() {
        // SKF 6205-2RS: 9 balls, d = 7.94 mm, D = 39.04 mm (preset cwru-6205-de), through
        // the core's eq. 17–20.
        let cfg = wearsim_core::presets::by_name("cwru-6205-de").expect("preset");
        let ff: FaultFrequencies =
            wearsim_core::kinematics::FaultOrders::of(&cfg.bearing).at(29.95, 3000.0);
        assert!(
            (ff.bpfo / 29.95 - 3.5848).abs() < 0.001,
            "{}",
            ff.bpfo / 29.95
        );
        assert!((ff.bpfi / 29.95 - 5.4152).abs() < 0.001);
        assert!((ff.ftf / 29.95 - 0.39828).abs() < 0.0001);
        assert!((ff.bsf / 29.95 - 2.357).abs() < 0.001, "{}", ff.bsf / 29.95);
    }

    #[test]
    fn outer_race_fault() {
        let d = diagnose(&signal(cwru().bpfo, 0.0, 0.0, 1));
        assert_eq!(d.family, FaultFamily::OuterRace, "{d:#?}");
        assert_eq!(d.evidence[1].found, 5);
        // BPFI/BPFO is close to 3/2 for this bearing, so even BPFI harmonics
        // coincide with BPFO ones: the inner family gets some evidence too.
        assert_margin(&d, 1.5);
    }

    #[test]
    fn inner_race_fault() {
        let ff = cwru();
        let d = diagnose(&signal(ff.bpfi, ff.shaft_hz, 0.8, 2));
        assert_eq!(d.family, FaultFamily::InnerRace, "{d:#?}");
        let sidebands = d.evidence[0].harmonics[0].sidebands_db.unwrap();
        assert!(sidebands.iter().all(|db| *db > 10.0), "{sidebands:?}");
        assert_margin(&d, 3.0);
    }

    #[test]
    fn ball_fault() {
        let ff = cwru();
        let d = diagnose(&signal(2.0 * ff.bsf, ff.ftf, 0.8, 3));
        assert_eq!(d.family, FaultFamily::Ball, "{d:#?}");
        assert_eq!(d.evidence[2].found, 5);
        assert_margin(&d, 3.0);
    }

    #[test]
    fn noise_is_no_fault() {
        for seed in 10..14 {
            let x = gaussian_noise(N, 1.0, seed);
            let d = diagnose(&x);
            assert_eq!(d.family, FaultFamily::None, "seed {seed}: {d:#?}");
            assert_eq!(d.score, 0.0);
        }
    }

    #[test]
    fn evidence_reports_harmonic_levels() {
        // Hand-made spectrum: lines of 1.0 at k*103 Hz over a floor of 0.01 (not k*100 Hz:
        // a comb on twice a 50 Hz grid is the mains', `super::super::mains`).
        let mut values = vec![0.01; 1001];
        for k in 1..=5 {
            values[k * 103] = 1.0;
        }
        let env = Spectrum {
            df: 1.0,
            values,
            kind: SpectrumKind::Amplitude,
        };
        let ff = FaultFrequencies {
            shaft_hz: 30.0,
            ftf: 12.0,
            bpfo: 104.0, // 1 % slip
            bpfi: 163.0,
            bsf: 71.0,
            natural_hz: 3000.0,
        };
        let d = detect_fault(&env, &ff, &DetectParams::default());
        assert_eq!(d.family, FaultFamily::OuterRace);
        let outer = &d.evidence[1];
        assert_eq!(outer.found, 5);
        for h in &outer.harmonics {
            assert!((h.over_floor_db - 40.0).abs() < 1e-9);
            assert_eq!(h.peak.unwrap().bin, 103 * h.order);
        }
        assert!((d.score - 40.0).abs() < 1e-9, "{d:#?}");
    }

    #[test]
    fn common_fundamental_and_shared_lines() {
        // Outer-race comb at 1.2 % slip above the kinematic BPFO, 0.1 Hz bins.
        let ff = cwru();
        let f0 = ff.bpfo * 1.012;
        let mut values = vec![0.01; 20_000];
        for k in 1..=8 {
            values[(k as f64 * f0 / 0.1).round() as usize] = 1.0;
        }
        let env = Spectrum {
            df: 0.1,
            values,
            kind: SpectrumKind::Amplitude,
        };
        let d = detect_fault(&env, &ff, &DetectParams::default());
        assert_eq!(d.family, FaultFamily::OuterRace, "{d:#?}");
        let outer = &d.evidence[1];
        assert_eq!(outer.found, 5);
        assert!(
            (outer.fundamental_hz - f0).abs() < 0.1,
            "{}",
            outer.fundamental_hz
        );
        // 2x and 4x BPFI fall within 0.7 % of 3x and 6x BPFO: found, but shared,
        // so the inner-race family has no exclusive evidence.
        let inner = &d.evidence[0];
        assert!(inner.found <= 2, "{inner:#?}");
        assert!(
            inner.harmonics.iter().filter(|h| h.found).all(|h| h.shared),
            "{d:#?}"
        );
        assert_eq!(inner.exclusive_score, 0.0);
        assert!(
            (d.score - 40.0 * 4.0 / 5.0).abs() < 1e-6,
            "3x BPFO is shared: {}",
            d.score
        );
    }

    proptest! {
        #[test]
        fn detect_never_panics(
            values in prop::collection::vec(0.0f64..10.0, 0..400),
            df in 0.01f64..5.0,
            shaft in -10.0f64..100.0,
        ) {
            let env = Spectrum { df, values, kind: SpectrumKind::Amplitude };
            let ff = FaultFrequencies { shaft_hz: shaft, ftf: 0.4 * shaft, bpfo: 3.6 * shaft, bpfi: 5.4 * shaft, bsf: 2.4 * shaft, natural_hz: 3000.0 };
            let d = detect_fault(&env, &ff, &DetectParams::default());
            prop_assert!(d.score.is_finite());
        }
    }

    #[test]
    fn the_margin_names_whose_it_is() {
        let ev = |family, found, exclusive_score| FamilyEvidence {
            family,
            base_hz: 100.0,
            fundamental_hz: 100.0,
            sideband_hz: None,
            harmonics: vec![],
            found,
            score: exclusive_score,
            exclusive_score,
        };
        // A candidate: its own margin over the next family.
        let e = [
            ev(FaultFamily::InnerRace, 3, 9.0),
            ev(FaultFamily::Ball, 1, 4.0),
        ];
        assert_eq!(
            leading(&e, 2),
            (FaultFamily::InnerRace, FaultFamily::InnerRace, 5.0)
        );
        // No candidate (ball has one harmonic of two needed): the margin is the best
        // partial family's, and it says so.
        let e = [
            ev(FaultFamily::InnerRace, 0, 0.0),
            ev(FaultFamily::Ball, 1, 4.0),
        ];
        assert_eq!(leading(&e, 2), (FaultFamily::None, FaultFamily::Ball, 4.0));
        // No exclusive evidence at all.
        let e = [
            ev(FaultFamily::InnerRace, 0, 0.0),
            ev(FaultFamily::Ball, 0, 0.0),
        ];
        assert_eq!(leading(&e, 2), (FaultFamily::None, FaultFamily::None, 0.0));
    }
}
