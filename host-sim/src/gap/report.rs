//! The `wearsim gap` report: Markdown, JSON and plots (overlaid spectra and envelope
//! spectra of the first held-out record — measured, baseline, with the added effects —
//! and the cell gaps before and after as bars). The JSON is written last, so a directory
//! with `gap.json` holds a complete report.

use super::attribute::{Attribution, Dropped, Step};
use super::error::GapError;
use super::leave_one_out::LeaveOneOut;
use super::matched::Matched;
use super::stationary::GapOutput;
use crate::analysis::{self, Spectrum, WelchParams};
use crate::life::output::write_atomic;
use crate::plot::{db, e, points, range, register_fonts, render, PlotError, FONT, R};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

pub(crate) fn fmt_params(p: &[super::fit::FittedParam]) -> String {
    p.iter()
        .map(|q| {
            let std = q
                .std
                .map_or_else(|| " ± ?".to_string(), |s| format!(" ± {s:.3}"));
            let edge = if q.at_bound { " (edge)" } else { "" };
            format!("{} = {:.4}{std} {}{edge}", q.name, q.value, q.unit)
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// Cell groups named in the per-group shrinks.
fn groups(o: &GapOutput) -> Vec<String> {
    o.ranking
        .first()
        .map(|r| r.group_shrink.keys().cloned().collect())
        .unwrap_or_default()
}

/// The report as Markdown.
pub fn markdown(o: &GapOutput) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# Sim-to-real gap\n");
    let _ = writeln!(s, "## Records\n");
    let _ = writeln!(s, "| role | part | rpm (source) | bearing | defect |");
    let _ = writeln!(s, "|---|---|---|---|---|");
    for r in &o.records {
        let d = super::records::describe_defect(r.meta.defect);
        let _ = writeln!(
            s,
            "| {} | {} | {:.0} ({}) | {} | {} |",
            r.role, r.part, r.meta.rpm, r.meta.rpm_source, r.meta.bearing, d
        );
    }
    if let Some(c) = &o.calibration {
        let _ = writeln!(
            s,
            "\n## The rig, calibrated on the training part before any effect was ranked\n\nTraining gap {:.2} → {:.2} ({} simulations); factors on the nominal rig, each within its tolerance:\n",
            c.train_before, c.train_after, c.simulations
        );
        let _ = writeln!(s, "| nuisance | factor | tolerance | at bound |");
        let _ = writeln!(s, "|---|---:|---:|---|");
        for f in &c.fitted {
            let _ = writeln!(
                s,
                "| {} | {:.3} | ±{:.1} % | {} |",
                f.name,
                f.factor,
                100.0 * f.tolerance,
                if f.at_bound { "**yes**" } else { "no" }
            );
        }
        for n in &c.not_informed {
            let _ = writeln!(s, "| {} | 1 (not informed) | — | — |", n.name);
        }
    }
    let _ = writeln!(
        s,
        "\n## Where: cells by baseline gap (held-out)\n\nGap = (simulated − measured) / measured segment-to-segment spread; |gap| < 1 is within the measurement's own variability.\n"
    );
    let _ = writeln!(
        s,
        "| cell | unit | measured | simulated | spread | gap | gap after |"
    );
    let _ = writeln!(s, "|---|---|---:|---:|---:|---:|---:|");
    for c in o.where_.iter().take(15) {
        let _ = writeln!(
            s,
            "| {} | {} | {:.3} | {:.3} | {:.3} | {:+.2} | {:+.2} |",
            c.cell, c.unit, c.real, c.sim, c.spread, c.gap, c.gap_after
        );
    }
    let _ = writeln!(
        s,
        "\n## Which: each effect alone, fitted on training, ranked on validation, judged on test\n"
    );
    let _ = writeln!(
        s,
        "| rank | effect | fitted parameters (± 1 σ) | train gap | validation gap | validation shrink | shrink where | test shrink | converged |"
    );
    let _ = writeln!(s, "|---:|---|---|---:|---:|---:|---:|---:|---|");
    for (i, r) in o.ranking.iter().enumerate() {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {:.2} | {:.2} | {:+.0} % | {:+.0} % | {} | {} |",
            i + 1,
            r.effect,
            fmt_params(&r.params),
            r.train_gap,
            r.holdout_gap,
            100.0 * r.shrink,
            100.0 * r.where_shrink,
            r.test_shrink
                .map_or_else(|| "–".to_string(), |t| format!("{:+.0} %", 100.0 * t)),
            if r.converged { "yes" } else { "no" }
        );
    }
    let _ = writeln!(
        s,
        "\n### Identifiability: confounded sets and where each effect acts (validation shrink per cell group)\n"
    );
    let _ = writeln!(
        s,
        "| effect | confounded with | {} |",
        groups(o).join(" | ")
    );
    let _ = writeln!(s, "|---|---|{}", "---:|".repeat(groups(o).len()));
    for r in &o.ranking {
        let _ = writeln!(
            s,
            "| {} | {} | {} |",
            r.effect,
            if r.confounded_with.is_empty() {
                "–".to_string()
            } else {
                r.confounded_with.join(", ")
            },
            groups(o)
                .iter()
                .map(|g| r
                    .group_shrink
                    .get(g)
                    .map_or_else(|| "–".to_string(), |v| format!("{:+.0} %", 100.0 * v)))
                .collect::<Vec<_>>()
                .join(" | ")
        );
    }
    let _ = writeln!(s, "\n## How far: greedy addition (validation total gap)\n");
    let _ = writeln!(
        s,
        "Baseline: training {:.2}, validation {:.2}.\n",
        o.totals.train_before, o.totals.before
    );
    greedy_section(&mut s, &o.greedy, &o.dropped, &o.kept);
    let _ = writeln!(
        s,
        "\nTotal validation gap (chose the model, biased upwards): {:.2} → {:.2} ({:.0} % smaller).\n",
        o.totals.before,
        o.totals.after,
        100.0 * o.totals.shrink
    );
    if let (Some(b), Some(a), Some(sh)) = (
        o.totals.test_before,
        o.totals.test_after,
        o.totals.test_shrink,
    ) {
        let closed = match o.totals.closed_by_library {
            Some(true) => "the library closes it (within the measurement's variability)",
            _ => "the library does **not** close it (above the measurement's variability)",
        };
        let _ = writeln!(
            s,
            "**Total test gap** (chose nothing): {b:.2} → {a:.2} ({:.0} % smaller); {closed}.\n",
            100.0 * sh
        );
    }
    match &o.identified {
        // A tie (the report's own tie rule) is never headlined.
        Some(e) if !o.tied_with.is_empty() => {
            let _ = writeln!(
                s,
                "Named first: none — `{e}` ties with {} (within the tie rule); the cells do not tell them apart here.",
                o.tied_with
                    .iter()
                    .map(|t| format!("`{t}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            );
        }
        Some(e) => {
            let _ = writeln!(s, "Named first: **{e}**.");
        }
        None => {
            let _ = writeln!(
                s,
                "Named first: none (no effect shrinks the gap meaningfully)."
            );
        }
    }
    if let Some(loo) = &o.leave_one_out {
        leave_one_out_section(&mut s, loo);
    }
    if let Some(rows) = &o.stability {
        let _ = writeln!(
            s,
            "\n## Stability: the kept effects refitted on each record separately\n\nAgree = every pair of records that constrains the parameter lies within {} combined standard deviations.\n",
            crate::gap::stability::Z_LIMIT
        );
        let _ = writeln!(
            s,
            "| effect | parameter | per record (value ± std) | worst z | agree |"
        );
        let _ = writeln!(s, "|---|---|---|---:|---|");
        for r in rows {
            let per: Vec<String> = r
                .per_record
                .iter()
                .map(crate::gap::stability::PerRecord::describe)
                .collect();
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} |",
                r.effect,
                r.param,
                per.join("; "),
                r.worst_z.map_or("–".to_string(), |z| format!("{z:.1}")),
                if r.agree { "yes" } else { "**no**" }
            );
        }
    }
    findings_section(&mut s, &o.findings);
    let _ = writeln!(s, "\n{} simulations in {:.1} s.", o.simulations, o.seconds);
    s
}

/// The greedy additions as a table ("No effect was added." when none), the effects taken
/// out again, and the final model.
pub(crate) fn greedy_section(
    s: &mut String,
    greedy: &[Step],
    dropped: &[Dropped],
    kept: &[String],
) {
    if greedy.is_empty() {
        let _ = writeln!(s, "No effect was added.");
    } else {
        let _ = writeln!(
            s,
            "| step | effect | parameters | before | after | shrink |"
        );
        let _ = writeln!(s, "|---:|---|---|---:|---:|---:|");
        for (i, g) in greedy.iter().enumerate() {
            // A later step's confounded set (identify::step_set) beside its effect.
            let effect = if g.confounded_with.is_empty() {
                g.effect.clone()
            } else {
                format!(
                    "{} (confounded with {})",
                    g.effect,
                    g.confounded_with.join(", ")
                )
            };
            let _ = writeln!(
                s,
                "| {} | {} | {} | {:.2} | {:.2} | {:.0} % |",
                i + 1,
                effect,
                fmt_params(&g.params),
                g.before,
                g.after,
                100.0 * g.shrink
            );
        }
    }
    for d in dropped {
        let _ = writeln!(
            s,
            "\n`{}` was taken out again after `{}` was added: held-out gap {:.2} without it, {:.2} with it.",
            d.effect, d.after, d.without, d.with
        );
    }
    let _ = writeln!(
        s,
        "\nFinal model: {}.",
        if kept.is_empty() {
            "the baseline".to_string()
        } else {
            kept.join(" + ")
        }
    );
}

/// The leave-one-out checks as a table.
pub(crate) fn leave_one_out_section(s: &mut String, loo: &[LeaveOneOut]) {
    let _ = writeln!(s, "\n## Leave one effect out\n");
    let _ = writeln!(
        s,
        "| withheld | gap full model | gap without | named first | named |"
    );
    let _ = writeln!(s, "|---|---:|---:|---|---|");
    for l in loo {
        let _ = writeln!(
            s,
            "| {} | {:.2} | {:.2} | {} | {} |",
            l.effect,
            l.full,
            l.without,
            l.named_first.as_deref().unwrap_or("none"),
            if l.named { "yes" } else { "no" }
        );
    }
}

/// The findings as a list (nothing when there are none).
pub(crate) fn findings_section(s: &mut String, findings: &[String]) {
    if !findings.is_empty() {
        let _ = writeln!(s, "\n## Findings and limits\n");
        for f in findings {
            let _ = writeln!(s, "* {f}");
        }
    }
}

fn psd(x: &[f64], fs: f64) -> Option<Spectrum> {
    let nperseg = (x.len() / 8).next_power_of_two().clamp(256, 4096);
    analysis::welch_psd(
        x,
        fs,
        &WelchParams {
            nperseg,
            ..WelchParams::default()
        },
    )
    .ok()
}

pub(crate) const REAL_C: RGBColor = RGBColor(40, 40, 40);
pub(crate) const BASE_C: RGBColor = RGBColor(210, 40, 40);
pub(crate) const FINAL_C: RGBColor = RGBColor(20, 90, 200);

/// One curve: legend, colour, points.
pub(crate) type Series<'a> = (&'a str, RGBColor, Vec<(f64, f64)>);

/// [`draw_lines`] rendered to `<dir>/<name>.png` and `.svg` (see [`render`]).
pub(crate) fn render_lines(
    dir: &Path,
    name: &str,
    title: &str,
    xlabel: &str,
    ylabel: &str,
    x1: f64,
    series: &[Series],
) -> Result<Vec<PathBuf>, PlotError> {
    render(
        dir,
        name,
        |r| draw_lines(r, title, xlabel, ylabel, x1, series),
        |r| draw_lines(r, title, xlabel, ylabel, x1, series),
    )
}

pub(crate) fn draw_lines<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    title: &str,
    xlabel: &str,
    ylabel: &str,
    x1: f64,
    series: &[Series],
) -> R {
    e(root.fill(&WHITE))?;
    let all: Vec<(f64, f64)> = series.iter().flat_map(|s| s.2.iter().copied()).collect();
    let (lo, hi) = range(&all, 0.05, 0.1);
    let mut chart = e(ChartBuilder::on(&root)
        .caption(title, (FONT, 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..x1, lo..hi))?;
    e(chart
        .configure_mesh()
        .x_desc(xlabel)
        .y_desc(ylabel)
        .label_style((FONT, 13))
        .draw())?;
    for (name, col, pts) in series {
        let col = *col;
        e(chart.draw_series(LineSeries::new(pts.clone(), col.stroke_width(1))))?
            .label(*name)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], col.stroke_width(2)));
    }
    e(chart
        .configure_series_labels()
        .label_font((FONT, 13))
        .border_style(BLACK)
        .background_style(WHITE.mix(0.9))
        .position(SeriesLabelPosition::UpperRight)
        .draw())?;
    e(root.present())
}

