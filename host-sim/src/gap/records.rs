//! Measured records for `wearsim gap`: reading the files, resolving each record's metadata
//! (bearing, speed, defect, unit) from the file, its label and the command line, checking
//! that metadata against the content, and building the matched simulations of the
//! training and held-out parts.

use super::matched::{Matched, MEMO};
use super::memo::Memo;
use super::validate::spec_of;
use super::{CellSpec, Reference};
use crate::analysis::{self, FaultFamily};
use crate::io::{self, mat::CwruFault, ReadOptions, Record};
use serde::Serialize;
use std::path::{Path, PathBuf};
use wearsim_core::forces::defect::{DefectConfig, DefectLocation, DefectModel};
use wearsim_core::speed::SpeedProfile;
use wearsim_core::{presets, topography::Topography, ModelConfig, Real};

/// Standard gravity (m/s² per g), for records in g.
pub const G: f64 = 9.80665;
/// Depth of a defect given without one (m): the CWRU EDM depth, 0.011 in.
pub const DEFAULT_DEPTH: f64 = 0.011 * 0.0254;
/// Shortest part (training or held-out) of a record the gap accepts (s): 8 segments of
/// at least 0.0625 s, i.e. ≥ 5 periods of a 100 Hz fault frequency per segment.
pub const MIN_PART_S: f64 = 0.5;

/// Samples of `seconds` at `fs`, to the nearest sample: the fewest a record of that
/// duration holds (a part of [`MIN_PART_S`] is 24 414 samples at 48 828.125 Hz).
pub fn min_samples(seconds: f64, fs: f64) -> usize {
    (seconds * fs).round() as usize
}

/// A defect as the command line or a label gives it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DefectSpec {
    /// `inner`, `outer@6`, `outer@3`, `outer@12`, `ball`.
    pub location: &'static str,
    /// Size along the track and across it (m).
    pub size: f64,
    /// Depth (m).
    pub depth: f64,
}

/// Locations `--defect` accepts.
pub const LOCATIONS: &str = "none, inner, outer (= outer@6), outer@3, outer@6, outer@12, ball";

fn parse_len(s: &str, what: &str) -> Result<f64, String> {
    let s = s.trim();
    let (num, scale) = if let Some(n) = s.strip_suffix("in") {
        (n, 0.0254)
    } else if let Some(n) = s.strip_suffix("mm") {
        (n, 1e-3)
    } else {
        return Err(format!(
            "--defect: {what} `{s}` needs a unit: `in` or `mm` (e.g. 0.007in, 0.18mm)"
        ));
    };
    let v: f64 = num
        .trim()
        .parse()
        .map_err(|_| format!("--defect: {what} `{s}` is not a number"))?;
    let m = v * scale;
    if !(m.is_finite() && (1e-6..=0.02).contains(&m)) {
        return Err(format!(
            "--defect: {what} {s} is out of range 0.001 mm ..= 20 mm"
        ));
    }
    Ok(m)
}

/// Parses `LOCATION:SIZE[:DEPTH]` (`none` alone for a healthy record).
pub fn parse_defect(s: &str) -> Result<Option<DefectSpec>, String> {
    let parts: Vec<&str> = s.split(':').map(str::trim).collect();
    let loc = parts.first().copied().unwrap_or("");
    if loc == "none" {
        return Ok(None);
    }
    let location = match loc {
        "inner" => "inner",
        "outer" | "outer@6" => "outer@6",
        "outer@3" => "outer@3",
        "outer@12" => "outer@12",
        "ball" => "ball",
        other => {
            return Err(format!(
                "--defect: unknown location `{other}`; the model knows: {LOCATIONS}"
            ))
        }
    };
    let Some(size) = parts.get(1) else {
        return Err(format!(
            "--defect {s}: give the size, LOCATION:SIZE[:DEPTH] (e.g. inner:0.007in)"
        ));
    };
    let size = parse_len(size, "size")?;
    let depth = match parts.get(2) {
        Some(d) => parse_len(d, "depth")?,
        None => DEFAULT_DEPTH,
    };
    if parts.len() > 3 {
        return Err(format!("--defect {s}: expected LOCATION:SIZE[:DEPTH]"));
    }
    Ok(Some(DefectSpec {
        location,
        size,
        depth,
    }))
}

