//! Writing the documented feature table ([`super::feature_table`]) atomically, and the
//! conversion of a bearing of an IMS feature table into it.

use std::path::{Path, PathBuf};

use super::error::IoError;
use super::feature_table::{
    check_against_table, check_rows, check_sidecar, median_step, parse_band, sidecar_path,
    BearingInfo, FeatureRow, FeatureSidecar, FeatureTableError, FORMAT, FORMAT_VERSION,
    MIN_SNAPSHOTS, REQUIRED,
};

/// Writes `csv` and its sidecar atomically: both go to temporary files in the same folder
/// (which is locked, [`super::lock::DirLock`]), any old sidecar is removed, the CSV is
/// renamed into place and the sidecar last, so a table with a sidecar is complete. The
/// table is checked first (the same rules as [`super::feature_table::read_feature_table`]); nothing is written
/// if it fails. Numbers are written in shortest round-trip form.
pub fn write_feature_table(
    csv: &Path,
    sidecar: &FeatureSidecar,
    rows: &[FeatureRow],
    bands: &[(String, Vec<f64>)],
) -> Result<PathBuf, FeatureTableError> {
    let side = sidecar_path(csv);
    if csv.extension().is_none_or(|e| e != "csv") {
        return Err(IoError::unsupported(csv, "a feature table is written to a .csv file").into());
    }
    if rows.len() < MIN_SNAPSHOTS {
        return Err(FeatureTableError::TooFewSnapshots {
            path: csv.to_path_buf(),
            n: rows.len(),
            min: MIN_SNAPSHOTS,
        });
    }
    check_sidecar(&side, sidecar)?;
    check_rows(csv, rows)?;
    check_against_table(csv, &side, sidecar, rows)?;
    for (name, v) in bands {
        if parse_band(name).is_none() || v.len() != rows.len() {
            return Err(IoError::unsupported(
                csv,
                format!("band column {name:?}: name band_<lo>_<hi>_hz with one value per row"),
            )
            .into());
        }
    }
    let dir = match csv.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let _lock = super::lock::DirLock::try_acquire(&dir)?;
    let mut text = String::new();
    text.push_str(&REQUIRED.join(","));
    for (n, _) in bands {
        text.push(',');
        text.push_str(n);
    }
    text.push('\n');
    let mut buf = ryu::Buffer::new();
    for (i, r) in rows.iter().enumerate() {
        text.push_str(&r.snapshot.to_string());
        for v in [
            r.time_s,
            r.rms,
            r.kurtosis,
            r.crest_factor,
            r.skewness,
            r.peak,
        ] {
            text.push(',');
            text.push_str(buf.format(v));
        }
        for (_, v) in bands {
            text.push(',');
            text.push_str(buf.format(v.get(i).copied().unwrap_or(f64::NAN)));
        }
        text.push('\n');
    }
    let json = serde_json::to_string_pretty(sidecar)
        .map_err(|e| IoError::malformed(&side, e.to_string()))?;
    let put = |suffix: &str, body: &str| -> Result<tempfile::NamedTempFile, IoError> {
        let mut t = super::perms::output_builder()
            .prefix(".feature-table.")
            .suffix(suffix)
            .tempfile_in(&dir)
            .map_err(|e| IoError::io(&dir, "create temporary", e))?;
        use std::io::Write;
        t.write_all(body.as_bytes())
            .and_then(|_| t.as_file().sync_all())
            .map_err(|e| IoError::io(t.path(), "write", e))?;
        Ok(t)
    };
    let tmp_csv = put(".csv.tmp", &text)?;
    let tmp_json = put(".json.tmp", &json)?;
    match std::fs::remove_file(&side) {
        Ok(()) => {}
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
        Err(e) => return Err(IoError::io(&side, "remove old sidecar", e).into()),
    }
    tmp_csv
        .persist(csv)
        .map_err(|e| IoError::io(csv, "rename", e.error))?;
    if let Err(e) = tmp_json.persist(&side) {
        let _ = std::fs::remove_file(csv);
        return Err(IoError::io(&side, "rename", e.error).into());
    }
    Ok(side)
}

/// Builds the documented table of bearing `bearing` of an IMS feature table
/// (`features_chocho66/test*_timefeatures.csv`): live snapshots only (the rule of
/// [`super::ims_life::live_snapshots`]), time since the first snapshot of the test,
/// kurtosis converted from excess, peak = `B<k>_max_abs`. Rows whose statistics are not
/// finite or whose RMS is not positive are left out, as [`super::ims_life::read_life`] does.
pub fn from_ims_features(
    path: &Path,
    bearing: usize,
    source: &str,
) -> Result<(FeatureSidecar, Vec<FeatureRow>), FeatureTableError> {
    let f = super::ims::read_ims_features(path)?;
    let live = super::ims_life::live_snapshots(&f);
    let col = |name: &str| -> Result<&[f64], FeatureTableError> {
        let c = format!("B{bearing}_{name}");
        f.column(&c).ok_or(FeatureTableError::MissingColumn {
            path: path.to_path_buf(),
            column: c,
        })
    };
    let (rms, kurt, crest, skew, peak) = (
        col("rms")?,
        col("kurtosis")?,
        col("crest")?,
        col("skew")?,
        col("max_abs")?,
    );
    let mut rows = vec![];
    for (i, l) in live.iter().enumerate() {
        let r = FeatureRow {
            snapshot: i as u64,
            time_s: f.unix_s.get(i).copied().unwrap_or(0) as f64
                - f.unix_s.first().copied().unwrap_or(0) as f64,
            rms: rms[i],
            kurtosis: kurt[i] + 3.0,
            crest_factor: crest[i],
            skewness: skew[i],
            peak: peak[i],
        };
        let ok = [r.rms, r.kurtosis, r.crest_factor, r.skewness, r.peak]
            .iter()
            .all(|v| v.is_finite())
            && r.rms > 0.0;
        if *l && ok {
            rows.push(r);
        }
    }
    let sidecar = FeatureSidecar {
        format: FORMAT.into(),
        format_version: FORMAT_VERSION,
        source: source.into(),
        bearing: BearingInfo {
            preset: Some("ims-za2115".into()),
            geometry: None,
            id: format!("bearing {bearing}"),
        },
        channel: format!("B{bearing}"),
        unit: "g".into(),
        rpm: super::ims::IMS_RPM,
        radial_load_n: 6000.0 * 4.448_221_6,
        sample_rate_hz: super::ims::IMS_FS,
        snapshot_samples: super::ims::IMS_ROWS as u64,
        snapshot_interval_s: median_step(&rows),
        failure_mode: "unknown".into(),
        n_snapshots: Some(rows.len() as u64),
        notes: vec![format!(
            "converted from {} (dead snapshots dropped: mean |x| below 10 % of the test median on every channel)",
            path.display()
        )],
    };
    Ok((sidecar, rows))
}
