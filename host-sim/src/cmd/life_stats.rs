//! `wearsim life --lives N`: life statistics over many seeds (see [`crate::life::lives`]).

use super::life::{life_error, LifeArgs};
use crate::cli::{CliError, Progress};
use crate::life::lives::{exponent, run_lives, summarise, LoadGroup, PUBLISHED_SLOPES};
use crate::life::weibull::Estimate;
use serde_json::json;
use wearsim_core::bearing::ContactKind;

/// Runs `wearsim life --lives N`.
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
    for s in &scales {
        wearsim_core::error::check_range("loads", *s, 0.05, 20.0).map_err(CliError::input)?;
    }
    let threads = match a.threads {
        Some(t) if (1..=256).contains(&t) => t,
        Some(t) => {
            return Err(CliError::input(format!(
                "threads: {t} is out of range; allowed 1..=256"
            )))
        }
        None => std::thread::available_parallelism().map_or(1, |p| p.get()),
    };
    let _lock = crate::io::lock::DirLock::try_acquire(&a.out).map_err(CliError::input)?;
    let t0 = std::time::Instant::now();
    let bar = Progress::new(
        !a.json && std::io::IsTerminal::is_terminal(&std::io::stderr()),
        "lives",
    );
    let total = n * scales.len();
    let mut groups: Vec<LoadGroup> = vec![];
    for (gi, scale) in scales.iter().enumerate() {
        let mut specs = vec![];
        let mut iso = (0.0, 0.0);
        for i in 0..n {
            let mut args = a.clone();
            args.load_scale = *scale;
            args.seed = a.seed.wrapping_add(i as u64);
            let run = args.run()?;
            if i == 0 {
                let p = if run.life.contact_kind() == ContactKind::Point {
                    3.0
                } else {
                    10.0 / 3.0
                };
                let load = run.spec.model.radial_load;
                iso = (load, (run.life.rating() / load).powf(p) * 1e6);
            }
            specs.push(run.spec);
        }
        let done0 = gi * n;
        let lives =
            run_lives(specs, threads, &|d| bar.update(done0 + d, total)).map_err(life_error)?;
        groups.push(summarise(*scale, iso.0, iso.1, lives));
    }
    bar.finish();
    let wall = t0.elapsed().as_secs_f64();
    let exp = exponent(&groups);
    std::fs::create_dir_all(&a.out)
        .map_err(|e| CliError::input(format!("{}: {e}", a.out.display())))?;
    let mut csv = String::from("load_scale,seed,life_revs,onset_fraction,wall_s\n");
    for g in &groups {
        for l in &g.lives {
            csv.push_str(&format!(
                "{},{},{},{},{}\n",
                g.load_scale,
                l.seed,
                l.life,
                l.onset.map(|o| o.to_string()).unwrap_or_default(),
                l.wall_s
            ));
        }
    }
    let summary = json!({
        "lives_per_load": n,
        "threads": threads,
        "wall_s": wall,
        "groups": groups.iter().map(group_json).collect::<Vec<_>>(),
        "load_exponent": exp,
        "load_exponent_iso": [-3.0, -10.0 / 3.0],
        "published_slopes": PUBLISHED_SLOPES.iter().map(|(v, s)| json!({"slope": v, "source": s})).collect::<Vec<_>>(),
        "note": "the core draws each seed's fatigue scatter from a Weibull of slope 1.11 (ISO 281's 10/9): the fitted slope is that input diluted by the deterministic parts of the life, not an independent prediction",
    });
    let cp = a.out.join("lives.csv");
    crate::life::output::write_atomic(&cp, csv.as_bytes())
        .map_err(|e| CliError::run(format!("{}: {e}", cp.display())))?;
    // The summary is written last: its presence means the set is complete.
    let jp = a.out.join("lives.json");
    crate::life::output::write_atomic(
        &jp,
        &serde_json::to_vec_pretty(&summary).unwrap_or_default(),
    )
    .map_err(|e| CliError::run(format!("{}: {e}", jp.display())))?;
    if a.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&summary).unwrap_or_default()
        );
        return Ok(());
    }
    let est = |e: &Estimate| format!("{:.4} [{:.4}, {:.4}]", e.value, e.lo, e.hi);
    println!("{n} lives per load on {threads} threads in {wall:.1} s");
    for g in &groups {
        println!(
            "load ×{} ({:.0} N): ISO 281 L10 {:.4e} rev",
            g.load_scale, g.load_n, g.iso_l10
        );
        match &g.weibull {
            Some(w) => println!(
                "  Weibull slope {}; L10 {} rev (×{:.3} ISO); η {}",
                est(&w.shape),
                est(&w.l10),
                w.l10.value / g.iso_l10,
                est(&w.scale)
            ),
            None => println!("  Weibull fit: not possible (degenerate lives)"),
        }
        println!(
            "  onset of instability: median {} over {} of {} lives",
            g.onset_median
                .map_or("none".to_string(), |o| format!("{o:.3} of life")),
            g.onset_found,
            g.lives.len()
        );
        for (s, f) in &g.stage_onsets {
            println!("  {s:<20} median onset {f:.3} of life");
        }
    }
    match exp {
        Some(e) => println!(
            "life–load exponent {} (ISO 281: −3 ball, −10/3 roller)",
            est(&e)
        ),
        None => println!("life–load exponent: needs --loads with two or more loads"),
    }
    for (v, s) in PUBLISHED_SLOPES {
        println!("published slope {v:.3}: {s}");
    }
    println!("wrote {}\nwrote {}", cp.display(), jp.display());
    Ok(())
}

fn group_json(g: &LoadGroup) -> serde_json::Value {
    let lives: Vec<f64> = g.lives.iter().map(|l| l.life).collect();
    let (mn, mx) = lives
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(*x), b.max(*x)));
    json!({
        "load_scale": g.load_scale, "load_n": g.load_n, "iso_l10_revs": g.iso_l10,
        "weibull": g.weibull, "l10_over_iso": g.weibull.as_ref().map(|w| w.l10.value / g.iso_l10),
        "life_min": mn, "life_max": mx, "onset_median": g.onset_median, "onset_found": g.onset_found,
        "stage_onsets": g.stage_onsets,
        "mean_wall_s_per_life": g.lives.iter().map(|l| l.wall_s).sum::<f64>() / g.lives.len().max(1) as f64,
    })
}