/// The defect a CWRU file name states (None: normal; Err: not a CWRU name).
fn cwru_defect(path: &Path) -> Option<Option<DefectSpec>> {
    let name = path.file_name()?.to_string_lossy().into_owned();
    let label = io::mat::parse_cwru_name(&name)?;
    let size = label.diameter_in.map(|d| d * 0.0254);
    let location = match label.fault {
        CwruFault::Normal => return Some(None),
        CwruFault::InnerRace => "inner",
        CwruFault::Ball => "ball",
        CwruFault::OuterRace { clock: 3 } => "outer@3",
        CwruFault::OuterRace { clock: 12 } => "outer@12",
        CwruFault::OuterRace { .. } => "outer@6",
    };
    Some(size.map(|size| DefectSpec {
        location,
        size,
        depth: DEFAULT_DEPTH,
    }))
}

/// One measured record with its resolved metadata.
#[derive(Debug, Clone, Serialize)]
pub struct RealRecord {
    /// File.
    pub file: PathBuf,
    /// Samples in m/s².
    #[serde(skip)]
    pub accel: Vec<f64>,
    /// Sample rate (Hz).
    pub fs: f64,
    /// Shaft speed (rpm) used.
    pub rpm: f64,
    /// Where the speed came from: `argument`, `file`, `spectrum` (no speed stated: the
    /// strongest line near the preset's), or `shaft line` (a stated speed the record's 1×
    /// line contradicts, replaced by it as `analyze` does: [`analysis::shaft_line::refine`]).
    pub rpm_source: String,
    /// Bearing: a model preset's name, a catalogue bearing's, or `custom` (a geometry from
    /// `--bearing-geometry` or the sidecar, or a wearsim sidecar's own model).
    pub bearing: String,
    /// The rig's nominal model the matched simulations start from ([`base_model`]).
    #[serde(skip)]
    pub base: ModelConfig,
    /// Defect (None: healthy).
    pub defect: Option<DefectSpec>,
    /// Where the defect came from: `argument` (`--defect`), `label` (a CWRU file name),
    /// `sidecar` (the model of a wearsim sidecar: the record is wearsim's own output) or
    /// `none` (nothing said; simulated healthy, with a warning).
    pub defect_source: &'static str,
    /// The defect exactly as a wearsim sidecar's model holds it (location with its angle,
    /// formulation, whole topography), when [`defect_source`](Self::defect_source) is
    /// `sidecar`: the matched simulations use it as it is, not the summary in `defect`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub defect_model: Option<DefectConfig>,
    /// Unit of the file and the factor to m/s².
    pub unit: String,
    /// Upper edge (Hz) of what the record holds when it ends well below fs/2 (an
    /// acquisition low-pass or a resampled record,
    /// [`analysis::content_band::content_edge`]): the cells compare the record and
    /// its simulations below it only. `None`: content up to near fs/2.
    pub content_hz: Option<f64>,
    /// Things the metadata and the content disagree on, in words.
    pub warnings: Vec<String>,
}

/// What the command line says about every record.
#[derive(Debug, Clone, Default)]
pub struct Overrides {
    /// `--bearing`.
    pub bearing: Option<String>,
    /// `--bearing-geometry`.
    pub geometry: Option<String>,
    /// `--rpm`.
    pub rpm: Option<f64>,
    /// `--trust-rpm`: never replace a stated speed by the record's 1× line.
    pub trust_rpm: bool,
    /// `--defect` (Some(None) = `none`).
    pub defect: Option<Option<DefectSpec>>,
    /// `--channel`.
    pub channel: Option<String>,
    /// `--fs`.
    pub fs: Option<f64>,
    /// `--units` (`g` or `m/s^2`).
    pub units: Option<String>,
}

/// The factor from a physical acceleration unit to m/s² (`g`: standard gravity), or
/// `None` for a unit the gap cannot compare with simulated m/s².
pub fn unit_scale(unit: &str) -> Option<f64> {
    match unit {
        "g" | "G" => Some(G),
        "m/s^2" | "m/s2" | "m/s²" | "m s^-2" => Some(1.0),
        _ => None,
    }
}

/// Standard deviations (m/s²) of the accelerations the gap compares with simulations:
/// from 1e-9 m/s² (0.1 µg, below the resolution of seismic accelerometers, ~1e-8 m/s²) to
/// 1e6 m/s² (about 100 000 g, the range of shock accelerometers). Outside it a record is
/// in another unit or gain than it states; its cells would compare levels of no bearing
/// (stop 68: noise of 1e-300 ended in a NaN sensor noise, 1e200 in gaps of -7000 dB).
pub const LEVEL_RANGE: (f64, f64) = (1e-9, 1e6);

