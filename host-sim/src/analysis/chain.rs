//! The diagnosis chain of one record, from samples to a fault-family decision (no files,
//! no command): statistics, a demodulation band chosen by the kurtogram on a grid fixed in
//! Hz, cepstral pre-whitening, the envelope spectrum in that band, the calibrated family
//! decision ([`super::faults::detect_fault`], [`super::diagnose`]) and the El-Thalji zone
//! levels. `wearsim analyze` (`crate::analyze`) reads records and reports this chain's
//! result; the CWRU benchmark, the gap and the Python package call [`analyze_signal`]
//! directly.
//!
//! Sources: Randall & Antoni 2011, "Rolling element bearing diagnostics — a tutorial",
//! MSSP 25; Antoni 2007 (fast kurtogram); Sawalhi & Randall 2011 and Borghesani et al.
//! 2013 (cepstral pre-whitening); El-Thalji 2016 (frequency zones).

use crate::analysis::{
    self, detect_fault, welch_psd, zone_levels, DetectParams, FaultDiagnosis, FaultFamily,
    FaultFrequencies, Kurtogram, Spectrum, Stats, WelchParams, Window, ZoneBands, ZoneLevels,
};
use realfft::num_complex::Complex;
use serde::Serialize;

/// The fixed analysis method (one parameter set for every record).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Method {
    /// Cepstral pre-whitening of the record before the envelope (default true; the
    /// kurtogram always sees the raw record).
    pub prewhiten: bool,
    /// Demodulate in the band chosen by the kurtogram (default true); false: in the whole
    /// admissible band above the fault zone (`top`..fs/2), as a plain envelope analysis.
    pub kurtogram_band: bool,
    /// Bounds the candidate-band grid (default 6): at most `2 × max_level` band widths, the
    /// narrowest kept. The grid is fixed in Hz
    /// ([`analysis::kurtogram::hz_grid_kurtogram`]: widths 1000 or 1500 Hz × 2^k, cells at
    /// multiples of the width), its widths at least `min_band_factor × top` Hz and wide
    /// enough for 32 envelope samples, so the same record sees the same candidate bands at
    /// every sample rate.
    pub max_level: usize,
    /// Narrowest admissible demodulation band, as a multiple of the highest fault harmonic
    /// searched (`top = harmonics × max(BPFI, 2×BSF)`), so that the envelope can hold every
    /// harmonic the detector looks for (default 1.2). Admissible bands also start at or
    /// above `top` (the carrier lies above the fault-frequency zone it modulates); a record
    /// whose content leaves no room for that gets no call
    /// ([`KurtogramSummary::no_content`]).
    pub min_band_factor: f64,
    /// Envelope of the demodulated band: `false` (default) the envelope `|analytic signal|`,
    /// `true` the squared envelope (Randall & Antoni 2011, section 3.2).
    pub squared_envelope: bool,
    /// How the demodulation band is chosen among the admissible kurtogram cells (default
    /// [`BandRule::Kurtosis`]).
    pub band_rule: BandRule,
    /// Detector thresholds ([`DetectParams::default`]).
    pub detect: DetectParams,
}

/// Rule choosing the demodulation band among the admissible cells of the fast kurtogram
/// (the same cells, in Hz, at every sample rate; see [`Method::min_band_factor`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum BandRule {
    /// The cell of largest spectral kurtosis (Antoni 2007, fast kurtogram).
    Kurtosis,
    /// The cell whose envelope spectrum gives the leading fault family the largest evidence
    /// margin (the target-frequency band selection of the envelope-spectrum "gram" methods:
    /// Barszcz & Jabłoński 2011, protrugram, MSSP 25; Smith, Borghesani, Ni, Wang & Peng 2019,
    /// "Optimal demodulation-band selection for envelope-based diagnostics", MSSP 134);
    /// the kurtosis cell when no cell has a leading family.
    Evidence,
    /// The cell whose envelope spectrum is the most peaky over the searched fault-frequency
    /// range `(0, top × (1 + slip)]` Hz: the largest kurtosis of the envelope-spectrum
    /// amplitudes there (the protrugram, Barszcz & Jabłoński 2011, MSSP 25), which favours
    /// bands with discrete envelope lines without looking at which family they belong to.
    Protrugram,
}

