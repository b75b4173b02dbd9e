//! The sidecar of a feature table (`docs/feature-tables.md`, "`NAME.json`"): reading it,
//! refusing unknown keys at every level ([`SIDECAR_KEYS`]) and values of the wrong JSON
//! type naming their dotted key, and the range checks of every field (`check_sidecar`).
//! Split from [`super::feature_table`], which re-exports [`read_sidecar`].

use std::path::Path;

use super::feature_format::{
    sidecar_err, FeatureSidecar, FeatureTableError, FAILURE_MODES, FORMAT, FORMAT_VERSION, UNITS,
};
/// The keys of each object of a sidecar: the top level (`""`), `bearing` and
/// `bearing.geometry`. Any other key, at any level, is refused naming its dotted path
/// (`unknown_key`): a misspelt optional key (`presett`, `geomtry`) would otherwise be
/// silently absent.
pub const SIDECAR_KEYS: [(&str, &[&str]); 3] = [
    (
        "",
        &[
            "format",
            "format_version",
            "source",
            "bearing",
            "channel",
            "unit",
            "rpm",
            "radial_load_n",
            "sample_rate_hz",
            "snapshot_samples",
            "snapshot_interval_s",
            "failure_mode",
            "n_snapshots",
            "notes",
        ],
    ),
    ("bearing", &["preset", "geometry", "id"]),
    (
        "bearing.geometry",
        &["elements", "ball_mm", "pitch_mm", "angle_deg"],
    ),
];

/// The first key of sidecar `v` that is not one of its object's [`SIDECAR_KEYS`], as
/// (dotted path, message naming the object's allowed keys).
fn unknown_key(v: &serde_json::Value) -> Option<(String, String)> {
    SIDECAR_KEYS.iter().find_map(|(at, allowed)| {
        let obj = if at.is_empty() {
            v.as_object()
        } else {
            at.split('.')
                .try_fold(v, |x, k| x.get(k))
                .and_then(|x| x.as_object())
        }?;
        let key = obj.keys().find(|k| !allowed.contains(&k.as_str()))?;
        let path = if at.is_empty() {
            key.clone()
        } else {
            format!("{at}.{key}")
        };
        let within = if at.is_empty() {
            "the sidecar".to_string()
        } else {
            format!("`{at}`")
        };
        Some((
            path,
            format!(
                "unknown key `{key}` in {within}; allowed keys: {}",
                allowed.join(", ")
            ),
        ))
    })
}

/// Reads and checks a sidecar on its own (ranges of every field; unknown keys at any
/// level refused, [`SIDECAR_KEYS`]).
pub fn read_sidecar(path: &Path) -> Result<FeatureSidecar, FeatureTableError> {
    let v = super::sidecar::read_json(path)?;
    if v["format"] != FORMAT {
        return Err(sidecar_err(
            path,
            "format",
            format!("{} is not \"{FORMAT}\"", v["format"]),
        ));
    }
    if let Some((field, detail)) = unknown_key(&v) {
        return Err(sidecar_err(path, &field, detail));
    }
    let s: FeatureSidecar = serde_json::from_value(v.clone()).map_err(|e| {
        let msg = e.to_string();
        let field = mistyped_field(&v)
            .or_else(|| msg.split('`').nth(1).map(dotted_key))
            .unwrap_or_else(|| "(the sidecar)".into());
        sidecar_err(path, &field, msg)
    })?;
    check_sidecar(path, &s)?;
    Ok(s)
}

/// A key serde names without its place (a missing `id` of `bearing`), dotted as the
/// documentation names it: the keys of `bearing` and of its `geometry` are no top-level keys.
fn dotted_key(key: &str) -> String {
    match key {
        "preset" | "geometry" | "id" => format!("bearing.{key}"),
        "elements" | "ball_mm" | "pitch_mm" | "angle_deg" => format!("bearing.geometry.{key}"),
        _ => key.to_string(),
    }
}

/// The first sidecar key (dotted for `bearing.*`) whose value has the wrong JSON type:
/// serde's message for a wrong type names the type, not the key.
fn mistyped_field(v: &serde_json::Value) -> Option<String> {
    use serde_json::Value;
    let num = |x: &Value| x.is_number();
    let int = |x: &Value| x.is_u64();
    let string = |x: &Value| x.is_string();
    type Check = fn(&Value) -> bool;
    let top: [(&str, Check); 14] = [
        ("format", string),
        ("format_version", int),
        ("source", string),
        ("bearing", Value::is_object),
        ("channel", string),
        ("unit", string),
        ("rpm", num),
        ("radial_load_n", num),
        ("sample_rate_hz", num),
        ("snapshot_samples", int),
        ("snapshot_interval_s", num),
        ("failure_mode", string),
        ("n_snapshots", int),
        ("notes", Value::is_array),
    ];
    let bearing: [(&str, Check); 3] = [
        ("bearing.preset", string),
        ("bearing.geometry", Value::is_object),
        ("bearing.id", string),
    ];
    let geometry: [(&str, Check); 4] = [
        ("bearing.geometry.elements", int),
        ("bearing.geometry.ball_mm", num),
        ("bearing.geometry.pitch_mm", num),
        ("bearing.geometry.angle_deg", num),
    ];
    let get = |key: &str| {
        key.split('.')
            .try_fold(v, |x, k| x.get(k))
            .filter(|x| !x.is_null())
    };
    top.iter()
        .chain(&bearing)
        .chain(&geometry)
        .find(|(k, ok)| get(k).is_some_and(|x| !ok(x)))
        .map(|(k, _)| (*k).to_string())
}

