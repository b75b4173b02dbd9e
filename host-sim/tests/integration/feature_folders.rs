//! `wearsim features` on raw folders that are not quite right (the black-box probe's
//! findings): FEMTO clocks that step back without a midnight, IMS names that are no date,
//! missing and unread snapshot files (the table keeps each file's number and the sidecar
//! lists them), errors that name the input rather than the table never written, and the
//! messages for header rows the layout does not have (or lacks).

use crate::support;
use std::path::{Path, PathBuf};
use support::{refused, s, wearsim, FEMTO_FLAGS};

use wearsim_host::io::feature_table::{read_feature_table, sidecar_path};

/// FEMTO file `acc_{number}.csv` whose first row is at `clock` s since midnight, 256 rows
/// of a ±a square wave.
fn femto_file(dir: &Path, number: usize, clock: usize, a: f64) {
    let (h, m, sec) = (clock / 3600, (clock / 60) % 60, clock % 60);
    let text: String = (0..256)
        .map(|i| {
            let v = if i % 2 == 0 { a } else { -a };
            format!("{h},{m},{sec},{},{v},0.5\n", 39 * i)
        })
        .collect();
    std::fs::write(dir.join(format!("acc_{number:05}.csv")), text).unwrap();
}

/// FEMTO files 1..=n from 09:00:00, 10 s apart, except those in `leave_out`.
fn femto_folder(dir: &Path, n: usize, leave_out: &[usize]) {
    std::fs::create_dir_all(dir).unwrap();
    for k in 1..=n {
        if !leave_out.contains(&k) {
            femto_file(dir, k, 9 * 3600 + 10 * (k - 1), 0.1 * k as f64);
        }
    }
}

fn femto(raw: &Path, out: &Path, json: bool) -> std::process::Output {
    let mut args = vec!["features", s(raw), "--layout", "femto", "--out", s(out)];
    args.extend(FEMTO_FLAGS);
    if json {
        args.push("--json");
    }
    wearsim(&args)
}

/// XJTU-SY file `name` (header row unless `header` is false), 200 rows.
fn xjtu_file(dir: &Path, name: &str, a: f64, header: bool) {
    let mut text = String::new();
    if header {
        text.push_str("Horizontal_vibration_signals,Vertical_vibration_signals\n");
    }
    for i in 0..200 {
        let v = if i % 2 == 0 { a } else { -a };
        text.push_str(&format!("{v},0.25\n"));
    }
    std::fs::write(dir.join(name), text).unwrap();
}

fn xjtu(raw: &Path, out: &Path) -> std::process::Output {
    wearsim(&[
        "features",
        s(raw),
        "--layout",
        "xjtu",
        "--out",
        s(out),
        "--rpm",
        "2100",
        "--load-n",
        "12000",
        "--json",
    ])
}

fn nothing_written(out: &Path) {
    assert!(!out.exists() && !sidecar_path(out).exists());
}

#[test]
fn a_femto_clock_that_steps_back_at_9_am_is_refused_not_a_midnight() {
    let tmp = tempfile::tempdir().unwrap();
    let raw = tmp.path().join("swap");
    femto_folder(&raw, 12, &[]);
    // Files 4 and 5 swapped: 09:00:30 then 09:00:40 then 09:00:30 … used to add a day.
    femto_file(&raw, 4, 9 * 3600 + 40, 0.4);
    femto_file(&raw, 5, 9 * 3600 + 30, 0.5);
    let out = tmp.path().join("o/swap.csv");
    refused(
        &femto(&raw, &out, false),
        &[
            s(&raw),
            "acc_00005.csv starts at 09:00:30.000000",
            "acc_00004.csv at 09:00:40.000000",
            "under 12 h",
        ],
    );
    nothing_written(&out);
    // A step back from late in the day to early is a wrap past midnight.
    let raw = tmp.path().join("midnight");
    std::fs::create_dir_all(&raw).unwrap();
    for k in 1..=12 {
        femto_file(
            &raw,
            k,
            (86_400 - 30 + 10 * (k - 1)) % 86_400,
            0.1 * k as f64,
        );
    }
    let out = tmp.path().join("o/midnight.csv");
    assert!(femto(&raw, &out, false).status.success());
    let t = read_feature_table(&out).unwrap();
    let times: Vec<f64> = t.rows.iter().map(|r| r.time_s).collect();
    assert_eq!(times, (0..12).map(|k| 10.0 * k as f64).collect::<Vec<_>>());
}

