//! Any bearing: `--bearing-geometry elements=N,ball=D,pitch=P,angle=DEG` (ball and pitch
//! diameters in **mm**, contact angle in **degrees**), the same in a sidecar
//! (`"bearing_geometry"`), and a small catalogue of the bearings of public data sets that are
//! not model presets. Defect frequencies come from the core's one kinematics
//! ([`wearsim_core::kinematics::FaultOrders`], thesis eq. 17–20).
//!
//! Catalogue entries (each number from the data set's own documentation; see
//! `docs/readers.md`): the CWRU and IMS bearings are model presets (`cwru-6205-de`,
//! `cwru-6203-fe`, `ims-za2115`, see `wearsim presets`); [`CATALOGUE`] adds the MFPT (NICE),
//! Paderborn (6203) and XJTU-SY (LDK UER204) bearings. The FEMTO/PRONOSTIA bearing is not
//! listed: its geometry is not given in the PRONOSTIA documentation, so pass it with
//! `--bearing-geometry`.

use wearsim_core::bearing::{BearingGeometry, ContactKind};
use wearsim_core::model::{ModelConfig, Structure};

/// A bearing's kinematic geometry in the units of the flag.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct GeometrySpec {
    /// Number of rolling elements per row (3..=[`MAX_SPEC_ELEMENTS`]).
    pub elements: u32,
    /// Rolling-element diameter, mm (0.1 ..= 500, the core's range).
    pub ball_mm: f64,
    /// Pitch diameter, mm (1 ..= 5 000, the core's range, and more than 1.5 × the ball).
    pub pitch_mm: f64,
    /// Contact angle, degrees, 0 to 45.8 (0.8 rad, the core's limit).
    pub angle_deg: f64,
}

/// Most rolling elements accepted in a `--bearing-geometry`: the core's capacity
/// ([`wearsim_core::bearing::MAX_ELEMENTS`]).
pub const MAX_SPEC_ELEMENTS: u32 = wearsim_core::bearing::MAX_ELEMENTS as u32;

/// One catalogue bearing: name, description, geometry and where the numbers come from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CatalogueEntry {
    /// Name used by `--bearing` and by the readers (`mfpt-nice`).
    pub name: &'static str,
    /// What it is.
    pub description: &'static str,
    /// Geometry.
    pub geometry: GeometrySpec,
    /// Source of the numbers.
    pub source: &'static str,
}

/// Bearings of public data sets that are not model presets.
pub const CATALOGUE: [CatalogueEntry; 3] = [
    CatalogueEntry {
        name: "mfpt-nice",
        description: "MFPT fault data sets test-rig bearing (NICE)",
        geometry: GeometrySpec {
            elements: 8,
            ball_mm: 0.235 * 25.4,
            pitch_mm: 1.245 * 25.4,
            angle_deg: 0.0,
        },
        source: "MFPT Condition Based Maintenance Fault Database readme (E. Bechhoefer): roller diameter 0.235 in, pitch diameter 1.245 in, 8 elements, contact angle 0",
    },
    CatalogueEntry {
        name: "paderborn-6203",
        description: "Paderborn University KAt data centre, ball bearing 6203",
        geometry: GeometrySpec {
            elements: 8,
            ball_mm: 6.75,
            pitch_mm: 28.55,
            angle_deg: 0.0,
        },
        source: "Lessmeier et al. (2016), KAt-DataCenter documentation, bearing 6203: 8 balls of 6.75 mm, pitch circle 28.55 mm, contact angle 0",
    },
    CatalogueEntry {
        name: "xjtu-ldk-uer204",
        description: "XJTU-SY run-to-failure data set, LDK UER204",
        geometry: GeometrySpec {
            elements: 8,
            ball_mm: 7.92,
            pitch_mm: 34.55,
            angle_deg: 0.0,
        },
        source: "Wang et al. (2020), IEEE Trans. Reliability 69(1), XJTU-SY bearing parameters: 8 balls of 7.92 mm, pitch diameter 34.55 mm, contact angle 0",
    },
];

/// The catalogue entry named `name`.
pub fn catalogue(name: &str) -> Option<&'static CatalogueEntry> {
    CATALOGUE.iter().find(|e| e.name == name)
}

/// The geometry a wearsim preset or a catalogue bearing `name` stands for (mm, degrees).
pub fn named_geometry(name: &str) -> Option<GeometrySpec> {
    if let Some(m) = wearsim_core::presets::by_name(name) {
        return Some(GeometrySpec::of(&m.bearing));
    }
    catalogue(name).map(|e| e.geometry)
}

