//! Unit tests of the MAT tree reader and the layout/channel/metadata resolution.

use super::fixture::{mfpt_fixture, paderborn_fixture};
use super::*;
use crate::io::{read_any, IoError, ReadOptions};
use serde_json::json;
use std::path::{Path, PathBuf};

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

fn opts(channel: Option<&str>, fs: Option<f64>) -> ReadOptions {
    ReadOptions {
        channel: channel.map(str::to_string),
        fs,
        rpm: None,
    }
}

fn signal(n: usize) -> Vec<f64> {
    (0..n).map(|i| (i as f64 * 0.37).sin()).collect()
}

#[test]
fn mfpt_struct_plain_and_compressed_uses_stored_metadata() {
    let dir = tempfile::tempdir().unwrap();
    let gs = signal(1000);
    let raw = mfpt_fixture(&gs, 97_656.0, 25.0, 270.0);
    for (k, b) in [raw.clone(), mat5_compress(&raw)].iter().enumerate() {
        // A name that says nothing: the layout is recognised by content.
        let p = write(dir.path(), &format!("anything{k}.mat"), b);
        let r = read_any(&p, &opts(None, None)).unwrap();
        assert_eq!(r.samples, gs);
        assert_eq!(r.fs, 97_656.0);
        assert_eq!(r.rpm, Some(1500.0));
        assert_eq!(r.unit, "g");
        assert_eq!(r.bearing.as_deref(), Some("mfpt-nice"));
        assert_eq!(r.meta["layout"], json!("mfpt"));
        assert_eq!(r.meta["fs_source"], json!("file:bearing.sr"));
        assert_eq!(r.meta["rpm_source"], json!("file:bearing.rate"));
        assert_eq!(r.meta["load"], json!(270.0));
        for ch in ["bearing.gs", "gs", "bearing(1).gs"] {
            assert_eq!(
                read_any(&p, &opts(Some(ch), None)).unwrap().samples,
                gs,
                "{ch}"
            );
        }
        // Agreeing --fs is accepted, a contradicting one is refused naming the field.
        assert!(read_any(&p, &opts(None, Some(97_656.0))).is_ok());
        let e = read_any(&p, &opts(None, Some(48_828.0))).unwrap_err();
        assert!(matches!(e, IoError::Contradiction { .. }), "{e}");
        assert!(e.to_string().contains("field fs"), "{e}");
        // A wrong name lists every numeric array with its shape.
        match read_any(&p, &opts(Some("DE"), None)).unwrap_err() {
            IoError::UnknownChannel { available, .. } => assert_eq!(
                available,
                vec![
                    "bearing.sr [1x1] double",
                    "bearing.gs [1000x1] double",
                    "bearing.load [1x1] double",
                    "bearing.rate [1x1] double"
                ]
            ),
            e => panic!("{e}"),
        }
    }
}

#[test]
fn paderborn_nested_struct_array() {
    let dir = tempfile::tempdir().unwrap();
    let vib = signal(2000);
    let force = vec![1.0; 300];
    let raw = paderborn_fixture(
        "N15_M07_F10_K001_1",
        &[("force", &force), ("vibration_1", &vib)],
    );
    let p = write(dir.path(), "x.mat", &mat5_compress(&raw));
    let r = read_any(&p, &opts(None, None)).unwrap();
    let want: Vec<f64> = vib.iter().map(|&x| x as f32 as f64).collect();
    assert_eq!(r.samples, want);
    assert_eq!((r.fs, r.rpm), (64_000.0, Some(1500.0)));
    assert_eq!(r.channel, "vibration_1");
    assert_eq!(r.meta["layout"], json!("paderborn"));
    assert_eq!(r.meta["variable"], json!("N15_M07_F10_K001_1.Y(2).Data"));
    assert_eq!(r.meta["fs_source"], json!("layout:paderborn"));
    assert_eq!(r.bearing.as_deref(), Some("paderborn-6203"));
    let f = read_any(&p, &opts(Some("force"), None)).unwrap();
    assert_eq!(f.samples, force);
    let g = read_any(&p, &opts(Some("N15_M07_F10_K001_1.Y(1).Data"), None)).unwrap();
    assert_eq!(g.samples, force);
}

