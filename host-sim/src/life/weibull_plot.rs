//! Weibull probability plot of a life-statistics run (`wearsim life --lives N`):
//! `lives-weibull.png/svg`, one panel for the lives to failure and one for the lives to
//! the first spall. Per load: the failures at their median ranks (Johnson-adjusted for
//! suspensions, [`super::weibull::median_ranks`]), the maximum-likelihood line, and ISO
//! 281's L10 for the load as a vertical mark. The y axis is Weibull's
//! `ln(−ln(1 − F))`, labelled in unreliability F (%), so a Weibull distribution is a
//! straight line of slope β (Abernethy, *The New Weibull Handbook*, 5th ed., ch. 2).

use super::lives::LoadGroup;
use super::weibull::{median_ranks, Unit, Weibull, WeibullFit};
use crate::plot::{create_folder, e, register_fonts, render, PlotError, FONT, R};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// One colour per load group (cycled).
const LOAD_COLORS: [RGBColor; 4] = [
    RGBColor(20, 90, 200),
    RGBColor(210, 40, 40),
    RGBColor(20, 150, 60),
    RGBColor(140, 60, 170),
];

/// Unreliability ticks (%) of the y axis, as on Weibull probability paper.
const F_TICKS: [f64; 10] = [0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 63.2, 90.0, 99.0];

/// Weibull's y coordinate of unreliability `f` (0 < f < 1).
fn wy(f: f64) -> f64 {
    (-(1.0 - f).ln()).ln()
}

/// One panel's data per load: its median-rank points (log10 revolutions, y), its fitted
/// distribution and ISO L10 (revolutions), and its legend.
struct Series {
    points: Vec<(f64, f64)>,
    fit: Option<Weibull>,
    iso_l10: f64,
    label: String,
}

fn series(
    groups: &[LoadGroup],
    unit: fn(&super::lives::LifeOutcome) -> Unit,
    first_spall: bool,
) -> Vec<Series> {
    groups
        .iter()
        .map(|g| {
            let units: Vec<Unit> = g.lives.iter().map(unit).collect();
            let fit: Option<&WeibullFit> = if first_spall {
                g.first_spall_weibull.as_ref()
            } else {
                g.weibull.as_ref()
            };
            let suspended = units.iter().filter(|u| !u.failed).count();
            let fit = fit.map(|w| Weibull {
                shape: w.shape.value,
                scale: w.scale.value,
            });
            let label = match fit {
                Some(w) => format!(
                    "{:.0} N: β {:.2}, η {:.3e}{}",
                    g.load_n,
                    w.shape,
                    w.scale,
                    if suspended > 0 {
                        format!(", {suspended} suspended")
                    } else {
                        String::new()
                    }
                ),
                None => format!("{:.0} N: no fit ({suspended} suspended)", g.load_n),
            };
            Series {
                points: median_ranks(&units)
                    .into_iter()
                    .map(|(t, f)| (t.log10(), wy(f)))
                    .collect(),
                fit,
                iso_l10: g.iso_l10,
                label,
            }
        })
        .collect()
}

