//! `wearsim gap` on a lifetime record (an IMS feature table): arguments, the report
//! (Markdown, plots of the statistics along life and of the stage gaps, JSON written last)
//! answering where along life / which effect / how far.

use crate::analysis::stats::upper_median;
use crate::gap::attribute::{Dropped, Ranked, Step, Totals};
use crate::gap::error::GapError;
use crate::gap::fit::FittedParam;
use crate::gap::leave_one_out::LeaveOneOut;
use crate::gap::lifetime::{self, EarlyShrink, LifeCell, LifeGap, LifePoint, StageGap};
use crate::gap::report::{
    draw_gap_bars, findings_section, finish, fmt_params, greedy_section, leave_one_out_section,
    render_lines, Series, BASE_C, FINAL_C, REAL_C,
};
use crate::gap::roles;
use crate::plot::{register_fonts, render};
use plotters::style::RGBColor;
use serde::Serialize;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Whether `path` is a lifetime record: a CSV whose header has per-bearing `B<k>_rms` and
/// `B<k>_kurtosis` columns (an IMS timefeatures table).
pub fn is_life_table(path: &Path) -> bool {
    csv_header(path).is_some_and(|h| h.contains("B1_rms") && h.contains("B1_kurtosis"))
}

/// Whether `path` is an IMS feature table with two accelerometers per bearing (IMS test 1:
/// `B<k>_x_rms`, `B<k>_y_rms`, ...), which the lifetime diagnosis does not read
/// ([`TWO_CHANNEL_NOTE`]).
pub fn is_two_channel_ims_table(path: &Path) -> bool {
    csv_header(path).is_some_and(|h| h.contains("B1_x_rms") && h.contains("B1_x_kurtosis"))
}

/// Why a two-channel IMS feature table ([`is_two_channel_ims_table`]) is refused.
pub const TWO_CHANNEL_NOTE: &str = "an IMS feature table with two accelerometers per bearing (test 1's layout: B<k>_x_..., B<k>_y_...), which the lifetime diagnosis does not read: its IMS premise is one failed bearing whose neighbours on the shaft did not fail, and in test 1 bearings 3 and 4 both failed; give each bearing and channel as a documented feature table (docs/feature-tables.md)";

/// The first line of a `.csv` file, if it is one and can be read.
fn csv_header(path: &Path) -> Option<String> {
    if !path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("csv"))
    {
        return None;
    }
    let f = std::fs::File::open(path).ok()?;
    let mut line = String::new();
    std::io::BufRead::read_line(&mut std::io::BufReader::new(f), &mut line).ok()?;
    Some(line)
}

/// The early-life part of the answer.
#[derive(Debug, Clone, Serialize)]
pub struct Early {
    /// Stages counted as early life (their end ≤ this fraction of life).
    pub until: f64,
    /// Held-out early-life gap of the baseline.
    pub before: f64,
    /// With the final model of the whole life.
    pub after: f64,
    /// Each effect alone, best first.
    pub effects: Vec<EarlyShrink>,
    /// The effect that closes the early-life part, if one shrinks it by 5 % or more.
    pub closed_by: Option<String>,
    /// Held-out early-life gap a correct model would leave by sampling alone.
    pub noise_only: f64,
    /// On the test lives' early stages (none without a test part): the baseline's gap
    /// and the final early-life model's.
    pub test: Option<crate::gap::attribute::TestTotals>,
}