fn typed(class: u8, mi: u32, bytes: Vec<u8>, n: i32) -> FixtureValue {
    FixtureValue::Typed {
        class,
        mi,
        dims: vec![1, n],
        bytes,
        logical: false,
    }
}

#[test]
fn every_class_cells_chars_empty_and_sparse() {
    use super::v5::*;
    let le16 = |v: &[i16]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    let vars = vec![
        ("i8", typed(8, MI_INT8, vec![0xFF, 2], 2)),
        ("u8", typed(9, MI_UINT8, vec![255, 2], 2)),
        ("i16", typed(10, MI_INT16, le16(&[-300, 7]), 2)),
        (
            "u16",
            typed(11, MI_UINT16, 65535u16.to_le_bytes().to_vec(), 1),
        ),
        (
            "i32",
            typed(12, MI_INT32, (-70000i32).to_le_bytes().to_vec(), 1),
        ),
        (
            "u32",
            typed(13, MI_UINT32, 4_000_000_000u32.to_le_bytes().to_vec(), 1),
        ),
        (
            "i64",
            typed(14, MI_INT64, (-5i64).to_le_bytes().to_vec(), 1),
        ),
        ("u64", typed(15, MI_UINT64, 9u64.to_le_bytes().to_vec(), 1)),
        ("f32", typed(7, MI_SINGLE, 1.5f32.to_le_bytes().to_vec(), 1)),
        // MATLAB stores small doubles in a narrower type.
        ("dsmall", typed(6, MI_UINT8, vec![3, 4], 2)),
        (
            "flag",
            FixtureValue::Typed {
                class: 9,
                mi: MI_UINT8,
                dims: vec![1, 1],
                bytes: vec![1],
                logical: true,
            },
        ),
        ("empty", FixtureValue::Empty),
        ("sp", FixtureValue::Sparse),
        ("note", FixtureValue::Char("µ-sensor".into())),
        (
            "c",
            FixtureValue::Cell(vec![
                FixtureValue::Doubles(signal(400)),
                FixtureValue::Char("x".into()),
            ]),
        ),
        ("fs", FixtureValue::Doubles(vec![25_600.0])),
    ];
    let raw = mat5_tree_bytes(&vars);
    let tree = parse_mat_tree(&raw, Path::new("t.mat"), &|_| true).unwrap();
    let val = |p: &str| tree::find(&tree, p).unwrap().numbers().unwrap().to_vec();
    assert_eq!(val("i8"), vec![-1.0, 2.0]);
    assert_eq!(val("u8"), vec![255.0, 2.0]);
    assert_eq!(val("i16"), vec![-300.0, 7.0]);
    assert_eq!(val("u16"), vec![65535.0]);
    assert_eq!(val("i32"), vec![-70000.0]);
    assert_eq!(val("u32"), vec![4e9]);
    assert_eq!(val("i64"), vec![-5.0]);
    assert_eq!(val("u64"), vec![9.0]);
    assert_eq!(val("f32"), vec![1.5]);
    assert_eq!(val("dsmall"), vec![3.0, 4.0]);
    assert_eq!(val("flag"), vec![1.0]);
    assert!(val("empty").is_empty());
    assert_eq!(tree::find(&tree, "note").unwrap().text(), Some("µ-sensor"));
    assert_eq!(tree::find(&tree, "c{2}").unwrap().text(), Some("x"));
    let arrays = numeric_arrays(&tree);
    assert!(arrays.iter().any(|a| a.label() == "flag [1x1] logical"));
    assert!(arrays.iter().any(|a| a.label() == "c{1} [400x1] double"));

    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), "g.mat", &mat5_compress(&raw));
    // The only long signal is the cell element; the stored scalar `fs` gives the rate.
    let r = read_any(&p, &opts(None, None)).unwrap();
    assert_eq!(r.samples, signal(400));
    assert_eq!(r.meta["variable"], json!("c{1}"));
    assert_eq!(r.meta["fs_source"], json!("file:fs"));
    assert_eq!(r.fs, 25_600.0);
    let e = read_any(&p, &opts(Some("sp"), None)).unwrap_err();
    assert!(e.to_string().contains("sparse"), "{e}");
}