/// Pearson kurtosis (Gaussian 3) of the envelope-spectrum amplitudes of `env` in
/// `(0, hi]` Hz; 0 with fewer than 4 values or a constant spectrum.
fn spectrum_kurtosis(env: &analysis::Spectrum, hi: f64) -> f64 {
    if env.df <= 0.0 || !hi.is_finite() {
        return 0.0;
    }
    let k1 = ((hi / env.df).floor() as usize).min(env.values.len().saturating_sub(1));
    let v = env.values.get(1..=k1).unwrap_or(&[]);
    if v.len() < 4 {
        return 0.0;
    }
    let (m, sd) = analysis::stats::mean_std(v);
    if sd.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return 0.0;
    }
    let k = v.iter().map(|x| ((x - m) / sd).powi(4)).sum::<f64>() / v.len() as f64;
    if k.is_finite() {
        k
    } else {
        0.0
    }
}

impl Default for Method {
    fn default() -> Self {
        Method {
            prewhiten: true,
            kurtogram_band: true,
            max_level: 6,
            min_band_factor: 1.2,
            squared_envelope: false,
            band_rule: BandRule::Kurtosis,
            detect: DetectParams::default(),
        }
    }
}

/// Summary of the fast kurtogram.
#[derive(Debug, Clone, Serialize)]
pub struct KurtogramSummary {
    /// Depth of the grid: `ceil(log2(fs/2 / narrowest cell width))` (a label; the cells
    /// are fixed in Hz, see [`analysis::kurtogram::hz_grid_kurtogram`]).
    pub max_level: usize,
    /// Narrowest admissible band width, Hz (see [`Method::min_band_factor`]).
    pub min_band_hz: f64,
    /// Upper limit of the candidate bands, Hz: the lowest of the record's content edge
    /// (`analysis::kurtogram::content_edge_hz`) plus one 100 Hz chunk, its Nyquist frequency and
    /// `analysis::kurtogram::MAX_BAND_HZ` (20 kHz).
    pub span_hz: f64,
    /// Chosen demodulation band `(lo, hi)`, Hz: the admissible band of largest kurtosis.
    pub band_hz: (f64, f64),
    /// Kurtosis of the complex envelope in that band (0 for Gaussian noise).
    pub kurtosis: f64,
    /// Level of the chosen band, `log2(fs/2 / its width)` (a label, as `max_level`).
    pub level: f64,
    /// Band of largest kurtosis over the whole kurtogram (admissible or not), Hz.
    pub unrestricted_band_hz: (f64, f64),
    /// Its kurtosis.
    pub unrestricted_kurtosis: f64,
    /// Why there is nothing to demodulate, when the record's content ends before a band of
    /// the minimum width fits above the fault zone, when no candidate band above it
    /// holds more than rounding ([`analysis::kurtogram::ROUNDING_FLOOR`] of the record's
    /// power) or the chosen band's envelope is constant to rounding (its modulation below
    /// that floor): the call is then `None` (absent otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub no_content: Option<String>,
}

/// Zone bands and levels (El-Thalji 2016 frequency zones), from a Welch PSD of the raw record.
#[derive(Debug, Clone, Serialize)]
pub struct Zones {
    /// Band edges, Hz.
    pub bands: ZoneBands,
    /// RMS levels, signal units.
    pub levels: ZoneLevels,
}

