//! Envelope lines the shaft explains: a comb at integer orders of the shaft speed.
//!
//! Looseness, rub, misalignment and shaft-speed load variation modulate the whole
//! vibration, including the resonance band a bearing diagnosis demodulates, so the envelope
//! spectrum then holds a comb of lines at 1×, 2×, 3×, … the shaft speed: the
//! discrete-frequency content that Randall & Antoni (2011, MSSP 25:485–520) separate from
//! the bearing's before envelope analysis. A bearing
//! family whose fundamental lies on such an order — the 6203's BPFO is 3.05 orders and its
//! 2×BSF 3.99, both within slip of 3× and 4× — then has every harmonic on the shaft's comb
//! too, and frequency alone cannot say which of the two explains the lines. Those lines are
//! counted for neither (as lines two bearing families explain are, [`super::faults`]): a
//! wrong family is worse than no call.
//!
//! Only a family whose *fundamental* coincides with a shaft order is affected. A family
//! whose fundamental is not an integer order keeps a harmonic that happens to fall on one
//! (the 6205's BPFI is 5.415 orders, its 5th harmonic 27.08): its own comb, not the
//! shaft's, places that line.

use super::evidence::{family_evidence, DetectParams, FamilyEvidence, FaultFamily};
use super::spectrum::Spectrum;
use super::stats::median;
use serde::Serialize;

/// The shaft-order comb of an envelope spectrum.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ShaftComb {
    /// Shaft speed, Hz (the record's rpm / 60).
    pub shaft_hz: f64,
    /// Orders `1..=2 × harmonics` of `shaft_hz` found in the envelope spectrum, each by the
    /// test of a bearing family's harmonic (`min_db` and the false-alarm threshold of its
    /// search region; no slip: the shaft turns at its own speed), within two bins.
    pub orders: Vec<usize>,
    /// Height of each of `orders` over its local noise floor, dB.
    pub orders_db: Vec<f64>,
    /// Families whose lines the comb explains. The family's fitted fundamental lies on a
    /// shaft order `n`; the shaft has evidence of its own — at least `min_harmonics` found
    /// orders that the family's comb does not place a line on (multiples of `n`; `k n ± 1`
    /// for a family with shaft sidebands; for the ball family, whose `n` is 2×BSF,
    /// multiples of BSF, when its lines carry the cage modulation below), the rule a bearing
    /// family must meet to be diagnosed (noise alone,
    /// at the false-alarm rate of each order's search, puts three of ten orders over their
    /// thresholds in about 1 % of records); and those orders are as strong as the family's
    /// lines on the comb (median dB over floor at least theirs): the shaft explains them as
    /// well as the family does — or, for the ball family, its lines on the comb lack the
    /// cage (FTF) sidebands of a ball defect (fewer than half carry one). A fault whose
    /// lines stand above a weaker comb, or a ball whose lines are cage-modulated, keeps them.
    pub explains: Vec<FaultFamily>,
}

/// The integer order `n ≥ 1` of `shaft_hz` that `f` (Hz) lies on, within the harmonic
/// tolerance of [`DetectParams::harmonic_tol`] (never below two bins of `df`), if any.
fn order_of(f: f64, shaft_hz: f64, df: f64, p: &DetectParams) -> Option<usize> {
    if !(f.is_finite() && shaft_hz.is_finite() && shaft_hz > 0.0 && f > 0.0) {
        return None;
    }
    let n = (f / shaft_hz).round().max(1.0);
    ((f - n * shaft_hz).abs() <= (p.harmonic_tol * f).max(2.0 * df)).then_some(n as usize)
}

