//! Plots of `wearsim analyze`, each written as PNG and SVG with `plotters`:
//!
//! * `spectrum`: amplitude spectrum of the raw record, full band (with the demodulation band
//!   and the natural frequency) and a zoom on the fault-frequency zone, with the kinematic
//!   frequencies (1×, FTF, BPFO, BPFI, BSF families) marked and labelled;
//! * `envelope`: envelope spectrum in the chosen band with the same marks;
//! * `kurtogram`: fast-kurtogram heat map, level × frequency, chosen band outlined.
//!
//! Text uses DejaVu Sans embedded in the binary (crate `dejavu`, registered with plotters'
//! `ab_glyph` font backend), so rendering needs no system font and no fontconfig.

use crate::analysis::chain::Spectra;
use crate::analysis::FaultFrequencies;
use crate::analysis::{Kurtogram, Spectrum};
use crate::analyze::{family_name, Analysis};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::{Path, PathBuf};
use std::sync::Once;

/// Font family name under which DejaVu Sans is registered.
pub(crate) const FONT: &str = "sans-serif";
/// Plot size in pixels (PNG) and user units (SVG).
const SIZE: (u32, u32) = (1100, 700);
/// Most points drawn per curve (max-hold decimation keeps every peak visible).
const MAX_POINTS: usize = 1400;

static FONTS: Once = Once::new();

/// Register the embedded DejaVu Sans (regular and bold) as `sans-serif`, once per process.
pub fn register_fonts() {
    FONTS.call_once(|| {
        // Both are valid TrueType files shipped in the crate; an error would leave plotters
        // without a font and is reported by the first text draw.
        let _ = plotters::style::register_font(FONT, FontStyle::Normal, dejavu::sans::regular());
        let _ = plotters::style::register_font(FONT, FontStyle::Bold, dejavu::sans::bold());
    });
}

/// One kinematic mark: frequency (Hz), label, colour, label row.
struct Mark {
    hz: f64,
    label: String,
    color: RGBColor,
    row: usize,
}

const SHAFT_C: RGBColor = RGBColor(110, 110, 110);
const FTF_C: RGBColor = RGBColor(140, 60, 170);
const BPFO_C: RGBColor = RGBColor(20, 90, 200);
const BPFI_C: RGBColor = RGBColor(210, 40, 40);
const BALL_C: RGBColor = RGBColor(20, 150, 60);
const CURVE_C: RGBColor = RGBColor(30, 30, 30);
const NAT_C: RGBColor = RGBColor(200, 120, 0);

/// Kinematic marks up to `harmonics` orders: shaft 1×–3×, FTF, BPFO and BPFI harmonics,
/// BSF and the ball-defect family 2k×BSF.
fn marks(k: &FaultFrequencies, harmonics: usize) -> Vec<Mark> {
    let mut v = vec![];
    let name = |n: usize, s: &str| {
        if n == 1 {
            s.to_string()
        } else {
            format!("{n}×{s}")
        }
    };
    for n in 1..=3 {
        v.push(Mark {
            hz: n as f64 * k.shaft_hz,
            label: format!("{n}×"),
            color: SHAFT_C,
            row: 0,
        });
    }
    v.push(Mark {
        hz: k.ftf,
        label: "FTF".into(),
        color: FTF_C,
        row: 1,
    });
    for n in 1..=harmonics {
        v.push(Mark {
            hz: n as f64 * k.bpfo,
            label: name(n, "BPFO"),
            color: BPFO_C,
            row: 1,
        });
        v.push(Mark {
            hz: n as f64 * k.bpfi,
            label: name(n, "BPFI"),
            color: BPFI_C,
            row: 2,
        });
        v.push(Mark {
            hz: 2.0 * n as f64 * k.bsf,
            label: format!("{}×BSF", 2 * n),
            color: BALL_C,
            row: 3,
        });
    }
    v.push(Mark {
        hz: k.bsf,
        label: "BSF".into(),
        color: BALL_C,
        row: 3,
    });
    v
}

