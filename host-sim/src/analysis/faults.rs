//! Bearing fault detection from an envelope spectrum: search the harmonic
//! families of the characteristic defect frequencies and their modulation
//! sidebands (Randall & Antoni 2011, section 3).

use super::peaks::{noise_floor, peak_near, ratio_db, top_peaks, Peak};
use super::shaft_comb::{mark_shaft_lines, ShaftComb};
use super::spectrum::Spectrum;
use serde::{Deserialize, Serialize};

/// The project's one kinematics type (thesis eq. 17–20 and the structure's natural
/// frequency, Hz), defined in the core.
pub use wearsim_core::kinematics::FaultFrequencies;

/// Bearing fault family.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum FaultFamily {
    /// Inner-race defect: harmonics of BPFI with ±shaft sidebands.
    InnerRace,
    /// Outer-race defect: harmonics of BPFO.
    OuterRace,
    /// Rolling-element defect: harmonics of 2×BSF with ±FTF sidebands.
    Ball,
    /// No family detected.
    None,
}

/// Thresholds of [`detect_fault`]; the defaults are fixed, not tuned per record.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DetectParams {
    /// Harmonics searched per family, 1..=`harmonics` (default 5).
    pub harmonics: usize,
    /// Slip tolerance: the family's actual fundamental is searched within this fraction of
    /// the kinematic one (default 0.02; Smith & Randall 2015 report 1–2 % random slip).
    pub slip: f64,
    /// Tolerance of each harmonic around `order × fundamental`, once the fundamental has been
    /// fixed, as a fraction of the harmonic's frequency (default 0.004; never below 2 bins).
    /// Slip shifts all harmonics of a family together, so once the common fundamental is
    /// known its harmonics must line up closely; this is what separates, for example, BPFO
    /// harmonics from BPFI ones (2×BPFI is only 0.7 % from 3×BPFO on a 6205).
    pub harmonic_tol: f64,
    /// A peak counts as found when it is at least this many dB above the
    /// local noise floor (default 10 dB), and at least [`false_alarm_db`] of the
    /// harmonic's search region at `false_alarm`.
    pub min_db: f64,
    /// Probability that noise alone puts a harmonic over its threshold anywhere in the
    /// region the family search can place that harmonic (±`slip` of its kinematic
    /// frequency, widened by its tolerance): a constant-false-alarm-rate threshold, so
    /// that a longer record or a higher sample rate (more bins searched) does not find
    /// more noise lines (default 0.05, fixed a priori; see [`false_alarm_db`]).
    pub false_alarm: f64,
    /// Harmonics that must be found for a family to be diagnosed (default 3).
    pub min_harmonics: usize,
    /// Half-width of the noise-floor neighbourhood, as a fraction of the
    /// family's base frequency (default 0.5).
    pub floor_half_width: f64,
    /// Weight of a found sideband in the score relative to a harmonic
    /// (default 0: sidebands are reported as evidence but not scored. On the
    /// CWRU records the dense line combs of strong outer-race faults put peaks
    /// at ±shaft and ±FTF of almost any line, so scoring sidebands favoured the
    /// inner-race and ball families over true outer-race faults).
    pub sideband_weight: f64,
}

impl Default for DetectParams {
    fn default() -> Self {
        DetectParams {
            harmonics: 5,
            slip: 0.02,
            harmonic_tol: 0.004,
            min_db: 10.0,
            false_alarm: 0.05,
            min_harmonics: 3,
            floor_half_width: 0.5,
            sideband_weight: 0.0,
        }
    }
}

/// Evidence for one harmonic of a family.
#[derive(Debug, Clone, Serialize)]
pub struct HarmonicEvidence {
    /// Harmonic order (1 = fundamental).
    pub order: usize,
    /// Expected frequency, Hz: the order times the family's fitted fundamental
    /// ([`FamilyEvidence::fundamental_hz`]).
    pub expected_hz: f64,
    /// Largest local maximum within the slip tolerance, if any.
    pub peak: Option<Peak>,
    /// Height of that peak above the local noise floor, dB (0 if none).
    pub over_floor_db: f64,
    /// Height over the floor (dB) the peak must reach to count: `min_db` or the
    /// false-alarm threshold of this harmonic's search region, whichever is higher.
    pub threshold_db: f64,
    /// Whether the peak clears `threshold_db`.
    pub found: bool,
    /// Whether another family also claims this peak as one of its found harmonics (then it
    /// does not count in [`FamilyEvidence::exclusive_score`]).
    pub shared: bool,
    /// Whether the shaft explains this peak as well: it lies on a shaft order and the
    /// envelope's comb of shaft orders explains the family
    /// ([`super::shaft_comb::ShaftComb::explains`]; then it does not count in
    /// [`FamilyEvidence::exclusive_score`] nor in [`FamilyEvidence::bearing_lines`]).
    pub shaft: bool,
    /// Heights above floor (dB) of the lower and upper sidebands around the
    /// harmonic, for the families that have them (0 where none is found).
    pub sidebands_db: Option<[f64; 2]>,
}

