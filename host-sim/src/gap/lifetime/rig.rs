//! The simulated bearing of a lifetime diagnosis, built from what the measured life says
//! about it: a wearsim preset when one is named (a preset is a filled-in description), or
//! else a feature-table sidecar's geometry, speed, load, sample rate and snapshot length
//! with a structure scaled from the closest preset. Both go through one builder,
//! [`RigDescription::model`], so the preset case gives the preset's model exactly.
//!
//! **Structure of a bearing that is no preset** (an assumption, reported as such; the one
//! rule, [`crate::geometry::GeometrySpec::model`], which `analyze` uses too): the
//! vibrating structure (mass, stiffness, damping, hence its resonance) is that of the
//! preset whose pitch diameter is closest on a log scale, scaled
//! by geometric similitude with `s = pitch / pitch_preset` (same material and shape:
//! mass ∝ s³, stiffness ∝ s, damping at the preset's damping ratio ∝ s², so the
//! resonance ∝ 1/s; the scale-model law of an elastic structure, e.g. Harris & Piersol,
//! *Harris' Shock and Vibration Handbook*, dimensional analysis). Everything else the
//! model needs that a sidecar does not give (clearance, imbalance, waviness, roughness,
//! slip, integrator, conformities) is that preset's too; a sidecar bearing has point
//! contact (a ball bearing) and its bore/outside diameter are `pitch ∓ 1.7·ball` (a deep
//! groove bearing's section; checked by the core, used by no force). The diagnosis may
//! name this structure as part of the gap: it is not measured.

use crate::geometry::{catalogue, GeometrySpec};
use crate::io::feature_table::{sidecar_path, FeatureSidecar};
use serde::Serialize;
use std::path::Path;
use wearsim_core::bearing::BearingGeometry;
use wearsim_core::kinematics::FaultFrequencies;
use wearsim_core::model::{ModelConfig, Structure};
use wearsim_core::speed::SpeedProfile;

/// Window length of a preset's simulated life: the IMS snapshot's 20 480 samples (crest
/// factor and kurtosis depend on the length).
pub const PRESET_WINDOW_SAMPLES: usize = 20_480;

/// Relative tolerance of a table's `rpm` against its preset's shaft speed.
pub const RPM_TOL: f64 = 0.01;

/// Everything the simulated life of a measured bearing is built from.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RigDescription {
    /// Where the description comes from: `preset ims-za2115`, `sidecar geometry`,
    /// `catalogue bearing xjtu-ldk-uer204 (sidecar bearing.preset)`.
    pub origin: String,
    /// The preset whose other settings the model keeps (the named one, or the one the
    /// structure is scaled from).
    pub base: String,
    /// Rolling elements (per row).
    pub elements: u32,
    /// Rolling-element diameter, mm.
    pub ball_mm: f64,
    /// Pitch diameter, mm.
    pub pitch_mm: f64,
    /// Contact angle, degrees.
    pub angle_deg: f64,
    /// Shaft speed, Hz.
    pub shaft_hz: f64,
    /// Radial load on the simulated row, N.
    pub radial_load_n: f64,
    /// Sample rate of the simulated windows, Hz.
    pub sample_rate_hz: f64,
    /// Samples of a simulated window (the measured snapshot's length).
    pub window_samples: usize,
    /// Vibrating mass, kg.
    pub mass_kg: f64,
    /// Structural stiffness, N/m.
    pub stiffness_n_per_m: f64,
    /// Viscous damping, N·s/m.
    pub damping_n_s_per_m: f64,
    /// How the structure was obtained (the preset's own, or the scaling rule and factor).
    pub structure_origin: String,
    /// Assumptions the diagnosis may name as part of the gap (empty for a preset).
    pub assumptions: Vec<String>,
    #[serde(skip)]
    geometry: BearingGeometry,
}

fn preset(name: &str) -> Result<ModelConfig, String> {
    wearsim_core::presets::by_name(name).ok_or_else(|| format!("preset {name} missing"))
}

