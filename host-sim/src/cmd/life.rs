//! `wearsim life`: arguments and the command (one life, or `--lives N` statistics).

use crate::cmd::args::{CliError, Progress};
use crate::config::{self, ScenarioFile};
use crate::life::dense::DenseOptions;
use crate::life::lives::{
    against_published, exponent, run_lives, summarise, Initiation, LoadGroup,
    PUBLISHED_LOAD_EXPONENTS_BALL, PUBLISHED_SLOPES,
};
use crate::life::phases;
use crate::life::weibull::Estimate;
use crate::life::{LifeRun, LifeSpec};
use clap::Args;
use serde_json::json;
use std::path::PathBuf;
use wearsim_core::bearing::ContactKind;
use wearsim_core::wear::LifeConfig;

/// `wearsim life` arguments.
#[derive(Debug, Clone, Args)]
pub struct LifeArgs {
    /// Preset of the bearing and operating point.
    #[arg(long, default_value = config::DEFAULT_PRESET, conflicts_with = "config")]
    pub preset: String,
    /// TOML scenario file (as for `simulate`) instead of a preset.
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// Cycle cap: revolutions within which the bearing must fail, 1..=1e13 (with --lives, a
    /// life still running there ends as a suspension: right-censored, fitted as such).
    #[arg(long, default_value_t = 5.0e7)]
    pub cycles: f64,
    /// Revolutions between snapshots (a vibration window is also rendered at every transition).
    #[arg(long, default_value_t = 20_000.0)]
    pub snapshot_every: f64,
    /// Stream the continuous vibration of the whole life to disk (resumable).
    #[arg(long)]
    pub dense: bool,
    /// Multiplier of the radial load, 0.05..=20: the same bearing and material under a
    /// heavier or lighter load (the wear laws keep the unscaled load's reference pressure).
    #[arg(long, default_value_t = 1.0)]
    pub load_scale: f64,
    /// Film parameter λ (film thickness / composite roughness), 0.05..=20; default 2 (or the
    /// configuration's `[life] lambda`).
    #[arg(long)]
    pub lambda: Option<f64>,
    /// Seed (wear scatter and the windows' random streams).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Window length (s) rendered per snapshot, 0.02..=10.
    #[arg(long, default_value_t = 0.25)]
    pub window: f64,
    /// Output directory.
    #[arg(long, default_value = "wearsim-life")]
    pub out: PathBuf,
    /// Dense mode: stop after this many simulated seconds, leaving a checkpoint; rerun to go on.
    #[arg(long)]
    pub stop_after: Option<f64>,
    /// Machine-readable summary on stdout.
    #[arg(long)]
    pub json: bool,
    /// Switch a candidate effect on: NAME[:PARAM=VALUE,...] (repeatable; see `wearsim effects`).
    #[arg(long = "effect", value_name = "NAME[:PARAM=VALUE,...]")]
    pub effect: Vec<String>,
    /// Life statistics: run this many seeds (from --seed on), 3..=100000, and report the
    /// distribution of lives and onsets, a Weibull fit and ISO 281's L10.
    #[arg(long, conflicts_with = "dense")]
    pub lives: Option<usize>,
    /// With --lives: load scales to run (comma-separated, each 0.05..=20, at most 16, at
    /// least 5 % apart); two or more give the life–load exponent. Default: --load-scale.
    #[arg(long, value_delimiter = ',', requires = "lives")]
    pub loads: Vec<f64>,
    /// With --lives: worker threads, 1 ..= 256 (default: the machine's available parallelism).
    #[arg(long, requires = "lives")]
    pub threads: Option<usize>,
}