/// Evidence for one fault family.
#[derive(Debug, Clone, Serialize)]
pub struct FamilyEvidence {
    /// The family.
    pub family: FaultFamily,
    /// Base (first-harmonic) frequency, Hz: BPFI, BPFO or 2×BSF.
    pub base_hz: f64,
    /// Fundamental fitted within the slip tolerance of `base_hz` (the common fundamental
    /// whose harmonics scored best), Hz.
    pub fundamental_hz: f64,
    /// Sideband spacing, Hz (shaft for BPFI, FTF for balls), if any.
    pub sideband_hz: Option<f64>,
    /// Per-harmonic evidence, order 1 first.
    pub harmonics: Vec<HarmonicEvidence>,
    /// Number of harmonics found.
    pub found: usize,
    /// Score, dB per harmonic: the sum of the over-floor dB of the found
    /// harmonics plus `sideband_weight` times that of the found sidebands,
    /// divided by the number of harmonics searched.
    pub score: f64,
    /// Like `score`, counting only the harmonics and sidebands that no other family claims
    /// as a found harmonic; the decision compares these.
    pub exclusive_score: f64,
}

impl FamilyEvidence {
    /// Found harmonics the shaft does not explain ([`HarmonicEvidence::shaft`]): the lines
    /// that are evidence of a bearing fault at all. A family needs `min_harmonics` of them to
    /// lead.
    pub fn bearing_lines(&self) -> usize {
        let shaft = self.harmonics.iter().filter(|h| h.found && h.shaft).count();
        self.found.saturating_sub(shaft)
    }
}

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
    /// among those with at least `min_harmonics` harmonics found that the shaft does not explain, or `None`.
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
}

/// Look for one peak near `f` Hz; returns the peak and its dB over `floor`.
fn probe(env: &Spectrum, f: f64, tol: f64, floor: f64) -> (Option<Peak>, f64) {
    match peak_near(env, f, tol) {
        Some(p) => (Some(p), ratio_db(env.kind, p.value, floor)),
        None => (None, 0.0),
    }
}

/// Most local maxima taken from each harmonic's slip window as fundamental candidates.
const CANDIDATES_PER_HARMONIC: usize = 4;

/// Height over the median floor (dB) that the largest of `bins` bins of noise exceeds with
/// probability `p`, in an amplitude (or power) spectrum of Gaussian noise: a bin's magnitude is
/// Rayleigh (its power exponential), so a bin exceeds `a` times the median with probability
/// `exp(−a² ln 2)`, and the largest of `W` independent bins with `1 − (1 − exp(−a² ln 2))^W`
/// (the constant-false-alarm-rate threshold of radar detection; Richards 2005, *Fundamentals
/// of Radar Signal Processing*, §6.5). Setting that to `p` gives
/// `a² = −ln(1 − (1 − p)^{1/W}) / ln 2`, returned as `10 log10 a²`. Counting every bin as
/// independent (a Hann window correlates neighbours) errs on the high, safe side. One bin at
/// `p ≈ 0.001` gives 10 dB. `bins` below 1 count as 1; `p` outside (0, 1) gives infinity
/// (nothing is found) for `p ≤ 0` and 0 dB for `p ≥ 1`.
pub fn false_alarm_db(bins: f64, p: f64) -> f64 {
    if p.is_nan() || p <= 0.0 {
        return f64::INFINITY;
    }
    if p >= 1.0 {
        return 0.0;
    }
    let w = if bins.is_finite() { bins.max(1.0) } else { 1.0 };
    // 1 − (1 − p)^{1/W}, without cancellation for small p or large W.
    let per_bin = -((-p).ln_1p() / w).exp_m1();
    let a2 = -per_bin.ln() / core::f64::consts::LN_2;
    10.0 * a2.max(f64::MIN_POSITIVE).log10()
}

/// Evidence of one family for a fundamental `f0` Hz; `floors[k-1]` holds the noise floor
/// around harmonic `k`, those around its sidebands, and the height over the floor (dB) a
/// peak must reach to count.
fn evidence_at(
    env: &Spectrum,
    f0: f64,
    sideband_hz: Option<f64>,
    floors: &[(f64, [f64; 2], f64)],
    p: &DetectParams,
) -> (Vec<HarmonicEvidence>, usize, f64) {
    let min_tol = 2.0 * env.df;
    let mut score = 0.0;
    let mut found = 0;
    let harmonics = floors
        .iter()
        .enumerate()
        .map(|(i, &(floor, sb_floor, threshold_db))| {
            let order = i + 1;
            let expected_hz = order as f64 * f0;
            let tol = (p.harmonic_tol * expected_hz).max(min_tol);
            let (peak, db) = probe(env, expected_hz, tol, floor);
            let is_found = peak.is_some() && db >= threshold_db;
            if is_found {
                found += 1;
                score += db;
            }
            let centre = peak.filter(|_| is_found).map_or(expected_hz, |q| q.freq);
            let sidebands_db = sideband_hz.filter(|s| *s > 0.0).map(|s| {
                let mut out = [0.0; 2];
                for (j, f) in [centre - s, centre + s].into_iter().enumerate() {
                    let tol = (p.harmonic_tol * f.abs()).max(min_tol);
                    let (_, db) = probe(env, f, tol, sb_floor[j]);
                    if db >= p.min_db {
                        score += p.sideband_weight * db;
                        out[j] = db;
                    }
                }
                out
            });
            HarmonicEvidence {
                order,
                expected_hz,
                peak,
                over_floor_db: db,
                threshold_db,
                found: is_found,
                shared: false,
                shaft: false,
                sidebands_db,
            }
        })
        .collect();
    (harmonics, found, score)
}

