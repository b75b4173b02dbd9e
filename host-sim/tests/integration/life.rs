//! Whole-life behaviour (thesis Fig. 5–7, model.md §8) and the life command's modes and
//! errors.

use proptest::prelude::*;
use std::process::Command;
use wearsim_core::wear::{LifeConfig, Material, Stage};
use wearsim_host::life::dense::DenseOptions;
use wearsim_host::life::{LifeRun, LifeSpec};

fn reference(seed: u64, every: f64, window: f64) -> LifeSpec {
    LifeSpec {
        model: wearsim_core::presets::by_name("thesis-61810").unwrap(),
        life: LifeConfig::DEFAULT,
        seed,
        snapshot_every: every,
        window,
        settle: 0.05,
        calibration_load: None,
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

/// Normalised RMS over life: steady (within ±5 % of its median) over the steady-state
/// stage, a step of at least 30 % at the dent, a fall back below 80 % of the dent's level
/// with smoothing, and a rise to at least 10× the steady level at the end. (Seed 3 forms a
/// dent, at 0.08 of its life; where the dent falls in a life is the competition tested
/// below, not a property of one seed.)
#[test]
fn reference_life_follows_the_thesis() {
    let run = LifeRun::new(reference(3, 20_000.0, 0.25)).unwrap();
    let r = run.run_snapshots(|_, _| {}).unwrap();
    assert_eq!(r.state.stage, Stage::Failure);
    let rms = |stage: &str| -> Vec<f64> {
        r.snapshots
            .iter()
            .filter(|s| s.stage == stage)
            .map(|s| s.features.rms)
            .collect()
    };
    let steady = rms("steady-state");
    assert!(steady.len() > 20, "only {} steady snapshots", steady.len());
    let m = median(steady.clone());
    for v in &steady {
        assert!((v / m - 1.0).abs() < 0.05, "steady RMS {v} vs median {m}");
    }
    let dent = rms("dent");
    assert!(dent[0] > 1.3 * m, "dent step {} vs steady {m}", dent[0]);
    let smooth = rms("dent-smoothing");
    assert!(
        smooth.iter().any(|v| *v < 0.8 * dent[0]),
        "no fall with smoothing"
    );
    let end = r.snapshots.last().unwrap().features.rms;
    assert!(end > 10.0 * m, "end of life {end} vs steady {m}");
    // Every stage of the thesis occurs, in order.
    let stages: Vec<Stage> = r.state.events.iter().map(|e| e.stage).collect();
    for s in &Stage::ALL[1..] {
        assert!(stages.contains(s), "{s:?} missing in {stages:?}");
    }
}

/// Surface and subsurface initiation compete with independent scatter (issue 14: the
/// crack opened at exactly twice the dent's time in most lives, because the dent formed at
/// half of the same fatigue sum that later opened the crack). Over seeds 1–40 (coarse
/// snapshots): both ways occur — lives whose subsurface fatigue opens a crack before any
/// dent (steady state → crack opening) and lives that dent first — each in at least 10 %
/// of lives; among dented lives at most 10 % open their crack within 0.5 % of twice the
/// dent's time (it was 44 of 60 with one shared factor), and the dent's place in life
/// spreads over more than 0.4 of life.
#[test]
fn surface_and_subsurface_initiation_compete() {
    let (mut subsurface, mut ratios, mut fractions) = (0, Vec::new(), Vec::new());
    for seed in 1..=40 {
        let run = LifeRun::new(reference(seed, 200_000.0, 0.05)).unwrap();
        let r = run.run_snapshots(|_, _| {}).unwrap();
        assert_eq!(r.state.stage, Stage::Failure, "seed {seed}");
        let at = |stage: Stage| {
            r.state
                .events
                .iter()
                .find(|e| e.stage == stage)
                .map(|e| e.cycles)
        };
        let crack = at(Stage::CrackOpening).expect("every life opens a crack");
        match at(Stage::Dent) {
            None => {
                subsurface += 1;
                assert!(at(Stage::DentSmoothing).is_none(), "seed {seed}");
            }
            Some(dent) => {
                ratios.push(crack / dent);
                fractions.push(dent / r.state.cycles);
            }
        }
    }
    let dented = ratios.len();
    eprintln!(
        "subsurface {subsurface}/40, crack/dent ratios {ratios:?}, dent fractions {fractions:?}"
    );
    assert!(
        subsurface >= 4 && dented >= 4,
        "subsurface {subsurface}, dented {dented}"
    );
    let clock = ratios
        .iter()
        .filter(|r| (*r / 2.0 - 1.0).abs() < 0.005)
        .count();
    assert!(
        clock * 10 <= dented,
        "{clock} of {dented} dented lives crack at 2× the dent time"
    );
    let spread = fractions.iter().cloned().fold(0.0, f64::max)
        - fractions.iter().cloned().fold(1.0, f64::min);
    assert!(spread > 0.4, "dent fractions {fractions:?}");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, .. ProptestConfig::default() })]
    /// Over many seeds the stage order is never violated, the life ends in failure, and no
    /// feature is NaN.
    #[test]
    fn stage_order_holds_for_any_seed(seed in 0u64..1_000_000) {
        let run = LifeRun::new(reference(seed, 200_000.0, 0.05)).unwrap();
        let r = run.run_snapshots(|_, _| {}).unwrap();
        let idx: Vec<usize> = r.state.events.iter().map(|e| e.stage.index()).collect();
        prop_assert!(idx.windows(2).all(|w| w[0] <= w[1]), "{:?}", idx);
        prop_assert_eq!(r.state.stage, Stage::Failure);
        let cycles: Vec<f64> = r.state.events.iter().map(|e| e.cycles).collect();
        prop_assert!(cycles.windows(2).all(|w| w[0] <= w[1]));
        prop_assert!(r.snapshots.iter().all(|s| s.features.rms.is_finite() && s.features.kurtosis.is_finite()));
    }
}