impl LifeArgs {
    /// The validated run.
    pub fn run(&self) -> Result<LifeRun, CliError> {
        let mut file = match &self.config {
            Some(p) => ScenarioFile::load(p).map_err(CliError::input)?,
            None => ScenarioFile {
                preset: Some(self.preset.clone()),
                ..Default::default()
            },
        };
        if file.preset.is_none() && self.config.is_none() {
            file.preset = Some(self.preset.clone());
        }
        crate::cmd::args::add_effect_args(&mut file, &self.effect)?;
        let (mut model, _) = file.resolve().map_err(CliError::input)?;
        wearsim_core::error::check_range("load_scale", self.load_scale, 0.05, 20.0)
            .map_err(CliError::input)?;
        // The material's wear limits stay those of the unscaled scenario (see
        // `LifeSpec::calibration_load`).
        let calibration_load = Some(model.radial_load);
        model.radial_load *= self.load_scale;
        let d = LifeConfig::DEFAULT;
        let ls = file.life.clone().unwrap_or_default();
        let material = file
            .material
            .as_ref()
            .map(|m| m.apply(d.material))
            .unwrap_or(d.material);
        let life = LifeConfig {
            material,
            lambda: self.lambda.or(ls.lambda).unwrap_or(d.lambda),
            roughness: ls.roughness.unwrap_or(d.roughness),
            running_in: ls.running_in.unwrap_or(d.running_in),
            slip: ls.slip.unwrap_or(d.slip),
            cycle_cap: self.cycles,
        };
        let spec = LifeSpec {
            model,
            life,
            seed: self.seed,
            snapshot_every: self.snapshot_every,
            window: self.window,
            settle: 0.05,
            calibration_load,
        };
        LifeRun::new(spec).map_err(CliError::input)
    }
}

/// Runs `wearsim life`.
pub fn life_cmd(a: &LifeArgs) -> Result<(), CliError> {
    if a.stop_after.is_some() && !a.dense {
        return Err(CliError::input("--stop-after applies to --dense runs only"));
    }
    if let Some(n) = a.lives {
        return lives_cmd(a, n);
    }
    let run = a.run()?;
    // Exclusive, writable output directory before any work (docs/reliability.md).
    let _lock = crate::io::lock::DirLock::try_acquire(&a.out).map_err(CliError::input)?;
    let bar = Progress::new(
        !a.json && std::io::IsTerminal::is_terminal(&std::io::stderr()),
        "life",
    );
    let cap = a.cycles;
    let update = |c: f64, _: f64| bar.update((c.min(cap) / cap * 1000.0) as usize, 1000);
    let extra = json!({ "preset": a.preset, "config": a.config, "load_scale": a.load_scale, "lambda": a.lambda, "mode": if a.dense { "dense" } else { "snapshot" } });
    let mut event_windows = vec![];
    let (snapshots, state, wall, windows, dense_info) = if a.dense {
        let r = run
            .run_dense(
                &DenseOptions {
                    dir: a.out.clone(),
                    stop_after: a.stop_after,
                },
                update,
            )
            .map_err(|e| match e {
                crate::life::dense::DenseError::Life(l) => life_error(l),
                other => CliError::input(other),
            })?;
        bar.finish();
        if !r.complete {
            let msg = json!({ "complete": false, "samples": r.samples, "generated": r.generated, "cycles": r.state.cycles, "resumed": r.resumed,
                "wall_s": r.wall_s, "samples_per_s": r.generated as f64 / r.wall_s.max(1e-9),
                "note": "stopped with a checkpoint; rerun the same command to continue" });
            if a.json {
                crate::cmd::report::print_json(&msg)?;
            } else {
                println!("dense run stopped at {} samples ({:.0} revolutions); rerun the same command to continue", r.samples, r.state.cycles);
            }
            return Ok(());
        }
        let info = json!({ "samples": r.samples, "generated": r.generated, "resumed": r.resumed, "samples_per_s": r.generated as f64 / r.wall_s.max(1e-9), "fs": r.fs });
        (r.snapshots, r.state, r.wall_s, 0usize, Some(info))
    } else {
        let r = run.run_snapshots(update).map_err(life_error)?;
        bar.finish();
        event_windows = r.event_windows;
        (r.snapshots, r.state, r.wall_s, r.windows, None)
    };
    let extra = json!({ "args": extra, "wall_s": wall, "windows": windows, "dense": dense_info });
    let timeline = crate::life::output::timeline(&state);
    let title = format!(
        "normalised RMS over life: {} (seed {})",
        a.config
            .as_ref()
            .map(|p| p.display().to_string())
            .unwrap_or(a.preset.clone()),
        a.seed
    );
    std::fs::create_dir_all(&a.out)
        .map_err(|e| CliError::input(format!("{}: {e}", a.out.display())))?;
    let mut plots =
        crate::life::plot::life_rms(&a.out, &snapshots, &timeline, state.cycles.max(1.0), &title)?;
    let base = wearsim_core::Model::new_checked(wearsim_core::ModelConfig {
        defect: None,
        ..run.spec.model.clone()
    })
    .map_err(CliError::input)?;
    let f_site = run
        .life
        .site()
        .pass_frequency_hz(&base.frequencies_at(run.shaft_hz));
    plots.extend(crate::life::plot::events(
        &a.out,
        &event_windows,
        base.config().output_rate,
        f_site,
        base.natural_frequency_hz(),
    )?);
    // The summary is written last: its presence means the set is complete.
    let mut files =
        crate::life::output::write_life(&a.out, &run, &snapshots, &state, extra.clone())
            .map_err(|e| CliError::run(format!("{}: {e}", a.out.display())))?;
    files.extend(plots);
    if a.json {
        let v = json!({
            "complete": true,
            "cycles_to_failure": state.cycles,
            "site": crate::life::site_json::site_json(&run),
            "timeline": timeline,
            "events": state.events.iter().map(crate::life::state_json::EventJson::from).collect::<Vec<_>>(),
            "snapshots": snapshots.len(),
            "wall_s": wall,
            "windows": windows,
            "dense": dense_info,
            "files": files,
            "units": crate::life::output::units(),
        });
        crate::cmd::report::print_json(&v)?;
    } else {
        println!(
            "life to failure: {:.0} revolutions ({:.2} h at {:.2} Hz); {} snapshots in {:.2} s",
            state.cycles,
            state.cycles / run.shaft_hz / 3600.0,
            run.shaft_hz,
            snapshots.len(),
            wall
        );
        println!(
            "{:<20} {:>14} {:>14} {:>8}",
            "stage", "start (rev)", "end (rev)", "share"
        );
        for s in &timeline {
            println!(
                "{:<20} {:>14.0} {:>14.0} {:>7.1}%",
                s.stage,
                s.start,
                s.end,
                100.0 * (s.end - s.start) / state.cycles.max(1.0)
            );
        }
        for f in &files {
            println!("wrote {}", f.display());
        }
    }
    Ok(())
}