/// Refuses a record (m/s²) that is constant, holds a sample beyond the analysable range,
/// or whose standard deviation is outside [`LEVEL_RANGE`]; the message names the level.
fn check_level(accel: &[f64]) -> Result<(), String> {
    analysis::error::check_magnitude(accel).map_err(|e| e.to_string())?;
    let st = analysis::stats(accel).map_err(|e| e.to_string())?;
    let (lo, hi) = LEVEL_RANGE;
    if !(lo..=hi).contains(&st.std) {
        return Err(format!(
            "the record's standard deviation is {:.3e} m/s^2, outside {lo:e} ..= {hi:e} m/s^2 (what accelerometers measure): is the unit or the gain right (--units, the file's unit)?",
            st.std
        ));
    }
    Ok(())
}

/// The error for a record whose samples are in no acceleration unit the gap can compare
/// with simulated m/s², saying how to give one.
fn no_acceleration_unit(rec: &Record) -> String {
    let p = rec.source.display();
    if rec.unit == "FS" {
        format!(
            "{p}: integer WAV samples in unit `FS` (full scale, channel `{}`) cannot be compared with simulated m/s²; allowed units g or m/s^2: give the file a JSON sidecar (`<file>.json`) with the physical value of full scale, `\"wav\": {{\"scale\": G_AT_FULL_SCALE, \"unit\": \"g\"}}`",
            rec.channel
        )
    } else {
        format!(
            "{p}: samples in unit `{}` (channel `{}`) cannot be compared with simulated m/s²; allowed units g or m/s^2: give --units g (or m/s^2) when the file states none, or the file a JSON sidecar (`<file>.json`) with `\"units\": {{\"{}\": \"g\"}}` or `\"units\": \"g\"`",
            rec.unit, rec.channel, rec.channel
        )
    }
}