/// Points `(f, value)` of `s` in `[f0, f1]`, decimated by max-hold to at most `MAX_POINTS`,
/// values mapped by `map`.
pub(crate) fn points(s: &Spectrum, f0: f64, f1: f64, map: impl Fn(f64) -> f64) -> Vec<(f64, f64)> {
    if s.is_empty() || s.df <= 0.0 {
        return vec![];
    }
    let k0 = s.bin_of(f0);
    let k1 = s.bin_of(f1).max(k0);
    let n = k1 - k0 + 1;
    let step = n.div_ceil(MAX_POINTS).max(1);
    (k0..=k1)
        .step_by(step)
        .map(|k| {
            let end = (k + step).min(k1 + 1);
            let (kmax, vmax) = (k..end).fold((k, f64::NEG_INFINITY), |b, j| {
                if s.values[j] > b.1 {
                    (j, s.values[j])
                } else {
                    b
                }
            });
            (s.freq(kmax), map(vmax))
        })
        .collect()
}

/// Amplitude in dB re 1 signal unit (floored at -200 dB).
pub(crate) fn db(v: f64) -> f64 {
    20.0 * v.max(1e-10).log10()
}

/// Range `(lo, hi)` of the finite values, padded; a fallback for empty or flat data.
pub(crate) fn range(pts: &[(f64, f64)], pad_lo: f64, pad_hi: f64) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for &(_, y) in pts {
        if y.is_finite() {
            lo = lo.min(y);
            hi = hi.max(y);
        }
    }
    if !lo.is_finite() || !hi.is_finite() {
        return (0.0, 1.0);
    }
    if hi - lo < 1e-12 {
        return (lo - 1.0, hi + 1.0);
    }
    let span = hi - lo;
    (lo - pad_lo * span, hi + pad_hi * span)
}

pub(crate) type R = Result<(), String>;

/// Turn any drawing error into a message.
pub(crate) fn e<T, E: std::fmt::Display>(r: Result<T, E>) -> Result<T, String> {
    r.map_err(|err| err.to_string())
}

/// One spectrum panel: curve, optional shaded band, kinematic marks with labels in rows.
#[allow(clippy::too_many_arguments)]
fn panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    pts: &[(f64, f64)],
    x: (f64, f64),
    y: (f64, f64),
    y_desc: &str,
    marks: &[Mark],
    shade: Option<((f64, f64), String)>,
) -> R {
    let mut chart = e(ChartBuilder::on(area)
        .caption(title, (FONT, 17))
        .margin(8)
        .margin_right(20)
        .x_label_area_size(42)
        .y_label_area_size(70)
        .build_cartesian_2d(x.0..x.1, y.0..y.1))?;
    e(chart
        .configure_mesh()
        .x_desc("frequency (Hz)")
        .y_desc(y_desc)
        .label_style((FONT, 13))
        .axis_desc_style((FONT, 14))
        .light_line_style(WHITE.mix(0.0))
        .bold_line_style(BLACK.mix(0.08))
        .draw())?;
    if let Some(((lo, hi), label)) = shade {
        let (lo, hi) = (lo.max(x.0), hi.min(x.1));
        if lo < hi {
            e(chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(lo, y.0), (hi, y.1)],
                    RGBColor(255, 170, 0).mix(0.18).filled(),
                )))
                .map(|s| {
                    s.label(label).legend(|(a, b)| {
                        Rectangle::new(
                            [(a, b - 5), (a + 18, b + 5)],
                            RGBColor(255, 170, 0).mix(0.4).filled(),
                        )
                    })
                }))?;
        }
    }
    let span = y.1 - y.0;
    let mut seen_colors: Vec<RGBColor> = vec![];
    for m in marks.iter().filter(|m| m.hz > x.0 && m.hz < x.1) {
        let c = m.color;
        e(chart.draw_series(std::iter::once(PathElement::new(
            vec![(m.hz, y.0), (m.hz, y.1 - 0.03 * span)],
            c.mix(0.45).stroke_width(1),
        ))))?;
        let ly = y.1 - (0.035 + 0.045 * m.row as f64) * span;
        let style = TextStyle::from((FONT, 12).into_font())
            .color(&c)
            .pos(Pos::new(HPos::Center, VPos::Center));
        e(chart.draw_series(std::iter::once(Text::new(
            m.label.clone(),
            (m.hz, ly),
            style,
        ))))?;
        if !seen_colors.contains(&c) {
            seen_colors.push(c);
            let legend = match c {
                SHAFT_C => "shaft 1×, 2×, 3×",
                FTF_C => "cage FTF",
                BPFO_C => "outer race BPFO ×k",
                BPFI_C => "inner race BPFI ×k",
                NAT_C => "natural frequency of the preset",
                _ => "ball BSF, 2k×BSF",
            };
            e(chart
                .draw_series(std::iter::empty::<PathElement<(f64, f64)>>())
                .map(|s| {
                    s.label(legend).legend(move |(a, b)| {
                        PathElement::new(vec![(a, b), (a + 18, b)], c.stroke_width(2))
                    })
                }))?;
        }
    }
    e(chart.draw_series(LineSeries::new(
        pts.iter().copied(),
        CURVE_C.stroke_width(1),
    )))?;
    e(chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .margin(10)
        .label_font((FONT, 12))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .draw())?;
    Ok(())
}

