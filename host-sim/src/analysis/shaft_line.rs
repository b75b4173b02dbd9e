//! Is the shaft where the sample rate and the speed put it?
//!
//! A wrong sample rate or a wrong shaft speed scales every frequency the diagnosis looks
//! for, and a harmonic series scaled by 2 (or ½) still lies on a harmonic series: the CWRU
//! inner-race record `IR007_0` analysed at twice or half its rate is still called inner
//! race, and `IR021_2` at half its rate is called outer race at confidence 0.80. The raw
//! spectrum of a rotating machine nearly always carries a line at the shaft speed
//! (residual unbalance, ISO 21940), so the record itself can say whether the rate and
//! speed it was given are right: the 1× line must be there (within the tolerance a speed
//! stated to a few percent needs), and no line at ½× (where the true 1× sits when the
//! rate given is half the true one, or the speed twice).
//!
//! Thresholds set before looking at any record: a line is a local maximum at least
//! [`LINE_DB`] = 6 dB (4× in power) over the median of its neighbourhood; tolerance
//! [`TOLERANCE`] = ±3 % of the shaft frequency. On the CWRU development part (drive end,
//! 0–1 hp, at their own rate) the 1× lines stand 14.2–38.8 dB and the ½× at most 3.8 dB;
//! the figures of the other parts are in `docs/cwru-detector.md`. The check reports; it
//! does not change the call.
//!
//! [`refine`] goes one step further when the record contradicts the speed it was given: a
//! speed a few percent off (a motor's nameplate or synchronous speed typed for its running
//! speed — a 4-pole 60 Hz induction motor runs 2–5 % below 1 800 rpm at full load — or a
//! stored speed that is wrong) moves every fault frequency out of the detector's ±2 % slip
//! window, and the call goes to whichever family lies there (CWRU `IR007_0` analysed at
//! 1 851 rpm instead of 1 797 was called ball at 0.98). When no line stands within
//! ±[`REFINE_MIN`] of the stated 1× and the strongest line within ±[`SEARCH`] does, more
//! than [`REFINE_MIN`] away, with a line at its own 2× or 3×, that line is the shaft, and the
//! diagnosis uses the speed fitted to its 1×–5× series (stop 57), a line more than a bin
//! from the series dropped (stop 58, `series_fit`). Set a priori (not fitted
//! on any record): ±5 % covers the full-load slip of standard induction motors; 1 % is half
//! the slip window, an error the detector absorbs
//! and the spectrum's resolution (1 % of the shaft frequency) can just resolve. Windows are
//! exact in the lines' interpolated frequencies (since stop 56; rounded out to whole bins,
//! ±1 % reached ±1.67 %). The harmonic (stop 56): a wrong sample rate moves the true 1× 10–25 %
//! away, and some other lone line 1–5 % from the stated speed was taken for the shaft,
//! silencing [`check`]'s warning; a shaft shows harmonics (2× or 3×: a 4-pole 60 Hz motor's
//! 2× lies a few percent from the 60 Hz line, which can mask it).

use super::peaks::{over_floor_db, peak_over_floor_db, peak_within};
use super::spectrum::{welch_psd, Spectrum, WelchParams};
use super::stats::upper_median;
use super::window::Window;
use serde::Serialize;