/// The lifetime report (`--json`).
#[derive(Debug, Clone, Serialize)]
pub struct LifeGapOutput {
    /// `lifetime`.
    pub mode: &'static str,
    /// Training lives (role `train`: every parameter fitted on them). Each life is named
    /// by its bearing id and its file ([`lifetime::MeasuredLife::label`]).
    pub train: Vec<String>,
    /// Validation lives (role `validation`: the model was chosen on them). Without a test
    /// part, all held-out lives, which then also were judged (`totals.test_note`).
    pub validation: Vec<String>,
    /// Test lives (role `test`: judged only, chose nothing; `totals.test_*`); empty
    /// without a test part.
    pub test: Vec<String>,
    /// Every life not trained on: `validation` then `test` (kept for readers of earlier
    /// reports; the order of `holdout_spans`).
    pub holdout: Vec<String>,
    /// Every cell of every life, each with its life's role, ranked by |baseline gap|
    /// ("where").
    #[serde(rename = "where")]
    pub where_: Vec<LifeCell>,
    /// Stages ranked by their baseline gap, training life.
    pub stages_train: Vec<StageGap>,
    /// Stages of the validation lives (which chose the model).
    pub stages_holdout: Vec<StageGap>,
    /// Stages of the test lives (empty without a test part).
    pub stages_test: Vec<StageGap>,
    /// How the training life is compared (whole life, simulated wear site), and which
    /// life it is (`path`, `id`, `source`, `number`, `role`).
    pub train_span: lifetime::LifeSpan,
    /// How each life not trained on is compared: its failure mode, the part of its life
    /// judged (`t_max`), the simulated wear site; which life it is and its role.
    pub holdout_spans: Vec<lifetime::LifeSpan>,
    /// Effects ranked by held-out shrink.
    pub ranking: Vec<Ranked>,
    /// Greedy additions.
    pub greedy: Vec<Step>,
    /// Effects taken out again.
    pub dropped: Vec<Dropped>,
    /// Exchanges after the greedy additions (`--exchange`; empty without it).
    pub exchanged: Vec<crate::gap::exchange::Exchanged>,
    /// Effects of the final model.
    pub kept: Vec<String>,
    /// Totals: `before`/`after` on the validation lives (they chose the model: biased
    /// upwards), `test_*` on the test lives (null without a test part, `test_note` says
    /// why).
    pub totals: LifeTotals,
    /// Effect named first.
    pub identified: Option<String>,
    /// Effects tied with it.
    pub tied_with: Vec<String>,
    /// The early-life part.
    pub early: Early,
    /// The simulated bearing (its preset, or the sidecar's geometry and operating point
    /// with a scaled structure) and the assumptions behind it.
    pub rig: lifetime::RigDescription,
    /// Its closed-form defect frequencies (Hz).
    pub kinematics: wearsim_core::kinematics::FaultFrequencies,
    /// Calibrated life factor (on the training bearing's measured life).
    pub life_factor: f64,
    /// Calibrated propagation limit `material.propagation_passes` (passes; on the training
    /// bearing's onset of instability; the material's default when it has none).
    pub propagation_passes: f64,
    /// Training bearing's onset of instability (fraction of life; `null`: none).
    pub measured_onset: Option<f64>,
    /// The calibrated simulated life's onset of instability (fraction of life).
    pub simulated_onset: Option<f64>,
    /// What `simulated_onset` was read from: `rms` (the measured life's rule on the
    /// simulated RMS) or `wear-stages` (its RMS never left its steady band, e.g. on a slow
    /// rig: the start of its first spall or of its new defects after the first quarter of
    /// its life).
    pub simulated_onset_basis: &'static str,
    /// Training bearing's measured life (revolutions).
    pub measured_revs: f64,
    /// Held-out gap of the whole life a correct model would leave by sampling alone.
    pub noise_only: f64,
    /// Findings and limits in words.
    pub findings: Vec<String>,
    /// Leave-one-out checks (with `--leave-one-out`).
    pub leave_one_out: Option<Vec<LeaveOneOut>>,
    /// Lives simulated (calibration included).
    pub simulations: usize,
    /// Wall-clock time (s).
    pub seconds: f64,
    /// Files written.
    pub files: Vec<PathBuf>,
}

/// The totals of a lifetime diagnosis: those of records of seconds ([`Totals`], the same
/// keys) and, when the `test_*` figures are null, why.
#[derive(Debug, Clone, Serialize)]
pub struct LifeTotals {
    /// The totals.
    #[serde(flatten)]
    pub totals: Totals,
    /// Why `test_*` are null (no test part: the held-out lives chose the model and were
    /// judged); `null` when a test part was judged.
    pub test_note: Option<String>,
}

