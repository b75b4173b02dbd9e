//! Property and corruption tests of the measurement readers: mutated, truncated and hostile
//! inputs must give `Err` naming the file, never a panic or an absurd allocation; valid data
//! written by `write_outputs` must read back exactly (CSV) or within f32 rounding (WAV).
//!
//! Fixtures are built by the tests themselves (a tiny MAT v5 writer in `io::mat::mat5_bytes`,
//! `write_outputs` for CSV/WAV); the first KB of one real CWRU file is mutated too when the
//! data folder is present. No data file is committed.

use std::path::{Path, PathBuf};

use proptest::prelude::*;
use wearsim_host::io::{self, mat, IoError, ReadOptions};

fn cfg(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// Apply byte mutations: (position fraction, new byte) pairs, then an optional truncation.
fn mutate(base: &[u8], edits: &[(f64, u8)], keep: Option<f64>) -> Vec<u8> {
    let mut b = base.to_vec();
    for &(at, v) in edits {
        if !b.is_empty() {
            let i = ((at * b.len() as f64) as usize).min(b.len() - 1);
            b[i] = v;
        }
    }
    if let Some(f) = keep {
        let n = (f * b.len() as f64) as usize;
        b.truncate(n);
    }
    b
}

/// Check the contract for a reader result on corrupt input: either Ok with finite samples and a
/// sane rate, or an error whose message names the file.
fn check(path: &Path, r: Result<io::Record, IoError>) -> Result<(), TestCaseError> {
    match r {
        Ok(rec) => {
            prop_assert!(rec.samples.iter().all(|x| x.is_finite()));
            prop_assert!(!rec.samples.is_empty());
            prop_assert!(rec.fs >= io::MIN_FS && rec.fs <= io::MAX_FS);
        }
        Err(e) => {
            let name = path.file_name().unwrap().to_string_lossy().to_string();
            let msg = e.to_string();
            // Sidecar errors name the sidecar, whose name starts with the data file's stem.
            let stem = path.file_stem().unwrap().to_string_lossy().to_string();
            prop_assert!(msg.contains(&name) || msg.contains(&stem), "{msg}");
        }
    }
    Ok(())
}

fn small_mat() -> Vec<u8> {
    let de: Vec<f64> = (0..64).map(|i| (i as f64 * 0.3).sin()).collect();
    let fe: Vec<f64> = (0..64).map(|i| i as f64 * 0.01).collect();
    mat::mat5_bytes(&[
        ("X105_DE_time", &de),
        ("X105_FE_time", &fe),
        ("X105RPM", &[1797.0]),
    ])
}

fn edits() -> impl Strategy<Value = Vec<(f64, u8)>> {
    prop::collection::vec((0.0f64..1.0, any::<u8>()), 0..8)
}

fn keep() -> impl Strategy<Value = Option<f64>> {
    prop::option::of(0.0f64..1.0)
}

proptest! {
    #![proptest_config(cfg(256))]

    #[test]
    fn mat_mutations_never_panic(e in edits(), k in keep(), compressed in any::<bool>()) {
        let base = small_mat();
        let base = if compressed { mat::mat5_compress(&base) } else { base };
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("12k_Drive_End_IR007_0_105.mat");
        std::fs::write(&p, mutate(&base, &e, k)).unwrap();
        check(&p, mat::read_cwru(&p, "DE", None))?;
        let _ = mat::list_mat_variables(&p);
    }

    #[test]
    fn mat_struct_layouts_mutations_never_panic(e in edits(), k in keep(), which in 0usize..3, compressed in any::<bool>()) {
        let x: Vec<f64> = (0..300).map(|i| (i as f64 * 0.3).sin()).collect();
        let base = match which {
            0 => mat::fixture::mfpt_fixture(&x, 48_828.0, 25.0, 0.0),
            1 => mat::fixture::paderborn_fixture("N09_M07_F10_K001_1", &[("vibration_1", &x)]),
            _ => mat::mat5_tree_bytes(&[("c", mat::FixtureValue::Cell(vec![
                mat::FixtureValue::Doubles(x.clone()),
                mat::FixtureValue::Char("note".into()),
                mat::FixtureValue::Empty,
            ])), ("fs", mat::FixtureValue::Doubles(vec![1000.0]))]),
        };
        let base = if compressed { mat::mat5_compress(&base) } else { base };
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("record.mat");
        std::fs::write(&p, mutate(&base, &e, k)).unwrap();
        check(&p, io::read_any(&p, &ReadOptions::default()))?;
        let _ = mat::read_mat_tree(&p, &|_| true);
    }

    #[test]
    fn mat_header_fields_hostile(offset in 128usize..300, value in any::<u32>()) {
        // Overwrite one aligned 32-bit word (tags, sizes, dims, flags) with any value.
        let mut b = small_mat();
        let o = offset & !3;
        if o + 4 <= b.len() {
            b[o..o + 4].copy_from_slice(&value.to_le_bytes());
        }
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("12k_Drive_End_IR007_0_105.mat");
        std::fs::write(&p, &b).unwrap();
        check(&p, mat::read_cwru(&p, "DE", None))?;
    }

    #[test]
    fn wav_mutations_never_panic(e in edits(), k in keep(), sidecar in any::<bool>()) {
        let dir = tempfile::tempdir().unwrap();
        let a: Vec<f64> = (0..50).map(|i| i as f64 - 25.0).collect();
        let set = io::write_outputs(dir.path(), "f", &[("v_g", &a)], 1000.0, &serde_json::json!({})).unwrap();
        if !sidecar {
            std::fs::remove_file(&set.json).unwrap();
        }
        let base = std::fs::read(&set.wav).unwrap();
        std::fs::write(&set.wav, mutate(&base, &e, k)).unwrap();
        check(&set.wav, io::read_any(&set.wav, &ReadOptions::default()))?;
    }

    #[test]
    fn csv_mutations_never_panic(e in edits(), k in keep()) {
        let dir = tempfile::tempdir().unwrap();
        let a: Vec<f64> = (0..30).map(|i| i as f64 * 0.5).collect();
        let set = io::write_outputs(dir.path(), "c", &[("v_g", &a), ("w_g", &a)], 1000.0, &serde_json::json!({})).unwrap();
        let base = std::fs::read(&set.csv).unwrap();
        std::fs::write(&set.csv, mutate(&base, &e, k)).unwrap();
        check(&set.csv, io::read_any(&set.csv, &ReadOptions::default()))?;
        // Mutate the sidecar as well.
        let side = std::fs::read(&set.json).unwrap();
        std::fs::write(&set.json, mutate(&side, &e, None)).unwrap();
        check(&set.csv, io::read_any(&set.csv, &ReadOptions::default()))?;
    }

    #[test]
    fn random_bytes_under_every_extension(bytes in prop::collection::vec(any::<u8>(), 0..600), ext in 0usize..6) {
        let names = ["x.mat", "x.wav", "x.csv", "x.npy", "2004.02.12.10.32.39", "x.txt"];
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join(names[ext]);
        std::fs::write(&p, &bytes).unwrap();
        let opts = ReadOptions { fs: Some(1000.0), ..Default::default() };
        check(&p, io::read_any(&p, &opts))?;
    }

    #[test]
    fn csv_round_trip_exact(
        v in prop::collection::vec(-1e30f64..1e30, 1..64),
        wide in prop::collection::vec(-1e300f64..1e300, 64),
        tiny in prop::collection::vec(-1e-300f64..1e-300, 1..4),
        fs in 1.0f64..1e6,
    ) {
        // The first column goes to the f32 WAV too, so it must fit f32; the second spans the
        // whole f64 range including subnormals.
        let dir = tempfile::tempdir().unwrap();
        let mut a = v.clone();
        a.extend(tiny.iter().map(|x| x * 1e-10));
        let mut b: Vec<f64> = wide[..a.len() - tiny.len()].to_vec();
        b.extend(tiny);
        let set = io::write_outputs(dir.path(), "r", &[("a_m_s2", &a), ("b_g", &b)], fs, &serde_json::json!({})).unwrap();
        let r = io::read_any(&set.csv, &ReadOptions::default()).unwrap();
        prop_assert_eq!(&r.samples, &a);
        prop_assert_eq!(r.fs, fs);
        let r = io::read_any(&set.csv, &ReadOptions { channel: Some("b_g".into()), ..Default::default() }).unwrap();
        prop_assert_eq!(&r.samples, &b);
        prop_assert_eq!(r.unit.as_str(), "g");
    }

    #[test]
    fn wav_round_trip_f32(v in prop::collection::vec(-1e30f64..1e30, 1..64), fs in 1u32..200_000) {
        let dir = tempfile::tempdir().unwrap();
        let set = io::write_outputs(dir.path(), "r", &[("a_m_s2", &v)], fs as f64, &serde_json::json!({})).unwrap();
        let r = io::read_any(&set.wav, &ReadOptions::default()).unwrap();
        prop_assert_eq!(r.samples.len(), v.len());
        for (x, y) in r.samples.iter().zip(&v) {
            prop_assert_eq!(*x, *y as f32 as f64);
        }
        prop_assert_eq!(r.fs, fs as f64);
        prop_assert_eq!(r.unit.as_str(), "m/s^2");
    }
}

fn data_file(rel: &str) -> Result<Option<PathBuf>, IoError> {
    Ok(io::data_dir()?.map(|d| d.join(rel)))
}

/// Mutate the first 4 KB of a real CWRU file (read at test time, never committed).
#[test]
fn real_mat_prefix_mutations() -> Result<(), IoError> {
    let Some(p) = data_file("cwru/12k_Drive_End_B007_0_118.mat")? else {
        return Ok(());
    };
    let full = std::fs::read(&p).map_err(|e| IoError::Io {
        path: p.clone(),
        op: "read",
        source: e,
    })?;
    let head = &full[..4096.min(full.len())];
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("12k_Drive_End_B007_0_118.mat");
    let mut runner = proptest::test_runner::TestRunner::new(cfg(128));
    runner
        .run(&(edits(), keep()), |(e, k)| {
            let mut b = mutate(head, &e, k);
            b.extend_from_slice(&full[head.len()..]);
            std::fs::write(&target, &b).unwrap();
            check(&target, mat::read_cwru(&target, "DE", None))
        })
        .unwrap();
    Ok(())
}

#[test]
fn corrupt_inputs_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cases: Vec<(&str, Vec<u8>)> = vec![
        ("empty.mat", vec![]),
        ("empty.wav", vec![]),
        ("empty.csv", vec![]),
        ("empty.npy", vec![]),
        ("wav_named.mat", {
            let a = [1.0, 2.0];
            let set = io::write_outputs(d, "tmpw", &[("a", &a)], 100.0, &serde_json::Value::Null)
                .unwrap();
            let b = std::fs::read(&set.wav).unwrap();
            for f in [set.csv, set.wav, set.json] {
                std::fs::remove_file(f).unwrap();
            }
            b
        }),
        ("mat_named.wav", small_mat()),
        ("mat_named.npy", small_mat()),
        ("thing.xyz", b"1,2,3".to_vec()),
        ("side.json", b"{}".to_vec()),
    ];
    for (name, bytes) in cases {
        let p = d.join(name);
        std::fs::write(&p, &bytes).unwrap();
        let e = io::read_any(
            &p,
            &ReadOptions {
                fs: Some(100.0),
                ..Default::default()
            },
        )
        .expect_err(name);
        assert!(e.to_string().contains(name), "{name}: {e}");
        assert_eq!(e.path(), p.as_path());
    }
    // Missing file.
    let p = d.join("missing.csv");
    let e = io::read_any(&p, &ReadOptions::default()).unwrap_err();
    assert!(matches!(e, IoError::Io { .. }) && e.to_string().contains("missing.csv"));
}