impl RigDescription {
    /// The description preset `name` fills in, simulated in windows of
    /// [`PRESET_WINDOW_SAMPLES`].
    pub fn preset(name: &str) -> Result<Self, String> {
        let m = preset(name)?;
        let g = m.bearing;
        Ok(RigDescription {
            origin: format!("preset {name}"),
            base: name.to_string(),
            elements: u32::from(g.elements),
            ball_mm: g.element_diameter * 1e3,
            pitch_mm: g.pitch_diameter * 1e3,
            angle_deg: g.contact_angle.to_degrees(),
            shaft_hz: m.speed.shaft_hz(0.0),
            radial_load_n: m.radial_load,
            sample_rate_hz: m.output_rate,
            window_samples: PRESET_WINDOW_SAMPLES,
            mass_kg: m.structure.mass,
            stiffness_n_per_m: m.structure.stiffness,
            damping_n_s_per_m: m.structure.damping,
            structure_origin: format!("preset {name}"),
            assumptions: vec![],
            geometry: g,
        })
    }

    /// The description of a feature table's sidecar (`path` is the table, for errors): its
    /// preset when it names a model preset (whose speed, sample rate and snapshot length
    /// the sidecar must match), else the geometry of the catalogue bearing it names
    /// ([`crate::geometry::CATALOGUE`]) or its `geometry`, with its rpm, radial load,
    /// sample rate and snapshot length and a scaled structure (module docs).
    pub fn from_sidecar(s: &FeatureSidecar, path: &Path) -> Result<Self, String> {
        let side = sidecar_path(path);
        let field =
            |f: &str, what: String| format!("{}: sidecar field `{f}`: {what}", side.display());
        let model_preset = s
            .bearing
            .preset
            .as_deref()
            .filter(|n| wearsim_core::presets::by_name(n).is_some());
        if let Some(name) = model_preset {
            let d = Self::preset(name)?;
            let rpm = (d.shaft_hz * 60.0 * 1e6).round() / 1e6;
            if (s.rpm - rpm).abs() > RPM_TOL * rpm {
                return Err(field(
                    "rpm",
                    format!(
                        "{} rpm, but preset {name} runs at {rpm} rpm (allowed ±{:.0} %; leave `preset` out and give `geometry` to simulate this bearing at its own speed)",
                        s.rpm,
                        100.0 * RPM_TOL
                    ),
                ));
            }
            if s.snapshot_samples != d.window_samples as u64 {
                return Err(field(
                    "snapshot_samples",
                    format!(
                        "{}, but the simulated windows of preset {name} hold {} samples (crest factor and kurtosis depend on the length)",
                        s.snapshot_samples, d.window_samples
                    ),
                ));
            }
            if (s.sample_rate_hz - d.sample_rate_hz).abs() > 1e-6 * d.sample_rate_hz {
                return Err(field(
                    "sample_rate_hz",
                    format!(
                        "{} Hz, but preset {name} is rendered at {} Hz",
                        s.sample_rate_hz, d.sample_rate_hz
                    ),
                ));
            }
            return Ok(d);
        }
        let spec = match (s.bearing.preset.as_deref(), &s.bearing.geometry) {
            (Some(name), _) => {
                catalogue(name)
                    .ok_or_else(|| {
                        field(
                            "bearing.preset",
                            format!("unknown preset {name:?} (see `wearsim presets`)"),
                        )
                    })?
                    .geometry
            }
            (None, Some(g)) => GeometrySpec {
                elements: g.elements,
                ball_mm: g.ball_mm,
                pitch_mm: g.pitch_mm,
                angle_deg: g.angle_deg,
            }
            .checked()
            .map_err(|e| field("bearing.geometry", e))?,
            (None, None) => return Err(field(
                "bearing.geometry",
                "missing: a life gap simulates the sidecar's bearing, give `bearing.preset` (a preset or catalogue bearing) or `bearing.geometry` (elements, ball_mm, pitch_mm, angle_deg)".into(),
            )),
        };
        // The bearing is simulated at this speed: the simulation's range, in rpm.
        if let Err(e) = crate::config::check_sim_rpm("rpm", s.rpm) {
            return Err(field("rpm", e));
        }
        if !(s.radial_load_n.is_finite() && s.radial_load_n > 0.0) {
            return Err(field(
                "radial_load_n",
                format!(
                    "{} N: a simulated life needs the load that wears the bearing (allowed (0, 10^8] N)",
                    s.radial_load_n
                ),
            ));
        }
        let window = usize::try_from(s.snapshot_samples)
            .ok()
            .filter(|n| (64..=1 << 22).contains(n))
            .ok_or_else(|| {
                field(
                    "snapshot_samples",
                    format!(
                        "{}: a simulated window needs 64..=4194304 samples",
                        s.snapshot_samples
                    ),
                )
            })?;
        let mut d = Self::scaled(
            spec,
            s.rpm / 60.0,
            s.radial_load_n,
            s.sample_rate_hz,
            window,
        )?;
        // Say where the geometry came from: a catalogue bearing the sidecar names, or its
        // own numbers.
        if let Some(name) = s.bearing.preset.as_deref() {
            d.origin = format!("catalogue bearing {name} (sidecar bearing.preset)");
        }
        d.check_rate().map_err(|e| field("sample_rate_hz", e))?;
        Ok(d)
    }