pub(crate) fn check_sidecar(path: &Path, s: &FeatureSidecar) -> Result<(), FeatureTableError> {
    if s.format_version != FORMAT_VERSION {
        return Err(sidecar_err(
            path,
            "format_version",
            format!("{} (this reader knows {FORMAT_VERSION})", s.format_version),
        ));
    }
    let pos = |field: &str, v: f64, lo: f64, hi: f64| {
        if v.is_finite() && v > lo && v <= hi {
            Ok(())
        } else {
            Err(sidecar_err(
                path,
                field,
                format!("{v} is outside ({lo}, {hi}]"),
            ))
        }
    };
    pos("rpm", s.rpm, 0.0, 1e6)?;
    pos("sample_rate_hz", s.sample_rate_hz, 0.0, super::MAX_FS)?;
    pos("snapshot_interval_s", s.snapshot_interval_s, 0.0, 1e9)?;
    if !(s.radial_load_n.is_finite() && (0.0..=1e8).contains(&s.radial_load_n)) {
        return Err(sidecar_err(
            path,
            "radial_load_n",
            format!("{} is outside [0, 1e8] N", s.radial_load_n),
        ));
    }
    if s.snapshot_samples < 2 {
        return Err(sidecar_err(
            path,
            "snapshot_samples",
            format!("{} (at least 2)", s.snapshot_samples),
        ));
    }
    let length = s.snapshot_samples as f64 / s.sample_rate_hz;
    if length > s.snapshot_interval_s * (1.0 + 1e-9) {
        return Err(sidecar_err(
            path,
            "snapshot_interval_s",
            format!(
                "{} s is shorter than one snapshot (snapshot_samples / sample_rate_hz = {length} s)",
                s.snapshot_interval_s
            ),
        ));
    }
    if !FAILURE_MODES.contains(&s.failure_mode.as_str()) {
        return Err(sidecar_err(
            path,
            "failure_mode",
            format!(
                "{:?} is not one of {}",
                s.failure_mode,
                FAILURE_MODES.join(", ")
            ),
        ));
    }
    if !UNITS.contains(&s.unit.as_str()) {
        return Err(sidecar_err(
            path,
            "unit",
            format!("{:?} is not one of {}", s.unit, UNITS.join(", ")),
        ));
    }
    if s.bearing.id.trim().is_empty() {
        // The life's label in every report (`MeasuredLife::label`): a blank one names nothing.
        return Err(sidecar_err(
            path,
            "bearing.id",
            "empty (free text naming the bearing, e.g. \"test 2 bearing 1\")",
        ));
    }
    if s.bearing.preset.is_none() && s.bearing.geometry.is_none() {
        return Err(sidecar_err(
            path,
            "bearing",
            "give `preset` (a wearsim preset) or `geometry` (elements, ball_mm, pitch_mm, angle_deg)",
        ));
    }
    if let Some(p) = &s.bearing.preset {
        if wearsim_core::presets::by_name(p).is_none() && crate::geometry::catalogue(p).is_none() {
            return Err(sidecar_err(
                path,
                "bearing.preset",
                format!(
                    "unknown preset {p:?} (a wearsim preset, see `wearsim presets`, or a catalogue bearing: {})",
                    crate::geometry::CATALOGUE.map(|e| e.name).join(", ")
                ),
            ));
        }
    }
    if let Some(g) = &s.bearing.geometry {
        // The limits of `--bearing-geometry` (the core's, in mm and degrees).
        let spec = crate::geometry::GeometrySpec {
            elements: g.elements,
            ball_mm: g.ball_mm,
            pitch_mm: g.pitch_mm,
            angle_deg: g.angle_deg,
        };
        if let Err(m) = spec.checked() {
            return Err(sidecar_err(path, "bearing.geometry", m));
        }
        // A preset is a geometry too: both given must be one bearing.
        let named = s
            .bearing
            .preset
            .as_deref()
            .and_then(|p| crate::geometry::named_geometry(p).map(|n| (p, n)));
        if let Some((p, n)) = named {
            let stated = crate::geometry::GeometrySpec {
                elements: g.elements,
                ball_mm: g.ball_mm,
                pitch_mm: g.pitch_mm,
                angle_deg: g.angle_deg,
            };
            if !n.same_as(&stated) {
                return Err(sidecar_err(
                    path,
                    "bearing.geometry",
                    format!(
                        "{} (mm, degrees) contradicts `bearing.preset` {p}, which is {}; give the preset or the geometry of this bearing, not both",
                        stated.describe(),
                        n.describe()
                    ),
                ));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    /// A sidecar every check accepts (the worked example of `docs/feature-tables.md`).
    fn good() -> serde_json::Value {
        json!({
            "format": FORMAT, "format_version": 1, "source": "test",
            "bearing": {
                "geometry": { "elements": 13, "ball_mm": 3.5, "pitch_mm": 25.6, "angle_deg": 0.0 },
                "id": "b1"
            },
            "channel": "horiz", "unit": "g", "rpm": 1800.0, "radial_load_n": 4000.0,
            "sample_rate_hz": 25600.0, "snapshot_samples": 2560,
            "snapshot_interval_s": 3600.0, "failure_mode": "outer-race"
        })
    }

    /// Writes `v` as a sidecar in a fresh folder and reads it back.
    fn read(name: &str, v: &serde_json::Value) -> Result<FeatureSidecar, FeatureTableError> {
        let dir =
            std::env::temp_dir().join(format!("wearsim-sidecar-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("t.json");
        std::fs::write(&p, serde_json::to_vec(v).unwrap()).unwrap();
        let r = read_sidecar(&p);
        let _ = std::fs::remove_dir_all(&dir);
        r
    }

    fn refused_field(name: &str, v: &serde_json::Value) -> (String, String) {
        match read(name, v) {
            Err(FeatureTableError::Sidecar { field, detail, .. }) => (field, detail),
            other => panic!("{name}: expected a sidecar error, got {other:?}"),
        }
    }

    #[test]
    fn the_good_sidecar_is_read() {
        assert!(read("good", &good()).is_ok());
    }

    /// Probe defect: misspelt keys inside `bearing` and `bearing.geometry` were ignored
    /// (exit 0). Each is refused naming its dotted path and the object's allowed keys.
    #[test]
    fn unknown_keys_inside_bearing_and_its_geometry_are_refused_by_path() {
        let mut v = good();
        v["bearing"]["geomtry"] = v["bearing"]["geometry"].clone();
        let (f, d) = refused_field("geomtry", &v);
        assert_eq!(f, "bearing.geomtry");
        assert!(d.contains("allowed keys: preset, geometry, id"), "{d}");

        let mut v = good();
        v["bearing"]["presett"] = json!("cwru-6205-de");
        assert_eq!(refused_field("presett", &v).0, "bearing.presett");

        let mut v = good();
        v["bearing"]["geometry"]["contact_angle_deg"] = json!(15);
        let (f, d) = refused_field("angle", &v);
        assert_eq!(f, "bearing.geometry.contact_angle_deg");
        assert!(
            d.contains("allowed keys: elements, ball_mm, pitch_mm, angle_deg"),
            "{d}"
        );

        let mut v = good();
        v["sample_rate"] = json!(25600.0);
        let (f, d) = refused_field("top", &v);
        assert_eq!(f, "sample_rate");
        assert!(d.contains("in the sidecar; allowed keys: format,"), "{d}");
    }

    /// Probe find (stop 68): a blank `bearing.id` was read, and every report then labelled
    /// the life by nothing.
    #[test]
    fn a_blank_bearing_id_is_refused() {
        for id in ["", "  \t"] {
            let mut v = good();
            v["bearing"]["id"] = json!(id);
            let (f, d) = refused_field("blank-id", &v);
            assert_eq!(f, "bearing.id");
            assert!(d.starts_with("empty"), "{d}");
        }
    }

    /// Every key the serde structs know is in [`SIDECAR_KEYS`] and no other: a key added to
    /// a struct but not to the list would be refused as unknown.
    #[test]
    fn the_key_lists_are_those_of_the_structs() {
        let s: FeatureSidecar = serde_json::from_value(good()).unwrap();
        let mut full = serde_json::to_value(&s).unwrap();
        full["n_snapshots"] = json!(10);
        full["notes"] = json!(["n"]);
        full["bearing"]["preset"] = json!("cwru-6205-de");
        for (at, allowed) in SIDECAR_KEYS {
            let obj = if at.is_empty() {
                &full
            } else {
                at.split('.').try_fold(&full, |x, k| x.get(k)).unwrap()
            };
            let mut keys: Vec<&str> = obj
                .as_object()
                .unwrap()
                .keys()
                .map(|k| k.as_str())
                .collect();
            let mut want = allowed.to_vec();
            keys.sort_unstable();
            want.sort_unstable();
            assert_eq!(keys, want, "keys of `{at}`");
        }
    }
}
