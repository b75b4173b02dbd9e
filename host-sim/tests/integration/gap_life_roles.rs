//! Which life is which, and what each did, in the report of `wearsim gap --life` on
//! documented feature tables (an outside reviewer's probe E):
//! * a life is named by its sidecar's bearing id and its path, and the JSON carries per
//!   life its path, id and source — not by file name and position (two tables both called
//!   `run.csv` were "run.csv bearing 1" and "run.csv bearing 2", the number being the
//!   position among `--real`, so B1_2 was called "bearing 1");
//! * the roles are stated as records of seconds state them (`gap::roles`): `train`
//!   (fitted), `validation` (chose the model), `test` (judged only), in the top-level keys,
//!   in `where[].role` and in `holdout_spans[].role`; without a test part a finding and
//!   `totals.test_note` say that the held-out lives both chose and were judged.

use crate::support;
use std::path::{Path, PathBuf};
use support::{json_ok, s, wearsim};

const GEOMETRY: &str = r#"{ "elements": 13, "ball_mm": 3.5, "pitch_mm": 25.6, "angle_deg": 0.0 }"#;

/// A small life (150 hourly snapshots, RMS rising over its last 40 %) of the bearing `id`
/// as `dir/name.csv`, its sidecar's source `source`.
fn life(dir: &Path, name: &str, seed: u64, id: &str, source: &str) -> PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    let bearing = format!(r#"{{ "geometry": {GEOMETRY}, "id": "{id}" }}"#);
    support::rig_table(
        dir,
        name,
        &support::RigTable {
            n: 150,
            seed,
            bearing: &bearing,
            load: "4000.0",
            rpm: 1800.0,
            interval: 3600.0,
            rise: (0.6, 4.0),
            source,
        },
    )
}

/// `gap --life` of `tables` (the first trained on) with `extra` flags, quick settings;
/// its JSON and `gap.md`.
fn gap(tables: &[&Path], out: &Path, extra: &[&str]) -> (serde_json::Value, String) {
    let mut args = vec!["gap", "--life"];
    for t in tables {
        args.extend(["--real", s(t)]);
    }
    args.extend([
        "--effects",
        "sensor",
        "--life-search",
        "1",
        "--out",
        s(out),
        "--json",
    ]);
    args.extend_from_slice(extra);
    let j = json_ok(&wearsim(&args));
    let md = std::fs::read_to_string(out.join("gap.md")).expect("gap.md");
    (j, md)
}

fn strings(v: &serde_json::Value) -> Vec<String> {
    v.as_array()
        .unwrap_or_else(|| panic!("not an array: {v}"))
        .iter()
        .map(|x| x.as_str().unwrap_or_default().to_string())
        .collect()
}

/// Probe E, defect 1: `--real lab2/run.csv --real lab1/run.csv` (sidecar ids B1_2, B1_1)
/// reported `train: ["run.csv bearing 1"]`, `holdout: ["run.csv bearing 2"]`, and neither
/// the id, the path nor the source anywhere.
#[test]
fn lives_of_files_of_one_name_are_named_by_their_sidecar_and_path() {
    let tmp = tempfile::tempdir().unwrap();
    let one = life(&tmp.path().join("lab1"), "run", 1, "B1_1", "lab one, rig A");
    let two = life(&tmp.path().join("lab2"), "run", 2, "B1_2", "lab two, rig A");
    let (j, md) = gap(&[&two, &one], &tmp.path().join("out"), &[]);
    let (train, held) = (strings(&j["train"]), strings(&j["holdout"]));
    assert_eq!(train, [format!("B1_2 ({})", two.display())]);
    assert_eq!(held, [format!("B1_1 ({})", one.display())]);
    // The JSON carries each life's path, id and source, and its number as the flags count.
    for (sp, p, id, src, number, role) in [
        (&j["train_span"], &two, "B1_2", "lab two, rig A", 1, "train"),
        (
            &j["holdout_spans"][0],
            &one,
            "B1_1",
            "lab one, rig A",
            2,
            "validation",
        ),
    ] {
        assert_eq!(sp["path"], s(p), "{sp}");
        assert_eq!(sp["id"], id, "{sp}");
        assert_eq!(sp["source"], src, "{sp}");
        assert_eq!(sp["number"], number, "{sp}");
        assert_eq!(sp["role"], role, "{sp}");
    }
    // Every cell is its life's, by the same label; no "bearing N" made of a position.
    for c in j["where"].as_array().unwrap() {
        let rec = c["record"].as_str().unwrap();
        assert!(train.contains(&rec.to_string()) || held.contains(&rec.to_string()));
        assert!(!rec.contains("bearing"), "{rec}");
    }
    assert!(md.contains(&train[0]) && md.contains(&held[0]), "{md}");
    assert!(!md.contains("run.csv bearing"), "{md}");
}