fn life_with(load_scale: f64, lambda: f64, seed: u64, every: f64) -> (f64, LifeRun) {
    let mut spec = reference(seed, every, 0.05);
    // The same bearing and material under a scaled load (as `--load-scale`).
    spec.calibration_load = Some(spec.model.radial_load);
    spec.model.radial_load *= load_scale;
    spec.life.lambda = lambda;
    spec.life.cycle_cap = 1e12;
    let run = LifeRun::new(spec).unwrap();
    let r = run.run_snapshots(|_, _| {}).unwrap();
    assert!(r
        .snapshots
        .iter()
        .all(|s| s.features.rms.is_finite() && s.features.zone_high.is_finite()));
    (r.state.cycles, run)
}

/// Probe finding (stop 53): a scenario with `radial_load = 0` was refused as
/// "calibration_load = 0 is out of range", a key the user never wrote. The error now names
/// the scenario's `radial_load`.
#[test]
fn a_life_without_load_names_radial_load() {
    let mut spec = reference(1, 2e4, 0.05);
    spec.calibration_load = Some(0.0);
    let Err(e) = LifeRun::new(spec) else {
        panic!("a life without load was accepted")
    };
    let e = e.to_string();
    assert!(e.starts_with("radial_load = 0 is out of range"), "{e}");
}

/// No NaN over whole lives at the corners of the load and lubrication ranges.
#[test]
fn corners_of_the_parameter_ranges() {
    for (load, lambda) in [(0.2, 0.1), (0.2, 10.0), (5.0, 0.1), (5.0, 10.0)] {
        let (life, _) = life_with(load, lambda, 7, 1e7);
        assert!(
            life.is_finite() && life > 0.0,
            "load {load} lambda {lambda}: {life}"
        );
    }
}

