//! Named reference configurations. Every value not given by its source is marked
//! "chosen" with the reason; the README's preset table repeats these notes.

use crate::bearing::{BearingGeometry, ContactKind};
use crate::forces::defect::{DefectConfig, DefectLocation, DefectModel};
use crate::forces::imbalance::Imbalance;
use crate::forces::surface::{Roughness, Waviness};
use crate::integrate::IntegratorKind;
use crate::model::{Channels, ModelConfig, Structure};
use crate::real::{Real, PI};
use crate::speed::SpeedProfile;
use crate::topography;

/// Names of all presets, in the order `wearsim presets` lists them.
pub const NAMES: [&str; 5] = [
    "thesis-61810",
    "thesis-as-printed",
    "cwru-6205-de",
    "cwru-6203-fe",
    "ims-za2115",
];

/// AISI 52100 bearing steel: E = 208 GPa, ν = 0.3, ρ = 7830 kg/m³ (Harris & Kotzalas 2006).
const STEEL: (Real, Real, Real) = (208e9, 0.3, 7830.0);

/// Inch to metre.
const IN: Real = 0.0254;

/// SKF 61810 as the thesis models it (ch. 4; bore 50 mm, OD 65 mm, 0.052 kg). SKF does not
/// publish the internal geometry; chosen: 14 balls of 5/32 in (3.969 mm) on a 57.5 mm pitch
/// circle (the mean of bore and OD), which puts BPFO at 166 Hz for the thesis's 160 rad/s,
/// inside its reported ~170 Hz fault zone. Conformities 0.52/0.515 (Harris, typical deep
/// groove).
pub const SKF_61810: BearingGeometry = BearingGeometry {
    elements: 14,
    element_diameter: 3.969e-3,
    pitch_diameter: 57.5e-3,
    contact_angle: 0.0,
    bore: 50e-3,
    outside_diameter: 65e-3,
    contact: ContactKind::Point,
    outer_conformity: 0.52,
    inner_conformity: 0.515,
    roller_length: 0.0,
    youngs_modulus: STEEL.0,
    poisson: STEEL.1,
    density: STEEL.2,
};

/// SKF 6205-2RS JEM, CWRU drive end: 9 balls, 7.94 mm, pitch 39.04 mm, 0° (CWRU; Smith &
/// Randall 2015 Table 2). Conformities chosen 0.52/0.515 as above.
pub const SKF_6205: BearingGeometry = BearingGeometry {
    elements: 9,
    element_diameter: 0.3126 * IN,
    pitch_diameter: 1.537 * IN,
    contact_angle: 0.0,
    bore: 25e-3,
    outside_diameter: 52e-3,
    ..SKF_61810
};

/// SKF 6203-2RS JEM, CWRU fan end: 8 balls, 6.75 mm, pitch 28.50 mm, 0°.
pub const SKF_6203: BearingGeometry = BearingGeometry {
    elements: 8,
    element_diameter: 0.2656 * IN,
    pitch_diameter: 1.122 * IN,
    contact_angle: 0.0,
    bore: 17e-3,
    outside_diameter: 40e-3,
    ..SKF_61810
};

/// Rexnord ZA-2115 (IMS): 16 rollers per row, 0.331 in, pitch 2.815 in, 15.17°; line
/// contact. Chosen: effective roller length 0.35 in (≈ roller diameter), bore 2 3/16 in,
/// OD 3.54 in (catalogue dimensions of the ZA-2115 insert are not given by the data set).
pub const REXNORD_ZA2115: BearingGeometry = BearingGeometry {
    elements: 16,
    element_diameter: 0.331 * IN,
    pitch_diameter: 2.815 * IN,
    contact_angle: 15.17 * PI / 180.0,
    bore: 2.1875 * IN,
    outside_diameter: 3.54 * IN,
    contact: ContactKind::Line,
    roller_length: 0.35 * IN,
    ..SKF_61810
};

/// Shaft speed of the thesis: 160 rad/s (25.46 Hz).
pub const THESIS_SHAFT_HZ: Real = 160.0 / (2.0 * PI);

/// Static radial load of the thesis reference (N). The thesis gives none; chosen 500 N,
/// about 3 % of the 61810's dynamic rating (C ≈ 15.6 kN), a light industrial load.
pub const THESIS_RADIAL_LOAD: Real = 500.0;

/// Radial clearance of the reference (m). Not given by the thesis; chosen 0 (a slight
/// interference after mounting), so that the healthy spectrum shows the thesis's clear 1×
/// imbalance peak: with a few µm of clearance the varying compliance of the ball passage
/// (Sunnersjö 1978) excites BPFO multiples above the imbalance line.
pub const THESIS_CLEARANCE: Real = 0.0;