/// Highest frequency of the fault-zone views: just above the highest searched harmonic.
fn zoom_hz(a: &Analysis) -> f64 {
    let k = &a.kinematics;
    let h = a.method.detect.harmonics.max(1) as f64;
    ((h + 0.6) * k.bpfi.max(2.0 * k.bsf)).min(a.fs / 2.0)
}

/// Title line shared by the plots.
fn heading(a: &Analysis) -> String {
    format!(
        "{} [{}], {:.0} rpm, {}: diagnosis {}",
        crate::analyze::short_name(&a.file),
        a.channel,
        a.rpm,
        a.bearing,
        family_name(a.diagnosis.family)
    )
}

/// Spectrum figure: full band (dB) above, fault-frequency zoom (dB) below.
fn draw_spectrum<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, a: &Analysis, s: &Spectra) -> R {
    e(root.fill(&WHITE))?;
    let (top, bottom) = root.split_vertically(SIZE.1 / 2);
    let nyq = a.fs / 2.0;
    let full = points(&s.spectrum, 0.0, nyq, db);
    let y = range(&full, 0.05, 0.35);
    let mut m = marks(&a.kinematics, a.method.detect.harmonics);
    m.retain(|m| m.row == usize::MAX); // full band: only the natural frequency below
    m.push(Mark {
        hz: a.kinematics.natural_hz,
        label: "natural".into(),
        color: NAT_C,
        row: 0,
    });
    let unit = &a.unit;
    panel(
        &top,
        &format!("Amplitude spectrum, {}", heading(a)),
        &full,
        (0.0, nyq),
        y,
        &format!("amplitude (dB re 1 {unit})"),
        &m,
        Some((a.kurtogram.band_hz, "demodulation band".into())),
    )?;
    let z = zoom_hz(a);
    let zoom = points(&s.spectrum, 0.0, z, db);
    let y = range(&zoom, 0.05, 0.45);
    panel(
        &bottom,
        "Fault-frequency zone (kinematic frequencies at the record's speed)",
        &zoom,
        (0.0, z),
        y,
        &format!("amplitude (dB re 1 {unit})"),
        &marks(&a.kinematics, a.method.detect.harmonics),
        None,
    )?;
    e(root.present())
}

/// Envelope-spectrum figure (linear amplitude).
fn draw_envelope<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, a: &Analysis, s: &Spectra) -> R {
    e(root.fill(&WHITE))?;
    let z = zoom_hz(a);
    let pts = points(&s.envelope, 0.0, z, |v| v);
    let (_, hi) = range(&pts, 0.0, 0.0);
    let y = (0.0, hi.max(1e-300) * 1.3);
    let unit = if a.method.prewhiten {
        "envelope amplitude (pre-whitened, unit-less)".to_string()
    } else {
        format!("envelope amplitude ({})", a.unit)
    };
    let (lo_b, hi_b) = a.kurtogram.band_hz;
    panel(
        &root,
        &format!(
            "Envelope spectrum, band {lo_b:.0}-{hi_b:.0} Hz; {}",
            heading(a)
        ),
        &pts,
        (0.0, z),
        y,
        &unit,
        &marks(&a.kinematics, a.method.detect.harmonics),
        None,
    )?;
    e(root.present())
}

