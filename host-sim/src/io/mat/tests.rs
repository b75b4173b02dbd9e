//! Unit tests of the MAT reader.

use super::v5::*;
use super::*;
use crate::io::IoError;
use serde_json::json;
use std::path::{Path, PathBuf};

fn tmp_file(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

#[test]
fn parses_names() {
    let l = parse_cwru_name("12k_Drive_End_OR007@12_1_158.mat").unwrap();
    assert_eq!(l.fault, CwruFault::OuterRace { clock: 12 });
    assert_eq!(l.fault.or_position(), Some("opposite_12"));
    assert_eq!(l.diameter_in, Some(0.007));
    assert_eq!((l.load_hp, l.record, l.fs_hz), (1, 158, 12000.0));
    let n = parse_cwru_name("/x/y/normal_0_97.mat").unwrap();
    assert_eq!(
        (n.fault, n.fs_hz, n.record),
        (CwruFault::Normal, 48000.0, 97)
    );
    let b = parse_cwru_name("12k_Drive_End_B021_3_225").unwrap();
    assert_eq!((b.fault, b.diameter_in), (CwruFault::Ball, Some(0.021)));
    for bad in [
        "105.mat",
        "12k_Drive_End_IR7_0_1.mat",
        "12k_Drive_End_OR007_0_1.mat",
        "x",
        "",
        "12k_Drive_End_IR007_9_1.mat",
        "96k_Drive_End_IR007_0_1.mat",
        "12k_Drive_End_OR007@5_0_1.mat",
    ] {
        assert!(parse_cwru_name(bad).is_none(), "{bad}");
    }
}

#[test]
fn reads_synthetic_file_plain_and_compressed() {
    let dir = tempfile::tempdir().unwrap();
    let de: Vec<f64> = (0..100).map(|i| (i as f64 * 0.1).sin()).collect();
    let fe: Vec<f64> = (0..100).map(|i| i as f64).collect();
    let other = [9.0; 100];
    let bytes = mat5_bytes(&[
        ("X099_DE_time", &other),
        ("X105_DE_time", &de),
        ("X105_FE_time", &fe),
        ("X105RPM", &[1797.0]),
    ]);
    for (k, b) in [bytes.clone(), mat5_compress(&bytes)].iter().enumerate() {
        let sub = dir.path().join(k.to_string());
        std::fs::create_dir(&sub).unwrap();
        let p = tmp_file(&sub, "12k_Drive_End_IR007_0_105.mat", b);
        let r = read_cwru(&p, "de", None).unwrap();
        assert_eq!(r.samples, de);
        assert_eq!(r.fs, 12000.0);
        assert_eq!(r.rpm, Some(1797.0));
        assert_eq!(r.bearing.as_deref(), Some("cwru-6205-de"));
        assert_eq!(r.meta["label"]["fault"], json!("inner_race"));
        let r = read_cwru(&p, "FE", Some(48000.0)).unwrap();
        assert_eq!(r.samples, fe);
        assert_eq!(r.fs, 48000.0);
        assert_eq!(r.bearing.as_deref(), Some("cwru-6203-fe"));
        match read_cwru(&p, "BA", None).unwrap_err() {
            IoError::UnknownChannel { available, .. } => {
                assert_eq!(available, vec!["DE", "FE"])
            }
            e => panic!("{e:?}"),
        }
        let vars = list_mat_variables(&p).unwrap();
        assert_eq!(vars.len(), 4);
        assert_eq!(vars[1], ("X105_DE_time".to_string(), 100));
        // No recognisable name and no override: no sample rate.
        let q = tmp_file(&sub, "105.mat", b);
        assert!(matches!(
            read_cwru(&q, "DE", None),
            Err(IoError::MissingSampleRate { .. })
        ));
        assert_eq!(read_cwru(&q, "DE", Some(12000.0)).unwrap().samples, de);
    }
}

#[test]
fn a_fan_end_fault_file_is_read_on_its_own_accelerometer_by_default() {
    let dir = tempfile::tempdir().unwrap();
    let de = [1.0; 300];
    let fe = [2.0; 300];
    let bytes = mat5_bytes(&[
        ("X294_DE_time", &de),
        ("X294_FE_time", &fe),
        ("X294RPM", &[1797.0]),
    ]);
    for (name, want, bearing) in [
        ("12k_Fan_End_OR007@6_0_294.mat", 2.0, "cwru-6203-fe"),
        ("12k_Drive_End_OR007@6_0_294.mat", 1.0, "cwru-6205-de"),
        ("normal_0_294.mat", 1.0, "cwru-6205-de"),
    ] {
        let p = tmp_file(dir.path(), name, &bytes);
        let r = read_mat_record(&p, &crate::io::ReadOptions::default()).unwrap();
        assert_eq!(
            (r.samples[0], r.bearing.as_deref()),
            (want, Some(bearing)),
            "{name}"
        );
    }
    // An explicit channel still wins.
    let p = dir.path().join("12k_Fan_End_OR007@6_0_294.mat");
    let de_opts = crate::io::ReadOptions {
        channel: Some("DE".into()),
        ..Default::default()
    };
    assert_eq!(read_mat_record(&p, &de_opts).unwrap().samples[0], 1.0);
}

#[test]
fn rejects_corrupt_files() {
    let dir = tempfile::tempdir().unwrap();
    let good = mat5_bytes(&[("X105_DE_time", &[1.0, 2.0, 3.0])]);
    let name = "12k_Drive_End_IR007_0_105.mat";
    // Empty, short, bad magic, bad endian.
    for (bytes, want) in [
        (Vec::new(), "truncated"),
        (good[..100].to_vec(), "truncated"),
        (b"hello world".repeat(20), "bad magic"),
    ] {
        let p = tmp_file(dir.path(), name, &bytes);
        let e = read_cwru(&p, "DE", None).unwrap_err();
        assert!(e.to_string().contains(want), "{e}");
        assert!(e.to_string().contains(name), "{e}");
    }
    // Truncated in the data.
    let p = tmp_file(dir.path(), name, &good[..good.len() - 9]);
    assert!(matches!(
        read_cwru(&p, "DE", None),
        Err(IoError::Truncated { .. })
    ));
    // Element claiming 4 GiB.
    let mut huge = good.clone();
    huge[132..136].copy_from_slice(&u32::MAX.to_le_bytes());
    let p = tmp_file(dir.path(), name, &huge);
    assert!(matches!(
        read_cwru(&p, "DE", None),
        Err(IoError::Truncated { .. })
    ));
    // Dimensions that disagree with the data.
    let mut dims = good.clone();
    // dims sub-element data starts at 128 + 8 (tag) + 16 (flags) + 8 (dims tag)
    dims[160..164].copy_from_slice(&1_000_000i32.to_le_bytes());
    let p = tmp_file(dir.path(), name, &dims);
    assert!(matches!(
        read_cwru(&p, "DE", None),
        Err(IoError::Contradiction { .. })
    ));
    // NaN sample.
    let nan = mat5_bytes(&[("X105_DE_time", &[1.0, f64::NAN, 3.0])]);
    let p = tmp_file(dir.path(), name, &nan);
    match read_cwru(&p, "DE", None).unwrap_err() {
        IoError::NonFinite { index, .. } => assert_eq!(index, 1),
        e => panic!("{e:?}"),
    }
    // Absurd override.
    let p = tmp_file(dir.path(), name, &good);
    assert!(matches!(
        read_cwru(&p, "DE", Some(1e9)),
        Err(IoError::AbsurdSampleRate { .. })
    ));
    // Zlib bomb-ish: compressed element claiming garbage.
    let mut z = good[..128].to_vec();
    z.extend_from_slice(&MI_COMPRESSED.to_le_bytes());
    z.extend_from_slice(&16u32.to_le_bytes());
    z.extend_from_slice(&[0x78, 0x9c, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14]);
    let p = tmp_file(dir.path(), name, &z);
    assert!(read_cwru(&p, "DE", None).is_err());
}

/// Every `.mat` of the CWRU folder: DE present, fs from the name, plausible length and rpm,
/// finite values, and the parsed label equals the inventory row.
#[test]
fn real_cwru_files_match_inventory() -> Result<(), IoError> {
    let Some(dir) = crate::io::data_dir()? else {
        return Ok(());
    };
    let cwru = dir.join("cwru");
    let inv_path = cwru.join("inventory.csv");
    let mut inv = ::csv::Reader::from_path(&inv_path).expect("inventory.csv");
    let headers = inv.headers().unwrap().clone();
    let col = |name: &str| headers.iter().position(|h| h == name).unwrap();
    let (c_file, c_rec, c_fs, c_end, c_type, c_dia, c_or, c_load, c_rpm, c_n) = (
        col("file"),
        col("cwru_record"),
        col("sample_rate_hz"),
        col("fault_end"),
        col("fault_type"),
        col("fault_diameter_in"),
        col("or_position"),
        col("load_hp"),
        col("rpm_in_file"),
        col("de_samples"),
    );
    let mut seen = 0;
    for row in inv.records() {
        let row = row.unwrap();
        let file = &row[c_file];
        let path = cwru.join(file);
        let label = parse_cwru_name(file).unwrap_or_else(|| panic!("name {file}"));
        assert_eq!(label.record.to_string(), &row[c_rec], "{file}");
        assert_eq!(label.fs_hz, row[c_fs].parse::<f64>().unwrap(), "{file}");
        assert_eq!(
            label.fault_end.as_deref().unwrap_or(""),
            &row[c_end],
            "{file}"
        );
        assert_eq!(label.fault.type_name(), &row[c_type], "{file}");
        assert_eq!(
            label.fault.or_position().unwrap_or(""),
            &row[c_or],
            "{file}"
        );
        assert_eq!(label.load_hp.to_string(), &row[c_load], "{file}");
        match label.diameter_in {
            Some(d) => assert_eq!(d, row[c_dia].parse::<f64>().unwrap(), "{file}"),
            None => assert_eq!(&row[c_dia], "", "{file}"),
        }
        let r = read_cwru(&path, "DE", None)?;
        assert_eq!(
            r.fs,
            if file.starts_with("normal") {
                48000.0
            } else {
                12000.0
            }
        );
        assert!(r.samples.len() > 100_000, "{file}: {}", r.samples.len());
        assert_eq!(r.samples.len().to_string(), &row[c_n], "{file}");
        assert!(r.samples.iter().all(|x| x.is_finite()));
        let rpm = r.rpm.expect("rpm");
        assert!((1700.0..=1800.0).contains(&rpm), "{file}: {rpm}");
        assert_eq!(rpm, row[c_rpm].parse::<f64>().unwrap(), "{file}");
        let fe = read_cwru(&path, "FE", None)?;
        assert_eq!(fe.samples.len(), r.samples.len());
        seen += 1;
    }
    // Every .mat in the folder is in the inventory.
    let mats = std::fs::read_dir(&cwru)
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .path()
                .extension()
                .is_some_and(|x| x == "mat")
        })
        .count();
    assert_eq!(seen, mats);
    assert!(seen > 0);
    Ok(())
}