fn life_error(e: crate::life::LifeError) -> CliError {
    match e {
        crate::life::LifeError::CapReached { .. }
        | crate::life::LifeError::Unloaded { .. }
        | crate::life::LifeError::Config(_)
        | crate::life::LifeError::SnapshotInterval { .. } => CliError::input(e),
        crate::life::LifeError::WindowCap { .. } => CliError::input(format!(
            "{e}: --snapshot-every is too small for this life (at most {} windows per life); raise it",
            crate::life::MAX_LIFE_WINDOWS
        )),
        crate::life::LifeError::Interrupted => CliError::interrupted(),
        other => CliError::run(other),
    }
}

/// Most load scales one `life --lives` run takes: each runs all its lives (a probe's
/// 1000 loads started 1000 × N lives), and an exponent needs two to a handful.
pub const MAX_LOADS: usize = 16;

/// Smallest ratio between two load scales of one run: the life–load exponent is a slope
/// over ln(load), and `--loads 1,1.000001` gave an interval of [−3·10⁵, 3·10⁵]. At 5 %
/// apart and a Weibull slope of 1.5, 100 000 lives per load leave the exponent a standard
/// error of about 0.07; 1 000 lives, about 0.7.
pub const MIN_LOAD_RATIO: f64 = 1.05;