/// Colour of `t` in [0, 1] on a viridis-like map.
fn colormap(t: f64) -> RGBColor {
    const STOPS: [(f64, f64, f64); 5] = [
        (68.0, 1.0, 84.0),
        (59.0, 82.0, 139.0),
        (33.0, 145.0, 140.0),
        (94.0, 201.0, 98.0),
        (253.0, 231.0, 37.0),
    ];
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let x = t * (STOPS.len() - 1) as f64;
    let i = (x.floor() as usize).min(STOPS.len() - 2);
    let f = x - i as f64;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    let mix = |p: f64, q: f64| (p + (q - p) * f).round().clamp(0.0, 255.0) as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// Kurtogram figure: rows = levels (level 0 on top), columns = frequency bands.
fn draw_kurtogram<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    a: &Analysis,
    kg: &Kurtogram,
) -> R {
    e(root.fill(&WHITE))?;
    let (main, bar) = root.split_horizontally(SIZE.0 - 130);
    let rows = kg.grid.len().max(1);
    let nyq = kg.fs / 2.0;
    // Colours on log10(1 + kurtosis): near-empty bands (e.g. an anti-alias roll-off) can
    // reach kurtoses of hundreds and would otherwise flatten the rest of the map.
    let lk = |k: f64| (1.0 + k.max(0.0)).log10();
    let kmax = kg
        .grid
        .iter()
        .flatten()
        .copied()
        .filter(|v| v.is_finite())
        .map(lk)
        .fold(0.0_f64, f64::max)
        .max(1e-9);
    let mut chart = e(ChartBuilder::on(&main)
        .caption(
            format!("Fast kurtogram (Antoni 2007), {}", heading(a)),
            (FONT, 17),
        )
        .margin(8)
        .x_label_area_size(42)
        .y_label_area_size(70)
        .build_cartesian_2d(0.0..nyq, 0.0..rows as f64))?;
    e(chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("frequency (Hz)")
        .y_desc("level (log2 of the number of bands)")
        .y_labels(0)
        .label_style((FONT, 13))
        .axis_desc_style((FONT, 14))
        .draw())?;
    for (r, row) in kg.grid.iter().enumerate() {
        let y1 = (rows - r) as f64;
        let w = kg
            .row_width_hz
            .get(r)
            .copied()
            .unwrap_or(nyq / row.len().max(1) as f64);
        e(chart.draw_series(row.iter().enumerate().map(|(i, &k)| {
            Rectangle::new(
                [(i as f64 * w, y1 - 1.0), ((i + 1) as f64 * w, y1)],
                colormap(lk(k) / kmax).filled(),
            )
        })))?;
        let level = kg.level_values.get(r).copied().unwrap_or(0.0);
        let (px, py) = chart.backend_coord(&(0.0, y1 - 0.5));
        e(main.draw_text(
            &format!("{level:.1}"),
            &TextStyle::from((FONT, 13).into_font()).pos(Pos::new(HPos::Right, VPos::Center)),
            (px - 8, py),
        ))?;
    }
    // Outline the chosen band in its row.
    let (lo, hi) = a.kurtogram.band_hz;
    if let Some(r) = kg
        .level_values
        .iter()
        .position(|l| (l - a.kurtogram.level).abs() < 1e-9)
    {
        let y1 = (rows - r) as f64;
        e(chart.draw_series(std::iter::once(Rectangle::new(
            [(lo, y1 - 1.0), (hi, y1)],
            RED.stroke_width(3),
        ))))?;
        let style = TextStyle::from((FONT, 14, FontStyle::Bold).into_font())
            .color(&WHITE)
            .pos(Pos::new(HPos::Center, VPos::Top));
        let label = format!(
            "chosen {lo:.0}-{hi:.0} Hz, kurtosis {:.1}",
            a.kurtogram.kurtosis
        );
        let (px, py) = chart.backend_coord(&((lo + hi) / 2.0, y1 - 1.0));
        e(main.draw_text(&label, &style, (px, py + 4)))?;
    }
    // Colour bar.
    let mut cb = e(ChartBuilder::on(&bar)
        .margin_top(40)
        .margin_bottom(50)
        .margin_right(10)
        .y_label_area_size(55)
        .build_cartesian_2d(0.0..1.0, 0.0..kmax))?;
    let fmt = |v: &f64| format!("{:.1}", 10f64.powf(*v) - 1.0);
    e(cb.configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_label_formatter(&fmt)
        .y_desc("kurtosis of the band envelope (log scale)")
        .label_style((FONT, 12))
        .axis_desc_style((FONT, 13))
        .draw())?;
    let steps = 100;
    e(cb.draw_series((0..steps).map(|i| {
        let (a0, a1) = (i as f64 / steps as f64, (i + 1) as f64 / steps as f64);
        Rectangle::new([(0.0, a0 * kmax), (1.0, a1 * kmax)], colormap(a0).filled())
    })))?;
    e(root.present())
}