/// Reads `path` and resolves its metadata; the error names the file and what is missing
/// or contradictory.
pub fn load(path: &Path, o: &Overrides) -> Result<RealRecord, String> {
    let rec: Record = io::read_any(
        path,
        &ReadOptions {
            channel: o.channel.clone(),
            fs: o.fs,
            rpm: None,
        },
    )
    .map_err(|e| e.to_string())?;
    let p = path.display();
    let mut warnings = vec![];
    let (bearing, base) = base_model(&rec, o, &mut warnings).map_err(|e| format!("{p}: {e}"))?;
    let scale = match (o.units.as_deref(), unit_scale(&rec.unit)) {
        (None, Some(s)) => s,
        (Some(u), Some(s)) if unit_scale(u) == Some(s) => s,
        // A file that states no unit takes the argument's; one that states another
        // (a velocity, volts, full scale) is not overridden.
        (Some(u), None) if rec.unit == "unknown" => {
            unit_scale(u).ok_or_else(|| format!("--units `{u}`: allowed g or m/s^2"))?
        }
        (Some(u), _) => {
            return Err(format!(
                "{p}: --units {u} contradicts the file's unit `{}` (channel `{}`); the gap compares accelerations in g or m/s^2",
                rec.unit, rec.channel
            ))
        }
        (None, None) => return Err(no_acceleration_unit(&rec)),
    };
    let accel: Vec<f64> = rec.samples.iter().map(|v| v * scale).collect();
    check_level(&accel).map_err(|e| format!("{p}: {e}"))?;
    let fs = rec.fs;
    let need = 2.0 * MIN_PART_S;
    // Counted in whole samples: at a rate that is no whole number of Hz (48 828.125) a
    // record of exactly 1 s holds the rounded number of samples, not one more.
    let need_samples = min_samples(need, fs);
    if accel.len() < need_samples {
        return Err(format!(
            "{p}: {} samples at {fs} Hz are {:.4} s; the gap needs at least {need} s ({need_samples} samples: a training and a held-out part of {MIN_PART_S} s) — is the sample rate right?",
            accel.len(),
            rec.duration_s()
        ));
    }
    // Speed: argument, file, or the spectrum.
    let nominal: f64 = base.speed.shaft_hz(0.0);
    let (rpm, rpm_source) = match (o.rpm, rec.rpm) {
        (Some(r), _) => (r, "argument"),
        (None, Some(r)) => (r, "file"),
        (None, None) => match analysis::shaft_line::find(&accel, fs, nominal) {
            Some(f) => (60.0 * f, "spectrum"),
            None => {
                return Err(format!(
                    "{p}: the shaft speed is not in the file and not estimable from the spectrum (no line within ±25 % of the preset's {:.0} rpm); give --rpm",
                    60.0 * nominal
                ))
            }
        },
    };
    // A stated speed the record contradicts by 1-5 % is replaced by its own 1× line, as
    // `analyze` replaces it (one definition, [`analysis::shaft_line::refine`]): simulated at
    // the stated speed, every fault line would sit where the record has none. Not for a
    // speed read from the spectrum already, nor for a record whose sidecar says the speed
    // varies (handled below).
    let varying = speed_range(&rec).is_some_and(|(lo, hi)| hi > lo * (1.0 + MAX_SPEED_SPREAD));
    let refined = if o.trust_rpm || rpm_source == "spectrum" || varying {
        None
    } else {
        analysis::shaft_line::refine(&accel, fs, rpm / 60.0)
    };
    let (rpm, rpm_source) = match refined {
        Some(r) => {
            warnings.push(format!(
                "speed refined: no shaft line at the stated {rpm:.0} rpm ({rpm_source}); the record's shaft (its 1x line {:.1} dB, the speed fitted to {} of its 1x-{}x lines) turns at {:.0} rpm ({:+.1} %), which the matched simulations use (--trust-rpm keeps the stated speed)",
                r.line_db,
                r.harmonics,
                analysis::shaft_line::SERIES_HARMONICS,
                r.rpm(),
                100.0 * r.offset
            ));
            (r.rpm(), analysis::shaft_line::REFINED_SOURCE)
        }
        None => (rpm, rpm_source),
    };
    // The record is simulated at this speed: the simulation's range, in rpm.
    let what = match rpm_source {
        "argument" => "--rpm".to_string(),
        src => format!("{p}: the shaft speed from the {src}"),
    };
    crate::config::check_sim_rpm(&what, rpm)?;
    if let Some((lo, hi)) = speed_range(&rec).filter(|_| varying) {
        let varies = format!(
            "the shaft speed varies over the record, {lo:.0}-{hi:.0} rpm (its sidecar), and the gap simulates one constant speed"
        );
        if rpm_source != "argument" {
            return Err(format!(
                "{p}: {varies}: give --rpm to choose it, or a part of the record at constant speed"
            ));
        }
        warnings.push(format!("{varies}: --rpm {rpm:.0} used"));
    }
    // A stated speed is checked as `analyze` checks it (one definition,
    // [`analysis::shaft_line::check`]): a 1x line within ±3 % of it and none at ½x. The
    // strongest line within ±25 % of the preset's nominal speed is no such check: at a
    // speed far from the nominal one it is whatever line falls there (at 300 rpm, twice
    // the BPFO of the 6205 at 35.9 Hz). A record too short to resolve 2.5 % of the shaft
    // frequency is not checked (`analyze`'s `speed_check: null`).
    // A speed the gap read from the spectrum itself must pass the check: the strongest
    // line near the nominal speed may be a bearing line (at 300 rpm on a 6205 preset, twice
    // the BPFO, whose fundamental then stands at ½x), and a whole attribution at a wrong
    // speed is worse than asking for it.
    let checked = analysis::shaft_line::check(&accel, fs, rpm / 60.0);
    if rpm_source == "spectrum" {
        if let Some(r) = checked.as_ref().and_then(|c| c.reason.as_ref()) {
            return Err(format!(
                "{p}: the shaft speed is not in the file, and the line the spectrum suggests ({rpm:.0} rpm, the strongest within ±25 % of the preset's {:.0} rpm) fails the shaft-line check: {r}; give --rpm",
                60.0 * nominal
            ));
        }
    }
    if let Some(r) = checked.and_then(|c| c.reason) {
        warnings.push(format!(
            "speed check: {r}; the matched simulations assume {rpm:.0} rpm at {fs} Hz"
        ));
    }
    // Defect: argument, else label, else a wearsim sidecar's own model; argument and label
    // different is a contradiction, argument and sidecar different a warning.
    let labelled = cwru_defect(path);
    let simulated = sidecar_model(&rec).map(|m| m.defect);
    let (defect, defect_model, defect_source) = match (o.defect, labelled) {
        (Some(a), Some(l)) if a.map(|d| d.location) != l.map(|d| d.location) => {
            return Err(format!(
                "{p}: --defect {} contradicts the file's label ({}); remove one",
                a.map_or("none", |d| d.location),
                l.map_or("none", |d| d.location)
            ))
        }
        (Some(a), _) => {
            if let Some(s) = simulated {
                let from_model = s.as_ref().map(defect_spec_of);
                if !same_defect(a, from_model) {
                    warnings.push(format!(
                        "--defect {} differs from the defect the file's sidecar model simulated ({}): the argument is used",
                        describe_defect(a),
                        describe_defect(from_model)
                    ));
                }
            }
            (a, None, "argument")
        }
        (None, Some(l)) => (l, None, "label"),
        (None, None) => match simulated {
            Some(s) => (s.as_ref().map(defect_spec_of), s, "sidecar"),
            None => {
                warnings.push(format!(
                    "no defect given and none in the file's label: simulated healthy{}",
                    detector_disagrees(&accel, fs, &base, rpm)
                ));
                (None, None, "none")
            }
        },
    };
    let content_hz = analysis::content_band::content_edge(&accel, fs);
    if let Some(e) = content_hz {
        warnings.push(format!(
            "the record holds no content above {e:.0} Hz (every 1/6-octave band above lies {:.0} dB or more under the octave below; fs/2 = {:.0} Hz): an acquisition low-pass or a resampled record. The record and its simulations are compared below {e:.0} Hz only",
            analysis::content_band::EMPTY_DB,
            fs / 2.0
        ));
    }
    Ok(RealRecord {
        file: path.to_path_buf(),
        content_hz,
        accel,
        fs,
        rpm,
        rpm_source: rpm_source.into(),
        bearing,
        base,
        defect,
        defect_source,
        defect_model,
        unit: rec.unit,
        warnings,
    })
}

