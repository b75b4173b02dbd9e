//! An outside probe of `wearsim sweep` and `wearsim simulate` as a new user drives them:
//! a grid far larger than its records is labelled without holding every cell, a
//! configuration or spec that never ends (`/dev/zero`) is refused within a bound, a core
//! range error names the scenario file's own key (in its unit), and a data set resumed in
//! a directory that cannot be written is refused before any simulation.

use crate::support::{refused, s, wearsim};
use std::process::{Command, Output};
use wearsim_host::sweep::{record, SweepSpec};

/// Runs `wearsim args` under an address-space limit of `mib` MiB (`ulimit -v`), so that an
/// unbounded allocation fails in the child instead of exhausting the machine.
fn wearsim_limited(mib: u64, args: &[&str]) -> Output {
    let bin = env!("CARGO_BIN_EXE_wearsim");
    Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {}; exec \"$0\" \"$@\"", mib * 1024))
        .arg(bin)
        .args(args)
        .output()
        .expect("run wearsim under sh")
}

fn grid_spec(rpms: usize, loads: usize) -> String {
    let list = |n: usize, first: f64| {
        (0..n)
            .map(|i| format!("{:.2}", first + i as f64 * 0.01))
            .collect::<Vec<_>>()
            .join(", ")
    };
    format!(
        "seed = 3\nrecords = 6\nrecords_per_shard = 3\nduration = 0.01\nfs = 12000.0\n\
         [grid]\npreset = [\"cwru-6205-de\"]\nrpm = [{}]\nradial_load = [{}]\n\
         fault = [\"healthy\", \"outer\"]\nstage = [\"mild-defect\", \"large-defect\"]\n",
        list(rpms, 1000.0),
        list(loads, 100.0)
    )
}

/// 20 000 speeds × 20 000 loads × 3 (fault, stage) pairs = 1.2·10⁹ cells for 6 records:
/// the sweep holds none of the cells it does not label (it built every one, about 400
/// bytes each, and compared every pair of axis values to find a repeat: minutes, then
/// out of memory), and its labels are the first cells in the documented order.
#[test]
fn a_grid_larger_than_its_records_is_not_materialised() {
    let dir = tempfile::tempdir().unwrap();
    let spec_path = dir.path().join("huge grid.toml");
    let text = grid_spec(20_000, 20_000);
    std::fs::write(&spec_path, &text).unwrap();
    let out = dir.path().join("set ü");
    let t0 = std::time::Instant::now();
    let o = wearsim_limited(2048, &["sweep", s(&spec_path), "--out", s(&out), "--json"]);
    assert!(
        o.status.success(),
        "exit {:?}: {}",
        o.status.code(),
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(t0.elapsed().as_secs() < 60, "took {:?}", t0.elapsed());
    assert!(out.join("manifest.json").is_file());
    let spec = SweepSpec::parse(&text, "spec").unwrap();
    let cells = record::cells(&spec);
    assert_eq!(cells.len(), 20_000 * 20_000 * 3);
    let labels: Vec<String> = (0..6)
        .map(|i| {
            let c = record::record(&spec, &cells, i).cell;
            format!("{} {:?} {} {}", c.rpm, c.radial_load, c.fault, c.stage)
        })
        .collect();
    assert_eq!(
        labels,
        [
            "1000 Some(100.0) healthy healthy",
            "1000 Some(100.0) outer mild-defect",
            "1000 Some(100.0) outer large-defect",
            "1000 Some(100.01) healthy healthy",
            "1000 Some(100.01) outer mild-defect",
            "1000 Some(100.01) outer large-defect",
        ]
    );
    let last = cells.get(cells.len() - 1);
    assert_eq!(
        (last.rpm, last.radial_load, last.stage.as_str()),
        (1199.99, Some(299.99), "large-defect")
    );
}

/// A repeated value at the end of a long axis is still found, in one pass.
#[test]
fn a_repeat_on_a_long_axis_is_named_quickly() {
    let dir = tempfile::tempdir().unwrap();
    let spec_path = dir.path().join("spec.toml");
    // The repeat is the last pair: a search of every pair met it last.
    let text = grid_spec(100_000, 1).replace("]\nradial_load", ", 1999.99]\nradial_load");
    assert!(text.contains("1999.99, 1999.99]"));
    std::fs::write(&spec_path, text).unwrap();
    let t0 = std::time::Instant::now();
    let o = wearsim(&["sweep", s(&spec_path), "--out", s(&dir.path().join("o"))]);
    refused(&o, &["grid.rpm", "1999.99 twice"]);
    assert!(t0.elapsed().as_secs() < 30, "took {:?}", t0.elapsed());
    assert!(!dir.path().join("o").exists());
}

/// A configuration or spec that never ends is refused at the documented bound (it was read
/// whole: gigabytes of RAM in seconds), exit 2, naming the limit.
#[test]
fn endless_configuration_files_are_refused_within_a_bound() {
    if !std::path::Path::new("/dev/zero").exists() {
        eprintln!("skipped: no /dev/zero");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    for args in [
        vec!["simulate", "--config", "/dev/zero", "--out", s(&out)],
        vec!["sweep", "/dev/zero", "--out", s(&out)],
        vec!["life", "--config", "/dev/zero", "--out", s(&out)],
    ] {
        let o = wearsim_limited(2048, &args);
        refused(&o, &["/dev/zero", "too large", "1048576 bytes"]);
    }
    assert!(!out.exists());
    // Not UTF-8: refused as such, exit 2.
    let bin = dir.path().join("bin.toml");
    std::fs::write(&bin, [0xff, 0xfe, 0x00, 0x41]).unwrap();
    refused(
        &wearsim(&["simulate", "--config", s(&bin), "--out", s(&out)]),
        &["bin.toml", "UTF-8"],
    );
}

/// Range errors the core raises in its own terms name the scenario file's key, in the
/// file's unit: `defect.angle_deg` in degrees (was `defect.angle` in radians),
/// `speed.ramp_duration` (was `speed.duration`), `[defect]` sizes (were `topography.*`).
#[test]
fn core_range_errors_name_the_files_keys() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&str, &[&str]); 7] = [
        (
            "[defect]\nlocation = \"outer\"\nangle_deg = 1000.0",
            &["defect.angle_deg = 1000", "572.9"],
        ),
        (
            // Degrees went to radians and back: 1e9 was echoed as 1000000000.0000001.
            "[defect]\nlocation = \"outer\"\nangle_deg = 1e9",
            &[
                "defect.angle_deg = 1000000000 is out of range",
                "572.957795131 (finite)",
            ],
        ),
        (
            "[speed]\nfrom_hz = 5.0\nto_hz = 30.0\nramp_duration = 0.0",
            &["speed.ramp_duration = 0", "0.000001"],
        ),
        (
            "[defect]\nlocation = \"outer\"\nlength = 1.0",
            &["defect.length = 1", "0.02"],
        ),
        (
            "[defect]\nlocation = \"inner\"\ndepth = -1.0",
            &["defect.depth = -1", "0.005"],
        ),
        (
            "[defect]\nlocation = \"outer\"\ncount = 9",
            &["defect.count = 9", "allowed 1 ..= 8"],
        ),
        (
            // Was "0 entries; at most 8 are supported": the minimum went unsaid.
            "[defect]\nlocation = \"outer\"\ncount = 0",
            &["defect.count = 0", "allowed 1 ..= 8"],
        ),
    ];
    for (i, (body, needles)) in cases.iter().enumerate() {
        let cfg = dir.path().join(format!("c{i}.toml"));
        std::fs::write(&cfg, format!("preset = \"cwru-6205-de\"\n{body}\n")).unwrap();
        let out = dir.path().join(format!("o{i}"));
        let o = wearsim(&[
            "simulate",
            "--config",
            s(&cfg),
            "--duration",
            "0.01",
            "--out",
            s(&out),
        ]);
        refused(&o, needles);
        let msg = String::from_utf8_lossy(&o.stderr);
        assert!(!msg.contains("topography."), "{msg}");
        assert!(!out.join("simulate.json").exists());
    }
}