impl GeometrySpec {
    /// The geometry of a model's bearing, in the flag's units (mm, degrees).
    pub fn of(g: &BearingGeometry) -> Self {
        GeometrySpec {
            elements: u32::from(g.elements),
            ball_mm: g.element_diameter * 1e3,
            pitch_mm: g.pitch_diameter * 1e3,
            angle_deg: g.contact_angle.to_degrees(),
        }
    }

    /// The geometry as `--bearing-geometry` takes it, to 4 decimals:
    /// `elements=16,ball=8.4074,pitch=71.501,angle=15.17`.
    pub fn describe(&self) -> String {
        let r = |x: f64| (x * 1e4).round() / 1e4;
        format!(
            "elements={},ball={},pitch={},angle={}",
            self.elements,
            r(self.ball_mm),
            r(self.pitch_mm),
            r(self.angle_deg)
        )
    }

    /// Whether `other` is the same bearing: equal element count, diameters within 0.1 %
    /// and contact angle within 0.1° (a geometry written in mm to a few digits).
    pub fn same_as(&self, other: &GeometrySpec) -> bool {
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-3 * a.abs().max(b.abs());
        self.elements == other.elements
            && close(self.ball_mm, other.ball_mm)
            && close(self.pitch_mm, other.pitch_mm)
            && (self.angle_deg - other.angle_deg).abs() <= 0.1
    }

    /// Check every field; the error names the field (`bearing-geometry.pitch`, ...) and its
    /// allowed range in the flag's units. The ranges are the core's
    /// ([`BearingGeometry::new_checked`], which every model of the bearing must pass),
    /// translated to millimetres and degrees.
    pub fn checked(self) -> Result<Self, String> {
        self.checked_syntax()?;
        let Err(e) = BearingGeometry::new_checked(self.bearing()?) else {
            return Ok(self);
        };
        use wearsim_core::error::ConfigError as C;
        let f = |name: &str, v: f64, range: String| {
            format!("bearing-geometry.{name} = {v} is impossible (allowed {range})")
        };
        Err(match e {
            C::OutOfRange { field, min, max, .. } => match field {
                "bearing.element_diameter" => {
                    f("ball", self.ball_mm, format!("{} ..= {} mm", min * 1e3, max * 1e3))
                }
                "bearing.pitch_diameter" => {
                    f("pitch", self.pitch_mm, format!("{} ..= {} mm", min * 1e3, max * 1e3))
                }
                "bearing.contact_angle" => f(
                    "angle",
                    self.angle_deg,
                    format!("0 ..= {:.1} degrees", max.to_degrees()),
                ),
                _ => format!("bearing-geometry: {e}"),
            },
            C::Inconsistent {
                field: "bearing.pitch_diameter",
                ..
            } => f(
                "pitch",
                self.pitch_mm,
                format!("more than 1.5 × ball = {} mm", 1.5 * self.ball_mm),
            ),
            C::Inconsistent {
                field: "bearing.elements",
                ..
            } => format!(
                "bearing-geometry.elements = {}: {} balls of {} mm do not fit on a pitch circle of {} mm (at most {} fit)",
                self.elements,
                self.elements,
                self.ball_mm,
                self.pitch_mm,
                ((std::f64::consts::PI * self.pitch_mm / self.ball_mm).ceil() as u32).saturating_sub(1)
            ),
            other => format!("bearing-geometry: {other}"),
        })
    }

    /// The checks that need no model: counts, finite values, pitch above ball.
    fn checked_syntax(self) -> Result<Self, String> {
        let f = |name: &str, v: f64, range: &str| {
            format!("bearing-geometry.{name} = {v} is impossible (allowed {range})")
        };
        if !(3..=MAX_SPEC_ELEMENTS).contains(&self.elements) {
            return Err(f(
                "elements",
                self.elements as f64,
                &format!("3..={MAX_SPEC_ELEMENTS}"),
            ));
        }
        if !(self.ball_mm.is_finite() && self.ball_mm > 0.0 && self.ball_mm <= 1000.0) {
            return Err(f(
                "ball",
                self.ball_mm,
                "a finite diameter in mm, 0.1 ..= 500",
            ));
        }
        // The core's rule (`BearingGeometry::new_checked`), stated here already because the
        // section diameters below are derived from pitch and ball.
        if !(self.pitch_mm.is_finite() && self.pitch_mm > 1.5 * self.ball_mm) {
            return Err(f(
                "pitch",
                self.pitch_mm,
                &format!("more than 1.5 × ball = {} mm", 1.5 * self.ball_mm),
            ));
        }
        // The ranges of pitch and contact angle are the core's, named in `checked`.
        Ok(self)
    }