/// What a healthy baseline misses when `analyze`'s detector calls a fault on the record
/// (samples `accel` at `fs` Hz, the bearing of `base` at `rpm`): a clause for the warning
/// that it is simulated healthy, empty when the detector calls none or cannot run. A
/// record without a label (a CWRU file under its number, another rig's snapshot late in
/// its life) would otherwise be matched by a healthy model, and the gap would attribute
/// the fault's own lines to the effects.
fn detector_disagrees(accel: &[f64], fs: f64, base: &ModelConfig, rpm: f64) -> String {
    let call = crate::kinematics::of_config(base, rpm)
        .ok()
        .and_then(|kin| {
            analysis::chain::analyze_signal(accel, fs, &kin, &analysis::chain::Method::default())
                .ok()
        });
    let Some(d) = call.map(|a| a.diagnosis) else {
        return String::new();
    };
    let flag = match d.family {
        FaultFamily::InnerRace => "inner",
        FaultFamily::OuterRace => "outer",
        FaultFamily::Ball => "ball",
        FaultFamily::None => return String::new(),
    };
    format!(
        "; `analyze`'s detector calls the record {} (confidence {:.2}): a healthy model leaves that fault's lines to the effects — give --defect {flag}:SIZE if the bearing has it",
        crate::analyze::family_name(d.family),
        d.confidence
    )
}