/// Height over the neighbourhood (dB, power) from which a local maximum counts as a line.
pub const LINE_DB: f64 = 6.0;
/// Relative tolerance on the expected shaft frequency (a speed stated to a few percent).
pub const TOLERANCE: f64 = 0.03;
/// Coarsest resolution (as a fraction of the shaft frequency) at which the check is made:
/// coarser, the ±3 % window holds barely one bin and a neighbouring line leaks into it.
pub const MAX_RESOLUTION: f64 = 0.025;
/// Resolution aimed at (fraction of the shaft frequency) when the record is long enough.
const TARGET_RESOLUTION: f64 = 0.01;
/// Half-width of the neighbourhood whose median is a line's floor, as a fraction of the
/// shaft frequency (±15 %: away from the next shaft harmonic).
const FLOOR_HALF_WIDTH: f64 = 0.15;
/// Longest segment: a quarter of the record (seven half-overlapping segments).
const MIN_SEGMENTS_DIV: usize = 4;
/// Half-width (fraction of the stated shaft frequency) searched for the true 1× line by
/// [`refine`]: a stated speed up to 5 % off.
pub const SEARCH: f64 = 0.05;
/// Highest shaft harmonic [`ShaftSpectrum::refine`] reads the measured speed from (the
/// 1×–5× of unbalance, misalignment and looseness; above them lines of other origin crowd
/// in).
pub const SERIES_HARMONICS: usize = 5;
/// Half-width (fraction of a preset's nominal shaft frequency) [`find`] searches for the
/// shaft of a record that states no speed.
pub const FIND_SEARCH: f64 = 0.25;
/// Height (dB, power) over the median of its ±5 Hz neighbourhood from which [`find`] takes
/// a line for the shaft in its coarse spectrum.
const FIND_LINE_DB: f64 = 10.0;
/// Where a refined speed came from, as `analyze` and `gap` report it (`rpm_source`).
pub const REFINED_SOURCE: &str = "shaft line";
/// Least offset (fraction of the stated shaft frequency) of the measured 1× line at which
/// [`refine`] replaces the stated speed; below it the slip window absorbs the error.
pub const REFINE_MIN: f64 = 0.01;

/// What the raw spectrum says about the shaft speed a record was analysed at.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ShaftLine {
    /// Shaft frequency the sample rate and speed put the 1× line at, Hz.
    pub shaft_hz: f64,
    /// Frequency resolution of the spectrum checked, Hz.
    pub resolution_hz: f64,
    /// Height of the strongest line within ±3 % of `shaft_hz` over its neighbourhood, dB
    /// (`None`: no local maximum there).
    pub line_db: Option<f64>,
    /// The same at half the shaft frequency.
    pub half_line_db: Option<f64>,
    /// A 1× line of at least [`LINE_DB`] and none at ½×: the rate and speed agree with the
    /// record. `false`: the shaft is not where they put it — check `--fs` and `--rpm`.
    pub consistent: bool,
    /// Why not, in words (`None` when consistent).
    pub reason: Option<String>,
}

/// The shaft-line check of `x` (sampled at `fs` Hz) for a shaft at `shaft_hz`; `None`
/// when the record is too short to resolve [`MAX_RESOLUTION`] of the shaft frequency
/// (or the spectrum cannot be computed), i.e. when the check would say nothing.
pub fn check(x: &[f64], fs: f64, shaft_hz: f64) -> Option<ShaftLine> {
    ShaftSpectrum::new(x, fs, shaft_hz).map(|s| s.check())
}

/// The measured shaft frequency of `x` (sampled at `fs` Hz) when the stated `shaft_hz` is
/// off ([`ShaftSpectrum::refine`]); `None` when the record confirms the stated speed, shows
/// no line near it, or cannot be checked.
pub fn refine(x: &[f64], fs: f64, shaft_hz: f64) -> Option<Refinement> {
    ShaftSpectrum::new(x, fs, shaft_hz)?.refine()
}

