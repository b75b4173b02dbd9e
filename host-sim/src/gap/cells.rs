//! Feature cells (sim-to-real.md, "Terms"): zone levels and fractional-octave shape of the
//! thesis's four zones, time-domain statistics, and envelope-spectrum cells of the fault
//! family (peak over floor of harmonics 1–5, sidebands at ±1× and ±FTF, harmonic decay,
//! offset of the measured fault frequency from the kinematic one).

use crate::analysis::{self, AnalysisError, FaultFamily, FaultFrequencies, WelchParams, ZoneBands};

/// What the cells are computed for.
#[derive(Debug, Clone)]
pub struct CellSpec {
    /// Sample rate (Hz).
    pub fs: f64,
    /// Kinematic frequencies of the bearing at the record's speed; its `natural_hz` (the
    /// structural resonance) sets the natural-frequency zone.
    pub ff: FaultFrequencies,
    /// Fault family whose harmonics the envelope cells follow (none: BPFO).
    pub family: FaultFamily,
    /// Upper edge (Hz) of what the measured record holds, when it ends well below its
    /// Nyquist frequency ([`analysis::content_band::content_edge`]): the record and every
    /// simulation are low-passed there and the zones cut there
    /// ([`super::segment_cells`]). `None`: the whole band up to fs/2.
    pub band_hz: Option<f64>,
}

/// One cell value.
#[derive(Debug, Clone)]
pub struct CellValue {
    /// Name.
    pub name: String,
    /// Group: `zone`, `shape`, `stat`, `env`.
    pub group: &'static str,
    /// Unit.
    pub unit: &'static str,
    /// Value.
    pub value: f64,
}

fn db(x: f64) -> f64 {
    20.0 * x.max(1e-12).log10()
}

fn push(v: &mut Vec<CellValue>, name: String, group: &'static str, unit: &'static str, value: f64) {
    if value.is_finite() {
        v.push(CellValue {
            name,
            group,
            unit,
            value,
        });
    } else {
        v.push(CellValue {
            name,
            group,
            unit,
            value: 0.0,
        });
    }
}

/// Half-width of the envelope-spectrum neighbourhood whose median is a fault line's floor,
/// as a fraction of the fault frequency (±40 %: clear of the neighbouring harmonics).
pub const FLOOR_HALF_WIDTH: f64 = 0.4;

/// Periods of the fault fundamental a segment must hold for its envelope cells: the bound
/// `analyze` puts on a whole record ([`crate::resolvable::MIN_PERIODS`], ten), so that the
/// envelope spectrum's bins are at most a tenth of the fault frequency and the floor of
/// ±[`FLOOR_HALF_WIDTH`] around a line holds four bins or more beside its ±2-bin main lobe.
pub const MIN_ENVELOPE_PERIODS: f64 = crate::resolvable::MIN_PERIODS;

/// The fault frequency (Hz) whose harmonics the envelope cells of `spec` follow: BPFI for
/// the inner race, twice the BSF for a ball, BPFO otherwise.
pub fn fault_base_hz(spec: &CellSpec) -> f64 {
    match spec.family {
        FaultFamily::InnerRace => spec.ff.bpfi,
        FaultFamily::Ball => 2.0 * spec.ff.bsf,
        _ => spec.ff.bpfo,
    }
}

/// Whether a segment of `n` samples at `fs` Hz resolves a fault line at `base_hz` and its
/// floor: it holds at least [`MIN_ENVELOPE_PERIODS`] periods of it. The decision depends on
/// the segment's length only, so a measured part and its simulation (the same length) have
/// the same cells.
pub fn envelope_resolved(n: usize, fs: f64, base_hz: f64) -> bool {
    fs > 0.0 && base_hz > 0.0 && n as f64 / fs * base_hz >= MIN_ENVELOPE_PERIODS
}

/// Shortest segment (s) whose envelope cells `spec` resolves ([`envelope_resolved`]);
/// `None` without a positive fault frequency.
pub fn min_envelope_segment_s(spec: &CellSpec) -> Option<f64> {
    let base = fault_base_hz(spec);
    (base > 0.0 && base.is_finite()).then(|| MIN_ENVELOPE_PERIODS / base)
}

