//! `wearsim effects` and the `--effect` / `[[effect]]` inputs: the catalogue is complete
//! and machine-readable, effects change the output, and bad input exits with code 2 and a
//! message naming the effect, the parameter and the bounds.

use std::process::{Command, Output};

fn wearsim(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wearsim"))
        .args(args)
        .output()
        .expect("run wearsim")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn effects_json_lists_every_effect_with_bounds() {
    let o = wearsim(&["effects", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let list = v.as_array().unwrap();
    let names: Vec<&str> = list.iter().map(|e| e["name"].as_str().unwrap()).collect();
    assert_eq!(
        names,
        [
            "slip",
            "load-zone",
            "transfer-path",
            "speed-fluctuation",
            "sensor",
            "shaft-harmonics",
            "running-in",
            "roughness",
            "edge-shape"
        ]
    );
    for e in list {
        assert!(!e["description"].as_str().unwrap().is_empty());
        let params = e["params"].as_array().unwrap();
        assert!(!params.is_empty());
        for p in params {
            let (min, max, d) = (
                p["min"].as_f64().unwrap(),
                p["max"].as_f64().unwrap(),
                p["default"].as_f64().unwrap(),
            );
            assert!(min <= d && d <= max, "{p}");
            assert!(p["unit"].is_string() && p["name"].is_string());
        }
    }
    let lz = &list[1]["params"];
    assert_eq!(lz[1]["name"], "epsilon");
    assert_eq!(
        (lz[1]["min"].as_f64(), lz[1]["max"].as_f64()),
        (Some(0.2), Some(1.0))
    );
    let text = wearsim(&["effects"]);
    assert!(text.status.success());
    assert!(String::from_utf8_lossy(&text.stdout).contains("speed-fluctuation"));
}

fn rms_of(args: &[&str]) -> f64 {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    let mut a = vec![
        "simulate",
        "--duration",
        "0.3",
        "--json",
        "--out",
        out.to_str().unwrap(),
    ];
    a.extend_from_slice(args);
    let o = wearsim(&a);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let side: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("simulate.json")).unwrap()).unwrap();
    assert!(side["effects"].is_object());
    v["summary"]["stats"]["rms"].as_f64().unwrap()
}

#[test]
fn effect_arguments_and_config_tables_change_the_output() {
    let base = rms_of(&[]);
    // A 50 m/s² noise floor adds in power to the default scenario's level.
    let noisy = rms_of(&["--effect", "sensor:noise=50"]);
    let expect = (base * base + 2500.0).sqrt();
    assert!(
        (noisy - expect).abs() < 0.03 * expect,
        "{base} -> {noisy} (expected {expect})"
    );
    let dir = tempfile::tempdir().unwrap();
    let cfg = dir.path().join("s.toml");
    std::fs::write(
        &cfg,
        "preset = \"thesis-61810\"\n[[effect]]\nname = \"sensor\"\nparams = { noise = 50.0 }\n",
    )
    .unwrap();
    let from_file = rms_of(&["--config", cfg.to_str().unwrap()]);
    assert_eq!(from_file, noisy);
    // Several effects at once, defaults for parameters not given.
    let many = rms_of(&[
        "--effect",
        "load-zone:depth=0.5",
        "--effect",
        "shaft-harmonics",
        "--effect",
        "roughness:scale=2",
    ]);
    assert!(many.is_finite() && many != base);
}

fn bad(args: &[&str], expect: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    let mut a = vec!["--duration", "0.1", "--out", out.to_str().unwrap()];
    a.extend_from_slice(args);
    for cmd in ["simulate", "life"] {
        let mut full = vec![cmd];
        if cmd == "life" {
            full.extend_from_slice(&["--out", out.to_str().unwrap()]);
            full.extend_from_slice(args);
        } else {
            full.extend_from_slice(&a);
        }
        let o = wearsim(&full);
        assert_eq!(o.status.code(), Some(2), "{cmd} {args:?}: {}", stderr(&o));
        let e = stderr(&o);
        for s in expect {
            assert!(e.contains(s), "{cmd} {args:?}: `{e}` lacks `{s}`");
        }
    }
}

#[test]
fn bad_effects_exit_2_naming_effect_parameter_and_bounds() {
    bad(
        &["--effect", "ball-defect"],
        &["unknown effect `ball-defect`", "load-zone"],
    );
    bad(
        &["--effect", "sensor:gain=2"],
        &["`sensor`", "no parameter `gain`", "hum_hz"],
    );
    bad(
        &["--effect", "load-zone:epsilon=0.1"],
        &["`load-zone`", "`epsilon`", "[0.2, 1]"],
    );
    bad(
        &["--effect", "sensor:hum_hz=80"],
        &["`sensor`", "`hum_hz`", "[40, 70] Hz"],
    );
    bad(
        &["--effect", "slip:fraction=abc"],
        &["`fraction`", "not a number"],
    );
    bad(
        &["--effect", "transfer-path:f1=9000"],
        &["transfer-path.f1", "8000"],
    );
}

#[test]
fn bad_effect_table_in_config_exits_2() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = dir.path().join("s.toml");
    std::fs::write(
        &cfg,
        "preset = \"thesis-61810\"\n[[effect]]\nname = \"running-in\"\nparams = { factor = 20 }\n",
    )
    .unwrap();
    let out = dir.path().join("o");
    let o = wearsim(&[
        "simulate",
        "--config",
        cfg.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("`running-in`") && stderr(&o).contains("[1, 10]"),
        "{}",
        stderr(&o)
    );
    std::fs::write(
        &cfg,
        "preset = \"thesis-61810\"\n[[effect]]\nname = \"slip\"\nfraction = 0.1\n",
    )
    .unwrap();
    let o = wearsim(&[
        "simulate",
        "--config",
        cfg.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("fraction"), "{}", stderr(&o));
}

/// A misspelled effect name is an error in every entry point of the library (command
/// line argument, scenario section, switching off in the attribution, fit spaces), never
/// a silently different effect.
#[test]
fn misspelled_effect_name_is_an_error_everywhere() {
    use wearsim_core::effects::{EffectKind, Effects};
    use wearsim_host::effects::{apply, build, kind, parse_arg, EffectSection};
    use wearsim_host::gap::matched::{merge, without};
    let bad = "edge-shap";
    assert!(kind(bad)
        .unwrap_err()
        .contains("unknown effect `edge-shap`"));
    assert!(parse_arg("edge-shap:length_scale=0.5").is_err());
    let sec = EffectSection {
        name: bad.into(),
        params: Default::default(),
    };
    let mut fx = Effects::NONE;
    assert!(apply(&mut fx, &sec).is_err());
    assert!(build(&[sec]).is_err());
    let mut on = Effects::NONE;
    apply(&mut on, &parse_arg("edge-shape:length_scale=0.5").unwrap()).unwrap();
    assert!(without(&on, bad).is_err());
    assert_eq!(without(&on, "edge-shape").unwrap(), Effects::NONE);
    // merge copies exactly the effects that are on, by kind.
    let mut into = Effects::NONE;
    merge(&mut into, &on);
    assert_eq!(into, on);
    assert!(EffectKind::from_name(bad).is_err());
    assert!(wearsim_core::effects::info(bad).is_none());
    assert!(fx.set_named(bad, &[1.0, 1.0]).is_err());
    assert_eq!(fx, Effects::NONE);
    // Every registered effect has a fit space, named by kind, and every fitted or fixed
    // parameter name is one of the effect's parameters.
    let ctx = wearsim_host::gap::space::Context {
        fs: 12_000.0,
        shaft_hz: 30.0,
        rms: 1.0,
        mains_hz: 60.0,
        preload_max: wearsim_host::gap::space::preload_limit(
            &wearsim_core::presets::by_name("cwru-6205-de").unwrap(),
        ),
    };
    let spaces = wearsim_host::gap::space::spaces(&ctx);
    assert_eq!(spaces.len(), EffectKind::ALL.len());
    for (s, k) in spaces.iter().zip(EffectKind::ALL) {
        assert_eq!(s.kind, k);
        let spec = k.spec();
        for n in s
            .fitted
            .iter()
            .map(|f| f.name)
            .chain(s.fixed.iter().map(|f| f.0))
        {
            assert!(spec.param(n).is_some(), "{}: fit names `{n}`", spec.name);
        }
        // The values a fit produces are accepted.
        let mid = vec![0.5; s.fitted.len()];
        let mut fx = Effects::NONE;
        s.apply(&mut fx, &mid).unwrap();
        assert!(fx.is_on(k));
    }
}
