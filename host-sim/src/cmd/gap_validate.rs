//! `wearsim gap-validate`: arguments, the run, and the printed confusion matrix.

use crate::cmd::args::{CliError, Progress};
use crate::cmd::report::print_json;
use crate::gap::nuisance::Tolerances;
use crate::gap::twin::Mismatch;
use crate::gap::validate::{validate, TwinOptions, TwinReport};
use clap::Args;

/// `wearsim gap-validate` arguments.
#[derive(Debug, Clone, Args)]
pub struct GapValidateArgs {
    /// Trials per effect, 1..=1000 (the acceptance uses ≥ 20).
    #[arg(long, default_value_t = 20)]
    pub trials: usize,
    /// Effects to withhold, comma-separated (default: every effect of `wearsim effects`).
    #[arg(long, value_delimiter = ',')]
    pub effects: Vec<String>,
    /// Additional trials withholding two effects at once.
    #[arg(long, default_value_t = 0)]
    pub pairs: usize,
    /// Additional twins with no effect withheld (false-attribution rate).
    #[arg(long, default_value_t = 0)]
    pub null: usize,
    /// Additional trials withholding three effects at once.
    #[arg(long, default_value_t = 0)]
    pub triples: usize,
    /// Additional twins with a mechanism outside the library (a gear mesh): the rate at
    /// which the report says the library does not close the gap.
    #[arg(long, default_value_t = 0)]
    pub outside: usize,
    /// Twins equal to the baseline apart from the withheld effects (the best case);
    /// by default their structure, defect size, load and speed differ from it by
    /// realistic random amounts the diagnosis does not know.
    #[arg(long)]
    pub no_mismatch: bool,
    /// Do not calibrate the rig (resonance, damping, defect size, load, speed within their
    /// tolerances) on the training run before ranking effects: the diagnosis as it was
    /// before the calibration, for comparison.
    #[arg(long)]
    pub no_calibration: bool,
    /// At each greedy step, refit the effects already added with the candidate on (one
    /// backfitting round; an experiment, off by default: see
    /// `docs/sim-to-real-results.md`, "Pairs of effects").
    #[arg(long)]
    pub backfit: bool,
    /// Keep the rig's calibration made with no effect through the greedy addition instead
    /// of calibrating it again after each addition with the effects kept so far (the
    /// diagnosis as it was before, for comparison: `docs/sim-to-real-results.md`, "The
    /// rig calibrated again at each greedy step").
    #[arg(long)]
    pub fixed_calibration: bool,
    /// After the greedy additions, try exchanging each kept effect for each effect not
    /// yet tried, the others refitted on top (`gap::exchange`; an experiment, off by
    /// default for its cost: `docs/sim-to-real-results.md`, "Exchanges after the greedy
    /// additions").
    #[arg(long)]
    pub exchange: bool,
    /// Seed of the parameter draws and realisations.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Length of each twin run (training, held-out, strength) (s), 0.5..=10.
    #[arg(long, default_value_t = 1.0)]
    pub half: f64,
    /// White measurement noise added to the twins, fraction of their RMS, 0..=0.5.
    #[arg(long, default_value_t = 0.01)]
    pub noise: f64,
    /// Worker threads, 1 ..= 256 (default: all cores).
    #[arg(long)]
    pub jobs: Option<usize>,
    /// Machine-readable report on stdout.
    #[arg(long)]
    pub json: bool,
}

impl GapValidateArgs {
    /// Checked options.
    pub fn options(&self) -> Result<TwinOptions, CliError> {
        if !(1..=1000).contains(&self.trials) {
            return Err(CliError::input(format!(
                "--trials {} is out of range 1..=1000",
                self.trials
            )));
        }
        if self.null > 1000 {
            return Err(CliError::input(format!(
                "--null {} is out of range 0..=1000",
                self.null
            )));
        }
        for (name, v) in [
            ("--pairs", self.pairs),
            ("--triples", self.triples),
            ("--outside", self.outside),
        ] {
            if v > 1000 {
                return Err(CliError::input(format!(
                    "{name} {v} is out of range 0..=1000"
                )));
            }
        }
        if !(self.half.is_finite() && (0.5..=10.0).contains(&self.half)) {
            return Err(CliError::input(format!(
                "--half {} s is out of range 0.5..=10",
                self.half
            )));
        }
        if !(self.noise.is_finite() && (0.0..=0.5).contains(&self.noise)) {
            return Err(CliError::input(format!(
                "--noise {} is out of range 0..=0.5 (fraction of the RMS)",
                self.noise
            )));
        }
        let jobs = crate::lanes::workers("--jobs", self.jobs).map_err(CliError::input)?;
        crate::effects::check_listed(&self.effects, "--effects").map_err(CliError::input)?;
        // Trials of k withheld effects need k effects to draw from: with fewer listed they
        // would be skipped without a word (`"pairs": null`).
        for (name, v, k) in [("--pairs", self.pairs, 2), ("--triples", self.triples, 3)] {
            let listed = self.effects.len();
            if v > 0 && listed > 0 && listed < k {
                return Err(CliError::input(format!(
                    "{name} {v} withholds {k} effects at once: --effects lists {listed} (give at least {k}, or none for all)"
                )));
            }
        }
        Ok(TwinOptions {
            trials: self.trials,
            effects: self.effects.clone(),
            pair_trials: self.pairs,
            triple_trials: self.triples,
            outside_trials: self.outside,
            mismatch: if self.no_mismatch {
                Mismatch::NONE
            } else {
                Mismatch::RIG
            },
            calibrate: if self.no_calibration {
                Tolerances::NONE
            } else {
                Tolerances::CALIBRATE
            },
            null_trials: self.null,
            seed: self.seed,
            half_s: self.half,
            noise: self.noise,
            jobs,
            backfit: self.backfit,
            fixed_calibration: self.fixed_calibration,
            exchange: self.exchange,
        })
    }
}