    /// Whether the bearing can be simulated at the description's sample rate (the
    /// simulated windows' rate): inside the simulator's output range, and high enough for
    /// its step to resolve the stiffest contact mode (at most
    /// [`wearsim_core::model::MAX_OVERSAMPLE`] internal steps per sample). The message
    /// states the rate that would be accepted; the model's other fields are the
    /// description's and checked where they are set.
    #[allow(clippy::unnecessary_cast)] // Real is f32 in `f32` builds
    fn check_rate(&self) -> Result<(), String> {
        let (lo, hi) = wearsim_core::model::OUTPUT_RATE_RANGE;
        let (lo, hi) = (lo as f64, hi as f64);
        let fs = self.sample_rate_hz;
        if !(fs.is_finite() && (lo..=hi).contains(&fs)) {
            return Err(format!(
                "{fs} Hz: the simulated windows are rendered at the table's rate, allowed {lo}..={hi} Hz"
            ));
        }
        match wearsim_core::Model::new_checked(self.model()?) {
            Err(wearsim_core::ConfigError::StepTooLarge {
                field: "fs",
                min_internal_rate_hz,
                max_oversample: Some(k),
                waviness_hz,
                ..
            }) => Err(format!(
                "{fs} Hz is too low to simulate this bearing: {} needs a sample rate of at least {:.0} Hz ({k} internal steps per sample at most), allowed up to {hi} Hz",
                waviness_hz.map_or("its stiffest contact mode".to_string(), |w| format!("the races' waviness, passing at {w:.0} Hz at this speed,")),
                (min_internal_rate_hz / f64::from(k)).ceil(),
            )),
            _ => Ok(()),
        }
    }