/// The shaft frequency (Hz) of a record that states none (the gap's `rpm_source`
/// `spectrum`): the strongest local maximum within ±[`FIND_SEARCH`] of `nominal_hz` that
/// stands 10 dB over the median of its ±5 Hz neighbourhood, in a Welch spectrum of
/// segments as long as half the record allows (1 024 to 65 536 points: any record of a
/// second holds one); then, where the record resolves [`MAX_RESOLUTION`] of it
/// ([`ShaftSpectrum`]), the speed fitted to the harmonic series of the strongest line of
/// [`LINE_DB`] within one coarse bin (at least ±[`REFINE_MIN`]) of it. The coarse bin alone
/// errs by up to half a bin: 65 536 points at 97.656 kHz are 1.5 Hz, and a 24.6 Hz shaft
/// was read 2.9 % off (0.8–1.2 % at 48 kHz; stop 58), outside the fault detector's ±2 %
/// slip window. `None` when there is no such line.
pub fn find(x: &[f64], fs: f64, nominal_hz: f64) -> Option<f64> {
    let nperseg = (x.len() / 2).next_power_of_two().clamp(1024, 1 << 16);
    let params = WelchParams {
        nperseg,
        ..WelchParams::default()
    };
    let psd = welch_psd(x, fs, &params).ok()?;
    let k0 = psd.bin_of((1.0 - FIND_SEARCH) * nominal_hz).max(1);
    let k1 = psd.bin_of((1.0 + FIND_SEARCH) * nominal_hz);
    let (k, v) = (k0..=k1)
        .filter_map(|k| psd.values.get(k).map(|v| (k, *v)))
        .max_by(|a, b| a.1.total_cmp(&b.1))?;
    let w = ((5.0 / psd.df) as usize).max(3);
    let neighbours: Vec<f64> = (k.saturating_sub(w)..=k + w)
        .filter(|j| j.abs_diff(k) > 1)
        .filter_map(|j| psd.values.get(j).copied())
        .collect();
    let floor = upper_median(neighbours)?;
    if !(floor > 0.0 && v > 10f64.powf(FIND_LINE_DB / 10.0) * floor) {
        return None;
    }
    let coarse = psd.freq(k);
    let fine = ShaftSpectrum::new(x, fs, coarse).and_then(|s| {
        let tol = psd.df.max(REFINE_MIN * coarse);
        let (line, db) = peak_over_floor_db(&s.psd, coarse, tol, FLOOR_HALF_WIDTH * coarse)?;
        (db >= LINE_DB).then(|| s.series_hz(line.freq).0)
    });
    Some(fine.unwrap_or(coarse))
}

/// The Welch power spectrum [`check`] and [`refine`] read around one shaft frequency
/// (≈ 1 % of it per bin, at least seven half-overlapping Hann segments), computed once
/// when a record is both refined and checked at its stated speed.
#[derive(Debug, Clone)]
pub struct ShaftSpectrum {
    psd: Spectrum,
    /// Frequency resolution, Hz.
    resolution_hz: f64,
    /// Shaft frequency the spectrum was laid out for, Hz.
    shaft_hz: f64,
    /// Sample rate, Hz.
    fs: f64,
}

impl ShaftSpectrum {
    /// The spectrum of `x` (sampled at `fs` Hz) for a shaft at `shaft_hz` (≈
    /// 1 % of it per bin); `None` when a line within ±[`TOLERANCE`] of it
    /// is above Nyquist, the record is too short to resolve
    /// [`MAX_RESOLUTION`] of the shaft frequency, or the spectrum cannot be computed.
    pub fn new(x: &[f64], fs: f64, shaft_hz: f64) -> Option<Self> {
        let (psd, resolution_hz) = shaft_spectrum(x, fs, shaft_hz)?;
        Some(Self {
            psd,
            resolution_hz,
            shaft_hz,
            fs,
        })
    }

    /// Shaft frequency the spectrum was laid out for, Hz.
    pub fn shaft_hz(&self) -> f64 {
        self.shaft_hz
    }

    /// The shaft-line check at [`Self::shaft_hz`] (see [`check`]).
    pub fn check(&self) -> ShaftLine {
        let (psd, shaft_hz, resolution_hz) = (&self.psd, self.shaft_hz, self.resolution_hz);
        let height = |f: f64| line_height_db(psd, f);
        let line_db = height(shaft_hz);
        let half_line_db = height(0.5 * shaft_hz);
        let db = |d: Option<f64>| d.map_or("none".to_string(), |d| format!("{d:.1} dB"));
        let reason = if line_db.is_none_or(|d| d < LINE_DB) {
            Some(format!(
            "no shaft line at 1x ({shaft_hz:.2} Hz +-3 %: {}; a line needs {LINE_DB} dB): the sample rate or the speed is wrong, or this machine shows no 1x",
            db(line_db)
        ))
        } else if half_line_db.is_some_and(|d| d >= LINE_DB) {
            Some(format!(
            "a line at 1/2x ({:.2} Hz: {}): the sample rate given is half the true one (or the speed twice), or the machine vibrates at half orders (looseness, rub)",
            0.5 * shaft_hz,
            db(half_line_db)
        ))
        } else {
            None
        };
        ShaftLine {
            shaft_hz,
            resolution_hz,
            line_db,
            half_line_db,
            consistent: reason.is_none(),
            reason,
        }
    }

