//! Writing the results of a life run: per-snapshot features, the stage timeline and the
//! event log (CSV and JSON), and the summary — each file written to a temporary file and
//! renamed, the summary last, so an interrupted run never leaves a set that looks complete.

use super::state_json::EventJson;
use super::{LifeRun, Snapshot};
use serde_json::json;
use std::io::Write;
use std::path::{Path, PathBuf};
use wearsim_core::wear::LifeState;

/// Writes `bytes` to `path` atomically (temporary file in the same directory, fsync, rename),
/// with the mode of a file created directly (the umask applies: [`crate::io::perms`]).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let mut tmp = crate::io::perms::output_builder().tempfile_in(dir)?;
    tmp.write_all(bytes)?;
    tmp.as_file().sync_all()?;
    tmp.persist(path).map_err(|e| e.error)?;
    Ok(())
}

/// Name of the completion marker of a life set (written last by [`write_life`]).
pub const SUMMARY: &str = "life-summary.json";

/// Name of the completion marker of a life-statistics set (`life --lives`, written last).
pub const LIVES_SUMMARY: &str = "lives.json";

/// Removes the completion marker of a life set in `dir` (if any) and syncs the directory,
/// before anything of a new run is written: a set is never presented as complete while
/// its files are being replaced.
pub fn invalidate(dir: &Path) -> std::io::Result<()> {
    remove_marker(dir, SUMMARY)
}

/// Removes the completion marker `name` in `dir` (if any) and syncs the directory (see
/// [`invalidate`]).
pub fn remove_marker(dir: &Path, name: &str) -> std::io::Result<()> {
    match std::fs::remove_file(dir.join(name)) {
        Ok(()) => {
            if let Ok(d) = std::fs::File::open(dir) {
                let _ = d.sync_all();
            }
            Ok(())
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(e),
    }
}

/// One stage's span in revolutions.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Span {
    /// Stage name.
    pub stage: String,
    /// First revolution.
    pub start: f64,
    /// Last revolution (the next stage's start, or the end of life).
    pub end: f64,
}

/// The stage timeline from the event log.
pub fn timeline(st: &LifeState) -> Vec<Span> {
    let mut spans: Vec<Span> = vec![Span {
        stage: "running-in".into(),
        start: 0.0,
        end: st.cycles,
    }];
    for e in st.events.iter() {
        if e.stage.name() == spans.last().map(|s| s.stage.as_str()).unwrap_or("") {
            continue;
        }
        if let Some(last) = spans.last_mut() {
            last.end = e.cycles;
        }
        spans.push(Span {
            stage: e.stage.name().into(),
            start: e.cycles,
            end: st.cycles,
        });
    }
    spans
}

/// Writes features, timeline, events and summary into `dir`; returns the files written.
/// Units of the columns of `life-features.csv` (and the fields of `life-features.json`'s
/// snapshots and their `features`), stated in `life-summary.json`: the windows are
/// simulated acceleration at the sensor in m/s².
pub fn units() -> serde_json::Value {
    json!({
        "cycles": "revolutions of the shaft",
        "life_fraction": "1 (cycles / cycles to failure)",
        "rms": "m/s^2",
        "kurtosis": "1 (m4/m2^2, 3 for Gaussian noise; not the excess)",
        "crest_factor": "1 (peak / rms)",
        "zone_rotating": "m/s^2 (RMS in the band)",
        "zone_fault": "m/s^2 (RMS in the band)",
        "zone_natural": "m/s^2 (RMS in the band; 0 when the band lies beyond fs/2)",
        "zone_high": "m/s^2 (RMS in the band; 0 when the band lies beyond fs/2)",
        "fault_peak": "m/s^2 (envelope-spectrum amplitude at the wear site's pass frequency)",
        "resonance_peak": "m/s^2 (amplitude-spectrum peak within ±30 % of the natural frequency; 0 when none)",
        "asperity_m": "m", "length_m": "m", "crack_m": "m",
        "count": "1 (defects)",
        "debris": "1 (debris level)",
        "zone_load_n": "N (power mean of the pass loads in the load zone)",
        "edge_load_n": "N (cubic mean of the defect-edge loads)",
    })
}

pub fn write_life(
    dir: &Path,
    run: &LifeRun,
    snapshots: &[Snapshot],
    st: &LifeState,
    extra: serde_json::Value,
) -> std::io::Result<Vec<PathBuf>> {
    let _lock = crate::io::lock::DirLock::try_acquire(dir).map_err(std::io::Error::other)?;
    invalidate(dir)?;
    let life_end = st.cycles.max(1.0);
    let mut csv = String::from("cycles,life_fraction,stage,rms,kurtosis,crest_factor,zone_rotating,zone_fault,zone_natural,zone_high,fault_peak,resonance_peak,asperity_m,length_m,count,crack_m,debris,zone_load_n,edge_load_n\n");
    for s in snapshots {
        let f = &s.features;
        csv.push_str(&format!(
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
            s.cycles,
            s.cycles / life_end,
            s.stage,
            f.rms,
            f.kurtosis,
            f.crest_factor,
            f.zone_rotating,
            f.zone_fault,
            f.zone_natural,
            f.zone_high,
            f.fault_peak,
            f.resonance_peak,
            s.asperity,
            s.length,
            s.count,
            s.crack,
            s.debris,
            s.zone_load,
            s.edge_load
        ));
    }
    let spans = timeline(st);
    let mut tl = String::from("stage,start_cycles,end_cycles\n");
    for s in &spans {
        tl.push_str(&format!("{},{},{}\n", s.stage, s.start, s.end));
    }
    let events: Vec<EventJson> = st.events.iter().map(Into::into).collect();
    let mut ev = String::from("stage,cycles,asperity_m,length_m,width_m,depth_m,count,crack_m\n");
    for e in &events {
        let t = &e.topography;
        ev.push_str(&format!(
            "{},{},{},{},{},{},{},{}\n",
            e.stage, e.cycles, t.asperity_height, t.length, t.width, t.depth, t.count, e.crack
        ));
    }
    let files = [
        ("life-features.csv", csv.into_bytes()),
        ("life-features.json", serde_json::to_vec_pretty(snapshots)?),
        ("life-timeline.csv", tl.into_bytes()),
        ("life-events.csv", ev.into_bytes()),
        (
            "life-events.json",
            serde_json::to_vec_pretty(
                &json!({ "events": events, "timeline": spans, "lost_events": st.lost_events }),
            )?,
        ),
    ];
    let mut written = vec![];
    for (name, bytes) in files {
        let p = dir.join(name);
        write_atomic(&p, &bytes)?;
        written.push(p);
    }
    let summary = json!({
        "complete": true,
        "cycles_to_failure": st.cycles,
        "stage": st.stage.name(),
        "site": super::site_json::site_json(run),
        "events": events,
        "timeline": spans,
        "snapshots": snapshots.len(),
        "rating_n": run.life.rating(),
        "weibull_scatter": st.scatter,
        "propagation_scatter": st.propagation_scatter,
        "initiation_scatter": st.initiation_scatter,
        "dent_scatter": st.dent_scatter,
        "seed": run.spec.seed,
        "units": units(),
        "run": extra,
    });
    let p = dir.join(SUMMARY);
    write_atomic(&p, &serde_json::to_vec_pretty(&summary)?)?;
    written.push(p);
    Ok(written)
}