    /// A bearing of geometry `g` at `shaft_hz`, `load_n`, rendered at `rate_hz` in
    /// windows of `window` samples, with the structure of the closest preset scaled to its
    /// size (module docs).
    pub fn scaled(
        g: GeometrySpec,
        shaft_hz: f64,
        load_n: f64,
        rate_hz: f64,
        window: usize,
    ) -> Result<Self, String> {
        let scaled = g.model()?;
        let (base, s, st) = (scaled.base, scaled.scale, scaled.model.structure);
        let base_pitch_mm = g.pitch_mm / s;
        let geometry = scaled.model.bearing;
        Ok(RigDescription {
            origin: "sidecar geometry".into(),
            base: base.to_string(),
            elements: g.elements,
            ball_mm: g.ball_mm,
            pitch_mm: g.pitch_mm,
            angle_deg: g.angle_deg,
            shaft_hz,
            radial_load_n: load_n,
            sample_rate_hz: rate_hz,
            window_samples: window,
            mass_kg: st.mass,
            stiffness_n_per_m: st.stiffness,
            damping_n_s_per_m: st.damping,
            structure_origin: format!(
                "preset {} scaled by geometric similitude, s = pitch {} mm / {:.2} mm = {s:.4}: mass × s³, stiffness × s, damping × s²",
                base,
                g.pitch_mm,
                base_pitch_mm
            ),
            assumptions: vec![
                format!("structure (mass, stiffness, damping, resonance) scaled from preset {}, not measured", base),
                format!("clearance, imbalance, waviness, roughness and slip of preset {base}"),
                "ball bearing (point contact), conformities 0.52/0.515".into(),
            ],
            geometry,
        })
    }

    /// The dynamic model of the simulated life: the base preset with every described
    /// field set. For a preset's own description this is the preset, bit for bit.
    pub fn model(&self) -> Result<ModelConfig, String> {
        let mut m = preset(&self.base)?;
        m.bearing = self.geometry;
        m.structure = Structure {
            mass: self.mass_kg,
            stiffness: self.stiffness_n_per_m,
            damping: self.damping_n_s_per_m,
        };
        m.speed = SpeedProfile::Constant(self.shaft_hz);
        m.radial_load = self.radial_load_n;
        m.output_rate = self.sample_rate_hz;
        Ok(m)
    }

    /// Closed-form defect frequencies of the simulated bearing (thesis eq. 17–20) and the
    /// natural frequency of its structure with the contacts, Hz (the one kinematics type).
    pub fn kinematics(&self) -> Result<FaultFrequencies, String> {
        crate::kinematics::of_config(&self.model()?, 60.0 * self.shaft_hz)
            .map_err(|e| format!("simulated bearing ({}): {e}", self.origin))
    }