    /// The measured shaft frequency when the stated [`Self::shaft_hz`] is off: no line of
    /// [`LINE_DB`] within ±[`REFINE_MIN`] of it, and the strongest local maximum within
    /// ±[`SEARCH`] a line of [`LINE_DB`] more than [`REFINE_MIN`] away, with a line of
    /// [`LINE_DB`] within ±[`REFINE_MIN`] of its own 2× or 3×; the measured speed is then
    /// fitted to that line's series ([`SERIES_HARMONICS`]), and must itself lie more than
    /// [`REFINE_MIN`] (and at most [`SEARCH`]) from the stated one. `None` when the
    /// record confirms the stated speed, shows no line near it, or a line ±[`SEARCH`] away
    /// would be above Nyquist.
    pub fn refine(&self) -> Option<Refinement> {
        let (psd, shaft_hz) = (&self.psd, self.shaft_hz);
        if shaft_hz * (1.0 + SEARCH) >= 0.5 * self.fs {
            return None;
        }
        let floor = FLOOR_HALF_WIDTH * shaft_hz;
        // Exactly ±REFINE_MIN: at 1 % of the shaft per bin, a window rounded to whole bins
        // reached 1.67 % and took the true 1× line of a speed stated 1.6 % off for a line
        // at the stated speed (stop 56).
        if line_within_db(psd, shaft_hz, REFINE_MIN * shaft_hz).is_some_and(|db| db >= LINE_DB) {
            return None;
        }
        let (line, line_db) = peak_over_floor_db(psd, shaft_hz, SEARCH * shaft_hz, floor)?;
        // A shaft has harmonics: its 2× or 3× must stand too (within ±REFINE_MIN of that
        // multiple of the line). A wrong sample rate moves the true 1× 10–25 % away and can
        // leave some other lone line 1–5 % from the stated speed. Either of two, as a
        // 4-pole 60 Hz motor's 2× lies within a few percent of the 60 Hz line, which can
        // mask it.
        let harmonic = [2.0, 3.0].iter().any(|&k| {
            line_within_db(psd, k * line.freq, k * REFINE_MIN * line.freq)
                .is_some_and(|db| db >= LINE_DB)
        });
        if !(harmonic && line_db >= LINE_DB) {
            return None;
        }
        // The speed from the whole series, not the 1× alone (stop 57): the k-th harmonic
        // resolves the shaft k times finer, and a non-shaft line beside the 1× weighs
        // 1/Σk² of the fit (CWRU `OR007@12_1`: 1× read at 30.16 Hz, series at 29.94 Hz).
        let (measured_hz, harmonics) = self.series_hz(line.freq);
        let offset = measured_hz / shaft_hz - 1.0;
        (offset.abs() > REFINE_MIN && offset.abs() <= SEARCH).then_some(Refinement {
            stated_hz: shaft_hz,
            measured_hz,
            offset,
            line_db,
            harmonics,
            resolution_hz: self.resolution_hz,
        })
    }

    /// The shaft frequency (Hz) of the harmonic series whose 1× is near `f1`, and how many
    /// of its first [`SERIES_HARMONICS`] lines it rests on: every harmonic `k` (below
    /// Nyquist) with a line of [`LINE_DB`] within ±[`REFINE_MIN`] of `k·f1` gives a
    /// frequency `f_k`, and the estimate is their least-squares fit `Σ k f_k / Σ k²` to
    /// `f_k = k f` (equal errors in Hz: the k-th harmonic weighs k² times the 1×). While
    /// three or more lines remain and one lies more than a bin of the spectrum from `k`
    /// times the fit, the farthest is dropped and the rest refitted ([`series_fit`]).
    /// Without such a line, `f1` itself.
    fn series_hz(&self, f1: f64) -> (f64, usize) {
        let mut lines: [Option<f64>; SERIES_HARMONICS] = [None; SERIES_HARMONICS];
        for (i, slot) in lines.iter_mut().enumerate() {
            let fk = (i + 1) as f64 * f1;
            if fk * (1.0 + REFINE_MIN) >= 0.5 * self.fs {
                break;
            }
            *slot = peak_within(&self.psd, fk, REFINE_MIN * fk)
                .map(|p| over_floor_db(&self.psd, p, FLOOR_HALF_WIDTH * f1))
                .filter(|&(_, db)| db >= LINE_DB)
                .map(|(p, _)| p.freq);
        }
        series_fit(&mut lines, self.resolution_hz).unwrap_or((f1, 0))
    }
}