/// `wearsim life --lives N`: life statistics over many seeds (see [`crate::life::lives`]).
pub fn lives_cmd(a: &LifeArgs, n: usize) -> Result<(), CliError> {
    if !(3..=100_000).contains(&n) {
        return Err(CliError::input(format!(
            "lives: {n} is out of range; allowed 3..=100000"
        )));
    }
    let scales = if a.loads.is_empty() {
        vec![a.load_scale]
    } else {
        a.loads.clone()
    };
    if scales.len() > MAX_LOADS {
        return Err(CliError::input(format!(
            "loads: {} load scales given; at most {MAX_LOADS} (each runs --lives lives)",
            scales.len()
        )));
    }
    for (i, s) in scales.iter().enumerate() {
        wearsim_core::error::check_range("loads", *s, 0.05, 20.0).map_err(CliError::input)?;
        if scales[..i].contains(s) {
            return Err(CliError::input(format!(
                "loads: {s} is given twice; each load scale runs once (two or more different ones give the life–load exponent)"
            )));
        }
        if let Some(o) = scales[..i]
            .iter()
            .find(|o| (s / *o).max(*o / s) < MIN_LOAD_RATIO)
        {
            return Err(CliError::input(format!(
                "loads: {s} and {o} differ by less than {:.0} %; the exponent is a slope over ln(load), and the lives' scatter swamps it at loads this close: use loads at least {:.0} % apart, e.g. 0.5,1,2",
                (MIN_LOAD_RATIO - 1.0) * 100.0,
                (MIN_LOAD_RATIO - 1.0) * 100.0
            )));
        }
    }
    let threads = crate::lanes::workers("--threads", a.threads).map_err(CliError::input)?;
    let _lock = crate::io::lock::DirLock::try_acquire(&a.out).map_err(CliError::input)?;
    // A set left by an earlier run stops being presented as complete: its marker is written
    // again only when this run's files are all in place (a killed rerun left the old
    // lives.json beside this run's lives.csv, or beside nothing of this run).
    use crate::life::output::{remove_marker, LIVES_SUMMARY};
    remove_marker(&a.out, LIVES_SUMMARY)
        .map_err(|e| CliError::input(format!("{}: {e}", a.out.display())))?;
    let t0 = std::time::Instant::now();
    let bar = Progress::new(
        !a.json && std::io::IsTerminal::is_terminal(&std::io::stderr()),
        "lives",
    );
    let total = n * scales.len();
    let mut groups: Vec<LoadGroup> = vec![];
    let mut site = serde_json::Value::Null;
    let mut point = true;
    for (gi, scale) in scales.iter().enumerate() {
        let mut specs = vec![];
        let mut iso = (0.0, 0.0);
        for i in 0..n {
            let mut args = a.clone();
            args.load_scale = *scale;
            args.seed = a.seed.wrapping_add(i as u64);
            let run = args.run()?;
            if i == 0 && gi == 0 {
                site = crate::life::site_json::site_json(&run);
            }
            if i == 0 {
                point = run.life.contact_kind() == ContactKind::Point;
                let p = if point { 3.0 } else { 10.0 / 3.0 };
                let load = run.spec.model.radial_load;
                iso = (load, (run.life.rating() / load).powf(p) * 1e6);
            }
            specs.push(run.spec);
        }
        let done0 = gi * n;
        let lives =
            run_lives(specs, threads, &|d| bar.update(done0 + d, total)).map_err(|(seed, e)| {
                // Which of the lives: a cap that one load scale or one seed's scatter does
                // not reach is otherwise not told from the others.
                let c = life_error(e);
                CliError {
                    message: format!("load scale {scale}, seed {seed}: {}", c.message),
                    ..c
                }
            })?;
        groups.push(summarise(*scale, iso.0, iso.1, lives));
    }
    bar.finish();
    crate::cancel::check()?;
    let wall = t0.elapsed().as_secs_f64();
    let exp = exponent(&groups, false);
    let exp_spall = exponent(&groups, true);
    let shares: Vec<_> = groups.iter().map(|g| (g.load_n, g.phases)).collect();
    let (crack_trend, post_trend) = (
        phases::crack_trend(&shares),
        phases::post_spall_trend(&shares),
    );
    std::fs::create_dir_all(&a.out)
        .map_err(|e| CliError::input(format!("{}: {e}", a.out.display())))?;
    let mut csv = String::from(
        "load_scale,seed,life_revs,suspended,first_spall_revs,initiation,onset_fraction,wall_s\n",
    );
    let opt = |x: Option<f64>| x.map(|o| o.to_string()).unwrap_or_default();
    for g in &groups {
        for l in &g.lives {
            csv.push_str(&format!(
                "{},{},{},{},{},{},{},{}\n",
                g.load_scale,
                l.seed,
                l.life,
                l.suspended,
                opt(l.first_spall),
                l.initiation.map_or("", |i| i.name()),
                opt(l.onset),
                l.wall_s
            ));
        }
    }
    let summary = json!({
        "lives_per_load": n,
        "cycle_cap": a.cycles,
        "site": site,
        "threads": threads,
        "wall_s": wall,
        "groups": groups.iter().map(group_json).collect::<Vec<_>>(),
        "load_exponent": exp,
        "first_spall_load_exponent": exp_spall,
        "load_exponent_note": (exp.is_none() || exp_spall.is_none()).then(|| if groups.len() < 2 {
            "an exponent needs --loads with two or more loads".to_string()
        } else {
            "an exponent needs at least two loads whose lives (to failure, or to the first spall) hold three failures each: see groups[].no_fit".to_string()
        }),
        "load_exponent_iso": [-3.0, -10.0 / 3.0],
        "load_exponent_published": if point {
            PUBLISHED_LOAD_EXPONENTS_BALL.iter().map(|(v, s)| json!({"exponent": v, "source": s})).collect::<Vec<_>>()
        } else {
            vec![json!({"exponent": -10.0 / 3.0, "source": "ISO 281, line contact"})]
        },
        "load_exponent_against_published": exp.as_ref().and_then(|e| against_published(e, point)),
        "first_spall_load_exponent_against_published": exp_spall.as_ref().and_then(|e| against_published(e, point)),
        "crack_share_trend": crack_trend,
        "post_spall_share_trend": post_trend,
        "published_slopes": PUBLISHED_SLOPES.iter().map(|(v, s)| json!({"slope": v, "source": s})).collect::<Vec<_>>(),
        "note": "the core draws four independent scatter factors per seed: subsurface fatigue, surface damage (the dent) and surface crack initiation at the dent from Weibulls of slope 1.11 (ISO 281's 10/9, Lundberg-Palmgren), spall propagation from one of slope 1.1 (Hoeprich 1992); the fitted slopes are those inputs combined through the stages (competing surface and subsurface initiation, then propagation), not independent predictions. Published slopes are of endurance tests stopped at the first spall: compare them with first_spall.weibull",
    });
    let cp = a.out.join("lives.csv");
    crate::life::output::write_atomic(&cp, csv.as_bytes())
        .map_err(|e| CliError::run(format!("{}: {e}", cp.display())))?;
    let plots = crate::life::weibull_plot::lives_weibull(&a.out, &groups)?;
    // The summary is written last: its presence means the set is complete.
    let jp = a.out.join(LIVES_SUMMARY);
    crate::life::output::write_atomic(
        &jp,
        &serde_json::to_vec_pretty(&summary).map_err(CliError::run)?,
    )
    .map_err(|e| CliError::run(format!("{}: {e}", jp.display())))?;
    if a.json {
        crate::cmd::report::print_json(&summary)?;
        return Ok(());
    }
    let est = |e: &Estimate| format!("{:.4} [{:.4}, {:.4}]", e.value, e.lo, e.hi);
    println!("{n} lives per load on {threads} threads in {wall:.1} s");
    for g in &groups {
        println!(
            "load ×{} ({:.0} N): ISO 281 L10 {:.4e} rev",
            g.load_scale, g.load_n, g.iso_l10
        );
        let suspended = g.lives.iter().filter(|l| l.suspended).count();
        if suspended > 0 {
            println!(
                "  {suspended} of {} lives did not fail within the cycle cap ({:.3e} rev): fitted as suspensions",
                g.lives.len(),
                a.cycles
            );
        }
        for (what, fit) in [
            ("to failure", &g.weibull),
            ("to the first spall", &g.first_spall_weibull),
        ] {
            match fit {
                Some(w) => println!(
                    "  {what}: Weibull slope {}; L10 {} rev (×{:.3} ISO); η {}",
                    est(&w.shape),
                    est(&w.l10),
                    w.l10.value / g.iso_l10,
                    est(&w.scale)
                ),
                None => println!(
                    "  {what}: no Weibull fit: it needs 3 lives that reach it within the cycle cap ({:.3e} rev; raise --cycles) and not all alike",
                    a.cycles
                ),
            }
        }
        let failed = g.lives.len() - suspended;
        println!(
            "  onset of instability: median {} over {} of {failed} failed lives{}",
            g.onset_median
                .map_or("none".to_string(), |o| format!("{o:.3} of life")),
            g.onset_found,
            if g.onset_found < failed {
                // The rule (`life::ims::onset`) needs a steady band before the rise.
                format!(
                    "; {} without one: no rise that stays above the steady band after the first quarter of the life, a rise inside that quarter (the band's baseline), or fewer than {} windows in it (a smaller --snapshot-every gives more)",
                    failed - g.onset_found,
                    crate::life::ims::MIN_BASELINE
                )
            } else {
                String::new()
            }
        );
        for (s, f) in &g.stage_onsets {
            println!("  {s:<20} median onset {f:.3} of life (failed lives)");
        }
        let p = &g.phases;
        for (what, e, of) in [
            (
                "crack share of the life to the first spall",
                p.crack,
                p.crack_lives,
            ),
            (
                "post-spall share of the life to failure",
                p.post_spall,
                p.post_spall_lives,
            ),
        ] {
            if let Some(e) = e {
                println!("  {what}: median {} over {of} lives", est(&e));
            }
        }
    }
    for (what, t) in [
        ("crack share", &crack_trend),
        ("post-spall share", &post_trend),
    ] {
        if let Some(t) = t {
            println!(
                "{what} from {:.0} N to {:.0} N: {:?}{}",
                t.loads_n[0],
                t.loads_n[1],
                t.direction,
                match (t.published, t.agrees) {
                    (Some(p), Some(a)) => format!(
                        " — published {p:?}: {}",
                        if a { "agrees" } else { "disagrees" }
                    ),
                    (Some(p), None) => format!(" — published {p:?}: no direction to compare"),
                    _ => String::new(),
                }
            );
            println!("  ({})", t.source);
        }
    }
    for (what, e) in [("to failure", exp), ("to the first spall", exp_spall)] {
        match e {
            Some(e) => {
                println!(
                    "life–load exponent {what} {} (ISO 281: −3 ball, −10/3 roller)",
                    est(&e)
                );
                if let Some(r) = against_published(&e, point) {
                    println!(
                        "  against the published ball-bearing range [{}, {}]: value {}, interval {}",
                        r.range[0],
                        r.range[1],
                        if r.value_inside { "inside" } else { "outside" },
                        if r.interval_inside {
                            "inside"
                        } else if r.interval_overlaps {
                            "overlaps it"
                        } else {
                            "outside"
                        }
                    );
                }
            }
            None => println!("life–load exponent {what}: needs --loads with two or more loads"),
        }
    }
    for (v, s) in PUBLISHED_SLOPES {
        println!("published slope {v:.3}: {s}");
    }
    if point {
        for (v, s) in PUBLISHED_LOAD_EXPONENTS_BALL {
            println!("published life–load exponent {v}: {s}");
        }
    }
    for f in plots.iter().chain([&cp, &jp]) {
        println!("wrote {}", f.display());
    }
    Ok(())
}