/// A MAT element claiming a huge size, and a compressed element inflating far beyond its size,
/// must fail without allocating in proportion to the claim.
#[test]
fn hostile_sizes_do_not_allocate() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("12k_Drive_End_IR007_0_105.mat");
    // miMATRIX claiming 4 GiB.
    let mut b = small_mat();
    b[132..136].copy_from_slice(&0xFFFF_FFF0u32.to_le_bytes());
    std::fs::write(&p, &b).unwrap();
    assert!(matches!(
        mat::read_cwru(&p, "DE", None),
        Err(IoError::Truncated { .. })
    ));
    // Dims claiming 2^31 x 2^31 elements.
    let mut b = small_mat();
    b[160..164].copy_from_slice(&i32::MAX.to_le_bytes());
    b[164..168].copy_from_slice(&i32::MAX.to_le_bytes());
    std::fs::write(&p, &b).unwrap();
    assert!(mat::read_cwru(&p, "DE", None).is_err());
    // A zlib stream of 64 MiB of zeros in a ~64 KB compressed element (a bomb at the deflate
    // ratio limit): inflating is bounded by 1032x the compressed size (so by the file size), and
    // the zeros are no valid variable, so the result is an error.
    use std::io::Write;
    let mut enc = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::best());
    let zeros = vec![0u8; 1 << 20];
    for _ in 0..64 {
        enc.write_all(&zeros).unwrap();
    }
    let z = enc.finish().unwrap();
    let mut bomb = small_mat()[..128].to_vec();
    bomb.extend_from_slice(&15u32.to_le_bytes());
    bomb.extend_from_slice(&(z.len() as u32).to_le_bytes());
    bomb.extend_from_slice(&z);
    std::fs::write(&p, &bomb).unwrap();
    let e = mat::read_cwru(&p, "DE", None).unwrap_err();
    assert!(
        e.to_string().contains("12k_Drive_End_IR007_0_105.mat"),
        "{e}"
    );
}

#[test]
fn data_dir_rules() {
    let missing = Some(std::ffi::OsString::from(
        "/nonexistent/wearsim-data-for-test",
    ));
    assert!(matches!(
        io::resolve_data_dir(missing.clone(), false),
        Ok(None)
    ));
    match io::resolve_data_dir(missing, true) {
        Err(IoError::DataDirMissing { path }) => {
            assert_eq!(path, PathBuf::from("/nonexistent/wearsim-data-for-test"))
        }
        other => panic!("{other:?}"),
    }
    let tmp = tempfile::tempdir().unwrap();
    let found = io::resolve_data_dir(Some(tmp.path().as_os_str().to_owned()), true).unwrap();
    assert_eq!(found.as_deref(), Some(tmp.path()));
}
