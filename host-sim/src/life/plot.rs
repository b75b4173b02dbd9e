//! Plots of a life run (PNG and SVG, text in the embedded DejaVu Sans of
//! [`crate::plot`]): normalised RMS over life with the stages shaded (thesis Fig. 5–6),
//! one figure per sampled event with time response, spectrum and envelope spectrum
//! (publication IV Figs. 9–16), and the overlay of simulated and measured life.

use super::ims_compare::ImsComparison;
use super::output::Span;
use super::{EventWindow, Snapshot};
use crate::analysis::stats::upper_median;
use crate::analysis::{self, Window};
use crate::plot::{
    create_folder, db, e, points, range, register_fonts, render, PlotError, FONT, R,
};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

const STAGE_COLORS: [RGBColor; 10] = [
    RGBColor(235, 235, 235),
    RGBColor(220, 238, 220),
    RGBColor(255, 228, 196),
    RGBColor(255, 245, 200),
    RGBColor(250, 210, 210),
    RGBColor(240, 200, 230),
    RGBColor(200, 215, 245),
    RGBColor(210, 240, 250),
    RGBColor(230, 210, 250),
    RGBColor(200, 200, 200),
];

fn stage_color(name: &str) -> RGBColor {
    let i = wearsim_core::wear::Stage::ALL
        .iter()
        .position(|s| s.name() == name)
        .unwrap_or(0);
    STAGE_COLORS[i % STAGE_COLORS.len()]
}

fn log_range(v: impl Iterator<Item = f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for x in v.filter(|x| x.is_finite() && *x > 0.0) {
        lo = lo.min(x);
        hi = hi.max(x);
    }
    if !lo.is_finite() || hi <= 0.0 {
        return (0.1, 10.0);
    }
    (lo / 1.5, hi * 1.5)
}

/// Axes of a normalised-RMS-over-life chart: life fraction 0–1 against a log ratio.
fn life_axes<'a, DB: DrawingBackend>(
    root: &'a DrawingArea<DB, Shift>,
    title: &str,
    (lo, hi): (f64, f64),
    x_desc: &str,
    y_desc: &str,
) -> Result<
    ChartContext<
        'a,
        DB,
        Cartesian2d<
            plotters::coord::types::RangedCoordf64,
            plotters::coord::combinators::LogCoord<f64>,
        >,
    >,
    String,
> {
    let mut chart = e(ChartBuilder::on(root)
        .caption(title, (FONT, 18))
        .margin(10)
        .margin_right(20)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(0f64..1f64, (lo..hi).log_scale()))?;
    e(chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .label_style((FONT, 13))
        .axis_desc_style((FONT, 14))
        .light_line_style(WHITE.mix(0.0))
        .draw())?;
    Ok(chart)
}

fn draw_life<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    snaps: &[Snapshot],
    spans: &[Span],
    end: f64,
    title: &str,
) -> R {
    e(root.fill(&WHITE))?;
    let base = {
        let v: Vec<f64> = snaps
            .iter()
            .filter(|s| s.stage == "steady-state")
            .map(|s| s.features.rms)
            .collect();
        upper_median(v).unwrap_or(1.0).max(1e-300)
    };
    let pts: Vec<(f64, f64)> = snaps
        .iter()
        .map(|s| (s.cycles / end, s.features.rms / base))
        .collect();
    let (lo, hi) = log_range(pts.iter().map(|p| p.1));
    let mut chart = life_axes(
        &root,
        title,
        (lo, hi),
        "fraction of life (revolutions / revolutions to failure)",
        "RMS / steady-state RMS",
    )?;
    for (i, s) in spans.iter().enumerate() {
        let (a, b) = (s.start / end, (s.end / end).max(s.start / end + 0.002));
        e(chart.draw_series(std::iter::once(Rectangle::new(
            [(a, lo), (b, hi)],
            stage_color(&s.stage).filled(),
        ))))?;
        let y = hi / 1.2 / (1.0 + 0.35 * (i % 4) as f64);
        e(chart.draw_series(std::iter::once(Text::new(
            s.stage.clone(),
            (a + 0.003, y),
            (FONT, 12).into_font(),
        ))))?;
    }
    e(chart.draw_series(LineSeries::new(pts.clone(), BLACK.stroke_width(2))))?;
    e(chart.draw_series(pts.iter().map(|p| Circle::new(*p, 2, BLACK.filled()))))?;
    e(root.present())
}

