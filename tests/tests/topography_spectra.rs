//! The spectral behaviour the thesis reports for its wear events (publication IV §3,
//! thesis §6; model.md §8), asserted on simulated spectra of the Table 1 topographies with
//! ratios that a wrong model would miss.

use wearsim_core::forces::imbalance::Imbalance;
use wearsim_core::forces::slip::Slip;
use wearsim_core::forces::surface::{Roughness, Waviness};
use wearsim_core::topography::{self, Topography};
use wearsim_core::{presets, Model, ModelConfig};
use wearsim_host::analysis::{self, WelchParams, Window, ZoneBands};
use wearsim_tests::{bare_reference, simulate};

/// Reference with imbalance, waviness and roughness (the healthy background of the
/// thesis's event 1) and, optionally, an outer-race defect of topography `t`.
fn scenario(t: Option<Topography>, slip: f64) -> ModelConfig {
    ModelConfig {
        imbalance: Some(Imbalance {
            mass: 0.005,
            radius: 0.1,
        }),
        waviness: Some(Waviness {
            amplitude: 0.1e-6,
            wavelength: 0.8e-3,
        }),
        roughness: Some(Roughness {
            rms: 0.005e-6,
            wavelength: 0.02e-3,
            debris_gain: 4.0,
        }),
        defect: t.map(presets::outer_race_defect),
        slip: (slip > 0.0).then_some(Slip { fraction: slip }),
        ..bare_reference()
    }
}

struct Figures {
    natural: f64,
    fault_zone: f64,
    bpfo: [f64; 3],
}

fn figures(t: Option<Topography>, slip: f64) -> Figures {
    let cfg = scenario(t, slip);
    let model = Model::new_checked(cfg.clone()).unwrap();
    let ff = model.frequencies_at(cfg.speed.shaft_hz(0.0));
    let (x, fs) = simulate(cfg, 4.0, 11);
    let psd = analysis::welch_psd(
        &x,
        fs,
        &WelchParams {
            nperseg: 8192,
            ..WelchParams::default()
        },
    )
    .unwrap();
    let zones = ZoneBands::new(&ff, fs).unwrap();
    let levels = analysis::zone_levels(&psd, &zones);
    let spec = analysis::amplitude_spectrum(&x, fs, Window::Hann).unwrap();
    let at = |k: f64| {
        analysis::peak_near(&spec, k * ff.bpfo, 2.0 * spec.df)
            .map(|p| p.value)
            .unwrap_or(0.0)
    };
    Figures {
        natural: levels.natural,
        fault_zone: levels.fault,
        bpfo: [at(1.0), at(2.0), at(3.0)],
    }
}

#[test]
fn dent_excites_the_natural_zone_not_the_fault_frequency() {
    let healthy = figures(None, 0.0);
    let dent = figures(Some(topography::REAL_DENT), 0.0);
    let medium = figures(Some(topography::MEDIUM_DEFECT), 0.0);
    println!(
        "natural zone: healthy {:.4}, dent {:.4}",
        healthy.natural, dent.natural
    );
    println!(
        "BPFO peak: dent {:.4}, medium {:.4}",
        dent.bpfo[0], medium.bpfo[0]
    );
    assert!(
        dent.natural > 2.0 * healthy.natural,
        "dent {} vs healthy {}",
        dent.natural,
        healthy.natural
    );
    assert!(
        dent.bpfo[0] < 0.1 * medium.bpfo[0],
        "dent BPFO {} vs medium {}",
        dent.bpfo[0],
        medium.bpfo[0]
    );
}

#[test]
fn smoothing_the_dent_lowers_the_natural_zone() {
    let dent = figures(Some(topography::REAL_DENT), 0.0);
    let smooth = figures(Some(topography::SMOOTHED_DENT), 0.0);
    println!(
        "natural zone: dent {:.4}, smoothed {:.4}",
        dent.natural, smooth.natural
    );
    assert!(smooth.natural < 0.7 * dent.natural);
}

#[test]
fn fault_peaks_grow_with_defect_size_with_harmonics() {
    let mild = figures(Some(topography::MILD_DEFECT), 0.0);
    let medium = figures(Some(topography::MEDIUM_DEFECT), 0.0);
    let large = figures(Some(topography::LARGE_DEFECT), 0.0);
    println!(
        "BPFO: mild {:?} medium {:?} large {:?}",
        mild.bpfo, medium.bpfo, large.bpfo
    );
    // The first three BPFO harmonics together (the acceleration of a pulse train rises as
    // f² below resonance, so the fundamental alone is the weakest line).
    let sum = |f: &Figures| f.bpfo.iter().sum::<f64>();
    assert!(
        sum(&medium) > 1.3 * sum(&mild),
        "{} vs {}",
        sum(&medium),
        sum(&mild)
    );
    assert!(
        sum(&large) > 1.3 * sum(&medium),
        "{} vs {}",
        sum(&large),
        sum(&medium)
    );
    assert!(large.fault_zone > medium.fault_zone && medium.fault_zone > mild.fault_zone);
    // Harmonics: 2x and 3x BPFO carry at least a fifth of the fundamental for the large one.
    assert!(
        large.bpfo[1] > 0.2 * large.bpfo[0] && large.bpfo[2] > 0.2 * large.bpfo[0],
        "{:?}",
        large.bpfo
    );
}

#[test]
fn smoothed_large_defect_is_lower_in_both_zones() {
    let large = figures(Some(topography::LARGE_DEFECT), 0.0);
    let smooth = figures(Some(topography::SMOOTHED_LARGE_DEFECT), 0.0);
    println!(
        "large: nat {:.4} fault {:.4}; smoothed: nat {:.4} fault {:.4}",
        large.natural, large.fault_zone, smooth.natural, smooth.fault_zone
    );
    assert!(smooth.natural < 0.8 * large.natural);
    assert!(smooth.fault_zone < 0.9 * large.fault_zone);
}

#[test]
fn damage_growth_exceeds_a_single_large_defect() {
    let one = figures(Some(topography::LARGE_DEFECT), 0.0);
    let two = figures(Some(topography::TWO_LARGE_DEFECTS), 0.0);
    println!(
        "one: fault {:.4} nat {:.4}; two: fault {:.4} nat {:.4}",
        one.fault_zone, one.natural, two.fault_zone, two.natural
    );
    assert!(two.fault_zone > 1.1 * one.fault_zone);
}