    /// The first field in which `other` differs from this description, if any, with this
    /// description's value and `other`'s (as the sidecar states them: rpm, N, Hz, samples).
    pub fn differs(&self, other: &Self) -> Option<(&'static str, String, String)> {
        let geometry = |d: &Self| {
            format!(
                "{} × {} mm on {} mm, {}°",
                d.elements, d.ball_mm, d.pitch_mm, d.angle_deg
            )
        };
        // The geometry first (what a reader can check against the sidecars), then the
        // simulated structure: a model preset against a geometry scaled from one, or two
        // presets. Where the geometry came from (a catalogue name or its numbers) is no
        // difference.
        let f = [
            (
                "bearing.geometry",
                self.geometry != other.geometry,
                geometry(self),
                geometry(other),
            ),
            (
                "bearing",
                self.structure_origin != other.structure_origin || self.base != other.base,
                format!("{}: structure of {}", self.origin, self.structure_origin),
                format!("{}: structure of {}", other.origin, other.structure_origin),
            ),
            (
                "rpm",
                self.shaft_hz != other.shaft_hz,
                format!("{}", 60.0 * self.shaft_hz),
                format!("{}", 60.0 * other.shaft_hz),
            ),
            (
                "radial_load_n",
                self.radial_load_n != other.radial_load_n,
                format!("{}", self.radial_load_n),
                format!("{}", other.radial_load_n),
            ),
            (
                "sample_rate_hz",
                self.sample_rate_hz != other.sample_rate_hz,
                format!("{}", self.sample_rate_hz),
                format!("{}", other.sample_rate_hz),
            ),
            (
                "snapshot_samples",
                self.window_samples != other.window_samples,
                format!("{}", self.window_samples),
                format!("{}", other.window_samples),
            ),
        ];
        f.into_iter()
            .find(|(_, d, _, _)| *d)
            .map(|(n, _, a, b)| (n, a, b))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_preset_is_its_own_description_and_a_geometry_scales_the_closest_structure() {
        for n in wearsim_core::presets::NAMES {
            let d = RigDescription::preset(n).unwrap();
            assert_eq!(d.model().unwrap(), preset(n).unwrap(), "{n}");
        }
        // An XJTU-like bearing (34.55 mm pitch) is closest to the 6205 (39.04 mm).
        let g = GeometrySpec::parse("elements=8,ball=7.92,pitch=34.55").unwrap();
        let d = RigDescription::scaled(g, 35.0, 12_000.0, 25_600.0, 32_768).unwrap();
        assert_eq!(d.base, "cwru-6205-de");
        let b = preset("cwru-6205-de").unwrap().structure;
        let s: f64 = 34.55 / (1.537 * 25.4);
        assert!((d.mass_kg / b.mass - s.powi(3)).abs() < 1e-12);
        assert!((d.stiffness_n_per_m / b.stiffness - s).abs() < 1e-12);
        // Same damping ratio: C / √(K M) unchanged.
        let z = |c: f64, k: f64, m: f64| c / (k * m).sqrt();
        assert!(
            (z(d.damping_n_s_per_m, d.stiffness_n_per_m, d.mass_kg)
                / z(b.damping, b.stiffness, b.mass)
                - 1.0)
                .abs()
                < 1e-12
        );
        let m = d.model().unwrap();
        assert_eq!(m.output_rate, 25_600.0);
        assert_eq!(m.radial_load, 12_000.0);
        assert!(wearsim_core::Model::new_checked(m).is_ok());
        let k = d.kinematics().unwrap();
        assert!((k.bpfo + k.bpfi - 8.0 * 35.0).abs() < 1e-9);
        assert!(d.differs(&d.clone()).is_none());
        let mut e = d.clone();
        e.radial_load_n = 1.0;
        assert_eq!(d.differs(&e).map(|x| x.0), Some("radial_load_n"));
    }

    #[test]
    fn a_catalogue_bearing_is_a_geometry() {
        use crate::io::feature_table::{BearingInfo, FeatureSidecar};
        let side = |preset: Option<&str>| FeatureSidecar {
            format: "wearsim-feature-table".into(),
            format_version: 1,
            source: "test".into(),
            bearing: BearingInfo {
                preset: preset.map(String::from),
                geometry: None,
                id: "b".into(),
            },
            channel: "h".into(),
            unit: "g".into(),
            rpm: 2100.0,
            radial_load_n: 12_000.0,
            sample_rate_hz: 25_600.0,
            snapshot_samples: 32_768,
            snapshot_interval_s: 60.0,
            failure_mode: "unknown".into(),
            n_snapshots: None,
            notes: vec![],
        };
        let p = Path::new("x.csv");
        let d = RigDescription::from_sidecar(&side(Some("xjtu-ldk-uer204")), p).unwrap();
        assert_eq!(
            (d.origin.as_str(), d.elements, d.ball_mm, d.pitch_mm),
            (
                "catalogue bearing xjtu-ldk-uer204 (sidecar bearing.preset)",
                8,
                7.92,
                34.55
            )
        );
        // The same geometry typed into the sidecar is the same bearing.
        let mut typed = side(None);
        typed.bearing.geometry = Some(crate::io::feature_table::Geometry {
            elements: 8,
            ball_mm: 7.92,
            pitch_mm: 34.55,
            angle_deg: 0.0,
        });
        let t = RigDescription::from_sidecar(&typed, p).unwrap();
        assert_eq!(t.origin, "sidecar geometry");
        assert!(d.differs(&t).is_none(), "{:?}", d.differs(&t));
        assert_eq!(d.window_samples, 32_768);
        let e = RigDescription::from_sidecar(&side(None), p).unwrap_err();
        assert!(e.contains("`bearing.geometry`"), "{e}");
        let e = RigDescription::from_sidecar(&side(Some("6205")), p).unwrap_err();
        assert!(e.contains("`bearing.preset`"), "{e}");
    }
}