/// The spectra behind an analysis (`wearsim analyze`'s report), for plots.
#[derive(Debug, Clone)]
pub struct Spectra {
    /// Amplitude spectrum of the raw record (Hann window, whole record), signal units.
    pub spectrum: Spectrum,
    /// Envelope spectrum in the chosen band (of the pre-whitened record if
    /// [`Method::prewhiten`]); signal units, or unit-less when pre-whitened.
    pub envelope: Spectrum,
    /// The fast kurtogram of the raw record.
    pub kurtogram: Kurtogram,
}

/// Result of [`analyze_signal`]: the figures that depend only on the samples.
#[derive(Debug, Clone)]
pub struct SignalAnalysis {
    /// Statistics of the raw signal.
    pub stats: Stats,
    /// Transients cut out before the band was chosen and the record demodulated
    /// ([`analysis::transients`]); the statistics, the spectrum and the zones are of the
    /// record as given. `None`: nothing cut.
    pub transients: Option<analysis::transients::Transients>,
    /// Demodulation band.
    pub kurtogram: KurtogramSummary,
    /// Fault decision.
    pub diagnosis: FaultDiagnosis,
    /// Zones, or the reason they are missing.
    pub zones: Result<Zones, String>,
    /// Spectra for plots.
    pub spectra: Spectra,
}

/// Cepstral pre-whitening (Sawalhi & Randall 2011; Borghesani et al. 2013): the inverse FFT
/// of `X(f) / |X(f)|` of the mean-removed record, i.e. the record with its real cepstrum set
/// to zero except at quefrency 0. The mean and bins of zero magnitude become zero. The output
/// has the input's length and a flat (unit-less) magnitude spectrum: every bin has magnitude
/// 1 before the inverse FFT's 1/n scaling. Fewer than 2 samples give zeros.
pub fn prewhiten(x: &[f64]) -> Vec<f64> {
    let n = x.len();
    if n < 2 {
        return vec![0.0; n];
    }
    prewhiten_spectrum(analysis::fft::rfft(x, analysis::stats::mean(x)), n)
}

/// [`prewhiten`] from `spec`, the one-sided spectrum (`n/2 + 1` bins) of the mean-removed
/// record of `n >= 2` samples (the spectrum the fast kurtogram cuts its bands from; plans
/// cached per thread).
fn prewhiten_spectrum(mut spec: Vec<Complex<f64>>, n: usize) -> Vec<f64> {
    let inv = analysis::fft::plan_c2r(n);
    if spec.len() != n / 2 + 1 {
        return vec![0.0; n];
    }
    // A bin holding nothing but rounding stays (numerically) zero: whitened, it would be
    // raised to the magnitude of every real line.
    let mean_power =
        spec.iter().skip(1).map(|c| c.norm_sqr()).sum::<f64>() / (spec.len() - 1).max(1) as f64;
    let floor = analysis::kurtogram::ROUNDING_FLOOR * mean_power;
    for (k, c) in spec.iter_mut().enumerate() {
        let m = c.norm();
        // DC and (even n) Nyquist must stay real for the inverse real FFT.
        if k == 0 || m == 0.0 || !m.is_finite() || c.norm_sqr() < floor {
            *c = Complex::new(0.0, 0.0);
        } else {
            *c /= m;
        }
    }
    if n.is_multiple_of(2) {
        if let Some(last) = spec.last_mut() {
            *last = Complex::new(last.re, 0.0);
        }
    }
    let mut out = inv.make_output_vec();
    if inv.process(&mut spec, &mut out).is_err() {
        return vec![0.0; n];
    }
    let scale = 1.0 / n as f64;
    out.iter_mut().for_each(|v| *v *= scale);
    out
}

/// Band edges `(lo, hi)` Hz of cell `i` of kurtogram row `r`.
pub fn kurtogram_band(kg: &Kurtogram, r: usize, i: usize) -> (f64, f64) {
    let w = kg.row_width_hz.get(r).copied().unwrap_or(kg.fs / 2.0);
    (i as f64 * w, (i + 1) as f64 * w)
}