/// Vibrating mass of the reference (kg), chosen so that the linearised natural
/// frequency `√((K + k_c0)/M)/2π` lands at the thesis's ~1100 Hz natural-frequency zone
/// with the thesis's K = 5.96·10⁷ N/m plus the contact stiffness at 500 N.
pub const THESIS_MASS: Real = 2.76;

/// Damping of the reference: ζ ≈ 3 % (chosen, light damping of a bolted housing),
/// `C = 2ζ√((K + k_c0) M)`.
pub const THESIS_DAMPING: Real = 1145.0;

/// The default outer-race defect: five-step load function, at the load-zone centre.
pub const fn outer_race_defect(t: topography::Topography) -> DefectConfig {
    DefectConfig {
        location: DefectLocation::OuterRace { angle: PI / 2.0 },
        model: DefectModel::FiveStep,
        topography: t,
        sassi_k_impact: 1.0,
    }
}

/// Looks a preset up by name. The defect (if any) is the preset's default topography;
/// front ends replace or remove it.
pub fn by_name(name: &str) -> Option<ModelConfig> {
    let thesis = ModelConfig {
        bearing: SKF_61810,
        structure: Structure {
            mass: THESIS_MASS,
            stiffness: 5.96e7,
            damping: THESIS_DAMPING,
        },
        radial_load: THESIS_RADIAL_LOAD,
        clearance: THESIS_CLEARANCE,
        speed: SpeedProfile::Constant(THESIS_SHAFT_HZ),
        imbalance: Some(Imbalance {
            mass: 0.005,
            radius: 0.1,
        }),
        waviness: Some(Waviness {
            amplitude: 0.1e-6,
            wavelength: 0.8e-3,
        }),
        // Effective roughness excitation transmitted through the EHL film (chosen): the
        // composite Rq of ground races is 0.05–0.1 µm, but at λ > 1 most of it is carried
        // by the film; 5 nm puts the healthy natural-zone level well below a dent's.
        roughness: Some(Roughness {
            rms: 0.005e-6,
            wavelength: 0.02e-3,
            debris_gain: 4.0,
        }),
        defect: Some(outer_race_defect(topography::MEDIUM_DEFECT)),
        slip: Some(crate::forces::slip::Slip { fraction: 0.01 }),
        integrator: IntegratorKind::ExactFoh,
        output_rate: 20_000.0,
        oversample: None,
        channels: Channels::Acceleration,
        effects: crate::effects::Effects::NONE,
    };
    match name {
        "thesis-61810" => Some(thesis),
        "thesis-as-printed" => Some(ModelConfig {
            structure: Structure {
                mass: 11.0,
                stiffness: 5.96e7,
                damping: 5e7,
            },
            ..thesis
        }),
        "cwru-6205-de" => Some(ModelConfig {
            bearing: SKF_6205,
            // Chosen: a drive-end housing mode near 3.3 kHz (the band where CWRU drive-end
            // fault impulses ring; Smith & Randall 2015), gravity load of the rotor ≈ 200 N.
            structure: Structure {
                mass: 0.16,
                stiffness: 1.0e7,
                damping: 330.0,
            },
            radial_load: 200.0,
            speed: SpeedProfile::Constant(1797.0 / 60.0),
            imbalance: Some(Imbalance {
                mass: 0.001,
                radius: 0.05,
            }),
            defect: Some(outer_race_defect(topography::Topography {
                asperity_height: 5e-6,
                length: 0.007 * IN,
                width: 0.007 * IN,
                depth: 0.011 * IN,
                count: 1,
                debris: 0.0,
            })),
            output_rate: 12_000.0,
            ..thesis
        }),
        "cwru-6203-fe" => Some(ModelConfig {
            bearing: SKF_6203,
            defect: None,
            ..by_name("cwru-6205-de")?
        }),
        "ims-za2115" => Some(ModelConfig {
            bearing: REXNORD_ZA2115,
            // Chosen: a housing mode near 3 kHz; 6000 lbf shared by the two rows of the
            // loaded bearing.
            structure: Structure {
                mass: 5.0,
                stiffness: 1.0e9,
                damping: 4000.0,
            },
            radial_load: 6000.0 * 4.448_221_6 / 2.0,
            clearance: 5e-6,
            speed: SpeedProfile::Constant(2000.0 / 60.0),
            defect: Some(outer_race_defect(topography::REAL_DENT)),
            ..thesis
        }),
        _ => None,
    }
}