#[test]
fn ims_names_of_the_pattern_that_are_no_date_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    for bad in ["2004.02.30.11.50.39", "2004.02.12.11.70.39"] {
        let raw = tmp.path().join(format!("ims_{bad}"));
        std::fs::create_dir_all(&raw).unwrap();
        for k in 0..11 {
            let name = format!("2004.02.12.10.{:02}.39", 5 * k);
            std::fs::write(raw.join(name), "0.1\t0.2\t0.3\t0.4\n").unwrap();
        }
        std::fs::write(raw.join(bad), "0.1\t0.2\t0.3\t0.4\n").unwrap();
        let out = tmp.path().join("o/ims.csv");
        let o = wearsim(&["features", s(&raw), "--layout", "ims", "--out", s(&out)]);
        refused(&o, &[bad, "not a date and time"]);
        nothing_written(&out);
    }
}

/// One IMS snapshot of 8 columns among 4-column ones (test 1's layout among test 2's):
/// channel 3 would be another sensor in it, so the folder is refused, naming the file.
#[test]
fn an_ims_snapshot_of_other_columns_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let raw = tmp.path().join("ims_mixed");
    std::fs::create_dir_all(&raw).unwrap();
    let rows = |cols: usize| -> String {
        (0..64)
            .map(|i| {
                let row: Vec<String> = (0..cols)
                    .map(|c| format!("{:.3}", ((i * 7 + c * 3) % 11) as f64 * 0.01 - 0.05))
                    .collect();
                row.join("\t") + "\n"
            })
            .collect()
    };
    for k in 0..12 {
        let name = format!("2004.02.12.10.{:02}.39", 5 * k);
        std::fs::write(raw.join(name), rows(if k == 7 { 8 } else { 4 })).unwrap();
    }
    let out = tmp.path().join("o/ims.csv");
    std::fs::create_dir_all(out.parent().unwrap()).unwrap();
    let o = wearsim(&[
        "features",
        s(&raw),
        "--layout",
        "ims",
        "--channel",
        "3",
        "--out",
        s(&out),
    ]);
    refused(
        &o,
        &["2004.02.12.10.35.39", "8 columns, the first snapshot has 4"],
    );
    nothing_written(&out);
}

#[test]
fn missing_and_unread_files_keep_their_numbers_and_are_listed() {
    let tmp = tempfile::tempdir().unwrap();
    // FEMTO without acc_00005.csv: row 4 is file 6, at its own time.
    let raw = tmp.path().join("femto");
    femto_folder(&raw, 12, &[5]);
    let out = tmp.path().join("o/femto.csv");
    let o = femto(&raw, &out, true);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let t = read_feature_table(&out).unwrap();
    let index: Vec<u64> = t.rows.iter().map(|r| r.snapshot).collect();
    assert_eq!(index, [1, 2, 3, 4, 6, 7, 8, 9, 10, 11, 12]);
    assert_eq!(t.rows[4].time_s, 50.0);
    assert!(
        t.sidecar
            .notes
            .iter()
            .any(|n| n.starts_with("missing: acc_00005.csv")),
        "{:?}",
        t.sidecar.notes
    );
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(j["missing"], serde_json::json!(["acc_00005.csv"]));
    // XJTU-SY without 5.csv, with a 0.csv (the numbering starts at 1: not read, listed).
    let raw = tmp.path().join("xjtu");
    std::fs::create_dir_all(&raw).unwrap();
    for k in (0..=12).filter(|k| *k != 5) {
        xjtu_file(&raw, &format!("{k}.csv"), 0.1 * (k + 1) as f64, true);
    }
    let out = tmp.path().join("o/xjtu.csv");
    let o = xjtu(&raw, &out);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let t = read_feature_table(&out).unwrap();
    let index: Vec<u64> = t.rows.iter().map(|r| r.snapshot).collect();
    assert_eq!(index, [1, 2, 3, 4, 6, 7, 8, 9, 10, 11, 12]);
    assert_eq!(t.rows[4].time_s, 300.0);
    let notes = t.sidecar.notes.join("\n");
    assert!(
        notes.contains("missing: 5.csv") && notes.contains("0.csv: not read"),
        "{notes}"
    );
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(j["missing"], serde_json::json!(["5.csv"]));
    assert!(j["skipped"][0].as_str().unwrap().contains("0.csv"));
    // Two files of one number are refused, naming both.
    xjtu_file(&raw, "03.csv", 0.3, true);
    refused(
        &xjtu(&raw, &out),
        &["03.csv and 3.csv", "same snapshot number"],
    );
}