    /// Parse `elements=N,ball=D,pitch=P[,angle=DEG]` (mm, degrees; angle defaults to 0).
    pub fn parse(s: &str) -> Result<Self, String> {
        let (mut n, mut b, mut p, mut a) = (None, None, None, 0.0);
        // Keys given so far (aliases as their canonical name): a repeat is refused, as
        // silently keeping the last of two values hides a typo.
        let mut seen: Vec<&str> = Vec::new();
        for part in s.split(',').map(str::trim).filter(|x| !x.is_empty()) {
            let (k, v) = part.split_once('=').ok_or_else(|| {
                format!("bearing-geometry: {part:?} is not KEY=VALUE (expected elements=N,ball=MM,pitch=MM,angle=DEG)")
            })?;
            let num: f64 = v
                .trim()
                .parse()
                .map_err(|_| format!("bearing-geometry.{}: {v:?} is not a number", k.trim()))?;
            let key = match k.trim() {
                "elements" | "n" => "elements",
                "ball" | "ball_mm" => "ball",
                "pitch" | "pitch_mm" => "pitch",
                "angle" | "angle_deg" => "angle",
                other => {
                    return Err(format!(
                        "bearing-geometry: unknown key {other:?} (allowed: elements, ball [mm], pitch [mm], angle [deg])"
                    ))
                }
            };
            if seen.contains(&key) {
                return Err(format!(
                    "bearing-geometry.{key} is given twice; give each of elements, ball, pitch, angle once"
                ));
            }
            seen.push(key);
            match key {
                "elements" => {
                    if !(0.0..=1e6).contains(&num) {
                        return Err(format!("bearing-geometry.elements = {num} is out of range: allowed 3..={MAX_SPEC_ELEMENTS} rolling elements"));
                    }
                    if num.fract() != 0.0 {
                        return Err(format!("bearing-geometry.elements = {num} is not a whole number of rolling elements (allowed 3..={MAX_SPEC_ELEMENTS})"));
                    }
                    n = Some(num as u32)
                }
                "ball" => b = Some(num),
                "pitch" => p = Some(num),
                _ => a = num,
            }
        }
        let missing = |k: &str| {
            format!(
                "bearing-geometry.{k} is missing (expected elements=N,ball=MM,pitch=MM,angle=DEG)"
            )
        };
        GeometrySpec {
            elements: n.ok_or_else(|| missing("elements"))?,
            ball_mm: b.ok_or_else(|| missing("ball"))?,
            pitch_mm: p.ok_or_else(|| missing("pitch"))?,
            angle_deg: a,
        }
        .checked()
    }

    /// Read the geometry from a sidecar value: a string in the flag's form, or an object with
    /// `elements`, `ball_mm`, `pitch_mm`, `angle_deg`.
    pub fn from_json(v: &serde_json::Value) -> Result<Self, String> {
        if let Some(s) = v.as_str() {
            return Self::parse(s);
        }
        let g = |k: &str| v.get(k).and_then(serde_json::Value::as_f64);
        let parts: Vec<String> = [
            ("elements", "elements"),
            ("ball", "ball_mm"),
            ("pitch", "pitch_mm"),
            ("angle", "angle_deg"),
        ]
        .iter()
        .filter_map(|(flag, key)| g(key).map(|x| format!("{flag}={x}")))
        .collect();
        Self::parse(&parts.join(","))
    }

    /// The core's geometry of this bearing: a deep-groove ball bearing (point contact,
    /// conformities and material of the reference bearing) whose bore and outside diameter
    /// are `pitch ∓ 1.7·ball` (a 6205's section is 1.70 balls, a 6203's 1.74; the core checks
    /// them, no force uses them).
    pub fn bearing(&self) -> Result<BearingGeometry, String> {
        let mm = 1e-3;
        let (bore, outside_diameter) = section_diameters(self.pitch_mm * mm, self.ball_mm * mm);
        Ok(BearingGeometry {
            elements: u8::try_from(self.elements).map_err(|_| {
                format!(
                    "bearing-geometry.elements = {} (allowed 3..={MAX_SPEC_ELEMENTS})",
                    self.elements
                )
            })?,
            element_diameter: self.ball_mm * mm,
            pitch_diameter: self.pitch_mm * mm,
            contact_angle: self.angle_deg.to_radians(),
            bore,
            outside_diameter,
            contact: ContactKind::Point,
            roller_length: 0.0,
            ..wearsim_core::presets::SKF_61810
        })
    }