/// Search the shaft-order comb of `env` and, in every bearing family of `evidence` that the
/// comb explains ([`ShaftComb::explains`]), mark the found harmonics on shaft orders as
/// explained by the shaft ([`super::evidence::HarmonicEvidence::shaft`]). Returns the comb.
pub fn mark_shaft_lines(
    env: &Spectrum,
    shaft_hz: f64,
    evidence: &mut [FamilyEvidence],
    p: &DetectParams,
) -> ShaftComb {
    // Orders 1..=2H: a diagnosable family's comb is extended to twice the harmonics
    // searched when lines are shared (`mark_shared`), and the shaft's is searched as far.
    let exact = DetectParams {
        slip: 0.0,
        harmonics: 2 * p.harmonics,
        ..*p
    };
    let comb = family_evidence(env, FaultFamily::None, shaft_hz, None, &exact);
    let found: Vec<(usize, f64)> = comb
        .harmonics
        .iter()
        .filter(|h| h.found)
        .map(|h| (h.order, h.over_floor_db))
        .collect();
    let orders: Vec<usize> = found.iter().map(|o| o.0).collect();
    let orders_db: Vec<f64> = found.iter().map(|o| o.1).collect();
    let mut explains = Vec::new();
    for e in evidence.iter_mut() {
        let Some(n) = order_of(e.fundamental_hz, shaft_hz, env.df, p) else {
            continue;
        };
        let shaft_sidebands = e
            .sideband_hz
            .is_some_and(|s| (s - shaft_hz).abs() <= 2.0 * env.df);
        let on_comb: Vec<usize> = (0..e.harmonics.len())
            .filter(|&i| {
                let h = &e.harmonics[i];
                let f = h.peak.map_or(h.expected_hz, |q| q.freq);
                h.found && order_of(f, shaft_hz, env.df, p).is_some()
            })
            .collect();
        // A ball's lines are the ball's only with the cage modulation a ball defect carries
        // (`cage_modulated`); without it the shaft explains them whenever it has lines of
        // its own.
        let modulated = e.family != FaultFamily::Ball || cage_modulated(e, &on_comb);
        // A ball's defect strikes each race once per spin: its comb is 2×BSF's, with lines
        // at odd multiples of BSF itself when the two strikes differ (Randall & Antoni 2011)
        // — modulated at FTF as well, so unmodulated lines there are the shaft's.
        let spin = (e.family == FaultFamily::Ball && n % 2 == 0 && modulated).then_some(n / 2);
        let own = |j: usize| {
            j.is_multiple_of(n)
                || spin.is_some_and(|m| j.is_multiple_of(m))
                || (shaft_sidebands
                    && ((j + 1).is_multiple_of(n) || (j > n && (j - 1).is_multiple_of(n))))
        };
        let shaft_own: Vec<f64> = found.iter().filter(|o| !own(o.0)).map(|o| o.1).collect();
        if shaft_own.len() < p.min_harmonics.max(1) {
            continue;
        }
        let family_db: Vec<f64> = on_comb
            .iter()
            .map(|&i| e.harmonics[i].over_floor_db)
            .collect();
        // The shaft explains the lines when its own lines are as strong as them (medians),
        // or when they are a ball's without its cage modulation.
        let as_strong = matches!(
            (median(shaft_own), median(family_db)),
            (Some(shaft), Some(family)) if shaft >= family
        );
        if modulated && !as_strong {
            continue;
        }
        explains.push(e.family);
        for i in on_comb {
            e.harmonics[i].shaft = true;
        }
    }
    ShaftComb {
        shaft_hz,
        orders,
        orders_db,
        explains,
    }
}