/// Prints the report as a table.
pub fn print(r: &TwinReport) {
    println!("twin experiments: {}; mismatch {}", r.scenario, r.mismatch);
    println!(
        "noise-only held-out gap (median): {:.2}; {} simulations in {:.1} s",
        r.noise_only_gap, r.simulations, r.seconds
    );
    println!();
    println!(
        "{:<18} {:>6} {:>6} {:>7} {:>10} {:>13} {:>14} {:>8}",
        "withheld",
        "trials",
        "top-1",
        "rate",
        "top-1 class",
        "median shrink",
        "after / noise",
        "detectable"
    );
    for e in &r.rates {
        println!(
            "{:<18} {:>6} {:>6} {:>6.0}% {:>10} {:>12.0}% {:>14.2} {:>8}",
            e.effect,
            e.trials,
            e.top1,
            100.0 * e.rate,
            e.top1_class,
            100.0 * e.median_shrink,
            e.median_after_over_noise,
            e.detectable
        );
    }
    println!();
    println!("confusion (rows: withheld; columns: ranked first)");
    let short = |s: &str| s.chars().take(6).collect::<String>();
    print!("{:<18}", "");
    for c in &r.columns {
        print!(" {:>6}", short(c));
    }
    println!();
    for (l, row) in r.labels.iter().zip(&r.confusion) {
        print!("{l:<18}");
        for v in row {
            print!(" {v:>6}");
        }
        println!();
    }
    println!();
    for e in &r.rates {
        println!(
            "{:<18} truth inside the reported set {:>3}/{} (detectable {:>3}/{}), mean set size {:.2} (detectable {:.2})",
            e.effect,
            e.in_set,
            e.trials,
            e.in_set_detectable,
            e.detectable,
            e.mean_set_size,
            e.mean_set_size_detectable
        );
    }
    println!();
    println!(
        "detection power against strength (gap of an independent run to the twin without what was withheld / noise-only gap):"
    );
    for b in &r.power {
        println!(
            "  strength >= {:>4.1}: truth inside the reported set {:>3}/{}",
            b.from, b.in_set, b.trials
        );
    }
    if let Some((n, named)) = r.null {
        println!(
            "no effect withheld ({n} trials): attributed to an effect {named} ({:.0} %)",
            100.0 * named as f64 / n.max(1) as f64
        );
    }
    if let Some(t) = r.null_threshold {
        println!(
            "  their 5 % false-alarm level (95th percentile of their held-out gaps, rounded up to 0.1): {t:.1} (in force: {:.1}; `gap --significant-gap`)",
            crate::gap::attribute::SIGNIFICANT_GAP
        );
    }
    if let Some((n, open)) = r.outside {
        println!(
            "mechanism outside the library ({n} trials): reported as not closed by the library {open} ({:.0} %)",
            100.0 * open as f64 / n.max(1) as f64
        );
    }
    if let Some((n, all)) = r.triples {
        println!(
            "three effects withheld ({n} trials): all three added by the greedy steps {:.0} %",
            100.0 * all
        );
    }
    if let Some((n, any, both)) = r.pairs {
        println!();
        println!(
            "two effects withheld ({n} trials): first-ranked is one of them {:.0} %, both added by the greedy step {:.0} %",
            100.0 * any,
            100.0 * both
        );
    }
    for (k, d) in [("two", r.pairs_detectable), ("three", r.triples_detectable)] {
        if let Some((n, named)) = d {
            println!(
                "{k} effects withheld, each detectable on its own ({n} trials): all named {named} ({:.0} %)",
                100.0 * named as f64 / n.max(1) as f64
            );
        }
    }
    if let Some((n, in_sets, size)) = r.pairs_in_sets_detectable {
        println!(
            "two effects withheld, each detectable on its own ({n} trials): both inside the two additions' reported sets {in_sets} ({:.0} %), mean set size {size:.2}",
            100.0 * in_sets as f64 / n.max(1) as f64
        );
    }
    println!();
    println!("confounded sets at other angles (detectable single-effect trials):");
    for a in &r.set_angles {
        println!(
            "  {:>4.1}°: truth in set {}/{}, worst effect {:.0} %, largest mean set size {:.2}",
            a.angle_deg,
            a.in_set,
            a.detectable,
            100.0 * a.worst_effect_in_set,
            a.largest_mean_set_size
        );
    }
    println!();
    for (a, b, why) in &r.indistinguishable {
        println!("indistinguishable: {a} / {b}: {why}");
    }
}

/// `wearsim gap-validate`.
pub fn run(a: &GapValidateArgs) -> Result<(), CliError> {
    let opt = a.options()?;
    let bar = Progress::new(!a.json, "twins");
    let r = validate(&opt, &|d, t| bar.update(d, t)).map_err(CliError::run)?;
    bar.finish();
    if a.json {
        print_json(&r)?;
    } else {
        print(&r);
    }
    Ok(())
}