#[test]
fn refusals_name_the_input_folder_and_files_not_the_table() {
    let tmp = tempfile::tempdir().unwrap();
    // Two FEMTO files at one time.
    let raw = tmp.path().join("dup");
    femto_folder(&raw, 12, &[]);
    femto_file(&raw, 11, 9 * 3600 + 90, 1.1);
    let out = tmp.path().join("o/dup.csv");
    let o = femto(&raw, &out, false);
    refused(
        &o,
        &[
            s(&raw),
            "acc_00010.csv and acc_00011.csv both start at 09:01:30",
        ],
    );
    assert!(!String::from_utf8_lossy(&o.stderr).contains("dup.csv"));
    nothing_written(&out);
    // Too few snapshots.
    let raw = tmp.path().join("few");
    femto_folder(&raw, 3, &[]);
    let out = tmp.path().join("o/few.csv");
    let o = femto(&raw, &out, false);
    refused(&o, &[s(&raw), "3 snapshots", "at least 10"]);
    assert!(!String::from_utf8_lossy(&o.stderr).contains("few.csv"));
    nothing_written(&out);
}

#[test]
fn header_rows_are_named_in_the_messages() {
    let tmp = tempfile::tempdir().unwrap();
    // A FEMTO file with a header row: `hour` is its first non-number.
    let raw = tmp.path().join("fh");
    femto_folder(&raw, 12, &[]);
    let p = raw.join("acc_00003.csv");
    let body = std::fs::read_to_string(&p).unwrap();
    std::fs::write(&p, format!("hour,min,sec,usec,horiz,vert\n{body}")).unwrap();
    let out: PathBuf = tmp.path().join("o/fh.csv");
    refused(
        &femto(&raw, &out, false),
        &["acc_00003.csv", "\"hour\"", "FEMTO files have none"],
    );
    nothing_written(&out);
    // An XJTU-SY file without its header row.
    let raw = tmp.path().join("xh");
    std::fs::create_dir_all(&raw).unwrap();
    for k in 1..=12 {
        xjtu_file(&raw, &format!("{k}.csv"), 0.1 * k as f64, k != 3);
    }
    let out = tmp.path().join("o/xh.csv");
    refused(
        &xjtu(&raw, &out),
        &[
            "3.csv",
            "lacks the XJTU-SY header row `Horizontal_vibration_signals,Vertical_vibration_signals`",
        ],
    );
    nothing_written(&out);
}