/// Whether a ball family's found lines on the shaft comb (`on_comb`, indices into its
/// harmonics) carry the cage modulation of a ball defect: at least half of them with an FTF
/// sideband found on either side. A defective ball enters and leaves the load zone once per
/// cage revolution, so its 2×BSF lines are modulated at FTF (Randall & Antoni 2011), and
/// FTF sidebands (0.38 orders on the 6203) never fall on a shaft order: the one piece of a
/// ball's signature that a shaft comb cannot supply. A real ball fault can lack them (the
/// CWRU fan-end B014 record at 1 hp has one on four found lines), so the test decides only
/// where the comb already has lines of its own ([`ShaftComb::explains`]).
fn cage_modulated(e: &FamilyEvidence, on_comb: &[usize]) -> bool {
    e.sidebands_on(on_comb)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::faults::detect_fault;
    use crate::analysis::spectrum::SpectrumKind;
    use wearsim_core::kinematics::{FaultFrequencies, FaultOrders};

    /// Envelope spectrum with 0.1 Hz bins (a 10 s record), floor 0.01, and lines of
    /// amplitude `a` at the given frequencies.
    fn spectrum(lines: &[(f64, f64)]) -> Spectrum {
        let df = 0.1;
        let mut values = vec![0.01; 20_000];
        for &(f, a) in lines {
            values[(f / df).round() as usize] += a;
        }
        Spectrum {
            df,
            values,
            kind: SpectrumKind::Amplitude,
        }
    }

    /// The CWRU fan-end 6203 at 1500 rpm: BPFO 3.05 and 2×BSF 3.99 orders.
    fn fe_6203() -> FaultFrequencies {
        let cfg = wearsim_core::presets::by_name("cwru-6203-fe").expect("preset");
        FaultOrders::of(&cfg.bearing).at(25.0, 3000.0)
    }

    /// Shaft orders 1..=12 of a healthy 6203 (looseness): the outer-race family fits its
    /// fundamental at 3× (1.7 % slip, inside the search) and the ball family at 4×, every
    /// harmonic of both is on the comb, and nothing is called. Without the shaft comb the
    /// same spectrum's lines were an outer-race call.
    #[test]
    fn a_shaft_comb_is_no_bearing_fault_on_a_bearing_whose_orders_are_integers() {
        let ff = fe_6203();
        assert!((ff.bpfo / ff.shaft_hz - 3.05).abs() < 0.01, "{ff:?}");
        let comb: Vec<(f64, f64)> = (1..=12).map(|k| (k as f64 * 25.0, 1.0)).collect();
        let d = detect_fault(&spectrum(&comb), &ff, &DetectParams::default());
        assert_eq!(d.shaft_comb.orders, (1..=10).collect::<Vec<_>>());
        assert!(
            d.shaft_comb.explains.contains(&FaultFamily::OuterRace),
            "{d:#?}"
        );
        assert_eq!(d.family, FaultFamily::None, "{d:#?}");
        assert_eq!(d.candidate, FaultFamily::None, "{d:#?}");
        let outer = &d.evidence[1];
        assert!((outer.fundamental_hz - 75.0).abs() < 0.1, "{outer:#?}");
        assert!(outer.found >= 3 && outer.bearing_lines() == 0, "{outer:#?}");
        // The outer-race comb alone (its own orders 3, 6, 9 found, nothing else): the shaft
        // has no evidence of its own against the outer race and the outer-race call stands.
        // (The ball family's one line, at 12×, has no cage sidebands: orders 3, 6, 9 explain
        // it, which changes no call.)
        let alone: Vec<(f64, f64)> = (1..=4).map(|k| (k as f64 * 75.0, 1.0)).collect();
        let d = detect_fault(&spectrum(&alone), &ff, &DetectParams::default());
        assert_eq!(d.shaft_comb.orders, vec![3, 6, 9], "{:?}", d.shaft_comb);
        assert_eq!(
            d.shaft_comb.explains,
            vec![FaultFamily::Ball],
            "{:?}",
            d.shaft_comb
        );
        assert_eq!(d.family, FaultFamily::OuterRace, "{d:#?}");
    }

    /// A true outer-race fault of the 6203 at 1 % slip (3.02 orders, 0.8 % from 3×) on top
    /// of the same shaft comb is called: its fundamental is not a shaft order.
    #[test]
    fn a_fault_between_shaft_orders_is_called_over_a_shaft_comb() {
        let ff = fe_6203();
        let f0 = ff.bpfo * 0.99;
        let mut lines: Vec<(f64, f64)> = (1..=12).map(|k| (k as f64 * 25.0, 0.3)).collect();
        lines.extend((1..=5).map(|k| (k as f64 * f0, 1.0)));
        let d = detect_fault(&spectrum(&lines), &ff, &DetectParams::default());
        assert_eq!(d.shaft_comb.orders.len(), 10, "{:?}", d.shaft_comb);
        // The comb explains the families that fit on its orders (inner race at 5×, ball at
        // 4×), not the outer race, whose lines stand between them.
        assert!(
            !d.shaft_comb.explains.contains(&FaultFamily::OuterRace),
            "{:?}",
            d.shaft_comb
        );
        assert_eq!(d.family, FaultFamily::OuterRace, "{d:#?}");
        assert!(d.evidence[1].harmonics.iter().all(|h| !h.shaft), "{d:#?}");
    }

    /// The 6205's BPFI is 5.415 orders: its 5th harmonic (27.08 orders at 1797 rpm) lies on
    /// the 27th shaft order within the harmonic tolerance, but the family's fundamental is
    /// not a shaft order, so the shaft explains none of its lines and the call stands with
    /// its full score — a rule that discounted every line on a shaft order would take it.
    #[test]
    fn a_family_off_the_shaft_orders_keeps_a_harmonic_that_falls_on_one() {
        let ff = crate::analysis::synth::cwru_6205_1797rpm();
        let fr = ff.shaft_hz;
        assert!((5.0 * ff.bpfi - 27.0 * fr).abs() <= 0.004 * 5.0 * ff.bpfi);
        let mut lines: Vec<(f64, f64)> = (1..=12).map(|k| (k as f64 * fr, 0.3)).collect();
        lines.extend((1..=5).map(|k| (k as f64 * ff.bpfi, 1.0)));
        let d = detect_fault(&spectrum(&lines), &ff, &DetectParams::default());
        assert_eq!(d.shaft_comb.orders.len(), 10, "{:?}", d.shaft_comb);
        assert!(d.shaft_comb.explains.is_empty(), "{:?}", d.shaft_comb);
        assert_eq!(d.family, FaultFamily::InnerRace, "{d:#?}");
        let inner = &d.evidence[0];
        assert_eq!(inner.bearing_lines(), 5, "{inner:#?}");
        assert!(inner.harmonics[4].found && !inner.harmonics[4].shaft);
    }

    /// A ball family at 4× on the 6203 (2×BSF 3.99 orders) with a comb of shaft orders
    /// weaker than its lines: without cage sidebands the comb explains it and nothing is
    /// called; the same lines with FTF sidebands are a ball defect's and the call stands.
    #[test]
    fn ball_lines_on_a_shaft_comb_need_their_cage_sidebands() {
        let ff = fe_6203();
        let fr = ff.shaft_hz;
        assert!((2.0 * ff.bsf / fr - 3.99).abs() < 0.01, "{ff:?}");
        let mut lines: Vec<(f64, f64)> = (1..=12)
            .filter(|k| k % 2 == 1)
            .map(|k| (k as f64 * fr, 0.3))
            .collect();
        lines.extend((1..=5).map(|k| (k as f64 * 4.0 * fr, 1.0)));
        let d = detect_fault(&spectrum(&lines), &ff, &DetectParams::default());
        assert!(
            d.shaft_comb.explains.contains(&FaultFamily::Ball),
            "{:?}",
            d.shaft_comb
        );
        assert_eq!(d.family, FaultFamily::None, "{d:#?}");
        let mut modulated = lines.clone();
        modulated.extend((1..=5).flat_map(|k| {
            let f = k as f64 * 4.0 * fr;
            [(f - ff.ftf, 0.5), (f + ff.ftf, 0.5)]
        }));
        let d = detect_fault(&spectrum(&modulated), &ff, &DetectParams::default());
        assert!(
            !d.shaft_comb.explains.contains(&FaultFamily::Ball),
            "{:?}",
            d.shaft_comb
        );
        assert_eq!(d.family, FaultFamily::Ball, "{d:#?}");
        // A comb of even orders only (a 2× force): every order is a multiple of BSF (2
        // orders), the ball's own comb when modulated; unmodulated, orders 2, 6 and 10 are
        // the shaft's own and explain the ball's lines on 4, 8, ….
        let mut even: Vec<(f64, f64)> = (1..=6).map(|k| (2.0 * k as f64 * fr, 0.3)).collect();
        even.extend((1..=5).map(|k| (k as f64 * 4.0 * fr, 1.0)));
        let d = detect_fault(&spectrum(&even), &ff, &DetectParams::default());
        assert_eq!(
            d.shaft_comb.orders,
            vec![2, 4, 6, 8, 10],
            "{:?}",
            d.shaft_comb
        );
        assert!(
            d.shaft_comb.explains.contains(&FaultFamily::Ball),
            "{:?}",
            d.shaft_comb
        );
        assert_eq!(d.family, FaultFamily::None, "{d:#?}");
    }

    /// The order test: within the harmonic tolerance of an integer order, not between
    /// orders, never at or below zero, and two bins wide at least.
    #[test]
    fn order_of_is_the_harmonic_tolerance_around_integer_orders() {
        let p = DetectParams::default();
        let (fr, df) = (10.0, 0.01);
        assert_eq!(order_of(30.0, fr, df, &p), Some(3));
        assert_eq!(order_of(30.1, fr, df, &p), Some(3)); // 0.33 % < 0.4 %
        assert_eq!(order_of(30.2, fr, df, &p), None); // 0.66 %
        assert_eq!(order_of(35.0, fr, df, &p), None);
        assert_eq!(order_of(5.0 + 0.01, 5.0, df, &p), Some(1));
        assert_eq!(order_of(0.0, fr, df, &p), None);
        assert_eq!(order_of(f64::NAN, fr, df, &p), None);
        // Two bins of a coarse spectrum widen the tolerance.
        assert_eq!(order_of(30.9, fr, 0.5, &p), Some(3));
        assert_eq!(order_of(31.1, fr, 0.5, &p), None);
    }
}