/// Life against load follows a power law with an exponent between 2 and 4.5 (ball-bearing
/// rating life ∝ load⁻³); the load acts through the dynamic model's contact loads.
#[test]
fn life_against_load_is_a_power_law() {
    let scales: [f64; 5] = [0.6, 0.8, 1.0, 1.25, 1.6];
    let pts: Vec<(f64, f64)> = scales
        .iter()
        .map(|s| (s.ln(), life_with(*s, 2.0, 5, 100_000.0).0.ln()))
        .collect();
    let n = pts.len() as f64;
    let (mx, my) = (
        pts.iter().map(|p| p.0).sum::<f64>() / n,
        pts.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let slope = pts.iter().map(|(x, y)| (x - mx) * (y - my)).sum::<f64>()
        / pts.iter().map(|(x, _)| (x - mx) * (x - mx)).sum::<f64>();
    println!("life ∝ load^{slope:.2}");
    assert!((-4.5..=-2.0).contains(&slope), "fitted exponent {slope}");
}

/// Poor lubrication (λ < 1) shortens life against full separation (λ > 3).
#[test]
fn poor_lubrication_shortens_life() {
    let (poor, _) = life_with(1.0, 0.8, 5, 100_000.0);
    let (good, _) = life_with(1.0, 4.0, 5, 100_000.0);
    println!("life at λ=0.8: {poor:.3e}, at λ=4: {good:.3e}");
    assert!(poor < 0.5 * good);
}

/// A thesis-bearing life on accelerated material (`Material::ACCELERATED`), sampled at
/// 5 kHz with 0.1 s windows every 100 revolutions: a whole life in seconds.
pub(crate) fn accelerated(seed: u64) -> LifeSpec {
    let mut model = wearsim_core::presets::by_name("thesis-61810").unwrap();
    model.output_rate = 5000.0;
    let material = Material::ACCELERATED;
    LifeSpec {
        model,
        life: LifeConfig {
            material,
            running_in: 1.0,
            ..LifeConfig::DEFAULT
        },
        seed,
        snapshot_every: 100.0,
        window: 0.1,
        settle: 0.05,
        calibration_load: None,
    }
}

/// The same seed gives the same wear history in snapshot and dense mode, and a dense run
/// interrupted twice and resumed writes exactly the samples of an uninterrupted one.
#[test]
fn dense_mode_same_history_and_resume() {
    let run = LifeRun::new(accelerated(9)).unwrap();
    let snap = run.run_snapshots(|_, _| {}).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let whole = dir.path().join("whole");
    let dense = run
        .run_dense(
            &DenseOptions {
                dir: whole.clone(),
                stop_after: None,
            },
            |_, _| {},
        )
        .unwrap();
    assert!(dense.complete);
    let a: Vec<(Stage, u64)> = snap
        .state
        .events
        .iter()
        .map(|e| (e.stage, e.cycles.to_bits()))
        .collect();
    let b: Vec<(Stage, u64)> = dense
        .state
        .events
        .iter()
        .map(|e| (e.stage, e.cycles.to_bits()))
        .collect();
    assert_eq!(a, b);
    assert_eq!(dense.state.stage, Stage::Failure);
    let expected = (dense.state.cycles / run.shaft_hz * 5000.0) as u64;
    assert!(
        dense.samples.abs_diff(expected) <= 2,
        "{} samples for {} expected",
        dense.samples,
        expected
    );

    let split = dir.path().join("split");
    let opts = DenseOptions {
        dir: split.clone(),
        stop_after: Some(3.0),
    };
    let first = run.run_dense(&opts, |_, _| {}).unwrap();
    assert!(!first.complete && first.samples > 0);
    let manifest: serde_json::Value =
        serde_json::from_slice(&std::fs::read(split.join("life-dense.json")).unwrap()).unwrap();
    assert_eq!(manifest["complete"], false);
    // Simulate a crash after the checkpoint: garbage appended to the data file is dropped.
    {
        use std::io::Write;
        let mut f = std::fs::OpenOptions::new()
            .append(true)
            .open(split.join("life-dense.f32"))
            .unwrap();
        f.write_all(&[0xAB; 1000]).unwrap();
    }
    let second = run.run_dense(&opts, |_, _| {}).unwrap();
    assert!(second.resumed);
    let mut last = second;
    while !last.complete {
        last = run.run_dense(&opts, |_, _| {}).unwrap();
    }
    assert_eq!(
        std::fs::read(whole.join("life-dense.f32")).unwrap(),
        std::fs::read(split.join("life-dense.f32")).unwrap()
    );
    assert!(!split.join("life-dense.ckpt").exists());
    let manifest: serde_json::Value =
        serde_json::from_slice(&std::fs::read(split.join("life-dense.json")).unwrap()).unwrap();
    assert_eq!(manifest["complete"], true);
    assert_eq!(manifest["samples"], dense.samples);
}

fn wearsim(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_wearsim"))
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn life_command_outputs_and_errors() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("life");
    // One short life into `out`, with the lanes on or off (`WEARSIM_LANES_OFF`).
    let life = |out: &std::path::Path, lanes_off: bool| {
        let mut c = Command::new(env!("CARGO_BIN_EXE_wearsim"));
        c.args([
            "life",
            "--snapshot-every",
            "200000",
            "--window",
            "0.05",
            "--json",
        ])
        .arg("--out")
        .arg(out);
        if lanes_off {
            c.env("WEARSIM_LANES_OFF", "1");
        }
        c.output().unwrap()
    };
    let o = life(&out, false);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(v["cycles_to_failure"].as_f64().unwrap() > 1e5);
    // Every column of the features table has its unit, in the summary and on stdout
    // (probe finding, stop 53: none was stated anywhere).
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("life-summary.json")).unwrap()).unwrap();
    let header = std::fs::read_to_string(out.join("life-features.csv")).unwrap();
    for col in header
        .lines()
        .next()
        .unwrap()
        .split(',')
        .filter(|c| *c != "stage")
    {
        assert!(
            summary["units"][col].is_string() && v["units"][col].is_string(),
            "{col}"
        );
    }
    assert_eq!(summary["units"]["rms"], "m/s^2");
    for f in [
        "life-features.csv",
        "life-timeline.csv",
        "life-events.csv",
        "life-events.json",
        "life-summary.json",
    ] {
        assert!(out.join(f).exists(), "{f}");
    }
    // The driver renders the windows of unchanged models ahead as lanes; with the lanes
    // off (every window alone) the life is the same, byte for byte.
    let alone = dir.path().join("alone");
    let o = life(&alone, true);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for f in ["life-features.csv", "life-timeline.csv", "life-events.csv"] {
        let (a, b) = (
            std::fs::read(out.join(f)).unwrap(),
            std::fs::read(alone.join(f)).unwrap(),
        );
        assert!(a == b, "{f} differs with the lanes off");
    }
    let cfg = dir.path().join("bad.toml");
    for (text, args, needle) in [
        (
            "preset = \"thesis-61810\"\n[material]\nyield_strength = -1.0\n",
            vec![],
            "material.yield_strength",
        ),
        (
            "preset = \"thesis-61810\"\n[material]\nfracture = 1.0\n",
            vec![],
            "unknown field `fracture`",
        ),
        (
            "preset = \"thesis-61810\"\n",
            vec!["--snapshot-every", "1e9", "--cycles", "1e6"],
            "snapshot interval",
        ),
        (
            "preset = \"thesis-61810\"\n",
            vec!["--cycles", "1000", "--snapshot-every", "100"],
            "did not fail within the cycle cap",
        ),
        (
            "preset = \"thesis-61810\"\n",
            vec!["--lambda", "-1"],
            "lambda",
        ),
        (
            // A ball life is carried (tests/integration/life_ball.rs), but only on a ball the bearing
            // has (14 balls: 0..=13).
            "preset = \"thesis-61810\"\n[defect]\nlocation = \"ball\"\nelement = 14\n",
            vec![],
            "defect.element",
        ),
        (
            "preset = \"thesis-61810\"\n",
            vec!["--load-scale", "100"],
            "load_scale",
        ),
    ] {
        std::fs::write(&cfg, text).unwrap();
        let o2 = dir.path().join("o2");
        let mut a = vec![
            "life",
            "--config",
            cfg.to_str().unwrap(),
            "--out",
            o2.to_str().unwrap(),
        ];
        a.extend(args);
        let o = wearsim(&a);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{text}: {err}");
        assert!(err.contains(needle), "{err} lacks {needle}");
        assert!(!o2.join("life-summary.json").exists());
    }
}