#[test]
fn no_numeric_array_and_struct_without_signal_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(
        dir.path(),
        "a.mat",
        &mat5_tree_bytes(&[("note", FixtureValue::Char("hello".into()))]),
    );
    let e = read_any(&p, &opts(None, None)).unwrap_err();
    assert!(e.to_string().contains("no numeric array"), "{e}");
    let s = FixtureValue::Struct {
        dims: vec![1, 1],
        fields: vec!["a".into(), "b".into()],
        elems: vec![vec![
            FixtureValue::Doubles(vec![1.0, 2.0]),
            FixtureValue::Char("z".into()),
        ]],
    };
    let p = write(dir.path(), "b.mat", &mat5_tree_bytes(&[("s", s)]));
    let e = read_any(&p, &opts(Some("s"), Some(1000.0))).unwrap_err();
    assert!(
        e.to_string().contains("without a recognisable signal"),
        "{e}"
    );
    let e = read_any(&p, &opts(None, Some(1000.0))).unwrap_err();
    assert!(matches!(e, IoError::UnknownChannel { .. }), "{e}");
    assert!(e.to_string().contains("s.a [2x1] double"), "{e}");
}

#[test]
fn nesting_depth_is_bounded() {
    let mut v = FixtureValue::Doubles(vec![1.0]);
    for _ in 0..40 {
        v = FixtureValue::Cell(vec![v]);
    }
    let raw = mat5_tree_bytes(&[("deep", v)]);
    let e = parse_mat_tree(&raw, Path::new("d.mat"), &|_| true).unwrap_err();
    assert!(e.to_string().contains("nested deeper"), "{e}");
    // A struct that declares more elements than the bytes can hold allocates nothing.
    let mut raw = mat5_tree_bytes(&[(
        "s",
        FixtureValue::Struct {
            dims: vec![1, 1],
            fields: vec!["a".into()],
            elems: vec![vec![FixtureValue::Empty]],
        },
    )]);
    // dims sub-element of the top struct: header 128 + tag 8 + flags 16 + dims tag 8.
    let at = 128 + 8 + 16 + 8;
    raw[at..at + 4].copy_from_slice(&i32::MAX.to_le_bytes());
    raw[at + 4..at + 8].copy_from_slice(&i32::MAX.to_le_bytes());
    assert!(parse_mat_tree(&raw, Path::new("d.mat"), &|_| true).is_err());
}

#[test]
fn cwru_through_the_general_reader() {
    let dir = tempfile::tempdir().unwrap();
    let de = signal(500);
    let raw = mat5_bytes(&[
        ("X099_DE_time", &[9.0; 500]),
        ("X105_DE_time", &de),
        ("X105RPM", &[1797.0]),
    ]);
    let p = write(
        dir.path(),
        "12k_Drive_End_IR007_0_105.mat",
        &mat5_compress(&raw),
    );
    let r = read_any(&p, &opts(None, None)).unwrap();
    assert_eq!(r.samples, de);
    assert_eq!(
        (r.fs, r.rpm, r.channel.as_str()),
        (12_000.0, Some(1797.0), "DE")
    );
    assert_eq!(r.bearing.as_deref(), Some("cwru-6205-de"));
    assert_eq!(r.meta["rpm_source"], json!("file:X105RPM"));
    let r = read_any(&p, &opts(Some("X099_DE_time"), None)).unwrap();
    assert_eq!((r.samples[0], r.channel.as_str()), (9.0, "DE"));
    match read_any(&p, &opts(Some("FE"), None)).unwrap_err() {
        IoError::UnknownChannel { available, .. } => {
            assert_eq!(available.len(), 3);
            assert_eq!(available[1], "X105_DE_time [500x1] double");
        }
        e => panic!("{e}"),
    }
}