/// Probe defect: `features DIR --layout xjtu --out DIR/1.csv` replaced raw snapshot
/// `1.csv` with the table. Refused (exit 2, naming `--out`), the snapshot untouched and
/// nothing written; the same for a name of the naming that is not a file yet.
#[test]
fn the_table_may_not_overwrite_or_join_the_input_snapshots() {
    let tmp = tempfile::tempdir().unwrap();
    let raw = tmp.path().join("xjtu");
    std::fs::create_dir_all(&raw).unwrap();
    for k in 1..=12 {
        xjtu_file(&raw, &format!("{k}.csv"), 0.1 * k as f64, true);
    }
    let first = std::fs::read(raw.join("1.csv")).unwrap();
    refused(
        &xjtu(&raw, &raw.join("1.csv")),
        &["--out", "would overwrite"],
    );
    assert_eq!(std::fs::read(raw.join("1.csv")).unwrap(), first);
    assert!(!raw.join("1.json").exists());
    refused(
        &xjtu(&raw, &raw.join("13.csv")),
        &["--out", "snapshot naming (13.csv)"],
    );
    nothing_written(&raw.join("13.csv"));
    // Beside the snapshots under another name it is written.
    let o = xjtu(&raw, &raw.join("table.csv"));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// Probe defect: `--json`'s `hours` was the last row's `time_s`, not the span, when the
/// first file of the numbering was missing: XJTU-SY files 3..=14 (the first at 120 s)
/// span 11 minutes, not 13.
#[test]
fn hours_is_the_span_of_the_table() {
    let tmp = tempfile::tempdir().unwrap();
    let raw = tmp.path().join("xjtu");
    std::fs::create_dir_all(&raw).unwrap();
    for k in 3..=14 {
        xjtu_file(&raw, &format!("{k}.csv"), 0.1 * k as f64, true);
    }
    let o = xjtu(&raw, &tmp.path().join("o/t.csv"));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let hours = j["hours"].as_f64().unwrap();
    assert!((hours - 11.0 / 60.0).abs() < 1e-12, "hours {hours}");
}

/// Probe finding (stop 53): `features` accepted `--rpm 100000` and `--load-n 0` (the
/// format's ranges) and wrote tables that `gap --life` then refused (a simulated life takes
/// 0.06..=60 000 rpm and needs a load). The tables are still written — they are data — and
/// their sidecar notes say what `gap --life` will refuse.
#[test]
fn a_table_no_life_can_simulate_says_so_in_its_notes() {
    let tmp = tempfile::tempdir().unwrap();
    let raw = tmp.path().join("xjtu");
    std::fs::create_dir_all(&raw).unwrap();
    for k in 1..=40 {
        xjtu_file(&raw, &format!("{k}.csv"), 0.1 * k as f64, true);
    }
    let notes = |rpm: &str, load: &str| -> Vec<String> {
        let out = tmp.path().join(format!("o{rpm}-{load}/t.csv"));
        let o = wearsim(&[
            "features",
            s(&raw),
            "--layout",
            "xjtu",
            "--out",
            s(&out),
            "--rpm",
            rpm,
            "--load-n",
            load,
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let side: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(sidecar_path(&out)).unwrap()).unwrap();
        side["notes"]
            .as_array()
            .map(|a| a.iter().map(|n| n.as_str().unwrap().to_string()).collect())
            .unwrap_or_default()
    };
    assert!(notes("2100", "12000").is_empty());
    let n = notes("100000", "0");
    assert!(
        n.iter()
            .any(|t| t.starts_with("rpm 100000 is outside") && t.contains("gap --life"))
            && n.iter().any(|t| t.starts_with("radial_load_n 0")),
        "{n:?}"
    );
}

/// Probe findings (stop 53): a FEMTO folder holding XJTU-SY files and a README converted
/// without a word about them, and a directory named `acc_00006.csv` was listed as "missing
/// (no such file)". The other files are counted and named in the notes; the directory is
/// skipped as no regular file, and not listed as missing.
#[test]
fn other_files_and_a_directory_of_a_snapshot_name_are_noted() {
    let tmp = tempfile::tempdir().unwrap();
    let raw = tmp.path().join("femto");
    femto_folder(&raw, 12, &[6]);
    std::fs::create_dir(raw.join("acc_00006.csv")).unwrap();
    xjtu_file(&raw, "1.csv", 0.1, true);
    std::fs::write(raw.join("README.txt"), "rig 3").unwrap();
    let out = tmp.path().join("o/femto.csv");
    let o = femto(&raw, &out, true);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let t = read_feature_table(&out).unwrap();
    assert_eq!(t.rows.len(), 11);
    let notes = t.sidecar.notes.join("\n");
    assert!(
        notes.contains("not read: 2 file(s) not named as femto snapshots (1.csv, README.txt)"),
        "{notes}"
    );
    assert!(
        notes.contains("acc_00006.csv: not read: named as a snapshot but no regular file")
            && !notes.contains("missing:"),
        "{notes}"
    );
}