/// The rig's nominal model of record `rec` and the bearing's name, in this order of
/// precedence: `--bearing-geometry`; `--bearing` (a model preset, or a catalogue bearing);
/// the sidecar's `bearing_geometry`; the catalogue bearing the file or its layout names;
/// the faulty bearing a CWRU label names (whatever the channel); a model preset the file
/// names (this wins over a wearsim sidecar's model, so that a twin simulated away from a
/// preset is still matched to the preset's nominal description); a wearsim sidecar's own
/// structured model for a bearing it calls `custom` (its effects
/// removed: they are what the diagnosis looks for). A bearing that is no preset gets the
/// one rule for such bearings, [`crate::geometry::GeometrySpec::model`] (the nearest
/// preset's structure scaled by geometric similitude), and a warning that says so.
pub fn base_model(
    rec: &Record,
    o: &Overrides,
    warnings: &mut Vec<String>,
) -> Result<(String, ModelConfig), String> {
    if let (Some(b), Some(f)) = (&o.bearing, &rec.bearing) {
        if b != f {
            warnings.push(format!("--bearing {b} overrides the file's bearing {f}"));
        }
    }
    let preset = o.bearing.as_deref().and_then(presets::by_name);
    let custom = match preset {
        Some(_) if o.geometry.is_some() => {
            return Err("give either --bearing or --bearing-geometry, not both".into())
        }
        Some(_) => None,
        None => crate::geometry::choose(rec, o.bearing.as_deref(), o.geometry.as_deref())?,
    };
    let scaled = |name: String,
                  source: &str,
                  g: crate::geometry::GeometrySpec,
                  warnings: &mut Vec<String>| {
        // A geometry that is a preset's (as `GeometrySpec::same_as` compares: elements
        // equal, diameters within 0.1 %, angle within 0.1°) is that preset: the 6205's
        // geometry typed on the command line gets the 6205's model, not one scaled from it.
        let same = presets::NAMES
            .iter()
            .find(|n| crate::geometry::named_geometry(n).is_some_and(|p| p.same_as(&g)));
        if let Some(p) = same.and_then(|n| presets::by_name(n).map(|m| (n, m))) {
            warnings.push(format!(
                "the bearing ({name}, from the {source}) has model preset `{}`'s geometry (elements equal, diameters within 0.1 %, angle within 0.1 deg): the preset's model is used",
                p.0
            ));
            return Ok::<_, String>((p.0.to_string(), p.1));
        }
        let m = g.model()?;
        warnings.push(format!(
            "the bearing ({name}, from the {source}: {} elements of {:.3} mm on {:.3} mm, {:.1} deg) is no model preset: its model is `{}`'s with this geometry and the structure scaled by geometric similitude (s = {:.3}: mass x s^3, stiffness x s, damping x s^2); an assumption, so the zone levels and the rig's calibration start from it",
            g.elements, g.ball_mm, g.pitch_mm, g.angle_deg, m.base, m.scale
        ));
        Ok::<_, String>((name, m.model))
    };
    if let Some(p) = preset {
        return Ok((o.bearing.clone().unwrap_or_default(), p));
    }
    if let Some((name, source, g)) = custom {
        return scaled(name, source, g, warnings);
    }
    if let Some(b) = &o.bearing {
        return Err(crate::geometry::unknown_bearing(b));
    }
    // The defect sits in the bearing the file's label names (CWRU: the drive- or fan-end
    // bearing), whichever channel recorded it: a drive-end fault measured at the fan end or
    // on the base plate is the drive-end bearing seen through a longer path.
    if let Some(faulty) = io::mat::cwru_faulty_bearing(&rec.source) {
        if rec.bearing.as_deref() != Some(faulty) {
            warnings.push(format!(
                "the label puts the defect in the {faulty} bearing and the record is channel {} (whose bearing is {}): the matched simulation is of the faulty bearing, and the path from it to this sensor is left to the rig's calibration and the transfer-path effect",
                rec.channel,
                rec.bearing.as_deref().unwrap_or("none")
            ));
        }
        if let Some(p) = presets::by_name(faulty) {
            return Ok((faulty.to_string(), p));
        }
    }
    if let Some(named) = rec
        .bearing
        .as_deref()
        .and_then(|b| presets::by_name(b).map(|p| (b.to_string(), p)))
    {
        return Ok(named);
    }
    match (sidecar_model(rec), rec.bearing.as_deref()) {
        (Some(mut m), label) => {
            m.effects = wearsim_core::effects::Effects::NONE;
            Ok((label.unwrap_or("custom").to_string(), m))
        }
        (None, Some(b)) => Err(format!(
            "the file names the bearing `{b}`, which is no model preset and no catalogue bearing; {}",
            crate::geometry::bearing_choices()
        )),
        (None, None) => Err(format!(
            "the bearing is not known from the file; {}",
            crate::geometry::bearing_choices()
        )),
    }
}

/// The named outer-race defect positions and their angles in the model (rad): 3 o'clock at
/// 0, 6 o'clock (the load zone's centre) at π/2, 12 o'clock at −π/2. One table for reading a
/// name into an angle and an angle back into the nearest name.
const OUTER_POSITIONS: [(&str, f64); 3] = [
    ("outer@3", 0.0),
    ("outer@6", core::f64::consts::FRAC_PI_2),
    ("outer@12", -core::f64::consts::FRAC_PI_2),
];

/// The structured model of a wearsim sidecar next to `rec` (None: no sidecar, or not one of
/// wearsim's own with a `model`).
/// The largest relative spread of the shaft speed over a record (`max/min − 1`) that the
/// gap accepts as the one constant speed it simulates: 1 %, a fifth of the ±5 % that makes
/// a stated speed contradict the spectrum.
pub const MAX_SPEED_SPREAD: f64 = 0.01;

