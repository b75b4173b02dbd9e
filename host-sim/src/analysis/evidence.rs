//! Evidence of one harmonic family in an envelope spectrum: the fault families, the
//! detector's thresholds, and the search of a family's common fundamental and harmonics
//! with constant-false-alarm-rate thresholds (Randall & Antoni 2011, section 3).

use super::peaks::{noise_floor, peak_near, ratio_db, top_peaks, Peak};
use super::spectrum::Spectrum;
use serde::{Deserialize, Serialize};

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

/// Thresholds of [`super::detect_fault`]; the defaults are fixed, not tuned per record.
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
    /// Whether the mains explain this peak: every found line of the family lies on one
    /// comb of a supply harmonic and the family lacks its modulation sidebands
    /// ([`super::mains::mark_mains_lines`]; then, as a line the shaft explains, it does not
    /// count in [`FamilyEvidence::exclusive_score`] nor in [`FamilyEvidence::bearing_lines`]).
    pub mains: bool,
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
    /// Found harmonics neither the shaft nor the mains explain
    /// ([`HarmonicEvidence::explained`]): the lines that are evidence of a bearing fault at
    /// all. A family needs `min_harmonics` of them to lead.
    pub fn bearing_lines(&self) -> usize {
        let other = self
            .harmonics
            .iter()
            .filter(|h| h.found && h.explained())
            .count();
        self.found.saturating_sub(other)
    }
}

impl FamilyEvidence {
    /// Whether the harmonics `lines` (indices into [`FamilyEvidence::harmonics`]) carry
    /// the family's modulation: at least half of them with a sideband found on either side
    /// (the shaft's around inner-race lines, the cage's around a ball's). The one part of a
    /// family's signature that a comb of another source (shaft orders, the mains) does not
    /// supply: `super::shaft_comb` and `super::mains` test it.
    pub fn sidebands_on(&self, lines: &[usize]) -> bool {
        let with = lines
            .iter()
            .filter_map(|&i| self.harmonics.get(i))
            .filter(|h| h.sidebands_db.is_some_and(|s| s.iter().any(|db| *db > 0.0)))
            .count();
        2 * with >= lines.len()
    }
}

impl HarmonicEvidence {
    /// Whether a source other than a bearing explains this peak: the shaft
    /// ([`HarmonicEvidence::shaft`]) or the mains ([`HarmonicEvidence::mains`]).
    pub fn explained(&self) -> bool {
        self.shaft || self.mains
    }
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
                mains: false,
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