    /// A model of this bearing (the one rule for a bearing that is no preset): the settings
    /// of the preset among [`STRUCTURE_PRESETS`] whose pitch diameter is closest on a log
    /// scale, with this geometry and that preset's structure scaled by geometric similitude,
    /// `s = pitch / pitch_preset`: mass × s³, stiffness × s, damping × s² (same damping
    /// ratio, resonance × 1/s; the scale-model law of an elastic structure, Harris &
    /// Piersol, *Harris' Shock and Vibration Handbook*, dimensional analysis). An
    /// assumption, not a measurement: reports say so.
    pub fn model(&self) -> Result<ScaledModel, String> {
        let preset = |n: &str| {
            wearsim_core::presets::by_name(n).ok_or_else(|| format!("preset {n} missing"))
        };
        let mut best = (STRUCTURE_PRESETS[0], f64::INFINITY);
        for n in STRUCTURE_PRESETS {
            let d = (self.pitch_mm / (preset(n)?.bearing.pitch_diameter * 1e3))
                .ln()
                .abs();
            if d < best.1 {
                best = (n, d);
            }
        }
        let mut model = preset(best.0)?;
        let scale = self.pitch_mm / (model.bearing.pitch_diameter * 1e3);
        let st = model.structure;
        let mass = st.mass * scale.powi(3);
        if mass < wearsim_core::model::MASS_RANGE.0 {
            // The core would name `structure.mass`, a field the user never gave.
            return Err(format!(
                "bearing-geometry: pitch {} mm, ball {} mm is too small for the structure model \
                 (scaled from {} by similitude its structure would weigh {mass:.2e} kg, below \
                 {:e} kg; the smallest pitch accepted is about {:.1} mm); diameters are in \
                 millimetres — if these are inches, multiply by 25.4",
                self.pitch_mm,
                self.ball_mm,
                best.0,
                wearsim_core::model::MASS_RANGE.0,
                self.pitch_mm * (wearsim_core::model::MASS_RANGE.0 / mass).cbrt()
            ));
        }
        model.bearing = self.bearing()?;
        model.structure = Structure {
            mass,
            stiffness: st.stiffness * scale,
            damping: st.damping * scale * scale,
        };
        Ok(ScaledModel {
            model,
            base: best.0,
            scale,
        })
    }
}

/// Presets a bearing that is no preset may take its structure from ([`GeometrySpec::model`];
/// `thesis-as-printed` is left out: its damping is the thesis's misprint).
pub const STRUCTURE_PRESETS: [&str; 4] =
    ["thesis-61810", "cwru-6203-fe", "cwru-6205-de", "ims-za2115"];

/// Half the radial section of a bearing that is no preset, in ball diameters.
const SECTION_BALLS: f64 = 1.7;

/// Bore and outside diameter (m) of a bearing whose section is not given, from its pitch
/// diameter and ball diameter (m): `pitch ∓ 1.7·ball` (a 6205's section is 1.70 balls, a
/// 6203's 1.74), the bore at least 0.
pub fn section_diameters(pitch: f64, ball: f64) -> (f64, f64) {
    (
        (pitch - SECTION_BALLS * ball).max(0.0),
        pitch + SECTION_BALLS * ball,
    )
}

/// A model of a bearing that is no preset ([`GeometrySpec::model`]).
#[derive(Debug, Clone, PartialEq)]
pub struct ScaledModel {
    /// The model: the base preset's settings with the geometry and the scaled structure.
    pub model: ModelConfig,
    /// The preset the structure and the other settings come from.
    pub base: &'static str,
    /// Similitude factor `s` = pitch / the base preset's pitch.
    pub scale: f64,
}

/// What a bearing may be given as: the model presets, the catalogue bearings and
/// `--bearing-geometry` (for messages).
pub(crate) fn bearing_choices() -> String {
    format!(
        "give --bearing NAME (a model preset: {}; or a catalogue bearing: {}) or --bearing-geometry elements=N,ball=MM,pitch=MM,angle=DEG",
        wearsim_core::presets::NAMES.join(", "),
        CATALOGUE.map(|e| e.name).join(", ")
    )
}