/// The lowest and highest shaft speed over the record (rpm) that its sidecar states
/// (`rpm_range`), or that a wearsim sidecar's model speed profile gives from its settle time
/// over the record's length (sidecars written before `rpm_range` was); `None` without either.
#[allow(clippy::unnecessary_cast)] // Real is f32 in `f32` builds
fn speed_range(rec: &Record) -> Option<(f64, f64)> {
    let side = rec.meta.get("sidecar")?;
    if let Ok(Some(r)) = crate::io::sidecar::rpm_range(side) {
        return Some(r);
    }
    let m = sidecar_model(rec)?;
    let t0 = side
        .get("settle_s")
        .and_then(serde_json::Value::as_f64)
        .filter(|t| t.is_finite() && *t >= 0.0)
        .unwrap_or(0.0);
    let s = m.speed.over(t0 as Real, (t0 + rec.duration_s()) as Real);
    Some((60.0 * s.min_hz as f64, 60.0 * s.max_hz as f64))
}

fn sidecar_model(rec: &Record) -> Option<ModelConfig> {
    rec.meta
        .get("sidecar")
        .and_then(|s| crate::io::sidecar::structured_model(s).ok().flatten())
}

/// The [`DefectSpec`] summary of a model's defect: its location by name (an outer-race
/// defect by the nearest of the 3, 6 and 12 o'clock positions the model's angle gives), its
/// size along the track and its depth.
#[allow(clippy::unnecessary_cast)] // Real is f32 in `f32` builds
pub fn defect_spec_of(d: &DefectConfig) -> DefectSpec {
    use core::f64::consts::PI;
    let location = match d.location {
        DefectLocation::InnerRace { .. } => "inner",
        DefectLocation::Ball { .. } => "ball",
        DefectLocation::OuterRace { angle } => {
            // Distance on the circle from the angle to each named position.
            let dist = |c: f64| {
                let r = (angle as f64 - c).rem_euclid(2.0 * PI);
                r.min(2.0 * PI - r)
            };
            OUTER_POSITIONS
                .into_iter()
                .min_by(|a, b| dist(a.1).total_cmp(&dist(b.1)))
                .map_or("outer@6", |(n, _)| n)
        }
    };
    DefectSpec {
        location,
        size: d.topography.length as f64,
        depth: d.topography.depth as f64,
    }
}

/// Whether two defects are the same to the gap: both healthy, or the same location with
/// size and depth within 1 %.
fn same_defect(a: Option<DefectSpec>, b: Option<DefectSpec>) -> bool {
    let close = |x: f64, y: f64| (x - y).abs() <= 0.01 * x.abs().max(y.abs());
    match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => {
            a.location == b.location && close(a.size, b.size) && close(a.depth, b.depth)
        }
        _ => false,
    }
}

/// A defect in words, for messages and the report: `outer@6 0.178 mm × 0.279 mm deep`, or
/// `none`.
pub fn describe_defect(d: Option<DefectSpec>) -> String {
    d.map_or("none".to_string(), |d| {
        format!(
            "{} {:.3} mm × {:.3} mm deep",
            d.location,
            1e3 * d.size,
            1e3 * d.depth
        )
    })
}

/// The matched baseline configuration of a record.
pub fn matched_config(r: &RealRecord) -> Result<ModelConfig, String> {
    let mut cfg = r.base.clone();
    cfg.speed = SpeedProfile::Constant((r.rpm / 60.0) as Real);
    cfg.output_rate = r.fs as Real;
    cfg.defect = match (r.defect_model, r.defect) {
        (Some(exact), _) => Some(exact),
        (None, None) => None,
        (None, Some(d)) => {
            let location = match d.location {
                "inner" => DefectLocation::InnerRace { angle: 0.0 },
                "ball" => DefectLocation::Ball {
                    element: 0,
                    phase: 0.0,
                },
                // outer@6 for an unnamed position, as `defect_spec_of` reads it back.
                outer => DefectLocation::OuterRace {
                    angle: OUTER_POSITIONS
                        .iter()
                        .find(|(n, _)| *n == outer)
                        .map_or(core::f64::consts::FRAC_PI_2, |(_, a)| *a)
                        as Real,
                },
            };
            let asperity = cfg.defect.map_or(5e-6, |d| d.topography.asperity_height);
            Some(DefectConfig {
                location,
                model: DefectModel::FiveStep,
                topography: Topography {
                    asperity_height: asperity,
                    length: d.size as Real,
                    width: d.size as Real,
                    depth: d.depth as Real,
                    count: 1,
                    debris: 0.0,
                },
                sassi_k_impact: 0.0,
            })
        }
    };
    // Validate now, so a record the model cannot take is named here.
    wearsim_core::Model::new_checked(cfg.clone()).map_err(|e| {
        // The matched simulations run at the record's own rate: one too low for the model's
        // stiffest mode is a property of the record, and resampling it is the remedy.
        let hint = match e {
            wearsim_core::ConfigError::StepTooLarge { .. } => format!(
                "; the gap simulates at the record's own rate ({} Hz): resample the record to at least that rate (band-limited; the gap then compares below the record's content edge, README \"Records of other rates, sensor positions and rigs\")",
                r.fs
            ),
            _ => String::new(),
        };
        format!("{}: the matched model is invalid: {e}{hint}", r.file.display())
    })?;
    Ok(cfg)
}

