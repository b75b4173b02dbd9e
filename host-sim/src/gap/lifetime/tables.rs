//! The measured side of a lifetime diagnosis from documented feature tables
//! (`docs/feature-tables.md`, [`crate::io::feature_table`]): one table per life, each read
//! into the same [`MeasuredLife`] an IMS table gives, then the one path of
//! [`super::measured_from`]. The simulated bearing is built from each table's sidecar
//! ([`RigDescription::from_sidecar`]: its preset, or its geometry and operating point);
//! all lives of one diagnosis must describe the same bearing, or the field that differs
//! is named. The training life must have failed (its length calibrates the life
//! factor); a held-out life is judged over its whole life unless it did not fail
//! ([`super::diagnose::holdout_t_max`]).

use super::diagnose::{measured_from, LifeOptions, MeasuredSet};
use super::rig::RigDescription;
use super::MeasuredLife;
use crate::io::feature_table::{read_feature_table, sidecar_path, MAX_TABLE_BYTES};
use std::path::{Path, PathBuf};

/// Refuses a life given twice among the tables `lives` of `paths` (numbered from 1, as
/// `--train`/`--holdout` count them): the same file (resolved path) or two files of
/// identical content. A held-out life that is the training life would be reported as an
/// out-of-sample result while it is in-sample. A number without a table is left to the
/// reader, which names it.
fn distinct(paths: &[PathBuf], lives: impl Iterator<Item = usize>) -> Result<(), String> {
    let mut seen: Vec<(usize, &Path, PathBuf, u64, u64)> = vec![];
    for k in lives {
        let Some(p) = k.checked_sub(1).and_then(|i| paths.get(i)) else {
            continue;
        };
        let real = p.canonicalize().unwrap_or_else(|_| p.clone());
        let read =
            |p: &Path| crate::io::record::read_capped(p, MAX_TABLE_BYTES, "feature table", "").ok();
        let bytes = read(p);
        let (len, hash) = bytes.as_deref().map_or((0, 0), |b| {
            use std::hash::{Hash, Hasher};
            let mut h = std::collections::hash_map::DefaultHasher::new();
            b.hash(&mut h);
            (b.len() as u64, h.finish())
        });
        for (j, q, real_q, len_q, hash_q) in &seen {
            let what = if *real_q == real {
                "are the same file".to_string()
            } else if bytes.is_some() && (*len_q, *hash_q) == (len, hash) && read(q) == bytes {
                "have identical contents".to_string()
            } else {
                continue;
            };
            return Err(format!(
                "--real: tables {j} ({}) and {k} ({}) {what}: one life given twice; the training life and each held-out life must be different lives (a held-out life that is the training life is no out-of-sample test)",
                q.display(),
                p.display()
            ));
        }
        seen.push((k, p, real, len, hash));
    }
    Ok(())
}

/// Reads documented feature tables `paths` (life `k` is `paths[k - 1]`): life `o.train`
/// is trained on, lives `o.holdout` judged. Every problem is one of the input.
pub fn measured_tables(paths: &[PathBuf], o: &LifeOptions) -> Result<MeasuredSet, String> {
    let read = |k: usize| -> Result<(MeasuredLife, RigDescription), String> {
        let p = k
            .checked_sub(1)
            .and_then(|i| paths.get(i))
            .ok_or_else(|| {
                format!(
                    "life {k}: only {} feature tables were given (--train/--holdout count the --real tables from 1)",
                    paths.len()
                )
            })?;
        let t = read_feature_table(p).map_err(|e| e.to_string())?;
        let rig = RigDescription::from_sidecar(&t.sidecar, p)?;
        Ok((t.to_life(k), rig))
    };
    let (train, rig) = read(o.train)?;
    if !train.failed() {
        return Err(format!(
            "{}: sidecar field `failure_mode`: {:?}, but the training life must have run to failure ({}): its length calibrates the life factor, and a life that did not fail (or is not known to have) would set it to a life that never ended",
            sidecar_path(std::path::Path::new(&train.file)).display(),
            train.failure_mode,
            crate::io::feature_table::FAILURE_MODES
                .iter()
                .filter(|m| !matches!(**m, "none" | "unknown"))
                .copied()
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    let mut holdout = vec![];
    for k in &o.holdout {
        let (life, r) = read(*k)?;
        if let Some((f, ours, theirs)) = rig.differs(&r) {
            return Err(format!(
                "{}: sidecar field `{f}` differs from the training life's ({}): {theirs} against {ours}; the lives of one diagnosis share one simulated bearing",
                sidecar_path(std::path::Path::new(&life.file)).display(),
                sidecar_path(std::path::Path::new(&train.file)).display()
            ));
        }
        holdout.push(life);
    }
    let set = measured_from(train, holdout, rig)?;
    // Last, so that a table's own problem (and one of the pair's: bearings that differ, a
    // table too sparse for the stages) is named first; still before any simulation.
    distinct(
        paths,
        std::iter::once(o.train).chain(o.holdout.iter().copied()),
    )?;
    Ok(set)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Probe defect: `gap --life --real A --real A` was accepted and reported a
    /// held-out life that was the training life. The same file (also through another
    /// spelling of its path) and a copy of it are refused naming `--real`; two different
    /// tables are not.
    #[test]
    fn a_life_given_twice_is_refused() {
        let dir = std::env::temp_dir().join(format!("wearsim-distinct-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        let (a, b, copy) = (dir.join("a.csv"), dir.join("b.csv"), dir.join("copy.csv"));
        std::fs::write(&a, "snapshot,time_s\n0,0\n").unwrap();
        std::fs::write(&b, "snapshot,time_s\n0,1\n").unwrap();
        std::fs::write(&copy, "snapshot,time_s\n0,0\n").unwrap();
        let again = dir.join("sub").join("..").join("a.csv");
        let check = |ps: Vec<PathBuf>| distinct(&ps, 1..=ps.len());
        let e = check(vec![a.clone(), again]).unwrap_err();
        assert!(e.starts_with("--real: tables 1 ("), "{e}");
        assert!(
            e.contains("and 2 (") && e.contains("are the same file"),
            "{e}"
        );
        let e = check(vec![a.clone(), b.clone(), copy.clone()]).unwrap_err();
        assert!(e.contains("tables 1 (") && e.contains("and 3 ("), "{e}");
        assert!(e.contains("identical contents"), "{e}");
        assert!(check(vec![a.clone(), b.clone()]).is_ok());
        // Only the lives of the diagnosis count: a copy that is neither trained on nor
        // held out is not one of them.
        assert!(distinct(&[a, b, copy], [1, 2].into_iter()).is_ok());
        let _ = std::fs::remove_dir_all(&dir);
    }
}