/// Why a group's Weibull fit is `null`: `k` of `n` lives give the fit's data, and a fit
/// needs three failures ([`crate::life::weibull::fit_units`]) that are not all equal.
fn no_fit(k: usize, n: usize, what: &str) -> String {
    if k < 3 {
        format!("{k} of {n} {what}: a Weibull fit needs at least 3 (the rest are suspensions at --cycles)")
    } else {
        format!("{k} of {n} {what}, all at one time: no Weibull fit")
    }
}

fn group_json(g: &LoadGroup) -> serde_json::Value {
    let failed = g.lives.iter().filter(|l| !l.suspended).count();
    let spalled = g.lives.iter().filter(|l| l.first_spall.is_some()).count();
    let lives: Vec<f64> = g.lives.iter().map(|l| l.life).collect();
    let (mn, mx) = lives
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(*x), b.max(*x)));
    json!({
        "load_scale": g.load_scale, "load_n": g.load_n, "iso_l10_revs": g.iso_l10,
        "weibull": g.weibull, "l10_over_iso": g.weibull.as_ref().map(|w| w.l10.value / g.iso_l10),
        "no_fit": g.weibull.is_none().then(|| no_fit(failed, g.lives.len(), "failures")),
        "first_spall": {
            "weibull": g.first_spall_weibull,
            "l10_over_iso": g.first_spall_weibull.as_ref().map(|w| w.l10.value / g.iso_l10),
            "reached": spalled,
            "no_fit": g.first_spall_weibull.is_none().then(|| no_fit(spalled, g.lives.len(), "lives reached the first spall")),
        },
        "initiation": {
            "surface": g.lives.iter().filter(|l| l.initiation == Some(Initiation::Surface)).count(),
            "subsurface": g.lives.iter().filter(|l| l.initiation == Some(Initiation::Subsurface)).count(),
        },
        "failed": failed,
        "suspended": g.lives.iter().filter(|l| l.suspended).count(),
        "life_min": mn, "life_max": mx, "onset_median": g.onset_median, "onset_found": g.onset_found,
        "stage_onsets": g.stage_onsets,
        "phases": g.phases,
        "mean_wall_s_per_life": g.lives.iter().map(|l| l.wall_s).sum::<f64>() / g.lives.len().max(1) as f64,
    })
}