/// `life-rms.png/svg`.
pub fn life_rms(
    dir: &Path,
    snaps: &[Snapshot],
    spans: &[Span],
    end: f64,
    title: &str,
) -> Result<Vec<PathBuf>, PlotError> {
    register_fonts();
    render(
        dir,
        "life-rms",
        |r| draw_life(r, snaps, spans, end, title),
        |r| draw_life(r, snaps, spans, end, title),
    )
}

fn draw_event<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    w: &EventWindow,
    fs: f64,
    bpfo: f64,
    fnat: f64,
    label: &str,
) -> R {
    e(root.fill(&WHITE))?;
    let areas = root.split_evenly((3, 1));
    let title = format!("{label}: {} at {:.0} revolutions", w.stage.name(), w.cycles);
    // Time response (first 0.1 s).
    let n = ((0.1 * fs) as usize).min(w.samples.len());
    let tp: Vec<(f64, f64)> = w.samples[..n]
        .iter()
        .enumerate()
        .map(|(i, x)| (i as f64 / fs * 1e3, *x))
        .collect();
    let (ylo, yhi) = range(&tp, 0.05, 0.05);
    let mut c = e(ChartBuilder::on(&areas[0])
        .caption(title, (FONT, 16))
        .margin(6)
        .x_label_area_size(35)
        .y_label_area_size(70)
        .build_cartesian_2d(0f64..(n as f64 / fs * 1e3).max(1.0), ylo..yhi))?;
    e(c.configure_mesh()
        .x_desc("time (ms)")
        .y_desc("accel. (m/s²)")
        .label_style((FONT, 12))
        .axis_desc_style((FONT, 13))
        .draw())?;
    e(c.draw_series(LineSeries::new(tp, BLUE.stroke_width(1))))?;
    // Spectrum (dB re 1 m/s²) up to 0.4 fs with BPFO harmonics and the natural frequency.
    let spec = e(analysis::amplitude_spectrum(&w.samples, fs, Window::Hann))?;
    let sp = points(&spec, 0.0, 0.4 * fs, db);
    let (slo, shi) = range(&sp, 0.05, 0.1);
    let mut c = e(ChartBuilder::on(&areas[1])
        .margin(6)
        .x_label_area_size(35)
        .y_label_area_size(70)
        .build_cartesian_2d(0f64..0.4 * fs, slo..shi))?;
    e(c.configure_mesh()
        .x_desc("frequency (Hz)")
        .y_desc("spectrum (dB re 1 m/s²)")
        .label_style((FONT, 12))
        .axis_desc_style((FONT, 13))
        .draw())?;
    e(c.draw_series(std::iter::once(PathElement::new(
        vec![(fnat, slo), (fnat, shi)],
        RGBColor(200, 120, 0).stroke_width(2),
    ))))?;
    e(c.draw_series(std::iter::once(Text::new(
        "natural",
        (fnat, shi - 0.08 * (shi - slo)),
        (FONT, 12).into_font(),
    ))))?;
    e(c.draw_series(LineSeries::new(sp, BLACK.stroke_width(1))))?;
    // Envelope spectrum up to 6 × BPFO.
    let env = e(analysis::envelope_spectrum(&w.samples, fs, None))?;
    let fmax = (6.5 * bpfo).min(0.4 * fs);
    let ep = points(&env, 0.0, fmax, |v| v);
    let (_, ehi) = range(&ep, 0.0, 0.15);
    let mut c = e(ChartBuilder::on(&areas[2])
        .margin(6)
        .x_label_area_size(35)
        .y_label_area_size(70)
        .build_cartesian_2d(0f64..fmax, 0f64..ehi.max(1e-12)))?;
    e(c.configure_mesh()
        .x_desc("frequency (Hz)")
        .y_desc("envelope (m/s²)")
        .label_style((FONT, 12))
        .axis_desc_style((FONT, 13))
        .draw())?;
    for k in 1..=6 {
        let f = k as f64 * bpfo;
        e(c.draw_series(std::iter::once(PathElement::new(
            vec![(f, 0.0), (f, ehi)],
            RGBColor(20, 90, 200).mix(0.4),
        ))))?;
        let lab = if k == 1 {
            "BPFO".to_string()
        } else {
            format!("{k}×")
        };
        e(c.draw_series(std::iter::once(Text::new(
            lab,
            (f, ehi * 0.93),
            (FONT, 11).into_font(),
        ))))?;
    }
    e(c.draw_series(LineSeries::new(ep, BLACK.stroke_width(1))))?;
    e(root.present())
}