/// Probe finding (stop 53): with every life suspended at `--cycles`, twelve fields of
/// `lives.json` were `null` with nothing in the JSON saying why. Each null fit and exponent
/// now comes with its reason.
#[test]
fn null_fits_say_why() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("lives");
    let o = Command::new(env!("CARGO_BIN_EXE_wearsim"))
        .args([
            "life", "--lives", "3", "--cycles", "2e5", "--window", "0.05", "--json", "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let g = &v["groups"][0];
    assert_eq!(g["suspended"], 3, "{g}");
    assert!(g["weibull"].is_null() && g["first_spall"]["weibull"].is_null());
    let why = g["no_fit"].as_str().unwrap();
    assert!(
        why.starts_with("0 of 3 failures") && why.contains("at least 3"),
        "{why}"
    );
    assert!(g["first_spall"]["no_fit"]
        .as_str()
        .unwrap()
        .starts_with("0 of 3 lives reached"));
    assert!(v["load_exponent"].is_null());
    assert!(v["load_exponent_note"]
        .as_str()
        .unwrap()
        .contains("two or more loads"));
}

/// `life --lives N` at two loads: every life fails, the Weibull fit and the life–load
/// exponent come with intervals that contain their estimates, and the exponent has the
/// sign and size of a fatigue law (ISO 281: −3 for ball bearings; the lives carry
/// deterministic stages after initiation, so it is allowed to be flatter, not positive
/// or steeper than −6).
#[test]
fn lives_give_weibull_and_load_exponent() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("lives");
    let o = Command::new(env!("CARGO_BIN_EXE_wearsim"))
        .args([
            "life",
            "--lives",
            "8",
            "--loads",
            "1,1.6",
            "--snapshot-every",
            "200000",
            "--window",
            "0.05",
            "--threads",
            "2",
            "--json",
            "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["site"]["name"], "outer_race");
    assert_eq!(v["site"]["pass_frequency"], "BPFO");
    let groups = v["groups"].as_array().unwrap();
    assert_eq!(groups.len(), 2);
    for g in groups {
        let w = &g["weibull"]["shape"];
        let (b, lo, hi) = (
            w["value"].as_f64().unwrap(),
            w["lo"].as_f64().unwrap(),
            w["hi"].as_f64().unwrap(),
        );
        assert!(b > 0.3 && b < 20.0 && lo <= b && b <= hi, "{w}");
        assert!(g["iso_l10_revs"].as_f64().unwrap() > 0.0);
    }
    assert!(v["load_exponent_note"].is_null() && groups.iter().all(|g| g["no_fit"].is_null()));
    let e = &v["load_exponent"];
    let x = e["value"].as_f64().unwrap();
    assert!((-6.0..=-1.0).contains(&x), "life–load exponent {e}");
    assert!(e["lo"].as_f64().unwrap() <= x && x <= e["hi"].as_f64().unwrap());
    let es = &v["first_spall_load_exponent"]["value"];
    assert!(
        es.as_f64().is_some_and(|x| (-6.0..=-1.0).contains(&x)),
        "first-spall exponent {es}"
    );
    // The ball bearing's published range, and the comparison consistent with the estimate.
    let pubs: Vec<f64> = v["load_exponent_published"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["exponent"].as_f64().unwrap())
        .collect();
    assert_eq!(pubs, [-3.0, -4.0]);
    let r = &v["load_exponent_against_published"];
    assert_eq!(r["range"], serde_json::json!([-4.0, -3.0]));
    assert_eq!(
        r["value_inside"].as_bool().unwrap(),
        (-4.0..=-3.0).contains(&x),
        "{r}"
    );
    let csv = std::fs::read_to_string(out.join("lives.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 16);
    // The Weibull plot: both loads' fits in the legend of both panels, ISO's L10 marked.
    assert!(out.join("lives-weibull.png").exists());
    let svg = std::fs::read_to_string(out.join("lives-weibull.svg")).unwrap();
    for g in groups {
        let beta = format!("β {:.2}", g["weibull"]["shape"]["value"].as_f64().unwrap());
        assert!(svg.contains(&beta), "{beta} not in the plot");
    }
    assert_eq!(svg.matches("ISO L10").count(), 4, "two loads × two panels");
    // Every life reaches its first spall before it fails.
    let head: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |name: &str| head.iter().position(|h| *h == name).unwrap();
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let life: f64 = f[col("life_revs")].parse().unwrap();
        let spall: f64 = f[col("first_spall_revs")].parse().unwrap();
        assert!(spall > 0.0 && spall < life, "{line}");
        assert!(
            ["surface", "subsurface"].contains(&f[col("initiation")]),
            "{line}"
        );
    }
    for g in groups {
        assert_eq!(g["first_spall"]["reached"], 8);
        let modes = &g["initiation"];
        assert_eq!(
            modes["surface"].as_u64().unwrap() + modes["subsurface"].as_u64().unwrap(),
            8,
            "{modes}"
        );
        let b = g["first_spall"]["weibull"]["shape"]["value"]
            .as_f64()
            .unwrap();
        assert!(b > 0.3 && b < 20.0, "{g}");
    }
    // The post-spall share is the median of (life − first spall)/life over the lives of
    // lives.csv (all failed); the crack share lies inside (0, 1); the trend's direction is
    // the one its two intervals allow.
    for g in groups {
        let scale = g["load_scale"].as_f64().unwrap();
        let mut post: Vec<f64> = csv
            .lines()
            .skip(1)
            .map(|l| l.split(',').collect::<Vec<_>>())
            .filter(|f| f[col("load_scale")].parse::<f64>().unwrap() == scale)
            .map(|f| {
                let life: f64 = f[col("life_revs")].parse().unwrap();
                (life - f[col("first_spall_revs")].parse::<f64>().unwrap()) / life
            })
            .collect();
        post.sort_by(f64::total_cmp);
        assert_eq!(post.len(), 8);
        let want = 0.5 * (post[3] + post[4]);
        let p = &g["phases"];
        assert_eq!(p["post_spall_lives"], 8, "{p}");
        let got = p["post_spall"]["value"].as_f64().unwrap();
        assert!((got - want).abs() < 1e-12, "{got} vs {want}");
        let c = &p["crack"];
        let (v, lo, hi) = (
            c["value"].as_f64().unwrap(),
            c["lo"].as_f64().unwrap(),
            c["hi"].as_f64().unwrap(),
        );
        assert!(0.0 < lo && lo <= v && v <= hi && hi < 1.0, "{c}");
    }
    for key in ["crack_share_trend", "post_spall_share_trend"] {
        let t = &v[key];
        let (a, b) = (&t["shares"][0], &t["shares"][1]);
        let want = if b["hi"].as_f64() < a["lo"].as_f64() {
            "falls"
        } else if b["lo"].as_f64() > a["hi"].as_f64() {
            "rises"
        } else {
            "undecided"
        };
        assert_eq!(t["direction"], want, "{t}");
    }
    assert_eq!(v["crack_share_trend"]["published"], "falls");
    assert!(v["post_spall_share_trend"]["published"].is_null());
}

/// Bad `--lives`/`--loads` values: exit 2, the field named, nothing written.
#[test]
fn lives_reject_bad_values() {
    let many_loads = (0..17)
        .map(|i| format!("{}", 1.1f64.powi(i)))
        .collect::<Vec<_>>()
        .join(",");
    for (args, field) in [
        (vec!["--lives", "2"], "lives"),
        (vec!["--lives", "5", "--loads", "1,0"], "loads"),
        (vec!["--lives", "5", "--loads", "1,1"], "given twice"),
        // 1 % apart gave an exponent interval of ±3·10⁵; 1000 loads started 1000 × 5 lives.
        (
            vec!["--lives", "5", "--loads", "1,1.000001"],
            "differ by less than 5 %",
        ),
        (
            vec!["--lives", "5", "--loads", "2,1,0.98"],
            "0.98 and 1 differ",
        ),
        (
            vec!["--lives", "5", "--loads", &many_loads],
            "17 load scales given; at most 16",
        ),
        (vec!["--lives", "5", "--threads", "0"], "threads"),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("x");
        let o = Command::new(env!("CARGO_BIN_EXE_wearsim"))
            .arg("life")
            .args(&args)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(field), "{args:?}: {err}");
        assert!(!out.join("lives.json").exists());
    }
}

/// A life into a directory that holds another seed's life: the event plots it does not
/// redraw are removed (seed 2 has a dent, seed 1 none: seed 2's `event-4-dent.png` stayed
/// beside seed 1's set, indistinguishable from it), and files not of the life's naming stay.
#[test]
fn a_life_over_another_removes_the_event_plots_it_does_not_redraw() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("life");
    let run = |seed: &str| {
        let o = wearsim(&["life", "--seed", seed, "--out", out.to_str().unwrap()]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    };
    run("2");
    assert!(out.join("event-4-dent.png").is_file(), "seed 2 has a dent");
    std::fs::write(out.join("event-notes.txt"), "mine").unwrap();
    run("1");
    for f in [
        "event-4-dent.png",
        "event-4-dent.svg",
        "event-5-dent-smoothing.png",
    ] {
        assert!(
            !out.join(f).exists(),
            "{f} of seed 2 left beside seed 1's plots"
        );
    }
    assert!(out.join("event-1-steady-state.png").is_file());
    assert!(out.join("event-notes.txt").is_file());
}

/// A `life --lives` run into a folder holding an earlier run's set removes that set's
/// completion marker (`lives.json`) before its first life: while it runs, or after it is
/// killed, the folder is not presented as a complete set (an outside user's probe found a
/// killed rerun's folder still holding the old `lives.json`).
#[test]
fn a_rerun_of_lives_takes_the_old_sets_marker_away_first() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("set");
    std::fs::create_dir(&out).unwrap();
    let marker = out.join("lives.json");
    std::fs::write(&marker, "stale").unwrap();
    // Long enough that it is still running when the marker is looked at (killed below).
    let mut child = Command::new(env!("CARGO_BIN_EXE_wearsim"))
        .args([
            "life",
            "--lives",
            "1000",
            "--threads",
            "1",
            "--json",
            "--out",
        ])
        .arg(&out)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let t0 = std::time::Instant::now();
    let gone = loop {
        if std::fs::read(&marker).map_or(true, |b| b != b"stale") {
            break true;
        }
        if t0.elapsed() > std::time::Duration::from_secs(60) {
            break false;
        }
        std::thread::sleep(std::time::Duration::from_millis(10));
    };
    let running = child.try_wait().unwrap().is_none();
    let _ = child.kill();
    let _ = child.wait();
    assert!(gone, "the old lives.json stayed while the rerun ran");
    assert!(
        running,
        "1000 lives finished before the marker was looked at"
    );
    assert!(!marker.exists(), "a killed rerun left a lives.json");
}
