//! Whether a record can resolve the defect frequencies of its bearing at all: a sample rate
//! too low for the fault harmonics, or a record too short to hold a few impacts of the
//! slowest fault family (so that its envelope spectrum has a line at all), contradicts the analysis asked for and is refused (exit 2) rather
//! than answered with a call.

/// Highest fault harmonic that must lie below Nyquist (the detector searches harmonics of the
/// fundamental; three is the least that a harmonic fit can use).
pub const MIN_HARMONICS: f64 = 3.0;
/// Periods of the slowest fault fundamental a record must hold (one envelope-spectrum line
/// needs several impacts; ten keep its bin at most a tenth of the frequency).
pub const MIN_PERIODS: f64 = 10.0;

/// Check that `n` samples at `fs` Hz resolve the fault fundamentals `f` = [BPFO, BPFI, 2×BSF]
/// (Hz) of a shaft at `shaft_hz`: `fs / 2` above
/// [`MIN_HARMONICS`] × max(BPFI, BPFO, 2×BSF), and a duration `n / fs` of at least
/// [`MIN_PERIODS`] periods of min(BPFO, BPFI, 2×BSF). The message
/// names the field (`fs`, record length) and the bound.
pub fn check_resolvable(n: usize, fs: f64, shaft_hz: f64, f: [f64; 3]) -> Result<(), String> {
    let top = f.iter().copied().fold(0.0, f64::max);
    let need = 2.0 * MIN_HARMONICS * top;
    if fs <= need {
        return Err(format!(
            "field fs: {fs} Hz cannot resolve the defect frequencies of this bearing at {:.1} rpm (allowed fs > {need:.1} Hz = 2 x {MIN_HARMONICS} x max(BPFO, BPFI, 2xBSF))",
            shaft_hz * 60.0
        ));
    }
    let low = f.iter().copied().fold(f64::INFINITY, f64::min);
    if low.is_finite() && low > 0.0 {
        let min_s = MIN_PERIODS / low;
        let dur = n as f64 / fs;
        if dur < min_s {
            return Err(format!(
                "record length: {n} samples at {fs} Hz = {dur:.4} s is too short to resolve the defect frequencies (the slowest, {low:.2} Hz, needs >= {MIN_PERIODS} periods: allowed >= {min_s:.4} s, i.e. >= {} samples)",
                (min_s * fs).ceil()
            ));
        }
    }
    Ok(())
}
