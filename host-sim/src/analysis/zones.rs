//! Band levels in the four frequency zones of bearing-wear monitoring
//! (El-Thalji 2016, "Dynamic modelling and vibration analysis of rolling
//! element bearing wear", thesis, Linnaeus University): rotating, fault,
//! natural (resonance) and high frequency.

use super::error::{bad, check_fs, AnalysisError};
use super::faults::FaultFrequencies;
use super::spectrum::Spectrum;
use serde::Serialize;

/// Frequency bands `(lo, hi)` in Hz of the four zones. Zones may overlap
/// (e.g. the fault zone starts below 5× shaft): each level is an independent
/// band RMS, not a partition of the total.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ZoneBands {
    /// Rotating-frequency zone: `[0.5, 5] × shaft`, Hz.
    pub rotating: (f64, f64),
    /// Fault-frequency zone: from half the lowest to 5× the highest of
    /// BPFO, BPFI and 2×BSF (the first five harmonics of every family), Hz.
    pub fault: (f64, f64),
    /// Natural-frequency zone: resonance ± 30 %, Hz.
    pub natural: (f64, f64),
    /// High-frequency zone: from 1.3 × resonance to fs/2, Hz.
    pub high: (f64, f64),
}

/// RMS levels (signal units) in each zone, from a PSD.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ZoneLevels {
    /// RMS in the rotating zone, signal units.
    pub rotating: f64,
    /// RMS in the fault-frequency zone, signal units.
    pub fault: f64,
    /// RMS in the natural-frequency zone, signal units.
    pub natural: f64,
    /// RMS in the high-frequency zone, signal units.
    pub high: f64,
    /// RMS over the whole spectrum (the standard deviation), signal units.
    pub total: f64,
}

impl ZoneBands {
    /// Zones for a bearing with characteristic frequencies `ff` (the shaft
    /// frequency is `ff.shaft_hz`, the structural resonance `ff.natural_hz`)
    /// and sampling frequency `fs`, all in Hz. Upper edges are clipped to
    /// fs/2. Errors: a non-positive or non-finite frequency, or a zone that
    /// is empty after clipping (e.g. resonance too close to fs/2).
    pub fn new(ff: &FaultFrequencies, fs: f64) -> Result<Self, AnalysisError> {
        Self::build(ff, fs, false)
    }

    /// [`ZoneBands::new`], except that a zone lying wholly at or above fs/2 (a resonance
    /// beyond the record's band, e.g. a structure stiffened by a heavy load) is kept as the
    /// empty band `(lo, lo)`: it holds no bin of a spectrum of this rate, so its level
    /// ([`band_rms`]) is 0 — nothing of it is in the record. For series of windows (a life's
    /// snapshots) that must report every zone; the other errors are those of `new`.
    pub fn new_clipped(ff: &FaultFrequencies, fs: f64) -> Result<Self, AnalysisError> {
        Self::build(ff, fs, true)
    }

    fn build(ff: &FaultFrequencies, fs: f64, allow_empty: bool) -> Result<Self, AnalysisError> {
        check_fs(fs)?;
        let positive = [
            ("shaft_hz", ff.shaft_hz),
            ("bpfo", ff.bpfo),
            ("bpfi", ff.bpfi),
            ("bsf", ff.bsf),
            ("natural_hz", ff.natural_hz),
        ];
        for (name, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(bad(name, "finite and > 0", v));
            }
        }
        let nyquist = fs / 2.0;
        let family = [ff.bpfo, ff.bpfi, 2.0 * ff.bsf];
        let fmin = family.iter().copied().fold(f64::INFINITY, f64::min);
        let fmax = family.iter().copied().fold(0.0, f64::max);
        let clip = |lo: f64, hi: f64| -> Result<(f64, f64), AnalysisError> {
            let hi = hi.min(nyquist);
            if lo < hi {
                Ok((lo, hi))
            } else if allow_empty && lo >= nyquist {
                Ok((lo, lo))
            } else {
                Err(AnalysisError::BadBand {
                    lo,
                    hi,
                    nyquist,
                    extra: " (zone empty below fs/2)".to_string(),
                })
            }
        };
        Ok(ZoneBands {
            rotating: clip(0.5 * ff.shaft_hz, 5.0 * ff.shaft_hz)?,
            fault: clip(0.5 * fmin, 5.0 * fmax)?,
            natural: clip(0.7 * ff.natural_hz, 1.3 * ff.natural_hz)?,
            high: clip(1.3 * ff.natural_hz, nyquist)?,
        })
    }

    /// The zones cut at `top` (Hz): a record that holds nothing above `top`
    /// ([`super::content_band::content_edge`]) informs no level above it. The natural or
    /// high zone starting at or above `top` becomes the empty band `(top, top)` (nothing of
    /// it is recorded, as with [`ZoneBands::new_clipped`] at fs/2); the rotating or fault
    /// zone doing so is an error naming it (the record holds nothing of the bearing's
    /// lines). A zone already empty stays empty.
    pub fn below(self, top: f64) -> Result<Self, AnalysisError> {
        let cut = |name: &'static str, (lo, hi): (f64, f64)| -> Result<(f64, f64), AnalysisError> {
            if lo >= hi {
                Ok((lo, lo))
            } else if lo < top {
                Ok((lo, hi.min(top)))
            } else if matches!(name, "natural zone" | "high zone") {
                Ok((top, top))
            } else {
                Err(AnalysisError::BadParameter {
                    name,
                    allowed: format!(
                        "a zone starting below {top:.0} Hz, the edge of what the record holds (it has no content above)"
                    ),
                    value: format!("({lo:.0}, {hi:.0}) Hz"),
                })
            }
        };
        Ok(ZoneBands {
            rotating: cut("rotating zone", self.rotating)?,
            fault: cut("fault zone", self.fault)?,
            natural: cut("natural zone", self.natural)?,
            high: cut("high zone", self.high)?,
        })
    }
}