/// `event-<n>-<stage>.png/svg` for each sampled event (publication IV numbering).
pub fn events(
    dir: &Path,
    windows: &[EventWindow],
    fs: f64,
    bpfo: f64,
    fnat: f64,
) -> Result<Vec<PathBuf>, PlotError> {
    register_fonts();
    let mut out = vec![];
    for w in windows {
        let Some(n) = w.stage.publication_event() else {
            continue;
        };
        let name = format!("event-{n}-{}", w.stage.name());
        let label = format!("event {n}");
        out.extend(render(
            dir,
            &name,
            |r| draw_event(r, w, fs, bpfo, fnat, &label),
            |r| draw_event(r, w, fs, bpfo, fnat, &label),
        )?);
    }
    remove_stale_events(dir, &out);
    Ok(out)
}

/// Removes the event plots (`event-<n>-<stage>.png/svg`, names only this command writes) of
/// an earlier life in `dir` that this life did not redraw: a seed without a dent left the
/// previous seed's `event-4-dent.png` beside its own set, indistinguishable from it (stop 68).
fn remove_stale_events(dir: &Path, kept: &[PathBuf]) {
    let Ok(rd) = std::fs::read_dir(dir) else {
        return;
    };
    for p in rd.flatten().map(|e| e.path()) {
        let name = p
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let ours = name
            .strip_prefix("event-")
            .is_some_and(|r| r.starts_with(|c: char| c.is_ascii_digit()))
            && (name.ends_with(".png") || name.ends_with(".svg"));
        if ours && p.is_file() && !kept.iter().any(|k| k.file_name() == p.file_name()) {
            let _ = std::fs::remove_file(&p);
        }
    }
}

fn draw_ims<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, c: &ImsComparison) -> R {
    e(root.fill(&WHITE))?;
    let (lo, hi) = log_range(c.measured.rms.iter().chain(&c.simulated.rms).copied());
    let title = format!(
        "IMS test 2 bearing 1 vs wearsim ims-za2115: onset {} vs {}, distance {:.1} dB rms",
        c.onset_measured
            .map(|x| format!("{x:.2}"))
            .unwrap_or("-".into()),
        c.onset_simulated
            .map(|x| format!("{x:.2}"))
            .unwrap_or("-".into()),
        c.distance_db_rms
    );
    let mut chart = life_axes(
        &root,
        &title,
        (lo, hi),
        "fraction of life",
        "RMS / early-life median",
    )?;
    for (curve, label, col) in [
        (&c.measured, "measured (IMS)", RGBColor(210, 40, 40)),
        (&c.simulated, "simulated (wearsim)", RGBColor(20, 90, 200)),
    ] {
        let pts: Vec<(f64, f64)> = curve
            .t
            .iter()
            .copied()
            .zip(curve.rms.iter().copied())
            .collect();
        e(chart.draw_series(LineSeries::new(pts, col.stroke_width(2))))?
            .label(label)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], col.stroke_width(2)));
    }
    for (o, col) in [
        (c.onset_measured, RGBColor(210, 40, 40)),
        (c.onset_simulated, RGBColor(20, 90, 200)),
    ] {
        if let Some(o) = o {
            e(chart.draw_series(std::iter::once(PathElement::new(
                vec![(o, lo), (o, hi)],
                col.stroke_width(1),
            ))))?;
        }
    }
    e(chart
        .configure_series_labels()
        .label_font((FONT, 13))
        .border_style(BLACK)
        .background_style(WHITE.mix(0.9))
        .position(SeriesLabelPosition::UpperLeft)
        .draw())?;
    e(root.present())
}

/// `ims-overlay.png/svg`.
pub fn ims_overlay(dir: &Path, c: &ImsComparison) -> Result<Vec<PathBuf>, PlotError> {
    register_fonts();
    create_folder(dir)?;
    render(dir, "ims-overlay", |r| draw_ims(r, c), |r| draw_ims(r, c))
}