/// The error for a `--bearing` that is neither a model preset nor a catalogue bearing
/// (`analyze` and `gap` alike).
pub(crate) fn unknown_bearing(b: &str) -> String {
    format!("--bearing: unknown bearing `{b}`; {}", bearing_choices())
}

/// The bearing `analyze` uses when it is not a model preset: from `--bearing-geometry`
/// (`geometry`), a catalogue name given with `--bearing` (`preset`), a sidecar's
/// `"bearing_geometry"`, or a catalogue name a reader set from the file's layout. Returns
/// `(name, source, geometry)`, or `None` when the bearing is a model preset (or unknown, when
/// not given with `--bearing`). A `--bearing` that is neither a preset nor a catalogue
/// bearing is an error listing both.
pub fn choose(
    rec: &crate::io::Record,
    preset: Option<&str>,
    geometry: Option<&str>,
) -> Result<Option<(String, &'static str, GeometrySpec)>, String> {
    if let Some(g) = geometry {
        if preset.is_some() {
            return Err("give either --bearing or --bearing-geometry, not both".into());
        }
        return Ok(Some(("custom".into(), "argument", GeometrySpec::parse(g)?)));
    }
    if let Some(b) = preset {
        if wearsim_core::presets::by_name(b).is_none() && catalogue(b).is_none() {
            return Err(unknown_bearing(b));
        }
        return Ok(catalogue(b).map(|e| (b.to_string(), "argument", e.geometry)));
    }
    let sidecar = rec.meta.get("sidecar");
    if let Some(v) = sidecar.and_then(|s| s.get("bearing_geometry")) {
        let g = GeometrySpec::from_json(v)?;
        // A sidecar naming a bearing too must name the same one: which of two was meant
        // cannot be guessed (the geometry was taken, silently).
        if let Some(name) = sidecar
            .and_then(|s| s.get("bearing"))
            .and_then(serde_json::Value::as_str)
        {
            let named = match (catalogue(name), wearsim_core::presets::by_name(name)) {
                (Some(e), _) => Some(e.geometry),
                (None, Some(p)) => Some(GeometrySpec::of(&p.bearing)),
                (None, None) => None,
            };
            if let Some(n) = named.filter(|n| !n.same_as(&g)) {
                return Err(format!(
                    "sidecar: `bearing` = \"{name}\" ({} elements, ball {} mm, pitch {} mm, angle {}°) and `bearing_geometry` ({} elements, ball {} mm, pitch {} mm, angle {}°) are different bearings; give one of them",
                    n.elements, n.ball_mm, n.pitch_mm, n.angle_deg, g.elements, g.ball_mm, g.pitch_mm, g.angle_deg
                ));
            }
        }
        return Ok(Some(("custom".into(), "sidecar", g)));
    }
    Ok(rec
        .bearing
        .as_deref()
        .and_then(catalogue)
        .map(|e| (e.name.to_string(), "file", e.geometry)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 6205 typed in inches (ball 0.3126 in, pitch 1.537 in) is refused naming the
    /// geometry and the unit, not `structure.mass`, a field the user never gave (probe F).
    #[test]
    fn a_bearing_given_in_inches_is_refused_saying_so() {
        let g = GeometrySpec::parse("elements=9,ball=0.3126,pitch=1.537,angle=0").expect("parses");
        let e = g.model().expect_err("too small for the structure model");
        assert!(
            e.starts_with("bearing-geometry:") && e.contains("inches"),
            "{e}"
        );
        assert!(!e.contains("structure.mass"), "{e}");
        // The pitch the message gives as the smallest accepted is accepted.
        let mm = g.pitch_mm * 6.0;
        let ok = GeometrySpec::parse(&format!("elements=9,ball=0.3126,pitch={mm},angle=0"))
            .expect("parses");
        assert!(ok.model().is_ok());
    }
    use wearsim_core::kinematics::FaultOrders;

    #[test]
    fn parse_check_and_match_the_preset() {
        // The CWRU drive-end bearing by its numbers (CWRU bearing page: 9 balls of 0.3126 in,
        // pitch 1.537 in) gives the preset's frequencies.
        let s = GeometrySpec::parse("elements=9,ball=7.94004,pitch=39.0398,angle=0").unwrap();
        let k = FaultOrders::of(&s.bearing().unwrap()).at(1797.0 / 60.0, 3000.0);
        let b = wearsim_core::presets::by_name("cwru-6205-de")
            .unwrap()
            .bearing;
        let p = FaultOrders::of(&b).at(1797.0 / 60.0, 3000.0);
        assert!(
            (k.bpfi - p.bpfi).abs() < 1e-3 * p.bpfi,
            "{} vs {}",
            k.bpfi,
            p.bpfi
        );
        assert!((k.bpfo - p.bpfo).abs() < 1e-3 * p.bpfo);
        assert!((k.bsf - p.bsf).abs() < 1e-3 * p.bsf);
        // BPFO + BPFI = N x shaft, whatever the geometry.
        let s = GeometrySpec::parse("elements=16, ball=8.4, pitch=71.5, angle=15.17").unwrap();
        let k = FaultOrders::of(&s.bearing().unwrap()).at(2000.0 / 60.0, 3000.0);
        assert!((k.bpfo + k.bpfi - 16.0 * 2000.0 / 60.0).abs() < 1e-9);
        for (bad, field) in [
            ("elements=9,ball=8,pitch=7.9", "pitch"),
            ("elements=9,ball=8,pitch=8", "pitch"),
            ("elements=9,ball=8,pitch=30,angle=90", "angle"),
            ("elements=9,ball=8,pitch=30,angle=-1", "angle"),
            ("elements=2,ball=8,pitch=30", "elements"),
            ("elements=9.5,ball=8,pitch=30", "elements"),
            ("elements=9,ball=0,pitch=30", "ball"),
            ("elements=9,ball=nan,pitch=30", "ball"),
            ("elements=9,pitch=30", "ball"),
            ("elements=9,ball=8,pitch=30,size=3", "size"),
            // The core's limits, in the flag's field names and units.
            (
                "elements=9,ball=600,pitch=2000",
                "bearing-geometry.ball = 600 is impossible (allowed 0.1 ..= 500 mm)",
            ),
            (
                "elements=9,ball=8,pitch=39,angle=60",
                "bearing-geometry.angle = 60 is impossible (allowed 0 ..= 45.8 degrees)",
            ),
            (
                "elements=40,ball=2,pitch=100",
                "bearing-geometry.elements = 40 is impossible (allowed 3..=32)",
            ),
            (
                "elements=30,ball=8,pitch=39",
                "30 balls of 8 mm do not fit on a pitch circle of 39 mm (at most 15 fit)",
            ),
            ("elements=9,ball=8,pitch=11", "more than 1.5 × ball = 12 mm"),
            // Every refusal states the range that is applied (stop 68: angle 95 was told
            // "0 <= angle < 90" and angle 60 then refused; pitch 5 with ball 10 was told
            // "ball < pitch <= 10000 mm").
            (
                "elements=9,ball=7.94,pitch=39.04,angle=95",
                "bearing-geometry.angle = 95 is impossible (allowed 0 ..= 45.8 degrees)",
            ),
            (
                "elements=9,ball=10,pitch=5,angle=0",
                "bearing-geometry.pitch = 5 is impossible (allowed more than 1.5 × ball = 15 mm)",
            ),
            (
                "elements=9,ball=8,pitch=6000",
                "bearing-geometry.pitch = 6000 is impossible (allowed 1 ..= 5000 mm)",
            ),
            // A repeat (also through an alias) is named, not the last value kept.
            (
                "elements=9,ball=7.94,pitch=39,ball_mm=8",
                "bearing-geometry.ball is given twice",
            ),
            (
                "elements=1e20,ball=7.94,pitch=39",
                "bearing-geometry.elements = 100000000000000000000 is out of range: allowed 3..=32",
            ),
        ] {
            let e = GeometrySpec::parse(bad).unwrap_err();
            assert!(e.contains(field), "{bad}: {e}");
            assert!(e.starts_with("bearing-geometry"), "{bad}: {e}");
        }
        let j = serde_json::json!({"elements": 8, "ball_mm": 7.92, "pitch_mm": 34.55});
        assert_eq!(GeometrySpec::from_json(&j).unwrap(), CATALOGUE[2].geometry);
        for e in CATALOGUE {
            assert_eq!(e.geometry.checked(), Ok(e.geometry), "{}", e.name);
        }
    }
}