/// Probe E, defect 2: with `--validation` the validation life was listed, labelled and
/// reported as `holdout` next to the test life, which had no cells in `where`; without
/// it, nothing said that the held-out lives both chose and were judged, nor why
/// `totals.test_*` are null.
#[test]
fn the_roles_of_the_lives_are_stated_in_the_report() {
    let tmp = tempfile::tempdir().unwrap();
    let src = "synthetic rig (gap_life_roles.rs)";
    let a = life(tmp.path(), "a", 1, "A", src);
    let b = life(tmp.path(), "b", 2, "B", src);
    let c = life(tmp.path(), "c", 3, "C", src);
    let label = |id: &str, p: &Path| format!("{id} ({})", p.display());
    let flags = ["--train", "1", "--validation", "2", "--holdout", "3"];
    let (j, md) = gap(&[&a, &b, &c], &tmp.path().join("three"), &flags);
    assert_eq!(strings(&j["train"]), [label("A", &a)]);
    assert_eq!(strings(&j["validation"]), [label("B", &b)]);
    assert_eq!(strings(&j["test"]), [label("C", &c)]);
    // `holdout` keeps its meaning: every life not trained on, validation then test.
    assert_eq!(strings(&j["holdout"]), [label("B", &b), label("C", &c)]);
    let roles: Vec<&str> = j["holdout_spans"]
        .as_array()
        .unwrap()
        .iter()
        .map(|sp| sp["role"].as_str().unwrap())
        .collect();
    assert_eq!(roles, ["validation", "test"]);
    // Every cell carries its life's role; the test life's cells are there.
    let cells = j["where"].as_array().unwrap();
    for cell in cells {
        let want = match cell["record"].as_str().unwrap() {
            r if r == label("A", &a) => "train",
            r if r == label("B", &b) => "validation",
            r if r == label("C", &c) => "test",
            r => panic!("unknown life {r}"),
        };
        assert_eq!(cell["role"], want, "{cell}");
    }
    assert!(cells.iter().any(|cell| cell["role"] == "test"));
    assert!(!j["stages_test"].as_array().unwrap().is_empty());
    assert!(j["totals"]["test_before"].as_f64().is_some());
    assert!(j["totals"]["test_note"].is_null());
    assert!(md.contains(&format!("Validation (chose the model): {}", label("B", &b))));
    assert!(md.contains(&format!(
        "Test (judged only, chose nothing): {}",
        label("C", &c)
    )));
    assert!(md.contains("**Total test gap**"), "{md}");

    // Two parts: the held-out life chose the model and was judged, and the report says so.
    let (j, md) = gap(&[&a, &b], &tmp.path().join("two"), &[]);
    assert_eq!(strings(&j["validation"]), [label("B", &b)]);
    assert!(strings(&j["test"]).is_empty());
    assert!(j["totals"]["test_before"].is_null());
    let note = j["totals"]["test_note"].as_str().expect("test_note");
    assert!(
        note.contains("both chose the model") && note.contains("no clean test figure"),
        "{note}"
    );
    assert!(
        j["findings"].to_string().contains("no separate test part"),
        "{}",
        j["findings"]
    );
    assert!(j["where"]
        .as_array()
        .unwrap()
        .iter()
        .all(|c| c["role"] == "train" || c["role"] == "validation"));
    assert!(md.contains("no separate test part"), "{md}");
}

/// Probe finding (stop 53): one table alone was refused with "--holdout: give at least one
/// held-out bearing", though no flag was given and the table holds one life: the message
/// now asks for a second table.
#[test]
fn one_table_alone_is_asked_for_a_second() {
    let tmp = tempfile::tempdir().unwrap();
    let a = life(&tmp.path().join("lab1"), "run", 1, "B1_1", "lab 1");
    support::refused(
        &wearsim(&[
            "gap",
            "--life",
            "--real",
            s(&a),
            "--out",
            s(&tmp.path().join("o")),
        ]),
        &["the input holds one life", "give a second table (--real)"],
    );
}