/// Resuming a data set in a directory this run cannot write is refused before any record
/// is simulated (exit 2, naming the directory), not after the first shard (exit 1).
/// Needs a user whom permissions bind (skipped as root, who writes anyway).
#[cfg(unix)]
#[test]
fn resuming_in_an_unwritable_directory_is_refused_first() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let spec_path = dir.path().join("spec.toml");
    std::fs::write(&spec_path, grid_spec(2, 1)).unwrap();
    let out = dir.path().join("set");
    let o = wearsim(&["sweep", s(&spec_path), "--out", s(&out), "--json"]);
    assert!(o.status.success());
    let shards = out.join("shards");
    std::fs::remove_file(shards.join("shard-00001.done.json")).unwrap();
    std::fs::remove_file(out.join("manifest.json")).unwrap();
    std::fs::set_permissions(&shards, std::fs::Permissions::from_mode(0o555)).unwrap();
    if std::fs::write(shards.join("probe"), b"").is_ok() {
        let _ = std::fs::remove_file(shards.join("probe"));
        std::fs::set_permissions(&shards, std::fs::Permissions::from_mode(0o755)).unwrap();
        eprintln!("skipped: permissions do not bind this user (root)");
        return;
    }
    let o = wearsim(&["sweep", s(&spec_path), "--out", s(&out), "--json"]);
    std::fs::set_permissions(&shards, std::fs::Permissions::from_mode(0o755)).unwrap();
    refused(&o, &["set", "cannot be written"]);
    assert!(!out.join("manifest.json").exists());
}

/// `channels = "all"` states a unit for every column it writes: `disp_m` was `"unknown"`
/// in the sidecar (the suffix table knew `_um` and `_mm`, not `_m`).
#[test]
fn every_simulated_column_has_its_unit() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = dir.path().join("all.toml");
    std::fs::write(
        &cfg,
        "preset = \"cwru-6205-de\"\nchannels = \"all\"\nduration = 0.01\n",
    )
    .unwrap();
    let out = dir.path().join("o");
    let o = wearsim(&["simulate", "--config", s(&cfg), "--out", s(&out), "--json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let side: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("simulate.json")).unwrap()).unwrap();
    let units = &side["units"];
    for (col, unit) in [
        ("accel_m_s2", "m/s^2"),
        ("accel_g", "g"),
        ("vel_m_s", "m/s"),
        ("disp_m", "m"),
    ] {
        assert_eq!(units[col], unit, "{col}: {units}");
    }
}

/// A "CSV" without line ends (`/dev/zero` behind a `.csv` name) is refused at the bound
/// on one line (it grew to gigabytes: the `csv` crate holds a whole record).
#[cfg(unix)]
#[test]
fn a_csv_line_without_end_is_refused_within_a_bound() {
    if !std::path::Path::new("/dev/zero").exists() {
        eprintln!("skipped: no /dev/zero");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("zero.csv");
    std::os::unix::fs::symlink("/dev/zero", &csv).unwrap();
    let args = [
        "analyze",
        s(&csv),
        "--fs",
        "12000",
        "--rpm",
        "1797",
        "--bearing",
        "cwru-6205-de",
    ];
    refused(
        &wearsim_limited(2048, &args),
        &["zero.csv", "too large", "1048576 bytes per line"],
    );
}