/// Analyse samples `x` at `fs` Hz of a bearing with frequencies `kin` using `method`.
/// Errors (signal too short, constant, non-finite, bad fs) come from [`analysis`].
pub fn analyze_signal(
    raw: &[f64],
    fs: f64,
    kin: &FaultFrequencies,
    method: &Method,
) -> Result<SignalAnalysis, analysis::AnalysisError> {
    let stats = analysis::stats(raw)?;
    analysis::error::check_magnitude(raw)?;
    // DC and level removed: every decision below depends on the record's shape only, not
    // on its units, gain or offset.
    let normalised: Vec<f64> = if stats.std > 0.0 {
        raw.iter().map(|v| (v - stats.mean) / stats.std).collect()
    } else {
        raw.to_vec()
    };
    // A knock or burst is not the bearing: cut out before anything is chosen from the record.
    let (normalised, transients) = analysis::transients::excise(normalised, fs, kin.shaft_hz);
    let x = normalised.as_slice();
    analysis::error::check_signal(x, 128, "kurtogram")?;
    // Constant once its transients are cut out (zeros and one knock): named in the record's
    // own units, not the normalised ones.
    analysis::kurtogram::check_not_constant(x).map_err(|_| analysis::AnalysisError::Constant {
        value: x.first().map_or(stats.mean, |v| v * stats.std + stats.mean),
        what: if transients.is_some() {
            "once its knocks and bursts are cut out, the spectral kurtosis"
        } else {
            "spectral kurtosis"
        },
    })?;
    let top = method.detect.harmonics.max(1) as f64 * kin.bpfi.max(2.0 * kin.bsf);
    // The band is chosen on the record with its ends faded (50 ms): how a record's ends
    // meet is not evidence of a fault. The envelope spectrum needs no fade (its Hann window
    // already gives the ends no weight) and must not get one: the fade is itself an
    // envelope modulation.
    let mut faded = normalised.clone();
    analysis::window::taper_ends(&mut faded, fs);
    let spec = analysis::fft::rfft(&faded, analysis::stats::mean(&faded));
    // Candidate bands on a grid fixed in Hz (issue 12: cells in fractions of fs/2 moved with
    // the sample rate and so changed the call of a record resampled with no new content),
    // up to where the record holds content, its Nyquist frequency and `MAX_BAND_HZ`.
    // The edge is known to its 100 Hz chunk, so a band may reach one chunk past the last
    // chunk with content: a 12 kHz CWRU record's anti-alias roll-off leaves 5.9-6 kHz under
    // the -80 dB floor once the ends are faded, which put the 4.5-6 kHz cell, holding one
    // record's impacts (kurtosis 32), out of reach (probe G, stop 54).
    let span = (analysis::kurtogram::content_edge_hz(&spec, x.len(), fs)
        + analysis::kurtogram::CONTENT_CHUNK_HZ)
        .min(fs / 2.0)
        .min(analysis::kurtogram::MAX_BAND_HZ);
    let min_band_hz = (method.min_band_factor * top).min(span);
    // The narrowest cells need 32 envelope samples (32 / duration Hz wide).
    let min_width = min_band_hz.max(32.0 * fs / x.len() as f64);
    let kg = analysis::kurtogram::hz_grid_kurtogram(
        &spec,
        x.len(),
        fs,
        min_width,
        span,
        2 * method.max_level.clamp(1, 16),
    )?;
    let level = kg.levels;
    let lowest = top.min(span - min_band_hz).max(0.0);
    // A cell holding nothing but rounding is not admissible (its kurtosis is round-off's).
    let floor = analysis::kurtogram::ROUNDING_FLOOR
        * spec.iter().skip(1).map(|c| c.norm_sqr()).sum::<f64>();
    let holds_content =
        |band: (f64, f64)| analysis::kurtogram::band_power(&spec, x.len(), fs, band) > floor;
    let mut admissible: Vec<(f64, usize, usize)> = Vec::new();
    let mut best: Option<(f64, usize, usize)> = None;
    for (r, row) in kg.grid.iter().enumerate() {
        let width = kg.row_width_hz[r];
        if width + 1e-9 < min_band_hz {
            continue;
        }
        for (i, &k) in row.iter().enumerate() {
            // The carrier band must lie above the fault harmonics it is to reveal.
            if (i as f64) * width + 1e-9 < lowest || !holds_content(kurtogram_band(&kg, r, i)) {
                continue;
            }
            admissible.push((k, r, i));
            if best.is_none_or(|b| k > b.0) {
                best = Some((k, r, i));
            }
        }
    }
    // No grid cell fits above the fault zone: the band (lowest, span), as without the kurtogram.
    let fallback = best.is_none();
    // A record whose content ends before a band of the minimum width fits above the fault
    // harmonics (a pure tone, a velocity or displacement probe, a record low-passed below
    // the resonances) has no carrier to demodulate: a band reaching down into the fault
    // zone would hold the lines themselves (or a tone's rounding), not their modulation of
    // a resonance (stop 68: 16-bit tones at 50-1000 Hz and a 1x sine were called inner race
    // or ball at confidence 1.00 from a 0-300 Hz band).
    let no_content = if lowest + 1e-9 < top {
        Some(format!(
            "the record's content ends at {span:.0} Hz: no band of at least {:.0} Hz fits above the fault zone (up to {top:.0} Hz, the highest searched fault harmonic), so there is no resonance to demodulate and no call",
            method.min_band_factor * top
        ))
    } else {
        (fallback && !holds_content((lowest, span))).then(|| {
            format!(
                "no band above the fault zone ({lowest:.0}-{span:.0} Hz) holds more than rounding (power below {:e} of the record's): nothing to demodulate, so no call",
                analysis::kurtogram::ROUNDING_FLOOR
            )
        })
    };
    let fallback_kurtosis = if fallback {
        analysis::kurtogram::band_kurtosis(&spec, x.len(), fs, (lowest, span))
    } else {
        0.0
    };
    // Cepstral pre-whitening of the mean-removed record (checked: finite, not constant,
    // long enough).
    let white;
    let y: &[f64] = if method.prewhiten {
        white = prewhiten(x);
        &white
    } else {
        x
    };
    let (mut kurtosis, mut r, mut i) = best.unwrap_or((0.0, 0, 0));
    // One forward FFT of the record to be demodulated, shared by every band tried.
    let yspec = analysis::fft::rfft(y, 0.0);
    let env_of = |band: (f64, f64)| {
        analysis::envelope::envelope_spectrum_of_spectrum(
            &yspec,
            y.len(),
            fs,
            band,
            method.squared_envelope,
        )
    };
    if method.kurtogram_band && method.band_rule == BandRule::Evidence {
        // The cell whose envelope spectrum gives the leading family the largest margin.
        let mut lead: Option<(f64, f64, usize, usize)> = None;
        for &(k, rr, ii) in &admissible {
            let d = detect_fault(&env_of(kurtogram_band(&kg, rr, ii))?, kin, &method.detect);
            if d.candidate != FaultFamily::None
                && lead.is_none_or(|l| d.margin_db > l.0 || (d.margin_db == l.0 && k > l.1))
            {
                lead = Some((d.margin_db, k, rr, ii));
            }
        }
        if let Some((_, k, rr, ii)) = lead {
            (kurtosis, r, i) = (k, rr, ii);
        }
    }
    if method.kurtogram_band && method.band_rule == BandRule::Protrugram {
        let hi = top * (1.0 + method.detect.slip);
        let mut peaky: Option<(f64, f64, usize, usize)> = None;
        for &(k, rr, ii) in &admissible {
            let p = spectrum_kurtosis(&env_of(kurtogram_band(&kg, rr, ii))?, hi);
            if peaky.is_none_or(|l| p > l.0 || (p == l.0 && k > l.1)) {
                peaky = Some((p, k, rr, ii));
            }
        }
        if let Some((_, k, rr, ii)) = peaky {
            (kurtosis, r, i) = (k, rr, ii);
        }
    }
    let band = if method.kurtogram_band && !fallback {
        kurtogram_band(&kg, r, i)
    } else {
        (lowest, span)
    };
    if fallback {
        kurtosis = fallback_kurtosis;
    }
    let (env, modulation) = analysis::envelope::envelope_spectrum_and_modulation(
        &yspec,
        y.len(),
        fs,
        band,
        method.squared_envelope,
    )?;
    // An envelope constant to rounding (a band holding one pure line, or nothing) carries
    // no fault lines: what the detector would find in it is round-off.
    let no_content = no_content.or_else(|| {
        (modulation <= analysis::kurtogram::ROUNDING_FLOOR).then(|| {
            format!(
                "the envelope in {:.0}-{:.0} Hz is constant to rounding (its modulation is {modulation:.1e} of its power, below {:e}): no fault lines, so no call",
                band.0,
                band.1,
                analysis::kurtogram::ROUNDING_FLOOR
            )
        })
    });
    let summary = KurtogramSummary {
        max_level: level,
        min_band_hz,
        band_hz: band,
        kurtosis,
        level: if fallback {
            (fs / 2.0 / (band.1 - band.0).max(1e-9)).log2()
        } else {
            kg.level_values.get(r).copied().unwrap_or(0.0)
        },
        span_hz: span,
        unrestricted_band_hz: kg.best_band,
        unrestricted_kurtosis: kg.best_kurtosis,
        no_content: no_content.clone(),
    };
    let mut diagnosis = detect_fault(&env, kin, &method.detect);
    if no_content.is_some() {
        // Round-off is no evidence: the call is None, with the confidence of no evidence.
        let (_, confidence) =
            super::diagnose::call::<FaultFamily>(None, 0.0, &super::diagnose::CALIBRATION);
        diagnosis = FaultDiagnosis {
            family: FaultFamily::None,
            candidate: FaultFamily::None,
            confidence,
            margin_db: 0.0,
            margin_family: FaultFamily::None,
            score: 0.0,
            ..diagnosis
        };
    }
    let spectrum = analysis::amplitude_spectrum(raw, fs, Window::Hann)?;
    let zones = zones(raw, fs, kin);
    Ok(SignalAnalysis {
        stats,
        transients,
        kurtogram: summary,
        diagnosis,
        zones,
        spectra: Spectra {
            spectrum,
            envelope: env,
            kurtogram: kg,
        },
    })
}