/// What the failure modes of the lives mean for the comparison: which part of each
/// held-out life is judged, against which simulated wear site.
fn span_findings(g: &LifeGap) -> Vec<String> {
    let mut f = vec![];
    let t = &g.train_span;
    let how = if t.failure_mode == "unknown" {
        "is taken as the life to failure (its table does not state the failure mode)".to_string()
    } else {
        format!("failed at {}", t.failure_mode)
    };
    f.push(format!(
        "the training life ({}) {how} and is compared over its whole life with a simulated life wearing at the {}",
        t.life, t.simulated_site
    ));
    for h in &g.holdout_spans {
        let why = if h.t_max < 1.0 && h.shared_shaft && h.failure_mode == "none" {
            format!(
                "it did not fail (the IMS end-of-test finding), and its late stages carry the failing neighbour's vibration through the shaft (IMS: the bearings ran on one shaft); it is compared on the stages before {:.0} % of the test",
                100.0 * h.t_max
            )
        } else if h.t_max < 1.0 && h.shared_shaft {
            format!(
                "its table does not say whether it failed (no known IMS test); it ran on one shaft with the other bearings, so its late stages may carry a failing neighbour's vibration: it is compared on the stages before {:.0} % of the test",
                100.0 * h.t_max
            )
        } else if h.t_max < 1.0 {
            format!(
                "its sidecar says it did not fail (failure_mode none): it has no end of life, its time line is that of its test, so it is compared only on the stages before {:.0} % of the test, and the late-life part rests on the training life and the lives that failed",
                100.0 * h.t_max
            )
        } else if h.failure_mode == "unknown" {
            format!(
                "its failure mode is unknown: it is taken to have run to failure and is compared over its whole life with a simulated life wearing at the {}",
                h.simulated_site
            )
        } else if lifetime::sim::failure_site(&h.failure_mode).is_none() {
            format!(
                "it failed at {}, a site the wear machine does not grow: it is compared over its whole life with a simulated life wearing at the {}, which may itself be part of the gap",
                h.failure_mode, h.simulated_site
            )
        } else {
            format!(
                "it failed at {} and is compared over its whole life with a simulated life wearing at the {} (same life factor)",
                h.failure_mode, h.simulated_site
            )
        };
        f.push(format!("held-out {} life {}: {why}", h.role, h.life));
    }
    for sp in std::iter::once(t).chain(&g.holdout_spans) {
        if let Some(name) = sp.merged_early {
            let st = lifetime::stage_named(name).map_or(0.0, |s| s.hi);
            f.push(format!(
                "{}: its table has fewer than {} snapshots in a fine early stage (running-in 0-1 %, early 1-3 %{}), so its first {:.0} % of life is compared as one stage, `{name}`; a gap inside that part (a running-in bump) is not resolved in time",
                sp.life,
                lifetime::MIN_SNAPSHOTS,
                if st > 0.05 { ", settled 3-10 %" } else { "" },
                100.0 * st
            ));
        }
    }
    for sp in std::iter::once(t).chain(&g.holdout_spans) {
        // A well-named band is ignored only for reaching above the table's Nyquist
        // frequency; anything else is no column of the format.
        let (bands, other): (Vec<&String>, Vec<&String>) = sp
            .ignored_columns
            .iter()
            .partition(|c| crate::io::feature_table::parse_band(c).is_some());
        let list = |v: &[&String]| {
            v.iter()
                .map(|c| format!("`{c}`"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        if !other.is_empty() {
            f.push(format!(
                "{}: columns not part of the feature-table format were ignored: {} (a band level must be named `band_<lo>_<hi>_hz` with lo < hi in Hz; docs/feature-tables.md)",
                sp.life,
                list(&other)
            ));
        }
        if !bands.is_empty() {
            f.push(format!(
                "{}: band levels reaching above the Nyquist frequency (half the sidecar's sample_rate_hz) were ignored: {}",
                sp.life,
                list(&bands)
            ));
        }
    }
    let mut units: Vec<&str> = std::iter::once(t)
        .chain(&g.holdout_spans)
        .map(|s| s.unit.as_str())
        .collect();
    units.sort_unstable();
    units.dedup();
    f.push(format!(
        "units ({}) do not enter the gap: RMS counts only in dB re each life's own steady level, and kurtosis, crest factor and skewness have none{}",
        units.join(", "),
        if units.len() > 1 {
            "; the lives, in different units, compare as they are"
        } else {
            ""
        }
    ));
    f
}

fn findings(g: &LifeGap) -> Vec<String> {
    let steel = wearsim_core::wear::Material::BEARING_STEEL.propagation_passes;
    let mut f = vec![match g.measured_onset {
        Some(u) => format!(
            "the life factor ({:.3e}) and the propagation limit ({:.3e} passes, {:.3e} times the material's {steel:.1e}) are calibrated on the training bearing's measured life ({:.3e} revolutions) and its onset of instability ({u:.3} of life; simulated {}): the length of the simulated life and the training life's onset are in-sample, the rest of its shape is not, and a held-out life's onset is a test of the calibration; the propagation limit has no literature value, so its ratio to the material's is itself a finding on this rig's spall growth",
            g.life_factor,
            g.propagation_passes,
            g.propagation_passes / steel,
            g.measured_revs,
            g.simulated_onset.map_or("none".to_string(), |v| format!("{v:.3}"))
        ),
        None => format!(
            "the life factor ({:.3e}) is calibrated on the training bearing's measured life ({:.3e} revolutions): the length of the simulated life is in-sample, its shape is not; the training life has no onset of instability that the rule can place (its RMS does not stay above the steady band of the snapshots before it for {} snapshots anywhere after the first quarter of its life: it never rose, or it rose inside that quarter, which is the band's baseline), so the propagation limit stays the material's {steel:.1e} passes",
            g.life_factor,
            g.measured_revs,
            crate::life::ims::PERSIST
        ),
    }];
    if let Some(u) = g.measured_onset {
        let off = g.simulated_onset.map_or(f64::INFINITY, |v| (v - u).abs());
        if off > crate::life::calibrate::ONSET_TOLERANCE {
            f.push(format!(
                "the calibration did not bring the simulated onset of instability ({}) within {} of the training life's ({u:.3}): the length is matched, the onset is not, and the stages between them carry that difference{}",
                g.simulated_onset.map_or("none".to_string(), |v| format!("{v:.3}")),
                crate::life::calibrate::ONSET_TOLERANCE,
                match g.simulated_onset {
                    Some(v) if v < u => format!(
                        "; the part after the onset could not be shortened to the measured one (the propagation limit went down to {:.3e} passes): after the first spall the simulated life still runs its crack growth on absolute stresses, which at this load lasts longer than the measured life after its onset",
                        g.propagation_passes
                    ),
                    _ => String::new(),
                }
            ));
        }
    }
    if g.simulated_onset_basis == lifetime::sim::OnsetBasis::WearStages {
        f.push(format!(
            "the simulated life's RMS never leaves its steady band at {:.0} rpm (its defect's impacts, which weaken with speed, stay within the steady vibration of the simulated structure), so its onset of instability ({}) is read from its wear stages: the start of its first spall or of its new defects after the first quarter of its life, where the RMS shows the onset at ordinary speeds; the measured RMS rise is then itself part of the gap",
            60.0 * g.rig.shaft_hz,
            g.simulated_onset.map_or("none".to_string(), |v| format!("{v:.3}"))
        ));
    }
    f.extend(span_findings(g));
    for a in &g.rig.assumptions {
        f.push(format!(
            "the simulated bearing is not a preset: {a}; this assumption may itself be part of the gap"
        ));
    }
    f.extend(g.attribution.findings.iter().cloned());
    f.extend(g.early_findings.iter().map(|x| format!("early life: {x}")));
    let threshold = lifetime::SIGNIFICANCE * g.noise_only.1;
    f.push(format!(
        "a correct model would leave a held-out gap of {:.2} over the whole life and {:.2} over its early part by sampling alone (stage means of n measured snapshots and m simulated windows: variance 1/n + 1/m per cell); a gap counts from {:.0}× that",
        g.noise_only.0,
        g.noise_only.1,
        lifetime::SIGNIFICANCE
    ));
    // A baseline early gap below the threshold is said once, by the early-life
    // attribution's own finding (with the same level, `significance::level`).
    match &g.early_effect {
        Some(e) => {
            if let Some(x) = g.early.first() {
                let set = if x.confounded_with.is_empty() {
                    String::new()
                } else {
                    let others = x.confounded_with.join(", ");
                    format!(
                        "; confounded with {others}: the early-life ranking inside {{{e}, {others}}} is not evidence for `{e}`"
                    )
                };
                let test = match (x.test_shrink, g.early_test) {
                    (Some(ts), Some(t)) => format!(
                        "; on the test lives' early stages (chose nothing) {:.2} → {:.2} ({:.0} % smaller)",
                        t.before,
                        x.test_gap.unwrap_or(f64::NAN),
                        100.0 * ts
                    ),
                    _ => String::new(),
                };
                f.push(format!(
                    "`{e}` closes the early-life part: held-out early-life gap {:.2} → {:.2} ({:.0} % smaller) with it alone, fitted on the training life's early stages{set}{test}",
                    g.early_before,
                    x.gap,
                    100.0 * x.shrink
                ));
            }
        }
        None if g.early_before >= threshold => f.push(
            "no candidate effect shrinks the held-out early-life gap by 5 % or more".to_string(),
        ),
        None => {}
    }
    f
}

/// Builds the report from a diagnosis.
pub fn output(g: &LifeGap) -> LifeGapOutput {
    let at = &g.attribution;
    LifeGapOutput {
        mode: "lifetime",
        train: g.train.clone(),
        validation: g.validation.clone(),
        test: g.test.clone(),
        holdout: g.holdout.clone(),
        where_: g.cells.clone(),
        stages_train: g.stages_train.clone(),
        stages_holdout: g.stages_holdout.clone(),
        stages_test: g.stages_test.clone(),
        train_span: g.train_span.clone(),
        holdout_spans: g.holdout_spans.clone(),
        ranking: at.ranking.clone(),
        greedy: at.greedy.clone(),
        dropped: at.dropped.clone(),
        exchanged: at.exchanged.clone(),
        kept: at.kept.clone(),
        totals: LifeTotals {
            totals: Totals::of(at),
            test_note: g.test_note.clone(),
        },
        identified: at.identified.clone(),
        tied_with: at.tied_with.clone(),
        early: Early {
            until: lifetime::EARLY_T_MAX,
            before: g.early_before,
            after: g.early_after,
            effects: g.early.clone(),
            closed_by: g.early_effect.clone(),
            noise_only: g.noise_only.1,
            test: g.early_test,
        },
        rig: g.rig.clone(),
        kinematics: g.kinematics,
        life_factor: g.life_factor,
        propagation_passes: g.propagation_passes,
        measured_onset: g.measured_onset,
        simulated_onset: g.simulated_onset,
        simulated_onset_basis: g.simulated_onset_basis.name(),
        measured_revs: g.measured_revs,
        noise_only: g.noise_only.0,
        findings: findings(g),
        leave_one_out: (!g.leave_one_out.is_empty()).then(|| g.leave_one_out.clone()),
        simulations: g.simulations,
        seconds: g.seconds,
        files: vec![],
    }
}

fn stage_table(s: &mut String, title: &str, stages: &[StageGap]) {
    let _ = writeln!(s, "### {title}\n");
    let _ = writeln!(
        s,
        "| stage | life | gap before | gap after | largest cell | simulated | measured | its gap |"
    );
    let _ = writeln!(s, "|---|---|---:|---:|---|---:|---:|---:|");
    for g in stages {
        let _ = writeln!(
            s,
            "| {} | {:.0}–{:.0} % | {:.2} | {:.2} | {} | {:.3} | {:.3} | {:+.2} |",
            g.stage,
            100.0 * g.span.0,
            100.0 * g.span.1,
            g.before,
            g.after,
            g.worst.0,
            g.worst.1,
            g.worst.2,
            g.worst.3
        );
    }
    let _ = writeln!(s);
}

/// One effect at a time: effect, fitted parameters, the held-out gap with it (column
/// `gap`), its shrink.
fn alone_table<'a>(
    s: &mut String,
    gap: &str,
    rows: impl Iterator<Item = (&'a str, &'a [FittedParam], f64, f64)>,
) {
    let _ = writeln!(s, "| effect | parameters | {gap} | shrink |");
    let _ = writeln!(s, "|---|---|---:|---:|");
    for (effect, params, g, shrink) in rows {
        let _ = writeln!(
            s,
            "| {effect} | {} | {g:.2} | {:+.0} % |",
            fmt_params(params),
            100.0 * shrink
        );
    }
}

/// What the lives that chose the model are called: `validation` beside a test part,
/// `held-out` without one (they were also judged).
fn held_word(o: &LifeGapOutput) -> &'static str {
    if o.test.is_empty() {
        "held-out"
    } else {
        roles::VALIDATION
    }
}

/// The roles of the lives, for the report's first lines.
fn roles_line(o: &LifeGapOutput) -> String {
    let mut s = format!("Training life (fitted): {}.", o.train.join(", "));
    if o.test.is_empty() {
        s += &format!(
            " Held-out (chose the model and judged; no separate test part): {}.",
            o.validation.join(", ")
        );
    } else {
        s += &format!(
            " Validation (chose the model): {}. Test (judged only, chose nothing): {}.",
            o.validation.join(", "),
            o.test.join(", ")
        );
    }
    s
}

/// The report as Markdown.
pub fn markdown(o: &LifeGapOutput) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# Sim-to-real gap along a life\n");
    let _ = writeln!(
        s,
        "{} Simulated: {} ({} elements, ball {:.3} mm, pitch {:.3} mm, {:.2}°; {:.1} rpm, {:.0} N; structure: {}; BPFO {:.2} Hz, BPFI {:.2} Hz, natural frequency {:.0} Hz) with the core's stress-driven wear, life factor {:.3e} and propagation limit {:.3e} passes (calibrated on the training life, {:.3e} revolutions, onset of instability at {}).\n",
        roles_line(o),
        o.rig.origin,
        o.rig.elements,
        o.rig.ball_mm,
        o.rig.pitch_mm,
        o.rig.angle_deg,
        60.0 * o.rig.shaft_hz,
        o.rig.radial_load_n,
        o.rig.structure_origin,
        o.kinematics.bpfo,
        o.kinematics.bpfi,
        o.kinematics.natural_hz,
        o.life_factor,
        o.propagation_passes,
        o.measured_revs,
        o.measured_onset
            .map_or("none: the propagation limit is the material's".to_string(), |u| format!("{u:.3} of life"))
    );
    let _ = writeln!(
        s,
        "## Where along life\n\nCells: the steady stage (10–50 % of life) holds the absolute kurtosis, crest factor and skewness; every other stage its contrast to the steady stage (RMS in dB re the steady median, differences of the others). Gap = (simulated − measured) / the measured snapshot-to-snapshot spread of the stage.\n"
    );
    stage_table(&mut s, "Training life", &o.stages_train);
    let chose = if o.test.is_empty() {
        "Held-out lives (chose the model and judged: no separate test part)"
    } else {
        "Validation lives (chose the model)"
    };
    stage_table(&mut s, chose, &o.stages_holdout);
    if !o.test.is_empty() {
        stage_table(
            &mut s,
            "Test lives (judged only, chose nothing)",
            &o.stages_test,
        );
    }
    let _ = writeln!(s, "Largest cells:\n");
    let _ = writeln!(
        s,
        "| life | role | cell | measured | simulated | spread | gap | simulated after | gap after |"
    );
    let _ = writeln!(s, "|---|---|---|---:|---:|---:|---:|---:|---:|");
    for c in o.where_.iter().take(12) {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {:.3} | {:.3} | {:.3} | {:+.2} | {:.3} | {:+.2} |",
            c.record, c.role, c.cell, c.real, c.sim, c.spread, c.gap, c.sim_after, c.gap_after
        );
    }
    let held = held_word(o);
    let _ = writeln!(
        s,
        "\n## Which: each effect alone (fitted on the training life, judged on the {held} lives)\n"
    );
    alone_table(
        &mut s,
        &format!("{held} gap"),
        o.ranking.iter().map(|r| {
            (
                r.effect.as_str(),
                r.params.as_slice(),
                r.holdout_gap,
                r.shrink,
            )
        }),
    );
    let _ = writeln!(
        s,
        "\n### The early-life part (stages before {:.0} % of life)\n\nEach effect fitted on the training life's early stages alone and judged on the {held} lives' early stages (their contrasts to the steady stage).\n",
        100.0 * o.early.until
    );
    alone_table(
        &mut s,
        &format!("{held} early gap"),
        o.early
            .effects
            .iter()
            .map(|e| (e.effect.as_str(), e.params.as_slice(), e.gap, e.shrink)),
    );
    let _ = writeln!(
        s,
        "\nEarly-life gap of the {held} lives {:.2} (baseline; {:.2} by sampling alone) → {:.2} (final model of the whole life); closed by: {}.\n",
        o.early.before,
        o.early.noise_only,
        o.early.after,
        o.early.closed_by.as_deref().unwrap_or("none")
    );
    for e in &o.early.effects {
        let mut notes = vec![];
        if !e.confounded_with.is_empty() {
            notes.push(format!("confounded with {}", e.confounded_with.join(", ")));
        }
        if let (Some(g), Some(ts)) = (e.test_gap, e.test_shrink) {
            notes.push(format!(
                "test early gap {g:.2} ({:.0} % smaller)",
                100.0 * ts
            ));
        }
        if !notes.is_empty() {
            let _ = writeln!(s, "* `{}`: {}", e.effect, notes.join("; "));
        }
    }
    if let Some(t) = &o.early.test {
        let _ = writeln!(
            s,
            "\nTest lives' early-life gap {:.2} (baseline) → {:.2} (the early-life model); nothing was fitted or chosen on them.\n",
            t.before, t.after
        );
    }
    let _ = writeln!(s, "## How far: greedy addition\n");
    greedy_section(&mut s, &o.greedy, &o.dropped, &o.kept);
    let _ = writeln!(
        s,
        "\nTotal {} gap {:.2} → {:.2} ({:.0} % smaller; {:.2} by sampling alone); training life before: {:.2}.",
        if o.test.is_empty() {
            "held-out (chose the model and judged)"
        } else {
            "validation (chose the model, biased upwards)"
        },
        o.totals.totals.before,
        o.totals.totals.after,
        100.0 * o.totals.totals.shrink,
        o.noise_only,
        o.totals.totals.train_before
    );
    let t = &o.totals.totals;
    match (t.test_before, t.test_after, &o.totals.test_note) {
        (Some(b), Some(a), _) => {
            let _ = writeln!(
                s,
                "\n**Total test gap** (chose nothing): {b:.2} → {a:.2} ({:.0} % smaller).",
                100.0 * (1.0 - a / b)
            );
        }
        (_, _, Some(n)) => {
            let _ = writeln!(s, "\n**No test figure**: {n}.");
        }
        _ => {}
    }
    if let Some(loo) = &o.leave_one_out {
        leave_one_out_section(&mut s, loo);
    }
    findings_section(&mut s, &o.findings);
    let _ = writeln!(
        s,
        "\n{} lives simulated in {:.1} s.",
        o.simulations, o.seconds
    );
    s
}