/// Two rates or two speeds beside the channel that disagree make the file ambiguous: refused,
/// both named, with the flag that settles it (which then reads the file); agreeing ones (rpm
/// and the same speed in Hz) and a disagreeing one elsewhere in the file (warned about) do not.
#[test]
fn a_file_stating_two_rates_or_speeds_for_its_channel_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let x: Vec<f64> = (0..600).map(|i| (i as f64 * 0.7).sin()).collect();
    let read = |name: &str, vars: &[(&str, &[f64])], fs: Option<f64>, rpm: Option<f64>| {
        let p = tmp_file(dir.path(), name, &mat5_bytes(vars));
        let opts = crate::io::ReadOptions {
            fs,
            rpm,
            ..Default::default()
        };
        read_mat_record(&p, &opts)
    };
    let two_rates: &[(&str, &[f64])] =
        &[("acc", &x), ("fs", &[12000.0]), ("sample_rate", &[24000.0])];
    let e = read("rates.mat", two_rates, None, None)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("two sample rates") && e.contains("`sample_rate` = 24000") && e.contains("--fs"),
        "{e}"
    );
    assert_eq!(
        read("rates.mat", two_rates, Some(12000.0), None)
            .unwrap()
            .fs,
        12000.0
    );
    let two_speeds: &[(&str, &[f64])] = &[
        ("acc", &x),
        ("fs", &[12000.0]),
        ("rpm", &[900.0]),
        ("rate", &[29.95]),
    ];
    let e = read("speeds.mat", two_speeds, None, None)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("two shaft speeds")
            && e.contains("`rate` = 29.95 (1797 rpm)")
            && e.contains("--rpm"),
        "{e}"
    );
    assert_eq!(
        read("speeds.mat", two_speeds, None, Some(1797.0))
            .unwrap()
            .rpm,
        Some(1797.0)
    );
    let agreeing: &[(&str, &[f64])] = &[
        ("acc", &x),
        ("fs", &[12000.0]),
        ("rpm", &[1797.0]),
        ("rate", &[29.95]),
    ];
    assert_eq!(
        read("agree.mat", agreeing, None, None).unwrap().rpm,
        Some(1797.0)
    );
    // The MFPT struct's own rate beside `gs` is taken over a root-level `fs` of another value.
    let p = tmp_file(dir.path(), "mfpt.mat", &{
        let mut b = super::fixture::mfpt_fixture(&x, 48_828.0, 25.0, 270.0);
        b.extend_from_slice(&mat5_bytes(&[("fs", &[12000.0])])[128..]);
        b
    });
    assert_eq!(
        read_mat_record(&p, &Default::default()).unwrap().fs,
        48_828.0
    );
}