/// Zone levels from a Welch PSD (segments of about 1 Hz resolution, at most the record).
fn zones(x: &[f64], fs: f64, kin: &FaultFrequencies) -> Result<Zones, String> {
    let bands = ZoneBands::new(kin, fs).map_err(|e| format!("frequency zones undefined: {e}"))?;
    let mut nperseg = 4096usize;
    while nperseg > x.len() && nperseg > 64 {
        nperseg /= 2;
    }
    let psd = welch_psd(
        x,
        fs,
        &WelchParams {
            nperseg,
            ..WelchParams::default()
        },
    )
    .map_err(|e| format!("zone PSD: {e}"))?;
    Ok(Zones {
        levels: zone_levels(&psd, &bands),
        bands,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::synth::gaussian_noise;
    use std::f64::consts::PI;

    const FS: f64 = 12_000.0;

    use crate::analysis::synth::cwru_6205_1797rpm as cwru;

    /// Outer-race fault record: impulses at BPFO with 1 % random slip between impacts
    /// (uniform, Randall & Antoni 2011 report 1-2 %; a jitter-free train would be a purely
    /// periodic signal, which cepstral pre-whitening flattens away with the machine lines),
    /// each ringing a 3.5 kHz resonance (damping 0.05), in white noise of sigma 0.3.
    fn outer_race_record(n: usize) -> Vec<f64> {
        let mut x = gaussian_noise(n, 0.3, 7);
        let (wn, zeta) = (2.0 * PI * 3500.0, 0.05);
        let ring = ((9.2 / (zeta * wn)) * FS).ceil() as usize + 1;
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut t = 0.0;
        while t * FS < n as f64 {
            let first = (t * FS).ceil() as usize;
            for (i, xi) in x.iter_mut().enumerate().skip(first).take(ring) {
                let dt = i as f64 / FS - t;
                *xi += (-zeta * wn * dt).exp() * (wn * dt).sin();
            }
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let u = (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
            t += (1.0 + 0.02 * u) / cwru().bpfo;
        }
        x
    }

    #[test]
    fn every_band_rule_keeps_to_admissible_cells() -> Result<(), analysis::AnalysisError> {
        let ff = cwru();
        let x = outer_race_record(48_000);
        let base = Method::default();
        let top = base.detect.harmonics as f64 * ff.bpfi.max(2.0 * ff.bsf);
        let mut margins = Vec::new();
        for rule in [BandRule::Kurtosis, BandRule::Evidence, BandRule::Protrugram] {
            let a = analyze_signal(
                &x,
                FS,
                &ff,
                &Method {
                    band_rule: rule,
                    ..base
                },
            )?;
            let (lo, hi) = a.kurtogram.band_hz;
            // Above the searched fault zone and at least the narrowest admissible width.
            assert!(
                lo + 1e-9 >= top,
                "{rule:?}: band {lo}-{hi} starts below {top} Hz"
            );
            assert!(
                hi - lo + 1e-9 >= a.kurtogram.min_band_hz,
                "{rule:?}: {lo}-{hi}"
            );
            assert_eq!(a.diagnosis.family, FaultFamily::OuterRace, "{rule:?}");
            margins.push(a.diagnosis.margin_db);
        }
        // The evidence rule maximises the margin over the same cells the kurtosis rule
        // chooses from, so it can never give less.
        assert!(margins[1] + 1e-9 >= margins[0], "{margins:?}");
        Ok(())
    }
    /// A record with energy only at DC and Nyquist (`1, 0, 1, 0, …`), and a pure tone
    /// below the fault zone with a whole number of periods: above the fault zone they hold
    /// nothing but rounding, which the kurtogram once rated (kurtosis 1336 in a 4-8 kHz cell
    /// of round-off) and the detector called inner race with confidence 1.00. No band is
    /// demodulated, the call is None and the summary says why.
    #[test]
    fn a_record_of_rounding_only_gets_no_call() -> Result<(), analysis::AnalysisError> {
        let ff = cwru();
        let nyquist: Vec<f64> = (0..51_200).map(|i| f64::from(i % 2 == 0)).collect();
        let tone: Vec<f64> = (0..48_000)
            .map(|i| (2.0 * PI * 100.0 * i as f64 / FS).sin())
            .collect();
        for (name, x, fs) in [("nyquist", nyquist, 25_600.0), ("tone", tone, FS)] {
            for rule in [BandRule::Kurtosis, BandRule::Evidence, BandRule::Protrugram] {
                let m = Method {
                    band_rule: rule,
                    ..Method::default()
                };
                let a = analyze_signal(&x, fs, &ff, &m)?;
                let d = &a.diagnosis;
                assert_eq!(d.family, FaultFamily::None, "{name} {rule:?}: {d:?}");
                assert_eq!(d.candidate, FaultFamily::None, "{name} {rule:?}");
                assert!(d.confidence.is_finite() && d.margin_db.is_finite());
                let why = a.kurtogram.no_content.as_deref().unwrap_or("");
                // The tone's content ends at 200 Hz: no band fits above the fault zone.
                let expect = if name == "tone" {
                    "content ends"
                } else {
                    "rounding"
                };
                assert!(why.contains(expect), "{name} {rule:?}: {why:?}");
            }
        }
        Ok(())
    }

    /// Zeros and one knock: constant once the knock is cut out, and said so in the record's
    /// own units (stop 68: the error named the normalised value, -0.00707, not in the data).
    #[test]
    fn a_record_constant_but_for_a_knock_is_named_constant_in_its_units() {
        let mut x = vec![0.0; 48_000];
        x[20_000] = 5.0;
        match analyze_signal(&x, FS, &cwru(), &Method::default()) {
            Err(analysis::AnalysisError::Constant { value, what }) => {
                assert!(value.abs() < 1e-9, "{value}");
                assert!(what.contains("knocks"), "{what}");
            }
            other => panic!(
                "expected a constant record, got {:?}",
                other.map(|a| a.diagnosis)
            ),
        }
    }

    /// A calibrator tone or a shaft-rate sine, as a 16-bit converter stores it (rounded to
    /// whole counts at 90 % of full scale) or in floating point: its content ends just above
    /// the tone (the rounding is 90 dB or more down), so no band of the minimum width fits
    /// above the fault zone. Stop 68 found such tones called inner race or ball with
    /// confidence 1.00 from a band reaching into the fault zone (0-300 Hz, 227-1200 Hz),
    /// where the detector read the tone's own rounding as fault lines. A tone with noise
    /// spreading content over the whole spectrum gets a band above the fault zone instead.
    #[test]
    fn a_pure_tone_gets_no_call() -> Result<(), analysis::AnalysisError> {
        let ff = cwru();
        let fs = 25_600.0;
        let tone = |f: f64, counts: Option<f64>| -> Vec<f64> {
            (0..256_000)
                .map(|i| {
                    let v = 0.9 * (2.0 * PI * f * i as f64 / fs).sin();
                    counts.map_or(v, |c| (v * c).round() / c)
                })
                .collect()
        };
        for f in [29.95, 50.0, 60.0, 120.0, 1000.0] {
            for counts in [Some(32_767.0), None] {
                let a = analyze_signal(&tone(f, counts), fs, &ff, &Method::default())?;
                assert_eq!(a.diagnosis.family, FaultFamily::None, "{f} Hz {counts:?}");
                let why = a.kurtogram.no_content.as_deref().unwrap_or("");
                assert!(why.contains("content ends"), "{f} Hz {counts:?}: {why:?}");
            }
        }
        let mut noisy = tone(60.0, None);
        for (v, n) in noisy.iter_mut().zip(gaussian_noise(256_000, 0.01, 3)) {
            *v += n;
        }
        let a = analyze_signal(&noisy, fs, &ff, &Method::default())?;
        assert!(a.kurtogram.no_content.is_none(), "{:?}", a.kurtogram);
        assert!(
            a.kurtogram.band_hz.0 + 1e-9 >= 5.0 * ff.bpfi,
            "{:?}",
            a.kurtogram
        );
        assert_eq!(a.diagnosis.family, FaultFamily::None);
        Ok(())
    }

    #[test]
    fn noise_is_healthy_under_every_band_rule() -> Result<(), analysis::AnalysisError> {
        let ff = cwru();
        for seed in [11, 12] {
            let x = gaussian_noise(48_000, 1.0, seed);
            for rule in [BandRule::Kurtosis, BandRule::Evidence, BandRule::Protrugram] {
                for squared_envelope in [false, true] {
                    let m = Method {
                        band_rule: rule,
                        squared_envelope,
                        ..Method::default()
                    };
                    let d = analyze_signal(&x, FS, &ff, &m)?.diagnosis;
                    assert_eq!(d.family, FaultFamily::None, "seed {seed} {m:?}: {d:?}");
                    assert!(d.confidence.is_finite() && d.margin_db.is_finite());
                }
            }
        }
        Ok(())
    }
}