/// Per-snapshot statistic `i` (0 RMS dB re the steady median, 1 kurtosis) of a series.
fn along(pts: &[LifePoint], i: usize) -> Vec<(f64, f64)> {
    let steady = &lifetime::STAGES[lifetime::STEADY];
    let r: Vec<f64> = pts
        .iter()
        .filter(|p| p.t >= steady.lo && p.t < steady.hi)
        .map(|p| p.rms)
        .collect();
    let med = upper_median(r).unwrap_or(1.0).max(1e-300);
    pts.iter()
        .map(|p| {
            let y = if i == 0 {
                20.0 * (p.rms / med).max(1e-12).log10()
            } else {
                p.kurtosis
            };
            (p.t, y)
        })
        .collect()
}

/// Writes plots, `gap.md` and (last) `gap.json`; returns the files.
pub fn write(dir: &Path, o: &LifeGapOutput, g: &LifeGap) -> Result<Vec<PathBuf>, GapError> {
    register_fonts();
    std::fs::create_dir_all(dir)
        .map_err(|err| GapError::input(format!("--out {}: {err}", dir.display())))?;
    let mut files = vec![];
    const HOLD_C: RGBColor = RGBColor(160, 160, 160);
    for (i, name, ylabel) in [
        (0, "gap-life-rms", "RMS (dB re steady median)"),
        (1, "gap-life-kurtosis", "kurtosis"),
    ] {
        let mut ser: Vec<Series> = vec![];
        for (k, (label, pts)) in g.measured.iter().enumerate() {
            let col = if k == 0 { REAL_C } else { HOLD_C };
            ser.push((label.as_str(), col, along(pts, i)));
        }
        for ((label, pts), col) in g.series.iter().zip([BASE_C, FINAL_C]) {
            ser.push((label.as_str(), col, along(pts, i)));
        }
        let title = format!("{ylabel} along life: measured and simulated");
        files.extend(render_lines(
            dir,
            name,
            &title,
            "fraction of life",
            ylabel,
            1.0,
            &ser,
        )?);
    }
    let held = held_word(o);
    let rows: Vec<(String, f64, f64)> = o
        .stages_train
        .iter()
        .map(|s| (format!("train {}", s.stage), s.before, s.after))
        .chain(
            o.stages_holdout
                .iter()
                .map(|s| (format!("{} {}", held, s.stage), s.before, s.after)),
        )
        .chain(
            o.stages_test
                .iter()
                .map(|s| (format!("test {}", s.stage), s.before, s.after)),
        )
        .collect();
    let title = format!(
        "stage gaps: {held} total {:.2} → {:.2}",
        o.totals.totals.before, o.totals.totals.after
    );
    files.extend(render(
        dir,
        "gap-life-stages",
        |r| draw_gap_bars(r, &title, &rows),
        |r| draw_gap_bars(r, &title, &rows),
    )?);
    finish(dir, &markdown(o), files, |f| LifeGapOutput {
        files: f,
        ..o.clone()
    })
}