fn draw_panel<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, title: &str, s: &[Series]) -> R {
    let xs = s
        .iter()
        .flat_map(|x| x.points.iter().map(|p| p.0).chain([x.iso_l10.log10()]))
        .filter(|x| x.is_finite());
    let (mut x0, mut x1) = (f64::INFINITY, f64::NEG_INFINITY);
    for x in xs {
        x0 = x0.min(x);
        x1 = x1.max(x);
    }
    if !(x0.is_finite() && x1.is_finite()) {
        (x0, x1) = (5.0, 9.0);
    }
    let (x0, x1) = ((x0 - 0.3).floor(), (x1 + 0.3).ceil());
    let (y0, y1) = (wy(0.002), wy(0.998));
    let mut chart = e(ChartBuilder::on(area)
        .caption(title, (FONT, 17))
        .margin(8)
        .margin_right(16)
        .x_label_area_size(42)
        .y_label_area_size(60)
        .build_cartesian_2d(x0..x1, y0..y1))?;
    e(chart
        .configure_mesh()
        .x_desc("revolutions")
        .y_desc("unreliability F (%)")
        .x_label_formatter(&|x| format!("1e{x:.0}"))
        .y_labels(0)
        .disable_y_mesh()
        .label_style((FONT, 12))
        .axis_desc_style((FONT, 13))
        .draw())?;
    // Weibull paper's unreliability ticks, labelled beside the axis; 10 % (L10) darker.
    let base = area.get_base_pixel();
    for f in F_TICKS {
        let y = wy(f / 100.0);
        let shade = if f == 10.0 { 150 } else { 225 };
        e(chart.draw_series(std::iter::once(PathElement::new(
            vec![(x0, y), (x1, y)],
            RGBColor(shade, shade, shade).stroke_width(1),
        ))))?;
        let (px, py) = chart.backend_coord(&(x0, y));
        e(area.draw(&Text::new(
            format!("{f}"),
            (px - base.0 - 38, py - base.1 - 6),
            (FONT, 12).into_font(),
        )))?;
    }
    for (i, x) in s.iter().enumerate() {
        let c = LOAD_COLORS[i % LOAD_COLORS.len()];
        let iso = x.iso_l10.log10();
        if iso.is_finite() {
            e(chart.draw_series(std::iter::once(PathElement::new(
                vec![(iso, y0), (iso, y1)],
                c.mix(0.5).stroke_width(1),
            ))))?;
            e(chart.draw_series(std::iter::once(Text::new(
                "ISO L10",
                (iso, y0 + 0.3 + 0.5 * i as f64),
                (FONT, 11).into_font().color(&c),
            ))))?;
        }
        if let Some(w) = x.fit {
            // y = β (ln t − ln η), with ln t = x · ln 10, drawn between the y limits
            // (plotters would clamp the ends of a longer segment onto the frame).
            let at =
                |y: f64| ((y / w.shape + w.scale.ln()) / std::f64::consts::LN_10).clamp(x0, x1);
            let line = |lx: f64| w.shape * (lx * std::f64::consts::LN_10 - w.scale.ln());
            let (a, b) = (at(y0), at(y1));
            e(chart.draw_series(std::iter::once(PathElement::new(
                vec![(a, line(a)), (b, line(b))],
                c.stroke_width(2),
            ))))?
            .label(x.label.clone())
            .legend(move |(a, b)| PathElement::new(vec![(a, b), (a + 18, b)], c.stroke_width(2)));
        } else {
            e(chart.draw_series(std::iter::empty::<Circle<(f64, f64), i32>>()))?
                .label(x.label.clone())
                .legend(move |(a, b)| Circle::new((a + 9, b), 3, c.filled()));
        }
        e(chart.draw_series(x.points.iter().map(|p| Circle::new(*p, 3, c.filled()))))?;
    }
    e(chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .label_font((FONT, 12))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.3))
        .draw())?;
    Ok(())
}

fn draw<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, groups: &[LoadGroup]) -> R {
    e(root.fill(&WHITE))?;
    let (left, right) = root.split_horizontally(root.dim_in_pixel().0 / 2);
    let fail = series(groups, super::lives::to_failure, false);
    let spall = series(groups, super::lives::to_first_spall, true);
    draw_panel(
        &left,
        "Lives to failure (Weibull plot, median ranks)",
        &fail,
    )?;
    draw_panel(&right, "Lives to the first spall", &spall)?;
    e(root.present())
}

/// `lives-weibull.png/svg` in `dir` (created if missing); returns the files written.
pub fn lives_weibull(dir: &Path, groups: &[LoadGroup]) -> Result<Vec<PathBuf>, PlotError> {
    register_fonts();
    create_folder(dir)?;
    render(
        dir,
        "lives-weibull",
        |r| draw(r, groups),
        |r| draw(r, groups),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Unreliability (%) at Weibull y coordinate `y` (the inverse of [`wy`], in %).
    fn unreliability_pct(y: f64) -> f64 {
        100.0 * (1.0 - (-(y.exp())).exp())
    }

    /// The y axis is Weibull's: F = 63.2 % at y = 0, and `wy` inverts to F.
    #[test]
    fn weibull_axis_round_trips() {
        assert!(wy(1.0 - (-1.0f64).exp()).abs() < 1e-12);
        for f in [0.01, 0.1, 0.5, 0.9] {
            assert!((unreliability_pct(wy(f)) - 100.0 * f).abs() < 1e-9);
        }
    }
}
