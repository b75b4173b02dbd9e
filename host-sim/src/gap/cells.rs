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
    /// Kinematic frequencies of the bearing at the record's speed.
    pub ff: FaultFrequencies,
    /// Structural resonance (Hz) that sets the natural-frequency zone.
    pub resonance_hz: f64,
    /// Fault family whose harmonics the envelope cells follow (none: BPFO).
    pub family: FaultFamily,
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
    let zones = ZoneBands::new(&spec.ff, spec.resonance_hz, fs)?;
    for (name, band) in [
        ("rotating", zones.rotating),
        ("fault", zones.fault),
        ("natural", zones.natural),
        ("high", zones.high),
    ] {
        let level = analysis::zones::band_rms(&psd, band);
        push(&mut v, format!("zone:{name}"), "zone", "dB", db(level));
        // Third-octave bands inside the zone, relative to the zone level.
        let mut f = band.0.max(psd.df * 2.0);
        let mut k = 0;
        while f * 2f64.powf(1.0 / 3.0) <= band.1 && k < 12 {
            let hi = f * 2f64.powf(1.0 / 3.0);
            let b = analysis::zones::band_rms(&psd, (f, hi));
            push(
                &mut v,
                format!("shape:{name}:{k}"),
                "shape",
                "dB",
                db(b) - db(level),
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
    // Envelope cells of the family's fault frequency.
    let base = match spec.family {
        FaultFamily::InnerRace => spec.ff.bpfi,
        FaultFamily::Ball => 2.0 * spec.ff.bsf,
        _ => spec.ff.bpfo,
    };
    let env = analysis::envelope_spectrum(x, fs, None)?;
    let tol = 0.02 * base + env.df;
    let floor_w = 0.4 * base;
    let mut levels = vec![];
    let mut f1 = base;
    for h in 1..=5 {
        let (p, pof) = analysis::peak_over_floor_db(&env, h as f64 * base, h as f64 * tol, floor_w)
            .map(|(p, d)| (Some(p), d))
            .unwrap_or((None, 0.0));
        if h == 1 {
            if let Some(p) = p {
                f1 = p.freq;
            }
        }
        levels.push(p.map(|p| db(p.value)).unwrap_or(-240.0));
        push(&mut v, format!("env:h{h}"), "env", "dB", pof);
    }
    let h1 = levels.first().copied().unwrap_or(-240.0);
    for (name, df) in [("1x", spec.ff.shaft_hz), ("ftf", spec.ff.ftf)] {
        let lo = analysis::peak_near(&env, f1 - df, env.df * 1.5)
            .map(|p| db(p.value))
            .unwrap_or(-240.0);
        let hi = analysis::peak_near(&env, f1 + df, env.df * 1.5)
            .map(|p| db(p.value))
            .unwrap_or(-240.0);
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