/// Why figures could not be written.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// The output folder cannot be created (bad input: the path the user gave).
    #[error("{}: cannot create the plot folder: {source}", dir.display())]
    Folder {
        /// The folder.
        dir: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A figure could not be drawn or written (the run failed).
    #[error("{}: {message}", file.display())]
    Draw {
        /// The figure's file.
        file: PathBuf,
        /// What plotters reported.
        message: String,
    },
}

/// Creates the output folder `dir` (and its parents) if missing.
pub fn create_folder(dir: &Path) -> Result<(), PlotError> {
    std::fs::create_dir_all(dir).map_err(|source| PlotError::Folder {
        dir: dir.to_path_buf(),
        source,
    })
}

/// Render one figure to `<dir>/<name>.png` and `.svg`.
pub(crate) fn render(
    dir: &Path,
    name: &str,
    draw_png: impl FnOnce(DrawingArea<BitMapBackend, Shift>) -> R,
    draw_svg: impl FnOnce(DrawingArea<SVGBackend, Shift>) -> R,
) -> Result<Vec<PathBuf>, PlotError> {
    let png = dir.join(format!("{name}.png"));
    let svg = dir.join(format!("{name}.svg"));
    draw_png(BitMapBackend::new(&png, SIZE).into_drawing_area()).map_err(|message| {
        PlotError::Draw {
            file: png.clone(),
            message,
        }
    })?;
    draw_svg(SVGBackend::new(&svg, SIZE).into_drawing_area()).map_err(|message| {
        PlotError::Draw {
            file: svg.clone(),
            message,
        }
    })?;
    Ok(vec![png, svg])
}

/// Write `spectrum`, `envelope` and `kurtogram` as PNG and SVG into `dir` (created if
/// missing); returns the files written. A directory that cannot be created is bad input
/// (exit 2), a drawing failure a run failure (exit 1).
pub fn write_all(dir: &Path, a: &Analysis, s: &Spectra) -> Result<Vec<PathBuf>, PlotError> {
    create_folder(dir)?;
    register_fonts();
    let mut out = vec![];
    out.extend(render(
        dir,
        "spectrum",
        |r| draw_spectrum(r, a, s),
        |r| draw_spectrum(r, a, s),
    )?);
    out.extend(render(
        dir,
        "envelope",
        |r| draw_envelope(r, a, s),
        |r| draw_envelope(r, a, s),
    )?);
    out.extend(render(
        dir,
        "kurtogram",
        |r| draw_kurtogram(r, a, &s.kurtogram),
        |r| draw_kurtogram(r, a, &s.kurtogram),
    )?);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colormap_ends_and_clamps() {
        assert_eq!(colormap(0.0), RGBColor(68, 1, 84));
        assert_eq!(colormap(1.0), RGBColor(253, 231, 37));
        assert_eq!(colormap(7.0), colormap(1.0));
        assert_eq!(colormap(f64::NAN), colormap(0.0));
    }

    #[test]
    fn max_hold_keeps_the_peak() {
        let mut values = vec![0.0; 100_000];
        values[54_321] = 5.0;
        let s = Spectrum {
            df: 0.1,
            values,
            kind: crate::analysis::SpectrumKind::Amplitude,
        };
        let p = points(&s, 0.0, 10_000.0, |v| v);
        assert!(p.len() <= MAX_POINTS + 1);
        let top = p
            .iter()
            .fold((0.0, 0.0), |b, q| if q.1 > b.1 { *q } else { b });
        assert_eq!(top, (5432.1, 5.0));
    }
}