/// A matched part `[start, start + len)` of `r`.
pub fn part(
    r: &RealRecord,
    start: usize,
    len: usize,
    seed: u64,
    tag: &str,
) -> Result<Matched, String> {
    let cfg = matched_config(r)?;
    let spec = CellSpec {
        band_hz: r.content_hz,
        ..spec_of(&cfg)?
    };
    let x = r
        .accel
        .get(start..start + len)
        .ok_or_else(|| format!("{}: part out of range", r.file.display()))?;
    Ok(Matched {
        label: format!(
            "{} [{tag}: {:.2}–{:.2} s]",
            r.file
                .file_name()
                .map_or_else(String::new, |n| n.to_string_lossy().into_owned()),
            start as f64 / r.fs,
            (start + len) as f64 / r.fs
        ),
        base: cfg,
        reference: Reference::new(x, &spec).map_err(|e| format!("{}: {e}", r.file.display()))?,
        samples: len,
        seed,
        real: x.to_vec(),
        memo: Memo::new(MEMO),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::synth::{gaussian_noise, FaultSignal};

    /// Levels no accelerometer measures, constants and samples past the analysable range are
    /// refused with the level named; 1 m/s² and 1 g-scale noise pass.
    #[test]
    fn a_record_outside_what_accelerometers_measure_is_refused() {
        let noise = gaussian_noise(12_000, 1.0, 7);
        let scaled = |k: f64| noise.iter().map(|v| v * k).collect::<Vec<f64>>();
        assert!(check_level(&noise).is_ok());
        assert!(check_level(&scaled(G)).is_ok());
        let e = check_level(&scaled(1e200)).expect_err("1e200");
        assert!(e.contains("analysable range"), "{e}");
        let e = check_level(&scaled(1e-300)).expect_err("1e-300");
        assert!(
            e.contains("standard deviation") && e.contains("1e-9"),
            "{e}"
        );
        let e = check_level(&scaled(1e7)).expect_err("1e7");
        assert!(e.contains("standard deviation") && e.contains("1e6"), "{e}");
        let e = check_level(&[5.0; 100]).expect_err("constant");
        assert!(e.contains("constant (value 5)"), "{e}");
    }

    /// An unlabelled record whose envelope holds the 6205's BPFO comb (impulses ringing
    /// 3 kHz, 1 % slip; McFadden & Smith 1984) is named as outer race in the warning that
    /// it is simulated healthy, with the flag to give; white noise adds nothing.
    #[test]
    fn a_healthy_baseline_names_the_fault_the_detector_calls() {
        let base = presets::by_name("cwru-6205-de").expect("preset");
        let (fs, rpm) = (12_000.0, 1797.0);
        let kin = crate::kinematics::of_config(&base, rpm).expect("kinematics");
        let x = FaultSignal {
            fs,
            fault_hz: kin.bpfo,
            mod_hz: 0.0,
            mod_depth: 0.0,
            resonance_hz: 3000.0,
            damping: 0.05,
            impulse_amp: 1.0,
            noise_sigma: 0.3,
            seed: 7,
            jitter: 0.01,
        }
        .generate(4 * 12_000);
        let clause = detector_disagrees(&x, fs, &base, rpm);
        assert!(clause.contains("calls the record outer race"), "{clause}");
        assert!(clause.contains("--defect outer:SIZE"), "{clause}");
        let noise = gaussian_noise(4 * 12_000, 1.0, 3);
        assert_eq!(detector_disagrees(&noise, fs, &base, rpm), "");
    }
}