fn draw_bars<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, o: &GapOutput) -> R {
    let rows: Vec<(String, f64, f64)> = o
        .where_
        .iter()
        .take(20)
        .map(|c| (c.cell.clone(), c.gap, c.gap_after))
        .collect();
    let title = format!(
        "cell gaps, held-out: total {:.2} → {:.2}",
        o.totals.before, o.totals.after
    );
    draw_gap_bars(root, &title, &rows)
}

/// Horizontal bars of gaps before (red, upper) and after (blue, lower), one row per
/// `(label, before, after)`, first row on top.
pub(crate) fn draw_gap_bars<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    title: &str,
    rows: &[(String, f64, f64)],
) -> R {
    e(root.fill(&WHITE))?;
    let n = rows.len().max(1);
    let m = rows
        .iter()
        .flat_map(|c| [c.1.abs(), c.2.abs()])
        .filter(|v| v.is_finite())
        .fold(1.0, f64::max)
        * 1.1;
    let mut chart = e(ChartBuilder::on(&root)
        .caption(title, (FONT, 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(170)
        .build_cartesian_2d(-m..m, 0.0..n as f64))?;
    e(chart
        .configure_mesh()
        .disable_y_mesh()
        .y_labels(n)
        .y_label_formatter(&|y: &f64| {
            let i = n.saturating_sub(1 + y.floor() as usize);
            rows.get(i).map_or_else(String::new, |c| c.0.clone())
        })
        .x_desc("gap (simulated − measured) / measured spread")
        .label_style((FONT, 12))
        .draw())?;
    for (i, c) in rows.iter().enumerate() {
        let y = (n - 1 - i) as f64;
        e(chart.draw_series(std::iter::once(Rectangle::new(
            [(0.0, y + 0.5), (c.1, y + 0.9)],
            BASE_C.filled(),
        ))))?;
        e(chart.draw_series(std::iter::once(Rectangle::new(
            [(0.0, y + 0.1), (c.2, y + 0.5)],
            FINAL_C.filled(),
        ))))?;
    }
    e(chart.draw_series(std::iter::once(PathElement::new(
        vec![(0.0, 0.0), (0.0, n as f64)],
        BLACK.stroke_width(1),
    ))))?;
    e(root.present())
}

/// Writes the plots, `gap.md` and (last) `gap.json` into `dir`; returns the files.
pub fn write(
    dir: &Path,
    o: &GapOutput,
    hold: &[Matched],
    at: &Attribution,
) -> Result<Vec<PathBuf>, GapError> {
    register_fonts();
    std::fs::create_dir_all(dir)
        .map_err(|err| GapError::input(format!("--out {}: {err}", dir.display())))?;
    let mut files = vec![];
    if let Some(m) = hold.first() {
        let fs = m.spec().fs;
        let base = m
            .simulate(&wearsim_core::effects::Effects::NONE)
            .map_err(GapError::run)?;
        let fin = m.simulate(&at.final_effects).map_err(GapError::run)?;
        let spectra: Vec<Option<Spectrum>> =
            [&m.real, &base, &fin].iter().map(|x| psd(x, fs)).collect();
        let pts = |s: &Option<Spectrum>, f1: f64| {
            s.as_ref().map_or_else(Vec::new, |s| {
                points(s, 0.0, f1, |v| 10.0 * v.max(1e-30).log10())
            })
        };
        let nyq = 0.5 * fs;
        let ser = [
            ("measured", REAL_C, pts(&spectra[0], nyq)),
            ("baseline", BASE_C, pts(&spectra[1], nyq)),
            ("with added effects", FINAL_C, pts(&spectra[2], nyq)),
        ];
        let title = format!("PSD, held-out: {}", m.label);
        files.extend(render_lines(
            dir,
            "gap-spectra",
            &title,
            "frequency (Hz)",
            "PSD (dB re 1 (m/s²)²/Hz)",
            nyq,
            &ser,
        )?);
        let ff = &m.spec().ff;
        let f1 = 6.0 * ff.bpfi.max(ff.bpfo).max(2.0 * ff.bsf);
        let env: Vec<Vec<(f64, f64)>> = [&m.real, &base, &fin]
            .iter()
            .map(|x| {
                analysis::envelope_spectrum(x, fs, None)
                    .map(|s| points(&s, 0.0, f1, db))
                    .unwrap_or_default()
            })
            .collect();
        let eser = [
            ("measured", REAL_C, env[0].clone()),
            ("baseline", BASE_C, env[1].clone()),
            ("with added effects", FINAL_C, env[2].clone()),
        ];
        let title = format!("envelope spectrum, held-out: {}", m.label);
        files.extend(render_lines(
            dir,
            "gap-envelope",
            &title,
            "frequency (Hz)",
            "envelope amplitude (dB re 1 m/s²)",
            f1,
            &eser,
        )?);
    }
    files.extend(render(
        dir,
        "gap-cells",
        |r| draw_bars(r, o),
        |r| draw_bars(r, o),
    )?);
    finish(dir, &markdown(o), files, |f| GapOutput {
        files: f,
        ..o.clone()
    })
}

/// Writes `gap.md` (text `md`) and, last, `gap.json` into `dir` after the plots `files`:
/// a directory holding `gap.json` holds a complete report. `with_files` gives the JSON
/// document listing every file written (itself included). Returns that list.
pub(crate) fn finish<T: serde::Serialize>(
    dir: &Path,
    md: &str,
    mut files: Vec<PathBuf>,
    with_files: impl FnOnce(Vec<PathBuf>) -> T,
) -> Result<Vec<PathBuf>, GapError> {
    let path = dir.join("gap.md");
    write_atomic(&path, md.as_bytes())
        .map_err(|err| GapError::run(format!("{}: {err}", path.display())))?;
    files.push(path);
    let js = dir.join("gap.json");
    files.push(js.clone());
    let text = serde_json::to_string_pretty(&with_files(files.clone())).map_err(GapError::run)?;
    write_atomic(&js, text.as_bytes())
        .map_err(|err| GapError::run(format!("{}: {err}", js.display())))?;
    Ok(files)
}