/// RMS in `band` (Hz, edges inclusive) from a one-sided PSD:
/// `sqrt(Σ PSD_k · df)` over the bins whose centre lies in the band.
pub fn band_rms(psd: &Spectrum, band: (f64, f64)) -> f64 {
    // Only the bins near the band are tested (the nearest bin to each edge, widened by one),
    // with the same test and in the same order as a scan of the whole spectrum: the same
    // sum, without visiting every bin for every band.
    let lo = psd.bin_of(band.0).saturating_sub(1);
    let hi = psd.bin_of(band.1).saturating_add(1).min(psd.values.len());
    let near = psd.values.get(lo..hi).unwrap_or(&[]);
    let power: f64 = near
        .iter()
        .enumerate()
        .filter(|(j, _)| {
            let f = psd.freq(lo + *j);
            f >= band.0 && f <= band.1
        })
        .map(|(_, v)| v * psd.df)
        .sum();
    power.max(0.0).sqrt()
}

/// Zone levels (RMS, signal units) of `psd`, a one-sided PSD such as
/// [`super::welch_psd`] returns (other spectrum kinds give meaningless levels).
pub fn zone_levels(psd: &Spectrum, z: &ZoneBands) -> ZoneLevels {
    ZoneLevels {
        rotating: band_rms(psd, z.rotating),
        fault: band_rms(psd, z.fault),
        natural: band_rms(psd, z.natural),
        high: band_rms(psd, z.high),
        total: band_rms(psd, (0.0, f64::INFINITY)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::spectrum::{welch_psd, WelchParams};
    use crate::analysis::synth::sine;

    /// The windowed sum equals the scan of every bin, bit for bit, for bands whose edges
    /// fall on, between and beyond the bins (including empty, reversed and unbounded ones).
    #[test]
    fn band_rms_equals_the_scan_of_every_bin() {
        let psd = Spectrum {
            values: (0..1000)
                .map(|k| 1.0 + ((k * 7919) % 97) as f64 / 13.0)
                .collect(),
            df: 2.5,
            kind: crate::analysis::spectrum::SpectrumKind::Psd,
        };
        let scan = |band: (f64, f64)| -> f64 {
            let power: f64 = psd
                .values
                .iter()
                .enumerate()
                .filter(|(k, _)| {
                    let f = psd.freq(*k);
                    f >= band.0 && f <= band.1
                })
                .map(|(_, v)| v * psd.df)
                .sum();
            power.max(0.0).sqrt()
        };
        let edges = [
            0.0, 1.0, 2.5, 3.74, 3.75, 3.76, 100.0, 101.25, 999.0, 2497.5, 2500.0, 3000.0,
        ];
        for &a in &edges {
            for &b in &edges {
                assert_eq!(
                    band_rms(&psd, (a, b)).to_bits(),
                    scan((a, b)).to_bits(),
                    "{a}..{b}"
                );
            }
        }
        let whole = (0.0, f64::INFINITY);
        assert_eq!(band_rms(&psd, whole).to_bits(), scan(whole).to_bits());
        assert_eq!(
            band_rms(&psd, (f64::NAN, 10.0)).to_bits(),
            scan((f64::NAN, 10.0)).to_bits()
        );
    }

    fn ff() -> FaultFrequencies {
        FaultFrequencies {
            shaft_hz: 30.0,
            ftf: 12.0,
            bpfo: 107.0,
            bpfi: 162.0,
            bsf: 70.0,
            natural_hz: 3000.0,
        }
    }

    fn with_natural(natural_hz: f64) -> FaultFrequencies {
        FaultFrequencies { natural_hz, ..ff() }
    }

    /// A record whose content ends at `top` (a low-passed or resampled record): the zones
    /// are cut there, the natural and high zones beyond it become empty at `top`, and the
    /// fault zone beyond it is an error naming it.
    #[test]
    fn zones_below_a_content_edge() {
        let z = ZoneBands::new(&ff(), 12_000.0).unwrap();
        let b = z.below(1600.0).unwrap();
        assert_eq!((b.rotating, b.fault), (z.rotating, z.fault));
        assert_eq!((b.natural, b.high), ((1600.0, 1600.0), (1600.0, 1600.0)));
        let b = z.below(3000.0).unwrap();
        assert_eq!((b.natural, b.high), ((2100.0, 3000.0), (3000.0, 3000.0)));
        let e = z.below(40.0).unwrap_err().to_string();
        assert!(e.contains("fault zone"), "{e}");
        // Already empty (beyond fs/2): stays empty.
        let c = ZoneBands::new_clipped(&with_natural(10_000.0), 12_000.0).unwrap();
        assert_eq!(c.below(5000.0).unwrap().high, (13_000.0, 13_000.0));
    }

    #[test]
    fn bands_follow_the_definitions() {
        let z = ZoneBands::new(&ff(), 12_000.0).unwrap();
        assert_eq!(z.rotating, (15.0, 150.0));
        assert_eq!(z.fault, (53.5, 810.0));
        assert!((z.natural.0 - 2100.0).abs() < 1e-9 && (z.natural.1 - 3900.0).abs() < 1e-9);
        assert_eq!(z.high, (3900.0, 6000.0));
        assert!(ZoneBands::new(&with_natural(5000.0), 12_000.0).is_err());
        // Clipped: a resonance whose zones lie beyond fs/2 leaves them empty, level 0;
        // the zones below keep their bands.
        let c = ZoneBands::new_clipped(&with_natural(10_000.0), 12_000.0).unwrap();
        assert_eq!(
            (c.natural, c.high),
            ((7000.0, 7000.0), (13_000.0, 13_000.0))
        );
        assert_eq!(c.fault, ZoneBands::new(&ff(), 12_000.0).unwrap().fault);
        let x = crate::analysis::synth::gaussian_noise(12_000, 1.0, 3);
        let psd = crate::analysis::welch_psd(&x, 12_000.0, &Default::default()).unwrap();
        let l = zone_levels(&psd, &c);
        assert_eq!((l.natural, l.high), (0.0, 0.0));
        assert!(l.fault > 0.0);
        // A zone that straddles fs/2 is cut there, as by `new`.
        let c = ZoneBands::new_clipped(&with_natural(5000.0), 12_000.0).unwrap();
        assert_eq!((c.natural, c.high), ((3500.0, 6000.0), (6500.0, 6500.0)));
        assert!(ZoneBands::new(&with_natural(0.0), 12_000.0).is_err());
        assert!(ZoneBands::new(&ff(), -1.0).is_err());
        let mut bad = ff();
        bad.bpfi = f64::NAN;
        assert!(ZoneBands::new(&bad, 12_000.0).is_err());
    }

    #[test]
    fn levels_of_one_tone_per_zone() {
        let fs = 12_000.0;
        let n = 120_000;
        // 20 Hz: rotating only; 400 Hz: fault only; 3 kHz: natural; 5 kHz: high.
        let tones = [(20.0, 1.0), (400.0, 2.0), (3000.0, 0.5), (5000.0, 0.25)];
        let mut x = vec![0.0; n];
        for (f, a) in tones {
            for (xi, s) in x.iter_mut().zip(sine(n, fs, f, a, 0.3)) {
                *xi += s;
            }
        }
        let psd = welch_psd(&x, fs, &WelchParams::default()).unwrap();
        let l = zone_levels(&psd, &ZoneBands::new(&ff(), fs).unwrap());
        let rms = |a: f64| a / 2f64.sqrt();
        let close = |got: f64, want: f64| (got / want - 1.0).abs() < 0.01;
        assert!(close(l.rotating, rms(1.0)), "{l:?}");
        assert!(close(l.fault, rms(2.0)), "{l:?}");
        assert!(close(l.natural, rms(0.5)), "{l:?}");
        assert!(close(l.high, rms(0.25)), "{l:?}");
        let total = tones.iter().map(|(_, a)| a * a / 2.0).sum::<f64>().sqrt();
        assert!(close(l.total, total), "{l:?}");
    }
}