/// Least-squares shaft frequency (Hz) of the harmonic lines `lines[k−1] = f_k` (Hz; `None`
/// where harmonic `k` shows no line), `Σ k f_k / Σ k²`, and how many lines it rests on.
/// A line farther than `bin_hz` (the spectrum's resolution) from `k` times the fit is not
/// of the series — a line of other origin stronger than the harmonic in its ±1 % window
/// (CWRU drive-end `IR021_3`: a line at 114.11 Hz where the 4× lies at 115.17 Hz, 3.7 bins
/// away, read the speed 0.25 % low, stop 57) — while the interpolated frequency of a
/// harmonic errs by a fraction of a bin (0.09 bin measured for Hann on a CWRU 1×, stop 57).
/// So the farthest such line is dropped (set to `None`) and the rest refitted, as long as
/// three or more lines remain: of two that disagree, neither is known to be the stray.
/// The one-bin limit is the resolution's own scale, set before any record was looked at.
/// `None` without lines.
fn series_fit(lines: &mut [Option<f64>], bin_hz: f64) -> Option<(f64, usize)> {
    loop {
        let (mut num, mut den, mut n) = (0.0, 0.0, 0);
        for (i, fk) in lines.iter().enumerate() {
            if let Some(fk) = fk {
                let k = (i + 1) as f64;
                num += k * fk;
                den += k * k;
                n += 1;
            }
        }
        if n == 0 || den <= 0.0 {
            return None;
        }
        let f = num / den;
        let worst = lines
            .iter()
            .enumerate()
            .filter_map(|(i, fk)| fk.map(|fk| (i, (fk - (i + 1) as f64 * f).abs())))
            .max_by(|a, b| a.1.total_cmp(&b.1));
        match worst {
            Some((i, r)) if n >= 3 && r > bin_hz => lines[i] = None,
            _ => return Some((f, n)),
        }
    }
}

/// The Welch power spectrum of [`ShaftSpectrum::new`] and its resolution, Hz.
fn shaft_spectrum(x: &[f64], fs: f64, shaft_hz: f64) -> Option<(Spectrum, f64)> {
    if !(fs.is_finite() && fs > 0.0 && shaft_hz.is_finite() && shaft_hz > 0.0) {
        return None;
    }
    if shaft_hz * (1.0 + TOLERANCE) >= 0.5 * fs {
        return None;
    }
    let wanted = (fs / (TARGET_RESOLUTION * shaft_hz)).ceil();
    // At least seven half-overlapping segments: with fewer averages the noise alone makes
    // 6 dB maxima in a ±3 % window too often. Any length (not a power of two), so that the
    // resolution follows the record's duration, 4/T Hz, rather than steps of two.
    let longest = x.len() / MIN_SEGMENTS_DIV;
    let nperseg = if wanted < longest as f64 {
        wanted as usize
    } else {
        longest
    };
    if nperseg < 2 {
        return None;
    }
    let resolution_hz = fs / nperseg as f64;
    if resolution_hz > MAX_RESOLUTION * shaft_hz {
        return None;
    }
    let psd = welch_psd(
        x,
        fs,
        &WelchParams {
            nperseg,
            overlap: 0.5,
            window: Window::Hann,
        },
    )
    .ok()?;
    Some((psd, resolution_hz))
}

/// The shaft speed the record shows when it contradicts the one stated (see the module
/// documentation and [`refine`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Refinement {
    /// Shaft frequency stated (argument, file, sidecar or configuration), Hz.
    pub stated_hz: f64,
    /// Measured shaft frequency, Hz: the least-squares fit to the lines of its series
    /// (`harmonics` of them, each by parabolic interpolation of the power spectrum; see
    /// [`ShaftSpectrum::refine`]), the shaft frequency the diagnosis uses.
    pub measured_hz: f64,
    /// `measured_hz / stated_hz − 1`.
    pub offset: f64,
    /// Height of the measured line over its ±15 % neighbourhood, dB (≥ [`LINE_DB`]).
    pub line_db: f64,
    /// Lines of the shaft's series (1×–[`SERIES_HARMONICS`]×) `measured_hz` was fitted to.
    pub harmonics: usize,
    /// Frequency resolution of the spectrum searched, Hz.
    pub resolution_hz: f64,
}