/// Search the harmonics (and sidebands) of one family in `env`.
///
/// Slip moves every harmonic of a family by the same factor, so the family is evaluated on a
/// common fundamental: the candidates are the kinematic `base_hz` and `peak / order` for the
/// largest local maxima within `slip` of each harmonic `order × base_hz`; each candidate's
/// harmonics are then looked for within `harmonic_tol` of `order × candidate`, and the
/// candidate with the highest score is kept. Noise floors are medians around the kinematic
/// harmonic and sideband frequencies.
pub(super) fn family_evidence(
    env: &Spectrum,
    family: FaultFamily,
    base_hz: f64,
    sideband_hz: Option<f64>,
    p: &DetectParams,
) -> FamilyEvidence {
    let min_tol = 2.0 * env.df;
    let usable = base_hz.is_finite() && base_hz > 0.0 && env.df > 0.0;
    if !usable || p.harmonics == 0 {
        return FamilyEvidence {
            family,
            base_hz,
            fundamental_hz: base_hz,
            sideband_hz,
            harmonics: Vec::new(),
            found: 0,
            score: 0.0,
            exclusive_score: 0.0,
        };
    }
    let floor_hw = (p.floor_half_width * base_hz).max(4.0 * min_tol);
    let s = sideband_hz
        .filter(|s| s.is_finite() && *s > 0.0)
        .unwrap_or(0.0);
    let floors: Vec<(f64, [f64; 2], f64)> = (1..=p.harmonics)
        .map(|order| {
            let f = order as f64 * base_hz;
            // The region the search can place this harmonic in: the fundamental's slip
            // window times the order, widened by the harmonic's own tolerance.
            let region = 2.0 * (p.slip * f).max(min_tol) + 2.0 * (p.harmonic_tol * f).max(min_tol);
            (
                noise_floor(env, f, floor_hw),
                [
                    noise_floor(env, f - s, floor_hw),
                    noise_floor(env, f + s, floor_hw),
                ],
                p.min_db.max(false_alarm_db(region / env.df, p.false_alarm)),
            )
        })
        .collect();
    let mut candidates = vec![base_hz];
    for order in 1..=p.harmonics {
        let f = order as f64 * base_hz;
        let tol = (p.slip * f).max(min_tol);
        for q in top_peaks(env, CANDIDATES_PER_HARMONIC, f - tol, f + tol, 0.0) {
            candidates.push(q.freq / order as f64);
        }
    }
    let mut best: Option<(f64, Vec<HarmonicEvidence>, usize, f64)> = None;
    for f0 in candidates {
        let (h, found, score) = evidence_at(env, f0, sideband_hz, &floors, p);
        let better = match &best {
            None => true,
            Some((b0, _, _, bs)) => {
                score > *bs || (score == *bs && (f0 - base_hz).abs() < (b0 - base_hz).abs())
            }
        };
        if better {
            best = Some((f0, h, found, score));
        }
    }
    let (fundamental_hz, harmonics, found, score) = best.unwrap_or((base_hz, Vec::new(), 0, 0.0));
    FamilyEvidence {
        family,
        base_hz,
        fundamental_hz,
        sideband_hz,
        harmonics,
        found,
        score: score / p.harmonics.max(1) as f64,
        exclusive_score: 0.0,
    }
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
/// exclusive score among those with at least `min_harmonics` harmonics found (not counting lines the shaft explains, [`super::shaft_comb`])
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
            if !h.shared && !h.shaft {
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
        // Hand-made spectrum: lines of 1.0 at k*100 Hz over a floor of 0.01.
        let mut values = vec![0.01; 1001];
        for k in 1..=5 {
            values[k * 100] = 1.0;
        }
        let env = Spectrum {
            df: 1.0,
            values,
            kind: SpectrumKind::Amplitude,
        };
        let ff = FaultFrequencies {
            shaft_hz: 30.0,
            ftf: 12.0,
            bpfo: 101.0, // 1 % slip
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
            assert_eq!(h.peak.unwrap().bin, 100 * h.order);
        }
        assert!((d.score - 40.0).abs() < 1e-9);
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