/// The cells of record `x` (same order and names for every record with the same spec).
pub fn cells(x: &[f64], spec: &CellSpec) -> Result<Vec<CellValue>, AnalysisError> {
    let mut v = vec![];
    let fs = spec.fs;
    // Zones: level (dB re 1 unit RMS) and 1/3-octave shape relative to the zone level.
    let nperseg = (x.len() / 4).next_power_of_two().clamp(256, 8192);
    let psd = analysis::welch_psd(
        x,
        fs,
        &WelchParams {
            nperseg,
            ..WelchParams::default()
        },
    )?;
    // A zone wholly beyond fs/2 (a record sampled below twice the housing's high zone,
    // 5–6 kHz for the CWRU rig) is empty: it has no cells, as nothing of it is recorded.
    let zones = ZoneBands::new_clipped(&spec.ff, fs)?;
    let zones = match spec.band_hz {
        Some(top) => zones.below(top)?,
        None => zones,
    };
    let amp = analysis::amplitude_spectrum(x, fs, analysis::Window::Hann).ok();
    // The natural-frequency zone of the cells spans every structural resonance band between
    // the fault zone and the high zone (the thesis's zone is the model's one resonance ±30 %;
    // a measured record's housing modes lie anywhere above the fault zone, and a mode in a
    // gap between zones would be invisible to every zone cell).
    let natural = (zones.fault.1.min(zones.natural.0), zones.natural.1);
    // Shape resolution: 1/3 octave in the rotating and fault zones (few PSD bins per band
    // at low frequency), 1/6 octave in the natural and high zones (a mode of 5 % damping is
    // about 1/7 octave wide).
    for (name, band, per_octave) in [
        ("rotating", zones.rotating, 3.0),
        ("fault", zones.fault, 3.0),
        ("natural", natural, 6.0),
        ("high", zones.high, 6.0),
    ] {
        if band.0 >= band.1 {
            continue;
        }
        let level = analysis::zones::band_rms(&psd, band);
        push(&mut v, format!("zone:{name}"), "zone", "dB", db(level));
        if name == "rotating" {
            // The rotating zone is lines, not bands: the levels of the 1×–5× shaft
            // harmonics (largest amplitude within ±¼ order of each, from one Hann-windowed
            // FFT of the segment), relative to the zone level. Fractional-octave bands at
            // these frequencies are narrower than a segment's frequency resolution.
            for k in 1..=5 {
                let f = k as f64 * spec.ff.shaft_hz;
                let a = amp
                    .as_ref()
                    .map(|a| {
                        let k0 = a.bin_of((f - 0.25 * spec.ff.shaft_hz).max(0.0));
                        let k1 = a.bin_of(f + 0.25 * spec.ff.shaft_hz);
                        (k0..=k1)
                            .filter_map(|j| a.values.get(j).copied())
                            .fold(0.0, f64::max)
                    })
                    .unwrap_or(0.0);
                push(
                    &mut v,
                    format!("shape:rotating:{k}x"),
                    "shape",
                    "dB",
                    (db(a / std::f64::consts::SQRT_2) - db(level)).max(-80.0),
                );
            }
            continue;
        }
        // Fractional-octave bands inside the zone, relative to the zone level.
        let step = 2f64.powf(1.0 / per_octave);
        let mut f = band.0.max(psd.df * 2.0);
        let mut k = 0;
        while f * step <= band.1 && k < 40 {
            let hi = f * step;
            let b = analysis::zones::band_rms(&psd, (f, hi));
            push(
                &mut v,
                format!("shape:{name}:{k}"),
                "shape",
                "dB",
                // Bands more than 80 dB below the zone level are empty on any record
                // (numerical floor, not signal): clamped so they cannot carry a gap.
                (db(b) - db(level)).max(-80.0),
            );
            f = hi;
            k += 1;
        }
    }
    // Statistics.
    let st = analysis::stats(x)?;
    push(&mut v, "stat:rms".into(), "stat", "dB", db(st.rms));
    push(&mut v, "stat:kurtosis".into(), "stat", "", st.kurtosis);
    push(&mut v, "stat:crest".into(), "stat", "", st.crest_factor);
    push(&mut v, "stat:skewness".into(), "stat", "", st.skewness);
    // Envelope cells of the family's fault frequency, when the segment resolves it.
    let base = fault_base_hz(spec);
    if !envelope_resolved(x.len(), fs, base) {
        return Ok(v);
    }
    let env = analysis::envelope_spectrum(x, fs, None)?;
    let tol = 0.02 * base + env.df;
    let floor_w = FLOOR_HALF_WIDTH * base;
    let mut levels = vec![];
    let mut f1 = base;
    for h in 1..=5 {
        let p = analysis::peak_near(&env, h as f64 * base, h as f64 * tol);
        if h == 1 {
            if let Some(p) = p {
                f1 = p.freq;
            }
        }
        // Line over the median of its neighbourhood, both clamped as `db` does: a floor
        // of zeros (an envelope without noise) gives a bounded level, not 20·log10 of the
        // smallest positive number.
        let pof = p.map_or(0.0, |p| {
            db(p.value) - db(analysis::noise_floor(&env, p.freq, floor_w))
        });
        levels.push(p.map(|p| db(p.value)).unwrap_or(-240.0));
        push(&mut v, format!("env:h{h}"), "env", "dB", pof);
    }
    // Sidebands: the largest envelope value within ±1.5 bins of f1 ± Δ (always defined,
    // unlike a local-maximum search that returns nothing for a missing sideband), mean of
    // both sides in dB relative to the largest value within ±1.5 bins of f1.
    let window_max = |f: f64| -> f64 {
        let k0 = env.bin_of((f - 1.5 * env.df).max(0.0));
        let k1 = env.bin_of(f + 1.5 * env.df);
        (k0..=k1)
            .filter_map(|k| env.values.get(k).copied())
            .fold(0.0, f64::max)
    };
    let h1 = db(window_max(f1));
    for (name, df) in [("1x", spec.ff.shaft_hz), ("ftf", spec.ff.ftf)] {
        let lo = db(window_max(f1 - df));
        let hi = db(window_max(f1 + df));
        push(
            &mut v,
            format!("env:sideband-{name}"),
            "env",
            "dB",
            0.5 * (lo + hi) - h1,
        );
    }
    // Harmonic decay: least-squares slope of the harmonic levels (dB per harmonic).
    let n = levels.len() as f64;
    let mx = (n + 1.0) / 2.0;
    let my = levels.iter().sum::<f64>() / n;
    let slope = levels
        .iter()
        .enumerate()
        .map(|(i, y)| (i as f64 + 1.0 - mx) * (y - my))
        .sum::<f64>()
        / levels
            .iter()
            .enumerate()
            .map(|(i, _)| (i as f64 + 1.0 - mx).powi(2))
            .sum::<f64>();
    push(&mut v, "env:decay".into(), "env", "dB", slope);
    push(
        &mut v,
        "env:slip".into(),
        "env",
        "%",
        100.0 * (f1 / base - 1.0),
    );
    Ok(v)
}