impl Refinement {
    /// The measured shaft speed, rpm.
    pub fn rpm(&self) -> f64 {
        60.0 * self.measured_hz
    }
}

/// Height (dB) of the strongest local maximum within ±[`TOLERANCE`] of `f` over the
/// median of its ±15 % neighbourhood.
fn line_height_db(psd: &Spectrum, f: f64) -> Option<f64> {
    line_within_db(psd, f, TOLERANCE * f)
}

/// Height (dB) of the strongest local maximum whose interpolated frequency lies within
/// exactly `f ± tol_hz` ([`peak_within`]: a window rounded out to whole bins
/// of 1 % of the shaft would stretch ±1 % to ±1.67 %) over the median of its ±15 %
/// neighbourhood.
fn line_within_db(psd: &Spectrum, f: f64, tol_hz: f64) -> Option<f64> {
    peak_within(psd, f, tol_hz).map(|p| over_floor_db(psd, p, FLOOR_HALF_WIDTH * f).1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::synth::{gaussian_noise, sine};

    /// A shaft at 29.95 Hz with 2× and 3× harmonics in noise, 20 s at 12 kHz.
    fn machine(fs: f64) -> Vec<f64> {
        let n = (20.0 * fs) as usize;
        let f = 29.95;
        let noise = gaussian_noise(n, 1.0, 7);
        sine(n, fs, f, 0.3, 0.1)
            .iter()
            .zip(sine(n, fs, 2.0 * f, 0.2, 0.4))
            .zip(sine(n, fs, 3.0 * f, 0.1, 0.9))
            .zip(noise)
            .map(|(((a, b), c), d)| a + b + c + d)
            .collect()
    }

    #[test]
    fn the_right_rate_is_consistent_and_wrong_ones_are_not() {
        let fs = 12_000.0;
        let x = machine(fs);
        let ok = check(&x, fs, 29.95).unwrap();
        assert!(ok.consistent, "{ok:?}");
        assert!(ok.line_db.unwrap() > 15.0, "{ok:?}");
        // Twice the rate (or half the speed): 1× expected where nothing is; half the rate:
        // the true 1× lands on ½×, though the true 2× lands on 1×. ±10 % and ±25 %: off.
        for k in [2.0, 0.5, 1.1, 0.9, 1.25, 0.8] {
            let c = check(&x, fs * k, 29.95).unwrap();
            assert!(!c.consistent, "rate x{k}: {c:?}");
        }
        // The same by a wrong speed instead of a wrong rate.
        for rpm_factor in [2.0, 0.5, 1.25] {
            let c = check(&x, fs, 29.95 * rpm_factor).unwrap();
            assert!(!c.consistent, "speed x{rpm_factor}: {c:?}");
        }
        // A speed 2 % off is within the tolerance.
        assert!(check(&x, fs, 29.95 * 1.02).unwrap().consistent);
    }

    #[test]
    fn noise_has_no_shaft_line_and_short_records_are_not_checked() {
        let fs = 12_000.0;
        let x = gaussian_noise(240_000, 1.0, 3);
        let c = check(&x, fs, 29.95).unwrap();
        assert!(!c.consistent, "{c:?}");
        // Segments of a quarter of the record resolve 4/T Hz: 6 s, 0.67 Hz = 2.2 % of
        // 30 Hz, enough; 5 s, 0.8 Hz = 2.7 %, too coarse.
        assert!(check(&machine(fs)[..72_000], fs, 29.95).unwrap().consistent);
        assert_eq!(check(&machine(fs)[..60_000], fs, 29.95), None);
        assert_eq!(check(&[], fs, 29.95), None);
        assert_eq!(check(&x, fs, f64::NAN), None);
        assert_eq!(check(&x, fs, 7000.0), None);
    }

    /// A stated speed 1.5–4 % off either way is replaced by the line's, to within a tenth of
    /// the spectrum's resolution; one the record confirms (exact, or 0.5 % off: within the
    /// slip window) is kept; one 8 % off is outside the search and kept (the check then
    /// reports it); noise has no line to refine to. At 1.5 % (bins of 1 % of the shaft) the
    /// true line's bin lies inside the ±1 % window once rounded to whole bins: before stop
    /// 56 that bin "confirmed" the stated speed.
    #[test]
    fn a_contradicted_speed_is_measured_from_the_shaft_line() {
        let fs = 12_000.0;
        let x = machine(fs);
        let truth = 29.95;
        for k in [0.96, 0.97, 0.98, 0.985, 1.015, 1.02, 1.03, 1.04] {
            let r = refine(&x, fs, truth * k).unwrap_or_else(|| panic!("x{k}: not refined"));
            assert!(
                (r.measured_hz - truth).abs() < 0.1 * r.resolution_hz,
                "x{k}: {r:?}"
            );
            assert!((r.offset - (1.0 / k - 1.0)).abs() < 0.003, "x{k}: {r:?}");
            assert!(r.line_db >= LINE_DB);
            assert!(check(&x, fs, r.measured_hz).unwrap().consistent);
        }
        for k in [1.0, 0.995, 1.005, 0.92, 1.08] {
            assert_eq!(refine(&x, fs, truth * k), None, "x{k}");
        }
        let noise = gaussian_noise(240_000, 1.0, 3);
        for k in [0.97, 1.0, 1.03] {
            assert_eq!(refine(&noise, fs, truth * k), None, "noise x{k}");
        }
        assert_eq!(refine(&x[..60_000], fs, truth * 1.03), None, "too short");
    }

    /// A lone line 1–5 % from the stated speed, without a 2× or 3× of its own, is not taken
    /// for the shaft (what a wrong sample rate leaves near the expected 1×); with either
    /// harmonic it is, and the 60 Hz line that can mask a 4-pole motor's 2× does not matter
    /// when the 3× stands.
    #[test]
    fn a_line_without_harmonics_is_not_a_shaft() {
        let fs = 12_000.0;
        let n = (20.0 * fs) as usize;
        let f = 29.95;
        let noise = || gaussian_noise(n, 1.0, 11);
        let with = |parts: &[(f64, f64)]| -> Vec<f64> {
            let mut x = noise();
            for &(freq, amp) in parts {
                for (v, s) in x.iter_mut().zip(sine(n, fs, freq, amp, 0.3)) {
                    *v += s;
                }
            }
            x
        };
        let stated = f * 0.97;
        assert_eq!(refine(&with(&[(f, 0.3)]), fs, stated), None, "lone line");
        for (k, name) in [(2.0, "2x"), (3.0, "3x")] {
            let r = refine(&with(&[(f, 0.3), (k * f, 0.2)]), fs, stated)
                .unwrap_or_else(|| panic!("with its {name}: not refined"));
            assert!(
                (r.measured_hz - f).abs() < 0.1 * r.resolution_hz,
                "{name}: {r:?}"
            );
        }
        // A 2× masked by a stronger line 1.5 % above it (a 60 Hz line), the 3× standing.
        let masked = with(&[
            (f, 0.3),
            (2.0 * f, 0.05),
            (2.0 * f * 1.015, 0.4),
            (3.0 * f, 0.2),
        ]);
        assert!(refine(&masked, fs, stated).is_some());
    }

    /// The speed is the series', not the 1× line's: a machine whose shaft turns at
    /// 29.94 Hz (1×–5× standing) beside a stronger non-shaft line at 30.2 Hz, stated at
    /// 29.55 Hz (CWRU `OR007@12_1`'s case), is measured at the series to within 0.1 %,
    /// where the 1× alone read the other line (0.9 % off); all five lines are used.
    /// Unit white noise (seed `seed`) with sines `(Hz, amplitude)`, 20 s at `fs`.
    fn lines_in_noise(fs: f64, seed: u64, lines: &[(f64, f64)]) -> Vec<f64> {
        let n = (20.0 * fs) as usize;
        let mut x = gaussian_noise(n, 1.0, seed);
        for &(freq, amp) in lines {
            for (v, s) in x.iter_mut().zip(sine(n, fs, freq, amp, 0.7)) {
                *v += s;
            }
        }
        x
    }

    #[test]
    fn the_speed_is_fitted_to_the_shaft_series() {
        let fs = 12_000.0;
        let f = 29.94;
        let parts = [(f, 0.15), (2.0 * f, 0.2), (3.0 * f, 0.2), (4.0 * f, 0.15)];
        let x = lines_in_noise(
            fs,
            5,
            &[parts.as_slice(), &[(5.0 * f, 0.15), (30.2, 0.3)]].concat(),
        );
        let r = refine(&x, fs, 29.55).expect("refined");
        assert!((r.measured_hz / f - 1.0).abs() < 0.001, "{r:?}");
        assert_eq!(r.harmonics, SERIES_HARMONICS, "{r:?}");
    }

    #[test]
    fn a_stray_line_in_a_harmonic_window_is_dropped_from_the_fit() {
        // CWRU drive-end IR021_3's case: a line of other origin, stronger than the 4×, 2.5
        // bins below it inside the 4×'s ±1 % window.
        let fs = 12_000.0;
        let f = 28.79;
        let bin = 0.01 * f;
        let parts = [(f, 0.3), (2.0 * f, 0.2), (3.0 * f, 0.2), (4.0 * f, 0.08)];
        let stray = [(5.0 * f, 0.15), (4.0 * f - 2.5 * bin, 0.3)];
        let x = lines_in_noise(fs, 9, &[parts.as_slice(), &stray].concat());
        let r = refine(&x, fs, 28.0).expect("refined");
        assert_eq!(r.harmonics, SERIES_HARMONICS - 1, "{r:?}");
        assert!((r.measured_hz / f - 1.0).abs() < 0.0005, "{r:?}");
        // Kept, the stray would pull the fit by 4·2.5·bin/Σk² ≈ 0.18 % of the shaft.
        let mut all = [
            Some(f),
            Some(2.0 * f),
            Some(3.0 * f),
            Some(4.0 * f - 2.5 * bin),
            Some(5.0 * f),
        ];
        let (fitted, used) = series_fit(&mut all, bin).unwrap();
        assert_eq!((used, all[3]), (4, None));
        assert!((fitted / f - 1.0).abs() < 1e-12, "{fitted}");
    }

    #[test]
    fn lines_within_a_bin_are_all_kept_and_two_are_never_judged() {
        let bin = 0.3;
        // Every harmonic 0.8 bin off in turn: kept, the fit moves.
        for j in 0..SERIES_HARMONICS {
            let mut lines: [Option<f64>; SERIES_HARMONICS] = core::array::from_fn(|i| {
                Some((i + 1) as f64 * 30.0 + if i == j { 0.8 * bin } else { 0.0 })
            });
            let (f, used) = series_fit(&mut lines, bin).unwrap();
            assert_eq!(used, SERIES_HARMONICS);
            assert!(f > 30.0, "{f}");
        }
        // Two lines that disagree: neither is dropped.
        let mut two = [Some(30.0), None, Some(90.0 + 3.0 * bin), None, None];
        assert_eq!(series_fit(&mut two, bin).map(|r| r.1), Some(2));
        assert_eq!(series_fit(&mut [None; SERIES_HARMONICS], bin), None);
    }

    /// A record that states no speed: its shaft is found to well within the detector's
    /// slip window at any rate (the coarse line alone: up to 2.9 % off at 97.656 kHz),
    /// and a record without a line near the nominal speed gives none.
    #[test]
    fn a_shaft_is_found_without_a_stated_speed_at_any_rate() {
        for fs in [12_000.0, 25_600.0, 48_000.0, 97_656.0] {
            for f in [29.17, 24.61] {
                let parts = [(f, 0.3), (2.0 * f, 0.2), (3.0 * f, 0.1)];
                let x = lines_in_noise(fs, 3, &parts);
                let found = find(&x, fs, 29.95).expect("found");
                assert!((found / f - 1.0).abs() < 0.001, "{fs} Hz, {f} Hz: {found}");
            }
            assert_eq!(
                find(&lines_in_noise(fs, 4, &[]), fs, 29.95),
                None,
                "{fs} Hz"
            );
        }
    }
}
